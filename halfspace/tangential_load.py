"""Tangential load control, step (a.1) of section 3.4: the rigid shift g_t,o whose
tractions carry a given resultant Q (Eq. 37), or, under mixed control, the shift along
one direction whose resultant along it is given while the shift across it is imposed
(the fretting path with the transverse motion free: Qy = 0 at an imposed shift along x).

The resultant is a monotone function of the shift; it is found by a quasi-Newton
(Broyden) iteration on F(g_t,o) = sum(p_t) dA - Q, to |F| <= 10 tol scale (scale: |Q|,
or a small fraction of mu P when Q nearly vanishes).  Each evaluation of F is a
tangential solve (Eq. 16), whose residual is relative to ||p_n||: an error r in it moves
the resultant by about r P (the traction error summed over the contact, P = sum(p_n) dA),
not by r |Q|, and |Q| may be a small fraction of P (small mu, or the first increments of a
load path).  Every solve tolerance below is therefore the wanted accuracy of F divided by
P.  Far from the answer the solves need no more accuracy than F has (inexact Newton):
they stop at a residual of INNER_TOL_FACTOR x |F| / P, at most INNER_TOL_MAX.  Once the
mismatch is met, or an inexact step fails to reduce it, every later solve is exact, and
exact means FINAL_TOL_FACTOR x tol x min(1, scale / P): the tractions meet the case's
own tolerance, and the resultant's error (about that residual x P) is a tenth of its
tolerance 10 tol scale.  A tighter exact solve buys nothing the test of |F| can see and
costs most of the iterations: the last decades of a tangential solve converge slowest.
An inexact solve's error in F is about NOISE_FRACTION x its tolerance x P (measured:
``benchmarks/README.md``, "Partial-slip load control"); a kept step whose |F| falls
below that is not resolved, and a Newton step from it would follow the noise, so F is
solved exactly where it stands before the next step.

A step is kept only if it reduces |F| by the fraction SUFFICIENT_DECREASE at least (an
inexact solve started from the previous tractions may meet its tolerance at once and
return F unchanged; a secant update from such a step would flatten J along the step).
A step that fails, solved exactly, is undone.  If its solve returned its start unchanged
(the start already met the tolerance at the new shift: F is at the noise level of the
exact solves and cannot resolve the step), the exact tolerance is tightened tenfold, down
to TOL_FLOOR (round-off of the residual), and F re-solved at the kept shift.  At TOL_FLOOR
a solve that returns its start, the same tractions and so the same F (to ROUNDOFF P) at
both shifts, shows the mismatch at what floating point resolves (the residual is insensitive to a
resultant error far above round-off where the augmentation is soft against the
stiffness): it is met if at most RESOLVED_FRACTION P.  A solve whose F changes, or a
mismatch beyond that, is never taken as met.  Otherwise J
is refreshed by finite differences at the last kept shift (the secant can be nearly
singular under strong orthotropy), and if J was fresh already the step length is halved
(a full step can overshoot into gross slip, where F is flat and no Jacobian points back).
The mismatch is always measured on the tractions returned, so the loop either meets the
tolerance or raises ContactNotConverged after MAX_NEWTON steps.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .normal import ContactNotConverged
from .tangential import TangentialSolution

INNER_TOL_FACTOR = 5e-3  # chosen on a sweep of ten problems: benchmarks/README.md
#: a mismatch the exact solves cannot resolve (module doc) is met if at most this
#: fraction of P: far below any tolerance of the comparisons
RESOLVED_FRACTION = 1e-8
#: the same F to round-off: a change of at most this fraction of P
ROUNDOFF = 1e-14
INNER_TOL_MAX = 1e-4
FINAL_TOL_FACTOR = 1.0
TOL_FLOOR = 1e-15
NOISE_FRACTION = 0.1  # an inexact solve's error in F, in units of its tolerance x P
TIGHTEN = 0.1
MAX_NEWTON = 100
SUFFICIENT_DECREASE = 1e-4

Solve = Callable[[np.ndarray, tuple[np.ndarray, np.ndarray] | None, float], TangentialSolution]


def shift_for_resultant(solve: Solve, Q: np.ndarray, zeta: np.ndarray,
                        p0: tuple[np.ndarray, np.ndarray] | None, *, J: np.ndarray,
                        max_step: float, scale: float, P: float, dA: float,
                        tol: float, basis: np.ndarray | None = None,
                        ) -> tuple[TangentialSolution, np.ndarray, int, np.ndarray]:
    """(tractions, shift, tangential iterations, the last secant of d(B^T Q)/ds) with
    ``|B^T sum(p_t) dA - Q| <= 10 tol scale``.

    ``basis`` B (2 x k, orthonormal columns; default the identity) holds the directions
    along which the shift is unknown: the shift is ``zeta + B s`` with ``zeta``'s part
    along B replaced by s, the rest of ``zeta`` held (mixed control: the motion along
    one direction imposed, the resultant along the other given).  ``Q`` is then the
    resultant's k components along B.  ``solve(shift, start, tol)`` gives the tractions
    of a shift from the tractions ``start``; ``J`` (k x k) is the initial d(B^T Q)/ds,
    ``max_step`` caps a Newton step, ``P`` is the normal resultant (converts a solve's
    residual into the resultant's error)."""
    B = np.eye(2) if basis is None else np.asarray(basis, float).reshape(2, -1)
    zeta = np.asarray(zeta, float)
    held = zeta - B @ (B.T @ zeta)
    tol_Q = 10.0 * tol * scale
    lowest = min(TOL_FLOOR, FINAL_TOL_FACTOR * tol)
    load = P if P > 0 else np.inf  # no contact: no tractions, any tolerance is met
    exact_tol = max(lowest, FINAL_TOL_FACTOR * tol * min(1.0, scale / load))

    def evaluate(s, start, t):
        sol = solve(held + B @ s, start, t)
        return sol, B.T @ np.array([sol.p_x.sum(), sol.p_y.sum()]) * dA - Q

    zeta = B.T @ zeta  # the unknowns s from here on
    sol, F = evaluate(zeta, p0, max(INNER_TOL_MAX, exact_tol))
    iters, exact = sol.iterations, INNER_TOL_MAX <= exact_tol
    final, fresh, step = exact, False, max_step
    for _ in range(MAX_NEWTON):
        if np.linalg.norm(F) <= tol_Q:
            if exact:
                return sol, held + B @ zeta, iters, J
            sol, F = evaluate(zeta, (sol.p_x, sol.p_y), exact_tol)
            iters, exact, final = iters + sol.iterations, True, True
            continue
        dz = -np.linalg.solve(J, F)
        if np.linalg.norm(dz) > step:  # the secant flattens near gross slip
            dz *= step / np.linalg.norm(dz)
        t = exact_tol if final else max(exact_tol, min(
            INNER_TOL_MAX, INNER_TOL_FACTOR * np.linalg.norm(F) / load))
        trial, F_new = evaluate(zeta + dz, (sol.p_x, sol.p_y), t)
        iters, trial_exact = iters + trial.iterations, t <= exact_tol
        bound = (1.0 - SUFFICIENT_DECREASE) * np.linalg.norm(F)
        if np.linalg.norm(F_new) > bound and not trial_exact:
            trial, F_new = evaluate(zeta + dz, (sol.p_x, sol.p_y), exact_tol)
            iters, trial_exact, final = iters + trial.iterations, True, True
        if np.linalg.norm(F_new) <= bound:
            J = J + np.outer(F_new - F - J @ dz, dz) / float(dz @ dz)  # Broyden update
            zeta, sol, F, exact = zeta + dz, trial, F_new, trial_exact
            fresh, step = False, max_step
            if not exact and np.linalg.norm(F) < NOISE_FRACTION * t * load:
                # below the noise of its own solve: F is not resolved, the next step
                # would follow the noise (solve it exactly where it stands)
                sol, F = evaluate(zeta, (sol.p_x, sol.p_y), exact_tol)
                iters, exact, final = iters + sol.iterations, True, True
            continue
        if not exact:  # judge the step against an exact F at the kept shift
            sol, F = evaluate(zeta, (sol.p_x, sol.p_y), exact_tol)
            iters, exact, final = iters + sol.iterations, True, True
            continue
        if exact_tol <= lowest and _unresolved(trial, F, F_new, load):
            return sol, held + B @ zeta, iters, J
        if trial.iterations <= 1 and exact_tol > lowest:
            # the solve returned its start: the step is below what the tolerance resolves
            exact_tol = max(lowest, TIGHTEN * exact_tol)
            sol, F = evaluate(zeta, (sol.p_x, sol.p_y), exact_tol)
            iters += sol.iterations
            continue
        if fresh:
            step = 0.5 * min(step, np.linalg.norm(dz))
        else:
            J, probe_iters = _fd_jacobian(evaluate, zeta, F, sol, 1e-3 * max_step, exact_tol)
            iters, fresh = iters + probe_iters, True
    raise ContactNotConverged(
        f"tangential load control did not converge: |Q - Q_target| = {np.linalg.norm(F):.3e} N "
        f"> {tol_Q:.3e} N (tangential solves to residual {exact_tol:.1e})")


def _unresolved(trial: TangentialSolution, F: np.ndarray, F_new: np.ndarray,
                load: float) -> bool:
    """Whether the tightest solve returned its start, the same tractions to round-off at
    both shifts, with the mismatch within RESOLVED_FRACTION P: what floating point
    resolves at this residual (module doc)."""
    return (trial.iterations <= 1 and np.linalg.norm(F_new - F) <= ROUNDOFF * load
            and np.linalg.norm(F) <= RESOLVED_FRACTION * load)


def _fd_jacobian(evaluate, zeta: np.ndarray, F: np.ndarray, sol: TangentialSolution,
                 h: float, tol: float) -> tuple[np.ndarray, int]:
    """dF/ds by forward differences of step ``h`` (same tolerance as F's solve)."""
    J, iters = np.empty((F.size, zeta.size)), 0
    for col in range(zeta.size):
        e = np.zeros(zeta.size)
        e[col] = h
        probe, Fp = evaluate(zeta + e, (sol.p_x, sol.p_y), tol)
        iters += probe.iterations
        J[:, col] = (Fp - F) / h
    return J, iters
