"""One contact step of section 3.4: normal and frictional tractions on the grid.

``ContactSolver.solve`` takes the separation profile ``h`` (geometric gap + wear, Eq. 29
without the rigid approach), the normal control (load P or approach), the tangential
control (load Q, rigid shift g_t,o, or gross sliding) and the state of the previous
step (its tangential displacement g_t^(k-1), Eq. 23/30) and returns the tractions, the
slip increment and the contact states.  For dissimilar materials (K != 0, Eq. 6) the
normal and tangential problems are coupled and solved alternately until both
complementarity residuals are below tolerance; for K = 0 one pass is exact.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cases.model import CaseError, Friction, Grid
from cases.result import OPEN, SLIP, STICK

from .friction import mu_norm
from .materials import Materials
from .normal import (
    ContactNotConverged,
    NormalSolution,
    normal_residual,
    roundoff_floor,
)
from .operator import SurfaceOperator
from .tangential import TangentialSolution, solve_tangential, tangential_residual
from .tangential_load import shift_for_resultant
from .window import WindowedNormal

SLIP_RTOL = 1e-6  # a contact cell slips when its traction is on the friction limit


def _tangential_bound(op: SurfaceOperator) -> float:
    """Largest eigenvalue of the padded circulant of A_tt (2 x 2 symbol per frequency),
    an upper bound of the aperiodic block it contains."""
    s = op.spectra
    half = 0.5 * (s["xx"].real - s["yy"].real)
    return float((0.5 * (s["xx"].real + s["yy"].real)
                  + np.sqrt(half**2 + s["xy"].real ** 2)).max())


class ContactAtEdge(RuntimeError, CaseError):
    """The contact area reaches the edge of the potential contact grid: the case's grid
    is too small (also a CaseError: the user enlarges grid.Lx/grid.Ly)."""


@dataclass
class ContactState:
    """What a step hands to the next: tractions, rigid motion and g_t (Eq. 30)."""

    p_n: np.ndarray
    p_x: np.ndarray
    p_y: np.ndarray
    g_x: np.ndarray  # total tangential gap g_t = g_t,o + u_t at the end of the step
    g_y: np.ndarray
    shift_x: float = 0.0  # rigid tangential displacement g_t,o
    shift_y: float = 0.0
    approach: float = 0.0
    #: the secant dQ/ds of a step whose transverse shift was free (mixed control): it
    #: starts the search of the same step of the next cycle (None: none)
    dQ_ds: np.ndarray | None = None

    @classmethod
    def initial(cls, shape: tuple[int, int]) -> ContactState:
        z = np.zeros(shape)
        return cls(z, z.copy(), z.copy(), z.copy(), z.copy())


@dataclass
class StepSolution:
    state: ContactState
    gap: np.ndarray
    slip_x: np.ndarray
    slip_y: np.ndarray
    status: np.ndarray  # OPEN / STICK / SLIP per cell
    P: float
    Qx: float
    Qy: float
    iterations: int
    residual_n: float
    residual_t: float


class ContactSolver:
    """Contact steps on one grid with one material pair and friction law."""

    def __init__(self, grid: Grid, mat: Materials, friction: Friction, *,
                 method: str = "cg", tol: float = 1e-10, max_iter: int = 20000):
        if method not in ("cg", "uzawa"):
            raise ValueError(f"unknown method {method!r}")
        self.grid, self.mat, self.friction = grid, mat, friction
        self.method, self.tol, self.max_iter = method, tol, max_iter
        self.op = SurfaceOperator(grid.nx, grid.ny, grid.dx, grid.dy, mat)
        self.dA = grid.dx * grid.dy
        self.normal_solver = WindowedNormal((grid.nx, grid.ny), grid.dx, grid.dy, mat, method,
                                            tol, max_iter, full_op=self.op)
        self._boxes: dict[tuple[int, int], tuple[SurfaceOperator, float]] = {}
        self.c_n = 1.0 / self.op.self_zz
        self.c_t = 1.0 / self.op.self_tt

    # ------------------------------------------------------------------ pieces
    def _normal(self, h, P, approach, p0, wear_rate=None) -> NormalSolution:
        """Normal solve on the potential-contact window (:mod:`halfspace.window`);
        ``wear_rate`` k_w adds the implicit wear k_w p_n to the gap."""
        return self.normal_solver.solve(h, P=P, approach=approach, p0=p0, wear_rate=wear_rate)

    def _box_operator(self, n: tuple[int, int]) -> tuple[SurfaceOperator, float]:
        """Tangential operator on an n-cell sub-grid and its Lipschitz bound (cached)."""
        if n not in self._boxes:
            if len(self._boxes) > 64:
                self._boxes.clear()
            op = SurfaceOperator(*n, self.grid.dx, self.grid.dy, self.mat)
            self._boxes[n] = (op, _tangential_bound(op))
        return self._boxes[n]

    def _tangential(self, shift, u_tn, g_prev, p_n, p0, tol=None) -> TangentialSolution:
        """Tractions for fixed p_n (to the residual ``tol``, default the solver's).  Cells
        with p_n = 0 carry none, so the problem lives on the bounding box of the contact:
        the same coefficients (they depend on the offset only, Eq. 42) convolved on a
        smaller padded grid."""
        b_x = shift[0] + u_tn[0] - g_prev[0]
        b_y = shift[1] + u_tn[1] - g_prev[1]
        rows, cols = np.flatnonzero(p_n.any(axis=1)), np.flatnonzero(p_n.any(axis=0))
        if rows.size == 0:
            return TangentialSolution(np.zeros_like(p_n), np.zeros_like(p_n), 0, 0.0)
        box = np.s_[rows[0]:rows[-1] + 1, cols[0]:cols[-1] + 1]
        op, L = self._box_operator((rows[-1] + 1 - rows[0], cols[-1] + 1 - cols[0]))
        sol = solve_tangential(op.tangential, b_x[box], b_y[box], p_n[box], self.friction, L,
                               self.c_t, p0=(p0[0][box], p0[1][box]), method=self.method,
                               tol=tol or self.tol, max_iter=self.max_iter)
        p_x, p_y = np.zeros_like(p_n), np.zeros_like(p_n)
        p_x[box], p_y[box] = sol.p_x, sol.p_y
        return TangentialSolution(p_x, p_y, sol.iterations, sol.residual)

    def _tangential_load(self, Q, shift0, u_tn, g_prev, p_n, p0, free=None, dQ_ds=None):
        """Find the rigid shift g_t,o that makes the tangential resultant equal Q (a.1);
        with ``free`` (a unit vector) only the shift along ``free`` is found, for a
        resultant along it of zero, the rest of ``shift0`` held (mixed control), the
        search started from the secant ``dQ_ds`` if given.  Returns (tractions, shift,
        iterations, the last secant)."""
        fr = self.friction
        Q = np.zeros(2) if free is not None else np.asarray(Q, float)
        P = p_n.sum() * self.dA
        qn = np.hypot(*Q)
        if qn > 0:
            # resultants the friction can carry: P times the friction ellipse, ||Q||_mu <= P
            capacity = P / float(mu_norm(Q[0] / qn, Q[1] / qn, fr))
            if qn >= capacity * (1 - 1e-9):
                raise ContactNotConverged(
                    f"tangential load |Q| = {qn:.6g} N reaches the friction capacity "
                    f"{capacity:.6g} N: gross sliding, use load.sliding instead")
        if free is not None and P == 0:  # no contact: no tractions, any shift will do
            return self._tangential(shift0, u_tn, g_prev, p_n, p0), shift0, 0, dQ_ds
        # Mindlin stick stiffness 8 G* a, 1/G* = 2 (2 - nu) / G (Eq. 6 averages); the
        # resultant on body a opposes the shift of a: dQ/dg_t,o = -k_t in full stick
        a_eff = np.sqrt(np.count_nonzero(p_n > 0) * self.dA / np.pi)
        k_t = 4.0 * a_eff * self.mat.G / (2.0 - self.mat.nu)
        basis = np.eye(2) if free is None else np.asarray(free, float).reshape(2, 1)
        J = -np.eye(basis.shape[1]) * k_t
        if dQ_ds is not None and np.shape(dQ_ds) == J.shape:
            J = np.asarray(dQ_ds, float)
        max_step = 2.0 * P * max(fr.mu1, fr.mu2) / k_t  # twice the gross-slip shift
        if free is not None:
            # in gross slip Qy turns with the direction of the slip increment, which the
            # shift across the motion sets on the scale of the motion itself: a nearly
            # unloaded contact's gross-slip shift would cap the search far below it
            max_step = max(max_step, float(np.linalg.norm(shift0)))
        # the resultant's scale: |Q|, or a small share of the friction's when Q nearly
        # vanishes on a load path; under mixed control the friction's itself, since the
        # imposed component's resultant is only as accurate as the solves (module doc of
        # tangential_load: about tol P)
        scale = (P * max(fr.mu1, fr.mu2) if free is not None else
                 max(qn, 1e-3 * P * max(fr.mu1, fr.mu2)))

        def solve_at(zeta, start, tol):
            return self._tangential(zeta, u_tn, g_prev, p_n, start, tol)

        return shift_for_resultant(solve_at, basis.T @ Q, np.asarray(shift0, float), p0,
                                   J=J, max_step=max_step, scale=scale, P=P, dA=self.dA,
                                   tol=self.tol, basis=basis)

    # ------------------------------------------------------------------ a step
    def solve(
        self,
        h: np.ndarray,
        *,
        P: float | None = None,
        approach: float | None = None,
        Q: tuple[float, float] | None = None,
        shift: tuple[float, float] | None = None,
        free: tuple[float, float] | None = None,
        prev: ContactState | None = None,
        wear_rate: np.ndarray | None = None,
        guess: ContactState | None = None,
        check_edge: bool = True,
    ) -> StepSolution:
        """Solve one step. Tangential control: ``Q`` (load) or ``shift`` (g_t,o, total);
        neither: the rigid shift of ``prev`` is held.  ``free`` (a unit vector, with
        ``shift``): the shift along ``free`` is not imposed but found so that the
        resultant along it vanishes (``shift``'s part along it only starts the search).
        ``wear_rate`` (mm/MPa per cell) makes the wear of the step implicit: the gap
        gains ``wear_rate * p_n`` (Eq. 23, 29 with a known slip norm); the returned gap
        includes it.  ``guess`` only starts the iterations (default: ``prev``'s
        tractions); the slip history is ``prev``'s."""
        prev = prev or ContactState.initial((self.grid.nx, self.grid.ny))
        if shift is None:
            shift = (prev.shift_x, prev.shift_y)
        shift = np.asarray(shift, float)
        if Q is not None and free is not None:
            raise ValueError("give Q or free, not both")
        nsol, tsol, shift, iters, dQ_ds = self._tractions(h, P, approach, Q, shift, prev,
                                                          guess or prev, wear_rate, free)
        sol = self._assemble(h, approach, nsol, tsol, shift, prev, wear_rate, iters,
                             check_edge)
        sol.state.dQ_ds = dQ_ds
        return sol

    def _tractions(self, h, P, approach, Q, shift, prev: ContactState, start: ContactState,
                   wear_rate, free=None
                   ) -> tuple[NormalSolution, TangentialSolution, np.ndarray, int,
                              np.ndarray | None]:
        """The normal and tangential tractions of a step: one normal and one tangential
        solve when they decouple (K = 0 or no friction), else alternating solves until
        the normal problem is consistent with the tangential tractions (Eq. 6, K != 0).
        Returns (normal solution, tangential solution, rigid shift, iterations, the
        secant dQ/ds of a free transverse shift or None)."""
        shape = (self.grid.nx, self.grid.ny)
        frictional = self.friction.mu1 > 0
        coupled = self.op.coupled and frictional
        p_x, p_y = start.p_x, start.p_y
        p_n0 = start.p_n if np.any(start.p_n > 0) else None
        g_prev = (prev.g_x, prev.g_y)
        iters, zero, dQ_ds = 0, np.zeros(shape), start.dQ_ds if free is not None else None
        for _ in range(200 if coupled else 1):
            h_n = h + self.op.normal_from_tangential(p_x, p_y) if coupled else h
            nsol = self._normal(h_n, P, approach, p_n0, wear_rate)
            iters += nsol.iterations
            if not frictional:
                return nsol, TangentialSolution(zero, zero.copy(), 0, 0.0), shift, iters, None
            u_tn = self.op.tangential_from_normal(nsol.p_n)
            if Q is not None or free is not None:
                tsol, shift, it_t, J = self._tangential_load(Q, shift, u_tn, g_prev,
                                                             nsol.p_n, (p_x, p_y), free, dQ_ds)
                dQ_ds = J if free is not None else None
            else:
                tsol = self._tangential(shift, u_tn, g_prev, nsol.p_n, (p_x, p_y))
                it_t = tsol.iterations
            iters += it_t
            if not coupled:
                return nsol, tsol, shift, iters, dQ_ds
            change = np.hypot(np.linalg.norm(tsol.p_x - p_x), np.linalg.norm(tsol.p_y - p_y))
            p_x, p_y, p_n0 = tsol.p_x, tsol.p_y, nsol.p_n
            # converged when the normal problem is consistent with the new tractions
            h_chk = h + self.op.normal_from_tangential(p_x, p_y)
            g_chk = h_chk + self.op.normal(nsol.p_n) - nsol.approach
            if wear_rate is not None:
                g_chk = g_chk + wear_rate * nsol.p_n
            if (normal_residual(nsol.p_n, g_chk, self.c_n,
                                roundoff_floor(self.c_n, h_chk, approach)) < self.tol
                    and change <= self.tol * np.linalg.norm(nsol.p_n)):
                return nsol, tsol, shift, iters, dQ_ds
        raise ContactNotConverged("normal-tangential coupling (K != 0) did not converge "
                                  f"in 200 passes: traction change {change:.3e}")

    def _assemble(self, h, approach, nsol: NormalSolution, tsol: TangentialSolution,
                  shift: np.ndarray, prev: ContactState, wear_rate, iters: int,
                  check_edge: bool) -> StepSolution:
        """The step from its tractions: gap (Eq. 1), slip (Eq. 2), stick/slip/open state,
        the residuals of both problems re-checked once on the assembled step."""
        frictional = self.friction.mu1 > 0
        g_prev = (prev.g_x, prev.g_y)
        p_n = nsol.p_n
        u_x, u_y, u_z = self.op(tsol.p_x, tsol.p_y, p_n)
        gap = h + u_z - nsol.approach
        if wear_rate is not None:
            gap = gap + wear_rate * p_n
        g_x, g_y = shift[0] + u_x, shift[1] + u_y
        slip_x, slip_y = g_x - g_prev[0], g_y - g_prev[1]
        status = np.where(p_n > 0, STICK, OPEN)
        if frictional:
            on_limit = mu_norm(tsol.p_x, tsol.p_y, self.friction) >= (1 - SLIP_RTOL) * p_n
            status = np.where((p_n > 0) & on_limit, SLIP, status)
        else:
            status = np.where(p_n > 0, SLIP, OPEN)
        if check_edge:
            self._check_edge(p_n)
        res_t = (tangential_residual(tsol.p_x, tsol.p_y, slip_x, slip_y, p_n, self.friction,
                                     self.c_t) if frictional and np.any(p_n > 0) else 0.0)
        res_n = normal_residual(p_n, gap, self.c_n, roundoff_floor(self.c_n, h, approach))
        if max(res_n, res_t) > 100 * self.tol:  # the assembled step, checked once more
            raise ContactNotConverged(
                f"contact step inconsistent after convergence: residuals normal {res_n:.3e}, "
                f"tangential {res_t:.3e} (tol {self.tol:.1e})")
        state = ContactState(p_n, tsol.p_x, tsol.p_y, g_x, g_y, float(shift[0]),
                             float(shift[1]), float(nsol.approach))
        return StepSolution(
            state=state, gap=gap, slip_x=slip_x, slip_y=slip_y, status=status,
            P=float(p_n.sum() * self.dA), Qx=float(tsol.p_x.sum() * self.dA),
            Qy=float(tsol.p_y.sum() * self.dA), iterations=iters,
            residual_n=res_n, residual_t=res_t)

    def _check_edge(self, p_n: np.ndarray) -> None:
        contact = p_n > 0
        if contact[0].any() or contact[-1].any() or contact[:, 0].any() or contact[:, -1].any():
            raise ContactAtEdge(
                "the contact area reaches the edge of the potential contact grid "
                f"({self.grid.Lx} x {self.grid.Ly} mm): enlarge grid.Lx/grid.Ly")
