"""Hostile ``[external.NAME]`` tables and files (issue 59, point 5): every one gets one
``contact-vv: error: …`` line naming the key or the file and the cause, exit status 2,
while the run is planned — no traceback, no hang, and nothing in or beside the results
directory written or removed.  The valid table the probes spoil, a surface table of the
Hertz pressure on a small case, runs and is compared (exit 0).

Each probe states its expectation: (id, the table's lines changed, the file's text
changed, the needle of the error line).
"""

from __future__ import annotations

import numpy as np
import pytest
from test_cli_hostile_inputs import TINY, _answer, hang_guard  # noqa: F401 (a fixture)

from cases import load_point

#: the valid table: a CSV surface table of the Hertz pressure, the files' units mm/MPa
TABLE = {
    "files": '"surface.csv"',
    "format": '"csv"',
    "budget": "{ default = 0.5 }",
}
FIELDS = {"p_n": '"p"'}


def surface_csv() -> str:
    """The Hertz pressure of TINY on a 21 x 21 point grid of its contact surface."""
    case = load_point_text(TINY)
    a0, p0 = case.hertz_scales
    x, y = np.meshgrid(np.linspace(-1.5 * a0, 1.5 * a0, 21), np.linspace(-1.5 * a0, 1.5 * a0,
                                                                          21))
    p = p0 * np.sqrt(np.clip(1.0 - (x**2 + y**2) / a0**2, 0.0, None))
    rows = [f"{a:.17g},{b:.17g},0.0,{c:.17g}" for a, b, c in zip(x.ravel(), y.ravel(), p.ravel(),
                                                        strict=True)]
    return "x,y,z,p\n" + "\n".join(rows) + "\n"


def load_point_text(text: str):
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "tiny.toml"
        path.write_text(text)
        return load_point(path)


def case_text(table: dict[str, str | None], fields: dict[str, str | None],
              raw: str = "") -> str:
    lines = [TINY, "[external.fe]"]
    lines += [f"{k} = {v}" for k, v in table.items() if v is not None]
    lines += [raw, "[external.fe.fields]"] if raw else ["[external.fe.fields]"]
    lines += [f"{k} = {v}" for k, v in fields.items() if v is not None]
    return "\n".join(lines) + "\n"


def _t(**changes: str | None) -> dict[str, str | None]:
    return {**TABLE, **changes}


def _f(**changes: str | None) -> dict[str, str | None]:
    return {**FIELDS, **changes}


