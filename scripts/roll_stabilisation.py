#!/usr/bin/env python
"""S175 roll stabilisation in beam seas and speed loss in head seas (resistance/thrust balance).

Part 1 — roll stabilisation sanity
----------------------------------
The S175 at U = 9 m/s (Fn = 0.22) in long-crested beam seas (β = 90°, waves travelling to
starboard), JONSWAP Hs = 3.5 m, γ = 3.3, Tp = the roll natural period T_φ = 2π/ω_φ = 17.9 s of the
database (``natural_frequency(db, "Roll")``): the peak of the sea sits on the roll resonance.
Propulsion (Holtrop–Mennen resistance + B-series propeller at the self-propulsion shaft speed),
hull manoeuvring forces and the PID heading autopilot are on, so sway and yaw are free and the
autopilot holds the course: holding sway/yaw instead would suppress the sway–roll coupling of a
beam sea and the drift the fins' lift would really see. Two runs on the same sea (same seed):

* passive: ``fins="none"`` (no fins at all);
* stabilised: ``fins="controller"`` — the classical PD stabiliser of
  :class:`ship_gym.control.stabilisers.FinController` (ζ_add = 0.3 of critical roll damping,
  c_add = 0.2 of C₄₄) behind the fin servo (±25°, 15 °/s, 0.1 s lag).

Reported: RMS roll of both runs and the reduction 1 − φ_rms,fins/φ_rms,passive, the fin angle
RMS, the fraction of time the applied angle sits at its ±25° limit and the fraction of time the
command exceeds it, the fraction of time the servo is rate limited, the mean of K_fin·p (the fins
must take energy out of the roll: < 0), heading and speed statistics. Statistics over
t ≥ ``--transient`` (after the 50 s wave ramp).

Part 2 — speed trial in head seas
---------------------------------
The S175 with the shaft speed fixed at the calm-water self-propulsion point for 10 m/s
(Fn = 0.24), autopilot on, in three runs: calm water; long-crested head seas (β = 180°) JONSWAP
Hs = 4.5 m, Tp = 11 s (λ_p/L = 1.08, near the added-resistance peak), 60 components, with the
simulator's wave models only; the same sea with
:class:`ship_gym.forces.added_resistance.AddedResistance` (SNNM, Liu & Papanikolaou 2020 /
ITTC 2021) appended to the force list. Reported: the mean speeds over t ≥ ``--settle`` and the
speed loss vs the calm run, the mean surge-force balance (propeller, calm-water resistance,
rudder, added resistance, the wave models together, and the closure residual), and two
quasi-steady predictions: U* where (1 − t) T(n, U*) = R_T(U*) + R̄_AW(U*) (SNNM alone, R̄_AW of
the same wave realisation), and the same with the mean resisting force the wave models produced
in the run without the SNNM model added (what the simulation with both should reach).

Part 3 — the simulator's own added resistance (regular head waves)
------------------------------------------------------------------
Linear radiation and diffraction give no mean force, but the nonlinear Froude–Krylov force on the
instantaneous wetted hull, with the heave and pitch motions, does: σ_AW of the simulator's wave
models (surge held at 10 m/s, heave and pitch free, ζ_a = 1 m; the mean body-x force over whole
encounter periods minus its calm-water value) against the SNNM curve. With the forward-speed
linearisation it stays below SNNM at every λ/L (8.8 against 9.6 at its peak, λ/L ≈ 1.15) and
vanishes in short waves (no reflection without the diffraction pressure in the quadratic
terms), so adding the SNNM total on top counts most of the motion part twice (see the report).

Wave groups: the ship's speed follows the local wave energy (surge time constant ≈ 100 s), so
means over a few hundred seconds scatter by several per cent between windows; the default runs
are 2400 s long.

The simulator is built from :func:`ship_gym.engine.ship.build_force_models` plus the model
(ShipSetup has no switch for it yet).

Usage::

    python scripts/roll_stabilisation.py [--json PATH] [--figure PATH]
                                         [--part all|roll|speed|rao] [--quick]

``--json`` keys: ``rms_roll_passive_deg``, ``rms_roll_fins_deg``, ``reduction_percent``,
``fin_angle_rms_deg``, ``fin_saturation_fraction``, ``speed_loss_percent`` (simulated, with the
SNNM model), ``quasi_steady_speed_loss_percent`` (SNNM alone), ``regular_wave_sigma_aw``, …
"""

from __future__ import annotations

import dataclasses
import os

