"""Analytical references: Hertz, Cattaneo–Mindlin, the sliding sphere, pin wear.

Independent of the ``halfspace`` and ``fem_reference`` packages (they are verified
against it).  Modules:

- :mod:`.pointforce` — Boussinesq and Cerruti point-force stresses (Johnson 1985 §3.2);
- :mod:`.quadrature` — stresses of Hertz-shaped tractions on a circle by quadrature;
- :mod:`.hertz` — Hertz contact, on-axis and surface closed forms, Hamilton–Goodman field;
- :mod:`.mindlin` — Cattaneo–Mindlin partial slip, tangential compliance, fretting regime;
- :mod:`.fretting` — the first fretting cycle: Mindlin–Deresiewicz loop, energy, slip, wear;
- :mod:`.sliding` — the sliding sphere: stresses, σ_VM maximum vs μ, surface jump;
- :mod:`.wear` — Argatov (2011) and Hegadekatte (2008) pin wear, orthotropic i_w(θ);
- :mod:`.solver` — the "analytic" solver: ``solve(case, *, progress, on_output)`` and
  ``supports(case)`` (None, or why the case has no closed form), exported here as the
  solver protocol of :mod:`reports.registry.solvers`.
"""

from __future__ import annotations

from collections.abc import Callable

from cases.model import Case, one_case
from cases.result import RunResult, StepResult


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """The closed forms of ``case`` (:func:`analytic.solver.solve`); imported on first use,
    so that a module of this package loads without the others."""
    from .solver import solve as _solve

    return _solve(one_case(case, "analytic"), progress=progress, on_output=on_output)


def supports(case: Case) -> str | None:
    """None, or why the case has no closed form (:func:`analytic.solver.supports`)."""
    from .solver import supports as _supports

    return _supports(case)


def surface_jump(nu: float):
    """The μ at which the sliding sphere's σ_VM maximum jumps to the surface
    (:func:`analytic.sliding.surface_jump`)."""
    from .sliding import surface_jump as _surface_jump

    return _surface_jump(nu)


def axis_vm_max(nu: float) -> tuple[float, float]:
    """(σ_VM,max / p0, z / a) of the Hertz contact on its axis
    (:func:`analytic.hertz.axis_vm_max`)."""
    from .hertz import axis_vm_max as _axis_vm_max

    return _axis_vm_max(nu)


def axis_von_mises(z, a: float, p0: float, nu: float):
    """σ_VM on the Hertz contact's axis at depths z (:func:`analytic.hertz.axis_von_mises`)."""
    from .hertz import axis_von_mises as _axis_von_mises

    return _axis_von_mises(z, a, p0, nu)


def sliding_vm_max(mu: float, nu: float) -> tuple[float, float, float]:
    """(σ_VM,max / p0, x / a, z / a) of the sliding sphere over its xz plane, exact
    (:func:`analytic.sliding.vm_max_xz`; the surface maximum at the trailing edge's cusp)."""
    from .sliding import vm_max_xz

    found = vm_max_xz(mu, nu)
    return float(found.value), float(found.x), float(found.z)


def worn_pin(s, a0: float, i1: float, i2: float, theta_deg: float, P: float, R: float
             ) -> dict[str, object]:
    """The worn pin's closed forms at sliding distances s (:mod:`analytic.wear`): Archard's
    volume, Argatov's radius, wear depth and uniform pressure, Hegadekatte's wear depth,
    with the orthotropic i_w(θ) of formulation Eq. 19."""
    from . import wear

    i_w = wear.wear_coefficient(i1, i2, theta_deg)
    return {"i_w": i_w, "volume": wear.archard_volume(s, i_w, P),
            "a": wear.argatov_radius(s, a0, i_w, P, R),
            "w": wear.argatov_wear_depth(s, a0, i_w, P, R),
            "p_max": wear.argatov_p_max(s, a0, i_w, P, R),
            "w_cap": wear.hegadekatte_wear_depth(s, i_w, P, R)}


__all__ = ["axis_vm_max", "axis_von_mises", "sliding_vm_max", "solve", "supports",
           "surface_jump", "worn_pin"]
