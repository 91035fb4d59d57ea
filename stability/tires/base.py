"""Shared pieces of the tire classes: what data a tire has, and the camber force of eq (4-2)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from numpy.typing import ArrayLike

from stability.tires import law
from stability.tires.ranges import Policy

__all__ = ["TireCapabilities"]


@dataclass(frozen=True)
class TireCapabilities:
    """Which data a tire has (:attr:`Tire.capabilities`).

    Attributes
    ----------
    name : str
        Tire name.
    camber : bool
        A camber coefficient ``f_c`` (eq 4-2) is known.
    rolling : bool
        Rolling-resistance data (Appendix B cubic or ``f_r``) are known.
    """

    name: str
    camber: bool
    rolling: bool


class _CamberForce:
    """Eq (4-2), shared by :class:`Tire` and :class:`LinearTire` (which supply
    ``lateral_force`` and ``camber_coefficient``)."""

    if TYPE_CHECKING:
        @property
        def camber_coefficient(self) -> float: ...

        def lateral_force(self, slip_deg: ArrayLike, fz: ArrayLike, *, policy: Policy = "clamp",
                          warn: bool = True) -> Any: ...

    def camber_force(
        self,
        camber_deg: ArrayLike,
        fz: ArrayLike,
        camber_coefficient: float | None = None,
        *,
        policy: Policy = "clamp",
        warn: bool = True,
    ) -> Any:
        """Camber force (N), eq (4-2): ``f_c * F_y(alpha = gamma, fz)``.

        ``F_y`` is the cornering force of :meth:`lateral_force` at a slip
        angle equal to the camber angle (``f_c * C * gamma`` for a
        :class:`LinearTire`). The force has the sign of
        ``camber_deg`` (it acts toward the side to which the wheel leans);
        the caller maps it onto the vehicle axes. Differences from WCHAIR,
        which uses ``POLYFT(TIRY, INT(CAMANG), FZ)`` unscaled: here the
        camber angle is interpolated and ``lateral_scale`` applies.

        Parameters
        ----------
        camber_deg : float or array_like
            Camber angle(s), deg.
        fz : float or array_like
            Normal force(s), N.
        camber_coefficient : float, optional
            ``f_c``; defaults to :attr:`camber_coefficient`.
        policy, warn
            As for :meth:`lateral_force`.

        Returns
        -------
        float or ndarray
            N.
        """
        fc = self.camber_coefficient if camber_coefficient is None else float(camber_coefficient)
        return law.camber_force(fc, self.lateral_force(camber_deg, fz, policy=policy, warn=warn))
