"""Standard manoeuvring trials in calm water and the IMO standards for manoeuvrability.

Full-scale trials of IMO Resolution MSC.137(76) (2002), run on the assembled 6-DOF simulator
(:func:`ship_gym.engine.ship.build_simulator`: nonlinear Froude–Krylov + hydrostatics, Cummins
radiation memory, Ikeda roll damping, Holtrop–Mennen resistance, B-series propeller, Clarke hull
derivatives with cross-flow drag, rudder behind its servo), all six DOFs free:

* :func:`turning_circle` — rudder hard over (35°) from a steady straight run;
* :func:`zigzag` — δ/ψ zig-zags (10°/10°, 20°/20°);
* :func:`speed_trial` — commanded shaft speed → steady calm-water speed, with the surge balance;
* :func:`autopilot_step` — the heading autopilot holding a course and taking a heading step;
* :func:`imo_criteria` — the pass/fail table of MSC.137(76) §5.3–5.4.

Definitions (MSC/Circ.1053, explanatory notes to MSC.137(76))
--------------------------------------------------------------
The reference point is the midship point — the body origin O (amidships, on the centreline).
Distances are measured from O's position at the instant the rudder is *ordered* ("execute"),
in the frame of the original course (x ahead, y to the side of the turn):

* **advance**: x when the heading has changed by 90°; **transfer**: y at 90°;
* **tactical diameter**: y when the heading has changed by 180°;
* **steady turning diameter**: 2 U/|r| averaged over the last 30 s of the run (U = √(u² + v²);
  by default the run ends at 540° of heading change, where the S175's speed is still falling
  slowly — the surge time constant at 4 m/s is a few minutes);
* **initial turning**: track distance run when the heading has changed by 10° under 10° rudder
  (here: until the first reversal of the 10°/10° zig-zag, the same event);
* **overshoot angles** of a δ/ψ zig-zag: the heading excursion beyond the check angle ψ after
  a rudder reversal (first overshoot after the first reversal, second after the second).

Limits (MSC.137(76) §5.3–5.4), with L/V in seconds (L the length between perpendiculars [m],
V the test speed [m/s]):

* advance ≤ 4.5 L; tactical diameter ≤ 5 L; initial turning ≤ 2.5 L;
* 10°/10° first overshoot ≤ 10° if L/V < 10 s, ≤ 20° if L/V ≥ 30 s, else (5 + ½ L/V)°;
* 10°/10° second overshoot ≤ the first-overshoot limit + 15°;
* 20°/20° first overshoot ≤ 25°.

(The stopping ability, track reach ≤ 15 L, is not evaluated: the propeller's astern quadrant
is a crude mirror of the ahead curves, see :mod:`ship_gym.forces.propeller`.)

Procedure
---------
Each trial builds the ship at its test speed, sets the shaft speed so that the straight run is
steady *at* that speed (:func:`trim_shaft_speed`: the self-propulsion point of the propeller
helpers plus the drag of the rudder at 0°, ≈ 2 % of R_T for the S175, which the Holtrop–Mennen
resistance does not include), runs straight for ``settle`` seconds (sinkage, trim and the
radiation memory settle), then executes the manoeuvre with the servo-limited rudder
(±35°, 2.32 °/s). Commands and the engine (shaft speed) are held constant during the manoeuvre,
as in a trial.

Numerics and modelling sensitivity (S175 at 10.36 m/s, measured with ``scripts/manoeuvres.py
--dt-check --dof-check``): dt = 0.05 s and 0.1 s give the same metrics to < 0.01 %; holding
heave, roll and pitch changes them by ≤ 1.3 % (tactical diameter +1.0 %, 20°/20° overshoot
−1.3 %) — the model has no heel-dependent hull forces (Y_φ, N_φ), so roll acts only through
the inertial coupling and the rudder's roll-rate inflow; direct convolution instead of the
state-space radiation memory changes them by < 1 % (the fitted state-space memory has a small
spurious zero-frequency gain, which the convolution of the kernel nearly does not).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np
from scipy.optimize import brentq

from ship_gym.conventions import wrap_angle
from ship_gym.engine.ship import ShipSetup, build_simulator, propeller_of, trim_shaft_speed
from ship_gym.forces.propeller import Propeller
from ship_gym.ship import hull_of, load_ship

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from ship_gym.engine.simulator import Simulator

__all__ = [
    "Criterion",
    "HeadingStepResult",
    "SpeedTrialPoint",
    "SpeedTrialResult",
    "TurningCircleResult",
    "TurningMetrics",
    "ZigzagMetrics",
    "ZigzagResult",
    "autopilot_step",
    "format_criteria",
    "imo_criteria",
    "nomoto_of",
    "overshoot_limits",
    "plot_heading_step",
    "plot_speed_trial",
    "plot_turning_circle",
    "plot_zigzag",
    "report",
    "speed_trial",
    "trial_setup",
    "trim_shaft_speed",
    "turning_circle",
    "turning_metrics",
    "zigzag",
    "zigzag_metrics",
]

ADVANCE_LIMIT = 4.5
"""MSC.137(76) §5.3.1: advance ≤ 4.5 L."""

TACTICAL_DIAMETER_LIMIT = 5.0
"""MSC.137(76) §5.3.1: tactical diameter ≤ 5 L."""

INITIAL_TURNING_LIMIT = 2.5
"""MSC.137(76) §5.3.2: ≤ 2.5 L run until 10° heading change with 10° rudder."""

ZIGZAG20_FIRST_LIMIT_DEG = 25.0
"""MSC.137(76) §5.4.3: 20°/20° first overshoot ≤ 25°."""


# ------------------------------------------------------------------------------ set-up
def trial_setup(
    hull: str = "s175", speed: float | None = None, *, dt: float = 0.1, **overrides
) -> ShipSetup:
    """The set-up of a manoeuvring trial: 6 DOF free, calm water, state-space radiation,
    propulsion, hull manoeuvring forces and a commanded rudder.

    Parameters
    ----------
    hull : str
        Library hull.
    speed : float, optional
        Test speed [m/s]; default the ship's service speed (its ship file's ``[speed]``
        ``service_mps`` / ``service_froude``, Fn 0.25 if it gives none; S175: 10.358 m/s).
    dt : float
        Physics time step [s] (0.1 s: the S175 trial metrics differ from dt = 0.05 s by
        < 0.01 %).
    **overrides
        Further :class:`ShipSetup` fields (e.g. ``rudder="autopilot"``, ``free_dofs``).
    """
    if speed is None:
        speed = load_ship(hull).service_speed
    kw = {
        "hull": hull,
        "speed": float(speed),
        "radiation": "state_space",
        "dt": float(dt),
        "propulsion": True,
        "manoeuvring": True,
        "rudder": "command",
        **overrides,
    }
    return ShipSetup(**kw)


def _check_setup(setup: ShipSetup, rudder: str | None = "command") -> None:
    if not (setup.propulsion and setup.manoeuvring and setup.speed > 0.0):
        raise ValueError(
            "a manoeuvring trial needs propulsion=True, manoeuvring=True and a positive speed "
            f"(got propulsion={setup.propulsion}, manoeuvring={setup.manoeuvring}, "
            f"speed={setup.speed}); see trial_setup()"
        )
    if rudder is not None and setup.rudder != rudder:
        raise ValueError(f"this trial needs rudder={rudder!r}, got {setup.rudder!r}")


def capsize_angle(setup: ShipSetup) -> float:
    """The roll angle [rad] beyond which a trial counts as a capsize: the angle of vanishing
    stability of the setup's loading (calm-water GZ at free sinkage and trim, ≤ 90°)."""
    from ship_gym.envs.loading import loading_condition

    return math.radians(loading_condition(setup).vanishing_angle_deg)


