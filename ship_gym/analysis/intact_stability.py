"""Second-generation intact stability flavour: parametric roll and the dead-ship condition.

Parametric roll (Mathieu check)
-------------------------------
A ship in head or following regular waves of length λ ≈ L sees its metacentric height oscillate
at the encounter frequency ω_e as crests and troughs pass along the hull. With
GM(t) = GM (1 + h cos ω_e t) the linearised roll equation is the damped Mathieu equation

    φ̈ + 2ζω_φ φ̇ + ω_φ² (1 + h cos ω_e t) φ = 0,      h = ΔGM/GM.

With τ = ω_e t/2 it reads φ'' + 2μφ' + (a − 2q cos 2τ) φ = 0, a = 4ω_φ²/ω_e², q = −2hω_φ²/ω_e²,
μ = 2ζω_φ/ω_e. Near the principal resonance (a ≈ 1, ω_e ≈ 2ω_φ) first-order averaging gives the
Floquet exponent s = ½√(q² − (a − 1)²) − μ per unit τ (growth rate σ = s ω_e/2 [1/s]); roll
grows when s > 0, i.e. inside the damped first instability tongue (a − 1)² + 4μ² < q². At exact
tuning this is the classic threshold h > 4ζ.

ΔGM comes from *our* hydrostatics on the wave: the ship is balanced (free heave and trim) on a
regular wave of length λ and height H with the crest at several positions along the hull, using
the same nonlinear Froude–Krylov + hydrostatic pressure integration as the simulator
(:class:`ship_gym.forces.froude_krylov.FroudeKrylovHydrostatics`, Smith effect included); GM is
the roll stiffness −∂K/∂φ/(mg) by central differences at ±0.5°. ΔGM = (GM_max − GM_min)/2.
Next to the Mathieu check we print the IMO second-generation level-1 style ratio ΔGM/GM against
R_PR (MSC.1/Circ.1627 uses waterline inertias at two draughts; we use the wave itself, so this is
"in the spirit of", not the regulation): R_PR = 0.17 for C_m > 0.96 without bilge keels.

ζ is the equivalent linear roll damping ratio at ω_φ: radiation B44(ω_φ) plus the Ikeda viscous
B1 + (8/3π) ω_φ φ_a B2 at a small amplitude φ_a (default 5°), over 2√(C44 (I44 + A44)).

:func:`simulate_parametric_roll` gives the simulator's answer: the 6-DOF model (autopilot,
propeller) in the same regular wave at the same speed, from a small initial heel; roll grows or
decays. It runs on the engine (a one-ship :class:`~ship_gym.engine.batch.BatchSimulator`,
:func:`ship_gym.analysis.capsize_map.simulate_ships_until_capsize`); ``engine="simulator"``
runs the single-ship reference :class:`~ship_gym.engine.simulator.Simulator` instead (same
answer to rounding).

Dead ship
---------
:func:`dead_ship`: no propulsion, no rudder, zero speed, beam irregular seas (long-crested
JONSWAP); roll statistics and the capsize probability over seeds (capsize as in
:mod:`ship_gym.analysis.capsize_map`). The seeds run as the ships of one engine batch (one
batch per worker with ``n_jobs`` > 1; a seed's result does not depend on its batch), or, with
``engine="simulator"``, one single-ship Simulator each.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Literal

import numpy as np

if TYPE_CHECKING:
    from ship_gym.engine.batch import BatchSimulator
    from ship_gym.engine.simulator import Simulator

__all__ = [
    "R_PR_NO_BILGE_KEELS",
    "DeadShipResult",
    "ParametricRollCheck",
    "ParametricRollSimulation",
    "dead_ship",
    "gm_in_waves",
    "mathieu_growth",
    "parametric_roll_check",
    "simulate_parametric_roll",
]

R_PR_NO_BILGE_KEELS = 0.17
"""IMO level-1 parametric-roll standard R_PR for C_m > 0.96 (or < 0.94) without bilge keels."""


def mathieu_growth(h: float, zeta: float, omega_e: float, omega_roll: float) -> tuple[float, bool]:
    """Growth rate of roll in the principal parametric resonance (first-order averaging).

    Parameters
    ----------
    h : float
        Relative GM amplitude ΔGM/GM [-].
    zeta : float
        Linear roll damping ratio ζ [-].
    omega_e : float
        Encounter frequency |ω_e| > 0 [rad/s].
    omega_roll : float
        Roll natural frequency ω_φ > 0 [rad/s].

    Returns
    -------
    sigma : float
        Growth rate σ [1/s] of the roll amplitude (negative: decays; −inf outside the tongue's
        reach is never returned — a negative σ is the damping rate minus the detuned drive).
    unstable : bool
        σ > 0: inside the damped first instability tongue.
    """
    for name, value in (("omega_e", omega_e), ("omega_roll", omega_roll)):
        if not (math.isfinite(value) and value > 0.0):
            raise ValueError(f"{name} must be a positive frequency [rad/s], got {value!r}")
    if not (math.isfinite(h) and h >= 0.0):
        raise ValueError(f"h = ΔGM/GM must be >= 0, got {h!r}")
    if not (math.isfinite(zeta) and zeta >= 0.0):
        raise ValueError(f"zeta must be >= 0, got {zeta!r}")
    a = 4.0 * omega_roll**2 / omega_e**2
    q = 2.0 * h * omega_roll**2 / omega_e**2
    mu = 2.0 * zeta * omega_roll / omega_e
    disc = q * q - (a - 1.0) ** 2
    s = (0.5 * math.sqrt(disc) if disc > 0.0 else 0.0) - mu
    if disc <= 0.0:
        s = -mu - 0.5 * math.sqrt(-disc)  # outside the undamped tongue: oscillating, decaying
    sigma = s * omega_e / 2.0
    return float(sigma), bool(sigma > 0.0)


def _hydrostatic_force(hull, wave_field) -> Callable[[float, float, float], np.ndarray]:
    """Body-axis Froude–Krylov + hydrostatic force and weight [N, N·m] at rest at t = 0, as a
    function of (heave [m], trim [rad], heel [rad])."""
    from ship_gym.engine.rigid_body import gravity_force
    from ship_gym.forces.base import ForceContext
    from ship_gym.forces.froude_krylov import FroudeKrylovHydrostatics
    from ship_gym.kinematics import rotation_matrix

    fk = FroudeKrylovHydrostatics(hull, wave_field)
    phasor = wave_field.phasor(0.0)
    mass = hull.mass

    def force(heave: float, trim: float, heel: float) -> np.ndarray:
        eta = np.array([0.0, 0.0, heave, heel, trim, 0.0])
        rot = rotation_matrix(heel, trim, 0.0)
        ctx = ForceContext(t=0.0, eta=eta, nu=np.zeros(6), rotation=rot, wave_phasor=phasor)
        f, _ = fk.evaluate(ctx, np.zeros(0))
        return f + gravity_force(mass.mass, mass.cog, rot, hull.g)

    return force


def gm_in_waves(
    hull,
    wavelength: float,
    height: float,
    crest_positions: np.ndarray,
    *,
    dphi: float = math.radians(0.5),
) -> np.ndarray:
    """Metacentric height [m] of the ship balanced on a regular wave, per crest position.

    Parameters
    ----------
    hull : Hull
        Hull and loading condition.
    wavelength, height : float
        λ and H [m] of a wave travelling along the ship (head/following seas).
    crest_positions : array_like
        x of the crest relative to O [m] (0: crest amidships, ±λ/2: trough amidships).
    dphi : float
        Heel step of the central difference [rad].

    Returns
    -------
    numpy.ndarray
        GM [m] per crest position (free heave and trim at zero heel).
    """
    from scipy.optimize import root

    from ship_gym.hull import equilibrium
    from ship_gym.waves.sea_state import RegularWave
    from ship_gym.waves.wave_field import WaveField

    eq0 = equilibrium(hull)
    mg = hull.mass.mass * hull.g
    length = hull.particulars.lpp
    out = []
    k = 2.0 * math.pi / wavelength
    guess = np.array([eq0.heave, eq0.trim])
    for xc in np.atleast_1d(np.asarray(crest_positions, float)):
        # waves travel to χ = 0 (north = +x); ζ = a cos(ωt − kX + ε): crest at X = xc at t = 0
        wave = RegularWave(height=height, wavelength=wavelength, phase=k * xc, ramp_time=0.0)
        force = _hydrostatic_force(hull, WaveField.regular(wave))

        def residual(v: np.ndarray, force=force) -> np.ndarray:
            f = force(v[0], v[1], 0.0)
            return np.array([f[2] / mg, f[4] / (mg * length)])

        sol = root(residual, guess, method="hybr", tol=1e-10)
        if not sol.success and np.max(np.abs(residual(sol.x))) > 1e-6:
            raise RuntimeError(f"no equilibrium on the wave with the crest at x = {xc:.1f} m")
        heave, trim = sol.x
        k_plus = force(heave, trim, dphi)[3]
        k_minus = force(heave, trim, -dphi)[3]
        out.append(-(k_plus - k_minus) / (2.0 * dphi) / mg)
    return np.array(out)


@dataclass(frozen=True)
class ParametricRollCheck:
    """Result of :func:`parametric_roll_check`.

    Attributes
    ----------
    hull : str
        Hull name; ``hull_overrides`` its loading condition.
    wavelength, height : float
        Wave λ, H [m].
    heading_deg : float
        β [deg] (180 head, 0 following).
    froude, speed : float
        Fn [-] and U [m/s].
    gm_calm : float
        Calm-water GM [m].
    crest_positions : numpy.ndarray
        Crest x [m] of the GM-in-waves scan; ``gm_waves`` the GM there [m].
    delta_gm : float
        ΔGM = (max − min)/2 [m]; ``h`` = ΔGM/GM_calm [-].
    omega_wave, omega_e, omega_roll : float
        ω, |ω_e| and ω_φ [rad/s]; ``frequency_ratio`` = |ω_e|/ω_φ.
    zeta : float
        Equivalent linear roll damping ratio [-].
    growth_rate : float
        Mathieu growth rate σ [1/s]; ``mathieu_unstable`` σ > 0.
    level1_ratio_exceeded : bool
        h > R_PR (IMO level-1 style).
    susceptible : bool
        Both: the GM variation exceeds R_PR and the Mathieu tongue is entered.
    """

    hull: str
    hull_overrides: dict
    wavelength: float
    height: float
    heading_deg: float
    froude: float
    speed: float
    gm_calm: float
    crest_positions: np.ndarray
    gm_waves: np.ndarray
    delta_gm: float
    h: float
    omega_wave: float
    omega_e: float
    omega_roll: float
    frequency_ratio: float
    zeta: float
    growth_rate: float
    mathieu_unstable: bool
    level1_ratio_exceeded: bool
    susceptible: bool
    r_pr: float = R_PR_NO_BILGE_KEELS
    notes: list = field(default_factory=list)


def _roll_damping_ratio(hull, database, omega_roll: float, speed: float, amp: float) -> float:
    from ship_gym.forces.viscous import ViscousRollDamping
    from ship_gym.hull import equilibrium, hydrostatics

    eq = equilibrium(hull)
    c44 = hydrostatics(hull, heave=eq.heave, trim=eq.trim).stiffness[3, 3]
    w = database["omega"].values
    finite = np.isfinite(w) & (w > 0.0)
    a44 = float(np.interp(omega_roll, w[finite], database["added_mass"].values[finite, 3, 3]))
    b44 = float(
        np.interp(omega_roll, w[finite], database["radiation_damping"].values[finite, 3, 3])
    )
    visc = ViscousRollDamping.from_hull(
        hull, omega=omega_roll, forward_speed=speed, on_out_of_range="ignore"
    ).coefficients
    b_eq = b44 + visc.b1 + 8.0 / (3.0 * math.pi) * omega_roll * amp * visc.b2
    i44 = hull.mass.rigid_body_matrix()[3, 3]
    return float(b_eq / (2.0 * math.sqrt(c44 * (i44 + a44))))


def parametric_roll_check(
    hull: str = "s175",
    hull_overrides: dict | None = None,
    *,
    wavelength_ratio: float = 1.0,
    steepness: float = 1.0 / 30.0,
    heading_deg: float = 180.0,
    froude: float | None = None,
    n_crest_positions: int = 8,
    damping_amplitude_deg: float = 5.0,
) -> ParametricRollCheck:
    """Mathieu-type parametric-roll susceptibility in head or following regular waves.

    Parameters
    ----------
    hull : str
        Library hull; ``hull_overrides`` its loading condition (e.g. ``{"kg": 10.1}``).
    wavelength_ratio : float
        λ/L [-].
    steepness : float
        H/λ [-].
    heading_deg : float
        β [deg]: 180 head seas or 0 following seas (others accepted; the GM scan is still
        done along the ship).
    froude : float, optional
        Fn [-]; None: the speed that tunes |ω_e| = 2ω_φ at this heading (ValueError if none).
    n_crest_positions : int
        Crest positions over one wavelength for the GM scan.
    damping_amplitude_deg : float
        Roll amplitude of the equivalent linear viscous damping [deg].
    """
    from ship_gym.engine.ship import ShipSetup, database_of, roll_natural_frequency
    from ship_gym.hull import equilibrium, hydrostatics
    from ship_gym.kinematics import encounter_frequency
    from ship_gym.ship import hull_of

    overrides = dict(hull_overrides or {})
    ship = hull_of(hull, **overrides)
    length = ship.particulars.lpp
    g = ship.g
    if not (wavelength_ratio > 0.0 and 0.0 < steepness < 1.0 / 7.0):
        raise ValueError(
            f"need wavelength_ratio > 0 and 0 < steepness < 1/7, got {wavelength_ratio!r}, "
            f"{steepness!r}"
        )
    lam = wavelength_ratio * length
    height = steepness * lam
    omega = math.sqrt(2.0 * math.pi * g / lam)
    db = database_of(ShipSetup(hull=hull, hull_overrides=overrides))
    w_roll = roll_natural_frequency(ship, db)
    beta = math.radians(heading_deg)
    cosb = math.cos(beta)
    notes = []
    if froude is None:
        # |ω − ω²U cosβ/g| = 2ω_φ for the smallest U ≥ 0
        candidates = []
        if abs(cosb) > 1e-9:
            for target in (2.0 * w_roll, -2.0 * w_roll):
                u = (omega - target) * g / (omega**2 * cosb)
                if u >= 0.0:
                    candidates.append(u)
        if not candidates:
            raise ValueError(
                f"no forward speed tunes |ω_e| = 2ω_φ = {2 * w_roll:.3f} rad/s at β = "
                f"{heading_deg:g}° for λ/L = {wavelength_ratio:g} (ω = {omega:.3f} rad/s); give "
                "froude explicitly"
            )
        speed = min(candidates)
        froude = speed / math.sqrt(g * length)
        notes.append("speed chosen to tune |ω_e| = 2 ω_φ")
    else:
        if not (math.isfinite(froude) and froude >= 0.0):
            raise ValueError(f"froude must be >= 0, got {froude!r}")
        speed = froude * math.sqrt(g * length)
    w_e = abs(float(encounter_frequency(omega, speed, beta, g)))
    eq = equilibrium(ship)
    gm_calm = hydrostatics(ship, heave=eq.heave, trim=eq.trim).gmt
    crests = np.linspace(-lam / 2.0, lam / 2.0, int(n_crest_positions), endpoint=False)
    gm_w = gm_in_waves(ship, lam, height, crests)
    delta = 0.5 * float(gm_w.max() - gm_w.min())
    h = delta / gm_calm
    zeta = _roll_damping_ratio(ship, db, w_roll, speed, math.radians(damping_amplitude_deg))
    sigma, unstable = mathieu_growth(h, zeta, max(w_e, 1e-9), w_roll)
    exceeded = h > R_PR_NO_BILGE_KEELS
    return ParametricRollCheck(
        hull=hull,
        hull_overrides=overrides,
        wavelength=lam,
        height=height,
        heading_deg=float(heading_deg),
        froude=float(froude),
        speed=float(speed),
        gm_calm=float(gm_calm),
        crest_positions=crests,
        gm_waves=gm_w,
        delta_gm=delta,
        h=float(h),
        omega_wave=omega,
        omega_e=w_e,
        omega_roll=float(w_roll),
        frequency_ratio=w_e / w_roll,
        zeta=zeta,
        growth_rate=sigma,
        mathieu_unstable=unstable,
        level1_ratio_exceeded=exceeded,
        susceptible=bool(unstable and exceeded),
        notes=notes,
    )


def check_to_dict(check: ParametricRollCheck) -> dict:
    """JSON-ready dict of a check."""
    d = asdict(check)
    d["crest_positions"] = check.crest_positions.tolist()
    d["gm_waves"] = check.gm_waves.tolist()
    return d


def format_check(check: ParametricRollCheck) -> str:
    """Human-readable summary of a check."""
    return "\n".join(
        [
            f"parametric roll, {check.hull} {check.hull_overrides or '(design loading)'}: "
            f"λ = {check.wavelength:.1f} m, H = {check.height:.2f} m, β = {check.heading_deg:g}°, "
            f"Fn = {check.froude:.3f} (U = {check.speed:.2f} m/s)"
            + (f" [{'; '.join(check.notes)}]" if check.notes else ""),
            f"  GM calm {check.gm_calm:.3f} m; on the wave {check.gm_waves.min():.3f} … "
            f"{check.gm_waves.max():.3f} m → ΔGM/GM = {check.h:.3f} "
            f"(level-1 style R_PR {check.r_pr}: "
            f"{'EXCEEDED' if check.level1_ratio_exceeded else 'ok'})",
            f"  ω_e = {check.omega_e:.3f} rad/s, ω_φ = {check.omega_roll:.3f} rad/s, "
            f"ω_e/ω_φ = {check.frequency_ratio:.2f}; ζ = {check.zeta:.4f} "
            f"(4ζ = {4 * check.zeta:.3f})",
            f"  Mathieu growth rate σ = {check.growth_rate:+.4f} 1/s → "
            f"{'UNSTABLE' if check.mathieu_unstable else 'stable'}; susceptible: "
            f"{'YES' if check.susceptible else 'no'}",
        ]
    )


@dataclass(frozen=True)
class ParametricRollSimulation:
    """Simulator answer to a parametric-roll check.

    Attributes
    ----------
    initial_heel_deg : float
        Initial heel [deg].
    hold_speed : bool
        Surge held at U.
    t, roll : numpy.ndarray
        Time [s] and roll [rad].
    early_amplitude_deg, late_amplitude_deg : float
        max |φ| in the first and last quarter of the run after the ramp [deg].
    growth_ratio : float
        late amplitude / initial heel [-]; ``grows`` when > 2.
    max_abs_roll_deg : float
        [deg].
    capsized : bool
        |φ| beyond the vanishing angle or divergence.
    """

    initial_heel_deg: float
    hold_speed: bool
    t: np.ndarray
    roll: np.ndarray
    early_amplitude_deg: float
    late_amplitude_deg: float
    growth_ratio: float
    grows: bool
    max_abs_roll_deg: float
    capsized: bool


def simulate_parametric_roll(
    check: ParametricRollCheck,
    *,
    duration: float = 600.0,
    dt: float = 0.1,
    initial_heel_deg: float = 2.0,
    hold_speed: bool = True,
    progress: bool = False,
    engine: Literal["auto", "engine", "simulator"] = "auto",
) -> ParametricRollSimulation:
    """Run the 6-DOF simulator in the wave of a check, from a small initial heel.

    The ship (PID autopilot, state-space radiation, propeller at the calm-water self-propulsion
    rpm) runs at the check's speed and heading in the regular wave (ramp T_f = 50 s). Roll
    ``grows`` when its amplitude over the last quarter of the run is more than twice the initial
    heel (a decaying roll ends far below it; a parametric resonance grows until the nonlinear
    restoring detunes it and then stays large).

    ``hold_speed`` (default) holds surge at U so that the run tests the Mathieu tuning the check
    is about: at constant rpm the S175 in steep head seas at U = 3 m/s slows to ≈ 0.9 m/s mean
    (added resistance of the nonlinear Froude–Krylov force), which detunes ω_e/ω_φ from 2.0 to
    ≈ 1.8, outside the instability tongue. ``hold_speed=False`` gives the constant-rpm answer.

    Parameters
    ----------
    check : ParametricRollCheck
        The wave, speed, heading and loading condition.
    duration, dt : float
        Run length and physics step [s].
    initial_heel_deg : float
        Initial heel φ₀ [deg].
    hold_speed : bool
        Hold surge at U.
    progress : bool
        tqdm progress bar.
    engine : {"auto", "engine", "simulator"}
        The engine (default; RK4 and state-space radiation are engine models) or the
        single-ship reference Simulator (:data:`ship_gym.analysis.capsize_map.EngineChoice`).
    """
    from ship_gym.analysis.capsize_map import (
        capsize_angle_of,
        simulate_until_capsize,
        use_engine,
    )
    from ship_gym.engine.ship import ShipSetup, build_simulator, wave_field_for
    from ship_gym.waves.sea_state import RegularWave

    setup = ShipSetup(
        hull=check.hull,
        hull_overrides=dict(check.hull_overrides),
        speed=max(check.speed, 0.5),
        dt=dt,
        propulsion=True,
        manoeuvring=True,
        rudder="autopilot",
        free_dofs=(not hold_speed, True, True, True, True, True),
    )
    sea = RegularWave(height=check.height, wavelength=check.wavelength, ramp_time=50.0)
    beta = math.radians(check.heading_deg)
    sim: Simulator | BatchSimulator
    if use_engine(engine, setup.radiation, setup.integrator):
        from ship_gym.engine.batch import build_batch_simulator

        sim = build_batch_simulator(setup, [wave_field_for(sea, beta)], sea=sea, wave_heading=beta)
        eta0 = sim.eta[0].copy()
        eta0[3] = math.radians(initial_heel_deg)
        sim.reset(eta=eta0)  # commands (the trimmed shaft speed) are kept
    else:
        sim = build_simulator(setup, sea, wave_heading=beta)
        eta0 = sim.eta.copy()
        eta0[3] = math.radians(initial_heel_deg)
        commands = dict(sim.commands)
        sim.reset(eta=eta0)
        sim.commands = commands
    angle = capsize_angle_of(check.hull, check.hull_overrides)
    outcome, series = simulate_until_capsize(
        sim, duration, math.radians(angle), record_every=5, progress=progress
    )
    t, roll = series["t"], series["eta"][:, 3]
    after = t >= 50.0
    span = max(duration - 50.0, dt)
    early = after & (t < 50.0 + span / 4.0)
    late = t >= duration - span / 4.0
    early_amp = float(np.degrees(np.max(np.abs(roll[early])))) if early.any() else math.nan
    late_amp = float(np.degrees(np.max(np.abs(roll[late])))) if late.any() else math.nan
    if outcome.capsized:
        late_amp = outcome.max_abs_roll_deg
    ratio = late_amp / initial_heel_deg if initial_heel_deg > 0 else math.inf
    return ParametricRollSimulation(
        initial_heel_deg=initial_heel_deg,
        hold_speed=hold_speed,
        t=t,
        roll=roll,
        early_amplitude_deg=early_amp,
        late_amplitude_deg=late_amp,
        growth_ratio=float(ratio),
        grows=bool(ratio > 2.0),
        max_abs_roll_deg=outcome.max_abs_roll_deg,
        capsized=outcome.capsized,
    )


def simulation_to_dict(sim: ParametricRollSimulation) -> dict:
    """JSON-ready scalars of a simulation."""
    return {k: v for k, v in asdict(sim).items() if k not in ("t", "roll")}


def plot_parametric_roll(
    check: ParametricRollCheck, sim: ParametricRollSimulation, path: str | Path
) -> Path:
    """Roll time history of the simulator check (PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ship_gym.io_utils import atomic_write

    fig, ax = plt.subplots(figsize=(8, 3.5))
    ax.plot(sim.t, np.degrees(sim.roll), lw=0.8)
    ax.set(
        xlabel="t [s]",
        ylabel="roll φ [deg]",
        title=(
            f"{check.hull} λ = {check.wavelength:.0f} m, H = {check.height:.1f} m, β = "
            f"{check.heading_deg:g}°, Fn = {check.froude:.3f}: ω_e/ω_φ = "
            f"{check.frequency_ratio:.2f}, ΔGM/GM = {check.h:.2f}"
        ),
    )
    ax.title.set_fontsize(9)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    path = Path(path)
    atomic_write(path, lambda p: fig.savefig(p, dpi=100, format="png"))
    plt.close(fig)
    return path


# ----------------------------------------------------------------------------- dead ship
@dataclass(frozen=True)
class DeadShipResult:
    """Dead-ship roll statistics over seeds.

    Attributes
    ----------
    hull, hull_overrides : str, dict
        Ship and loading condition.
    hs, tp : float
        Sea state [m, s] (beam seas, β = 90°).
    seeds : tuple of int
        Seeds run.
    capsize_angle_deg : float
        Capsize angle [deg].
    outcomes : list of dict
        Per seed: capsized, reason, time_to_capsize, max/RMS roll [deg].
    capsize_probability : float
        Fraction of seeds that capsized.
    rms_roll_deg, max_abs_roll_deg : float
        Mean RMS φ and max |φ| over seeds [deg].
    """

    hull: str
    hull_overrides: dict
    hs: float
    tp: float
    seeds: tuple
    capsize_angle_deg: float
    outcomes: list
    capsize_probability: float
    rms_roll_deg: float
    max_abs_roll_deg: float


def _dead_ship_setup(hull, overrides, dt, hold_yaw):
    from ship_gym.engine.ship import ShipSetup

    return ShipSetup(
        hull=hull,
        hull_overrides=dict(overrides),
        speed=0.0,
        dt=dt,
        free_dofs=(True, True, True, True, True, not hold_yaw),
    )


def _dead_ship_seed(hull, overrides, hs, tp, seed, duration, dt, angle, hold_yaw) -> dict:
    """One seed on the single-ship reference Simulator."""
    from ship_gym.analysis.capsize_map import simulate_until_capsize, single_threaded_blas
    from ship_gym.engine.ship import build_simulator
    from ship_gym.waves.sea_state import IrregularSea

    with single_threaded_blas():
        setup = _dead_ship_setup(hull, overrides, dt, hold_yaw)
        sea = IrregularSea(hs=hs, tp=tp)
        sim = build_simulator(
            setup, sea, wave_heading=math.pi / 2.0, rng=np.random.default_rng(seed)
        )
        out, _ = simulate_until_capsize(
            sim, duration, math.radians(angle), record_every=5, stats_after=sea.ramp_time
        )
    return {"seed": seed, **asdict(out)}


def _dead_ship_seeds(hull, overrides, hs, tp, seeds, duration, dt, angle, hold_yaw) -> list:
    """Seeds as the ships of one engine batch (each as it would run alone)."""
    from ship_gym.analysis.capsize_map import simulate_ships_until_capsize, single_threaded_blas
    from ship_gym.engine.batch import build_batch_simulator
    from ship_gym.engine.ship import wave_field_for
    from ship_gym.waves.sea_state import IrregularSea

    with single_threaded_blas():
        setup = _dead_ship_setup(hull, overrides, dt, hold_yaw)
        sea = IrregularSea(hs=hs, tp=tp)
        beta = math.pi / 2.0
        fields = [wave_field_for(sea, beta, np.random.default_rng(s)) for s in seeds]
        sim = build_batch_simulator(setup, fields, sea=sea, wave_heading=beta)
        results = simulate_ships_until_capsize(
            sim, duration, math.radians(angle), record_every=5, stats_after=sea.ramp_time
        )
    return [{"seed": s, **asdict(out)} for s, (out, _) in zip(seeds, results, strict=True)]


def dead_ship(
    hull: str = "s175",
    hull_overrides: dict | None = None,
    *,
    hs: float = 7.0,
    tp: float = 15.0,
    seeds: tuple[int, ...] = (0, 1, 2, 3),
    duration: float = 600.0,
    dt: float = 0.1,
    n_jobs: int = 1,
    hold_yaw: bool = False,
    engine: Literal["auto", "engine", "simulator"] = "auto",
) -> DeadShipResult:
    """Dead ship (no propulsion, no rudder, U = 0) in beam long-crested JONSWAP seas.

    At zero speed the model has no manoeuvring forces, so only radiation resists yaw and the
    ship turns away from beam seas over a run (most seeds by ≥ 90° in 600 s): with the default
    free yaw this is a dead ship *starting* beam-on. ``hold_yaw=True`` keeps it beam-on, as the
    IMO dead-ship criterion assumes (S175, Hs 8 m, Tp 18 s: RMS roll 8.91° held vs 8.82° free).

    Parameters
    ----------
    hull : str
        Library hull; ``hull_overrides`` its loading condition.
    hs, tp : float
        Significant wave height [m] and peak period [s].
    seeds : tuple of int
        One sea realisation per seed.
    duration, dt : float
        Run length and physics step [s].
    n_jobs : int
        joblib worker processes.
    hold_yaw : bool
        Hold the heading (beam-on throughout).
    engine : {"auto", "engine", "simulator"}
        The seeds as one engine batch per worker (default) or one single-ship reference
        Simulator each (:data:`ship_gym.analysis.capsize_map.EngineChoice`).
    """
    from ship_gym.analysis.capsize_map import capsize_angle_of, use_engine

    overrides = dict(hull_overrides or {})
    if not seeds:
        raise ValueError("seeds must not be empty")
    angle = capsize_angle_of(hull, overrides)
    seeds_ = [int(s) for s in seeds]
    if use_engine(engine, "state_space", "rk4"):  # the dead ship's radiation and integrator
        n_batches = max(1, min(int(n_jobs), len(seeds_)))
        size = math.ceil(len(seeds_) / n_batches)
        batches = [seeds_[i : i + size] for i in range(0, len(seeds_), size)]
        args_b = [(hull, overrides, hs, tp, b, duration, dt, angle, hold_yaw) for b in batches]
        if len(batches) == 1:
            parts = [_dead_ship_seeds(*a) for a in args_b]
        else:
            from joblib import Parallel, delayed

            parts = Parallel(n_jobs=n_jobs)(delayed(_dead_ship_seeds)(*a) for a in args_b)
        outcomes = [o for part in parts for o in part]
    else:
        args = [(hull, overrides, hs, tp, s, duration, dt, angle, hold_yaw) for s in seeds_]
        if n_jobs == 1:
            outcomes = [_dead_ship_seed(*a) for a in args]
        else:
            from joblib import Parallel, delayed

            outcomes = Parallel(n_jobs=n_jobs)(delayed(_dead_ship_seed)(*a) for a in args)
    return DeadShipResult(
        hull=hull,
        hull_overrides=overrides,
        hs=hs,
        tp=tp,
        seeds=tuple(int(s) for s in seeds),
        capsize_angle_deg=angle,
        outcomes=outcomes,
        capsize_probability=sum(o["capsized"] for o in outcomes) / len(outcomes),
        rms_roll_deg=float(np.mean([o["rms_roll_deg"] for o in outcomes])),
        max_abs_roll_deg=float(max(o["max_abs_roll_deg"] for o in outcomes)),
    )


def dead_ship_to_dict(res: DeadShipResult) -> dict:
    """JSON-ready dict."""
    return asdict(res)


def format_dead_ship(res: DeadShipResult) -> str:
    """Human-readable summary."""
    lines = [
        f"dead ship {res.hull} {res.hull_overrides or '(design loading)'}: beam seas JONSWAP "
        f"Hs {res.hs:g} m Tp {res.tp:g} s, {len(res.seeds)} seeds; capsize |φ| > "
        f"{res.capsize_angle_deg:.1f}°",
        "  seed  capsized  reason    t_capsize [s]  max|φ| [deg]  RMS φ [deg]",
    ]
    for o in res.outcomes:
        tc = "–" if o["time_to_capsize"] is None else f"{o['time_to_capsize']:.0f}"
        lines.append(
            f"  {o['seed']:4d}  {o['capsized']!s:8}  {o['reason']:8}  {tc:>13}  "
            f"{o['max_abs_roll_deg']:12.1f}  {o['rms_roll_deg']:11.2f}"
        )
    lines.append(
        f"  capsize probability {res.capsize_probability:.2f}; mean RMS φ {res.rms_roll_deg:.2f}°, "
        f"max |φ| {res.max_abs_roll_deg:.1f}°"
    )
    return "\n".join(lines)
