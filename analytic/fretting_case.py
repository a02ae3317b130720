"""The analytic solver's fretting case: the first cycle of a fretting case with a
closed form (isotropic friction, K = 0, the first cycle an output): Mindlin–Deresiewicz
loop and energy, Archard's first-cycle wear of both bodies, the Hertz pressure and the
Cattaneo traction at the cycle's end (:mod:`analytic.fretting`), on the path the solvers
impose."""

from __future__ import annotations

import math
import time

import numpy as np

from cases.model import Case, Fretting
from cases.result import CYCLE_COLUMNS, LOOP_COLUMNS, StepResult, gross_slip, table_of

from . import fields, wear
from . import fretting as fr
from .mindlin import fretting_regime


def imposed_cycle(amplitude: float, steps_per_cycle: int) -> np.ndarray:
    """The displacements of one cycle as the fretting solvers impose them
    (:meth:`cases.model.Fretting.cycle_path`)."""
    return Fretting(amplitude=amplitude, steps_per_cycle=steps_per_cycle).cycle_path()


def imposed_history(amplitude: float, steps_per_cycle: int) -> tuple[np.ndarray, int]:
    """(history, q): the whole imposed displacement history of a first cycle from the
    unloaded contact — 0, the initial loading 0 -> +A in q steps
    (:meth:`cases.model.Fretting.loading_path`), then :func:`imposed_cycle`;
    ``history[q:]`` is the closed cycle from +A (its first point) back to +A."""
    path = Fretting(amplitude=amplitude, steps_per_cycle=steps_per_cycle)
    loading = path.loading_path()
    return np.concatenate([[0.0], loading, path.cycle_path()]), loading.size


def no_solution_reason(case: Case) -> str | None:
    """Why a fretting case has no first-cycle closed form here (None: it has one)."""
    f, fc, a, b = case.friction, case.fretting, case.a, case.b
    if fc is None:
        return "fretting without a [fretting] table (no imposed path)"
    if not f.isotropic:
        return ("fretting with orthotropic friction (Mindlin-Deresiewicz needs isotropic "
                "friction, mu1 == mu2)")
    try:
        fr.check_uncoupled(a.E, a.nu, b.E, b.nu)
    except ValueError:
        return ("fretting of a pair with normal-tangential coupling (K != 0: the "
                "tangential load changes the pressure)")
    if (a.i1 != a.i2 or b.i1 != b.i2) and (case.load.slide_angle - f.beta) % 90.0 != 0.0:
        return ("fretting across the principal axes of orthotropic wear coefficients "
                "(slide_angle - beta not a multiple of 90 deg)")
    if fc.jump != 1.0:
        return (f"fretting with cycle jump {fc.jump:g}: the closed form is the first "
                "cycle, an output only with fretting.jump = 1")
    if 1 not in fc.output_cycles and fc.cycles != 1:
        return ("fretting: the first cycle is not an output (the closed form covers only "
                "cycle 1; add 1 to fretting.output_cycles)")
    return None


def fretting_reference(case: Case) -> fr.MindlinDeresiewicz:
    """The scales of the case's first fretting cycle: Hertz at the held load or approach,
    δ* and λ of the pair (:class:`analytic.fretting.MindlinDeresiewicz`)."""
    a, b, mu = case.a, case.b, case.friction.mu1
    if case.load.P is not None:
        return fr.MindlinDeresiewicz.from_load(case.load.P, case.R, mu, a.E, a.nu, b.E, b.nu)
    return fr.MindlinDeresiewicz.from_approach(case.load.approach, case.R, mu, a.E, a.nu, b.E, b.nu)


