#!/usr/bin/env python
"""Tune the classical baseline of a ship task on training seeds until its optimum lies inside the
grid: the fin stabiliser of RollStabilization, the heading autopilot of CourseKeeping, the T-foil
ride controller of RideControl, the IMO-guidance master of CapsizeAvoidance.

The baselines leave design choices open, which a grid over them settles on the tuning episodes
(:data:`ship_gym.agents.protocol.TUNING_SEEDS`, seeds 0–47 of the training range, one episode
each with the env's default episode distribution) by fewest capsizes, then the best mean return
— the env's own trade-off of the task error against actuator effort and travel
(:func:`ship_gym.agents.tuning.default_score`) — and, among the points whose return is within
one standard error of the best (the return is flat along a ridge of gains), the lowest task
metric (:func:`ship_gym.agents.tuning.one_standard_error_choice`). While the chosen point lies
on the edge of an axis
that may go further the grid is widened by one step along it and the script prints so
(:func:`ship_gym.agents.tuning.tune_grid`):

* **RollStabilization-v2**, the PD fin law δ = −(k_φ φ + k_p p) of
  :func:`ship_gym.engine.ship.fin_stabiliser`: the rate gain adds a fraction ζ_add of critical
  roll damping, k_p = 2 ζ_add √(C₄₄ (I₄₄ + A₄₄)) / K_δ, the angle gain a fraction c_add of the
  hydrostatic stiffness, k_φ = c_add C₄₄ / K_δ (grid: ζ_add × c_add);
* **CourseKeeping-v2**, the PID autopilot of :func:`ship_gym.engine.ship.heading_autopilot`,
  placed on the Nomoto model (K, T) identified from the ship's manoeuvring, propulsion and rudder
  models: K_p = T ω_n²/K, K_d = (2 ζ ω_n T − 1)/K, K_i = K_p ω_n/10 (grid: ω_n × ζ; a point whose
  K_d would be negative is infeasible);
* **RideControl-v2**, the T-foil law δ = k_w w − k_q q of
  :func:`ship_gym.engine.ship.ride_controller`: each gain adds a fraction of critical damping
  to its mode as if the foil acted on it alone (grid: ζ_3 × ζ_5);
* **CapsizeAvoidance-v2**, :class:`ship_gym.agents.baselines.IMOGuidanceMaster`: the
  resonance band, the widening of the surf-riding and high-wave zones and the beam-sea limit
  (the high-wave weight changed no decision on the former grid: fixed at 0.5).

Gains are written in action units (per unit of the action, i.e. divided by the actuator limit),
the form :mod:`ship_gym.agents.baselines` takes; put the printed ones into its
``DEFAULT_GAINS``. No held-out episode is run: that is ``ship-gym benchmark``'s job.

Outputs (``--out``, default ``docs/benchmarks``): ``<stem>_tuning.csv`` (every grid point) and
``<stem>.json`` (final grid, chosen point and gains, where the optimum lies on each axis, the
widenings, the former gains on the same episodes); ``<stem>`` is ``<task>_baseline``
(``capsize_master`` for CapsizeAvoidance).

Usage::

    python scripts/tune_baseline.py CourseKeeping [--seeds 0 48] [--out docs/benchmarks]
"""

from __future__ import annotations

import argparse
import csv
import io
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
from ship_gym.agents.protocol import TUNING_SEEDS, check_choice_seeds, wilson_interval
from ship_gym.agents.tuning import Axis, one_standard_error_choice, tune_grid
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


def _master_settings(
    setup: Any, resonance_band: float, zone_margin: float, beam_limit_deg: float
) -> dict[str, Any]:
    return {
        "resonance_band": resonance_band,
        "zone_margin": zone_margin,
        "beam_limit_deg": beam_limit_deg,
        "zone_weights": (3.0, 0.5, 1.0, 1.0, 3.0),
    }


@dataclass(frozen=True)
class Design:
    """A baseline with open design choices and the grid that settles them."""

    env_id: str
    baseline: str
    metric: str
    axes: tuple[Axis, ...]
    former: dict[str, float]
    """The former choice (evaluated on the same episodes for comparison)."""
    gains: Callable[..., dict[str, Any]]
    stem: str


