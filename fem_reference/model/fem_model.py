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
carry roller conditions (zero normal displacement).  The full block is a quarter block
and its three mirror images, solved and condensed as the quarter's four parity problems
(:mod:`fem_reference.model.parity`): the same numbers as the mirrored mesh's own
factorisation to round-off, for a quarter of its factorisation's unknowns each.

One more half block: identical materials sliding along ±x with axes *not* along x, y
(the orthotropic pin at β = 45°).  Its contact problem is a normal one (K = 0) and
symmetric about Y = 0, but the friction traction c p_n (``Law.slide_traction``) has a y
component, even in y like p_n: a load antisymmetric about the plane.  The half block
carries it as a *companion* problem, the same half block with the mirror conditions
swapped (u_x = u_z = 0 on Y = 0, u_y free), factorised once more but never condensed;
the displacement of a body is the sum of the two solutions (:class:`BodyDisplacement`),
and the companion's components change sign under the mirror where the symmetric
solution's do not (``fem_reference.fields.planes``, ``fem_reference.output``).  Half the
DOFs of the full block: a third of its factorisation and condensation time.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np
import scipy.linalg as la

from cases.model import Case, CaseError

from ..contact.laws import Law, axes_tensor, norm_with
from ..contact.relative import RelativeCompliance
from ..errors import FemError, FemUnsupported
from . import block
from .mesh import MeshSpec
from .shape import (
    choose_shape,
    condensed_radius,
    has_companion,
    mesh_reach,
    reference_length,
    slide_direction,
)


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
        self.a_max = mesh_reach(case, self.a_ref)  # units of a_ref
        r_c = 1.25 * self.a_max + 2.0 * fem.h
        self.r_touch = condensed_radius(case, self.a_ref, r_c)
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
        core = block.factorised_block(self.spec, self.a_ref, comps,
                                      (case.a.nu, case.b.nu), log,
                                      companion=self.sym.companion, r_touch=self.r_touch)
        self.core = core
        self.mesh, self.space = core.mesh, core.space
        self.fixed, self.free = core.fixed, core.free
        self.surface, self.top, self.cidx = core.surface, core.top, core.cidx
        self.factor, self.stiffness = core.factor, core.stiffness
        C1 = core.C1
        Rz = np.where(self.surface.dof_comp[self.cidx] == 2, -1.0, 1.0)
        self.compliance = RelativeCompliance(C1[case.a.nu], C1[case.b.nu], Rz, case.a.E,
                                             case.b.E)
        self.law = self._law()
        self.timings = {**core.timings, "reused": core.uses > 1,
                        "setup_s": time.perf_counter() - t0}

    @cached_property
    def Crel(self) -> np.ndarray:
        """The condensed relative compliance whole, formed on first use: only the augmented
        solve (``fem.contact = "augmented"``) needs it; the semi-smooth solve works on
        :attr:`compliance` (:mod:`fem_reference.contact.relative`)."""
        return self.compliance.dense()

    @cached_property
    def Krel(self) -> np.ndarray:
        """The condensed relative stiffness ``C_rel⁻¹``, formed on first use: only the
        augmented solve (``fem.contact = "augmented"``) needs it; the semi-smooth solve
        works on the compliance."""
        K = la.cho_solve(la.cho_factor(self.Crel), np.eye(self.Crel.shape[0]))
        return 0.5 * (K + K.T)

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
        if self.law_mode == "frictionless":  # with friction: nothing slips (Law.stuck)
            return Law(k_n=k_n, stuck=case.friction.mu1 > 0.0)
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
        if not block.cache_enabled():
            self.core.release()
