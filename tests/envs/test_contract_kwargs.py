"""The environments' keyword arguments (issue #15): every bad value of every registered id raises
a ValueError/TypeError naming the keyword as typed and what was expected, before the simulator
is built; numpy scalars are accepted; a property test draws keyword values.
"""

from __future__ import annotations

import inspect
import math
import re
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ship_gym.envs.course_keeping import CourseKeepingEnv
from ship_gym.envs.roll_one_dof import RollOneDOFEnv
from tests.envs._contract import (
    ALL,
    PROPERTY,
    SHIP,
    _finite_or_clear,
    floats,
    raises_naming,
)
from tests.envs._ship_env_checks import COARSE

# =============================================================================================
# keyword arguments
# =============================================================================================
SHIP_KWARG_CASES: list[tuple[dict[str, Any], str, str]] = [
    # kwargs, the name the message must hold, what was expected
    ({"physics_dt_s": 0.0}, "physics_dt_s", "[0.01, 0.5]"),
    ({"physics_dt_s": 10.0}, "physics_dt_s", "[0.01, 0.5]"),
    ({"physics_dt_s": "0.1"}, "physics_dt_s", "finite number"),
    ({"physics_dt_s": float("nan")}, "physics_dt_s", "finite number"),
    ({"control_dt_s": 1e6}, "control_dt_s", "at most"),
    ({"control_dt_s": 0.33}, "control_dt_s", "integer multiple"),
    ({"control_dt_s": -0.5}, "control_dt_s", "positive"),
    ({"control_dt_s": "0.5"}, "control_dt_s", "positive finite"),
    ({"control_dt_s": float("inf")}, "control_dt_s", "positive finite"),
    ({"kg_m": 11.0}, "kg_m", "GM"),
    ({"kg_m": 10.9}, "kg_m", "kg_m <="),
    ({"kg_m": 16.0}, "kg_m", "[0, 15.4]"),
    ({"kg_m": "9.5"}, "kg_m", "finite number"),
    ({"froude_number": 0.9}, "froude_number", "[0.05, 0.5]"),
    ({"froude_number": "0.2"}, "froude_number", "finite number"),
    ({"gm_range_m": (0.0, 1.0)}, "gm_range_m", "0.05 <= min"),
    ({"gm_range_m": (2.0, 1.0)}, "gm_range_m", "min <= max"),
    ({"gm_range_m": "12"}, "gm_range_m", "(min, max) pair"),
    ({"gm_range_m": 1.0}, "gm_range_m", "(min, max) pair"),
    ({"capsize_angle_deg": 0.0}, "capsize_angle_deg", "(0, 180]"),
    ({"capsize_angle_deg": 200.0}, "capsize_angle_deg", "(0, 180]"),
    ({"capsize_angle_deg": "60"}, "capsize_angle_deg", "finite number"),
    ({"dangerous_roll_deg": 95.0}, "dangerous_roll_deg", "(0, 90)"),
    ({"dangerous_roll_deg": True}, "dangerous_roll_deg", "finite number"),
    ({"sensor_noise": -1.0}, "sensor_noise", "[0, 100]"),
    ({"num_threads": 0}, "num_threads", "integer"),
    ({"num_threads": 1.5}, "num_threads", "integer"),
    ({"capsize_penalty": -1.0}, "capsize_penalty", ">= 0"),
    ({"wave_preview_m": "abc"}, "wave_preview_m", "distances"),
    ({"wave_preview_m": (1e5,)}, "wave_preview_m", "5 km"),
    ({"hull_mesh": (1, 2, 3)}, "hull_mesh", "4 integers"),
    ({"integrator": "euler"}, "integrator", "holloway"),
    ({"precision": "float16"}, "precision", "float32"),
    ({"n_wave_components": 0}, "n_wave_components", "1…1000"),
    ({"wave_ramp_time_s": -1.0}, "wave_ramp_time_s", "[0, 3600]"),
    ({"wave_heading_range_deg": (0.0, 1000.0)}, "wave_heading_range_deg", "720"),
]
IRREGULAR_CASES: list[tuple[dict[str, Any], str, str]] = [
    ({"hs_range_m": (30.0, 30.0), "tp_range_s": (1.0, 2.0)}, "hs_range_m", "DNV-RP-C205"),
    ({"hs_range_m": (3.0, 12.0), "tp_range_s": (5.0, 12.0)}, "tp_range_s", "Hs <="),
    ({"hs_range_m": (3.0, 40.0)}, "hs_range_m", "<= 30"),
    ({"tp_range_s": (0.5, 3.0)}, "tp_range_s", "1.0 <= min"),
    ({"hs_range_m": "3"}, "hs_range_m", "(min, max) pair"),
    ({"wave_spreading_s": -1.0}, "wave_spreading_s", "[0, 1000]"),
]
CAPSIZE_CASES: list[tuple[dict[str, Any], str, str]] = [
    ({"sea_kind": "irregular", "wave_height_range_m": (25.0, 25.0)}, "wave_height_range_m", "DNV"),
    ({"wave_height_range_m": (30.0, 40.0)}, "wave_height_range_m", "<= 30"),
    ({"froude_range": (0.1, 0.9)}, "froude_range", "0.5"),
    ({"heading_rate_deg": 0.0}, "heading_rate_deg", "(0, 45.0]"),
]
TASK_CASES: dict[str, list[tuple[dict[str, Any], str, str]]] = {
    "CourseKeeping": [
        *IRREGULAR_CASES,
        ({"initial_heading_error_deg": 200.0}, "initial_heading_error_deg", "[0, 180]"),
        ({"initial_heading_error_deg": "5"}, "initial_heading_error_deg", "finite number"),
        ({"rudder_mode": "rate"}, "rudder_mode", "absolute"),
        ({"speed_range_mps": (0.0, 50.0)}, "speed_range_mps", "0.1 <= min"),
    ],
    "RollStabilization": [*IRREGULAR_CASES],
    "RideControl": [*IRREGULAR_CASES],
    "CapsizeAvoidance": CAPSIZE_CASES,
}


