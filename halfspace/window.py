"""The normal problem (Eq. 7/15) solved on its potential-contact window.

The kernel A_zz is positive (Eq. 5: ``(1 - nu) / (pi G s)``, integrated over a cell), so
for ``p_n >= 0`` the normal displacement ``A_zz p_n`` is ``>= 0`` everywhere and the gap
``g_n = h + A_zz p_n - delta`` (Eq. 29) of a cell with ``h >= delta`` is never negative.
Such a cell carries no pressure in the solution.  The contact therefore lies inside the
rigid overlap ``{h < delta}``, and the problem restricted to any window holding that
set, with ``p_n = 0`` outside, *is* the problem on the whole grid: its solution, with
zeros outside, satisfies Eq. 15 on every cell.  The implicit wear term ``k_w p_n`` of
step (IV) keeps this true (it vanishes where ``p_n`` does).

- Displacement control: delta is given, the window is the box around ``{h < delta}``;
  one solve.
- Load control: delta is not known before the solve.  It is estimated (from the
  previous step's pressure, or from the same problem on a grid twice as coarse, solved
  the same way: nested continuation), the window is cut around ``{h < delta_guess}``,
  and after the solve the overlap box of the *found* delta is checked to lie inside the
  window; if not, the window grows to it and the solve continues from the pressure it
  has.  The check makes the result independent of the estimate.

The convolutions then run on the window's zero-padded grid (Eq. 27 depends on offsets
only), not on the whole grid's: the cost of an iteration follows the contact, not the
grid (a Hertz contact covers ~3 % of the bundled 1.6 mm grid).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .influence import surface_coefficients
from .materials import Materials
from .normal import NormalSolution, polonsky_keer, roundoff_floor, uzawa_normal
from .operator import ConvolutionOperator, normal_operator

ROUND = 8  # window sizes are rounded up to a multiple of this (fewer distinct operators)
COARSEST = 96  # grids with fewer cells per axis are solved without a coarser level
SLACK = 0.1  # relative margin on the estimated overlap depth delta - min(h)

Box = tuple[slice, slice]


def overlap_box(h: np.ndarray, delta: float) -> Box | None:
    """Bounding box of the rigid overlap ``{h < delta}`` grown by one cell, or None."""
    inside = h < delta
    rows, cols = np.flatnonzero(inside.any(axis=1)), np.flatnonzero(inside.any(axis=0))
    if rows.size == 0:
        return None
    n = h.shape
    return (slice(max(rows[0] - 1, 0), min(rows[-1] + 2, n[0])),
            slice(max(cols[0] - 1, 0), min(cols[-1] + 2, n[1])))


def rounded(box: Box, n: tuple[int, int]) -> Box:
    """``box`` grown to a multiple of ROUND cells per axis (centred, kept on the grid)."""
    out = []
    for s, ni in zip(box, n, strict=True):
        size = min(-(-(s.stop - s.start) // ROUND) * ROUND, ni)
        start = min(max(s.start - (size - (s.stop - s.start)) // 2, 0), ni - size)
        out.append(slice(start, start + size))
    return out[0], out[1]


def contains(outer: Box, inner: Box) -> bool:
    return all(o.start <= i.start and i.stop <= o.stop for o, i in zip(outer, inner, strict=True))


def union(a: Box, b: Box) -> Box:
    return (slice(min(a[0].start, b[0].start), max(a[0].stop, b[0].stop)),
            slice(min(a[1].start, b[1].start), max(a[1].stop, b[1].stop)))


def coarsen(f: np.ndarray) -> np.ndarray:
    """Means over 2 x 2 blocks of cells (a trailing odd row/column is dropped)."""
    m0, m1 = f.shape[0] // 2, f.shape[1] // 2
    return f[: 2 * m0, : 2 * m1].reshape(m0, 2, m1, 2).mean(axis=(1, 3))


def prolong(f: np.ndarray, n: tuple[int, int]) -> np.ndarray:
    """Each coarse cell's value on its 2 x 2 fine cells (edge-padded to ``n``)."""
    fine = np.kron(f, np.ones((2, 2)))
    return np.pad(fine, [(0, n[0] - fine.shape[0]), (0, n[1] - fine.shape[1])], mode="edge")


