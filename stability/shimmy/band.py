"""The shimmy-free trail band(s) of a chair's caster, and the chair's margin to the nearest boundary.

The caster as a towed wheel (:func:`stability.shimmy.chair.caster_wheel`: pin on the frame's lateral
spring, relaxation-length tire at its static load) is linearly stable where every eigenvalue has a
negative real part.  Over trail that set need not be a half-line: a soft pin or a long relaxation
length can make the caster shimmy at short trails (the classic lower boundary) *and* at long ones
(the pin-spring mode, docs/shimmy.md), leaving a band such as 5-17 cm.  :func:`shimmy_band` finds
every boundary: the spectral abscissa (largest real part) on a trail grid for all speeds and all
compliance cases at once (vectorised), then each sign change bisected to 1e-9 m together.

Conventions: trails in m; a band's end at the search limit (:data:`TRAIL_SEARCH_M`) is not a
boundary (the band may go on).  The margin of the chair's own trail is the signed distance to the
nearest true boundary: positive inside a shimmy-free band, negative inside a shimmy zone.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stability.models import shimmy as shimmy_model
from stability.models.params import parameters
from stability.models.statics import normal_loads
from stability.shimmy.compliance import CasterCompliance
from stability.shimmy.layout_caster import CasterSource, LayoutCaster

__all__ = ["TRAIL_SEARCH_M", "GRID_POINTS", "ShimmyBand", "shimmy_band", "band_core", "shimmy_intervals", "abscissa",
           "margin_to_boundaries", "margin_words", "margin_cell", "margin_bound"]

#: Trails searched for boundaries (m): 1 mm to 25 cm.
TRAIL_SEARCH_M = (0.001, 0.25)
#: Grid points on the search range (a band or gap narrower than one step, 2.5 mm, can be missed).
GRID_POINTS = 100
_BISECTIONS = 24          # bracket 2.5 mm / 2^24 ~ 1.5e-10 m


def _wheel_params(chair: CasterSource, trails: np.ndarray, comp: CasterCompliance) -> tuple[str, dict]:
    """Towed-wheel parameters of the left caster (or the layout's caster) at each trail (arrays), as caster_wheel
    builds them."""
    if isinstance(chair, LayoutCaster):
        n_a = np.nan_to_num(chair.loads(trails), nan=-1.0)
    else:
        n_a = normal_loads(parameters(chair)._replace(trail=trails))[0]
    with np.errstate(invalid="ignore"):
        c_alpha = np.asarray(chair.caster_tire_model().cornering_stiffness_per_rad(np.maximum(n_a, 1e-9)), float)
    c_alpha = np.where(n_a > 0, c_alpha, np.nan)
    inertia = chair.i_zp - chair.m_c * chair.l1**2
    rigid_pivot = math.isinf(comp.lateral_stiffness)
    case = shimmy_model.case_name(rigid_pivot, False)
    params = dict(mass=chair.m_c, inertia=inertia, a=trails - chair.l1, b=chair.l1,
                  k=1.0 if rigid_pivot else comp.lateral_stiffness, C=c_alpha, sigma=comp.relaxation_length,
                  c=chair.pin_damping)
    return case, params


def abscissa(chair: CasterSource, trails, speeds, comp: CasterCompliance | None = None) -> np.ndarray:
    """Largest real part of the caster's eigenvalues (1/s), shape ``(len(trails), len(speeds))``.

    Parameters
    ----------
    chair : Chair or LayoutCaster
        The chair (its left caster; its trail replaced by each of ``trails``).
    trails : array_like
        Trails (m).
    speeds : array_like
        Speeds (m/s).
    comp : CasterCompliance, optional
        Relaxation length and pin lateral stiffness; default the estimates.

    Returns
    -------
    ndarray
        NaN where the caster would carry no load (trail outside the chair's statics).
    """
    comp = comp or CasterCompliance()
    T = np.asarray(trails, float)
    U = np.asarray(speeds, float)
    case, params = _wheel_params(chair, T[:, None] + 0 * U[None, :], comp)
    ok = np.isfinite(params["C"])
    params["C"] = np.where(ok, params["C"], 1.0)
    A, _ = shimmy_model.state_matrices(case, params, U[None, :])
    out = np.linalg.eigvals(A).real.max(axis=-1)
    return np.where(ok, out, np.nan)


def _damping_ratio(chair: CasterSource, speeds: np.ndarray, comp: CasterCompliance) -> np.ndarray:
    """Damping ratio of the least damped oscillatory caster mode at the chair's trail, per speed."""
    case, params = _wheel_params(chair, np.full(speeds.size, chair.trail), comp)
    A, _ = shimmy_model.state_matrices(case, params, speeds)
    ev = np.linalg.eigvals(A)
    osc = np.abs(ev.imag) > 1e-9 * np.abs(ev).max(axis=-1, keepdims=True)
    zeta = np.where(osc, -ev.real / np.maximum(np.abs(ev), 1e-300), np.inf)
    return zeta.min(axis=-1)


def _boundaries(chair: CasterSource, speeds: np.ndarray, comp: CasterCompliance) -> tuple[list, list]:
    """Per speed: stable intervals [(lo, hi), ...] and the true boundaries (sorted), m."""
    return _boundaries_many(chair, speeds, [comp])[0]


def _boundaries_many(chair: CasterSource, speeds: np.ndarray, comps: list) -> list[tuple[list, list]]:
    """:func:`_boundaries` for several compliances, every bisection step one vectorised call per pivot case."""
    grid = np.linspace(*TRAIL_SEARCH_M, GRID_POINTS)
    scans = [abscissa(chair, grid, speeds, comp) for comp in comps]
    # brackets of every sign change (valid neighbours only) of every compliance, bisected together
    owner, ii, jj = [], [], []
    for n, s in enumerate(scans):
        stable = s < 0
        i, j = np.nonzero((stable[:-1] != stable[1:]) & np.isfinite(s[:-1]) & np.isfinite(s[1:]))
        owner += [n] * i.size
        ii += i.tolist()
        jj += j.tolist()
    own, i, j = np.array(owner, int), np.array(ii, int), np.array(jj, int)
    lo, hi = grid[i].copy(), grid[i + 1].copy()
    lo_stable = np.array([scans[n][a, b] < 0 for n, a, b in zip(own, i, j, strict=True)], bool)
    ks = np.array([comps[n].lateral_stiffness for n in own], float)
    sig = np.array([comps[n].relaxation_length for n in own], float)
    rigid = np.isinf(ks)
    for _ in range(_BISECTIONS if i.size else 0):
        mid = 0.5 * (lo + hi)
        mid_stable = np.empty(mid.size, bool)
        for flag in (False, True):
            sel = rigid == flag
            if sel.any():
                mid_stable[sel] = _abscissa_pairs(chair, mid[sel], speeds[j[sel]], ks[sel], sig[sel], flag) < 0
        same = mid_stable == lo_stable
        lo = np.where(same, mid, lo)
        hi = np.where(same, hi, mid)
    edges = 0.5 * (lo + hi)
    out = []
    for n, s in enumerate(scans):
        stable = s < 0
        valid = np.isfinite(s)
        intervals, bounds = [], []
        for k in range(speeds.size):
            e = np.sort(edges[(own == n) & (j == k)])
            bounds.append(tuple(float(x) for x in e))
            first = grid[valid[:, k]][0] if valid[:, k].any() else TRAIL_SEARCH_M[0]
            last = grid[valid[:, k]][-1] if valid[:, k].any() else TRAIL_SEARCH_M[0]
            pts = [float(first), *e.tolist(), float(last)]
            start_stable = bool(stable[valid[:, k], k][0]) if valid[:, k].any() else False
            iv = [(pts[m], pts[m + 1]) for m in range(len(pts) - 1) if (m % 2 == 0) == start_stable]
            intervals.append(tuple(iv))
        out.append((intervals, bounds))
    return out


def shimmy_intervals(chair: CasterSource, speeds, compliance: CasterCompliance) -> list:
    """Per speed, the shimmy-free trail intervals ``[(lo, hi), ...]`` (m) at one compliance.

    Parameters
    ----------
    chair : Chair or LayoutCaster
    speeds : array_like
        m/s.
    compliance : CasterCompliance

    Returns
    -------
    list of tuple
        An interval ending at :data:`TRAIL_SEARCH_M`'s upper limit may go on beyond it.
    """
    return _boundaries(chair, np.atleast_1d(np.asarray(speeds, float)), compliance)[0]


def _abscissa_pairs(chair: CasterSource, trails: np.ndarray, speeds: np.ndarray, ks: np.ndarray, sigmas: np.ndarray,
                    rigid: bool) -> np.ndarray:
    """Abscissa (1/s) at paired (trail, speed, pin stiffness, relaxation length) points of one pivot case."""
    comp = CasterCompliance(lateral_stiffness=math.inf if rigid else 1.0, relaxation_length=1.0,
                            lateral_stiffness_range=(1.0, math.inf), relaxation_length_range=(1.0, 1.0))
    case, params = _wheel_params(chair, trails, comp)
    params["C"] = np.where(np.isfinite(params["C"]), params["C"], 1.0)
    params["sigma"] = sigmas
    if not rigid:
        params["k"] = ks
    A, _ = shimmy_model.state_matrices(case, params, speeds)
    return np.linalg.eigvals(A).real.max(axis=-1)


def margin_to_boundaries(trail: float, intervals, boundaries) -> float:
    """Signed distance (m) from ``trail`` to the nearest boundary: + inside a stable band, - inside a shimmy zone.

    Parameters
    ----------
    trail : float
        The chair's trail (m).
    intervals : sequence of (float, float)
        Shimmy-free intervals (m).
    boundaries : sequence of float
        True boundaries (m); the search limits are not boundaries.

    Returns
    -------
    float
        ``+inf`` when stable with no boundary found, ``-inf`` when no trail searched is stable.
    """
    inside = any(a <= trail <= b for a, b in intervals)
    if not boundaries:
        return math.inf if inside else -math.inf
    d = min(abs(trail - x) for x in boundaries)
    return d if inside else -d


def margin_words(margin: float) -> str:
    """A shimmy margin in words, cm; an unbounded one (:func:`margin_to_boundaries`' infinities) as what it means.

    Parameters
    ----------
    margin : float
        Signed distance of the trail from the nearest shimmy boundary (m): + shimmy-free, - inside a shimmy zone,
        ``+inf`` no boundary on the trails searched (:data:`TRAIL_SEARCH_M`), ``-inf`` no trail searched is stable.

    Returns
    -------
    str
        ``"+3.14 cm"``, ``"no shimmy boundary between 0.1 and 25 cm"`` or ``"it shimmies at every trail from 0.1 to
        25 cm"``.
    """
    lo, hi = (f"{100 * x:g}" for x in TRAIL_SEARCH_M)
    if math.isinf(margin):
        return (f"no shimmy boundary between {lo} and {hi} cm" if margin > 0 else
                f"it shimmies at every trail from {lo} to {hi} cm")
    return f"{100 * margin:+.2f} cm"


def margin_cell(margin: float, spec: str = "+.2f") -> str:
    """A shimmy margin in a table's cell, cm without the unit; an unbounded one in two words.

    Parameters
    ----------
    margin : float
        As :func:`margin_words` (m).
    spec : str
        Format of a finite margin in cm.

    Returns
    -------
    str
        ``"+3.14"``, ``"none found"`` (``+inf``: no boundary on the trails searched) or ``"every trail"``
        (``-inf``: every trail searched shimmies).
    """
    if math.isinf(margin):
        return "none found" if margin > 0 else "every trail"
    return format(100 * margin, spec)


def margin_bound(margin: float, trail: float) -> tuple[float, str]:
    """A shimmy margin as a value or a bound, for ranking (a bound is a value: :mod:`stability.study.censored`).

    An infinite margin (:func:`margin_to_boundaries`) still says something: with no boundary on the trails
    searched (:data:`TRAIL_SEARCH_M`) any boundary lies beyond the search's ends, so a shimmy-free trail is at
    least its distance to the nearer end from one (``+inf``: ``"above"``), and a trail where every trail searched
    shimmies is at least that far inside a shimmy zone (``-inf``: ``"below"``, minus the distance).

    Parameters
    ----------
    margin : float
        As :func:`margin_words` (m; NaN: none computed).
    trail : float
        The trail the margin is of (m).

    Returns
    -------
    (float, str)
        ``(margin m, "found")`` for a finite margin, ``(+-distance m, "above" / "below")`` for an infinite one (the
        distance from ``trail`` to the nearer end of :data:`TRAIL_SEARCH_M`, 0 outside it), ``(nan, "")`` for NaN.
    """
    if math.isnan(margin):
        return margin, ""
    if math.isfinite(margin):
        return margin, "found"
    lo, hi = TRAIL_SEARCH_M
    d = max(0.0, min(trail - lo, hi - trail))
    return (d, "above") if margin > 0 else (-d, "below")


@dataclass(frozen=True)
class ShimmyBand:
    """The shimmy-free trail band(s) of a chair's caster at its use speeds, with the chair's margin.

    Attributes
    ----------
    chair : str
        Chair name.
    trail_m : float
        The chair's own trail (m).
    speeds_m_s : tuple of float
        Speeds (m/s).
    compliance : CasterCompliance
        Nominal estimates and their ranges (relaxation length, pin lateral stiffness).
    intervals_m : tuple
        Per speed, the shimmy-free trail intervals ``((lo, hi), ...)`` at the nominal estimates (m).
    boundaries_m : tuple
        Per speed, every true boundary at the nominal estimates (m, ascending).
    corner_intervals_m : tuple
        Per corner of the estimate ranges (:meth:`CasterCompliance.corners`), per speed, the intervals.
    margin_m : tuple of float
        Per speed, signed distance of the chair's trail to the nearest boundary at the nominal estimates
        (m; negative inside a shimmy zone, +-inf when no boundary was found).
    margin_range_m : tuple
        Per speed, ``(min, max)`` of that margin over the nominal estimates and the corners (m).
    damping_ratio : tuple of float
        Per speed, damping ratio of the least damped oscillatory caster mode at the chair's trail (nominal).
    """

    chair: str
    trail_m: float
    speeds_m_s: tuple
    compliance: CasterCompliance
    intervals_m: tuple
    boundaries_m: tuple
    corner_intervals_m: tuple
    margin_m: tuple
    margin_range_m: tuple
    damping_ratio: tuple

    @property
    def shimmy_margin_m(self) -> float:
        """The smallest margin over the speeds (m), nominal estimates: the advisor's ``shimmy_margin_m``."""
        return min(self.margin_m)

    @property
    def shimmy_margin_interval_m(self) -> tuple[float, float]:
        """``(low, high)`` of :attr:`shimmy_margin_m` over the estimate ranges (m)."""
        return (min(r[0] for r in self.margin_range_m), min(r[1] for r in self.margin_range_m))

    @property
    def straddles(self) -> bool:
        """True when the margin changes sign over the estimate ranges: measure pin stiffness and relaxation first."""
        lo, hi = self.shimmy_margin_interval_m
        return lo < 0 < hi

    @property
    def nearest_boundary_m(self) -> float | None:
        """The boundary nearest the chair's trail over the speeds (nominal), m; None if none was found."""
        all_b = [b for bs in self.boundaries_m for b in bs]
        return min(all_b, key=lambda b: abs(b - self.trail_m)) if all_b else None

    def describe(self, k: int) -> str:
        """The band(s) at speed index ``k`` in words, cm (``"5.0-17.2"``, ``"none"``; ``"+"`` at the search end)."""
        iv = self.intervals_m[k]
        if not iv:
            return "none"
        # an interval reaching the search end ends exactly at it: the grid's last point is linspace's stop
        return ", ".join(f"{a * 100:.1f}-{b * 100:.1f}{'+' if b >= TRAIL_SEARCH_M[1] else ''}" for a, b in iv)

    def to_mapping(self) -> dict:
        """JSON-ready dict (m, m/s; infinite margins as null)."""
        def f(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        return {
            "trail_m": self.trail_m, "speeds_m_s": list(self.speeds_m_s),
            "trail_search_m": list(TRAIL_SEARCH_M),
            "shimmy_free_intervals_m": [[list(iv) for iv in ivs] for ivs in self.intervals_m],
            "boundaries_m": [list(b) for b in self.boundaries_m],
            "corners": [{"relaxation_length_m": c.relaxation_length, "lateral_stiffness_N_per_m": c.lateral_stiffness,
                         "shimmy_free_intervals_m": [[list(iv) for iv in ivs] for ivs in civ]}
                        for c, civ in zip(self.compliance.corners(), self.corner_intervals_m, strict=True)],
            "margin_m": [f(m) for m in self.margin_m],
            "margin_range_m": [[f(a), f(b)] for a, b in self.margin_range_m],
            "damping_ratio": [f(z) for z in self.damping_ratio],
            "shimmy_margin_m": f(self.shimmy_margin_m),
            "shimmy_margin_interval_m": [f(x) for x in self.shimmy_margin_interval_m],
            "straddles_estimate_range": self.straddles,
            "null_means": "no boundary found on the trail search range (margin unbounded)",
        }


def band_core(chair: CasterSource, speeds, compliance: CasterCompliance | None = None) -> tuple:
    """The trail-independent part of :func:`shimmy_band`: intervals and boundaries, nominal and per corner.

    Everything here depends on the chair except its own trail, so chairs differing only in trail can
    share it (``shimmy_band(chair, speeds, core=...)``).

    Parameters
    ----------
    chair : Chair or LayoutCaster
    speeds : array_like
        m/s.
    compliance : CasterCompliance, optional

    Returns
    -------
    tuple
        ``(speeds, compliance, (intervals, boundaries), [(intervals, boundaries) per corner])``.
    """
    comp = compliance or CasterCompliance()
    U = np.atleast_1d(np.asarray(speeds, float))
    if chair.m_c <= 0 or chair.i_zp - chair.m_c * chair.l1**2 <= 0:
        raise ValueError(f"chair parameter i_zp={chair.i_zp!r} is invalid for shimmy; valid range: "
                         f"> m_c*l1^2 = {chair.m_c * chair.l1**2:.6g} kg m^2 with m_c > 0")
    allb = _boundaries_many(chair, U, [comp, *comp.corners()])
    return U, comp, allb[0], allb[1:]


def shimmy_band(chair: CasterSource, speeds, compliance: CasterCompliance | None = None, *,
                core: tuple | None = None) -> ShimmyBand:
    """Every boundary of the shimmy-free trail set of ``chair``'s caster, and the chair's margin.

    Parameters
    ----------
    chair : Chair or LayoutCaster
        The chair (left caster; trail > 0, m_c > 0).
    speeds : array_like
        Speeds (m/s, > 0).
    compliance : CasterCompliance, optional
        Nominal estimates and ranges; default :class:`CasterCompliance`.
    core : tuple, optional
        :func:`band_core` of a chair that differs from ``chair`` at most in its trail (saves the search).

    Returns
    -------
    ShimmyBand
    """
    U, comp, (nominal, bounds), corners = core if core is not None else band_core(chair, speeds, compliance)
    margin = [margin_to_boundaries(chair.trail, nominal[k], bounds[k]) for k in range(U.size)]
    rng = []
    for k in range(U.size):
        vals = [margin[k]] + [margin_to_boundaries(chair.trail, ci[k], cb[k]) for ci, cb in corners]
        rng.append((min(vals), max(vals)))
    return ShimmyBand(chair=chair.name, trail_m=chair.trail, speeds_m_s=tuple(float(u) for u in U), compliance=comp,
                      intervals_m=tuple(nominal), boundaries_m=tuple(bounds),
                      corner_intervals_m=tuple(tuple(ci) for ci, _ in corners), margin_m=tuple(margin),
                      margin_range_m=tuple(rng),
                      damping_ratio=tuple(float(z) for z in _damping_ratio(chair, U, comp)))
