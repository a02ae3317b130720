"""FEM reference with friction: Cattaneo–Mindlin partial slip and the sliding sphere.

References: Cattaneo–Mindlin (Johnson 1985 §7.2) stick radius c = a (1 − Q/μP)^(1/3) and
traction q(r) = μ p0 √(1 − r²/a²) − (c/a) μ p0 √(1 − r²/c²) (r < c); full sliding:
p_t = μ p_n against the slip, and for identical materials the pressure stays Hertzian;
Hamilton (1983): the σ_VM maximum of the sliding sphere lies below the surface for small
μ and jumps to the surface (trailing edge) above μ ≈ 0.3 (ν = 0.3).

Fast tier: half block, h = a0/4, L = H = 10 a0.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
from vv_testing import assert_converges, assert_surface_row_is_the_traction

from cases.loader import load_case
from cases.model import FemSettings, Friction
from cases.result import SLIP, STICK
from fem_reference import solve

pytestmark = pytest.mark.fem


@functools.cache
def cattaneo(h: float = 0.25, block: float = 10.0, penalty: float = 100.0):
    case = load_case("cattaneo_mindlin", quick=True)[1]  # Q/(μP) = 0.5
    case = case.with_changes(fem=FemSettings(block=block, depth=block, h=h, penalty=penalty))
    return case, solve(case, vtu=False)


@functools.cache
def sliding(mu: float, h: float = 0.25, block: float = 10.0):
    case = load_case("sliding_friction", quick=True, overrides={"friction.mu": mu})[0]
    case = case.with_changes(fem=FemSettings(block=block, depth=block, h=h))
    return case, solve(case, vtu=False)


#: the half-width of the band around Mindlin's stick edge c, in elements, where the
#: traction has a √(c − r) kink: the FEM's error there depends on where its nodes fall
#: against c and is not monotone in h on the grids from a0/4 to a0/8 (benchmarks/README.md,
#: "Cattaneo–Mindlin's stick edge on five grids"); it is bounded, not converged
CUSP_BAND = 2.0


def _check_cattaneo(case, res) -> tuple[float, float, float]:
    """(the stick radius' error / a0, the traction's largest error in the cusp band and
    its rms error away from it, both / μ p0) along the x line, against Mindlin's."""
    a0, p0 = case.hertz_scales
    mu, P, Q = case.friction.mu1, case.load.P, case.load.Qx
    assert Q / (mu * P) == pytest.approx(0.5)
    h = case.fem.h * a0
    sc = res.steps[0].scalars
    assert res.meta["model"] == "half"
    assert sc["P"] == pytest.approx(P, rel=1e-9) and sc["Qx"] == pytest.approx(Q, rel=1e-9)
    assert sc["Qy"] == 0.0
    c_ref = a0 * (1 - Q / (mu * P)) ** (1 / 3)
    c_area = math.sqrt(sc["stick_area"] / math.pi)
    line = res.tables["line_x/0"]
    stick = line["state"] == STICK
    c_line = 0.5 * (line["s"][stick].max() - line["s"][stick].min())
    assert abs(c_area - c_ref) < 2 * h
    assert abs(c_line - c_ref) < 2 * h
    # the slip annulus slips, the centre sticks
    st = res.steps[0].surface["state"]
    g = case.grid
    i0, j0 = np.argmin(np.abs(g.x)), np.argmin(np.abs(g.y))
    assert st[i0, j0] == STICK
    # tangential traction along x against Mindlin's, inside the contact
    s = line["s"]
    inside = np.abs(s) < 0.95 * a0
    q = mu * p0 * np.sqrt(np.clip(1 - (s / a0) ** 2, 0, None)) - (c_ref / a0) * mu * p0 * np.sqrt(
        np.clip(1 - (s / c_ref) ** 2, 0, None))
    err = np.abs(line["p_x"] - q) / (mu * p0)
    band = np.abs(np.abs(s) - c_ref) <= CUSP_BAND * h
    cusp = err[inside & band].max()
    away = float(np.sqrt(np.mean(err[inside & ~band] ** 2)))
    print(f"\nCattaneo-Mindlin Q/muP=0.5 h={case.fem.h}a0: stick radius (area) "
          f"{c_area / a0:.4f} a0, (x line) {c_line / a0:.4f} a0, Mindlin {c_ref / a0:.4f} a0; "
          f"|p_x - q|/(mu p0): max in the cusp band {cusp:.3f}, rms away from it {away:.4f}; "
          f"DOFs {res.meta['dofs']}, contact DOFs {res.meta['surface_dofs']}")
    return abs(c_area - c_ref) / a0, cusp, away


