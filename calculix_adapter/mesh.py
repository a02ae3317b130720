"""The two bodies of a sphere-on-plane case as tensor grids of 8-node hexahedra (C3D8),
graded in every direction from the contact.

The gap between the bodies is the sphere's profile h(r) = r²/2R (the closed forms' and
the half-space solver's), shared between the two faces in the ratio of the bodies'
compliances, k = (1 − ν²)/E: body a (the indenter) is the box X × Y × [0, H] whose
lower face is carried onto z = c_a h by z -> z + c_a h (1 − z/H), body b the box
X × Y × [−H, 0] whose upper face is carried onto z = −c_b h by z -> z − c_b h (1 + z/H),
with c_a = k_a / (k_a + k_b) and c_b = 1 − c_a.  Each face then sinks by its own share of
δ − h inside a Hertz contact, so the deformed interface is the plane z = −c_b δ: the
contact's normal is z, as the half-space theory states its tractions, where a flat plane
under a sphere would meet it on a surface of radius (1 + k_a/k_b) R, tilting the normal
by r/R and with it the friction force's direction by as much as the friction law's
allowance (:mod:`calculix_adapter.traction`).  The maps move a node by at most h and
leave the far faces flat.  Global z points into body a (README, Conventions).

X and Y are [0, L] on a symmetry plane of the model (quarter, half) and [−L, L]
otherwise (:data:`SYMMETRY`); both bodies share the spacings of :func:`graded`: h out to
:data:`FINE` a0 from the centre, then growing by :data:`GROWTH` per element to L; in
depth a first layer :data:`SURFACE` h thick grows to h.

The mesh is a tensor grid built with numpy (no mesher needed) so that the fields are
read back by interpolation on the grid of reference coordinates; it shares no code with
the other solvers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: uniform spacing h out to FINE a0 from the centre (x, y and depth), then spacings
#: growing by GROWTH per element (the far field, where the fields are smooth)
FINE = 1.2
GROWTH = 2.0
#: the first element layer under the contact face, in h, growing by SURFACE_GROWTH to h
SURFACE = 0.5
SURFACE_GROWTH = 1.5
#: which half-axes a model keeps: the symmetry planes x = 0 and y = 0 it cuts at
SYMMETRY = {"quarter": (True, True), "half_y0": (False, True), "half_x0": (True, False),
            "full": (False, False)}
#: the share of the whole contact a model holds
SHARE = {"quarter": 0.25, "half_y0": 0.5, "half_x0": 0.5, "full": 1.0}


def graded(h: float, fine: float, side: float, surface: float | None = None) -> np.ndarray:
    """Coordinates 0 … ``side``: spacing ``h`` up to ``fine`` (whole elements), then
    growing by :data:`GROWTH` per element, the last stretched to end at ``side``; with
    ``surface``, the first spacings are ``surface`` growing by :data:`SURFACE_GROWTH`
    up to h."""
    x = [0.0]
    step = surface if surface is not None else h
    while step < h:
        x.append(x[-1] + step)
        step *= SURFACE_GROWTH
    n = max(1, round((fine - x[-1]) / h))
    x += list(x[-1] + np.arange(1, n + 1) * h)
    step = h
    while x[-1] < side:
        step *= GROWTH
        x.append(x[-1] + step)
    if len(x) > n + 2 and (x[-1] - side) > 0.5 * step:
        x.pop()
    x[-1] = side
    return np.asarray(x)


def axis(h: float, fine: float, side: float, cut: bool) -> np.ndarray:
    """An in-plane axis: :func:`graded` on [0, side] when the model is ``cut`` at 0,
    else mirrored onto [-side, side]."""
    g = graded(h, fine, side)
    return g if cut else np.concatenate([-g[:0:-1], g])


@dataclass(frozen=True)
class Body:
    """One meshed body on the tensor grid xs × ys × zs (its reference coordinates):
    nodes (n, 3) after the profile map, hexahedra (m, 8) in CalculiX's order, and
    node index arrays: ``contact`` (the face at z = 0, (nx, ny)), ``far`` (the face
    opposite), ``x0``/``y0`` (the symmetry planes, empty when not cut)."""

    xs: np.ndarray
    ys: np.ndarray
    zs: np.ndarray
    nodes: np.ndarray
    cells: np.ndarray
    faces: dict[str, np.ndarray]

    @property
    def shape(self) -> tuple[int, int, int]:
        return self.xs.size, self.ys.size, self.zs.size


def box(xs: np.ndarray, ys: np.ndarray, zs: np.ndarray, contact_top: bool) -> Body:
    """The hexahedra of the tensor grid (zs increasing); the contact face is z = 0, the
    top of the box (body b, ``contact_top``) or its bottom (body a)."""
    nx, ny, nz = xs.size, ys.size, zs.size
    X, Y, Z = np.meshgrid(xs, ys, zs, indexing="ij")
    nodes = np.stack([X.ravel(), Y.ravel(), Z.ravel()], axis=1)
    idx = np.arange(nodes.shape[0]).reshape(nx, ny, nz)
    c = idx[:-1, :-1, :-1].ravel()
    dx, dy, dz = ny * nz, nz, 1
    cells = np.stack([c, c + dx, c + dx + dy, c + dy,
                      c + dz, c + dx + dz, c + dx + dy + dz, c + dy + dz], axis=1)
    k0, k1 = (nz - 1, 0) if contact_top else (0, nz - 1)
    faces = {"contact": idx[:, :, k0], "far": idx[:, :, k1].ravel(),
             "x0": idx[0].ravel() if xs[0] == 0.0 else np.zeros(0, int),
             "y0": idx[:, 0].ravel() if ys[0] == 0.0 else np.zeros(0, int)}
    return Body(xs=xs, ys=ys, zs=zs, nodes=nodes, cells=cells, faces=faces)


def bodies(a0: float, R: float, h: float, side: float, height: float, symmetry: str,
           share_a: float) -> tuple[Body, Body]:
    """(body a, body b) of the model (module doc): spacing ``h`` [mm] at the contact,
    half-side ``side`` and height ``height`` [mm], cut at the planes of ``symmetry``,
    body a's face carrying ``share_a`` of the gap profile and body b's the rest."""
    cut_x, cut_y = SYMMETRY[symmetry]
    xs = axis(h, FINE * a0, side, cut_x)
    ys = axis(h, FINE * a0, side, cut_y)
    zs = graded(h, FINE * a0, height, SURFACE * h)
    b = box(xs, ys, -zs[::-1], contact_top=True)
    a = box(xs, ys, zs, contact_top=False)
    x, y, z = a.nodes.T
    a.nodes[:, 2] = z + share_a * profile(x, y, R) * (1.0 - z / height)
    x, y, z = b.nodes.T
    b.nodes[:, 2] = z - (1.0 - share_a) * profile(x, y, R) * (1.0 + z / height)
    return a, b


def profile_share(E_a: float, nu_a: float, E_b: float, nu_b: float) -> float:
    """c_a, body a's share of the gap profile: its compliance (1 − ν²)/E over the pair's
    (module doc)."""
    k_a, k_b = (1.0 - nu_a**2) / E_a, (1.0 - nu_b**2) / E_b
    return k_a / (k_a + k_b)


def profile(x: np.ndarray, y: np.ndarray, R: float) -> np.ndarray:
    """The sphere's gap profile r²/2R [mm] (the closed forms' and the half-space's)."""
    return (x**2 + y**2) / (2.0 * R)


def node_count(a0: float, h: float, side: float, height: float, symmetry: str) -> int:
    """The nodes of the two bodies of :func:`bodies` (no mesh built)."""
    cut_x, cut_y = SYMMETRY[symmetry]
    nx = axis(h, FINE * a0, side, cut_x).size
    ny = axis(h, FINE * a0, side, cut_y).size
    return 2 * nx * ny * graded(h, FINE * a0, height, SURFACE * h).size
