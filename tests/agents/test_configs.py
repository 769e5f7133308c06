"""ship_gym.agents as a package: shipped configs found by name from anywhere; no torch on import."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

import ship_gym
from ship_gym.agents.configs import find_config, shipped_config, shipped_config_names
from ship_gym.agents.train import load_config
from ship_gym.envs import ENV_IDS, REGISTERED_IDS

SHIPPED = [
    "ppo_capsize_avoidance",
    "ppo_course_keeping",
    "ppo_heavy_weather",
    "ppo_lagrangian_capsize_avoidance",
    "ppo_residual_course_keeping",
    "ppo_roll_one_dof",
    "ppo_roll_stabilization",
    "sac_ride_control",
]
REPO = Path(ship_gym.__file__).parents[1]


def test_shipped_configs_are_found_by_name_from_any_working_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert shipped_config_names() == SHIPPED
    for name in SHIPPED:
        for spelling in (name, f"{name}.toml"):
            config = load_config(spelling)
            assert config.env_id in REGISTERED_IDS
            # relative output directories stay relative: the user's working directory
            assert not Path(config.output_dir).is_absolute()
            assert Path(config.output_dir).resolve().is_relative_to(tmp_path)
        assert load_config(name, output_dir="here").output_dir == "here"
    # every environment has a shipped config; the ship tasks' configs train the -v2 ids, the
    # forward-speed model of the published benchmark (docs/benchmarks/results.md)
    names = {load_config(n).env_id.split("/")[1].split("-v")[0] for n in SHIPPED}
    assert names == {i.split("/")[1].split("-v")[0] for i in ENV_IDS}


def test_a_file_is_read_before_a_shipped_name_and_paths_work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    own = tmp_path / "ppo_roll_one_dof.toml"
    own.write_text('[env]\nid = "ship_gym/RollOneDOF-v0"\n[training]\noutput_dir = "mine"\n')
    assert load_config("ppo_roll_one_dof.toml").output_dir == "mine"  # the file here
    assert load_config("ppo_roll_one_dof").output_dir == "runs/ppo_roll_one_dof"  # shipped
    shipped = Path(str(shipped_config("ppo_roll_one_dof")))
    assert load_config(shipped).env_id == "ship_gym/RollOneDOF-v0"  # a path to the package file
    assert find_config(str(own)) == own


def test_unknown_configs_name_the_shipped_ones(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(FileNotFoundError, match="shipped: ppo_capsize_avoidance, "):
        load_config("ppo_roll_two_dof")
    with pytest.raises(FileNotFoundError, match="no config file"):
        load_config(tmp_path / "sub" / "ppo_roll_one_dof.toml")  # a path is not a name
    with pytest.raises(FileNotFoundError, match="no shipped config"):
        shipped_config("nope")


def _loaded_modules(code: str, cwd: Path | None = None) -> list[str]:
    out = subprocess.run(
        [sys.executable, "-c", f"{code}; import json, sys; print(json.dumps(sorted(sys.modules)))"],
        capture_output=True,
        text=True,
        timeout=120,
        check=True,
        cwd=cwd,
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize(
    "module",
    [
        "ship_gym.agents",
        "ship_gym.agents.baselines",
        "ship_gym.agents.train",
        "ship_gym.agents.evaluate",
    ],
)
def test_importing_the_agents_loads_neither_torch_nor_sb3(module):
    loaded = _loaded_modules(f"import {module}")
    assert module in loaded
    assert not [m for m in loaded if m.split(".")[0] in ("torch", "stable_baselines3")]


def test_no_top_level_agents_package_is_installed(tmp_path):
    code = (
        "import importlib.util; spec = importlib.util.find_spec('agents'); "
        "print('ORIGIN', None if spec is None else spec.origin)"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, check=True,
        cwd=tmp_path,
    ).stdout  # fmt: skip
    origin = out.split("ORIGIN ", 1)[1].strip()
    assert origin == "None" or not Path(origin).resolve().is_relative_to(REPO)


def test_cli_trains_a_shipped_config_by_name_into_the_working_directory(tmp_path, monkeypatch):
    pytest.importorskip("stable_baselines3")
    from ship_gym.cli import main

    monkeypatch.chdir(tmp_path)
    argv = ["train", "ppo_roll_one_dof", "--timesteps", "64", "--n-envs", "2", "--no-progress"]
    assert main(argv) == 0
    run = tmp_path / "runs" / "ppo_roll_one_dof"
    assert (run / "model.zip").exists() and (run / "config.toml").exists()
