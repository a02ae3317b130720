"""The node-wise contact laws of :mod:`fem_reference.contact.augmented` (its module doc gives the
kinematics and the laws, Eqs. 1-2, 7-17, 21-23): the friction axes (Eq. 11), the law's
parameters, the contact points, and the laws evaluated with their tangent."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from cases.result import OPEN, SLIP, STICK


def rotation(beta_deg: float) -> np.ndarray:
    """Eq. 11: components in the tribological axes (e1, e2) from (x, y)."""
    b = np.radians(beta_deg)
    return np.array([[np.cos(b), np.sin(b)], [-np.sin(b), np.cos(b)]])


def axes_tensor(c1: float, c2: float, beta_deg: float) -> np.ndarray:
    """``Rᵀ diag(c1, c2) R``: a tensor with principal values c1, c2 along e1, e2."""
    R = rotation(beta_deg)
    return R.T @ np.diag([c1, c2]) @ R


def norm_with(tensor: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``sqrt(vᵀ T v)`` row-wise for v (..., 2)."""
    return np.sqrt(np.maximum(np.einsum("...i,ij,...j->...", v, tensor, v), 0.0))


@dataclass
class Law:
    """Contact law parameters.

    ``mode``: 'frictionless', 'sliding' (prescribed slip direction, full sliding) or
    'friction' (incremental return map with history).  ``stuck``: a frictionless solve
    of a frictional contact that carries no tangential traction (identical materials, no
    tangential load): its closed points stick (‖p_t‖_μ = 0 < p_n), they do not slip.
    """

    k_n: float
    mode: str = "frictionless"
    stuck: bool = False
    k_t: float = 0.0
    M2: np.ndarray = field(default_factory=lambda: np.zeros((2, 2)))  # 𝕄² in x, y
    M2inv: np.ndarray = field(default_factory=lambda: np.zeros((2, 2)))
    slide_traction: np.ndarray = field(default_factory=lambda: np.zeros(2))  # p_t / p_n


@dataclass
class Points:
    """Contact evaluation points: the surface nodes (dual weights > 0, ``G`` giving the
    modified coefficients, :mod:`fem_reference.model.nodal_basis`) or samples (weights 0)."""

    G: sp.csr_matrix  # (3n, m): condensed DOFs -> [u_x; u_y; u_z]
    w: np.ndarray  # integration weights [mm²]
    xy: np.ndarray  # (n, 2)
    h: np.ndarray  # indenter profile [mm]
    inside: np.ndarray  # points of the contact zone (others are never in contact)
    wear_a: np.ndarray | None = None  # wear depths of the bodies (n,)
    wear_b: np.ndarray | None = None
    t_old: np.ndarray | None = None  # tangential multiplier λ_t (n, 2): see evaluate
    gt_old: np.ndarray | None = None  # tangential gap at the last converged state (n, 2)
    lam_n: np.ndarray | None = None  # normal multiplier λ_n (n,): see evaluate

    def __post_init__(self) -> None:
        n = self.w.size
        for name, shape in (("wear_a", (n,)), ("wear_b", (n,)), ("t_old", (n, 2)),
                            ("gt_old", (n, 2)), ("lam_n", (n,))):
            if getattr(self, name) is None:
                setattr(self, name, np.zeros(shape))

    @property
    def n(self) -> int:
        return self.w.size

    def displacement(self, u: np.ndarray) -> np.ndarray:
        return (self.G @ u).reshape(3, -1).T  # (n, 3)


@dataclass
class Evaluation:
    gn: np.ndarray
    pn: np.ndarray
    t: np.ndarray  # (n, 2)
    gt: np.ndarray  # (n, 2)
    state: np.ndarray
    T: np.ndarray  # (n, 3, 3) d(t_x, t_y, p_n)/d(u_x, u_y, u_z)
    Tdelta: np.ndarray  # (n, 3) d(t_x, t_y, p_n)/dδ
    TD: np.ndarray  # (n, 3, 2) d(t_x, t_y, p_n)/d(g_t,o)


