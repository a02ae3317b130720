"""What one contact solve is asked and what it returns, shared by the solves
(:mod:`.semismooth`, the default, and :mod:`.augmented`) and by the load paths that call
them: the control (:class:`Control`, its unknowns besides the tractions, :func:`unknowns`)
and the solution (:class:`Solution`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .laws import Evaluation


@dataclass
class Control:
    """Load or displacement control of one contact solve.

    ``P``: total normal load (None: the approach ``delta`` is prescribed).
    ``Q``: total tangential load (x, y) with ``None`` per component for a prescribed
    ``D`` (rigid tangential displacement g_t,o) in that component.
    ``sym``: symmetry factor (4 quarter, 2 half, 1 full).
    ``approach``: under approach control with a far-field ``compliance`` c > 0 (the
    block's missing compliance, :meth:`fem_reference.model.fem_model.FemModel.far_compliance`)
    the half-space approach: δ is then an unknown with the equation δ + c P = approach.
    ``shift``: likewise the half-space's rigid tangential displacement per component
    (None: ``D`` itself is prescribed) with the tangential ``compliance_t``: D_c + c_t Q_c
    = shift_c.
    """

    P: float | None
    delta: float
    D: np.ndarray
    Q: tuple[float | None, float | None] = (None, None)
    sym: float = 1.0
    approach: float | None = None
    compliance: float = 0.0
    shift: tuple[float | None, float | None] = (None, None)
    compliance_t: float = 0.0


@dataclass
class Solution:
    u: np.ndarray
    delta: float
    D: np.ndarray
    ev: Evaluation
    iterations: int
    residual: float
    outer: int = 1  # multiplier updates (augmented Lagrangian)


def unknowns(ctrl: Control) -> tuple[tuple[str, int | None], ...]:
    """The unknowns besides u: ``("delta", None)`` under load control on P,
    ``("approach", None)`` (δ too) under approach control with a far-field compliance,
    ``("D", c)`` for each tangential load component c."""
    extra = []
    if ctrl.P is not None:
        extra.append(("delta", None))
    elif ctrl.approach is not None and ctrl.compliance != 0:
        extra.append(("approach", None))
    for c in (0, 1):
        if ctrl.Q[c] is not None:
            extra.append(("D", c))
        elif ctrl.shift[c] is not None and ctrl.compliance_t != 0:
            extra.append(("shift", c))
    return tuple(extra)
