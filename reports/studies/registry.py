"""The studies a run knows (:class:`reports.studies.study.Study`), in the order their
runs run, their tables are written and their findings are folded into the verdict
(:func:`reports.compare.verdict.decide`).  A new study is a module and a line here."""

from __future__ import annotations

from reports.registry.errors import UserError
from reports.studies.gridstudy import GRID_STUDY
from reports.studies.jumpstudy import JUMP_STUDY
from reports.studies.probe import PROBE
from reports.studies.study import Study

#: every study, in order
STUDIES: list[Study] = [GRID_STUDY, JUMP_STUDY, PROBE]


def by_name(name: str) -> Study:
    """The study named ``name`` (UserError naming the known ones)."""
    for s in STUDIES:
        if s.name == name:
            return s
    raise UserError(f"unknown study {name!r} (known: {', '.join(s.name for s in STUDIES)})")


def rank(study: Study) -> int:
    """Where ``study`` stands in :data:`STUDIES` (one not listed: last)."""
    return next((k for k, s in enumerate(STUDIES) if s is study), len(STUDIES))
