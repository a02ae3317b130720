"""Grid and jump studies, the resolution probe, numerical uncertainty, events and the
article's claims.  A study of a run is one subclass of :class:`reports.studies.study.Study`, its
instances listed in :mod:`reports.studies.registry`.  Its public face is the modules the
other rooms import (``__all__``; ``tests/test_suite_public_api.py`` keeps it true); the
others are its own."""

__all__ = [
    "claims",
    "events",
    "gridstudy",
    "jumpstudy",
    "probe",
    "registry",
    "study",
    "three_level",
]
