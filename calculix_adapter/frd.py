"""The suite's reader of CalculiX's result files: the nodal result blocks of the
``.frd`` file (fixed-width text), and the contact statistics (``*CONTACT PRINT``) and
nodal tables (``*NODE PRINT``) of the ``.dat`` file.

A ``.frd`` result block is a ``1PSTEP`` line (result set, increment, step), a ``100CL``
header (its time), a ``-4`` line (the block's name and number of components), one ``-5``
line per component, then one ``-1`` line per node: the node number (10 characters) and
the values (12 characters each, which may run together: ``0.0E+00-2.9E+00``), closed
by ``-3``.  Only what the plugin reads is parsed; the rest is skipped.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np


class ResultFileError(ValueError):
    """A result file CalculiX did not finish, or not of the form read here."""


@dataclass(frozen=True)
class Block:
    """One nodal result block: its name (``DISP``, ``STRESS``, ``CONTACT``), component
    names, step and increment numbers, time, node numbers (n,) and values (n, c)."""

    name: str
    components: tuple[str, ...]
    step: int
    increment: int
    time: float
    nodes: np.ndarray
    values: np.ndarray

    def field(self, component: str) -> np.ndarray:
        """One component's values (n,)."""
        return self.values[:, self.components.index(component)]


def _values(line: str, n: int) -> list[float]:
    return [float(line[13 + 12 * k:25 + 12 * k]) for k in range(n)]


def read_frd(path: Path) -> list[Block]:
    """The nodal result blocks of a ``.frd`` file, in the order written."""
    lines = Path(path).read_text(errors="replace").splitlines()
    if not lines or lines[-1].strip() != "9999":
        raise ResultFileError(f"{path}: not a complete .frd file (no closing 9999)")
    blocks: list[Block] = []
    step = increment = 0
    time = 0.0
    i = 0
    while i < len(lines):
        line = lines[i]
        head = line.split()[:3]
        if head and head[0] == "1PSTEP":
            increment, step = int(head[2]), int(line.split()[3])
        elif head and head[0] == "100CL":
            time = float(head[2])
        elif line.startswith(" -4"):
            parts = line.split()
            name, ncomp = parts[1], int(parts[2])
            comps = []
            i += 1
            while i < len(lines) and lines[i].startswith(" -5"):
                comps.append(lines[i].split()[1])
                i += 1
            comps = [c for c in comps if c != "ALL"][:ncomp]
            ids, vals = [], []
            while i < len(lines) and lines[i].startswith(" -1"):
                ids.append(int(lines[i][3:13]))
                vals.append(_values(lines[i], len(comps)))
                i += 1
            if i >= len(lines) or not lines[i].startswith(" -3"):
                raise ResultFileError(f"{path}: block {name} not closed (line {i + 1})")
            blocks.append(Block(name, tuple(comps), step, increment, time,
                                np.asarray(ids, dtype=np.int64),
                                np.asarray(vals, dtype=float).reshape(len(ids), len(comps))))
        i += 1
    return blocks


def last(blocks: list[Block], name: str) -> Block:
    """The last block named ``name`` (the last increment of the last step written)."""
    found = [b for b in blocks if b.name == name]
    if not found:
        raise ResultFileError(f"no {name} block in the .frd file")
    return found[-1]


@dataclass(frozen=True)
class ContactForces:
    """``*CONTACT PRINT`` CF of one time: the total force on the slave surface
    (fx, fy, fz) [N], its contact area [mm²], normal force (+ tension) and shear size."""

    time: float
    force: tuple[float, float, float]
    area: float
    normal: float
    shear: float


_NUMBER = r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?"


def read_contact_forces(path: Path) -> list[ContactForces]:
    """The contact statistics of a ``.dat`` file, one per time written."""
    text = Path(path).read_text(errors="replace")
    out = []
    for m in re.finditer(r"statistics for slave set .*? and time\s+(" + _NUMBER + r")", text):
        rest = text[m.end():]
        force = re.search(r"total surface force.*?\n\s*\n?\s*(" + r")\s+(".join([_NUMBER] * 3)
                          + ")", rest, re.S)
        area = re.search(r"area,\s+normal force.*?\n\s*\n?\s*(" + r")\s+(".join([_NUMBER] * 3)
                         + ")", rest, re.S)
        if force is None or area is None:
            raise ResultFileError(f"{path}: contact statistics at time {m.group(1)} "
                                  "incomplete")
        out.append(ContactForces(float(m.group(1)), tuple(float(force.group(k))
                                                          for k in (1, 2, 3)),
                                 *(float(area.group(k)) for k in (1, 2, 3))))
    return out


def read_node_print(path: Path, what: str = "displacements") -> tuple[np.ndarray, np.ndarray]:
    """(node numbers, values (n, 3)) of the last ``*NODE PRINT`` table of ``what`` in a
    ``.dat`` file (``displacements (vx,vy,vz) for set SKIN and time …``)."""
    text = Path(path).read_text(errors="replace")
    heads = list(re.finditer(what + r" \(.*?\) for set \S+ and time\s+(" + _NUMBER + ")",
                             text))
    if not heads:
        raise ResultFileError(f"{path}: no table of {what}")
    ids, vals = [], []
    for line in text[heads[-1].end():].splitlines()[1:]:
        parts = line.split()
        if not parts:
            if ids:
                break
            continue
        if not parts[0].isdigit() or len(parts) != 4:
            break
        ids.append(int(parts[0]))
        vals.append([float(v) for v in parts[1:]])
    if not ids:
        raise ResultFileError(f"{path}: the table of {what} is empty")
    return np.asarray(ids, dtype=np.int64), np.asarray(vals)
