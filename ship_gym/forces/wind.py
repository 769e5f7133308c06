"""Mean wind load on the above-water hull and superstructure (Blendermann's coefficients).

A steady, uniform wind of speed V_w [m/s] (at 10 m) blowing **from** the earth direction χ_w
[rad] (meteorological: χ_w = 0 a wind from the north) loads the ship through the relative wind
of its body-axis velocity. With the wind's velocity in body axes (roll and pitch neglected),

    u_w = −V_w cos(χ_w − ψ),    v_w = −V_w sin(χ_w − ψ),

the relative velocity u_r = u − u_w, v_r = v − v_w, V_r² = u_r² + v_r², and the angle of the
relative wind off the bow γ = −atan2(v_r, u_r) (γ = 0: a head wind; γ = −π/2: a wind on the
starboard beam), the loads are (Blendermann 1994, in the form of Fossen 2011, §8.1.1,
eq. 8.24–8.31; q = ½ ρ_a V_r²)

    X = q A_F C_X(γ),  Y = q A_L C_Y(γ),  K = q A_L H_L C_K(γ),  N = q A_L L_oa C_N(γ),

    C_X = −C_Dl,AF(γ) cos γ / D(γ),           C_Y = C_Dt sin γ / D(γ),
    C_K = κ C_Y,                               C_N = [s_L / L_oa − 0.18 (|γ| − π/2)] C_Y,
    D(γ) = 1 − ½ δ (1 − C_Dl / C_Dt) sin² 2γ,  C_Dl = C_Dl,AF(γ) A_F / A_L,

with C_Dl,AF(γ) = C_Dl,AF(0) for |γ| ≤ π/2 (wind from ahead) and C_Dl,AF(π) otherwise. A_F, A_L
[m²] are the frontal and lateral projected windage areas, H_L [m] the height of the centroid
of A_L above the waterline, s_L [m] its distance forward of amidships, L_oa [m] the length
over all; C_Dt, C_Dl,AF, δ (the cross-force parameter) and κ (the rolling-moment factor) are
Blendermann's coefficients of the ship type. The body origin O is at the waterline amidships
(:mod:`ship_gym.conventions`), so (X, Y, 0, K, 0, N) is the load about O. The yaw moment uses
|γ| so that a port wind mirrors a starboard one. Wind speed profile and gusts are not
modelled (a constant mean wind).

The default coefficients are those Fossen (2011, Table 8.1) lists after Blendermann (1994) for
a loaded container ship: C_Dt = 0.90, C_Dl,AF(0) = 0.55, C_Dl,AF(π) = 0.55, δ = 0.40,
κ = 1.4. Check them against the source for another ship type.

References
----------
Blendermann, W. (1994). Parameter identification of wind loads on ships. J. Wind Eng. Ind.
Aerodyn. 51, 339–351.
Fossen, T. I. (2011). Handbook of Marine Craft Hydrodynamics and Motion Control. Wiley, §8.1.
Isherwood, R. M. (1972). Wind resistance of merchant ships. Trans. RINA 115, 327–338 (the
regression these tables superseded for modern ship types).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numba as nb
import numpy as np

from ship_gym.forces.base import RowKernelModel, RowLayout

__all__ = ["AIR_DENSITY", "MeanWind", "WindRecord", "Windage", "mean_wind_row"]

AIR_DENSITY = 1.226
"""ρ_a [kg/m³] of air at 15 °C (ITTC)."""


@dataclass(frozen=True)
class Windage:
    """The above-water geometry and Blendermann coefficients of a ship.

    Attributes
    ----------
    frontal_area : float
        A_F [m²], projected on the midship plane.
    lateral_area : float
        A_L [m²], projected on the centreline plane.
    centroid_height : float
        H_L [m], height of the centroid of A_L above the waterline.
    centroid_x : float
        s_L [m], distance of the centroid of A_L forward of amidships.
    length_overall : float
        L_oa [m].
    cdt, cdl_af_ahead, cdl_af_astern, delta, kappa : float
        C_Dt, C_Dl,AF(0), C_Dl,AF(π), δ, κ [-] (defaults: loaded container ship).
    """

    frontal_area: float
    lateral_area: float
    centroid_height: float
    centroid_x: float
    length_overall: float
    cdt: float = 0.90
    cdl_af_ahead: float = 0.55
    cdl_af_astern: float = 0.55
    delta: float = 0.40
    kappa: float = 1.4

    def __post_init__(self) -> None:
        for name in ("frontal_area", "lateral_area", "length_overall", "cdt"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"{name} must be positive and finite, got {value!r}")
        for name in ("centroid_height", "centroid_x", "cdl_af_ahead", "cdl_af_astern", "delta",
                     "kappa"):  # fmt: skip
            if not math.isfinite(getattr(self, name)):
                raise ValueError(f"{name} must be finite, got {getattr(self, name)!r}")


class WindRecord(NamedTuple):
    """:func:`mean_wind_row`'s parameters (scalars, shared by all ships)."""

    speed: float
    direction_from: float
    rho_air: float
    frontal_area: float
    lateral_area: float
    centroid_height: float
    centroid_x: float
    length_overall: float
    cdt: float
    cdl_ahead: float
    cdl_astern: float
    delta: float
    kappa: float


