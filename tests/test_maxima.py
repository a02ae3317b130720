"""The location of the σ_VM maximum is gated only where the maximum is unique to within
the vm_max tolerance (reports.compare.maxima): two separate maxima of nearly equal value make the
location jump between them, as on the sliding sphere near the friction coefficient at
which the maximum moves to the surface."""

from __future__ import annotations

import numpy as np
import pytest

from cases.result import Plane, StepResult
from reports.compare import maxima

S = np.linspace(-1.0, 1.0, 81)
Z = np.linspace(0.0, 0.6, 31)


def step_with(second: float) -> StepResult:
    """An xz plane with a subsurface bump of 1.0 at (0.2, 0.3) and a surface bump of
    ``second`` at (-0.8, 0)."""
    s, z = np.meshgrid(S, Z, indexing="ij")
    vm = (np.exp(-((s - 0.2) ** 2 + (z - 0.3) ** 2) / 0.02)
          + second * np.exp(-((s + 0.8) ** 2 + z**2) / 0.005))
    return StepResult({}, S, np.array([0.0]), {}, {"xz": Plane(S, Z, {"vm": vm})})


@pytest.mark.parametrize(("second", "rel", "ambiguous"), [
    (0.99, 0.02, True),   # 1 % apart, tolerance 2 %: either could be the maximum
    (0.97, 0.02, False),  # 3 % apart: the subsurface maximum is the maximum
    (1.01, 0.02, True),   # the surface one wins by 1 %: the same ambiguity
])
def test_a_rival_maximum_within_the_tolerance_makes_the_location_undetermined(
        second, rel, ambiguous):
    st = step_with(second)
    top = max(maxima.local_maxima(st, 0.0, 0.0))
    note = maxima.ambiguity({"ic": st}, {"ic": top}, 0.3, rel, 0.0, 0.0)
    assert bool(note) == ambiguous
    if ambiguous:
        assert note.startswith("ic: σ_VM maxima ") and "not determined" in note
        assert "(-0.8, 0, 0)" in note and "(0.2, 0, 0.3)" in note


def test_a_broad_single_maximum_has_no_rival():
    st = step_with(0.0)
    peaks = maxima.local_maxima(st, 0.0, 0.0)
    top = max(peaks)
    assert top[1:] == pytest.approx((0.2, 0.0, 0.3))
    # its own neighbourhood is no rival, however close in value
    assert maxima.rival(st, top, 0.3, 0.0, 0.0) is None or \
        maxima.rival(st, top, 0.3, 0.0, 0.0)[0] < 1e-6
    assert maxima.ambiguity({"ic": st}, {"ic": top}, 0.3, 0.02, 0.0, 0.0) == ""
