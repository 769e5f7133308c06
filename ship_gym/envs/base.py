"""One task, two faces: N episodes stepped together, seen as a ``gymnasium.Env`` or a ``VectorEnv``.

An environment author writes one :class:`BatchedTask`: the physics, observations, rewards and
termination of N independent episodes held in arrays with a leading episode axis (for the ship
tasks, one :class:`ship_gym.engine.batch.BatchSimulator` holding N ships). Two generic
wrappers turn it into Gymnasium objects:

* :class:`TaskEnv` — one episode (N = 1), a ``gymnasium.Env``: what ``gymnasium.make`` returns
  (wrapped in ``TimeLimit`` by the registration's ``max_episode_steps``);
* :class:`TaskVectorEnv` — N episodes in one call, a ``gymnasium.vector.VectorEnv``: what
  ``gymnasium.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")`` returns.

Both run the *same* code path, so episode i of a vector env reset with ``seed=s`` is the single
env reset with ``seed=s + i`` (same sea, same trajectory, to the last bit): a policy can be
trained batched and evaluated single, on identical seas.

Rules shared by every environment (DESIGN.md §4):

* actions are ``Box(-1, 1, float32)``; a non-finite action or one of the wrong shape raises
  ``ValueError``; finite actions outside [-1, 1] are clipped;
* the reward is the sum of the weighted terms of :attr:`TaskStep.reward_terms`, each reported as
  ``info["reward_<term>"]``; the Safe-RL cost is ``info["cost"]``; ``info["time"]`` is the
  episode time [s];
* observation spaces have finite bounds (the checkers of Gymnasium and stable-baselines3 warn on
  infinite ones); the wrappers clip observations to them as a last guard (a task whose
  :attr:`BatchedTask.observations_bounded` is true clips them itself), so a task documents
  bounds its physical values stay inside in normal operation;
* capsize is ``terminated``; the time limit is ``truncated`` (``TimeLimit`` for the single env,
  the vector env's own step counter); a capsize on the last step of the limit is both, in both;
  the single env never resets itself;
* all randomness comes from the episode's generator (``self.np_random`` for the single env, one
  generator per episode for the vector env), so ``reset(seed=s)`` reproduces the same sea; an
  automatic reset continues that generator where the single env's ``reset()`` would (in
  ``NEXT_STEP`` mode the waiting step's draws are undone), so the vector env is Gymnasium's
  ``SyncVectorEnv`` of single envs bit for bit in both autoreset modes.

Autoreset of the vector env follows Gymnasium 1.x: ``AutoresetMode.NEXT_STEP`` (default; the
step after an episode ended resets it, returns its first observation with reward 0 and ignores
its action) or ``AutoresetMode.SAME_STEP`` (the episode is reset in the step that ended it;
its last observation and info are in ``info["final_obs"]`` / ``info["final_info"]``, what the
stable-baselines3 adapter :mod:`ship_gym.envs.sb3` needs). Partial resets through
``reset(options={"reset_mask": mask})`` are supported.
"""

from __future__ import annotations

import abc
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import gymnasium
import numba
import numpy as np
from gymnasium import spaces
from gymnasium.utils import seeding
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space
from numpy.typing import ArrayLike, NDArray

from ship_gym.envs._kernels import clip_scalar_bound

if TYPE_CHECKING:
    from ship_gym.envs.rendering import HumanViewer, RenderSnapshot

__all__ = ["BatchedTask", "TaskEnv", "TaskStep", "TaskVectorEnv", "validate_actions"]

RENDER_MODES = ("human", "rgb_array")


@dataclass(frozen=True)
class TaskStep:
    """Outcome of one control step for all N episodes of a task.

    Attributes
    ----------
    reward_terms : Mapping[str, NDArray]
        Weighted reward terms, name → (N,) [-]; the reward is their sum.
    cost : NDArray
        (N,) Safe-RL cost ≥ 0 (e.g. dangerous-roll exceedance) [-].
    terminated : NDArray
        (N,) bool: the episode reached a terminal state (capsize, divergence).
    info : Mapping[str, NDArray]
        Further per-episode diagnostics, name → (N,) (e.g. ``"capsized"``, ``"roll_deg"``).
    """

    reward_terms: Mapping[str, NDArray]
    cost: NDArray
    terminated: NDArray
    info: Mapping[str, NDArray]

    def reward(self) -> NDArray:
        """Σ of the weighted terms, (N,) float64, summed in the terms' order."""
        total = np.zeros(np.asarray(self.cost).shape)
        for value in self.reward_terms.values():
            total = total + np.asarray(value, dtype=np.float64)
        return total


