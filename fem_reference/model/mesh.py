"""Tetrahedral meshes of the elastic block (gmsh), cached on disk by their parameters.

The block occupies ``-H <= Z <= 0`` below its contact surface ``Z = 0`` and
``|X|, |Y| <= L`` (or the quarter ``X, Y >= 0`` / the half ``Y >= 0`` when the case is
symmetric).  Lengths are stored in units of the Hertz radius ``a0`` so one cached mesh
serves every case with the same dimensionless parameters; :func:`block_mesh` scales
them to mm.

The element size is ``h`` inside the refined zone (a cylinder of radius ``r_ref``
around the Z axis, from the surface down to depth ``z_ref``) and grows linearly with
the distance ``d`` from that zone, ``size = h + grading * d``, capped at ``h_max``.
With ``r_fine < r_ref`` (a contact that grows, e.g. by wear) the size inside the zone is
``h`` within the distance ``r_fine`` of the origin and ``h ρ / r_fine`` beyond.  With
``h_surface < h`` the zone is refined further towards the contact surface: its size is
``min(h, h_surface + SURFACE_GRADING |Z|)`` (each scaled by ``max(1, ρ / r_fine)`` as
above), so the contact tractions are resolved at ``h_surface`` while the subsurface
stresses keep ``h`` from the depth ``(h - h_surface) / SURFACE_GRADING`` down.
gmsh runs single-threaded (HXT with several threads is not bit-reproducible).

Cache directory: ``$CONTACT_VV_CACHE/fem-meshes`` if the variable is set, else
``~/.cache/contact-vv/fem-meshes``.  The cache never changes a number: an entry holds
its full key (the parameters, the recipe's version, gmsh's version) and a SHA-256 of
its arrays, both checked when it is read; an entry that fails the check (unreadable,
truncated, another key's, edited) is discarded with one line on stderr and meshed
again.  Entries are written under a temporary name and renamed, so concurrent writers
leave one whole entry; an unwritable cache keeps the mesh in memory and says so.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
from skfem import MeshTet

from cases.result import atomic_path

from ..errors import MeshError

SHAPES = ("quarter", "half", "full")
_MESH_VERSION = 2  # bump when the meshing recipe changes
SURFACE_GRADING = 0.1  # size growth per unit depth below the contact surface (h_surface)


@dataclass(frozen=True)
class MeshSpec:
    """Dimensionless mesh parameters (lengths in units of a0)."""

    shape: str  # 'quarter' (X, Y >= 0), 'half' (Y >= 0) or 'full'
    L: float  # block half-width
    H: float  # block depth
    h: float  # element size in the refined zone
    r_ref: float  # radius of the refined zone
    z_ref: float  # depth of the refined zone
    grading: float = 0.25  # size growth per unit distance from the refined zone
    h_max: float = 4.0  # largest element size
    r_fine: float | None = None  # radius of the h zone (None: r_ref); beyond, h ∝ distance
    h_surface: float | None = None  # element size at the contact surface (None: h)

    def __post_init__(self) -> None:
        if self.shape not in SHAPES:
            raise MeshError(f"mesh shape {self.shape!r}: must be one of {SHAPES}")
        if self.r_fine is not None and not (0 < self.r_fine <= self.r_ref):
            raise MeshError(f"mesh parameter r_fine = {self.r_fine!r}: must lie in (0, r_ref]")
        for key in ("L", "H", "h", "r_ref", "z_ref", "grading", "h_max"):
            value = getattr(self, key)
            if not (np.isfinite(value) and value > 0):
                raise MeshError(f"mesh parameter {key} = {value!r}: must be finite and > 0")
        if self.r_ref >= self.L or self.z_ref >= self.H:
            raise MeshError(
                f"refined zone (r_ref = {self.r_ref}, z_ref = {self.z_ref}) does not fit in the "
                f"block (L = {self.L}, H = {self.H}); enlarge fem.block / fem.depth"
            )
        if self.h_surface is not None and not (0 < self.h_surface <= self.h):
            raise MeshError(f"mesh parameter h_surface = {self.h_surface!r}: must lie in "
                            f"(0, h = {self.h}]")
        if self.h >= self.r_ref:
            raise MeshError(f"element size h = {self.h} must be below r_ref = {self.r_ref}")

    def payload(self) -> str:
        """The full key of the mesh: its parameters, the recipe's version and gmsh's."""
        import gmsh

        fields = asdict(self)
        if fields["h_surface"] is None:  # the meshes cached before the key existed
            del fields["h_surface"]
        else:
            fields["surface_grading"] = SURFACE_GRADING
        return json.dumps(
            {**fields, "version": _MESH_VERSION, "gmsh": gmsh.__version__}, sort_keys=True
        )

    def key(self) -> str:
        """The cache entry's name: a digest of :meth:`payload`."""
        return hashlib.sha256(self.payload().encode()).hexdigest()[:20]


