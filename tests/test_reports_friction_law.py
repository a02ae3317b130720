"""The friction law's row (:mod:`reports.compare.laws`) against the ellipse of Eq. 9
written here in the friction axes: tractions on the ellipse read zero at any μ₁, μ₂, β;
scaled by 1 + ε they read ε times the pressure where they are largest, over the peak;
turned the wrong way (β → −β) an orthotropic ellipse is left; no friction, no row."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from cases.model import Friction
from cases.result import StepResult
from reports.compare import laws


def _step(p_n: np.ndarray, p_x: np.ndarray, p_y: np.ndarray) -> StepResult:
    n = p_n.shape[0]
    x = np.linspace(-1.0, 1.0, n)
    return StepResult(scalars={}, x=x, y=x, surface={"p_n": p_n, "p_x": p_x, "p_y": p_y})


def _on_ellipse(f: Friction, seed: int, n: int = 9):
    """Pressures and tractions on the ellipse ‖p_t‖_μ = p_n, directions at random."""
    rng = np.random.default_rng(seed)
    p_n = rng.uniform(0.0, 100.0, (n, n))
    theta = rng.uniform(0.0, 2 * math.pi, (n, n))
    p_1, p_2 = f.mu1 * p_n * np.cos(theta), f.mu2 * p_n * np.sin(theta)
    b = math.radians(f.beta)
    return p_n, math.cos(b) * p_1 - math.sin(b) * p_2, math.sin(b) * p_1 + math.cos(b) * p_2


frictions = st.builds(Friction, mu1=st.floats(0.05, 1.0), mu2=st.floats(0.05, 1.0),
                      beta=st.floats(-180.0, 180.0))


@settings(max_examples=50, deadline=None)
@given(f=frictions, seed=st.integers(0, 2**31), eps=st.floats(1e-3, 0.1))
def test_the_excess_is_zero_on_the_ellipse_and_eps_beyond_it(f, seed, eps):
    p_n, p_x, p_y = _on_ellipse(f, seed)
    assert laws.excess(_step(p_n, p_x, p_y), f) <= 1e-12
    # inside the ellipse (stick) reads zero too
    assert laws.excess(_step(p_n, 0.5 * p_x, 0.5 * p_y), f) == 0.0
    value = laws.excess(_step(p_n, (1 + eps) * p_x, (1 + eps) * p_y), f)
    assert math.isclose(value, eps, rel_tol=1e-9)  # at the peak pressure: ε p_max / p_max


@settings(max_examples=50, deadline=None)
@given(f=frictions, seed=st.integers(0, 2**31))
@example(f=Friction(mu1=0.2, mu2=0.6, beta=45.0), seed=0)
def test_axes_turned_the_wrong_way_leave_an_orthotropic_ellipse(f, seed):
    p_n, p_x, p_y = _on_ellipse(f, seed)
    wrong = Friction(mu1=f.mu1, mu2=f.mu2, beta=-f.beta)
    turned = math.sin(2 * math.radians(f.beta))  # β ≡ −β (mod 180) leaves nothing to see
    ratio = max(f.mu1, f.mu2) / min(f.mu1, f.mu2)
    value = laws.excess(_step(p_n, p_x, p_y), wrong)
    if abs(turned) > 0.5 and ratio > 1.5:
        assert value > 0.01
    assert value >= 0.0


def test_no_row_without_friction_or_tractions():
    p_n, p_x, p_y = _on_ellipse(Friction(mu1=0.3, mu2=0.3), 1)
    step = _step(p_n, p_x, p_y)
    assert laws.excess(step, Friction()) is None
    assert laws.excess(_step(p_n, p_x, p_y), Friction(mu1=0.3, mu2=0.0)) is None
    bare = StepResult(scalars={}, x=step.x, y=step.y, surface={"p_n": p_n})
    assert laws.excess(bare, Friction(mu1=0.3, mu2=0.3)) is None
    assert laws.rows(bare, bare, Friction(mu1=0.3, mu2=0.3)) == []
    # the pair's row is the worse of its two solvers', whichever comes first
    bad = _step(p_n, 1.02 * p_x, 1.02 * p_y)
    f = Friction(mu1=0.3, mu2=0.3)
    assert laws.rows(step, bad, f) == laws.rows(bad, step, f)
    assert math.isclose(laws.rows(step, bad, f)[0][2], 0.02, rel_tol=1e-9)
