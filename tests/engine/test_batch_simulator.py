"""BatchSimulator of N ships against N one-ship runs (same setup, same seas), and its row
models against the single-ship force models they are built from.

A ship of a batch must follow the trajectory it has alone (a :class:`Simulator`: the engine with
one ship) to rounding, whatever the other ships do; the row force models must equal the
single-ship :class:`ForceModel` implementations evaluated at the same state.
"""

import numpy as np
import pytest

from ship_gym.engine.batch import (
    BatchSimulator,
    PerShipForceModel,
    build_batch_simulator,
)
from ship_gym.engine.ship import ShipSetup, build_simulator, wave_field_for
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.kinematics import rotation_matrix
from ship_gym.waves.sea_state import IrregularSea

# short ramp so that the waves are fully up within the few hundred steps compared
SEA = IrregularSea(hs=5.0, tp=11.0, n_components=50, ramp_time=5.0)
SEA_SMALL = IrregularSea(hs=3.0, tp=9.0, n_components=30, ramp_time=5.0)
REL_TOL = 1e-9


def _ships(setup):
    """Three single-ship simulators: head seas, oblique short sea turning, calm and heeled."""
    specs = [
        (SEA, np.pi, 1, 0.05, 0.0),
        (SEA_SMALL, 2.5, 2, -0.1, 0.01),  # yaw rate: the diffraction cache must refresh
        (None, np.pi, 3, 0.2, 0.0),
    ]
    sims = []
    for sea, beta, seed, heel, yaw_rate in specs:
        sim = build_simulator(setup, sea, wave_heading=beta, rng=np.random.default_rng(seed))
        eta = sim.eta.copy()
        eta[3] = heel
        nu = sim.nu.copy()
        nu[5] = yaw_rate
        sim.reset(eta=eta, nu=nu)
        sims.append(sim)
    return sims


def _batch_like(setup, sims, **kwargs) -> BatchSimulator:
    batch = build_batch_simulator(setup, [s.wave_field for s in sims], **kwargs)
    batch.reset(eta=np.array([s.eta for s in sims]), nu=np.array([s.nu for s in sims]))
    return batch


def _assert_close(batch_series, single_series, what):
    # per DOF, relative to the largest magnitude that DOF reached (floor: 1e-6 of the largest
    # of all DOF, for the DOF that stay ≈ 0)
    scale = np.abs(single_series).max(axis=0)
    scale = np.maximum(scale, 1e-6 * scale.max())
    err = np.abs(batch_series - single_series).max(axis=0) / scale
    assert err.max() < REL_TOL, f"{what}: relative error per DOF {err}"


@pytest.mark.parametrize(
    ("integrator", "n_steps", "free"),
    [
        ("rk4", 160, (True,) * 6),
        ("holloway", 320, (True,) * 6),
        ("rk4", 60, (False, False, True, True, True, False)),  # surge, sway, yaw held
    ],
)
def test_batch_matches_independent_simulators(integrator, n_steps, free):
    setup = ShipSetup(integrator=integrator, speed=4.0, free_dofs=free)
    sims = _ships(setup)
    batch = _batch_like(setup, sims)
    assert batch.n_components == 50  # padded: 50, 30 and 0 (calm) components
    single = np.empty((n_steps, len(sims), 2, 6))
    batched = np.empty_like(single)
    for k in range(n_steps):
        batch.step()
        for i, s in enumerate(sims):
            s.step()
            single[k, i] = s.eta, s.nu
        batched[k, :, 0], batched[k, :, 1] = batch.eta, batch.nu
    assert not batch.diverged.any()
    np.testing.assert_allclose(batch.t, [s.t for s in sims], rtol=0, atol=1e-12)
    for i, s in enumerate(sims):
        _assert_close(batched[:, i, 0], single[:, i, 0], f"ship {i} eta")
        _assert_close(batched[:, i, 1], single[:, i, 1], f"ship {i} nu")
        z_scale = max(np.abs(s.z).max(), 1e-30)
        assert np.abs(batch.z[i] - s.z).max() < REL_TOL * z_scale
    if all(free):
        # the turning ship moved by more than the diffraction cache tolerance (0.5°)
        assert np.degrees(np.ptp(single[:, 1, 0, 5])) > 1.0
        # the seas did move the ships (not a trivial agreement)
        assert np.abs(single[:, 0, 0, 2] - single[0, 0, 0, 2]).max() > 0.1


