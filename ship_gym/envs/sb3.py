"""stable-baselines3 adapter: a Gymnasium ``VectorEnv`` (ours: batched) seen as an SB3 ``VecEnv``.

SB3 algorithms step a ``stable_baselines3.common.vec_env.VecEnv``, whose conventions differ from
Gymnasium 1.x vector envs:

* step returns ``obs, reward, terminated, truncated, infos`` (Gymnasium) vs
  ``obs, reward, done, infos`` (SB3);
* infos are one dict of (N,) arrays with ``_key`` masks vs a list of N dicts;
* the last observation of an episode is ``infos["final_obs"][i]`` (``SAME_STEP`` autoreset) vs
  ``infos[i]["terminal_observation"]``; a time-limit end is ``truncated[i]`` vs
  ``infos[i]["TimeLimit.truncated"]``;
* seeding is ``reset(seed=s)`` vs ``seed(s)`` followed by ``reset()``.

:class:`SB3VecEnv` translates: it wraps a vector env built with
``autoreset_mode=AutoresetMode.SAME_STEP`` (the episode that ends in a step is reset in that same
step, as SB3 expects), turns the dict of arrays into per-episode dicts, and passes the seeds of
:meth:`seed` (``s + i`` for episode i, SB3's rule, identical to our vector env's) to the next
reset. With the same seed, episode i of ``SB3VecEnv(make_vec(id, N))`` therefore runs the same
trajectory as environment i of ``DummyVecEnv([make(id)] * N)`` (tested), while stepping all N
ships in one batched call.

Attributes and methods of the wrapped vector env are shared by all its episodes:
:meth:`get_attr` returns the one value for every requested index (``observation_space`` and
``action_space`` are answered with the single-episode spaces, as SB3 expects), :meth:`env_method`
calls the method once and repeats the result, and :meth:`set_attr` only accepts all indices.

stable-baselines3 (and torch) are imported only when the adapter is used: ``SB3VecEnv`` is
created on first access (module ``__getattr__``, PEP 562), so ``import ship_gym.envs.sb3`` stays
light, as every ``ship_gym`` module must (``tests/package/test_import_boundaries.py``).
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Protocol

import gymnasium
import numpy as np
from gymnasium.vector import AutoresetMode
from numpy.typing import NDArray

if TYPE_CHECKING:
    from stable_baselines3.common.vec_env import VecEnv

__all__ = ["SB3VecEnv", "make_sb3_vec_env", "vector_infos_to_list"]  # noqa: F822 (lazy)

_SINGLE_SPACE_ALIASES = {
    "observation_space": "single_observation_space",
    "action_space": "single_action_space",
}
_SKIPPED_INFO_KEYS = frozenset({"final_obs", "final_info"})


def vector_infos_to_list(infos: dict[str, Any], num_envs: int) -> list[dict[str, Any]]:
    """Gymnasium vector infos (dict of (N,) arrays with ``_key`` masks) → N per-episode dicts.

    Entries whose mask is False for episode i are left out of its dict; numpy scalars become
    Python numbers. ``final_obs`` / ``final_info`` are skipped (the adapter handles them).
    """
    out: list[dict[str, Any]] = [{} for _ in range(num_envs)]
    for key, values in infos.items():
        if key.startswith("_") or key in _SKIPPED_INFO_KEYS:
            continue
        mask = infos.get(f"_{key}")
        if isinstance(values, dict):  # nested info dict (Gymnasium layout): recurse
            nested = vector_infos_to_list(values, num_envs)
            for i in range(num_envs):
                if (mask is None or mask[i]) and nested[i]:
                    out[i][key] = nested[i]
            continue
        for i in range(num_envs):
            if mask is None or mask[i]:
                value = values[i]
                out[i][key] = value.item() if isinstance(value, np.generic) else value
    return out


class _BatchedVectorEnv(Protocol):
    """What :class:`SB3VecEnv` uses of a Gymnasium vector env: one seed per episode at reset
    (as :class:`~ship_gym.envs.base.TaskVectorEnv` and Gymnasium's ``SyncVectorEnv`` take
    them), batched steps and one rgb frame per episode."""

    @property
    def metadata(self) -> dict[str, Any]: ...
    @property
    def num_envs(self) -> int: ...
    @property
    def single_observation_space(self) -> gymnasium.Space[Any]: ...
    @property
    def single_action_space(self) -> gymnasium.Space[Any]: ...
    def reset(
        self,
        *,
        seed: int | Sequence[int | None] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[NDArray, dict[str, Any]]: ...
    def step(
        self, actions: NDArray
    ) -> tuple[NDArray, NDArray, NDArray, NDArray, dict[str, Any]]: ...
    def render(self) -> tuple[NDArray, ...] | None: ...
    def close(self) -> None: ...


@functools.cache
def _sb3_vec_env_class() -> type:
    """Define :class:`SB3VecEnv` (imports stable-baselines3; done once, on first use)."""
    from stable_baselines3.common.vec_env import VecEnv

    class SB3VecEnv(VecEnv):
        """A Gymnasium ``VectorEnv`` with ``SAME_STEP`` autoreset as an SB3 ``VecEnv``.

        Parameters
        ----------
        env : gymnasium.vector.VectorEnv
            The vector env, built with ``autoreset_mode=AutoresetMode.SAME_STEP`` (checked from
            its ``metadata["autoreset_mode"]``; anything else raises ``ValueError``).

        Notes
        -----
        Per-episode infos carry ``"terminal_observation"`` (float32 observation at the end of an
        episode, before the automatic reset) and ``"TimeLimit.truncated"`` (True when the episode
        ended by the time limit and not by termination), as SB3's ``DummyVecEnv`` does.
        """

        def __init__(self, env: _BatchedVectorEnv) -> None:
            mode = env.metadata.get("autoreset_mode", AutoresetMode.NEXT_STEP)
            if AutoresetMode(mode) != AutoresetMode.SAME_STEP:
                raise ValueError(
                    "SB3VecEnv needs a vector env with autoreset_mode=AutoresetMode.SAME_STEP, "
                    f"got {mode!r} (pass autoreset_mode=AutoresetMode.SAME_STEP to make_vec)"
                )
            self.env = env
            self._actions: NDArray | None = None
            super().__init__(
                num_envs=env.num_envs,
                observation_space=env.single_observation_space,
                action_space=env.single_action_space,
            )

        # -- stepping ---------------------------------------------------------------------
        def reset(self) -> NDArray:
            seeds = None if all(s is None for s in self._seeds) else list(self._seeds)
            options = self._options[0] if self._options else {}
            if any(o != options for o in self._options):
                raise ValueError(
                    "SB3VecEnv steps one batched env: set_options() must give every episode the "
                    f"same options, got {self._options!r}"
                )
            obs, infos = self.env.reset(seed=seeds, options=dict(options) or None)
            self.reset_infos = vector_infos_to_list(infos, self.num_envs)
            self._reset_seeds()
            self._reset_options()
            return obs

        def step_async(self, actions: NDArray) -> None:
            self._actions = np.asarray(actions)

        def step_wait(self) -> tuple[NDArray, NDArray, NDArray, list[dict[str, Any]]]:
            if self._actions is None:
                raise RuntimeError("step_wait() called without step_async()")
            obs, reward, terminated, truncated, infos = self.env.step(self._actions)
            self._actions = None
            terminated = np.asarray(terminated, dtype=bool)
            truncated = np.asarray(truncated, dtype=bool)
            dones = terminated | truncated
            per_env = vector_infos_to_list(infos, self.num_envs)
            final_obs = infos.get("final_obs")
            for i in range(self.num_envs):
                per_env[i]["TimeLimit.truncated"] = bool(truncated[i] and not terminated[i])
                if dones[i]:
                    if final_obs is None or final_obs[i] is None:
                        raise RuntimeError(
                            f"episode {i} ended but the vector env gave no final_obs: it must "
                            "use autoreset_mode=AutoresetMode.SAME_STEP"
                        )
                    per_env[i]["terminal_observation"] = final_obs[i]
                    self.reset_infos[i] = {}
            return obs, np.asarray(reward, dtype=np.float32), dones, per_env

        def close(self) -> None:
            self.env.close()

        # -- rendering --------------------------------------------------------------------
        def get_images(self) -> Sequence[NDArray | None]:
            if self.render_mode != "rgb_array":
                return [None] * self.num_envs
            frames = self.env.render()
            return list(frames) if frames is not None else [None] * self.num_envs

        # -- attributes shared by all episodes ------------------------------------------------
        def _indices(self, indices: Any) -> list[int]:
            ids = list(self._get_indices(indices))
            bad = [i for i in ids if not 0 <= int(i) < self.num_envs]
            if bad:
                raise ValueError(f"env indices {bad} out of range [0, {self.num_envs})")
            return [int(i) for i in ids]

        def get_attr(self, attr_name: str, indices: Any = None) -> list[Any]:
            value = getattr(self.env, _SINGLE_SPACE_ALIASES.get(attr_name, attr_name))
            return [value for _ in self._indices(indices)]

        def set_attr(self, attr_name: str, value: Any, indices: Any = None) -> None:
            if sorted(self._indices(indices)) != list(range(self.num_envs)):
                raise ValueError(
                    f"set_attr({attr_name!r}): attributes of the batched env are shared by all "
                    f"{self.num_envs} episodes; set them for all indices (indices=None)"
                )
            setattr(self.env, attr_name, value)

        def env_method(
            self, method_name: str, *method_args: Any, indices: Any = None, **method_kwargs: Any
        ) -> list[Any]:
            ids = self._indices(indices)
            result = getattr(self.env, method_name)(*method_args, **method_kwargs)
            return [result for _ in ids]

        def env_is_wrapped(self, wrapper_class: type, indices: Any = None) -> list[bool]:
            wrapped = isinstance(self.env, wrapper_class)
            return [wrapped for _ in self._indices(indices)]

    SB3VecEnv.__module__ = __name__
    SB3VecEnv.__qualname__ = "SB3VecEnv"
    return SB3VecEnv


def __getattr__(name: str) -> Any:  # PEP 562: build the SB3 class on first access
    if name == "SB3VecEnv":
        return _sb3_vec_env_class()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def make_sb3_vec_env(
    env_id: str,
    n_envs: int,
    seed: int | None = None,
    *,
    monitor: bool = True,
    vectorization: str = "vector",
    env_kwargs: dict[str, Any] | None = None,
    **kwargs: Any,
) -> VecEnv:
    """Build an SB3 ``VecEnv`` of ``n_envs`` episodes of a registered environment.

    Parameters
    ----------
    env_id : str
        Registered id, e.g. ``"ship_gym/RollOneDOF-v0"`` (``"ship_gym:"`` prefix optional).
    n_envs : int
        Number of parallel episodes.
    seed : int, optional
        Episode i is seeded ``seed + i`` at the first reset (SB3's ``VecEnv.seed`` rule).
    monitor : bool
        Wrap in SB3's ``VecMonitor`` (episode returns/lengths in ``info["episode"]``, which SB3's
        loggers and ``evaluate_policy`` read).
    vectorization : {"vector", "dummy"}
        ``"vector"``: our batched ``TaskVectorEnv`` (``make_vec(..., "vector_entry_point")``,
        all episodes in one call) through :class:`SB3VecEnv`; ``"dummy"``: SB3's
        ``DummyVecEnv`` of single ``gymnasium.make`` envs (the reference path).
    env_kwargs : dict, optional
        Keyword arguments of the environment (physics, reward, ``render_mode``...).
    **kwargs
        Merged into ``env_kwargs`` (convenience).

    Returns
    -------
    stable_baselines3.common.vec_env.VecEnv
        Not yet reset; call ``reset()`` (SB3 algorithms do).
    """
    from stable_baselines3.common.vec_env import DummyVecEnv, VecMonitor

    if isinstance(n_envs, bool) or not isinstance(n_envs, int | np.integer) or n_envs < 1:
        raise ValueError(f"n_envs must be a positive integer, got {n_envs!r}")
    env_kwargs = {**(env_kwargs or {}), **kwargs}
    full_id = env_id if ":" in env_id else f"ship_gym:{env_id}"
    if vectorization == "vector":
        vector_env = gymnasium.make_vec(
            full_id,
            num_envs=int(n_envs),
            vectorization_mode="vector_entry_point",
            autoreset_mode=AutoresetMode.SAME_STEP,
            **env_kwargs,
        )
        venv = _sb3_vec_env_class()(vector_env)
    elif vectorization == "dummy":
        venv = DummyVecEnv(
            [functools.partial(gymnasium.make, full_id, **env_kwargs) for _ in range(int(n_envs))]
        )
    else:
        raise ValueError(f"vectorization must be 'vector' or 'dummy', got {vectorization!r}")
    if seed is not None:
        venv.seed(int(seed))
    return VecMonitor(venv) if monitor else venv
