"""The loading condition of a ship task: GM, GZ curve and angle of vanishing stability of the
nominal loading (calm water, free sinkage and trim), cached per process.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from ship_gym.engine.ship import ShipSetup


@dataclass(frozen=True)
class LoadingCondition:
    """Stability of the nominal loading condition of a hull (calm water, free sinkage and trim).

    Attributes
    ----------
    kg : float
        Height of G above the keel [m].
    gm : float
        Transverse metacentric height GM of the upright floating hull [m].
    heel_deg : numpy.ndarray
        Heel angles of the GZ table [deg] (0 … 90).
    gz : numpy.ndarray
        Righting arms there [m].
    vanishing_angle_deg : float
        Angle of vanishing stability [deg] (90 if GZ stays positive up to 90°).
    draught, heave : float
        Design draught [m] and the equilibrium sinkage of O [m] (z down).
    """

    kg: float
    gm: float
    heel_deg: NDArray
    gz: NDArray
    vanishing_angle_deg: float
    draught: float
    heave: float

    def vanishing_angles(self, delta_kg: NDArray) -> NDArray:
        """Angle of vanishing stability [rad] after raising G by ``delta_kg`` [m].

        GZ(φ) − ΔKG sin φ on the cubic interpolant of the GZ table (exact for a vertical shift
        of G at the same free sinkage and trim); the first down-crossing, 90° if none.
        """
        from scipy.interpolate import CubicSpline

        d = np.atleast_1d(np.asarray(delta_kg, float))
        out = np.full(d.shape, math.radians(self.vanishing_angle_deg))
        moved = d != 0.0
        if moved.any():
            fine = np.linspace(0.0, 90.0, 1801)
            gz = CubicSpline(self.heel_deg, self.gz)(fine)[None, :] - d[moved, None] * np.sin(
                np.radians(fine)
            )
            for r, row in zip(np.flatnonzero(moved), gz, strict=True):
                pos = np.flatnonzero(row[1:] > 0.0)
                start = int(pos[0]) + 1 if pos.size else 1  # first positive GZ after 0°
                down = np.flatnonzero((row[start:-1] > 0.0) & (row[start + 1 :] <= 0.0))
                if down.size == 0:
                    out[r] = math.pi / 2 if pos.size else math.radians(fine[1])
                    continue
                i = start + int(down[0])
                x = fine[i] + (fine[i + 1] - fine[i]) * row[i] / (row[i] - row[i + 1])
                out[r] = math.radians(x)
        return out


@lru_cache(maxsize=16)
def _loading_condition(hull_name: str, overrides: tuple) -> LoadingCondition:
    from ship_gym.hull import equilibrium, hydrostatics, righting_arm
    from ship_gym.ship import hull_of

    hull = hull_of(hull_name, **dict(overrides))
    eq = equilibrium(hull)
    hs = hydrostatics(hull, eq.heave, 0.0, eq.trim)
    heels = np.arange(0.0, 90.0 + 1e-9, 5.0)
    curve = righting_arm(hull, heels)
    vanishing = curve.vanishing_angle_deg
    if not math.isfinite(vanishing):
        vanishing = 90.0
    return LoadingCondition(
        kg=float(hull.kg),
        gm=float(hs.gmt),
        heel_deg=curve.heel_deg,
        gz=curve.gz,
        vanishing_angle_deg=float(min(vanishing, 90.0)),
        draught=float(hull.particulars.draught),
        heave=float(eq.heave),
    )


def loading_condition(setup: ShipSetup) -> LoadingCondition:
    """GZ table, GM and vanishing angle of the setup's hull and loading (cached per process)."""
    return _loading_condition(setup.hull, tuple(sorted(setup.hull_overrides.items())))
