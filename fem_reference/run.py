"""One FEM run of a case: its set-up on a model, its current state, its output states.

:func:`start_run` builds the contact points (the surface quadrature points, where the
penalty tractions are integrated, and the output probes of :mod:`fem_reference.sampling`),
the traction recovery and the stress sampler, and starts from the displacements under
the Hertz pressure (:func:`hertz_start`).  The load path (:mod:`fem_reference.loading`)
advances the state and hands over an :class:`OutputState` per output step; the output
recovery (:mod:`fem_reference.output`) reads both.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from .contact import Evaluation, Points, Solution
from .contact_zone import gap_tolerance
from .model import FemModel
from .recovery import TractionRecovery, traction_recovery
from .sampling import ProbeSampling, probe_layout, probe_sampling
from .stresses import PointLocator


@dataclass
class Run:
    """The set-up of a run and its current converged state (``u``, ``delta``, ``D`` and
    the histories ``t_old, gt_old, wear_a, wear_b`` of ``quad`` and ``probes``)."""

    model: FemModel
    quad: Points  # surface quadrature points
    probes: Points  # output probes (weights 0)
    G_all: sp.csr_matrix  # all surface DOFs -> displacements at the quadrature points
    sampling: ProbeSampling
    recovery: TractionRecovery
    locator: PointLocator  # finds the elements of stress sample points
    gap_tol: float  # ε: gaps below it count as closed (fem_reference.contact_zone)
    u: np.ndarray  # relative surface displacements (condensed DOFs)
    delta: float  # rigid approach δ
    D: np.ndarray  # rigid tangential displacement g_t,o


@dataclass(frozen=True)
class OutputState:
    """A converged state the load path reports: output step ``step`` at sliding distance
    ``s``, its solution, the probe evaluation, the slip of the step at the probes and the
    contact iterations it took."""

    step: int
    sol: Solution
    probe_ev: Evaluation
    slip: np.ndarray  # (nprobes, 2), global frame
    iterations: int
    s: float = float("nan")


def start_run(model: FemModel) -> Run:
    """Contact points, probes, recovery and the Hertz start of a run on ``model``."""
    case, surf = model.case, model.surface
    R = case.R
    G_all = surf.operator(surf.Nq)  # all surface DOFs (forces on the blocks)
    quad = Points(G=G_all[:, model.cidx].tocsr(), w=surf.quad_w, xy=surf.quad_xy,
                  h=(surf.quad_xy**2).sum(axis=1) / (2 * R),
                  inside=np.ones(surf.quad_w.size, bool))
    layout = probe_layout(case.grid, model.shape, surf.r_c, model.h)
    sampling = probe_sampling(model, layout)
    xy = layout.xy
    probes = Points(G=surf.operator(sampling.N)[:, model.cidx].tocsr(), w=np.zeros(xy.shape[0]),
                    xy=xy, h=(xy**2).sum(axis=1) / (2 * R), inside=sampling.found)
    u, delta = hertz_start(model, quad)
    return Run(model=model, quad=quad, probes=probes, G_all=G_all, sampling=sampling,
               recovery=traction_recovery(surf, sampling), locator=PointLocator(model.space),
               gap_tol=gap_tolerance(model.a_ref, R), u=u, delta=delta, D=np.zeros(2))


def hertz_start(model: FemModel, quad: Points) -> tuple[np.ndarray, float]:
    """Initial guess (u, δ): the displacements under the Hertz pressure of the case.

    Starting the semi-smooth Newton iteration from an almost right active set saves
    most of the iterations a start from u = 0 (every point of h < δ penetrating)
    takes.  δ is the mean of h + u_n over the Hertz contact (constant for a
    half-space); under approach control the prescribed approach.
    """
    case = model.case
    a = model.a_ref
    p0 = 2.0 * case.E_star * a / (math.pi * case.R)
    r2 = (quad.xy**2).sum(axis=1)
    pH = p0 * np.sqrt(np.maximum(1.0 - r2 / a**2, 0.0))
    w = quad.w
    n = w.size
    f = quad.G.T @ np.concatenate([np.zeros(2 * n), w * pH])
    u = model.Crel @ f
    if case.load.P is None:
        return u, float(case.load.approach)
    uz = quad.displacement(u)[:, 2]
    inner = r2 < (0.8 * a) ** 2
    return u, float(np.mean(quad.h[inner] + uz[inner]))
