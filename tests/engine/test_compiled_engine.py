"""The compiled backend of the row engine against its numpy path, and batch-size independence.

The compiled loop (:mod:`ship_gym.engine.compiled`) runs the same row kernels as the numpy path
of :class:`~ship_gym.engine.batch.BatchSimulator`; the only arithmetic difference is the wave
phasor (polynomial sin/cos in turns vs libm), a few ulp per component, so states agree to
rounding: the tolerance 1e-11 relative (to each column's largest value) over 200 steps leaves
three orders of magnitude above the ≈ 1e-14 observed.
"""

import numpy as np
import pytest

from ship_gym.engine.batch import build_batch_simulator
from ship_gym.engine.ship import ShipSetup, wave_field_for
from ship_gym.waves.sea_state import IrregularSea

HEADINGS = (1.2, 2.5, 0.6)
REL_TOL = 1e-11


def _fields(n=3):
    sea = IrregularSea(hs=4.0, tp=11.0, n_components=30)
    return [wave_field_for(sea, HEADINGS[i % 3], np.random.default_rng(i)) for i in range(n)]


def _commands(k):
    cmd = {"t_foil_command": np.array([0.1 * np.sin(0.3 * k), 0.3, -0.05])}
    if k >= 5:
        cmd["heading"] = np.array([0.0, 0.15, -0.3])
    return cmd


def _state(sim):
    angles = [sim.actuator_angles(n) for n in ("rudder", "roll_fins", "t_foil")]
    return np.column_stack([sim.eta, sim.nu, sim.z, *angles])


@pytest.mark.parametrize("integrator", ["holloway", "rk4"])
def test_compiled_backend_equals_the_numpy_path_with_every_actuator(integrator):
    # propulsion (Holtrop + B-series), manoeuvring, autopilot with a heading step, fin
    # controller, commanded T-foil (sinusoid and a saturating constant), diffraction, memory
    setup = ShipSetup(
        speed=10.0, propulsion=True, manoeuvring=True, rudder="autopilot", fins="controller",
        t_foil="command", integrator=integrator,
    )  # fmt: skip
    fields = _fields()
    sims = [build_batch_simulator(setup, fields, backend=b) for b in ("numpy", "compiled")]
    assert not sims[0].compiled and sims[1].compiled
    for k in range(40):
        reds = [s.advance(5, _commands(k), danger_roll=0.01) for s in sims]
    ref, got = _state(sims[0]), _state(sims[1])
    scale = np.maximum(np.abs(ref).max(axis=0), 1e-6)
    assert (np.abs(got - ref).max(axis=0) / scale).max() < REL_TOL
    np.testing.assert_allclose(reds[1].max_abs_roll, reds[0].max_abs_roll, rtol=1e-10)
    np.testing.assert_allclose(reds[1].sum_sq_roll, reds[0].sum_sq_roll, rtol=1e-10)
    np.testing.assert_array_equal(reds[1].danger_steps, reds[0].danger_steps)
    assert reds[1].danger_steps.max() > 0  # the threshold was crossed: the count is tested
    np.testing.assert_array_equal(sims[1].n_steps, sims[0].n_steps)
    # the actuators moved (the foil of ship 1 reached its 15° limit)
    assert sims[1].actuator_angles("t_foil")[1] == pytest.approx(np.radians(15.0), abs=1e-12)


def test_ship_i_of_a_batch_is_the_ship_alone_bit_for_bit():
    # no reduction across ships reaches a state: any N gives the same trajectory per ship
    setup = ShipSetup(
        speed=8.0, propulsion=True, manoeuvring=True, rudder="autopilot", fins="controller",
        integrator="holloway",
    )  # fmt: skip
    fields = _fields(5)
    batch = build_batch_simulator(setup, fields, backend="compiled")
    alone = build_batch_simulator(setup, fields[3:4], backend="compiled")
    for _ in range(30):
        batch.advance(4, {"heading": np.full(5, 0.1)})
        alone.advance(4, {"heading": np.full(1, 0.1)})
    np.testing.assert_array_equal(batch.eta[3], alone.eta[0])
    np.testing.assert_array_equal(batch.nu[3], alone.nu[0])
    np.testing.assert_array_equal(
        batch.actuator_angles("rudder")[3], alone.actuator_angles("rudder")[0]
    )


