"""Qualitative events of a solver result, and the bisection that finds where one changes
(``contact-vv threshold``, :mod:`reports.run.threshold`).

An event is a yes/no property of one output step of a solver's result
(:class:`cases.result.StepResult`); :func:`bisect` halves a bracket of a parameter
until it is at most a resolution wide, keeping the event different at its ends.

- ``vm_max_on_surface``: the maximum of σ_VM over the subsurface planes the solver
  writes (xz and yz through the load centre, :func:`cases.result.vm_max_location`) lies
  on the surface: its depth z is at most ``surface_depth`` (default 0: the first layer of
  ``stress.z``, which is z = 0).  Any case kind whose solver writes σ_VM planes.
- ``gross_to_partial_slip``: the contact has stick cells at the selected output step
  (the surface ``state`` map holds a cell in ``STICK``; without a state map, the
  ``stick_area`` scalar is positive): partial slip; no stick cell is gross slip.
  Fretting cases only.

The output step is chosen by ``--at`` (:func:`select_step`): a sliding distance for
``sliding_wear`` cases, a cycle count for ``fretting`` cases, ``step=N`` for an output
step number; by default the last output step.

Exact thresholds (:func:`exact_threshold`): for ``vm_max_on_surface`` in ``friction.mu``
of a sphere in full sliding on an identical half-space (a static sliding case, or a
sliding-wear case at s = 0, before any wear), Hamilton's field has its maximum jump to
the trailing edge at the μ of :func:`analytic.sliding.surface_jump` (0.3047 for ν = 0.3).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from cases.model import Case
from cases.result import STICK, RunResult, StepResult, vm_max_location
from reports.registry import solvers
from reports.registry.errors import UserError


class EventUndefined(Exception):
    """The result lacks what the event needs (e.g. a closed form without σ_VM planes)."""


@dataclass(frozen=True)
class EventOptions:
    """How an event is read: the output step (``at``: '' for the last, ``s=V``,
    ``cycle=N``, ``step=N`` or a bare number read by the case kind) and the depth
    [mm] down to which a σ_VM maximum counts as on the surface."""

    at: str = ""
    surface_depth: float = 0.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.surface_depth) and self.surface_depth >= 0):
            raise UserError("--surface-depth must be a finite number >= 0")


@dataclass(frozen=True)
class Event:
    """A yes/no property of an output step; ``kinds`` the case kinds it applies to
    (None: all), ``true_means`` / ``false_means`` what its values say."""

    name: str
    test: Callable[[StepResult, EventOptions], bool]
    kinds: tuple[str, ...] | None
    true_means: str
    false_means: str

    def applies(self, case: Case) -> str | None:
        """None if the event applies to ``case``, else why not."""
        if self.kinds is None or case.kind in self.kinds:
            return None
        return (f"event {self.name} does not apply to case {case.name} (kind "
                f"{case.kind!r}; it needs a {' or '.join(self.kinds)} case)")


def vm_max_depth(step: StepResult) -> float:
    """Depth [mm] of the σ_VM maximum over the step's planes (xz, yz)."""
    value, _, _, z = vm_max_location(step.planes, 0.0, 0.0)
    if not math.isfinite(value):
        raise EventUndefined("the result has no σ_VM plane (a closed form with scalars only)")
    return float(z)


def vm_max_on_surface(step: StepResult, options: EventOptions) -> bool:
    """Whether the σ_VM maximum lies at depth <= ``options.surface_depth``."""
    return vm_max_depth(step) <= options.surface_depth + 1e-12


def has_stick(step: StepResult, options: EventOptions) -> bool:
    """Whether the step has stick cells (partial slip)."""
    state = step.surface.get("state")
    if state is not None and np.size(state):
        return bool(np.any(np.asarray(state) == STICK))
    area = step.scalars.get("stick_area")
    if area is None or not math.isfinite(float(area)):
        raise EventUndefined("the result has neither a stick/slip state map nor stick_area")
    return float(area) > 0.0


