"""Ship description files: one human-editable TOML file per ship and loading condition.

A ship file says everything the simulator needs to know about a ship that is not the sea: the
hull geometry (a mesh file, a table of offsets or a library hull), the main particulars, the
loading condition, the appendages and the speed range. Every field has a unit in its name
(``kg_m``, ``area_m2``) and is validated on reading; an error names the field as it is written
in the file (``[loading] kg_m``) with the bad value and what was expected. What a file leaves out
is estimated from the main particulars (:mod:`ship_gym.ship.appendages`, the loading defaults
below), and ``ship-gym ship check FILE`` prints every value with where it came from.

Schema (version 1)
------------------
::

    schema = 1                       # optional; the version of this layout
    name = "my_ship"                 # required: letters, digits, '_' or '-'
    description = "…"                # optional free text

    [hull]                           # exactly one of library / mesh / offsets
    library = "s175"                 # a library hull (ship_gym.hull.HULLS)
    mesh = "hull.stl"                # or a closed mesh to the deck (STL, GDF, Nemoh .dat, OBJ),
    format = "stl"                   #   path relative to this file; format from the suffix
    frame = "z_up"                   #   "z_up" (x fwd, y port, z up: most CAD) or "z_down"
    scale = 1.0                      #   metres per file unit
    translate_m = [0.0, 0.0, 0.0]    #   shift to put O amidships on the design waterline
    offsets = "offsets.csv"          # or station offsets (columns as ship_gym/data/s175)
    [hull.options]                   # library builder keywords, or the offsets mesh resolution
    n_sections = 60                  #   (n_sections, n_below, n_above, n_deck)

    [particulars]                    # mesh: inferred from the mesh where left out;
    lpp_m = 175.0                    # offsets: draught_m and depth_m required;
    beam_m = 25.4                    # library: not allowed (the builder's own)
    draught_m = 9.5
    depth_m = 15.4

    [loading]                        # library: optional (the builder's design loading)
    displacement_t = 24589.0         # default ρ V at the design waterline
    kg_m = 9.55                      # or gm_m (KG = KM − GM at the design waterline)
    lcg_m = -2.55                    # positive forward of amidships; default the LCB
    radii_of_gyration_m = [8.33, 42.0, 42.0]   # r44, r55, r66 about G; default 0.35 B,
                                     # 0.25 Lpp, 0.25 Lpp (ITTC 7.5-02-07-04.1 typical values)
    # inertia_tensor_kgm2 = [[…], […], […]]    # instead of the radii: 3×3 about G, body axes

    [speed]
    service_mps = 10.36              # or service_froude; default Fn 0.25
    range_mps = [0.0, 12.0]          # speeds the ship is used at (default 0 … 1.2 × service)

    [rudder]                         # each appendage table optional: estimated when left out
    [propeller]                      # (ship_gym.ship.appendages); ``fitted = false`` removes
    [fins]                           # fins or T-foil from the tasks that would use them
    [t_foil]

    [hydrodynamics]
    database = "my_ship_hydro.nc"    # optional: a bundled name or a NetCDF path; default the
    n_omega = 40                     #   database built from the hull by ``ship-gym ship build``
    omega_max_rad_s = 2.5            #   and cached (ship_gym.ship.database_cache)
    headings_deg = [0, 30, 60, 90, 120, 150, 180]

Appendage keys (all optional; units in the names):

* ``[rudder]``: ``area_m2``, ``aspect_ratio``, ``x_m``, ``z_m``, ``lateral_positions_m``,
  ``wake_fraction``, ``drift_straightening``, ``yaw_straightening``, ``propeller_diameter_m``,
  ``propeller_distance_m``, ``stall_angle_deg``;
* ``[propeller]``: ``diameter_m``, ``blades``, ``blade_area_ratio``, ``pitch_ratio``, ``rpm``,
  ``wake_fraction``, ``thrust_deduction`` (one propeller on the centreline: a twin-screw ship
  is modelled by one propeller delivering the whole thrust);
* ``[fins]``: ``fitted``, ``area_m2``, ``span_m``, ``x_m``, ``y_m``, ``z_m``, ``max_angle_deg``;
* ``[t_foil]``: ``fitted``, ``area_m2``, ``span_m``, ``x_m``, ``z_m``, ``max_angle_deg``;
* ``[wind]``: the windage of :class:`ship_gym.forces.wind.Windage`: ``frontal_area_m2``,
  ``lateral_area_m2``, ``centroid_height_m``, ``centroid_x_m``, ``length_overall_m`` and
  Blendermann's ``cdt``, ``cdl_af_ahead``, ``cdl_af_astern``, ``delta``, ``kappa`` (defaults:
  a loaded container ship).
"""

