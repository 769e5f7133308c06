"""The benchmark protocol (ship_gym.agents.protocol) and the baselines' grid tuning
(ship_gym.agents.tuning): paired bootstrap against known cases, Wilson intervals, seed ranges
that refuse to overlap, a grid widened until its optimum lies inside."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ship_gym.agents.protocol import (
    HELD_OUT_FIRST,
    SELECTION_SEEDS,
    TRAINING_SEEDS,
    TUNING_SEEDS,
    VALIDATION_SEEDS,
    Interval,
    check_choice_seeds,
    check_disjoint,
    check_held_out,
    mean_ratio,
    paired_bootstrap,
    relative_gain,
    verdict,
    wilson_interval,
)
from ship_gym.agents.tuning import Axis, tune_grid


def test_paired_bootstrap_of_two_episodes_is_the_enumerated_distribution():
    # reference [1, 3], candidate [1, 1]: the four equally likely resamples of two episodes give
    # gains 0 (both episode 0), 1/2 (twice: one of each) and 2/3 (both episode 1); the 2.5 %
    # and 97.5 % percentiles are 0 and 2/3, the point (2 − 1)/2
    got = paired_bootstrap([1.0, 3.0], [1.0, 1.0], resamples=20_000, seed=1)
    assert got.point == pytest.approx(0.5)
    assert got.low == pytest.approx(0.0) and got.high == pytest.approx(2.0 / 3.0)


def test_paired_bootstrap_of_a_constant_ratio_has_no_width():
    # a policy 20 % below the baseline in every episode: every resample says 20 %, however much
    # the seas vary (an unpaired comparison would be as wide as the seas)
    rng = np.random.default_rng(3)
    reference = rng.lognormal(0.0, 0.8, size=200)
    got = paired_bootstrap(reference, 0.8 * reference)
    assert (got.point, got.low, got.high) == pytest.approx((0.2, 0.2, 0.2))
    ratio = paired_bootstrap(reference, 1.1 * reference, mean_ratio)
    assert ratio.as_list() == pytest.approx([1.1, 1.1, 1.1])


def test_paired_bootstrap_of_a_mean_difference_matches_the_normal_interval():
    rng = np.random.default_rng(7)
    n, sigma = 400, 0.3
    seas = rng.lognormal(0.0, 1.0, size=n)  # large common variation, cancelled by pairing
    noise = rng.normal(0.0, sigma, size=n)
    reference, candidate = seas + 1.0, seas + 0.9 + noise

    def difference(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.mean(a, axis=-1) - np.mean(b, axis=-1)

    got = paired_bootstrap(reference, candidate, difference, resamples=20_000)
    d = reference - candidate
    half = 1.959964 * d.std() / math.sqrt(n)
    assert got.point == pytest.approx(d.mean())
    assert got.low == pytest.approx(d.mean() - half, abs=0.1 * half)
    assert got.high == pytest.approx(d.mean() + half, abs=0.1 * half)
    # pairing matters: the seas alone would make the interval of the two means ~10× wider
    assert got.high - got.low < 0.2 * (1.96 * 2 * seas.std() * math.sqrt(2 / n))


def test_paired_bootstrap_is_reproducible_and_refuses_bad_input():
    a, b = np.arange(1.0, 11.0), np.arange(1.0, 11.0) * 0.9
    assert paired_bootstrap(a, b, seed=5) == paired_bootstrap(a, b, seed=5)
    with pytest.raises(ValueError, match="same episodes"):
        paired_bootstrap(a, b[:-1])
    with pytest.raises(ValueError, match="finite"):
        paired_bootstrap([1.0, np.nan], [1.0, 1.0])
    with pytest.raises(ValueError, match="confidence"):
        paired_bootstrap(a, b, confidence=1.0)
    assert relative_gain(np.array([2.0, 2.0]), np.array([1.0, 1.0])) == pytest.approx(0.5)


def test_wilson_interval_known_values():
    # k = 0: (0, z²/(n + z²)); k = n/2: symmetric about 1/2
    z2 = 1.959964**2
    assert wilson_interval(0, 200) == pytest.approx((0.0, z2 / (200 + z2)), rel=1e-6)
    low, high = wilson_interval(100, 200)
    assert low + high == pytest.approx(1.0) and high - low == pytest.approx(0.1372, abs=2e-4)
    # 5 of 60 (the PPO-Lagrangian row of the former table): [0.036, 0.18]
    assert wilson_interval(5, 60) == pytest.approx((0.0361, 0.1807), abs=5e-4)


def test_the_target_is_judged_on_the_interval():
    assert verdict(Interval(0.25, 0.21, 0.29), 0.2) == "met"
    assert verdict(Interval(0.25, 0.15, 0.35), 0.2) == "undecided"
    assert verdict(Interval(0.12, 0.08, 0.19), 0.2) == "not met"


def test_the_seed_ranges_are_disjoint_and_overlaps_are_refused():
    check_disjoint({"training": TRAINING_SEEDS, "validation": VALIDATION_SEEDS,
                    "held-out": range(HELD_OUT_FIRST, HELD_OUT_FIRST + 200)})  # fmt: skip
    assert set(TUNING_SEEDS) <= set(TRAINING_SEEDS)
    assert set(SELECTION_SEEDS) <= set(VALIDATION_SEEDS)
    with pytest.raises(ValueError, match=r"training seeds 0 … 9 and validation seeds 5 … 14 "
                                         r"overlap \(seeds 5 … 9\)"):  # fmt: skip
        check_disjoint({"training": range(10), "validation": range(5, 15)})
    # the former held-out seeds chose the shipped policies: burnt, refused
    with pytest.raises(ValueError, match=r"held-out seeds 10000 … 10199 start in the burnt range"):
        check_held_out(range(10_000, 10_200))
    with pytest.raises(ValueError, match=r"start in the validation range"):
        check_held_out(range(5_000, 5_040))
    with pytest.raises(ValueError, match=r"held-out seeds 20000 … 20009 and validation seeds"):
        check_held_out(range(20_000, 20_010), validation=range(20_005, 20_050))
    check_held_out(range(20_000, 20_200), training=range(0, 18), validation=range(5000, 5032))
    # nothing is tuned or chosen on burnt or held-out seeds
    check_choice_seeds(TUNING_SEEDS, "tuning")
    with pytest.raises(ValueError, match="reach into the held-out range"):
        check_choice_seeds(range(HELD_OUT_FIRST, HELD_OUT_FIRST + 5), "--seeds")
    with pytest.raises(ValueError, match="reach into the burnt range"):
        check_choice_seeds(range(6_990, 7_010), "--seeds")


def test_a_grid_is_widened_until_its_optimum_lies_inside():
    messages: list[str] = []
    calls: list[dict] = []

    def evaluate(point: dict) -> dict:
        calls.append(point)
        return {"capsized": 0, "mean_return": -((point["a"] - 0.25) ** 2) - (point["b"] - 2) ** 2}

    result = tune_grid(
        [Axis("a", (0.5, 0.6, 0.7), lower=0.0), Axis("b", (0.0, 1.0, 2.0, 3.0), lower=0.0)],
        evaluate,
        report=messages.append,
    )
    assert result.best["a"] == pytest.approx(0.2) and result.best["b"] == 2.0
    assert result.inside and result.position == {"a": "inside", "b": "inside"}
    assert result.axes["a"] == pytest.approx((0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7))
    assert len(messages) == 4 and "a = 0.5 on the edge" in messages[0]
    assert len(calls) == len({tuple(c.values()) for c in calls}) == 7 * 4  # each point once


def test_capsizes_come_first_and_physical_bounds_and_the_widening_limit_are_reported():
    def evaluate(point: dict) -> dict:
        # the best return lies at high gain, where the ship capsizes
        return {"capsized": int(point["k"] > 2.5), "mean_return": point["k"] - point["z"]}

    result = tune_grid(
        [Axis("k", (1.0, 2.0, 3.0, 4.0)), Axis("z", (0.0, 0.1, 0.2), lower=0.0)],
        evaluate,
        report=lambda m: None,
    )
    assert result.best["k"] == 2.0 and result.position["k"] == "inside"
    assert result.position["z"] == "on the lower bound" and result.inside
    limited = tune_grid(
        [Axis("k", (1.0, 2.0, 3.0))],
        lambda p: {"capsized": 0, "mean_return": p["k"]},
        max_widenings=2,
        report=lambda m: None,
    )
    assert limited.best["k"] == 5.0 and limited.position == {"k": "on the edge"}
    assert not limited.inside and len(limited.widenings) == 2
    with pytest.raises(ValueError, match="≥ 3 strictly increasing"):
        Axis("k", (1.0, 2.0))


def test_the_one_standard_error_rule_takes_the_best_metric_among_equal_returns():
    from ship_gym.agents.tuning import one_standard_error_choice

    rng = np.random.default_rng(0)
    seas = rng.normal(-60.0, 30.0, size=48)
    wobble = np.resize([3.0, -3.0], 48)  # paired differences of standard error 3/√48 ≈ 0.44
    rows = [
        # the best return by a hair, but the worst metric: a tie within the noise
        {"k": 1, "capsized": 0, "returns": seas + 0.3 + wobble, "rms": 1.6},
        {"k": 2, "capsized": 0, "returns": seas, "rms": 1.5},
        # clearly lower return: not a tie, although best on the metric
        {"k": 3, "capsized": 0, "returns": seas - 8.0 + wobble, "rms": 1.3},
        # capsizes: never a tie with a point that does not
        {"k": 4, "capsized": 1, "returns": seas + 5.0, "rms": 1.0},
    ]
    for row in rows:
        row["mean_return"] = float(np.mean(row["returns"]))
    assert rows[0]["mean_return"] > rows[1]["mean_return"]
    assert one_standard_error_choice("rms")(rows)["k"] == 2
