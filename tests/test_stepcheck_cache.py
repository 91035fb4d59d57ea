"""The step check's cache (:mod:`stability.simulate.stepcheck`): what it returns for a pair it has seen is what an
eigen-decomposition of that pair gives, whatever the other pairs of the call and the order of the calls."""

import numpy as np
import pytest

from stability.chair import preset
from stability.linear import state_matrices
from stability.simulate import stepcheck


def _direct(chair, u, model, casters):
    """The limit and growth rate of one pair from its own eigenvalues (the definition in the module's docstring)."""
    lam = np.linalg.eigvals(state_matrices(chair, np.array([u]), model=model, casters=casters))[0]
    dec = lam[lam.real < 0]
    lim = float(np.min(-2.0 * dec.real / np.abs(dec) ** 2)) if dec.size else np.inf
    return lim, float(lam.real.max())


@pytest.mark.parametrize(("model", "casters"), [("exact", "free"), ("thesis", "free"), ("exact", "locked")])
def test_cached_pairs_equal_their_own_eigenvalues(model, casters):
    """A cold call, a warm call and a call mixing seen and unseen pairs all give each pair's own eigenvalues' limit
    and growth rate, bit for bit (the cache keeps the floats computed, nothing is recomputed differently)."""
    stepcheck._CACHE.clear()
    ej, rev = preset("ej-premier"), preset("revised")
    chairs = [ej, rev, ej, ej]
    speeds = np.array([0.75, 0.5, 1.2, 0.75])
    cold = stepcheck.step_limits_and_growth(chairs, speeds, model, casters)
    warm = stepcheck.step_limits_and_growth(chairs, speeds, model, casters)
    mixed = stepcheck.step_limits_and_growth([rev, ej, rev], np.array([0.5, 0.9, 1.3]), model, casters)
    for got in (cold, warm):
        for i, (c, u) in enumerate(zip(chairs, speeds, strict=True)):
            assert (got[0][i], got[1][i]) == _direct(c, float(u), model, casters)
    for i, (c, u) in enumerate(zip([rev, ej, rev], [0.5, 0.9, 1.3], strict=True)):
        assert (mixed[0][i], mixed[1][i]) == _direct(c, u, model, casters)


def test_cache_is_bounded_and_keyed_by_the_settings(monkeypatch):
    """At most ``CACHE_SIZE`` pairs are kept (the oldest dropped), and the model and caster state are part of the
    key: the same pair under another model gets that model's limit."""
    monkeypatch.setattr(stepcheck, "CACHE_SIZE", 3)
    stepcheck._CACHE.clear()
    ej = preset("ej-premier")
    stepcheck.step_limits_and_growth([ej] * 5, np.linspace(0.5, 1.5, 5), "exact", "free")
    assert len(stepcheck._CACHE) == 3
    exact = stepcheck.stable_steps([ej], np.array([0.3]), "exact", "free")[0]
    locked = stepcheck.stable_steps([ej], np.array([0.3]), "exact", "locked")[0]
    assert exact == _direct(ej, 0.3, "exact", "free")[0]
    assert locked == _direct(ej, 0.3, "exact", "locked")[0]
    assert exact != locked
