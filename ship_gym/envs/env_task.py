"""The ship tasks' set-up: S175 mesh presets, the :class:`~ship_gym.engine.ship.ShipSetup` of a
task (:func:`task_setup`, any ship: the S175 by default, a bundled ship or a ship file) and
:class:`ShipEnvTask`, the ship task built from the keyword arguments every ship environment
shares.
"""

from __future__ import annotations

import abc
import dataclasses
import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np
from numpy.typing import NDArray

from ship_gym.conventions import GRAVITY
from ship_gym.envs.config import FROUDE_LIMITS, PHYSICS_DT_LIMITS, SHIP_FIELDS, ShipConfig
from ship_gym.envs.observations import Observation
from ship_gym.envs.seas import SeaSampler
from ship_gym.envs.ship_task import ShipTask, StepStatistics
from ship_gym.envs.validation import check_real
from ship_gym.typing import ForwardSpeedModel, IntegratorName, Precision

if TYPE_CHECKING:
    from ship_gym.engine.ship import ShipSetup


S175_MESH: tuple[int, int, int, int] = ShipConfig.hull_mesh
"""Default S175 mesh resolution (n_sections, n_below, n_above, n_deck): 2400 panels, the
library hull's. Against a 9600-panel mesh (``docs/accuracy/results.md``): GZ within 2.4 mm, roll
period −0.28 %, RMS roll +2.8 % in a stern-quartering sea near roll resonance."""

S175_MESH_FAST: tuple[int, int, int, int] = (50, 10, 4, 2)
"""The fastest mesh the accuracy study admits: 1500 panels, faster than :data:`S175_MESH`
(``docs/benchmarks.md``); GZ within 4.2 mm and roll period −0.43 %, but RMS roll +4.5 % near roll
resonance (``docs/accuracy/results.md``)."""

S175_MESH_FINE: tuple[int, int, int, int] = (90, 18, 9, 6)
"""5400 panels: RMS motions within 0.3 % of a 9600-panel mesh, at a higher cost than
:data:`S175_MESH` (``docs/accuracy/results.md``; timings in ``docs/benchmarks.md``)."""

RUDDER_LIMIT_DEG = 35.0
"""Rudder angle limit of the servo [deg] (:data:`ship_gym.control.actuators.RUDDER_SERVO`)."""


MIN_GM_M = 0.05
"""Smallest GM [m] of a loading the ship tasks accept (``kg_m``, ``gm_range_m``, ``gm_m``): the
upright ship must be stable (positive restoring, a roll natural frequency)."""


def _metacentre_height(ship: str, mesh_overrides: tuple[tuple[str, Any], ...]) -> float:
    """KM = KG + GM [m] of the upright ship at its design loading on a mesh (independent of KG:
    KB + BM), from the cached loading condition."""
    from ship_gym.engine.ship import ShipSetup
    from ship_gym.envs.loading import loading_condition

    lc = loading_condition(ShipSetup(hull=ship, hull_overrides=dict(mesh_overrides)))
    return lc.kg + lc.gm


def check_ship(value: Any) -> str:
    """The ``ship`` argument of an environment: a bundled ship name or a ship-file path,
    checked (and the ship loaded, so that a bad file fails here, naming ``ship``)."""
    import os

    from ship_gym.ship import load_ship

    if not isinstance(value, str | os.PathLike) or not os.fspath(value):
        raise ValueError(
            f"ship must be a bundled ship name (e.g. 's175') or a ship file path (.toml), "
            f"got {value!r}"
        )
    text = os.fspath(value)
    try:
        load_ship(text)
    except (ValueError, FileNotFoundError) as exc:
        raise type(exc)(f"ship = {text!r}: {exc}") from None
    return text


def ship_particulars(ship: str) -> Any:
    """Main particulars (:class:`ship_gym.hull.hull.Particulars`) of an environment's ``ship``
    (checked by :func:`check_ship`), for the defaults that scale with the ship."""
    from ship_gym.ship import load_ship

    return load_ship(check_ship(ship)).hull.particulars


