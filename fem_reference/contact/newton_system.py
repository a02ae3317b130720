"""The Newton system of the semi-smooth solve (:mod:`fem_reference.contact.semismooth`) on
the active set: the linearised Alart–Curnier functions of :mod:`.alart_curnier` in the
tractions of the active nodes and the control unknowns, solved with kept factors
(:class:`~fem_reference.contact.kept_factors.KeptFactors`)."""

from __future__ import annotations

import numpy as np

from ..errors import ContactNotConverged
from .alart_curnier import Laws, Problem, State, merit
from .block_system import block_step
from .kept_factors import KeptFactors
from .newton_rows import control_rows, dead_rows, slip_rows, slip_terms, stick_rows
from .row_system import Rows


def newton_step(p: Problem, s: State, L: Laws, kept: KeptFactors
                ) -> tuple[np.ndarray, np.ndarray]:
    """The Newton increment (Δλ (3, n), Δ of the control unknowns) on the active set;
    λ of every other component is set to zero (frictionless: λ_t; open: all).  Friction
    between identical materials is solved block by block (:mod:`.block_system`)."""
    law, n = p.law, p.pts.n
    act = np.flatnonzero(L.active)
    keep_t = law.mode == "friction"  # sliding: Δλ_t = c Δλ_n − F_t, eliminated
    comps = (0, 1, 2) if keep_t else (2,)
    cols = np.concatenate([c * n + act for c in comps])  # kept unknowns (flat 3n index)
    dlam = -L.F.copy()  # eliminated components: Δλ = −F = −λ
    dlam_flat = dlam.ravel()
    known = np.ones(3 * n, bool)
    known[cols] = False
    d_e = p.op.apply(np.where(known & (dlam_flat != 0.0), dlam_flat, 0.0).reshape(3, n))
    if act.size == 0 and any(c is None for _, c in p.extra):
        raise ContactNotConverged(
            "semi-smooth Newton: no node in contact under a prescribed load (the "
            f"iterate lost the contact; relative residual {merit(p, s, L):.3e})")
    nk = cols.size
    with np.errstate(divide="ignore", invalid="ignore"):
        if keep_t and p.op.decoupled:
            x = block_step(p, s, L, kept, act, dlam, d_e)
        else:
            x = _whole_step(p, s, L, kept, act, cols, dlam, d_e)
    if not np.isfinite(x).all():
        raise ContactNotConverged("singular semi-smooth Newton system")
    dlam_flat[cols] = x[:nk]
    if law.mode == "sliding":
        for c in (0, 1):
            dlam_flat[c * n + act] += law.slide_traction[c] * x[:nk]
    return dlam_flat.reshape(3, n), x[nk:]


def _whole_step(p: Problem, s: State, L: Laws, kept: KeptFactors, act: np.ndarray,
                cols: np.ndarray, dlam: np.ndarray, d_e: np.ndarray) -> np.ndarray:
    """The increments of the kept unknowns ``cols`` and the control unknowns from one
    system of them all."""
    law, n, na, ne = p.law, p.pts.n, act.size, len(p.extra)
    nk = cols.size
    # every kept row starts as the nodal compliance of its component: Δd on the
    # kept unknowns (the rows of the kept components are the kept unknowns' indices)
    B = p.op.block(cols)
    if law.mode == "sliding":  # the tangential tractions c Δλ_n of the kept Δλ_n
        c = law.slide_traction
        B = B + (c[0] * p.op.cross(cols, act) + c[1] * p.op.cross(cols, n + act))
    J = Rows(B, ne)
    iz = nk - na + np.arange(na)  # the λ_n block of the kept unknowns
    cw = p.cw[act]
    # normal rows (in mm): −Δδ + Δd_z + c_w Δλ_n = −g̃_n
    J.b[iz] = -(L.gn[act] + cw * s.lam[2, act]) - d_e[2, act]
    ecol = {k: nk + j for j, k in enumerate(p.extra)}
    dcol = next((ecol[k] for k in p.extra if k[1] is None), None)
    if dcol is not None:
        J.add(iz, dcol, -1.0)
    if law.mode == "friction":  # the slip rows read Δd_z, the rows of B (before c_w)
        stick_rows(p, L, act, d_e, J, ecol)
        S = slip_terms(p, L, act, d_e)
        if S is not None:
            slip_rows(S, na, J, ecol, whole=True, dcol=dcol)
    J.add(iz, iz, cw)
    control_rows(p, J, L, cols, dlam, ecol)
    dead_rows(p, s, J, cols)
    return kept.solve(J.system(), cols)
