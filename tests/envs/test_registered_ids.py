"""Every registered id through Gymnasium's own entry points (make, make_vec, TimeLimit).

The per-environment physics, reward and checker tests live next to each environment; these
check what a user of the registry sees, for all ids alike.
"""

from __future__ import annotations

import json
import subprocess
import sys

import gymnasium
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import ship_gym  # noqa: F401 - registers the ids
from ship_gym.envs.base import TaskVectorEnv
from ship_gym.envs.registration import ENTRIES, ENV_IDS


def test_every_entry_is_registered_with_its_time_limit():
    for entry in ENTRIES:
        spec = gymnasium.spec(entry.id)
        assert spec.entry_point == entry.entry_point
        assert spec.vector_entry_point == entry.vector_entry_point
        assert spec.max_episode_steps == entry.max_episode_steps


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_make_with_module_prefix_in_a_fresh_interpreter(env_id):
    """``gymnasium.make("ship_gym:<id>")`` works with no prior import; seeded resets agree
    across processes (the same first observation, bit for bit)."""
    code = (
        "import gymnasium, json; "
        f"env = gymnasium.make('ship_gym:{env_id}'); "
        "obs, _ = env.reset(seed=7); "
        "print(json.dumps([float(x) for x in obs]))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=300
    )
    obs_child = np.array(json.loads(out.stdout.strip().splitlines()[-1]))
    env = gymnasium.make(env_id)
    obs, _ = env.reset(seed=7)
    np.testing.assert_array_equal(obs.astype(np.float64), obs_child)
    env.close()


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_time_limit_truncates(env_id):
    env = gymnasium.make(env_id, max_episode_steps=3)
    env.reset(seed=0)
    flags = [env.step(np.zeros(env.action_space.shape, np.float32))[2:4] for _ in range(3)]
    env.close()
    assert flags[-1] == (False, True), "the third step must be truncated, not terminated"
    assert all(f == (False, False) for f in flags[:-1])


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_vector_entry_point_matches_sync_vector_env(env_id):
    """make_vec's batched env and Gymnasium's SyncVectorEnv give the same episodes for the same
    seeds (episode i seeded s + i in both)."""
    n, steps = 2, 4
    batched = gymnasium.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point")
    assert isinstance(batched.unwrapped, TaskVectorEnv)
    assert batched.metadata["autoreset_mode"] == AutoresetMode.NEXT_STEP
    sync = gymnasium.make_vec(env_id, num_envs=n, vectorization_mode="sync")
    ob_b, _ = batched.reset(seed=3)
    ob_s, _ = sync.reset(seed=3)
    np.testing.assert_allclose(ob_b, ob_s, rtol=1e-6, atol=1e-6)
    rng = np.random.default_rng(1)
    for _ in range(steps):
        a = rng.uniform(-1, 1, batched.action_space.shape).astype(np.float32)
        ob_b, r_b, *_ = batched.step(a)
        ob_s, r_s, *_ = sync.step(a)
        # same arithmetic except the batch axis: rounding-level differences only
        np.testing.assert_allclose(ob_b, ob_s, rtol=1e-5, atol=1e-6)
        np.testing.assert_allclose(r_b, r_s, rtol=1e-9, atol=1e-9)
    batched.close()
    sync.close()
