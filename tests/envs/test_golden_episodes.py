"""The registered environments keep their behaviour bit for bit (tests/data/golden_episodes.npz).

The file was recorded by ``tests/envs/make_golden_episodes.py`` on the code before the task
layer of issue #31 (one observation table, the episode sampler, the frozen config, the comfort
component): the same seeds and actions must give the same observations, rewards, reward terms,
costs, flags, reset infos, observation names and bounds, to the last bit (NaN included).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from .make_golden_episodes import CASES, VECTOR_CASE, record, record_vector

DATA = Path(__file__).resolve().parents[1] / "data" / "golden_episodes.npz"


@pytest.fixture(scope="module")
def golden() -> dict[str, np.ndarray]:
    with np.load(DATA) as data:
        return {key: data[key] for key in data.files}


def _assert_same(name: str, key: str, got: np.ndarray, want: np.ndarray) -> None:
    got, want = np.asarray(got), np.asarray(want)
    assert got.shape == want.shape, f"{name}/{key}: shape {got.shape} != {want.shape}"
    if got.dtype.kind in "fc":
        # bitwise: NaN where NaN, −0.0 where −0.0
        assert got.dtype == want.dtype, f"{name}/{key}: dtype {got.dtype} != {want.dtype}"
        assert got.tobytes() == want.tobytes(), f"{name}/{key} differs"
    else:
        np.testing.assert_array_equal(got, want, err_msg=f"{name}/{key}")


@pytest.mark.parametrize("name", list(CASES))
def test_episodes_are_bit_for_bit_the_recorded_ones(name: str, golden) -> None:
    env_id, kwargs = CASES[name]
    arrays = record(env_id, kwargs)
    for key, value in arrays.items():
        _assert_same(name, key, value, golden[f"{name}/{key}"])


def test_vector_episodes_are_bit_for_bit_the_recorded_ones(golden) -> None:
    for key, value in record_vector(*VECTOR_CASE).items():
        _assert_same("vector", key, value, golden[f"vector/{key}"])
