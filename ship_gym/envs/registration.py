"""The registered environment ids (``ship_gym/<Name>-vN``) and their entry points.

Gymnasium 1.x does not read package entry points: ``import ship_gym`` calls
:func:`register_envs`, and ``gymnasium.make("ship_gym:ship_gym/CourseKeeping-v2")`` imports
``ship_gym`` first (the ``module:`` prefix), so the ids work in a fresh interpreter. Entry points
are strings: registering imports no environment module (and no simulator).

Each id has a single-episode ``entry_point`` (:class:`ship_gym.envs.base.TaskEnv`) and a batched
``vector_entry_point`` (:class:`ship_gym.envs.base.TaskVectorEnv`, used by
``gymnasium.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import gymnasium

if TYPE_CHECKING:
    from ship_gym.envs.base import TaskEnv

NAMESPACE = "ship_gym"


@dataclass(frozen=True)
class EnvEntry:
    """One registered environment.

    Attributes
    ----------
    name : str
        Name without namespace and version (``"CourseKeeping"``).
    module : str
        Module under :mod:`ship_gym.envs` holding ``<name>Env`` and ``<name>VectorEnv``.
    max_episode_steps : int
        Time limit in control steps (the ``TimeLimit`` wrapper of ``gymnasium.make``; the
        vector env counts its own steps).
    version : int
        The id's ``-vN`` (bumped when dynamics, observations, rewards or termination change).
    earlier : tuple of (int, tuple of (str, object))
        Earlier versions kept registered, each with the keyword arguments (name, value pairs)
        that reproduce it (its published results and shipped policies were made with it).
    """

    name: str
    module: str
    max_episode_steps: int
    version: int
    earlier: tuple[tuple[int, tuple[tuple[str, object], ...]], ...] = ()

    @property
    def id(self) -> str:
        return f"{NAMESPACE}/{self.name}-v{self.version}"

    def ids(self) -> tuple[str, ...]:
        """The current id and the ids of the :attr:`earlier` versions."""
        return (self.id, *(f"{NAMESPACE}/{self.name}-v{v}" for v, _ in self.earlier))

    @property
    def entry_point(self) -> str:
        return f"ship_gym.envs.{self.module}:{self.name}Env"

    @property
    def vector_entry_point(self) -> str:
        return f"ship_gym.envs.{self.module}:{self.name}VectorEnv"


_RADIATION_ONLY = ((2, (("forward_speed_model", "radiation_only"),)),)
"""v2 of the ship tasks: the forward-speed model of issue #13 (docstrings.FORWARD_SPEED_V3)."""

ENTRIES: tuple[EnvEntry, ...] = (
    EnvEntry("CourseKeeping", "course_keeping", 1000, 3, _RADIATION_ONLY),
    EnvEntry("RollStabilization", "roll_stabilisation", 1000, 3, _RADIATION_ONLY),
    EnvEntry("RideControl", "ride_control", 1000, 3, _RADIATION_ONLY),
    EnvEntry("CapsizeAvoidance", "capsize_avoidance", 1500, 3, _RADIATION_ONLY),
    EnvEntry("RollOneDOF", "roll_one_dof", 1000, 0),
    EnvEntry("HeavyWeather", "heavy_weather", 360, 0),
)
ENV_IDS: tuple[str, ...] = tuple(e.id for e in ENTRIES)
"""The current id of every environment."""
REGISTERED_IDS: tuple[str, ...] = tuple(i for e in ENTRIES for i in e.ids())
"""Every registered id: the current ones and the earlier versions kept
(:attr:`EnvEntry.earlier`)."""


def max_episode_steps(name: str) -> int:
    """The registered time limit [control steps] of ``ship_gym/<name>-vN`` (single source)."""
    for entry in ENTRIES:
        if entry.name == name:
            return entry.max_episode_steps
    raise ValueError(f"no registered environment {name!r}; known: {[e.name for e in ENTRIES]}")


def env_class_of(env_id: str) -> type[TaskEnv]:
    """The single-episode env class (``<Name>Env``) of a registered id (``"ship_gym/X-vN"``, the
    ``"ship_gym:"`` module prefix optional).

    Raises
    ------
    ValueError
        If ``env_id`` is not a ship_gym id.
    """
    import importlib

    bare = env_id.split(":", 1)[1] if env_id.startswith(f"{NAMESPACE}:") else env_id
    for entry in ENTRIES:
        if bare in entry.ids():
            module = importlib.import_module(f"ship_gym.envs.{entry.module}")
            env_class: type[TaskEnv] = getattr(module, f"{entry.name}Env")
            return env_class
    raise ValueError(f"{env_id!r} is not a ship_gym environment id; known: {list(REGISTERED_IDS)}")


def register_envs() -> None:
    """Register every ship_gym id with Gymnasium (idempotent)."""
    for entry in ENTRIES:
        versions = ((entry.version, ()), *entry.earlier)
        for version, kwargs in versions:
            env_id = f"{NAMESPACE}/{entry.name}-v{version}"
            if env_id in gymnasium.registry:
                continue
            gymnasium.register(
                id=env_id,
                entry_point=entry.entry_point,
                vector_entry_point=entry.vector_entry_point,
                max_episode_steps=entry.max_episode_steps,
                kwargs=dict(kwargs),
            )
