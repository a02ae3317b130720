"""The half-space solver: normal, partial-slip, sliding and fretting solves at two sizes,
and the σ_VM block (time, peak memory, iterations)."""

from __future__ import annotations

import numpy as np

import halfspace
from halfspace.problem import contact_solver, profile
from halfspace.stresses import StressEvaluator

from .problems import fretting, hertz, mindlin, sliding


class _Timed:
    """Time and peak memory of ``self._solve()``."""

    def time_solve(self, *params):
        self._solve()

    def peakmem_solve(self, *params):
        self._solve()


class NormalContact(_Timed):
    """Hertz, frictionless: Polonsky–Keer CG with zero-padded FFTs."""

    params = [128, 512]
    param_names = ["n"]

    def setup(self, n):
        self.case = hertz(n)

    def _solve(self):
        return contact_solver(self.case).solve(profile(self.case), P=self.case.load.P)

    def track_iterations(self, n):
        return self._solve().iterations


class PartialSlip(_Timed):
    """Cattaneo–Mindlin under load control: the normal step, then the tangential one."""

    params = [128, 256]
    param_names = ["n"]

    def setup(self, n):
        self.case = mindlin(n)

    def _solve(self):
        solver, h = contact_solver(self.case), profile(self.case)
        P, Q = self.case.load.P, self.case.load.Qx
        normal = solver.solve(h, P=P)
        return normal, solver.solve(h, P=P, Q=(Q, 0.0), prev=normal.state)

    def track_tangential_iterations(self, n):
        return self._solve()[1].iterations


class FullSliding(_Timed):
    """Orthotropic full sliding (a far shift): one step of PK + FISTA."""

    params = [128, 256]
    param_names = ["n"]

    def setup(self, n):
        self.case = sliding(n)

    def _solve(self):
        return contact_solver(self.case).solve(profile(self.case), P=self.case.load.P,
                                                shift=(1e3, 0.0))

    def track_iterations(self, n):
        return self._solve().iterations


class FrettingPoint:
    """A quick fretting sweep point, every cycle and output."""

    params = ["isotropic", "orthotropic_beta90"]
    param_names = ["point"]
    timeout = 300

    def setup(self, point):
        self.case = fretting(point)

    def time_solve(self, point):
        halfspace.solve(self.case)

    def peakmem_solve(self, point):
        halfspace.solve(self.case)


class StressBlock:
    """σ_VM on 64 layers to 0.3 mm under the Hertz contact."""

    params = [128, 256]
    param_names = ["n"]

    def setup(self, n):
        case = hertz(n)
        self.state = contact_solver(case).solve(profile(case), P=case.load.P).state
        self.case = case

    def _block(self):
        ev = StressEvaluator(self.case.grid, np.linspace(0.0, 0.3, 64), self.case.b.nu, "b")
        return ev.block(self.state.p_x, self.state.p_y, self.state.p_n)

    def time_block(self, n):
        self._block()

    def peakmem_block(self, n):
        self._block()
