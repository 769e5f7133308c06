"""Environment throughput: single env, our batched vector env, and Gymnasium's SyncVectorEnv.

For every registered id (or ``--ids``) this measures, in one run:

* **single** — ``gymnasium.make(id)`` (the registered TimeLimit and checkers included), env steps
  per second over ``--steps`` steps;
* **vector** — ``gymnasium.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")``:
  our :class:`ship_gym.envs.base.TaskVectorEnv`, all N episodes in one batched call;
* **sync** — ``gymnasium.make_vec(id, num_envs=N, vectorization_mode="sync")``: Gymnasium's
  ``SyncVectorEnv`` looping over N single envs,

for each N of ``--n`` (default 1, 16, 64), and prints a table with the ratio vector / sync. Steps
per second count env steps (N per vector step). Actions are uniform random in [-1, 1] from a fixed
seed; episodes that end are reset (autoreset), and that cost is included, as in training. The
first reset and 5 steps (numba compilation, caches) are not timed. Times are wall-clock
(``time.perf_counter``) with the process' default thread settings; the CPU time
(``time.process_time``) is reported too, since shared machines make wall time noisy.

``--json PATH`` writes ``{id: single_sps, ..., "single": {id: sps},
"vector_steps_per_s": {id: {N: sps}}, "sync_vector_steps_per_s": {id: {N: sps}},
"cpu_time": {...}, "conditions": {...}}``.

Usage::

    python benchmarks/bench_envs.py --ids ship_gym/RollOneDOF-v0 --steps 2000 --n 1 16 64
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
import traceback
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import gymnasium
import numpy as np

import ship_gym  # noqa: F401  (registers the ids)
from ship_gym.envs import ENV_IDS
from ship_gym.io_utils import atomic_write_text

WARMUP_STEPS = 5


def _timed(run: Callable[[], int]) -> tuple[float, float, int]:
    """(wall [s], CPU [s], env steps) of ``run()``."""
    w0, c0 = time.perf_counter(), time.process_time()
    steps = run()
    return time.perf_counter() - w0, time.process_time() - c0, steps


def bench_single(env_id: str, steps: int, seed: int = 0) -> tuple[float, float]:
    """(env steps/s wall, env steps/s CPU) of ``gymnasium.make(env_id)``."""
    env = gymnasium.make(f"ship_gym:{env_id}")
    rng = np.random.default_rng(seed)
    shape = env.action_space.shape
    actions = rng.uniform(-1.0, 1.0, (steps + WARMUP_STEPS, *shape)).astype(np.float32)
    env.reset(seed=seed)
    for a in actions[:WARMUP_STEPS]:
        _, _, terminated, truncated, _ = env.step(a)
        if terminated or truncated:
            env.reset()

    def run() -> int:
        for a in actions[WARMUP_STEPS:]:
            _, _, terminated, truncated, _ = env.step(a)
            if terminated or truncated:
                env.reset()
        return steps

    wall, cpu, n = _timed(run)
    env.close()
    return n / wall, n / max(cpu, 1e-12)


def bench_engine(env_id: str, steps: int, seed: int = 0) -> float | None:
    """Engine-only rate [control steps/s] of a ship env's physics: its engine's
    ``advance(substeps)`` with the env's commands held, on the env's own simulator after a
    reset (None for an env without a 6-DOF engine)."""
    env = gymnasium.make(f"ship_gym:{env_id}")
    env.reset(seed=seed)
    task = getattr(env.unwrapped, "task", None)
    if task is None or not hasattr(task, "sim"):
        env.close()
        return None
    sim = task.sim
    for _ in range(WARMUP_STEPS):
        sim.advance(task.substeps, task.commands, danger_roll=task.dangerous_roll)

    def run() -> int:
        for _ in range(steps):
            sim.advance(task.substeps, task.commands, danger_roll=task.dangerous_roll)
        return steps

    wall, _, n = _timed(run)
    env.close()
    return n / wall


def bench_vector(
    env_id: str, num_envs: int, mode: str, steps: int, seed: int = 0, threads: int = 1
) -> tuple[float, float]:
    """(env steps/s wall, env steps/s CPU) of ``make_vec(env_id, num_envs, mode)``.

    ``steps`` is the env-step budget: ``max(steps // num_envs, 10)`` vector steps are timed.
    ``threads`` > 1 passes ``num_threads`` to a ship env's batched vector env.
    """
    kwargs: dict[str, Any] = {}
    if threads > 1 and mode == "vector_entry_point" and "RollOneDOF" not in env_id:
        kwargs["num_threads"] = threads
    env = gymnasium.make_vec(
        f"ship_gym:{env_id}", num_envs=num_envs, vectorization_mode=mode, **kwargs
    )
    vector_steps = max(steps // num_envs, 10)
    rng = np.random.default_rng(seed)
    shape = env.action_space.shape
    actions = rng.uniform(-1.0, 1.0, (vector_steps + WARMUP_STEPS, *shape)).astype(np.float32)
    env.reset(seed=seed)
    for a in actions[:WARMUP_STEPS]:
        env.step(a)  # autoreset (NEXT_STEP) inside the vector env

    def run() -> int:
        for a in actions[WARMUP_STEPS:]:
            env.step(a)
        return vector_steps * num_envs

    wall, cpu, n = _timed(run)
    env.close()
    return n / wall, n / max(cpu, 1e-12)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ids", nargs="*", default=list(ENV_IDS), help="env ids (default: all)")
    parser.add_argument("--steps", type=int, default=1000, help="env steps per measurement")
    parser.add_argument("--n", nargs="*", type=int, default=[1, 16, 64], help="vector sizes N")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--json", default=None, help="write the numbers to this JSON file")
    parser.add_argument(
        "--threads", type=int, default=1, help="numba threads of the batched ship envs"
    )
    parser.add_argument("--no-sync", action="store_true", help="skip SyncVectorEnv")
    args = parser.parse_args(argv)
    if args.steps < 1 or any(n < 1 for n in args.n):
        parser.error("--steps and every --n must be positive")
    unknown = [i for i in args.ids if i not in ENV_IDS]
    if unknown:
        parser.error(f"unknown ids {unknown}; registered: {list(ENV_IDS)}")

    single: dict[str, float] = {}
    vector: dict[str, dict[str, float]] = {}
    sync: dict[str, dict[str, float]] = {}
    cpu: dict[str, Any] = {"single": {}, "vector": {}, "sync": {}}
    failed: dict[str, str] = {}
    engine: dict[str, float] = {}
    for env_id in args.ids:
        try:
            rate = bench_engine(env_id, args.steps, args.seed)
            if rate is not None:
                engine[env_id] = rate
            single[env_id], cpu["single"][env_id] = bench_single(env_id, args.steps, args.seed)
            vector[env_id], sync[env_id] = {}, {}
            cpu["vector"][env_id], cpu["sync"][env_id] = {}, {}
            for n in args.n:
                key = str(n)
                vector[env_id][key], cpu["vector"][env_id][key] = bench_vector(
                    env_id, n, "vector_entry_point", args.steps, args.seed, args.threads
                )
                if args.no_sync:
                    sync[env_id][key], cpu["sync"][env_id][key] = float("nan"), float("nan")
                    continue
                sync[env_id][key], cpu["sync"][env_id][key] = bench_vector(
                    env_id, n, "sync", args.steps, args.seed
                )
        except Exception as exc:  # an env not written yet or broken: report, go on
            failed[env_id] = f"{type(exc).__name__}: {exc}"
            traceback.print_exc(limit=2)
            single.pop(env_id, None)
            vector.pop(env_id, None)
            sync.pop(env_id, None)

    print(
        f"env steps/s (wall clock; {args.steps} env steps per measurement; "
        f"{os.cpu_count()} CPUs, numba threads {os.environ.get('NUMBA_NUM_THREADS', 'default')})"
    )
    header = f"{'env id':34s} {'single':>9s}"
    for n in args.n:
        header += f" | N={n:<3d} {'vector':>9s} {'sync':>9s} {'ratio':>6s}"
    print(header)
    for env_id in single:
        row = f"{env_id:34s} {single[env_id]:9.0f}"
        for n in args.n:
            v, s = vector[env_id][str(n)], sync[env_id][str(n)]
            row += f" |       {v:9.0f} {s:9.0f} {v / s:6.2f}"
        print(row)
    for env_id, why in failed.items():
        print(f"{env_id:34s} unavailable: {why}")
    if engine:
        print("\nsingle env vs its engine alone (advance(substeps) with the commands held):")
        for env_id, rate in engine.items():
            if env_id in single:
                print(
                    f"{env_id:34s} engine {rate:8.0f} steps/s, env {single[env_id]:8.0f} steps/s: "
                    f"env step = {rate / single[env_id]:.2f} × the engine's cost"
                )

    if args.json:
        payload: dict[str, Any] = dict(single)
        payload.update(
            {
                "single": single,
                "engine_steps_per_s": engine,
                "vector_steps_per_s": vector,
                "sync_vector_steps_per_s": sync,
                "cpu_time_steps_per_s": cpu,
                "failed": failed,
                "conditions": {
                    "steps": args.steps,
                    "n": args.n,
                    "seed": args.seed,
                    "cpu_count": os.cpu_count(),
                    "platform": platform.platform(),
                    "python": platform.python_version(),
                    "numba_num_threads": os.environ.get("NUMBA_NUM_THREADS"),
                    "threads": args.threads,
                    "actions": "uniform random in [-1, 1]",
                },
            }
        )
        atomic_write_text(Path(args.json), json.dumps(payload, indent=2))
        print(f"wrote {args.json}")
    return 1 if failed and not single else 0


if __name__ == "__main__":
    raise SystemExit(main())
