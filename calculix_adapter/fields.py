"""The CalculiX solution on the case's grid and planes, mirrored from the model.

- Surface: the tractions at the nodes of body b's face (p_n, p_x, p_y on body a, from
  the nodal forces: :mod:`calculix_adapter.traction`) are bilinear on the face's
  tensor grid, read at the cell centres of the case grid; 0 outside the face.  A node
  slips where its shear reaches the friction bound within :data:`SLIP_TOL` (the return
  map puts a slipping integration point's shear on μ p_n; a node combines several).
- Stresses: CalculiX's nodal stresses of the reported body (its element values
  extrapolated to the nodes and averaged) are trilinear on the body's tensor grid of
  reference coordinates, in which the depth into the body is the reference z (the
  profile maps move a face by its share of r²/2R, under 2e-3 a0 within the bundled
  grids, and the depth below it not at all to first order).
- Mirror images (a quarter or half model): x -> -x changes the sign of p_x, σ_xy and
  σ_xz; y -> -y that of p_y, σ_xy and σ_yz.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import RegularGridInterpolator

from cases.result import Plane, von_mises

from .mesh import Body

#: a node slips where |p_t| >= (1 - SLIP_TOL) μ p_n
SLIP_TOL = 2e-3
COMPONENTS = ("sxx", "syy", "szz", "sxy", "sxz", "syz")
#: CalculiX's stress components in the .frd file, in :data:`COMPONENTS`' order
FRD_STRESS = ("SXX", "SYY", "SZZ", "SXY", "SZX", "SYZ")
#: the sign of each field when x (first) or y (second) is mirrored
MIRROR = {"p_n": (1, 1), "p_x": (-1, 1), "p_y": (1, -1), "sxx": (1, 1), "syy": (1, 1),
          "szz": (1, 1), "sxy": (-1, -1), "sxz": (-1, 1), "syz": (1, -1)}


def _mirror(body: Body, x: np.ndarray, y: np.ndarray, field: str
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(x, y) taken into the model (|x| where it is cut at x = 0, |y| likewise) and the
    sign of ``field`` there."""
    sx, sy = MIRROR[field]
    sign = np.ones(np.broadcast(x, y).shape)
    if body.xs[0] == 0.0:
        sign = np.where(x < 0, sx * sign, sign)
        x = np.abs(x)
    if body.ys[0] == 0.0:
        sign = np.where(y < 0, sy * sign, sign)
        y = np.abs(y)
    return x, y, sign


def on_face(body: Body, nodal: np.ndarray, field: str, x: np.ndarray, y: np.ndarray
            ) -> np.ndarray:
    """A field at the face's nodes (nx, ny) at the points (x[i], y[j]), (len x, len y)."""
    X, Y = np.meshgrid(x, y, indexing="ij")
    X, Y, sign = _mirror(body, X, Y, field)
    f = RegularGridInterpolator((body.xs, body.ys), nodal, bounds_error=False,
                                fill_value=0.0)
    return sign * f(np.stack([X.ravel(), Y.ravel()], axis=1)).reshape(X.shape)


def slipping(p_n: np.ndarray, p_x: np.ndarray, p_y: np.ndarray, mu: float) -> np.ndarray:
    """Where a node of the face's grid (nx, ny) in contact slips: its shear reaches the
    friction bound, within :data:`SLIP_TOL`, times the coherence of the shear's direction
    around it.  A node's traction is a positive combination of its support's (the nodal
    force, :mod:`calculix_adapter.traction`): where every point of the support slips but
    the direction turns across it (the radial shear of a compression, by the support's
    angle seen from the centre), the combination's length falls short of μ p_n by the
    mean resultant of the directions, about 1 − α²/6 for directions spread over ±α.
    That mean is taken over the node and its neighbours in contact (the support's
    extremes, so it errs towards slip by at most the same second-order amount; stick
    nodes next to a slip zone sit well below: a √ kink)."""
    t = np.hypot(p_x, p_y)
    contact = p_n > 0
    unit = np.stack([p_x, p_y], axis=-1) / np.where(t > 0, t, 1.0)[..., None]
    d = np.where((contact & (t > 0))[..., None], unit, 0.0)
    total = d.copy()
    count = contact.astype(float)
    for axis in (0, 1):
        for shift in (1, -1):
            nb = np.roll(d, shift, axis=axis)
            ok = np.roll(contact, shift, axis=axis)
            edge = [slice(None)] * 2
            edge[axis] = 0 if shift == 1 else -1  # no wrap-around
            nb[tuple(edge)] = 0.0
            ok = ok.copy()
            ok[tuple(edge)] = False
            total += nb
            count += ok
    coherence = np.linalg.norm(total, axis=-1) / np.maximum(count, 1.0)
    return contact & (t >= (1.0 - SLIP_TOL) * coherence * mu * p_n)


def tributary(body: Body) -> np.ndarray:
    """The area [mm²] each node of the face stands for (nx, ny): half its two
    neighbouring spacings in x times the same in y."""
    def half(s: np.ndarray) -> np.ndarray:
        d = np.diff(s)
        return 0.5 * (np.concatenate([[0.0], d]) + np.concatenate([d, [0.0]]))

    return np.outer(half(body.xs), half(body.ys))


def planes(body: Body, stress: np.ndarray, *, x: np.ndarray, y: np.ndarray,
           z: np.ndarray, x0: float, y0: float, sign_z: float) -> dict[str, Plane]:
    """The xz plane (at y = ``y0``, along ``x``) and the yz plane (at x = ``x0``, along
    ``y``) at the depths ``z`` into the body (reference z = ``sign_z`` · depth), from its
    nodal stresses (n, 6) in :data:`COMPONENTS` order, with σ_VM."""
    grid = (body.xs, body.ys, body.zs)
    values = stress.reshape(body.shape + (6,))
    out = {}
    for name, s in (("xz", x), ("yz", y)):
        S, Z = np.meshgrid(s, z, indexing="ij")
        px = S if name == "xz" else np.full_like(S, x0)
        py = np.full_like(S, y0) if name == "xz" else S
        fields = {}
        for c, comp in enumerate(COMPONENTS):
            qx, qy, sign = _mirror(body, px, py, comp)
            f = RegularGridInterpolator(grid, values[..., c], bounds_error=False,
                                        fill_value=None)
            pts = np.stack([qx.ravel(), qy.ravel(), sign_z * Z.ravel()], axis=1)
            fields[comp] = sign * f(pts).reshape(S.shape)
        fields["vm"] = von_mises(*(fields[c] for c in COMPONENTS))
        out[name] = Plane(s=np.asarray(s, float).copy(), z=np.asarray(z, float).copy(),
                          fields=fields)
    return out
