"""ship_gym/CourseKeeping-v0: API checks, determinism, rewards, termination, vector env.

A coarse S175 mesh (24 sections, 864 panels; GM and vanishing angle within 2 % and 0.1° of the
default mesh) keeps the rollouts fast; the simulator is built once per process and copied.
"""

import warnings

import gymnasium
import numpy as np
import pytest

import ship_gym  # noqa: F401  (registers the ids)
from ship_gym.envs.course_keeping import (
    MAX_EPISODE_STEPS,
    CourseKeepingEnv,
    CourseKeepingVectorEnv,
)

COARSE = {"hull_mesh": (24, 6, 3, 2), "n_wave_components": 20}


def _env(**kwargs) -> CourseKeepingEnv:
    return CourseKeepingEnv(**{**COARSE, **kwargs})


def _rollout(env, seed: int, n: int, action_seed: int = 0):
    rng = np.random.default_rng(action_seed)
    obs, _ = env.reset(seed=seed)
    out = [obs]
    rewards = []
    for _ in range(n):
        obs, r, term, trunc, _ = env.step(env.action_space.sample() * 0 + rng.uniform(-1, 1, 1))
        out.append(obs)
        rewards.append(r)
        if term or trunc:
            break
    return np.array(out), np.array(rewards)


def test_gymnasium_check_env_without_warnings():
    from gymnasium.utils.env_checker import check_env

    env = _env()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env, skip_render_check=True)
    assert [str(w.message) for w in caught] == []


def test_sb3_check_env_without_warnings():
    from stable_baselines3.common.env_checker import check_env

    env = _env()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(env, warn=True)
    assert [str(w.message) for w in caught] == []


def test_seeded_rollouts_identical_across_instances():
    a_obs, a_rew = _rollout(_env(), seed=11, n=12)
    b_obs, b_rew = _rollout(_env(), seed=11, n=12)
    np.testing.assert_array_equal(a_obs, b_obs)
    np.testing.assert_array_equal(a_rew, b_rew)
    c_obs, _ = _rollout(_env(), seed=12, n=2)
    assert not np.array_equal(a_obs[:3], c_obs)  # another seed, another sea and set-point


def test_reward_is_sum_of_terms_and_observations_inside_space():
    env = _env(sensor_noise=1.0, wave_preview_m=(50.0, 100.0))
    obs, info = env.reset(seed=3)
    assert env.observation_space.contains(obs)
    assert {"wave_height_m", "wave_period_s", "wave_heading_deg", "gm_m"} <= info.keys()
    rng = np.random.default_rng(1)
    for _ in range(15):
        obs, reward, term, _trunc, info = env.step(rng.uniform(-1, 1, 1).astype(np.float32))
        terms = {k: v for k, v in info.items() if k.startswith("reward_")}
        assert set(terms) == {"reward_heading", "reward_rudder", "reward_roll", "reward_capsize"}
        # summed in the same order as the task: exact to rounding of the float sum
        assert reward == pytest.approx(sum(terms.values()), rel=1e-12, abs=1e-12)
        assert np.all(np.isfinite(obs)) and env.observation_space.contains(obs)
        assert 0.0 <= info["cost"] <= 1.0
        assert not term


@pytest.mark.slow
def test_long_random_rollout_stays_finite_and_inside_space():
    env = _env()
    env.reset(seed=5)
    for _ in range(400):
        obs, reward, term, _, info = env.step(env.action_space.sample())
        assert np.isfinite(reward) and env.observation_space.contains(obs)
        if term:
            assert info["capsized"]
            break


def test_capsize_terminates_with_penalty():
    # beam seas and a capsize angle of 0.5°: the first roll beyond it ends the episode
    env = _env(capsize_angle_deg=0.5, wave_heading_range_deg=(90.0, 90.0), wave_ramp_time_s=0.0)
    _, info = env.reset(seed=0)
    assert info["capsize_angle_deg"] == pytest.approx(0.5)
    for k in range(200):  # noqa: B007 (k read after the loop)
        _, _reward, term, _, info = env.step(np.zeros(1))
        if term:
            break
    assert term and info["capsized"] and abs(info["max_roll_deg"]) > 0.5
    assert info["reward_capsize"] == -100.0
    assert k < 60  # rolls beyond 0.5° within 30 s in 3–5 m beam seas


