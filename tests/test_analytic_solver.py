"""The "analytic" solver: common result of the Hertz, sliding, Cattaneo–Mindlin and wear cases."""

import math

import numpy as np
import pytest

from analytic import hertz as hz
from analytic import mindlin as md
from analytic import sliding as sl
from analytic.solver import ASYMPTOTIC_FROM, has_solution, sliding_traction_vector, solve
from cases import load_case
from cases.model import Body, CaseError, Friction, Load, SlidingWear
from cases.result import OPEN, SLIP, STICK, SUMMARY_COLUMNS


def lattice_bound(h_over_a: float) -> float:
    """Bound on |Σ p(x_ij) h² / P - 1| for the Hertz pressure sampled at cell centres.

    The Fourier transform of √(1 - r²)₊ decays like |k|⁻², so by Poisson summation the
    relative error of the lattice sum is O((h/a)² ln(a/h)); measured over 40 random grid
    offsets for h/a in [1/64, 1/2] it never exceeded 0.25 (h/a)^(3/2), the bound used here.
    """
    return 0.25 * h_over_a**1.5


@pytest.fixture(scope="module")
def hertz_quick():
    case = load_case("hertz", quick=True)[0]
    return case, solve(case)


def test_hertz_scalars(hertz_quick):
    case, res = hertz_quick
    assert res.solver == "analytic" and len(res.steps) == 1
    s = res.steps[0].scalars
    h = hz.hertz(case.load.P, case.R, case.E_star)
    assert s["P"] == case.load.P and s["step"] == 0
    assert s["p_max"] == pytest.approx(1.5 * case.load.P / (math.pi * h.a**2), rel=1e-14)
    assert s["contact_area"] == pytest.approx(math.pi * case.hertz_a0**2, rel=1e-14)
    assert s["a_x"] == s["a_y"] == pytest.approx(case.hertz_a0, rel=1e-14)
    assert s["stick_area"] == 0.0 and s["converged"] is True and s["iterations"] == 0
    assert set(SUMMARY_COLUMNS) - {"case", "solver", "param"} <= set(s)


def test_hertz_planes_against_the_axis_closed_form(hertz_quick):
    case, res = hertz_quick
    step = res.steps[0]
    h = hz.hertz(case.load.P, case.R, case.E_star)
    z = case.stress.z
    axis = hz.axis_von_mises(z, h.a, h.p0, case.b.nu)
    k = int(np.argmax(axis))
    s = step.scalars
    # the sampled maximum is the on-axis value at the best depth layer (x = 0 is a cell
    # centre of the odd grid): exact up to rounding
    assert s["vm_max"] == pytest.approx(axis[k], rel=1e-12)
    assert (s["vm_max_x"], s["vm_max_y"], s["vm_max_z"]) == (0.0, 0.0, z[k])
    # and within the sampling error of the continuous maximum 0.620 p0 at 0.481 a:
    # the maximum lies within Δz/2 of a layer, so the sampled value is at least the closed
    # form at z* ± Δz/2
    vm, zs = hz.axis_vm_max(case.b.nu)
    dz = z[1] - z[0]
    lower = min(hz.axis_von_mises(zs * h.a + d, h.a, h.p0, case.b.nu) for d in (-dz / 2, dz / 2))
    assert lower <= s["vm_max"] <= vm * h.p0
    assert abs(s["vm_max_z"] - zs * h.a) <= dz / 2
    # both planes carry the same axisymmetric field
    np.testing.assert_allclose(step.planes["xz"].fields["vm"], step.planes["yz"].fields["vm"],
                               rtol=1e-12, atol=1e-9 * h.p0)


def test_hertz_surface_is_consistent_with_the_planes(hertz_quick):
    case, res = hertz_quick
    step = res.steps[0]
    j0 = int(np.argmin(np.abs(case.grid.y - case.stress.y0)))
    # z = 0: σ_zz = -p_n (traction boundary condition), also outside the contact
    np.testing.assert_allclose(step.planes["xz"].fields["szz"][:, 0], -step.surface["p_n"][:, j0],
                               atol=1e-9 * step.scalars["p_max"])
    assert np.all(step.surface["gap"][step.surface["p_n"] > 0] == 0.0)
    assert np.all(step.surface["gap"][step.surface["p_n"] == 0] >= 0.0)
    assert set(np.unique(step.surface["state"])) == {OPEN, SLIP}  # frictionless: slip


