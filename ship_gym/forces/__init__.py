"""Force models (one protocol, :class:`ForceModel`; one module per physical concept).

The classes are imported from their modules (``ship_gym.forces.radiation`` …); this package
import stays light.
"""

from ship_gym.forces.base import ForceContext, ForceModel

__all__ = ["ForceContext", "ForceModel"]
