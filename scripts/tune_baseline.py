#!/usr/bin/env python
"""Tune the classical baseline of a ship task on training seeds, then evaluate it on held-out
seeds: the fin stabiliser of RollStabilization, the heading autopilot of CourseKeeping, the
T-foil ride controller of RideControl.

Both baselines are designed from the ship's own linear model and leave two design choices open,
which a grid over them settles on the training seeds (default 0–23, one episode each with the
env's default episode distribution) by the best mean return — the env's own trade-off of the
task error against actuator effort and travel:

* **RollStabilization-v2**, the PD fin law δ = −(k_φ φ + k_p p) of
  :func:`ship_gym.engine.ship.fin_stabiliser`: the rate gain adds a fraction ζ_add of critical
  roll damping, k_p = 2 ζ_add √(C₄₄ (I₄₄ + A₄₄)) / K_δ, the angle gain a fraction c_add of the
  hydrostatic stiffness, k_φ = c_add C₄₄ / K_δ (grid: ζ_add × c_add);
* **CourseKeeping-v2**, the PID autopilot of :func:`ship_gym.engine.ship.heading_autopilot`,
  placed on the Nomoto model (K, T) identified from the ship's manoeuvring, propulsion and rudder
  models: K_p = T ω_n²/K, K_d = (2 ζ ω_n T − 1)/K, K_i = K_p ω_n/10 (grid: ω_n × ζ);
* **RideControl-v2**, the T-foil law δ = k_w w − k_q q of
  :func:`ship_gym.engine.ship.ride_controller`: each gain adds a fraction of critical damping
  to its mode as if the foil acted on it alone, k_w = 2 ζ_3 √(C₃₃ (m + A₃₃)) / Z_δ and
  k_q = 2 ζ_5 √(C₅₅ (I₅₅ + A₅₅)) / M_δ (grid: ζ_3 × ζ_5; the S175's 12.8 m² foil is small
  against its pitch inertia, so the fractions are small: ζ_5 = 0.023 is k_q = 40 action units).

Gains are written in action units (per unit of the action, i.e. divided by the actuator limit),
the form :mod:`ship_gym.agents.baselines` takes. The tuned baseline, the design's defaults and the
zero action then run on the held-out seeds (default 10 000–10 039), never used in tuning.

Outputs (``--out``, default ``docs/benchmarks``): ``<task>_baseline_tuning.csv`` (every grid
point) and ``<task>_baseline.json`` (the chosen point and the held-out results).

Usage::

    python scripts/tune_baseline.py RollStabilization [--train-seeds 0 24]
                                    [--test-seeds 10000 40] [--out docs/benchmarks]
"""

from __future__ import annotations

import argparse
import csv
import io
import itertools
import json
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import gymnasium

import ship_gym  # noqa: F401  (registers the ids)
from ship_gym.agents.baselines import make_baseline
from ship_gym.agents.evaluate import run_episodes, summarize
from ship_gym.engine.ship import fin_stabiliser, heading_autopilot, ride_controller
from ship_gym.envs.env_task import RUDDER_LIMIT_DEG
from ship_gym.envs.ride_control import FOIL_LIMIT_DEG
from ship_gym.envs.roll_stabilisation import FIN_LIMIT_DEG
from ship_gym.io_utils import atomic_write_text


def _fin_gains(setup: Any, added_damping: float, added_stiffness: float) -> dict[str, float]:
    design = fin_stabiliser(setup, added_damping=added_damping, added_stiffness=added_stiffness)
    limit = math.radians(FIN_LIMIT_DEG)
    return {"k_roll": float(design.k_roll) / limit, "k_rate": float(design.k_rate) / limit}


def _autopilot_gains(setup: Any, natural_frequency: float, damping: float) -> dict[str, float]:
    design = heading_autopilot(setup, natural_frequency=natural_frequency, damping=damping)
    limit = math.radians(RUDDER_LIMIT_DEG)
    return {"k_p": design.kp / limit, "k_d": design.kd / limit, "k_i": design.ki / limit}


def _ride_gains(setup: Any, heave_damping: float, pitch_damping: float) -> dict[str, float]:
    design = ride_controller(setup, heave_damping=heave_damping, pitch_damping=pitch_damping)
    limit = math.radians(FOIL_LIMIT_DEG)
    return {"k_heave": float(design.k_heave) / limit, "k_pitch": float(design.k_pitch) / limit}


@dataclass(frozen=True)
class Design:
    """A baseline designed from the ship's model with two open choices."""

    env_id: str
    baseline: str
    metric: str
    grid: dict[str, tuple[float, ...]]
    defaults: dict[str, float]
    gains: Callable[..., dict[str, float]]
    reference: str = "design defaults"
    """What ``defaults`` are, in the held-out report."""