GOOD = surface_csv()
# (id, table, fields, file text (None: the good one), the needle of the error line)
PROBES = [
    # files
    ("files-missing-key", _t(files=None), _f(), None, "external.fe.files is required"),
    ("files-absent", _t(files='"gone.csv"'), _f(), None, "gone.csv"),
    ("files-glob-empty", _t(files='"none_*.csv"'), _f(), None, "none_*.csv"),
    ("files-number", _t(files="3"), _f(), None, "external.fe.files"),
    ("files-list-of-numbers", _t(files="[1, 2]"), _f(), None, "external.fe.files"),
    ("files-empty-list", _t(files="[]"), _f(), None, "external.fe.files"),
    ("files-a-directory", _t(files='"."'), _f(), None, "external.fe.files"),
    # format
    ("format-unknown", _t(format='"nonsense"'), _f(), None, "surface.csv"),
    ("format-number", _t(format="3"), _f(), None, "external.fe.format"),
    # meshio's VTU reader exits the process on a file that is not XML (SystemExit)
    ("format-mesh-of-a-csv", _t(format='"vtu"'), _f(), None, "surface.csv"),
    # steps
    ("steps-too-many", _t(steps="[0, 1]"), _f(), None, "external.fe.steps"),
    ("steps-float", _t(steps="[0.5]"), _f(), None, "external.fe.steps"),
    ("steps-bool", _t(steps="[true]"), _f(), None, "external.fe.steps"),
    ("steps-string", _t(steps='["0"]'), _f(), None, "external.fe.steps"),
    ("steps-not-a-list", _t(steps="0"), _f(), None, "external.fe.steps"),
    # fields
    ("fields-no-p_n", _t(), _f(p_n=None, p_x='"p"'), None, "external.fe.fields.p_n"),
    ("fields-unknown-quantity", _t(), _f(colour='"p"'), None, "external.fe.fields.colour"),
    ("fields-absent-column", _t(), _f(p_n='"CPRESS"'), None, "CPRESS"),
    ("fields-empty-name", _t(), _f(p_n='""'), None, "external.fe.fields.p_n"),
    ("fields-only-minus", _t(), _f(p_n='"-"'), None, "external.fe.fields.p_n"),
    ("fields-bad-component", _t(), _f(p_n='"p:x"'), None, "external.fe.fields.p_n"),
    ("fields-component-of-a-scalar", _t(), _f(p_n='"p:2"'), None, "p"),
    ("fields-number", _t(), _f(p_n="3"), None, "external.fe.fields.p_n"),
    ("fields-stress-on-a-surface", _t(), _f(sxx='"p"'), None, "fill the body"),
    # scalars and their file
    ("scalars-unknown", _t(scalars='{ colour = "p" }'), _f(), None, "external.fe.scalars"),
    ("scalars-absent", _t(scalars='{ P = "LOAD" }'), _f(), None, "LOAD"),
    ("scalars-file-absent", _t(scalars_file='"gone.csv"', scalars='{ P = "P" }'), _f(),
     None, "gone.csv"),
    ("scalars-file-number", _t(scalars_file="3", scalars='{ P = "P" }'), _f(), None,
     "external.fe.scalars_file"),
    # units
    ("length-unit-unknown", _t(length_unit='"furlong"'), _f(), None,
     "external.fe.length_unit"),
    ("length-unit-negative", _t(length_unit="-1.0"), _f(), None, "external.fe.length_unit"),
    ("length-unit-zero", _t(length_unit="0.0"), _f(), None, "external.fe.length_unit"),
    ("length-unit-nan", _t(length_unit="nan"), _f(), None, "external.fe.length_unit"),
    ("length-unit-bool", _t(length_unit="true"), _f(), None, "external.fe.length_unit"),
    ("stress-unit-unknown", _t(stress_unit='"psi"'), _f(), None, "external.fe.stress_unit"),
    ("stress-unit-inf", _t(stress_unit="inf"), _f(), None, "external.fe.stress_unit"),
    # axes, origin, mirror
    ("axes-two", _t(axes='["x", "y"]'), _f(), None, "external.fe.axes"),
    ("axes-repeated", _t(axes='["x", "x", "-z"]'), _f(), None, "external.fe.axes"),
    ("axes-unknown", _t(axes='["x", "y", "w"]'), _f(), None, "external.fe.axes"),
    ("axes-string", _t(axes='"xyz"'), _f(), None, "external.fe.axes"),
    ("axes-depth-in-the-plane", _t(axes='["x", "z", "-y"]'), _f(), None, "external.fe.axes"),
    ("origin-two", _t(origin="[0.0, 0.0]"), _f(), None, "external.fe.origin"),
    ("origin-strings", _t(origin='["0", "0", "0"]'), _f(), None, "external.fe.origin"),
    ("origin-bools", _t(origin="[true, false, true]"), _f(), None, "external.fe.origin"),
    # 100 mm off: the file's scalars alone looked right and the gate passed (issue 59)
    ("origin-far-away", _t(origin="[100.0, 100.0, 0.0]"), _f(), None,
     "covers no point of the case's grid"),
    ("mirror-z", _t(mirror='["z"]'), _f(), None, "external.fe.mirror"),
    ("mirror-string", _t(mirror='"x"'), _f(), None, "external.fe.mirror"),
    # budget and cell
    ("budget-missing", _t(budget=None), _f(), None, "external.fe.budget"),
    ("budget-no-default", _t(budget="{ p_max = 0.1 }"), _f(), None, "external.fe.budget"),
    ("budget-negative", _t(budget="{ default = -0.1 }"), _f(), None,
     "external.fe.budget.default"),
    ("budget-nan", _t(budget="{ default = nan }"), _f(), None, "external.fe.budget.default"),
    ("budget-string", _t(budget='{ default = "small" }'), _f(), None,
     "external.fe.budget.default"),
    ("budget-bool", _t(budget="{ default = true }"), _f(), None,
     "external.fe.budget.default"),
    ("budget-a-number", _t(budget="0.1"), _f(), None, "external.fe.budget"),
    ("cell-zero", _t(cell="0.0"), _f(), None, "external.fe.cell"),
    ("cell-negative", _t(cell="-0.01"), _f(), None, "external.fe.cell"),
    ("cell-string", _t(cell='"fine"'), _f(), None, "external.fe.cell"),
    # the table itself
    ("unknown-key", _t(colour='"red"'), _f(), None, "unknown key external.fe.colour"),
    # the file's contents
    ("file-header-only", _t(), _f(), "x,y,z,p\n", "0 point(s)"),
    ("file-empty", _t(), _f(), "", "surface.csv"),
    ("file-no-z", _t(), _f(), "x,y,p\n0,0,1\n1,0,1\n0,1,1\n", "surface.csv"),
    ("file-text-values", _t(), _f(), "x,y,z,p\na,b,c,d\n", "surface.csv"),
    ("file-nan-coordinates", _t(), _f(), "x,y,z,p\nnan,0,0,1\n1,0,0,1\n0,1,0,1\n",
     "surface.csv"),
    ("file-nan-pressure", _t(), _f(), "\n".join(
        [GOOD.splitlines()[0], GOOD.splitlines()[1].rsplit(",", 1)[0] + ",nan",
         *GOOD.splitlines()[2:]]) + "\n", "external.fe.fields.p_n"),
    ("file-binary", _t(), _f(), bytes(range(256)).decode("latin-1"), "surface.csv"),
    ("file-one-point", _t(), _f(), "x,y,z,p\n0,0,0,1\n", "1 point(s)"),
    ("file-collinear-points", _t(), _f(),
     "x,y,z,p\n" + "".join(f"{0.01 * i},0,0,1\n" for i in range(9)), "surface.csv"),
]


