"""Subsurface stresses from the surface tractions (Eq. 32-34) by FFT convolution.

For each depth z the stress influence coefficients B (Eq. 33, Appendix C) depend on the
horizontal offset only, so sigma_ij = B^Sx p_x + B^Sy p_y + B^N p_n is a convolution per
depth layer: along x only for the xz plane (one row of kernels per traction row), in 2D
for a full block.

Stresses are reported in the body ``body`` ('a' upper, 'b' lower) with z >= 0 the depth
into that body and x, y the global axes.  Body a occupies the kernels' half-space
directly.  Body b is mapped through the rotation (x, y, z) -> (x, -y, -z): the kernels
are evaluated at (xo, -yo), body b carries the traction (-p_x, -p_y) which reads
(-p_x, +p_y) in its frame, and sxy, syz change sign on the way back.
"""

from __future__ import annotations

import numpy as np
import scipy.fft as sfft

from cases.model import Grid
from cases.result import STRESS_COMPONENTS, Plane, von_mises

from .operator import WORKERS, padded_shape, wrap_offsets
from .stress_kernels import coefficient_table

LOADS = ("x", "y", "n")


def _signs(body: str) -> tuple[float, float, float]:
    """(sign of yo, sign of p_x, sign of sxy/syz) for the reported body."""
    if body == "a":
        return 1.0, 1.0, 1.0
    if body == "b":
        return -1.0, -1.0, -1.0
    raise ValueError(f"body must be 'a' or 'b', not {body!r}")


def _finish(sig: dict[str, np.ndarray], flip: float) -> dict[str, np.ndarray]:
    sig["sxy"] = flip * sig["sxy"]
    sig["syz"] = flip * sig["syz"]
    sig["vm"] = von_mises(*(sig[c] for c in STRESS_COMPONENTS))
    return sig