def fretting_steps(case: Case) -> tuple[list[StepResult], dict]:
    """The output step of the first cycle of a ``fretting`` case, and its tables.

    Path (as the solvers impose it): after the normal load, 0 -> +A along d = (cos φ,
    sin φ), φ = ``load.slide_angle``, in a quarter cycle, then +A -> -A -> +A in
    ``steps_per_cycle`` steps (:func:`imposed_history`).  The step is
    numbered 1 (the solvers number fretting outputs by simulated cycle), ``cycle`` = 1.

    - scalars: Hertz P, p_max = p0, a, contact area (the pressure stays Hertzian: K = 0
      and the first-cycle wear is negligible against the approach for the bundled wear
      coefficients); Q = -F(A) d at the end of the cycle (the loop has closed on the
      virgin curve; the traction on a opposes a's shift); stick area π c², c = a√(1 -
      A/δ*) (0 in gross slip); w_max and the worn volume i_w ΔW / μ of the cycle;
    - surface: Hertz p_n, the Cattaneo traction of the shift A at the cycle's end, the
      state (stick r < c, slip c < r < a, open outside), the wear of each body: the gap's
      first-cycle wear :func:`analytic.fretting.cycle_wear` (with the ν-term of the
      Cerruti kernel) split in the ratio of the bodies' coefficients i_w(θ), θ =
      slide_angle - β (Eq. 19: the Cattaneo slip is taken along d);
    - planes: Hamilton–Goodman plus the quadrature of that traction;
    - tables: ``loops`` (cycle, displacement, Qx, Qy) at the cycle's imposed
      displacements, Q = -Q_MD d (:func:`analytic.fretting.md_path`); ``cycles`` (cycle,
      energy, energy_exact, min_stick_area, gross_slip, w_max): ``energy`` is the
      trapezoidal rule on the same steps, as every solver's ``energy`` column, and
      ``energy_exact`` the closed form :func:`analytic.fretting.cycle_energy`, so that
      the comparison of ``energy`` measures the solver and not the time rule.
    """
    t0 = time.perf_counter()
    fc, f, g = case.fretting, case.friction, case.grid
    ref = fretting_reference(case)
    h = fields.normal(case)
    fields.check_grid(case, h.a, "Hertz")
    mu, A, steps = f.mu1, fc.amplitude, fc.steps_per_cycle
    phi = math.radians(case.load.slide_angle)
    d = np.array([math.cos(phi), math.sin(phi)])
    hist, q = imposed_history(A, steps)
    Q_md = fr.md_path(hist, mu, ref.P, ref.delta_star)
    Q_end = fr.load_amplitude(A, mu, ref.P, ref.delta_star)
    c = fr.stick_radius_at(A, ref.a, ref.delta_star)
    theta = wear.sliding_angle(f.beta, case.load.slide_angle)
    i_a, i_b = (wear.wear_coefficient(bd.i1, bd.i2, theta) for bd in (case.a, case.b))
    # the Cattaneo traction at +A: the virgin state of the shift A (module doc)
    e = -d
    q0 = mu * h.p0
    terms = [(h.a, tuple(q0 * e))] + ([(c, tuple(-(c / h.a) * q0 * e))] if c > 0 else [])
    tang = dict(terms=terms, Q=tuple(float(v) for v in -Q_end * d), c=c)
    surface = fields.surface(case, h, tang)
    w_max = _wear_fields(case, ref, surface, d, i_a, i_b)
    planes = fields.planes(case, h, terms)
    stick = math.pi * c * c
    W_exact = fr.cycle_energy(A, mu, ref.P, ref.delta_star)
    W_trap = fr.loop_area(hist[q:], Q_md[q:])
    scalars = dict(
        step=1, s=math.nan, cycle=1.0, P=h.P, Qx=tang["Q"][0], Qy=tang["Q"][1],
        contact_area=h.area, a_x=h.a, a_y=h.a, p_max=h.p0, w_max=w_max,
        wear_volume=fr.cycle_wear_volume(A, mu, ref.P, ref.delta_star, i_a + i_b),
        **fields.vm_scalars(case, planes), stick_area=stick, slip_area=h.area - stick,
        iterations=0, converged=True, approach=h.delta, stick_radius=c, p0=h.p0, a0=h.a,
        delta_star=ref.delta_star, amplitude=A, energy=W_trap, energy_exact=W_exact,
    )
    scalars["wall_s"] = time.perf_counter() - t0
    cyc = hist[q + 1:]
    loops = table_of(LOOP_COLUMNS, {"cycle": np.ones(cyc.size), "displacement": cyc,
                                    "Qx": -Q_md[q + 1:] * d[0], "Qy": -Q_md[q + 1:] * d[1]})
    cycles = table_of(CYCLE_COLUMNS, {
        "cycle": 1.0, "energy": W_trap, "energy_exact": W_exact, "min_stick_area": stick,
        "gross_slip": gross_slip(fretting_regime(A, ref.delta_star)), "w_max": w_max},
        extra=("energy_exact",))
    step = StepResult(scalars=scalars, x=g.x.copy(), y=g.y.copy(), surface=surface,
                      planes=planes)
    return [step], {"loops": loops, "cycles": cycles}


def _wear_fields(case: Case, ref: fr.MindlinDeresiewicz, surface: dict[str, np.ndarray],
                 d: np.ndarray, i_a: float, i_b: float) -> float:
    """Add the first-cycle wear of each body (the gap's :func:`analytic.fretting.cycle_wear`
    in the path frame, split in the ratio of the coefficients) to ``surface`` and the gap;
    return the maximum of the closed form (|s + λ n cos 2θ| peaks at cos 2θ = ±1)."""
    g, A, i_w = case.grid, case.fretting.amplitude, i_a + i_b
    X, Y = np.meshgrid(g.x, g.y, indexing="ij")
    Xp, Yp = X * d[0] + Y * d[1], -X * d[1] + Y * d[0]  # the path frame
    w_gap = fr.cycle_wear(Xp, Yp, A, ref.a, ref.p0, ref.delta_star, i_w, ref.lam)
    share = i_a / i_w if i_w > 0 else 0.0
    surface["wear_a"] = share * w_gap
    surface["wear_b"] = (1.0 - share) * w_gap
    surface["gap"] = surface["gap"] + w_gap
    r = np.linspace(0.0, ref.a, 4001)
    zero = np.zeros_like(r)
    return float(max(fr.cycle_wear(r, zero, A, ref.a, ref.p0, ref.delta_star, i_w,
                                   ref.lam).max(),
                     fr.cycle_wear(zero, r, A, ref.a, ref.p0, ref.delta_star, i_w,
                                   ref.lam).max()))