class BatchedTask(abc.ABC):
    """N independent episodes of one task, stepped together (the single env is N = 1).

    Subclasses set, in ``__init__``, :attr:`observation_space` and :attr:`action_space` (one
    episode's, float32), :attr:`observation_names`, :attr:`action_names` (units in the names)
    and :attr:`control_dt` [s], and validate their keyword arguments (typed, with units, listed
    in the environment's docstring) with clear errors.
    """

    observation_space: spaces.Box
    action_space: spaces.Box
    observation_names: tuple[str, ...]
    action_names: tuple[str, ...]
    control_dt: float
    observations_bounded: ClassVar[bool] = False
    """True if :meth:`observations` returns a new float32 array already clipped to the
    bounds of :attr:`observation_space` (the wrappers then skip their clip)."""

    def __init__(self, num_envs: int) -> None:
        if isinstance(num_envs, bool) or not isinstance(num_envs, int | np.integer):
            raise ValueError(f"num_envs must be a positive integer, got {num_envs!r}")
        if num_envs < 1:
            raise ValueError(f"num_envs must be a positive integer, got {num_envs!r}")
        self.num_envs = int(num_envs)

    @abc.abstractmethod
    def reset_episodes(
        self,
        ids: NDArray[np.int64],
        rngs: Sequence[np.random.Generator],
        options: Mapping[str, Any] | None,
    ) -> None:
        """Start new episodes ``ids``; all randomness of episode ``ids[k]`` from ``rngs[k]``."""

    @abc.abstractmethod
    def step(self, actions: NDArray) -> TaskStep:
        """Advance every episode by :attr:`control_dt`.

        ``actions`` is (N, n_act) float64, finite and inside [-1, 1]. Episodes that are over may
        be advanced too (the wrapper resets them afterwards): a capsized or diverged ship being
        stepped must not raise.
        """

    @abc.abstractmethod
    def observations(self) -> NDArray:
        """(N, n_obs) float32 observations, inside :attr:`observation_space`."""

    def reset_info(self, ids: NDArray[np.int64]) -> Mapping[str, NDArray]:
        """Per-episode information at reset (sampled sea, heading, loading…), name → (len(ids),)."""
        return {}

    def snapshot(self, i: int) -> RenderSnapshot:
        """What :mod:`ship_gym.envs.rendering` draws for episode ``i``."""
        raise NotImplementedError(f"{type(self).__name__} does not render")

    def close(self) -> None:  # noqa: B027 - optional hook, nothing to release by default
        """Release resources (nothing by default)."""


def validate_actions(
    actions: ArrayLike,
    shape: tuple[int, ...],
    name: str = "actions",
    scalar_ok: bool = False,
) -> NDArray:
    """Actions as float64 of ``shape``, clipped to [-1, 1].

    ``name`` is the argument as the user passed it (``"action"`` for the single env,
    ``"actions"`` for the vector env, whose ``shape`` is ``(num_envs, n_actions)``); with
    ``scalar_ok`` a plain number stands for an action of one entry. No reshaping: an array of
    the right size but the wrong shape (e.g. (n_actions, num_envs)) would give the ships each
    other's commands.

    Raises
    ------
    TypeError
        Not an array of real numbers (strings, complex, objects, booleans).
    ValueError
        Wrong shape, or any NaN/inf entry (a diverging policy must fail loudly, not steer the
        ship with NaN).
    """
    expected = f"expected shape {shape} float array in Box(-1, 1)"
    if isinstance(actions, np.ndarray):
        a = actions
    else:
        try:
            a = np.asarray(actions)
        except (TypeError, ValueError) as err:  # ragged sequences
            raise ValueError(
                f"{name} must be an array of {expected}, got {actions!r}: {err}"
            ) from None
    if a.dtype.kind not in "fiu":
        raise TypeError(
            f"{name} must be real numbers ({expected}), got dtype {a.dtype} shape {a.shape}: "
            f"{actions!r}"
        )
    if a.shape != shape:
        if scalar_ok and a.ndim == 0 and math.prod(shape) == 1:
            a = a.reshape(shape)
        else:
            raise ValueError(
                f"{name} must have shape {shape} ({expected}), got shape {a.shape}: {a!r}"
            )
    a = a.astype(np.float64, copy=False)
    out = np.empty(shape)
    if not _clip_unit(a.reshape(-1), out.reshape(-1)):
        raise ValueError(f"{name} must be finite ({expected}), got {a!r}")
    return out


