"""The input contract of the environments (issue #15): every bad keyword argument, action, reset
option and seed of every registered id raises a ValueError/TypeError naming the argument as the
user typed it and what was expected; no state ever reaches the agent as NaN.

Bad keyword arguments fail before the simulator is built (cheap); the envs that are stepped use
the coarse mesh of ``_ship_env_checks`` and are built once per module.
"""

from __future__ import annotations

import inspect
import math
import re
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from ship_gym.envs.base import TaskEnv, TaskVectorEnv
from ship_gym.envs.capsize_avoidance import CapsizeAvoidanceEnv, CapsizeAvoidanceVectorEnv
from ship_gym.envs.course_keeping import CourseKeepingEnv, CourseKeepingVectorEnv
from ship_gym.envs.ride_control import RideControlEnv, RideControlVectorEnv
from ship_gym.envs.roll_one_dof import RollOneDOFEnv, RollOneDOFVectorEnv
from ship_gym.envs.roll_stabilisation import RollStabilizationEnv, RollStabilizationVectorEnv
from tests.envs._ship_env_checks import COARSE, COARSE_MESH

SHIP = {
    "CourseKeeping": (CourseKeepingEnv, CourseKeepingVectorEnv, COARSE),
    "RollStabilization": (RollStabilizationEnv, RollStabilizationVectorEnv, COARSE),
    "RideControl": (RideControlEnv, RideControlVectorEnv, COARSE),
    "CapsizeAvoidance": (
        CapsizeAvoidanceEnv,
        CapsizeAvoidanceVectorEnv,
        {"hull_mesh": COARSE_MESH, "n_wave_components": 20},
    ),
}
ALL = {**SHIP, "RollOneDOF": (RollOneDOFEnv, RollOneDOFVectorEnv, {})}
N_VEC = 3

_single: dict[str, TaskEnv] = {}
_vector: dict[str, TaskVectorEnv] = {}


def single(name: str) -> TaskEnv:
    """One reset single env per id (shared: a refused input leaves it unchanged)."""
    if name not in _single:
        cls, _, kwargs = ALL[name]
        env = cls(**kwargs)
        env.reset(seed=0)
        _single[name] = env
    return _single[name]


def vector(name: str) -> TaskVectorEnv:
    if name not in _vector:
        _, cls, kwargs = ALL[name]
        env = cls(num_envs=N_VEC, **kwargs)
        env.reset(seed=0)
        _vector[name] = env
    return _vector[name]


def raises_naming(call: Callable[[], Any], error: type | tuple, *fragments: str) -> str:
    """``call()`` raises ``error`` whose message holds every fragment (literally)."""
    with pytest.raises(error) as caught:
        call()
    message = str(caught.value)
    for fragment in fragments:
        assert fragment in message, f"{fragment!r} not in {message!r}"
    return message


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
    ({"kg_m": 4.0}, "kg_m", "[5, 12]"),
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


# =============================================================================================
# actions
# =============================================================================================
def _single_bad_actions(n: int) -> list[tuple[Any, type, str]]:
    z = np.zeros(n, dtype=np.float32)
    return [
        (np.zeros(n + 1, np.float32), ValueError, f"shape ({n},)"),
        (np.zeros((1, n), np.float32), ValueError, f"shape ({n},)"),
        (np.zeros((2, n), np.float32), ValueError, f"shape ({n},)"),
        (z + np.nan, ValueError, "finite"),
        (z + np.inf, ValueError, "finite"),
        (z - np.inf, ValueError, "finite"),
        (np.array(["0.5"] * n), TypeError, "dtype <U3"),
        ("0.5", TypeError, "real numbers"),
        (z + 0.5j, TypeError, "complex"),
        (np.array([0.5] * n, dtype=object), TypeError, "dtype object"),
        (np.ones(n, dtype=bool), TypeError, "dtype bool"),
        ([[0.1], [0.2, 0.3]], ValueError, "action"),
        (None, TypeError, "dtype object"),
    ]


def _vector_bad_actions(n: int) -> list[tuple[Any, type, str]]:
    shape = f"({N_VEC}, {n})"
    z = np.zeros((N_VEC, n), np.float32)
    cases = [
        (np.zeros((n, N_VEC), np.float32), ValueError, shape),  # transposed
        (np.zeros(N_VEC * n, np.float32), ValueError, shape),  # flat
        (np.zeros((N_VEC + 1, n), np.float32), ValueError, shape),
        (np.zeros((N_VEC, n, 1), np.float32), ValueError, shape),
        (z + np.nan, ValueError, "finite"),
        (z + np.inf, ValueError, "finite"),
        (z.astype(str), TypeError, "dtype <U"),
        (z + 1j, TypeError, "complex"),
        (z.astype(object), TypeError, "dtype object"),
    ]
    if n == 1:
        cases.append((np.zeros(N_VEC), ValueError, shape))
    return cases


