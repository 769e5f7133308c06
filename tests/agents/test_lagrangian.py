"""PPO-Lagrangian (ship_gym.agents.lagrangian): the shaped reward, the multiplier's dual ascent,
the [safe] table and a training run that writes its learning curve."""

from __future__ import annotations

import csv
import itertools
import json

import gymnasium as gym
import numpy as np
import pytest

import ship_gym  # noqa: F401
from ship_gym.agents.lagrangian import (
    EFFORT_INFO_KEY,
    EPISODE_RMS_INFO_KEY,
    MultiplierState,
    SafeConfig,
    exploration_variance,
    find_cost_shaped,
    lagrange_multiplier_callback,
    make_cost_shaped,
    record_action_effort,
    resolve_effort_budget,
    safe_config,
    update_multiplier,
)
from ship_gym.agents.train import config_from_mapping, train
from ship_gym.envs.sb3 import make_sb3_vec_env

# strong forcing: the 1-DOF roll passes its dangerous angle within a few steps (cost > 0)
KWARGS = {"forcing_amplitude": [0.05, 0.05], "dangerous_roll_angle": 0.1}  # [rad]


def _tiny_config(tmp_path, safe, *, n_envs=4, n_steps=64, timesteps=2048, seed=0, policy=None,
                 **sections):  # fmt: skip
    """A PPO run of a few rollouts on the strongly forced 1-DOF roll, with a ``[safe]`` table
    and optional extra tables (``residual``, ``validation``)."""
    return config_from_mapping(
        {
            "env": {"id": "ship_gym/RollOneDOF-v0", "n_envs": n_envs, "kwargs": KWARGS},
            "algorithm": {
                "name": "PPO",
                "hyperparameters": {"n_steps": n_steps, "batch_size": 128, "n_epochs": 1},
                "policy_kwargs": {"net_arch": [16], **(policy or {})},
            },
            "safe": safe,
            "training": {
                "total_timesteps": timesteps,
                "seed": seed,
                "output_dir": str(tmp_path / "run"),
                "progress_bar": False,
                "tensorboard": False,
                "torch_threads": 1,
            },
            **sections,
        }
    )


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
        ({}, "needs exactly one of cost_limit"),
        ({"cost_limit": 1, "effort_limit": 0.2}, "needs exactly one of cost_limit"),
        ({"effort_limit": 0}, r"effort_limit = 0; expected a number > 0 and <= 1"),
        ({"effort_limit": 1.5}, r"effort_limit = 1.5; expected a number > 0 and <= 1"),
        ({"effort_limit": True}, r"effort_limit = True; expected a number"),
        ({"effort_limit": "zero"}, r"effort_limit = 'zero'; expected an RMS action .*\['fins'"),
        ({"effort_limit": "fin"}, r"effort_limit = 'fin'; expected .* name of a baseline"),
        ({"cost_limit": -1}, r"cost_limit = -1; expected a number >= 0"),
        ({"cost_limit": 1, "lagrangian_lr": 0}, r"lagrangian_lr = 0; expected a number > 0"),
        ({"cost_limit": 1, "lagrangian_kp": -1}, r"lagrangian_kp = -1; expected a number >= 0"),
        ({"cost_limit": 1, "lagrangian_kd": "x"}, r"lagrangian_kd = 'x'; expected a number"),
        (
            {"cost_limit": 1, "lagrangian_smoothing": 1},
            r"lagrangian_smoothing = 1; expected a number >= 0 and < 1",
        ),
        ({"cost_limit": 1, "lambda": 1}, r"unknown keys \['lambda'\]"),
        ({"cost_limit": 1, "lambda_init": 5, "lambda_max": 2}, "exceeds lambda_max"),
    ],
)
def test_bad_safe_tables_are_refused(table, message):
    with pytest.raises(ValueError, match=message):
        safe_config(table)


def test_training_with_a_cost_budget_writes_lambda_and_the_learning_curve(tmp_path):
    config = _tiny_config(tmp_path, {"cost_limit": 0.0, "lagrangian_lr": 0.01})
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


