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
multiplied by J (results must be shown converged in J).  Every simulated cycle is
watched for regime events (:class:`cases.result.RegimeEvents`, in ``RunResult.events``):
gross -> partial slip and back (stick cells at the tangential extremes ±A), and under
a held approach the load lost (P < :data:`cases.result.LOAD_LOST_FRACTION` P0) and the
contact worn through (no contact cell), each with the real cycle at which it was seen,
to within J.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from tqdm.auto import tqdm

from cases.model import Case, Fretting
from cases.result import (
    CYCLE_COLUMNS,
    LOOP_COLUMNS,
    RegimeEvents,
    RunResult,
    StepResult,
    cycle_regime,
    gross_slip,
)
from cases.steps import fretting_outputs, sliding_outputs, sliding_steps

from .contact import STICK, ContactNotConverged, ContactSolver, ContactState, StepSolution
from .friction import wear_norm
from .output import SOLVER_NAME, step_result
from .problem import contact_solver, profile, slide_direction, stress_evaluator
from .wear_spread import spread

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


def _committed(case: Case, dw: np.ndarray) -> np.ndarray:
    """The wear increment ``dw`` as committed: spread over ``solver.wear_spread``
    (:mod:`halfspace.wear_spread`, the resolution probe), else as solved."""
    return spread(dw, case.solver.wear_spread, case.grid.dx, case.grid.dy)


# ---------------------------------------------------------------------- pin-on-disk


def sliding_wear(case: Case, progress: bool = False,
                 on_output: OutputCallback | None = None) -> RunResult:
    """Pin-on-disk (cases 4, 5): constant load, every step slides ``step`` along
    ``load.slide_angle``; only bodies with wear coefficients wear."""
    t0 = time.perf_counter()
    sw = case.sliding_wear
    n_steps = sliding_steps(sw)
    outputs = set(sliding_outputs(sw))
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
    for k in tqdm(range(n_steps + 1), disable=not progress,
                  desc=f"ic {case.name} {case.param}".strip(), unit="step", leave=False):
        h = h0 + w_a + w_b
        if k == 0:
            # s = 0: the unworn pin already sliding (friction tractions on), no wear yet
            sol = solver.solve(h, P=case.load.P, shift=ds)
        else:
            shift = np.array([state.shift_x, state.shift_y]) + ds
            sol = solver.solve(h, P=case.load.P, shift=shift, prev=state,
                               wear_rate=k_a + k_b)
            w_a = w_a + _committed(case, k_a * sol.state.p_n)
            w_b = w_b + _committed(case, k_b * sol.state.p_n)
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


def cycle_path(amplitude: float, steps_per_cycle: int) -> np.ndarray:
    """Imposed displacements of one cycle +A -> -A -> +A (excluding the start +A):
    :meth:`cases.model.Fretting.cycle_path`."""
    return Fretting(amplitude=amplitude, steps_per_cycle=steps_per_cycle).cycle_path()


