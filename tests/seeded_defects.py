"""Seeded defects: one-line changes a careful developer could make, and the gate that
must catch each (``tests/test_suite_seeded_defects.py``; the list and the catch rate are in
``benchmarks/README.md``, "Escapes").

Each defect replaces ``old`` by ``new`` in ``path`` (every occurrence; ``count`` says how
many there are) in a scratch copy of the packages.  ``cases`` are the bundled cases whose
quick gate (``--solver ic,analytic``, or with the FEM where ``fem``) must then fail — at
the one sweep point ``sweep`` (``contact-vv sweep CASE --param SWEEP``) where it is set;
``selftest`` defects live in the comparisons themselves, where the gate on a correct
solver cannot fail, and the gate's self-test (``tests/test_reports_gate_selftest.py``) must fail
instead; ``baseline`` defects take gated rows out of the gate without moving a number,
which the quick chain's ``gate --baseline tests/baselines`` must name (its cases run
with the default solvers, as the chain runs them).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Defect:
    name: str
    path: str
    old: str
    new: str
    cases: tuple[str, ...] = ()
    count: int = 1
    fem: bool = False
    selftest: bool = False
    sweep: str = ""
    baseline: bool = False


DEFECTS = [
    # ---------------------------------------------------------------- halfspace
    Defect("normal kernel: its Poisson factor",
           "halfspace/influence.py", "return (1.0 - mat.nu) / (np.pi * mat.G) * i_s",
           "return (1.0 - 0.8 * mat.nu) / (np.pi * mat.G) * i_s", ("hertz",)),
    Defect("Cerruti kernel: sign of the nu term of the xx block",
           "halfspace/influence.py", '"xx": c * ((1.0 - nu) * i_s + nu * i_xx),',
           '"xx": c * ((1.0 - nu) * i_s - nu * i_xx),', ("fretting_isotropic",)),
    Defect("coupling: the sign of K",
           "halfspace/materials.py",
           "K = 0.25 * G * ((1.0 - 2.0 * a.nu) / a.G - (1.0 - 2.0 * b.nu) / b.G)",
           "K = -0.25 * G * ((1.0 - 2.0 * a.nu) / a.G - (1.0 - 2.0 * b.nu) / b.G)",
           ("spence",)),
    Defect("coupling: K left out of the tangential step",
           "halfspace/contact.py", "u_tn = self.op.tangential_from_normal(nsol.p_n)",
           "u_tn = (0.0 * nsol.p_n, 0.0 * nsol.p_n)", ("spence",)),
    Defect("tribological axes turned the wrong way",
           "halfspace/friction.py", "np.sin(np.radians(beta))", "np.sin(np.radians(-beta))",
           ("pin_on_disk_orthotropic",), count=2),
    Defect("friction limit: tractions projected onto 90 % of the friction ellipse",
           "halfspace/friction.py", "scale = np.where(outside, rho / np.where(outside, norm, 1.0)",
           "scale = np.where(outside, 0.9 * rho / np.where(outside, norm, 1.0)",
           ("sliding_friction",)),
    Defect("orthotropic wear coefficients swapped",
           "halfspace/friction.py", "return np.hypot(i1 * g1, i2 * g2)",
           "return np.hypot(i2 * g1, i1 * g2)", ("pin_on_disk_orthotropic",)),
    Defect("the worn pin slides backwards",
           "halfspace/wear.py", "ds = sw.step * slide_direction(case.load.slide_angle)",
           "ds = -sw.step * slide_direction(case.load.slide_angle)", ("pin_on_disk",)),
    Defect("wear law: the pin's worn depth 20 % short of Archard's",
           "halfspace/wear.py", "w_a = w_a + _committed(case, k_a * sol.state.p_n)",
           "w_a = w_a + _committed(case, 0.8 * k_a * sol.state.p_n)", ("pin_on_disk",)),
    Defect("cycle jump: a simulated cycle's wear counted J - 1 times",
           "halfspace/wear.py",
           "return sol, J * sn_a * sol.state.p_n, J * sn_b * sol.state.p_n",
           "return sol, (J - 1) * sn_a * sol.state.p_n, (J - 1) * sn_b * sol.state.p_n",
           ("fretting_isotropic",)),
    # the worn orthotropic fretting contact: no closed form, and without the FEM the
    # relations miss the first and see the second in one row only (the 30° turn's energy
    # at β = 90°, which the cycle jump does not converge); the FEM's worn gross-slip
    # point sees both (issue 34, benchmarks/README.md)
    Defect("fretting corrector: its wear compliance without the cycle jump",
           "halfspace/wear.py", "wear_rate=J * (sn_a + sn_b)", "wear_rate=sn_a + sn_b",
           ("fretting_orthotropic",), fem=True, sweep="friction.beta=0"),
    Defect("fretting: body b worn with body a's slip norm",
           "halfspace/wear.py", "J * sn_b * sol.state.p_n", "J * sn_a * sol.state.p_n",
           ("fretting_orthotropic",), fem=True, sweep="friction.beta=0"),
    # in partial slip the FEM's rows are those the resolution probe admits (issue 51)
    Defect("fretting, partial slip: body b worn with body a's slip norm",
           "halfspace/wear.py", "J * sn_b * sol.state.p_n", "J * sn_a * sol.state.p_n",
           ("fretting_orthotropic",), fem=True, sweep="friction.beta=90"),
    Defect("fretting path 10 % short of the amplitude",
           "halfspace/wear.py",
           "return Fretting(amplitude=amplitude, steps_per_cycle=steps_per_cycle)",
           "return Fretting(amplitude=0.9 * amplitude, steps_per_cycle=steps_per_cycle)",
           ("fretting_isotropic",)),
    Defect("tangential load control aims at 90 % of Q",
           "halfspace/tangential_load.py",
           "return sol, B.T @ np.array([sol.p_x.sum(), sol.p_y.sum()]) * dA - Q",
           "return sol, B.T @ np.array([sol.p_x.sum(), sol.p_y.sum()]) * dA - 0.9 * Q",
           ("cattaneo_mindlin",)),
    Defect("stress kernel: Poisson term of sxx under a normal load",
           "halfspace/stress_kernels.py",
           '"sxx": -2.0 * nu * at + 2.0 * (1.0 - 2.0 * nu) * np.arctan2(x, rp_y + z) - xz_y,',
           '"sxx": -2.0 * nu * at + 2.0 * (1.0 - nu) * np.arctan2(x, rp_y + z) - xz_y,',
           ("hertz",)),
    Defect("stress kernel: sign of syy's log term under a tangential load",
           "halfspace/stress_kernels.py", '"syy": 2.0 * nu * ln_y - z * m * y_rz',
           '"syy": -2.0 * nu * ln_y - z * m * y_rz', ("sliding_friction",)),
    Defect("stress planes one cell off the centre",
           "halfspace/stresses.py", 'return {"xz": self.plane(p_x, p_y, p_n, "x", j0),',
           'return {"xz": self.plane(p_x, p_y, p_n, "x", j0 + 1),', ("hertz",)),
    # ---------------------------------------------------------------- analytic
    Defect("Hertz: p0 with 2.1 pi for 2 pi",
           "analytic/hertz.py", "p0=3.0 * P / (2.0 * math.pi * a * a)",
           "p0=3.0 * P / (2.1 * math.pi * a * a)", ("hertz",), count=2),
    Defect("Cattaneo-Mindlin: stick radius with the exponent 1/2",
           "analytic/mindlin.py", "return a * max(1.0 - ratio, 0.0) ** (1.0 / 3.0)",
           "return a * max(1.0 - ratio, 0.0) ** (1.0 / 2.0)", ("cattaneo_mindlin",)),
    Defect("sliding sphere: the traction along the slip",
           "analytic/fields.py", "te = -np.array([f.mu1**2 * de[0], f.mu2**2 * de[1]]) / norm",
           "te = np.array([f.mu1**2 * de[0], f.mu2**2 * de[1]]) / norm",
           ("sliding_friction",)),
    Defect("Argatov: the worn radius with 2 for 4",
           "analytic/wear.py",
           "return (a0**4 + 4.0 * i_w * P * np.asarray(s, float) * R / math.pi) ** 0.25",
           "return (a0**4 + 2.0 * i_w * P * np.asarray(s, float) * R / math.pi) ** 0.25",
           ("pin_on_disk",)),
    Defect("Mindlin: delta* with 12 a for 16 a",
           "analytic/mindlin.py", "return 3.0 * mu * P / (16.0 * a) * comp",
           "return 3.0 * mu * P / (12.0 * a) * comp", ("fretting_isotropic",)),
    Defect("Spence: the slip annulus's traction turned",
           "analytic/spence.py", "sigma = -math.copysign(1.0, K)",
           "sigma = math.copysign(1.0, K)", ("spence",)),
    # ---------------------------------------------------------------- fem_reference
    Defect("FEM: friction axes turned the wrong way",
           "fem_reference/contact/laws.py", "b = np.radians(beta_deg)",
           "b = np.radians(-beta_deg)",
           ("pin_on_disk_orthotropic",), fem=True),
    Defect("FEM: Lame's lambda with (1 - nu) for (1 - 2 nu)",
           "fem_reference/model/elasticity.py",
           "return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))",
           "return E * nu / ((1.0 + nu) * (1.0 - nu)), E / (2.0 * (1.0 + nu))",
           ("hertz",), fem=True),
    Defect("FEM: the normal-tangential coupling blocks of the relative compliance dropped",
           "fem_reference/contact/compliance.py",
           "if R[:, :lo].any() or R[:, hi:].any():", "if False:", ("spence",), fem=True),
    # ---------------------------------------------------------------- reports
    Defect("resolution probe: judging every pair, not the FEM's own",
           "reports/registry/resolution.py",
           "return any(solvers.record(s).step_width is not None for s in pair.split(\"-\", 1))",
           "return True", ("fretting_isotropic",), fem=True, baseline=True),
    Defect("metric normalisation: L2 over twice the reference's norm",
           "reports/compare/metrics.py",
           '{"l2": float(np.linalg.norm(diff)) / l2_ref,',
           '{"l2": float(np.linalg.norm(diff)) / (2.0 * l2_ref),', selftest=True),
    Defect("metric support: the planes' neighbourhood a fifth as deep",
           "reports/compare/metrics.py",
           "<= 0.5 * (hi - lo) * (1.0 + 1e-9)", "<= 0.1 * (hi - lo) * (1.0 + 1e-9)",
           selftest=True),
    Defect("metric support: the max norm over every other point",
           "reports/compare/metrics.py", '"max": float(np.max(np.abs(diff[inner]))) / max_ref',
           '"max": float(np.max(np.abs(diff[inner][::7]))) / max_ref', selftest=True),
    Defect("location: near-maximum sets ten times too wide",
           "reports/compare/maxima.py", "(field >= top * (1.0 - rel))",
           "(field >= top * (1.0 - 10 * rel))", selftest=True),
    Defect("verdict: a metric passes up to twice its tolerance",
           "reports/registry/tolerances.py", "& (v <= t)", "& (v <= 2 * t)", selftest=True),
]