def _capsized(sim: Simulator, limit: float) -> bool:
    """|φ| beyond ``limit`` [rad] or a non-finite state."""
    roll = float(sim.eta[3])
    return not (math.isfinite(roll) and abs(roll) <= limit and np.all(np.isfinite(sim.nu)))


def _has_actuator(sim: Simulator, name: str) -> str:
    """``name`` if the simulator has a servo-driven force model of that name (else ValueError)."""
    sim.actuator_angle(name)
    return name


def _prepare(
    setup: ShipSetup, *, settle: float, trim_approach: bool, rudder: str | None = "command"
) -> Simulator:
    _check_setup(setup, rudder)
    sim = build_simulator(setup)
    if rudder == "command":
        sim.commands = {**sim.commands, "rudder_command": 0.0}
    if trim_approach:
        trim_shaft_speed(sim, setup.speed)
    for _ in range(round(settle / sim.dt)):
        sim.step()
    return sim


class _Recorder:
    """Per-step record of a trial: time, position, attitude, velocities, rudder, order."""

    def __init__(self, sim: Simulator, rudder: str | None) -> None:
        self.sim = sim
        self.rudder = rudder
        self.t0 = sim.t
        self.x0, self.y0 = float(sim.eta[0]), float(sim.eta[1])
        self.psi0 = float(sim.eta[5])
        self.rows: list[tuple[float, ...]] = []
        self._psi = 0.0  # unwrapped heading change
        self._last = self.psi0

    @property
    def heading_change(self) -> float:
        """ψ − ψ₀ [rad], unwrapped."""
        return self._psi

    def record(self, order: float) -> None:
        s = self.sim
        self._psi += float(wrap_angle(s.eta[5] - self._last))
        self._last = float(s.eta[5])
        delta = s.actuator_angle(self.rudder) if self.rudder is not None else 0.0
        self.rows.append(
            (
                s.t - self.t0,
                s.eta[0] - self.x0,
                s.eta[1] - self.y0,
                self._psi,
                *s.nu,
                s.eta[3],
                s.eta[4],
                s.eta[2],
                delta,
                order,
            )
        )

    def arrays(self) -> dict[str, np.ndarray]:
        a = np.array(self.rows)
        c, s = math.cos(self.psi0), math.sin(self.psi0)
        north, east = a[:, 1], a[:, 2]
        return {
            "t": a[:, 0],
            "x": c * north + s * east,  # along the original course
            "y": -s * north + c * east,  # to starboard of it
            "psi": a[:, 3],
            "u": a[:, 4],
            "v": a[:, 5],
            "w": a[:, 6],
            "p": a[:, 7],
            "q": a[:, 8],
            "r": a[:, 9],
            "roll": a[:, 10],
            "pitch": a[:, 11],
            "heave": a[:, 12],
            "rudder": a[:, 13],
            "order": a[:, 14],
        }


def _progress(total: float, desc: str, enabled: bool):
    if not enabled:
        return None
    from tqdm import tqdm

    return tqdm(total=round(total), desc=desc, unit="s sim", mininterval=0.5, leave=False)


# ------------------------------------------------------------------------------ metrics
def _crossing(values: np.ndarray, level: float) -> tuple[int, float] | None:
    """First i and fraction f with values[i-1] + f (values[i] − values[i-1]) = level."""
    above = np.flatnonzero(values >= level)
    if above.size == 0:
        return None
    i = int(above[0])
    if i == 0:
        return 0, 1.0
    v0, v1 = values[i - 1], values[i]
    return i, float((level - v0) / (v1 - v0)) if v1 != v0 else 1.0


def _at(series: np.ndarray, where: tuple[int, float] | None) -> float:
    if where is None:
        return math.nan
    i, f = where
    if i == 0:
        return float(series[0])
    return float(series[i - 1] + f * (series[i] - series[i - 1]))


@dataclass(frozen=True)
class TurningMetrics:
    """Turning-circle metrics [m, s] (NaN where the heading change was not reached)."""

    advance: float
    transfer: float
    tactical_diameter: float
    time_to_90: float
    time_to_180: float


def turning_metrics(
    t: np.ndarray, x: np.ndarray, y: np.ndarray, heading_change: np.ndarray
) -> TurningMetrics:
    """Advance, transfer and tactical diameter of a turn (MSC/Circ.1053).

    Parameters
    ----------
    t : numpy.ndarray
        Times since the rudder order [s].
    x, y : numpy.ndarray
        Position of the reference point from its position at the order, along the original
        course and across it towards the side of the turn [m].
    heading_change : numpy.ndarray
        Heading change in the direction of the turn [rad] (increasing).

    Notes
    -----
    Values at 90° and 180° are interpolated linearly between samples.
    """
    t, x, y, h = (np.asarray(a, float) for a in (t, x, y, heading_change))
    c90 = _crossing(h, 0.5 * math.pi)
    c180 = _crossing(h, math.pi)
    return TurningMetrics(
        advance=_at(x, c90),
        transfer=_at(y, c90),
        tactical_diameter=_at(y, c180),
        time_to_90=_at(t, c90),
        time_to_180=_at(t, c180),
    )


@dataclass(frozen=True)
class ZigzagMetrics:
    """Zig-zag metrics.

    Attributes
    ----------
    overshoots_deg : tuple of float
        Overshoot after each rudder reversal [deg] (first, second, …).
    overshoot_times : tuple of float
        When each overshoot peak occurred [s].
    reversal_times : tuple of float
        Times of the rudder reversals [s].
    """

    overshoots_deg: tuple[float, ...]
    overshoot_times: tuple[float, ...]
    reversal_times: tuple[float, ...]

    @property
    def first_overshoot_deg(self) -> float:
        return self.overshoots_deg[0] if self.overshoots_deg else math.nan

    @property
    def second_overshoot_deg(self) -> float:
        return self.overshoots_deg[1] if len(self.overshoots_deg) > 1 else math.nan


