"""Residual policies: a learned correction on top of a classical controller.

The env receives a = clip(a_baseline(o) + scale · a_learned(o), −1, 1): the baseline
(:mod:`ship_gym.agents.baselines`, with its tuned per-env gains) acts on the raw observation o,
the learned policy adds at most ``scale`` of full command on top. With the learned output near
zero at the start of training (SB3 initialises the action head with gain 0.01), the agent
starts *at* the classical controller and the reinforcement learning only has to find the
improvement — residual policy learning (Silver et al. 2018, arXiv:1812.06298; Johannink et al.
2019, ICRA, "Residual reinforcement learning for robot control"). It also makes the benchmark's
"equal or lower effort" reachable: exploration starts from the baseline's effort, not from a
random policy's.

A training config asks for it with a table::

    [residual]
    baseline = "pid"      # a key of ship_gym.agents.baselines.BASELINES (not "zero")
    scale = 0.3           # authority of the learned part, in action units (0, 2]
    [residual.gains]      # optional: override the baseline's per-env default gains
    k_p = 1.5

Training wraps the SB3 VecEnv (raw observations, under any ``VecNormalize``) in
:func:`residual_vec_env`; the run folder then holds ``residual.json`` — the baseline's name,
*all* its resolved gains, the scale and the env layout it was bound to — so that the saved
policy stays the one trained even if the default gains change later. :func:`load_agent_policy`
reads a run back as a :class:`ResidualPolicy` (or a plain
:class:`~ship_gym.envs.saved_policies.ModelPolicy`); ``ship-gym evaluate`` and
``ship-gym benchmark`` use it.
"""

from __future__ import annotations

import functools
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ship_gym.agents.baselines import BASELINES, Baseline, EnvLayout, make_baseline
from ship_gym.envs.saved_policies import RESIDUAL_FILE, ModelPolicy, load_policy

__all__ = [
    "RESIDUAL_FILE",
    "ResidualConfig",
    "ResidualPolicy",
    "find_residual",
    "load_agent_policy",
    "residual_action",
    "residual_config",
    "residual_vec_env",
    "save_residual",
]

_MAX_SCALE = 2.0  # a learned part that can flip a saturated baseline command end to end


@dataclass(frozen=True)
class ResidualConfig:
    """The ``[residual]`` table of a training config.

    Attributes
    ----------
    baseline : str
        Name of the classical controller (a key of
        :data:`~ship_gym.agents.baselines.BASELINES`).
    scale : float
        Authority of the learned part [action units]: a = clip(a_baseline + scale · a_learned).
    gains : Mapping[str, float]
        Overrides of the baseline's per-env default gains (field names of its class).
    """

    baseline: str
    scale: float = 0.5
    gains: Mapping[str, float] = field(default_factory=dict)


def residual_config(table: Mapping[str, Any]) -> ResidualConfig:
    """Validate a ``[residual]`` table (names the bad key and value; unknown keys → ValueError)."""
    known = {"baseline", "scale", "gains"}
    extra = set(table) - known
    if extra:
        raise ValueError(f"unknown keys {sorted(extra)} in [residual]; expected {sorted(known)}")
    name = table.get("baseline")
    choices = sorted(set(BASELINES) - {"zero"})
    if name not in choices:
        raise ValueError(f"residual.baseline must be one of {choices}, got {name!r}")
    scale = table.get("scale", 0.5)
    if not (
        isinstance(scale, int | float)
        and not isinstance(scale, bool)
        and math.isfinite(scale)
        and 0.0 < scale <= _MAX_SCALE
    ):
        raise ValueError(f"residual.scale must be a number in (0, {_MAX_SCALE:g}], got {scale!r}")
    gains = table.get("gains", {})
    if not isinstance(gains, Mapping):
        raise ValueError(f"residual.gains must be a table of gains, got {gains!r}")
    fields = BASELINES[name].parameter_names()
    unknown = set(gains) - set(fields)
    if unknown:
        raise ValueError(
            f"unknown gains {sorted(unknown)} in [residual.gains] of {name!r}; "
            f"expected some of {sorted(fields)}"
        )
    return ResidualConfig(baseline=str(name), scale=float(scale), gains=dict(gains))


def _baseline_parameters(baseline: Baseline) -> dict[str, Any]:
    """Every gain and setting of a baseline (JSON-ready: tuples → lists)."""
    return {
        name: (list(v) if isinstance(v := getattr(baseline, name), tuple) else v)
        for name in baseline.parameter_names()
    }


def residual_action(base: NDArray, learned: NDArray, scale: float) -> NDArray:
    """The env action clip(a_baseline + scale · a_learned, −1, 1) (one formula for training
    and evaluation)."""
    return np.clip(base + scale * np.asarray(learned), -1.0, 1.0)


def save_residual(run_dir: str | Path, baseline: Baseline, scale: float) -> Path:
    """Write ``residual.json`` of a run: baseline name, resolved gains, scale and env layout."""
    from ship_gym.io_utils import atomic_write_text

    layout = baseline.layout
    data = {
        "baseline": baseline.name,
        "parameters": _baseline_parameters(baseline),
        "scale": float(scale),
        "layout": {
            "observation_names": list(layout.observation_names),
            "action_names": list(layout.action_names),
            "control_dt": layout.control_dt,
            "env_id": layout.env_id,
        },
    }
    path = Path(run_dir) / RESIDUAL_FILE
    atomic_write_text(path, json.dumps(data, indent=2, ensure_ascii=False) + "\n")
    return path


