"""Compare solvers pairwise: tractions, wear, contact extent, σ_VM planes and maxima.

For every pair of solvers (in registry order, the second one the reference: ``ic-fem``,
``ic-analytic``, ``fem-analytic``), sweep point and output step present in both, fields
are interpolated onto common sample points — per axis, the coarser of the two grids'
coordinates inside their overlap — and reduced to the metrics of
:mod:`reports.registry.tolerances`.  Quantities missing from either solver, or zero in both, are
skipped; a NaN metric fails.

Max norms leave out the *edge band*: the sample points within one cell of either
solver's contact boundary.  There a cell-average (IC) and a point value (FEM, closed
forms) of a traction that falls to zero inside the cell differ by a fraction of the
traction itself, and a worn contact, whose pressure drops almost as a step at the edge
(Argatov's limit is uniform pressure), makes that fraction O(1) at any grid size; the
near-edge σ_VM follows the edge traction (its gradient ∝ jump/distance).  The L2 norms
of the tractions, the semi-widths and the contact area still measure the edge.  The
σ_VM planes are compared over the contact's neighbourhood (:func:`neighbourhood`),
their edge band left out of both norms — the plane points within one cell (the coarser
sample spacing) or the longer of the two solvers' stress reaches (``SolverRecord.reach``:
the FEM's element diameter, for its stress at a point is the linear field of the element
holding it, which an element reaching the edge's √ profile carries to all its points)
of either solver's contact boundary, by their distance in space to the boundary's
surface points, so that a plane off the centre, which crosses the boundary
obliquely, leaves out what passes near it (the false alarm that showed it:
benchmarks/README.md, "False alarms"): at a worn
frictional edge the surface stress is log-singular (docs/formulation.md §2.6), the
neighbourhood of the singularity carries most of the difference and no grid settles it
(worn pin, quick set-up, μ = 0.5,
s = 160 mm: ic 41² against ic 161² 0.030 with the band, 0.015 without; the FEM 0.040
and 0.010).  The σ_VM maximum and its location are compared by
:mod:`reports.compare.maxima`.

Max norms of the tangential tractions and both norms of the σ_VM planes also leave out
the *stick band*: the sample points within one cell — the coarser of the two solvers' own
cells (``SolverRecord.cell_size``, the FEM's element) and the sample spacing — of either
solver's stick–slip boundary (a stick point with a slip point of the same solver that
close, or the reverse; on the planes, within the edge band's width of the boundary's
surface points — one cell or the pair's stress reach, the longer: an element that
reaches the kink carries its error to every point of it, as one that reaches the contact
edge does; the false alarm that showed it: benchmarks/README.md, "False alarms").  There
the tangential traction has a √(c − r) kink (docs/formulation.md §2.7):
a field held at points h apart and interpolated between them misses it by O(√(h/a)) of
μp₀ whatever the solver, so the max norm across it measures the node spacing, not the
solver (Cattaneo–Mindlin, Q/μP = 0.25, exact Mindlin sampled at the FEM's nodes and
interpolated: 0.266 at a0/8, 0.177 at a0/12, 0.092 at a0/24).  The max over the band is
still written, as the metric ``kink``, and is not gated (status "not gated", reason
``stick_band``); the
tractions' L2 norms (under the slip zone's resolution floor, :mod:`reports.registry.
resolution`) and the stick-zone radius (``stick_area``) still measure the boundary.  The
planes' L2 norms leave the band out too: they have no such floor, and where the slip
annulus spans less than a cell the kink's band at the surface holds most of their
difference (the false alarm that showed it: benchmarks/README.md, "False alarms").

Fretting runs also carry per-cycle tables (``loops``: cycle, displacement, Qx, Qy;
``cycles``: cycle, energy, ...); at an output step whose ``cycle`` both solvers' tables
hold, the loop (``loop_q``) and the dissipated energy (``energy``) of that cycle are
compared too (:func:`compare_tables`); a cycle only one solver has is skipped.
"""

from __future__ import annotations

import math

import numpy as np

