"""The case-independent part of an FE model, kept for the next case of a sweep: the block
mesh, its P2 space and supports, the factorised stiffness and the condensed one-block
compliances C₁(ν) (E = 1) of the contact DOFs."""

from __future__ import annotations

import os
import time
from dataclasses import replace

import numpy as np
from skfem import MeshTet

from ..errors import FemError
from .elasticity import Factorization, P2Space, stiffness
from .mesh import MeshSpec, block_mesh
from .parity import (
    ParityCompliance,
    ParityFactorization,
    ParitySplit,
    condensed,
    extension,
    held,
    mirrored,
    parities,
)
from .surface import ContactSurface


def cache_enabled() -> bool:
    return os.environ.get("CONTACT_VV_FEM_CACHE", "1") not in ("0", "", "no", "false")


#: the mirror planes X_axis = 0 a block of each shape is made of a quarter by
#: (:func:`.parity.mirrored`; the quarter is gmsh's own): the half block about X = 0
#: (two parities, and two for a companion), the full block about X = 0 and Y = 0 (four)
MIRRORED: dict[str, tuple[int, ...]] = {"quarter": (), "half": (0,), "full": (0, 1)}


class FactorisedBlock:
    """The case-independent part of a model: mesh, P2 space, supports, factorisations
    and the condensed one-block compliances C₁(ν) (E = 1) of the contact DOFs.

    A block of a shape :data:`MIRRORED` names (the half and full blocks) is a quarter
    block and its mirror images, factorised and condensed as the quarter's parity
    problems (:mod:`.parity`): ``factor`` (``factor_anti``) and ``C1`` then hold
    :class:`~.parity.ParityFactorization` and :class:`~.parity.ParityCompliance`, which
    solve and multiply as the block's own would."""

    def __init__(self, spec: MeshSpec, a_ref: float, comps: tuple[int, ...],
                 nus: tuple[float, ...], log=None, companion: bool = False,
                 r_touch: float | None = None):
        t0 = time.perf_counter()
        tol = 1e-9 * a_ref
        self.split: ParitySplit | None = None
        axes = MIRRORED[spec.shape]
        if axes:
            quarter = block_mesh(replace(spec, shape="quarter"), a_ref)
            P, T, image = mirrored(quarter.p, quarter.t, tol, axes)
            self.mesh = MeshTet(P, T)
            quarter_space = P2Space(MeshTet(np.ascontiguousarray(P[:, :quarter.p.shape[1]]),
                                             quarter.t))
        else:
            self.mesh = block_mesh(spec, a_ref)
        t_mesh = time.perf_counter()
        self.space = space = P2Space(self.mesh)
        if axes:
            self.split = ParitySplit(quarter_space, space, image, axes)
        bottom = bottom_of(space, spec, a_ref)
        self.fixed = fixed = bottom | _mirror_supports(space, spec.shape, tol, (1, 1))
        self.free = np.nonzero(~fixed)[0]
        # the companion's supports: the same bottom, the mirror plane Y = 0 holding u_x, u_z
        self.free_anti = None
        if companion:
            self.free_anti = np.nonzero(~(bottom | _mirror_supports(space, "half", tol,
                                                                     (1, -1))))[0]
        # condensed: the refined zone, or within r_touch where no node beyond can touch
        r_cond = spec.r_ref if r_touch is None else min(spec.r_ref, r_touch)
        self.surface = ContactSurface(space, r_cond * a_ref, (0, 1, 2), fixed)
        self.top = ContactSurface(space, np.inf, (2,), fixed)
        self.cidx = np.nonzero(np.isin(self.surface.dof_comp, comps))[0]
        cdofs = self.surface.dofs[self.cidx]
        pos = np.searchsorted(self.free, cdofs)
        if not np.array_equal(self.free[pos], cdofs):
            raise FemError("internal error: a condensed surface DOF is fixed")
        # stiffness, factorisation and condensation per distinct Poisson's ratio
        self.factor: dict[float, Factorization | ParityFactorization] = {}
        self.factor_anti: dict[float, Factorization | ParityFactorization] = {}  # not condensed
        self.stiffness: dict[float, object] = {}  # rows of K (E = 1) at the fixed DOFs
        self.C1: dict[float, np.ndarray | ParityCompliance] = {}
        fixed_at = np.nonzero(fixed)[0]
        t_asm = t_fac = 0.0
        for nu in sorted(set(nus)):
            ta = time.perf_counter()
            if self.split is None:
                K = stiffness(space, nu)
                self.stiffness[nu] = K[fixed_at].tocsr()
                tb = time.perf_counter()
                F = Factorization(K[self.free][:, self.free].tocsr(), partial=pos)
                self.factor[nu], self.C1[nu] = F, F.schur_inverse()
                unknowns = [self.free.size]
            else:
                held_nodes = np.flatnonzero(fixed.reshape(-1, 3).any(axis=1))
                support = np.isin(space.element_nodes, held_nodes).any(axis=0)
                self.stiffness[nu] = stiffness(space, nu, elements=np.flatnonzero(support)
                                               )[fixed_at].tocsr()
                K = stiffness(self.split.quarter, nu)
                tb = time.perf_counter()
                bottom_q = bottom_of(self.split.quarter, spec, a_ref)
                self.factor[nu], self.C1[nu], unknowns = _parity_factors(
                    self.split, K, bottom_q, self.free, cdofs, parities(axes))
            tc = time.perf_counter()
            t_anti = 0.0
            if self.free_anti is not None:
                fa = self.free_anti
                if self.split is None:
                    self.factor_anti[nu] = Factorization(K[fa][:, fa].tocsr())
                else:
                    self.factor_anti[nu] = _parity_factors(
                        self.split, K, bottom_q, fa, None, parities(axes, -1))[0]
                t_anti = time.perf_counter() - tc
            t_asm, t_fac = t_asm + tb - ta, t_fac + tc - tb + t_anti
            if log:
                log(f"nu={nu}: {'+'.join(map(str, unknowns))} free DOFs, assembly "
                    f"{tb - ta:.1f} s, factorisation and condensation ({pos.size} DOFs) "
                    f"{tc - tb:.1f} s")
        self.timings = {"mesh_s": t_mesh - t0, "assembly_s": t_asm, "factorisation_s": t_fac,
                        "condensation_s": 0.0}
        self.uses = 0

    def release(self) -> None:
        for F in (*self.factor.values(), *self.factor_anti.values()):
            F.free()
        self.factor.clear()
        self.factor_anti.clear()


