"""Regime events of the half-space fretting loop (``cases.result.RegimeEvents``): gross
-> partial slip and back, the load lost and the contact worn through under a held
approach, each with the real cycle at which it was seen (to within the cycle jump J);
``events.csv`` beside ``summary.csv`` and the report's Events table
(``reports/store/event_table.py``).

Runs (quick size, about 20 s in all):

- ``fretting_orthotropic --quick`` (31², 8 steps per cycle, 2000 cycles, J = 500,
  β ∈ {0, 90, 60}) through ``contact-vv run``.  Along x the friction coefficient is
  μ1 = 0.1 at β = 0 and μ2 = 0.65 at β = 90; Mindlin's gross-slip displacement at the
  held approach, δ* = μ (2 - ν) δ_n / (2 (1 - ν)) (docs/cases.md, case 6), is 0.97 µm
  and 6.3 µm against the 4 µm amplitude: gross slip at β = 0 (no stick cell at ±A in
  any cycle), partial slip at β = 90 (stick cells at ±A in every cycle), no event.  At
  β = 60 the orthotropic law has no Mindlin closed form; it lies below the quick
  threshold (80.2°, next point), so the contact slides in every cycle there too.
- The same file at β = 80.5, just above the quick threshold (80.2° after 2000 cycles,
  reports/README.md): the contact starts in gross slip and, as the worn contact spreads,
  the stick zone appears at ±A.  Measured: stick area 0 at both extremes at cycles 500
  and 1000 (at 1000 one stick cell at +A only), 0.0208 mm² at both from 1500; event
  ``gross_to_partial_slip`` at cycle 1500 ± 500.
- Case 6 at β = 0 with 30 times its wear coefficients, 6000 cycles: P falls
  geometrically (the wear is implicit in p_n) from 778 N to 55 N (cycle 500), 2.8 N
  (1000), ... 1.2e-10 N (5000), and at 5500 no cell is in contact: ``load_lost`` at
  1000 and ``contact_worn_through`` at 5500, each ± 500.
"""

from __future__ import annotations

import shutil
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

import halfspace.wear as hw
from analytic import fretting as afr
from cases.loader import case_path, load_case
from cases.result import (
    GROSS,
    LOAD_LOST_FRACTION,
    PARTIAL,
    SLIP,
    STICK,
    RegimeEvents,
    cycle_regime,
)
from reports.cli import main
from reports.render.pages import report_text

J = 500.0
CASE = "fretting_orthotropic"
NEAR = "fretting_near_threshold"  # the bundled file under another name, β = 80.5


def _table(out: Path, case: str, param: str, name: str) -> pd.DataFrame:
    return pd.read_csv(out / case / "fields" / "ic" / param / f"{name}.csv")


def _events(out: Path, case: str) -> pd.DataFrame:
    return pd.read_csv(out / case / "events.csv", keep_default_na=False)


@pytest.fixture(scope="module")
def results(tmp_path_factory) -> Path:
    """The quick sweep (β = 0, 90, 60) and the β = 80.5 point, run and reported in one
    DIR."""
    out = tmp_path_factory.mktemp("events")
    near = out.parent / f"{NEAR}.toml"
    shutil.copyfile(case_path(CASE), near)
    # the half-space solver's events (the FEM's: tests/test_fem_fretting.py)
    assert main(["run", CASE, "--quick", "--solver", "ic,analytic", "--out", str(out),
                 "--no-progress"]) == 0
    assert main(["run", str(near), "--quick", "--set", "friction.beta=80.5", "--solver",
                 "ic,analytic", "--out", str(out), "--no-progress"]) == 0
    assert main(["report", "--out", str(out)]) == 0
    return out


# ------------------------------------------------------------------ the detector alone


def _watch(held_approach: bool, cycles: float) -> RegimeEvents:
    """A watch on a 500-cycle-jump case whose initial loading is in partial slip."""
    case = SimpleNamespace(fretting=SimpleNamespace(jump=J, cycles=cycles),
                           grid=SimpleNamespace(dx=0.1, dy=0.1),
                           load=SimpleNamespace(load_controlled=not held_approach))
    first = SimpleNamespace(P=100.0, status=np.array([STICK, SLIP]),
                            state=SimpleNamespace(p_n=np.array([1.0, 1.0])))
    return hw.regime_events(case, first)


def _seen(stick, contact, P) -> hw.CycleObservation:
    return hw.CycleObservation(0.01, list(stick), list(contact), P, min(stick),
                               min(contact))


def test_regime_at_the_extremes():
    assert cycle_regime([0], [5]) == GROSS and cycle_regime([1], [5]) == PARTIAL
    assert cycle_regime([0], [0]) is None
    # the whole contact slides at one extreme: the cycle is in gross slip
    assert _seen([0, 3], [5, 5], 1.0).regime() == GROSS
    assert _seen([2, 3], [5, 5], 1.0).regime() == PARTIAL
    assert _seen([0, 0], [0, 5], 1.0).regime() is None


def test_events_once_with_the_real_cycle_and_its_resolution():
    watch = _watch(held_approach=True, cycles=1800.0)  # the last cycle stands for 300
    for n, seen in enumerate([_seen([1, 1], [5, 5], 50.0),   # partial, as initially
                              _seen([0, 2], [5, 5], 40.0),   # gross at -A
                              _seen([0, 0], [5, 5], 0.5),    # P < 1 % of P0 = 100 N
                              _seen([0, 0], [0, 0], 0.0)],   # no contact
                             start=1):
        seen.observed_by(watch, n)
    got = [(e.event, e.cycle, e.cycle_resolution) for e in watch.events]
    assert got == [("partial_to_gross_slip", 1000.0, 500.0), ("load_lost", 1500.0, 500.0),
                   ("contact_worn_through", 1800.0, 300.0)]
    assert "last with contact" in watch.events[-1].detail


