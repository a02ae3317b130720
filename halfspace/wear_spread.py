"""A committed wear increment spread over a length: the resolution probe's half-space run
(``solver.wear_spread``; ``reports/README.md``, "The resolution probe").

The half-space solver holds the step a worn profile takes at a stick edge sharp, at a
cell face: its pressure is piecewise constant and its influence coefficients exact.  A
solver whose surface is a polynomial within an element of width h resolves the same step
only across about an element.  Spreading each committed increment Δw by a separable tent
of half-width r,

    Δw ← T_r ∗ Δw,   T_r(s) = max(0, 1 − |s|/r) / r,

models that smoothing (docs/fem-notes.md, part 5, "Why").  Δw is piecewise constant on
the cells, so the tent is applied to that field and the result averaged over each cell:
the weight of the cell k cells away is ∫ Λ_dx(t) T_r(k dx + t) dt, Λ_dx the triangle of
half-width dx and unit integral (the difference of two uniform points of a cell).  The
weights sum to one (the worn volume is kept), and r → 0 gives the identity on any grid,
so a spread below a cell still acts.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.ndimage import convolve1d

#: quadrature points per cell of the weights' integral (Gauss–Legendre on each piece)
_GAUSS = np.polynomial.legendre.leggauss(8)


def _tent(s: np.ndarray, r: float) -> np.ndarray:
    return np.maximum(0.0, 1.0 - np.abs(s) / r) / r


def weights(r: float, dx: float) -> np.ndarray:
    """The cell weights of a tent of half-width ``r`` on cells of side ``dx`` (module doc),
    offsets −m … m with m = ⌈r/dx⌉; ``[1.0]`` for ``r = 0``.  Computed once per (r, dx):
    a run spreads every committed increment with the same weights."""
    return np.array(_weights(float(r), float(dx)))


@lru_cache(maxsize=16)
def _weights(r: float, dx: float) -> tuple[float, ...]:
    if r < 0 or dx <= 0:
        raise ValueError(f"wear spread r = {r!r} on cells dx = {dx!r}: need r ≥ 0, dx > 0")
    if r == 0.0:
        return (1.0,)
    m = int(np.ceil(r / dx))
    # the integrand is smooth between the kinks of Λ (t = −dx, 0, dx) and of T_r
    # (k dx + t = −r, 0, r); integrate piece by piece between every kink
    t_gauss, w_gauss = _GAUSS
    out = np.empty(2 * m + 1)
    for j, k in enumerate(range(-m, m + 1)):
        knots = np.array([-dx, 0.0, dx, -r - k * dx, -k * dx, r - k * dx])
        knots = np.unique(np.clip(knots, -dx, dx))
        a, b = knots[:-1, None], knots[1:, None]
        t = 0.5 * (b - a) * t_gauss + 0.5 * (b + a)
        f = (1.0 - np.abs(t) / dx) / dx * _tent(k * dx + t, r)
        out[j] = float(np.sum(0.5 * (b - a) * (f @ np.diag(w_gauss))))
    return tuple(out / out.sum())


def spread(dw: np.ndarray, r: float, dx: float, dy: float) -> np.ndarray:
    """``dw`` (cells, axis 0 along x) spread by the separable tent of half-width ``r`` [mm]
    (module doc); beyond the grid the increment is taken as zero."""
    if r == 0.0:
        return dw
    out = convolve1d(dw, weights(r, dx), axis=0, mode="constant")
    return convolve1d(out, weights(r, dy), axis=1, mode="constant")