def test_safe_config_names_its_constraint_and_its_validation_limit():
    cost = safe_config({"cost_limit": 2})
    effort = safe_config({"effort_limit": 0.25, "lagrangian_lr": 0.02})
    assert (cost.constraint, cost.info_key, cost.validation_limit) == (
        "cost", "cost", ("mean_cost", 2.0))  # fmt: skip
    assert (effort.constraint, effort.info_key, effort.validation_limit) == (
        "effort", EFFORT_INFO_KEY, ("rms_action", 0.25))  # fmt: skip
    with pytest.raises(ValueError, match="exactly one of cost_limit"):
        SafeConfig()


def test_the_effort_recorder_sees_the_clipped_total_residual_command():
    """Below the residual wrapper the recorder sees clip(a_baseline + scale · a_learned): the
    command whose RMS the benchmark calls effort, not the learned correction."""
    from ship_gym.agents.residual import ResidualConfig, residual_vec_env

    env_id = "ship_gym/RollOneDOF-v0"
    recorded = record_action_effort(make_sb3_vec_env(env_id, 2, seed=3, env_kwargs=KWARGS))
    residual = residual_vec_env(recorded, ResidualConfig(baseline="fins", scale=0.5), env_id)
    plain = make_sb3_vec_env(env_id, 2, seed=3, env_kwargs=KWARGS)
    from ship_gym.agents.baselines import make_baseline

    fins = make_baseline("fins", plain, env_id=env_id)
    residual.reset()
    obs_p = plain.reset()
    starts = np.ones(2, dtype=bool)
    rng = np.random.default_rng(1)
    base_seen = 0.0
    for _ in range(40):
        learned = rng.uniform(-1, 1, (2, 1))
        base, _ = fins.predict(obs_p, episode_start=starts)
        total = np.clip(base + 0.5 * learned, -1, 1)
        _, _, dones, infos = residual.step(learned)
        obs_p, _, _, _ = plain.step(total)
        starts = np.asarray(dones, dtype=bool)
        np.testing.assert_allclose(
            [info[EFFORT_INFO_KEY] for info in infos], np.mean(total**2, axis=1), atol=1e-12
        )
        base_seen += float(np.abs(base).sum())
    assert base_seen > 0  # the baseline acted, so the total differs from the learned part


def _effort_callback(limit, lr=0.5, lam0=0.0, lam_max=1.0):
    venv = make_cost_shaped(make_sb3_vec_env("ship_gym/RollOneDOF-v0", 1, seed=0), lam0,
                            EFFORT_INFO_KEY)  # fmt: skip
    cb = lagrange_multiplier_callback(
        SafeConfig(effort_limit=limit, lagrangian_lr=lr, lambda_init=lam0, lambda_max=lam_max)
    )
    model = _Model(venv)
    cb.init_callback(model)
    return cb, find_cost_shaped(venv), model


def test_effort_multiplier_follows_the_relative_violation_of_the_mean_square():
    cb, shaped, model = _effort_callback(limit=0.2)
    shaped.step_cost_sum, shaped.step_count = 0.08 * 10, 10  # mean square 0.08 = 2 × 0.2²
    cb._on_rollout_end()
    assert shaped.multiplier == pytest.approx(0.5 * (0.08 / 0.04 - 1.0))  # 0.5
    assert (shaped.step_cost_sum, shaped.step_count) == (0.0, 0)  # taken by the update
    assert model.logger.records["safe/effort"] == pytest.approx(0.08**0.5)
    assert model.logger.records["safe/effort_limit"] == 0.2
    shaped.step_cost_sum, shaped.step_count = 0.12 * 4, 4  # 3 × the budget: +1, clipped at 1
    cb._on_rollout_end()
    assert shaped.multiplier == pytest.approx(1.0)
    cb._on_rollout_end()  # no steps: unchanged
    assert shaped.multiplier == pytest.approx(1.0)
    for _ in range(3):  # zero effort: λ -= 0.5 per update, projected on λ ≥ 0
        shaped.step_cost_sum, shaped.step_count = 0.0, 8
        cb._on_rollout_end()
    assert shaped.multiplier == 0.0
    assert [h[1] for h in cb.history] == pytest.approx([0.5, 1.0, 0.5, 0.0, 0.0])


