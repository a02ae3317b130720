"""End-to-end: the FEM reference through `contact-vv run` on the quick Hertz case."""

from __future__ import annotations

import pytest
from test_cli_e2e import run_one

from cases.loader import load_case


@pytest.mark.fem
def test_fem_hertz(tmp_path):
    _, p0 = load_case("hertz", quick=True)[0].hertz_scales
    row = run_one(tmp_path, "fem")
    assert row["converged"]
    # docs/fem-notes.md: p_max 0.996-0.998 p0, σ_VM,max 0.622 p0 at h = a/8
    assert row["p_max"] / p0 == pytest.approx(1.0, abs=0.02)
    assert row["vm_max"] / p0 == pytest.approx(0.620, rel=0.02)
    assert (tmp_path / "res" / "hertz" / "fields" / "fem" / "base" / "step_0000.vtu").is_file()
