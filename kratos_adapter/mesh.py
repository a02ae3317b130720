"""The two bodies of a sphere-on-plane case as quarter models of structured trilinear
hexahedra (Kratos' mortar contact conditions are then bilinear quadrilaterals).

Body b (the plane) is the block [0, L] x [0, L] x [-H, 0]; body a (the sphere) the block
[0, L] x [0, L] x [0, H] whose lower face is carried onto the sphere's profile
z = r² / 2R by the map z -> z + (r² / 2R)(1 - z / H) (the profile of the closed forms and
of the half-space solver; the map moves the nodes by at most r²/2R and leaves the top
face flat).  Global z points into body a (README, Conventions).  Both bodies have the
same tensor grid of spacings (:func:`graded`): h near the contact, finer layers under
the contact face, growing away from it.

Why hexahedra: on the bundled Hertz case at h = a0/6, quarter models of linear
tetrahedra (gmsh, the same sizes) gave nodal pressures scattered by ±0.05–0.08 p0 about
Hertz's from node to node (the unstructured elements' stiffness), p_max 4.6 % high
(2.5 % at a0/10); the structured hexahedra give a smooth pressure, p_max within 0.05 %
(benchmarks/README.md, "Kratos through the gates").  The tensor grid is built here
with numpy (no mesher needed); no code is shared with ``fem_reference``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Body:
    """One meshed quarter body: node coordinates (n, 3), its cells (m, 8) as indices into
    them (Kratos' hexahedron order), the contact face's quadrilaterals (k, 4) turned to
    the outward normal, and the node indices of its faces by name (``x0``, ``y0``: the
    symmetry planes; ``far``: the face opposite the contact; ``contact``)."""

    nodes: np.ndarray
    cells: np.ndarray
    contact: np.ndarray
    faces: dict[str, np.ndarray]


#: the structured mesh: uniform spacing h out to :data:`HEX_FINE` a0 from the centre (in
#: x, y and depth), then spacings growing by :data:`HEX_GROWTH` per element to the side L
HEX_FINE = 1.5
HEX_GROWTH = 1.5
#: the first element layer under the contact face, in h (growing to h by HEX_GROWTH)
SURFACE = 0.5


def graded(h: float, fine: float, side: float, surface: float | None = None) -> np.ndarray:
    """Coordinates 0 … ``side``: spacing ``h`` up to ``fine`` (rounded to whole elements),
    then growing by :data:`HEX_GROWTH` per element, the last one stretched to end at
    ``side``; with ``surface``, the first spacings are ``surface`` growing by
    :data:`HEX_GROWTH` up to ``h`` (the depth direction: the stresses' steep gradient
    under the surface)."""
    x = [0.0]
    step = surface if surface is not None else h
    while step < h:
        x.append(x[-1] + step)
        step *= HEX_GROWTH
    n = max(1, round((fine - x[-1]) / h))
    x += list(x[-1] + np.arange(1, n + 1) * h)
    step = h
    while x[-1] < side:
        step *= HEX_GROWTH
        x.append(x[-1] + step)
    if len(x) > n + 2 and (x[-1] - side) > 0.5 * step:
        x.pop()
    x[-1] = side
    return np.asarray(x)


def _hex_box(xs: np.ndarray, zs: np.ndarray, outward: float) -> Body:
    """The hexahedra of the tensor grid xs × xs × zs (zs increasing); the contact face
    is the plane z = 0 (the top of body b, ``outward`` +1, or the bottom of body a, -1)."""
    nx, nz = xs.size, zs.size
    X, Y, Z = np.meshgrid(xs, xs, zs, indexing="ij")
    nodes = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
    idx = np.arange(nodes.shape[0]).reshape(nx, nx, nz)
    c = idx[:-1, :-1, :-1].ravel()
    dx, dy, dz = nx * nz, nz, 1  # index strides along x, y, z
    hexes = np.stack([c, c + dx, c + dx + dy, c + dy,
                      c + dz, c + dx + dz, c + dx + dy + dz, c + dy + dz], axis=1)
    k0 = nz - 1 if outward > 0 else 0
    q = idx[:-1, :-1, k0].ravel()
    quads = np.stack([q, q + dx, q + dx + dy, q + dy], axis=1)
    if outward < 0:
        quads = quads[:, ::-1]
    far = idx[:, :, 0 if outward > 0 else nz - 1].ravel()
    faces = {"x0": idx[0].ravel(), "y0": idx[:, 0].ravel(),
             "contact": idx[:, :, k0].ravel(), "far": far}
    return Body(nodes=nodes, cells=hexes, contact=quads, faces=faces)


def hex_bodies(a0: float, R: float, h: float, side: float, height: float
               ) -> tuple[Body, Body]:
    """(body a, body b): the quarter sphere cap and the quarter block (module doc), with
    spacing ``h`` [mm] near the contact, side L = ``side`` and height H = ``height``."""
    xs = graded(h, HEX_FINE * a0, side)
    zs = graded(h, HEX_FINE * a0, height, SURFACE * h)
    b = _hex_box(xs, -zs[::-1], 1.0)
    a = _hex_box(xs, zs, -1.0)
    x, y, z = a.nodes.T
    a.nodes[:, 2] = z + (x**2 + y**2) / (2.0 * R) * (1.0 - z / height)
    return a, b


def node_count(a0: float, h: float, side: float) -> int:
    """The nodes of the two quarter bodies of :func:`hex_bodies` (no mesh built)."""
    xs = graded(h, HEX_FINE * a0, side)
    zs = graded(h, HEX_FINE * a0, side, SURFACE * h)
    return 2 * xs.size**2 * zs.size
