"""ship_gym.agents.validation: deterministic evaluation during training and checkpoint choice.

The run's saved checkpoints are checked against the evaluations recorded during training by
re-evaluating them on the same validation episodes: the deterministic policy on the same seeds
gives the same return to rounding (1e-9 relative: the same float operations, only the order of
the batched episodes' sums could differ), so the best checkpoint and its observation statistics
must have been saved together at the moment of its evaluation.
"""

import csv
import json

import pytest

import ship_gym  # noqa: F401
from ship_gym.agents.evaluate import run_episodes
from ship_gym.agents.residual import load_agent_policy
from ship_gym.agents.train import config_from_mapping, train
from ship_gym.agents.validation import (
    VALIDATION_FILE,
    ValidationConfig,
    best_evaluation,
    validation_config,
)

from .test_train import _tiny_config

ENV = "ship_gym/RollOneDOF-v0"
STEPS = 40  # episode length of the validation (and training) episodes [control steps]


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ({"evry": 10}, r"unknown keys \['evry'\] in \[validation\]"),
        ({"every": 0}, r"validation.every must be an integer >= 1, got 0"),
        ({"every": 1.5}, r"validation.every must be an integer >= 1, got 1.5"),
        ({"episodes": True}, r"validation.episodes must be an integer >= 1, got True"),
        ({"first_seed": -1}, r"validation.first_seed must be an integer >= 0, got -1"),
        ({"keep_best": "yes"}, r"validation.keep_best must be true or false, got 'yes'"),
    ],
)
def test_bad_validation_tables_name_the_key_and_value(table, message):
    with pytest.raises(ValueError, match=message):
        validation_config(table)
    with pytest.raises(ValueError, match=message):  # the same through a training config
        config_from_mapping({"env": {"id": ENV}, "validation": table})


def test_validation_seeds_may_not_be_training_episodes():
    data = {"env": {"id": ENV, "n_envs": 4}, "training": {"seed": 4998}, "validation": {}}
    message = (
        r"validation seeds 5000 … 5007 overlap the training episodes' seeds 4998 … 5001 "
        r"\(training.seed 4998, env.n_envs 4\)"
    )
    with pytest.raises(ValueError, match=message):
        config_from_mapping(data)
    data["training"]["seed"] = 4996  # episodes 4996 … 4999
    assert config_from_mapping(data).validation == ValidationConfig()


def test_defaults_and_seeds():
    config = validation_config({"episodes": 3, "first_seed": 70})
    assert config == ValidationConfig(every=50_000, episodes=3, first_seed=70, keep_best=True)
    assert list(config.seeds) == [70, 71, 72]


def _rows(*pairs):
    return [{"mean_return": r, "mean_cost": c} for r, c in pairs]


def test_best_evaluation_is_the_highest_return_within_the_cost_limit():
    rows = _rows((-5.0, 3.0), (-1.0, 9.0), (-2.0, 1.0), (-1.0, 0.5))
    assert best_evaluation(rows) == 1  # ties go to the earliest
    assert best_evaluation(rows, ("mean_cost", 2.0)) == 3  # -1.0 at cost 0.5 is feasible
    assert best_evaluation(rows, ("mean_cost", 1.0)) == 3
    assert best_evaluation(rows, ("mean_cost", 0.1)) == 3  # none feasible: the least cost
    efforts = [dict(r, rms_action=e) for r, e in zip(rows, (0.1, 0.3, 0.2, 0.4), strict=True)]
    assert best_evaluation(efforts, ("rms_action", 0.25)) == 2  # -2.0 at 0.2: best feasible
    assert best_evaluation(efforts, ("rms_action", 0.05)) == 0  # none feasible: least effort
    with pytest.raises(ValueError, match="no column 'rms'"):
        best_evaluation(efforts, ("rms", 0.1))
    with pytest.raises(ValueError, match="no evaluations"):
        best_evaluation([])


