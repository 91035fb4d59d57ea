"""One OpenBLAS thread for the command lines.

The toolkit's matrices are small (at most a few dozen states): OpenBLAS computes them on one thread and its other
threads, once woken by a product, busy-wait on the cores the compiled kernels and the other processes need.
Measured on a 2-core machine, ``python -m stability.assist --chair mid-wheel-drive``: 12.8 s CPU and 8.4 s wall
with OpenBLAS's default threads, 6.2 s CPU and 6.2 s wall with one, the same output.  ``stability/__init__.py``
calls :func:`one_thread_for_commands` when the package is imported by a command line, before numpy is imported
(OpenBLAS reads the variable once, when it loads).  A library user's process is not touched, and a value the
environment sets is kept.  The tests run with the same setting (``tests/conftest.py``).

This module imports only the standard library.
"""

from __future__ import annotations

from collections.abc import Container, MutableMapping

__all__ = ["VARIABLE", "one_thread_for_commands"]

#: The environment variable OpenBLAS reads for its thread count when it loads.
VARIABLE = "OPENBLAS_NUM_THREADS"


def one_thread_for_commands(environ: MutableMapping[str, str], modules: Container[str]) -> bool:
    """Set :data:`VARIABLE` to 1 in ``environ`` unless it is set or numpy is already loaded.

    Parameters
    ----------
    environ : mutable mapping of str to str
        The process environment (``os.environ``).
    modules : container of str
        Names of the modules already imported (``sys.modules``): once numpy is loaded its OpenBLAS has read the
        variable, and setting it would only mislead child processes about this one.

    Returns
    -------
    bool
        Whether the variable was set here.
    """
    if VARIABLE in environ or "numpy" in modules:
        return False
    environ[VARIABLE] = "1"
    return True
