"""Sampling two solvers' fields onto common points, and the bands the max norms leave out.

Fields are interpolated onto common sample points — per axis, the coarser of the two
grids' coordinates inside their overlap.  The *edge band* (points within one cell of a
contact boundary) and the *stick band* (points within one cell of a stick–slip boundary)
are found here; why the max norms leave them out is in :mod:`reports.compare.metrics`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy import ndimage
from scipy.interpolate import RegularGridInterpolator
from scipy.spatial import cKDTree

from cases.result import SLIP, STICK, StepResult

_TINY = 1e-12


def spacing(coords: np.ndarray) -> float:
    coords = np.asarray(coords, dtype=float)
    return float(np.max(np.diff(coords))) if coords.size > 1 else 0.0


def common_axis(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The coarser of two sorted coordinate vectors, restricted to their overlap."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    lo, hi = max(a.min(), b.min()), min(a.max(), b.max())
    eps = 1e-9 * max(a.max() - a.min(), b.max() - b.min(), 1.0)
    coarse = a if a.size <= b.size else b
    return coarse[(coarse >= lo - eps) & (coarse <= hi + eps)]


def sample(axes: Sequence[np.ndarray], values: np.ndarray,
           at: Sequence[np.ndarray]) -> np.ndarray:
    """Linear interpolation of a field on a regular grid at the tensor points ``at``.

    An axis with a single coordinate (a field known on one line only) is matched
    exactly: samples off that line are NaN.  Samples outside the grid are NaN.
    """
    axes = [np.asarray(ax, dtype=float) for ax in axes]
    at = [np.asarray(q, dtype=float) for q in at]
    values = np.asarray(values, dtype=float)
    shape = tuple(q.size for q in at)
    mask = np.ones(shape, dtype=bool)
    single = [dim for dim, ax in enumerate(axes) if ax.size == 1]
    for dim in single:
        ok = np.isclose(at[dim], axes[dim][0], rtol=0.0,
                        atol=1e-9 * max(1.0, abs(axes[dim][0])))
        mask &= ok.reshape([-1 if d == dim else 1 for d in range(len(at))])
    keep = [dim for dim in range(len(axes)) if dim not in single]
    reduced = values.reshape([axes[d].size for d in keep]) if keep else values.reshape(())
    if keep:
        interp = RegularGridInterpolator([axes[d] for d in keep], reduced, method="linear",
                                         bounds_error=False, fill_value=np.nan)
        mesh = np.meshgrid(*[at[d] for d in keep], indexing="ij")
        part = interp(np.stack([m.ravel() for m in mesh], axis=-1))
        part = part.reshape([at[d].size if d in keep else 1 for d in range(len(at))])
    else:
        part = reduced.reshape([1] * len(at))
    out = np.broadcast_to(part, shape).copy()
    out[~mask] = np.nan
    return out


def interior(contact: np.ndarray) -> np.ndarray:
    """The points of a contact mask whose eight neighbours are in contact too."""
    return ndimage.binary_erosion(contact, structure=np.ones((3, 3), dtype=bool),
                                  border_value=0)


def edge_band(contact: np.ndarray) -> np.ndarray:
    """The points within one cell of a contact's boundary, on either side of it."""
    cross = np.ones((3, 3), dtype=bool)
    return (ndimage.binary_dilation(contact, structure=cross)
            & ~ndimage.binary_erosion(contact, structure=cross, border_value=0))


def contact_edges(s: np.ndarray, p_n: np.ndarray) -> np.ndarray:
    """Contact boundary points along a line: midpoints between a sample with p_n > 0
    and a neighbour without."""
    on = np.nan_to_num(np.asarray(p_n, dtype=float)) > 0
    k = np.flatnonzero(on[1:] != on[:-1])
    return 0.5 * (s[k] + s[k + 1])


