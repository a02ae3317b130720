"""Where the FEM's time and memory go on each quick point (issue 58).

    python benchmarks/fem_stages.py                       # every quick FEM point
    python benchmarks/fem_stages.py --case fretting_orthotropic:2 --threads 1

Each ``CASE:INDEX`` (quick set-up, sweep point INDEX; default: every point of every
bundled case the FEM runs) is run by ``fem_reference.solve`` in a fresh process (a cold
point: no kept block), with the stages timed by wrapping the functions that do them:
meshing, assembly, factorisation, condensation, the run's set-up (contact points,
probes, far-field compliance, Hertz start), the contact solves (each semi-smooth or
augmented solve, counted with its Newton iterations) and the output (stress recovery and
sampling of every output step).  Printed as a Markdown table with the work counts
(unknowns of the block, of the condensed contact system, factorisations, contact solves,
Newton steps) and the process's peak RSS.
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time
from collections import defaultdict

STAGES = ("mesh", "assembly", "factorisation", "condensation", "setup", "solves", "output")


def _wrap(owner, name: str, stage: str, clock: dict, counts: dict) -> None:
    inner = getattr(owner, name)

    def timed(*args, **kwargs):
        t0 = time.perf_counter()
        try:
            return inner(*args, **kwargs)
        finally:
            clock[stage] += time.perf_counter() - t0
            counts[stage] += 1

    setattr(owner, name, timed)


def measure(spec: str, overrides: dict | None = None) -> dict:
    """One point, in this process: stage times [s], counts and the peak RSS [MB]
    (``overrides``: dotted case keys, as ``--set``)."""
    import fem_reference.loading as loading
    import fem_reference.model.block as block
    import fem_reference.model.elasticity as elasticity
    import fem_reference.solver as solver
    from cases.loader import load_case

    clock: dict = defaultdict(float)
    counts: dict = defaultdict(int)
    _wrap(block, "block_mesh", "mesh", clock, counts)
    _wrap(block, "stiffness", "assembly", clock, counts)
    _wrap(elasticity.Factorization, "__init__", "factorisation", clock, counts)
    _wrap(elasticity.Factorization, "schur_inverse", "condensation", clock, counts)
    _wrap(solver, "start_run", "setup", clock, counts)
    _wrap(solver, "step_output", "output", clock, counts)
    newton = []
    for name in ("semismooth", "augmented"):  # the contact solves of every load path
        inner = getattr(loading, name)

        def solved(*args, _inner=inner, **kwargs):
            t0 = time.perf_counter()
            sol = _inner(*args, **kwargs)
            clock["solves"] += time.perf_counter() - t0
            counts["solves"] += 1
            newton.append(int(sol.iterations))
            return sol

        setattr(loading, name, solved)
    name, _, index = spec.partition(":")
    case = load_case(name, quick=True, overrides=overrides or {})[int(index or 0)]
    t0 = time.perf_counter()
    result = solver.solve(case, vtu=False)
    wall = time.perf_counter() - t0
    meta = result.meta
    # the set-up's own time excludes the solves it does not make; the condensation is
    # timed inside the factorisation's owner, not inside Factorization.__init__
    return {"point": f"{name}:{index or 0}", "param": case.param or "", "wall_s": wall,
            **{f"{s}_s": clock[s] for s in STAGES},
            "model": meta["model"], "elements": meta["elements"], "dofs": meta["dofs"],
            "m": meta["surface_dofs"], "factorisations": counts["factorisation"],
            "solves": counts["solves"], "newton": sum(newton),
            "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}


def fem_points() -> list[str]:
    """Every quick point of every bundled case the FEM runs by default."""
    from cases.loader import BUNDLED, load_case
    from reports.registry import solvers

    return [f"{name}:{i}" for name in BUNDLED
            for i, case in enumerate(load_case(name, quick=True))
            if solvers.unsupported("fem", case) is None
            and solvers.not_by_default("fem", case) is None]


def _overrides(pairs: list[str]) -> dict:
    """``KEY=VALUE`` pairs as case overrides (a number where the value reads as one)."""
    out = {}
    for kv in pairs:
        key, _, text = kv.partition("=")
        try:
            out[key] = float(text)
        except ValueError:
            out[key] = text
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", nargs="*", help="CASE:INDEX, quick set-up (default: all)")
    ap.add_argument("--threads", type=int, default=None, help="BLAS/PARDISO threads")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a dotted case key for every point, e.g. fem.contact=augmented")
    ap.add_argument("--one", help=argparse.SUPPRESS)  # the child process
    args = ap.parse_args()
    if args.one:
        if args.threads:
            from threadpoolctl import threadpool_limits

            threadpool_limits(args.threads)
        print(json.dumps(measure(args.one, _overrides(args.set))))
        return
    rows = []
    for spec in args.case or fem_points():
        cmd = [sys.executable, __file__, "--one", spec,
               *(x for kv in args.set for x in ("--set", kv))]
        if args.threads:
            cmd += ["--threads", str(args.threads)]
        out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
        rows.append(json.loads(out.strip().splitlines()[-1]))
        print(rows[-1], file=sys.stderr, flush=True)
    head = ["point", "param", "model", "elements", "dofs", "m", "factorisations", "solves",
            "newton", *[f"{s}_s" for s in STAGES], "wall_s", "peak_mb"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for r in rows:
        print("| " + " | ".join(f"{r[k]:.1f}" if isinstance(r[k], float) else str(r[k])
                                for k in head) + " |")
    total = {k: sum(r[k] for r in rows) for k in ("wall_s", *[f"{s}_s" for s in STAGES])}
    print("\ntotal: " + ", ".join(f"{k} {v:.1f}" for k, v in total.items()))


if __name__ == "__main__":
    main()
