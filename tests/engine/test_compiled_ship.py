"""CompiledShip (one ship on the compiled engine) against the engine's numpy path and the
single-ship Simulator (same setup, same sea, same start).

The compiled loop runs the row kernels of the force models; with float64 wave sums it must
follow the numpy path and the Simulator to rounding, and with float32 wave sums stay within a
stated tolerance of its float64 self.
"""

import numpy as np
import pytest

from ship_gym.engine.batch import build_batch_simulator
from ship_gym.engine.compiled import build_compiled_ship
from ship_gym.engine.ship import ShipSetup, build_simulator, wave_field_for
from ship_gym.engine.simulator import SimulationDiverged
from ship_gym.waves.sea_state import IrregularSea

# bow-quartering (roll excited) with a short ramp: the waves are fully up within the compared
# window; the oblique sea turns the ship, so the diffraction cache is refreshed along the way
SEA = IrregularSea(hs=5.0, tp=11.0, n_components=50, ramp_time=5.0)
BETA = np.radians(135.0)
# Rounding-level agreement: the engines do the same arithmetic except the order of a few sums
# (BLAS vs loops) and the wave phasors (polynomial sin/cos vs libm, a few ulp): differences of
# ~1e-15 that a stable, damped system carries along without growth; observed ≲ 1e-14 relative
# over 300 steps. 1e-9 (the BatchSimulator test's bar) leaves a wide margin.
REL_TOL = 1e-9
# float32 wave sums: forces within ~1e-7 of the hydrostatic scale (test_froude_krylov.py);
# observed trajectory differences ≲ 2e-7 of the motion over 300 steps; bar 2e-6.
F32_TOL = 2e-6


def _field(seed: int = 0, beta: float = BETA):
    return wave_field_for(SEA, beta, np.random.default_rng(seed))


