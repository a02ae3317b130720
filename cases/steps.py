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
"""

from __future__ import annotations

from .model import Case, CaseError, Fretting, SlidingWear


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
