"""``python -m stability.shimmy``: caster shimmy summary for a chair (compliance values are estimates)."""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence

import numpy as np

from stability import cli
from stability.settings import defaults as D
from stability.shimmy.band import ShimmyBand, margin_words, shimmy_band
from stability.shimmy.chair import SECONDS_PER_SPEED, CasterCompliance, caster_summary, check_speed_count, trail_chart
from stability.shimmy.chair_modes import chair_shimmy

#: Trails of the PDF's trail x speed chart, m.
CHART_TRAILS_M = np.linspace(0.02, 0.12, 26)
#: The models of the charts, for their titles.
SHORT_FORM_MODELS = "left caster as a towed wheel (shimmy); exact linear model (yaw divergence)"
LAYOUT_MODELS = ("caster row as a towed wheel at its own static load (shimmy); layout linear model (yaw "
                 "divergence)")


def _check_chart_speeds(args, speeds: np.ndarray) -> None:
    """-o draws a trail x speed chart per direction: at least two speeds in each direction given."""
    if not args.output:
        return
    for name, u in (("forwards", speeds[speeds > 0]), ("backwards", speeds[speeds < 0])):
        if u.size == 1:
            raise ValueError(f"--speeds {args.speeds!r} gives 1 speed {name}; -o draws a trail x speed chart, "
                             "valid: at least 2 speeds in each direction (e.g. --speeds 0.5:2:0.5)")


def build_parser() -> cli.OneLineErrorParser:
    p = cli.OneLineErrorParser(prog="python -m stability.shimmy", description=__doc__)
    cli.add_chair_options(p)
    p.add_argument("--speeds", default=D.SHIMMY_SPEEDS,
                   help=f"START:STOP:STEP or a list (m/s; negative: reverse, each caster row swung round; "
                        f"default {D.SHIMMY_SPEEDS})")
    p.add_argument("--relaxation-length", type=float, default=None, help="caster tire relaxation length (m)")
    p.add_argument("--lateral-stiffness", type=float, default=None, help="frame lateral stiffness at the pin (N/m)")
    p.add_argument("--amplitude-deg", type=float, default=D.SHIMMY_AMPLITUDE_DEG,
                   help=f"shimmy amplitude for the friction estimate, deg (default {D.SHIMMY_AMPLITUDE_DEG:g})")
    cli.add_json_options(p)
    cli.add_output_option(p, ("pdf",), what="the trail x speed design chart and the friction needed (a PDF, "
                          "one figure a page; a layout: two pages per caster row and direction)", aliases=("--pdf",))
    p.add_argument("--chair-model", action="store_true",
                   help="also give the shimmy mode of the full chair model with relaxation-length caster tires "
                        "(rigid and compliant pins)")
    return p


def _fmt(x: float, scale: float = 1.0, spec: str = ".1f") -> str:
    return "none" if x == 0 else (">20" if math.isinf(x) else format(x * scale, spec))


def _compliance(args) -> CasterCompliance:
    comp = CasterCompliance()
    for name in ("relaxation_length", "lateral_stiffness"):
        v = getattr(args, name)
        if v is not None:                       # parsed within its range (OPTION_BOUNDS)
            lo, hi = getattr(comp, name + "_range")
            comp = comp.__class__(**{**comp.__dict__, name: v, name + "_range": (min(lo, v), max(hi, v))})
    return comp


