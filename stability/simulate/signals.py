"""Reading time histories: time to reach a level, exponential rates, settling time.

Pure functions of sampled arrays; used by the studies, the validation and the
motor-assist checks alike.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["time_to_level", "growth_rate", "envelope_rate", "settle_time"]


def time_to_level(t, y, level: float) -> float:
    """First time ``|y|`` reaches ``level``, linearly interpolated between samples (s).

    Parameters
    ----------
    t : array_like
        Sample times, s (increasing).
    y : array_like
        The signal (e.g. yaw rate, rad/s).  A non-finite sample counts as
        reaching the level at its own time.
    level : float
        Threshold on ``|y|`` (same unit as ``y``), > 0.

    Returns
    -------
    float
        The crossing time, s, or ``inf`` when ``|y|`` never reaches ``level``.
    """
    t = np.asarray(t, dtype=float)
    r = np.abs(np.asarray(y, dtype=float))
    finite = np.isfinite(r)
    hit = np.flatnonzero((r >= level) | ~finite)
    if not len(hit):
        return math.inf
    k = int(hit[0])
    if k == 0 or not finite[k]:
        return float(t[k])
    r0, r1 = r[k - 1], r[k]
    return float(t[k - 1] + (level - r0) / (r1 - r0) * (t[k] - t[k - 1]))


def growth_rate(t, y, oscillatory: bool, window: tuple[float, float]) -> float:
    """Exponential growth (positive) or decay rate of ``y(t)`` inside ``window`` (1/s).

    Parameters
    ----------
    t, y : array_like
        Uniformly sampled time (s) and signal.
    oscillatory : bool
        Fit a complex pair by Prony's method of order 2 instead of a
        straight line through ``log|y|`` (a single real mode).
    window : (float, float)
        Start and end of the fit, s.

    Returns
    -------
    float
        The rate, 1/s (the real part of the mode's eigenvalue).
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    sel = (t >= window[0]) & (t <= window[1]) & np.isfinite(y)
    ts, ys = t[sel], y[sel]
    if len(ts) < 8:
        raise ValueError(f"window={window} holds only {len(ts)} samples; need at least 8")
    if not oscillatory:
        if np.any(ys == 0) or np.any(np.sign(ys) != np.sign(ys[0])):
            raise ValueError("signal changes sign inside the window: not a single real mode")
        return float(np.polyfit(ts, np.log(np.abs(ys)), 1)[0])
    dt = float(np.median(np.diff(ts)))
    A = np.column_stack([ys[1:-1], ys[:-2]])
    c1, c0 = np.linalg.lstsq(A, ys[2:], rcond=None)[0]
    z = np.roots([1.0, -c1, -c0])
    return float(np.log(np.max(np.abs(z))) / dt)


def envelope_rate(t, y, t_start: float, t_end: float) -> float:
    """Exponential rate of the envelope of ``y`` on ``[t_start, t_end]`` (1/s, negative for decay).

    With at least three local maxima of ``|y|`` in the window (an oscillating
    response) the logs of those peaks, refined by a parabola through the three
    samples around each, are fitted with a straight line (the extrema of
    ``A e^(st) cos(wt + p)`` shrink by ``e^(s pi/w)`` each); otherwise
    ``log|y|`` at every sample is.

    Parameters
    ----------
    t, y : array_like
        Sample times (s) and signal.
    t_start, t_end : float
        The fitting window, s.

    Returns
    -------
    float
        The rate, 1/s.
    """
    t = np.asarray(t, dtype=float)
    a = np.abs(np.asarray(y, dtype=float))
    w = (t >= t_start) & (t <= t_end) & (a > 0)
    tw, aw = t[w], a[w]
    if tw.size < 3:
        raise ValueError("envelope_rate: fewer than 3 samples in the window")
    peaks = np.flatnonzero((aw[1:-1] > aw[:-2]) & (aw[1:-1] >= aw[2:])) + 1
    if peaks.size >= 3:
        la = np.log(aw)
        pt, pv = [], []
        for i in peaks:
            y0, y1, y2 = la[i - 1], la[i], la[i + 1]
            den = y0 - 2 * y1 + y2
            off = 0.5 * (y0 - y2) / den if den != 0 else 0.0
            h = tw[i + 1] - tw[i]
            pt.append(tw[i] + off * h)
            pv.append(y1 - 0.25 * (y0 - y2) * off)
        return float(np.polyfit(pt, pv, 1)[0])
    return float(np.polyfit(tw, np.log(aw), 1)[0])


def settle_time(t, y, fraction: float = 0.05, floor: float = 0.0, final_window: float = 0.0) -> float | None:
    """First time after which ``y`` stays within ``max(fraction * peak, floor)`` of its final value (s).

    The final value is 0 with ``final_window = 0`` (settling to zero), else the mean of ``y`` over the last
    ``final_window`` of the run (a fraction of its duration), and then ``y`` must stay within the band over that
    whole window: a response still drifting at the end has no final value and does not settle.  ``peak`` is the
    largest ``|y - final value|``.

    Parameters
    ----------
    t, y : array_like
        Sample times (s) and signal.
    fraction : float
        Band as a fraction of the peak departure from the final value.
    floor : float
        Smallest band, in the unit of ``y``.
    final_window : float
        Share of the run (0 to 1) whose mean is the final value (0: the final value is 0).

    Returns
    -------
    float or None
        The settling time, s; 0 when ``y`` never leaves the band; None when it is still outside the band at the last
        sample, or (``final_window > 0``) within the final window.
    """
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    if y.size == 0:
        return None
    tail = t >= t[-1] - final_window * (t[-1] - t[0]) if final_window > 0 else np.zeros(t.size, dtype=bool)
    a = np.abs(y - float(np.mean(y[tail]))) if final_window > 0 else np.abs(y)
    band = max(fraction * float(a.max()), floor)
    out = np.flatnonzero(a > band)
    if out.size == 0:
        return 0.0
    i = int(out[-1]) + 1
    return float(t[i]) if i < t.size and not tail[i - 1] else None