def _validated_config(tmp_path, keep_best=True, residual=False):
    data = _tiny_config(tmp_path, total_timesteps=256)
    data["env"]["kwargs"] = {"max_episode_steps": STEPS}
    data["validation"] = {"every": 64, "episodes": 3, "first_seed": 900, "keep_best": keep_best}
    if residual:
        data["residual"] = {"baseline": "fins", "scale": 0.5}
    return config_from_mapping(data)


def _table(out):
    with (out / VALIDATION_FILE).open() as fh:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(fh)]


def _validation_return(path):
    seeds = [900, 901, 902]
    stats = run_episodes(ENV, load_agent_policy(path), seeds, {"max_episode_steps": STEPS})
    return float(stats.returns.mean())


@pytest.mark.parametrize("residual", [False, True])
def test_the_run_keeps_the_best_checkpoint_with_its_statistics(tmp_path, residual):
    out = train(_validated_config(tmp_path, residual=residual))
    rows = _table(out)
    # every 64 steps (2 envs x 32-step rollouts), the last at the end of training
    assert [r["timesteps"] for r in rows] == [64, 128, 192, 256]
    best = max(range(len(rows)), key=lambda i: (rows[i]["mean_return"], -i))
    summary = json.loads((out / "summary.json").read_text())["validation"]
    assert summary["model"] == "best"
    assert summary["best_timesteps"] == rows[best]["timesteps"]
    assert summary["seeds"] == [900, 902]
    # model.zip (with vecnormalize.npz) is the best evaluated policy, final_model.zip (with
    # final_vecnormalize.npz) the last: both reproduce their recorded validation return
    assert _validation_return(out) == pytest.approx(rows[best]["mean_return"], rel=1e-9)
    last = rows[-1]["mean_return"]
    assert _validation_return(out / "final_model.zip") == pytest.approx(last, rel=1e-9)
    assert not (out / "best_model.zip").exists()  # moved into model.zip
    assert len({round(r["mean_return"], 9) for r in rows}) > 1  # the policy did change


def test_without_keep_best_the_model_is_the_last_and_stale_checkpoints_go(tmp_path):
    stale = tmp_path / "run"
    stale.mkdir()
    (stale / "final_model.zip").write_text("an earlier run's")
    out = train(_validated_config(tmp_path, keep_best=False))
    assert not (out / "final_model.zip").exists()
    rows = _table(out)
    assert _validation_return(out) == pytest.approx(rows[-1]["mean_return"], rel=1e-9)
    assert json.loads((out / "summary.json").read_text())["validation"]["model"] == "final"


def test_the_benchmark_shows_the_validation_curve_and_the_chosen_checkpoint(tmp_path):
    from ship_gym.agents.benchmark import TASKS, _curve, _plot_curves, _row, results_markdown

    out = train(_validated_config(tmp_path))
    curve = _curve(out)
    assert curve["validation_timesteps"] == [64, 128, 192, 256]
    assert curve["validation_return"] == [r["mean_return"] for r in _table(out)]
    figure = tmp_path / "curves.png"
    _plot_curves("RollOneDOF", TASKS["RollOneDOF"], {"tiny": [curve]}, figure)
    assert figure.stat().st_size > 1000
    metrics = {"episodes": 2.0, "capsize_rate": 0.0, "rms_action": 0.1, "mean_return": 1.0,
               "mean_cost": 0.0}  # fmt: skip
    row = _row("tiny seed 0", metrics, TASKS["RollOneDOF"],
               {"config": "tiny", "timesteps": 256_000, "model_timesteps": 128_000})  # fmt: skip
    task = {"env_id": ENV, "metric_label": "capsize rate [-]", "strongest_baseline": None,
            "seed": 10_000, "episodes": 2, "n_seeds": 1, "timesteps": 256, "date": "today",
            "rows": [row]}  # fmt: skip
    assert "| 256 k (model at 128 k) |" in results_markdown({"tasks": {"RollOneDOF": task}})
