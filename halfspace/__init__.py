"""Influence-coefficient (boundary-element) solver on the elastic half-space.

Implements shared/paper/formulation.md: kernels (Eq. 5, 41), FFT influence products,
orthotropic frictional contact (Eq. 7-17, section 3.4), orthotropic Archard wear
(Eq. 18-23) and subsurface stresses (Eq. 32-34, Appendices A and C).
"""

from __future__ import annotations


def solve(case, progress: bool = False, on_output=None):
    """Solve a case (see :func:`halfspace.solver.solve`); solver name "ic".  ``on_output``
    receives each output step as soon as it is computed."""
    from .solver import solve as _solve

    return _solve(case, progress=progress, on_output=on_output)


__all__ = ["solve"]
