"""The first fretting cycle of a sphere in closed form: Mindlin–Deresiewicz loop, energy, wear.

A sphere pressed by a constant normal load P (Hertz radius a, peak pressure p0) is moved
tangentially by an imposed rigid displacement δ(t) along x, isotropic friction μ
(Mindlin & Deresiewicz 1953; Johnson 1985 §7.2–7.4).  Everything here is written with
the gross-slip displacement of :mod:`.mindlin`,

    δ* = (3μP / 16a) [(2-ν_a)/G_a + (2-ν_b)/G_b] = 3μP / (16 G* a),
    1/G* = (2-ν_a)/G_a + (2-ν_b)/G_b           (:func:`tangential_modulus`),

which is the *relative* shift of the two bodies (for identical bodies 1/G* = 2(2-ν)/G,
not the composite G of formulation Eq. 6).  The closed forms hold for pairs without
normal–tangential coupling, K = 0 of Eq. 6 ((1-2ν_a)/G_a = (1-2ν_b)/G_b, e.g. identical
bodies): otherwise the tangential load changes the pressure and no closed form exists
(:func:`check_uncoupled` refuses such a pair).

**Loop** (Johnson §7.4).  The virgin curve is Cattaneo–Mindlin's F(δ) = μP[1 - (1 -
|δ|/δ*)^(3/2)] sign δ, held at ±μP beyond δ* (:func:`.mindlin.load_from_shift`).  After a
reversal at (δ_r, Q_r) the increment is the virgin problem with twice the friction limit
(the tractions μp of the slipping annulus flip to -μp): Q = Q_r + 2F((δ - δ_r)/2)
(Masing's rule).  A branch that reaches the point it started from rejoins the branch
that point lay on (the loop closes; on the virgin curve at the mirror point -δ_r), which
:func:`md_path` implements for any displacement history with a stack of reversal points.
In gross slip the doubled curve saturates at Q_r ∓ 2μP = ∓μP: the plateau.

**Energy per cycle** (Johnson eq. 7.58 / Mindlin & Deresiewicz 1953), for a loop of
load amplitude Q* <= μP, t = Q*/μP:

    ΔW = (9 μ²P² / (10 a G*)) [1 - (1-t)^(5/3) - (5t/6)(1 + (1-t)^(2/3))]
       = (24/5) μP δ* [...]            (:func:`.mindlin.dissipated_energy`),

~ (4/27) μP δ* t³ = Q*³ / (36 μP G* a) for small t, and (4/5) μP δ* at t = 1.  A
displacement amplitude δ_A > δ* adds the plateaus: ΔW = 4μP(δ_A - δ*) + (4/5)μPδ*
(:func:`cycle_energy`).

**Slip and wear** (Johnson §7.2, §7.4).  The Cattaneo traction with stick radius c,
q = μp0√(1-r²/a²) - (c/a)μp0√(1-r²/c²), displaces the stick zone rigidly by
δ = δ*(1 - c²/a²); in the annulus c < r < a the x-slip (rigid shift minus relative
elastic displacement) is

    s(r; c) = (δ*/πa²) [(r² - 2c²) acos(c/r) + c √(r² - c²)] + λ n(r; c) cos 2θ,

whose axisymmetric part (:func:`cattaneo_slip`) comes from the angular mean (2-ν)/(4πG s)
of the Cerruti kernel and the second part (:func:`slip_anisotropy`) from its ν ξ²/s³
term, weighted by λ = (ν_a/G_a + ν_b/G_b) / ((2-ν_a)/G_a + (2-ν_b)/G_b)
(:func:`poisson_weight`; ν/(2-ν) for identical bodies).  The cos 2θ term integrates to
zero against the axisymmetric pressure, so it changes the local wear, not the energy or
the worn volume.  Like Cattaneo–Mindlin itself, the field neglects the small y-slip (the
traction is taken parallel to x).  By Masing's rule a half cycle of partial slip from
amplitude δ_A slips 2 s(r; c) with c = a√(1 - δ_A/δ*), the stick radius at the
amplitude, and the cycle twice that; in gross slip each half cycle adds the rigid slide
2(δ_A - δ*) to the transition slip 2 s(r; 0) = δ* r²/a² (1 - (λ/2) cos 2θ).  With the
Hertz pressure constant in time, Archard's law (formulation Eq. 18, 23) gives the depth
worn in one cycle w(r) = i_w p(r) S(r) (:func:`cycle_wear`), i_w the sum of both bodies'
coefficients for the gap, and the volume i_w ΔW / μ (:func:`cycle_wear_volume`), since
ΔW = ∫ μ p |ds| dA.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import hertz as hz
from . import mindlin as md

# ---------------------------------------------------------------------- constants


def tangential_modulus(G_a: float, nu_a: float, G_b: float | None = None,
                       nu_b: float | None = None) -> float:
    """G* with 1/G* = (2-ν_a)/G_a + (2-ν_b)/G_b (body b rigid if G_b is None), so that
    δ* = 3μP/(16 G* a) equals :func:`.mindlin.gross_slip_shift` (Johnson 1985 §7.2)."""
    comp = (2.0 - nu_a) / G_a
    if G_b is not None:
        comp += (2.0 - (nu_a if nu_b is None else nu_b)) / G_b
    return 1.0 / comp


def poisson_weight(G_a: float, nu_a: float, G_b: float | None = None,
                   nu_b: float | None = None) -> float:
    """λ = (ν_a/G_a + ν_b/G_b) / ((2-ν_a)/G_a + (2-ν_b)/G_b): the weight of the ν ξ²/s³
    part of the Cerruti kernel in the slip field; ν/(2-ν) for identical bodies."""
    num = nu_a / G_a
    if G_b is not None:
        num += (nu_a if nu_b is None else nu_b) / G_b
    return num * tangential_modulus(G_a, nu_a, G_b, nu_b)


def check_uncoupled(E_a: float, nu_a: float, E_b: float, nu_b: float,
                    rtol: float = 1e-12) -> None:
    """Raise ValueError unless K = 0 (formulation Eq. 6): (1-2ν_a)/G_a = (1-2ν_b)/G_b.

    With K != 0 a tangential load changes the normal pressure (and P under a held
    approach), which the Mindlin–Deresiewicz closed forms ignore.
    """
    ka = (1.0 - 2.0 * nu_a) * 2.0 * (1.0 + nu_a) / E_a
    kb = (1.0 - 2.0 * nu_b) * 2.0 * (1.0 + nu_b) / E_b
    if abs(ka - kb) > rtol * max(abs(ka), abs(kb)):
        raise ValueError("the Mindlin–Deresiewicz closed forms need K = 0 "
                         "((1-2ν_a)/G_a = (1-2ν_b)/G_b); this pair couples normal and "
                         "tangential loads")


@dataclass(frozen=True)
class MindlinDeresiewicz:
    """Scales of one fretting problem: μ, P [N], a [mm], p0 [MPa], δ* [mm], G* [MPa], λ."""

    mu: float
    P: float
    a: float
    p0: float
    delta_star: float
    G_star: float
    lam: float

    @classmethod
    def from_hertz(cls, h: hz.Hertz, mu: float, E_a: float, nu_a: float, E_b: float,
                   nu_b: float) -> MindlinDeresiewicz:
        """From a Hertz solution (:mod:`.hertz`) and the two bodies; K = 0 is required."""
        check_uncoupled(E_a, nu_a, E_b, nu_b)
        G_a, G_b = E_a / (2.0 * (1.0 + nu_a)), E_b / (2.0 * (1.0 + nu_b))
        G_star = tangential_modulus(G_a, nu_a, G_b, nu_b)
        return cls(mu=mu, P=h.P, a=h.a, p0=h.p0,
                   delta_star=md.gross_slip_shift(mu, h.P, h.a, G_a, nu_a, G_b, nu_b),
                   G_star=G_star, lam=poisson_weight(G_a, nu_a, G_b, nu_b))

    @classmethod
    def from_load(cls, P: float, R: float, mu: float, E_a: float, nu_a: float, E_b: float,
                  nu_b: float) -> MindlinDeresiewicz:
        """Load control: Hertz a, p0 of P (Johnson §4.2)."""
        E_star = 1.0 / ((1.0 - nu_a**2) / E_a + (1.0 - nu_b**2) / E_b)
        return cls.from_hertz(hz.hertz(P, R, E_star), mu, E_a, nu_a, E_b, nu_b)

    @classmethod
    def from_approach(cls, approach: float, R: float, mu: float, E_a: float, nu_a: float,
                      E_b: float, nu_b: float) -> MindlinDeresiewicz:
        """A held normal approach: P = (4/3)E*√R δ_n^(3/2), a = √(R δ_n) (Johnson §4.2)."""
        E_star = 1.0 / ((1.0 - nu_a**2) / E_a + (1.0 - nu_b**2) / E_b)
        return cls.from_hertz(hz.hertz_from_approach(approach, R, E_star), mu, E_a, nu_a,
                              E_b, nu_b)

    @property
    def muP(self) -> float:
        return self.mu * self.P


# ---------------------------------------------------------------------- the loop


def virgin_curve(delta, mu: float, P: float, delta_star: float) -> np.ndarray:
    """F(δ) = μP[1 - (1 - |δ|/δ*)^(3/2)] sign δ, ±μP beyond δ* (Johnson 1985 §7.2);
    :func:`.mindlin.load_from_shift` applied elementwise."""
    d = np.asarray(delta, float)
    return np.reshape([md.load_from_shift(float(v), mu, P, delta_star) for v in d.ravel()],
                      d.shape)


def _md_states(displacement, delta_star: float) -> list[list[tuple[float, float]]]:
    """The Cattaneo terms of the traction at each point of a displacement history that
    starts from the unloaded contact (Mindlin & Deresiewicz 1953; Johnson 1985 §7.4).

    A state is a list of terms (w, x): the traction is Σ w T(x), T(x) the Cattaneo
    traction of the virgin shift x >= 0, μp0[√(1-r²/a²) - (c/a)√(1-r²/c²)] with
    c = a√(1 - x/δ*), whose resultant is F(x).  The virgin curve is the one term
    (sign δ, |δ|); a branch from the reversal (δ_r, state_r) adds (2 sign(δ - δ_r),
    |δ - δ_r|/2) to state_r (Masing's rule: the slipping annulus reverses its traction).
    A branch that passes the point its parent branch started from rejoins the
    grandparent branch (two reversals forgotten, the tractions there are equal); the
    first branch rejoins the virgin curve at -δ_1.  Gross slip (x >= δ*) saturates T.
    """
    def state(d, rev):
        if not rev:
            return [(float(np.sign(d)), abs(d))]
        dr, terms = rev[-1]
        return terms + [(2.0 * float(np.sign(d - dr)), 0.5 * abs(d - dr))]

    def target(rev):
        # the displacement at which the current branch closes
        return rev[-2][0] if len(rev) >= 2 else -rev[0][0]

    rev: list[tuple[float, list[tuple[float, float]]]] = []
    cur = 0.0
    terms: list[tuple[float, float]] = [(0.0, 0.0)]
    out = []
    for d in np.atleast_1d(np.asarray(displacement, float)):
        d = float(d)
        if d != cur:
            going = np.sign(cur) if not rev else np.sign(target(rev) - rev[-1][0])
            if going != 0 and np.sign(d - cur) != going:  # a reversal at the current point
                rev.append((cur, terms))
            while rev:
                t = target(rev)
                if (d - t) * np.sign(t - rev[-1][0]) < 0:  # the branch has not closed
                    break
                del rev[-2 if len(rev) >= 2 else -1:]
            cur, terms = d, state(d, rev)
        out.append(terms)
    return out


def md_path(displacement, mu: float, P: float, delta_star: float) -> np.ndarray:
    """Q at each point of an imposed displacement history that starts from the unloaded
    contact (δ = 0, Q = 0): Mindlin & Deresiewicz (1953) through Masing's rule with memory
    (Johnson 1985 §7.4).

    On a branch from the last reversal (δ_r, Q_r), Q = Q_r + 2F((δ - δ_r)/2); a branch
    that passes the point its parent branch started from rejoins the grandparent branch,
    the first branch rejoins the virgin curve at (-δ_1, -Q_1); gross slip (|Q| = μP
    plateaus) follows from the saturation of F (:func:`_md_states`).
    """
    return np.array([sum(w * md.load_from_shift(x, mu, P, delta_star) for w, x in terms)
                     for terms in _md_states(displacement, delta_star)])


def md_slip_path(displacement, x, y, a: float, delta_star: float,
                 lam: float = 0.0) -> np.ndarray:
    """The accumulated x-slip g = δ - ū_x at the points (x, y) at each point of the
    history (shape (len(displacement),) + x.shape): the rigid shift minus the relative
    elastic displacement of the Cattaneo tractions of :func:`_md_states` (module
    docstring; ``lam`` = λ of :func:`poisson_weight`, 0 for the axisymmetric mean).
    Its differences are the slip increments of Archard's law; in the stick zone g stays
    constant."""
    x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
    r = np.hypot(x, y)
    with np.errstate(invalid="ignore", divide="ignore"):
        cos2 = np.where(r > 0, (x * x - y * y) / np.where(r > 0, r * r, 1.0), 0.0)
    scale = 2.0 * delta_star / (math.pi**2 * a)  # μp0 / (4πG*)
    phi_a, n_a = _potentials(r, a)
    cache: dict[float, np.ndarray] = {}

    def u_term(xv: float) -> np.ndarray:
        # relative displacement of T(x): (μp0/4πG*)[Φ_a - (c/a)Φ_c - λ(N_a - (c/a)N_c)cos2θ]
        if xv not in cache:
            c = stick_radius_at(min(xv, delta_star), a, delta_star)
            phi, n = phi_a.copy(), n_a.copy()
            if c > 0.0:
                phi_c, n_c = _potentials(r, c)
                phi, n = phi - (c / a) * phi_c, n - (c / a) * n_c
            cache[xv] = scale * (phi - lam * n * cos2)
        return cache[xv]

    path = np.atleast_1d(np.asarray(displacement, float))
    out = np.empty(path.shape + r.shape)
    for k, (d, terms) in enumerate(zip(path, _md_states(path, delta_star), strict=True)):
        u = np.zeros(r.shape)
        for w, xv in terms:
            if w:
                u = u + w * u_term(xv)
        out[k] = d - u
    return out


def md_work(displacement, mu: float, P: float, delta_star: float, start: int = 0,
            refine: int = 2000) -> float:
    """∫ Q dδ along a piecewise-linear history from the unloaded contact, counted from
    its point ``start`` on; each segment is cut into ``refine`` parts (trapezoidal rule,
    error O(refine⁻²)).  Over a closed cycle: the energy the cycle dissipates."""
    path = np.atleast_1d(np.asarray(displacement, float))
    t = np.linspace(0.0, 1.0, refine + 1)[1:]
    fine = np.concatenate([path[:1]] + [p0 + (p1 - p0) * t for p0, p1 in
                                        zip(path[:-1], path[1:], strict=True)])
    Q = md_path(fine, mu, P, delta_star)[start * refine:]
    return float(np.sum(0.5 * (Q[1:] + Q[:-1]) * np.diff(fine[start * refine:])))


def md_loop(amplitude: float, mu: float, P: float, delta_star: float,
            n: int = 201) -> tuple[np.ndarray, np.ndarray]:
    """The steady loop (δ, Q) of amplitude δ_A, partial or gross slip: +δ_A -> -δ_A ->
    +δ_A in 2(n-1) equal steps, after the virgin loading 0 -> +δ_A (:func:`md_path`)."""
    dA = abs(float(amplitude))
    down = np.linspace(dA, -dA, n)
    path = np.concatenate([[0.0], down, -down[1:]])
    Q = md_path(path, mu, P, delta_star)
    return path[1:], Q[1:]


def loop_area(delta: np.ndarray, Q: np.ndarray) -> float:
    """|∮ Q dδ| by the trapezoidal rule along a closed (δ, Q) path (the fretting
    solver's energy per cycle)."""
    d, q = np.asarray(delta, float), np.asarray(Q, float)
    return abs(float(np.sum(0.5 * (q[1:] + q[:-1]) * np.diff(d))))


# ---------------------------------------------------------------------- energy


def load_amplitude(amplitude: float, mu: float, P: float, delta_star: float) -> float:
    """Q* = F(δ_A), the load amplitude of a loop of displacement amplitude δ_A."""
    return md.load_from_shift(abs(amplitude), mu, P, delta_star)


def energy_johnson(Q_amp: float, mu: float, P: float, a: float, G_star: float) -> float:
    """ΔW = (9μ²P²/(10 a G*)) [1 - (1-t)^(5/3) - (5t/6)(1 + (1-t)^(2/3))], t = Q*/μP
    (Johnson 1985 eq. 7.58, Mindlin & Deresiewicz 1953) with :func:`tangential_modulus`
    G*; identical to :func:`.mindlin.dissipated_energy` with δ* = 3μP/(16G*a)."""
    t = min(abs(Q_amp) / (mu * P), 1.0)
    return 9.0 * (mu * P) ** 2 / (10.0 * a * G_star) * (
        1.0 - (1.0 - t) ** (5.0 / 3.0) - 5.0 * t / 6.0 * (1.0 + (1.0 - t) ** (2.0 / 3.0)))


def energy_small_amplitude(Q_amp: float, mu: float, P: float, delta_star: float) -> float:
    """Leading term for Q* << μP: ΔW ≈ (4/27) μP δ* (Q*/μP)³ = Q*³/(36 μP G* a)."""
    return 4.0 / 27.0 * mu * P * delta_star * (abs(Q_amp) / (mu * P)) ** 3


def cycle_energy(amplitude: float, mu: float, P: float, delta_star: float) -> float:
    """Energy dissipated per cycle of displacement amplitude δ_A: the Mindlin–Deresiewicz
    ΔW(F(δ_A)) in partial slip, 4μP(δ_A - δ*) + (4/5)μPδ* in gross slip (the loop of
    :func:`md_loop` with its two plateaus)."""
    dA = abs(float(amplitude))
    if dA <= delta_star:
        return md.dissipated_energy(load_amplitude(dA, mu, P, delta_star), mu, P, delta_star)
    return 4.0 * mu * P * (dA - delta_star) + 0.8 * mu * P * delta_star


# ---------------------------------------------------------------------- slip and wear


def stick_radius_at(amplitude: float, a: float, delta_star: float) -> float:
    """c = a √(1 - δ_A/δ*) (δ = δ*(1 - c²/a²), Johnson §7.2); 0 in gross slip."""
    return a * math.sqrt(max(1.0 - abs(amplitude) / delta_star, 0.0))


def _potentials(r: np.ndarray, rho: float) -> tuple[np.ndarray, np.ndarray]:
    """(Φ, N) of the unit Hertz-shaped traction √(1 - ρ'²/ρ²) on the circle of radius
    ρ: Φ = ∫∫ q/s dA', N = Φ - (2/r²)∫_0^r Φ r' dr' (the cos 2θ factor of ∫∫ q ξ²/s³ dA'
    up to sign; Johnson §3.4 for Φ, integrated once for N)."""
    r = np.asarray(r, float)
    inside = r <= rho
    ro = np.where(inside, rho, r)
    u = ro * ro - rho * rho
    asn = np.arcsin(rho / ro)
    phi_out = math.pi / (2.0 * rho) * ((2 * rho**2 - ro**2) * asn + rho * np.sqrt(u))
    m_out = 3.0 * math.pi**2 * rho**3 / 16.0 + math.pi / (2.0 * rho) * (
        (rho**2 * ro**2 - ro**4 / 4.0) * asn + 0.75 * rho**3 * np.sqrt(u)
        + 0.25 * rho * u**1.5 - 3.0 * math.pi / 8.0 * rho**4)
    phi = np.where(inside, math.pi**2 * (2 * rho**2 - r**2) / (4.0 * rho), phi_out)
    n_in = -math.pi**2 * r**2 / (8.0 * rho)
    n = np.where(inside, n_in, phi_out - 2.0 * m_out / ro**2)
    return phi, n


def cattaneo_slip(r, c: float, a: float, delta_star: float) -> np.ndarray:
    """Axisymmetric part of the slip at radius r for the stick radius c (Johnson §7.2):
    s = (δ*/πa²)[(r² - 2c²) acos(c/r) + c√(r² - c²)] in c < r < a, 0 in r <= c; 0 outside
    the contact (r >= a).  At c = 0, s = δ* r²/(2a²)."""
    r = np.abs(np.asarray(r, float))
    ro = np.maximum(r, max(c, 1e-300))
    s = delta_star / (math.pi * a * a) * (
        (ro * ro - 2 * c * c) * np.arccos(np.clip(c / ro, -1.0, 1.0))
        + c * np.sqrt(np.clip(ro * ro - c * c, 0.0, None)))
    return np.where((r > c) & (r < a), s, 0.0)


def slip_anisotropy(r, c: float, a: float, delta_star: float) -> np.ndarray:
    """n(r; c): the slip's cos 2θ part is λ n cos 2θ (see the module docstring);
    n = (2δ*/π²a)[N_a(r) - (c/a)N_c(r)], zero in the stick zone and outside the contact;
    n = -δ* r²/(4a²) at c = 0."""
    r = np.abs(np.asarray(r, float))
    n_a = _potentials(r, a)[1]
    n_c = _potentials(r, c)[1] if c > 0.0 else np.zeros_like(r)
    n = 2.0 * delta_star / (math.pi**2 * a) * (n_a - (c / a) * n_c)
    return np.where((r > c) & (r < a), n, 0.0)


def cycle_slip(x, y, amplitude: float, a: float, delta_star: float,
               lam: float = 0.0) -> np.ndarray:
    """Slip path length ∫|ds| of the point (x, y) over one steady cycle ±δ_A (after the
    first quarter): 4 s(r, θ; c) in partial slip, 4(δ_A - δ*) + 4 s(r, θ; 0) in gross slip.
    ``lam`` = λ of :func:`poisson_weight` (0: the axisymmetric mean)."""
    x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
    r = np.hypot(x, y)
    with np.errstate(invalid="ignore", divide="ignore"):
        cos2 = np.where(r > 0, (x * x - y * y) / np.where(r > 0, r * r, 1.0), 0.0)
    c = stick_radius_at(amplitude, a, delta_star)
    s = cattaneo_slip(r, c, a, delta_star)
    if lam:
        s = s + lam * slip_anisotropy(r, c, a, delta_star) * cos2
    s = 4.0 * np.abs(s)
    if abs(amplitude) > delta_star:
        s = s + np.where(r < a, 4.0 * (abs(amplitude) - delta_star), 0.0)
    return s


def cycle_wear(x, y, amplitude: float, a: float, p0: float, delta_star: float, i_w: float,
               lam: float = 0.0) -> np.ndarray:
    """Wear depth of the gap after one cycle, w = i_w p(r) ∫|ds| (Archard, formulation
    Eq. 18 with the Hertz pressure constant in time), i_w the sum over both bodies."""
    r = np.hypot(*np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float)))
    return i_w * hz.pressure(r, a, p0) * cycle_slip(x, y, amplitude, a, delta_star, lam)


def cycle_wear_volume(amplitude: float, mu: float, P: float, delta_star: float,
                      i_w: float) -> float:
    """Worn volume of one cycle, i_w ΔW / μ (ΔW = ∫ μ p |ds| dA, :func:`cycle_energy`)."""
    return i_w * cycle_energy(amplitude, mu, P, delta_star) / mu
