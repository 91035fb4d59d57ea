"""The lanes kernel's tire-table lookup (selects over a lane's table, no gather) against the tire law's indexing.

:func:`stability.simulate.lanes_physics.l_segment_force` picks segment ``min(floor(s), 7)``'s coefficients by
selects from the table read as a tuple (:func:`~stability.simulate.lanes_physics.l_table`) and evaluates the law's
cubic on them: the same operations on the same operands as :func:`stability.tires.law.segment_force`, so the two
agree bit for bit (no tolerance: a difference would be a wrong segment or a wrong row), over slips in every
segment, on the segment boundaries, beyond the table (8 deg and above: segment 7 extended), NaN, and loads at,
below and above zero.  The law's own values are checked against the thesis's tables in tests/test_tires.py.
"""

import math

import numpy as np
from numba import njit

from stability import tires
from stability.simulate.lanes_physics import l_segment_force, l_table
from stability.tires import law

ROWS = 48          # a table's rows in the lanes block: row 8 r + q is coefficient r of segment q


@njit(cache=False)
def _lane_forces(table, s, fz):
    """The lane lookup, lane ``j`` reading its table from column ``j`` of a block-like array."""
    W = np.empty((ROWS, s.size))
    for j in range(s.size):
        for r in range(ROWS):
            W[r, j] = table[r]
    out = np.empty(s.size)
    for j in range(s.size):
        out[j] = l_segment_force(l_table(W, 0, j), s[j], fz[j], 0)
    return out


def test_lane_lookup_is_the_law_bit_for_bit():
    seg = np.array(tires.get("SS").segment_arrays(), dtype=float)          # (6, 8): rows a0, b0, c0, da, db, dc
    slips = np.concatenate([np.linspace(0.0, 11.0, 221), np.arange(9.0), [7.999999999, 8.0, 30.0, math.nan]])
    loads = np.array([-10.0, 0.0, 1.0, 150.0, 449.9, 600.0, math.nan])
    s, fz = (a.ravel() for a in np.meshgrid(slips, loads))
    got = _lane_forces(seg.ravel(), s, fz)
    want = np.array([law.segment_force(seg, a, b) for a, b in zip(s, fz, strict=True)])
    assert np.array_equal(got, want, equal_nan=True)
    assert np.isnan(got[np.isnan(s) & (fz > 0.0)]).all()    # NaN slip gives NaN force, as the law says
