"""Where a run puts its files: the output layout of ``DIR/<case>/``.

::

    DIR/<case>/manifest.json                      written last: the run is complete
    DIR/<case>/summary.csv                        one row per (solver, param, step)
    DIR/<case>/metrics.csv                        one row per compared quantity
    DIR/<case>/events.csv                         fretting: one row per regime event
                                                  (reports.store.event_table)
    DIR/<case>/convergence.csv                    run --convergence: one row per (solver,
                                                  param, step, gated quantity) of the
                                                  three-grid studies (reports.studies.gridstudy)
    DIR/<case>/jump_study.csv                     run --jump-study: one row per (solver,
                                                  param, output cycle, quantity) of the
                                                  cycle-jump studies (reports.studies.jumpstudy)
    DIR/<case>/probe.csv                          worn points the FEM runs: one row per
                                                  (param, pair, step, quantity, metric) of
                                                  the resolution probe (reports.studies.probe)
    DIR/<case>/<study>.csv                        the table of any study of the run
                                                  (reports.studies.study, study_file)
    DIR/<case>/fields/<solver>/<param>/step_NNNN.npz   surface fields and planes
    DIR/<case>/fields/<solver>/<param>/step_NNNN.vtu   FEM meshes (ParaView)
    DIR/<case>/fields/<solver>/<param>/step_NNNN_surface.vtu   grid steps: surface cells
    DIR/<case>/fields/<solver>/<param>/step_NNNN_planes.vtu    grid steps: xz/yz planes
    DIR/<case>/fields/<solver>/<param>/<table>.csv     tables (e.g. fretting loops)
    DIR/.<case>.partial/                          staging area of a run in progress
    DIR/.<case>.lock                              locked by the run of <case> in progress

``<param>`` is the sweep label (``mu=0.25``) or ``base`` for a case without a sweep.
The fields are those of the run's own grid; the coarser grids of a grid study write no
fields, only ``convergence.csv`` (and their records in the manifest's ``units``).
A run writes into the staging directory and renames it to ``DIR/<case>`` only after the
manifest is written, so a case directory is either complete or absent.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path

MANIFEST = "manifest.json"
SUMMARY = "summary.csv"
METRICS = "metrics.csv"


def study_file(name: str) -> str:
    """The table of the study ``name`` in a case directory (:mod:`reports.studies.study`)."""
    return f"{name}.csv"


#: the tables of the studies the store knows (:mod:`reports.store.study_tables`)
CONVERGENCE = study_file("convergence")
JUMP_STUDY = study_file("jump_study")
PROBE = study_file("probe")
EVENTS = "events.csv"
FIELDS = "fields"
PARTIAL_SUFFIX = ".partial"
#: the report's case pages' folder (reports.render.pages): no case's name, since a case
#: name starts with a letter or digit; its staging folder is the report's, not a case's
REPORT_PAGES = "_report"
FAILED = "failed.json"
SWEEP_PLOT = "sweep.png"
SWEEP_CHECK = "sweep_check.json"
#: beside the case directories: ``contact-vv threshold``'s table and the report
THRESHOLDS = "thresholds.csv"
REPORT = "index.html"
#: ``contact-vv article``: its page, and the folder of its figures (PNG), their data (CSV)
#: and the claims table (CSV)
ARTICLE = "article.html"
ARTICLE_DIR = "article"
CLAIMS = "claims.csv"


#: names a case directory may hold; a directory with none of them is not a result
OWN_NAMES = frozenset({MANIFEST, SUMMARY, METRICS, CONVERGENCE, JUMP_STUDY, PROBE, EVENTS,
                       FIELDS,
                       SWEEP_PLOT, SWEEP_CHECK})

_UNSAFE = re.compile(r"[^A-Za-z0-9._=+-]")


def safe_name(text: str) -> str:
    """A file-name-safe form of a case name or sweep label: one plain path component
    (never empty, ``.`` or ``..``)."""
    name = _UNSAFE.sub("_", text)
    return name if name.strip(".") else "_" * max(len(name), 1)


def param_dir(param: str) -> str:
    """Directory name of one sweep point: the label, or ``base`` without a sweep."""
    return safe_name(param) if param else "base"


def case_dir(out: Path, case: str) -> Path:
    return Path(out) / safe_name(case)


def sweep_dir_name(case: str, keys: list[str]) -> str:
    """The case directory's name of ``contact-vv sweep CASE --param KEY=...`` (one or more
    swept dotted keys): ``<case>__sweep_<last parts of the keys>``."""
    return f"{case}__sweep_" + "_".join(key.split(".")[-1] for key in keys)


def staging_dir(out: Path, case: str) -> Path:
    return Path(out) / f".{safe_name(case)}{PARTIAL_SUFFIX}"


def lock_file(out: Path, case: str) -> Path:
    """The file whose OS lock a run of ``case`` holds (reports.store.staging.case_lock)."""
    return Path(out) / f".{safe_name(case)}.lock"


def unit_dir(root: Path, solver: str, param: str) -> Path:
    """Field directory of one (solver, sweep point) under a case or staging directory."""
    return Path(root) / FIELDS / safe_name(solver) / param_dir(param)


def step_file(root: Path, solver: str, param: str, step: int, ext: str = "npz") -> Path:
    return unit_dir(root, solver, param) / f"step_{int(step):04d}.{ext}"


def looks_like_result(path: Path) -> bool:
    """Whether a directory holds anything a run writes (so it may be a damaged result)."""
    return Path(path).is_dir() and any((Path(path) / n).exists() for n in OWN_NAMES)


#: what a run writes into fields/<solver>/<param>/: output steps and their meshes (.npz,
#: .vtu) and solver tables (.csv), named by :func:`safe_name`
_FIELD_FILE = re.compile(r"[A-Za-z0-9._=+-]+\.(npz|vtu|csv)")
#: the temporary of an atomic write of file NAME (cases.result.atomic_path, tempfile's
#: eight random characters) that a crash left behind
_TEMPORARY = re.compile(r"\.(?P<name>.+)\.[a-z0-9_]{8}\.part")


def _own_file(name: str, own: Callable[[str], bool]) -> bool:
    """Whether ``name`` is a file the run writes (``own``) or the temporary of one."""
    m = _TEMPORARY.fullmatch(name)
    return own(m.group("name") if m else name)


def foreign(root: Path, extra: frozenset[str] = frozenset()) -> Path | None:
    """The first path below ``root`` that a run did not write, None when every entry is a
    run's: a symbolic link anywhere; at the top a name other than :data:`OWN_NAMES` (and
    ``extra``); under ``fields/`` anything but directories ``<solver>/<param>/`` of step
    files, meshes and tables.  Temporaries of the atomic writes of those count as the
    run's.  Links are never followed."""
    def plain_dir(p: Path) -> bool:
        return p.is_dir() and not p.is_symlink()

    def plain_file(p: Path, own: Callable[[str], bool]) -> bool:
        return p.is_file() and not p.is_symlink() and _own_file(p.name, own)

    top_names = (OWN_NAMES | extra) - {FIELDS}
    for top in sorted(Path(root).iterdir()):
        if top.name == FIELDS and plain_dir(top):
            for solver in sorted(top.iterdir()):
                if not plain_dir(solver):
                    return solver
                for point in sorted(solver.iterdir()):
                    if not plain_dir(point):
                        return point
                    for f in sorted(point.iterdir()):
                        if not plain_file(f, _FIELD_FILE.fullmatch):
                            return f
        elif not plain_file(top, top_names.__contains__):
            return top
    return None


def partial_case_name(path: Path) -> str | None:
    """The case name of a case's staging directory, or None if ``path`` is not one (the
    report's own, ``._report.partial``, is not: ``_report`` is no case name)."""
    name = Path(path).name
    if name.startswith(".") and name.endswith(PARTIAL_SUFFIX):
        case = name[1 : -len(PARTIAL_SUFFIX)]
        return None if case == REPORT_PAGES else case
    return None
