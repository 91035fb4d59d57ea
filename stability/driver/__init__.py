"""The driver in the loop: how fast this user can drive this chair.

``model`` (the driver's effective delay and strength, literature defaults) -> ``linear`` (the human-limited
speed: the divergence rule ``lambda(U) tau = 1`` and the delayed PD loop on the full linear chair) -> ``text``
(the sentence the commands print).  Linear and frictionless; docs/driver.md says what that leaves out.
``tracking`` (the critical tracking task that measures a user's delay, and its escape factor from the delayed
loop) -> ``protocol`` (its trials, their validity, the result and the chair file's ``[user]`` table).
"""

from __future__ import annotations

from stability.driver.linear import HumanLimit, OperatorFit, human_limit, operator_fit
from stability.driver.model import REACTION_TIME_S, Driver, yaw_moment_limit

__all__ = ["Driver", "REACTION_TIME_S", "yaw_moment_limit", "HumanLimit", "human_limit", "OperatorFit",
           "operator_fit"]
