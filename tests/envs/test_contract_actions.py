"""Actions of the single and the vector envs (issue #15): wrong shapes (never reshaped), dtypes
and non-finite values are refused naming `action`/`actions`; a diverged state never reaches the
agent as NaN; a property test draws actions.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from ship_gym.envs.capsize_avoidance import CapsizeAvoidanceVectorEnv
from ship_gym.envs.roll_one_dof import RollOneDOFEnv
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
