"""ContactMechanics verified through the suite's own gates (contactmechanics_adapter;
the [peers] extra, part of the test extra): the chain of issue 49 (run, report, gate)
with its rows, the cases it does not model declined with the reason, a seeded adapter
defect caught, generated normal-contact cases nobody bundled, and nothing offered
without it."""

from __future__ import annotations

import importlib.util
import json

import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings

pytest.importorskip("ContactMechanics")  # the test extra installs it

from case_generator import user_case  # noqa: E402
from vv_testing import load_bundled  # noqa: E402

import contactmechanics_adapter  # noqa: E402
from reports.cli import main  # noqa: E402
from reports.registry import plugins, solvers  # noqa: E402
from reports.render.pages import report_text
from reports.store import layout  # noqa: E402

SOLVERS = "ic,analytic,contactmechanics"


def ours(out, case):
    m = pd.read_csv(out / case / layout.METRICS)
    return m[m["pair"].str.startswith("contactmechanics-") & (m["status"] == "gated")]


def test_the_chain_of_the_issue(tmp_path, capsys):
    """``run hertz dissimilar --quick --solver ic,analytic,contactmechanics``: Hertz's
    pressure, load, peak and extent gated against the half-space solver and the closed
    form, all passing; the frictional dissimilar case declined with the reason."""
    out = tmp_path / "res"
    assert main(["run", "hertz", "dissimilar", "--quick", "--no-progress", "--solver",
                 SOLVERS, "--out", str(out)]) == 0
    rows = ours(out, "hertz")
    assert {"p_n", "P", "p_max", "a_x", "contact_area"} <= set(rows["quantity"])
    assert {"contactmechanics-ic", "contactmechanics-analytic"} == set(rows["pair"])
    assert rows["passed"].all(), rows[~rows["passed"]]
    # the same discretisation as the half-space solver's (cells, E*, the profile at
    # their centres): the peak agrees to its tolerance, not to a grid error
    peak = rows[(rows["pair"] == "contactmechanics-ic") & (rows["quantity"] == "p_max")]
    assert float(peak["value"].iloc[0]) < 1e-6
    skipped = json.loads((out / "dissimilar" / layout.MANIFEST).read_text())["skipped"]
    assert "frictionless normal contact only" in skipped["contactmechanics"]
    assert main(["report", str(out)]) == 0
    assert "contactmechanics-analytic" in report_text(out)
    capsys.readouterr()
    assert main(["gate", str(out)]) == 1  # dissimilar: ic alone, nothing compared
    said = capsys.readouterr()
    assert "NO METRICS dissimilar" in said.out + said.err
    assert not [ln for ln in said.out.splitlines() if ln.startswith("FAIL")]


def test_the_gate_catches_a_wrong_modulus(tmp_path, monkeypatch, capsys):
    """Seeded adapter defect: the half-space given body a's E instead of the pair's E*."""
    monkeypatch.setattr(contactmechanics_adapter, "contact_modulus", lambda case: case.a.E)
    out = tmp_path / "res"
    assert main(["run", "hertz", "--quick", "--no-progress", "--solver", SOLVERS,
                 "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["gate", str(out)]) == 1
    failed = ours(out, "hertz")
    assert {"p_max", "p_n"} <= set(failed.loc[~failed["passed"], "quantity"])


def test_declined_cases_say_why_and_it_runs_only_when_named():
    case = load_bundled("hertz", quick=True)
    assert solvers.not_by_default("contactmechanics", case) is not None
    assert solvers.unsupported("contactmechanics", case) is None
    for name, why in (("cattaneo_mindlin", "tangential load"),
                      ("pin_on_disk", "no wear law"), ("fretting_isotropic", "no wear law"),
                      ("sliding_friction", "tangential load")):
        assert why in solvers.unsupported("contactmechanics", load_bundled(name, quick=True))


def test_no_contactmechanics_the_plugin_is_offered_unavailable(monkeypatch):
    """Without the extra the entry points offer their records, unavailable with how to
    get them (``contact-vv list`` names them; issue 76, point 7), and say nothing else."""
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name == "ContactMechanics" else real(name, *a))
    builtin = {k: v for k, v in solvers.REGISTRY.items() if k not in solvers.PLUGINS}
    found, errors = plugins.load(builtin)
    assert errors == []
    assert "ContactMechanics is not installed: pip install 'contact-vv[peers]'" in \
        found["contactmechanics"].requires()


@settings(max_examples=10, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(text=user_case(kinds=("hertz", "dissimilar")))
def test_contactmechanics_passes_the_gate_on_cases_nobody_bundled(text, tmp_path_factory):
    """Generated normal contacts (tests/case_generator.py: other R, P, E, ν, grids, the
    load or the approach held): every gated row passes at the default tolerances where
    it models the case and converges; elsewhere it says why and the others run.  Its
    displacement-controlled solve (the approach held) stalls on some draws, where it
    says so (benchmarks/README.md, "ContactMechanics through the gates"): under the load
    it always converged."""
    from cases import load_case

    tmp = tmp_path_factory.mktemp("case")
    (tmp / "user.toml").write_text(text)
    case = load_case(tmp / "user.toml")[0]
    if contactmechanics_adapter.supports(case) is None:
        try:
            contactmechanics_adapter.solve(case)
        except RuntimeError as exc:
            assert "did not converge" in str(exc) and case.load.P is None, text
            return
    out = tmp / "res"
    assert main(["run", str(tmp / "user.toml"), "--solver", SOLVERS, "--no-progress",
                 "--out", str(out)]) == 0
    assert main(["gate", str(out)]) == 0, text
    skipped = json.loads((out / "user" / layout.MANIFEST).read_text())["skipped"]
    assert ("contactmechanics" in skipped) == ours(out, "user").empty, text
