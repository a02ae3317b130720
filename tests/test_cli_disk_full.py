"""A disk that fills during a run (issue 77, point 6 and the full-disk probe): the run
ends with a line saying the disk is full — not that a solver crashed — exit 1, earlier
results intact, and no ``.<case>.partial`` left where the disk allows removing it; the
``.<case>.old-<pid>`` a killed rerun left is removed by the next run of the case, unless
it holds a file no run writes.  Found by these probes: "solver ic crashed: OSError:
[Errno 28]", the staging directories left behind, and the old copies nothing removed."""

from __future__ import annotations

import errno
import shutil
from pathlib import Path

import pytest
from test_cli_hostile_inputs import TINY, _answer

from reports.run import runner, units


def _full(*args, **kwargs):
    raise OSError(errno.ENOSPC, "No space left on device")


@pytest.fixture
def world(tmp_path):
    for name in ("a", "b"):
        (tmp_path / f"{name}.toml").write_text(f'name = "{name}"\n' + TINY)
    return tmp_path


def _run(world: Path, capsys, *names: str) -> tuple[int, str]:
    return _answer(["run", *(str(world / f"{n}.toml") for n in names), "--solver",
                    "ic,analytic", "--no-progress", "--out", str(world / "out")], capsys)


def _tree(out: Path) -> dict[str, bytes]:
    return {str(p.relative_to(out)): p.read_bytes() for p in out.rglob("*") if p.is_file()}


@pytest.mark.parametrize("where", ["streaming a step", "writing the unit", "failed.json",
                                   "the tables"])
def test_a_full_disk_is_said_and_leaves_no_partial(world, capsys, monkeypatch, where):
    assert _run(world, capsys, "a")[0] in (0, 1)
    out = world / "out"
    before = _tree(out / "a")
    if where == "streaming a step":
        monkeypatch.setattr(units, "save_step", _full)
    elif where == "writing the unit":
        monkeypatch.setattr(runner, "write_unit", _full)
    elif where == "the tables":
        monkeypatch.setattr(runner, "write_csv", _full)
    else:  # a solver that fails, then a disk that cannot take its failed.json
        monkeypatch.setattr(units, "save_step", lambda *a: (_ for _ in ()).throw(
            RuntimeError("did not converge")))
        monkeypatch.setattr(runner, "atomic_write_text", _full)
    code, err = _run(world, capsys, "b")
    assert code == 1, err
    if where == "the tables":
        assert "b: the disk is full: the case's tables could not be written (No space " \
            "left on device)" in err, err
    elif where != "failed.json":
        assert "b: the disk is full: solver ic's results could not be written (No space " \
            "left on device)" in err and "crashed" not in err, err
    assert "b: nothing written (its partial results removed)" in err, err
    assert sorted(p.name for p in out.iterdir()) == ["a"]  # no .b.partial, no lock
    assert _tree(out / "a") == before


def test_what_a_killed_rerun_left_is_removed_by_the_next_run(world, capsys):
    assert _run(world, capsys, "a")[0] in (0, 1)
    out = world / "out"
    shutil.copytree(out / "a", out / ".a.old-12345")  # remove_dir killed mid-way
    shutil.copytree(out / "a" / "fields", out / "..a.partial.old-777" / "fields")
    foreign = out / ".a.old-999"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("mine")
    assert _run(world, capsys, "a")[0] in (0, 1)
    assert sorted(p.name for p in out.iterdir()) == [".a.old-999", "a"]
    assert (foreign / "notes.txt").read_text() == "mine"
