"""Shared test helpers: bundled cases, the Hertz solution of a case, and the one way the
suite asserts convergence under refinement.

A plain module (no ``__init__.py`` in ``tests/``): pytest's default ``prepend`` import
mode puts ``tests/`` on ``sys.path``, so ``from vv_testing import assert_converges``
works from ``pytest``, ``pytest tests/test_x.py`` and inside functions cached at module
level, where fixtures cannot reach.  ``tests/conftest.py`` wraps the case helpers as
fixtures.

Convergence: :func:`assert_converges` takes the errors of a quantity on a sequence of
grids (or, with ``values=``, the quantity itself when no exact value is known) and asserts
an observed order, a bound on the finest error or on the last change.  Which formula
gives the order depends on what is known (``reports/studies/three_level.py``):

- **errors against an exact value** e_k = f_k − f_exact: the errors' ratios,
  p = ln(|e_coarse| / |e_fine|) / ln(h_coarse / h_fine), for every consecutive pair.  It
  is ``observed_order``'s constant-ratio formula ln|ε32/ε21| / ln r with the differences ε
  replaced by the errors themselves, as the limit is known.  No outer ``abs``: an error
  that grows under refinement gives p < 0.  Do not pass errors to ``observed_order`` instead: the
  differences of errors are the differences of the values, so it fits
  f = f_lim + C h^p with f_lim free and would report an error that stalls at a floor
  (e = 0.05 + C h²) as order 2; its ``abs`` also turns a growing error into a positive
  order.  That three-grid order of the errors, and the Richardson limit of the errors
  (≈ 0 when the errors do vanish), are reported in the message, not asserted;
- **values without an exact value**: ``observed_order`` of the three finest values
  (Celik et al. 2008, the order of the report's convergence table), asserted only
  together with ``converging`` (|f2 − f1| < |f3 − f2|), as the ``abs`` in its formula
  hides divergence; the change between the two finest grids is Roache's relative
  difference |f2/f1 − 1| (e21 of the GCI).

Every bound is strict (order > min_order, error < finest, change < max_change), as the
suite's assertions were written.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from analytic.hertz import Hertz, hertz, hertz_from_approach
from cases.loader import BUNDLED, load_case
from cases.model import Case
from reports.studies.three_level import observed_order, richardson


def load_bundled(name: str, *, quick: bool = False, overrides: dict | None = None,
                 index: int = 0) -> Case:
    """Case ``index`` of the bundled case file ``name`` (``cases/<name>.toml``) through
    :func:`cases.loader.load_case`; ``quick`` applies its ``[quick]`` table, ``overrides``
    (dotted keys) are applied last."""
    if name not in BUNDLED:
        raise ValueError(f"{name!r} is not a bundled case (one of {', '.join(BUNDLED)})")
    return load_case(name, quick=quick, overrides=overrides)[index]


def hertz_solution(case: Case) -> Hertz:
    """The closed-form Hertz contact of the case's sphere under its normal load
    (:mod:`analytic.hertz`): a, p0 and the approach δ.  Load control: ``hertz(P, R, E*)``;
    displacement control: ``hertz_from_approach(δ, R, E*)``.  (a, p0) are
    ``case.hertz_scales``; use this where δ0 = a0²/R is needed too."""
    if case.load.P is not None:
        return hertz(case.load.P, case.R, case.E_star)
    return hertz_from_approach(float(case.load.approach), case.R, case.E_star)


@dataclass(frozen=True)
class Convergence:
    """The measured convergence of one quantity; grids ordered coarse to fine."""

    what: str
    h: tuple[float, ...]
    errors: tuple[float, ...] | None  # against an exact value, as given (may be signed)
    values: tuple[float, ...] | None  # when no exact value is known
    orders: tuple[float, ...]  # errors' ratios, one per consecutive pair (errors only)
    three_grid_order: float  # observed_order of the three finest (nan with < 3 grids)
    converging: bool  # errors: |e| decreases pair by pair; values: |f2-f1| < |f3-f2|
    limit: float  # Richardson limit of the three finest (errors: ≈ 0 if they vanish)
    change: float  # values: |f2/f1 - 1| of the two finest; nan for errors

    @property
    def finest(self) -> float:
        """|error| on the finest grid (errors), nan for values."""
        return abs(self.errors[-1]) if self.errors is not None else math.nan

    def __str__(self) -> str:
        data = self.errors if self.errors is not None else self.values
        kind = "error" if self.errors is not None else "value"
        rows = ", ".join(f"h={h:.6g}: {e:.6g}" for h, e in zip(self.h, data, strict=True))
        out = [f"{self.what or 'quantity'} ({kind} per h, coarse to fine): {rows}"]
        if self.errors is not None:
            out.append("orders (errors' ratios, per pair) "
                       + ", ".join(f"{p:.4g}" for p in self.orders)
                       + f"; finest |error| {self.finest:.6g}")
            if len(self.h) >= 3:
                out.append(f"three-grid order of the errors {self.three_grid_order:.4g} "
                           f"(Richardson limit of the errors {self.limit:.3g})")
        else:
            if len(self.h) >= 3:
                out.append(f"three-grid observed order {self.three_grid_order:.4g}, "
                           f"differences shrink {self.converging}, "
                           f"Richardson limit {self.limit:.6g}")
            out.append(f"change of the two finest |f2/f1 - 1| = {self.change:.4g}")
        return "; ".join(out)


def _three_finest(f_fine_first: Sequence[float], h_fine_first: Sequence[float]):
    """observed_order and Richardson limit of the three finest (finest first), or nan."""
    if len(f_fine_first) < 3:
        return math.nan, math.nan
    (f1, f2, f3), (h1, h2, h3) = f_fine_first[:3], h_fine_first[:3]
    r21, r32 = h2 / h1, h3 / h2
    p = observed_order(f1, f2, f3, r21, r32)
    return p, richardson(f1, f2, r21, p)


def measure(h: Sequence[float], errors: Sequence[float] | None = None, *,
            values: Sequence[float] | None = None, what: str = "") -> Convergence:
    """The convergence record of ``errors`` (against an exact value) or ``values`` on the
    grids ``h`` (any order; sorted coarse to fine here)."""
    if (errors is None) == (values is None):
        raise ValueError("give exactly one of errors (against an exact value) and values")
    data = [float(v) for v in (errors if errors is not None else values)]
    hs = [float(x) for x in h]
    if len(hs) != len(data) or len(hs) < 2:
        raise ValueError(f"need matching h and data on >= 2 grids, got {len(hs)}, {len(data)}")
    if not all(math.isfinite(x) and x > 0 for x in hs) or len(set(hs)) != len(hs):
        raise ValueError(f"h must be distinct positive numbers, got {hs}")
    if not all(math.isfinite(v) for v in data):
        raise AssertionError(f"{what or 'quantity'}: non-finite data {data} on h = {hs}")
    pairs = sorted(zip(hs, data, strict=True), reverse=True)  # coarse to fine
    hs, data = [p[0] for p in pairs], [p[1] for p in pairs]
    p3, limit = _three_finest(data[::-1], hs[::-1])
    if errors is not None:
        orders = []
        for (hc, ec), (hf, ef) in zip(pairs, pairs[1:], strict=False):
            if ef == 0:
                orders.append(math.inf if ec != 0 else math.nan)
            elif ec == 0:
                orders.append(-math.inf)
            else:
                orders.append(math.log(abs(ec) / abs(ef)) / math.log(hc / hf))
        converging = all(abs(ef) < abs(ec) for ec, ef in zip(data, data[1:], strict=False))
        return Convergence(what, tuple(hs), tuple(data), None, tuple(orders), p3, converging,
                           limit, math.nan)
    f1, f2 = data[-1], data[-2]
    change = abs(f2 / f1 - 1) if f1 != 0 else math.inf
    converging = len(data) >= 3 and abs(f2 - f1) < abs(data[-3] - f2)
    return Convergence(what, tuple(hs), None, tuple(data), (), p3, converging, limit, change)


def assert_converges(h: Sequence[float], errors: Sequence[float] | None = None, *,
                     values: Sequence[float] | None = None, min_order: float | None = None,
                     finest: float | None = None, max_change: float | None = None,
                     what: str = "") -> Convergence:
    """Assert convergence under refinement; returns the :class:`Convergence` (print it).

    ``errors`` against an exact value on the grids ``h``: |e| decreases from grid to grid
    and every pairwise order of the errors' ratios exceeds ``min_order`` (required,
    >= 0: 0 asserts only the decrease); ``finest`` bounds |e| on the finest grid.

    ``values`` without an exact value: ``min_order`` bounds ``observed_order`` of the
    three finest (needs >= 3 grids; the differences must shrink), ``max_change`` the
    relative change |f2/f1 - 1| of the two finest (f1 finest).

    The failure message gives the data per h, the fitted order(s) and the finest error.
    """
    conv = measure(h, errors, values=values, what=what)
    fails = []
    if errors is not None:
        if min_order is None or min_order < 0:
            raise ValueError("errors need min_order >= 0 (0: the errors only decrease)")
        if max_change is not None:
            raise ValueError("max_change bounds values; for errors use finest")
        if not conv.converging:
            fails.append("the error does not decrease under every refinement")
        low = [p for p in conv.orders if not p > min_order]
        if low:
            fails.append(f"order(s) {', '.join(f'{p:.4g}' for p in low)} not > {min_order:g}")
        if finest is not None and not conv.finest < finest:
            fails.append(f"finest |error| {conv.finest:.6g} not < {finest:g}")
    else:
        if finest is not None:
            raise ValueError("finest bounds errors; for values use max_change")
        if min_order is None and max_change is None:
            raise ValueError("values need min_order and/or max_change")
        if min_order is not None:
            if len(conv.h) < 3:
                raise ValueError("an observed order of values needs >= 3 grids")
            if not conv.converging:
                fails.append("the differences do not shrink (|f2 - f1| >= |f3 - f2|)")
            if not conv.three_grid_order > min_order:
                fails.append(f"observed order {conv.three_grid_order:.4g} not > {min_order:g}")
        if max_change is not None and not conv.change < max_change:
            fails.append(f"change |f2/f1 - 1| = {conv.change:.4g} not < {max_change:g}")
    assert not fails, f"{' and '.join(fails)}: {conv}"
    return conv


def assert_surface_row_is_the_traction(case: Case, result) -> None:
    """The σ_VM planes' surface row (depth 0) carries the boundary condition: in the
    reported frame σ_zz = −p_n, and (σ_xz, σ_yz) = (p_x, p_y) on body b, the opposite on
    body a (the tractions of the common format are body a's; body b carries −p_t).
    Checked where the plane's line runs through the surface grid (the planes of the
    bundled cases do), at the points in contact, on every output step."""
    sign = 1.0 if case.stress.body == "b" else -1.0
    x0, y0 = case.plane_centre
    for step in result.steps:
        for name, plane in step.planes.items():
            assert plane.z[0] == 0.0
            axis, at = (step.y, y0) if name == "xz" else (step.x, x0)
            k = int(np.argmin(np.abs(axis - at)))
            assert abs(axis[k] - at) < 1e-12 * max(1.0, abs(at))
            line = {q: (f[:, k] if name == "xz" else f[k, :]) for q, f in step.surface.items()}
            on = line["p_n"] > 0.0
            assert on.sum() >= 3
            scale = float(np.max(line["p_n"]))
            for comp, want in (("szz", -line["p_n"]), ("sxz", sign * line["p_x"]),
                               ("syz", sign * line["p_y"])):
                np.testing.assert_allclose(plane.fields[comp][on, 0], want[on],
                                           atol=1e-9 * scale, err_msg=f"{name} {comp}")
