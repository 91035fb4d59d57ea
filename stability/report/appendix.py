"""The report's appendix texts: the method (push convention, model variants, verdict thresholds), a glossary
and the references.  Stated here once; the other pages refer to them."""

from __future__ import annotations

from stability.report.compute import ReportData
from stability.report.quick import coarsened_text
from stability.report.summary import model_gap
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH
from stability.study.facts import PROPORTIONAL_RANGE

__all__ = ["method_text", "GLOSSARY", "REFERENCES", "glossary_text"]


def method_text(d: ReportData) -> list[str]:
    """Paragraphs of the method appendix; every number from ``d`` or from :mod:`stability.settings.reference`.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    list of str
    """
    dt = d.settings.dt if d.scheme == "wchair" else None
    crit = d.thesis.criterion
    a, b = PROPORTIONAL_RANGE
    quick = coarsened_text(d.settings) + " " if d.settings.quick else ""
    return [
        quick + "Models. Linear: straight-line motion, tire forces linear in slip with the cornering stiffness at "
        "the static load (the thesis's Table 4-1 method), free casters without pin friction (Coulomb friction has "
        "no linearisation). Nonlinear: the thesis's simulator WCHAIR, re-implemented and compiled, with the "
        "treadmill tire data and Coulomb pin friction. " + model_gap(d),
        "The push (used throughout). The thesis disturbs the chair with a lateral force at the centre of gravity: "
        + THESIS_PUSH.describe(dt) + ". The force acts while t <= "
        f"{THESIS_PUSH.duration:g} s, so on WCHAIR's fixed step it is applied on one step more than the duration "
        "divided by the step, which is why the impulse is slightly above force x duration.",
        f"Instability measures. Reference case: the {REFERENCE_CHAIR} at {REFERENCE_SPEED:g} m/s after the push; "
        f"{crit.describe()}. Equal-instability speed: the speed at which a chair takes exactly as long as the "
        "reference case (a bracketing search on speed: a first round of candidate speeds, then a regula-falsi "
        "pair per round, one batch of simulations per round). Critical impulse: the smallest "
        "push (same 0.1 s duration) that brings |yaw rate| to the level within the same time; unlike the "
        "equal-instability speed it does not depend on the size of the thesis's push.",
        "Verdict thresholds for the thesis's conclusions (chapter 9). The thesis compares response curves by eye; "
        "our measures are speeds, which move less than the times the thesis read. 'Agree' needs an effect the "
        "thesis would call significant, chosen well above the bisection's resolution and the few per cent that the "
        "push's size alone moves the speed (the equal-instability page shows that range): at least +10 % in speed "
        "for a geometric change (conclusions 2, 3), at least +5 % for the 2 cm trail step (conclusion 4), +30..+80 % "
        "for the "
        "combined revision (the thesis reports +46 %, conclusion 5), a speed exponent "
        f"{a:g}-{b:g} for 'roughly proportional' (conclusion 6), less than 2 s to the level at 2 m/s (conclusion "
        "7), under 5 % for 'no significant effect' (conclusion 8), and for conclusion 9 the softest tire the most "
        "stable at the thesis's own 0.62 m/s, at least 10 % ahead of the next tire (the thesis's 'significantly') "
        "with a spread of at most 60 % over all tires. 'Partly' means the direction agrees but not the size. The "
        "verdicts are computed on the thesis's chairs only, so every report prints the same ones; a chair's own "
        "test is a separate column, 'not applicable' for a front-caster chair and 'not testable (bound)' when its "
        "speeds are bounds.",
        "Validity. Curves on the time-history pages end where a run leaves the model's range: slip above 8 deg, "
        "a load outside the tire data, heading past 90 deg or the speed reversing. Caster shimmy uses two "
        "estimated inputs (the caster tire's relaxation length and the frame's lateral stiffness at the pin), "
        "which the thesis does not give.",
    ]


#: The thesis's title exactly as its title page prints it (the seed's first line).
THESIS_TITLE = ("AN ANALYSIS OF PARAMETERS RELATED TO THE DIRECTIONAL INSTABILITY OF REAR CASTER WHEELCHAIRS")
#: The 2022 hand-rim study's DOI (the source of :data:`stability.report.clinician.TYPICAL_PUSH_N`).
HANDRIM_STUDY_DOI = "10.1186/s12984-022-01007-5"