for _var in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
from scipy.optimize import brentq  # noqa: E402
from scipy.signal import welch  # noqa: E402

from ship_gym.control.actuators import FIN_SERVO  # noqa: E402
from ship_gym.control.stabilisers import fin_law  # noqa: E402
from ship_gym.engine.ship import (  # noqa: E402
    ShipSetup,
    build_simulator,
)
from ship_gym.engine.simulator import Simulator  # noqa: E402
from ship_gym.forces.added_resistance import AddedResistance  # noqa: E402
from ship_gym.forces.base import ForceContext  # noqa: E402
from ship_gym.hull import load_hull  # noqa: E402
from ship_gym.hydro import load_database  # noqa: E402
from ship_gym.hydro.rao import natural_frequency  # noqa: E402
from ship_gym.kinematics import rotation_matrix  # noqa: E402
from ship_gym.waves.sea_state import IrregularSea  # noqa: E402

ROLL_SPEED = 9.0
ROLL_HS = 3.5
ROLL_SEED = 2024
TRIAL_SPEED = 10.0
TRIAL_HS, TRIAL_TP = 4.5, 11.0
TRIAL_SEED = 7
DT = 0.1


def build(
    setup: ShipSetup,
    sea: IrregularSea | None,
    beta: float,
    seed: int,
    *,
    added_resistance: bool = False,
) -> tuple[Simulator, AddedResistance | None]:
    """The simulator of ``build_simulator`` with, optionally, the full SNNM added resistance
    (``added_resistance="total"``), and that model (or None)."""
    setup = dataclasses.replace(setup, added_resistance="total" if added_resistance else "none")
    sim = build_simulator(setup, sea, wave_heading=beta, rng=np.random.default_rng(seed))
    raw = next((f for f in sim.forces if isinstance(f, AddedResistance)), None)
    return sim, raw


# ---------------------------------------------------------------------------------- part 1
def roll_run(fins: str, duration: float, sea: IrregularSea) -> dict:
    """One beam-sea run; time series and fin quantities."""
    setup = ShipSetup(
        speed=ROLL_SPEED,
        dt=DT,
        propulsion=True,
        manoeuvring=True,
        rudder="autopilot",
        fins=fins,
    )
    sim, _ = build(setup, sea, np.pi / 2, ROLL_SEED)
    n = round(duration / sim.dt)
    # the single-ship model in sim.forces gives the parameters (controller gains, the fins'
    # lift); its servo and controller states are not stepped: those live in the engine
    fin = None
    if fins != "none":
        fin = next(f for f in sim.forces if f.name == "roll_fins")
    t = np.empty(n + 1)
    eta = np.empty((n + 1, 6))
    nu = np.empty((n + 1, 6))
    delta = np.zeros(n + 1)
    command = np.zeros(n + 1)
    moment = np.zeros(n + 1)
    rate_limited = np.zeros(n + 1, bool)
    t0 = time.perf_counter()
    for i in range(n + 1):
        if i:
            sim.step()
        t[i], eta[i], nu[i] = sim.t, sim.eta, sim.nu
        if fin is not None:
            angle = sim.actuator_angle("roll_fins")
            integral = float(sim.engine.actuator_model("roll_fins").states.integral[0])
            applied = float(FIN_SERVO.applied(angle))
            ctx = ForceContext(
                t=sim.t,
                eta=sim.eta,
                nu=sim.nu,
                rotation=rotation_matrix(*sim.eta[3:]),
                forward_speed=sim.forward_speed,
                commands={"fins": applied},
            )
            command[i], _ = fin_law(fin.gains, sim.eta, sim.nu, integral, FIN_SERVO.max_angle)
            delta[i] = applied
            moment[i] = fin.model.evaluate(ctx, np.zeros(0))[0][3]
            target = float(FIN_SERVO.applied(command[i]))
            rate_limited[i] = abs(target - angle) > FIN_SERVO.max_rate * FIN_SERVO.lag
    wall = time.perf_counter() - t0
    return {
        "t": t,
        "eta": eta,
        "nu": nu,
        "delta": delta,
        "command": command,
        "moment": moment,
        "rate_limited": rate_limited,
        "wall_s": wall,
    }


