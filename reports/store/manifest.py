"""The run manifest (written last) and the provenance it records.

A case directory is *complete* when its ``manifest.json`` exists, says
``"complete": true`` and every file it lists still has the recorded SHA-256.  ``report``
and ``gate`` trust nothing else.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import importlib.metadata
import json
import math
import os
import platform
import subprocess
import sys
from pathlib import Path
from typing import Any

from cases.result import atomic_write_text
from reports.registry.errors import IncompleteRun
from reports.store import layout
from reports.store.readers import JSON_NAMES, Malformed, json_kind, read_json, read_result

FORMAT = "contact-vv-run/1"
_PACKAGES = (
    "contact-vv", "numpy", "scipy", "pandas", "matplotlib", "tqdm", "meshio",
    "scikit-fem", "gmsh", "pypardiso", "dask", "distributed",
)
THREAD_VARS = (
    "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS",
)




def sha256_file(path: str | Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def versions() -> dict[str, str]:
    """Installed versions of the packages a result depends on (absent ones omitted)."""
    out = {"python": platform.python_version()}
    for name in _PACKAGES:
        try:
            out[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            continue
    return out


def threads() -> dict[str, Any]:
    """The thread settings that can change floating-point results."""
    info: dict[str, Any] = {"cpu_count": os.cpu_count()}
    for var in THREAD_VARS:
        if var in os.environ:
            info[var] = os.environ[var]
    try:
        from threadpoolctl import threadpool_info
    except ImportError:
        pass
    else:
        info["threadpools"] = [
            {k: p.get(k) for k in ("internal_api", "num_threads", "version")}
            for p in threadpool_info()
        ]
    return info


def git_state(where: Path | None = None) -> dict[str, Any]:
    """Commit and dirtiness of the repository holding this package (None outside git)."""
    where = where or Path(__file__).resolve().parents[2]

    def git(*args: str) -> str | None:
        try:
            proc = subprocess.run(
                ["git", *args], cwd=where, capture_output=True, text=True, timeout=10
            )
        except (OSError, subprocess.SubprocessError):
            return None
        return proc.stdout.strip() if proc.returncode == 0 else None

    commit = git("rev-parse", "HEAD")
    status = git("status", "--porcelain", "--untracked-files=no") if commit else None
    return {"commit": commit, "dirty": bool(status) if status is not None else None}


#: packages whose source code determines the numbers of a run
SOURCE_PACKAGES = ("halfspace", "fem_reference", "cases", "reports")


def source_hashes(root: Path | None = None) -> dict[str, str]:
    """SHA-256 over the Python sources of each package (uncommitted edits included)."""
    root = root or Path(__file__).resolve().parents[2]
    out = {}
    for package in SOURCE_PACKAGES:
        h = hashlib.sha256()
        files = sorted((root / package).rglob("*.py"))
        for f in files:
            h.update(f.relative_to(root).as_posix().encode())
            h.update(f.read_bytes())
        if files:
            out[package] = h.hexdigest()
    return out


def provenance() -> dict[str, Any]:
    """Date, git state, versions, threads and host of the current process."""
    return {
        "date": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "git": git_state(),
        "versions": versions(),
        "threads": threads(),
        "host": {"platform": platform.platform(), "machine": platform.machine()},
        "command": list(sys.argv),
    }


def file_hashes(root: Path) -> dict[str, str]:
    """SHA-256 of every regular file under ``root`` (relative POSIX paths), sorted."""
    root = Path(root)
    return {
        p.relative_to(root).as_posix(): sha256_file(p)
        for p in sorted(root.rglob("*"))
        if p.is_file() and p.name != layout.MANIFEST and not p.name.startswith(".")
    }


def write(root: Path, manifest: dict[str, Any]) -> None:
    """Hash every file under ``root`` and write the manifest atomically, marked complete."""
    body = dict(manifest, format=FORMAT, complete=True, files=file_hashes(root))
    atomic_write_text(Path(root) / layout.MANIFEST, json.dumps(body, indent=1, default=str))


#: what a manifest value must be, by key (absent keys are allowed; ``files`` is required)
_NUMBER = (int, float)
_TYPES: dict[str, tuple[type, ...]] = {
    "case": (str,), "dir": (str,), "kind": (str,), "description": (str,),
    "case_file": (str,), "case_sha256": (str, type(None)), "quick": (bool,),
    "overrides": (dict, type(None)), "params": (list,), "points": (list,),
    "solvers": (list,), "skipped": (dict,), "not_run": (dict,), "units": (list,),
    "wall_s": _NUMBER,
    "unit_wall_s": _NUMBER, "provenance": (dict,), "sources": (dict, type(None)),
    "sources_changed_during_run": (bool,), "files": (dict,),
}
#: keys of the items of list- or dict-valued entries, with their types
_ITEMS: dict[str, dict[str, tuple[type, ...]]] = {
    "points": {"param": (str,), "hertz_a0": _NUMBER, "hertz_p0": _NUMBER},
    "units": {"solver": (str,), "param": (str,), "wall_s": _NUMBER},
    "provenance": {"git": (dict,), "versions": (dict,), "threads": (dict,),
                   "command": (list,)},
}
#: item keys that are scales (divided by): positive finite numbers
_POSITIVE = frozenset({"hertz_a0", "hertz_p0"})
#: files a later command may add beside a complete run (views, not results)
ADDED_AFTER = frozenset({layout.SWEEP_PLOT, layout.SWEEP_CHECK})


def _type_name(types: tuple[type, ...]) -> str:
    return " or ".join(dict.fromkeys(JSON_NAMES.get(t, t.__name__) for t in types))


def _is(value: Any, types: tuple[type, ...]) -> bool:
    return isinstance(value, types) and not (isinstance(value, bool) and bool not in types)


def check_schema(body: Any) -> list[str]:
    """What is wrong with the structure of a manifest (empty if nothing)."""
    if not isinstance(body, dict):
        return [f"not a JSON object ({json_kind(body)})"]
    wrong = []
    if "files" not in body:
        wrong.append("no files")
    for key, types in _TYPES.items():
        if key in body and not _is(body[key], types):
            wrong.append(f"{key} is not {_type_name(types)}")
    prov = body.get("provenance")
    for key in ("params", "solvers", "command"):
        items = body.get(key) if key != "command" else \
            prov.get(key) if isinstance(prov, dict) else None
        if isinstance(items, list) and not all(isinstance(v, str) for v in items):
            wrong.append(f"{key} is not a list of strings")
    for key in ("files", "sources"):
        if isinstance(body.get(key), dict) and not all(
                isinstance(v, str) for v in body[key].values()):
            wrong.append(f"{key} does not map names to strings")
    for key, fields in _ITEMS.items():
        value = body.get(key)
        listed = isinstance(value, list) and list in _TYPES[key]
        items = value if listed else [value] if isinstance(value, dict) else []
        for i, item in enumerate(items):
            where = f"{key}[{i}]" if listed else key
            if not isinstance(item, dict):
                wrong.append(f"{where} is not an object")
                continue
            for name, types in fields.items():
                required = key == "units"  # the report tabulates these three
                if (name in item or required) and not _is(item.get(name), types):
                    wrong.append(f"{where}.{name} is not {_type_name(types)}")
                elif name in _POSITIVE and name in item and not (
                        math.isfinite(item[name]) and item[name] > 0):
                    wrong.append(f"{where}.{name} is {item[name]!r}, not a positive number")
    for rel in body.get("files", {}) if isinstance(body.get("files"), dict) else ():
        parts = rel.split("/")
        if not rel or rel.startswith("/") or "\\" in rel or ".." in parts or "" in parts:
            wrong.append(f"files lists {rel!r}, a path outside the case directory")
    return wrong


def read(case_dir: Path, *, verify: bool = True) -> dict[str, Any]:
    """The manifest of a complete case directory; :class:`IncompleteRun` otherwise
    (:class:`reports.store.readers.DamagedResult`, a subclass, if the manifest cannot be read
    or is not shaped as a run writes it).

    ``verify``: every file it lists must exist with the recorded SHA-256, and every file
    of the directory must be listed (except dot files and :data:`ADDED_AFTER`).
    """

    def parse(p: Path) -> dict[str, Any]:
        body = read_json(p)
        wrong = check_schema(body)
        if wrong:
            raise Malformed("not a run manifest: " + "; ".join(wrong[:3])
                            + (f" (and {len(wrong) - 3} more)" if len(wrong) > 3 else ""))
        return body

    case_dir = Path(case_dir)
    path = case_dir / layout.MANIFEST
    if not path.exists() and not path.is_symlink():
        raise IncompleteRun(f"{case_dir}: no {layout.MANIFEST} (interrupted or not a run)")
    manifest = read_result(path, parse)
    if manifest.get("format") != FORMAT or manifest.get("complete") is not True:
        raise IncompleteRun(f"{path}: manifest not marked complete")
    if verify:
        files = manifest["files"]
        for rel, digest in files.items():
            f = case_dir / rel
            if not f.is_file():
                raise IncompleteRun(f"{case_dir}: {rel} listed in the manifest is "
                                    + ("missing" if not f.exists() else "not a regular file"))
            if sha256_file(f) != digest:
                raise IncompleteRun(f"{case_dir}: {rel} changed after the run (hash mismatch)")
        for f in sorted(case_dir.rglob("*")):
            rel = f.relative_to(case_dir).as_posix()
            if (f.is_file() and rel not in files and rel != layout.MANIFEST
                    and rel not in ADDED_AFTER and not f.name.startswith(".")):
                raise IncompleteRun(f"{case_dir}: {rel} is not listed in the manifest "
                                    "(added after the run)")
    return manifest