DESIGNS = {
    "RollStabilization": Design(
        "ship_gym/RollStabilization-v2",
        "fins",
        "rms_roll_deg",
        (
            Axis("added_damping", (0.4, 0.6, 0.8, 1.1, 1.5), lower=0.0),
            Axis("added_stiffness", (0.2, 0.5, 0.8, 1.2), lower=0.0),
        ),
        {"added_damping": 0.8, "added_stiffness": 0.5},
        _fin_gains,
        "RollStabilization_baseline",
    ),
    "CourseKeeping": Design(
        "ship_gym/CourseKeeping-v2",
        "pid",
        "rms_heading_error_deg",
        (
            Axis("natural_frequency", (0.06, 0.08, 0.1, 0.12, 0.14), lower=0.01),
            Axis("damping", (0.2, 0.3, 0.5, 0.7), lower=0.1),
        ),
        {"natural_frequency": 0.06, "damping": 0.7},
        _autopilot_gains,
        "CourseKeeping_baseline",
    ),
    "RideControl": Design(
        "ship_gym/RideControl-v2",
        "ride",
        "rms_vertical_acceleration_mps2",
        (
            Axis("heave_damping", (0.0, 0.02, 0.05), lower=0.0),
            Axis("pitch_damping", (0.01, 0.02, 0.03, 0.05, 0.08), lower=0.0),
        ),
        {"heave_damping": 0.0, "pitch_damping": 0.02},
        _ride_gains,
        "RideControl_baseline",
    ),
    "CapsizeAvoidance": Design(
        "ship_gym/CapsizeAvoidance-v2",
        "imo-guidance",
        "capsize_rate",
        (
            Axis("resonance_band", (0.1, 0.2, 0.3), lower=0.0, upper=0.9),
            Axis("zone_margin", (0.1, 0.2, 0.3), lower=0.0, upper=0.9),
            Axis("beam_limit_deg", (15.0, 20.0, 25.0), lower=5.0, upper=90.0),
        ),
        {"resonance_band": 0.2, "zone_margin": 0.2, "beam_limit_deg": 20.0},
        _master_settings,
        "capsize_master",
    ),
}


def _run(design: Design, gains: dict, seeds: list[int]) -> dict[str, Any]:
    t0 = time.perf_counter()
    try:
        stats = run_episodes(
            design.env_id, lambda env: make_baseline(design.baseline, env, **gains), seeds
        )
    except ValueError as exc:  # e.g. a negative derivative gain: not a controller
        return {"feasible": False, "why": str(exc), "capsized": len(seeds),
                "mean_return": -math.inf}  # fmt: skip
    metrics = summarize(stats)
    k = int(stats.capsized.sum())
    return {
        "returns": [float(x) for x in stats.returns],
        "feasible": True,
        design.metric: metrics[design.metric],
        "rms_action": metrics["rms_action"],
        "mean_return": metrics["mean_return"],
        "capsized": k,
        "capsize_ci95_high": wilson_interval(k, len(seeds))[1],
        "mean_cost": metrics["mean_cost"],
        "wall_s": time.perf_counter() - t0,
    }


def _feasible_gains(design: Design, setup: Any, point: dict) -> dict[str, Any] | str:
    try:
        gains = design.gains(setup, **point)
    except ValueError as exc:
        return str(exc)
    negative = [k for k, v in gains.items() if isinstance(v, float) and v < 0.0]
    return f"negative gains {negative}" if negative else gains


