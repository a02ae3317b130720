"""Hostile inputs to ``run``, ``sweep``, ``report`` and ``gate``: every one gets a clear
one-line ``contact-vv: error: …`` naming the key, file or cause and the documented exit
status (2 user error, 1 solver or result problem), or a correct result — never a
traceback, never a hang, never an allocation past the limit, and nothing outside the
case's own directories touched.  Damaged result directories: tests/test_reports_damaged_results.py.
"""

from __future__ import annotations

import os
import signal
from pathlib import Path

import pytest
from test_cli_run import HERTZ

from reports.cli import main
from reports.store import layout

TINY = HERTZ.replace("Lx = 1.6\nnx = 21", "Lx = 1.6\nLy = 1.6\nnx = 11\nny = 11").replace(
    "nz = 11", "nz = 5")
WEAR = TINY.replace('kind = "static"', 'kind = "sliding_wear"') + """[friction]
mu = 0.3
[sliding_wear]
step = 1.0
distance = 2.0
"""
FRET = TINY.replace('kind = "static"', 'kind = "fretting"').replace(
    "P = 10.2", "approach = 0.001") + """[friction]
mu = 0.3
[fretting]
amplitude = 0.001
steps_per_cycle = 4
cycles = 2
jump = 1.0
"""
SWEEP = TINY + """[friction]
mu = 0.2
[sweep]
key = "friction.mu"
values = [0.2, 0.3]
"""


