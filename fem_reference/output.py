"""The output of one step: surface fields, line and axis tables, stress planes, scalars,
the FE mesh.

Surface fields on the case grid (cell centres; a quarter/half model is mirrored, and
components odd under a mirror vanish on the mirror plane):
``p_n, p_x, p_y`` the nodal tractions of the contact solve (one multiplier per surface
node, :mod:`fem_reference.model.nodal_basis`) interpolated linearly on the four
sub-triangles of each facet — a monotone reconstruction that does not ring where the
traction falls to zero inside a facet (the edge of a worn flat) — zero outside the
contact; ``gap`` from the full FE displacements;
``state``: a cell is closed inside the contact boundary r(θ), the outermost point with
a gap below ``GAP_TOL`` × δ0 along rays from the centre (robust against the penalty:
see :func:`fem_reference.fields.contact_zone.contact_states`), stick or slip by the return map
evaluated at the cell centre with its own history; ``wear_a/b`` likewise; ``slip_x/y``
the relative tangential displacement increment of the step (tangential loading: since
the end of the normal loading; static full sliding: the unit slip direction).

Scalars: ``P, Qx, Qy`` the resultants of the nodal tractions (Σ d_k λ_k); ``contact_area``
the area inside r(θ), ``stick_area`` the dual weights of the stick nodes summed,
``slip_area`` the rest; ``a_x, a_y`` half the closed length of the lines through the
centre; ``p_max`` the largest nodal pressure; ``w_max`` the largest total wear depth
of the wear field on the case grid (not of its coefficients in the modified basis,
which overshoot the field: +11 % in the partial-slip fretting annulus), ``wear_volume``
the wear field's integral (Σ d_k w_k); ``vm_max`` and its
location over both planes (the plane samples, :func:`cases.result.vm_max_location`);
``wall_s`` the time since ``solve`` started.  Extra: ``approach`` (the half-space's
δ, :mod:`fem_reference.model.far_field`; ``approach_block`` the blocks'), ``shift_x/y``
(likewise; ``shift_block_x/y``)
(g_t,o), ``P_reaction`` (the support reaction of the block: global equilibrium),
``vm_axis_max``/``vm_axis_z`` (the on-axis σ_VM maximum and its depth from a
least-squares cubic, :func:`fem_reference.fields.planes.axis_peak`).

Tables: ``"axis/<step>"`` the stresses on the load axis (x0, y0) at 8x the plane
resolution in depth; ``"line_x/<step>"`` and ``"line_y/<step>"`` the projected
tractions, the gap and the states along the lines through the centre.  Mesh: the FE
fields of the reported body (:func:`fem_reference.fields.vtu.fields_mesh`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import meshio
import numpy as np

from cases.model import Body
from cases.result import OPEN, STICK, Plane, StepResult, vm_max_location

from .contact.laws import Evaluation
from .fields.contact_zone import ContactZone, closing_measure, contact_zone
from .fields.planes import AXIS_FIT_WINDOW, SurfaceStress, axis_peak, stress_planes
from .fields.vtu import add_tractions, fields_mesh
from .model.fem_model import BodyDisplacement
from .run import OutputState, Run

Table = dict[str, np.ndarray]


@dataclass(frozen=True)
class StepOutput:
    """One output step: the common step result, the solver tables of the step
    (``"line_x/<step>"``, ``"line_y/<step>"``, ``"axis/<step>"``) and the FE mesh of the
    reported body (None without ``vtu``)."""

    result: StepResult
    tables: dict[str, Table]
    mesh: meshio.Mesh | None


@dataclass(frozen=True)
class Tractions:
    """Recovered tractions on body a: nodal pressure, and at the samples the pressure and
    the tangential tractions in the reported frame (not limited to the contact)."""

    pn_nodes: np.ndarray
    pn: np.ndarray
    px: np.ndarray
    py: np.ndarray


def step_output(run: Run, out: OutputState, *, t0: float, vtu: bool = True) -> StepOutput:
    """Recover the output of the converged state ``out`` of ``run`` (``t0``: the start
    of the run for ``wall_s``)."""
    m = run.model
    case = m.case
    ev = out.sol.ev
    ua, ub = body_displacements(run, ev)
    tractions = recover_tractions(run, ev)
    active = (run.sampling.Nsub @ (ev.pn > 0.0).astype(float))
    zone = contact_zone(run.sampling.layout, run.sampling.mapped, closing_measure(active),
                        out.sample_ev.state, run.samples.inside)
    surface = surface_fields(run, out, zone, tractions, sample_gap(run, ua, ub))
    tables = line_tables(run, out, zone, tractions)
    u_body, mat = (ua, case.a) if case.stress.body == "a" else (ub, case.b)
    planes, axis = stress_planes(m, run.locator, u_body, mat.nu, mat.E,
                                 surface_stress(run, ev, case.stress.body))
    tables[f"axis/{out.step}"] = axis
    scalars = step_scalars(run, out, zone, tractions, planes, axis)
    scalars.update(_body_scalars(run, u_body, mat, t0, scalars["P"],
                                 (scalars["Qx"], scalars["Qy"])))
    mesh = None
    if vtu:
        mesh = add_tractions(fields_mesh(m.space, u_body.total, mat.nu, mat.E),
                             m.surface.nodes, ev.pn, ev.t)
    g = case.grid
    result = StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(), surface=surface,
                        planes=planes)
    return StepOutput(result=result, tables=tables, mesh=mesh)


def body_displacements(run: Run, ev: Evaluation
                       ) -> tuple[BodyDisplacement, BodyDisplacement]:
    """Full FE displacements of bodies a and b (block frames) under the nodal tractions
    of ``ev`` (forces ``Gᵀ W λ``, :mod:`fem_reference.model.nodal_basis`; with a companion
    also the y forces at every surface node,
    :meth:`fem_reference.model.fem_model.FemModel.body_displacements`)."""
    w = run.nodes.w
    wt = np.concatenate([w * ev.t[:, 0], w * ev.t[:, 1], w * ev.pn])
    f_y = run.Binv @ (w * ev.t[:, 1]) if run.model.sym.companion else None
    return run.model.body_displacements(run.G_all.T @ wt, f_y)


def sample_gap(run: Run, ua: BodyDisplacement, ub: BodyDisplacement) -> np.ndarray:
    """The normal gap g_n = h + w_a + w_b − δ + u_n at the samples from the full FE
    displacements of both bodies (a companion's u_z is odd under the mirror)."""
    nodes = run.model.top.nodes
    Ntop, sy = run.sampling.Ntop, run.sampling.sy

    def u_z(u: BodyDisplacement) -> np.ndarray:
        uz = Ntop @ u.sym.reshape(-1, 3)[nodes, 2]
        return uz if u.anti is None else uz + sy * (Ntop @ u.anti.reshape(-1, 3)[nodes, 2])

    uza, uzb = u_z(ua), u_z(ub)
    pr = run.samples
    return pr.h + pr.wear_a + pr.wear_b - run.delta + (-uza - uzb)


def recover_tractions(run: Run, ev: Evaluation) -> Tractions:
    """The nodal tractions of ``ev`` and their values at the samples (linear on the
    facets' sub-triangles, :meth:`fem_reference.model.surface.ContactSurface.sub_interpolation`)."""
    Nsub, sampling = run.sampling.Nsub, run.sampling
    # with a companion the y traction is even under the mirror (module doc of .model)
    sy = 1.0 if run.model.sym.companion else sampling.sy
    return Tractions(pn_nodes=ev.pn, pn=Nsub @ ev.pn, px=sampling.sx * (Nsub @ ev.t[:, 0]),
                     py=sy * (Nsub @ ev.t[:, 1]))


def surface_stress(run: Run, ev: Evaluation, body: str) -> SurfaceStress:
    """The surface stresses σ_zz, σ_xz, σ_yz of the reported body at global points: the
    tractions it carries, from the nodal tractions of ``ev`` (on body a) interpolated
    like the surface fields.  In the reported frame (depth z into the body) σ_zz = −p_n
    on either body; body a carries (p_x, p_y), so σ_xz, σ_yz = −(p_x, p_y) there, and
    body b carries the opposite.  Zero off the contact zone (a free surface)."""
    model = run.model
    sign = 1.0 if body == "b" else -1.0

    def at(xy: np.ndarray) -> dict[str, np.ndarray]:
        mapped, sx, sy = model.sym.map(xy)
        N, _ = model.surface.sub_interpolation(mapped)
        sy = 1.0 if model.sym.companion else sy  # the y traction is even there (.model)
        return {"szz": -np.maximum(N @ ev.pn, 0.0), "sxz": sign * sx * (N @ ev.t[:, 0]),
                "syz": sign * sy * (N @ ev.t[:, 1])}

    return at


def surface_fields(run: Run, out: OutputState, zone: ContactZone, tractions: Tractions,
                   gap: np.ndarray) -> dict[str, np.ndarray]:
    """The surface fields on the case grid (tractions and slip zero outside the contact)."""
    sampling = run.sampling
    grid = run.model.case.grid
    ng = sampling.layout.ngrid
    state = zone.state
    contact = state != OPEN
    slip = np.where(contact[:, None], out.slip, 0.0)  # the slip of contact points only
    pn = np.where(contact, np.maximum(tractions.pn, 0.0), 0.0)
    px = np.where(contact, tractions.px, 0.0)
    py = np.where(contact, tractions.py, 0.0)
    pr = run.samples
    fields = {
        "p_n": pn, "p_x": px, "p_y": py, "gap": gap,
        "slip_x": sampling.sx * slip[:, 0], "slip_y": sampling.sy * slip[:, 1],
        "state": state, "wear_a": pr.wear_a, "wear_b": pr.wear_b,
    }
    return {name: v[:ng].reshape(grid.nx, grid.ny) for name, v in fields.items()}


def line_tables(run: Run, out: OutputState, zone: ContactZone, tractions: Tractions
                ) -> dict[str, Table]:
    """``line_x/<step>``, ``line_y/<step>``: projected tractions (not limited to the
    contact), gap and states along the lines through the centre."""
    layout = run.sampling.layout
    tables = {}
    for name, sl in (("line_x", layout.line_x), ("line_y", layout.line_y)):
        tables[f"{name}/{out.step}"] = {
            "s": layout.line.copy(), "p_n": tractions.pn[sl],
            "p_x": tractions.px[sl], "p_y": tractions.py[sl],
            "gap": out.sample_ev.gn[sl], "state": zone.state[sl],
        }
    return tables


def step_scalars(run: Run, out: OutputState, zone: ContactZone, tractions: Tractions,
                 planes: dict[str, Plane], axis: Table) -> dict[str, float]:
    """The summary scalars of a step from its nodal tractions, contact zone and
    stresses (symmetry factors applied)."""
    m = run.model
    sym, nodes, ev = m.sym, run.nodes, out.sol.ev
    w = nodes.w
    stick = ev.state == STICK
    vm, vm_x, vm_y, vm_z = vm_max_location(planes, *m.case.plane_centre)
    vm_axis, z_axis = axis_peak(axis["z"], axis["vm"],
                                AXIS_FIT_WINDOW * max(zone.a_x, zone.a_y, m.h))
    Q = [float(np.sum(w * ev.t[:, c])) for c in (0, 1)]
    if m.shape == "quarter":
        Q = [0.0, 0.0]
    elif m.shape == "half":
        Q = [sym.factor * Q[0], sym.factor * Q[1] if sym.companion else 0.0]
    wear_q = nodes.wear_a + nodes.wear_b
    wear_sampled = run.samples.wear_a + run.samples.wear_b
    return {
        "step": out.step, "s": out.s, "cycle": out.cycle,
        "P": sym.factor * float(np.sum(w * ev.pn)),
        "Qx": Q[0], "Qy": Q[1],
        "contact_area": sym.factor * zone.area,
        "a_x": zone.a_x, "a_y": zone.a_y,
        "p_max": float(tractions.pn_nodes.max()),
        "w_max": float(wear_sampled[:run.sampling.layout.ngrid].max()),
        "wear_volume": sym.factor * float(np.sum(w * wear_q)),
        "vm_max": vm, "vm_max_x": vm_x, "vm_max_y": vm_y, "vm_max_z": vm_z,
        "stick_area": sym.factor * float(np.sum(w[stick])),
        "slip_area": sym.factor * (zone.area - float(np.sum(w[stick]))),
        "vm_axis_max": vm_axis, "vm_axis_z": z_axis,
        "iterations": int(out.iterations), "converged": True,
    }


def _body_scalars(run: Run, u_body: BodyDisplacement, mat: Body, t0: float, P: float,
                  Q: tuple[float, float]) -> dict[str, float]:
    """``wall_s`` and the state scalars: the approach and the shift (the half-space's:
    the blocks' δ plus c P and g_t,o plus c_t Q, :mod:`fem_reference.model.far_field`;
    ``approach_block``, ``shift_block_x/y`` the blocks' own), support reaction."""
    return {
        "wall_s": time.perf_counter() - t0,
        "approach": float(run.delta) + run.compliance * P,
        "approach_block": float(run.delta),
        "P_reaction": run.model.support_reaction(u_body, mat),
        "shift_x": float(run.D[0]) + run.compliance_t * Q[0],
        "shift_y": float(run.D[1]) + run.compliance_t * Q[1],
        "shift_block_x": float(run.D[0]), "shift_block_y": float(run.D[1]),
    }
