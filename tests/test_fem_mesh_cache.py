"""The mesh cache never changes a number (fem_reference/model/mesh.py): an entry swapped
with another key's, truncated, of garbage, edited, or in a cache that cannot be written
is discarded with one line and meshed again, bit-identical to a clean cache."""

from __future__ import annotations

import errno

import numpy as np
import pytest

from fem_reference.model import mesh
from fem_reference.model.mesh import MeshSpec, build_points, cache_dir

A = MeshSpec("half", 5.0, 5.0, 0.5, 1.5, 1.0, h_max=1.5)
B = MeshSpec("half", 5.0, 5.0, 0.6, 1.5, 1.0, h_max=1.5)


def entry(spec: MeshSpec):
    return cache_dir() / f"block-{spec.key()}.npz"


@pytest.fixture
def clean(tmp_path, monkeypatch):
    """The clean-cache meshes of A and B, and a cache holding both entries."""
    monkeypatch.setenv("CONTACT_VV_CACHE", str(tmp_path))
    return {A: build_points(A, use_cache=False), B: build_points(B, use_cache=False)}


def same(got, want) -> bool:
    return all(np.array_equal(g, w) and g.dtype == w.dtype for g, w in zip(got, want, strict=True))


def test_entries_swapped_on_disk_are_rebuilt(clean, capsys):
    build_points(A), build_points(B)
    a, b = entry(A), entry(B)
    tmp = a.with_suffix(".swap")
    a.rename(tmp), b.rename(a), tmp.rename(b)
    assert same(build_points(A), clean[A]) and same(build_points(B), clean[B])
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and all("another mesh's key" in line for line in err)
    assert str(a) in err[0] and str(b) in err[1]
    capsys.readouterr()
    assert same(build_points(A), clean[A])  # the rebuilt entry is trusted again
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("damage", ["truncated", "garbage", "nodes moved", "old format",
                                    "a directory"])
def test_a_damaged_entry_is_discarded_once(clean, capsys, damage):
    build_points(A)
    path = entry(A)
    if damage == "truncated":
        path.write_bytes(path.read_bytes()[:len(path.read_bytes()) // 2])
    elif damage == "garbage":
        path.write_bytes(b"\x00garbage" * 64)
    elif damage == "nodes moved":
        with np.load(path) as data:
            arrays = dict(data)
        arrays["points"] = arrays["points"] * 1.05
        np.savez(path, **arrays)
    elif damage == "old format":  # the entries written before they held their key
        np.savez(path, points=clean[A][0], tets=clean[A][1])
    else:
        path.unlink()
        path.mkdir()
    assert same(build_points(A), clean[A])
    err = capsys.readouterr().err.splitlines()
    assert len(err) == (2 if damage == "a directory" else 1)
    assert "discarded" in err[0] and str(path) in err[0]
    if damage != "a directory":
        assert same(build_points(A), clean[A]) and capsys.readouterr().err == ""


def test_a_read_only_cache_meshes_in_memory_and_says_so(clean, capsys, monkeypatch):
    build_points(A)
    path = entry(A)
    path.write_bytes(b"garbage")

    def read_only(*args, **kwargs):
        raise OSError(errno.EROFS, "Read-only file system")

    monkeypatch.setattr(mesh, "atomic_path", read_only)
    monkeypatch.setattr(type(path), "unlink", read_only)
    for _ in range(2):  # every run meshes again: the entry cannot be replaced
        assert same(build_points(A), clean[A])
        err = capsys.readouterr().err.splitlines()
        assert len(err) == 2 and "discarded" in err[0]
        assert "not written (Read-only file system)" in err[1]
    assert path.read_bytes() == b"garbage"


def test_an_entry_holds_its_key_and_checksum(clean):
    build_points(A)
    with np.load(entry(A)) as data:
        assert str(data["key"]) == A.payload()
        assert str(data["sha256"]) == mesh.digest(data["points"], data["tets"])
    assert mesh.digest(*clean[A]) != mesh.digest(clean[A][0] * (1 + 1e-15), clean[A][1])
