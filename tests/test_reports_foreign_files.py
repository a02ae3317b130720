"""Files the suite did not write are never altered (issue 31): a results directory holding
foreign files at any depth — beside a run's own, inside a case directory, a staging
directory or a field directory, dot-files, files named like the run's own, symbolic links
to files outside — is left byte for byte as it was by ``run``, ``sweep``, ``threshold``,
``report`` and ``gate``, and by the links' targets.  A command that would have to replace
a foreign file refuses (exit 2, the path named); the others leave it alone.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import pytest
from test_cli_hostile_inputs import TINY, _answer

from reports.store import layout

CASE = TINY + "[friction]\nmu = 0.2\n"


def snapshot(root: Path) -> dict[str, tuple[str, object]]:
    """Every entry below ``root``, links not followed: a file's bytes, a link's target."""
    out: dict[str, tuple[str, object]] = {}
    for folder, dirs, files in os.walk(root, followlinks=False):
        for name in dirs + files:
            p = Path(folder) / name
            key = str(p.relative_to(root))
            if p.is_symlink():
                out[key] = ("link", os.readlink(p))
            elif p.is_dir():
                out[key] = ("dir", None)
            else:
                out[key] = ("file", p.read_bytes())
    return out


@pytest.fixture(scope="module")
def pristine(tmp_path_factory) -> Path:
    """A results directory with case ``c`` (ic, analytic and the relations, quick)."""
    root = tmp_path_factory.mktemp("foreign")
    (root / "c.toml").write_text(CASE)
    code = _run(["run", str(root / "c.toml"), "--quick", "--solver", "ic,analytic",
                 "--no-progress", "--out", str(root / "out")])
    assert code == 0
    return root


def _run(argv: list[str]) -> int:
    from reports.cli import main

    return main(argv)


@pytest.fixture
def world(pristine, tmp_path) -> Path:
    """A copy of the results beside ``outside/`` (the targets of the links)."""
    shutil.copytree(pristine, tmp_path / "w", symlinks=True)
    outside = tmp_path / "w" / "outside"
    outside.mkdir()
    (outside / "target.txt").write_text("the user's file")
    (outside / "dir").mkdir()
    (outside / "dir" / "kept.txt").write_text("kept")
    return tmp_path / "w"


def _link(path: Path, target: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.symlink_to(target)


# (id, what to put where: path below out -> text, or ("link", target below the world))
FOREIGN = [
    ("fields-notes", {"c/fields/notes.txt": "mine"}),
    ("case-dot-file", {"c/.notes": "mine"}),
    ("case-subdir", {"c/mine/data.txt": "mine"}),
    ("unit-readme", {"c/fields/ic/base/readme.md": "mine"}),
    ("unit-lookalike-dir", {"c/fields/ic/base/step_0009.npz/x": "mine"}),
    ("solver-file", {"c/fields/ic/notes": "mine"}),
    ("link-as-step", {"c/fields/ic/base/step_0009.npz": ("link", "outside/target.txt")}),
    ("link-as-summary", {"c/summary.csv.bak": ("link", "outside/target.txt")}),
    ("link-dir-as-unit", {"c/fields/ic/mu=9": ("link", "outside/dir")}),
    ("link-as-fields", {"c/fields": ("link", "outside/dir")}),
    ("link-as-case", {"c": ("link", "outside/dir")}),
    ("lock-link", {".c.lock": ("link", "outside/target.txt")}),
    ("lock-dangling-link", {".c.lock": ("link", "outside/absent.txt")}),
    ("lock-dir", {".c.lock/x": "mine"}),
    ("staging-notes", {".c.partial/notes.txt": "mine"}),
    ("staging-dot-file", {".c.partial/.keep": "mine"}),
    ("staging-link", {".c.partial": ("link", "outside/dir")}),
    ("staging-deep", {".c.partial/fields/ic/base/x.txt": "mine"}),
]


def _plant(world: Path, items: dict) -> list[str]:
    out = world / "out"
    for rel, what in items.items():
        p = out / rel
        if p.is_symlink() or p.is_file():
            p.unlink()
        elif p.is_dir() and isinstance(what, tuple):
            shutil.rmtree(p)
        if isinstance(what, tuple):
            _link(p, world / what[1])
        else:
            if p.parent.is_file():  # e.g. the lock file a run left, made a directory
                p.parent.unlink()
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_text(what)
    return list(items)


@pytest.mark.parametrize("items", [f[1] for f in FOREIGN], ids=[f[0] for f in FOREIGN])
def test_a_run_refuses_to_replace_what_it_did_not_write(world, capsys, items):
    _plant(world, items)
    before = snapshot(world)
    code, err = _answer(["run", str(world / "c.toml"), "--quick", "--solver", "ic",
                         "--no-progress", "--out", str(world / "out")], capsys)
    assert code == 2, err
    assert err.startswith("contact-vv: error:") and str(world / "out") in err, err
    assert snapshot(world) == before


def test_a_run_replaces_its_own_result_and_a_crashed_runs_temporaries(world, capsys):
    """The ownership check is not a refusal of everything: the run's own files, with the
    temporaries an interrupted atomic write leaves, are replaced."""
    out = world / "out"
    for folder, name in ((out / "c", layout.SUMMARY),
                         (out / "c" / layout.FIELDS / "ic" / "base", "step_0000.npz")):
        fd, _ = tempfile.mkstemp(prefix=f".{name}.", suffix=".part", dir=folder)  # as
        os.close(fd)  # cases.result.atomic_path names them
    (out / "c" / ".notes.txt.abcdefgh.part").write_text("mine")  # not a temporary of ours
    code, err = _answer(["run", str(world / "c.toml"), "--quick", "--solver", "ic",
                         "--no-progress", "--out", str(out)], capsys)
    assert code == 2 and ".notes.txt.abcdefgh.part is not a file a run writes" in err, err
    (out / "c" / ".notes.txt.abcdefgh.part").unlink()
    code, err = _answer(["run", str(world / "c.toml"), "--quick", "--solver", "ic",
                         "--no-progress", "--out", str(out)], capsys)
    assert code == 0, err
    assert not list((out / "c").rglob("*.part"))


def test_every_command_leaves_foreign_files_byte_for_byte(world, capsys):
    """All the foreign files at once (but those that make ``run`` refuse, which the test
    above covers), then every command: the foreign entries and the links' targets are as
    they were; what the commands write is their own."""
    out = world / "out"
    planted = _plant(world, {
        "notes.txt": "mine", ".hidden/x": "mine", "sub/dir/deep.txt": "mine",
        "link-out": ("link", "outside/target.txt"), "link-dir": ("link", "outside/dir"),
        "c__sweep_mu": ("link", "outside/dir"),  # where the sweep would write
        ".thresholds.csv.lock": ("link", "outside/target.txt"),
    })
    before = snapshot(world)
    foreign = {k: v for k, v in before.items()
               if k.startswith("outside") or any(k.startswith(f"out/{p}") for p in planted)}
    runs = [
        (["run", str(world / "c.toml"), "--quick", "--solver", "ic,analytic", "--no-progress",
          "--out", str(out)], 0),
        (["sweep", str(world / "c.toml"), "--param", "friction.mu=0.2,0.3", "--workers", "0",
          "--solver", "ic", "--no-progress", "--out", str(out)], 2),  # c__sweep_mu is a link
        (["threshold", "sliding_friction", "--param", "friction.mu", "--event",
          "vm_max_on_surface", "--quick", "--solver", "analytic", "--grids", "1", "--range",
          "0.2", "0.4", "--resolution", "0.1", "--no-progress", "--out", str(out)], 2),  # lock
        (["report", "--out", str(out)], 0),
        (["gate", "--out", str(out)], 1),  # 11 x 11 cells: p_max beyond its tolerance
        (["gate", "--out", str(out), "--update-baseline", str(world / "baselines")], 0),
        (["gate", "--out", str(out), "--baseline", str(world / "baselines")], 1),
    ]
    for argv, expected in runs:
        code, err = _answer(argv, capsys)
        assert code == expected, (argv, err)
    after = snapshot(world)
    assert {k: after.get(k) for k in foreign} == foreign


@pytest.mark.parametrize("where", ["out/c", "out/c/fields", "out", "out/new"])
def test_baselines_are_never_written_into_the_results(world, capsys, where):
    before = snapshot(world)
    code, err = _answer(["gate", "--out", str(world / "out"), "--update-baseline",
                         str(world / where)], capsys)
    assert code == 2 and "inside the results directory" in err, err
    assert snapshot(world) == before


@pytest.mark.parametrize("content", ["c.csv is my spreadsheet\n", "case,solver\nx,y\n", ""])
def test_a_baseline_folder_file_that_is_not_a_baseline_is_not_replaced(world, capsys,
                                                                        content):
    folder = world / "baselines"
    folder.mkdir()
    (folder / "c.csv").write_text(content)
    code, err = _answer(["gate", "--out", str(world / "out"), "--update-baseline",
                         str(folder)], capsys)
    assert code == 2 and "exists and is not a baseline" in err, err
    assert (folder / "c.csv").read_text() == content


@pytest.mark.parametrize("plant", [
    lambda p: p.write_text("<html><title>my page</title></html>"),
    lambda p: p.write_bytes(b"\x00\x01binary"),
    lambda p: p.symlink_to(p.parent.parent / "outside" / "target.txt"),
    lambda p: p.mkdir(),
])
def test_a_report_does_not_replace_a_page_it_did_not_write(world, capsys, plant):
    page = world / "out" / layout.REPORT
    plant(page)
    before = snapshot(world)
    code, err = _answer(["report", "--out", str(world / "out")], capsys)
    assert code == 2 and str(page) in err, err
    assert snapshot(world) == before


def test_a_report_replaces_its_own_page(world, capsys):
    assert _answer(["report", "--out", str(world / "out")], capsys)[0] == 0
    assert _answer(["report", "--out", str(world / "out")], capsys)[0] == 0


@pytest.mark.parametrize("plant", [
    lambda p, w: p.symlink_to(w / "outside" / "target.txt"),
    lambda p, w: p.symlink_to(w / "outside" / "absent.csv"),
    lambda p, w: p.mkdir(),
])
def test_a_threshold_table_that_is_not_a_file_is_not_replaced(world, capsys, plant):
    table = world / "out" / layout.THRESHOLDS
    plant(table, world)
    before = snapshot(world)
    code, err = _answer(["threshold", "sliding_friction", "--param", "friction.mu", "--event",
                         "vm_max_on_surface", "--quick", "--solver", "analytic", "--grids",
                         "1", "--range", "0.2", "0.4", "--resolution", "0.1", "--no-progress",
                         "--out", str(world / "out")], capsys)
    assert code == 2 and str(table) in err, err
    assert snapshot(world) == before
