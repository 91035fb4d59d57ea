"""The value groups of docs/report.md: the E&J Premier's numbers as the report's own functions compute them (see
``value_groups.py``)."""

from __future__ import annotations

import math

from value_groups import fixed, group, sig, signed
from value_groups_pages import _preset

#: issue 35: the quick report at most this share of the full report's CPU time
QUICK_TARGET = 0.25

#: docs/report.md's growth-rate uncertainty (uniform): s1 +-0.01 m, I_z +-0.3 kg m^2 about the chair's, pin damping
#: 0-0.05 N m s/rad
S1_HALF, I_Z_HALF, PIN_DAMPING_SPAN = 0.01, 0.3, (0.0, 0.05)


def _uncertainty_text(c) -> str:
    return (f'[s1]\ndistribution = "uniform"\nlow = {c.s1 - S1_HALF!r}\nhigh = {c.s1 + S1_HALF!r}\n\n'
            f'[i_z]\ndistribution = "uniform"\nlow = {c.i_z - I_Z_HALF!r}\nhigh = {c.i_z + I_Z_HALF!r}\n\n'
            f'[pin_damping]\ndistribution = "uniform"\nlow = {PIN_DAMPING_SPAN[0]!r}\nhigh = {PIN_DAMPING_SPAN[1]!r}\n')


@group("report_slope", "stability.report.slope_data.slope_section(ej_premier) (python -m stability.report --chair "
       "ej-premier: the cross-slope page)")
def report_slope() -> dict:
    """The cross-slope page's numbers for the E&J Premier."""
    import numpy as np

    from stability.report.slope_data import TREADMILL, slope_section

    s = slope_section(_preset("ej-premier"))
    c = s.curve
    i6 = int(np.argmax(c.cross_slopes_deg))
    mean, lo, hi = s.treadmill_m_x
    p = s.path
    out = {"speed": f"{s.speed:g}", "per_deg": fixed(s.per_degree, 2),
           "closed_form": fixed(s.closed_form_per_degree, 2),
           "top_slope": f"{c.cross_slopes_deg[i6]:g}", "top_moment": sig(c.holding_moment[i6], 3),
           "band_lo": sig(c.friction_low[i6], 3), "band_hi": sig(c.friction_high[i6], 3),
           "rim_top": sig(s.drive_difference[i6], 3), "m_x": sig(s.m_x, 3),
           "treadmill_lo": sig(lo, 2), "treadmill_hi": sig(hi, 2),
           "times_mean": sig(s.per_degree / TREADMILL[0], 2), "path_slope": f"{s.path_slope:g}"}
    if p is not None:
        out.update(turn=p.turn, heading=signed(float(s.path_heading_deg[-1]), 1), end=fixed(float(p.t[-1]), 2),
                   ended=p.ended)
    return out


@group("report_shimmy", "stability.report.shimmy_data.shimmy_section(ej_premier, Settings.for_mode(quick=True)"
       ".shimmy_trails, .shimmy_speeds) (the report's shimmy page, --quick)")
def report_shimmy() -> dict:
    """The nominal and chair-model shimmy boundaries and their range over the compliance estimates."""
    import math

    from stability.report.settings import Settings
    from stability.report.shimmy_data import shimmy_section

    st = Settings.for_mode(True)
    sh = shimmy_section(_preset("ej-premier"), st.shimmy_trails, st.shimmy_speeds)
    finite = [x for _, _, x in sh.corners if math.isfinite(x)]
    return {"critical_cm": sig(100 * sh.critical, 3), "chair_model_cm": sig(100 * sh.chair_model_critical, 3),
            "lo_cm": sig(100 * min(finite), 3),
            "hi": "> 25" if any(not math.isfinite(x) for _, _, x in sh.corners) else sig(100 * max(finite), 3)}


@group("report_elasticities", "stability.study.elasticities(ej_premier, 0.75, report_run('exact', "
       "Settings.for_mode(quick=True), 'wchair'), rel_tol=0.01) (the report's parametric page, --quick)")
