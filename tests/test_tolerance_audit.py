"""No float tolerance in tests/ without its error model stated next to it, beyond the shrinking allow-list (issue 34).

``tests/tolerance_audit.py`` finds the tolerances (parsing the files; nothing is imported) and decides whether a
comment beside each states its error model; ``tests/tolerances_pending.py`` lists those not yet done.
"""

from __future__ import annotations

from collections import Counter

import pytest
import tolerance_audit as audit
from tolerances_pending import PENDING, PENDING_LIMIT


@pytest.fixture(scope="module")
def found() -> list[audit.Tolerance]:
    return audit.scan()


def _pending() -> Counter:
    return Counter((path, function, snippet) for path, entries in PENDING.items() for function, snippet in entries)


def test_every_tolerance_states_its_error_model_or_is_pending(found):
    missing = Counter(t.key for t in found if not t.stated)
    new = missing - _pending()
    where = {t.key: t for t in found}
    shown = "\n".join(f"{where[k].path}:{where[k].line}: {k[1]}: {k[2]}" for k in list(new)[:30])
    assert not new, (f"{sum(new.values())} tolerances without an error model: state it in a comment beside each "
                     f"(one of tolerance_audit.STATED_FORMS: derive the model, measure the error, allow ~100x), or "
                     f"name a tolerance of tests/numerics.py:\n{shown}")


def test_pending_entries_are_still_unstated_tolerances(found):
    missing = Counter(t.key for t in found if not t.stated)
    stale = _pending() - missing
    shown = "\n".join(f"{p}: {f}: {s}" for p, f, s in list(stale)[:30])
    assert not stale, (f"{sum(stale.values())} entries of tests/tolerances_pending.py are no longer unstated "
                       f"tolerances (stated now, or the comparison changed): remove them and lower PENDING_LIMIT:\n"
                       f"{shown}")


def test_pending_entries_only_shrink():
    pending = sum(_pending().values())
    assert pending <= PENDING_LIMIT, f"{pending} pending tolerances > {PENDING_LIMIT}: unstated tolerances were added"


@pytest.mark.parametrize(("src", "expected"), [
    ("assert x == pytest.approx(y)", [False]),                                 # approx's default rel=1e-6
    ("assert x == pytest.approx(y, rel=1e-9)  # rounding: 3 ulp", [True]),
    ("# error model: bisection bracket 1e-3\nassert x == approx(y, rel=1e-3)", [True]),
    ("# the same chair\nassert x == approx(y, rel=1e-3)", [False]),
    ("# rounding\nassert a == approx(b, rel=1e-9)\nassert c == approx(d, rel=1e-9)", [True, True]),
    ("# rounding\nassert a == approx(b, rel=1e-9)\n\nassert c == approx(d, rel=1e-9)", [True, False]),
    ("a = 1  # rounding\nassert x == approx(y, rel=1e-3)", [False]),           # another statement's comment
    ("np.testing.assert_allclose(a, b, rtol=0)", []),                          # exact: atol defaults to 0
    ("np.testing.assert_allclose(a, b)", [False]),                             # rtol defaults to 1e-7
    ("np.testing.assert_allclose(a, b, 0, 0)", []),
    ("assert np.allclose(a, b, 0, 0)", []),
    ("assert np.allclose(a, b, rtol=0)", [False]),                             # atol defaults to 1e-8
    ("assert math.isclose(a, b, rel_tol=1e-6)", [False]),
    ("assert abs(a - b) < 1e-9", [False]),
    ("assert abs(math.log(a / b)) < 0.01", [False]),
    ("assert abs(residual) < 1e-12", [False]),
    ("assert abs(heading) < 5.0", []),                                         # a physical threshold
    ("assert abs(a - b) == 0", []),
    ("assert 1e-9 > abs(a - b)", [False]),
    ("TOL = 1e-9  # error model: 10 roundings\nassert x == approx(y, rel=TOL)", [True]),
    ("from numerics import EPS\nassert x == approx(y, rel=10 * EPS)", [True]),
    ("RTOL = 1e-6\nassert x == approx(y, rel=RTOL)", [False]),
    ("assert x == approx(\n    y,\n    rel=1e-9,  # ulp count: 4\n)", [True]),
    ("solve_ivp(f, (0, 1), y0, rtol=1e-9)", []),                               # a setting, not a comparison
])
def test_scanner_rules(src, expected):
    assert [t.stated for t in audit.scan_source(src)] == expected


def test_stated_forms_are_words_not_fragments():
    assert audit.states_model("# error model: 4 ulp")
    assert audit.states_model("# n eps cond(M)")
    assert not audit.states_model("# the steps of the sweep")                 # 'eps' inside a word
    assert not audit.states_model("# exactly these paragraphs")                # only the word itself
