"""``ship_gym/RollOneDOF-v0``: keep a single-DOF rolling ship (the Edith Terkol) from capsizing.

A fast, cheap capsize task on the nonlinear roll equation of McCue & Campbell eq. 1
(:class:`ship_gym.roll.equation.RollEquation`, Soliman & Thompson's *Edith Terkol*)
driven by a regular beam-sea roll moment F sin(ωₑt + ε), with a controllable roll moment (an
anti-roll tank or fin pair reduced to an ideal moment per unit inertia) as the action. N episodes
are integrated together by one compiled RK4 kernel (:meth:`RollEquation.advance`), so thousands of
episodes step in milliseconds.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from gymnasium import spaces
from numpy.typing import NDArray

from ship_gym.envs.base import BatchedTask, TaskEnv, TaskStep, TaskVectorEnv
from ship_gym.envs.observations import Observation
from ship_gym.envs.registration import max_episode_steps
from ship_gym.envs.validation import check_options, check_real, is_real
from ship_gym.roll.equation import EDITH_TERKOL_NATURAL_FREQUENCY, RollEquation

if TYPE_CHECKING:
    from ship_gym.envs.rendering import RenderSnapshot

__all__ = [
    "MAX_EPISODE_STEPS",
    "RollOneDOFEnv",
    "RollOneDOFTask",
    "RollOneDOFVectorEnv",
]

#: Time limit in control steps, from the registration (500 s at the default control_dt = 0.5 s,
#: ≈ 50 roll periods).
MAX_EPISODE_STEPS = max_episode_steps("RollOneDOF")

#: Observation bounds: roll [rad] and roll rate [rad/s] (the state is held at the capsize angle
#: once capsized, so it stays far inside these in operation).
ROLL_BOUND = math.pi
ROLL_RATE_BOUND = 2.0 * math.pi

#: Nominal small ship drawn by the renderer [m] (a side trawler of the Edith Terkol's size).
NOMINAL_LENGTH, NOMINAL_BEAM, NOMINAL_DRAUGHT, NOMINAL_DEPTH = 30.0, 7.5, 2.8, 4.2
RENDER_HISTORY_STEPS = 200
RESET_OPTIONS = ("forcing_amplitude", "forcing_phase", "initial_roll", "initial_roll_rate")

MAX_ROLL_MOMENT = 10.0
"""Largest accepted ``forcing_amplitude`` and ``max_moment`` [rad/s²]: 50 times the Edith
Terkol's largest restoring moment per unit inertia (≈ 0.2 rad/s² near 0.4 rad); a larger moment
capsizes any ship within one control step and only overflows the integration."""

MAX_SUBSTEPS = 1000
"""Most RK4 steps in one control step (``control_dt`` ≤ 1000 ``physics_dt``)."""

MAX_PHYSICS_DT = 0.5
"""Largest accepted ``physics_dt`` [s]: T_n/20 of the Edith Terkol (T_n = 10.1 s), the step of
an accurate RK4 roll integration (and ≤ T_n/20 of any other ``roll_equation``)."""


def _finite_float(value: Any, name: str, unit: str) -> float:
    if not is_real(value):
        raise ValueError(
            f"{name} must be a finite number [{unit}], got {value!r} ({type(value).__name__})"
        )
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be a finite number [{unit}], got {value!r}")
    return v


def _non_negative(value: Any, name: str) -> float:
    v = _finite_float(value, name, "-")
    if v < 0.0:
        raise ValueError(f"{name} must be >= 0, got {value!r}")
    return v


def _range(
    value: float | Sequence[float], name: str, unit: str, *, non_negative: bool = False
) -> tuple[float, float]:
    """A (low, high) sampling range from a scalar (fixed) or a pair, validated."""
    expected = f"{name} must be a number or a (low, high) pair [{unit}], got {value!r}"
    if isinstance(value, int | float | np.floating | np.integer):
        if isinstance(value, bool):
            raise ValueError(expected)
        low = high = _finite_float(value, name, unit)
    else:
        try:
            low, high = (_finite_float(v, name, unit) for v in value)
        except (TypeError, ValueError):
            raise ValueError(expected) from None
    if low > high:
        raise ValueError(f"{name} must have low <= high [{unit}], got {value!r}")
    if non_negative and low < 0.0:
        raise ValueError(f"{name} must be >= 0 [{unit}], got {value!r}")
    return low, high


class RollOneDOFTask(BatchedTask):
    """N episodes of the single-DOF Edith Terkol capsize task (see :class:`RollOneDOFEnv`)."""

    def __init__(
        self,
        num_envs: int,
        *,
        forcing_amplitude: float | tuple[float, float] = (0.02, 0.05),
        forcing_frequency: float = 0.85 * EDITH_TERKOL_NATURAL_FREQUENCY,
        random_forcing_phase: bool = True,
        max_moment: float = 0.03,
        control_dt: float = 0.5,
        physics_dt: float = 0.05,
        initial_roll: float | tuple[float, float] = (-0.1, 0.1),
        initial_roll_rate: float | tuple[float, float] = (-0.05, 0.05),
        capsize_angle: float | None = None,
        dangerous_roll_angle: float = 0.4,
        alive_weight: float = 1.0,
        roll_weight: float = 1.0,
        roll_rate_weight: float = 0.1,
        effort_weight: float = 0.05,
        capsize_penalty: float = 100.0,
        roll_noise_std: float = 0.0,
        roll_rate_noise_std: float = 0.0,
        observe_forcing_phase: bool = True,
        roll_equation: RollEquation | None = None,
    ) -> None:
        super().__init__(num_envs)
        n = self.num_envs
        base = RollEquation.edith_terkol() if roll_equation is None else roll_equation
        if not isinstance(base, RollEquation):
            raise ValueError(f"roll_equation must be a RollEquation or None, got {base!r}")
        omega = _finite_float(forcing_frequency, "forcing_frequency", "rad/s")
        if omega < 0.0:
            raise ValueError(f"forcing_frequency must be >= 0 [rad/s], got {forcing_frequency!r}")
        self.equation = dataclasses.replace(
            base, forcing_amplitude=0.0, forcing_frequency=omega, forcing_phase=0.0
        )
        self.forcing_amplitude_range = _range(
            forcing_amplitude, "forcing_amplitude", "rad/s^2", non_negative=True
        )
        if self.forcing_amplitude_range[1] > MAX_ROLL_MOMENT:
            raise ValueError(
                f"forcing_amplitude must be in [0, {MAX_ROLL_MOMENT:g}] [rad/s^2] (50 times the "
                f"largest restoring moment), got {forcing_amplitude!r}"
            )
        self.random_forcing_phase = bool(random_forcing_phase)
        self.max_moment = check_real(
            "max_moment", max_moment, low=0.0, high=MAX_ROLL_MOMENT, unit="rad/s^2",
            why=" (50 times the largest restoring moment)",
        )  # fmt: skip

        wn = base.natural_frequency
        dt_high = MAX_PHYSICS_DT
        if math.isfinite(wn) and wn > 0.0:
            dt_high = min(dt_high, 2.0 * math.pi / wn / 20.0)
        self.physics_dt = check_real(
            "physics_dt", physics_dt, low=0.0, high=dt_high, unit="s", low_open=True,
            why=" (T_n/20 of the roll equation: an accurate RK4 step)",
        )  # fmt: skip
        self.control_dt = check_real(
            "control_dt", control_dt, low=0.0, high=MAX_SUBSTEPS * self.physics_dt, unit="s",
            low_open=True, why=f" (at most {MAX_SUBSTEPS} physics_dt steps per control step)",
        )  # fmt: skip
        ratio = self.control_dt / self.physics_dt
        self.substeps = round(ratio)
        if self.substeps < 1 or abs(ratio - self.substeps) > 1e-9 * ratio:
            raise ValueError(
                f"control_dt = {control_dt!r} s must be an integer multiple of physics_dt = "
                f"{physics_dt!r} s (ratio {ratio!r})"
            )

        self.initial_roll_range = _range(initial_roll, "initial_roll", "rad")
        self.initial_roll_rate_range = _range(initial_roll_rate, "initial_roll_rate", "rad/s")
        if max(abs(v) for v in self.initial_roll_rate_range) > ROLL_RATE_BOUND:
            raise ValueError(
                f"initial_roll_rate must stay within ±{ROLL_RATE_BOUND:.4f} rad/s (the "
                f"observation bound 2π), got {initial_roll_rate!r}"
            )
        if capsize_angle is None:
            capsize_angle = self.equation.vanishing_angle()
        self.capsize_angle = _finite_float(capsize_angle, "capsize_angle", "rad")
        if not 0.0 < self.capsize_angle <= math.pi:
            raise ValueError(
                f"capsize_angle must be in (0, pi] [rad] (default: the vanishing angle), "
                f"got {capsize_angle!r}"
            )
        if max(abs(v) for v in self.initial_roll_range) >= self.capsize_angle:
            raise ValueError(
                f"initial_roll {initial_roll!r} must stay inside the capsize angle "
                f"{self.capsize_angle:.4f} rad"
            )
        self.dangerous_roll_angle = _finite_float(
            dangerous_roll_angle, "dangerous_roll_angle", "rad"
        )
        if not 0.0 < self.dangerous_roll_angle <= self.capsize_angle:
            raise ValueError(
                f"dangerous_roll_angle must be in (0, capsize_angle = {self.capsize_angle:.4f}] "
                f"[rad], got {dangerous_roll_angle!r}"
            )
        self.alive_weight = _non_negative(alive_weight, "alive_weight")
        self.roll_weight = _non_negative(roll_weight, "roll_weight")
        self.roll_rate_weight = _non_negative(roll_rate_weight, "roll_rate_weight")
        self.effort_weight = _non_negative(effort_weight, "effort_weight")
        self.capsize_penalty = _non_negative(capsize_penalty, "capsize_penalty")
        self.roll_noise_std = _non_negative(roll_noise_std, "roll_noise_std")
        self.roll_rate_noise_std = _non_negative(roll_rate_noise_std, "roll_rate_noise_std")
        self.observe_forcing_phase = bool(observe_forcing_phase)
        wn = self.equation.natural_frequency
        #: roll-rate scale of the reward [rad/s]: ωₙ φ_c (the rate of a free roll of amplitude φ_c)
        self.roll_rate_scale = (wn if math.isfinite(wn) else 1.0) * self.capsize_angle

        entries = [
            Observation("roll", "rad", -ROLL_BOUND, ROLL_BOUND, self.roll_noise_std,
                        doc="roll φ", aliases=("roll angle", "phi")),
            Observation("roll rate", "rad/s", -ROLL_RATE_BOUND, ROLL_RATE_BOUND,
                        self.roll_rate_noise_std, doc="roll rate φ̇",
                        aliases=("roll velocity", "p")),
        ]  # fmt: skip
        if self.observe_forcing_phase:
            entries += [
                Observation("sin(forcing phase)", "-", -1.0, 1.0),
                Observation("cos(forcing phase)", "-", -1.0, 1.0),
            ]
        self.observation_entries = tuple(entries)
        """The observation table (:mod:`ship_gym.envs.observations`)."""
        self.observation_names = tuple(e.label for e in entries)
        h = np.array([e.high for e in entries], dtype=np.float32)
        self.observation_space = spaces.Box(-h, h, dtype=np.float32)
        self.action_space = spaces.Box(-1.0, 1.0, (1,), dtype=np.float32)
        self.action_names = (f"roll moment (-1..1 = ±{self.max_moment:g} rad/s^2)",)

        self.phi = np.zeros(n)
        self.phidot = np.zeros(n)
        self.time = np.zeros(n)
        self.amplitude = np.zeros(n)
        self.phase = np.zeros(n)
        self.moment = np.zeros(n)
        self.capsized = np.zeros(n, dtype=bool)
        self.diverged = np.zeros(n, dtype=bool)
        self._noise = np.zeros((n, 2))
        self._noise_rngs: list[np.random.Generator | None] = [None] * n
        self._hist_roll = np.full((n, RENDER_HISTORY_STEPS), np.nan)
        self._hist_len = np.zeros(n, dtype=np.int64)

    # ----------------------------------------------------------------- episodes
    def reset_episodes(
        self,
        ids: NDArray[np.int64],
        rngs: Sequence[np.random.Generator],
        options: Mapping[str, Any] | None,
    ) -> None:
        opts = self._check_reset_options(options)
        for i, rng in zip(ids, rngs, strict=True):
            i = int(i)
            # draws always happen, in this order, so options do not shift the random stream
            amp = rng.uniform(*self.forcing_amplitude_range)
            phase = rng.uniform(0.0, 2.0 * math.pi) if self.random_forcing_phase else 0.0
            phi0 = rng.uniform(*self.initial_roll_range)
            phidot0 = rng.uniform(*self.initial_roll_rate_range)
            noise_seed = rng.integers(0, 2**63 - 1)
            self.amplitude[i] = opts.get("forcing_amplitude", amp)
            self.phase[i] = opts.get("forcing_phase", phase)
            self.phi[i] = opts.get("initial_roll", phi0)
            self.phidot[i] = opts.get("initial_roll_rate", phidot0)
            self.time[i] = 0.0
            self.moment[i] = 0.0
            self.capsized[i] = abs(self.phi[i]) > self.capsize_angle
            self.diverged[i] = False
            self._noise_rngs[i] = np.random.default_rng(int(noise_seed))
            self._hist_len[i] = 0
        self._draw_noise(ids)
        self._record(np.asarray(ids, dtype=np.int64))

    def _check_reset_options(self, options: Mapping[str, Any] | None) -> dict[str, float]:
        """``reset(options=...)`` with the constructor's checks: unknown keys, non-numbers and
        values outside the constructor's limits raise, naming the key."""
        opts = check_options(options, RESET_OPTIONS)
        out: dict[str, float] = {}
        for key, value in opts.items():
            name = f"options[{key!r}]"
            if key == "forcing_amplitude":
                out[key] = check_real(name, value, low=0.0, high=MAX_ROLL_MOMENT, unit="rad/s^2")
            elif key == "forcing_phase":
                out[key] = check_real(
                    name, value, low=-4.0 * math.pi, high=4.0 * math.pi, unit="rad"
                )
            elif key == "initial_roll":
                c = self.capsize_angle
                out[key] = check_real(
                    name, value, low=-c, high=c, unit="rad", low_open=True, high_open=True,
                    why=" (inside the capsize angle)",
                )  # fmt: skip
            else:
                out[key] = check_real(
                    name, value, low=-ROLL_RATE_BOUND, high=ROLL_RATE_BOUND, unit="rad/s"
                )
        return out

    def _draw_noise(self, ids: NDArray[np.int64]) -> None:
        if self.roll_noise_std == 0.0 and self.roll_rate_noise_std == 0.0:
            return
        for i in ids:
            rng = self._noise_rngs[int(i)]
            assert rng is not None
            self._noise[int(i)] = rng.normal(0.0, 1.0, 2) * (
                self.roll_noise_std,
                self.roll_rate_noise_std,
            )

    def _record(self, ids: NDArray[np.int64]) -> None:
        """Append the roll of episodes ``ids`` to their render history (a ring buffer)."""
        self._hist_roll[ids, self._hist_len[ids] % RENDER_HISTORY_STEPS] = self.phi[ids]
        self._hist_len[ids] += 1

    def step(self, actions: NDArray) -> TaskStep:
        a = np.asarray(actions, dtype=np.float64)[:, 0]
        was_capsized = self.capsized.copy()
        self.moment = self.max_moment * a
        # the forcing sin(ωₑ(tᵢ + τ) + εᵢ) of episode i at its own time tᵢ: fold tᵢ into the phase
        phase = self.phase + self.equation.forcing_frequency * self.time
        phi, phidot, crossed = self.equation.advance(
            0.0,
            self.phi,
            self.phidot,
            self.substeps,
            self.physics_dt,
            self.moment,
            self.amplitude,
            phase,
            stop_at=self.capsize_angle,
        )
        # a diverged integration (non-finite state) ends the episode, held at its last state
        diverged = ~(np.isfinite(phi) & np.isfinite(phidot))
        if diverged.any():
            # held capsized: at the capsize angle on the side it was going, at rest
            hold = diverged & ~was_capsized
            self.diverged = self.diverged | hold
            side = np.where(np.where(np.isnan(phi), self.phi, phi) < 0.0, -1.0, 1.0)
            phi = np.where(hold, side * self.capsize_angle, phi)
            phidot = np.where(hold, 0.0, phidot)
            crossed = crossed | diverged
            was_held = was_capsized
        else:
            was_held = was_capsized
        # a capsized ship is held where it capsized (stepping it again must not raise)
        self.phi = np.where(was_held, self.phi, phi)
        self.phidot = np.where(was_held, self.phidot, phidot)
        self.time = self.time + self.control_dt
        self.capsized = was_capsized | crossed
        ids = np.arange(self.num_envs)
        self._draw_noise(ids[~was_capsized])
        self._record(ids)

        up = ~self.capsized
        roll_n = self.phi / self.capsize_angle
        rate_n = self.phidot / self.roll_rate_scale
        terms = {
            "alive": self.alive_weight * up,
            "roll": -self.roll_weight * roll_n**2,
            "roll_rate": -self.roll_rate_weight * rate_n**2,
            "effort": -self.effort_weight * a**2,
            "capsize": -self.capsize_penalty * (self.capsized & ~was_capsized),
        }
        cost = (np.abs(self.phi) > self.dangerous_roll_angle).astype(np.float64)
        return TaskStep(
            reward_terms={k: np.asarray(v, dtype=np.float64) for k, v in terms.items()},
            cost=cost,
            terminated=self.capsized.copy(),
            info={
                "capsized": self.capsized.copy(),
                "diverged": self.diverged.copy(),
                "roll_deg": np.degrees(self.phi),
                "roll_moment": self.moment.copy(),
                "forcing_amplitude": self.amplitude.copy(),
            },
        )

    def observations(self) -> NDArray:
        cols = [self.phi + self._noise[:, 0], self.phidot + self._noise[:, 1]]
        if self.observe_forcing_phase:
            arg = self.equation.forcing_frequency * self.time + self.phase
            cols += [np.sin(arg), np.cos(arg)]
        return np.stack(cols, axis=1).astype(np.float32)

    def reset_info(self, ids: NDArray[np.int64]) -> Mapping[str, NDArray]:
        return {
            "forcing_amplitude": self.amplitude[ids].copy(),
            "forcing_phase": self.phase[ids].copy(),
        }

    def snapshot(self, i: int) -> RenderSnapshot:
        from ship_gym.envs.rendering import RenderSnapshot

        count = int(self._hist_len[i])
        k = min(count, RENDER_HISTORY_STEPS)
        order = (count - k + np.arange(k)) % RENDER_HISTORY_STEPS
        t_hist = self.time[i] - self.control_dt * np.arange(k - 1, -1, -1, dtype=np.float64)
        half_l, half_b = 0.5 * NOMINAL_LENGTH, 0.5 * NOMINAL_BEAM
        return RenderSnapshot(
            time=float(self.time[i]),
            eta=np.array([0.0, 0.0, 0.0, self.phi[i], 0.0, 0.0]),
            length=NOMINAL_LENGTH,
            beam=NOMINAL_BEAM,
            draught=NOMINAL_DRAUGHT,
            depth=NOMINAL_DEPTH,
            profile_x=np.linspace(-half_l, half_l, 2),
            profile_elevation=np.zeros(2),
            section_y=np.linspace(-2 * half_b, 2 * half_b, 2),
            section_elevation=np.zeros(2),
            history_time=t_hist,
            history={"roll [deg]": np.degrees(self._hist_roll[i, order])},
            actions={"roll moment [rad/s^2]": float(self.moment[i])},
            title=f"RollOneDOF (Edith Terkol), F = {self.amplitude[i]:.3f} rad/s^2",
            roll_limit=self.capsize_angle,
        )


