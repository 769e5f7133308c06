"""The classical controllers designed from the ship's own linear model
(ship_gym.engine.ship.fin_stabiliser, heading_autopilot): the same design the simulator builds
for fins="controller" and rudder="autopilot", and the design's dependence on its choices."""

import dataclasses

import pytest

from ship_gym.control.actuators import Actuated
from ship_gym.control.autopilot import HeadingAutopilot
from ship_gym.control.stabilisers import FinController
from ship_gym.engine.ship import ShipSetup, build_simulator, fin_stabiliser, heading_autopilot

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
