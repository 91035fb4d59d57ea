"""The garbage collector of a command line: the objects its imports made kept out of the later collections.

A command imports numpy, scipy, matplotlib and the toolkit (about 100,000 objects tracked by CPython's cyclic
garbage collector: modules, functions, classes, docstrings' tables) before it computes, and they live until the
process ends.  CPython's full collections traverse every one of them again each time (tens of milliseconds
each, several in a report), and its youngest-generation collections run every 700 allocations while the imports
make them, finding little to free.  ``stability/__init__.py`` calls :func:`defer_for_imports` when the package
is imported by a command line (the branch that calls :func:`stability.runtime.blas.one_thread_for_commands`):
the youngest generation's threshold is raised while the command imports; :func:`stability.cli.run` calls
:func:`settle` when the command starts (its module and the modules it imports at the top loaded): the objects
alive then are moved to the permanent generation (:func:`gc.freeze`), which the collector no longer traverses,
and the youngest generation's threshold stays raised (:data:`RUN_THRESHOLD`) while the command runs.  The
collector stays on: the cycles the computation makes are collected, every :data:`RUN_THRESHOLD` allocations
instead of every 700, and a cycle of the imports, if any, is kept (a few objects, for a process that ends with its
command).
No number changes (the collector frees memory only): the reports' PDF, text and JSON are byte for byte the same.
Measured on the shared 2-core machine (user + system CPU time of the process, best of three, before and after run
in turn, twice): ``python -m stability.report --chair ej-premier --quick --no-progress`` 4.62 -> 4.03 s and
4.78 -> 4.15 s, the full report 12.63 -> 12.19 s and 13.79 -> 13.44 s.  The threshold kept raised while the command
runs (the modules it imports later, numba's kernel, the PDF backend and fontTools, and the computation's objects
are traversed by far fewer collections): the collections' own CPU time, measured with :data:`gc.callbacks` in the
process, 0.16 -> 0.04 s in the quick report and 0.69 -> 0.24 s in the full one (five full collections of the
unfrozen objects, about 0.1 s each, no longer run), the peak memory the same (245 MB and 314 MB).  A library
user's process and the test suite's are not touched: :func:`settle` does nothing unless
:func:`defer_for_imports` ran.

This module imports only the standard library.
"""

from __future__ import annotations

import gc

__all__ = ["IMPORT_THRESHOLD", "RUN_THRESHOLD", "defer_for_imports", "settle"]

#: Allocations between two youngest-generation collections while a command imports (CPython's default: 700).
IMPORT_THRESHOLD = 100_000

#: Allocations between two youngest-generation collections while a command runs, after :func:`settle` (the
#: full report: 4 young collections instead of about 660, and no full collection instead of 5).
RUN_THRESHOLD = 100_000

#: The thresholds :func:`defer_for_imports` replaced, until :func:`settle` sets the command's.
_saved: list[tuple[int, ...]] = []


def defer_for_imports() -> bool:
    """Raise the youngest generation's collection threshold to :data:`IMPORT_THRESHOLD` until :func:`settle`.

    Returns
    -------
    bool
        Whether it was raised here (False when an earlier call has not been settled yet, or the collector is off).
    """
    if _saved or not gc.isenabled():
        return False
    before = gc.get_threshold()
    _saved.append(before)
    gc.set_threshold(max(IMPORT_THRESHOLD, before[0]), *before[1:])
    return True


def settle() -> bool:
    """After :func:`defer_for_imports`: freeze the objects alive now (:func:`gc.freeze`) and set the youngest
    generation's threshold to :data:`RUN_THRESHOLD` for the command's run (the older generations' put back).

    Returns
    -------
    bool
        Whether anything was done (False without a pending :func:`defer_for_imports`: a library or a test
        process, or a second command run in one process).
    """
    if not _saved:
        return False
    before = _saved.pop()
    gc.freeze()
    gc.set_threshold(max(RUN_THRESHOLD, before[0]), *before[1:])
    return True
