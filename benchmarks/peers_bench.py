"""Side-by-side benchmark of the half-space solver against Tamaas (when it is installed).

    pip install -e ".[peers]"        # optional: Tamaas 2.9.0, the peer code
    python benchmarks/peers_bench.py [--problems hertz mindlin vm] [--sizes N ...]
                                     [--repeat 3] [--out benchmarks/README.md]

The same problems on the same grid, for both codes: steel on steel (E = 210000 MPa,
nu = 0.3 both bodies), sphere R = 50 mm, P = 10.2 N, a square grid of side 1.6 mm
centred on the contact, n^2 cells, the profile sampled on the cell centres.

- ``hertz`` (n = 512, 1024): frictionless normal contact.  This project against Tamaas's
  PolonskyKeerRey with the non-periodic DC-FFT operator and with its default periodic
  operator; both stop at a relative complementarity residual of 1e-10.  Accuracy:
  p_max / p0 - 1 against Hertz and the total force against P.
- ``mindlin`` (n = 256, 512): Cattaneo-Mindlin partial slip, Q = mu P / 2, mu = 0.3.
  This project (normal step, then one tangential step under Q) against Tamaas's
  PolonskyKeerTan, which solves both at once (``solve([Q/L^2, 0, P/L^2])``, mean tractions).
  Tamaas models one elastic half-space under a rigid indenter; with nu = 0.3 its normal
  and tangential problems would be coupled, unlike two identical steels, so it gets
  nu = 0.5 and E = 0.75 E* (the same E*, no coupling): the same problem, whose traction
  (Mindlin's) does not depend on the tangential compliance.  Its surface_2d model is
  periodic only.  The error measure of PolonskyKeerTan levels off at a non-zero value in
  partial slip (about 1.2e-11 here, at every grid), so its tolerance cannot stop it: it
  runs a fixed budget of iterations (:func:`pkt_budget`): 800 up to 256^2, 1000 above.
  Measured at 128^2, 256^2 and 512^2 with 1000, its forces then match P and Q to 1e-5
  and its traction no longer changes; 800 were enough at 128^2 and 256^2, 500 left Q
  4e-4 short at 512^2.  Accuracy:
  relative L2 and max (in mu p0) of p_x - q against Mindlin's q(r), and the force
  errors of P and Q.
- ``vm`` (n = 256, this project only): the sigma_VM block of 64 layers to 0.3 mm under
  the Hertz contact; accuracy: its maximum against 0.6200 p0.

Each measurement is a fresh Python process running this file with ``--worker``; it
prints a JSON line with its in-process solve time (model and kernels built, solved;
imports excluded), iterations and peak RSS (getrusage of itself), and saves its
tractions, whose accuracy the parent computes (outside the timed process: checking
against the closed forms is neither code's work).  The parent
measures the whole process: wall time around it, CPU time (user + system) from the
RUSAGE_CHILDREN deltas.  The codes alternate within each repetition (project, Tamaas,
project, Tamaas, ...) and the table gives the median of the repetitions, with the
ratios project / Tamaas of the wall and CPU times.  OMP_NUM_THREADS=1 for both.  With
``--out`` the table is written into that file between the markers below (appended if
they are absent).  Without Tamaas the project's half runs alone.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import os
import platform
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from importlib.util import find_spec
from pathlib import Path
from typing import Any

import numpy as np

E, NU, R, P, L, MU = 210000.0, 0.3, 50.0, 10.2, 1.6, 0.3
Q = 0.5 * MU * P
TOL = 1e-10  # relative complementarity residual, both codes (normal contact)
PKT_ITERATIONS = 1000  # PolonskyKeerTan's iteration budget above 256^2 (see the docstring)
PKT_ITERATIONS_SMALL = 800  # ... and up to 256^2, where 800 suffice
PKT_NU = 0.5  # decouples Tamaas's normal and tangential problems, as K = 0 does here
VM_DEPTH, VM_LAYERS = 0.3, 64

SIZES = {"hertz": (512, 1024), "mindlin": (256, 512), "vm": (256,)}
CODES = {"hertz": ("project", "tamaas-dcfft", "tamaas-periodic", "contactmechanics"),
         "mindlin": ("project", "tamaas-pkt"), "vm": ("project",)}
PEERS = {"contactmechanics": "ContactMechanics, FreeFFT (non-periodic)",
         "tamaas-dcfft": "Tamaas PKR, DC-FFT (non-periodic)",
         "tamaas-periodic": "Tamaas PKR, periodic", "tamaas-pkt": "Tamaas PKT, periodic"}
BEGIN, END = "<!-- peers-bench:begin -->", "<!-- peers-bench:end -->"
ITER_LINE = re.compile(r"^\s*(\d+)\s+\S+\s+\S+\s*$", re.M)

Row = dict[str, Any]


# ----------------------------------------------------------------- closed forms
def e_star() -> float:
    """Composite modulus of two identical bodies, E / (2 (1 - nu^2))."""
    return E / (2.0 * (1.0 - NU**2))


def hertz_ref() -> tuple[float, float]:
    """Hertz contact radius a and peak pressure p0 for P."""
    from analytic.hertz import hertz

    h = hertz(P, R, e_star())
    return h.a, h.p0


def cell_centres(n: int) -> np.ndarray:
    """Cell-centre coordinates of n cells on [-L/2, L/2]."""
    return (np.arange(n) + 0.5) * (L / n) - 0.5 * L


def radius2(n: int) -> np.ndarray:
    """r^2 on the n x n cell centres (indexing 'ij')."""
    x = cell_centres(n)
    X, Y = np.meshgrid(x, x, indexing="ij")
    return X**2 + Y**2


def normal_accuracy(p_n: np.ndarray) -> Row:
    """p_max / p0 - 1 and the relative error of the total force against P."""
    _, p0 = hertz_ref()
    force = float(p_n.sum()) * (L / p_n.shape[0]) ** 2
    return {"p_max_err": float(p_n.max() / p0 - 1.0), "force_err": abs(force / P - 1.0)}


def traction_accuracy(p_n: np.ndarray, p_x: np.ndarray) -> Row:
    """Normal accuracy plus p_x against Mindlin's q(r): relative L2, max in mu p0, and
    the force error of Q (the larger of the P and Q errors is ``force_err``)."""
    from analytic.mindlin import stick_radius, traction

    a, p0 = hertz_ref()
    q = traction(np.sqrt(radius2(p_x.shape[0])), a, stick_radius(a, Q, MU, P), MU, p0)
    out = normal_accuracy(p_n)
    q_err = abs(float(p_x.sum()) * (L / p_x.shape[0]) ** 2 / Q - 1.0)
    out.update(force_err=max(out["force_err"], q_err),
               px_l2=float(np.linalg.norm(p_x - q) / np.linalg.norm(q)),
               px_max=float(np.abs(p_x - q).max() / (MU * p0)))
    return out


# ----------------------------------------------------------------- this project
def _project_case(problem: str, n: int):
    from cases import load_case

    if problem == "mindlin":
        over = {"grid.nx": n, "grid.ny": n, "grid.Lx": L, "grid.Ly": L, "load.Qx": Q}
        return load_case("cattaneo_mindlin", overrides=over)[0]
    return load_case("hertz", overrides={"grid.nx": n, "grid.ny": n})[0]


def project_hertz(n: int) -> Row:
    from halfspace.problem import contact_solver, profile

    case = _project_case("hertz", n)
    t0 = time.perf_counter()
    sol = contact_solver(case).solve(profile(case), P=case.load.P)
    solve_s = time.perf_counter() - t0
    return {"solve_s": solve_s, "iterations": sol.iterations, "p_n": sol.state.p_n}


def project_mindlin(n: int) -> Row:
    from halfspace.problem import contact_solver, profile

    case = _project_case("mindlin", n)
    t0 = time.perf_counter()
    solver, h = contact_solver(case), profile(case)
    s1 = solver.solve(h, P=P)
    s2 = solver.solve(h, P=P, Q=(Q, 0.0), prev=s1.state)  # one step: exact for K = 0
    solve_s = time.perf_counter() - t0
    return {"solve_s": solve_s, "iterations": s1.iterations + s2.iterations,
            "p_n": s2.state.p_n, "p_x": s2.state.p_x}


def project_vm(n: int) -> Row:
    from halfspace.problem import contact_solver, profile
    from halfspace.stresses import StressEvaluator

    case = _project_case("hertz", n)
    st = contact_solver(case).solve(profile(case), P=case.load.P).state
    t0 = time.perf_counter()
    ev = StressEvaluator(case.grid, np.linspace(0.0, VM_DEPTH, VM_LAYERS), case.b.nu, "b")
    vm = ev.block(st.p_x, st.p_y, st.p_n)["vm"]
    solve_s = time.perf_counter() - t0
    return {"solve_s": solve_s, "iterations": 0, "vm_max": float(vm.max())}


# ----------------------------------------------------------------- Tamaas
def _iterations(log: str) -> int:
    """The last iteration number in a Tamaas solver's log (its dump lines)."""
    found = [int(m) for m in ITER_LINE.findall(log)]
    return max(found) if found else -1


