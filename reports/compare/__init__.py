"""Sampling onto common points, metrics, cycles, maxima and the one verdict. Its public
face is the modules the other rooms import (``__all__``;
``tests/test_suite_public_api.py`` keeps it true); the others are its own."""

__all__ = [
    "metrics",
    "point",
    "sampling",
    "verdict",
]