def _check(design: Design, out: Path, seeds: list[int]) -> int:
    """The chosen and the former point on validation episodes, added to the tuning json."""
    check_choice_seeds(seeds, "--check")
    path = out / f"{design.stem}.json"
    report = json.loads(path.read_text(encoding="utf-8"))
    env = gymnasium.make(design.env_id)
    unwrapped: Any = env.unwrapped
    setup = unwrapped.task.setup
    env.close()
    results: dict[str, Any] = {}
    for label, point in (("chosen", report["chosen"]), ("former", report["former"])):
        gains = design.gains(setup, **point)
        result = _run(design, gains, seeds)
        low, high = wilson_interval(int(result["capsized"]), len(seeds))
        result.pop("returns", None)
        results[label] = {**point, **result, "capsize_ci95": [low, high]}
        print(f"{label} {point}: {design.metric} {result.get(design.metric)}, effort "
              f"{result.get('rms_action')}, return {result['mean_return']:.1f}, capsized "
              f"{result['capsized']}/{len(seeds)} [{low:.3f}, {high:.3f}]")  # fmt: skip
    report["validation_check"] = {"seeds": [seeds[0], len(seeds)], **results}
    atomic_write_text(path, json.dumps(report, indent=2, default=str))
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("task", choices=sorted(DESIGNS), help="the ship task")
    parser.add_argument(
        "--seeds",
        nargs=2,
        type=int,
        default=(TUNING_SEEDS.start, len(TUNING_SEEDS)),
        metavar=("FIRST", "N"),
        help="tuning episodes (training or validation seeds only)",
    )
    parser.add_argument("--out", default="docs/benchmarks", help="output folder")
    parser.add_argument("--max-widenings", type=int, default=4)
    parser.add_argument(
        "--check",
        nargs=2,
        type=int,
        default=None,
        metavar=("FIRST", "N"),
        help="instead of tuning: run the chosen and the former point of <out>/<stem>.json on "
        "these validation episodes (capsizes are rare: 48 tuning episodes may not show them) "
        "and add the results to the json as 'validation_check'",
    )
    args = parser.parse_args()
    design = DESIGNS[args.task]
    if args.check is not None:
        return _check(design, Path(args.out), list(range(args.check[0], sum(args.check))))
    seeds = list(range(args.seeds[0], args.seeds[0] + args.seeds[1]))
    try:
        check_choice_seeds(seeds, "--seeds")
    except ValueError as exc:
        parser.error(str(exc))
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    env = gymnasium.make(design.env_id)
    unwrapped: Any = env.unwrapped
    setup = unwrapped.task.setup  # the ship, loading and speed of the default episodes
    env.close()

    def evaluate(point: dict) -> dict[str, Any]:
        gains = _feasible_gains(design, setup, point)
        if isinstance(gains, str):
            result: dict[str, Any] = {"feasible": False, "why": gains, "capsized": len(seeds),
                                      "mean_return": -math.inf}  # fmt: skip
        else:
            result = {**gains, **_run(design, gains, seeds)}
        shown = {k: (round(v, 4) if isinstance(v, float) else v) for k, v in result.items()
                 if k != "returns"}  # fmt: skip
        print(f"{point} → {shown}", flush=True)
        return result

    t0 = time.perf_counter()
    tuned = tune_grid(design.axes, evaluate, choose=one_standard_error_choice(design.metric),
                      max_widenings=args.max_widenings)  # fmt: skip
    best = tuned.best
    keys = [a.name for a in design.axes]
    chosen = {k: best[k] for k in keys}
    chosen_gains = design.gains(setup, **chosen)
    former_key = tuple(design.former[k] for k in keys)
    former = next((r for r in tuned.rows if tuple(r[k] for k in keys) == former_key), None)
    if former is None:
        former = {**design.former, **evaluate(dict(design.former))}
    columns: list[str] = []
    for row in tuned.rows:
        columns += [c for c in row if c not in columns and c != "returns"]
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=columns, extrasaction="ignore")
    writer.writeheader()
    writer.writerows(
        {k: (list(v) if isinstance(v, tuple) else v) for k, v in row.items()} for row in tuned.rows
    )
    atomic_write_text(out / f"{design.stem}_tuning.csv", buffer.getvalue())
    report = {
        "env_id": design.env_id,
        "baseline": design.baseline,
        "tuning_seeds": [seeds[0], len(seeds)],
        "criterion": "fewest capsizes on the tuning episodes, then the highest mean return; "
        "among the points within one standard error (paired, per episode) of that return, "
        "the lowest task metric",
        "grid": {k: list(v) for k, v in tuned.axes.items()},
        "bounds": {a.name: [a.lower, a.upper] for a in design.axes},
        "chosen": chosen,
        "chosen_gains": chosen_gains,
        "optimum_position": tuned.position,
        "optimum_inside": tuned.inside,
        "widenings": tuned.widenings,
        "chosen_result": {k: v for k, v in best.items() if k not in (*keys, "returns")},
        "former": design.former,
        "former_result": {k: v for k, v in former.items() if k not in (*keys, "returns")},
        "wall_s": time.perf_counter() - t0,
    }
    atomic_write_text(out / f"{design.stem}.json", json.dumps(report, indent=2, default=str))
    where = ", ".join(f"{k} {v}" for k, v in tuned.position.items())
    print(f"chosen on seeds {seeds[0]}…{seeds[-1]}: {chosen} → {chosen_gains} ({where})")
    print(
        f"  {design.metric} {best.get(design.metric)}, return {best['mean_return']:.1f}, "
        f"capsized {best['capsized']}; former {design.former}: return "
        f"{former['mean_return']:.1f}, capsized {former['capsized']}"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
