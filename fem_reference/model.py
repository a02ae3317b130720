"""The finite-element model of a case: block mesh, symmetry, factorisations, condensation.

Two bodies, one mesh.  Both bodies are modelled by the same finite block (half-width L,
depth H, bottom fixed, sides traction-free) in its own frame (X, Y, Z) with Z = −depth:
body b is the block as it stands (global frame = block frame), body a is its mirror
image (Z = −z).  Condensing each block onto the surface DOFs of the contact zone gives
its compliance C₁(ν)/E (unit forces, E = 1); the relative displacement u = u⁽ᵃ⁾ − u⁽ᵇ⁾
under the forces f on body a (−f on body b) is then

    u = (R C₁(ν_a) R / E_a + C₁(ν_b) / E_b) f,       R = diag(1, 1, −1) per node,

the FE counterpart of the half-space influence matrix A of Eqs. 3-6.  For identical
materials the normal–tangential coupling blocks cancel (K = 0, Eq. 6) and the normal
and tangential blocks equal those of one block of modulus E/2 = E*(1 − ν²) against a
rigid indenter (erratum 10).  For dissimilar materials the coupling is kept.

Symmetry: a quarter block (X, Y ≥ 0) when no tangential traction breaks the symmetry
about both vertical planes (frictionless, or friction with no tangential load and the
tribological axes along x, y), a half block (Y ≥ 0) for friction, tangential loading
and sliding along ±x with axes along x, y; otherwise the full block.  Symmetry planes
carry roller conditions (zero normal displacement).

One more half block: identical materials sliding along ±x with axes *not* along x, y
(the orthotropic pin at β = 45°).  Its contact problem is a normal one (K = 0) and
symmetric about Y = 0, but the friction traction c p_n (``Law.slide_traction``) has a y
component, even in y like p_n: a load antisymmetric about the plane.  The half block
carries it as a *companion* problem, the same half block with the mirror conditions
swapped (u_x = u_z = 0 on Y = 0, u_y free), factorised once more but never condensed;
the displacement of a body is the sum of the two solutions (:class:`BodyDisplacement`),
and the companion's components change sign under the mirror where the symmetric
solution's do not (``fem_reference.stress_planes``, ``fem_reference.output``).  Half the
DOFs of the full block: a third of its factorisation and condensation time.
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import scipy.linalg as la

from cases.model import Case, CaseError

from .contact import Law, axes_tensor, norm_with
from .elasticity import Factorization, P2Space, stiffness
from .mesh import MeshSpec, block_mesh
from .surface import ContactSurface


class FemError(RuntimeError):
    """The FEM reference failed on this case (the message names the cause)."""


class FemUnsupported(FemError, CaseError):
    """The case needs a feature the FEM reference does not have (also a CaseError)."""


def reference_length(case: Case) -> float:
    """The length unit of ``case.fem``: the Hertz radius a0 (load control) or √(R δ)."""
    if case.load.P is not None:
        return case.hertz_a0
    return math.sqrt(case.R * case.load.approach)


def slide_direction(case: Case) -> np.ndarray:
    a = math.radians(case.load.slide_angle)
    return np.array([math.cos(a), math.sin(a)])


def wear_norms(case: Case, slip: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``‖Δg‖_i`` of bodies a and b (Eq. 21) for slip increments Δg (..., 2)."""
    beta = case.friction.beta
    return tuple(norm_with(axes_tensor(body.i1**2, body.i2**2, beta), slip)
                 for body in (case.a, case.b))


def wear_compliances(case: Case, slip: np.ndarray) -> tuple[float, float]:
    """``‖Δg‖_i`` of bodies a and b for one slip increment Δg (2,) (Eq. 21)."""
    ia, ib = wear_norms(case, slip)
    return float(ia), float(ib)


