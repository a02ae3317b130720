"""Subsurface stresses from the surface tractions (Eq. 32-34) by FFT convolution.

For each depth z the stress influence coefficients B (Eq. 33, Appendix C) depend on the
horizontal offset only, so sigma_ij = B^Sx p_x + B^Sy p_y + B^N p_n is a convolution per
depth layer: along x only for the xz plane (one row of kernels per traction row), in 2D
for a full block.

The convolution is exact and aperiodic.  Only the bounding box of the nonzero tractions
(w cells along an axis of n cells; usually the contact) is convolved, with the kernel
sampled at the n + w - 1 offsets (output - source) it meets, zero-padded to an FFT length
>= n + w - 1: no wrap-around reaches the n outputs (:func:`_source_offsets`).  A traction
component that vanishes everywhere is skipped.  The kernels are tabulated on one quadrant
of offsets and mirrored by their parity (:func:`halfspace.stress_kernels.symmetric_table`).

Stresses are reported in the body ``body`` ('a' upper, 'b' lower) with z >= 0 the depth
into that body and x, y the global axes.  Body a occupies the kernels' half-space
directly.  Body b is mapped through the rotation (x, y, z) -> (x, -y, -z): the kernels
are evaluated at (xo, -yo), body b carries the traction (-p_x, -p_y) which reads
(-p_x, +p_y) in its frame, and sxy, syz change sign on the way back.

Depth layers are independent; up to ``STRESS_WORKERS`` threads evaluate them, each layer
entirely on one thread with single-threaded FFTs, so the result is bit-identical
whatever the number of threads or their scheduling.
"""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
import scipy.fft as sfft

from cases.model import Grid
from cases.result import STRESS_COMPONENTS, Plane, von_mises

from .stress_kernels import coefficient_table, folded_range, parity, symmetric_table, unfold

LOADS = ("x", "y", "n")
FLIPPED = ("sxy", "syz")  # components that change sign from body a's frame to body b's
STRESS_WORKERS = 2  # threads over depth layers (the bits do not depend on it, see above)
FFT_WORKERS = 1  # threads inside one FFT
BLOCK_CHUNK = 8  # consecutive layers a thread buffers before writing them into the block


def _signs(body: str) -> tuple[int, float, float]:
    """(sign of yo, sign of p_x, sign of sxy/syz) for the reported body."""
    if body == "a":
        return 1, 1.0, 1.0
    if body == "b":
        return -1, -1.0, -1.0
    raise ValueError(f"body must be 'a' or 'b', not {body!r}")


@dataclass(frozen=True)
class _Window:
    """The nonzero traction components cut to their common bounding box, whose first
    cell is ``lo``."""

    loads: dict[str, np.ndarray]
    lo: tuple[int, int]

    @property
    def shape(self) -> tuple[int, int]:
        return next(iter(self.loads.values())).shape

    @property
    def key(self) -> tuple:
        return tuple(self.loads), self.lo, self.shape


def _window(tractions: dict[str, np.ndarray]) -> _Window | None:
    """The window of the tractions (any nonzero or NaN value counts), None if all vanish."""
    nonzero = {ld: np.asarray(p, float) for ld, p in tractions.items() if np.any(p)}
    if not nonzero:
        return None
    mask = np.logical_or.reduce([p != 0 for p in nonzero.values()])
    rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
    box = (slice(rows[0], rows[-1] + 1), slice(cols[0], cols[-1] + 1))
    return _Window({ld: p[box] for ld, p in nonzero.items()}, (int(rows[0]), int(cols[0])))


def _scaled(r: range, sign: int) -> range:
    """The elements of ``r`` times ``sign`` (+-1), in the same order."""
    return range(sign * r.start, sign * r.stop, sign * r.step)


def _source_offsets(n: int, lo: int, w: int, sign: int = 1) -> range:
    """``sign * d`` for the cell offsets d = i - i' between outputs i in [0, n) and
    sources i' in [lo, lo + w), d increasing from -(lo + w - 1): the n + w - 1 kernel
    samples of the convolution.  Sampled in this order and zero-padded to L >= n + w - 1,
    the cyclic convolution with the window's tractions equals the aperiodic sum at
    indices w - 1 .. w + n - 2 (output i at index i + w - 1)."""
    return _scaled(range(-(lo + w - 1), n - lo), sign)


def _across_offsets(j0: int, lo: int, w: int, sign: int = 1) -> range:
    """``sign * (j0 - j')`` for the window's sources j' = lo .. lo + w - 1, in that order."""
    return _scaled(range(j0 - lo, j0 - lo - w, -1), sign)


