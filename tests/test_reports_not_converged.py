"""Quantities that are not converged numbers are compared and shown, not gated
(reports/registry/tolerances.py): the ``[not_converged]`` declaration a case file may
still make, its checks, the gate and the report; and on the bundled worn pin, measured,
what the comparisons decide by themselves: its surface σ_VM maximum grows without limit
and its companion below a quarter of the contact radius converges
(reports/compare/maxima.py)."""

from __future__ import annotations

import io

import numpy as np
import pytest
import test_cli_fakes as fakes
from test_cli_run import HERTZ, write_case

from cases.loader import load_case
from cases.result import vm_max_below
from reports.cli import main
from reports.compare.maxima import below_depth
from reports.registry.solvers import resolve
from reports.render.gate import run_gate
from reports.render.pages import report_text
from reports.store import layout
from reports.store.readers import read_metrics

SKEW = 0.3  # relative error the fake solver below puts on p_max only

DECLARED = HERTZ + """\
[not_converged]
p_max = "made up for the test: 1.0 / 1.1 / 1.2 MPa on three grids"
"""


def supports_all(case):
    return None


def solve_skewed(case, *, progress=False, on_output=None):
    """The exact fake fields; only the p_max scalar is off by SKEW."""
    result = fakes.solve_exact(case)
    for step in result.steps:
        step.scalars["p_max"] *= 1.0 + SKEW
    return result


@pytest.fixture
def skewed(monkeypatch):
    fakes.use(monkeypatch, ic="solve_exact", analytic="solve_exact")
    from dataclasses import replace

    from reports.registry import solvers

    rec = replace(solvers.REGISTRY["ic"], package=__name__, solve_attr="solve_skewed")
    monkeypatch.setitem(solvers.REGISTRY, "ic", rec)


def run(*argv: str) -> int:
    return main(["run", "--no-progress", *argv])


def test_a_declared_quantity_is_shown_not_gated(tmp_path, skewed):
    out = tmp_path / "res"
    assert run(str(write_case(tmp_path, DECLARED)), "--out", str(out)) == 0
    m = read_metrics(out / "small" / layout.METRICS)
    p = m[m["quantity"] == "p_max"].iloc[0]
    assert p["value"] == pytest.approx(SKEW / (1.0 + 0.0), rel=1e-9)  # compared, written
    assert p["status"] == "not gated" and p["note"].startswith("declared: made up")
    assert p["reason"] == "declared" and (m.loc[m["status"] == "gated", "reason"] == "").all()
    stream = io.StringIO()
    assert run_gate(out, stream=stream, verbose=True) == 0
    printed = stream.getvalue()
    (line,) = [x for x in printed.splitlines() if x.startswith("  small: ")]  # by default
    assert line.startswith("  small: 13/13 passed, ") and "declared 1" in line, line
    assert "NOT GATED small ic-analytic p_max rel (1 row(s), largest 0.3 at step 0): " \
        "declared: made up" in printed
    assert main(["report", "--out", str(out)]) == 0
    html = report_text(out)
    assert "Shown and not gated" in html and "made up for the test" in html
    # a metrics.csv an earlier release wrote ("not converged" for a row not gated)
    path = out / "small" / layout.METRICS
    path.write_text(path.read_text().replace(",not gated,", ",not converged,"))
    assert ",not converged," in path.read_text()
    old = read_metrics(path)
    assert (old["status"] == m["status"]).all() and (old["status"] == "not gated").sum() == 3


def test_the_same_error_fails_the_gate_when_not_declared(tmp_path, skewed, capsys):
    out = tmp_path / "res"
    case = write_case(tmp_path, DECLARED.split("[not_converged]")[0])
    assert run(str(case), "--out", str(out)) == 0
    assert main(["gate", "--out", str(out)]) == 1
    assert "FAIL small step 0 ic-analytic p_max rel = 0.3 > tolerance 0.035" in \
        capsys.readouterr().out


@pytest.mark.parametrize("edit, message", [
    (lambda t: t + "[tolerances]\np_max = 0.2\n",
     "tolerances.p_max: 'p_max' is declared not converged"),
    (lambda t: t + '[tolerances]\n"ic-fem.p_max" = 0.2\n',
     "tolerances.ic-fem.p_max: 'p_max' is declared not converged"),
    (lambda t: t.replace("p_max = \"made", "p_maxx = \"made"),
     "not_converged.p_maxx: unknown quantity"),
    (lambda t: t.replace('"made up for the test: 1.0 / 1.1 / 1.2 MPa on three grids"',
                         '"  "'), "not_converged.p_max = '  ': must be a non-empty"),
    (lambda t: t.replace("nz = 11", "nz = 11\nz_below = 0.5"),
     "stress.z_below = 0.5: must lie in (0, stress.depth = 0.3] mm"),
])
def test_declarations_are_checked(tmp_path, skewed, capsys, edit, message):
    case = write_case(tmp_path, edit(DECLARED))
    assert run(str(case), "--out", str(tmp_path / "res")) == 2
    assert message in capsys.readouterr().err


# ------------------------------------------------------------------ the bundled worn pin


