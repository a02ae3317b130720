"""FFT influence products equal the dense sums of Eq. 26 (no periodic images)."""

import numpy as np
import pytest

from cases.model import Body
from halfspace.influence import surface_coefficients
from halfspace.materials import Materials
from halfspace.operator import SurfaceOperator

PAIRS = {
    "identical": (Body(210000.0, 0.3), Body(210000.0, 0.3)),
    "dissimilar": (Body(70000.0, 0.33), Body(210000.0, 0.28)),
}


def dense_matrix(nx, ny, dx, dy, mat, key):
    x = np.arange(nx) * dx
    y = np.arange(ny) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    xf, yf = X.ravel(), Y.ravel()
    return surface_coefficients(xf[:, None] - xf[None, :], yf[:, None] - yf[None, :],
                                dx, dy, mat)[key]


@pytest.mark.parametrize("pair", PAIRS)
def test_fft_product_equals_dense(pair):
    nx, ny, dx, dy = 12, 9, 0.013, 0.031  # aspect ratio != 1
    mat = Materials.from_bodies(*PAIRS[pair])
    op = SurfaceOperator(nx, ny, dx, dy, mat)
    rng = np.random.default_rng(1)
    p = {k: rng.standard_normal((nx, ny)) for k in "xyz"}
    u = dict(zip("xyz", op(p["x"], p["y"], p["z"]), strict=True))
    for i in "xyz":
        dense = sum(dense_matrix(nx, ny, dx, dy, mat, i + j) @ p[j].ravel() for j in "xyz")
        err = np.abs(u[i].ravel() - dense).max() / np.abs(dense).max()
        assert err < 1e-12, (i, err)


def test_operator_is_aperiodic():
    """A load in one corner produces no image at the opposite corner: compare with the
    exact coefficient at the largest offset."""
    nx, ny, dx = 16, 16, 0.01
    mat = Materials.from_bodies(*PAIRS["identical"])
    op = SurfaceOperator(nx, ny, dx, dx, mat)
    p = np.zeros((nx, ny))
    p[0, 0] = 1.0
    u = op.normal(p)
    exact = surface_coefficients(np.array((nx - 1) * dx), np.array((ny - 1) * dx), dx, dx,
                                 mat)["zz"]
    assert abs(u[-1, -1] - exact) < 1e-12 * abs(exact)
