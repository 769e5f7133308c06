"""Regenerate ``simulator_reference.npz``: ship trajectories frozen for the engine's tests.

The first stored file was written by the single-ship Python ``Simulator`` of commit 6586197,
before that class became the one-ship view of the engine; it was regenerated with this script
at the physics changes of issue #13. ``tests/engine/test_engine_reference.py`` checks that the
engine still produces them. Rerun only on purpose (a physics change), from the
repository root: ``python tests/data/make_simulator_reference.py``.
"""

import json
import subprocess

import numpy as np

from ship_gym.engine.ship import ShipSetup, build_simulator
from ship_gym.waves.sea_state import IrregularSea, RegularWave

CASES = {
    "controlled_holloway": dict(
        setup=dict(
            speed=8.0,
            integrator="holloway",
            dt=0.1,
            propulsion=True,
            manoeuvring=True,
            rudder="autopilot",
            fins="controller",
            added_resistance="reflection",
        ),
        sea=("irregular", 4.0, 11.0, 30),
        heading=150.0,
        seed=3,
        steps=300,
    ),
    "controlled_rk4": dict(
        setup=dict(
            speed=9.0,
            integrator="rk4",
            dt=0.05,
            propulsion=True,
            manoeuvring=True,
            rudder="autopilot",
            t_foil="controller",
            fins="command",
        ),
        sea=("irregular", 3.0, 9.0, 25),
        heading=120.0,
        seed=5,
        steps=200,
    ),
    "convolution_rk4": dict(
        setup=dict(radiation="convolution", integrator="rk4", dt=0.05),
        sea=("regular", 4.0, 175.0),
        heading=180.0,
        seed=0,
        steps=200,
    ),
    "case2a_held": dict(
        setup=dict(
            radiation="2a",
            integrator="rk4",
            dt=0.1,
            speed=5.0,
            free_dofs=(False, False, True, True, True, False),
        ),
        sea=("regular", 3.0, 150.0),
        heading=90.0,
        seed=0,
        steps=200,
    ),
    "rudder_command_holloway": dict(
        setup=dict(speed=6.0, integrator="holloway", dt=0.1, manoeuvring=True, rudder="command"),
        sea=None,
        heading=180.0,
        seed=0,
        steps=200,
        commands={"rudder_command": 0.1},
    ),
}
out = {}
for name, c in CASES.items():
    setup = ShipSetup(**c["setup"])
    s = c["sea"]
    sea = (
        None
        if s is None
        else (
            IrregularSea(hs=s[1], tp=s[2], n_components=s[3])
            if s[0] == "irregular"
            else RegularWave(height=s[1], wavelength=s[2])
        )
    )
    sim = build_simulator(
        setup, sea, wave_heading=np.radians(c["heading"]), rng=np.random.default_rng(c["seed"])
    )
    if c.get("commands"):
        sim.commands = {**sim.commands, **c["commands"]}
    eta, nu = [sim.eta.copy()], [sim.nu.copy()]
    for _ in range(c["steps"]):
        sim.step()
        eta.append(sim.eta.copy())
        nu.append(sim.nu.copy())
    out[f"{name}/eta"] = np.array(eta)
    out[f"{name}/nu"] = np.array(nu)
    for f in sim.forces:
        if hasattr(f, "angle"):  # a servo-driven actuator: its angle lives in the engine
            out[f"{name}/angle/{f.name}"] = np.array(float(sim.actuator_angle(f.name)))
    print(
        name, np.abs(np.array(eta)[-1]).round(4), [k for k in out if k.startswith(name + "/angle")]
    )
rev = subprocess.check_output(["git", "rev-parse", "--short", "HEAD"], text=True).strip()
np.savez_compressed(
    "tests/data/simulator_reference.npz", cases=json.dumps(CASES), commit=rev, **out
)