from __future__ import annotations

import hashlib
import math
import os
import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any, Final

__all__ = [
    "SCHEMA_VERSION",
    "HullGeometry",
    "HydrodynamicsSpec",
    "LoadingSpec",
    "ShipDescription",
    "ShipFileError",
    "SpeedSpec",
    "bundled_ship_path",
    "bundled_ships",
    "is_ship_file",
    "read_ship",
]

SCHEMA_VERSION: Final = 1
"""Version of the ship-file layout read here."""


class ShipFileError(ValueError):
    """A ship file is unreadable or a field has a bad value (the message names the field)."""


# =============================================================================== value objects
@dataclass(frozen=True)
class HullGeometry:
    """Where the hull comes from: exactly one of ``library``, ``mesh``, ``offsets``.

    Attributes
    ----------
    library : str or None
        Library hull name (:data:`ship_gym.hull.HULLS`).
    mesh : pathlib.Path or None
        Closed mesh file to the deck (absolute path).
    offsets : pathlib.Path or None
        Station offsets CSV (absolute path).
    options : tuple of (str, object)
        Builder keywords (library) or mesh resolution (offsets), sorted.
    format : str or None
        Mesh format (None: from the suffix).
    frame : {"z_up", "z_down"}
        Frame of the mesh file.
    scale : float
        Metres per mesh-file unit [m].
    translate : tuple of float
        Shift applied after the frame conversion [m].
    """

    library: str | None = None
    mesh: Path | None = None
    offsets: Path | None = None
    options: tuple[tuple[str, Any], ...] = ()
    format: str | None = None
    frame: str = "z_up"
    scale: float = 1.0
    translate: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def kind(self) -> str:
        """``"library"``, ``"mesh"`` or ``"offsets"``."""
        return "library" if self.library else "mesh" if self.mesh else "offsets"


@dataclass(frozen=True)
class LoadingSpec:
    """Loading condition as written (None: estimated, see :func:`ship_gym.ship.build_hull`).

    Attributes
    ----------
    displacement_t : float or None
        Mass [t].
    kg_m, gm_m : float or None
        Height of G above the keel, or transverse metacentric height at the design waterline
        [m] (at most one).
    lcg_m : float or None
        Longitudinal position of G, positive forward of amidships [m].
    radii_of_gyration_m : tuple of 3 float or None
        r44, r55, r66 about G [m].
    inertia_tensor_kgm2 : tuple of 3 tuples of 3 float or None
        Inertia tensor about G in body axes [kg·m²] (instead of the radii).
    """

    displacement_t: float | None = None
    kg_m: float | None = None
    gm_m: float | None = None
    lcg_m: float | None = None
    radii_of_gyration_m: tuple[float, float, float] | None = None
    inertia_tensor_kgm2: tuple[tuple[float, ...], ...] | None = None

    @property
    def given(self) -> bool:
        """Whether any loading field was written."""
        return any(getattr(self, f) is not None for f in self.__dataclass_fields__)


@dataclass(frozen=True)
class SpeedSpec:
    """Service speed and speed range.

    Attributes
    ----------
    service_mps : float or None
        Service speed [m/s].
    service_froude : float or None
        Service Froude number on Lpp [-] (instead of ``service_mps``).
    range_mps : tuple of 2 float or None
        Speeds the ship is used at [m/s].
    """

    service_mps: float | None = None
    service_froude: float | None = None
    range_mps: tuple[float, float] | None = None


@dataclass(frozen=True)
class HydrodynamicsSpec:
    """The BEM database of the ship: given, or built from the hull with these settings.

    Attributes
    ----------
    database : str or None
        Bundled database name or NetCDF path (absolute); None: built and cached.
    n_omega : int
        Finite frequencies of the BEM grid.
    omega_max_rad_s : float or None
        Largest finite frequency [rad/s] (None: what the mesh resolves).
    headings_deg : tuple of float
        Wave headings of the diffraction problems [deg] (0 following, 180 head seas).
    """

    database: str | None = None
    n_omega: int = 40
    omega_max_rad_s: float | None = None
    headings_deg: tuple[float, ...] = (0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0)


