"""Tune the classical masters of HeavyWeather-v0 on training seeds until each optimum lies inside
its grid.

Coordinate search on the mean return (the task's reward: progress, dangerous roll and the
capsize penalty that makes a capsize never worth its progress) over episodes of the training
range (seeds 1000 … 1000 + episodes − 1; never the validation 5000 … or held-out 20 000 …
seeds of :mod:`ship_gym.agents.protocol`): each parameter in turn is set to the best value of
its grid, the others held; where the best value is at an end of the grid that is not a hard
limit, the grid is widened by one step beyond it and searched again (printed), so that the
reported optimum lies inside the grid searched. Passes repeat until none changes a parameter.

Writes ``docs/benchmarks/heavy_weather_masters.json`` (the tuned parameters, their grids, the
mean return / progress / capsize rate of the optimum) and
``heavy_weather_<master>_tuning.csv`` (every evaluation).

    python scripts/tune_heavy_weather_masters.py [--episodes 60] [--masters imo-guidance,polar]
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import time
from pathlib import Path
from typing import Any

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")


import ship_gym  # noqa: F401  (registers the ids)
from ship_gym.agents.baselines import make_baseline
from ship_gym.agents.evaluate import run_episodes, summarize

ROOT = Path(__file__).resolve().parents[1]
ENV_ID = "ship_gym/HeavyWeather-v0"
FIRST_SEED = 1000

# parameter: (grid, hard lower limit, hard upper limit) — a grid end at a hard limit needs no
# widening (the optimum there is the limit itself)
GRIDS: dict[str, dict[str, tuple[list[float], float, float]]] = {
    "imo-guidance": {
        "zone_margin": ([0.0, 0.1, 0.2, 0.3], 0.0, 0.9),
        "resonance_band": ([0.1, 0.2, 0.3], 0.0, 0.9),
        "beam_limit_deg": ([20.0, 45.0, 70.0, 90.0], 0.0, 90.0),
    },
    # the IMO zones' margin is the IMO master's tuned one (0: the guidance's own zones)
    "polar": {
        "risk_limit": ([0.003, 0.01, 0.03], 0.001, 1.0),
        "damping_ratio": ([0.03, 0.06, 0.12], 0.0, 1.0),
    },
}


def evaluate(master: str, params: dict[str, float], seeds: list[int]) -> dict[str, float]:
    """Mean return, voyage progress and capsize rate of a master on the seeds."""
    stats = run_episodes(ENV_ID, lambda env: make_baseline(master, env, **params), seeds)
    out = summarize(stats)
    return {k: out[k] for k in ("mean_return", "voyage_progress", "capsize_rate")}


def widened(grid: list[float], best: float, low: float, high: float) -> list[float] | None:
    """The grid extended one step beyond ``best`` if it is an end that is not a hard limit."""
    if best == grid[0] and grid[0] > low:
        step = grid[1] - grid[0]
        return [max(low, grid[0] - step), *grid]
    if best == grid[-1] and grid[-1] < high:
        step = grid[-1] - grid[-2]
        return [*grid, min(high, grid[-1] + step)]
    return None


def tune(
    master: str, seeds: list[int], rows: list[dict[str, Any]], passes: int = 4
) -> dict[str, Any]:
    """Coordinate search of one master (module docstring)."""
    grids = {k: list(v[0]) for k, v in GRIDS[master].items()}
    params = {k: g[len(g) // 2] for k, g in grids.items()}
    cache: dict[tuple[tuple[str, float], ...], dict[str, float]] = {}

    def score(p: dict[str, float]) -> dict[str, float]:
        key = tuple(sorted(p.items()))
        if key not in cache:
            t0 = time.perf_counter()
            cache[key] = evaluate(master, p, seeds)
            rows.append({"master": master, **p, **cache[key]})
            print(f"  {master} {p}: {cache[key]} ({time.perf_counter() - t0:.0f} s)", flush=True)
        return cache[key]

    for _ in range(passes):
        changed = False
        for name in grids:
            while True:
                values = grids[name]
                results = {v: score({**params, name: v})["mean_return"] for v in values}
                best = max(values, key=lambda v: results[v])
                _, low, high = GRIDS[master][name]
                wider = widened(values, best, low, high)
                if wider is None:
                    break
                print(f"  {master}: optimum {name} = {best} on the grid's edge: widened to {wider}")
                grids[name] = wider
            if best != params[name]:
                params[name], changed = best, True
        if not changed:
            break
    best_result = score(params)
    inside = {
        name: (grids[name][0] < params[name] < grids[name][-1])
        or params[name] in (GRIDS[master][name][1], GRIDS[master][name][2])
        for name in grids
    }
    return {"parameters": params, "grids": grids, "result": best_result, "inside_grid": inside}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--episodes", type=int, default=60)
    parser.add_argument("--masters", default="imo-guidance,polar")
    parser.add_argument("--passes", type=int, default=4, help="coordinate-search passes at most")
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "benchmarks")
    args = parser.parse_args()
    seeds = list(range(FIRST_SEED, FIRST_SEED + args.episodes))
    path = args.out / "heavy_weather_masters.json"
    out: dict[str, Any] = json.loads(path.read_text()) if path.exists() else {}
    if out.get("seeds") != [seeds[0], seeds[-1]]:
        out = {}  # another tuning set: start afresh
    if "keep" not in out:
        out["keep"] = evaluate("keep", {}, seeds)
        print(f"keep course and speed: {out['keep']}", flush=True)
    out.update({"env_id": ENV_ID, "seeds": [seeds[0], seeds[-1]], "criterion": "mean return"})
    for master in args.masters.split(","):
        rows: list[dict[str, Any]] = []
        out[master] = tune(master, seeds, rows, args.passes)
        print(f"{master}: {out[master]}", flush=True)
        args.out.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps(out, indent=2) + "\n")  # after each master
        table = args.out / f"heavy_weather_{master.replace('-', '_')}_tuning.csv"
        with open(table, "w", newline="") as fh:
            writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)
        print(f"wrote {path} and {table}")


if __name__ == "__main__":
    main()
