"""The FEM's model-form term: how its scalars change when the finite block grows.

    python benchmarks/fem_block.py                          # the four measured cases
    python benchmarks/fem_block.py --case hertz:0 --blocks 20 40

The FEM models a block of half-width and depth ``fem.block`` / ``fem.depth`` (in a0)
instead of a half-space.  For each ``CASE:INDEX`` (quick set-up, sweep point INDEX) the
FEM runs with both set to each of ``--blocks`` (the mesh regenerated, the contact-zone
element size unchanged) and the relative change of p_max and σ_VM,max from the first
block to the last is printed.  ``reports.registry.solvers.FEM_BLOCK_TERMS`` holds twice the
largest change (an error decaying like a0/L leaves as much again beyond the last block).
"""

from __future__ import annotations

import argparse
import time

CASES = ["hertz:0", "sliding_friction:1", "cattaneo_mindlin:1", "dissimilar:0"]
QUANTITIES = ("p_max", "vm_max", "a_x", "contact_area")


def run(spec: str, block: float) -> dict[str, float]:
    from cases.loader import load_case
    from fem_reference import solve

    name, _, index = spec.partition(":")
    case = load_case(name, quick=True,
                     overrides={"fem.block": block, "fem.depth": block})[int(index or 0)]
    t0 = time.perf_counter()
    row = solve(case).summary_rows()[-1]
    return {"wall_s": time.perf_counter() - t0, **{q: float(row[q]) for q in QUANTITIES}}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", nargs="+", default=CASES, help="CASE:INDEX, quick set-up")
    ap.add_argument("--blocks", nargs="+", type=float, default=[20.0, 40.0])
    args = ap.parse_args()
    for spec in args.case:
        rows = {b: run(spec, b) for b in args.blocks}
        for b, r in rows.items():
            print(spec, f"block {b:g} a0:", ", ".join(f"{k} {v:.6g}" for k, v in r.items()),
                  flush=True)
        first, last = rows[args.blocks[0]], rows[args.blocks[-1]]
        print(spec, "change:", ", ".join(
            f"{q} {100 * (last[q] - first[q]) / first[q]:+.3f} %" for q in ("p_max", "vm_max")),
            flush=True)


if __name__ == "__main__":
    main()
