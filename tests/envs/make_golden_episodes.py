"""Record ``tests/data/golden_episodes.npz``: the registered environments' episodes, frozen.

For each case (an id with keyword arguments) the environment is reset with a fixed seed and
stepped with fixed actions uniform in [-1, 1]; after ``STEPS`` steps it is reset again without a
seed (the generator goes on) and stepped ``STEPS`` more. Every observation, reward, reward term,
cost, termination and truncation flag and the reset infos are stored, with the observation
names and bounds. ``tests/envs/test_golden_episodes.py`` checks that the environments still
produce them to the last bit: the task layer may be refactored, the behaviour of the ids not.

Rerun only on purpose (a change of an id's behaviour, which bumps its version), from the
repository root::

    python tests/envs/make_golden_episodes.py
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import gymnasium
import numpy as np

import ship_gym  # noqa: F401  (registers the ids)

DATA = Path(__file__).resolve().parents[1] / "data" / "golden_episodes.npz"
STEPS = 25
"""Control steps per episode (two episodes per case)."""
SEED = 31
COARSE = {"hull_mesh": (24, 6, 3, 2), "n_wave_components": 20}

CASES: dict[str, tuple[str, dict[str, Any]]] = {
    # name: (id, keyword arguments); the -v2 cases at the defaults (coarse mesh), the -v3 ones
    # with every sampler option (speed, loading, noise, preview) so the whole layer is covered
    "CourseKeeping-v2": ("ship_gym/CourseKeeping-v2", {**COARSE}),
    "CourseKeeping-v3": (
        "ship_gym/CourseKeeping-v3",
        {
            **COARSE,
            "speed_range_mps": (8.0, 9.5),
            "gm_range_m": (0.8, 1.2),
            "sensor_noise": 1.0,
            "wave_preview_m": (50.0, 100.0),
        },
    ),
    "CourseKeeping-v3-increment": (
        "ship_gym/CourseKeeping-v3",
        {**COARSE, "rudder_mode": "increment", "capsize_angle_deg": 40.0},
    ),
    "RollStabilization-v2": ("ship_gym/RollStabilization-v2", {**COARSE}),
    "RollStabilization-v3": (
        "ship_gym/RollStabilization-v3",
        {
            **COARSE,
            "rudder_roll_stabilization": True,
            "gm_range_m": (0.7, 1.1),
            "sensor_noise": 0.5,
            "wave_preview_m": ((0.0, 60.0), (40.0, -30.0)),
        },
    ),
    "RideControl-v2": ("ship_gym/RideControl-v2", {**COARSE}),
    "RideControl-v3": (
        "ship_gym/RideControl-v3",
        {**COARSE, "speed_range_mps": (10.5, 12.5), "sensor_noise": 1.0},
    ),
    "CapsizeAvoidance-v2": ("ship_gym/CapsizeAvoidance-v2", {"hull_mesh": (24, 6, 3, 2)}),
    "CapsizeAvoidance-v3": (
        "ship_gym/CapsizeAvoidance-v3",
        {"hull_mesh": (24, 6, 3, 2), "gm_range_m": (0.6, 1.0), "sensor_noise": 1.0},
    ),
    "RollOneDOF-v0": ("ship_gym/RollOneDOF-v0", {"roll_noise_std": 0.01}),
}


def record(env_id: str, kwargs: dict[str, Any], steps: int = STEPS) -> dict[str, np.ndarray]:
    """The arrays of one case (module docstring): ``obs`` (2, steps + 1, n_obs), ``reward``,
    ``cost``, ``terminated``, ``truncated`` (2, steps), ``terms`` (2, steps, n_terms),
    ``reset_info`` (2, n_keys), ``names``, ``term_names``, ``reset_keys``, ``low``, ``high``.
    Steps after an episode ended are NaN (obs, reward, cost, terms) and False (flags)."""
    env = gymnasium.make(env_id, disable_env_checker=True, **kwargs).unwrapped
    rng = np.random.default_rng(1234)
    actions = rng.uniform(-1.0, 1.0, (2, steps, *env.action_space.shape)).astype(np.float32)
    n_obs = env.observation_space.shape[0]
    obs_all = np.full((2, steps + 1, n_obs), np.nan, dtype=np.float32)
    reward = np.full((2, steps), np.nan)
    cost = np.full((2, steps), np.nan)
    terminated = np.zeros((2, steps), dtype=bool)
    truncated = np.zeros((2, steps), dtype=bool)
    term_names: list[str] = []
    terms: list[list[list[float]]] = [[], []]
    reset_infos: list[dict[str, float]] = []
    for e in range(2):
        obs, info = env.reset(seed=SEED if e == 0 else None)
        reset_infos.append({k: float(v) for k, v in info.items() if np.ndim(v) == 0})
        obs_all[e, 0] = obs
        for k in range(steps):
            obs, r, term, trunc, info = env.step(actions[e, k])
            obs_all[e, k + 1] = obs
            reward[e, k] = r
            cost[e, k] = info.get("cost", np.nan)
            terminated[e, k] = term
            truncated[e, k] = trunc
            row = {key: float(v) for key, v in info.items() if key.startswith("reward_")}
            if not term_names:
                term_names = list(row)
            terms[e].append([row[t] for t in term_names])
            if term or trunc:
                break
    n_terms = len(term_names)
    terms_arr = np.full((2, steps, n_terms), np.nan)
    for e in range(2):
        if terms[e]:
            terms_arr[e, : len(terms[e])] = np.array(terms[e])
    keys = sorted(reset_infos[0])
    env.close()
    return {
        "obs": obs_all,
        "reward": reward,
        "cost": cost,
        "terminated": terminated,
        "truncated": truncated,
        "terms": terms_arr,
        "reset_info": np.array([[ri[k] for k in keys] for ri in reset_infos]),
        "names": np.array(getattr(env, "observation_names", ()), dtype=str),
        "term_names": np.array(term_names, dtype=str),
        "reset_keys": np.array(keys, dtype=str),
        "low": env.observation_space.low,
        "high": env.observation_space.high,
    }


VECTOR_CASE = (
    "ship_gym/CourseKeeping-v3",
    {**COARSE, "speed_range_mps": (8.0, 9.5), "gm_range_m": (0.8, 1.2), "sensor_noise": 1.0},
)
"""A vector env of 3 episodes (seeds s + i, one engine call for all): ``VECTOR_STEPS`` steps."""
VECTOR_STEPS = 10


def record_vector(env_id: str, kwargs: dict[str, Any]) -> dict[str, np.ndarray]:
    """``obs`` (steps + 1, 3, n_obs), ``reward``, ``cost``, ``terminated`` (steps, 3) of the
    vector env of ``env_id`` (autoreset after an ending, as the vector env does)."""
    env = gymnasium.make_vec(env_id, num_envs=3, vectorization_mode="vector_entry_point", **kwargs)
    rng = np.random.default_rng(99)
    actions = rng.uniform(-1.0, 1.0, (VECTOR_STEPS, *env.action_space.shape)).astype(np.float32)
    obs, _ = env.reset(seed=SEED)
    out_obs, out_r, out_c, out_t = [obs], [], [], []
    for k in range(VECTOR_STEPS):
        obs, r, term, _, info = env.step(actions[k])
        out_obs.append(obs)
        out_r.append(r)
        out_c.append(info["cost"])
        out_t.append(term)
    env.close()
    return {
        "obs": np.array(out_obs),
        "reward": np.array(out_r),
        "cost": np.array(out_c),
        "terminated": np.array(out_t),
    }


def main() -> None:
    arrays: dict[str, np.ndarray] = {}
    for key, value in record_vector(*VECTOR_CASE).items():
        arrays[f"vector/{key}"] = value
    for name, (env_id, kwargs) in CASES.items():
        for key, value in record(env_id, kwargs).items():
            arrays[f"{name}/{key}"] = value
        print(name, "recorded", file=sys.stderr)
    commit = subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True, check=False
    ).stdout.strip()
    arrays["commit"] = np.array(commit)
    np.savez_compressed(DATA, **arrays)  # type: ignore[arg-type]
    print(f"wrote {DATA} (code of {commit})", file=sys.stderr)


if __name__ == "__main__":
    main()
