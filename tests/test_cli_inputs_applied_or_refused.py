"""Every input is applied or refused, and every number in the domain the formulas compute
in (issue 31): a key a case of that kind does not use, a sweep of the run's own tables, a
flag that would do nothing, a Hertz scale or cycle count outside the floats, a cycle
count the jump grid would mislabel.  Each refusal is one ``contact-vv: error:`` line
naming the key, exit 2, nothing written (the harness of tests/test_cli_hostile_inputs.py);
the valid inputs that used to fail now run.
"""

from __future__ import annotations

import pandas as pd
import pytest
from test_cli_hostile_inputs import FRET, SWEEP, TINY, WEAR, _answer, _set, hang_guard  # noqa: F401

from reports.store import layout

# (id, case-file text, extra argv, needle in the one error line)
REFUSED = [
    # the Hertz scales a0, p0 (and a0⁴, p0²) outside the normal floats
    ("P-subnormal", _set(TINY, "P = 10.2", "P = 5e-324"), [], "load.P = 5e-324"),
    ("E-huge", TINY.replace("E = 210000.0", "E = 1e300"), [], "the Hertz a0 = "),
    ("approach-tiny", _set(TINY, "P = 10.2", "approach = 1e-300"), [],
     "load.approach = 1e-300"),
    ("R-huge-P-huge", _set(_set(TINY, "R = 50.0", "R = 1e300"), "P = 10.2", "P = 1e300"), [],
     "the Hertz"),
    # cycles / jump not a finite number
    ("jump-subnormal", _set(FRET, "jump = 1.0", "jump = 5e-324"), [], "fretting.jump = 5e-324"),
    ("jump-tiny", _set(FRET, "jump = 1.0", "jump = 1e-310"), [], "fretting.jump = 1e-310"),
    ("jump-tiny-cycles-big", _set(_set(FRET, "jump = 1.0", "jump = 1e-308"), "cycles = 2",
                                  "cycles = 1000000"), [], "fretting.jump = 1e-308"),
    # load keys a kind of case has no use for
    ("static-wear-spread", TINY.replace("[grid]", "[solver]\nwear_spread = 0.01\n\n[grid]"),
     [], "solver.wear_spread = 0.01: a case without wear does not use it"),
    ("fretting-Qx", _set(FRET, "approach = 0.001", "approach = 0.001\nQx = 1.0"), [],
     "load.Qx = 1.0: a fretting case does not use it"),
    ("fretting-sliding", _set(FRET, "approach = 0.001", "approach = 0.001\nsliding = true"),
     [], "load.sliding = True: a fretting case does not use it"),
    ("fretting-shift", _set(FRET, "approach = 0.001", "approach = 0.001\nshift_y = 0.001"),
     [], "load.shift_y = 0.001"),
    ("wear-Qy", _set(WEAR, "P = 10.2", "P = 10.2\nQy = 0.5"), [],
     "load.Qy = 0.5: a sliding_wear case does not use it"),
    ("wear-shift", _set(WEAR, "P = 10.2", "P = 10.2\nshift_x = 0.001"), [], "load.shift_x"),
    ("static-angle", _set(TINY, "P = 10.2", "P = 10.2\nslide_angle = 30.0"), [],
     "load.slide_angle = 30.0: only used with load.sliding = true"),
    ("static-angle-with-Q", TINY.replace("P = 10.2", "P = 10.2\nQx = 0.5\nslide_angle = 90.0")
     + "[friction]\nmu = 0.3\n", [], "load.slide_angle = 90.0"),
    # a sweep of the run's own tables, or of a quick key the run never applies
    ("sweep-name", TINY + '[sweep]\nkey = "name"\nvalues = ["a", "b"]\n', [],
     "sweep.key = 'name'"),
    ("sweep-sweep", TINY + '[sweep]\nkey = "sweep.key"\nvalues = ["a", "b"]\n', [],
     "sweep.key = 'sweep.key'"),
    ("sweep-quick", TINY + '[sweep]\nkey = "quick.grid.nx"\nvalues = [5, 7]\n', [],
     "sweep.key = 'quick.grid.nx'"),
    ("quick-sweep-key", SWEEP + '[quick]\n"sweep.key" = "grid.nx"\n', ["--quick"],
     "quick.'sweep.key'"),
    ("quick-name", TINY + '[quick]\nname = "other"\n', [], "quick.'name'"),
    ("quick-quick", TINY + '[quick]\n"quick.grid.nx" = 5\n', [], "quick.'quick.grid.nx'"),
    # string sweep values whose field directories would be one
    ("sweep-slash-underscore", TINY + '[sweep]\nkey = "description"\nvalues = ["a/b", "a_b"]\n',
     [], "would share the field directory description=a_b/"),
    ("sweep-space-tab", TINY + '[sweep]\nkey = "description"\nvalues = ["a b", "a\\tb"]\n', [],
     "would share the field directory"),
    ("sweep-unicode", TINY + '[sweep]\nkey = "description"\nvalues = ["é", "ü"]\n', [],
     "would share the field directory"),
    ("sweep-too-long", TINY + f'[sweep]\nkey = "description"\nvalues = ["{"x" * 300}"]\n', [],
     "too long to name a directory"),
    # tolerance pairs compared in the other order, or never compared
    ("pair-reversed", TINY + '[tolerances]\n"analytic-ic.p_max" = 0.1\n', [],
     "'analytic-ic' is not a compared pair"),
    ("pair-relation-reversed", TINY + '[tolerances]\n"ic+axes90-ic.p_max" = 0.1\n', [],
     "'ic+axes90-ic' is not a compared pair"),
    ("pair-two-relations", TINY + '[tolerances]\n"ic+axes90-ic+mirror.p_max" = 0.1\n', [],
     "is not a compared pair"),
    ("pair-fem-order", TINY + '[tolerances]\n"analytic-fem.p_max" = 0.1\n', [],
     "'analytic-fem' is not a compared pair"),
    # no σ_VM maximum gated at all
    ("nc-both-maxima", TINY + '[not_converged]\nvm_max = "x"\nvm_max_below = "y"\n', [],
     "not_converged: vm_max and vm_max_below both declared"),
    # the FEM's contact solve: an unknown one, and a penalty the chosen one has not
    ("fem-contact-unknown", TINY + '[fem]\ncontact = "newton"\n', [], "fem.contact"),
    ("fem-penalty-semismooth", TINY + '[fem]\npenalty = 10.0\n', [],
     "fem.penalty applies to fem.contact = 'augmented' only"),
    # flags and solvers that would do nothing
    ("convergence-closed-form", TINY, ["--solver", "analytic", "--convergence"],
     "--convergence: no run has a grid to refine"),
    ("convergence-closed-form-fretting", FRET + "output_cycles = [1]\n",
     ["--solver", "analytic", "--convergence"], "--convergence: no run has a grid to refine"),
    ("all-decline-fretting", FRET, ["--solver", "analytic"], "none of the solvers analytic runs"),
    ("all-decline-jump", _set(FRET, "cycles = 2", "cycles = 4").replace(
        "jump = 1.0", "jump = 2.0"), ["--solver", "analytic"], "none of the solvers analytic"),
    ("all-decline-wear", _set(WEAR, "[friction]\nmu = 0.3\n", "[friction]\nmu = 0.3\n")
     .replace("[materials.b]", "i1 = 1e-7\n[materials.b]").replace(
         'E = 210000.0\nnu = 0.3\n[', 'E = 70000.0\nnu = 0.3\n[', 1),
     ["--solver", "analytic"], "none of the solvers analytic runs"),
]