def fretting(case: Case, progress: bool = False,
             on_output: OutputCallback | None = None) -> RunResult:
    """Fretting (case 6): normal approach (or load) held, tangential displacement along x
    0 -> +A, then cycles +A -> -A -> +A; both bodies wear; cycle jump factor J.  The
    regime of every simulated cycle is watched (:class:`cases.result.RegimeEvents`)."""
    t0 = time.perf_counter()
    fr = case.fretting
    J = fr.jump
    n_sim = fr.simulated_cycles
    out_sim = fretting_outputs(fr)
    solver, stresses = contact_solver(case), stress_evaluator(case)
    h0 = profile(case)
    w_a, w_b = np.zeros(h0.shape), np.zeros(h0.shape)
    normal = {"P": case.load.P} if case.load.load_controlled else {
        "approach": case.load.approach}
    d = slide_direction(case.load.slide_angle)
    free = np.array([-d[1], d[0]]) if fr.transverse == "free" else None
    first = _initial_loading(case, solver, h0, normal, d, free)
    watch = regime_events(case, first)
    state = first.state
    path = cycle_path(fr.amplitude, fr.steps_per_cycle)
    loops, cycles = [], []
    steps: list[StepResult] = []
    last_cycle: list[ContactState | None] = [None] * len(path)  # warm starts
    for n in tqdm(range(1, n_sim + 1), disable=not progress,
                  desc=f"ic {case.name} {case.param}".strip(), unit="cycle", leave=False):
        seen = CycleObservation(case.grid.dx * case.grid.dy)
        energy, Q_prev, u_prev = 0.0, state_Q(state, case), fr.amplitude
        for k, u in enumerate(path):
            shift = _shift(u, d, free, last_cycle[k] or state)
            sol, dw_a, dw_b = _fretting_step(case, solver, h0 + w_a + w_b, normal, shift,
                                             state, J, last_cycle[k], free)
            w_a, w_b = w_a + _committed(case, dw_a), w_b + _committed(case, dw_b)
            _check_wear(w_a, w_b)
            state = last_cycle[k] = sol.state
            Q = np.array([sol.Qx, sol.Qy])
            energy += 0.5 * float((Q + Q_prev) @ d) * (u - u_prev)
            Q_prev, u_prev = Q, u
            seen.see(sol, extreme=abs(abs(u) - fr.amplitude) <= 1e-12 * fr.amplitude)
            loops.append((min(n * J, fr.cycles), u, sol.Qx, sol.Qy))
        seen.observed_by(watch, n)
        cycles.append(seen.row(min(n * J, fr.cycles), abs(energy), (w_a + w_b).max()))
        if n in out_sim:
            res = step_result(case, sol, stresses, step=n, wear_a=w_a, wear_b=w_b,
                              wall_s=time.perf_counter() - t0, cycle=out_sim[n])
            steps.append(res)
            if on_output is not None:
                on_output(res)
    return RunResult(case=case.name, solver=SOLVER_NAME, param=case.param, steps=steps,
                     meta={"method": case.solver.method, "jump": J},
                     tables=_fretting_tables(loops, cycles), events=watch.events)


def _initial_loading(case: Case, solver: ContactSolver, h0: np.ndarray, normal: dict,
                     d: np.ndarray, free: np.ndarray | None) -> StepSolution:
    """The normal load (or approach), then 0 -> +A in a quarter cycle (no wear counted);
    the step solution at +A."""
    fr = case.fretting
    sol = solver.solve(h0, **normal)
    for u in fr.loading_path():
        sol = solver.solve(h0, **normal, shift=_shift(u, d, free, sol.state), free=free,
                           prev=sol.state)
    return sol


def _shift(u: float, d: np.ndarray, free: np.ndarray | None,
           start: ContactState) -> np.ndarray:
    """The rigid shift u d imposed along ``d``; with the transverse motion ``free``, plus
    ``start``'s shift along ``free`` (where the search for it starts)."""
    if free is None:
        return u * d
    return u * d + float(free @ (start.shift_x, start.shift_y)) * free


def _fretting_tables(loops: list[tuple], cycles: list[tuple]) -> dict[str, dict]:
    """The ``loops`` table (:data:`cases.result.LOOP_COLUMNS`, a row per step) and the
    ``cycles`` table (:data:`cases.result.CYCLE_COLUMNS`, a row per simulated cycle;
    ``gross_slip`` by :func:`cases.result.gross_slip`)."""
    loops_a, cyc_a = np.array(loops), np.array(cycles)
    return {"loops": {c: loops_a[:, i] for i, c in enumerate(LOOP_COLUMNS)},
            "cycles": {c: cyc_a[:, i] for i, c in enumerate(CYCLE_COLUMNS)}}


# ---------------------------------------------------------------------- regime events


