"""The gate's lines and ``contact-vv list`` (issue 76, points 6 and 7): a case's line
names as "not run" only the solvers the run was asked for (or that run by default) and
did not run — not the plugins nobody named nor the metamorphic relations that do not
apply; each problem is printed once; ``list`` names every bundled plugin, installed or
not, with how to get it and what it models.  Found on a green default chain: every case
line ended in "not run: contactmechanics, ic+axes90, ic+axes180, ic+mirror, ic+turned,
tamaas, tamaas_periodic", and kratos was not listed."""

from __future__ import annotations

from pathlib import Path

import pytest
from test_cli_hostile_inputs import TINY

from reports.cli import main
from reports.registry import solvers
from reports.store import manifest


@pytest.fixture(scope="module")
def chain(tmp_path_factory) -> Path:
    """TINY (coarse: some rows fail) by ic and analytic at --quick (the relations come
    with ic and decline the case), and a frictional case naming contactmechanics (which
    declines friction)."""
    out = tmp_path_factory.mktemp("quiet") / "out"
    (out.parent / "t.toml").write_text(TINY)
    (out.parent / "f.toml").write_text('name = "f"\n' + TINY.replace(
        "P = 10.2", "P = 10.2\nQx = 0.1") + "[friction]\nmu = 0.3\n")
    assert main(["run", str(out.parent / "t.toml"), "--quick", "--solver", "ic,analytic",
                 "--no-progress", "--out", str(out)]) in (0, 1)
    main(["run", str(out.parent / "f.toml"), "--quick", "--solver",
          "ic,analytic,contactmechanics", "--no-progress", "--out", str(out)])
    return out


def _case_line(text: str, name: str) -> str:
    return next(x for x in text.splitlines() if x.startswith(f"  {name}: "))


def test_not_run_names_only_what_was_asked_for(chain, capsys):
    relations = [s for s in solvers.names() if solvers.record(s).base]
    assert set(relations) <= set(manifest.read(chain / "t")["skipped"])  # all declined
    main(["gate", str(chain)])
    out = capsys.readouterr().out
    assert "not run" not in _case_line(out, "t")
    line = _case_line(out, "f")
    assert line.endswith("; not run: contactmechanics"), line


def test_each_problem_is_printed_once(chain, capsys):
    """The coarse chain's failed rows: each once, on standard output with the verdict;
    the error line counts them (they were repeated, one error line each)."""
    assert main(["gate", str(chain)]) == 1
    captured = capsys.readouterr()
    fails = [x for x in captured.out.splitlines() if x.startswith("FAIL ")]
    assert fails and len(set(fails)) == len(fails)
    assert "FAIL " not in captured.err
    assert [x for x in captured.err.splitlines() if x.startswith("contact-vv: error:")] == [
        f"contact-vv: error: the gate found {len(fails)} problem(s), each listed above"]


def test_every_solver_skipped_is_still_said_with_verbose(chain, capsys):
    main(["gate", str(chain), "--verbose"])
    out = capsys.readouterr().out
    for s in manifest.read(chain / "t")["skipped"]:
        assert f"note: t: solver {s} not run (" in out


def test_a_manifest_without_not_run_reads_every_skipped_solver(chain):
    from reports.store.results import scan

    case = next(c for c in scan(chain).complete if c.name == "t")
    old = dict(case.manifest)
    old.pop("not_run")
    assert type(case)(case.path, old, case.summary, case.metrics).not_run == old["skipped"]


def test_list_names_every_bundled_plugin_with_its_state_and_scope(capsys):
    code = main(["list"])
    out = capsys.readouterr().out
    assert code == 0
    for name in ("tamaas", "tamaas_periodic", "contactmechanics", "kratos", "calculix"):
        line = next(x for x in out.splitlines() if x.startswith(f"solver {name} "))
        ok, reason = solvers.available(name)
        assert ("available" in line) if ok else ("pip install" in line or "apt-get" in line)
        scope = out.splitlines()[out.splitlines().index(line) + 1]
        assert scope.strip().startswith("models ") and "declines" in scope
