"""The shared keyword arguments of the ship environments, written once: :class:`ShipConfig`.

Every ship environment takes the same ≈ 20 keyword arguments (the ship, its speed, the sea, the
loading, the numerics, the capsize and safety settings, the sensors). :class:`ShipConfig` is
their single source: one frozen dataclass whose fields carry the default, the unit, the meaning
and the accepted limits (:func:`argument`). From it come

* the rows of the environments' ``## Arguments`` docstring tables
  (:data:`ship_gym.envs.docstrings.SHIP_ARGUMENTS`);
* the limits the task layer checks the values against (:data:`SPEED_LIMITS`,
  :data:`GM_LIMITS`, … are read from the fields);
* the keyword arguments of a task written the small way
  (:class:`ship_gym.envs.env_task.ConfigShipTask`: ``**config`` is a ShipConfig, its defaults
  the task's :attr:`~ship_gym.envs.env_task.ConfigShipTask.defaults`).

The environment classes keep flat keyword arguments (``gymnasium.make(id, hs_range_m=...)``).
"""

from __future__ import annotations

# ruff: noqa: RUF009  (the fields are made by argument(), a dataclasses.field with metadata)
import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from ship_gym.typing import ForwardSpeedModel, IntegratorName, Precision

__all__ = [
    "CAPSIZE_ANGLE_LIMITS",
    "GM_LIMITS",
    "SHIP_FIELDS",
    "SPEED_LIMITS",
    "Argument",
    "ShipConfig",
    "argument",
    "config_arguments",
]


@dataclass(frozen=True)
class Argument:
    """Unit, meaning and accepted limits of a keyword argument.

    Attributes
    ----------
    unit : str
        Unit (``"m/s"``, ``"-"``).
    meaning : str
        One line for the docstring table.
    limits : tuple of float or None
        Accepted (low, high) of a number or of both ends of a range [unit]; None: not a number.
    """

    unit: str
    meaning: str
    limits: tuple[float, float] | None = None


def argument(
    default: Any, unit: str, meaning: str, limits: tuple[float, float] | None = None
) -> Any:
    """A :class:`ShipConfig` field: its default and its :class:`Argument` (in the metadata)."""
    return field(default=default, metadata={"argument": Argument(unit, meaning, limits)})


S175_MESH_DEFAULT: tuple[int, int, int, int] = (60, 12, 6, 4)
"""The S175's default mesh (:data:`ship_gym.envs.env_task.S175_MESH` is this)."""