def test_exploration_variance_is_the_gaussian_policys_scaled_noise():
    """PPO's state-independent σ = exp(log_std) (its share of the applied mean square), scaled
    by the residual authority; policies without one are charged nothing."""
    import torch
    from stable_baselines3 import PPO

    from ship_gym.agents.residual import ResidualConfig, residual_vec_env

    env_id = "ship_gym/RollOneDOF-v0"
    venv = make_sb3_vec_env(env_id, 1, seed=0)
    model = PPO("MlpPolicy", venv, policy_kwargs={"log_std_init": -1.0}, device="cpu", n_steps=8)
    assert exploration_variance(model) == pytest.approx(np.exp(-2.0))
    residual = residual_vec_env(make_sb3_vec_env(env_id, 1, seed=0),
                                ResidualConfig(baseline="fins", scale=0.3), env_id)  # fmt: skip
    model = PPO("MlpPolicy", residual, device="cpu", n_steps=8)
    with torch.no_grad():
        model.policy.log_std.fill_(np.log(0.5))
    assert exploration_variance(model) == pytest.approx(0.3**2 * 0.25)
    assert exploration_variance(_Model(venv)) == 0.0


@pytest.mark.parametrize("measure", ["mean_square", "episode_rms"])
def test_training_with_a_tight_effort_budget_raises_lambda(tmp_path, measure):
    """A residual on the fin controller with a budget of 0.05 RMS, far below the fins' own
    effort in this strong forcing: λ grows every rollout (the recorder charges the total
    command, not the small learned correction), and the validation keeps the checkpoint within
    the budget or, when none is, the one of least effort — for either mean of the effort."""
    config = _tiny_config(
        tmp_path,
        {"effort_limit": 0.05, "lagrangian_lr": 0.01, "effort_measure": measure},
        n_envs=2,
        n_steps=128,
        timesteps=2560,  # the curve starts at the first episode's end (1000)
        policy={"log_std_init": -3.0},
        residual={"baseline": "fins", "scale": 0.3},
        validation={"every": 512, "episodes": 2, "first_seed": 900},
    )
    out = train(config)
    lambdas = [float(r["lambda"]) for r in csv.DictReader((out / "progress.csv").open())]
    assert len(lambdas) >= 2 and lambdas[0] > 0
    assert all(b >= a for a, b in itertools.pairwise(lambdas))
    rows = list(csv.DictReader((out / "validation.csv").open()))
    efforts = [float(r["rms_action"]) for r in rows]
    summary = json.loads((out / "summary.json").read_text())
    chosen = [int(float(r["timesteps"])) for r in rows].index(
        summary["validation"]["best_timesteps"]
    )
    feasible = [e <= 0.05 for e in efforts]
    if any(feasible):
        assert feasible[chosen]
    else:
        assert efforts[chosen] == min(efforts)


def test_a_baselines_effort_budget_is_its_measured_mean_square_and_validation_rms():
    """``effort_limit = "fins"``: e = √(mean of a² over every step of the fins' episodes on the
    training seeds), summed here by stepping the env by hand; the validation's limit is the
    fins' mean RMS action over the validation episodes (the column it compares)."""
    from ship_gym.agents.baselines import make_baseline
    from ship_gym.agents.evaluate import run_episodes, summarize

    env_id = "ship_gym/RollOneDOF-v0"
    safe = safe_config({"effort_limit": "fins", "lagrangian_lr": 0.02})
    assert safe.constraint == "effort" and safe.effort_baseline == "fins"
    with pytest.raises(ValueError, match="not measured yet"):
        _ = safe.validation_limit
    resolved, limit = resolve_effort_budget(safe, env_id, KWARGS, [7, 8], [30, 31, 32])
    squares, steps = 0.0, 0
    for seed in (7, 8):
        env = gym.make(env_id, **KWARGS)
        fins = make_baseline("fins", env)
        obs, _ = env.reset(seed=seed)
        start, done = True, False
        while not done:
            action, _ = fins.predict(obs[None], episode_start=np.array([start]))
            start = False
            a = np.clip(action[0], -1, 1)
            squares += float(np.mean(a**2))
            steps += 1
            obs, _, terminated, truncated, _ = env.step(a)
            done = terminated or truncated
    assert resolved.effort_limit == pytest.approx(np.sqrt(squares / steps), rel=1e-9)
    assert resolved.effort_baseline == "fins" and resolved.lagrangian_lr == 0.02
    fins_on_validation = summarize(run_episodes(env_id, lambda e: make_baseline("fins", e),
                                                [30, 31, 32], KWARGS))  # fmt: skip
    assert limit == ("rms_action", pytest.approx(fins_on_validation["rms_action"]))
    assert 0.0 < limit[1] <= 1.0
    # numeric budgets pass through; the validation's limit is the same number
    number = safe_config({"effort_limit": 0.3})
    assert resolve_effort_budget(number, env_id, KWARGS, [7], [30]) == (number, ("rms_action", 0.3))
    assert resolve_effort_budget(number, env_id, KWARGS, [7], None) == (number, None)


