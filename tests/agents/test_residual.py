"""ship_gym.agents.residual: a learned correction on a classical controller.

The composition a = clip(a_baseline + scale · a_learned, −1, 1) is checked exactly (the same
float arithmetic on both sides) on RollOneDOF-v0, the cheapest env with a baseline.
"""

import json

import numpy as np
import pytest

import ship_gym  # noqa: F401
from ship_gym.agents.baselines import DEFAULT_GAINS, make_baseline
from ship_gym.agents.evaluate import evaluate_policies
from ship_gym.agents.residual import (
    RESIDUAL_FILE,
    ResidualConfig,
    ResidualPolicy,
    find_residual,
    load_agent_policy,
    residual_config,
    residual_vec_env,
)
from ship_gym.agents.train import config_from_mapping, load_config, train
from ship_gym.envs.sb3 import make_sb3_vec_env

from .test_train import _tiny_config

ENV = "ship_gym/RollOneDOF-v0"


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ({"baseline": "fins", "scales": 0.5}, r"unknown keys \['scales'\] in \[residual\]"),
        ({"baseline": "zero"}, r"residual.baseline must be one of .*got 'zero'"),
        ({"baseline": "fin"}, r"residual.baseline must be one of .*got 'fin'"),
        ({"baseline": "fins", "scale": 0.0}, r"residual.scale must be .*got 0.0"),
        ({"baseline": "fins", "scale": 3}, r"residual.scale must be .*got 3"),
        ({"baseline": "fins", "scale": True}, r"residual.scale must be .*got True"),
        ({"baseline": "fins", "gains": {"k_p": 1.0}}, r"unknown gains \['k_p'\] .* of 'fins'"),
    ],
)
def test_bad_residual_tables_name_the_key_and_value(table, message):
    with pytest.raises(ValueError, match=message):
        residual_config(table)
    with pytest.raises(ValueError, match=message):  # the same through a training config
        config_from_mapping({"env": {"id": ENV}, "residual": table})


def test_wrapper_steps_the_env_with_the_baseline_plus_the_scaled_residual():
    scale = 0.4
    wrapped = residual_vec_env(make_sb3_vec_env(ENV, 3, seed=5), ResidualConfig("fins", scale), ENV)
    baseline = wrapped.baseline
    # an SB3 VecEnv has no spec: the env id given selects the per-env gains and is recorded
    assert baseline.layout.env_id == ENV
    gains = DEFAULT_GAINS[("fins", "RollOneDOF")]
    assert (baseline.k_roll, baseline.k_rate) == (gains["k_roll"], gains["k_rate"])
    reference = make_sb3_vec_env(ENV, 3, seed=5)
    reference_baseline = make_baseline("fins", reference, env_id=ENV)
    obs, ref_obs = wrapped.reset(), reference.reset()
    rng = np.random.default_rng(0)
    for step in range(40):
        residual = rng.uniform(-1, 1, (3, 1)).astype(np.float32) * (step % 2)
        base, _ = reference_baseline.predict(ref_obs)
        ref_obs, ref_reward, _, _ = reference.step(np.clip(base + scale * residual, -1, 1))
        obs, reward, _, _ = wrapped.step(residual)
        np.testing.assert_array_equal(obs, ref_obs)
        np.testing.assert_array_equal(reward, ref_reward)
    assert find_residual(wrapped) is wrapped
    with pytest.raises(ValueError, match="no residual wrapper"):
        find_residual(reference)


def _residual_training_config(tmp_path, gains=None):
    residual = {"baseline": "fins", "scale": 0.3}
    if gains:
        residual["gains"] = gains
    data = _tiny_config(tmp_path, total_timesteps=64, tensorboard=False)  # RollOneDOF-v0, PPO
    return config_from_mapping({**data, "residual": residual})


def test_a_trained_residual_run_loads_as_baseline_plus_scaled_model(tmp_path):
    out = train(_residual_training_config(tmp_path, gains={"k_rate": 12.5}))
    saved = json.loads((out / RESIDUAL_FILE).read_text())
    # every gain is recorded, resolved: the override and the per-env default of the other
    assert saved["parameters"] == {"k_roll": 2.0, "k_rate": 12.5}
    assert saved["layout"]["env_id"] == ENV
    policy = load_agent_policy(out)
    assert isinstance(policy, ResidualPolicy)
    assert (policy.baseline.k_roll, policy.baseline.k_rate, policy.scale) == (2.0, 12.5, 0.3)
    obs = np.random.default_rng(1).normal(0.0, 0.05, (5, 4)).astype(np.float32)
    action, _ = policy.predict(obs)
    base, _ = policy.baseline.predict(obs)
    learned, _ = policy.learned.predict(obs)
    np.testing.assert_array_equal(action, np.clip(base + 0.3 * learned, -1, 1).astype(np.float32))
    # the bare correction is never taken for the policy (campaign cells load with load_policy)
    from ship_gym.envs.saved_policies import load_policy

    with pytest.raises(ValueError, match=r"is a residual policy .*load_agent_policy"):
        load_policy(out)
    # the saved gains, not the current defaults, define the policy
    saved["parameters"]["k_rate"] = 40.0
    (out / RESIDUAL_FILE).write_text(json.dumps(saved))
    assert load_agent_policy(out).baseline.k_rate == 40.0


def test_evaluation_runs_a_residual_run_through_its_baseline(tmp_path):
    out = train(_residual_training_config(tmp_path))
    results = evaluate_policies(
        ENV, ["fins", f"model:{out}"], episodes=2, seed=50, max_steps=30, progress=False
    )
    rows = results["policies"]
    # a 64-step PPO's correction is tiny (action head initialised at gain 0.01): the residual
    # policy acts as the fin baseline to within a few per cent of its action
    fins, residual = rows["fins"], rows["model:run"]
    assert residual["rms_action"] == pytest.approx(fins["rms_action"], rel=0.1)
    assert residual["rms_action"] != fins["rms_action"]


def test_shipped_residual_configs_name_a_baseline_of_their_env():
    for name, baseline in (("ppo_residual_course_keeping", "pid"),):
        config = load_config(name)
        assert config.residual is not None and config.residual.baseline == baseline
        env_name = config.env_id.split("/")[-1].split("-v")[0]
        assert (baseline, env_name) in DEFAULT_GAINS