def test_default_capsize_angle_is_the_vanishing_angle():
    env = _env()
    _, info = env.reset(seed=0)
    # S175 GZ curve: vanishing angle ≈ 66° (coarse and default meshes agree within 0.2°)
    assert 64.0 < info["capsize_angle_deg"] < 68.0


def test_time_limit_truncates_via_registration():
    env = gymnasium.make("ship_gym/CourseKeeping-v0", max_episode_steps=3, **COARSE)
    env.reset(seed=0)
    flags = [env.step(np.zeros(1, dtype=np.float32))[2:4] for _ in range(3)]
    assert flags == [(False, False), (False, False), (False, True)]
    assert gymnasium.spec("ship_gym/CourseKeeping-v0").max_episode_steps == MAX_EPISODE_STEPS


@pytest.mark.parametrize(
    "kwargs",
    [
        {"control_dt_s": 0.25},  # not a multiple of physics_dt_s = 0.1
        {"physics_dt_s": -0.1},
        {"hs_range_m": (5.0, 3.0)},
        {"tp_range_s": (0.5, 3.0)},
        {"rudder_mode": "angle"},
        {"heading_weight": -1.0},
        {"capsize_angle_deg": 0.0},
        {"dangerous_roll_deg": 95.0},
        {"hull_mesh": (24, 6, 3)},
        {"gm_range_m": (0.0, 1.0)},
        {"integrator": "euler"},
        {"wave_preview_m": ("ahead",)},
    ],
)
def test_bad_kwargs_raise_value_error(kwargs):
    with pytest.raises(ValueError):
        _env(**kwargs)


def test_nan_and_wrong_shape_actions_raise_value_error():
    env = _env()
    env.reset(seed=0)
    with pytest.raises(ValueError):
        env.step(np.array([np.nan], dtype=np.float32))
    with pytest.raises(ValueError):
        env.step(np.zeros(2, dtype=np.float32))


def test_vector_env_episode_i_equals_single_env_seeded_s_plus_i():
    n, seed, steps = 3, 20, 8
    actions = np.random.default_rng(2).uniform(-1, 1, (steps, n, 1))
    venv = CourseKeepingVectorEnv(num_envs=n, **COARSE)
    obs_v, info_v = venv.reset(seed=seed)
    vec = [obs_v]
    rew_v = []
    for a in actions:
        o, r, *_ = venv.step(a)
        vec.append(o)
        rew_v.append(r)
    vec, rew_v = np.array(vec), np.array(rew_v)
    for i in range(n):
        env = _env()
        obs, info = env.reset(seed=seed + i)
        assert info["wave_height_m"] == info_v["wave_height_m"][i]
        single = [obs]
        rew = []
        for a in actions:
            o, r, *_ = env.step(a[i])
            single.append(o)
            rew.append(r)
        # same sea, same code path; the batch's (N, 6) @ (6, 6) products may round in another
        # order than N = 1, so allow a few float32 ulps
        np.testing.assert_allclose(vec[:, i], np.array(single), rtol=1e-5, atol=1e-6)
        np.testing.assert_allclose(rew_v[:, i], rew, rtol=1e-6, atol=1e-9)


def test_rudder_increment_mode_accumulates_and_saturates():
    env = _env(rudder_mode="increment", max_rudder_increment_deg=5.0)
    names = env.observation_names
    obs, _ = env.reset(seed=0)
    for k in range(1, 10):
        obs, *_ = env.step(np.ones(1, dtype=np.float32))
        command = obs[names.index("rudder command [rad]")]
        assert np.degrees(command) == pytest.approx(min(5.0 * k, 35.0), abs=1e-4)
    # the servo follows at 2.32 °/s: 9 steps of 0.5 s → at most 10.4°
    assert np.degrees(obs[names.index("rudder angle [rad]")]) <= 65.0 / 28.0 * 4.5 + 1e-3


def test_observation_names_are_stable_for_the_autopilot_baseline():
    names = _env().observation_names
    for name in ("heading error [rad]", "yaw rate [rad/s]", "rudder angle [rad]", "roll [rad]"):
        assert name in names
    assert len(names) == _env().observation_space.shape[0]