def test_training_on_a_baselines_budget_records_it_in_the_summary(tmp_path):
    config = _tiny_config(
        tmp_path,
        {"effort_limit": "fins"},
        n_envs=2,
        timesteps=256,
        seed=3,
        validation={"every": 128, "episodes": 2, "first_seed": 900},
    )
    out = train(config)
    budget = json.loads((out / "summary.json").read_text())["effort_budget"]
    from ship_gym.agents.lagrangian import CALIBRATION_EPISODES

    expected, limit = resolve_effort_budget(
        config.safe, config.env_id, KWARGS, range(3, 3 + CALIBRATION_EPISODES), range(900, 902)
    )
    assert budget == {
        "baseline": "fins",
        "training_rms_action": pytest.approx(expected.effort_limit),
        "validation_rms_action": pytest.approx(limit[1]),
    }


def test_pid_multiplier_without_p_and_d_is_the_projected_integral_update():
    config = SafeConfig(effort_limit=0.2, lagrangian_lr=0.3, lambda_max=2.0)
    state, lam, integral_only = MultiplierState(integral=0.5), 0.5, 0.5
    for violation in (1.0, 4.0, -0.2, -3.0, -1.0, 0.7):
        state, lam = update_multiplier(config, state, violation)
        integral_only = min(max(integral_only + 0.3 * violation, 0.0), 2.0)
        assert lam == pytest.approx(integral_only) and state.integral == pytest.approx(lam)


def test_pid_multiplier_prices_an_excess_at_once_and_releases_it_when_it_ends():
    """P adds K_p Δ̄ on top of the integral; D adds K_d × the rise of Δ̄ only; the smoothed
    violation is the EMA α Δ̄ + (1 − α) Δ; λ stays in [0, λ_max]."""
    config = SafeConfig(effort_limit=0.2, lagrangian_lr=0.1, lagrangian_kp=2.0,
                        lagrangian_kd=1.0, lagrangian_smoothing=0.5, lambda_max=3.0)  # fmt: skip
    state, lam = update_multiplier(config, MultiplierState(integral=0.0), 0.4)
    assert state.smoothed == pytest.approx(0.4)  # the first violation seeds the average
    assert lam == pytest.approx(0.04 + 2.0 * 0.4)  # no rise measured yet
    state, lam = update_multiplier(config, state, 0.8)  # Δ̄ = 0.6, rise 0.2
    assert (state.integral, state.smoothed) == pytest.approx((0.12, 0.6))
    assert lam == pytest.approx(0.12 + 2.0 * 0.6 + 1.0 * 0.2)
    state, lam = update_multiplier(config, state, -1.0)  # Δ̄ = −0.2: falling, no D
    assert lam == pytest.approx(max(0.02 + 2.0 * -0.2, 0.0)) and lam == 0.0
    assert state.integral == pytest.approx(0.02)
    _, lam = update_multiplier(config, MultiplierState(integral=2.9, smoothed=5.0), 5.0)
    assert lam == 3.0  # clipped at lambda_max


