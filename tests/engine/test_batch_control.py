"""Vectorised control models (ship_gym.engine.batch_control) against the single-ship ones.

A batch built with the vectorised control models must follow (a) the same batch with every
control model wrapped per ship in PerShipForceModel (the single-ship models' own code) and (b)
independent one-ship runs (:class:`Simulator`), to rounding, while rudder (autopilot or
command), fins and T-foil (command or controller) move.
"""

import numpy as np
import pytest

from ship_gym.engine.batch import PerShipForceModel, build_batch_simulator
from ship_gym.engine.batch_control import (
    BatchActuatedSurfaces,
    BatchHullManoeuvring,
    BatchPropeller,
    BatchResistance,
    batch_control_model,
)
from ship_gym.engine.ship import ShipSetup, build_simulator
from ship_gym.forces.added_resistance import AddedResistance
from ship_gym.forces.base import ForceContext
from ship_gym.forces.fins import SternFlaps
from ship_gym.waves.sea_state import IrregularSea

SEA = IrregularSea(hs=4.0, tp=10.0, n_components=30, ramp_time=5.0)
# The batch repeats the single-ship arithmetic statement by statement; the only differences
# are summation orders (cross-flow strips, the shaft-speed trim's force sum): ≈ 1e-15 relative
# is observed after 200 steps, 1e-9 leaves room for the growth of rounding in a chaotic-ish
# nonlinear system while still catching any modelling difference (those show at ≥ 1e-4).
REL_TOL = 1e-9
HEADINGS = (1.2, 2.5, 0.6)  # stern-quartering, bow-quartering, following-quartering


def _single_and_batches(setup):
    sims = [
        build_simulator(setup, SEA, wave_heading=b, rng=np.random.default_rng(i))
        for i, b in enumerate(HEADINGS)
    ]
    fields = [s.wave_field for s in sims]
    batches = [build_batch_simulator(setup, fields, control=c) for c in ("batch", "per_ship")]
    for b in batches:
        b.reset(eta=np.array([s.eta for s in sims]), nu=np.array([s.nu for s in sims]))
    return sims, batches


def _actuator_states(sim) -> np.ndarray:
    """Servo angles and controller integrals of every actuator of a simulator (per ship rows)."""
    cols = []
    for f in sim.forces:
        models = getattr(f, "models", [f])  # PerShipForceModel: one Actuated per ship
        st = [getattr(m, "states", None) for m in models]
        if st[0] is None or getattr(f, "servo", getattr(models[0], "servo", None)) is None:
            continue
        if len(st) == 1:
            cols += [st[0].delta, st[0].integral]
        else:
            cols += [
                np.concatenate([x.delta for x in st]),
                np.concatenate([x.integral for x in st]),
            ]
    return np.column_stack(cols) if cols else np.zeros((1, 0))


def _commands(k: int, dt: float) -> dict:
    t = k * dt
    cmd = {
        "fins_command": np.array([0.2 * np.sin(0.5 * t), -0.3 * np.sin(0.3 * t), 0.6]),
        "t_foil_command": np.array([0.1 * np.cos(0.7 * t), 0.3, -0.05]),
        "rudder_command": np.array([0.1 * np.sin(0.2 * t), -0.7, 0.05]),
    }
    if k > 20:
        cmd["heading"] = np.array([0.0, 0.15, -0.3])
    return cmd


def _run_and_compare(setup, n_steps):
    sims, (batch, per_ship) = _single_and_batches(setup)
    assert not any(isinstance(f, PerShipForceModel) for f in batch.forces)
    assert sum(isinstance(f, PerShipForceModel) for f in per_ship.forces) >= 3
    assert batch.n_states == per_ship.n_states == sims[0].n_states
    np.testing.assert_allclose(
        batch.commands["shaft_speed"], [s.commands["shaft_speed"] for s in sims], rtol=1e-12
    )
    applied = np.zeros((n_steps, len(sims)))
    for k in range(n_steps):
        cmd = _commands(k, setup.dt)
        batch.step(cmd)
        per_ship.step(cmd)
        for i, s in enumerate(sims):
            s.step({key: float(v[i]) for key, v in cmd.items()})
        applied[k] = batch.forces[-1].angle  # the last actuator's servo angle
    single = np.array(
        [np.concatenate([s.eta, s.nu, s.z, _actuator_states(s.engine).ravel()]) for s in sims]
    )
    for other, what in ((batch, "vectorised"), (per_ship, "per-ship")):
        state = np.concatenate([other.eta, other.nu, other.z, _actuator_states(other)], axis=1)
        scale = np.maximum(np.abs(single).max(axis=0), 1e-6)
        err = np.abs(state - single).max(axis=0) / scale
        assert err.max() < REL_TOL, f"{what} vs single-ship: worst relative error {err.max()}"
    assert not batch.diverged.any()
    return batch, applied


