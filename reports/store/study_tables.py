"""The study tables of a results directory: ``convergence.csv`` (grid studies,
``run --convergence``), ``jump_study.csv`` (cycle-jump studies, ``run --jump-study``) and
``probe.csv`` (the resolution probe, :mod:`reports.studies.probe`), their columns, the
statuses a row may hold, and their readers; the table of a study the store does not know
(:mod:`reports.studies.study`) is read as a solver table, by its name."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from reports.store import layout
from reports.store.readers import Malformed, read_csv, read_result, read_table

#: statuses of a three-level study (:func:`reports.studies.three_level.classify`):
#: ``unsettled``, a quantity the study does not find converging (not a solver run that did
#: not converge)
CONVERGED, OSCILLATING, UNSETTLED, EXACT = "converged", "oscillating", "unsettled", "exact"
STATUSES = (CONVERGED, OSCILLATING, UNSETTLED, EXACT)
#: the status earlier releases wrote for :data:`UNSETTLED`, read as it
OLD_STATUS = {"not converged": UNSETTLED}
#: the columns of ``convergence.csv``; the first 14 required
CONVERGENCE_COLUMNS = ["solver", "param", "step", "quantity", "h1", "h2", "h3", "f1", "f2",
                       "f3", "order", "f_extrapolated", "gci_fine", "status", "gci_coarse",
                       "asymptotic", "note"]
#: the columns of ``jump_study.csv``: sizes are the jumps J/4, J/2, J
JUMP_COLUMNS = ["solver", "param", "cycle", "step", "quantity", "h1", "h2", "h3", "f1", "f2",
                "f3", "change_halved", "order", "f_extrapolated", "gci_fine", "status",
                "gci_coarse", "asymptotic", "note", "cell_size"]

#: the columns of ``probe.csv``: the sensitivity of each probed row's quantity, by the
#: row's metric, to a wear step spread over ``spread`` mm, for an element ``width`` mm wide
PROBE_COLUMNS = ["param", "pair", "step", "cycle", "quantity", "metric", "sensitivity",
                 "width", "spread"]


def read_study(path: Path, columns: list[str], required: list[str]) -> pd.DataFrame:
    """A study table with ``columns`` (``required`` among them): text and numbers as a
    run writes them, a known ``status``; ``Malformed`` otherwise."""
    text = ("solver", "param", "quantity", "status", "note")
    frame = read_csv(path, required=required, text=text,
                     numeric=[c for c in columns if c not in (*text, "step")],
                     integer=["step"])
    frame["status"] = frame["status"].replace(OLD_STATUS)  # as an earlier release wrote it
    bad = ~frame["status"].isin(STATUSES)
    if bad.any():
        i = int(bad.to_numpy().nonzero()[0][0])
        raise Malformed(f"column 'status' holds {frame['status'].iloc[i][:40]!r} (data row "
                        f"{i + 1}), not one of {', '.join(STATUSES)}")
    return frame


def read_convergence(path: Path) -> pd.DataFrame:
    """``convergence.csv`` (a parser for :func:`reports.store.readers.read_result`)."""
    return read_study(path, CONVERGENCE_COLUMNS, CONVERGENCE_COLUMNS[:14])


def read_jump_study(path: Path) -> pd.DataFrame:
    """``jump_study.csv`` (a parser for :func:`reports.store.readers.read_result`)."""
    return read_study(path, JUMP_COLUMNS, JUMP_COLUMNS)


def read_probe(path: Path) -> pd.DataFrame:
    """``probe.csv`` (a parser for :func:`reports.store.readers.read_result`)."""
    return read_csv(path, required=PROBE_COLUMNS, text=("param", "pair", "quantity", "metric"),
                    numeric=["cycle", "sensitivity", "width", "spread"], integer=["step"])


@dataclass(frozen=True)
class Table:
    """A study table the store knows: its columns and its parser."""

    columns: list[str]
    parse: Callable[[Path], pd.DataFrame]


#: the study tables the store knows, by study name
TABLES = {"convergence": Table(CONVERGENCE_COLUMNS, read_convergence),
          "jump_study": Table(JUMP_COLUMNS, read_jump_study),
          "probe": Table(PROBE_COLUMNS, read_probe)}


def read_study_table(folder: Path, name: str) -> pd.DataFrame:
    """The table of study ``name`` in the case directory ``folder``
    (:func:`reports.store.layout.study_file`; :class:`DamagedResult` if it cannot be read);
    an empty table, with the known columns, where the study did not run."""
    known = TABLES.get(name)
    path = Path(folder) / layout.study_file(name)
    if not path.exists():
        return pd.DataFrame(columns=known.columns if known else [])
    return read_result(path, known.parse if known else read_table)