def _run_quiet(solve: Callable[[], object]) -> int:
    """Run a Tamaas solve with its log captured (PolonskyKeerRey writes it to sys.stderr,
    PolonskyKeerTan to file descriptor 2); return the number of iterations it reports."""
    log = io.StringIO()
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile() as raw:
        os.dup2(raw.fileno(), 2)
        try:
            with contextlib.redirect_stderr(log):
                solve()
        finally:
            os.dup2(saved, 2)
            os.close(saved)
        raw.seek(0)
        text = raw.read().decode(errors="replace")
    return _iterations(log.getvalue() + "\n" + text)


def contactmechanics_hertz(n: int) -> Row:
    """ContactMechanics's Polonsky–Keer solve (``NonSmoothContactSystem.minimize_proxy``)
    on its zero-padded free half-space, to a penetration of TOL times the profile's
    range (its tolerance is a length)."""
    from ContactMechanics import FreeFFTElasticHalfSpace
    from ContactMechanics.Systems import NonSmoothContactSystem
    from SurfaceTopography import Topography

    heights = -radius2(n) / (2.0 * R)
    t0 = time.perf_counter()
    system = NonSmoothContactSystem(
        substrate=FreeFFTElasticHalfSpace((n, n), e_star(), (L, L)),
        surface=Topography(heights, (L, L), periodic=False))
    res = system.minimize_proxy(external_force=P, pentol=TOL * float(np.ptp(heights)))
    solve_s = time.perf_counter() - t0
    return {"solve_s": solve_s, "iterations": int(res.nit),
            "p_n": np.asarray(res.jac, dtype=float) / (L / n) ** 2}


