"""Subsurface stress kernels: point loads (Appendix A) and uniform cell tractions (Appendix C).

Conventions (erratum 9, settled by the tests in tests/test_halfspace_stress_kernels.py):

- One elastic half-space occupies ``z > 0``; z is the depth into it, x and y are
  surface axes; ``(x, y)`` is always the field point relative to the load point
  (``field - load``).  Tensile stress is positive.  ``nu`` is the Poisson ratio of the
  body whose stresses are computed (``nu^(alpha)``, never the composite nu of Eq. 6).
- Loads: ``"n"`` a unit normal force pushing into the body (compressive, +z);
  ``"x"`` / ``"y"`` a unit tangential force along +x / +y acting on the body's surface.
- The surface z = 0 has outward normal -z, so an applied traction ``t`` equals
  ``-sigma_iz`` there: under a uniform unit load, ``sigma_zz(z -> 0+) = -1`` inside the
  loaded area for ``"n"``, and ``sigma_xz(z -> 0+) = -1`` for ``"x"``; across any plane
  ``z = c`` the stresses carry ``∫∫ sigma_iz dA = -F_i``.
- Trailing side of a tangential force is tensile:
  ``sigma_xx(x < 0, 0, 0+) = +(1 + nu) Q / (pi x²)`` for Q along +x.

Corrections to the extracted text (verified symbolically against stresses derived from
Johnson's Boussinesq and Cerruti displacement fields, and by quadrature):

- Eq. 39, ``T_xy^N``: the term ``(1 - z/rho) xy / r²`` needs a factor 2.
- Eq. 44 (erratum 6) and Eq. 48 (erratum 7) as listed; every ``nu`` of Appendix C is
  the body's ``nu^(alpha)``.  With those, the antiderivatives of Eq. 44 and 46 satisfy
  ``∂²T̄/∂x∂y = 2 pi T`` with T the (corrected) Appendix A kernel of field - load, so the
  corner offsets of Eq. 43, 45, 47 are ``x_± = x_I - x'_J ± dx/2`` (field - load),
  not Eq. 42's ``x'_J - x_I ± dx/2``.
- The logarithms ``ln(rho + y)`` and ``ln(rho + x)`` are replaced by
  ``asinh(y / sqrt(x² + z²))`` and ``asinh(x / sqrt(y² + z²))`` (they differ by a
  function of one in-plane coordinate, which cancels in the corner sum), and every
  ``rho + y`` with ``y < 0`` is evaluated as ``(x² + z²)/(rho - y)``: no cancellation.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from cases.result import STRESS_COMPONENTS, von_mises

__all__ = ["LOADS", "STRESS_COMPONENTS", "cell_stress_coefficients", "coefficient_table",
           "folded_range", "parity", "point_stresses", "symmetric_table", "unfold",
           "von_mises"]

LOADS = ("x", "y", "n")
_SWAP = {"sxx": "syy", "syy": "sxx", "szz": "szz", "sxy": "sxy", "sxz": "syz", "syz": "sxz"}


def _swap_xy(comps: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Relabel a stress tensor under the exchange of the x and y axes."""
    return {c: comps[_SWAP[c]] for c in STRESS_COMPONENTS}


# ---------------------------------------------------------------- Appendix A


