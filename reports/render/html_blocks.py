"""The pieces of the report's HTML: its style sheet, escaping, inlined PNG figures and
tables whose rows carry a pass / fail or a given class."""

from __future__ import annotations

import base64
import html
import math
from collections.abc import Callable
from typing import Any

import pandas as pd

from reports.render.frame import png

CSS = """
body{font-family:system-ui,sans-serif;margin:1.5em;max-width:1400px;color:#222}
h1{margin-bottom:0}h2{border-bottom:2px solid #446;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}
td,th{border:1px solid #bbb;padding:.15em .5em;text-align:right}
th{background:#eef}td.l,th.l{text-align:left}
tr.pass td{background:#e5f5e5}tr.fail td{background:#fbdcdc;font-weight:600}
tr.ng td{background:#fff3cd}
.warn{background:#fff3cd;border:1px solid #e0c060;padding:.5em 1em}
.bad{color:#a00;font-weight:600}.ok{color:#070;font-weight:600}
figure{margin:.5em 0}img{max-width:100%}
.provenance{background:#f6f6f9;border:1px solid #ccd;padding:.5em 1em;font-size:.85em}
.scroll{max-height:30em;overflow:auto}
"""


def escape(text: Any) -> str:
    return html.escape(str(text))


def img(png: bytes, alt: str) -> str:
    data = base64.b64encode(png).decode("ascii")
    return f'<figure><img alt="{escape(alt)}" src="data:image/png;base64,{data}"></figure>'


def fig(fig, alt: str) -> str:
    return img(png(fig), alt) if fig is not None else ""


def fmt(v: Any) -> str:
    if isinstance(v, float):
        return "" if math.isnan(v) else f"{v:.4g}"
    return escape(v)


def table_html(frame: pd.DataFrame, *, status: str | None = None, left: int = 0,
               row_class: Callable[[pd.Series], str] | None = None) -> str:
    """An HTML table; rows coloured by a boolean column ``status`` (pass / fail), or given
    the class ``row_class(row)`` (none if it returns '')."""
    head = "".join(f'<th class="{"l" if i < left else ""}">{escape(c)}</th>'
                   for i, c in enumerate(frame.columns))
    body = []
    for _, row in frame.iterrows():
        cls = ""
        if status is not None:
            ok = str(row[status]).lower() in ("true", "1")
            cls = ' class="pass"' if ok else ' class="fail"'
        elif row_class is not None and row_class(row):
            cls = f' class="{escape(row_class(row))}"'
        cells = "".join(f'<td class="{"l" if i < left else ""}">{fmt(v)}</td>'
                        for i, v in enumerate(row.tolist()))
        body.append(f"<tr{cls}>{cells}</tr>")
    return f"<table><tr>{head}</tr>{''.join(body)}</table>"
