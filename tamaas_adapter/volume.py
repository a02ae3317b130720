"""Subsurface stresses by Tamaas's volume operators: its Boussinesq–Cerruti gradient
(``boussinesq_gradient``: the strain under the surface tractions) and Hooke's law
(``hooke``), on a ``volume_2d`` model of the case's layers z = 0 … ``stress.depth``.

Tamaas's volume operators are periodic in the surface plane.  For the non-periodic
solver the tractions are set on a domain padded with zeros (:func:`padding`) to a period
of at least :data:`PERIOD_PER_WIDTH` times the loaded width, and their mean is removed:
the mean traction of a periodic half-space is a uniform stress state (σ_zz = −p̄ at
every depth) that a finite load does not cause, and removing it removes the images'
leading term (the measured effect of both: benchmarks/README.md, "Tamaas through the
gates").  For ``tamaas_periodic`` the stresses are the periodic problem's own, on the
case grid.

The stresses of the reported body (``stress.body``, its ν) are those of the half-space
under the traction that body's surface carries (:data:`FRAME`).
"""

from __future__ import annotations

import math

import numpy as np

from cases.model import Case
from cases.result import Plane, von_mises

#: the order of the six components of Tamaas's symmetric tensors, whose shear components
#: are stored in Mandel's form (√2 σ_ij)
MANDEL = (("sxx", 1.0), ("syy", 1.0), ("szz", 1.0), ("sxy", 2**-0.5), ("sxz", 2**-0.5),
          ("syz", 2**-0.5))

#: body -> the sign of the tangential traction its surface carries (body a carries
#: (p_x, p_y), body b the opposite); Tamaas's stresses are then the reported body's own.
#: Order, Mandel factor and signs checked against Hamilton's sliding sphere on both
#: bodies at slide angles 0 and 60° (tests/test_tamaas_adapter.py)
FRAME = {"a": 1.0, "b": -1.0}


#: the smallest period of the padded domain, in loaded widths (module doc)
PERIOD_PER_WIDTH = 8.0


def grids_for(case: Case, width: float) -> int:
    """How many case grids the padded domain spans along each side (at least 2) for a
    loaded ``width`` [mm]: its period is at least :data:`PERIOD_PER_WIDTH` widths."""
    g = case.grid
    return max(2, math.ceil(PERIOD_PER_WIDTH * width / min(g.Lx, g.Ly) - 1e-9))


def padding(case: Case, p_n: np.ndarray) -> int:
    """:func:`grids_for` the width of the cells ``p_n`` loads."""
    g = case.grid
    rows, cols = np.nonzero(p_n > 0)
    if rows.size == 0:
        return 2
    return grids_for(case, max((np.ptp(rows) + 1) * g.dx, (np.ptp(cols) + 1) * g.dy))


def stress_block(case: Case, p_x: np.ndarray, p_y: np.ndarray, p_n: np.ndarray,
                 periodic: bool) -> dict[str, np.ndarray]:
    """The six stress components [MPa] of the reported body on (nz, nx, ny) points: the
    case's layers under its cell centres."""
    import tamaas as tm

    g, st = case.grid, case.stress
    sign = FRAME[st.body]
    pad = 1 if periodic else padding(case, p_n)
    shape = (pad * g.nx, pad * g.ny)
    model = tm.ModelFactory.createModel(
        tm.model_type.volume_2d, [st.depth, pad * g.Lx, pad * g.Ly], [st.nz, *shape])
    nu = (case.a if st.body == "a" else case.b).nu
    model.E, model.nu = 1.0, nu  # the stresses under given tractions depend on nu only
    tm.ModelFactory.registerVolumeOperators(model)
    traction = np.zeros((*shape, 3))
    traction[:g.nx, :g.ny] = np.stack([sign * p_x, sign * p_y, p_n], axis=-1)
    if not periodic:
        traction -= traction.mean(axis=(0, 1))
    strain = np.zeros((st.nz, *shape, 6))
    model.operators["boussinesq_gradient"](traction, strain)
    stress = np.zeros_like(strain)
    model.operators["hooke"](strain, stress)
    return {name: factor * stress[:, :g.nx, :g.ny, k] for k, (name, factor) in enumerate(MANDEL)}


def planes(case: Case, block: dict[str, np.ndarray]) -> dict[str, Plane]:
    """The xz and yz planes through the case's plane centre, with σ_VM."""
    g, z = case.grid, case.stress.z
    i0, j0 = g.nearest_cell(case.stress.x0, case.stress.y0)
    out = {}
    for name, s, cut in (("xz", g.x, np.s_[:, :, j0]), ("yz", g.y, np.s_[:, i0, :])):
        fields = {k: np.ascontiguousarray(v[cut].T) for k, v in block.items()}
        fields["vm"] = von_mises(*(fields[k] for k in ("sxx", "syy", "szz", "sxy", "sxz",
                                                       "syz")))
        out[name] = Plane(s=s.copy(), z=z.copy(), fields=fields)
    return out