def test_force_breakdown_matches_single_models():
    setup = ShipSetup(speed=4.0)
    sims = _ships(setup)
    for s in sims:  # ramp fully up, the ships off equilibrium
        for _ in range(3):
            s.step()
    batch = _batch_like(setup, sims)
    batch.t[:] = [s.t for s in sims]
    batch.z[:] = [s.z for s in sims]
    got = batch.force_breakdown()
    for i, s in enumerate(sims):
        # the single-ship models themselves (ForceModel.evaluate), at the ship's state; the
        # batch starts with fresh diffraction caches: so does the single model
        eta, nu, z = s.eta, s.nu, s.z
        ctx = ForceContext(
            t=s.t, eta=eta, nu=nu, rotation=rotation_matrix(*eta[3:]),
            forward_speed=s.forward_speed,
            wave_phasor=None if s.wave_field is None else s.wave_field.phasor(s.t),
        )  # fmt: skip
        ref, start = {}, 0
        for f in s.forces:
            if f.name == "diffraction":
                f.reset(s.t, ctx)
            ref[f.name], _ = f.evaluate(ctx, z[start : start + f.n_states])
            start += f.n_states
        for name in ("froude_krylov_hydrostatic", "radiation", "viscous_roll"):
            np.testing.assert_allclose(got[name][i], ref[name], rtol=1e-12, atol=1e-9)
        if "diffraction" in ref:
            np.testing.assert_allclose(got["diffraction"][i], ref["diffraction"], rtol=1e-12)
            assert np.abs(ref["diffraction"]).max() > 1e3
        else:  # calm water: no diffraction model in the single simulator, zero in the batch
            assert np.all(got["diffraction"][i] == 0.0)


def test_reset_subset_leaves_others_untouched():
    # Holloway keeps a per-ship history: ship 1 restarts its RK4 start-up while ships 0 and 2
    # go on with μ-Taylor steps.
    setup = ShipSetup(integrator="holloway", speed=4.0)
    sims = _ships(setup)
    batch = _batch_like(setup, sims)
    for _ in range(60):
        batch.step()
        for s in sims:
            s.step()
    new_field = wave_field_for(SEA_SMALL, 3.0, np.random.default_rng(7))
    fresh = build_simulator(setup, SEA_SMALL, wave_heading=3.0, rng=np.random.default_rng(7))
    eta = fresh.eta.copy()
    eta[3] = 0.15
    fresh.reset(eta=eta)
    before = batch.eta[[0, 2]].copy()
    batch.reset([1], eta=eta, wave_fields=[new_field])
    np.testing.assert_array_equal(batch.eta[[0, 2]], before)
    assert batch.t[1] == 0.0 and batch.n_steps[1] == 0 and np.all(batch.z[1] == 0.0)
    for _ in range(100):
        batch.step()
        fresh.step()
        sims[0].step()
        sims[2].step()
    for i, s in ((0, sims[0]), (1, fresh), (2, sims[2])):
        assert batch.t[i] == pytest.approx(s.t, abs=1e-12)
        scale = np.maximum(np.abs(s.eta), 1e-3)
        np.testing.assert_array_less(np.abs(batch.eta[i] - s.eta) / scale, REL_TOL)
        np.testing.assert_array_less(np.abs(batch.nu[i] - s.nu), REL_TOL * np.abs(s.nu).max())


