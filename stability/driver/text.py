"""The human-limited speed in words: one sentence that every command and the report print."""

from __future__ import annotations

from stability.driver.linear import HumanLimit
from stability.driver.model import Driver

__all__ = ["human_text", "human_sentence", "held_where", "limit_values", "layout_human_text"]


def human_sentence(h: HumanLimit, driver: Driver) -> str:
    """``"A driver who corrects the heading 0.3 s late can hold this chair up to 1.79 m/s (6.5 km/h)"``.

    Parameters
    ----------
    h : HumanLimit
    driver : Driver

    Returns
    -------
    str
        Without a final full stop; a bound reads "beyond 6 m/s (the fastest speed checked)".
    """
    where = held_where(h.speed_m_s, h.side)
    return f"A driver who corrects the heading {driver.reaction_time_s:g} s late can hold this chair straight {where}"


def held_where(u: float, side: str) -> str:
    """Where a chair can be held: ``"up to 1.79 m/s (6.4 km/h)"``, or the bound's words.

    Parameters
    ----------
    u : float
        The limit or the searched range's end, m/s.
    side : {"=", ">", "<"}
        Found, above the range (held everywhere checked), below it.

    Returns
    -------
    str
    """
    if side == ">":
        return f"at every speed checked, up to {u:g} m/s ({3.6 * u:.1f} km/h)"
    if side == "<":
        return f"not even at {u:g} m/s, the slowest speed checked"
    return f"up to {u:.3g} m/s ({3.6 * u:.1f} km/h)"


def human_text(h: HumanLimit, driver: Driver, lane_line: str | None = None) -> str:
    """The human-limited speed as the commands print it: the sentence, the two limits and what they leave out.

    Parameters
    ----------
    h : HumanLimit
    driver : Driver
    lane_line : str, optional
        The nonlinear lane limit (:func:`stability.study.lane.lane_text`), printed after the linear ones.

    Returns
    -------
    str
    """
    return (f"Driver (reaction time {driver.reaction_time_s:g} s, from {driver.source}):\n"
            f"  {human_sentence(h, driver)} ({h.model} model, free frictionless casters).\n"
            + _limits(h, "  ")
            + ("" if lane_line is None else f"  {lane_line}\n")
            + "  The linear limits leave out pin friction, which can hold the casters after a small push or trap the "
            "driver in a slow stick-slip weave (the nonlinear line has it); no model here has fatigue, preview or "
            "learning (docs/driver.md).")



def _bound(u: float, side: str) -> str:
    """A limit as a value: ``"1.04 m/s"``, or a bound ``"> 6 m/s"`` (:mod:`stability.study.censored`)."""
    return ("" if side == "=" else f"{side} ") + f"{u:.3g} m/s"


def limit_values(h: HumanLimit) -> str:
    """Both limits' values, for a sentence that names the lower (``h.limited_by``).

    Parameters
    ----------
    h : HumanLimit

    Returns
    -------
    str
        ``"divergence rule 1.04 m/s, delayed loop 1.02 m/s"`` (a bound as a bound: ``"> 6 m/s"``); the advisor
        checks its changes on the divergence rule alone, so both are given.
    """
    return (f"divergence rule {_bound(h.rule_speed_m_s, h.rule_side)}, "
            f"delayed loop {_bound(h.loop_speed_m_s, h.loop_side)}")


def _limits(h: HumanLimit, indent: str) -> str:
    """The divergence rule's and the delayed loop's lines."""
    rule, loop = _bound(h.rule_speed_m_s, h.rule_side), _bound(h.loop_speed_m_s, h.loop_side)
    return (f"{indent}divergence rule (the chair's divergence rate reaches 1/tau): {rule}\n"
            f"{indent}delayed loop (the driver's best delayed heading correction on the full linear chair): {loop}\n")


def layout_human_text(forward: HumanLimit, reverse: HumanLimit, driver: Driver) -> str:
    """A wheel layout's human-limited speeds forwards and backwards, as :func:`human_text` prints the short form's.

    Parameters
    ----------
    forward, reverse : HumanLimit
        :func:`stability.driver.layout.layout_human_limit` forward and in reverse (speeds are sizes).
    driver : Driver

    Returns
    -------
    str
    """
    out = [f"Driver (reaction time {driver.reaction_time_s:g} s, from {driver.source}; the layout's linear model, "
           "free frictionless casters trailing the direction of travel):"]
    for way, h in (("forwards", forward), ("backwards", reverse)):
        out.append(f"  {way}: {human_sentence(h, driver)}.")
        out.append(_limits(h, "    ").rstrip("\n"))
    out.append("  The linear limits leave out pin friction, which can hold the casters after a small push or trap the "
               "driver in a slow stick-slip weave; the nonlinear lane limit and the limit with the assist on are the "
               "short form's (docs/driver.md).")
    return "\n".join(out)