@pytest.mark.parametrize(("text", "extra", "needle"), [c[1:] for c in REFUSED],
                         ids=[c[0] for c in REFUSED])
def test_refused_with_the_key_named(tmp_path, capsys, hang_guard, text, extra, needle):  # noqa: F811
    case = tmp_path / "case.toml"
    case.write_text(text)
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    argv = ["run", str(case), "--out", str(out), "--no-progress"]
    code, err = _answer(argv + (extra if "--solver" in extra else ["--solver", "ic", *extra]),
                        capsys)
    assert code == 2, err
    lines = [line for line in err.splitlines() if line.startswith("contact-vv: error:")]
    assert len(lines) == 1 and needle in lines[0], err
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == before
    assert (out / "notes.txt").read_text() == "mine"


@pytest.mark.parametrize(("cycles", "jump", "simulated"), [(21, 1.4, 15), (21, 0.7, 30),
                                                           (69, 2.3, 30), (33, 2.2, 15)])
def test_a_cycle_count_on_the_jump_grid_is_simulated_once(tmp_path, capsys, cycles, jump,
                                                           simulated):
    """cycles / jump a whole number only up to rounding (21 / 1.4 = 15.000000000000002,
    33 / 2.2 = 14.999999999999998): that many cycles simulated, one output step, labelled
    with the cycle count."""
    assert cycles / jump != simulated  # the floats do not divide exactly
    case = tmp_path / "case.toml"
    case.write_text(_set(_set(FRET, "cycles = 2", f"cycles = {cycles}"), "jump = 1.0",
                         f"jump = {jump}"))
    out = tmp_path / "out"
    code, err = _answer(["run", str(case), "--out", str(out), "--no-progress", "--solver", "ic"],
                        capsys)
    assert code == 0, err
    summary = pd.read_csv(out / "case" / layout.SUMMARY)
    assert summary[["step", "cycle"]].values.tolist() == [[simulated, cycles]]
    cycles_table = pd.read_csv(out / "case" / layout.FIELDS / "ic" / "base" / "cycles.csv")
    assert len(cycles_table) == simulated
    assert cycles_table["cycle"].iloc[-1] == cycles


