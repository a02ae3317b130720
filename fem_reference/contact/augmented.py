"""Penalty contact laws at points of the contact surface and the condensed Newton solver.

Kinematics (formulation Eqs. 1-2, global frame, z into body a): at a surface point,

    g_n = h(x, y) + w_a + w_b − δ + u_n,        g_t = g_t,o + u_t,

with ``u = u^(a) − u^(b)`` the relative surface displacement, ``h`` the indenter
profile, ``w`` the wear depths and ``δ`` the rigid approach.

Laws (augmented penalty regularisation of Eqs. 7, 8, 13; multipliers λ_n, λ_t):

- normal: ``p_n = ⟨λ_n − k_n g_n⟩`` (Eq. 15 with ``p_n* = λ_n − k_n g_n``);
- friction: a predictor ``p_t* = λ_t − k_t 𝕄² Δg_t`` (the augmented traction of Eq. 16,
  Δg_t the tangential gap since the last converged state) and the radial projection onto
  the friction ellipse ``‖p_t‖_μ ≤ p_n`` (Eqs. 9, 17): ``p_t = p_n p_t*/‖p_t*‖_μ`` when
  ``‖p_t*‖_μ > p_n``.  With the 𝕄²-weighted penalty this projection is the closest point
  in the metric of the penalty, so the slip increment is ``∝ −𝕄⁻² p_t`` — the associated
  sliding rule (Eq. 13, erratum 11);
- full sliding along a unit direction d (slip of a relative to b): ``p_t = −p_n 𝕄² d/‖d‖*_μ``
  (Eq. 13 with ġ_t ∥ d, Eq. 10);
- wear (Eq. 23, backward Euler like step IV of §3.4): a step that slides every point by
  Δg adds ``Δw = p_n ‖Δg‖_i`` (Eq. 21) to each body; with the wear in the gap the
  normal law becomes ``p_n = ⟨λ_n − k_n g_n⟩/(1 + k_n c_w)`` with
  ``c_w = ‖Δg‖_i,a + ‖Δg‖_i,b``.

:func:`newton` solves the laws with the multipliers held (λ_n = 0 and λ_t the last
converged traction: the plain penalty method); :func:`augmented` updates the multipliers
to the tractions until they no longer change (Alart & Curnier 1991, the Uzawa iteration
of Eqs. 15-17), which makes the gap zero and a stick point fixed exactly, independently
of the penalty.  The points are the surface nodes with dual weights
(:mod:`fem_reference.model.nodal_basis`): one condition per node.

The elastic response is condensed onto the surface DOFs: ``u = C f`` with the nodal
forces ``f = Gᵀ W t`` on body a, and the Newton iteration works on the dense stiffness
``K = C⁻¹`` bordered by the load-control equations (P, Q).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp

from ..errors import ContactNotConverged
from .control import Control, Solution, unknowns
from .laws import Evaluation, Law, Points, evaluate, weighted_blocks
from .stiffened import StiffenedSolver
from .threads import blas_threads


def _solve_stiffened(C: np.ndarray, B: sp.spmatrix, rhs: np.ndarray,
                     lin: StiffenedSolver | None = None) -> np.ndarray:
    """Solve ``(K + B) x = rhs`` with ``K = C⁻¹`` (dense) and a sparse contact tangent B
    by the push-through identity on the DOFs of B (:mod:`fem_reference.contact.stiffened`);
    ``lin`` keeps the factors for the next solves of the same contact problem."""
    return (lin if lin is not None else StiffenedSolver(C)).solve(B, rhs)


def newton(K: np.ndarray, C: np.ndarray, law: Law, pts: Points, ctrl: Control, u0: np.ndarray, *,
           cw: float | np.ndarray = 0.0, tol: float = 1e-9, max_iter: int = 150,
           lin: StiffenedSolver | None = None) -> Solution:
    """Semi-smooth Newton iteration of the condensed contact problem.

    ``K`` is the condensed stiffness, ``C = K⁻¹`` the compliance.
    Unknowns: the relative surface displacements u, and δ (load control on P) and
    the components of g_t,o under tangential load control.  Equations:
    ``K u − Gᵀ W t(u) = 0``, ``sym Σ w p_n = P`` and ``sym Σ w p_t = Q``.
    Raises :class:`ContactNotConverged` with the residual if it does not converge.
    """
    with blas_threads(1):
        return _newton(K, C, law, pts, ctrl, u0, cw=cw, tol=tol, max_iter=max_iter,
                       lin=lin)


MAX_OUTER = 40  # multiplier updates of one augmented solve


def augmented(K: np.ndarray, C: np.ndarray, law: Law, pts: Points, ctrl: Control,
              u0: np.ndarray, *, cw: float | np.ndarray = 0.0, tol: float = 1e-9,
              max_outer: int = MAX_OUTER, lin: StiffenedSolver | None = None) -> Solution:
    """Augmented-Lagrangian solve (Alart & Curnier 1991; Eqs. 15-17 on the penalty): the
    penalty Newton solve of :func:`newton` with the multipliers λ_n = ``pts.lam_n`` and
    λ_t = ``pts.t_old`` held, then ``λ ← (p_n, p_t)``, until the multipliers change by
    less than ``tol`` times the largest pressure.  At that fixed point the gap of every
    pressed point is zero (``λ_n − k_n g_n = λ_n``) and a stick point has not slipped
    since the last converged state, whatever the penalty: the penalty sets only the rate
    (each update shrinks the constraint violation by about the ratio of the surface
    stiffness to k_n).  ``iterations`` of the result: Newton iterations of every pass.
    ``lin``: the linear solver of the Newton steps (:mod:`fem_reference.contact.stiffened`) on
    ``C``, kept by the caller to reuse its factors in the next solves (default: a new
    one for this solve).
    """
    u, delta, D = u0, float(ctrl.delta), np.array(ctrl.D, dtype=float)
    total = 0
    change = float("inf")
    lin = lin if lin is not None else StiffenedSolver(C)
    for outer in range(1, max_outer + 1):
        step_ctrl = replace(ctrl, delta=delta, D=D)
        sol = newton(K, C, law, pts, step_ctrl, u, cw=cw, tol=tol, lin=lin)
        total += sol.iterations
        ev = sol.ev
        scale = max(float(ev.pn.max(initial=0.0)), 1e-300)
        change = float(np.abs(ev.pn - pts.lam_n).max(initial=0.0))
        pts.lam_n = ev.pn.copy()
        if law.mode == "friction":  # λ_t: only the friction law with history has one
            change = max(change, float(np.abs(ev.t - pts.t_old).max(initial=0.0)))
            pts.t_old = ev.t.copy()
        change /= scale
        u, delta, D = sol.u, sol.delta, sol.D
        if change < tol:
            return Solution(u=u, delta=delta, D=D, ev=ev, iterations=total,
                            residual=sol.residual, outer=outer)
    raise ContactNotConverged(
        f"augmented Lagrangian did not converge in {max_outer} multiplier updates: "
        f"relative multiplier change {change:.3e} (tolerance {tol:.1e})"
    )


def _newton(K: np.ndarray, C: np.ndarray, law: Law, pts: Points, ctrl: Control, u0: np.ndarray,
            *, cw: float | np.ndarray, tol: float, max_iter: int, lin: StiffenedSolver | None = None
            ) -> Solution:
    eqs = _Equations(K=K, C=C, law=law, pts=pts, ctrl=ctrl, cw=cw, extra=unknowns(ctrl),
                     lin=lin)
    u = u0.copy()
    delta = float(ctrl.delta)
    D = np.array(ctrl.D, dtype=float)
    res_hist = []
    ev, f, Ru, Re = eqs.residual(u, delta, D)
    res = eqs.merit(f, Ru, Re)
    for it in range(1, max_iter + 1):
        res_hist.append(res)
        dx = eqs.newton_step(ev, Ru, Re, it, res)
        u, delta, D, (ev, f, Ru, Re), res = eqs.line_search(u, delta, D, dx, res, tol)
        if res < tol:
            return Solution(u=u, delta=delta, D=D, ev=ev, iterations=it, residual=res)
    raise ContactNotConverged(
        f"contact Newton did not converge in {max_iter} iterations: relative residual "
        f"{res_hist[-1]:.3e} (tolerance {tol:.1e}); last residuals "
        + ", ".join(f"{r:.2e}" for r in res_hist[-5:])
    )


@dataclass(frozen=True)
class _Equations:
    """The condensed contact equations of one solve: ``K u − Gᵀ W t(u) = 0`` bordered by
    the control equations ``sym Σ w p_n = P`` and ``sym Σ w p_t,c = Q_c`` for the
    unknowns ``extra`` (:func:`unknowns`)."""

    K: np.ndarray
    C: np.ndarray
    law: Law
    pts: Points
    ctrl: Control
    cw: float | np.ndarray
    extra: tuple[tuple[str, int | None], ...]
    lin: StiffenedSolver | None = None  # the kept factors (:func:`_solve_stiffened`)

    def residual(self, u: np.ndarray, delta: float, D: np.ndarray
                 ) -> tuple[Evaluation, np.ndarray, np.ndarray, np.ndarray]:
        """(evaluation, nodal forces f, residual of the u equations, of the controls)."""
        w, G, ctrl = self.pts.w, self.pts.G, self.ctrl
        ev = evaluate(self.law, self.pts, u, delta, D, self.cw)
        f = G.T @ np.concatenate([w * ev.t[:, 0], w * ev.t[:, 1], w * ev.pn])
        Ru = self.K @ u - f
        Re = []
        for kind, c in self.extra:
            if kind == "delta":
                Re.append(np.sum(w * ev.pn) - ctrl.P / ctrl.sym)
            elif kind == "approach":  # δ + c P = approach [mm]
                Re.append(delta + ctrl.compliance * ctrl.sym * np.sum(w * ev.pn) - ctrl.approach)
            elif kind == "shift":  # D_c + c_t Q_c = shift_c [mm]
                Re.append(D[c] + ctrl.compliance_t * ctrl.sym * np.sum(w * ev.t[:, c])
                          - ctrl.shift[c])
            else:
                Re.append(np.sum(w * ev.t[:, c]) - ctrl.Q[c] / ctrl.sym)
        return ev, f, Ru, np.asarray(Re, dtype=float)

    def merit(self, f: np.ndarray, Ru: np.ndarray, Re: np.ndarray) -> float:
        """Relative residual: ‖Ru‖ over the nodal forces ‖f‖, the control residuals over
        the nodal forces of the loads (‖f‖ when there are no loads), the approach's over
        the approach."""
        ctrl = self.ctrl
        load_scale = max(abs(ctrl.P or 0.0), *(abs(q or 0.0) for q in ctrl.Q)) / ctrl.sym
        fs = max(np.linalg.norm(f), 1e-300)
        ls = load_scale if load_scale > 0 else fs
        shift_scale = max(max(abs(v or 0.0) for v in ctrl.shift),
                          ctrl.compliance_t * ctrl.sym * ls, 1e-300)
        scales = [abs(ctrl.approach) if kind == "approach" else
                  shift_scale if kind == "shift" else ls for kind, _ in self.extra]
        return max(np.linalg.norm(Ru) / fs, *(np.abs(Re) / np.asarray(scales)), 0.0)

    def newton_step(self, ev: Evaluation, Ru: np.ndarray, Re: np.ndarray, it: int,
                    res: float) -> np.ndarray:
        """The Newton increment of (u, extra unknowns): the bordered Jacobian
        ``[[K + B, U], [V, W]]`` with ``B = −Gᵀ W T G`` solved by block elimination."""
        w, G, extra = self.pts.w, self.pts.G, self.extra
        m, ne = self.K.shape[0], len(extra)
        B = -(G.T @ weighted_blocks(w, ev.T) @ G)
        dcols = [ev.Tdelta if c is None else ev.TD[:, :, c] for kind, c in extra]
        U = np.empty((m, ne))
        V = np.empty((ne, m))
        W = np.empty((ne, ne))
        for j, d in enumerate(dcols):
            U[:, j] = -(G.T @ np.concatenate([w * d[:, 0], w * d[:, 1], w * d[:, 2]]))
        for i, (kind, c) in enumerate(extra):
            r = 2 if c is None else c  # row of T: p_n or t_c
            V[i] = G.T @ np.concatenate([w * ev.T[:, r, 0], w * ev.T[:, r, 1], w * ev.T[:, r, 2]])
            for j, d in enumerate(dcols):
                W[i, j] = np.sum(w * d[:, r])
            if kind in ("approach", "shift"):  # displacement equations: rows × c sym, + 1
                cs = self.ctrl.sym * (self.ctrl.compliance if kind == "approach"
                                      else self.ctrl.compliance_t)
                V[i] *= cs
                W[i] *= cs
                W[i, i] += 1.0
        try:
            X = _solve_stiffened(self.C, B, np.column_stack([-Ru, U]), self.lin)
            xu, Xu = X[:, 0], X[:, 1:]
            dx_e = la.solve(W - V @ Xu, -Re - V @ xu) if ne else np.zeros(0)
        except (la.LinAlgError, ValueError) as exc:
            raise ContactNotConverged(
                f"singular contact Jacobian at iteration {it} (residual {res:.3e}): {exc}"
            ) from None
        return np.concatenate([xu - Xu @ dx_e, dx_e])

    def line_search(self, u: np.ndarray, delta: float, D: np.ndarray, dx: np.ndarray,
                    res: float, tol: float) -> tuple:
        """Backtracking on the residual norm (the laws are only piecewise smooth): halve
        the step until the merit decreases (at most 12 times).  Returns the new
        ``(u, delta, D, residual(...), merit)``."""
        m = self.K.shape[0]
        step = 1.0
        for _ in range(12):
            u_t = u + step * dx[:m]
            delta_t, D_t = delta, D.copy()
            for j, (_, c) in enumerate(self.extra):
                if c is None:
                    delta_t += step * dx[m + j]
                else:
                    D_t[c] += step * dx[m + j]
            trial = self.residual(u_t, delta_t, D_t)
            res_t = self.merit(*trial[1:])
            if res_t < res or res_t < tol:
                break
            step *= 0.5
        return u_t, delta_t, D_t, trial, res_t
