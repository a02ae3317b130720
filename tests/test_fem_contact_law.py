"""The FEM contact laws at single points: friction return map, sliding, wear, tangents."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from cases.model import Body, Friction
from cases.result import OPEN, SLIP, STICK
from fem_reference.contact.laws import Law, Points, axes_tensor, evaluate, norm_with
from fem_reference.model.shape import wear_compliances

pytestmark = pytest.mark.fem

MU1, MU2, BETA = 0.25, 0.5, 30.0


def friction_law(k_n=1e6, mode="friction"):
    M2 = axes_tensor(MU1**2, MU2**2, BETA)
    M2inv = axes_tensor(MU1**-2, MU2**-2, BETA)
    return Law(k_n=k_n, mode=mode, k_t=k_n / MU1**2, M2=M2, M2inv=M2inv)


def points(n, disp):
    """n points whose displacement (n, 3) is given directly (G = identity blocks)."""
    G = sp.identity(3 * n, format="csr")
    pts = Points(G=G, w=np.ones(n), xy=np.zeros((n, 2)), h=np.zeros(n), inside=np.ones(n, bool))
    u = np.asarray(disp, dtype=float).T.ravel()
    return pts, u


def test_ellipse_norms_follow_eqs_9_10():
    t = np.array([0.3, -0.7])
    R = np.array([[math.cos(math.radians(BETA)), math.sin(math.radians(BETA))],
                  [-math.sin(math.radians(BETA)), math.cos(math.radians(BETA))]])
    te = R @ t
    law = friction_law()
    assert norm_with(law.M2inv, t) == pytest.approx(math.hypot(te[0] / MU1, te[1] / MU2))
    assert norm_with(law.M2, t) == pytest.approx(math.hypot(MU1 * te[0], MU2 * te[1]))


def test_gross_slip_from_rest_is_eq_13():
    """From rest, a large slip increment returns p_t = −p_n 𝕄² Δg / ‖Δg‖*_μ (Eq. 13)."""
    law = friction_law()
    rng = np.random.default_rng(4)
    n = 20
    dg = rng.normal(size=(n, 2)) * 1e-3
    disp = np.column_stack([dg, np.full(n, 1e-4)])  # u_n = 1e-4 with δ = 2e-4: g_n = −1e-4
    pts, u = points(n, disp)
    ev = evaluate(law, pts, u, 2e-4, np.zeros(2))
    pn = law.k_n * 1e-4
    assert np.allclose(ev.pn, pn)
    expected = -pn * (dg @ law.M2.T) / norm_with(law.M2, dg)[:, None]
    assert np.allclose(ev.t, expected, rtol=1e-12, atol=1e-12 * pn)
    assert np.allclose(norm_with(law.M2inv, ev.t), pn)  # on the ellipse (Eq. 9)
    assert np.all(ev.state == SLIP)


def test_return_map_slip_is_associated():
    """From a stuck state, the plastic part of the slip is ∝ −𝕄⁻² p_t (normal to the ellipse)."""
    law = friction_law()
    pn = 100.0
    t_old = np.array([[10.0, 5.0]])
    dg = np.array([[2e-4, -1e-4]])
    pts, u = points(1, np.column_stack([dg, [[-pn / law.k_n + 0.0]]]))
    pts.t_old = t_old
    ev = evaluate(law, pts, u, 0.0, np.zeros(2))
    assert ev.pn[0] == pytest.approx(pn)
    assert ev.state[0] == SLIP
    # elastic relation t = t_old − k_t 𝕄² (Δg − Δg_p)  =>  Δg_p
    dg_p = dg[0] - np.linalg.solve(law.k_t * law.M2, t_old[0] - ev.t[0])
    normal = law.M2inv @ ev.t[0]
    cross = dg_p[0] * normal[1] - dg_p[1] * normal[0]
    assert abs(cross) < 1e-9 * np.linalg.norm(dg_p) * np.linalg.norm(normal)
    assert dg_p @ normal < 0  # slip opposes the traction on body a


def test_stick_and_open():
    law = friction_law()
    pts, u = points(2, [[1e-9, 0.0, -1e-4], [0.0, 0.0, 1e-3]])
    ev = evaluate(law, pts, u, 0.0, np.zeros(2))
    assert ev.state[0] == STICK and ev.state[1] == OPEN
    assert np.allclose(ev.t[0], -law.k_t * law.M2 @ np.array([1e-9, 0.0]))
    assert ev.pn[1] == 0 and np.all(ev.t[1] == 0)


def test_sliding_traction_erratum_11():
    """Sliding along d resists with p_n ‖d‖*_μ along −d plus a component across d."""
    law = friction_law()
    d = np.array([1.0, 0.0])
    c = -(law.M2 @ d) / norm_with(law.M2, d)
    law = Law(k_n=law.k_n, mode="sliding", M2=law.M2, M2inv=law.M2inv, slide_traction=c)
    pts, u = points(1, [[0.0, 0.0, -2e-4]])
    ev = evaluate(law, pts, u, 0.0, np.zeros(2))
    pn = ev.pn[0]
    R = np.radians(BETA)
    d_star = math.hypot(MU1 * math.cos(R) * d[0], MU2 * math.sin(R) * d[0])
    assert -ev.t[0] @ d == pytest.approx(pn * d_star)
    assert abs(ev.t[0, 1]) > 0.01 * pn  # β = 30°: not parallel to the slip (Eq. 38)
    assert norm_with(law.M2inv, ev.t[0]) == pytest.approx(pn)


@pytest.mark.parametrize("mode", ["friction", "sliding"])
def test_consistent_tangents_match_finite_differences(mode):
    rng = np.random.default_rng(0)
    n, m = 60, 40
    G = sp.csr_matrix(rng.normal(size=(3 * n, m)) * (rng.random((3 * n, m)) < 0.3))
    pts = Points(G=G, w=np.ones(n), xy=np.zeros((n, 2)), h=rng.random(n) * 1e-3,
                 inside=np.ones(n, bool))
    pts.t_old = rng.normal(size=(n, 2)) * 10
    pts.gt_old = rng.normal(size=(n, 2)) * 1e-4
    law = friction_law(mode="friction")
    if mode == "sliding":
        d = np.array([0.6, 0.8])
        c = -(law.M2 @ d) / norm_with(law.M2, d)
        law = Law(k_n=law.k_n, mode="sliding", M2=law.M2, M2inv=law.M2inv, slide_traction=c)
    u = rng.normal(size=m) * 1e-4
    delta, D = 5e-4, np.array([1e-5, -2e-5])
    ev = evaluate(law, pts, u, delta, D, cw=1e-7)
    assert len(set(ev.state.tolist())) >= 2
    eps = 1e-10

    def stack(e):
        return np.column_stack([e.t, e.pn])

    v = rng.normal(size=m)
    fd = (stack(evaluate(law, pts, u + eps * v, delta, D, cw=1e-7)) - stack(ev)) / eps
    an = np.einsum("nij,nj->ni", ev.T, (G @ v).reshape(3, -1).T)
    assert np.abs(fd - an).max() < 1e-5 * np.abs(an).max()
    fd = (stack(evaluate(law, pts, u, delta + eps, D, cw=1e-7)) - stack(ev)) / eps
    assert np.abs(fd - ev.Tdelta).max() < 1e-5 * np.abs(ev.Tdelta).max()
    for c in range(2):
        Dp = D.copy()
        Dp[c] += eps
        fd = (stack(evaluate(law, pts, u, delta, Dp, cw=1e-7)) - stack(ev)) / eps
        assert np.abs(fd - ev.TD[:, :, c]).max() <= 1e-5 * max(np.abs(ev.TD).max(), 1.0)


def test_wear_compliance_is_eq_19_21():
    """‖Δg‖_i (Eq. 21) = i_w(θ) ‖Δg‖ with θ the slip angle from e1 (Eq. 19)."""
    from types import SimpleNamespace

    case = SimpleNamespace(
        a=Body(E=1.0, nu=0.3, i1=1.33e-7, i2=2.66e-7),
        b=Body(E=1.0, nu=0.3, i1=0.5e-7, i2=0.25e-7),
        friction=Friction(mu1=0.25, mu2=0.5, beta=45.0),
    )
    dg = 2.0 * np.array([1.0, 0.0])  # slide 2 mm along +x: θ = −β
    ca, cb = wear_compliances(case, dg)
    th = math.radians(-45.0)
    assert ca == pytest.approx(2.0 * math.hypot(1.33e-7 * math.cos(th), 2.66e-7 * math.sin(th)))
    assert cb == pytest.approx(2.0 * math.hypot(0.5e-7 * math.cos(th), 0.25e-7 * math.sin(th)))


def test_implicit_wear_softens_the_penalty():
    """Backward-Euler wear: p_n = k/(1 + k c_w) ⟨−g⟩, so Δw = c_w p_n closes the gap."""
    law = Law(k_n=1e6)
    pts, u = points(1, [[0.0, 0.0, 0.0]])
    cw = 1e-5
    ev = evaluate(law, pts, u, 1e-3, np.zeros(2), cw=cw)
    pn = ev.pn[0]
    assert pn == pytest.approx(1e6 * 1e-3 / (1 + 1e6 * cw))
    # the gap after wear, h + w + Δw − δ + u_n, is the penalty penetration −p_n/k_n
    assert 0 + cw * pn - 1e-3 == pytest.approx(-pn / 1e6)


@pytest.mark.parametrize("pattern", ["symmetric", "row_without_column"])
def test_stiffened_solve_equals_the_dense_solve(pattern):
    """``_solve_stiffened`` (Woodbury on the DOFs of the contact tangent) equals a dense
    solve of (K + B) x = rhs, also when B has a nonzero row whose column is empty (a
    slip point couples its tangential traction to u_n but not p_n to u_t: with the
    nodal contact points of the dissimilar case 7 such rows occurred, and restricting to
    the columns alone gave a 3 % wrong Newton step)."""
    from fem_reference.contact.augmented import _solve_stiffened

    rng = np.random.default_rng(7)
    n = 40
    X = rng.standard_normal((n, n))
    K = X @ X.T + n * np.eye(n)
    C = np.linalg.inv(K)
    B = np.zeros((n, n))
    idx = rng.choice(n, 8, replace=False)
    B[np.ix_(idx, idx)] = rng.standard_normal((8, 8))
    if pattern == "row_without_column":
        B[idx[0], :] = 0.0
        B[:, idx[0]] = 0.0
        B[idx[0], idx[1:4]] = [3.0, -2.0, 1.5]  # row idx[0], its column stays empty
    rhs = rng.standard_normal((n, 2))
    x = _solve_stiffened(C, sp.csr_matrix(B), rhs)
    assert np.allclose(x, np.linalg.solve(K + B, rhs), rtol=0, atol=1e-12)


def test_stiffened_solver_updates_equal_fresh_solves():
    """The kept factors with Woodbury updates (:mod:`fem_reference.contact.stiffened`) solve a
    sequence of contact tangents like a dense solve of each, while points change state
    (a local change of B), come into contact (new DOFs) and leave it; a change of too
    high a rank refactorises."""
    from fem_reference.contact.stiffened import StiffenedSolver

    rng = np.random.default_rng(11)
    n = 200
    X = rng.standard_normal((n, n))
    K = X @ X.T + n * np.eye(n)
    C = np.linalg.inv(K)
    C = 0.5 * (C + C.T)
    act = rng.choice(n, 80, replace=False)
    B = np.zeros((n, n))
    B[np.ix_(act, act)] = 0.3 * rng.standard_normal((80, 80)) + 5.0 * np.eye(80)
    lin = StiffenedSolver(C)
    for it in range(10):
        rhs = rng.standard_normal((n, 2))
        x = lin.solve(sp.csr_matrix(B), rhs)
        ref = np.linalg.solve(K + B, rhs)
        assert np.abs(x - ref).max() < 1e-12 * np.abs(ref).max()
        assert np.allclose(lin.solve(sp.csr_matrix(B), rhs[:, 0]), ref[:, 0], rtol=0,
                           atol=1e-12 * np.abs(ref).max())
        k = rng.choice(act, 3, replace=False)  # points change state
        B[np.ix_(k, k)] += 0.5 * rng.standard_normal((3, 3))
        new = rng.choice(np.setdiff1d(np.arange(n), act), 2, replace=False)  # come in
        loc = np.concatenate([new, k[:2]])
        B[np.ix_(loc, loc)] += 0.2 * rng.standard_normal((4, 4)) + 5.0 * np.eye(4)
        act = np.concatenate([act, new])
        if it == 4:  # two DOFs leave the contact
            B[act[:2], :] = 0.0
            B[:, act[:2]] = 0.0
            act = act[2:]
    assert lin.factorisations < lin.updates
    B[np.ix_(act, act)] += 0.1 * rng.standard_normal((act.size, act.size))  # all change
    before = lin.factorisations
    rhs = rng.standard_normal(n)
    assert np.allclose(lin.solve(sp.csr_matrix(B), rhs), np.linalg.solve(K + B, rhs),
                       rtol=0, atol=1e-12)
    assert lin.factorisations == before + 1


def _block_compliance(xy: np.ndarray, coupling: float, rng) -> np.ndarray:
    """A block's condensed compliance on the points ``xy`` (G = identity): a smooth SPD
    kernel per component and a normal–tangential coupling of relative size ``coupling``."""
    n = len(xy)
    r = np.linalg.norm(xy[:, None] - xy[None], axis=-1)
    K = 1e-4 * (np.exp(-r / 0.3) + 0.05 * np.eye(n))
    Z = np.zeros((n, n))
    C = np.block([[0.8 * K, Z, Z], [Z, 0.8 * K, Z], [Z, Z, K]])
    S = rng.standard_normal((n, 2 * n)) * coupling * 1e-4 / n
    C[2 * n:, :2 * n] += S
    C[:2 * n, 2 * n:] += S.T
    return C


def _mirrored_blocks(rng) -> tuple:
    """(xy, G, w, C₁, C₁ mirrored z → −z) of a block on a 9 × 9 grid of points (G the
    identity, weights 0.01): two such blocks of one material are decoupled."""
    g = np.linspace(-0.4, 0.4, 9)
    xy = np.array([(x, y) for x in g for y in g])
    n = len(xy)
    Rz = np.r_[np.ones(2 * n), -np.ones(n)]
    C1 = _block_compliance(xy, 0.5, rng)
    return (xy, sp.identity(3 * n, format="csr"), np.full(n, 0.01), C1,
            Rz[:, None] * C1 * Rz[None, :])


def _same_newton_step(op, law, pts, ctrl) -> None:
    """The Newton increment of the state in ``pts`` under ``ctrl``, block by block and
    from the whole system (fresh LU factors both), equal to round-off."""
    import dataclasses

    from fem_reference.contact.alart_curnier import State, laws, problem
    from fem_reference.contact.kept_factors import KeptFactors
    from fem_reference.contact.newton_system import newton_step

    steps = []
    for decoupled in (True, False):
        p = problem(dataclasses.replace(op, decoupled=decoupled), law, pts, ctrl, 0.0, 1e-9)
        s = State(lam=np.vstack([pts.t_old.T, pts.lam_n[None, :]]), delta=ctrl.delta,
                  D=np.array(ctrl.D, dtype=float))
        steps.append(newton_step(p, s, laws(p, s), KeptFactors()))
    (dlam, dx), (dlam0, dx0) = steps
    assert np.abs(dlam - dlam0).max() <= 1e-9 * np.abs(dlam0).max()
    assert np.allclose(dx, dx0, rtol=1e-9, atol=1e-9 * np.abs(dx0).max())


def _block_and_whole(mu1, mu2, beta, approach, amplitude, angle) -> np.ndarray:
    """The semi-smooth solves of a fretting path on two identical mirrored blocks, block
    by block and as whole systems, asserted equal; returns the states (steps, n)."""
    import dataclasses

    from fem_reference.contact.compliance import NodalCompliance
    from fem_reference.contact.control import Control
    from fem_reference.contact.kept_factors import KeptFactors
    from fem_reference.contact.semismooth import semismooth

    rng = np.random.default_rng(3)
    xy, G, w, C1, mirrored = _mirrored_blocks(rng)
    n = len(xy)
    op = NodalCompliance.build(mirrored + C1, G, w)
    assert op.decoupled
    assert not NodalCompliance.build(mirrored + _block_compliance(xy, 0.3, rng), G,
                                     w).decoupled
    law = Law(k_n=1.0, mode="friction", k_t=1.0, M2=axes_tensor(mu1**2, mu2**2, beta),
              M2inv=axes_tensor(mu1**-2, mu2**-2, beta))
    e = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    runs = []
    for decoupled in (True, False):
        pts = Points(G=G, w=w, xy=xy, h=(xy**2).sum(axis=1) / 20.0,
                     inside=np.ones(n, bool))
        kept, out = KeptFactors(), []
        for s in (0.0, 0.5, 1.0, 0.0, -1.0, 0.0):
            shift = s * amplitude * e
            ctrl = Control(P=None, delta=approach, D=np.zeros(2), approach=approach,
                           compliance=1e-5, shift=tuple(shift), compliance_t=1e-5)
            if decoupled:  # one Newton increment from this state, both ways, exactly
                _same_newton_step(op, law, pts, ctrl)
            sol = semismooth(dataclasses.replace(op, decoupled=decoupled), law, pts, ctrl,
                             kept=kept)
            pts.gt_old = sol.ev.gt.copy()
            out.append((np.c_[pts.t_old, pts.lam_n], sol.ev.state, sol.delta, sol.D))
        runs.append(out)
        assert (kept.factorisations == 0) == decoupled  # the path taken
    # both solves stop at functions below tol = 1e-9 of the largest pressure: their
    # solutions agree to 10 tol
    for (lam, state, delta, D), (lam0, state0, delta0, D0) in zip(*runs, strict=True):
        np.testing.assert_array_equal(state, state0)
        assert np.abs(lam - lam0).max() <= 1e-8 * np.abs(lam0).max()
        assert delta == pytest.approx(delta0, rel=1e-8)
        assert np.allclose(D, D0, rtol=1e-8, atol=1e-8 * amplitude)
    return np.array([r[1] for r in runs[0]])


def test_the_block_triangular_newton_solve_is_the_whole_one():
    """Two identical blocks, one mirrored (z → −z), have a relative compliance whose
    normal–tangential blocks cancel exactly (Dundurs' β = 0): the semi-smooth Newton
    systems are then block triangular and solved block by block
    (:attr:`NodalCompliance.decoupled`).  Over a held approach and an orthotropic
    partial-slip fretting path (stick and slip nodes, the far-field unknowns δ and D)
    the block solve gives the whole system's solution to round-off; blocks of different
    materials keep their coupling and the whole system."""
    states = _block_and_whole(0.3, 0.6, 60.0, 1.5e-2, 2e-3, 63.4)
    assert ((states == STICK).any(axis=1) & (states == SLIP).any(axis=1)).sum() >= 3


@settings(max_examples=12, derandomize=True, deadline=None, database=None)
@given(mu1=st.floats(0.1, 0.8), mu2=st.floats(0.1, 0.8), beta=st.floats(0.0, 180.0),
       approach=st.floats(8e-3, 2e-2), amplitude=st.floats(2e-4, 3e-3),
       angle=st.floats(0.0, 360.0))
def test_the_block_triangular_solve_on_generated_paths(mu1, mu2, beta, approach, amplitude,
                                                       angle):
    """The same on generated friction ellipses, approaches, amplitudes and directions."""
    _block_and_whole(mu1, mu2, beta, approach, amplitude, angle)


@settings(max_examples=10, derandomize=True, deadline=None, database=None)
@given(mu1=st.floats(0.15, 0.8), mu2=st.floats(0.15, 0.8), beta=st.floats(0.0, 180.0),
       angle=st.floats(0.0, 360.0), wear=st.floats(0.2, 3.0), coupled=st.booleans())
def test_the_newton_step_is_the_derivative_of_the_functions(mu1, mu2, beta, angle, wear,
                                                           coupled):
    """The semi-smooth Newton increment Δ solves J Δ = −F with J the derivative of the
    Alart–Curnier functions (:mod:`fem_reference.contact.semismooth`) on the sets of the
    state: along it, by finite differences, dF/dt = −F (and likewise the control
    equations).  Checked from a converged partial-slip state taken to a new shift with
    a wear compliance c_w of the order of the nodal compliance (the corrector solves of
    :mod:`fem_reference.fretting`), so that stick, slip and wear terms all enter;
    identical (decoupled, block-triangular solve) and different materials."""
    from fem_reference.contact.alart_curnier import State, laws, problem
    from fem_reference.contact.compliance import NodalCompliance
    from fem_reference.contact.control import Control
    from fem_reference.contact.kept_factors import KeptFactors
    from fem_reference.contact.newton_system import newton_step
    from fem_reference.contact.semismooth import _update, semismooth

    rng = np.random.default_rng(5)
    xy, G, w, C1, mirrored = _mirrored_blocks(rng)
    n = len(xy)
    other = _block_compliance(xy, 0.3, rng) if coupled else C1
    op = NodalCompliance.build(mirrored + other, G, w, (xy**2).sum(axis=1))
    assert op.decoupled != coupled
    law = Law(k_n=1.0, mode="friction", k_t=1.0, M2=axes_tensor(mu1**2, mu2**2, beta),
              M2inv=axes_tensor(mu1**-2, mu2**-2, beta))
    e = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    pts = Points(G=G, w=w, xy=xy, h=(xy**2).sum(axis=1) / 20.0, inside=np.ones(n, bool))

    def control(shift: float) -> Control:
        return Control(P=None, delta=1.5e-2, D=np.zeros(2), approach=1.5e-2,
                       compliance=1e-5, shift=tuple(shift * e), compliance_t=1e-5)

    sol = semismooth(op, law, pts, control(1e-3))
    pts.gt_old = sol.ev.gt.copy()
    cw = wear * float(op.diagonal()[2].mean())  # [mm/MPa], the nodal compliance's size
    # the start of a step of the fretting path: the rigid shift moved, the tractions not
    # (the first step back that leaves both stick and slip nodes)
    for back in (3e-4, 1e-4, 6e-4, 2e-5):
        p = problem(op, law, pts, control(1e-3 - back), cw, 1e-9)
        s = State(lam=np.vstack([pts.t_old.T, pts.lam_n[None, :]]), delta=sol.delta,
                  D=np.array(sol.D, dtype=float) - back * e)
        L = laws(p, s)
        if L.stick.any() and L.slip.any():
            break
    assume(L.stick.any() and L.slip.any())
    dlam, dx = newton_step(p, s, L, KeptFactors())
    eps = 1e-7
    Lt = laws(p, _update(p, s, dlam, dx, eps))
    assert np.array_equal(Lt.active, L.active) and np.array_equal(Lt.stick, L.stick)
    # F is linear in the unknowns but for the slip projection: the difference quotient
    # is the derivative to O(eps |Δ|) relative
    scale = float(np.abs(L.F).max())
    assert np.abs((Lt.F - L.F) / eps + L.F).max() <= 1e-5 * scale
    # the controls are linear: their quotient is exact but for round-off of values of
    # the approach's size (1.5e-2 mm) over eps
    assert np.abs((Lt.Fe - L.Fe) / eps + L.Fe).max() <= 1e-6 * 1.5e-2


@settings(max_examples=10, derandomize=True, deadline=None, database=None)
@given(seed=st.integers(0, 2**31 - 1), coupled=st.booleans(), loaded=st.floats(0.0, 1.0))
def test_the_nodal_compliance_in_touch_order_is_the_dense_one(seed, coupled, loaded):
    """:class:`NodalCompliance` keeps ``HW = G C Gᵀ W`` with its nodes in touch order and
    reads only the loaded columns: its products, blocks, cross blocks and diagonal equal
    the dense matrix's in the nodes' own order (a random profile, tractions on a random
    subset of the nodes, coupled or decoupled materials), to round-off."""
    from fem_reference.contact.compliance import NodalCompliance

    rng = np.random.default_rng(seed)
    xy = rng.uniform(-0.5, 0.5, (30, 2))
    n = len(xy)
    G = sp.identity(3 * n, format="csr")
    if coupled:  # and points that mix the condensed DOFs
        G = G + sp.random(3 * n, 3 * n, density=0.05, random_state=rng, format="csr")
    w = rng.uniform(0.5, 2.0, n)
    Rz = np.r_[np.ones(2 * n), -np.ones(n)]
    C1 = _block_compliance(xy, 0.5, rng)
    C = Rz[:, None] * C1 * Rz[None, :] + (_block_compliance(xy, 0.3, rng) if coupled else C1)
    op = NodalCompliance.build(C, G, w, rng.uniform(0.0, 1.0, n))
    assert op.decoupled != coupled
    HW = (G @ C @ G.T.toarray()) * np.tile(w, 3)[None, :]
    lam = rng.standard_normal((3, n)) * (rng.uniform(0, 1, n) < loaded)
    scale = np.abs(HW).max() * np.abs(lam).sum()
    assert np.abs(op.apply(lam) - (HW @ lam.ravel()).reshape(3, n)).max() <= 1e-13 * scale
    cols = np.sort(rng.choice(3 * n, 40, replace=False))
    rows = rng.choice(3 * n, 17, replace=False)
    top = 1e-15 * np.abs(HW).max()  # G C Gᵀ summed in another order
    assert np.abs(op.cross(rows, cols) - HW[np.ix_(rows, cols)]).max() <= top
    assert np.abs(op.diagonal() - np.diag(HW).reshape(3, n)).max() <= top
    assert np.abs(op.block(cols) - HW[np.ix_(cols, cols)]).max() <= top
