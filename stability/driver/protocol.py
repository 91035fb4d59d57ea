"""The critical tracking task's protocol: trials, their validity, the result, the chair file's ``[user]`` table.

The task itself (the plant, the ramp, the escape factor) is :mod:`.tracking`; this module judges the trials the
browser reports (:class:`TrialRecord`: untrusted, every field checked), plans the next one (:func:`next_trial`),
and turns the valid scored trials into ``tau_e = E / mean(lambda_c)`` with its spread (:func:`tracking_result`),
written into a chair file as a ``[user]`` table (:func:`user_toml`).  docs/driver.md states the protocol.
"""

from __future__ import annotations

import json
import math
import unicodedata
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from stability.driver.model import REACTION_TIME_RANGE_S
from stability.driver.tracking import (
    EARLY_RISE,
    FIRST_TIME_CONSTANT_S,
    INPUT_DEADBAND,
    LAMBDA_MAX_1_S,
    MIN_VALID,
    PRACTICE_RAMP_S_PER_S,
    PRACTICE_TRIALS,
    RAMP_S_PER_S,
    SCORED_TRIALS,
    START_FRACTION,
    EscapeFactor,
    escape_factor,
)

__all__ = ["TrialRecord", "Trial", "judge", "next_trial", "TrackingResult", "tracking_result", "user_toml"]


