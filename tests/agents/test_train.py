"""ship_gym.agents.train and ship_gym.cli.agents: configs, a tiny training run, CLI wiring."""

import argparse
import tomllib

import numpy as np
import pytest

import ship_gym  # noqa: F401
from ship_gym.agents.configs import shipped_config_names
from ship_gym.agents.evaluate import load_policy
from ship_gym.agents.train import config_from_mapping, dump_toml, load_config, train
from ship_gym.cli import agents as cli_agents
from ship_gym.envs import ENV_IDS, REGISTERED_IDS

CONFIGS = shipped_config_names()


def test_there_is_a_config_for_every_env_id():
    # by environment name: the ship tasks' configs train the -v2 ids of the published benchmark
    ids = {load_config(p).env_id for p in CONFIGS}
    assert ids <= set(REGISTERED_IDS)
    assert {i.split("/")[1].split("-v")[0] for i in ids} == {
        i.split("/")[1].split("-v")[0] for i in ENV_IDS
    }


@pytest.mark.parametrize("name", CONFIGS)
def test_shipped_configs_are_valid_and_round_trip(name):
    config = load_config(name)
    assert config.algorithm in ("PPO", "SAC")
    assert config.total_timesteps > 10_000
    assert tomllib.loads(dump_toml(config.raw)) == config.raw


def test_config_errors_are_clear(tmp_path):
    with pytest.raises(ValueError, match="unknown keys"):
        config_from_mapping({"env": {"id": "x", "n_env": 4}})
    with pytest.raises(ValueError, match=r"\[env\] id"):
        config_from_mapping({"env": {}})
    with pytest.raises(ValueError, match=r"algorithm\.name"):
        config_from_mapping({"env": {"id": "x"}, "algorithm": {"name": "DQNN"}})
    bad = tmp_path / "bad.toml"
    bad.write_text("[env\nid=")
    with pytest.raises(ValueError, match="invalid TOML"):
        load_config(bad)
    with pytest.raises(FileNotFoundError):
        load_config(tmp_path / "missing.toml")


def _tiny_config(tmp_path, **training):
    return {
        "env": {"id": "ship_gym/RollOneDOF-v0", "n_envs": 2, "normalize": True},
        "algorithm": {
            "name": "PPO",
            "hyperparameters": {"n_steps": 32, "batch_size": 64, "n_epochs": 1},
            "policy_kwargs": {"net_arch": [16]},
        },
        "training": {
            "total_timesteps": 128,
            "output_dir": str(tmp_path / "run"),
            "progress_bar": False,
            "tensorboard": True,
            **training,
        },
    }


def test_smoke_train_tiny_ppo_saves_model_config_normalizer(tmp_path):
    out = train(config_from_mapping(_tiny_config(tmp_path)))
    for name in ("model.zip", "config.toml", "vecnormalize.npz", "summary.json"):
        assert (out / name).exists(), name
    assert not (out / "vecnormalize.pkl").exists()  # no pickle written
    assert any((out / "tensorboard").rglob("events.out.tfevents*"))
    policy = load_policy(out)  # no opt-in: its digest was recorded by this training
    assert policy.obs_normalizer is not None
    action, _ = policy.predict(np.zeros((3, 4), np.float32))
    assert action.shape == (3, 1)


def test_a_retrain_removes_the_earlier_summary_before_it_starts(tmp_path, monkeypatch):
    # summary.json marks a finished run (the benchmark reuses it): while a new run trains in the
    # same folder, the earlier run's summary must be gone, else its model would pass as this one
    import ship_gym.agents.train as train_module

    config = config_from_mapping(_tiny_config(tmp_path, tensorboard=False))
    out = train(config)
    seen = []
    make_curve = train_module.learning_curve_callback

    def spying_curve():
        curve = make_curve()
        start = curve._on_training_start

        def on_start():
            seen.append((out / "summary.json").exists())
            start()

        curve._on_training_start = on_start
        return curve

    monkeypatch.setattr(train_module, "learning_curve_callback", spying_curve)
    train(config)
    assert seen == [False]
    assert (out / "summary.json").exists()