def _set(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


# (id, case-file text or bytes, extra argv, expected exit, needle in the error)
CASE_FILES = [
    ("not-utf8", b"\xff\xfe\x00 kind", [], 2, "not a UTF-8 text file"),
    ("binary", bytes(range(256)) * 4, [], 2, "not a UTF-8 text file"),
    ("nul-bytes", b"kind = \"static\"\x00\x00", [], 2, "malformed TOML"),
    ("empty-file", b"", [], 2, "materials.a is required"),
    ("deep-arrays", "x = " + "[" * 5000 + "]" * 5000 + "\n", [], 2, "nested too deeply"),
    ("deep-tables", "x = " + "{a = " * 800 + "1" + "}" * 800 + "\n", [], 2, ""),
    ("unknown-top-key", "colour = 1\n" + TINY, [], 2, "unknown key 'colour'"),
    ("table-as-number", "geometry = 5\n" + TINY.replace("[geometry]\nR = 50.0\n", ""), [], 2,
     "'geometry' must be a table"),
    ("string-number", _set(TINY, "R = 50.0", 'R = "50"'), [], 2, "geometry.R = '50'"),
    ("list-number", _set(TINY, "R = 50.0", "R = [50.0]"), [], 2, "geometry.R = [50.0]"),
    ("bool-number", _set(TINY, "nx = 11", "nx = true"), [], 2, "grid.nx = True"),
    ("nan", _set(TINY, "R = 50.0", "R = nan"), [], 2, "geometry.R = nan: must be finite"),
    ("inf", _set(TINY, "P = 10.2", "P = inf"), [], 2, "load.P = inf: must be finite"),
    ("negative-E", _set(TINY, "E = 210000.0", "E = -1.0"), [], 2, "materials.a.E"),
    ("zero-R", _set(TINY, "R = 50.0", "R = 0.0"), [], 2, "geometry.R"),
    ("nu-half", _set(TINY, "nu = 0.3", "nu = 0.5"), [], 2, "materials.a.nu = 0.5"),
    ("nu-minus-one", _set(TINY, "nu = 0.3", "nu = -1.0"), [], 2, "materials.a.nu"),
    ("tiny-grid", _set(TINY, "nx = 11", "nx = 2"), [], 2, "grid.nx = 2"),
    ("grid-too-small", _set(TINY, "Lx = 1.6", "Lx = 0.2"), [], 2, "grid.Lx = 0.2"),
    ("no-load", TINY.replace("[load]\nP = 10.2\n", ""), [], 2, "[load] is required"),
    ("load-and-approach", _set(TINY, "P = 10.2", "P = 10.2\napproach = 0.001"), [], 2,
     "exactly one of load.P"),
    ("nz-one", _set(TINY, "nz = 5", "nz = 1"), [], 2, "stress.nz = 1"),
    ("nz-huge", _set(TINY, "nz = 5", "nz = 100000000"), [], 2, "reduce stress.nz"),
    ("grid-huge", _set(TINY, "nx = 11\nny = 11", "nx = 300000\nny = 300000"), [], 2,
     "GiB"),
    ("body-c", _set(TINY, "nz = 5", 'nz = 5\nbody = "c"'), [], 2, "stress.body = 'c'"),
    ("method-x", TINY + '[solver]\nmethod = "x"\n', [], 2, "solver.method = 'x'"),
    ("max-iter-0", TINY + "[solver]\nmax_iter = 0\n", [], 2, "solver.max_iter = 0"),
    ("tol-negative", TINY + "[solver]\ntol = -1e-8\n", [], 2, "solver.tol"),
    ("kind-x", _set(TINY, 'kind = "static"', 'kind = "dynamic"'), [], 2, "kind = 'dynamic'"),
    ("name-dot", 'name = "."\n' + TINY, [], 2, "name = '.'"),
    ("name-dotdot", 'name = ".."\n' + TINY, [], 2, "name = '..'"),
    ("name-slash", 'name = "a/b"\n' + TINY, [], 2, "name = 'a/b'"),
    ("name-absolute", 'name = "/tmp/x"\n' + TINY, [], 2, "name = '/tmp/x'"),
    ("name-empty", 'name = ""\n' + TINY, [], 2, "name = ''"),
    ("name-hidden", 'name = ".git"\n' + TINY, [], 2, "name = '.git'"),
    ("name-long", f'name = "{"n" * 300}"\n' + TINY, [], 2, "a case name must be"),
    ("tolerance-string", TINY + '[tolerances]\np_max = "x"\n', [], 2, "tolerances.p_max"),
    ("tolerance-negative", TINY + "[tolerances]\np_max = -0.1\n", [], 2, "tolerances.p_max"),
    ("tolerance-unknown", TINY + "[tolerances]\nfoo = 0.1\n", [], 2, "unknown tolerance key"),
    ("tolerance-pair", TINY + '[tolerances]\n"ic-ic.p_max" = 0.1\n', [], 2,
     "is not a compared pair"),
    ("sweep-no-values", TINY + '[sweep]\nkey = "friction.mu"\nvalues = []\n', [], 2,
     "non-empty 'values'"),
    ("sweep-key-number", TINY + "[sweep]\nkey = 3\nvalues = [1]\n", [], 2, "sweep.key = 3"),
    ("sweep-nested-list", TINY + '[sweep]\nkey = "grid.nx"\nvalues = [[11, 13]]\n', [], 2,
     "sweep.values[0] = [11, 13]"),
    ("sweep-table-value", TINY + '[sweep]\nkey = "grid.nx"\nvalues = [{a = 1}]\n', [], 2,
     "sweep.values[0]"),
    ("sweep-string-value", TINY + '[sweep]\nkey = "grid.nx"\nvalues = ["a"]\n', [], 2,
     "grid.nx = 'a'"),
    ("sweep-repeated", _set(SWEEP, "values = [0.2, 0.3]", "values = [0.2, 0.2]"), [], 2,
     "repeated value(s) 0.2"),
    ("sweep-bad-key", TINY + '[sweep]\nkey = "grid.nope"\nvalues = [1]\n', [], 2,
     "unknown key 'grid.nope'"),
    ("quick-empty-sweep", SWEEP + '[quick]\n"sweep.values" = []\n', ["--quick"], 2,
     "the quick sweep needs at least one value"),
    ("quick-sweep-strings", SWEEP + '[quick]\n"sweep.values" = [[1]]\n', ["--quick"], 2,
     'quick."sweep.values"[0] = [1]'),
    ("quick-bad-key", TINY + '[quick]\n"grid.nope" = 1\n', ["--quick"], 2,
     "unknown key 'grid.nope'"),
    ("wear-output-strings", WEAR + 'output_s = ["x"]\n', [], 2,
     "sliding_wear.output_s[0] = 'x'"),
    ("wear-zero-step", _set(WEAR, "step = 1.0", "step = 0.0"), [], 2, "sliding_wear.step"),
    ("wear-endless", _set(WEAR, "distance = 2.0", "distance = 1e15"), [], 2,
     "reduce sliding_wear.distance"),
    ("fretting-endless", _set(FRET, "cycles = 2", "cycles = 1000000000000"), [], 2,
     "reduce fretting.cycles"),
    ("fretting-huge-steps", _set(FRET, "steps_per_cycle = 4",
                                 "steps_per_cycle = 2000000000"), [], 2,
     "fretting.steps_per_cycle"),
    ("fretting-steps-3", _set(FRET, "steps_per_cycle = 4", "steps_per_cycle = 3"), [], 2,
     "fretting.steps_per_cycle = 3: must be >= 4"),
    ("fretting-off-jump-grid", _set(FRET, "jump = 1.0", "jump = 3.0") , [], 2,
     "fretting.cycles = 2: not a whole number of simulated cycles"),
    ("fretting-output-off-grid", _set(FRET, "jump = 1.0", "jump = 2.0\noutput_cycles = [1]")
     .replace("cycles = 2\n", "cycles = 4\n", 1), [], 2,
     "fretting.output_cycles[0] = 1: not a whole number"),
    ("fretting-output-beyond", FRET + "output_cycles = [3]\n", [], 2,
     "fretting.output_cycles[0] = 3: must lie in (0, fretting.cycles = 2]"),
    ("fretting-output-repeated", FRET + "output_cycles = [1, 1]\n", [], 2, "repeated cycle"),
    ("fretting-transverse", FRET + 'transverse = "sideways"\n', [], 2,
     "fretting.transverse = 'sideways': must be one of 'held', 'free'"),
    ("fretting-output-nested", FRET + "output_cycles = [[1]]\n", [], 2,
     "fretting.output_cycles[0] = [1]: must be an integer"),
    ("fretting-no-friction", FRET.replace("[friction]\nmu = 0.3\n", ""), [], 2,
     "fretting needs friction"),
    ("set-name", TINY, ["--set", "name=x"], 2, "--set name: the case's name cannot"),
    ("set-sweep-values", SWEEP, ["--set", "sweep.values=[1]"], 2, "--set sweep.values"),
    ("set-quick", TINY, ["--set", "quick.grid.nx=5"], 2, "--set quick.grid.nx"),
    ("set-unknown", TINY, ["--set", "grid.nope=5"], 2, "unknown key 'grid.nope'"),
    ("set-no-equals", TINY, ["--set", "grid.nx"], 2, "expected KEY=VALUE"),
    ("set-wrong-type", TINY, ["--set", "grid.nx=abc"], 2, "grid.nx = 'abc'"),
    ("max-memory-tiny", TINY, ["--max-memory", "0.000001"], 2, "--max-memory"),
    ("max-memory-negative", TINY, ["--max-memory", "-1"], 2, "--max-memory must be"),
    ("max-hours-nan", TINY, ["--max-hours", "nan"], 2, "--max-hours must be"),
    ("max-hours-tiny", _set(WEAR, "distance = 2.0", "distance = 2000.0"),
     ["--max-hours", "1e-9"], 2, "reduce sliding_wear.distance"),
    ("unknown-solver", TINY, ["--solver", "nope"], 2, "unknown solver(s) nope"),
    ("empty-solver", TINY, ["--solver", ","], 2, "--solver needs at least one"),
]


@pytest.fixture
def hang_guard():
    """Fail instead of hanging: every input here must be answered within a minute."""
    def hang(signum, frame):
        raise AssertionError("no answer within 60 s")

    old = signal.signal(signal.SIGALRM, hang)
    signal.alarm(60)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, old)


