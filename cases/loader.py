"""Read, validate and expand TOML case files (schema: ``cases/README.md``).

``load_case(name_or_path, quick=False)`` returns one :class:`~cases.model.Case` per sweep
point.  Every error is a :class:`~cases.model.CaseError` whose message names the key.
"""

from __future__ import annotations

import copy
import math
import tomllib
from pathlib import Path
from typing import Any

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

CASES_DIR = Path(__file__).resolve().parent
BUNDLED = (
    "hertz",
    "cattaneo_mindlin",
    "sliding_friction",
    "pin_on_disk",
    "pin_on_disk_orthotropic",
    "fretting_orthotropic",
    "dissimilar",
)
KINDS = ("static", "sliding_wear", "fretting")

# key -> (type, required); a table maps its keys the same way.
_SCHEMA: dict[str, Any] = {
    "name": str,
    "description": str,
    "kind": str,
    "materials": {
        "a": {"E": float, "nu": float, "i1": float, "i2": float},
        "b": {"E": float, "nu": float, "i1": float, "i2": float},
    },
    "geometry": {"R": float},
    "grid": {"Lx": float, "Ly": float, "nx": int, "ny": int},
    "friction": {"mu": float, "mu1": float, "mu2": float, "beta": float},
    "load": {
        "P": float,
        "approach": float,
        "Qx": float,
        "Qy": float,
        "shift_x": float,
        "shift_y": float,
        "sliding": bool,
        "slide_angle": float,
    },
    "sliding_wear": {"step": float, "distance": float, "output_s": list},
    "fretting": {
        "amplitude": float,
        "steps_per_cycle": int,
        "cycles": int,
        "jump": float,
        "output_cycles": list,
    },
    "stress": {"body": str, "depth": float, "nz": int, "x0": float, "y0": float},
    "solver": {"method": str, "tol": float, "max_iter": int},
    "fem": {"block": float, "depth": float, "h": float, "order": int, "penalty": float},
    "tolerances": dict,
    "sweep": {"key": str, "values": list, "label": str},
    "quick": dict,
}


def case_path(name_or_path: str | Path) -> Path:
    """Resolve a bundled case name (file stem in ``cases/``) or a path to a TOML file."""
    p = Path(name_or_path)
    if p.suffix == ".toml" or p.exists():
        if not p.is_file():
            raise CaseError(f"case file {p} does not exist")
        return p
    bundled = CASES_DIR / f"{name_or_path}.toml"
    if not bundled.is_file():
        names = ", ".join(sorted(q.stem for q in CASES_DIR.glob("*.toml")))
        raise CaseError(f"unknown case {name_or_path!r}; bundled cases: {names}")
    return bundled


def read_toml(path: Path) -> dict:
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(f"{path}: malformed TOML: {exc}") from None


def _check_types(data: dict, schema: dict, prefix: str = "") -> None:
    for key, value in data.items():
        dotted = f"{prefix}{key}"
        if key not in schema:
            allowed = ", ".join(sorted(schema))
            raise CaseError(f"unknown key {dotted!r} (allowed here: {allowed})")
        expected = schema[key]
        if isinstance(expected, dict):
            if not isinstance(value, dict):
                raise CaseError(f"{dotted!r} must be a table")
            _check_types(value, expected, dotted + ".")
        elif expected is float:
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise CaseError(f"{dotted} = {value!r}: must be a number")
            if not math.isfinite(value):
                raise CaseError(f"{dotted} = {value!r}: must be finite")
        elif expected is int:
            if isinstance(value, bool) or not isinstance(value, int):
                raise CaseError(f"{dotted} = {value!r}: must be an integer")
        elif not isinstance(value, expected):
            raise CaseError(f"{dotted} = {value!r}: must be of type {expected.__name__}")


def _set_dotted(data: dict, dotted: str, value: Any) -> None:
    parts = dotted.split(".")
    node = data
    for part in parts[:-1]:
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise CaseError(f"cannot set {dotted!r}: {part!r} is not a table")
    node[parts[-1]] = value


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
    # A memory estimate before anything is allocated: the FFT operator holds 9 complex
    # kernels of (2nx)(2ny) plus work arrays, about 40 float64 grids of that size.
    mem_gb = 40 * 4 * g.nx * g.ny * 8 / 1e9
    if mem_gb > 16:
        raise CaseError(f"grid {g.nx} x {g.ny} needs about {mem_gb:.0f} GB (limit 16 GB)")
    return g


def _load(d: dict) -> Load:
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


