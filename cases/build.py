"""A validated :class:`~cases.model.Case` from a type-checked case table: every value
in its range, every combination consistent, each error naming its key."""

from __future__ import annotations

import math
import re

import numpy as np

from .model import (
    Body,
    Case,
    CaseError,
    FemSettings,
    Fretting,
    Friction,
    Grid,
    Load,
    SlidingWear,
    Solver,
    StressOutput,
    check_positive,
)
from .steps import sliding_outputs

KINDS = ("static", "sliding_wear", "fretting")


def _body(d: dict, key: str) -> Body:
    if "E" not in d or "nu" not in d:
        raise CaseError(f"materials.{key} needs E and nu")
    body = Body(E=float(d["E"]), nu=float(d["nu"]), i1=float(d.get("i1", 0.0)),
                i2=float(d.get("i2", d.get("i1", 0.0))))
    check_positive(body.E, f"materials.{key}.E")
    if not -1.0 < body.nu < 0.5:
        raise CaseError(f"materials.{key}.nu = {body.nu}: Poisson's ratio must lie in (-1, 0.5)")
    check_positive(body.i1, f"materials.{key}.i1", allow_zero=True)
    check_positive(body.i2, f"materials.{key}.i2", allow_zero=True)
    return body


def _friction(d: dict) -> Friction:
    if "mu" in d and ("mu1" in d or "mu2" in d):
        raise CaseError("friction: give either mu (isotropic) or mu1/mu2, not both")
    mu1 = float(d.get("mu", d.get("mu1", 0.0)))
    mu2 = float(d.get("mu", d.get("mu2", mu1)))
    beta = float(d.get("beta", 0.0))
    check_positive(mu1, "friction.mu1", allow_zero=True)
    check_positive(mu2, "friction.mu2", allow_zero=True)
    if (mu1 == 0) != (mu2 == 0):
        raise CaseError("friction: mu1 and mu2 must be both zero or both positive")
    if not -360.0 <= beta <= 360.0:
        raise CaseError(f"friction.beta = {beta}: must lie in [-360, 360] degrees")
    return Friction(mu1=mu1, mu2=mu2, beta=beta)


def _grid(d: dict) -> Grid:
    for key in ("Lx", "nx"):
        if key not in d:
            raise CaseError(f"grid.{key} is required")
    g = Grid(Lx=float(d["Lx"]), Ly=float(d.get("Ly", d["Lx"])), nx=int(d["nx"]),
             ny=int(d.get("ny", d["nx"])))
    check_positive(g.Lx, "grid.Lx")
    check_positive(g.Ly, "grid.Ly")
    for key, n in (("grid.nx", g.nx), ("grid.ny", g.ny)):
        if n < 4:
            raise CaseError(f"{key} = {n}: need at least 4 cells")
    return g  # what the grid costs each solver is its own estimate (reports.run.plan.Limits)


#: the load keys a kind of case has no use for (refused rather than ignored): the path
#: of a wear run is its own table's ([sliding_wear] slides, [fretting] shifts)
_UNUSED_LOAD = {"sliding_wear": ("Qx", "Qy", "shift_x", "shift_y"),
                "fretting": ("Qx", "Qy", "shift_x", "shift_y", "sliding")}


def _load(d: dict, kind: str) -> Load:
    for key in _UNUSED_LOAD.get(kind, ()):
        if key in d and d[key] is not False:
            raise CaseError(f"load.{key} = {d[key]!r}: a {kind} case does not use it (its "
                            f"tangential path is set by [{kind}]); remove it")
    if kind == "static" and "slide_angle" in d and not d.get("sliding", False):
        raise CaseError(f"load.slide_angle = {d['slide_angle']!r}: only used with load.sliding "
                        "= true (a Qx/Qy load or shift_x/shift_y gives its own direction)")
    load = Load(**{k: d[k] for k in d})
    if (load.P is None) == (load.approach is None):
        raise CaseError("load: give exactly one of load.P (N) and load.approach (mm)")
    if load.P is not None:
        check_positive(load.P, "load.P")
    if load.approach is not None:
        check_positive(load.approach, "load.approach")
    has_q = load.Qx is not None or load.Qy is not None
    has_s = load.shift_x is not None or load.shift_y is not None
    if sum((has_q, has_s, load.sliding)) > 1:
        raise CaseError("load: give at most one of Qx/Qy, shift_x/shift_y and sliding = true")
    return load


def _one_of(value, allowed: tuple, key: str) -> None:
    if value not in allowed:
        raise CaseError(f"{key} = {value!r}: must be one of {', '.join(map(repr, allowed))}")


def _at_least(value: int, low: int, key: str) -> None:
    if value < low:
        raise CaseError(f"{key} = {value}: must be >= {low}")


