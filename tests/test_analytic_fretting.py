"""The first fretting cycle (analytic/fretting.py): Mindlin–Deresiewicz loop, energy per
cycle, slip field and wear, each checked a second way (loop area, Cerruti quadrature,
the path sum of the slip, the worn volume against the dissipation).  The half-space
solver against it: tests/test_halfspace_fretting.py."""


from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from analytic import fretting as fr
from analytic import hertz as hz
from analytic import mindlin as md

E, NU = 210000.0, 0.3
G = E / (2 * (1 + NU))
MU, P, R = 0.3, 100.0, 50.0
H = hz.hertz(P, R, E / (2 * (1 - NU**2)))
G_STAR = fr.tangential_modulus(G, NU, G, NU)
DSTAR = md.gross_slip_shift(MU, P, H.a, G, NU, G, NU)
LAM = fr.poisson_weight(G, NU, G, NU)


def branches(amp: float):
    """The steady loop's unloading and reloading branches, Q(δ) of :func:`fr.md_path`."""
    def down(d):
        return float(fr.md_path([0.0, amp, d], MU, P, DSTAR)[-1])

    def up(d):
        return float(fr.md_path([0.0, amp, -amp, d], MU, P, DSTAR)[-1])

    return down, up


# ---------------------------------------------------------------------- constants


def test_constants_agree_with_mindlin_module():
    assert 3 * MU * P / (16 * G_STAR * H.a) == pytest.approx(DSTAR, rel=1e-14)
    assert G_STAR == pytest.approx(G / (2 * (2 - NU)), rel=1e-14)
    assert LAM == pytest.approx(NU / (2 - NU), rel=1e-14)
    ref = fr.MindlinDeresiewicz.from_approach(0.008, R, MU, E, NU, E, NU)
    E_star = E / (2 * (1 - NU**2))
    assert ref.delta_star == pytest.approx(md.gross_slip_shift_from_approach(
        0.008, MU, E_star, G, NU, G, NU), rel=1e-13)
    assert ref.a == pytest.approx(math.sqrt(R * 0.008), rel=1e-14)
    ref = fr.MindlinDeresiewicz.from_load(P, R, MU, E, NU, E, NU)
    assert (ref.a, ref.p0, ref.delta_star) == pytest.approx((H.a, H.p0, DSTAR), rel=1e-14)
    # the stick radius at an amplitude is Cattaneo's at the load amplitude
    for f in (0.1, 0.5, 0.9):
        Qa = fr.load_amplitude(f * DSTAR, MU, P, DSTAR)
        assert fr.stick_radius_at(f * DSTAR, H.a, DSTAR) == pytest.approx(
            md.stick_radius(H.a, Qa, MU, P), rel=1e-12)
    assert fr.stick_radius_at(1.5 * DSTAR, H.a, DSTAR) == 0.0


def test_coupled_pairs_are_refused():
    # steel on aluminium: K != 0 (formulation Eq. 6), no closed form
    with pytest.raises(ValueError, match="K = 0"):
        fr.MindlinDeresiewicz.from_load(P, R, MU, E, NU, 70000.0, 0.33)
    fr.check_uncoupled(E, NU, E, NU)
    # dissimilar but uncoupled: (1-2ν)/G equal (ν = 0.5 would be the other way; here
    # E_b chosen to match) -> accepted, with δ* of both bodies
    nu_b = 0.25
    E_b = E * (1 - 2 * nu_b) * (1 + nu_b) / ((1 - 2 * NU) * (1 + NU))
    ref = fr.MindlinDeresiewicz.from_load(P, R, MU, E, NU, E_b, nu_b)
    G_b = E_b / (2 * (1 + nu_b))
    assert ref.delta_star == pytest.approx(
        md.gross_slip_shift(MU, P, ref.a, G, NU, G_b, nu_b), rel=1e-13)


# ---------------------------------------------------------------------- the loop


@pytest.mark.parametrize("f", [0.01, 0.2, 0.5, 0.9, 1.0, 1.5, 3.0])
def test_energy_closed_form_is_the_loop_area(f):
    """ΔW (Johnson eq. 7.58, with the plateaus beyond δ*) = ∮ Q dδ of the implemented
    loop, integrated by adaptive quadrature to 1e-8."""
    amp = f * DSTAR
    down, up = branches(amp)
    kinks = [amp - 2 * DSTAR, -amp + 2 * DSTAR] if f > 1 else None
    area = quad(lambda d: up(d) - down(d), -amp, amp, points=kinks, epsabs=0,
                epsrel=1e-12, limit=200)[0]
    assert area == pytest.approx(fr.cycle_energy(amp, MU, P, DSTAR), rel=1e-8)
    # the Johnson form with G* is the δ* form of analytic.mindlin
    Qa = fr.load_amplitude(amp, MU, P, DSTAR)
    if f <= 1:
        assert fr.energy_johnson(Qa, MU, P, H.a, G_STAR) == pytest.approx(
            md.dissipated_energy(Qa, MU, P, DSTAR), rel=1e-13)


