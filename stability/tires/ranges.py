"""The fitted range of a tire and the one policy for data outside it.

Two levels: the *evaluation* policies of :meth:`Tire.lateral_force`
(:data:`POLICIES`: clamp, extrapolate, raise) and the toolkit's *range policy*
(:data:`RANGE_POLICIES`: warn, raise, clamp) that every analysis follows, set
per context with :func:`set_policy` / :func:`range_policy`; notes of data used
outside the fits are gathered with :func:`collect_notes`. See ``docs/tires.md``.
"""

from __future__ import annotations

import functools
import warnings
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import asdict, dataclass
from typing import Any, Literal, ParamSpec, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from stability.tires.data import FZ_MAX_N, SLIP_MAX_DEG

__all__ = [
    "summarise_notes",
    "POLICIES",
    "RANGE_POLICIES",
    "Policy",
    "RangeNote",
    "RangePolicy",
    "TireRangeWarning",
    "collect_notes",
    "get_policy",
    "out_of_range",
    "range_policy",
    "set_policy",
]

#: Out-of-range policies of :meth:`Tire.lateral_force` (how a force is evaluated).
POLICIES: tuple[str, ...] = ("clamp", "extrapolate", "raise")
#: The toolkit's tire-range policies (what an analysis does with data outside the fits).
RANGE_POLICIES: tuple[str, ...] = ("warn", "raise", "clamp")

Policy = Literal["clamp", "extrapolate", "raise"]
RangePolicyName = Literal["warn", "raise", "clamp"]


class TireRangeWarning(UserWarning):
    """Warning: a tire force or stiffness was asked for outside the fitted range.

    Emitted at most once per call of :meth:`Tire.lateral_force` (and the
    methods built on it) when ``|slip|`` or ``F_z`` exceeds the tire's fitted
    range (8 deg, 450 N for the thesis tires) and the policy is ``"clamp"``,
    ``"extrapolate"`` or (range policy) ``"warn"``.
    """


@dataclass(frozen=True)
class RangePolicy:
    """The tire-range policy in force.

    Attributes
    ----------
    name : {"warn", "raise", "clamp"}
        ``"warn"`` (default): compute with the fit as is (extrapolate), emit a
        :class:`TireRangeWarning` and record a :class:`RangeNote`;
        ``"raise"``: refuse with a one-line ValueError; ``"clamp"``: evaluate at
        the edge of the fitted range and record a note.
    """

    name: RangePolicyName = "warn"

    @property
    def evaluation(self) -> Policy:
        """The matching :data:`POLICIES` value for :meth:`Tire.lateral_force` (warn -> extrapolate)."""
        return "extrapolate" if self.name == "warn" else self.name


