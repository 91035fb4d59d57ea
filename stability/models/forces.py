"""Contact forces of the chair: the door to :mod:`stability._generated.forces`.

Derived in ``derivations/forces.py`` and generated once: the caster contact
points (eq 6-24), the normal loads with quasi-static load transfer on a plane
(eq 6-25; level ground is ``gn = g``), the resultant and yaw moment of the tire
forces (eqs 6-2, 6-3), the signed slip angle and Coulomb pin friction (the
kinetic moment, the stick condition, the break-away moment, the fixed-step
rest rule).  The simulator's kernels compile these functions as they are;
:mod:`stability.models.statics` and :mod:`stability.models.full_width` wrap
them for the analyses.
"""

from __future__ import annotations

from stability._generated import forces as _fo

__all__ = ["generated", "slip_angle", "kinetic_pin_moment", "pin_holds", "break_away_moment", "rest_rate"]

#: The generated module itself (what the kernels compile).
generated = _fo

slip_angle = _fo.slip_angle
kinetic_pin_moment = _fo.kinetic_pin_moment
pin_holds = _fo.pin_holds
break_away_moment = _fo.break_away_moment
rest_rate = _fo.rest_rate