def test_energy_limits():
    # Q* -> 0: ΔW = (4/27) μP δ* t³ (1 + 2t/3 + O(t²)) = Q*³/(36 μP G* a) (...)
    for t in (1e-2, 1e-3):
        W = md.dissipated_energy(t * MU * P, MU, P, DSTAR)
        lead = fr.energy_small_amplitude(t * MU * P, MU, P, DSTAR)
        assert lead == pytest.approx((t * MU * P) ** 3 / (36 * MU * P * G_STAR * H.a),
                                     rel=1e-13)
        assert (W / lead - 1) / t == pytest.approx(2 / 3, rel=0.02)
    # Q* = μP: gross-slip onset, (4/5) μP δ*, continuous with the plateau formula
    assert fr.cycle_energy(DSTAR, MU, P, DSTAR) == pytest.approx(0.8 * MU * P * DSTAR,
                                                                 rel=1e-14)
    for eps in (1e-6, -1e-6):
        assert fr.cycle_energy(DSTAR * (1 + eps), MU, P, DSTAR) == pytest.approx(
            0.8 * MU * P * DSTAR, rel=1e-5)
    # slope dΔW/dδ_A = 4μP beyond δ*: every extra slide dissipates μP per unit length
    assert (fr.cycle_energy(2 * DSTAR, MU, P, DSTAR) - fr.cycle_energy(1.5 * DSTAR, MU, P,
            DSTAR)) == pytest.approx(4 * MU * P * 0.5 * DSTAR, rel=1e-13)


@pytest.mark.parametrize("f", [0.5, 1.5])
def test_loop_closes_and_repeats(f):
    amp = f * DSTAR
    cyc = np.concatenate([np.linspace(amp, -amp, 21)[1:], np.linspace(-amp, amp, 21)[1:]])
    hist = np.concatenate([np.linspace(0, amp, 11), cyc, cyc, cyc])
    Q = fr.md_path(hist, MU, P, DSTAR)
    Qa = fr.load_amplitude(amp, MU, P, DSTAR)
    assert Q[10] == pytest.approx(Qa, rel=1e-14)
    n = len(cyc)
    for k in range(3):
        assert Q[10 + (k + 1) * n] == pytest.approx(Qa, rel=1e-14)  # closes at +A
    np.testing.assert_allclose(Q[11 + n:11 + 2 * n], Q[11:11 + n], rtol=0, atol=1e-14 * Qa)
    # the steady loop of md_loop, and the partial-slip loop of analytic.mindlin
    d, q = fr.md_loop(amp, MU, P, DSTAR, n=21)
    np.testing.assert_allclose(q, np.concatenate([[Qa], Q[11:11 + n]]), rtol=1e-14)
    if f < 1:
        d2, q2 = md.loop_partial_slip(amp, MU, P, DSTAR, n=21)
        np.testing.assert_allclose(d, d2, rtol=1e-14)
        np.testing.assert_allclose(q, q2, rtol=1e-13, atol=1e-13 * Qa)
    else:
        # gross slip: each half ends on the plateau ∓μP over its last 2(δ_A - δ*)
        half = len(d) // 2
        down_plateau = d[:half + 1] <= amp - 2 * DSTAR
        up_plateau = d[half:] >= -amp + 2 * DSTAR
        np.testing.assert_allclose(q[:half + 1][down_plateau], -MU * P, rtol=1e-13)
        np.testing.assert_allclose(q[half:][up_plateau], MU * P, rtol=1e-13)
        assert np.all(np.abs(q[1:half + 1][~down_plateau[1:]]) < MU * P)  # the transition


