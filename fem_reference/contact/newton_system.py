"""The Newton system of the semi-smooth solve (:mod:`fem_reference.contact.semismooth`) on
the active set: the linearised Alart–Curnier functions of :mod:`.alart_curnier` in the
tractions of the active nodes and the control unknowns, solved with kept factors
(:class:`~fem_reference.contact.kept_factors.KeptFactors`)."""

from __future__ import annotations

import numpy as np

from .alart_curnier import Laws, Problem, State, merit
from .augmented import ContactNotConverged
from .kept_factors import KeptFactors


def newton_step(p: Problem, s: State, L: Laws, kept: KeptFactors
                ) -> tuple[np.ndarray, np.ndarray]:
    """The Newton increment (Δλ (3, n), Δ of the control unknowns) on the active set;
    λ of every other component is set to zero (frictionless: λ_t; open: all)."""
    law, HW, n = p.law, p.op.HW, p.pts.n
    act = np.flatnonzero(L.active)
    keep_t = law.mode == "friction"  # sliding: Δλ_t = c Δλ_n − F_t, eliminated
    comps = (0, 1, 2) if keep_t else (2,)
    cols = np.concatenate([c * n + act for c in comps])  # kept unknowns (flat 3n index)
    dlam = -L.F.copy()  # eliminated components: Δλ = −F = −λ
    dlam_flat = dlam.ravel()
    known = np.ones(3 * n, bool)
    known[cols] = False
    elim = np.flatnonzero(known & (dlam_flat != 0.0))
    d_e = HW[:, elim] @ dlam_flat[elim] if elim.size else np.zeros(3 * n)
    d_e = d_e.reshape(3, n)
    na, ne = act.size, len(p.extra)
    if na == 0 and any(c is None for _, c in p.extra):
        raise ContactNotConverged(
            "semi-smooth Newton: no node in contact under a prescribed load (the "
            f"iterate lost the contact; relative residual {merit(p, s, L):.3e})")
    nk = cols.size
    cw = p.cw[act]
    J = np.zeros((nk + ne, nk + ne))
    # every kept row starts as the nodal compliance of its component: Δd on the
    # kept unknowns (the rows of the kept components are the kept unknowns' indices)
    J[:nk, :nk] = p.op.block(cols)
    if law.mode == "sliding":  # the tangential tractions c Δλ_n of the kept Δλ_n
        c = law.slide_traction
        J[:nk, :nk] += c[0] * HW[np.ix_(cols, act)] + c[1] * HW[np.ix_(cols, n + act)]
    b = np.zeros(nk + ne)
    iz = (len(comps) - 1) * na + np.arange(na)  # the λ_n block of the kept unknowns
    # normal rows (in mm): −Δδ + Δd_z + c_w Δλ_n = −g̃_n
    J[iz, iz] += cw
    b[iz] = -(L.gn[act] + cw * s.lam[2, act]) - d_e[2, act]
    ecol = {k: nk + j for j, k in enumerate(p.extra)}
    dcol = next((ecol[k] for k in p.extra if k[1] is None), None)
    if dcol is not None:
        J[iz, dcol] = -1.0
    if keep_t:
        _tangential_rows(p, J, b, s, L, act, nk, d_e, ecol, dcol)
    _control_rows(p, J, b, L, act, cols, dlam, ecol)
    # a dead tangential component (friction) lies on a symmetry plane: λ = 0 there
    dead = np.flatnonzero(p.dead.ravel()[cols] & (cols < 2 * n))
    J[dead] = 0.0
    J[dead, dead] = 1.0
    b[dead] = -s.lam.ravel()[cols[dead]]
    with np.errstate(divide="ignore", invalid="ignore"):
        x = _solve(p, kept, J, b, cols, na)
    if not np.isfinite(x).all():
        raise ContactNotConverged("singular semi-smooth Newton system")
    dlam_flat[cols] = x[:nk]
    if law.mode == "sliding":
        for c in (0, 1):
            dlam_flat[c * n + act] += law.slide_traction[c] * x[:nk]
    return dlam_flat.reshape(3, n), x[nk:]


def _solve(p: Problem, kept: KeptFactors, J: np.ndarray, b: np.ndarray, cols: np.ndarray,
           na: int) -> np.ndarray:
    """``J x = b``.  Where the normal rows do not see the tangential unknowns
    (friction between identical materials: :attr:`NodalCompliance.decoupled`), the
    system is block triangular: the normal block (Δλ_n, Δδ) is solved first, then the
    tangential block (Δλ_t, ΔD) with the normal increments known — two factors of
    orders |A| and 2|A| instead of one of 3|A|."""
    nk = cols.size
    kinds = [c is None for _, c in p.extra]  # δ first (unknowns): its block is
    e0 = nk + sum(kinds)                         # rows and columns 2|A| .. e0
    if not (p.op.decoupled and p.law.mode == "friction"
            and kinds == sorted(kinds, reverse=True)):
        return kept.solve(J, b, cols)
    n0 = 2 * na
    if J[n0:e0, :n0].any() or J[n0:e0, e0:].any():  # a coupled row (not expected)
        return kept.solve(J, b, cols)
    t = np.r_[0:n0, e0:J.shape[0]]  # the tangential unknowns
    x = np.empty_like(b)
    x[n0:e0] = kept.part("normal").solve(
        np.ascontiguousarray(J[n0:e0, n0:e0]), b[n0:e0], cols[n0:])
    Jtt = np.empty((t.size, t.size))
    Jtt[:n0, :n0], Jtt[:n0, n0:] = J[:n0, :n0], J[:n0, e0:]
    Jtt[n0:, :n0], Jtt[n0:, n0:] = J[e0:, :n0], J[e0:, e0:]
    x[t] = kept.part("tangential").solve(
        Jtt, b[t] - J[t, n0:e0] @ x[n0:e0], cols[:n0])
    return x