EVENTS: dict[str, Event] = {
    "vm_max_on_surface": Event("vm_max_on_surface", vm_max_on_surface, None,
                               "max σ_VM on the surface", "max σ_VM below the surface"),
    "gross_to_partial_slip": Event("gross_to_partial_slip", has_stick, ("fretting",),
                                   "partial slip (stick cells)", "gross slip (no stick)"),
}


def event(name: str) -> Event:
    """The event called ``name``; UserError naming the known ones otherwise."""
    if name not in EVENTS:
        raise UserError(f"--event {name!r}: unknown event (known: {', '.join(EVENTS)})")
    return EVENTS[name]


# ------------------------------------------------------------------ bisection


class NoChange(ValueError):
    """The event has the same value ``value`` at both ends of the bracket."""

    def __init__(self, message: str, value: bool):
        super().__init__(message)
        self.value = value


@dataclass(frozen=True)
class Bisection:
    """The final bracket [lo, hi], the event's values at its ends, and the number of
    evaluations made (ends included)."""

    lo: float
    hi: float
    at_lo: bool
    at_hi: bool
    evaluations: int

    @property
    def value(self) -> float:
        return 0.5 * (self.lo + self.hi)

    @property
    def uncertainty(self) -> float:
        return 0.5 * (self.hi - self.lo)


#: at most this many halvings: 2^-1100 of any finite bracket is below the smallest float
MAX_HALVINGS = 1100


def bisect(test: Callable[[float], bool], lo: float, hi: float, resolution: float, *,
           at_lo: bool | None = None, at_hi: bool | None = None,
           guess: Guess | None = None) -> Bisection:
    """Halve [lo, hi] until it is at most ``resolution`` wide, keeping ``test`` different
    at its ends, or until no float lies between them (a resolution below the bracket's
    float spacing: the returned interval is then wider than asked); ``at_lo``/``at_hi``
    are the end values if already known.
    :class:`NoChange` if ``test`` is the same at both ends.

    With a ``guess`` (the threshold of a nearby problem: another grid, another output
    cycle) the same final interval is searched from the guess outwards
    (:func:`_search_leaves`): where the event changes once in [lo, hi], as bisection
    assumes, the result is the one plain bisection gives, bit for bit, in 2 evaluations
    when the guess falls in it."""
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(f"bracket [{lo}, {hi}] is not an interval")
    if not (math.isfinite(resolution) and resolution > 0):
        raise ValueError(f"resolution {resolution} is not a positive number")
    halvings = _exact_halvings(lo, hi, resolution)
    if guess is not None and halvings is not None:
        return _search_leaves(test, lo, hi, halvings, at_lo, at_hi, guess)
    count = 0
    if at_lo is None:
        at_lo, count = bool(test(lo)), count + 1
    if at_hi is None:
        at_hi, count = bool(test(hi)), count + 1
    if at_lo == at_hi:
        raise NoChange(f"the event is {at_lo} at both ends of [{lo:g}, {hi:g}]", at_lo)
    # halvings to the resolution, and never past the floats between lo and hi: a
    # resolution below their spacing ends where the midpoint is an end (MAX_HALVINGS)
    ratio = (hi - lo) / resolution
    steps = MAX_HALVINGS if not math.isfinite(ratio) else \
        min(max(math.ceil(math.log2(ratio)), 0), MAX_HALVINGS)
    for _ in range(steps):
        if hi - lo <= resolution * (1 + 1e-9):
            break
        mid = 0.5 * lo + 0.5 * hi  # = 0.5 (lo + hi), which can overflow
        if not lo < mid < hi:  # the float spacing of the bracket: no narrower interval
            break
        if bool(test(mid)) == at_lo:
            lo = mid
        else:
            hi = mid
        count += 1
    return Bisection(lo, hi, at_lo, at_hi, count)


@dataclass(frozen=True)
class Guess:
    """Where a nearby bisection ended: its threshold ``value`` and the event ``at_lo``
    below it (the side a search from the guess turns to)."""

    value: float
    at_lo: bool


