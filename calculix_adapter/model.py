"""The model of one case: the element size, the two bodies, and the parameters of the
deck (:class:`calculix_adapter.deck.Model`).

Model parameters (chosen, and their effect measured: benchmarks/README.md, "CalculiX
through the gates"):

- the element size at the contact :data:`H_FACTOR` times the FEM's ``fem.h`` (so that
  a grid study refines both FEMs alike);
- the bodies' half-side and height :data:`SIDE` a0 (the FEM reference's block too,
  the same choice of domain, measured separately);
- the penalty's normal stiffness :data:`K_N` E*/h and stick slope :data:`K_T` E*/h
  (E* the pair's contact modulus): both grow as the mesh is refined, so the penalty's
  error vanishes with h;
- the normal load path: contact radii from two elements growing by
  1 + 0.01/(|β| μ), between 1.1 and 1.4, per increment (the stick traction of a
  frictional contact of dissimilar materials follows its load path: docs/formulation.md
  §2.9).
"""

from __future__ import annotations

from cases.model import Case

from .deck import Model
from .mesh import SHARE, Body, bodies, profile_share
from .support import symmetry

#: the element size at the contact over the FEM's ``fem.h`` (times a0)
H_FACTOR = 2.0
#: the bodies' half-side and height, in a0
SIDE = 20.0
#: the penalty's normal stiffness and stick slope, in E*/h
K_N = 40.0
K_T = 10.0
#: the approach of the first step over Hertz's a0²/R (the finite bodies are stiffer
#: than half-spaces; force control then takes the load to P)
APPROACH = 0.98


def element_size(case: Case) -> float:
    """The element size [mm] at the contact: :data:`H_FACTOR` times the FEM's."""
    fem = case.fem
    h = fem.h_surface if fem.h_surface is not None else fem.h
    return H_FACTOR * h * case.hertz_scales[0]


def friction(case: Case) -> float:
    """The friction coefficient the deck is given (one place, for the seeded defects of
    tests/test_calculix_adapter.py)."""
    return case.friction.mu1


def stick_slope(case: Case, h: float) -> float:
    """The stick slope [MPa/mm] (module doc; one place, for the seeded defects)."""
    return K_T * case.E_star / h


def radius_ratio(case: Case) -> float:
    """The contact radius's growth per normal increment (module doc)."""
    coupling = abs(case.dundurs_beta) * friction(case)
    return 1.4 if coupling == 0 else min(1.4, max(1.1, 1.0 + 0.01 / coupling))


def model(case: Case, h: float) -> tuple[Body, Body, Model]:
    """The two bodies and the deck's parameters of ``case`` at element size ``h``."""
    a0 = case.hertz_scales[0]
    shape = symmetry(case)
    a, b = bodies(a0, case.R, h, SIDE * a0, SIDE * a0, shape,
                  profile_share(case.a.E, case.a.nu, case.b.E, case.b.nu))
    share = SHARE[shape]
    ld = case.load
    m = Model(E_a=case.a.E, nu_a=case.a.nu, E_b=case.b.E, nu_b=case.b.nu,
              mu=friction(case), k_n=K_N * case.E_star / h, k_t=stick_slope(case, h),
              approach=APPROACH * a0**2 / case.R, radius_ratio=radius_ratio(case),
              first_radius=min(1.0, 2.0 * h / a0), P=share * ld.P,
              Qx=share * (ld.Qx or 0.0), Qy=share * (ld.Qy or 0.0),
              stress_body=case.stress.body)
    return a, b, m
