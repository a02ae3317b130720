"""Quantities that are not converged numbers are compared and shown, not gated
(reports/registry/tolerances.py, issue 14 point 3): the ``[not_converged]`` declaration of a case
file, its checks, its converged companion ``vm_max_below``, the gate and the report; and
on the bundled worn pin, the measured facts the declaration rests on."""

from __future__ import annotations

import io

import numpy as np
import pandas as pd
import pytest
import test_cli_fakes as fakes
from test_cli_run import HERTZ, write_case

from cases.loader import load_case
from cases.result import load_step
from reports.cli import main
from reports.registry.solvers import resolve
from reports.render.gate import run_gate
from reports.store import layout
from reports.store.readers import read_metrics

SKEW = 0.3  # relative error the fake solver below puts on vm_max only

DECLARED = HERTZ.replace("nz = 11", "nz = 11\nz_below = 0.09") + """\
[not_converged]
vm_max = "made up for the test: 1.0 / 1.1 / 1.2 MPa on three grids"
"""


def supports_all(case):
    return None


def solve_skewed(case, *, progress=False, on_output=None):
    """The exact fake fields; only the vm_max scalar is off by SKEW (as a singular
    surface maximum would be), so vm_max_below (from the planes) agrees."""
    result = fakes.solve_exact(case)
    for step in result.steps:
        step.scalars["vm_max"] *= 1.0 + SKEW
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
    vm = m[m["quantity"] == "vm_max"].iloc[0]
    assert vm["value"] == pytest.approx(SKEW, rel=1e-9)  # still compared and written
    assert vm["status"] == "not converged" and vm["note"].startswith("declared: made up")
    below = m[m["quantity"] == "vm_max_below"].iloc[0]
    assert below["status"] == "gated" and below["value"] < 1e-12 and below["passed"]
    # the companion is the plane maximum at z >= z_below
    step = load_step(out / "small" / "fields" / "ic" / "base" / "step_0000.npz")
    deep = step.planes["xz"].z >= 0.09 - 1e-12
    expected = max(float(p.fields["vm"][:, deep].max()) for p in step.planes.values())
    summary = pd.read_csv(out / "small" / layout.SUMMARY)
    assert summary["vm_max_below"].to_numpy() == pytest.approx([expected] * 2, rel=1e-12)
    assert expected < float(summary["vm_max"].iloc[1])  # the analytic's surface-free max
    stream = io.StringIO()
    assert run_gate(out, stream=stream) == 0
    printed = stream.getvalue()
    assert "NOT GATED small ic-analytic vm_max rel (1 row(s), largest 0.3 at step 0): " \
        "not converged; declared: made up" in printed
    assert "1 not gated (not converged), 0 problem(s)" in printed
    assert main(["report", "--out", str(out)]) == 0
    html = (out / "index.html").read_text()
    assert "Not converged, so not gated (1 rows)" in html and "made up for the test" in html


def test_the_same_error_fails_the_gate_when_not_declared(tmp_path, skewed, capsys):
    out = tmp_path / "res"
    case = write_case(tmp_path, DECLARED.split("[not_converged]")[0])
    assert run(str(case), "--out", str(out)) == 0
    assert main(["gate", "--out", str(out)]) == 1
    assert "FAIL small step 0 ic-analytic vm_max rel = 0.3 > tolerance 0.02" in \
        capsys.readouterr().out


@pytest.mark.parametrize("edit, message", [
    (lambda t: t + "[tolerances]\nvm_max = 0.2\n",
     "tolerances.vm_max: 'vm_max' is declared not converged"),
    (lambda t: t + '[tolerances]\n"ic-fem.vm_max" = 0.2\n',
     "tolerances.ic-fem.vm_max: 'vm_max' is declared not converged"),
    (lambda t: t.replace("z_below = 0.09\n", ""),
     "not_converged.vm_max needs its converged companion: set stress.z_below"),
    (lambda t: t.replace("vm_max = \"made", "p_maxx = \"made"),
     "not_converged.p_maxx: unknown quantity"),
    (lambda t: t.replace('"made up for the test: 1.0 / 1.1 / 1.2 MPa on three grids"',
                         '"  "'), "not_converged.vm_max = '  ': must be a non-empty"),
    (lambda t: t.replace("z_below = 0.09", "z_below = 0.5"),
     "stress.z_below = 0.5: must lie in (0, stress.depth = 0.3] mm"),
])
def test_declarations_are_checked(tmp_path, skewed, capsys, edit, message):
    case = write_case(tmp_path, edit(DECLARED))
    assert run(str(case), "--out", str(tmp_path / "res")) == 2
    assert message in capsys.readouterr().err


# ------------------------------------------------------------------ the bundled worn pin


def _pin(n: int):
    case = load_case("pin_on_disk", quick=True, overrides={"grid.nx": n, "grid.ny": n})[1]
    assert case.friction.mu1 == 0.5 and "vm_max" in case.not_converged
    from reports.run.units import add_derived

    result = resolve("ic")(case)
    add_derived(result, case)
    return case, [s.scalars for s in result.steps]


@pytest.fixture(scope="module")
def pin_grids():
    return [_pin(n)[1] for n in (41, 81, 161)]


def test_worn_pin_surface_maximum_grows_and_its_companion_converges(pin_grids):
    """The declaration of cases/pin_on_disk.toml, measured: at mu = 0.5 the surface
    maximum of every worn output step (s = 80, 160, 320 mm) sits on the surface and grows
    by more than 5 % at each doubling 41^2 -> 81^2 -> 161^2, while vm_max_below on 41^2
    and 81^2 lies within the half-space solver's 2 % budget for a sigma_VM maximum of its
    161^2 value."""
    for steps in zip(*pin_grids, strict=True):
        if not steps[0]["s"] > 0:
            continue
        top = [st["vm_max"] for st in steps]
        below = [st["vm_max_below"] for st in steps]
        print(f"s = {steps[0]['s']:g}: vm_max " + " / ".join(f"{v:.2f}" for v in top)
              + ", vm_max_below " + " / ".join(f"{v:.2f}" for v in below))
        assert all(st["vm_max_z"] == 0.0 for st in steps)
        assert min(np.diff(top) / top[:-1]) > 0.05
        assert max(abs(v / below[-1] - 1.0) for v in below[:-1]) < 0.02
        assert all(b < t for b, t in zip(below, top, strict=True))


def test_a_singular_edge_leaves_the_band_out_of_the_plane_l2():
    """Two steps that differ only at the surface point of the contact edge (where a
    log-singular stress has no converged value) and at one interior point: the plane L2
    counts the edge point unless the case declares the singular edge; the interior one
    always."""
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

    def l2(**kw):
        return {(q, m): v for q, m, v in compare_steps(sa, sb, a0=a0, p0=p0, **kw)}[
            ("vm_xz", "l2")]

    assert l2() > 0.05
    assert l2(singular_edge=True) == 0.0
    bumped[edge // 2, 5] += 5.0 * p0  # an interior point still counts
    assert l2(singular_edge=True) > 0.05


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
