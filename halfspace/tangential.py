"""Tangential (frictional) contact for fixed normal pressure, Eq. 8-17 and 3.4 (III).

With p_n fixed, the incremental problem with the associated rule (Eq. 13) is the
convex minimisation over p_t of ``1/2 p_t.A_tt p_t + p_t.b`` on the product of friction
ellipses ``||p_t||_mu <= p_n`` (Eq. 9), whose gradient is the slip increment
``dg_t = A_tt p_t + b`` (b = g_t,o + A_tn p_n - g_t^(k-1), Eq. 30).  In the scaled
variables ``q = M^-1 R p_t`` (R: rotation to e1, e2) the ellipses become discs of radius
p_n and the update of step (III), ``p_t <- P_E(p_t - r_t M^2 dg_t)``, is exactly the
projected gradient ``q <- P_disc(q - r_t M R dg_t)``.  Two solvers share that map:

- ``method="uzawa"``: the fixed-point iteration of section 3.4 with r_t = 1/L;
- ``method="cg"``: accelerated projected gradient (FISTA with adaptive restart; Beck &
  Teboulle 2009, O'Donoghue & Candes 2015) on the same problem in the unscaled tractions,
  with the Euclidean projection onto each ellipse: O(sqrt(kappa)) iterations, and the
  scaling by M (which multiplies the condition number by (mu2/mu1)^2) avoided.

Both stop on the natural-map residual of Eq. 16,
``||p_t - P_E(p_t - c_t M^2 dg_t)|| / ||p_n||`` with c_t = 1/A_tt,self.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from cases.model import Friction

from .friction import from_axes, mu_squared, project, to_axes
from .normal import ContactNotConverged


@dataclass
class TangentialSolution:
    p_x: np.ndarray
    p_y: np.ndarray
    iterations: int
    residual: float


def tangential_residual(p_x, p_y, dg_x, dg_y, p_n, fr: Friction, c: float) -> float:
    """Natural-map residual of Eq. 16, relative to ||p_n||."""
    mx, my = mu_squared(dg_x, dg_y, fr)
    sx, sy = project(p_x - c * mx, p_y - c * my, p_n, fr)
    scale = np.linalg.norm(p_n)
    return float(np.hypot(np.linalg.norm(p_x - sx), np.linalg.norm(p_y - sy)) / scale)


def _disc(q1, q2, rho):
    n = np.hypot(q1, q2)
    s = np.where(n > rho, rho / np.where(n > 0, n, 1.0), 1.0)
    return q1 * s, q2 * s


def _ellipse(y1, y2, a, b, t_start=None, iters: int = 100):
    """Euclidean projection onto the ellipses (v1/a)^2 + (v2/b)^2 <= 1 (a, b >= 0):
    v_i = a_i^2 y_i / (a_i^2 + t) with t >= 0 the root of the secular equation
    f(t) = sum (a_i y_i / (a_i^2 + t))^2 - 1 = 0.  Returns (v1, v2, t).

    f is convex and decreasing, so Newton from a point left of the root converges
    monotonically, and a Newton step from the right lands left of it.  Each term alone is
    <= 1 at the root, so t_lo = max(a|y1| - a^2, b|y2| - b^2) is left of it; the
    iteration starts from max(t_lo, t_start) (the root of the previous, nearby
    projection when given) and is kept >= t_lo."""
    a2, b2 = a * a, b * b
    live = (a > 0) & (b > 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        outside = live & ((y1 * y1) / np.where(live, a2, 1) + (y2 * y2) / np.where(live, b2, 1)
                          > 1.0)
    t = np.zeros_like(y1)
    if np.any(outside):
        A1, A2 = (a * y1)[outside] ** 2, (b * y2)[outside] ** 2
        aa, bb = a2[outside], b2[outside]
        t_lo = np.maximum(np.sqrt(A1) - aa, np.sqrt(A2) - bb)
        tt = t_lo if t_start is None else np.maximum(t_lo, t_start[outside])
        for _ in range(iters):
            d1, d2 = aa + tt, bb + tt
            r1, r2 = A1 / (d1 * d1), A2 / (d2 * d2)
            step = (r1 + r2 - 1.0) / (2.0 * (r1 / d1 + r2 / d2))
            tt = np.maximum(tt + step, t_lo)
            if np.all(np.abs(step) <= 1e-15 * (tt + aa + bb)):
                break
        t[outside] = tt
    with np.errstate(divide="ignore", invalid="ignore"):
        v1 = np.where(outside, y1 * a2 / (a2 + t), np.where(live, y1, 0.0))
        v2 = np.where(outside, y2 * b2 / (b2 + t), np.where(live, y2, 0.0))
    return v1, v2, t


def _projection(fr: Friction, p_n: np.ndarray, accelerate: bool):
    """(s1, s2, proj): the scaling of the iterate v along (e1, e2) and the projection onto
    the friction sets at the pressure p_n."""
    mu1, mu2 = fr.mu1, fr.mu2
    if not accelerate:
        # section 3.4 (III): v = q = M^-1 R p_t, projection onto discs of radius p_n
        return mu1, mu2, lambda v1, v2: _disc(v1, v2, p_n)
    # Euclidean metric: v = p_t in the axes (e1, e2), projection onto the ellipses
    if mu1 == mu2:  # isotropic: the ellipses are discs
        return 1.0, 1.0, lambda v1, v2: _disc(v1, v2, mu1 * p_n)
    t_last = [np.zeros_like(p_n)]  # secular roots of the last projection (warm start)

    def proj(v1, v2):
        v1, v2, t_last[0] = _ellipse(v1, v2, mu1 * p_n, mu2 * p_n, t_last[0])
        return v1, v2

    return 1.0, 1.0, proj


def solve_tangential(
    apply_tt: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
    b_x: np.ndarray,
    b_y: np.ndarray,
    p_n: np.ndarray,
    fr: Friction,
    L: float,
    c: float,
    *,
    p0: tuple[np.ndarray, np.ndarray] | None = None,
    method: str = "cg",
    tol: float = 1e-10,
    max_iter: int = 20000,
) -> TangentialSolution:
    """Frictional tractions for fixed p_n; L bounds the largest eigenvalue of A_tt."""
    mu1, beta = fr.mu1, fr.beta
    if mu1 == 0 or not np.any(p_n > 0):
        z = np.zeros_like(p_n)
        return TangentialSolution(z, z.copy(), 0, 0.0)
    accelerate = method == "cg"
    s1, s2, proj = _projection(fr, p_n, accelerate)
    step = 1.0 / (L * max(s1, s2) ** 2)

    def slip(v1, v2):
        px, py = from_axes(s1 * v1, s2 * v2, beta)
        ux, uy = apply_tt(px, py)
        return px, py, ux + b_x, uy + b_y

    def grad(dg_x, dg_y):
        g1, g2 = to_axes(dg_x, dg_y, beta)
        return s1 * g1, s2 * g2

    if p0 is None:
        q1 = q2 = np.zeros_like(p_n)
    else:
        a1, a2 = to_axes(*p0, beta)
        q1, q2 = proj(a1 / s1, a2 / s2)
    y1, y2, t = q1, q2, 1.0
    res = np.inf
    for it in range(1, max_iter + 1):
        px, py, dgx, dgy = slip(y1, y2)
        if not accelerate or it % 10 == 1:
            # residual at the current iterate q (y == q without acceleration)
            current = slip(q1, q2) if accelerate else (px, py, dgx, dgy)
            res = tangential_residual(*current, p_n, fr, c)
            if res < tol:
                return TangentialSolution(current[0], current[1], it, res)
        g1, g2 = grad(dgx, dgy)
        n1, n2 = proj(y1 - step * g1, y2 - step * g2)
        if accelerate:
            # gradient restart: drop momentum when it points uphill
            if np.vdot(y1 - n1, n1 - q1) + np.vdot(y2 - n2, n2 - q2) > 0:
                t = 1.0
            t_new = 0.5 * (1.0 + np.sqrt(1.0 + 4.0 * t * t))
            w = (t - 1.0) / t_new
            y1, y2 = n1 + w * (n1 - q1), n2 + w * (n2 - q2)
            t = t_new
        else:
            y1, y2 = n1, n2
        q1, q2 = n1, n2
        if not np.all(np.isfinite(q1)) or not np.all(np.isfinite(q2)):
            raise ContactNotConverged("tangential traction became NaN/Inf")
    raise ContactNotConverged(
        f"tangential contact ({method}) did not converge in {max_iter} iterations: "
        f"residual {res:.3e} > tol {tol:.1e}")
