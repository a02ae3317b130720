"""Unit tests of the FE building blocks: mesh, P2 space, stiffness, condensation, stresses."""

from __future__ import annotations

from dataclasses import asdict

import numpy as np
import pytest
from skfem import Basis, CellBasis, ElementTetP2, ElementVector, MeshTet, asm
from skfem.models.elasticity import lame_parameters, linear_elasticity

from fem_reference.errors import MeshError
from fem_reference.fields.stresses import PointLocator, sample_displacement, sample_stresses
from fem_reference.model.elasticity import Factorization, P2Space, stiffness, stress_from_gradient
from fem_reference.model.mesh import MeshSpec, block_mesh, build_points
from fem_reference.model.surface import ContactSurface

pytestmark = pytest.mark.fem


def _distorted_box() -> MeshTet:
    m = MeshTet.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 2, 3), np.linspace(-1, 0, 4))
    return MeshTet(m.p + 0.05 * np.sin(3 * m.p[[1, 2, 0]]), m.t)


def test_p2_numbering_is_scikit_fem_p2():
    m = _distorted_box()
    space = P2Space(m)
    basis = CellBasis(m, ElementTetP2())
    assert np.array_equal(space.element_nodes, basis.element_dofs)
    assert np.allclose(space.nodes, basis.doflocs)


def test_stiffness_matches_scikit_fem_linear_elasticity():
    m = _distorted_box()
    space = P2Space(m)
    nu = 0.27
    K = stiffness(space, nu)
    basis = Basis(m, ElementVector(ElementTetP2()))
    K_ref = asm(linear_elasticity(*lame_parameters(1.0, nu)), basis)
    # scikit-fem numbers the vector DOFs per entity; ours are 3 * node + component
    ref_dofs = np.vstack([basis.nodal_dofs.T, basis.edge_dofs.T])  # (nnodes, 3)
    perm = np.empty(K.shape[0], dtype=int)
    perm[(3 * np.arange(space.nnodes)[:, None] + np.arange(3)).ravel()] = ref_dofs.ravel()
    diff = abs(K - K_ref[perm][:, perm]).max()
    assert diff < 1e-12 * abs(K_ref).max()


def test_stiffness_passes_the_patch_test():
    """A linear displacement field (uniform strain) leaves no force on interior nodes, and
    the rigid-body motions none anywhere."""
    m = _distorted_box()
    space = P2Space(m)
    K = stiffness(space, 0.3)
    x = space.nodes
    rng = np.random.default_rng(1)
    A = rng.normal(size=(3, 3))
    u_lin = (A @ x).T.ravel()
    boundary = np.zeros(space.nnodes, bool)
    # boundary nodes of the (distorted) box: those on its boundary facets
    bf = m.facets[:, m.boundary_facets()]
    boundary[np.unique(bf)] = True
    e = m.edges[:, np.unique(m.f2e[:, m.boundary_facets()])]
    boundary[space.edge_node(e[0], e[1])] = True
    interior = np.repeat(~boundary, 3)
    f = K @ u_lin
    assert np.abs(f[interior]).max() < 1e-12 * np.abs(f).max()
    rot = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 0]], float)
    for u in ((rot @ x).T.ravel(), np.tile([1.0, -2.0, 0.5], space.nnodes)):
        assert np.abs(K @ u).max() < 1e-12 * abs(K).max() * np.abs(u).max()


def test_schur_condensation_equals_the_inverse():
    """The Schur-complement factorisation: its condensation is the block of the dense
    inverse, and its solves (forward substitution, the Schur block, backward
    substitution) are those of the plain factorisation, one column or many."""
    m = _distorted_box()
    space = P2Space(m)
    K = stiffness(space, 0.3)
    bottom = np.nonzero(np.isclose(space.nodes[2], -1.0))[0]
    fixed = np.zeros(space.ndofs, bool)
    fixed[(3 * bottom[:, None] + np.arange(3)).ravel()] = True
    free = np.nonzero(~fixed)[0]
    Kff = K[free][:, free].tocsr()
    pick = np.array([3, 17, 40, 41, 100, len(free) - 1])
    F = Factorization(Kff, partial=pick)
    C = F.schur_inverse()
    C_ref = np.linalg.inv(Kff.toarray())[np.ix_(pick, pick)]
    assert np.allclose(C, C_ref, rtol=1e-9, atol=0)
    b = np.random.default_rng(0).normal(size=len(free))
    assert np.allclose(Kff @ F.solve(b), b, atol=1e-9 * np.abs(b).max())
    plain = Factorization(Kff)
    B = np.random.default_rng(1).normal(size=(len(free), 3))
    X = F.solve(B)
    assert X.shape == B.shape
    # two backward-stable solves differ by the condition number times the round-off
    bound = 10 * np.linalg.cond(Kff.toarray()) * np.finfo(float).eps * np.abs(X).max()
    assert np.abs(X - plain.solve(B)).max() < bound
    assert np.abs(X[:, 1] - F.solve(B[:, 1])).max() < bound
    F.free()
    plain.free()


