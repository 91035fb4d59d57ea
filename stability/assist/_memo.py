"""Results computed once per frozen object: the margins of one design asked several times in one command."""

from __future__ import annotations

import pickle
import weakref
from collections.abc import Callable
from typing import Any, TypeVar

__all__ = ["memo"]

_T = TypeVar("_T")
#: Margins already computed, per design (a design is frozen; weakly held): key -> (the pickled design, result).
_MEMO: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def memo(d: Any, key: tuple, compute: Callable[[], _T]) -> _T:
    """``compute()`` of the design ``d``, once per ``key``: the same object again while ``d`` is unchanged.

    A design is frozen; the pickled design is compared too, so an array of it changed in place is computed
    again.  (The margins of one design are asked several times in one command: the rows, the export's
    margin top speed, the quantisation table's ideal loop.)

    Parameters
    ----------
    d : stability.assist.design.Design
        Frozen, weakly referable.
    key : tuple
        What is computed (hashable).
    compute : callable
        Of no arguments.

    Returns
    -------
    object
        ``compute()``'s result.
    """
    try:
        state = pickle.dumps(d)
        per = _MEMO.setdefault(d, {})
    except (TypeError, AttributeError, pickle.PicklingError):     # not picklable or not weakly referable
        return compute()
    hit = per.get(key)
    if hit is not None and hit[0] == state:
        return hit[1]
    out = compute()
    per[key] = (state, out)
    return out