def report_elasticities() -> dict:
    """The critical impulse's elasticities (the report's --quick settings)."""
    from stability import study
    from stability.report.compute import report_run
    from stability.report.settings import Settings

    st = Settings.for_mode(True)
    sens = study.elasticities(_preset("ej-premier"), 0.75, report_run("exact", st, "wchair"), rel_tol=st.impulse_tol)
    out = {"impulse_lo": sig(sens.nominal.low_Ns, 3), "impulse_hi": sig(sens.nominal.high_Ns, 3)}
    for e in sens.elasticities:
        out[e.parameter] = signed(e.critical_impulse, 2) if e.critical_impulse is not None else "undefined"
    out["names"] = ", ".join(e.parameter for e in sens.elasticities)
    return out


@group("report_growth", "stability.linear.intervals.linear_intervals(ej_premier, loads_uncertainty(FILE), "
       "speeds=[0.75], samples=1000, seed=0) with FILE: s1 +-0.01 m, I_z +-0.3 kg m^2 uniform, pin damping "
       "0-0.05 N m s/rad (python -m stability.critical_speed --uncertainty FILE --speeds 0.75)")
def report_growth() -> dict:
    """The growth rate's 95 % interval at 0.75 m/s and its dominant parameter."""
    from stability.linear.intervals import linear_intervals
    from stability.uncertainty import loads_uncertainty

    c = _preset("ej-premier")
    li = linear_intervals(c, loads_uncertainty(_uncertainty_text(c)), speeds=[0.75])
    lo, hi = li.rate[0]
    return {"lo": fixed(lo, 2), "hi": fixed(hi, 2), "dominant": li.dominant_parameters[0][0],
            "level": f"{100 * li.level:g}"}


@group("report_span", "stability.chair.design._cg_ratio_span(chair) (the c.g.-ratio span of the root loci) for "
       "ej-premier-front-caster; CG_RATIO_SPAN", cheap=True)
def report_span() -> dict:
    """Where the front-caster E&J Premier's c.g.-ratio locus ends, against the default span."""
    from stability.chair.design import CG_RATIO_SPAN, _cg_ratio_span

    return {"fc_hi": f"{_cg_ratio_span(_preset('ej-premier-front-caster'))[1]:.3f}",
            "default_hi": f"{CG_RATIO_SPAN[1]:.2f}"}


#: Counted rounds of the quick/full CPU measurement (each round runs both reports, in turn).
QUICK_CPU_ROUNDS = 3


@group("report_quick", "simulated runs counted at stability.simulate.engine._launch: "
       "stability.report.brief.compute_brief(ej_premier), stability.advise.advise(ej_premier) (with its memo, "
       "without it, prune=False), stability.report.compute.compute(ej_premier); CPU time (user + sys of the child) "
       "of python -m stability.report --chair ej-premier [--quick] --no-progress -o FILE, the two run in turn, "
       "best of 3 rounds after one uncounted, on the build machine, with python -c 'import stability.report.__main__' "
       "(the imports) in the same rounds; the advisor's CPU time (time.process_time around advise(ej_premier) in "
       "this process, best of 2); the three pages' CPU time (time.process_time around "
       "stability.report.document.build(ej_premier, FILE, data=the brief's data) in this process, best of 2)")
