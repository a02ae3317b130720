"""The gate's power against a foreign solver (issue 63, point 3): a solver plugin that
wraps the half-space solver and applies one physical defect at a time — to the case it
solves (a modulus, the friction or wear axes) or to the results it returns (tractions,
parities, shifts, the wear of body b, the depth of a stress plane) — must fail the quick
gate on a bundled case where the defect is physics, with ic and the closed forms as its
references; the ones it does not yet see are listed with the measurement (:data:`GAPS`),
and a defect in a scalar the suite does not take from a solver — it derives it from the
solver's fields — must leave every stored and gated number as without it
(:data:`DERIVED`).
The plugin is installed as pip would (a module and a ``.dist-info`` with the entry
point) and is not one of the suite's own solvers: the gate judges it as it would a
user's.  Its catch rate is in ``benchmarks/README.md`` beside the other error rates."""

from __future__ import annotations

import sys

import pandas as pd
import pytest
from plugin_site import reload_registry, write_distribution

from reports.cli import main
from reports.registry import solvers
from reports.store.readers import read_summary

NAME = "foreign_ic"
PLUGIN = '''"""A foreign solver for the gate's tests: the half-space solver with one defect."""
import dataclasses
import os

import numpy as np

import halfspace

DEFECT = os.environ.get("CONTACT_VV_TEST_DEFECT", "none")


def record():
    from reports.registry.record import SolverRecord
    from reports.registry.solvers import grid_budget, refine_grid

    return SolverRecord("foreign_ic", __name__, budget=grid_budget, refine=refine_grid)


def supports(case):
    return halfspace.supports(case)


def estimate(case):
    return halfspace.estimate(case)


def _case(case):
    """The case the defective solver solves instead of ``case``."""
    a, b, f = case.a, case.b, case.friction
    if DEFECT == "E_b_from_a":
        return case.with_changes(b=dataclasses.replace(b, E=a.E, nu=a.nu))
    if DEFECT == "coupling_dropped":  # both bodies the pair's G and nu: K = 0 (Eq. 6)
        ga, gb = a.E / (2 * (1 + a.nu)), b.E / (2 * (1 + b.nu))
        G = 2.0 / (1.0 / ga + 1.0 / gb)
        nu = 0.5 * G * (a.nu / ga + b.nu / gb)
        same = dataclasses.replace(a, E=2.0 * G * (1.0 + nu), nu=nu)
        return case.with_changes(a=same, b=dataclasses.replace(b, E=same.E, nu=nu))
    if DEFECT == "friction_axes_turned":
        return case.with_changes(friction=dataclasses.replace(f, beta=f.beta + 20.0))
    if DEFECT == "wear_axes_turned":
        return case.with_changes(a=dataclasses.replace(a, i1=a.i2, i2=a.i1),
                                 b=dataclasses.replace(b, i1=b.i2, i2=b.i1))
    if DEFECT == "friction_scaled":
        return case.with_changes(friction=dataclasses.replace(f, mu1=1.05 * f.mu1,
                                                              mu2=1.05 * f.mu2))
    return case


def _step(step):
    s = step.surface
    if DEFECT == "traction_scaled":
        for k in ("p_x", "p_y"):
            s[k] = 1.03 * s[k]
    elif DEFECT == "traction_halved":
        for k in ("p_x", "p_y"):
            s[k] = 0.5 * s[k]
    elif DEFECT.startswith("no_slip_zone"):  # every contact point reported stuck
        from cases.result import OPEN, STICK

        s["state"] = np.where(s["state"] == OPEN, OPEN, STICK).astype(s["state"].dtype)
        step.scalars["stick_area"] = step.scalars["contact_area"]
        step.scalars["slip_area"] = 0.0
    elif DEFECT == "pressure_scaled":
        s["p_n"] = 1.03 * s["p_n"]
    elif DEFECT == "p_x_sign":
        s["p_x"] = -s["p_x"]
    elif DEFECT == "p_y_parity":
        s["p_y"] = -s["p_y"][:, ::-1]
    elif DEFECT in ("shift_one_cell_x", "shift_two_cells_y"):
        axis, by = (0, 1) if DEFECT.endswith("x") else (1, 2)
        for k in list(s):
            s[k] = np.roll(s[k], by, axis=axis)
    elif DEFECT == "wear_b_from_a":
        s["wear_b"] = s["wear_a"].copy()
    elif DEFECT == "plane_one_cell_deep":
        for plane in step.planes.values():
            for k, v in plane.fields.items():
                plane.fields[k] = np.concatenate([v[:, 1:], v[:, -1:]], axis=1)
    elif DEFECT == "vm_max_depth":
        step.scalars["vm_max_z"] = 1.1 * step.scalars["vm_max_z"]
    return step


def solve(case, *, progress=False, on_output=None):
    import halfspace.influence as influence

    assemble = influence._assemble
    if DEFECT == "cerruti_turned":  # A_xx with A_yy's integral and back: turned by 90°
        influence._assemble = lambda i_s, i_xx, i_yy, *rest: assemble(i_s, i_yy, i_xx, *rest)
    try:
        result = halfspace.solve(_case(case), progress=progress)
    finally:
        influence._assemble = assemble
    result.steps = [_step(s) for s in result.steps]
    if on_output is not None:
        for s in result.steps:
            on_output(s)
    return dataclasses.replace(result, case=case.name, solver="foreign_ic",
                               param=case.param)
'''

