"""The σ_VM maximum of two solvers, compared where it is a number.

Both solvers' σ_VM planes are sampled on common points (:mod:`reports.compare.sampling`).

Value.  ``vm_max`` compares the two maxima over the points *off the edge band* — farther
than one cell from either solver's contact boundary (in space), as the max norms
of the planes do.  At the edge a contact whose tractions fall to zero inside a cell (or,
worn, drop as a step) has a surface σ_VM with a cusp or a log singularity that no sample
held a cell apart resolves: the sliding sphere's trailing edge, the first fretting
cycle's edge cell, the worn pin's edge (docs/formulation.md §2.6).  The maximum over
every point is still written, as the metric ``edge``, and not gated; where it lies off
the band it equals the gated one.

Near the surface.  A maximum that either solver places shallower than a quarter of the
contact radius (``stress.z_below`` where a case sets it) lies where the surface tractions'
own discretisation (cell-wise constant, nodal) and the edge's cusp or singularity govern
the field: it converges like (h/a)^1/2 or not at all.  It is written as ``vm_max``
``surface``, not gated, and its companion ``vm_max_below`` — the maximum from a quarter of
the contact radius down, and at least two cells down (:func:`below_depth`) — is gated
with its location.  The Hertzian maximum at 0.48 a stays ``rel``.

Location.  ``vm_max_loc`` is judged by the *near-maximum set* of each solver: the points
of the gated region where its σ_VM is within the pair's ``vm_max`` tolerance of its
maximum.  A maximum located anywhere in that set is as good as any other to the tolerance
of the value, so the metric is the larger of the distances from each solver's maximum to
the other's set: 0 where each maximum lies in the other's set, the distance between the
two maxima where both are sharp peaks.  A ridge or a plateau (the surface σ_VM of a partial
slip contact changes by 0.3 % between 0.72 a and 0.99 a) and two rival peaks of nearly
equal value (the sliding sphere near the friction coefficient at which the maximum moves
to the surface) then leave the location as undetermined as it is, without a false alarm,
while a maximum moved out of the other's set is caught.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

#: the metric of a maximum off the edge band that lies on the surface: written, not gated
SURFACE = "surface"
SURFACE_NOTE = ("the maximum lies on the surface, where a solver's samples carry the "
                "tractions' own discretisation (cell-wise constant, nodal) and the field has "
                "a cusp or a log singularity at the contact edge: it converges at order 1/2 "
                "or not at all; gated instead: vm_max_below, the maximum from a quarter of "
                "the contact radius (two cells at least) down (reports.compare.maxima)")
#: the metric of the maximum over every point, the edge band included: written, not gated
EDGE = "edge"
EDGE_NOTE = ("max over every point, the band within one cell of the contact edge "
             "included, where the surface sigma_VM has a cusp or a log singularity that "
             "no sample a cell apart resolves; not gated (reports.compare.maxima)")


@dataclass(frozen=True)
class PlaneSamples:
    """Both solvers' σ_VM on one plane at common points: ``xyz`` the points (n, 3),
    ``a`` and ``b`` the two fields (n,), ``off`` the points off the edge band (n,)."""

    xyz: np.ndarray
    a: np.ndarray
    b: np.ndarray
    off: np.ndarray


def plane_points(name: str, s: np.ndarray, z: np.ndarray, x0: float, y0: float
                 ) -> np.ndarray:
    """The points (x, y, z) of plane ``name`` (``xz`` at y = y0, ``yz`` at x = x0) on the
    tensor samples (s, z), in C order."""
    ss, zz = np.meshgrid(s, z, indexing="ij")
    fixed = np.full(ss.size, y0 if name == "xz" else x0)
    along = ss.ravel()
    if name == "xz":
        return np.column_stack([along, fixed, zz.ravel()])
    return np.column_stack([fixed, along, zz.ravel()])


def _top(field: np.ndarray, where: np.ndarray) -> int:
    """Index of the largest finite value of ``field`` among ``where`` (-1: none)."""
    ok = where & np.isfinite(field)
    if not ok.any():
        return -1
    idx = np.flatnonzero(ok)
    return int(idx[np.argmax(field[idx])])


def _near(field: np.ndarray, where: np.ndarray, top: float, rel: float) -> np.ndarray:
    """The points of ``where`` whose ``field`` is within ``rel`` of its maximum ``top``."""
    return where & np.isfinite(field) & (field >= top * (1.0 - rel))


def _distance(point: np.ndarray, xyz: np.ndarray, near: np.ndarray, scale: np.ndarray
              ) -> float:
    """Distance (in units of ``scale`` per axis) from ``point`` to the points ``near``."""
    if not near.any():
        return math.inf
    return float(np.min(np.linalg.norm((xyz[near] - point) / scale, axis=1)))


def rows(samples: Sequence[PlaneSamples], *, rel: float, cell: Sequence[float], a0: float,
         a: float, z_below: float | None = None) -> list[tuple[str, str, float]]:
    """Metric rows (quantity, metric, value) of the σ_VM maximum (module doc): ``vm_max``
    ``rel`` off the edge band — ``surface`` instead, with its companion ``vm_max_below``
    ``rel``, when either solver's maximum lies shallower than a quarter of the contact
    radius ``a`` (``z_below`` where the case sets it), its companion taken from
    :func:`below_depth` on — and
    ``edge`` over every point; ``vm_max_loc``, the location of the gated maximum, in
    ``cells`` (``cell``: the cell sizes along x, y, z) and in ``a0``.  None without
    samples."""
    if not samples:
        return []
    xyz = np.concatenate([p.xyz for p in samples])
    fa = np.concatenate([p.a for p in samples])
    fb = np.concatenate([p.b for p in samples])
    off = np.concatenate([p.off for p in samples])
    ia, ib = _top(fa, off), _top(fb, off)
    if ia < 0 or ib < 0 or not (fb[ib] > 0):
        return []
    value = abs(fa[ia] - fb[ib]) / fb[ib]
    shallow = 0.25 * a if z_below is None else z_below
    where = off  # the region whose maximum and its location are gated
    if min(xyz[ia, 2], xyz[ib, 2]) >= shallow * (1.0 - 1e-9):
        out = [("vm_max", "rel", value)]
    else:  # a near-surface maximum: shown, its companion below gated
        out = [("vm_max", SURFACE, value)]
        depth = below_depth(cell, a, z_below)
        where = off & (xyz[:, 2] >= depth * (1.0 - 1e-9))
        ia, ib = _top(fa, where), _top(fb, where)
        if ia >= 0 and ib >= 0 and fb[ib] > 0:
            out.append(("vm_max_below", "rel", abs(fa[ia] - fb[ib]) / fb[ib]))
    ja, jb = _top(fa, np.ones_like(off)), _top(fb, np.ones_like(off))
    out.append(("vm_max", EDGE, abs(fa[ja] - fb[jb]) / fb[jb]))
    if ia < 0 or ib < 0:
        return out
    near_a, near_b = _near(fa, where, fa[ia], rel), _near(fb, where, fb[ib], rel)
    for metric, scale in (("cells", np.asarray(cell, float)), ("a0", np.full(3, a0))):
        out.append(("vm_max_loc", metric, max(_distance(xyz[ia], xyz, near_b, scale),
                                              _distance(xyz[ib], xyz, near_a, scale))))
    return out


def below_depth(cell: Sequence[float], a: float, z_below: float | None = None) -> float:
    """The depth from which the companion of a near-surface σ_VM maximum is taken:
    ``stress.z_below`` where a case sets it, else a quarter of the contact radius ``a`` and
    at least two cells, below the reach of the tractions' cell-wise discretisation
    (module doc)."""
    if z_below is not None:
        return float(z_below)
    return max(0.25 * a, 2.0 * max(cell))
