"""Influence products u = A p (Eq. 27) as aperiodic FFT convolutions.

The influence coefficients depend on the offset x_I - x_J only (Eq. 5, 41), so each
block of A is a discrete convolution.  Zero padding to at least 2n - 1 points per axis
makes the cyclic FFT convolution equal the aperiodic sum exactly (no periodic images):
O(N log N) time, O(N) memory, no dense N x N matrix.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .influence import normal_coefficients, surface_coefficients
from .materials import Materials

WORKERS = 1  # FFT threads (numpy.fft: one); results bit-reproducible for a given version


def fast_length(n: int) -> int:
    """The smallest 5-smooth number 2^a 3^b 5^c >= n, the lengths pocketfft's real
    transforms are fast at (what ``scipy.fft.next_fast_len(n, real=True)`` returns; the
    products here use numpy.fft, so that a solve does not import scipy.fft and with it
    scipy.special)."""
    best, p5 = None, 1
    while p5 < 2 * n:
        p35 = p5
        while p35 < 2 * n:
            m = p35
            while m < n:
                m *= 2
            best = m if best is None else min(best, m)
            p35 *= 3
        p5 *= 5
    return max(best, 1)


def padded_shape(nx: int, ny: int) -> tuple[int, int]:
    """FFT sizes >= 2n - 1 (no wrap-around of the aperiodic convolution)."""
    return fast_length(2 * nx - 1), fast_length(2 * ny - 1)


def wrap_offsets(n: int, m: int) -> np.ndarray:
    """Integer cell offsets in the wrap-around order of a length-m FFT: 0 .. n-1, then the
    unused middle (marked n, outside the kernel's support), then -(n-1) .. -1."""
    k = np.full(m, n)
    k[:n] = np.arange(n)
    k[m - n + 1 :] = np.arange(-(n - 1), 0)
    return k


class _LazySpectra(dict):
    """Kernel spectra computed on first access by ``build(key)``."""

    def __init__(self, build):
        super().__init__()
        self._build = build

    def __missing__(self, key: str) -> np.ndarray:
        self[key] = value = self._build(key)
        return value


@dataclass
class ConvolutionOperator:
    """A set of convolution kernels on one grid, applied by zero-padded FFT."""

    n: tuple[int, int]
    shape: tuple[int, int]
    spectra: dict[str, np.ndarray]

    def forward(self, f: np.ndarray) -> np.ndarray:
        return np.fft.rfft2(f, s=self.shape)

    def backward(self, F: np.ndarray) -> np.ndarray:
        return np.fft.irfft2(F, s=self.shape)[: self.n[0], : self.n[1]]

    def apply(self, key: str, f: np.ndarray) -> np.ndarray:
        return self.backward(self.spectra[key] * self.forward(f))


# Parity (in x, in y) of each kernel of Eq. 5 / 41 under a reflection of the offset.
PARITY = {"xx": (1, 1), "yy": (1, 1), "zz": (1, 1), "xy": (-1, -1),
          "xz": (-1, 1), "zx": (-1, 1), "yz": (1, -1), "zy": (1, -1)}


def mirrored(q: np.ndarray, parity: tuple[int, int], shape: tuple[int, int]) -> np.ndarray:
    """A kernel on the wrap-around offsets of a ``shape`` FFT grid (as
    :func:`wrap_offsets`, zero outside |offset| < n) from its values ``q`` on the
    offsets 0 .. n-1 of one quadrant and its parity in x and y."""
    n0, n1 = q.shape
    k = np.zeros(shape)
    k[:n0, :n1] = q
    k[shape[0] - n0 + 1:, :n1] = parity[0] * q[:0:-1, :]
    k[:, shape[1] - n1 + 1:] = parity[1] * k[:, n1 - 1:0:-1]
    return k


def quadrant_offsets(nx: int, ny: int, dx: float, dy: float) -> tuple[np.ndarray, np.ndarray]:
    """Offsets 0 .. n-1 cells along x and y (broadcastable), in mm."""
    return np.arange(nx)[:, None] * dx, np.arange(ny)[None, :] * dy


def normal_operator(nx: int, ny: int, dx: float, dy: float, mat: Materials) -> ConvolutionOperator:
    """The A_zz block of Eq. 27 alone (key "zz") on an nx x ny grid."""
    shape = padded_shape(nx, ny)
    zz = normal_coefficients(*quadrant_offsets(nx, ny, dx, dy), dx, dy, mat)
    k = mirrored(zz, PARITY["zz"], shape)
    return ConvolutionOperator(n=(nx, ny), shape=shape,
                               spectra={"zz": np.fft.rfft2(k)})


class SurfaceOperator(ConvolutionOperator):
    """u = A p for the nine blocks of Eq. 27 on a regular grid of dx x dy cells.

    ``u_i(x_I) = sum_J A_ij(x_I - x_J) p_j(x_J)`` with (i, j) in {x, y, z}; p is the
    traction on body a, u = u^(a) - u^(b) (Eq. 1-2).
    """

    def __init__(self, nx: int, ny: int, dx: float, dy: float, mat: Materials):
        shape = padded_shape(nx, ny)
        super().__init__(n=(nx, ny), shape=shape, spectra=_LazySpectra(self._spectrum))
        self.dx, self.dy = dx, dy
        self.mat = mat
        self.coupled = mat.K != 0
        self._table: dict[str, np.ndarray] | None = None
        centre = surface_coefficients(np.zeros(1), np.zeros(1), dx, dy, mat)
        self.self_zz = float(centre["zz"][0])  # diagonal of A_zz (cell on itself)
        self.self_tt = float(max(centre["xx"][0], centre["yy"][0]))

    def _spectrum(self, key: str) -> np.ndarray:
        """rfft2 of one block's kernel, built when first used (a normal solve needs
        A_zz only; the coupling blocks exist only for K != 0)."""
        if key not in PARITY or (key[0] != key[1] and "z" in key and not self.coupled):
            raise KeyError(key)
        q = self._quadrant(key)
        return np.fft.rfft2(mirrored(q, PARITY[key], self.shape))

    def _quadrant(self, key: str) -> np.ndarray:
        offsets = quadrant_offsets(*self.n, self.dx, self.dy)
        if key == "zz" and self._table is None:
            return normal_coefficients(*offsets, self.dx, self.dy, self.mat)
        if self._table is None:
            self._table = surface_coefficients(*offsets, self.dx, self.dy, self.mat)
        return self._table[key]

    def normal(self, p_n: np.ndarray) -> np.ndarray:
        """u_z due to the normal pressure alone (A_zz p_n)."""
        return self.apply("zz", p_n)

    def tangential(self, p_x: np.ndarray, p_y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(u_x, u_y) due to the tangential tractions alone (A_tt p_t)."""
        Fx, Fy = self.forward(p_x), self.forward(p_y)
        s = self.spectra
        return (self.backward(s["xx"] * Fx + s["xy"] * Fy),
                self.backward(s["xy"] * Fx + s["yy"] * Fy))

    def normal_from_tangential(self, p_x: np.ndarray, p_y: np.ndarray) -> np.ndarray:
        """u_z due to tangential tractions (A_zx p_x + A_zy p_y); zero when K = 0."""
        if not self.coupled:
            return np.zeros(self.n)
        s = self.spectra
        return self.backward(s["zx"] * self.forward(p_x) + s["zy"] * self.forward(p_y))

    def tangential_from_normal(self, p_n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(u_x, u_y) due to the normal pressure (A_xz p_n, A_yz p_n); zero when K = 0."""
        if not self.coupled:
            return np.zeros(self.n), np.zeros(self.n)
        F = self.forward(p_n)
        return self.backward(self.spectra["xz"] * F), self.backward(self.spectra["yz"] * F)

    def __call__(self, p_x, p_y, p_n) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """All three components of u = A p (Eq. 27); blocks of a zero traction are
        skipped (their product is exactly zero)."""
        tangential = np.any(p_x) or np.any(p_y)
        zero = np.zeros(self.n)
        u_x, u_y = self.tangential(p_x, p_y) if tangential else (zero, zero.copy())
        u_z = self.normal(p_n)
        if self.coupled:
            ux_n, uy_n = self.tangential_from_normal(p_n)
            u_x, u_y = u_x + ux_n, u_y + uy_n
            if tangential:
                u_z = u_z + self.normal_from_tangential(p_x, p_y)
        return u_x, u_y, u_z
