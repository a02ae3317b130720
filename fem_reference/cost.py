"""What a case will cost the FEM reference, estimated before any meshing or allocation.

Mesh: :func:`mesh_spec` builds the :class:`~fem_reference.model.mesh.MeshSpec` that
:class:`~fem_reference.model.fem_model.FemModel` builds, and :func:`element_count` counts the
tetrahedra gmsh will make without meshing, integrating the element density of the size
field of :mod:`fem_reference.model.mesh` over the block by Gauss-Legendre panels in (r, z);
P2 nodes, free DOFs and the condensed surface DOFs follow.  Memory: the parts alive
together at the peak — the process and its mesh, PARDISO's factors, the dense surface
operators.  Time: meshing, assembly, factorisation with the Schur block of the condensed
DOFs and its inverse, the set-up of a cold point, then the contact solves of the load
path (by the solve of ``fem.contact``; the semi-smooth one by kind of contact).
:attr:`Cost.memory_keys` and ``time_keys`` name the keys whose refinement raises the
estimate by 10 % or more, strongest first. The model's constants are fitted on this
project's meshes and runs; the fit, the measurements and the scaling of each stage are
in ``benchmarks/README.md``
("The FEM's cost estimate").
"""

from __future__ import annotations

import dataclasses
import math
import types
from dataclasses import dataclass

import numpy as np

from cases.model import Case, FemSettings
from cases.result import Cost
from cases.steps import fretting_outputs, normal_fractions, sliding_outputs, sliding_steps

from .model.fem_model import FemModel
from .model.mesh import SURFACE_GRADING, MeshSpec
from .model.shape import (
    choose_shape,
    condensed_radius,
    has_companion,
    mesh_reach,
    reference_length,
)

C_TET = 0.225  # mean tetrahedron volume / size³ of gmsh's meshes
C_TRI = 0.405  # mean surface triangle area / size²
# Memory, fitted on the quick points' peak RSS (benchmarks/README.md, "The FEM's cost
# estimate"): the process and its mesh, PARDISO's factors, the dense surface operators
# alive together (fitted while C_rel was formed whole and the nodal compliance kept its
# zero blocks: an upper bound since, held by tests/test_fem_cost.py)
BASE_BYTES = 44e6
BYTES_PER_TET = 11.9e3  # the mesh, the P2 space and the assembly's arrays
FACTOR_BYTES_PER_DOF = 279.0  # times n^(1/3), per factorisation
DENSE_COPIES = 3.12  # m x m float64 arrays alive at once
# Time [s], fitted on the wall times of the quick points (same section)
SECONDS_BASE = 0.54  # the point's own overhead: case set-up, results
SECONDS_PER_TET_MESH = 2e-5
SECONDS_PER_TET_ASSEMBLY = 1.08e-4  # per Poisson's ratio
SECONDS_FACTOR = 6.35e-10  # times n² per factorisation (PARDISO with its Schur block)
SECONDS_SCHUR = 2.575e-11  # times m³ per Poisson's ratio (the Schur block and its inverse)
SECONDS_SETUP = 6.44e-7  # times m^1.5 (the nodal compliance, the far field)
#: the semi-smooth solve (fem.contact = semismooth): times m A per contact solve (its
#: Newton systems on the A contact DOFs read the rows of the m condensed ones), by kind
#: of contact: frictionless, full sliding, a static friction load, fretting ...
SECONDS_SEMISMOOTH = {"frictionless": 4.91e-8, "sliding": 1.054e-7, "friction": 5.87e-8,
                      "fretting": 1.85e-8}
