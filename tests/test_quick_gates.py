r"""The CI accuracy gates (issue 5, item 6) and the regression baselines.

Every bundled case runs in its quick variant through the half-space solver and the
analytic references, and hertz, cattaneo_mindlin, sliding_friction, pin_on_disk,
pin_on_disk_orthotropic and dissimilar also through the FEM reference, exactly as
``contact-vv run`` does it; every tolerance of ``metrics.csv`` must hold (``contact-vv
gate`` exits 0), the report must show every case, and the key numbers must not drift
from ``tests/baselines/*.csv``
(relative drift 1e-6: the runs are deterministic, tests/test_determinism.py).  Update
the baselines explicitly with

    contact-vv run --all --quick --solver ic,analytic --out results
    contact-vv run hertz cattaneo_mindlin sliding_friction pin_on_disk \
        pin_on_disk_orthotropic dissimilar --quick --out results
    contact-vv gate --out results --update-baseline tests/baselines

The FEM runs fretting only on request (tests/test_fem_fretting.py checks its first cycle).
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

from cases.loader import BUNDLED
from reports.cli import main
from reports.store import layout

BASELINES = Path(__file__).resolve().parent / "baselines"
WITH_FEM = ("hertz", "cattaneo_mindlin", "sliding_friction", "pin_on_disk",
            "pin_on_disk_orthotropic", "dissimilar")


@pytest.fixture(scope="module")
def quick(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("quick") / "results"
    assert main(["run", "--all", "--quick", "--solver", "ic,analytic", "--no-progress",
                 "--out", str(out)]) == 0
    assert main(["run", *WITH_FEM, "--quick", "--no-progress", "--out", str(out)]) == 0
    return out


def test_every_case_ran(quick):
    """Every bundled case is complete with the IC (and the FEM where run) beside its
    references."""
    for name in BUNDLED:
        summary = pd.read_csv(quick / name / layout.SUMMARY)
        solvers = set(summary["solver"])
        assert "ic" in solvers, name
        if name in WITH_FEM:
            assert "fem" in solvers, name
            assert "ic-fem" in set(pd.read_csv(quick / name / layout.METRICS)["pair"])


def test_gate_passes(quick, capsys):
    code = main(["gate", "--out", str(quick)])
    out = capsys.readouterr().out
    assert code == 0, out


def test_report_has_every_case(quick):
    assert main(["report", "--out", str(quick)]) == 0
    html = (quick / "index.html").read_text()
    for name in BUNDLED:
        assert name in html


def test_no_drift_from_the_baselines(quick, capsys):
    code = main(["gate", "--out", str(quick), "--baseline", str(BASELINES)])
    out = capsys.readouterr().out
    assert code == 0, "\n".join(ln for ln in out.splitlines() if ln.startswith("DRIFT"))
