"""Shared fixtures: bundled cases and the Hertz scales of a case.

The functions behind them, and the convergence assertion ``assert_converges``, live in
the plain module ``tests/vv_testing.py`` (importable by name from every test module, also
inside module-level cached functions that fixtures cannot reach).
"""

from __future__ import annotations

import os

import pytest
from threadpoolctl import threadpool_limits
from vv_testing import load_bundled

#: under pytest-xdist (pyproject.toml: two workers on two cores) each worker's BLAS runs
#: on one thread, so that the workers do not contend for the cores
_ONE_BLAS_THREAD = threadpool_limits(1) if os.environ.get("PYTEST_XDIST_WORKER") else None


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The modules marked ``long`` (the quick chain's and the quick article run's) first,
    in their collected order (a stable sort): under ``--dist loadfile
    --no-loadscope-reorder`` the two workers start on them and share the short modules
    at the end, instead of one of them starting a long module when the other has little
    left."""
    items.sort(key=lambda item: item.get_closest_marker("long") is None)


@pytest.fixture(scope="session")
def bundled_case():
    """``bundled_case(name, quick=False, overrides=None, index=0) -> Case``: a bundled case
    file through :func:`cases.loader.load_case` (unknown names fail)."""
    return load_bundled


@pytest.fixture(scope="session")
def hertz_case():
    """The article's Hertz case (``cases/hertz.toml``, full size)."""
    return load_bundled("hertz")


@pytest.fixture(scope="session")
def hertz_scales(hertz_case):
    """(a0 [mm], p0 [MPa]) of the article's Hertz case: ``Case.hertz_scales``."""
    return hertz_case.hertz_scales
