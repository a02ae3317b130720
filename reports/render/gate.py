"""``contact-vv gate``: fail on any failed metric (``passed`` recomputed from value and
tolerance; a recorded ``passed`` that disagrees is a problem too), case with no gated
metric, non-converged run, incomplete or damaged case, output step of a plugin or of
external results that nothing compares, and threshold of ``thresholds.csv`` that is not a
bracket or disagrees with the exact one or another solver's
(:mod:`reports.render.threshold_gate`), naming each.

It prints, by default, the verdict and the counts on its first line, then every problem
(a failed metric with its case, point, step, pair, quantity, metric, value, tolerance,
the tolerance's source and where the report shows it), then one line per case (its
counts, the rows shown but not gated by reason, the solvers not run), and the notes
that may change what the numbers mean (a case file or solver source changed since the
run).  ``--verbose`` adds the whole metrics table, every ``NOT GATED …`` row with its
value and reason, the grid and jump studies' ``UNSETTLED …`` notes with their three
values and every solver not run with why.  Neither a not-gated row nor a study note
fails the gate.  ``--junit FILE`` also writes the verdict as JUnit XML
(:mod:`reports.render.junit`)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TextIO

import pandas as pd

from reports.registry import solvers
from reports.registry.errors import RunFailed, UserError
from reports.registry.tolerances import UNCERTAINTY, reason_words
from reports.render.threshold_gate import threshold_gate
from reports.store.layout import METRICS, THRESHOLDS
from reports.store.readers import gated, ungated
from reports.store.results import CaseResults, Scan, not_converged, scan
from reports.studies.registry import STUDIES

_SHOW = ["case", "param", "step", "pair", "oracle", "quantity", "metric", "value", "tolerance",
         "passed", "status", "tolerance_key", "tolerance_kind", "budget", "uncertainty"]


def metrics_table(results: Scan) -> pd.DataFrame:
    """All cases' metrics in one table (case, param, step, pair, quantity, ...)."""
    frames = [c.metrics.assign(case=c.name) for c in results.complete if not c.metrics.empty]
    if not frames:
        return pd.DataFrame(columns=_SHOW)
    table = pd.concat(frames, ignore_index=True)
    return table[[c for c in _SHOW if c in table.columns]]


def _where(case: str, param: object, step: object) -> str:
    param = "" if pd.isna(param) else str(param)
    return case + (f" [{param}]" if param else "") + (
        f" step {int(step)}" if not pd.isna(step) else "")


def _num(x: float) -> str:
    return f"{x:.4g}"


def metric_problems(case: CaseResults, report: Path | None = None) -> list[str]:
    """One line per failed metric of a case (``passed`` as recomputed from value and
    tolerance, :func:`reports.registry.tolerances.passes`) and per metric whose recorded
    ``passed`` disagrees with that; a failure names the case's section of ``report``
    (the HTML report) where it is given."""
    lines = []
    shown = f"; shown in {report}#case-{case.name}" if report is not None else ""
    on = gated(case.metrics).to_numpy()
    for k, r in enumerate(case.metrics.itertuples(index=False)):
        what = f"{_where(case.name, r.param, r.step)} {r.pair} {r.quantity} {r.metric}"
        value, tol = float(r.value), float(r.tolerance)
        if on[k] and not r.passed:
            key = getattr(r, "tolerance_key", "")
            if not math.isfinite(value):
                why = f"= {value} (not a finite number; tolerance {_num(tol)})"
            elif not math.isfinite(tol):
                why = f"= {_num(value)} against tolerance {tol} (not a finite number)"
            else:
                why = f"= {_num(value)} > tolerance {_num(tol)}"
            if r.tolerance_kind == UNCERTAINTY:
                why += (f" (the combined uncertainty of the grid studies; budget "
                        f"{_num(float(r.budget))}, tolerance key {key}{shown})")
            elif isinstance(key, str) and key:
                why += f" (tolerance key {key}{shown})"
            lines.append(f"FAIL {what} {why}")
        if bool(r.passed_recorded) != bool(r.passed):
            lines.append(f"INCONSISTENT {what}: {case.path / METRICS} records passed = "
                         f"{bool(r.passed_recorded)}, but value {_num(value)} against "
                         f"tolerance {_num(tol)} {'passes' if r.passed else 'fails'}")
    return lines


