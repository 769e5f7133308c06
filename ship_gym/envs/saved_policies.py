"""A policy saved by ``ship-gym train`` (:mod:`ship_gym.agents.train`), loaded to act.

A run folder holds ``model.zip`` (the SB3 model), ``vecnormalize.npz`` when it was trained under
SB3's ``VecNormalize`` (the observation statistics as plain arrays, applied here to raw
observations; runs of earlier versions saved a pickled ``vecnormalize.pkl``) and ``config.toml``
(the algorithm and the training env). Loading an SB3 model runs code from the file, so a model is
loaded only when trusted (:mod:`ship_gym.envs.policy_trust`). :func:`load_policy` returns a
:class:`ModelPolicy` with SB3's ``predict`` signature, which the evaluation
(:mod:`ship_gym.agents.evaluate`) and the capsize campaigns
(:mod:`ship_gym.analysis.policy_cells`) run like any classical controller. stable-baselines3 is
imported only when a policy is loaded.
"""

from __future__ import annotations

import io
import math
import pickle
import tomllib
import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "ALGORITHMS",
    "NORMALIZER_SUFFIX",
    "RESIDUAL_FILE",
    "ModelPolicy",
    "ObsNormalizer",
    "convert_legacy_normalizer",
    "load_policy",
    "read_obs_normalizer",
    "read_run_config",
    "save_obs_normalizer",
]

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
    obs_normalizer : ObsNormalizer, VecNormalize or None
        Observation normalisation used in training (applied to raw observations here): anything
        with ``normalize_obs``.
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


NORMALIZER_SUFFIX = "vecnormalize.npz"
"""The observation statistics beside ``<prefix>model.zip``: ``<prefix>vecnormalize.npz``."""

_LEGACY_NORMALIZER_SUFFIX = "vecnormalize.pkl"


@dataclass(frozen=True)
class ObsNormalizer:
    """The observation part of SB3's ``VecNormalize``, saved and read without pickle.

    ``normalize_obs(o) = clip((o − mean) / √(var + epsilon), −clip_obs, clip_obs)`` as float32,
    SB3's formula (the same numbers as the ``VecNormalize`` it was taken from).

    Attributes
    ----------
    mean, var : NDArray
        Running mean and variance of each observation entry [observation units, their square].
    count : float
        Samples behind the statistics [-].
    clip_obs : float
        Bound of the normalised observation [-].
    epsilon : float
        Added to the variance [observation units²].
    norm_obs : bool
        False when the run normalised rewards only (observations pass unchanged).
    """

    mean: NDArray
    var: NDArray
    count: float = 1.0
    clip_obs: float = 10.0
    epsilon: float = 1e-8
    norm_obs: bool = True

    def normalize_obs(self, obs: NDArray) -> NDArray:
        """Normalised observations (any leading batch shape) [-]."""
        if not self.norm_obs:
            return np.asarray(obs)
        scaled = (np.asarray(obs) - self.mean) / np.sqrt(self.var + self.epsilon)
        return np.clip(scaled, -self.clip_obs, self.clip_obs).astype(np.float32)


def save_obs_normalizer(venv: Any, path: str | Path) -> None:
    """Write the observation statistics of a ``VecNormalize`` as an ``.npz`` of plain arrays.

    Parameters
    ----------
    venv : VecNormalize or ObsNormalizer
        The training env's normaliser (or statistics already extracted).
    path : str or Path
        Where to write (use :func:`ship_gym.io_utils.atomic_write` for an atomic file).
    """
    rms = getattr(venv, "obs_rms", None)
    if isinstance(rms, dict):
        raise ValueError("dict observation spaces are not supported by the saved statistics")
    mean = np.asarray(rms.mean if rms is not None else venv.mean, dtype=np.float64)
    var = np.asarray(rms.var if rms is not None else venv.var, dtype=np.float64)
    count = float(rms.count if rms is not None else venv.count)
    with open(path, "wb") as fh:
        np.savez(
            fh,
            mean=mean,
            var=var,
            count=np.float64(count),
            clip_obs=np.float64(venv.clip_obs),
            epsilon=np.float64(venv.epsilon),
            norm_obs=np.bool_(venv.norm_obs),
        )


