"""The worn orthotropic fretting contact through both solvers, in CI (issue 34).

Without this module the worn fretting contact is checked in CI by one solver only: the
quick gates run ``fretting_orthotropic`` through the half-space solver and its
metamorphic relations, and the FEM runs only the first cycle of ``fretting_isotropic``
(tests/test_fem_fretting.py), whose two bodies wear alike.  A defect of the worn path
that the relations map onto themselves — the corrector's wear compliance without the
cycle jump, body b worn with body a's slip norm — then passes, or is seen by chance in a
quantity the cycle jump does not converge (tests/seeded_defects.py, the defects whose
cases name ``fretting_orthotropic``; benchmarks/README.md, "Escapes").

Here the FEM runs two gross-slip points of the bundled case (friction (0.1, 0.65), both
bodies wearing with their own orthotropic coefficients, the held approach):

- β = 0: 2000 cycles at J = 500, four simulated cycles, on the half block;
- β = 60°, an oblique angle near the article's regime change: the same settings on the
  full block (no symmetry).

Both are points of the case's quick sweep, at its quick settings.

Every output cycle gates ic-fem rows of the worn contact — the wear fields of both
bodies, w_max, the wear volume, the tractions, p_max, both stress planes, the loop and its
energy — at the default tolerances, and every gated row passes (``contact-vv gate`` exits
0; the σ_VM maximum over the contact's edge band is shown, not gated, as everywhere).
Partial slip (β = 90°) is not here: there the two solvers part in the worn stick zone
(docs/fem-notes.md, part 5).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from cases.loader import load_case
from reports.cli import main
from reports.store.results import CaseResults, scan

pytestmark = pytest.mark.fem

#: the worn-contact quantities every output cycle must gate (ic-fem)
WORN = ("wear_a", "wear_b", "w_max", "wear_volume", "p_n", "p_x", "p_max", "vm_xz",
        "vm_yz", "loop_q", "energy")
#: of those, the ones a slip zone as wide as the contact always resolves
#: (reports.registry.resolution: the loop and its energy also need 8 cells per radius)
WEAR = ("wear_a", "wear_b", "w_max", "wear_volume")


#: the points of the quick sweep run here, at the quick settings
POINTS = ("beta=0", "beta=60")
#: their output cycles and simulated cycles (cycles / jump), from the case itself
_FRETTING = load_case("fretting_orthotropic", quick=True)[0].fretting
OUTPUT_CYCLES = sorted(float(c) for c in _FRETTING.output_cycles)
SIMULATED = round(_FRETTING.cycles / _FRETTING.jump)


@pytest.fixture(scope="module", params=POINTS)
def worn(request, tmp_path_factory) -> tuple[str, Path]:
    out = tmp_path_factory.mktemp("worn") / "results"
    assert main(["sweep", "fretting_orthotropic", "--quick", "--solver", "ic,fem",
                 "--param", f"friction.{request.param}",
                 "--workers", "0", "--no-progress", "--out", str(out)]) == 0
    return request.param, out


def results(out: Path) -> CaseResults:
    (found,) = scan(out).complete
    return found


def test_the_gate_passes(worn, capsys):
    code = main(["gate", "--out", str(worn[1])])
    out = capsys.readouterr().out
    assert code == 0, out


def test_every_output_cycle_gates_the_worn_contact(worn):
    """The pass means something: every output cycle carries gated ic-fem rows of every
    worn-contact quantity, at the default tolerances."""
    point, out = worn
    m = results(out).metrics
    m = m[m["pair"] == "ic-fem"]
    assert sorted(m["cycle"].unique()) == OUTPUT_CYCLES
    for cycle, rows in m.groupby("cycle"):
        gated = rows[rows["status"] == "gated"]
        assert set(WORN) <= set(gated["quantity"]), (cycle, set(WORN) - set(gated["quantity"]))
        assert gated["tolerance_key"].str.startswith("default").all()
        assert gated["passed"].all()


def test_the_point_wears_in_gross_slip_in_both_solvers(worn):
    """What the gate covers: every simulated cycle in gross slip, in both solvers (the
    cycles table each writes), the worn depth growing from the first simulated cycle on,
    and — between the output cycles too — the two solvers' depths within the tolerance
    their output cycles' w_max is gated with."""
    point, out = worn
    found = results(out)
    depth = {}
    for solver in ("ic", "fem"):
        cycles = found.tables(solver, point)["cycles"]
        assert len(cycles) == SIMULATED, solver
        assert (cycles["gross_slip"] == 1.0).all(), solver
        assert (np.diff(cycles["w_max"], prepend=0.0) > 0).all(), solver
        depth[solver] = cycles["w_max"].to_numpy()
    m = found.metrics
    (limit,) = set(m[(m["pair"] == "ic-fem") & (m["quantity"] == "w_max")]["tolerance"])
    assert depth["fem"] == pytest.approx(depth["ic"], rel=limit)


