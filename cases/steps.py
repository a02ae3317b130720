"""The output steps of a case: the step numbers every solver writes, one definition.

Results of two solvers meet step by step (:func:`reports.compare.point.common_steps`),
and an ``[external.NAME]`` table names the steps of its files, so the numbers are a fact
of the case, not of a solver:

- static cases: step 0;
- sliding wear: step k is the state after k sliding steps of ``sliding_wear.step`` (s =
  k step); the output steps are 0, the last one and round(s / step) for each
  ``output_s`` distance;
- fretting: step n is the end of simulated cycle n (real cycle n J, J the cycle jump);
  the output steps are the simulated cycles that end at the ``output_cycles`` within the
  run, and the last one.

And the path of a static case's normal loading where it depends on the path
(:func:`normal_fractions`), so that every incremental solver walks the same one.
"""

from __future__ import annotations

import math

import numpy as np

from .model import Case, CaseError, Fretting, SlidingWear

#: an incremental normal loading (:func:`normal_fractions`): its contact radius grows from
#: a fifth of the final one to 0.98 of it by a constant ratio per increment, 1 +
#: LOADING_GROWTH / (|β| μ) within RATIOS (7 to 19 increments with the last), then by 2 %
FIRST_RADIUS, LAST_BUT_ONE, LOADING_GROWTH, RATIOS = 0.2, 0.98, 0.01, (1.1, 1.4)
#: the smallest first contact of that loading, in cells of the grid
FIRST_CONTACT_CELLS = 2.0


def sliding_steps(sw: SlidingWear) -> int:
    """The number of sliding steps; CaseError unless the distance is a whole number of
    steps."""
    n = int(round(sw.distance / sw.step))
    if n < 1 or abs(n * sw.step - sw.distance) > 1e-9 * sw.distance:
        raise CaseError(f"sliding_wear.distance = {sw.distance} is not a whole number of "
                        f"steps of sliding_wear.step = {sw.step}")
    return n


def sliding_outputs(sw: SlidingWear) -> list[int]:
    """The output steps of a sliding-wear run (module doc), ascending; CaseError for an
    ``output_s`` distance outside the run."""
    n = sliding_steps(sw)
    bad = [s for s in sw.output_s if not 0 <= round(s / sw.step) <= n]
    if bad:
        raise CaseError(f"sliding_wear.output_s = {list(sw.output_s)}: {bad} lie outside "
                        f"the run (0 .. {sw.distance:g} mm)")
    return sorted({round(s / sw.step) for s in sw.output_s} | {0, n})


def fretting_outputs(fr: Fretting) -> dict[int, int]:
    """Output step (simulated cycle) -> the real cycle it ends (module doc), ascending."""
    out = {fr.simulated_cycle(c): c for c in fr.output_cycles if c <= fr.cycles}
    out.setdefault(fr.simulated_cycles, fr.cycles)
    return dict(sorted(out.items()))


def output_steps(case: Case) -> list[int]:
    """The step numbers of ``case``'s output steps, ascending (module doc)."""
    if case.kind == "sliding_wear":
        return sliding_outputs(case.sliding_wear)
    if case.kind == "fretting":
        return list(fretting_outputs(case.fretting))
    return [0]


def normal_fractions(case: Case) -> tuple[float, ...]:
    """The fractions of the normal load (or approach) of the increments of a normal
    loading whose result depends on the path — friction between dissimilar materials
    (Spence's compression, docs/formulation.md §2.9): a point that sticks keeps the
    displacement it had when it stuck, so the loading is a sequence of contact radii
    (the load ∝ a³, the approach ∝ a²).  The radii grow by a constant ratio, so that each
    increment leaves the same relative imprint on the stick zone's history — a ring in
    the traction where the increment's stick zone ended, of a size ∝ |β| μ (ratio − 1),
    hence the ratio 1 + :data:`LOADING_GROWTH` / (|β| μ) within :data:`RATIOS`; the
    thinner the slip annulus, the more of the contact keeps such rings — and the last
    step is 2 % of the radius, the stick radius's error (a point sticks an increment
    late: c = k a of the increment before).  The first contact spans at least
    :data:`FIRST_CONTACT_CELLS` of the grid (Hertz's radius).  Measured against the
    self-similar solution
    (:func:`analytic.spence.compression`): benchmarks/README.md, "Spence's compression,
    exact"."""
    power = 3 if case.load.P is not None else 2
    a0, _ = case.hertz_scales
    first = min(max(FIRST_RADIUS, FIRST_CONTACT_CELLS * max(case.grid.dx, case.grid.dy) / a0),
                LAST_BUT_ONE)
    coupling = abs(case.dundurs_beta) * max(case.friction.mu1, case.friction.mu2)
    lo, hi = RATIOS
    ratio = min(max(1.0 + LOADING_GROWTH / coupling, lo), hi) if coupling > 0 else hi
    steps = max(math.ceil(math.log(LAST_BUT_ONE / first) / math.log(ratio)), 5) + 1
    radii = (*(float(r) for r in np.geomspace(first, LAST_BUT_ONE, steps)), 1.0)
    return tuple(r ** power for r in radii)