def _checked(table: str, cls, d: dict, *, choices: dict | None = None,
             positive: tuple[str, ...] = (), minimum: dict | None = None):
    """``cls(**d)`` with its values checked: ``choices`` {key: allowed}, ``positive``
    keys, ``minimum`` {key: lowest integer}; errors name ``table.key``."""
    obj = cls(**d)
    for key, allowed in (choices or {}).items():
        _one_of(getattr(obj, key), allowed, f"{table}.{key}")
    for key in positive:
        check_positive(getattr(obj, key), f"{table}.{key}")
    for key, low in (minimum or {}).items():
        _at_least(getattr(obj, key), low, f"{table}.{key}")
    return obj


def _fem(d: dict) -> FemSettings:
    fem = _checked("fem", FemSettings, d,
                   choices={"order": (1, 2), "contact": ("semismooth", "augmented")},
                   positive=("block", "depth", "h", "penalty"))
    if "penalty" in d and fem.contact != "augmented":
        raise CaseError(f"fem.penalty applies to fem.contact = 'augmented' only (the "
                        f"penalty of its augmented Lagrangian); fem.contact = {fem.contact!r} "
                        "has none")
    if fem.h_surface is not None:
        check_positive(fem.h_surface, "fem.h_surface")
        if fem.h_surface > fem.h:
            raise CaseError(f"fem.h_surface = {fem.h_surface!r}: must not exceed fem.h = "
                            f"{fem.h!r} (it refines the contact surface)")
    return fem


def _sliding_wear(d: dict, load: Load) -> SlidingWear:
    d = dict(d, output_s=tuple(float(v) for v in d.get("output_s", ())))
    sliding_wear = _checked("sliding_wear", SlidingWear, d, positive=("step", "distance"))
    if load.P is None:
        raise CaseError("sliding_wear needs load control (load.P)")
    sliding_outputs(sliding_wear)  # a whole number of steps, the outputs within the run
    return sliding_wear


def _fretting(d: dict, friction: Friction) -> Fretting:
    d = dict(d, output_cycles=tuple(int(v) for v in d.get("output_cycles", ())))
    fretting = _checked("fretting", Fretting, d, positive=("amplitude", "jump"),
                        minimum={"steps_per_cycle": 4, "cycles": 1},
                        choices={"transverse": ("held", "free")})
    if friction.mu1 == 0:
        raise CaseError("fretting needs friction (friction.mu or mu1/mu2 > 0)")
    _on_jump_grid(fretting.cycles, fretting.jump, "fretting.cycles")
    for k, c in enumerate(fretting.output_cycles):
        key = f"fretting.output_cycles[{k}]"
        if not 0 < c <= fretting.cycles:
            raise CaseError(f"{key} = {c}: must lie in (0, fretting.cycles = "
                            f"{fretting.cycles}]")
        _on_jump_grid(c, fretting.jump, key)
    if len(set(fretting.output_cycles)) < len(fretting.output_cycles):
        raise CaseError(f"fretting.output_cycles = {list(fretting.output_cycles)}: repeated "
                        "cycle")
    return fretting


def _on_jump_grid(cycles: int, jump: float, key: str) -> None:
    """Each simulated cycle stands for ``jump`` cycles: a cycle count the run reports
    must be a whole number of simulated cycles (else its label and its wear differ)."""
    n = cycles / jump
    if not math.isfinite(n):
        raise CaseError(f"fretting.jump = {jump!r}: {key} = {cycles} / jump is not a finite "
                        "number of simulated cycles")
    if n < 1 or abs(n - round(n)) > 1e-9 * n:
        low, high = max(math.floor(n), 1) * jump, max(math.ceil(n), 1) * jump
        raise CaseError(f"{key} = {cycles}: not a whole number of simulated cycles of "
                        f"fretting.jump = {jump:g} cycles (nearest: {low:g} or {high:g})")


def _tolerances(d: dict) -> dict[str, float]:
    tolerances = {}
    for key, value in d.items():
        if isinstance(value, bool) or not isinstance(value, int | float) or value <= 0:
            raise CaseError(f"tolerances.{key} = {value!r}: must be a positive number")
        tolerances[key] = float(value)
    return tolerances


def _not_converged(d: dict) -> dict[str, str]:
    """``[not_converged]``: quantity -> the reason (a non-empty string); the quantity names
    are checked against the comparisons' by the reports (:mod:`reports.registry.tolerances`)."""
    for key, value in d.items():
        if not isinstance(value, str) or not value.strip():
            raise CaseError(f"not_converged.{key} = {value!r}: must be a non-empty string "
                            "saying why (with the measured values)")
    return dict(d)


