"""What the article's claims are judged from: the runs (a bundled case and the sweep of
the article's figures) and the thresholds (``contact-vv threshold``), at the article's
size or at quick size (``--quick``: the quick grids and cycle counts of the case files,
the article's sweep points kept, so that every claim is still decided).

At article size every sweep below is the bundled case's own, so the case directories of
``contact-vv run --all`` serve as they are; otherwise a source is run as the sweep
``DIR/<case>__sweep_<key>/`` (:func:`reports.run.sweep.plan_sweep`)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from cases.loader import CASES_DIR
from reports.registry.errors import IncompleteRun
from reports.store import layout
from reports.store.readers import DamagedResult, read_result, read_thresholds
from reports.store.results import CaseResults, read_case
from reports.studies.claims.finding import Article, value_of

#: the article's grid of the static and pin cases (docs/cases.md, cases 1–5)
ARTICLE_NX = 81


@dataclass(frozen=True)
class Source:
    """One case the claims read, with the values of its swept key ('' for none)."""

    case: str
    key: str = ""
    values: tuple[float, ...] = ()

    @property
    def label(self) -> str:
        return self.key.split(".")[-1]

    @property
    def name(self) -> str:
        """The case's name: a bundled case's, or a case file's stem."""
        return Path(self.case).stem


MU = (0.0, 0.15, 0.25, 0.35, 0.5, 0.65)
BETA = (0.0, 30.0, 60.0, 70.0, 80.0, 90.0)
#: the fretting case under the other normal control the article leaves open (load held),
#: and both controls with the other transverse motion it leaves open (free: Qy = 0)
FRETTING_LOAD = str(CASES_DIR / "examples" / "fretting_orthotropic_load.toml")
FRETTING_FREE = str(CASES_DIR / "examples" / "fretting_orthotropic_free.toml")
FRETTING_LOAD_FREE = str(CASES_DIR / "examples" / "fretting_orthotropic_load_free.toml")
#: the oblique angle of claim 11: the only sweep point where the transverse motion held
#: or free are different problems (at β = 0 and 90° the held reading carries no Qy)
BETA_OBLIQUE = (30.0,)
SOURCES: dict[str, Source] = {
    "hertz": Source("hertz"),
    "sliding": Source("sliding_friction", "friction.mu", MU),
    "pin": Source("pin_on_disk", "friction.mu", MU),
    "pin_ortho": Source("pin_on_disk_orthotropic", "friction.beta", (0.0, 45.0, 90.0)),
    "fretting": Source("fretting_orthotropic", "friction.beta", BETA),
    "fretting_load": Source(FRETTING_LOAD, "friction.beta", BETA),
    "fretting_free": Source(FRETTING_FREE, "friction.beta", BETA_OBLIQUE),
    "fretting_load_free": Source(FRETTING_LOAD_FREE, "friction.beta", BETA_OBLIQUE),
}


#: the sources each claim reads (claims 4 and 13 also read thresholds); claims 10 and 12
#: are at β = 0 and 90°, where the transverse motion held or free is the same problem
NEEDS = {1: ("hertz",), 2: ("pin",), 3: ("pin",), 4: ("pin",), 5: ("sliding",),
         **{n: ("pin_ortho",) for n in (6, 7, 8, 9)},
         **{n: ("fretting", "fretting_load") for n in (10, 12)},
         11: ("fretting", "fretting_load", "fretting_free", "fretting_load_free"),
         13: ("fretting",)}


def candidates(source: Source) -> list[str]:
    """Case directories that can serve a source, in order: the bundled run's, then the
    article's own sweep."""
    names = [source.name]
    if source.key:
        names.append(layout.sweep_dir_name(source.name, [source.key]))
    return names


def serves(case: CaseResults, source: Source, quick: bool) -> str | None:
    """None if a case directory holds every point a source needs at the size asked for,
    else why not."""
    if bool(case.manifest.get("quick")) != quick:
        return f"{case.path.name} is {'quick' if case.manifest.get('quick') else 'full'}-size"
    if case.manifest.get("overrides"):
        return f"{case.path.name} was run with --set {case.manifest['overrides']}"
    have = {value_of(p) for p in case.manifest.get("params", [])}
    lacking = [v for v in source.values if v not in have]
    if lacking:
        return (f"{case.path.name} has no {source.label} = "
                f"{', '.join(f'{v:g}' for v in lacking)}")
    return None


def find(out: Path, source: Source, quick: bool) -> tuple[CaseResults | None, str]:
    """The case directory under ``out`` that serves a source, or None and why not."""
    reasons = []
    for name in candidates(source):
        path = layout.case_dir(out, name)
        if not path.is_dir():
            continue
        try:
            case = read_case(path)
        except (DamagedResult, IncompleteRun) as exc:
            reasons.append(str(exc))
            continue
        why = serves(case, source, quick)
        if why is None:
            return case, ""
        reasons.append(why)
    return None, "; ".join(reasons) or f"not run ({' or '.join(candidates(source))})"


def collect(out: Path, quick: bool, claims: tuple[int, ...] = tuple(NEEDS)) -> Article:
    """The results the ``claims`` are judged from (:class:`Article`)."""
    cases, missing = {}, {}
    for key in dict.fromkeys(k for n in claims for k in NEEDS[n]):
        source = SOURCES[key]
        cases[key], why = find(out, source, quick)
        if why:
            missing[key] = why
    path = Path(out) / layout.THRESHOLDS
    thresholds = read_result(path, read_thresholds) if path.exists() else \
        pd.DataFrame(columns=["case", "event", "param", "solver", "grid", "threshold"])
    return Article(cases, missing, thresholds[of_tier(thresholds, quick)])


def of_tier(thresholds: pd.DataFrame, quick: bool) -> pd.Series:
    """The rows of ``thresholds.csv`` of one tier (its ``quick`` column reads as text)."""
    if "quick" not in thresholds.columns:
        return pd.Series(True, index=thresholds.index)
    text = thresholds["quick"].astype(str).str.strip().str.lower()
    return text.isin(("true", "1", "1.0")) == quick