def read_obs_normalizer(
    path: str | Path, obs_shape: tuple[int, ...] | None = None
) -> ObsNormalizer:
    """Read statistics written by :func:`save_obs_normalizer` (never unpickles anything).

    Parameters
    ----------
    path : str or Path
        The ``vecnormalize.npz`` file.
    obs_shape : tuple of int, optional
        The model's observation shape, which the statistics must have.

    Raises
    ------
    ValueError
        A damaged or foreign file, naming it and what is wrong.
    """
    p = Path(path)
    fields = ("mean", "var", "count", "clip_obs", "epsilon", "norm_obs")
    try:
        with np.load(p, allow_pickle=False) as data:
            missing = [k for k in fields if k not in data.files]
            if missing:
                raise ValueError(f"missing arrays {missing}")
            arrays = {k: np.asarray(data[k]) for k in fields}
    except (OSError, ValueError, EOFError, zipfile.BadZipFile) as exc:
        raise ValueError(
            f"{p}: not observation statistics saved by ship-gym train ({exc}); expected an .npz "
            f"with {list(fields)} (retrain, or restore the file)"
        ) from None
    mean, var = arrays["mean"], arrays["var"]
    scalars = {k: arrays[k] for k in fields[2:]}
    problem = ""
    if mean.dtype.kind != "f" or var.dtype.kind != "f" or mean.shape != var.shape:
        problem = f"mean {mean.dtype}{mean.shape} and var {var.dtype}{var.shape}"
    elif any(a.shape != () or a.dtype.kind not in "fb" for a in scalars.values()):
        problem = "count, clip_obs, epsilon and norm_obs must be scalars"
    elif not (np.all(np.isfinite(mean)) and np.all(np.isfinite(var)) and np.all(var >= 0)):
        problem = "non-finite mean or negative variance"
    elif not (float(scalars["clip_obs"]) > 0 and float(scalars["epsilon"]) >= 0):
        problem = f"clip_obs {float(scalars['clip_obs'])!r}, epsilon {float(scalars['epsilon'])!r}"
    elif obs_shape is not None and tuple(mean.shape) != tuple(obs_shape):
        problem = f"statistics of shape {mean.shape}, the model observes shape {tuple(obs_shape)}"
    if problem:
        raise ValueError(f"{p}: {problem}; expected the statistics of this run's model")
    count = float(scalars["count"])
    return ObsNormalizer(
        mean=mean.astype(np.float64),
        var=var.astype(np.float64),
        count=count if math.isfinite(count) else 0.0,
        clip_obs=float(scalars["clip_obs"]),
        epsilon=float(scalars["epsilon"]),
        norm_obs=bool(scalars["norm_obs"]),
    )


def _read_legacy_normalizer(path: Path) -> Any:
    """A pickled ``VecNormalize`` (runs code from the file: only for trusted files)."""
    try:
        with open(path, "rb") as fh:
            normalizer = pickle.load(fh)  # the caller opted in (trusted=True)
    except Exception as exc:  # a damaged pickle can raise almost anything
        raise ValueError(
            f"{path}: not a VecNormalize pickle ({type(exc).__name__}: {exc}); expected the "
            "file that ship-gym train wrote beside model.zip"
        ) from None
    if not hasattr(normalizer, "obs_rms") or not hasattr(normalizer, "normalize_obs"):
        raise ValueError(
            f"{path}: holds a {type(normalizer).__name__}, not a VecNormalize; expected the "
            "file that ship-gym train wrote beside model.zip"
        )
    normalizer.training = False
    return normalizer


def convert_legacy_normalizer(path: str | Path) -> Path:
    """Write ``<prefix>vecnormalize.npz`` beside a trusted ``<prefix>vecnormalize.pkl``.

    The pickle is read (this runs code from it: call this only on a file you trust).

    Returns
    -------
    Path
        The ``.npz`` written.
    """
    from ship_gym.io_utils import atomic_write

    p = Path(path)
    normalizer = _read_legacy_normalizer(p)
    target = p.with_name(p.name.removesuffix(_LEGACY_NORMALIZER_SUFFIX) + NORMALIZER_SUFFIX)
    atomic_write(target, lambda tmp: save_obs_normalizer(normalizer, tmp))
    return target


