"""Ways to damage a results directory, for tests/test_reports_damaged_results.py: each edits
one file of a copied case as a disk fault, a hand edit or a hostile user would."""

from __future__ import annotations

import io
import json
import shutil
import zipfile
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pandas as pd

from reports.store import manifest


def rehash(case: Path) -> None:
    """Rewrite the manifest's file hashes as a run would have (the damage is 'trusted')."""
    mf = json.loads((case / "manifest.json").read_text())
    manifest.write(case, {k: v for k, v in mf.items() if k not in ("files", "format",
                                                                     "complete")})


def edit_manifest(case: Path, change: Callable[[dict], object]) -> None:
    mf = json.loads((case / "manifest.json").read_text())
    change(mf)
    (case / "manifest.json").write_text(json.dumps(mf))


def edit_csv(path: Path, change: Callable[[pd.DataFrame], object]) -> None:
    """Rewrite a CSV (as text) through ``change``, which edits the frame or returns a new
    one."""
    frame = pd.read_csv(path, dtype=object, keep_default_na=False)
    new = change(frame)
    (frame if new is None else new).to_csv(path, index=False)


def npz(case: Path, solver: str = "ic") -> Path:
    return case / "fields" / solver / "base" / "step_0000.npz"


def to_dir(path: Path, *, filled: bool = True) -> None:
    if path.is_dir():
        shutil.rmtree(path)
    elif path.exists():
        path.unlink()
    path.mkdir()
    if filled:
        (path / "x").write_text("a directory where a file should be")


def set_metric(frame: pd.DataFrame, quantity: str, **values: str) -> None:
    row = frame.index[frame["quantity"] == quantity][0]
    for k, v in values.items():
        frame.loc[row, k] = v


def metric_edit(quantity: str, **values: str) -> Callable[[Path], None]:
    """A damage of a case: the metrics.csv row of ``quantity`` given ``values``."""
    return lambda case: edit_csv(case / "metrics.csv",
                                 lambda f: set_metric(f, quantity, **values))


def truncated(path: Path) -> None:
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])


def bad_crc(path: Path) -> None:
    data = bytearray(path.read_bytes())
    data[len(data) // 2] ^= 0xFF
    path.write_bytes(bytes(data))


def edit_npz(path: Path, change: Callable[[dict[str, np.ndarray]], object]) -> None:
    with np.load(path) as d:
        arrays = {k: d[k] for k in d.files}
    change(arrays)
    with open(path, "wb") as fh:
        np.savez_compressed(fh, **arrays)


def wrong_shape(path: Path) -> None:
    edit_npz(path, lambda a: a.__setitem__("surface/p_n", a["surface/p_n"][:-1]))


def huge_array(path: Path) -> None:
    """An .npy header claiming 7 TiB of data."""
    buf = io.BytesIO()
    np.lib.format.write_array_header_1_0(
        buf, {"descr": "<f8", "fortran_order": False, "shape": (10**12,)})
    buf.write(b"\0" * 64)
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("scalars.npy", buf.getvalue())
        z.writestr("x.npy", buf.getvalue())