@numba.njit(cache=True, nogil=True)
def _clip_unit(a: NDArray, out: NDArray) -> bool:  # pragma: no cover - compiled
    """out = np.clip(a, -1, 1) (1-D, bit for bit); False if an entry is not finite."""
    for i in range(a.shape[0]):
        v = a[i]
        if not math.isfinite(v):
            return False
        out[i] = clip_scalar_bound(v, -1.0, 1.0)
    return True


def _bounded(obs: NDArray, space: spaces.Box, task: BatchedTask) -> NDArray[np.float32]:
    """Observations as float32 clipped to the space's bounds (broadcast over episodes); as
    they are from a task whose :meth:`BatchedTask.observations` already does that."""
    if task.observations_bounded:
        return obs
    out = np.clip(obs, space.low, space.high).astype(np.float32, copy=False)
    if not np.isfinite(out).all():  # a diverged state never reaches the agent as NaN
        out = np.nan_to_num(out, nan=0.0, posinf=0.0, neginf=0.0)
    return out


def _guard_divergence(
    reward: NDArray, terminated: NDArray, info: dict[str, Any]
) -> tuple[NDArray, NDArray]:
    """Episodes whose reward is not finite: reward 0, terminated, ``info["diverged"]`` set (the
    last guard behind the tasks' own divergence checks; a no-op for finite rewards)."""
    bad = ~np.isfinite(reward)
    if bad.any():
        reward = np.where(bad, 0.0, reward)
        terminated = terminated | bad
        info["diverged"] = np.asarray(info.get("diverged", np.zeros(bad.shape, bool)), bool) | bad
    return reward, terminated


def _check_options(options: Any) -> None:
    if options is not None and not isinstance(options, Mapping):
        raise TypeError(
            f"options must be a mapping (dict) of reset options or None, got "
            f"{type(options).__name__} {options!r}"
        )


def _check_render_mode(render_mode: str | None) -> str | None:
    if render_mode is not None and render_mode not in RENDER_MODES:
        raise ValueError(f"render_mode must be one of {RENDER_MODES} or None, got {render_mode!r}")
    return render_mode


def _render_fps(control_dt: float) -> int:
    return max(1, round(1.0 / float(control_dt)))


class _Rendering:
    """rgb_array / human rendering of one episode of a task (shared by both wrappers)."""

    def __init__(self, render_mode: str | None) -> None:
        self.render_mode = _check_render_mode(render_mode)
        self._viewer: HumanViewer | None = None

    def frame(self, task: BatchedTask, i: int) -> NDArray[np.uint8] | None:
        from ship_gym.envs.rendering import HumanViewer

        if self.render_mode == "rgb_array":
            return self.rgb(task, i)
        if self.render_mode == "human":
            if self._viewer is None:
                self._viewer = HumanViewer()
            self._viewer.show(task.snapshot(i))
        return None

    def rgb(self, task: BatchedTask, i: int) -> NDArray[np.uint8]:
        """The rgb_array frame of episode i."""
        from ship_gym.envs.rendering import render_rgb

        return render_rgb(task.snapshot(i))

    def close(self) -> None:
        if self._viewer is not None:
            self._viewer.close()
            self._viewer = None


class _TaskView:
    """What both wrappers expose of their task: names of the entries and the control step."""

    task: BatchedTask

    @property
    def observation_names(self) -> tuple[str, ...]:
        """Names (with units) of one episode's observation entries."""
        return self.task.observation_names

    @property
    def observation_entries(self) -> tuple[Any, ...]:
        """The task's observation table (:class:`ship_gym.envs.observations.Observation` per
        entry: name, unit, bounds, noise; empty for a task without one)."""
        return tuple(getattr(self.task, "observation_entries", ()))

    @property
    def action_names(self) -> tuple[str, ...]:
        """Names (with the physical scaling) of one episode's action entries."""
        return self.task.action_names

    @property
    def control_dt(self) -> float:
        """Control time step [s]."""
        return self.task.control_dt


