"""The CalculiX input deck (``.inp``) of one static case: the two bodies of
:mod:`calculix_adapter.mesh` as C3D8 elements of the case's materials, penalty
surface-to-surface contact with Coulomb friction, and the load path.

- Contact: body b's face (the plane) is the slave, body a's the master
  (``*CONTACT PAIR, TYPE=SURFACE TO SURFACE``); ``*SURFACE BEHAVIOR,
  PRESSURE-OVERCLOSURE=LINEAR`` with the normal stiffness :attr:`Model.k_n` and
  ``*FRICTION`` μ with the stick slope :attr:`Model.k_t` [MPa/mm] (CalculiX's friction
  is isotropic).
- Load: body a's far face is a rigid body (``*RIGID BODY``) whose reference node
  carries the loads, its rotations held; body b's far face is held; the symmetry planes
  of the model hold the normal displacement.
- Steps (Eq. 1 under load control): (1) the approach ``approach`` imposed on the
  reference node from 0 (the bodies just touching: force control would be singular);
  (2) force control at the model's share of P (the approach's boundary released);
  (3) with a tangential load, (Qx, Qy) added in increments of at most
  :data:`TANGENTIAL_INC` of it.  The contact traction on body a sums to (Qx, Qy) and P
  (README, Conventions), so the reference node's loads are their negatives.
- Output only in the last step, at its last increment (:func:`output`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .mesh import Body

#: the largest increment of the tangential step, a fraction of its load
TANGENTIAL_INC = 0.25


@dataclass(frozen=True)
class Model:
    """What the deck says beyond the mesh: materials (E [MPa], ν) of bodies a and b,
    friction μ, the penalty's normal stiffness ``k_n`` and stick slope ``k_t``
    [MPa/mm], the approach of step 1 [mm] and its path (:func:`approach_path`), the
    model's share of the loads (P, Qx, Qy)
    [N], and the body whose stresses are written ('a' or 'b')."""

    E_a: float
    nu_a: float
    E_b: float
    nu_b: float
    mu: float
    k_n: float
    k_t: float
    approach: float
    radius_ratio: float
    first_radius: float
    P: float
    Qx: float
    Qy: float
    stress_body: str


def approach_path(ratio: float, first: float) -> tuple[np.ndarray, np.ndarray]:
    """(step times, the approach's fractions) of step 1, one increment each: 0, then
    contact radii (∝ √δ, Hertz) from ``first`` growing by ``ratio`` per increment to 1:
    the radius grows by a bounded ratio (a frictional contact's stick traction follows
    its load path: docs/formulation.md §2.9)."""
    m = max(0, int(np.ceil(np.log(1.0 / first) / np.log(ratio) - 1e-9)))
    radii = np.concatenate([[0.0], first ** (1.0 - np.arange(m + 1) / max(m, 1))])
    times = np.linspace(0.0, 1.0, radii.size)
    return times, radii**2


def _rows(values: np.ndarray, fmt: str) -> str:
    return "\n".join(fmt % tuple(r) for r in values)


def _set(name: str, ids: np.ndarray) -> str:
    ids = np.asarray(ids).ravel() + 1
    lines = [", ".join(str(i) for i in ids[k:k + 16]) for k in range(0, ids.size, 16)]
    return f"*NSET, NSET={name}\n" + "\n".join(lines)


def write(a: Body, b: Body, model: Model) -> str:
    """The deck's text (module doc).  Node numbers: body b's from 1, then body a's, then
    the reference and rotation nodes; elements likewise."""
    nb, na = b.nodes.shape[0], a.nodes.shape[0]
    ref, rot = nb + na + 1, nb + na + 2
    mb, ma = b.cells.shape[0], a.cells.shape[0]
    nodes = np.concatenate([b.nodes, a.nodes])
    ids = np.arange(1, nb + na + 1)
    top = np.zeros(3)
    out = ["*HEADING", "contact-vv calculix model",
           "*NODE, NSET=NALL",
           _rows(np.column_stack([ids, nodes]), "%d, %.12g, %.12g, %.12g"),
           f"{ref}, {top[0]:.6g}, {top[1]:.6g}, {a.nodes[:, 2].max():.12g}",
           f"{rot}, {top[0]:.6g}, {top[1]:.6g}, {a.nodes[:, 2].max():.12g}",
           "*ELEMENT, TYPE=C3D8, ELSET=EB",
           _rows(np.column_stack([np.arange(1, mb + 1), b.cells + 1]), "%d" + ", %d" * 8),
           "*ELEMENT, TYPE=C3D8, ELSET=EA",
           _rows(np.column_stack([np.arange(mb + 1, mb + ma + 1), a.cells + nb + 1]),
                 "%d" + ", %d" * 8)]
    # the contact faces: body b's hexahedra below z = 0 (their top, face S2), body a's
    # above it (their bottom, face S1)
    top_b = np.flatnonzero(np.isin(b.cells[:, 4:], b.faces["contact"]).all(axis=1)) + 1
    bottom_a = np.flatnonzero(np.isin(a.cells[:, :4], a.faces["contact"]).all(axis=1))
    out += ["*SURFACE, NAME=SB, TYPE=ELEMENT",
            "\n".join(f"{e}, S2" for e in top_b),
            "*SURFACE, NAME=SA, TYPE=ELEMENT",
            "\n".join(f"{e + mb + 1}, S1" for e in bottom_a)]
    far_a = a.faces["far"]
    out += [_set("FARB", b.faces["far"]), _set("FARA", far_a + nb),
            _set("SKIN", skin(b))]
    cut = {}
    for plane, dof in (("x0", 1), ("y0", 2)):
        ids = [body.faces[plane] + off for body, off in ((b, 0), (a, nb))]
        ids = np.setdiff1d(np.concatenate(ids), far_a + nb)  # a's far face is rigid
        if ids.size:
            out.append(_set(plane.upper(), ids))
            cut[plane.upper()] = dof
    out += ["*MATERIAL, NAME=MA", "*ELASTIC", f"{model.E_a:.12g}, {model.nu_a:.12g}",
            "*MATERIAL, NAME=MB", "*ELASTIC", f"{model.E_b:.12g}, {model.nu_b:.12g}",
            "*SOLID SECTION, ELSET=EA, MATERIAL=MA",
            "*SOLID SECTION, ELSET=EB, MATERIAL=MB",
            f"*RIGID BODY, NSET=FARA, REF NODE={ref}, ROT NODE={rot}",
            "*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE", "SB, SA",
            "*SURFACE INTERACTION, NAME=SI",
            "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{model.k_n:.12g}"]
    if model.mu > 0:
        out += ["*FRICTION", f"{model.mu:.12g}, {model.k_t:.12g}"]

    out += steps(model, ref, rot, cut)
    out += output(model)
    out += ["*END STEP"]
    return "\n".join(out) + "\n"


def steps(model: Model, ref: int, rot: int, cut: dict[str, int]) -> list[str]:
    """The amplitudes and the steps of the load path (module doc), up to the last
    step's output: ``ref`` and ``rot`` the rigid body's reference and rotation nodes,
    ``cut`` the symmetry planes' node sets and the displacement each holds."""

    def held(ref_dofs: tuple[int, ...], approach: bool) -> list[str]:
        """The boundary conditions of a step: the far face of b, the rotations, the
        symmetry planes, the reference node's held translations."""
        lines = ["FARB, 1, 3, 0.0", f"{rot}, 1, 3, 0.0"]
        lines += [f"{name}, {dof}, {dof}, 0.0" for name, dof in cut.items()]
        lines += [f"{ref}, {d}, {d}, 0.0" for d in ref_dofs]
        if approach:
            lines += [f"{ref}, 3, 3, {-model.approach:.12g}"]
        return lines

    tangential = model.Qx != 0.0 or model.Qy != 0.0
    times, values = approach_path(model.radius_ratio, model.first_radius)
    n = times.size - 1
    out = ["*AMPLITUDE, NAME=APPROACH",
            _rows(np.column_stack([times, values]), "%.12g, %.12g"),
            "*AMPLITUDE, NAME=HELD", "0.0, 1.0, 1.0, 1.0"]
    out += ["*STEP, INC=1000", "*STATIC", f"{1.0 / n:.12g}, 1.0, 1e-6, {1.0 / n:.12g}",
            "*BOUNDARY, AMPLITUDE=APPROACH"] + held((), approach=True)
    out += ["*BOUNDARY"] + held((1, 2), approach=False) + ["*END STEP"]
    out += ["*STEP, INC=1000", "*STATIC", "1.0, 1.0, 1e-6, 1.0",
            "*BOUNDARY, OP=NEW"] + held((1, 2), approach=False)
    out += ["*CLOAD, AMPLITUDE=HELD", f"{ref}, 3, {-model.P:.12g}"]
    if tangential:
        # the reference node's translation held only across a symmetry plane it lies on
        free = tuple(d for d, c in ((1, "X0"), (2, "Y0")) if c in cut)
        out += ["*END STEP", "*STEP, INC=1000", "*STATIC",
                f"{TANGENTIAL_INC}, 1.0, 1e-6, {TANGENTIAL_INC}",
                "*BOUNDARY, OP=NEW"] + held(free, approach=False)
        out += ["*CLOAD, AMPLITUDE=HELD", f"{ref}, 3, {-model.P:.12g}", "*CLOAD"]
        out += [f"{ref}, {d}, {-q:.12g}" for d, q, c in ((1, model.Qx, "X0"),
                                                         (2, model.Qy, "Y0")) if c not in cut]
    return out


def skin(b: Body) -> np.ndarray:
    """Body b's nodes of its face and of the node layer under it: those of the face's
    element layer, whose displacements give the contact forces
    (:mod:`calculix_adapter.traction`)."""
    nx, ny, nz = b.shape
    return np.arange(b.nodes.shape[0]).reshape(nx, ny, nz)[:, :, -2:].ravel()


#: output at the last increment of the step only (an increment count no step reaches)
ONCE = "FREQUENCY=100000"


def output(model: Model) -> list[str]:
    """The last step's output requests (module doc): the displacements of body b's
    skin to seven digits (``*NODE PRINT``), the nodal stresses and contact fields
    (``.frd``), the contact forces (``*CONTACT PRINT``)."""
    return [f"*NODE PRINT, NSET=SKIN, {ONCE}", "U", f"*EL FILE, {ONCE}", "S",
            f"*CONTACT FILE, {ONCE}", "CSTR",
            f"*CONTACT PRINT, SLAVE=SB, MASTER=SA, {ONCE}", "CF"]
