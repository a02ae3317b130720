"""The common result container shared by every solver, and its atomic on-disk form.

A solver returns a :class:`RunResult`: per output step a :class:`StepResult` with the
scalar summary (the ``summary.csv`` columns, :data:`SUMMARY_COLUMNS`), surface fields on a regular
grid, and subsurface planes (xz and yz through the load centre).

Surface fields, arrays of shape (nx, ny) indexed [i, j] = (x[i], y[j]):
``p_n, p_x, p_y`` tractions on body a [MPa]; ``gap`` normal gap [mm]; ``slip_x, slip_y``
slip increment of the step [mm]; ``wear_a, wear_b`` accumulated wear depth [mm];
``state`` 0 open, 1 stick, 2 slip.

Plane fields, arrays of shape (ns, nz) for coordinates (s, z), s = x on 'xz' and y on
'yz', z the depth into the reported body: ``sxx, syy, szz, sxy, sxz, syz, vm`` [MPa].

Solvers that watch an evolution for regime events (gross -> partial slip, the load lost,
the contact worn through) list them in :attr:`RunResult.events` (:class:`RunEvent`).
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

SUMMARY_COLUMNS = [
    "case", "solver", "param", "step", "s", "cycle", "P", "Qx", "Qy", "contact_area",
    "a_x", "a_y", "p_max", "w_max", "wear_volume", "vm_max", "vm_max_x", "vm_max_y",
    "vm_max_z", "stick_area", "iterations", "converged", "wall_s",
]
STRESS_COMPONENTS = ("sxx", "syy", "szz", "sxy", "sxz", "syz")
OPEN, STICK, SLIP = 0, 1, 2  # the surface field ``state`` of every solver
#: the columns of an event (``events.csv`` adds ``case, solver, param`` before them)
EVENT_COLUMNS = ["event", "cycle", "cycle_resolution", "detail"]
#: a fretting run's ``cycles`` table, one row per simulated cycle: the real cycle count at
#: its end, the dissipated energy [N mm], the least stick area over its steps [mm²],
#: ``gross_slip`` (1 gross, 0 partial, NaN no contact), w_max [mm], the stick areas at
#: -A and +A [mm²], the least P [N] and the least contact area [mm²] over its steps
CYCLE_COLUMNS = ("cycle", "energy", "min_stick_area", "gross_slip", "w_max",
                 "stick_area_neg", "stick_area_pos", "P_min", "contact_area_min")
#: a fretting run's ``loops`` table, one row per step: real cycle, imposed displacement,
#: tangential loads [N]
LOOP_COLUMNS = ("cycle", "displacement", "Qx", "Qy")
#: the event ``load_lost``: under a held approach the least P of a cycle falls below this
#: fraction of P0, the load after the initial loading (the contact then carries too little
#: load for its tractions, stresses and wear to matter; P itself only decays geometrically
#: under implicit wear, and reaches 0 only when the contact is worn through)
LOAD_LOST_FRACTION = 0.01


def table_of(columns: tuple[str, ...], values: Mapping[str, object],
             extra: tuple[str, ...] = ()) -> dict[str, np.ndarray]:
    """A run's table (``cycles``: :data:`CYCLE_COLUMNS`, ``loops``: :data:`LOOP_COLUMNS`)
    from ``values`` (column -> values, in their order): each column one of ``columns`` or
    of the solver's own ``extra`` ones, else ValueError naming it (a misspelt column
    would be a column no comparison reads)."""
    unknown = [c for c in values if c not in columns and c not in extra]
    if unknown:
        raise ValueError(f"table column(s) {', '.join(unknown)}: not among "
                         f"{', '.join(columns)} nor the solver's own {', '.join(extra)}")
    return {c: np.atleast_1d(np.asarray(v, dtype=float)) for c, v in values.items()}


def von_mises(sxx, syy, szz, sxy, sxz, syz):
    """Von Mises equivalent stress sqrt(3 J2)."""
    return np.sqrt(
        0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2)
        + 3.0 * (sxy**2 + sxz**2 + syz**2)
    )


def semi_widths(x: np.ndarray, y: np.ndarray, p_n: np.ndarray) -> tuple[float, float]:
    """``(a_x, a_y)`` [mm]: half the extent of the contact (the cells with ``p_n > 0``)
    along x and along y, each cell counted with its width — the contact's own semi-axes,
    wherever its centre and the stress planes lie (``cases/README.md``, ``a_x``).  On a
    regular grid of spacing h the value moves in steps of h/2 and lies within h/2 of the
    semi-axis of the discrete contact; 0 without contact."""
    pressed = p_n > 0
    if not pressed.any():
        return 0.0, 0.0

    def half_extent(coord: np.ndarray, along: np.ndarray) -> float:
        c = coord[along]
        width = float(coord[1] - coord[0]) if coord.size > 1 else 0.0
        return 0.5 * float(c.max() - c.min() + width)

    return half_extent(x, pressed.any(axis=1)), half_extent(y, pressed.any(axis=0))


@dataclass
class Plane:
    """A subsurface plane: coordinate s along the plane, depth z, stress components."""

    s: np.ndarray
    z: np.ndarray
    fields: dict[str, np.ndarray]

    def vm_max(self) -> tuple[float, float, float]:
        """(max sigma_VM, s at max, z at max)."""
        vm = self.fields["vm"]
        i, k = np.unravel_index(int(np.argmax(vm)), vm.shape)
        return float(vm[i, k]), float(self.s[i]), float(self.z[k])


def vm_max_location(planes: Mapping[str, Plane], x0: float, y0: float
                    ) -> tuple[float, float, float, float]:
    """(max σ_VM, x, y, z) over the planes: ``xz`` lies at y = ``y0``, ``yz`` at x = ``x0``
    (the coordinates where the solver sampled them).  On a tie the first plane wins;
    planes without a finite σ_VM field (what a closed form does not cover) are skipped;
    NaNs when no plane has one."""
    best = (math.nan,) * 4
    for name, plane in planes.items():
        vm = plane.fields.get("vm")
        if vm is None or vm.size == 0 or not np.isfinite(vm).all():
            continue
        value, s_at, z_at = plane.vm_max()
        if not math.isfinite(best[0]) or value > best[0]:
            best = (value, s_at, y0, z_at) if name == "xz" else (value, x0, s_at, z_at)
    return best


def vm_max_below(planes: Mapping[str, Plane], z_below: float) -> float:
    """The largest σ_VM over the planes' samples at depth z >= ``z_below`` (a maximum
    that stays a number where the surface maximum is singular, e.g. at the step-like
    edge of a worn frictional contact, docs/formulation.md §2.6); NaN when no plane has a
    finite σ_VM field there."""
    best = math.nan
    for plane in planes.values():
        vm = plane.fields.get("vm")
        if vm is None or vm.size == 0 or not np.isfinite(vm).all():
            continue
        deep = np.asarray(plane.z) >= z_below * (1.0 - 1e-12)
        if deep.any():
            value = float(np.max(vm[:, deep]))
            best = value if math.isnan(best) else max(best, value)
    return best


@dataclass
class StepResult:
    scalars: dict[str, float]
    x: np.ndarray
    y: np.ndarray
    surface: dict[str, np.ndarray]
    planes: dict[str, Plane] = field(default_factory=dict)

    def number(self, index: int) -> int:
        """The output step number: the ``step`` scalar, else ``index`` (its position)."""
        value = self.scalars.get("step")
        if value is None or not math.isfinite(float(value)):
            return index
        return int(value)


@dataclass(frozen=True)
class RunEvent:
    """A regime event of an evolution run (e.g. ``gross_to_partial_slip``): it happened
    after cycle ``cycle - cycle_resolution`` and at or before cycle ``cycle`` (real
    cycles: a solver with a cycle jump J sees it to within J); ``detail`` says what
    was seen."""

    event: str
    cycle: float
    cycle_resolution: float
    detail: str = ""

#: the slip regimes of a fretting cycle (:func:`cycle_regime`)
GROSS, PARTIAL = "gross", "partial"


def cycle_regime(stick: list[float], contact: list[float]) -> str | None:
    """The slip regime of a fretting cycle from the stick and the contact (areas, cells or
    nodes) at its tangential extremes ±A: :data:`GROSS` when at either extreme nothing
    sticks (every point in contact is on the friction limit, Eq. 13: the whole contact
    slid), :data:`PARTIAL` when something sticks at both, None when an extreme has no
    contact."""
    if not contact or min(contact) <= 0:
        return None
    return GROSS if min(stick) <= 0 else PARTIAL


def gross_slip(regime: str | None) -> float:
    """The ``gross_slip`` column of the ``cycles`` table (:data:`CYCLE_COLUMNS`)."""
    return math.nan if regime is None else float(regime == GROSS)


class RegimeEvents:
    """The regime events of a fretting run (docs/cases.md, case 6), one simulated cycle
    at a time, the same rules for every solver: ``gross_to_partial_slip`` /
    ``partial_to_gross_slip`` when the regime of a cycle (:func:`cycle_regime`) changes,
    the first cycle compared with the initial loading 0 -> +A; under a held approach
    ``load_lost`` (the least P of a cycle below :data:`LOAD_LOST_FRACTION` of P0, the
    load after the initial loading) and ``contact_worn_through`` (a step with nothing in
    contact), each once.

    Simulated cycle n stands for the real cycles (n - 1) J + 1 .. n J (J the cycle jump,
    the last one cut at ``total``): an event seen in it is recorded at cycle min(n J,
    total) with ``cycle_resolution`` J, i.e. it happened after cycle (n - 1) J and at or
    before n J.  ``nothing`` says what "nothing in contact" is for the solver ("no
    contact cell", "no node in contact")."""

    def __init__(self, jump: float, total: float, P0: float, regime: str | None,
                 stick: float, held_approach: bool, nothing: str):
        self.jump, self.total, self.P0, self.held = jump, total, P0, held_approach
        self.regime, self.stick, self.nothing = regime, stick, nothing
        self.last = (0.0, P0)  # (cycle, least P) of the last cycle with contact
        self.events: list[RunEvent] = []

    def cycle(self, n: int) -> float:
        """The real cycle count at the end of simulated cycle n."""
        return float(min(n * self.jump, self.total))

    def observe(self, n: int, regime: str | None, stick: float, P_min: float,
                contact_min: float) -> None:
        """Record the events of simulated cycle n: its regime, its least stick area at
        the extremes [mm²], its least P [N] and least contact over its steps."""
        at, before = self.cycle(n), self.cycle(n - 1)
        if regime is not None:  # without contact at an extreme, no regime
            if self.regime is not None and regime != self.regime:
                self._add(f"{self.regime}_to_{regime}_slip", at, before,
                          f"least stick area at the extremes ±A {self.stick:.4g} mm² at "
                          f"cycle {before:g} -> {stick:.4g} mm² at cycle {at:g}")
            self.regime, self.stick = regime, stick
        if self.held:
            self._load(P_min, contact_min, at, before)
        if contact_min > 0:
            self.last = (at, P_min)

    def _add(self, event: str, at: float, before: float, detail: str) -> None:
        self.events.append(RunEvent(event, at, at - before, detail))

    def _load(self, P_min: float, contact_min: float, at: float, before: float) -> None:
        done = {e.event for e in self.events}
        if "load_lost" not in done and P_min < LOAD_LOST_FRACTION * self.P0:
            self._add("load_lost", at, before,
                      f"P = {P_min:.4g} N < {LOAD_LOST_FRACTION:.0%} of P0 = "
                      f"{self.P0:.4g} N (least P of the cycle; P0 after the initial "
                      "loading)")
        if "contact_worn_through" not in done and contact_min <= 0:
            self._add("contact_worn_through", at, before,
                      f"{self.nothing}, P = 0 (least P {self.last[1]:.4g} N at cycle "
                      f"{self.last[0]:g}, the last with contact)")



@dataclass
class RunResult:
    """What a solver returns for one sweep point: the output steps, metadata, per-cycle
    or per-step tables (numeric columns), and ``events``: the regime events a solver
    that watches for them saw (None: it does not watch; [] it watched, none happened)."""

    case: str
    solver: str
    param: str
    steps: list[StepResult]
    meta: dict = field(default_factory=dict)
    tables: dict[str, dict[str, np.ndarray]] = field(default_factory=dict)
    events: list[RunEvent] | None = None

    def summary_rows(self) -> list[dict]:
        """One ``summary.csv`` row per output step: the contract columns
        (:data:`SUMMARY_COLUMNS`, NaN where a solver says nothing), then every further
        scalar of the step; ``step`` is :meth:`StepResult.number`."""
        rows = []
        for k, step in enumerate(self.steps):
            row = {c: step.scalars.get(c, math.nan) for c in SUMMARY_COLUMNS}
            row.update({key: v for key, v in step.scalars.items() if key not in row})
            row.update(case=self.case, solver=self.solver, param=self.param,
                       step=step.number(k))
            rows.append(row)
        return rows

    def event_rows(self) -> list[dict]:
        """One ``events.csv`` row per event: ``case, solver, param``, then
        :data:`EVENT_COLUMNS`, in the order the solver saw them."""
        return [{"case": self.case, "solver": self.solver, "param": self.param,
                 **{c: getattr(e, c) for c in EVENT_COLUMNS}} for e in self.events or ()]


@dataclass(frozen=True)
class Cost:
    """What a solver expects a case to take before it starts (its ``estimate(case)``):
    peak memory [bytes] and wall time [s] (order of magnitude), each with the case keys
    that drive it, so a refusal can name what to change."""

    memory: float
    seconds: float
    memory_keys: tuple[str, ...] = ()
    time_keys: tuple[str, ...] = ()
    #: the calibration of ``seconds``: measured wall times lie within this factor of it
    #: (a run past it has gone wrong: reports.run.deadline); inf: not calibrated
    time_factor: float = math.inf


# ---------------------------------------------------------------- atomic files


def _umask() -> int:
    """The process's umask (read by setting and restoring it)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


@contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success give it the mode a plain
    ``open`` would (0666 less the umask), flush it to disk and rename it onto ``path``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=path.parent)
    os.close(fd)
    tmp = Path(tmp)
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~_umask())
        with open(tmp, "rb+") as fh:
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def atomic_write_text(path: str | Path, text: str) -> None:
    with atomic_path(path) as tmp:
        tmp.write_text(text)


def save_step(path: str | Path, step: StepResult) -> None:
    """Write one step as ``.npz`` atomically (surface fields, planes, scalars as JSON)."""
    arrays: dict[str, np.ndarray] = {"x": step.x, "y": step.y}
    for key, arr in step.surface.items():
        arrays[f"surface/{key}"] = arr
    for name, plane in step.planes.items():
        arrays[f"plane/{name}/s"] = plane.s
        arrays[f"plane/{name}/z"] = plane.z
        for comp, arr in plane.fields.items():
            arrays[f"plane/{name}/{comp}"] = arr
    arrays["scalars"] = np.array(json.dumps(step.scalars, default=float))
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as fh:
            np.savez_compressed(fh, **arrays)


def load_step(path: str | Path) -> StepResult:
    with np.load(path) as data:
        surface, planes_raw = {}, {}
        for key in data.files:
            if key.startswith("surface/"):
                surface[key.split("/", 1)[1]] = data[key]
            elif key.startswith("plane/"):
                _, name, comp = key.split("/")
                planes_raw.setdefault(name, {})[comp] = data[key]
        planes = {
            name: Plane(s=d.pop("s"), z=d.pop("z"), fields=d) for name, d in planes_raw.items()
        }
        return StepResult(
            scalars=json.loads(str(data["scalars"])), x=data["x"], y=data["y"],
            surface=surface, planes=planes,
        )


def write_vtu(path: str | Path, mesh: Any) -> Path:
    """Write the meshio mesh ``mesh`` to ``path`` (.vtu, binary, written atomically, so a
    reader never sees half a file; :func:`atomic_path`); return the path.  The one writer
    of every ``.vtu`` file of a run: the FEM's meshes and the grid solvers' steps."""
    import meshio

    path = Path(path)
    if path.suffix != ".vtu":
        raise ValueError(f"{path}: expected a .vtu file name")
    if not isinstance(mesh, meshio.Mesh):
        raise TypeError(f"{path}: a {type(mesh).__name__}, not a meshio.Mesh")
    with atomic_path(path) as tmp:
        meshio.write(tmp, mesh, file_format="vtu", binary=True)
    return path


def read_vtu(path: str | Path) -> Any:
    """The meshio mesh :func:`write_vtu` wrote to ``path``."""
    import meshio

    return meshio.read(path, file_format="vtu")
