"""The verdict on Tamaas through the suite's own gates: a table per case and quantity of
the Tamaas plugins' metrics (tamaas-analytic, tamaas-ic, tamaas-fem, tamaas_periodic-…)
with their tolerances, from results written by ``contact-vv run``.

    pip install -e ".[peers]"
    contact-vv run hertz cattaneo_mindlin sliding_friction dissimilar spence pin_on_disk \\
        fretting_isotropic --quick --solver ic,fem,tamaas,tamaas_periodic,analytic --out DIR
    python benchmarks/tamaas_verdict.py DIR [--label quick] [--out benchmarks/README.md]

One row per case and gated metric, one column per pair: the worst value over the sweep
points and output steps, its tolerance there, and how many rows failed.  The cases a
plugin does not model are listed with the reason its ``supports`` gave.  With ``--out``
the table goes into that file between the markers
``<!-- tamaas-verdict:LABEL:begin/end -->`` (appended if absent).
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
from datetime import date
from importlib import metadata
from pathlib import Path

import pandas as pd

PLUGINS = ("tamaas", "tamaas_periodic")


def rows(results: Path) -> tuple[pd.DataFrame, dict[str, dict[str, str]]]:
    """(the plugins' gated metric rows of every case in ``results``, {case: {plugin:
    why it was skipped}})."""
    frames, skipped = [], {}
    for manifest in sorted(results.glob("*/manifest.json")):
        case = manifest.parent.name
        notes = json.loads(manifest.read_text()).get("skipped", {})
        skipped[case] = {p: notes[p] for p in PLUGINS if p in notes}
        metrics = manifest.parent / "metrics.csv"
        if metrics.is_file():
            m = pd.read_csv(metrics)
            ours = m["pair"].str.split("-").str[0].isin(PLUGINS) & (m["status"] == "gated")
            frames.append(m[ours].assign(case=case))
    return (pd.concat(frames) if frames else pd.DataFrame()), skipped


def _cell(g: pd.DataFrame) -> str:
    if g.empty:
        return ""
    worst = g.loc[(g["value"] / g["tolerance"]).idxmax()]
    text = f"{worst['value']:.2g} / {worst['tolerance']:.2g}"
    bad = int((~g["passed"]).sum())
    return text if bad == 0 else f"**{text} ✗** ({bad}/{len(g)})"


def table(results: Path, label: str) -> str:
    """The verdict as Markdown (module doc)."""
    m, skipped = rows(results)
    versions = {p: metadata.version(p) for p in ("tamaas", "contact-vv")}
    head = (f"Measured {date.today().isoformat()} ({label}) on {platform.machine()}, Python "
            f"{platform.python_version()}, Tamaas {versions['tamaas']}, contact-vv "
            f"{versions['contact-vv']}. Each cell: the worst value over the sweep points "
            "and output steps / its tolerance; ✗ where a row fails (how many of how "
            "many).\n\n")
    lines = []
    if not m.empty:
        m["passed"] = m["passed"].astype(str).str.lower().eq("true")
        pairs = list(dict.fromkeys(m["pair"]))
        lines = ["| case | quantity | metric | " + " | ".join(pairs) + " |",
                 "|---|---|---|" + "---|" * len(pairs)]
        for (case, quantity, metric), g in m.groupby(["case", "quantity", "metric"],
                                                     sort=False):
            cells = [_cell(g[g["pair"] == pair]) for pair in pairs]
            lines.append(f"| {case} | {quantity} | {metric} | " + " | ".join(cells) + " |")
    out = head + "\n".join(lines) + "\n"
    notes = [f"- `{case}`: {plugin} — {why}" for case, by in skipped.items()
             for plugin, why in by.items()]
    if notes:
        out += "\nNot modelled (each plugin's `supports`):\n\n" + "\n".join(notes) + "\n"
    return out


def write_between(path: Path, text: str, label: str) -> None:
    begin, end = f"<!-- tamaas-verdict:{label}:begin -->", f"<!-- tamaas-verdict:{label}:end -->"
    doc = path.read_text()
    block = f"{begin}\n{text}{end}"
    if begin in doc and end in doc:
        doc = doc[:doc.index(begin)] + block + doc[doc.index(end) + len(end):]
    else:
        doc = doc.rstrip("\n") + "\n\n" + block + "\n"
    path.write_text(doc)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", type=Path)
    parser.add_argument("--label", default="quick")
    parser.add_argument("--out", type=Path)
    args = parser.parse_args(argv)
    text = table(args.results, args.label)
    if args.out is None:
        sys.stdout.write(text)
    else:
        write_between(args.out, text, args.label)
    return 0


if __name__ == "__main__":
    sys.exit(main())