@pytest.mark.parametrize("n", [41, 81])
def test_sampled_pressure_carries_the_load(n):
    case = load_case("hertz", quick=True, overrides={"grid.nx": n, "grid.ny": n,
                                                      "stress.nz": 2})[0]
    step = solve(case).steps[0]
    g = case.grid
    total = step.surface["p_n"].sum() * g.dx * g.dy
    bound = lattice_bound(g.dx / case.hertz_a0)
    assert abs(total / case.load.P - 1) <= bound  # 3.4 % (41 cells), 1.2 % (81 cells)


def test_sliding_body_conventions():
    # μ = 0.5, a slides in +x over b: traction on a is -μp, on b +μp along x
    base = load_case("sliding_friction", quick=True)[1]
    assert base.param == "mu=0.5"
    case_b = base.with_changes(stress=base.stress.__class__(**{**base.stress.__dict__, "nz": 11}))
    case_a = case_b.with_changes(stress=case_b.stress.__class__(
        **{**case_b.stress.__dict__, "body": "a"}))
    rb, ra = solve(case_b).steps[0], solve(case_a).steps[0]
    P, mu = base.load.P, 0.5
    assert rb.scalars["Qx"] == pytest.approx(-mu * P) and rb.scalars["Qy"] == 0.0
    g = base.grid
    assert rb.surface["p_x"].sum() * g.dx * g.dy == pytest.approx(
        -mu * P, rel=lattice_bound(g.dx / base.hertz_a0))
    np.testing.assert_allclose(rb.surface["p_x"], -mu * rb.surface["p_n"], atol=0)
    assert np.all(rb.surface["state"][rb.surface["p_n"] > 0] == SLIP)
    assert rb.scalars["stick_area"] == 0.0
    j0 = int(np.argmin(np.abs(g.y)))
    # z = 0 traction conditions: body a σ_xz = -p_x; body b (depth axis -z) σ_xζ = +p_x
    p_x = rb.surface["p_x"][:, j0]
    np.testing.assert_allclose(ra.planes["xz"].fields["sxz"][:, 0], -p_x, atol=1e-9)
    np.testing.assert_allclose(rb.planes["xz"].fields["sxz"][:, 0], p_x, atol=1e-9)
    # the two bodies are mirror images in x: σ_VM_a(x) = σ_VM_b(-x) (symmetric grid)
    for name in ("xz", "yz"):
        vb, va = rb.planes[name].fields["vm"], ra.planes[name].fields["vm"]
        if name == "xz":
            va = va[::-1]
        np.testing.assert_allclose(va, vb, rtol=1e-9, atol=1e-9)
    # b's trailing edge is x < 0 (the traction on b is +x): tensile σ_xx there, and the
    # sampled surface maximum of σ_VM lies on that side, below the closed-form cusp value
    sxx = rb.planes["xz"].fields["sxx"][:, 0]
    x = rb.planes["xz"].s
    edge = np.argmin(np.abs(x + base.hertz_a0))
    assert sxx[edge] > 0 and sxx[len(x) - 1 - edge] < sxx[edge]
    h = hz.hertz(P, base.R, base.E_star)
    assert rb.scalars["vm_max_x"] < 0 and rb.scalars["vm_max_z"] == 0.0
    assert rb.scalars["vm_max"] <= sl.trailing_edge_von_mises(mu, base.b.nu) * h.p0