def _body(args) -> int:
    from stability.layout.io import is_layout_spec

    if is_layout_spec(args.chair):
        return _body_layout(args)
    chair = cli.load_chair(args.chair, args.set)
    cli.check_outputs({"--json-file": args.json_file, "-o": args.output}, {"--chair": args.chair})
    speeds = cli.parse_speeds(args.speeds, signed=True)
    _check_chart_speeds(args, speeds)
    if np.any(speeds < 0):
        # reverse: the casters swing round and carry the reversed statics' loads, which the layout form computes
        if args.chair_model:
            raise ValueError(f"--chair-model with --speeds {args.speeds!r} is invalid: the full-chair shimmy model "
                             "is linearised about casters trailing behind their pins in forward motion, and in "
                             "reverse they lead them (an unstable state the casters swing out of); valid: "
                             "--chair-model with speeds > 0")
        from stability.layout import Layout

        return _layout_answer(args, Layout.from_chair(chair), speeds)
    check_speed_count("--speeds", len(speeds), SECONDS_PER_SPEED["summary"]
                      + (SECONDS_PER_SPEED["chart"] if args.output else 0.0))
    comp = _compliance(args)
    s = caster_summary(chair, speeds, comp, math.radians(args.amplitude_deg))
    band = shimmy_band(chair, speeds, comp)
    modes = {pin: chair_shimmy(chair, speeds, comp, pin=pin) for pin in ("rigid", "compliant")} \
        if args.chair_model else {}
    outputs = {"--json-file": args.json_file, "-o": args.output}
    with cli.output_files(outputs) as tmp:
        if args.json or args.json_file:
            mapping = s.to_mapping()
            mapping["shimmy_band"] = band.to_mapping()
            if modes:
                mapping["chair_model"] = {f"{pin}_pin": m.to_mapping() for pin, m in modes.items()}
            options = {"speeds_m_s": [float(u) for u in speeds], "relaxation_length_m": comp.relaxation_length,
                       "lateral_stiffness_N_per_m": comp.lateral_stiffness, "amplitude_deg": args.amplitude_deg,
                       "chair_model": bool(args.chair_model)}
            cli.emit_json({**cli.json_header(chair, "exact", options), **mapping}, args,
                          write_to=tmp.get("--json-file"))
        if not args.json:
            print(f"caster shimmy, chair {s.chair_name!r} (left caster as a towed wheel on its pin; trail "
                  f"{s.trail * 100:g} cm, pin friction {s.pin_friction:g} N m)")
            print(f"NOTE: {s.note}: relaxation length {comp.relaxation_length * 1000:g} mm "
                  f"(range {comp.relaxation_length_range[0] * 1000:g}-{comp.relaxation_length_range[1] * 1000:g}), "
                  f"lateral stiffness {comp.lateral_stiffness / 1000:g} kN/m "
                  f"(range {comp.lateral_stiffness_range[0] / 1000:g}-{comp.lateral_stiffness_range[1] / 1000:g}).")
            _print_table(s, band, args.amplitude_deg)
            _print_band(band)
            for pin, m in modes.items():
                _print_chair_model(pin, m)
        if args.output:
            from stability.runtime.files import write_pdf
            from stability.shimmy.plots import trail_chart_pages

            chart = trail_chart(chair, CHART_TRAILS_M, speeds, comp, math.radians(args.amplitude_deg))
            write_pdf(trail_chart_pages(chart, SHORT_FORM_MODELS), tmp["-o"], title=f"caster shimmy: {chair.name}")
    for path in outputs.values():
        if path:
            print(f"wrote {path}", file=sys.stderr)
    return 0


def _print_table(s, band: ShimmyBand, amplitude_deg: float, speeds: np.ndarray | None = None) -> None:
    """The per-speed table of one caster and its legend (``speeds``: the signed speeds to show, m/s; default
    the summary's)."""
    print(f"{'speed':>6} {'linear':>9} {'freq':>6} {'growth':>7} {'damping':>8} {'shimmy-free trail cm':>22} "
          f"{'friction N m':>13} {'held below cm':>14}")
    print(f"{'m/s':>6} {'':>9} {'Hz':>6} {'1/s':>7} {'ratio':>8} {'(nominal estimates)':>22} "
          f"{f'@{amplitude_deg:g} deg':>13} {'(pin friction)':>14}")
    for i, u in enumerate(s.speeds if speeds is None else speeds):
        print(f"{u:6.2f} {'stable' if s.stable[i] else 'SHIMMY':>9} {s.shimmy_frequency_hz[i]:6.1f} "
              f"{s.shimmy_growth_rate[i]:7.2f} {band.damping_ratio[i]:8.4f} {band.describe(i):>22} "
              f"{s.friction_needed[i]:13.3f} {_fmt(s.friction_trail[i], 100):>14}")
    print("linear/growth/damping: the caster at this chair's trail without Coulomb pin friction; shimmy-free "
          "trail: every band of trail (searched 0.1-25 cm, '+': goes on beyond 25 cm) where it does not "
          "shimmy; friction: Coulomb pin friction that holds shimmy of that amplitude (describing function); "
          "held below: trail under which the chair's own pin friction no longer does.")


