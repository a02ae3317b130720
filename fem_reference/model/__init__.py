"""The finite-element model of a case: the gmsh mesh (:mod:`.mesh`), P2 elasticity
(:mod:`.elasticity`), the finite block and its factorisation (:mod:`.block`; the full
block's by its quarter's four mirror-parity problems, :mod:`.parity`), the contact
surface and its node-wise basis (:mod:`.surface`, :mod:`.nodal_basis`), the model's shape
and symmetry (:mod:`.shape`), the far-field compliance the block lacks
(:mod:`.far_field`) and the model that ties them to a case (:mod:`.fem_model`).

Imports only the laws of :mod:`fem_reference.contact` (the friction ellipse's norms).

Its public face: the modules the rest of the package imports (``__all__``,
``tests/test_suite_public_api.py``)."""

__all__ = [
    "elasticity",
    "far_field",
    "fem_model",
    "mesh",
    "nodal_basis",
    "shape",
]
