"""Which cases the ``calculix`` plugin models, and why not the others; the program it
needs.

It models static contact of the case's sphere on its plane (identical or dissimilar
materials, with or without isotropic Coulomb friction) under the normal load P, with
an optional tangential load (Qx, Qy) after it: ``hertz``, ``cattaneo_mindlin``,
``dissimilar``, ``spence`` and user cases of these kinds.  The model keeps the
symmetry the load allows (:func:`symmetry`).  What it declines, case by case:

- wear (sliding wear, fretting): CalculiX has no Archard wear law on contact;
- orthotropic friction: CalculiX's ``*FRICTION`` is isotropic;
- a rigid shift or full sliding: not modelled by this plugin yet (the load path of a
  prescribed shift past gross slip);
- the approach held: the plugin imposes the normal load P (the approach of its finite
  bodies is not the half-space's, which the case's approach means).
"""

from __future__ import annotations

import shutil

from cases.model import Case

#: the CalculiX program, and how to get it
PROGRAM = "ccx"
HOW_TO_GET = ("install CalculiX: apt-get install calculix-ccx (Debian, Ubuntu), or put "
              "a ccx of version 2.20 on the PATH")


def missing() -> str | None:
    """Why the plugin cannot run here (no ``ccx`` on the PATH), None if it can."""
    if shutil.which(PROGRAM) is None:
        return f"the CalculiX program {PROGRAM!r} is not on the PATH: {HOW_TO_GET}"
    return None


def symmetry(case: Case) -> str:
    """'quarter' under a normal load alone, 'half_y0' (cut at y = 0) under a tangential
    load along x, 'half_x0' along y, else 'full': the mirror planes the load keeps (the
    bodies and the isotropic friction keep both; :data:`calculix_adapter.mesh.SYMMETRY`)."""
    ld = case.load
    qx, qy = ld.Qx or 0.0, ld.Qy or 0.0
    if qx == 0.0 and qy == 0.0:
        return "quarter"
    if qy == 0.0:
        return "half_y0"
    return "half_x0" if qx == 0.0 else "full"


def supports(case: Case) -> str | None:
    """None when ``calculix`` models the case, else why not (module doc)."""
    ld, f = case.load, case.friction
    if case.kind != "static":
        return (f"{case.kind.replace('_', ' ')}: the calculix plugin models static contact "
                "only (CalculiX has no Archard wear law on contact)")
    if not f.isotropic:
        return "orthotropic friction: CalculiX's friction is isotropic"
    if ld.tangential_mode in ("shift", "sliding"):
        return (f"a tangential {ld.tangential_mode}: the calculix plugin imposes tangential "
                "loads only (Qx, Qy)")
    if ld.P is None:
        return ("the approach held: the calculix plugin imposes the normal load P (the "
                "approach of its finite bodies is not the half-space's)")
    return None
