"""Analytical references: Hertz, Cattaneo–Mindlin, the sliding sphere, pin wear.

Independent of the ``halfspace`` and ``fem_reference`` packages (they are verified
against it).  Modules:

- :mod:`.pointforce` — Boussinesq and Cerruti point-force stresses (Johnson 1985 §3.2);
- :mod:`.quadrature` — stresses of Hertz-shaped tractions on a circle by quadrature;
- :mod:`.hertz` — Hertz contact, on-axis and surface closed forms, Hamilton–Goodman field;
- :mod:`.mindlin` — Cattaneo–Mindlin partial slip, tangential compliance, fretting regime;
- :mod:`.fretting` — the first fretting cycle: Mindlin–Deresiewicz loop, energy, slip, wear;
- :mod:`.sliding` — the sliding sphere: stresses, σ_VM maximum vs μ, surface jump;
- :mod:`.wear` — Argatov (2011) and Hegadekatte (2008) pin wear, orthotropic i_w(θ);
- :mod:`.solver` — the "analytic" solver: ``solve(case, *, progress, on_output)`` and
  ``supports(case)`` (None, or why the case has no closed form), exported here as the
  solver protocol of :mod:`reports.solvers`.
"""

from .solver import solve, supports

__all__ = ["solve", "supports"]
