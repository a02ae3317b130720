"""Subsurface stresses of the reported body: the xz and yz planes and the load axis.

Samples the exact P2 element stresses (:func:`fem_reference.fields.stresses.sample_stresses`)
in the reported frame (x, y, depth z) on the case's planes: ``xz`` at y = y0 over the
grid x, ``yz`` at x = x0 over the grid y ((x0, y0) = ``case.plane_centre``), both at the
depths ``stress.z``; and on the load axis (x0, y0) at 8x the plane resolution in depth,
whose σ_VM maximum :func:`axis_peak` locates.

On the surface itself (depth 0) the components σ_zz, σ_xz, σ_yz are the boundary
condition, the tractions the body carries, and are taken from the recovered nodal
tractions (``surface``) rather than from the element gradients: the P2 stresses of the
surface elements carry their largest error there, most under a worn profile's steep
traction, where the nodal tractions of the contact solve are the FEM's most accurate
surface quantity (``docs/fem-notes.md``).  σ_xx, σ_yy, σ_xy stay the elements'.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from cases.result import Plane, von_mises

from ..model.fem_model import BodyDisplacement, FemModel
from .stresses import COMPONENTS, PointLocator, sample_stresses

AXIS_FIT_WINDOW = 0.3  # half-width of the axis σ_VM fit window, in contact semi-widths
AXIS_REFINEMENT = 8  # depth samples on the axis per plane depth interval
#: the surface tractions' stresses of the reported body at global (n, 2) points:
#: {"szz", "sxz", "syz"} in the reported frame
SurfaceStress = Callable[[np.ndarray], dict[str, np.ndarray]]


def stress_at(model: FemModel, locator: PointLocator, u: BodyDisplacement, nu: float,
              E: float, xyz: np.ndarray, surface: SurfaceStress | None = None
              ) -> dict[str, np.ndarray]:
    """Stress components and σ_VM in the reported frame (x, y, depth) at global (x, y,
    depth) ``xyz`` (n, 3), of the body with block-frame displacement ``u`` and (ν, E);
    at depth 0, σ_zz, σ_xz, σ_yz from ``surface`` where given (module doc).

    The mirror image of the symmetric solution keeps σ_xx, σ_yy, σ_zz, σ_xz and changes
    the sign of σ_xy, σ_yz (sign 0 on the mirror plane: they vanish there); the
    companion's (antisymmetric) image does the opposite, its σ_xx, σ_yy, σ_zz, σ_xz
    vanishing on the plane (:mod:`fem_reference.model.fem_model`)."""
    mapped, sx, sy = model.sym.map(xyz[:, :2])
    pts = np.column_stack([mapped, -xyz[:, 2]])
    sig = sample_stresses(model.space, locator, u.sym, nu, E, pts)
    sig["sxy"] = sig["sxy"] * sx * sy
    sig["sxz"] = -sig["sxz"] * sx  # reported z is the depth (= −Z)
    sig["syz"] = -sig["syz"] * sy
    if u.anti is not None:  # a half block: sx = 1
        anti = sample_stresses(model.space, locator, u.anti, nu, E, pts)
        for c in ("sxx", "syy", "szz"):
            sig[c] = sig[c] + anti[c] * sy
        sig["sxy"] = sig["sxy"] + anti["sxy"] * sx
        sig["sxz"] = sig["sxz"] - anti["sxz"] * sx * sy
        sig["syz"] = sig["syz"] - anti["syz"]
    top = xyz[:, 2] == 0.0
    if surface is not None and top.any():
        for c, v in surface(xyz[top, :2]).items():
            sig[c] = sig[c].copy()
            sig[c][top] = v
    sig["vm"] = von_mises(*(sig[c] for c in COMPONENTS))
    return sig


def stress_planes(model: FemModel, locator: PointLocator, u: BodyDisplacement, nu: float,
                  E: float, surface: SurfaceStress | None = None
                  ) -> tuple[dict[str, Plane], dict[str, np.ndarray]]:
    """(planes ``{"xz", "yz"}``, axis table ``{"z", components, "vm"}``) of the body with
    displacement ``u`` and (ν, E); on the surface with the tractions' components of
    ``surface`` (module doc)."""
    case = model.case
    st = case.stress
    x0, y0 = case.plane_centre
    z = st.z
    planes = {}
    for name, s in (("xz", case.grid.x), ("yz", case.grid.y)):
        S, Z = np.meshgrid(s, z, indexing="ij")
        if name == "xz":
            xyz = np.column_stack([S.ravel(), np.full(S.size, y0), Z.ravel()])
        else:
            xyz = np.column_stack([np.full(S.size, x0), S.ravel(), Z.ravel()])
        sig = stress_at(model, locator, u, nu, E, xyz, surface)
        planes[name] = Plane(s=s.copy(), z=z.copy(),
                             fields={k: v.reshape(S.shape) for k, v in sig.items()})
    zf = np.linspace(0.0, st.depth, AXIS_REFINEMENT * (st.nz - 1) + 1)
    xyz = np.column_stack([np.full(zf.size, x0), np.full(zf.size, y0), zf])
    axis = {"z": zf, **stress_at(model, locator, u, nu, E, xyz, surface)}
    return planes, axis


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
