"""The shared test helpers themselves (tests/vv_testing.py, tests/conftest.py): the
convergence assertion on manufactured sequences, and the case fixtures."""

from __future__ import annotations

import math

import pytest
from vv_testing import assert_converges, hertz_solution, load_bundled, measure

from cases.model import Load

H = (0.4, 0.2, 0.1, 0.05)


def test_power_law_errors_give_their_order():
    """e = C h² on four grids: every pairwise order of the errors' ratios, and the
    three-grid observed_order of the errors, is 2 to 1e-9; the Richardson limit of the
    errors is 0."""
    conv = assert_converges(H, [0.7 * h**2 for h in H], min_order=1.9, finest=2e-3,
                            what="e = 0.7 h^2")
    assert len(conv.orders) == 3
    assert all(p == pytest.approx(2.0, abs=1e-9) for p in conv.orders)
    assert conv.three_grid_order == pytest.approx(2.0, abs=1e-9)
    assert conv.limit == pytest.approx(0.0, abs=1e-15)
    assert conv.finest == pytest.approx(0.7 * 0.05**2, rel=1e-15)


def test_grid_order_and_signs_do_not_matter():
    """h given fine to coarse, errors of alternating sign, non-constant ratios."""
    h = (0.01, 0.0195, 0.0381)
    errors = [(-1) ** k * 3.0 * hh**1.5 for k, hh in enumerate(h)]
    conv = assert_converges(h, errors, min_order=1.4)
    assert conv.h == (0.0381, 0.0195, 0.01)
    assert all(p == pytest.approx(1.5, abs=1e-9) for p in conv.orders)


@pytest.mark.parametrize("errors", [
    [0.1, 0.2, 0.4],  # grows under refinement (observed_order's abs would say order 1)
    [0.1, 0.1, 0.1],  # stalls
    [0.1, 0.05, 0.06],  # decreases, then grows
])
def test_non_converging_errors_fail(errors):
    with pytest.raises(AssertionError, match="does not decrease"):
        assert_converges((0.4, 0.2, 0.1), errors, min_order=0.0)


def test_an_error_floor_fails_the_order_the_three_grid_fit_would_pass():
    """e = 0.05 + h²: the errors' differences shrink at order 2 (what observed_order of
    the errors measures), but the errors stall at 0.05; the errors' ratios say so."""
    errors = [0.05 + h**2 for h in H]
    conv = measure(H, errors)
    assert conv.three_grid_order == pytest.approx(2.0, abs=1e-9)
    assert conv.limit == pytest.approx(0.05, rel=1e-9)
    with pytest.raises(AssertionError, match="not > 1"):
        assert_converges(H, errors, min_order=1.0)


def test_failure_message_states_orders_errors_and_finest():
    with pytest.raises(AssertionError) as info:
        assert_converges((0.5, 0.25, 0.125), [0.04, 0.02, 0.0101], min_order=1.0,
                         finest=0.01, what="p_max")
    msg = str(info.value)
    assert "order(s) 1, 0.9856 not > 1" in msg  # the first order is 1.0: not > 1
    assert "finest |error| 0.0101 not < 0.01" in msg
    assert ("p_max (error per h, coarse to fine): h=0.5: 0.04, h=0.25: 0.02, h=0.125: 0.0101"
            in msg)
    assert "orders (errors' ratios, per pair) 1, 0.9856; finest |error| 0.0101" in msg


def test_bounds_are_strict():
    with pytest.raises(AssertionError, match="not > 1"):
        assert_converges((0.25, 0.125), [0.2, 0.1], min_order=1.0)  # order exactly 1
    with pytest.raises(AssertionError, match="not < 0.1"):
        assert_converges((0.25, 0.125), [0.4, 0.1], min_order=1.0, finest=0.1)


def test_values_use_observed_order_of_the_three_finest():
    """f = 1 + 0.3 h²: observed_order of the values is 2; a diverging sequence of
    values, whose observed order is positive too, fails on its growing differences."""
    f = [1.0 + 0.3 * h**2 for h in H]
    conv = assert_converges(H, values=f, min_order=1.9, max_change=3e-3)
    assert conv.three_grid_order == pytest.approx(2.0, abs=1e-9)
    assert conv.limit == pytest.approx(1.0, abs=1e-13)
    assert conv.change == pytest.approx(abs(f[-2] / f[-1] - 1), rel=1e-15)
    with pytest.raises(AssertionError, match="differences do not shrink"):
        assert_converges(H, values=[1.0 + 0.3 / h for h in H], min_order=0.5)


def test_values_change_of_two_grids():
    """The two-grid form: |f2/f1 - 1| of the two finest (f1 finest) below max_change."""
    assert_converges((4.0, 2.0), values=[1.004, 1.0], max_change=0.005)
    with pytest.raises(AssertionError, match="change"):
        assert_converges((4.0, 2.0), values=[1.006, 1.0], max_change=0.005)


def test_misuse_is_a_value_error():
    with pytest.raises(ValueError):
        assert_converges((0.2, 0.1), [0.2, 0.1])  # no min_order
    with pytest.raises(ValueError):
        assert_converges((0.2, 0.1), [0.2, 0.1], min_order=-1.0)
    with pytest.raises(ValueError):
        assert_converges((0.2, 0.2), [0.2, 0.1], min_order=1.0)
    with pytest.raises(ValueError):
        assert_converges((0.2, 0.1), values=[1.0, 1.1], min_order=1.0)  # needs 3 grids
    with pytest.raises(ValueError):
        assert_converges((0.2, 0.1), [0.2, 0.1], values=[1.0, 1.1], min_order=1.0)


def test_case_fixtures(bundled_case, hertz_case, hertz_scales):
    assert hertz_case == bundled_case("hertz")
    assert hertz_scales == hertz_case.hertz_scales
    quick = bundled_case("hertz", quick=True, overrides={"grid.nx": 21})
    assert quick.grid.nx == 21
    with pytest.raises(ValueError, match="not a bundled case"):
        bundled_case("hertz.toml")


@pytest.mark.parametrize("control", ["load", "approach"])
def test_hertz_solution_is_the_case_scales(control):
    """The two shared sources of the Hertz scales agree, under both load controls."""
    case = load_bundled("hertz")
    if control == "approach":
        delta = hertz_solution(case).delta
        case = case.with_changes(load=Load(approach=delta))
    hz = hertz_solution(case)
    a0, p0 = case.hertz_scales
    assert hz.a == pytest.approx(a0, rel=1e-12) and hz.p0 == pytest.approx(p0, rel=1e-12)
    assert hz.delta == pytest.approx(a0**2 / case.R, rel=1e-12)
    assert hz.P == pytest.approx(10.2, rel=1e-12)
    assert math.isclose(a0, 0.1491, abs_tol=5e-5)
