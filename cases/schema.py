"""The case-file schema: every key with its type, the checks that name an offending key,
reading a TOML file into a table, and dotted-key assignment (``cases/README.md``)."""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path
from typing import Any

from .model import CaseError

SCALAR = object()  # schema type: a number, string or boolean (a sweep value)
#: a case name becomes a directory name: one plain file-name component
NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9._=+-]{0,99}")
#: keys a ``--set`` override cannot change (they shape the run, not the case)
NOT_OVERRIDABLE = ("name", "sweep", "quick")

# key -> (type, required); a table maps its keys the same way.
SCHEMA: dict[str, Any] = {
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
    "sliding_wear": {"step": float, "distance": float, "output_s": [float]},
    "fretting": {
        "amplitude": float,
        "steps_per_cycle": int,
        "cycles": int,
        "jump": float,
        "output_cycles": [int],
        "transverse": str,
    },
    "stress": {"body": str, "depth": float, "nz": int, "x0": float, "y0": float,
               "z_below": float},
    "solver": {"method": str, "tol": float, "max_iter": int, "wear_spread": float},
    "fem": {"block": float, "depth": float, "h": float, "order": int, "penalty": float,
            "h_surface": float, "contact": str},
    "tolerances": dict,
    "not_converged": dict,
    "external": dict,
    "sweep": {"key": str, "values": [SCALAR], "label": str},
    "quick": dict,
}



def read_toml(path: Path) -> dict:
    """The TOML table of a case file; CaseError naming the file for anything that is not
    readable UTF-8 TOML of reasonable nesting."""
    try:
        with open(path, "rb") as fh:
            return tomllib.load(fh)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError(f"{path}: malformed TOML: {exc}") from None
    except UnicodeDecodeError as exc:
        raise CaseError(f"{path}: not a UTF-8 text file (byte {exc.start}: "
                        f"{exc.reason})") from None
    except RecursionError:
        raise CaseError(f"{path}: nested too deeply to be a case file") from None
    except IsADirectoryError:
        raise CaseError(f"case file {path} is a directory") from None


def check_value(value: Any, expected: Any, dotted: str) -> None:
    """CaseError naming ``dotted`` unless ``value`` has the schema type ``expected``."""
    if isinstance(expected, dict):
        if not isinstance(value, dict):
            raise CaseError(f"{dotted!r} must be a table")
        check_types(value, expected, dotted + ".")
    elif isinstance(expected, list):  # a list of one element type
        if not isinstance(value, list):
            raise CaseError(f"{dotted} = {_short(value)}: must be a list")
        for k, item in enumerate(value):
            check_value(item, expected[0], f"{dotted}[{k}]")
    elif expected is SCALAR:
        if not isinstance(value, bool | int | float | str):
            raise CaseError(f"{dotted} = {_short(value)}: must be a number, string or boolean")
        if isinstance(value, float) and not math.isfinite(value):
            raise CaseError(f"{dotted} = {value!r}: must be finite")
    elif expected is float:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise CaseError(f"{dotted} = {_short(value)}: must be a number")
        if not math.isfinite(value):
            raise CaseError(f"{dotted} = {value!r}: must be finite")
    elif expected is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise CaseError(f"{dotted} = {_short(value)}: must be an integer")
    elif not isinstance(value, expected):
        raise CaseError(f"{dotted} = {_short(value)}: must be of type {expected.__name__}")


def _short(value: Any) -> str:
    """repr of a value, cut to one readable line."""
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def check_types(data: dict, schema: dict, prefix: str = "") -> None:
    for key, value in data.items():
        dotted = f"{prefix}{key}"
        if key not in schema:
            allowed = ", ".join(sorted(schema))
            raise CaseError(f"unknown key {dotted!r} (allowed here: {allowed})")
        check_value(value, schema[key], dotted)


#: tables whose keys may hold a dot themselves (``"ic-fem.p_max"``): a dotted key sets
#: everything after the table's name as one key
FLAT_TABLES = ("tolerances",)


def set_dotted(data: dict, dotted: str, value: Any) -> None:
    table, dot, rest = dotted.partition(".")
    if table in FLAT_TABLES and dot and rest:
        node = data.setdefault(table, {})
        if not isinstance(node, dict):
            raise CaseError(f"cannot set {dotted!r}: {table!r} is not a table")
        node[rest] = value
        return
    parts = dotted.split(".")
    node = data
    for part in parts[:-1]:
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise CaseError(f"cannot set {dotted!r}: {part!r} is not a table")
    node[parts[-1]] = value