class RollOneDOFEnv(TaskEnv):
    """Keep a single-DOF rolling ship upright in regular beam seas with a roll moment.

    Description
    -----------
    The roll of the *Edith Terkol* (Soliman & Thompson 1991; McCue & Campbell 2007 eq. 1):
    φ̈ + b₁φ̇ + b₂|φ̇|φ̇ + c₁φ + c₂|φ|φ + c₃φ³ + c₄|φ|φ³ + c₅φ⁵ = F sin(ωₑt + ε) + m, with
    b₁ = 0.0043, b₂ = 0.0225, c₁ = 0.384, c₂ = 0.1296, c₃ = 1.0368, c₄ = −4.059, c₅ = 2.4052
    (natural frequency 0.62 rad/s, period 10.1 s, vanishing angle 0.856 rad = 49.1°), a wave
    moment at ωₑ = 0.85 ωₙ and a control moment m (all per unit roll inertia). Without control,
    from the default initial states, no ship capsizes in 500 s at F = 0.02 rad/s², 70 % do at
    F = 0.04 (median 35 s) and all do at F ≥ 0.05 (the safe basin is eroded: see
    ``ship-gym safe-basin``); the agent must keep it up with a bounded moment ``max_moment``
    smaller than the wave moment (a plain roll-rate feedback already saves most ships at
    F = 0.045, tested). Integrated with RK4 at ``physics_dt``.

    Action Space
    ------------
    ``Box(-1, 1, (1,), float32)``: roll moment command; m = max_moment · a [rad/s²] held over the
    control step (zero-order hold). Positive rolls to starboard (φ > 0).

    Observation Space
    -----------------
    ``Box(float32)`` of 4 (2 if ``observe_forcing_phase`` is False), physical units:

    ====  ============================  ==================  ======================
    idx   observation                   unit                bounds
    ====  ============================  ==================  ======================
    0     roll φ (+ noise)              rad                 ±π
    1     roll rate φ̇ (+ noise)         rad/s               ±2π
    2     sin(ωₑt + ε)                  -                   ±1
    3     cos(ωₑt + ε)                  -                   ±1
    ====  ============================  ==================  ======================

    Rewards
    -------
    Reward = Σ of the weighted terms, each in ``info["reward_<term>"]``:
    ``alive`` = alive_weight while upright; ``roll`` = −roll_weight (φ/φ_c)²; ``roll_rate`` =
    −roll_rate_weight (φ̇/(ωₙφ_c))²; ``effort`` = −effort_weight a²; ``capsize`` =
    −capsize_penalty on the step that capsizes. φ_c is the capsize angle. The alive bonus makes
    surviving always better than capsizing early. ``info["cost"]`` (Safe RL) = 1 while
    |φ| > dangerous_roll_angle, else 0.

    Starting State
    --------------
    φ₀ ~ U(initial_roll), φ̇₀ ~ U(initial_roll_rate), F ~ U(forcing_amplitude) (domain
    randomisation), ε ~ U(0, 2π) if ``random_forcing_phase``; all from the episode's generator.
    ``reset(options=...)`` may fix ``forcing_amplitude`` [rad/s²] (0 … 10), ``forcing_phase``
    [rad] (±4π), ``initial_roll`` [rad] (inside ±capsize_angle), ``initial_roll_rate`` [rad/s]
    (±2π), with the constructor's checks; other keys, a non-mapping and values outside these
    raise, naming the key.

    Episode End
    -----------
    Terminated when |φ| exceeds ``capsize_angle`` at any physics step (capsize; the state is held
    there), or when the integration diverges (non-finite state: ``info["diverged"]``, the state
    held at its last finite value). Truncated after ``MAX_EPISODE_STEPS`` control steps, the
    registered time limit
    (:data:`ship_gym.envs.registration.ENTRIES`: 500 s at the default ``control_dt``).

    Arguments
    ---------
    forcing_amplitude : float or (low, high)
        Wave roll moment amplitude F [rad/s²], fixed or sampled per episode; default (0.02, 0.05)
        (McCue & Campbell's runs: 0.0195).
    forcing_frequency : float
        ωₑ [rad/s], default 0.85 · 0.62 = 0.527.
    random_forcing_phase : bool
        Sample ε ~ U(0, 2π) per episode (else ε = 0).
    max_moment : float
        Control moment at |a| = 1 [rad/s²], default 0.03; at most 10 (``MAX_ROLL_MOMENT``, as
        ``forcing_amplitude``).
    control_dt : float
        Control step [s], default 0.5; an integer multiple of physics_dt, at most 1000 of them.
    physics_dt : float
        RK4 step [s], default 0.05; at most 0.5 s = T_n/20 (the roll equation's natural period
        over 20: an accurate RK4 step).
    initial_roll : float or (low, high)
        φ₀ [rad], default (−0.1, 0.1).
    initial_roll_rate : float or (low, high)
        φ̇₀ [rad/s], default (−0.05, 0.05); within ±2π.
    capsize_angle : float or None
        φ_c [rad]; default the vanishing angle of the restoring (0.856 rad).
    dangerous_roll_angle : float
        Cost threshold [rad], default 0.4 (23°).
    alive_weight, roll_weight, roll_rate_weight, effort_weight, capsize_penalty : float
        Reward weights [-] (≥ 0): 1.0, 1.0, 0.1, 0.05, 100.
    roll_noise_std, roll_rate_noise_std : float
        Gaussian observation noise [rad], [rad/s] (default 0), drawn from a per-episode generator
        seeded from the episode's generator at reset.
    observe_forcing_phase : bool
        Append sin/cos of the wave phase ωₑt + ε to the observation (default True).
    roll_equation : RollEquation or None
        Other damping/restoring coefficients (e.g. an identified McCue & Campbell eq. 2 model);
        its forcing is replaced by the kwargs above. Default: the Edith Terkol.

    Version History
    ---------------
    v0: initial version.
    """

    task_class = RollOneDOFTask


class RollOneDOFVectorEnv(TaskVectorEnv):
    """N episodes of :class:`RollOneDOFEnv` in one call (one RK4 kernel call per control step)."""

    task_class = RollOneDOFTask
