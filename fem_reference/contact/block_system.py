"""The semi-smooth Newton system of friction between identical materials, block by block.

Where the normal displacements do not see the tangential tractions
(:attr:`~fem_reference.contact.compliance.NodalCompliance.decoupled`: Dundurs' β = 0), the
Newton system of :mod:`.newton_system` is block triangular: the normal rows (the gap
functions, the load or approach) hold only the normal unknowns (Δλ_n, Δδ).  They are
built and solved alone; then the tangential system (Δλ_t, ΔD) is built with the normal
increments known, its slip rows' normal terms ``n̂ (Δd_z + c_n Δλ_n − Δδ)``
(:mod:`.newton_rows`) moved to the right-hand side.  Two systems of orders |A| and
2|A|, each with its own kept factors, and no system of order 3|A| built; each held as
rows of its compliance block (:mod:`.row_system`).
"""

from __future__ import annotations

import numpy as np

from .alart_curnier import Laws, Problem, State
from .kept_factors import KeptFactors
from .newton_rows import control_rows, dead_rows, slip_rows, slip_terms, stick_rows
from .row_system import Rows


def block_step(p: Problem, s: State, L: Laws, kept: KeptFactors, act: np.ndarray,
               dlam: np.ndarray, d_e: np.ndarray) -> np.ndarray:
    """The increments of the kept unknowns, in the order of the whole system
    (Δλ_x, Δλ_y, Δλ_n of the active nodes ``act``, then the control unknowns);
    ``dlam`` (3, n) holds the eliminated increments, ``d_e`` their displacements."""
    n, na = p.pts.n, act.size
    normal = [k for k in p.extra if k[1] is None]
    tangential = [k for k in p.extra if k[1] is not None]
    # normal rows (in mm): −Δδ + Δd_z + c_w Δλ_n = −g̃_n
    cols_n = 2 * n + act
    Bn = p.op.block(cols_n)
    Jn = Rows(Bn, len(normal))
    cw = p.cw[act]
    Jn.b[:na] = -(L.gn[act] + cw * s.lam[2, act]) - d_e[2, act]
    ecol_n = {k: na + j for j, k in enumerate(normal)}
    if normal:
        Jn.add(np.arange(na), na, -1.0)
    control_rows(p, Jn, L, cols_n, dlam, ecol_n)
    Jn.add(np.arange(na), np.arange(na), cw)
    xn = kept.part("normal").solve(Jn.system(), cols_n)
    # tangential rows, the normal increments known
    cols_t = np.concatenate([act, n + act])
    Jt = Rows(p.op.block(cols_t), len(tangential))
    ecol_t = {k: 2 * na + j for j, k in enumerate(tangential)}
    stick_rows(p, L, act, d_e, Jt, ecol_t)
    S = slip_terms(p, L, act, d_e)
    if S is not None:
        slip_rows(S, na, Jt, ecol_t, whole=False, dcol=None)
        # their normal terms: Δd_z (the rows of the normal block, before c_w), Δλ_n, Δδ
        known = Bn[S.k] @ xn[:na] + S.c_n * xn[S.k] - (xn[na] if normal else 0.0)
        for c in (0, 1):
            Jt.b[c * na + S.k] -= S.nhat[:, c] * known
    control_rows(p, Jt, L, cols_t, dlam, ecol_t)
    dead_rows(p, s, Jt, cols_t)
    xt = kept.part("tangential").solve(Jt.system(), cols_t)
    nt = 2 * na
    return np.concatenate([xt[:nt], xn[:na], xn[na:], xt[nt:]])
