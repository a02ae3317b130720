"""What a case will cost the half-space solver, estimated before anything is allocated.

Memory: the surface operator holds 9 complex kernels on the zero-padded (2nx)(2ny) grid
plus work arrays, about 40 float64 grids of that size (1280 bytes per cell); the stress
planes keep, per depth layer, the spectra of 18 coefficients for each of the two planes
(576 bytes per cell and layer); fretting keeps one warm-start state (8 grids) per step
of the cycle, and the loop tables grow with the simulated steps.

Time: contact solves x cells x a per-cell cost measured on this project's runs (4.8e-6 s
for a frictional pin-on-disk step on 81², 4e-5 s for a partial-slip fretting step on 61²;
2e-5 s is used, an order-of-magnitude figure), plus the stress planes of every output
step.  Its calibration, :data:`TIME_FACTOR`: the wall times of the test suite's and the
quick chain's runs lie within that factor of the estimate (benchmarks/README.md, "The
cost estimates' calibration").
"""

from __future__ import annotations

from cases.model import Case
from cases.result import Cost

SECONDS_PER_CELL_SOLVE = 2e-5
SECONDS_PER_CELL_LAYER = 2e-7  # one plane pair's stresses, per cell and depth layer
STATIC_SOLVES = 12  # normal and tangential load increments of a static case (at most: 7 + 5)
TIME_FACTOR = 10.0  # measured wall times lie within this factor of the estimate


def contact_solves(case: Case) -> tuple[int, int]:
    """(contact solves, output steps) of the case's load path."""
    if case.kind == "sliding_wear":
        sw = case.sliding_wear
        return int(round(sw.distance / sw.step)) + 1, max(len(sw.output_s), 1)
    if case.kind == "fretting":
        fr = case.fretting
        n_sim = fr.simulated_cycles
        return n_sim * fr.steps_per_cycle + fr.steps_per_cycle // 4 + 1, \
            max(len(fr.output_cycles), 1)
    return STATIC_SOLVES, 1


def estimate(case: Case) -> Cost:
    """Peak memory and wall time of :func:`halfspace.solve` on ``case`` (module doc)."""
    g, nz = case.grid, case.stress.nz
    cells = g.nx * g.ny
    solves, outputs = contact_solves(case)
    terms = {("grid.nx", "grid.ny"): 1280.0 * cells,
             ("stress.nz", "grid.nx", "grid.ny"): 576.0 * nz * cells}
    if case.kind == "fretting":
        fr = case.fretting
        terms[("fretting.steps_per_cycle", "grid.nx", "grid.ny")] = \
            8 * 8.0 * cells * fr.steps_per_cycle
        terms[("fretting.cycles", "fretting.jump")] = 160.0 * solves  # loop rows
    elif case.kind == "sliding_wear":
        terms[("sliding_wear.distance", "sliding_wear.step")] = 10 * 8.0 * solves
    solve_s = SECONDS_PER_CELL_SOLVE * cells * solves
    stress_s = SECONDS_PER_CELL_LAYER * cells * nz * (outputs + 1)
    time_keys = {"fretting": ("fretting.cycles", "fretting.jump", "fretting.steps_per_cycle"),
                 "sliding_wear": ("sliding_wear.distance", "sliding_wear.step")
                 }.get(case.kind, ())
    if stress_s > solve_s:
        time_keys = ("stress.nz",)
    memory = sum(terms.values())
    drivers = sorted((t for t in terms if terms[t] >= 0.1 * memory), key=terms.get,
                     reverse=True)
    return Cost(memory=memory, seconds=solve_s + stress_s, time_factor=TIME_FACTOR,
                memory_keys=tuple(dict.fromkeys(k for t in drivers for k in t)),
                time_keys=time_keys + ("grid.nx", "grid.ny"))