SINGLE_ACTION_CASES = [pytest.param(name, i, id=f"{name}-{i}") for name in ALL for i in range(13)]
VECTOR_ACTION_CASES = [pytest.param(name, i, id=f"{name}-{i}") for name in ALL for i in range(9)]


@pytest.mark.parametrize(("name", "i"), SINGLE_ACTION_CASES)
def test_bad_single_env_actions(name, i):
    env = single(name)
    n = env.action_space.shape[0]
    bad, error, fragment = _single_bad_actions(n)[i]
    raises_naming(lambda: env.step(bad), error, "action", fragment)


@pytest.mark.parametrize(("name", "i"), VECTOR_ACTION_CASES)
def test_bad_vector_env_actions(name, i):
    env = vector(name)
    n = env.single_action_space.shape[0]
    bad, error, fragment = _vector_bad_actions(n)[i]
    raises_naming(lambda: env.step(bad), error, "actions", fragment)


def test_transposed_batch_is_refused_not_reshaped():
    """Issue #15 item 1: a (2, 4) array for a batch of 4 ships with 2 actions."""
    env = CapsizeAvoidanceVectorEnv(num_envs=4, **SHIP["CapsizeAvoidance"][2])
    env.reset(seed=0)
    raises_naming(lambda: env.step(np.zeros((2, 4))), ValueError, "actions", "(4, 2)", "(2, 4)")
    env.close()


def test_scalar_action_of_a_one_action_env():
    env = single("RollOneDOF")
    obs, reward, *_ = env.step(0.5)
    assert np.all(np.isfinite(obs)) and math.isfinite(reward)


# =============================================================================================
# reset options and seeds
# =============================================================================================
SHIP_OPTION_CASES: list[tuple[Any, type, tuple[str, ...]]] = [
    ({"wave_height": 3.0}, ValueError, ("'wave_height'", "accepted keys", "wave_height_m")),
    ({"hs": 3.0}, ValueError, ("'hs'", "wave_period_s")),
    ({"reset_mask": np.ones(1, bool)}, ValueError, ("'reset_mask'",)),
    ("wave_height_m=3", TypeError, ("options", "mapping")),
    ([("wave_height_m", 3.0)], TypeError, ("options", "mapping")),
    ({"wave_height_m": float("nan")}, ValueError, ("options['wave_height_m']", "[0, 30]")),
    ({"wave_height_m": -1.0}, ValueError, ("options['wave_height_m']", "[0, 30]")),
    ({"wave_height_m": 31.0}, ValueError, ("options['wave_height_m']", "[0, 30]")),
    ({"wave_height_m": "3"}, ValueError, ("options['wave_height_m']", "finite number")),
    ({"wave_height_m": 25.0, "wave_period_s": 3.0}, ValueError, ("options['wave_height_m']",)),
    ({"wave_period_s": 0.5}, ValueError, ("options['wave_period_s']", "[1, 40]")),
    ({"wave_period_s": None}, ValueError, ("options['wave_period_s']", "finite number")),
    ({"wave_heading_deg": 1000.0}, ValueError, ("options['wave_heading_deg']", "720")),
    ({"wave_heading_deg": float("inf")}, ValueError, ("options['wave_heading_deg']",)),
    ({"initial_speed_mps": 50.0}, ValueError, ("options['initial_speed_mps']", "[0.1, 30]")),
    ({"initial_speed_mps": 0.0}, ValueError, ("options['initial_speed_mps']", "[0.1, 30]")),
    ({"gm_m": 0.01}, ValueError, ("options['gm_m']", "[0.05, 10]")),
    ({"gm_m": "1"}, ValueError, ("options['gm_m']", "finite number")),
    ({"roll_deg": 89.0}, ValueError, ("options['roll_deg']", "capsize angle")),
    ({"roll_deg": 120.0}, ValueError, ("options['roll_deg']", "(-90, 90)")),
    ({"roll_rate_dps": 100.0}, ValueError, ("options['roll_rate_dps']", "[-30, 30]")),
    ({"roll_deg": [1.0]}, ValueError, ("options['roll_deg']", "finite number")),
]
ROLL_OPTION_CASES: list[tuple[Any, type, tuple[str, ...]]] = [
    ({"wave_height": 3.0}, ValueError, ("'wave_height'", "initial_roll_rate")),
    ("forcing_amplitude", TypeError, ("options", "mapping")),
    ({"initial_roll": 5.0}, ValueError, ("options['initial_roll']", "capsize angle")),
    ({"initial_roll": "0.1"}, ValueError, ("options['initial_roll']", "finite number")),
    ({"forcing_amplitude": -1.0}, ValueError, ("options['forcing_amplitude']", "[0, 10]")),
    ({"forcing_amplitude": 1e100}, ValueError, ("options['forcing_amplitude']", "[0, 10]")),
    ({"forcing_amplitude": float("nan")}, ValueError, ("options['forcing_amplitude']",)),
    ({"initial_roll_rate": 100.0}, ValueError, ("options['initial_roll_rate']",)),
    ({"forcing_phase": float("inf")}, ValueError, ("options['forcing_phase']",)),
]
OPTION_CASES = [
    pytest.param(name, i, id=f"{name}-{i}") for name in SHIP for i in range(len(SHIP_OPTION_CASES))
] + [pytest.param("RollOneDOF", i, id=f"RollOneDOF-{i}") for i in range(len(ROLL_OPTION_CASES))]


