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
import os
import platform
import subprocess
import sys
from pathlib import Path
from typing import Any

from cases.result import atomic_write_text

from . import layout

FORMAT = "contact-vv-run/1"
_PACKAGES = (
    "contact-vv", "numpy", "scipy", "pandas", "matplotlib", "tqdm", "meshio",
    "scikit-fem", "gmsh", "pypardiso", "dask", "distributed",
)
THREAD_VARS = (
    "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMEXPR_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS",
)


class IncompleteRun(Exception):
    """A case directory whose manifest is missing, incomplete or contradicted by its files."""


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
    where = where or Path(__file__).resolve().parent.parent

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
    root = root or Path(__file__).resolve().parent.parent
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


def read(case_dir: Path, *, verify: bool = True) -> dict[str, Any]:
    """The manifest of a complete case directory; :class:`IncompleteRun` otherwise."""
    path = Path(case_dir) / layout.MANIFEST
    if not path.is_file():
        raise IncompleteRun(f"{case_dir}: no {layout.MANIFEST} (interrupted or not a run)")
    try:
        manifest = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as exc:
        raise IncompleteRun(f"{path}: unreadable manifest ({exc})") from None
    if manifest.get("format") != FORMAT or manifest.get("complete") is not True:
        raise IncompleteRun(f"{path}: manifest not marked complete")
    if verify:
        for rel, digest in manifest.get("files", {}).items():
            f = Path(case_dir) / rel
            if not f.is_file():
                raise IncompleteRun(f"{case_dir}: {rel} listed in the manifest is missing")
            if sha256_file(f) != digest:
                raise IncompleteRun(f"{case_dir}: {rel} changed after the run (hash mismatch)")
    return manifest