def test_no_load_events_under_load_control():
    watch = _watch(held_approach=False, cycles=1000.0)
    _seen([1, 1], [5, 5], 0.5).observed_by(watch, 1)
    _seen([1, 1], [5, 5], 0.5).observed_by(watch, 2)
    assert watch.events == []


# ------------------------------------------------------------------ solver runs


def test_quick_sweep_gross_slip_at_0_partial_slip_at_90(results):
    case = load_case(CASE, quick=True)[0]
    A, delta_n, nu = case.fretting.amplitude, case.load.approach, case.a.nu
    star = {mu: afr.MindlinDeresiewicz.from_approach(delta_n, case.R, mu, case.a.E, nu, case.b.E,
                                           nu).delta_star for mu in (0.1, 0.65)}
    assert star[0.1] < A < star[0.65]  # Mindlin: gross slip at β = 0, partial at 90
    for param, gross in (("beta=0", True), ("beta=90", False), ("beta=60", True)):
        cyc = _table(results, CASE, param, "cycles")
        assert list(cyc["cycle"]) == [500.0, 1000.0, 1500.0, 2000.0]
        stick = cyc[["stick_area_neg", "stick_area_pos"]].to_numpy()
        if gross:
            assert np.all(stick == 0.0) and np.all(cyc["gross_slip"] == 1.0)
        else:
            assert np.all(stick > 0.0) and np.all(cyc["gross_slip"] == 0.0)
    events = _events(results, CASE)
    assert list(events.columns) == ["case", "solver", "param", "event", "cycle",
                                    "cycle_resolution", "detail"]
    assert events.empty  # the same regime from the initial loading to cycle 2000


def test_gross_to_partial_at_the_cycle_the_stick_area_appears(results):
    events = _events(results, NEAR)
    assert list(events["event"]) == ["gross_to_partial_slip"]
    ev = events.iloc[0]
    assert (ev["case"], ev["solver"], ev["param"]) == (NEAR, "ic", "beta=80.5")
    cyc = _table(results, NEAR, "beta=80.5", "cycles")
    stick = cyc[["stick_area_neg", "stick_area_pos"]].min(axis=1).to_numpy()
    first = int(np.flatnonzero(stick > 0)[0])
    assert first > 0 and np.all(stick[:first] == 0) and np.all(stick[first:] > 0)
    assert ev["cycle"] == cyc["cycle"][first] == 1500.0
    assert ev["cycle_resolution"] == J == cyc["cycle"][first] - cyc["cycle"][first - 1]
    assert list(cyc["gross_slip"]) == [1.0] * first + [0.0] * (len(cyc) - first)


def test_events_in_the_report(results):
    page = report_text(results)
    assert page.count('class="events"') == 1  # only the case with an event has the table
    section = page[page.index(f'id="events-{NEAR}"'):]
    section = section[:section.index("</table>")]
    assert "gross_to_partial_slip" in section and "beta=80.5" in section
    assert "<td class=\"\">1500</td><td class=\"\">500</td>" in section
    assert f'id="events-{CASE}"' not in page


def test_worn_through_under_held_approach():
    over = {"friction.beta": 0.0, "fretting.cycles": 6000, "fretting.output_cycles": [6000],
            "stress.nz": 2}
    for body, factor in (("a", 30.0), ("b", 15.0)):  # 30 x case 6 (b: half of a)
        over[f"materials.{body}.i1"] = factor * 1.33e-7
        over[f"materials.{body}.i2"] = factor * 8.645e-7
    case = load_case(CASE, quick=True, overrides=over)[0]
    run = hw.fretting(case)
    cyc = {k: np.asarray(v) for k, v in run.tables["cycles"].items()}
    got = [(e.event, e.cycle, e.cycle_resolution) for e in run.events]
    assert [g[0] for g in got] == ["load_lost", "contact_worn_through"]
    assert all(res == J for _, _, res in got)
    # worn through: the first cycle without a contact cell, P > 0 in every cycle before
    gone = int(np.flatnonzero(cyc["contact_area_min"] == 0)[0])
    assert got[1][1] == cyc["cycle"][gone]
    assert np.all(cyc["P_min"][:gone] > 0) and np.all(cyc["P_min"][gone:] == 0)
    assert np.all(np.isnan(cyc["gross_slip"][gone:]))  # no regime without contact
    # load lost: the first cycle whose least P is below 1 % of P0 (Hertz at the approach)
    P0 = afr.MindlinDeresiewicz.from_approach(case.load.approach, case.R, 0.1, case.a.E, case.a.nu,
                                    case.b.E, case.b.nu).P
    ratio = cyc["P_min"] / (LOAD_LOST_FRACTION * P0)
    assert np.all(np.abs(ratio[ratio > 0] - 1) > 0.1)  # no cycle near the threshold
    assert got[0][1] == cyc["cycle"][int(np.flatnonzero(ratio < 1)[0])]


def test_damaged_events_file_is_named(results, tmp_path):
    """An events.csv that does not hold cycle counts makes its case damaged, not a
    traceback (reports/store/readers.py::read_result)."""
    from damage_kit import rehash

    from reports.store.results import scan

    out = tmp_path / "out"
    shutil.copytree(results / NEAR, out / NEAR)
    assert scan(out).complete and not scan(out).damaged
    path = out / NEAR / "events.csv"
    path.write_text(path.read_text().replace(",1500.0,", ",soon,"))
    rehash(out / NEAR)
    found = scan(out)
    assert not found.complete
    assert "events.csv: column 'cycle'" in found.damaged[NEAR]
