"""CalculiX (the ``ccx`` program) verified through the suite's own gates (calculix_adapter;
issue 74): the reader on files ccx wrote (``tests/data/calculix``, the deck of
:func:`tiny_deck`), the tractions from nodal forces, the fields' interpolation and
mirrors, the deck, the cases declined with the reason, the plugin without ``ccx``; with
``ccx``, one small case through it (the fast tier), the chain of the issue and the seeded
defects (``full``: about two minutes per point on one core, benchmarks/README.md,
"CalculiX through the gates").  Where ``ccx`` is not installed the tests that run it are
skipped (``.ci/run`` installs it where ``apt-get`` exists)."""

from __future__ import annotations

import dataclasses
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from vv_testing import load_bundled

import calculix_adapter
from calculix_adapter import deck, fields, frd, mesh, program, support, traction
from calculix_adapter import model as ccx_model
from calculix_adapter import run as ccx_run
from reports.cli import main
from reports.registry import solvers
from reports.store import layout

DATA = Path(__file__).resolve().parent / "data" / "calculix"
needs_ccx = pytest.mark.skipif(shutil.which("ccx") is None,
                               reason="CalculiX is not installed (apt-get install calculix-ccx)")

#: the tiny model of the fixture: steel on aluminium, half model, μ = 0.3, elements a0/2
A0, R, H = 0.149, 50.0, 0.149 / 2
E_A, NU_A, E_B, NU_B = 210000.0, 0.3, 70000.0, 0.33
P_HALF, QX_HALF = 5.1, 0.765


def tiny_bodies() -> tuple[mesh.Body, mesh.Body]:
    return mesh.bodies(A0, R, H, 3 * A0, 3 * A0, "half_y0",
                       mesh.profile_share(E_A, NU_A, E_B, NU_B))


def tiny_deck() -> str:
    """The deck of the fixture (``ccx -i job`` on it wrote ``tests/data/calculix``)."""
    a, b = tiny_bodies()
    e_star = 1.0 / ((1 - NU_A**2) / E_A + (1 - NU_B**2) / E_B)
    m = deck.Model(E_A, NU_A, E_B, NU_B, 0.3, 20 * e_star / H, 10 * e_star / H,
                   0.98 * A0**2 / R, 1.4, 1.0, P_HALF, QX_HALF, 0.0, "b")
    return deck.write(a, b, m)


def ours(out: Path, case: str) -> pd.DataFrame:
    m = pd.read_csv(out / case / layout.METRICS)
    return m[m["pair"].str.startswith("calculix-") & (m["status"] == "gated")]


# ------------------------------------------------------------------ the reader


def test_the_fixture_is_the_deck_the_writer_writes():
    """The committed files are ccx's answer to the deck written now (else regenerate:
    write :func:`tiny_deck` to job.inp and run ``ccx -i job`` in tests/data/calculix)."""
    assert (DATA / "job.inp").read_text() == tiny_deck()


def test_the_reader_reads_the_files_ccx_wrote():
    """The .frd blocks of the last increment of the last step (the .sta file's), every
    node of the deck; the contact force ``*CONTACT PRINT`` wrote equals the loads of the
    deck within ccx's own residual tolerance (0.5 % of the average force, its default),
    and the displacements ``*NODE PRINT`` wrote cover body b's skin."""
    blocks = frd.read_frd(DATA / "job.frd")
    a, b = tiny_bodies()
    n = a.nodes.shape[0] + b.nodes.shape[0]
    sta = [r.split() for r in (DATA / "job.sta").read_text().splitlines()[2:] if r.strip()]
    step, inc = int(sta[-1][0]), int(sta[-1][1])
    assert {"STRESS", "CONTACT"} <= {bl.name for bl in blocks}
    for bl in blocks:
        assert (bl.step, bl.increment, bl.time) == (step, inc, 3.0)
        assert bl.nodes.size >= n and np.isfinite(bl.values).all()
    assert frd.last(blocks, "STRESS").components == ("SXX", "SYY", "SZZ", "SXY", "SYZ", "SZX")
    (forces,) = frd.read_contact_forces(DATA / "job.dat")
    fx, _, fz = forces.force
    assert forces.time == 3.0
    assert fz == pytest.approx(-P_HALF, rel=5e-3) and fx == pytest.approx(-QX_HALF, rel=5e-3)
    ids, u = frd.read_node_print(DATA / "job.dat")
    assert sorted(ids - 1) == sorted(deck.skin(b)) and u.shape == (ids.size, 3)
    assert program.increments(DATA) == (len(sta), sum(int(r[3]) for r in sta))


