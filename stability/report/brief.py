"""The quick report's data (``python -m stability.report --quick``): page 1's decision, the clinician sheet and
the references, nothing else computed."""

from __future__ import annotations

from typing import Any

from stability.advise import advise
from stability.advise.measures import measure_chairs
from stability.chair import Chair, preset
from stability.report.clinician_sheet import clinician_sheet
from stability.report.compute import ReportData
from stability.report.settings import Settings
from stability.settings.reference import REFERENCE_CHAIR

__all__ = ["compute_brief"]


def compute_brief(c: Chair, model: str = "exact", *, progress: bool = True, driver: Any = None,
                  intended_speed: float | None = None) -> ReportData:
    """The quick report's data: the advisor's decision (as in the full report), the thesis's reference chair
    measured the same way, and the clinician sheet at the advisor's use speeds; nothing else is computed, so
    every measure the quick PDF prints has one value.

    Parameters
    ----------
    c : Chair
    model : {"exact", "thesis"}
    progress : bool
    driver : stability.driver.Driver, optional
        The user's reaction time: the advisor weighs the speed this user can hold (as in the full report and
        ``python -m stability.advise``), and page 1 and the clinician sheet say up to which speed this user holds
        the chair.
    intended_speed : float, optional
        With ``driver``: the speed the user wants to drive at, m/s (the advisor's ``intended_speed``).

    Returns
    -------
    ReportData
        With ``brief`` set; the fields the brief pages do not use are empty.
    """
    s = Settings.for_mode(False)
    ref_chair = preset(REFERENCE_CHAIR)
    advice = advise(c, progress=progress, driver=driver, intended_speed=intended_speed)
    tau = None if driver is None else driver.reaction_time_s        # the reference chair's user limit too
    ref_m = None if c == ref_chair else measure_chairs([ref_chair], speeds=advice.speeds_m_s,
                                                      cross_slope_deg=advice.cross_slope_deg,
                                                      reaction_time=tau)[0]
    sheet = clinician_sheet(c, tuple(advice.speeds_m_s), model, driver)
    return ReportData(c, model, s, None, None, {}, [], [], None, None, None, [], sheet.responses, None, None, None,
                      None, [], validity={"responses": sheet.validity}, slope=sheet.slope, tipping=sheet.tipping,
                      advice=advice, reference_measures=ref_m, reference_trail=ref_chair.trail, brief=True,
                      sheet=sheet, driver=driver, human=sheet.human)
