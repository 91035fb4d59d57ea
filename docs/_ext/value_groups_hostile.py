"""The value groups of docs/hostile-input.md: the work limits' largest allowed values, the heavy chair's caster
load (see ``value_groups.py``)."""

from __future__ import annotations

from value_groups import group


@group("hostile_limits", "stability.linear.batch (MAX_EIGEN_SOLVES, EIGEN_SECONDS) and "
       "MAX_EIGEN_SOLVES // stability.linear.intervals.solves_per_draw(len(SUMMARY_SPEEDS), GRID_POINTS) "
       "(python -m stability.critical_speed --uncertainty FILE --samples N refuses above it)", cheap=True)
def hostile_limits() -> dict:
    """The eigenvalue-problem budget and the largest sample count of the default table."""
    from stability.linear.batch import EIGEN_SECONDS, MAX_EIGEN_SOLVES
    from stability.linear.intervals import GRID_POINTS, solves_per_draw
    from stability.settings.defaults import SUMMARY_SPEEDS

    return {"solves": f"{MAX_EIGEN_SOLVES:.2g}".replace("e+0", "e"), "us_each": f"{1e6 * EIGEN_SECONDS:g}",
            "minutes": f"{MAX_EIGEN_SOLVES * EIGEN_SECONDS / 60:.0f}",
            "samples": f"{MAX_EIGEN_SOLVES // solves_per_draw(len(SUMMARY_SPEEDS), GRID_POINTS):,}"}


@group("hostile_heavy", "python -m stability.slope --cross-slope 2 --speed 0.75 --set m=200 --tire-range warn "
       "--json (normal_loads_N)", cheap=True)
def hostile_heavy() -> dict:
    """The casters' normal load of the E&J Premier at 200 kg on the slope command's default case."""
    import contextlib
    import io
    import json

    from stability.slope.__main__ import main

    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        status = main(["--cross-slope", "2", "--speed", "0.75", "--set", "m=200", "--tire-range", "warn", "--json"])
    if status != 0:
        raise RuntimeError(f"the slope command exited with status {status}")
    loads = json.loads(out.getvalue())["normal_loads_N"]
    lo, hi = sorted((loads["caster_left"], loads["caster_right"]))
    return {"mass": "200", "caster_lo": f"{lo:.0f}", "caster_hi": f"{hi:.0f}"}
