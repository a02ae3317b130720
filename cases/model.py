"""The case model: a validated, immutable description of one contact problem.

A case is read from a TOML file (see ``cases/README.md`` for every key) by
:func:`cases.loader.load_case`.  Solvers receive a :class:`Case` and nothing else.
Units: mm, N, MPa; angles in degrees.

Conventions shared by both solvers (``docs/formulation.md``):

- body ``a`` is the upper body (the indenter, sphere, pin), body ``b`` the lower one
  (the plane, disk); global z points into body ``a``;
- the indenter profile is the paraboloid ``h(x, y) = (x² + y²) / (2 R)``;
- ``p_n > 0`` is compressive; ``(p_x, p_y)`` is the tangential traction acting on body
  ``a`` (Eq. 13: it opposes the slip of ``a`` relative to ``b``);
- the rigid tangential displacement ``g_t,o`` is that of ``a`` relative to ``b``;
- subsurface stresses are reported in the body ``stress.body`` with ``z >= 0`` the
  depth into that body, x and y the global axes; tensile stress positive.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace


class CaseError(ValueError):
    """A case definition is invalid; the message names the offending key."""


@dataclass(frozen=True)
class Body:
    """Elastic constants and orthotropic wear coefficients of one body (Eq. 19, 21)."""

    E: float
    nu: float
    i1: float = 0.0  # wear coefficient along e1 [1/MPa]
    i2: float = 0.0  # wear coefficient along e2 [1/MPa]

    @property
    def G(self) -> float:
        return self.E / (2.0 * (1.0 + self.nu))


@dataclass(frozen=True)
class Friction:
    """Orthotropic Coulomb friction (Eqs. 9-14): principal coefficients and axes angle."""

    mu1: float = 0.0
    mu2: float = 0.0
    beta: float = 0.0  # angle of e1 from x, counter-clockwise [deg]

    @property
    def isotropic(self) -> bool:
        return self.mu1 == self.mu2


@dataclass(frozen=True)
class Grid:
    """Potential contact area [-Lx/2, Lx/2] x [-Ly/2, Ly/2] with nx x ny cells."""

    Lx: float
    Ly: float
    nx: int
    ny: int

    @property
    def dx(self) -> float:
        return self.Lx / self.nx

    @property
    def dy(self) -> float:
        return self.Ly / self.ny

    @property
    def x(self):
        import numpy as np

        return (np.arange(self.nx) + 0.5) * self.dx - 0.5 * self.Lx

    @property
    def y(self):
        import numpy as np

        return (np.arange(self.ny) + 0.5) * self.dy - 0.5 * self.Ly

    def nearest_cell(self, x0: float, y0: float) -> tuple[int, int]:
        """(i, j) of the cell centre nearest to the point (x0, y0)."""
        import numpy as np

        return int(np.argmin(np.abs(self.x - x0))), int(np.argmin(np.abs(self.y - y0)))


@dataclass(frozen=True)
class Load:
    """Static loading of one step: normal load or approach, tangential load or shift.

    Normal: exactly one of ``P`` [N] (load control) and ``approach`` [mm]
    (displacement control, the rigid approach g_o of Eq. 1).
    Tangential: either a load ``(Qx, Qy)`` [N] (load control), or a rigid shift
    ``(shift_x, shift_y)`` [mm] of body a relative to body b (displacement control), or
    ``sliding = true``: gross sliding of a relative to b along ``slide_angle`` [deg from x].
    """

    P: float | None = None
    approach: float | None = None
    Qx: float | None = None
    Qy: float | None = None
    shift_x: float | None = None
    shift_y: float | None = None
    sliding: bool = False
    slide_angle: float = 0.0

    @property
    def load_controlled(self) -> bool:
        return self.P is not None

    @property
    def tangential_mode(self) -> str:
        """'none', 'load', 'shift' or 'sliding'."""
        if self.sliding:
            return "sliding"
        if self.Qx is not None or self.Qy is not None:
            return "load"
        if self.shift_x is not None or self.shift_y is not None:
            return "shift"
        return "none"


@dataclass(frozen=True)
class SlidingWear:
    """Pin-on-disk: constant load, every cell slides ``step`` per increment (case 4, 5)."""

    step: float = 1.0  # sliding distance per increment [mm]
    distance: float = 640.0  # total sliding distance [mm]
    output_s: tuple[float, ...] = ()  # sliding distances written out [mm]


@dataclass(frozen=True)
class Fretting:
    """Alternating tangential displacement 0 -> +d -> -d -> +d ... (case 6)."""

    amplitude: float = 0.004  # [mm]
    steps_per_cycle: int = 20
    cycles: int = 100
    jump: float = 1.0  # cycle-jump (wear acceleration) factor
    output_cycles: tuple[int, ...] = ()
    #: the rigid motion across the imposed one: "held" at zero, or "free" (no resultant
    #: across it; the shift across is found in each step)
    transverse: str = "held"

    @property
    def simulated_cycles(self) -> int:
        """How many cycles are simulated: cycles / jump, a whole number when the case is
        built (:func:`cases.build._on_jump_grid`; rounded, not cut up: 21 / 1.4 is
        15.000000000000002 in floats)."""
        return self.simulated_cycle(self.cycles)

    def simulated_cycle(self, cycle: float) -> int:
        """The simulated cycle that ends at real cycle ``cycle`` (a whole number of jumps)."""
        return max(round(cycle / self.jump), 1)

    def loading_path(self):
        """The imposed displacements of the initial loading 0 -> +A: q =
        max(steps_per_cycle // 4, 1) equal steps, the start 0 excluded."""
        import numpy as np

        q = max(self.steps_per_cycle // 4, 1)
        return self.amplitude * np.arange(1, q + 1) / q

    def cycle_path(self):
        """The imposed displacements of one cycle +A -> -A -> +A: steps of
        2A / (steps_per_cycle // 2), the start +A excluded (its last point is +A)."""
        import numpy as np

        half = self.steps_per_cycle // 2
        down = self.amplitude * (1 - 2 * np.arange(1, half + 1) / half)  # +A -> -A
        return np.concatenate([down, down[::-1][1:], [self.amplitude]])  # -A -> +A


@dataclass(frozen=True)
class StressOutput:
    """Where subsurface stresses are sampled (Eq. 32-34)."""

    body: str = "b"  # body whose stresses are reported: 'a' or 'b'
    depth: float = 0.3  # deepest layer [mm]
    nz: int = 31  # layers from z = 0 to depth (inclusive)
    x0: float = 0.0  # planes pass through (x0, y0)
    y0: float = 0.0
    #: the depth [mm] from which ``vm_max_below`` (the σ_VM maximum over the planes at
    #: z >= z_below) is taken; None: not reported
    z_below: float | None = None

    @property
    def z(self):
        import numpy as np

        return np.linspace(0.0, self.depth, self.nz)


@dataclass(frozen=True)
class Solver:
    """Half-space solver settings (section 3.4)."""

    method: str = "cg"  # 'cg' (Polonsky-Keer normal + accelerated tangential) or 'uzawa'
    tol: float = 1e-10  # relative residual of the complementarity conditions
    max_iter: int = 20000
    #: half-width [mm] of the tent each committed wear increment is spread by (the
    #: resolution probe, halfspace/wear_spread.py); 0: none
    wear_spread: float = 0.0


@dataclass(frozen=True)
class FemSettings:
    """Finite-element reference settings; lengths in units of the Hertz radius a0."""

    block: float = 20.0  # block half-width L / a0
    depth: float = 20.0  # block depth H / a0
    h: float = 0.125  # element size in the contact zone / a0
    order: int = 2
    penalty: float = 100.0  # normal penalty in units of E*/h_contact ('augmented' only)
    contact: str = "semismooth"  # contact solve: 'semismooth' or 'augmented' (penalty)
    h_surface: float | None = None  # element size at the contact surface / a0 (None: h)

    @property
    def h_contact(self) -> float:
        """The element size at the contact surface / a0: ``h_surface``, else ``h``."""
        return self.h if self.h_surface is None else self.h_surface

    @property
    def surface_layer(self) -> float | None:
        """``h_surface`` where it refines the surface (below ``h``), else None."""
        return self.h_surface if self.h_surface is not None and self.h_surface < self.h else None

    def refined(self, factor: float) -> FemSettings:
        """These settings with every element size divided by ``factor``."""
        hs = None if self.h_surface is None else self.h_surface / factor
        return replace(self, h=self.h / factor, h_surface=hs)


@dataclass(frozen=True)
class Case:
    name: str
    kind: str  # 'static' | 'sliding_wear' | 'fretting'
    a: Body
    b: Body
    R: float
    grid: Grid
    friction: Friction
    load: Load
    stress: StressOutput = field(default_factory=StressOutput)
    solver: Solver = field(default_factory=Solver)
    sliding_wear: SlidingWear | None = None
    fretting: Fretting | None = None
    fem: FemSettings = field(default_factory=FemSettings)
    tolerances: dict[str, float] = field(default_factory=dict)
    #: quantity -> why it is not a converged number (compared, shown, not gated)
    not_converged: dict[str, str] = field(default_factory=dict)
    #: NAME -> the ``[external.NAME]`` table: result files of another code, read by the
    #: solver ``external:NAME`` (:mod:`external_results.spec` checks it)
    external: dict[str, dict] = field(default_factory=dict)
    description: str = ""
    param: str = ""  # sweep label such as 'mu=0.25'; '' when not a sweep point
    source: str = ""  # path of the TOML file

    @property
    def plane_centre(self) -> tuple[float, float]:
        """(x, y) where every solver's stress planes cross: the cell centre of the case's
        grid nearest to (``stress.x0``, ``stress.y0``) (the half-space solver evaluates its
        stresses at cell centres; a plane half a cell off would compare another field)."""
        i, j = self.grid.nearest_cell(self.stress.x0, self.stress.y0)
        return float(self.grid.x[i]), float(self.grid.y[j])

    @property
    def identical_materials(self) -> bool:
        return self.a.E == self.b.E and self.a.nu == self.b.nu

    @property
    def dundurs_beta(self) -> float:
        """Dundurs' β of the pair, ½ [(1 − 2ν_a)/G_a − (1 − 2ν_b)/G_b] / [(1 − ν_a)/G_a +
        (1 − ν_b)/G_b] (docs/formulation.md §2.8; K / (1 − ν) of Eq. 6): 0 without the
        normal–tangential coupling."""
        a, b = self.a, self.b
        ga, gb = a.E / (2 * (1 + a.nu)), b.E / (2 * (1 + b.nu))
        return 0.5 * ((1 - 2 * a.nu) / ga - (1 - 2 * b.nu) / gb) / ((1 - a.nu) / ga
                                                                     + (1 - b.nu) / gb)

    @property
    def E_star(self) -> float:
        """Contact modulus 1/E* = (1 - nu_a^2)/E_a + (1 - nu_b^2)/E_b."""
        return 1.0 / ((1 - self.a.nu**2) / self.a.E + (1 - self.b.nu**2) / self.b.E)

    @property
    def hertz_a0(self) -> float:
        """Hertz radius a0 = (3 P R / 4 E*)^(1/3) for the normal load (load control only)."""
        if self.load.P is None:
            raise CaseError("hertz_a0 needs load.P")
        return (3.0 * self.load.P * self.R / (4.0 * self.E_star)) ** (1.0 / 3.0)

    @property
    def hertz_scales(self) -> tuple[float, float]:
        """(a0 [mm], p0 [MPa]) of the Hertz contact of the sphere at the case's normal
        load: the length and stress scales of tables and plots (x/a0, σ/p0).

        Load control: a0 = (3PR / 4E*)^(1/3), p0 = 3P / (2π a0²).  Displacement control
        (approach δ): a0 = √(Rδ), p0 = 2 E* a0 / (π R) — the same Hertz contact.
        """
        if self.load.P is not None:
            a0 = self.hertz_a0
            return a0, 3.0 * self.load.P / (2.0 * math.pi * a0**2)
        a0 = math.sqrt(self.R * float(self.load.approach))
        return a0, 2.0 * self.E_star * a0 / (math.pi * self.R)

    @property
    def _slide_in_axes(self) -> tuple[float, float]:
        """(d_e1, d_e2): the unit sliding direction ``load.slide_angle`` in the
        tribological axes, rotated by β."""
        theta = math.radians(self.load.slide_angle - self.friction.beta)
        return math.cos(theta), math.sin(theta)

    @property
    def sliding_wear_coefficient(self) -> float:
        """i_w of the gap for sliding along ``load.slide_angle``: the sum over both bodies
        of ‖d‖_i = √((i1 d_e1)² + (i2 d_e2)²) (Eq. 19-21) for the unit direction d."""
        c, s = self._slide_in_axes
        return sum(math.hypot(b.i1 * c, b.i2 * s) for b in (self.a, self.b))

    @property
    def sliding_friction(self) -> float:
        """μ along ``load.slide_angle``: ``‖d‖*_μ = √((μ1 d_e1)² + (μ2 d_e2)²)``, the friction
        force per unit pressure opposing gross slip along d (Eq. 13)."""
        c, s = self._slide_in_axes
        return math.hypot(self.friction.mu1 * c, self.friction.mu2 * s)

    @property
    def expected_radius(self) -> float:
        """The largest contact radius the case should reach [mm], an a-priori estimate:
        the Hertz a0, and for sliding wear under load control Argatov's worn-pin radius
        a = (a0⁴ + 4 i_w P s R / π)^(1/4) at the final distance (docs/cases.md, case 4),
        with i_w from :attr:`sliding_wear_coefficient`."""
        if self.sliding_wear is not None and self.load.P is not None:
            return self.worn_pin_radius(self.sliding_wear.distance)
        return self.hertz_scales[0]

    def worn_pin_radius(self, s: float) -> float:
        """Argatov's worn-pin radius a = (a0⁴ + 4 i_w P s R / π)^(1/4) [mm] after the
        sliding distance ``s`` [mm] under the held load P (docs/cases.md, case 4), i_w
        from :attr:`sliding_wear_coefficient`."""
        a0, _ = self.hertz_scales
        i_w = self.sliding_wear_coefficient
        return (a0**4 + 4.0 * i_w * self.load.P * s * self.R / math.pi) ** 0.25

    @property
    def worn_radius_estimate(self) -> float | None:
        """For fretting, the worn contact radius to expect at the last cycle [mm] (None
        for other kinds), before any work.  Held approach δ: the rigid overlap √(2Rδ), a
        bound (wear and elastic displacement only open the gap).  Held load:
        :meth:`worn_pin_radius` for the slip distance of gross slip in every cycle,
        s = 4 A N, with i_w along the imposed displacement.  In gross slip it is
        close (bundled β sweep under a held 778.41 N: a_x within 1 % at 2000 cycles,
        −3.7 % at 1e5); where a stick zone stays or the elastic tangential displacement
        takes part of the amplitude it over-estimates (β = 30–70 at 1e5 cycles: 1.3–1.6
        times the worn area; β = 90: 3.8 times the radius)."""
        if self.kind != "fretting" or self.fretting is None:
            return None
        if self.load.P is None:
            return math.sqrt(2.0 * self.R * self.load.approach)
        return self.worn_pin_radius(4.0 * self.fretting.amplitude * self.fretting.cycles)

    def with_changes(self, **kw) -> Case:
        return replace(self, **kw)


def check_positive(value: float, key: str, *, allow_zero: bool = False) -> None:
    ok = value >= 0 if allow_zero else value > 0
    if not (isinstance(value, int | float) and math.isfinite(value) and ok):
        bound = ">= 0" if allow_zero else "> 0"
        raise CaseError(f"{key} = {value!r}: must be a finite number {bound}")


def one_case(case: object, solver: str) -> Case:
    """``case`` if it is one :class:`Case`, else a TypeError for the solver ``solver``
    that says how to get one (:func:`cases.load_case` gives a list, a Case per sweep
    point)."""
    if isinstance(case, Case):
        return case
    hint = (" (load_case gives a list, one Case per sweep point: take one, or use "
            "cases.load_point(name, point))" if isinstance(case, list | tuple) else "")
    raise TypeError(f"{solver}.solve takes one Case, not a {type(case).__name__}{hint}")

