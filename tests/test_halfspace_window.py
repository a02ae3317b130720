"""The normal problem on its potential-contact window (halfspace/window.py) against the
same problem on the whole grid (halfspace/normal.py, every cell free): the window is an
exact restriction, so the two agree to the solver's tolerance, whatever the estimate
of the approach that cut the window."""

from __future__ import annotations

import numpy as np
import pytest

import halfspace.window as window
from cases.model import Body
from halfspace.materials import Materials
from halfspace.normal import polonsky_keer, uzawa_normal
from halfspace.operator import normal_operator
from halfspace.window import WindowedNormal, overlap_box, rounded

MAT = Materials.from_bodies(Body(E=210000.0, nu=0.3), Body(E=70000.0, nu=0.33))
N, L, R, P = 128, 1.6, 50.0, 10.2  # >= COARSEST: the coarse estimate is used
DX = L / N
TOL = 1e-11


def grid_h(two_spots: bool = False, n: int = N) -> np.ndarray:
    x = (np.arange(n) + 0.5) * (L / n) - L / 2
    X, Y = np.meshgrid(x, x, indexing="ij")
    h = (X**2 + Y**2) / (2 * R)
    if two_spots:  # a second, slightly lower-lying asperity away from the first
        h = np.minimum(h, ((X - 0.45) ** 2 + (Y + 0.3) ** 2) / (2 * R) + 2e-5)
    return h


def full_grid(h, method="cg", wear_rate=None, **control):
    """Reference: the same solver on the whole grid, no window."""
    n, dx = h.shape[0], L / h.shape[0]
    op = normal_operator(n, n, dx, dx, MAT)
    k = np.zeros_like(h) if wear_rate is None else wear_rate

    def apply(p):
        return op.apply("zz", p) + k * p

    solver = WindowedNormal((n, n), dx, dx, MAT, method, TOL, 100000)
    if method == "cg":
        return polonsky_keer(apply, h, dx * dx, solver.c, tol=TOL, **control)
    L_op = solver.L + float(k.max())
    return uzawa_normal(apply, h, dx * dx, solver.c, 1.0 / L_op, tol=TOL, max_iter=100000,
                        **control)


def windowed(h, method="cg", wear_rate=None, **control):
    n = h.shape[0]
    return WindowedNormal((n, n), L / n, L / n, MAT, method, TOL, 100000).solve(
        h, wear_rate=wear_rate, **control)


def assert_same(a, b, rtol=1e-8):
    scale = np.abs(b.p_n).max()
    assert np.abs(a.p_n - b.p_n).max() < rtol * scale
    assert a.approach == pytest.approx(b.approach, rel=1e-8)
    assert np.abs(a.gap - b.gap).max() < 1e-6 * np.ptp(b.gap)


@pytest.mark.parametrize("two_spots", [False, True])
def test_load_control_matches_the_whole_grid(two_spots):
    h = grid_h(two_spots)
    ref = full_grid(h, P=P)
    sol = windowed(h, P=P)
    assert_same(sol, ref)
    assert sol.p_n.sum() * DX * DX == pytest.approx(P, rel=1e-12)
    if two_spots:  # the reference really has two contact spots, both kept
        assert ref.p_n[np.ix_(np.arange(N) > 3 * N // 4, np.arange(N) < N // 2)].max() > 0


def test_displacement_control_matches_the_whole_grid():
    h = grid_h(True)
    ref = full_grid(h, approach=4e-4)
    assert_same(windowed(h, approach=4e-4), ref)


def test_implicit_wear_term_matches_the_whole_grid():
    h = grid_h()
    k_w = np.full_like(h, 2e-7)
    assert_same(windowed(h, wear_rate=k_w, P=P), full_grid(h, wear_rate=k_w, P=P))


def test_uzawa_on_the_window_matches_the_whole_grid(monkeypatch):
    """(Uzawa converges linearly: a 48² grid, the coarse level forced on.)"""
    monkeypatch.setattr(window, "COARSEST", 16)
    h = grid_h(n=48)
    assert_same(windowed(h, method="uzawa", P=P), full_grid(h, method="uzawa", P=P),
                rtol=1e-7)


def test_a_window_cut_too_small_grows_to_the_answer(monkeypatch):
    """A negative slack cuts the first window inside the contact; the check on the found
    approach must grow it until the answer is the whole grid's."""
    h = grid_h()
    cuts = []
    original = window.WindowedNormal._on

    def spy(self, h_, box, *args):
        cuts.append((box[0].stop - box[0].start) * (box[1].stop - box[1].start))
        return original(self, h_, box, *args)

    monkeypatch.setattr(window, "SLACK", -0.6)
    monkeypatch.setattr(window.WindowedNormal, "_on", spy)
    sol = windowed(h, P=P)
    assert len(cuts) >= 3 and cuts[-1] > cuts[-2]  # coarse level(s), then growth
    assert_same(sol, full_grid(h, P=P))


def test_warm_start_from_a_previous_pressure():
    h = grid_h()
    ref = full_grid(h, P=P)
    assert_same(windowed(h, P=P, p0=np.roll(ref.p_n, 3, axis=0)), ref)


def test_boxes():
    h = grid_h()
    box = overlap_box(h, 1e-4)
    r = np.sqrt(2 * R * 1e-4) / DX  # overlap radius in cells
    assert box[0].stop - box[0].start == pytest.approx(2 * r + 2, abs=2)
    wide = rounded(box, (N, N))
    assert all((s.stop - s.start) % window.ROUND == 0 for s in wide)
    assert all(w.start <= b.start and b.stop <= w.stop for w, b in zip(wide, box, strict=True))
    assert overlap_box(h, -1.0) is None