def tamaas_hertz(n: int, periodic: bool) -> Row:
    import tamaas as tm

    surface = -radius2(n) / (2.0 * R)
    t0 = time.perf_counter()
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [L, L], [n, n])
    model.E, model.nu = E / 2.0, NU  # E / (1 - nu^2) = E*
    solver = tm.PolonskyKeerRey(model, surface, TOL)
    if not periodic:
        tm.ModelFactory.registerNonPeriodic(model, "dcfft")
        solver.setIntegralOperator("dcfft")
    solver.max_iter, solver.dump_freq = 20000, 1
    iters = _run_quiet(lambda: solver.solve(P / L**2))  # mean pressure
    solve_s = time.perf_counter() - t0
    return {"solve_s": solve_s, "iterations": iters,
            "p_n": np.array(model.traction).reshape(n, n)}


def pkt_budget(n: int) -> int:
    """PolonskyKeerTan's iteration budget on n^2 cells (the smallest measured to leave
    its traction unchanged)."""
    return PKT_ITERATIONS_SMALL if n <= 256 else PKT_ITERATIONS


def tamaas_mindlin(n: int, iterations: int = PKT_ITERATIONS) -> Row:
    import tamaas as tm

    surface = -radius2(n) / (2.0 * R)
    t0 = time.perf_counter()
    model = tm.ModelFactory.createModel(tm.model_type.surface_2d, [L, L], [n, n])
    model.E, model.nu = e_star() * (1.0 - PKT_NU**2), PKT_NU
    solver = tm.PolonskyKeerTan(model, surface, 0.0, MU)  # tolerance never met: budget
    solver.max_iter, solver.dump_freq = iterations, 1
    iters = _run_quiet(lambda: solver.solve([Q / L**2, 0.0, P / L**2]))  # mean tractions
    solve_s = time.perf_counter() - t0
    t = np.array(model.traction)
    return {"solve_s": solve_s, "iterations": iters, "p_n": t[..., 2], "p_x": t[..., 0]}


