"""`contact-vv report`: sections, embedded plots, pass/fail colouring, convergence."""

from __future__ import annotations

import re

import pytest
import test_cli_fakes as fakes
from test_cli_run import HERTZ, write_case

from reports.cli import main
from reports.render.pages import report_text

WEAR = HERTZ.replace('kind = "static"', 'kind = "sliding_wear"').replace(
    "[materials.b]", "i1 = 1.33e-7\n[materials.b]") + """\
[sliding_wear]
step = 1.0
distance = 10.0
output_s = [0.0, 1.0, 2.0]
"""


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """A results directory with a static case, a wear case, a grid study and a failure."""
    mp = pytest.MonkeyPatch()
    tmp = tmp_path_factory.mktemp("html")
    out = tmp / "res"
    try:
        fakes.use(mp, ic="solve_ic", analytic="solve_exact")
        static = write_case(tmp, HERTZ, "static")
        wear = write_case(tmp, WEAR, "wear")
        assert main(["run", "--no-progress", str(static), str(wear), "--out", str(out),
                     "--set", "tolerances.vm_xz_l2=0.01"]) == 0
        assert main(["sweep", "--no-progress", str(static), "--workers", "0", "--out",
                     str(out), "--param", "grid.nx=20,40,80", "--param",
                     "grid.ny=20,40,80", "--solver", "ic"]) == 0
        fakes.use(mp, ic="solve_diverging")
        broken = write_case(tmp, HERTZ, "broken")
        assert main(["run", "--no-progress", str(broken), "--out", str(out)]) == 1
        # the report is written, and exits 1 because it shows the incomplete "broken"
        assert main(["report", "--out", str(out)]) == 1
    finally:
        mp.undo()
    return out, report_text(out)


def section(text: str, case: str) -> str:
    start = text.index(f'id="case-{case}"')
    end = text.find('<section class="case"', start)
    return text[start: end if end > 0 else None]


def test_every_case_has_its_sections(report):
    _, text = report
    assert text.startswith("<!DOCTYPE html>")
    for case in ("static", "wear", "static__sweep_nx_ny"):
        sec = section(text, case)
        for cls in ("metrics", "convergence", "provenance"):
            assert f'class="{cls}"' in sec, (case, cls)
    for cls in ("profiles", "differences", "vm-planes"):
        assert f'<div class="{cls}"><figure>' in section(text, "static"), cls
    wear = section(text, "wear")
    assert '<div class="wear"><figure>' in wear
    assert '<div class="evolution"><figure>' in wear
    assert '<div class="loops"><figure>' in wear  # the fake writes a fretting_loop table
    assert '<div class="sweep"><figure>' in section(text, "static__sweep_nx_ny")


def test_plots_are_png_files_beside_the_case_pages(report):
    """The figures are files in _report/<case>/, loaded lazily; the index has none and
    stays small; nothing is fetched from elsewhere."""
    out, text = report
    images = re.findall(r'<img alt="[^"]*" loading="lazy" src="([^"]+)">', text)
    assert len(images) >= 10
    pages = out / "_report"
    assert all((pages / src).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for src in images)
    assert "data:image" not in text
    index = (out / "index.html").read_text()
    assert "<img" not in index and len(index.encode()) < 100_000
    assert "src=\"http" not in text and "<script" not in text  # self-contained


def test_metrics_coloured_and_failure_named(report):
    _, text = report
    static = section(text, "static")
    # vm_xz l2 is 0.015 against the deliberately tight 0.01: a failing (red) row
    assert re.search(r'<tr class="fail"><td class="l">ic-analytic</td><td class="l">closed '
                     r'form</td><td class="l">vm_xz</td><td class="l">l2</td><td class="">'
                     r'0\.015</td>', static)
    assert '<tr class="pass">' in static
    # each row says which kind of tolerance it used, with the budget beside U
    assert ">tolerance_kind</th>" in static and ">uncertainty</th>" in static
    assert "<i>uncertainty</i> (the combined numerical uncertainty" in static
    assert "FAIL static step 0 ic-analytic vm_xz l2 = 0.015 &gt; tolerance 0.01" in text


def test_incomplete_run_is_flagged_not_reported(report):
    _, text = report
    assert 'id="incomplete"' in text
    assert "<b>broken</b>: run failed: broken: solver ic did not converge" in text
    assert 'id="case-broken"' not in text


def test_grid_convergence_table_from_the_sweep(report):
    _, text = report
    conv = section(text, "static__sweep_nx_ny").split('class="convergence"')[1]
    # the fake pressure sampled at cell centres ±h/2 has p_max = 1.02 p0 √(1 − h²/2a0²):
    # the observed order of the three finest grids follows from those values
    from cases.loader import load_case
    from reports.studies.three_level import study

    a0, p0 = load_case("hertz")[0].hertz_scales
    h = [1.6 / n for n in (80, 40, 20)]
    f = [1.02 * p0 * (1 - x**2 / (2 * a0**2)) ** 0.5 for x in h]
    expected = study(tuple(f), tuple(h)).p
    assert 1.9 < expected < 2.2
    row = re.search(r'<td class="l">ic</td><td class="l">p_max</td>(.*?)</tr>', conv).group(1)
    cells = re.findall(r"<td[^>]*>([^<]*)</td>", row)
    assert float(cells[6]) == pytest.approx(expected, rel=1e-3)  # "order p" column


def test_axes_are_labelled():
    """Every axis of every report figure has a label with units or a dimensionless group."""
    import matplotlib.pyplot as plt

    from cases.loader import load_case
    from reports.render import plots

    case = load_case("hertz", quick=True)[0]
    a0, p0 = case.hertz_scales
    steps = {"ic": fakes.hertz_step(case, 1.02, 0), "analytic": fakes.hertz_step(case, 1.0, 0)}
    figs = [plots.traction_profiles(steps, a0, p0), plots.difference_maps(steps, a0, p0),
            plots.plane_difference_maps(steps, a0, p0), plots.vm_planes(steps, a0, p0)]
    pattern = re.compile(r"/ ?a0|/ ?p0|\[.+\]|cycles|step")
    for fig in figs:
        for ax in fig.axes:
            if not ax.get_visible() or not ax.axison:
                continue
            labels = [ax.get_xlabel(), ax.get_ylabel()]
            if ax.get_label() == "<colorbar>":
                labels = [ax.get_ylabel()]
            for lab in labels:
                assert lab and pattern.search(lab), (lab, fig._suptitle.get_text())
        plt.close(fig)
