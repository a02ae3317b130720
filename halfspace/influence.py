"""Surface influence coefficients of two elastic half-spaces (Eq. 3-6, 26, 41-42).

Conventions (settled by the physics and by quadrature, see tests/test_halfspace_influence.py):

- All kernels are functions of the offset ``(xo, yo) = field - load`` (erratum 9).
- ``p = (p_x, p_y, p_z)`` is the traction acting on body a (the upper body, global z
  points into it); body b carries ``-p``.  ``p_z = p_n > 0`` is compressive.
- The kernels give the relative displacement ``u = u^(a) - u^(b)`` (Eq. 1-2).  A
  compressive ``p_n`` makes ``u_z > 0`` (both surfaces recede from the interface, which
  adds to the gap of Eq. 1).
- Point kernel (Eq. 5 with erratum 1), ``s = sqrt(xo² + yo²)``::

      A_xx = ((1 - nu)/s + nu xo²/s³) / (pi G)      A_xy = A_yx = nu xo yo / (pi G s³)
      A_yy = ((1 - nu)/s + nu yo²/s³) / (pi G)      A_zz = (1 - nu) / (pi G s)
      A_xz = -K xo / (pi G s²)                      A_zx = +K xo / (pi G s²)
      A_yz = -K yo / (pi G s²)                      A_zy = +K yo / (pi G s²)

  The coupling sign follows from Johnson (1985) §3.2: a compressive normal force on one
  body pulls its surface towards the load (``u_r = -(1-2nu) P / (4 pi G s)``) and, by
  reciprocity, a tangential force Q in +x lifts the surface ahead of it into the body
  (``u_z = +(1-2nu) Q xo / (4 pi G s²)``).  Summing body a (traction +p, z into a) and
  body b (traction -p, z into b is -z) gives the blocks above with Eq. 6's K.  Eq. 5
  writes the same kernel in terms of ``x' - x = load - field = -xo``, consistently.
- Cell coefficients are the point kernel integrated over the loaded cell.  Eq. 41 is
  correct (after erratum 2) for the symmetric blocks; its xz/yz blocks carry the sign of
  offsets ``x_+ = x_I - x'_J + dx/2`` (field - load), not Eq. 42's ``x'_J - x_I + dx/2``.
  Here they are written as corner sums of antiderivatives in asinh/arctan form, which
  are finite (and exact) when the field point lies on an edge or corner of the cell.
"""

from __future__ import annotations

import numpy as np

from halfspace.materials import Materials

BLOCKS = ("xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz")

_RATIO_MAX = 1e300  # clip for b/|a| so that a * asinh(b/|a|) never overflows


def point_kernel(xo: np.ndarray, yo: np.ndarray, mat: Materials) -> dict[str, np.ndarray]:
    """Point-force kernel ``A_ij(field - load)`` of Eq. 5 (erratum 1), in mm/N.

    ``u_i = A_ij p_j`` for a unit force ``p_j`` on body a at the load point.  The kernel
    is singular at ``s = 0``: there the diagonal blocks are ``inf`` and the off-diagonal
    ones are set to 0 (their principal value).
    """
    xo, yo = np.broadcast_arrays(np.asarray(xo, float), np.asarray(yo, float))
    s2 = xo**2 + yo**2
    zero = s2 == 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.sqrt(s2)
        inv_s = np.where(zero, np.inf, 1.0 / s)
        s3 = np.where(zero, 1.0, s2 * s)
        s2_safe = np.where(zero, 1.0, s2)
        xx = np.where(zero, 0.0, xo * xo / s3)
        yy = np.where(zero, 0.0, yo * yo / s3)
        xy = np.where(zero, 0.0, xo * yo / s3)
        cx = np.where(zero, 0.0, xo / s2_safe)
        cy = np.where(zero, 0.0, yo / s2_safe)
    return _assemble(inv_s, xx, yy, xy, cx, cy, mat)


