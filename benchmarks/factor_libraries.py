"""The FEM's factorisation and condensation by three sparse libraries, side by side (issue 75).

    python benchmarks/factor_libraries.py                       # the three default points
    python benchmarks/factor_libraries.py --case fretting_orthotropic:2 --rounds 2

For each ``CASE:INDEX`` (quick set-up) the block's stiffness K_ff and its condensed
unknowns s are taken from the FEM as it builds the point (``fem_reference.model.block``),
and the condensed compliance ``C = S⁻¹`` (S the Schur complement of K_ff onto s) is formed
in a fresh process by each library:

- ``pardiso``: the FEM's own :class:`fem_reference.model.elasticity.Factorization`
  (MKL PARDISO's Schur complement mode, then LAPACK's Cholesky inverse);
- ``mumps``: MUMPS's Schur complement (``python-mumps``, ``Context.schur``, METIS), then
  the same inverse;
- ``cholmod``: CHOLMOD's supernodal Cholesky factor (``scikit-sparse``) of K_ff ordered
  with s last (METIS on the other unknowns), whose trailing block is the Cholesky factor
  of S, inverted by LAPACK (potri).

None of the last two is a dependency of the suite: ``pip install python-mumps`` and
``pip install "scikit-sparse<0.5"`` build against Debian's ``libmumps-seq-dev`` and
``libsuitesparse-dev`` (a library that is not importable is left out of the table).
Printed as a Markdown table: the factorisation with the Schur complement, the inverse, the
peak RSS of the process, 32 solves with K_ff where the library keeps a factor of all of it,
the largest difference of C from PARDISO's on every 97th row (relative to max |C|) and a
digest of C (equal digests in two rounds: the same bits in another process).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy.sparse as sp

POINTS = ("cattaneo_mindlin:0", "fretting_orthotropic:0", "fretting_orthotropic:2")
LIBRARIES = {"pardiso": "pypardiso", "mumps": "mumps", "cholmod": "sksparse.cholmod"}
ROWS = 97  # every ROWS-th row of C is compared across libraries


class _Taken(Exception):
    pass


def dump(spec: str, folder: str) -> None:
    """Build ``spec``'s block up to its first condensed factorisation; save K_ff and s."""
    import fem_reference.model.block as block
    import fem_reference.solver as solver
    from cases.loader import load_case

    def take(self, A, partial=None):
        if partial is None:
            raise RuntimeError("the first factorisation has no condensed unknowns")
        sp.save_npz(os.path.join(folder, "A.npz"), sp.csr_matrix(A))
        np.save(os.path.join(folder, "s.npy"), np.asarray(partial))
        raise _Taken

    block.Factorization.__init__ = take
    name, _, index = spec.partition(":")
    case = load_case(name, quick=True)[int(index or 0)]
    try:
        solver.solve(case, vtu=False)
    except _Taken:
        return
    raise RuntimeError(f"{spec}: the FEM built no condensed block")


def _symmetric_from_lower(C: np.ndarray, b: int = 512) -> np.ndarray:
    m = C.shape[0]
    for j0 in range(0, m, b):
        j1 = min(j0 + b, m)
        D = C[j0:j1, j0:j1]
        C[j0:j1, j0:j1] = np.tril(D) + np.tril(D, -1).T
        C[j0:j1, j1:] = C[j1:, j0:j1].T
    return C


def condense(lib: str, A: sp.csr_matrix, s: np.ndarray):
    """``(C, solve or None, t_factor)``: the condensed compliance by library ``lib``."""
    from fem_reference.model.elasticity import Factorization, _spd_inverse

    t0 = time.perf_counter()
    if lib == "pardiso":
        F = Factorization(A, partial=s)
        return F.schur_inverse(), F.solve, time.perf_counter() - t0
    if lib == "mumps":
        import mumps

        ctx = mumps.Context()
        ctx.set_matrix(sp.triu(A, format="coo"), symmetric=True)
        S = np.asfortranarray(ctx.schur(s, ordering="metis"))
        t1 = time.perf_counter()
        return _spd_inverse(S), None, t1 - t0
    from scipy.linalg import lapack
    from sksparse.cholmod import analyze, cholesky

    n = A.shape[0]
    rest = np.setdiff1d(np.arange(n), s)
    order = analyze(A[rest][:, rest].tocsc(), ordering_method="metis").P()
    perm = np.concatenate([rest[order], s])
    f = cholesky(A[perm][:, perm].tocsc(), ordering_method="natural", mode="supernodal")
    t1 = time.perf_counter()
    L_ss = np.asfortranarray(f.L()[n - s.size:, n - s.size:].toarray())  # chol(S)
    C, info = lapack.dpotri(L_ss, lower=1, overwrite_c=1)
    if info:
        raise RuntimeError(f"potri {info}")

    def solve(B):
        X = np.empty_like(B)
        X[perm] = f(B[perm])
        return X

    return _symmetric_from_lower(C), solve, t1 - t0


