"""Gymnasium environments (stage 7).

``import ship_gym`` registers every id (:mod:`ship_gym.envs.registration`) without importing the
environment modules themselves; ``gymnasium.make("ship_gym:ship_gym/<Name>-vN")`` imports the
one it needs. Every environment is a :class:`ship_gym.envs.base.BatchedTask` (N episodes stepped
together) seen through :class:`~ship_gym.envs.base.TaskEnv` (one episode, ``gymnasium.Env``) or
:class:`~ship_gym.envs.base.TaskVectorEnv` (N episodes in one call, ``gymnasium.vector.VectorEnv``).
"""

from ship_gym.envs.registration import ENV_IDS, REGISTERED_IDS, register_envs

__all__ = ["ENV_IDS", "REGISTERED_IDS", "register_envs"]
