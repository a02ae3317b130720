"""Hertz scales of a case: the contact radius a0 and peak pressure p0 used to make
lengths (x/a0, z/a0) and stresses (σ/p0) dimensionless in tables and plots."""

from __future__ import annotations

import math

from cases.model import Case


def hertz_scales(case: Case) -> tuple[float, float]:
    """(a0 [mm], p0 [MPa]) of the Hertz contact of the case's sphere at its normal load.

    Load control: a0 = (3PR / 4E*)^(1/3), p0 = 3P / (2π a0²).  Displacement control
    (approach δ): a0 = √(Rδ), p0 = 2 E* a0 / (π R) — the same Hertz contact.
    """
    if case.load.P is not None:
        a0 = case.hertz_a0
        return a0, 3.0 * case.load.P / (2.0 * math.pi * a0**2)
    a0 = math.sqrt(case.R * float(case.load.approach))
    return a0, 2.0 * case.E_star * a0 / (math.pi * case.R)