def _rel_err(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Max |a − b| per DOF over time, relative to the largest excursion of b from its start
    (floor: 1e-6 of the largest excursion, for DOF that stay ≈ still)."""
    scale = np.abs(b - b[0]).max(axis=0)
    scale = np.maximum(scale, 1e-6 * scale.max())
    return np.abs(a - b).max(axis=0) / scale


@pytest.mark.parametrize(
    ("integrator", "n_steps", "free"),
    [
        ("holloway", 300, (True,) * 6),
        ("rk4", 80, (True,) * 6),
        ("holloway", 120, (False, False, True, True, True, False)),  # surge, sway, yaw held
    ],
)
def test_matches_batch_simulator(integrator, n_steps, free):
    setup = ShipSetup(integrator=integrator, free_dofs=free)
    field = _field()
    ship = build_compiled_ship(setup, field)
    batch = build_batch_simulator(setup, [field], backend="numpy")
    np.testing.assert_array_equal(ship.eta, batch.eta[0])
    mine = ship.run(n_steps)
    theirs = batch.run(n_steps)
    np.testing.assert_allclose(mine["t"], theirs["t"][:, 0], rtol=1e-12)
    for key in ("eta", "nu"):
        err = _rel_err(mine[key], theirs[key][:, 0])
        assert err.max() < REL_TOL, f"{integrator} {key}: relative error per DOF {err}"
    np.testing.assert_allclose(ship.z, batch.z[0], rtol=0, atol=REL_TOL * np.abs(batch.z).max())
    if free[5]:
        assert ship.n_refreshes > 1  # the cache was refreshed after the first look-up


def test_constant_coefficient_radiation_matches_batch_simulator():
    # Matusiak's case 2b (no memory states, −B_c ν_p, A_c on the left): the bench's baseline
    setup = ShipSetup(integrator="holloway", radiation="2b")
    field = _field()
    ship = build_compiled_ship(setup, field, sea=SEA, wave_heading=BETA)
    batch = build_batch_simulator(setup, [field], sea=SEA, wave_heading=BETA, backend="numpy")
    assert ship.n_states == 0
    mine, theirs = ship.run(120), batch.run(120)
    for key in ("eta", "nu"):
        err = _rel_err(mine[key], theirs[key][:, 0])
        assert err.max() < REL_TOL, f"{key}: relative error per DOF {err}"


def test_matches_simulator_with_speed_and_initial_heel():
    # the single-ship engine (its own Holloway start-up), at 4 m/s with an initial heel and yaw
    # rate so that every term (Coriolis, encounter-frequency diffraction, U in ν_p) is active
    setup = ShipSetup(integrator="holloway", speed=4.0)
    sim = build_simulator(setup, SEA, wave_heading=2.5, rng=np.random.default_rng(2))
    field = sim.wave_field
    eta, nu = sim.eta.copy(), sim.nu.copy()
    eta[3], nu[5] = 0.1, 0.01
    sim.reset(eta=eta, nu=nu)
    ship = build_compiled_ship(setup, field)
    ship.reset(eta=eta, nu=nu)
    steps = 160
    ref_eta, ref_nu = [sim.eta.copy()], [sim.nu.copy()]
    for _ in range(steps):
        sim.step()
        ref_eta.append(sim.eta.copy())
        ref_nu.append(sim.nu.copy())
    mine = ship.run(steps)
    for key, ref in (("eta", np.array(ref_eta)), ("nu", np.array(ref_nu))):
        err = _rel_err(mine[key], ref)
        assert err.max() < REL_TOL, f"{key}: relative error per DOF {err}"


def test_float32_wave_sums_stay_close_to_float64():
    setup = ShipSetup(integrator="holloway")
    field = _field()
    f64 = build_compiled_ship(setup, field).run(300)
    f32 = build_compiled_ship(setup, field, precision="float32").run(300)
    for key in ("eta", "nu"):
        err = _rel_err(f32[key], f64[key])
        assert err.max() < F32_TOL, f"{key}: relative error per DOF {err}"
    # and it is not trivially the same computation
    assert np.any(f32["eta"] != f64["eta"])


def test_calm_water_equilibrium_stays_put():
    # at the free-floating equilibrium in calm water every force balances: the ship must not
    # move (1e-9 m, 1e-9 rad over 200 steps: the equilibrium solver's tolerance)
    ship = build_compiled_ship(ShipSetup(integrator="holloway"), None)
    start = ship.eta.copy()
    ship.advance(200)
    np.testing.assert_allclose(ship.eta, start, rtol=0, atol=1e-9)
    assert ship.t == pytest.approx(10.0)
    assert ship.n_steps == 200


def test_advance_in_pieces_equals_one_call():
    setup = ShipSetup(integrator="holloway")
    field = _field(1)
    a = build_compiled_ship(setup, field)
    b = build_compiled_ship(setup, field)
    a.advance(50)
    for n in (1, 2, 7, 40):
        b.advance(n)
    np.testing.assert_array_equal(a.eta, b.eta)
    np.testing.assert_array_equal(a.nu, b.nu)
    np.testing.assert_array_equal(a.z, b.z)


def test_divergence_raises_and_keeps_the_last_state():
    setup = ShipSetup(integrator="holloway")
    ship = build_compiled_ship(setup, _field())
    ship.max_abs_velocity = 1e-3  # the waves push the ship faster than this within a few s
    with pytest.raises(SimulationDiverged, match="diverged"):
        ship.advance(400)
    assert np.all(np.abs(ship.nu) <= 1e-3)
    assert 0 < ship.n_steps < 400
    assert ship.t == pytest.approx(ship.n_steps * ship.dt)


def test_bad_input_is_rejected():
    setup = ShipSetup(integrator="holloway")
    ship = build_compiled_ship(setup, None)
    with pytest.raises(ValueError, match="n_steps"):
        ship.advance(-1)
    with pytest.raises(ValueError, match=r"eta must have shape \(6,\)"):
        ship.reset(eta=np.zeros(5))
    with pytest.raises(ValueError, match="precision"):
        build_compiled_ship(setup, None, precision="half")
    with pytest.raises(NotImplementedError, match=r"'radiation' \(PerShipForceModel\) has no"):
        build_compiled_ship(ShipSetup(integrator="holloway", radiation="convolution"), None)


@pytest.mark.parametrize("speed", [0.0, 7.5])
def test_compiled_diffraction_refresh_equals_the_models_look_up(speed):
    # the refresh inside the compiled loop (no return to Python) against
    # Diffraction.heading_expansion, at headings all around the circle and at forward speed
    # (encounter frequencies, some beyond the table: zero, some negative: conjugated)
    from ship_gym.engine.batch import BatchDiffraction
    from ship_gym.engine.compiled import refresh_diffraction_cache
    from ship_gym.forces.diffraction import diffraction_row

    ship = build_compiled_ship(ShipSetup(integrator="holloway", speed=speed), _field())
    batch_model = next(f for f in ship.sim.forces if isinstance(f, BatchDiffraction))
    model = batch_model.template
    w = ship.wave_field
    n_c = w.n_components
    assert ship.backend.record_of(diffraction_row) is not None  # diffraction runs compiled
    table, beta, omega_db = batch_model.lookup
    tables = (
        table, beta, omega_db, np.ascontiguousarray(w.direction), np.ascontiguousarray(w.omega),
        np.ascontiguousarray(w.wavenumber), model.frequency == "encounter", model.kirchhoff,
        *model.complex_mass, model.heading_step, False, np.zeros((3, n_c, 8), dtype=complex),
        np.zeros(1, dtype=np.int64),
    )  # fmt: skip
    for psi in np.radians([0.0, 37.0, 90.0, 179.9, 180.0, 251.0, -33.0, 719.0]):
        xd = np.zeros((n_c, 8), dtype=complex)
        dxd = np.zeros((n_c, 8), dtype=complex)
        ref = np.array([np.nan, np.nan])
        assert refresh_diffraction_cache(psi, speed, tables, xd, dxd, ref)
        x, dx, _, _ = model.heading_expansion(w.direction, w.omega, w.wavenumber, psi, speed)
        # the same arithmetic; np.cos (numpy's SIMD loop) and math.cos may differ by an ulp
        np.testing.assert_allclose(xd, x, rtol=1e-13, atol=1e-13 * np.abs(x).max())
        np.testing.assert_allclose(dxd, dx, rtol=1e-9, atol=1e-9 * np.abs(dx).max())
        np.testing.assert_array_equal(ref, [psi, speed])


def test_turning_ship_refreshes_in_the_compiled_loop():
    # a beam-sea ship turned by the waves leaves the 0.5° band many times: every refresh is done
    # inside the one compiled call (no return to Python), and the run equals BatchSimulator's
    setup = ShipSetup(integrator="holloway")
    field = _field(beta=np.radians(100.0))
    ship = build_compiled_ship(setup, field, wave_heading=np.radians(100.0))
    batch = build_batch_simulator(setup, [field], wave_heading=np.radians(100.0), backend="numpy")
    mine, theirs = ship.run(400, record_every=400), batch.run(400)
    assert ship.n_refreshes > 3
    err = _rel_err(np.stack([mine["eta"][0], mine["eta"][-1]]), theirs["eta"][[0, -1], 0])
    assert err.max() < REL_TOL


def test_diffraction_above_range_raise_runs_on_the_numpy_path():
    # above_range="raise" cannot raise inside numba: the engine leaves such a model to its
    # numpy path, where the model raises with its message and the state stays as it was
    from ship_gym.engine.batch import BatchSimulator, batch_force_models
    from ship_gym.engine.ship import build_force_models, database_of, ship_of
    from ship_gym.forces.diffraction import Diffraction

    setup = ShipSetup(integrator="holloway", speed=12.0)
    field = _field(beta=np.pi)  # head seas at 12 m/s: encounter frequencies beyond the table
    hull, database = ship_of(setup).hull, database_of(setup)
    built = build_force_models(setup, hull, database, field, None, np.pi)
    models = [
        Diffraction(database, field, above_range="raise") if isinstance(m, Diffraction) else m
        for m in (built[0] if isinstance(built, tuple) else built)
    ]
    sim = BatchSimulator(hull, batch_force_models(models), [field], forward_speed=12.0)
    assert not sim.compiled
    eta = sim.eta.copy()
    with pytest.raises(ValueError, match="above_range='raise'"):
        sim.advance(3)
    np.testing.assert_array_equal(sim.eta, eta)
    with pytest.raises(NotImplementedError, match="above_range='raise'"):
        BatchSimulator(
            hull, batch_force_models(models), [field], forward_speed=12.0, backend="compiled"
        ).advance(1)