def zigzag_metrics(
    t: np.ndarray,
    heading_change_deg: np.ndarray,
    reversal_times: Sequence[float],
    switch_deg: float,
) -> ZigzagMetrics:
    """Overshoot angles of a zig-zag from its heading record and rudder reversals.

    Parameters
    ----------
    t : numpy.ndarray
        Times [s].
    heading_change_deg : numpy.ndarray
        Heading change from the original course [deg], positive towards the side of the
        *first* rudder order.
    reversal_times : sequence of float
        Times of the rudder reversals [s] (the k-th reversal, k = 1, 2, …, turns the rudder
        towards the side opposite to the first order for odd k).
    switch_deg : float
        Check (switch) heading angle [deg] (> 0).

    Notes
    -----
    The k-th overshoot is max over [t_k, t_{k+1}] (or to the end of the record) of
    ±h − switch_deg (+ for odd k, − for even k): the excursion beyond the check angle.
    """
    t = np.asarray(t, float)
    h = np.asarray(heading_change_deg, float)
    rev = [float(v) for v in reversal_times]
    shoots, times = [], []
    for k, start in enumerate(rev):
        end = rev[k + 1] if k + 1 < len(rev) else math.inf
        sel = (t >= start) & (t <= end)
        if not np.any(sel):
            break
        sign = 1.0 if k % 2 == 0 else -1.0
        excursion = sign * h[sel]
        j = int(np.argmax(excursion))
        shoots.append(float(excursion[j] - switch_deg))
        times.append(float(t[sel][j]))
    return ZigzagMetrics(tuple(shoots), tuple(times), tuple(rev))


def overshoot_limits(length_over_speed: float) -> tuple[float, float, float]:
    """MSC.137(76) §5.4 overshoot limits [deg] at L/V [s]: (10°/10° first, 10°/10° second,
    20°/20° first)."""
    lv = float(length_over_speed)
    if not (math.isfinite(lv) and lv > 0.0):
        raise ValueError(f"L/V must be a positive time [s], got {length_over_speed!r}")
    if lv < 10.0:
        first = 10.0
    elif lv >= 30.0:
        first = 20.0
    else:
        first = 5.0 + 0.5 * lv
    return first, first + 15.0, ZIGZAG20_FIRST_LIMIT_DEG


# ------------------------------------------------------------------------------ results
@dataclass(frozen=True, eq=False)
class TurningCircleResult:
    """A turning-circle trial: series (from the rudder order) and metrics.

    Series (all (n,)): ``t`` [s], ``x``, ``y`` [m] (along / to the turning side of the original
    course, from the execute point), ``heading_change_deg`` (towards the turn), ``rudder_deg``
    (applied, signed), ``speed`` √(u² + v²) [m/s], ``yaw_rate_deg_s``, ``drift_deg``
    (β = atan2(−v, u), positive bow inside the turn), ``roll_deg`` (positive: heeled to the
    side of the turn).
    """

    rudder_order_deg: float
    approach_speed: float
    length: float
    shaft_speed: float
    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    heading_change_deg: np.ndarray
    rudder_deg: np.ndarray
    speed: np.ndarray
    yaw_rate_deg_s: np.ndarray
    drift_deg: np.ndarray
    roll_deg: np.ndarray
    metrics: TurningMetrics
    steady_diameter: float
    steady_speed: float
    steady_roll_deg: float
    max_outward_heel_deg: float
    max_inward_heel_deg: float
    wall_time: float = math.nan
    capsize_time: float = math.nan

    @property
    def capsized(self) -> bool:
        """The ship heeled beyond the angle of vanishing stability (at :attr:`capsize_time` [s]
        after the order; the trial stopped there)."""
        return math.isfinite(self.capsize_time)

    @property
    def advance_over_L(self) -> float:
        return self.metrics.advance / self.length

    @property
    def transfer_over_L(self) -> float:
        return self.metrics.transfer / self.length

    @property
    def tactical_diameter_over_L(self) -> float:
        return self.metrics.tactical_diameter / self.length

    @property
    def steady_diameter_over_L(self) -> float:
        return self.steady_diameter / self.length

    def summary(self) -> dict[str, float]:
        """The metrics as a flat dict (JSON-ready)."""
        m = self.metrics
        return {
            "rudder_deg": self.rudder_order_deg,
            "approach_speed_m_s": self.approach_speed,
            "advance_m": m.advance,
            "advance_over_L": self.advance_over_L,
            "transfer_over_L": self.transfer_over_L,
            "tactical_diameter_m": m.tactical_diameter,
            "tactical_diameter_over_L": self.tactical_diameter_over_L,
            "steady_diameter_over_L": self.steady_diameter_over_L,
            "time_to_90_s": m.time_to_90,
            "time_to_180_s": m.time_to_180,
            "steady_speed_m_s": self.steady_speed,
            "steady_speed_ratio": self.steady_speed / self.approach_speed,
            "steady_heel_deg": self.steady_roll_deg,
            "max_outward_heel_deg": self.max_outward_heel_deg,
            "max_inward_heel_deg": self.max_inward_heel_deg,
            "capsized": self.capsized,
            "capsize_time_s": self.capsize_time,
        }


@dataclass(frozen=True, eq=False)
class ZigzagResult:
    """A δ/ψ zig-zag trial: series (from the first rudder order) and metrics.

    Series: ``t`` [s], ``heading_change_deg`` (positive towards the first rudder side),
    ``rudder_deg`` (applied) and ``order_deg`` (ordered), both positive towards the first side,
    ``x``, ``y`` [m] (along / across the original course, y towards the first side),
    ``speed`` [m/s], ``roll_deg``.
    """

    rudder_order_deg: float
    switch_deg: float
    approach_speed: float
    length: float
    t: np.ndarray
    heading_change_deg: np.ndarray
    rudder_deg: np.ndarray
    order_deg: np.ndarray
    x: np.ndarray
    y: np.ndarray
    speed: np.ndarray
    roll_deg: np.ndarray
    metrics: ZigzagMetrics
    initial_turning_distance: float
    wall_time: float = math.nan
    capsize_time: float = math.nan

    @property
    def capsized(self) -> bool:
        """The ship heeled beyond the angle of vanishing stability (at :attr:`capsize_time` [s]
        after the first order; the trial stopped there)."""
        return math.isfinite(self.capsize_time)

    @property
    def first_overshoot_deg(self) -> float:
        return self.metrics.first_overshoot_deg

    @property
    def second_overshoot_deg(self) -> float:
        return self.metrics.second_overshoot_deg

    @property
    def initial_turning_over_L(self) -> float:
        return self.initial_turning_distance / self.length

    def summary(self) -> dict[str, float | list[float]]:
        """The metrics as a flat dict (JSON-ready)."""
        m = self.metrics
        return {
            "rudder_deg": self.rudder_order_deg,
            "switch_deg": self.switch_deg,
            "approach_speed_m_s": self.approach_speed,
            "first_overshoot_deg": self.first_overshoot_deg,
            "second_overshoot_deg": self.second_overshoot_deg,
            "overshoots_deg": list(m.overshoots_deg),
            "reversal_times_s": list(m.reversal_times),
            "overshoot_times_s": list(m.overshoot_times),
            "initial_turning_over_L": self.initial_turning_over_L,
            "max_heel_deg": float(np.abs(self.roll_deg).max()),
            "capsized": self.capsized,
            "capsize_time_s": self.capsize_time,
        }


