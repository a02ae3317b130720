"""The contact solve on the condensed surface: the friction and wear laws at the nodes
(:mod:`.laws`), the semi-smooth Newton solve (:mod:`.semismooth`, the default) and the
augmented Lagrangian on a penalty Newton solve (:mod:`.augmented`), what a solve is asked
and returns (:mod:`.control`), the nodal compliance (:mod:`.compliance`), the kept factors
and their low-rank updates (:mod:`.kept_factors`, :mod:`.stiffened`) and the
single-threaded BLAS they run under (:mod:`.threads`).

The ground room of the package: it imports no other room.

Its public face: the modules the rest of the package imports (``__all__``,
``tests/test_suite_public_api.py``)."""

__all__ = [
    "augmented",
    "compliance",
    "control",
    "kept_factors",
    "laws",
    "relative",
    "semismooth",
    "stiffened",
]