def test_a_solve_does_not_depend_on_where_its_arrays_lie():
    """MKL chooses its code path by the alignment of the arrays it is given unless its
    reproducible mode is on (``elasticity.CBWR``): the same run in another process (a Dask
    worker, ``run --workers``) then differed in the last bit.  The same right-hand side at
    eight offsets in memory gives the same solution, bit for bit, in a plain and a Schur
    factorisation."""
    import scipy.sparse as sp

    n = 25
    one, T = sp.identity(n), sp.diags([-1.0, 2.1, -1.0], [-1, 0, 1], shape=(n, n))
    A = (sp.kron(sp.kron(T, one), one) + sp.kron(sp.kron(one, T), one)
         + sp.kron(sp.kron(one, one), T)).tocsr()
    b = np.random.default_rng(0).standard_normal(A.shape[0])
    for F in (Factorization(A), Factorization(A, partial=np.arange(0, A.shape[0], 7))):
        got, buf = [], np.empty(b.size + 8)
        for offset in range(8):  # every 8-byte step of a 64-byte line
            buf[offset:offset + b.size] = b
            got.append(F.solve(buf[offset:offset + b.size]))
        F.free()
        assert all(np.array_equal(got[0], x) for x in got[1:])


def test_p2_stresses_exact_for_a_quadratic_field():
    """P2 reproduces quadratic displacements: the sampled stress is exact at any point."""
    m = _distorted_box()
    space = P2Space(m)
    x, y, z = space.nodes

    def field(x, y, z):
        return np.stack([x * y + z**2, 0.3 * x * x - y * z, x + y * z + 0.2 * y * y])

    def grad(x, y, z):
        return np.array([[y, x, 2 * z], [0.6 * x, -z, -y], [np.ones_like(x), z + 0.4 * y, y]])

    u = field(x, y, z).T.ravel()
    rng = np.random.default_rng(3)
    pts = np.column_stack([rng.uniform(0.05, 0.95, 50), rng.uniform(0.1, 1.9, 50),
                           rng.uniform(-0.95, -0.05, 50)])
    pts = np.vstack([pts, space.nodes[:, :20].T])  # nodes: several elements contain them
    loc = PointLocator(space)
    sig = sample_stresses(space, loc, u, 0.3, 2.0, pts)
    g = np.moveaxis(grad(*pts.T), -1, 0)
    ref = stress_from_gradient(g, 0.3, 2.0)
    for name, (i, j) in zip(("sxx", "syy", "szz", "sxy", "sxz", "syz"),
                            ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)), strict=True):
        assert np.allclose(sig[name], ref[:, i, j], rtol=0, atol=1e-11)
    assert np.allclose(sample_displacement(space, loc, u, pts), field(*pts.T).T, atol=1e-12)
    with pytest.raises(ValueError, match="outside"):
        loc.locate(np.array([[5.0, 0.0, 0.0]]))


def test_contact_surface_quadrature_and_interpolation():
    mesh = block_mesh(MeshSpec("quarter", 4.0, 4.0, 0.25, 1.5, 1.0, h_max=1.0), 1.0)
    space = P2Space(mesh)
    surf = ContactSurface(space, 1.5, (2,), np.zeros(space.ndofs, bool))
    # degree-5 rule: exact for x^a y^b with a + b <= 5 over each facet
    v = surf.vert_xy
    exact_area = surf.area.sum()
    assert np.isclose(surf.quad_w.sum(), exact_area, rtol=1e-13)
    # ∫ x² y² dA by a fine subdivision-free identity: compare with the 12-point rule
    from skfem.quadrature import get_quadrature
    from skfem.refdom import RefTri

    X, W = get_quadrature(RefTri, 8)
    lam = np.vstack([1 - X[0] - X[1], X[0], X[1]]).T
    xy8 = np.einsum("qk,fkd->fqd", lam, v)
    ref = np.sum(2 * surf.area[:, None] * W[None, :] * xy8[..., 0] ** 2 * xy8[..., 1] ** 3)
    got = np.sum(surf.quad_w * surf.quad_xy[:, 0] ** 2 * surf.quad_xy[:, 1] ** 3)
    assert np.isclose(got, ref, rtol=1e-12)
    # the surface interpolation reproduces quadratics
    f = 1 + surf.xy[:, 0] ** 2 - 2 * surf.xy[:, 0] * surf.xy[:, 1] + 0.5 * surf.xy[:, 1]
    pts = np.random.default_rng(2).uniform(0.0, 0.9, size=(40, 2))
    N, found = surf.interpolation(pts)
    assert found.all()
    ref = 1 + pts[:, 0] ** 2 - 2 * pts[:, 0] * pts[:, 1] + 0.5 * pts[:, 1]
    assert np.allclose(N @ f, ref, atol=1e-12)
    _, found = surf.interpolation(np.array([[2.0, 0.0]]))
    assert not found.any()


