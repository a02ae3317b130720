"""ContactMechanics (Pastewka's group, the ``[peers]`` extra) as a contact-vv solver
plugin, a second peer of another kind than Tamaas, verified through the suite's own
comparisons and gates (its verdict: benchmarks/README.md, "ContactMechanics through
the gates").

``contactmechanics``: non-periodic frictionless normal contact of the case's sphere on
the case grid: ``FreeFFTElasticHalfSpace`` (the contact modulus E*, zero-padded FFT)
against the rigid profile r²/2R at the cell centres, solved by
``NonSmoothContactSystem.minimize_proxy`` (Polonsky–Keer) under the load ``load.P`` or
the approach ``load.approach``, to a penetration of ``solver.tol`` times the profile's
range over the grid (its tolerance is a length).  ContactMechanics has no friction,
wear or subsurface stresses; the cases that need them are declined with the reason
(:func:`supports`).  It runs only when named (``--solver contactmechanics,ic,analytic``);
without ContactMechanics installed the record is not offered (nothing changes).
"""

from __future__ import annotations

import importlib.util
import math
import time
from collections.abc import Callable

import numpy as np

from cases.model import Case
from cases.result import Cost, RunResult, StepResult, semi_widths
from reports.plugin import SolverRecord

__all__ = ["record", "solve", "supports", "by_default", "estimate"]


def grid_budget(quantity: str, metric: str) -> float:
    """ContactMechanics holds the pressure on the case's cells as the half-space solver
    does: the grid solvers' budget (:func:`reports.registry.solvers.grid_budget`)."""
    from reports.plugin import grid_budget as budget  # not at plugin load

    return budget(quantity, metric)


def refine_grid(case: Case, factor: float) -> Case:
    """The case grid refined by ``factor`` (:func:`reports.registry.discretisation.refine_grid`)."""
    from reports.plugin import refine_grid as refine  # not at plugin load

    return refine(case, factor)


def missing() -> str | None:
    """Why the plugin cannot run here (ContactMechanics not installed), None if it can."""
    if importlib.util.find_spec("ContactMechanics") is None:
        return "ContactMechanics is not installed: pip install 'contact-vv[peers]'"
    return None


def record() -> SolverRecord:
    """The ``contactmechanics`` solver, offered always and available where
    ContactMechanics is installed (:func:`missing`)."""
    return SolverRecord("contactmechanics", __name__, budget=grid_budget, refine=refine_grid,
                        requires=missing, scope="static frictionless normal contact; "
                        "declines friction, tangential loads and wear",
                        style={"color": "C8", "ls": "-", "marker": "^", "ms": 3})


def supports(case: Case) -> str | None:
    """None when ContactMechanics models the case, else why not: it solves frictionless
    normal contact only."""
    ld, f = case.load, case.friction
    if case.kind != "static":
        return f"{case.kind.replace('_', ' ')}: ContactMechanics has no wear law"
    if ld.tangential_mode != "none":
        return (f"a tangential load ({ld.tangential_mode}): ContactMechanics solves "
                "frictionless normal contact only")
    if not case.identical_materials and f.mu1 > 0:
        return ("dissimilar materials with friction: the normal problem couples with the "
                "tangential one (K != 0), which ContactMechanics does not model")
    return None


def by_default(case: Case) -> str:
    """A peer under verification runs only when named."""
    return "a peer code under verification: name it with --solver"


def estimate(case: Case) -> Cost:
    """Peak memory and wall time: a few padded (2n)² FFT arrays, some hundred FFT pairs."""
    n = 4 * case.grid.nx * case.grid.ny
    return Cost(memory=4e8 + 400.0 * n, seconds=0.5 + 2e-5 * n * math.log2(n),
                memory_keys=("grid.nx", "grid.ny"), time_keys=("grid.nx", "grid.ny"))


def contact_modulus(case: Case) -> float:
    """The modulus of ContactMechanics's one half-space: the pair's E*
    (``Case.E_star``), which makes its rigid-indenter problem the two bodies'
    frictionless one."""
    return case.E_star


def solve(case: Case, *, progress: bool = False,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """One output step of ``case`` by ContactMechanics (module doc)."""
    from ContactMechanics import FreeFFTElasticHalfSpace
    from ContactMechanics.Systems import NonSmoothContactSystem
    from SurfaceTopography import Topography

    t0 = time.perf_counter()
    g = case.grid
    X, Y = np.meshgrid(g.x, g.y, indexing="ij")
    heights = -(X**2 + Y**2) / (2.0 * case.R)
    surface = Topography(heights, (g.Lx, g.Ly), periodic=False)
    substrate = FreeFFTElasticHalfSpace((g.nx, g.ny), contact_modulus(case), (g.Lx, g.Ly))
    system = NonSmoothContactSystem(substrate=substrate, surface=surface)
    load = ({"external_force": case.load.P} if case.load.P is not None
            else {"offset": case.load.approach})
    res = system.minimize_proxy(pentol=case.solver.tol * float(np.ptp(heights)),
                                maxiter=case.solver.max_iter, **load)
    if not res.success:
        raise RuntimeError(f"ContactMechanics did not converge: {res.message}")
    p_n = np.asarray(system.force, dtype=float)[:g.nx, :g.ny] / system.area_per_pt
    dA = g.dx * g.dy
    a_x, a_y = semi_widths(g.x, g.y, p_n)
    scalars = {
        "step": 0, "P": float(p_n.sum() * dA), "Qx": 0.0, "Qy": 0.0,
        "contact_area": float(np.count_nonzero(p_n > 0) * dA), "a_x": a_x, "a_y": a_y,
        "p_max": float(p_n.max()), "approach": float(res.offset),
        "iterations": int(res.nit), "converged": True, "wall_s": time.perf_counter() - t0,
    }
    zero = np.zeros_like(p_n)
    step = StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(),
                      surface={"p_n": p_n, "p_x": zero, "p_y": zero.copy()})
    if on_output is not None:
        on_output(step)
    return RunResult(case=case.name, solver="contactmechanics", param=case.param,
                     steps=[step], meta={"ContactMechanics": _version()})


def _version() -> str:
    from importlib.metadata import version

    return version("ContactMechanics")
