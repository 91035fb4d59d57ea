"""Running a sweep: chunks written atomically, resumable, merged into one CSV or Parquet file, with a summary.

Chunk ``i`` goes to ``RESULTS.chunks/chunk-iiiiii.csv`` (written to a
temporary name and renamed, so a chunk file is complete or absent); the spec
it was made from is kept there as ``spec.json``.  ``resume=True`` computes
only the missing chunks of the same spec.  The final file is built from the
chunk files alone (floats written with ``repr``, which reads back exactly), so
an interrupted and resumed sweep gives the same bytes as an uninterrupted one.
"""

from __future__ import annotations

import csv
import io
import json
import os
import shutil
import time
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

import numpy as np

from stability.runtime.files import atomic_path, atomic_write_text
from stability.study.censored import describe, quantile, side_of, sort_key
from stability.sweep.measures import columns, compute_chunk, n_chunks
from stability.sweep.spec import GRID_UNITS, INVALID, MEASURES, SweepSpec

__all__ = ["chunk_dir", "run_sweep", "read_rows", "summary", "summary_text", "TEXT_COLUMNS", "HIGHER_IS_BETTER",
           "STATUS_OF", "COLUMN_UNITS", "row_sides", "check_output_format"]

#: Columns holding text (everything else is a number).
TEXT_COLUMNS = ("critical_speed_status", "locked_critical_speed_status", "critical_impulse_status",
                "equal_instability_status", "shimmy_margin_status", "human_limited_status", "error")
#: Measures where a larger value is better (a chair that needs more to go wrong); growth rate: smaller is better.
HIGHER_IS_BETTER = {"critical_speed_m_s": True, "locked_critical_speed_m_s": True, "critical_impulse_Ns": True,
                    "equal_instability_speed_m_s": True, "growth_rate_1_s": False, "shimmy_margin_m": True,
                    "static_stability_deg": True, "tip_toward_casters_deg": True, "tip_toward_main_wheels_deg": True,
                    "tip_lateral_deg": True, "holding_moment_N_m_per_deg": False,
                    "human_limited_speed_m_s": True, "bench_worst_score": False, "level_braking_distance_m": False}


def chunk_dir(out: str | os.PathLike[str]) -> Path:
    """Where the chunks of ``out`` are kept while the sweep runs.

    Parameters
    ----------
    out : path
        The results file.

    Returns
    -------
    Path
        ``out`` with ``.chunks`` appended to its name.
    """
    p = Path(out)
    return p.with_name(p.name + ".chunks")


def _cell(x: Any) -> str:
    if isinstance(x, str):
        return x
    if isinstance(x, (int, np.integer)) and not isinstance(x, bool):
        return str(int(x))
    return repr(float(x))


def _chunk_text(rows: Sequence[Sequence[Any]]) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    for r in rows:
        w.writerow([_cell(x) for x in r])
    return buf.getvalue()


def run_sweep(spec: SweepSpec, out: str | os.PathLike[str], *, resume: bool = False,
              mapper: Callable[[Callable[[int], str], Sequence[int]], Iterable[tuple[int, str]]] | None = None,
              progress: Callable[[int, int, int, float], None] | None = None) -> Path:
    """Run every chunk not yet done, then write ``out`` (CSV, or Parquet for a ``.parquet`` suffix).

    Parameters
    ----------
    spec : SweepSpec
    out : path
        The results file.
    resume : bool
        Keep the finished chunks of an interrupted run of the same spec.
    mapper : callable, optional
        ``mapper(fn, indices)`` yields ``(index, fn(index))`` for every chunk
        index, in any order (a cluster); default: in this process, in order.
    progress : callable, optional
        ``progress(chunks_done, chunks_total, rows_done, seconds)`` after each chunk.

    Returns
    -------
    Path
        ``out``.
    """
    check_output_format(out)
    d = chunk_dir(out)
    manifest = json.dumps(spec.to_dict(), sort_keys=True, indent=1)
    if d.exists():
        if not resume:
            raise ValueError(f"output {str(out)!r} has unfinished chunks in {str(d)!r}; valid: --resume to finish "
                             "them, or remove that directory")
        old = (d / "spec.json").read_text() if (d / "spec.json").exists() else ""
        if old != manifest:
            raise ValueError(f"--resume: the chunks in {str(d)!r} come from another spec; valid: the same spec, "
                             "or remove that directory")
    else:
        d.mkdir(parents=True)
        atomic_write_text(d / "spec.json", manifest)
    total = n_chunks(spec)
    todo = [i for i in range(total) if not (d / f"chunk-{i:06d}.csv").exists()]
    done = total - len(todo)
    start = time.perf_counter()
    rows_done = 0
    run = mapper if mapper is not None else _in_process
    for i, text in run(lambda i: _chunk_text(compute_chunk(spec, i)), todo):
        atomic_write_text(d / f"chunk-{i:06d}.csv", text)
        done += 1
        rows_done += text.count("\n")
        if progress is not None:
            progress(done, total, rows_done, time.perf_counter() - start)
    _merge(spec, d, total, Path(out))
    shutil.rmtree(d)
    return Path(out)


