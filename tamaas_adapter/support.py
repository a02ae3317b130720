"""Which cases the Tamaas plugins model, and why not the others.

Tamaas solves one linear elastic half-space against a rigid surface (E, ν of the
half-space; the pair's contact modulus E* gives the normal problem exactly).  What that
cannot be made to model, case by case:

- wear (sliding wear, fretting): Tamaas has no wear law;
- orthotropic friction (μ1 ≠ μ2): its frictional solvers take one isotropic μ;
- dissimilar materials with friction: the normal–tangential coupling of two bodies
  (K ≠ 0, Spence) has no counterpart in one half-space against a rigid surface;
- the approach or a rigid shift held: the plugins impose the loads (mean tractions);
- full sliding on ``tamaas_periodic`` (the sliding law needs no periodic solve: it
  runs on ``tamaas``).

Tamaas's other frictional solver, Condat, solves an associated Coulomb law (its normal
and tangential slips coupled), not the Coulomb law of the cases: the plugins do not use
it.  Full sliding needs no frictional solve: the sliding law on Tamaas's pressure
(PolonskyKeerTan at Q = μP would be the degenerate edge of its feasible set).

Partial slip under a tangential load (Cattaneo–Mindlin): PolonskyKeerTan on Tamaas's
periodic surface model, with ν = 0.5 and E = 0.75 E* so that, as for two identical
bodies, the normal and tangential problems do not couple; the tangential compliance is
then not the pair's, which Mindlin's traction does not depend on.
"""

from __future__ import annotations

from cases.model import Case


def _common(case: Case) -> str | None:
    f = case.friction
    if case.kind != "static":
        return f"{case.kind.replace('_', ' ')}: Tamaas has no wear law"
    if case.load.P is None:
        return "the approach held: the Tamaas plugins impose the normal load P"
    if not f.isotropic:
        return "orthotropic friction (mu1 != mu2): Tamaas's friction solvers take one mu"
    if not case.identical_materials and f.mu1 > 0:
        return ("dissimilar materials with friction: the normal-tangential coupling of "
                "two bodies (K != 0) has no counterpart in Tamaas's one half-space")
    if case.load.tangential_mode == "shift":
        return "a rigid shift held: the Tamaas plugins impose the tangential load"
    return None


def supports(case: Case) -> str | None:
    """None when ``tamaas`` models the case, else why not (module doc)."""
    return _common(case)


def supports_periodic(case: Case) -> str | None:
    """None when ``tamaas_periodic`` models the case, else why not (module doc)."""
    if (why := _common(case)) is not None:
        return why
    if case.load.tangential_mode == "sliding":
        return ("full sliding: the sliding law on Tamaas's pressure runs on tamaas "
                "(nothing periodic to add)")
    return None