def _build(data: dict, *, name: str, source: str, param: str) -> Case:
    kind = data.get("kind", "static")
    if kind not in KINDS:
        raise CaseError(f"kind = {kind!r}: must be one of {', '.join(KINDS)}")
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
    load = _load(data["load"])
    if load.sliding and friction.mu1 == 0 and kind == "static":
        pass  # frictionless sliding is allowed: it is the normal problem
    if load.tangential_mode == "load" and friction.mu1 == 0:
        raise CaseError("load.Qx/Qy need friction (friction.mu or mu1/mu2 > 0)")

    stress = StressOutput(**data.get("stress", {}))
    if stress.body not in ("a", "b"):
        raise CaseError(f"stress.body = {stress.body!r}: must be 'a' or 'b'")
    check_positive(stress.depth, "stress.depth")
    if stress.nz < 2:
        raise CaseError(f"stress.nz = {stress.nz}: need at least 2 layers")

    solver = Solver(**data.get("solver", {}))
    if solver.method not in ("cg", "uzawa"):
        raise CaseError(f"solver.method = {solver.method!r}: must be 'cg' or 'uzawa'")
    check_positive(solver.tol, "solver.tol")
    if solver.max_iter < 1:
        raise CaseError(f"solver.max_iter = {solver.max_iter}: must be >= 1")

    fem = FemSettings(**data.get("fem", {}))
    for key in ("block", "depth", "h", "penalty"):
        check_positive(getattr(fem, key), f"fem.{key}")
    if fem.order not in (1, 2):
        raise CaseError(f"fem.order = {fem.order}: must be 1 or 2")

    sliding_wear = fretting = None
    if kind == "sliding_wear":
        d = dict(data.get("sliding_wear", {}))
        d["output_s"] = tuple(float(v) for v in d.get("output_s", ()))
        sliding_wear = SlidingWear(**d)
        check_positive(sliding_wear.step, "sliding_wear.step")
        check_positive(sliding_wear.distance, "sliding_wear.distance")
        if load.P is None:
            raise CaseError("sliding_wear needs load control (load.P)")
    if kind == "fretting":
        d = dict(data.get("fretting", {}))
        d["output_cycles"] = tuple(int(v) for v in d.get("output_cycles", ()))
        fretting = Fretting(**d)
        check_positive(fretting.amplitude, "fretting.amplitude")
        check_positive(fretting.jump, "fretting.jump")
        if fretting.steps_per_cycle < 4:
            raise CaseError("fretting.steps_per_cycle must be >= 4")
        if fretting.cycles < 1:
            raise CaseError("fretting.cycles must be >= 1")
        if friction.mu1 == 0:
            raise CaseError("fretting needs friction (friction.mu or mu1/mu2 > 0)")

    tolerances = {}
    for key, value in data.get("tolerances", {}).items():
        if isinstance(value, bool) or not isinstance(value, int | float) or value <= 0:
            raise CaseError(f"tolerances.{key} = {value!r}: must be a positive number")
        tolerances[key] = float(value)

    return Case(
        name=name,
        kind=kind,
        a=_body(mats["a"], "a"),
        b=_body(mats["b"], "b"),
        R=R,
        grid=_grid(data["grid"]),
        friction=friction,
        load=load,
        stress=stress,
        solver=solver,
        sliding_wear=sliding_wear,
        fretting=fretting,
        fem=fem,
        tolerances=tolerances,
        description=data.get("description", ""),
        param=param,
        source=source,
    )


def _fmt(value: Any) -> str:
    return f"{value:g}" if isinstance(value, float) else str(value)


def load_case(name_or_path: str | Path, *, quick: bool = False,
              overrides: dict[str, Any] | None = None) -> list[Case]:
    """Load a case file and return one validated Case per sweep value.

    ``quick`` applies the file's ``[quick]`` table (dotted keys, coarse grids for CI);
    ``overrides`` (dotted keys) are applied last, e.g. ``{"grid.nx": 41}``.
    """
    path = case_path(name_or_path)
    raw = read_toml(path)
    _check_types(raw, _SCHEMA)
    name = raw.get("name", path.stem)
    data = copy.deepcopy({k: v for k, v in raw.items() if k not in ("sweep", "quick", "name")})
    if quick:
        for key, value in raw.get("quick", {}).items():
            if not key.startswith("sweep."):
                _set_dotted(data, key, value)
    for key, value in (overrides or {}).items():
        _set_dotted(data, key, value)
    _check_types(data, _SCHEMA)

    sweep = raw.get("sweep")
    if not sweep:
        return [_build(data, name=name, source=str(path), param="")]
    if "key" not in sweep or "values" not in sweep or not sweep["values"]:
        raise CaseError("sweep needs 'key' (a dotted key) and a non-empty 'values' list")
    values = sweep["values"]
    if quick and "sweep.values" in raw.get("quick", {}):
        values = raw["quick"]["sweep.values"]
    if overrides and sweep["key"] in overrides:
        values = [overrides[sweep["key"]]]  # overriding the swept key narrows the sweep
    label = sweep.get("label", sweep["key"].split(".")[-1])
    cases = []
    for value in values:
        point = copy.deepcopy(data)
        _set_dotted(point, sweep["key"], value)
        _check_types(point, _SCHEMA)
        cases.append(_build(point, name=name, source=str(path), param=f"{label}={_fmt(value)}"))
    return cases
