"""The σ_VM maximum compared where it is a number (reports.compare.maxima): the value off
the edge band, a near-surface maximum shown and its companion gated, and the location
judged by the near-maximum sets — two maxima of nearly equal value, or a ridge, leave it
as undetermined as it is; a maximum moved out of the other's set is caught."""

from __future__ import annotations

import numpy as np
import pytest

from reports.compare import maxima

S = np.linspace(-1.0, 1.0, 81)
Z = np.linspace(0.0, 0.6, 31)
CELL = (S[1] - S[0], S[1] - S[0], Z[1] - Z[0])


def field(peaks: list[tuple[float, float, float, float]]) -> np.ndarray:
    """σ_VM on the xz plane: Gaussian peaks (height, s, z, width²)."""
    s, z = np.meshgrid(S, Z, indexing="ij")
    return sum(h * np.exp(-((s - s0) ** 2 + (z - z0) ** 2) / w) for h, s0, z0, w in peaks)


def rows(a: np.ndarray, b: np.ndarray, off: np.ndarray | None = None, rel: float = 0.02,
         a_contact: float = 0.4) -> dict[tuple[str, str], float]:
    xyz = maxima.plane_points("xz", S, Z, 0.0, 0.0)
    off = np.ones(a.size, dtype=bool) if off is None else off.ravel()
    samples = [maxima.PlaneSamples(xyz, a.ravel(), b.ravel(), off)]
    return {(q, m): v for q, m, v in maxima.rows(samples, rel=rel, cell=CELL, a0=0.4,
                                                  a=a_contact)}


SUB = (1.0, 0.2, 0.3, 0.02)  # a subsurface maximum at z = 0.3 (0.75 a)


@pytest.mark.parametrize(("second", "undetermined"), [
    (0.99, True),   # 1 % apart, tolerance 2 %: either could be the maximum
    (1.01, True),   # the other one wins by 1 %: the same
    (0.97, False),  # 3 % apart: the subsurface one is the maximum
])
def test_two_rival_maxima_within_the_tolerance_leave_the_location_undetermined(
        second, undetermined):
    """Both solvers have a second peak at (-0.5, 0.35): A of height ``second``, B of
    height 0.99.  Within the tolerance each maximum lies in the other's near-maximum set
    and the location metric is 0 (no false alarm); beyond it, a maximum moved to where
    the other solver has none is seen at its distance."""
    rival = (second, -0.5, 0.35, 0.02)
    got = rows(field([SUB, rival]), field([SUB, (0.99, -0.5, 0.35, 0.02)]))
    assert got[("vm_max", "rel")] < 0.02  # the values agree to the tolerance
    if undetermined:
        assert got[("vm_max_loc", "cells")] == pytest.approx(0.0, abs=1e-9)
    else:
        assert got[("vm_max_loc", "cells")] == pytest.approx(0.0, abs=1e-9)  # same peak
        moved = rows(field([(1.0, -0.5, 0.35, 0.02), (0.9, 0.2, 0.3, 0.02)]),
                     field([SUB, (0.9, -0.5, 0.35, 0.02)]))
        assert moved[("vm_max_loc", "cells")] > 20.0  # 0.7 apart, 0.025 a cell


def test_a_ridge_leaves_the_location_undetermined_without_a_false_alarm():
    """A flat ridge along s (0.3 % variation over its length): the two solvers' maxima at
    opposite ends lie in each other's near-maximum sets."""
    s, z = np.meshgrid(S, Z, indexing="ij")
    ridge = np.exp(-((z - 0.3) ** 2) / 0.02) * (1.0 - 0.003 * np.clip(np.abs(s), 0, 0.6))
    a = ridge * (1.0 + 0.001 * s)  # its maximum at the +s end of the plateau
    b = ridge * (1.0 - 0.001 * s)  # at the -s end
    got = rows(a, b)
    assert got[("vm_max_loc", "cells")] == pytest.approx(0.0, abs=1e-9)


def test_the_maximum_is_compared_off_the_edge_band_and_written_over_it():
    """A cusp in A at a point of the edge band: ``edge`` sees it, ``rel`` does not."""
    b = field([SUB])
    a = b.copy()
    i, k = int(np.argmin(np.abs(S - 0.4))), 0
    a[i, k] = 1.5
    off = np.ones_like(a, dtype=bool)
    off[i - 1:i + 2, :2] = False
    got = rows(a, b, off)
    assert got[("vm_max", "rel")] == pytest.approx(0.0, abs=1e-12)
    assert got[("vm_max", maxima.EDGE)] == pytest.approx(0.5, rel=1e-9)


def test_a_near_surface_maximum_is_shown_and_its_companion_gated():
    """Maxima on the surface: ``vm_max`` becomes ``surface``; the companion is the maximum
    from a quarter of the contact radius down, which sees a 5 % error there."""
    surface = (1.2, 0.3, 0.0, 0.01)
    b = field([SUB, surface])
    a = b * np.where(Z[None, :] >= 0.1, 1.05, 1.0)
    got = rows(a, b, a_contact=0.4)
    assert ("vm_max", "rel") not in got
    assert got[("vm_max", maxima.SURFACE)] == pytest.approx(0.0, abs=1e-12)
    assert got[("vm_max_below", "rel")] == pytest.approx(0.05, rel=1e-9)
    assert maxima.below_depth(CELL, 0.4) == pytest.approx(0.1)
    assert maxima.below_depth(CELL, 0.04) == pytest.approx(2 * max(CELL))  # two cells
    assert maxima.below_depth(CELL, 0.4, z_below=0.2) == 0.2
