"""Assemble a two-stage ship model (hull + database + sea → force models → simulator).

One call, :func:`build_simulator`, turns a :class:`ShipSetup` (which hull, database, radiation
model, integrator, time step…) and a sea state into a ready :class:`Simulator` whose state is the
free-floating equilibrium at the given speed:

* nonlinear Froude–Krylov + hydrostatics on the instantaneous wetted hull (stage 2);
* radiation: Cummins memory by state-space (fast) or direct convolution (reference), or
  Matusiak's constant-coefficient cases 2a / 2b, or none;
* diffraction from the database at the encounter frequency and relative heading;
* viscous roll damping B1 p + B2 |p| p from the simplified Ikeda method at the roll natural
  frequency.

The ship starts heading north (ψ = 0) at the origin, so the waves travel to χ = β.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Literal

import numpy as np

from ship_gym.dynamics.simulator import IntegratorName, Simulator
from ship_gym.forces.base import ForceModel
from ship_gym.forces.diffraction import Diffraction
from ship_gym.forces.froude_krylov import FroudeKrylovHydrostatics
from ship_gym.forces.radiation import ConstantCoefficientRadiation, RadiationMemory
from ship_gym.forces.viscous import BilgeKeel, ViscousRollDamping
from ship_gym.hull import equilibrium, load_hull
from ship_gym.hull.hull import Hull
from ship_gym.hydro import load_database
from ship_gym.hydro.rao import natural_frequency
from ship_gym.kinematics import encounter_frequency
from ship_gym.waves.sea_state import IrregularSea, RegularWave
from ship_gym.waves.wave_field import WaveField

if TYPE_CHECKING:
    import xarray as xr

RadiationName = Literal["state_space", "convolution", "2a", "2b", "none"]
RADIATION_MODELS: tuple[str, ...] = ("state_space", "convolution", "2a", "2b", "none")


@dataclass(frozen=True)
class ShipSetup:
    """Everything that defines a simulated ship apart from the sea.

    Attributes
    ----------
    hull : str
        Library hull name (:func:`ship_gym.hull.load_hull`).
    hull_overrides : dict
        Keyword overrides of the hull builder (resolution, KG, …).
    database : str
        ``"s175"`` or a NetCDF path (:func:`ship_gym.hydro.load_database`).
    speed : float
        Steady forward speed U [m/s].
    radiation : {"state_space", "convolution", "2a", "2b", "none"}
        Radiation model.
    diffraction : bool
        Include the linear diffraction force.
    viscous_roll : bool
        Include Ikeda viscous roll damping.
    bilge_keels : bool
        Fit bilge keels (an assumed 0.25 Lpp × 0.45 m pair amidships) in the Ikeda estimate.
    integrator : {"rk4", "abm", "holloway"}
        Time integration scheme.
    dt : float
        Physics time step [s].
    fk_method : {"fast", "reference"}
        Froude–Krylov kernel implementation.
    free_dofs : tuple of bool
        DOFs integrated (held DOFs keep their initial velocity).
    lumped : bool
        Holloway's lumped mode (radiation added mass in the force; needs ``integrator="holloway"``
        and a Cummins radiation model).
    """

    hull: str = "s175"
    hull_overrides: dict = field(default_factory=dict)
    database: str = "s175"
    speed: float = 0.0
    radiation: RadiationName = "state_space"
    diffraction: bool = True
    viscous_roll: bool = True
    bilge_keels: bool = False
    integrator: IntegratorName = "rk4"
    dt: float = 0.05
    fk_method: Literal["fast", "reference"] = "fast"
    free_dofs: tuple[bool, ...] = (True, True, True, True, True, True)
    lumped: bool = False

    def __post_init__(self) -> None:
        if self.radiation not in RADIATION_MODELS:
            raise ValueError(
                f"radiation must be one of {RADIATION_MODELS}, got {self.radiation!r}"
            )
        if self.lumped and (
            self.integrator != "holloway" or self.radiation not in ("state_space", "convolution")
        ):
            raise ValueError(
                "lumped radiation needs integrator='holloway' and a Cummins radiation model "
                f"('state_space' or 'convolution'), got integrator={self.integrator!r}, "
                f"radiation={self.radiation!r}"
            )
        if not (np.isfinite(self.speed) and self.speed >= 0.0):
            raise ValueError(f"speed must be a non-negative speed [m/s], got {self.speed!r}")
        if len(self.free_dofs) != 6:
            raise ValueError(f"free_dofs must have 6 entries, got {self.free_dofs!r}")


Sea = RegularWave | IrregularSea | None


def wave_field_for(
    sea: Sea, wave_heading: float, rng: np.random.Generator | None = None
) -> WaveField | None:
    """Wave field of a sea state seen by a ship heading north: waves travel to χ = β.

    Parameters
    ----------
    sea : RegularWave, IrregularSea or None
        Sea state (its own ``heading`` is replaced by ``wave_heading``).
    wave_heading : float
        Relative wave heading β [rad] (0 following, π head seas).
    rng : numpy.random.Generator, optional
        Source of the random phases/frequencies of an irregular sea.
    """
    if sea is None:
        return None
    sea = dataclasses.replace(sea, heading=float(wave_heading))
    if isinstance(sea, RegularWave):
        return WaveField.regular(sea)
    if rng is None:
        raise ValueError("an irregular sea needs a numpy.random.Generator (rng)")
    return WaveField.from_sea_state(sea, rng)


def _peak_frequency(sea: Sea) -> float:
    if isinstance(sea, RegularWave):
        return float(sea.omega)
    if isinstance(sea, IrregularSea):
        return float(sea.omega_peak)
    raise ValueError("constant-coefficient radiation (2a/2b) needs a sea state to set ω_e")


def build_force_models(
    setup: ShipSetup,
    hull: Hull,
    database: xr.Dataset,
    wave_field: WaveField | None,
    sea: Sea,
    wave_heading: float,
) -> list[ForceModel]:
    """The force models of a setup (see the module docstring for the list)."""
    models: list[ForceModel] = [
        FroudeKrylovHydrostatics(hull, wave_field, method=setup.fk_method)
    ]
    omega_roll = natural_frequency(database, "Roll")
    if setup.radiation in ("state_space", "convolution"):
        models.append(
            RadiationMemory(
                database, method=setup.radiation, dt=setup.dt, lumped=setup.lumped
            )
        )
    elif setup.radiation in ("2a", "2b"):
        w_e = abs(
            float(encounter_frequency(_peak_frequency(sea), setup.speed, wave_heading, hull.g))
        )
        models.append(
            ConstantCoefficientRadiation(
                database,
                case=setup.radiation,
                encounter_frequency=w_e,
                roll_natural_frequency=omega_roll,
            )
        )
    if setup.diffraction and wave_field is not None:
        models.append(Diffraction(database, wave_field))
    if setup.viscous_roll:
        keel = None
        if setup.bilge_keels:
            keel = BilgeKeel(length=0.25 * hull.particulars.lpp, breadth=0.45)
        models.append(
            ViscousRollDamping.from_hull(
                hull, omega=omega_roll, forward_speed=setup.speed, bilge_keel=keel
            )
        )
    return models


def build_simulator(
    setup: ShipSetup,
    sea: Sea = None,
    *,
    wave_heading: float = np.pi,
    rng: np.random.Generator | None = None,
) -> Simulator:
    """A simulator at the free-floating equilibrium, moving at ``setup.speed`` heading north.

    Parameters
    ----------
    setup : ShipSetup
        Ship, models and numerics.
    sea : RegularWave, IrregularSea or None
        Sea state (None: calm water).
    wave_heading : float
        Relative wave heading β [rad] (0 following seas, π head seas).
    rng : numpy.random.Generator, optional
        For irregular seas (one seed, one sea).
    """
    hull = load_hull(setup.hull, **setup.hull_overrides)
    database = load_database(setup.database)
    wave_field = wave_field_for(sea, wave_heading, rng)
    models = build_force_models(setup, hull, database, wave_field, sea, wave_heading)
    lumped_a = None
    if setup.lumped:
        lumped_a = next(m for m in models if isinstance(m, RadiationMemory)).A_inf
    sim = Simulator(
        hull,
        models,
        wave_field=wave_field,
        forward_speed=setup.speed,
        dt=setup.dt,
        integrator=setup.integrator,
        free_dofs=setup.free_dofs,
        lumped_added_mass=lumped_a,
    )
    eq = equilibrium(hull)
    sim.reset(eta=np.array([0.0, 0.0, eq.heave, 0.0, eq.trim, 0.0]))
    return sim
