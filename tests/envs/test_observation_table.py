"""One observation table drives the names, bounds, noise, docs and the baselines' look-ups."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ship_gym.agents.baselines import EnvLayout, PIDAutopilot, RollFinController, env_layout
from ship_gym.envs.course_keeping import CourseKeepingEnv
from ship_gym.envs.docstrings import SHIP_OBSERVATION_TABLE
from ship_gym.envs.observations import (
    SENSOR_NOISE_STD,
    SHIP_OBSERVATIONS,
    Observation,
    find_observation,
    markdown_table,
    observation_from_tuple,
)
from ship_gym.envs.roll_one_dof import RollOneDOFEnv

from ._ship_env_checks import COARSE


@pytest.fixture(scope="module")
def env():
    env = CourseKeepingEnv(**COARSE, sensor_noise=1.0, wave_preview_m=(50.0,))
    yield env
    env.close()


def test_names_bounds_and_noise_come_from_the_table(env):
    task = env.unwrapped.task
    entries = env.unwrapped.observation_entries
    assert entries == task.observation_entries
    assert env.unwrapped.observation_names == tuple(e.label for e in entries)
    assert entries[: len(SHIP_OBSERVATIONS)] == SHIP_OBSERVATIONS  # rudder and shaft present
    np.testing.assert_array_equal(
        env.observation_space.low, np.array([e.low for e in entries], np.float32)
    )
    np.testing.assert_array_equal(
        env.observation_space.high, np.array([e.high for e in entries], np.float32)
    )
    np.testing.assert_array_equal(task._noise_std, [e.noise_std for e in entries])
    assert entries[-1].label == "wave elevation 50 m ahead [m]" and entries[-1].noise_std == 0.1
    assert SENSOR_NOISE_STD["roll [rad]"] == math.radians(0.2)
    assert "rudder angle [rad]" not in SENSOR_NOISE_STD  # actuator feedback: noise-free


def test_the_docstring_table_is_generated_from_the_table(env):
    assert SHIP_OBSERVATION_TABLE == markdown_table(SHIP_OBSERVATIONS)
    rows = SHIP_OBSERVATION_TABLE.splitlines()[2:]
    assert len(rows) == len(SHIP_OBSERVATIONS)
    assert rows[0] == "| 0 | roll φ | rad | ±π |"
    assert rows[13] == "| 13 | shaft speed | rev/s | ±20 |"
    assert "| 9 | heading error wrap(ψ_ref − ψ) | rad | ±π |" in type(env.unwrapped).__doc__


def test_the_tasks_rows_of_the_docstring_table_come_from_their_entries():
    from ship_gym.envs.capsize_avoidance import CapsizeAvoidanceEnv, CapsizeAvoidanceTask

    doc = CapsizeAvoidanceEnv.__doc__
    assert "| 16 | telegraph f | × self-propulsion rpm | 0 … 2 |" in doc
    assert "| 21… | incident elevation at the ``wave_preview_m`` points (if any) | m | ±30 |" in doc
    task = CapsizeAvoidanceTask(1, hull_mesh=COARSE["hull_mesh"])
    assert task.observation_entries[14:21] == CapsizeAvoidanceTask.task_observations


def test_extra_observation_tuples_become_entries():
    entry = observation_from_tuple(("fin command [rad]", -0.4, 0.4))
    assert entry == Observation("fin command", "rad", -0.4, 0.4)
    assert entry.label == "fin command [rad]"
    with pytest.raises(ValueError, match="unit in brackets"):
        observation_from_tuple(("fin command", -1.0, 1.0))


def test_baselines_find_their_inputs_through_the_table(env):
    layout = env_layout(env)
    assert layout.observation_entries == env.unwrapped.observation_entries
    names = layout.observation_names
    assert layout.observation(("heading error",)) == (names.index("heading error [rad]"), 1.0)
    assert layout.observation(("r",))[0] == names.index("yaw rate [rad/s]")  # an alias
    # the table, not a pattern: "error" is no entry's name or alias
    entries = env.unwrapped.observation_entries
    assert find_observation(entries, ("error",)) is None
    PIDAutopilot.for_env(env)  # binds
    one_dof = RollOneDOFEnv()
    fins = RollFinController.for_env(one_dof)
    assert fins._idx["rate"] == (1, 1.0)


def test_a_layout_without_a_table_reads_the_entries_from_the_names():
    layout = EnvLayout(("roll [deg]", "roll rate [deg/s]"), ("fins [-]",), 0.5)
    assert layout.observation(("roll rate",)) == (1, math.pi / 180.0)
    assert layout.observation(("pitch",), required=False) == (-1, 1.0)