def test_mesh_cache_and_determinism(tmp_path, monkeypatch):
    monkeypatch.setenv("CONTACT_VV_CACHE", str(tmp_path))
    spec = MeshSpec("half", 5.0, 5.0, 0.5, 1.5, 1.0, h_max=1.5)
    p1, t1 = build_points(spec)
    files = list((tmp_path / "fem-meshes").glob("block-*.npz"))
    assert len(files) == 1
    p2, t2 = build_points(spec)  # from the cache
    assert np.array_equal(p1, p2) and np.array_equal(t1, t2)
    p3, t3 = build_points(spec, use_cache=False)  # gmsh again, single-threaded
    assert np.array_equal(p1, p3) and np.array_equal(t1, t3)
    # the half block covers -L <= x <= L, 0 <= y <= L, -H <= z <= 0
    assert np.allclose(p1.min(axis=1), [-5, 0, -5]) and np.allclose(p1.max(axis=1), [5, 5, 0])
    other = MeshSpec("half", 5.0, 5.0, 0.4, 1.5, 1.0, h_max=1.5)
    assert other.key() != spec.key()


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(shape="disk"), "shape"),
        (dict(h=-0.1), "h = "),
        (dict(r_ref=6.0), "does not fit"),
        (dict(h=2.0), "below r_ref"),
        (dict(h_surface=0.3), "h_surface"),
        (dict(h_surface=0.0), "h_surface"),
    ],
)
def test_mesh_spec_errors(kwargs, match):
    base = dict(shape="quarter", L=5.0, H=5.0, h=0.25, r_ref=1.5, z_ref=1.0)
    base.update(kwargs)
    with pytest.raises(MeshError, match=match):
        MeshSpec(**base)


def test_surface_layer_refines_the_contact_surface_only(tmp_path, monkeypatch):
    """``h_surface``: the top facets in the refined zone have about h_surface edges (not
    h), the elements at depth keep h, and the estimate counts the refined mesh's
    tetrahedra and contact facets as it counts uniform ones (within its calibration)."""
    from fem_reference import cost

    monkeypatch.setenv("CONTACT_VV_CACHE", str(tmp_path))
    kw = dict(shape="half", L=5.0, H=5.0, h=0.25, r_ref=1.5, z_ref=2.0, h_max=1.5)

    def edges(points, tets, where):
        """Mean edge length of the tetrahedra whose centroid satisfies ``where``."""
        c = points[:, tets].mean(axis=1)
        keep = where(c)
        P = points[:, tets[:, keep]]
        pairs = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
        return float(np.mean([np.linalg.norm(P[:, i] - P[:, j], axis=0) for i, j in pairs]))

    def top(c):
        return (np.hypot(c[0], c[1]) < 1.0) & (c[2] > -0.05)

    def deep(c):  # below the layer, (h - h_surface) / SURFACE_GRADING = 1.25 deep
        return (np.hypot(c[0], c[1]) < 1.0) & (c[2] < -1.4) & (c[2] > -1.9)

    uniform = build_points(MeshSpec(**kw))
    layered = build_points(MeshSpec(**kw, h_surface=0.125))
    # the uniform mesh's elements of size h at depth are the yardstick (edge ~ 1.4 size)
    ratio_top = edges(*layered, top) / edges(*uniform, deep)
    ratio_deep = edges(*layered, deep) / edges(*uniform, deep)
    assert 0.35 < ratio_top < 0.6, ratio_top  # h_surface / h = 0.5 (measured 0.45)
    assert 0.9 < ratio_deep < 1.1, ratio_deep
    assert MeshSpec(**kw, h_surface=0.125).key() != MeshSpec(**kw).key()
    for spec, (_, tets) in ((MeshSpec(**kw), uniform),
                            (MeshSpec(**kw, h_surface=0.125), layered)):
        assert 0.8 < tets.shape[1] / cost.element_count(asdict(spec)) < 1.25
