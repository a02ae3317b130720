"""The relative compliance held as the blocks' compliances
(:class:`fem_reference.contact.relative.RelativeCompliance`) against the matrix formed
whole: its rows the same numbers, its products equal to round-off, and the nodal
compliance built from it the same matrix bit for bit (decoupled where the whole one is)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from fem_reference.contact.compliance import NodalCompliance
from fem_reference.contact.relative import RelativeCompliance


def _spd(m: int, rng, fortran: bool) -> np.ndarray:
    """An exactly symmetric SPD block compliance with normal–tangential coupling."""
    A = rng.standard_normal((m, m)) / m
    C = A @ A.T + np.eye(m)
    C = 0.5 * (C + C.T)
    return np.asfortranarray(C) if fortran else C


@pytest.mark.parametrize("same, fortran", [(True, True), (False, True), (True, False)])
def test_the_relative_compliance_is_the_whole_one(same, fortran):
    rng = np.random.default_rng(7)
    n = 40
    m = 3 * n
    C_b = _spd(m, rng, fortran)
    C_a = C_b if same else _spd(m, rng, fortran)
    Rz = np.r_[np.ones(2 * n), -np.ones(n)]
    E_a, E_b = (2.1e5, 2.1e5) if same else (1.1e5, 2.1e5)
    whole = (Rz[:, None] * C_a * Rz[None, :]) / E_a + C_b / E_b  # as formed before
    rel = RelativeCompliance(C_a, C_b, Rz, E_a, E_b)
    K = np.sort(rng.choice(m, 25, replace=False))
    assert np.array_equal(rel.rows(K), whole[K])
    assert np.array_equal(rel.dense(), whole)
    for v in (rng.standard_normal(m), rng.standard_normal((m, 3))):
        assert np.abs(rel @ v - whole @ v).max() <= 1e-14 * np.abs(whole).max() * m
    G = (sp.identity(m) + sp.random(m, m, density=0.03, random_state=rng)).tocsr()
    # the nodal basis maps each component onto its own condensed DOFs
    comp = np.repeat(np.arange(3), n)
    G = G.multiply(comp[:, None] == comp[None, :]).tocsr()
    w = rng.uniform(0.5, 2.0, n)
    h = rng.uniform(0.0, 1.0, n)
    a = NodalCompliance.build(whole, G, w, h)
    b = NodalCompliance.build(rel, G, w, h)
    assert len(a.blocks) == len(b.blocks) == (2 if same else 1)
    for (fa, Ba), (fb, Bb) in zip(a.blocks, b.blocks, strict=True):
        assert fa == fb and np.array_equal(Ba, Bb)
    assert a.decoupled == b.decoupled == same
    lam = rng.standard_normal((3, n))
    assert np.abs(a.u(lam) - b.u(lam)).max() <= 1e-14 * np.abs(a.u(lam)).max() * m


def test_a_normal_contact_keeps_its_normal_block_alone():
    """Condensed normal DOFs only (a frictionless or sliding contact between identical
    materials): the nodal compliance keeps its normal block alone, and its products,
    blocks, cross blocks and diagonal are the whole matrix's."""
    rng = np.random.default_rng(11)
    n = 30
    C = _spd(n, rng, True)
    G = sp.vstack([sp.csr_matrix((2 * n, n)),
                   sp.identity(n) + sp.random(n, n, density=0.05, random_state=rng)]).tocsr()
    w = rng.uniform(0.5, 2.0, n)
    op = NodalCompliance.build(C, G, w, rng.uniform(0.0, 1.0, n))
    assert op.decoupled and [first for first, _ in op.blocks] == [2 * n]
    HW = (G @ C @ G.T.toarray()) * np.tile(w, 3)[None, :]
    top = 1e-14 * np.abs(HW).max()
    lam = rng.standard_normal((3, n))
    assert np.abs(op.apply(lam) - (HW @ lam.ravel()).reshape(3, n)).max() <= top * n
    assert np.abs(op.diagonal() - np.diag(HW).reshape(3, n)).max() <= top
    cols = np.sort(rng.choice(3 * n, 40, replace=False))
    assert np.abs(op.block(cols) - HW[np.ix_(cols, cols)]).max() <= top
    rows = rng.choice(3 * n, 17, replace=False)
    assert np.abs(op.cross(rows, cols) - HW[np.ix_(rows, cols)]).max() <= top
