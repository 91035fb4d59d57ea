"""``python -m stability.advise``: verdict, design levers and the recommended change for a chair."""

from __future__ import annotations

import argparse
from collections.abc import Sequence

from stability import cli
from stability.advise.advisor import advise
from stability.advise.text import advice_mapping, advice_text
from stability.advise.uncertain import tip_interval
from stability.settings import defaults as D
from stability.settings.bounds import ADVISE_SPEED, ADVISE_SPEED_COUNT


def build_parser() -> argparse.ArgumentParser:
    p = cli.OneLineErrorParser(prog="python -m stability.advise", description=__doc__)
    cli.add_chair_options(p)
    p.add_argument("--speeds", default=D.ADVISE_SPEEDS, metavar="SPEEDS",
                   help=f"use speeds, m/s: START:STOP:STEP, a list, or a range A:B (its ends and middle); "
                        f"default {D.ADVISE_SPEEDS}")
    p.add_argument("--uncertainty", metavar="FILE",
                   help="uncertainty file (measure's): adds the interval of the chair's static stability angle; for a "
                        "wheel layout or reverse speeds its tables name the layout's axes (m, i_z, h, caster_K_FIELD, "
                        "wheel_J_FIELD, trail_ROW, drive_x; docs/layouts.md)")
    p.add_argument("--min-tip-deg", type=float, default=None, metavar="D",
                   help="smallest acceptable static stability angle, deg (default: the chair's own; no citable "
                        "standard minimum was found, docs/tipping.md)")
    p.add_argument("--cross-slope", type=float, default=D.ADVISE_CROSS_SLOPE_DEG, metavar="DEG",
                   help=f"cross slope of the hand-rim force constraint, deg (default {D.ADVISE_CROSS_SLOPE_DEG:g})")
    cli.add_driver_options(p)
    cli.add_intended_speed_option(p)
    p.add_argument("--no-progress", action="store_true", help="no progress bars on stderr")
    cli.add_json_options(p)
    return p


#: The advisor's speeds in size, m/s (the --speeds check and its messages).
SPEED_RANGE_M_S = (ADVISE_SPEED.lo, ADVISE_SPEED.hi)
_RANGE_TEXT = f"{SPEED_RANGE_M_S[0]:g} to {SPEED_RANGE_M_S[1]:g} m/s"


def _speeds(text: str) -> tuple[float, ...]:
    """Use speeds: all forward, or all backwards (a leading ``-`` on a range ``-A:B``, a range of two negative ends
    ``-B:-A`` or every value negative)."""
    if text.startswith("-") and text.count(":") == 1 and not text.split(":")[1].startswith("-"):
        return tuple(-u for u in _speeds(text[1:]))             # -A:B: the range A:B backwards
    if text.count(":") == 1 and all(x.strip().startswith("-") for x in text.split(":")):
        a, b = (x.strip()[1:] for x in text.split(":"))
        try:
            return tuple(-u for u in _speeds(f"{b}:{a}"))      # -B:-A (signed, B >= A): the range A:B backwards
        except ValueError:
            raise ValueError(f"--speeds {text!r} is invalid; valid: -B:-A with 0 < A <= B (m/s), in reverse; "
                             f"speeds {_RANGE_TEXT} in size") from None
    if "," in text and all(x.strip().startswith("-") for x in text.split(",")):
        return tuple(-u for u in _speeds(",".join(x.strip()[1:] for x in text.split(","))))
    if text.startswith("-") and ":" not in text and "," not in text:
        return tuple(-u for u in _speeds(text[1:]))
    speeds = tuple(float(u) for u in cli.parse_speeds(text, max_count=ADVISE_SPEED_COUNT))    # A:B: its ends and middle
    if max(speeds) > SPEED_RANGE_M_S[1] or min(speeds) < SPEED_RANGE_M_S[0]:
        raise ValueError(f"--speeds {text!r} is invalid; valid range: {_RANGE_TEXT} (all negative: in reverse, "
                         "e.g. -0.5,-0.75 or -0.5:1)")
    return speeds


def _driver(a: argparse.Namespace):
    """The driver of ``--reaction-time`` (or the chair file's ``[user]``), with ``--intended-speed`` checked."""
    driver = cli.driver_from_args(a)
    cli.intended_speed_from_args(a, driver)
    return driver