def one(lib: str, folder: str) -> dict:
    A = sp.load_npz(os.path.join(folder, "A.npz")).tocsr()
    s = np.load(os.path.join(folder, "s.npy"))
    s = np.nonzero(s)[0] if s.dtype == bool else np.unique(s)
    t0 = time.perf_counter()
    C, solve, t_factor = condense(lib, A, s)
    t_c = time.perf_counter() - t0
    row = {"lib": lib, "dofs": A.shape[0], "m": s.size, "factor_schur_s": t_factor,
           "condensed_s": t_c, "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
           "digest": hashlib.sha256(np.ascontiguousarray(C).tobytes()).hexdigest()[:10]}
    picked = np.ascontiguousarray(C[::ROWS])
    ref = os.path.join(folder, "C_pardiso.npy")
    if lib == "pardiso" and not os.path.exists(ref):
        np.save(ref, picked)
    if os.path.exists(ref):
        R = np.load(ref)
        row["dC"] = float(np.max(np.abs(picked - R)) / np.max(np.abs(R)))
    if solve is not None:
        B = np.random.default_rng(0).standard_normal((A.shape[0], 32))
        t1 = time.perf_counter()
        X = solve(B)
        row["solve32_s"] = time.perf_counter() - t1
        row["residual"] = float(np.linalg.norm(A @ X - B) / np.linalg.norm(B))
    return row


def processor() -> str:
    out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
    info = dict(line.split(":", 1) for line in out.splitlines() if ":" in line)
    return f"{info.get('Model name', '?').strip()} ({info.get('Vendor ID', '?').strip()})"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", nargs="*", default=list(POINTS), help="CASE:INDEX, quick set-up")
    ap.add_argument("--lib", nargs="*", help="libraries (default: every importable one)")
    ap.add_argument("--rounds", type=int, default=1, help="rounds, libraries alternating")
    ap.add_argument("--one", nargs=2, help=argparse.SUPPRESS)  # the child: LIB FOLDER
    ap.add_argument("--dump", nargs=2, help=argparse.SUPPRESS)  # the child: SPEC FOLDER
    args = ap.parse_args()
    if args.dump:
        return dump(*args.dump)
    if args.one:
        return print(json.dumps(one(*args.one)))
    from importlib.util import find_spec

    def importable(module: str) -> bool:
        try:
            return find_spec(module) is not None
        except ModuleNotFoundError:
            return False

    libs = args.lib or [k for k, mod in LIBRARIES.items() if importable(mod)]
    print(f"{processor()}, {os.cpu_count()} cores\n")
    head = ["point", "lib", "dofs", "m", "factor_schur_s", "condensed_s", "solve32_s",
            "peak_mb", "dC", "digest"]
    print("| " + " | ".join(head) + " |\n|" + "---|" * len(head))
    for spec in args.case:
        with tempfile.TemporaryDirectory() as folder:
            subprocess.run([sys.executable, __file__, "--dump", spec, folder], check=True,
                           capture_output=True)
            for _ in range(args.rounds):
                for lib in ["pardiso", *(x for x in libs if x != "pardiso")]:
                    out = subprocess.run([sys.executable, __file__, "--one", lib, folder],
                                         capture_output=True, text=True, check=True).stdout
                    r = {"point": spec, **json.loads(out.strip().splitlines()[-1])}
                    print("| " + " | ".join(
                        f"{r[k]:.1e}" if k == "dC" and k in r else
                        f"{r[k]:.1f}" if isinstance(r.get(k), float) else str(r.get(k, ""))
                        for k in head) + " |", flush=True)


if __name__ == "__main__":
    main()
