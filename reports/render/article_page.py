"""``contact-vv article``: ``DIR/article.html`` — the source article's claims judged
(:mod:`reports.studies.claims`): the claims table (measured numbers, uncertainty,
verdict, why) and every claim's figure in the article's dimensionless axes — and, in
``DIR/article/``, each figure as PNG with its data as CSV, and the claims table as CSV.
Only files this command writes are ever replaced."""

from __future__ import annotations

import textwrap
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

from cases.result import atomic_path, atomic_write_text
from reports.registry.errors import UserError
from reports.render.frame import png
from reports.render.html_blocks import CSS, escape
from reports.store import layout
from reports.store.write import write_csv
from reports.studies.claims import CLAIMS, Claim, judge
from reports.studies.claims.finding import VERDICTS, Article, Finding, Panel
from reports.studies.claims.sources import collect

TITLE = "contact-vv: does the article hold?"
COLOURS = {"holds": "pass", "does not hold": "fail"}
#: a series of at most this many points is drawn with its points marked
FEW = 12
#: a panel title wraps at this many characters (panels stand side by side)
TITLE_WIDTH = 45


def figure(panels: tuple[Panel, ...], title: str) -> bytes | None:
    """The panels side by side, one line (or markers) per series."""
    if not panels:
        return None
    fig, axes = plt.subplots(1, len(panels), figsize=(4.6 * len(panels), 3.6), squeeze=False,
                             layout="constrained")
    for ax, panel in zip(axes[0], panels, strict=True):
        for label, (x, y) in panel.series.items():  # a few outputs: their points shown
            ax.plot(x, y, "o-" if panel.markers or len(x) <= FEW else "-", ms=4, label=label)
        ax.set(xlabel=panel.xlabel, ylabel=panel.ylabel)
        ax.set_title(textwrap.fill(panel.title, TITLE_WIDTH), fontsize=9)
        ax.grid(alpha=0.3)
        if panel.series:
            ax.legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    return png(fig)


def claims_frame(findings: dict[int, Finding]) -> pd.DataFrame:
    """The claims table: one row per claim."""
    return pd.DataFrame([{"claim": c.number, "figure": c.figure, "statement": c.text,
                          "measured": findings[c.number].measured,
                          "uncertainty": findings[c.number].uncertainty,
                          "verdict": findings[c.number].verdict,
                          "why": findings[c.number].why}
                         for c in CLAIMS if c.number in findings])


def _writable(path: Path) -> None:
    """UserError unless ``path`` is absent or a regular file (never a link)."""
    if path.is_symlink() or (path.exists() and not path.is_file()):
        raise UserError(f"{path} is not a regular file; refusing to replace it")


def _check_page(path: Path) -> None:
    _writable(path)
    if path.exists() and TITLE.encode() not in path.read_bytes()[:4096]:
        raise UserError(f"{path} exists and is not a contact-vv article page; refusing to "
                        "replace it (remove it or use another --out)")


def summary_html(table: pd.DataFrame) -> str:
    """One line per claim — its number (a link to its section), figure, statement, verdict
    and why in one sentence — the measured numbers and their uncertainty one click away."""
    rows = "".join(
        f'<tr class="{COLOURS.get(r["verdict"], "ng")}"><td class="l"><a href="#claim-'
        f'{r["claim"]}">{r["claim"]}</a></td><td class="l">{escape(str(r["figure"]))}</td>'
        f'<td class="l">{escape(str(r["statement"]))}</td>'
        f'<td class="l">{escape(str(r["verdict"]))}</td>'
        f'<td class="l">{escape(str(r["why"]))}</td></tr>' for _, r in table.iterrows())
    return ("<table><tr><th class='l'>claim</th><th class='l'>figure</th><th class='l'>"
            "statement</th><th class='l'>verdict</th><th class='l'>why</th></tr>"
            + rows + "</table>")


def _claim_html(claim: Claim, finding: Finding, png: str | None) -> str:
    return (f'<section id="claim-{claim.number}"><h2>Claim {claim.number} (article Fig. '
            f"{escape(claim.figure)}): {escape(finding.verdict)}</h2>"
            f"<p><i>{escape(claim.text)}</i></p>"
            f"<p><b>Measured:</b> {escape(finding.measured)}</p>"
            f"<p><b>Uncertainty:</b> {escape(finding.uncertainty)}</p>"
            f"<p><b>Why:</b> {escape(finding.why)}</p>"
            + (f'<figure><img alt="claim {claim.number}" loading="lazy" src="{png}"></figure>'
               if png else
               '<p class="warn">no figure: the results it needs are missing</p>')
            + "</section>")


def write_article(out: Path, article: Article, findings: dict[int, Finding],
                  header: str) -> Path:
    """Write the page, the figures and their data (module doc); the page's path."""
    out = Path(out)
    folder = out / layout.ARTICLE_DIR
    page = out / layout.ARTICLE
    _check_page(page)
    if folder.is_symlink() or (folder.exists() and not folder.is_dir()):
        raise UserError(f"{folder} is not a directory; refusing to write into it")
    table = claims_frame(findings)
    sections = []
    for claim in CLAIMS:
        if claim.number not in findings:
            continue
        finding = findings[claim.number]
        png = figure(finding.panels, f"Claim {claim.number} (article Fig. {claim.figure})")
        stem = f"claim_{claim.number:02d}"
        if png is not None:
            _writable(folder / f"{stem}.png")
            with atomic_path(folder / f"{stem}.png") as tmp:
                tmp.write_bytes(png)
            data = pd.concat([p.frame() for p in finding.panels], ignore_index=True)
            _writable(folder / f"{stem}.csv")
            write_csv(folder / f"{stem}.csv", data)
        sections.append(_claim_html(claim, finding, None if png is None else
                                    f"{layout.ARTICLE_DIR}/{stem}.png"))
    _writable(folder / layout.CLAIMS)
    write_csv(folder / layout.CLAIMS, table)
    counts = table["verdict"].value_counts()
    legend = ", ".join(f"{counts.get(v, 0)} {v}" for v in VERDICTS)
    missing = "".join(f'<p class="warn">{escape(k)}: {escape(v)}</p>'
                      for k, v in article.missing.items())
    body = (f"<!doctype html><html><head><meta charset='utf-8'><title>{TITLE}</title>"
            f"<style>{CSS}</style></head><body><h1>{TITLE}</h1><p>{escape(header)}</p>"
            f"<p>{escape(legend)}.</p>{missing}<h2>Claims</h2>"
            + summary_html(table)
            + "".join(sections) + "</body></html>")
    atomic_write_text(page, body)
    return page


def judge_and_write(out: Path, quick: bool, claims: tuple[int, ...]
                    ) -> tuple[Path, dict[int, Finding]]:
    """Judge ``claims`` from the results in ``out`` and write the page (module doc)."""
    article = collect(out, quick, claims)
    findings = judge(article, claims)
    size = "quick" if quick else "article"
    return write_article(out, article, findings, f"{size}-size results in {out}"), findings