def _read_residual(path: Path) -> tuple[Baseline, float]:
    """The baseline (rebuilt from its saved gains and layout) and scale of ``residual.json``."""
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        lay = data["layout"]
        layout = EnvLayout(
            observation_names=tuple(lay["observation_names"]),
            action_names=tuple(lay["action_names"]),
            control_dt=float(lay["control_dt"]),
            env_id=lay.get("env_id"),
        )
        cls = BASELINES[data["baseline"]]
        parameters = {
            k: (tuple(v) if isinstance(v, list) else v) for k, v in data["parameters"].items()
        }
        scale = float(data["scale"])
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise ValueError(f"{path}: not a residual description ({exc!r})") from None
    return cls(layout=layout, **parameters), scale


@dataclass
class ResidualPolicy:
    """A learned policy acting as a correction of a classical one (SB3 ``predict`` signature).

    Attributes
    ----------
    learned : ModelPolicy
        The trained model (applies its own observation normalisation).
    baseline : Baseline
        The classical controller, on raw observations.
    scale : float
        Authority of the learned part [action units].
    """

    learned: ModelPolicy
    baseline: Baseline
    scale: float

    @property
    def path(self) -> str:
        return self.learned.path

    @property
    def training_env(self) -> dict:
        return self.learned.training_env

    def predict(
        self,
        observation: NDArray,
        state: Any = None,
        episode_start: NDArray | None = None,
        deterministic: bool = True,
    ) -> tuple[NDArray, Any]:
        """clip(a_baseline + scale · a_learned, −1, 1); ``state`` is the baseline's memory (the
        learned part is a feed-forward network)."""
        base, memory = self.baseline.predict(observation, state=state, episode_start=episode_start)
        learned, _ = self.learned.predict(observation, deterministic=deterministic)
        return residual_action(base, learned, self.scale).astype(np.float32), memory


def load_agent_policy(
    path: str | Path, device: str = "cpu", *, trusted: bool = False
) -> ModelPolicy | ResidualPolicy:
    """A trained run as a policy: :func:`~ship_gym.envs.saved_policies.load_policy`, composed
    with its baseline when the run folder holds ``residual.json``.

    ``trusted`` is the caller's opt-in to load a model neither trained here nor shipped (loading
    an SB3 model runs code from the file: :mod:`ship_gym.envs.policy_trust`)."""
    policy = load_policy(path, device=device, residual=True, trusted=trusted)
    p = Path(path)
    residual = (p if p.is_dir() else p.parent) / RESIDUAL_FILE
    if not residual.exists():
        return policy
    baseline, scale = _read_residual(residual)
    return ResidualPolicy(learned=policy, baseline=baseline, scale=scale)


@functools.cache
def _residual_vec_env_class() -> type:
    """Define the SB3 wrapper (imports stable-baselines3; done once, on first use)."""
    from stable_baselines3.common.vec_env import VecEnvWrapper

    class ResidualVecEnv(VecEnvWrapper):
        """Steps the wrapped VecEnv with clip(a_baseline(o) + scale · a, −1, 1), o the raw
        observation the wrapped env returned last (its memory cleared where an episode
        starts)."""

        def __init__(self, venv: Any, baseline: Baseline, scale: float) -> None:
            super().__init__(venv)
            self.baseline = baseline
            self.scale = float(scale)
            self._obs: NDArray | None = None
            self._starts = np.ones(venv.num_envs, dtype=bool)

        def reset(self) -> Any:
            obs = self.venv.reset()
            self._obs = np.asarray(obs)
            self._starts[:] = True
            self.baseline.reset()
            return obs

        def step_async(self, actions: NDArray) -> None:
            if self._obs is None:
                raise RuntimeError("reset the residual VecEnv before stepping it")
            base, _ = self.baseline.predict(self._obs, episode_start=self._starts)
            self._starts[:] = False
            self.venv.step_async(residual_action(base, actions, self.scale))

        def step_wait(self) -> Any:
            obs, rewards, dones, infos = self.venv.step_wait()
            self._obs = np.asarray(obs)  # after an end: the next episode's first observation
            self._starts = np.asarray(dones, dtype=bool).copy()
            return obs, rewards, dones, infos

    return ResidualVecEnv


def residual_vec_env(venv: Any, config: ResidualConfig, env_id: str) -> Any:
    """Wrap an SB3 VecEnv of raw observations so that its actions are residuals.

    Parameters
    ----------
    venv : stable_baselines3 VecEnv
        The training env (before any ``VecNormalize``: the baseline reads SI observations).
    config : ResidualConfig
        Baseline, gains and scale.
    env_id : str
        The registered id (selects the baseline's per-env default gains).

    Returns
    -------
    VecEnv
        The wrapper; its ``baseline`` and ``scale`` are what :func:`save_residual` records.
    """
    baseline = make_baseline(config.baseline, venv, env_id=env_id, **config.gains)
    return _residual_vec_env_class()(venv, baseline, config.scale)


def find_residual(venv: Any) -> Any:
    """The residual wrapper inside a chain of SB3 VecEnv wrappers (ValueError if none)."""
    env = venv
    while env is not None:
        if isinstance(env, _residual_vec_env_class()):
            return env
        env = getattr(env, "venv", None)
    raise ValueError("the VecEnv has no residual wrapper")
