"""Roll stabilisation by fins in beam seas, and the speed a ship loses in head seas.

Fins: the classical stabiliser (:class:`ship_gym.control.stabilisers.FinController`, PD on roll
angle and rate sized to add ζ_add = 0.3 of critical roll damping and 0.2 C₄₄ of stiffness) must
take energy out of the roll — the fin roll moment K is anti-correlated with the roll rate p and
its mean power K·p is negative — and reduce the RMS roll of the S175 at 9 m/s in beam seas whose
spectral peak sits on the roll resonance.

Bound on the reduction (≥ 30 %): for a linear roll oscillator driven by a sea whose peak is at
its natural frequency, the response is dominated by the resonance and its RMS scales roughly as
ζ^{-1/2} (broad-band excitation) to ζ^{-1} (narrow-band); the passive S175 at speed has a total
roll damping of ≈ 0.05–0.1 of critical (radiation + Ikeda viscous + hull lift), so adding 0.3
lowers the RMS by 1 − √(0.1/0.4) = 50 % to 1 − 0.05/0.35 = 86 % for unsaturated fins; the added
stiffness detunes the resonance too (helps). Fin saturation and rate limits, the nonlinear
Froude–Krylov roll moment and the sway–roll coupling eat into this, hence the margin: ≥ 30 %.
The script ``scripts/roll_stabilisation.py`` reports the full-length numbers.

Speed loss: in head seas at a fixed shaft speed the ship with
:class:`ship_gym.forces.added_resistance.AddedResistance` must slow down more than without it,
to the speed where thrust balances calm-water resistance, the SNNM mean added resistance and the
mean wave force the simulator's nonlinear Froude–Krylov model already produces.
"""

import dataclasses
import os

import numpy as np
import pytest
from scipy.optimize import brentq

from ship_gym.control.stabilisers import FinController, control_derivative, fin_law
from ship_gym.engine.ship import ShipSetup, build_simulator
from ship_gym.forces.added_resistance import AddedResistance
from ship_gym.forces.base import ForceContext
from ship_gym.forces.fins import RollFins
from ship_gym.hydro import load_database
from ship_gym.hydro.rao import natural_frequency
from ship_gym.kinematics import rotation_matrix
from ship_gym.waves.sea_state import IrregularSea

ROLL_SPEED = 9.0


@pytest.fixture(scope="module")
def database():
    return load_database("s175")


def _build(setup, sea, beta, seed, *, added_resistance=False):
    """The simulator of ``build_simulator`` with, optionally, the full SNNM added resistance
    (``added_resistance="total"``), and that model (or None)."""
    setup = dataclasses.replace(setup, added_resistance="total" if added_resistance else "none")
    sim = build_simulator(setup, sea, wave_heading=beta, rng=np.random.default_rng(seed))
    raw = next((f for f in sim.forces if isinstance(f, AddedResistance)), None)
    return sim, raw


def _roll_run(fins, sea, duration, seed=2024, dt=0.1):
    """Beam-sea run with course keeping; roll angle, roll rate and the fin roll moment."""
    setup = ShipSetup(
        speed=ROLL_SPEED, dt=dt, propulsion=True, manoeuvring=True, rudder="autopilot", fins=fins
    )
    sim, _ = _build(setup, sea, np.pi / 2, seed)
    n = round(duration / dt)
    t, phi, p, moment = (np.zeros(n) for _ in range(4))
    fin = None
    if fins != "none":
        names = [f.name for f in sim.forces]
        fin = sim.forces[names.index("roll_fins")]
    for i in range(n):
        sim.step()
        t[i], phi[i], p[i] = sim.t, sim.eta[3], sim.nu[3]
        if fin is not None:
            ctx = ForceContext(
                t=sim.t,
                eta=sim.eta,
                nu=sim.nu,
                rotation=rotation_matrix(*sim.eta[3:]),
                forward_speed=sim.forward_speed,
                commands={"fins": fin.angle},
            )
            moment[i] = fin.model.evaluate(ctx, np.zeros(0))[0][3]
    return t, phi, p, moment