def _span(off: range) -> tuple[int, int]:
    """(min, max) of a nonempty range of step +-1."""
    return min(off[0], off[-1]), max(off[0], off[-1])


def _kernels(offx: range, offy: range, z: float, dx: float, dy: float, nu: float,
             loads: tuple[str, ...]) -> dict[str, dict[str, np.ndarray]]:
    """B (Eq. 33) at the offsets (offx[a] dx, offy[b] dy), as arrays indexed [a, b]."""
    table = symmetric_table(_span(offx), _span(offy), z, dx, dy, nu, loads)
    order = (slice(None, None, offx.step), slice(None, None, offy.step))
    return {ld: {c: arr[order] for c, arr in comps.items()} for ld, comps in table.items()}


def _run_layers(work: Callable[[range], None], nz: int, chunk: int = 1) -> None:
    """``work(ks)`` for the chunks ks = range(k0, k0 + chunk) of the nz layers; thread t of
    ``STRESS_WORKERS`` takes the chunks t, t + (thread count), ...  Each call must write
    only its own layers' outputs."""
    chunks = [range(k, min(k + chunk, nz)) for k in range(0, nz, chunk)]
    nw = max(1, min(STRESS_WORKERS, len(chunks)))
    if nw == 1:
        for ks in chunks:
            work(ks)
        return
    with ThreadPoolExecutor(nw) as pool:
        jobs = [pool.submit(lambda t=t: [work(ks) for ks in chunks[t::nw]]) for t in range(nw)]
        for job in jobs:
            job.result()


@dataclass(frozen=True)
class _Sampling:
    """Where a block layer's kernel samples go: the offset spans (x, y) of
    :func:`_source_offsets`, whether the y samples run down the span (body b), the FFT
    shape and the slice of the cyclic convolution that holds the grid's outputs."""

    spans: tuple[tuple[int, int], tuple[int, int]]
    y_reversed: bool
    shape: tuple[int, int]
    keep: tuple[slice, slice]


def _layer_fields(quad: dict[str, dict[str, np.ndarray]], F: dict[str, np.ndarray],
                  sampling: _Sampling, flip: float) -> dict[str, np.ndarray]:
    """One layer of Eq. 34: sigma_c = irfft2(sum_ld rfft2(B_ld,c) P̂_ld) for the six
    components (B from the quadrant table ``quad``, P̂ the window's traction spectra),
    sxy and syz times ``flip``, and sigma_VM."""
    nsx, nsy = (hi - lo + 1 for lo, hi in sampling.spans)
    padded = np.zeros(sampling.shape)  # one kernel at a time, zero-padded to the FFT shape
    kernel = padded[:nsx, :nsy][:, ::-1] if sampling.y_reversed else padded[:nsx, :nsy]
    fields = {}
    for c in STRESS_COMPONENTS:
        acc = None
        for ld, P in F.items():
            unfold(quad[ld][c], *sampling.spans, parity(ld, c), out=kernel)
            term = sfft.rfft2(padded, workers=FFT_WORKERS)
            term *= P
            acc = term if acc is None else np.add(acc, term, out=acc)
        fields[c] = sfft.irfft2(acc, s=sampling.shape, workers=FFT_WORKERS)[sampling.keep]
        if c in FLIPPED:
            fields[c] *= flip
    fields["vm"] = von_mises(*(fields[c] for c in STRESS_COMPONENTS))
    return fields


def _zeros(n: int, nt: int, nz: int | None = None) -> dict[str, np.ndarray]:
    shape = (n, nt) if nz is None else (n, nt, nz)
    return {c: np.zeros(shape) for c in (*STRESS_COMPONENTS, "vm")}


