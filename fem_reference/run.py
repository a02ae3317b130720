"""One FEM run of a case: its set-up on a model, its current state, its output states.

:func:`start_run` builds the contact points (one per surface node of the contact zone,
with the dual weights of :mod:`fem_reference.model.nodal_basis`, and the output samples of
:mod:`fem_reference.fields.sampling`) and the stress sampler, and starts from the displacements
under the Hertz pressure (:func:`hertz_start`).  The load path (:mod:`fem_reference.loading`)
advances the state and hands over an :class:`OutputState` per output step; the output
recovery (:mod:`fem_reference.output`) reads both.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from .contact.compliance import NodalCompliance
from .contact.control import Solution
from .contact.kept_factors import KeptFactors
from .contact.laws import Evaluation, Points
from .contact.stiffened import StiffenedSolver
from .fields.sampling import SampleInterpolation, sample_interpolation, sample_layout
from .fields.stresses import PointLocator
from .model.far_field import block_offset, block_offset_t
from .model.fem_model import FemModel
from .model.nodal_basis import coefficients, dual_weights, modified_basis


@dataclass
class Run:
    """The set-up of a run and its current converged state (``u``, ``delta``, ``D`` and
    the histories ``lam_n, t_old, gt_old, wear_a, wear_b`` of ``nodes`` and ``samples``)."""

    model: FemModel
    nodes: Points  # contact points: the surface nodes (modified coefficients, dual weights)
    samples: Points  # output samples (weights 0)
    G_all: sp.csr_matrix  # all surface DOFs -> modified coefficients at the nodes
    Binv: sp.csr_matrix  # modified coefficients -> nodal values (forces: Binv W λ per node)
    Nmod: sp.csr_matrix  # modified coefficients -> field values at the samples (N Bᵀ)
    sampling: SampleInterpolation
    locator: PointLocator  # finds the elements of stress sample points
    u: np.ndarray  # relative surface displacements (condensed DOFs)
    delta: float  # rigid approach δ of the blocks
    D: np.ndarray  # rigid tangential displacement g_t,o
    compliance: float = 0.0  # far-field compliance c: half-space approach = δ + c P
    compliance_t: float = 0.0  # tangential: half-space shift = D + c_t Q (Q on body a)
    lin: StiffenedSolver | None = None  # the augmented solves' kept factors (start_run)
    op: NodalCompliance | None = None  # the semi-smooth solves' nodal compliance
    kept: KeptFactors = field(default_factory=KeptFactors)  # ... and their kept factors


@dataclass(frozen=True)
class OutputState:
    """A converged state the load path reports: output step ``step`` at sliding distance
    ``s`` or fretting cycle ``cycle``, its solution, the sample evaluation, the slip of
    the step at the samples, the contact iterations it took and the run's tables so far."""

    step: int
    sol: Solution
    sample_ev: Evaluation
    slip: np.ndarray  # (nsamples, 2), global frame
    iterations: int
    s: float = float("nan")
    cycle: float = float("nan")
    tables: dict = field(default_factory=dict)  # run tables so far (fretting loops, cycles)
    events: list | None = None  # regime events so far (fretting), None: not watched


