"""One static case by CalculiX: the model of :mod:`calculix_adapter.model` written as a
deck (:mod:`calculix_adapter.deck`) to a scratch directory, ``ccx`` run on it
(:mod:`calculix_adapter.program`), its ``.frd`` and ``.dat`` files read back
(:mod:`calculix_adapter.frd`): the tractions from the nodal forces of body b's face
(:mod:`calculix_adapter.traction`), the stresses from the nodal stresses, both onto the
case's grid and planes (:mod:`calculix_adapter.fields`).
"""

from __future__ import annotations

import shutil
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from cases.model import Case
from cases.result import OPEN, SLIP, STICK, RunResult, StepResult, semi_widths, vm_max_location

from . import fields, traction
from .deck import Model, write
from .frd import (
    ContactForces,
    ResultFileError,
    last,
    read_contact_forces,
    read_frd,
    read_node_print,
)
from .mesh import SHARE, Body
from .model import element_size, model
from .program import CalculixFailed, ccx, increments, version
from .support import symmetry

#: a node is in contact where its pressure exceeds NOISE times the largest: the nodal
#: forces of displacements printed to seven digits scatter by 4e-7 of it outside the
#: contact (the quick Cattaneo–Mindlin contact at Q = 0.75 μP): 25 times that
NOISE = 1e-5


def run(case: Case, on_output: Callable[[StepResult], None] | None = None,
        keep: Path | None = None) -> RunResult:
    """One output step of ``case`` by CalculiX (module doc); the scratch directory is
    removed, unless ``keep`` names a directory to copy its files to."""
    t0 = time.perf_counter()
    h = element_size(case)
    a, b, m = model(case, h)
    with tempfile.TemporaryDirectory(prefix="contact-vv-ccx-") as tmp:
        work = Path(tmp)
        _, ccx_s = ccx(write(a, b, m), work)
        try:
            blocks = read_frd(work / "job.frd")
            forces = read_contact_forces(work / "job.dat")
            skin = read_node_print(work / "job.dat")
        except (OSError, ResultFileError) as exc:
            raise CalculixFailed(f"ccx wrote no complete results: {exc}") from None
        n_inc, n_it = increments(work)
        if keep is not None:
            keep.mkdir(parents=True, exist_ok=True)
            for f in work.iterdir():
                shutil.copy2(f, keep / f.name)
    step = result(case, a, b, m, blocks, forces[-1], skin)
    step.scalars.update({"iterations": n_it, "increments": n_inc, "h": h,
                         "nodes": a.nodes.shape[0] + b.nodes.shape[0],
                         "elements": a.cells.shape[0] + b.cells.shape[0],
                         "ccx_s": ccx_s, "wall_s": time.perf_counter() - t0})
    if on_output is not None:
        on_output(step)
    return RunResult(case=case.name, solver="calculix", param=case.param, steps=[step],
                     meta={"calculix": version()})


def result(case: Case, a: Body, b: Body, m: Model, blocks, forces: ContactForces,
           skin: tuple[np.ndarray, np.ndarray]) -> StepResult:
    """The common result of one step from CalculiX's last increment: the tractions from
    the nodal forces of body b's face (:mod:`calculix_adapter.traction`), the stresses
    from the nodal stresses (:mod:`calculix_adapter.fields`)."""
    g = case.grid
    nb = b.nodes.shape[0]
    u = np.zeros((nb, 3))
    ids, values = skin
    u[ids[ids <= nb] - 1] = values[ids <= nb]
    F = traction.nodal_forces(b, u, case.b.E, case.b.nu)
    area = fields.tributary(b)
    pn, px, py = (-F[..., k] / area for k in (2, 0, 1))
    # a component odd under a model's mirror plane is 0 on it: there F holds the plane's
    # reaction, not a contact force
    if b.xs[0] == 0.0:
        px[0, :] = 0.0
    if b.ys[0] == 0.0:
        py[:, 0] = 0.0
    contact = pn > NOISE * pn.max()
    pn, px, py = (np.where(contact, v, 0.0) for v in (pn, px, py))
    slip = fields.slipping(pn, px, py, m.mu)
    factor = 1.0 / SHARE[symmetry(case)]
    p_n = np.maximum(fields.on_face(b, pn, "p_n", g.x, g.y), 0.0)
    p_x = fields.on_face(b, px, "p_x", g.x, g.y)
    p_y = fields.on_face(b, py, "p_y", g.x, g.y)
    slip_g = fields.on_face(b, slip.astype(float), "p_n", g.x, g.y) >= 0.5
    inside = p_n > 0.0
    state = np.where(inside, np.where(slip_g | (m.mu == 0.0), SLIP, STICK), OPEN)
    planes = stress_planes(case, a, b, blocks)
    x0, y0 = case.plane_centre
    vm, vx, vy, vz = vm_max_location(planes, x0, y0)
    a_x, a_y = semi_widths(g.x, g.y, p_n)
    total = F.sum(axis=(0, 1))
    fx, fy, fz = forces.force
    scalars = {
        "step": 0, "P": factor * float(np.sum(pn * area)),
        # a resultant odd under a model's mirror plane vanishes
        "Qx": 0.0 if b.xs[0] == 0.0 else factor * float(np.sum(px * area)),
        "Qy": 0.0 if b.ys[0] == 0.0 else factor * float(np.sum(py * area)),
        "contact_area": factor * float(area[contact].sum()), "a_x": a_x, "a_y": a_y,
        "stick_area": factor * float(area[contact & ~slip].sum()) if m.mu > 0 else 0.0,
        "p_max": float(pn.max()), "vm_max": vm, "vm_max_x": vx, "vm_max_y": vy,
        "vm_max_z": vz, "x0": x0, "y0": y0, "converged": True,
        # the contact force of the nodal forces against CalculiX's own total
        "P_contact_print": -factor * fz, "P_nodal_forces": -factor * float(total[2]),
    }
    return StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(),
                      surface={"p_n": p_n, "p_x": p_x, "p_y": p_y,
                               "state": state.astype(np.int8)},
                      planes=planes)


def stress_planes(case: Case, a: Body, b: Body, blocks) -> dict:
    """The σ planes of the reported body from CalculiX's nodal stresses."""
    st = case.stress
    body, offset = (a, b.nodes.shape[0]) if st.body == "a" else (b, 0)
    block = last(blocks, "STRESS")
    s_nodal = np.zeros((b.nodes.shape[0] + a.nodes.shape[0], 6))
    s_nodal[block.nodes - 1] = np.column_stack([block.field(c) for c in fields.FRD_STRESS])
    x0, y0 = case.plane_centre
    return fields.planes(body, s_nodal[offset:offset + body.nodes.shape[0]], x=case.grid.x,
                         y=case.grid.y, z=st.z, x0=x0, y0=y0,
                         sign_z=1.0 if st.body == "a" else -1.0)