def test_a_diverging_ship_is_frozen_and_the_others_go_on():
    setup = ShipSetup(speed=8.0, propulsion=True, manoeuvring=True, rudder="command")
    fields = _fields(2)
    sim = build_batch_simulator(setup, fields, backend="compiled")
    sim.advance(2)
    nu = sim.nu.copy()
    nu[1, 3] = 1e3  # absurd roll rate: the next step fails the divergence test
    sim.nu[:] = nu
    eta_before = sim.eta[1].copy()
    red = sim.advance(3)
    assert red.diverged.tolist() == [False, True]
    assert sim.diverged.tolist() == [False, True]
    np.testing.assert_array_equal(sim.eta[1], eta_before)  # state of the failed step's start
    assert "ship 1 diverged" in sim.divergence_messages[1]
    assert sim.n_steps.tolist() == [5, 2]


def test_models_without_a_compiled_version_fall_back_or_refuse():
    setup = ShipSetup(speed=8.0, propulsion=True, added_resistance="reflection")
    fields = _fields(1)
    auto = build_batch_simulator(setup, fields)
    assert not auto.compiled  # added resistance runs per ship in Python
    auto.advance(2)
    with pytest.raises(NotImplementedError, match="no compiled version"):
        build_batch_simulator(setup, fields, backend="compiled").advance(1)


def test_record_equals_the_simulator_run_with_the_wave_elevation():
    # BatchSimulator.record (the engine behind `ship-gym simulate`) against Simulator.run:
    # same states to rounding (1e-9 as the other engine equivalences) and the same incident
    # elevation at O (computed after the run from the recorded states: 1e-9 m)
    from ship_gym.engine.ship import build_simulator

    setup = ShipSetup(integrator="holloway", speed=3.0)
    sea = IrregularSea(hs=3.0, tp=10.0, n_components=30, ramp_time=5.0)
    sim = build_simulator(setup, sea, wave_heading=2.0, rng=np.random.default_rng(4))
    batch = build_batch_simulator(setup, [sim.wave_field], backend="compiled")
    ref = sim.run(20.0)
    got = batch.record(20.0)
    scale = np.maximum(np.abs(ref.eta - ref.eta[0]).max(axis=0), 1e-6)
    assert (np.abs(got.eta - ref.eta).max(axis=0) / scale).max() < 1e-9
    np.testing.assert_allclose(got.t, ref.t, rtol=1e-12)
    np.testing.assert_allclose(got.elevation, ref.elevation, rtol=0, atol=1e-9)
    assert np.abs(ref.elevation).max() > 0.5  # the sea is up


def test_the_parallel_loop_equals_the_serial_one_bit_for_bit():
    # numba's threads over the ships (prange) change nothing: each ship's arithmetic is its own
    import numba

    setup = ShipSetup(
        speed=8.0, propulsion=True, manoeuvring=True, rudder="autopilot", integrator="holloway"
    )
    fields = _fields(4)
    serial = build_batch_simulator(setup, fields, backend="compiled")
    parallel = build_batch_simulator(setup, fields, backend="compiled", parallel=True)
    numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
    for _ in range(10):
        reds = [s.advance(5, {"heading": np.full(4, 0.2)}) for s in (serial, parallel)]
    np.testing.assert_array_equal(parallel.eta, serial.eta)
    np.testing.assert_array_equal(parallel.z, serial.z)
    np.testing.assert_array_equal(reds[1].sum_sq_roll, reds[0].sum_sq_roll)


