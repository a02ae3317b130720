"""The results directory: its file names, staging, manifest, writers and readers. Its
public face is the modules the other rooms import (``__all__``;
``tests/test_suite_public_api.py`` keeps it true); the others are its own."""

__all__ = [
    "event_table",
    "layout",
    "manifest",
    "readers",
    "results",
    "staging",
    "study_tables",
    "targets",
    "write",
]
