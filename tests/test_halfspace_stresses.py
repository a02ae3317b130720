"""Subsurface stresses of the half-space solver against Hertz and the sliding sphere."""

import numpy as np
import pytest
from vv_testing import assert_converges

import halfspace
from analytic.hertz import axis_vm_max
from analytic.sliding import sliding_sphere_stresses, vm_max_sweep
from cases import load_case
from cases.model import Grid
from cases.result import STRESS_COMPONENTS, von_mises
from halfspace.stresses import StressEvaluator


def test_hertz_axis_von_mises_81(hertz_case, hertz_scales):
    """Acceptance: on-axis max sigma_VM/p0 within 1% of the closed form, depth within
    0.02 a0 (81^2 cells, 61 layers of 0.034 a0)."""
    case = hertz_case
    res = halfspace.solve(case).steps[0]
    a0, p0 = hertz_scales
    plane = res.planes["xz"]
    axis = int(np.argmin(np.abs(plane.s)))
    vm_axis = plane.fields["vm"][axis]
    k = int(np.argmax(vm_axis))
    ref_value, ref_depth = axis_vm_max(case.b.nu)
    assert abs(vm_axis[k] / p0 / ref_value - 1) < 0.01
    assert abs(plane.z[k] / a0 - ref_depth) < 0.02
    # the plane maximum is the axis maximum, and both planes agree (axisymmetry)
    assert res.scalars["vm_max"] == pytest.approx(vm_axis[k], rel=1e-12)
    yz = res.planes["yz"].fields["vm"]
    assert np.abs(yz - plane.fields["vm"]).max() < 1e-9 * p0
    # surface on the axis: sigma_zz = -p0, sigma_xx = -(1 + 2 nu)/2 p0 (Johnson 3.41)
    assert plane.fields["szz"][axis, 0] / p0 == pytest.approx(-1.0, abs=0.002)
    assert plane.fields["sxx"][axis, 0] / p0 == pytest.approx(-0.8, abs=0.002)


@pytest.fixture(scope="module")
def sliding_runs():
    ref = {round(float(r.mu), 2): r for r in vm_max_sweep([0.0, 0.15, 0.25, 0.5, 0.65], 0.3)}
    cases = [c for c in load_case("sliding_friction") if round(c.friction.mu1, 2) in ref]
    return [(c, halfspace.solve(c).steps[0], ref[round(c.friction.mu1, 2)]) for c in cases]


def test_sliding_subsurface_maximum(sliding_runs):
    """mu <= 0.25: the maximum lies below the surface; value within 1% of quadrature of
    the point-force solutions over the analytic tractions, location within one cell."""
    checked = 0
    for case, res, ref in sliding_runs:
        if ref.z == 0:
            continue
        a0, p0 = case.hertz_scales
        s = res.scalars
        assert abs(s["vm_max"] / p0 / ref.value - 1) < 0.01, case.param
        assert abs(s["vm_max_x"] - ref.x * a0) <= case.grid.dx, case.param
        dz = case.stress.depth / (case.stress.nz - 1)
        assert abs(s["vm_max_z"] - ref.z * a0) <= dz, case.param
        checked += 1
    assert checked == 3


def test_sliding_surface_maximum_on_the_grid(sliding_runs):
    """mu >= 0.5: the maximum is at the surface behind the centre.  The continuous
    maximum is a cusp exactly at the trailing edge x = -a, between cell centres, which a
    cell-centred grid cannot sample: compare with the reference sampled at the same
    points (value within 1%, location within one cell).  The gap to the cusp itself is
    measured, not hidden: 4.7% at mu = 0.5 and 1.9% at mu = 0.65 on this grid."""
    checked = 0
    for case, res, ref in sliding_runs:
        if ref.z != 0:
            continue
        a0, p0 = case.hertz_scales
        plane = res.planes["xz"]
        near = np.abs(plane.s) < 1.5 * a0
        x = plane.s[near]
        sig = sliding_sphere_stresses(x, np.zeros_like(x), np.zeros_like(x), a0, p0,
                                      case.friction.mu1, case.b.nu)
        vm_ref = von_mises(*(sig[c] for c in STRESS_COMPONENTS))
        i = int(np.argmax(vm_ref))
        s = res.scalars
        assert s["vm_max_z"] == 0.0, case.param
        assert abs(s["vm_max"] / vm_ref[i] - 1) < 0.01, case.param
        assert abs(s["vm_max_x"] - x[i]) <= case.grid.dx * (1 + 1e-9), case.param
        cusp_gap = 1 - s["vm_max"] / p0 / ref.value
        print(f"{case.param}: grid maximum {cusp_gap:.1%} below the trailing-edge cusp")
        assert 0 < cusp_gap < 0.06
        checked += 1
    assert checked == 2


