"""The one definition of the semi-widths ``a_x``, ``a_y`` (``cases.result.semi_widths``):
half the contact's extent along x and y, whatever the centre of the contact and of the
stress planes.  Checked against the exact extent of elliptic contacts on rectangular
grids, and through the half-space solver against Hertz's radius with the planes off the
centre (at bf2adeb the half-space solver measured the chords through the planes' centre:
x0 = −0.035 mm and a = 0.072 mm gave 0.062 mm)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cases.result import semi_widths
from reports.cli import main


@settings(max_examples=200, deadline=None, derandomize=True, database=None)
@given(A=st.floats(0.2, 1.0), B=st.floats(0.2, 1.0), cx=st.floats(-0.5, 0.5),
       cy=st.floats(-0.5, 0.5), nx=st.integers(8, 90), ny=st.integers(8, 90))
def test_semi_widths_are_the_semi_axes_to_half_a_cell(A, B, cx, cy, nx, ny):
    """Cells whose centres lie inside an ellipse of semi-axes (A, B) centred at (cx, cy).
    The row of centres nearest y = cy lies within hy/2 of it, where the ellipse's chord
    has the half-length A√(1 − (hy/2B)²), and the outermost centres inside lie within one
    cell of any chord's ends; none lies beyond the ellipse.  So half the extent plus a cell
    lies between that half-chord − hx/2 and A + hx/2 (likewise in y)."""
    Lx, Ly = 3.2, 3.0
    hx, hy = Lx / nx, Ly / ny
    x = (np.arange(nx) + 0.5) * hx - Lx / 2
    y = (np.arange(ny) + 0.5) * hy - Ly / 2
    inside = ((x[:, None] - cx) / A) ** 2 + ((y[None, :] - cy) / B) ** 2 < 1.0
    a_x, a_y = semi_widths(x, y, np.where(inside, 1.0, 0.0))
    if not inside.any():
        assert (a_x, a_y) == (0.0, 0.0)
        return
    eps = 1e-12
    assert a_x <= A + hx / 2 + eps and a_y <= B + hy / 2 + eps
    if hy / 2 < B:
        assert a_x >= A * math.sqrt(1 - (hy / (2 * B)) ** 2) - hx / 2 - eps
    if hx / 2 < A:
        assert a_y >= B * math.sqrt(1 - (hx / (2 * A)) ** 2) - hy / 2 - eps
    # the steps of half a cell
    assert 2 * a_x / hx == pytest.approx(round(2 * a_x / hx), abs=1e-9)


def test_no_contact_has_no_width():
    x = np.linspace(-1, 1, 5)
    assert semi_widths(x, x, np.zeros((5, 5))) == (0.0, 0.0)


def _hertz(x0: float, y0: float) -> str:
    # R = 10 mm, P = 5 N, steel pair: a = 0.0860 mm, 31 x 27 cells on 0.30 x 0.26 mm
    return ('kind = "static"\n[materials.a]\nE = 210000.0\nnu = 0.3\n[materials.b]\n'
            "E = 210000.0\nnu = 0.3\n[geometry]\nR = 10.0\n[grid]\nLx = 0.30\nnx = 31\n"
            "Ly = 0.26\nny = 27\n[load]\nP = 5.0\n"
            f"[stress]\ndepth = 0.13\nnz = 21\nx0 = {x0!r}\ny0 = {y0!r}\n")


def test_off_centre_planes_keep_every_scalar_within_its_budget(tmp_path):
    """Hertz with the stress planes at up to 0.8 a off the centre, run through the
    half-space solver and the closed form: a_x, a_y and every other gated scalar pass
    at the default tolerances, and the semi-widths are Hertz's radius within a cell."""
    a = (3 * 5.0 * 10.0 / (4 * 210000.0 / (2 * (1 - 0.3**2)))) ** (1 / 3)
    for k, (fx, fy) in enumerate(((0.8, 0.0), (-0.8, 0.8), (0.0, -0.8), (0.5, 0.5))):
        path = tmp_path / f"off{k}.toml"
        path.write_text(_hertz(fx * a, fy * a))
        out = tmp_path / f"res{k}"
        assert main(["run", str(path), "--solver", "ic,analytic", "--no-progress",
                     "--out", str(out)]) == 0
        assert main(["gate", "--out", str(out)]) == 0
        summary = pd.read_csv(out / path.stem / "summary.csv")
        ic = summary[summary["solver"] == "ic"].iloc[-1]
        assert abs(ic["a_x"] - a) <= 0.30 / 31 and abs(ic["a_y"] - a) <= 0.26 / 27
        metrics = pd.read_csv(out / path.stem / "metrics.csv")
        rows = metrics[(metrics["pair"] == "ic-analytic") & metrics["quantity"].isin(
            ["a_x", "a_y", "contact_area", "p_max", "P"])]
        assert {"a_x", "a_y", "contact_area", "p_max"} <= set(rows["quantity"])
        assert rows["passed"].astype(bool).all() and math.isfinite(rows["value"].max())