class StressEvaluator:
    """Stress planes and blocks for one grid, one set of depths and one body.

    The kernels of the two planes are built once and reused for every call (wear
    evolution calls it at every output step).
    """

    def __init__(self, grid: Grid, z: np.ndarray, nu: float, body: str = "b"):
        self.grid, self.z, self.nu, self.body = grid, np.asarray(z, float), nu, body
        self._plane_cache: dict[tuple, dict] = {}

    # ---------------------------------------------------------------- planes
    def _line_spectra(self, along: str, j0: int) -> dict:
        """Per layer: rfft along the plane's axis of B(s_i - s_i', t_j0 - t_j)."""
        key = (along, j0)
        if key in self._plane_cache:
            return self._plane_cache[key]
        g = self.grid
        ysign, _, _ = _signs(self.body)
        n, nt = (g.nx, g.ny) if along == "x" else (g.ny, g.nx)
        m = sfft.next_fast_len(2 * n - 1, real=True)
        ks = wrap_offsets(n, m)  # cell offsets along the plane, FFT order
        kt = j0 - np.arange(nt)  # offsets across the plane
        spectra = []
        for z in self.z:
            if along == "x":
                kx, ky = ks[:, None], ysign * kt[None, :]
            else:
                kx, ky = kt[None, :], ysign * ks[:, None]
            B = _table_lookup(kx, ky, z, g.dx, g.dy, self.nu)
            valid = (np.abs(ks) < n)[:, None]
            spectra.append({
                (ld, c): sfft.rfft(np.where(valid, B[ld][c], 0.0), axis=0, workers=WORKERS)
                for ld in LOADS for c in STRESS_COMPONENTS
            })
        out = {"m": m, "n": n, "spectra": spectra}
        self._plane_cache[key] = out
        return out

    def plane(self, p_x, p_y, p_n, along: str, j0: int) -> Plane:
        """Stresses on the vertical plane along x ('x': the xz plane at y = y[j0]) or
        along y ('y': the yz plane at x = x[j0])."""
        _, sx, flip = _signs(self.body)
        tractions = {"x": sx * p_x, "y": p_y, "n": p_n}
        if along == "y":
            tractions = {k: v.T for k, v in tractions.items()}
        data = self._line_spectra(along, j0)
        m, n = data["m"], data["n"]
        F = {k: sfft.rfft(v, n=m, axis=0, workers=WORKERS) for k, v in tractions.items()}
        fields = {c: np.empty((n, self.z.size)) for c in STRESS_COMPONENTS}
        for k, spec in enumerate(data["spectra"]):
            for c in STRESS_COMPONENTS:
                acc = sum(spec[(ld, c)] * F[ld] for ld in LOADS)
                fields[c][:, k] = sfft.irfft(acc.sum(axis=1), n=m, workers=WORKERS)[:n]
        s = self.grid.x if along == "x" else self.grid.y
        return Plane(s=s.copy(), z=self.z.copy(), fields=_finish(fields, flip))

    def plane_centre(self, x0: float = 0.0, y0: float = 0.0) -> tuple[float, float]:
        """(x, y) of the cell centre nearest to (x0, y0), where :meth:`planes` cross."""
        i0, j0 = self.grid.nearest_cell(x0, y0)
        return float(self.grid.x[i0]), float(self.grid.y[j0])

    def planes(self, p_x, p_y, p_n, x0: float = 0.0, y0: float = 0.0) -> dict[str, Plane]:
        """The xz and yz planes through the cell centre nearest to (x0, y0)."""
        i0, j0 = self.grid.nearest_cell(x0, y0)
        return {"xz": self.plane(p_x, p_y, p_n, "x", j0),
                "yz": self.plane(p_x, p_y, p_n, "y", i0)}

    # ---------------------------------------------------------------- block
    def block(self, p_x, p_y, p_n) -> dict[str, np.ndarray]:
        """All components and sigma_VM on the (nx, ny, nz) block under the grid."""
        g = self.grid
        ysign, sx, flip = _signs(self.body)
        shape = padded_shape(g.nx, g.ny)
        kx, ky = wrap_offsets(g.nx, shape[0]), wrap_offsets(g.ny, shape[1])
        valid = (np.abs(kx) < g.nx)[:, None] & (np.abs(ky) < g.ny)[None, :]
        F = {k: sfft.rfft2(v, s=shape, workers=WORKERS)
             for k, v in {"x": sx * p_x, "y": p_y, "n": p_n}.items()}
        out = {c: np.empty((g.nx, g.ny, self.z.size)) for c in STRESS_COMPONENTS}
        for k, z in enumerate(self.z):
            B = _table_lookup(kx[:, None], ysign * ky[None, :], z, g.dx, g.dy, self.nu)
            for c in STRESS_COMPONENTS:
                acc = sum(sfft.rfft2(np.where(valid, B[ld][c], 0.0), workers=WORKERS) * F[ld]
                          for ld in LOADS)
                out[c][:, :, k] = sfft.irfft2(acc, s=shape, workers=WORKERS)[: g.nx, : g.ny]
        return _finish(out, flip)


def _table_lookup(kx: np.ndarray, ky: np.ndarray, z: float, dx: float, dy: float,
                  nu: float) -> dict[str, dict[str, np.ndarray]]:
    """Stress coefficients at the integer offsets (kx, ky) (broadcast) from one
    :func:`coefficient_table` over their range."""
    kx, ky = np.rint(kx).astype(np.int64), np.rint(ky).astype(np.int64)
    lo_x, hi_x = int(kx.min()), int(kx.max())
    lo_y, hi_y = int(ky.min()), int(ky.max())
    table = coefficient_table((lo_x, hi_x), (lo_y, hi_y), z, dx, dy, nu)
    ix, iy = np.broadcast_arrays(kx - lo_x, ky - lo_y)
    return {ld: {c: arr[ix, iy] for c, arr in comps.items()} for ld, comps in table.items()}