from cases.model import Friction
from cases.result import StepResult, vm_max_location
from reports.compare import laws, maxima
from reports.compare.sampling import (
    common_axis,
    contact_boundary,
    contact_edges,
    edge_band,
    interior,
    off_boundary,
    off_edges,
    sample,
    spacing,
    stick_band,
    stick_edges,
)
from reports.registry import tolerances as tol

_TINY = 1e-12
#: the metric of the max over the stick band (module doc): written, never gated
KINK = "kink"
KINK_NOTE = ("max within one cell of the stick-slip boundary, where the traction has a "
             "sqrt(c - r) kink that points h apart miss by O(sqrt(h/a)): it measures the "
             "node spacing, not the solver; not gated (reports.compare.metrics)")


def field_errors(fa: np.ndarray, fb: np.ndarray, mask: np.ndarray | None,
                 scale: float, ref: np.ndarray | None = None,
                 max_mask: np.ndarray | None = None) -> dict[str, float] | None:
    """Relative L2 and max errors of ``fa`` against ``fb`` on ``mask`` (None: skip).

    The max norm of the difference is taken on ``mask & max_mask`` (the points off the
    edge band, see the module doc), or on ``mask`` when that leaves no point (a contact
    of a few cells).  The norms of ``ref`` (default ``fb``, over all of ``mask``)
    normalise the errors: a traction component is measured against the whole
    tangential traction |p_t| of the reference, so that a component that is nearly zero
    in both solvers does not produce a large relative error.  Points where a field is
    NaN are ignored; with no point left, or both fields zero (below 1e-12 ``scale``),
    there is nothing to compare.  A reference that is zero while the other field is not
    is normalised by ``scale``.
    """
    ref = fb if ref is None else ref
    ok = np.isfinite(fa) & np.isfinite(fb) & np.isfinite(ref)
    if mask is not None:
        ok &= mask
    if not ok.any():
        return None
    a, b, r = fa[ok], fb[ok], ref[ok]
    tiny = _TINY * scale
    if np.max(np.abs(a)) <= tiny and np.max(np.abs(b)) <= tiny:
        return None
    diff = a - b
    if np.max(np.abs(r)) <= tiny:  # reference identically zero: normalise by the scale
        l2_ref, max_ref = scale * math.sqrt(r.size), scale
    else:
        l2_ref, max_ref = float(np.linalg.norm(r)), float(np.max(np.abs(r)))
    inner = np.ones(diff.shape, dtype=bool) if max_mask is None else max_mask[ok]
    if not inner.any():
        inner[:] = True
    return {"l2": float(np.linalg.norm(diff)) / l2_ref,
            "max": float(np.max(np.abs(diff[inner]))) / max_ref}


# ------------------------------------------------------------------ per step


def scalar(step: StepResult, key: str) -> float:
    value = step.scalars.get(key)
    try:
        value = float(value)
    except (TypeError, ValueError):
        return math.nan
    return value


def _vm_location(step: StepResult) -> tuple[float, float, float, float]:
    """(vm_max, x, y, z) from the scalars, else from the planes (crossing at the ``x0``,
    ``y0`` scalars, default 0)."""
    keys = ("vm_max", "vm_max_x", "vm_max_y", "vm_max_z")
    vals = tuple(scalar(step, k) for k in keys)
    if all(math.isfinite(v) for v in vals):
        return vals  # type: ignore[return-value]
    return vm_max_location(step.planes, float(step.scalars.get("x0", 0.0)),
                           float(step.scalars.get("y0", 0.0)))


def _plane_edges(step: StepResult, name: str, s: np.ndarray, x0: float, y0: float
                 ) -> np.ndarray:
    """Contact boundary of a step along the surface line of plane ``name`` (xz: y = y0,
    yz: x = x0), at the plane's samples ``s``; empty without a surface pressure."""
    if not step.surface or "p_n" not in step.surface:
        return np.empty(0)
    at = (s, np.array([y0])) if name == "xz" else (np.array([x0]), s)
    line = sample((step.x, step.y), step.surface["p_n"], at).ravel()
    return contact_edges(s, line)