def point_scaled_from_s175(ship: str, point: Sequence[float]) -> tuple[float, float, float]:
    """A body-frame point [m] chosen on the S175, moved to ``ship`` in proportion to its
    length, beam and draught (x/175 · L, y/25.4 · B, z/9.5 · T): the default passenger points."""
    p = ship_particulars(ship)
    x, y, z = (float(v) for v in point)
    return (x / 175.0 * p.lpp, y / 25.4 * p.beam, z / 9.5 * p.draught)


def task_setup(
    *,
    ship: str = "s175",
    froude_number: float,
    physics_dt: float,
    integrator: IntegratorName,
    rudder: Literal["command", "autopilot"],
    hull_mesh: Sequence[int],
    kg: float | None,
    precision: Precision = "float32",
    forward_speed_model: ForwardSpeedModel = "relative_motion",
    wind: tuple[float, float] | None = None,
) -> ShipSetup:
    """The setup of the ship tasks: state-space radiation memory, diffraction, Ikeda roll
    damping, propulsion (Holtrop resistance + B-series propeller), manoeuvring forces and a
    rudder behind its servo (commanded, or under the heading autopilot).

    Parameters
    ----------
    ship : str
        Bundled ship name or ship file (:func:`ship_gym.ship.load_ship`); default the S175.
    froude_number : float
        Reference Froude number Fn = U/√(g Lpp) [-] (0.05 … 0.5).
    physics_dt : float
        Physics time step [s] (0.01 … 0.5).
    integrator : {"holloway", "rk4"}
        Holloway's μ-Taylor scheme (1 force evaluation per step) or RK4 (4).
    rudder : {"command", "autopilot"}
        Rudder following ``"rudder_command"`` or the PID heading autopilot (``"heading"``).
    hull_mesh : sequence of 4 int
        Mesh (n_sections, n_below, n_above, n_deck) of a hull built from offsets (the S175 and
        ``[hull] offsets`` ships); :data:`S175_MESH` is the default (the file's own mesh).
    kg : float or None
        KG of the loading [m] (None: the ship's; the S175's 9.55 m, GM ≈ 1.0 m).
    precision : {"float32", "float64"}
        Wave sums of the Froude–Krylov kernel (``fk_method`` "fast32" or "fast").
    forward_speed_model : {"relative_motion", "radiation_only"}
        The speed terms on the motion relative to the incident flow (default), or on the
        radiated momentum only, without the moment's high-pass (the ``-v2`` environments;
        :data:`FORWARD_SPEED_MODELS`).
    wind : (float, float) or None
        A constant mean wind (V_w [m/s], χ_w [rad] it blows from) (:attr:`ShipSetup.wind`).
    """
    from ship_gym.engine.ship import ShipSetup
    from ship_gym.ship import load_ship

    ship = check_ship(ship)
    described = load_ship(ship)
    low, high = FROUDE_LIMITS
    froude_number = check_real("froude_number", froude_number, low=low, high=high, unit="-")
    low, high = PHYSICS_DT_LIMITS
    physics_dt = check_real("physics_dt_s", physics_dt, low=low, high=high, unit="s")
    if integrator not in ("holloway", "rk4"):
        raise ValueError(f"integrator must be 'holloway' or 'rk4', got {integrator!r}")
    if precision not in ("float32", "float64"):
        raise ValueError(f"precision must be 'float32' or 'float64', got {precision!r}")
    mesh = tuple(hull_mesh) if isinstance(hull_mesh, Sequence) else ()
    if len(mesh) != 4 or not all(
        isinstance(v, int | np.integer) and not isinstance(v, bool) and v >= 2 for v in mesh
    ):
        raise ValueError(
            f"hull_mesh must be 4 integers >= 2 (n_sections, n_below, n_above, n_deck), "
            f"got {hull_mesh!r}"
        )
    overrides: dict[str, Any] = {}
    geometry = described.description.hull
    meshed_from_offsets = geometry.library == "s175" or geometry.kind == "offsets"
    if mesh != S175_MESH and not meshed_from_offsets:
        raise ValueError(
            f"hull_mesh = {hull_mesh!r} applies to hulls built from offsets (the S175, "
            f"[hull] offsets ships); ship {ship!r} has a {geometry.kind} hull: leave hull_mesh "
            "at its default"
        )
    if mesh != S175_MESH:  # the library hull's own mesh
        overrides.update(
            n_sections=int(mesh[0]),
            n_below=int(mesh[1]),
            n_above=int(mesh[2]),
            n_deck=int(mesh[3]),
        )
    if kg is not None:
        depth = described.hull.particulars.depth
        kg = check_real(
            "kg_m", kg, low=0.0, high=depth, unit="m", why=f" (ship {ship!r}: depth {depth:g} m)"
        )
        km = _metacentre_height(ship, tuple(sorted(overrides.items())))
        if kg > km - MIN_GM_M:
            raise ValueError(
                f"kg_m = {kg!r} m leaves GM = KM - KG = {km - kg:.3f} m: the upright ship "
                f"needs GM >= {MIN_GM_M} m, i.e. kg_m <= {km - MIN_GM_M:.3f} m (KM = {km:.3f} m "
                f"on this hull_mesh)"
            )
        overrides["kg"] = float(kg)
    speed = float(froude_number) * math.sqrt(GRAVITY * described.hull.particulars.lpp)
    return ShipSetup(
        hull=ship,
        hull_overrides=overrides,
        database="auto",
        speed=speed,
        radiation="state_space",
        diffraction=True,
        viscous_roll=True,
        integrator=integrator,
        dt=float(physics_dt),
        propulsion=True,
        manoeuvring=True,
        rudder=rudder,
        fk_method="fast32" if precision == "float32" else "fast",
        wind=wind,
        **forward_speed_fields(forward_speed_model),
    )


