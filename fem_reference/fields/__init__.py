"""What is read off a solved model: the surface sample points (:mod:`.sampling`), the
contact zone (:mod:`.contact_zone`), stresses recovered from the P2 elements
(:mod:`.stresses`), the subsurface stress planes (:mod:`.planes`) and the ``.vtu`` files
(:mod:`.vtu`).

Imports :mod:`fem_reference.model`, never :mod:`fem_reference.contact`.

Its public face: the modules the rest of the package imports (``__all__``,
``tests/test_suite_public_api.py``)."""

__all__ = [
    "contact_zone",
    "planes",
    "sampling",
    "stresses",
    "vtu",
]
