"""What the tests of the S175 ship environments share: the coarse mesh, the environments with
their reward terms, rollouts and the generic checks (parametrised in test_ship_task.py).

A coarse S175 mesh (24 sections, 864 panels; GM and vanishing angle within 2 % and 0.1° of the
default mesh) and 20 wave components keep the rollouts fast; the simulator of each setup is built
once per process and deep-copied for every environment (ship_task.prototype_simulator).
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pytest

from ship_gym.envs.base import TaskEnv, TaskVectorEnv
from ship_gym.envs.capsize_avoidance import CapsizeAvoidanceEnv, CapsizeAvoidanceVectorEnv
from ship_gym.envs.course_keeping import CourseKeepingEnv, CourseKeepingVectorEnv
from ship_gym.envs.heavy_weather import HeavyWeatherEnv, HeavyWeatherVectorEnv
from ship_gym.envs.ride_control import RideControlEnv, RideControlVectorEnv
from ship_gym.envs.roll_stabilisation import RollStabilizationEnv, RollStabilizationVectorEnv

COARSE_MESH = (24, 6, 3, 2)
COARSE = {"hull_mesh": COARSE_MESH, "n_wave_components": 20}

RESET_INFO_KEYS = {
    "wave_height_m",
    "wave_period_s",
    "wave_heading_deg",
    "initial_speed_mps",
    "gm_m",
    "capsize_angle_deg",
}
"""What every ship environment reports at reset (ShipTask.reset_info)."""


@dataclass(frozen=True)
class ShipEnvCase:
    """One ship environment configuration of the generic checks."""

    env_class: type[TaskEnv]
    vector_class: type[TaskVectorEnv]
    reward_terms: tuple[str, ...]  # in the order the task sums them (capsize last)
    kwargs: Mapping[str, Any] = field(default_factory=lambda: COARSE)

    def env(self, **kwargs: Any) -> TaskEnv:
        return self.env_class(**{**self.kwargs, **kwargs})

    def vector_env(self, num_envs: int, **kwargs: Any) -> TaskVectorEnv:
        return self.vector_class(num_envs=num_envs, **{**self.kwargs, **kwargs})


SHIP_ENVS: dict[str, ShipEnvCase] = {
    "CourseKeeping": ShipEnvCase(
        CourseKeepingEnv,
        CourseKeepingVectorEnv,
        ("heading", "rudder", "rudder_rate", "roll", "capsize"),
    ),
    # noise and wave preview: observation entries beyond the common ones, seeded noise
    "CourseKeeping-noise-preview": ShipEnvCase(
        CourseKeepingEnv,
        CourseKeepingVectorEnv,
        ("heading", "rudder", "rudder_rate", "roll", "capsize"),
        {**COARSE, "sensor_noise": 1.0, "wave_preview_m": (50.0, 100.0)},
    ),
    # regular waves (one component)
    "CapsizeAvoidance": ShipEnvCase(
        CapsizeAvoidanceEnv,
        CapsizeAvoidanceVectorEnv,
        ("progress", "dangerous_roll", "capsize"),
        {"hull_mesh": COARSE_MESH},
    ),
    "RollStabilization": ShipEnvCase(
        RollStabilizationEnv,
        RollStabilizationVectorEnv,
        ("roll", "roll_rate", "lateral", "effort", "fin_rate", "capsize"),
    ),
    "RollStabilization-rudder": ShipEnvCase(
        RollStabilizationEnv,
        RollStabilizationVectorEnv,
        ("roll", "roll_rate", "lateral", "effort", "fin_rate", "heading", "capsize"),
        {**COARSE, "rudder_roll_stabilization": True},
    ),
    "RideControl": ShipEnvCase(
        RideControlEnv, RideControlVectorEnv, ("vertical", "effort", "foil_rate", "capsize")
    ),
    # short-crested seas, GM drawn per episode, set-point actions
    "HeavyWeather": ShipEnvCase(
        HeavyWeatherEnv, HeavyWeatherVectorEnv, ("progress", "dangerous_roll", "capsize")
    ),
}


@dataclass
class Rollout:
    """Observations (n + 1), rewards (n), step infos (n) and the reset info of one episode."""

    observations: np.ndarray
    rewards: np.ndarray
    infos: list[dict[str, Any]]
    reset_info: dict[str, Any]
    ended: bool


def rollout(
    env: TaskEnv,
    seed: int,
    actions: Sequence[np.ndarray] | Callable[[np.ndarray], np.ndarray],
    steps: int | None = None,
) -> Rollout:
    """Reset with ``seed`` and step with the given actions (or a policy of the observation for
    ``steps`` steps) until they run out or the episode ends."""
    obs, reset_info = env.reset(seed=seed)
    observations, rewards, infos = [obs], [], []
    n = len(actions) if steps is None else steps  # type: ignore[arg-type]
    ended = False
    for k in range(n):
        a = actions(obs) if callable(actions) else actions[k]
        obs, reward, terminated, truncated, info = env.step(a)
        observations.append(obs)
        rewards.append(reward)
        infos.append(info)
        if terminated or truncated:
            ended = True
            break
    return Rollout(np.array(observations), np.array(rewards), infos, reset_info, ended)


def uniform_actions(env: TaskEnv | TaskVectorEnv, steps: int, seed: int) -> np.ndarray:
    """(steps, *action shape) float32 actions uniform in [-1, 1]."""
    rng = np.random.default_rng(seed)
    return rng.uniform(-1.0, 1.0, (steps, *env.action_space.shape)).astype(np.float32)


def reward_terms(info: Mapping[str, Any]) -> dict[str, float]:
    """The ``reward_<term>`` entries of a step info, term → value, in their order."""
    return {k.removeprefix("reward_"): v for k, v in info.items() if k.startswith("reward_")}


def assert_checkers_pass_without_warnings(make_env: Callable[[], TaskEnv]) -> None:
    """Gymnasium's and stable-baselines3's environment checkers pass without a warning."""
    from gymnasium.utils.env_checker import check_env
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        check_env(make_env(), skip_render_check=True)
        sb3_check_env(make_env(), warn=True)
    assert [str(w.message) for w in caught] == []


def assert_bad_actions_raise(env: TaskEnv) -> None:
    """NaN, inf and wrong-shape actions raise ValueError (base.validate_actions)."""
    env.reset(seed=0)
    good = np.zeros(env.action_space.shape, dtype=np.float32)
    for bad in (good + np.nan, good + np.inf, np.zeros(good.size + 1, dtype=np.float32)):
        with pytest.raises(ValueError, match="action"):
            env.step(bad)


def full_scale_travel(env: TaskEnv, surface: str, term: str, weight: float) -> list[float]:
    """Step a single-surface env with a = +1 for 6 steps from rest and check the servo-travel
    bookkeeping of ``surface`` (``"fin"``, ``"T-foil"``): the command is observed at full scale,
    the travel entry is Δδ/(δ̇_max Δt) and the ``term`` reward is −weight · travel²; a reset puts
    the surface back at rest and charges no travel for the jump. Returns the travels."""
    names = env.observation_names
    i_cmd = names.index(f"{surface} command [rad]")
    i_travel = names.index(f"{surface} travel over the last step [rate limit x step]")
    limit = env.unwrapped.task.actuators[0][2]  # the command at a = 1 [rad]
    env.reset(seed=0)
    travel, terms = [], []
    for _ in range(6):
        obs, _, _, _, info = env.step(np.ones(1, dtype=np.float32))
        travel.append(float(obs[i_travel]))
        terms.append(float(info[f"reward_{term}"]))
        assert obs[i_cmd] == pytest.approx(limit, rel=1e-6)
    np.testing.assert_allclose(terms, -weight * np.square(travel), rtol=1e-5, atol=1e-7)
    assert abs(travel[-1]) < 1e-3  # the servo has arrived
    obs, _ = env.reset(seed=1)
    assert obs[i_travel] == 0.0
    _, _, _, _, info = env.step(np.zeros(1, dtype=np.float32))
    assert info[f"reward_{term}"] == 0.0
    return travel