def _answer(argv: list[str], capsys) -> tuple[int, str]:
    code = main(argv)
    captured = capsys.readouterr()
    text = captured.out + captured.err
    assert "Traceback" not in text, text
    return code, captured.err


@pytest.mark.parametrize(("text", "extra", "code", "needle"),
                         [c[1:] for c in CASE_FILES], ids=[c[0] for c in CASE_FILES])
def test_hostile_case_file(tmp_path, capsys, hang_guard, text, extra, code, needle):
    case = tmp_path / "case.toml"
    (case.write_bytes if isinstance(text, bytes) else case.write_text)(text)
    out = tmp_path / "out"
    out.mkdir()
    (out / ".git").mkdir()  # a neighbour that must survive whatever the case says
    (out / ".git" / "HEAD").write_text("ref")
    (tmp_path / "neighbour").write_text("kept")
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    got, err = _answer(["run", str(case), "--out", str(out), "--no-progress",
                        "--solver", "ic", *extra], capsys)
    assert got == code, err
    lines = [line for line in err.splitlines() if line.startswith("contact-vv: error:")]
    assert len(lines) == 1, err
    assert needle in lines[0], err
    after = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    assert after == before  # refused before anything was written or removed
    assert (out / ".git" / "HEAD").read_text() == "ref"