def test_bad_commands_are_refused_before_any_step():
    setup = ShipSetup(speed=8.0, propulsion=True, manoeuvring=True, rudder="autopilot")
    sim = build_batch_simulator(setup, _fields(2), backend="compiled")
    eta = sim.eta.copy()
    with pytest.raises(ValueError, match=r"'heading'.*finite"):
        sim.advance(3, {"heading": np.array([0.1, np.nan])})
    with pytest.raises(ValueError, match=r"'shaft_speed'.*\(N,\)"):
        sim.advance(3, {"shaft_speed": np.ones(3), "heading": np.zeros(2)})
    np.testing.assert_array_equal(sim.eta, eta)
    assert sim.n_steps.tolist() == [0, 0]
    sim.advance(2)  # the refused commands were not kept
    assert sim.n_steps.tolist() == [2, 2]


def test_rudder_thrust_commands_without_a_propeller_run_on_the_numpy_path():
    # the compiled loop knows only the rudder's C_Th: a "propeller_thrust" command (read by the
    # numpy path for a rudder without a propeller) sends the call to the numpy path under
    # "auto", with the numpy path's result, and is refused under "compiled"
    setup = ShipSetup(speed=6.0, manoeuvring=True, rudder="command")
    fields = _fields(2)
    cmd = {"rudder_command": np.full(2, 0.2), "propeller_thrust": np.array([4e5, 8e5])}
    auto = build_batch_simulator(setup, fields)
    numpy_path = build_batch_simulator(setup, fields, backend="numpy")
    assert auto.compiled
    for sim in (auto, numpy_path):
        sim.advance(20, cmd)
    np.testing.assert_array_equal(auto.eta, numpy_path.eta)
    compiled = build_batch_simulator(setup, fields, backend="compiled")
    with pytest.raises(NotImplementedError, match="propeller_thrust"):
        compiled.advance(1, cmd)
    assert "propeller_thrust" not in compiled.commands


def test_reset_and_replay_reproduce_a_run_bit_for_bit():
    """A ship reset to its initial state repeats its run exactly, whichever backend filled its
    diffraction cache before (the capsize map's replay relies on it). The numpy path and the
    compiled loop refresh the cache with the same kernel: before they did not, and a
    replay in following seas at Fn 0.4 drifted by 2e-31 in yaw rate after 87 s and failed."""
    from ship_gym.engine.batch import build_batch_simulator
    from ship_gym.engine.ship import ShipSetup, wave_field_for
    from ship_gym.waves.sea_state import IrregularSea

    sea = IrregularSea(hs=4.0, tp=10.0, n_components=20)
    field = wave_field_for(sea, np.radians(30.0), rng=np.random.default_rng(4))
    setup = ShipSetup(speed=8.0, propulsion=True, manoeuvring=True, rudder="autopilot")
    sim = build_batch_simulator(setup, [field], sea=sea, wave_heading=np.radians(30.0))
    t0, eta0, nu0 = sim.t.copy(), sim.eta.copy(), sim.nu.copy()
    first = []
    for _ in range(40):
        sim.advance(10)
        first.append(np.concatenate([sim.eta[0], sim.nu[0]]))
    sim.reset(np.array([0]), eta=eta0, nu=nu0, t0=t0)
    for k in range(40):
        sim.advance(10)
        np.testing.assert_array_equal(np.concatenate([sim.eta[0], sim.nu[0]]), first[k])
    # the cache as the numpy path fills it (the build's shaft-speed trim) and as the compiled
    # loop refills it after a reset, at the same heading and speed: bit-identical
    from ship_gym.engine.batch import BatchDiffraction

    fresh = build_batch_simulator(setup, [field], sea=sea, wave_heading=np.radians(30.0))
    diff = next(f for f in fresh.forces if isinstance(f, BatchDiffraction))
    xd, dxd, ref = (c.copy() for c in diff.caches)
    assert np.isfinite(ref[0, 0])  # filled while building
    fresh.reset(np.array([0]), eta=eta0, nu=nu0, t0=t0)
    fresh.advance(1)
    np.testing.assert_array_equal(diff.caches[2][0], ref[0])
    np.testing.assert_array_equal(diff.caches[0], xd)
    np.testing.assert_array_equal(diff.caches[1], dxd)  # differed by 1e-17 relative before
