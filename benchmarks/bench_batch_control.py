#!/usr/bin/env python
"""Cost of the control force models in BatchSimulator: vectorised vs one Python call per ship.

Setup: the S175 at 10 m/s with propulsion (Holtrop–Mennen resistance + B-series propeller),
hull manoeuvring forces, the rudder under the PID heading autopilot, roll fins and T-foil under
open-loop commands (the models of ``ShipSetup(propulsion=True, manoeuvring=True,
rudder="autopilot", fins="command", t_foil="command")``), Holloway's integrator, irregular
beam-quartering seas (Hs = 4 m, Tp = 10 s, 30 components, one seed per ship).

For N = 1, 16 and 64 ships, two batches are built with
:func:`ship_gym.engine.batch.build_batch_simulator`: ``control="batch"`` (the vectorised
models of :mod:`ship_gym.engine.batch_control`) and ``control="per_ship"``
(:class:`~ship_gym.engine.batch.PerShipForceModel`: one single-ship model per ship, looped in
Python). After a few steps (actuators moving), printed and written with ``--json PATH``:

* the **process time** (``time.process_time``, CPU seconds of this process: less sensitive to
  the other jobs on a shared machine than the wall clock) of one evaluation of all control
  models together, µs, and per model;
* the process time of one whole step (Holloway: one evaluation of every model + integrator);
* their ratios per-ship / vectorised.

Medians over interleaved blocks, so that a varying load hits both variants alike. Threads:
numba, OpenMP and BLAS threads are set to 1 before numpy is imported.

Usage::

    python benchmarks/bench_batch_control.py [--json PATH] [--quick]
"""

from __future__ import annotations

import os

for _var in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from ship_gym.engine.batch import BatchSimulator, build_batch_simulator  # noqa: E402
from ship_gym.engine.ship import ShipSetup, wave_field_for  # noqa: E402
from ship_gym.io_utils import atomic_write_text  # noqa: E402
from ship_gym.waves.sea_state import IrregularSea  # noqa: E402

CONTROL_MODELS = ("resistance", "propeller", "hull_manoeuvring", "rudder", "roll_fins", "t_foil")
SETUP = ShipSetup(
    speed=10.0,
    propulsion=True,
    manoeuvring=True,
    rudder="autopilot",
    fins="command",
    t_foil="command",
    integrator="holloway",
)
SEA = IrregularSea(hs=4.0, tp=10.0, n_components=30, ramp_time=5.0)


def _commands(n: int, k: int) -> dict:
    t = 0.05 * k
    phase = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    return {
        "fins_command": 0.2 * np.sin(0.5 * t + phase),
        "t_foil_command": 0.1 * np.cos(0.7 * t + phase),
        "heading": 0.1 * np.cos(phase),
    }


def _per_evaluation(batch: BatchSimulator, repeats: int) -> dict[str, float]:
    """Process time [s] of one evaluate() call per control model at the current state."""
    ctx, _, _ = batch._context(batch._all, True, batch.t, batch.eta, batch.nu)
    out: dict[str, float] = {}
    for f, sl in zip(batch.forces, batch._slices, strict=True):
        if f.name not in CONTROL_MODELS:
            continue
        z = batch.z[:, sl]
        t0 = time.process_time()
        for _ in range(repeats):
            f.evaluate(ctx, z)
        out[f.name] = (time.process_time() - t0) / repeats
    return out


def _per_step(batch: BatchSimulator, repeats: int, k0: int) -> float:
    t0 = time.process_time()
    for k in range(repeats):
        batch.step(_commands(batch.n_ships, k0 + k))
    return (time.process_time() - t0) / repeats


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path, default=None, help="write the numbers here")
    parser.add_argument("--quick", action="store_true", help="fewer repeats")
    args = parser.parse_args()
    blocks, eval_repeats, step_repeats = (3, 20, 3) if args.quick else (7, 50, 5)
    results: dict = {"setup": repr(SETUP), "timer": "time.process_time", "sizes": {}}
    for n in (1, 16, 64):
        fields = [wave_field_for(SEA, 1.2 + 0.02 * i, np.random.default_rng(i)) for i in range(n)]
        batches = {
            c: build_batch_simulator(SETUP, fields, control=c) for c in ("batch", "per_ship")
        }
        for b in batches.values():
            for k in range(10):
                b.step(_commands(n, k))
        evals: dict[str, list[dict[str, float]]] = {c: [] for c in batches}
        steps: dict[str, list[float]] = {c: [] for c in batches}
        for block in range(blocks):
            for c, b in batches.items():
                evals[c].append(_per_evaluation(b, eval_repeats))
                steps[c].append(_per_step(b, step_repeats, 10 + block * step_repeats))
        row: dict = {}
        for c in batches:
            per_model = {m: 1e6 * float(np.median([e[m] for e in evals[c]])) for m in evals[c][0]}
            row[c] = {
                "control_models_us_per_evaluation": sum(per_model.values()),
                "per_model_us": per_model,
                "step_us": 1e6 * float(np.median(steps[c])),
            }
        row["control_ratio_per_ship_over_batch"] = (
            row["per_ship"]["control_models_us_per_evaluation"]
            / row["batch"]["control_models_us_per_evaluation"]
        )
        row["step_ratio_per_ship_over_batch"] = row["per_ship"]["step_us"] / row["batch"]["step_us"]
        results["sizes"][str(n)] = row
        vec, loop = row["batch"], row["per_ship"]
        print(
            f"N = {n:3d}: control models per evaluation "
            f"{vec['control_models_us_per_evaluation']:9.1f} µs vectorised, "
            f"{loop['control_models_us_per_evaluation']:9.1f} µs per ship "
            f"(× {row['control_ratio_per_ship_over_batch']:.1f}); whole step "
            f"{vec['step_us']:9.1f} µs vs {loop['step_us']:9.1f} µs "
            f"(× {row['step_ratio_per_ship_over_batch']:.2f})"
        )
        for c in batches:
            models = ", ".join(f"{m} {v:.1f}" for m, v in row[c]["per_model_us"].items())
            print(f"          {c:8s} µs per model: {models}")
    results["load_average"] = os.getloadavg()
    print(f"load average {results['load_average']}")
    if args.json is not None:
        atomic_write_text(args.json, json.dumps(results, indent=2) + "\n")


if __name__ == "__main__":
    main()
