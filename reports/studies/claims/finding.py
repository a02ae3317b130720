"""What a claim of the source article becomes once judged: a :class:`Finding` (the
suite's measured numbers, their numerical uncertainty, a verdict and why) with the
:class:`Panel` figures that show it, and the helpers the claims share to read numbers
and uncertainties from stored results (:class:`Article`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from reports.registry import solvers
from reports.store.results import CaseResults
from reports.studies.gridstudy import GRID_STUDY, SETTLED

#: the four verdicts, in the order of the claims table's legend
HOLDS = "holds"
ARTICLE_GRID = "holds only on the article's grid"
FAILS = "does not hold"
UNDECIDED = "cannot be decided"
VERDICTS = (HOLDS, ARTICLE_GRID, FAILS, UNDECIDED)


@dataclass(frozen=True)
class Panel:
    """One plot of a figure, in the article's dimensionless axes: ``series`` maps a label
    (solver and point) to its (x, y) arrays."""

    title: str
    xlabel: str
    ylabel: str
    series: dict[str, tuple[np.ndarray, np.ndarray]]
    markers: bool = False

    def frame(self) -> pd.DataFrame:
        """The panel's data as rows (panel, series, x, y), for the figure's CSV."""
        rows = [pd.DataFrame({"panel": self.title, "series": label, "x": np.asarray(x),
                              "y": np.asarray(y)})
                for label, (x, y) in self.series.items()]
        return pd.concat(rows, ignore_index=True) if rows else \
            pd.DataFrame(columns=["panel", "series", "x", "y"])


@dataclass(frozen=True)
class Finding:
    """A judged claim: ``measured`` and ``uncertainty`` are sentences of numbers,
    ``verdict`` one of :data:`VERDICTS`, ``why`` one sentence."""

    measured: str
    uncertainty: str
    verdict: str
    why: str
    panels: tuple[Panel, ...] = ()
    values: dict[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.verdict not in VERDICTS:
            raise ValueError(f"verdict {self.verdict!r} is not one of {VERDICTS}")


def undecided(why: str, panels: tuple[Panel, ...] = ()) -> Finding:
    """A claim the results at hand cannot decide, and why (e.g. a run is missing)."""
    return Finding("—", "—", UNDECIDED, why, panels)


@dataclass
class Article:
    """The results a claims table is judged from: one case directory per source of
    :mod:`reports.studies.claims.sources` (None where it is missing, with the reason) and
    the rows of ``thresholds.csv``."""

    cases: dict[str, CaseResults | None]
    missing: dict[str, str]
    thresholds: pd.DataFrame

    def case(self, source: str) -> CaseResults:
        found = self.cases.get(source)
        if found is None:
            raise MissingSource(f"no results for {source}: {self.missing.get(source, '')}")
        return found

    def rows(self, source: str, solver: str) -> pd.DataFrame:
        """Summary rows of one solver, with the swept value as column ``value`` (the number
        after ``=`` in ``param``), sorted by value and step."""
        s = self.case(source).summary
        s = s[s["solver"] == solver].copy()
        s["value"] = [value_of(p) for p in s["param"]]
        return s.sort_values(["value", "step"])

    def base_solvers(self, source: str) -> list[str]:
        """The solvers of a source, metamorphic relations left out."""
        return [s for s in self.solvers(source) if not solvers.record(s).base]

    def half_cell(self, source: str, param: str) -> tuple[float, float]:
        """Half a cell of the stress grid (depth step, surface step) [mm]: how far a
        sampled maximum can lie from the true one."""
        point = self.case(source).point(param)
        st, g = point["stress"], point["grid"]
        return 0.5 * st["depth"] / (st["nz"] - 1), 0.5 * g["Lx"] / g["nx"]

    def scale(self, source: str, param: str) -> tuple[float, float]:
        """(a0, p0) of the unworn Hertz contact of a sweep point."""
        point = self.case(source).point(param)
        return float(point["hertz_a0"]), float(point["hertz_p0"])

    def solvers(self, source: str) -> list[str]:
        """The solvers with results in a source, by role (:func:`reports.registry.solvers.
        by_role`): a plugin that declined every point, or one installed beside them, never
        takes a built-in solver's place."""
        case = self.case(source)
        ran = set(case.summary["solver"]) if "solver" in case.summary else set()
        return solvers.by_role(s for s in case.manifest.get("solvers", []) if s in ran)


class MissingSource(LookupError):
    """A claim needs results the directory does not hold."""


