"""The rows of the semi-smooth Newton system (:mod:`.newton_system`, :mod:`.block_system`)
beyond the nodal compliance: the linearised friction functions of the active nodes
(:mod:`.alart_curnier`, the return onto the ellipse of Eqs. 9, 13, 17), the control
equations and the components a symmetry plane holds.

A stick node's rows (in mm) are ``ΔD + Δd_t = −Δg_t``.  A slip node's rows, over its
normal stiffness r, are

    [(I − ρP) Δλ_t − n̂ (1 − r c_w) Δλ_n + n̂ r Δd_z + A Δd_t − n̂ r Δδ + A ΔD] / r = −F_t / r

with ``A = ρ P r_t 𝕄²``, ``P`` the derivative of the direction ``t*/‖t*‖_μ`` and
``n̂ = t*/‖t*‖_μ``: ``Δd_z`` is the normal displacement alone (the wear term ``c_w Δλ_n``
of the normal function is the ``r c_w`` of its coefficient).  :func:`slip_terms` gives
the coefficients; the whole system (:func:`.newton_system.newton_step`) and the
block-triangular one (:mod:`.block_system`) write them as rows of the compliance block
and entries of their own (:mod:`.row_system`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .alart_curnier import Laws, Problem, State
from .row_system import Rows


@dataclass(frozen=True)
class SlipTerms:
    """The coefficients of the slip rows (module doc), over r, of the slip nodes at
    positions ``k`` of the active set: ``A`` (ns, 2, 2) of Δd_t and ΔD, ``IP`` (ns, 2, 2)
    of Δλ_t, ``nhat`` (ns, 2) (of Δd_z, and −n̂ of Δδ), ``c_n`` (ns,) the factor of n̂ of
    the node's own Δλ_n, and ``rhs`` (ns, 2) with the eliminated tractions' part."""

    k: np.ndarray
    A: np.ndarray
    IP: np.ndarray
    nhat: np.ndarray
    c_n: np.ndarray
    rhs: np.ndarray


def dcols(ecol: dict) -> list[int | None]:
    """The columns of ΔD_x, ΔD_y (a tangential load or a shift unknown) in ``ecol``."""
    return [ecol.get(("D", c), ecol.get(("shift", c))) for c in (0, 1)]


def stick_rows(p: Problem, L: Laws, act: np.ndarray, d_e: np.ndarray, J: Rows,
               ecol: dict) -> None:
    """The stick rows: rows ``c |A| + k`` of the active node k, component c (Δd_t, the
    rows of B as they are, and ΔD)."""
    na, st = act.size, L.stick[act]
    D = dcols(ecol)
    for c in (0, 1):
        k = c * na + np.flatnonzero(st)
        J.b[k] = -(L.gt[act[st], c] - p.pts.gt_old[act[st], c]) - d_e[c, act[st]]
        if D[c] is not None:
            J.add(k, D[c], 1.0)


def slip_terms(p: Problem, L: Laws, act: np.ndarray, d_e: np.ndarray) -> SlipTerms | None:
    """The slip rows' coefficients (module doc), None without a slip node."""
    sl = L.slip[act]
    if not sl.any():
        return None
    k = np.flatnonzero(sl)
    nodes = act[k]
    law = p.law
    ts, ns, ps = L.tstar[nodes], L.nrm[nodes], L.rho[nodes]
    q = ts @ law.M2inv.T
    P = (np.eye(2)[None] - ts[:, :, None] * q[:, None, :] / (ns**2)[:, None, None]) \
        / ns[:, None, None]
    nhat = ts / ns[:, None]
    rr = p.r[nodes]
    A = (ps / rr)[:, None, None] * P * p.r_t[nodes, None, None] @ law.M2  # ρ P r_t 𝕄² / r
    IP = (np.eye(2)[None] - ps[:, None, None] * P) / rr[:, None, None]
    rhs = -L.F[:2, nodes].T / rr[:, None] - (
        np.einsum("kab,kb->ka", A, d_e[:2, nodes].T) + nhat * d_e[2, nodes][:, None])
    return SlipTerms(k=k, A=A, IP=IP, nhat=nhat, c_n=-(1.0 - rr * p.cw[nodes]) / rr,
                     rhs=rhs)


def slip_rows(S: SlipTerms, na: int, J: Rows, ecol: dict, whole: bool,
              dcol: int | None) -> None:
    """The slip rows (rows ``c |A| + k``): combinations of the rows of B (Δd) of the
    node's components, and their own entries.  ``whole``: the system has the normal
    unknowns too (rows and columns ``2 |A| + k``, their rows Δd_z alone); else the
    caller moves their terms to the right-hand side.  ``dcol``: the column of Δδ."""
    kx, ky, kz = S.k, na + S.k, 2 * na + S.k
    D = dcols(ecol)
    for c, k in ((0, kx), (1, ky)):
        terms = [(kx, S.A[:, c, 0]), (ky, S.A[:, c, 1])]
        if whole:
            terms.append((kz, S.nhat[:, c]))
        J.combine(k, terms)  # in the order of the sum (the same numbers as before)
        J.add(k, kx, S.IP[:, c, 0])
        J.add(k, ky, S.IP[:, c, 1])
        if whole:
            J.add(k, kz, S.nhat[:, c] * S.c_n)
        J.b[k] = S.rhs[:, c]
        if dcol is not None:
            J.add(k, dcol, -S.nhat[:, c])
        for e in (0, 1):
            if D[e] is not None:
                J.add(k, D[e], S.A[:, c, e])


def control_rows(p: Problem, J: Rows, L: Laws, cols: np.ndarray, dlam: np.ndarray,
                 ecol: dict) -> None:
    """The rows ``ecol[k]`` of the control unknowns k in ``ecol`` (the load or approach,
    the tangential load or shift); ``cols``: the flat indices (``c n + node``) of the
    system's traction unknowns, ``dlam`` (3, n) the eliminated increments."""
    ctrl, w, n = p.ctrl, p.pts.w, p.pts.n
    nk = cols.size
    for (kind, c), i in ecol.items():
        comp = 2 if c is None else c
        sel = (cols >= comp * n) & (cols < (comp + 1) * n)
        coeff = np.zeros(nk)
        coeff[sel] = w[cols[sel] - comp * n]
        known = float(w @ dlam[comp]) - float(coeff[sel] @ dlam.ravel()[cols[sel]])
        on = np.flatnonzero(coeff)
        if kind in ("approach", "shift"):
            cs = ctrl.sym * (ctrl.compliance if kind == "approach" else ctrl.compliance_t)
            J.add(np.full(on.size, i), on, cs * coeff[on])
            J.add(i, i, 1.0)
            J.b[i] = -L.Fe[p.extra.index((kind, c))] - cs * known
        else:
            J.add(np.full(on.size, i), on, coeff[on])
            J.b[i] = -L.Fe[p.extra.index((kind, c))] - known


def dead_rows(p: Problem, s: State, J: Rows, cols: np.ndarray) -> None:
    """A dead tangential component (friction) lies on a symmetry plane: λ = 0 there, in
    place of its row (``cols`` as in :func:`control_rows`)."""
    dead = np.flatnonzero(p.dead.ravel()[cols] & (cols < 2 * p.pts.n))
    J.clear(dead)
    J.add(dead, dead, 1.0)
    J.b[dead] = -s.lam.ravel()[cols[dead]]