def test_cattaneo_mindlin_stick_radius():
    """The stick radius within two elements at h = a0/4 and a0/8 and converging to
    Mindlin's; the tangential traction converging to Mindlin's away from the stick edge
    (at least order 0.7: the penalty's error is O(h)) and bounded (0.2 μ p0) in the band
    of the √(c − r) kink, whose error is not monotone in h (:data:`CUSP_BAND`)."""
    hs = (0.25, 0.125)
    radius, cusp, away = zip(*(_check_cattaneo(*cattaneo(h)) for h in hs), strict=True)
    print(assert_converges(hs, radius, min_order=0.35, what="|c - c_Mindlin|/a0"))
    print(assert_converges(hs, away, min_order=0.7, finest=0.005,
                           what="rms |p_x - q|/(mu p0) away from the stick edge"))
    assert max(cusp) < 0.2


def test_sliding_low_friction_maximum_below_surface():
    case, res = sliding(0.15)
    a0, p0 = case.hertz_scales
    sc = res.steps[0].scalars
    mu, P = case.friction.mu1, case.load.P
    assert sc["Qx"] == pytest.approx(-mu * P, rel=1e-9)  # traction on the sliding pin
    assert abs(sc["p_max"] / p0 - 1) < 0.02  # identical materials: Hertzian pressure
    assert sc["vm_max_z"] > 0.2 * a0
    state = res.steps[0].surface["state"]
    assert set(np.unique(state).tolist()) <= {0, SLIP}


def test_sliding_high_friction_maximum_at_surface():
    case, res = sliding(0.5)
    a0, p0 = case.hertz_scales
    sc = res.steps[0].scalars
    assert sc["vm_max_z"] == 0.0
    # at the trailing side of body b (its traction is +x: tensile σ_xx at x < 0)
    assert -1.2 * a0 < sc["vm_max_x"] < 0
    xz = res.steps[0].planes["xz"]
    assert xz.fields["sxx"][:, 0].max() > 0 and xz.s[np.argmax(xz.fields["sxx"][:, 0])] < 0
    low = sliding(0.15)[1].steps[0].scalars
    assert sc["vm_max"] > low["vm_max"]
    print(f"\nsliding: mu=0.15 vm_max/p0={low['vm_max'] / p0:.4f} at "
          f"({low['vm_max_x'] / a0:.3f}, {low['vm_max_z'] / a0:.3f}) a0; mu=0.5 "
          f"{sc['vm_max'] / p0:.4f} at ({sc['vm_max_x'] / a0:.3f}, {sc['vm_max_z'] / a0:.3f}) a0")


def test_the_surface_row_carries_the_tractions():
    """Body b, sliding at μ = 0.5 (the σ_VM maximum on the surface): the planes' surface
    row is the boundary condition, the recovered tractions, not the surface elements'
    gradients (fem_reference.fields.planes); the half-space solver's kernels give its
    own surface row the same convention."""
    import halfspace

    case, res = sliding(0.5)
    assert case.stress.body == "b"
    assert_surface_row_is_the_traction(case, res)
    assert_surface_row_is_the_traction(case, halfspace.solve(case))


@pytest.mark.full
def test_cattaneo_mindlin_fine():
    case, res = cattaneo(h=0.125, block=20.0)
    _, cusp, away = _check_cattaneo(case, res)
    assert cusp < 0.15 and away < 0.005