@dataclass(frozen=True)
class TrialRecord:
    """One trial as the browser reports it.

    Attributes
    ----------
    kind : str
        ``"practice"`` or ``"scored"``.
    lambda_start_1_s : float
        The instability at the start, 1/s.
    lambda_c_1_s : float
        The instability when control was lost, 1/s.
    duration_s : float
        From the start to the loss, s.
    input_range : float
        How far the input moved during the trial (largest minus smallest, fraction of full deflection, 0-2).
    device : str
        ``"keyboard"``, ``"mouse"``, ``"gamepad"`` (the last one used).
    """

    kind: str
    lambda_start_1_s: float
    lambda_c_1_s: float
    duration_s: float
    input_range: float
    device: str = "keyboard"

    @classmethod
    def from_mapping(cls, data: Mapping) -> TrialRecord:
        """A record from the browser's JSON (untrusted: every field checked).

        Parameters
        ----------
        data : mapping
            The fields of :class:`TrialRecord`.

        Returns
        -------
        TrialRecord

        Raises
        ------
        ValueError
            On a missing, non-finite or out-of-range field.
        """
        if not isinstance(data, Mapping):
            raise ValueError("a trial must be a table of numbers")
        kind = data.get("kind")
        if kind not in ("practice", "scored"):
            raise ValueError(f"trial kind={kind!r} is invalid; valid: 'practice', 'scored'")
        nums = {}
        for name, lo, hi in (("lambda_start_1_s", 0.0, LAMBDA_MAX_1_S), ("lambda_c_1_s", 0.0, LAMBDA_MAX_1_S),
                             ("duration_s", 0.0, 3600.0), ("input_range", 0.0, 2.0)):
            v = data.get(name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or not lo <= v <= hi:
                raise ValueError(f"trial {name}={v!r} is invalid; valid range: {lo:g} to {hi:g}")
            nums[name] = float(v)
        device = data.get("device", "keyboard")
        if device not in ("keyboard", "mouse", "gamepad"):
            device = "keyboard"
        return cls(str(kind), device=str(device), **nums)


@dataclass(frozen=True)
class Trial:
    """A judged trial.

    Attributes
    ----------
    record : TrialRecord
    valid : bool
    reason : str
        Why it is invalid (``"no input"``, ``"early loss"``), or ``""``.
    """

    record: TrialRecord
    valid: bool
    reason: str = ""


def judge(records: Sequence[TrialRecord]) -> tuple[Trial, ...]:
    """Apply the validity rules to each trial.

    Parameters
    ----------
    records : sequence of TrialRecord

    Returns
    -------
    tuple of Trial
        Invalid: the input never moved more than :data:`INPUT_DEADBAND` of its range (``"no input"``), or control
        was lost before ``lambda`` rose by :data:`EARLY_RISE` from the trial's start (``"early loss"``).
    """
    out = []
    for r in records:
        if r.input_range <= INPUT_DEADBAND:
            out.append(Trial(r, False, "no input"))
        elif r.lambda_c_1_s < EARLY_RISE * r.lambda_start_1_s:
            out.append(Trial(r, False, "early loss"))
        else:
            out.append(Trial(r, True))
    return tuple(out)


def next_trial(records: Sequence[TrialRecord]) -> dict | None:
    """The next trial of the protocol, or None when it is complete.

    Parameters
    ----------
    records : sequence of TrialRecord
        The trials so far.

    Returns
    -------
    dict or None
        ``kind``, ``number`` (1-based within its kind), ``lambda_start_1_s``, ``rate_s_per_s``, ``seq`` (the
        trials so far).  The first trial (practice, to find the range) runs the fast ramp from
        ``1 / FIRST_TIME_CONSTANT_S``; every later one (the second practice trial, then the scored trials) runs the
        scored ramp from ``START_FRACTION`` of the user's limit estimated so far: the mean ``lambda_c`` of the valid
        trials at the scored ramp over its escape factor (before there is one, the first trial's ``lambda_c``
        over the fast ramp's); lower after an early loss.  Scored trials continue until :data:`SCORED_TRIALS` are
        valid or twice that many have run.
    """
    trials = judge(records)
    practice = sum(1 for t in trials if t.record.kind == "practice")
    scored = [t for t in trials if t.record.kind == "scored"]
    valid_scored = sum(1 for t in scored if t.valid)
    same_ramp = [t.record.lambda_c_1_s for t in trials[1:] if t.valid]
    if same_ramp:                                       # averaged: one lucky trial does not move the next start
        limit = float(np.mean(same_ramp)) / escape_factor(RAMP_S_PER_S).mean
    elif trials and trials[0].valid:
        limit = trials[0].record.lambda_c_1_s / escape_factor(PRACTICE_RAMP_S_PER_S,
                                                              lambda0_1_s=1.0 / FIRST_TIME_CONSTANT_S).mean
    else:
        limit = 1.0 / (START_FRACTION * FIRST_TIME_CONSTANT_S)
    lam0 = START_FRACTION * limit
    if trials and trials[-1].reason == "early loss":   # lost at once: start lower than that trial did
        lam0 = min(lam0, START_FRACTION * trials[-1].record.lambda_start_1_s)
    rate = PRACTICE_RAMP_S_PER_S if not trials else RAMP_S_PER_S
    if practice < PRACTICE_TRIALS:
        return {"kind": "practice", "number": practice + 1, "lambda_start_1_s": lam0, "rate_s_per_s": rate,
                "seq": len(records)}
    if valid_scored >= SCORED_TRIALS or len(scored) >= 2 * SCORED_TRIALS:
        return None
    return {"kind": "scored", "number": len(scored) + 1, "lambda_start_1_s": lam0, "rate_s_per_s": rate,
            "seq": len(records)}


@dataclass(frozen=True)
class TrackingResult:
    """The task's result: ``lambda_c`` and the user's effective delay with its spread.

    Attributes
    ----------
    trials : tuple of Trial
    lambda_c_1_s : float or None
        Mean ``lambda_c`` of the valid scored trials, 1/s (None: fewer than :data:`MIN_VALID`).
    lambda_c_sd_1_s : float or None
        Their standard deviation, 1/s.
    escape : EscapeFactor
    reaction_time_s : float or None
        ``tau_e = E / lambda_c``, s.
    reaction_time_sd_s : float or None
        Its spread, s: the trials' and the escape factor's relative spreads combined in quadrature.
    """

    trials: tuple[Trial, ...]
    lambda_c_1_s: float | None
    lambda_c_sd_1_s: float | None
    escape: EscapeFactor
    reaction_time_s: float | None
    reaction_time_sd_s: float | None

    @property
    def valid_scored(self) -> int:
        """Valid scored trials."""
        return sum(1 for t in self.trials if t.valid and t.record.kind == "scored")

    def user_table(self, note: str = "") -> dict:
        """The chair file's ``[user]`` table (:meth:`stability.driver.Driver.from_mapping` reads it back).

        Parameters
        ----------
        note : str
            The user's own note (who, when); kept as text in ``source``.

        Returns
        -------
        dict
            Empty without a result.  The reaction time is rounded to 0.1 ms (and kept inside
            :data:`stability.driver.model.REACTION_TIME_RANGE_S`).
        """
        if self.reaction_time_s is None:
            return {}
        lo, hi = REACTION_TIME_RANGE_S
        scored = [t for t in self.trials if t.record.kind == "scored"]
        src = (f"critical tracking task: {self.valid_scored} valid scored trials, lambda_c "
               f"{self.lambda_c_1_s:.3f} +/- {self.lambda_c_sd_1_s:.3f} 1/s, escape factor "
               f"{self.escape.mean:.3f} +/- {self.escape.sd:.3f}")
        if note.strip():
            src += "; " + " ".join(note.split())[:200]
        return {"reaction_time_s": round(float(min(max(self.reaction_time_s, lo), hi)), 4),
                "reaction_time_sd_s": round(float(self.reaction_time_sd_s or 0.0), 4),
                "source": src,
                "tracking_lambda_c_1_s": [round(t.record.lambda_c_1_s, 4) for t in scored],
                "tracking_valid": [t.valid for t in scored]}


def tracking_result(records: Sequence[TrialRecord], escape: EscapeFactor | None = None) -> TrackingResult:
    """Judge the trials and compute ``tau_e``.

    Parameters
    ----------
    records : sequence of TrialRecord
    escape : EscapeFactor, optional
        Default :func:`escape_factor` for :data:`RAMP_S_PER_S`.

    Returns
    -------
    TrackingResult
        ``tau_e = E / mean(lambda_c)`` over the valid scored trials; relative spread
        ``sqrt((sd_E / E)^2 + (sd_lambda / lambda)^2)``.
    """
    esc = escape or escape_factor()
    trials = judge(records)
    lam = np.array([t.record.lambda_c_1_s for t in trials if t.valid and t.record.kind == "scored"])
    if lam.size < MIN_VALID:
        return TrackingResult(trials, None, None, esc, None, None)
    mean, sd = float(lam.mean()), float(lam.std(ddof=1))
    tau = esc.mean / mean
    rel = math.hypot(esc.sd / esc.mean, sd / mean)
    return TrackingResult(trials, mean, sd, esc, tau, tau * rel)


def _toml_scalar(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        if not math.isfinite(float(value)):
            raise ValueError(f"[user] value {value!r} is not finite")
        return repr(float(value))
    text = "".join(c for c in str(value) if unicodedata.category(c) != "Cc")     # no control characters
    return json.dumps(text, ensure_ascii=False)              # a TOML basic string: \\ and \" escaped


def user_toml(table: Mapping) -> str:
    """A ``[user]`` table as TOML text (to append to :func:`stability.chair.dumps`'s flat table).

    Parameters
    ----------
    table : mapping
        Keys (from :data:`stability.driver.model.TRACKING_KEYS` and :meth:`Driver.to_mapping`) to numbers,
        booleans, text or lists of them.  Text is written as an escaped string without control characters.

    Returns
    -------
    str
        ``"\\n[user]\\nkey = value\\n..."``.
    """
    lines = ["", "[user]"]
    for key, value in table.items():
        if not key.replace("_", "").isalnum() or not key.isascii():
            raise ValueError(f"[user] key {key!r} is invalid; valid: ASCII letters, digits and _")
        if isinstance(value, (list, tuple)):
            lines.append(f"{key} = [" + ", ".join(_toml_scalar(v) for v in value) + "]")
        else:
            lines.append(f"{key} = {_toml_scalar(value)}")
    return "\n".join(lines) + "\n"