def test_the_nodal_forces_carry_the_total_contact_force():
    """Σ of the face's nodal forces (from the printed displacements and this module's
    C3D8 stiffness) against ``*CONTACT PRINT``'s total on the slave face: the same force
    by equilibrium (not in y: a node at y = 0 also holds the symmetry plane's reaction,
    and carries the contact force of its tributary strip), to 1e-4 of P: ccx integrates
    its contact stresses for CF apart from the elements' forces, and the two differ by
    its Newton residual (2.1e-5 of P here); a modulus 0.1 % off moves the nodal forces'
    total by 1e-3."""
    _, b = tiny_bodies()
    ids, values = frd.read_node_print(DATA / "job.dat")
    u = np.zeros((b.nodes.shape[0], 3))
    u[ids - 1] = values
    F = traction.nodal_forces(b, u, E_B, NU_B)
    (forces,) = frd.read_contact_forces(DATA / "job.dat")
    fx, _, fz = forces.force
    total = F.sum(axis=(0, 1))
    assert total[0] == pytest.approx(fx, abs=1e-4 * P_HALF)
    assert total[2] == pytest.approx(fz, abs=1e-4 * P_HALF)
    # the friction law at every node (the positive weights of the integration points),
    # to the printed digits
    F[:, 0, 1] = 0.0  # the symmetry plane's reaction
    assert np.all(np.hypot(F[..., 0], F[..., 1]) <= 0.3 * np.maximum(-F[..., 2], 0.0)
                  + 1e-6 * P_HALF)


def test_values_that_run_together_are_read_by_their_columns(tmp_path):
    """The .frd's fixed columns: a negative value joins the one before it."""
    line = " -1        12 1.00000E+00-2.50000E-01 3.00000E+02"
    assert frd._values(line, 3) == [1.0, -0.25, 300.0]
    path = tmp_path / "cut.frd"
    path.write_text((DATA / "job.frd").read_text()[:5000])
    with pytest.raises(frd.ResultFileError, match="not a complete"):
        frd.read_frd(path)
    # an attempt that did not converge (U) is cut back: its iterations count, it does not
    (tmp_path / "job.sta").write_text(
        "SUMMARY OF JOB INFORMATION\n  STEP      INC     ATT  ITRS     TOT TIME\n"
        "     1          1     1U    7  0.0\n     1          1     2     9  0.25\n"
        "     1          2     1     4  0.5\n")
    assert program.increments(tmp_path) == (2, 20)


# ------------------------------------------------------------------ the fields


def test_nodal_forces_of_a_uniform_stress_are_its_traction_times_the_area():
    """A linear displacement field (uniform strain) is exact in C3D8: at a node inside a
    flat face (the whole profile on body a), the force is σ·e_z times its tributary
    area."""
    _, b = mesh.bodies(A0, R, H, 3 * A0, 3 * A0, "half_y0", 1.0)
    eps = np.array([[1e-4, 3e-5, -2e-5], [3e-5, -5e-5, 4e-5], [-2e-5, 4e-5, 2e-4]])
    u = b.nodes @ eps.T
    F = traction.nodal_forces(b, u, E_B, NU_B)
    D = traction.elasticity(E_B, NU_B)
    e = np.array([eps[0, 0], eps[1, 1], eps[2, 2], 2 * eps[0, 1], 2 * eps[1, 2],
                  2 * eps[0, 2]])
    s = D @ e
    t = np.array([s[5], s[4], s[2]])  # σ·e_z: (σ_xz, σ_yz, σ_zz)
    area = fields.tributary(b)
    inner = np.s_[1:-1, 1:-1]
    np.testing.assert_allclose(F[inner], t * area[inner][..., None], rtol=1e-10)


