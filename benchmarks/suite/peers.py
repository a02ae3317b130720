"""This project beside Tamaas on the same problems (``benchmarks/peers_bench.py``'s set-ups:
Hertz at 512² against PolonskyKeerRey with the non-periodic DC-FFT operator, and
Cattaneo–Mindlin at 256² against PolonskyKeerTan); the ratio is read from the two
timings of one run.  Skipped where Tamaas is not installed."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # benchmarks/peers_bench.py
import peers_bench as pb  # noqa: E402


class Paired:
    params = (["hertz_512", "mindlin_256"], ["project", "tamaas"])
    param_names = ["problem", "code"]

    def setup(self, problem, code):
        if code == "tamaas" and importlib.util.find_spec("tamaas") is None:
            raise NotImplementedError("Tamaas is not installed")

    def time_solve(self, problem, code):
        if problem == "hertz_512":
            (pb.project_hertz(512) if code == "project" else pb.tamaas_hertz(512, False))
        else:
            (pb.project_mindlin(256) if code == "project"
             else pb.tamaas_mindlin(256, pb.pkt_budget(256)))
