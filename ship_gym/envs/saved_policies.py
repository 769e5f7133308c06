"""A policy saved by ``ship-gym train`` (:mod:`ship_gym.agents.train`), loaded to act.

A run folder holds ``model.zip`` (the SB3 model), ``vecnormalize.pkl`` when it was trained under
SB3's ``VecNormalize`` (the observation statistics, applied here to raw observations) and
``config.toml`` (the algorithm and the training env). :func:`load_policy` returns a
:class:`ModelPolicy` with SB3's ``predict`` signature, which the evaluation
(:mod:`ship_gym.agents.evaluate`) and the capsize campaigns
(:mod:`ship_gym.analysis.policy_cells`) run like any classical controller. stable-baselines3 is
imported only when a policy is loaded.
"""

from __future__ import annotations

import pickle
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["ALGORITHMS", "RESIDUAL_FILE", "ModelPolicy", "load_policy", "read_run_config"]

ALGORITHMS = ("PPO", "SAC", "TD3", "A2C", "DDPG")
"""The stable-baselines3 algorithms a run may name (``[algorithm] name``)."""

RESIDUAL_FILE = "residual.json"
"""In a run folder: the model is a correction of a classical controller
(:mod:`ship_gym.agents.residual`), not a policy by itself."""


@dataclass
class ModelPolicy:
    """A saved SB3 model (and its ``VecNormalize`` observation statistics, if any).

    Attributes
    ----------
    model : stable_baselines3 BaseAlgorithm
        The loaded model.
    obs_normalizer : VecNormalize or None
        Observation normalisation used in training (applied to raw observations here).
    """

    model: Any
    obs_normalizer: Any = None
    path: str = ""
    #: ``[env]`` of the run's ``config.toml`` (``id``, ``kwargs``) when saved with the model.
    training_env: dict = field(default_factory=dict)
    _unused: dict = field(default_factory=dict, repr=False)

    def predict(
        self,
        observation: NDArray,
        state: Any = None,
        episode_start: NDArray | None = None,
        deterministic: bool = True,
    ) -> tuple[NDArray, Any]:
        obs = observation
        if self.obs_normalizer is not None:
            obs = self.obs_normalizer.normalize_obs(np.asarray(observation))
        return self.model.predict(
            obs, state=state, episode_start=episode_start, deterministic=deterministic
        )


def read_run_config(config_path: Path) -> dict[str, Any]:
    """The parsed ``config.toml`` of a training run.

    Raises
    ------
    ValueError
        If it is not valid TOML (naming the file).
    """
    try:
        return tomllib.loads(config_path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{config_path}: invalid TOML: {exc}") from None


def load_policy(path: str | Path, device: str = "cpu", *, residual: bool = False) -> ModelPolicy:
    """Load a model saved by :mod:`ship_gym.agents.train` (a run directory or a ``.zip``).

    The algorithm is read from the run's ``config.toml`` when present, else every SB3 algorithm
    is tried. A ``vecnormalize.pkl`` beside the model is applied to the observations (for
    ``<prefix>model.zip``, e.g. ``final_model.zip``, the ``<prefix>vecnormalize.pkl``).

    A residual run (``residual.json`` beside the model) holds only the correction of a classical
    controller: it is refused unless ``residual`` is True (what
    :func:`ship_gym.agents.residual.load_agent_policy`, which adds the controller, passes), so
    that the correction is never run as if it were the policy.
    """
    import stable_baselines3

    p = Path(path)
    run_dir = p if p.is_dir() else p.parent
    zip_path = p / "model.zip" if p.is_dir() else p
    if not zip_path.exists():
        raise FileNotFoundError(f"no saved model at {zip_path}")
    if not residual and (run_dir / RESIDUAL_FILE).exists():
        raise ValueError(
            f"{run_dir} is a residual policy (a correction of the classical controller in "
            f"{RESIDUAL_FILE}); load it with ship_gym.agents.residual.load_agent_policy "
            "(ship-gym evaluate does)"
        )
    names: list[str] = list(ALGORITHMS)
    config_path = run_dir / "config.toml"
    training_env: dict = {}
    if config_path.exists():
        saved = read_run_config(config_path)
        algo = str(saved.get("algorithm", {}).get("name", "")).upper()
        if algo:
            names = [algo]
        env = saved.get("env", {})
        training_env = {"id": env.get("id"), "kwargs": dict(env.get("kwargs", {}))}
    model = None
    errors = []
    for name in names:
        try:
            model = getattr(stable_baselines3, name).load(zip_path, device=device)
            break
        except Exception as exc:  # wrong algorithm class: try the next
            errors.append(f"{name}: {exc}")
    if model is None:
        raise ValueError(f"could not load {zip_path} with {names}: {errors}")
    normalizer = None
    # each checkpoint beside its own statistics: model.zip + vecnormalize.pkl, and the
    # validation's final_model.zip + final_vecnormalize.pkl (ship_gym.agents.validation)
    prefix = zip_path.name.removesuffix("model.zip") if zip_path.name.endswith("model.zip") else ""
    norm_path = run_dir / f"{prefix}vecnormalize.pkl"
    if norm_path.exists():
        with open(norm_path, "rb") as fh:
            normalizer = pickle.load(fh)
        normalizer.training = False
    return ModelPolicy(
        model=model, obs_normalizer=normalizer, path=str(zip_path), training_env=training_env
    )