def test_a_rigid_motion_of_the_curved_face_carries_no_force():
    """On body b's mapped elements (its share of the profile): a translation and an
    infinitesimal rotation strain nothing, so the nodal forces vanish to round-off."""
    _, b = tiny_bodies()
    assert np.ptp(b.nodes[b.faces["contact"].ravel(), 2]) > 0  # the face is curved
    omega = np.array([2e-4, -3e-4, 5e-4])
    u = np.array([1e-3, -2e-3, 3e-3]) + np.cross(omega, b.nodes)
    F = traction.nodal_forces(b, u, E_B, NU_B)
    assert np.abs(F).max() < 1e-9 * E_B * H**2 * np.abs(omega).max()


def test_the_bodies_share_the_gap_and_meet_on_the_profile():
    """The two faces, each carrying its share of r²/2R, are apart by the whole profile
    (the gap of the closed forms), the shares in the ratio of the compliances."""
    a, b = tiny_bodies()
    share = mesh.profile_share(E_A, NU_A, E_B, NU_B)
    assert share == pytest.approx(((1 - NU_A**2) / E_A)
                                  / ((1 - NU_A**2) / E_A + (1 - NU_B**2) / E_B))
    fa, fb = a.nodes[a.faces["contact"].ravel()], b.nodes[b.faces["contact"].ravel()]
    np.testing.assert_allclose(fa[:, :2], fb[:, :2])
    np.testing.assert_allclose(fa[:, 2] - fb[:, 2], mesh.profile(fa[:, 0], fa[:, 1], R),
                               rtol=1e-12)
    np.testing.assert_allclose(fa[:, 2], share * mesh.profile(fa[:, 0], fa[:, 1], R))


def test_a_node_slips_where_its_support_slips_in_turning_directions():
    """Radial shear at the bound, μ p e_r, everywhere (a compression's annulus), held at
    the nodes as the nodal forces hold it: the support's traction weighted by the
    node's bilinear hat.  The combination's length falls short of μ p_n where the
    direction turns across the support, and every node still slips; a shear along x
    at the bound slips, at 0.95 of it sticks."""
    h, mu = 0.125, 0.3
    xs = np.arange(0, 9) * h
    X, Y = np.meshgrid(xs, xs, indexing="ij")
    s = np.linspace(-h, h, 41)
    hat = np.outer(1 - np.abs(s) / h, 1 - np.abs(s) / h)
    SX, SY = np.meshgrid(s, s, indexing="ij")
    p_n, p_x, p_y = (np.zeros_like(X) for _ in range(3))
    for i, j in np.ndindex(X.shape):
        x, y = np.abs(X[i, j] + SX), np.abs(Y[i, j] + SY)  # the mirror planes' images
        r = np.hypot(x, y)
        p = np.clip(1.0 - r**2, 0.0, None)
        w = hat / hat.sum()
        sx = np.sign(X[i, j] + SX)  # p_x odd in x, p_y odd in y
        sy = np.sign(Y[i, j] + SY)
        p_n[i, j] = np.sum(w * p)
        p_x[i, j] = np.sum(w * mu * p * sx * x / np.where(r > 0, r, 1))
        p_y[i, j] = np.sum(w * mu * p * sy * y / np.where(r > 0, r, 1))
    ratio = np.hypot(p_x, p_y) / (mu * np.where(p_n > 0, p_n, np.nan))
    inner = (np.hypot(X, Y) > 0.2) & (np.hypot(X, Y) < 0.85)
    short = inner & (ratio < 1 - fields.SLIP_TOL)  # below the bound: turning directions
    assert short.sum() >= 10
    slip = fields.slipping(p_n, p_x, p_y, mu)
    assert slip[inner].all()
    along = fields.slipping(p_n, mu * p_n, 0 * p_n, mu)
    below = fields.slipping(p_n, 0.95 * mu * p_n, 0 * p_n, mu)
    assert along[p_n > 0].all() and not below.any()