def test_names_are_refused_and_the_output_directory_untouched(tmp_path, capsys):
    """name = ".", "..", "a/b" or absolute: refused, and --out with a .git, another run's
    staging directory and the neighbours of --out stay as they were."""
    out = tmp_path / "out"
    (out / ".git").mkdir(parents=True)
    (out / ".git" / "config").write_text("[core]")
    (out / ".other.partial").mkdir()
    (out / ".other.partial" / "summary.csv").write_text("x")
    (tmp_path / "sibling").mkdir()
    (tmp_path / "sibling" / "file").write_text("s")
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    for name in (".", "..", "a/b", str(tmp_path / "sibling"), "../sibling"):
        case = tmp_path / "c.toml"
        case.write_text(f'name = "{name}"\n' + TINY)
        code, err = _answer(["run", str(case), "--out", str(out), "--no-progress"], capsys)
        assert code == 2 and f"name = {name!r}" in err, err
    case.unlink()
    assert {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()} == before


@pytest.mark.parametrize(("argv", "code", "needle"), [
    (["report", "--out", "{tmp}/missing"], 2, "does not exist"),
    (["gate", "--out", "{tmp}/missing"], 2, "does not exist"),
    (["gate", "--out", "{tmp}/file"], 2, ""),
    (["report", "--out", "{tmp}/file"], 2, ""),
    (["gate", "--out", "{tmp}/empty"], 2, "no results"),
    (["gate", "--out", "{tmp}/empty", "--drift", "-1"], 2, "--drift must be"),
    (["gate", "--out", "{tmp}/empty", "--drift", "nan"], 2, "--drift must be"),
    (["gate", "--out", "{tmp}/empty", "--baseline", "{tmp}/missing"], 2, ""),
    (["sweep", "{tmp}/case.toml", "--param", "friction.mu"], 2, "friction.mu"),
    (["sweep", "{tmp}/case.toml", "--param", "friction.mu=1:0:0.1"], 2, ""),
    (["sweep", "{tmp}/case.toml", "--param", "friction.mu=0:1:0"], 2, ""),
    (["sweep", "{tmp}/case.toml", "--param", "friction.mu=a,b"], 2, "friction.mu"),
    (["sweep", "{tmp}/case.toml", "--param", "name=a,b"], 2, ""),
    (["sweep", "{tmp}/case.toml", "--param", "grid.nx=11,11", "--solver", "ic"], 2,
     "repeated"),
    (["sweep", "{tmp}/case.toml", "--param", "grid.nx=11", "--workers", "-1"], 2,
     "--workers"),
    (["sweep", "{tmp}/case.toml", "--param", "stress.nz=5,100000000", "--solver", "ic"], 2,
     "reduce stress.nz"),
    (["run", "{tmp}/case.toml", "--out", "{tmp}/file"], 2, ""),
    (["run", "{tmp}/dir.toml"], 2, "is a directory"),
    (["run", "{tmp}/case.toml", "{tmp}/case.toml", "--out", "{tmp}/o"], 2, "both write"),
])
def test_hostile_arguments(tmp_path, capsys, hang_guard, argv, code, needle):
    (tmp_path / "file").write_text("not a directory")
    (tmp_path / "empty").mkdir()
    (tmp_path / "dir.toml").mkdir()
    (tmp_path / "case.toml").write_text(TINY + "[friction]\nmu = 0.2\n")
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    got, err = _answer(argv + (["--no-progress"] if argv[0] in ("run", "sweep") else []),
                       capsys)
    assert got == code, err
    assert err.strip().splitlines()[-1].startswith("contact-vv: error:"), err
    assert needle in err, err


