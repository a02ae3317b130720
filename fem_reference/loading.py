"""The load paths of static and sliding-wear runs and the solve steps they share with
fretting (:mod:`fem_reference.fretting`); :func:`fem_reference.solver.load_path` picks
the path of a case.

- static cases: the normal load (or approach) first — in one step for identical
  materials (no normal–tangential coupling), in the increments of
  :func:`cases.steps.normal_fractions` otherwise — then a
  tangential load (Qx, Qy) or shift in 5 increments with the friction history (return
  map); full sliding (``load.sliding``) prescribes the slip direction instead (Eq. 13).
  One output step (``step = 0``) with the final state.
- ``sliding_wear`` (pin-on-disk): constant load; step k slides every contact point by
  ``sliding_wear.step`` along ``load.slide_angle`` and adds the wear of Eq. 23 to each
  body (backward Euler, as step IV of §3.4).  The condensed stiffness is reused for every
  step.  Output steps: ``step = round(s / sliding_wear.step)`` for s = 0, the
  ``output_s`` distances and the total distance (every step if ``output_s`` is empty).

Each path is a generator of :class:`~fem_reference.run.OutputState`: it yields an output
step as soon as it has converged, and goes on when the caller asks for the next one.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from cases.model import Case
from cases.result import OPEN, SLIP, STICK
from cases.steps import normal_fractions, sliding_outputs, sliding_steps

from .contact.augmented import augmented
from .contact.control import Control, Solution
from .contact.laws import Evaluation, evaluate
from .contact.semismooth import semismooth
from .errors import FemError
from .model.shape import slide_direction, wear_compliances
from .run import OutputState, Run, hertz_start

N_TANGENTIAL = 5  # tangential load (or shift) increments


def control(run: Run, P_frac: float = 1.0, Q_frac: float = 0.0) -> Control:
    """The control of a solve at fractions of the case's normal and tangential loads
    (approach and shift likewise); the state's δ and g_t,o where they are unknowns.  A
    held approach or shift is the half-space's: the blocks' δ and g_t,o follow from
    the far-field compliances (:mod:`fem_reference.model.far_field`)."""
    m = run.model
    load = m.case.load
    P = None if load.P is None else load.P * P_frac
    approach = None if load.P is not None else load.approach * P_frac
    Q: tuple = (None, None)
    shift: tuple = (None, None)
    D = run.D.copy()
    if load.tangential_mode == "load" and Q_frac > 0:
        qx, qy = (load.Qx or 0.0) * Q_frac, (load.Qy or 0.0) * Q_frac
        Q = (qx, None) if m.shape == "half" else (qx, qy)
    elif load.tangential_mode == "shift":
        target = np.array([load.shift_x or 0.0, load.shift_y or 0.0]) * Q_frac
        shift = (target[0], None if m.shape == "half" else target[1])
        if run.compliance_t == 0:
            D = target
    delta = approach if approach is not None and run.compliance == 0 else run.delta
    return Control(P=P, delta=delta, D=D, Q=Q, sym=m.sym.factor, approach=approach,
                   compliance=run.compliance, shift=shift, compliance_t=run.compliance_t)


def solve_increment(run: Run, ctrl: Control, cw: float | np.ndarray = 0.0
                    ) -> tuple[Solution, Evaluation]:
    """Solve the contact under ``ctrl`` (wear compliance ``cw``, one value or one per
    node) from the current state, make the solution the run's state and evaluate the
    samples on it.

    Raises :class:`~fem_reference.errors.FemError` when the contact reaches the edge of
    the FE contact zone (1.5 elements from r_c).
    """
    m = run.model
    tol = max(1e-9, 10 * m.case.solver.tol)
    if run.op is not None:
        sol = semismooth(run.op, m.law, run.nodes, ctrl, cw=cw, tol=tol, kept=run.kept)
    else:
        sol = augmented(m.Krel, m.Crel, m.law, run.nodes, ctrl, run.u, cw=cw, tol=tol,
                        lin=run.lin)
    ev = sol.ev
    active = ev.pn > 0
    if active.any():
        rad = np.hypot(run.nodes.xy[active, 0], run.nodes.xy[active, 1]).max()
        if rad > m.surface.r_c - 1.5 * m.h:
            raise FemError(
                f"the contact (radius {rad:.4g} mm) reached the edge of the FE contact zone "
                f"(r_c = {m.surface.r_c:.4g} mm)"
            )
    run.u, run.delta, run.D = sol.u, sol.delta, sol.D.copy()
    return sol, probe_evaluation(run, sol.ev)


def probe_evaluation(run: Run, ev: Evaluation) -> Evaluation:
    """The state at the samples: gaps from the P2 displacement field, tractions and
    states from the nodal solution ``ev`` (linear on the facets' sub-triangles; a sample
    sticks where its stick weight, the interpolated stick indicator, is at least 1/2)."""
    m = run.model
    sample = evaluate(m.law, run.samples, run.u, run.delta, run.D)
    Nsub = run.sampling.Nsub
    pn = Nsub @ ev.pn
    t = Nsub @ ev.t
    stick = (Nsub @ (ev.state == STICK).astype(float)) >= 0.5
    state = np.where(pn > 0.0, np.where(stick, STICK, SLIP), OPEN)
    return Evaluation(gn=sample.gn, pn=pn, t=t, gt=sample.gt, state=state, T=sample.T,
                      Tdelta=sample.Tdelta, TD=sample.TD)


def commit(run: Run, sol: Solution, sample_ev: Evaluation) -> None:
    """Make the tractions and tangential gaps of a converged solve the friction history."""
    for pts, ev in ((run.nodes, sol.ev), (run.samples, sample_ev)):
        pts.t_old = ev.t.copy()
        pts.gt_old = ev.gt.copy()


def add_wear(run: Run, dw_a: np.ndarray, dw_b: np.ndarray) -> None:
    """Add the wear increments of a step, Δw = p_n ‖Δg‖_i per node, to bodies a and b:
    nodal coefficients in the modified basis (the weighted gap,
    :mod:`fem_reference.model.nodal_basis`), and at the samples the wear field they define (the
    field the gap of the samples holds)."""
    for pts, inc_a, inc_b in ((run.nodes, dw_a, dw_b),
                              (run.samples, run.Nmod @ dw_a, run.Nmod @ dw_b)):
        pts.wear_a = pts.wear_a + inc_a
        pts.wear_b = pts.wear_b + inc_b


def static_path(run: Run, progress: bool = False) -> Iterator[OutputState]:
    """Normal, then tangential loading; one output state (step 0) at the end."""
    m = run.model
    case = m.case
    mode = case.load.tangential_mode
    iters = 0
    if m.law_mode != "friction":
        sol, pev = solve_increment(run, control(run))
        iters += sol.iterations
        slip = np.zeros((run.samples.n, 2))
        if m.law_mode == "sliding":
            slip[:] = slide_direction(case)
        yield OutputState(step=0, sol=sol, sample_ev=pev, slip=slip, iterations=iters)
        return
    n_tangential = N_TANGENTIAL if mode in ("load", "shift") else 0
    with progress_bar(progress, len(normal_increments(case)) + n_tangential, case) as bar:
        sol, pev, iters = normal_loading(run, bar)
        gt_ref = pev.gt.copy()
        for i in range(1, n_tangential + 1):
            sol, pev = solve_increment(run, control(run, Q_frac=i / N_TANGENTIAL))
            commit(run, sol, pev)
            iters += sol.iterations
            bar.update()
    slip = pev.gt - gt_ref
    yield OutputState(step=0, sol=sol, sample_ev=pev, slip=slip, iterations=iters)


def normal_increments(case: Case) -> tuple[float, ...]:
    """The load (or approach) fractions of the normal loading's increments: one for
    identical materials (no normal–tangential coupling), those of
    :func:`cases.steps.normal_fractions` otherwise."""
    return (1.0,) if case.identical_materials else normal_fractions(case)


def normal_loading(run: Run, bar=None) -> tuple[Solution, Evaluation, int]:
    """The normal load (or approach) in :func:`normal_increments` increments with the
    friction history committed; the last solution, its sample evaluation and the Newton
    iterations of all increments."""
    fractions = normal_increments(run.model.case)
    if len(fractions) > 1:  # start the first increment from its own Hertz solution
        run.u, run.delta = hertz_start(run.model, run.nodes, fractions[0])
    iters = 0
    for f in fractions:
        sol, pev = solve_increment(run, control(run, P_frac=f))
        commit(run, sol, pev)
        iters += sol.iterations
        if bar is not None:
            bar.update()
    return sol, pev, iters


def sliding_wear_path(run: Run, progress: bool = False) -> Iterator[OutputState]:
    """Sliding steps at constant load with wear; an output state per output step."""
    case = run.model.case
    sw = case.sliding_wear
    n = sliding_steps(sw)
    dg = sw.step * slide_direction(case)
    ca, cb = wear_compliances(case, dg)
    wanted = set(sliding_outputs(sw))
    with progress_bar(progress, n + 1, case) as bar:
        for k in range(n + 1):
            cw = 0.0 if k == 0 else ca + cb
            sol, pev = solve_increment(run, control(run), cw=cw)
            if k > 0:
                add_wear(run, ca * sol.ev.pn, cb * sol.ev.pn)
            commit(run, sol, pev)
            bar.update()
            if k in wanted:
                slip = np.zeros((run.samples.n, 2))
                if k > 0:
                    slip[:] = dg
                yield OutputState(step=k, sol=sol, sample_ev=pev, slip=slip,
                                  iterations=sol.iterations, s=k * sw.step)


class _NoBar:
    def __enter__(self) -> _NoBar:
        return self

    def __exit__(self, *exc) -> None:
        pass

    def update(self, n: int = 1) -> None:
        pass


def progress_bar(progress: bool, total: int, case: Case):
    """A tqdm progress bar of ``total`` steps (a context manager), or a silent stand-in."""
    if not progress:
        return _NoBar()
    from tqdm import tqdm

    return tqdm(total=total, desc=f"fem {case.name} {case.param}".strip(), unit="step",
                leave=False)