def test_face_fields_are_bilinear_and_mirrored():
    """On the face's tensor grid a bilinear nodal field is read exactly; the mirror of
    a half model (y ≥ 0) keeps p_x and p_n and turns p_y."""
    _, b = tiny_bodies()
    X, Y = np.meshgrid(b.xs, b.ys, indexing="ij")
    field = 2.0 + 3.0 * X - 5.0 * Y + 7.0 * X * Y
    x = np.linspace(-0.2, 0.2, 9)
    y = np.linspace(0.0, 0.2, 5)
    got = fields.on_face(b, field, "p_x", x, y)
    np.testing.assert_allclose(got, 2.0 + 3.0 * x[:, None] - 5.0 * y + 7.0 * np.outer(x, y),
                               rtol=1e-12)
    np.testing.assert_allclose(fields.on_face(b, field, "p_x", x, -y), got, rtol=1e-12)
    np.testing.assert_allclose(fields.on_face(b, field, "p_y", x, -y[1:]), -got[:, 1:],
                               rtol=1e-12)


def test_planes_read_a_linear_stress_and_mirror_its_signs():
    """Trilinear stresses of the body's tensor grid (its reference coordinates, in which
    the planes' depth is read), read on the planes, with σ_xy and σ_yz turned on the
    mirrored half (y < 0) of a half model."""
    _, b = tiny_bodies()
    x, y, z = (c.ravel() for c in np.meshgrid(b.xs, b.ys, b.zs, indexing="ij"))  # reference
    stress = np.stack([1 + x, 2 + y, 3 + z, 4 + x, 5 + z, 6 + y], axis=1)
    s = np.linspace(-0.1, 0.1, 5)
    depth = np.array([0.0, 0.05, 0.1])
    planes = fields.planes(b, stress, x=s, y=s, z=depth, x0=0.0, y0=0.0, sign_z=-1.0)
    xz, yz = planes["xz"].fields, planes["yz"].fields
    np.testing.assert_allclose(xz["sxx"], 1 + s[:, None] + 0 * depth, atol=1e-12)
    np.testing.assert_allclose(xz["szz"], 3 - depth + 0 * s[:, None], atol=1e-12)
    np.testing.assert_allclose(yz["syy"], 2 + np.abs(s)[:, None] + 0 * depth, atol=1e-12)
    sign = np.where(s < 0, -1.0, 1.0)[:, None]
    np.testing.assert_allclose(yz["sxy"], sign * 4 + 0 * depth, atol=1e-12)
    np.testing.assert_allclose(yz["syz"], sign * (6 + np.abs(s)[:, None]) + 0 * depth,
                               atol=1e-12)


# ------------------------------------------------------------------ the deck


def test_the_deck_says_what_the_case_asks():
    """Materials, μ and the stick slope, the loads (their negatives on the reference
    node, the model's share), the symmetry plane held, three steps under a tangential
    load."""
    text = tiny_deck()
    e_star = 1.0 / ((1 - NU_A**2) / E_A + (1 - NU_B**2) / E_B)
    assert f"*FRICTION\n0.3, {10 * e_star / H:.12g}\n" in text
    assert f"{E_B:.12g}, {NU_B:.12g}" in text and f"{E_A:.12g}, {NU_A:.12g}" in text
    assert text.count("*STEP") == 3
    assert f", 1, {-QX_HALF:.12g}" in text and f", 3, {-P_HALF:.12g}" in text
    assert "Y0, 2, 2, 0.0" in text and "X0," not in text


@pytest.mark.parametrize("ratio,first", [(1.4, 0.5), (1.1, 0.4), (1.25, 0.13), (1.4, 1.0)])
def test_the_approach_grows_the_radius_by_the_ratio_at_most(ratio, first):
    """Hertz's radius ∝ √δ: the radii of step 1 start at ``first`` and grow by no more
    than ``ratio`` to 1."""
    times, values = deck.approach_path(ratio, first)
    radii = np.sqrt(values)
    assert times[0] == 0.0 and times[-1] == 1.0 and np.all(np.diff(times) > 0)
    assert radii[0] == 0.0 and radii[1] == pytest.approx(first) and radii[-1] == 1.0
    assert np.all(radii[2:] / radii[1:-1] <= ratio * (1 + 1e-12))


