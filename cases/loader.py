"""Read, validate and expand TOML case files (schema: ``cases/README.md``).

``load_case(name_or_path, quick=False)`` returns one :class:`~cases.model.Case` per sweep
point.  Every error is a :class:`~cases.model.CaseError` whose message names the key.
"""

from __future__ import annotations

import copy
import difflib
from pathlib import Path
from typing import Any

from .build import build
from .model import Case, CaseError
from .schema import (
    NAME,
    NOT_OVERRIDABLE,
    SCALAR,
    SCHEMA,
    check_types,
    check_value,
    read_toml,
    set_dotted,
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
    "fretting_isotropic",
    "spence",
)
def case_path(name_or_path: str | Path) -> Path:
    """Resolve a bundled case name (file stem in ``cases/``) or a path to a TOML file."""
    p = Path(name_or_path)
    if p.suffix == ".toml" or p.exists():
        if p.is_dir():
            raise CaseError(f"case file {p} is a directory")
        if not p.is_file():
            raise CaseError(f"case file {p} " + ("is not a regular file (a device or a "
                            "pipe: name a TOML file)" if p.exists() else "does not exist"))
        return p
    bundled = CASES_DIR / f"{name_or_path}.toml"
    if not bundled.is_file():
        stems = sorted(q.stem for q in CASES_DIR.glob("*.toml"))
        near = difflib.get_close_matches(str(name_or_path), stems, n=1)
        guess = f" (did you mean {near[0]!r}?)" if near else ""
        raise CaseError(f"unknown case {name_or_path!r}{guess}; bundled cases: "
                        + ", ".join(stems))
    return bundled


def value_label(value: Any) -> str:
    """A sweep value as a label: 6 significant digits where they give the value back
    exactly, else the shortest exact form (two values never share a label)."""
    if isinstance(value, float):
        short = f"{value:g}"
        return short if float(short) == value else repr(value)
    return str(value)


def _name(raw: dict, path: Path) -> str:
    """The case name (``name`` or the file stem): one plain file-name component, since
    it names the result directory."""
    name = raw.get("name", path.stem)
    if not NAME.fullmatch(name) or name in (".", ".."):
        raise CaseError(f"name = {name!r}: a case name must be a plain file name (letters, "
                        "digits and . _ = + -, starting with a letter or digit, at most 100 "
                        "characters)")
    return name


def _check_overrides(overrides: dict[str, Any]) -> None:
    for key in overrides:
        if key.split(".")[0] in NOT_OVERRIDABLE:
            raise CaseError(f"--set {key}: the case's {key.split('.')[0]} cannot be "
                            "overridden (edit the case file, or sweep a key with "
                            "`contact-vv sweep CASE --param KEY=V1,V2`)")


def _sweep_values(raw: dict, quick: bool, overrides: dict[str, Any]) -> list[Any]:
    """The swept values: the file's, the ``[quick]`` table's, or the one value of an
    override of the swept key; non-empty, of scalars, with distinct labels."""
    sweep = raw["sweep"]
    if "key" not in sweep or "values" not in sweep or not sweep["values"]:
        raise CaseError("sweep needs 'key' (a dotted key) and a non-empty 'values' list")
    if sweep["key"].split(".")[0] in NOT_OVERRIDABLE:
        raise CaseError(f"sweep.key = {sweep['key']!r}: a case's {sweep['key'].split('.')[0]} "
                        "cannot be swept (name, sweep and quick shape the run, not the case)")
    values, where = sweep["values"], "sweep.values"
    if quick and "sweep.values" in raw.get("quick", {}):
        values, where = raw["quick"]["sweep.values"], "quick.\"sweep.values\""
        check_value(values, [SCALAR], where)
        if not values:
            raise CaseError(f"{where}: the quick sweep needs at least one value")
    if sweep["key"] in overrides:
        values = [overrides[sweep["key"]]]  # overriding the swept key narrows the sweep
    labels = [value_label(v) for v in values]
    repeated = sorted({lab for lab in labels if labels.count(lab) > 1})
    if repeated:
        raise CaseError(f"{where}: repeated value(s) {', '.join(repeated)}")
    return values


def load_case(name_or_path: str | Path, *, quick: bool = False,
              overrides: dict[str, Any] | None = None) -> list[Case]:
    """Load a case file and return one validated Case per sweep value.

    ``quick`` applies the file's ``[quick]`` table (dotted keys, coarse grids for CI);
    ``overrides`` (dotted keys) are applied last, e.g. ``{"grid.nx": 41}``; the name,
    sweep and quick tables cannot be overridden.
    """
    path = case_path(name_or_path)
    raw = read_toml(path)
    check_types(raw, SCHEMA)
    name = _name(raw, path)
    overrides = dict(overrides or {})
    _check_overrides(overrides)
    data = copy.deepcopy({k: v for k, v in raw.items() if k not in ("sweep", "quick", "name")})
    for key in raw.get("quick", {}):
        if key.split(".")[0] in NOT_OVERRIDABLE and key != "sweep.values":
            raise CaseError(f"quick.{key!r}: the quick tier can change the case's keys and "
                            "\"sweep.values\", not its name, sweep or quick tables")
    if quick:
        for key, value in raw.get("quick", {}).items():
            if key != "sweep.values":
                set_dotted(data, key, value)
    for key, value in overrides.items():
        set_dotted(data, key, value)
    check_types(data, SCHEMA)

    if not raw.get("sweep"):
        return [build(data, name=name, source=str(path), param="")]
    sweep = raw["sweep"]
    label = sweep.get("label", sweep["key"].split(".")[-1])
    cases = []
    for value in _sweep_values(raw, quick, overrides):
        point = copy.deepcopy(data)
        set_dotted(point, sweep["key"], value)
        check_types(point, SCHEMA)
        cases.append(build(point, name=name, source=str(path),
                            param=f"{label}={value_label(value)}"))
    return cases


def load_point(name_or_path: str | Path, point: int | str = 0, *, quick: bool = False,
               overrides: dict[str, Any] | None = None) -> Case:
    """One point of a case file (:func:`load_case` gives them all): ``point`` its index,
    or its label (``"mu=0.35"``: the swept key's label and value, as results name it).
    A case without a sweep has the one point 0."""
    points = load_case(name_or_path, quick=quick, overrides=overrides)
    labels = [c.param for c in points]
    if isinstance(point, str) and point in labels:
        return points[labels.index(point)]
    if isinstance(point, int) and -len(points) <= point < len(points):
        return points[point]
    raise CaseError(f"{name_or_path}: no point {point!r}; its points are "
                    + ", ".join(f"{k} ({lab or 'no sweep'})" for k, lab in enumerate(labels)))