def report_quick() -> dict:
    """The quick report's work against the full report's, their CPU time on the machine that built the page, and
    the advisor's share of both."""
    import contextlib
    import os
    import tempfile
    import time

    from value_groups import best_alternating

    from stability.advise import advise
    from stability.report.brief import compute_brief
    from stability.report.compute import compute
    from stability.report.document import build
    from stability.simulate import engine
    from stability.study import memo

    c = _preset("ej-premier")
    n = [0]
    inner = engine._launch
    advisor_cpu = [math.inf]

    def counting(k, threads, n_runs, args):
        n[0] += int(n_runs)
        return inner(k, threads, n_runs, args)

    def runs(fn) -> int:
        start = n[0]
        fn()
        return n[0] - start

    def timed_advice() -> None:
        t0 = time.process_time()
        advise(c)
        advisor_cpu[0] = min(advisor_cpu[0], time.process_time() - t0)

    engine._launch = counting
    orig = memo.search_memo
    try:
        brief = []
        out = {"runs_quick": runs(lambda: brief.append(compute_brief(c, progress=False))),
               "runs_advisor": runs(timed_advice),
               "runs_every": runs(lambda: advise(c, prune=False)),
               "runs_full": runs(lambda: compute(c, progress=False))}
        timed_advice()
        memo.search_memo = contextlib.nullcontext            # type: ignore[assignment]
        out["runs_no_memo"] = runs(lambda: advise(c))
    finally:
        memo.search_memo = orig
        engine._launch = inner

    with tempfile.TemporaryDirectory() as tmp:
        pdf = os.path.join(tmp, "r.pdf")
        pages_cpu = math.inf
        for _ in range(2):                      # the pages of the quick report, its data already computed
            t0 = time.process_time()
            build(c, pdf, data=brief[0], progress=False)
            pages_cpu = min(pages_cpu, time.process_time() - t0)
        base = ["-m", "stability.report", "--chair", "ej-premier", "--no-progress", "-o", pdf]
        cpu = best_alternating({"quick": [*base, "--quick"], "full": base,
                                "imports": ["-c", "import stability.report.__main__"]}, QUICK_CPU_ROUNDS)
    quick, full, adv, imports = cpu["quick"], cpu["full"], advisor_cpu[0], cpu["imports"]
    return {**{k: f"{v:,}" for k, v in out.items()}, "quick_cpu_s": sig(quick, 2), "full_cpu_s": sig(full, 2),
            "ratio": fixed(quick / full, 2),
            "ratio_verdict": "reached" if quick / full <= QUICK_TARGET else "not reached",
            "advisor_cpu_s": sig(adv, 2), "rest_cpu_s": sig(quick - adv, 2),
            "ratio_without_advisor": fixed((quick - adv) / (full - adv), 2), "rounds": f"{QUICK_CPU_ROUNDS}",
            "imports_cpu_s": sig(imports, 2), "pages_cpu_s": sig(pages_cpu, 2),
            "other_cpu_s": sig(quick - adv - imports - pages_cpu, 2),
            "ratio_floor": fixed((imports + pages_cpu) / full, 2)}


@group("report_pages", "the committed reports' page lists (reports/NAME.txt, written by python "
       "tests/test_committed_reports.py, which the slow test keeps equal to what the code builds) split by "
       "stability.report.contents.parts", cheap=True)
def report_pages() -> dict:
    """Each committed report's pages: how many, the results and the appendix, and the pages left out."""
    import re
    from pathlib import Path

    from value_groups import Table

    from stability.report.contents import RESULTS_LIMIT, parts

    root = Path(__file__).resolve().parents[2]
    out: dict = {}
    rows = []
    for name in ("ej-premier", "revised", "ej-premier-front-caster", "measured-chair"):
        text = (root / "reports" / f"{name}.txt").read_text(encoding="utf-8")
        titles = re.findall(r"^=== page \d+: (.*)$", text, flags=re.M)
        results, appendix = parts(titles)
        left = re.search(r"Pages left out of this report, and why[^\n]*\n((?:- [^\n]*\n(?:  [^\n]*\n)*)*)", text)
        gone = [] if left is None else [ln[2:].split(":", 1)[0] for ln in left.group(1).splitlines()
                                        if ln.startswith("- ")]
        out[f"{name}.pages"] = str(len(titles))
        out[f"{name}.results"] = str(len(results))
        out[f"{name}.appendix"] = str(len(appendix))
        rows.append((name, str(len(titles)), f"{len(results)} (pp. 1-{results[-1]})",
                     f"{len(appendix)} (pp. {appendix[0]}-{appendix[-1]})", "; ".join(gone) or "none"))
    out["table"] = Table(("report", "pages", "results", "appendix", "left out (cannot apply to the chair)"),
                         tuple(rows))
    counts = [int(out[f"{r[0]}.results"]) for r in rows]
    out["min_results"], out["max_results"] = str(min(counts)), str(max(counts))
    out["results_limit"] = str(RESULTS_LIMIT)
    return out
