"""Whether the location of the σ_VM maximum is a determined quantity.

Where the σ_VM field has two separate local maxima of nearly the same value (the
subsurface Hertzian maximum and the surface maximum at the trailing edge of a sliding
contact near the friction coefficient at which the maximum moves to the surface), the
location of the global maximum jumps from one to the other under an arbitrarily small
change of the field.  Two solvers whose σ_VM values agree to within the tolerance of
``vm_max`` can then place the maximum a contact radius apart, and neither is wrong.  The
location is compared and shown but not gated when, for either solver, a *rival* local
maximum — one farther from the global maximum than the location tolerance — comes
within the ``vm_max`` tolerance of it (:func:`ambiguity`); the values ``vm_max`` and the
planes stay gated.  Measured on ``sliding_friction`` at μ = 0.35 (81² grid): the closed
form's maximum lies on the surface at x = −0.91 a0 (149.6 MPa), the half-space solver's
0.40 a0 deep (147.5 MPa), 1.4 a0 apart.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import ndimage

from cases.result import StepResult

Point = tuple[float, float, float, float]  # (σ_VM, x, y, z)


def local_maxima(step: StepResult, x0: float, y0: float) -> list[Point]:
    """Every local maximum of σ_VM on the step's planes (a sample not smaller than its
    eight neighbours; ``xz`` lies at y = ``y0``, ``yz`` at x = ``x0``)."""
    out: list[Point] = []
    for name, plane in step.planes.items():
        vm = plane.fields.get("vm")
        if vm is None or vm.size == 0 or not np.isfinite(vm).all():
            continue
        peak = vm >= ndimage.maximum_filter(vm, size=3, mode="nearest")
        for i, k in zip(*np.nonzero(peak), strict=True):
            s, z = float(plane.s[i]), float(plane.z[k])
            out.append((float(vm[i, k]), s, y0, z) if name == "xz" else
                       (float(vm[i, k]), x0, s, z))
    return out


def rival(step: StepResult, at: Point, distance: float, x0: float, y0: float
          ) -> Point | None:
    """The largest local maximum farther than ``distance`` from the maximum ``at``."""
    far = [p for p in local_maxima(step, x0, y0)
           if math.dist(p[1:], at[1:]) > distance]
    return max(far, default=None)


def ambiguity(steps: dict[str, StepResult], at: dict[str, Point], distance: float,
              rel: float, x0: float, y0: float) -> str:
    """'' when every solver's σ_VM maximum is unique to within ``rel`` beyond
    ``distance``; else a note naming the solver and both maxima."""
    notes = []
    for name, step in steps.items():
        top = at[name]
        other = rival(step, top, distance, x0, y0)
        if other is None or not math.isfinite(top[0]) or top[0] <= 0:
            continue
        gap = (top[0] - other[0]) / top[0]
        if gap <= rel:
            notes.append(
                f"{name}: σ_VM maxima {top[0]:.5g} MPa at {_xyz(top)} and {other[0]:.5g} at "
                f"{_xyz(other)} mm differ by {100 * gap:.2g} %, within the vm_max tolerance "
                f"{rel:g}: where the maximum lies is not determined")
    return "; ".join(notes)


def _xyz(p: Point) -> str:
    return "(" + ", ".join(f"{v:.4g}" for v in p[1:]) + ")"
