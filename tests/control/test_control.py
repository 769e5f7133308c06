"""Servo limits inside the simulator, and the heading autopilot on a Nomoto plant."""

import numpy as np
import pytest

from ship_gym.control import (
    FIN_SERVO,
    FOIL_SERVO,
    RUDDER_SERVO,
    Actuated,
    HeadingAutopilot,
    NomotoModel,
    ServoSpec,
)
from ship_gym.engine.simulator import Simulator
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
        angles.append(sim.forces[0].angle)
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
    assert np.degrees(abs(sim.forces[0].angle)) <= 35.0


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


@pytest.mark.parametrize("integrator", ["rk4", "holloway"])
@pytest.mark.parametrize("dt", [0.05, 0.1, 0.5])
@pytest.mark.parametrize(
    "servo", [RUDDER_SERVO, FIN_SERVO, FOIL_SERVO], ids=["rudder", "fins", "foil"]
)
def test_servo_settles_to_a_constant_command_under_every_integrator(s175, integrator, dt, servo):
    # A constant +5° command from 0 (well inside the limits): the angle rises monotonically,
    # never faster than the rate limit, never past the command, and settles on it. Before the
    # servo was sampled exactly, Holloway's explicit update of the stiff lag (Δt ≈ T) made a
    # +5° fin command cycle 2.68° ↔ 7.18° and a +7° rudder command 6.63° ↔ 7.32°.
    # Tolerances: 1e-12 rad of rounding on the bounds; settled to 1e-9 rad after ten lags
    # beyond the ramp (e^-10 of the ≤ δ̇_max T band left).
    model = NomotoModel(0.05, 30.0)
    inertia = s175.mass.rigid_body_matrix()[5, 5]
    steering = Actuated(NomotoYaw(inertia, model), servo, "rudder")
    sim = Simulator(s175, [steering], dt=dt, integrator=integrator, free_dofs=[0, 0, 0, 0, 0, 1])
    sim.reset(eta=np.zeros(6), nu=np.zeros(6))
    command = np.radians(5.0)
    duration = command / servo.max_rate + 10.0 * servo.lag + 2.0
    angles = [steering.angle]
    for _ in range(int(np.ceil(duration / dt))):
        sim.step({"rudder_command": command})
        angles.append(steering.angle)
    angles = np.array(angles)
    steps = np.diff(angles)
    assert np.all(steps >= -1e-12), "the servo moved away from its command"
    assert np.all(steps <= servo.max_rate * dt + 1e-12), "the servo beat its rate limit"
    assert angles.max() <= command + 1e-12, "the servo overshot its command"
    assert angles[-1] == pytest.approx(command, abs=1e-9)


def test_servo_angle_is_the_exact_solution_of_the_lag_and_rate_limit():
    # closed form vs a fine explicit integration of δ̇ = clip((c − δ)/T, ±R) (Euler, 1e-6 s:
    # error O(R·1e-6) ≈ 1e-7 rad), over a ramp and the exponential tail
    servo = FIN_SERVO
    c, t_end, h = np.radians(20.0), 3.0, 1e-6
    delta, t, checks = 0.0, 0.0, []
    for t_check in (0.2, 1.0, 1.33, 1.5, 3.0):
        while t < t_check - h / 2:
            delta += h * np.clip((c - delta) / servo.lag, -servo.max_rate, servo.max_rate)
            t += h
        checks.append((t_check, delta))
    for t_check, expected in checks:
        assert servo.angle_after(0.0, c, t_check) == pytest.approx(expected, abs=2e-6)
    assert t_end == checks[-1][0]