def test_cattaneo_mindlin_fields():
    case = load_case("cattaneo_mindlin", quick=True, overrides={"stress.nz": 4})[1]
    step = solve(case).steps[0]
    s, g = step.scalars, case.grid
    h = hz.hertz(case.load.P, case.R, case.E_star)
    mu, Q = case.friction.mu1, case.load.Qx
    c = md.stick_radius(h.a, Q, mu, case.load.P)
    assert s["stick_area"] == pytest.approx(math.pi * c * c, rel=1e-14)
    X, Y = np.meshgrid(g.x, g.y, indexing="ij")
    r = np.hypot(X, Y)
    state = step.surface["state"]
    assert np.all(state[r < c] == STICK) and np.all(state[(r >= c) & (r < h.a)] == SLIP)
    assert np.all(state[r >= h.a] == OPEN)
    # traction on a along +Q, on the slip limit in the annulus
    np.testing.assert_allclose(step.surface["p_x"], md.traction(r, h.a, c, mu, h.p0),
                               atol=1e-12 * h.p0)
    ann = (r >= c) & (r < h.a)
    np.testing.assert_allclose(step.surface["p_x"][ann], mu * step.surface["p_n"][ann],
                               rtol=1e-12)
    # a moves against the traction it feels: shift_x = -δ_t(Q) of two identical bodies
    dstar = 3 * mu * case.load.P * (2 - case.a.nu) / (8 * case.a.G * h.a)
    assert s["shift_x"] == pytest.approx(-md.shift_from_load(Q, mu, case.load.P, dstar),
                                         rel=1e-13)
    assert s["Qx"] == pytest.approx(Q, rel=1e-14)
    # body b at z = 0: σ_xζ = +p_x(a), σ_ζζ = -p_n
    j0 = int(np.argmin(np.abs(g.y)))
    f = step.planes["xz"].fields
    np.testing.assert_allclose(f["sxz"][:, 0], step.surface["p_x"][:, j0], atol=1e-9 * h.p0)
    np.testing.assert_allclose(f["szz"][:, 0], -step.surface["p_n"][:, j0], atol=1e-9 * h.p0)


def _wear_case(beta=0.0, i1=1.33e-7, i2=1.33e-7):
    base = load_case("hertz", quick=True)[0]
    return base.with_changes(
        kind="sliding_wear",
        a=Body(E=base.a.E, nu=base.a.nu, i1=i1, i2=i2),
        friction=Friction(mu1=0.25, mu2=0.5, beta=beta),
        load=Load(P=base.load.P, sliding=True),
        sliding_wear=SlidingWear(step=1.0, distance=640.0,
                                 output_s=(1.0, 20.0, 40.0, 80.0, 160.0)))


def test_sliding_wear_scalars():
    case = _wear_case()
    res = solve(case)
    steps = {st.scalars["step"]: st.scalars for st in res.steps}
    assert sorted(steps) == [0, 1, 20, 40, 80, 160, 640]
    P, R, i_w = case.load.P, case.R, 1.33e-7
    s_valid = ASYMPTOTIC_FROM * steps[0]["s_transition"]
    for n, s in steps.items():
        assert s["s"] == n * 1.0
        # Archard: the worn volume is exact at every s
        assert s["wear_volume"] == pytest.approx(i_w * P * n, rel=1e-14, abs=0)
        if 0 < n < s_valid:  # Argatov's asymptotic quantities: no reference yet
            assert math.isnan(s["w_max"]) and math.isnan(s["p_max"]) and math.isnan(s["a_x"])
            continue
        # the depth is the paraboloid cap of the worn volume
        assert s["w_max"] == pytest.approx(math.sqrt(i_w * P * n / (math.pi * R)), rel=1e-12)
        assert s["contact_area"] == pytest.approx(math.pi * s["a_x"] ** 2, rel=1e-14)
    assert s_valid == pytest.approx(230.0, rel=0.05)  # 10 s_c, s_c about 23 mm here
    assert steps[0]["p_max"] == pytest.approx(hz.hertz(P, R, case.E_star).p0, rel=1e-14)
    a = steps[640]["a_x"]
    assert steps[640]["p_max"] == pytest.approx(P / (math.pi * a * a), rel=1e-14)
    assert steps[640]["w_max_hegadekatte"] == pytest.approx(steps[640]["w_max"], rel=2e-5)
    # s = 0 is the sphere sliding on the plane, before any wear: Hertz's pressure and the
    # full-sliding traction (Eq. 13), with stresses; the worn steps carry scalars only
    first = res.steps[0]
    assert first.surface["p_n"].max() == pytest.approx(steps[0]["p_max"], rel=0.05)
    t = sliding_traction_vector(case)
    assert (steps[0]["Qx"], steps[0]["Qy"]) == pytest.approx((P * t[0], P * t[1]), rel=1e-12)
    assert set(first.planes) == {"xz", "yz"}
    assert all(st.surface == {} and st.planes == {} for st in res.steps[1:])


