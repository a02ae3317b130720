"""What ``contact-vv threshold`` is asked (:mod:`reports.run.threshold`): the request, its
key, bracket and grids checked, and the columns of its rows."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from cases.schema import SCHEMA
from reports.registry import solvers
from reports.registry.errors import UserError
from reports.run.plan import Limits
from reports.studies.events import EventOptions

#: default (bracket, resolution) per parameter
DEFAULTS: dict[str, tuple[tuple[float, float], float]] = {
    **{f"friction.{k}": ((0.0, 1.0), 0.01) for k in ("mu", "mu1", "mu2")},
    "friction.beta": ((0.0, 90.0), 1.0)}
#: the case grid and one coarser by 1.5
DEFAULT_GRIDS = (1.0, 1.0 / 1.5)
COLUMNS = ["case", "point", "event", "param", "at", "quick", "solver", "grid", "refine",
           "cell_size", "threshold", "uncertainty", "resolution", "lo", "hi", "range_lo",
           "range_hi", "evaluations", "grid_shift", "status", "wall_s"]


@dataclass(frozen=True)
class Request:
    """What ``contact-vv threshold`` was asked for (module doc)."""

    case: str
    param: str
    event: str
    lo: float
    hi: float
    resolution: float
    grids: tuple[float, ...] = DEFAULT_GRIDS
    solvers: tuple[str, ...] = field(default_factory=lambda: tuple(
        s for s in solvers.names() if not solvers.record(s).base))
    quick: bool = False
    overrides: dict[str, Any] = field(default_factory=dict)
    options: EventOptions = EventOptions()
    limits: Limits | None = None
    explicit: bool = True  # the solvers were named (--solver): optional ones run too


def check_param(param: str) -> None:
    """UserError unless ``param`` is a real-valued dotted key of the case schema."""
    node: Any = SCHEMA
    for part in param.split("."):
        if not isinstance(node, dict) or part not in node or part in ("sweep", "quick"):
            raise UserError(f"--param {param!r}: not a case key (see cases/README.md)")
        node = node[part]
    if node is not float:
        raise UserError(f"--param {param!r}: not a real-valued case key (a threshold is "
                        "bisected on a number)")


def bracket(param: str, given: tuple[float, float] | None, resolution: float | None
            ) -> tuple[float, float, float]:
    """(lo, hi, resolution): the given ones, else the defaults of ``param``."""
    default = DEFAULTS.get(param)
    if default is None and (given is None or resolution is None):
        raise UserError(f"--param {param}: no default bracket; give --range LO HI and "
                        "--resolution R")
    lo, hi = given if given is not None else default[0]
    res = resolution if resolution is not None else default[1]
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise UserError(f"--range {lo:g} {hi:g}: needs finite LO < HI")
    if not (math.isfinite(res) and 0 < res < hi - lo):
        raise UserError(f"--resolution {res:g}: needs 0 < R < HI - LO = {hi - lo:g}")
    return lo, hi, res


def parse_grids(text: str | None) -> tuple[float, ...]:
    """``--grids F1,F2``: refinement factors (1 the case grid, 1.5 finer by 1.5, 1/1.5
    or 0.5 coarser); a factor may be written ``A/B``."""
    if text is None:
        return DEFAULT_GRIDS
    out = []
    for token in (t.strip() for t in text.split(",") if t.strip()):
        num, slash, den = token.partition("/")
        try:
            f = float(num) / (float(den) if slash else 1.0)
        except (ValueError, ZeroDivisionError):
            raise UserError(f"--grids {text!r}: {token!r} is not a number or A/B") from None
        if not (math.isfinite(f) and f > 0):
            raise UserError(f"--grids {text!r}: {token!r} must be positive")
        out.append(f)
    if not out or len(set(out)) != len(out):
        raise UserError(f"--grids {text!r}: needs distinct factors")
    return tuple(out)