def value_of(param: str) -> float:
    """The swept value of a ``param`` label (``beta=45`` -> 45.0); NaN for none."""
    _, eq, text = str(param).partition("=")
    try:
        return float(text) if eq else math.nan
    except ValueError:
        return math.nan


def budget(solver: str, quantity: str, metric: str = "rel") -> float:
    """The solver's error budget for a quantity (:mod:`reports.registry.solvers`): the
    relative error the suite expects of it, used as its uncertainty where no second
    solver or grid study measures one."""
    return float(solvers.record(solver).budget(quantity, metric))


def closed_form(name: str):
    """A closed form of the ``analytic`` solver's package (through the registry)."""
    return solvers.record("analytic").entry(name)


def fmt(x: float, digits: int = 3) -> str:
    return "—" if not math.isfinite(x) else f"{x:.{digits}g}"


@dataclass(frozen=True)
class Measured:
    """A scalar of one solver with its numerical uncertainty ``u`` (same unit) and where
    ``u`` comes from; ``settled`` is False when a grid study found it not converging."""

    value: float
    u: float
    basis: str
    settled: bool = True

    def text(self, digits: int = 3, scale: float = 1.0) -> str:
        return f"{fmt(self.value / scale, digits)} ± {fmt(self.u / scale, 2)}"


def measure(art: Article, source: str, solver: str, param: str, step: int, quantity: str,
            value: float) -> Measured:
    """``value`` (the solver's ``quantity`` at ``step``) with its uncertainty: the GCI of
    the grid study where ``run --convergence`` made one (module
    :mod:`reports.studies.gridstudy`; a study that does not converge says so, with the
    last refinement's change as a lower bound), else the solver's error budget."""
    study = art.case(source).study(GRID_STUDY.name)
    row = study[(study["solver"] == solver) & (study["param"] == param)
                & (study["step"] == step) & (study["quantity"] == quantity)]
    if not row.empty:
        r = row.iloc[0]
        if r["status"] in SETTLED:
            u = abs(value) * float(r["gci_fine"]) if math.isfinite(r["gci_fine"]) else 0.0
            return Measured(value, u, "grid study (GCI)")
        change = abs(float(r["f1"]) - float(r["f2"]))
        return Measured(value, change, f"grid study: {r['status']} (the last refinement "
                        f"moved it by {fmt(change)})", settled=False)
    s = art.case(source).summary
    closed = s[(s["solver"] == "analytic") & (s["param"] == param) & (s["step"] == step)]
    if solver != "analytic" and not closed.empty and math.isfinite(closed[quantity].iloc[0]):
        return Measured(value, abs(value - float(closed[quantity].iloc[0])),
                        "its difference from the closed form (no grid study)")
    return Measured(value, abs(value) * budget(solver, quantity),
                    f"{solver}'s error budget (no grid study, no closed form)")


def study_evidence(case, param: str, step: int, quantities: tuple[str, ...]) -> str:
    """What the run's studies of ``case`` (its results) at ``param`` and ``step`` say of
    ``quantities``: the half-space solver's grid study status of each (``run
    --convergence``) and, where the FEM ran, the resolution probe's sensitivity against
    half the ic-fem tolerance (:mod:`reports.studies.probe`); '' without either."""
    from reports.studies.probe import FRACTION, PROBE, admitted

    parts = []
    grid = case.study(GRID_STUDY.name)
    grid = grid[(grid["solver"] == "ic") & (grid["param"] == param) & (grid["step"] == step)]
    if not grid.empty:
        status = dict(zip(grid["quantity"], grid["status"], strict=True))
        parts.append("grid study: " + ", ".join(f"{q} {status[q]}" for q in quantities
                                                if q in status))
    table = case.study(PROBE.name)
    table = table[(table["param"] == param) & (table["step"] == step)
                  & (table["pair"] == "ic-fem")]
    if not table.empty:
        rows = admitted(case.metrics, table).set_index("quantity")
        said = [f"{q} {_moved(rows.at[q, 'sensitivity'], rows.at[q, 'metric'])} "
                f"({'admitted' if rows.at[q, 'admitted'] else 'not a number the mesh gives'})"
                for q in quantities if q in rows.index]
        parts.append(f"resolution probe (the worn step spread over half the FEM's element; "
                     f"admitted below {FRACTION:g} of the ic-fem tolerance): " + ", ".join(said))
    return "".join(f"; {p}" for p in parts)


def _moved(value: float, metric: str) -> str:
    return f"{value:.2g} cells" if metric == "cells" else f"{100 * value:.2g} %"