def _takes(name: str, kwargs: dict[str, Any]) -> bool:
    params = inspect.signature(SHIP[name][0].task_class.__init__).parameters
    return all(k in params for k in kwargs)


KWARG_CASES = [
    pytest.param(name, kwargs, key, expected, id=f"{name}-{key}-{i}")
    for name in SHIP
    for i, (kwargs, key, expected) in enumerate(SHIP_KWARG_CASES + TASK_CASES[name])
    if _takes(name, kwargs)
]

ROLL_KWARG_CASES: list[tuple[dict[str, Any], str, str]] = [
    ({"max_moment": 1e100}, "max_moment", "[0, 10]"),
    ({"max_moment": -0.1}, "max_moment", "[0, 10]"),
    ({"max_moment": "0.03"}, "max_moment", "finite number"),
    ({"forcing_amplitude": 1e100}, "forcing_amplitude", "[0, 10]"),
    ({"forcing_amplitude": (0.0, 1e100)}, "forcing_amplitude", "[0, 10]"),
    ({"forcing_amplitude": -0.01}, "forcing_amplitude", ">= 0"),
    ({"forcing_amplitude": "0.02"}, "forcing_amplitude", "number or a (low, high) pair"),
    ({"physics_dt": 10.0}, "physics_dt", "T_n/20"),
    ({"physics_dt": 0.0}, "physics_dt", "(0, "),
    ({"physics_dt": "0.05"}, "physics_dt", "finite number"),
    ({"control_dt": 1e6}, "control_dt", "1000 physics_dt"),
    ({"control_dt": 0.33}, "control_dt", "integer multiple"),
    ({"control_dt": float("nan")}, "control_dt", "finite number"),
    ({"initial_roll": 5.0}, "initial_roll", "capsize angle"),
    ({"initial_roll_rate": 100.0}, "initial_roll_rate", "2π"),
    ({"capsize_angle": 4.0}, "capsize_angle", "(0, pi]"),
    ({"dangerous_roll_angle": 2.0}, "dangerous_roll_angle", "capsize_angle"),
    ({"alive_weight": -1.0}, "alive_weight", ">= 0"),
    ({"roll_weight": float("inf")}, "roll_weight", "finite"),
    ({"forcing_frequency": -1.0}, "forcing_frequency", ">= 0"),
    ({"roll_equation": "edith"}, "roll_equation", "RollEquation"),
]