def _body_layout(args) -> int:
    """Every caster row of a wheel layout: the towed-wheel summary and band at the caster's own static load."""
    if args.chair_model:
        raise ValueError(f"--chair-model with --chair {args.chair!r} is invalid: the full-chair shimmy model's "
                         "equations (relaxation-length caster tires, compliant pins, coupled to the body) are "
                         "derived for two main wheels and one caster pair; a layout's casters are answered row by "
                         "row as towed wheels at their own static loads; valid: --chair-model with a short-form "
                         "chair (e.g. --chair ej-premier)")
    cli.check_outputs({"--json-file": args.json_file, "-o": args.output}, {"--chair": args.chair})
    speeds = cli.parse_speeds(args.speeds, signed=True)
    _check_chart_speeds(args, speeds)
    return _layout_answer(args, cli.load_layout(args.chair, args.set), speeds)


def _rows(layout, reverse: bool) -> list:
    """One caster per row and direction (a left-right pair on one pin line shares its answer)."""
    from stability.shimmy.layout_caster import layout_casters

    rows, seen = [], set()
    for c in layout_casters(layout, reverse):
        cc = layout.casters[c.index]
        key = (round(cc.x, 9), cc.trail, cc.m_c, cc.i_zp, cc.l, cc.tire, cc.pin_damping, cc.pin_friction,
               cc.lateral_scale, round(c.static_load(), 6))
        if key not in seen:
            seen.add(key)
            rows.append(c)
    return rows


def _layout_answer(args, layout, speeds: np.ndarray) -> int:
    """Every caster row of ``layout`` at the forward speeds and, swung round, at the reverse ones."""
    from stability.shimmy.layout_caster import leading_divergence_rate

    comp = _compliance(args)
    groups = [(rev, speeds[speeds < 0] if rev else speeds[speeds > 0]) for rev in (False, True)]
    groups = [(rev, u) for rev, u in groups if u.size]
    rows = [(c, u) for rev, u in groups for c in _rows(layout, rev)]
    if not rows:
        raise ValueError(f"--chair {args.chair!r}: the layout has no casters; valid: a layout with casters")
    check_speed_count("--speeds", sum(u.size for _, u in rows), SECONDS_PER_SPEED["summary"]
                      + (SECONDS_PER_SPEED["chart"] if args.output else 0.0))
    amp = math.radians(args.amplitude_deg)
    results = [(c, u, caster_summary(c, np.abs(u), comp, amp), shimmy_band(c, np.abs(u), comp)) for c, u in rows]
    with cli.output_files({"--json-file": args.json_file, "-o": args.output}) as tmp:
        if args.output:
            from stability.runtime.files import write_pdf
            from stability.shimmy.plots import trail_chart_pages

            write_pdf([fig for c, u, *_ in results
                       for fig in trail_chart_pages(trail_chart(c, CHART_TRAILS_M, np.abs(u), comp, amp),
                                                    LAYOUT_MODELS + (" | reverse: speeds backwards, casters swung "
                                                                     "round" if c.reverse else ""))],
                      tmp["-o"], title=f"caster shimmy: {layout.name}")
        if args.json or args.json_file:
            casters = []
            for c, u, s, b in results:
                signed = [float(x) for x in u]
                entry = {"caster": c.name, "direction": "reverse" if c.reverse else "forward",
                         "static_load_N": c.static_load(), **s.to_mapping(),
                         "shimmy_band": {**b.to_mapping(), "speeds_m_s": signed}, "speeds_m_s": signed}
                if c.reverse:
                    entry["leading_divergence_rate_1_s"] = [float(x) for x in leading_divergence_rate(c.trail, u)]
                casters.append(entry)
            doc = {"schema": "stability.shimmy.layout/1", "layout": layout.name,
                   "options": {"speeds_m_s": [float(u) for u in speeds],
                               "relaxation_length_m": comp.relaxation_length,
                               "lateral_stiffness_N_per_m": comp.lateral_stiffness,
                               "amplitude_deg": args.amplitude_deg},
                   "casters": casters}
            cli.emit_json(doc, args, write_to=tmp.get("--json-file"))
        if not args.json:
            print(f"caster shimmy, layout {layout.name!r}: each caster row as a towed wheel on its pin at its own "
                  f"static load (a left-right pair shares one answer)")
            print(f"NOTE: {results[0][2].note}: relaxation length {comp.relaxation_length * 1000:g} mm, lateral "
                  f"stiffness {comp.lateral_stiffness / 1000:g} kN/m.")
            if any(c.reverse for c, *_ in results):
                print("reverse (negative speeds): when the chair reverses each caster leads its pin, which is "
                      "unstable (its swivel angle grows at 'leading' 1/s, |speed|/trail); it swings round and "
                      "trails the other way, so its shimmy is the towed wheel's at |speed| with the load of the "
                      "casters trailing backwards (each contact moved by twice the trail)")
            for c, u, s, band in results:
                print(f"\n{c.name}: trail {c.trail * 100:g} cm, pin friction {c.pin_friction_left:g} N m, static "
                      f"load {c.static_load():.1f} N")
                if c.reverse:
                    rate = leading_divergence_rate(c.trail, u)
                    print("leading 1/s: " + ", ".join(f"{x:g} m/s: {r:.1f}" for x, r in zip(u, rate, strict=True)))
                _print_table(s, band, args.amplitude_deg, u)
                _print_band(band, u)
    for path in (args.json_file, args.output):
        if path:
            print(f"wrote {path}", file=sys.stderr)
    return 0