@dataclass(frozen=True, eq=False)
class SpeedTrialPoint:
    """One shaft speed of a speed trial: the simulated steady speed and its surge balance.

    ``steady_speed`` is the Aitken Δ² extrapolation of the last three samples of u(t) taken
    ``duration/4`` apart (exact for an exponential approach); ``final_speed`` the speed at the
    end of the run. The forces [N] are those at the end of the run: ``resistance`` R_T(u),
    ``thrust`` T, ``net_thrust`` (1 − t) T, ``rudder_drag`` (the rudder's −X at 0°) and
    ``other_surge`` (every other surge force incl. hydrostatics + gravity, Coriolis, radiation).
    ``predicted_speed``: :meth:`Propeller.steady_speed_for` (thrust = resistance only);
    ``predicted_speed_with_rudder``: the same balance with the rudder drag added.
    """

    shaft_speed: float
    steady_speed: float
    final_speed: float
    predicted_speed: float
    predicted_speed_with_rudder: float
    resistance: float
    thrust: float
    net_thrust: float
    rudder_drag: float
    other_surge: float
    t: np.ndarray
    u: np.ndarray

    @property
    def rpm(self) -> float:
        return 60.0 * self.shaft_speed

    @property
    def relative_error(self) -> float:
        """(simulated − predicted)/predicted steady speed."""
        return self.steady_speed / self.predicted_speed - 1.0


@dataclass(frozen=True, eq=False)
class SpeedTrialResult:
    """Speed trial: points per shaft speed, and the balance curves R(U), (1 − t) T(n, U)."""

    points: tuple[SpeedTrialPoint, ...]
    speed_grid: np.ndarray
    resistance_curve: np.ndarray
    net_thrust_curves: np.ndarray
    wake_fraction: float
    thrust_deduction: float
    wall_time: float = math.nan

    def summary(self) -> list[dict[str, float]]:
        return [
            {
                "shaft_speed_rev_s": p.shaft_speed,
                "rpm": p.rpm,
                "steady_speed_m_s": p.steady_speed,
                "final_speed_m_s": p.final_speed,
                "predicted_speed_m_s": p.predicted_speed,
                "predicted_speed_with_rudder_drag_m_s": p.predicted_speed_with_rudder,
                "relative_error": p.relative_error,
                "resistance_N": p.resistance,
                "thrust_N": p.thrust,
                "net_thrust_N": p.net_thrust,
                "rudder_drag_N": p.rudder_drag,
                "other_surge_N": p.other_surge,
            }
            for p in self.points
        ]


@dataclass(frozen=True, eq=False)
class HeadingStepResult:
    """Autopilot course keeping then a heading step.

    ``hold_max_deviation_deg``: max |ψ − ψ₀| during the course-keeping phase;
    ``overshoot_pct``: max excursion beyond the new set-point, in % of the step;
    ``settling_time``: time after the step order after which |ψ − ψ_ref| stays below
    ``band_deg``; ``rise_time``: 10 % → 90 % of the step. Series from the step order.
    """

    step_deg: float
    band_deg: float
    hold_max_deviation_deg: float
    overshoot_pct: float
    settling_time: float
    rise_time: float
    max_rudder_deg: float
    nomoto_gain: float
    nomoto_time_constant: float
    t: np.ndarray
    heading_deg: np.ndarray
    rudder_deg: np.ndarray
    wall_time: float = math.nan


# ------------------------------------------------------------------------------ trials
def turning_circle(
    setup: ShipSetup,
    rudder_deg: float = 35.0,
    *,
    heading_change_deg: float = 540.0,
    max_time: float = 1200.0,
    settle: float = 60.0,
    trim_approach: bool = True,
    progress: bool = False,
) -> TurningCircleResult:
    """Turning-circle trial: straight run, then the rudder ordered to ``rudder_deg``.

    Parameters
    ----------
    setup : ShipSetup
        With propulsion, manoeuvring and ``rudder="command"`` (:func:`trial_setup`).
    rudder_deg : float
        Rudder order [deg]; positive turns to starboard.
    heading_change_deg : float
        Stop when the heading has changed by this much [deg] (≥ 180 for the tactical diameter).
    max_time : float
        Stop at the latest this long after the order [s].
    settle : float
        Straight run before the order [s].
    trim_approach : bool
        Trim the shaft speed for a steady approach at ``setup.speed`` (:func:`trim_shaft_speed`).
    progress : bool
        tqdm progress bar.
    """
    import time

    if rudder_deg == 0.0:
        raise ValueError("a turning circle needs a non-zero rudder angle")
    start = time.perf_counter()
    sim = _prepare(setup, settle=settle, trim_approach=trim_approach)
    side = math.copysign(1.0, rudder_deg)
    order = math.radians(rudder_deg)
    rec = _Recorder(sim, _has_actuator(sim, "rudder"))
    u0 = float(math.hypot(sim.nu[0], sim.nu[1]))
    rec.record(order)
    bar = _progress(max_time, f"turning {rudder_deg:g}°", progress)
    target = math.radians(heading_change_deg)
    limit = capsize_angle(setup)
    capsize_time = math.nan
    sim.commands = {**sim.commands, "rudder_command": order}
    while side * rec.heading_change < target and sim.t - rec.t0 < max_time - 1e-9:
        sim.step()
        rec.record(order)
        if _capsized(sim, limit):
            capsize_time = sim.t - rec.t0
            break
        if bar is not None:
            bar.update(round(sim.t - rec.t0) - bar.n)
    if bar is not None:
        bar.close()
    a = rec.arrays()
    y = side * a["y"]
    h = side * a["psi"]
    metrics = turning_metrics(a["t"], a["x"], y, h)
    speed = np.hypot(a["u"], a["v"])
    # steady values: mean over the last 30 s
    tail = a["t"] >= a["t"][-1] - 30.0
    r_end = float(np.mean(np.abs(a["r"][tail])))
    u_end = float(np.mean(speed[tail]))
    roll = side * np.degrees(a["roll"])
    return TurningCircleResult(
        rudder_order_deg=float(rudder_deg),
        approach_speed=u0,
        length=hull_of(setup.hull, **setup.hull_overrides).particulars.lpp,
        shaft_speed=float(sim.commands["shaft_speed"]),
        t=a["t"],
        x=a["x"],
        y=y,
        heading_change_deg=np.degrees(h),
        rudder_deg=side * np.degrees(a["rudder"]),
        speed=speed,
        yaw_rate_deg_s=side * np.degrees(a["r"]),
        drift_deg=side * np.degrees(np.arctan2(-a["v"], a["u"])),
        roll_deg=roll,
        metrics=metrics,
        steady_diameter=2.0 * u_end / r_end if r_end > 0.0 else math.inf,
        steady_speed=u_end,
        steady_roll_deg=float(np.mean(roll[tail])),
        max_outward_heel_deg=float(max(-roll.min(), 0.0)),
        max_inward_heel_deg=float(max(roll.max(), 0.0)),
        wall_time=time.perf_counter() - start,
        capsize_time=capsize_time,
    )