def _lagged_plant_run(config, updates=488):
    """The mean-square ratio m (Ĵ/e²) of a policy that learns its price λ with a lag: it moves
    1 % per update towards 1.5 / (1 + λ) (1.5 × the budget at λ = 0, on budget at λ = 0.5),
    starting at 1.5; 488 updates are 1 M steps of 8 × 256-step rollouts. Returns the ratios and
    multipliers per update."""
    state, lam, m = MultiplierState(integral=0.0), 0.0, 1.5
    ratios, lams = [], []
    for _ in range(updates):
        state, lam = update_multiplier(config, state, m - 1.0)
        m += 0.01 * (1.5 / (1.0 + lam) - m)
        ratios.append(m)
        lams.append(lam)
    return np.array(ratios), np.array(lams)


def test_pid_multiplier_winds_up_less_than_the_integral_alone_on_a_lagged_learner():
    """The windup of the shipped runs in miniature: with a slow learner the integral alone
    (K_i = 0.05) overshoots the equilibrium price λ = 0.5 almost threefold and then holds the
    policy at ≈ 0.8 of its budget (as RollStabilization seed 1 did: λ 0.9–1.4); K_p = 1 with
    K_i = 0.02 overshoots far less and leaves a third of the unspent budget. Both end on the
    budget (the integral's fixed point), so the test compares transients, not end points."""
    integral = SafeConfig(effort_limit=0.2, lagrangian_lr=0.05)
    pid = SafeConfig(effort_limit=0.2, lagrangian_lr=0.02, lagrangian_kp=1.0)
    m_i, lam_i = _lagged_plant_run(integral)
    m_p, lam_p = _lagged_plant_run(pid)
    assert abs(m_i[-1] - 1.0) < 0.02 and abs(m_p[-1] - 1.0) < 0.02
    assert lam_i.max() > 2.0 * 0.5 and m_i.min() < 0.85  # windup, then underspend
    assert lam_p.max() < 0.6 * lam_i.max() and m_p.min() > 0.95
    under_i, under_p = np.sum(np.clip(1.0 - m_i, 0, None)), np.sum(np.clip(1.0 - m_p, 0, None))
    assert under_p < 0.5 * under_i  # the unspent budget (what windup costs the task)


def test_the_callback_runs_the_pid_update_from_the_wrappers_initial_multiplier():
    venv = make_cost_shaped(make_sb3_vec_env("ship_gym/RollOneDOF-v0", 1, seed=0), 0.3,
                            EFFORT_INFO_KEY)  # fmt: skip
    config = SafeConfig(effort_limit=0.2, lagrangian_lr=0.1, lagrangian_kp=1.0)
    cb = lagrange_multiplier_callback(config)
    model = _Model(venv)
    cb.init_callback(model)
    shaped = find_cost_shaped(venv)
    shaped.step_cost_sum, shaped.step_count = 0.06 * 10, 10  # 1.5 × the budget's mean square
    cb._on_rollout_end()
    assert shaped.multiplier == pytest.approx(0.3 + 0.1 * 0.5 + 1.0 * 0.5)
    assert model.logger.records["safe/lambda_integral"] == pytest.approx(0.35)
    shaped.step_cost_sum, shaped.step_count = 0.04 * 10, 10  # on budget: P releases its share
    cb._on_rollout_end()
    assert shaped.multiplier == pytest.approx(0.35)


class _FiveStepEnv(gym.Env):
    """A minimal Gymnasium env: any action, episodes of 5 steps (for the effort recorder)."""

    observation_space = gym.spaces.Box(-1.0, 1.0, (1,))
    action_space = gym.spaces.Box(-1.0, 1.0, (2,))

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.t = 0
        return np.zeros(1, dtype=np.float32), {}

    def step(self, action):
        self.t += 1
        return np.zeros(1, dtype=np.float32), 0.0, False, self.t == 5, {}


