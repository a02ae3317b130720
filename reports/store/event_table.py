"""The regime events of a run: ``DIR/<case>/events.csv`` beside ``summary.csv``, its
reader and the report's view of it.

A solver that watches for events (the half-space fretting loop,
:class:`halfspace.wear.RegimeWatch`) returns them in :attr:`cases.result.RunResult.events`
(None when it does not watch).  A case any of whose units watched gets ``events.csv``:
one row per event and (solver, sweep point), columns ``case, solver, param, event,
cycle, cycle_resolution, detail``, in the order of the summary (sweep point, then
solver) and, within a unit, in the order the solver saw them; a header only when no
event happened.  The event happened after cycle ``cycle - cycle_resolution`` and at or
before ``cycle`` (real cycles; the resolution is the cycle jump J).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pandas as pd

from cases.result import EVENT_COLUMNS
from reports.store.readers import Malformed, read_csv

COLUMNS = ["case", "solver", "param", *EVENT_COLUMNS]
_TEXT = ("case", "solver", "param", "event", "detail")

#: what the report says above a case's Events table
EVENTS_NOTE = ("Regime events seen by the solvers (<code>events.csv</code>): each happened "
               "after cycle <i>cycle</i> &minus; <i>resolution</i> and at or before "
               "<i>cycle</i> (the resolution is the cycle jump J: one simulated cycle "
               "stands for J cycles).")


def events_frame(rows: list[dict[str, Any]]) -> pd.DataFrame:
    """``events.csv`` from :meth:`cases.result.RunResult.event_rows` rows."""
    return pd.DataFrame.from_records(rows, columns=COLUMNS)


def read_events(path: Path) -> pd.DataFrame:
    """``events.csv``: text columns as str, ``cycle`` and ``cycle_resolution`` finite
    numbers >= 0 (:class:`reports.store.readers.Malformed` otherwise)."""
    frame = read_csv(path, required=COLUMNS, text=_TEXT,
                     numeric=("cycle", "cycle_resolution"))
    for col in ("cycle", "cycle_resolution"):
        for i, v in enumerate(frame[col]):
            if not (math.isfinite(v) and v >= 0):
                raise Malformed(f"column {col!r} holds {v!r} (data row {i + 1}), not a "
                                "cycle count >= 0")
    return frame


def events_view(events: pd.DataFrame) -> pd.DataFrame:
    """The report's Events table of a case (empty when it has no event)."""
    return pd.DataFrame({
        "solver": events["solver"], "param": events["param"], "event": events["event"],
        "detail": events["detail"], "cycle": events["cycle"],
        "resolution [cycles]": events["cycle_resolution"]})