def surface_coefficients(
    xo: np.ndarray, yo: np.ndarray, dx: float, dy: float, mat: Materials
) -> dict[str, np.ndarray]:
    """Cell influence coefficients ``C_ij`` (Eq. 26, 41-42, errata 1-2), in mm/MPa.

    ``(xo, yo) = field - cell centre`` (arrays, broadcast together); the cell is
    ``dx × dy`` and carries a uniform unit traction in direction j on body a.
    ``u_i(field) = sum_J C_ij(x_I - x_J) p_j,J`` is the relative displacement
    ``u^(a) - u^(b)``.  Keys: ``BLOCKS``.  Exact (finite) when the field point lies on
    an edge or a corner of the loaded cell.
    """
    xo, yo = np.broadcast_arrays(np.asarray(xo, float), np.asarray(yo, float))
    t = (xo + 0.5 * dx, xo - 0.5 * dx)  # t = field - load over the cell: [t[1], t[0]]
    u = (yo + 0.5 * dy, yo - 0.5 * dy)

    def corners(f):
        return f(t[0], u[0]) - f(t[0], u[1]) - f(t[1], u[0]) + f(t[1], u[1])

    i_s = corners(lambda a, b: _a_asinh(a, b) + _a_asinh(b, a))  # ∫∫ 1/s
    i_xx = corners(lambda a, b: _a_asinh(b, a))  # ∫∫ t²/s³
    i_yy = corners(lambda a, b: _a_asinh(a, b))  # ∫∫ u²/s³
    i_xy = corners(lambda a, b: -np.hypot(a, b))  # ∫∫ t u/s³
    i_x = corners(_log_atan)  # ∫∫ t/s²
    i_y = corners(lambda a, b: _log_atan(b, a))  # ∫∫ u/s²
    return _assemble(i_s, i_xx, i_yy, i_xy, i_x, i_y, mat)


def normal_coefficients(xo: np.ndarray, yo: np.ndarray, dx: float, dy: float,
                        mat: Materials) -> np.ndarray:
    """The A_zz block of :func:`surface_coefficients` alone (Eq. 41, erratum 2): the
    normal displacement due to a uniform unit pressure on the cell."""
    xo, yo = np.broadcast_arrays(np.asarray(xo, float), np.asarray(yo, float))
    t = (xo + 0.5 * dx, xo - 0.5 * dx)
    u = (yo + 0.5 * dy, yo - 0.5 * dy)

    def f(a, b):
        return _a_asinh(a, b) + _a_asinh(b, a)

    i_s = f(t[0], u[0]) - f(t[0], u[1]) - f(t[1], u[0]) + f(t[1], u[1])  # ∫∫ 1/s
    return (1.0 - mat.nu) / (np.pi * mat.G) * i_s


def _assemble(i_s, i_xx, i_yy, i_xy, i_x, i_y, mat: Materials) -> dict[str, np.ndarray]:
    """Combine the integrals of 1/s, t²/s³, u²/s³, tu/s³, t/s², u/s² into the blocks."""
    c = 1.0 / (np.pi * mat.G)
    nu = mat.nu
    xy = c * nu * i_xy
    xz = -c * mat.K * i_x
    yz = -c * mat.K * i_y
    return {
        "xx": c * ((1.0 - nu) * i_s + nu * i_xx),
        "xy": xy,
        "xz": xz,
        "yx": xy.copy(),
        "yy": c * ((1.0 - nu) * i_s + nu * i_yy),
        "yz": yz,
        "zx": -xz,
        "zy": -yz,
        "zz": c * (1.0 - nu) * i_s,
    }


def _a_asinh(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a asinh(b/|a|)``, continuous with limit 0 at ``a = 0``.

    Equals ``a ln(b + s)`` up to ``a ln|a|``, which cancels in a corner sum over b
    (``s = sqrt(a² + b²)``).  Its ∂²/∂a∂b is ``b²/s³``; that of
    ``a asinh(b/|a|) + b asinh(a/|b|)`` is ``1/s``.
    """
    abs_a = np.abs(a)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ratio = np.clip(b / abs_a, -_RATIO_MAX, _RATIO_MAX)
        return np.where(abs_a > 0.0, a * np.arcsinh(ratio), 0.0)


def _log_atan(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``b ln(sqrt(a² + b²)) + a atan(b/a)``: its ∂²/∂a∂b is ``a/(a² + b²)``.

    (Up to a term linear in b, which cancels in a corner sum.)  Both terms tend to 0
    where their prefactor vanishes.
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        log_term = np.where(b != 0.0, b * np.log(np.hypot(a, b)), 0.0)
        atan_term = np.where(a != 0.0, a * np.arctan(b / a), 0.0)
    return log_term + atan_term