def test_cattaneo_mindlin_shift_is_the_half_space_one():
    """Under Q = μP/2 the rigid shift of Mindlin's half-spaces is
    δ_t = δ* [1 − (1 − Q/μP)^(2/3)], δ* = 3μP(2 − ν)/(8 G a0) (Johnson 1985, §7.2, two
    identical bodies).  The blocks alone shift more (they also rock about their fixed
    bottoms): +3.6 % (L = 10 a0) and +1.6 % (20 a0) at h = a0/4, +1.7 % at the quick
    a0/8, 20 a0 and +0.8 % at a0/8, 40 a0.  With the far-field compliance of
    fem_reference/model/far_field.py the shift is the half-space's whatever the block
    (measured −0.03 / −0.15 % at a0/4; −0.05 and −0.04 % at a0/8, 20 and 40 a0): bound
    0.5 %, the two blocks within 0.3 % of each other (the blocks' own: 2.0 %)."""
    shifts = []
    for block in (10.0, 20.0):
        case, res = cattaneo(block=block)
        a0 = case.hertz_a0
        mu, P, Q = case.friction.mu1, case.load.P, case.load.Qx
        G, nu = case.a.E / (2 * (1 + case.a.nu)), case.a.nu
        d_ref = 3 * mu * P * (2 - nu) / (8 * G * a0) * (1 - (1 - Q / (mu * P)) ** (2 / 3))
        sc = res.steps[0].scalars
        own, hs = abs(sc["shift_block_x"]) / d_ref - 1, abs(sc["shift_x"]) / d_ref - 1
        print(f"\nL = {block} a0: shift/Mindlin - 1 blocks {own:+.4f}, half-space {hs:+.4f}")
        assert own > 0.01 and abs(hs) < 0.005
        shifts.append(abs(sc["shift_x"]) / d_ref)
    assert abs(shifts[1] - shifts[0]) < 0.003


def test_orthotropic_sliding_half_block_with_companion(monkeypatch):
    """β = 45°: p_t is not parallel to the slip (Eq. 38).  The contact problem is normal
    and symmetric about y = 0, so a half block solves it; the y traction, even in y, is
    carried by the antisymmetric companion (fem_reference.model.fem_model).  Against the full
    block (same h, its own mesh): σ_VM planes within 3.5 % (L2; measured 3.0 % / 2.6 %
    on xz / yz, the two meshes' difference: p_n 3.1 %), Q and the support reaction to
    1e-9.  Without the companion the yz plane misses by 15.5 %, with its sign flipped by
    26 %."""
    from fem_reference.model import fem_model, shape
    from reports.compare.metrics import compare_steps

    case = load_case("sliding_friction", quick=True)[0]
    case = case.with_changes(fem=FemSettings(block=10.0, depth=10.0, h=0.25),
                             friction=Friction(mu1=0.25, mu2=0.5, beta=45.0))
    res = solve(case, vtu=False)
    sc = res.steps[0].scalars
    assert res.meta["model"] == "half"
    P = case.load.P
    th = math.radians(45.0)
    d_star = math.hypot(0.25 * math.cos(th), 0.5 * math.sin(th))
    assert -sc["Qx"] == pytest.approx(P * d_star, rel=1e-9)
    assert abs(sc["Qy"]) > 0.05 * P
    assert sc["P_reaction"] == pytest.approx(P, rel=1e-9)
    monkeypatch.setattr(fem_model, "has_companion", lambda case: False)
    monkeypatch.setattr(shape, "has_companion", lambda case: False)
    full = solve(case, vtu=False)
    assert full.meta["model"] == "full"
    for key in ("Qx", "Qy", "P_reaction"):
        assert sc[key] == pytest.approx(full.steps[0].scalars[key], rel=1e-9)
    a0, p0 = case.hertz_scales
    rows = {(q, m): v for q, m, v in compare_steps(res.steps[0], full.steps[0], a0=a0,
                                                   p0=p0)}
    print(f"\nhalf + companion against the full block: {rows}")
    assert rows[("vm_xz", "l2")] < 0.035 and rows[("vm_yz", "l2")] < 0.035
    assert rows[("p_y", "l2")] < 0.035