def _body(a: argparse.Namespace) -> int:
    cli.check_outputs({"--json-file": a.json_file}, {"--chair": a.chair, "--uncertainty": a.uncertainty})
    speeds = _speeds(a.speeds)
    # --min-tip-deg, --cross-slope and --intended-speed were parsed within their ranges (OPTION_BOUNDS)
    from stability.layout.io import is_layout_spec

    if is_layout_spec(a.chair) or min(speeds) < 0:
        return _body_layout(a, speeds)
    chair = cli.load_chair(a.chair, a.set)
    driver = _driver(a)
    unc = None
    if a.uncertainty:
        from stability.uncertainty import load_uncertainty
        unc = load_uncertainty(a.uncertainty)
    tips = None if unc is None else tip_interval(chair, unc)    # before the advice: a bad file fails at once
    advice = advise(chair, speeds=speeds, min_tip_deg=a.min_tip_deg, cross_slope_deg=a.cross_slope,
                    progress=not a.no_progress, driver=driver, intended_speed=a.intended_speed)
    data = advice_mapping(advice)
    if tips is not None:
        _add_tip_interval(data, tips, a.uncertainty)
    if a.json or a.json_file:
        options = {"speeds_m_s": list(speeds), "uncertainty": a.uncertainty, "min_tip_deg": a.min_tip_deg,
                   "cross_slope_deg": a.cross_slope,
                   "reaction_time_s": None if driver is None else driver.reaction_time_s,
                   "intended_speed_m_s": advice.intended_speed_m_s}
        cli.emit_json({**cli.json_header(chair, "exact", options), **data}, a)
        if a.json:
            return 0
    print(data["text"])
    if unc is not None:
        print(_tip_interval_line(data, a.uncertainty))
    return 0


def _body_layout(a: argparse.Namespace, speeds: tuple[float, ...]) -> int:
    """A wheel layout, or any chair at reverse speeds (as its layout): the layout levers and measures."""
    import dataclasses

    from stability import __version__

    layout = cli.load_layout(a.chair, a.set)
    unc = None
    if a.uncertainty is not None:      # tables naming the layout's axes (a short-form chair's expanded layout's)
        from stability.advise.layout_axes import load_layout_uncertainty
        unc = load_layout_uncertainty(a.uncertainty, layout)
    driver = _driver(a)
    tips = None if unc is None else tip_interval(layout, unc)   # before the advice: a bad file fails at once
    advice = advise(layout, speeds=speeds, min_tip_deg=a.min_tip_deg, cross_slope_deg=a.cross_slope,
                    progress=not a.no_progress, driver=driver, intended_speed=a.intended_speed)
    data = advice_mapping(advice)
    if tips is not None:
        _add_tip_interval(data, tips, a.uncertainty)
    if a.json or a.json_file:
        options = {"speeds_m_s": list(speeds), "uncertainty": a.uncertainty, "min_tip_deg": a.min_tip_deg,
                   "cross_slope_deg": a.cross_slope,
                   "reaction_time_s": None if driver is None else driver.reaction_time_s,
                   "intended_speed_m_s": advice.intended_speed_m_s,
                   "direction": "reverse" if speeds[0] < 0 else "forward"}
        cli.emit_json({"stability_version": __version__, "chair": layout.name,
                       "chair_parameters": dataclasses.asdict(layout), "model": "exact", "options": options,
                       **data}, a)
        if a.json:
            return 0
    print(data["text"])
    if unc is not None:
        print(_tip_interval_line(data, a.uncertainty))
    return 0


def _add_tip_interval(data: dict, interval: tuple[float, float], path: str) -> None:
    """The static stability's interval over the uncertainty file's draws, into the advice's JSON verdict."""
    from stability.advise.uncertain import SAMPLES

    lo, hi = interval
    data["verdict"]["static_stability_deg"]["interval"] = [lo, hi]
    data["verdict"]["static_stability_interval_source"] = f"{path} (2.5-97.5 % of {SAMPLES} draws)"


def _tip_interval_line(data: dict, path: str) -> str:
    from stability.advise.uncertain import SAMPLES

    lo, hi = data["verdict"]["static_stability_deg"]["interval"]
    return f"Static stability over {path}: {lo:.1f}-{hi:.1f} deg (2.5-97.5 % of {SAMPLES} draws)."


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    return cli.run(build_parser(), argv, _body)


if __name__ == "__main__":
    raise SystemExit(main())


__all__ = ["main", "advice_text"]