def zigzag(
    setup: ShipSetup,
    rudder_deg: float = 10.0,
    switch_deg: float | None = None,
    *,
    reversals: int = 4,
    max_time: float = 1200.0,
    settle: float = 60.0,
    trim_approach: bool = True,
    progress: bool = False,
) -> ZigzagResult:
    """δ/ψ zig-zag trial (MSC/Circ.1053): rudder to δ; when the heading has changed by ψ to
    that side, rudder to −δ; when it has changed by ψ to the other side, rudder to +δ; …

    Parameters
    ----------
    setup : ShipSetup
        With propulsion, manoeuvring and ``rudder="command"``.
    rudder_deg : float
        δ [deg]; positive: the first order is to starboard.
    switch_deg : float, optional
        Check heading ψ [deg] (> 0; default |δ|).
    reversals : int
        The run ends at the (reversals + 1)-th check-heading crossing, so that ``reversals``
        overshoots are complete (≥ 2 for the second overshoot).
    max_time, settle, trim_approach, progress
        As :func:`turning_circle`.
    """
    import time

    if rudder_deg == 0.0:
        raise ValueError("a zig-zag needs a non-zero rudder angle")
    switch = abs(rudder_deg) if switch_deg is None else float(switch_deg)
    if not switch > 0.0:
        raise ValueError(f"switch_deg must be positive, got {switch_deg!r}")
    if reversals < 1:
        raise ValueError(f"reversals must be >= 1, got {reversals!r}")
    start = time.perf_counter()
    sim = _prepare(setup, settle=settle, trim_approach=trim_approach)
    side = math.copysign(1.0, rudder_deg)
    delta = math.radians(abs(rudder_deg))
    check = math.radians(switch)
    rec = _Recorder(sim, _has_actuator(sim, "rudder"))
    u0 = float(math.hypot(sim.nu[0], sim.nu[1]))
    direction = 1.0  # +1: rudder towards the first side
    rec.record(side * direction * delta)
    reversal_times: list[float] = []
    initial_distance = math.nan
    track = 0.0
    last_xy = (float(sim.eta[0]), float(sim.eta[1]))
    bar = _progress(max_time, f"zig-zag {abs(rudder_deg):g}/{switch:g}", progress)
    limit = capsize_angle(setup)
    capsize_time = math.nan
    while sim.t - rec.t0 < max_time - 1e-9:
        sim.step({"rudder_command": side * direction * delta})
        track += math.hypot(sim.eta[0] - last_xy[0], sim.eta[1] - last_xy[1])
        last_xy = (float(sim.eta[0]), float(sim.eta[1]))
        rec.record(side * direction * delta)
        if _capsized(sim, limit):
            capsize_time = sim.t - rec.t0
            break
        h = side * rec.heading_change
        if direction * h >= check:
            if not reversal_times:
                initial_distance = track
            if len(reversal_times) == reversals:
                break
            reversal_times.append(sim.t - rec.t0)
            direction = -direction
            rec.rows[-1] = (*rec.rows[-1][:-1], side * direction * delta)
        if bar is not None:
            bar.update(round(sim.t - rec.t0) - bar.n)
    if bar is not None:
        bar.close()
    a = rec.arrays()
    h_deg = side * np.degrees(a["psi"])
    metrics = zigzag_metrics(a["t"], h_deg, reversal_times, switch)
    return ZigzagResult(
        rudder_order_deg=float(rudder_deg),
        switch_deg=switch,
        approach_speed=u0,
        length=hull_of(setup.hull, **setup.hull_overrides).particulars.lpp,
        t=a["t"],
        heading_change_deg=h_deg,
        rudder_deg=side * np.degrees(a["rudder"]),
        order_deg=side * np.degrees(a["order"]),
        x=a["x"],
        y=side * a["y"],
        speed=np.hypot(a["u"], a["v"]),
        roll_deg=np.degrees(a["roll"]),
        metrics=metrics,
        initial_turning_distance=initial_distance,
        wall_time=time.perf_counter() - start,
        capsize_time=capsize_time,
    )


def _aitken(u0: float, u1: float, u2: float) -> float:
    d1, d2 = u1 - u0, u2 - u1
    den = d2 - d1
    if abs(den) < 1e-15 or abs(d2) < 1e-12 or d1 * d2 <= 0.0:
        return u2
    return u2 - d2 * d2 / den


