"""Valid cases a user could write, over the closed forms' domains, as Hypothesis strategies.

Each draw is the text of a case file (so it goes through the loader's validation like a
user's).  The ranges (also in ``benchmarks/README.md``, "False alarms"):

- kinds: Hertz (identical materials, frictionless or with friction and no tangential
  load), Hertz of a dissimilar frictionless pair (either under the load or the approach
  held), Cattaneo–Mindlin partial slip under an oblique tangential load or an oblique
  rigid shift (0.1–0.9 of Mindlin's δ*), full sliding in any direction with isotropic or
  orthotropic friction, the worn pin (Argatov's asymptotic solution) frictionless or with
  isotropic or orthotropic friction, its wear isotropic or orthotropic (i2/i1 0.2–5, the
  axes at any β, sliding in any direction), and the first fretting cycle
  (Mindlin–Deresiewicz) under a held approach, in any direction, its wear orthotropic
  along a principal axis (the closed form's domain; i2/i1 1, or 1.25–5 either way), 1–3
  cycles with cycle 1 an output,
  or a cycle jump of 2 over 4 cycles with orthotropic wear (where the closed form declines
  and the half-space solver's exact relations compare), the transverse motion held or
  free;
- R 5–200 mm, P 1–300 N (log-uniform), E 70–400 GPa, ν −0.3–0.45, μ 0.05–0.8 (sliding)
  or 0.1–0.8, Q/(μP) 0.1–0.9, fretting amplitude 0.2–3 δ*, worn contact radius 1.5–3 a0;
- the grid: 3.5–10 cells per contact radius (the worn radius for a pin), its half-width
  1.3–2.2 contact radii, at most 81 cells a side (odd or even counts), square or
  rectangular (``Ly``, ``ny`` drawn alike: rectangular cells); the stress planes 1.5
  contact radii deep with 11–31 layers, through the centre or through (x0, y0) up to 0.8
  contact radii off it, in body b or body a, ``z_below`` 0.25–1 contact radii or unset;
  the solver's ``method`` (CG or, for the static contacts without sliding, Uzawa's),
  ``tol`` 1e-12–1e-8 (fretting 1e-10–1e-8) and ``max_iter`` 5000–50000, or unset; a
  ``description``.

:func:`fem_case` draws the kinds no closed form covers for the FEM (its variants in its
docstring; ``tests/test_fem_generated_cases.py``, 20 draws in the full tier).

Not drawn, and why: ``name`` (the file stem; a directory name, no physics), ``[fem]``
(it acts on the FEM alone, which runs on the generated cases at its default mesh, the
one a user's case gets), ``[tolerances]`` and ``[not_converged]`` (the
gate's own settings: the false-alarm rate is that of the defaults), ``[sweep]`` and
``[quick]`` (each of their points is a case of the kinds above), ``solver.wear_spread``
(the resolution probe's own setting, which the closed forms decline; its run is drawn by
``tests/test_fem_fretting_worn.py``).
"""

from __future__ import annotations

import math

from hypothesis import assume
from hypothesis import strategies as st

KINDS = ("hertz", "dissimilar", "partial_slip", "sliding", "pin", "fretting")


