"""ship_gym/CapsizeAvoidance-v1: progress reward, autopilot, telegraph, termination, arguments.

The checks every ship environment passes (checkers, seeding, reward = Σ terms, vector env,
actions, time limit) are parametrised in test_ship_task.py; coarse S175 mesh as there.
"""

import numpy as np
import pytest

from ship_gym.envs.capsize_avoidance import CapsizeAvoidanceEnv

from ._ship_env_checks import COARSE_MESH

COARSE = {"hull_mesh": COARSE_MESH}


def _env(**kwargs) -> CapsizeAvoidanceEnv:
    return CapsizeAvoidanceEnv(**{**COARSE, **kwargs})


def test_progress_is_one_per_step_on_course_at_the_reference_speed():
    env = _env(wave_height_range_m=(0.0, 0.0), froude_range=None)
    env.reset(seed=1)
    # calm water, on course at the reference speed with the telegraph at the self-propulsion
    # rpm (a = (1 − lo)/(hi − lo)·2 − 1 for fraction 1): progress ≈ 1 per step
    a_tel = (1.0 - 0.3) / (1.2 - 0.3) * 2.0 - 1.0
    for _ in range(10):
        _, _, _, _, info = env.step(np.array([0.0, a_tel], dtype=np.float32))
        assert info["reward_dangerous_roll"] == 0.0 and info["cost"] == 0.0
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
