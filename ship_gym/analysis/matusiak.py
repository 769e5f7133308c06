"""Matusiak's memory-effect study ("Importance of memory effect for capsizing prediction").

Matusiak simulated the ITTC A-1 container ship (L = 150 m) in steep regular waves — amplitude
A_w = 4.5 m, λ = 1.5 L, 720 s per run, the wave amplitude ramped in over T_f = 50 s (his eq. 12)
— at four (Fn, heading) pairs, with three radiation models: case 1, Cummins' memory
(retardation function, his eq. 15–16), and the constant-coefficient cases 2a (a, b at the
encounter frequency, roll terms at the roll natural frequency) and 2b (all at the encounter
frequency) of his eq. 13–14. The ship keeps course with an autopilot (a 13th ODE for the rudder)
and runs at constant propeller rpm; surge is not linearised. RK4, Δt = 0.1 s, full scale.

The A-1 hull data are not public, so we run the S175 (L = 175 m) and scale the wave with the
length: λ = 1.5 L = 262.5 m and A_w = 4.5 m × 175/150 = 5.25 m (H = 10.5 m, H/λ = 1/25, the
same steepness as his 9 m / 225 m). Froude number and heading are his. Our setup, as far as the
paper describes one (it gives no autopilot gains or propeller data):

* the two-stage model (the force models of :func:`ship_gym.engine.ship.build_force_models`):
  nonlinear Froude–Krylov + hydrostatics on the instantaneous wetted hull, linear diffraction
  at the encounter frequency, Ikeda viscous roll damping, Holtrop resistance + B-series
  propeller at the calm-water self-propulsion rpm (held constant), hull manoeuvring forces and
  a rudder under the PID heading autopilot (Nomoto pole placement);
* radiation ``"state_space"`` (case 1; a state-space fit of Cummins' kernel, with
  ``"convolution"`` as the direct-convolution reference), ``"2a"`` and ``"2b"``;
* RK4 at Δt = 0.1 s (Matusiak's step; ``scripts/convergence_study.py`` gives a relative RMS
  error ≤ 1e-6 against Δt = 0.0125 s in steep regular waves);
* capsize: |φ| beyond the angle of vanishing stability of the loading condition, or the
  simulator diverging (:mod:`ship_gym.analysis.capsize_map`).

The runs use the engine (a one-ship :class:`~ship_gym.engine.batch.BatchSimulator`,
:meth:`Scenario.build_engine`, run by
:func:`~ship_gym.analysis.capsize_map.simulate_ships_until_capsize`) for the state-space, 2a and
2b radiation with RK4 or Holloway; the direct convolution and the ABM integrator exist only in
the single-ship :class:`~ship_gym.engine.simulator.Simulator` (:meth:`Scenario.build`), which
runs those. The two paths agree to rounding (``run_scenario(..., engine="simulator")`` forces
the reference).

Heading 0° is following seas in both Matusiak's convention and ours (β = χ − ψ).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Literal

import numpy as np

from ship_gym.conventions import GRAVITY
from ship_gym.waves.sea_state import RegularWave

__all__ = [
    "A1_LENGTH",
    "A1_WAVE_AMPLITUDE",
    "MATUSIAK_TABLE",
    "RAMP_TIME",
    "MatusiakRow",
    "Scenario",
    "ScenarioResult",
    "run_scenario",
    "scaled_wave",
    "speed_from_froude",
    "study_scenarios",
]

A1_LENGTH = 150.0
"""Length of Matusiak's A-1 container ship [m]."""
A1_WAVE_AMPLITUDE = 4.5
"""His regular-wave amplitude A_w [m] (λ = 1.5 L = 225 m)."""
WAVELENGTH_RATIO = 1.5
"""λ/L of his table [-]."""
RAMP_TIME = 50.0
"""T_f of his eq. 12 [s]."""
DURATION = 720.0
"""Run length of a non-capsizing case [s]."""

RadiationCase = Literal["state_space", "convolution", "2a", "2b"]


@dataclass(frozen=True)
class MatusiakRow:
    """One column of Matusiak's results table (capsize True/False).

    Attributes
    ----------
    froude : float
        Fn [-].
    heading_deg : float
        Heading relative to the waves [deg] (0 following).
    experiment, case_1, case_2ab : bool
        Capsize in the Osaka model tests, with the memory model, with the constant-coefficient
        models (2a and 2b agree in every case).
    """

    froude: float
    heading_deg: float
    experiment: bool
    case_1: bool
    case_2ab: bool