def roll_statistics(passive: dict, fins: dict, transient: float) -> dict:
    """RMS roll, reduction, fin usage over t ≥ transient."""
    keep = passive["t"] >= transient
    phi_p = np.degrees(passive["eta"][keep, 3])
    phi_f = np.degrees(fins["eta"][keep, 3])
    rms_p = float(np.sqrt(np.mean((phi_p - phi_p.mean()) ** 2)))
    rms_f = float(np.sqrt(np.mean((phi_f - phi_f.mean()) ** 2)))
    limit = FIN_SERVO.max_angle
    delta = fins["delta"][keep]
    p = fins["nu"][keep, 3]
    k = fins["moment"][keep]
    psi_f = np.degrees(fins["eta"][keep, 5])
    psi_p = np.degrees(passive["eta"][keep, 5])
    return {
        "rms_roll_passive_deg": rms_p,
        "rms_roll_fins_deg": rms_f,
        "reduction_percent": 100.0 * (1.0 - rms_f / rms_p),
        "max_roll_passive_deg": float(np.abs(phi_p).max()),
        "max_roll_fins_deg": float(np.abs(phi_f).max()),
        "fin_angle_rms_deg": float(np.degrees(np.sqrt(np.mean(delta**2)))),
        "fin_saturation_fraction": float(np.mean(np.abs(delta) >= 0.999 * limit)),
        "fin_command_beyond_limit_fraction": float(np.mean(np.abs(fins["command"][keep]) > limit)),
        "fin_rate_limited_fraction": float(np.mean(fins["rate_limited"][keep])),
        "fin_power_mean_MW": float(np.mean(k * p) / 1e6),
        "fin_moment_rate_correlation": float(np.corrcoef(k, p)[0, 1]),
        "heading_rms_passive_deg": float(np.sqrt(np.mean(psi_p**2))),
        "heading_rms_fins_deg": float(np.sqrt(np.mean(psi_f**2))),
        "mean_speed_passive_m_s": float(passive["nu"][keep, 0].mean()),
        "mean_speed_fins_m_s": float(fins["nu"][keep, 0].mean()),
    }


# ---------------------------------------------------------------------------------- part 2
def trial_run(
    sea: IrregularSea | None, duration: float, settle: float, *, added_resistance: bool
) -> dict:
    """One head-sea (or calm) run at the calm-water self-propulsion shaft speed for 10 m/s.

    The surge components of every force model are averaged over t ≥ ``settle`` at every step
    (sampling them more sparsely aliases the short encounter periods into the mean).
    """
    setup = ShipSetup(
        speed=TRIAL_SPEED, dt=DT, propulsion=True, manoeuvring=True, rudder="autopilot"
    )
    sim, raw = build(setup, sea, np.pi, TRIAL_SEED, added_resistance=added_resistance)
    n = round(duration / sim.dt)
    t, u = np.empty(n + 1), np.empty(n + 1)
    sums: dict[str, float] = {}
    count = 0
    t0 = time.perf_counter()
    for i in range(n + 1):
        if i:
            sim.step()
        t[i], u[i] = sim.t, sim.nu[0]
        if sim.t >= settle - 1e-9:
            for name, f in sim.force_breakdown().items():
                sums[name] = sums.get(name, 0.0) + float(f[0])
            count += 1
    wall = time.perf_counter() - t0
    keep = t >= settle - 1e-9
    mass = sim.mass_rb[0, 0] + sim.added_mass_lhs[0, 0]
    du_dt = float(np.polyfit(t[keep], u[keep], 1)[0]) if keep.sum() > 2 else 0.0
    return {
        "t": t,
        "u": u,
        "mean_surge_forces": {k: v / max(count, 1) for k, v in sums.items()},
        "mean_inertia_force": float(mass * du_dt),
        "shaft_speed": float(sim.commands["shaft_speed"]),
        "sim": sim,
        "raw": raw,
        "wall_s": wall,
    }