def point_stresses(x, y, z, nu: float, load: str) -> dict[str, np.ndarray]:
    """Stresses at (x, y, z) = field - load, z >= 0, due to a unit surface force (Eq. 39-40).

    ``load`` is ``"n"`` (normal, into the body), ``"x"`` or ``"y"`` (tangential); see the
    module docstring for signs.  Valid for ``rho = |(x, y, z)| > 0``; at z = 0 it gives
    the surface limit z -> 0+ away from the load point.  The Boussinesq terms are
    written without ``1/r²`` (finite on the load axis); Eq. 39's ``T_xy^N`` carries the
    missing factor 2.
    """
    x, y, z = np.broadcast_arrays(*(np.asarray(v, float) for v in (x, y, z)))
    if load == "y":
        return _swap_xy(point_stresses(y, x, z, nu, "x"))
    if load not in ("x", "n"):
        raise ValueError(f"load must be one of {LOADS}, not {load!r}")
    a = 1.0 / (2.0 * np.pi)
    m = 1.0 - 2.0 * nu
    rho = np.sqrt(x * x + y * y + z * z)
    rz = rho + z
    r3, r5 = rho**3, rho**5
    if load == "n":
        return {
            "sxx": a * (m * (x * x - y * y + z * z + z * y * y / rz) / (r3 * rz)
                        - 3.0 * z * x * x / r5),
            "syy": a * (m * (y * y - x * x + z * z + z * x * x / rz) / (r3 * rz)
                        - 3.0 * z * y * y / r5),
            "szz": -3.0 * a * z**3 / r5,
            "sxy": a * (m * x * y * (2.0 * rho + z) / (r3 * rz**2) - 3.0 * x * y * z / r5),
            "sxz": -3.0 * a * x * z * z / r5,
            "syz": -3.0 * a * y * z * z / r5,
        }
    rz2, rz3 = rz**2, rz**3
    return {
        "sxx": a * (-3.0 * x**3 / r5 + m * (x / r3 - 3.0 * x / (rho * rz2)
                                            + x**3 / (r3 * rz2) + 2.0 * x**3 / (rho**2 * rz3))),
        "syy": a * (-3.0 * x * y * y / r5
                    + m * (x / r3 - x / (rho * rz2) + x * y * y / (r3 * rz2)
                           + 2.0 * x * y * y / (rho**2 * rz3))),
        "szz": -3.0 * a * x * z * z / r5,
        "sxy": a * (-3.0 * x * x * y / r5
                    + m * (-y / (rho * rz2) + x * x * y / (r3 * rz2)
                           + 2.0 * x * x * y / (rho**2 * rz3))),
        "sxz": -3.0 * a * x * x * z / r5,
        "syz": -3.0 * a * x * y * z / r5,
    }


# ---------------------------------------------------------------- Appendix C


def cell_stress_coefficients(
    xo, yo, z, dx: float, dy: float, nu: float
) -> dict[str, dict[str, np.ndarray]]:
    """Stresses due to a unit uniform traction on a ``dx × dy`` cell (Eq. 33, 43-48).

    ``(xo, yo) = field - cell centre`` and depth ``z >= 0`` broadcast together.
    Returns ``{"x": {...}, "y": {...}, "n": {...}}`` with the six components
    ``STRESS_COMPONENTS`` each: the B^Sx, B^Sy, B^N of Eq. 32-33.  Each is the corner
    sum ``(1/2pi) [T̄(x+, y+) + T̄(x-, y-) - T̄(x-, y+) - T̄(x+, y-)]`` with
    ``x± = xo ± dx/2``, ``y± = yo ± dy/2``.

    ``z = 0`` gives the surface limit z -> 0+, which is unique off the cell's edge
    lines (e.g. at cell centres, the case used by the solver): there ``sigma_zz = -1``
    and ``sigma_xz = sigma_yz = 0`` inside the cell for ``"n"``, ``sigma_xz = -1`` for
    ``"x"``.  A z = 0 field point on an edge line ``xo = ±dx/2`` or ``yo = ±dy/2``
    (where some surface stresses are log-singular or jump) raises ``ValueError``.
    """
    xo, yo, z = np.broadcast_arrays(*(np.asarray(v, float) for v in (xo, yo, z)))
    if np.any(z < 0) or not np.all(np.isfinite(z)):
        raise ValueError("depth z must be finite and >= 0")
    xs = (xo + 0.5 * dx, xo - 0.5 * dx)
    ys = (yo + 0.5 * dy, yo - 0.5 * dy)
    surface = z == 0.0
    on_edge = (xs[0] == 0) | (xs[1] == 0) | (ys[0] == 0) | (ys[1] == 0)
    if np.any(surface & on_edge):
        raise ValueError(
            "surface stresses (z = 0) are not defined on the edge lines of a loaded cell"
        )

    def corner_sum(antiderivative):
        terms = [antiderivative(xs[i], ys[j], z, nu) for i in (0, 1) for j in (0, 1)]
        return {c: (terms[0][c] - terms[1][c] - terms[2][c] + terms[3][c]) / (2.0 * np.pi)
                for c in STRESS_COMPONENTS}

    return {
        "x": corner_sum(_antiderivative_x),
        "y": _swap_xy(corner_sum(_antiderivative_y_swapped)),
        "n": corner_sum(_antiderivative_n),
    }


def _rho_plus(rho: np.ndarray, a: np.ndarray, q2: np.ndarray) -> np.ndarray:
    """``rho + a`` without cancellation, ``q2 = rho² - a²`` (the other two squares)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(a >= 0.0, rho + a, q2 / (rho - a))


def _safe_div(num: np.ndarray, den: np.ndarray) -> np.ndarray:
    """``num / den``, 0 where ``den == 0`` (only at excluded points where num -> 0 too)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den != 0.0, num / np.where(den != 0.0, den, 1.0), 0.0)


