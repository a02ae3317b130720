"""Planning and running cases, sweeps, thresholds and the article's runs, serially or on a
Dask cluster. Its public face is the modules the other rooms import (``__all__``;
``tests/test_suite_public_api.py`` keeps it true); the others are its own."""

__all__ = [
    "article_sources",
    "cluster",
    "plan",
    "runner",
    "sweep",
    "threshold",
    "threshold_table",
    "units",
]
