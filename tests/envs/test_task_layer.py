"""The task layer of issue #31: the config, the episode sampler, the comfort component and a
new task written the small way (the example of docs/tutorials/your_own_task.md, run here)."""

from __future__ import annotations

import dataclasses
import importlib.util
import re
import sys
from pathlib import Path

import gymnasium
import numpy as np
import pytest

from ship_gym.agents.baselines import RollFinController
from ship_gym.envs.config import SHIP_FIELDS, SPEED_LIMITS, ShipConfig, config_arguments
from ship_gym.envs.course_keeping import CourseKeepingTask
from ship_gym.envs.docstrings import SHIP_ARGUMENTS
from ship_gym.envs.env_task import SHIP_KWARGS, ShipEnvTask

from ._ship_env_checks import COARSE, COARSE_MESH, assert_checkers_pass_without_warnings

TUTORIAL = Path(__file__).resolve().parents[2] / "docs" / "tutorials" / "your_own_task.md"


def test_the_config_is_the_single_source_of_the_shared_arguments():
    rows = config_arguments()
    assert tuple(rows) == SHIP_FIELDS
    for name, arg in rows.items():
        assert SHIP_ARGUMENTS[name] == (arg.unit, arg.meaning)
    assert rows["speed_range_mps"].limits == SPEED_LIMITS
    assert set(SHIP_KWARGS) <= set(SHIP_FIELDS)
    config = ShipConfig()
    with pytest.raises(dataclasses.FrozenInstanceError):
        config.froude_number = 0.3  # type: ignore[misc]
    with pytest.raises(ValueError, match="hs_rnge_m"):
        config.replace(hs_rnge_m=(1.0, 2.0))
    # the shared defaults are those of the environments that do not change them
    task_defaults = {
        p.name: p.default
        for p in __import__("inspect").signature(CourseKeepingTask.__init__).parameters.values()
    }
    for name in ("physics_dt_s", "control_dt_s", "integrator", "hull_mesh", "precision"):
        assert getattr(config, name) == task_defaults[name]


def test_the_sampler_draws_what_the_reset_reports():
    task = CourseKeepingTask(3, **COARSE, speed_range_mps=(8.0, 9.0), gm_range_m=(0.8, 1.2))
    rngs = [np.random.default_rng(s) for s in (1, 2, 3)]
    drawn = task.episodes.draw([np.random.default_rng(s) for s in (1, 2, 3)], {})
    task.reset_episodes(np.arange(3), rngs, None)
    info = task.reset_info(np.arange(3))
    np.testing.assert_array_equal(info["initial_speed_mps"], drawn.speed)
    np.testing.assert_array_equal(info["gm_m"], drawn.gm)
    np.testing.assert_array_equal(info["capsize_angle_deg"], np.degrees(drawn.capsize_angle))
    assert [i["wave_height_m"] for i in drawn.infos] == list(info["wave_height_m"])
    fixed = task.episodes.draw([np.random.default_rng(1)], {"gm_m": 0.9})
    assert fixed.gm[0] == 0.9 and fixed.speed[0] == drawn.speed[0]  # the stream is unshifted


def _tutorial_module(tmp_path: Path):
    text = TUTORIAL.read_text(encoding="utf-8")
    code = re.search(r"```python\n(.*?)```", text, re.DOTALL)
    assert code is not None
    path = tmp_path / "fin_comfort.py"
    path.write_text(code.group(1), encoding="utf-8")
    spec = importlib.util.spec_from_file_location("fin_comfort", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules["fin_comfort"] = module
    spec.loader.exec_module(module)
    return module, code.group(1)


def test_the_tutorial_task_is_small_and_runs(tmp_path):
    module, code = _tutorial_module(tmp_path)
    assert len(code.splitlines()) <= 110  # "about 90 lines", imports and registration included
    assert issubclass(module.FinComfortTask, ShipEnvTask)
    env = gymnasium.make("my_tasks/FinComfort-v0", hull_mesh=COARSE_MESH, n_wave_components=20)
    names = env.unwrapped.observation_names
    assert names[-2:] == ("fin angle [rad]", "lateral specific force at the passenger [m/s^2]")
    assert env.observation_space.shape == (16,)
    obs, info = env.reset(seed=4)
    assert info["wave_heading_deg"] >= 30.0
    fins = RollFinController.for_env(env)  # the baseline finds roll, roll rate and the fins
    total = 0.0
    for _ in range(20):
        action, _ = fins.predict(obs)
        obs, reward, _, _, info = env.step(action)
        total += reward
        assert set(info) >= {"reward_lateral", "reward_effort", "reward_capsize", "cost", "msdv_z"}
    assert np.isfinite(total) and total <= 0.0
    assert obs[-2] != 0.0  # the fin moved
    doc = module.FinComfortEnv.__doc__
    assert "| hs_range_m | (2, 5) | m | significant wave height range |" in doc
    assert "| lateral_weight | 1 | - | weight of the lateral-force term |" in doc
    with pytest.raises(ValueError, match="hs_rnge_m"):
        module.FinComfortEnv(hs_rnge_m=(1.0, 2.0))
    vec = gymnasium.make_vec(
        "my_tasks/FinComfort-v0",
        num_envs=2,
        vectorization_mode="vector_entry_point",
        hull_mesh=COARSE_MESH,
        n_wave_components=20,
    )
    obs, _ = vec.reset(seed=4)
    np.testing.assert_array_equal(obs[0], env.reset(seed=4)[0])
    vec.close()
    env.close()


def test_the_tutorial_env_passes_the_checkers(tmp_path):
    module, _ = _tutorial_module(tmp_path)
    assert_checkers_pass_without_warnings(lambda: module.FinComfortEnv(**COARSE))
