"""FEM reference, pin-on-disk sliding wear (case 4) against Archard and Argatov.

References: Archard, worn volume W = i_w P s (exact for the discrete law: every step
removes i_w Δs ∫ p_n dA = i_w P Δs); Argatov (2011), worn-pin radius
a = (a0⁴ + 4 i_w P s R/π)^(1/4) and the depth √(a⁴ − a0⁴)/(2R) of the flattened cap of
that radius — asymptotic (large s) results: the elastic part of the profile makes the
early worn shape rounder, so the FE depth approaches them from below as s grows.

Fast tier: the quick pin-on-disk (80 mm in 2 mm steps) on the coarse quarter block
(h = a0/4 at the initial contact, L = H = 10 a0).
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from cases.loader import load_case
from cases.model import FemSettings
from fem_reference import solve

pytestmark = pytest.mark.fem


@functools.cache
def pin_on_disk(mu: float = 0.0, h: float = 0.25, block: float = 10.0):
    case = load_case("pin_on_disk", quick=True, overrides={"friction.mu": mu})[0]
    case = case.with_changes(fem=FemSettings(block=block, depth=block, h=h))
    return case, solve(case, vtu=False)


def argatov(case, s):
    a0 = case.hertz_a0
    iw = case.a.i1
    a = (a0**4 + 4 * iw * case.load.P * s * case.R / math.pi) ** 0.25
    return a, math.sqrt(a**4 - a0**4) / (2 * case.R)


def test_pin_on_disk_against_archard_and_argatov():
    case, res = pin_on_disk()
    sw = case.sliding_wear
    iw, P = case.a.i1, case.load.P
    steps = res.steps
    numbers = [int(st.scalars["step"]) for st in steps]
    assert numbers == sorted({0, *(round(s / sw.step) for s in sw.output_s),
                              round(sw.distance / sw.step)})
    h0 = case.fem.h * case.hertz_a0
    rel_depth = []
    for st in steps:
        sc = st.scalars
        s = sc["s"]
        assert sc["P"] == pytest.approx(P, rel=1e-9)
        assert sc["wear_volume"] == pytest.approx(iw * P * s, rel=1e-6, abs=1e-18)
        assert np.all(st.surface["wear_b"] == 0)  # the disk does not wear
        a, w = argatov(case, s)
        # the growing contact is meshed with about as many elements per radius as the
        # initial one: one element size there is h0 a/a0
        assert abs(sc["a_x"] - a) < h0 * a / case.hertz_a0
        if s > 0:
            rel_depth.append(sc["w_max"] / w - 1)
            assert st.surface["wear_a"].max() <= sc["w_max"] * (1 + 1e-12)
    # the FE depth approaches Argatov's asymptote from below
    assert all(r < 0 for r in rel_depth)
    assert all(abs(r2) < abs(r1) for r1, r2 in zip(rel_depth, rel_depth[1:], strict=False))
    assert abs(rel_depth[-1]) < 0.05
    # the pressure flattens: p_max falls towards P/(π a²)
    pmax = [st.scalars["p_max"] for st in steps]
    assert all(b < a for a, b in zip(pmax, pmax[1:], strict=False))
    print("\npin-on-disk: " + "; ".join(
        f"s={sc['s']:g} a_x/a_Arg={sc['a_x'] / argatov(case, sc['s'])[0]:.4f}"
        for sc in (st.scalars for st in steps))
        + "; w_max/Argatov-1: " + ", ".join(f"{r:+.3f}" for r in rel_depth))


def test_wear_profile_is_axisymmetric_and_follows_the_pressure():
    case, res = pin_on_disk()
    st = res.steps[-1]
    w = st.surface["wear_a"]
    assert np.allclose(w, w[::-1, :], atol=1e-9 * w.max())
    assert np.allclose(w, w.T, atol=0.05 * w.max())  # quarter model: x and y alike
    g = case.grid
    i0, j0 = np.argmin(np.abs(g.x)), np.argmin(np.abs(g.y))
    assert w[i0, j0] == pytest.approx(w.max())  # deepest at the centre
    # the worn gap: inside the contact the gap closes on the worn profile
    closed = st.surface["state"] != 0
    d0 = case.hertz_a0**2 / case.R
    assert np.abs(st.surface["gap"][closed]).max() < 0.02 * d0


@pytest.mark.full
def test_pin_on_disk_with_friction_wears_alike():
    """Identical materials: friction does not change the normal problem, so μ = 0.5 wears
    the pin exactly as μ = 0 (the half block against the quarter), with Q = −μP."""
    c0, r0 = pin_on_disk(0.0)
    c5, r5 = pin_on_disk(0.5)
    assert r5.meta["model"] == "half"
    for s0, s5 in zip(r0.steps, r5.steps, strict=True):
        assert s5.scalars["Qx"] == pytest.approx(-0.5 * c5.load.P, rel=1e-9)
        assert s5.scalars["wear_volume"] == pytest.approx(s0.scalars["wear_volume"], rel=1e-6)
        assert s5.scalars["a_x"] == pytest.approx(s0.scalars["a_x"], rel=0.03)