def ungated_lines(case: CaseResults) -> list[str]:
    """One ``NOT GATED …`` note per quantity of a case shown and not gated
    (:func:`reports.store.readers.ungated`), with its largest value and why (its note; the
    words of its reason where it has none)."""
    return [f"NOT GATED {case.name} {r.pair} {r.quantity} {r.metric} ({r.rows} row(s), "
            f"largest {_num(float(r.value))} at {_where('', r.param, r.step).strip()}): "
            f"{r.note or reason_words(r.reason)}"
            for r in ungated(case.metrics).itertuples(index=False)]


def uncompared_lines(case: CaseResults) -> list[str]:
    """One ``UNCOMPARED …`` problem per output step of a solver not of this suite (a
    plugin, external results) that no row of ``metrics.csv`` compares: results a user
    named that would otherwise pass unread (a step the case does not have, a file
    beyond its output steps)."""
    summary, metrics = case.summary, case.metrics
    if summary.empty or "solver" not in summary:
        return []
    compared: dict[str, set[str]] = {}
    for r in metrics.itertuples(index=False) if "pair" in metrics else ():
        a, _, b = str(r.pair).partition("-")
        for name in (a, b):
            compared.setdefault(name, set()).add(_where("", r.param, r.step))
    lines = []
    for r in summary.itertuples(index=False):
        if solvers.builtin(r.solver) or _where("", r.param, r.step) in compared.get(
                r.solver, set()):
            continue
        hint = (f"; [external.{r.solver.partition(':')[2]}] names a step or a file that "
                "no other solver of the case has (its steps, its files)"
                if solvers.is_external(r.solver) else "")
        lines.append(f"UNCOMPARED {_where(case.name, r.param, r.step)}: solver "
                     f"{r.solver}'s results are compared with nothing{hint}")
    return lines


def case_problems(results: Scan) -> list[str]:
    """One line per incomplete and per damaged case."""
    return ([f"INCOMPLETE {name}: {reason}" for name, reason in results.incomplete.items()]
            + [f"DAMAGED {name}: {reason}" for name, reason in results.damaged.items()])


def _second_hint(case: CaseResults) -> str:
    """What would compare a case's lonely results: the solvers it ran with one it has not
    tried (:func:`reports.registry.solvers.second_solvers`), and those that declined."""
    have = set(case.summary.get("solver", ()))
    ran = [s for s in solvers.by_role(case.manifest.get("solvers", []))
           if s in have and not solvers.record(s).base]
    declined = dict(case.manifest.get("skipped", {}))
    untried = solvers.second_solvers(ran, declined)
    said = "; ".join(f"{s} declined: {why}" for s, why in declined.items())
    if not untried:
        return "no built-in solver is left to try" + (f"; {said}" if said else "")
    hint = f"run it with a solver that compares, e.g. --solver {','.join(ran + untried[:1])}"
    return hint + (f"; {said}" if said else "")


def problems(results: Scan, report: Path | None = None) -> list[str]:
    """One line per failed or inconsistent metric, case without a gated metric,
    non-converged run, incomplete and damaged case."""
    lines = []
    for case in results.complete:
        lines += metric_problems(case, report)
        lines += uncompared_lines(case)
        if not gated(case.metrics).any():
            lines.append(f"NO METRICS {case.name}: {case.path / METRICS} holds no gated "
                         f"comparison, so nothing in it is verified ({_second_hint(case)})")
    for case in results.complete:
        for r in not_converged(case.summary).itertuples(index=False):
            lines.append(f"NOT CONVERGED {_where(case.name, r.param, r.step)} "
                         f"solver {r.solver}")
    return lines + case_problems(results)


def stale_case_file(mf: dict) -> bool:
    """Whether the case file of a run exists and no longer has the recorded hash."""
    from reports.store.manifest import sha256_file

    path = Path(str(mf.get("case_file", "")))
    return path.is_file() and sha256_file(path) != mf.get("case_sha256")


def case_line(case: CaseResults) -> str:
    """One line of a case: its gated rows passed, those shown but not gated by reason,
    and the solvers not run that it was asked for (:attr:`CaseResults.not_run`)."""
    m = case.metrics
    on = gated(m)
    passed = int((m["passed"].astype(bool) & on).sum()) if len(m) else 0
    text = f"  {case.name}: {passed}/{int(on.sum())} passed"
    if len(m) and (~on).any():
        counts = m.loc[~on, "reason"].map(reason_words).value_counts()
        text += f", {int((~on).sum())} not gated (" + ", ".join(
            f"{k} {v}" for k, v in counts.items()) + ")"
    if case.not_run:
        text += f"; not run: {', '.join(case.not_run)}"
    return text


