"""Constrained RL by a Lagrange multiplier on the Safe-RL cost (PPO-Lagrangian, any SB3 algorithm).

The problem: maximise the expected return J_r(π) subject to the expected episode cost
J_c(π) = E[Σ_t c_t] ≤ d, with c_t = ``info["cost"]`` of the ship envs (the fraction of the
control step spent violating the task's safety constraints, 1 in the step that capsizes:
:mod:`ship_gym.envs.ship_task`), so J_c is the expected time in violation [control steps] and d
(``cost_limit``) a budget of it. Its Lagrangian relaxation, max_π min_{λ≥0} J_r − λ (J_c − d), is
solved by the two-time-scale scheme of the Safety Gym baselines (Ray, Achiam & Amodei 2019,
"Benchmarking Safe Exploration in Deep Reinforcement Learning", §5; Stooke, Achiam & Abbeel
2020 for the multiplier update):

* the policy is trained by the unconstrained algorithm on the shaped reward r_t − λ c_t
  (:func:`make_cost_shaped`; the advantage of r − λc is A_r − λA_c, so one critic of the shaped
  reward replaces the separate cost critic of the original — exact for the returns, approximate
  for a learned value function);
* after every rollout, λ ← clip(λ + η (Ĵ_c − d), 0, λ_max) by projected gradient ascent on the
  dual, Ĵ_c the mean cost of the episodes completed since the last update
  (:func:`lagrange_multiplier_callback`; η = ``lagrangian_lr``).

The callback logs ``safe/lambda``, ``safe/episode_cost`` and ``safe/cost_limit`` to SB3's logger
(tensorboard). :func:`ship_gym.agents.train.train` uses both when the config has a ``[safe]``
table (``cost_limit``, ``lagrangian_lr``, ``lambda_init``, ``lambda_max``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["SafeConfig", "lagrange_multiplier_callback", "make_cost_shaped", "safe_config"]


@dataclass(frozen=True)
class SafeConfig:
    """The ``[safe]`` table of a training config.

    Attributes
    ----------
    cost_limit : float
        Budget d of the expected episode cost [control steps in violation] (≥ 0).
    lagrangian_lr : float
        Step η of the multiplier's update [1 / cost unit] (> 0).
    lambda_init : float
        Initial λ [-] (≥ 0).
    lambda_max : float
        Upper bound of λ [-] (keeps the shaped reward bounded).
    """

    cost_limit: float
    lagrangian_lr: float = 0.05
    lambda_init: float = 0.0
    lambda_max: float = 100.0


def safe_config(table: Mapping[str, Any]) -> SafeConfig:
    """Validate a ``[safe]`` table (errors name the key as written)."""
    known = {"cost_limit", "lagrangian_lr", "lambda_init", "lambda_max"}
    unknown = sorted(set(table) - known)
    if unknown:
        raise ValueError(f"unknown keys {unknown} in [safe]; expected {sorted(known)}")
    if "cost_limit" not in table:
        raise ValueError("[safe] needs cost_limit (the episode-cost budget, >= 0)")
    out: dict[str, float] = {}
    for key, low, strict in (
        ("cost_limit", 0.0, False),
        ("lagrangian_lr", 0.0, True),
        ("lambda_init", 0.0, False),
        ("lambda_max", 0.0, True),
    ):
        if key not in table:
            continue
        value = table[key]
        ok = isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)
        if not ok or value < low or (strict and value == low):
            what = "> 0" if strict else ">= 0"
            raise ValueError(f"[safe] {key} = {value!r}; expected a number {what}")
        out[key] = float(value)
    config = SafeConfig(**out)
    if config.lambda_init > config.lambda_max:
        raise ValueError(
            f"[safe] lambda_init = {config.lambda_init!r} exceeds lambda_max = "
            f"{config.lambda_max!r}"
        )
    return config


def make_cost_shaped(venv: Any, lambda_init: float) -> Any:
    """``venv`` (an SB3 VecEnv whose infos carry ``"cost"``) with reward r − λ c
    (``CostShapedVecEnv``, built on first use so that SB3 is imported only then)."""
    from stable_baselines3.common.vec_env import VecEnvWrapper

    class CostShapedVecEnv(VecEnvWrapper):
        """Reward r − λ c per step; tracks the cost of every episode (``episode_costs``).

        ``multiplier`` is λ (set by :func:`lagrange_multiplier_callback`); ``episode_costs``
        collects Σ c of the episodes that end, until the callback takes them.
        """

        def __init__(self, inner: Any, multiplier: float) -> None:
            super().__init__(inner)
            self.multiplier = float(multiplier)
            self.episode_costs: list[float] = []
            self._running = np.zeros(inner.num_envs)

        def reset(self) -> Any:
            self._running[:] = 0.0
            return self.venv.reset()

        def step_wait(self) -> Any:
            obs, reward, done, infos = self.venv.step_wait()
            cost = np.array([float(info.get("cost", 0.0)) for info in infos])
            self._running += cost
            for i in np.flatnonzero(done):
                self.episode_costs.append(float(self._running[i]))
                self._running[i] = 0.0
            return obs, reward - self.multiplier * cost, done, infos

    return CostShapedVecEnv(venv, lambda_init)


def find_cost_shaped(venv: Any) -> Any:
    """The cost-shaping wrapper inside a VecEnv stack (ValueError if none).

    Looked up by the wrapper's *own* attributes: SB3's wrappers forward unknown attribute reads
    to the env they wrap, so ``hasattr`` on an outer wrapper (VecNormalize) would find the
    inner one's ``multiplier`` and a write would land on the outer one, silently unused.
    """
    env = venv
    while env is not None:
        own = vars(env)
        if "episode_costs" in own and "multiplier" in own:
            return env
        env = own.get("venv")
    raise ValueError("no cost-shaping wrapper in the VecEnv stack (make_cost_shaped)")


def lagrange_multiplier_callback(config: SafeConfig) -> Any:
    """An SB3 callback updating λ after every rollout (module docstring); built on first use so
    that SB3 is imported only then. ``history`` holds (time steps, λ, Ĵ_c) per update."""
    from stable_baselines3.common.callbacks import BaseCallback

    class _Callback(BaseCallback):
        def __init__(self) -> None:
            super().__init__()
            self.config = config
            self.history: list[tuple[int, float, float]] = []

        def _on_step(self) -> bool:
            return True

        def _on_rollout_end(self) -> None:
            shaped = find_cost_shaped(self.training_env)
            costs, shaped.episode_costs = shaped.episode_costs, []
            if not costs:  # no episode ended in this rollout: λ waits
                return
            mean_cost = float(np.mean(costs))
            c = self.config
            lam = shaped.multiplier + c.lagrangian_lr * (mean_cost - c.cost_limit)
            shaped.multiplier = float(min(max(lam, 0.0), c.lambda_max))
            self.history.append((int(self.num_timesteps), shaped.multiplier, mean_cost))
            self.logger.record("safe/lambda", shaped.multiplier)
            self.logger.record("safe/episode_cost", mean_cost)
            self.logger.record("safe/cost_limit", c.cost_limit)

    return _Callback()
