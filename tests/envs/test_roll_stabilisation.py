"""ship_gym/RollStabilization-v2: the fins damp the roll; arguments.

The checks every ship environment passes (checkers, seeding, reward = Σ terms, vector env,
actions, time limit), with and without rudder roll stabilisation, are parametrised in
test_ship_task.py; the coarse mesh is described in _ship_env_checks.py.
"""

import numpy as np
import pytest

from ship_gym.envs.roll_stabilisation import RollStabilizationEnv

from ._ship_env_checks import COARSE, full_scale_travel, rollout

BEAM_SEA = {
    "wave_heading_range_deg": (90.0, 90.0),
    "hs_range_m": (4.0, 4.0),
    "tp_range_s": (14.0, 14.0),
}


def _env(**kwargs) -> RollStabilizationEnv:
    return RollStabilizationEnv(**{**COARSE, **kwargs})


def test_fin_stabiliser_through_the_actions_reduces_roll():
    # A PD roll stabiliser δ = −(k_φ φ + k_p p) through the fin action, against zero action on
    # the same beam sea (Hs 4 m, Tp 14 s, seed 3): the fins must damp the roll. Observed with the
    # default mesh: RMS roll 1.07° → 0.76°; the margin asks for a 15 % reduction.
    def rms_roll(policy) -> float:
        run = rollout(_env(**BEAM_SEA), 3, policy, steps=200)
        assert not run.ended
        return float(np.std(run.observations[61:, 0]))

    zero_roll = rms_roll(lambda obs: np.zeros(1, dtype=np.float32))
    pd_roll = rms_roll(
        lambda obs: np.clip([-(2.0 * obs[0] + 15.0 * obs[3])], -1.0, 1.0).astype(np.float32)
    )
    assert np.degrees(zero_roll) > 0.3  # the sea does roll the ship
    assert pd_roll < 0.85 * zero_roll


def test_bad_arguments_raise():
    with pytest.raises(ValueError, match="roll_weight"):
        _env(roll_weight=-1.0)
    with pytest.raises(ValueError, match="passenger_point_m"):
        _env(passenger_point_m=(1.0, 2.0))
    with pytest.raises(ValueError, match="rudder_roll_stabilization"):
        _env(rudder_roll_stabilization="yes")
    with pytest.raises(ValueError, match="control_dt"):
        _env(control_dt_s=0.25, physics_dt_s=0.1)
    with pytest.raises(ValueError, match="comfort_time_constant_s"):
        _env(comfort_time_constant_s=0.0)


def test_fin_travel_is_observed_and_costs_wear():
    # v2: the fin command and the servo travel over the step (as a fraction of the 15 °/s × 0.5 s
    # = 7.5° the servo can travel in one step) are observed; the fin_rate term is
    # −fin_rate_weight · travel². A full-scale step command (0 → 25°) keeps the servo at its rate
    # limit for 25/7.5 = 3.3 steps: travel 1, 1, 1, then ≈ 1/3 and the tail of its 0.1 s lag.
    travel = full_scale_travel(_env(fin_rate_weight=0.5), "fin", "fin_rate", 0.5)
    np.testing.assert_allclose(travel[:3], 1.0, atol=1e-6)
    assert travel[3] == pytest.approx(1.0 / 3.0, abs=0.01)
    assert sum(travel) == pytest.approx(25.0 / 7.5, abs=1e-4)


def test_every_servo_travel_is_kept_by_the_ship_task():
    # ShipTask keeps Δδ/(δ̇_max Δt) of every servo-driven surface, once per step: with rudder
    # roll stabilisation both the fins (15 °/s) and the rudder (2.32 °/s) are commanded
    env = _env(rudder_roll_stabilization=True)
    task = env.unwrapped.task
    assert set(task._servo_names) == {"rudder", "roll_fins"}
    env.reset(seed=0)
    before = {name: task.sim.actuator_model(name).angle.copy() for name in task._servo_names}
    env.step(np.array([0.3, -1.0], dtype=np.float32))
    for name in task._servo_names:
        servo = task.sim.actuator_model(name)
        expected = (servo.angle - before[name]) / (servo.servo.max_rate * task.control_dt)
        np.testing.assert_array_equal(task.servo_travel(name), expected)
    # the rudder ran at its rate limit the whole step; the fins reached 0.3 · 25° = 7.5° = 1 step
    assert task.servo_travel("rudder")[0] == pytest.approx(-1.0, abs=1e-9)
    assert 0.9 < task.servo_travel("roll_fins")[0] <= 1.0
    with pytest.raises(ValueError, match="read-only"):
        task.servo_travel("rudder")[0] = 0.0
    with pytest.raises(ValueError, match=r"no servo-driven force model 'fins'; the setup's are"):
        task.servo_travel("fins")