DESIGNS = {
    "RollStabilization": Design(
        "ship_gym/RollStabilization-v2",
        "fins",
        "rms_roll_deg",
        {"added_damping": (0.1, 0.2, 0.3, 0.5, 0.8, 1.2), "added_stiffness": (0.0, 0.2, 0.5)},
        {"added_damping": 0.3, "added_stiffness": 0.2},
        _fin_gains,
    ),
    "CourseKeeping": Design(
        "ship_gym/CourseKeeping-v2",
        "pid",
        "rms_heading_error_deg",
        {"natural_frequency": (0.04, 0.06, 0.08, 0.1, 0.12), "damping": (0.7, 0.9, 1.2)},
        {"natural_frequency": 0.06, "damping": 0.9},
        _autopilot_gains,
    ),
    "RideControl": Design(
        "ship_gym/RideControl-v2",
        "ride",
        "rms_vertical_acceleration_mps2",
        {"heave_damping": (0.0, 0.02, 0.05, 0.1), "pitch_damping": (0.01, 0.02, 0.03, 0.05, 0.08)},
        {"heave_damping": 0.0, "pitch_damping": 0.023},
        _ride_gains,
        "former hand-tuned gains",
    ),
}


def _run(design: Design, name: str, gains: dict, seeds: list[int]) -> dict:
    t0 = time.perf_counter()
    stats = run_episodes(design.env_id, lambda env: make_baseline(name, env, **gains), seeds)
    metrics = summarize(stats)
    return {
        design.metric: metrics[design.metric],
        "rms_action": metrics["rms_action"],
        "mean_return": metrics["mean_return"],
        "capsize_rate": metrics["capsize_rate"],
        "wall_s": time.perf_counter() - t0,
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("task", choices=sorted(DESIGNS), help="the ship task")
    parser.add_argument("--train-seeds", nargs=2, type=int, default=(0, 24), metavar=("FIRST", "N"))
    parser.add_argument(
        "--test-seeds", nargs=2, type=int, default=(10_000, 40), metavar=("FIRST", "N")
    )
    parser.add_argument("--out", default="docs/benchmarks", help="output folder")
    args = parser.parse_args()
    design = DESIGNS[args.task]
    train = list(range(args.train_seeds[0], args.train_seeds[0] + args.train_seeds[1]))
    test = list(range(args.test_seeds[0], args.test_seeds[0] + args.test_seeds[1]))
    if not train or not test:
        parser.error("--train-seeds and --test-seeds need N >= 1")
    if set(train) & set(test):
        parser.error("--train-seeds and --test-seeds overlap; held-out seeds must be new")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    env = gymnasium.make(design.env_id)
    setup = env.unwrapped.task.setup  # the ship, loading and speed of the default episodes
    env.close()
    keys = list(design.grid)
    points = [
        dict(zip(keys, values, strict=True)) for values in itertools.product(*design.grid.values())
    ]
    from tqdm.auto import tqdm

    rows = []
    for point in tqdm(points, desc=f"{args.task} grid", unit="point"):
        gains = design.gains(setup, **point)
        rows.append({**point, **gains, **_run(design, design.baseline, gains, train)})
    best = max(rows, key=lambda r: r["mean_return"])
    chosen = {k: best[k] for k in keys}
    chosen_gains = design.gains(setup, **chosen)
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
    stem = f"{args.task}_baseline"
    atomic_write_text(out / f"{stem}_tuning.csv", buffer.getvalue())

    held_out = {
        "zero": _run(design, "zero", {}, test),
        f"{design.baseline} (tuned)": _run(design, design.baseline, chosen_gains, test),
        f"{design.baseline} ({design.reference})": _run(
            design, design.baseline, design.gains(setup, **design.defaults), test
        ),
    }
    report = {
        "env_id": design.env_id,
        "baseline": design.baseline,
        "train_seeds": [train[0], len(train)],
        "test_seeds": [test[0], len(test)],
        "grid": design.grid,
        design.reference.replace(" ", "_"): design.defaults,
        "chosen": chosen,
        "chosen_gains": chosen_gains,
        "chosen_train_return": best["mean_return"],
        "held_out": held_out,
    }
    atomic_write_text(out / f"{stem}.json", json.dumps(report, indent=2))
    text = ", ".join(f"{k} {v:g}" for k, v in chosen.items())
    gains_text = ", ".join(f"{k} {v:.4g}" for k, v in chosen_gains.items())
    print(f"chosen on seeds {train[0]}…{train[-1]}: {text} → {gains_text}")
    for name, r in held_out.items():
        print(
            f"{name:32s} {design.metric} {r[design.metric]:.3f}  effort {r['rms_action']:.3f}  "
            f"return {r['mean_return']:.1f}  capsize {r['capsize_rate']:.2f}"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
