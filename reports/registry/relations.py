"""Metamorphic relations as solvers: the oracles of the orthotropic laws where no closed
form exists.

A relation runs a base solver on a transformed case and maps the result back onto the
original one (:mod:`cases.symmetry`); the pair ``<base>-<base>+<relation>`` (e.g.
``ic-ic+mirror``) is compared and gated like any other, against the relation's own
allowance, not the base's budget: an exact relation on the same grid allows round-off
only (the iterations stop at a relative residual of 1e-10), the turn by a non-right
angle the difference of two discretisations of the same problem, twice the base's
budget.  Relations run with their base on a case with orthotropic friction or wear, the
laws they check (:func:`applies`), in the quick tier or when named
(:func:`reports.run.plan.select_solvers`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from cases import symmetry
from cases.model import Case
from cases.result import RunResult

#: what an exact relation allows on every metric: round-off of the solvers' iterations
EXACT = 1e-6


@dataclass(frozen=True)
class Relation:
    """A transform of the case and the map of its result back (:mod:`cases.symmetry`)."""

    name: str
    transform: Callable[[Case], Case]
    back: Callable[[RunResult], RunResult]
    exact: bool
    meaning: str


RELATIONS = (
    Relation("axes90", symmetry.axes_turned_90, symmetry.same, True,
             "beta + 90 with mu1 <-> mu2 and i1 <-> i2: the same problem"),
    Relation("axes180", symmetry.axes_turned_180, symmetry.same, True,
             "beta + 180: the same problem (the friction ellipse and the wear law are even)"),
    Relation("mirror", symmetry.mirrored, symmetry.mirror_back, True,
             "the mirror y -> -y with beta -> -beta: the mirrored result"),
    Relation("turned", symmetry.turned, symmetry.turn_back, False,
             f"load direction and friction axes turned by {symmetry.TURN:g} deg: the same "
             "invariants (the sense of beta)"),
)


def applies(case: Case) -> str | None:
    """None when the relations check something on ``case`` (orthotropic friction or
    wear), else why not."""
    f = case.friction
    orthotropic = f.mu1 != f.mu2 or case.a.i1 != case.a.i2 or case.b.i1 != case.b.i2
    return None if orthotropic else "isotropic friction and wear: no orthotropic law to check"


def wrap(relation: Relation, solve: Callable[..., RunResult]) -> Callable[..., RunResult]:
    """The solve of a relation: ``solve`` on the transformed case, mapped back; each output
    step handed over once mapped."""
    def run(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
        result = relation.back(solve(relation.transform(case), progress=progress,
                                     on_output=None))
        result.events = None  # compared with its base, not watched for regime events
        for step in result.steps if on_output is not None else ():
            on_output(step)
        return result

    return run


def budget(relation: Relation, base_budget: Callable[[str, str], float]
           ) -> Callable[[str, str], float]:
    """The allowance of a relation's pair (module doc)."""
    if relation.exact:
        return lambda quantity, metric: EXACT
    return lambda quantity, metric: 2.0 * base_budget(quantity, metric)
