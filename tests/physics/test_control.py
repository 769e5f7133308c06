"""Servo limits inside the simulator, and the heading autopilot on a Nomoto plant."""

import numpy as np
import pytest

from ship_gym.control import (
    RUDDER_SERVO,
    Actuated,
    HeadingAutopilot,
    NomotoModel,
    ServoSpec,
)
from ship_gym.dynamics.simulator import Simulator
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.hull import equilibrium, load_hull


class NomotoYaw(ForceModel):
    """Yaw moment making the held-everything-but-yaw ship obey T ṙ + r = K δ exactly."""

    name = "nomoto"

    def __init__(self, inertia: float, model: NomotoModel) -> None:
        self.inertia, self.model = inertia, model

    def evaluate(self, ctx: ForceContext, states):
        delta = ctx.commands.get("rudder", 0.0)
        n = self.inertia * (self.model.gain * delta - ctx.nu[5]) / self.model.time_constant
        return np.array([0, 0, 0, 0, 0, n]), np.zeros(0)


@pytest.fixture(scope="module")
def s175():
    return load_hull("s175")


def _yaw_sim(hull, model, autopilot=None, servo=RUDDER_SERVO, dt=0.1):
    inertia = hull.mass.rigid_body_matrix()[5, 5]
    steering = Actuated(NomotoYaw(inertia, model), servo, "rudder", controller=autopilot)
    # only yaw is free: buoyancy and weight act on held DOFs, so no hydrostatics is needed
    sim = Simulator(hull, [steering], dt=dt, free_dofs=[0, 0, 0, 0, 0, 1])
    eq = equilibrium(hull)
    sim.reset(eta=np.array([0, 0, eq.heave, 0, eq.trim, 0.0]))
    return sim


def test_servo_rate_and_saturation_are_exact(s175):
    # A hard-over command from 0: the angle grows at exactly the rate limit (RK4 weights are
    # positive and every stage slope is clipped), then stops at the limit.
    model = NomotoModel(0.05, 30.0)
    sim = _yaw_sim(s175, model)
    rate = RUDDER_SERVO.max_rate
    angles = []
    for _ in range(200):
        sim.step({"rudder_command": np.radians(60.0)})  # beyond the ±35° limit
        angles.append(sim.z[0])
    angles = np.array(angles)
    steps = np.diff(np.concatenate([[0.0], angles]))
    assert np.all(steps <= rate * sim.dt * (1 + 1e-12))
    # the servo is rate limited while far from the target: exactly max_rate·dt per step
    far = np.abs(RUDDER_SERVO.max_angle - angles) > rate * 0.05 + rate * sim.dt
    np.testing.assert_allclose(steps[far], rate * sim.dt, rtol=1e-12)
    assert RUDDER_SERVO.applied(angles).max() <= RUDDER_SERVO.max_angle
    assert angles[-1] == pytest.approx(RUDDER_SERVO.max_angle, abs=1e-6)


def test_autopilot_holds_course_and_steps_20_degrees(s175):
    # Closed loop on an exact Nomoto plant: with ω_n = 0.06 rad/s, ζ = 0.9 the PD pair gives an
    # overshoot of e^{−πζ/√(1−ζ²)} ≈ 0.15 % for the linear loop; the integral action and the
    # rate-limited servo add some: bound the overshoot at 5 % of the step and settle within 1°.
    model = NomotoModel(gain=0.05, time_constant=40.0)
    ap = HeadingAutopilot.from_nomoto(model)
    sim = _yaw_sim(s175, model, autopilot=ap)
    res = sim.run(100.0)
    assert np.abs(res.eta[:, 5]).max() < 1e-9  # course held (no disturbance)
    sim.commands = {"heading": np.radians(20.0)}
    res = sim.run(400.0)
    psi = np.degrees(res.eta[:, 5])
    assert psi.max() < 20.0 * 1.05
    assert abs(psi[-1] - 20.0) < 1.0
    assert np.degrees(np.abs(sim.z[0])) <= 35.0


def test_anti_windup_limits_the_integral(s175):
    # A 90° heading change saturates the rudder for a long time; with back-calculation the
    # integral stays bounded and the overshoot stays moderate (without it, it would wind up).
    model = NomotoModel(gain=0.05, time_constant=40.0)
    ap = HeadingAutopilot.from_nomoto(model, natural_frequency=0.1)
    sim = _yaw_sim(s175, model, autopilot=ap)
    sim.commands = {"heading": np.radians(90.0)}
    res = sim.run(600.0)
    psi = np.degrees(res.eta[:, 5])
    assert psi.max() < 90.0 * 1.15
    assert abs(psi[-1] - 90.0) < 2.0


def test_nomoto_identification_recovers_k_and_t():
    t = np.linspace(0, 200, 401)
    r = 0.04 * 0.1 * (1 - np.exp(-t / 25.0))
    m = NomotoModel.identify(t, r, 0.1)
    assert m.gain == pytest.approx(0.04, rel=1e-6)
    assert m.time_constant == pytest.approx(25.0, rel=1e-6)


def test_bad_servo_and_gains_are_rejected():
    with pytest.raises(ValueError, match="max_rate"):
        ServoSpec(max_angle=0.5, max_rate=0.0)
    with pytest.raises(ValueError, match="Nomoto gain"):
        NomotoModel(-1.0, 10.0)
    with pytest.raises(ValueError, match="kp"):
        HeadingAutopilot(kp=-1.0, kd=0.0, ki=0.0)