def test_stress_block_matches_planes():
    """The 3D block (2D FFT per layer) equals the planes (1D FFT per row) where they meet,
    for an asymmetric traction, for both bodies."""
    grid = Grid(0.5, 0.4, 21, 17)
    rng = np.random.default_rng(3)
    p = [rng.random((21, 17)) for _ in range(3)]
    for body in ("a", "b"):
        ev = StressEvaluator(grid, np.array([0.0, 0.02, 0.1]), 0.3, body)
        block = ev.block(*p)
        planes = ev.planes(*p, x0=0.05, y0=-0.03)
        i0 = int(np.argmin(np.abs(grid.x - 0.05)))
        j0 = int(np.argmin(np.abs(grid.y + 0.03)))
        for c in (*STRESS_COMPONENTS, "vm"):
            assert np.allclose(planes["xz"].fields[c], block[c][:, j0, :], rtol=0, atol=1e-10)
            assert np.allclose(planes["yz"].fields[c], block[c][i0, :, :], rtol=0, atol=1e-10)


def test_body_b_is_the_mirror_of_body_a():
    """Identical tractions seen from the two bodies: a y-symmetric normal load gives the
    same field in both; a tangential load on a is the opposite load on b, so sxz flips."""
    grid = Grid(0.4, 0.4, 15, 15)
    X, Y = np.meshgrid(grid.x, grid.y, indexing="ij")
    p_n = np.clip(1 - (X**2 + Y**2) / 0.1**2, 0, None)
    zero = np.zeros_like(p_n)
    z = np.array([0.0, 0.05])
    a = StressEvaluator(grid, z, 0.3, "a").block(zero, zero, p_n)
    b = StressEvaluator(grid, z, 0.3, "b").block(zero, zero, p_n)
    for c in STRESS_COMPONENTS:
        assert np.allclose(a[c], b[c], atol=1e-12)
    a = StressEvaluator(grid, z, 0.3, "a").block(p_n, zero, zero)
    b = StressEvaluator(grid, z, 0.3, "b").block(p_n, zero, zero)
    assert np.allclose(a["sxz"], -b["sxz"], atol=1e-12)
    assert np.allclose(a["sxx"], -b["sxx"], atol=1e-12)


def test_refinement_of_the_von_mises_maximum():
    """Issue 2: the on-axis sigma_VM-maximum error decreases over three grids (layers
    0.004 a0 apart around the maximum, so the grid, not the depth sampling, dominates);
    the observed orders (against the cell size) are printed."""
    from halfspace.problem import contact_solver, profile

    ref, _ = axis_vm_max(0.3)
    h, errs = [], []
    for n in (21, 41, 81):
        case = load_case("hertz", overrides={"grid.nx": n, "grid.ny": n})[0]
        a0, p0 = case.hertz_scales
        sol = contact_solver(case).solve(profile(case), P=case.load.P).state
        ev = StressEvaluator(case.grid, np.linspace(0.40 * a0, 0.56 * a0, 41), 0.3, "b")
        vm = ev.planes(sol.p_x, sol.p_y, sol.p_n)["xz"].vm_max()[0]
        h.append(case.grid.dx)
        errs.append(abs(vm / p0 / ref - 1))
    print(assert_converges(h, errs, min_order=0.0, what="|sigma_VM,max/ref - 1|"))


@pytest.mark.parametrize("z", [0.0, 0.004, 0.05])
def test_coefficient_table_equals_cell_corner_sums(z):
    """The corner-lattice table (shared corners) equals the cell-by-cell corner sums of
    Eq. 43-48, including the surface values at cell centres."""
    from halfspace.stress_kernels import cell_stress_coefficients, coefficient_table

    dx, dy, nu = 0.02, 0.03, 0.28
    table = coefficient_table((-5, 7), (-3, 4), z, dx, dy, nu)
    i, j = np.arange(-5, 8)[:, None], np.arange(-3, 5)[None, :]
    ref = cell_stress_coefficients(i * dx, j * dy, z, dx, dy, nu)
    for load, comps in table.items():
        for c, arr in comps.items():
            scale = max(np.abs(ref[load][c]).max(), 1e-3)
            assert np.abs(arr - ref[load][c]).max() < 1e-12 * scale, (load, c)