@dataclass
class CycleObservation:
    """What one simulated cycle showed: stick and contact cells at its tangential
    extremes (-A mid-cycle, +A at its end, in that order), the least load P [N], stick
    and contact cell counts over its steps; ``dA`` the cell area [mm²]."""

    dA: float
    stick: list[int] = field(default_factory=list)
    contact: list[int] = field(default_factory=list)
    P_min: float = math.inf
    min_stick: int = sys.maxsize
    contact_min: int = sys.maxsize

    def see(self, sol: StepSolution, extreme: bool) -> None:
        """Take in one step of the cycle (``extreme``: the imposed shift is ±A)."""
        stick = int(np.count_nonzero(sol.status == STICK))
        contact = int(np.count_nonzero(sol.state.p_n > 0))
        self.P_min = min(self.P_min, sol.P)
        self.min_stick = min(self.min_stick, stick)
        self.contact_min = min(self.contact_min, contact)
        if extreme:
            self.stick.append(stick)
            self.contact.append(contact)

    def regime(self) -> str | None:
        """The cycle's regime (:func:`cases.result.cycle_regime` of its cells)."""
        return cycle_regime(self.stick, self.contact)

    def extremes(self) -> tuple[float, float]:
        """Stick areas [mm²] at -A and +A."""
        return self.stick[0] * self.dA, self.stick[-1] * self.dA

    def row(self, cycle: float, energy: float, w_max: float) -> tuple[float, ...]:
        """The cycle's row of the ``cycles`` table (:data:`cases.result.CYCLE_COLUMNS`)."""
        return (cycle, energy, self.min_stick * self.dA, gross_slip(self.regime()), w_max,
                *self.extremes(), self.P_min, self.contact_min * self.dA)

    def observed_by(self, events: RegimeEvents, n: int) -> None:
        """Hand simulated cycle n to the run's :class:`cases.result.RegimeEvents`."""
        stick = min(self.extremes()) if self.stick else math.nan
        events.observe(n, self.regime(), stick, self.P_min, self.contact_min)


def regime_events(case: Case, first: StepSolution) -> RegimeEvents:
    """The regime events of a fretting run (:class:`cases.result.RegimeEvents`) from its
    initial loading ``first``."""
    fr, dA = case.fretting, case.grid.dx * case.grid.dy
    stick = int(np.count_nonzero(first.status == STICK))
    contact = int(np.count_nonzero(first.state.p_n > 0))
    return RegimeEvents(fr.jump, fr.cycles, first.P, cycle_regime([stick], [contact]),
                        stick * dA, held_approach=not case.load.load_controlled,
                        nothing="no contact cell")


def state_Q(state: ContactState, case: Case) -> np.ndarray:
    dA = case.grid.dx * case.grid.dy
    return np.array([state.p_x.sum(), state.p_y.sum()]) * dA


def _fretting_step(case, solver, h, normal, shift, prev, J, guess=None, free=None):
    """One fretting step, wear semi-implicit: a predictor solve gives the slip; the
    corrector solves the step with the wear J p_n ||dg_t||_i of that slip in the gap
    (implicit in p_n, as step IV, explicit in the slip).  The wear added afterwards is
    exactly the one the corrector's gap contains.  A fixed point in the slip as well does
    not contract for large cycle jumps in partial slip (measured: no convergence in 30
    passes at J = 1000, beta = 90); the error of the lagged slip is O(J) and is what the
    cycle-jump convergence test measures.  The iterations start from ``guess`` (the same
    point of the previous cycle) and the corrector from the predictor; the slip history
    is ``prev``'s either way.  ``free``: the transverse shift is found (Qy = 0 across
    the imposed motion), the corrector's search starting from the predictor's."""
    sol = solver.solve(h, **normal, shift=shift, free=free, prev=prev, guess=guess)
    if case.a.i1 == case.a.i2 == case.b.i1 == case.b.i2 == 0:
        return sol, np.zeros_like(h), np.zeros_like(h)
    sn_a, sn_b = slip_norms(case, sol.slip_x, sol.slip_y)
    if free is not None:  # the imposed part is the same; the free part starts found
        shift = np.array([sol.state.shift_x, sol.state.shift_y])
    sol = solver.solve(h, **normal, shift=shift, free=free, prev=prev,
                       wear_rate=J * (sn_a + sn_b), guess=sol.state)
    return sol, J * sn_a * sol.state.p_n, J * sn_b * sol.state.p_n
