"""Grid and jump studies, the resolution probe, numerical uncertainty, events and the
article's claims. Its public face is the modules the other rooms import (``__all__``;
``tests/test_suite_public_api.py`` keeps it true); the others are its own."""

__all__ = [
    "claims",
    "convergence",
    "events",
    "gridstudy",
    "jumpstudy",
    "probe",
    "uncertainty",
]
