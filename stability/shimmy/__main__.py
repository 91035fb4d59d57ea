"""``python -m stability.shimmy``: caster shimmy summary for a chair (compliance values are estimates)."""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence

import numpy as np

from .. import cli
from .. import defaults as D
from .chair import CasterCompliance, caster_summary, trail_chart
from .chair_modes import chair_shimmy


def build_parser() -> cli.OneLineErrorParser:
    p = cli.OneLineErrorParser(prog="python -m stability.shimmy", description=__doc__)
    cli.add_chair_options(p)
    p.add_argument("--speeds", default=D.SHIMMY_SPEEDS,
                   help=f"START:STOP:STEP or a list (m/s; default {D.SHIMMY_SPEEDS})")
    p.add_argument("--relaxation-length", type=float, default=None, help="caster tire relaxation length (m)")
    p.add_argument("--lateral-stiffness", type=float, default=None, help="frame lateral stiffness at the pin (N/m)")
    p.add_argument("--amplitude-deg", type=float, default=D.SHIMMY_AMPLITUDE_DEG,
                   help=f"shimmy amplitude for the friction estimate, deg (default {D.SHIMMY_AMPLITUDE_DEG:g})")
    out = p.add_mutually_exclusive_group()
    out.add_argument("--json", action="store_true", help="print JSON to stdout")
    out.add_argument("--json-file", metavar="FILE", help="write JSON to FILE (atomically)")
    p.add_argument("--pdf", metavar="FILE", help="write the trail x speed design chart to FILE")
    p.add_argument("--chair-model", action="store_true",
                   help="also give the shimmy mode of the full chair model with relaxation-length caster tires "
                        "(rigid and compliant pins)")
    return p


def _fmt(x: float, scale: float = 1.0, spec: str = ".1f") -> str:
    return "none" if x == 0 else (">20" if math.isinf(x) else format(x * scale, spec))


def _body(args) -> int:
    chair = cli.load_chair(args.chair, args.set)
    cli.check_outputs({"--json-file": args.json_file, "--pdf": args.pdf}, {"--chair": args.chair})
    speeds = cli.parse_speeds(args.speeds)
    comp = CasterCompliance()
    for name in ("relaxation_length", "lateral_stiffness"):
        v = getattr(args, name)
        if v is not None:
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"--{name.replace('_', '-')}={v!r} is invalid; valid range: > 0 (finite)")
            lo, hi = getattr(comp, name + "_range")
            comp = comp.__class__(**{**comp.__dict__, name: v, name + "_range": (min(lo, v), max(hi, v))})
    if not (0 < args.amplitude_deg < 45):
        raise ValueError(f"--amplitude-deg={args.amplitude_deg!r} is invalid; valid range: 0 < value < 45 deg")
    s = caster_summary(chair, speeds, comp, math.radians(args.amplitude_deg))
    modes = {pin: chair_shimmy(chair, speeds, comp, pin=pin) for pin in ("rigid", "compliant")} \
        if args.chair_model else {}
    outputs = {"--json-file": args.json_file, "--pdf": args.pdf}
    with cli.output_files(outputs) as tmp:
        if args.json or args.json_file:
            mapping = s.to_mapping()
            if modes:
                mapping["chair_model"] = {f"{pin}_pin": m.to_mapping() for pin, m in modes.items()}
            options = {"speeds_m_s": [float(u) for u in speeds], "relaxation_length_m": comp.relaxation_length,
                       "lateral_stiffness_N_m": comp.lateral_stiffness, "amplitude_deg": args.amplitude_deg,
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
            print(f"{'speed':>6} {'linear':>9} {'freq':>6} {'growth':>7} {'crit trail cm':>20} "
                  f"{'friction N m':>13} {'held below cm':>14}")
            print(f"{'m/s':>6} {'':>9} {'Hz':>6} {'1/s':>7} {'nominal [range]':>20} "
                  f"{f'@{args.amplitude_deg:g} deg':>13} {'(pin friction)':>14}")
            for i, u in enumerate(s.speeds):
                rng = f"{_fmt(s.critical_trail[i], 100)} [{_fmt(s.critical_trail_low[i], 100)}-" \
                      f"{_fmt(s.critical_trail_high[i], 100)}]"
                print(f"{u:6.2f} {'stable' if s.stable[i] else 'SHIMMY':>9} {s.shimmy_frequency_hz[i]:6.1f} "
                      f"{s.shimmy_growth_rate[i]:7.2f} {rng:>20} {s.friction_needed[i]:13.3f} "
                      f"{_fmt(s.friction_trail[i], 100):>14}")
            print("crit trail: below it the caster shimmies without pin friction ('>20': at every trail up to 20 cm, "
                  "'none': at no trail); friction: Coulomb pin friction that holds shimmy of that amplitude "
                  "(describing function); held below: trail under which the chair's own pin friction no longer does.")
            for pin, m in modes.items():
                _print_chair_model(pin, m)
        if args.pdf:
            from ..output import _pyplot, write_pdf
            from .plots import plot_friction_needed, plot_trail_chart

            plt = _pyplot()
            chart = trail_chart(chair, np.linspace(0.02, 0.12, 26), speeds, comp, math.radians(args.amplitude_deg))
            fig1, ax1 = plt.subplots(figsize=(8, 6))
            plot_trail_chart(chart, ax1)
            fig2, ax2 = plt.subplots(figsize=(8, 5))
            plot_friction_needed(chart, ax2, trails_cm=[3, 4, 5, 6, 8])
            write_pdf([fig1, fig2], tmp["--pdf"], title=f"caster shimmy: {chair.name}")
    for path in outputs.values():
        if path:
            print(f"wrote {path}", file=sys.stderr)
    return 0


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
