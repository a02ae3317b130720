"""What a case will cost the Tamaas plugins, before any work (``estimate``).

Memory: Tamaas's volume operators hold about :data:`BYTES_PER_VOLUME_POINT` per point of
the stress domain (the case's layers on the padded grid, :func:`tamaas_adapter.volume.
padding`, whose loaded width is taken as the Hertz contact's, 2 a0, plus a cell); the
surface solves are small beside it.  Time: PolonskyKeerTan's fixed iterations on its
widened cell, and the volume operators per point.  Coefficients measured on the bundled
cases (benchmarks/README.md, "Tamaas through the gates"); the estimate is an order of
magnitude, not calibrated for a deadline.
"""

from __future__ import annotations

from cases.model import Case
from cases.result import Cost

from . import contact, volume

BYTES_PER_VOLUME_POINT = 520.0  # above most runs measured (benchmarks/README.md)
BASE_BYTES = 0.15e9  # interpreter, numpy, Tamaas
SECONDS_PER_VOLUME_POINT = 1e-6
SECONDS_PER_PKT_CELL = 1e-6  # one PolonskyKeerTan iteration, per cell of its cell


def estimate(case: Case, periodic: bool) -> Cost:
    """Peak memory and wall time of one Tamaas run of ``case`` (module doc)."""
    g, st = case.grid, case.stress
    a0 = case.hertz_scales[0]
    pad = 1 if periodic else volume.grids_for(case, 2.0 * a0 + max(g.dx, g.dy))
    points = st.nz * pad**2 * g.nx * g.ny
    seconds = points * SECONDS_PER_VOLUME_POINT
    if case.load.tangential_mode == "load":
        cells = g.nx * g.ny * (1 if periodic else 4)
        seconds += contact.PKT_ITERATIONS * cells * SECONDS_PER_PKT_CELL
    return Cost(memory=BASE_BYTES + BYTES_PER_VOLUME_POINT * points, seconds=seconds,
                memory_keys=("grid.nx", "grid.ny", "stress.nz"),
                time_keys=("grid.nx", "grid.ny", "stress.nz"))
