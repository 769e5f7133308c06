"""SB3 training as Ray tasks on a local 2-CPU cluster: env creation inside the workers, two seeds
of the shipped ppo_roll_one_dof config, both models saved and loadable."""

from __future__ import annotations

import json
import time

import pytest

from ship_gym.agents.distributed import plan_runs, train_on_ray


def test_plan_runs_validates_before_any_cluster(tmp_path):
    plans = plan_runs(["ppo_roll_one_dof"], [3, 4], timesteps=512, n_envs=2, output_dir=tmp_path)
    assert [p.seed for p in plans] == [3, 4]
    assert plans[0].output_dir == str(tmp_path / "ppo_roll_one_dof" / "seed_3")
    assert all(p.total_timesteps == 512 and p.n_envs == 2 and not p.progress_bar for p in plans)
    with pytest.raises(ValueError, match="seeds must be distinct"):
        plan_runs(["ppo_roll_one_dof"], [1, 1])
    with pytest.raises(ValueError, match="seeds must be integers"):
        plan_runs(["ppo_roll_one_dof"], [1.5])  # type: ignore[list-item]
    with pytest.raises(ValueError, match="configs must be a non-empty sequence"):
        plan_runs("ppo_roll_one_dof", [1])
    with pytest.raises(FileNotFoundError, match="no config file"):
        plan_runs(["no_such_config"], [1])


def test_two_seeds_on_a_local_two_worker_cluster(tmp_path):
    ray = pytest.importorskip("ray")
    pytest.importorskip("stable_baselines3")
    from stable_baselines3 import PPO

    assert not ray.is_initialized()
    t0 = time.perf_counter()
    models = train_on_ray(
        ["ppo_roll_one_dof"],
        [0, 1],
        workers=2,
        timesteps=512,
        n_envs=2,
        tensorboard=False,
        output_dir=tmp_path,
    )
    print(f"train_on_ray: {time.perf_counter() - t0:.1f} s")
    assert not ray.is_initialized()  # the local cluster it started is shut down
    assert models == [tmp_path / "ppo_roll_one_dof" / f"seed_{s}" / "model.zip" for s in (0, 1)]
    params = []
    for model_path in models:
        assert model_path.is_file()
        summary = json.loads((model_path.parent / "summary.json").read_text())
        assert summary["num_timesteps"] >= 512
        model = PPO.load(model_path, device="cpu")
        assert model.seed in (0, 1)
        params.append(next(iter(model.policy.parameters())).detach().numpy().copy())
    assert (params[0] != params[1]).any()  # different seeds, different policies