FORWARD_SPEED_MODELS: dict[str, dict[str, Any]] = {
    "relative_motion": {},
    "radiation_only": {"speed_cutoff": 0.0, "diffraction_speed_terms": False},
}
"""The :class:`~ship_gym.engine.ship.ShipSetup` fields of each forward-speed model."""


def forward_speed_fields(model: str) -> dict[str, Any]:
    """The ShipSetup fields of ``forward_speed_model`` (a ValueError naming it otherwise)."""
    if model not in FORWARD_SPEED_MODELS:
        raise ValueError(
            f"forward_speed_model={model!r}; expected one of {tuple(FORWARD_SPEED_MODELS)}"
        )
    return dict(FORWARD_SPEED_MODELS[model])


# =============================================================================================
# the S175 task built from the environments' shared keyword arguments
# =============================================================================================
SEA_KWARGS: tuple[str, ...] = (
    "hs_range_m",
    "tp_range_s",
    "wave_heading_range_deg",
    "n_wave_components",
    "wave_spreading_s",
    "wave_ramp_time_s",
)
"""The :class:`~ship_gym.envs.config.ShipConfig` fields of the irregular sea
(:func:`irregular_sea`)."""

SHIP_KWARGS: tuple[str, ...] = tuple(name for name in SHIP_FIELDS if name not in SEA_KWARGS)
"""The environment keyword arguments :class:`ShipEnvTask` takes as they are
(:func:`ship_kwargs`): the :class:`~ship_gym.envs.config.ShipConfig` fields but the sea's."""


def ship_kwargs(values: Mapping[str, Any]) -> dict[str, Any]:
    """The :data:`SHIP_KWARGS` among an environment task's arguments (its ``locals()``).

    Every ship environment task declares its keyword arguments explicitly (typed, with units,
    with its own defaults) and forwards the shared ones to :class:`ShipEnvTask` by name with this.
    """
    return {key: values[key] for key in SHIP_KWARGS if key in values}


def irregular_sea(values: Mapping[str, Any]) -> SeaSampler:
    """The JONSWAP :class:`SeaSampler` of an environment task's irregular-sea arguments
    ``hs_range_m``, ``tp_range_s``, ``wave_heading_range_deg``, ``n_wave_components``,
    ``wave_spreading_s`` and ``wave_ramp_time_s`` (in ``values``, its ``locals()``)."""
    return SeaSampler(
        kind="irregular",
        height_range=values["hs_range_m"],
        period_range=values["tp_range_s"],
        heading_range_deg=values["wave_heading_range_deg"],
        n_components=values["n_wave_components"],
        spreading_s=values["wave_spreading_s"],
        ramp_time=values["wave_ramp_time_s"],
        keywords=(
            "hs_range_m",
            "tp_range_s",
            "wave_heading_range_deg",
            "n_wave_components",
            "gamma",
            "wave_spreading_s",
            "wave_ramp_time_s",
        ),
    )


