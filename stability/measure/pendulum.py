"""Moments of inertia from pendulum periods: torsional, bifilar/trifilar and compound pendulums.

All small-amplitude formulas; SI units (kg, m, s, N m/rad, kg m^2).  See
docs/measure.md for the set-ups and their error sources.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import ellipk

from stability.chair.units import STANDARD_GRAVITY

__all__ = [
    "torsional_pendulum_inertia",
    "torsional_rigidity",
    "solid_cylinder_inertia",
    "multifilar_pendulum_inertia",
    "bifilar_pendulum_inertia",
    "trifilar_pendulum_inertia",
    "compound_pendulum_inertia",
    "small_amplitude_period",
]


def _positive(name: str, value, unit: str) -> None:
    v = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(v)) or np.any(v <= 0):
        raise ValueError(f"{name}={value!r} is invalid; valid range: > 0 {unit}".rstrip())


def torsional_pendulum_inertia(period, rigidity, fixture_inertia=0.0):
    """Inertia of a body hung on a torsional pendulum at its centre of gravity (eq D-1).

    Collins (1987) eq D-1, ``T = 2 pi sqrt(I / K_t)``, solved for ``I``:
    ``I = K_t T^2 / (4 pi^2) - I_fixture``.

    Parameters
    ----------
    period : float or array
        Period of the twisting oscillation T (s).
    rigidity : float or array
        Torsional rigidity of the rod K_t (N m/rad), e.g. from :func:`torsional_rigidity`.
    fixture_inertia : float, optional
        Inertia of the clamps and bar that hold the body (kg m^2), subtracted;
        measure it as ``torsional_pendulum_inertia(T_empty, K_t)``.

    Returns
    -------
    float or ndarray
        Inertia about the rod axis (kg m^2).
    """
    _positive("period", period, "s")
    _positive("rigidity", rigidity, "N m/rad")
    return np.asarray(rigidity) * np.asarray(period) ** 2 / (4 * math.pi**2) - fixture_inertia


def torsional_rigidity(period, calibration_inertia):
    """Torsional rigidity K_t of a pendulum rod from a calibration body (eq D-1).

    ``K_t = 4 pi^2 I_cal / T_cal^2`` (Collins 1987, Appendix D: a 50 lbf solid
    cylinder gave K_t = 0.66 ft lbf/rad).

    Parameters
    ----------
    period : float or array
        Period with the calibration body hung on the rod (s).
    calibration_inertia : float or array
        Its known inertia about the rod axis (kg m^2), e.g. :func:`solid_cylinder_inertia`.

    Returns
    -------
    float or ndarray
        K_t (N m/rad).
    """
    _positive("period", period, "s")
    _positive("calibration_inertia", calibration_inertia, "kg m^2")
    return 4 * math.pi**2 * np.asarray(calibration_inertia) / np.asarray(period) ** 2


def solid_cylinder_inertia(mass, radius):
    """Inertia of a uniform solid cylinder about its axis, ``m r^2 / 2`` (Appendix D calibration body).

    Parameters
    ----------
    mass : float or array
        Cylinder mass (kg, > 0).
    radius : float or array
        Cylinder radius (m, > 0).

    Returns
    -------
    float or ndarray
        Inertia about the cylinder axis (kg m^2).
    """
    _positive("mass", mass, "kg")
    _positive("radius", radius, "m")
    return 0.5 * np.asarray(mass) * np.asarray(radius) ** 2


def multifilar_pendulum_inertia(mass, radius, length, period, g: float = STANDARD_GRAVITY):
    """Inertia of a platform hung on n >= 2 equal vertical strings on a circle of radius R.

    ``I = m g R^2 T^2 / (4 pi^2 L)`` for small twist: each string tilts by
    ``R theta / L`` and the n string tensions ``m g / n`` give a restoring
    moment ``m g R^2 theta / L`` (Soule & Miller 1934, NACA Report 467; du Bois,
    Lieven & Adhikari 2009, Exp. Mech. 49:533).

    Parameters
    ----------
    mass : float or array
        Total suspended mass, body plus platform (kg).
    radius : float or array
        Distance of each string from the vertical axis through the c.g. (m).
    length : float or array
        String length L (m).
    period : float or array
        Period of the twisting oscillation (s).
    g : float
        Gravitational acceleration (m/s^2).

    Returns
    -------
    float or ndarray
        Inertia of everything on the strings about the vertical axis (kg m^2);
        subtract the empty platform's to get the body's.
    """
    for name, v, u in (("mass", mass, "kg"), ("radius", radius, "m"), ("length", length, "m"),
                       ("period", period, "s")):
        _positive(name, v, u)
    return (np.asarray(mass) * g * np.asarray(radius) ** 2 * np.asarray(period) ** 2
            / (4 * math.pi**2 * np.asarray(length)))


def bifilar_pendulum_inertia(mass, spacing, length, period, g: float = STANDARD_GRAVITY):
    """Bifilar pendulum: ``I = m g d^2 T^2 / (16 pi^2 L)`` with string spacing d.

    The two-string case of :func:`multifilar_pendulum_inertia` (R = d/2); the
    c.g. must lie midway between the strings.

    Parameters
    ----------
    mass : float or array
        Total suspended mass, body plus platform (kg, > 0).
    spacing : float or array
        Distance between the two strings d (m, > 0).
    length : float or array
        String length L (m, > 0).
    period : float or array
        Period of the twisting oscillation T (s, > 0).
    g : float
        Gravitational acceleration (m/s^2).

    Returns
    -------
    float or ndarray
        Inertia of everything on the strings about the vertical axis (kg m^2).
    """
    _positive("spacing", spacing, "m")
    return multifilar_pendulum_inertia(mass, np.asarray(spacing) / 2, length, period, g)


def trifilar_pendulum_inertia(mass, radius, length, period, g: float = STANDARD_GRAVITY):
    """Trifilar pendulum: ``I = m g R^2 T^2 / (4 pi^2 L)``, strings 120 deg apart on radius R.

    The three-string case of :func:`multifilar_pendulum_inertia`.

    Parameters
    ----------
    mass : float or array
        Total suspended mass, body plus platform (kg, > 0).
    radius : float or array
        Distance R of each string from the vertical axis through the c.g. (m, > 0).
    length : float or array
        String length L (m, > 0).
    period : float or array
        Period of the twisting oscillation T (s, > 0).
    g : float
        Gravitational acceleration (m/s^2).

    Returns
    -------
    float or ndarray
        Inertia of everything on the strings about the vertical axis (kg m^2).
    """
    return multifilar_pendulum_inertia(mass, radius, length, period, g)


def small_amplitude_period(period, amplitude):
    """Small-amplitude period of a pendulum timed at a finite swing amplitude.

    ``T_0 = T pi / (2 K(sin^2(theta_0/2)))`` with ``K`` the complete elliptic
    integral of the first kind (parameter m = k^2): the exact period of a
    gravity pendulum released at ``theta_0`` is ``T_0 2 K / pi``.

    Parameters
    ----------
    period : float or array
        Measured period (s).
    amplitude : float or array
        Release amplitude (rad), 0 <= amplitude < pi.

    Returns
    -------
    float or ndarray
        T_0, the period at vanishing amplitude (s); equal to ``period`` at amplitude 0.
    """
    a = np.asarray(amplitude, dtype=float)
    if np.any(a < 0) or np.any(a >= math.pi):
        raise ValueError(f"amplitude={amplitude!r} is invalid; valid range: 0 <= amplitude < pi rad")
    return np.asarray(period) * math.pi / (2 * ellipk(np.sin(a / 2) ** 2))


def compound_pendulum_inertia(mass, pivot_distance, period, amplitude=0.0, g: float = STANDARD_GRAVITY):
    """Inertia of a caster about its pin, swung as a compound pendulum about the pin.

    Clamp the pin axis horizontal and let the caster swing about it:
    ``T = 2 pi sqrt(I_pin / (m g l1))`` for small swings (physical pendulum,
    e.g. Meriam & Kraige, *Engineering Mechanics: Dynamics*), so
    ``I_pin = m g l1 T^2 / (4 pi^2)``.  The pin axis is the caster's yaw axis
    when mounted, so this is I_zp directly.

    Parameters
    ----------
    mass : float or array
        Caster assembly mass m_c (kg).
    pivot_distance : float or array
        Pin axis to caster c.g., l1 (m).
    period : float or array
        Swing period (s).
    amplitude : float or array, optional
        Release amplitude (rad); corrected with :func:`small_amplitude_period`.
    g : float
        Gravitational acceleration (m/s^2).

    Returns
    -------
    float or ndarray
        I_zp (kg m^2).  It is at least ``m l1^2``; a shorter period than
        ``2 pi sqrt(l1/g)`` is physically impossible and raises ValueError.
    """
    for name, v, u in (("mass", mass, "kg"), ("pivot_distance", pivot_distance, "m"), ("period", period, "s")):
        _positive(name, v, u)
    t0 = small_amplitude_period(period, amplitude)
    tmin = 2 * math.pi * np.sqrt(np.asarray(pivot_distance) / g)
    if np.any(t0 < tmin * (1 - 1e-12)):
        raise ValueError(f"period={period!r} is invalid; valid range: > 2 pi sqrt(l1/g) = "
                         f"{np.max(tmin):.4g} s (a point mass at l1 swings faster than any real caster)")
    return np.asarray(mass) * g * np.asarray(pivot_distance) * t0**2 / (4 * math.pi**2)
