"""The half-space's ring influence functions: axisymmetric tractions on the surface of the
pair, and the relative displacements they give (docs/formulation.md §2.9).

A pressure p(t) and a radial shear q(t) (on body a, the formulation's p_n and p_t = q r̂)
on the ring of radius t give, through the kernel of Eq. (5) (errata 1) integrated over
the ring's angle φ, the relative normal and radial displacements at radius r:

    u_z(r) = (1 − ν)/(π G) ∫ p(t) t I0(r, t) dt − (2K/G) ∫_r^∞ q(t) dt,
    u_r(r) = (1 − ν)/(π G) ∫ q(t) t I1(r, t) dt − (2K/G) (1/r) ∫_0^r p(t) t dt,

with G, ν, K of Eq. (6), s² = r² + t² − 2 r t cos φ and

    I0 = ∫_0^{2π} dφ / s       = 4 K(m) / (r + t),
    I1 = ∫_0^{2π} cos φ / s dφ = 4 / (r + t) [(2/m − 1) K(m) − (2/m) E(m)],

m = 4 r t / (r + t)², K and E the complete elliptic integrals.  The ν term of the
Cerruti kernel, ν (x' − x)((x' − x) cos φ + (y' − y) sin φ) / s³, integrates to zero over
every ring (its numerator is [(r² − t²)² − s⁴] / (4 r t), and ∫ dφ/s³ = 4 E / ((r + t)
(r − t)²), ∫ s dφ = 4 (r + t) E); the coupling terms are the ring integrals of A_xz and
A_zx, ∫ (t cos φ − r) / s² dφ = −2π/r for t < r, 0 beyond, and ∫ (t − r cos φ) / s² dφ
= 2π/t for t > r, 0 below.

Discretised here for tractions linear between nodes 0 = ρ_0 < … < ρ_N = 1 (in units of
the contact radius), collocated at the nodes: the log-singular ring kernels by
Gauss–Legendre quadrature on each half element, clustered toward its node by t = end +
L u² (the logarithm becomes u ln u); the coupling integrals exactly.  Nothing here is
shared with :mod:`halfspace`, which integrates the same kernel over square cells.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from scipy.special import ellipe, ellipkm1, roots_legendre

#: Gauss–Legendre points on each half element
_GAUSS = 24
#: below this m, I1 by its series π m / (r + t) / 4 (the closed form cancels)
_SMALL_M = 1e-5


def ring_kernels(r: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(t I0(r, t), t I1(r, t)) of the module doc, elementwise (r ≠ t)."""
    rt = r + t
    p = ((r - t) / rt) ** 2  # 1 − m, exact near the ring
    m = 1.0 - p
    k = ellipkm1(p)
    with np.errstate(divide="ignore", invalid="ignore"):
        i1 = 4.0 / rt * ((2.0 / m - 1.0) * k - (2.0 / m) * ellipe(m))
    i1 = np.where(m < _SMALL_M, np.pi * m / (4.0 * rt), i1)
    return t * 4.0 * k / rt, t * i1


@dataclass(frozen=True)
class RingOperators:
    """The discretised ring influence functions on ``nodes`` (ρ_0 = 0 … ρ_N = 1), acting
    on nodal values of p or q: ``Z`` ∫ φ_j t I0 dt, ``R`` ∫ φ_j t I1 dt, ``C`` ∫_ρi^1 φ_j
    dt, ``D`` (1/ρ_i) ∫_0^ρi φ_j t dt (φ_j the hat functions; row i the node ρ_i)."""

    nodes: np.ndarray
    Z: np.ndarray
    R: np.ndarray
    C: np.ndarray
    D: np.ndarray


@functools.lru_cache(maxsize=4)
def ring_operators(n: int) -> RingOperators:
    """The operators on n + 1 nodes ρ_i = sin(π i / 2n), clustered toward the contact
    edge, where the pressure falls as √(1 − ρ)."""
    nodes = np.sin(np.linspace(0.0, 0.5 * np.pi, n + 1))
    Z, R = _singular(nodes)
    C, D = _cumulative(nodes)
    for M in (Z, R, C, D):
        M.setflags(write=False)
    return RingOperators(nodes=nodes, Z=Z, R=R, C=C, D=D)


def rings_at(nodes: np.ndarray, at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The rows of Z and R (:class:`RingOperators`) at the radii ``at`` (any, ≠ a node
    off the element ends): the displacements of nodal tractions there."""
    return _singular(nodes, np.asarray(at, float))


def _singular(nodes: np.ndarray, at: np.ndarray | None = None
              ) -> tuple[np.ndarray, np.ndarray]:
    """Z and R (rows at ``at``, default the nodes): each element in two halves, each
    half's rule clustered toward its end node, so that the log singularity at a
    collocation node (an element end) is removed."""
    u, w = roots_legendre(_GAUSS)
    u, w = 0.5 * (u + 1.0), 0.5 * w
    lo, hi = nodes[:-1], nodes[1:]
    width = (hi - lo)[None, :, None]
    rho = (nodes if at is None else at)[:, None, None]
    Z = np.zeros((rho.shape[0], nodes.size))
    R = np.zeros_like(Z)
    for end in (lo, hi):
        half = 0.5 * (lo + hi) - end
        t = end[None, :, None] + half[None, :, None] * u ** 2
        jac = np.abs(half)[None, :, None] * 2.0 * u * w
        k0, k1 = ring_kernels(rho, t)
        to_lo, to_hi = (hi[None, :, None] - t) / width, (t - lo[None, :, None]) / width
        for kernel, M in ((k0, Z), (k1, R)):
            M[:, :-1] += np.sum(kernel * jac * to_lo, axis=2)
            M[:, 1:] += np.sum(kernel * jac * to_hi, axis=2)
    return Z, R


def _cumulative(nodes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """C and D, exact for tractions linear between the nodes."""
    n = nodes.size
    h = np.diff(nodes)
    e = np.arange(n - 1)
    area = np.zeros((n - 1, n))  # ∫ φ_j over element e
    moment = np.zeros((n - 1, n))  # ∫ φ_j t over element e
    area[e, e] = area[e, e + 1] = h / 2
    moment[e, e] = h * (2 * nodes[:-1] + nodes[1:]) / 6
    moment[e, e + 1] = h * (nodes[:-1] + 2 * nodes[1:]) / 6
    beyond = np.vstack([np.cumsum(area[::-1], axis=0)[::-1], np.zeros((1, n))])
    within = np.vstack([np.zeros((1, n)), np.cumsum(moment, axis=0)])
    D = np.zeros((n, n))
    D[1:] = within[1:] / nodes[1:, None]
    return beyond, D
