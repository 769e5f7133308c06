"""Hull geometry, loading conditions and calm-water hydrostatics (first pipeline stage).

``load_hull(name, **overrides)`` gives a frozen :class:`Hull`; ``righting_arm(hull, heel_deg)``
its GZ curve at free sinkage and trim.
"""

from ship_gym.hull.hull import Hull, Particulars
from ship_gym.hull.hydrostatics import (
    Equilibrium,
    Hydrostatics,
    RightingArmCurve,
    equilibrium,
    hydrostatics,
    pressure_integral,
    righting_arm,
)
from ship_gym.hull.library import HULLS, box_barge, hemisphere, load_hull, s175, wigley
from ship_gym.hull.mass import MassProperties
from ship_gym.hull.mesh import MeshError, PanelMesh, immersed_part, mesh_from_polygons

__all__ = [
    "HULLS",
    "Equilibrium",
    "Hull",
    "Hydrostatics",
    "MassProperties",
    "MeshError",
    "PanelMesh",
    "Particulars",
    "RightingArmCurve",
    "box_barge",
    "equilibrium",
    "hemisphere",
    "hydrostatics",
    "immersed_part",
    "load_hull",
    "mesh_from_polygons",
    "pressure_integral",
    "righting_arm",
    "s175",
    "wigley",
]
