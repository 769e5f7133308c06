"""ship_gym/CapsizeAvoidance-v2: progress reward, autopilot, telegraph, termination, arguments.

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
    # calm water, on course at the reference speed with the telegraph kept at the
    # self-propulsion rpm (zero action): progress ≈ 1 per step
    for _ in range(10):
        _, _, _, _, info = env.step(np.zeros(2, dtype=np.float32))
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
        a = np.array([1.0 if k < 10 else 0.0, 0.0], dtype=np.float32)
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


def test_telegraph_changes_per_step_and_the_shaft_is_rate_limited():
    env = _env(wave_height_range_m=(0.0, 0.0), froude_range=None)
    names = env.observation_names
    i_tel = names.index("telegraph [× self-propulsion rpm]")
    obs, _ = env.reset(seed=0)
    n0 = obs[names.index("shaft speed [rev/s]")]
    assert obs[i_tel] == pytest.approx(1.0)  # at the reference speed's self-propulsion rpm
    obs, *_ = env.step(np.array([0.0, -1.0], dtype=np.float32))
    n1 = obs[names.index("shaft speed [rev/s]")]
    assert obs[i_tel] == pytest.approx(0.98)  # telegraph_step 0.02 per step at a = -1
    # the shaft follows at 1 % of the self-propulsion rpm per second, 0.5 s per step
    assert n0 - n1 == pytest.approx(0.005 * n0, rel=1e-4)
    for _ in range(60):  # stays within shaft_speed_range
        obs, *_ = env.step(np.array([0.0, -1.0], dtype=np.float32))
    assert obs[i_tel] == pytest.approx(0.3)


def test_zero_action_keeps_course_and_the_initial_speed():
    # calm water, initial Fn 0.25 below the reference 0.3: the telegraph starts and stays at
    # that speed's self-propulsion rpm, so the ship keeps its speed (within 1 %) and course
    env = _env(wave_height_range_m=(0.0, 0.0), froude_range=(0.25, 0.25))
    names = env.observation_names
    obs, info = env.reset(seed=3)
    u0 = info["initial_speed_mps"]
    assert u0 == pytest.approx(0.25 * np.sqrt(9.81 * 175.0), rel=1e-3)
    f0 = obs[names.index("telegraph [× self-propulsion rpm]")]
    assert 0.6 < f0 < 0.75  # rpm roughly ∝ speed (0.25/0.35 = 0.71), more so at low speed
    for _ in range(200):
        obs, *_ = env.step(np.zeros(2, dtype=np.float32))
    assert obs[names.index("telegraph [× self-propulsion rpm]")] == f0
    assert obs[names.index("surge speed [m/s]")] == pytest.approx(u0, rel=0.01)
    assert abs(obs[names.index("heading from voyage course [rad]")]) < 1e-4


def test_sea_state_and_roll_period_are_observed():
    env = _env(gm_range_m=(0.5, 1.0))
    names = env.observation_names
    for seed in (0, 1):
        obs, info = env.reset(seed=seed)
        t_w = info["wave_period_s"]
        assert obs[names.index("wave period [s]")] == pytest.approx(t_w)
        # deep water λ = g T²/2π, over the S175's 175 m
        ratio = 9.81 * t_w**2 / (2 * np.pi) / 175.0
        assert obs[names.index("wavelength / ship length [-]")] == pytest.approx(ratio, 1e-3)
        assert 1.4 <= ratio <= 1.6 * 1.001  # the default wavelength_ratio_range
        h = obs[names.index("wave height / ship length [-]")]
        assert h == pytest.approx(info["wave_height_m"] / 175.0, rel=1e-5)
        # T_R ∝ 1/√GM; the nominal loading's T_R from its own C44 and I44 + A44(ω_φ)
        t_r = obs[names.index("roll natural period [s]")]
        assert t_r == pytest.approx(info["roll_period_s"], rel=1e-6)
        nominal = env.unwrapped.task._nominal_roll_period
        gm0 = env.unwrapped.task.loading.gm
        assert t_r == pytest.approx(nominal * np.sqrt(gm0 / info["gm_m"]), rel=1e-6)
    assert 15.0 < nominal < 30.0  # the S175 at GM ≈ 1 m rolls at ≈ 20–25 s


def test_cost_is_one_in_the_step_that_capsizes():
    env = _env(capsize_angle_deg=1.0, dangerous_roll_deg=30.0, wave_heading_range_deg=(40.0, 45.0),
               wave_ramp_time_s=0.0)  # fmt: skip
    env.reset(seed=0)
    for _ in range(200):
        _, _, term, _, info = env.step(np.zeros(2, dtype=np.float32))
        if term:
            break
        assert info["cost"] == 0.0  # |φ| < 1° < 30°
    assert term and info["capsized"] and info["cost"] == 1.0