def start_run(model: FemModel) -> Run:
    """Contact points, samples, recovery and the Hertz start of a run on ``model``."""
    case, surf = model.case, model.surface
    R = case.R
    B, Binv = modified_basis(surf)
    G_all = surf.operator(Binv.T.tocsr())  # all surface DOFs (forces on the blocks)
    nodes = Points(G=G_all[:, model.cidx].tocsr(), w=dual_weights(surf, B), xy=surf.xy,
                   h=coefficients(Binv, (surf.xy**2).sum(axis=1) / (2 * R)),
                   inside=np.ones(surf.nnodes, bool))
    # over the refined zone (the mesh's), whatever part of it is condensed
    layout = sample_layout(case.grid, model.shape, model.spec.r_ref * model.a_ref, model.h)
    sampling = sample_interpolation(model, layout)
    xy = layout.xy
    samples = Points(G=surf.operator(sampling.N)[:, model.cidx].tocsr(), w=np.zeros(xy.shape[0]),
                    xy=xy, h=(xy**2).sum(axis=1) / (2 * R), inside=sampling.found)
    u, delta = hertz_start(model, nodes)
    semismooth = case.fem.contact == "semismooth"
    return Run(model=model, nodes=nodes, samples=samples, G_all=G_all, Binv=Binv.tocsr(),
               Nmod=(sampling.N @ B.T).tocsr(), sampling=sampling,
               locator=PointLocator(model.space),
               u=u, delta=delta, D=np.zeros(2),
               lin=None if semismooth else StiffenedSolver(model.Crel),
               op=NodalCompliance.build(model.compliance, nodes.G, nodes.w, nodes.h)
               if semismooth else None,
               **dict(zip(("compliance", "compliance_t"),
                          far_compliance(model, nodes, G_all), strict=True)))


def far_compliance(model: FemModel, nodes: Points, G_all: sp.csr_matrix
                   ) -> tuple[float, float]:
    """(c, c_t) = Σ_bodies c₁(ν)/E [mm/N], the normal and tangential far-field
    compliances the blocks lack (:mod:`fem_reference.model.far_field`): normal from a unit load
    of the Hertz distribution of radius a_ref applied through the contact points'
    weights, tangential from a unit force at the axis (0 for the quarter model, which
    carries no tangential load)."""
    case, a = model.case, model.a_ref
    r2 = (nodes.xy**2).sum(axis=1)
    p = np.sqrt(np.maximum(1.0 - r2 / a**2, 0.0))
    p /= model.sym.factor * float(nodes.w @ p)
    n = nodes.n
    f_b = -(G_all.T @ np.concatenate([np.zeros(2 * n), nodes.w * p]))  # into block b
    nodes_xyz = model.space.nodes
    c1 = {nu: block_offset(model.factor[nu], model.free, model.surface.dofs, f_b,
                           nodes_xyz, a, nu)[0] for nu in model.factor}
    c1t = {nu: 0.0 if model.shape == "quarter" else
           block_offset_t(model.factor[nu], model.free, nodes_xyz, a, nu,
                          model.sym.factor)[0] for nu in model.factor}
    # Q is the resultant on body a and opposes the rigid shift g_t,o: shift = D − c₁ₜ Q/E
    return (c1[case.a.nu] / case.a.E + c1[case.b.nu] / case.b.E,
            -(c1t[case.a.nu] / case.a.E + c1t[case.b.nu] / case.b.E))


def hertz_start(model: FemModel, pts: Points, frac: float = 1.0) -> tuple[np.ndarray, float]:
    """Initial guess (u, δ): the displacements under the Hertz pressure of the case at
    the fraction ``frac`` of its normal load (or approach).

    Starting the semi-smooth Newton iteration from an almost right active set saves
    most of the iterations a start from u = 0 (every point of h < δ penetrating)
    takes.  δ is the mean of h + u_n over the Hertz contact (constant for a
    half-space); under approach control the prescribed approach.
    """
    case = model.case
    # Hertz: a ∝ P^(1/3) under load control, a ∝ δ^(1/2) under approach control
    a = model.a_ref * (frac ** (1.0 / 3.0) if case.load.P is not None else math.sqrt(frac))
    p0 = 2.0 * case.E_star * a / (math.pi * case.R)
    r2 = (pts.xy**2).sum(axis=1)
    pH = p0 * np.sqrt(np.maximum(1.0 - r2 / a**2, 0.0))
    w = pts.w
    n = w.size
    f = pts.G.T @ np.concatenate([np.zeros(2 * n), w * pH])
    u = model.compliance @ f
    if case.load.P is None:
        return u, float(case.load.approach) * frac
    uz = pts.displacement(u)[:, 2]
    inner = r2 < (0.8 * a) ** 2
    return u, float(np.mean(pts.h[inner] + uz[inner]))