@dataclass(frozen=True)
class ShipDescription:
    """A ship file, read and validated (:func:`read_ship`).

    Attributes
    ----------
    name : str
        Ship identifier.
    description : str
        Free text.
    source : pathlib.Path or None
        The file it was read from.
    hull : HullGeometry
        Hull geometry.
    particulars : tuple of (str, float)
        Given main particulars (``lpp_m``, ``beam_m``, ``draught_m``, ``depth_m``).
    loading : LoadingSpec
        Loading condition.
    speed : SpeedSpec
        Service speed and range.
    rudder, propeller, fins, t_foil, wind : tuple of (str, object)
        Appendage fields as written (sorted items; empty: estimated).
    hydrodynamics : HydrodynamicsSpec
        Database settings.
    digest : str
        SHA-256 of the file's bytes and of every file it refers to.
    """

    name: str
    hull: HullGeometry
    description: str = ""
    source: Path | None = None
    particulars: tuple[tuple[str, float], ...] = ()
    loading: LoadingSpec = field(default_factory=LoadingSpec)
    speed: SpeedSpec = field(default_factory=SpeedSpec)
    rudder: tuple[tuple[str, Any], ...] = ()
    propeller: tuple[tuple[str, Any], ...] = ()
    fins: tuple[tuple[str, Any], ...] = ()
    t_foil: tuple[tuple[str, Any], ...] = ()
    wind: tuple[tuple[str, Any], ...] = ()
    hydrodynamics: HydrodynamicsSpec = field(default_factory=HydrodynamicsSpec)
    digest: str = ""

    def appendage(self, name: str) -> dict[str, Any]:
        """The written fields of one appendage table (``"rudder"``, ``"fins"``, …)."""
        return dict(getattr(self, name))


# ====================================================================== the schema, as a table
_TOP_KEYS: Final = {
    "schema",
    "name",
    "description",
    "hull",
    "particulars",
    "loading",
    "speed",
    "rudder",
    "propeller",
    "fins",
    "t_foil",
    "wind",
    "hydrodynamics",
}
_HULL_KEYS: Final = {"library", "mesh", "offsets", "options", "format", "frame", "scale",
                     "translate_m"}  # fmt: skip
_PARTICULARS: Final = ("lpp_m", "beam_m", "draught_m", "depth_m")
_OFFSETS_OPTIONS: Final = ("n_sections", "n_below", "n_above", "n_deck", "n_end")

# appendage tables: key → (kind, lower bound, upper bound); kinds: "length" (> 0 [m]),
# "coordinate" (finite [m]), "fraction", "angle" (deg), "int", "bool", "positions"
APPENDAGE_FIELDS: Final[dict[str, dict[str, tuple[str, float, float]]]] = {
    "rudder": {
        "area_m2": ("positive", 0.0, math.inf),
        "aspect_ratio": ("positive", 0.0, 10.0),
        "x_m": ("coordinate", -math.inf, math.inf),
        "z_m": ("coordinate", -math.inf, math.inf),
        "lateral_positions_m": ("positions", -math.inf, math.inf),
        "wake_fraction": ("fraction", 0.0, 0.99),
        "drift_straightening": ("number", 0.0, 2.0),
        "yaw_straightening": ("number", 0.0, 2.0),
        "propeller_diameter_m": ("positive", 0.0, math.inf),
        "propeller_distance_m": ("number", 0.0, math.inf),
        "stall_angle_deg": ("number", 5.0, 60.0),
    },
    "propeller": {
        "diameter_m": ("positive", 0.0, math.inf),
        "blades": ("int", 2, 7),
        "blade_area_ratio": ("number", 0.3, 1.05),
        "pitch_ratio": ("number", 0.5, 1.4),
        "rpm": ("positive", 0.0, 5000.0),
        "wake_fraction": ("fraction", 0.0, 0.8),
        "thrust_deduction": ("fraction", 0.0, 0.6),
    },
    "fins": {
        "fitted": ("bool", 0, 1),
        "area_m2": ("positive", 0.0, math.inf),
        "span_m": ("positive", 0.0, math.inf),
        "x_m": ("coordinate", -math.inf, math.inf),
        "y_m": ("positive", 0.0, math.inf),
        "z_m": ("coordinate", -math.inf, math.inf),
        "max_angle_deg": ("number", 1.0, 45.0),
    },
    "t_foil": {
        "fitted": ("bool", 0, 1),
        "area_m2": ("positive", 0.0, math.inf),
        "span_m": ("positive", 0.0, math.inf),
        "x_m": ("coordinate", -math.inf, math.inf),
        "z_m": ("coordinate", -math.inf, math.inf),
        "max_angle_deg": ("number", 1.0, 45.0),
    },
    "wind": {
        "frontal_area_m2": ("positive", 0.0, math.inf),
        "lateral_area_m2": ("positive", 0.0, math.inf),
        "centroid_height_m": ("coordinate", -math.inf, math.inf),
        "centroid_x_m": ("coordinate", -math.inf, math.inf),
        "length_overall_m": ("positive", 0.0, math.inf),
        "cdt": ("positive", 0.0, 3.0),
        "cdl_af_ahead": ("number", 0.0, 3.0),
        "cdl_af_astern": ("number", 0.0, 3.0),
        "delta": ("number", 0.0, 1.0),
        "kappa": ("number", 0.0, 5.0),
    },
}
"""Allowed fields of each appendage table: (kind, lower, upper bound)."""

