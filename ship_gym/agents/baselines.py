"""Classical controllers as policies: the baselines a learned policy must beat.

Each baseline has the stable-baselines3 policy signature

    ``predict(obs, state=None, episode_start=None, deterministic=True) -> (action, state)``

so that the same evaluation code (:mod:`ship_gym.agents.evaluate`, or SB3's
``evaluate_policy``) runs learned and classical policies. They read the environment's
``observation_names`` and ``action_names`` (ship_gym envs name every entry with its unit, e.g.
``"roll rate [rad/s]"``) and look their inputs and outputs up *by name*, so they survive layout
changes; a missing name raises a ``ValueError`` listing what the environment offers. Build them
with ``Baseline.for_env(env)``.

Observations in degrees (``[deg]``, ``[deg/s]``) are converted to radians. Actions are in the
env's normalised units (``Box(-1, 1)``): the gains below are "action units per SI unit", i.e.
the physical gain divided by the command at |a| = 1 (e.g. the maximum fin angle). Every action the
controller does not drive is 0. Outputs are clipped to [-1, 1].

* :class:`ZeroAction` — all commands zero (the passive ship).
* :class:`PIDAutopilot` — heading PID on the rudder, δ = k_p e − k_d r + k_i ∫e dt with
  e = wrap(ψ_ref − ψ) (the ``"heading error [rad]"`` observation) and r the yaw rate; positive
  rudder turns to starboard (:mod:`ship_gym.control.autopilot`; Fossen 2011, ch. 7 / 12).
* :class:`RollFinController` — classical PD roll stabiliser δ = −(k_φ φ + k_p p) on the fins (or
  any roll-moment actuator: positive command, starboard-down moment;
  :class:`ship_gym.control.stabilisers.FinController`).
* :class:`RideController` — T-foil ride control δ = k_w w − k_q q on heave velocity and pitch
  rate (positive command, upward force and bow-up moment;
  :class:`ship_gym.control.stabilisers.RideController`).
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "BASELINES",
    "Baseline",
    "PIDAutopilot",
    "RideController",
    "RollFinController",
    "ZeroAction",
    "env_layout",
    "find_name",
    "make_baseline",
]

_DEGREE_UNITS = {"deg": math.pi / 180.0, "deg/s": math.pi / 180.0}


def _base_and_unit(name: str) -> tuple[str, str | None]:
    """``"roll rate [rad/s]"`` → (``"roll rate"``, ``"rad/s"``); unit None when not bracketed."""
    unit_match = re.search(r"\[([^\]]*)\]", name)
    base = re.split(r"[\[(]", name, maxsplit=1)[0].strip().lower()
    return base, (unit_match.group(1).strip() if unit_match else None)


def find_name(
    names: Sequence[str], keywords: Sequence[str], *, what: str, required: bool = True
) -> int | None:
    """Index of the entry of ``names`` matching one of ``keywords`` (tried in order).

    A name matches a keyword when its base (the text before ``[`` or ``(``, lower case) equals
    it; failing that, when the base contains it as whole words. Several matches → ValueError.

    Parameters
    ----------
    names : sequence of str
        The env's ``observation_names`` or ``action_names``.
    keywords : sequence of str
        Accepted bases, most specific first (e.g. ``("roll rate", "roll velocity")``).
    what : str
        What is looked up, for the error message (e.g. ``"observation 'roll rate'"``).
    required : bool
        Raise when nothing matches (else return None).
    """
    bases = [_base_and_unit(n)[0] for n in names]
    for keyword in keywords:
        k = keyword.lower()
        exact = [i for i, b in enumerate(bases) if b == k]
        if len(exact) == 1:
            return exact[0]
        pattern = re.compile(rf"\b{re.escape(k)}\b")
        partial = [i for i, b in enumerate(bases) if pattern.search(b)]
        if len(partial) == 1:
            return partial[0]
        if len(exact) > 1 or len(partial) > 1:
            hits = [names[i] for i in (exact or partial)]
            raise ValueError(f"{what}: {keyword!r} is ambiguous among {hits}")
    if required:
        raise ValueError(
            f"{what} not found: none of {list(keywords)} among the env's names {list(names)}"
        )
    return None


@dataclass(frozen=True)
class EnvLayout:
    """What a baseline needs to know of an env: names, control step, env id."""

    observation_names: tuple[str, ...]
    action_names: tuple[str, ...]
    control_dt: float
    env_id: str | None = None

    def observation(self, keywords: Sequence[str], *, required: bool = True) -> tuple[int, float]:
        """(index, factor to SI) of an observation; index −1 if optional and missing."""
        i = find_name(
            self.observation_names, keywords, what=f"observation {keywords[0]!r}", required=required
        )
        if i is None:
            return -1, 1.0
        unit = _base_and_unit(self.observation_names[i])[1]
        return i, _DEGREE_UNITS.get(unit or "", 1.0)

    def action(self, keywords: Sequence[str]) -> int:
        i = find_name(self.action_names, keywords, what=f"action {keywords[0]!r}")
        assert i is not None
        return i


def _env_attr(env: Any, name: str) -> Any:
    """An attribute of a Gymnasium env/vector env (through wrappers) or an SB3 VecEnv."""
    if hasattr(env, "get_attr") and hasattr(env, "env_method"):  # SB3 VecEnv
        return env.get_attr(name)[0]
    if hasattr(env, "get_wrapper_attr"):
        try:
            return env.get_wrapper_attr(name)
        except AttributeError:
            pass
    for candidate in (env, getattr(env, "unwrapped", None)):
        if candidate is not None and hasattr(candidate, name):
            return getattr(candidate, name)
    raise ValueError(
        f"the env {env!r} has no {name!r}: baselines need a ship_gym env "
        "(observation_names, action_names, control_dt)"
    )


def env_layout(env: Any) -> EnvLayout:
    """The names, control step and id of a ship_gym env (single, vector or SB3 VecEnv)."""
    spec = getattr(env, "spec", None)
    if spec is None and hasattr(env, "unwrapped"):
        spec = getattr(env.unwrapped, "spec", None)
    return EnvLayout(
        observation_names=tuple(_env_attr(env, "observation_names")),
        action_names=tuple(_env_attr(env, "action_names")),
        control_dt=float(_env_attr(env, "control_dt")),
        env_id=getattr(spec, "id", None),
    )


@dataclass
class Baseline:
    """A classical controller with SB3's ``predict`` signature (subclasses set the law).

    Attributes
    ----------
    layout : EnvLayout
        Names and control step of the env it was built for.
    """

    name: ClassVar[str] = "baseline"
    layout: EnvLayout
    _idx: dict[str, Any] = field(default_factory=dict, init=False, repr=False)

    @classmethod
    def for_env(cls, env: Any, **gains: float) -> Baseline:
        """Build for a ship_gym env (single, Gymnasium vector or SB3 VecEnv); ``gains``
        override the defaults (same names as the dataclass fields)."""
        return cls(layout=env_layout(env), **gains)

    def __post_init__(self) -> None:
        for key, value in self.__dict__.items():
            if key.startswith(("k_", "gain")) and not (
                isinstance(value, int | float) and math.isfinite(value) and value >= 0.0
            ):
                raise ValueError(
                    f"{type(self).__name__}.{key} must be a finite gain >= 0, got {value!r}"
                )
        self._bind()

    def _bind(self) -> None:
        """Look the needed names up into ``_idx`` (ValueError when missing)."""

    def _observed(self, obs: NDArray, key: str) -> NDArray:
        """(N,) observation bound to ``key`` in ``_idx``, in SI units (angles in radians)."""
        i, factor = self._idx[key]
        return obs[:, i] * factor

    def _drive(self, obs: NDArray, key: str, command: NDArray) -> NDArray:
        """(N, n_act) actions: ``command`` on the action bound to ``key`` in ``_idx``, 0 on the
        others."""
        actions = np.zeros((obs.shape[0], len(self.layout.action_names)))
        actions[:, self._idx[key]] = command
        return actions

    def _law(self, obs: NDArray, state: NDArray | None) -> tuple[NDArray, NDArray | None]:
        """(N, n_obs) → ((N, n_act) actions, new state)."""
        raise NotImplementedError

    def _initial_state(self, n: int) -> NDArray | None:
        return None

    def predict(
        self,
        observation: NDArray,
        state: NDArray | None = None,
        episode_start: NDArray | None = None,
        deterministic: bool = True,
    ) -> tuple[NDArray[np.float32], NDArray | None]:
        """Actions for one observation (n_obs,) or a batch (N, n_obs), SB3 style.

        Parameters
        ----------
        observation : NDArray
            Raw (un-normalised) observations.
        state : NDArray, optional
            Controller memory returned by the previous call (the PID integral); None uses the
            memory kept in the object.
        episode_start : NDArray of bool, optional
            (N,) True where a new episode starts: its memory is cleared.
        deterministic : bool
            Ignored (the controllers are deterministic).

        Returns
        -------
        action : NDArray[np.float32]
            (n_act,) or (N, n_act) in [-1, 1].
        state : NDArray or None
            The memory to pass back next call (None for memoryless controllers).
        """
        obs = np.asarray(observation, dtype=np.float64)
        single = obs.ndim == 1
        obs2 = obs[None, :] if single else obs
        n_obs = len(self.layout.observation_names)
        if obs2.ndim != 2 or obs2.shape[1] != n_obs:
            raise ValueError(
                f"{type(self).__name__}: observation must have shape ({n_obs},) or (N, {n_obs}) "
                f"for names {self.layout.observation_names}, got {obs.shape}"
            )
        n = obs2.shape[0]
        memory = state if state is not None else getattr(self, "_memory", None)
        if memory is not None and np.shape(memory)[0] != n:
            memory = None
        if memory is None:
            memory = self._initial_state(n)
        if memory is not None and episode_start is not None:
            starts = np.asarray(episode_start, dtype=bool).reshape((n,) + (1,) * (memory.ndim - 1))
            memory = np.where(starts, 0.0, memory)
        action, memory = self._law(np.nan_to_num(obs2), memory)
        self._memory = memory
        action = np.clip(action, -1.0, 1.0).astype(np.float32)
        return (action[0] if single else action), memory

    def reset(self) -> None:
        """Forget the memory kept in the object (e.g. between evaluation runs)."""
        self._memory = None


@dataclass
class ZeroAction(Baseline):
    """All commands zero: the passive ship (rudder amidships, fins and foils at rest)."""

    name: ClassVar[str] = "zero"

    def _law(self, obs: NDArray, state: NDArray | None) -> tuple[NDArray, NDArray | None]:
        return np.zeros((obs.shape[0], len(self.layout.action_names))), None


@dataclass
class PIDAutopilot(Baseline):
    """Heading PID on the rudder: a = k_p e − k_d r + k_i ∫e dt (action units).

    Default gains are :meth:`ship_gym.control.autopilot.HeadingAutopilot.from_nomoto` for an
    S175-like Nomoto model (K ≈ 0.05 1/s, T ≈ 20 s) at ω_n = 0.06 rad/s, ζ = 0.9, divided by the
    35° rudder limit: k_p = 1.44 rad/rad → 2.4, k_d = 23 s → 38, k_i = 0.0086 1/s → 0.014.
    The integral is clamped to ±``integral_limit`` (anti-windup) [rad·s].

    Attributes
    ----------
    k_p : float
        Proportional gain [action / rad].
    k_d : float
        Yaw-rate gain [action / (rad/s)]; uses ``"yaw rate"`` (or the difference quotient of the
        heading error if the env has no yaw-rate observation).
    k_i : float
        Integral gain [action / (rad·s)].
    integral_limit : float
        Bound of ∫e dt [rad·s].
    """

    name: ClassVar[str] = "pid"
    k_p: float = 2.4
    k_d: float = 38.0
    k_i: float = 0.014
    integral_limit: float = 30.0

    def _bind(self) -> None:
        self._idx["error"] = self.layout.observation(("heading error", "course error"))
        self._idx["rate"] = self.layout.observation(("yaw rate", "r"), required=False)
        self._idx["rudder"] = self.layout.action(("rudder", "rudder command", "rudder angle"))

    def _initial_state(self, n: int) -> NDArray:
        # columns: ∫e dt [rad·s], previous error [rad] (for the difference quotient)
        return np.zeros((n, 2))

    def _law(self, obs: NDArray, state: NDArray | None) -> tuple[NDArray, NDArray | None]:
        assert state is not None
        e = self._observed(obs, "error")
        dt = self.layout.control_dt
        if self._idx["rate"][0] >= 0:
            r = self._observed(obs, "rate")
        else:  # e = ψ_ref − ψ with a fixed set-point: ė = −r
            r = -(e - state[:, 1]) / dt
        integral = np.clip(state[:, 0] + e * dt, -self.integral_limit, self.integral_limit)
        command = self.k_p * e - self.k_d * r + self.k_i * integral
        return self._drive(obs, "rudder", command), np.column_stack([integral, e])


@dataclass
class RollFinController(Baseline):
    """Classical PD roll stabiliser on the fins: a = −(k_roll φ + k_rate p) (action units).

    Also drives any roll-moment actuator named ``"roll moment"`` (RollOneDOF-v0). Defaults:
    for the S175 fins (±25°), the rate gain k_p ≈ 3 s of fin angle per roll rate (adds ≈ 0.3 of
    critical damping, :meth:`ship_gym.control.stabilisers.FinController.tuned`) → 7 action
    units/(rad/s); the angle gain is small (k_φ ≈ 0.2 C₄₄/K_δ → 1 action unit/rad). For
    RollOneDOF-v0 (moment ±0.03 rad/s², wave moment up to 0.05 rad/s²) the damping must saturate
    early: :data:`DEFAULT_GAINS` sets k_rate = 20, k_roll = 2.

    Attributes
    ----------
    k_roll : float
        Roll-angle gain [action / rad].
    k_rate : float
        Roll-rate gain [action / (rad/s)].
    """

    name: ClassVar[str] = "fins"
    k_roll: float = 1.0
    k_rate: float = 7.0

    def _bind(self) -> None:
        self._idx["roll"] = self.layout.observation(("roll", "roll angle"))
        self._idx["rate"] = self.layout.observation(("roll rate", "roll velocity", "p"))
        names = self.layout.action_names
        fin = find_name(names, ("fins", "fin", "fin angle"), what="action 'fins'", required=False)
        if fin is None:
            fin = find_name(
                names, ("roll moment",), what="action 'fins'/'fin'/'fin angle'/'roll moment'"
            )
        self._idx["fins"] = fin

    def _law(self, obs: NDArray, state: NDArray | None) -> tuple[NDArray, NDArray | None]:
        roll, rate = self._observed(obs, "roll"), self._observed(obs, "rate")
        return self._drive(obs, "fins", -(self.k_roll * roll + self.k_rate * rate)), None


@dataclass
class RideController(Baseline):
    """Classical T-foil ride control: a = k_heave w − k_pitch q (action units).

    w is the heave velocity (body, positive down), q the pitch rate (positive bow up); a positive
    T-foil command gives an upward force and a bow-up moment
    (:class:`ship_gym.control.stabilisers.RideController`), so both terms damp.

    Defaults tuned on RideControl-v1 (S175, Fn 0.3, head/bow seas Hs 2–4 m, Tp 7–11 s; 60 s
    episodes, seeds 0–7): pitch-rate damping alone, k_pitch = 40 action units/(rad/s) (the ±15°
    foil saturates at q ≈ 1.4°/s), lowers the RMS vertical acceleration at the passenger by 6.6 %
    (seeds 0–3) and 4.3 % (seeds 4–7) against zero action, and the return with it. Heave-velocity
    feedback did not help (k_heave = 4, k_pitch = 0: +5.5 %; the former defaults 1, 10: −1.3 %
    and +0.5 %), nor did feedback on the earth-vertical velocity w cos θ − u sin θ instead of
    the body w (≈ ż + U θ at speed U): so k_heave = 0.

    Attributes
    ----------
    k_heave : float
        Heave-velocity gain [action / (m/s)].
    k_pitch : float
        Pitch-rate gain [action / (rad/s)].
    """

    name: ClassVar[str] = "ride"
    k_heave: float = 0.0
    k_pitch: float = 40.0

    def _bind(self) -> None:
        self._idx["w"] = self.layout.observation(("heave velocity", "heave rate", "w"))
        self._idx["q"] = self.layout.observation(("pitch rate", "pitch velocity", "q"))
        self._idx["foil"] = self.layout.action(("t-foil", "tfoil", "foil"))

    def _law(self, obs: NDArray, state: NDArray | None) -> tuple[NDArray, NDArray | None]:
        w, q = self._observed(obs, "w"), self._observed(obs, "q")
        return self._drive(obs, "foil", self.k_heave * w - self.k_pitch * q), None


BASELINES: Mapping[str, type[Baseline]] = {
    cls.name: cls for cls in (ZeroAction, PIDAutopilot, RollFinController, RideController)
}
"""Baselines by short name (as used by ``ship-gym evaluate --policies``)."""

DEFAULT_GAINS: Mapping[tuple[str, str], Mapping[str, float]] = {
    ("fins", "RollOneDOF"): {"k_roll": 2.0, "k_rate": 20.0},
}
"""Per-env default gains: (baseline name, env name without namespace/version) → gains."""


def make_baseline(name: str, env: Any, **gains: float) -> Baseline:
    """Baseline ``name`` (a key of :data:`BASELINES`) for ``env``, with per-env default gains.

    Raises
    ------
    ValueError
        Unknown name, or the env lacks an observation/action the controller needs.
    """
    if name not in BASELINES:
        raise ValueError(f"unknown baseline {name!r}; expected one of {sorted(BASELINES)}")
    layout = env_layout(env)
    env_name = (layout.env_id or "").split("/")[-1].split("-v")[0]
    merged = {**DEFAULT_GAINS.get((name, env_name), {}), **gains}
    return BASELINES[name](layout=layout, **merged)
