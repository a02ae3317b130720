"""The peak pressure's row (:mod:`reports.compare.laws`, ``pressure_peak``): a pressure
sampled from the representations the suite's solvers and results files use — a closed
form at any grid, a nodal field interpolated linearly on any triangulation, cell values —
never exceeds the peak the solver reports (0 to round-off), and the same field scaled by
1 + ε reads ε; without a peak or a pressure there is no row; a pair's row is the worse
of its two solvers' whichever comes first."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.interpolate import LinearNDInterpolator
from scipy.spatial import Delaunay

from cases.result import StepResult
from reports.compare import laws
from reports.registry.tolerances import EXCESS, OWN_ALLOWANCE, PEAK


def _step(p_n: np.ndarray, p_max: float | None) -> StepResult:
    x = np.linspace(-1.0, 1.0, p_n.shape[0])
    y = np.linspace(-1.0, 1.0, p_n.shape[1])
    scalars = {} if p_max is None else {"p_max": p_max}
    return StepResult(scalars=scalars, x=x, y=y, surface={"p_n": p_n})


def _hertz(a: float, p0: float, n: tuple[int, int], shift: tuple[float, float]):
    """Hertz's pressure p0 √(1 − r²/a²) (contact radius a, centre ``shift``) sampled at
    the points of an n[0] × n[1] grid on [−1, 1]²."""
    x = np.linspace(-1.0, 1.0, n[0])[:, None] - shift[0]
    y = np.linspace(-1.0, 1.0, n[1])[None, :] - shift[1]
    return p0 * np.sqrt(np.clip(1.0 - (x * x + y * y) / (a * a), 0.0, None))


@settings(max_examples=60, deadline=None)
@given(a=st.floats(0.05, 0.9), p0=st.floats(1e-3, 1e5), nx=st.integers(5, 90),
       ny=st.integers(5, 90), sx=st.floats(-0.1, 0.1), sy=st.floats(-0.1, 0.1),
       eps=st.floats(2 * OWN_ALLOWANCE, 0.2))
def test_a_closed_form_sampled_on_any_grid_stays_under_its_peak(a, p0, nx, ny, sx, sy, eps):
    p_n = _hertz(a, p0, (nx, ny), (sx, sy))
    if not p_n.max() > 0:
        return  # the contact between the samples: no pressure, no row
    assert laws.peak_excess(_step(p_n, p0)) == 0.0
    # the field scaled by 1 + ε without its scalar: ε times the sampled max over the peak
    value = laws.peak_excess(_step((1 + eps) * p_n, p0))
    assert math.isclose(value, max((1 + eps) * p_n.max() / p0 - 1.0, 0.0), rel_tol=1e-9)
    if p_n.max() == p0:  # a sample at the centre
        assert math.isclose(value, eps, rel_tol=1e-9)


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**31), nodes=st.integers(10, 300), n=st.integers(5, 60))
def test_a_nodal_field_interpolated_linearly_stays_under_its_nodes_max(seed, nodes, n):
    """A results file's or the FEM's grid values: nodal pressures interpolated linearly
    on a triangulation (convex combinations) never exceed the nodal max."""
    rng = np.random.default_rng(seed)
    xy = np.vstack([rng.uniform(-1.0, 1.0, (nodes, 2)),
                    [[-1, -1], [-1, 1], [1, -1], [1, 1]]])  # the grid inside the hull
    p_nodes = np.clip(rng.normal(50.0, 40.0, len(xy)), 0.0, None)
    if not p_nodes.max() > 0:
        return
    g = np.linspace(-1.0, 1.0, n)
    X, Y = np.meshgrid(g, g, indexing="ij")
    p_n = LinearNDInterpolator(Delaunay(xy), p_nodes)(X, Y)
    assert laws.peak_excess(_step(p_n, float(p_nodes.max()))) <= 1e-12


def test_no_row_without_a_peak_or_a_pressure_and_the_worse_of_the_pair():
    p_n = _hertz(0.5, 100.0, (21, 21), (0.0, 0.0))
    good, high = _step(p_n, 100.0), _step(1.02 * p_n, 100.0)
    assert laws.peak_excess(_step(p_n, None)) is None
    assert laws.peak_excess(_step(p_n, math.nan)) is None
    assert laws.peak_excess(_step(np.zeros_like(p_n), 0.0)) is None
    bare = StepResult(scalars={"p_max": 100.0}, x=good.x, y=good.y, surface={})
    assert laws.peak_excess(bare) is None
    assert laws.rows(good, bare, None) == [(PEAK, EXCESS, 0.0)]
    assert laws.rows(good, high, None) == laws.rows(high, good, None)
    assert math.isclose(laws.rows(good, high, None)[0][2], 0.02, rel_tol=1e-9)
