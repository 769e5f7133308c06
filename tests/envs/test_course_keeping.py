"""ship_gym/CourseKeeping-v2: rewards, termination, arguments, rudder modes.

The checks every ship environment passes (checkers, seeding, reward = Σ terms, vector env,
actions, time limit) are parametrised in test_ship_task.py; the coarse mesh is described in
_ship_env_checks.py.
"""

import numpy as np
import pytest

from ship_gym.envs.course_keeping import CourseKeepingEnv

from ._ship_env_checks import COARSE


def _env(**kwargs) -> CourseKeepingEnv:
    return CourseKeepingEnv(**{**COARSE, **kwargs})


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
        {"capsize_penalty": -1.0},
    ],
)
def test_bad_kwargs_raise_value_error(kwargs):
    with pytest.raises(ValueError):
        _env(**kwargs)


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