MATUSIAK_TABLE: tuple[MatusiakRow, ...] = (
    MatusiakRow(0.2, 0.0, True, False, False),
    MatusiakRow(0.2, 45.0, False, False, False),
    MatusiakRow(0.3, 30.0, False, False, True),
    MatusiakRow(0.4, 30.0, True, True, True),
)
"""Matusiak's "Table: Summary of the results" (A-1 ship, A_w = 4.5 m, λ = 1.5 L)."""


def scaled_wave(length: float) -> tuple[float, float]:
    """Matusiak's wave scaled to a ship of another length (same λ/L and steepness).

    Parameters
    ----------
    length : float
        Ship length L [m].

    Returns
    -------
    amplitude, wavelength : float
        A_w = 4.5 m × L/150 m and λ = 1.5 L [m].
    """
    if not (math.isfinite(length) and length > 0.0):
        raise ValueError(f"length must be a positive length [m], got {length!r}")
    return A1_WAVE_AMPLITUDE * length / A1_LENGTH, WAVELENGTH_RATIO * length


def speed_from_froude(froude: float, length: float, g: float = GRAVITY) -> float:
    """Ship speed U = Fn √(g L) [m/s] for Froude number Fn [-] and length L [m]."""
    if not (math.isfinite(froude) and froude >= 0.0):
        raise ValueError(f"froude must be a non-negative Froude number, got {froude!r}")
    if not (math.isfinite(length) and length > 0.0):
        raise ValueError(f"length must be a positive length [m], got {length!r}")
    return froude * math.sqrt(g * length)


@dataclass(frozen=True)
class Scenario:
    """One run of the study.

    Parameters
    ----------
    froude : float
        Fn [-].
    heading_deg : float
        Relative wave heading β [deg] (0 following).
    radiation : {"state_space", "convolution", "2a", "2b"}
        Case 1 (state-space or convolution memory) or 2a / 2b.
    kg : float, optional
        KG override [m] (None: the design loading condition, KG = 9.55 m, GM ≈ 1.0 m).
    hull : str
        Library hull.
    duration, dt : float
        Run length and physics step [s].
    integrator : {"rk4", "holloway"}
        Time integrator.
    ramp_time : float
        T_f of eq. 12 [s].
    """

    froude: float
    heading_deg: float
    radiation: RadiationCase = "state_space"
    kg: float | None = None
    hull: str = "s175"
    duration: float = DURATION
    dt: float = 0.1
    integrator: Literal["rk4", "holloway"] = "rk4"
    ramp_time: float = RAMP_TIME

    def __post_init__(self) -> None:
        if self.radiation not in ("state_space", "convolution", "2a", "2b"):
            raise ValueError(
                f"radiation must be 'state_space', 'convolution', '2a' or '2b', "
                f"got {self.radiation!r}"
            )
        if not (math.isfinite(self.froude) and 0.0 < self.froude < 1.0):
            raise ValueError(f"froude must be in (0, 1), got {self.froude!r}")

    @property
    def hull_overrides(self) -> dict:
        """Loading-condition overrides of the hull builder."""
        return {} if self.kg is None else {"kg": float(self.kg)}

    @property
    def label(self) -> str:
        """E.g. ``"Fn0.3_h30_state_space_kg10.1"``."""
        cond = "design" if self.kg is None else f"kg{self.kg:g}"
        return f"Fn{self.froude:g}_h{self.heading_deg:g}_{self.radiation}_{cond}"

    def length(self) -> float:
        """Ship length L [m] (Lpp of the library hull)."""
        from ship_gym.ship import hull_of

        return hull_of(self.hull).particulars.lpp

    def sea(self, length: float | None = None) -> RegularWave:
        """Matusiak's regular wave scaled to this hull (eq. 12 ramp, T_f = ``ramp_time``)."""
        amplitude, wavelength = scaled_wave(self.length() if length is None else length)
        return RegularWave(height=2.0 * amplitude, wavelength=wavelength, ramp_time=self.ramp_time)

    def setup(self, length: float | None = None):
        """The :class:`~ship_gym.engine.ship.ShipSetup` of the run (self-propelled, under the
        heading autopilot: :func:`ship_gym.analysis.capsize_map.autopilot_setup`)."""
        from ship_gym.analysis.capsize_map import autopilot_setup

        speed = speed_from_froude(self.froude, self.length() if length is None else length)
        return autopilot_setup(
            self.hull,
            self.hull_overrides,
            speed,
            radiation=self.radiation,
            integrator=self.integrator,
            dt=self.dt,
        )

    def build(self):
        """The single-ship :class:`~ship_gym.engine.simulator.Simulator` at the start of the
        run (heading north, waves to β): the engine with one ship."""
        from ship_gym.engine.ship import build_simulator

        length = self.length()
        return build_simulator(
            self.setup(length), self.sea(length), wave_heading=math.radians(self.heading_deg)
        )

    def build_engine(self):
        """The run as a one-ship :class:`~ship_gym.engine.batch.BatchSimulator` (the engine).

        Raises
        ------
        NotImplementedError
            For the convolution radiation or the ABM integrator (use :meth:`build`).
        """
        from ship_gym.engine.batch import build_batch_simulator
        from ship_gym.engine.ship import wave_field_for

        length = self.length()
        sea = self.sea(length)
        beta = math.radians(self.heading_deg)
        return build_batch_simulator(
            self.setup(length), [wave_field_for(sea, beta)], sea=sea, wave_heading=beta
        )


