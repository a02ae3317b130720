"""Frictional compression of a dissimilar pair (Spence 1975; Johnson 1985 §5.5): the
normal–tangential coupling's reference — the uncoupled closed form (SP1) below, and the
coupled self-similar solution, numerically exact on rings (:func:`compression`,
docs/formulation.md §2.9), which :mod:`analytic.solver` states.

Pressed together, the two surfaces move radially inward by amounts ∝ (1 − 2ν)/G: the one
with the larger (1 − 2ν)/G slides inward over the other.  With friction μ the contact
grows self-similarly (a stick disc r < c and a slip annulus c < r < a, c/a fixed), and in
the annulus the traction on each body is μ p, radial, opposing its slip: with Dundurs'

    β = ½ [(1 − 2ν_a)/G_a − (1 − 2ν_b)/G_b] / [(1 − ν_a)/G_a + (1 − ν_b)/G_b],

body a (the upper one) moves inward relative to b for β > 0, so the traction on a points
outward, q_a = sign(β) μ p r̂; for β < 0 inward (Spence 1975; Vollebregt's CONTACT, user
guide, example spence35: c/a = 1/2 at β = 1/2, μ = 0.2986, traction on body 1 outward).

**(SP1)** (not in the source article; docs/formulation.md §2.8) The stick radius of the
uncoupled problem (the pressure kept Hertzian, the shear driven by the pressure's radial
displacements; a self-similar, monotonic loading with a traction bounded at r = c)
solves

    |β| / μ = k K(√(1 − k²)) / artanh k,   k = c / a,

K the complete elliptic integral of the first kind.  With the coupling the stick disc is
smaller (1/2 against 0.623 at β = 1/2; within 0.01 a for |β| ≤ 0.2): on r > c of (SP1)
the pair slips, and there the traction is the exact μ p r̂ above — but the pressure is
not Hertz's: the coupling raises its peak (docs/formulation.md §2.9), which is why the
reference states :func:`compression` instead.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq
from scipy.special import ellipk

from cases.model import Case

from . import axisymmetric


def dundurs_beta(case: Case) -> float:
    """Dundurs' β of the pair (module doc; :attr:`cases.model.Case.dundurs_beta`)."""
    return case.dundurs_beta


def stick_ratio(beta: float, mu: float) -> float:
    """c / a of (SP1) (module doc); 1 without coupling."""
    target = abs(beta) / mu
    if target == 0.0:
        return 1.0

    def excess(y: float) -> float:  # k = tanh y resolves k -> 1
        k = math.tanh(y)
        return k * ellipk(1.0 / math.cosh(y) ** 2) / y - target

    if excess(40.0) >= 0.0:  # |β|/μ below π/80: c/a = tanh 40, 1 to double precision
        return 1.0
    return math.tanh(brentq(excess, 1e-12, 40.0, xtol=1e-14))


#: ring nodes of the coupled solution (:func:`compression`); its convergence to 800 is
#: held by tests/test_analytic_spence.py (measured: benchmarks/README.md, "Spence's
#: compression, exact")
N_RINGS = 400


@dataclass(frozen=True)
class Compression:
    """Spence's self-similar frictional compression of a dissimilar pair, the coupling
    solved whole (docs/formulation.md §2.9): at the nodes ``rho`` (units of the contact
    radius a), the pressure ``p`` and the radial shear on body a ``q`` in units of
    G a / R, the stick ratio ``k`` = c / a, the approach ``delta`` in units of a² / R and
    the load ``load`` = P R / (G a³) (G, ν, K of Eq. 6)."""

    k: float
    rho: np.ndarray
    p: np.ndarray
    q: np.ndarray
    delta: float
    load: float
    #: the smallest slip rate against the traction over the slip nodes, in units of a / R
    #: (≥ 0: the slip opposes the traction, Eq. 13; :class:`SlipAgainstFriction` if not)
    slip_rate_min: float
    nu: float

    def gap(self, rho: np.ndarray) -> np.ndarray:
        """The normal gap at radii ``rho`` (units of a; a² / R): 0 in the contact,
        ρ²/2 − δ + u_z outside, u_z of the pressure alone there (the shear's coupling
        term ∫_ρ q dt vanishes beyond the contact), interpolated between 64 radii."""
        rho = np.abs(np.asarray(rho, float))
        top = float(rho.max(initial=1.0))
        if top <= 1.0:
            return np.zeros_like(rho)
        at = 1.0 + (top - 1.0) * np.linspace(0.0, 1.0, 64) ** 2
        Z, _ = axisymmetric.rings_at(self.rho, at)
        g = 0.5 * at ** 2 - self.delta + (1.0 - self.nu) / np.pi * Z @ self.p
        return np.where(rho > 1.0, np.interp(rho, at, np.maximum(g, 0.0)), 0.0)


