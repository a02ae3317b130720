"""The fretting contract (cases.result): a run's ``cycles`` and ``loops`` columns are
checked against CYCLE_COLUMNS and LOOP_COLUMNS by the one helper every solver uses; the
regime of a cycle has one rule (cycle_regime) and one column value (gross_slip); the
regime events one watch (RegimeEvents) for every solver (the half-space solver's own
cycles: tests/test_halfspace_fretting_events.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cases.result import (
    CYCLE_COLUMNS,
    GROSS,
    LOOP_COLUMNS,
    PARTIAL,
    RegimeEvents,
    cycle_regime,
    gross_slip,
    table_of,
)


def test_a_table_keeps_its_columns_in_order_as_float_arrays():
    t = table_of(CYCLE_COLUMNS, {"cycle": 1.0, "energy": 2.5, "own": [3, 4]}, extra=("own",))
    assert list(t) == ["cycle", "energy", "own"]
    assert all(v.dtype == np.float64 and v.ndim == 1 for v in t.values())
    assert t["own"].tolist() == [3.0, 4.0]


def test_a_misspelt_column_is_named():
    with pytest.raises(ValueError, match="energie"):
        table_of(CYCLE_COLUMNS, {"cycle": 1.0, "energie": 2.0})
    with pytest.raises(ValueError, match="dispalcement"):
        table_of(LOOP_COLUMNS, {"cycle": [1.0], "dispalcement": [0.1]})


@pytest.mark.parametrize(("stick", "contact", "regime"), [
    ([0.0, 3.0], [5.0, 5.0], GROSS),    # one extreme slides whole: gross slip
    ([2.0, 3.0], [5.0, 5.0], PARTIAL),  # both stick somewhere
    ([0.0, 0.0], [0.0, 5.0], None),     # an extreme without contact: no regime
    ([], [], None),
])
def test_the_regime_of_a_cycle(stick, contact, regime):
    assert cycle_regime(stick, contact) == regime
    value = gross_slip(regime)
    assert math.isnan(value) if regime is None else value == float(regime == GROSS)


def test_regime_events_are_recorded_once_with_their_cycle():
    """A made-up history as the FEM reports it (J = 100, 1000 cycles, held approach,
    P0 = 500 N, areas in mm²): partial slip after the loading, gross slip in cycle 3 (at
    300 ± 100), load below 1 % of P0 in cycle 5, no contact in cycle 6 (cut at 1000
    cycles in the last simulated one)."""
    watch = RegimeEvents(100.0, 1000.0, 500.0, PARTIAL, 0.2, held_approach=True,
                         nothing="no node in contact")
    history = [(PARTIAL, 0.1, 400.0, 1.0), (PARTIAL, 0.1, 300.0, 1.0),
               (GROSS, 0.0, 200.0, 1.0), (GROSS, 0.0, 50.0, 0.5), (GROSS, 0.0, 4.0, 0.1),
               (None, 0.0, 0.0, 0.0), (None, 0.0, 0.0, 0.0)]
    for n, (regime, stick, P_min, contact) in enumerate(history, start=1):
        watch.observe(n, regime, stick, P_min, contact)
    got = [(e.event, e.cycle, e.cycle_resolution) for e in watch.events]
    assert got == [("partial_to_gross_slip", 300.0, 100.0), ("load_lost", 500.0, 100.0),
                   ("contact_worn_through", 600.0, 100.0)]
    assert "0.1 mm² at cycle 200 -> 0 mm² at cycle 300" in watch.events[0].detail
    assert watch.events[2].detail == ("no node in contact, P = 0 (least P 4 N at cycle 500, "
                                      "the last with contact)")
    load = RegimeEvents(100.0, 1000.0, 500.0, GROSS, 0.0, held_approach=False,
                        nothing="no node in contact")
    load.observe(1, PARTIAL, 0.2, 1.0, 0.0)  # held load: no load events; gross -> partial
    assert [e.event for e in load.events] == ["gross_to_partial_slip"]
