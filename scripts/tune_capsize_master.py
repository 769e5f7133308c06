#!/usr/bin/env python
"""Tune the rule-based master of CapsizeAvoidance (the IMO guidance MSC.1/Circ.1228) on training
seeds, then evaluate it and keep-course-and-speed on held-out seeds.

:class:`ship_gym.agents.baselines.IMOGuidanceMaster` has four tuning choices the guidance leaves
open: how close to resonance counts as "nearly equal" (``resonance_band``), how much to widen the
surf-riding and high-wave zones (``zone_margin``), how far off the stern steep waves may come
(``beam_limit_deg``) and how much worse a high-wave encounter is than the other zones (the second
of ``zone_weights``). A grid of them runs on the training seeds (default 0–39, one episode each
on ``ship_gym/CapsizeAvoidance-v2`` with its default episode distribution); the best mean return
(progress, dangerous roll and the capsize penalty together) is kept. The tuned master and the zero
action (keep course and speed) then run on the held-out seeds (default 10 000–10 059), never used
in tuning, and their capsize rate (Wilson 95 %), return, progress and cost are reported.

Outputs (``--out``, default ``docs/benchmarks``): ``capsize_master_tuning.csv`` (every grid point),
``capsize_master.json`` (the chosen parameters and the held-out results).

Usage::

    python scripts/tune_capsize_master.py [--train-seeds 0 40] [--test-seeds 10000 60]
                                          [--out docs/benchmarks]
"""

from __future__ import annotations

import argparse
import csv
import io
import itertools
import json
import time
from pathlib import Path

import ship_gym  # noqa: F401  (registers the ids)
from ship_gym.agents.baselines import IMOGuidanceMaster, make_baseline
from ship_gym.agents.evaluate import run_episodes, summarize
from ship_gym.analysis.capsize_statistics import wilson_interval
from ship_gym.io_utils import atomic_write_text

ENV_ID = "ship_gym/CapsizeAvoidance-v2"
GRID = {
    "resonance_band": (0.1, 0.2),
    "zone_margin": (0.0, 0.2),
    "beam_limit_deg": (15.0, 20.0, 30.0),
    "high_wave_weight": (0.5, 1.0),
}


def _gains(point: dict) -> dict:
    weights = list(IMOGuidanceMaster.zone_weights)
    weights[1] = point["high_wave_weight"]
    gains = {k: v for k, v in point.items() if k != "high_wave_weight"}
    gains["zone_weights"] = tuple(weights)
    return gains


def _run(name: str, gains: dict, seeds: list[int]) -> dict:
    t0 = time.perf_counter()
    stats = run_episodes(ENV_ID, lambda env: make_baseline(name, env, **gains), seeds)
    metrics = summarize(stats)
    k, n = int(stats.capsized.sum()), len(seeds)
    low, high = wilson_interval(k, n)
    return {
        "capsized": k,
        "episodes": n,
        "capsize_rate": k / n,
        "capsize_ci95": [low, high],
        "mean_return": metrics["mean_return"],
        "progress_per_step": float((stats.returns / stats.lengths).mean()),
        "mean_cost": metrics["mean_cost"],
        "mean_length": metrics["mean_length"],
        "wall_s": time.perf_counter() - t0,
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--train-seeds", nargs=2, type=int, default=(0, 40), metavar=("FIRST", "N"))
    parser.add_argument(
        "--test-seeds", nargs=2, type=int, default=(10_000, 60), metavar=("FIRST", "N")
    )
    parser.add_argument("--out", default="docs/benchmarks", help="output folder")
    args = parser.parse_args()
    train = list(range(args.train_seeds[0], args.train_seeds[0] + args.train_seeds[1]))
    test = list(range(args.test_seeds[0], args.test_seeds[0] + args.test_seeds[1]))
    if set(train) & set(test):
        parser.error("--train-seeds and --test-seeds overlap; held-out seeds must be new")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    rows = []
    keys = list(GRID)
    points = [dict(zip(keys, values, strict=True)) for values in itertools.product(*GRID.values())]
    from tqdm.auto import tqdm

    for point in tqdm(points, desc="grid", unit="point"):
        result = _run("imo-guidance", _gains(point), train)
        rows.append({**point, **{k: v for k, v in result.items() if k != "capsize_ci95"}})
    best = max(rows, key=lambda r: r["mean_return"])
    chosen = {k: best[k] for k in keys}
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
    atomic_write_text(out / "capsize_master_tuning.csv", buffer.getvalue())

    held_out = {
        "zero (keep course and speed)": _run("zero", {}, test),
        "imo-guidance (tuned)": _run("imo-guidance", _gains(chosen), test),
        "imo-guidance (untuned defaults of the guidance)": _run(
            "imo-guidance",
            {
                "resonance_band": 0.2,
                "zone_margin": 0.0,
                "beam_limit_deg": 90.0,
                "zone_weights": (1.0, 1.0, 1.0, 1.0, 1.0),
            },
            test,
        ),
    }
    report = {
        "env_id": ENV_ID,
        "train_seeds": [train[0], len(train)],
        "test_seeds": [test[0], len(test)],
        "grid": GRID,
        "chosen": chosen,
        "chosen_train_return": best["mean_return"],
        "held_out": held_out,
    }
    atomic_write_text(out / "capsize_master.json", json.dumps(report, indent=2))
    print(f"chosen on seeds {train[0]}…{train[-1]}: {chosen} (return {best['mean_return']:.0f})")
    for name, r in held_out.items():
        lo, hi = r["capsize_ci95"]
        print(
            f"{name:48s} capsize {r['capsized']}/{r['episodes']} [{lo:.2f}, {hi:.2f}]  "
            f"return {r['mean_return']:.0f}  progress/step {r['progress_per_step']:.3f}  "
            f"cost {r['mean_cost']:.1f}"
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
