"""The frame of the report's figures: panels in fixed margins, their colorbars, and the
PNG bytes of a figure (Agg backend, no display)."""

from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

DPI = 80

#: the frame of every figure, in inches: its margins (the left one holds a panel's tick
#: labels and y label, the top one the figure's and a panel's title), the gaps between
#: panels, and what a colorbar's ticks and label add to the right of its panel.  A fixed
#: frame draws each figure once (matplotlib's constrained layout draws it a second time
#: to measure its labels, and ``bbox_inches="tight"`` a second time to crop).
LEFT, RIGHT, BOTTOM, TOP = 0.8, 0.25, 0.55, 0.62
ACROSS, DOWN = 0.85, 0.85
COLORBAR = 0.8


def panels(nrows: int, ncols: int, size: tuple[float, float], *, colorbar: str = "",
           **kw) -> tuple[Figure, np.ndarray]:
    """A figure of ``nrows`` × ``ncols`` panels of ``size`` (width, height) inches each
    in the fixed frame above (``plt.subplots``'s axes, squeezed as it does unless
    ``squeeze=False``); ``colorbar`` "each" leaves room for a colorbar right of every
    panel (:func:`colorbar`), "shared" for one right of them all."""
    w, h = size
    across = ACROSS + (COLORBAR if colorbar == "each" else 0.0)
    right = RIGHT + (COLORBAR if colorbar else 0.0)
    width = LEFT + ncols * w + (ncols - 1) * across + right
    height = BOTTOM + nrows * h + (nrows - 1) * DOWN + TOP
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, height), **kw)
    fig.subplots_adjust(left=LEFT / width, right=1 - right / width, bottom=BOTTOM / height,
                        top=1 - TOP / height, wspace=across / w, hspace=DOWN / h)
    return fig, axes


def colorbar(fig: Figure, mappable, ax, label: str, **kw):
    """A colorbar 0.15 in wide taken from the right of ``ax`` (a panel, or a list of
    panels for a shared one), its ticks and label in the room :func:`panels` left."""
    boxes = [a.get_position() for a in np.atleast_1d(ax)]
    span = (max(b.x1 for b in boxes) - min(b.x0 for b in boxes)) * fig.get_figwidth()
    return fig.colorbar(mappable, ax=ax, label=label, fraction=0.15 / span, pad=0.1 / span,
                        **kw)


def png(fig: Figure) -> bytes:
    """Render and close a figure, drawn once in its fixed frame (:func:`panels`)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=DPI)
    plt.close(fig)
    return buf.getvalue()