@pytest.mark.parametrize(("name", "kwargs", "key", "expected"), KWARG_CASES)
def test_bad_ship_kwargs_name_the_keyword(name, kwargs, key, expected):
    cls = SHIP[name][0]
    base = dict(SHIP[name][2])
    raises_naming(lambda: cls(**{**base, **kwargs}), ValueError, key, expected)


@pytest.mark.parametrize(
    ("kwargs", "key", "expected"),
    [pytest.param(*case, id=f"{case[1]}-{i}") for i, case in enumerate(ROLL_KWARG_CASES)],
)
def test_bad_roll_one_dof_kwargs_name_the_keyword(kwargs, key, expected):
    raises_naming(lambda: RollOneDOFEnv(**kwargs), ValueError, key, expected)


@pytest.mark.parametrize("name", list(ALL))
def test_vector_env_refuses_bad_num_envs(name):
    cls, kwargs = ALL[name][1], ALL[name][2]
    for bad in (0, 1.5, "2", True):
        raises_naming(lambda bad=bad: cls(num_envs=bad, **kwargs), ValueError, "num_envs")


def test_numpy_scalars_are_accepted():
    """float32/int64 values are numbers: no contradictory range message (issue #15 item 7)."""
    env = CourseKeepingEnv(
        **COARSE,
        physics_dt_s=np.float32(0.1),
        control_dt_s=np.float32(0.5),
        kg_m=np.float64(9.55),
        num_threads=np.int64(1),
        dangerous_roll_deg=np.float32(25.0),
        capsize_penalty=np.float32(100.0),
    )
    assert env.unwrapped.task.control_dt == pytest.approx(0.5)
    RollOneDOFEnv(max_moment=np.float32(0.03), physics_dt=np.float32(0.05))


def test_kg_below_the_metacentre_is_accepted():
    """The KG bound is KM − 0.05 m of the hull mesh: 10.5 m (GM ≈ 0.1 m) builds."""
    message = raises_naming(
        lambda: CourseKeepingEnv(**COARSE, kg_m=10.58), ValueError, "kg_m", "KM ="
    )
    km = float(re.search(r"KM = ([0-9.]+) m", message).group(1))
    assert 10.3 < km < 10.8


ROLL_KWARGS = ("max_moment", "forcing_amplitude", "physics_dt", "control_dt", "initial_roll")
SHIP_CHEAP_KWARGS = ("capsize_angle_deg", "dangerous_roll_deg", "sensor_noise", "capsize_penalty")


@pytest.mark.parametrize("name", list(ALL))
@PROPERTY
@given(data=st.data())
def test_property_kwargs(name, data):
    """Kwargs that do not change the simulator build (so each example is cheap)."""
    cls, _, base = ALL[name]
    keys = ROLL_KWARGS if name == "RollOneDOF" else SHIP_CHEAP_KWARGS
    values = st.one_of(floats, st.floats(0.0, 200.0), st.floats(1e-3, 1.0), st.text(max_size=2))
    kwargs = data.draw(st.dictionaries(st.sampled_from(keys), values, max_size=2))
    env = _finite_or_clear(lambda: cls(**{**base, **kwargs}), *keys)
    if env is None:
        return
    obs, _ = env.reset(seed=0)
    assert np.all(np.isfinite(obs))
    for _ in range(2):
        obs, reward, terminated, *_ = env.step(np.ones(env.action_space.shape, np.float32))
        assert np.all(np.isfinite(obs)) and math.isfinite(reward)
        if terminated:
            break
    env.close()
