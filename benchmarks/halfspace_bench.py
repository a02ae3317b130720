"""Half-space solver benchmark: wall time, iterations and peak memory.

    python benchmarks/halfspace_bench.py [--sizes 81 256 512 1024] [--out benchmarks/README.md]

Runs each measurement in its own process (peak RSS via getrusage) on the Hertz case:
the frictionless normal solve, the orthotropic full-sliding step (mu = 0.25/0.5,
beta = 45 deg) and the sigma_VM block of 64 layers under a 256^2 grid.  Prints a
markdown table and, with --out, writes it into that file between markers.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

WORKER = r"""
import json, resource, sys, time
import numpy as np
from cases import load_case
from cases.model import Friction
from halfspace.problem import contact_solver, profile, stress_evaluator
from halfspace.stresses import StressEvaluator
kind, n = sys.argv[1], int(sys.argv[2])
case = load_case("hertz", overrides={"grid.nx": n, "grid.ny": n})[0]
t0 = time.perf_counter()
if kind == "block":
    sol = contact_solver(case).solve(profile(case), P=case.load.P)
    t0 = time.perf_counter()
    ev = StressEvaluator(case.grid, np.linspace(0.0, 0.3, 64), case.b.nu, "b")
    out = ev.block(sol.state.p_x, sol.state.p_y, sol.state.p_n)
    iters = 0
else:
    if kind == "sliding":
        case = case.with_changes(friction=Friction(0.25, 0.5, 45.0))
    solver = contact_solver(case)
    kw = {"shift": (1e3, 0.0)} if kind == "sliding" else {}
    sol = solver.solve(profile(case), P=case.load.P, **kw)
    iters = sol.iterations
wall = time.perf_counter() - t0
rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
print(json.dumps({"kind": kind, "n": n, "wall_s": wall, "iterations": iters, "peak_mb": rss}))
"""

BEGIN, END = "<!-- halfspace-bench:begin -->", "<!-- halfspace-bench:end -->"


def run(kind: str, n: int) -> dict:
    env = dict(os.environ, OMP_NUM_THREADS="1")
    out = subprocess.run([sys.executable, "-c", WORKER, kind, str(n)], capture_output=True,
                         text=True, env=env, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def table(rows: list[dict]) -> str:
    head = ("| measurement | grid | wall time [s] | iterations | peak memory [MB] |\n"
            "|---|---|---|---|---|\n")
    names = {"normal": "Hertz normal solve (Polonsky-Keer CG)",
             "sliding": "orthotropic full sliding step (PK + FISTA)",
             "block": "sigma_VM block, 64 layers"}
    return head + "".join(
        f"| {names[r['kind']]} | {r['n']}² | {r['wall_s']:.2f} | {r['iterations']} | "
        f"{r['peak_mb']:.0f} |\n" for r in rows)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[81, 256, 512, 1024])
    ap.add_argument("--out", type=Path)
    args = ap.parse_args()
    rows = []
    for kind in ("normal", "sliding"):
        for n in args.sizes:
            rows.append(run(kind, n))
            print(rows[-1], flush=True)
    rows.append(run("block", 256))
    print(rows[-1], flush=True)
    stamp = (f"Measured {time.strftime('%Y-%m-%d')} on {platform.machine()}, "
             f"{os.cpu_count()} cores, Python {platform.python_version()}, one FFT thread; "
             f"wall time excludes interpreter start-up, includes building the kernels.\n\n")
    text = stamp + table(rows)
    print(text)
    if args.out:
        doc = args.out.read_text() if args.out.exists() else ""
        block = f"{BEGIN}\n{text}{END}"
        if BEGIN in doc and END in doc:
            doc = doc[: doc.index(BEGIN)] + block + doc[doc.index(END) + len(END):]
        else:
            doc = doc + "\n" + block + "\n"
        args.out.write_text(doc)


if __name__ == "__main__":
    main()
