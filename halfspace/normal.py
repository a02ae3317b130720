"""Normal contact (Signorini, Eq. 7/15) on the grid for a given separation profile.

The gap of Eq. 29 is written ``g_n = h + A_zz p_n - delta`` where ``h`` collects the
geometric gap, the wear and the normal displacement due to tangential tractions, and
``delta`` is the rigid approach.  Two solvers:

- :func:`polonsky_keer` — the conjugate-gradient method of Polonsky & Keer (Wear 231,
  1999) with load control (P given, delta found) or displacement control (delta given);
- :func:`uzawa_normal` — the projected fixed-point update of section 3.4 step (III),
  ``p_n <- max(0, p_n - r_n g_n)`` (the text's ``p_n + r_n g_n`` has the wrong sign for
  Eq. 7's g_n >= 0), with the load balance of step (a.1) solved exactly each iteration.

Both stop on the natural-map residual of Eq. 15,
``||p_n - max(0, p_n - c g_n)|| / ||p_n||`` with c = 1/A_zz,self, and raise
:class:`ContactNotConverged` (with the residual) when the iteration cap is reached.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np


class ContactNotConverged(RuntimeError):
    """A contact iteration reached its cap; the message gives the residual."""


@dataclass
class NormalSolution:
    p_n: np.ndarray
    approach: float
    gap: np.ndarray
    iterations: int
    residual: float


# Round-off of a gap assembled by FFT products, relative to the gap's scale (measured:
# two assemblies of the same gap differ by ~1e-16 of it; a few hundred ulps of margin).
GAP_ROUNDOFF = 1e-14


def roundoff_floor(c: float, h: np.ndarray, approach: float | None = None) -> float:
    """Norm of the natural-map residual that round-off of the gap alone produces:
    c * GAP_ROUNDOFF * (gap scale) per cell, the gap scale max(|approach|, ptp(h)).  It
    matters only when the pressure nearly vanishes (displacement control with the contact
    worn through: measured ||p_n|| = 8e-5 MPa, where 2e-18 mm of round-off in the gap
    gave a relative residual of 1e-6)."""
    scale = max(abs(approach or 0.0), float(np.ptp(h)))
    return float(c * GAP_ROUNDOFF * scale * np.sqrt(h.size))


def normal_residual(p: np.ndarray, g: np.ndarray, c: float, floor: float = 0.0) -> float:
    """Natural-map residual of Eq. 15, beyond the round-off ``floor`` (see
    :func:`roundoff_floor`), relative to ||p||."""
    r = float(np.linalg.norm(p - np.maximum(0.0, p - c * g)))
    scale = np.linalg.norm(p)
    if scale == 0:  # no pressure: consistent when no overlap beyond round-off
        return 0.0 if r <= floor else np.inf
    return max(r - floor, 0.0) / scale


def _check_finite(arr: np.ndarray, what: str) -> None:
    if not np.all(np.isfinite(arr)):
        raise ContactNotConverged(f"{what} became NaN/Inf")


def _start(h: np.ndarray, c: float, P: float | None, approach: float | None,
           floor: float | None) -> tuple[bool, float, NormalSolution | None]:
    """Checks shared by the normal solvers: (load control?, residual floor, the solution
    when displacement control leaves no overlap beyond round-off, else None)."""
    load = P is not None
    if load == (approach is not None):
        raise ValueError("give exactly one of P and approach")
    if not np.all(np.isfinite(h)):
        raise ContactNotConverged("the separation profile (geometry + wear) contains NaN/Inf")
    if floor is None:
        floor = roundoff_floor(c, h, approach)
    if not load:
        g = h - approach
        if normal_residual(np.zeros_like(g), g, c, floor) == 0.0:  # touching, no load
            return load, floor, NormalSolution(np.zeros_like(g), approach, g, 0, 0.0)
    return load, floor, None


def polonsky_keer(
    apply: Callable[[np.ndarray], np.ndarray],
    h: np.ndarray,
    dA: float,
    c: float,
    *,
    P: float | None = None,
    approach: float | None = None,
    p0: np.ndarray | None = None,
    tol: float = 1e-10,
    max_iter: int = 5000,
    floor: float | None = None,
) -> NormalSolution:
    """Polonsky-Keer CG for ``min 1/2 p.Ap + p.(h - delta)``, ``p >= 0``.

    Load control (``P``): the mean gap over the contact set plays the rigid approach and
    the pressure is rescaled to carry P each iteration.  Displacement control
    (``approach``): the gap is ``h - approach + A p`` and no rescaling is done.  The
    residual is measured beyond ``floor`` (default :func:`roundoff_floor`).
    """
    load, floor, unloaded = _start(h, c, P, approach, floor)
    if unloaded is not None:
        return unloaded
    hh = h if load else h - approach
    if p0 is not None and np.any(p0 > 0):
        p = np.array(p0, dtype=float)
    else:
        p = np.where(hh < hh.min() + 0.5 * np.ptp(hh) + 1e-300, 1.0, 0.0)
        if not load:
            p = np.where(hh < 0, -hh, 0.0) * c  # rigid-punch guess
    if load:
        p *= P / (p.sum() * dA)
    t = np.zeros_like(p)
    G_old, conj = 1.0, False
    gbar = 0.0
    for it in range(1, max_iter + 1):
        S = p > 0
        if not np.any(S):
            raise ContactNotConverged("normal contact set became empty")
        g = apply(p) + hh
        if load:
            gbar = g[S].mean()
            g -= gbar
        res = normal_residual(p, g, c, floor)
        if res < tol:
            return NormalSolution(p, gbar if load else approach, g, it, res)
        G = float(np.dot(g[S], g[S]))
        t = np.where(S, g + (G / G_old) * t if conj else g, 0.0)
        G_old = G
        r = apply(t)
        if load:
            r -= r[S].mean()
        denom = float(np.dot(r[S], t[S]))
        if denom <= 0:
            raise ContactNotConverged(f"normal CG lost positivity at iteration {it} "
                                      f"(residual {res:.3e})")
        tau = float(np.dot(g[S], t[S])) / denom
        p = np.where(S, p - tau * t, 0.0)
        p[p < 0] = 0.0
        overlap = (p == 0) & (g < 0)
        conj = not np.any(overlap)
        if not conj:
            p[overlap] -= tau * g[overlap]
        if load:
            total = p.sum() * dA
            if total <= 0:
                raise ContactNotConverged("normal load vanished during the iteration")
            p *= P / total
        _check_finite(p, "normal pressure")
    raise ContactNotConverged(
        f"normal contact (Polonsky-Keer) did not converge in {max_iter} iterations: "
        f"residual {res:.3e} > tol {tol:.1e}")


def balance_approach(y: np.ndarray, r: float, target: float) -> float:
    """delta with sum(max(0, y + r delta)) = target, solved exactly (piecewise linear)."""
    ys = np.sort(y.ravel())[::-1]
    csum = np.cumsum(ys)
    k = np.arange(1, ys.size + 1)
    delta = (target - csum) / (k * r)
    nxt = np.append(ys[1:], -np.inf)
    ok = (ys + r * delta > 0) & (nxt + r * delta <= 0)
    return float(delta[np.argmax(ok)])


def uzawa_normal(
    apply: Callable[[np.ndarray], np.ndarray],
    h: np.ndarray,
    dA: float,
    c: float,
    r: float,
    *,
    P: float | None = None,
    approach: float | None = None,
    p0: np.ndarray | None = None,
    tol: float = 1e-10,
    max_iter: int = 20000,
    floor: float | None = None,
) -> NormalSolution:
    """Section 3.4 (III) for the normal tractions: p <- max(0, p - r g) (step r <= 1/lambda_max);
    the residual is measured beyond ``floor`` (default :func:`roundoff_floor`)."""
    load, floor, unloaded = _start(h, c, P, approach, floor)
    if unloaded is not None:
        return unloaded
    p = np.zeros_like(h) if p0 is None else np.array(p0, dtype=float)
    delta = 0.0 if load else approach
    res = np.inf
    for it in range(1, max_iter + 1):
        g = h + apply(p) - delta
        res = normal_residual(p, g, c, floor) if np.any(p > 0) else np.inf
        if res < tol:
            return NormalSolution(p, delta, g, it, res)
        y = p - r * g
        if load:
            # y + r delta with delta the correction of the approach: choose it so that
            # the updated pressure carries P exactly (step a.1 solved in closed form).
            d_delta = balance_approach(y, r, P / dA)
            delta += d_delta
            p = np.maximum(0.0, y + r * d_delta)
        else:
            p = np.maximum(0.0, y)
        _check_finite(p, "normal pressure")
    raise ContactNotConverged(
        f"normal contact (Uzawa) did not converge in {max_iter} iterations: "
        f"residual {res:.3e} > tol {tol:.1e}")
