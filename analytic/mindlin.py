"""Cattaneo–Mindlin partial slip of a sphere under a monotonic tangential load (Johnson §7.2).

Normal load P first (Hertz radius a, peak p0), then a tangential load Q < μP (isotropic
μ, identical elastic constants or, for the tangential compliance, any pair without
normal–tangential coupling).  The traction on the loaded body, parallel to Q, is

    q(r) = μ p0 √(1 - r²/a²) - (c/a) μ p0 √(1 - r²/c²)   (the second term for r < c only),

with the stick radius c = a (1 - Q/μP)^(1/3) (Johnson 1985 §7.2): slip in c <= r < a,
stick in r < c.

Tangential compliance (derivation from Johnson 1985 §7.2): the traction q0 √(1 - r²/a²) in x
displaces the surface of *one* half-space of shear modulus G, Poisson ratio ν, by
u_x = π q0 [4(2-ν)a² - (4-3ν)x² - (4-ν)y²] / (32 G a) inside r < a.  In the stick zone the
x², y² terms of the two Cattaneo terms cancel and u_x = π μ p0 (2-ν)(a² - c²) / (8 G a) =
3μP(2-ν)/(16 G a) · [1 - (1 - Q/μP)^(2/3)]: the one-body-on-rigid-plane result.  Two
bodies carry opposite tractions and displace in opposite senses, so the rigid shift of
one body relative to the other (distant points; the stick zone moves rigidly) is

    δ_t(Q) = δ* [1 - (1 - Q/μP)^(2/3)],   δ* = (3μP / 16a) [(2-ν_a)/G_a + (2-ν_b)/G_b]

(Johnson 1985 §7.2), i.e. δ* = 3μP(2-ν)/(8Ga) for two identical bodies (G, ν of either
body; NOT the G/2 of the combined kernel of formulation Eq. 6 in this formula).  δ* is the
shift at which gross slip starts.  Under a held normal approach δ_n (displacement
control, P = (4/3)E*√R δ_n^(3/2), a = √(R δ_n)):

    δ* = (μ E* δ_n / 4) [(2-ν_a)/G_a + (2-ν_b)/G_b] = μ (2-ν) δ_n / (2(1-ν))  (identical),

so a fretting amplitude δ_amp < δ* stays in partial slip, δ_amp >= δ* reaches gross slip
(:func:`fretting_regime`).  The Mindlin–Deresiewicz loop (Johnson §7.4) follows from
Q(δ) by Masing's rule, :func:`loop_partial_slip`, and its area (Johnson 1985 §7.4)
rewritten with δ*: ΔW = (24/5) μP δ* {1 - (1-Q*/μP)^(5/3) - (5Q*/6μP)[1 + (1-Q*/μP)^(2/3)]}
(equivalently 8∫_0^δA F dδ - 4 Q* δA, with F the virgin curve; ~ (4/27) μP δ* (Q*/μP)³).
"""

from __future__ import annotations

import numpy as np

from cases.result import GROSS, PARTIAL


def stick_radius(a: float, Q: float, mu: float, P: float) -> float:
    """c = a (1 - |Q|/μP)^(1/3) (Johnson 1985 §7.2); 0 at or beyond gross slip."""
    ratio = abs(Q) / (mu * P)
    return a * max(1.0 - ratio, 0.0) ** (1.0 / 3.0)


def traction(r, a: float, c: float, mu: float, p0: float) -> np.ndarray:
    """|q|(r) = μ p0 √(1 - r²/a²) - (c/a) μ p0 √(1 - r²/c²) [r < c] (Johnson §7.2)."""
    r = np.asarray(r, float)
    q = mu * p0 * np.sqrt(np.clip(1.0 - (r / a) ** 2, 0.0, None))
    if c > 0.0:
        q = q - (c / a) * mu * p0 * np.sqrt(np.clip(1.0 - (r / c) ** 2, 0.0, None))
    return q