def _asinh_ratio(a: np.ndarray, q: np.ndarray) -> np.ndarray:
    """``asinh(a / q)``: ``ln(rho + a)`` up to ``ln q`` (q > 0 wherever it is used)."""
    return np.arcsinh(_safe_div(a, q))


def _antiderivative_n(x, y, z, nu) -> dict[str, np.ndarray]:
    """T̄^N of Eq. 44 (erratum 6): ∂²T̄/∂x∂y = 2 pi T^N (normal load)."""
    rho = np.sqrt(x * x + y * y + z * z)
    rp_y = _rho_plus(rho, y, x * x + z * z)
    rp_x = _rho_plus(rho, x, y * y + z * z)
    at = np.arctan2(x * y, rho * z)  # atan(xy / (rho z)), = pi/2 sign(xy) at z = 0
    xz_y = _safe_div(x * z, rho * rp_y)
    yz_x = _safe_div(y * z, rho * rp_x)
    return {
        "sxx": -2.0 * nu * at + 2.0 * (1.0 - 2.0 * nu) * np.arctan2(x, rp_y + z) - xz_y,
        "syy": -2.0 * nu * at + 2.0 * (1.0 - 2.0 * nu) * np.arctan2(y, rp_x + z) - yz_x,
        "szz": -at + xz_y + yz_x,
        "sxy": (2.0 * nu - 1.0) * np.log(rho + z) - _safe_div(z, rho),
        "sxz": -_safe_div(z * z, rho * rp_y),
        "syz": -_safe_div(z * z, rho * rp_x),
    }


def _antiderivative_x(x, y, z, nu) -> dict[str, np.ndarray]:
    """T̄^Sx of Eq. 46: ∂²T̄/∂x∂y = 2 pi T^Sx (tangential load along +x)."""
    rho = np.sqrt(x * x + y * y + z * z)
    rp_y = _rho_plus(rho, y, x * x + z * z)
    ln_y = _asinh_ratio(y, np.sqrt(x * x + z * z))  # ln(rho + y)
    ln_x = _asinh_ratio(x, np.sqrt(y * y + z * z))  # ln(rho + x)
    m = 1.0 - 2.0 * nu
    y_rz = _safe_div(y, rho * (rho + z))
    return {
        "sxx": 2.0 * ln_y + z * m * (y_rz + _safe_div(z, rho * rp_y))
        - 2.0 * nu * _safe_div(x * x, rho * rp_y),
        "syy": 2.0 * nu * ln_y - z * m * y_rz - 2.0 * nu * _safe_div(y, rho),
        "szz": -_safe_div(z * z, rho * rp_y),
        "sxy": ln_x - z * m * _safe_div(x, rho * (rho + z)) - 2.0 * nu * _safe_div(x, rho),
        "sxz": -_safe_div(x * z, rho * rp_y) - np.arctan2(x * y, rho * z),
        "syz": -_safe_div(z, rho),
    }


def _antiderivative_y_swapped(x, y, z, nu) -> dict[str, np.ndarray]:
    """T̄^Sy (Eq. 48, erratum 7) in swapped axes: T̄^Sx(y, x, z), relabelled by the caller."""
    return _antiderivative_x(y, x, z, nu)


def coefficient_table(kx: tuple[int, int], ky: tuple[int, int], z: float, dx: float,
                      dy: float, nu: float, loads: Sequence[str] = LOADS
                      ) -> dict[str, dict[str, np.ndarray]]:
    """:func:`cell_stress_coefficients` for every integer offset (i dx, j dy), i in
    [kx[0], kx[1]], j in [ky[0], ky[1]], as arrays indexed [i - kx[0], j - ky[0]];
    only the loads in ``loads`` (default all three).

    Neighbouring cells share corners, so the antiderivatives of Eq. 44-48 are evaluated
    once on the corner lattice ((i ± 1/2) dx, (j ± 1/2) dy) and differenced: a quarter of
    the work of the corner sums cell by cell.  Corners never lie on x = 0 or y = 0, so
    z = 0 (surface values at cell centres) is regular here.
    """
    if z < 0 or not np.isfinite(z):
        raise ValueError("depth z must be finite and >= 0")
    if not set(loads) <= set(LOADS):
        raise ValueError(f"loads must be among {LOADS}, not {tuple(loads)!r}")
    xc = (np.arange(kx[0], kx[1] + 2) - 0.5)[:, None] * dx
    yc = (np.arange(ky[0], ky[1] + 2) - 0.5)[None, :] * dy
    zz = np.full(np.broadcast_shapes(xc.shape, yc.shape), float(z))

    def differenced(antiderivative, x, y):
        T = antiderivative(x, y, zz, nu)
        return {c: (T[c][1:, 1:] - T[c][1:, :-1] - T[c][:-1, 1:] + T[c][:-1, :-1])
                / (2.0 * np.pi) for c in STRESS_COMPONENTS}

    build = {
        "x": lambda: differenced(_antiderivative_x, xc, yc),
        "y": lambda: _swap_xy(differenced(_antiderivative_y_swapped, xc, yc)),
        "n": lambda: differenced(_antiderivative_n, xc, yc),
    }
    return {ld: build[ld]() for ld in LOADS if ld in loads}


