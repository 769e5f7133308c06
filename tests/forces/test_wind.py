"""The mean wind load (ship_gym.forces.wind): Blendermann's closed form, the compiled path, and
the ship file / ShipSetup / gymnasium.make routes to it."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import ship_gym  # noqa: F401  (registers the environments)
from ship_gym.engine.batch import build_batch_simulator
from ship_gym.engine.ship import ShipSetup, ship_of
from ship_gym.forces.wind import AIR_DENSITY, MeanWind, Windage

WINDAGE = Windage(
    frontal_area=500.0, lateral_area=2300.0, centroid_height=7.3, centroid_x=-5.0,
    length_overall=183.0,
)  # fmt: skip


def _closed_form(w: Windage, v_w: float, chi: float, psi: float, u: float, v: float):
    """Blendermann (1994) in Fossen's (2011, eq. 8.24–8.31) notation, written independently."""
    u_r = u + v_w * math.cos(chi - psi)
    v_r = v + v_w * math.sin(chi - psi)
    gamma = -math.atan2(v_r, u_r)
    q = 0.5 * AIR_DENSITY * (u_r**2 + v_r**2)
    cdl_af = w.cdl_af_ahead if abs(gamma) <= math.pi / 2 else w.cdl_af_astern
    cdl = cdl_af * w.frontal_area / w.lateral_area
    d = 1.0 - 0.5 * w.delta * (1.0 - cdl / w.cdt) * math.sin(2.0 * gamma) ** 2
    cx = -cdl * (w.lateral_area / w.frontal_area) * math.cos(gamma) / d
    cy = w.cdt * math.sin(gamma) / d
    cn = (w.centroid_x / w.length_overall - 0.18 * (abs(gamma) - math.pi / 2)) * cy
    return np.array([
        q * w.frontal_area * cx, q * w.lateral_area * cy, 0.0,
        q * w.lateral_area * w.centroid_height * w.kappa * cy, 0.0,
        q * w.lateral_area * w.length_overall * cn,
    ])  # fmt: skip


def test_head_and_beam_wind_are_the_drag_coefficients():
    v_w = 20.0
    q = 0.5 * AIR_DENSITY * v_w**2
    head = MeanWind(WINDAGE, v_w, 0.0).load(psi=0.0)
    np.testing.assert_allclose(head, [-q * 500.0 * 0.55, 0, 0, 0, 0, 0], atol=1e-6)
    # from the starboard beam (ship heading north, wind from the east): pushed to port, heeled
    # to port, and the bow turned by the centroid's 5 m aft of amidships
    beam = MeanWind(WINDAGE, v_w, math.pi / 2).load(psi=0.0)
    y = -q * 2300.0 * 0.90
    expected = [0.0, y, 0.0, 7.3 * 1.4 * y, 0.0, -5.0 * y]
    np.testing.assert_allclose(beam, expected, rtol=1e-12, atol=1e-6)
    # a stern wind pushes the ship ahead with C_Dl,AF(π)
    stern = MeanWind(WINDAGE, v_w, math.pi).load(psi=0.0)
    assert stern[0] == pytest.approx(q * 500.0 * 0.55)


@pytest.mark.parametrize(
    ("chi", "psi", "u", "v"),
    [(0.3, 0.0, 0.0, 0.0), (2.0, 0.4, 6.0, 0.5), (-2.5, 1.0, 8.0, -1.0), (1.0, 1.0, 3.0, 0.0)],
)
def test_any_relative_wind_is_the_closed_form(chi, psi, u, v):
    got = MeanWind(WINDAGE, 17.0, chi).load(psi=psi, u=u, v=v)
    np.testing.assert_allclose(got, _closed_form(WINDAGE, 17.0, chi, psi, u, v), rtol=1e-12)


def test_a_port_wind_mirrors_a_starboard_wind():
    stbd = MeanWind(WINDAGE, 12.0, 0.7).load(psi=0.0, u=4.0)
    port = MeanWind(WINDAGE, 12.0, -0.7).load(psi=0.0, u=4.0)
    np.testing.assert_allclose(port, stbd * [1, -1, 1, -1, 1, -1], rtol=1e-12)


def test_the_ship_file_and_setup_route_runs_compiled_and_equals_the_numpy_path():
    windage = ship_of(ShipSetup()).windage()
    assert windage.lateral_area == 2300.0
    setup = ShipSetup(integrator="holloway", wind=(18.0, math.pi / 2), dt=0.1)
    fast = build_batch_simulator(setup, [None, None])
    slow = build_batch_simulator(setup, [None, None], backend="numpy")
    assert fast.compiled
    assert any(isinstance(f, MeanWind) for f in fast.forces)
    fast.advance(200)
    slow.advance(200)
    np.testing.assert_allclose(fast.eta, slow.eta, rtol=1e-9, atol=1e-9)
    assert fast.nu[0, 1] < -0.05  # a wind from the east sets the ship to the west (port)
    np.testing.assert_array_equal(fast.eta[0], fast.eta[1])  # ship i of a batch = ship alone


def test_gymnasium_make_takes_the_wind():
    env = gym.make("ship_gym/CourseKeeping-v3", wind_speed_mps=15.0, wind_from_deg=90.0)
    try:
        sim = env.unwrapped.task.sim
        wind = next(f for f in sim.forces if isinstance(f, MeanWind))
        assert wind.speed == 15.0 and wind.direction_from == pytest.approx(math.pi / 2)
        env.reset(seed=0)
        env.step(env.action_space.sample())
    finally:
        env.close()
    with pytest.raises(ValueError, match="wind_speed_mps"):
        gym.make("ship_gym/CourseKeeping-v3", wind_speed_mps=-1.0)