def compare_steps(sa: StepResult, sb: StepResult, *, a0: float, p0: float,
                  x0: float = 0.0, y0: float = 0.0, cell: float = 0.0, reach: float = 0.0,
                  vm_rel: float = 0.02, z_below: float | None = None,
                  friction: Friction | None = None) -> list[tuple[str, str, float]]:
    """Metric rows (quantity, metric, value) of step ``sa`` against reference ``sb``
    (planes through (x0, y0)).  ``cell``: the coarser of the two
    solvers' own cell sizes (``SolverRecord.cell_size``, e.g. the FEM's element size),
    the unit of the ``cells`` metrics where it is coarser than the sample spacing.
    ``reach``: the longer of the two solvers' stress reaches (``SolverRecord.reach``, the
    FEM's element diameter), the planes' edge band where longer than the sample spacing.
    ``vm_rel``: the pair's ``vm_max`` tolerance, which bounds the near-maximum sets of
    ``vm_max_loc`` (:mod:`reports.compare.maxima`).  ``friction``: the case's, for the
    friction law's row (:mod:`reports.compare.laws`)."""
    hx = max(spacing(sa.x), spacing(sb.x))
    hy = max(spacing(sa.y), spacing(sb.y))
    band = max(hx, hy, cell)  # the stick band's half-width (module doc)
    rows = _surface_rows(sa, sb, a0, p0, band, tangential_scale(p0, friction))
    plane_rows, hz, samples = _plane_rows(sa, sb, p0, x0, y0, max(hx, hy, reach), band)
    cells = (max(hx, cell), max(hy, cell), max(hz, cell) if hz > 0 else 0.0)
    radius = [scalar(st, k) for st in (sa, sb) for k in ("a_x", "a_y")]
    a = max((r for r in radius if math.isfinite(r)), default=a0)
    vm_rows = maxima.rows(samples, rel=vm_rel, cell=cells, a0=a0, a=a, z_below=z_below)
    law = laws.rows(sa, sb, friction)
    return rows + law + plane_rows + vm_rows + _scalar_rows(sa, sb, a0, p0, *cells,
                                                            vm_from_scalars=not vm_rows)


def tangential_scale(p0: float, friction: Friction | None) -> float:
    """The largest tangential traction a contact of peak pressure ``p0`` can carry, μ p0
    (μ the larger principal coefficient, Eq. 9): the scale of a tangential traction whose
    reference is zero, so that a traction that should not be there is measured on the
    size it could have, not on p0 (p0 without friction, where any traction is wrong)."""
    mu = max(friction.mu1, friction.mu2) if friction is not None else 0.0
    return mu * p0 if mu > 0 else p0


def _surface_rows(sa: StepResult, sb: StepResult, a0: float, p0: float, band: float,
                  q0: float) -> list[tuple[str, str, float]]:
    """Surface fields: the L2 norms over the contact of either solver, off each one's edge
    band (a contact one of them lacks is an error, not a smaller support); the max norms
    over the interior of the common contact, the tangential tractions' also off the stick
    band of half-width ``band`` (module doc).  ``q0``: the tangential tractions' scale
    (:func:`tangential_scale`)."""
    if not (sa.surface and sb.surface and "p_n" in sa.surface and "p_n" in sb.surface):
        return []
    xs, ys = common_axis(sa.x, sb.x), common_axis(sa.y, sb.y)
    if not (xs.size and ys.size):
        return []
    pa = sample((sa.x, sa.y), sa.surface["p_n"], (xs, ys))
    pb = sample((sb.x, sb.y), sb.surface["p_n"], (xs, ys))
    contact = (pa > 0) & (pb > 0)
    # the L2 norms: over either solver's contact (a contact one of them lacks is an error,
    # not a smaller support), off the edge band of each
    l2_mask = ((pa > 0) | (pb > 0)) & ~(edge_band(pa > 0) | edge_band(pb > 0))
    fields = {"p_n": (pa, pb)}
    for q in tol.SURFACE_FIELDS[1:]:
        if q in sa.surface and q in sb.surface:
            fields[q] = (sample((sa.x, sa.y), sa.surface[q], (xs, ys)),
                         sample((sb.x, sb.y), sb.surface[q], (xs, ys)))
    pt_ref = None
    if "p_x" in fields and "p_y" in fields:
        pt_ref = np.hypot(fields["p_x"][1], fields["p_y"][1])
    wear_ref = _wear_reference(fields, a0)
    inner = interior(contact)
    kink = stick_band((sa, sb), xs, ys, band) & contact
    rows = []
    for q, (fa, fb) in fields.items():
        tangential = q in ("p_x", "p_y")
        scale = q0 if tangential else p0 if q == "p_n" else a0
        ref = pt_ref if tangential else wear_ref.get(q)
        off = inner & ~kink if tangential else inner
        err = field_errors(fa, fb, l2_mask, scale, ref, max_mask=off)
        if err is not None:
            rows += [(q, m, err[m]) for m in tol.QUANTITY_METRICS[q]]
            rows += _kink_row(q, fa, fb, l2_mask, kink if tangential else None, scale, ref)
    return rows