def evaluate(law: Law, pts: Points, u: np.ndarray, delta: float, D: np.ndarray,
             cw: float | np.ndarray = 0.0) -> Evaluation:
    """Tractions on body a, states and consistent tangents at the points ``pts``.

    Augmented laws (Eqs. 15-17 with the multipliers ``pts.lam_n``, ``pts.t_old``):
    ``p_n = ⟨λ_n − k_n g_n⟩ / (1 + k_n c_w)`` and the predictor
    ``p_t* = λ_t − k_t 𝕄² (g_t − g_t,old)``; ``cw``: the wear compliance, one value or
    one per point.  With λ_n = 0 and λ_t the last converged
    traction they are the plain penalty laws; :func:`augmented` iterates the multipliers
    until the gap and the stick condition hold exactly.
    """
    n = pts.n
    disp = pts.displacement(u)
    gn = pts.h + pts.wear_a + pts.wear_b - delta + disp[:, 2]
    k = law.k_n / (1.0 + law.k_n * cw)
    trial = pts.lam_n / law.k_n - gn  # (λ_n − k_n g_n) / k_n
    active = (trial > 0.0) & pts.inside
    pn = np.where(active, k * trial, 0.0)
    dpn_du = np.where(active, -k, 0.0)
    dpn_dd = np.where(active, k, 0.0)
    T = np.zeros((n, 3, 3))
    Tdelta = np.zeros((n, 3))
    TD = np.zeros((n, 3, 2))
    T[:, 2, 2] = dpn_du
    Tdelta[:, 2] = dpn_dd
    gt = D[None, :] + disp[:, :2]
    state = np.where(active, STICK if law.stuck else SLIP, OPEN)
    if law.mode == "frictionless":
        t = np.zeros((n, 2))
    elif law.mode == "sliding":
        c = law.slide_traction
        t = pn[:, None] * c[None, :]
        T[:, :2, 2] = c[None, :] * dpn_du[:, None]
        Tdelta[:, :2] = c[None, :] * dpn_dd[:, None]
    elif law.mode == "friction":
        A = -law.k_t * law.M2
        tstar = pts.t_old + (gt - pts.gt_old) @ A.T
        nrm = norm_with(law.M2inv, tstar)
        slip = active & (nrm > pn)
        stick = active & ~slip
        t = np.zeros((n, 2))
        t[stick] = tstar[stick]
        T[stick, :2, :2] = A
        TD[stick, :2, :] = A
        if slip.any():
            ts, ns, ps = tstar[slip], nrm[slip], pn[slip]
            q = ts @ law.M2inv.T
            P = (ps / ns)[:, None, None] * (
                np.eye(2)[None] - ts[:, :, None] * q[:, None, :] / (ns**2)[:, None, None]
            )
            t[slip] = (ps / ns)[:, None] * ts
            T[slip, :2, :2] = P @ A
            TD[slip, :2, :] = P @ A
            direction = ts / ns[:, None]
            T[slip, :2, 2] = direction * dpn_du[slip, None]
            Tdelta[slip, :2] = direction * dpn_dd[slip, None]
        state = np.where(stick, STICK, state)
    else:
        raise ValueError(f"unknown contact law mode {law.mode!r}")
    return Evaluation(gn=gn, pn=pn, t=t, gt=gt, state=state, T=T, Tdelta=Tdelta, TD=TD)


def weighted_blocks(w: np.ndarray, T: np.ndarray) -> sp.csr_matrix:
    """Sparse (3n x 3n) matrix with entries w_p T[p, r, c] at (r n + p, c n + p)."""
    n = w.size
    p = np.arange(n)
    rows = (np.arange(3)[None, :, None] * n + p[:, None, None]) + np.zeros((1, 1, 3), int)
    cols = (np.arange(3)[None, None, :] * n + p[:, None, None]) + np.zeros((1, 3, 1), int)
    data = w[:, None, None] * T
    return sp.csr_matrix((data.ravel(), (rows.ravel(), cols.ravel())), shape=(3 * n, 3 * n))
