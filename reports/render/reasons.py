"""Why a metric row is shown and not gated, in a word: the short reason of its note, as
the gate's per-case line and the baselines of gated rows name it."""

from __future__ import annotations

from reports.compare.maxima import EDGE_NOTE, SURFACE_NOTE
from reports.compare.metrics import KINK_NOTE
from reports.studies import probe

#: why a row is shown and not gated, by the start of its note (the notes' own texts:
#: reports.registry.tolerances, reports.registry.resolution, reports.compare.point,
#: reports.studies.gridstudy, reports.studies.probe), as the gate's per-case line names
#: them
REASONS = (("declared: ", "declared"), ("not resolved", "below a resolution floor"),
           (KINK_NOTE, "stick band"), (EDGE_NOTE, "edge band"),
           (SURFACE_NOTE, "maximum on the surface"), ("grid study", "grid study"),
           ("jump study", "jump study"), (probe.NOTE, "resolution probe"))


def reason_of(note: str) -> str:
    """The short reason of a not-gated row's note (:data:`REASONS`; 'other')."""
    note = str(note)
    return next((label for start, label in REASONS if note.startswith(start[:40])), "other")