def _stress(d: dict) -> StressOutput:
    stress = _checked("stress", StressOutput, d, choices={"body": ("a", "b")},
                      positive=("depth",), minimum={"nz": 2})
    if stress.z_below is not None and not 0 < stress.z_below <= stress.depth:
        raise CaseError(f"stress.z_below = {stress.z_below!r}: must lie in (0, stress.depth "
                        f"= {stress.depth:g}] mm")
    return stress


#: the name of an external result set (solver ``external:NAME``)
NAME_RE = re.compile(r"[a-z][a-z0-9_]*")


def _external(d: dict) -> dict[str, dict]:
    """``[external.NAME]``: a table per name (its keys are checked by the solver that
    reads them, :mod:`external_results.spec`)."""
    for key, value in d.items():
        if not NAME_RE.fullmatch(key):
            raise CaseError(f"external.{key}: a name is lower-case letters, digits and '_', "
                            "starting with a letter")
        if not isinstance(value, dict):
            raise CaseError(f"external.{key} must be a table")
    return {k: dict(v) for k, v in d.items()}


def build(data: dict, *, name: str, source: str, param: str) -> Case:
    kind = data.get("kind", "static")
    _one_of(kind, KINDS, "kind")
    mats = data.get("materials", {})
    for key in ("a", "b"):
        if key not in mats:
            raise CaseError(f"materials.{key} is required")
    if "R" not in data.get("geometry", {}):
        raise CaseError("geometry.R is required")
    R = float(data["geometry"]["R"])
    check_positive(R, "geometry.R")
    if "grid" not in data:
        raise CaseError("[grid] is required")
    if "load" not in data:
        raise CaseError("[load] is required")
    friction = _friction(data.get("friction", {}))
    load = _load(data["load"], kind)
    if load.tangential_mode == "load" and friction.mu1 == 0:
        raise CaseError("load.Qx/Qy need friction (friction.mu or mu1/mu2 > 0)")
    solver = _checked("solver", Solver, data.get("solver", {}),
                      choices={"method": ("cg", "uzawa")}, positive=("tol",),
                      minimum={"max_iter": 1})
    if not (math.isfinite(solver.wear_spread) and solver.wear_spread >= 0):
        raise CaseError(f"solver.wear_spread = {solver.wear_spread!r}: must be a length "
                        "≥ 0 [mm]")
    case = Case(
        name=name,
        kind=kind,
        a=_body(mats["a"], "a"),
        b=_body(mats["b"], "b"),
        R=R,
        grid=_grid(data["grid"]),
        friction=friction,
        load=load,
        stress=_stress(data.get("stress", {})),
        solver=solver,
        sliding_wear=_sliding_wear(data.get("sliding_wear", {}), load)
        if kind == "sliding_wear" else None,
        fretting=_fretting(data.get("fretting", {}), friction) if kind == "fretting" else None,
        fem=_fem(data.get("fem", {})),
        tolerances=_tolerances(data.get("tolerances", {})),
        not_converged=_not_converged(data.get("not_converged", {})),
        external=_external(data.get("external", {})),
        description=data.get("description", ""),
        param=param,
        source=source,
    )
    _check_scales(case)
    wears = any(v > 0 for v in (case.a.i1, case.a.i2, case.b.i1, case.b.i2))
    if solver.wear_spread > 0 and not (kind in ("sliding_wear", "fretting") and wears):
        raise CaseError(f"solver.wear_spread = {solver.wear_spread!r}: a case without wear "
                        "does not use it (it spreads the wear increments)")
    return case


def _check_scales(case: Case) -> None:
    """The Hertz radius a0 and pressure p0 (:attr:`cases.model.Case.hertz_scales`), the
    scales every solver and table divides by, and the powers the formulas take of them
    (a0⁴ in the worn-pin radius, p0² in σ_VM²) must be normal finite floats; else the
    inputs lie outside the domain the formulas are computed in."""
    load = "load.P" if case.load.P is not None else "load.approach"
    value = case.load.P if case.load.P is not None else case.load.approach
    try:
        scales = case.hertz_scales
    except (ZeroDivisionError, OverflowError):  # a0 underflowed to 0, or overflowed
        scales = (0.0, math.nan)
    with np.errstate(all="ignore"):
        a0, p0 = (np.float64(v) for v in scales)
        for name, v, power, unit in (("a0", a0, 4, "mm"), ("p0", p0, 2, "MPa")):
            if not (np.isfinite(v ** power) and v ** power >= np.finfo(float).tiny):
                raise CaseError(
                    f"{load} = {value!r} with geometry.R = {case.R!r}, materials.a.E = "
                    f"{case.a.E!r}, materials.b.E = {case.b.E!r}: the Hertz {name} = "
                    f"{float(v):.3g} {unit} is outside the range the formulas compute in "
                    f"({name}^{power} must be a normal finite float)")
