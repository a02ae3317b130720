"""The Newton system held as rows of the compliance block
(:mod:`fem_reference.contact.row_system`): its product, its dense form and its diagonal
agree with one another and with the rows written out by hand — a mapped row is B's row,
a combined row the sum of its terms in their order (the same numbers, bit for bit), a
cleared row only what is added after, an extra row only its entries."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from fem_reference.contact.row_system import Rows


def _system(seed: int, nk: int, ne: int):
    rng = np.random.default_rng(seed)
    B = rng.normal(size=(nk, nk))
    J = Rows(B, ne)
    rows = rng.choice(nk, size=min(3, nk), replace=False)
    a, b = rng.normal(size=rows.size), rng.normal(size=rows.size)
    half = nk // 2  # the x row and the y row of a node: two distinct rows of B
    cx = rng.integers(0, half, rows.size)
    cy = cx + half
    J.combine(rows, [(cx, a), (cy, b)])
    diag_add = rng.normal(size=nk)
    J.add(np.arange(nk), np.arange(nk), diag_add)
    extra = nk + np.arange(ne)
    for i in extra:
        J.add(np.full(nk, i), np.arange(nk), rng.normal(size=nk))
        J.add(i, i, 1.0)
    dead = rng.choice(nk, size=1)
    J.clear(dead)
    J.add(dead, dead, 1.0)
    # the same rows written out
    N = nk + ne
    D = np.zeros((N, N))
    D[:nk, :nk] = B
    for r, i, j, u, v in zip(rows, cx, cy, a, b, strict=True):
        D[r, :nk] = u * B[i]
        D[r, :nk] += v * B[j]
    D[np.arange(nk), np.arange(nk)] += diag_add
    sysm = J.system()
    for i in extra:
        D[i] = sysm.E[[i]].toarray()[0]
    D[dead] = 0.0
    D[dead, dead] = 1.0
    return sysm, D, rng


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**31), nk=st.integers(3, 40), ne=st.integers(0, 3))
def test_product_dense_form_and_diagonal_are_the_rows_written_out(seed, nk, ne):
    sysm, D, rng = _system(seed, nk, ne)
    J = sysm.dense()
    assert np.array_equal(J, D)  # the same numbers, bit for bit
    x = rng.normal(size=nk + ne)
    assert np.allclose(sysm.matvec(x), D @ x, rtol=1e-12, atol=1e-12 * np.abs(D).sum())
    assert np.allclose(sysm.diagonal(), np.diag(D), rtol=1e-14, atol=0.0)
    assert sysm.shape == D.shape
