"""Which cases the ``kratos`` plugin models, and why not the others.

It models frictionless normal contact of the case's sphere on its plane under the normal
load P (identical or dissimilar materials), as a quarter model (:mod:`kratos_adapter.mesh`).
What it declines, case by case:

- wear (sliding wear, fretting): no wear law is driven through Kratos here;
- a tangential load, a rigid shift or full sliding: Kratos' frictional mortar contact
  (augmented-Lagrangian and penalty, 10.4.4) did not converge on the sphere-on-block
  contact in any setting tried, its own frictional tests' settings among them, where
  the same model converges without friction (the measurements: benchmarks/README.md,
  "Kratos through the gates"; issue 60, point 3);
- dissimilar materials with friction under a normal load: the normal–tangential coupling
  (K ≠ 0) needs the frictional contact;
- the approach held: the plugin drives the normal load P; the approach of its finite
  bodies is not the half-space's, which the case's approach means.
"""

from __future__ import annotations

from cases.model import Case


def supports(case: Case) -> str | None:
    """None when ``kratos`` models the case, else why not (module doc)."""
    ld, f = case.load, case.friction
    if case.kind != "static":
        return (f"{case.kind.replace('_', ' ')}: the kratos plugin models static contact "
                "only (no wear law)")
    if ld.tangential_mode != "none":
        return (f"a tangential load ({ld.tangential_mode}): the kratos plugin models "
                "frictionless normal contact only (Kratos' frictional mortar contact "
                "did not converge on this contact)")
    if not case.identical_materials and max(f.mu1, f.mu2) > 0:
        return ("dissimilar materials with friction: the normal-tangential coupling "
                "(K != 0) needs frictional contact, which the kratos plugin does not model")
    if ld.P is None:
        return ("the approach held: the kratos plugin imposes the normal load P (the "
                "approach of its finite bodies is not the half-space's)")
    return None
