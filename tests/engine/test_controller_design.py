"""The classical controllers designed from the ship's own linear model
(ship_gym.engine.ship.fin_stabiliser, heading_autopilot, ride_controller): the same design the
simulator builds for fins="controller", rudder="autopilot" and t_foil="controller", and the
design's dependence on its choices."""

import dataclasses

import pytest

from ship_gym.control.actuators import Actuated
from ship_gym.control.autopilot import HeadingAutopilot
from ship_gym.control.stabilisers import FinController, RideController
from ship_gym.engine.ship import (
    ShipSetup,
    build_simulator,
    fin_stabiliser,
    heading_autopilot,
    ride_controller,
)

SETUP = ShipSetup(speed=10.0, propulsion=True, manoeuvring=True)


def _controller(setup: ShipSetup, kind: type):
    sim = build_simulator(setup)
    found = [
        f.controller
        for f in sim.forces
        if isinstance(f, Actuated) and isinstance(f.controller, kind)
    ]
    assert len(found) == 1
    return found[0]


def test_fin_stabiliser_is_the_simulators_fin_controller_and_linear_in_its_fractions():
    # fins="controller" builds FinController.tuned(K_δ, C44, I44 + A44) at ζ_add 0.3, c_add 0.2:
    # fin_stabiliser rebuilds it from the setup alone, to rounding
    built = _controller(dataclasses.replace(SETUP, fins="controller"), FinController)
    design = fin_stabiliser(SETUP)
    assert design.k_rate == pytest.approx(built.k_rate, rel=1e-12)
    assert design.k_roll == pytest.approx(built.k_roll, rel=1e-12)
    # k_p = 2 ζ √(C44 (I44 + A44)) / K_δ and k_φ = c C44 / K_δ
    unit = fin_stabiliser(SETUP, added_damping=1.0, added_stiffness=1.0)
    assert design.k_rate == pytest.approx(0.3 * unit.k_rate, rel=1e-12)
    assert design.k_roll == pytest.approx(0.2 * unit.k_roll, rel=1e-12)
    with pytest.raises(ValueError, match="added_damping"):
        fin_stabiliser(SETUP, added_damping=-0.1)
    with pytest.raises(ValueError, match="added_stiffness"):
        fin_stabiliser(SETUP, added_stiffness=float("nan"))


def test_heading_autopilot_is_the_simulators_autopilot_and_follows_pole_placement():
    built = _controller(dataclasses.replace(SETUP, rudder="autopilot"), HeadingAutopilot)
    design = heading_autopilot(SETUP)
    assert (design.kp, design.kd, design.ki) == pytest.approx(
        (built.kp, built.kd, built.ki), rel=1e-12
    )
    # K_p = T ω²/K: doubling ω_n quadruples K_p; K_i = K_p ω_n/10
    fast = heading_autopilot(SETUP, natural_frequency=0.12)
    assert fast.kp == pytest.approx(4.0 * design.kp, rel=1e-12)
    assert fast.ki == pytest.approx(fast.kp * 0.12 / 10.0, rel=1e-12)
    # K_d = (2 ζ ω T − 1)/K grows with ζ
    assert heading_autopilot(SETUP, damping=1.2).kd > design.kd
    with pytest.raises(ValueError, match="natural_frequency"):
        heading_autopilot(SETUP, natural_frequency=0.0)
    with pytest.raises(ValueError, match="damping"):
        heading_autopilot(SETUP, damping=-1.0)


def test_ride_controller_is_the_simulators_and_linear_in_its_damping_fractions():
    # t_foil="controller" builds RideController.tuned(Z_δ, M_δ, C33, m + A33, C55, I55 + A55)
    # at ζ_3 = ζ_5 = 0.2: ride_controller rebuilds it from the setup alone, to rounding
    built = _controller(dataclasses.replace(SETUP, t_foil="controller"), RideController)
    design = ride_controller(SETUP)
    assert design.k_heave == pytest.approx(built.k_heave, rel=1e-12)
    assert design.k_pitch == pytest.approx(built.k_pitch, rel=1e-12)
    # k_w = 2 ζ_3 √(C33 (m + A33)) / Z_δ, k_q = 2 ζ_5 √(C55 (I55 + A55)) / M_δ: each gain
    # scales with its own fraction only
    pitch_only = ride_controller(SETUP, heave_damping=0.0, pitch_damping=1.0)
    assert pitch_only.k_heave == 0.0
    assert pitch_only.k_pitch == pytest.approx(5.0 * design.k_pitch, rel=1e-12)
    with pytest.raises(ValueError, match="heave_damping"):
        ride_controller(SETUP, heave_damping=-0.1)
    with pytest.raises(ValueError, match="pitch_damping"):
        ride_controller(SETUP, pitch_damping=float("inf"))