def _in_process(fn: Callable[[int], str], indices: Sequence[int]) -> Iterable[tuple[int, str]]:
    for i in indices:
        yield i, fn(i)


def _merge(spec: SweepSpec, d: Path, total: int, out: Path) -> None:
    header = _chunk_text([columns(spec)])
    parts = [(d / f"chunk-{i:06d}.csv").read_text() for i in range(total)]
    if out.suffix.lower() == ".parquet":
        _write_parquet(spec, header + "".join(parts), out)
    else:
        atomic_write_text(out, header + "".join(parts))


def check_output_format(out: str | os.PathLike[str]) -> None:
    """Refuse a Parquet results file where pyarrow is not installed, before any chunk is computed.

    Parameters
    ----------
    out : path
        The results file (``.parquet`` needs pyarrow; ``.csv`` needs nothing).

    Raises
    ------
    ValueError
        In one line naming ``-o``, what it needs and the valid alternative.
    """
    if Path(out).suffix.lower() != ".parquet":
        return
    try:
        import pyarrow  # noqa: F401
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        raise ValueError("-o: a .parquet file needs pyarrow (pip install 'stability[scale]'); valid: a .csv file "
                         "without it") from None


def _write_parquet(spec: SweepSpec, text: str, out: Path) -> None:
    import pyarrow as pa  # checked before the sweep ran (check_output_format)
    import pyarrow.parquet as pq

    cols = columns(spec)
    data = read_rows(text)
    table = pa.table({c: pa.array(data[c], type=pa.string() if c in TEXT_COLUMNS else pa.float64()) for c in cols})
    with atomic_path(out) as tmp:
        pq.write_table(table, tmp)


def read_rows(text: str) -> dict[str, list]:
    """Columns of results CSV text.

    Parameters
    ----------
    text : str
        CSV with a header row.

    Returns
    -------
    dict of str to list
        Numbers as float, the :data:`TEXT_COLUMNS` as str.
    """
    reader = csv.reader(io.StringIO(text))
    head = next(reader)
    cols: dict[str, list] = {h: [] for h in head}
    for r in reader:
        for h, x in zip(head, r, strict=True):
            cols[h].append(x if h in TEXT_COLUMNS else float(x))
    return cols


#: The status column of a measure whose searches can end beyond their range (a bound is a value).
STATUS_OF = {"critical_speed_m_s": "critical_speed_status", "locked_critical_speed_m_s": "locked_critical_speed_status",
             "critical_impulse_Ns": "critical_impulse_status",
             "equal_instability_speed_m_s": "equal_instability_status", "shimmy_margin_m": "shimmy_margin_status",
             "human_limited_speed_m_s": "human_limited_status"}


def row_sides(data: dict[str, list], col: str) -> np.ndarray:
    """The side of every row's value of measure ``col`` (:func:`stability.study.censored.side_of` of its status
    column, :data:`STATUS_OF`): ``"="`` found, ``">"`` / ``"<"`` a bound; ``"="`` for a measure without bounds and
    for a row without a chair (:data:`INVALID`, its value NaN).

    Parameters
    ----------
    data : dict
        Column -> values, as :func:`read_rows` gives them.
    col : str
        A measure column.

    Returns
    -------
    ndarray of str
    """
    status = data.get(STATUS_OF.get(col, ""), [""] * len(data[col]))
    return np.array([side_of(x) if isinstance(x, str) and x != INVALID else "=" for x in status], dtype=object)


#: Units of the measure columns, as printed.
COLUMN_UNITS = {"growth_rate_1_s": "1/s", "critical_speed_m_s": "m/s", "locked_critical_speed_m_s": "m/s",
                "critical_impulse_Ns": "N s", "equal_instability_speed_m_s": "m/s", "shimmy_margin_m": "m",
                "static_stability_deg": "deg", "tip_toward_casters_deg": "deg", "tip_toward_main_wheels_deg": "deg",
                "tip_lateral_deg": "deg", "holding_moment_N_m_per_deg": "N m/deg", "human_limited_speed_m_s": "m/s",
                "bench_worst_score": "", "level_braking_distance_m": "m"}


