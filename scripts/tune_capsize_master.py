#!/usr/bin/env python
"""Tune CapsizeAvoidance's IMO-guidance master: ``scripts/tune_baseline.py CapsizeAvoidance``.

Kept so that the former command still works; the grid, the criterion (fewest capsizes, then the
best mean return on the training seeds 0–47), the widening of a grid whose optimum lies on its
edge and the outputs (``docs/benchmarks/capsize_master_tuning.csv``, ``capsize_master.json``)
are those of :mod:`tune_baseline`; held-out episodes are the benchmark's (``ship-gym
benchmark``).

Usage::

    python scripts/tune_capsize_master.py [--seeds 0 48] [--out docs/benchmarks]
"""

from __future__ import annotations

import runpy
import sys
from pathlib import Path

if __name__ == "__main__":
    sys.argv = [
        str(Path(__file__).with_name("tune_baseline.py")),
        "CapsizeAvoidance",
        *sys.argv[1:],
    ]
    runpy.run_path(sys.argv[0], run_name="__main__")