def direct_block(grid: Grid, z, nu: float, body: str, p) -> dict[str, np.ndarray]:
    """Eq. 34 by direct summation over every (field cell, loaded cell) pair with the
    coefficients of one full coefficient_table (no FFT, no window, no mirroring)."""
    from halfspace.stress_kernels import coefficient_table

    nx, ny = grid.nx, grid.ny
    ysign, sx, flip = (1, 1.0, 1.0) if body == "a" else (-1, -1.0, -1.0)
    loads = {"x": sx * p[0], "y": p[1], "n": p[2]}
    i, j = np.arange(nx), np.arange(ny)
    di = i[:, None, None, None] - i[None, None, :, None] + nx - 1  # [i, j, i', j']
    dj = ysign * (j[None, :, None, None] - j[None, None, None, :]) + ny - 1
    out = {c: np.empty((nx, ny, len(z))) for c in STRESS_COMPONENTS}
    for k, zk in enumerate(z):
        T = coefficient_table((-(nx - 1), nx - 1), (-(ny - 1), ny - 1), zk, grid.dx,
                              grid.dy, nu)
        for c in STRESS_COMPONENTS:
            s = sum(np.einsum("ijab,ab->ij", T[ld][c][di, dj], f) for ld, f in loads.items())
            out[c][:, :, k] = flip * s if c in ("sxy", "syz") else s
    out["vm"] = von_mises(*(out[c] for c in STRESS_COMPONENTS))
    return out


@pytest.mark.parametrize("body", ["a", "b"])
@pytest.mark.parametrize("support", ["patch", "edge", "full", "normal only"])
def test_block_and_planes_equal_direct_summation(body, support):
    """The windowed, mirrored FFT convolution (block and both planes) equals the direct
    sum of Eq. 34 to 1e-12 of the field scale: non-square grid, dx != dy, tangential
    tractions, a traction window off-centre, touching the grid's corner, or the whole
    grid, and zero tangential components (skipped loads)."""
    grid = Grid(0.45, 0.26, 9, 13)
    rng = np.random.default_rng(11)
    p = [np.zeros((9, 13)) for _ in range(3)]
    box = {"patch": np.s_[2:5, 6:10], "edge": np.s_[6:9, 0:4], "full": np.s_[:, :],
           "normal only": np.s_[1:6, 3:8]}[support]
    for f in p:
        f[box] = rng.standard_normal(f[box].shape)
    if support == "normal only":
        p[0][:], p[1][:] = 0.0, 0.0
    z = np.array([0.0, 0.013, 0.08])
    ref = direct_block(grid, z, 0.27, body, p)
    ev = StressEvaluator(grid, z, 0.27, body)
    block = ev.block(*p)
    scale = max(np.abs(ref[c]).max() for c in STRESS_COMPONENTS)
    for c in (*STRESS_COMPONENTS, "vm"):
        assert np.abs(block[c] - ref[c]).max() < 1e-12 * scale, c
    for x0, y0 in [(0.0, 0.0), (-0.2, 0.11)]:
        planes = ev.planes(*p, x0, y0)
        i0, j0 = grid.nearest_cell(x0, y0)
        for c in (*STRESS_COMPONENTS, "vm"):
            assert np.abs(planes["xz"].fields[c] - ref[c][:, j0, :]).max() < 1e-12 * scale
            assert np.abs(planes["yz"].fields[c] - ref[c][i0, :, :]).max() < 1e-12 * scale


def test_block_is_bit_identical_for_any_thread_count(monkeypatch):
    """Each layer is computed by one thread alone: 1, 2 or 3 threads, layers handed out
    one, two or eight at a time, give the same bits, and so does a second call (planes:
    a cache hit gives the bits of a fresh evaluator)."""
    import halfspace.stresses as stresses

    grid = Grid(0.5, 0.4, 21, 17)
    rng = np.random.default_rng(5)
    p = [rng.random((21, 17)) for _ in range(3)]
    z = np.linspace(0.0, 0.1, 5)
    runs = []
    for workers, chunk in [(1, 8), (2, 1), (3, 2)]:
        monkeypatch.setattr(stresses, "STRESS_WORKERS", workers)
        monkeypatch.setattr(stresses, "BLOCK_CHUNK", chunk)
        ev = StressEvaluator(grid, z, 0.3, "b")
        runs.append((ev.block(*p), ev.planes(*p, 0.05, 0.0), ev.planes(*p, 0.05, 0.0)))
    for block, first, again in runs:
        for c in (*STRESS_COMPONENTS, "vm"):
            assert np.array_equal(block[c], runs[0][0][c])
            for name in ("xz", "yz"):
                assert np.array_equal(first[name].fields[c], runs[0][1][name].fields[c])
                assert np.array_equal(again[name].fields[c], first[name].fields[c])


def test_zero_tractions_give_zero_stresses():
    grid = Grid(0.5, 0.4, 6, 5)
    zero = np.zeros((6, 5))
    ev = StressEvaluator(grid, np.array([0.0, 0.1]), 0.3, "b")
    block = ev.block(zero, zero, zero)
    plane = ev.plane(zero, zero, zero, "x", 2)
    for c in (*STRESS_COMPONENTS, "vm"):
        assert block[c].shape == (6, 5, 2) and not block[c].any()
        assert plane.fields[c].shape == (6, 2) and not plane.fields[c].any()
