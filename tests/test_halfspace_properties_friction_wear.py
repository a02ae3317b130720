"""Property-based tests (Hypothesis) of the friction law, its projection and the wear
evolution (issue 6, item 2).

Friction (Eq. 9-17): the projection P_E_rho of Eq. 17 is the radial scaling onto the
elliptic disc ||p||_mu <= rho; the slip traction of Eq. 13 is the associated
(maximum-dissipation) traction.  These are exact identities evaluated in a handful of
floating-point operations, so the tolerances are a few hundred ulps (1e-12 relative),
and "inside the ellipse" allows ||.||_mu <= rho (1 + 1e-12).  Coefficients sample
mu1 in [0.01, 2] with orthotropy mu2/mu1 in [1/50, 50] (issue 6 item 6), beta in
[-360, 360] degrees, tractions and slips over twelve decades.

Wear (Eq. 18-23, erratum 5): in a pin-on-disk run the wear depth of every cell never
decreases, and the worn volume grows per step by exactly sum_bodies i_w(theta) P ds
(the implicit scheme with the imposed slip; round-off only), while the per-cell
increment is Eq. 23's p_n ||g_t(k) - g_t(k-1)||_i up to the elastic part of the slip.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import halfspace
from cases.loader import load_case
from cases.model import Friction
from halfspace.friction import (
    from_axes,
    mu_dual_norm,
    mu_norm,
    project,
    slip_traction,
    to_axes,
    wear_coefficient,
    wear_norm,
)

RTOL = 1e-12  # a few hundred ulps: closed-form identities of a few flops
MANY = settings(max_examples=200, deadline=None)


# ---------------------------------------------------------------- strategies


@st.composite
def frictions(draw):
    """mu1 in [0.01, 2], mu2 = mu1 r with r in [1/50, 50], beta in [-360, 360] deg."""
    mu1 = draw(st.floats(0.01, 2.0))
    ratio = math.exp(draw(st.floats(-math.log(50.0), math.log(50.0))))
    beta = draw(st.floats(-360.0, 360.0))
    return Friction(mu1=mu1, mu2=mu1 * ratio, beta=beta)


magnitudes = st.floats(-6.0, 6.0).map(lambda e: 10.0**e)
angles = st.floats(-math.pi, math.pi)


@st.composite
def vectors(draw, nonzero: bool = False):
    """A 2D vector (x, y): magnitude 1e-6..1e6 at any angle, or exactly zero."""
    if not nonzero and draw(st.booleans()) and draw(st.booleans()):
        return 0.0, 0.0
    r, t = draw(magnitudes), draw(angles)
    return r * math.cos(t), r * math.sin(t)


# ---------------------------------------------------------------- Eq. 11, 9, 10


@MANY
@given(v=vectors(), beta=st.floats(-360.0, 360.0))
def test_axes_rotation_is_orthogonal(v, beta):
    """Eq. 11-12: to_axes is a rotation (norm preserving) and from_axes its inverse."""
    e1, e2 = to_axes(*v, beta)
    x, y = from_axes(e1, e2, beta)
    n = math.hypot(*v)
    assert abs(math.hypot(e1, e2) - n) <= RTOL * n
    assert abs(x - v[0]) <= RTOL * n and abs(y - v[1]) <= RTOL * n


@MANY
@given(fr=frictions(), g=vectors(nonzero=True))
def test_dual_norm_is_the_support_function(fr, g):
    """||g||*_mu (Eq. 10) is the dual of ||.||_mu (Eq. 9): the slip traction with
    p_n = 1 lies on the unit ellipse and realises max_{||q||_mu <= 1} (-q . g)."""
    px, py = slip_traction(*g, 1.0, fr)
    assert abs(mu_norm(px, py, fr) - 1.0) <= RTOL
    power = -(px * g[0] + py * g[1])
    assert abs(power - mu_dual_norm(*g, fr)) <= RTOL * mu_dual_norm(*g, fr)


# ---------------------------------------------------------------- projection, Eq. 17


@MANY
@given(fr=frictions(), p=vectors(), rho=st.one_of(st.just(0.0), magnitudes))
def test_projection_inside_ellipse(fr, p, rho):
    """P_E_rho(p) lies in the elliptic disc: ||P(p)||_mu <= rho (1 + 1e-12)."""
    qx, qy = project(*p, rho, fr)
    assert mu_norm(qx, qy, fr) <= rho * (1.0 + RTOL)


@MANY
@given(fr=frictions(), p=vectors(), rho=st.one_of(st.just(0.0), magnitudes))
def test_projection_idempotent(fr, p, rho):
    """P(P(p)) = P(p) (to round-off: a point on the boundary is rescaled by 1 +- ulps)."""
    q = project(*p, rho, fr)
    qq = project(*q, rho, fr)
    scale = math.hypot(*q)
    assert abs(qq[0] - q[0]) <= RTOL * scale and abs(qq[1] - q[1]) <= RTOL * scale


@MANY
@given(fr=frictions(), p=vectors(), t=st.floats(0.0, 1.0))
def test_projection_leaves_inside_points_unchanged(fr, p, t):
    """||p||_mu <= rho  =>  P(p) = p exactly (Eq. 17, first branch), including points
    on the boundary (rho = ||p||_mu)."""
    n = float(mu_norm(*p, fr))
    rho = n / t if t > 0 else n  # rho >= ||p||_mu; t = 1 puts p on the boundary
    assume(math.isfinite(rho))
    qx, qy = project(*p, rho, fr)
    assert (float(qx), float(qy)) == p


@MANY
@given(fr=frictions(), p=vectors(nonzero=True), rho=st.one_of(st.just(0.0), magnitudes))
def test_projection_is_radial(fr, p, rho):
    """P(p) = s p with 0 <= s <= 1 (Eq. 17 scales, never rotates): parallel to p,
    same sense, not longer; and on the ellipse (||P(p)||_mu = rho) when p is outside."""
    qx, qy = project(*p, rho, fr)
    n, m = math.hypot(*p), math.hypot(qx, qy)
    assert abs(p[0] * qy - p[1] * qx) <= RTOL * n * m
    assert p[0] * qx + p[1] * qy >= 0.0
    assert m <= n * (1.0 + RTOL)
    if mu_norm(*p, fr) > rho:
        assert abs(mu_norm(qx, qy, fr) - rho) <= RTOL * rho


# ---------------------------------------------------------------- associated rule, Eq. 13


@MANY
@given(fr=frictions(), g=vectors(nonzero=True), p_n=magnitudes)
def test_slip_traction_on_the_limit_and_dissipative(fr, g, p_n):
    """Eq. 13: p_t = -p_n M^2 g / ||g||*_mu lies on the friction limit ||p_t||_mu = p_n,
    and its power is non-negative and equals p_n ||g||*_mu (erratum 11):
    -p_t . g = p_n ||g||*_mu >= 0."""
    px, py = slip_traction(*g, p_n, fr)
    assert abs(mu_norm(px, py, fr) - p_n) <= RTOL * p_n
    power = -(px * g[0] + py * g[1])
    expected = p_n * mu_dual_norm(*g, fr)
    assert power >= 0.0
    assert abs(power - expected) <= RTOL * expected


@MANY
@given(fr=frictions(), g=vectors(nonzero=True), p_n=magnitudes,
       t=st.floats(0.0, 1.0), phi=angles)
def test_maximum_dissipation(fr, g, p_n, t, phi):
    """Associated rule = maximum dissipation: for every admissible q (||q||_mu <= p_n),
    -q . g <= -p_t . g with p_t the slip traction of Eq. 13."""
    # an arbitrary point of the elliptic disc, built in the tribological axes
    q1, q2 = p_n * t * fr.mu1 * math.cos(phi), p_n * t * fr.mu2 * math.sin(phi)
    qx, qy = from_axes(q1, q2, fr.beta)
    assert mu_norm(qx, qy, fr) <= p_n * (1.0 + RTOL)
    px, py = slip_traction(*g, p_n, fr)
    best = -(px * g[0] + py * g[1])
    assert -(qx * g[0] + qy * g[1]) <= best + RTOL * best


@MANY
@given(fr=frictions(), g=vectors(nonzero=True), p_n=magnitudes, c=magnitudes)
def test_slip_traction_depends_on_direction_only(fr, g, p_n, c):
    """Eq. 13 is positively homogeneous of degree 0 in the slip: p_t(c g) = p_t(g)."""
    a = slip_traction(*g, p_n, fr)
    b = slip_traction(c * g[0], c * g[1], p_n, fr)
    scale = math.hypot(*a)
    assert abs(a[0] - b[0]) <= RTOL * scale and abs(a[1] - b[1]) <= RTOL * scale


@MANY
@given(mu=st.floats(0.01, 2.0), beta=st.floats(-360.0, 360.0), g=vectors(nonzero=True),
       p_n=magnitudes)
def test_isotropic_slip_traction_is_coulomb(mu, beta, g, p_n):
    """mu1 = mu2 = mu: Eq. 13 reduces to Coulomb, p_t = -mu p_n g / |g|, whatever beta."""
    px, py = slip_traction(*g, p_n, Friction(mu, mu, beta))
    n = math.hypot(*g)
    ex, ey = -mu * p_n * g[0] / n, -mu * p_n * g[1] / n
    assert abs(px - ex) <= RTOL * mu * p_n and abs(py - ey) <= RTOL * mu * p_n


# ---------------------------------------------------------------- wear norm, Eq. 19-21


wear_coefficients = st.floats(-9.0, -5.0).map(lambda e: 10.0**e)


@MANY
@given(g=vectors(), i1=wear_coefficients, i2=wear_coefficients,
       beta=st.floats(-360.0, 360.0))
def test_wear_norm_is_iw_theta_times_slip(g, i1, i2, beta):
    """Eq. 20-21: ||g||_i = i_w(theta) ||g|| with theta the angle of g from e1 (Eq. 19);
    it is non-negative and vanishes only for g = 0."""
    w = float(wear_norm(*g, i1, i2, beta))
    n = math.hypot(*g)
    theta = math.degrees(math.atan2(g[1], g[0])) - beta
    assert w >= 0.0 and (w == 0.0) == (n == 0.0)
    assert abs(w - float(wear_coefficient(theta, i1, i2)) * n) <= RTOL * max(i1, i2) * n
    assert min(i1, i2) * n * (1 - RTOL) <= w <= max(i1, i2) * n * (1 + RTOL)


# ---------------------------------------------------------------- wear evolution


def pin_case(name: str, nx: int, step: float, n_steps: int, over: dict):
    overrides = {"grid.nx": nx, "grid.ny": nx, "sliding_wear.step": step,
                 "sliding_wear.distance": step * n_steps,
                 "sliding_wear.output_s": [step * k for k in range(1, n_steps + 1)],
                 "stress.nz": 2, **over}
    return load_case(name, overrides=overrides)[0]


@st.composite
def pin_runs(draw):
    """Pin-on-disk variants: isotropic or orthotropic case, friction, sliding angle,
    identical or dissimilar disk, one or both bodies wearing; 5 or 8 steps."""
    name = draw(st.sampled_from(("pin_on_disk", "pin_on_disk_orthotropic")))
    over: dict = {"load.slide_angle": draw(st.sampled_from((0.0, 30.0, 90.0, -135.0)))}
    if name == "pin_on_disk":
        over["friction.mu"] = draw(st.sampled_from((0.0, 0.3)))
    else:
        over["friction.beta"] = draw(st.sampled_from((0.0, 45.0, -60.0)))
    if draw(st.booleans()):
        over["materials.b.E"] = 70000.0
        over["materials.b.nu"] = 0.33
    if draw(st.booleans()):
        over["materials.b.i1"] = 0.5e-7
        over["materials.b.i2"] = 1.5e-7
    nx = draw(st.sampled_from((17, 21)))
    step = draw(st.sampled_from((2.0, 5.0)))
    n_steps = draw(st.sampled_from((5, 8)))
    return pin_case(name, nx, step, n_steps, over)


def step_increment(case):
    """The imposed slip ds of one step and the wear norms ||ds||_i of a and b."""
    t = math.radians(case.load.slide_angle)
    ds = case.sliding_wear.step * np.array([math.cos(t), math.sin(t)])
    beta = case.friction.beta
    k_a = float(wear_norm(*ds, case.a.i1, case.a.i2, beta))
    k_b = float(wear_norm(*ds, case.b.i1, case.b.i2, beta))
    return ds, k_a, k_b


@settings(max_examples=6, deadline=None)
@given(case=pin_runs())
def test_pin_on_disk_wear_monotone_and_archard(case):
    """Pin-on-disk, every step written out:

    - monotone: w(k) >= w(k-1) at every cell, for each body (Eq. 23 adds
      p_n ||dg||_i >= 0), and the history's w_max and worn volume never decrease;
    - worn volume: V(k) - V(k-1) = (||ds||_i,a + ||ds||_i,b) P(k) (Archard, exact for the
      implicit scheme), and V(n) = sum over steps of i_w P ds, to round-off (1e-10);
    - per cell, Eq. 23: w(k) - w(k-1) = p_n(k) ||g_t(k) - g_t(k-1)||_i with the step's
      slip, up to |p_n| i_max ||slip - ds|| (the scheme uses the imposed slip ds; the
      elastic part of the slip is < 1e-3 ds in gross sliding).
    """
    run = halfspace.solve(case)
    ds, k_a, k_b = step_increment(case)
    hist = run.tables["history"]
    n = len(hist["s"]) - 1
    assert len(run.steps) == n + 1  # step 0 (unworn) and every sliding step
    P, V = hist["P"], hist["wear_volume"]
    np.testing.assert_allclose(P, case.load.P, rtol=1e-8)
    assert np.all(np.diff(hist["w_max"]) >= 0) and np.all(np.diff(V) >= 0)
    dV = np.diff(V)
    np.testing.assert_allclose(dV, (k_a + k_b) * P[1:], rtol=0, atol=1e-10 * V[-1])
    assert abs(V[-1] - (k_a + k_b) * P[1:].sum()) <= 1e-10 * V[-1]
    assert V[-1] > 0
    i_max = {"a": max(case.a.i1, case.a.i2), "b": max(case.b.i1, case.b.i2)}
    for prev, cur in zip(run.steps[:-1], run.steps[1:], strict=True):
        sp, sc = prev.surface, cur.surface
        p_n, gx, gy = sc["p_n"], sc["slip_x"], sc["slip_y"]
        contact = p_n > 0
        elastic = np.hypot(gx - ds[0], gy - ds[1])
        assert elastic[contact].max() < 1e-3 * case.sliding_wear.step
        for body, props in (("a", case.a), ("b", case.b)):
            w0, w1 = sp[f"wear_{body}"], sc[f"wear_{body}"]
            assert np.all(w1 >= w0), f"wear of body {body} decreased"
            eq23 = p_n * wear_norm(gx, gy, props.i1, props.i2, case.friction.beta)
            bound = p_n * i_max[body] * elastic + 1e-12 * max(w1.max(), 1e-300)
            assert np.all(np.abs((w1 - w0) - eq23) <= bound), f"Eq. 23, body {body}"
        assert np.all(sc["wear_a"] + sc["wear_b"] >= sp["wear_a"] + sp["wear_b"])


# ---------------------------------------------------- Euclidean projection (FISTA)


@MANY
@given(y=vectors(), a=magnitudes, ratio=st.floats(-math.log10(50), math.log10(50)),
       t0=st.floats(0.0, 1e6))
def test_euclidean_ellipse_projection_is_the_nearest_point(y, a, ratio, t0):
    """halfspace.tangential._ellipse (the projection of the accelerated solver): inside
    points unchanged; outside points land on the ellipse with y - v along its normal
    (the KKT conditions of min |v - y|), and any warm start of the secular root gives
    the same point (to 1e-9 relative: Newton's last step is below 1e-15 of the root).
    Semi-axes b/a in [1/50, 50], the orthotropy range of the friction tests."""
    from halfspace.tangential import _ellipse

    ab = (a, a * 10.0**ratio)
    a, b = (np.array([v]) for v in ab)
    y1, y2 = np.array([y[0]]), np.array([y[1]])
    v1, v2, t = _ellipse(y1, y2, a, b)
    w1, w2, _ = _ellipse(y1, y2, a, b, np.array([t0]))
    level = (y[0] / ab[0]) ** 2 + (y[1] / ab[1]) ** 2
    scale = math.hypot(*y)
    if level <= 1 - 1e-12:  # clearly inside (on the boundary either branch is right)
        assert (v1[0], v2[0]) == y
        return
    if level <= 1:
        assert math.hypot(v1[0] - y[0], v2[0] - y[1]) <= 1e-11 * scale
        return
    assert abs((v1[0] / ab[0]) ** 2 + (v2[0] / ab[1]) ** 2 - 1) < 1e-9
    # y - v = t (v1 / a^2, v2 / b^2): the residual of that identity relative to |y|
    r1, r2 = y[0] - v1[0] - t[0] * v1[0] / ab[0] ** 2, y[1] - v2[0] - t[0] * v2[0] / ab[1] ** 2
    assert math.hypot(r1, r2) <= 1e-9 * scale
    assert math.hypot(w1[0] - v1[0], w2[0] - v2[0]) <= 1e-9 * scale
