"""``solve(case)``: the FEM reference run of a case, in the common result format.

The run is assembled from one module per job:

- :mod:`fem_reference.model.fem_model`: the FE model of the case (mesh, symmetry, condensation);
- :mod:`fem_reference.run`: the set-up of a run (contact points, samples, recovery) and
  its state, started from the Hertz solution;
- :mod:`fem_reference.loading`: the load paths of static cases (normal, then
  tangential loading; one output step ``step = 0``) and sliding wear (output steps
  ``round(s / sliding_wear.step)``); :mod:`fem_reference.fretting`: fretting (output
  steps per output cycle, ``loops`` and ``cycles`` tables, regime events);
  :func:`load_path` picks the case's;
- :mod:`fem_reference.output`: the output of one step — surface fields on the case grid
  (the nodal tractions of :mod:`fem_reference.model.nodal_basis`, interpolated; the contact
  region, :mod:`fem_reference.fields.contact_zone`), the scalars, the stress planes and the
  load axis (:mod:`fem_reference.fields.planes`), the tables and the ``.vtu`` mesh.

Extra outputs: ``RunResult.tables["axis/<step>"]`` holds the stresses on the load axis
(x0, y0) at 8x the plane resolution in depth; ``tables["line_x/<step>"]`` and
``["line_y/<step>"]`` the projected tractions, the gap and the states along the lines
through the centre; ``RunResult.meta["vtu"]`` a list of ``(step, meshio.Mesh)`` with the
FE fields of the reported body (write them with :func:`fem_reference.fields.vtu.write_vtu`);
``meta`` also gives the model (quarter/half/full), DOFs, penalty and timings.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import asdict

import meshio

from cases.model import Case
from cases.result import RunResult, StepResult

from .errors import FemUnsupported
from .fretting import fretting_path
from .loading import sliding_wear_path, static_path
from .model.fem_model import FemModel
from .output import step_output
from .run import OutputState, Run, start_run


def load_path(run: Run, progress: bool = False) -> Iterator[OutputState]:
    """The output states of the case's load path: static, sliding wear or fretting."""
    kind = run.model.case.kind
    paths = {"static": static_path, "sliding_wear": sliding_wear_path,
             "fretting": fretting_path}
    if kind not in paths:
        raise FemUnsupported(f"kind {kind!r} is not supported by fem_reference")
    return paths[kind](run, progress)


def solve(case: Case, progress: bool = False, *, vtu: bool = True, log=None,
          on_output: Callable[[StepResult], None] | None = None) -> RunResult:
    """Run the FEM reference on ``case`` and return its :class:`~cases.result.RunResult`.

    ``on_output`` receives each output step as soon as it is computed (before the load
    path goes on).  ``vtu``: keep the FE fields of every output step in ``meta["vtu"]``
    as ``(step, meshio.Mesh)`` pairs.  ``log``: optional callable receiving progress
    messages (set-up timings).  Raises :class:`~fem_reference.model.fem_model.FemError` for a case
    the model cannot represent and
    :class:`~fem_reference.errors.ContactNotConverged` (with the residual) when the
    contact iteration fails.
    """
    t0 = time.perf_counter()
    model = FemModel(case, log=log)
    steps: list[StepResult] = []
    tables: dict = {}
    events = None
    meshes: list[tuple[int, meshio.Mesh]] = []
    try:
        run = start_run(model)
        for state in load_path(run, progress):
            out = step_output(run, state, t0=t0, vtu=vtu)
            steps.append(out.result)
            tables.update(out.tables)
            tables.update(state.tables)
            events = state.events if state.events is not None else events
            if out.mesh is not None:
                meshes.append((state.step, out.mesh))
            if on_output is not None:
                on_output(out.result)
    finally:
        model.free_memory()
    return RunResult(case=case.name, solver="fem", param=case.param, steps=steps,
                     meta=_meta(model, t0, meshes), tables=tables, events=events)


def _meta(model: FemModel, t0: float, meshes: list[tuple[int, meshio.Mesh]]) -> dict:
    """The run's ``meta``: model, mesh, penalty, sizes, timings and the ``.vtu`` meshes."""
    return {
        "model": model.shape,
        "mesh": asdict(model.spec),
        "a_ref": model.a_ref,
        "h": model.h,
        "r_c": model.surface.r_c,
        "k_n": model.law.k_n,
        "k_t": model.law.k_t,
        "law": model.law_mode,
        "dofs": int(model.free.size),
        "elements": int(model.space.nel),
        "surface_dofs": int(model.cidx.size),
        "timings": {**model.timings, "total_s": time.perf_counter() - t0},
        "vtu": meshes,
    }