def cache_dir() -> Path:
    root = os.environ.get("CONTACT_VV_CACHE")
    base = Path(root) if root else Path.home() / ".cache" / "contact-vv"
    return base / "fem-meshes"


def _generate(spec: MeshSpec) -> tuple[np.ndarray, np.ndarray]:
    """Run gmsh; return (points (3, n), tets (4, m)) in units of a0."""
    import gmsh

    x0 = 0.0 if spec.shape == "quarter" else -spec.L
    y0 = -spec.L if spec.shape == "full" else 0.0
    # Distance from the refined cylinder; gmsh's MathEval parser knows Sqrt and Max.
    dist = (
        f"Sqrt(Max(Sqrt(x*x + y*y) - {spec.r_ref!r}, 0)^2 + Max(-z - {spec.z_ref!r}, 0)^2)"
    )
    scale = ""
    if spec.r_fine is not None and spec.r_fine < spec.r_ref:
        scale = f" * Max(1, Sqrt(x*x + y*y + z*z) / {spec.r_fine!r})"
    inner = f"{spec.h!r}{scale}"
    if spec.h_surface is not None and spec.h_surface < spec.h:
        inner = f"Min({inner}, {spec.h_surface!r}{scale} + {SURFACE_GRADING!r} * Max(-z, 0))"
    size = f"Min({inner} + {spec.grading!r} * {dist}, {spec.h_max!r})"
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.option.setNumber("Mesh.MaxNumThreads3D", 1)
        gmsh.option.setNumber("Mesh.RandomSeed", 1)
        gmsh.model.add("block")
        gmsh.model.occ.addBox(x0, y0, -spec.H, spec.L - x0, spec.L - y0, spec.H)
        gmsh.model.occ.synchronize()
        field = gmsh.model.mesh.field.add("MathEval")
        gmsh.model.mesh.field.setString(field, "F", size)
        gmsh.model.mesh.field.setAsBackgroundMesh(field)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)  # Frontal-Delaunay 2D
        gmsh.option.setNumber("Mesh.Algorithm3D", 10)  # HXT
        gmsh.option.setNumber("Mesh.Optimize", 1)
        gmsh.model.mesh.generate(3)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        etypes, _, conn = gmsh.model.mesh.getElements(3)
    except Exception as exc:  # gmsh raises bare Exceptions with its log message
        raise MeshError(f"gmsh failed to mesh the block {spec}: {exc}") from exc
    finally:
        gmsh.finalize()
    if 4 not in list(etypes):
        raise MeshError(f"gmsh produced no tetrahedra for {spec}")
    tets = np.asarray(conn[list(etypes).index(4)], dtype=np.int64).reshape(-1, 4)
    tags = np.asarray(tags, dtype=np.int64)
    lookup = np.full(tags.max() + 1, -1, dtype=np.int64)
    lookup[tags] = np.arange(tags.size)
    tets = lookup[tets]
    used = np.unique(tets)
    points = np.asarray(coords, dtype=float).reshape(-1, 3)
    # drop nodes not used by any tetrahedron (e.g. geometry points), renumber
    renum = np.full(points.shape[0], -1, dtype=np.int64)
    renum[used] = np.arange(used.size)
    points, tets = points[used], renum[tets]
    return points.T.copy(), tets.T.copy()