def _run(tmp_path, capsys, table, fields, text=None, *, prepare=None) -> tuple[int, str]:
    """``run`` of the case with ``table`` and ``fields`` and the file ``text`` (None: the
    good one) into ``tmp_path/out`` (``prepare(out)`` first, if given)."""
    (tmp_path / "surface.csv").write_text(GOOD if text is None else text,
                                          encoding="latin-1")
    (tmp_path / "c.toml").write_text(case_text(table, fields))
    out = tmp_path / "out"
    if prepare is not None:
        prepare(out)
    return _answer(["run", str(tmp_path / "c.toml"), "--solver", "external:fe,ic",
                    "--no-progress", "--out", str(out)], capsys)


def test_the_valid_table_runs(tmp_path, capsys, hang_guard):  # noqa: F811
    code, err = _run(tmp_path, capsys, TABLE, FIELDS)
    assert code == 0, err


def _kept(out):
    out.mkdir()
    (out / "kept.txt").write_text("kept")  # a file the run did not create


@pytest.mark.parametrize(("table", "fields", "text", "needle"),
                         [p[1:] for p in PROBES], ids=[p[0] for p in PROBES])
def test_hostile_external_table(tmp_path, capsys, hang_guard, table, fields, text,  # noqa: F811
                                needle):
    before = []

    def prepare(out):
        _kept(out)
        before.extend(sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")))

    code, err = _run(tmp_path, capsys, table, fields, text, prepare=prepare)
    lines = [line for line in err.splitlines() if line.startswith("contact-vv: error:")]
    assert code == 2, err
    assert len(lines) == 1, err
    assert needle in lines[0], err
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == before
    assert (tmp_path / "out" / "kept.txt").read_text() == "kept"


def test_a_file_in_the_wrong_unit_fails_the_gate(tmp_path, capsys, hang_guard):  # noqa: F811
    """A file in mm read as metres covers the grid a thousand times too wide: it is read,
    and the gate fails it on the load and the contact size (exit 1)."""
    from reports.cli import main

    code, err = _run(tmp_path, capsys, _t(length_unit='"m"'), FIELDS)
    assert code == 0, err
    assert main(["gate", "--out", str(tmp_path / "out")]) == 1
    out = capsys.readouterr().out  # the problems, once, with the verdict
    assert "external:fe-ic P rel" in out and "external:fe-ic a_x cells" in out, out