def _log_uniform(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(math.log(lo), math.log(hi)).map(math.exp)


def hertz_radius(R: float, P: float, a: tuple[float, float], b: tuple[float, float]
                 ) -> float:
    """Hertz's contact radius (3PR / 4E*)^(1/3) of materials a, b = (E, ν)."""
    e_star = 1.0 / ((1 - a[1] ** 2) / a[0] + (1 - b[1] ** 2) / b[0])
    return (3.0 * P * R / (4.0 * e_star)) ** (1.0 / 3.0)


def mindlin_shift(mu: float, P: float, a0: float, mat: tuple[float, float]) -> float:
    """Mindlin's rigid shift at full slip δ* = 3μP(2 − ν)/(8 G a0) of each of two
    identical bodies (E, ν), summed."""
    G = mat[0] / (2 * (1 + mat[1]))
    return 3 * mu * P / (16 * a0) * 2 * (2 - mat[1]) / G


#: the kinds the FEM is drawn on (:func:`fem_case`): those no closed form covers
FEM_KINDS = ("dissimilar", "partial_slip", "sliding", "hertz", "fretting")


def fem_case() -> st.SearchStrategy[str]:
    """A valid case of the kinds no closed form covers, for the FEM (issue 58, point 4):
    dissimilar frictional partial slip under an oblique tangential load, oblique partial
    slip on a rectangular grid, orthotropic sliding at an angle, the approach held with
    the planes off the centre, worn fretting (2–3 cycles, the last one an output, the
    transverse motion held); the ranges otherwise those of :func:`user_case`."""
    return user_case(kinds=FEM_KINDS, fem=True)


@st.composite
def user_case(draw: st.DrawFn, kinds: tuple[str, ...] = KINDS, fem: bool = False) -> str:
    """The text of a valid case file of one of ``kinds`` (module doc); ``fem``: the
    variants of :func:`fem_case`."""
    kind = draw(st.sampled_from(kinds))
    R = draw(_log_uniform(5.0, 200.0))
    P = draw(_log_uniform(1.0, 300.0))
    mat_a = (draw(st.floats(70e3, 400e3)), draw(st.floats(-0.3, 0.45)))
    mat_b = mat_a
    if kind == "dissimilar":
        mat_b = (draw(st.floats(70e3, 400e3)), draw(st.floats(-0.3, 0.45)))
    a0 = hertz_radius(R, P, mat_a, mat_b)
    body_a = body_b = ""
    friction, load, extra = "", f"P = {P!r}\n", ""
    top = 'kind = "static"\n'
    reach = a0
    if kind in ("hertz", "dissimilar") and (fem and kind == "hertz" or draw(st.booleans())):
        load = f"approach = {a0**2 / R!r}\n"  # the approach held
    if fem and kind == "dissimilar":  # frictional partial slip under an oblique load
        mu, q = draw(st.floats(0.1, 0.8)), draw(st.floats(0.1, 0.9))
        angle = draw(st.floats(0.0, 2 * math.pi))
        friction = f"[friction]\nmu = {mu!r}\n"
        load = (f"P = {P!r}\nQx = {q * mu * P * math.cos(angle)!r}\n"
                f"Qy = {q * mu * P * math.sin(angle)!r}\n")
    elif kind == "hertz" and draw(st.booleans()):
        friction = f"[friction]\nmu = {draw(st.floats(0.05, 0.8))!r}\n"
    elif kind == "partial_slip":
        mu, q = draw(st.floats(0.1, 0.8)), draw(st.floats(0.1, 0.9))
        angle = draw(st.floats(0.0, 2 * math.pi))
        friction = f"[friction]\nmu = {mu!r}\n"
        if draw(st.booleans()):  # the tangential load held
            load += (f"Qx = {q * mu * P * math.cos(angle)!r}\n"
                     f"Qy = {q * mu * P * math.sin(angle)!r}\n")
        else:  # a rigid shift, q of Mindlin's full-slip shift δ*
            shift = q * mindlin_shift(mu, P, a0, mat_a)
            load += (f"shift_x = {shift * math.cos(angle)!r}\n"
                     f"shift_y = {shift * math.sin(angle)!r}\n")
    elif kind == "sliding":
        if not fem and draw(st.booleans()):
            friction = f"[friction]\nmu = {draw(st.floats(0.05, 0.8))!r}\n"
        else:
            friction = (f"[friction]\nmu1 = {draw(st.floats(0.05, 0.8))!r}\n"
                        f"mu2 = {draw(st.floats(0.05, 0.8))!r}\n"
                        f"beta = {draw(st.floats(-180.0, 180.0))!r}\n")
        load += f"sliding = true\nslide_angle = {draw(st.floats(-180.0, 180.0))!r}\n"
    elif kind == "pin":
        top = 'kind = "sliding_wear"\n'
        beta = draw(st.floats(-180.0, 180.0))
        friction = draw(st.sampled_from([
            "", f"[friction]\nmu = {draw(st.floats(0.05, 0.8))!r}\nbeta = {beta!r}\n",
            f"[friction]\nmu1 = {draw(st.floats(0.05, 0.8))!r}\n"
            f"mu2 = {draw(st.floats(0.05, 0.8))!r}\nbeta = {beta!r}\n"]))
        if not friction:
            friction = f"[friction]\nbeta = {beta!r}\n"  # the wear axes, frictionless
        reach = draw(st.floats(1.5, 3.0)) * a0  # the worn radius at the end
        distance = 100.0
        # Archard with the pin sliding through: a^4 = a0^4 + 4 i_w P s R / π, and
        # orthotropic wear i_w(θ) = √((i1 cos θ)² + (i2 sin θ)²), θ from e1
        i_w = (reach**4 - a0**4) * math.pi / (4.0 * P * R * distance)
        slide = draw(st.floats(-180.0, 180.0))
        theta = math.radians(slide - beta)
        ratio = draw(st.sampled_from([1.0, draw(_log_uniform(0.2, 5.0))]))  # i2 / i1
        i1 = i_w / math.hypot(math.cos(theta), ratio * math.sin(theta))
        body_a = f"i1 = {i1!r}\ni2 = {ratio * i1!r}\n"
        n_steps = draw(st.integers(20, 40))
        load += f"slide_angle = {slide!r}\n"
        extra = (f"[sliding_wear]\nstep = {distance / n_steps!r}\ndistance = {distance!r}\n"
                 f"output_s = [{distance / 2!r}]\n")
    elif kind == "fretting":
        top = 'kind = "fretting"\n'
        mu = draw(st.floats(0.1, 0.8))
        friction = f"[friction]\nmu = {mu!r}\n"
        approach = a0**2 / R
        load = f"approach = {approach!r}\n"
        delta_star = mindlin_shift(mu, P, a0, mat_a)
        i_w = draw(_log_uniform(1e-10, 1e-8))
        # orthotropic wear along a principal axis (the closed form's domain): β = φ + k 90°
        slide = draw(st.floats(-180.0, 180.0))  # any direction
        beta = slide + 90.0 * draw(st.integers(-2, 2))
        jumped = draw(st.integers(0, 3)) == 0  # a cycle jump: the closed form declines,
        # and the half-space solver's exact relations of orthotropic wear compare it
        orthotropic = draw(_log_uniform(1.25, 5.0)) ** draw(st.sampled_from([1, -1]))
        ratio = orthotropic if jumped else draw(st.sampled_from([1.0, orthotropic]))  # i2/i1
        body_a = body_b = f"i1 = {i_w!r}\ni2 = {ratio * i_w!r}\n"
        friction += f"beta = {beta!r}\n"
        load += f"slide_angle = {slide!r}\n"
        cycles = draw(st.integers(2 if fem else 1, 3))  # the closed form is cycle 1's
        outputs = sorted({1, draw(st.integers(1, cycles))} | ({cycles} if fem else set()))
        jump = ""
        if jumped:
            cycles, outputs = 4, sorted({4, draw(st.sampled_from([2, 4]))})
            jump = "jump = 2.0\n"
        extra = (f"[fretting]\namplitude = {draw(st.floats(0.2, 3.0)) * delta_star!r}\n"
                 f"steps_per_cycle = {draw(st.sampled_from([8, 12, 20]))}\n"
                 f"cycles = {cycles}\n{jump}output_cycles = {outputs}\n"
                 f"transverse = \"{'held' if fem else draw(st.sampled_from(['held', 'free']))}\"\n"
                 f"[solver]\ntol = {draw(_log_uniform(1e-10, 1e-8))!r}\n")
    cells = draw(st.floats(3.5, 10.0))  # cells per contact radius
    L = 2.0 * reach * draw(st.floats(1.3, 2.2))
    n = max(min(round(L / (a0 / cells)), 81), 9)
    grid = f"Lx = {L!r}\nnx = {n}\n"
    if fem and kind == "partial_slip" or draw(st.booleans()):  # a rectangular grid
        Ly = 2.0 * reach * draw(st.floats(1.3, 2.2))
        ny = max(min(round(Ly / (a0 / draw(st.floats(3.5, 10.0)))), 81), 9)
        grid += f"Ly = {Ly!r}\nny = {ny}\n"
    nz = draw(st.integers(11, 31))
    stress = f"depth = {1.5 * reach!r}\nnz = {nz}\n"
    if fem and kind == "hertz" or draw(st.booleans()):  # planes off the centre, inside
        x0, y0 = (draw(st.floats(-0.8, 0.8)) * reach for _ in range(2))
        stress += f"x0 = {x0!r}\ny0 = {y0!r}\n"
    if draw(st.booleans()):
        stress += 'body = "a"\n'
    if draw(st.booleans()):  # the companion's depth set by hand, within the planes
        stress += f"z_below = {draw(st.floats(0.25, 1.0)) * reach!r}\n"
    if kind != "fretting" and draw(st.booleans()):
        method = '"uzawa"' if kind in ("hertz", "dissimilar", "partial_slip") and \
            draw(st.booleans()) else '"cg"'
        extra += (f"[solver]\nmethod = {method}\ntol = {draw(_log_uniform(1e-12, 1e-8))!r}\n"
                  f"max_iter = {draw(st.integers(5000, 50000))}\n")
    if draw(st.booleans()):
        top = f'description = "generated {kind}"\n' + top
    return (top + f"[materials.a]\nE = {mat_a[0]!r}\nnu = {mat_a[1]!r}\n{body_a}"
            f"[materials.b]\nE = {mat_b[0]!r}\nnu = {mat_b[1]!r}\n{body_b}"
            f"[geometry]\nR = {R!r}\n[grid]\n{grid}{friction}"
            f"[load]\n{load}{extra}[stress]\n{stress}")


def dundurs_beta(a: tuple[float, float], b: tuple[float, float]) -> float:
    """Dundurs' β of materials a, b = (E, ν) (docs/formulation.md §2.8)."""
    ga, gb = a[0] / (2 * (1 + a[1])), b[0] / (2 * (1 + b[1]))
    return 0.5 * ((1 - 2 * a[1]) / ga - (1 - 2 * b[1]) / gb) / ((1 - a[1]) / ga
                                                               + (1 - b[1]) / gb)


@st.composite
def compression_case(draw: st.DrawFn, tangential: bool | None = None) -> str:
    """A valid case of frictional contact between dissimilar materials across Dundurs'
    range (issue 73, point 6): |β| ≤ 0.5 through ν of each body −0.9–0.499, the moduli
    70–400 GPa and their ratio 1/1000–1000 (rigid-on-soft pairs both ways; auxetic pairs
    beyond |β| = 0.5 are left out), μ 0.01–1 (log-uniform), R 5–200 mm,
    P 1–300 N; Spence's compression (the normal load or the approach held) or, with
    ``tangential`` (drawn when None), a partial-slip tangential load 0.1–0.9 μP at any
    angle after it, which no closed form covers (the half-space solver's exact relations
    compare it); the grid 4–10 cells per contact radius, its half-width 1.3–2.2 contact
    radii; the stress planes through the centre, 1.5 contact radii deep, in either body."""
    R = draw(_log_uniform(5.0, 200.0))
    P = draw(_log_uniform(1.0, 300.0))
    E_a = draw(st.floats(70e3, 400e3))
    mat_a = (E_a, draw(st.floats(-0.9, 0.499)))
    mat_b = (E_a * draw(_log_uniform(1e-3, 1e3)), draw(st.floats(-0.9, 0.499)))
    assume(abs(dundurs_beta(mat_a, mat_b)) <= 0.5)  # beyond, only auxetic pairs
    a0 = hertz_radius(R, P, mat_a, mat_b)
    mu = draw(_log_uniform(0.01, 1.0))
    load = f"P = {P!r}\n" if draw(st.booleans()) else f"approach = {a0**2 / R!r}\n"
    if tangential is None:
        tangential = draw(st.integers(0, 3)) == 0
    if tangential:
        q, angle = draw(st.floats(0.1, 0.9)), draw(st.floats(0.0, 2 * math.pi))
        load = (f"P = {P!r}\nQx = {q * mu * P * math.cos(angle)!r}\n"
                f"Qy = {q * mu * P * math.sin(angle)!r}\n")
    cells = draw(st.floats(4.0, 10.0))
    L = 2.0 * a0 * draw(st.floats(1.3, 2.2))
    n = max(min(round(L / (a0 / cells)), 81), 9)
    body = draw(st.sampled_from(["a", "b"]))
    return ('kind = "static"\n'
            f"[materials.a]\nE = {mat_a[0]!r}\nnu = {mat_a[1]!r}\n"
            f"[materials.b]\nE = {mat_b[0]!r}\nnu = {mat_b[1]!r}\n"
            f"[geometry]\nR = {R!r}\n[grid]\nLx = {L!r}\nnx = {n}\n"
            f"[friction]\nmu = {mu!r}\n[load]\n{load}"
            f"[stress]\ndepth = {1.5 * a0!r}\nnz = {draw(st.integers(11, 21))}\n"
            f'body = "{body}"\n')