def _check(points: np.ndarray, tets: np.ndarray, spec: MeshSpec) -> None:
    if tets.size == 0 or (tets < 0).any():
        raise MeshError(f"invalid tetrahedral connectivity for {spec}")
    P = points[:, tets]
    J = np.stack([P[:, 1] - P[:, 0], P[:, 2] - P[:, 0], P[:, 3] - P[:, 0]], axis=1)
    vol = np.abs(np.linalg.det(np.moveaxis(J, -1, 0))) / 6.0
    x0 = 0.0 if spec.shape == "quarter" else -spec.L
    y0 = -spec.L if spec.shape == "full" else 0.0
    expected = (spec.L - x0) * (spec.L - y0) * spec.H
    if (vol <= 0).any() or abs(vol.sum() - expected) > 1e-6 * expected:
        raise MeshError(
            f"mesh of {spec} is invalid: volume {vol.sum():.6g} vs {expected:.6g}, "
            f"{int((vol <= 0).sum())} degenerate tetrahedra"
        )


def digest(points: np.ndarray, tets: np.ndarray) -> str:
    """SHA-256 of the mesh arrays (dtype, shape and bytes of each)."""
    h = hashlib.sha256()
    for a in (points, tets):
        h.update(f"{a.dtype.str}{a.shape}".encode())
        h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()


def _say(line: str) -> None:
    print(f"contact-vv: note: {line}", file=sys.stderr)


def read_entry(path: Path, spec: MeshSpec) -> tuple[np.ndarray, np.ndarray] | str:
    """The (points, tets) of the cache entry ``path`` if it holds ``spec``'s mesh whole,
    else why not."""
    try:
        with np.load(path, allow_pickle=False) as data:
            if "key" not in data.files or "sha256" not in data.files:
                return "written without its key (an older version)"
            if str(data["key"]) != spec.payload():
                return "holds another mesh's key"
            points, tets = data["points"], data["tets"]
            if str(data["sha256"]) != digest(points, tets):
                return "its arrays do not match their checksum"
    except Exception as exc:  # a file numpy cannot read: truncated, garbage, not a zip
        return f"unreadable: {type(exc).__name__}"
    return points, tets


def _write_entry(path: Path, spec: MeshSpec, points: np.ndarray, tets: np.ndarray) -> None:
    try:
        with atomic_path(path) as tmp:
            with open(tmp, "wb") as fh:
                np.savez(fh, points=points, tets=tets, key=spec.payload(),
                         sha256=digest(points, tets))
    except OSError as exc:  # an unwritable cache only costs time
        _say(f"mesh cache {path.parent} not written ({exc.strerror or exc}); the mesh is "
             "kept in memory only")


def build_points(spec: MeshSpec, *, use_cache: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Dimensionless (points, tets) for ``spec``, from the cache (checked: module doc) or
    freshly meshed."""
    path = cache_dir() / f"block-{spec.key()}.npz"
    if use_cache and path.exists():
        entry = read_entry(path, spec)
        if not isinstance(entry, str):
            return entry
        _say(f"mesh cache entry {path} discarded ({entry}); meshed again")
        try:
            path.unlink()
        except OSError:
            pass  # a read-only cache: the new mesh cannot replace it either
    points, tets = _generate(spec)
    _check(points, tets, spec)
    if use_cache:
        _write_entry(path, spec, points, tets)
    return points, tets


def block_mesh(spec: MeshSpec, a0: float, *, use_cache: bool = True) -> MeshTet:
    """The block mesh of ``spec`` in mm (coordinates scaled by ``a0``)."""
    points, tets = build_points(spec, use_cache=use_cache)
    return MeshTet(points * a0, tets.astype(np.int64))
