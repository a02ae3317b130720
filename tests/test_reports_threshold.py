"""Thresholds (reports/run/threshold.py, reports/studies/events.py): the bisection against functions
with a known threshold, the events on hand-made steps, and the sliding-sphere friction
threshold of the half-space solver and the closed form against Hamilton's field
evaluated independently on a fine grid."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from analytic.pointforce import COMPONENTS
from analytic.sliding import sliding_sphere_stresses, trailing_edge_von_mises
from cases.result import SLIP, STICK, Plane, RunResult, StepResult, von_mises
from reports.registry.errors import UserError
from reports.run import threshold as th
from reports.studies.events import (
    MAX_HALVINGS,
    EventOptions,
    EventUndefined,
    Guess,
    NoChange,
    _exact_halvings,
    bisect,
    has_stick,
    select_step,
    vm_max_on_surface,
)

# ------------------------------------------------------------------ bisection


@pytest.mark.parametrize("true_above", [True, False])
@pytest.mark.parametrize(("t0", "resolution"), [(0.31416, 1e-3), (0.9, 0.01), (1e-3, 0.05)])
def test_bisection_finds_a_known_threshold(t0, resolution, true_above):
    calls = []

    def test(x: float) -> bool:
        calls.append(x)
        return (x > t0) == true_above

    b = bisect(test, 0.0, 1.0, resolution)
    assert b.lo <= t0 <= b.hi
    assert b.hi - b.lo <= resolution
    assert abs(b.value - t0) <= resolution / 2 == pytest.approx(resolution / 2)
    assert b.uncertainty <= resolution / 2
    assert (b.at_lo, b.at_hi) == (not true_above, true_above)
    # two ends plus ceil(log2(width / resolution)) halvings, each one evaluation
    assert b.evaluations == len(calls) == 2 + math.ceil(math.log2(1.0 / resolution) - 1e-9)


def test_bisection_uses_known_ends_and_refuses_no_change():
    calls = []

    def test(x: float) -> bool:
        calls.append(x)
        return x > 2.5

    b = bisect(test, 0.0, 10.0, 1.0, at_lo=False, at_hi=True)
    assert b.evaluations == len(calls) == 4 and 0.0 not in calls and 10.0 not in calls
    assert b.lo <= 2.5 <= b.hi
    with pytest.raises(NoChange, match="at both ends"):
        bisect(lambda x: True, 0.0, 1.0, 0.1)
    with pytest.raises(ValueError, match="not an interval"):
        bisect(test, 1.0, 0.0, 0.1)


@pytest.mark.parametrize(("lo", "hi", "t0", "resolution"), [
    (0.0, 1.0, 0.3, 1e-300),  # below the spacing of the floats near 0.3
    (0.0, 1.0, 0.3, 5e-324),  # the smallest float
    (-1.7e308, 1.7e308, 1e300, 1e-300),  # a bracket whose width overflows
    (1.0, 1.0 + 2**-52, 1.0, 1e-300),  # two adjacent floats
    (0.0, 5e-324 * 4, 5e-324, 5e-324),  # subnormals
])
def test_bisection_ends_for_any_resolution(lo, hi, t0, resolution):
    """A resolution below the bracket's float spacing ends at two adjacent floats (the
    midpoint is an end) instead of halving forever; the count stays within the bound."""
    b = bisect(lambda x: x > t0, lo, hi, resolution)
    assert b.lo <= t0 <= b.hi
    assert math.nextafter(b.lo, math.inf) == b.hi or b.hi - b.lo <= resolution
    assert b.evaluations <= 2 + MAX_HALVINGS


@settings(max_examples=300, deadline=None)
@given(lo=st.floats(-1e3, 1e3), width=st.floats(1e-3, 1e3), halvings=st.integers(1, 30),
       at_t=st.floats(0, 1), at_g=st.floats(0, 1), true_above=st.booleans(),
       guess_above=st.booleans(), known=st.sampled_from(["none", "lo", "hi", "both"]))
def test_a_guess_gives_plain_bisections_interval_bit_for_bit(
        lo, width, halvings, at_t, at_g, true_above, guess_above, known):
    """Searched from a guess (another grid's or cycle's threshold, either side, either
    orientation), the final interval is plain bisection's to the last bit where the event
    changes once; 2 evaluations when the guess falls in it, at most 2 + 2 log2 of the
    leaves (3 if the guess points the wrong way); the same refusal where it does not
    change.  (Near the float spacing, where bisection's depth could depend on its path,
    the guess is not used.)"""
    hi = lo + width
    resolution = width / 2**halvings * 1.01
    t0 = lo + at_t * width
    assume(lo < t0 < hi)

    def event(x: float) -> bool:
        return (x > t0) == true_above

    ends = {"at_lo": event(lo) if known in ("lo", "both") else None,
            "at_hi": event(hi) if known in ("hi", "both") else None}
    plain = bisect(event, lo, hi, resolution)
    guess = Guess(lo + at_g * width, (not true_above) if guess_above else true_above)
    guided = bisect(event, lo, hi, resolution, guess=guess, **ends)
    assert (guided.lo, guided.hi, guided.at_lo, guided.at_hi) == \
        (plain.lo, plain.hi, plain.at_lo, plain.at_hi)
    # outwards and back: one doubling walk (and a second one if it turned the wrong way)
    walks = 2 if guess.at_lo == plain.at_lo else 3
    assert guided.evaluations <= 2 + walks * (halvings + 1)
    if plain.lo <= guess.value < plain.hi and _exact_halvings(lo, hi, resolution):
        assert guided.evaluations <= 2  # a known end is not evaluated again
    with pytest.raises(NoChange, match="at both ends"):
        bisect(lambda x: true_above, lo, hi, resolution, guess=guess)


# ------------------------------------------------------------------ request parsing


def test_grid_factors_brackets_and_keys():
    assert th.parse_grids(None) == th.DEFAULT_GRIDS
    assert th.parse_grids("1, 1/1.5,2") == pytest.approx((1.0, 1 / 1.5, 2.0))
    for bad in ("1,x", "1,-2", "1,1", "1/0"):
        with pytest.raises(UserError, match="--grids"):
            th.parse_grids(bad)
    assert th.bracket("friction.mu", None, None) == (0.0, 1.0, 0.01)
    assert th.bracket("friction.beta", None, None) == (0.0, 90.0, 1.0)
    assert th.bracket("load.P", (5.0, 20.0), 0.5) == (5.0, 20.0, 0.5)
    with pytest.raises(UserError, match="--param load.P: no default bracket"):
        th.bracket("load.P", None, None)
    with pytest.raises(UserError, match="--resolution"):
        th.bracket("friction.mu", None, 2.0)
    th.check_param("friction.beta")
    with pytest.raises(UserError, match="'friction.muu': not a case key"):
        th.check_param("friction.muu")
    with pytest.raises(UserError, match="'grid.nx': not a real-valued case key"):
        th.check_param("grid.nx")


# ------------------------------------------------------------------ events


def _step(vm: np.ndarray, z: np.ndarray, *, state=None, scalars=None) -> StepResult:
    s = np.linspace(-1.0, 1.0, vm.shape[0])
    surface = {} if state is None else {"state": state}
    return StepResult(scalars=dict(scalars or {}), x=s, y=s, surface=surface,
                      planes={"xz": Plane(s=s, z=z, fields={"vm": vm})})


def test_vm_max_on_surface_reads_the_depth_of_the_maximum():
    z = np.array([0.0, 0.01, 0.02])
    vm = np.ones((5, 3))
    vm[2, 0] = 2.0
    assert vm_max_on_surface(_step(vm, z), EventOptions())
    vm[2, 1] = 3.0  # now one layer down
    assert not vm_max_on_surface(_step(vm, z), EventOptions())
    assert vm_max_on_surface(_step(vm, z), EventOptions(surface_depth=0.01))
    with pytest.raises(EventUndefined, match="no σ_VM plane"):
        vm_max_on_surface(StepResult({}, z, z, {}), EventOptions())


def test_stick_cells_mean_partial_slip():
    state = np.full((4, 4), SLIP)
    z = np.array([0.0, 1.0])
    assert not has_stick(_step(np.ones((4, 2)), z, state=state), EventOptions())
    state[1, 2] = STICK
    assert has_stick(_step(np.ones((4, 2)), z, state=state), EventOptions())
    assert has_stick(_step(np.ones((4, 2)), z, scalars={"stick_area": 0.1}), EventOptions())
    with pytest.raises(EventUndefined):
        has_stick(_step(np.ones((4, 2)), z), EventOptions())


def test_output_step_by_distance_cycle_or_number(bundled_case):
    case = bundled_case("pin_on_disk", quick=True)
    z = np.array([0.0, 1.0])
    steps = [_step(np.ones((3, 2)), z, scalars={"s": s, "step": n})
             for s, n in ((0.0, 0), (80.0, 10), (320.0, 40))]
    result = RunResult(case.name, "ic", "", steps)
    assert select_step(result, case, "")[1] == "s=320"
    assert select_step(result, case, "80")[0] is steps[1]
    assert select_step(result, case, "step=0")[1] == "s=0"
    with pytest.raises(UserError, match="no output step at s = 100 .*outputs: 0, 80, 320"):
        select_step(result, case, "100")
    with pytest.raises(UserError, match="--at 'x=1'"):
        select_step(result, case, "x=1")


# ------------------------------------------------------------------ the sliding sphere


class Hamilton:
    """σ_VM/p0 of Hamilton's field on y = 0, by the point-force quadrature of
    analytic/sliding.py, linear in μ (fields at μ = 0 and 1 combined): the surface line
    x/a ∈ [-1, 1] (h = 0.005 a, x = -a exactly: the cusp) plus ``extra`` surface points,
    and a fine box (h = 0.005 a) around the subsurface maximum."""

    def __init__(self, extra: tuple[float, ...] = (), nu: float = 0.3):
        x = np.linspace(0.25, 0.45, 41)
        z = np.linspace(0.36, 0.47, 23)
        X, Z = np.meshgrid(x, z, indexing="ij")
        xs = np.concatenate([np.linspace(-1.0, 1.0, 401), extra])
        pts = (np.concatenate([X.ravel(), xs]), np.concatenate([Z.ravel(), 0 * xs]))
        self.n_sub, self.n_extra = X.size, len(extra)
        s0, s1 = (sliding_sphere_stresses(pts[0], 0 * pts[0], pts[1], 1.0, 1.0, mu, nu)
                  for mu in (0.0, 1.0))
        self.base = {c: s0[c] for c in COMPONENTS}
        self.slope = {c: s1[c] - s0[c] for c in COMPONENTS}
        self.box_shape = X.shape

    def vm(self, mu: float) -> np.ndarray:
        return von_mises(*(self.base[c] + mu * self.slope[c] for c in COMPONENTS))

    def maxima(self, mu: float) -> tuple[float, float, np.ndarray]:
        """(surface max, subsurface max, σ_VM at the extra surface points)."""
        vm = self.vm(mu)
        sub = vm[: self.n_sub].reshape(self.box_shape)
        i, k = np.unravel_index(int(np.argmax(sub)), sub.shape)
        assert 0 < i < sub.shape[0] - 1 and 0 < k < sub.shape[1] - 1  # inside the box
        surface = vm[self.n_sub:]
        return float(surface.max()), float(sub.max()), surface[len(surface) - self.n_extra:]


@pytest.fixture(scope="module")
def sliding_thresholds():
    """Thresholds of the quick sliding_friction case, ic and analytic, on its grid."""
    request = th.Request(case="sliding_friction", param="friction.mu",
                         event="vm_max_on_surface", lo=0.2, hi=0.5, resolution=0.01,
                         grids=(1.0,), solvers=("ic", "analytic"), quick=True)
    rows = th.run(request)
    return {(r["solver"], r["grid"]): r for r in rows}


@pytest.fixture(scope="module")
def hamilton(bundled_case):
    """Hamilton's field, with the quick grid's surface sample nearest the trailing edge
    inside the contact (x = -0.785 a) as an extra point."""
    case = bundled_case("sliding_friction", quick=True)
    x = case.grid.x / case.hertz_scales[0]
    return Hamilton(extra=(float(x[x > -1.0].min()),))


def test_exact_sliding_threshold_against_the_field(sliding_thresholds, hamilton):
    exact = sliding_thresholds[("analytic", "exact")]
    mu = exact["threshold"]
    assert mu == pytest.approx(0.3047, abs=1e-4)  # analytic/sliding.py, Johnson "about 0.3"
    # independently: below the threshold the subsurface maximum wins, above it the surface
    # (σ_VM at μ ± 0.002 differs by ± 0.0024 p0 between the two maxima)
    below, above = hamilton.maxima(mu - 0.002), hamilton.maxima(mu + 0.002)
    assert below[0] < below[1] and above[0] > above[1]
    # the surface maximum is the trailing-edge cusp, Hamilton's closed form
    assert above[0] == pytest.approx(trailing_edge_von_mises(mu + 0.002, 0.3), rel=1e-8)


def test_sliding_threshold_of_ic_and_analytic_agree(sliding_thresholds, hamilton):
    """Thresholds on the quick 41² grid (cells of 0.26 a).  A lattice does not sample the
    cusp at the trailing edge (analytic/sliding.py): its sampled surface maximum falls
    short, and the threshold moves up to where the surface value at the sample nearest
    the edge (x = -0.785 a), without the cusp, overtakes the subsurface maximum: μ_s, the
    reference of the closed form sampled on the grid (± the lattice's error on the broad
    subsurface maximum, 0.2 % p0 or 0.002 in μ).

    The half-space solver against it: within one resolution plus the solver's error on
    the surface σ_VM near the trailing edge.  Near μ_s that surface value grows by 1.6
    p0 and the subsurface maximum by 0.29 p0 per unit μ (1.3 p0 per unit μ between them),
    and the solver's surface σ_VM two cells inside the trailing edge is up to 2.5 % p0
    below the closed form at the same point (measured on the 81² grid, μ = 0.35):
    0.025 / 1.3 = 0.02 in μ."""
    from scipy.optimize import brentq

    ic = sliding_thresholds[("ic", "41x41")]
    sampled = sliding_thresholds[("analytic", "41x41")]
    exact = sliding_thresholds[("analytic", "exact")]["threshold"]
    for row in (ic, sampled):
        assert row["status"].startswith("bisected") and row["uncertainty"] <= 0.005
        assert exact < row["lo"]  # the lattice misses the cusp: later, never earlier
    mu_s = brentq(lambda mu: hamilton.maxima(mu)[2][0] - hamilton.maxima(mu)[1], 0.33, 0.37,
                  xtol=1e-5)
    assert abs(sampled["threshold"] - mu_s) <= sampled["uncertainty"] + 0.002
    assert abs(ic["threshold"] - sampled["threshold"]) <= 0.01 + 0.02