# ----------------------------------------------------------------- worker
def run_worker(code: str, problem: str, n: int, fields: Path) -> Row:
    """One measurement in this process: solve time, iterations, peak RSS; the tractions
    go to ``fields`` (.npz) so that their accuracy is computed outside the timed
    process (neither code's work)."""
    runners: dict[tuple[str, str], Callable[[int], Row]] = {
        ("project", "hertz"): project_hertz,
        ("project", "mindlin"): project_mindlin,
        ("project", "vm"): project_vm,
        ("tamaas-dcfft", "hertz"): lambda k: tamaas_hertz(k, periodic=False),
        ("tamaas-periodic", "hertz"): lambda k: tamaas_hertz(k, periodic=True),
        ("tamaas-pkt", "mindlin"): lambda k: tamaas_mindlin(k, pkt_budget(k)),
        ("contactmechanics", "hertz"): contactmechanics_hertz,
    }
    if (code, problem) not in runners:
        raise ValueError(f"no {code!r} run of problem {problem!r}")
    row = runners[code, problem](n)
    np.savez(fields, **{k: row.pop(k) for k in ("p_n", "p_x") if k in row})
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    return {"code": code, "problem": problem, "n": n, **row, "peak_mb": peak}


def accuracy(row: Row, fields: Path) -> Row:
    """The closed-form errors of a worker's result (in the parent)."""
    if row["problem"] == "vm":
        from analytic.hertz import axis_vm_max

        _, p0 = hertz_ref()
        return {"vm_max_err": row.pop("vm_max") / (axis_vm_max(NU)[0] * p0) - 1.0}
    with np.load(fields) as f:
        if "p_x" in f.files:
            return traction_accuracy(f["p_n"], f["p_x"])
        return normal_accuracy(f["p_n"])


def evaluate(code: str, problem: str, n: int, fields: Path) -> Row:
    """:func:`run_worker` in this process, with its accuracy."""
    row = run_worker(code, problem, n, fields)
    row.update(accuracy(row, fields))
    return row


