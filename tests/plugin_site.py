"""Installing a solver plugin in a test as pip would (no tests here): its ``.dist-info``
with the entry point beside its code on the path, and the registry loaded again as at
import — the built-in records, then the plugins found
(:mod:`reports.registry.plugins`)."""

from __future__ import annotations

import importlib
from pathlib import Path

import pytest

from reports.registry import plugins, solvers


def write_distribution(site: Path, dist: str, entry: str) -> None:
    """The ``.dist-info`` of the project ``dist`` (its name as in ``METADATA``) in
    ``site`` with the entry point line ``entry`` (``NAME = module:record``) of the solver
    group."""
    info = site / f"{dist.replace('-', '_')}-0.1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 0.1.0\n")
    (info / "entry_points.txt").write_text(f"[{plugins.GROUP}]\n{entry}\n")


def reload_registry(mp: pytest.MonkeyPatch, site: Path | None = None) -> list[str]:
    """``site`` put on the path (if given) and the plugins loaded again into the registry
    (undone with ``mp``); the lines of the plugins left out."""
    if site is not None:
        mp.syspath_prepend(str(site))
    importlib.invalidate_caches()
    builtin = {k: v for k, v in solvers.REGISTRY.items() if k not in solvers.PLUGINS}
    found, errors = plugins.load(builtin)
    mp.setattr(solvers, "REGISTRY", {**found, **builtin})
    mp.setattr(solvers, "PLUGINS", found)
    mp.setattr(solvers, "PLUGIN_ERRORS", errors)
    return errors
