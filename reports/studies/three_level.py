"""The mathematics of a three-level study (grid or cycle jump): observed order, Richardson
extrapolation and Roache's grid-convergence index (GCI).

Three solutions f1 (finest), f2, f3 (coarsest) on grids of representative cell sizes
h1 < h2 < h3, refinement ratios r21 = h2/h1 and r32 = h3/h2 (Roache 1998; Celik et al.,
J. Fluids Eng. 130 (2008) 078001; docs/formulation.md §4.1, (G1) and (G2)):

- ε21 = f2 − f1, ε32 = f3 − f2, s = sign(ε32/ε21) (s < 0: oscillatory convergence);
- observed order p solves p = |ln|ε32/ε21| + q(p)| / ln r21 with
  q(p) = ln((r21^p − s)/(r32^p − s)); for a constant ratio r, q = 0 and
  p = |ln|ε32/ε21|| / ln r (the absolute value hides divergence: see ``converging``);
- Richardson extrapolation f_ext = (r21^p f1 − f2)/(r21^p − 1);
- GCI21 = Fs |e21| / (r21^p − 1) with the relative difference e21 = (f1 − f2)/f1 and the
  safety factor Fs = 1.25 for three grids; GCI32 likewise on the coarser pair;
- asymptotic range: GCI32 / (r21^p GCI21) ≈ 1.

:func:`classify` names the behaviour of a study (the ``status`` of ``convergence.csv``,
:mod:`reports.studies.gridstudy`):

- ``exact``: the three values agree to :data:`EXACT_REL` (a load the solver imposes, a
  quantity that is zero on every grid); no order, GCI 0;
- ``oscillating``: the differences ε21 and ε32 change sign;
- ``unsettled``: the differences do not shrink (|ε21| ≥ |ε32|, p ≤ 0: diverging or
  stalled), only the finest pair agrees (no order), a value is missing, or the
  asymptotic-range check fails: an observed order outside :data:`ORDER_RANGE` (a
  three-point fit always reproduces its own data, so an order far from what a
  discretisation can give — a coarse grid outside the asymptotic range, quantisation to
  cells — is the sign that the GCI cannot be trusted) or GCI32 / (r21^p GCI21) outside
  :data:`ASYMPTOTIC_BAND` (the values change by more than about 20 %);
- ``converged``: monotone, shrinking differences, 0 < p within :data:`ORDER_RANGE` and
  the asymptotic-range check within its band.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from reports.store.study_tables import (  # the statuses of classify()
    CONVERGED,
    EXACT,
    OSCILLATING,
    UNSETTLED,
)

FS_THREE_GRIDS = 1.25

#: three values within this relative spread are ``exact`` (solver tolerances are 1e-10)
EXACT_REL = 1e-9
#: observed orders a discretisation of these solvers can plausibly show: the √-edge of a
#: contact pressure limits some quantities to 0.5, quadratic elements give at most 3–4
ORDER_RANGE = (0.5, 5.0)
#: accepted range of GCI32 / (r21^p GCI21) (1 in the asymptotic range)
ASYMPTOTIC_BAND = (0.8, 1.25)


@dataclass(frozen=True)
class ThreeGrids:
    """Result of a three-grid study of one quantity (f1 on the finest grid)."""

    f: tuple[float, float, float]
    h: tuple[float, float, float]
    p: float  # observed order
    f_ext: float  # Richardson-extrapolated value
    gci_fine: float  # GCI21, a relative uncertainty of f1
    gci_coarse: float  # GCI32
    asymptotic: float  # GCI32 / (r21^p GCI21), 1 in the asymptotic range
    oscillatory: bool
    converging: bool  # |f2 − f1| < |f3 − f2|: differences shrink under refinement

    @property
    def r21(self) -> float:
        return self.h[1] / self.h[0]

    @property
    def r32(self) -> float:
        return self.h[2] / self.h[1]


def observed_order(f1: float, f2: float, f3: float, r21: float, r32: float | None = None,
                   *, tol: float = 1e-12, max_iter: int = 200) -> float:
    """Observed order of convergence from three solutions (finest first).

    Constant ratio (``r32`` None or equal to ``r21``): p = ln|ε32/ε21| / ln r.  Otherwise
    the fixed-point iteration of Celik et al. (2008).  NaN when the solutions do not
    change (ε21 = 0 or ε32 = 0).
    """
    r32 = r21 if r32 is None else r32
    if r21 <= 1 or r32 <= 1:
        raise ValueError("refinement ratios must exceed 1 (order grids finest first)")
    e21, e32 = f2 - f1, f3 - f2
    if e21 == 0 or e32 == 0:
        return math.nan
    ratio = e32 / e21
    s = math.copysign(1.0, ratio)
    log_ratio = math.log(abs(ratio))
    p = abs(log_ratio) / math.log(r21)
    if math.isclose(r21, r32, rel_tol=1e-12):
        return p
    for _ in range(max_iter):
        num, den = r21**p - s, r32**p - s
        if num <= 0 or den <= 0:
            return math.nan
        p_new = abs(log_ratio + math.log(num / den)) / math.log(r21)
        if abs(p_new - p) < tol:
            return p_new
        p = p_new
    return p


def gci(f_fine: float, f_coarse: float, r: float, p: float,
        fs: float = FS_THREE_GRIDS) -> float:
    """Roache's GCI of the finer solution of a pair: Fs |(f_fine − f_coarse)/f_fine| /
    (r^p − 1)."""
    if f_fine == 0 or not math.isfinite(p) or p <= 0:
        return math.nan
    return fs * abs((f_fine - f_coarse) / f_fine) / (r**p - 1.0)


def richardson(f1: float, f2: float, r21: float, p: float) -> float:
    """Richardson-extrapolated value from the two finest solutions."""
    if not math.isfinite(p) or p <= 0:
        return math.nan
    return (r21**p * f1 - f2) / (r21**p - 1.0)


def study(f: tuple[float, float, float], h: tuple[float, float, float]) -> ThreeGrids:
    """Three-grid study; ``f`` and ``h`` in any order (sorted here, finest first)."""
    pairs = sorted(zip(h, f, strict=True))
    (h1, f1), (h2, f2), (h3, f3) = pairs
    r21, r32 = h2 / h1, h3 / h2
    p = observed_order(f1, f2, f3, r21, r32)
    g21 = gci(f1, f2, r21, p)
    g32 = gci(f2, f3, r32, p)
    asym = g32 / (r21**p * g21) if g21 and math.isfinite(g21) and g21 > 0 else math.nan
    return ThreeGrids(f=(f1, f2, f3), h=(h1, h2, h3), p=p, f_ext=richardson(f1, f2, r21, p),
                     gci_fine=g21, gci_coarse=g32, asymptotic=asym,
                     oscillatory=(f3 - f2) * (f2 - f1) < 0,
                     converging=abs(f2 - f1) < abs(f3 - f2))


def is_exact(f: tuple[float, float, float], rel: float = EXACT_REL) -> bool:
    """Whether three finite values agree to ``rel`` of the largest (all zero included)."""
    scale = max(abs(v) for v in f)
    return max(f) - min(f) <= rel * scale


def classify(st: ThreeGrids) -> tuple[str, str]:
    """(status, reason) of a three-grid study (module doc); the reason is empty for
    ``converged`` and ``exact``."""
    f1, f2, f3 = st.f
    if not all(math.isfinite(v) for v in st.f):
        return UNSETTLED, "a value is missing (not finite) on some grid"
    if is_exact(st.f):
        return EXACT, ""
    e21, e32 = f2 - f1, f3 - f2
    if st.oscillatory:
        return OSCILLATING, (f"differences change sign (f2 - f1 = {e21:.3g}, "
                             f"f3 - f2 = {e32:.3g})")
    if e21 == 0 or e32 == 0:
        return UNSETTLED, ("only the finest pair agrees" if e21 == 0 else
                               "only the coarsest pair agrees") + ": no observed order"
    if not st.converging or not (st.p > 0):
        return UNSETTLED, (f"differences do not shrink (|f2 - f1| = {abs(e21):.3g} >= "
                               f"|f3 - f2| = {abs(e32):.3g})")
    lo, hi = ORDER_RANGE
    if not lo <= st.p <= hi:
        return UNSETTLED, (f"observed order {st.p:.3g} outside [{lo:g}, {hi:g}]: not "
                               "in the asymptotic range")
    lo, hi = ASYMPTOTIC_BAND
    if not lo <= st.asymptotic <= hi:
        return UNSETTLED, (f"GCI32/(r21^p GCI21) = {st.asymptotic:.3g} outside "
                               f"[{lo:g}, {hi:g}]: not in the asymptotic range")
    return CONVERGED, ""