def test_the_episode_rms_share_is_a_squared_over_the_running_rms_and_restarts_per_episode():
    """c_t = mean(a²) / max(ρ_t, ρ_min), ρ_t the RMS over the episode's steps so far (this one
    included); the running sums restart after the step that ends an episode; actions clip to
    ±1 first, as the env applies them."""
    from stable_baselines3.common.vec_env import DummyVecEnv

    venv = record_action_effort(DummyVecEnv([_FiveStepEnv, _FiveStepEnv]), rms_floor=0.1)
    venv.reset()
    rng = np.random.default_rng(3)
    sums, steps = np.zeros(2), np.zeros(2)
    for _ in range(12):  # two episodes and a part of a third
        actions = rng.uniform(-1.5, 1.5, (2, 2)) * rng.choice([0.01, 1.0], (2, 1))
        ms = np.mean(np.clip(actions, -1, 1) ** 2, axis=1)
        _, _, dones, infos = venv.step(actions)
        sums, steps = sums + ms, steps + 1
        expected = ms / np.maximum(np.sqrt(sums / steps), 0.1)
        np.testing.assert_allclose([i[EPISODE_RMS_INFO_KEY] for i in infos], expected, rtol=1e-12)
        np.testing.assert_allclose([i[EFFORT_INFO_KEY] for i in infos], ms, rtol=1e-12)
        sums[dones], steps[dones] = 0.0, 0.0
    plain = record_action_effort(DummyVecEnv([_FiveStepEnv]))
    plain.reset()
    _, _, _, infos = plain.step(np.zeros((1, 2)))
    assert EPISODE_RMS_INFO_KEY not in infos[0]  # only with a floor


def test_an_episode_rms_budget_is_the_baselines_mean_rms_and_prices_its_share(monkeypatch):
    from ship_gym.agents.baselines import make_baseline
    from ship_gym.agents.evaluate import run_episodes, summarize

    env_id = "ship_gym/RollOneDOF-v0"
    safe = safe_config({"effort_limit": "fins", "effort_measure": "episode_rms"})
    assert safe.info_key == EPISODE_RMS_INFO_KEY
    with pytest.raises(ValueError, match="not measured yet"):
        _ = safe.rms_floor
    resolved, _ = resolve_effort_budget(safe, env_id, KWARGS, [7, 8, 9], None)
    fins = summarize(run_episodes(env_id, lambda e: make_baseline("fins", e), [7, 8, 9], KWARGS))
    assert resolved.effort_limit == pytest.approx(fins["rms_action"], rel=1e-12)
    assert resolved.rms_floor == pytest.approx(0.5 * resolved.effort_limit)
    assert safe_config({"effort_limit": 0.3}).rms_floor is None  # the default measure
    # the multiplier sees (mean share / e)² − 1: here 1.5 × the budget's RMS, K_i = 0.1
    venv = make_cost_shaped(make_sb3_vec_env(env_id, 1, seed=0), 0.0, EPISODE_RMS_INFO_KEY)
    cb = lagrange_multiplier_callback(SafeConfig(effort_limit=0.2, effort_measure="episode_rms",
                                                 lagrangian_lr=0.1))  # fmt: skip
    model = _Model(venv)
    cb.init_callback(model)
    shaped = find_cost_shaped(venv)
    shaped.step_cost_sum, shaped.step_count = 0.3 * 10, 10
    cb._on_rollout_end()
    assert model.logger.records["safe/effort"] == pytest.approx(0.3)
    assert shaped.multiplier == pytest.approx(0.1 * (1.5**2 - 1.0))
    # with exploration noise of variance v the mean share is the noisy RMS √(ρ² + v)
    import ship_gym.agents.lagrangian as lagrangian

    monkeypatch.setattr(lagrangian, "exploration_variance", lambda model: 0.05)
    shaped.step_cost_sum, shaped.step_count = 0.3 * 10, 10
    cb._on_rollout_end()
    assert model.logger.records["safe/effort"] == pytest.approx(np.sqrt(0.3**2 - 0.05))


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ({"effort_limit": 0.2, "effort_measure": "rms"}, r"effort_measure = 'rms'; expected one"),
        ({"cost_limit": 1, "effort_measure": "episode_rms"}, r"effort_measure = 'episode_rms'"),
    ],
)
def test_bad_effort_measures_are_refused(table, message):
    with pytest.raises(ValueError, match=message):
        safe_config(table)
