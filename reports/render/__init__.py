"""What reads a results directory for people: HTML report, plots, gate, baselines. Its
public face is the modules the other rooms import (``__all__``;
``tests/test_suite_public_api.py`` keeps it true); the others are its own."""

__all__ = [
    "article_page",
    "gate",
    "pages",
    "plots",
]
