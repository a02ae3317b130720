"""Fake solvers for the reports/CLI tests (no tests here).

``solve_exact`` returns the Hertz solution sampled on the case grid with a synthetic
σ_VM field; ``solve_ic`` returns the same scaled by ``1 + ERROR``, so every relative
metric of the pair ic-analytic is exactly ``ERROR`` and every length metric zero.
"""

from __future__ import annotations

import math
import os
import time

import numpy as np

from cases.model import Case, CaseError
from cases.result import Plane, RunResult, StepResult, von_mises

ERROR = 0.015  # relative error of the fake "ic" solver (below every default tolerance)
N_STEPS = 3  # output steps of a sliding_wear case


def hertz_step(case: Case, scale: float, k: int) -> StepResult:
    a0, p0 = case.hertz_scales
    x, y = case.grid.x, case.grid.y
    r2 = x[:, None] ** 2 + y[None, :] ** 2
    p = scale * p0 * np.sqrt(np.clip(1.0 - r2 / a0**2, 0.0, None))
    mu = case.friction.mu1
    wear = scale * 1e-4 * k * p / p0
    surface = {
        "p_n": p, "p_x": mu * p, "p_y": np.zeros_like(p), "gap": np.where(p > 0, 0.0, 1e-4),
        "slip_x": np.zeros_like(p), "slip_y": np.zeros_like(p), "wear_a": wear,
        "wear_b": np.zeros_like(p), "state": np.where(p > 0, 2, 0),
    }
    z = case.stress.z
    planes = {}
    for name, s in (("xz", x), ("yz", y)):
        S, Z = np.meshgrid(s / a0, z / a0, indexing="ij")
        szz = -scale * p0 * np.exp(-(S**2) - (Z - 0.48) ** 2)
        zeros = np.zeros_like(szz)
        f = {"sxx": 0.5 * szz, "syy": 0.5 * szz, "szz": szz, "sxy": zeros, "sxz": zeros,
             "syz": zeros}
        f["vm"] = von_mises(**f)
        planes[name] = Plane(s=s, z=z, fields=f)
    vm, sx, sz = planes["xz"].vm_max()
    dx, dy = case.grid.dx, case.grid.dy
    inside = p > 0
    step_len = case.sliding_wear.step if case.sliding_wear else 0.0
    scalars = {
        "step": k, "s": k * step_len if case.sliding_wear else math.nan,
        "P": float(p.sum() * dx * dy), "contact_area": float(inside.sum() * dx * dy),
        "a_x": float(np.abs(x[inside.any(axis=1)]).max() + dx / 2),
        "a_y": float(np.abs(y[inside.any(axis=0)]).max() + dy / 2),
        "p_max": float(p.max()), "w_max": float(wear.max()),
        "wear_volume": float(wear.sum() * dx * dy), "vm_max": vm, "vm_max_x": sx,
        "vm_max_y": 0.0, "vm_max_z": sz, "iterations": 7, "converged": True,
        "wall_s": 0.001,
    }
    return StepResult(scalars=scalars, x=x, y=y, surface=surface, planes=planes)


def _result(case: Case, solver: str, scale: float) -> RunResult:
    n = N_STEPS if case.kind == "sliding_wear" else 1
    steps = [hertz_step(case, scale, k) for k in range(n)]
    tables = {}
    if case.kind == "sliding_wear":
        d = 1e-3 * np.tile(np.linspace(-4.0, 4.0, 9), 2)
        tables["loops"] = {"cycle": np.repeat([1.0, 2.0], 9), "displacement": d,
                           "Qx": scale * np.tanh(3e3 * d), "Qy": np.zeros_like(d)}
    return RunResult(case=case.name, solver=solver, param=case.param, steps=steps,
                     meta={"note": "fake"}, tables=tables)


