"""When a recovery has settled: the one rule of the short form's and a layout's recovery and smallest torque.

The disturbance response settles when it stays within ``max(SETTLE_FRACTION * peak departure, SETTLE_FLOOR_DEG)``
of its final value, the mean over the run's last :data:`SETTLE_FINAL_WINDOW`, within whose band it must already
stay (:func:`stability.simulate.signals.settle_time`).
"""

from __future__ import annotations

import numpy as np

from stability.simulate.signals import settle_time as _settle_time

__all__ = ["SETTLE_FRACTION", "SETTLE_FLOOR_DEG", "SETTLE_FINAL_WINDOW", "settle_time", "settled_value",
           "recovery_rule"]

#: Settling: the disturbance's effect on the heading stays within this fraction of its peak ...
SETTLE_FRACTION = 0.05
#: ... or within this many degrees, whichever is larger: the dead band Coulomb pin friction leaves.  With the
#: stick-slip law the casters stop wherever the holding moment falls within the friction limit, and the closed
#: loop's heading then wanders inside a band of a tenth of a degree (power-fwd at 3 m/s after a 40 N s push:
#: 0.05-0.09 deg from 1 s on, gyro noise included); program WCHAIR's kinetic law, which switches the pin
#: moment every step and so averages it away, hid that band.
SETTLE_FLOOR_DEG = 0.1
#: ... of its final value: the mean over this last share of the run, over which it must already stay in that band.
#: After a push the assisted heading does not return to zero but to a new constant heading: the controller holds
#: the running sum of the sampled gyro (its heading estimate), which differs from the heading by what the sum
#: misses of the push's fast transient (the mid-wheel-drive base at 1 m/s in reverse: 0.11 deg after the 400 N
#: push, flat to 1e-9 deg from 5 s on).  A heading that drifts at a constant rate has no final value: over the
#: last fifth of the run it departs from its mean by a tenth of the run's drift, more than 5 % of the peak.
SETTLE_FINAL_WINDOW = 0.2



def settle_time(t: np.ndarray, response_deg: np.ndarray) -> float | None:
    """First time after which the response stays within max(5 % of its peak departure, 0.1 deg) of its final value.

    The rule of every recovery criterion, the short form's and a layout's (:data:`SETTLE_FRACTION`,
    :data:`SETTLE_FLOOR_DEG`, :data:`SETTLE_FINAL_WINDOW`; :func:`stability.simulate.signals.settle_time`): the
    final value is the mean over the last fifth of the run, within whose band the response must already stay.

    Parameters
    ----------
    t : ndarray
        Time (s).
    response_deg : ndarray
        Disturbance response (deg).

    Returns
    -------
    float or None
        Seconds; None if it never settles.
    """
    return _settle_time(t, response_deg, SETTLE_FRACTION, SETTLE_FLOOR_DEG, SETTLE_FINAL_WINDOW)


def settled_value(t: np.ndarray, response_deg: np.ndarray) -> float | None:
    """The final value :func:`settle_time` settles about (deg), None when it does not settle.

    Parameters
    ----------
    t, response_deg : ndarray
        s, deg.

    Returns
    -------
    float or None
    """
    if settle_time(t, response_deg) is None:
        return None
    t = np.asarray(t, dtype=float)
    return float(np.mean(np.asarray(response_deg, dtype=float)[t >= t[-1] - SETTLE_FINAL_WINDOW * (t[-1] - t[0])]))


def recovery_rule(max_heading_deg: float | None = 10.0) -> str:
    """The recovery criterion in words, for the text of both forms (:func:`minimum_torque_limit`).

    Parameters
    ----------
    max_heading_deg : float or None
        deg; None: the settling rule alone (:func:`settle_time`).

    Returns
    -------
    str
    """
    settle = (f"settles to within {100 * SETTLE_FRACTION:g} % of its peak departure (at least {SETTLE_FLOOR_DEG:g} "
              f"deg) about its final value, the mean over the last {100 * SETTLE_FINAL_WINDOW:g} % of the run")
    return settle if max_heading_deg is None else f"the heading stays within {max_heading_deg:g} deg and {settle}"