@pytest.mark.parametrize("description", ["two\nlines", 'quote " and back\\slash',
                                         "tab\there and del \x7f", "ünïcödé ✓"])
def test_a_sweep_of_any_description_runs(tmp_path, capsys, description):
    """The case file the sweep writes for its workers carries any string the case did."""
    import json

    case = tmp_path / "case.toml"
    text = json.dumps(description, ensure_ascii=True)
    case.write_text(_set(TINY, 'description = "small Hertz for tests"',
                         f"description = {text}") + "[friction]\nmu = 0.2\n")
    code, err = _answer(["sweep", str(case), "--param", "friction.mu=0.2,0.3", "--workers", "0",
                         "--solver", "ic", "--out", str(tmp_path / "o"), "--no-progress"],
                        capsys)
    assert code == 0, err
    summary = pd.read_csv(tmp_path / "o" / "case__sweep_mu" / layout.SUMMARY)
    assert len(summary) == 2


@pytest.mark.parametrize(("argv", "needle"), [
    (["--set", "tolerances.nope=0.1"], "unknown tolerance key 'nope'"),
    (["--set", "tolerances.analytic-ic.p_max=0.1"], "'analytic-ic' is not a compared pair"),
    (["--set", "not_converged.nope=x"], "not_converged.nope: unknown quantity"),
])
def test_threshold_refuses_the_keys_a_run_refuses(tmp_path, capsys, argv, needle):
    code, err = _answer(["threshold", "sliding_friction", "--param", "friction.mu", "--event",
                         "vm_max_on_surface", "--quick", "--no-progress", "--solver", "analytic",
                         "--grids", "1", "--out", str(tmp_path / "o"), *argv], capsys)
    assert code == 2 and needle in err, err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("address", ["127.0.0.1:notaport", "nonsense://x", "tcp://[::1"])
def test_a_scheduler_address_that_is_not_one(tmp_path, capsys, address):
    case = tmp_path / "case.toml"
    case.write_text(TINY + "[friction]\nmu = 0.2\n")
    code, err = _answer(["sweep", str(case), "--param", "friction.mu=0.2,0.3", "--scheduler",
                         address, "--solver", "ic", "--out", str(tmp_path / "o"),
                         "--no-progress"], capsys)
    assert code == 2, err
    assert f"--scheduler {address!r}" in err or f"Dask scheduler {address}" in err, err
