"""Exact symmetries of the contact problem: a case transformed, and a result of the
transformed case mapped back onto the original one (metamorphic relations, the oracles of
the orthotropic laws where no closed form exists; ``reports/registry/relations.py``).

- ``axes_turned_90``: β → β + 90° with μ1 ↔ μ2 and i1 ↔ i2 of both bodies names the same
  axes the other way round: the same problem, the same result.
- ``axes_turned_180``: β → β + 180° turns e1 and e2 into −e1 and −e2; the friction
  ellipse and the wear law are even: the same result.
- ``mirrored``: the mirror y → −y (β → −β, the load direction and the tangential load or
  shift mirrored, the planes' centre too) mirrors the result: a field f(x, y) becomes
  f(x, −y), its y component and σ_xy, σ_yz change sign.
- ``turned``: the load direction and the friction axes turned together by φ about z turn
  the result: on a grid that does not turn with it, only the invariants are compared —
  the loads' magnitudes (the load vectors turned back), the pressure's peak, the areas, the
  wear's maximum and volume, a fretting cycle's loop and energy.  Every relation above that
  is exact on a square grid is blind to a sense of β turned the wrong way (the ellipse is
  even); this one, at a non-right φ, is not.

Every transform keeps the grid; mirrored and turned results are compared on it.
"""

from __future__ import annotations

import copy
import dataclasses
import math

import numpy as np

from cases.model import Case
from cases.result import RunResult

#: the angle of :func:`turned` [deg]: not a multiple of 90, where the grid would turn too
TURN = 30.0
#: scalars that do not change when the problem turns about z
INVARIANT_SCALARS = ("step", "s", "cycle", "P", "contact_area", "stick_area", "slip_area",
                     "p_max", "w_max", "wear_volume", "iterations", "converged", "wall_s")


def _rotate(vx: float | None, vy: float | None, phi: float) -> tuple[float | None, ...]:
    if vx is None and vy is None:
        return vx, vy
    c, s = math.cos(math.radians(phi)), math.sin(math.radians(phi))
    x, y = vx or 0.0, vy or 0.0
    return c * x - s * y, s * x + c * y


def axes_turned_90(case: Case) -> Case:
    f = case.friction
    return case.with_changes(
        friction=dataclasses.replace(f, beta=f.beta + 90.0, mu1=f.mu2, mu2=f.mu1),
        a=dataclasses.replace(case.a, i1=case.a.i2, i2=case.a.i1),
        b=dataclasses.replace(case.b, i1=case.b.i2, i2=case.b.i1))


def axes_turned_180(case: Case) -> Case:
    f = case.friction
    return case.with_changes(friction=dataclasses.replace(f, beta=f.beta + 180.0))


def mirrored(case: Case) -> Case:
    ld, f, st = case.load, case.friction, case.stress
    load = dataclasses.replace(
        ld, slide_angle=-ld.slide_angle, Qy=None if ld.Qy is None else -ld.Qy,
        shift_y=None if ld.shift_y is None else -ld.shift_y)
    # the planes of the mirrored case cross at the mirror of the case's own centre (on an
    # even grid the cell centre nearest to -y0 need not mirror the one nearest to y0)
    x0, y0 = case.plane_centre
    return case.with_changes(load=load, friction=dataclasses.replace(f, beta=-f.beta),
                             stress=dataclasses.replace(st, x0=x0, y0=-y0))


def turned(case: Case, phi: float = TURN) -> Case:
    ld, f = case.load, case.friction
    Qx, Qy = _rotate(ld.Qx, ld.Qy, phi)
    sx, sy = _rotate(ld.shift_x, ld.shift_y, phi)
    load = dataclasses.replace(ld, slide_angle=ld.slide_angle + phi, Qx=Qx, Qy=Qy,
                               shift_x=sx, shift_y=sy)
    return case.with_changes(load=load, friction=dataclasses.replace(f, beta=f.beta + phi))


# ---------------------------------------------------------------- results mapped back

_MIRROR_ODD_SURFACE = ("p_y", "slip_y", "g_y")
_MIRROR_ODD_STRESS = ("sxy", "syz")
_MIRROR_ODD_SCALARS = ("Qy", "shift_y", "vm_max_y", "y0")


def same(result: RunResult, phi: float = 0.0) -> RunResult:
    """The result of an exact relation: unchanged."""
    return result


def mirror_back(result: RunResult, phi: float = 0.0) -> RunResult:
    """A result of :func:`mirrored` mirrored back (module doc)."""
    out = copy.deepcopy(result)
    for st in out.steps:
        st.surface = {k: _flipped(v[:, ::-1], k in _MIRROR_ODD_SURFACE)
                      for k, v in st.surface.items()}
        for name, plane in st.planes.items():
            flip = slice(None, None, -1) if name == "yz" else slice(None)
            plane.fields = {k: _flipped(v[flip], k in _MIRROR_ODD_STRESS)
                            for k, v in plane.fields.items()}
        for key in _MIRROR_ODD_SCALARS:
            if isinstance(st.scalars.get(key), float):
                st.scalars[key] = -st.scalars[key]
    for table in out.tables.values():
        if "Qy" in table:
            table["Qy"] = -np.asarray(table["Qy"])
    return out


def _flipped(values: np.ndarray, odd: bool) -> np.ndarray:
    """A mirrored field, its sign changed where it is odd in y (dtype kept)."""
    values = np.array(values)
    return -values if odd else values


def turn_back(result: RunResult, phi: float = TURN) -> RunResult:
    """A result of :func:`turned` by ``phi`` turned back: its invariants only (module
    doc), the load vectors turned by −φ."""
    out = copy.deepcopy(result)
    for st in out.steps:
        qx, qy = _rotate(st.scalars.get("Qx"), st.scalars.get("Qy"), -phi)
        st.scalars = {k: v for k, v in st.scalars.items() if k in INVARIANT_SCALARS}
        st.scalars.update(Qx=qx, Qy=qy)
        st.surface, st.planes = {}, {}
    for table in out.tables.values():
        if "Qx" in table and "Qy" in table:
            table["Qx"], table["Qy"] = _rotate_arrays(table["Qx"], table["Qy"], -phi)
    return out


def _rotate_arrays(vx, vy, phi: float) -> tuple[np.ndarray, np.ndarray]:
    c, s = math.cos(math.radians(phi)), math.sin(math.radians(phi))
    vx, vy = np.asarray(vx, float), np.asarray(vy, float)
    return c * vx - s * vy, s * vx + c * vy