def expected_radius(case: Case, a_ref: float) -> float:
    """Largest contact radius expected during the run, in units of ``a_ref``.

    Hertz for static cases; Argatov's worn-pin radius (docs/cases.md, case 4)
    a⁴ = a0⁴ + 4 i_w P s R / π at the end of a sliding-wear run.

    Fretting: the worn depth is estimated by Archard's law with the Hertz pressure p0
    and the largest slip a cycle can have, 4A (gross slip), over all cycles, with the
    larger wear coefficient of each body: w = (i_a + i_b) p0 4A N.  Under a held load
    the radius grows like the worn pin's (s = 4AN); under a held approach δ the flattened
    sphere closes up to a² = R(δ + w), never beyond the rigid overlap a² = 2Rδ.
    """
    a = a_ref
    if case.kind == "sliding_wear" and case.sliding_wear is not None:
        d = slide_direction(case)
        ia, ib = wear_compliances(case, d)
        s = case.sliding_wear.distance
        a = (a_ref**4 + 4.0 * (ia + ib) * case.load.P * s * case.R / math.pi) ** 0.25
    elif case.kind == "fretting" and case.fretting is not None:
        fr = case.fretting
        i_w = max(case.a.i1, case.a.i2) + max(case.b.i1, case.b.i2)
        s = 4.0 * fr.amplitude * fr.cycles
        if case.load.P is not None:
            a = (a_ref**4 + 4.0 * i_w * case.load.P * s * case.R / math.pi) ** 0.25
        else:
            p0 = 2.0 * case.E_star * a_ref / (math.pi * case.R)
            growth = 1.0 + i_w * p0 * s / case.load.approach
            a = a_ref * math.sqrt(min(growth, 2.0))
    return a / a_ref


def has_companion(case: Case) -> bool:
    """Whether the half block carries the y friction traction by an antisymmetric
    companion problem (module doc): identical materials in full sliding along ±x, friction
    axes not along x, y."""
    fr = case.friction
    if case.kind == "fretting" or not case.identical_materials or fr.mu1 == 0.0:
        return False
    if not (case.load.tangential_mode == "sliding" or case.kind == "sliding_wear"):
        return False
    return _slides_along_x(case) and not _axes_aligned(fr)


def _axes_aligned(fr) -> bool:
    """Isotropic friction, or tribological axes along x and y."""
    beta = fr.beta % 90.0
    return fr.isotropic or min(beta, 90.0 - beta) < 1e-12


def _slides_along_x(case: Case) -> bool:
    return abs(math.sin(math.radians(case.load.slide_angle))) < 1e-12


def choose_shape(case: Case) -> str:
    fr = case.friction
    mode = case.load.tangential_mode
    if fr.mu1 == 0.0 and fr.mu2 == 0.0:
        return "quarter"
    aligned = _axes_aligned(fr)
    if mode == "none" and case.kind == "static" and aligned:
        return "quarter"
    along_x = False
    if mode == "load":
        along_x = not case.load.Qy
    elif mode == "shift":
        along_x = not case.load.shift_y
    if mode == "sliding" or case.kind in ("sliding_wear", "fretting"):
        along_x = _slides_along_x(case)
    if (aligned and along_x) or has_companion(case):
        return "half"
    return "full"


class BodyDisplacement(NamedTuple):
    """A body's displacement on the modelled block (block frame, true units): ``sym``
    under the load as the symmetry planes see it, ``anti`` the companion's under the
    antisymmetric part (None without a companion, module doc)."""

    sym: np.ndarray
    anti: np.ndarray | None = None

    @property
    def total(self) -> np.ndarray:
        """The displacement on the modelled block itself (both parts)."""
        return self.sym if self.anti is None else self.sym + self.anti