#: defect -> (quick case, what is wrong)
DEFECTS = {
    "E_b_from_a": ("dissimilar", "body b's modulus and Poisson's ratio taken from body a"),
    "cerruti_turned": ("fretting_isotropic", "the tangential compliance's anisotropy turned "
                       "by 90° (the Cerruti block A_xx built with A_yy's integral)"),
    "friction_axes_turned": ("pin_on_disk_orthotropic", "the friction axes turned by 20°"),
    "wear_axes_turned": ("pin_on_disk_orthotropic", "the wear axes turned by 90°"),
    "friction_scaled": ("sliding_friction", "μ 5 % high"),
    "traction_scaled": ("sliding_friction", "the tangential tractions 3 % high"),
    "traction_halved": ("spence", "the tangential tractions half their size (μ = 0.04)"),
    "coupling_dropped": ("spence", "the normal-tangential coupling dropped (K = 0: both "
                         "bodies of the pair's G and nu)"),
    "no_slip_zone": ("cattaneo_mindlin", "no slip zone reported: every contact point "
                     "stuck, the stick area the contact's"),
    "no_slip_zone_compressed": ("spence", "no slip zone reported under Spence's "
                                "compression: every contact point stuck"),
    "pressure_scaled": ("hertz", "the pressure field 3 % high (its scalars not)"),
    "p_x_sign": ("sliding_friction", "p_x of the wrong sign"),
    "p_y_parity": ("pin_on_disk_orthotropic", "p_y mirrored in y: the wrong parity"),
    "shift_one_cell_x": ("hertz", "the surface fields one cell off in x"),
    "shift_two_cells_y": ("hertz", "the surface fields two cells off in y"),
    "wear_b_from_a": ("pin_on_disk_orthotropic", "body b's wear field that of body a"),
    "plane_one_cell_deep": ("sliding_friction", "the stress planes read one cell deep"),
    "vm_max_depth": ("hertz", "the reported depth of the σ_VM maximum 10 % deep"),
}
#: the defects the quick gate does not see, each with why: the test holds the catch rate
#: to this table, so that a hole closed or opened is seen (none since 2026-11-29: the
#: scaled pressure field fails the peak pressure's row, reports.compare.laws)
GAPS: dict[str, str] = {}
#: defects of a scalar the suite derives from every solver's fields (reports.run.units.
#: derive): what the solver said never reaches summary.csv, the report or the gate
DERIVED = {"vm_max_depth": ("vm_max_z", "the maximum over the stress planes")}


@pytest.fixture
def foreign(tmp_path, monkeypatch):
    """``load(defect)``: the plugin installed as pip would (:mod:`plugin_site`) with
    ``defect``."""
    site = tmp_path / "site"
    site.mkdir()
    (site / f"{NAME}.py").write_text(PLUGIN)
    write_distribution(site, NAME, f"{NAME} = {NAME}:record")
    monkeypatch.syspath_prepend(str(site))

    def load(defect: str) -> None:
        monkeypatch.setenv("CONTACT_VV_TEST_DEFECT", defect)
        monkeypatch.delitem(sys.modules, NAME, raising=False)
        assert reload_registry(monkeypatch) == [] and NAME in solvers.PLUGINS
    return load


def _gate(case: str, tmp_path, capsys) -> tuple[int, list[str]]:
    out = tmp_path / "res"
    assert main(["run", case, "--quick", "--no-progress", "--solver",
                 f"{NAME},ic,analytic", "--out", str(out)]) == 0
    capsys.readouterr()
    code = main(["gate", "--out", str(out)])
    lines = capsys.readouterr().out.splitlines()
    return code, [ln for ln in lines if ln.startswith("FAIL")]


def _summary(case: str, tmp_path) -> pd.DataFrame:
    return read_summary(tmp_path / "res" / case / "summary.csv")


@pytest.mark.parametrize("case", sorted({c for c, _ in DEFECTS.values()}))
def test_the_plugin_without_a_defect_passes(case, foreign, tmp_path, capsys):
    """No false alarm: the wrapped solver as it is passes every case the defects use."""
    foreign("none")
    code, fails = _gate(case, tmp_path, capsys)
    assert code == 0, fails


@pytest.mark.parametrize("defect", list(DEFECTS))
def test_the_quick_gates_catch_of_foreign_defects(defect, foreign, tmp_path, capsys):
    """Every defect outside :data:`GAPS` fails the quick gate on a row of the plugin's
    pairs (the suite's own ic-analytic rows unmoved); the defects in it pass, as
    measured."""
    case, why = DEFECTS[defect]
    foreign(defect)
    code, fails = _gate(case, tmp_path, capsys)
    assert not any(" ic-analytic " in f for f in fails)
    if defect in GAPS:
        assert code == 0, f"{defect} ({why}) is caught now: take it out of GAPS"
    elif defect in DERIVED:  # the solver's word is not taken: its numbers as ic's
        column, _ = DERIVED[defect]
        summary = _summary(case, tmp_path).set_index("solver")
        assert code == 0, fails
        assert summary.loc[NAME, column] == summary.loc["ic", column]
    else:
        assert code == 1 and any(f" {NAME}-" in f for f in fails), (defect, why, fails)