# ---------------------------------------------------------------- parity


def parity(load: str, comp: str) -> tuple[float, float]:
    """Signs of B^load_comp (Eq. 33) under xo -> -xo and under yo -> -yo.

    Reflecting x maps the load ``"x"`` to its opposite and flips every component with
    one x index (sxy, sxz); likewise for y.  So B is even or odd in each offset, with
    sign (-1)^(number of x indices of comp + [load == "x"]) for x, and the same for y.
    """
    if load not in LOADS or comp not in STRESS_COMPONENTS:
        raise ValueError(f"unknown load {load!r} or component {comp!r}")
    return ((-1.0) ** (comp[1:].count("x") + (load == "x")),
            (-1.0) ** (comp[1:].count("y") + (load == "y")))


def folded_range(lo: int, hi: int) -> tuple[int, int]:
    """The range of |k| for the integers k in [lo, hi]."""
    if lo <= 0 <= hi:
        return 0, max(-lo, hi)
    return min(abs(lo), abs(hi)), max(abs(lo), abs(hi))


def _mirror_pieces(lo: int, hi: int) -> list[tuple[slice, slice, bool]]:
    """(destination over k - lo, source over |k| - folded lo, mirrored?) for k in [lo, hi]:
    the pieces that copy a table over :func:`folded_range` to one over [lo, hi]."""
    n = hi - lo + 1
    if lo >= 0:
        return [(slice(0, n), slice(0, n), False)]
    if hi < 0:  # all negative: |k| runs down the folded range [-hi, -lo]
        return [(slice(0, n), slice(None, None, -1), True)]
    return [(slice(0, -lo), slice(-lo, 0, -1), True),  # k = lo .. -1, |k| = -lo .. 1
            (slice(-lo, n), slice(0, hi + 1), False)]


def unfold(q: np.ndarray, kx: tuple[int, int], ky: tuple[int, int],
           signs: tuple[float, float], out: np.ndarray | None = None) -> np.ndarray:
    """A coefficient over the offsets [kx[0], kx[1]] x [ky[0], ky[1]] from its table ``q``
    over |offsets| (:func:`folded_range` of each), with f(-i, j) = signs[0] f(i, j) and
    f(i, -j) = signs[1] f(i, j) (:func:`parity`); written into ``out`` if given."""
    if out is None:
        out = np.empty((kx[1] - kx[0] + 1, ky[1] - ky[0] + 1))
    for dst_x, src_x, neg_x in _mirror_pieces(*kx):
        for dst_y, src_y, neg_y in _mirror_pieces(*ky):
            sign = (signs[0] if neg_x else 1.0) * (signs[1] if neg_y else 1.0)
            np.multiply(q[src_x, src_y], sign, out=out[dst_x, dst_y])
    return out


def symmetric_table(kx: tuple[int, int], ky: tuple[int, int], z: float, dx: float,
                    dy: float, nu: float, loads: Sequence[str] = LOADS
                    ) -> dict[str, dict[str, np.ndarray]]:
    """:func:`coefficient_table` over the same offsets, evaluated on one quadrant.

    Each coefficient of Eq. 33 is even or odd in each offset (:func:`parity`), so the
    antiderivatives of Eq. 44-48 are evaluated for |i|, |j| only and mirrored
    (:func:`unfold`): up to a quarter of the transcendental work when the ranges
    straddle zero.  Equal to :func:`coefficient_table` up to round-off.
    """
    quad = coefficient_table(folded_range(*kx), folded_range(*ky), z, dx, dy, nu, loads)
    return {ld: {c: unfold(q, kx, ky, parity(ld, c)) for c, q in comps.items()}
            for ld, comps in quad.items()}
