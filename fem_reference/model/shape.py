"""What a case asks of the FE model: its length unit, the sliding direction, the wear
norms of the bodies (Eq. 21), the largest contact radius to mesh for, and the block's
symmetry — a quarter, a half (with or without an antisymmetric companion, the module doc of
:mod:`fem_reference.model.fem_model`) or the full block."""

from __future__ import annotations

import math

import numpy as np

from cases.model import Case

from ..contact.laws import axes_tensor, norm_with


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


def mesh_reach(case: Case, a_ref: float) -> float:
    """The largest contact radius the FE contact zone must hold during the run, in units
    of ``a_ref`` (an upper estimate for the mesh, unlike the case's own
    :attr:`cases.model.Case.expected_radius`, which is Hertz's or the worn pin's radius).

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


def touch_bound(case: Case, a_ref: float) -> float | None:
    """The radius no point of the surface can touch at, in units of ``a_ref``, where the
    case fixes one: under a held approach δ between identical materials, the rigid
    overlap √(2 R δ).  Outside it the gap starts positive (r²/2R > δ), the pressure's
    normal displacements only open it (Boussinesq's, positive), wear only removes
    material, and identical materials' tangential tractions move no surface normally
    (Dundurs' β = 0).  None where the reach is an estimate (:func:`mesh_reach`)."""
    if case.load.P is not None or not case.identical_materials:
        return None
    return math.sqrt(2.0 * case.R * case.load.approach) / a_ref


#: elements of the contact surface between the touch bound and the edge of the condensed
#: zone: the run stops where the contact comes within 1.5 of the edge
#: (:func:`fem_reference.loading.solve_increment`), 1.5 elements beyond the bound
TOUCH_MARGIN = 3.0


def condensed_radius(case: Case, a_ref: float, r_c: float) -> float:
    """The radius of the condensed contact zone in units of ``a_ref``: the refined zone's
    ``r_c``, or :data:`TOUCH_MARGIN` surface elements beyond the :func:`touch_bound`
    where that is nearer (the nodes farther out can never touch)."""
    bound = touch_bound(case, a_ref)
    if bound is None:
        return r_c
    return min(r_c, bound + TOUCH_MARGIN * case.fem.h_contact)


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
