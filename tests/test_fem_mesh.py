"""The FEM's contact-zone elements against the stress reach the gate allows them
(``reports.registry.discretisation.FEM_ELEMENT_DIAMETER``): the planes' edge band of an FEM pair
is as wide as the longest element that can touch the contact edge, because the FEM's
stress at a point is the linear field of the element holding it."""

from __future__ import annotations

import numpy as np
import pytest

from fem_reference.model.mesh import MeshSpec, build_points
from reports.registry.discretisation import FEM_ELEMENT_DIAMETER

_PAIRS = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]


def _surface_diameters(points: np.ndarray, tets: np.ndarray, r: float) -> np.ndarray:
    """The longest edge of every element with a vertex on the contact surface (z = 0)
    within radius ``r``."""
    on_top = (np.abs(points[2]) < 1e-12) & (np.hypot(points[0], points[1]) < r)
    keep = on_top[tets].any(axis=0)
    P = points[:, tets[:, keep]]
    return np.max([np.linalg.norm(P[:, i] - P[:, j], axis=0) for i, j in _PAIRS], axis=0)


@pytest.mark.parametrize("shape, h, h_surface, r_fine", [("quarter", 0.125, None, None),
                                                         ("full", 0.125, 0.08, 1.25),
                                                         ("half", 0.125, 0.0625, None)])
def test_contact_elements_are_within_the_reach(shape, h, h_surface, r_fine):
    """Every element touching the contact surface where its size is h_contact (within
    r_fine) is at most FEM_ELEMENT_DIAMETER times h_contact long, and the bound is not
    loose: the longest is over 2.1 (the band is a diameter, not a size)."""
    spec = MeshSpec(shape, 6.0, 6.0, h, 1.5, 1.5, h_max=1.5, r_fine=r_fine,
                    h_surface=h_surface)
    points, tets = build_points(spec)
    h_contact = h if h_surface is None else h_surface
    d = _surface_diameters(points, tets, spec.r_fine or spec.r_ref) / h_contact
    assert d.size > 100
    assert d.max() <= FEM_ELEMENT_DIAMETER, d.max()
    assert d.max() > 2.1, d.max()