def _wear_reference(fields: dict, a0: float) -> dict[str, np.ndarray]:
    """The norm of a body's wear where the reference solver wears that body not at all
    but the other one: the reference's whole wear (both bodies), so that wear of the
    wrong body is an error of the wear's own size, not one of the wear over the contact
    radius (the scale of a zero reference in :func:`field_errors`).  Without any wear in
    the reference, the scale stays."""
    tiny = _TINY * a0
    wear = {q: f for q, f in fields.items() if q.startswith("wear_")}
    if not wear:
        return {}
    total = sum(np.abs(fb) for _, fb in wear.values())
    if not np.nanmax(total, initial=0.0) > tiny:
        return {}
    return {q: total for q, (_, fb) in wear.items()
            if not np.nanmax(np.abs(fb), initial=0.0) > tiny}


def _kink_row(q: str, fa: np.ndarray, fb: np.ndarray, mask: np.ndarray | None,
              kink: np.ndarray | None, scale: float, ref: np.ndarray | None = None
              ) -> list[tuple[str, str, float]]:
    """The ``kink`` row of a field: its max error over the stick band ``kink`` (in the
    normalisation of the max norm), none when the band holds no point of ``mask``."""
    if kink is None:
        return []
    ok = kink & np.isfinite(fa) & np.isfinite(fb)
    if mask is not None:
        ok &= mask
    if not ok.any():
        return []
    err = field_errors(fa, fb, mask, scale, ref, max_mask=kink)
    return [] if err is None else [(q, KINK, err["max"])]


def _plane_rows(sa: StepResult, sb: StepResult, p0: float, x0: float, y0: float,
                edge: float, band: float = 0.0
                ) -> tuple[list[tuple[str, str, float]], float, list[maxima.PlaneSamples]]:
    """Subsurface σ_VM planes over the contact's neighbourhood, the edge band of
    half-width ``edge`` left out (:func:`neighbourhood`); both norms also leave out the
    stick band, of half-width ``band`` or ``edge`` (the longer), below the stick
    boundary's surface points (module doc).  Also the larger depth spacing hz of the
    planes (0 if none) and both solvers' σ_VM at the common points
    (:mod:`reports.compare.maxima`)."""
    rows, hz, samples = [], 0.0, []
    for q, name in tol.PLANE_FIELDS.items():
        pa_, pb_ = sa.planes.get(name), sb.planes.get(name)
        if pa_ is None or pb_ is None or "vm" not in pa_.fields or "vm" not in pb_.fields:
            continue
        hz = max(hz, spacing(pa_.z), spacing(pb_.z))
        ss, zs = common_axis(pa_.s, pb_.s), common_axis(pa_.z, pb_.z)
        if not (ss.size and zs.size):
            continue
        fa = sample((pa_.s, pa_.z), pa_.fields["vm"], (ss, zs))
        fb = sample((pb_.s, pb_.z), pb_.fields["vm"], (ss, zs))
        edges = np.concatenate([_plane_edges(st, name, ss, x0, y0) for st in (sa, sb)])
        surface = maxima.plane_points(name, ss, np.zeros(1), x0, y0)[:, :2]
        boundary = np.concatenate([contact_boundary(st) for st in (sa, sb)])
        off = off_boundary(surface, zs, boundary, edge)
        line = (ss, np.array([y0])) if name == "xz" else (np.array([x0]), ss)
        kinks = np.concatenate([stick_edges(st, ss, line) for st in (sa, sb)])
        kink = off & ~off_edges(ss, zs, kinks, max(band, edge)) if kinks.size else None
        mask = off & neighbourhood(ss, zs, edges)
        # both norms off the stick band: below the kink, the plane carries the traction's
        # unresolved √(c − r) (the tractions' own L2 has the slip zone's floor instead)
        err = field_errors(fa, fb, mask if kink is None else mask & ~kink, p0)
        if err is not None:
            rows += [(q, m, err[m]) for m in tol.QUANTITY_METRICS[q]]
            rows += _kink_row(q, fa, fb, mask, kink, p0)
        samples.append(maxima.PlaneSamples(maxima.plane_points(name, ss, zs, x0, y0),
                                           fa.ravel(), fb.ravel(), off.ravel()))
    return rows, hz, samples


