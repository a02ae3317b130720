"""Static cases a user writes, not bundled: every solver, every pair, default tolerances.

The bundled cases are what the tolerances were measured on; these are not.  Each case
file below sets only physics, a grid and the stress planes (no ``[fem]``, no
``[tolerances]``), and its run must pass every gated row of every pair at the default
tolerances (``reports.registry.tolerances``): the FEM against the closed forms and against the
half-space solver, the half-space solver against the closed forms.

- partial slip with another radius, load and friction (R = 100 mm, P = 30 N, μ = 0.2,
  Q = 0.6 μP; Cattaneo–Mindlin);
- a frictionless dissimilar pair (titanium sphere on aluminium, R = 20 mm, P = 50 N;
  Hertz, stresses in the plane);
- partial slip of a dissimilar pair (steel on titanium, R = 40 mm, P = 20 N, μ = 0.4,
  Q = 0.4 μP): the normal–tangential coupling, no closed form, ic-fem only;
- (full tier) orthotropic partial slip under an oblique load (R = 30 mm, P = 25 N,
  μ = (0.3, 0.5), β = 30°, Q = (3, 2) N), a full block for the FEM.

Measured 2026-11-25 (FEM at the default a0/8): the largest value/tolerance is 0.59
(Ti on Al, fem-analytic vm_yz max), 0.68 (R = 100, fem-analytic vm_yz max), 0.68
(steel on Ti, ic-fem p_x max); the orthotropic case 0.40 (ic-fem vm_xz max; its kink
0.164, not gated).  FEM 9 s, 29 s, 58 s and 133 s (4.8 GB).
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

from reports.cli import main

pytestmark = pytest.mark.fem

STEEL = "E = 210000.0\nnu = 0.3\n"
TITANIUM = "E = 110000.0\nnu = 0.34\n"
ALUMINIUM = "E = 70000.0\nnu = 0.33\n"


def _case(description: str, a: str, b: str, R: float, L: float, load: str,
          friction: str = "", body: str = "a", depth: float = 0.5) -> str:
    return (f'description = "{description}"\nkind = "static"\n'
            f"[materials.a]\n{a}[materials.b]\n{b}[geometry]\nR = {R}\n"
            f"[grid]\nLx = {L}\nLy = {L}\nnx = 61\nny = 61\n{friction}"
            f"[load]\n{load}[stress]\nbody = \"{body}\"\ndepth = {depth}\nnz = 31\n")


CASES = {
    "slip_r100": _case("partial slip, R = 100 mm, mu = 0.2, Q = 0.6 mu P", STEEL, STEEL,
                       100.0, 0.8, "P = 30.0\nQx = 3.6\n", "[friction]\nmu = 0.2\n"),
    "ti_on_al": _case("frictionless titanium sphere on aluminium", TITANIUM, ALUMINIUM,
                      20.0, 0.8, "P = 50.0\n", body="b"),
    "steel_on_ti_slip": _case("steel on titanium, mu = 0.4, Q = 0.4 mu P", STEEL, TITANIUM,
                              40.0, 0.6, "P = 20.0\nQx = 3.2\n", "[friction]\nmu = 0.4\n",
                              body="b", depth=0.4),
}
ORTHOTROPIC = _case("orthotropic partial slip, oblique load", STEEL, STEEL, 30.0, 0.6,
                    "P = 25.0\nQx = 3.0\nQy = 2.0\n",
                    "[friction]\nmu1 = 0.3\nmu2 = 0.5\nbeta = 30.0\n", depth=0.35)


def _run_and_gate(tmp_path: Path, name: str, text: str) -> pd.DataFrame:
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    out = tmp_path / "res"
    assert main(["run", str(path), "--no-progress", "--out", str(out)]) == 0
    assert main(["gate", "--out", str(out)]) == 0
    return pd.read_csv(out / name / "metrics.csv")


def _check(metrics: pd.DataFrame, pairs: set[str]) -> None:
    gated = metrics[metrics["status"] == "gated"]
    assert set(gated["pair"]) == pairs
    assert (gated["tolerance_kind"] == "budget").all()  # defaults, nothing from a case
    assert gated["passed"].all(), gated[~gated["passed"]]
    # the ungated rows are what the comparisons decide by themselves: the maxima over the
    # bands (stick-slip kink, contact edge) and near the surface, and fields in a zone
    # narrower than their resolution floor
    off = metrics[metrics["status"] != "gated"]
    shown = off["metric"].isin(["kink", "edge", "surface"])
    assert (shown | off["note"].str.startswith("not resolved")).all(), off[~shown]


@pytest.mark.parametrize("name", sorted(CASES))
def test_user_case_passes_every_default_tolerance(tmp_path, name):
    metrics = _run_and_gate(tmp_path, name, CASES[name])
    pairs = {"ic-fem"} if name == "steel_on_ti_slip" else {"ic-fem", "ic-analytic",
                                                             "fem-analytic"}
    _check(metrics, pairs)


@pytest.mark.full
def test_orthotropic_oblique_user_case_passes_every_default_tolerance(tmp_path):
    """The case of stop 27 whose ic-fem vm_xz max (0.164) missed the default 0.16 at the
    stick-slip kink before the stick band (docs/formulation.md §2.7)."""
    metrics = _run_and_gate(tmp_path, "orthotropic", ORTHOTROPIC)
    _check(metrics, {"ic-fem"})  # no closed form for orthotropic partial slip