@pytest.mark.parametrize("f", [0.3, 0.8, 1.5])
def test_masing_symmetry(f):
    """Unloading Q_A - 2F((δ_A - δ)/2), reloading its point reflection (Johnson §7.4)."""
    amp = f * DSTAR
    down, up = branches(amp)
    Qa = fr.load_amplitude(amp, MU, P, DSTAR)
    for d in np.linspace(-amp, amp, 13):
        assert up(d) == pytest.approx(-down(-d), rel=1e-13, abs=1e-13 * MU * P)
        assert down(d) == pytest.approx(
            max(Qa - 2 * md.load_from_shift((amp - d) / 2, MU, P, DSTAR), -MU * P),
            rel=1e-13, abs=1e-13 * MU * P)
    # initial slope after a reversal: the virgin stiffness (3/2) μP / δ* (the stick
    # zone spans the contact again)
    eps = 1e-9 * DSTAR
    assert (Qa - down(amp - eps)) / eps == pytest.approx(1.5 * MU * P / DSTAR, rel=1e-5)


def test_masing_memory():
    """An inner loop, once closed, is forgotten; past -δ_1 the virgin curve continues."""
    A = 0.7 * DSTAR
    with_inner = fr.md_path([0, A, 0.1 * A, 0.6 * A, 0.1 * A, -0.5 * A], MU, P, DSTAR)
    without = fr.md_path([0, A, -0.5 * A], MU, P, DSTAR)
    assert with_inner[-1] == pytest.approx(without[-1], rel=1e-13)
    beyond = fr.md_path([0, A, -A, -1.2 * A], MU, P, DSTAR)[-1]
    assert beyond == pytest.approx(-md.load_from_shift(1.2 * A, MU, P, DSTAR), rel=1e-13)
    # the virgin curve itself
    d = np.linspace(0, 1.5 * DSTAR, 7)
    np.testing.assert_allclose(fr.md_path(d, MU, P, DSTAR), fr.virgin_curve(d, MU, P, DSTAR),
                               rtol=1e-15)
    # reloading past +A (after a full loop) rejoins the virgin curve too
    again = fr.md_path([0, A, -A, 1.3 * A], MU, P, DSTAR)[-1]
    assert again == pytest.approx(md.load_from_shift(1.3 * A, MU, P, DSTAR), rel=1e-13)


# ---------------------------------------------------------------------- slip and wear


def cerruti_ux(x0: float, y0: float, rho: float, nu: float) -> float:
    """u_x of one half-space (G = 1) at a surface point outside the circle of radius ρ
    under the traction √(1 - r²/ρ²) along x, by the Cerruti kernel
    [(1-ν)/s + ν ξ²/s³]/(2π) (Johnson §3.2): along each ray from the point the traction
    integrates to π disc/(2ρ), disc = b² + ρ² - r0²."""
    r0, th0 = math.hypot(x0, y0), math.atan2(y0, x0)
    h = math.asin(rho / r0)

    def ray(p):
        b = x0 * math.cos(p) + y0 * math.sin(p)
        disc = b * b + rho * rho - r0 * r0
        return ((1 - nu) + nu * math.cos(p) ** 2) * math.pi * max(disc, 0.0) / (2 * rho)

    return quad(ray, th0 + math.pi - h, th0 + math.pi + h, epsabs=0, epsrel=1e-12)[0] / (
        2 * math.pi)


def test_slip_potentials_are_the_cerruti_displacement():
    rho = 0.7
    for x0, y0 in ((1.0, 0.0), (0.0, 1.0), (0.8, 0.5), (2.0, -1.0)):
        r = math.hypot(x0, y0)
        phi, n = (float(v[0]) for v in fr._potentials(np.array([r]), rho))
        want = ((1 - NU / 2) * phi - (NU / 2) * n * (x0 * x0 - y0 * y0) / r**2) / (2 * math.pi)
        assert cerruti_ux(x0, y0, rho, NU) == pytest.approx(want, rel=1e-10)
    # N = Φ - (2/r²) ∫_0^r Φ r' dr' (inside and outside)
    for r in (0.3, 0.7, 0.9, 3.0):
        phi, n = (float(v[0]) for v in fr._potentials(np.array([r]), rho))
        M = quad(lambda t: t * fr._potentials(np.array([t]), rho)[0][0], 0, r,
                 points=[rho] if r > rho else None, epsabs=0, epsrel=1e-12)[0]
        assert n == pytest.approx(phi - 2 * M / r**2, rel=1e-12)


