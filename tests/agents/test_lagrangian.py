"""PPO-Lagrangian (ship_gym.agents.lagrangian): the shaped reward, the multiplier's dual ascent,
the [safe] table and a training run that writes its learning curve."""

from __future__ import annotations

import csv
import itertools
import json

import numpy as np
import pytest

import ship_gym  # noqa: F401
from ship_gym.agents.lagrangian import (
    SafeConfig,
    find_cost_shaped,
    lagrange_multiplier_callback,
    make_cost_shaped,
    safe_config,
)
from ship_gym.agents.train import config_from_mapping, train
from ship_gym.envs.sb3 import make_sb3_vec_env

# strong forcing: the 1-DOF roll passes its dangerous angle within a few steps (cost > 0)
KWARGS = {"forcing_amplitude": [0.05, 0.05], "dangerous_roll_angle": 0.1}  # [rad]


def test_shaped_reward_is_reward_minus_lambda_times_cost():
    plain = make_sb3_vec_env("ship_gym/RollOneDOF-v0", 3, seed=4, env_kwargs=KWARGS)
    shaped = make_cost_shaped(make_sb3_vec_env("ship_gym/RollOneDOF-v0", 3, seed=4,
                                               env_kwargs=KWARGS), 2.5)  # fmt: skip
    plain.reset(), shaped.reset()
    rng = np.random.default_rng(0)
    seen_cost = 0.0
    for _ in range(60):
        a = rng.uniform(-1, 1, (3, 1)).astype(np.float32)
        _, r0, d0, infos = plain.step(a)
        _, r1, d1, _ = shaped.step(a)
        cost = np.array([info["cost"] for info in infos])
        seen_cost += cost.sum()
        np.testing.assert_array_equal(d0, d1)
        np.testing.assert_allclose(r1, r0 - 2.5 * cost, rtol=0, atol=1e-12)
    assert seen_cost > 0  # the check bit
    assert find_cost_shaped(shaped) is shaped
    with pytest.raises(ValueError, match="no cost-shaping wrapper"):
        find_cost_shaped(plain)


def test_the_multiplier_is_found_and_set_under_vecnormalize():
    """SB3 wrappers forward attribute reads inward: λ must be set on the shaping wrapper itself,
    not on the VecNormalize around it (where it would be silently unused)."""
    from stable_baselines3.common.vec_env import VecNormalize

    inner = make_cost_shaped(make_sb3_vec_env("ship_gym/RollOneDOF-v0", 2, seed=1,
                                              env_kwargs=KWARGS), 0.0)  # fmt: skip
    stack = VecNormalize(inner)
    assert find_cost_shaped(stack) is inner
    cb = lagrange_multiplier_callback(SafeConfig(cost_limit=0.0, lagrangian_lr=1.0))
    cb.init_callback(_Model(stack))
    inner.episode_costs = [3.0]
    cb._on_rollout_end()
    assert inner.multiplier == 3.0 and "multiplier" not in vars(stack)
    assert inner.episode_costs == []


class _Logger:
    def __init__(self):
        self.records = {}

    def record(self, key, value):
        self.records[key] = value


class _Model:
    """What the callback reads of an SB3 algorithm: its env, logger and time steps."""

    def __init__(self, venv):
        self.venv, self.logger, self.num_timesteps = venv, _Logger(), 0

    def get_env(self):
        return self.venv


def test_multiplier_rises_above_the_budget_falls_below_and_stays_in_bounds():
    venv = make_cost_shaped(make_sb3_vec_env("ship_gym/RollOneDOF-v0", 1, seed=0), 1.0)
    cb = lagrange_multiplier_callback(SafeConfig(cost_limit=5.0, lagrangian_lr=0.1, lambda_max=2.0))
    model = _Model(venv)
    cb.init_callback(model)
    shaped = find_cost_shaped(venv)
    shaped.episode_costs = [15.0, 25.0]  # mean 20 > 5: λ += 0.1 · 15
    cb._on_rollout_end()
    assert shaped.multiplier == pytest.approx(2.0)  # 1 + 1.5 = 2.5, clipped to lambda_max
    shaped.episode_costs = [0.0]  # below the budget: λ -= 0.1 · 5
    cb._on_rollout_end()
    assert shaped.multiplier == pytest.approx(1.5)
    cb._on_rollout_end()  # no episode ended: unchanged
    assert shaped.multiplier == pytest.approx(1.5) and shaped.episode_costs == []
    shaped.episode_costs = [0.0] * 4
    for _ in range(10):
        shaped.episode_costs = [0.0]
        cb._on_rollout_end()
    assert shaped.multiplier == 0.0  # projected on λ ≥ 0
    assert model.logger.records["safe/cost_limit"] == 5.0
    assert [h[1] for h in cb.history][:2] == pytest.approx([2.0, 1.5])


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ({}, "needs cost_limit"),
        ({"cost_limit": -1}, r"cost_limit = -1; expected a number >= 0"),
        ({"cost_limit": 1, "lagrangian_lr": 0}, r"lagrangian_lr = 0; expected a number > 0"),
        ({"cost_limit": 1, "lambda": 1}, r"unknown keys \['lambda'\]"),
        ({"cost_limit": 1, "lambda_init": 5, "lambda_max": 2}, "exceeds lambda_max"),
    ],
)
def test_bad_safe_tables_are_refused(table, message):
    with pytest.raises(ValueError, match=message):
        safe_config(table)


def test_training_with_a_cost_budget_writes_lambda_and_the_learning_curve(tmp_path):
    config = config_from_mapping(
        {
            "env": {"id": "ship_gym/RollOneDOF-v0", "n_envs": 4, "kwargs": KWARGS},
            "algorithm": {
                "name": "PPO",
                "hyperparameters": {"n_steps": 64, "batch_size": 128, "n_epochs": 1},
                "policy_kwargs": {"net_arch": [16]},
            },
            "safe": {"cost_limit": 0.0, "lagrangian_lr": 0.01},
            "training": {
                "total_timesteps": 2048,
                "output_dir": str(tmp_path / "run"),
                "progress_bar": False,
                "tensorboard": False,
                "torch_threads": 1,
            },
        }
    )
    assert config.safe == SafeConfig(cost_limit=0.0, lagrangian_lr=0.01)
    out = train(config)
    rows = list(csv.DictReader((out / "progress.csv").open()))
    assert len(rows) >= 4
    steps = [float(r["timesteps"]) for r in rows]
    assert steps == sorted(steps) and steps[-1] == 2048
    lambdas = [float(r["lambda"]) for r in rows]
    # a budget of 0 with cost > 0: λ only grows (each update adds 0.01 × the mean cost)
    assert lambdas[-1] > 0 and all(b >= a for a, b in itertools.pairwise(lambdas))
    assert all(float(r["mean_cost"]) > 0 for r in rows)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["final_lambda"] == pytest.approx(lambdas[-1])
    assert summary["recent_mean_cost"] > 0