class ShipEnvTask(ShipTask, abc.ABC):
    """A :class:`ShipTask` of a ship (:func:`task_setup`) from the shared environment
    keyword arguments (:data:`SHIP_ARGUMENTS` for their meaning and units).

    Parameters
    ----------
    num_envs : int
        Number of episodes N.
    rudder : {"command", "autopilot"}
        Rudder following ``"rudder_command"`` or the PID heading autopilot.
    sea : SeaSampler
        Per-episode sea.
    ship, froude_number, physics_dt_s, integrator, hull_mesh, kg_m, precision
        :func:`task_setup` arguments (ship, Fn [-], dt [s], scheme, mesh, KG [m], wave sums).
    forward_speed_model : {"relative_motion", "radiation_only"}
        :func:`task_setup`'s forward-speed model.
    wind_speed_mps, wind_from_deg : float
        A constant mean wind V_w [m/s] from the earth direction χ_w [deg] (0: from the north,
        ahead of the ship at its start) on the ship's windage (``[wind]`` of its ship file;
        :class:`ship_gym.forces.wind.MeanWind`); 0 m/s: none.
    num_threads : int
        numba threads over the ships in the compiled loop (1: serial).
    control_dt_s : float
        Control step [s], an integer multiple of ``physics_dt_s``.
    speed_range_mps : tuple of float or None
        Initial speed range [m/s] (None: the reference speed).
    gm_range_m : tuple of float or None
        GM range [m] of the episodes' loading (None: nominal).
    capsize_angle_deg, dangerous_roll_deg, capsize_penalty, sensor_noise, wave_preview_m
        :class:`ShipTask` arguments.
    setup_changes : mapping, optional
        :class:`ship_gym.engine.ship.ShipSetup` fields replaced after :func:`task_setup`
        (e.g. ``{"fins": "command"}``).
    extra_observations : sequence of Observation or of (name, low, high)
        The subclass's observation entries (:class:`ShipTask`).
    """

    def __init__(
        self,
        num_envs: int,
        *,
        rudder: Literal["command", "autopilot"],
        sea: SeaSampler,
        froude_number: float,
        physics_dt_s: float,
        control_dt_s: float,
        integrator: IntegratorName,
        hull_mesh: Sequence[int],
        capsize_angle_deg: float | None,
        dangerous_roll_deg: float,
        precision: Precision = "float32",
        num_threads: int = 1,
        capsize_penalty: float,
        sensor_noise: float,
        wave_preview_m: Sequence[float] | Sequence[Sequence[float]],
        kg_m: float | None = None,
        speed_range_mps: tuple[float, float] | None = None,
        gm_range_m: tuple[float, float] | None = None,
        setup_changes: Mapping[str, Any] | None = None,
        extra_observations: Sequence[tuple[str, float, float] | Observation] = (),
        ship: str = "s175",
        forward_speed_model: ForwardSpeedModel = "relative_motion",
        wind_speed_mps: float = 0.0,
        wind_from_deg: float = 0.0,
    ) -> None:
        wind_speed = check_real("wind_speed_mps", wind_speed_mps, low=0.0, high=80.0, unit="m/s")
        wind_from = check_real("wind_from_deg", wind_from_deg, low=-360.0, high=360.0, unit="deg")
        setup = task_setup(
            ship=ship,
            froude_number=froude_number,
            physics_dt=physics_dt_s,
            integrator=integrator,
            rudder=rudder,
            hull_mesh=hull_mesh,
            kg=kg_m,
            precision=precision,
            forward_speed_model=forward_speed_model,
            wind=(wind_speed, math.radians(wind_from)) if wind_speed > 0.0 else None,
        )
        if not (
            isinstance(num_threads, int | np.integer)
            and not isinstance(num_threads, bool)
            and 1 <= num_threads <= 1024
        ):
            raise ValueError(f"num_threads must be an integer in [1, 1024], got {num_threads!r}")
        self.num_threads = int(num_threads)
        if setup_changes:
            setup = dataclasses.replace(setup, **setup_changes)
        super().__init__(
            num_envs,
            setup=setup,
            sea=sea,
            control_dt=control_dt_s,
            speed_range=speed_range_mps,
            gm_range=gm_range_m,
            capsize_angle_deg=capsize_angle_deg,
            dangerous_roll_deg=dangerous_roll_deg,
            sensor_noise=sensor_noise,
            wave_preview_m=wave_preview_m,
            extra_observations=extra_observations,
            capsize_penalty=capsize_penalty,
        )
        self.sim.parallel = num_threads > 1

    def nominal_roll_period(self) -> float:
        """Undamped roll natural period T_R = 2π/ω_φ [s] of the nominal loading (its own
        stiffness and inertia, A44 at ω_φ: :func:`ship_gym.engine.ship.roll_natural_frequency`)."""
        from ship_gym.engine.ship import database_of, roll_natural_frequency

        return 2.0 * math.pi / roll_natural_frequency(self.sim.hull, database_of(self.setup))

    # ------------------------------------------------------------------ shared reward terms
    def roll_term(self, stats: StepStatistics, weight: float, scale: float) -> NDArray:
        """−weight · mean(φ²)/scale² over the physics steps of the control step (scale [rad])."""
        return -weight * stats.mean_square_roll / scale**2

    def heading_term(self, weight: float, scale: float) -> NDArray:
        """−weight · (e/scale)², e the wrapped heading error (scale [rad])."""
        return -weight * (self._current_heading_error() / scale) ** 2


