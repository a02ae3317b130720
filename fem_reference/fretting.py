"""The fretting load path (docs/cases.md, case 6) on the condensed FE surface operator.

The normal load (or approach) is applied and held; the tangential rigid displacement
g_t,o of body a follows the case's imposed path along ``load.slide_angle``: the initial
loading 0 → +A (:meth:`cases.model.Fretting.loading_path`, no wear counted), then cycles
+A → −A → +A (:meth:`cases.model.Fretting.cycle_path`).  Each step solves the friction
law with its history (the return map of :mod:`fem_reference.contact.augmented`, augmented so that
stick is exact) and wears both bodies by the orthotropic Archard law (Eqs. 21–23):

    Δw_k = J p_n ‖Δg_t‖_i,k      at every contact node,

J the cycle jump (each simulated cycle stands for J cycles).  The wear is
semi-implicit: a predictor solve without wear gives the slip Δg_t of every node; the
corrector solves the step again with the wear compliance c_w = J (‖Δg_t‖_i,a +
‖Δg_t‖_i,b) per node in the normal law (implicit in p_n, as step IV of §3.4), and the
wear added is the one its gap holds.  The condensed operator stays valid throughout:
wear changes only the gap.

Tables of the run (the columns the half-space solver writes, :mod:`reports.compare.cycles`):
``loops`` (cycle, displacement, Qx, Qy per step) and ``cycles`` (per simulated cycle:
the real cycle count at its end, the energy ∮ Q·d dδ by the trapezoidal rule on the
steps, the least stick area, gross slip 1 / partial 0 / NaN without contact at an
extreme ±A, w_max, the stick areas at −A and +A, the least P and contact area).
Output steps: ``step = n`` for the simulated cycle n that ends at an output cycle
(``round(c / J)``), and the last.  Regime events (:class:`cases.result.RegimeEvents`,
the rules every solver shares): gross ↔ partial slip, and under a held approach the load
lost and the contact worn through.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import replace

import numpy as np

from cases.result import (
    CYCLE_COLUMNS,
    LOOP_COLUMNS,
    STICK,
    RegimeEvents,
    cycle_regime,
    gross_slip,
)
from cases.steps import fretting_outputs

from .contact.control import Control, Solution
from .contact.laws import Evaluation
from .loading import (
    add_wear,
    commit,
    normal_increments,
    normal_loading,
    progress_bar,
    solve_increment,
)
from .model.shape import slide_direction, wear_norms
from .run import OutputState, Run


def fretting_control(run: Run, shift: float) -> Control:
    """The normal load (or approach) held and the rigid tangential displacement
    ``shift`` along ``load.slide_angle`` prescribed (a held approach is the
    half-space's, :mod:`fem_reference.model.far_field`; δ starts from the current one)."""
    m = run.model
    load = m.case.load
    target = shift * slide_direction(m.case)
    free = (target[0], None if m.shape == "half" else target[1])
    return Control(P=load.P, delta=run.delta, D=run.D.copy(), sym=m.sym.factor,
                   approach=load.approach, compliance=run.compliance, shift=free,
                   compliance_t=run.compliance_t)


def fretting_step(run: Run, shift: float, J: float) -> tuple[Solution, Evaluation, np.ndarray]:
    """One step of a cycle (module doc): predictor, corrector with the wear of the
    predicted slip, wear added, state committed.  Returns the solution, the sample
    evaluation and the slip of the step at the samples."""
    m = run.model
    case = m.case
    ctrl = fretting_control(run, shift)
    # start from full stick: the relative surface displacement absorbs the change of
    # the rigid shift, and the blocks' D takes it whole (the Newton iteration then
    # finds D + c_t Q = shift)
    comp = m.surface.dof_comp[m.cidx]
    now = run.D + run.compliance_t * tangential_load(run, run.nodes.t_old)
    dD = np.array([v if v is not None else now[c] for c, v in enumerate(ctrl.shift)]) - now
    run.u = run.u - np.where(comp == 0, dD[0], np.where(comp == 1, dD[1], 0.0))
    run.D = run.D + dD
    ctrl = replace(ctrl, D=run.D.copy())
    sol, pev = solve_increment(run, ctrl)
    if J > 0 and max(case.a.i1, case.a.i2, case.b.i1, case.b.i2) > 0:
        s_a, s_b = wear_norms(case, sol.ev.gt - run.nodes.gt_old)
        sol, pev = solve_increment(run, replace(ctrl, delta=run.delta, D=run.D.copy()),
                                   cw=J * (s_a + s_b))
        add_wear(run, J * s_a * sol.ev.pn, J * s_b * sol.ev.pn)
    slip = pev.gt - run.samples.gt_old
    commit(run, sol, pev)
    return sol, pev, slip


def tangential_load(run: Run, t: np.ndarray) -> np.ndarray:
    """(Qx, Qy) of the nodal tractions ``t`` (n, 2), symmetry included (the half model
    carries no Qy)."""
    m = run.model
    Q = m.sym.factor * (run.nodes.w @ t)
    if m.shape == "half":
        Q[1] = 0.0
    return Q


def resultants(run: Run, ev: Evaluation) -> tuple[float, float, float, float, float]:
    """(P, Qx, Qy, contact area, stick area) of the nodal solution ``ev``, symmetry
    included."""
    w, f = run.nodes.w, run.model.sym.factor
    Q = tangential_load(run, ev.t)
    return (f * float(w @ ev.pn), float(Q[0]), float(Q[1]),
            f * float(w[ev.pn > 0].sum()), f * float(w[ev.state == STICK].sum()))


def fretting_path(run: Run, progress: bool = False) -> Iterator[OutputState]:
    """The initial loading, then the simulated cycles; an output state per output cycle
    (``tables`` of the last state hold the ``loops`` and ``cycles`` of the run)."""
    case = run.model.case
    fr = case.fretting
    J = fr.jump
    n_sim = fr.simulated_cycles
    out_sim = fretting_outputs(fr)
    d = slide_direction(case)
    loading, path = fr.loading_path(), fr.cycle_path()
    loops: list[tuple] = []
    cycles: list[tuple] = []
    with progress_bar(progress, len(normal_increments(case)) + loading.size + n_sim * path.size,
              case) as bar:
        sol, pev, iters = normal_loading(run, bar)
        for u in loading:
            sol, pev, _ = fretting_step(run, float(u), 0.0)
            bar.update()
        P0, _, _, contact0, stick0 = resultants(run, sol.ev)
        watch = RegimeEvents(fr.jump, fr.cycles, P0, cycle_regime([stick0], [contact0]),
                             stick0, held_approach=case.load.P is None,
                             nothing="no node in contact")
        Q_prev = tangential_load(run, sol.ev.t)
        for n in range(1, n_sim + 1):
            energy, u_prev = 0.0, fr.amplitude
            stick_ext, contact_ext = [], []
            P_min = min_stick = contact_min = math.inf
            for u in path:
                sol, pev, slip = fretting_step(run, float(u), J)
                iters += sol.iterations
                P, Qx, Qy, contact, stick = resultants(run, sol.ev)
                Q = np.array([Qx, Qy])
                energy += 0.5 * float((Q + Q_prev) @ d) * (u - u_prev)
                Q_prev, u_prev = Q, u
                P_min, min_stick = min(P_min, P), min(min_stick, stick)
                contact_min = min(contact_min, contact)
                if abs(abs(u) - fr.amplitude) <= 1e-12 * fr.amplitude:
                    stick_ext.append(stick)
                    contact_ext.append(contact)
                loops.append((min(n * J, fr.cycles), u, Qx, Qy))
                bar.update()
            w_max = float((run.nodes.wear_a + run.nodes.wear_b).max())
            regime = cycle_regime(stick_ext, contact_ext)
            cycles.append((min(n * J, fr.cycles), abs(energy), min_stick, gross_slip(regime),
                           w_max, stick_ext[0], stick_ext[-1], P_min, contact_min))
            watch.observe(n, regime, min(stick_ext), P_min, contact_min)
            if n in out_sim:
                yield OutputState(step=n, sol=sol, sample_ev=pev, slip=slip, iterations=iters,
                                  cycle=float(out_sim[n]),
                                  tables=_tables(loops, cycles), events=list(watch.events))
                iters = 0


def _tables(loops: list[tuple], cycles: list[tuple]) -> dict[str, dict[str, np.ndarray]]:
    la, ca = np.array(loops), np.array(cycles)
    return {"loops": {c: la[:, i] for i, c in enumerate(LOOP_COLUMNS)},
            "cycles": {c: ca[:, i] for i, c in enumerate(CYCLE_COLUMNS)}}
