"""Wear evolution (section 2.4, 3.2, 3.4 steps I-VI): pin-on-disk and fretting.

Orthotropic Archard law per body k (Eq. 21-23, erratum 5)::

    w_k^(k) = w_k^(k-1) + p_n^(k) || g_t^(k) - g_t^(k-1) ||_{i,k}

and the normal gap sees the sum of both bodies' wear (Eq. 29).  The wear of a step is
implicit, as in step (IV) where it is updated inside the contact iteration: with the
slip norm s_k = ||dg_t||_{i,k} of the step known, the gap gains (s_a + s_b) p_n and the
normal problem is solved with the operator A_zz + diag(s_a + s_b) (exactly step IV's
fixed point).  In gross sliding (pin-on-disk) the slip is the imposed rigid slip, so one
solve is exact and the worn volume equals sum_k i_w P ds (Archard) to round-off.  In
fretting the slip is unknown: it is taken from a predictor solve of the step (see
:func:`_fretting_step`).

Fretting uses a cycle jump factor J: each simulated cycle stands for J cycles, its wear
multiplied by J (results must be shown converged in J).
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np
from tqdm.auto import tqdm

from cases.model import Case
from cases.result import RunResult, StepResult

from .contact import STICK, ContactNotConverged, ContactState
from .friction import wear_norm
from .output import SOLVER_NAME, step_result
from .problem import contact_solver, profile, slide_direction, stress_evaluator

OutputCallback = Callable[[StepResult], None]


def slip_norms(case: Case, slip_x, slip_y) -> tuple[np.ndarray, np.ndarray]:
    """||dg_t||_i for body a and body b (Eq. 21), in the tribological axes of friction.beta."""
    beta = case.friction.beta
    return (wear_norm(slip_x, slip_y, case.a.i1, case.a.i2, beta),
            wear_norm(slip_x, slip_y, case.b.i1, case.b.i2, beta))


def _check_wear(w_a: np.ndarray, w_b: np.ndarray) -> None:
    if not (np.all(np.isfinite(w_a)) and np.all(np.isfinite(w_b))):
        raise ContactNotConverged("wear depth became NaN/Inf")
    if w_a.min() < 0 or w_b.min() < 0:
        raise ContactNotConverged("negative wear depth")


def solve_evolution(case: Case, progress: bool = False,
                    on_output: OutputCallback | None = None) -> RunResult:
    """Run a ``sliding_wear`` or ``fretting`` case; ``on_output`` receives each output
    step as soon as it is computed (so a runner can write it at once)."""
    if case.kind == "sliding_wear":
        return sliding_wear(case, progress, on_output)
    if case.kind == "fretting":
        return fretting(case, progress, on_output)
    raise ValueError(f"case kind {case.kind!r} has no evolution")


def _output_indices(values, unit: float, last: int) -> set[int]:
    idx = {int(round(v / unit)) for v in values}
    bad = [v for v in values if not 0 <= round(v / unit) <= last]
    if bad:
        raise ValueError(f"output points {bad} lie outside the run (0 .. {last * unit:g})")
    return idx | {0, last}


# ---------------------------------------------------------------------- pin-on-disk


def sliding_wear(case: Case, progress: bool = False,
                 on_output: OutputCallback | None = None) -> RunResult:
    """Pin-on-disk (cases 4, 5): constant load, every step slides ``step`` along
    ``load.slide_angle``; only bodies with wear coefficients wear."""
    t0 = time.perf_counter()
    sw = case.sliding_wear
    n_steps = int(round(sw.distance / sw.step))
    outputs = _output_indices(sw.output_s, sw.step, n_steps)
    solver, stresses = contact_solver(case), stress_evaluator(case)
    h0 = profile(case)
    shape = h0.shape
    w_a, w_b = np.zeros(shape), np.zeros(shape)
    ds = sw.step * slide_direction(case.load.slide_angle)
    k_a, k_b = (np.full(shape, float(k)) for k in slip_norms(case, *ds))
    steps: list[StepResult] = []
    hist = {k: np.empty(n_steps + 1) for k in
            ("s", "P", "Qx", "Qy", "p_max", "w_max", "wear_volume", "contact_area", "a_x")}
    state: ContactState | None = None
    dA = case.grid.dx * case.grid.dy
    for k in tqdm(range(n_steps + 1), disable=not progress, desc=f"{case.name} {case.param}",
                  unit="step"):
        h = h0 + w_a + w_b
        if k == 0:
            # s = 0: the unworn pin already sliding (friction tractions on), no wear yet
            sol = solver.solve(h, P=case.load.P, shift=ds)
        else:
            shift = np.array([state.shift_x, state.shift_y]) + ds
            sol = solver.solve(h, P=case.load.P, shift=shift, prev=state,
                               wear_rate=k_a + k_b)
            w_a = w_a + k_a * sol.state.p_n
            w_b = w_b + k_b * sol.state.p_n
            _check_wear(w_a, w_b)
        state = sol.state
        w = w_a + w_b
        for key, val in (("s", k * sw.step), ("P", sol.P), ("Qx", sol.Qx), ("Qy", sol.Qy),
                         ("p_max", state.p_n.max()), ("w_max", w.max()),
                         ("wear_volume", w.sum() * dA),
                         ("contact_area", np.count_nonzero(state.p_n > 0) * dA)):
            hist[key][k] = val
        hist["a_x"][k] = np.nan
        if k in outputs:
            res = step_result(case, sol, stresses, step=k, wear_a=w_a, wear_b=w_b,
                              wall_s=time.perf_counter() - t0, s=k * sw.step)
            hist["a_x"][k] = res.scalars["a_x"]
            steps.append(res)
            if on_output is not None:
                on_output(res)
    return RunResult(case=case.name, solver=SOLVER_NAME, param=case.param, steps=steps,
                     meta={"method": case.solver.method}, tables={"history": hist})


# ---------------------------------------------------------------------- fretting


def fretting_path(amplitude: float, steps_per_cycle: int) -> np.ndarray:
    """Imposed displacements of one cycle +A -> -A -> +A (excluding the start +A)."""
    half = steps_per_cycle // 2
    down = amplitude * (1 - 2 * np.arange(1, half + 1) / half)  # +A -> -A
    return np.concatenate([down, down[::-1][1:], [amplitude]])  # -A -> +A on the same points


def fretting(case: Case, progress: bool = False,
             on_output: OutputCallback | None = None) -> RunResult:
    """Fretting (case 6): normal approach (or load) held, tangential displacement along x
    0 -> +A, then cycles +A -> -A -> +A; both bodies wear; cycle jump factor J."""
    t0 = time.perf_counter()
    fr = case.fretting
    J = fr.jump
    n_sim = int(np.ceil(fr.cycles / J))
    out_sim = {int(round(c / J)): c for c in fr.output_cycles if c <= fr.cycles}
    out_sim.setdefault(n_sim, fr.cycles)
    solver, stresses = contact_solver(case), stress_evaluator(case)
    h0 = profile(case)
    shape = h0.shape
    w_a, w_b = np.zeros(shape), np.zeros(shape)
    normal = {"P": case.load.P} if case.load.load_controlled else {
        "approach": case.load.approach}
    d = slide_direction(case.load.slide_angle)
    # initial loading: normal, then 0 -> +A in a quarter cycle (no wear counted)
    state = solver.solve(h0, **normal).state
    quarter = fr.steps_per_cycle // 4 or 1
    for u in fr.amplitude * np.arange(1, quarter + 1) / quarter:
        state = solver.solve(h0, **normal, shift=u * d, prev=state).state
    path = fretting_path(fr.amplitude, fr.steps_per_cycle)
    loops, cycles = [], []
    steps: list[StepResult] = []
    last_cycle: list[ContactState | None] = [None] * len(path)  # warm starts
    for n in tqdm(range(1, n_sim + 1), disable=not progress,
                  desc=f"{case.name} {case.param}", unit="cycle"):
        energy, min_stick, Q_prev, u_prev = 0.0, np.inf, state_Q(state, case), fr.amplitude
        for k, u in enumerate(path):
            sol, dw_a, dw_b = _fretting_step(case, solver, h0 + w_a + w_b, normal, u * d,
                                             state, J, last_cycle[k])
            w_a, w_b = w_a + dw_a, w_b + dw_b
            _check_wear(w_a, w_b)
            state = last_cycle[k] = sol.state
            Q = np.array([sol.Qx, sol.Qy])
            energy += 0.5 * float((Q + Q_prev) @ d) * (u - u_prev)
            Q_prev, u_prev = Q, u
            min_stick = min(min_stick, float(np.count_nonzero(sol.status == STICK)))
            loops.append((n * J, u, sol.Qx, sol.Qy))
        cycles.append((n * J, abs(energy), min_stick * case.grid.dx * case.grid.dy,
                       1.0 if min_stick == 0 else 0.0, (w_a + w_b).max()))
        if n in out_sim:
            res = step_result(case, sol, stresses, step=n, wear_a=w_a, wear_b=w_b,
                              wall_s=time.perf_counter() - t0, cycle=out_sim[n])
            steps.append(res)
            if on_output is not None:
                on_output(res)
    loops_a, cyc_a = np.array(loops), np.array(cycles)
    tables = {
        "loops": {"cycle": loops_a[:, 0], "displacement": loops_a[:, 1],
                  "Qx": loops_a[:, 2], "Qy": loops_a[:, 3]},
        "cycles": {"cycle": cyc_a[:, 0], "energy": cyc_a[:, 1], "min_stick_area": cyc_a[:, 2],
                   "gross_slip": cyc_a[:, 3], "w_max": cyc_a[:, 4]},
    }
    return RunResult(case=case.name, solver=SOLVER_NAME, param=case.param, steps=steps,
                     meta={"method": case.solver.method, "jump": J}, tables=tables)


def state_Q(state: ContactState, case: Case) -> np.ndarray:
    dA = case.grid.dx * case.grid.dy
    return np.array([state.p_x.sum(), state.p_y.sum()]) * dA


def _fretting_step(case, solver, h, normal, shift, prev, J, guess=None):
    """One fretting step, wear semi-implicit: a predictor solve gives the slip; the
    corrector solves the step with the wear J p_n ||dg_t||_i of that slip in the gap
    (implicit in p_n, as step IV, explicit in the slip).  The wear added afterwards is
    exactly the one the corrector's gap contains.  A fixed point in the slip as well does
    not contract for large cycle jumps in partial slip (measured: no convergence in 30
    passes at J = 1000, beta = 90); the error of the lagged slip is O(J) and is what the
    cycle-jump convergence test measures.  The iterations start from ``guess`` (the same
    point of the previous cycle) and the corrector from the predictor; the slip history
    is ``prev``'s either way."""
    sol = solver.solve(h, **normal, shift=shift, prev=prev, guess=guess)
    if case.a.i1 == case.a.i2 == case.b.i1 == case.b.i2 == 0:
        return sol, np.zeros_like(h), np.zeros_like(h)
    sn_a, sn_b = slip_norms(case, sol.slip_x, sol.slip_y)
    sol = solver.solve(h, **normal, shift=shift, prev=prev, wear_rate=J * (sn_a + sn_b),
                       guess=sol.state)
    return sol, J * sn_a * sol.state.p_n, J * sn_b * sol.state.p_n
