"""Solver plugins by entry point (reports/registry/plugins.py): the example plugin of
``docs/examples/solver_plugin`` installed as a distribution (its package and a
``.dist-info`` with ``entry_points.txt`` on the path) is listed, run, compared with the
built-in solvers, reported and gated; a wrong one fails the gate; a broken one is left
out with one line naming it and the built-in chain runs unchanged."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest
from plugin_site import reload_registry, write_distribution

from reports.cli import main
from reports.registry import solvers
from reports.render.pages import report_text
from reports.store import layout

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "docs" / "examples" / "solver_plugin"
ENTRY = "hertz_example = hertz_example:record"
RUN = ["run", "hertz", "--quick", "--no-progress"]


def _site(tmp_path: Path, entry: str, edit: tuple[str, str] | None) -> Path:
    """The example distribution installed into a directory of its own (what pip writes:
    the package and its .dist-info with the entry point)."""
    site = tmp_path / "site"
    shutil.copytree(EXAMPLE / "hertz_example", site / "hertz_example")
    if edit is not None:
        module = site / "hertz_example" / "__init__.py"
        text = module.read_text()
        assert edit[0] in text
        module.write_text(text.replace(*edit))
    write_distribution(site, "contact-vv-hertz-example", entry)
    return site


@pytest.fixture
def install(tmp_path, monkeypatch):
    """``install(entry=ENTRY, edit=None) -> lines left out``: the example installed and the
    registry loaded again as at import (the built-in records, then the plugins found)."""
    def _install(entry: str = ENTRY, edit: tuple[str, str] | None = None) -> list[str]:
        site = _site(tmp_path, entry, edit)
        monkeypatch.delitem(sys.modules, "hertz_example", raising=False)
        return reload_registry(monkeypatch, site)
    return _install


def _metrics(out: Path) -> pd.DataFrame:
    return pd.read_csv(out / "hertz" / "metrics.csv")


def test_plugin_is_run_compared_reported_and_gated(tmp_path, install, capsys):
    assert install() == []
    assert main(["list"]) == 0
    assert "solver hertz_example available (plugin: runs only when named)" in \
        capsys.readouterr().out
    out = tmp_path / "res"
    assert main([*RUN, "--solver", "hertz_example,ic,analytic", "--out", str(out)]) == 0
    m = _metrics(out)
    ours = m[m["pair"].str.startswith("hertz_example-")]
    # the plugin is the first of its pairs: the built-in solvers are its references
    assert set(ours["pair"]) == {"hertz_example-ic", "hertz_example-analytic"}
    gated = ours[ours["status"] == "gated"]
    assert {"p_max", "contact_area", "a_x", "p_n"} <= set(gated["quantity"])
    assert gated["passed"].all()
    p_max = gated[(gated["pair"] == "hertz_example-analytic") & (gated["quantity"] == "p_max")]
    assert p_max["value"].abs().max() < 1e-12  # the same closed form
    assert main(["report", "--out", str(out)]) == 0
    assert "hertz_example-ic" in report_text(out)
    assert main(["gate", "--out", str(out)]) == 0


def test_a_wrong_plugin_fails_the_gate(tmp_path, install, capsys):
    install(edit=("SCALE = 1.0", "SCALE = 1.1"))
    out = tmp_path / "res"
    assert main([*RUN, "--solver", "hertz_example,ic,analytic", "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["gate", "--out", str(out)]) == 1
    fails = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("FAIL")]
    assert any("hertz_example-analytic p_max rel" in f for f in fails)
    assert any("hertz_example-ic p_max rel" in f for f in fails)
    assert not any(" ic-analytic " in f for f in fails)


def test_a_plugin_step_no_comparison_reads_fails_the_gate(tmp_path, install, capsys):
    """Issue 59: a plugin that writes a step the case does not have (here a copy of its
    step numbered 1, 20 % high) is compared nowhere: the gate names it (UNCOMPARED)."""
    extra = ("steps=[step, StepResult(scalars={**step.scalars, 'step': 1.0}, x=x, y=y, "
             "surface={'p_n': 1.2 * p_n})])")
    install(edit=("steps=[step])", extra))
    out = tmp_path / "res"
    assert main([*RUN, "--solver", "hertz_example,ic,analytic", "--out", str(out)]) == 0
    capsys.readouterr()
    assert main(["gate", "--out", str(out)]) == 1
    lines = [ln for ln in capsys.readouterr().out.splitlines() if "UNCOMPARED" in ln]
    assert len(lines) == 1 and "hertz step 1" in lines[0] and "hertz_example" in lines[0], lines


@pytest.mark.parametrize("entry, edit, why", [
    ("hertz_example = no_such_package:record", None, "cannot load it: ModuleNotFoundError"),
    ("hertz_example = hertz_example:budget", None, "cannot load it: TypeError"),
    ("hertz_example = hertz_example:SCALE", None, "gives a float, not a"),
    ("ic = hertz_example:record", None, "taken by a built-in solver"),
    ("hertz-example = hertz_example:record", None, "lower-case letters, digits and '_'"),
    ("other = hertz_example:record", None, "its record is named 'hertz_example'"),
    (ENTRY, ("import math\n", "import math\nraise RuntimeError('half installed')\n"),
     "cannot load it: RuntimeError: half installed"),
])
def test_a_broken_plugin_is_left_out_naming_it(tmp_path, install, capsys, entry, edit, why):
    clean = tmp_path / "clean"
    assert main([*RUN, "--solver", "ic,analytic", "--out", str(clean)]) == 0
    errors = install(entry, edit)
    assert len(errors) == 1 and why in errors[0]
    assert errors[0].startswith(f"solver plugin {entry.split(' = ')[0]!r}")
    assert "hertz_example" not in solvers.names()
    capsys.readouterr()
    out = tmp_path / "res"
    assert main([*RUN, "--solver", "ic,analytic", "--out", str(out)]) == 0
    err = capsys.readouterr().err.splitlines()
    assert [ln for ln in err if "plugin" in ln] == [f"contact-vv: warning: {errors[0]}"]
    keys = ["pair", "quantity", "metric", "step"]
    got = _metrics(out).sort_values(keys).reset_index(drop=True)
    want = _metrics(clean).sort_values(keys).reset_index(drop=True)
    pd.testing.assert_frame_equal(got, want)


def test_a_plugin_whose_supports_raises_is_skipped_there(tmp_path, install):
    install(edit=('    f = case.friction\n', '    raise KeyError("mu3")\n'))
    out = tmp_path / "res"
    assert main([*RUN, "--solver", "hertz_example,ic,analytic", "--out", str(out)]) == 0
    skipped = json.loads((out / "hertz" / layout.MANIFEST).read_text())["skipped"]
    assert skipped["hertz_example"].startswith(
        "solver plugin 'hertz_example': supports() raised KeyError: 'mu3'")
    assert set(_metrics(out)["pair"]) == {"ic-analytic"}


def test_the_console_script_loads_plugins_at_start(tmp_path):
    """A fresh process: the entry points are read when the registry is imported."""
    env = dict(os.environ)
    for entry, expect in ((ENTRY, "solver hertz_example available (plugin: runs only when named)"),
                          ("hertz_example = gone:record", "contact-vv: warning: solver "
                           "plugin 'hertz_example' (gone:record of contact-vv-hertz-example "
                           "0.1.0) left out: cannot load it")):
        shutil.rmtree(tmp_path / "site", ignore_errors=True)
        site = _site(tmp_path, entry, None)
        env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(site), env.get("PYTHONPATH")]))
        done = subprocess.run([sys.executable, "-m", "reports", "list"], env=env,
                              capture_output=True, text=True, cwd=tmp_path, timeout=120)
        assert done.returncode == 0
        assert expect in done.stdout + done.stderr
        assert "solver ic        available" in done.stdout


def test_silenced_keeps_a_peers_output_out_and_restores_it(capfd):
    """What a peer code writes to file descriptors 1 and 2 inside ``silenced`` is not in
    the run's output; both descriptors write again after it, also after an error."""
    import os

    from reports.registry.plugins import silenced

    with pytest.raises(RuntimeError), silenced():
        os.write(1, b"banner\n")
        os.write(2, b"log line\n")
        raise RuntimeError("the peer failed")
    os.write(1, b"after\n")
    out, err = capfd.readouterr()
    assert "banner" not in out and "log line" not in err and "after" in out
