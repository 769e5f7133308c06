"""ship_gym.agents.evaluate: batched episodes equal single-env episodes of the same seeds;
outputs."""

import csv
import json

import gymnasium
import numpy as np
import pytest

import ship_gym  # noqa: F401  (registers the ids)
from ship_gym.agents.baselines import make_baseline
from ship_gym.agents.evaluate import (
    METRICS,
    evaluate_policies,
    run_episodes,
    summarize,
    write_results,
)

ROLL_ID = "ship_gym/RollOneDOF-v0"


def test_batched_episodes_equal_single_env_episodes_of_the_same_seeds():
    """Episode k of the batched evaluation == gymnasium.make(id) reset with seed k, to the bit
    for the return (same sea, same controller, same arithmetic)."""
    seeds = [3, 4, 5, 6]
    steps = 120
    batched = run_episodes(ROLL_ID, lambda env: make_baseline("fins", env), seeds, max_steps=steps)
    env = gymnasium.make(ROLL_ID, max_episode_steps=steps)
    policy = make_baseline("fins", env)
    for k, seed in enumerate(seeds):
        obs, _ = env.reset(seed=seed)
        total, length, done = 0.0, 0, False
        while not done:
            action, _ = policy.predict(obs)
            obs, reward, terminated, truncated, _ = env.step(action)
            total += reward
            length += 1
            done = terminated or truncated
        assert batched.lengths[k] == length
        assert batched.returns[k] == total


def test_zero_policy_metrics_and_capsizes_end_episodes_early():
    seeds = list(range(8))
    stats = run_episodes(ROLL_ID, lambda env: make_baseline("zero", env), seeds)
    m = summarize(stats)
    assert m["rms_action"] == 0.0
    assert np.isnan(m["rms_heading_error_deg"])  # RollOneDOF has no heading
    assert np.isnan(m["rms_vertical_acceleration_mps2"])  # nor a passenger point
    # capsized episodes are exactly those shorter than the 1000-step time limit
    np.testing.assert_array_equal(stats.capsized, stats.lengths < 1000)
    assert 0.0 < m["capsize_rate"] < 1.0
    assert m["mean_length"] == pytest.approx(stats.lengths.mean())


def test_evaluate_policies_writes_csv_json_png(tmp_path):
    results = evaluate_policies(
        ROLL_ID, ["zero", "fins"], episodes=3, seed=7, max_steps=30, progress=False
    )
    assert results["seeds"] == [7, 8, 9]
    out = write_results(results, tmp_path)
    rows = list(csv.reader((out / "evaluation.csv").open()))
    assert rows[0][: 1 + len(METRICS)] == ["policy", *METRICS]
    assert [r[0] for r in rows[1:]] == ["zero", "fins"]
    data = json.loads((out / "evaluation.json").read_text())
    assert len(data["policies"]["fins"]["per_episode"]["returns"]) == 3
    assert (out / "evaluation.png").stat().st_size > 10_000


def test_bad_policy_and_episode_count():
    with pytest.raises(ValueError, match="unknown policy"):
        evaluate_policies(ROLL_ID, ["lqg"], episodes=1, seed=0)
    with pytest.raises(ValueError, match="episodes"):
        evaluate_policies(ROLL_ID, ["zero"], episodes=0, seed=0)
    with pytest.raises(FileNotFoundError):
        evaluate_policies(ROLL_ID, ["model:/nonexistent/run"], episodes=1, seed=0)


def test_vertical_acceleration_metric_is_the_rms_of_the_env_info():
    """RideControl-v2 gives ``info["vertical_acceleration_mps2"]``: the metric is its RMS over
    the episode's steps, as a single env stepped by hand gives it (same seed and arithmetic:
    equal to rounding, rel 1e-12)."""
    steps = 24
    stats = run_episodes(
        "ship_gym/RideControl-v2", lambda env: make_baseline("zero", env), [5], max_steps=steps
    )
    env = gymnasium.make("ship_gym/RideControl-v2", max_episode_steps=steps)
    env.reset(seed=5)
    squares = []
    for _ in range(steps):
        _, _, terminated, truncated, info = env.step(np.zeros(1, dtype=np.float32))
        squares.append(float(info["vertical_acceleration_mps2"]) ** 2)
        if terminated or truncated:
            break
    env.close()
    expected = np.sqrt(np.mean(squares))
    assert expected > 0.0
    assert stats.rms_vertical_acceleration_mps2[0] == pytest.approx(expected, rel=1e-12)
    assert summarize(stats)["rms_vertical_acceleration_mps2"] == pytest.approx(expected, rel=1e-12)