@pytest.mark.parametrize("c_ratio", [0.0, 0.3, 0.8])
def test_cattaneo_slip(c_ratio):
    a, c = H.a, c_ratio * H.a
    r = np.linspace(0.0, 0.999, 40) * a
    s = fr.cattaneo_slip(r, c, a, DSTAR)
    # = rigid shift δ*(1 - c²/a²) minus the elastic displacement of the two Cattaneo terms
    phi_a = fr._potentials(r, a)[0]
    phi_c = fr._potentials(r, c)[0] if c > 0 else 0.0
    u = 2 * DSTAR / (math.pi**2 * a) * (phi_a - c / a * phi_c)
    want = np.where(r > c, DSTAR * (1 - c * c / a / a) - u, 0.0)
    np.testing.assert_allclose(s, want, rtol=1e-12, atol=1e-15 * DSTAR)
    if c == 0:
        np.testing.assert_allclose(s, DSTAR * r**2 / (2 * a * a), rtol=1e-12)
        np.testing.assert_allclose(fr.slip_anisotropy(r, c, a, DSTAR),
                                   -DSTAR * r**2 / (4 * a * a), rtol=1e-12)
    assert np.all(np.diff(s) >= 0)  # grows outwards from the stick edge
    # the cos 2θ part vanishes at the stick edge too and stays below the mean
    n = fr.slip_anisotropy(r, c, a, DSTAR)
    assert np.all(LAM * np.abs(n) <= s + 1e-15 * DSTAR)


def intended_history(amp: float, steps: int, quarter: int) -> np.ndarray:
    return np.concatenate([amp * np.arange(0, quarter + 1) / quarter,
                           intended_path(amp, steps)])


@pytest.mark.parametrize("f", [0.5, 1.5])
def test_cycle_wear_closed_form_is_the_path_sum(f):
    """The closed-form cycle slip (4 s(r, θ; c), plus the plateaus in gross slip) equals
    Σ |Δg| of the slip field :func:`fr.md_slip_path` over 400 steps of the cycle."""
    amp = f * DSTAR
    x = np.linspace(-1.1, 1.1, 23) * H.a
    X, Y = np.meshgrid(x, 0.37 * x, indexing="ij")
    hist = intended_history(amp, 400, 100)
    for lam in (0.0, LAM):
        g = fr.md_slip_path(hist, X, Y, H.a, DSTAR, lam)[100:]
        path_sum = np.where(np.hypot(X, Y) < H.a, np.abs(np.diff(g, axis=0)).sum(axis=0), 0)
        closed = fr.cycle_slip(X, Y, amp, H.a, DSTAR, lam)
        # (round-off: g is the difference of two O(δ*) terms, summed over 400 steps)
        np.testing.assert_allclose(path_sum, closed, rtol=1e-8, atol=1e-12 * DSTAR)
        stick = np.hypot(X, Y) <= fr.stick_radius_at(amp, H.a, DSTAR)
        if f < 1:  # the stick zone does not slip
            assert stick.any() and np.all(closed[stick] == 0)
            assert np.ptp(g[:, stick], axis=0).max() < 1e-12 * DSTAR
        else:  # the centre slides the plateaus only: 4(δ_A - δ*)
            assert closed[np.hypot(X, Y) == 0] == pytest.approx(4 * (amp - DSTAR), rel=1e-14)


@pytest.mark.parametrize("f", [0.2, 0.5, 0.9, 1.0, 1.5])
def test_wear_volume_is_iw_times_dissipation_over_mu(f):
    """∫ w dA = i_w ΔW / μ: the dissipation is ∫ μ p |ds| dA (quadrature of the depth
    against the closed-form energy: adaptive in r, the trapezoidal rule on 8 angles in θ,
    exact for the cos 2θ term, which integrates to zero)."""
    amp, iw = f * DSTAR, 2.5e-7
    want = fr.cycle_wear_volume(amp, MU, P, DSTAR, iw)
    assert want == pytest.approx(iw * fr.cycle_energy(amp, MU, P, DSTAR) / MU, rel=1e-15)
    c = fr.stick_radius_at(amp, H.a, DSTAR)
    th = 2 * math.pi * np.arange(8) / 8
    for lam in (0.0, LAM):
        def ring(r, lam=lam):
            w = fr.cycle_wear(r * np.cos(th), r * np.sin(th), amp, H.a, H.p0, DSTAR, iw, lam)
            return 2 * math.pi * r * float(w.mean())
        V = quad(ring, c, H.a, epsabs=0, epsrel=1e-12, limit=200)[0]
        assert V == pytest.approx(want, rel=1e-9)


# ---------------------------------------------------------------------- the solver

def intended_path(amplitude: float, steps_per_cycle: int) -> np.ndarray:
    """The documented cycle +A -> -A -> +A in ``steps_per_cycle`` equal steps (excluding
    the start), what ``halfspace.wear.cycle_path`` should return."""
    half = steps_per_cycle // 2
    down = amplitude * (1 - 2 * np.arange(1, half + 1) / half)
    return np.concatenate([down, down[::-1][1:], [amplitude]])
