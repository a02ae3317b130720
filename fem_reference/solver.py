"""``solve(case)``: the FEM reference run of a case, in the common result format.

Load path:

- static cases: the normal load (or approach) first — in one step for identical
  materials (no normal–tangential coupling), in 5 increments otherwise — then a
  tangential load (Qx, Qy) or shift in 5 increments with the friction history (return
  map); full sliding (``load.sliding``) prescribes the slip direction instead (Eq. 13).
  One output step (``step = 0``) with the final state.
- ``sliding_wear`` (pin-on-disk): constant load; step k slides every contact point by
  ``sliding_wear.step`` along ``load.slide_angle`` and adds the wear of Eq. 23 to each
  body (backward Euler, as step IV of §3.4).  The condensed stiffness is reused for every
  step.  Output steps: ``step = round(s / sliding_wear.step)`` for s = 0, the
  ``output_s`` distances and the total distance (every step if ``output_s`` is empty).

Surface fields on the case grid (cell centres; a quarter/half model is mirrored, and
components odd under a mirror vanish on the mirror plane):
``p_n`` is the L2 projection of the Gauss-point penalty pressure on the P2 surface space,
limited to the range of the Gauss-point values around each point (see
:meth:`_Run._recover`: the projection rings where the traction falls to zero inside a
facet, at the edge of a worn flat), ``p_x, p_y`` the limited L2 projections of the
tangential tractions on P1 (:meth:`_Run._recover_p1`: the Gauss-point values oscillate
at the stick–slip boundary), all zero outside the contact; ``gap`` from the full FE
displacements;
``state``: a cell is closed inside the contact boundary r(θ), the outermost point with
a gap below ``GAP_TOL`` × δ0 along rays from the centre (robust against the penalty:
see :func:`contact_states`), stick or slip by the return map evaluated at the cell
centre with its own history; ``wear_a/b`` likewise; ``slip_x/y`` the relative
tangential displacement increment of the step (tangential loading: since the end of the
normal loading; static full sliding: the unit slip direction).

Scalars: ``P, Qx, Qy`` the resultants of the Gauss-point tractions; ``contact_area`` the
area inside r(θ), ``stick_area`` the Gauss-point integral of the stick states,
``slip_area`` the rest; ``a_x, a_y`` half the closed length of the lines through the
centre; ``p_max`` the largest nodal value of the limited projected pressure; ``vm_max`` and its
location over both planes (the plane samples); ``wall_s`` the time since ``solve``
started.  Extra: ``approach`` (δ), ``shift_x/y`` (g_t,o), ``P_reaction`` (the support
reaction of the block: global equilibrium), ``vm_axis_max``/``vm_axis_z`` (the on-axis
σ_VM maximum and its depth from a least-squares cubic, :func:`axis_peak`).

Extra outputs: ``RunResult.tables["axis/<step>"]`` holds the stresses on the load axis
(x0, y0) at 8x the plane resolution in depth; ``tables["line_x/<step>"]`` and
``["line_y/<step>"]`` the projected tractions, the gap and the states along the lines
through the centre; ``RunResult.meta["vtu"]`` a list of ``(step, meshio.Mesh)`` with the
FE fields of the reported body (write them with :func:`fem_reference.vtu.write_vtu`);
``meta`` also gives the model (quarter/half/full), DOFs, penalty and timings.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict

import numpy as np
import scipy.sparse.linalg as spla

from cases.model import Case, CaseError
from cases.result import OPEN, SLIP, STICK, Plane, RunResult, StepResult, von_mises

from .contact import Control, Points, evaluate, newton
from .model import FemError, FemModel, FemUnsupported, slide_direction, wear_compliances
from .stresses import COMPONENTS, PointLocator, sample_stresses
from .vtu import fields_mesh

N_NORMAL_DISSIMILAR = 5
N_TANGENTIAL = 5


GAP_TOL = 1e-4  # a gap below GAP_TOL * a_ref²/R (the Hertz approach) counts as closed
AXIS_FIT_WINDOW = 0.3  # half-width of the axis σ_VM fit window, in contact semi-widths


def contact_states(ev, eps: float) -> np.ndarray:
    """Output states: closed (gap < eps) points are stick or slip, the others open.

    The penalty law loads only penetrating points, and near the contact edge the sign of
    a gap of the order of the FE interpolation error (≪ p/k_n) decides; counting gaps
    below a tolerance ε as closed makes the contact region independent of the penalty.
    Outside the contact the Hertz gap grows like δ (r/a − 1)^(3/2), so ε = 1e-4 δ moves
    the edge by about 0.2 % of a.
    """
    closed = ev.gn < eps
    return np.where(closed, np.where(ev.state == STICK, STICK, SLIP), OPEN).astype(np.int8)


def _semi_width(s: np.ndarray, gn: np.ndarray, inside: np.ndarray, eps: float) -> float:
    """Half the length of the closed interval (gap < eps) of a line, interpolated."""
    g = gn - eps
    c = (g < 0) & inside
    if not c.any():
        return 0.0
    idx = np.nonzero(c)[0]
    i0, i1 = idx[0], idx[-1]
    left = s[i0]
    if i0 > 0:
        left = s[i0 - 1] + (s[i0] - s[i0 - 1]) * g[i0 - 1] / (g[i0 - 1] - g[i0])
    right = s[i1]
    if i1 < s.size - 1:
        right = s[i1] + (s[i1 + 1] - s[i1]) * g[i1] / (g[i1] - g[i1 + 1])
    return 0.5 * (right - left)


def _ray_extent(r: np.ndarray, gn: np.ndarray, inside: np.ndarray, eps: float) -> np.ndarray:
    """Radius of the outermost closed point (gap < eps) along each ray (rows), interpolated."""
    g = gn - eps
    c = (g < 0) & inside
    n = r.size
    last = n - 1 - np.argmax(c[:, ::-1], axis=1)
    out = np.where(c.any(axis=1), r[last], 0.0)
    k = np.nonzero(c.any(axis=1) & (last < n - 1))[0]
    j = last[k]
    g0, g1 = g[k, j], g[k, j + 1]
    out[k] = r[j] + (r[j + 1] - r[j]) * g0 / (g0 - g1)
    return out


def axis_peak(z: np.ndarray, vm: np.ndarray, window: float) -> tuple[float, float]:
    """(max σ_VM, depth) on the load axis from a least-squares cubic around the sample max.

    Along the axis σ_VM is flat near its maximum (closed-form Hertz, ν = 0.3: 0.2 %
    below the peak 0.03 a away), so the depth of the largest FE sample is decided by
    discretisation noise of that size; the fit over ±``window`` averages it out.  On the
    closed form a ±0.3 a window shifts the peak by 0.001 a.  A maximum at the surface
    is returned as sampled.
    """
    i = int(np.argmax(vm))
    if i == 0:
        return float(vm[0]), float(z[0])
    sel = np.abs(z - z[i]) <= window
    if sel.sum() < 6:
        return float(vm[i]), float(z[i])
    c = np.polyfit(z[sel], vm[sel], 3)
    roots = np.roots(np.polyder(c))
    roots = roots[np.isreal(roots)].real
    roots = roots[(roots >= z[sel].min()) & (roots <= z[sel].max())]
    if roots.size == 0:
        return float(vm[i]), float(z[i])
    best = roots[np.argmax(np.polyval(c, roots))]
    return float(np.polyval(c, best)), float(best)


class _Run:
    def __init__(self, model: FemModel, *, vtu: bool):
        self.model = m = model
        case = model.case
        self.case = case
        self.vtu = vtu
        self.t0 = time.perf_counter()
        surf = m.surface
        R = case.R
        self.Gq_full = surf.operator(surf.Nq)  # all surface DOFs (forces on the blocks)
        self.quad = Points(G=self.Gq_full[:, m.cidx].tocsr(), w=surf.quad_w, xy=surf.quad_xy,
                           h=(surf.quad_xy**2).sum(axis=1) / (2 * R),
                           inside=np.ones(surf.quad_w.size, bool))
        # probes: grid cell centres, then the x and y lines through the centre
        g = case.grid
        X, Y = np.meshgrid(g.x, g.y, indexing="ij")
        grid_xy = np.column_stack([X.ravel(), Y.ravel()])
        r = surf.r_c
        nl = int(math.ceil(2 * r / (m.h / 20.0))) + 1
        self.line = np.linspace(-r, r, nl)
        lx = np.column_stack([self.line, np.zeros(nl)])
        ly = np.column_stack([np.zeros(nl), self.line])
        # rays from the centre over the modelled sector: the contact boundary r(θ)
        sector = {"quarter": 0.5 * math.pi, "half": math.pi, "full": 2 * math.pi}[m.shape]
        n_theta = int(round(sector / (0.5 * math.pi) * 24))
        self.theta = np.linspace(0.0, sector, n_theta + (m.shape != "full"),
                                 endpoint=m.shape != "full")
        self.ray_r = np.linspace(0.0, r, nl // 2 + 1)
        rays = (self.ray_r[None, :, None]
                * np.stack([np.cos(self.theta), np.sin(self.theta)], -1)[:, None, :])
        xy = np.vstack([grid_xy, lx, ly, rays.reshape(-1, 2)])
        self.ngrid = grid_xy.shape[0]
        self.nline = nl
        mapped, self.sx, self.sy = m.sym.map(xy)
        N, found = surf.interpolation(mapped)
        self.Nprobe = N
        facet, _ = surf.locate(mapped)
        # per probe: the surface nodes around it (of its facet) for the limiter of _recover
        self.probe_nodes = np.where(found[:, None], surf.facets[np.maximum(facet, 0)], -1)
        self.probes = Points(G=surf.operator(N)[:, m.cidx].tocsr(), w=np.zeros(xy.shape[0]), xy=xy,
                             h=(xy**2).sum(axis=1) / (2 * R), inside=found)
        Ntop, found_top = m.top.interpolation(mapped)
        if not found_top.all():
            raise FemError("a grid point lies outside the block's top surface")
        self.Ntop = Ntop
        self.mass = spla.splu(surf.mass().tocsc())
        # tangential tractions: limited L2 projection on P1 (_recover_p1)
        self.F1, M1, self.E1 = surf.p1_projection()
        self.M1 = spla.splu(M1.tocsc())
        self.Nprobe1, _ = surf.interpolation(mapped, p1=True)
        self.locator = PointLocator(m.space)
        self.D = np.zeros(2)
        self.u, self.delta = self._hertz_start()
        self.gap_tol = GAP_TOL * m.a_ref**2 / R
        self.tables: dict[str, dict[str, np.ndarray]] = {}
        self.meshes: list = []

    # ---------------------------------------------------------------- solving

    def _hertz_start(self) -> tuple[np.ndarray, float]:
        """Initial guess: the displacements under the Hertz pressure of the case.

        Starting the semi-smooth Newton iteration from an almost right active set saves
        most of the iterations a start from u = 0 (every point of h < δ penetrating)
        takes.  δ is the mean of h + u_n over the Hertz contact (constant for a
        half-space).
        """
        case, m = self.case, self.model
        a = m.a_ref
        p0 = 2.0 * case.E_star * a / (math.pi * case.R)
        r2 = (self.quad.xy**2).sum(axis=1)
        pH = p0 * np.sqrt(np.maximum(1.0 - r2 / a**2, 0.0))
        w = self.quad.w
        n = w.size
        f = self.quad.G.T @ np.concatenate([np.zeros(2 * n), w * pH])
        u = m.Crel @ f
        if case.load.P is None:
            return u, float(case.load.approach)
        uz = self.quad.displacement(u)[:, 2]
        inner = r2 < (0.8 * a) ** 2
        return u, float(np.mean(self.quad.h[inner] + uz[inner]))

    def _control(self, P_frac: float = 1.0, Q_frac: float = 0.0) -> Control:
        case, m = self.case, self.model
        load = case.load
        P = None if load.P is None else load.P * P_frac
        delta = self.delta if load.P is not None else load.approach * P_frac
        Q: tuple = (None, None)
        D = self.D.copy()
        if load.tangential_mode == "load" and Q_frac > 0:
            qx, qy = (load.Qx or 0.0) * Q_frac, (load.Qy or 0.0) * Q_frac
            Q = (qx, None) if m.shape == "half" else (qx, qy)
        elif load.tangential_mode == "shift":
            D = np.array([load.shift_x or 0.0, load.shift_y or 0.0]) * Q_frac
        return Control(P=P, delta=delta, D=D, Q=Q, sym=m.sym.factor)

    def _solve(self, ctrl: Control, cw: float = 0.0):
        m = self.model
        sol = newton(m.Krel, m.Crel, m.law, self.quad, ctrl, self.u, cw=cw,
                     tol=max(1e-9, 10 * self.case.solver.tol))
        ev = sol.ev
        active = ev.pn > 0
        if active.any():
            rad = np.hypot(self.quad.xy[active, 0], self.quad.xy[active, 1]).max()
            if rad > m.surface.r_c - 1.5 * m.h:
                raise FemError(
                    f"the contact (radius {rad:.4g} mm) reached the edge of the FE contact zone "
                    f"(r_c = {m.surface.r_c:.4g} mm)"
                )
        self.u, self.delta, self.D = sol.u, sol.delta, sol.D.copy()
        probe_ev = evaluate(m.law, self.probes, self.u, self.delta, self.D, cw)
        return sol, probe_ev

    def _commit(self, sol, probe_ev) -> None:
        for pts, ev in ((self.quad, sol.ev), (self.probes, probe_ev)):
            pts.t_old = ev.t.copy()
            pts.gt_old = ev.gt.copy()

    # ---------------------------------------------------------------- plans

    def run_static(self, progress) -> list[StepResult]:
        case, m = self.case, self.model
        mode = case.load.tangential_mode
        iters = 0
        if m.law_mode != "friction":
            sol, pev = self._solve(self._control())
            iters += sol.iterations
            slip = np.zeros((self.probes.n, 2))
            if m.law_mode == "sliding":
                slip[:] = slide_direction(case)
            return [self._output(0, sol, pev, slip, iters)]
        n_normal = 1 if case.identical_materials else N_NORMAL_DISSIMILAR
        bar = _bar(progress, n_normal + (N_TANGENTIAL if mode in ("load", "shift") else 0),
                   case)
        for i in range(1, n_normal + 1):
            sol, pev = self._solve(self._control(P_frac=i / n_normal))
            self._commit(sol, pev)
            iters += sol.iterations
            bar.update()
        gt_ref = pev.gt.copy()
        if mode in ("load", "shift"):
            for i in range(1, N_TANGENTIAL + 1):
                sol, pev = self._solve(self._control(Q_frac=i / N_TANGENTIAL))
                self._commit(sol, pev)
                iters += sol.iterations
                bar.update()
        bar.close()
        slip = pev.gt - gt_ref
        return [self._output(0, sol, pev, slip, iters)]

    def run_sliding_wear(self, progress) -> list[StepResult]:
        case = self.case
        sw = case.sliding_wear
        n = int(round(sw.distance / sw.step))
        if n < 1 or abs(n * sw.step - sw.distance) > 1e-9 * sw.distance:
            raise CaseError(
                f"sliding_wear.distance = {sw.distance} is not a whole number of steps "
                f"of sliding_wear.step = {sw.step}"
            )
        d = slide_direction(case)
        dg = sw.step * d
        ca, cb = wear_compliances(case, dg)
        if sw.output_s:
            wanted = {int(round(v / sw.step)) for v in sw.output_s} | {0, n}
        else:
            wanted = set(range(n + 1))
        steps = []
        bar = _bar(progress, n + 1, case)
        for k in range(n + 1):
            cw = 0.0 if k == 0 else ca + cb
            sol, pev = self._solve(self._control(), cw=cw)
            if k > 0:
                for pts, ev in ((self.quad, sol.ev), (self.probes, pev)):
                    pts.wear_a = pts.wear_a + ev.pn * ca
                    pts.wear_b = pts.wear_b + ev.pn * cb
            self._commit(sol, pev)
            bar.update()
            s = k * sw.step
            if k in wanted:
                slip = np.zeros((self.probes.n, 2))
                if k > 0:
                    slip[:] = dg
                steps.append(self._output(k, sol, pev, slip, sol.iterations, s=s))
        bar.close()
        return steps

    # ---------------------------------------------------------------- output

    def _project(self, values: np.ndarray) -> np.ndarray:
        """L2 projection of quadrature-point values on the P2 surface space (nodal)."""
        return self.mass.solve(self.model.surface.Nq.T @ (self.quad.w * values))

    def _recover(self, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Limited L2 projection of quadrature-point tractions: (nodal values, probe values).

        The projection on the P2 surface space, clipped at each node to the range of the
        quadrature-point values of the facets around it (its patch), and at each probe to
        the range of the patches of its facet's nodes.  Where the traction is smooth the
        projection lies inside those ranges and is unchanged; where it falls within a
        fraction of a facet (the edge of a worn flat: from about P/(π a²) to 0 across
        p Δw/|∇g| ≪ h) the projection rings like a Fourier series and overshoots by
        10-30 % of the jump, in both directions, over the last element, at any h.  Not a
        property of the traction the model carries: the Gauss-point values are bounded.
        """
        surf = self.model.surface
        nodal = self._project(values)
        lo, hi = surf.node_ranges(values)
        probe = self.Nprobe @ nodal
        found = self.probe_nodes[:, 0] >= 0
        idx = self.probe_nodes[found]
        probe[found] = np.clip(probe[found], lo[idx].min(axis=1), hi[idx].max(axis=1))
        return np.clip(nodal, lo, hi), probe

    def _recover_p1(self, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Limited L2 projection of quadrature-point tractions on continuous P1 (vertex
        values clipped to the range of their patch, probes linear on each facet):
        (nodal values, probe values).

        For the tangential tractions.  In partial slip their Gauss-point values oscillate
        next to the stick–slip boundary: the P2 displacement cannot follow the 3/2-power
        slip inside the facets it cuts, and the stiff penalty turns that interpolation
        error into traction errors of the order of the traction (Cattaneo–Mindlin,
        Q/μP = 0.5, h = a0/8: stick-point values from −0.8 to +1.7 times Mindlin's within
        0.1 a of the boundary), of nearly zero mean over a patch.  The P2 projection
        passes that mode on (its vertex functions have negative lobes): its max-norm error
        against Mindlin's on the quick grid grew under refinement (0.29 at h = a0/8, 0.40
        at a0/12).  On P1 it converges at the cusp's rates: max 0.180 -> 0.143 (order
        0.57), L2 0.073 -> 0.050 (order 0.93); also for Q/μP = 0.25 and 0.75.
        """
        surf = self.model.surface
        lo, hi = surf.node_ranges(values)
        vert = np.clip(self.M1.solve(self.F1 @ values), lo, hi)
        return self.E1 @ vert, self.Nprobe1 @ vert

    def _output(self, step: int, sol, pev, slip: np.ndarray, iterations: int,
                s: float = float("nan")) -> StepResult:
        case, m = self.case, self.model
        g = case.grid
        quad, ev = self.quad, sol.ev
        sym = m.sym
        wt = np.concatenate([quad.w * ev.t[:, 0], quad.w * ev.t[:, 1], quad.w * ev.pn])
        ua, ub = m.body_displacements(self.Gq_full.T @ wt)
        # gap on the probes from the full displacement fields
        nodes = m.top.nodes
        uza = self.Ntop @ ua.reshape(-1, 3)[nodes, 2]
        uzb = self.Ntop @ ub.reshape(-1, 3)[nodes, 2]
        pr = self.probes
        gap = pr.h + pr.wear_a + pr.wear_b - self.delta + (-uza - uzb)
        # projected tractions
        pn_nodes, pn_probe = self._recover(ev.pn)
        _, tx_probe = self._recover_p1(ev.t[:, 0])
        _, ty_probe = self._recover_p1(ev.t[:, 1])
        eps = self.gap_tol
        ng, nl = self.ngrid, self.nline
        r_edge = _ray_extent(self.ray_r, pev.gn[ng + 2 * nl:].reshape(self.theta.size, -1),
                             pr.inside[ng + 2 * nl:].reshape(self.theta.size, -1), eps)
        pstate = contact_states(pev, eps)
        # grid points: closed inside the contact boundary r(θ) of the rays
        mapped, _, _ = m.sym.map(pr.xy[:ng])
        rho = np.hypot(mapped[:, 0], mapped[:, 1])
        phi = np.arctan2(mapped[:, 1], mapped[:, 0]) % (2 * math.pi)
        if m.shape == "full":
            edge = np.interp(phi, self.theta, r_edge, period=2 * math.pi)
        else:
            edge = np.interp(phi, self.theta, r_edge)
        closed = (rho <= edge) & pr.inside[:ng]
        pstate[:ng] = np.where(closed, np.where(pev.state[:ng] == STICK, STICK, SLIP), OPEN)
        contact = pstate != OPEN
        slip = np.where(contact[:, None], slip, 0.0)  # the slip of contact points only
        if m.shape == "full":
            area = 0.5 * float(np.sum(r_edge**2)) * (self.theta[1] - self.theta[0])
        else:
            area = 0.5 * float(np.trapezoid(r_edge**2, self.theta))
        pn = np.where(contact, np.maximum(pn_probe, 0.0), 0.0)
        px = np.where(contact, self.sx * tx_probe, 0.0)
        py = np.where(contact, self.sy * ty_probe, 0.0)
        shape = (g.nx, g.ny)
        surface = {
            "p_n": pn[:ng].reshape(shape),
            "p_x": px[:ng].reshape(shape),
            "p_y": py[:ng].reshape(shape),
            "gap": gap[:ng].reshape(shape),
            "slip_x": (self.sx * slip[:, 0])[:ng].reshape(shape),
            "slip_y": (self.sy * slip[:, 1])[:ng].reshape(shape),
            "state": pstate[:ng].reshape(shape),
            "wear_a": pr.wear_a[:ng].reshape(shape),
            "wear_b": pr.wear_b[:ng].reshape(shape),
        }
        # lines through the centre
        for k, name in enumerate(("line_x", "line_y")):
            sl = slice(ng + k * nl, ng + (k + 1) * nl)
            self.tables[f"{name}/{step}"] = {
                "s": self.line.copy(), "p_n": pn_probe[sl],
                "p_x": (self.sx * tx_probe)[sl],
                "p_y": (self.sy * ty_probe)[sl],
                "gap": pev.gn[sl], "state": pstate[sl],
            }
        a_x = _semi_width(self.line, pev.gn[ng:ng + nl], pr.inside[ng:ng + nl], eps)
        a_y = _semi_width(self.line, pev.gn[ng + nl:ng + 2 * nl], pr.inside[ng + nl:ng + 2 * nl],
                          eps)
        # stresses of the reported body
        body = case.stress.body
        u_body, mat = (ua, case.a) if body == "a" else (ub, case.b)
        planes, axis = self._planes(u_body, mat.nu, mat.E)
        self.tables[f"axis/{step}"] = axis
        vm_best = (-1.0, 0.0, 0.0, 0.0)
        for name, plane in planes.items():
            v, s_at, z_at = plane.vm_max()
            if v > vm_best[0]:
                if name == "xz":
                    vm_best = (v, s_at, case.stress.y0, z_at)
                else:
                    vm_best = (v, case.stress.x0, s_at, z_at)
        w = quad.w
        stick = ev.state == STICK
        vm_axis, z_axis = axis_peak(axis["z"], axis["vm"],
                                    AXIS_FIT_WINDOW * max(a_x, a_y, self.model.h))
        Q = [float(np.sum(w * ev.t[:, c])) for c in (0, 1)]
        if m.shape == "quarter":
            Q = [0.0, 0.0]
        elif m.shape == "half":
            Q = [sym.factor * Q[0], 0.0]
        wear_q = quad.wear_a + quad.wear_b
        scalars = {
            "step": step, "s": s, "cycle": float("nan"),
            "P": sym.factor * float(np.sum(w * ev.pn)),
            "Qx": Q[0], "Qy": Q[1],
            "contact_area": sym.factor * area,
            "a_x": a_x, "a_y": a_y,
            "p_max": float(pn_nodes.max()),
            "w_max": float(max(wear_q.max(), (pr.wear_a + pr.wear_b)[:ng].max())),
            "wear_volume": sym.factor * float(np.sum(w * wear_q)),
            "vm_max": vm_best[0], "vm_max_x": vm_best[1], "vm_max_y": vm_best[2],
            "vm_max_z": vm_best[3],
            "stick_area": sym.factor * float(np.sum(w[stick])),
            "slip_area": sym.factor * (area - float(np.sum(w[stick]))),
            "vm_axis_max": vm_axis, "vm_axis_z": z_axis,
            "iterations": int(iterations), "converged": True,
            "wall_s": time.perf_counter() - self.t0,
            "approach": float(self.delta),
            "P_reaction": m.support_reaction(u_body, mat),
            "shift_x": float(self.D[0]), "shift_y": float(self.D[1]),
        }
        if self.vtu:
            self.meshes.append((step, fields_mesh(m.space, u_body, mat.nu, mat.E)))
        return StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(), surface=surface,
                          planes=planes)

    def _stress_at(self, u: np.ndarray, nu: float, E: float, xyz: np.ndarray
                   ) -> dict[str, np.ndarray]:
        """Stress components in the reported frame (x, y, depth) at global (x, y, depth)."""
        mapped, sx, sy = self.model.sym.map(xyz[:, :2])
        pts = np.column_stack([mapped, -xyz[:, 2]])
        sig = sample_stresses(self.model.space, self.locator, u, nu, E, pts)
        sig["sxy"] = sig["sxy"] * sx * sy
        sig["sxz"] = -sig["sxz"] * sx  # reported z is the depth (= −Z)
        sig["syz"] = -sig["syz"] * sy
        sig["vm"] = von_mises(*(sig[c] for c in COMPONENTS))
        return sig

    def _planes(self, u: np.ndarray, nu: float, E: float):
        case = self.case
        st = case.stress
        z = st.z
        planes = {}
        for name, s in (("xz", case.grid.x), ("yz", case.grid.y)):
            S, Z = np.meshgrid(s, z, indexing="ij")
            if name == "xz":
                xyz = np.column_stack([S.ravel(), np.full(S.size, st.y0), Z.ravel()])
            else:
                xyz = np.column_stack([np.full(S.size, st.x0), S.ravel(), Z.ravel()])
            sig = self._stress_at(u, nu, E, xyz)
            planes[name] = Plane(s=s.copy(), z=z.copy(),
                                 fields={k: v.reshape(S.shape) for k, v in sig.items()})
        zf = np.linspace(0.0, st.depth, 8 * (st.nz - 1) + 1)
        xyz = np.column_stack([np.full(zf.size, st.x0), np.full(zf.size, st.y0), zf])
        axis = {"z": zf, **self._stress_at(u, nu, E, xyz)}
        return planes, axis


class _NoBar:
    def update(self, n: int = 1) -> None:
        pass

    def close(self) -> None:
        pass


def _bar(progress: bool, total: int, case: Case):
    if not progress:
        return _NoBar()
    from tqdm import tqdm

    return tqdm(total=total, desc=f"fem {case.name} {case.param}".strip(), unit="step")


def solve(case: Case, progress: bool = False, *, vtu: bool = True, log=None) -> RunResult:
    """Run the FEM reference on ``case`` and return its :class:`~cases.result.RunResult`.

    ``vtu``: keep the FE fields of every output step in ``meta["vtu"]`` as
    ``(step, meshio.Mesh)`` pairs.  ``log``: optional callable receiving progress
    messages (set-up timings).  Raises :class:`~fem_reference.model.FemError` for a case
    the model cannot represent and
    :class:`~fem_reference.contact.ContactConvergenceError` (with the residual) when the
    contact iteration fails.
    """
    t0 = time.perf_counter()
    model = FemModel(case, log=log)
    try:
        run = _Run(model, vtu=vtu)
        run.t0 = t0
        if case.kind == "static":
            steps = run.run_static(progress)
        elif case.kind == "sliding_wear":
            steps = run.run_sliding_wear(progress)
        else:
            raise FemUnsupported(f"kind {case.kind!r} is not supported by fem_reference")
    finally:
        model.free_memory()
    meta = {
        "model": model.shape,
        "mesh": asdict(model.spec),
        "a_ref": model.a_ref,
        "h": model.h,
        "r_c": model.surface.r_c,
        "k_n": model.law.k_n,
        "k_t": model.law.k_t,
        "law": model.law_mode,
        "dofs": int(model.free.size),
        "elements": int(model.space.nel),
        "surface_dofs": int(model.cidx.size),
        "timings": {**model.timings, "total_s": time.perf_counter() - t0},
        "vtu": run.meshes,
    }
    return RunResult(case=case.name, solver="fem", param=case.param, steps=steps, meta=meta,
                     tables=run.tables)