def test_sweep_reuses_the_model_core(monkeypatch):
    """A sweep point reuses the previous point's mesh, factorisation and condensation,
    with the same numbers as a fresh model."""
    sliding(0.15)
    case, reused = sliding(0.5)
    assert reused.meta["timings"]["reused"]
    monkeypatch.setenv("CONTACT_VV_FEM_CACHE", "0")
    fresh = solve(case, vtu=False)
    assert not fresh.meta["timings"]["reused"]
    a, b = reused.steps[0].scalars, fresh.steps[0].scalars
    for key in ("P", "Qx", "p_max", "vm_max", "a_x", "approach", "contact_area"):
        assert b[key] == pytest.approx(a[key], rel=1e-9, abs=1e-15)


def _mindlin_errors(case, res):
    """(L2, max, banded max) errors of the FE p_x on the case grid against Mindlin's
    traction, in the metrics' normalisation (reports.registry.tolerances): L2 over the contact,
    max outside the band of one cell inside the contact edge, banded max also outside
    the stick band (one element on either side of the stick radius c, docs/formulation.md
    §2.7), all over max |q|."""
    a0, p0 = case.hertz_scales
    mu, P, Q = case.friction.mu1, case.load.P, case.load.Qx
    c = a0 * (1 - Q / (mu * P)) ** (1 / 3)
    g = case.grid
    X, Y = np.meshgrid(g.x, g.y, indexing="ij")
    r = np.hypot(X, Y)
    q = mu * p0 * (np.sqrt(np.clip(1 - (r / a0) ** 2, 0, None))
                   - (c / a0) * np.sqrt(np.clip(1 - (r / c) ** 2, 0, None)))
    e = res.steps[0].surface["p_x"] - q
    inside = r < a0
    band = r < a0 - max(g.dx, g.dy)
    off = band & (np.abs(r - c) > case.fem.h * a0)
    return (float(np.linalg.norm(e[inside]) / np.linalg.norm(q[inside])),
            float(np.abs(e[band]).max() / np.abs(q).max()),
            float(np.abs(e[off]).max() / np.abs(q).max()))


def test_cattaneo_mindlin_traction_converges_on_three_meshes():
    """Node-wise augmented contact: the tangential traction of Q/μP = 0.5 converges to
    Mindlin's on h = a0/4, a0/6, a0/8 (half block 10 a0) in L2 and in the max norm,
    with observed orders from the three meshes.  L2: order above 0.6 (the √(c − r)
    kink at the stick radius allows about 1).  Max norm: it decreases on every mesh, but
    its pairwise order depends on where the kink falls between the nodes (measured
    0.245 -> 0.193 -> 0.180, orders 0.58 and 0.25), so only the decrease is asserted.
    Off the stick band the max error is within 0.10 (issue 12's bound) on every mesh
    (measured 0.038, 0.026, 0.048: the rest of the discretisation, no order to read)."""
    hs = (0.25, 1 / 6, 0.125)
    errs = [_mindlin_errors(*cattaneo(h)) for h in hs]
    l2, mx, off = ([e[k] for e in errs] for k in range(3))
    print(assert_converges(hs, l2, min_order=0.6, what="p_x L2 error"))
    print(assert_converges(hs, mx, min_order=0.0, what="p_x max error"))
    print(f"p_x max error off the stick band: {off}")
    assert max(off) < 0.10


def test_a_frictional_contact_without_tangential_load_sticks():
    """Identical materials pressed with friction and no tangential load carry no
    tangential traction, so nothing slips: every closed point sticks, as in the
    half-space solver and the closed form (the FEM solves it frictionless, and labelled
    every closed point slip: stick area 0 against the contact area, a generated case's
    false alarm, issue 58 point 4)."""
    case = load_case("hertz", quick=True, overrides={"friction.mu": 0.5})[0]
    res = solve(case, vtu=False).steps[0]
    sc, state = res.scalars, res.surface["state"]
    assert sc["Qx"] == 0.0 and sc["Qy"] == 0.0
    assert not np.any(state == SLIP) and np.any(state == STICK)
    assert sc["stick_area"] == pytest.approx(sc["contact_area"], rel=0.02)
