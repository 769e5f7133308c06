"""ship_gym/HeavyWeather-v0: the sea drawn, set-point actions, progress metric, capsize penalty.

The checks every ship environment passes (checkers, seeding, reward = Σ terms, vector env,
actions, time limit) are parametrised in test_ship_task.py; coarse S175 mesh as there.
"""

import math

import numpy as np
import pytest

from ship_gym.conventions import GRAVITY
from ship_gym.envs.heavy_weather import (
    MAX_EPISODE_STEPS,
    HeavyWeatherEnv,
    HeavyWeatherSea,
    action_of_telegraph,
    telegraph_of_action,
    voyage_progress,
)
from ship_gym.waves.sea_state import irregular_steepness_limit

from ._ship_env_checks import COARSE

LPP = 175.0


def _env(**kwargs) -> HeavyWeatherEnv:
    return HeavyWeatherEnv(**{**COARSE, **kwargs})


def test_seas_are_drawn_over_the_whole_physical_range():
    sea = HeavyWeatherSea(lpp=LPP)
    rng = np.random.default_rng(0)
    rows = []
    for _ in range(400):
        _, info = sea.sample(rng)
        tp, hs = info["wave_period_s"], info["wave_height_m"]
        wavelength = GRAVITY * tp**2 / (2 * math.pi)
        rows.append((wavelength / LPP, hs / LPP, hs / wavelength, info["wave_spreading_s"]))
        # every sea is physical: DNV-RP-C205's steepness limit at its Tp
        assert hs / wavelength <= irregular_steepness_limit(tp) + 1e-12
    lam, height, _, spread = np.array(rows).T
    assert 0.6 <= lam.min() < 0.65 and 1.95 < lam.max() <= 2.0
    assert 0.02 <= height.min() < 0.022 and 0.068 < height.max() <= 0.07
    assert 2.0 <= spread.min() < 2.5 and 40.0 < spread.max() <= 50.0
    # the steep end is reachable only with long waves (Hs/λp ≤ 1/15 … 1/25): no steep short sea
    assert height[lam < 0.8].max() <= 0.8 / 15 + 1e-9


def test_bad_sea_ranges_name_the_keyword():
    with pytest.raises(ValueError, match="height_ratio_range"):
        _env(height_ratio_range=(0.15, 0.2), wavelength_ratio_range=(0.6, 0.7))
    with pytest.raises(ValueError, match="wavelength_ratio_range"):
        _env(wavelength_ratio_range=(2.0, 1.0))
    with pytest.raises(ValueError, match="shaft_speed_range"):
        _env(shaft_speed_range=(1.1, 1.2))


def test_telegraph_action_keeps_the_service_rpm_at_zero_and_inverts():
    a = np.linspace(-1.0, 1.0, 21)
    f = telegraph_of_action(a, 0.3, 1.2)
    assert f[10] == 1.0 and f[0] == pytest.approx(0.3) and f[-1] == pytest.approx(1.2)
    assert np.all(np.diff(f) > 0)
    np.testing.assert_allclose(action_of_telegraph(f, 0.3, 1.2), a, atol=1e-12)


def test_calm_water_on_course_makes_one_unit_of_progress_per_step():
    env = _env(height_ratio_range=(0.0, 0.0), froude_range=None, gm_range_m=None)
    env.reset(seed=3)
    for _ in range(10):
        _, _, _, _, info = env.step(np.zeros(2, dtype=np.float32))
        assert info["cost"] == 0.0
    # the calm-water self-propulsion point ignores the appendages: within 1 %
    assert info["reward_progress"] == pytest.approx(1.0, abs=0.01)
    nominal = env.task.setup.speed * env.control_dt * MAX_EPISODE_STEPS
    assert info["voyage_progress"] == pytest.approx(10 / MAX_EPISODE_STEPS, rel=0.01)
    assert info["distance_along_voyage_m"] == pytest.approx(
        10 * nominal / MAX_EPISODE_STEPS, rel=0.01
    )


def test_course_set_point_turns_the_ship_and_costs_progress():
    # calm water: a = (1/3, 0) asks for 45° off the voyage course; the autopilot (tuned on the
    # identified Nomoto model) overshoots by less than half and settles within 8 minutes; the
    # ship then makes cos 45° ≈ 0.71 of the progress per step
    env = _env(height_ratio_range=(0.0, 0.0), froude_range=None, gm_range_m=None)
    names = env.observation_names
    env.reset(seed=0)
    headings = []
    for _ in range(96):
        obs, _, _, _, info = env.step(np.array([1.0 / 3.0, 0.0], dtype=np.float32))
        headings.append(math.degrees(obs[names.index("heading from voyage course [rad]")]))
    assert max(headings) < 45.0 * 1.5
    assert headings[-1] == pytest.approx(45.0, abs=2.0)
    assert info["reward_progress"] == pytest.approx(math.cos(math.radians(45.0)), abs=0.05)


def test_capsize_is_never_worth_its_progress_and_scores_zero():
    env = _env()
    task = env.task
    # the most progress of an episode: every step at the highest telegraph's speed (the speed
    # grows at most linearly with the shaft speed at the same advance ratio)
    most = MAX_EPISODE_STEPS * task.shaft_fraction_range[1]
    assert task.capsize_penalty > most
    env = _env(capsize_angle_deg=1.0, wave_heading_range_deg=(60.0, 90.0))
    env.reset(seed=0)
    for _ in range(MAX_EPISODE_STEPS):
        _, _, term, _, info = env.step(np.zeros(2, dtype=np.float32))
        if term:
            break
    assert term and info["capsized"] and info["reward_capsize"] == -task.capsize_penalty
    assert info["voyage_progress"] == 0.0 and info["distance_along_voyage_m"] > 0.0
    assert voyage_progress(np.array([100.0, 100.0]), np.array([True, False]), 200.0).tolist() == [
        0.0,
        0.5,
    ]


def test_bridge_statistics_follow_the_roll():
    env = _env(
        height_ratio_range=(0.05, 0.05),
        wavelength_ratio_range=(1.2, 1.2),
        wave_heading_range_deg=(90.0, 90.0),
        gm_range_m=(1.0, 1.0),
    )
    names = env.observation_names
    obs, info = env.reset(seed=2)
    assert obs[names.index("significant wave height [m]")] == pytest.approx(0.05 * LPP, rel=1e-6)
    assert obs[names.index("wave spreading exponent [-]")] == pytest.approx(
        info["wave_spreading_s"], rel=1e-6
    )
    rolls = []
    for _ in range(60):
        obs, *_ = env.step(np.zeros(2, dtype=np.float32))
        rolls.append(abs(obs[names.index("roll [rad]")]))
    rms = obs[names.index("RMS roll, recent [rad]")]
    peak = obs[names.index("max roll, recent [rad]")]
    # beam seas: the ship rolls; the recent statistics are positive, peak ≥ RMS, and the
    # peak is at least the largest sampled roll of the last statistics time constant decayed
    assert 0.0 < rms < peak
    assert peak >= max(rolls[-5:]) * 0.9
