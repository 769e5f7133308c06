"""Speed of the ship-task environments: build time and env steps per second (process time).

For CourseKeeping-v2 and CapsizeAvoidance-v2 (default S175 mesh unless ``--coarse``): the
first build in this process (hull, database, state-space fit, GZ curve, Nomoto identification,
numba cache load), a second build (cached prototype, deep copy), then random-action steps of
the single env and of the vector env with N = 16, timed with ``time.process_time()`` (CPU time
of this process: less sensitive to other jobs on a shared machine than wall time). Prints the
vector/single throughput ratio measured in the same run; ``--json PATH`` writes the numbers.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np


def _measure(env_cls, vec_cls, kwargs: dict, steps: int, n_vec: int) -> dict[str, float]:
    t0 = time.process_time()
    env = env_cls(**kwargs)
    first_build = time.process_time() - t0
    t0 = time.process_time()
    env_cls(**kwargs)
    second_build = time.process_time() - t0
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    n_act = env.action_space.shape[0]
    t0 = time.process_time()
    for _ in range(steps):
        _, _, term, _, _ = env.step(rng.uniform(-0.3, 0.3, n_act))
        if term:
            env.reset()
    single = steps / (time.process_time() - t0)
    venv = vec_cls(num_envs=n_vec, **kwargs)
    venv.reset(seed=0)
    n_vec_steps = max(steps // 4, 10)
    t0 = time.process_time()
    for _ in range(n_vec_steps):
        venv.step(rng.uniform(-0.3, 0.3, (n_vec, n_act)))
    vector = n_vec * n_vec_steps / (time.process_time() - t0)
    return {
        "first_build_s": first_build,
        "second_build_s": second_build,
        "single_env_steps_per_s": single,
        f"vector_env_N{n_vec}_env_steps_per_s": vector,
        "vector_over_single": vector / single,
    }


def main(argv: list[str] | None = None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=200, help="single-env control steps")
    parser.add_argument("--num-envs", type=int, default=16, help="vector env size")
    parser.add_argument("--coarse", action="store_true", help="coarse S175 mesh (24 sections)")
    parser.add_argument("--json", type=str, default=None, help="write the numbers here")
    args = parser.parse_args(argv)
    from ship_gym.envs.capsize_avoidance import CapsizeAvoidanceEnv, CapsizeAvoidanceVectorEnv
    from ship_gym.envs.course_keeping import CourseKeepingEnv, CourseKeepingVectorEnv

    kwargs = {"hull_mesh": (24, 6, 3, 2)} if args.coarse else {}
    results = {}
    for name, env_cls, vec_cls in (
        ("CourseKeeping-v2", CourseKeepingEnv, CourseKeepingVectorEnv),
        ("CapsizeAvoidance-v2", CapsizeAvoidanceEnv, CapsizeAvoidanceVectorEnv),
    ):
        r = _measure(env_cls, vec_cls, kwargs, args.steps, args.num_envs)
        results[name] = r
        print(
            f"{name:22s} build {r['first_build_s']:6.2f} s (again {r['second_build_s']:.3f} s); "
            f"single {r['single_env_steps_per_s']:7.1f} steps/s; N={args.num_envs} "
            f"{r[f'vector_env_N{args.num_envs}_env_steps_per_s']:7.1f} env-steps/s "
            f"(×{r['vector_over_single']:.2f}) [process time]"
        )
    if args.json:
        from ship_gym.io_utils import atomic_write_text

        atomic_write_text(args.json, json.dumps(results, indent=2))
    return results


if __name__ == "__main__":
    main()