@dataclass(frozen=True)
class ScenarioResult:
    """Outcome and time histories of a scenario.

    Attributes
    ----------
    scenario : Scenario
        The run.
    capsized : bool
        Capsize (|φ| beyond the vanishing angle, or divergence).
    reason : str
        ``"none"``, ``"roll"`` or ``"diverged"``.
    time_to_capsize : float or None
        [s].
    capsize_angle_deg : float
        Vanishing angle of the loading condition [deg].
    gm : float
        Metacentric height of the loading condition at its equilibrium [m].
    max_abs_roll_deg, rms_roll_deg, max_abs_pitch_deg, max_heading_deviation_deg : float
        Motion statistics [deg] (RMS after the ramp).
    mean_speed : float
        Mean surge speed after the ramp [m/s].
    encounter_frequency : float
        |ω_e| [rad/s] of the wave at the nominal speed and heading.
    roll_natural_frequency : float
        ω_φ of the loading condition [rad/s].
    t, roll, pitch, yaw, rudder, u : numpy.ndarray
        Time histories: [s], [rad] ×3, applied rudder [rad], surge speed [m/s].
    cpu_s : float
        CPU time of the run (build included) [s].
    engine : str
        Path that ran it: ``"compiled"`` or ``"numpy"`` (the engine's backend) or
        ``"simulator"`` (the single-ship reference).
    """

    scenario: Scenario
    capsized: bool
    reason: str
    time_to_capsize: float | None
    capsize_angle_deg: float
    gm: float
    max_abs_roll_deg: float
    rms_roll_deg: float
    max_abs_pitch_deg: float
    max_heading_deviation_deg: float
    mean_speed: float
    encounter_frequency: float
    roll_natural_frequency: float
    t: np.ndarray
    roll: np.ndarray
    pitch: np.ndarray
    yaw: np.ndarray
    rudder: np.ndarray
    u: np.ndarray
    cpu_s: float
    engine: str = "simulator"

    def row(self) -> dict:
        """Scalars for the CSV table."""
        s = self.scenario
        return {
            "froude": s.froude,
            "heading_deg": s.heading_deg,
            "radiation": s.radiation,
            "kg_m": s.kg if s.kg is not None else 9.55,
            "gm_m": round(self.gm, 3),
            "capsize_angle_deg": round(self.capsize_angle_deg, 2),
            "capsized": self.capsized,
            "reason": self.reason,
            "time_to_capsize_s": (
                None if self.time_to_capsize is None else round(self.time_to_capsize, 1)
            ),
            "max_abs_roll_deg": round(self.max_abs_roll_deg, 2),
            "rms_roll_deg": round(self.rms_roll_deg, 2),
            "max_abs_pitch_deg": round(self.max_abs_pitch_deg, 2),
            "max_heading_deviation_deg": round(self.max_heading_deviation_deg, 2),
            "mean_speed_m_s": round(self.mean_speed, 3),
            "encounter_frequency_rad_s": round(self.encounter_frequency, 4),
            "roll_natural_frequency_rad_s": round(self.roll_natural_frequency, 4),
            "cpu_s": round(self.cpu_s, 1),
            "engine": self.engine,
        }