def _parser():
    parser = argparse.ArgumentParser()
    sub = parser.add_subparsers(dest="command", required=True)
    cli_agents.add_commands(sub)
    return parser


def test_smoke_cli_train_and_evaluate(tmp_path, capsys):
    config = tmp_path / "c.toml"
    config.write_text(dump_toml(_tiny_config(tmp_path, tensorboard=False)))
    args = _parser().parse_args(["train", str(config), "--timesteps", "64", "--no-progress"])
    assert args.func(args) == 0
    run = tmp_path / "run"
    args = _parser().parse_args(
        [
            "evaluate",
            "--env",
            "ship_gym/RollOneDOF-v0",
            "--policies",
            f"zero,fins,model:{run}",
            "--episodes",
            "2",
            "--max-steps",
            "20",
            "--out",
            str(tmp_path / "ev"),
            "--no-progress",
            "--no-plot",
        ]
    )
    assert args.func(args) == 0
    printed = capsys.readouterr().out
    assert "capsize_rate" in printed
    assert (tmp_path / "ev" / "evaluation.csv").exists()


@pytest.mark.parametrize(
    ("section", "key", "value", "expected"),
    [
        ("hyperparameters", "batch_size", 0, r"algorithm\.hyperparameters\.batch_size = 0; exp"),
        ("hyperparameters", "batch_size", 1, r"batch_size = 1; expected an integer in \[2, "),
        ("hyperparameters", "n_steps", 0, r"algorithm\.hyperparameters\.n_steps = 0; expected"),
        ("hyperparameters", "gamma", 2, r"algorithm\.hyperparameters\.gamma = 2; .* \(0, 1\]"),
        ("hyperparameters", "gamma", True, r"gamma = True; expected a number in \(0, 1\]"),
        ("hyperparameters", "learning_rate", "fast", r"learning_rate = 'fast'; expected a num"),
        ("hyperparameters", "n_epochs", 2.5, r"n_epochs = 2\.5; expected an integer"),
        ("hyperparameters", "ent_coef", -1.0, r"ent_coef = -1\.0; expected a number >= 0"),
        ("hyperparameters", "n_step", 64, r"hyperparameters\.n_step: not a PPO hyperparameter"),
        ("algorithm", "policy", "CnnPolicy", r"algorithm\.policy = 'CnnPolicy'; expected one of"),
        ("training", "total_timesteps", True, r"training\.total_timesteps = True; expected an i"),
        ("training", "total_timesteps", 1e20, r"total_timesteps = 1e\+20; expected an integer"),
        ("training", "total_timesteps", 0, r"training\.total_timesteps = 0; expected"),
    ],
)
def test_bad_training_values_are_refused_at_read_time_naming_the_key(
    tmp_path, section, key, value, expected
):
    data = _tiny_config(tmp_path)
    if section == "hyperparameters":
        data["algorithm"]["hyperparameters"][key] = value
    else:
        data[section][key] = value
    with pytest.raises(ValueError, match=expected):
        config_from_mapping(data)


def test_a_one_step_rollout_is_refused_and_integral_floats_are_counts(tmp_path):
    data = _tiny_config(tmp_path)
    data["env"]["n_envs"] = 1
    data["algorithm"]["hyperparameters"]["n_steps"] = 1
    with pytest.raises(ValueError, match=r"n_steps = 1 with env\.n_envs = 1: .* >= 2"):
        config_from_mapping(data)
    data = _tiny_config(tmp_path)
    data["training"]["total_timesteps"] = 1e3  # TOML 1e3 is a float
    assert config_from_mapping(data).total_timesteps == 1000


def test_train_cli_names_a_bad_hyperparameter_without_a_traceback(tmp_path, capsys):
    from ship_gym.cli import main

    config = tmp_path / "bad.toml"
    config.write_text(
        '[env]\nid = "ship_gym/RollOneDOF-v0"\n[algorithm.hyperparameters]\nbatch_size = 0\n',
        encoding="utf-8",
    )
    assert main(["train", str(config), "--no-progress"]) == 1
    err = capsys.readouterr().err
    assert "algorithm.hyperparameters.batch_size = 0" in err and "internal error" not in err
    assert "Traceback" not in err
