"""Capsize-risk maps: heading × Froude number (× sea state × seeds) under the heading autopilot.

Each *cell* of the map is one run of the 6-DOF two-stage model (the force models of
:func:`ship_gym.engine.ship.build_force_models`; the roll natural frequency of the damping
follows the loading condition, :func:`ship_gym.engine.ship.roll_natural_frequency`): the ship
starts at the free-floating equilibrium heading north at U = Fn √(g L), keeps its heading with
the PID autopilot (``ShipSetup(rudder="autopilot", manoeuvring=True, propulsion=True)``, command
``"heading"`` = 0) and the propeller at the calm-water self-propulsion rpm, while the waves travel
at the relative heading β (0° following, 180° head seas; :mod:`ship_gym.conventions`) and ramp up
over T_f (Matusiak eq. 12).

Capsize is declared, and the run stopped, when

* ``"roll"``: |φ| exceeds the capsize angle — by default the angle of vanishing stability of the
  loading condition (:func:`ship_gym.hull.righting_arm`, calm water, free sinkage and trim), or
* ``"diverged"``: the state no longer makes sense (non-finite, or |ν| above the engine's
  limit, e.g. the hull flying out of the water): the engine flags the ship (one ship on a
  :class:`~ship_gym.engine.simulator.Simulator` raises
  :class:`~ship_gym.engine.simulator.SimulationDiverged`).

Both are checked after every physics step. The time to capsize is that of the first step beyond
the angle (``"roll"``) or of the step that failed (``"diverged"``: the last valid time + Δt).

Engine. The cells of one (sea, heading, Froude number) run together on ONE
:class:`~ship_gym.engine.batch.BatchSimulator`, a ship per seed (:func:`run_cells`,
:func:`simulate_ships_until_capsize`): one compiled call
(:meth:`~ship_gym.engine.batch.BatchSimulator.advance`) advances all of them by one recording
interval (``record_every`` steps), its per-step reductions (``danger_steps`` with the capsize angle
as threshold) and per-ship divergence flags tell which ship capsized in it. A ship that capsized is
stopped there; its exact capsize step is then found by *replaying* it — reset to its initial state,
the same chunks up to the one in which it capsized, then that chunk step by step — so the time to
capsize, the statistics and the final state are those of the step-by-step run, not of the chunk end.
(The compiled engine is bit-identical per ship for any batch size and chunk split, so the replay
reproduces the run exactly; this is checked and a mismatch raises. On the engine's numpy backend —
the Cummins convolution radiation — the ships advance step by step instead, without replay.)
``engine="simulator"`` runs one cell at a time on a :class:`~ship_gym.engine.simulator.Simulator`
(:func:`~ship_gym.engine.ship.build_simulator`: the same engine with one ship); both agree to
rounding (≈ 1e-12 relative; tested). On the compiled engine a ship's result does not depend on the
cells it runs with (bit for bit), so a map is the same run serially, in parallel, or resumed.

Per cell: capsize yes/no, the reason, the time to capsize [s], max |φ| and RMS φ after the ramp
[deg], max |θ| [deg], max heading deviation [deg] and the mean surge speed [m/s]. Over seeds a
cell's capsize *probability* is the fraction of seeds that capsize (:func:`summarise`).

Runs are resumable: :func:`run_capsize_map` writes a JSON-lines file whose first line is the
configuration and every further line one finished cell, appended and ``fsync``-ed as each batch
of cells finishes (the parent process is the only writer, so parallel workers never
interleave). Besides the outcome, a record holds ``speed`` [m/s], ``cpu_s`` (the CPU time of its
batch [s] divided by the batch's cells), ``engine`` (``"compiled"`` or ``"numpy"``: the
:class:`~ship_gym.engine.batch.BatchSimulator` backend; ``"simulator"``: one cell at a time on a
:class:`~ship_gym.engine.simulator.Simulator`) and ``batch_size`` (ships run together; 1 for
``"simulator"``); records written
before these two fields existed lack them. A rerun with the same configuration skips the cells
already there; a different configuration raises a ValueError naming the differing keys (results
are never mixed). A torn last line (a crash during a write) is cut off before appending.

Seeds: for an irregular sea the seed draws the wave phases (the same realisation for every
heading and speed: common random numbers); for a regular wave it draws the wave phase ε at the
ship, uniform in [0, 2π).
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import json
import math
import os
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from ship_gym.typing import IntegratorName
from ship_gym.waves.sea_state import IrregularSea, RegularWave

if TYPE_CHECKING:
    from ship_gym.engine.batch import BatchSimulator, EngineBackend
    from ship_gym.engine.ship import RadiationName, ShipSetup
    from ship_gym.engine.simulator import Simulator

__all__ = [
    "FORMAT_VERSION",
    "CapsizeMapConfig",
    "CapsizeMapResult",
    "Cell",
    "EngineChoice",
    "RunOutcome",
    "SeaSpec",
    "autopilot_setup",
    "build_cells_simulator",
    "capsize_angle_of",
    "engine_supports",
    "load_results",
    "plot_capsize_map",
    "run_capsize_map",
    "run_cell",
    "run_cells",
    "simulate_ships_until_capsize",
    "simulate_until_capsize",
    "single_threaded_blas",
    "summarise",
    "use_engine",
]

FORMAT_VERSION = 1
"""Version of the results-file layout (part of the configuration header)."""

CellRunner = Callable[["CapsizeMapConfig", "Cell", float], dict]

EngineChoice = Literal["auto", "engine", "simulator"]
"""How a capsize study drives the engine: ``"auto"`` and ``"engine"`` run the cells of one
(sea, heading, Froude number) together, a ship per seed, on one
:class:`~ship_gym.engine.batch.BatchSimulator`; ``"simulator"`` runs one cell at a time on a
:class:`~ship_gym.engine.simulator.Simulator` (the same engine with one ship, stepped and
checked after every step by the study)."""


def engine_supports(radiation: str, integrator: str) -> bool:
    """Whether the engine runs this radiation model and integrator.

    Every radiation model of :class:`~ship_gym.engine.ship.ShipSetup` and both integrators run
    on the engine (the Cummins convolution on its numpy path).

    Parameters
    ----------
    radiation : str
        Radiation model (:class:`~ship_gym.engine.ship.ShipSetup`).
    integrator : str
        Time integrator.
    """
    from ship_gym.engine.ship import RADIATION_MODELS

    return radiation in RADIATION_MODELS and integrator in ("rk4", "holloway")


def use_engine(engine: EngineChoice, radiation: str, integrator: str) -> bool:
    """Resolve an :data:`EngineChoice` for a configuration: True for batched cells.

    Raises
    ------
    ValueError
        For an unknown choice, radiation model or integrator.
    """
    if engine not in ("auto", "engine", "simulator"):
        raise ValueError(f"engine must be 'auto', 'engine' or 'simulator', got {engine!r}")
    if not engine_supports(radiation, integrator):
        raise ValueError(
            f"radiation={radiation!r}, integrator={integrator!r}: expected a radiation model of "
            "ShipSetup and integrator 'rk4' or 'holloway'"
        )
    return engine != "simulator"


# ----------------------------------------------------------------------------- sea states
@dataclass(frozen=True)
class SeaSpec:
    """A sea state of the map, in JSON-friendly numbers.

    Parameters
    ----------
    kind : {"regular", "irregular"}
        Regular wave (``height`` H, ``wavelength`` λ or ``period`` T) or a JONSWAP sea
        (``height`` Hs, ``period`` Tp, ``gamma``, ``n_components``, ``spreading_s``).
    height : float
        H or Hs [m].
    period : float, optional
        T or Tp [s].
    wavelength : float, optional
        λ [m] (regular only; give it or ``period``).
    gamma : float
        JONSWAP peak enhancement γ [-] (irregular only).
    n_components : int
        Wave components (irregular only).
    ramp_time : float
        Start-up ramp T_f [s] (Matusiak eq. 12).
    spreading_s : float or None
        Cos-2s directional spreading exponent s [-] of a short-crested JONSWAP sea (each
        component's direction drawn from the spreading about β,
        :class:`~ship_gym.waves.sea_state.IrregularSea`); None: long-crested (irregular only).
    """

    kind: Literal["regular", "irregular"] = "regular"
    height: float = 10.5
    period: float | None = None
    wavelength: float | None = 262.5
    gamma: float = 3.3
    n_components: int = 50
    ramp_time: float = 50.0
    spreading_s: float | None = None

    def __post_init__(self) -> None:
        if self.kind not in ("regular", "irregular"):
            raise ValueError(f"sea kind must be 'regular' or 'irregular', got {self.kind!r}")
        if self.kind == "regular" and self.spreading_s is not None:
            raise ValueError("a regular wave is long-crested: spreading_s must be None")
        if self.kind == "irregular" and self.period is None:
            raise ValueError("an irregular sea needs its peak period Tp [s] (period=...)")
        self.to_sea()  # validates the numbers (steepness, positivity…)

    def to_sea(self, phase: float = 0.0) -> RegularWave | IrregularSea:
        """The sea-state object (heading set later by the simulator builder).

        Parameters
        ----------
        phase : float
            Regular-wave phase ε [rad] (ignored for an irregular sea).
        """
        if self.kind == "regular":
            return self._regular_wave(phase)
        assert self.period is not None  # an irregular sea's Tp (checked in __post_init__)
        return IrregularSea(
            hs=self.height,
            tp=float(self.period),
            gamma=self.gamma,
            n_components=int(self.n_components),
            ramp_time=self.ramp_time,
            spreading_s=None if self.spreading_s is None else float(self.spreading_s),
        )

    def _regular_wave(self, phase: float = 0.0) -> RegularWave:
        period = None if self.wavelength is not None else self.period
        return RegularWave(
            height=self.height,
            period=period,
            wavelength=self.wavelength,
            phase=phase,
            ramp_time=self.ramp_time,
        )

    @property
    def label(self) -> str:
        """Short human-readable name, e.g. ``"regular H=10.5 m λ=262.5 m"``."""
        if self.kind == "regular":
            return f"regular H={self.height:g} m λ={self._regular_wave().wavelength:.1f} m"
        crest = "" if self.spreading_s is None else f" cos-2s s={self.spreading_s:g}"
        return f"JONSWAP Hs={self.height:g} m Tp={self.period:g} s{crest}"

    @classmethod
    def parse(cls, text: str) -> SeaSpec:
        """Parse ``"regular:H:λ"`` (height [m], wavelength [m]) or ``"jonswap:Hs:Tp"``.

        Raises
        ------
        ValueError
            For any other form.
        """
        parts = text.split(":")
        try:
            if len(parts) == 3 and parts[0] == "regular":
                return cls("regular", float(parts[1]), wavelength=float(parts[2]))
            if len(parts) == 3 and parts[0] in ("jonswap", "irregular"):
                return cls("irregular", float(parts[1]), period=float(parts[2]), wavelength=None)
        except ValueError as exc:
            raise ValueError(f"bad sea state {text!r}: {exc}") from None
        raise ValueError(
            f"bad sea state {text!r}; expected 'regular:H:lambda' (H, λ in m) or "
            "'jonswap:Hs:Tp' (Hs in m, Tp in s)"
        )


# ----------------------------------------------------------------------------- configuration
@dataclass(frozen=True)
class CapsizeMapConfig:
    """Everything that defines a capsize map (and is checked against a results file).

    Parameters
    ----------
    hull : str
        Library hull name.
    hull_overrides : dict
        Loading condition: keyword overrides of the hull builder, e.g. ``{"kg": 10.1}`` [m].
    database : str
        Hydrodynamic database: "auto" (the ship's own), a bundled name or a path.
    headings_deg : tuple of float
        Relative wave headings β [deg] (0 following, 180 head seas).
    froude_numbers : tuple of float
        Fn = U/√(gL) > 0 [-].
    seas : tuple of SeaSpec
        Sea states.
    seeds : tuple of int
        Random seeds (wave phases) per cell.
    duration : float
        Simulated time per run [s] (multiple of ``dt``).
    dt : float
        Physics time step [s].
    integrator : {"rk4", "holloway"}
        Time integrator.
    radiation : {"state_space", "convolution", "2a", "2b", "none"}
        Radiation model.
    capsize_angle_deg : float, optional
        |φ| that counts as capsize [deg]; None: the vanishing angle of the loading condition.
    record_every : int
        Steps between the samples used for the roll statistics.
    initial_heel_deg : float
        Each seed starts heeled by an angle drawn uniform in ±this [deg] (from the seed's
        generator, after the wave draws, so the seas are those of the same seed without it):
        an instability (parametric or synchronous roll) then grows from a stated disturbance
        instead of from round-off, whose growth time depends on the platform and the
        duration. 0 (default): upright, as before this option existed.
    """

    hull: str = "s175"
    hull_overrides: dict = field(default_factory=dict)
    database: str = "auto"
    headings_deg: tuple[float, ...] = (0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0)
    froude_numbers: tuple[float, ...] = (0.1, 0.2, 0.3)
    seas: tuple[SeaSpec, ...] = (SeaSpec(),)
    seeds: tuple[int, ...] = (0,)
    duration: float = 720.0
    dt: float = 0.1
    integrator: IntegratorName = "rk4"
    radiation: Literal["state_space", "convolution", "2a", "2b", "none"] = "state_space"
    capsize_angle_deg: float | None = None
    record_every: int = 5
    initial_heel_deg: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "headings_deg", tuple(float(h) for h in self.headings_deg))
        object.__setattr__(self, "froude_numbers", tuple(float(f) for f in self.froude_numbers))
        object.__setattr__(self, "seeds", tuple(int(s) for s in self.seeds))
        object.__setattr__(self, "seas", tuple(self.seas))
        if not isinstance(self.hull_overrides, dict) or not all(
            isinstance(k, str) for k in self.hull_overrides
        ):
            raise ValueError(
                f"hull_overrides must be a dict of str keys, got {self.hull_overrides!r}"
            )
        for name in ("headings_deg", "froude_numbers", "seas", "seeds"):
            if len(getattr(self, name)) == 0:
                raise ValueError(f"{name} must not be empty")
        if not all(np.isfinite(h) and -360.0 <= h <= 360.0 for h in self.headings_deg):
            raise ValueError(f"headings_deg must be within ±360 deg, got {self.headings_deg!r}")
        if not all(np.isfinite(f) and 0.0 < f < 1.0 for f in self.froude_numbers):
            raise ValueError(
                f"froude_numbers must lie in (0, 1) (the autopilot needs headway), "
                f"got {self.froude_numbers!r}"
            )
        if not all(isinstance(s, SeaSpec) for s in self.seas):
            raise ValueError("seas must be SeaSpec objects")
        if not (np.isfinite(self.dt) and self.dt > 0.0):
            raise ValueError(f"dt must be a positive time step [s], got {self.dt!r}")
        n = round(self.duration / self.dt)
        if n < 1 or abs(n * self.dt - self.duration) > 1e-9 * max(1.0, self.duration):
            raise ValueError(
                f"duration {self.duration!r} s must be a positive multiple of dt = {self.dt} s"
            )
        if self.capsize_angle_deg is not None and not 0.0 < self.capsize_angle_deg <= 180.0:
            raise ValueError(
                f"capsize_angle_deg must be in (0, 180] deg or None, got {self.capsize_angle_deg!r}"
            )
        if int(self.record_every) < 1:
            raise ValueError(f"record_every must be >= 1, got {self.record_every!r}")
        heel = self.initial_heel_deg
        if not (isinstance(heel, int | float) and math.isfinite(heel) and 0.0 <= heel <= 30.0):
            raise ValueError(
                f"initial_heel_deg must be a heel in [0, 30] deg (a disturbance, not a loading), "
                f"got {heel!r}"
            )
        object.__setattr__(self, "initial_heel_deg", float(heel))

    def to_dict(self) -> dict:
        """JSON-ready dict (with the results-file format version)."""
        d = dataclasses.asdict(self)
        for sea in d["seas"]:  # long-crested seas read as before spreading_s existed
            if sea["spreading_s"] is None:
                del sea["spreading_s"]
        if d["initial_heel_deg"] == 0.0:  # upright maps read as before the option existed
            del d["initial_heel_deg"]
        d["format_version"] = FORMAT_VERSION
        return json.loads(json.dumps(d))

    @classmethod
    def from_dict(cls, d: dict) -> CapsizeMapConfig:
        """Inverse of :meth:`to_dict`."""
        d = dict(d)
        d.pop("format_version", None)
        d["seas"] = tuple(SeaSpec(**s) for s in d["seas"])
        for key in ("headings_deg", "froude_numbers", "seeds"):
            d[key] = tuple(d[key])
        return cls(**d)

    def cells(self) -> list[Cell]:
        """All cells in a fixed order (sea, heading, Froude number, seed)."""
        return [
            Cell(i_sea, i_h, i_f, i_s)
            for i_sea in range(len(self.seas))
            for i_h in range(len(self.headings_deg))
            for i_f in range(len(self.froude_numbers))
            for i_s in range(len(self.seeds))
        ]


@dataclass(frozen=True)
class Cell:
    """Indices of one run in a :class:`CapsizeMapConfig` (sea, heading, Froude number, seed)."""

    sea: int
    heading: int
    froude: int
    seed: int

    @property
    def key(self) -> str:
        """Unique key of the cell in a results file."""
        return f"{self.sea}/{self.heading}/{self.froude}/{self.seed}"


# ----------------------------------------------------------------------------- simulation
def capsize_angle_of(hull: str, hull_overrides: dict | None = None) -> float:
    """Angle of vanishing stability [deg] of a loading condition (GZ from 0 to 90° by 5°).

    Raises
    ------
    ValueError
        If GZ stays positive up to 90° (no capsize angle from the GZ curve: give one).
    """
    from ship_gym.hull import righting_arm
    from ship_gym.ship import hull_of

    curve = righting_arm(hull_of(hull, **(hull_overrides or {})), np.arange(0.0, 90.1, 5.0))
    if not np.isfinite(curve.vanishing_angle_deg):
        raise ValueError(
            f"{hull} {hull_overrides or {}}: GZ stays positive up to 90 deg; give "
            "capsize_angle_deg explicitly"
        )
    return float(curve.vanishing_angle_deg)


@dataclass(frozen=True)
class RunOutcome:
    """What one run did.

    Attributes
    ----------
    capsized : bool
        Whether the run ended in capsize.
    reason : {"none", "roll", "pitch", "diverged"}
        Why it ended early: ``"pitch"`` is a "capsize" whose recorded pitch passed ±90° (a
        pitch-pole: the Euler angles flip through θ = ±90°, so the roll criterion fired with
        it). For a ship this means the run left the validity of the model (e.g. surf-riding
        at high speed, :mod:`ship_gym.hydro.forward_speed`) — read it as "not a result".
    time_to_capsize : float or None
        Time of capsize [s] (None without capsize).
    max_abs_roll_deg, rms_roll_deg : float
        max |φ| over the run and RMS φ after the ramp [deg].
    max_abs_pitch_deg : float
        max |θ| [deg].
    max_heading_deviation_deg : float
        max |ψ − ψ_ref| [deg].
    mean_speed : float
        Mean surge speed u after the ramp [m/s].
    simulated_time : float
        Time actually simulated [s].
    """

    capsized: bool
    reason: str
    time_to_capsize: float | None
    max_abs_roll_deg: float
    rms_roll_deg: float
    max_abs_pitch_deg: float
    max_heading_deviation_deg: float
    mean_speed: float
    simulated_time: float


def _outcome(
    series: dict[str, np.ndarray],
    reason: str,
    t_capsize: float | None,
    simulated_time: float,
    *,
    heading_command: float,
    stats_after: float,
) -> RunOutcome:
    """The statistics of a recorded run (the same for both paths)."""
    t, eta, nu = series["t"], series["eta"], series["nu"]
    late = t >= stats_after
    if not late.any():
        late = np.ones_like(t, bool)
    dev = np.angle(np.exp(1j * (eta[:, 5] - heading_command)))
    if reason == "roll" and np.any(np.abs(eta[:, 4]) >= 0.5 * math.pi):
        reason = "pitch"  # a pitch-pole (RunOutcome): outside the model, not a roll capsize
    return RunOutcome(
        capsized=reason != "none",
        reason=reason,
        time_to_capsize=None if t_capsize is None else float(t_capsize),
        max_abs_roll_deg=float(np.degrees(np.max(np.abs(eta[:, 3])))),
        rms_roll_deg=float(np.degrees(np.sqrt(np.mean(eta[late, 3] ** 2)))),
        max_abs_pitch_deg=float(np.degrees(np.max(np.abs(eta[:, 4])))),
        max_heading_deviation_deg=float(np.degrees(np.max(np.abs(dev)))),
        mean_speed=float(np.mean(nu[late, 0])),
        simulated_time=float(simulated_time),
    )


def simulate_until_capsize(
    sim: Simulator | BatchSimulator,
    duration: float,
    capsize_angle: float,
    *,
    heading_command: float = 0.0,
    record_every: int = 1,
    stats_after: float = 0.0,
    progress: bool = False,
) -> tuple[RunOutcome, dict[str, np.ndarray]]:
    """Step a simulator until ``duration`` or capsize, recording the motions.

    The ship is recorded at its initial state, every ``record_every`` steps and at the step
    that ends the run (capsize, or the last valid state before a divergence); the statistics of
    the :class:`RunOutcome` are taken over these samples. Capsize is checked after every step.

    Parameters
    ----------
    sim : Simulator or BatchSimulator
        A built simulator at its initial state: the single-ship
        :class:`~ship_gym.engine.simulator.Simulator` (stepped in Python), or a one-ship
        :class:`~ship_gym.engine.batch.BatchSimulator`, run by
        :func:`simulate_ships_until_capsize` (same results to rounding).
    duration : float
        Simulated time [s].
    capsize_angle : float
        |φ| beyond which the ship has capsized [rad].
    heading_command : float
        Autopilot set-point ψ_ref [rad] (ignored without an autopilot).
    record_every : int
        Record every n-th step.
    stats_after : float
        RMS roll and mean speed are taken over t ≥ ``stats_after`` [s] (e.g. the ramp time).
    progress : bool
        tqdm progress bar.

    Returns
    -------
    RunOutcome, dict
        The outcome and the recorded series ``t`` [s], ``eta`` (n, 6), ``nu`` (n, 6),
        ``rudder`` (n,) [rad] (applied rudder angle where a rudder exists, else NaN).

    Raises
    ------
    ValueError
        For a BatchSimulator of more than one ship (use :func:`simulate_ships_until_capsize`).
    """
    from ship_gym.engine.batch import BatchSimulator

    if isinstance(sim, BatchSimulator):
        if sim.n_ships != 1:
            raise ValueError(
                f"simulate_until_capsize runs one ship; this BatchSimulator has {sim.n_ships} "
                "(use simulate_ships_until_capsize)"
            )
        return simulate_ships_until_capsize(
            sim,
            duration,
            capsize_angle,
            heading_command=heading_command,
            record_every=record_every,
            stats_after=stats_after,
            progress=progress,
        )[0]
    n = round(duration / sim.dt)
    sim.commands = {**sim.commands, "heading": float(heading_command)}
    rec_t, rec_eta, rec_nu, rec_rudder = [], [], [], []
    rudder = _rudder_probe(sim)

    def record() -> None:
        rec_t.append(sim.t)
        rec_eta.append(sim.eta.copy())
        rec_nu.append(sim.nu.copy())
        rec_rudder.append(rudder())

    from ship_gym.engine.simulator import SimulationDiverged

    steps: Iterable[int] = range(n)
    if progress:
        from tqdm import tqdm

        steps = tqdm(steps, desc="simulating", unit="step", mininterval=0.5)
    record()
    reason = "none"
    t_capsize = None
    for i in steps:
        try:
            sim.step()
        except SimulationDiverged:
            reason, t_capsize = "diverged", sim.t + sim.dt
            record()
            break
        if abs(sim.eta[3]) > capsize_angle:
            reason, t_capsize = "roll", sim.t
            record()
            break
        if (i + 1) % record_every == 0:
            record()
    series = {
        "t": np.array(rec_t),
        "eta": np.array(rec_eta),
        "nu": np.array(rec_nu),
        "rudder": np.array(rec_rudder),
    }
    outcome = _outcome(
        series,
        reason,
        t_capsize,
        sim.t,
        heading_command=heading_command,
        stats_after=stats_after,
    )
    return outcome, series


def simulate_ships_until_capsize(
    sim: BatchSimulator,
    duration: float,
    capsize_angle: float,
    *,
    heading_command: float = 0.0,
    record_every: int = 1,
    stats_after: float = 0.0,
    progress: bool = False,
) -> list[tuple[RunOutcome, dict[str, np.ndarray]]]:
    """:func:`simulate_until_capsize` for every ship of a batch, on the engine.

    The ships advance together by chunks of ``record_every`` physics steps, one
    :meth:`~ship_gym.engine.batch.BatchSimulator.advance` call each (one compiled call with the
    compiled backend). Its reductions tell which ship had a step with |φ| > ``capsize_angle``
    (``danger_steps``) or diverged in the chunk; such a ship is stopped (held by the engine's
    per-ship freeze, its ``diverged`` flag, which this function restores at the end to the true
    divergences). A ship that capsized inside a chunk is then *replayed*: reset to its initial
    state and advanced by the same chunks up to that one (bit-identical: the engine's result per
    ship does not depend on the chunk split or on the other ships), then step by step up to its
    first step beyond the angle. Time to capsize, records and final state are therefore those of
    the step-by-step run (:func:`simulate_until_capsize` on the Simulator gives the same to
    rounding); the replay costs at most the simulated time to capsize of those ships (none with
    ``record_every`` = 1). Ships that diverge stop at their last valid state, time to capsize
    that time + Δt. On the engine's numpy backend (force models without a compiled version;
    none in the capsize studies) the ships advance one step per call, with no replay.

    Parameters
    ----------
    sim : BatchSimulator
        N ships at a reset state (freshly built, or :meth:`~BatchSimulator.reset` with no step
        since): the replay restarts a ship from there.
    duration : float
        Simulated time [s].
    capsize_angle : float
        |φ| beyond which a ship has capsized [rad].
    heading_command : float
        Autopilot set-point ψ_ref [rad] of every ship (ignored without an autopilot).
    record_every : int
        Record every n-th step (also the chunk length of the engine calls).
    stats_after : float
        RMS roll and mean speed are taken over t ≥ ``stats_after`` [s].
    progress : bool
        tqdm progress bar over the steps.

    Returns
    -------
    list of (RunOutcome, dict)
        Per ship, as :func:`simulate_until_capsize`.

    Raises
    ------
    ValueError
        If a ship has stepped since its reset, or ``record_every`` < 1.
    RuntimeError
        If a replay does not reproduce its ship's run (an engine that is not deterministic).
    """
    n_ships = sim.n_ships
    every = int(record_every)
    if every < 1:
        raise ValueError(f"record_every must be >= 1, got {record_every!r}")
    if np.any(sim.n_steps != 0) or sim.diverged.any():
        raise ValueError(
            "simulate_ships_until_capsize needs every ship at a reset state (freshly built or "
            "reset, no step since): a ship that capsizes inside a chunk is replayed from it"
        )
    n = round(duration / sim.dt)
    sim.commands = {**sim.commands, "heading": np.full(n_ships, float(heading_command))}
    t0, eta0, nu0 = sim.t.copy(), sim.eta.copy(), sim.nu.copy()
    rudder = _batch_rudder_probe(sim)
    rec: list[dict[str, list]] = [
        {"t": [], "eta": [], "nu": [], "rudder": []} for _ in range(n_ships)
    ]

    def record(ships: Iterable[int]) -> None:
        angles = rudder()
        for s in ships:
            rec[s]["t"].append(float(sim.t[s]))
            rec[s]["eta"].append(sim.eta[s].copy())
            rec[s]["nu"].append(sim.nu[s].copy())
            rec[s]["rudder"].append(float(angles[s]))

    reason = ["none"] * n_ships
    t_capsize: list[float | None] = [None] * n_ships
    diverged = np.zeros(n_ships, dtype=bool)  # true divergences (the rest of the flags: frozen)
    capsize_chunk: dict[int, int] = {}  # ship → chunk in which it capsized (to replay)
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=n, desc=f"simulating {n_ships} ships", unit="step", mininterval=0.5)
    record(range(n_ships))
    try:
        # chunks of one recording interval; on the numpy backend (stepped in Python anyway, and
        # bit-identical per ship only for the same set of running ships) single steps: no replay
        length = every if sim.compiled else 1
        done, chunk = 0, 0
        while done < n and not sim.diverged.all():
            k = min(length, n - done)
            ran = np.flatnonzero(~sim.diverged)
            red = sim.advance(k, danger_roll=capsize_angle)
            done += k
            for s in (int(x) for x in ran):
                if red.danger_steps[s] > 0:  # capsized (before any divergence in the chunk)
                    if k == 1:  # the chunk is the step
                        reason[s], t_capsize[s] = "roll", float(sim.t[s])
                        record([s])
                    else:
                        capsize_chunk[s] = chunk
                    sim.diverged[s] = True  # stop it here
                elif red.diverged[s]:
                    reason[s], t_capsize[s] = "diverged", float(sim.t[s]) + sim.dt
                    diverged[s] = True
                    record([s])
                elif done % every == 0:
                    record([s])
            chunk += 1
            if bar is not None:
                bar.update(k)
        if capsize_chunk:
            _replay_capsizes(sim, capsize_chunk, every, capsize_angle, (t0, eta0, nu0), rec)
            for s in capsize_chunk:
                reason[s], t_capsize[s] = "roll", float(sim.t[s])
    finally:
        sim.diverged[:] = diverged
        if bar is not None:
            bar.close()
    out = []
    for s in range(n_ships):
        series = {key: np.array(values) for key, values in rec[s].items()}
        outcome = _outcome(
            series,
            reason[s],
            t_capsize[s],
            float(sim.t[s]),
            heading_command=heading_command,
            stats_after=stats_after,
        )
        out.append((outcome, series))
    return out


def _replay_capsizes(
    sim: BatchSimulator,
    capsize_chunk: dict[int, int],
    every: int,
    capsize_angle: float,
    initial: tuple[np.ndarray, np.ndarray, np.ndarray],
    rec: list[dict[str, list]],
) -> None:
    """Find the capsize step of the ships ``capsize_chunk`` (ship → chunk index) by replay.

    Every other ship is frozen; the replayed ships restart from their initial states
    ``initial`` = (t, η, ν) and advance by chunks of ``every`` steps, each stepping singly
    through the chunk in which it capsized until its first step with |φ| > ``capsize_angle``
    (its state there is appended to its records ``rec`` and it is frozen).
    """
    t0, eta0, nu0 = initial
    ships = np.array(sorted(capsize_chunk), dtype=np.int64)
    sim.diverged[:] = True
    sim.reset(ships, eta=eta0[ships], nu=nu0[ships], t0=t0[ships])
    pending = {int(s) for s in ships}
    chunk = 0
    while pending:
        due = sorted(s for s in pending if capsize_chunk[s] == chunk)
        if due:
            waiting = [s for s in pending if s not in due]
            sim.diverged[waiting] = True
            for s in due:  # the replay is at the start of the chunk: the last record
                if not (
                    float(sim.t[s]) == rec[s]["t"][-1]
                    and np.array_equal(sim.eta[s], rec[s]["eta"][-1])
                    and np.array_equal(sim.nu[s], rec[s]["nu"][-1])
                ):
                    raise RuntimeError(
                        f"the replay of ship {s} does not reproduce its run at t = "
                        f"{rec[s]['t'][-1]:.3f} s (the engine should be deterministic per ship)"
                    )
            left = list(due)
            for _ in range(every):
                red = sim.advance(1, danger_roll=capsize_angle)
                for s in list(left):
                    if red.danger_steps[s] > 0:
                        rec[s]["t"].append(float(sim.t[s]))
                        rec[s]["eta"].append(sim.eta[s].copy())
                        rec[s]["nu"].append(sim.nu[s].copy())
                        angles = _batch_rudder_probe(sim)()
                        rec[s]["rudder"].append(float(angles[s]))
                        sim.diverged[s] = True
                        left.remove(s)
                        pending.discard(s)
                    elif red.diverged[s]:
                        left.clear()  # reported below
                        break
                if not left:
                    break
            if left or any(s in pending for s in due):
                raise RuntimeError(
                    f"the replay of ships {due} does not capsize in chunk {chunk} as their run "
                    "did (the engine should be deterministic per ship)"
                )
            sim.diverged[waiting] = False
        if pending:
            red = sim.advance(every, danger_roll=capsize_angle)
            if red.diverged[list(pending)].any():
                raise RuntimeError(
                    "a replayed ship diverged where its run did not (the engine should be "
                    "deterministic per ship)"
                )
            chunk += 1


def _rudder_probe(sim: Simulator) -> Callable[[], float]:
    """A callable returning the applied rudder angle [rad] (NaN when there is no rudder)."""
    probe = _batch_rudder_probe(sim.engine)
    return lambda: float(probe()[0])


def _batch_rudder_probe(sim: BatchSimulator) -> Callable[[], np.ndarray]:
    """A callable returning the (N,) applied rudder angles [rad] (NaN without a rudder)."""
    from ship_gym.control.actuators import ServoSpec
    from ship_gym.engine.batch_control import BatchActuatedSurfaces

    for f in sim.forces:
        if isinstance(f, BatchActuatedSurfaces) and f.key == "rudder" and f.servo is not None:

            def angle(f: BatchActuatedSurfaces = f, servo: ServoSpec = f.servo) -> np.ndarray:
                return np.asarray(servo.applied(f.angle), dtype=float)

            return angle
    nan = np.full(sim.n_ships, math.nan)
    return lambda: nan


def autopilot_setup(
    hull: str,
    hull_overrides: dict,
    speed: float,
    *,
    radiation: RadiationName,
    integrator: IntegratorName,
    dt: float,
    database: str = "auto",
) -> ShipSetup:
    """The ship of the capsize studies: self-propelled, hull manoeuvring forces, rudder under the
    heading autopilot (this map and :mod:`ship_gym.analysis.matusiak`).

    Parameters
    ----------
    hull : str
        Library hull; ``hull_overrides`` its loading condition (copied).
    speed : float
        Speed U [m/s] (the self-propulsion rpm is set for it).
    radiation, integrator : str
        Radiation model and time integrator (:class:`~ship_gym.engine.ship.ShipSetup`).
    dt : float
        Physics step [s].
    database : str
        Hydrodynamic database: "auto" (the ship's own), a bundled name or a path.
    """
    from ship_gym.engine.ship import ShipSetup

    return ShipSetup(
        hull=hull,
        hull_overrides=dict(hull_overrides),
        database=database,
        speed=speed,
        radiation=radiation,
        integrator=integrator,
        dt=dt,
        propulsion=True,
        manoeuvring=True,
        rudder="autopilot",
    )


def cell_setup(config: CapsizeMapConfig, cell: Cell) -> tuple[ShipSetup, Any, float, Any]:
    """ShipSetup, sea, wave heading β [rad] and rng of a cell."""
    from ship_gym.ship import hull_of

    spec = config.seas[cell.sea]
    seed = config.seeds[cell.seed]
    rng = np.random.default_rng(seed)
    sea = (
        spec.to_sea(phase=float(rng.uniform(0.0, 2.0 * np.pi)))
        if spec.kind == "regular"
        else (spec.to_sea())
    )
    hull = hull_of(config.hull, **config.hull_overrides)
    speed = config.froude_numbers[cell.froude] * math.sqrt(hull.g * hull.particulars.lpp)
    setup = autopilot_setup(
        config.hull,
        config.hull_overrides,
        speed,
        radiation=config.radiation,
        integrator=config.integrator,
        dt=config.dt,
        database=config.database,
    )
    return setup, sea, math.radians(config.headings_deg[cell.heading]), rng


def build_cells_simulator(
    config: CapsizeMapConfig,
    cells: Sequence[Cell],
    *,
    backend: EngineBackend = "auto",
    steered: bool = True,
) -> BatchSimulator:
    """One :class:`~ship_gym.engine.batch.BatchSimulator` whose ship i is ``cells[i]``.

    The cells must share their sea state, heading and Froude number (they differ by seed: ship
    i has the wave field of seed i, drawn as in :func:`cell_setup`); each ship behaves as the
    cell's :func:`~ship_gym.engine.ship.build_simulator` would.

    Parameters
    ----------
    config : CapsizeMapConfig
        The map (radiation and integrator supported by the engine: :func:`engine_supports`).
    cells : sequence of Cell
        The cells (≥ 1).
    backend : {"auto", "compiled", "numpy"}
        Engine backend (:func:`~ship_gym.engine.batch.build_batch_simulator`).
    steered : bool
        Under the heading autopilot (the map's ship); False: no rudder at all.

    Raises
    ------
    ValueError
        If ``cells`` is empty or mixes seas, headings or Froude numbers.
    """
    from ship_gym.engine.batch import build_batch_simulator
    from ship_gym.engine.ship import wave_field_for

    if not cells:
        raise ValueError("cells must not be empty")
    groups = {(c.sea, c.heading, c.froude) for c in cells}
    if len(groups) != 1:
        raise ValueError(
            "the cells of one engine batch must share sea, heading and Froude number (they "
            f"differ by seed); got (sea, heading, froude) indices {sorted(groups)}"
        )
    fields = []
    heels = np.zeros(len(cells))
    for k, cell in enumerate(cells):
        setup, sea, beta, rng = cell_setup(config, cell)
        fields.append(wave_field_for(sea, beta, rng))
        heels[k] = initial_heel(config, rng)
    if not steered:
        setup = dataclasses.replace(setup, rudder="none")
    sim = build_batch_simulator(
        setup,
        fields,
        sea=sea,
        wave_heading=beta,
        backend=backend,
    )
    if config.initial_heel_deg > 0.0:
        eta = np.tile(sim.initial_eta, (len(cells), 1))
        eta[:, 3] = heels
        sim.reset(np.arange(len(cells)), eta=eta)
    return sim


def initial_heel(config: CapsizeMapConfig, rng: np.random.Generator) -> float:
    """A seed's initial heel [rad]: uniform in ±``config.initial_heel_deg`` from its generator
    (after its wave draws); 0 without drawing when the option is off."""
    if config.initial_heel_deg == 0.0:
        return 0.0
    return math.radians(float(rng.uniform(-config.initial_heel_deg, config.initial_heel_deg)))


def run_cells(
    config: CapsizeMapConfig,
    cells: Sequence[Cell],
    capsize_angle_deg: float,
    *,
    engine: EngineChoice = "auto",
    steered: bool = True,
) -> list[dict]:
    """Simulate cells of one (sea, heading, Froude number) and return their records.

    On the engine (:data:`EngineChoice`) the cells run as the ships of one batch
    (:func:`build_cells_simulator`, :func:`simulate_ships_until_capsize`), each with the result
    it has alone; with ``engine="simulator"`` one
    :class:`~ship_gym.engine.simulator.Simulator` after the other.

    Parameters
    ----------
    config : CapsizeMapConfig
        The map.
    cells : sequence of Cell
        Cells sharing sea, heading and Froude number.
    capsize_angle_deg : float
        |φ| counted as capsize [deg].
    engine : {"auto", "engine", "simulator"}
        Which path (:data:`EngineChoice`).
    steered : bool
        Under the heading autopilot; False: no rudder (on the engine only).

    Returns
    -------
    list of dict
        Per cell (in order): the :class:`RunOutcome` fields, ``speed`` [m/s], ``cpu_s`` [s]
        (the batch's CPU time, build included, divided by its cells), ``engine``
        (``"compiled"``, ``"numpy"`` or ``"simulator"``) and ``batch_size``.
    """
    cells = list(cells)
    if not use_engine(engine, config.radiation, config.integrator):
        if not steered:
            raise ValueError("an unsteered ship runs on the engine only (engine='auto')")
        return [_run_cell_simulator(config, c, capsize_angle_deg) for c in cells]
    if not cells:
        return []
    t0 = time.process_time()
    sim = build_cells_simulator(config, cells, steered=steered)
    setup, _, _, _ = cell_setup(config, cells[0])
    results = simulate_ships_until_capsize(
        sim,
        config.duration,
        math.radians(capsize_angle_deg),
        record_every=config.record_every,
        stats_after=config.seas[cells[0].sea].ramp_time,
    )
    cpu = (time.process_time() - t0) / len(cells)
    path = "compiled" if sim.compiled else "numpy"
    return [
        {
            **dataclasses.asdict(outcome),
            "speed": setup.speed,
            "cpu_s": cpu,
            "engine": path,
            "batch_size": len(cells),
        }
        for outcome, _ in results
    ]


def _run_cell_simulator(config: CapsizeMapConfig, cell: Cell, capsize_angle_deg: float) -> dict:
    """One cell on the single-ship reference :class:`~ship_gym.engine.simulator.Simulator`."""
    from ship_gym.engine.ship import build_simulator

    t0 = time.process_time()
    setup, sea, beta, rng = cell_setup(config, cell)
    sim = build_simulator(setup, sea, wave_heading=beta, rng=rng)
    if config.initial_heel_deg > 0.0:
        eta = np.asarray(sim.eta, float).copy()
        eta[3] = initial_heel(config, rng)
        sim.reset(eta=eta)
    spec = config.seas[cell.sea]
    outcome, _ = simulate_until_capsize(
        sim,
        config.duration,
        math.radians(capsize_angle_deg),
        record_every=config.record_every,
        stats_after=spec.ramp_time,
    )
    return {
        **dataclasses.asdict(outcome),
        "speed": setup.speed,
        "cpu_s": time.process_time() - t0,
        "engine": "simulator",
        "batch_size": 1,
    }


def run_cell(
    config: CapsizeMapConfig,
    cell: Cell,
    capsize_angle_deg: float,
    *,
    engine: EngineChoice = "auto",
) -> dict:
    """Simulate one cell and return its JSON-ready record (:func:`run_cells` of one cell).

    Parameters
    ----------
    config : CapsizeMapConfig
        The map.
    cell : Cell
        Which run.
    capsize_angle_deg : float
        |φ| counted as capsize [deg].
    engine : {"auto", "engine", "simulator"}
        Which path (:data:`EngineChoice`).
    """
    return run_cells(config, [cell], capsize_angle_deg, engine=engine)[0]


# ----------------------------------------------------------------------------- results file
def _read_lines(path: Path) -> tuple[dict | None, list[dict], int]:
    """Header, records and the byte length of the intact part of a results file."""
    raw = path.read_bytes()
    intact = raw.rfind(b"\n") + 1  # a torn last line (no newline) is not part of the file
    header = None
    records = []
    for k, line in enumerate(raw[:intact].decode("utf-8").splitlines()):
        if not line.strip():
            continue
        try:
            obj = json.loads(line)
        except json.JSONDecodeError as exc:
            raise ValueError(f"{path}: line {k + 1} is not valid JSON ({exc})") from None
        if k == 0:
            if "config" not in obj:
                raise ValueError(f"{path}: first line is not a capsize-map header")
            header = obj["config"]
        else:
            records.append(obj)
    return header, records, intact


def load_results(path: str | Path) -> tuple[CapsizeMapConfig, list[dict]]:
    """Configuration and finished-cell records of a results file.

    Raises
    ------
    FileNotFoundError, ValueError
        Missing file or not a capsize-map results file.
    """
    path = Path(path)
    header, records, _ = _read_lines(path)
    if header is None:
        raise ValueError(f"{path}: empty results file")
    return CapsizeMapConfig.from_dict(header), records


def _config_mismatch(old: dict, new: dict) -> list[str]:
    keys = sorted(set(old) | set(new))
    return [
        f"{k}: file has {old.get(k)!r}, run has {new.get(k)!r}"
        for k in keys
        if old.get(k) != new.get(k)
    ]


def _append_record(path: Path, record: dict) -> None:
    with open(path, "a", encoding="utf-8") as fh:
        fh.write(json.dumps(record, default=float) + "\n")
        fh.flush()
        os.fsync(fh.fileno())


@dataclass(frozen=True)
class CapsizeMapResult:
    """A finished (or partly finished) map.

    Attributes
    ----------
    config : CapsizeMapConfig
        The map.
    records : list of dict
        One record per finished cell (``key``, indices, heading, Fn, seed, outcome fields).
    capsize_angle_deg : float
        Capsize angle used [deg].
    n_run : int
        Cells simulated by this call (the others were read back).
    wall_s : float
        Wall time of this call [s].
    """

    config: CapsizeMapConfig
    records: list[dict]
    capsize_angle_deg: float
    n_run: int
    wall_s: float

    def summary(self) -> list[dict]:
        """:func:`summarise` of the records."""
        return summarise(self.config, self.records)


@contextlib.contextmanager
def single_threaded_blas() -> Iterator[None]:
    """Run the block with one BLAS thread in every BLAS library loaded (restored afterwards).

    Multithreaded OpenBLAS splits some products differently from the single-threaded one, and the
    last-bit differences grow over a long nonlinear run (measured: 1e-8 relative in the mean
    speed, 1e-4° in a 1e-3° roll). joblib's workers run with one BLAS thread each, so every cell
    runs with one thread whatever the process: serial and parallel maps are bit-identical.
    numpy and scipy each bundle their own OpenBLAS; ``threadpoolctl`` finds and limits both.
    """
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        yield


def _keyed(config: CapsizeMapConfig, cell: Cell, out: dict) -> dict:
    return {
        "key": cell.key,
        "sea": cell.sea,
        "heading_deg": config.headings_deg[cell.heading],
        "froude": config.froude_numbers[cell.froude],
        "seed": config.seeds[cell.seed],
        **out,
    }


def _run_keyed(runner: CellRunner, config: CapsizeMapConfig, cell: Cell, angle: float) -> dict:
    with single_threaded_blas():
        out = runner(config, cell, angle)
    return _keyed(config, cell, out)


def _run_keyed_one(
    runner: CellRunner, config: CapsizeMapConfig, cell: Cell, angle: float
) -> list[dict]:
    return [_run_keyed(runner, config, cell, angle)]


def _run_keyed_batch(
    config: CapsizeMapConfig, cells: list[Cell], angle: float, engine: EngineChoice
) -> list[dict]:
    with single_threaded_blas():
        outs = run_cells(config, cells, angle, engine=engine)
    return [_keyed(config, c, o) for c, o in zip(cells, outs, strict=True)]


MAX_BATCH = 16
"""Most cells (seeds) per engine batch of :func:`run_capsize_map` (results are written per
batch: this bounds what an interruption loses)."""


def _batches(pending: list[Cell], n_jobs: int) -> list[list[Cell]]:
    """Pending cells grouped by (sea, heading, Froude number), in order, cut to at most
    :data:`MAX_BATCH` cells — and, with ``n_jobs`` > 1, to ⌈len(pending)/n_jobs⌉ so that every
    worker has work."""
    groups: dict[tuple[int, int, int], list[Cell]] = {}
    for c in pending:
        groups.setdefault((c.sea, c.heading, c.froude), []).append(c)
    size = max(1, min(MAX_BATCH, math.ceil(len(pending) / max(1, n_jobs))))
    return [g[i : i + size] for g in groups.values() for i in range(0, len(g), size)]


def run_capsize_map(
    config: CapsizeMapConfig,
    results_path: str | Path,
    *,
    n_jobs: int = 1,
    progress: bool = True,
    cell_runner: CellRunner | None = None,
    engine: EngineChoice = "auto",
) -> CapsizeMapResult:
    """Run (or resume) a capsize map, writing the cells as they finish.

    With the default runner, the pending seeds of each (sea, heading, Froude number) run as one
    engine batch (:func:`run_cells`; at most :data:`MAX_BATCH` seeds, split further so that
    ``n_jobs`` workers all have work) and
    their records are written when the batch finishes; with ``engine="simulator"`` and with a
    ``cell_runner``, cell by cell. A cell's result
    does not depend on its batch.

    Parameters
    ----------
    config : CapsizeMapConfig
        The map.
    results_path : str or Path
        JSON-lines results file (created with a configuration header, or resumed).
    n_jobs : int
        Parallel worker processes (joblib/loky); 1 runs in this process.
    progress : bool
        tqdm progress bar over cells.
    cell_runner : callable, optional
        ``runner(config, cell, capsize_angle_deg) -> dict``, called per cell (default: the
        batched :func:`run_cells`); must be picklable for ``n_jobs > 1``.
    engine : {"auto", "engine", "simulator"}
        Path of the default runner (:data:`EngineChoice`; ignored with a ``cell_runner``).

    Raises
    ------
    ValueError
        If the results file holds a different configuration, or ``n_jobs < 1``.
    """
    if int(n_jobs) < 1:
        raise ValueError(f"n_jobs must be >= 1, got {n_jobs!r}")
    batched = cell_runner is None and use_engine(engine, config.radiation, config.integrator)
    runner: CellRunner = (
        functools.partial(run_cell, engine=engine) if cell_runner is None else cell_runner
    )
    path = Path(results_path)
    wanted = config.to_dict()
    t0 = time.perf_counter()
    done: dict[str, dict] = {}
    if path.exists():
        header, records, intact = _read_lines(path)
        if header is None:
            raise ValueError(f"{path}: exists but has no configuration header; remove it")
        diff = _config_mismatch(header, wanted)
        if diff:
            raise ValueError(
                f"{path} holds a capsize map with a different configuration "
                f"({'; '.join(diff)}); use another results file or remove this one"
            )
        if intact != path.stat().st_size:
            with open(path, "r+b") as fh:  # cut a torn last line before appending
                fh.truncate(intact)
                os.fsync(fh.fileno())
        done = {r["key"]: r for r in records}
    else:
        from ship_gym.io_utils import atomic_write_text

        atomic_write_text(path, json.dumps({"config": wanted}) + "\n")
    if config.capsize_angle_deg is not None:
        angle = float(config.capsize_angle_deg)
    else:
        angle = capsize_angle_of(config.hull, config.hull_overrides)
    pending = [c for c in config.cells() if c.key not in done]
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=len(pending), desc="capsize map", unit="cell")
    # (function, its arguments): a batch of cells or one cell, each giving a list of records
    tasks: list[tuple[Callable[..., list[dict]], tuple[Any, ...]]]
    if batched:
        tasks = [
            (_run_keyed_batch, (config, b, angle, engine)) for b in _batches(pending, int(n_jobs))
        ]
    else:
        tasks = [(_run_keyed_one, (runner, config, c, angle)) for c in pending]
    try:
        if n_jobs == 1 or len(tasks) <= 1:
            results: Iterable[list[dict]] = (fn(*a) for fn, a in tasks)
        else:
            from joblib import Parallel, delayed

            results = Parallel(n_jobs=int(n_jobs), return_as="generator_unordered")(
                delayed(fn)(*a) for fn, a in tasks
            )
        for batch in results:
            for rec in batch:
                _append_record(path, rec)
                done[rec["key"]] = rec
            if bar is not None:
                bar.update(len(batch))
    finally:
        if bar is not None:
            bar.close()
    order = {c.key: i for i, c in enumerate(config.cells())}
    records = sorted(done.values(), key=lambda r: order[r["key"]])
    return CapsizeMapResult(config, records, angle, len(pending), time.perf_counter() - t0)


# ----------------------------------------------------------------------------- summary, plot
def summarise(config: CapsizeMapConfig, records: list[dict]) -> list[dict]:
    """Per (sea, heading, Froude number): capsize probability over seeds and roll statistics.

    Returns
    -------
    list of dict
        ``sea``, ``heading_deg``, ``froude``, ``n`` (seeds finished), ``capsize_probability``,
        ``n_roll`` / ``n_diverged`` (capsizes by reason), ``max_abs_roll_deg`` (max over seeds),
        ``rms_roll_deg`` (mean over seeds), ``mean_time_to_capsize`` [s] (NaN without one).
    """
    groups: dict[tuple[int, float, float], list[dict]] = {}
    for r in records:
        groups.setdefault((r["sea"], r["heading_deg"], r["froude"]), []).append(r)
    out = []
    for i_sea in range(len(config.seas)):
        for h in config.headings_deg:
            for fn in config.froude_numbers:
                rs = groups.get((i_sea, h, fn), [])
                if not rs:
                    continue
                times = [r["time_to_capsize"] for r in rs if r["capsized"]]
                out.append(
                    {
                        "sea": i_sea,
                        "heading_deg": h,
                        "froude": fn,
                        "n": len(rs),
                        "capsize_probability": sum(r["capsized"] for r in rs) / len(rs),
                        "n_roll": sum(r["reason"] == "roll" for r in rs),
                        "n_diverged": sum(r["reason"] == "diverged" for r in rs),
                        "max_abs_roll_deg": max(r["max_abs_roll_deg"] for r in rs),
                        "rms_roll_deg": float(np.mean([r["rms_roll_deg"] for r in rs])),
                        "mean_time_to_capsize": float(np.mean(times)) if times else math.nan,
                    }
                )
    return out


def plot_capsize_map(result: CapsizeMapResult, path: str | Path) -> Path:
    """Polar capsize diagram per sea state: heading β (0° following at the top, clockwise) vs
    Froude number (radius); cell colour the capsize probability, label the max |φ| [deg]."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LinearSegmentedColormap

    config = result.config
    summary = summarise(config, result.records)
    n = len(config.seas)
    fig, axes = plt.subplots(
        1, n, figsize=(5.2 * n + 0.8, 5.4), subplot_kw={"projection": "polar"}, squeeze=False
    )
    cmap = LinearSegmentedColormap.from_list("capsize", ["#2c7bb6", "#ffffbf", "#d7191c"])
    heads = np.radians(np.array(config.headings_deg))
    fns = np.array(config.froude_numbers)
    dh = np.min(np.diff(np.sort(heads))) if len(heads) > 1 else np.radians(30.0)
    dfn = np.min(np.diff(np.sort(fns))) if len(fns) > 1 else 0.1
    for i_sea, ax in enumerate(axes[0]):
        ax.set_theta_zero_location("N")
        ax.set_theta_direction(-1)
        ax.set_rlabel_position(250)  # Fn tick labels on the port side, clear of 0–180° cells
        for row in (s for s in summary if s["sea"] == i_sea):
            th, fn = math.radians(row["heading_deg"]), row["froude"]
            ax.bar(
                th,
                dfn,
                width=dh,
                bottom=fn - dfn / 2,
                color=cmap(row["capsize_probability"]),
                edgecolor="k",
                lw=0.4,
            )
            ax.text(th, fn, f"{row['max_abs_roll_deg']:.0f}", ha="center", va="center", fontsize=7)
        ax.set_rlim(0.0, fns.max() + dfn / 2)
        ax.set_title(f"{config.seas[i_sea].label}\n(label: max |φ| [deg])", fontsize=9)
        ax.set_xlabel("Fn (radius), β (angle: 0° following, 180° head)", fontsize=8)
    sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0.0, 1.0))
    fig.colorbar(sm, ax=axes[0].tolist(), label="capsize probability", shrink=0.8)
    cond = ", ".join(f"{k} = {v}" for k, v in config.hull_overrides.items()) or "design"
    fig.suptitle(
        f"{config.hull} ({cond}), capsize |φ| > {result.capsize_angle_deg:.1f}°, "
        f"{config.duration:g} s, seeds {len(config.seeds)}",
        fontsize=10,
    )
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    from ship_gym.io_utils import atomic_write

    atomic_write(path, lambda p: fig.savefig(p, dpi=110, format="png"))
    plt.close(fig)
    return path
