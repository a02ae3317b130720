"""The first fretting cycle (analytic/fretting.py): Mindlin–Deresiewicz loop, energy per
cycle, slip field and wear; and the half-space solver measured against it.

Solver runs: case 6 (``fretting_orthotropic``, quick table) made isotropic (μ1 = μ2 =
0.3, β = 0), approach held at 0.008 mm (a = 0.632 mm on the 2 mm = 3.16 a domain),
one cycle, wear coefficients 1e-9 MPa⁻¹ per body (the worn depth is ~1e-10 of the
approach: the pressure stays Hertzian).  Amplitudes 0.5 δ* (partial slip) and 1.5 δ*
(gross slip).

Measured (ν = 0.3, the intended cycle +A -> -A -> +A, 20 steps per cycle; 31² / 61² /
81² / 121²; partial | gross):

- loop, max |Q_ic - Q_MD| / μP: 0.22 / 0.034 / 0.036 / 0.033 % | 0.13 / 0.073 / 0.076 /
  0.073 %.  The floor is Cattaneo–Mindlin's neglect of the y-slip for ν != 0: with
  ν = 0 (where it is exact) 0.19 / 0.021 / 0.011 % | 0.11 / 0.019 / 0.012 %;
- energy, the solver's trapezoid over the loop vs the same rule on the MD loop:
  -2.5 / -0.01 / -0.16 / -0.24 % | +0.005 / +0.05 / +0.05 / +0.04 %; against the closed
  form -3.5 / -1.0 / -1.2 / -1.2 % | -0.86 / -0.81 / -0.81 / -0.82 %: at 20 steps the
  trapezoidal rule itself is -1.0 | -0.86 % (-6.3 | -5.6 % at the quick 8 steps);
  the dissipation ∫ μ p |Δg| dA of the solver's steps (μ × worn volume / i_w) vs the
  closed form: -2.5 / -0.001 / -0.16 / -0.24 % | -0.03 / +0.05 / +0.05 / +0.04 %;
- first-cycle wear depth, max error / max w over the cells at least one cell inside
  the contact edge (the edge cells compare a cell value with a point value of the √
  pressure edge, as the max norms of cases/README.md): 2.4 / 2.0 / 1.5 / 1.6 % | 1.25 /
  1.28 / 0.96 / 0.91 %; L2 over all cells 6.2 / 4.5 / 3.5 / 2.6 % | 1.7 / 1.2 / 0.91 /
  0.67 %.  Against the axisymmetric mean slip (λ = 0) the interior error is 11–16 % |
  3.1–3.6 %: the ν ξ²/s³ part of the Cerruti kernel (the cos 2θ term) is needed.

This comparison found that ``halfspace.wear.fretting_path`` imposed +A -> -A, then
+0.8A -> -0.8A and a jump to +A (20 steps): one "cycle" dissipated 1.49 | 1.57 times the
cycle's energy (partial | gross slip).  Fixed; :func:`test_bundled_fretting_path_is_the_
documented_cycle` holds it to :func:`intended_path`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pytest
from scipy.integrate import quad

import halfspace
import halfspace.wear as hw
from analytic import fretting as fr
from analytic import hertz as hz
from analytic import mindlin as md
from cases.loader import load_case

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
    ref = fr.Fretting.from_approach(0.008, R, MU, E, NU, E, NU)
    E_star = E / (2 * (1 - NU**2))
    assert ref.delta_star == pytest.approx(md.gross_slip_shift_from_approach(
        0.008, MU, E_star, G, NU, G, NU), rel=1e-13)
    assert ref.a == pytest.approx(math.sqrt(R * 0.008), rel=1e-14)
    ref = fr.Fretting.from_load(P, R, MU, E, NU, E, NU)
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
        fr.Fretting.from_load(P, R, MU, E, NU, 70000.0, 0.33)
    fr.check_uncoupled(E, NU, E, NU)
    # dissimilar but uncoupled: (1-2ν)/G equal (ν = 0.5 would be the other way; here
    # E_b chosen to match) -> accepted, with δ* of both bodies
    nu_b = 0.25
    E_b = E * (1 - 2 * nu_b) * (1 + nu_b) / ((1 - 2 * NU) * (1 + NU))
    ref = fr.Fretting.from_load(P, R, MU, E, NU, E_b, nu_b)
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

IC_MU = 0.3
IC_IW = 1e-9  # per body, MPa⁻¹
REGIMES = {"partial": 0.5, "gross": 1.5}


def intended_path(amplitude: float, steps_per_cycle: int) -> np.ndarray:
    """The documented cycle +A -> -A -> +A in ``steps_per_cycle`` equal steps (excluding
    the start), what ``halfspace.wear.fretting_path`` should return."""
    half = steps_per_cycle // 2
    down = amplitude * (1 - 2 * np.arange(1, half + 1) / half)
    return np.concatenate([down, down[::-1][1:], [amplitude]])


@dataclass(frozen=True)
class Measured:
    """Errors of one IC fretting run against the Mindlin–Deresiewicz solution."""

    loop: float  # max |Q_ic - Q_MD| / μP over the cycle's steps
    energy_table: float  # the cycles table's energy / closed-form ΔW - 1
    energy_same_rule: float  # same / the trapezoid of the MD loop on the same points - 1
    dissipation: float  # μ (worn volume) / i_w  vs  the exact ∮Q dδ of the imposed path
    wear_interior: float  # max |w_ic - w| / max w, cells >= 1 cell inside the edge
    wear_l2: float  # ||w_ic - w|| / ||w|| over all cells
    wear_interior_axisym: float  # the same against the λ = 0 (axisymmetric) slip
    gross_flag: float
    P_rel: float  # P_ic / P_Hertz - 1 under the held approach


@functools.cache
def ic_run(n: int, regime: str, steps: int) -> Measured:
    ref = fr.Fretting.from_approach(0.008, 50.0, IC_MU, E, NU, E, NU)
    amp = REGIMES[regime] * ref.delta_star
    over = {"grid.nx": n, "grid.ny": n, "friction.mu1": IC_MU, "friction.mu2": IC_MU,
            "friction.beta": 0.0, "fretting.amplitude": amp, "fretting.cycles": 1,
            "fretting.jump": 1.0, "fretting.steps_per_cycle": steps,
            "fretting.output_cycles": [1], "stress.nz": 2,
            **{f"materials.{b}.i{k}": IC_IW for b in "ab" for k in (1, 2)}}
    case = load_case("fretting_orthotropic", quick=True, overrides=over)[0]
    assert (case.load.approach, case.R, case.a.E, case.a.nu) == (0.008, 50.0, E, NU)
    assert case.grid.Lx == pytest.approx(3.16 * ref.a, rel=1e-3)
    run = halfspace.solve(case)
    loops, cycles, step = run.tables["loops"], run.tables["cycles"], run.steps[-1]
    q = max(steps // 4, 1)
    hist = np.concatenate([amp * np.arange(0, q + 1) / q, loops["displacement"]])
    Q_md = fr.md_path(hist, IC_MU, ref.P, ref.delta_star)
    W_cf = fr.cycle_energy(amp, IC_MU, ref.P, ref.delta_star)
    W_path = abs(fr.md_work(hist, IC_MU, ref.P, ref.delta_star, start=q, refine=200))
    X, Y = np.meshgrid(step.x, step.y, indexing="ij")
    Rr = np.hypot(X, Y)
    w_ic = step.surface["wear_a"] + step.surface["wear_b"]
    dA = case.grid.dx * case.grid.dy
    interior = Rr < ref.a - case.grid.dx

    def wear(lam):
        g = fr.md_slip_path(hist, X, Y, ref.a, ref.delta_star, lam)[q:]
        return 2 * IC_IW * hz.pressure(Rr, ref.a, ref.p0) * np.abs(np.diff(g, axis=0)).sum(0)

    w, w0 = wear(ref.lam), wear(0.0)
    # on the cycle, the path sum is the closed form
    np.testing.assert_allclose(w, fr.cycle_wear(X, Y, amp, ref.a, ref.p0, ref.delta_star,
                                                2 * IC_IW, ref.lam),
                               rtol=1e-9, atol=1e-12 * w.max())
    assert W_path == pytest.approx(W_cf, rel=1e-5)
    return Measured(
        loop=float(np.max(np.abs(-loops["Qx"] - Q_md[q + 1:]))) / ref.muP,
        energy_table=cycles["energy"][0] / W_cf - 1,
        energy_same_rule=cycles["energy"][0] / fr.loop_area(hist[q:], Q_md[q:]) - 1,
        dissipation=IC_MU * w_ic.sum() * dA / (2 * IC_IW) / W_path - 1,
        wear_interior=float(np.abs(w_ic - w)[interior].max() / w.max()),
        wear_l2=float(np.linalg.norm(w_ic - w) / np.linalg.norm(w)),
        wear_interior_axisym=float(np.abs(w_ic - w0)[interior].max() / w0.max()),
        gross_flag=float(cycles["gross_slip"][0]),
        P_rel=step.scalars["P"] / ref.P - 1)


# tolerances at the bundled grid (61², 20 steps per cycle), about twice the measured
# errors (module docstring): loop 0.034 | 0.073 % of μP, energy (same rule) 0.01 |
# 0.05 %, dissipation 0.001 | 0.05 %, wear interior 2.0 | 1.3 %, wear L2 4.5 | 1.2 %
TOL_61 = {"partial": dict(loop=0.001, energy_same_rule=0.003, dissipation=0.003,
                          wear_interior=0.03, wear_l2=0.07),
          "gross": dict(loop=0.0015, energy_same_rule=0.003, dissipation=0.003,
                        wear_interior=0.025, wear_l2=0.025)}


@pytest.mark.parametrize("regime", list(REGIMES))
def test_ic_loop_and_energy_at_the_bundled_grid(regime):
    """61² on 3.16 a, 20 steps per cycle: the issue's 2 % on the loop and on the energy
    per cycle holds; the energy's -1.0 | -0.8 % is the trapezoidal rule of 20 steps."""
    m = ic_run(61, regime, 20)
    print(f"\n{regime}: {m}")
    tol = TOL_61[regime]
    assert abs(m.P_rel) < 1e-3
    assert m.gross_flag == (1.0 if regime == "gross" else 0.0)
    assert m.loop < tol["loop"]
    assert abs(m.energy_same_rule) < tol["energy_same_rule"]
    assert abs(m.dissipation) < tol["dissipation"]
    assert abs(m.energy_table) < 0.02  # the 2 %
    # what is left is the time rule: the MD loop's own trapezoid error at 20 steps
    ref = fr.Fretting.from_approach(0.008, 50.0, IC_MU, E, NU, E, NU)
    amp = REGIMES[regime] * ref.delta_star
    hist = intended_history(amp, 20, 5)
    trap = fr.loop_area(hist[5:], fr.md_path(hist, IC_MU, ref.P, ref.delta_star)[5:])
    rule = trap / fr.cycle_energy(amp, IC_MU, ref.P, ref.delta_star) - 1
    assert -0.011 < rule < -0.008
    assert abs(m.energy_table - rule) < tol["energy_same_rule"]