def _tangential_rows(p: Problem, J, b, s, L, act, nk, d_e, ecol, dcol) -> None:
    """The tangential rows of the active nodes, in place: ``J[:nk, :nk]`` holds Δd_t
    and Δd_z on entry (:meth:`step`)."""
    law = p.law
    na = act.size
    ix, iy, iz = np.arange(na), na + np.arange(na), 2 * na + np.arange(na)
    r = p.r[act]
    st, sl = L.stick[act], L.slip[act]
    dcols = [ecol.get(k) for k in (("D", 0), ("D", 1), ("shift", 0), ("shift", 1))]
    Dcol = [dcols[0] if dcols[0] is not None else dcols[2],
            dcols[1] if dcols[1] is not None else dcols[3]]
    # stick rows (in mm): ΔD + Δd_t = −Δg_t
    for c, ic in ((0, ix), (1, iy)):
        k = ic[st]
        b[k] = -(L.gt[act[st], c] - p.pts.gt_old[act[st], c]) - d_e[c, act[st]]
        if Dcol[c] is not None:
            J[k, Dcol[c]] = 1.0
    if not sl.any():
        return
    k_sl = np.flatnonzero(sl)
    nodes = act[k_sl]
    ts, ns, ps = L.tstar[nodes], L.nrm[nodes], L.rho[nodes]
    q = ts @ law.M2inv.T
    P = (np.eye(2)[None] - ts[:, :, None] * q[:, None, :] / (ns**2)[:, None, None]) \
        / ns[:, None, None]
    nhat = ts / ns[:, None]
    rr = r[k_sl]
    A = (ps / rr)[:, None, None] * P * p.r_t[nodes, None, None] @ law.M2  # ρ P r_t 𝕄² / r
    # slip rows over r: [(I − ρP)Δλ_t − n̂(1 − r c_w)Δλ_n + n̂ r Δd_z + A Δd_t
    #                   − n̂ r Δδ + A ΔD] / r = −F_t / r  (A: ρ P r_t 𝕄²)
    # decoupled: Δd_t has only tangential columns, Δd_z only normal ones
    t, z = (slice(0, 2 * na), slice(2 * na, nk)) if p.op.decoupled else (
        slice(0, nk), slice(0, nk))
    kx, ky, kz = ix[k_sl], iy[k_sl], iz[k_sl]
    dx, dy, dz = J[kx, t], J[ky, t], J[kz, z]
    IP = (np.eye(2)[None] - ps[:, None, None] * P) / rr[:, None, None]
    cwk = p.cw[nodes]
    rhs = -L.F[:2, nodes].T / rr[:, None] - (
        np.einsum("kab,kb->ka", A, d_e[:2, nodes].T) + nhat * d_e[2, nodes][:, None])
    for c, k in ((0, kx), (1, ky)):
        # the new row written in place, in the order of the sum above (no zeroed row of
        # the system's width built and copied; the same numbers)
        row = A[:, c, 0, None] * dx
        row += A[:, c, 1, None] * dy
        if p.op.decoupled:  # t and z part the kept columns
            J[k, t] = row
            J[k, z] = nhat[:, c, None] * dz
        else:
            row += nhat[:, c, None] * dz
            J[k, :nk] = row
        J[k, nk:] = 0.0
        J[k, kx] += IP[:, c, 0]
        J[k, ky] += IP[:, c, 1]
        J[k, kz] += -nhat[:, c] * (1.0 - rr * cwk) / rr
        b[k] = rhs[:, c]
        if dcol is not None:
            J[k, dcol] = -nhat[:, c]
        for e in (0, 1):
            if Dcol[e] is not None:
                J[k, Dcol[e]] = A[:, c, e]


def _control_rows(p: Problem, J, b, L, act, cols, dlam, ecol) -> None:
    """The rows of the control unknowns (the load or approach, the tangential load or
    shift), in place."""
    ctrl, w, n = p.ctrl, p.pts.w, p.pts.n
    nk = cols.size
    for (kind, c), i in ((k, ecol[k]) for k in p.extra):
        comp = 2 if c is None else c
        sel = (cols >= comp * n) & (cols < (comp + 1) * n)
        coeff = np.zeros(nk)
        coeff[sel] = w[cols[sel] - comp * n]
        known = float(w @ dlam[comp]) - float(coeff[sel] @ dlam.ravel()[cols[sel]])
        if kind in ("approach", "shift"):
            cs = ctrl.sym * (ctrl.compliance if kind == "approach" else ctrl.compliance_t)
            J[i, :nk] = cs * coeff
            J[i, i] = 1.0
            b[i] = -L.Fe[p.extra.index((kind, c))] - cs * known
        else:
            J[i, :nk] = coeff
            b[i] = -L.Fe[p.extra.index((kind, c))] - known
