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
:func:`fem_reference.contact.augmented.unknowns`.  Each iteration solves one dense system on the
active set (open nodes: ``λ = 0`` exactly), started from the previous state's tractions
and so from its active sets.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cases.result import OPEN, SLIP, STICK

from .augmented import ContactNotConverged, Control, Solution, unknowns
from .compliance import NodalCompliance
from .kept_factors import KeptFactors
from .laws import Evaluation, Law, Points, norm_with
from .threads import blas_threads

MAX_ITER = 100  # Newton iterations of one solve
MAX_HALVINGS = 10  # line search


@dataclass
class _State:
    lam: np.ndarray  # (3, n): λ_x, λ_y, λ_n
    delta: float
    D: np.ndarray


@dataclass
class _Laws:
    """The Alart–Curnier functions at one state (module doc) and what their Newton step
    needs."""

    F: np.ndarray  # (3, n) [MPa]
    Fe: np.ndarray  # control residuals
    gn: np.ndarray
    gt: np.ndarray  # (n, 2)
    active: np.ndarray
    stick: np.ndarray
    slip: np.ndarray
    rho: np.ndarray
    tstar: np.ndarray  # (n, 2)
    nrm: np.ndarray


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
    Raises :class:`~fem_reference.contact.augmented.ContactNotConverged` with the residual.
    """
    with blas_threads(1):
        return _Solver(op, law, pts, ctrl, cw, tol, kept or KeptFactors()).run(
            max_iter or MAX_ITER)


class _Solver:
    def __init__(self, op: NodalCompliance, law: Law, pts: Points, ctrl: Control,
                 cw: float | np.ndarray, tol: float, kept: KeptFactors):
        self.op, self.law, self.pts, self.ctrl, self.tol = op, law, pts, ctrl, tol
        self.kept = kept
        n = pts.n
        self.cw = np.broadcast_to(np.asarray(cw, dtype=float), (n,)).copy()
        self.extra = unknowns(ctrl)
        diag = np.diag(op.HW).reshape(3, n)  # self-compliance of each node [mm/MPa]
        # components the surface cannot move (tangential on a symmetry plane, or every
        # tangential one of a model without tangential coupling): a stick condition
        # there holds whatever the traction, which symmetry sets to 0 (:meth:`step`)
        self.dead = diag <= 1e-12 * diag.max()
        # r: the nodal stiffness, softened by the wear compliance like the penalty law's
        # (k_n / (1 + k_n c_w)): ⟨λ_n − r g̃_n⟩ then holds a pressed node's λ_n at g_n = 0
        r = 1.0 / np.where(self.dead[2], np.inf, diag[2])
        self.r = r / (1.0 + r * self.cw)
        mu2 = float(np.linalg.eigvalsh(law.M2).max()) if law.mode != "frictionless" else 1.0
        c_t = diag[:2].max(axis=0)
        c_t = np.where(c_t > 0, c_t, diag[2])
        self.r_t = 1.0 / (c_t * max(mu2, 1e-300))

    # ------------------------------------------------------------------ functions

    def laws(self, s: _State) -> _Laws:
        law, pts, ctrl = self.law, self.pts, self.ctrl
        lam = s.lam
        d = self._displacements(lam)
        gn = pts.h + pts.wear_a + pts.wear_b - s.delta + d[2]
        gt = s.D[None, :] + d[:2].T
        aug = lam[2] - self.r * (gn + self.cw * lam[2])
        active = (aug > 0.0) & pts.inside
        rho = np.where(active, aug, 0.0)
        F = np.empty_like(lam)
        F[2] = lam[2] - rho
        n = pts.n
        tstar = np.zeros((n, 2))
        nrm = np.zeros(n)
        stick = np.zeros(n, bool)
        slip = np.zeros(n, bool)
        if law.mode == "frictionless":
            F[:2] = lam[:2]
        elif law.mode == "sliding":  # λ_t = c λ_n where pressed (= c ρ at the solution)
            F[:2] = lam[:2] - law.slide_traction[:, None] * np.where(active, lam[2], 0.0)
            slip = active
        else:
            tstar = lam[:2].T - self.r_t[:, None] * ((gt - pts.gt_old) @ law.M2.T)
            nrm = norm_with(law.M2inv, tstar)
            slip = active & (nrm > rho)
            stick = active & ~slip
            proj = np.where(stick[:, None], tstar, 0.0)
            proj[slip] = (rho[slip] / nrm[slip])[:, None] * tstar[slip]
            F[:2] = lam[:2] - proj.T
        w, sym = pts.w, ctrl.sym
        Fe = []
        for kind, c in self.extra:
            if kind == "delta":
                Fe.append(w @ lam[2] - ctrl.P / sym)
            elif kind == "approach":
                Fe.append(s.delta + ctrl.compliance * sym * (w @ lam[2]) - ctrl.approach)
            elif kind == "shift":
                Fe.append(s.D[c] + ctrl.compliance_t * sym * (w @ lam[c]) - ctrl.shift[c])
            else:
                Fe.append(w @ lam[c] - ctrl.Q[c] / sym)
        return _Laws(F=F, Fe=np.asarray(Fe, float), gn=gn, gt=gt, active=active,
                     stick=stick, slip=slip, rho=rho, tstar=tstar, nrm=nrm)

    def _displacements(self, lam: np.ndarray) -> np.ndarray:
        """``HW λ`` (3, n); decoupled: the normal and tangential blocks alone."""
        HW, n = self.op.HW, self.pts.n
        if not self.op.decoupled:
            return (HW @ lam.ravel()).reshape(3, n)
        d = np.empty_like(lam)
        d[:2] = (HW[:2 * n, :2 * n] @ lam[:2].ravel()).reshape(2, n)
        d[2] = HW[2 * n:, 2 * n:] @ lam[2]
        return d

    def merit(self, s: _State, L: _Laws) -> float:
        """The largest function over the largest pressure; a control's over its scale
        (the load, or the nodal load of the largest pressure; the approach; the shift)."""
        ctrl, w = self.ctrl, self.pts.w
        p = max(float(s.lam[2].max(initial=0.0)), float(L.rho.max(initial=0.0)), 1e-300)
        load = max(abs(ctrl.P or 0.0), *(abs(q or 0.0) for q in ctrl.Q)) / ctrl.sym
        ls = load if load > 0 else p * float(w.sum())
        out = float(np.abs(L.F).max(initial=0.0)) / p
        for (kind, c), f in zip(self.extra, L.Fe, strict=True):
            if kind == "approach":
                scale = abs(ctrl.approach)
            elif kind == "shift":
                scale = max(abs(ctrl.shift[c]), abs(ctrl.compliance_t) * ctrl.sym * ls, 1e-300)
            else:
                scale = ls
            out = max(out, abs(f) / scale)
        return out

    # ------------------------------------------------------------------ Newton step

    def step(self, s: _State, L: _Laws) -> tuple[np.ndarray, np.ndarray]:
        """The Newton increment (Δλ (3, n), Δ of the control unknowns) on the active set;
        λ of every other component is set to zero (frictionless: λ_t; open: all)."""
        law, HW, n = self.law, self.op.HW, self.pts.n
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
        na, ne = act.size, len(self.extra)
        if na == 0 and any(c is None for _, c in self.extra):
            raise ContactNotConverged(
                "semi-smooth Newton: no node in contact under a prescribed load (the "
                f"iterate lost the contact; relative residual {self.merit(s, L):.3e})")
        nk = cols.size
        cw = self.cw[act]
        J = np.zeros((nk + ne, nk + ne))
        # every kept row starts as the nodal compliance of its component: Δd on the
        # kept unknowns (the rows of the kept components are the kept unknowns' indices)
        J[:nk, :nk] = self.op.block(cols)
        if law.mode == "sliding":  # the tangential tractions c Δλ_n of the kept Δλ_n
            c = law.slide_traction
            J[:nk, :nk] += c[0] * HW[np.ix_(cols, act)] + c[1] * HW[np.ix_(cols, n + act)]
        b = np.zeros(nk + ne)
        iz = (len(comps) - 1) * na + np.arange(na)  # the λ_n block of the kept unknowns
        # normal rows (in mm): −Δδ + Δd_z + c_w Δλ_n = −g̃_n
        J[iz, iz] += cw
        b[iz] = -(L.gn[act] + cw * s.lam[2, act]) - d_e[2, act]
        ecol = {k: nk + j for j, k in enumerate(self.extra)}
        dcol = next((ecol[k] for k in self.extra if k[1] is None), None)
        if dcol is not None:
            J[iz, dcol] = -1.0
        if keep_t:
            self._tangential_rows(J, b, s, L, act, nk, d_e, ecol, dcol)
        self._control_rows(J, b, L, act, cols, dlam, ecol)
        # a dead tangential component (friction) lies on a symmetry plane: λ = 0 there
        dead = np.flatnonzero(self.dead.ravel()[cols] & (cols < 2 * n))
        J[dead] = 0.0
        J[dead, dead] = 1.0
        b[dead] = -s.lam.ravel()[cols[dead]]
        with np.errstate(divide="ignore", invalid="ignore"):
            x = self._solve(J, b, cols, na)
        if not np.isfinite(x).all():
            raise ContactNotConverged("singular semi-smooth Newton system")
        dlam_flat[cols] = x[:nk]
        if law.mode == "sliding":
            for c in (0, 1):
                dlam_flat[c * n + act] += law.slide_traction[c] * x[:nk]
        return dlam_flat.reshape(3, n), x[nk:]

    def _solve(self, J: np.ndarray, b: np.ndarray, cols: np.ndarray, na: int) -> np.ndarray:
        """``J x = b``.  Where the normal rows do not see the tangential unknowns
        (friction between identical materials: :attr:`NodalCompliance.decoupled`), the
        system is block triangular: the normal block (Δλ_n, Δδ) is solved first, then the
        tangential block (Δλ_t, ΔD) with the normal increments known — two factors of
        orders |A| and 2|A| instead of one of 3|A|."""
        nk = cols.size
        kinds = [c is None for _, c in self.extra]  # δ first (unknowns): its block is
        e0 = nk + sum(kinds)                         # rows and columns 2|A| .. e0
        if not (self.op.decoupled and self.law.mode == "friction"
                and kinds == sorted(kinds, reverse=True)):
            return self.kept.solve(J, b, cols)
        n0 = 2 * na
        if J[n0:e0, :n0].any() or J[n0:e0, e0:].any():  # a coupled row (not expected)
            return self.kept.solve(J, b, cols)
        t = np.r_[0:n0, e0:J.shape[0]]  # the tangential unknowns
        x = np.empty_like(b)
        x[n0:e0] = self.kept.part("normal").solve(
            np.ascontiguousarray(J[n0:e0, n0:e0]), b[n0:e0], cols[n0:])
        Jtt = np.empty((t.size, t.size))
        Jtt[:n0, :n0], Jtt[:n0, n0:] = J[:n0, :n0], J[:n0, e0:]
        Jtt[n0:, :n0], Jtt[n0:, n0:] = J[e0:, :n0], J[e0:, e0:]
        x[t] = self.kept.part("tangential").solve(
            Jtt, b[t] - J[t, n0:e0] @ x[n0:e0], cols[:n0])
        return x

    def _tangential_rows(self, J, b, s, L, act, nk, d_e, ecol, dcol) -> None:
        """The tangential rows of the active nodes, in place: ``J[:nk, :nk]`` holds Δd_t
        and Δd_z on entry (:meth:`step`)."""
        law = self.law
        na = act.size
        ix, iy, iz = np.arange(na), na + np.arange(na), 2 * na + np.arange(na)
        r = self.r[act]
        st, sl = L.stick[act], L.slip[act]
        dcols = [ecol.get(k) for k in (("D", 0), ("D", 1), ("shift", 0), ("shift", 1))]
        Dcol = [dcols[0] if dcols[0] is not None else dcols[2],
                dcols[1] if dcols[1] is not None else dcols[3]]
        # stick rows (in mm): ΔD + Δd_t = −Δg_t
        for c, ic in ((0, ix), (1, iy)):
            k = ic[st]
            b[k] = -(L.gt[act[st], c] - self.pts.gt_old[act[st], c]) - d_e[c, act[st]]
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
        A = (ps / rr)[:, None, None] * P * self.r_t[nodes, None, None] @ law.M2  # ρ P r_t 𝕄² / r
        # slip rows over r: [(I − ρP)Δλ_t − n̂(1 − r c_w)Δλ_n + n̂ r Δd_z + A Δd_t
        #                   − n̂ r Δδ + A ΔD] / r = −F_t / r  (A: ρ P r_t 𝕄²)
        # decoupled: Δd_t has only tangential columns, Δd_z only normal ones
        t, z = (slice(0, 2 * na), slice(2 * na, nk)) if self.op.decoupled else (
            slice(0, nk), slice(0, nk))
        dx, dy, dz = J[ix[k_sl], t], J[iy[k_sl], t], J[iz[k_sl], z]
        new_x, new_y = np.zeros((k_sl.size, nk)), np.zeros((k_sl.size, nk))
        new_x[:, t] = A[:, 0, 0, None] * dx + A[:, 0, 1, None] * dy
        new_y[:, t] = A[:, 1, 0, None] * dx + A[:, 1, 1, None] * dy
        new_x[:, z] += nhat[:, 0, None] * dz
        new_y[:, z] += nhat[:, 1, None] * dz
        IP = (np.eye(2)[None] - ps[:, None, None] * P) / rr[:, None, None]
        cwk = self.cw[nodes]
        rhs = -L.F[:2, nodes].T / rr[:, None] - (
            np.einsum("kab,kb->ka", A, d_e[:2, nodes].T) + nhat * d_e[2, nodes][:, None])
        for c, new in ((0, new_x), (1, new_y)):
            k = (ix, iy)[c][k_sl]
            J[k, :nk] = new
            J[k, nk:] = 0.0
            J[k, ix[k_sl]] += IP[:, c, 0]
            J[k, iy[k_sl]] += IP[:, c, 1]
            J[k, iz[k_sl]] += -nhat[:, c] * (1.0 - rr * cwk) / rr
            b[k] = rhs[:, c]
            if dcol is not None:
                J[k, dcol] = -nhat[:, c]
            for e in (0, 1):
                if Dcol[e] is not None:
                    J[k, Dcol[e]] = A[:, c, e]

    def _control_rows(self, J, b, L, act, cols, dlam, ecol) -> None:
        ctrl, w, n = self.ctrl, self.pts.w, self.pts.n
        nk = cols.size
        for (kind, c), i in ((k, ecol[k]) for k in self.extra):
            comp = 2 if c is None else c
            sel = (cols >= comp * n) & (cols < (comp + 1) * n)
            coeff = np.zeros(nk)
            coeff[sel] = w[cols[sel] - comp * n]
            known = float(w @ dlam[comp]) - float(coeff[sel] @ dlam.ravel()[cols[sel]])
            if kind in ("approach", "shift"):
                cs = ctrl.sym * (ctrl.compliance if kind == "approach" else ctrl.compliance_t)
                J[i, :nk] = cs * coeff
                J[i, i] = 1.0
                b[i] = -L.Fe[self.extra.index((kind, c))] - cs * known
            else:
                J[i, :nk] = coeff
                b[i] = -L.Fe[self.extra.index((kind, c))] - known

    # ------------------------------------------------------------------ iteration

    def update(self, s: _State, dlam: np.ndarray, dx: np.ndarray, t: float) -> _State:
        delta, D = s.delta, s.D.copy()
        for j, (_, c) in enumerate(self.extra):
            if c is None:
                delta += t * dx[j]
            else:
                D[c] += t * dx[j]
        return _State(lam=s.lam + t * dlam, delta=delta, D=D)

    def run(self, max_iter: int) -> Solution:
        pts, ctrl = self.pts, self.ctrl
        lam = np.vstack([pts.t_old.T, pts.lam_n[None, :]]).astype(float)
        s = _State(lam=lam, delta=float(ctrl.delta), D=np.array(ctrl.D, dtype=float))
        L = self.laws(s)
        res = self.merit(s, L)
        hist = [res]
        for it in range(1, max_iter + 1):
            sets = (L.active, L.stick)
            dlam, dx = self.step(s, L)
            t = 1.0
            for _ in range(MAX_HALVINGS):
                trial = self.update(s, dlam, dx, t)
                Lt = self.laws(trial)
                res_t = self.merit(trial, Lt)
                if res_t < res or res_t < self.tol:
                    break
                t *= 0.5
            else:  # no decrease along the step: take it whole (the sets change)
                trial = self.update(s, dlam, dx, 1.0)
                Lt = self.laws(trial)
                res_t = self.merit(trial, Lt)
            s, L, res = trial, Lt, res_t
            hist.append(res)
            same = np.array_equal(sets[0], L.active) and np.array_equal(sets[1], L.stick)
            if res < self.tol and same:
                return self.solution(s, L, it, res)
        raise ContactNotConverged(
            f"semi-smooth Newton did not converge in {max_iter} iterations: relative "
            f"residual {hist[-1]:.3e} (tolerance {self.tol:.1e}); last residuals "
            + ", ".join(f"{v:.2e}" for v in hist[-5:]))

    def solution(self, s: _State, L: _Laws, it: int, res: float) -> Solution:
        pts, n = self.pts, self.pts.n
        pn = np.where(L.active, np.maximum(s.lam[2], 0.0), 0.0)
        t = np.where(L.active[:, None], s.lam[:2].T, 0.0)
        pts.lam_n = pn.copy()
        pts.t_old = t.copy()
        state = np.where(L.stick, STICK, np.where(L.active, SLIP, OPEN))
        ev = Evaluation(gn=L.gn, pn=pn, t=t, gt=L.gt, state=state, T=np.zeros((n, 3, 3)),
                        Tdelta=np.zeros((n, 3)), TD=np.zeros((n, 3, 2)))
        return Solution(u=self.op.u(np.vstack([t.T, pn[None, :]])), delta=s.delta, D=s.D,
                        ev=ev, iterations=it, residual=res)
