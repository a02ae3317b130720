"""Observed order and GCI on manufactured sequences f(h) = f_exact + C h^p."""

from __future__ import annotations

import math

import pytest

from reports.studies.three_level import gci, observed_order, richardson, study


def seq(h, p=2.0, exact=1.0, c=0.3):
    return [exact + c * hh**p for hh in h]


def test_constant_ratio_recovers_the_order_exactly():
    h = (0.01, 0.02, 0.04)
    f1, f2, f3 = seq(h, p=2.0)
    # ε32/ε21 = (0.3·(16−4)e-4)/(0.3·(4−1)e-4) = 4 = 2^2
    assert observed_order(f1, f2, f3, 2.0) == pytest.approx(2.0, rel=1e-12)


def test_nonconstant_ratio_iteration_recovers_the_order():
    h = (0.01, 0.0195, 0.0381)  # like nx = 161, 81, 41 cells: ratios 1.95, 1.954
    f = seq(h, p=1.5)
    assert observed_order(*f, h[1] / h[0], h[2] / h[1]) == pytest.approx(1.5, rel=1e-9)


def test_gci_and_richardson_on_an_exact_power_law():
    h = (0.01, 0.02, 0.04)
    s = study(tuple(seq(h, p=2.0, exact=1.0, c=0.3)), h)
    # exact power law: Richardson removes the error completely
    assert s.f_ext == pytest.approx(1.0, abs=1e-13)
    # GCI21 = 1.25 |(f1 - f2)/f1| / (2^2 - 1), f1 = 1.00003, f2 = 1.00012
    assert s.gci_fine == pytest.approx(1.25 * 9e-5 / 1.00003 / 3, rel=1e-9)
    # in the asymptotic range GCI32 / (r^p GCI21) = f1/f2 (ratio of the normalisations)
    assert s.asymptotic == pytest.approx(1.00003 / 1.00012, rel=1e-9)
    assert s.converging and not s.oscillatory
    # the GCI bounds the true error of f1 (3e-5) with the safety factor
    assert abs(s.f[0] - 1.0) <= s.gci_fine * s.f[0]


def test_study_sorts_grids_and_flags_oscillation_and_divergence():
    h = (0.04, 0.01, 0.02)
    f = (1.0 + 0.3 * 0.04**2, 1.0 + 0.3 * 0.01**2, 1.0 + 0.3 * 0.02**2)
    assert study(f, h).p == pytest.approx(2.0, rel=1e-12)
    osc = study((1.0, 1.1, 0.6), (0.01, 0.02, 0.04))
    assert osc.oscillatory and osc.p == pytest.approx(math.log(5) / math.log(2), rel=1e-12)
    div = study((1.0, 1.2, 1.25), (0.01, 0.02, 0.04))
    assert not div.converging


def test_degenerate_inputs():
    assert math.isnan(observed_order(1.0, 1.0, 1.2, 2.0))  # no change on the finest pair
    assert math.isnan(gci(0.0, 1.0, 2.0, 2.0))
    assert math.isnan(richardson(1.0, 1.1, 2.0, math.nan))
    with pytest.raises(ValueError, match="finest first"):
        observed_order(1.0, 1.1, 1.2, 0.5)
