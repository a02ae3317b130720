"""The Alart–Curnier functions of the nodal contact problem and their merit: the equations
the semi-smooth Newton solve zeroes (:mod:`fem_reference.contact.semismooth`, whose module
doc states them).  A :class:`Problem` holds what one solve keeps fixed; a :class:`State`
the unknowns; :class:`Laws` the functions at a state and the sets they define."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .compliance import NodalCompliance
from .control import Control, unknowns
from .laws import Law, Points, norm_with


@dataclass(frozen=True)
class Problem:
    """One contact solve: the nodal compliance ``op``, the ``law``, the points ``pts``
    (their tractions are the start and, on return, the solution), the control ``ctrl``,
    the wear compliance ``cw`` of each node (Eq. 23), the control unknowns ``extra``
    (:func:`fem_reference.contact.control.unknowns`), the components the surface cannot
    move (``dead``), the augmentation parameters ``r`` and ``r_t`` (they set the
    iteration's path, not its solution) and the tolerance."""

    op: NodalCompliance
    law: Law
    pts: Points
    ctrl: Control
    cw: np.ndarray
    extra: list
    dead: np.ndarray
    r: np.ndarray
    r_t: np.ndarray
    tol: float


def problem(op: NodalCompliance, law: Law, pts: Points, ctrl: Control,
            cw: float | np.ndarray, tol: float) -> Problem:
    """The :class:`Problem` of a solve: ``r`` the nodal normal stiffness, softened by the
    wear compliance; ``r_t`` the tangential one in the metric of the friction ellipse."""
    n = pts.n
    cw = np.broadcast_to(np.asarray(cw, dtype=float), (n,)).copy()
    extra = unknowns(ctrl)
    diag = op.diagonal()  # self-compliance of each node [mm/MPa]
    # components the surface cannot move (tangential on a symmetry plane, or every
    # tangential one of a model without tangential coupling): a stick condition
    # there holds whatever the traction, which symmetry sets to 0
    # (:func:`fem_reference.contact.newton_system.newton_step`)
    dead = diag <= 1e-12 * diag.max()
    # r: the nodal stiffness, softened by the wear compliance like the penalty law's
    # (k_n / (1 + k_n c_w)): ⟨λ_n − r g̃_n⟩ then holds a pressed node's λ_n at g_n = 0
    r = 1.0 / np.where(dead[2], np.inf, diag[2])
    r = r / (1.0 + r * cw)
    mu2 = float(np.linalg.eigvalsh(law.M2).max()) if law.mode != "frictionless" else 1.0
    c_t = diag[:2].max(axis=0)
    c_t = np.where(c_t > 0, c_t, diag[2])
    r_t = 1.0 / (c_t * max(mu2, 1e-300))
    return Problem(op=op, law=law, pts=pts, ctrl=ctrl, cw=cw, extra=extra, dead=dead, r=r,
                   r_t=r_t, tol=tol)


@dataclass
class State:
    """The unknowns: the tractions λ (3, n) (λ_x, λ_y, λ_n), the approach δ and the rigid
    tangential shift D."""

    lam: np.ndarray  # (3, n): λ_x, λ_y, λ_n
    delta: float
    D: np.ndarray


@dataclass
class Laws:
    """The Alart–Curnier functions at one state (module doc) and what their Newton step
    needs."""

    F: np.ndarray  # (3, n) [MPa]
    Fe: np.ndarray  # control residuals
    gn: np.ndarray
    gt: np.ndarray  # (n, 2)
    active: np.ndarray
    stick: np.ndarray
    slip: np.ndarray
    rho: np.ndarray
    tstar: np.ndarray  # (n, 2)
    nrm: np.ndarray


def laws(p: Problem, s: State) -> Laws:
    """The Alart–Curnier functions at state ``s`` (module doc) and the sets they define."""
    law, pts, ctrl = p.law, p.pts, p.ctrl
    lam = s.lam
    d = displacements(p, lam)
    gn = pts.h + pts.wear_a + pts.wear_b - s.delta + d[2]
    gt = s.D[None, :] + d[:2].T
    aug = lam[2] - p.r * (gn + p.cw * lam[2])
    active = (aug > 0.0) & pts.inside
    rho = np.where(active, aug, 0.0)
    F = np.empty_like(lam)
    F[2] = lam[2] - rho
    n = pts.n
    tstar = np.zeros((n, 2))
    nrm = np.zeros(n)
    stick = np.zeros(n, bool)
    slip = np.zeros(n, bool)
    if law.mode == "frictionless":
        F[:2] = lam[:2]
    elif law.mode == "sliding":  # λ_t = c λ_n where pressed (= c ρ at the solution)
        F[:2] = lam[:2] - law.slide_traction[:, None] * np.where(active, lam[2], 0.0)
        slip = active
    else:
        tstar = lam[:2].T - p.r_t[:, None] * ((gt - pts.gt_old) @ law.M2.T)
        nrm = norm_with(law.M2inv, tstar)
        slip = active & (nrm > rho)
        stick = active & ~slip
        proj = np.where(stick[:, None], tstar, 0.0)
        proj[slip] = (rho[slip] / nrm[slip])[:, None] * tstar[slip]
        F[:2] = lam[:2] - proj.T
    w, sym = pts.w, ctrl.sym
    Fe = []
    for kind, c in p.extra:
        if kind == "delta":
            Fe.append(w @ lam[2] - ctrl.P / sym)
        elif kind == "approach":
            Fe.append(s.delta + ctrl.compliance * sym * (w @ lam[2]) - ctrl.approach)
        elif kind == "shift":
            Fe.append(s.D[c] + ctrl.compliance_t * sym * (w @ lam[c]) - ctrl.shift[c])
        else:
            Fe.append(w @ lam[c] - ctrl.Q[c] / sym)
    return Laws(F=F, Fe=np.asarray(Fe, float), gn=gn, gt=gt, active=active,
                 stick=stick, slip=slip, rho=rho, tstar=tstar, nrm=nrm)


def displacements(p: Problem, lam: np.ndarray) -> np.ndarray:
    """``HW λ`` (3, n) (:meth:`NodalCompliance.apply`)."""
    return p.op.apply(lam)


def merit(p: Problem, s: State, L: Laws) -> float:
    """The largest function over the largest pressure; a control's over its scale
    (the load, or the nodal load of the largest pressure; the approach; the shift)."""
    ctrl, w = p.ctrl, p.pts.w
    top = max(float(s.lam[2].max(initial=0.0)), float(L.rho.max(initial=0.0)), 1e-300)
    load = max(abs(ctrl.P or 0.0), *(abs(q or 0.0) for q in ctrl.Q)) / ctrl.sym
    ls = load if load > 0 else top * float(w.sum())
    out = float(np.abs(L.F).max(initial=0.0)) / top
    for (kind, c), f in zip(p.extra, L.Fe, strict=True):
        if kind == "approach":
            scale = abs(ctrl.approach)
        elif kind == "shift":
            scale = max(abs(ctrl.shift[c]), abs(ctrl.compliance_t) * ctrl.sym * ls, 1e-300)
        else:
            scale = ls
        out = max(out, abs(f) / scale)
    return out