def load_policy(
    path: str | Path,
    device: str = "cpu",
    *,
    residual: bool = False,
    trusted: bool = False,
    expected_sha256: str | None = None,
) -> ModelPolicy:
    """Load a model saved by :mod:`ship_gym.agents.train` (a run directory or a ``.zip``).

    Loading an SB3 model runs code from the file (pickle): the model is loaded only when
    trusted (:func:`ship_gym.envs.policy_trust.check_policy_trust`: ``trusted``, a matching
    ``expected_sha256``, trained by this installation or shipped), else
    :class:`~ship_gym.envs.policy_trust.UntrustedPolicyError` is raised before anything of it
    is unpickled.

    The algorithm is read from the run's ``config.toml`` when present, else every SB3 algorithm
    is tried. A ``vecnormalize.npz`` beside the model is applied to the observations (for
    ``<prefix>model.zip``, e.g. ``final_model.zip``, the ``<prefix>vecnormalize.npz``); a
    ``vecnormalize.pkl`` of an earlier version (a pickle) only with ``trusted``.

    A residual run (``residual.json`` beside the model) holds only the correction of a classical
    controller: it is refused unless ``residual`` is True (what
    :func:`ship_gym.agents.residual.load_agent_policy`, which adds the controller, passes), so
    that the correction is never run as if it were the policy.

    Parameters
    ----------
    path : str or Path
        The run folder or its ``model.zip``.
    device : str
        torch device.
    residual : bool
        Accept a residual run's correction.
    trusted : bool
        The caller vouches for the files (explicit opt-in; also allows a legacy ``.pkl``).
    expected_sha256 : str, optional
        The model's SHA-256 recorded earlier: the file must match it.
    """
    from ship_gym.envs.policy_trust import UntrustedPolicyError, check_policy_trust

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
    data = zip_path.read_bytes()  # checked and loaded from the same bytes
    check_policy_trust(data, zip_path, trusted=trusted, expected_sha256=expected_sha256)
    # each checkpoint beside its own statistics: model.zip + vecnormalize.npz, and the
    # validation's final_model.zip + final_vecnormalize.npz (ship_gym.agents.validation)
    prefix = zip_path.name.removesuffix("model.zip") if zip_path.name.endswith("model.zip") else ""
    norm_path = run_dir / f"{prefix}{NORMALIZER_SUFFIX}"
    legacy_path = run_dir / f"{prefix}{_LEGACY_NORMALIZER_SUFFIX}"
    if not norm_path.exists() and legacy_path.exists() and not trusted:
        raise UntrustedPolicyError(
            f"{legacy_path}: observation statistics saved as a pickle (by an earlier version), "
            "which runs any code its author put in it when loaded; if you trust where it came "
            "from, pass --trust-policy (ship-gym evaluate, campaign run) or trusted=True, or "
            "convert it once with ship_gym.envs.saved_policies.convert_legacy_normalizer; see "
            "docs/security.md"
        )
    import stable_baselines3

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
            model = getattr(stable_baselines3, name).load(io.BytesIO(data), device=device)
            break
        except Exception as exc:  # wrong algorithm class or a damaged file: try the next
            errors.append(f"{name}: {exc}")
    if model is None:
        raise ValueError(f"{zip_path}: could not load it as {names}: {'; '.join(errors)}")
    normalizer: Any = None
    shape = getattr(model.observation_space, "shape", None)
    if norm_path.exists():
        normalizer = read_obs_normalizer(norm_path, shape)
    elif legacy_path.exists():
        normalizer = _read_legacy_normalizer(legacy_path)
        legacy_shape = getattr(getattr(normalizer, "obs_rms", None), "mean", np.empty(0)).shape
        if shape is not None and tuple(legacy_shape) != tuple(shape):
            raise ValueError(
                f"{legacy_path}: statistics of shape {legacy_shape}, the model observes shape "
                f"{tuple(shape)}; expected the statistics of this run's model"
            )
    return ModelPolicy(
        model=model, obs_normalizer=normalizer, path=str(zip_path), training_env=training_env
    )
