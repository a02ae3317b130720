"""The FEM's false-alarm rate on cases nobody bundled (issue 58, point 4): the ic–fem rows
are the only check of the cases no closed form covers, so a correct pair must pass the
gate on valid cases of those kinds drawn at random — dissimilar frictional partial slip,
oblique partial slip on rectangular grids, orthotropic sliding at an angle, the approach
held with the planes off the centre, worn fretting (:func:`case_generator.fem_case`) —
run through ``ic,fem,analytic`` with the default tolerances, and the gate must have gated
ic–fem rows (a gate that passes by gating nothing would hide every defect).  Full tier:
each draw runs the FEM at its default mesh; the rate and the run time are in
``benchmarks/README.md`` ("False alarms")."""

from __future__ import annotations

import functools
import re

import pandas as pd
import pytest
from case_generator import FEM_KINDS, user_case
from hypothesis import HealthCheck, given, settings

from reports.cli import main

#: draws of the full tier (issue 58: at least 20), as many of each kind
DRAWS = 20


def _physics(text: str) -> tuple:
    """What makes two draws different cases: R, P (or the approach) and the moduli to
    two significant digits (Hypothesis' derandomised generator also mutates its earlier
    examples, which differ in a tolerance or a description only)."""
    return tuple(f"{float(v):.2g}" for v in re.findall(
        r"^(?:R|P|approach|E) = ([-\d.e+]+)$", text, flags=re.M))


def _examples(kind: str, count: int) -> list[str]:
    """``count`` examples of ``kind`` by Hypothesis' derandomised generator."""
    texts: list[str] = []

    @settings(max_examples=count, derandomize=True, database=None, deadline=None)
    @given(text=user_case(kinds=(kind,), fem=True))
    def collect(text: str) -> None:
        texts.append(text)

    collect()
    return texts


@functools.lru_cache(maxsize=1)
def draws(count: int = DRAWS) -> tuple[str, ...]:
    """``count`` case files, the same number of each kind of
    :data:`case_generator.FEM_KINDS`, drawn by :func:`case_generator.fem_case`'s
    strategy with Hypothesis' derandomised generator (the same draws on every run), kept
    where their physics differs from every earlier one (:func:`_physics`) and taken
    evenly spread over the sequence (its first examples sit on the ranges' bounds:
    E = 70 GPa, P = 1 N).  Built once, when a test first asks."""
    out: list[str] = []
    per = count // len(FEM_KINDS)
    for kind in FEM_KINDS:
        seen: set[tuple] = set()
        kept = [t for t in _examples(kind, 10 * count)
                if not (_physics(t) in seen or seen.add(_physics(t)))]
        out += [kept[(k + 1) * len(kept) // (per + 1)] for k in range(per)]
    return tuple(out)


@pytest.mark.full
@pytest.mark.parametrize("index", range(DRAWS), ids=lambda i: f"draw{i:02d}")
def test_the_fem_passes_the_gate_on_cases_no_closed_form_covers(index, tmp_path):
    """Each draw a test, reported, not shrunk (a FEM run is a minute)."""
    text = draws()[index]
    gated = ic_fem_gated(text, tmp_path)
    assert gated["quantity"].isin(["p_n", "P", "p_max"]).any(), text


def ic_fem_gated(text: str, tmp) -> pd.DataFrame:
    """The gated ic–fem rows of case file ``text`` run through ``ic,fem,analytic`` in
    ``tmp``, the gate passing."""
    path = tmp / "user.toml"
    path.write_text(text)
    out = tmp / "res"
    assert main(["run", str(path), "--solver", "ic,fem,analytic", "--quick",
                 "--no-progress", "--out", str(out)]) == 0, text
    assert main(["gate", "--out", str(out)]) == 0, text
    metrics = pd.read_csv(out / "user" / "metrics.csv")
    return metrics[(metrics["status"] == "gated") & (metrics["pair"] == "ic-fem")]


#: draws of the Dundurs range with the FEM (issue 73: at least 12)
DUNDURS_DRAWS = 12


@functools.lru_cache(maxsize=1)
def dundurs_draws(count: int = DUNDURS_DRAWS) -> tuple[str, ...]:
    """``count`` frictional contacts of dissimilar pairs across Dundurs' range
    (:func:`case_generator.compression_case`: Spence's compression, a quarter of them
    with a tangential load after it), kept and spread as :func:`draws` does."""
    from case_generator import compression_case

    texts: list[str] = []

    @settings(max_examples=10 * count, derandomize=True, database=None, deadline=None,
              suppress_health_check=list(HealthCheck))
    @given(text=compression_case())
    def collect(text: str) -> None:
        texts.append(text)

    collect()
    seen: set[tuple] = set()
    kept = [t for t in texts if not (_physics(t) in seen or seen.add(_physics(t)))]
    return tuple(kept[(k + 1) * len(kept) // (count + 1)] for k in range(count))


@pytest.mark.full
@pytest.mark.parametrize("index", range(DUNDURS_DRAWS), ids=lambda i: f"draw{i:02d}")
def test_the_fem_passes_the_gate_across_the_dundurs_range(index, tmp_path):
    """Issue 73: the half-space solver, the FEM and the coupled self-similar solution
    (where there is no tangential load) agree within the gate on frictional contacts of
    dissimilar pairs across Dundurs' range, ic–fem rows of the pressure gated."""
    text = dundurs_draws()[index]
    assert ic_fem_gated(text, tmp_path)["quantity"].isin(["p_n", "P"]).any(), text
