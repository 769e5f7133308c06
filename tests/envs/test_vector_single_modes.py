"""Batched == single in every mode (issue #35): the vector env against Gymnasium's own
SyncVectorEnv of single envs under TimeLimit, bit for bit, in both autoreset modes, with sensor
noise and with capsizes on the last step of the time limit (``terminated`` and ``truncated``
both True, Gymnasium's TimeLimit rule)."""

from __future__ import annotations

import numpy as np
import pytest
from gymnasium.vector import AutoresetMode, SyncVectorEnv
from gymnasium.wrappers import TimeLimit

from ._ship_env_checks import SHIP_ENVS

LIMIT = 10  # [control steps]: RollStabilization at full fin command and a 4° capsize angle
# capsizes on step 10 (seeds 0-5 checked), so those episodes end by both flags at once
KWARGS = {"sensor_noise": 0.5, "capsize_angle_deg": 4.0}


def _actions(n: int, steps: int, shape: tuple[int, ...]) -> np.ndarray:
    """Full command for every third episode (capsize on the last step), random for the others."""
    rng = np.random.default_rng(7)
    a = rng.uniform(-1.0, 1.0, (steps, *shape)).astype(np.float32)
    a[:, ::3] = 1.0
    return a


@pytest.mark.parametrize("mode", [AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP])
@pytest.mark.parametrize("n", [1, 2, 7, 64])
def test_vector_env_is_the_sync_vector_env_of_single_envs_with_noise_and_last_step_capsizes(
    n, mode
):
    case = SHIP_ENVS["RollStabilization"]
    steps = 2 * LIMIT + 5  # every episode ends and restarts at least twice
    vec = case.vector_env(n, max_episode_steps=LIMIT, autoreset_mode=mode, **KWARGS)
    sync = SyncVectorEnv(
        [lambda: TimeLimit(case.env(**KWARGS), LIMIT) for _ in range(n)], autoreset_mode=mode
    )
    try:
        obs_v, _ = vec.reset(seed=3)
        obs_s, _ = sync.reset(seed=3)
        np.testing.assert_array_equal(obs_v, obs_s)
        both = 0
        for k, a in enumerate(_actions(n, steps, vec.action_space.shape)):
            ov, rv, tv, uv, iv = vec.step(a)
            os_, rs, ts, us, is_ = sync.step(a)
            np.testing.assert_array_equal(ov, os_, err_msg=f"observations at step {k}")
            np.testing.assert_array_equal(rv, rs, err_msg=f"rewards at step {k}")
            np.testing.assert_array_equal(tv, ts, err_msg=f"terminated at step {k}")
            np.testing.assert_array_equal(uv, us, err_msg=f"truncated at step {k}")
            if mode == AutoresetMode.SAME_STEP and (tv | uv).any():
                for i in np.flatnonzero(tv | uv):
                    np.testing.assert_array_equal(iv["final_obs"][i], is_["final_obs"][i])
            both += int(np.sum(tv & uv))
        assert both >= 2, "the test needs capsizes on the last step"
    finally:
        vec.close()
        sync.close()


@pytest.mark.parametrize("mode", [AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP])
def test_course_keeping_noise_after_an_autoreset_is_the_single_envs(mode):
    # the audit's case: sensor_noise = 0.5, N = 7; the step that waits for a NEXT_STEP reset
    # must not draw from the episode's generator
    case, n, limit = SHIP_ENVS["CourseKeeping"], 7, 4
    vec = case.vector_env(n, max_episode_steps=limit, autoreset_mode=mode, sensor_noise=0.5)
    sync = SyncVectorEnv(
        [lambda: TimeLimit(case.env(sensor_noise=0.5), limit) for _ in range(n)],
        autoreset_mode=mode,
    )
    try:
        np.testing.assert_array_equal(vec.reset(seed=11)[0], sync.reset(seed=11)[0])
        rng = np.random.default_rng(2)
        for k in range(3 * limit + 2):
            a = rng.uniform(-1.0, 1.0, vec.action_space.shape).astype(np.float32)
            for x, y in zip(vec.step(a)[:4], sync.step(a)[:4], strict=True):
                np.testing.assert_array_equal(x, y, err_msg=f"step {k}")
    finally:
        vec.close()
        sync.close()