def test_the_model_keeps_the_symmetry_of_the_load():
    hertz = load_bundled("hertz", quick=True)
    load = hertz.load
    assert support.symmetry(hertz) == "quarter"
    for q, shape in (((1.0, None), "half_y0"), ((None, 1.0), "half_x0"),
                     ((1.0, 0.5), "full")):
        case = dataclasses.replace(hertz, load=dataclasses.replace(load, Qx=q[0], Qy=q[1]))
        assert support.symmetry(case) == shape


def test_declined_cases_say_why():
    cm = load_bundled("cattaneo_mindlin", quick=True)
    ortho = dataclasses.replace(cm, friction=dataclasses.replace(cm.friction, mu2=0.5))
    held = dataclasses.replace(cm, load=dataclasses.replace(cm.load, P=None, approach=0.001))
    for case, why in ((load_bundled("pin_on_disk", quick=True), "static contact only"),
                      (load_bundled("fretting_isotropic", quick=True), "static contact only"),
                      (load_bundled("sliding_friction", quick=True), "tangential sliding"),
                      (ortho, "isotropic"), (held, "approach held")):
        assert why in calculix_adapter.supports(case), case.name
    for name in ("hertz", "cattaneo_mindlin", "dissimilar", "spence"):
        assert calculix_adapter.supports(load_bundled(name, quick=True)) is None
    assert calculix_adapter.by_default(cm) is not None


def test_without_ccx_the_plugin_says_how_to_get_it(monkeypatch, tmp_path, capsys):
    """Offered, unavailable, with the way to install it; a run asked of it is refused
    and writes nothing."""
    monkeypatch.setattr(support.shutil, "which", lambda name: None)
    ok, reason = solvers.available("calculix")
    assert not ok and "apt-get install calculix-ccx" in reason
    assert main(["list"]) == 0
    assert "apt-get install calculix-ccx" in capsys.readouterr().out
    out = tmp_path / "res"
    assert main(["run", "hertz", "--quick", "--no-progress", "--solver", "calculix",
                 "--out", str(out)]) != 0
    assert "apt-get install calculix-ccx" in capsys.readouterr().err
    assert not out.exists()


# ------------------------------------------------------------------ through ccx


@needs_ccx
def test_hertz_through_ccx_passes_its_gates(tmp_path, capsys):
    """The small case of the fast tier (a quarter model, frictionless, about ten
    seconds): every calculix row the gate holds passes, the load to the printed digits
    and the nodal forces' total equal to ccx's own."""
    out = tmp_path / "res"
    assert main(["run", "hertz", "--quick", "--no-progress", "--solver", "calculix,analytic",
                 "--out", str(out)]) == 0
    rows = ours(out, "hertz")
    assert {"P", "p_max", "p_n", "a_x", "a_y", "vm_max"} <= set(rows["quantity"])
    assert rows["passed"].all(), rows[~rows["passed"]]
    s = pd.read_csv(out / "hertz" / layout.SUMMARY)
    s = s[s["solver"] == "calculix"].iloc[0]
    assert s["P_nodal_forces"] == pytest.approx(s["P_contact_print"], rel=1e-4)
    # the work the load path plans, no increment cut back: the approach's radii, the
    # force step (a deterministic count: a slower convergence cannot land unseen)
    case = load_bundled("hertz", quick=True)
    a0 = case.hertz_scales[0]
    planned = deck.approach_path(ccx_model.radius_ratio(case),
                                 2 * ccx_model.element_size(case) / a0)[0].size
    assert s["increments"] == planned
    capsys.readouterr()
    assert main(["gate", str(out)]) == 0


@needs_ccx
def test_a_run_that_ccx_stops_says_why(monkeypatch, tmp_path):
    """A deck ccx fails on (a keyword misspelt: it stops with exit 255), and one it
    finishes without results: each run fails saying so, not with a reader's traceback."""
    case = load_bundled("hertz", quick=True)
    real = ccx_run.write
    monkeypatch.setattr(ccx_run, "write",
                        lambda a, b, m: real(a, b, m).replace("*ELASTIC\n", "*ELASTIK\n"))
    with pytest.raises(program.CalculixFailed, match=r"ccx stopped \(exit 255\)"):
        ccx_run.run(case)
    monkeypatch.setattr(ccx_run, "write", lambda a, b, m: "*NODE\n1, 0, 0, 0\n*STEP\n")
    with pytest.raises(program.CalculixFailed, match="ccx wrote no complete results"):
        ccx_run.run(case)