@dataclass
class Symmetry:
    shape: str
    companion: bool = False  # a half block with an antisymmetric companion (module doc)

    @property
    def factor(self) -> float:
        return {"quarter": 4.0, "half": 2.0, "full": 1.0}[self.shape]

    def map(self, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Points mapped into the modelled part and the reflection signs (sx, sy).

        A component odd under a reflection (p_x, σ_xy, σ_xz for x → −x) is multiplied by
        its sign; on a mirror plane itself the sign is 0: those components vanish there by
        symmetry, the average of the field and its mirror image.
        """
        xy = np.array(xy, dtype=float, copy=True)
        sx = np.ones(xy.shape[0])
        sy = np.ones(xy.shape[0])
        tol = 1e-9 * max(float(np.abs(xy).max(initial=0.0)), 1e-300)
        if self.shape == "quarter":
            sx = np.where(xy[:, 0] < 0, -1.0, 1.0)
            sx[np.abs(xy[:, 0]) <= tol] = 0.0
            xy[:, 0] = np.abs(xy[:, 0])
        if self.shape in ("quarter", "half"):
            sy = np.where(xy[:, 1] < 0, -1.0, 1.0)
            sy[np.abs(xy[:, 1]) <= tol] = 0.0
            xy[:, 1] = np.abs(xy[:, 1])
        return xy, sx, sy


def _cache_enabled() -> bool:
    return os.environ.get("CONTACT_VV_FEM_CACHE", "1") not in ("0", "", "no", "false")


class _Core:
    """The case-independent part of a model: mesh, P2 space, supports, factorisations
    and the condensed one-block compliances C₁(ν) (E = 1) of the contact DOFs."""

    def __init__(self, spec: MeshSpec, a_ref: float, comps: tuple[int, ...],
                 nus: tuple[float, ...], log=None, companion: bool = False):
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
        self.surface = ContactSurface(space, spec.r_ref * a_ref, (0, 1, 2), fixed)
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


_CORE: list = []  # [(key, core)]: the last core, kept for the next case of a sweep


def _core(spec: MeshSpec, a_ref: float, comps: tuple[int, ...], nus: tuple[float, ...],
          log=None, companion: bool = False) -> _Core:
    """The core for these parameters, reused from the previous call when they match.

    A sweep (μ, β, Q values) runs the same mesh, materials and contact DOFs again and
    again: the mesh, factorisation and condensation are then done once.  Only the last
    core is kept; ``CONTACT_VV_FEM_CACHE=0`` disables the reuse.
    """
    key = (spec.key(), float(a_ref), tuple(comps), tuple(sorted(set(nus))), companion)
    if _cache_enabled() and _CORE and _CORE[0][0] == key and _CORE[0][1].factor:
        core = _CORE[0][1]
    else:
        while _CORE:
            _CORE.pop()[1].release()
        core = _Core(spec, a_ref, comps, nus, log, companion)
        if _cache_enabled():
            _CORE.append((key, core))
    core.uses += 1
    return core


class FemModel:
    """Mesh, factorised stiffness and condensed two-body surface stiffness of a case."""

    def __init__(self, case: Case, *, log=None):
        t0 = time.perf_counter()
        self.case = case
        fem = case.fem
        if fem.order != 2:
            raise FemUnsupported(
                f"fem.order = {fem.order}: fem_reference implements P2 (order 2) only"
            )
        self.a_ref = reference_length(case)
        self.h = fem.h_contact * self.a_ref  # element size at the contact surface [mm]
        self.a_max = expected_radius(case, self.a_ref)  # units of a_ref
        r_c = 1.25 * self.a_max + 2.0 * fem.h
        z_ref = max(1.0, 0.8 * self.a_max)
        # a growing (worn) contact: h in the initial contact, then h ∝ distance, so the
        # final contact of radius a_max is resolved with about the same elements per radius
        r_fine = min(1.25, r_c) if self.a_max > 1.25 else r_c
        self.shape = choose_shape(case)
        self.sym = Symmetry(self.shape, companion=has_companion(case))
        grid = case.grid
        L_mm, H_mm = fem.block * self.a_ref, fem.depth * self.a_ref
        half_grid = 0.5 * max(grid.Lx, grid.Ly) + max(abs(case.stress.x0), abs(case.stress.y0))
        if half_grid >= L_mm:
            raise CaseError(
                f"fem.block = {fem.block} (L = {L_mm:.4g} mm) does not cover the contact grid "
                f"(half-width {half_grid:.4g} mm); increase fem.block"
            )
        if case.stress.depth >= H_mm:
            raise CaseError(
                f"fem.depth = {fem.depth} (H = {H_mm:.4g} mm) is not deeper than stress.depth "
                f"= {case.stress.depth} mm; increase fem.depth"
            )
        if self.a_max * self.a_ref >= 0.5 * min(grid.Lx, grid.Ly):
            raise CaseError(
                f"the expected contact (radius {self.a_max * self.a_ref:.4g} mm) reaches the edge "
                f"of the potential contact grid (grid.Lx, grid.Ly)"
            )
        self.spec = MeshSpec(self.shape, fem.block, fem.depth, fem.h, r_c, z_ref,
                             grading=0.25, h_max=fem.block / 4.0, r_fine=r_fine,
                             h_surface=fem.surface_layer)
        self.law_mode = self._law_mode()
        # The contact iteration needs the tangential DOFs only when the tangential
        # tractions depend on them: friction with history, or any friction with the
        # normal–tangential coupling of dissimilar materials.  Frictionless contact and
        # full sliding of identical materials (traction = const * p_n, K = 0) are normal
        # problems; their tangential tractions only load the blocks.
        normal_only = self.law_mode == "frictionless" or (
            self.law_mode == "sliding" and case.identical_materials
        )
        comps = (2,) if normal_only else (0, 1, 2)
        if self.sym.companion and not normal_only:
            raise FemError("internal error: an antisymmetric companion needs a normal "
                           "contact problem")
        core = _core(self.spec, self.a_ref, comps, (case.a.nu, case.b.nu), log,
                     companion=self.sym.companion)
        self.core = core
        self.mesh, self.space = core.mesh, core.space
        self.fixed, self.free = core.fixed, core.free
        self.surface, self.top, self.cidx = core.surface, core.top, core.cidx
        self.factor, self.stiffness = core.factor, core.stiffness
        C1 = core.C1
        Rz = np.where(self.surface.dof_comp[self.cidx] == 2, -1.0, 1.0)
        Crel = (Rz[:, None] * C1[case.a.nu] * Rz[None, :]) / case.a.E + C1[case.b.nu] / case.b.E
        self.Crel = Crel
        cho = la.cho_factor(Crel)
        self.Krel = la.cho_solve(cho, np.eye(Crel.shape[0]))
        self.Krel = 0.5 * (self.Krel + self.Krel.T)
        self.law = self._law()
        self.timings = {**core.timings, "reused": core.uses > 1,
                        "setup_s": time.perf_counter() - t0}

    # ------------------------------------------------------------------ contact law

    def _law_mode(self) -> str:
        case = self.case
        if case.friction.mu1 == 0.0:
            return "frictionless"
        mode = case.load.tangential_mode
        if mode == "sliding" or case.kind == "sliding_wear":
            return "sliding"
        if mode in ("load", "shift") or case.kind == "fretting" or not case.identical_materials:
            return "friction"
        return "frictionless"  # identical materials, no tangential load: p_t stays 0

    def _law(self) -> Law:
        case = self.case
        k_n = case.fem.penalty * case.E_star / self.h
        if self.law_mode == "frictionless":
            return Law(k_n=k_n)
        fr = case.friction
        M2 = axes_tensor(fr.mu1**2, fr.mu2**2, fr.beta)
        M2inv = axes_tensor(fr.mu1**-2, fr.mu2**-2, fr.beta)
        if self.law_mode == "sliding":
            d = slide_direction(case)
            c = -(M2 @ d) / float(norm_with(M2, d))
            return Law(k_n=k_n, mode="sliding", M2=M2, M2inv=M2inv, slide_traction=c)
        # tangential penalty k_t 𝕄²: at least k_n along the weaker friction axis
        k_t = k_n / min(fr.mu1, fr.mu2) ** 2
        return Law(k_n=k_n, mode="friction", k_t=k_t, M2=M2, M2inv=M2inv)

    # ------------------------------------------------------------------ full solves

    def body_displacements(self, f: np.ndarray, f_y: np.ndarray | None = None
                           ) -> tuple[BodyDisplacement, BodyDisplacement]:
        """Block-frame displacements (E = 1 scaling removed) of bodies a and b.

        ``f``: nodal forces on body a at all surface DOFs (global frame).  Returns the true
        displacement fields (3 * nnodes,) of a and b, each in its own block frame.  With a
        companion (module doc) ``f_y``, the y forces on body a at every surface node (the
        mirror plane's too, whose u_y the block holds), load the companion, and the y
        forces of ``f`` are left out of the block's load.
        """
        case = self.case
        surf = self.surface
        if self.sym.companion and f_y is None:
            raise ValueError("a model with a companion needs the y forces f_y")
        out = []
        for body, sign in ((case.a, 1.0), (case.b, -1.0)):
            F = np.zeros(self.space.ndofs)
            # body b carries −f in the global frame; body a f, its block frame z = −z
            F[surf.dofs] = sign * np.where((surf.dof_comp == 2) & (sign > 0), -f, f)
            anti = None
            if self.sym.companion:
                F[1::3] = 0.0
                F_anti = np.zeros(self.space.ndofs)
                F_anti[3 * surf.nodes + 1] = sign * f_y
                fa = self.core.free_anti
                anti = np.zeros(self.space.ndofs)
                anti[fa] = self.core.factor_anti[body.nu].solve(F_anti[fa]) / body.E
            u = np.zeros(self.space.ndofs)
            u[self.free] = self.factor[body.nu].solve(F[self.free]) / body.E
            out.append(BodyDisplacement(u, anti))
        return out[0], out[1]

    def support_reaction(self, u: BodyDisplacement, body) -> float:
        """Total vertical force of the block's supports on a body (symmetry included).

        ``u``: the body's true displacement (block frame).  Equilibrium of the whole FE
        block: equals the transmitted normal load P.  A companion's vertical reactions
        are odd in y and cancel over the whole block.
        """
        r = body.E * (self.stiffness[body.nu] @ u.sym)  # reactions at the fixed DOFs
        fixed = np.nonzero(self.fixed)[0]
        z = (fixed % 3) == 2
        return self.sym.factor * float(r[z].sum())

    def free_memory(self) -> None:
        """Release the factorisations unless the core is kept for the next case."""
        if not _cache_enabled():
            self.core.release()
