"""Semi-smooth Newton solve of the nodal contact problem in the tractions.

The laws of :mod:`fem_reference.contact.augmented` (Eqs. 7-17, 21-23) written, node by node, as
the zeros of the Alart–Curnier functions (Alart & Curnier 1991; Hüeber, Stadler &
Wohlmuth 2008 for 3D Coulomb friction with dual bases), in the tractions
``λ = (λ_x, λ_y, λ_n)`` on body a:

    F_n = λ_n − ρ,                          ρ = ⟨λ_n − r g̃_n⟩,  g̃_n = g_n + c_w λ_n,
    F_t = λ_t − Π_ρ(λ_t − r_t 𝕄² Δg_t),

(full sliding along a prescribed direction: ``F_t = λ_t − c λ_n`` on a pressed node,
Eq. 13, whose tangential tractions then leave the Newton system), with ``Π_ρ`` the
radial projection onto the friction ellipse ``‖p_t‖_μ ≤ ρ`` (Eqs. 9,
17), ``Δg_t = g_t − g_t,old`` the tangential gap since the last converged state and
``c_w`` the wear compliance of the step (Eq. 23).  A zero is the exact solution: an
active point has no gap, a stick point has not slipped, a slipping one lies on the
ellipse and slips along ``−𝕄⁻² p_t`` (the associated rule, Eq. 13) — the fixed point
the augmented Lagrangian of :func:`fem_reference.contact.augmented.augmented` reaches, with no
penalty: ``r`` and ``r_t`` set only the path of the iteration.

The elastic response is the nodal compliance ``d = H W λ`` with ``H = G C Gᵀ`` (the
condensed compliance seen from the nodes, :class:`NodalCompliance`), so the unknowns are
the tractions of the active nodes and the control unknowns (δ, g_t,o) of
:func:`fem_reference.contact.control.unknowns`.  Each iteration solves one dense system on the
active set (open nodes: ``λ = 0`` exactly), started from the previous state's tractions
and so from its active sets.  The functions and their merit are in
:mod:`fem_reference.contact.alart_curnier`, the Newton system in
:mod:`fem_reference.contact.newton_system`; this module iterates.
"""

from __future__ import annotations

import numpy as np

from cases.result import OPEN, SLIP, STICK

from ..errors import ContactNotConverged
from .alart_curnier import Laws, Problem, State, laws, merit, problem
from .compliance import NodalCompliance
from .control import Control, Solution
from .kept_factors import KeptFactors
from .laws import Evaluation, Law, Points
from .newton_system import newton_step
from .threads import blas_threads

MAX_ITER = 100  # Newton iterations of one solve
MAX_HALVINGS = 10  # line search


def semismooth(op: NodalCompliance, law: Law, pts: Points, ctrl: Control, *,
               cw: float | np.ndarray = 0.0, tol: float = 1e-9,
               max_iter: int | None = None, kept: KeptFactors | None = None) -> Solution:
    """Solve the contact under ``ctrl`` from the tractions ``pts.lam_n``, ``pts.t_old``
    (the last state's) by the semi-smooth Newton method of the module doc; on return
    ``pts.lam_n``, ``pts.t_old`` hold the solution's tractions (as after
    :func:`fem_reference.contact.augmented.augmented`).  Converged when every function is below
    ``tol`` times the largest pressure (and the controls likewise) with the active sets
    of the last step unchanged; at most ``max_iter`` (default :data:`MAX_ITER`)
    iterations.  ``iterations``: Newton iterations.  ``kept``: the factors of the
    Newton systems (:class:`KeptFactors`), kept by the caller for the next solves.
    Raises :class:`~fem_reference.errors.ContactNotConverged` with the residual.
    """
    with blas_threads(1):
        return _run(problem(op, law, pts, ctrl, cw, tol), kept or KeptFactors(),
                    max_iter or MAX_ITER)


def _update(p: Problem, s: State, dlam: np.ndarray, dx: np.ndarray, t: float) -> State:
    """The state a fraction ``t`` along the Newton increment."""
    delta, D = s.delta, s.D.copy()
    for j, (_, c) in enumerate(p.extra):
        if c is None:
            delta += t * dx[j]
        else:
            D[c] += t * dx[j]
    return State(lam=s.lam + t * dlam, delta=delta, D=D)


def _run(p: Problem, kept: KeptFactors, max_iter: int) -> Solution:
    """Newton iterations with a halving line search on the merit, from the tractions of
    ``p.pts`` (module doc)."""
    pts, ctrl = p.pts, p.ctrl
    lam = np.vstack([pts.t_old.T, pts.lam_n[None, :]]).astype(float)
    s = State(lam=lam, delta=float(ctrl.delta), D=np.array(ctrl.D, dtype=float))
    L = laws(p, s)
    res = merit(p, s, L)
    hist = [res]
    for it in range(1, max_iter + 1):
        sets = (L.active, L.stick)
        dlam, dx = newton_step(p, s, L, kept)
        t = 1.0
        for _ in range(MAX_HALVINGS):
            trial = _update(p, s, dlam, dx, t)
            Lt = laws(p, trial)
            res_t = merit(p, trial, Lt)
            if res_t < res or res_t < p.tol:
                break
            t *= 0.5
        else:  # no decrease along the step: take it whole (the sets change)
            trial = _update(p, s, dlam, dx, 1.0)
            Lt = laws(p, trial)
            res_t = merit(p, trial, Lt)
        s, L, res = trial, Lt, res_t
        hist.append(res)
        same = np.array_equal(sets[0], L.active) and np.array_equal(sets[1], L.stick)
        if res < p.tol and same:
            return _solution(p, s, L, it, res)
    raise ContactNotConverged(
        f"semi-smooth Newton did not converge in {max_iter} iterations: relative "
        f"residual {hist[-1]:.3e} (tolerance {p.tol:.1e}); last residuals "
        + ", ".join(f"{v:.2e}" for v in hist[-5:]))


def _solution(p: Problem, s: State, L: Laws, it: int, res: float) -> Solution:
    """The solution of state ``s``; ``p.pts`` takes its tractions (the next solve's
    start)."""
    pts, n = p.pts, p.pts.n
    pn = np.where(L.active, np.maximum(s.lam[2], 0.0), 0.0)
    t = np.where(L.active[:, None], s.lam[:2].T, 0.0)
    pts.lam_n = pn.copy()
    pts.t_old = t.copy()
    stick = L.active if p.law.stuck else L.stick
    state = np.where(stick, STICK, np.where(L.active, SLIP, OPEN))
    ev = Evaluation(gn=L.gn, pn=pn, t=t, gt=L.gt, state=state, T=np.zeros((n, 3, 3)),
                    Tdelta=np.zeros((n, 3)), TD=np.zeros((n, 3, 2)))
    return Solution(u=p.op.u(np.vstack([t.T, pn[None, :]])), delta=s.delta, D=s.D,
                    ev=ev, iterations=it, residual=res)