#: ... times this in fretting in partial slip (the stick edge moves at every step: more
#: Newton iterations a solve than in gross slip) ...
PARTIAL_SLIP_SOLVES = 1.53
#: ... and, for either solve, times this where friction couples dissimilar materials'
#: normal and tangential problems (more iterations)
COUPLED_SOLVES = 2.17
SECONDS_CONTACT = 4.62e-11  # fem.contact = augmented: times A³ per iteration ...
SECONDS_CONTACT_M2 = 2.1e-9  # ... + m² (dense products, line search)
SECONDS_OUTPUT = 0.3  # per output step (recovery, stress planes, .vtu)
#: the calibration of the time estimate: the calibration runs' wall times lie within
#: this factor of it (benchmarks/README.md, tests/test_fem_cost.py)
TIME_FACTOR = 2.0
ITERATIONS = {"single": 5, "friction": 10, "wear": 3}

_PANELS_MAX = 40  # geometric panels beyond the refined zone
_GAUSS = np.polynomial.legendre.leggauss(10)


def mesh_spec(case: Case) -> tuple[MeshSpec | None, dict]:
    """The mesh parameters :class:`~fem_reference.model.fem_model.FemModel` uses for ``case``
    (None for the spec when they are invalid: the run would refuse them) and the model's
    other drivers: ``a_max`` (expected radius / a_ref), ``r_c``, ``r_cond`` (the condensed
    zone's radius), ``shape``, ``comps``
    (condensed components), ``nus`` (distinct Poisson's ratios), ``law``."""
    fem = case.fem
    a_max = mesh_reach(case, reference_length(case))
    r_c = 1.25 * a_max + 2.0 * fem.h
    z_ref = max(1.0, 0.8 * a_max)
    r_fine = min(1.25, r_c) if a_max > 1.25 else r_c
    shape = choose_shape(case)
    law = FemModel._law_mode(types.SimpleNamespace(case=case))
    normal_only = law == "frictionless" or (law == "sliding" and case.identical_materials)
    info = {"a_max": a_max, "r_c": r_c, "shape": shape, "law": law,
            "r_cond": condensed_radius(case, reference_length(case), r_c),
            "comps": (2,) if normal_only else (0, 1, 2),
            "nus": tuple(sorted({case.a.nu, case.b.nu})), "companion": has_companion(case)}
    kw = dict(shape=shape, L=fem.block, H=fem.depth, h=fem.h, r_ref=r_c, z_ref=z_ref,
              grading=0.25, h_max=fem.block / 4.0, r_fine=r_fine, h_surface=fem.surface_layer)
    try:
        spec = MeshSpec(**kw)
    except Exception:  # invalid parameters: estimate them all the same
        spec = None
    info["params"] = kw
    return spec, info


# ---------------------------------------------------------------- mesh size and counts


def _size(r: np.ndarray, z: np.ndarray, p: dict) -> np.ndarray:
    """The mesh-size field of :func:`fem_reference.model.mesh._generate` at radius r, depth z."""
    scale = 1.0
    if p["r_fine"] is not None and p["r_fine"] < p["r_ref"]:
        scale = np.maximum(1.0, np.hypot(r, z) / p["r_fine"])
    inner = p["h"] * scale
    if p["h_surface"] is not None and p["h_surface"] < p["h"]:
        inner = np.minimum(inner, p["h_surface"] * scale + SURFACE_GRADING * z)
    d = np.hypot(np.maximum(r - p["r_ref"], 0.0), np.maximum(z - p["z_ref"], 0.0))
    return np.minimum(inner + p["grading"] * d, p["h_max"])


