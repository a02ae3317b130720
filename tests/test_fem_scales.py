"""Every valid case runs at any scale, the FEM too (issue 59, point 3): its tolerances are
relative to the problem's own scale (loads, lengths, moduli), never below what floating
point gives.  Hertz and Cattaneo–Mindlin cases at R 0.05–5000 mm, P 1e-4–1e5 N,
E 1e3–1.2e6 MPa, ν 0–0.49, μ 0.001–0.8, Q 0.05–0.95 μP along ±x or ±y (a half block;
the FEM's oblique loads: tests/test_fem_generated_cases.py), written as case
files, run through ``fem,analytic`` and gated with the default tolerances: exit 0 both
times, the FEM's rows gated.  A sample in the fast tier (two Hertz draws); ``-m full``
draws both kinds.  (The half-space solver's: ``tests/test_halfspace_robustness.py``.)"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from reports.cli import main


def _log(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(math.log(lo), math.log(hi)).map(math.exp)


@st.composite
def scaled_case(draw: st.DrawFn, kinds: tuple[str, ...] = ("hertz", "partial_slip")) -> str:
    """The text of a Hertz or Cattaneo–Mindlin case at any scale (module doc), its grid
    3.2 contact radii wide with 21 cells, its planes 1.5 radii deep."""
    kind = draw(st.sampled_from(kinds))
    E, nu = draw(_log(1e3, 1.2e6)), draw(st.floats(0.0, 0.49))
    R, P = draw(_log(0.05, 5000.0)), draw(_log(1e-4, 1e5))
    a0 = (3.0 * P * R * (1.0 - nu * nu) / (2.0 * E)) ** (1.0 / 3.0)
    friction, load = "", f"P = {P!r}\n"
    if kind == "partial_slip":
        mu, q = draw(_log(0.001, 0.8)), draw(st.floats(0.05, 0.95))
        angle = 0.5 * math.pi * draw(st.integers(0, 3))  # along an axis: a half block
        friction = f"[friction]\nmu = {mu!r}\n"
        load += (f"Qx = {q * mu * P * math.cos(angle)!r}\n"
                 f"Qy = {q * mu * P * math.sin(angle)!r}\n")
    body = f"E = {E!r}\nnu = {nu!r}\n"
    return (f'kind = "static"\n[materials.a]\n{body}[materials.b]\n{body}[geometry]\n'
            f"R = {R!r}\n[grid]\nLx = {3.2 * a0!r}\nnx = 21\n{friction}[load]\n{load}"
            f"[stress]\ndepth = {1.5 * a0!r}\nnz = 11\n")


def _runs_and_passes(text: str, tmp) -> None:
    path = tmp / "scaled.toml"
    path.write_text(text)
    out = tmp / "res"
    assert main(["run", str(path), "--solver", "fem,analytic", "--no-progress",
                 "--out", str(out)]) == 0, text
    assert main(["gate", "--out", str(out)]) == 0, text
    metrics = pd.read_csv(out / "scaled" / "metrics.csv")
    gated = metrics[(metrics["pair"] == "fem-analytic") & (metrics["status"] == "gated")]
    assert {"P", "p_max"} <= set(gated["quantity"]), text
    assert np.isfinite(gated["value"]).all(), text


@pytest.mark.fem
@settings(max_examples=2, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(text=scaled_case(kinds=("hertz",)))
def test_the_fem_runs_at_any_scale(text, tmp_path_factory):
    _runs_and_passes(text, tmp_path_factory.mktemp("scale"))


@pytest.mark.full
@settings(max_examples=12, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(text=scaled_case())
def test_the_fem_runs_at_any_scale_many(text, tmp_path_factory):
    _runs_and_passes(text, tmp_path_factory.mktemp("scale"))