# =============================================================================================
# a task written the small way: the config, the observation table and two hooks
# =============================================================================================
class ConfigShipTask(ShipEnvTask, abc.ABC):
    """A ship task declared in a few lines: its shared keyword arguments are a
    :class:`~ship_gym.envs.config.ShipConfig`, its observations a table of
    :class:`~ship_gym.envs.observations.Observation` with getters.

    A subclass sets the class attributes below, takes its own keyword arguments explicitly
    (typed, with units) and the shared ones as ``**config``, and implements
    :meth:`~ShipTask._apply_actions` and :meth:`~ShipTask._reward_terms` (the other hooks of
    :class:`~ship_gym.envs.ship_task.ShipTask` stay available). The ``## Arguments`` table of
    its environment lists ``**config`` as the ShipConfig fields with :attr:`defaults`
    (:func:`ship_gym.envs.docstrings.arguments_table`). ``docs/tutorials/your_own_task.md``
    writes one.

    Class attributes
    ----------------
    defaults : ShipConfig
        The task's defaults of the shared keyword arguments (the sea included: an irregular
        JONSWAP sea from the ``hs_range_m`` … ``wave_ramp_time_s`` fields; override
        :meth:`make_sea` for another).
    steering : {"autopilot", "command"}
        The rudder under the heading autopilot, or following ``commands["rudder_command"]``.
    setup_changes : tuple of (str, object)
        :class:`~ship_gym.engine.ship.ShipSetup` fields replaced, as (name, value) pairs
        (``(("fins", "command"),)``).
    task_observations : tuple of Observation
        The task's entries after the common ones, each with a getter (a function of the task
        returning the (N,) values).
    action_names : tuple of str
        Names of the action entries (with the physical scaling).

    Parameters
    ----------
    num_envs : int
        Number of episodes N.
    **config
        :class:`~ship_gym.envs.config.ShipConfig` fields (ValueError naming an unknown one).
    """

    defaults: ClassVar[ShipConfig] = ShipConfig()
    steering: ClassVar[Literal["autopilot", "command"]] = "autopilot"
    setup_changes: ClassVar[tuple[tuple[str, Any], ...]] = ()

    def __init__(self, num_envs: int, **config: Any) -> None:
        self.config = type(self).defaults.replace(**config)
        """The task's :class:`~ship_gym.envs.config.ShipConfig`."""
        super().__init__(
            num_envs,
            rudder=self.steering,
            sea=self.make_sea(self.config),
            setup_changes=dict(self.setup_changes),
            extra_observations=self.task_observations,
            **self.config.values(SHIP_KWARGS),
        )

    def make_sea(self, config: ShipConfig) -> SeaSampler:
        """The episodes' sea: the irregular sea of the config's sea fields."""
        return irregular_sea(config.values(SEA_KWARGS))