class StressEvaluator:
    """Stress planes and blocks for one grid, one set of depths and one body.

    The kernel spectra of a plane are kept for the latest traction window of that plane
    and reused while the window stays the same (wear evolution calls it at every output
    step).
    """

    def __init__(self, grid: Grid, z: np.ndarray, nu: float, body: str = "b"):
        self.grid, self.z, self.nu, self.body = grid, np.asarray(z, float), nu, body
        _signs(body)
        self._plane_cache: dict[tuple[str, int], tuple[tuple, dict]] = {}

    # ---------------------------------------------------------------- planes
    def _line_spectra(self, along: str, j0: int, win: _Window) -> dict:
        """Per layer: rfft along the plane's axis of B(s_i - s_i', t_j0 - t_j') for the
        window's sources (s_i', t_j'), sampled as in :func:`_source_offsets`."""
        cached = self._plane_cache.get((along, j0))
        if cached is not None and cached[0] == win.key:
            return cached[1]
        g = self.grid
        ysign, _, _ = _signs(self.body)
        n = g.nx if along == "x" else g.ny
        offs = _source_offsets(n, win.lo[0], win.shape[0])
        offt = _across_offsets(j0, win.lo[1], win.shape[1])
        offx, offy = (offs, _scaled(offt, ysign)) if along == "x" else (offt, _scaled(offs, ysign))
        m = sfft.next_fast_len(len(offs), real=True)
        loads = tuple(win.loads)
        spectra: list[dict] = [{} for _ in self.z]

        def layers(ks: range) -> None:
            for k in ks:
                B = _kernels(offx, offy, self.z[k], g.dx, g.dy, self.nu, loads)
                for ld in loads:
                    for c in STRESS_COMPONENTS:
                        b = B[ld][c] if along == "x" else B[ld][c].T
                        spectra[k][(ld, c)] = sfft.rfft(b, n=m, axis=0, workers=FFT_WORKERS)

        _run_layers(layers, self.z.size)
        out = {"m": m, "n": n, "spectra": spectra}
        self._plane_cache[(along, j0)] = (win.key, out)
        return out

    def plane(self, p_x, p_y, p_n, along: str, j0: int) -> Plane:
        """Stresses on the vertical plane along x ('x': the xz plane at y = y[j0]) or
        along y ('y': the yz plane at x = x[j0]) (Eq. 34)."""
        _, sx, flip = _signs(self.body)
        tractions = {"x": sx * p_x, "y": p_y, "n": p_n}
        if along == "y":
            tractions = {k: v.T for k, v in tractions.items()}
        s = self.grid.x if along == "x" else self.grid.y
        fields = _zeros(s.size, self.z.size)
        win = _window(tractions)
        if win is not None:
            data = self._line_spectra(along, j0, win)
            m, n, w = data["m"], data["n"], win.shape[0]
            F = {ld: sfft.rfft(p, n=m, axis=0, workers=FFT_WORKERS) for ld, p in win.loads.items()}
            for k, spec in enumerate(data["spectra"]):
                for c in STRESS_COMPONENTS:
                    acc = sum(spec[(ld, c)] * F[ld] for ld in F)
                    line = sfft.irfft(acc.sum(axis=1), n=m, workers=FFT_WORKERS)[w - 1 : w - 1 + n]
                    fields[c][:, k] = flip * line if c in FLIPPED else line
            fields["vm"] = von_mises(*(fields[c] for c in STRESS_COMPONENTS))
        return Plane(s=s.copy(), z=self.z.copy(), fields=fields)

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
        """All components and sigma_VM on the (nx, ny, nz) block under the grid (Eq. 34):
        per layer one 2D kernel spectrum per (load, component), the loads summed in
        Fourier space and one inverse FFT per component."""
        g = self.grid
        ysign, sx, flip = _signs(self.body)
        out = _zeros(g.nx, g.ny, self.z.size)
        win = _window({"x": sx * p_x, "y": p_y, "n": p_n})
        if win is None:
            return out
        (wx, wy), (ix, jy) = win.shape, win.lo
        offx = _source_offsets(g.nx, ix, wx)
        offy = _source_offsets(g.ny, jy, wy, ysign)
        shape = (sfft.next_fast_len(len(offx)), sfft.next_fast_len(len(offy), real=True))
        F = {ld: sfft.rfft2(p, s=shape, workers=FFT_WORKERS) for ld, p in win.loads.items()}
        keep = (slice(wx - 1, wx - 1 + g.nx), slice(wy - 1, wy - 1 + g.ny))
        spans = (_span(offx), _span(offy))
        folded = (folded_range(*spans[0]), folded_range(*spans[1]))
        sampling = _Sampling(spans, offy.step < 0, shape, keep)

        def layers(ks: range) -> None:
            # layer-major buffer, copied at once: runs of len(ks) contiguous outputs
            buf = {c: np.empty((len(ks), g.nx, g.ny)) for c in out}
            for a, k in enumerate(ks):
                quad = coefficient_table(*folded, self.z[k], g.dx, g.dy, self.nu, tuple(F))
                for c, f in _layer_fields(quad, F, sampling, flip).items():
                    buf[c][a] = f
            for c in out:
                out[c][:, :, ks.start : ks.stop] = buf[c].transpose(1, 2, 0)

        _run_layers(layers, self.z.size, BLOCK_CHUNK)
        return out