@pytest.mark.parametrize(("name", "i"), OPTION_CASES)
@pytest.mark.parametrize("face", ["single", "vector"])
def test_bad_reset_options(name, i, face):
    env = single(name) if face == "single" else vector(name)
    cases = ROLL_OPTION_CASES if name == "RollOneDOF" else SHIP_OPTION_CASES
    options, error, fragments = cases[i]
    if face == "vector" and isinstance(options, dict) and "reset_mask" in options:
        pytest.skip("reset_mask is a vector-env option")
    raises_naming(lambda: env.reset(seed=1, options=options), error, *fragments)


def test_heading_setpoint_option_is_course_keeping_only():
    raises_naming(
        lambda: single("RideControl").reset(options={"heading_setpoint_deg": 5.0}),
        ValueError,
        "'heading_setpoint_deg'",
    )
    raises_naming(
        lambda: single("CourseKeeping").reset(options={"heading_setpoint_deg": 500.0}),
        ValueError,
        "options['heading_setpoint_deg']",
        "[-180, 180]",
    )


@pytest.mark.parametrize("name", list(SHIP))
def test_reset_options_replay_the_sea(name):
    """The options fix what the generator draws; reset info reports them; without options the
    next reset of the same seed is the drawn episode again."""
    env = single(name)
    _, drawn = env.reset(seed=3)
    options = {
        "wave_height_m": 2.5,
        "wave_period_s": 11.0,
        "wave_heading_deg": 30.0,
        "initial_speed_mps": drawn["initial_speed_mps"] * 0.95,
        "gm_m": 1.2,
        "roll_deg": 5.0,
        "roll_rate_dps": 1.0,
    }
    obs, info = env.reset(seed=3, options=options)
    assert info["wave_height_m"] == 2.5 and info["wave_period_s"] == 11.0
    assert info["wave_heading_deg"] == pytest.approx(30.0)
    assert info["gm_m"] == pytest.approx(1.2)
    assert info["initial_speed_mps"] == pytest.approx(options["initial_speed_mps"])
    names = env.unwrapped.observation_names
    assert obs[names.index("roll [rad]")] == pytest.approx(math.radians(5.0), rel=1e-6)
    for _ in range(3):
        obs, reward, *_ = env.step(np.zeros(env.action_space.shape, np.float32))
        assert np.all(np.isfinite(obs)) and math.isfinite(reward)
    obs2, again = env.reset(seed=3)
    assert again == drawn
    # the drawn episode from the seed with its own values as options: the same start
    replay = {k: drawn[k] for k in ("wave_height_m", "wave_period_s", "wave_heading_deg")}
    obs3, info3 = env.reset(seed=3, options=replay)
    np.testing.assert_array_equal(obs3, obs2)
    assert info3 == drawn


def test_roll_one_dof_options_use_the_constructor_checks():
    env = single("RollOneDOF")
    obs, info = env.reset(seed=0, options={"initial_roll": 0.3, "forcing_amplitude": 0.04})
    assert obs[0] == pytest.approx(0.3) and info["forcing_amplitude"] == 0.04


BAD_SEEDS: list[Any] = [1.5, "1", True, -1, [1, 2], [1.5] * N_VEC, {"a": 1}]


