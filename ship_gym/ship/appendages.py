"""Appendage sizes of a ship: what its file gives, and documented estimates for the rest.

Each function takes the hull (its main particulars and mesh), the ship's service speed and GM,
and the fields written in the ship file's appendage table (:mod:`ship_gym.ship.description`,
names with units: ``area_m2``), and returns the keyword arguments of the force model
(:class:`~ship_gym.forces.rudder.Rudder`, :class:`~ship_gym.forces.fins.RollFins`,
:class:`~ship_gym.forces.fins.TFoil`, :func:`~ship_gym.forces.propeller.design_propeller_for`)
together with the provenance of every value (``"given"`` or ``"estimated"``).

Estimates (L = Lpp, B, T the design draught)
-------------------------------------------
Rudder
    Area A_R = 1.99 % of L·T, the S175's (Son & Nomoto 1982; the upper end of the usual
    1.6–2 % for fast, directionally weakly stable ships), never below the classification minimum
    (L T/100)[1 + 25 (B/L)²] (DNV rules, Pt. 3 Ch. 14); geometric aspect ratio 1.82 (S175), span
    s = √(AR A_R), at most 0.85 T so that the tip stays 0.076 T above the keel line (S175: 0.72 m);
    centre of pressure at the aft perpendicular (x = −L/2), mid-span z = 0.924 T − s/2. Wake
    and flow-straightening factors: the S175's MMG values (:mod:`ship_gym.forces.rudder`).
    The propeller ahead of it: the ship's propeller diameter (given, else 0.7 T as
    :func:`~ship_gym.forces.propeller.design_propeller_for`), disk 0.536 D ahead of the
    centre of pressure (S175: 3.5 m at D = 6.53 m).
Roll fins
    Sized the way stabiliser fins are specified: the pair at the service speed U and 20° of
    fin angle gives the righting moment of 5° of heel, Δ g GM sin 5° (the S175's fins do,
    :mod:`ship_gym.forces.fins`), with eq. (1) of that module: A_f = Δ g GM sin 5° /
    (2 y_f ½ρU² C_Lα(AR_e) · 20°), geometric AR 1.6 (effective 3.2, root on the hull). Fins at
    amidships (x = 0) at the turn of the bilge, z_f = 0.79 T (S175: 2 m above the keel), root
    at the hull's half-breadth there (from the mesh), centre of pressure at mid-span y_f. A span
    larger than 0.35 B is clipped (with it the area: a fast ship with little GM gets small fins,
    a slow stiff one the largest a hull carries).
T-foil
    Geometrically similar to the S175 default (illustrative, :mod:`ship_gym.forces.fins`):
    area 0.288 % of L·B, span 0.315 B (AR ≈ 5), x = 0.371 L, z = 1.158 T (on a strut under the
    forefoot).
Propeller
    :func:`~ship_gym.forces.propeller.design_propeller_for` at the service speed: D = 0.7 T,
    Z = 4, Keller's blade-area ratio, the optimum P/D on the loading line, Holtrop's w, t, η_R —
    every given field replaces its estimate.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, Final

import numpy as np

from ship_gym.forces.lifting_surface import lift_slope

if TYPE_CHECKING:
    from ship_gym.hull.hull import Hull

__all__ = [
    "FIN_DESIGN_ANGLE_DEG",
    "FIN_DESIGN_HEEL_DEG",
    "Estimate",
    "fins_arguments",
    "propeller_arguments",
    "rudder_arguments",
    "t_foil_arguments",
]

Estimate = tuple[dict[str, Any], dict[str, str]]
"""Keyword arguments of a force model and the provenance ("given"/"estimated") of each."""

RUDDER_AREA_RATIO: Final = 0.019872
"""A_R/(L T) of the S175 rudder (33.04 m² at L 175 m, T 9.5 m; Son & Nomoto 1982) [-]."""
RUDDER_ASPECT_RATIO: Final = 1.8219
"""Geometric aspect ratio of the S175 rudder [-]."""
FIN_DESIGN_HEEL_DEG: Final = 5.0
"""Heel [deg] whose righting moment the estimated fin pair balances at service speed."""
FIN_DESIGN_ANGLE_DEG: Final = 20.0
"""Fin angle [deg] of that design point (below the 25° limit and the stall)."""
FIN_ASPECT_RATIO: Final = 1.6
"""Geometric aspect ratio of an estimated fin [-] (S175 default fins)."""

# ship-file field → force-model keyword (with the unit conversion where one is needed)
_RUDDER_KEYS: Final = {
    "area_m2": "area", "aspect_ratio": "aspect_ratio", "x_m": "x", "z_m": "z",
    "lateral_positions_m": "lateral_positions", "wake_fraction": "wake_fraction",
    "drift_straightening": "drift_straightening", "yaw_straightening": "yaw_straightening",
    "propeller_diameter_m": "propeller_diameter", "propeller_distance_m": "propeller_distance",
    "stall_angle_deg": "stall_angle",
}  # fmt: skip
_FIN_KEYS: Final = {"area_m2": "area", "span_m": "span", "x_m": "x", "y_m": "y", "z_m": "z",
                    "max_angle_deg": "max_angle"}  # fmt: skip
_PROPELLER_KEYS: Final = {
    "diameter_m": "diameter", "blades": "z_blades", "blade_area_ratio": "ae_a0",
    "pitch_ratio": "p_d", "rpm": "rpm", "wake_fraction": "wake_fraction",
    "thrust_deduction": "thrust_deduction",
}  # fmt: skip


def _given(table: Mapping[str, Any], keys: Mapping[str, str]) -> Estimate:
    """The written fields as model keywords (angles to radians) and their provenance."""
    kwargs: dict[str, Any] = {}
    source: dict[str, str] = {}
    for name, value in table.items():
        if name == "fitted":
            continue
        key = keys[name]
        kwargs[key] = math.radians(value) if name.endswith("_deg") else value
        source[key] = "given"
    return kwargs, source


def _estimate(kwargs: dict[str, Any], source: dict[str, str], key: str, value: Any) -> None:
    if key not in kwargs:
        kwargs[key] = value
        source[key] = "estimated"


def _half_breadth(hull: Hull, x: float, z: float) -> float:
    """Largest half-breadth [m] of the immersed hull within ±5 % L of x and ±10 % T of z."""
    p = hull.particulars
    v = hull.immersed_mesh.vertices
    near = (np.abs(v[:, 0] - x) <= 0.05 * p.lpp) & (np.abs(v[:, 2] - z) <= 0.1 * p.draught)
    return float(np.abs(v[near, 1]).max()) if np.any(near) else 0.5 * p.beam


def rudder_arguments(hull: Hull, table: Mapping[str, Any], propeller_diameter: float | None
                     ) -> Estimate:  # fmt: skip
    """Keyword arguments of :class:`~ship_gym.forces.rudder.Rudder` (module docstring).

    Parameters
    ----------
    hull : Hull
        The ship's hull.
    table : mapping
        The ``[rudder]`` fields of the ship file.
    propeller_diameter : float or None
        Diameter of the ship's propeller [m] (None: 0.7 T).
    """
    p = hull.particulars
    kwargs, source = _given(table, _RUDDER_KEYS)
    minimum = p.lpp * p.draught / 100.0 * (1.0 + 25.0 * (p.beam / p.lpp) ** 2)
    ar = kwargs.get("aspect_ratio", RUDDER_ASPECT_RATIO)
    area = kwargs.get("area", max(RUDDER_AREA_RATIO * p.lpp * p.draught, minimum))
    span = math.sqrt(ar * area)
    if "area" not in kwargs and span > 0.85 * p.draught:
        span = 0.85 * p.draught
        area = span**2 / ar
    _estimate(kwargs, source, "area", area)
    _estimate(kwargs, source, "aspect_ratio", ar)
    span = math.sqrt(kwargs["aspect_ratio"] * kwargs["area"])
    _estimate(kwargs, source, "x", -0.5 * p.lpp)
    _estimate(kwargs, source, "z", max(0.924 * p.draught - 0.5 * span, 0.5 * span))
    diameter = 0.7 * p.draught if propeller_diameter is None else float(propeller_diameter)
    _estimate(kwargs, source, "propeller_diameter", diameter)
    _estimate(kwargs, source, "propeller_distance", 0.536 * kwargs["propeller_diameter"])
    return kwargs, source


def fins_arguments(hull: Hull, table: Mapping[str, Any], *, speed: float, gm: float,
                   rho: float) -> Estimate:  # fmt: skip
    """Keyword arguments of :class:`~ship_gym.forces.fins.RollFins` (module docstring).

    Parameters
    ----------
    hull : Hull
        The ship's hull.
    table : mapping
        The ``[fins]`` fields of the ship file.
    speed : float
        Service speed U [m/s] of the sizing rule.
    gm : float
        GM of the loading [m] (> 0).
    rho : float
        Water density [kg/m³].
    """
    p = hull.particulars
    kwargs, source = _given(table, _FIN_KEYS)
    _estimate(kwargs, source, "x", 0.0)
    _estimate(kwargs, source, "z", 0.79 * p.draught)
    root = _half_breadth(hull, kwargs["x"], kwargs["z"])
    moment = hull.mass.mass * hull.g * max(gm, 0.0) * math.sin(math.radians(FIN_DESIGN_HEEL_DEG))
    c_l = float(lift_slope(2.0 * FIN_ASPECT_RATIO)) * math.radians(FIN_DESIGN_ANGLE_DEG)
    q = 0.5 * rho * max(speed, 1.0) ** 2
    if not gm > 0.0:
        raise ValueError(f"fins are sized on the loading's GM; got GM = {gm!r} m, expected > 0")
    given_span = "span" in kwargs
    if "area" in kwargs:
        area = float(kwargs["area"])
        span = kwargs.get("span", math.sqrt(FIN_ASPECT_RATIO * area))
    else:
        span = kwargs.get("span", 0.1 * p.beam)
        for _ in range(6):  # y_f depends on the span, the span on the area
            area = moment / (2.0 * kwargs.get("y", root + 0.5 * span) * q * c_l)
            if not given_span:
                span = math.sqrt(FIN_ASPECT_RATIO * area)
        if not given_span and span > 0.35 * p.beam:
            span = 0.35 * p.beam
            area = span**2 / FIN_ASPECT_RATIO
    _estimate(kwargs, source, "area", float(area))
    _estimate(kwargs, source, "span", float(span))
    _estimate(kwargs, source, "y", root + 0.5 * kwargs["span"])
    return kwargs, source


def t_foil_arguments(hull: Hull, table: Mapping[str, Any]) -> Estimate:
    """Keyword arguments of :class:`~ship_gym.forces.fins.TFoil` (module docstring).

    Parameters
    ----------
    hull : Hull
        The ship's hull.
    table : mapping
        The ``[t_foil]`` fields of the ship file.
    """
    p = hull.particulars
    kwargs, source = _given(table, _FIN_KEYS)
    _estimate(kwargs, source, "area", 0.00288 * p.lpp * p.beam)
    _estimate(kwargs, source, "span", 0.315 * p.beam)
    _estimate(kwargs, source, "x", 0.371 * p.lpp)
    _estimate(kwargs, source, "z", 1.158 * p.draught)
    return kwargs, source


def propeller_arguments(table: Mapping[str, Any]) -> Estimate:
    """Keyword arguments of :func:`~ship_gym.forces.propeller.design_propeller_for` from the
    ``[propeller]`` fields (the rest is that function's own design procedure)."""
    kwargs, source = _given(table, _PROPELLER_KEYS)
    for key in ("diameter", "z_blades", "ae_a0", "p_d", "wake_fraction", "thrust_deduction"):
        source.setdefault(key, "estimated")
    return kwargs, source