@pytest.mark.parametrize("regime", list(REGIMES))
def test_ic_first_cycle_wear_at_the_bundled_grid(regime):
    """Wear depth after the first cycle against i_w p(r) × the cycle slip of the
    Cattaneo field with the ν-term of the Cerruti kernel; the axisymmetric mean slip
    alone is off by 11–16 | 3–4 % (measured) and must not be used for ν = 0.3."""
    m = ic_run(61, regime, 20)
    tol = TOL_61[regime]
    assert m.wear_interior < tol["wear_interior"]
    assert m.wear_l2 < tol["wear_l2"]
    assert m.wear_interior_axisym > 2 * m.wear_interior


def test_ic_errors_shrink_with_the_grid():
    """31² -> 61² -> 81² (8 steps per cycle: the loop points and the wear do not depend
    on the step count): the wear errors decrease in both regimes; the loop error falls
    from 31² to 61² and then stays at the Cattaneo–Mindlin floor (< 0.1 % of μP)."""
    for regime in REGIMES:
        ms = [ic_run(n, regime, 8) for n in (31, 61, 81)]
        for n, m in zip((31, 61, 81), ms, strict=True):
            print(f"{regime} {n}²: loop {m.loop:.2e}, energy (same rule) "
                  f"{m.energy_same_rule:+.2e}, dissipation {m.dissipation:+.2e}, wear "
                  f"interior {m.wear_interior:.3f}, L2 {m.wear_l2:.3f}")
        l2 = [m.wear_l2 for m in ms]
        assert l2[0] > l2[1] > l2[2]
        assert ms[0].wear_interior > ms[2].wear_interior
        assert ms[1].loop < ms[0].loop and ms[2].loop < 1e-3
        assert max(abs(m.dissipation) for m in ms[1:]) < 0.003


def test_ic_on_the_quick_resolution():
    """The quick case's resolution (31², 8 steps per cycle): the solver follows the MD
    response (loop, energy by the same trapezoid, dissipation against ∮ Q dδ of the path,
    wear against the path's slip sum); tolerances about twice the measured 31² errors
    (partial | gross: loop 0.10 | 0.14 %, energy 1.8 | 0.06 %, dissipation 2.5 | 0.03 %,
    wear interior 2.4 | 1.24 %)."""
    for regime in REGIMES:
        m = ic_run(31, regime, 8)
        print(f"\n{regime}: {m}")
        assert m.loop < 0.004
        assert abs(m.energy_same_rule) < 0.035
        assert abs(m.dissipation) < 0.05
        assert m.wear_interior < 0.04


def test_bundled_fretting_path_is_the_documented_cycle():
    for steps in (8, 20):
        np.testing.assert_array_equal(hw.fretting_path(1.0, steps), intended_path(1.0, steps))
