"""The resolution probe's wear spread (halfspace/wear_spread.py): cell weights of a tent
against an independent quadrature, the worn volume kept, and the key's checks."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy import integrate

import analytic
import fem_reference
import halfspace
from cases.loader import load_case
from cases.model import CaseError
from halfspace.wear_spread import spread, weights


def _weight(k: int, r: float, dx: float) -> float:
    """The part of a unit cell average that a tent T_r (unit integral) moves k cells
    away: (1/dx) ∫∫ T_r(k dx + u − v) du dv over a cell's u and v, by a double integral
    (not the module's one-dimensional reduction)."""
    def tent(v: float, u: float) -> float:
        return max(0.0, 1.0 - abs(k * dx + u - v) / r) / r
    value, _ = integrate.dblquad(tent, -dx / 2, dx / 2, -dx / 2, dx / 2, epsabs=1e-12,
                                 epsrel=1e-10)
    return value / dx


@pytest.mark.parametrize("ratio", [0.3, 0.7, 1.0, 1.6, 2.5])
def test_weights_are_the_cell_means_of_the_tent(ratio):
    dx = 0.0645
    r = ratio * dx
    w = weights(r, dx)
    m = (w.size - 1) // 2
    assert w.sum() == pytest.approx(1.0, abs=1e-14)
    assert np.allclose(w, w[::-1], rtol=0, atol=1e-15)
    for k in range(m + 1):
        # the double quadrature of a kinked integrand is good to a few 1e-9
        assert w[m + k] == pytest.approx(_weight(k, r, dx), abs=5e-8), k


def test_weights_limits():
    """No spread is the identity; a tent one cell wide is the cubic B-spline's
    (1/6, 2/3, 1/6); a tent much narrower than a cell moves r / (6 dx) to each side."""
    assert list(weights(0.0, 0.1)) == [1.0]
    assert weights(0.1, 0.1) == pytest.approx([1 / 6, 2 / 3, 1 / 6], abs=1e-12)
    assert weights(1e-4, 0.1)[0] == pytest.approx(1e-4 / 0.6, rel=1e-3)
    with pytest.raises(ValueError, match="wear spread"):
        weights(-0.01, 0.1)


def test_spread_keeps_the_volume_and_acts_per_axis():
    dw = np.zeros((21, 15))
    dw[10, 7] = 1.0
    out = spread(dw, 0.15, 0.1, 0.05)
    assert out.sum() == pytest.approx(1.0, abs=1e-14)
    wx, wy = weights(0.15, 0.1), weights(0.15, 0.05)
    mx, my = (wx.size - 1) // 2, (wy.size - 1) // 2
    block = out[10 - mx:10 + mx + 1, 7 - my:7 + my + 1]
    assert np.allclose(block, np.outer(wx, wy), rtol=0, atol=1e-15)
    assert spread(dw, 0.0, 0.1, 0.05) is dw


def test_a_spread_worn_pin_keeps_archards_volume():
    """In gross sliding the worn volume is Archard's Σ i_w P Δs whatever the spread
    (each increment's volume is kept): the half-space solver's pin with its wear spread
    over two cells against the closed form's volume, to round-off."""
    case = load_case("pin_on_disk", quick=True)[0]
    r = 2.0 * case.grid.dx
    spread_case = case.with_changes(solver=dataclasses.replace(case.solver, wear_spread=r))
    ic = halfspace.solve(spread_case).steps[-1].scalars
    plain = halfspace.solve(case).steps[-1].scalars
    exact = analytic.solve(case).steps[-1].scalars
    assert ic["wear_volume"] == pytest.approx(exact["wear_volume"], rel=1e-9)
    assert ic["w_max"] < plain["w_max"]  # the same volume, spread out


def test_the_key_is_checked_and_declined_by_the_other_solvers():
    case = load_case("fretting_orthotropic", quick=True)[0]
    with pytest.raises(CaseError, match=r"solver\.wear_spread"):
        load_case("fretting_orthotropic", quick=True,
                  overrides={"solver.wear_spread": -0.01})
    spread_case = case.with_changes(solver=dataclasses.replace(case.solver,
                                                               wear_spread=0.04))
    assert "wear_spread" in fem_reference.supports(spread_case)
    assert fem_reference.supports(case) is None
    static = load_case("hertz", quick=True)[0]
    assert analytic.supports(static.with_changes(
        solver=dataclasses.replace(static.solver, wear_spread=0.04))) is None  # no wear
