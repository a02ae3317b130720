"""``contact-vv article``: the runs and thresholds the article's claims are judged from
(:mod:`reports.studies.claims.sources`), run where ``DIR`` lacks them, after their cost
estimate is printed. Each source runs with its grid study (``run --convergence``): the
uncertainty of a claim's numbers comes from it."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import pandas as pd

from cases.loader import load_case
from reports.registry import solvers
from reports.registry.errors import UserError
from reports.run import threshold as th
from reports.run.plan import CasePlan, Limits, plan_case, request_study
from reports.run.sweep import plan_sweep
from reports.run.threshold_table import existing
from reports.store import layout
from reports.studies.claims.sources import (
    ARTICLE_NX,
    FRETTING_FREE,
    FRETTING_LOAD,
    FRETTING_LOAD_FREE,
    NEEDS,
    SOURCES,
    candidates,
    find,
    of_tier,
)
from reports.studies.events import EventOptions

#: the solvers a threshold of the claims runs (the FEM's thresholds are on request:
#: ``contact-vv threshold ... --solver fem``)
THRESHOLD_SOLVERS = ("ic", "analytic")
#: the solvers the claims' fretting sources leave out unless named: the FEM's four quick
#: sweeps with their grid studies would add over an hour to ``article --quick``
#: (``benchmarks/README.md``, "The resolution probe"), and the claims read the half-space
#: solver; ``--solver ic,fem,analytic`` adds them, with the probe's evidence (claim 12)
FRETTING_ON_REQUEST = ("fem",)


#: evaluations a bisection searched from a nearby threshold is costed at (2 where the
#: threshold has not moved, one or two more where it moved by an interval or more)
GUESSED = 3


@dataclass(frozen=True)
class ClaimThreshold:
    """One ``contact-vv threshold`` a claim reads: its ``request`` (case, key, event,
    bracket, resolution and grid factors; the tier, solvers and limits are the article
    run's), the article's own grid added where ``article_grid`` (81 cells a side), and with
    ``every_output`` one bisection after each of ``cycles`` and each output cycle of the
    case, each run cut there."""

    claim: int
    request: th.Request
    article_grid: bool = False
    every_output: bool = False
    cycles: tuple[int, ...] = ()  # outputs added to the case's (fretting)


def _request(case: str, param: str, event: str, lo: float, hi: float, resolution: float,
             grids: tuple[float, ...]) -> th.Request:
    return th.Request(case=case, param=param, event=event, lo=lo, hi=hi,
                      resolution=resolution, grids=grids, solvers=THRESHOLD_SOLVERS,
                      explicit=False)


THRESHOLDS = (
    # claim 4: where the sliding sphere's σ_VM maximum reaches the surface (s = 0)
    ClaimThreshold(4, _request("sliding_friction", "friction.mu", "vm_max_on_surface", 0.2,
                               0.5, 0.005, (1.0 / 1.5, 1.0, 2.0)), article_grid=True),
    # claim 13: the fretting regime change in β, under both normal controls, with the
    # transverse motion held and free
    *(ClaimThreshold(13, _request(case, "friction.beta", "gross_to_partial_slip", 45.0, 90.0,
                                  1.0, (1.0 / 1.5, 1.0)), every_output=True, cycles=(1, 100))
      for case in ("fretting_orthotropic", FRETTING_LOAD, FRETTING_FREE, FRETTING_LOAD_FREE)),
)


@dataclass
class Work:
    """What ``article`` will run: case plans and threshold requests, with their cost."""

    plans: list[CasePlan] = field(default_factory=list)
    requests: list[th.Request] = field(default_factory=list)
    seconds: float = 0.0
    unknown: list[str] = field(default_factory=list)

    def describe(self) -> str:
        if not (self.plans or self.requests):
            return "article: every run it needs is in the results directory"
        runs = sum(len(p.units()) for p in self.plans)
        text = (f"article: {len(self.plans)} case(s) to run ({runs} solver runs, with their "
                f"grid studies) and {len(self.requests)} threshold(s); estimated "
                f"{self.seconds / 60:.1f} min")
        if self.unknown:
            text += f" (no estimate for {', '.join(sorted(set(self.unknown)))})"
        return text


def _cost(work: Work, solver: str, case, times: float) -> None:
    cost = solvers.estimate(solver, case)
    if cost is None:
        work.unknown.append(solver)
    else:
        work.seconds += times * cost.seconds


def _have(table: pd.DataFrame | None, case: str, spec: ClaimThreshold, at: str,
          quick: bool) -> bool:
    """Whether thresholds.csv already holds the ic rows of a threshold."""
    if table is None or table.empty:
        return False
    r = spec.request
    t = table[(table["case"] == case) & (table["event"] == r.event)
              & (table["param"] == r.param) & (table["solver"] == "ic")
              & of_tier(table, quick) & table["threshold"].notna()]
    return bool(len(t[t["at"].astype(str) == at])) if at else bool(len(t))


def threshold_requests(spec: ClaimThreshold, quick: bool, chosen: list[str],
                       limits: Limits) -> list[tuple[th.Request, str]]:
    """The requests of one threshold the claims read, with the ``at`` label each writes."""
    base = spec.request
    case = load_case(base.case, quick=quick)[0]
    grids = tuple(sorted({*base.grids, *([ARTICLE_NX / case.grid.nx] if spec.article_grid
                                         else [])}))
    names = tuple(s for s in base.solvers if s in chosen)
    outputs = [None]
    if spec.every_output and case.fretting is not None:
        outputs = sorted({*spec.cycles, *(int(c) for c in case.fretting.output_cycles)})
    out = []
    for n in outputs:
        overrides = {} if n is None else {"fretting.cycles": n, "fretting.output_cycles": [n]}
        if n is not None and case.fretting.jump > n / 4:
            # fewer cycles than four jumps: a jump of a quarter of them (one: none)
            overrides["fretting.jump"] = float(max(1, n // 4))
        out.append((replace(base, grids=grids, solvers=names, quick=quick,
                            overrides=overrides,
                            options=EventOptions("" if n is None else str(n)),
                            limits=limits),
                    "" if n is None else f"cycle={n}"))
    return out


def plan(out: Path, quick: bool, chosen: list[str], limits: Limits,
         claims: tuple[int, ...], explicit: bool) -> Work:
    """What the claims need that ``out`` lacks, and its estimated cost."""
    work = Work()
    for key in dict.fromkeys(k for n in claims for k in NEEDS[n]):
        source = SOURCES[key]
        found, why = find(out, source, quick)
        if found is not None:
            continue
        mine = layout.case_dir(out, candidates(source)[-1])
        if mine.exists():  # a run of other points or size: not replaced behind its back
            raise UserError(f"{mine} does not serve the article ({why}); remove it or use "
                            "another --out")
        names = chosen
        if not explicit and load_case(source.case, quick=quick)[0].kind == "fretting":
            names = [s for s in chosen if s not in FRETTING_ON_REQUEST]
        if source.key:
            p = plan_sweep(source.case, [(source.key, list(source.values))], names,
                           quick=quick, limits=limits, explicit=explicit)
        else:
            p = plan_case(source.case, names, quick=quick, limits=limits, explicit=explicit)
        work.plans.append(p)
        for i, s in p.units():
            _cost(work, s, p.points[i], 1.0 + (0.65 if solvers.record(s).refine else 0.0))
    if work.plans:
        work.plans = request_study(work.plans, "convergence")[0]
    table = existing(out)
    for spec in THRESHOLDS:
        if spec.claim not in claims:
            continue
        name = load_case(spec.request.case, quick=quick)[0].name
        searched = False  # the first bisection; the others search from its threshold
        for request, at in threshold_requests(spec, quick, chosen, limits):
            if _have(table, name, spec, at, quick):
                continue
            work.requests.append(request)
            case = load_case(request.case, quick=quick, overrides=request.overrides)[0]
            full = 2 + math.ceil(math.log2((request.hi - request.lo) / request.resolution))
            sizes = [max(g, 1.0) ** 2 for g in request.grids]
            evaluations = (0 if searched else full * sizes[0] - GUESSED * sizes[0]) \
                + GUESSED * sum(sizes)
            searched = True
            for s in request.solvers:
                _cost(work, s, case, evaluations)
    return work


def execute(work: Work, out: Path, *, progress: bool | None,
            report: Callable[[list], int], log: Callable[[str], None] | None,
            cluster: Any = None) -> int:
    """Run the plans and thresholds of ``work`` (on ``cluster``, a
    :class:`reports.run.cluster.DaskExecutor`, where given); the worst exit status of
    the runs."""
    from reports.run.runner import execute as run_plan
    from reports.run.threshold_table import write_rows

    if cluster is None:
        codes = [report([run_plan(p, out, progress=progress)]) for p in work.plans]
    else:
        from reports.run.cluster import execute_cases

        codes = [report([r]) for r in execute_cases(work.plans, out, cluster, progress)]
    found: dict[tuple[str, str], list[str]] = {}
    guesses: dict = {}  # each output cycle's bisection searched from the one before
    for k, request in enumerate(work.requests):
        rows = th.run(request, guesses=guesses, cluster=cluster)
        write_rows(out, rows)
        group = (Path(request.case).stem, request.event)
        found.setdefault(group, []).extend(
            f"{r['solver']} {r['grid']}{' ' + r['at'] if r['at'] else ''} "
            + (f"{r['threshold']:.4g}" if r["status"].startswith(("bisected", "exact"))
               else r["status"].split(":")[0]) for r in rows)
        last = k + 1 == len(work.requests) or \
            (Path(work.requests[k + 1].case).stem, work.requests[k + 1].event) != group
        if last and log is not None:  # one line per threshold study of the claims
            log(f"{group[0]} {group[1]} in {request.param}: " + ", ".join(found[group]))
    return max(codes, default=0)