def summary(spec: SweepSpec, data: dict[str, list], top: int = 3, level: float = 0.95) -> dict[str, Any]:
    """The best designs for each measure and speed by the conservative end of its interval over the draws.

    For a measure where more is better (critical impulse, critical speeds,
    equal-instability speed) designs are ranked by the low end of the
    central ``level`` interval over the draws; for the growth rate (less is
    better) by the high end.  A draw whose search ended beyond its range
    counts at its bound (a bound is a value: "above 3 m/s" ranks above any
    speed found inside the range), and an end that is such a bound says so
    (``conservative_side`` ``">"`` or ``"<"``).  Draws without a value
    (invalid chair, error) count as the worst case; a design with such a draw
    says how many.

    Parameters
    ----------
    spec : SweepSpec
    data : dict
        Columns (:func:`read_rows`).
    top : int
    level : float

    Returns
    -------
    dict
        ``{"level": level, "measures": {column: {"speeds_m_s": [...], "best": [[{"design": d, "grid": {...},
        "conservative": x, "conservative_side": "=" | ">" | "<", "median": m, "median_side": ..., "missing": n,
        "bounds": b}, ...], ...]}}}``: per speed (in the order of ``speeds_m_s``) the best designs first
        (``bounds``: draws beyond the searched range).
    """
    design = np.asarray(data["design"], dtype=int)
    speed = np.asarray(data["speed_m_s"], dtype=float)
    grid_cols = [f"grid_{a}" for a, _ in spec.grid]
    q = (1.0 - level) / 2.0
    result: dict[str, Any] = {}
    for m in spec.measures:
        for col in MEASURES[m][0]:
            if col not in HIGHER_IS_BETTER:
                continue
            up = HIGHER_IS_BETTER[col]
            vals = np.asarray(data[col], dtype=float)
            sides = row_sides(data, col)
            best = []
            for sp in spec.speeds:
                ranked: list[dict[str, Any]] = []
                for dsg in np.unique(design):
                    sel = (design == dsg) & (speed == sp)
                    v, sd = vals[sel], sides[sel]
                    fin = np.isfinite(v)
                    if not fin.any():
                        continue
                    cons, cons_side = quantile(v, sd, q if up else 1.0 - q)
                    med, med_side = quantile(v, sd, 0.5)
                    first = int(np.flatnonzero(sel)[0])
                    ranked.append({"design": int(dsg), "grid": {c[5:]: data[c][first] for c in grid_cols},
                                   "conservative": cons, "conservative_side": cons_side, "median": med,
                                   "median_side": med_side, "missing": int(v.size - fin.sum()),
                                   "bounds": int(sum(1 for x, f in zip(sd, fin, strict=True) if f and x != "="))})
                ranked.sort(key=lambda e: (e["missing"], sort_key(e["conservative"], e["conservative_side"], up)))
                best.append(ranked[:top])
            result[col] = {"speeds_m_s": [float(x) for x in spec.speeds], "best": best}
    return {"level": level, "measures": result}


def _grid_text(grid: dict[str, Any]) -> str:
    if not grid:
        return "the base chair"
    return ", ".join(f"{k} {v:g}" + (f" {GRID_UNITS[k]}" if k in GRID_UNITS else "") for k, v in grid.items())


def summary_text(spec: SweepSpec, s: dict[str, Any]) -> str:
    """The summary as a table of text: per measure and speed, the best designs first.

    Parameters
    ----------
    spec : SweepSpec
    s : dict
        From :func:`summary`.

    Returns
    -------
    str
    """
    lines = [f"best designs by the conservative end of the {100 * s['level']:g} % interval over {spec.draws} "
             "draw(s); a value beyond the searched range is ranked as its bound ('> 3 m/s' is at least 3 m/s)"]
    for col, per in s["measures"].items():
        end = "low end" if HIGHER_IS_BETTER[col] else "high end"
        unit = COLUMN_UNITS.get(col, "")
        for sp, ranked in zip(per["speeds_m_s"], per["best"], strict=True):
            lines.append(f"{col} at {sp:g} m/s ({end} | median | design):")
            if not ranked:
                lines.append("  no design has a value")
            for rank, e in enumerate(ranked, start=1):
                note = []
                if e["bounds"]:
                    note.append(f"{e['bounds']} draw(s) beyond the searched range")
                if e["missing"]:
                    note.append(f"{e['missing']} draw(s) without a value")
                lines.append(f"  {rank}. {describe(e['conservative'], e['conservative_side'], unit):>14} | "
                             f"{describe(e['median'], e['median_side'], unit):>14} | {_grid_text(e['grid'])}"
                             + (f" ({'; '.join(note)})" if note else ""))
    return "\n".join(lines)


