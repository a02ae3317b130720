"""Metamorphic relations (cases/symmetry.py, reports/registry/relations.py): the exact
ones hold to round-off on odd and even grids — the planes of a mirrored case cross at the
mirror of the original's centre — and the 30° turn keeps the invariants to within the
grid's own uncertainty."""

from __future__ import annotations

import tomllib

import pytest

from cases import symmetry
from cases.build import build
from reports.compare.point import compare_point
from reports.registry import solvers


def _case(n: int, load: str = "P = 10.2\nsliding = true\nslide_angle = 20.0\n"):
    text = ('kind = "static"\n[materials.a]\nE = 210000.0\nnu = 0.3\n[materials.b]\n'
            f"E = 210000.0\nnu = 0.3\n[geometry]\nR = 50.0\n[grid]\nLx = 0.5\nnx = {n}\n"
            "[friction]\nmu1 = 0.25\nmu2 = 0.5\nbeta = 35.0\n"
            f"[load]\n{load}[stress]\ndepth = 0.2\nnz = 11\n")
    return build(tomllib.loads(text), name="rel", source="<test>", param="")


@pytest.mark.parametrize("n", [31, 32], ids=["odd grid", "even grid"])
@pytest.mark.parametrize("load", ["P = 10.2\nsliding = true\nslide_angle = 20.0\n",
                                  "P = 10.2\nQx = 1.2\nQy = -0.7\n"],
                         ids=["full sliding", "partial slip"])
def test_the_exact_relations_hold_to_round_off(n, load):
    case = _case(n, load)
    results = {name: solvers.resolve(name)(case)
               for name in ("ic", "ic+axes90", "ic+axes180", "ic+mirror")}
    m = compare_point(case, results)
    assert set(m["oracle"]) == {"metamorphic relation"}
    assert (m["status"] == "gated").all() and len(m) > 40
    assert m["value"].max() < 1e-6, m.sort_values("value").tail(3)


def test_the_turn_keeps_the_invariants():
    """Turned by 30° with the load, the sliding contact keeps its invariants to within the
    grid's uncertainty (the grid does not turn); the load vectors turn back.  (That the
    turn sees friction axes turned the wrong way, through the wear of a pin, is a seeded
    defect of tests/test_suite_seeded_defects.py.)"""
    case = _case(41)
    turned = symmetry.turned(case)
    assert (turned.load.slide_angle, turned.friction.beta) == pytest.approx((50.0, 65.0))
    base, back = (solvers.resolve(n)(case) for n in ("ic", "ic+turned"))
    m = compare_point(case, {"ic": base, "ic+turned": back})
    assert m["passed"].all() and set(m["quantity"]) >= {"p_max", "contact_area"}
    q = [(r.steps[0].scalars["Qx"], r.steps[0].scalars["Qy"]) for r in (base, back)]
    assert q[1] == pytest.approx(q[0], rel=0.02)  # the resultant turned back
