"""The mirror-parity split of the full and half blocks (``fem_reference.model.parity``):
the quarter's parity problems reproduce the mirrored mesh's own factorisation and
condensation to round-off, their solves its solves (a half block's companion too), and
a sign put wrong breaks the identity."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from fem_reference.model import block, parity
from fem_reference.model.block import FactorisedBlock
from fem_reference.model.elasticity import Factorization, stiffness
from fem_reference.model.mesh import MeshSpec, build_points

SPEC = MeshSpec("full", 4.0, 4.0, 0.45, 1.5, 1.2, h_max=1.3)
NU = 0.3


def _direct(core: FactorisedBlock) -> tuple[Factorization, np.ndarray]:
    """The mirrored mesh's own factorisation and Schur-complement compliance."""
    K = stiffness(core.space, NU)
    pos = np.searchsorted(core.free, core.surface.dofs[core.cidx])
    F = Factorization(K[core.free][:, core.free].tocsr(), partial=pos)
    return F, F.schur_inverse()


@pytest.fixture(scope="module", params=["full", "half"])
def core(request) -> FactorisedBlock:
    """The full block (four parities) and the half block mirrored about X = 0 with a
    companion (two and two), whatever ``block.MIRRORED`` holds."""
    half = request.param == "half"
    with pytest.MonkeyPatch.context() as mp:
        mp.setitem(block.MIRRORED, "half", (0,))
        return FactorisedBlock(replace(SPEC, shape=request.param), 1.0, (0, 1, 2), (NU,),
                               companion=half)


def test_the_mirrored_mesh_is_the_quarter_and_its_images():
    points, tets = build_points(MeshSpec("quarter", *[getattr(SPEC, k) for k in (
        "L", "H", "h", "r_ref", "z_ref", "grading", "h_max")]))
    P, T, image = parity.mirrored(points, tets, 1e-9)
    n_plane = [int((points[a] == 0.0).sum()) for a in (0, 1)]
    n_axis = int(((points[0] == 0.0) & (points[1] == 0.0)).sum())
    assert P.shape[1] == 4 * points.shape[1] - 2 * sum(n_plane) + n_axis
    assert T.shape[1] == 4 * tets.shape[1]
    np.testing.assert_array_equal(np.abs(P[:2]), points[:2, image])
    np.testing.assert_array_equal(P[2], points[2, image])
    # the point set is its own mirror image about both planes, point for point
    keys = {tuple(p) for p in P.T}
    for axis in (0, 1):
        Q = P.copy()
        Q[axis] = -Q[axis]
        assert {tuple(q) for q in Q.T} == keys

    def det(p, t):
        X = p[:, t]
        return np.linalg.det(np.moveaxis(np.stack([X[:, k] - X[:, 0] for k in (1, 2, 3)],
                                                  axis=1), -1, 0))

    d_q, d_f = det(points, tets), det(P, T)
    np.testing.assert_allclose(np.abs(d_f).sum(), 4 * np.abs(d_q).sum(), rtol=1e-12)
    np.testing.assert_array_equal(np.sign(d_f), np.tile(np.sign(d_q), 4))


def test_the_four_quarter_problems_are_the_full_blocks_compliance(core):
    _, C_direct = _direct(core)
    C = core.C1[NU]
    assert C.shape == C_direct.shape
    dense = C.dense()
    scale = np.abs(C_direct).max()
    # two factorisations of one matrix: round-off apart (measured about 1e-14)
    assert np.abs(dense - C_direct).max() <= 1e-11 * scale
    np.testing.assert_array_equal(dense, dense.T)  # exactly symmetric, as C₁ is
    rows = np.array([0, 5, C.shape[0] - 1, 17])
    np.testing.assert_array_equal(C.rows(rows), dense[rows])
    V = np.random.default_rng(1).standard_normal((C.shape[0], 3))
    assert np.abs(C @ V - C_direct @ V).max() <= 1e-11 * np.abs(C_direct @ V).max()
    assert (C @ V[:, 0]).shape == (C.shape[0],)
    # a block per parity, of about 1/4 (full) or 1/2 (half) of the contact DOFs each
    sizes = [B.shape[0] for B in C.blocks]
    assert len(sizes) == C.images and max(sizes) < 1.6 * C.shape[0] / C.images


def test_the_four_quarter_solves_are_the_full_blocks_solve(core):
    F, _ = _direct(core)
    B = np.random.default_rng(2).standard_normal((core.free.size, 2))
    x = core.factor[NU].solve(B)
    assert np.abs(x - F.solve(B)).max() <= 1e-11 * np.abs(x).max()
    x0 = core.factor[NU].solve(B[:, 0])
    np.testing.assert_allclose(x0, x[:, 0], rtol=0, atol=1e-13 * np.abs(x).max())
    if core.free_anti is not None:  # the companion: the half mesh's antisymmetric problem
        fa = core.free_anti
        F_anti = Factorization(stiffness(core.space, NU)[fa][:, fa].tocsr())
        b = np.random.default_rng(3).standard_normal(fa.size)
        x = core.factor_anti[NU].solve(b)
        assert np.abs(x - F_anti.solve(b)).max() <= 1e-11 * np.abs(x).max()


def test_the_supports_rows_are_the_full_stiffness_rows(core):
    K = stiffness(core.space, NU)
    fixed = np.nonzero(core.fixed)[0]
    diff = core.stiffness[NU] - K[fixed]
    assert abs(diff).max() <= 1e-14 * abs(K).max()


def test_a_wrong_parity_sign_breaks_the_identity(monkeypatch):
    """The identity test sees a seeded defect: u_z's mirror sign about X = 0 turned."""
    right = parity.parity_signs

    def wrong(p):
        s = right(p)
        s[0, 2] = -s[0, 2]
        return s

    monkeypatch.setattr(parity, "parity_signs", wrong)
    bad = FactorisedBlock(SPEC, 1.0, (0, 1, 2), (NU,))  # the full block
    monkeypatch.undo()
    _, C_direct = _direct(bad)
    assert np.abs(bad.C1[NU].dense() - C_direct).max() > 1e-3 * np.abs(C_direct).max()