def speed_trial(
    setup: ShipSetup,
    shaft_speeds: Sequence[float],
    *,
    duration: float = 400.0,
    start_speed: float | None = None,
    linearise_at: Literal["predicted", "setup"] = "predicted",
    progress: bool = False,
) -> SpeedTrialResult:
    """Speed trial: for each shaft speed n [rev/s], run straight in calm water, rudder at 0°,
    and extrapolate the steady speed.

    Parameters
    ----------
    setup : ShipSetup
        With propulsion (and usually manoeuvring + rudder, so that their straight-line terms
        are part of the balance).
    shaft_speeds : sequence of float
        Shaft speeds [rev/s].
    duration : float
        Run length per shaft speed [s] (a multiple of 4 dt); the steady speed is the Aitken
        extrapolation of u at duration/2, 3/4 and 1.
    start_speed : float, optional
        Initial surge velocity [m/s]; default the speed predicted by
        :meth:`Propeller.steady_speed_for` (the simulated ship then drifts to its own balance,
        and the extrapolation converges in a few surge time constants; from another speed the
        approach is slower, τ = (m + A₁₁)/(∂R/∂U − ∂X_P/∂U) ≈ 100–150 s).
    linearise_at : {"predicted", "setup"}
        Forward speed about which the radiation memory is linearised (its perturbation velocity
        is ν − (U, 0, …)): the speed predicted by :meth:`Propeller.steady_speed_for` (default;
        a seakeeping model is linearised about the ship's own steady speed) or the set-up
        speed. With ``"setup"`` any zero-frequency gain of the fitted state-space memory in
        surge (it should be 0: B₁₁(0) = 0) acts as a spurious force ∝ (u − U).
    progress : bool
        tqdm progress bar.
    """
    import time

    if not setup.propulsion:
        raise ValueError("a speed trial needs propulsion=True")
    if len(shaft_speeds) == 0:
        raise ValueError("give at least one shaft speed")
    if linearise_at not in ("predicted", "setup"):
        raise ValueError(f"linearise_at must be 'predicted' or 'setup', got {linearise_at!r}")
    start = time.perf_counter()
    sim = build_simulator(setup)
    prop = propeller_of(sim)
    if setup.rudder == "command":
        sim.commands = {**sim.commands, "rudder_command": 0.0}
    base = dict(sim.commands)
    eta0 = sim.eta.copy()
    n_steps = round(duration / sim.dt)
    if n_steps < 4 or n_steps % 4:
        raise ValueError(f"duration must be a multiple of 4 dt = {4 * sim.dt} s")
    quarter = n_steps // 4
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(
            total=n_steps * len(shaft_speeds),
            desc="speed trial",
            unit="step",
            mininterval=0.5,
            leave=False,
        )
    resistance = prop.resistance
    if resistance is None:
        raise ValueError(
            "the propeller has no resistance model (design_propeller_for attaches one); the "
            "speed trial's predictions need it"
        )
    points = []
    for n in shaft_speeds:
        n = float(n)
        pred = prop.steady_speed_for(n)
        sim.forward_speed = pred if linearise_at == "predicted" else float(setup.speed)
        u_start = pred if start_speed is None else float(start_speed)
        sim.reset(eta=eta0, nu=np.array([u_start, 0, 0, 0, 0, 0.0]))
        sim.commands = {**base, "shaft_speed": n}
        ts, us = [sim.t], [float(sim.nu[0])]
        for i in range(n_steps):
            sim.step()
            if (i + 1) % 10 == 0 or i + 1 == n_steps:
                ts.append(sim.t)
                us.append(float(sim.nu[0]))
            if bar is not None:
                bar.update(1)
        ts_a, us_a = np.array(ts), np.array(us)
        samples = [float(np.interp(sim.t - k * quarter * sim.dt, ts_a, us_a)) for k in (2, 1, 0)]
        u_inf = _aitken(*samples)
        bd = sim.force_breakdown()
        op = prop.operating_point(float(sim.nu[0]), n)
        rudder_drag = float(-bd["rudder"][0]) if "rudder" in bd else 0.0
        res_name = resistance.name
        other = sum(v[0] for k, v in bd.items() if k not in (prop.name, "rudder", res_name))
        # balance with the rudder's drag added, as a function of U (drag ∝ its own dynamic
        # pressure: scale the end-of-run value by (u/u_end)² — enough for a 2 % term)
        u_end = float(sim.nu[0])

        def net_with_rudder(u: float, n: float = n, d: float = rudder_drag, ue: float = u_end):
            return (
                prop.operating_point(u, n).surge_force
                - float(resistance.resistance(u))
                - d * (u / ue) ** 2
            )

        pred_r = float(brentq(net_with_rudder, 0.5 * pred, 1.2 * pred, xtol=1e-12))
        points.append(
            SpeedTrialPoint(
                shaft_speed=n,
                steady_speed=u_inf,
                final_speed=u_end,
                predicted_speed=pred,
                predicted_speed_with_rudder=pred_r,
                resistance=float(resistance.resistance(u_end)),
                thrust=op.thrust,
                net_thrust=op.surge_force,
                rudder_drag=rudder_drag,
                other_surge=float(other),
                t=ts_a - ts_a[0],
                u=us_a,
            )
        )
    if bar is not None:
        bar.close()
    speeds = np.array([p.steady_speed for p in points])
    grid = np.linspace(0.5 * speeds.min(), 1.2 * speeds.max(), 80)
    r_curve = np.array([float(resistance.resistance(u)) for u in grid])
    t_curves = np.array(
        [[prop.operating_point(u, p.shaft_speed).surge_force for u in grid] for p in points]
    )
    return SpeedTrialResult(
        points=tuple(points),
        speed_grid=grid,
        resistance_curve=r_curve,
        net_thrust_curves=t_curves,
        wake_fraction=prop.wake_fraction,
        thrust_deduction=prop.thrust_deduction,
        wall_time=time.perf_counter() - start,
    )


def autopilot_step(
    setup: ShipSetup,
    step_deg: float = 20.0,
    *,
    hold: float = 200.0,
    duration: float = 400.0,
    band_deg: float = 1.0,
    trim_approach: bool = True,
    progress: bool = False,
) -> HeadingStepResult:
    """The heading autopilot keeps the initial course for ``hold`` s, then takes a heading
    step of ``step_deg`` (positive to starboard) and is recorded for ``duration`` s.

    ``setup`` must have ``rudder="autopilot"`` (gains by pole placement on the Nomoto model
    identified for the hull at ``setup.speed``).
    """
    import time

    if step_deg == 0.0:
        raise ValueError("step_deg must be non-zero")
    start = time.perf_counter()
    sim = _prepare(setup, settle=0.0, trim_approach=trim_approach, rudder="autopilot")
    k_nom, t_nom = nomoto_of(sim)
    psi0 = float(sim.eta[5])
    _has_actuator(sim, "rudder")
    dev = 0.0
    total = hold + duration
    bar = _progress(total, "autopilot", progress)
    for _ in range(round(hold / sim.dt)):
        sim.step()
        dev = max(dev, abs(float(wrap_angle(sim.eta[5] - psi0))))
        if bar is not None:
            bar.update(round(sim.t) - bar.n)
    ref = psi0 + math.radians(step_deg)
    sim.commands = {**sim.commands, "heading": ref}
    t0 = sim.t
    ts, psis, deltas = [0.0], [float(sim.eta[5])], [sim.actuator_angle("rudder")]
    for _ in range(round(duration / sim.dt)):
        sim.step()
        ts.append(sim.t - t0)
        psis.append(float(sim.eta[5]))
        deltas.append(sim.actuator_angle("rudder"))
        if bar is not None:
            bar.update(round(sim.t) - bar.n)
    if bar is not None:
        bar.close()
    t = np.array(ts)
    side = math.copysign(1.0, step_deg)
    h = side * np.degrees(np.unwrap(np.array(psis)) - psi0)  # towards the step
    step = abs(step_deg)
    err = np.abs(h - step)
    outside = np.flatnonzero(err > band_deg)
    settling = (
        float(t[outside[-1] + 1])
        if outside.size and outside[-1] + 1 < t.size
        else (0.0 if not outside.size else math.nan)
    )
    c10, c90 = _crossing(h, 0.1 * step), _crossing(h, 0.9 * step)
    return HeadingStepResult(
        step_deg=float(step_deg),
        band_deg=float(band_deg),
        hold_max_deviation_deg=math.degrees(dev),
        overshoot_pct=float(max(h.max() - step, 0.0) / step * 100.0),
        settling_time=settling,
        rise_time=_at(t, c90) - _at(t, c10),
        max_rudder_deg=float(np.degrees(np.abs(deltas).max())),
        nomoto_gain=k_nom,
        nomoto_time_constant=t_nom,
        t=t,
        heading_deg=h,
        rudder_deg=side * np.degrees(np.array(deltas)),
        wall_time=time.perf_counter() - start,
    )


