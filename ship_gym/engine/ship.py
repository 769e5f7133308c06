"""Assemble a two-stage ship model (hull + database + sea → force models → simulator).

One call, :func:`build_simulator`, turns a :class:`ShipSetup` (which hull, database, radiation
model, integrator, time step…) and a sea state into a ready :class:`Simulator` whose state is the
free-floating equilibrium at the given speed:

* nonlinear Froude–Krylov + hydrostatics on the instantaneous wetted hull (stage 2);
* radiation: Cummins memory by state-space (fast) or direct convolution (reference), or
  Matusiak's constant-coefficient cases 2a / 2b, or none;
* diffraction from the database at the encounter frequency and relative heading;
* viscous roll damping B1 p + B2 |p| p from the simplified Ikeda method at the roll natural
  frequency;
* optionally (issue 4): calm-water resistance (Holtrop–Mennen) and a Wageningen B-series
  propeller at the self-propulsion rpm (``propulsion``), hull manoeuvring forces (Clarke
  derivatives + cross-flow drag), a rudder behind its servo, open-loop or under the PID heading
  autopilot tuned on the Nomoto model identified for this hull at this speed, roll fins and a
  T-foil (open-loop or under their classical controllers).

Commands (``Simulator.step(commands)``, persistent until changed): ``"shaft_speed"`` [rev/s],
``"rudder_command"`` [rad] or ``"heading"`` [rad] (autopilot), ``"fins_command"`` [rad],
``"t_foil_command"`` [rad].

The ship starts heading north (ψ = 0) at the origin, so the waves travel to χ = β.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Literal, overload

import numpy as np

from ship_gym.control.actuators import (
    FIN_SERVO,
    FOIL_SERVO,
    RUDDER_SERVO,
    Actuated,
    Controller,
)
from ship_gym.control.autopilot import HeadingAutopilot
from ship_gym.control.stabilisers import FinController, RideController, control_derivative
from ship_gym.engine.linearisation import nomoto_from_models
from ship_gym.forces.added_resistance import AddedResistance
from ship_gym.forces.base import ForceModel
from ship_gym.forces.diffraction import Diffraction
from ship_gym.forces.froude_krylov import FroudeKrylovHydrostatics
from ship_gym.forces.manoeuvring import HullManoeuvring
from ship_gym.forces.propeller import Propeller
from ship_gym.forces.radiation import ConstantCoefficientRadiation, RadiationMemory
from ship_gym.forces.resistance import CalmWaterResistance
from ship_gym.forces.viscous import BilgeKeel, ViscousRollDamping
from ship_gym.forces.wind import MeanWind
from ship_gym.hull import equilibrium, hydrostatics
from ship_gym.hull.hull import Hull
from ship_gym.hydro import load_database
from ship_gym.hydro.forward_speed import (
    SpeedTerms,
    check_speed_cutoff,
    check_speed_terms,
    default_speed_cutoff,
)
from ship_gym.hydro.rao import natural_frequency
from ship_gym.kinematics import encounter_frequency
from ship_gym.ship import Ship, check_database_matches, load_ship
from ship_gym.typing import IntegratorName
from ship_gym.waves.sea_state import IrregularSea, RegularWave
from ship_gym.waves.wave_field import WaveField

if TYPE_CHECKING:
    import xarray as xr

    from ship_gym.engine.simulator import Simulator

RadiationName = Literal["state_space", "convolution", "2a", "2b", "none"]
RADIATION_MODELS: tuple[str, ...] = ("state_space", "convolution", "2a", "2b", "none")


@dataclass(frozen=True)
class ShipSetup:
    """Everything that defines a simulated ship apart from the sea.

    Attributes
    ----------
    hull : str
        The ship: a ship file (``.toml``, :mod:`ship_gym.ship.description`), the name of a
        bundled ship or a library hull (``"s175"``, ``"box_barge"``…;
        :func:`ship_gym.ship.load_ship`).
    hull_overrides : dict
        Loading overrides (``kg``, ``gm``, ``displacement_t``, ``lcg``,
        ``radii_of_gyration``) and hull-builder keywords (mesh resolution).
    database : str
        ``"auto"``: the ship's own database (named by its file, bundled, or built from the hull
        and cached); else a bundled name or a NetCDF path
        (:func:`ship_gym.hydro.load_database`). Either way a database whose waterplane
        stiffness is not the hull's is refused (:func:`ship_gym.ship.check_database_matches`).
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
    integrator : {"rk4", "holloway"}
        Time integration scheme.
    dt : float
        Physics time step [s].
    fk_method : {"fast", "fast32", "reference"}
        Froude–Krylov kernel implementation (``"fast32"``: wave sums in float32, faster
        (docs/benchmarks.md), forces within ≈ 1e-7 of the reference).
    free_dofs : tuple of bool
        DOFs integrated (held DOFs keep their initial velocity).
    propulsion : bool
        Resistance + propeller (surge balance; default shaft speed: self-propulsion at ``speed``).
    manoeuvring : bool or None
        Hull manoeuvring forces in sway/yaw (needed for steering). ``None`` (default): on when
        the ship has forward speed and sway or yaw is free — the hull's lift is the physics
        that holds a ship at speed on its course (without it the sway–yaw couplings of the
        radiation turn the S175 by 20° in 600 s at 5 m/s and 200° at 10 m/s from a 1° drift);
        off otherwise. The resolved value is stored.
    rudder : {"none", "command", "autopilot"}
        No rudder, a rudder following ``"rudder_command"``, or the heading autopilot.
    fins : {"none", "command", "controller"}
        Roll fins: none, open-loop ``"fins_command"``, or the classical PD stabiliser.
    t_foil : {"none", "command", "controller"}
        T-foil: none, open-loop ``"t_foil_command"``, or the classical ride controller.
    added_resistance : {"none", "reflection", "total"}
        Mean added resistance in waves (SNNM, Liu & Papanikolaou 2020). The nonlinear
        Froude–Krylov force on the moving hull already produces the motion-induced part, so
        ``"reflection"`` (short-wave reflection only) is the consistent choice with it;
        ``"total"`` double-counts the motion part and is there for comparisons.
    speed_terms : {"vertical", "all", "none"}
        Planes of the forward-speed Kirchhoff moment on the radiated and scattered momentum
        (:mod:`ship_gym.hydro.forward_speed`). ``"vertical"`` (default): the heave–pitch
        terms; the horizontal plane's steady Munk moment belongs to the hull's lift — inside
        the manoeuvring derivatives when ``manoeuvring=True``, absent without them, where
        ``"all"`` would turn a ship at speed away from its course (1° of yaw → 112° in 100 s at
        5 m/s on the S175). ``"all"`` is the full linear theory (for comparisons with strip
        theory with sway and yaw held), ``"none"`` the body-axis zero-speed model.
    speed_cutoff : float or None
        ω_c [rad/s] of the Kirchhoff moment's high-pass (:mod:`ship_gym.hydro.forward_speed`
        eq. 5): the steady and slowly varying momentum is the steady flow's. ``None``
        (default): 0.25 √(g/L) of the ship (0.059 rad/s for the S175); 0: none.
    diffraction_speed_terms : bool
        The diffraction force at speed in relative-motion form with the scattered flow's
        Kirchhoff moment (:mod:`ship_gym.hydro.forward_speed` eq. 4 and 6; default). False: the
        zero-speed force at the wave frequency without it — the model of issue #13, whose
        radiated momentum alone pitches a ship at speed in beam and quartering seas; kept for
        the ``-v2`` environments and comparisons.
    wind : (float, float) or None
        A constant mean wind (V_w [m/s], χ_w [rad], the earth direction it blows from; the
        ship starts heading north, χ_w = 0) on the windage of the ship's ``[wind]`` table
        (:class:`ship_gym.forces.wind.MeanWind`, Blendermann's coefficients). None: no wind.
    """

    hull: str = "s175"
    hull_overrides: dict = field(default_factory=dict)
    database: str = "auto"
    speed: float = 0.0
    radiation: RadiationName = "state_space"
    diffraction: bool = True
    viscous_roll: bool = True
    bilge_keels: bool = False
    integrator: IntegratorName = "rk4"
    dt: float = 0.05
    fk_method: Literal["fast", "fast32", "reference"] = "fast"
    free_dofs: tuple[bool, ...] = (True, True, True, True, True, True)
    propulsion: bool = False
    manoeuvring: bool | None = None
    rudder: Literal["none", "command", "autopilot"] = "none"
    fins: Literal["none", "command", "controller"] = "none"
    t_foil: Literal["none", "command", "controller"] = "none"
    added_resistance: Literal["none", "reflection", "total"] = "none"
    speed_terms: SpeedTerms = "vertical"
    speed_cutoff: float | None = None
    diffraction_speed_terms: bool = True
    wind: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        if self.manoeuvring is None:
            horizontal_free = len(self.free_dofs) == 6 and bool(
                self.free_dofs[1] or self.free_dofs[5]
            )
            auto = bool(np.isfinite(self.speed) and self.speed > 0.0 and horizontal_free)
            object.__setattr__(self, "manoeuvring", auto)
        check_speed_terms(self.speed_terms)
        if self.speed_cutoff is not None:
            check_speed_cutoff(self.speed_cutoff, "speed_cutoff")
        for name, allowed in (
            ("added_resistance", ("none", "reflection", "total")),
            ("rudder", ("none", "command", "autopilot")),
            ("fins", ("none", "command", "controller")),
            ("t_foil", ("none", "command", "controller")),
        ):
            if getattr(self, name) not in allowed:
                raise ValueError(f"{name} must be one of {allowed}, got {getattr(self, name)!r}")
        if self.rudder == "autopilot" and not (self.manoeuvring and self.speed > 0.0):
            raise ValueError(
                "the autopilot needs manoeuvring=True and a positive speed (its gains come from "
                "the Nomoto model identified at that speed)"
            )
        if self.radiation not in RADIATION_MODELS:
            raise ValueError(f"radiation must be one of {RADIATION_MODELS}, got {self.radiation!r}")
        if self.integrator not in ("rk4", "holloway"):
            raise ValueError(f"integrator must be 'rk4' or 'holloway', got {self.integrator!r}")
        if not (np.isfinite(self.speed) and self.speed >= 0.0):
            raise ValueError(f"speed must be a non-negative speed [m/s], got {self.speed!r}")
        if len(self.free_dofs) != 6:
            raise ValueError(f"free_dofs must have 6 entries, got {self.free_dofs!r}")
        if self.wind is not None:
            if len(self.wind) != 2 or not all(np.isfinite(x) for x in self.wind):
                raise ValueError(
                    f"wind must be (speed [m/s], direction it blows from [rad]), got {self.wind!r}"
                )
            if self.wind[0] < 0.0:
                raise ValueError(f"wind speed must be >= 0 [m/s], got {self.wind[0]!r}")


Sea = RegularWave | IrregularSea | None


def ship_of(setup: ShipSetup) -> Ship:
    """The setup's ship (:func:`ship_gym.ship.load_ship`, cached per process)."""
    return load_ship(setup.hull, **setup.hull_overrides)


def database_of(setup: ShipSetup, ship: Ship | None = None) -> xr.Dataset:
    """The setup's hydrodynamic database, checked against the ship's hull.

    ``"auto"``: the ship's own (:meth:`ship_gym.ship.Ship.database`, built and cached on first
    use); a bundled name or a path otherwise.
    """
    ship = ship_of(setup) if ship is None else ship
    if setup.database == "auto":
        return ship.database()
    database = load_database(setup.database)
    check_database_matches(ship.hull, database, str(setup.database))
    return database


def resolve_wave_heading(sea: Sea, wave_heading: float | None, default: float = 0.0) -> float:
    """The one relative wave heading β [rad] of a run, from the sea and/or ``wave_heading``.

    The ship starts heading north, so β equals the sea's direction χ. Rules:

    * only ``wave_heading`` given (the sea's ``heading`` left at its default): ``wave_heading``;
    * only the sea's ``heading`` given (``wave_heading=None``): the sea's heading;
    * both given: they must agree (modulo 2π, to 1e-9 rad), else :class:`ValueError` naming both;
    * neither: ``default``.
    """
    from ship_gym.waves.sea_state import heading_is_set

    given = sea is not None and heading_is_set(sea)
    if wave_heading is None:
        return float(sea.heading) if given and sea is not None else float(default)
    try:
        beta = float(wave_heading)
    except (TypeError, ValueError):
        raise ValueError(
            f"wave_heading must be a relative wave heading in radians, got {wave_heading!r}"
        ) from None
    if not np.isfinite(beta):
        raise ValueError(f"wave_heading must be finite [rad], got {wave_heading!r}")
    if given and sea is not None:
        diff = abs(np.angle(np.exp(1j * (beta - float(sea.heading)))))
        if diff > 1e-9:
            raise ValueError(
                f"two different wave headings: {type(sea).__name__}(heading="
                f"{float(sea.heading)!r}) ({np.degrees(float(sea.heading)):.6g} deg) and "
                f"wave_heading={beta!r} ({np.degrees(beta):.6g} deg); give only one of them "
                "(the sea's heading, or wave_heading with the sea's heading left unset)"
            )
    return beta


@overload
def wave_field_for(
    sea: RegularWave | IrregularSea,
    wave_heading: float | None = None,
    rng: np.random.Generator | None = None,
) -> WaveField: ...
@overload
def wave_field_for(
    sea: Sea, wave_heading: float | None = None, rng: np.random.Generator | None = None
) -> WaveField | None: ...
def wave_field_for(
    sea: Sea, wave_heading: float | None = None, rng: np.random.Generator | None = None
) -> WaveField | None:
    """Wave field of a sea state seen by a ship heading north: waves travel to χ = β.

    One source of truth for the heading (:func:`resolve_wave_heading`): ``wave_heading`` when
    the sea's own ``heading`` is left at its default, the sea's ``heading`` when
    ``wave_heading`` is None; both given and different raise :class:`ValueError`.

    Parameters
    ----------
    sea : RegularWave, IrregularSea or None
        Sea state.
    wave_heading : float, optional
        Relative wave heading β [rad] (0 following, π head seas).
    rng : numpy.random.Generator, optional
        Source of the random phases/frequencies of an irregular sea.

    Raises
    ------
    ValueError
        If the sea's explicit ``heading`` and ``wave_heading`` differ, or an irregular sea
        comes without ``rng``.
    """
    if sea is None:
        return None
    beta = resolve_wave_heading(sea, wave_heading)
    sea = dataclasses.replace(sea, heading=beta)
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


def roll_natural_frequency(hull: Hull, database: xr.Dataset) -> float:
    """Uncoupled roll natural frequency ω_φ [rad/s] of this loading condition.

    The database's radiation data do not depend on G, but its stored hydrostatic stiffness is
    that of the loading condition it was built for; C44 and M44 here are the hull's own (C at
    its free-floating equilibrium, :func:`ship_gym.hull.hydrostatics`; M_RB about O), so a KG
    override moves ω_φ (used by the Ikeda damping and Matusiak's case 2a) as it should.
    """
    eq = equilibrium(hull)
    stiffness = hydrostatics(hull, heave=eq.heave, trim=eq.trim).stiffness
    return natural_frequency(
        database,
        "Roll",
        hull_hydrostatic_stiffness=stiffness,
        mass_matrix=hull.mass.rigid_body_matrix(),
    )


def speed_cutoff_of(setup: ShipSetup, hull: Hull) -> float:
    """The setup's ω_c [rad/s]: ``speed_cutoff``, or
    :func:`~ship_gym.hydro.forward_speed.default_speed_cutoff` of the hull's Lpp."""
    if setup.speed_cutoff is not None:
        return float(setup.speed_cutoff)
    return default_speed_cutoff(hull.particulars.lpp, hull.g)


def build_force_models(
    setup: ShipSetup,
    hull: Hull,
    database: xr.Dataset,
    wave_field: WaveField | None,
    sea: Sea,
    wave_heading: float,
) -> tuple[list[ForceModel], dict]:
    """The force models of a setup and the initial commands (e.g. the self-propulsion shaft
    speed); see the module docstring for the list."""
    models: list[ForceModel] = [FroudeKrylovHydrostatics(hull, wave_field, method=setup.fk_method)]
    omega_roll = roll_natural_frequency(hull, database)
    terms, cutoff = setup.speed_terms, speed_cutoff_of(setup, hull)
    if setup.radiation in ("state_space", "convolution"):
        models.append(
            RadiationMemory(
                database,
                method=setup.radiation,
                dt=setup.dt,
                speed_terms=terms,
                speed_cutoff=cutoff,
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
        # the scattered flow's Kirchhoff moment pairs with the radiated flow's (same planes and
        # high-pass); without the memory model there is no moment to pair with
        memory = setup.radiation in ("state_space", "convolution")
        paired = memory and setup.diffraction_speed_terms
        models.append(
            Diffraction(
                database,
                wave_field,
                speed_terms=terms if paired else "none",
                speed_cutoff=cutoff,
            )
        )
    if setup.added_resistance != "none" and wave_field is not None:
        models.append(
            AddedResistance.from_hull(hull, wave_field, components=setup.added_resistance)
        )
    if setup.viscous_roll:
        keel = None
        if setup.bilge_keels:
            keel = BilgeKeel(length=0.25 * hull.particulars.lpp, breadth=0.45)
        models.append(
            ViscousRollDamping.from_hull(
                hull, omega=omega_roll, forward_speed=setup.speed, bilge_keel=keel
            )
        )
    if setup.wind is not None and setup.wind[0] > 0.0:
        speed, direction = setup.wind
        models.append(MeanWind(ship_of(setup).windage(), float(speed), float(direction)))
    control, commands = _control_models(setup, hull, database, models)
    return [*models, *control], commands


def _propulsion_and_manoeuvring(setup: ShipSetup, hull: Hull) -> tuple[list[ForceModel], dict]:
    """Resistance and propeller (with the self-propulsion shaft speed as initial command) and
    the hull manoeuvring forces, as the setup asks."""
    out: list[ForceModel] = []
    commands: dict = {}
    if setup.propulsion:
        propeller = ship_of(setup).propeller()
        out += [propeller.resistance or CalmWaterResistance.from_hull(hull), propeller]
        commands["shaft_speed"] = propeller.shaft_speed_for(setup.speed)
    if setup.manoeuvring:
        out.append(HullManoeuvring.from_hull(hull))
    return out, commands


def _lhs_added_mass(models: list[ForceModel]) -> np.ndarray:
    """(6, 6) added mass the models put on the left-hand side [kg, kg·m, kg·m²]."""
    return sum((m.added_mass for m in models if m.added_mass is not None), np.zeros((6, 6)))


def _control_models(
    setup: ShipSetup, hull: Hull, database: xr.Dataset, wave_models: list[ForceModel]
) -> tuple[list[ForceModel], dict]:
    """Propulsion, manoeuvring and actuated surfaces (evaluated after the wave forces; the
    propeller before the rudder, which reads its thrust from ``ctx.shared``)."""
    ship = ship_of(setup)
    out, commands = _propulsion_and_manoeuvring(setup, hull)
    a_lhs = _lhs_added_mass(wave_models)
    mass = hull.mass.rigid_body_matrix() + a_lhs
    # the loading's own restoring (the hull at its free-floating equilibrium), not the
    # database's: a cached database carries the stiffness of whichever loading built it
    eq = equilibrium(hull)
    c = hydrostatics(hull, heave=eq.heave, trim=eq.trim).stiffness
    if setup.rudder != "none":
        rudder = ship.rudder()
        controller: Controller | None = None
        if setup.rudder == "autopilot":
            nomoto = nomoto_from_models(
                hull, [*out, rudder], setup.speed, added_mass=a_lhs, commands=commands
            )
            controller = HeadingAutopilot.from_nomoto(nomoto)
        out.append(Actuated(rudder, RUDDER_SERVO, "rudder", controller=controller))
    if setup.fins != "none":
        fins = ship.fins()
        controller = None
        if setup.fins == "controller":
            controller = _fin_controller(fins, setup.speed, c[3, 3], mass[3, 3])
        out.append(Actuated(fins, FIN_SERVO, "fins", controller=controller))
    if setup.t_foil != "none":
        foil = ship.t_foil()
        controller = None
        if setup.t_foil == "controller":
            controller = _ride_controller(foil, setup.speed, c, mass)
        out.append(Actuated(foil, FOIL_SERVO, "t_foil", controller=controller))
    return out, commands


def _fin_controller(
    fins: ForceModel, speed: float, c44: float, i44_total: float, **design: float
) -> FinController:
    """:meth:`FinController.tuned` (``design``: its fractions) with K_δ = ∂K/∂δ of ``fins`` at
    ``speed`` (≥ 1 m/s)."""
    k_delta = control_derivative(fins, "fins", 3, max(speed, 1.0))
    return FinController.tuned(k_delta, c44, i44_total, **design)


def fin_stabiliser(
    setup: ShipSetup, *, added_damping: float = 0.3, added_stiffness: float = 0.2
) -> FinController:
    """The classical PD fin stabiliser of ``setup``'s ship, designed from its own linear roll
    model (:meth:`ship_gym.control.stabilisers.FinController.tuned`).

    The model is the one ``fins="controller"`` builds: K_δ = ∂K/∂δ of the ship's fins at the
    setup's speed, C₄₄ of the loading at its free-floating equilibrium and I₄₄ + A₄₄ (the
    rigid-body inertia about O and the radiation models' left-hand-side added inertia).

    Parameters
    ----------
    setup : ShipSetup
        Ship, loading, speed and radiation model (its ``fins`` field is not read).
    added_damping : float
        ζ_add, the fraction of critical roll damping the rate gain adds [-].
    added_stiffness : float
        c_add, the fraction of C₄₄ the angle gain adds [-].

    Returns
    -------
    FinController
        Gains k_φ [rad/rad] and k_p [rad·s/rad] on the fin angle.
    """
    if not (np.isfinite(added_damping) and added_damping >= 0.0):
        raise ValueError(f"added_damping must be a fraction >= 0 [-], got {added_damping!r}")
    if not (np.isfinite(added_stiffness) and added_stiffness >= 0.0):
        raise ValueError(f"added_stiffness must be a fraction >= 0 [-], got {added_stiffness!r}")
    mass, stiffness = _linear_inertia_and_stiffness(setup)
    design = {"added_damping": added_damping, "added_stiffness": added_stiffness}
    return _fin_controller(
        ship_of(setup).fins(), setup.speed, stiffness[3, 3], mass[3, 3], **design
    )


def _linear_inertia_and_stiffness(setup: ShipSetup) -> tuple[np.ndarray, np.ndarray]:
    """(6, 6) total inertia M_RB + A_lhs (the radiation models' left-hand-side added inertia)
    and hydrostatic stiffness of the loading at its free-floating equilibrium: what the
    simulator's controllers are designed on (:func:`_control_models`)."""
    ship = ship_of(setup)
    hull = ship.hull
    bare = dataclasses.replace(
        setup, rudder="none", fins="none", t_foil="none", propulsion=False, manoeuvring=False
    )
    wave_models, _ = build_force_models(bare, hull, database_of(setup, ship), None, None, np.pi)
    eq = equilibrium(hull)
    stiffness = hydrostatics(hull, heave=eq.heave, trim=eq.trim).stiffness
    return hull.mass.rigid_body_matrix() + _lhs_added_mass(wave_models), stiffness


def _ride_controller(
    foil: ForceModel, speed: float, stiffness: np.ndarray, mass: np.ndarray, **design: float
) -> RideController:
    """:meth:`RideController.tuned` (``design``: its damping fractions) with the heave force
    and pitch moment per radian of ``foil`` at ``speed`` (≥ 1 m/s) and the (6, 6) stiffness and
    total inertia."""
    u = max(speed, 1.0)
    return RideController.tuned(
        control_derivative(foil, "t_foil", 2, u),
        control_derivative(foil, "t_foil", 4, u),
        stiffness[2, 2],
        mass[2, 2],
        stiffness[4, 4],
        mass[4, 4],
        **design,
    )


def ride_controller(
    setup: ShipSetup, *, heave_damping: float = 0.2, pitch_damping: float = 0.2
) -> RideController:
    """The classical T-foil ride controller of ``setup``'s ship, designed from its own linear
    heave and pitch model (:meth:`ship_gym.control.stabilisers.RideController.tuned`; the one
    ``t_foil="controller"`` builds at the defaults).

    The model: the foil's heave force and pitch moment per radian at the setup's speed, C₃₃ and
    C₅₅ of the loading at its free-floating equilibrium, m + A₃₃ and I₅₅ + A₅₅ (rigid-body
    inertia and the radiation models' left-hand-side added inertia).

    Parameters
    ----------
    setup : ShipSetup
        Ship, loading, speed and radiation model (its ``t_foil`` field is not read).
    heave_damping : float
        ζ_3, the fraction of critical heave damping the heave-velocity gain adds [-].
    pitch_damping : float
        ζ_5, the fraction of critical pitch damping the pitch-rate gain adds [-].

    Returns
    -------
    RideController
        Gains k_w [rad/(m/s)] and k_q [rad/(rad/s)] on the foil angle.
    """
    for name, value in (("heave_damping", heave_damping), ("pitch_damping", pitch_damping)):
        if not (np.isfinite(value) and value >= 0.0):
            raise ValueError(f"{name} must be a fraction >= 0 [-], got {value!r}")
    mass, stiffness = _linear_inertia_and_stiffness(setup)
    design = {"heave_damping": heave_damping, "pitch_damping": pitch_damping}
    return _ride_controller(ship_of(setup).t_foil(), setup.speed, stiffness, mass, **design)


def heading_autopilot(
    setup: ShipSetup, *, natural_frequency: float = 0.06, damping: float = 0.9
) -> HeadingAutopilot:
    """The PID heading autopilot of ``setup``'s ship, placed on the Nomoto model identified from
    its own manoeuvring, propulsion and rudder models at the setup's speed
    (:meth:`ship_gym.control.autopilot.HeadingAutopilot.from_nomoto`; the autopilot
    ``rudder="autopilot"`` builds at the defaults).

    Parameters
    ----------
    setup : ShipSetup
        Ship, loading, speed and radiation model (its ``rudder`` field is not read).
    natural_frequency : float
        Closed-loop ω_n [rad/s].
    damping : float
        Closed-loop ζ [-].

    Returns
    -------
    HeadingAutopilot
        Gains K_p [-], K_d [s], K_i [1/s] on the rudder angle.
    """
    if not (np.isfinite(natural_frequency) and natural_frequency > 0.0):
        raise ValueError(f"natural_frequency must be positive [rad/s], got {natural_frequency!r}")
    if not (np.isfinite(damping) and damping > 0.0):
        raise ValueError(f"damping must be positive [-], got {damping!r}")
    ship = ship_of(setup)
    hull = ship.hull
    bare = dataclasses.replace(setup, rudder="none", fins="none", t_foil="none")
    models, _ = build_force_models(bare, hull, database_of(setup, ship), None, None, np.pi)
    steering, commands = _propulsion_and_manoeuvring(setup, hull)
    nomoto = nomoto_from_models(
        hull,
        [*steering, ship.rudder()],
        setup.speed,
        added_mass=_lhs_added_mass(models),
        commands=commands,
    )
    return HeadingAutopilot.from_nomoto(
        nomoto, natural_frequency=natural_frequency, damping=damping
    )


def build_simulator(
    setup: ShipSetup,
    sea: Sea = None,
    *,
    wave_heading: float | None = None,
    rng: np.random.Generator | None = None,
) -> Simulator:
    """A simulator at the free-floating equilibrium, moving at ``setup.speed`` heading north.

    Parameters
    ----------
    setup : ShipSetup
        Ship, models and numerics.
    sea : RegularWave, IrregularSea or None
        Sea state (None: calm water).
    wave_heading : float, optional
        Relative wave heading β [rad] (0 following seas, π head seas). Default: the sea's own
        ``heading`` if it was given, else π (head seas); both given and different raise
        :class:`ValueError` (:func:`resolve_wave_heading`).
    rng : numpy.random.Generator, optional
        For irregular seas (one seed, one sea).
    """
    wave_heading = resolve_wave_heading(sea, wave_heading, default=np.pi)
    ship = ship_of(setup)
    hull = ship.hull
    database = database_of(setup, ship)
    wave_field = wave_field_for(sea, wave_heading, rng)
    models, commands = build_force_models(setup, hull, database, wave_field, sea, wave_heading)
    from ship_gym.engine.simulator import Simulator

    sim = Simulator(
        hull,
        models,
        wave_field=wave_field,
        forward_speed=setup.speed,
        dt=setup.dt,
        integrator=setup.integrator,
        free_dofs=setup.free_dofs,
    )
    sim.commands = dict(commands)
    eq = equilibrium(hull)
    sim.reset(eta=np.array([0.0, 0.0, eq.heave, 0.0, eq.trim, 0.0]))
    if setup.propulsion and setup.speed > 0.0:
        # the self-propulsion point of the propeller alone ignores the appendages' drag (the
        # rudder's ≈ 2 % of R_T): balance the surge force of the assembled ship instead
        trim_shaft_speed(sim, setup.speed)
    return sim


def propeller_of(sim: Simulator) -> Propeller:
    """The propeller model of a simulator (built with ``propulsion=True``)."""
    for f in sim.forces:
        if isinstance(f, Propeller):
            return f
    raise ValueError("the simulator has no propeller (build it with propulsion=True)")


def trim_shaft_speed(sim: Simulator, speed: float, iterations: int = 4) -> float:
    """Set (and return) the shaft speed [rev/s] that makes ``speed`` a steady straight run.

    The simulator's state is left as it was (build it at ``speed``: ν = (U, 0, …)). The surge
    force of every model but the propeller (resistance, rudder drag at the current
    rudder command, hydrostatics + gravity …) is evaluated at ν = (U, 0, 0, 0, 0, 0) and the
    propeller's (1 − t) T(n, (1 − w) U) is matched to it (Brent on n). The rudder's drag depends
    on the propeller's slipstream, hence a few fixed-point iterations
    (:func:`ship_gym.engine.batch_control.trim_batch_shaft_speed` on the simulator's engine).
    """
    from ship_gym.engine.batch_control import trim_batch_shaft_speed

    return float(trim_batch_shaft_speed(sim.engine, propeller_of(sim), speed, iterations)[0])