def study_scenarios(
    kgs: tuple[float | None, ...] = (None,),
    radiations: tuple[RadiationCase, ...] = ("state_space", "2a", "2b"),
    *,
    convolution_reference: tuple[float, float] | None = (0.3, 30.0),
    duration: float = DURATION,
    dt: float = 0.1,
) -> list[Scenario]:
    """The runs of the study: Matusiak's four (Fn, heading) pairs × models × loading conditions.

    Parameters
    ----------
    kgs : tuple
        Loading conditions (KG [m]; None = design).
    radiations : tuple
        Radiation models.
    convolution_reference : (Fn, heading_deg), optional
        One pair also run with the direct convolution (for every loading condition).
    duration, dt : float
        Run length and step [s].
    """
    out = []
    for kg in kgs:
        for row in MATUSIAK_TABLE:
            for rad in radiations:
                out.append(Scenario(row.froude, row.heading_deg, rad, kg, duration=duration, dt=dt))
            if convolution_reference == (row.froude, row.heading_deg):
                out.append(
                    Scenario(
                        row.froude, row.heading_deg, "convolution", kg, duration=duration, dt=dt
                    )
                )
    return out


def run_scenario(
    scenario: Scenario,
    *,
    record_every: int = 5,
    progress: bool = False,
    engine: Literal["auto", "engine", "simulator"] = "auto",
):
    """Simulate one scenario (stopped at capsize).

    Parameters
    ----------
    scenario : Scenario
        The run.
    record_every : int
        Record every n-th step of the time histories.
    progress : bool
        tqdm progress bar.
    engine : {"auto", "engine", "simulator"}
        ``"auto"``/``"engine"``: a batch of one ship (:meth:`Scenario.build_engine`);
        ``"simulator"``: a :class:`~ship_gym.engine.simulator.Simulator` (:meth:`Scenario.build`)
        stepped by the study (:data:`ship_gym.analysis.capsize_map.EngineChoice`).

    Returns
    -------
    ScenarioResult
    """
    from ship_gym.analysis.capsize_map import (
        capsize_angle_of,
        simulate_until_capsize,
        use_engine,
    )
    from ship_gym.engine.ship import database_of, roll_natural_frequency
    from ship_gym.hull import equilibrium, hydrostatics
    from ship_gym.kinematics import encounter_frequency
    from ship_gym.ship import hull_of

    t0 = time.process_time()
    hull = hull_of(scenario.hull, **scenario.hull_overrides)
    eq = equilibrium(hull)
    gm = hydrostatics(hull, heave=eq.heave, trim=eq.trim).gmt
    angle = capsize_angle_of(scenario.hull, scenario.hull_overrides)
    on_engine = use_engine(engine, scenario.radiation, scenario.integrator)
    sim = scenario.build_engine() if on_engine else scenario.build()
    sea = scenario.sea(hull.particulars.lpp)
    w_e = abs(
        float(
            encounter_frequency(
                sea.omega, sim.forward_speed, math.radians(scenario.heading_deg), hull.g
            )
        )
    )
    w_roll = roll_natural_frequency(hull, database_of(scenario.setup()))
    outcome, series = simulate_until_capsize(
        sim,
        scenario.duration,
        math.radians(angle),
        record_every=record_every,
        stats_after=scenario.ramp_time,
        progress=progress,
    )
    eta = series["eta"]
    return ScenarioResult(
        scenario=scenario,
        capsized=outcome.capsized,
        reason=outcome.reason,
        time_to_capsize=outcome.time_to_capsize,
        capsize_angle_deg=angle,
        gm=float(gm),
        max_abs_roll_deg=outcome.max_abs_roll_deg,
        rms_roll_deg=outcome.rms_roll_deg,
        max_abs_pitch_deg=outcome.max_abs_pitch_deg,
        max_heading_deviation_deg=outcome.max_heading_deviation_deg,
        mean_speed=outcome.mean_speed,
        encounter_frequency=w_e,
        roll_natural_frequency=w_roll,
        t=series["t"],
        roll=eta[:, 3],
        pitch=eta[:, 4],
        yaw=eta[:, 5],
        rudder=series["rudder"],
        u=series["nu"][:, 0],
        cpu_s=time.process_time() - t0,
        engine=("compiled" if sim.compiled else "numpy") if on_engine else "simulator",
    )
