"""Composite elastic constants of a pair of half-spaces (formulation Eq. 6).

Body ``a`` is the upper body (global z points into it), body ``b`` the lower one.  The
relative surface displacement ``u = u^(a) - u^(b)`` (Eq. 1-2) under the tractions ``p``
acting on ``a`` (and ``-p`` on ``b``) is governed by three constants::

    1/G = (1/G_a + 1/G_b) / 2
    nu/G = (nu_a/G_a + nu_b/G_b) / 2
    K = G/4 * ((1 - 2 nu_a)/G_a - (1 - 2 nu_b)/G_b)

K couples the normal and tangential problems; it vanishes for identical bodies
(erratum 10), which then act as one body of shear modulus G/2 on a rigid one.
Subsurface stresses depend on the per-body Poisson ratio (``nu_a``, ``nu_b``), not on
the composite ``nu``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from cases.model import Body


def _check_body(body: Body, name: str) -> None:
    if not (math.isfinite(body.E) and body.E > 0):
        raise ValueError(f"body {name}: E = {body.E!r} must be a finite number > 0")
    if not (math.isfinite(body.nu) and -1.0 < body.nu < 0.5):
        raise ValueError(f"body {name}: nu = {body.nu!r} must lie in (-1, 0.5)")


@dataclass(frozen=True)
class Materials:
    """Composite constants (G, nu, K) of Eq. 6, and the two bodies they come from.

    Build with :meth:`from_bodies`.  ``a`` and ``b`` may be omitted when only the surface
    kernels are needed; the per-body properties then raise.
    """

    G: float
    nu: float
    K: float
    a: Body | None = None
    b: Body | None = None

    @classmethod
    def from_bodies(cls, a: Body, b: Body) -> Materials:
        """Eq. 6 for upper body ``a`` (z points into it) and lower body ``b``."""
        _check_body(a, "a")
        _check_body(b, "b")
        G = 2.0 / (1.0 / a.G + 1.0 / b.G)
        nu = 0.5 * G * (a.nu / a.G + b.nu / b.G)
        K = 0.25 * G * ((1.0 - 2.0 * a.nu) / a.G - (1.0 - 2.0 * b.nu) / b.G)
        return cls(G=G, nu=nu, K=K, a=a, b=b)

    def body(self, which: str) -> Body:
        """The body ``'a'`` or ``'b'``."""
        body = {"a": self.a, "b": self.b}.get(which)
        if which not in ("a", "b"):
            raise ValueError(f"body must be 'a' or 'b', not {which!r}")
        if body is None:
            raise ValueError(f"Materials was built without body {which!r}; use from_bodies")
        return body

    @property
    def nu_a(self) -> float:
        """Poisson ratio of the upper body a (subsurface stresses in a)."""
        return self.body("a").nu

    @property
    def nu_b(self) -> float:
        """Poisson ratio of the lower body b (subsurface stresses in b)."""
        return self.body("b").nu
