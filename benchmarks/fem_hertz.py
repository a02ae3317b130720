"""Benchmark of the FEM reference: wall time and peak memory.

    python benchmarks/fem_hertz.py                 # Hertz at h = a0/8 and a0/4, 100 wear steps
    python benchmarks/fem_hertz.py --h 0.125 --block 20 --wear-steps 100 --mu 0 0.5

Each run happens in a fresh subprocess so its peak resident memory (``ru_maxrss``) is its
own.  Hertz: the static case of ``cases/hertz.toml`` (81 x 81 grid, 61 stress layers) with
the given ``fem`` settings; wear: ``cases/pin_on_disk.toml`` cut to ``--wear-steps`` steps
of 1 mm (output at the last step only).
"""

from __future__ import annotations

import argparse
import json
import multiprocessing as mp
import time


def _hertz(h: float, block: float, queue) -> None:
    import math
    import resource

    from cases.loader import load_case
    from cases.model import FemSettings
    from fem_reference import solve

    case = load_case("hertz")[0]
    case = case.with_changes(fem=FemSettings(block=block, depth=block, h=h))
    t0 = time.perf_counter()
    res = solve(case, vtu=True)
    wall = time.perf_counter() - t0
    sc = res.steps[0].scalars
    a0 = case.hertz_a0
    p0 = 3 * case.load.P / (2 * math.pi * a0**2)
    queue.put(dict(
        run="hertz", h=h, block=block, wall_s=wall,
        peak_rss_gb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6,
        dofs=res.meta["dofs"], contact_dofs=res.meta["surface_dofs"],
        p_max_p0=sc["p_max"] / p0, vm_axis_p0=sc["vm_axis_max"] / p0,
        vm_axis_z_a0=sc["vm_axis_z"] / a0, a_x_a0=sc["a_x"] / a0,
        timings={k: round(v, 2) for k, v in res.meta["timings"].items()},
    ))


def _wear(h: float, block: float, steps: int, mu: float, queue) -> None:
    import resource

    from cases.loader import load_case
    from cases.model import FemSettings
    from fem_reference import solve

    case = load_case("pin_on_disk", overrides={
        "friction.mu": mu, "sliding_wear.distance": float(steps),
        "sliding_wear.output_s": [float(steps)], "sliding_wear.step": 1.0})[0]
    case = case.with_changes(fem=FemSettings(block=block, depth=block, h=h))
    t0 = time.perf_counter()
    res = solve(case, vtu=True)
    wall = time.perf_counter() - t0
    last = res.steps[-1].scalars
    queue.put(dict(
        run="wear", h=h, block=block, mu=mu, steps=steps, wall_s=wall,
        peak_rss_gb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6,
        dofs=res.meta["dofs"], contact_dofs=res.meta["surface_dofs"], model=res.meta["model"],
        a_x_mm=last["a_x"], w_max_mm=last["w_max"],
        timings={k: round(v, 2) for k, v in res.meta["timings"].items()},
    ))


def _in_child(target, *args) -> dict:
    ctx = mp.get_context("spawn")
    queue = ctx.Queue()
    proc = ctx.Process(target=target, args=(*args, queue))
    proc.start()
    out = queue.get()
    proc.join()
    return out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--h", type=float, nargs="+", default=[0.125, 0.25],
                    help="element sizes in units of a0 (default: 0.125 0.25)")
    ap.add_argument("--block", type=float, default=20.0, help="block half-width/depth in a0")
    ap.add_argument("--wear-steps", type=int, default=100, help="1 mm wear steps (0: none)")
    ap.add_argument("--mu", type=float, nargs="+", default=[0.0],
                    help="friction coefficients of the wear runs (0: quarter block)")
    args = ap.parse_args(argv)
    for h in args.h:
        print(json.dumps(_in_child(_hertz, h, args.block)), flush=True)
    if args.wear_steps > 0:
        for mu in args.mu:
            print(json.dumps(_in_child(_wear, args.h[0], args.block, args.wear_steps, mu)),
                  flush=True)


if __name__ == "__main__":
    main()
