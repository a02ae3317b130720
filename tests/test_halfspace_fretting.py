"""The half-space solver's first fretting cycle against Mindlin–Deresiewicz
(analytic/fretting.py, verified in tests/test_analytic_fretting.py).

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

This comparison found that ``halfspace.wear.cycle_path`` imposed +A -> -A, then
+0.8A -> -0.8A and a jump to +A (20 steps): one "cycle" dissipated 1.49 | 1.57 times the
cycle's energy (partial | gross slip).  Fixed; :func:`test_bundled_fretting_path_is_the_
documented_cycle` holds it to :func:`intended_path`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pytest
from test_analytic_fretting import NU, E, intended_history, intended_path

import halfspace
import halfspace.wear as hw
from analytic import fretting as fr
from analytic import hertz as hz
from cases.loader import load_case

IC_MU = 0.3
IC_IW = 1e-9  # per body, MPa⁻¹
REGIMES = {"partial": 0.5, "gross": 1.5}


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
    ref = fr.MindlinDeresiewicz.from_approach(0.008, 50.0, IC_MU, E, NU, E, NU)
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
    ref = fr.MindlinDeresiewicz.from_approach(0.008, 50.0, IC_MU, E, NU, E, NU)
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
        np.testing.assert_array_equal(hw.cycle_path(1.0, steps), intended_path(1.0, steps))