def solve_exact(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    return _result(case, "analytic", 1.0)


def solve_ic(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    return _result(case, "ic", 1.0 + ERROR)


def solve_fem(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    """The exact solution with a (tiny) FE mesh per output step in meta["vtu"]."""
    import meshio

    result = _result(case, "fem", 1.0 - ERROR)
    points = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    result.meta["vtu"] = [
        (k, meshio.Mesh(points, [("tetra", np.array([[0, 1, 2, 3]]))],
                        point_data={"u_z": np.arange(4.0) * k}))
        for k in range(len(result.steps))]
    return result


def solve_bad_vtu(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    result = solve_exact(case)
    result.meta["vtu"] = [(0, "not a mesh")]
    return result


def solve_slow(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    """The fake ic, after a pause (for interruption tests)."""
    time.sleep(float(os.environ.get("FAKE_SLEEP", "0.5")))
    return solve_ic(case, progress=progress)


def _burn(seconds: float) -> None:
    """Spend ``seconds`` of this thread's CPU time."""
    t0 = time.thread_time()
    while time.thread_time() - t0 < seconds:
        sum(range(1000))


def solve_busy(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    """The fake ic after FAKE_SLEEP seconds of CPU time (a run that computes too long)."""
    _burn(float(os.environ.get("FAKE_SLEEP", "0.5")))
    return solve_ic(case, progress=progress)


def solve_crowded(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    """The fake ic as a busy machine runs it: FAKE_SLEEP seconds of CPU time spread over
    FAKE_STRETCH times as much wall time (computing one part in FAKE_STRETCH)."""
    cpu = float(os.environ.get("FAKE_SLEEP", "0.5"))
    stretch = float(os.environ.get("FAKE_STRETCH", "8"))
    for _ in range(20):
        _burn(cpu / 20)
        time.sleep(cpu / 20 * (stretch - 1))
    return solve_ic(case, progress=progress)


def solve_streaming(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    """The fake ic with N_STEPS output steps, one every FAKE_SLEEP seconds, each handed to
    ``on_output`` as it is computed (as the half-space wear runs do)."""
    steps = []
    for k in range(N_STEPS):
        time.sleep(float(os.environ.get("FAKE_SLEEP", "0.5")))
        steps.append(hertz_step(case, 1.0 + ERROR, k))
        if on_output is not None:
            on_output(steps[-1])
    return RunResult(case=case.name, solver="ic", param=case.param, steps=steps)


class NotConverged(RuntimeError):
    pass


def solve_diverging(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    raise NotConverged("Uzawa iteration did not converge: residual 3.2e-04 > tol 1e-10 "
                       "after 20000 iterations")


def solve_edge(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    raise CaseError("the contact area reaches the edge of the potential contact grid "
                    "(grid.Lx, grid.Ly too small)")


def solve_nan(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    result = solve_ic(case)
    result.steps[0].surface["p_n"][0, 0] = np.nan
    return result


def solve_partial(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    """A closed form that covers the surface only: NaN σ_VM scalars and planes."""
    result = solve_exact(case)
    for step in result.steps:
        for key in ("vm_max", "vm_max_x", "vm_max_y", "vm_max_z", "stick_area"):
            step.scalars[key] = math.nan
        for plane in step.planes.values():
            plane.fields["vm"] = np.full_like(plane.fields["vm"], np.nan)
    return result


def solve_nan_scalar(case: Case, *, progress: bool = False, on_output=None) -> RunResult:
    result = solve_ic(case)
    result.steps[0].scalars["p_max"] = math.nan
    return result


def supports_all(case: Case) -> str | None:
    return None


def fem_supports(case: Case) -> str | None:
    return None if case.kind == "static" else "does not support this case"


def analytic_supports(case: Case) -> str | None:
    return None if case.friction.mu1 < 0.5 else "no closed-form solution for this case"


SUPPORTS = {"analytic": "analytic_supports"}


def registry(**targets: str) -> dict:
    """The solver registry with fakes, e.g. ``registry(ic="solve_ic", analytic="solve_exact")``:
    the named solvers run this module's functions (analytic with :func:`analytic_supports`,
    the others :func:`supports_all`); solvers not named are made unavailable."""
    from dataclasses import replace

    from reports.registry import solvers

    out = {name: replace(rec, package="no_such_module_xyz")
           for name, rec in solvers.REGISTRY.items()}
    for name, fn in targets.items():
        out[name] = replace(out[name], package=__name__, solve_attr=fn,
                            supports_attr=SUPPORTS.get(name, "supports_all"))
    return out


def use(monkeypatch, **targets: str) -> None:
    """Point the registry at fakes for one test (see :func:`registry`)."""
    from reports.registry import solvers

    monkeypatch.setattr(solvers, "REGISTRY", registry(**targets))


def estimate_tiny(case: Case):
    """A calibrated estimate far below what :func:`solve_slow` takes (deadline tests)."""
    from cases.result import Cost

    return Cost(memory=1e6, seconds=0.01, time_factor=1.0)
