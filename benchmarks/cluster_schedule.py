"""The chain's cost on a cluster, computed from the planner's estimates (no solver runs).

    python benchmarks/cluster_schedule.py [--quick] [--workers 1,2,16,64]

Plans ``contact-vv run --all`` (article size, or ``--quick``) with the default solvers
and prints the planned cost (the sum of every unit's estimate, the resolution probes
included), the longest unit (with its case's probes after it, a lower bound of the wall
time on any number of workers) and, for each worker count, the wall
time of the schedule ``reports.run.cluster`` asks Dask for: every unit ready at the
start, a case's resolution probes once its units are done, each free worker taking the
longest ready unit (Dask's ``priority`` = the estimate).  A simulation on paper: it
assumes each unit takes its estimate on any worker and ignores the client's writing.
"""

from __future__ import annotations

import argparse
import heapq

from cases.loader import BUNDLED
from reports.registry import solvers
from reports.run.plan import plan_case, select_solvers


def tasks(quick: bool) -> list[tuple[str, str, float, bool]]:
    """(case, label, estimated seconds, is a study's run) of every unit of the chain."""
    chosen, skipped = select_solvers([], relations=quick)
    out = []
    for name in BUNDLED:
        plan = plan_case(name, chosen, quick=quick, skipped=skipped, explicit=False)
        runs = [(plan.points[i], s, False) for i, s in plan.units()]
        runs += [(g.case, g.solver, True) for g in plan.study_runs()]
        for case, s, probe in runs:
            cost = solvers.estimate(s, case)
            label = f"{name} [{case.param}] {s}" + (" (study)" if probe else "")
            out.append((name, label, 0.0 if cost is None else cost.seconds, probe))
    return out


def makespan(units: list[tuple[str, str, float, bool]], workers: int) -> float:
    """The wall time of the longest-first list schedule on ``workers`` (module doc)."""
    left = {}  # units of each case not yet finished
    for case, _, _, probe in units:
        if not probe:
            left[case] = left.get(case, 0) + 1
    ready = [(-t, k) for k, (case, _, t, probe) in enumerate(units) if not probe]
    waiting = {case: [(-t, k) for k, (c, _, t, p) in enumerate(units) if p and c == case]
               for case in left}
    heapq.heapify(ready)
    running: list[tuple[float, int]] = []  # (finish time, unit)
    free, now = workers, 0.0
    while ready or running:
        while free and ready:
            _, k = heapq.heappop(ready)
            heapq.heappush(running, (now + units[k][2], k))
            free -= 1
        now, k = heapq.heappop(running)
        free += 1
        case, _, _, probe = units[k]
        if not probe:
            left[case] -= 1
            if left[case] == 0:
                for item in waiting[case]:
                    heapq.heappush(ready, item)
    return now


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--workers", default="1,2,16,64")
    args = ap.parse_args()
    units = tasks(args.quick)
    total = sum(t for _, _, t, _ in units)
    longest = max(units, key=lambda u: u[2])
    print(f"{'quick' if args.quick else 'article-size'} chain: {len(units)} units, "
          f"planned cost {total / 3600:.2f} h ({total:.0f} s)")
    print(f"longest unit: {longest[1]}, {longest[2] / 3600:.2f} h "
          f"({longest[2]:.0f} s)")
    for n in (int(w) for w in args.workers.split(",")):
        span = makespan(units, n)
        print(f"{n:3d} workers: {span / 3600:6.2f} h ({span:7.0f} s), "
              f"{total / span / n:.0%} of the workers busy")


if __name__ == "__main__":
    main()