#: Terms a reader meets in the report, in plain words.
GLOSSARY: tuple[tuple[str, str], ...] = (
    ("growth rate (1/s)", "how fast a heading error grows when the chair runs straight; positive: it grows "
     "(unstable), negative: it dies out."),
    ("doubling time (s)", "the time for a heading error to double, ln 2 / growth rate: the time a user has to "
     "notice and correct it."),
    ("equal-instability speed (m/s)", "the speed at which the chair is as unstable as the thesis's reference case "
     f"(the {REFERENCE_CHAIR} at {REFERENCE_SPEED:g} m/s after the thesis's push); higher is better."),
    ("critical impulse (N s)", "the smallest sideways push (force x time) that spins the chair up to 1 rad/s "
     "within 10 s; higher is better."),
    ("trail (cm)", "how far behind its swivel pin a caster wheel touches the ground."),
    ("pin friction (N m)", "the friction torque that resists swivelling a caster about its pin; it holds the "
     "casters straight against small side forces."),
    ("c.g. ratio", "where the centre of gravity lies between the main axle (0) and the caster pins (1)."),
    ("caster shimmy", "a fast side-to-side oscillation of a caster about its pin, worse with a short trail."),
    ("holding moment (N m)", "the yaw moment a user or a motor must supply to keep the chair straight on a cross "
     "slope."),
    ("static stability angle (deg)", "the slope at which the braked chair tips over (ISO 7176-1); Loane and "
     "Kirby's 28.6 deg benchmark was measured with brakes unlocked, so it is a scale, not a like-for-like limit."),
    ("shimmy margin (cm)", "how far the chair's trail lies from the nearest trail at which the casters shimmy at "
     "the use speeds; positive: on the safe side."),
    ("relaxation length (m)", "the distance a rolling tire travels before its side force builds up after a "
     "change of slip (an estimated input of the shimmy model)."),
    ("pin stiffness", "the lateral stiffness of the frame at the caster pin (the other estimated shimmy input)."),
    ("elasticity", "the per cent change of a measure per per cent change of a parameter; +0.5: raising the "
     "parameter 10 % raises the measure 5 %. Two measures can have opposite-signed elasticities for one "
     "parameter: the linear growth rate ignores pin friction, the critical impulse includes it."),
    ("censored value / bound", "a search that ended at its bracket's edge: '> 3 m/s' means above 3 m/s, by how "
     "much unknown; bounds cannot rank parameters."),
    ("wchair scheme", "the thesis's simulator's fixed-step integration, re-implemented (step 1 ms)."),
    ("stick-slip pin friction", "the report's pin-friction law: a caster stays put until the side moment exceeds "
     "the friction torque, then slides against it; the simulate command's stick-slip friction law."),
    ("x_m", "the caster pins' distance ahead of (or behind) the centre of gravity along the chair, m."),
    ("M_f/l", "pin friction divided by trail: the side force at the caster's contact that the friction holds, N."),
    ("k_us", "the understeer coefficient of the locked-caster (zero-width) model, rad; negative: oversteer."),
    ("yaw rate (rad/s)", "how fast the heading changes; plotted counter-clockwise positive (seen from above) "
     "in every report."),
)

#: Sources the report uses.
REFERENCES: tuple[str, ...] = (
    f"Collins, T. J. (1987). {THESIS_TITLE}. M.S. thesis, University of Virginia, Charlottesville. (Tire data, "
    "models, WCHAIR, chapters 8-9.)",
    "ISO 7176-1: Wheelchairs - Part 1: Determination of static stability. (The static stability angles.)",
    "Loane, T. D. and Kirby, R. L. (1985). Static rear stability of conventional and lightweight variable-axle-"
    "position wheelchairs. Arch Phys Med Rehabil 66(3):174-176. (28.6 deg mean rear stability, brakes unlocked.)",
    "A novel push-pull central-lever mechanism reduces peak forces and energy-cost compared to hand-rim "
    "wheelchair propulsion during a controlled lab-based experiment (2022). J NeuroEng Rehabil, "
    f"doi:{HANDRIM_STUDY_DOI}. (Peak hand-rim force 63 +/- 21 N, the clinician paragraph's typical push.)",
    "Kauzlarich, J. J., Bruning, T. and Thacker, J. G.: caster shimmy and the dual-tread caster (cited by Collins "
    "1987 as ref. 8.2).",
    "Pacejka, H. B. (2006). Tyre and Vehicle Dynamics, 2nd ed. Butterworth-Heinemann. (Tire relaxation length.)",
    "Richter, W. M., Rodriguez, R., Woods, K. R. and Axelson, P. W. (2007). Consequences of a cross slope on "
    "wheelchair handrim biomechanics. Arch Phys Med Rehabil 88:76-80. (Cross-slope holding moments.)",
    "Okabe, M. and Ito, K. (2008). Color Universal Design. (The colour-blind-safe palette.)",
)


def glossary_text() -> list[str]:
    """The glossary and the references as paragraphs.

    Returns
    -------
    list of str
    """
    return (["Glossary"] + [f"- {term}: {meaning}" for term, meaning in GLOSSARY]
            + ["", "References"] + [f"- {r}" for r in REFERENCES])
