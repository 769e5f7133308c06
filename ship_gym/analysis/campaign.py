"""Capsize-risk campaigns: a TOML description, content-hashed cells, sharded resumable execution.

A *campaign* is the product ships × loading conditions × seas × headings × speeds × seeds, every
run the capsize-map run of :mod:`ship_gym.analysis.capsize_map` (the ship under the heading
autopilot, capsize when |φ| passes the capsize angle). It is described by a TOML file
(:func:`read_campaign`)::

    name = "s175-loading"
    ships = ["s175"]                       # bundled names or ship files (relative to this file)
    loadings = [{kg = 9.5}, {kg = 10.1}]   # hull overrides; default: the design loading
    headings_deg = [0, 45, 90, 135, 180]   # relative wave heading β (0 following, 180 head)
    froude_numbers = [0.15, 0.25]          # or speeds_mps = [...]
    seeds = 16                             # seeds 0 … 15 per cell
    duration_s = 600.0
    dt_s = 0.1
    integrator = "rk4"                     # or "holloway"
    radiation = "state_space"
    capsize_angle_deg = "vanishing"        # or a number [deg]
    controller = "autopilot"               # or "none" (no rudder)
    batch_seeds = 8                        # seeds per task (one engine call)

    [[seas]]
    kind = "regular"
    height_m = 10.5
    wavelength_m = 262.5                   # or period_s

    [[seas]]
    kind = "jonswap"
    hs_m = 7.0
    tp_s = 15.0
    gamma = 3.3
    spreading_s = 8                        # optional: short-crested (cos-2s), else long-crested

Cells and their ids. A cell is one run; its ``cell_id`` is the first 20 hex digits of the SHA-256
of a canonical JSON (sorted keys, no spaces, numbers as floats) of everything that defines the
run (:func:`cell_identity`):

* the ship by the *content* of its file (``load_ship(x).description.digest``: the TOML bytes and
  the mesh/offsets it names), not by its path — moving or renaming a file keeps its cells, editing
  it makes new ones (a library hull without a file: its name);
* the loading overrides, the sea state (kind, height, wavelength or period, ramp; γ and the number
  of components for a spectrum, and its spreading exponent when short-crested), the heading
  [deg], the speed as given (``froude`` or ``mps`` and its value), the seed;
* the run settings: duration, time step, integrator, radiation model, the capsize criterion
  (``"vanishing"`` or the angle), the controller (a trained policy by the content of its
  files), ``record_every`` and the database;
* :data:`CELL_SCHEMA`, bumped when a change of ship_gym changes what a cell computes.

The ship_gym version itself is *not* hashed — every release would otherwise invalidate every
finished campaign — but stored in each record (``ship_gym_version``) so that a mixed store can be
seen. A cell's id depends on nothing else (not on the order of the lists, nor on the other
cells), so extending a campaign (more headings, seeds, seas) runs only the new cells.

Tasks. Cells sharing all but the seed form a group; its pending seeds are cut into tasks of at
most ``batch_seeds`` seeds, each run as the ships of ONE engine batch by
:func:`~ship_gym.analysis.capsize_map.run_cells` (each ship bit-identical to alone), with one BLAS
thread. A task's id hashes its cell ids. :func:`run_campaign` skips the cells already in the
store, runs the tasks through an executor (:mod:`ship_gym.analysis.executors`: serial, local
processes or Ray) and writes each finished task as one Parquet shard, atomically
(:mod:`ship_gym.analysis.campaign_store`): a kill loses at most the running tasks, and the same
campaign gives bit-identical outcomes run serially, in parallel or resumed.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import sys
import time
import tomllib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path
from typing import Any, Literal

from ship_gym.analysis.capsize_map import SeaSpec
from ship_gym.analysis.executors import Executor, ProcessExecutor, WorkerLostError
from ship_gym.analysis.policy_cells import POLICY_PREFIX, PolicyController

__all__ = [
    "CELL_SCHEMA",
    "CampaignCell",
    "CampaignError",
    "CampaignResult",
    "CampaignSpec",
    "CampaignTask",
    "cell_identity",
    "cells",
    "read_campaign",
    "run_campaign",
    "run_task",
    "tasks",
]

CELL_SCHEMA = 1
"""Version of what a cell computes, part of every cell id: bump it when a change of the physics or
of the run protocol makes old results not comparable (old cells are then re-run)."""

ControllerName = str
"""``"autopilot"``, ``"none"`` or ``"policy:PATH"`` (:mod:`ship_gym.analysis.policy_cells`)."""

_SCALAR_KEYS = (
    "seeds",
    "duration_s",
    "dt_s",
    "integrator",
    "radiation",
    "capsize_angle_deg",
    "controller",
    "batch_seeds",
    "record_every",
    "initial_heel_deg",
    "database",
    "name",
)
"""Top-level keys taken as they are (checked by :class:`CampaignSpec`)."""
_TOP_KEYS = {
    *_SCALAR_KEYS,
    "description",
    "ships",
    "loadings",
    "headings_deg",
    "froude_numbers",
    "speeds_mps",
    "seas",
}
_REGULAR_KEYS = {"kind", "height_m", "wavelength_m", "period_s", "ramp_s"}
_JONSWAP_KEYS = {"kind", "hs_m", "tp_s", "gamma", "n_components", "ramp_s", "spreading_s"}
_RADIATIONS = ("state_space", "convolution", "2a", "2b", "none")


class CampaignError(ValueError):
    """A bad campaign description; the message names the field as written."""


# ----------------------------------------------------------------------------- description
def _is_number(x: object) -> bool:
    return isinstance(x, int | float) and not isinstance(x, bool) and math.isfinite(x)


@dataclass(frozen=True)
class CampaignSpec:
    """A campaign description (the TOML file, :func:`read_campaign`); field names as in the file.

    Parameters
    ----------
    ships : tuple of str
        Bundled ship names or ship files (``.toml``), as written; files are relative to
        ``base_dir``.
    headings_deg : tuple of float
        Relative wave headings β [deg] (0 following, 180 head seas).
    seas : tuple of SeaSpec
        Sea states.
    loadings : tuple of dict
        Loading conditions: hull overrides (``{"kg": 10.1}`` [m], mesh arguments…); ``({},)`` the
        design loading.
    froude_numbers : tuple of float
        Fn = U/√(gL) in (0, 1) [-]; give these or ``speeds_mps``.
    speeds_mps : tuple of float
        Speeds U [m/s] (converted per ship to Fn).
    seeds : int
        Seeds per cell (0 … seeds−1).
    duration_s, dt_s : float
        Simulated time per run and physics step [s].
    integrator : {"rk4", "holloway"}
        Time integrator.
    radiation : {"state_space", "convolution", "2a", "2b", "none"}
        Radiation model.
    capsize_angle_deg : float or "vanishing"
        |φ| counted as capsize [deg], or the angle of vanishing stability of each loading.
    controller : str
        ``"autopilot"``: the heading autopilot on the rudder; ``"none"``: no rudder at all
        (propeller at the self-propulsion rpm either way); ``"policy:PATH"``: a policy trained
        by ``ship-gym train`` (its run folder or ``model.zip``, relative to the campaign file)
        driving the environment it was trained in (:mod:`ship_gym.analysis.policy_cells`).
    batch_seeds : int
        Seeds per task (one engine call).
    record_every : int
        Steps between the samples of the roll statistics.
    initial_heel_deg : float
        Each seed starts heeled by a draw in ± this [deg]
        (:attr:`ship_gym.analysis.capsize_map.CapsizeMapConfig.initial_heel_deg`: instabilities
        grow from a stated disturbance, not round-off); 0: upright (autopilot and ``"none"``
        controllers only).
    database : str
        Hydrodynamic database ("auto": the ship's own).
    name : str
        Campaign name.
    base_dir : Path
        Folder that relative ship paths are relative to (the TOML file's).
    """

    ships: tuple[str, ...]
    headings_deg: tuple[float, ...]
    seas: tuple[SeaSpec, ...]
    loadings: tuple[dict, ...] = ({},)
    froude_numbers: tuple[float, ...] = ()
    speeds_mps: tuple[float, ...] = ()
    seeds: int = 1
    duration_s: float = 720.0
    dt_s: float = 0.1
    integrator: Literal["rk4", "holloway"] = "rk4"
    radiation: Literal["state_space", "convolution", "2a", "2b", "none"] = "state_space"
    capsize_angle_deg: float | str = "vanishing"
    controller: ControllerName = "autopilot"
    batch_seeds: int = 8
    record_every: int = 5
    initial_heel_deg: float = 0.0
    database: str = "auto"
    name: str = ""
    base_dir: Path = field(default_factory=Path.cwd)

    def __post_init__(self) -> None:
        object.__setattr__(self, "ships", tuple(self.ships))
        object.__setattr__(self, "seas", tuple(self.seas))
        object.__setattr__(self, "loadings", tuple(dict(x) for x in self.loadings))
        for name in ("headings_deg", "froude_numbers", "speeds_mps"):
            values = getattr(self, name)
            if not all(_is_number(v) for v in values):
                raise CampaignError(f"{name} = {list(values)!r}; expected a list of numbers")
            object.__setattr__(self, name, tuple(float(v) for v in values))
        if not self.ships or not all(isinstance(s, str) and s for s in self.ships):
            raise CampaignError(
                f"ships = {list(self.ships)!r}; expected a non-empty list of bundled ship names "
                "or .toml ship files"
            )
        _no_duplicates("ships", self.ships)
        if not self.headings_deg:
            raise CampaignError("headings_deg = []; expected at least one heading [deg]")
        if not all(-360.0 <= h <= 360.0 for h in self.headings_deg):
            raise CampaignError(
                f"headings_deg = {list(self.headings_deg)!r}; expected headings within ±360 deg"
            )
        _no_duplicates("headings_deg", [h % 360.0 for h in self.headings_deg])
        if bool(self.froude_numbers) == bool(self.speeds_mps):
            raise CampaignError(
                "give exactly one of froude_numbers (Fn [-]) and speeds_mps (U [m/s]); got "
                f"froude_numbers = {list(self.froude_numbers)!r}, "
                f"speeds_mps = {list(self.speeds_mps)!r}"
            )
        if not all(0.0 < f < 1.0 for f in self.froude_numbers):
            raise CampaignError(
                f"froude_numbers = {list(self.froude_numbers)!r}; expected values in (0, 1) "
                "(the autopilot needs headway)"
            )
        if not all(s > 0.0 for s in self.speeds_mps):
            raise CampaignError(
                f"speeds_mps = {list(self.speeds_mps)!r}; expected speeds > 0 [m/s]"
            )
        _no_duplicates("froude_numbers", self.froude_numbers)
        _no_duplicates("speeds_mps", self.speeds_mps)
        if not self.seas or not all(isinstance(s, SeaSpec) for s in self.seas):
            raise CampaignError("seas: expected at least one [[seas]] table")
        _no_duplicates("seas", self.seas)
        if not self.loadings:
            raise CampaignError("loadings = []; expected at least one table (e.g. {} or {kg = 10})")
        for i, load in enumerate(self.loadings):
            if not all(isinstance(k, str) for k in load) or not all(
                isinstance(v, str | bool | int | float) for v in load.values()
            ):
                raise CampaignError(
                    f"loadings[{i}] = {load!r}; expected a table of hull overrides with "
                    "number, string or boolean values, e.g. {kg = 10.1}"
                )
        _no_duplicates(
            "loadings", [json.dumps(_canonical(x), sort_keys=True) for x in self.loadings]
        )
        for name in ("seeds", "batch_seeds", "record_every"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or value < 1:
                raise CampaignError(f"{name} = {value!r}; expected an integer >= 1")
        for name in ("duration_s", "dt_s"):
            value = getattr(self, name)
            if not _is_number(value) or value <= 0.0:
                raise CampaignError(f"{name} = {value!r}; expected a time > 0 [s]")
        if self.dt_s > 1.0:
            raise CampaignError(
                f"dt_s = {self.dt_s!r}; expected <= 1 s (too coarse for the 6-DOF model)"
            )
        n = round(self.duration_s / self.dt_s)
        if n < 1 or abs(n * self.dt_s - self.duration_s) > 1e-9 * max(1.0, self.duration_s):
            raise CampaignError(
                f"duration_s = {self.duration_s!r}; expected a positive multiple of "
                f"dt_s = {self.dt_s!r}"
            )
        if self.integrator not in ("rk4", "holloway"):
            raise CampaignError(f"integrator = {self.integrator!r}; expected 'rk4' or 'holloway'")
        if self.radiation not in _RADIATIONS:
            raise CampaignError(
                f"radiation = {self.radiation!r}; expected one of {', '.join(_RADIATIONS)}"
            )
        heel = self.initial_heel_deg
        if not (_is_number(heel) and 0.0 <= float(heel) <= 30.0):
            raise CampaignError(
                f"initial_heel_deg = {heel!r}; expected a heel in [0, 30] [deg] (a disturbance "
                "drawn per seed within ± it)"
            )
        if float(heel) > 0.0 and str(self.controller).startswith(POLICY_PREFIX):
            raise CampaignError(
                f"initial_heel_deg = {heel!r} with controller = {self.controller!r}: a policy "
                "cell starts from its environment's reset; use 0 or the autopilot/none"
            )
        angle = self.capsize_angle_deg
        if not (angle == "vanishing" or (_is_number(angle) and 0.0 < float(angle) <= 180.0)):
            raise CampaignError(
                f"capsize_angle_deg = {angle!r}; expected an angle in (0, 180] [deg] or "
                "'vanishing' (the angle of vanishing stability of each loading)"
            )
        if not isinstance(self.controller, str) or not (
            self.controller in ("autopilot", "none") or self.controller.startswith(POLICY_PREFIX)
        ):
            raise CampaignError(
                f"controller = {self.controller!r}; expected 'autopilot', 'none' or "
                "'policy:PATH' (a `ship-gym train` run folder or its model.zip)"
            )
        if self.policy is not None:
            self._check_policy_cells()
        if not isinstance(self.database, str):
            raise CampaignError(f"database = {self.database!r}; expected a string")

    @cached_property
    def policy(self) -> PolicyController | None:
        """The trained policy of ``controller = "policy:PATH"`` (None for the others)."""
        if not self.controller.startswith(POLICY_PREFIX):
            return None
        from ship_gym.analysis.policy_cells import read_policy_controller

        raw = self.controller[len(POLICY_PREFIX) :]
        path = (self.base_dir / Path(raw).expanduser()).resolve()
        try:
            return read_policy_controller(path, field=f"controller = {self.controller!r}")
        except ValueError as exc:
            raise CampaignError(str(exc)) from None

    def _check_policy_cells(self) -> None:
        """What a policy's environment cannot run is refused before any work."""
        from ship_gym.analysis.policy_cells import cell_env_kwargs

        assert self.policy is not None
        field_of = f"controller = {self.controller!r}"
        if self.radiation != "state_space":
            raise CampaignError(
                f"radiation = {self.radiation!r}; a policy's environment runs state-space "
                f"radiation ({field_of}): expected 'state_space'"
            )
        if self.database != "auto":
            raise CampaignError(
                f"database = {self.database!r}; a policy's environment runs the ship's own "
                f"database ({field_of}): expected 'auto'"
            )
        for load in self.loadings:
            for sea in self.seas:
                try:
                    cell_env_kwargs(
                        self.policy, ship="s175", loading=load, sea=sea, dt_s=self.dt_s,
                        integrator=self.integrator, capsize_angle_deg=30.0,
                    )  # fmt: skip
                except ValueError as exc:
                    raise CampaignError(f"{exc} ({field_of})") from None

    @property
    def controller_identity(self) -> str | dict:
        """The controller as a cell id hashes it: a policy by its content, not its path."""
        return {"policy": self.policy.digest} if self.policy is not None else self.controller

    @property
    def speed_kind(self) -> Literal["froude", "mps"]:
        """``"froude"`` when the speeds are Froude numbers, ``"mps"`` for speeds [m/s]."""
        return "froude" if self.froude_numbers else "mps"

    @property
    def speeds(self) -> tuple[float, ...]:
        """The speeds as given (Fn or m/s, :attr:`speed_kind`)."""
        return self.froude_numbers or self.speeds_mps

    def resolve_ship(self, ship: str) -> str:
        """A ship as :func:`ship_gym.ship.load_ship` takes it (files made absolute)."""
        from ship_gym.ship import is_ship_file

        if is_ship_file(ship):
            return str((self.base_dir / Path(ship).expanduser()).resolve())
        return ship


def _no_duplicates(name: str, values: Sequence[Any]) -> None:
    dup = [v for i, v in enumerate(values) if v in values[:i]]
    if dup:
        shown = dup[0].label if isinstance(dup[0], SeaSpec) else dup[0]
        raise CampaignError(f"{name}: {shown!r} appears twice; expected each value once")


def _sea(table: object, where: str) -> SeaSpec:
    """One ``[[seas]]`` table → SeaSpec; ``where`` names it in errors (``[[seas]] #2``)."""
    if not isinstance(table, dict):
        raise CampaignError(f"{where} = {table!r}; expected a table")
    kind = table.get("kind")
    if kind not in ("regular", "jonswap"):
        raise CampaignError(f"{where} kind = {kind!r}; expected 'regular' or 'jonswap'")
    allowed = _REGULAR_KEYS if kind == "regular" else _JONSWAP_KEYS
    unknown = sorted(set(table) - allowed)
    if unknown:
        raise CampaignError(
            f"{where} {unknown[0]}: unknown key for a {kind} sea; expected {sorted(allowed)}"
        )

    def number(key: str, *, required: bool = True, default: float | None = None) -> float | None:
        if key not in table:
            if required:
                raise CampaignError(f"{where} {key}: missing; expected a number")
            return default
        value = table[key]
        if not _is_number(value) or value <= 0.0:
            raise CampaignError(f"{where} {key} = {value!r}; expected a number > 0")
        return float(value)

    ramp = number("ramp_s", required=False, default=50.0)
    assert ramp is not None
    try:
        if kind == "regular":
            wavelength = number("wavelength_m", required=False)
            period = number("period_s", required=False)
            if (wavelength is None) == (period is None):
                raise CampaignError(
                    f"{where}: give exactly one of wavelength_m [m] and period_s [s]"
                )
            height = number("height_m")
            assert height is not None
            return SeaSpec("regular", height, period=period, wavelength=wavelength, ramp_time=ramp)
        spreading = None
        if "spreading_s" in table:
            spreading = table["spreading_s"]
            if not _is_number(spreading) or not 0.0 <= spreading <= 1000.0:
                raise CampaignError(
                    f"{where} spreading_s = {spreading!r}; expected a cos-2s exponent s in "
                    "[0, 1000] (leave it out for a long-crested sea)"
                )
            spreading = float(spreading)
        hs, tp = number("hs_m"), number("tp_s")
        gamma = number("gamma", required=False, default=3.3)
        n_comp = table.get("n_components", 50)
        if isinstance(n_comp, bool) or not isinstance(n_comp, int) or n_comp < 1:
            raise CampaignError(f"{where} n_components = {n_comp!r}; expected an integer >= 1")
        assert hs is not None and tp is not None and gamma is not None
        from ship_gym.waves.sea_state import steepness_error

        error = steepness_error("irregular", hs, tp, "Hs", "Tp")
        if error is not None:
            raise CampaignError(f"{where} hs_m/tp_s: {error}; expected a lower Hs or longer Tp")
        return SeaSpec(
            "irregular",
            hs,
            period=tp,
            wavelength=None,
            gamma=gamma,
            n_components=n_comp,
            ramp_time=ramp,
            spreading_s=spreading,
        )
    except CampaignError:
        raise
    except ValueError as exc:
        raise CampaignError(f"{where}: {exc}") from None


def _list(doc: dict, key: str, default: list | None = None) -> list:
    if key not in doc:
        if default is None:
            raise CampaignError(f"{key}: missing (required)")
        return default
    value = doc[key]
    if not isinstance(value, list):
        raise CampaignError(f"{key} = {value!r}; expected a list")
    return value


def read_campaign(path: str | os.PathLike[str]) -> CampaignSpec:
    """Read and check a campaign description (schema in the module docstring).

    Every ship is loaded once (a bad name or ship file is reported here, before any work).

    Raises
    ------
    FileNotFoundError
        No such file.
    CampaignError
        Bad TOML, unknown key, bad or missing value: the message starts with the file and names
        the field as written (``[[seas]] #1 hs_m``, ``headings_deg``…).
    """
    path = Path(path)
    if path.is_dir():
        raise CampaignError(f"{path}: is a directory; expected a campaign .toml file")
    if not path.is_file():
        raise FileNotFoundError(f"campaign file {str(path)!r} not found")
    try:
        doc = tomllib.loads(path.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise CampaignError(f"{path}: not a valid TOML file ({exc})") from None
    try:
        unknown = sorted(set(doc) - _TOP_KEYS)
        if unknown:
            raise CampaignError(f"{unknown[0]}: unknown key; expected one of {sorted(_TOP_KEYS)}")
        seas = _list(doc, "seas")
        kw: dict[str, Any] = {
            "ships": _list(doc, "ships"),
            "headings_deg": _list(doc, "headings_deg"),
            "seas": tuple(_sea(s, f"[[seas]] #{i + 1}") for i, s in enumerate(seas)),
            "loadings": tuple(_list(doc, "loadings", [{}])),
            "froude_numbers": tuple(_list(doc, "froude_numbers", [])),
            "speeds_mps": tuple(_list(doc, "speeds_mps", [])),
            "base_dir": path.resolve().parent,
        }
        for key in _SCALAR_KEYS:
            if key in doc:
                kw[key] = doc[key]
        if not isinstance(kw.get("name", ""), str):
            raise CampaignError(f"name = {kw['name']!r}; expected a string")
        spec = CampaignSpec(**kw)
        _check_ships(spec)
    except CampaignError as exc:
        raise CampaignError(f"{path}: {exc}") from None
    return spec


def _check_ships(spec: CampaignSpec) -> None:
    from ship_gym.ship import load_ship

    for ship in spec.ships:
        for i, load in enumerate(spec.loadings):
            try:
                load_ship(spec.resolve_ship(ship), **load)
            except (ValueError, OSError, TypeError) as exc:
                what = f"ships: {ship!r}" if not load else f"ships {ship!r} with loadings[{i}]"
                raise CampaignError(f"{what}: {exc}") from None


# ----------------------------------------------------------------------------- cells, tasks
@dataclass(frozen=True)
class CampaignCell:
    """One run of a campaign.

    Attributes
    ----------
    cell_id : str
        Stable id (module docstring): 20 hex digits.
    ship : str
        Ship as written in the campaign; ``ship_path`` as loaded; ``ship_digest`` its content.
    loading : tuple of (str, object)
        Hull overrides (sorted items).
    sea : SeaSpec
        Sea state.
    heading_deg : float
        Relative wave heading β [deg].
    speed_kind : {"froude", "mps"}
        What ``speed_value`` is: Fn [-] or U [m/s].
    seed : int
        Wave seed.
    """

    cell_id: str
    ship: str
    ship_path: str
    ship_digest: str
    loading: tuple[tuple[str, Any], ...]
    sea: SeaSpec
    heading_deg: float
    speed_kind: str
    speed_value: float
    seed: int

    @property
    def group(self) -> tuple:
        """What the cell shares with the other seeds of its group."""
        return (
            self.ship_digest,
            self.loading,
            self.sea,
            self.heading_deg,
            self.speed_kind,
            self.speed_value,
        )


def _canonical(x: Any) -> Any:
    """Numbers as floats (``10`` and ``10.0`` hash alike), containers recursively."""
    if isinstance(x, bool) or x is None or isinstance(x, str):
        return x
    if isinstance(x, int | float):
        return float(x)
    if isinstance(x, dict):
        return {str(k): _canonical(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_canonical(v) for v in x]
    raise TypeError(f"cannot hash {x!r}")


def _sea_identity(sea: SeaSpec) -> dict:
    d: dict[str, Any] = {"kind": sea.kind, "height": sea.height, "ramp_time": sea.ramp_time}
    if sea.kind == "regular":
        d["wavelength"] = sea.wavelength
        d["period"] = sea.period if sea.wavelength is None else None
    else:
        d.update(period=sea.period, gamma=sea.gamma, n_components=sea.n_components)
        if sea.spreading_s is not None:  # long-crested cells keep the ids they had
            d["spreading_s"] = sea.spreading_s
    return d


def cell_identity(
    spec: CampaignSpec,
    ship_digest: str,
    loading: dict,
    sea: SeaSpec,
    heading_deg: float,
    speed_value: float,
    seed: int,
) -> dict:
    """The canonical content hashed into a cell id (module docstring)."""
    return _canonical(
        {
            "schema": CELL_SCHEMA,
            "ship": ship_digest,
            "loading": dict(loading),
            "sea": _sea_identity(sea),
            "heading_deg": heading_deg,
            "speed": {spec.speed_kind: speed_value},
            "seed": seed,
            "duration_s": spec.duration_s,
            "dt_s": spec.dt_s,
            "integrator": spec.integrator,
            "radiation": spec.radiation,
            "capsize_angle_deg": spec.capsize_angle_deg,
            "controller": spec.controller_identity,
            "record_every": spec.record_every,
            "database": spec.database,
            # only when set: the ids of upright cells stay those of before the option
            **({"initial_heel_deg": spec.initial_heel_deg} if spec.initial_heel_deg else {}),
        }
    )


def _hash(obj: Any, n: int = 20) -> str:
    text = json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:n]


def _ship_digest(path: str) -> str:
    from ship_gym.ship import load_ship

    digest = load_ship(path).description.digest
    return f"sha256:{digest}" if digest else f"library:{path.lower()}"


def cells(spec: CampaignSpec) -> list[CampaignCell]:
    """Every cell of a campaign, in the order ship, loading, sea, heading, speed, seed."""
    out = []
    for ship in spec.ships:
        path = spec.resolve_ship(ship)
        digest = _ship_digest(path)
        for load in spec.loadings:
            items = tuple(sorted(load.items()))
            for sea in spec.seas:
                for heading in spec.headings_deg:
                    for speed in spec.speeds:
                        for seed in range(spec.seeds):
                            ident = cell_identity(spec, digest, load, sea, heading, speed, seed)
                            out.append(
                                CampaignCell(
                                    _hash(ident),
                                    ship,
                                    path,
                                    digest,
                                    items,
                                    sea,
                                    heading,
                                    spec.speed_kind,
                                    speed,
                                    seed,
                                )
                            )
    return out


@dataclass(frozen=True)
class CampaignTask:
    """Seeds of one group run as one engine batch (:func:`run_task`; picklable).

    Attributes
    ----------
    task_id : str
        Hash of the cell ids (names the shard).
    cells : tuple of CampaignCell
        The cells (same group, different seeds).
    duration_s, dt_s, integrator, radiation, capsize_angle_deg, controller, record_every,
    database
        The campaign's run settings (:class:`CampaignSpec`).
    policy_sha256 : str
        For ``controller = "policy:…"``: the SHA-256 of its ``model.zip`` checked in the driver
        (:func:`~ship_gym.analysis.policy_cells.check_policy_controller`); a worker loads only
        that file.
    trust_policy : bool
        The user's opt-in (``--trust-policy``) to load a policy neither trained here nor shipped.
    """

    task_id: str
    cells: tuple[CampaignCell, ...]
    duration_s: float
    dt_s: float
    integrator: str
    radiation: str
    capsize_angle_deg: float | str
    controller: str
    record_every: int
    database: str
    policy_sha256: str = ""
    trust_policy: bool = False
    initial_heel_deg: float = 0.0


def tasks(
    spec: CampaignSpec, pending: Sequence[CampaignCell], *, trust_policy: bool = False
) -> list[CampaignTask]:
    """Group pending cells by all but the seed and cut the groups into ``batch_seeds`` chunks
    (``trust_policy``: the user's opt-in carried to the workers, :class:`CampaignTask`)."""
    groups: dict[tuple, list[CampaignCell]] = {}
    for c in pending:
        groups.setdefault(c.group, []).append(c)
    out = []
    size = spec.batch_seeds
    for members in groups.values():
        for i in range(0, len(members), size):
            chunk = tuple(members[i : i + size])
            out.append(
                CampaignTask(
                    task_id=_hash(sorted(c.cell_id for c in chunk), 16),
                    cells=chunk,
                    duration_s=spec.duration_s,
                    dt_s=spec.dt_s,
                    integrator=spec.integrator,
                    radiation=spec.radiation,
                    capsize_angle_deg=spec.capsize_angle_deg,
                    controller=(
                        spec.controller if spec.policy is None else POLICY_PREFIX + spec.policy.path
                    ),
                    record_every=spec.record_every,
                    database=spec.database,
                    policy_sha256=spec.policy.model_sha256 if spec.policy is not None else "",
                    trust_policy=trust_policy,
                    initial_heel_deg=spec.initial_heel_deg,
                )
            )
    return out


# ----------------------------------------------------------------------------- running
def run_task(task: CampaignTask) -> list[dict]:
    """Run one task (its seeds as one engine batch) and return its store records.

    Top-level and picklable: the executors call it in worker processes or on Ray nodes (which
    need the ship files at the same paths).
    """
    import socket

    from ship_gym.analysis import capsize_map as cm
    from ship_gym.ship import hull_of

    t0 = time.perf_counter()
    first = task.cells[0]
    loading = dict(first.loading)
    with cm.single_threaded_blas():
        if task.capsize_angle_deg == "vanishing":
            angle = cm.capsize_angle_of(first.ship_path, loading)
        else:
            angle = float(task.capsize_angle_deg)
        if first.speed_kind == "froude":
            froude = first.speed_value
        else:
            hull = hull_of(first.ship_path, **loading)
            froude = first.speed_value / math.sqrt(hull.g * hull.particulars.lpp)
        config = cm.CapsizeMapConfig(
            hull=first.ship_path,
            hull_overrides=loading,
            database=task.database,
            headings_deg=(first.heading_deg,),
            froude_numbers=(froude,),
            seas=(first.sea,),
            seeds=tuple(c.seed for c in task.cells),
            duration=task.duration_s,
            dt=task.dt_s,
            integrator=task.integrator,  # type: ignore[arg-type]
            radiation=task.radiation,  # type: ignore[arg-type]
            capsize_angle_deg=angle,
            record_every=task.record_every,
            initial_heel_deg=task.initial_heel_deg,
        )
        if task.controller.startswith(POLICY_PREFIX):
            outs = _run_policy_task(task, first, loading, froude, angle)
        else:
            steered = task.controller == "autopilot"
            outs = cm.run_cells(config, config.cells(), angle, steered=steered)
    wall = (time.perf_counter() - t0) / len(task.cells)
    host = socket.gethostname()
    version = _ship_gym_version()
    records = []
    for cell, out in zip(task.cells, outs, strict=True):
        sea = cell.sea
        records.append(
            {
                "cell_id": cell.cell_id,
                "task_id": task.task_id,
                "ship": cell.ship,
                "ship_digest": cell.ship_digest,
                "loading": json.dumps(dict(cell.loading), sort_keys=True),
                "sea": sea.label,
                "sea_kind": sea.kind,
                "sea_height_m": sea.height,
                "sea_wavelength_m": sea.wavelength,
                "sea_period_s": sea.period,
                "sea_gamma": sea.gamma if sea.kind == "irregular" else None,
                "sea_spreading_s": sea.spreading_s,
                "heading_deg": cell.heading_deg,
                "speed_kind": cell.speed_kind,
                "speed_value": cell.speed_value,
                "seed": cell.seed,
                "duration_s": task.duration_s,
                "dt_s": task.dt_s,
                "integrator": task.integrator,
                "radiation": task.radiation,
                "controller": task.controller,
                "capsize_criterion": str(task.capsize_angle_deg),
                "capsize_angle_deg": angle,
                "capsized": bool(out["capsized"]),
                "reason": out["reason"],
                "time_to_capsize_s": out["time_to_capsize"],
                "max_abs_roll_deg": out["max_abs_roll_deg"],
                "rms_roll_deg": out["rms_roll_deg"],
                "max_abs_pitch_deg": out["max_abs_pitch_deg"],
                "max_heading_deviation_deg": out["max_heading_deviation_deg"],
                "mean_speed_mps": out["mean_speed"],
                "simulated_time_s": out["simulated_time"],
                "speed_mps": out["speed"],
                "cpu_s": out["cpu_s"],
                "wall_s": wall,
                "engine": out["engine"],
                "batch_size": int(out["batch_size"]),
                "host": host,
                "ship_gym_version": version,
            }
        )
    return records


def _run_policy_task(
    task: CampaignTask, first: CampaignCell, loading: dict, froude: float, angle: float
) -> list[dict]:
    """The seeds of a task under its trained policy (:mod:`ship_gym.analysis.policy_cells`)."""
    import torch

    from ship_gym.analysis.policy_cells import read_policy_controller, run_policy_cells
    from ship_gym.ship import hull_of

    torch.set_num_threads(1)
    controller = read_policy_controller(
        task.controller[len(POLICY_PREFIX) :], field=f"controller = {task.controller!r}"
    )
    # the file the driver checked, not whatever is there now
    controller = replace(controller, model_sha256=task.policy_sha256)
    hull = hull_of(first.ship_path, **loading)
    return run_policy_cells(
        controller,
        ship=first.ship_path,
        loading=loading,
        sea=first.sea,
        heading_deg=first.heading_deg,
        speed_mps=froude * math.sqrt(hull.g * hull.particulars.lpp),
        seeds=[c.seed for c in task.cells],
        duration_s=task.duration_s,
        dt_s=task.dt_s,
        integrator=task.integrator,
        capsize_angle_deg=angle,
        trusted=task.trust_policy,
    )


def _ship_gym_version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("ship_gym")
    except PackageNotFoundError:  # pragma: no cover - a source tree without metadata
        return "unknown"


def make_campaign_executor(kind: str, *, workers: int = 1, address: str | None = None) -> Executor:
    """An executor of :mod:`ship_gym.analysis.executors`, the arguments checked first.

    Raises
    ------
    ValueError
        Unknown kind or workers < 1.
    ImportError
        Ray is not installed (``"ray"``).
    """
    if kind not in ("serial", "processes", "ray"):
        raise ValueError(f"executor must be 'serial', 'processes' or 'ray', got {kind!r}")
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers must be an integer >= 1, got {workers!r}")
    from ship_gym.analysis.executors import make_executor

    return make_executor(kind, workers=workers, address=address)  # type: ignore[arg-type]


@dataclass(frozen=True)
class CampaignResult:
    """What :func:`run_campaign` did.

    Attributes
    ----------
    spec : CampaignSpec
        The campaign.
    store : Path
        Its store folder.
    records : list of dict
        The records of the campaign's cells (in :func:`cells` order; other cells of the store
        left out).
    n_cells : int
        Cells of the campaign.
    n_run : int
        Cells simulated by this call (the others were in the store).
    n_tasks : int
        Tasks run by this call.
    wall_s : float
        Wall time of the call [s].
    """

    spec: CampaignSpec
    store: Path
    records: list[dict]
    n_cells: int
    n_run: int
    n_tasks: int
    wall_s: float


def campaign_records(
    spec: CampaignSpec, store: str | Path, *, report: Callable[[str], None] | None = None
) -> tuple[list[dict], int]:
    """The store's records of the campaign's cells (in :func:`cells` order) and the number of
    cells still missing (``report``: told of shards the store's manifest does not vouch for,
    :func:`~ship_gym.analysis.campaign_store.read_store`)."""
    from ship_gym.analysis.campaign_store import read_store

    order = {c.cell_id: i for i, c in enumerate(cells(spec))}
    records = [r for r in read_store(store, report=report) if r["cell_id"] in order]
    records.sort(key=lambda r: order[r["cell_id"]])
    return records, len(order) - len(records)


def describe_task(task: CampaignTask) -> str:
    """A task as a user reads it: ship, loading, sea, heading, speed and seeds of its cells."""
    c = task.cells[0]
    seeds = [cell.seed for cell in task.cells]
    loading = ", ".join(f"{k} = {v!r}" for k, v in c.loading) or "nominal loading"
    return (
        f"task {task.task_id} (ship {c.ship}, {loading}, sea {c.sea.label}, heading "
        f"{c.heading_deg:g} deg, {c.speed_kind} {c.speed_value:g}, seeds {seeds})"
    )


def _to_stderr(message: str) -> None:
    print(message, file=sys.stderr, flush=True)


def run_campaign(
    spec: CampaignSpec,
    store_dir: str | Path,
    *,
    executor: str | Executor = "serial",
    workers: int = 1,
    address: str | None = None,
    progress: bool = True,
    trust_policy: bool = False,
    report: Callable[[str], None] | None = None,
) -> CampaignResult:
    """Run (or resume, or extend) a campaign into a store folder.

    A ``controller = "policy:…"`` is checked first: a model neither trained by this
    installation nor shipped is refused unless ``trust_policy`` (loading an SB3 model runs code
    from the file; :func:`~ship_gym.analysis.policy_cells.check_policy_controller`), and every
    worker loads only the file of the SHA-256 checked here.

    Cells already in the store (by id) are skipped; the others are grouped into tasks
    (:func:`tasks`) and run by the executor, every finished task written as one shard
    (:func:`~ship_gym.analysis.campaign_store.write_shard`) as it comes back.

    Parameters
    ----------
    spec : CampaignSpec
        The campaign.
    store_dir : str or Path
        Store folder (created if missing).
    executor : {"serial", "processes", "ray"} or Executor
        Where tasks run (:func:`make_campaign_executor`), or an executor object (not closed
        here).
    workers : int
        Parallel workers (``"processes"``, ``"ray"``).
    address : str, optional
        Ray cluster address (``"ray"``).
    progress : bool
        tqdm progress bar over cells.
    trust_policy : bool
        The user's opt-in to load a policy neither trained here nor shipped.
    report : callable, optional
        Told (one line each) when a local worker process died and its task is run again
        (:class:`~ship_gym.analysis.executors.ProcessExecutor`; default: printed on stderr).

    Raises
    ------
    CampaignError
        A task whose worker died more often than the executor retries, naming its cells.
    """
    from ship_gym.analysis.campaign_store import (
        _pyarrow,
        campaign_digest,
        record_campaign,
        store_cell_ids,
        write_shard,
    )

    _pyarrow()  # fail before any work when pyarrow is missing
    t0 = time.perf_counter()
    say = report if report is not None else _to_stderr
    store = Path(store_dir)
    store.mkdir(parents=True, exist_ok=True)
    all_cells = cells(spec)
    digest = campaign_digest(c.cell_id for c in all_cells)
    record_campaign(store, digest, spec.name)
    done = store_cell_ids(store, report=say)
    pending = [c for c in all_cells if c.cell_id not in done]
    if spec.policy is not None and pending:
        from ship_gym.analysis.policy_cells import check_policy_controller

        try:
            check_policy_controller(spec.policy, trusted=trust_policy)
        except ValueError as exc:
            raise CampaignError(f"controller = {spec.controller!r}: {exc}") from None
    todo = tasks(spec, pending, trust_policy=trust_policy)
    own = isinstance(executor, str)
    ex: Executor = (
        make_campaign_executor(executor, workers=workers, address=address)
        if isinstance(executor, str)
        else executor
    )
    bar = None
    if progress and pending:
        from tqdm import tqdm

        bar = tqdm(total=len(pending), desc=spec.name or "campaign", unit="cell")
    lost: list[str] = []
    if isinstance(ex, ProcessExecutor) and ex.on_retry is None:

        def retry(index: int, attempt: int) -> None:
            lost.append(todo[index].task_id)
            say(
                f"campaign: a worker process died running {describe_task(todo[index])}; "
                f"running it again (attempt {attempt} of {ex.max_retries + 1})"
            )

        ex.on_retry = retry
    try:
        if todo:
            try:
                for i, records in ex.map_unordered(run_task, todo):
                    write_shard(store, todo[i].task_id, records, campaign=digest)
                    if bar is not None:
                        bar.update(len(records))
            except WorkerLostError as exc:
                raise CampaignError(
                    f"{describe_task(todo[exc.index])}: its worker process died {exc.attempts} "
                    "times (killed by a signal or out of memory); the finished tasks are kept in "
                    f"{store}: rerun to resume, with fewer --workers if memory ran out"
                ) from None
        if lost:
            say(
                f"campaign: {len(lost)} task(s) lost a worker process and were run again "
                f"({', '.join(sorted(set(lost)))}); every cell finished"
            )
    finally:
        if bar is not None:
            bar.close()
        if own:
            ex.close()
    records, _ = campaign_records(spec, store, report=lambda message: None)  # said above
    return CampaignResult(
        spec=spec,
        store=store,
        records=records,
        n_cells=len(all_cells),
        n_run=len(pending),
        n_tasks=len(todo),
        wall_s=time.perf_counter() - t0,
    )
