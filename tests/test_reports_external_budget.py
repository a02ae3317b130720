"""The external results' stated budget self-tested like the case's tolerances (issue 63,
point 4): every key kind of ``[external.NAME].budget`` — ``default``, a metric
(``rel``, ``l2``, ``cells``), a quantity (``p_max``), a quantity and metric
(``p_n_l2``) — set for a row kind while the others are loose, and the row injected at
0.97 and 1.03 times the tolerance it should give: the verdict must flip there.  The
tolerance of a pair ``external:NAME``–B is the stated budget plus B's (the triangle
inequality, :func:`reports.registry.tolerances.default_tolerance`); a lookup that
ignored the key would use ``default`` (0.5 here) and pass both injections.  Lengths
never take ``default``: they are in cells, :data:`external_results.spec.LENGTH_BUDGETS`
unless a ``cells`` or quantity key says otherwise."""

from __future__ import annotations

import copy

import pytest
from test_reports_gate_injection import INJECT, _expected_tolerance, _rows
from test_reports_gate_selftest import reference

from external_results.spec import LENGTH_BUDGETS

NAME = "external:fe"
LOOSE = 0.5
#: (row kind, budget key kind) -> the key, its value
PLANS = {
    (("p_max", "rel"), "default"): ("default", 0.011),
    (("p_max", "rel"), "metric"): ("rel", 0.012),
    (("p_max", "rel"), "quantity"): ("p_max", 0.013),
    (("p_n", "l2"), "default"): ("default", 0.021),
    (("p_n", "l2"), "metric"): ("l2", 0.022),
    (("p_n", "l2"), "quantity"): ("p_n", 0.023),
    (("p_n", "l2"), "quantity and metric"): ("p_n_l2", 0.024),
    (("a_x", "cells"), "metric"): ("cells", 0.4),
    (("a_x", "cells"), "quantity"): ("a_x", 0.6),
}


@pytest.mark.parametrize(("kind", "key_kind"), list(PLANS),
                         ids=[f"{q}.{m}-{k}" for (q, m), k in PLANS])
def test_each_budget_key_moves_the_verdict_at_its_tolerance(kind, key_kind):
    key, value = PLANS[(kind, key_kind)]
    case, inject = INJECT[kind]
    budget = {"default": LOOSE, key: value}
    case = case.with_changes(external={"fe": {"files": "fe.vtu", "budget": budget}})
    pair = f"{NAME}-analytic"
    good = reference(case)
    tol = _expected_tolerance(case, pair, *kind)
    reference_part = _expected_tolerance(case, "analytic-analytic", *kind) / 2
    assert tol == pytest.approx(value + reference_part, rel=1e-12)
    for k in (0.97, 1.03):
        tested = copy.deepcopy(good)
        inject(case, tested, k * tol, pair)
        rows = _rows(case, pair, tested, good)
        row_value, row_tol, status, passed, _ = rows[kind]
        assert status == "gated" and row_tol == pytest.approx(tol, rel=1e-9), (row_tol, tol)
        assert row_value == pytest.approx(k * tol, rel=1e-6)
        assert passed == (k < 1), f"{kind} {key_kind} at k = {k}"


def test_lengths_never_take_the_default():
    """``default`` is a relative error; a length's budget is in cells."""
    kind = ("a_x", "cells")
    case, _ = INJECT[kind]
    case = case.with_changes(external={"fe": {"files": "fe.vtu",
                                              "budget": {"default": LOOSE}}})
    tol = _expected_tolerance(case, f"{NAME}-analytic", *kind)
    reference_part = _expected_tolerance(case, "analytic-analytic", *kind) / 2
    assert tol == pytest.approx(LENGTH_BUDGETS["cells"] + reference_part, rel=1e-12)