@pytest.mark.full
@settings(max_examples=3, deadline=None, derandomize=True)
@given(mu1=st.floats(0.08, 0.3), ratio=st.floats(1.5, 6.0), beta=st.floats(20.0, 70.0),
       amplitude=st.floats(3e-3, 6e-3), held=st.sampled_from(["load", "approach"]))
def test_generated_worn_gross_slip_cases_pass(mu1, ratio, beta, amplitude, held):
    """Cases the suite has not seen — any orthotropic friction ellipse, an oblique angle
    (the full block, as CI's β = 60° point; β = 0 is its half block), any amplitude, the
    load or the approach held — worn for 500 cycles (one simulated cycle of
    J = 500), with the amplitude at least 1.2 times Mindlin's δ* for the friction along the
    motion (P and a fall as the contact wears, and δ* with them, so the contact stays in
    gross slip; not near the threshold, where one node or cell may part the regimes):
    both solvers slide through the whole cycle, and every gated ic-fem row passes at the
    default tolerances (a right pair of solvers raises no false alarm)."""
    import fem_reference
    import halfspace
    from analytic import hertz, mindlin
    from reports.compare.point import compare_point
    from reports.run.sweep import sweep_points

    name = ("fretting_orthotropic" if held == "approach"
            else Path(__file__).resolve().parents[1] / "cases" / "examples"
            / "fretting_orthotropic_load.toml")
    friction = [("friction.mu1", [mu1]), ("friction.mu2", [min(mu1 * ratio, 1.0)]),
                ("friction.beta", [beta])]
    (case,), _ = sweep_points(name, friction, quick=True, overrides={
        "fretting.amplitude": amplitude, "fretting.cycles": 500,
        "fretting.output_cycles": [500]})
    h = (hertz.hertz(case.load.P, case.R, case.E_star) if case.load.load_controlled
         else hertz.hertz_from_approach(case.load.approach, case.R, case.E_star))
    assume(amplitude > 1.2 * mindlin.gross_slip_shift(
        case.sliding_friction, h.P, h.a, case.a.G, case.a.nu, case.b.G, case.b.nu))
    ic = halfspace.solve(case)
    fem = fem_reference.solve(case, vtu=False)
    for run in (ic, fem):
        assert (run.tables["cycles"]["gross_slip"] == 1.0).all(), run.solver
    frame = compare_point(case, {"ic": ic, "fem": fem})
    gated = frame[frame["status"] == "gated"]
    # every worn-contact quantity compared, the wear gated; the loop and its energy are
    # gated where the contact radius spans the cells their budgets need (the held load's
    # 3 mm quick grid may not: shown, with the width)
    assert set(WORN) <= set(frame["quantity"])
    assert set(WEAR) <= set(gated["quantity"])
    worst = gated.loc[(gated["value"] / gated["tolerance"]).idxmax()]
    print(f"\nmu = ({mu1:.3f}, {case.friction.mu2:.3f}), beta = {beta:.1f}, amplitude "
          f"{amplitude * 1e3:.2f} um, {held} held: {len(gated)} gated rows, the closest "
          f"{worst['quantity']} {worst['metric']} {worst['value']:.3g} of {worst['tolerance']:g}")
    failed = gated[~gated["passed"]]
    assert failed.empty, failed[["quantity", "metric", "value", "tolerance"]].to_string()
