"""The :class:`Hull` value object: geometry, loading condition and main particulars."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ship_gym.conventions import GRAVITY, RHO_SEAWATER
from ship_gym.hull.mass import MassProperties
from ship_gym.hull.mesh import PanelMesh, immersed_part


@dataclass(frozen=True)
class Particulars:
    """Main particulars of the hull in its design condition.

    Parameters
    ----------
    lpp : float
        Length between perpendiculars [m].
    beam : float
        Moulded breadth [m].
    draught : float
        Design draught T [m] (the body-frame origin lies on this waterline).
    depth : float
        Moulded depth D [m] (keel to deck).
    reference : dict
        Published values of the loading condition (e.g. ``{"KB": 5.207, "GMt": 0.996}``) used
        by checks; units in the key names' documentation of each hull.
    """

    lpp: float
    beam: float
    draught: float
    depth: float
    reference: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        for name in ("lpp", "beam", "draught", "depth"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value > 0.0):
                raise ValueError(f"{name} must be a positive length [m], got {value!r}")
        if self.draught >= self.depth:
            raise ValueError(
                f"draught ({self.draught} m) must be smaller than depth ({self.depth} m)"
            )


@dataclass(frozen=True, eq=False)
class Hull:
    """A hull ready for hydrostatics, BEM and time-domain simulation.

    Parameters
    ----------
    name : str
        Identifier (e.g. ``"s175"``).
    mesh : PanelMesh
        Closed, watertight mesh up to the deck, body frame (x forward, y starboard, z down,
        origin amidships on the design waterline).
    mass : MassProperties
        Loading condition: mass [kg], centre of gravity [m], inertia about G [kg·m²].
    particulars : Particulars
        Main dimensions and published reference values.
    rho : float
        Water density [kg/m³].
    g : float
        Gravitational acceleration [m/s²].
    """

    name: str
    mesh: PanelMesh
    mass: MassProperties
    particulars: Particulars
    rho: float = RHO_SEAWATER
    g: float = GRAVITY

    def __post_init__(self) -> None:
        if not (self.rho > 0.0 and self.g > 0.0):
            raise ValueError(f"rho and g must be positive, got rho={self.rho}, g={self.g}")
        self.mesh.check(closed=True)

    @cached_property
    def immersed_mesh(self) -> PanelMesh:
        """Open mesh of the hull below the design waterline z = 0 (BEM input)."""
        return immersed_part(self.mesh)

    @property
    def kg(self) -> float:
        """Height of G above the keel [m]."""
        return self.particulars.draught - float(self.mass.cog[2])