_LAST: list = []  # [(key, core)]: the last core, kept for the next case of a sweep


def factorised_block(spec: MeshSpec, a_ref: float, comps: tuple[int, ...], nus: tuple[float, ...],
          log=None, companion: bool = False, r_touch: float | None = None) -> FactorisedBlock:
    """The factorised block for these parameters, reused from the previous call when
    they match.

    A sweep (μ, β, Q values) runs the same mesh, materials and contact DOFs again and
    again: the mesh, factorisation and condensation are then done once.  Only the last
    block is kept; ``CONTACT_VV_FEM_CACHE=0`` disables the reuse.
    """
    key = (spec.key(), float(a_ref), tuple(comps), tuple(sorted(set(nus))), companion,
           r_touch)
    if cache_enabled() and _LAST and _LAST[0][0] == key and _LAST[0][1].factor:
        core = _LAST[0][1]
    else:
        while _LAST:
            _LAST.pop()[1].release()
        core = FactorisedBlock(spec, a_ref, comps, nus, log, companion, r_touch)
        if cache_enabled():
            _LAST.append((key, core))
    core.uses += 1
    return core


def bottom_of(space: P2Space, spec: MeshSpec, a_ref: float) -> np.ndarray:
    """The DOFs (mask) of the block's fixed bottom Z = −H."""
    nodes = np.flatnonzero(np.abs(space.nodes[2] + spec.H * a_ref) < 1e-9 * a_ref)
    mask = np.zeros(space.ndofs, dtype=bool)
    mask[(3 * nodes[:, None] + np.arange(3)).ravel()] = True
    return mask


def _mirror_supports(space: P2Space, shape: str, tol: float,
                     parity: tuple[int, int]) -> np.ndarray:
    """The DOFs (mask) the mirror planes of a quarter (X = 0, Y = 0) or half (Y = 0)
    block hold in a field of ``parity`` (:func:`.parity.held`; the block's own load is
    even: roller conditions)."""
    axes = {"quarter": (0, 1), "half": (1,), "full": ()}[shape]
    if not axes:
        return np.zeros(space.ndofs, dtype=bool)
    return held({axis: np.abs(space.nodes[axis]) < tol for axis in axes}, parity)


def _parity_factors(split: ParitySplit, K, bottom: np.ndarray, free: np.ndarray,
                    cdofs: np.ndarray | None, of: tuple[tuple[int, int], ...]
                    ) -> tuple[ParityFactorization, ParityCompliance | None, list]:
    """The mirrored block's factorisation on its unknowns ``free`` and condensed
    compliance on the contact DOFs ``cdofs`` (None: no condensation) from the quarter's
    stiffness ``K`` and the parities ``of`` (:mod:`.parity`), and the unknowns of each
    factorisation."""
    parts, blocks, index, sign, unknowns = [], [], [], [], []
    for parity in of:
        free_p = np.flatnonzero(~(bottom | split.held(parity)))
        Kp = K[free_p][:, free_p].tocsr()
        if cdofs is None:
            F = Factorization(Kp)
        else:
            kept, row, s = condensed(split, parity, cdofs, free_p)
            F = Factorization(Kp, partial=kept)
            blocks.append(F.schur_inverse())
            index.append(row)
            sign.append(s)
        parts.append((extension(split, parity, free, free_p), F))
        unknowns.append(free_p.size)
    C = None if cdofs is None else ParityCompliance(tuple(blocks), np.array(index),
                                                    np.array(sign), split.images)
    return ParityFactorization(parts, split.images), C, unknowns