class TaskEnv(_TaskView, gymnasium.Env):
    """One episode of a :class:`BatchedTask` as a ``gymnasium.Env``.

    Subclasses set :attr:`task_class` and write the environment's docstring (Gymnasium v5
    template). Keyword arguments other than ``render_mode`` go to the task.
    """

    task_class: ClassVar[type[BatchedTask]]
    # an instance attribute with a class default, as gymnasium.Env declares it (make() reads the
    # class's render modes; __init__ sets the instance's render_fps)
    metadata: dict[str, Any] = {"render_modes": list(RENDER_MODES), "render_fps": 4}  # noqa: RUF012
    observation_space: spaces.Box
    action_space: spaces.Box

    def __init__(self, render_mode: str | None = None, **kwargs: Any) -> None:
        self._rendering = _Rendering(render_mode)
        self.render_mode = render_mode
        self.task = self.task_class(num_envs=1, **kwargs)
        self.observation_space = self.task.observation_space
        self.action_space = self.task.action_space
        self.metadata = {**type(self).metadata, "render_fps": _render_fps(self.task.control_dt)}
        self._ids = np.zeros(1, dtype=np.int64)
        self._steps = 0
        self._has_reset = False

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[NDArray[np.float32], dict[str, Any]]:
        if seed is not None and (
            isinstance(seed, bool) or not isinstance(seed, int | np.integer) or seed < 0
        ):
            raise ValueError(f"seed must be a non-negative int or None, got {seed!r}")
        _check_options(options)
        super().reset(seed=None if seed is None else int(seed))
        self.task.reset_episodes(self._ids, [self.np_random], options)
        self._steps = 0
        self._has_reset = True
        info = {k: _item(v, 0) for k, v in self.task.reset_info(self._ids).items()}
        info["time"] = 0.0
        if self.render_mode == "human":
            self.render()
        return _bounded(self.task.observations()[0], self.observation_space, self.task), info

    def step(
        self, action: ArrayLike
    ) -> tuple[NDArray[np.float32], float, bool, bool, dict[str, Any]]:
        if not self._has_reset:
            raise RuntimeError("call reset() before step()")
        a = validate_actions(
            action, self.action_space.shape, name="action", scalar_ok=True
        ).reshape(1, -1)
        result = self.task.step(a)
        self._steps += 1
        info: dict[str, Any] = {f"reward_{k}": float(v[0]) for k, v in result.reward_terms.items()}
        info["cost"] = float(result.cost[0])
        info.update({k: _item(v, 0) for k, v in result.info.items()})
        reward = float(result.reward()[0])
        terminated = bool(result.terminated[0])
        if not math.isfinite(reward):  # the last guard behind the task's divergence checks
            reward, terminated = 0.0, True
            info["diverged"] = True
        info["time"] = self._steps * self.task.control_dt
        if self.render_mode == "human":
            self.render()
        return (
            _bounded(self.task.observations()[0], self.observation_space, self.task),
            reward,
            terminated,
            False,
            info,
        )

    def render(self) -> NDArray[np.uint8] | None:
        if self.render_mode is None:
            gymnasium.logger.warn("render() called with render_mode=None: nothing to draw")
            return None
        return self._rendering.frame(self.task, 0)

    def close(self) -> None:
        self._rendering.close()
        self.task.close()


def _item(values: ArrayLike, i: int) -> Any:
    if type(values) is np.ndarray and values.ndim == 1:
        return values.item(i)  # what values[i].item() gives, without the NumPy scalar
    v = np.asarray(values)[i]
    return v.item() if isinstance(v, np.generic) else v


