"""The computed numbers of the documentation: named value groups, evaluated when the site builds.

A *value group* is one function that calls the toolkit's public API (or runs one command) once and returns a
dict of formatted values: ``{"key": "6.41", ...}``, or a :class:`Table` for a whole table. The pages quote a
value as ``{docvalue}`group.key``` and a table with the ``docvalue-table`` directive
(``stability_values.py``); README.md, which Sphinx does not build, carries ``<!--dv group.key-->6.41<!--/dv-->``
markers that ``python -m docs._ext.readme_values`` rewrites. Every group names the command or API call that
produced it (``source``), which the pages show beside the values.

Results are cached on disk (``docs/_build/docvalues/``) under a hash of every file of the ``stability`` package,
of this module, of ``value_groups_pages.py`` (its helpers are shared) and of the group's own module
(``value_groups_<page>.py``), so a rebuild without code changes reads them back and a change to one page's groups
recomputes only that module's; :func:`evaluate` says how long a group took.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CACHE = Path(os.environ.get("STABILITY_DOCVALUES_CACHE", ROOT / "docs" / "_build" / "docvalues"))


@dataclass(frozen=True)
class Table:
    """A table of formatted values: header and rows (strings)."""

    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]

    def to_json(self) -> dict:
        return {"table": True, "header": list(self.header), "rows": [list(r) for r in self.rows]}


@dataclass(frozen=True)
class Group:
    """A value group: its name, the command or API call that produced it, the function."""

    name: str
    source: str
    func: Callable[[], dict]
    cheap: bool = False            # computed by the default test run (README's groups must be)


GROUPS: dict[str, Group] = {}


def group(name: str, source: str, cheap: bool = False):
    """Register a value group (a decorator)."""
    def wrap(func: Callable[[], dict]) -> Callable[[], dict]:
        GROUPS[name] = Group(name, source, func, cheap)
        return func
    return wrap


# --- formatting ----------------------------------------------------------------------------------------------

def sig(x: float, n: int = 3) -> str:
    """``x`` to ``n`` significant figures, without an exponent for ordinary magnitudes (``6.41``, ``0.0512``)."""
    if x == 0 or not math.isfinite(x):
        return f"{x:g}"
    digits = n - 1 - int(math.floor(math.log10(abs(x))))
    return f"{x:.{max(digits, 0)}f}" if digits >= 0 else f"{round(x, digits):.0f}"


def fixed(x: float, nd: int) -> str:
    """``x`` with ``nd`` decimals (``-0.0`` printed as ``0.0``)."""
    s = f"{x:.{nd}f}"
    return s[1:] if s.startswith("-") and float(s) == 0 else s


def signed(x: float, nd: int) -> str:
    """``x`` with ``nd`` decimals and its sign (``+6.09``)."""
    return ("+" if x >= 0 else "") + fixed(x, nd)


def pct(x: float, nd: int = 0) -> str:
    """A fraction as a percentage number (``0.47`` -> ``47``)."""
    return fixed(100.0 * x, nd)


# --- evaluation and cache ------------------------------------------------------------------------------------

#: The modules every group may use (the formatting and cache here, the shared helpers of the pages' module).
_SHARED = ("value_groups.py", "value_groups_pages.py")


def source_hash(module: str | None = None) -> str:
    """Hash of the ``stability`` package's files (sources and data, not compiled caches) and of the group modules:
    all of them, or (``module``: a group module's file name) the shared ones and that one, so that editing one
    page's groups leaves the cached values of the other pages' groups valid."""
    h = hashlib.sha256()
    files = sorted(p for p in (ROOT / "stability").rglob("*")
                   if p.is_file() and "__pycache__" not in p.parts and p.suffix not in {".nbi", ".nbc", ".pyc"})
    here = Path(__file__).parent
    mods = sorted(here.glob("value_groups*.py")) if module is None else \
        [here / m for m in sorted({*_SHARED, module})]
    for p in [*files, *mods]:
        h.update(p.relative_to(ROOT).as_posix().encode())
        h.update(p.read_bytes())
    return h.hexdigest()[:16]


def _decode(d: dict) -> dict:
    return {k: Table(tuple(v["header"]), tuple(tuple(r) for r in v["rows"]))
            if isinstance(v, dict) and v.get("table") else v for k, v in d.items()}


def child_cpu(argv: list[str], env: dict | None = None) -> float:
    """CPU seconds (user + system, its threads included) of one child ``python argv...`` run from the repository's
    root, with this repository on ``PYTHONPATH``; its output discarded.

    Parameters
    ----------
    argv : list of str
        The interpreter's arguments (``["-m", "stability.report", ...]``).
    env : dict, optional
        Extra environment variables.

    Returns
    -------
    float
        s.
    """
    import resource
    import subprocess

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, *argv], cwd=ROOT, check=True, capture_output=True,
                   env={**os.environ, "PYTHONPATH": str(ROOT), **(env or {})})
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def best_alternating(commands: dict[str, list[str]], repeat: int) -> dict[str, float]:
    """The smallest CPU time of each command over ``repeat`` rounds, the commands run in turn in every round (so a
    busy spell on the shared machine falls on all of them), after one round that is not counted (numba's cache and
    the file cache warmed).

    Parameters
    ----------
    commands : dict of str to list of str
        Name -> the interpreter's arguments (:func:`child_cpu`).
    repeat : int
        Counted rounds (>= 1).

    Returns
    -------
    dict of str to float
        Name -> the best CPU time, s.
    """
    for argv in commands.values():
        child_cpu(argv)
    best = {k: math.inf for k in commands}
    for _ in range(repeat):
        for k, argv in commands.items():
            best[k] = min(best[k], child_cpu(argv))
    return best


def _cpu() -> float:
    """CPU seconds of this process and of its finished children (a group may run a command)."""
    import resource

    ch = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + ch.ru_utime + ch.ru_stime


def evaluate(name: str, use_cache: bool = True) -> tuple[dict, float, bool]:
    """The values of group ``name``, the CPU seconds the computation took (this process and the commands it ran;
    the wall time is stored in the cache file too), and whether they came from the cache.

    Raises
    ------
    KeyError
        If there is no group ``name``.
    """
    g = GROUPS[name]
    key = source_hash(Path(sys.modules[g.func.__module__].__file__ or "").name)
    path = CACHE / f"{name}-{key}.json"
    if use_cache and path.exists():
        data = json.loads(path.read_text())
        return _decode(data["values"]), float(data["seconds"]), True
    if str(ROOT) not in sys.path:
        sys.path.insert(0, str(ROOT))
    start, wall = _cpu(), time.perf_counter()
    values = g.func()
    took, wall = _cpu() - start, time.perf_counter() - wall
    bad = [k for k, v in values.items() if not isinstance(v, (str, Table))]
    if bad:
        raise TypeError(f"value group {name}: values {bad} are not formatted strings or Tables")
    CACHE.mkdir(parents=True, exist_ok=True)
    enc = {k: v.to_json() if isinstance(v, Table) else v for k, v in values.items()}
    tmp = path.with_suffix(".tmp")
    tmp.write_text(json.dumps({"group": name, "source": g.source, "seconds": took, "wall_seconds": wall,
                               "values": enc}, indent=1))
    tmp.replace(path)
    return values, took, False


from value_groups_advise import *  # noqa: E402,F401,F403
from value_groups_assist import *  # noqa: E402,F401,F403
from value_groups_assist_extra import *  # noqa: E402,F401,F403
from value_groups_hostile import *  # noqa: E402,F401,F403
from value_groups_layouts import *  # noqa: E402,F401,F403  (registers the layout groups)
from value_groups_measure import *  # noqa: E402,F401,F403
from value_groups_misc import *  # noqa: E402,F401,F403
from value_groups_pages import *  # noqa: E402,F401,F403  (registers the groups)
from value_groups_power import *  # noqa: E402,F401,F403
from value_groups_report import *  # noqa: E402,F401,F403
from value_groups_scale import *  # noqa: E402,F401,F403
from value_groups_shimmy import *  # noqa: E402,F401,F403
from value_groups_simulator import *  # noqa: E402,F401,F403
from value_groups_studies import *  # noqa: E402,F401,F403
