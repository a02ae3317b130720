"""Solver records, error budgets, tolerances and the errors the CLI reports. Its public
face is the modules the other rooms import (``__all__``;
``tests/test_suite_public_api.py`` keeps it true); the others are its own."""

__all__ = [
    "errors",
    "pairs",
    "record",
    "resolution",
    "solvers",
    "tolerances",
]