def _print_band(band: ShimmyBand, speeds: np.ndarray | None = None) -> None:
    shown = band.speeds_m_s if speeds is None else tuple(float(u) for u in speeds)
    m, (lo, hi) = band.shimmy_margin_m, band.shimmy_margin_interval_m
    near = band.nearest_boundary_m
    k = int(np.argmin(band.margin_m))
    if near is None:
        where = margin_words(m)
    else:
        side = "inside the shimmy-free band" if m > 0 else "inside a shimmy zone"
        where = (f"{abs(m) * 100:.2f} cm {side}, nearest boundary {near * 100:.2f} cm "
                 f"(at {shown[k]:g} m/s; damping ratio there {band.damping_ratio[k]:.4f})")
    print(f"this chair's trail {band.trail_m * 100:g} cm: {where}")

    def cm(x: float) -> str:
        return "unbounded" if math.isinf(x) and x > 0 else ("shimmies at every trail" if math.isinf(x)
                                                             else f"{x * 100:+.2f} cm")

    print(f"  margin over the estimate ranges (4 corners): {cm(lo)} to {cm(hi)}"
          + ("; the range straddles a boundary: measure pin lateral stiffness and caster relaxation length first"
             if band.straddles else ""))
    for c, iv in zip(band.compliance.corners(), band.corner_intervals_m, strict=True):
        bands = ", ".join(f"{a * 100:.1f}-{b * 100:.1f}" for a, b in iv[0])
        text = f"shimmy-free {bands} cm" if bands else "no shimmy-free trail"
        print(f"  relaxation {c.relaxation_length * 1000:g} mm, pin stiffness {c.lateral_stiffness / 1000:g} kN/m: "
              f"{text} at {shown[0]:g} m/s")


def _print_chair_model(pin: str, m) -> None:
    print(f"chair model with relaxation-length caster tires, {pin} pins (shimmy mode = least damped oscillation "
          f"above 2 Hz; divergence = chair's own modes, rigid-tire rate from stability.linear):")
    print(f"{'speed':>6} {'freq Hz':>8} {'damping':>8} {'Re 1/s':>8} {'diverg 1/s':>11} {'rigid-tire':>11} "
          f"{'crit trail cm':>14}")
    for i, u in enumerate(m.speeds):
        print(f"{u:6.2f} {m.frequency_hz[i]:8.2f} {m.damping_ratio[i]:8.4f} {m.real_part[i]:8.2f} "
              f"{m.divergence_rate[i]:11.3f} {m.rigid_tire_rate[i]:11.3f} {_fmt(m.critical_trail[i], 100, '.2f'):>14}")


def main(argv: Sequence[str] | None = None) -> int:
    return cli.run(build_parser(), argv, _body)


if __name__ == "__main__":
    raise SystemExit(main())