@dataclass(frozen=True)
class RangeNote:
    """One use of a tire fit outside its data.

    Attributes
    ----------
    tire : str
        Tire name.
    quantity : {"load", "slip"}
        Which input left the fitted range.
    value : float
        The value asked for (N or deg; the largest one for an array).
    low, high : float
        The fitted range (N or deg).
    policy : str
        The range policy applied (``"warn"``, ``"clamp"``, ``"raise"``).
    wheel : str or None
        Which wheel (e.g. ``"caster_left"``) when known.
    count : int
        Number of points outside the range in that call.
    """

    tire: str
    quantity: Literal["load", "slip"]
    value: float
    low: float
    high: float
    policy: str
    wheel: str | None = None
    count: int = 1

    @property
    def unit(self) -> str:
        """``"N"`` for a load, ``"deg"`` for a slip angle."""
        return "N" if self.quantity == "load" else "deg"

    def __str__(self) -> str:
        where = f"{self.wheel} tire {self.tire}" if self.wheel else f"tire {self.tire}"
        action = {"warn": "extrapolated", "clamp": f"clamped to {self.high:g} {self.unit}",
                  "raise": "refused"}.get(self.policy, self.policy)
        more = f" ({self.count} points)" if self.count > 1 else ""
        return (f"{where}: {self.quantity} {self.value:.4g} {self.unit} is outside the fitted range "
                f"{self.low:g} to {self.high:g} {self.unit}{more}; {action} (tire-range policy {self.policy!r})")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict, with the sentence under ``"message"``."""
        return {**asdict(self), "unit": self.unit, "message": str(self)}


def summarise_notes(notes: Sequence[RangeNote]) -> list[str]:
    """One line per tire, quantity and fitted range: how far outside, how often, on which wheels.

    The report and the studies evaluate a tire at many loads; one line per
    load (19-51 lines for a report) said the same thing again and again.

    Parameters
    ----------
    notes : sequence of RangeNote

    Returns
    -------
    list of str
        In the order the groups first appeared.

    Examples
    --------
    >>> n = [RangeNote("ER", "load", v, 0.0, 450.0, "warn", w) for v, w in
    ...      [(451.0, "caster_left"), (459.2, "caster_right"), (455.0, "caster_left")]]
    >>> print(summarise_notes(n)[0])  # doctest: +NORMALIZE_WHITESPACE
    tire ER: load up to 459.2 N (3 uses, 451-459.2 N; wheels caster_left, caster_right) is outside the
    fitted range 0 to 450 N; extrapolated (tire-range policy 'warn')
    """
    groups: dict[tuple, list[RangeNote]] = {}
    for n in notes:
        groups.setdefault((n.tire, n.quantity, n.low, n.high, n.policy), []).append(n)
    out = []
    for (tire, quantity, low, high, policy), ns in groups.items():
        if len(ns) == 1:
            out.append(str(ns[0]))
            continue
        vals = [n.value for n in ns]
        outside = [v for v in vals if v > high] or vals
        worst = max(outside) if any(v > high for v in vals) else min(vals)
        unit = ns[0].unit
        wheels = sorted({n.wheel for n in ns if n.wheel})
        where = f"; wheels {', '.join(wheels)}" if wheels else ""
        action = {"warn": "extrapolated", "clamp": f"clamped to {high:g} {unit}",
                  "raise": "refused"}.get(policy, policy)
        out.append(f"tire {tire}: {quantity} up to {worst:.4g} {unit} ({len(ns)} uses, {min(vals):.4g}-{max(vals):.4g} "
                   f"{unit}{where}) is outside the fitted range {low:g} to {high:g} {unit}; {action} "
                   f"(tire-range policy {policy!r})")
    return out


P = ParamSpec("P")
R = TypeVar("R")

_DEFAULT_POLICY = RangePolicy()
_POLICY: ContextVar[RangePolicy] = ContextVar("stability_tire_range_policy", default=_DEFAULT_POLICY)
_NOTES: ContextVar[list[RangeNote] | None] = ContextVar("stability_tire_range_notes", default=None)
_QUIET: ContextVar[bool] = ContextVar("stability_tire_range_quiet", default=False)


def _check_range_policy(name: str) -> RangePolicyName:
    if name not in RANGE_POLICIES:
        raise ValueError(f"tire-range policy {name!r} is not valid; choose one of {RANGE_POLICIES}")
    return name  # type: ignore[return-value]


def get_policy() -> RangePolicy:
    """The tire-range policy in force in this context (default ``"warn"``).

    Returns
    -------
    RangePolicy
    """
    return _POLICY.get()


def set_policy(name: str) -> RangePolicy:
    """Set the tire-range policy for this context (thread / task); returns the previous one.

    Parameters
    ----------
    name : {"warn", "raise", "clamp"}

    Returns
    -------
    RangePolicy
        The policy that was in force before.

    Raises
    ------
    ValueError
        For an unknown name (one line naming the valid choices).
    """
    previous = _POLICY.get()
    _POLICY.set(RangePolicy(_check_range_policy(name)))
    return previous


@contextmanager
def range_policy(name: str) -> Iterator[RangePolicy]:
    """Context manager: the tire-range policy ``name`` inside the block.

    Parameters
    ----------
    name : {"warn", "raise", "clamp"}

    Yields
    ------
    RangePolicy
    """
    token = _POLICY.set(RangePolicy(_check_range_policy(name)))
    try:
        yield _POLICY.get()
    finally:
        _POLICY.reset(token)


@contextmanager
def collect_notes() -> Iterator[list[RangeNote]]:
    """Context manager: a list that receives every :class:`RangeNote` recorded inside the block.

    Duplicates (same tire, wheel, quantity, value, policy) are recorded once.

    Yields
    ------
    list of RangeNote
    """
    notes: list[RangeNote] = []
    token = _NOTES.set(notes)
    try:
        yield notes
    finally:
        _NOTES.reset(token)


def record(note: RangeNote, *, warn: bool = True) -> None:
    """Add ``note`` to the active :func:`collect_notes` list; under ``"warn"`` also emit a warning.

    Parameters
    ----------
    note : RangeNote
    warn : bool
        Emit a :class:`TireRangeWarning` when the note's policy is ``"warn"``.
    """
    notes = _NOTES.get()
    if notes is not None and note not in notes:
        notes.append(note)
    if warn and note.policy == "warn" and not _QUIET.get():
        warnings.warn(str(note), TireRangeWarning, stacklevel=4)


def summarised_warnings(func: Callable[P, R]) -> Callable[P, R]:
    """Decorator: a function that evaluates tires at many loads warns once per group, not once per load.

    Inside ``func`` the notes are collected without a warning each; when it returns (or raises) every
    group of :func:`summarise_notes` is warned once as a :class:`TireRangeWarning` (the advisor screens
    dozens of candidate chairs: 300 warnings of one tire's load said one thing), and the notes pass on to
    an enclosing :func:`collect_notes` block (the command lines' note lines are unchanged).

    Parameters
    ----------
    func : callable

    Returns
    -------
    callable
    """
    @functools.wraps(func)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        notes: list[RangeNote] = []
        token, quiet = _NOTES.set(notes), _QUIET.set(True)
        try:
            return func(*args, **kwargs)
        finally:
            _NOTES.reset(token)
            _QUIET.reset(quiet)
            for n in notes:
                record(n, warn=False)
            for line in summarise_notes([n for n in notes if n.policy == "warn"]):
                warnings.warn(line, TireRangeWarning, stacklevel=2)
    return wrapper


def resolve(policy: str | None) -> RangePolicy:
    """The range policy named ``policy``, or the one in force when None."""
    return _POLICY.get() if policy is None else RangePolicy(_check_range_policy(policy))


def limit_load(tire: Any, fz: Any, policy: str | None, wheel: str | None = None) -> Any:
    """Apply the range policy to normal load(s) ``fz`` (N) of ``tire``; the loads to evaluate at.

    Parameters
    ----------
    tire : Tire
        Any object with ``name`` and ``fz_max_N``.
    fz : float or ndarray
        Normal load(s), N.
    policy : {"warn", "raise", "clamp"} or None
        None: the policy in force (:func:`get_policy`).
    wheel : str, optional
        Named in the note.

    Returns
    -------
    float or ndarray
        ``fz`` (warn), or clamped to ``fz_max_N`` (clamp).

    Raises
    ------
    ValueError
        Under ``"raise"`` when a load exceeds the fitted range.
    """
    pol = resolve(policy)
    high = float(tire.fz_max_N)
    arr = np.asarray(fz, dtype=float)
    bad = arr > high
    if not bad.any():
        return fz
    note = RangeNote(tire=tire.name, quantity="load", value=float(np.max(arr[bad])), low=0.0, high=high,
                     policy=pol.name, wheel=wheel, count=int(np.count_nonzero(bad)))
    if pol.name == "raise":
        raise ValueError(str(note) + "; use the 'warn' or 'clamp' tire-range policy to compute anyway")
    record(note)
    if pol.name == "clamp":
        return min(float(fz), high) if isinstance(fz, (int, float)) else np.minimum(arr, high)
    return fz


def out_of_range(slip_deg: ArrayLike, fz: ArrayLike, tire: Any = None) -> tuple[Any, Any]:
    """Masks of inputs outside the fitted range, without warnings.

    Parameters
    ----------
    slip_deg : array_like
        Slip angle(s), deg.
    fz : array_like
        Normal force(s), N.
    tire : Tire, optional
        Whose fitted range (``slip_max_deg``, ``fz_max_N``); the thesis tires'
        8 deg and 450 N when omitted.

    Returns
    -------
    slip_mask, fz_mask : bool or ndarray of bool
        ``|slip| > slip_max`` and ``fz > fz_max`` (broadcast together). Python
        bools for scalar inputs.
    """
    smax = SLIP_MAX_DEG if tire is None else tire.slip_max_deg
    fmax = FZ_MAX_N if tire is None else tire.fz_max_N
    if isinstance(slip_deg, (int, float)) and isinstance(fz, (int, float)):
        return abs(slip_deg) > smax, fz > fmax
    s, f = np.broadcast_arrays(np.asarray(slip_deg, dtype=float), np.asarray(fz, dtype=float))
    return np.abs(s) > smax, f > fmax


def _check_policy(policy: str) -> None:
    if policy not in POLICIES:
        raise ValueError(f"policy={policy!r} is not valid; choose one of {POLICIES}")


def _range_message(n_slip: int, n_fz: int, n_total: int, policy: str,
                   slip_max: float = SLIP_MAX_DEG, fz_max: float = FZ_MAX_N) -> str:
    return (
        f"{n_slip + n_fz} out-of-range input(s) among {n_total} point(s) "
        f"(|slip| > {slip_max:g} deg: {n_slip}, Fz > {fz_max:g} N: {n_fz}); "
        f"policy {policy!r} applied"
    )
