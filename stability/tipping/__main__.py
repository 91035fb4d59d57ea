"""``python -m stability.tipping``: ISO 7176-1 static stability angles (rigid chair, brakes locked)."""

from __future__ import annotations

import argparse
from collections.abc import Sequence

from stability import __version__, cli
from stability.tipping.angles import DIRECTIONS, LOANE_KIRBY_REAR_DEG, slope_tip, tip_angles

_WORDS = {"toward_main_wheels": "toward the main wheels", "toward_casters": "toward the casters",
          "lateral_left": "over the left side", "lateral_right": "over the right side"}


def build_parser() -> argparse.ArgumentParser:
    p = cli.OneLineErrorParser(prog="python -m stability.tipping", description=__doc__)
    cli.add_chair_options(p)
    p.add_argument("--cross-slope", type=float, default=0.0, metavar="DEG",
                   help="cross slope (deg, or 2%%, 1:50), positive falling to the right; with --grade: tipping on "
                        "that slope (default 0)")
    p.add_argument("--grade", type=float, default=0.0, metavar="DEG",
                   help="grade (deg, or 8%%, 1:12), uphill + (default 0)")
    cli.add_json_options(p)
    return p


def _slope_line(s) -> str:
    """The tipping on the given slope in one line (the chair and the layout forms alike)."""
    return (f"  on cross slope {s.cross_slope_deg:.3g} deg + grade {s.grade_deg:.3g} deg (tilt {s.tilt_deg:.2f} deg): "
            f"tips at a tilt of {s.tip_deg:.1f} deg along the same fall line, margin {s.margin_deg:+.1f} deg")


def _body(a: argparse.Namespace) -> int:
    cli.check_outputs({"--json-file": a.json_file}, {"--chair": a.chair})
    from stability.layout.io import is_layout_spec

    if is_layout_spec(a.chair):
        return _layout(a)
    chair = cli.load_chair(a.chair, a.set)
    t = tip_angles(chair)
    s = slope_tip(chair, a.cross_slope, a.grade)
    data = {**t.to_mapping(), "slope": s.to_mapping(), "reference_rear_stability_deg": LOANE_KIRBY_REAR_DEG}
    if a.json or a.json_file:
        options = {"cross_slope_deg": a.cross_slope, "grade_deg": a.grade}
        cli.emit_json({**cli.json_header(chair, None, options), **data}, a)
        if a.json:
            return 0
    print(f"{chair.name}: static stability angles (ISO 7176-1 directions; rigid chair, brakes locked, casters "
          "in their least stable swivel orientation)")
    for k in DIRECTIONS:
        ln = t.lines[k]
        casters = [f"{side} caster at {ang:+.0f} deg" for side, ang in zip(("left", "right"), ln.caster_angles_deg,
                                                                          strict=True) if ang is not None]
        extra = f" ({', '.join(casters)} from trailing)" if casters else ""
        print(f"  {_WORDS[k]:<24} {getattr(t, k + '_deg'):6.1f} deg   tipping line {ln.distance_m * 100:.1f} cm "
              f"from the c.g.{extra}")
    if t.anti_tip_deg is not None:
        print(f"  over the anti-tip devices {t.anti_tip_deg:6.1f} deg")
    print(f"  smallest: {t.smallest_deg:.1f} deg ({_WORDS[t.smallest_direction]})")
    if a.cross_slope or a.grade:
        print(_slope_line(s))
    print(f"  for scale: Loane & Kirby (1985) measured {LOANE_KIRBY_REAR_DEG} deg mean rear stability of an occupied "
          "conventional manual chair (brakes unlocked); no numeric minimum of EN 12183/12184 was found to cite")
    return 0


_LAYOUT_WORDS = {"forward": "forward", "backward": "backward", "left": "over the left side",
                 "right": "over the right side"}


def _layout(a: argparse.Namespace) -> int:
    """A chair in the ``[[wheel]]`` form or a layout preset: the tip angles over its outermost contacts."""
    from stability.layout import statics

    layout = cli.load_layout(a.chair, a.set)
    t = statics.tip_angles(layout)
    s = statics.slope_tip(layout, a.cross_slope, a.grade)
    smallest = min(t, key=lambda k: t[k])
    data = {**t, "smallest_deg": t[smallest], "smallest_direction": smallest.removesuffix("_deg"),
            "slope": s.to_mapping(), "reference_rear_stability_deg": LOANE_KIRBY_REAR_DEG}
    if a.json or a.json_file:
        options = {"cross_slope_deg": a.cross_slope, "grade_deg": a.grade}
        cli.emit_json({"stability_version": __version__, "chair": layout.name, "options": options, **data}, a)
        if a.json:
            return 0
    print(f"{layout.name}: static stability angles (ISO 7176-1 directions; rigid body, brakes locked, every caster "
          f"in its least stable swivel orientation; {len(layout.wheels)} fixed wheels, {len(layout.casters)} casters; "
          "suspension deflection neglected)")
    for k, v in t.items():
        print(f"  {_LAYOUT_WORDS[k.removesuffix('_deg')]:<24} {v:6.1f} deg")
    print(f"  smallest: {t[smallest]:.1f} deg ({_LAYOUT_WORDS[smallest.removesuffix('_deg')]})")
    if a.cross_slope or a.grade:
        print(_slope_line(s))
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    return cli.run(build_parser(), argv, _body)


if __name__ == "__main__":
    raise SystemExit(main())