def _rule(end: float, zone: float, p: dict, extra: tuple[float, ...] = ()
          ) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on [0, end]: panels split at ``zone``, ``extra``
    and geometrically beyond ``zone`` on the scale h/grading up to where the size reaches
    h_max."""
    h, g = p["h"], p["grading"]
    reach = min(max(p["h_max"] - h, 0.0) / g, max(end - zone, 0.0))
    cuts = {0.0, end, min(zone, end), min(zone + reach, end)}
    cuts.update(e for e in extra if 0.0 < e < end)
    if reach > 0:
        ratio = max(2.0, (g * reach / h) ** (1.0 / _PANELS_MAX)) if h > 0 else 2.0
        d = h / g
        while d < reach:
            cuts.add(zone + d)
            d *= ratio
    cuts = sorted(c for c in cuts if math.isfinite(c))
    x, w = _GAUSS
    nodes, weights = [], []
    for a, b in zip(cuts[:-1], cuts[1:], strict=True):
        if b > a:
            nodes.append(a + (b - a) * (x + 1.0) / 2.0)
            weights.append((b - a) / 2.0 * w)
    return np.concatenate(nodes), np.concatenate(weights)


_SECTORS = {"quarter": 1.0, "half": 2.0, "full": 4.0}
FREE = {"quarter": 0.925, "half": 0.955, "full": 0.985}  # free DOFs / 3 nodes (supports)


def _arc(r: np.ndarray, L: float, shape: str) -> np.ndarray:
    """Length of the circle of radius r inside the block's section (|x|, |y| <= L,
    restricted by the symmetry planes)."""
    theta = np.full_like(r, math.pi / 2)
    out = r > L
    theta[out] = math.pi / 2 - 2.0 * np.arccos(np.minimum(L / r[out], 1.0))
    return r * np.maximum(theta, 0.0) * _SECTORS[shape]


def _surface_layer(p: dict) -> tuple[float, ...]:
    """Depths that split the refined surface layer (``h_surface``) into panels."""
    hs, h = p["h_surface"], p["h"]
    if hs is None or hs >= h:
        return ()
    depth = (h - hs) / SURFACE_GRADING
    return tuple(depth * k / 4.0 for k in range(1, 5))


def element_count(p: dict) -> float:
    """Tetrahedra of the block mesh of parameters ``p`` (a MeshSpec's fields):
    ``∫ dV / (C_TET size³)``."""
    L, H = p["L"], p["H"]
    fine = (p["r_fine"],) if p["r_fine"] else ()
    r, wr = _rule(math.sqrt(2.0) * L, p["r_ref"], p, (L, *fine))
    z, wz = _rule(H, p["z_ref"], p, (*fine, *_surface_layer(p)))
    R, Z = np.meshgrid(r, z, indexing="ij")
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        density = _arc(R, L, p["shape"]) / _size(R, Z, p) ** 3
        return _finite_or_inf(float(wr @ density @ wz) / C_TET)


def surface_facets(p: dict, r_c: float) -> float:
    """Top-surface triangles within radius r_c: ``∫ dA / (C_TRI size²)``."""
    fine = (p["r_fine"],) if p["r_fine"] else ()
    r, w = _rule(r_c, r_c, p, fine)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        area = _finite_or_inf(float(w @ (r / _size(r, np.zeros_like(r), p) ** 2)))
    return area * _SECTORS[p["shape"]] * math.pi / 2 / C_TRI


# ---------------------------------------------------------------- the estimate


@dataclass(frozen=True)
class Breakdown:
    """The sizes and the memory [bytes] and time [s] terms of an estimate."""

    tets: float
    dofs: float  # free DOFs n
    surface_dofs: float  # condensed DOFs m
    contact_dofs: float  # DOFs in contact at the largest contact, A
    memory: dict  # part -> bytes, alive together at the peak
    seconds: dict  # stage -> seconds

    @property
    def peak(self) -> float:
        return sum(self.memory.values())

    @property
    def total_seconds(self) -> float:
        return sum(self.seconds.values())


def contact_solves(case: Case, law: str) -> tuple[float, int, int]:
    """(contact solves, Newton iterations per solve, output steps) of the load path
    (:mod:`fem_reference.loading`).  The normal load increments of dissimilar materials
    count by their contact size: the one of radius r a (:func:`cases.steps.normal_fractions`,
    the load fraction r³) has A³ ∝ r⁶."""
    if case.kind == "sliding_wear" and case.sliding_wear is not None:
        sw = case.sliding_wear
        n = sliding_steps(sw)
        return n + 1, ITERATIONS["wear"], len(sliding_outputs(sw))
    if case.kind == "fretting" and case.fretting is not None and law == "friction":
        fr = case.fretting
        n_sim = fr.simulated_cycles
        per_step = 2 if max(case.a.i1, case.a.i2, case.b.i1, case.b.i2) > 0 else 1
        loading = max(fr.steps_per_cycle // 4, 1)
        return (1 + loading + n_sim * fr.steps_per_cycle * per_step, ITERATIONS["friction"],
                len(fretting_outputs(fr)))
    if law != "friction":
        return 1, ITERATIONS["single"], 1
    n_normal = 1.0 if case.identical_materials else sum(
        f ** (6.0 / (3 if case.load.P is not None else 2)) for f in normal_fractions(case))
    n_tangential = 5 if case.load.tangential_mode in ("load", "shift") else 0
    return n_normal + n_tangential, ITERATIONS["friction"], 1


def breakdown(case: Case) -> Breakdown:
    """Sizes and cost terms of ``case`` on the FEM reference (module doc)."""
    with np.errstate(over="ignore", invalid="ignore"):  # a hostile h overflows to inf
        return _breakdown(case)


def _breakdown(case: Case) -> Breakdown:
    _, info = mesh_spec(case)
    p = info["params"]
    tets = np.float64(element_count(p))
    nodes = 1.35 * tets + 4.5 * tets ** (2.0 / 3.0)
    n = 3.0 * nodes * FREE[p["shape"]]
    facets = np.float64(surface_facets(p, info["r_cond"]))
    m = len(info["comps"]) * (2.0 * facets + 2.5 * np.sqrt(facets))
    A = m * min(1.0, (info["a_max"] / info["r_cond"]) ** 2)
    n_nu = len(info["nus"])
    n_factors = n_nu * (2 if info["companion"] else 1)  # a companion: one more, not condensed
    memory = {
        "mesh": BASE_BYTES + BYTES_PER_TET * tets,
        "factors": FACTOR_BYTES_PER_DOF * n ** (4.0 / 3.0) * n_factors,
        "dense": DENSE_COPIES * 8.0 * m * m,
    }
    solves, iterations, outputs = contact_solves(case, info["law"])
    coupled = COUPLED_SOLVES if coupled_friction(case) else 1.0
    seconds = {
        "base": SECONDS_BASE,
        "mesh": SECONDS_PER_TET_MESH * tets,
        "assembly": n_nu * SECONDS_PER_TET_ASSEMBLY * tets,
        "factorisation": n_factors * SECONDS_FACTOR * n * n,
        "condensation": n_nu * SECONDS_SCHUR * m**3,
        "setup": SECONDS_SETUP * m**1.5,
        "contact": coupled * solves * (
            SECONDS_SEMISMOOTH[solve_kind(case, info["law"])] * semismooth_factor(case) * m * A
            if case.fem.contact == "semismooth"
            else iterations * (SECONDS_CONTACT * A**3 + SECONDS_CONTACT_M2 * m * m)),
        "output": SECONDS_OUTPUT * outputs,
    }
    return Breakdown(tets=float(tets), dofs=float(n), surface_dofs=float(m),
                     contact_dofs=float(A),
                     memory={k: _finite_or_inf(v) for k, v in memory.items()},
                     seconds={k: _finite_or_inf(v) for k, v in seconds.items()})


def solve_kind(case: Case, law: str) -> str:
    """The key of :data:`SECONDS_SEMISMOOTH`: the contact law, fretting apart."""
    return "fretting" if case.kind == "fretting" and law == "friction" else law


def coupled_friction(case: Case) -> bool:
    """Friction between dissimilar materials (:data:`COUPLED_SOLVES`)."""
    return not case.identical_materials and case.friction.mu1 > 0.0


def semismooth_factor(case: Case) -> float:
    """:data:`PARTIAL_SLIP_SOLVES` for fretting in partial slip, else 1.  The regime is
    Mindlin's: partial slip while the amplitude is below the shift of full slip
    δ* = 3 μ P / (16 a) Σ (2 − ν_i) / G_i (Hertz's P and a at the held load or approach;
    μ the friction along the path, the radius of the friction ellipse in its direction)."""
    fr = case.fretting
    if case.kind != "fretting" or fr is None:
        return 1.0
    f = case.friction
    theta = math.radians(case.load.slide_angle - f.beta)
    if min(f.mu1, f.mu2) <= 0:
        return 1.0
    mu = 1.0 / math.hypot(math.cos(theta) / f.mu1, math.sin(theta) / f.mu2)
    a0, p0 = case.hertz_scales
    P = 2.0 * math.pi * a0 * a0 * p0 / 3.0
    compliance = sum((2.0 - b.nu) * 2.0 * (1.0 + b.nu) / b.E for b in (case.a, case.b))
    delta_star = 3.0 * mu * P / (16.0 * a0) * compliance
    return PARTIAL_SLIP_SOLVES if fr.amplitude < delta_star else 1.0


def _finite_or_inf(value: float) -> float:
    """NaN (an overflow met a zero weight) counts as infinite: beyond every limit."""
    return math.inf if math.isnan(value) else float(value)


def _with(case: Case, key: str, factor: float) -> Case:
    """``case`` with the numeric ``key`` (fem.*, sliding_wear.* or fretting.*)
    multiplied (an integer key stays an integer)."""
    section, name = key.split(".")
    sub = getattr(case, section)
    value = getattr(sub, name) * factor
    if isinstance(getattr(sub, name), int):
        value = int(round(value))
    return dataclasses.replace(case, **{section: dataclasses.replace(sub, **{name: value})})


def _drivers(case: Case, base: Breakdown) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(memory keys, time keys): the keys whose refinement (fem.h halved, the block,
    its depth or the sliding distance doubled, the wear step halved) raises the estimate
    by 10 % or more, the strongest first.  An estimate beyond floating point (inf) names
    the fem keys whose default value brings it back, the cheapest first."""
    if not (math.isfinite(base.peak) and math.isfinite(base.total_seconds)):
        default = FemSettings()
        found = []
        for key in ("fem.h", "fem.block", "fem.depth"):
            name = key.split(".")[1]
            b = breakdown(dataclasses.replace(case, fem=dataclasses.replace(
                case.fem, **{name: getattr(default, name)})))
            if math.isfinite(b.peak):
                found.append((b.peak, key))
        keys = tuple(k for _, k in sorted(found)) or ("fem.h", "fem.block", "fem.depth")
        return keys, keys
    moves = [("fem.h", 0.5), ("fem.block", 2.0), ("fem.depth", 2.0)]
    if case.fem.h_surface is not None:
        moves.append(("fem.h_surface", 0.5))
    if case.kind == "sliding_wear" and case.sliding_wear is not None:
        moves += [("sliding_wear.distance", 2.0), ("sliding_wear.step", 0.5)]
    if case.kind == "fretting" and case.fretting is not None:
        moves += [("fretting.cycles", 2.0), ("fretting.steps_per_cycle", 2.0)]
    mem, sec = {}, {}
    for key, factor in moves:
        b = breakdown(_with(case, key, factor))
        mem[key] = b.peak / base.peak
        sec[key] = b.total_seconds / base.total_seconds

    def ranked(ratios: dict) -> tuple[str, ...]:
        keys = [k for k in ratios if not ratios[k] < 1.1]  # NaN (inf/inf) counts
        keys.sort(key=lambda k: -ratios[k] if math.isfinite(ratios[k]) else -math.inf)
        return tuple(keys) or ("fem.h",)

    return ranked(mem), ranked(sec)


def estimate(case: Case) -> Cost:
    """Peak memory [bytes] and wall time [s] of :func:`fem_reference.solve` on ``case``
    (a cold run: mesh, factorisation and condensation included; module doc)."""
    b = breakdown(case)
    memory_keys, time_keys = _drivers(case, b)
    return Cost(memory=b.peak, seconds=b.total_seconds, memory_keys=memory_keys,
                time_keys=time_keys, time_factor=TIME_FACTOR)
