"""The gate's escape rate: every seeded defect (:mod:`seeded_defects`) must be caught.

Each defect is applied to a scratch copy of the five packages and the quick gate of its
cases runs there in a fresh process (``contact-vv run CASES --quick --solver
ic,analytic``, or ``contact-vv sweep CASE --param SWEEP`` at one point, then ``contact-vv
gate``), which must fail — a failed metric or a solver that no longer converges; a defect
in the comparisons themselves must fail the gate's self-test instead.  The defects
caught without the FEM run in CI; those that need the FEM (its own, and the half-space
solver's on the worn orthotropic fretting contact, which only the FEM compares; CI runs
that comparison itself, tests/test_fem_fretting_worn.py) run in the full tier.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from seeded_defects import DEFECTS, Defect

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("halfspace", "fem_reference", "analytic", "cases", "reports")


def scratch_copy(defect: Defect, where: Path) -> Path:
    """The packages copied to ``where`` with ``defect`` applied (its ``old`` text must
    stand ``count`` times in its file: a defect that no longer applies is an error)."""
    for name in PACKAGES:
        shutil.copytree(ROOT / name, where / name,
                        ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    path = where / defect.path
    text = path.read_text(encoding="utf-8")
    assert text.count(defect.old) == defect.count, \
        f"{defect.name}: {defect.old!r} stands {text.count(defect.old)} times in {defect.path}"
    path.write_text(text.replace(defect.old, defect.new), encoding="utf-8")
    return where


def _run(args: list[str], cwd: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": str(cwd)}
    return subprocess.run([sys.executable, *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=1200)


def caught(defect: Defect, tmp: Path) -> str:
    """What catches ``defect`` ('' when nothing does)."""
    src = scratch_copy(defect, tmp / "src")
    if defect.selftest:
        shutil.copy(ROOT / "tests" / "test_reports_gate_selftest.py", src)
        done = _run(["-m", "pytest", "-q", "-p", "no:cacheprovider", "-x",
                     "test_reports_gate_selftest.py"], src)
        failed = [ln for ln in done.stdout.splitlines() if ln.startswith("FAILED")]
        return f"gate self-test: {failed[0]}" if done.returncode and failed else ""
    out = tmp / "results"
    if defect.baseline:
        return caught_by_the_baselines(defect, src, out, tmp / "baselines")
    solvers = "ic,fem,analytic" if defect.fem else "ic,analytic"
    if defect.sweep:  # one point, whose only reference is the FEM: a failed ic-fem row
        (case,) = defect.cases
        command, solvers = ["sweep", case, "--param", defect.sweep, "--workers", "0"], "ic,fem"
    else:
        command = ["run", *defect.cases]
    run = _run(["-m", "reports", *command, "--quick", "--solver", solvers,
                "--no-progress", "--out", str(out)], src)
    gate = _run(["-m", "reports", "gate", "--out", str(out)], src)
    if gate.returncode == 0:
        return ""
    lines = [ln for ln in (gate.stdout + gate.stderr + run.stderr).splitlines()
             if "FAIL " in ln or "INCOMPLETE" in ln or "did not converge" in ln]
    if defect.sweep:
        return next((ln for ln in lines if "FAIL " in ln and " ic-fem " in ln), "")
    return lines[0] if lines else gate.stderr.strip()[:200]


def caught_by_the_baselines(defect: Defect, src: Path, out: Path, base: Path) -> str:
    """The first line of ``gate --baseline`` naming a row gated in the quick chain's
    baselines (``tests/baselines``, those of ``defect``'s cases) and not now ('' when the
    plain gate fails instead, or nothing does)."""
    for case in defect.cases:
        for path in (Path(case + ".csv"), Path("gated") / f"{case}.csv"):
            (base / path).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(ROOT / "tests" / "baselines" / path, base / path)
    _run(["-m", "reports", "run", *defect.cases, "--quick", "--no-progress", "--out",
          str(out)], src)
    if _run(["-m", "reports", "gate", "--out", str(out)], src).returncode != 0:
        return ""  # a defect of the rows' numbers: not this kind
    gate = _run(["-m", "reports", "gate", "--out", str(out), "--baseline", str(base)], src)
    return next((ln for ln in gate.stdout.splitlines()
                 if ln.startswith("DRIFT ") and "not gated now" in ln), "")


@pytest.mark.parametrize("defect", [d for d in DEFECTS if not d.fem],
                         ids=[d.name for d in DEFECTS if not d.fem])
def test_a_seeded_defect_is_caught_without_the_fem(defect, tmp_path):
    assert caught(defect, tmp_path), f"escaped: {defect.name}"


@pytest.mark.full
@pytest.mark.fem
@pytest.mark.parametrize("defect", [d for d in DEFECTS if d.fem],
                         ids=[d.name for d in DEFECTS if d.fem])
def test_a_seeded_defect_of_the_fem_is_caught(defect, tmp_path):
    assert caught(defect, tmp_path), f"escaped: {defect.name}"
