"""The passive U-tube anti-roll tank (ship_gym.forces.antiroll_tank): its closed forms, and a
tank tuned to the roll natural frequency reduces resonant beam-sea roll on the compiled path."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ship_gym.engine.batch import build_batch_simulator
from ship_gym.engine.ship import (
    ShipSetup,
    database_of,
    roll_natural_frequency,
    ship_of,
    wave_field_for,
)
from ship_gym.forces.antiroll_tank import UTubeTank
from ship_gym.forces.base import ForceContext
from ship_gym.waves import RegularWave


def test_natural_frequency_and_static_free_surface_moment():
    tank = UTubeTank(3.0, 10.0, 20.0, 3.0, 0.5, rho=1000.0, g=9.81)
    # ω_t² = 2 g / (2 h_r + b_r w / h_d) (the classical U-tube)
    assert tank.natural_frequency == pytest.approx(math.sqrt(2 * 9.81 / (6.0 + 3.0 * 20.0 / 0.5)))
    # at rest at heel φ the liquid stands at η = w sin φ / 2 and heels the ship by the
    # free-surface moment ρ g A_r w² sin φ / 2
    phi = 0.05
    eta_t = 20.0 * math.sin(phi) / 2.0
    ctx = ForceContext(t=0.0, eta=np.array([0, 0, 0, phi, 0, 0.0]), nu=np.zeros(6),
                       rotation=np.eye(3))  # fmt: skip
    force, zdot = tank.evaluate(ctx, np.array([eta_t, 0.0]))
    np.testing.assert_allclose(zdot, [0.0, 0.0], atol=1e-9)
    assert force[3] == pytest.approx(1000.0 * 9.81 * 30.0 * 20.0**2 * math.sin(phi) / 2.0)
    assert tank.tuned(0.3, 3.0, 10.0, 20.0, 3.0).natural_frequency == pytest.approx(0.3)


def test_a_tuned_tank_reduces_resonant_beam_sea_roll():
    setup = ShipSetup(
        integrator="holloway", dt=0.1, diffraction=True,
        free_dofs=(False, True, True, True, False, False),
    )  # fmt: skip
    ship = ship_of(setup)
    omega = roll_natural_frequency(ship.hull, database_of(setup, ship))
    sea = RegularWave(height=1.0, period=2 * math.pi / omega, ramp_time=30.0)
    field = wave_field_for(sea, math.pi / 2)
    # a tank of 0.4 % of the displacement (its free surface costs ≈ 11 % of the GM), tuned to
    # the roll natural frequency
    tank = UTubeTank.tuned(omega, 2.0, 8.0, 18.0, 2.0, damping_ratio=0.3)
    assert 0.002 < tank.liquid_mass / ship.hull.mass.mass < 0.01
    bare = build_batch_simulator(setup, [field], sea=sea, wave_heading=math.pi / 2)
    fitted = build_batch_simulator(
        setup, [field], sea=sea, wave_heading=math.pi / 2, extra_forces=[tank]
    )
    assert bare.compiled and fitted.compiled
    n = round(600.0 / setup.dt)
    rolls = []
    for sim in (bare, fitted):
        sim.advance(n // 2)  # the transient
        red = sim.advance(n // 2)
        rolls.append(float(red.max_abs_roll[0]))
    # a tuned passive tank reduces resonant roll substantially (Lloyd 1989, ch. 13); measured
    # here 9.1° → 1.6°: a linear model (linearised duct losses) on a lightly damped ship, more
    # than full-scale tanks achieve — the bound asks for half
    assert rolls[1] < 0.5 * rolls[0], rolls