def trial_statistics(calm: dict, waves: dict, waves_raw: dict, settle: float) -> dict:
    """Mean speeds, speed loss, surge-force balance and the quasi-steady prediction."""

    def mean_u(run: dict) -> float:
        return float(run["u"][run["t"] >= settle].mean())

    u_calm, u_waves, u_raw = mean_u(calm), mean_u(waves), mean_u(waves_raw)
    sim = waves_raw["sim"]
    prop = next(f for f in sim.forces if f.name == "propeller")
    res = next(f for f in sim.forces if f.name == "resistance")
    raw: AddedResistance = waves_raw["raw"]
    n = waves_raw["shaft_speed"]

    def net(u: float, with_raw: bool) -> float:
        x = prop._net_force(n, u, res)
        return x - (raw.resistance_at(0.0, u) if with_raw else 0.0)

    u_star = brentq(net, 1.0, 15.0, args=(True,), xtol=1e-10)
    # the mean resisting force of everything else (the wave models' nonlinear Froude–Krylov
    # mean force, the rudder) in the run without R_AW: the thrust–resistance surplus at that
    # run's mean speed, assumed independent of the speed
    f_wave = prop._net_force(n, u_waves, res)
    u_star_fk = brentq(lambda u: net(u, True) - f_wave, 1.0, 15.0, xtol=1e-10)
    # the same with only the SNNM reflection part on top of the wave models' own mean force
    refl = AddedResistance(raw.particulars, raw.wave_field, components="reflection")
    u_star_refl = brentq(
        lambda u: net(u, False) - refl.resistance_at(0.0, u) - f_wave, 1.0, 15.0, xtol=1e-10
    )
    u_calm_star = brentq(net, 1.0, 15.0, args=(False,), xtol=1e-10)
    h = 1e-3
    slope = (net(u_calm_star + h, False) - net(u_calm_star - h, False)) / (2 * h)
    r_aw0 = raw.resistance_at(0.0, u_calm_star)
    wave_models = ("froude_krylov_hydrostatic", "radiation", "diffraction", "gravity", "coriolis")

    def balance(run: dict) -> dict:
        """Mean surge forces [kN]; the wave group (FK + hydrostatics + gravity + rigid-body
        Coriolis + radiation + diffraction) summed, and the closure residual."""
        f = run["mean_surge_forces"]
        out = {
            "propeller_kN": f["propeller"] / 1e3,
            "calm_resistance_kN": f["resistance"] / 1e3,
            "rudder_kN": f.get("rudder", 0.0) / 1e3,
            "added_resistance_kN": f.get("added_resistance", 0.0) / 1e3,
            "wave_models_kN": sum(f[k] for k in wave_models if k in f) / 1e3,
        }
        out["residual_minus_inertia_kN"] = (sum(f.values()) - run["mean_inertia_force"]) / 1e3
        return out

    return {
        "shaft_speed_rps": n,
        "mean_speed_calm_m_s": u_calm,
        "mean_speed_waves_no_raw_m_s": u_waves,
        "mean_speed_waves_m_s": u_raw,
        "speed_loss_percent": 100.0 * (1.0 - u_raw / u_calm),
        "speed_loss_no_raw_percent": 100.0 * (1.0 - u_waves / u_calm),
        "added_resistance_at_10_m_s_kN": r_aw0 / 1e3,
        "added_resistance_at_mean_speed_kN": raw.resistance_at(0.0, u_raw) / 1e3,
        "calm_resistance_at_10_m_s_kN": float(res.resistance(u_calm_star)) / 1e3,
        "calm_resistance_at_mean_speed_kN": float(res.resistance(u_raw)) / 1e3,
        "raw_over_rt_at_10_m_s": r_aw0 / float(res.resistance(u_calm_star)),
        "quasi_steady_speed_m_s": u_star,
        "quasi_steady_speed_loss_percent": 100.0 * (1.0 - u_star / u_calm_star),
        "linearised_speed_loss_percent": 100.0 * (r_aw0 / -slope) / u_calm_star,
        "mean_other_resisting_force_no_raw_kN": f_wave / 1e3,
        "quasi_steady_speed_with_fk_mean_m_s": u_star_fk,
        "quasi_steady_speed_loss_with_fk_mean_percent": 100.0 * (1.0 - u_star_fk / u_calm_star),
        "reflection_part_at_10_m_s_kN": refl.resistance_at(0.0, u_calm_star) / 1e3,
        "quasi_steady_speed_loss_fk_plus_reflection_percent": 100.0
        * (1.0 - u_star_refl / u_calm_star),
        "balance_calm": balance(calm),
        "balance_waves_without_raw": balance(waves),
        "balance_waves_with_raw": balance(waves_raw),
    }


