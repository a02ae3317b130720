"""The reported contact region of a step: output states, semi-widths, boundary and area.

A sample counts as closed when more than half of its interpolation weight sits on nodes
in contact (:func:`closing_measure`).  The contact boundary r(θ) is the outermost
closed point along rays from the centre (:func:`ray_extent`); a grid cell is closed
inside it, and then stick or slip by its state.  The contact area is the area inside
r(θ), the semi-widths ``a_x, a_y`` half the closed length of the lines through the
centre (:func:`semi_width`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from cases.result import OPEN, SLIP, STICK

from .sampling import SampleLayout


def contact_states(closing: np.ndarray, state: np.ndarray) -> np.ndarray:
    """Output states: closed points (``closing < 0``) are stick or slip as ``state``
    says, the others open."""
    closed = closing < 0
    return np.where(closed, np.where(state == STICK, STICK, SLIP), OPEN).astype(np.int8)


def closing_measure(active_weight: np.ndarray) -> np.ndarray:
    """``1/2 − w``: negative where the active weight ``w`` of a sample (the indicator of
    the nodes in contact, interpolated linearly on the sub-triangles) exceeds 1/2.

    Each node carries one contact condition, so the discrete contact boundary lies
    between the last node in contact and the first open one; the midpoint is the
    unbiased estimate.  Neither the gap (zero at the nodes in contact, positive between
    the last of them and the first open node whatever the mesh) nor the support of the
    pressure (which reaches the first open node) is: they put the edge one node spacing
    inside or outside.
    """
    return 0.5 - active_weight


def semi_width(s: np.ndarray, closing: np.ndarray, inside: np.ndarray) -> float:
    """Half the length of the closed interval (closing < 0) of a line, interpolated."""
    g = closing
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


def ray_extent(r: np.ndarray, closing: np.ndarray, inside: np.ndarray) -> np.ndarray:
    """Radius of the outermost closed point (closing < 0) along each ray (rows),
    interpolated."""
    g = closing
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

    state: np.ndarray  # (n,) output state of every sample (int8: OPEN, STICK, SLIP)
    r_edge: np.ndarray  # boundary radius r(θ) along each ray
    area: float  # area inside r(θ) in the modelled sector
    a_x: float  # semi-widths along the x and y lines through the centre
    a_y: float


def contact_zone(layout: SampleLayout, mapped: np.ndarray, closing: np.ndarray,
                 state: np.ndarray, inside: np.ndarray) -> ContactZone:
    """The contact region from the samples' ``closing`` measure (negative: closed,
    :func:`closing_measure`) and return-map ``state`` (``mapped``: the samples in the
    modelled part; ``inside``: samples in the FE contact zone).

    Lines and rays are closed where ``closing < 0``; grid cells inside the boundary r(θ)
    of the rays.
    """
    ng = layout.ngrid
    r_edge = ray_extent(layout.ray_r, layout.on_rays(closing), layout.on_rays(inside))
    out = contact_states(closing, state)
    closed = inside_boundary(mapped[:ng], layout.theta, r_edge, layout.periodic) & inside[:ng]
    out[:ng] = np.where(closed, np.where(state[:ng] == STICK, STICK, SLIP), OPEN)
    lx, ly = layout.line_x, layout.line_y
    return ContactZone(
        state=out, r_edge=r_edge,
        area=sector_area(layout.theta, r_edge, layout.periodic),
        a_x=semi_width(layout.line, closing[lx], inside[lx]),
        a_y=semi_width(layout.line, closing[ly], inside[ly]),
    )