def measure(code: str, problem: str, n: int) -> Row:
    """Run one worker process; add its whole-process wall and CPU times."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    with tempfile.TemporaryDirectory() as tmp:
        fields = Path(tmp) / "fields.npz"
        cmd = [sys.executable, str(Path(__file__).resolve()), "--worker", code, problem,
               str(n), str(fields)]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        out = subprocess.run(cmd, capture_output=True, text=True, env=env, check=False)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if out.returncode:
            raise RuntimeError(f"{code} {problem} {n}: worker failed\n{out.stderr[-2000:]}")
        line = [s for s in out.stdout.splitlines() if s.startswith("{")][-1]
        row = json.loads(line)
        row.update(accuracy(row, fields))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {**row, "wall_s": wall, "cpu_s": cpu}


# ----------------------------------------------------------------- parent
def have_tamaas() -> bool:
    return find_spec("tamaas") is not None


def installed(code: str) -> bool:
    """Whether the package of ``code`` is importable (this project's always is)."""
    if code == "contactmechanics":
        return find_spec("ContactMechanics") is not None
    return code == "project" or have_tamaas()


def codes_for(problem: str, peers: bool) -> tuple[str, ...]:
    return tuple(c for c in CODES[problem] if c == "project" or peers and installed(c))


def median_row(runs: list[Row]) -> Row:
    """The median of every numeric field over the repetitions of one measurement."""
    row = dict(runs[0])
    for key, value in runs[0].items():
        if isinstance(value, int | float) and not isinstance(value, bool):
            row[key] = statistics.median(r[key] for r in runs)
    row["repeats"] = len(runs)
    return row


def bench(problems: list[str], sizes: list[int] | None, repeat: int, peers: bool,
          log: Callable[[str], None] = print) -> list[Row]:
    """All measurements, the codes alternating within each repetition; medians."""
    rows = []
    for problem in problems:
        codes = codes_for(problem, peers)
        for n in sizes or SIZES[problem]:
            runs: dict[str, list[Row]] = {c: [] for c in codes}
            for rep in range(repeat):
                for code in codes:
                    runs[code].append(measure(code, problem, n))
                    r = runs[code][-1]
                    log(f"[{rep + 1}/{repeat}] {problem} {n}^2 {code}: wall {r['wall_s']:.2f} s,"
                        f" cpu {r['cpu_s']:.2f} s, solve {r['solve_s']:.2f} s,"
                        f" {r['iterations']} it")
            rows += [median_row(runs[c]) for c in codes]
    return rows


def _fmt(value: float | None, spec: str) -> str:
    return "—" if value is None or not math.isfinite(value) else format(value, spec)


def _ratios(row: Row, base: Row | None) -> tuple[str, str]:
    if base is None or row["code"] == "project":
        return "—", "—"
    return (_fmt(base["wall_s"] / row["wall_s"], ".2f"), _fmt(base["cpu_s"] / row["cpu_s"], ".2f"))


def peer_table(rows: list[Row]) -> str:
    """Markdown table of the hertz / mindlin rows, ratios project / peer."""
    head = ("| problem | grid | code | wall [s] | CPU [s] | solve [s] | iterations | "
            "peak RSS [MB] | p_max/p0 − 1 | force err | p_x L2 | p_x max/(μ p0) | "
            "wall ratio | CPU ratio |\n|" + "---|" * 14 + "\n")
    base = {(r["problem"], r["n"]): r for r in rows if r["code"] == "project"}
    lines = []
    for r in rows:
        wr, cr = _ratios(r, base.get((r["problem"], r["n"])))
        lines.append(
            f"| {r['problem']} | {r['n']}² | {PEERS.get(r['code'], 'this project')} | "
            f"{r['wall_s']:.2f} | {r['cpu_s']:.2f} | {r['solve_s']:.2f} | "
            f"{r['iterations']:.0f} | {r['peak_mb']:.0f} | {_fmt(r['p_max_err'], '+.2e')} | "
            f"{_fmt(r['force_err'], '.1e')} | {_fmt(r.get('px_l2'), '.2e')} | "
            f"{_fmt(r.get('px_max'), '.2e')} | {wr} | {cr} |\n")
    return head + "".join(lines)


def vm_table(rows: list[Row]) -> str:
    head = ("| measurement | grid | wall [s] | CPU [s] | block [s] | peak RSS [MB] | "
            "σ_VM max / 0.6200 p0 − 1 |\n|---|---|---|---|---|---|---|\n")
    return head + "".join(
        f"| σ_VM block, {VM_LAYERS} layers (this project) | {r['n']}² | {r['wall_s']:.2f} | "
        f"{r['cpu_s']:.2f} | {r['solve_s']:.2f} | {r['peak_mb']:.0f} | "
        f"{r['vm_max_err']:+.2e} |\n" for r in rows)


def report(rows: list[Row], peers: bool, repeat: int, load: tuple[float, float]) -> str:
    """The text between the markers: a stamp, the tables and the settings."""
    version = "not installed: this project's half only"
    if peers:
        import importlib.metadata as md

        version = md.version("tamaas") if have_tamaas() else "not installed"
        if installed("contactmechanics"):
            version += f", ContactMechanics {md.version('ContactMechanics')}"
    text = (f"Measured {time.strftime('%Y-%m-%d')} on {platform.machine()}, "
            f"{os.cpu_count()} cores, Python {platform.python_version()}, Tamaas {version}; "
            f"OMP_NUM_THREADS=1; median of {repeat} runs, each a fresh process, the codes "
            f"alternating; load average {load[0]:.2f} before, {load[1]:.2f} after.  "
            "wall / CPU: the whole process (start-up and imports included, the check "
            "against the closed forms excluded); solve: in the "
            "process, building the model and kernels included; ratio: this project / peer.\n")
    peer_rows = [r for r in rows if r["problem"] != "vm"]
    vm_rows = [r for r in rows if r["problem"] == "vm"]
    if peer_rows:
        text += "\n" + peer_table(peer_rows)
    if vm_rows:
        text += "\n" + vm_table(vm_rows)
    if peers and any(r["code"] == "tamaas-pkt" for r in rows):
        text += (f"\nTamaas PolonskyKeerTan: surface_2d (periodic only), nu = {PKT_NU}, "
                 f"E = 0.75 E*, a fixed budget of {PKT_ITERATIONS_SMALL} iterations up to 256², "
                 f"{PKT_ITERATIONS} above (its error "
                 "measure levels off above zero in partial slip).  Tolerances: 1e-10 for "
                 "this project and PolonskyKeerRey.\n")
    return text


def write_between_markers(path: Path, text: str) -> None:
    """Put ``text`` between the markers in ``path``: replace the block, else append it."""
    doc = path.read_text() if path.exists() else ""
    block = f"{BEGIN}\n{text}{END}"
    if BEGIN in doc and END in doc:
        doc = doc[: doc.index(BEGIN)] + block + doc[doc.index(END) + len(END):]
    else:
        doc = doc + ("\n" if doc and not doc.endswith("\n") else "") + "\n" + block + "\n"
    path.write_text(doc)


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--problems", nargs="+", choices=list(SIZES), default=list(SIZES))
    ap.add_argument("--sizes", type=int, nargs="+",
                    help="grid sizes n for every problem (default: hertz 512 1024, "
                         "mindlin 256 512, vm 256)")
    ap.add_argument("--repeat", type=int, default=3, help="repetitions (median; >= 1)")
    ap.add_argument("--out", type=Path, help="write the table between the markers here")
    ap.add_argument("--worker", nargs=4, metavar=("CODE", "PROBLEM", "N", "FIELDS"),
                    help=argparse.SUPPRESS)
    return ap.parse_args(argv)


def main(argv: list[str] | None = None) -> None:
    args = parse_args(argv)
    if args.worker:
        code, problem, n, fields = args.worker
        print(json.dumps(run_worker(code, problem, int(n), Path(fields))), flush=True)
        return
    peers = any(installed(c) for c in PEERS)
    if not have_tamaas():
        print("Tamaas is not importable (pip install -e \".[peers]\"): running this "
              "project's half only.", flush=True)
    load0 = os.getloadavg()[0]
    rows = bench(args.problems, args.sizes, max(args.repeat, 1), peers,
                 log=lambda s: print(s, flush=True))
    text = report(rows, peers, max(args.repeat, 1), (load0, os.getloadavg()[0]))
    print("\n" + text)
    if args.out:
        write_between_markers(args.out, text)


if __name__ == "__main__":
    main()
