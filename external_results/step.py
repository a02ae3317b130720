"""One output step of the suite from one file: the surface fields on the case grid, the
stress planes, the scalars.

- Surface fields (``p_n, p_x, p_y, wear_a, wear_b, gap``) at the case grid's cell
  centres, interpolated on the surface's triangles (:mod:`external_results.interpolate`);
  zero where the file has no surface (a model carries no traction and wears nowhere
  else; ``gap`` is then left out).  ``state`` is the nearest surface point's.
- Planes ``xz`` at y = y0 over the grid x and ``yz`` at x = x0 over the grid y ((x0, y0)
  = ``case.plane_centre``), at the depths of ``[stress]``: the six components, and σ_VM
  from them (:func:`cases.result.von_mises`); from the file's own σ_VM where only that
  is mapped.
- A partial model (``mirror``): a point is read at its mirror image in the modelled part,
  the components odd under the mirror (x: p_x, σ_xy, σ_xz; y: p_y, σ_xy, σ_yz) with the
  sign of the coordinate (zero on the mirror plane).
- Scalars the file states (``scalars``) are taken as they are.  The others, with one
  definition for every file: ``P, Qx, Qy`` the integrals of the interpolated tractions
  over the surface triangles (the mirror images added), ``p_max`` the largest pressure
  at a surface point, ``a_x, a_y`` (:func:`cases.result.semi_widths`),
  ``contact_area`` and ``stick_area`` the grid cells with p_n > 0 and in stick,
  ``w_max`` the largest total wear depth on the grid, ``wear_volume`` its integral over
  the triangles; ``vm_max`` and its location over the planes
  (:func:`cases.result.vm_max_location`).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import QhullError

from cases.model import Case, CaseError
from cases.result import (
    STICK,
    STRESS_COMPONENTS,
    Plane,
    StepResult,
    semi_widths,
    vm_max_location,
    von_mises,
)

from .frame import Frame
from .interpolate import Surface, Volume
from .spec import Spec

#: components odd under the mirror x -> -x, y -> -y
ODD = {"x": ("p_x", "sxy", "sxz"), "y": ("p_y", "sxy", "syz")}
SURFACE_TOL = 1e-6  # a point lies on the surface within this fraction of the extent


def mirrored(xyz: np.ndarray, mirror: tuple[str, ...]
             ) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """The points read at their images in the modelled part, and per mirror the sign of
    the coordinate (0 on the plane)."""
    out, signs = xyz.copy(), {}
    for axis in mirror:
        k = "xy".index(axis)
        signs[axis] = np.sign(xyz[:, k])
        out[:, k] = np.abs(xyz[:, k])
    return out, signs


def _sign(quantity: str, signs: dict[str, np.ndarray]) -> np.ndarray | float:
    out: np.ndarray | float = 1.0
    for axis, s in signs.items():
        if quantity in ODD[axis]:
            out = out * s
    return out


def _mirror_factor(quantity: str, mirror: tuple[str, ...]) -> float:
    """What the integral over the modelled part is multiplied by for the whole."""
    f = 1.0
    for axis in mirror:
        f *= 0.0 if quantity in ODD[axis] else 2.0
    return f


def surface_fields(frame: Frame, surface: Surface, case: Case, spec: Spec
                   ) -> dict[str, np.ndarray]:
    """The surface fields on the case grid (module doc)."""
    g = case.grid
    X, Y = np.meshgrid(g.x, g.y, indexing="ij")
    q, signs = mirrored(np.column_stack([X.ravel(), Y.ravel(), np.zeros(X.size)]),
                        spec.mirror)
    inside, idx, w = surface.weights(q[:, :2])
    if not inside.any():
        where = f"external.{spec.name}"
        raise CaseError(f"{frame.path}: its contact surface covers no point of the case's "
                        f"grid (x {g.x[0]:g} to {g.x[-1]:g} mm, y {g.y[0]:g} to {g.y[-1]:g} "
                        f"mm) in the suite's frame; check {where}.origin, {where}.axes and "
                        f"{where}.length_unit")
    out = {}
    for name in ("p_n", "p_x", "p_y", "wear_a", "wear_b", "gap"):
        if name not in frame.values:
            continue
        if name == "gap" and not inside.all():
            continue
        v = (frame.values[name][idx] * w).sum(axis=1) * _sign(name, signs)
        out[name] = np.where(inside, v, 0.0).reshape(g.nx, g.ny)
    if "state" in frame.values:
        near = idx[np.arange(len(idx)), w.argmax(axis=1)]
        out["state"] = np.where(inside, np.rint(frame.values["state"][near]), 0.0
                                ).reshape(g.nx, g.ny)
    return out


def planes(frame: Frame, volume: Volume, case: Case, spec: Spec) -> dict[str, Plane]:
    """The xz and yz stress planes (module doc); none without mapped stresses."""
    comps = [c for c in STRESS_COMPONENTS if c in frame.values]
    if len(comps) < 6 and "vm" not in frame.values:
        return {}
    g, z = case.grid, case.stress.z
    x0, y0 = case.plane_centre
    out = {}
    for name, s in (("xz", g.x), ("yz", g.y)):
        S, Z = np.meshgrid(s, z, indexing="ij")
        fixed = np.full(S.size, y0 if name == "xz" else x0)
        xy = (S.ravel(), fixed) if name == "xz" else (fixed, S.ravel())
        q, signs = mirrored(np.column_stack([*xy, Z.ravel()]), spec.mirror)
        inside, idx, w = volume.weights(q)
        if not inside.all():
            k = int(np.flatnonzero(~inside)[0])
            raise CaseError(f"{frame.path}: {int((~inside).sum())} of {inside.size} points "
                            f"of the {name} stress plane lie outside its mesh, e.g. (x, y, "
                            f"depth) = {tuple(round(float(v), 6) for v in q[k])} mm: check "
                            f"external.{spec.name}.axes, origin and mirror")
        fields = {c: ((frame.values[c][idx] * w).sum(axis=1) * _sign(c, signs)
                      ).reshape(S.shape) for c in comps}
        if len(comps) == 6:
            fields["vm"] = von_mises(*(fields[c] for c in STRESS_COMPONENTS))
        else:
            fields["vm"] = (frame.values["vm"][idx] * w).sum(axis=1).reshape(S.shape)
        out[name] = Plane(s=np.asarray(s, dtype=float).copy(), z=z.copy(), fields=fields)
    return out


def scalars(frame: Frame, surface: Surface, fields: dict[str, np.ndarray],
            plane_set: dict[str, Plane], case: Case, spec: Spec) -> dict[str, float]:
    """The step's scalars (module doc): the file's, else derived."""
    g = case.grid
    cell = g.dx * g.dy
    out: dict[str, float] = {}
    for q, name in (("P", "p_n"), ("Qx", "p_x"), ("Qy", "p_y")):
        if name in frame.values:
            out[q] = _mirror_factor(name, spec.mirror) * surface.integral(frame.values[name])
    out["p_max"] = float(frame.values["p_n"][surface.nodes].max())
    p_n = fields["p_n"]
    out["a_x"], out["a_y"] = semi_widths(g.x, g.y, p_n)
    out["contact_area"] = float((p_n > 0).sum() * cell)
    if "state" in fields:
        out["stick_area"] = float((fields["state"] == STICK).sum() * cell)
    wear = [frame.values[w] for w in ("wear_a", "wear_b") if w in frame.values]
    if wear:
        total = sum(fields[w] for w in ("wear_a", "wear_b") if w in fields)
        out["w_max"] = float(np.max(total))
        out["wear_volume"] = _mirror_factor("wear_a", spec.mirror) * surface.integral(
            sum(wear))
    x0, y0 = case.plane_centre
    if plane_set:
        keys = ("vm_max", "vm_max_x", "vm_max_y", "vm_max_z")
        out.update(zip(keys, vm_max_location(plane_set, x0, y0), strict=True))
    out.update(frame.scalars)
    return out


def _first_line(exc: BaseException) -> str:
    """What an error says on its first line (Qhull's own dump follows it)."""
    text = str(exc).strip()
    return text.splitlines()[0] if text else type(exc).__name__


def geometry(frame: Frame, spec: Spec) -> tuple[Surface, Volume | None]:
    """The file's contact surface and, where stresses are mapped, the body's volume to
    interpolate them in; CaseError naming the file, the key and the likely cause."""
    extent = float(np.ptp(frame.xyz[:, :2], axis=0).max()) or 1.0
    where = f"external.{spec.name}"
    try:
        surface = Surface.of(frame.xyz, frame.cells, SURFACE_TOL * extent)
    except (ValueError, QhullError) as exc:
        raise CaseError(f"{frame.path}: no contact surface at depth 0 in the suite's frame "
                        f"({_first_line(exc)}); check {where}.axes and {where}.origin"
                        ) from None
    if not any(c in frame.values for c in (*STRESS_COMPONENTS, "vm")):
        return surface, None
    try:
        volume = Volume.of(frame.xyz, frame.cells)
    except (ValueError, QhullError) as exc:  # e.g. stresses on surface points only
        raise CaseError(f"{frame.path}: the stresses mapped in {where}.fields need points "
                        "that fill the body below the surface, and these make no "
                        f"tetrahedra ({_first_line(exc)}); map no stresses for a "
                        f"surface-only file, or check {where}.axes") from None
    return surface, volume


def step_result(frame: Frame, case: Case, spec: Spec, number: int) -> StepResult:
    """Output step ``number`` of ``case`` from ``frame`` (module doc)."""
    surface, volume = geometry(frame, spec)
    fields = surface_fields(frame, surface, case, spec)
    plane_set = planes(frame, volume, case, spec) if volume is not None else {}
    values = scalars(frame, surface, fields, plane_set, case, spec)
    values["step"] = float(number)
    g = case.grid
    return StepResult(scalars=values, x=np.asarray(g.x, float).copy(),
                      y=np.asarray(g.y, float).copy(), surface=fields, planes=plane_set)