def _pin(n: int) -> list[dict]:
    """The quick worn pin at μ = 0.5 on an n² grid: per output step, its surface maximum
    and the companion the comparisons gate, the maximum from a quarter of the contact
    radius down (reports.compare.maxima.below_depth; the two-cell floor is the coarse
    grid's)."""
    case = load_case("pin_on_disk", quick=True, overrides={"grid.nx": n, "grid.ny": n})[1]
    assert case.friction.mu1 == 0.5 and not case.not_converged
    out = []
    for step in resolve("ic")(case).steps:
        sc = dict(step.scalars)
        a = max(sc["a_x"], sc["a_y"])
        sc["below"] = vm_max_below(step.planes, 0.25 * a)
        sc["depth"] = below_depth((case.grid.dx, case.grid.dy, case.stress.depth
                                   / (case.stress.nz - 1)), a)
        out.append(sc)
    return out


@pytest.fixture(scope="module")
def pin_grids():
    return [_pin(n) for n in (41, 81, 161)]


def test_worn_pin_surface_maximum_grows_and_its_companion_converges(pin_grids):
    """Measured: at μ = 0.5 the σ_VM maximum of every worn output step (s = 80, 160,
    320 mm) sits on the surface and grows by more than 5 % at each doubling 41² -> 81² ->
    161², while the maximum from a quarter of the contact radius down lies within the
    half-space solver's 2 % budget of its 161² value on 41² and 81², and from 81² on the
    companion's depth is that quarter radius."""
    for steps in zip(*pin_grids, strict=True):
        if not steps[0]["s"] > 0:
            continue
        top = [st["vm_max"] for st in steps]
        below = [st["below"] for st in steps]
        print(f"s = {steps[0]['s']:g}: vm_max " + " / ".join(f"{v:.2f}" for v in top)
              + ", below a/4 " + " / ".join(f"{v:.2f}" for v in below))
        assert all(st["vm_max_z"] == 0.0 for st in steps)
        assert min(np.diff(top) / top[:-1]) > 0.05
        assert max(abs(v / below[-1] - 1.0) for v in below[:-1]) < 0.02
        assert all(b < t for b, t in zip(below, top, strict=True))
        for st in steps[1:]:
            assert st["depth"] == pytest.approx(0.25 * max(st["a_x"], st["a_y"]))


def test_the_plane_norms_leave_the_edge_band_out():
    """Two steps that differ only at the surface point of the contact edge (where a
    log-singular stress has no converged value) and at one interior point: the plane L2
    leaves the edge point out, for every case; the interior one counts."""
    from reports.compare.metrics import compare_steps

    case = load_case("pin_on_disk", quick=True)[1]
    a0, p0 = case.hertz_scales
    sa, sb = fakes.hertz_step(case, 1.0, 0), fakes.hertz_step(case, 1.0, 0)
    plane = sa.planes["xz"]
    p_line = sa.surface["p_n"][:, np.argmin(np.abs(sa.y))]
    edge = int(np.flatnonzero(p_line > 0)[-1])  # the last cell in contact along x
    bumped = plane.fields["vm"].copy()
    bumped[edge, 0] += 5.0 * p0
    sa.planes["xz"] = type(plane)(s=plane.s, z=plane.z, fields={**plane.fields, "vm": bumped})

    def l2():
        return {(q, m): v for q, m, v in compare_steps(sa, sb, a0=a0, p0=p0)}[("vm_xz", "l2")]

    assert l2() == 0.0
    bumped[int(np.argmin(np.abs(plane.s))), 5] += 5.0 * p0  # an interior point counts
    assert l2() > 0.05


def test_a_pair_tolerance_key_can_be_set_from_quick_and_the_command_line(tmp_path):
    """``[quick]`` and ``--set`` take a pair key whole (``tolerances.ic-fem.p_max``): the
    pair's dot is part of the key, not a nested table."""
    from cases.loader import load_case

    text = DECLARED.split("[not_converged]")[0] + \
        '[quick]\n"tolerances.ic-fem.p_n_l2" = 0.07\n'
    case = write_case(tmp_path, text)
    assert load_case(case, quick=True)[0].tolerances == {"ic-fem.p_n_l2": 0.07}
    got = load_case(case, overrides={"tolerances.fem-analytic.p_x_max": 0.3})[0]
    assert got.tolerances == {"fem-analytic.p_x_max": 0.3}


def test_the_reason_column_is_read_checked(tmp_path, skewed):
    """metrics.csv's ``reason`` (issue 76, point 2): a file written before the column reads
    its rows not gated as unrecorded; a code outside the closed set, or one on a gated
    row, is a damaged file."""
    import pandas as pd

    from reports.store.readers import Malformed

    out = tmp_path / "res"
    assert run(str(write_case(tmp_path, DECLARED)), "--out", str(out)) == 0
    path = out / "small" / layout.METRICS
    frame = pd.read_csv(path, keep_default_na=False)
    old = tmp_path / "old.csv"
    frame.drop(columns="reason").to_csv(old, index=False)
    m = read_metrics(old)
    assert set(m.loc[m["status"] != "gated", "reason"]) == {"unrecorded"}
    for k, code in ((frame.index[frame["status"] != "gated"][0], "made up"),
                    (frame.index[frame["status"] == "gated"][0], "floor")):
        bad = frame.copy()
        bad.loc[k, "reason"] = code
        bad.to_csv(old, index=False)
        with pytest.raises(Malformed, match="column 'reason'"):
            read_metrics(old)
