"""The worn orthotropic fretting contact through both solvers: generated cases (the full
tier; the bundled quick points are read in tests/test_suite_quick_gates.py).

Without this module the worn fretting contact is checked in CI by one solver only: the
quick gates run ``fretting_orthotropic`` through the half-space solver and its
metamorphic relations, and the FEM runs only the first cycle of ``fretting_isotropic``
(tests/test_fem_fretting.py), whose two bodies wear alike.  A defect of the worn path
that the relations map onto themselves — the corrector's wear compliance without the
cycle jump, body b worn with body a's slip norm — then passes, or is seen by chance in a
quantity the cycle jump does not converge (tests/seeded_defects.py, the defects whose
cases name ``fretting_orthotropic``; benchmarks/README.md, "Escapes").

The quick chain runs two gross-slip points of the bundled case through the FEM (friction
(0.1, 0.65), both bodies wearing with their own orthotropic coefficients, the held
approach):

- β = 0: 2000 cycles at J = 500, four simulated cycles, on the half block;
- β = 60°, an oblique angle near the article's regime change: the same settings on the
  full block (no symmetry).

Both are points of the case's quick sweep, at its quick settings.

Every output cycle gates ic-fem rows of the worn contact — the wear fields of both
bodies, w_max, the wear volume, the tractions, p_max, both stress planes, the loop and its
energy — at the default tolerances, and every gated row passes (``contact-vv gate`` exits
0; the σ_VM maximum over the contact's edge band is shown, not gated, as everywhere).
Partial slip (β = 90°): there the two solvers part in the worn stick zone
(docs/fem-notes.md, part 5), and the resolution probe decides which rows the FEM's surface
resolves (tests/test_suite_quick_gates.py; the generated cases of
:func:`test_generated_worn_partial_slip_cases_keep_the_probes_promise`).
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from cases.loader import load_case

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


@pytest.mark.full
@settings(max_examples=4, deadline=None, derandomize=True)
@given(mu1=st.floats(0.08, 0.3), ratio=st.floats(1.0, 6.0), beta=st.floats(0.0, 90.0),
       slip=st.floats(0.3, 2.0), held=st.sampled_from(["load", "approach"]))
def test_generated_worn_partial_slip_cases_keep_the_probes_promise(mu1, ratio, beta, slip,
                                                                    held, tmp_path_factory):
    """Worn fretting cases in either regime (issue 51): any friction ellipse, any angle
    (oblique ones on the full block), an amplitude of 0.3–2 times Mindlin's δ* for the
    friction along the motion (partial slip below 1, gross slip above), the load or the
    approach held, worn for 1000 cycles (two simulated cycles of J = 500), run as
    ``contact-vv run`` runs them — the FEM, the half-space solver and its resolution
    probe.  Where the probe admits an ic-fem row, the two solvers agree within its default
    tolerance (a right pair raises no false alarm through the probe); P, at least, is
    admitted."""
    from analytic import hertz, mindlin
    from reports.run.plan import plan_case
    from reports.run.runner import execute
    from reports.run.sweep import sweep_points

    name = ("fretting_orthotropic" if held == "approach"
            else Path(__file__).resolve().parents[1] / "cases" / "examples"
            / "fretting_orthotropic_load.toml")
    friction = [("friction.mu1", [mu1]), ("friction.mu2", [min(mu1 * ratio, 1.0)]),
                ("friction.beta", [beta])]
    (base,), _ = sweep_points(name, friction, quick=True)
    h = (hertz.hertz(base.load.P, base.R, base.E_star) if base.load.load_controlled
         else hertz.hertz_from_approach(base.load.approach, base.R, base.E_star))
    amplitude = slip * mindlin.gross_slip_shift(base.sliding_friction, h.P, h.a, base.a.G,
                                                base.a.nu, base.b.G, base.b.nu)
    assume(abs(slip - 1.0) > 0.15)  # not at the threshold, where a node or cell decides
    overrides = {"fretting.amplitude": amplitude, "fretting.cycles": 1000,
                 "fretting.output_cycles": [500, 1000]}
    (case,), sweep = sweep_points(name, friction, quick=True, overrides=overrides)
    plan = plan_case(name, ["ic", "fem"], quick=True, overrides=overrides, points=[case],
                     sweep=sweep, dir_name="generated")
    assert [p.study.name for p in plan.studies] == ["probe"]
    assert len(plan.study_runs()) == 1
    run = execute(plan, tmp_path_factory.mktemp("probe"), progress=False)
    assert not run.failures, run.failures
    m = run.metrics[run.metrics["pair"] == "ic-fem"]
    gated = m[m["status"] == "gated"]
    shown = m[m["note"].str.contains("resolution probe: ", na=False)]
    print(f"\nmu = ({mu1:.3f}, {case.friction.mu2:.3f}), beta = {beta:.1f}, amplitude "
          f"{slip:.2f} delta*, {held} held: {len(gated)} gated, {len(shown)} shown by the "
          f"probe ({', '.join(sorted(set(shown['quantity'])))})")
    assert "P" in set(gated["quantity"])
    failed = gated[~gated["passed"]]
    assert failed.empty, failed[["cycle", "quantity", "metric", "value", "tolerance"]
                                ].to_string()