def test_control_models_run_per_ship_with_array_commands():
    # The per-ship reference path (control="per_ship"): manoeuvring and a commanded rudder (a
    # servo state per ship) wrapped one copy per ship in PerShipForceModel; each ship gets its
    # own command.

    setup = ShipSetup(speed=5.0, manoeuvring=True, rudder="command", integrator="holloway")
    sims = [
        build_simulator(setup, SEA_SMALL, wave_heading=b, rng=np.random.default_rng(i))
        for i, b in enumerate((2.3, 1.2))
    ]
    batch = _batch_like(setup, sims, control="per_ship")
    assert isinstance(batch.forces[-1], PerShipForceModel)
    # servos are sampled actuator states, not ODE states: only the radiation memory integrates
    assert batch.n_states == sims[0].n_states == sims[0].forces[1].n_states
    command = np.array([0.1, -0.05])  # rudder angles [rad]
    for _ in range(80):
        batch.step({"rudder_command": command})
        for i, s in enumerate(sims):
            s.step({"rudder_command": float(command[i])})
    for i, s in enumerate(sims):
        scale = np.maximum(np.abs(s.eta), 1e-3)
        np.testing.assert_array_less(np.abs(batch.eta[i] - s.eta) / scale, REL_TOL)
        np.testing.assert_array_less(np.abs(batch.nu[i] - s.nu), REL_TOL * np.abs(s.nu).max())
    # the rudders turned the ships opposite ways
    assert batch.nu[0, 5] * batch.nu[1, 5] < 0.0


class _Kick(ForceModel):
    """A roll moment from a per-ship command (an absurd one makes that ship diverge)."""

    name = "kick"

    def evaluate(self, ctx: ForceContext, states):
        moment = float(ctx.commands.get("kick", 0.0)) * 1e15 * (1.0 + abs(ctx.nu[3]))
        return np.array([0.0, 0.0, 0.0, moment, 0.0, 0.0]), np.zeros(0)


def test_divergence_is_per_ship_and_commands_reach_models():
    setup = ShipSetup(integrator="rk4", diffraction=False)
    n = 3

    def make():
        kick = PerShipForceModel([_Kick() for _ in range(n)])
        return build_batch_simulator(setup, [None] * n, extra_forces=[kick])

    batch, calm = make(), make()
    for b in (batch, calm):
        b.reset(eta=b.initial_eta + np.array([0, 0, 0, 0.1, 0, 0]))
    start = batch.eta.copy()
    newly = batch.step({"kick": np.array([0.0, 1.0, 0.0])})
    calm.step({"kick": np.zeros(n)})
    np.testing.assert_array_equal(newly, [False, True, False])
    np.testing.assert_array_equal(batch.diverged, [False, True, False])
    assert "ship 1 diverged" in batch.divergence_messages[1]
    np.testing.assert_array_equal(batch.eta[1], start[1])  # kept the start of the failed step
    assert batch.t[1] == 0.0 and batch.t[0] == pytest.approx(setup.dt)
    np.testing.assert_allclose(batch.eta[[0, 2]], calm.eta[[0, 2]], rtol=1e-13)
    for _ in range(5):  # the others go on, the diverged ship stays frozen
        assert not batch.step().any()
        calm.step()
    np.testing.assert_array_equal(batch.eta[1], start[1])
    np.testing.assert_allclose(batch.eta[[0, 2]], calm.eta[[0, 2]], rtol=1e-13)
    batch.reset([1])  # autoreset
    assert not batch.diverged.any() and 1 not in batch.divergence_messages
    assert not batch.step({"kick": np.zeros(n)}).any()
    assert batch.t[1] == pytest.approx(setup.dt)


def test_unsupported_setups_and_bad_resets_raise():
    field = wave_field_for(SEA_SMALL, np.pi, np.random.default_rng(0))
    conv = build_batch_simulator(ShipSetup(radiation="convolution"), [field, None])
    assert not conv.compiled  # the Cummins convolution runs per ship on the numpy path
    assert isinstance(next(f for f in conv.forces if f.name == "radiation"), PerShipForceModel)
    with pytest.raises(ValueError, match="integrator must be 'rk4' or 'holloway'"):
        ShipSetup(integrator="abm")
    batch = build_batch_simulator(ShipSetup(), [field, None])
    big = wave_field_for(SEA, np.pi, np.random.default_rng(1))
    with pytest.raises(ValueError, match="max_components"):
        batch.reset([0], wave_fields=[big])
    with pytest.raises(ValueError, match="indices"):
        batch.reset([2])
    roomy = build_batch_simulator(ShipSetup(), [field, None], max_components=50)
    roomy.reset([1], wave_fields=[big])  # fits
    assert roomy.n_components == 50