@dataclass(frozen=True)
class ShipConfig:
    """The shared keyword arguments of the ship environments (module docstring).

    Each field's default is the common one (an environment sets its own with
    :func:`dataclasses.replace`); its unit, meaning and limits are in :func:`config_arguments`.
    The values are checked where they are used (:func:`~ship_gym.envs.env_task.task_setup`,
    :class:`~ship_gym.envs.ship_task.ShipTask`, :class:`~ship_gym.envs.seas.SeaSampler`,
    :class:`~ship_gym.envs.episodes.EpisodeSampler`), against these limits, with errors naming
    the keyword.
    """

    ship: str = argument(
        "s175", "-", "bundled ship name or ship file (.toml; ship-gym ship check FILE)"
    )
    froude_number: float = argument(
        0.25, "-", "reference speed U = Fn √(g L) (radiation, diffraction, propeller)", (0.05, 0.5)
    )
    speed_range_mps: tuple[float, float] | None = argument(
        None, "m/s", "initial speed range (self-propulsion rpm); keep near U", (0.1, 30.0)
    )
    hs_range_m: tuple[float, float] = argument(
        (3.0, 5.0), "m", "significant wave height range", (0.0, 30.0)
    )
    tp_range_s: tuple[float, float] = argument((9.0, 12.0), "s", "peak period range", (1.0, 40.0))
    wave_heading_range_deg: tuple[float, float] = argument(
        (0.0, 360.0), "deg", "relative wave heading β (0 following, 180 head seas)", (-360.0, 720.0)
    )
    n_wave_components: int = argument(40, "-", "components of the irregular sea")
    wave_spreading_s: float | None = argument(
        None, "-", "cos-2s spreading exponent (None: long-crested)"
    )
    wave_ramp_time_s: float = argument(
        30.0, "s", "start-up ramp of the waves (Matusiak 2003, eq. 12)"
    )
    gm_range_m: tuple[float, float] | None = argument(
        None, "m", "GM range of the loading (per episode; None: nominal)", (0.05, 10.0)
    )
    kg_m: float | None = argument(
        None, "m", "KG of the nominal loading (None: the ship's; S175 9.55 m)"
    )
    physics_dt_s: float = argument(0.1, "s", "physics time step", (0.01, 0.5))
    control_dt_s: float = argument(0.5, "s", "control step (integer multiple of physics_dt_s)")
    integrator: IntegratorName = argument(
        "holloway", "-", '"holloway" (1 force evaluation/step) or "rk4" (4)'
    )
    hull_mesh: tuple[int, int, int, int] = argument(
        S175_MESH_DEFAULT, "-", "offsets-hull mesh (sections, panels below/above water, deck)"
    )
    precision: Precision = argument(
        "float32", "-", '"float32" or "float64" wave sums of the Froude–Krylov kernel'
    )
    forward_speed_model: ForwardSpeedModel = argument(
        "relative_motion",
        "-",
        '"relative_motion" (speed terms on the motion relative to the waves) or '
        '"radiation_only" (the -v2 model)',
    )
    num_threads: int = argument(
        1, "-", "numba threads over the batch's ships (1: serial)", (1, 1024)
    )
    wind_speed_mps: float = argument(
        0.0, "m/s", "constant mean wind speed on the ship's windage (0: none)", (0.0, 80.0)
    )
    wind_from_deg: float = argument(
        0.0,
        "deg",
        "earth direction the wind blows from (0: north, ahead at the start)",
        (-360.0, 360.0),
    )
    capsize_angle_deg: float | None = argument(
        None, "deg", "capsize roll angle (None: vanishing angle of the loading)", (0.0, 180.0)
    )
    dangerous_roll_deg: float = argument(25.0, "deg", "roll angle of the Safe-RL cost", (0.0, 90.0))
    capsize_penalty: float = argument(100.0, "-", "penalty paid at capsize")
    sensor_noise: float = argument(
        0.0, "-", "multiplier of the sensor accuracies (SENSOR_NOISE_STD)", (0.0, 100.0)
    )
    wave_preview_m: tuple[float, ...] | tuple[tuple[float, float], ...] = argument(
        (), "m", "elevation preview: distances ahead of O, or (x, y) body-frame points"
    )

    def replace(self, **changes: Any) -> ShipConfig:
        """A copy with ``changes`` (ValueError naming an unknown keyword)."""
        unknown = sorted(set(changes) - set(SHIP_FIELDS))
        if unknown:
            raise ValueError(
                f"unknown keyword argument(s) {unknown}; the shared ones are {list(SHIP_FIELDS)}"
            )
        return dataclasses.replace(self, **changes)

    def values(self, names: Sequence[str] | None = None) -> dict[str, Any]:
        """The fields ``names`` (all by default) as keyword arguments."""
        return {name: getattr(self, name) for name in (names or SHIP_FIELDS)}


SHIP_FIELDS: tuple[str, ...] = tuple(f.name for f in dataclasses.fields(ShipConfig))
"""The names of the shared keyword arguments, in the order of :class:`ShipConfig`."""


def config_arguments() -> dict[str, Argument]:
    """Name → :class:`Argument` (unit, meaning, limits) of every :class:`ShipConfig` field."""
    return {f.name: f.metadata["argument"] for f in dataclasses.fields(ShipConfig)}


def _limits(name: str) -> tuple[float, float]:
    limits = config_arguments()[name].limits
    assert limits is not None
    return limits


SPEED_LIMITS: tuple[float, float] = _limits("speed_range_mps")
"""Accepted initial speeds [m/s] (``speed_range_mps``, ``reset(options={"initial_speed_mps"})``)."""

GM_LIMITS: tuple[float, float] = _limits("gm_range_m")
"""Accepted GM of an episode's loading [m] (``gm_range_m``, ``reset(options={"gm_m"})``)."""

CAPSIZE_ANGLE_LIMITS: tuple[float, float] = _limits("capsize_angle_deg")
"""Accepted fixed capsize angle [deg] (open below)."""

FROUDE_LIMITS: tuple[float, float] = _limits("froude_number")
"""Accepted reference Froude numbers [-]."""

PHYSICS_DT_LIMITS: tuple[float, float] = _limits("physics_dt_s")
"""Accepted physics time steps [s]."""

DANGEROUS_ROLL_LIMITS: tuple[float, float] = _limits("dangerous_roll_deg")
"""Accepted dangerous roll angles [deg] (open at both ends)."""

SENSOR_NOISE_LIMITS: tuple[float, float] = _limits("sensor_noise")
"""Accepted sensor-noise multipliers [-]."""


def documented_rows(
    extra: Mapping[str, tuple[str, str]] | None = None,
) -> dict[str, tuple[str, str]]:
    """Name → (unit, meaning) of the :class:`ShipConfig` fields, then ``extra``."""
    rows = {name: (a.unit, a.meaning) for name, a in config_arguments().items()}
    return {**rows, **(extra or {})}
