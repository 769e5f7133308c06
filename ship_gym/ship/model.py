"""A ship ready for the simulator: its description, hull, loading, appendages and database.

:func:`load_ship` turns a ship file (or the name of a bundled one, ``"s175"``…) into a
:class:`Ship`: the :class:`~ship_gym.hull.hull.Hull` with its loading condition, the keyword
arguments of its rudder, propeller, fins and T-foil (given or estimated,
:mod:`ship_gym.ship.appendages`), its service speed, and its BEM database (given, bundled, or
built from the hull and cached, :mod:`ship_gym.ship.database_cache`). The engine
(:mod:`ship_gym.engine.ship`), the environments and the studies take a ship this way.

Loading defaults (a ``[loading]`` table that leaves a field out)
----------------------------------------------------------------
* mass: ρ V of the hull at its design waterline (it floats at its design draught);
* LCG: the centre of buoyancy at the design waterline (no trim);
* KG: required (``kg_m``, or ``gm_m``: KG = KB + BMt − GM at the design waterline);
* radii of gyration: 0.35 B, 0.25 Lpp, 0.25 Lpp about G (typical values, ITTC
  7.5-02-07-04.1; the S175's are 0.33 B, 0.24 L, 0.24 L).

A library hull without a ``[loading]`` table keeps its builder's design loading.

Overrides (keyword arguments of :func:`load_ship`, e.g. the environments' ``kg_m``): ``kg``,
``gm``, ``displacement_t``, ``lcg``, ``radii_of_gyration`` replace the loading fields; any other
keyword is a library builder's argument (``n_sections=80``) or an offsets-mesh resolution.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, replace
from functools import cached_property, lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any, Final

import numpy as np

from ship_gym.ship.appendages import (
    fins_arguments,
    propeller_arguments,
    rudder_arguments,
    t_foil_arguments,
)
from ship_gym.ship.description import (
    HullGeometry,
    LoadingSpec,
    ShipDescription,
    ShipFileError,
    bundled_ship_path,
    bundled_ships,
    is_ship_file,
    read_ship,
)

if TYPE_CHECKING:
    import xarray as xr

    from ship_gym.forces.fins import RollFins, TFoil
    from ship_gym.forces.propeller import Propeller
    from ship_gym.forces.rudder import Rudder
    from ship_gym.forces.wind import Windage
    from ship_gym.hull.hull import Hull
    from ship_gym.hull.mass import MassProperties
    from ship_gym.hull.mesh import PanelMesh

__all__ = ["LOADING_OVERRIDES", "DatabaseMismatchError", "Ship", "build_hull",
           "check_database_matches", "hull_of", "load_ship"]  # fmt: skip

LOADING_OVERRIDES: Final[dict[str, str]] = {
    "kg": "kg_m",
    "gm": "gm_m",
    "displacement_t": "displacement_t",
    "lcg": "lcg_m",
    "radii_of_gyration": "radii_of_gyration_m",
}
"""Override keyword → ``[loading]`` field it replaces."""

DEFAULT_RADII: Final = (0.35, 0.25, 0.25)
"""Default radii of gyration as fractions of (B, Lpp, Lpp) [-]."""

WATERPLANE_TOLERANCE: Final = 0.03
"""Largest relative difference of C33 = ρ g A_wp and C55 between a database and the hull it is
used with (mesh-resolution changes of one hull stay below 1 %; another hull is tens of %)."""


class DatabaseMismatchError(ValueError):
    """A hydrodynamic database was built for another hull than the one it is used with."""


@dataclass(frozen=True, eq=False)
class Ship:
    """A ship ready for the simulator (:func:`load_ship`).

    Attributes
    ----------
    description : ShipDescription
        The ship file as read.
    hull : Hull
        Geometry and loading condition.
    service_speed : float
        Service speed [m/s].
    speed_range : tuple of float
        Speeds the ship is used at [m/s].
    overrides : tuple of (str, object)
        The overrides the ship was loaded with.

    The appendages' keyword arguments (:attr:`rudder_arguments`, :attr:`fins_arguments`,
    :attr:`t_foil_arguments`, :attr:`propeller_arguments`) and their :attr:`provenance` are
    worked out on first use (the fins' estimate needs an upright-stable loading).
    """

    description: ShipDescription
    hull: Hull
    service_speed: float
    speed_range: tuple[float, float]
    overrides: tuple[tuple[str, Any], ...] = ()

    @cached_property
    def _appendages(self) -> tuple[dict, dict | None, dict | None, dict, dict[str, str]]:
        return _appendage_arguments(self.description, self.hull, self.service_speed)

    @property
    def rudder_arguments(self) -> dict[str, Any]:
        """Keyword arguments of :class:`~ship_gym.forces.rudder.Rudder`."""
        return self._appendages[0]

    @property
    def fins_arguments(self) -> dict[str, Any] | None:
        """Keyword arguments of :class:`~ship_gym.forces.fins.RollFins` (None: not fitted)."""
        return self._appendages[1]

    @property
    def t_foil_arguments(self) -> dict[str, Any] | None:
        """Keyword arguments of :class:`~ship_gym.forces.fins.TFoil` (None: not fitted)."""
        return self._appendages[2]

    @property
    def propeller_arguments(self) -> dict[str, Any]:
        """Keyword arguments of :func:`~ship_gym.forces.propeller.design_propeller_for`."""
        return self._appendages[3]

    @property
    def provenance(self) -> dict[str, str]:
        """``"<appendage>.<keyword>"`` → ``"given"`` or ``"estimated"``."""
        return self._appendages[4]

    @property
    def name(self) -> str:
        """The ship's name."""
        return self.description.name

    def rudder(self) -> Rudder:
        """The ship's rudder model."""
        from ship_gym.forces.rudder import Rudder

        return Rudder(**self.rudder_arguments)

    def fins(self) -> RollFins:
        """The ship's roll fins (:class:`ValueError` if it has none)."""
        from ship_gym.forces.fins import RollFins

        if self.fins_arguments is None:
            raise ValueError(f"ship {self.name!r} has no roll fins ([fins] fitted = false)")
        return RollFins(**self.fins_arguments)

    def windage(self) -> Windage:
        """The ship's windage (its ``[wind]`` table; :class:`ValueError` without one)."""
        from ship_gym.forces.wind import Windage

        table = self.description.appendage("wind")
        if not table:
            raise ValueError(
                f"ship {self.name!r} has no [wind] table: write its windage (frontal_area_m2, "
                "lateral_area_m2, centroid_height_m, centroid_x_m, length_overall_m) in its ship "
                "file to use wind"
            )
        names = {"frontal_area_m2": "frontal_area", "lateral_area_m2": "lateral_area",
                 "centroid_height_m": "centroid_height", "centroid_x_m": "centroid_x",
                 "length_overall_m": "length_overall"}  # fmt: skip
        try:
            return Windage(**{names.get(k, k): float(v) for k, v in table.items()})
        except TypeError as exc:
            raise ValueError(f"ship {self.name!r}: [wind] table incomplete ({exc})") from None

    def t_foil(self) -> TFoil:
        """The ship's T-foil (:class:`ValueError` if it has none)."""
        from ship_gym.forces.fins import TFoil

        if self.t_foil_arguments is None:
            raise ValueError(f"ship {self.name!r} has no T-foil ([t_foil] fitted = false)")
        return TFoil(**self.t_foil_arguments)

    def propeller(self) -> Propeller:
        """The propeller designed for the hull at the service speed (cached per ship)."""
        return _designed_propeller(self)

    def database_source(self) -> str:
        """Where the database comes from: a bundled name, a file path, or the cache file."""
        given = self.description.hydrodynamics.database
        if given is not None:
            return given
        from ship_gym.ship.database_cache import cache_path

        return str(cache_path(self.hull, self.description))

    def database(self, *, build: bool = True, progress: bool = True) -> xr.Dataset:
        """The ship's hydrodynamic database, checked against its hull.

        Parameters
        ----------
        build : bool
            Build it (BEM, minutes) when it is neither given nor cached; else
            :class:`FileNotFoundError` naming ``ship-gym ship build``.
        progress : bool
            Progress bar while building.
        """
        from ship_gym.hydro.database import load_database

        given = self.description.hydrodynamics.database
        if given is not None:
            ds = load_database(given)
            check_database_matches(self.hull, ds, given)
            return ds
        from ship_gym.ship.database_cache import cached_database

        path = cached_database(self.hull, self.description, build=build, progress=progress)
        ds = load_database(path)
        check_database_matches(self.hull, ds, str(path))
        return ds


@lru_cache(maxsize=16)
def _designed_propeller(ship: Ship) -> Propeller:
    from ship_gym.forces.propeller import design_propeller_for

    return design_propeller_for(ship.hull, ship.service_speed, **ship.propeller_arguments)


# ==================================================================================== loading
def load_ship(name_or_path: str | os.PathLike[str] | Ship, **overrides: Any) -> Ship:
    """A ship from its file, the name of a bundled ship file or a library hull.

    Parameters
    ----------
    name_or_path : str, os.PathLike or Ship
        A ``.toml`` ship file; or a name: a bundled ship (:func:`bundled_ships`, ``"s175"``…)
        or a library hull without one. A :class:`Ship` is returned as it is (no overrides).
    **overrides
        Loading fields (``kg``, ``gm``, ``displacement_t``, ``lcg``, ``radii_of_gyration``)
        or hull-builder arguments (module docstring).

    Raises
    ------
    FileNotFoundError, ShipFileError
        As :func:`ship_gym.ship.description.read_ship`.
    ValueError
        Unknown name or override, or a loading that is not upright-stable.
    """
    if isinstance(name_or_path, Ship):
        if overrides:
            raise ValueError("overrides apply to a ship file or name, not to a loaded Ship")
        return name_or_path
    text = os.fspath(name_or_path)
    if is_ship_file(text):
        path = Path(text).expanduser().resolve()
        if not path.is_file():
            raise FileNotFoundError(f"ship file {text!r} not found")
        key = (str(path), path.stat().st_mtime_ns)
    else:
        from ship_gym.hull.library import HULLS

        name = text.lower()
        if name in bundled_ships():
            path = bundled_ship_path(name)
            key = (str(path), 0)
        elif name in HULLS:
            key = (name, -1)
        else:
            raise ValueError(
                f"unknown ship {text!r}; expected a .toml ship file or one of "
                f"{sorted(set(bundled_ships()) | set(HULLS))}"
            )
    return _load(key, tuple(sorted(overrides.items(), key=lambda kv: kv[0])))


def hull_of(name_or_path: str | os.PathLike[str], **overrides: Any) -> Hull:
    """The hull (with its loading) of a ship file, bundled ship or library hull:
    ``load_ship(name_or_path, **overrides).hull``."""
    return load_ship(name_or_path, **overrides).hull


@lru_cache(maxsize=32)
def _load(key: tuple[str, int], overrides: tuple[tuple[str, Any], ...]) -> Ship:
    where, stamp = key
    if stamp == -1:  # a library hull without a ship file
        desc = ShipDescription(name=where, hull=HullGeometry(library=where))
    else:
        desc = read_ship(where)
    hull = build_hull(desc, dict(overrides))
    return _assemble(desc, hull, overrides)


def _assemble(desc: ShipDescription, hull: Hull, overrides: tuple[tuple[str, Any], ...]) -> Ship:
    from ship_gym.conventions import GRAVITY

    if desc.speed.service_mps is not None:
        service = desc.speed.service_mps
    else:
        froude = 0.25 if desc.speed.service_froude is None else desc.speed.service_froude
        service = froude * math.sqrt(GRAVITY * hull.particulars.lpp)
    speed_range = desc.speed.range_mps or (0.0, 1.2 * service)
    return Ship(
        description=desc,
        hull=hull,
        service_speed=float(service),
        speed_range=(float(speed_range[0]), float(speed_range[1])),
        overrides=overrides,
    )


def _appendage_arguments(
    desc: ShipDescription, hull: Hull, service: float
) -> tuple[dict, dict | None, dict | None, dict, dict[str, str]]:
    """Rudder, fins, T-foil and propeller keyword arguments, and their provenance."""
    from ship_gym.hull import hydrostatics

    provenance: dict[str, str] = {}
    prop_kwargs, prop_src = propeller_arguments(desc.appendage("propeller"))
    rudder_kwargs, rudder_src = rudder_arguments(
        hull, desc.appendage("rudder"), prop_kwargs.get("diameter")
    )
    fins_table = desc.appendage("fins")
    fins_kwargs: dict[str, Any] | None = None
    fins_src: dict[str, str] = {}
    if fins_table.get("fitted", True):
        gm = float(hydrostatics(hull).gmt)
        fins_kwargs, fins_src = fins_arguments(hull, fins_table, speed=service, gm=gm, rho=hull.rho)
    foil_table = desc.appendage("t_foil")
    foil_kwargs: dict[str, Any] | None = None
    foil_src: dict[str, str] = {}
    if foil_table.get("fitted", True):
        foil_kwargs, foil_src = t_foil_arguments(hull, foil_table)
    for group, src in (("propeller", prop_src), ("rudder", rudder_src), ("fins", fins_src),
                       ("t_foil", foil_src)):  # fmt: skip
        provenance.update({f"{group}.{k}": v for k, v in src.items()})
    return rudder_kwargs, fins_kwargs, foil_kwargs, prop_kwargs, provenance


# ======================================================================================= hull
def build_hull(desc: ShipDescription, overrides: dict[str, Any] | None = None) -> Hull:
    """The :class:`~ship_gym.hull.hull.Hull` of a ship description (module docstring).

    Parameters
    ----------
    desc : ShipDescription
        The ship.
    overrides : dict, optional
        Loading fields and builder arguments (:func:`load_ship`).
    """
    from ship_gym.hull.hull import Hull
    from ship_gym.hull.library import load_hull
    from ship_gym.hull.mass import MassProperties
    from ship_gym.hull.mesh_io import read_mesh
    from ship_gym.hull.offsets import hull_mesh_from_stations, read_offsets_csv

    overrides = dict(overrides or {})
    loading_changes = {
        LOADING_OVERRIDES[k]: overrides.pop(k) for k in list(overrides) if k in LOADING_OVERRIDES
    }
    geometry = desc.hull
    if geometry.kind == "library":
        assert geometry.library is not None
        builder_args = {**dict(geometry.options), **overrides}
        if not desc.loading.given:
            # loading overrides the builder takes itself go to it (its own checks and defaults)
            import inspect

            from ship_gym.hull.library import HULLS

            accepted = inspect.signature(HULLS[geometry.library]).parameters
            for field_name in list(loading_changes):
                key = next(k for k, v in LOADING_OVERRIDES.items() if v == field_name)
                if key in accepted:
                    builder_args[key] = loading_changes.pop(field_name)
            if not loading_changes:
                return load_hull(geometry.library, **builder_args)
        if "kg" in builder_args:  # a library builder's own kg keyword is a loading field here
            loading_changes.setdefault("kg_m", builder_args.pop("kg"))
        base = load_hull(geometry.library, **builder_args)
        loading = _with_changes(desc.loading, loading_changes, where=desc.name)
        if not loading.given:
            return base
        mass = _mass(base, loading, desc, library_mass=base.mass)
        return Hull(desc.name, base.mesh, mass, base.particulars, base.rho, base.g)
    given = dict(desc.particulars)
    if geometry.kind == "offsets":
        options = {**dict(geometry.options), **overrides}
        unknown = sorted(set(options) - {"n_sections", "n_below", "n_above", "n_deck", "n_end"})
        if unknown:
            raise ValueError(
                f"ship {desc.name!r}: unknown override(s) {unknown}; an offsets hull takes "
                f"n_sections, n_below, n_above, n_deck, n_end and {sorted(LOADING_OVERRIDES)}"
            )
        assert geometry.offsets is not None
        try:
            stations = read_offsets_csv(str(geometry.offsets))
        except (ValueError, KeyError) as exc:
            raise ShipFileError(f"{desc.source}: [hull] offsets: {exc}") from None
        mesh = hull_mesh_from_stations(
            stations,
            draught=given["draught_m"],
            depth=given["depth_m"],
            name=desc.name,
            **options,
        )
    else:
        if overrides:
            raise ValueError(
                f"ship {desc.name!r}: unknown override(s) {sorted(overrides)}; a mesh hull takes "
                f"only the loading overrides {sorted(LOADING_OVERRIDES)}"
            )
        assert geometry.mesh is not None
        mesh = read_mesh(
            geometry.mesh,
            format=geometry.format,
            frame="z_up" if geometry.frame == "z_up" else "z_down",
            scale=geometry.scale,
            translate=geometry.translate,
            name=desc.name,
            fix_orientation=True,
        )
        mesh = mirror_symmetrised(mesh)
    particulars = _particulars(mesh, given, desc)
    placeholder = MassProperties(1.0, np.zeros(3), np.eye(3))
    base = Hull(desc.name, mesh, placeholder, particulars)
    loading = _with_changes(desc.loading, loading_changes, where=desc.name)
    return replace(base, mass=_mass(base, loading, desc, library_mass=None))


def mirror_symmetrised(mesh: PanelMesh, rtol: float = 1e-6) -> PanelMesh:
    """A port/starboard symmetric hull's mesh made exactly symmetric, else the mesh unchanged.

    A hull exported from CAD is symmetric in its geometry but rarely in its panels (a quad split
    into triangles along the same diagonal on both sides is not its mirror image; a transom is
    triangulated across the centreline), and the BEM then returns sway–heave couplings of a
    few per cent (1.7 % on a 360-panel STL) that a symmetric ship does not have; exact symmetry
    also halves capytaine's cost. When every vertex has a mirror image within ``rtol`` of the
    mesh size, the starboard half (panels across the centreline clipped at y = 0) and its mirror
    image replace the mesh; the result must be closed, else the original is returned.
    """
    from scipy.spatial import cKDTree

    from ship_gym.hull.mesh import MeshError, mesh_from_polygons

    v = mesh.vertices
    tol = rtol * float(np.ptp(v, axis=0).max())
    flip = np.array([1.0, -1.0, 1.0])
    if np.max(cKDTree(v).query(v * flip)[0]) > tol:
        return mesh  # not symmetric: solved as it is
    y = np.where(np.abs(v[:, 1]) <= tol, 0.0, v[:, 1])
    points: list[np.ndarray] = []
    polygons: list[list[int]] = []
    for face in mesh.faces:
        ids = list(dict.fromkeys(face.tolist()))  # a triangle repeats its last index
        if max(y[ids]) <= 0.0:
            continue  # port (or on the centreplane): replaced by the starboard images
        part: list[np.ndarray] = []
        for a, b in zip(ids, ids[1:] + ids[:1], strict=True):
            if y[a] >= 0.0:
                part.append(v[a] * np.array([1.0, 0.0, 1.0]) if y[a] == 0.0 else v[a])
            if (y[a] > 0.0 > y[b]) or (y[a] < 0.0 < y[b]):
                lo, hi = (a, b) if a < b else (b, a)  # the same point from both faces
                t = y[lo] / (y[lo] - y[hi])
                cut = v[lo] + t * (v[hi] - v[lo])
                cut[1] = 0.0
                part.append(cut)
        if len(part) < 3:
            continue
        start = len(points)
        points.extend(part)
        polygons.append(list(range(start, start + len(part))))
    half = np.array(points)
    n = len(half)
    mirrored = [[k + n for k in reversed(p)] for p in polygons]  # reversed: outward normal
    try:
        out = mesh_from_polygons(
            np.vstack([half, half * flip]), polygons + mirrored, name=mesh.name,
            merge_tolerance=tol,
        )  # fmt: skip
        out.check(closed=True)
    except MeshError:
        return mesh
    return out


def _with_changes(loading: LoadingSpec, changes: dict[str, Any], where: str) -> LoadingSpec:
    if not changes:
        return loading
    if "kg_m" in changes:
        loading = replace(loading, gm_m=None)
    if "gm_m" in changes:
        loading = replace(loading, kg_m=None)
    if "radii_of_gyration_m" in changes:
        radii = changes["radii_of_gyration_m"]
        changes["radii_of_gyration_m"] = tuple(float(r) for r in radii)
        loading = replace(loading, inertia_tensor_kgm2=None)
    for key, value in changes.items():
        number = isinstance(value, int | float) and not isinstance(value, bool)
        if key != "radii_of_gyration_m" and not (number and math.isfinite(value)):
            raise ValueError(f"ship {where!r}: override {key} = {value!r}; expected a number")
    return replace(loading, **changes)


def _particulars(mesh: Any, given: dict[str, float], desc: ShipDescription) -> Any:
    """Main particulars from the given fields, the rest measured on the mesh."""
    from ship_gym.hull.hull import Particulars

    v = mesh.vertices
    z_lo, z_hi = float(v[:, 2].min()), float(v[:, 2].max())
    if not (z_lo < 0.0 < z_hi):
        raise ShipFileError(
            f"{desc.source}: [hull] the mesh spans z = {z_lo:.4g} … {z_hi:.4g} m in the body frame "
            "(z down); the design waterline z = 0 must cut it: put the origin on the design "
            "waterline with translate_m (and check frame = 'z_up'/'z_down')"
        )
    wet = v[np.abs(v[:, 2]) <= 1e-6 * max(z_hi - z_lo, 1.0)]
    if len(wet) < 3:  # no mesh line on the waterline: measure the immersed part instead
        from ship_gym.hull.mesh import immersed_part

        wet = immersed_part(mesh).vertices
        wet = wet[np.abs(wet[:, 2]) <= 1e-6 * max(z_hi - z_lo, 1.0)]
    x_aft, x_fwd = float(wet[:, 0].min()), float(wet[:, 0].max())
    lwl = x_fwd - x_aft
    middle = 0.5 * (x_aft + x_fwd)
    if abs(middle) > 0.25 * lwl:
        raise ShipFileError(
            f"{desc.source}: [hull] the waterline runs from x = {x_aft:.4g} to {x_fwd:.4g} m; "
            "the body-frame origin must be amidships (x forward): shift the mesh with "
            f"translate_m = [{-middle:.4g}, 0, …]"
        )
    values = {
        "lpp_m": given.get("lpp_m", lwl),
        "beam_m": given.get("beam_m", 2.0 * float(np.abs(wet[:, 1]).max())),
        "draught_m": given.get("draught_m", z_hi),
        "depth_m": given.get("depth_m", z_hi - z_lo),
    }
    try:
        return Particulars(values["lpp_m"], values["beam_m"], values["draught_m"],
                           values["depth_m"], {})  # fmt: skip
    except ValueError as exc:
        raise ShipFileError(f"{desc.source}: [particulars] {exc}") from None


def _mass(hull: Hull, loading: LoadingSpec, desc: ShipDescription,
          library_mass: MassProperties | None) -> MassProperties:  # fmt: skip
    """Mass properties of a loading (defaults in the module docstring)."""
    from ship_gym.hull import hydrostatics
    from ship_gym.hull.mass import MassProperties

    p = hull.particulars
    hs = hydrostatics(hull)
    where = f"{desc.source or desc.name}: [loading]"
    mass = (
        loading.displacement_t * 1e3
        if loading.displacement_t is not None
        else library_mass.mass
        if library_mass is not None
        else hull.rho * hs.volume
    )
    lcg = (
        loading.lcg_m
        if loading.lcg_m is not None
        else float(library_mass.cog[0])
        if library_mass is not None
        else float(hs.centre_of_buoyancy[0])
    )
    km = hs.kb + hs.bmt
    if loading.kg_m is not None:
        kg = loading.kg_m
    elif loading.gm_m is not None:
        kg = km - loading.gm_m
    elif library_mass is not None:
        kg = p.draught - float(library_mass.cog[2])
    else:
        raise ShipFileError(f"{where} needs kg_m or gm_m (the height of G)")
    if not 0.0 < kg < p.depth:
        raise ShipFileError(
            f"{where} KG = {kg:.4g} m puts G outside the hull; expected 0 < KG < depth "
            f"{p.depth:.4g} m"
        )
    if kg >= km:
        raise ShipFileError(
            f"{where} KG = {kg:.4g} m gives GM = {km - kg:.4g} m <= 0 at the design waterline "
            f"(KM = {km:.4g} m): the ship is unstable upright; expected KG < KM"
        )
    cog = np.array([lcg, 0.0, p.draught - kg])
    if loading.inertia_tensor_kgm2 is not None:
        try:
            return MassProperties(mass, cog, np.array(loading.inertia_tensor_kgm2, dtype=float))
        except ValueError as exc:
            raise ShipFileError(f"{where} inertia_tensor_kgm2: {exc}") from None
    if loading.radii_of_gyration_m is not None:
        radii = loading.radii_of_gyration_m
    elif library_mass is not None:
        radii = tuple(float(r) for r in library_mass.radii_of_gyration)  # type: ignore[assignment]
    else:
        radii = (DEFAULT_RADII[0] * p.beam, DEFAULT_RADII[1] * p.lpp, DEFAULT_RADII[2] * p.lpp)
    return MassProperties.from_radii_of_gyration(mass, cog, (radii[0], radii[1], radii[2]))


# ============================================================================ database check
def check_database_matches(hull: Hull, database: xr.Dataset, source: str) -> None:
    """Refuse a database built for another hull (:class:`DatabaseMismatchError`).

    Compares the database's heave and pitch hydrostatic stiffness, C33 = ρ g A_wp and C55
    (dominated by ρ g I_L), with the hull's at its design waterline, within
    :data:`WATERPLANE_TOLERANCE`: the radiation and diffraction data of one hull's waterline
    are wrong for any other (``ship-gym simulate --hull box_barge`` with the S175 database ran
    the 10 250 t barge with the S175's 24 589 t hydrodynamics).
    """
    from ship_gym.hull import hydrostatics

    if "hydrostatic_stiffness" not in database:
        return
    c_db = np.asarray(database["hydrostatic_stiffness"].values, dtype=float)
    c_hull = hydrostatics(hull).stiffness
    for i, what in ((2, "C33 = rho g A_wp"), (4, "C55")):
        ref = abs(float(c_hull[i, i]))
        if ref == 0.0:
            continue
        err = abs(float(c_db[i, i]) - float(c_hull[i, i])) / ref
        if err > WATERPLANE_TOLERANCE:
            raise DatabaseMismatchError(
                f"database {source!r} does not belong to hull {hull.name!r}: its {what} is "
                f"{c_db[i, i]:.4g} against the hull's {c_hull[i, i]:.4g} ({100 * err:.1f} % off, "
                f"> {100 * WATERPLANE_TOLERANCE:g} %); build the hull's own database "
                "(ship-gym ship build FILE, or leave the database to the ship)"
            )