def nomoto_of(sim: Simulator) -> tuple[float, float]:
    """Nomoto K [1/s], T [s] of the assembled ship at its speed, identified as
    :func:`~ship_gym.engine.ship.build_simulator` does for the autopilot
    (:func:`~ship_gym.engine.linearisation.nomoto_from_models` on the resistance, propeller,
    hull manoeuvring and rudder models at the current commands)."""
    from ship_gym.control.actuators import Actuated
    from ship_gym.engine.linearisation import nomoto_from_models
    from ship_gym.forces.base import ForceModel
    from ship_gym.forces.manoeuvring import HullManoeuvring
    from ship_gym.forces.resistance import CalmWaterResistance

    models: list[ForceModel] = []
    for f in sim.forces:
        if isinstance(f, CalmWaterResistance | Propeller | HullManoeuvring):
            models.append(f)
        elif isinstance(f, Actuated) and f.key == "rudder":
            models.append(f.model)
    commands = {k: v for k, v in sim.commands.items() if k == "shaft_speed"}
    model = nomoto_from_models(
        sim.hull, models, sim.forward_speed, added_mass=sim.added_mass_lhs, commands=commands
    )
    return model.gain, model.time_constant


# ------------------------------------------------------------------------------ criteria
@dataclass(frozen=True)
class Criterion:
    """One row of the IMO table: ``value`` against ``limit`` (≤), with units."""

    name: str
    value: float
    limit: float
    unit: str
    reference: str
    capsized: bool = False

    @property
    def passed(self) -> bool:
        """Met: a finite value within the limit, and the trial did not capsize the ship."""
        return bool(not self.capsized and math.isfinite(self.value) and self.value <= self.limit)

    @property
    def margin(self) -> float:
        """limit − value (positive: met)."""
        return self.limit - self.value


def imo_criteria(
    results: Iterable[TurningCircleResult | ZigzagResult], length: float, speed: float
) -> tuple[Criterion, ...]:
    """The MSC.137(76) criteria that the given trials can check.

    Parameters
    ----------
    results : iterable
        :class:`TurningCircleResult` (35° rudder: advance and tactical diameter) and
        :class:`ZigzagResult` (10°/10°: initial turning, first and second overshoot;
        20°/20°: first overshoot). Trials of other angles are ignored.
    length : float
        L [m] (length between perpendiculars).
    speed : float
        Test speed V [m/s].
    """
    lv = float(length) / float(speed)
    first10, second10, first20 = overshoot_limits(lv)
    rows: list[Criterion] = []
    for res in results:
        if isinstance(res, TurningCircleResult) and abs(abs(res.rudder_order_deg) - 35.0) < 1e-9:
            rows.append(
                Criterion(
                    "advance",
                    res.metrics.advance / length,
                    ADVANCE_LIMIT,
                    "L",
                    "MSC.137(76) 5.3.1",
                    res.capsized,
                )
            )
            rows.append(
                Criterion(
                    "tactical diameter",
                    res.metrics.tactical_diameter / length,
                    TACTICAL_DIAMETER_LIMIT,
                    "L",
                    "MSC.137(76) 5.3.1",
                    res.capsized,
                )
            )
        elif isinstance(res, ZigzagResult):
            kind = (abs(res.rudder_order_deg), res.switch_deg)
            if kind == (10.0, 10.0):
                rows.append(
                    Criterion(
                        "initial turning (10° rudder → 10° heading)",
                        res.initial_turning_distance / length,
                        INITIAL_TURNING_LIMIT,
                        "L",
                        "MSC.137(76) 5.3.2",
                        res.capsized,
                    )
                )
                rows.append(
                    Criterion(
                        "10°/10° first overshoot",
                        res.first_overshoot_deg,
                        first10,
                        "deg",
                        f"MSC.137(76) 5.4.1 (L/V = {lv:.2f} s)",
                        res.capsized,
                    )
                )
                rows.append(
                    Criterion(
                        "10°/10° second overshoot",
                        res.second_overshoot_deg,
                        second10,
                        "deg",
                        "MSC.137(76) 5.4.2",
                        res.capsized,
                    )
                )
            elif kind == (20.0, 20.0):
                rows.append(
                    Criterion(
                        "20°/20° first overshoot",
                        res.first_overshoot_deg,
                        first20,
                        "deg",
                        "MSC.137(76) 5.4.3",
                        res.capsized,
                    )
                )
    return tuple(rows)


def format_criteria(rows: Sequence[Criterion]) -> str:
    """A printable table of :func:`imo_criteria` rows."""
    lines = [f"{'criterion':44s} {'value':>9s} {'limit':>9s}  unit  result"]
    for c in rows:
        verdict = "NOT MET (capsized)" if c.capsized else ("met" if c.passed else "NOT MET")
        value = f"{'—':>9s}" if c.capsized else f"{c.value:9.3f}"
        lines.append(
            f"{c.name:44s} {value} {c.limit:9.3f}  {c.unit:4s}  {verdict}  ({c.reference})"
        )
    return "\n".join(lines)


