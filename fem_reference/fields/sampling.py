"""Where the output is sampled on the contact surface: the surface sample points and their
interpolation matrices.

Probes, in this order (global frame, z = 0):

- the cell centres of the case grid (``nx * ny``, row-major in x);
- the x line and the y line through the centre, ``nline`` points each over
  ``[-r_c, r_c]`` at a spacing below h/20;
- rays from the centre over the modelled sector (24 per quarter turn, the last angle of
  a quarter or half sector included), ``nline // 2 + 1`` radii each over ``[0, r_c]``:
  the contact boundary r(θ) of :func:`fem_reference.fields.contact_zone.ray_extent`.

A quarter or half model samples the mirror image of a point in the modelled part; the
reflection signs ``sx, sy`` (0 on a mirror plane) turn the components odd under the
mirror (see :meth:`fem_reference.model.fem_model.Symmetry.map`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from cases.model import Grid

from ..errors import FemError
from ..model.fem_model import FemModel

RAYS_PER_QUARTER = 24
LINE_DIVISIONS = 20.0  # line samples per element size h (at least)


@dataclass(frozen=True)
class SampleLayout:
    """The surface sample points: grid cell centres, the lines through the centre, the rays."""

    xy: np.ndarray  # (n, 2) every sample, global frame
    ngrid: int  # grid cell centres (first)
    line: np.ndarray  # (nline,) abscissae of the lines through the centre
    theta: np.ndarray  # (ntheta,) ray angles
    ray_r: np.ndarray  # radii along each ray
    periodic: bool  # the rays go round the full circle (full model)

    @property
    def nline(self) -> int:
        return self.line.size

    @property
    def grid(self) -> slice:
        return slice(0, self.ngrid)

    @property
    def line_x(self) -> slice:
        return slice(self.ngrid, self.ngrid + self.nline)

    @property
    def line_y(self) -> slice:
        return slice(self.ngrid + self.nline, self.ngrid + 2 * self.nline)

    @property
    def rays(self) -> slice:
        return slice(self.ngrid + 2 * self.nline, self.xy.shape[0])

    def on_rays(self, values: np.ndarray) -> np.ndarray:
        """Probe ``values`` of the rays as (ntheta, nradii), one row per ray."""
        return values[self.rays].reshape(self.theta.size, -1)


def sample_layout(grid: Grid, shape: str, r_c: float, h: float) -> SampleLayout:
    """The samples of a model of ``shape`` with contact zone radius ``r_c`` and element
    size ``h`` in it, for the case grid ``grid``."""
    X, Y = np.meshgrid(grid.x, grid.y, indexing="ij")
    grid_xy = np.column_stack([X.ravel(), Y.ravel()])
    nl = int(math.ceil(2 * r_c / (h / LINE_DIVISIONS))) + 1
    line = np.linspace(-r_c, r_c, nl)
    lx = np.column_stack([line, np.zeros(nl)])
    ly = np.column_stack([np.zeros(nl), line])
    sector = {"quarter": 0.5 * math.pi, "half": math.pi, "full": 2 * math.pi}[shape]
    n_theta = int(round(sector / (0.5 * math.pi) * RAYS_PER_QUARTER))
    theta = np.linspace(0.0, sector, n_theta + (shape != "full"), endpoint=shape != "full")
    ray_r = np.linspace(0.0, r_c, nl // 2 + 1)
    rays = ray_r[None, :, None] * np.stack([np.cos(theta), np.sin(theta)], -1)[:, None, :]
    xy = np.vstack([grid_xy, lx, ly, rays.reshape(-1, 2)])
    return SampleLayout(xy=xy, ngrid=grid_xy.shape[0], line=line, theta=theta, ray_r=ray_r,
                       periodic=shape == "full")


@dataclass(frozen=True)
class SampleInterpolation:
    """Interpolation of the FE surface fields at the samples of ``layout``."""

    layout: SampleLayout
    mapped: np.ndarray  # (n, 2) the samples mapped into the modelled part
    sx: np.ndarray  # reflection signs of the x and y components (0 on a mirror plane)
    sy: np.ndarray
    found: np.ndarray  # samples inside the FE contact zone
    N: sp.csr_matrix  # P2 interpolation on the contact zone (n x surface nodes)
    Nsub: sp.csr_matrix  # nodal values: linear on the four sub-triangles of a facet
    Ntop: sp.csr_matrix  # P2 interpolation on the whole top surface of the block


def sample_interpolation(model: FemModel, layout: SampleLayout) -> SampleInterpolation:
    """The interpolation matrices of the samples on the model's contact surface and on the
    block's top surface (every grid point must lie on the latter)."""
    surf = model.surface
    mapped, sx, sy = model.sym.map(layout.xy)
    N, found = surf.interpolation(mapped)
    Ntop, found_top = model.top.interpolation(mapped)
    if not found_top.all():
        raise FemError("a grid point lies outside the block's top surface")
    Nsub, _ = surf.sub_interpolation(mapped)
    return SampleInterpolation(layout=layout, mapped=mapped, sx=sx, sy=sy, found=found, N=N,
                         Nsub=Nsub, Ntop=Ntop)
