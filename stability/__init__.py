"""stability: directional stability of wheelchairs with swivelling casters.

After T. J. Collins, *An analysis of parameters related to the directional
stability of rear caster wheelchairs* (M.S. thesis, University of Virginia,
1987).  The main entry points are available here; every subpackage stays
importable on its own (``docs/architecture.md`` shows the layout).

>>> import stability
>>> chair = stability.preset("ej-premier")
>>> round(stability.analyse(chair).divergence[2].rate, 2)   # growth rate at 0.75 m/s, 1/s
1.45

Importing :mod:`stability` loads neither sympy, scipy.optimize nor numba.
"""

from __future__ import annotations

import sys

# python -m stability.X (argv[0] is "-m" while the package is imported) or the console script ``stability``:
# Ctrl-C, SIGTERM and SIGHUP are handled from the first line (stability.runtime.interrupts)
_argv0 = (sys.argv or [""])[0]
if _argv0 == "-m" or _argv0.replace("\\", "/").rsplit("/", 1)[-1] in ("stability", "stability.exe"):
    import os

    from stability.runtime import blas, collector, interrupts

    interrupts.install_early()
    blas.one_thread_for_commands(os.environ, sys.modules)   # before numpy loads OpenBLAS (stability.runtime.blas)
    collector.defer_for_imports()          # the imports' objects frozen when the command starts (runtime.collector)

from importlib import import_module  # noqa: E402
from typing import Any  # noqa: E402

__version__ = "0.1.0"

#: Top-level names -> (module, attribute); loaded on first use.
_ENTRY_POINTS = {
    "Chair": ("stability.chair", "Chair"),
    "preset": ("stability.chair", "preset"),
    "preset_names": ("stability.chair", "preset_names"),
    "load_chair": ("stability.chair", "resolve"),
    "analyse": ("stability.linear", "analyse"),
    "state_space": ("stability.linear", "state_space"),
    "eigenvalues_vs_speed": ("stability.linear", "eigenvalues_vs_speed"),
    "RunSpec": ("stability.settings.run", "RunSpec"),
    "run_simulation": ("stability.simulate", "simulate"),
    "run_batch": ("stability.simulate", "simulate_batch"),
}

__all__ = ["__version__", *_ENTRY_POINTS]


def __getattr__(name: str) -> Any:
    try:
        module, attr = _ENTRY_POINTS[name]
    except KeyError:
        raise AttributeError(f"module 'stability' has no attribute {name!r}") from None
    return getattr(import_module(module), attr)


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_ENTRY_POINTS))