@dataclass
class WindowedNormal:
    """Normal solves on one grid (``n`` cells of ``dx x dy``) restricted to the window.

    ``c`` is 1/A_zz,self (Eq. 15's natural-map scale).  ``full_op`` (optional) is an
    operator of the whole grid with a "zz" kernel, reused instead of building one.
    """

    n: tuple[int, int]
    dx: float
    dy: float
    mat: Materials
    method: str
    tol: float
    max_iter: int
    full_op: ConvolutionOperator | None = None

    def __post_init__(self) -> None:
        self._ops: dict[tuple[int, int], ConvolutionOperator] = {}
        self._coarse: WindowedNormal | None = None
        self._L: float | None = None
        centre = surface_coefficients(np.zeros(1), np.zeros(1), self.dx, self.dy, self.mat)
        self.c = 1.0 / float(centre["zz"][0])

    @property
    def L(self) -> float:
        """Upper bound of A_zz's spectrum on the whole grid (the Uzawa step; a window's
        block is a principal sub-matrix, so the bound holds for it too)."""
        if self._L is None:
            self._L = float(np.abs(self.operator(self.n).spectra["zz"]).max())
        return self._L

    def operator(self, shape: tuple[int, int]) -> ConvolutionOperator:
        """A_zz on a ``shape``-cell window (cached; the kernels depend on offsets only)."""
        if shape == self.n and self.full_op is not None:
            return self.full_op
        if shape not in self._ops:
            if len(self._ops) > 32:
                self._ops.clear()
            self._ops[shape] = normal_operator(*shape, self.dx, self.dy, self.mat)
        return self._ops[shape]

    def solve(self, h: np.ndarray, *, P: float | None = None, approach: float | None = None,
              p0: np.ndarray | None = None,
              wear_rate: np.ndarray | None = None) -> NormalSolution:
        """The solution of Eq. 7/15 on the whole grid, computed on the window."""
        floor = roundoff_floor(self.c, h, approach)
        if approach is not None:
            box = overlap_box(h, approach)
            if box is None:  # no overlap: nothing touches
                return self._on(h, self.full, P, approach, None, wear_rate, floor)
            return self._on(h, rounded(box, self.n), P, approach, p0, wear_rate, floor)
        delta, p0 = self._estimate(h, P, p0, wear_rate)
        guess = overlap_box(h, delta + SLACK * (delta - float(h.min())))
        box = self.full if guess is None else rounded(guess, self.n)
        while True:
            sol = self._on(h, box, P, None, p0, wear_rate, floor)
            need = overlap_box(h, sol.approach)
            if need is None or contains(box, need):
                return sol
            box, p0 = rounded(union(box, need), self.n), sol.p_n

    @property
    def full(self) -> Box:
        return slice(0, self.n[0]), slice(0, self.n[1])

    def _estimate(self, h, P, p0, wear_rate) -> tuple[float, np.ndarray | None]:
        """(estimated approach, starting pressure) for load control: from the previous
        pressure ``p0`` when given, else from the problem on a grid twice as coarse."""
        if p0 is not None and np.any(p0 > 0):
            p = p0 * (P / (p0.sum() * self.dx * self.dy))
            g = self._apply_full(p, wear_rate) + h
            return float(g[p > 0].mean()), p0
        if min(self.n) < COARSEST:
            return float("inf"), None  # the whole grid
        if self._coarse is None:
            self._coarse = WindowedNormal((self.n[0] // 2, self.n[1] // 2), 2 * self.dx,
                                          2 * self.dy, self.mat, self.method, self.tol,
                                          self.max_iter)
        k_w = None if wear_rate is None else coarsen(wear_rate)
        coarse = self._coarse.solve(coarsen(h), P=P, wear_rate=k_w)
        return coarse.approach, prolong(coarse.p_n, self.n)

    def _apply_full(self, p: np.ndarray, wear_rate) -> np.ndarray:
        u = self.operator(self.n).apply("zz", p)
        return u if wear_rate is None else u + wear_rate * p

    def _on(self, h, box: Box, P, approach, p0, wear_rate, floor) -> NormalSolution:
        """Solve on ``box`` (p_n = 0 outside) and return the whole-grid solution."""
        op = self.operator((box[0].stop - box[0].start, box[1].stop - box[1].start))
        k_w = None if wear_rate is None else wear_rate[box]
        apply: Callable[[np.ndarray], np.ndarray]
        if k_w is None:
            def apply(p):
                return op.apply("zz", p)
        else:
            def apply(p):
                return op.apply("zz", p) + k_w * p
        kw = dict(P=P, approach=approach, p0=None if p0 is None else p0[box], tol=self.tol,
                  max_iter=self.max_iter, floor=floor)
        dA = self.dx * self.dy
        if self.method == "cg":
            sol = polonsky_keer(apply, h[box], dA, self.c, **kw)
        else:
            L = self.L + (0.0 if wear_rate is None else float(wear_rate.max()))
            sol = uzawa_normal(apply, h[box], dA, self.c, 1.0 / L, **kw)
        if box == self.full:
            return sol
        p_n = np.zeros(self.n)
        p_n[box] = sol.p_n
        gap = h + self._apply_full(p_n, wear_rate) - sol.approach
        return NormalSolution(p_n, sol.approach, gap, sol.iterations, sol.residual)
