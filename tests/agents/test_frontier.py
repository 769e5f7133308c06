"""ship_gym.agents.frontier: the gain-scaled family of a baseline and its metric at an effort."""

import gymnasium
import pytest

import ship_gym  # noqa: F401
from ship_gym.agents.baselines import DEFAULT_GAINS
from ship_gym.agents.evaluate import evaluate_policies
from ship_gym.agents.frontier import (
    FrontierPoint,
    baseline_frontier,
    gain_scaled_baseline,
    metric_at_effort,
)


def test_every_loop_gain_is_scaled_and_nothing_else():
    env = gymnasium.make("ship_gym/CourseKeeping-v2")
    try:
        pid = gain_scaled_baseline("pid", env, 2.5)
        tuned = DEFAULT_GAINS[("pid", "CourseKeeping")]
        assert (pid.k_p, pid.k_d, pid.k_i) == pytest.approx(
            (2.5 * tuned["k_p"], 2.5 * tuned["k_d"], 2.5 * tuned["k_i"]), rel=1e-15
        )
        assert pid.integral_limit == gain_scaled_baseline("pid", env, 1.0).integral_limit
        with pytest.raises(ValueError, match="factor must be a finite number > 0, got 0"):
            gain_scaled_baseline("pid", env, 0)
        with pytest.raises(ValueError, match="baseline 'zero' has no k_\\* gains"):
            gain_scaled_baseline("zero", env, 1.0)
    finally:
        env.close()


def _point(effort, metric):
    return FrontierPoint(factor=1.0, effort=effort, metric=metric, mean_return=0.0)


def test_metric_at_effort_interpolates_between_non_dominated_points():
    # (0.3, 1.1) is dominated by (0.2, 1.0); (0.5, 0.85) saturates: more gain did not help
    points = [_point(0.1, 2.0), _point(0.3, 1.1), _point(0.2, 1.0), _point(0.4, 0.8),
              _point(0.5, 0.85)]  # fmt: skip
    assert metric_at_effort(points, 0.15) == pytest.approx(1.5)
    assert metric_at_effort(points, 0.3) == pytest.approx(0.9)  # between 0.2 and 0.4
    assert metric_at_effort(points, 0.45) == pytest.approx(0.8)  # the best with no more effort
    assert metric_at_effort(points, 0.05) is None  # below the family's range
    assert metric_at_effort(points, 0.6) is None  # above it
    assert metric_at_effort([], 0.3) is None


def test_the_family_passes_through_the_tuned_baseline_and_gains_buy_effort():
    env_id, seeds, kwargs = "ship_gym/RollOneDOF-v0", [300, 301], {"max_episode_steps": 60}
    points = baseline_frontier(env_id, "fins", "rms_roll_deg", seeds, kwargs,
                               factors=(0.5, 1.0, 2.0))  # fmt: skip
    assert [p.factor for p in points] == [0.5, 1.0, 2.0]
    tuned = evaluate_policies(env_id, ["fins"], 2, 300, kwargs, progress=False)["policies"]["fins"]
    # c = 1 is the tuned controller itself: the same episodes, the same numbers
    assert points[1].effort == tuned["rms_action"] and points[1].metric == tuned["rms_roll_deg"]
    # more feedback gain: more fin action and less roll (a PD on roll angle and rate)
    assert points[0].effort < points[1].effort < points[2].effort
    assert points[0].metric > points[1].metric > points[2].metric


def test_the_benchmark_compares_each_policy_with_the_family_at_its_own_effort(tmp_path):
    from ship_gym.agents.benchmark import TASKS, _plot_frontier, _verdict, results_markdown

    task = TASKS["RollStabilization"]
    common = {"capsized": 0, "episodes": 4, "capsize_ci95": [0.0, 0.5], "mean_return": -1.0,
              "mean_cost": 0.0}  # fmt: skip
    rows = [
        {"policy": "zero", "metric": 2.0, "effort": 0.0, **common},
        {"policy": "fins", "metric": 1.0, "effort": 0.2, **common},
        # 20 % below the tuned fins but with more effort, where the family reaches 0.9
        {"policy": "ppo seed 0", "config": "ppo", "metric": 0.8, "effort": 0.3, **common},
        {"policy": "ppo seed 1", "config": "ppo", "metric": 0.7, "effort": 0.9, **common},
    ]
    frontier = [_point(0.1, 1.5), _point(0.2, 1.0), _point(0.4, 0.8)]
    result = _verdict(task, rows, frontier)
    first, second = (r for r in result["rows"] if "config" in r)
    assert first["target"] is False  # more effort than the tuned baseline
    assert first["frontier_metric"] == pytest.approx(0.9)
    assert first["gain_at_effort"] == pytest.approx((0.9 - 0.8) / 0.9)
    assert second["gain_at_effort"] is None  # beyond the family's effort range
    result.update(seed=10_000, episodes=4, n_seeds=2, timesteps=100, date="today")
    text = results_markdown({"tasks": {"RollStabilization": result}})
    assert "| +11 % (vs 0.9) |" in text and "| outside the gain range |" in text
    assert "![effort frontier](frontier_RollStabilization.png)" in text
    _plot_frontier("RollStabilization", task, result, tmp_path / "frontier.png")
    assert (tmp_path / "frontier.png").stat().st_size > 1000
