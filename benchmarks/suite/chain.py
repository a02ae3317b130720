"""The README's quick chain (``contact-vv run --all --quick``) on the bundled cases, whole."""

from __future__ import annotations

import tempfile
from pathlib import Path

from reports.cli import main


class QuickChain:
    number, repeat, rounds, warmup_time = 1, 1, 1, 0.0
    timeout = 3600

    def time_quick_chain(self):
        with tempfile.TemporaryDirectory() as tmp:
            code = main(["run", "--all", "--quick", "--no-progress", "--out",
                         str(Path(tmp) / "res")])
        if code != 0:
            raise RuntimeError(f"the quick chain exited {code}")
