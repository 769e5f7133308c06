"""Shared pieces of the environments' input-contract tests (issue #15): the envs of every
registered id on the coarse mesh, and the check that a call fails naming what was typed."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pytest
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

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


floats = st.floats(allow_nan=True, allow_infinity=True, width=64)
PROPERTY = settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _finite_or_clear(call: Callable[[], Any], *names: str) -> Any:
    try:
        return call()
    except (ValueError, TypeError) as err:
        assert any(n in str(err) for n in names), str(err)
        return None
