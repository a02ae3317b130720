"""The fixed problems the benchmarks time (each also a work-count test of the fast tier,
``tests/test_halfspace_work_counts.py`` and ``tests/test_fem_work_counts.py``)."""

from __future__ import annotations

import os

# one thread everywhere: timings comparable between machines and commits
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from cases import load_case  # noqa: E402
from cases.model import Case, Friction  # noqa: E402

#: the peers' Cattaneo–Mindlin problem: 1.6 mm square, Q = 0.5 μP, μ = 0.3
MINDLIN_L, MINDLIN_Q = 1.6, 0.5 * 0.3 * 10.2


def hertz(n: int) -> Case:
    return load_case("hertz", overrides={"grid.nx": n, "grid.ny": n})[0]


def mindlin(n: int) -> Case:
    return load_case("cattaneo_mindlin", overrides={
        "grid.nx": n, "grid.ny": n, "grid.Lx": MINDLIN_L, "grid.Ly": MINDLIN_L,
        "load.Qx": MINDLIN_Q})[0]


def sliding(n: int) -> Case:
    """Full sliding with orthotropic friction (μ1 = 0.25, μ2 = 0.5, β = 45°)."""
    return hertz(n).with_changes(friction=Friction(0.25, 0.5, 45.0))


#: quick fretting points: (case, sweep point) — partial slip in the first cycles, and the
#: worn partial slip at β = 90°
FRETTING = {"isotropic": ("fretting_isotropic", 0), "orthotropic_beta90": (
    "fretting_orthotropic", 1)}


def fretting(name: str) -> Case:
    case, index = FRETTING[name]
    return load_case(case, quick=True)[index]