def gross_slip_shift(mu: float, P: float, a: float, G_a: float, nu_a: float,
                     G_b: float | None = None, nu_b: float | None = None) -> float:
    """δ* = (3μP/16a) [(2-ν_a)/G_a + (2-ν_b)/G_b]; body b rigid if G_b is None (§7.2)."""
    comp = (2.0 - nu_a) / G_a
    if G_b is not None:
        comp += (2.0 - (nu_a if nu_b is None else nu_b)) / G_b
    return 3.0 * mu * P / (16.0 * a) * comp


def shift_from_load(Q: float, mu: float, P: float, delta_star: float) -> float:
    """Rigid tangential shift δ_t = δ* [1 - (1 - Q/μP)^(2/3)] for |Q| <= μP, signed like Q."""
    ratio = min(abs(Q) / (mu * P), 1.0)
    return float(np.sign(Q) * delta_star * (1.0 - (1.0 - ratio) ** (2.0 / 3.0)))


def load_from_shift(delta: float, mu: float, P: float, delta_star: float) -> float:
    """Inverse of :func:`shift_from_load`: Q = μP [1 - (1 - δ/δ*)^(3/2)], μP beyond δ*."""
    ratio = min(abs(delta) / delta_star, 1.0)
    return float(np.sign(delta) * mu * P * (1.0 - (1.0 - ratio) ** 1.5))


def gross_slip_shift_from_approach(delta_n: float, mu: float, E_star: float, G_a: float,
                                   nu_a: float, G_b: float, nu_b: float) -> float:
    """δ* for a held normal approach δ_n: (μ E* δ_n / 4)[(2-ν_a)/G_a + (2-ν_b)/G_b]."""
    return mu * E_star * delta_n / 4.0 * ((2.0 - nu_a) / G_a + (2.0 - nu_b) / G_b)


def fretting_regime(amplitude: float, delta_star: float) -> str:
    """:data:`cases.result.PARTIAL` if the shift amplitude stays below δ*, else
    :data:`cases.result.GROSS` (slip)."""
    return PARTIAL if abs(amplitude) < delta_star else GROSS


def loop_partial_slip(amplitude: float, mu: float, P: float, delta_star: float,
                      n: int = 201) -> tuple[np.ndarray, np.ndarray]:
    """One steady fretting loop (δ, Q): unloading +δA -> -δA, then reloading (Masing's rule).

    Q_unload(δ) = Q_A - 2 F((δ_A - δ)/2),  Q_reload(δ) = -Q_A + 2 F((δ + δ_A)/2), with
    F = :func:`load_from_shift` the virgin curve and Q_A = F(δ_A) (Mindlin & Deresiewicz
    1953; Johnson §7.4).  Valid for δ_A <= δ*.
    """
    if amplitude > delta_star:
        raise ValueError("loop_partial_slip: amplitude exceeds the gross-slip shift δ*")

    def F(d):
        return np.array([load_from_shift(v, mu, P, delta_star) for v in np.atleast_1d(d)])

    dA = abs(amplitude)
    QA = float(F(dA)[0])
    down = np.linspace(dA, -dA, n)
    up = np.linspace(-dA, dA, n)
    q_down = QA - 2.0 * F((dA - down) / 2.0)
    q_up = -QA + 2.0 * F((up + dA) / 2.0)
    return np.concatenate([down, up[1:]]), np.concatenate([q_down, q_up[1:]])


def dissipated_energy(Q_amp: float, mu: float, P: float, delta_star: float) -> float:
    """Energy per cycle ΔW (Johnson §7.4, with δ*): the area of :func:`loop_partial_slip`.

    ΔW = (24/5) μP δ* [1 - (1-t)^(5/3) - (5t/6)(1 + (1-t)^(2/3))], t = Q*/μP <= 1.
    """
    t = min(abs(Q_amp) / (mu * P), 1.0)
    return 24.0 / 5.0 * mu * P * delta_star * (
        1.0 - (1.0 - t) ** (5.0 / 3.0) - 5.0 * t / 6.0 * (1.0 + (1.0 - t) ** (2.0 / 3.0)))
