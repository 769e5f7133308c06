"""Control elements: actuator servos (saturation, rate limit, lag) and the heading autopilot."""

from ship_gym.control.actuators import (
    FIN_SERVO,
    FOIL_SERVO,
    RUDDER_SERVO,
    Actuated,
    ServoSpec,
)
from ship_gym.control.autopilot import HeadingAutopilot, NomotoModel

__all__ = [
    "FIN_SERVO",
    "FOIL_SERVO",
    "RUDDER_SERVO",
    "Actuated",
    "HeadingAutopilot",
    "NomotoModel",
    "ServoSpec",
]