def test_vectorised_control_models_match_per_ship_and_single_ship_runs():
    # propulsion + manoeuvring + autopilot (heading steps at t = 1 s) + commanded fins and
    # T-foil (sinusoids and saturating constants), Holloway: 200 steps = 10 s.
    setup = ShipSetup(
        speed=10.0, propulsion=True, manoeuvring=True, rudder="autopilot", fins="command",
        t_foil="command", integrator="holloway",
    )  # fmt: skip
    batch, applied = _run_and_compare(setup, 200)
    # the actuators moved: the foil servo of ship 1 reached its command 0.3 → limit 15°
    assert abs(applied[-1, 1] - np.radians(15.0)) < 1e-9
    assert np.ptp(applied[:, 0]) > 0.1
    # the autopilot put the rudder of ship 1 to starboard and of ship 2 to port
    rudder = batch.actuator_angles("rudder")
    assert rudder[1] > 0.01 and rudder[2] < -0.01


def test_vectorised_controllers_match_with_rk4():
    # commanded rudder, fin and ride controllers (closed loop on roll / heave and pitch rates)
    setup = ShipSetup(
        speed=8.0, propulsion=True, manoeuvring=True, rudder="command", fins="controller",
        t_foil="controller", integrator="rk4",
    )  # fmt: skip
    _run_and_compare(setup, 60)


def test_conversion_table_and_unsupported_models():
    setup = ShipSetup(
        speed=8.0, propulsion=True, manoeuvring=True, rudder="command", fins="command",
        added_resistance="reflection",
    )  # fmt: skip
    sim = build_simulator(setup, SEA, wave_heading=np.pi, rng=np.random.default_rng(0))
    kinds = {}
    for m in sim.forces:
        try:
            kinds[m.name] = type(batch_control_model(m))
        except NotImplementedError:
            kinds[m.name] = None
    assert kinds["resistance"] is BatchResistance
    assert kinds["propeller"] is BatchPropeller
    assert kinds["hull_manoeuvring"] is BatchHullManoeuvring
    assert kinds["rudder"] is kinds["roll_fins"] is BatchActuatedSurfaces
    added = next(m for m in sim.forces if isinstance(m, AddedResistance))
    assert kinds[added.name] is None  # stays per ship in build_batch_simulator
    batch = build_batch_simulator(setup, [sim.wave_field])
    assert isinstance(batch.forces[[f.name for f in batch.forces].index(added.name)],
                      PerShipForceModel)  # fmt: skip
    with pytest.raises(ValueError, match="control"):
        build_batch_simulator(setup, [None], control="python")


def test_bare_surfaces_read_their_angle_and_bad_commands_raise():
    # a bare SternFlaps (no servo) reads commands["flaps"]; its force at speed matches the
    # single-ship model's, and a NaN command is refused with a clear error
    flaps = SternFlaps(x=-85.0, z=1.0, span=3.0, chord=1.0, lateral_positions=(-4.0, 4.0))
    setup = ShipSetup(speed=8.0, diffraction=False)
    batch = build_batch_simulator(setup, [None, None], extra_forces=[batch_control_model(flaps)])
    batch.commands["flaps"] = np.array([0.1, -0.2])
    f = batch.force_breakdown()["stern_flaps"]
    for i, angle in enumerate((0.1, -0.2)):
        ctx = ForceContext(
            t=0.0, eta=batch.eta[i], nu=batch.nu[i], rotation=np.eye(3),
            commands={"flaps": angle},
        )  # fmt: skip
        np.testing.assert_allclose(f[i], flaps.evaluate(ctx, np.zeros(0))[0], rtol=1e-13)
    assert f[0, 2] < 0.0 < f[1, 2]  # trailing edges down: upward force (z down)
    with pytest.raises(ValueError, match="flaps"):
        batch.step({"flaps": np.array([np.nan, 0.0])})