def _exact_halvings(lo: float, hi: float, resolution: float) -> int | None:
    """The halvings :func:`bisect` makes of [lo, hi] whatever the event, or None where
    the stop rule (the width within 1e-9 of the resolution) or the float spacing could
    end it at another depth on another path."""
    ratio = (hi - lo) / resolution
    if not (math.isfinite(ratio) and 1.0 < ratio < 2.0**50):
        return None
    steps = math.ceil(math.log2(ratio))
    if (hi - lo) / 2.0 ** (steps - 1) <= resolution * (1 + 1e-6) or \
            (hi - lo) / 2.0**steps <= 1e-12 * max(abs(lo), abs(hi)):
        return None
    return steps


def _leaf_point(lo: float, hi: float, halvings: int, k: int) -> float:
    """The k-th of the 2^halvings + 1 points that bisection of [lo, hi] can reach,
    computed by the same midpoints (bit for bit) as :func:`bisect` on its way there."""
    if k == 2**halvings:
        return hi
    a, b = lo, hi
    for bit in reversed(range(halvings)):
        mid = 0.5 * a + 0.5 * b
        a, b = (mid, b) if (k >> bit) & 1 else (a, mid)
    return a


def _search_leaves(test: Callable[[float], bool], lo: float, hi: float, halvings: int,
                   at_lo: bool | None, at_hi: bool | None, guess: Guess) -> Bisection:
    """The leaf of :func:`bisect`'s tree whose ends differ, found from the guess's leaf:
    its two ends, then outwards by doubling steps towards the side ``guess.at_lo`` points
    to (the other side if the change is not there), then halving."""
    n = 2**halvings
    known = {k: v for k, v in ((0, at_lo), (n, at_hi)) if v is not None}
    count = 0

    def at(k: int) -> bool:
        nonlocal count
        if k not in known:
            known[k], count = bool(test(_leaf_point(lo, hi, halvings, k))), count + 1
        return known[k]

    g = min(max(int((guess.value - lo) / (hi - lo) * n), 0), n - 1)
    if g + 1 < n and guess.value >= _leaf_point(lo, hi, halvings, g + 1):
        g += 1  # the leaf of the guess by its own end points, not the rounded ratio
    elif g > 0 and guess.value < _leaf_point(lo, hi, halvings, g):
        g -= 1
    if at(g) != at(g + 1):
        k = g
    else:
        v = at(g)
        up = (g + 1, 1, n) if v == guess.at_lo else (g, -1, 0)
        down = (g, -1, 0) if v == guess.at_lo else (g + 1, 1, n)
        for start, sign, end in (up, down):
            k = _gallop(at, v, start, sign, end)
            if k is not None:
                break
        else:
            raise NoChange(f"the event is {v} at both ends of [{lo:g}, {hi:g}]", v)
    return Bisection(_leaf_point(lo, hi, halvings, k), _leaf_point(lo, hi, halvings, k + 1),
                     at(k), at(k + 1), count)


def _gallop(at: Callable[[int], bool], v: bool, start: int, sign: int, end: int
            ) -> int | None:
    """From index ``start`` (event ``v``) towards ``end`` by steps 1, 2, 4, ... until the
    event differs, then halving back: the lower index of the leaf where it changes, or
    None if it is ``v`` up to ``end``."""
    j, step = start, 1
    while j != end:
        nxt = j + sign * min(step, abs(end - j))
        if at(nxt) != v:
            while abs(nxt - j) > 1:
                m = (j + nxt) // 2
                j, nxt = (m, nxt) if at(m) == v else (j, m)
            return min(j, nxt)
        j, step = nxt, 2 * step
    return None


# ------------------------------------------------------------------ output step


def _at_key(case: Case, at: str) -> tuple[str, float]:
    """(scalar, value) that ``--at`` selects the output step by."""
    key, eq, text = at.partition("=")
    if not eq:
        key, text = {"sliding_wear": "s", "fretting": "cycle"}.get(case.kind, "step"), at
    key = key.strip()
    if key not in ("s", "cycle", "step"):
        raise UserError(f"--at {at!r}: expected VALUE, s=VALUE, cycle=N or step=N")
    try:
        value = float(text)
    except ValueError:
        raise UserError(f"--at {at!r}: {text.strip()!r} is not a number") from None
    return key, value


