"""The value groups of docs/advise.md: the advisor run once per chair (see ``value_groups.py``)."""

from __future__ import annotations

from value_groups import Table, fixed, group, pct, signed
from value_groups_pages import _preset, _span

ADVISE_CHAIRS = ("ej-premier", "revised", "ej-premier-front-caster", "power-fwd", "manual-front-caster",
                 "measured-example")
_ADVICE: dict = {}


def _advice(name: str):
    """``(chair, advise(chair), CPU seconds)`` of a preset or the measured example chair, once per process."""
    import time
    import warnings

    from value_groups import ROOT

    from stability import chair as chair_mod
    from stability.advise import advise

    if name not in _ADVICE:
        c = (chair_mod.load(ROOT / "docs" / "examples" / "measured_chair.toml") if name == "measured-example"
             else _preset(name))
        start = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")     # tire-range notes of candidate chairs (the verdict carries them)
            a = advise(c)
        _ADVICE[name] = (c, a, time.process_time() - start)
    return _ADVICE[name]


def _g(v) -> str:
    return "?" if v is None else f"{v:.3g}"


def _measures(prefix: str, m) -> dict:
    """The measures of one chair (as it is or changed) as formatted values under ``prefix``."""
    out = {f"{prefix}.ci": _g(m.critical_impulse_Ns.value), f"{prefix}.ci_lo": _g(m.critical_impulse_Ns.low),
           f"{prefix}.eis": _g(m.equal_instability_speed_m_s.value),
           f"{prefix}.eis_lo": _g(m.equal_instability_speed_m_s.low),
           f"{prefix}.eis_hi": _g(m.equal_instability_speed_m_s.high),
           f"{prefix}.tip": f"{m.static_stability_deg.value:.3g}",
           f"{prefix}.shimmy_cm": fixed(100 * m.shimmy_margin_m.value, 2),
           f"{prefix}.shimmy_mm": fixed(1e3 * m.shimmy_margin_m.value, 1),
           f"{prefix}.pin": f"{m.turning_effort_N_m:g}"}
    for k, v in m.tip_angles_deg.items():
        out[f"{prefix}.tip.{k}"] = f"{v:.3g}"
    return out


def _candidate(prefix: str, c) -> dict:
    out = {f"{prefix}.label": c.label, f"{prefix}.gain_pct": signed(100 * c.gain, 0),
           f"{prefix}.ci_gain_pct": signed(100 * c.gains["critical_impulse"], 0),
           f"{prefix}.eis_gain_pct": signed(100 * c.gains["equal_instability_speed"], 0)}
    return {**out, **_measures(prefix, c.measures)}


@group("advise_table", "python -m stability.advise --chair NAME (stability.advise.advise(chair))")
def advise_table() -> dict:
    """The advisor's verdict and recommendation for the presets and the measured example chair: the table, and
    per chair the recommendation, its single changes alone, the runner-up and the changes a limit blocks."""
    def fm(x, status):
        pre = {"above": "> ", "never": "> ", "below": "< "}.get(status, "")
        lo, hi = _g(x.low), _g(x.high)
        return f"{pre}{x.value:.3g}" + ("" if lo == hi else f" ({lo}-{hi})")      # no degenerate range

    rows, out, cpu = [], {}, []
    for name in ADVISE_CHAIRS:
        c, a, took = _advice(name)
        cpu.append(took)
        v, r = a.verdict, a.recommendations[0]
        p = r.candidate.measures
        rows.append((name, fm(v.critical_impulse_Ns, v.critical_impulse_status),
                     fm(v.equal_instability_speed_m_s, v.equal_instability_status),
                     f"{v.static_stability_deg.value:.1f}", f"{v.shimmy_margin_m.value * 100:+.2f}", r.candidate.label,
                     fm(p.critical_impulse_Ns, p.critical_impulse_status),
                     fm(p.equal_instability_speed_m_s, p.equal_instability_status)))
        out[f"{name}.eis"] = f"{v.equal_instability_speed_m_s.value:.3g}"
        out[f"{name}.ci"] = f"{v.critical_impulse_Ns.value:.3g}"
        out.update(_measures(f"{name}.verdict", v))
        out.update(_candidate(f"{name}.rec", r.candidate))
        out[f"{name}.rec.eis_status"] = p.equal_instability_status
        for i, b in enumerate(r.built_from):
            out.update(_candidate(f"{name}.rec.alone{i}", b))
        for rec in a.recommendations[1:2]:
            out.update(_candidate(f"{name}.runner", rec.candidate))
        for i, b in enumerate(a.blocked):
            out.update(_candidate(f"{name}.blocked{i}", b.candidate))
            out[f"{name}.blocked{i}.allow"] = b.allow
        out[f"{name}.singles"] = str(len(a.candidates))
        out[f"{name}.pairs_measured"] = str(a.pairs_measured)
        out[f"{name}.pairs_screened"] = str(a.pairs_screened)
        out[f"{name}.changes"] = str(len(a.candidates) + len(a.combinations))
        out[f"{name}.computed"] = str(a.intervals_computed)
    ej, rv = float(out["ej-premier.eis"]), float(out["revised.eis"])
    out["eis_gain_pct"] = pct(rv / ej - 1)
    out["ci_gain_pct"] = pct(float(out["revised.ci"]) / float(out["ej-premier.ci"]) - 1)
    out["singles"] = _span([int(out[f"{n}.singles"]) for n in ADVISE_CHAIRS], str)
    out["pairs_measured_max"] = str(max(int(out[f"{n}.pairs_measured"]) for n in ADVISE_CHAIRS))
    out["cpu_s"] = f"{min(cpu):.1f}-{max(cpu):.1f}"
    out["changes"] = _span([int(out[f"{n}.changes"]) for n in ADVISE_CHAIRS], str)
    out["computed"] = _span([int(out[f"{n}.computed"]) for n in ADVISE_CHAIRS], str)
    out["table"] = Table(("chair", "critical impulse", "equal-instability speed", "tip", "shimmy margin",
                          "recommendation", "predicted critical impulse", "predicted equal-instability speed"),
                         tuple(rows))
    return out


@group("advise_tip_interval", "python -m stability.advise --chair docs/examples/measured_chair.toml --uncertainty "
       "docs/examples/measured_chair.uncertainty.toml (stability.advise.uncertain.tip_interval(chair, "
       "load_uncertainty(FILE)))", cheap=True)
def advise_tip_interval() -> dict:
    """The measured example chair's static stability interval over its uncertainty file."""
    from value_groups import ROOT

    from stability import chair as chair_mod
    from stability.advise.uncertain import tip_interval
    from stability.uncertainty import load_uncertainty

    ex = ROOT / "docs" / "examples"
    lo, hi = tip_interval(chair_mod.load(ex / "measured_chair.toml"),
                          load_uncertainty(ex / "measured_chair.uncertainty.toml"))
    return {"lo": fixed(lo, 1), "hi": fixed(hi, 1)}
