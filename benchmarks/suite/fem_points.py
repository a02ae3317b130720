"""The FEM reference on quick points: Hertz, Cattaneo–Mindlin and a worn fretting point
(time, peak memory and the Newton iterations of the last step).  Each is minutes at
most; one measurement each (``repeat = 1``), the block cache off so that every
measurement factorises."""

from __future__ import annotations

import os

import fem_reference
from cases import load_case


class FemPoint:
    params = ["hertz", "cattaneo_mindlin", "fretting_orthotropic_beta0"]
    param_names = ["point"]
    number, repeat, rounds, warmup_time = 1, 1, 1, 0.0
    timeout = 1200

    def setup(self, point):
        os.environ["CONTACT_VV_FEM_CACHE"] = "0"
        if point.startswith("fretting"):
            self.case = load_case("fretting_orthotropic", quick=True)[0]  # β = 0, gross slip
        else:
            self.case = load_case(point, quick=True)[0]

    def _solve(self):
        return fem_reference.solve(self.case, vtu=False)

    def time_solve(self, point):
        self._solve()

    def peakmem_solve(self, point):
        self._solve()

    def track_newton_iterations(self, point):
        return self._solve().steps[-1].scalars["iterations"]


