"""One face for plugins (issue 76, point 3): ``reports.plugin`` holds every name a solver
plugin needs from the suite, each resolving to where it lives, and the bundled adapters
and the plugin example import nothing else of ``reports``; the face itself imports only
the registry and ``cases`` (its names are resolved when first used, so a plugin's record
can be built while the registry loads it)."""

from __future__ import annotations

import importlib
from pathlib import Path

import pytest
from test_suite_architecture import absolute_imports

import reports.plugin as face

ROOT = Path(__file__).resolve().parents[1]
PLUGINS = ["tamaas_adapter", "contactmechanics_adapter", "kratos_adapter",
           "calculix_adapter", "docs/examples/solver_plugin/hertz_example"]


@pytest.mark.parametrize("plugin", PLUGINS)
def test_a_bundled_plugin_imports_only_the_plugin_face(plugin):
    bad = [f"{path.relative_to(ROOT)}: {n}" for path, n in absolute_imports(ROOT / plugin)
           if n.split(".")[0] == "reports" and n != "reports.plugin"]
    assert bad == []


def test_every_name_of_the_face_resolves_where_it_lives():
    for name, home in face.HOMES.items():
        assert getattr(face, name) is getattr(importlib.import_module(home), name), name
        assert home.split(".")[0] == "cases" or home.startswith("reports.registry."), home
    assert sorted(face.__all__) == sorted(face.HOMES)
    with pytest.raises(AttributeError):
        face.no_such_name  # noqa: B018