def _verbose_notes(case: CaseResults) -> list[str]:
    return ([f"note: {case.name}: solver {s} not run ({why})"
             for s, why in case.manifest.get("skipped", {}).items()]
            + [line for s in STUDIES for line in s.notes(case.name, case.study(s.name))]
            + ungated_lines(case))


def _warnings(case: CaseResults) -> list[str]:
    """The notes that change what a case's numbers mean: printed always."""
    out = []
    if case.manifest.get("sources_changed_during_run"):
        out.append(f"note: {case.name}: solver sources changed during the run; its numbers "
                   "may mix two versions (re-run)")
    if stale_case_file(case.manifest):
        out.append(f"note: {case.name}: the case file {case.manifest.get('case_file')} "
                   "changed since the run (re-run to check the current version)")
    return out


def headline(results: Scan, table: pd.DataFrame, found: list[str]) -> str:
    """The verdict and its counts (the gate's first line)."""
    on = gated(table)
    n_ok = int((table["passed"].astype(bool) & on).sum())
    n_off = int((~on).sum())
    n_u = int((on & (table["tolerance_kind"] == UNCERTAINTY)).sum())
    return (f"gate: {len(results.complete)} case(s), {n_ok}/{len(table) - n_off} metric(s) "
            "passed" + (f" ({n_u} against the combined uncertainty of grid studies)"
                        if n_u else "")
            + (f", {n_off} shown and not gated" if n_off else "")
            + f", {len(found)} problem(s): " + ("FAILED" if found else "PASSED"))


def run_gate(out: Path, *, stream: TextIO | None = None, baseline: Path | None = None,
             update_baseline: Path | None = None, drift_tol: float | None = None,
             verbose: bool = False, junit: Path | None = None) -> int:
    """Print the verdict, the problems and a line per case (module doc); 0 if no problem,
    else :class:`RunFailed` with one line that counts them (each problem is printed once,
    with the verdict: the CLI adds that line as its error, exit 1).

    ``baseline``: also fail on key numbers that drifted from the baselines in that folder
    (a baseline folder that cannot be read is a :class:`UserError`, before any output);
    ``update_baseline``: write the baselines of the current results there instead;
    ``verbose``: every metric row and note; ``junit``: also write JUnit XML there.
    """
    import sys

    from reports.render import baseline as bl
    from reports.render.junit import check_path, write_junit
    from reports.store.targets import is_stdout

    if junit is not None:
        check_path(junit, out)
    # the XML alone on standard output when it goes there; the lines beside it
    stream = stream or (sys.stderr if junit is not None and is_stdout(junit) else sys.stdout)
    results = scan(out)
    if results.empty and not (Path(out) / THRESHOLDS).exists():
        raise UserError(f"no results in {out} (run `contact-vv run` first)")
    index = Path(out) / "index.html"
    found = problems(results, index if index.exists() else None)
    t_found, t_notes, t_gated = threshold_gate(out)
    found += t_found
    table = metrics_table(results)
    if update_baseline is not None:
        if results.incomplete or results.damaged:
            raise UserError("refusing to update baselines from incomplete or damaged "
                            "results: " + ", ".join([*results.incomplete, *results.damaged]))
        for path in bl.write(results, update_baseline, out):
            print(f"baseline written: {path}", file=stream)
        return 0
    if baseline is not None:
        found += bl.drift(results, baseline, bl.DEFAULT_DRIFT if drift_tol is None
                          else drift_tol)
    lines = [headline(results, table, found), *found]
    lines += [case_line(case) for case in results.complete]
    if t_gated or t_found or t_notes:
        lines.append(f"  {THRESHOLDS}: {t_gated - sum(x.startswith('FAIL ') for x in t_found)}"
                     f"/{t_gated} threshold comparison(s) passed"
                     + (f", {len(t_notes)} not gated" if t_notes else ""))
    lines += [w for case in results.complete for w in _warnings(case)]
    if verbose:
        with pd.option_context("display.max_rows", None, "display.width", 200,
                               "display.max_colwidth", 40):
            lines.append(table.to_string(index=False) if not table.empty else "(no metrics)")
        lines += [n for case in results.complete for n in _verbose_notes(case)] + t_notes
    else:
        lines.append("(--verbose: every metric row, not-gated row and study note)")
    print("\n".join(lines), file=stream)
    if junit is not None:
        print(f"junit: {write_junit(junit, results, found)}", file=stream)
    if found:
        raise RunFailed([f"the gate found {len(found)} problem(s), each listed above"])
    return 0