def test_orthotropic_wear_and_sliding_traction():
    i1, i2 = 1.33e-7, 2.66e-7
    res = solve(_wear_case(beta=45.0, i1=i1, i2=i2))
    s = res.steps[-1].scalars
    assert s["i_w"] == pytest.approx(math.sqrt((i1**2 + i2**2) / 2), rel=1e-14)
    # traction of Eq. 13 along +x with β = 45°: on the friction ellipse, dissipative
    # (t·d = -‖d‖*_μ) and with a y component (not parallel to the slip)
    case = _wear_case(beta=45.0)
    t = sliding_traction_vector(case)
    b = math.radians(45.0)
    te = np.array([[math.cos(b), math.sin(b)], [-math.sin(b), math.cos(b)]]) @ t
    assert math.hypot(te[0] / 0.25, te[1] / 0.5) == pytest.approx(1.0, rel=1e-14)
    de = np.array([math.cos(b), -math.sin(b)])
    assert t[0] == pytest.approx(-math.hypot(0.25 * de[0], 0.5 * de[1]), rel=1e-14)
    assert t[1] > 0.0
    assert s["Qx"] == pytest.approx(case.load.P * t[0]) and s["Qy"] > 0


def test_applicability_and_errors():
    hertz = load_case("hertz", quick=True)[0]
    cm = load_case("cattaneo_mindlin", quick=True)[0]
    assert has_solution(hertz) and has_solution(cm)
    fretting = cm.with_changes(kind="fretting")
    assert not has_solution(fretting)
    with pytest.raises(CaseError, match="no analytic solution.*fretting"):
        solve(fretting)
    soft = Body(E=70000.0, nu=0.33)
    assert not has_solution(cm.with_changes(b=soft))  # friction + dissimilar
    assert has_solution(hertz.with_changes(b=soft))  # frictionless Hertz is still exact
    ortho = cm.with_changes(friction=Friction(mu1=0.3, mu2=0.5))
    assert not has_solution(ortho)
    too_much = cm.with_changes(load=Load(P=cm.load.P, Qx=0.31 * cm.load.P))
    with pytest.raises(CaseError, match="mu P"):
        solve(too_much)
    # dissimilar frictionless: Hertz with the composite E*
    res = solve(hertz.with_changes(b=soft, stress=hertz.stress.__class__(nz=2)))
    E_star = 1 / ((1 - 0.09) / 210000.0 + (1 - 0.33**2) / 70000.0)
    assert res.steps[0].scalars["a_x"] == pytest.approx(
        (3 * hertz.load.P * hertz.R / (4 * E_star)) ** (1 / 3), rel=1e-14)


@pytest.mark.parametrize("body", ["a", "b"])
def test_body_frames_by_reflection(body):
    # Independent derivation of the body-b convention: isotropic elasticity is invariant
    # under the reflection z -> -z, so body b's stresses on the axes (x, y, depth) are the
    # half-space field at (x, y, depth) under the traction (-p_x, -p_y, p_n); body a's are
    # the field under (p_x, p_y, p_n).  The solver instead rotates by π about x; both must
    # agree.  Orthotropic sliding at β = 45° gives p_x, p_y != 0.
    from analytic.quadrature import hertzian_traction_stresses

    base = load_case("sliding_friction", quick=True)[0]
    st = base.stress.__class__(body=body, depth=0.2, nz=3, x0=0.0, y0=0.0)
    case = base.with_changes(friction=Friction(mu1=0.25, mu2=0.5, beta=45.0), stress=st)
    step = solve(case).steps[0]
    h = hz.hertz(case.load.P, case.R, case.E_star)
    t = sliding_traction_vector(case)
    sign = 1.0 if body == "a" else -1.0
    for name, plane in step.planes.items():
        S, Z = np.meshgrid(plane.s, plane.z, indexing="ij")
        X, Y = (S, 0 * S) if name == "xz" else (0 * S, S)
        want = hertzian_traction_stresses(X, Y, Z, h.a, p0=h.p0, qx0=sign * t[0] * h.p0,
                                          qy0=sign * t[1] * h.p0, nu=0.3)
        for c, v in want.items():
            np.testing.assert_allclose(plane.fields[c], v, atol=1e-6 * h.p0, err_msg=c)
        assert np.abs(want["syz"]).max() > 0.01 * h.p0  # the y traction shows
