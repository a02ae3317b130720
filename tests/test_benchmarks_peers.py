"""The side-by-side benchmark (benchmarks/peers_bench.py) on a 64^2 grid: every worker
returns sane numbers (the Hertz peak within 2 %, the forces exact), one measurement
runs as a whole process, and its table replaces itself between the markers."""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import numpy as np
import pytest

from cases import load_case

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "peers_bench.py"
N = 64


def _load():
    spec = importlib.util.spec_from_file_location("peers_bench", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


pb = _load()


def _check_row(row: dict, code: str, problem: str) -> None:
    assert (row["code"], row["problem"], row["n"]) == (code, problem, N)
    numbers = [v for v in row.values() if isinstance(v, int | float)]
    assert all(math.isfinite(v) for v in numbers)
    assert row["solve_s"] > 0 and row["peak_mb"] > 0 and row["iterations"] >= 0


def _check_hertz(row: dict, force_rtol: float = 1e-9) -> None:
    assert abs(row["p_max_err"]) < 0.02
    assert row["force_err"] < force_rtol


def test_grid_is_the_project_grid():
    case = load_case("hertz", overrides={"grid.nx": N, "grid.ny": N})[0]
    assert case.grid.Lx == pb.L and case.grid.nx == N
    np.testing.assert_allclose(pb.cell_centres(N), case.grid.x, rtol=0, atol=1e-15)
    np.testing.assert_allclose(pb.cell_centres(N), case.grid.y, rtol=0, atol=1e-15)


def test_project_hertz_worker(tmp_path):
    row = pb.evaluate("project", "hertz", N, tmp_path / "f.npz")
    _check_row(row, "project", "hertz")
    _check_hertz(row)
    assert row["iterations"] > 0


def test_project_mindlin_worker(tmp_path):
    row = pb.evaluate("project", "mindlin", N, tmp_path / "f.npz")
    _check_row(row, "project", "mindlin")
    _check_hertz(row)  # P and Q both to 1e-9
    assert row["px_l2"] < 0.15 and row["px_max"] < 0.15


def test_project_vm_worker(tmp_path):
    row = pb.evaluate("project", "vm", N, tmp_path / "f.npz")
    _check_row(row, "project", "vm")
    assert abs(row["vm_max_err"]) < 0.02


def test_unknown_pairing_is_refused(tmp_path):
    with pytest.raises(ValueError, match="no 'tamaas-pkt' run"):
        pb.evaluate("tamaas-pkt", "hertz", N, tmp_path / "f.npz")


def test_tamaas_workers(tmp_path):
    pytest.importorskip("tamaas")
    for code in ("tamaas-dcfft", "tamaas-periodic"):
        row = pb.evaluate(code, "hertz", N, tmp_path / "f.npz")
        _check_row(row, code, "hertz")
        _check_hertz(row)
        assert row["iterations"] > 0  # read from Tamaas's log
    row = pb.evaluate("tamaas-pkt", "mindlin", N, tmp_path / "f.npz")
    _check_row(row, "tamaas-pkt", "mindlin")
    _check_hertz(row, force_rtol=1e-6)  # a fixed budget: P and Q converge within it
    assert row["iterations"] == pb.pkt_budget(N)
    assert row["px_l2"] < 0.15 and row["px_max"] < 0.15


def test_main_without_tamaas_runs_the_project_half(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(pb, "have_tamaas", lambda: False)
    monkeypatch.setattr(pb, "installed", lambda code: code == "project")  # no peer at all
    out = tmp_path / "README.md"
    pb.main(["--problems", "hertz", "--sizes", str(N), "--repeat", "1", "--out", str(out)])
    said = capsys.readouterr().out
    assert "Tamaas is not importable" in said
    doc = out.read_text()
    assert doc.count(pb.BEGIN) == 1 and "Tamaas not installed" in doc
    rows = [ln for ln in doc.splitlines() if ln.startswith("| hertz |")]
    assert len(rows) == 1 and "this project" in rows[0]
    assert rows[0].split("|")[4].strip() != "—"  # the whole process's wall time


def test_measure_times_the_whole_process():
    row = pb.measure("project", "hertz", N)
    _check_row(row, "project", "hertz")
    assert row["wall_s"] > row["solve_s"] and row["cpu_s"] > 0


def _fake(code: str, problem: str, wall: float) -> dict:
    return {"code": code, "problem": problem, "n": N, "wall_s": wall, "cpu_s": wall / 2,
            "solve_s": wall / 4, "iterations": 10, "peak_mb": 100.0, "p_max_err": 1e-3,
            "force_err": 0.0, "px_l2": 0.01, "px_max": 0.02}


def test_medians_and_ratios():
    runs = [_fake("project", "hertz", w) for w in (3.0, 1.0, 2.0)]
    med = pb.median_row(runs)
    assert med["wall_s"] == 2.0 and med["repeats"] == 3
    text = pb.peer_table([med, _fake("tamaas-dcfft", "hertz", 4.0)])
    assert "| 0.50 | 0.50 |" in text  # project / peer, wall and CPU
    assert pb.codes_for("hertz", peers=False) == ("project",)


def test_markers_replaced_not_duplicated(tmp_path):
    out = tmp_path / "README.md"
    out.write_text("# Benchmarks\n\nintro\n")
    pb.write_between_markers(out, "first table\n")
    pb.write_between_markers(out, "second table\n")
    doc = out.read_text()
    assert doc.count(pb.BEGIN) == 1 and doc.count(pb.END) == 1
    assert "second table" in doc and "first table" not in doc
    assert doc.startswith("# Benchmarks\n\nintro\n")
    out.write_text(doc + "\ntrailing text\n")
    pb.write_between_markers(out, "third\n")
    doc = out.read_text()
    assert doc.count(pb.BEGIN) == 1 and "third" in doc and doc.endswith("trailing text\n")