# ---------------------------------------------------------------------------------- part 3
def regular_wave_added_resistance(lambdas: list[float], height: float = 2.0) -> dict:
    """σ_AW of the simulator's own wave models vs SNNM, regular head waves, U = 10 m/s.

    Surge (and sway, roll, yaw) held at the steady speed, heave and pitch free, no resistance or
    propeller: the mean of the total body-x force (all force models + gravity + rigid-body
    Coriolis) over whole encounter periods after 100 s, minus its calm-water value, is the
    mean added resistance of the nonlinear Froude–Krylov + linear radiation/diffraction model.
    """
    from ship_gym.engine.ship import build_simulator
    from ship_gym.forces.added_resistance import SNNMParticulars, added_resistance_coefficient
    from ship_gym.waves.sea_state import RegularWave

    hull = load_hull("s175")
    particulars = SNNMParticulars.from_hull(hull)
    u, dt = TRIAL_SPEED, 0.05
    norm = hull.rho * hull.g * particulars.beam**2 / particulars.length
    setup = ShipSetup(speed=u, dt=dt, free_dofs=(False, False, True, False, True, False))

    def mean_fx(sim: Simulator, duration: float) -> float:
        n = round(duration / dt)
        total = 0.0
        for _ in range(n):
            sim.step()
            total += sum(float(f[0]) for f in sim.force_breakdown().values())
        return total / n

    f_calm = mean_fx(build_simulator(setup, None), 10.0)
    out = {"lambda_over_L": [], "sigma_simulator": [], "sigma_snnm": []}
    for lam in lambdas:
        wave = RegularWave(height=height, wavelength=lam * particulars.length, ramp_time=30.0)
        sim = build_simulator(setup, wave, wave_heading=np.pi)
        sim.run(100.0)
        w = wave.omega
        t_e = 2 * np.pi / (w + w * w * u / hull.g)
        window = round(t_e * max(1, round(100.0 / t_e)) / dt) * dt
        f = mean_fx(sim, window)
        out["lambda_over_L"].append(lam)
        out["sigma_simulator"].append(-(f - f_calm) / (norm * wave.amplitude**2))
        out["sigma_snnm"].append(float(added_resistance_coefficient(w, np.pi, u, particulars)))
    return out


