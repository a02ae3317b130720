"""The case-independent part of an FE model, kept for the next case of a sweep: the block
mesh, its P2 space and supports, the factorised stiffness and the condensed one-block
compliances C₁(ν) (E = 1) of the contact DOFs."""

from __future__ import annotations

import os
import time

import numpy as np

from ..errors import FemError
from .elasticity import Factorization, P2Space, stiffness
from .mesh import MeshSpec, block_mesh
from .surface import ContactSurface


def cache_enabled() -> bool:
    return os.environ.get("CONTACT_VV_FEM_CACHE", "1") not in ("0", "", "no", "false")


class FactorisedBlock:
    """The case-independent part of a model: mesh, P2 space, supports, factorisations
    and the condensed one-block compliances C₁(ν) (E = 1) of the contact DOFs."""

    def __init__(self, spec: MeshSpec, a_ref: float, comps: tuple[int, ...],
                 nus: tuple[float, ...], log=None, companion: bool = False,
                 r_touch: float | None = None):
        t0 = time.perf_counter()
        self.mesh = block_mesh(spec, a_ref)
        t_mesh = time.perf_counter()
        self.space = space = P2Space(self.mesh)
        nodes = space.nodes
        tol = 1e-9 * a_ref
        fixed = np.zeros(space.ndofs, dtype=bool)
        bottom = np.nonzero(np.abs(nodes[2] + spec.H * a_ref) < tol)[0]
        fixed[(3 * bottom[:, None] + np.arange(3)).ravel()] = True
        if spec.shape == "quarter":
            fixed[3 * np.nonzero(np.abs(nodes[0]) < tol)[0]] = True
        if spec.shape in ("quarter", "half"):
            fixed[3 * np.nonzero(np.abs(nodes[1]) < tol)[0] + 1] = True
        self.fixed = fixed
        self.free = np.nonzero(~fixed)[0]
        # the companion's supports: the same bottom, the mirror plane Y = 0 holding u_x, u_z
        self.free_anti = None
        if companion:
            plane = np.nonzero(np.abs(nodes[1]) < tol)[0]
            fixed_anti = np.zeros(space.ndofs, dtype=bool)
            fixed_anti[(3 * bottom[:, None] + np.arange(3)).ravel()] = True
            fixed_anti[(3 * plane[:, None] + np.array([0, 2])).ravel()] = True
            self.free_anti = np.nonzero(~fixed_anti)[0]
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
        self.factor: dict[float, Factorization] = {}
        self.factor_anti: dict[float, Factorization] = {}  # the companion's (no condensation)
        self.stiffness: dict[float, object] = {}  # rows of K (E = 1) at the fixed DOFs
        self.C1: dict[float, np.ndarray] = {}
        t_asm = t_fac = t_cond = 0.0
        for nu in sorted(set(nus)):
            ta = time.perf_counter()
            K = stiffness(space, nu)
            Kff = K[self.free][:, self.free].tocsr()
            self.stiffness[nu] = K[np.nonzero(fixed)[0]].tocsr()
            tb = time.perf_counter()
            F = Factorization(Kff, partial=pos)
            tc = time.perf_counter()
            self.C1[nu] = F.schur_inverse()
            td = time.perf_counter()
            self.factor[nu] = F
            t_anti = 0.0
            if self.free_anti is not None:
                te = time.perf_counter()
                fa = self.free_anti
                self.factor_anti[nu] = Factorization(K[fa][:, fa].tocsr())
                t_anti = time.perf_counter() - te
            t_asm, t_cond = t_asm + tb - ta, t_cond + td - tc
            t_fac += tc - tb + t_anti
            if log:
                log(f"nu={nu}: {Kff.shape[0]} free DOFs, assembly {tb - ta:.1f} s, "
                    f"factorisation {tc - tb:.1f} s, "
                    f"condensation ({pos.size} DOFs) {td - tc:.1f} s")
        self.timings = {"mesh_s": t_mesh - t0, "assembly_s": t_asm, "factorisation_s": t_fac,
                        "condensation_s": t_cond}
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
