"""A trained policy as a campaign's controller (issue #17): the policy drives the env it was
trained in, with the cell's sea, heading, speed, loading and capsize angle pinned."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

pytest.importorskip("pyarrow")

from ship_gym.agents.train import config_from_mapping, train
from ship_gym.analysis import campaign as cp

CAMPAIGN = """
name = "policy"
ships = ["s175"]
loadings = [{{kg = 9.8}}]
headings_deg = {headings}
froude_numbers = [0.3]
seeds = 2
duration_s = 20.0
dt_s = 0.1
integrator = "holloway"
capsize_angle_deg = {angle}
controller = "policy:{run}"
batch_seeds = 2

[[seas]]
kind = "regular"
height_m = 4.0
wavelength_m = 200.0
ramp_s = 5.0
"""


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory) -> Path:
    """A (barely) trained PPO on CapsizeAvoidance-v2, saved with its config.toml."""
    out = tmp_path_factory.mktemp("ppo") / "run"
    config = config_from_mapping(
        {
            "env": {"id": "ship_gym/CapsizeAvoidance-v2", "n_envs": 1, "normalize": True},
            "algorithm": {
                "name": "PPO",
                "hyperparameters": {"n_steps": 32, "batch_size": 32, "n_epochs": 1},
                "policy_kwargs": {"net_arch": [8]},
            },
            "training": {
                "total_timesteps": 32,
                "output_dir": str(out),
                "progress_bar": False,
                "tensorboard": False,
                "torch_threads": 1,
            },
        }
    )
    return train(config)


def _campaign(tmp_path: Path, run: Path, headings="[180, 60]", angle="60.0") -> Path:
    path = tmp_path / "c.toml"
    path.write_text(CAMPAIGN.format(headings=headings, angle=angle, run=run))
    return path


def test_policy_cells_run_the_training_env_with_the_cells_sea(run_dir, tmp_path):
    spec = cp.read_campaign(_campaign(tmp_path, run_dir))
    assert spec.policy is not None and spec.policy.env_id == "ship_gym/CapsizeAvoidance-v2"
    res = cp.run_campaign(spec, tmp_path / "store", progress=False)
    assert res.n_run == 4
    by_heading = {}
    for r in res.records:
        assert r["engine"] == "env:ship_gym/CapsizeAvoidance-v2" and r["batch_size"] == 2
        assert r["controller"] == "policy:" + str(run_dir / "model.zip")
        assert r["simulated_time_s"] == pytest.approx(20.0) and not r["capsized"]
        # the cell's speed is the initial speed (Fn 0.3 of the S175: 12.43 m/s)
        assert abs(r["mean_speed_mps"] - 12.43) < 1.5
        by_heading.setdefault(r["heading_deg"], []).append(r["max_abs_roll_deg"])
    # the cell's heading reaches the env: head seas leave the symmetric ship upright while the
    # policy holds the course (its set-point changes are ≤ 2°/step; roll < 0.5°), 60° rolls it
    assert max(by_heading[180.0]) < 0.5 < min(by_heading[60.0])
    # run again: nothing new; the same campaign in a second store gives the same outcomes
    assert cp.run_campaign(spec, tmp_path / "store", progress=False).n_run == 0
    again = cp.run_campaign(spec, tmp_path / "store2", progress=False).records
    assert [r["max_abs_roll_deg"] for r in again] == [r["max_abs_roll_deg"] for r in res.records]


def test_capsize_under_a_policy_is_recorded_with_its_time(run_dir, tmp_path):
    spec = cp.read_campaign(_campaign(tmp_path, run_dir, headings="[90]", angle="1.0"))
    recs = cp.run_campaign(spec, tmp_path / "s", progress=False).records
    assert all(r["capsized"] and r["reason"] == "roll" for r in recs)
    for r in recs:
        assert 0.0 < r["time_to_capsize_s"] < 20.0
        assert r["simulated_time_s"] == pytest.approx(r["time_to_capsize_s"])
        assert r["max_abs_roll_deg"] > 1.0


def test_policy_cells_are_identified_by_the_model_content_not_its_path(run_dir, tmp_path):
    ids = {c.cell_id for c in cp.cells(cp.read_campaign(_campaign(tmp_path, run_dir)))}
    moved = tmp_path / "moved"
    shutil.copytree(run_dir, moved)
    assert {c.cell_id for c in cp.cells(cp.read_campaign(_campaign(tmp_path, moved)))} == ids
    (moved / "model.zip").write_bytes((moved / "model.zip").read_bytes() + b"\0")
    changed = {c.cell_id for c in cp.cells(cp.read_campaign(_campaign(tmp_path, moved)))}
    assert not changed & ids


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (('controller = "policy:', 'controller = "policy:missing/'), r"no saved model"),
        (('controller = "', 'controller = "pilot'), r"expected 'autopilot', 'none' or 'policy:"),
        (("dt_s = 0.1", 'dt_s = 0.1\nradiation = "convolution"'), r"radiation = 'convolution'"),
        (("{kg = 9.8}", "{kg = 9.8, n_sections = 40}"), r"n_sections = 40.*kg only"),
        (
            (
                "ramp_s = 5.0",
                "ramp_s = 5.0\n[[seas]]\nkind = 'jonswap'\nhs_m = 3.0\ntp_s = 10.0\n"
                "spreading_s = 4",
            ),
            r"spreading_s = 4.0.*long-crested seas only",
        ),
    ],
)
def test_what_the_policy_env_cannot_run_is_refused_at_read_time(run_dir, tmp_path, edit, message):
    path = _campaign(tmp_path, run_dir)
    path.write_text(path.read_text().replace(*edit))
    with pytest.raises(cp.CampaignError, match=message):
        cp.read_campaign(path)


def test_a_model_without_its_config_is_refused(run_dir, tmp_path):
    lone = tmp_path / "lone"
    lone.mkdir()
    shutil.copy(run_dir / "model.zip", lone / "model.zip")
    with pytest.raises(cp.CampaignError, match=r"config\.toml is missing"):
        cp.read_campaign(_campaign(tmp_path, lone / "model.zip"))


def test_a_residual_policy_is_refused_at_read_time(run_dir, tmp_path):
    # a residual run's model is only the correction of a classical controller: a campaign cell
    # cannot add the controller (analysis may not import agents), so it must not run it bare
    residual = tmp_path / "residual"
    shutil.copytree(run_dir, residual)
    (residual / "residual.json").write_text("{}")
    with pytest.raises(cp.CampaignError, match=r"is a residual policy .* campaign cells cannot"):
        cp.read_campaign(_campaign(tmp_path, residual))