def test_sweep_labels_are_exact_and_unique(tmp_path, capsys):
    """Values equal to 6 significant digits get labels of their own (no field file of one
    overwrites the other's)."""
    case = tmp_path / "c.toml"
    case.write_text(_set(SWEEP, "values = [0.2, 0.3]", "values = [0.1000001, 0.10000011]"))
    code, err = _answer(["run", str(case), "--out", str(tmp_path / "o"), "--no-progress",
                         "--solver", "ic"], capsys)
    assert code == 0, err
    fields = tmp_path / "o" / "tiny" if False else tmp_path / "o" / "c" / layout.FIELDS / "ic"
    assert sorted(p.name for p in fields.iterdir()) == ["mu=0.1000001", "mu=0.10000011"]


def test_result_files_take_the_umask(tmp_path, capsys):
    old = os.umask(0o022)
    try:
        code, err = _answer(["run", str(_write(tmp_path)), "--out", str(tmp_path / "o"),
                             "--no-progress", "--solver", "ic"], capsys)
    finally:
        os.umask(old)
    assert code == 0, err
    modes = {oct(p.stat().st_mode & 0o777) for p in (tmp_path / "o" / "c").rglob("*")
             if p.is_file()}
    assert modes == {oct(0o644)}


def _write(tmp_path: Path) -> Path:
    case = tmp_path / "c.toml"
    case.write_text(TINY)
    return case


def test_a_contact_at_the_grid_edge_is_a_user_error(tmp_path, capsys):
    """The half-space solver's own edge check, beyond the planner's a-priori radius: a
    fretting contact under held load that wears wider (i = 1e-3 /MPa) until it reaches
    the 0.5 mm grid is refused as a user error (exit 2) naming the keys to change."""
    case = tmp_path / "edge.toml"
    case.write_text(_set(_set(_set(FRET, "approach = 0.001", "P = 10.2"), "Lx = 1.6\nLy = 1.6",
                                "Lx = 0.5\nLy = 0.5"), "cycles = 2", "cycles = 20")
                    .replace("[materials.b]", "i1 = 1e-3\n[materials.b]")
                    .replace("amplitude = 0.001", "amplitude = 0.01"))
    code, err = _answer(["run", str(case), "--out", str(tmp_path / "o"), "--no-progress",
                         "--solver", "ic"], capsys)
    assert code == 2, err
    assert "solver ic rejected the case: the contact area reaches the edge" in err
    assert "enlarge grid.Lx/grid.Ly" in err