@pytest.mark.parametrize("name", list(ALL))
@pytest.mark.parametrize("seed", BAD_SEEDS, ids=repr)
def test_bad_vector_seed_names_seed(name, seed):
    raises_naming(lambda: vector(name).reset(seed=seed), ValueError, "seed", "int")


@pytest.mark.parametrize("seed", [1.5, "1", -1])
def test_bad_single_seed(seed):
    raises_naming(lambda: single("RollOneDOF").reset(seed=seed), ValueError, "seed")


# =============================================================================================
# never NaN out
# =============================================================================================
def test_roll_one_dof_divergence_terminates_with_finite_output():
    env = RollOneDOFEnv()
    env.reset(seed=0)
    env.unwrapped.task.phidot[:] = 1e300  # an overflowing state (what huge moments gave)
    obs, reward, terminated, _, info = env.step(np.zeros(1))
    assert terminated and info["diverged"]
    assert np.all(np.isfinite(obs)) and math.isfinite(reward)
    obs, reward, terminated, _, info = env.step(np.zeros(1))  # stepping it again is safe
    assert terminated and np.all(np.isfinite(obs)) and math.isfinite(reward)


def test_roll_one_dof_largest_moments_stay_finite():
    env = RollOneDOFEnv(max_moment=10.0, forcing_amplitude=10.0)
    env.reset(seed=0)
    for _ in range(5):
        obs, reward, terminated, *_ = env.step(np.ones(1))
        assert np.all(np.isfinite(obs)) and math.isfinite(reward)
    assert terminated


@pytest.mark.parametrize("name", list(SHIP))
def test_ship_divergence_terminates_with_finite_output(name):
    env = vector(name)
    env.reset(seed=0)
    env.task.sim.nu[0, 3] = np.inf
    obs, reward, terminated, _, info = env.step(np.zeros((N_VEC, *env.single_action_space.shape)))
    assert terminated[0] and info["diverged"][0] and not terminated[1:].any()
    assert np.all(np.isfinite(obs)) and np.all(np.isfinite(reward))
    env.reset(seed=0)


# =============================================================================================
# property-based: actions, kwargs and reset options of every id
# =============================================================================================
floats = st.floats(allow_nan=True, allow_infinity=True, width=64)
PROPERTY = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _finite_or_clear(call: Callable[[], Any], *names: str) -> Any:
    try:
        return call()
    except (ValueError, TypeError) as err:
        assert any(n in str(err) for n in names), str(err)
        return None


@pytest.mark.parametrize("name", list(ALL))
@PROPERTY
@given(data=st.data())
def test_property_actions(name, data):
    env = single(name)
    n = env.action_space.shape[0]
    shape = data.draw(
        st.one_of(st.just((n,)), hnp.array_shapes(min_dims=0, max_dims=3, max_side=4))
    )
    action = data.draw(hnp.arrays(np.float64, shape, elements=floats))
    out = _finite_or_clear(lambda: env.step(action), "action")
    if out is None:
        assert shape not in ((n,),) or not np.all(np.isfinite(action))
        return
    obs, reward, terminated, truncated, _ = out
    assert np.all(np.isfinite(obs)) and math.isfinite(reward)
    if terminated or truncated:
        env.reset(seed=0)


SHIP_OPTION_KEYS = (
    "wave_height_m", "wave_period_s", "wave_heading_deg", "initial_speed_mps", "gm_m",
    "roll_deg", "roll_rate_dps", "bogus",
)  # fmt: skip
ROLL_OPTION_KEYS = ("forcing_amplitude", "forcing_phase", "initial_roll", "initial_roll_rate", "x")


@pytest.mark.parametrize("name", list(ALL))
@PROPERTY
@given(data=st.data())
def test_property_reset_options(name, data):
    env = single(name)
    keys = ROLL_OPTION_KEYS if name == "RollOneDOF" else SHIP_OPTION_KEYS
    values = st.one_of(floats, st.floats(-50.0, 50.0), st.integers(-100, 100), st.text(max_size=2))
    options = data.draw(st.dictionaries(st.sampled_from(keys), values, max_size=3))
    out = _finite_or_clear(lambda: env.reset(seed=0, options=options), *keys, "options")
    if out is None:
        env.reset(seed=0)
        return
    obs, _ = out
    assert np.all(np.isfinite(obs))
    obs, reward, *_ = env.step(np.zeros(env.action_space.shape, np.float32))
    assert np.all(np.isfinite(obs)) and math.isfinite(reward)


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
