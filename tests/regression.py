"""Regression values: numbers this code printed, kept only to notice when they change (issue 34).

None of them is an outside reference: each was measured with this code at the commit named, and each test that
uses one also asserts the independent statement it stands for (given here), which is what makes the number right.
A change of a value here needs a reason in the commit message, not only a re-measurement.
"""

from __future__ import annotations

#: name -> (value, unit, commit that produced it, the independent statement the test asserts beside it)
REGRESSION = {
    "revised_equal_instability_40N_m_s": (
        1.02, "m/s", "fae0587",
        "the revised chair's time to 1 rad/s at this speed brackets the E&J Premier's at 0.75 m/s (the definition)"),
    "revised_equal_instability_80N_m_s": (
        0.79, "m/s", "fae0587", "the same definition with an 80 N push on both chairs"),
    "revised_equal_friction_0Nm_m_s": (
        0.68, "m/s", "fae0587", "the same definition with frictionless pins on both chairs"),
    "ej_handrim_force_difference_6deg_N": (
        -141.26, "N", "0dcad62",
        "the frictionless statics closed form (holding moment / half track x wheel radius / rim radius), within "
        "the moment the two pins' Coulomb friction can carry"),
    "ej_critical_impulse_docs_Ns": (
        3.26, "N s", "8b64911", "inside the band where the outcome flips, verified by full-length runs"),
    "revised_critical_impulse_docs_Ns": (
        5.12, "N s", "8b64911", "inside the band where the outcome flips, verified by full-length runs"),
}


def value(name: str) -> float:
    """The regression value ``name`` (see :data:`REGRESSION`)."""
    return REGRESSION[name][0]
