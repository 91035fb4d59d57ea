"""Cases that repeat one check on several presets, layouts, speeds or formats: one runs by default, the rest slow.

A parametrised test that checks the same thing (the same invariant, the same comparison with an independent
answer) on several presets keeps the case that catches most in the default suite (the mid-wheel-drive layout,
whose casters are ahead of and behind the drive axle; the E&J Premier, the thesis's chair) and runs the others
in CI's slow step (``-m slow``).  A case that is the only test of a behaviour (another code path, another
direction's branch, the issue's own input) is not a repeat and stays default (docs/testing.md, "Running the
suite").
"""
from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import pytest


def one_default(cases: Iterable[Any], *keep: Any) -> list[Any]:
    """``cases`` for ``pytest.mark.parametrize``: the ones in ``keep`` as they are, every other marked slow.

    A tuple case is the values of several arguments (``parametrize("name, speed", ...)``); the ids are pytest's
    own either way, so a case's id does not change with its marker.  Every case of ``keep`` must be one of
    ``cases`` (a renamed preset must not leave the default suite without its representative).
    """
    cases = list(cases)
    missing = [k for k in keep if k not in cases]
    if missing or not keep:
        raise ValueError(f"one_default: representative {missing or keep!r} is not among the cases {cases!r}")
    return [c if c in keep else pytest.param(*(c if isinstance(c, tuple) else (c,)), marks=pytest.mark.slow)
            for c in cases]