def neighbourhood(s: np.ndarray, z: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """The plane points (s, z) within one contact half-chord of the contact's chord on the
    surface line (between its outermost boundary points ``edges``): the region a contact
    stresses, so that the plane norms do not depend on how far a case's grid and stress
    planes extend beyond it (all points where the line misses the contact)."""
    if edges.size < 2:
        return np.ones((s.size, z.size), dtype=bool)
    lo, hi = float(edges.min()), float(edges.max())
    ds = np.maximum(np.maximum(lo - s, s - hi), 0.0)
    return np.hypot(ds[:, None], z[None, :]) <= 0.5 * (hi - lo) * (1.0 + 1e-9)


def _scalar_rows(sa: StepResult, sb: StepResult, a0: float, p0: float, hx: float,
                 hy: float, hz: float, vm_from_scalars: bool = True
                 ) -> list[tuple[str, str, float]]:
    """Peak values (relative), semi-widths and equivalent radii (in cells); with
    ``vm_from_scalars`` (a pair without common σ_VM planes) also the σ_VM maximum and its
    location (in cells and in a0) from the solvers' own scalars."""
    h = max(hx, hy)
    rows: list[tuple[str, str, float]] = []
    scale_of = {"P": p0 * a0 * a0, "p_max": p0, "vm_max": p0, "vm_max_below": p0, "w_max": a0,
                "wear_volume": a0**3}
    for q in tol.REL_SCALARS:
        if q in ("vm_max", "vm_max_below") and not vm_from_scalars:
            continue  # from the planes (reports.compare.maxima)
        a, b = scalar(sa, q), scalar(sb, q)
        if q == "vm_max":
            a, b = _vm_location(sa)[0], _vm_location(sb)[0]
        if math.isnan(a) or math.isnan(b):
            continue  # not reported by one solver (e.g. no closed form)
        tiny = _TINY * scale_of[q]
        if abs(a) <= tiny and abs(b) <= tiny:
            continue
        rows.append((q, "rel", abs(a - b) / abs(b) if abs(b) > tiny else math.inf))
    for q, cell in (("a_x", hx), ("a_y", hy)):
        a, b = scalar(sa, q), scalar(sb, q)
        if not (math.isnan(a) or math.isnan(b)) and cell > 0:
            rows.append((q, "cells", abs(a - b) / cell))
    for q in tol.AREA_SCALARS:
        a, b = scalar(sa, q), scalar(sb, q)
        if math.isnan(a) or math.isnan(b) or h <= 0:
            continue
        if abs(a) <= _TINY * a0**2 and abs(b) <= _TINY * a0**2:
            continue
        ra = math.sqrt(max(a, 0.0) / math.pi) if math.isfinite(a) else math.nan
        rb = math.sqrt(max(b, 0.0) / math.pi) if math.isfinite(b) else math.nan
        rows.append((q, "cells", abs(ra - rb) / h))
    la, lb = _vm_location(sa), _vm_location(sb)
    if vm_from_scalars and all(math.isfinite(v) for v in la + lb):
        d = np.subtract(la[1:], lb[1:])
        cells = np.array([hx, hy, hz if hz > 0 else h])
        cells[cells <= 0] = h if h > 0 else 1.0
        rows.append(("vm_max_loc", "cells", float(np.linalg.norm(d / cells))))
        rows.append(("vm_max_loc", "a0", float(np.linalg.norm(d)) / a0))
    return rows


# ------------------------------------------------------------------ per case


