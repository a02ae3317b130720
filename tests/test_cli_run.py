"""`contact-vv run` and `gate` on fake solvers: layout, summary, manifest, exit codes."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import test_cli_fakes as fakes

from cases.result import SUMMARY_COLUMNS, load_step
from reports.cli import main
from reports.store import layout, manifest
from reports.store.results import scan

HERTZ = """\
description = "small Hertz for tests"
kind = "static"
[materials.a]
E = 210000.0
nu = 0.3
[materials.b]
E = 210000.0
nu = 0.3
[geometry]
R = 50.0
[grid]
Lx = 1.6
nx = 21
[load]
P = 10.2
[stress]
depth = 0.3
nz = 11
"""

SWEEP = HERTZ.replace('kind = "static"', 'kind = "static"\n[friction]\nmu = 0.3') + """\
[sweep]
key = "friction.mu"
label = "mu"
values = [0.25, 0.6]
"""


def write_case(tmp_path: Path, text: str = HERTZ, name: str = "small") -> Path:
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return path


@pytest.fixture
def fake(monkeypatch):
    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")


def run(*argv: str) -> int:
    return main(["run", "--no-progress", *argv])


def test_run_writes_the_contract_layout(tmp_path, fake):
    case = write_case(tmp_path)
    out = tmp_path / "res"
    assert run(str(case), "--out", str(out)) == 0
    root = out / "small"
    assert sorted(p.name for p in root.iterdir()) == ["fields", "manifest.json", "metrics.csv",
                                                      "summary.csv"]
    summary = pd.read_csv(root / "summary.csv")
    assert list(summary.columns[: len(SUMMARY_COLUMNS)]) == SUMMARY_COLUMNS
    assert list(summary["solver"]) == ["ic", "analytic"]  # registry order
    assert summary["param"].isna().all()  # blank: not a sweep
    # the fake ic is the exact Hertz pressure scaled by 1.02
    ratio = summary.loc[0, "p_max"] / summary.loc[1, "p_max"]
    assert ratio == pytest.approx(1 + fakes.ERROR, rel=1e-12)
    step = load_step(root / "fields" / "ic" / "base" / "step_0000.npz")
    assert step.surface["p_n"].shape == (21, 21)
    assert set(step.planes) == {"xz", "yz"}

    mf = manifest.read(root)  # verifies every file hash
    assert mf["case"] == "small" and mf["solvers"] == ["ic", "analytic"]
    assert mf["case_sha256"] == manifest.sha256_file(case)
    assert "fem" in mf["skipped"]  # unavailable, skipped with its reason
    prov = mf["provenance"]
    assert {"date", "git", "versions", "threads"} <= set(prov)
    assert prov["versions"]["numpy"] == np.__version__
    assert {"fields/ic/base/step_0000.npz", "summary.csv", "metrics.csv"} <= set(mf["files"])
    assert set(mf["sources"]) >= {"cases", "reports"} and len(mf["sources"]["reports"]) == 64
    assert not layout.staging_dir(out, "small").exists()


def test_metrics_of_the_fake_pair_are_exact(tmp_path, fake):
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path)), "--out", str(out)) == 0
    m = pd.read_csv(out / "small" / "metrics.csv")
    assert list(m.columns[:6]) == ["quantity", "pair", "metric", "value", "tolerance", "passed"]
    assert set(m["pair"]) == {"ic-analytic"}
    v = m.set_index(["quantity", "metric"])["value"]
    # every field/scalar of the fake ic is 1.015 x the reference: relative errors 0.015
    for key in [("p_n", "l2"), ("p_n", "max"), ("p_x", "l2"), ("p_max", "rel"),
                ("vm_xz", "l2"), ("vm_yz", "max"), ("vm_max", "rel")]:
        if key[0] == "p_x":
            continue  # frictionless: p_x is zero in both, so not compared
        assert v[key] == pytest.approx(fakes.ERROR, rel=1e-9), key
    assert ("p_x", "l2") not in v.index
    # lengths are identical: zero cells apart
    for key in [("a_x", "cells"), ("contact_area", "cells"), ("vm_max_loc", "cells")]:
        assert v[key] == pytest.approx(0.0, abs=1e-12), key
    assert m["passed"].all()


def test_sweep_points_get_param_rows_and_directories(tmp_path, fake):
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path, SWEEP)), "--out", str(out)) == 0
    summary = pd.read_csv(out / "small" / "summary.csv")
    # analytic has no solution for mu >= 0.5 (fake has_solution)
    assert list(zip(summary["solver"], summary["param"], strict=True)) == [
        ("ic", "mu=0.25"), ("analytic", "mu=0.25"), ("ic", "mu=0.6")]
    assert (out / "small" / "fields" / "ic" / "mu=0.6" / "step_0000.npz").is_file()
    m = pd.read_csv(out / "small" / "metrics.csv")
    assert set(m["param"]) == {"mu=0.25"}
    # with friction p_x = mu p is compared too
    px = m[(m.quantity == "p_x") & (m.metric == "l2")]["value"]
    assert px.iloc[0] == pytest.approx(fakes.ERROR, rel=1e-9)


def test_run_is_deterministic(tmp_path, fake):
    case = write_case(tmp_path)
    a, b = tmp_path / "a", tmp_path / "b"
    assert run(str(case), "--out", str(a)) == 0
    assert run(str(case), "--out", str(b)) == 0
    assert (a / "small/metrics.csv").read_bytes() == (b / "small/metrics.csv").read_bytes()
    sa = pd.read_csv(a / "small/summary.csv").drop(columns="wall_s")
    sb = pd.read_csv(b / "small/summary.csv").drop(columns="wall_s")
    pd.testing.assert_frame_equal(sa, sb, check_exact=True)


def test_gate_passes_then_fails_on_a_broken_tolerance(tmp_path, fake, capsys):
    case = write_case(tmp_path)
    out = tmp_path / "res"
    assert run(str(case), "--out", str(out)) == 0
    capsys.readouterr()
    assert main(["gate", "--out", str(out)]) == 0
    assert "problem" in capsys.readouterr().out
    # deliberately broken tolerance: 2 % error against a 1 % tolerance
    assert run(str(case), "--out", str(out), "--set", "tolerances.p_max=0.01") == 0
    capsys.readouterr()
    assert main(["gate", "--out", str(out)]) == 1
    text = capsys.readouterr().out
    fails = [line for line in text.splitlines() if line.startswith("FAIL")]
    assert len(fails) == 1
    assert "ic-analytic p_max rel = 0.015 > tolerance 0.01" in fails[0]
    assert "tolerance key p_max" in fails[0]


def test_gate_notes_a_changed_case_file(tmp_path, fake, capsys):
    case = write_case(tmp_path)
    out = tmp_path / "res"
    assert run(str(case), "--out", str(out)) == 0
    case.write_text(HERTZ.replace("P = 10.2", "P = 12.0"))
    capsys.readouterr()
    assert main(["gate", "--out", str(out)]) == 0  # a note, not a failure
    assert f"note: small: the case file {case} changed since the run" in capsys.readouterr().out


def test_sources_edited_during_a_run_are_flagged(tmp_path, fake, monkeypatch, capsys):
    versions = iter([{"halfspace": "a" * 64}, {"halfspace": "b" * 64}])
    monkeypatch.setattr(manifest, "source_hashes", lambda: next(versions))
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path)), "--out", str(out)) == 0
    mf = manifest.read(out / "small")
    assert mf["sources"] == {"halfspace": "a" * 64} and mf["sources_changed_during_run"]
    capsys.readouterr()
    assert main(["gate", "--out", str(out)]) == 0
    assert "note: small: solver sources changed during the run" in capsys.readouterr().out


def test_pair_specific_tolerance_key(tmp_path, fake, capsys):
    text = HERTZ + '[tolerances]\n"ic-analytic.p_n_max" = 0.01\n'
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path, text)), "--out", str(out)) == 0
    capsys.readouterr()
    assert main(["gate", "--out", str(out)]) == 1
    fails = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("FAIL")]
    assert [("p_n max" in f and "ic-analytic.p_n_max" in f) for f in fails] == [True]


def test_non_converged_solver_exits_1_and_leaves_nothing_complete(tmp_path, monkeypatch,
                                                                 capsys):
    case = write_case(tmp_path)
    out = tmp_path / "res"
    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_exact")
    assert run(str(case), "--out", str(out)) == 0  # an older complete result ...
    fakes.use(monkeypatch, ic="solve_diverging", analytic="solve_exact")
    capsys.readouterr()
    assert run(str(case), "--out", str(out)) == 1
    err = capsys.readouterr().err
    assert "small: solver ic did not converge: Uzawa" in err and "residual 3.2e-04" in err
    assert "Traceback" not in err
    assert not (out / "small").exists()  # ... does not outlive the failing run
    failed = json.loads((layout.staging_dir(out, "small") / "failed.json").read_text())
    assert "residual 3.2e-04" in failed["failures"][0]
    assert main(["gate", "--out", str(out)]) == 1
    lines = capsys.readouterr().out.splitlines()
    assert any(ln.startswith("INCOMPLETE small: run failed") and "did not converge" in ln
               for ln in lines)


def test_three_solvers_three_pairs_and_vtu(tmp_path, monkeypatch):
    import meshio

    fakes.use(monkeypatch, ic="solve_ic", fem="solve_fem", analytic="solve_exact")
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path)), "--out", str(out)) == 0
    m = pd.read_csv(out / "small" / "metrics.csv")
    assert list(m["pair"].unique()) == ["ic-fem", "ic-analytic", "fem-analytic"]
    p = m[(m.quantity == "p_max")].set_index("pair")["value"]
    assert p["ic-fem"] == pytest.approx((1 + fakes.ERROR) / (1 - fakes.ERROR) - 1, rel=1e-9)
    assert p["fem-analytic"] == pytest.approx(fakes.ERROR, rel=1e-9)
    mesh = meshio.read(out / "small" / "fields" / "fem" / "base" / "step_0000.vtu")
    assert mesh.cells[0].type == "tetra" and mesh.points.shape == (4, 3)
    assert "fields/fem/base/step_0000.vtu" in manifest.read(out / "small")["files"]


def test_a_solver_that_does_not_support_a_case_is_skipped(tmp_path, monkeypatch, capsys):
    from reports.registry import solvers

    fakes.use(monkeypatch, ic="solve_ic", fem="solve_fem")
    monkeypatch.setitem(solvers.REGISTRY, "fem",
                        replace(solvers.REGISTRY["fem"], supports_attr="fem_supports"))
    wear = HERTZ.replace('kind = "static"', 'kind = "sliding_wear"') + \
        "[sliding_wear]\ndistance = 2.0\n"
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path, wear)), "--out", str(out)) == 0
    assert set(pd.read_csv(out / "small" / "summary.csv")["solver"]) == {"ic"}
    assert manifest.read(out / "small")["skipped"]["fem"] == "does not support this case"
    capsys.readouterr()
    assert main(["gate", "--out", str(out), "--verbose"]) == 1  # ic alone: nothing gated
    text = capsys.readouterr()
    assert "note: small: solver fem not run (does not support this case)" in text.out
    assert "NO METRICS small" in text.out  # once, with the verdict
    # the protocol asks every solver for supports(): without it the solver is unavailable
    monkeypatch.setitem(solvers.REGISTRY, "fem",
                        replace(solvers.REGISTRY["fem"], supports_attr="no_such_function"))
    ok, reason = solvers.available("fem")
    assert not ok and "has no entry point no_such_function()" in reason
    capsys.readouterr()
    assert run(str(write_case(tmp_path, wear)), "--out", str(out)) == 0
    assert "fem" in manifest.read(out / "small")["skipped"]


def test_unwritable_result_fails_cleanly(tmp_path, monkeypatch, capsys):
    fakes.use(monkeypatch, analytic="solve_bad_vtu")
    assert run(str(write_case(tmp_path)), "--out", str(tmp_path / "r")) == 1
    err = capsys.readouterr().err
    assert "solver analytic crashed: writing its results failed: RuntimeError: meta['vtu']" \
        in err
    assert not (tmp_path / "r" / "small").exists()


def test_non_finite_fields_fail_the_run(tmp_path, monkeypatch, capsys):
    fakes.use(monkeypatch, ic="solve_nan")
    assert run(str(write_case(tmp_path)), "--out", str(tmp_path / "r")) == 1
    assert "non-finite values in surface p_n" in capsys.readouterr().err


def test_nan_scalars_of_a_numerical_solver_fail_the_run(tmp_path, monkeypatch, capsys):
    fakes.use(monkeypatch, ic="solve_nan_scalar")
    assert run(str(write_case(tmp_path)), "--out", str(tmp_path / "r")) == 1
    assert "non-finite scalar p_max = nan at output step 0" in capsys.readouterr().err


def test_what_a_closed_form_does_not_cover_is_not_compared(tmp_path, monkeypatch):
    fakes.use(monkeypatch, ic="solve_ic", analytic="solve_partial")
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path)), "--out", str(out)) == 0
    m = pd.read_csv(out / "small" / "metrics.csv")
    assert set(m["quantity"]) == {"P", "p_n", "p_max", "a_x", "a_y", "contact_area",
                                  "pressure_peak"}  # the pressure against each one's p_max
    assert m["passed"].all()


def test_not_converged_rows_fail_the_gate(tmp_path, fake, capsys):
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path)), "--out", str(out)) == 0
    path = out / "small" / "summary.csv"
    frame = pd.read_csv(path)
    frame.loc[0, "converged"] = False
    frame.to_csv(path, index=False)
    capsys.readouterr()
    # the edited file no longer matches the manifest: flagged, not trusted
    assert main(["gate", "--out", str(out)]) == 1
    assert "summary.csv changed after the run" in capsys.readouterr().out
    # rewrite the manifest as a run would have: now the row itself fails the gate
    mf = json.loads((out / "small" / "manifest.json").read_text())
    manifest.write(out / "small", {k: v for k, v in mf.items() if k != "files"})
    assert main(["gate", "--out", str(out)]) == 1
    assert "NOT CONVERGED small step 0 solver ic" in capsys.readouterr().out


def test_manifest_missing_means_incomplete(tmp_path, fake):
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path)), "--out", str(out)) == 0
    (out / "small" / "manifest.json").unlink()
    found = scan(out)
    assert not found.complete and "no manifest.json" in found.incomplete["small"]


def test_foreign_directories_are_neither_replaced_nor_flagged(tmp_path, fake, capsys):
    out = tmp_path / "res"
    (out / "small").mkdir(parents=True)
    (out / "small" / "notes.txt").write_text("mine")
    (out / "plots").mkdir()
    assert run(str(write_case(tmp_path)), "--out", str(out)) == 2
    assert "res/small exists and is not a contact-vv result" in capsys.readouterr().err
    assert (out / "small" / "notes.txt").read_text() == "mine"
    assert not layout.staging_dir(out, "small").exists()
    found = scan(out)
    assert not found.complete and not found.incomplete  # neither is a result


def test_nan_metric_fails():
    from reports.compare.verdict import decide

    frame = pd.DataFrame({"quantity": ["p_max"] * 3, "pair": ["a-b"] * 3,
                          "metric": ["rel"] * 3, "value": [math.nan, 0.001, 0.001],
                          "tolerance": [0.01, 0.01, math.inf], "status": ["gated"] * 3,
                          "note": [""] * 3})
    assert list(decide(frame)["passed"]) == [False, True, False]


def test_each_step_file_is_written_once(tmp_path, monkeypatch):
    """The serial executor saves each output step as the solver hands it over, with the
    derived scalars (stress.z_below), and the writer of the unit does not save it again."""
    from reports.run import units
    from reports.store import write

    saved: list[Path] = []

    def counting(original):
        def save(path, step):
            saved.append(Path(path))
            return original(path, step)
        return save

    monkeypatch.setattr(units, "save_step", counting(units.save_step))
    monkeypatch.setattr(write, "save_step", counting(write.save_step))
    text = SWEEP.replace("nz = 11", "nz = 11\nz_below = 0.05")
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path, text)), "--solver", "ic,analytic", "--out",
               str(out)) == 0
    steps = sorted((out / "small" / "fields").rglob("step_*.npz"))
    assert len(steps) == 4  # two solvers at two sweep points, one step each
    assert len(saved) == len(set(saved)) == 4
    for path in steps:
        assert math.isfinite(load_step(path).scalars["vm_max_below"])