_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_\-]{0,63}$")


# ==================================================================================== reading
def is_ship_file(name: str | os.PathLike[str]) -> bool:
    """Whether ``name`` designates a ship file (a ``.toml`` path) rather than a library name."""
    return os.fspath(name).lower().endswith(".toml")


def bundled_ships() -> list[str]:
    """Names of the ship files shipped with ship_gym (``ship_gym/data/ships/*.toml``)."""
    folder = resources.files("ship_gym").joinpath("data", "ships")
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".toml"))


def bundled_ship_path(name: str) -> Path:
    """Path of a bundled ship file by name (``"s175"`` → ``ship_gym/data/ships/s175.toml``)."""
    return Path(str(resources.files("ship_gym").joinpath("data", "ships", f"{name}.toml")))


def read_ship(path: str | os.PathLike[str]) -> ShipDescription:
    """Read and validate a ship file (schema in the module docstring).

    Parameters
    ----------
    path : str or os.PathLike
        The TOML file. Relative paths inside it (mesh, offsets, database) are relative to the
        file's folder.

    Returns
    -------
    ShipDescription

    Raises
    ------
    FileNotFoundError
        The file, or a file it names, does not exist.
    ShipFileError
        TOML syntax error, unknown table or key, missing or bad value (the message names the
        field as written, e.g. ``[loading] kg_m``).
    """
    path = Path(path)
    if path.is_dir():
        raise ShipFileError(f"ship file {str(path)!r} is a directory; expected a .toml file")
    if not path.is_file():
        raise FileNotFoundError(f"ship file {str(path)!r} not found")
    data = path.read_bytes()
    try:
        doc = tomllib.loads(data.decode("utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ShipFileError(f"{path}: not a valid TOML file ({exc})") from None
    where = str(path)
    _only(doc, _TOP_KEYS, where, "")
    schema = doc.get("schema", SCHEMA_VERSION)
    if schema != SCHEMA_VERSION:
        raise ShipFileError(
            f"{where}: schema = {schema!r}; this ship_gym reads schema {SCHEMA_VERSION}"
        )
    name = doc.get("name")
    if not isinstance(name, str) or not _NAME.match(name):
        raise ShipFileError(
            f"{where}: name = {name!r}; expected 1-64 letters, digits, '_' or '-' (required)"
        )
    description = doc.get("description", "")
    if not isinstance(description, str):
        raise ShipFileError(f"{where}: description = {description!r}; expected a string")
    folder = path.resolve().parent
    hull = _hull(_table(doc, "hull", where, required=True), folder, where)
    particulars = _particulars(_table(doc, "particulars", where), hull, where)
    loading = _loading(_table(doc, "loading", where), where)
    speed = _speed(_table(doc, "speed", where), where)
    appendages = {key: _appendage(key, _table(doc, key, where), where) for key in APPENDAGE_FIELDS}
    hydro = _hydrodynamics(_table(doc, "hydrodynamics", where), folder, where)
    digest = hashlib.sha256(data)
    for ref in (hull.mesh, hull.offsets):
        if ref is not None:
            digest.update(ref.read_bytes())
    return ShipDescription(
        name=name,
        description=description,
        source=path.resolve(),
        hull=hull,
        particulars=particulars,
        loading=loading,
        speed=speed,
        hydrodynamics=hydro,
        digest=digest.hexdigest(),
        **appendages,
    )


# ------------------------------------------------------------------------------ validation
def _only(table: Mapping[str, Any], allowed: set[str] | Mapping[str, Any], where: str,
          section: str) -> None:  # fmt: skip
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        label = f"[{section}] " if section else ""
        raise ShipFileError(
            f"{where}: unknown {label}key(s) {unknown}; expected some of {sorted(allowed)}"
        )


def _table(doc: Mapping[str, Any], key: str, where: str, required: bool = False) -> dict:
    value = doc.get(key)
    if value is None:
        if required:
            raise ShipFileError(f"{where}: missing table [{key}]")
        return {}
    if not isinstance(value, dict):
        raise ShipFileError(f"{where}: {key} = {value!r}; expected a table [{key}]")
    return value


def _number(value: Any, label: str, where: str, low: float = -math.inf, high: float = math.inf,
            *, low_open: bool = False, unit: str = "") -> float:  # fmt: skip
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ShipFileError(f"{where}: {label} = {value!r}; expected a finite number {unit}")
    bad_low = value <= low if low_open else value < low
    if bad_low or value > high:
        lo = "(" if low_open else "["
        raise ShipFileError(
            f"{where}: {label} = {value!r}; expected a value in {lo}{low:g}, {high:g}] {unit}"
        )
    return float(value)


def _path(value: Any, label: str, folder: Path, where: str) -> Path:
    if not isinstance(value, str) or not value:
        raise ShipFileError(f"{where}: {label} = {value!r}; expected a file path (a string)")
    p = Path(value).expanduser()
    p = p if p.is_absolute() else folder / p
    if not p.is_file():
        raise FileNotFoundError(f"{where}: {label} = {value!r}: file {str(p)!r} not found")
    return p


def _hull(table: dict, folder: Path, where: str) -> HullGeometry:
    from ship_gym.hull.library import HULLS
    from ship_gym.hull.mesh_io import MESH_FORMATS

    _only(table, _HULL_KEYS, where, "hull")
    sources = [k for k in ("library", "mesh", "offsets") if k in table]
    if len(sources) != 1:
        raise ShipFileError(
            f"{where}: [hull] needs exactly one of library, mesh, offsets; got {sources or 'none'}"
        )
    kind = sources[0]
    options = table.get("options", {})
    if not isinstance(options, dict):
        raise ShipFileError(f"{where}: [hull] options = {options!r}; expected a table")
    if kind != "mesh":
        for key in ("format", "frame", "scale", "translate_m"):
            if key in table:
                raise ShipFileError(f"{where}: [hull] {key} applies to a mesh, not to {kind}")
    if kind == "library":
        lib = table["library"]
        if not isinstance(lib, str) or lib.lower() not in HULLS:
            raise ShipFileError(
                f"{where}: [hull] library = {lib!r}; expected one of {sorted(HULLS)}"
            )
        return HullGeometry(library=lib.lower(), options=tuple(sorted(options.items())))
    if kind == "offsets":
        _only(options, set(_OFFSETS_OPTIONS), where, "hull.options")
        for key, value in options.items():
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise ShipFileError(
                    f"{where}: [hull.options] {key} = {value!r}; expected an integer >= 1"
                )
        path = _path(table["offsets"], "[hull] offsets", folder, where)
        return HullGeometry(offsets=path, options=tuple(sorted(options.items())))
    if options:
        raise ShipFileError(f"{where}: [hull.options] applies to library or offsets hulls")
    fmt = table.get("format")
    if fmt is not None and fmt not in MESH_FORMATS:
        raise ShipFileError(
            f"{where}: [hull] format = {fmt!r}; expected one of {sorted(MESH_FORMATS)}"
        )
    frame = table.get("frame", "z_up")
    if frame not in ("z_up", "z_down"):
        raise ShipFileError(f"{where}: [hull] frame = {frame!r}; expected 'z_up' or 'z_down'")
    scale = _number(table.get("scale", 1.0), "[hull] scale", where, 0.0, low_open=True,
                    unit="[m per file unit]")  # fmt: skip
    shift = table.get("translate_m", [0.0, 0.0, 0.0])
    if not isinstance(shift, list) or len(shift) != 3:
        raise ShipFileError(f"{where}: [hull] translate_m = {shift!r}; expected 3 numbers [m]")
    translate = tuple(_number(v, "[hull] translate_m", where, unit="[m]") for v in shift)
    return HullGeometry(
        mesh=_path(table["mesh"], "[hull] mesh", folder, where),
        format=fmt,
        frame=frame,
        scale=scale,
        translate=(translate[0], translate[1], translate[2]),
    )


def _particulars(table: dict, hull: HullGeometry, where: str) -> tuple[tuple[str, float], ...]:
    _only(table, set(_PARTICULARS), where, "particulars")
    if table and hull.kind == "library":
        raise ShipFileError(
            f"{where}: [particulars] cannot be given for a library hull ({hull.library!r} has "
            "its own); use [hull] mesh or offsets for other dimensions"
        )
    if hull.kind == "offsets":
        missing = [k for k in ("draught_m", "depth_m") if k not in table]
        if missing:
            raise ShipFileError(
                f"{where}: an offsets hull needs [particulars] {', '.join(missing)} [m]"
            )
    values = {
        k: _number(v, f"[particulars] {k}", where, 0.0, low_open=True, unit="[m]")
        for k, v in table.items()
    }
    if "draught_m" in values and "depth_m" in values and values["draught_m"] >= values["depth_m"]:
        raise ShipFileError(
            f"{where}: [particulars] draught_m = {values['draught_m']:g} >= depth_m = "
            f"{values['depth_m']:g}; expected the design waterline below the deck"
        )
    return tuple(sorted(values.items()))


def _loading(table: dict, where: str) -> LoadingSpec:
    keys = {"displacement_t", "kg_m", "gm_m", "lcg_m", "radii_of_gyration_m",
            "inertia_tensor_kgm2"}  # fmt: skip
    _only(table, keys, where, "loading")
    if "kg_m" in table and "gm_m" in table:
        raise ShipFileError(f"{where}: [loading] give kg_m or gm_m, not both")
    if "radii_of_gyration_m" in table and "inertia_tensor_kgm2" in table:
        raise ShipFileError(
            f"{where}: [loading] give radii_of_gyration_m or inertia_tensor_kgm2, not both"
        )
    out: dict[str, Any] = {}
    if "displacement_t" in table:
        out["displacement_t"] = _number(table["displacement_t"], "[loading] displacement_t",
                                        where, 0.0, low_open=True, unit="[t]")  # fmt: skip
    if "kg_m" in table:
        out["kg_m"] = _number(table["kg_m"], "[loading] kg_m", where, unit="[m]")
    if "gm_m" in table:
        out["gm_m"] = _number(table["gm_m"], "[loading] gm_m", where, 0.0, low_open=True,
                              unit="[m] (an upright-stable loading)")  # fmt: skip
    if "lcg_m" in table:
        out["lcg_m"] = _number(table["lcg_m"], "[loading] lcg_m", where, unit="[m]")
    if "radii_of_gyration_m" in table:
        radii = table["radii_of_gyration_m"]
        if not isinstance(radii, list) or len(radii) != 3:
            raise ShipFileError(
                f"{where}: [loading] radii_of_gyration_m = {radii!r}; expected [r44, r55, r66] [m]"
            )
        r = tuple(
            _number(v, "[loading] radii_of_gyration_m", where, 0.0, low_open=True, unit="[m]")
            for v in radii
        )
        out["radii_of_gyration_m"] = (r[0], r[1], r[2])
    if "inertia_tensor_kgm2" in table:
        tensor = table["inertia_tensor_kgm2"]
        if not (isinstance(tensor, list) and len(tensor) == 3
                and all(isinstance(row, list) and len(row) == 3 for row in tensor)):  # fmt: skip
            raise ShipFileError(
                f"{where}: [loading] inertia_tensor_kgm2 = {tensor!r}; expected a 3×3 list "
                "[kg m^2] about G"
            )
        rows = tuple(
            tuple(_number(v, "[loading] inertia_tensor_kgm2", where, unit="[kg m^2]") for v in row)
            for row in tensor
        )
        out["inertia_tensor_kgm2"] = rows
    return LoadingSpec(**out)


def _speed(table: dict, where: str) -> SpeedSpec:
    _only(table, {"service_mps", "service_froude", "range_mps"}, where, "speed")
    if "service_mps" in table and "service_froude" in table:
        raise ShipFileError(f"{where}: [speed] give service_mps or service_froude, not both")
    out: dict[str, Any] = {}
    if "service_mps" in table:
        out["service_mps"] = _number(table["service_mps"], "[speed] service_mps", where, 0.0,
                                     low_open=True, unit="[m/s]")  # fmt: skip
    if "service_froude" in table:
        out["service_froude"] = _number(table["service_froude"], "[speed] service_froude",
                                        where, 0.0, 1.0, low_open=True, unit="[-]")  # fmt: skip
    if "range_mps" in table:
        rng = table["range_mps"]
        if not isinstance(rng, list) or len(rng) != 2:
            raise ShipFileError(f"{where}: [speed] range_mps = {rng!r}; expected [low, high] m/s")
        lo, hi = (_number(v, "[speed] range_mps", where, 0.0, unit="[m/s]") for v in rng)
        if hi <= lo:
            raise ShipFileError(f"{where}: [speed] range_mps = {rng!r}; expected low < high")
        out["range_mps"] = (lo, hi)
    return SpeedSpec(**out)


def _appendage(key: str, table: dict, where: str) -> tuple[tuple[str, Any], ...]:
    spec = APPENDAGE_FIELDS[key]
    _only(table, spec, where, key)
    out: dict[str, Any] = {}
    for name, value in table.items():
        kind, low, high = spec[name]
        label = f"[{key}] {name}"
        if kind == "bool":
            if not isinstance(value, bool):
                raise ShipFileError(f"{where}: {label} = {value!r}; expected true or false")
            out[name] = value
        elif kind == "int":
            if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
                raise ShipFileError(
                    f"{where}: {label} = {value!r}; expected an integer in [{low}, {high}]"
                )
            out[name] = value
        elif kind == "positions":
            if not isinstance(value, list) or not value:
                raise ShipFileError(f"{where}: {label} = {value!r}; expected a list of y [m]")
            out[name] = tuple(_number(v, label, where, unit="[m]") for v in value)
        else:
            out[name] = _number(value, label, where, low, high, low_open=kind == "positive")
    return tuple(sorted(out.items()))


def _hydrodynamics(table: dict, folder: Path, where: str) -> HydrodynamicsSpec:
    _only(table, {"database", "n_omega", "omega_max_rad_s", "headings_deg"}, where,
          "hydrodynamics")  # fmt: skip
    out: dict[str, Any] = {}
    if "database" in table:
        db = table["database"]
        if not isinstance(db, str) or not db:
            raise ShipFileError(
                f"{where}: [hydrodynamics] database = {db!r}; expected a bundled name or a path"
            )
        bare = "/" not in db and os.sep not in db and not db.endswith(".nc")
        out["database"] = db if bare else str(_path(db, "[hydrodynamics] database", folder, where))
    if "n_omega" in table:
        n = table["n_omega"]
        if isinstance(n, bool) or not isinstance(n, int) or not 10 <= n <= 400:
            raise ShipFileError(
                f"{where}: [hydrodynamics] n_omega = {n!r}; expected an integer in [10, 400]"
            )
        out["n_omega"] = n
    if "omega_max_rad_s" in table:
        out["omega_max_rad_s"] = _number(table["omega_max_rad_s"],
                                         "[hydrodynamics] omega_max_rad_s", where, 0.0,
                                         low_open=True, unit="[rad/s]")  # fmt: skip
    if "headings_deg" in table:
        heads = table["headings_deg"]
        if not isinstance(heads, list) or not heads:
            raise ShipFileError(
                f"{where}: [hydrodynamics] headings_deg = {heads!r}; expected a list [deg]"
            )
        values = tuple(
            _number(h, "[hydrodynamics] headings_deg", where, -360.0, 360.0, unit="[deg]")
            for h in heads
        )
        if len({round(v % 360.0, 9) for v in values}) != len(values):
            raise ShipFileError(
                f"{where}: [hydrodynamics] headings_deg = {heads!r}; repeated heading (mod 360)"
            )
        out["headings_deg"] = values
    return HydrodynamicsSpec(**out)