def pair_constants(case: Case) -> tuple[float, float, float]:
    """(G, ν, K) of the pair (Eq. 6)."""
    a, b = case.a, case.b
    ga, gb = a.E / (2 * (1 + a.nu)), b.E / (2 * (1 + b.nu))
    G = 2.0 / (1.0 / ga + 1.0 / gb)
    nu = 0.5 * G * (a.nu / ga + b.nu / gb)
    K = 0.25 * G * ((1 - 2 * a.nu) / ga - (1 - 2 * b.nu) / gb)
    return G, nu, K


@functools.lru_cache(maxsize=256)
def compression(nu: float, K: float, mu: float, n: int = N_RINGS) -> Compression:
    """The self-similar compression (docs/formulation.md §2.9) for the pair's ν, K and
    friction μ: tractions linear between the nodes of
    :func:`analytic.axisymmetric.ring_operators`, collocated at them —

    - normal, at every node: u_z = δ − ρ²/2 (the contact's edge at ρ = 1, p(1) = 0);
    - stick, 0 < ρ ≤ k: u_r = C ρ² (the displacement a point had when it stuck, a² U(k)
      of the self-similar u_r = a² U(r/a), kept since: U(ρ) ∝ ρ²; C unknown);
    - slip, k ≤ ρ ≤ 1: q = −σ μ p, σ the sign of the slip rate 2U − ρU' (∂u_r/∂a at a
      material point), −sign K: the pressure's own radial displacement −2K (1/r) ∫ p t dt
      drives it;
    - q(0) = 0 (symmetry);

    and k the largest stick ratio at a node for which the stick zone holds its traction
    inside the friction limit, |q| ≤ μ p (a larger one needs the √-singular traction of a
    stick zone too wide; a smaller one slips against its traction): a bisection over the
    nodes.  The slip annulus must then slip against its traction at every node
    (:class:`SlipAgainstFriction` if not).  Exact in the limit of many nodes: c/a agrees
    with CONTACT's published example (β = 1/2, μ = 0.2986: c/a = 1/2) and the pressure
    with Hertz's at K = 0."""
    ops = axisymmetric.ring_operators(n)
    rho, c = ops.nodes, (1.0 - nu) / np.pi
    sigma = -math.copysign(1.0, K)
    # unknowns: p_0 … p_{n-1} (p_n = 0), δ, q_0 … q_n, C
    i_d, i_q, i_c, size = n, n + 1, 2 * n + 2, 2 * n + 3
    A = np.zeros((size, size))
    b = np.zeros(size)
    A[:n + 1, :n] = c * ops.Z[:, :n]
    A[:n + 1, i_q:i_c] = -2.0 * K * ops.C
    A[:n + 1, i_d] = -1.0
    b[:n + 1] = -0.5 * rho ** 2
    A[n + 1, i_q] = 1.0
    stick = np.zeros((n + 1, size))
    stick[:, i_q:i_c] = c * ops.R
    stick[:, :n] = -2.0 * K * ops.D[:, :n]
    stick[:, i_c] = -rho ** 2
    slip = np.zeros((n + 1, size))
    slip[np.arange(n + 1), i_q + np.arange(n + 1)] = 1.0
    slip[np.arange(n), np.arange(n)] = sigma * mu

    def solved(m: int) -> np.ndarray:  # stick at nodes 1 … m, slip at m … n
        A[n + 2:] = np.vstack([stick[1:m + 1], slip[m:]])
        return np.linalg.solve(A, b)

    def holds(m: int) -> bool:
        x = solved(m)
        p, q = x[1:m], x[i_q + 1:i_q + m]
        return bool(np.all(np.abs(q) - mu * p <= 1e-12 * mu * x[0]))

    hi = n - 1  # the bisection's invariant: holds(lo), not holds(hi)
    if holds(hi):
        lo = hi
    else:  # from the edge inward: a stick zone too small to hold is only a few nodes
        step = max(n // 20, 1)
        lo = hi - step
        while lo > 1 and not holds(lo):
            hi, lo = lo, lo - step
        lo = max(lo, 1)
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (mid, hi) if holds(mid) else (lo, mid)
    x = solved(lo)
    p, q = np.append(x[:n], 0.0), x[i_q:i_c]
    u_r = c * ops.R @ q - 2.0 * K * ops.D @ p
    rate = float(np.min(sigma * (2.0 * u_r - rho * np.gradient(u_r, rho))[lo + 1:n],
                        initial=math.inf))
    if rate < 0.0:
        raise SlipAgainstFriction(
            f"Spence's compression (nu = {nu:g}, K = {K:g}, mu = {mu:g}): the annulus "
            f"slips along its traction (slip rate {rate:.3g} a/R), not against it")
    for v in (rho, p, q):
        v.setflags(write=False)
    return Compression(k=float(rho[lo]), rho=rho, p=p, q=q, delta=float(x[i_d]), nu=nu,
                       load=float(2.0 * np.pi * ops.D[-1] @ p), slip_rate_min=rate)


class SlipAgainstFriction(RuntimeError):
    """A solution of :func:`compression` whose slip annulus slips along its traction: the
    friction law's direction violated (a solution that did not converge to the law)."""
