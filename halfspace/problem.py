"""A case turned into the half-space solver's objects: the separation profile, the
contact solver of its grid, materials and friction, and the stress evaluator of its
output planes.  Shared by the static solve (:mod:`halfspace.solver`) and the wear
evolution (:mod:`halfspace.wear`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from cases.model import Case

from .contact import ContactSolver
from .materials import Materials

if TYPE_CHECKING:
    from .stresses import StressEvaluator


def profile(case: Case) -> np.ndarray:
    """Geometric gap h(x, y) = (x^2 + y^2) / (2R) of the paraboloid on the cell centres
    (the g_g part of g_n,o in Eq. 1)."""
    X, Y = np.meshgrid(case.grid.x, case.grid.y, indexing="ij")
    return (X**2 + Y**2) / (2.0 * case.R)


def slide_direction(angle_deg: float) -> np.ndarray:
    """Unit vector of the sliding direction, ``angle_deg`` from x."""
    t = np.radians(angle_deg)
    return np.array([np.cos(t), np.sin(t)])


def contact_solver(case: Case) -> ContactSolver:
    """The contact solver (section 3.4) of the case's grid, material pair (Eq. 6) and
    friction law (Eq. 9-14)."""
    mat = Materials.from_bodies(case.a, case.b)
    s = case.solver
    return ContactSolver(case.grid, mat, case.friction, method=s.method, tol=s.tol,
                         max_iter=s.max_iter)


def stress_evaluator(case: Case) -> StressEvaluator:
    """The subsurface stress evaluator (Eq. 32-34) of the reported body's depths."""
    from .stresses import StressEvaluator  # scipy.fft: imported where stresses are sampled

    body = case.stress.body
    nu = case.a.nu if body == "a" else case.b.nu
    return StressEvaluator(case.grid, case.stress.z, nu, body)
