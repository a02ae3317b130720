"""The reported contact region of a step: output states, semi-widths, boundary and area.

A point counts as closed when its gap lies below ε = ``GAP_TOL`` × a_ref²/R (the Hertz
approach; see :func:`contact_states`).  The contact boundary r(θ) is the outermost
closed point along rays from the centre (:func:`ray_extent`); a grid cell is closed
inside it, and then stick or slip by the return map at its centre.  The contact area is
the area inside r(θ), the semi-widths ``a_x, a_y`` half the closed length of the lines
through the centre (:func:`semi_width`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from cases.result import OPEN, SLIP, STICK

from .contact import Evaluation
from .sampling import ProbeLayout

GAP_TOL = 1e-4  # a gap below GAP_TOL * a_ref²/R (the Hertz approach) counts as closed


def gap_tolerance(a_ref: float, R: float) -> float:
    """ε: gaps below it count as closed (``GAP_TOL`` times the Hertz approach a_ref²/R)."""
    return GAP_TOL * a_ref**2 / R


def contact_states(ev: Evaluation, eps: float) -> np.ndarray:
    """Output states: closed (gap < eps) points are stick or slip, the others open.

    The penalty law loads only penetrating points, and near the contact edge the sign of
    a gap of the order of the FE interpolation error (≪ p/k_n) decides; counting gaps
    below a tolerance ε as closed makes the contact region independent of the penalty.
    Outside the contact the Hertz gap grows like δ (r/a − 1)^(3/2), so ε = 1e-4 δ moves
    the edge by about 0.2 % of a.
    """
    closed = ev.gn < eps
    return np.where(closed, np.where(ev.state == STICK, STICK, SLIP), OPEN).astype(np.int8)


def semi_width(s: np.ndarray, gn: np.ndarray, inside: np.ndarray, eps: float) -> float:
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


def ray_extent(r: np.ndarray, gn: np.ndarray, inside: np.ndarray, eps: float) -> np.ndarray:
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


def sector_area(theta: np.ndarray, r_edge: np.ndarray, periodic: bool) -> float:
    """Area ½ ∫ r(θ)² dθ inside the boundary r(θ) over the sampled sector (trapezoidal
    rule; on a full circle, ``periodic``, the equal-weight periodic rule)."""
    if periodic:
        return 0.5 * float(np.sum(r_edge**2)) * (theta[1] - theta[0])
    return 0.5 * float(np.trapezoid(r_edge**2, theta))


def inside_boundary(xy: np.ndarray, theta: np.ndarray, r_edge: np.ndarray,
                    periodic: bool) -> np.ndarray:
    """Points ``xy`` (of the modelled part) within the boundary r(θ), linear in θ."""
    rho = np.hypot(xy[:, 0], xy[:, 1])
    phi = np.arctan2(xy[:, 1], xy[:, 0]) % (2 * math.pi)
    if periodic:
        edge = np.interp(phi, theta, r_edge, period=2 * math.pi)
    else:
        edge = np.interp(phi, theta, r_edge)
    return rho <= edge


@dataclass(frozen=True)
class ContactZone:
    """The reported contact region of a step (modelled part of the surface)."""

    state: np.ndarray  # (n,) output state of every probe (int8: OPEN, STICK, SLIP)
    r_edge: np.ndarray  # boundary radius r(θ) along each ray
    area: float  # area inside r(θ) in the modelled sector
    a_x: float  # semi-widths along the x and y lines through the centre
    a_y: float


def contact_zone(layout: ProbeLayout, mapped: np.ndarray, ev: Evaluation, inside: np.ndarray,
                 eps: float) -> ContactZone:
    """The contact region from the probe evaluation ``ev`` (``mapped``: the probes in the
    modelled part; ``inside``: probes in the FE contact zone; ``eps``: the closing gap).

    Lines and rays are closed where their gap is below ``eps``
    (:func:`contact_states`); grid cells inside the boundary r(θ) of the rays.
    """
    ng = layout.ngrid
    r_edge = ray_extent(layout.ray_r, layout.on_rays(ev.gn), layout.on_rays(inside), eps)
    state = contact_states(ev, eps)
    closed = inside_boundary(mapped[:ng], layout.theta, r_edge, layout.periodic) & inside[:ng]
    state[:ng] = np.where(closed, np.where(ev.state[:ng] == STICK, STICK, SLIP), OPEN)
    lx, ly = layout.line_x, layout.line_y
    return ContactZone(
        state=state, r_edge=r_edge,
        area=sector_area(layout.theta, r_edge, layout.periodic),
        a_x=semi_width(layout.line, ev.gn[lx], inside[lx], eps),
        a_y=semi_width(layout.line, ev.gn[ly], inside[ly], eps),
    )
