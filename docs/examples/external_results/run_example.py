"""The worked example of docs/external-results.md, in one command:

    python docs/examples/external_results/run_example.py [DIR]

1. "Another code" writes its results: here the suite's own FEM stands in for it, and
   its mesh is exported as an Abaqus user might: SI units, the contact surface at Y = 0
   with the body below it, Abaqus-style names (CPRESS, CSHEAR1/2, S11 ... S23).
2. ``contact-vv run`` reads them as the solver ``external:my_fe``, beside the
   half-space solver and the closed forms (hertz_other_code.toml maps the fields).
3. ``contact-vv gate`` gives the verdict (exit status 0: every gated row passed).

Everything is written under DIR (default ``./external_example``).
"""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

import meshio
import numpy as np

HERE = Path(__file__).resolve().parent
CASE = HERE / "hertz_other_code.toml"


def other_code(folder: Path) -> Path:
    """The FEM's quick Hertz mesh in the other code's frame and units (module doc)."""
    import fem_reference
    from cases import load_case

    case = load_case(CASE, quick=True)[0]
    _, mesh = fem_reference.solve(case).meta["vtu"][0]
    x, y, z = mesh.points.T  # the FEM's frame: Z = -depth, mm
    d = mesh.point_data
    pa = 1e6  # MPa -> Pa
    data = {  # file axes: X = x, Y = Z (= -depth), Z = y
        "CPRESS": d["p_n"] * pa, "CSHEAR1": d["p_x"] * pa, "CSHEAR2": d["p_y"] * pa,
        "S11": d["sxx"] * pa, "S22": d["szz"] * pa, "S33": d["syy"] * pa,
        "S12": d["sxz"] * pa, "S13": d["sxy"] * pa, "S23": d["syz"] * pa,
    }
    points = np.column_stack([x, z, y]) * 1e-3  # mm -> m
    out = folder / "other_code" / "step_0000.vtu"
    out.parent.mkdir(parents=True, exist_ok=True)
    meshio.write(out, meshio.Mesh(points, mesh.cells, point_data=data))
    return out


def main(argv: list[str] | None = None) -> int:
    from reports import main as contact_vv

    args = sys.argv[1:] if argv is None else argv
    folder = Path(args[0] if args else "external_example")
    folder.mkdir(parents=True, exist_ok=True)
    case = folder / CASE.name
    shutil.copy(CASE, case)
    print(f"wrote {other_code(folder)}")
    results = folder / "results"
    code = contact_vv(["run", str(case), "--quick", "--no-progress",
                       "--solver", "external:my_fe,ic,analytic", "--out", str(results)])
    return code or contact_vv(["gate", str(results)])


if __name__ == "__main__":
    sys.exit(main())
