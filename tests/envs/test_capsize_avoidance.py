"""ship_gym/CapsizeAvoidance-v0: API checks, determinism, rewards, autopilot, termination.

Coarse S175 mesh (24 sections) as in test_course_keeping.py.
"""

import warnings

import gymnasium
import numpy as np
import pytest

import ship_gym  # noqa: F401  (registers the ids)
from ship_gym.envs.capsize_avoidance import (
    MAX_EPISODE_STEPS,
    CapsizeAvoidanceEnv,
    CapsizeAvoidanceVectorEnv,
)

COARSE = {"hull_mesh": (24, 6, 3, 2)}


def _env(**kwargs) -> CapsizeAvoidanceEnv:
    return CapsizeAvoidanceEnv(**{**COARSE, **kwargs})


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


def _rollout(env, seed, actions):
    obs, _ = env.reset(seed=seed)
    out, rewards = [obs], []
    for a in actions:
        obs, r, _term, _trunc, _ = env.step(a)
        out.append(obs)
        rewards.append(r)
    return np.array(out), np.array(rewards)


def test_seeded_rollouts_identical_across_instances():
    actions = np.random.default_rng(0).uniform(-1, 1, (10, 2)).astype(np.float32)
    a = _rollout(_env(), 4, actions)
    b = _rollout(_env(), 4, actions)
    np.testing.assert_array_equal(a[0], b[0])
    np.testing.assert_array_equal(a[1], b[1])


def test_reward_terms_sum_and_progress_scale():
    env = _env(wave_height_range_m=(0.0, 0.0), froude_range=None)
    obs, info = env.reset(seed=1)
    # calm water, on course at the reference speed with the telegraph at the self-propulsion
    # rpm (a = (1 − lo)/(hi − lo)·2 − 1 for fraction 1): progress ≈ 1 per step
    a_tel = (1.0 - 0.3) / (1.2 - 0.3) * 2.0 - 1.0
    for _ in range(10):
        obs, reward, _term, _, info = env.step(np.array([0.0, a_tel], dtype=np.float32))
        terms = {k: v for k, v in info.items() if k.startswith("reward_")}
        assert set(terms) == {"reward_progress", "reward_dangerous_roll", "reward_capsize"}
        assert reward == pytest.approx(sum(terms.values()), rel=1e-12, abs=1e-12)
        assert env.observation_space.contains(obs)
    # the calm-water self-propulsion point ignores the appendages: within 1 %
    assert info["reward_progress"] == pytest.approx(1.0, abs=0.01)


def test_autopilot_follows_a_heading_set_point_change():
    # calm water: 10 steps of +2°/step set a 20° set-point; the PID autopilot (ω_n = 0.06 rad/s,
    # ζ = 0.9 on the identified Nomoto model, rudder rate-limited to 2.32 °/s) turns the ship
    # onto it within a few degrees in ~100 s and settles
    env = _env(wave_height_range_m=(0.0, 0.0), froude_range=None)
    names = env.observation_names
    env.reset(seed=0)
    headings = []
    for k in range(400):
        a = np.array([1.0 if k < 10 else 0.0, 0.33], dtype=np.float32)
        obs, *_ = env.step(a)
        headings.append(np.degrees(obs[names.index("heading from voyage course [rad]")]))
        setpoint = np.degrees(obs[names.index("heading set-point from voyage course [rad]")])
    headings = np.array(headings)
    assert setpoint == pytest.approx(20.0, abs=1e-4)
    assert headings[240] > 15.0  # on the way within 120 s
    assert headings.max() < 30.0  # overshoot below 50 %
    assert abs(headings[-1] - 20.0) < 3.0  # settled after 200 s


def test_capsize_terminates_with_penalty():
    env = _env(capsize_angle_deg=1.0, wave_heading_range_deg=(40.0, 45.0), wave_ramp_time_s=0.0)
    env.reset(seed=0)
    for k in range(200):  # noqa: B007 (k read after the loop)
        _, _, term, _, info = env.step(np.zeros(2, dtype=np.float32))
        if term:
            break
    assert term and info["capsized"] and info["reward_capsize"] == -100.0
    assert k < 100


def test_time_limit_truncates_via_registration():
    env = gymnasium.make("ship_gym/CapsizeAvoidance-v0", max_episode_steps=2, **COARSE)
    env.reset(seed=0)
    flags = [env.step(np.zeros(2, dtype=np.float32))[2:4] for _ in range(2)]
    assert flags == [(False, False), (False, True)]
    assert gymnasium.spec("ship_gym/CapsizeAvoidance-v0").max_episode_steps == MAX_EPISODE_STEPS


@pytest.mark.parametrize(
    "kwargs",
    [
        {"control_dt_s": 0.15},
        {"sea_kind": "swell"},
        {"wavelength_ratio_range": (1.6, 1.4)},
        {"wave_height_range_m": (30.0, 40.0)},  # breaking: H/λ > 1/7
        {"froude_range": (0.3, 0.9)},
        {"shaft_speed_range": (1.0, 1.0)},
        {"heading_rate_deg": 0.0},
        {"progress_weight": float("nan")},
        {"sensor_noise": -1.0},
    ],
)
def test_bad_kwargs_raise_value_error(kwargs):
    with pytest.raises(ValueError):
        _env(**kwargs)


def test_nan_action_raises_value_error():
    env = _env()
    env.reset(seed=0)
    with pytest.raises(ValueError):
        env.step(np.array([0.0, np.inf], dtype=np.float32))


def test_vector_env_episode_i_equals_single_env_seeded_s_plus_i():
    n, seed = 2, 7
    actions = np.random.default_rng(3).uniform(-1, 1, (6, n, 2))
    venv = CapsizeAvoidanceVectorEnv(num_envs=n, **COARSE)
    obs_v, _ = venv.reset(seed=seed)
    vec = [obs_v] + [venv.step(a)[0] for a in actions]
    vec = np.array(vec)
    for i in range(n):
        env = _env()
        obs, _ = env.reset(seed=seed + i)
        single = np.array([obs] + [env.step(a[i])[0] for a in actions])
        # see test_course_keeping.py: a few float32 ulps of batch rounding allowed
        np.testing.assert_allclose(vec[:, i], single, rtol=1e-5, atol=1e-6)


def test_telegraph_is_rate_limited():
    env = _env(wave_height_range_m=(0.0, 0.0), froude_range=None)
    names = env.observation_names
    obs, _ = env.reset(seed=0)
    n0 = obs[names.index("shaft speed [rev/s]")]
    obs, *_ = env.step(np.array([0.0, -1.0], dtype=np.float32))
    target = obs[names.index("telegraph shaft speed [rev/s]")]
    n1 = obs[names.index("shaft speed [rev/s]")]
    assert target == pytest.approx(0.3 * n0, rel=1e-5)
    # 1 % of the self-propulsion rpm per second, 0.5 s per step
    assert n0 - n1 == pytest.approx(0.005 * n0, rel=1e-4)