# ------------------------------------------------------------------ the issue's chain

SOLVERS = "calculix,fem,ic,analytic"
#: the rows issue 74 asks to be gated
CM_ROWS = {"P", "p_max", "p_n", "p_x", "p_y", "a_x", "a_y", "stick_area"}
SPENCE_ROWS = {"p_x", "p_y"}


def one_point(tmp: Path, qx: float = 2.295) -> Path:
    """The bundled Cattaneo–Mindlin case at one tangential load (Q/μP = 0.75 by
    default: the slip annulus 1.85 elements wide, its tractions gated), its sweep
    removed."""
    import re

    text = (Path(__file__).resolve().parents[1] / "cases" / "cattaneo_mindlin.toml").read_text()
    text = re.sub(r"\[sweep\].*?(?=\n\[)", "", text, flags=re.S)
    path = tmp / "cm_point.toml"
    path.write_text(text.replace("Qx = 1.53", f"Qx = {qx!r}"))
    return path


@needs_ccx
@pytest.mark.full
def test_the_chain_of_the_issue(tmp_path, capsys):
    """``run cattaneo_mindlin dissimilar spence --quick --solver calculix,fem,ic,analytic``
    and ``gate`` pass; calculix rows are gated on the quantities issue 74 names; the
    report shows calculix–fem beside fem–analytic."""
    from reports.render.pages import report_text

    out = tmp_path / "res"
    assert main(["run", "cattaneo_mindlin", "dissimilar", "spence", "--quick",
                 "--no-progress", "--solver", SOLVERS, "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["gate", str(out)]) == 0
    cm = ours(out, "cattaneo_mindlin")
    assert CM_ROWS <= set(cm["quantity"]), CM_ROWS - set(cm["quantity"])
    spence = ours(out, "spence")
    assert SPENCE_ROWS <= set(spence["quantity"]), spence
    for name in ("cattaneo_mindlin", "dissimilar", "spence"):
        rows = ours(out, name)
        assert not rows.empty and rows["passed"].all(), rows[~rows["passed"]]
    assert main(["report", str(out)]) == 0
    text = report_text(out)
    assert "calculix-fem" in text and "fem-analytic" in text


@needs_ccx
@pytest.mark.full
@pytest.mark.parametrize("defect,pairs", [
    ("mu_high", ("calculix-analytic", "calculix-ic")),
    ("stick_slope_soft", ("calculix-analytic",)),
])
def test_the_gate_catches_a_seeded_deck_defect(defect, pairs, tmp_path, monkeypatch, capsys):
    """Seeded in the deck (issue 74), on one Cattaneo–Mindlin point: μ 10 % high fails
    the friction law (an exact law, against every pair), a stick slope 100 times too soft
    the tangential traction's max norm against the closed form (against the half-space
    solver, whose budget is the wider, it passes: benchmarks/README.md, "CalculiX through
    the gates")."""
    if defect == "mu_high":
        real = ccx_model.friction
        monkeypatch.setattr(ccx_model, "friction", lambda case: 1.1 * real(case))
    else:
        real = ccx_model.stick_slope
        monkeypatch.setattr(ccx_model, "stick_slope", lambda case, h: real(case, h) / 100)
    out = tmp_path / "res"
    assert main(["run", str(one_point(tmp_path)), "--no-progress", "--solver",
                 "calculix,ic,analytic", "--quick", "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["gate", str(out)]) == 1
    m = pd.read_csv(out / "cm_point" / layout.METRICS)
    failed = m[(m["status"] == "gated") & ~m["passed"]]
    for pair in pairs:
        assert (failed["pair"] == pair).any(), failed
    assert not failed["pair"].str.startswith("ic").any()