# ---------------------------------------------------------------------------------- output
def figure(
    path: Path,
    passive: dict | None,
    fins: dict | None,
    trials: dict | None,
    transient: float,
    rao: dict | None = None,
) -> None:
    """Roll time series and spectra (part 1), speed time series (part 2), σ_AW (part 3)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = (2 if passive is not None else 0) + (trials is not None) + (rao is not None)
    fig, axes = plt.subplots(rows, 1, figsize=(10, 3.2 * rows), squeeze=False)
    ax = list(axes[:, 0])
    if passive is not None and fins is not None:
        a0, a1 = ax.pop(0), ax.pop(0)
        a0.plot(passive["t"], np.degrees(passive["eta"][:, 3]), lw=0.8, label="passive")
        a0.plot(fins["t"], np.degrees(fins["eta"][:, 3]), lw=0.8, label="fin controller")
        a0.plot(fins["t"], np.degrees(fins["delta"]), lw=0.5, alpha=0.6, label="fin angle δ")
        a0.axvline(transient, color="k", lw=0.5, ls=":")
        a0.set(
            xlabel="t [s]",
            ylabel="roll φ, fin δ [deg]",
            title=f"S175 at {ROLL_SPEED} m/s, beam seas, JONSWAP Hs {ROLL_HS} m, Tp = T_φ",
        )
        a0.legend(loc="upper right", fontsize=8)
        keep = passive["t"] >= transient
        for run, label in ((passive, "passive"), (fins, "fin controller")):
            f, s = welch(
                np.degrees(run["eta"][keep, 3]), fs=1.0 / DT, nperseg=min(2048, int(keep.sum()))
            )
            a1.plot(2 * np.pi * f, s / (2 * np.pi), label=label)
        a1.set(xlim=(0, 1.0), xlabel="ω [rad/s]", ylabel="S_φ [deg² s/rad]", title="roll spectrum")
        a1.legend(fontsize=8)
    if trials is not None:
        a2 = ax.pop(0)
        for key, label in (
            ("calm", "calm water"),
            ("waves", "head seas, no R_AW model"),
            ("waves_raw", "head seas + SNNM R_AW"),
        ):
            a2.plot(trials[key]["t"], trials[key]["u"], label=label)
        a2.set(
            xlabel="t [s]",
            ylabel="u [m/s]",
            title=f"fixed shaft speed, head seas JONSWAP Hs {TRIAL_HS} m, Tp {TRIAL_TP} s",
        )
        a2.legend(fontsize=8)
    if rao is not None:
        a3 = ax.pop(0)
        a3.plot(
            rao["lambda_over_L"], rao["sigma_simulator"], "o-", label="simulator (nonlinear FK)"
        )
        a3.plot(rao["lambda_over_L"], rao["sigma_snnm"], "s-", label="SNNM (AddedResistance)")
        a3.set(
            xlabel="λ/L",
            ylabel="σ_AW = R_AW/(ρgζ²B²/L)",
            title=f"regular head waves, U = {TRIAL_SPEED} m/s (Fn 0.24), surge held",
        )
        a3.legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path, default=None, help="write the numbers to this file")
    parser.add_argument("--figure", type=Path, default=Path("out/roll_stabilisation.png"))
    parser.add_argument("--part", choices=("all", "roll", "speed", "rao"), default="all")
    parser.add_argument("--quick", action="store_true", help="short runs (smoke test)")
    parser.add_argument("--roll-duration", type=float, default=1500.0, help="[s]")
    parser.add_argument("--transient", type=float, default=200.0, help="[s]")
    parser.add_argument("--trial-duration", type=float, default=2400.0, help="[s]")
    parser.add_argument("--settle", type=float, default=300.0, help="[s]")
    args = parser.parse_args()
    if args.quick:
        args.roll_duration, args.transient = 300.0, 100.0
        args.trial_duration, args.settle = 300.0, 150.0
    out: dict = {"dt_s": DT}
    passive = fins = trials = rao = None
    started = time.perf_counter()
    if args.part in ("all", "roll"):
        omega_roll = natural_frequency(load_database("s175"), "Roll")
        sea = IrregularSea(hs=ROLL_HS, tp=2 * np.pi / omega_roll, n_components=100)
        print(
            f"roll: S175 {ROLL_SPEED} m/s, beam seas, JONSWAP Hs {ROLL_HS} m Tp "
            f"{sea.tp:.2f} s (= T_φ), {sea.n_components} components, seed {ROLL_SEED}, "
            f"{args.roll_duration:g} s (statistics after {args.transient:g} s), dt {DT} s"
        )
        passive = roll_run("none", args.roll_duration, sea)
        fins = roll_run("controller", args.roll_duration, sea)
        stats = roll_statistics(passive, fins, args.transient)
        out.update(stats)
        out.update(
            roll_natural_period_s=float(2 * np.pi / omega_roll),
            roll_wall_s=passive["wall_s"] + fins["wall_s"],
        )
        for k, v in stats.items():
            print(f"  {k:36s} {v: .4g}")
    if args.part in ("all", "speed"):
        sea = IrregularSea(hs=TRIAL_HS, tp=TRIAL_TP, n_components=60)
        print(
            f"speed trial: S175 shaft speed for {TRIAL_SPEED} m/s, head seas JONSWAP Hs "
            f"{TRIAL_HS} m Tp {TRIAL_TP} s, seed {TRIAL_SEED}, {args.trial_duration:g} s "
            f"(means after {args.settle:g} s)"
        )
        trials = {
            "calm": trial_run(None, args.trial_duration, args.settle, added_resistance=False),
            "waves": trial_run(sea, args.trial_duration, args.settle, added_resistance=False),
            "waves_raw": trial_run(sea, args.trial_duration, args.settle, added_resistance=True),
        }
        stats = trial_statistics(trials["calm"], trials["waves"], trials["waves_raw"], args.settle)
        out.update(stats)
        out["trial_wall_s"] = sum(r["wall_s"] for r in trials.values())
        for k, v in stats.items():
            if isinstance(v, dict):
                print(f"  {k}:")
                for kk, vv in v.items():
                    print(f"    {kk:34s} {vv: .4g}")
            else:
                print(f"  {k:36s} {v: .4g}")
    if args.part in ("all", "rao"):
        lambdas = [0.8, 1.15, 1.5] if args.quick else [0.5, 0.8, 1.0, 1.15, 1.3, 1.6, 2.0]
        print(
            f"regular head waves, H = 2 m, U = {TRIAL_SPEED} m/s, surge held: σ_AW of the "
            "simulator's own wave models vs SNNM"
        )
        t0 = time.perf_counter()
        rao = regular_wave_added_resistance(lambdas)
        out["regular_wave_sigma_aw"] = rao
        out["rao_wall_s"] = time.perf_counter() - t0
        for lam, a, b in zip(
            rao["lambda_over_L"], rao["sigma_simulator"], rao["sigma_snnm"], strict=True
        ):
            print(f"  λ/L {lam:4.2f}: simulator {a:6.2f}   SNNM {b:6.2f}")
    out["wall_s"] = time.perf_counter() - started
    print(f"wall time {out['wall_s']:.0f} s")
    if passive is not None or trials is not None or rao is not None:
        figure(args.figure, passive, fins, trials, args.transient, rao)
        print(f"figure: {args.figure}")
    if args.json is not None:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(out, indent=1))
        print(f"json: {args.json}")


if __name__ == "__main__":
    main()