class TaskVectorEnv(_TaskView, VectorEnv):
    """N episodes of a :class:`BatchedTask` stepped in one call, a ``gymnasium.vector.VectorEnv``.

    Parameters
    ----------
    num_envs : int
        Number of episodes N.
    render_mode : {"rgb_array", "human"}, optional
        ``render()`` returns one frame per episode (rgb_array) or shows episode 0 (human).
    max_episode_steps : int, optional
        Time limit in control steps (``truncated``); ``make_vec`` passes the registered one.
    autoreset_mode : AutoresetMode or str
        ``NEXT_STEP`` (Gymnasium's default) or ``SAME_STEP``; ``DISABLED`` is refused.
    **kwargs
        The task's keyword arguments (as for the single env).
    """

    task_class: ClassVar[type[BatchedTask]]
    single_observation_space: spaces.Box
    single_action_space: spaces.Box
    # as in TaskEnv: an instance attribute with a class default (gymnasium.vector.VectorEnv's)
    metadata: dict[str, Any] = {  # noqa: RUF012
        "render_modes": list(RENDER_MODES),
        "render_fps": 4,
        "autoreset_mode": AutoresetMode.NEXT_STEP,
    }

    def __init__(
        self,
        num_envs: int = 1,
        render_mode: str | None = None,
        max_episode_steps: int | None = None,
        autoreset_mode: AutoresetMode | str = AutoresetMode.NEXT_STEP,
        **kwargs: Any,
    ) -> None:
        try:
            mode = AutoresetMode(autoreset_mode)
        except ValueError:
            raise ValueError(
                f"autoreset_mode must be 'NextStep' or 'SameStep', got {autoreset_mode!r}"
            ) from None
        if mode not in (AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP):
            raise ValueError(f"autoreset_mode must be NEXT_STEP or SAME_STEP, got {mode!r}")
        if max_episode_steps is not None and (
            isinstance(max_episode_steps, bool)
            or not isinstance(max_episode_steps, int | np.integer)
            or max_episode_steps < 1
        ):
            raise ValueError(
                f"max_episode_steps must be a positive integer or None, got {max_episode_steps!r}"
            )
        self._rendering = _Rendering(render_mode)
        self.render_mode = render_mode
        self.task = self.task_class(num_envs=num_envs, **kwargs)
        self.num_envs = self.task.num_envs
        self.max_episode_steps = None if max_episode_steps is None else int(max_episode_steps)
        self.autoreset_mode = mode
        self.single_observation_space = self.task.observation_space
        self.single_action_space = self.task.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.metadata = {
            **type(self).metadata,
            "render_fps": _render_fps(self.task.control_dt),
            "autoreset_mode": mode,
        }
        n = self.num_envs
        self._rngs: list[np.random.Generator | None] = [None] * n
        self._steps = np.zeros(n, dtype=np.int64)
        self._pending_reset = np.zeros(n, dtype=bool)
        self._has_reset = False

    def _observations(self) -> NDArray[np.float32]:
        return _bounded(self.task.observations(), self.single_observation_space, self.task)

    def _seed(self, seed: int | Sequence[int | None] | None, ids: NDArray[np.int64]) -> None:
        if seed is None:
            seeds: list[int | None] = [None] * len(ids)
        elif isinstance(seed, int | np.integer):
            if isinstance(seed, bool) or seed < 0:
                raise ValueError(self._seed_error(seed))
            seeds = [int(seed) + int(i) for i in ids]
        else:
            if isinstance(seed, str | bytes | Mapping) or not isinstance(
                seed, Sequence | np.ndarray
            ):
                raise ValueError(self._seed_error(seed))
            seeds = list(seed)
            if len(seeds) != self.num_envs or not all(
                s is None
                or (isinstance(s, int | np.integer) and not isinstance(s, bool) and s >= 0)
                for s in seeds
            ):
                raise ValueError(self._seed_error(seed))
            seeds = [None if s is None else int(s) for s in seeds]
            seeds = [seeds[int(i)] for i in ids]
        for i, s in zip(ids, seeds, strict=True):
            if s is not None or self._rngs[int(i)] is None:
                self._rngs[int(i)], _ = seeding.np_random(s)

    def _seed_error(self, seed: object) -> str:
        return (
            f"seed must be a non-negative int, None or a sequence of {self.num_envs} such seeds "
            f"(one per episode), got {seed!r}"
        )

    def _rng(self, i: int) -> np.random.Generator:
        rng = self._rngs[i]
        assert rng is not None  # seeded by _seed at the first reset (all episodes)
        return rng

    def _reset_ids(self, ids: NDArray[np.int64], options: Mapping[str, Any] | None) -> None:
        if ids.size == 0:
            return
        self.task.reset_episodes(ids, [self._rng(int(i)) for i in ids], options)
        self._steps[ids] = 0
        self._pending_reset[ids] = False

    def reset(
        self,
        *,
        seed: int | Sequence[int | None] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[NDArray[np.float32], dict[str, Any]]:
        _check_options(options)
        options = dict(options or {})
        mask = options.pop("reset_mask", None)
        if mask is None:
            ids = np.arange(self.num_envs, dtype=np.int64)
        else:
            mask = np.asarray(mask)
            if mask.shape != (self.num_envs,) or mask.dtype != np.bool_:
                raise ValueError(
                    f"options['reset_mask'] must be a bool array of shape ({self.num_envs},), "
                    f"got {mask!r}"
                )
            if not self._has_reset and not mask.all():
                raise ValueError("the first reset() must reset every episode (reset_mask all True)")
            ids = np.flatnonzero(mask).astype(np.int64)
        self._seed(seed, ids)
        self._reset_ids(ids, options or None)
        self._has_reset = True
        infos: dict[str, Any] = {}
        mask_all = np.zeros(self.num_envs, dtype=bool)
        mask_all[ids] = True
        for key, value in self.task.reset_info(ids).items():
            full = np.zeros(self.num_envs, dtype=np.asarray(value).dtype)
            full[ids] = value
            _put(infos, key, full, mask_all)
        _put(infos, "time", np.zeros(self.num_envs), mask_all)
        return self._observations(), infos

    def step(
        self, actions: ArrayLike
    ) -> tuple[NDArray[np.float32], NDArray, NDArray, NDArray, dict[str, Any]]:
        if not self._has_reset:
            raise RuntimeError("call reset() before step()")
        a = validate_actions(actions, (self.num_envs, *self.single_action_space.shape))
        # an episode waiting for its NEXT_STEP reset is stepped with the others, but what the
        # task draws for it (sensor noise) is undone: its generator enters the reset where the
        # single env's reset() finds it, at the end of the last real step
        pending = np.flatnonzero(self._pending_reset).tolist()
        saved = [self._rng(k).bit_generator.state for k in pending]
        result = self.task.step(a)
        for k, state in zip(pending, saved, strict=True):
            self._rng(k).bit_generator.state = state
        stepped = ~self._pending_reset
        self._steps += stepped  # +1 where stepped
        reward = result.reward()
        terminated = np.asarray(result.terminated, dtype=bool).copy()
        diverged_info: dict[str, Any] = {}
        if "diverged" in result.info:
            diverged_info["diverged"] = result.info["diverged"]
        reward, terminated = _guard_divergence(reward, terminated, diverged_info)
        truncated = np.zeros(self.num_envs, dtype=bool)
        if self.max_episode_steps is not None:
            # TimeLimit's rule: the last step is truncated even when it also terminates
            truncated = self._steps >= self.max_episode_steps

        # the Gymnasium vector-info layout (_put): infos[key] and its own copy of the mask
        infos: dict[str, Any] = {}
        for key, value in result.reward_terms.items():
            infos[f"reward_{key}"] = np.asarray(value, dtype=np.float64)
            infos[f"_reward_{key}"] = stepped.copy()
        infos["cost"] = np.asarray(result.cost, dtype=np.float64)
        infos["_cost"] = stepped.copy()
        for key, value in {**result.info, **diverged_info}.items():
            infos[key] = np.asarray(value)
            infos[f"_{key}"] = stepped.copy()
        infos["time"] = self._steps * self.task.control_dt
        infos["_time"] = stepped.copy()

        if self.autoreset_mode == AutoresetMode.NEXT_STEP:
            if self._pending_reset.any():
                ids = np.flatnonzero(self._pending_reset).astype(np.int64)
                self._reset_ids(ids, None)
                reward[ids] = 0.0
                terminated[ids] = False
                truncated[ids] = False
            obs = self._observations()
            self._pending_reset = terminated | truncated
        else:
            done = terminated | truncated
            obs = self._observations()
            if done.any():
                final_obs = np.empty(self.num_envs, dtype=object)
                for i in np.flatnonzero(done):
                    final_obs[i] = obs[i].copy()
                infos["final_obs"] = final_obs
                infos["_final_obs"] = done.copy()
                infos["final_info"] = {
                    k: v for k, v in infos.items() if k not in ("final_obs", "_final_obs")
                }
                infos["_final_info"] = done.copy()
                self._reset_ids(np.flatnonzero(done).astype(np.int64), None)
                obs = self._observations()
        if self.render_mode == "human":
            self.render()
        return obs, reward, terminated, truncated, infos

    def render(self) -> tuple[NDArray[np.uint8], ...] | None:
        if self.render_mode is None:
            gymnasium.logger.warn("render() called with render_mode=None: nothing to draw")
            return None
        if self.render_mode == "human":
            self._rendering.frame(self.task, 0)
            return None
        return tuple(self._rendering.rgb(self.task, i) for i in range(self.num_envs))

    def close_extras(self, **kwargs: Any) -> None:
        self._rendering.close()
        self.task.close()


def _put(infos: dict[str, Any], key: str, values: NDArray, mask: NDArray) -> None:
    """Gymnasium vector-info layout: ``infos[key]`` (N,) and the mask ``infos["_" + key]``."""
    infos[key] = np.asarray(values)
    infos[f"_{key}"] = np.asarray(mask, dtype=bool).copy()