def select_step(result: RunResult, case: Case, at: str) -> tuple[StepResult, str]:
    """The output step ``at`` selects (module doc) and its label (``s=320``)."""
    if not result.steps:
        raise EventUndefined("the result has no output step")
    if not at:
        k = len(result.steps) - 1
        return result.steps[k], step_label(case, result.steps[k], k)
    key, value = _at_key(case, at)
    found = []
    for k, step in enumerate(result.steps):
        v = float(step.number(k)) if key == "step" else float(step.scalars.get(key, math.nan))
        found.append(v)
        if math.isfinite(v) and abs(v - value) <= 1e-9 * max(1.0, abs(value)):
            return step, step_label(case, step, k)
    have = ", ".join(f"{v:g}" for v in found if math.isfinite(v)) or "none"
    hint = {"s": "sliding_wear.output_s", "cycle": "fretting.output_cycles"}.get(key)
    raise UserError(f"--at {at}: case {case.name} has no output step at {key} = {value:g} "
                    f"(outputs: {have})" + (f"; add it with --set {hint}=[...]" if hint else ""))


def step_label(case: Case, step: StepResult, index: int) -> str:
    """``s=V`` (sliding wear), ``cycle=N`` (fretting) or ``step=N`` of an output step."""
    for key in {"sliding_wear": ("s",), "fretting": ("cycle",)}.get(case.kind, ()):
        v = step.scalars.get(key)
        if v is not None and math.isfinite(float(v)):
            return f"{key}={float(v):g}"
    return f"step={step.number(index)}"


# ------------------------------------------------------------------ exact values


@dataclass(frozen=True)
class Exact:
    """An exact threshold: ``value`` to within ± ``resolution``/2, from ``reference``."""

    value: float
    resolution: float
    reference: str


def selected_distance(case: Case, at: str) -> float:
    """The sliding distance [mm] ``at`` selects in a sliding-wear case (the last output,
    the total distance, by default)."""
    sw = case.sliding_wear
    if sw is None:
        return math.nan
    if not at:
        return sw.distance
    key, value = _at_key(case, at)
    return value * sw.step if key == "step" else value if key == "s" else math.nan


def hamilton_applies(case: Case, at: str) -> str | None:
    """None if the step ``at`` selects is a sphere in full sliding on an identical
    half-space with isotropic friction (Hamilton 1983), else why not."""
    if not case.identical_materials:
        return "dissimilar materials (normal-tangential coupling)"
    if not case.friction.isotropic:
        return "orthotropic friction"
    if case.kind == "static" and case.load.tangential_mode == "sliding":
        return None
    if case.kind == "sliding_wear" and selected_distance(case, at) == 0.0:
        return None  # before any wear the pin is a Hertzian sphere in full sliding
    return "no closed-form σ_VM field (only a static sliding sphere, or a pin at s = 0)"


def exact_threshold(event_name: str, param: str, case: Case, options: EventOptions
                    ) -> Exact | str:
    """The exact threshold of ``event_name`` in ``param`` for ``case`` at the step
    ``options.at`` selects, or why there is none (module doc)."""
    if event_name != "vm_max_on_surface" or param != "friction.mu":
        return f"no closed form for {event_name} in {param}"
    if options.surface_depth > 0:
        return "the closed form is for the maximum on the surface itself (--surface-depth 0)"
    reason = hamilton_applies(case, options.at)
    if reason is not None:
        return reason
    surface_jump = solvers.record("analytic").entry("surface_jump")
    xtol = 1e-7  # brentq's tolerance in analytic.sliding.surface_jump
    jump = surface_jump(case.a.nu)
    return Exact(jump.mu, 2 * xtol, f"Hamilton (1983): analytic.sliding.surface_jump, "
                                    f"nu = {case.a.nu:g}")