@nb.njit(cache=True, nogil=True)
def mean_wind_row(s, t, q, v, z, zdot, ctx, rec, out):  # pragma: no cover - compiled
    """Row kernel: Blendermann's wind load (module docstring) added to ``out`` [N, N·m]."""
    rel = rec.direction_from - q[5]
    u_r = v[0] + rec.speed * math.cos(rel)
    v_r = v[1] + rec.speed * math.sin(rel)
    v2 = u_r * u_r + v_r * v_r
    if v2 == 0.0:
        return
    gamma = -math.atan2(v_r, u_r)
    a = abs(gamma)
    cdl_af = rec.cdl_ahead if a <= 0.5 * math.pi else rec.cdl_astern
    cdl = cdl_af * rec.frontal_area / rec.lateral_area
    s2 = math.sin(2.0 * gamma)
    den = 1.0 - 0.5 * rec.delta * (1.0 - cdl / rec.cdt) * s2 * s2
    cx = -cdl_af * math.cos(gamma) / den
    cy = rec.cdt * math.sin(gamma) / den
    cn = (rec.centroid_x / rec.length_overall - 0.18 * (a - 0.5 * math.pi)) * cy
    qd = 0.5 * rec.rho_air * v2
    out[0] += qd * rec.frontal_area * cx
    out[1] += qd * rec.lateral_area * cy
    out[3] += qd * rec.lateral_area * rec.centroid_height * rec.kappa * cy
    out[5] += qd * rec.lateral_area * rec.length_overall * cn


class MeanWind(RowKernelModel):
    """A constant mean wind on the ship's windage (module docstring); no states.

    Parameters
    ----------
    windage : Windage
        The ship's above-water geometry and coefficients.
    speed : float
        V_w [m/s], ≥ 0.
    direction_from : float
        χ_w [rad], the earth direction the wind blows from (0: north; the ship starts heading
        north, so 0 is a head wind at the start).
    rho_air : float
        ρ_a [kg/m³].
    """

    name = "wind"
    kernel = mean_wind_row

    def __init__(
        self,
        windage: Windage,
        speed: float,
        direction_from: float = 0.0,
        *,
        rho_air: float = AIR_DENSITY,
    ) -> None:
        if not (math.isfinite(speed) and speed >= 0.0):
            raise ValueError(f"wind speed must be a non-negative speed [m/s], got {speed!r}")
        if not math.isfinite(direction_from):
            raise ValueError(f"direction_from must be finite [rad], got {direction_from!r}")
        self.windage = windage
        self.speed = float(speed)
        self.direction_from = float(direction_from)
        self.rho_air = float(rho_air)

    def record(self, layout: RowLayout) -> WindRecord:
        w = self.windage
        return WindRecord(
            self.speed, self.direction_from, self.rho_air, float(w.frontal_area),
            float(w.lateral_area), float(w.centroid_height), float(w.centroid_x),
            float(w.length_overall), float(w.cdt), float(w.cdl_af_ahead),
            float(w.cdl_af_astern), float(w.delta), float(w.kappa),
        )  # fmt: skip

    def load(self, psi: float, u: float = 0.0, v: float = 0.0) -> np.ndarray:
        """(6,) the load [N, N·m] at heading ψ [rad] and body velocities u, v [m/s]."""
        out = np.zeros(6)
        q = np.array([0.0, 0.0, 0.0, 0.0, 0.0, float(psi)])
        nu = np.array([float(u), float(v), 0.0, 0.0, 0.0, 0.0])
        force, _ = self.evaluate(_one_ship_context(q, nu), np.zeros(0))
        out += force
        return out


def _one_ship_context(eta: np.ndarray, nu: np.ndarray):
    from ship_gym.forces.base import ForceContext

    return ForceContext(t=0.0, eta=eta, nu=nu, rotation=np.eye(3))