def _state_is(step: StepResult, value: int, at: Sequence[np.ndarray]) -> np.ndarray | None:
    """Where a step's contact ``state`` is ``value`` at the points ``at`` (its indicator
    interpolated, then > 1/2); None without a state field."""
    state = step.surface.get("state") if step.surface else None
    if state is None:
        return None
    on = (np.asarray(state) == value).astype(float)
    return np.nan_to_num(sample((step.x, step.y), on, at)) > 0.5


def stick_band(steps: Sequence[StepResult], xs: np.ndarray, ys: np.ndarray,
               width: float) -> np.ndarray:
    """Sample points of ``xs`` × ``ys`` within ``width`` of a stick–slip boundary of any of
    ``steps``: a stick point with a slip point of the same step that close, or the
    reverse (module doc).  Empty where a step has no stick or no slip points."""
    band = np.zeros((xs.size, ys.size), dtype=bool)
    step = (max(spacing(xs), _TINY), max(spacing(ys), _TINY))
    for st in steps:
        stick, slip = _state_is(st, STICK, (xs, ys)), _state_is(st, SLIP, (xs, ys))
        if stick is None or slip is None or not stick.any() or not slip.any():
            continue
        for here, there in ((stick, slip), (slip, stick)):
            d = ndimage.distance_transform_edt(~there, sampling=step)
            band |= here & (d <= width * (1.0 + 1e-9))
    return band


def stick_edges(step: StepResult, s: np.ndarray, line: tuple[np.ndarray, np.ndarray]
                ) -> np.ndarray:
    """Stick–slip boundary points along a surface line (the tensor points ``line``, one of
    them of size 1, ``s`` the other): midpoints between a stick and a slip sample."""
    stick, slip = _state_is(step, STICK, line), _state_is(step, SLIP, line)
    if stick is None or slip is None:
        return np.empty(0)
    stick, slip = stick.ravel(), slip.ravel()
    k = np.flatnonzero((stick[:-1] & slip[1:]) | (slip[:-1] & stick[1:]))
    return 0.5 * (s[k] + s[k + 1])


def contact_boundary(step: StepResult) -> np.ndarray:
    """The contact boundary of a step on its surface grid, as points (n, 2): the midpoints
    between a sample with p_n > 0 and a neighbour along x or y without; empty without a
    surface pressure."""
    if not step.surface or "p_n" not in step.surface:
        return np.empty((0, 2))
    on = np.nan_to_num(np.asarray(step.surface["p_n"], dtype=float)) > 0
    x, y = np.asarray(step.x, dtype=float), np.asarray(step.y, dtype=float)
    i, j = np.nonzero(on[1:, :] != on[:-1, :])
    along_x = np.column_stack([0.5 * (x[i] + x[i + 1]), y[j]])
    i, j = np.nonzero(on[:, 1:] != on[:, :-1])
    along_y = np.column_stack([x[i], 0.5 * (y[j] + y[j + 1])])
    return np.concatenate([along_x, along_y])


def off_boundary(line: np.ndarray, z: np.ndarray, boundary: np.ndarray, width: float
                 ) -> np.ndarray:
    """Plane points farther than ``width`` from every contact boundary point: ``line``
    (n, 2) the plane's surface points (x, y), ``z`` its depths, ``boundary`` (m, 2) the
    boundary's surface points (:func:`contact_boundary`).  The distance is the true one
    in space, so that a plane crossing the boundary obliquely (off the centre) leaves out
    the points the boundary passes near, not only those near its crossing."""
    if boundary.size == 0:
        return np.ones((len(line), z.size), dtype=bool)
    d, _ = cKDTree(boundary).query(line)
    return np.hypot(np.asarray(d)[:, None], z[None, :]) > width


def off_edges(s: np.ndarray, z: np.ndarray, edges: np.ndarray, width: float) -> np.ndarray:
    """Plane points (s, z) farther than ``width`` from every surface point (edge, 0)."""
    if edges.size == 0:
        return np.ones((s.size, z.size), dtype=bool)
    ds = np.min(np.abs(s[:, None] - edges[None, :]), axis=1)
    return np.hypot(ds[:, None], z[None, :]) > width