def test_fin_controller_commands_a_moment_against_the_roll_rate():
    # static check of the sign chain: p > 0 (rolling to starboard) → δ_c < 0 → K < 0
    fins = RollFins()
    k_delta = control_derivative(fins, "fins", 3, ROLL_SPEED)
    assert k_delta > 0.0  # positive command, positive (starboard-down) moment
    controller = FinController.tuned(k_delta, c44=2.4e8, i44_total=2.0e9)
    assert controller.k_roll > 0.0 and controller.k_rate > 0.0
    for phi, p in ((0.0, 0.02), (0.05, 0.0), (-0.03, -0.01)):
        ctx = ForceContext(
            t=0.0,
            eta=np.array([0, 0, 0, phi, 0, 0.0]),
            nu=np.array([ROLL_SPEED, 0, 0, p, 0, 0.0]),
            rotation=rotation_matrix(phi, 0.0, 0.0),
            forward_speed=ROLL_SPEED,
        )
        delta, _ = fin_law(controller.gains(), ctx.eta, ctx.nu, 0.0, np.radians(25.0))
        assert np.sign(delta) == -np.sign(phi if phi else p)
        ctx.commands["fins"] = delta
        # moment from the commanded angle (the roll rate's own lift adds damping too)
        k = fins.evaluate(ctx, np.zeros(0))[0][3]
        assert k * (phi if phi else p) < 0.0


def test_fins_oppose_roll_in_beam_seas(database):
    # short 6-DOF run (90 s, 10 s ramp): the applied fin moment opposes the roll rate
    omega_roll = natural_frequency(database, "Roll")
    sea = IrregularSea(hs=3.5, tp=2 * np.pi / omega_roll, n_components=30, ramp_time=10.0)
    t, phi, p, moment = _roll_run("controller", sea, 90.0)
    keep = t >= 20.0
    assert np.degrees(np.abs(phi[keep]).max()) > 0.3  # the sea does roll the ship
    assert np.mean(moment[keep] * p[keep]) < 0.0  # energy taken out of the roll
    assert np.corrcoef(moment[keep], p[keep])[0, 1] < -0.5


@pytest.mark.slow
def test_fins_reduce_rms_roll_at_resonance_in_beam_seas(database):
    omega_roll = natural_frequency(database, "Roll")
    sea = IrregularSea(hs=3.5, tp=2 * np.pi / omega_roll, n_components=100)
    duration, transient = 900.0, 150.0
    runs = {fins: _roll_run(fins, sea, duration) for fins in ("none", "controller")}
    keep = runs["none"][0] >= transient

    def rms(phi):
        x = phi[keep]
        return float(np.sqrt(np.mean((x - x.mean()) ** 2)))

    passive, active = rms(runs["none"][1]), rms(runs["controller"][1])
    assert np.degrees(passive) > 1.0  # a real resonant roll to reduce
    reduction = 1.0 - active / passive
    assert reduction >= 0.30, f"RMS roll {np.degrees(passive):.2f}° → {np.degrees(active):.2f}°"


@pytest.mark.slow
def test_speed_drops_in_head_seas_with_added_resistance():
    """Fixed shaft speed (self-propulsion for 10 m/s), head seas Hs 4.5 m, Tp 11 s: the mean
    speed with AddedResistance is lower than without, and where the quasi-steady surge balance
    (1 − t)T(n, U) − R_T(U) − R̄_AW(U) − F_w = 0 puts it, F_w being the mean wave force of the
    run without the model (its thrust–resistance surplus at its own mean speed)."""
    setup = ShipSetup(speed=10.0, dt=0.1, propulsion=True, manoeuvring=True, rudder="autopilot")
    sea = IrregularSea(hs=4.5, tp=11.0, n_components=60)
    duration, settle = 500.0, 250.0
    mean_u = {}
    for with_raw in (False, True):
        sim, raw = _build(setup, sea, np.pi, 7, added_resistance=with_raw)
        us = []
        for _ in range(round(duration / setup.dt)):
            sim.step()
            if sim.t >= settle:
                us.append(sim.nu[0])
        mean_u[with_raw] = float(np.mean(us))
        if with_raw:
            prop = next(f for f in sim.forces if f.name == "propeller")
            res = next(f for f in sim.forces if f.name == "resistance")
            model, n = raw, sim.commands["shaft_speed"]
    u_w, u_raw = mean_u[False], mean_u[True]
    assert u_w < 10.0 and u_raw < u_w - 0.3  # the model costs well over 0.3 m/s here
    f_w = prop._net_force(n, u_w, res)  # mean wave force balanced by the surplus at u_w
    assert f_w > 0.0

    def balance(u):
        return prop._net_force(n, u, res) - model.resistance_at(0.0, u) - f_w

    u_pred = brentq(balance, 2.0, 12.0, xtol=1e-10)
    assert u_raw == pytest.approx(u_pred, rel=0.03)
    if os.environ.get("SHIP_GYM_VERBOSE"):
        print(f"u without R_AW {u_w:.3f}, with {u_raw:.3f}, predicted {u_pred:.3f} m/s")
