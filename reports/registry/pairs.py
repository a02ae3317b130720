"""Which solvers are compared: the pairs of the metric rows, and the names the
``[tolerances]`` table writes them by (``"ic-analytic.p_max"``)."""

from __future__ import annotations

import itertools
from collections.abc import Sequence

from reports.registry import solvers


def pairs(names: Sequence[str]) -> list[tuple[str, str]]:
    """All pairs in the given order, the second solver of a pair its reference; a
    metamorphic relation pairs with its base only."""
    def related(a: str, b: str) -> bool:
        ra, rb = solvers.record(a).base, solvers.record(b).base
        return (not ra and not rb) or ra == b or rb == a

    return [(a, b) for a, b in itertools.combinations(names, 2) if related(a, b)]


def pair_names(names: Sequence[str]) -> list[str]:
    """The pairs of :func:`pairs` as written in metric rows and tolerance keys: ``a-b``."""
    return [f"{a}-{b}" for a, b in pairs(names)]
