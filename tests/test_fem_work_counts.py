"""Work counts of a fixed FEM point, asserted within stated bounds (the FEM's side of
``tests/test_halfspace_work_counts.py``): the quick Hertz point factorises its block once
(the condensation and every contact iteration reuse the factors) and its semi-smooth
Newton solve takes the measured count plus a margin of two iterations.  The counts and
their history: ``benchmarks/README.md``, "Partial-slip load control and work counts"."""

from __future__ import annotations

import pytest

import fem_reference
from cases import load_case
from fem_reference.model import elasticity

pytestmark = pytest.mark.fem


def test_quick_hertz_point_work(monkeypatch):
    """Measured: 1 factorisation of 37710 free DOFs condensed onto 597 surface DOFs, 12
    Newton iterations, 3 right-hand sides solved with the factors (the far-field
    compliance, the two bodies' displacements of the output step; before the Schur
    complement, issue 58, the condensation solved one per condensed DOF: 600); the
    block cache off, so that the counts do not depend on which test ran first in the
    process."""
    monkeypatch.setenv("CONTACT_VV_FEM_CACHE", "0")
    built = []
    factorise = elasticity.Factorization.__init__

    def counted(self, *args, **kwargs):
        built.append(self)
        factorise(self, *args, **kwargs)

    monkeypatch.setattr(elasticity.Factorization, "__init__", counted)
    case = load_case("hertz", quick=True)[0]
    result = fem_reference.solve(case, vtu=False)
    assert len(built) == 1
    assert result.meta["dofs"] == 37710 and result.meta["surface_dofs"] == 597
    assert sum(f.columns for f in built) <= 3 + 2
    assert result.steps[-1].scalars["iterations"] <= 12 + 2
    assert result.steps[-1].scalars["P"] == pytest.approx(case.load.P, rel=1e-9)
