"""Result files of another code as solvers: the record of ``external:NAME``, which reads
the case's ``[external.NAME]`` table (:mod:`external_results`; the user's guide:
``docs/external-results.md``).  Like a plugin it is the first solver of each of its
pairs: the built-in solvers are its references."""

from __future__ import annotations

from cases.model import Case
from reports.registry import plugins
from reports.registry.record import SolverRecord, grid_cell

#: the prefix of the solvers that read another code's result files (external_results):
#: ``external:NAME`` reads the case's ``[external.NAME]`` table
EXTERNAL = "external:"


def is_external(name: str) -> bool:
    """Whether ``name`` is an external result set, ``external:NAME``."""
    return name.startswith(EXTERNAL) and bool(plugins.NAME.fullmatch(name[len(EXTERNAL):]))


def stated_only(quantity: str, metric: str) -> float:
    """No budget of its own: what the results state is a case term (:func:`external_record`)."""
    return 0.0


def external_record(name: str) -> SolverRecord:
    """The record of ``external:NAME``: its budget and element size are what the case's
    ``[external.NAME]`` table states (:func:`external_results.spec.stated`)."""
    from external_results.spec import stated

    short = name[len(EXTERNAL):]

    def term(case: Case, quantity: str, metric: str) -> float:
        return stated(case, short).budget_of(quantity, metric)

    def cell(case: Case) -> float:
        c = stated(case, short).cell
        return grid_cell(case) if c is None else c

    return SolverRecord(name, "external_results", budget=stated_only,
                        case_term=term, cell_size=cell, options={"name": short},
                        style={"color": "C4", "ls": "-", "marker": "d", "ms": 3})
