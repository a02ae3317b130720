"""Matplotlib figures of the report, returned as PNG bytes (Agg backend, no display).

Every axis is labelled with units or a dimensionless group: lengths in units of the
Hertz radius a0 (x/a0, z/a0, s/a0), stresses and tractions in units of the Hertz peak
pressure p0 (σ/p0, p/p0), wear depths in µm.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from cases.result import StepResult  # noqa: E402
from reports.compare.sampling import common_axis, sample  # noqa: E402
from reports.registry import solvers  # noqa: E402
from reports.registry.pairs import pairs  # noqa: E402
from reports.render.frame import colorbar, panels, png  # noqa: E402
from reports.store import layout  # noqa: E402


def style(solver: str) -> dict:
    """Line style of a solver (its registry record)."""
    return dict(solvers.record(solver).style)


def _centre_index(coords: np.ndarray, value: float = 0.0) -> int:
    return int(np.argmin(np.abs(np.asarray(coords) - value)))


def _extent(steps: Mapping[str, StepResult], a0: float) -> float:
    """Largest contact semi-width of the steps in units of a0 (1 if unknown)."""
    widths = [float(st.scalars.get(k, math.nan)) for st in steps.values()
              for k in ("a_x", "a_y")]
    widths = [w for w in widths if math.isfinite(w) and w > 0]
    return max(widths) / a0 if widths else 1.0


def traction_profiles(steps: Mapping[str, StepResult], a0: float, p0: float,
                      title: str = "") -> Figure | None:
    """p_n, p_x, p_y along x (y = 0) and p_n along y (x = 0), every solver on one plot."""
    if not any(s.surface for s in steps.values()):
        return None
    specs = [("p_n", "x", "p_n / p0"), ("p_x", "x", "p_x / p0"), ("p_y", "x", "p_y / p0"),
             ("p_n", "y", "p_n / p0")]

    def nonzero(field: str) -> bool:
        return any(field in st.surface and np.nanmax(np.abs(st.surface[field])) > 0
                   for st in steps.values())

    specs = [sp for sp in specs if sp[0] == "p_n" or nonzero(sp[0])]
    fig, axes = panels(1, len(specs), (2.6, 2.1), squeeze=False)
    axes = axes[0]
    for ax, (field, along, label) in zip(axes, specs, strict=True):
        for solver, st in steps.items():
            if field not in st.surface:
                continue
            f = np.asarray(st.surface[field])
            if along == "x":
                coord, line = st.x, f[:, _centre_index(st.y)]
            else:
                coord, line = st.y, f[_centre_index(st.x), :]
            ax.plot(np.asarray(coord) / a0, line / p0, label=solver, **style(solver))
        ax.set_xlim(-1.6 * _extent(steps, a0), 1.6 * _extent(steps, a0))
        ax.set_xlabel(f"{along} / a0 ({'y' if along == 'x' else 'x'} = 0)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend()
    fig.suptitle(title or "Surface tractions through the centre")
    return fig


def _difference_panel(fig: Figure, ax, axes_a, field_a, axes_b, field_b, a0: float,
                      p0: float, label: str) -> bool:
    """(A − B)/p0 on the common sample grid of two 2D fields, symmetric colour scale;
    False (axis switched off) when the grids share no 2D region."""
    u = common_axis(axes_a[0], axes_b[0])
    v = common_axis(axes_a[1], axes_b[1])
    if not (u.size > 1 and v.size > 1):
        ax.set_axis_off()
        return False
    d = (sample(axes_a, field_a, (u, v)) - sample(axes_b, field_b, (u, v))) / p0
    lim = float(np.nanmax(np.abs(d))) if np.isfinite(d).any() else 1.0
    im = ax.pcolormesh(u / a0, v / a0, d.T, cmap="RdBu_r", vmin=-lim or -1, vmax=lim or 1,
                       shading="nearest")
    colorbar(fig, im, ax, label)
    return True


def difference_maps(steps: Mapping[str, StepResult], a0: float, p0: float,
                    field: str = "p_n", title: str = "") -> Figure | None:
    """(A − B)/p0 of a surface field on the common sample grid of every pair."""
    todo = [(a, b) for a, b in pairs(list(steps))
            if field in steps[a].surface and field in steps[b].surface]
    if not todo:
        return None
    fig, axes = panels(1, len(todo), (3.2, 2.7), colorbar="each", squeeze=False)
    for ax, (a, b) in zip(axes[0], todo, strict=True):
        sa, sb = steps[a], steps[b]
        if not _difference_panel(fig, ax, (sa.x, sa.y), sa.surface[field], (sb.x, sb.y),
                                 sb.surface[field], a0, p0,
                                 f"({field}[{a}] − {field}[{b}]) / p0"):
            continue
        half = 1.4 * _extent(steps, a0)
        ax.set_xlim(-half, half)
        ax.set_ylim(-half, half)
        ax.set_aspect("equal")
        ax.set_xlabel("x / a0")
        ax.set_ylabel("y / a0")
        ax.set_title(f"{a} − {b}")
    fig.suptitle(title or f"Difference maps of {field}")
    return fig


def plane_difference_maps(steps: Mapping[str, StepResult], a0: float, p0: float,
                          plane: str = "xz", title: str = "") -> Figure | None:
    """(σ_VM[A] − σ_VM[B])/p0 on a plane, on the common sample grid of every pair."""
    have = {s: st.planes[plane] for s, st in steps.items()
            if plane in st.planes and "vm" in st.planes[plane].fields
            and min(np.shape(st.planes[plane].fields["vm"])) > 1}
    todo = pairs(list(have))
    if not todo:
        return None
    fig, axes = panels(1, len(todo), (3.2, 1.9), colorbar="each", squeeze=False)
    half = 3.0 * _extent(steps, a0)
    for ax, (a, b) in zip(axes[0], todo, strict=True):
        pa, pb = have[a], have[b]
        if not _difference_panel(fig, ax, (pa.s, pa.z), pa.fields["vm"], (pb.s, pb.z),
                                 pb.fields["vm"], a0, p0, f"(σ_VM[{a}] − σ_VM[{b}]) / p0"):
            continue
        ss = common_axis(pa.s, pb.s)
        ax.set_xlim(max(ss.min() / a0, -half), min(ss.max() / a0, half))
        ax.invert_yaxis()
        ax.set_xlabel(f"{plane[0]} / a0")
        ax.set_ylabel("z / a0 (depth)")
        ax.set_title(f"{a} − {b}, {plane} plane")
    fig.suptitle(title or f"Differences of σ_VM on the {plane} plane")
    return fig


def vm_planes(steps: Mapping[str, StepResult], a0: float, p0: float,
              title: str = "") -> Figure | None:
    """σ_VM/p0 contours on the xz and yz planes, solvers side by side, maxima marked."""
    names = sorted({n for st in steps.values() for n in st.planes})
    solvers = [s for s, st in steps.items() if st.planes]
    if not names or not solvers:
        return None
    levels = None
    vmax = max(float(np.nanmax(st.planes[n].fields["vm"])) for st in steps.values()
               for n in st.planes if "vm" in st.planes[n].fields) / p0
    if math.isfinite(vmax) and vmax > 0:
        levels = np.linspace(0.0, vmax, 21)
    fig, axes = panels(len(names), len(solvers), (3.3, 1.6),
                       colorbar="shared" if levels is not None else "each", squeeze=False)
    cs = None
    for row, name in enumerate(names):
        for col, solver in enumerate(solvers):
            ax = axes[row][col]
            plane = steps[solver].planes.get(name)
            if plane is None or "vm" not in plane.fields or min(plane.fields["vm"].shape) < 2:
                ax.set_axis_off()
                continue
            s, z = np.asarray(plane.s) / a0, np.asarray(plane.z) / a0
            cs = ax.contourf(s, z, np.asarray(plane.fields["vm"]).T / p0, levels=levels,
                             cmap="viridis")
            vm, sm, zm = plane.vm_max()
            ax.plot(sm / a0, zm / a0, "rx", ms=10, mew=2,
                    label=f"max {vm / p0:.3f} p0 at ({sm / a0:.2f}, {zm / a0:.2f})")
            ax.legend(loc="lower right", fontsize=7)
            half = 3.0 * _extent(steps, a0)
            ax.set_xlim(max(s.min(), -half), min(s.max(), half))
            ax.invert_yaxis()
            ax.set_xlabel(f"{name[0]} / a0")
            ax.set_ylabel("z / a0 (depth)")
            ax.set_title(f"{solver}, {name} plane")
            if levels is None:  # each panel its own scale
                colorbar(fig, cs, ax, "σ_VM / p0", format="%.2f")
    if levels is not None and cs is not None:  # one scale for every panel
        colorbar(fig, cs, axes.ravel().tolist(), "σ_VM / p0", format="%.2f")
    fig.suptitle(title or "Von Mises stress on the planes through the load centre")
    return fig


def wear_profiles(history: Mapping[str, Mapping[int, StepResult]], a0: float,
                  labels: Mapping[int, str], title: str = "") -> Figure | None:
    """Total wear depth (body a + b) along x through the centre at every output step."""
    lines = []
    for solver, steps in history.items():
        for n, st in steps.items():
            if "wear_a" in st.surface or "wear_b" in st.surface:
                w = sum(np.asarray(st.surface[k]) for k in ("wear_a", "wear_b")
                        if k in st.surface)
                if np.nanmax(np.abs(w)) > 0:
                    lines.append((solver, n, st.x, w[:, _centre_index(st.y)]))
    if not lines:
        return None
    fig, ax = panels(1, 1, (5.9, 2.4))
    order = sorted({n for _, n, _, _ in lines})
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(order)))
    for solver, n, x, w in lines:
        st = dict(style(solver), color=colours[order.index(n)])
        ax.plot(np.asarray(x) / a0, 1e3 * w, label=f"{solver} {labels.get(n, n)}", **st)
    ax.set_xlabel("x / a0 (y = 0)")
    ax.set_ylabel("wear depth w_a + w_b [µm]")
    ax.invert_yaxis()
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    ax.set_title(title or "Wear profiles")
    return fig


def progress_axis(summary: pd.DataFrame, a0: float) -> tuple[pd.Series, str]:
    """The evolution variable of a summary: s/a0, the cycle count, or the step."""
    if summary["s"].notna().any():
        return summary["s"] / a0, "sliding distance s / a0"
    if summary["cycle"].notna().any():
        return summary["cycle"], "fretting cycles N"
    return summary["step"], "output step"


#: short legend names of the evolution variables of :func:`progress_axis`
SHORT = {"sliding distance s / a0": "s/a0", "fretting cycles N": "N", "output step": "step"}


def histories(summary: pd.DataFrame, a0: float, p0: float, title: str = "") -> Figure | None:
    """w_max vs distance (when there is wear) and σ_VM,max / p0 and its depth vs step."""
    if summary.empty or summary["step"].nunique() < 2:
        return None
    has_wear = summary["w_max"].fillna(0).abs().max() > 0
    ncols = 3 if has_wear else 2
    fig, axes = panels(1, ncols, (3.4, 2.2))
    t, tlabel = progress_axis(summary, a0)
    for solver, rows in summary.groupby("solver", sort=False):
        tt = t.loc[rows.index]
        k = 0
        if has_wear:
            axes[0].plot(tt, 1e3 * rows["w_max"], label=solver, **style(solver))
            axes[0].set_ylabel("max wear depth w_max [µm]")
            k = 1
        axes[k].plot(tt, rows["vm_max"] / p0, label=solver, **style(solver))
        axes[k].set_ylabel("σ_VM,max / p0")
        axes[k + 1].plot(tt, rows["vm_max_z"] / a0, label=solver, **style(solver))
        axes[k + 1].set_ylabel("depth of σ_VM,max  z / a0")
        axes[k + 1].invert_yaxis() if not axes[k + 1].yaxis_inverted() else None
    for ax in axes:
        ax.set_xlabel(tlabel)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title or "Evolution")
    return fig


def _loop_columns(table: pd.DataFrame) -> tuple[str, str, str | None] | None:
    """(displacement, force, cycle) columns of a fretting-loop table, or None."""
    cols = list(table.columns)
    disp = next((c for c in cols if c.lower().startswith(("disp", "shift", "delta", "u_",
                                                          "g_t"))), None)
    force = next((c for c in cols if c in ("Qx", "Q", "Fx", "Q_x")), None) or \
        next((c for c in cols if c.lower().startswith(("q", "f")) and c != disp), None)
    cycle = next((c for c in cols if c.lower() in ("cycle", "cycles", "n")), None)
    if disp is None or force is None:
        rest = [c for c in cols if c != cycle]
        if len(rest) < 2:
            return None
        disp, force = rest[0], rest[1]
    return disp, force, cycle


def loops(tables: Mapping[str, Mapping[str, pd.DataFrame]], title: str = "") -> Figure | None:
    """Fretting loops: tangential force against displacement, one curve per recorded
    cycle, from every table whose name contains 'loop'."""
    items = []
    for solver, ts in tables.items():
        for name, t in ts.items():
            cols = _loop_columns(t) if "loop" in name else None
            if cols is not None:
                items.append((solver, name, t, cols))
    if not items:
        return None
    fig, ax = panels(1, 1, (4.9, 3.0))
    for solver, _name, t, (disp, force, cycle) in items:
        groups = t.groupby(cycle, sort=True) if cycle else [(None, t)]
        groups = list(groups)
        shades = np.linspace(0.35, 1.0, len(groups))
        for shade, (n, g) in zip(shades, groups, strict=True):
            st = dict(style(solver), ms=2, alpha=float(shade))
            label = f"{solver}" + (f" N={n:g}" if n is not None else "")
            ax.plot(1e3 * g[disp], g[force], label=label, **st)
    disp, force, _ = items[0][3]
    ax.set_xlabel(f"tangential displacement ({disp}) [µm]")
    ax.set_ylabel(f"tangential force ({force}) [N]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    ax.set_title(title or "Fretting loops")
    return fig


def param_value(label: str) -> float:
    """The (first) numeric value of a sweep label such as ``mu=0.25`` or ``nx=41,ny=41``."""
    try:
        return float(str(label).split(",")[0].split("=", 1)[1])
    except (IndexError, ValueError):
        return math.nan


def sweep_figure(summary: pd.DataFrame, points: Mapping[str, tuple[float, float]],
                 title: str = "") -> Figure | None:
    """Quantities of interest at the last output step against the swept parameter."""
    if summary.empty or summary["param"].fillna("").eq("").all():
        return None
    last = summary.sort_values("step").groupby(["solver", "param"], sort=False).tail(1)
    last = last.assign(v=last["param"].map(param_value))
    if last["v"].isna().all() or last["param"].nunique() < 2:
        return None
    a0 = last["param"].map(lambda p: points.get(p, (math.nan, math.nan))[0])
    p0 = last["param"].map(lambda p: points.get(p, (math.nan, math.nan))[1])
    last = last.assign(vm=last["vm_max"] / p0, z=last["vm_max_z"] / a0, pm=last["p_max"] / p0)
    fig, axes = panels(1, 3, (3.2, 2.2))
    key = str(last["param"].iloc[0]).split("=")[0]
    for solver, rows in last.groupby("solver", sort=False):
        rows = rows.sort_values("v")
        for ax, col in zip(axes, ("vm", "z", "pm"), strict=True):
            ax.plot(rows["v"], rows[col], label=solver, **style(solver))
    for ax, lab in zip(axes, ("σ_VM,max / p0", "depth of σ_VM,max  z / a0", "p_max / p0"),
                       strict=True):
        ax.set_xlabel(f"{key} (swept parameter)")
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[1].invert_yaxis()
    fig.suptitle(title or "Sweep: quantities of interest at the last output step")
    return fig


def write_sweep_plot(case_dir: Path) -> Path | None:
    """Write ``sweep.png`` beside a sweep's summary (outside the manifest: a view)."""
    from reports.store.results import scan

    for case in scan(Path(case_dir).parent, verify=False).complete:
        if case.path.resolve() == Path(case_dir).resolve():
            points = {p.get("param", ""): (p.get("hertz_a0", math.nan),
                                           p.get("hertz_p0", math.nan))
                      for p in case.manifest.get("points", [])}
            fig = sweep_figure(case.summary, points, title=f"{case.name}")
            if fig is None:
                return None
            path = Path(case_dir) / layout.SWEEP_PLOT
            from cases.result import atomic_path

            with atomic_path(path) as tmp:
                tmp.write_bytes(png(fig))
            return path
    return None
