"""The driver: a human who corrects the heading after an effective delay, with the force a hand (or a motor) has.

A rear-caster chair's divergence is one real mode whose rate ``lambda`` grows with speed.  A human who corrects
with an effective delay ``tau`` can hold a first-order divergence only while ``lambda tau < 1`` (delayed
proportional control: Stepan & Kollar 2000; the critical tracking task of Jex, McDonnell & Phatak 1966, which
ISO/TS 14198:2019 standardises, measures exactly that limit, ``lambda_c ~ 1 / tau_e``).  This module holds the
driver's parameters; :mod:`.linear` computes the speed at which this driver loses this chair.

References
----------
- Stepan G, Kollar L (2000) Balancing with reflex delay. Mathematical and Computer Modelling 31(4-5):199-205.
- Jex HR, McDonnell JD, Phatak AV (1966) A "critical" tracking task for manual control research. IEEE
  Transactions on Human Factors in Electronics HFE-7(4):138-145.
- McRuer DT, Krendel ES (1974) Mathematical models of human pilot behavior. AGARDograph AG-188.
- ISO/TS 14198:2019 Road vehicles - Ergonomic aspects of transport information and control systems -
  Calibration tasks for methods which assess driver demand due to the use of in-vehicle systems.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.chair.power import drive_kind
from stability.settings import defaults as D

__all__ = ["Driver", "REACTION_TIME_S", "REACTION_TIME_RANGE_S", "HAND_FORCE_N", "HAND_FORCE_RANGE_N", "TRACKING_KEYS",
           "yaw_moment_limit"]

#: Default effective delay of the driver's heading corrections, s: a design value inside the range the
#: literature gives for compensatory tracking (McRuer & Krendel 1974: effective delays of roughly 0.1-0.4 s
#: depending on the task; expert stick balancers about 0.23 s, Milton et al. 2016, J R Soc Interface
#: 13:20160212).  Users with slower reactions set their own (``--reaction-time``, the chair file's ``[user]``).
REACTION_TIME_S = 0.3
#: Valid effective delays, s: from a fast reflex to a very slow correction.
REACTION_TIME_RANGE_S = (0.05, 2.0)
#: Largest hand-rim force of one hand the driver uses to correct, N: the peak hand-rim force of level
#: propulsion at low intensity, 63 +/- 21 N (J NeuroEng Rehabil 2022, doi:10.1186/s12984-022-01007-5).
HAND_FORCE_N = 63.0
#: Valid hand forces, N.
HAND_FORCE_RANGE_N = (1.0, 1000.0)
#: Keys of a ``[user]`` table that record the critical tracking task (:mod:`stability.driver.tracking`):
#: the reaction time's spread (s) and the scored trials' ``lambda_c`` (1/s) and validity.
TRACKING_KEYS = ("reaction_time_sd_s", "tracking_lambda_c_1_s", "tracking_valid")


@dataclass(frozen=True)
class Driver:
    """A driver's heading correction: effective delay and strength.

    Parameters
    ----------
    reaction_time_s : float
        Effective delay ``tau`` of the heading corrections, s (:data:`REACTION_TIME_RANGE_S`).
    hand_force_N : float
        Largest hand-rim force of one hand, N (manual chairs; :data:`HAND_FORCE_RANGE_N`).
    source : str
        Where ``reaction_time_s`` comes from (``"default"``, ``"--reaction-time"``, ``"chair file [user]"``,
        ``"tracking task"``).
    """

    reaction_time_s: float = REACTION_TIME_S
    hand_force_N: float = HAND_FORCE_N
    source: str = "default"

    def __post_init__(self) -> None:
        for name, value, (lo, hi), unit in (("reaction_time_s", self.reaction_time_s, REACTION_TIME_RANGE_S, "s"),
                                            ("hand_force_N", self.hand_force_N, HAND_FORCE_RANGE_N, "N")):
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise TypeError(f"{name}={value!r} is invalid; expected a number ({unit})")
            if not (math.isfinite(value) and lo <= value <= hi):
                raise ValueError(f"{name}={value!r} is invalid; valid range: {lo:g} to {hi:g} {unit}")
            object.__setattr__(self, name, float(value))


    @classmethod
    def from_mapping(cls, data: dict, source: str = "chair file [user]") -> Driver:
        """A driver from a chair file's ``[user]`` table (:func:`stability.chair.user_table`).

        Parameters
        ----------
        data : dict
            ``reaction_time_s`` (required), ``hand_force_N`` (optional), ``source`` (optional text: where the
            reaction time was measured); the tracking task's record (:data:`TRACKING_KEYS`) is allowed and not
            used here.
        source : str
            Default source text.

        Returns
        -------
        Driver

        Raises
        ------
        ValueError
            On an unknown key, a missing ``reaction_time_s`` or a value out of range.
        """
        known = {"reaction_time_s", "hand_force_N", "source", *TRACKING_KEYS}
        unknown = sorted(set(data) - known)
        if unknown:
            raise ValueError(f"[user] has unknown key(s) {unknown}; valid: {sorted(known)}")
        if "reaction_time_s" not in data:
            raise ValueError("[user] needs reaction_time_s (s; valid range "
                             f"{REACTION_TIME_RANGE_S[0]:g} to {REACTION_TIME_RANGE_S[1]:g})")
        src = data.get("source", source)
        return cls(data["reaction_time_s"], data.get("hand_force_N", HAND_FORCE_N), str(src))

    def to_mapping(self) -> dict:
        """The ``[user]`` table / JSON form."""
        return {"reaction_time_s": self.reaction_time_s, "hand_force_N": self.hand_force_N, "source": self.source}


@takes_chair
def yaw_moment_limit(chair: Chair, driver: Driver) -> float:
    """The largest corrective yaw moment the driver can apply, N m.

    A manual chair: one hand pushes and the other pulls with ``hand_force_N`` at the rims; each wheel's contact
    force is that force times hand-rim radius over wheel radius, and the two act at ``d1`` and ``d2`` from the
    c.g. (eq 6-3 of Collins 1987: ``Mz = F (d1 + d2)``).  A power chair: the motors' torque limit at each drive
    wheel, ``Mz = T (d1 + d2) / r`` (docs/power-chair.md).

    Parameters
    ----------
    chair : Chair
    driver : Driver

    Returns
    -------
    float
        N m.
    """
    arm = chair.d1 + chair.d2
    if drive_kind(chair) == "motor":
        return D.TORQUE_LIMIT * arm / D.DRIVE_WHEEL_RADIUS
    return driver.hand_force_N * D.HANDRIM_RADIUS / D.HANDRIM_WHEEL_RADIUS * arm