def report(
    length: float,
    speed: float,
    turning: TurningCircleResult | None = None,
    zigzag10: ZigzagResult | None = None,
    zigzag20: ZigzagResult | None = None,
) -> dict:
    """JSON-ready numbers of the trials that were run: the keys of the issue
    (``advance_over_L``, ``tactical_diameter_over_L``, ``zigzag10_first_overshoot_deg``,
    ``zigzag10_second_overshoot_deg``, ``zigzag20_first_overshoot_deg``) at the top level, then
    per-trial summaries, the IMO limits at this L/V and the pass/fail table."""
    lv = float(length) / float(speed)
    first10, second10, first20 = overshoot_limits(lv)
    out: dict = {"length_m": float(length), "speed_m_s": float(speed), "L_over_V_s": lv}
    runs = [r for r in (turning, zigzag10, zigzag20) if r is not None]
    if turning is not None:
        out["advance_over_L"] = turning.advance_over_L
        out["tactical_diameter_over_L"] = turning.tactical_diameter_over_L
        out["turning"] = turning.summary()
    if zigzag10 is not None:
        out["zigzag10_first_overshoot_deg"] = zigzag10.first_overshoot_deg
        out["zigzag10_second_overshoot_deg"] = zigzag10.second_overshoot_deg
        out["initial_turning_over_L"] = zigzag10.initial_turning_over_L
        out["zigzag10"] = zigzag10.summary()
    if zigzag20 is not None:
        out["zigzag20_first_overshoot_deg"] = zigzag20.first_overshoot_deg
        out["zigzag20"] = zigzag20.summary()
    out["imo_limits"] = {
        "advance_over_L": ADVANCE_LIMIT,
        "tactical_diameter_over_L": TACTICAL_DIAMETER_LIMIT,
        "initial_turning_over_L": INITIAL_TURNING_LIMIT,
        "zigzag10_first_overshoot_deg": first10,
        "zigzag10_second_overshoot_deg": second10,
        "zigzag20_first_overshoot_deg": first20,
    }
    rows = imo_criteria(runs, length, speed)
    out["imo_criteria"] = [
        {
            "criterion": c.name,
            "value": c.value,
            "limit": c.limit,
            "unit": c.unit,
            "met": c.passed,
            "capsized": c.capsized,
            "reference": c.reference,
        }
        for c in rows
    ]
    out["imo_all_met"] = all(c.passed for c in rows)
    out["wall_time_s"] = {
        name: r.wall_time
        for name, r in (("turning", turning), ("zigzag10", zigzag10), ("zigzag20", zigzag20))
        if r is not None
    }
    return out


# ------------------------------------------------------------------------------ plots
def plot_turning_circle(ax: Axes, res: TurningCircleResult) -> None:
    """Track of the midship point (x ahead, y to the turning side, in L) with the advance,
    transfer and tactical diameter marked."""
    L = res.length
    m = res.metrics
    ax.plot(res.y / L, res.x / L, "k", lw=1.2, label="track of O (midship)")
    ax.plot(0.0, 0.0, "go", ms=5, label="rudder order")
    ax.plot(m.transfer / L, m.advance / L, "bs", ms=5)
    ax.annotate(
        f"advance {m.advance / L:.2f} L",
        (m.transfer / L, m.advance / L),
        textcoords="offset points",
        xytext=(6, 6),
        color="b",
    )
    ax.plot([0.0, m.transfer / L], [m.advance / L, m.advance / L], "b:", lw=0.8)
    c180 = _crossing(np.radians(res.heading_change_deg), math.pi)
    x180 = _at(res.x, c180)
    ax.plot(m.tactical_diameter / L, x180 / L, "rs", ms=5)
    ax.annotate(
        "",
        xy=(m.tactical_diameter / L, x180 / L),
        xytext=(0.0, x180 / L),
        arrowprops={"arrowstyle": "<->", "color": "r"},
    )
    ax.text(
        0.5 * m.tactical_diameter / L,
        x180 / L,
        f"tactical diameter {m.tactical_diameter / L:.2f} L",
        color="r",
        ha="center",
        va="bottom",
    )
    ax.axhline(ADVANCE_LIMIT, color="b", lw=0.6, ls="--", label=f"IMO advance {ADVANCE_LIMIT} L")
    ax.axvline(
        TACTICAL_DIAMETER_LIMIT,
        color="r",
        lw=0.6,
        ls="--",
        label=f"IMO tactical diameter {TACTICAL_DIAMETER_LIMIT} L",
    )
    ax.set_aspect("equal")
    ax.set(
        xlabel="transfer y / L (towards the turn)",
        ylabel="advance x / L",
        title=f"turning circle, δ = {res.rudder_order_deg:g}°, U₀ = {res.approach_speed:.2f} m/s",
    )
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")


def plot_zigzag(ax: Axes, res: ZigzagResult) -> None:
    """Heading change and rudder angle (ordered and applied) against time, overshoots marked."""
    ax.plot(res.t, res.heading_change_deg, "k", lw=1.2, label="heading change ψ")
    ax.plot(res.t, res.rudder_deg, "b", lw=1.0, label="rudder δ (applied)")
    ax.plot(res.t, res.order_deg, "b:", lw=0.8, label="rudder order")
    for k, (ts, os) in enumerate(
        zip(res.metrics.overshoot_times, res.metrics.overshoots_deg, strict=True)
    ):
        sign = 1.0 if k % 2 == 0 else -1.0
        peak = sign * (res.switch_deg + os)
        ax.plot(ts, peak, "rv" if sign > 0 else "r^", ms=5)
        ax.annotate(
            f"{os:.1f}°",
            (ts, peak),
            textcoords="offset points",
            xytext=(4, 4 * sign),
            color="r",
            fontsize=8,
        )
    for s in (res.switch_deg, -res.switch_deg):
        ax.axhline(s, color="gray", lw=0.5, ls="--")
    ax.set(
        xlabel="t since first order [s]",
        ylabel="[deg]",
        title=f"{abs(res.rudder_order_deg):g}°/{res.switch_deg:g}° zig-zag, "
        f"U₀ = {res.approach_speed:.2f} m/s",
    )
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower left")


def plot_speed_trial(ax: Axes, res: SpeedTrialResult) -> None:
    """R_T(U) and (1 − t) T(n, U) per shaft speed; simulated steady speeds marked."""
    ax.plot(res.speed_grid, res.resistance_curve / 1e3, "k", lw=1.5, label="R_T (Holtrop–Mennen)")
    for p, curve in zip(res.points, res.net_thrust_curves, strict=True):
        ax.plot(res.speed_grid, curve / 1e3, lw=0.9, label=f"(1−t)T at {p.rpm:.1f} rpm")
        ax.plot(p.steady_speed, p.net_thrust / 1e3, "o", ms=5, color="C3")
    ax.plot([], [], "o", color="C3", label="simulated steady speed")
    ax.set_ylim(0.0, 1.3 * res.resistance_curve.max() / 1e3)
    ax.set(xlabel="U [m/s]", ylabel="force [kN]", title="speed trial: thrust/resistance balance")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")


def plot_heading_step(ax: Axes, res: HeadingStepResult) -> None:
    """Autopilot heading step: heading and rudder against time."""
    ax.plot(res.t, res.heading_deg, "k", lw=1.2, label="heading change")
    ax.plot(res.t, res.rudder_deg, "b", lw=1.0, label="rudder δ")
    ax.axhline(abs(res.step_deg), color="gray", lw=0.6, ls="--")
    ax.axhspan(
        abs(res.step_deg) - res.band_deg, abs(res.step_deg) + res.band_deg, color="g", alpha=0.1
    )
    ax.set(
        xlabel="t since the step order [s]",
        ylabel="[deg]",
        title=f"autopilot {res.step_deg:g}° step: overshoot {res.overshoot_pct:.1f} %, "
        f"settled ±{res.band_deg:g}° after {res.settling_time:.0f} s",
    )
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
