"""ship_gym — Gymnasium environments for ship seakeeping on a two-stage 6-DOF ship model.

Importing the package registers the environment ids (``ship_gym/<Name>-vN``) with Gymnasium;
the environment modules and the simulator are imported only when an environment is made.
"""

__version__ = "0.1.0"

from ship_gym.envs.registration import register_envs as _register_envs

_register_envs()
