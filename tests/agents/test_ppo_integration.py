"""Slow integration test: a short PPO run on RollOneDOF-v0 learns to beat the passive ship.

Minutes of CPU: run with ``pytest -m slow tests/agents/test_ppo_integration.py``.
"""

import pytest

import ship_gym  # noqa: F401

ROLL_ID = "ship_gym/RollOneDOF-v0"


@pytest.mark.slow
def test_ppo_improves_on_zero_action_on_the_same_seas(tmp_path):
    """100k steps of PPO (16 batched episodes through the SB3 adapter, VecNormalize) vs the zero
    action on 20 held-out seeded seas (seeds 1000–1019, never seen in training: training seeds
    are 0–15 and their continuations).

    Margins: the passive ship capsizes in ~20 % of these seas (mean return ≈ 760 of a possible
    ≈ 1000, alive bonus 1 per step); a policy that damps roll keeps all upright (≈ 975 for the
    PD baseline). We require the learned policy to gain at least 100 in mean return (half the
    observed gap, room for seed-to-seed training variance) and to capsize strictly less often.
    """
    from ship_gym.agents.evaluate import evaluate_policies
    from ship_gym.agents.train import config_from_mapping, train

    config = config_from_mapping(
        {
            "env": {"id": ROLL_ID, "n_envs": 16, "vectorization": "vector", "normalize": True},
            "algorithm": {
                "name": "PPO",
                "hyperparameters": {
                    "n_steps": 128,
                    "batch_size": 512,
                    "n_epochs": 10,
                    "learning_rate": 3e-4,
                    "gamma": 0.99,
                },
                "policy_kwargs": {"net_arch": [64, 64]},
            },
            "training": {
                "total_timesteps": 100_000,
                "seed": 0,
                "output_dir": str(tmp_path / "run"),
                "progress_bar": False,
                "tensorboard": False,
                "torch_threads": 1,
            },
        }
    )
    run = train(config)
    results = evaluate_policies(
        ROLL_ID, ["zero", f"model:{run}"], episodes=20, seed=1000, progress=False
    )
    zero = results["policies"]["zero"]
    learned = results["policies"]["model:run"]
    assert zero["capsize_rate"] > 0.0  # the test seas are hard enough to matter
    assert learned["mean_return"] > zero["mean_return"] + 100.0
    assert learned["capsize_rate"] < zero["capsize_rate"]
