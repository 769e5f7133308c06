"""Reset options and seeds (issue #15): unknown keys, non-mappings and bad values are refused
naming the key; the supported options replay a sea; a property test draws options.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from tests.envs._contract import (
    ALL,
    N_VEC,
    PROPERTY,
    SHIP,
    _finite_or_clear,
    floats,
    raises_naming,
    single,
    vector,
)

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
    assert info["roll_deg"] == pytest.approx(5.0) and info["roll_rate_dps"] == pytest.approx(1.0)
    assert drawn["roll_deg"] == 0.0 and drawn["roll_rate_dps"] == 0.0  # upright, at rest
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
