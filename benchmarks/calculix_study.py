"""The calculix plugin's error budget from its own measurements (issue 74, point 4): its
errors against a reference solver on a case, at several element sizes and penalty
parameters, each run through the suite's own comparison (``metrics.csv``).

    python benchmarks/calculix_study.py cattaneo_mindlin --h 0.125 0.1 0.0833
    python benchmarks/calculix_study.py cattaneo_mindlin --h 0.1 --k-n 10 20 40 --k-t 5 10 20
    python benchmarks/calculix_study.py spence --h 0.125 --against analytic

``--h`` sets the case's ``fem.h`` (and ``fem.h_surface``; the plugin meshes at
``calculix_adapter.model.H_FACTOR`` times it), ``--k-n`` / ``--k-t`` the penalty's normal
stiffness and stick slope in E*/h (``K_N``, ``K_T``), one changed at a time from the
plugin's values.  For each run it prints the worst value of every calculix row of the
``--against`` pair over the case's sweep points (the quick tier's), the wall time, the
Newton iterations and the equations, as JSON lines.  Each run is a fresh
``contact-vv run`` in this process, one thread for ccx.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time
from pathlib import Path


def one(case: str, h: float, k_n: float | None, k_t: float | None, against: str) -> dict:
    import pandas as pd

    from calculix_adapter import model as ccx_model
    from reports.cli import main

    saved = ccx_model.K_N, ccx_model.K_T
    ccx_model.K_N = k_n if k_n is not None else saved[0]
    ccx_model.K_T = k_t if k_t is not None else saved[1]
    try:
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "res"
            t0 = time.perf_counter()
            code = main(["run", case, "--quick", "--no-progress", "--solver",
                         f"calculix,{against}", "--set", f"fem.h={h}", "--set",
                         f"fem.h_surface={h}", "--out", str(out)])
            wall = time.perf_counter() - t0
            name = Path(case).stem if case.endswith(".toml") else case
            m = pd.read_csv(out / name / "metrics.csv")
            s = pd.read_csv(out / name / "summary.csv")
    finally:
        ccx_model.K_N, ccx_model.K_T = saved
    rows = m[m["pair"] == f"calculix-{against}"]
    worst = rows.groupby(["quantity", "metric"])["value"].max()
    ours = s[s["solver"] == "calculix"]
    return {"case": case, "fem.h": h, "K_N": ccx_model.K_N if k_n is None else k_n,
            "K_T": ccx_model.K_T if k_t is None else k_t, "exit": code,
            "wall_s": round(wall, 1),
            "iterations": ours["iterations"].tolist(), "nodes": int(ours["nodes"].iloc[0]),
            "errors": {f"{q}.{k}": round(float(v), 5) for (q, k), v in worst.items()}}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", help="a bundled case name or a case file")
    ap.add_argument("--h", type=float, nargs="+", default=[0.1])
    ap.add_argument("--k-n", type=float, nargs="*", default=[])
    ap.add_argument("--k-t", type=float, nargs="*", default=[])
    ap.add_argument("--against", default="analytic")
    args = ap.parse_args()
    runs = [(h, None, None) for h in args.h]
    runs += [(args.h[0], k, None) for k in args.k_n] + [(args.h[0], None, k) for k in args.k_t]
    for h, k_n, k_t in runs:
        print(json.dumps(one(args.case, h, k_n, k_t, args.against)), flush=True)


if __name__ == "__main__":
    main()
