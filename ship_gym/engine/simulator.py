"""One ship on the engine: the single-ship view of :class:`~ship_gym.engine.batch.BatchSimulator`.

:class:`Simulator` is not a second engine. It converts its force models to the engine's row
protocol (:func:`~ship_gym.engine.batch.batch_force_models`; a model without a row version,
e.g. the Cummins convolution or added resistance in waves, is wrapped in a
:class:`~ship_gym.engine.batch.PerShipForceModel`), builds a batch of N = 1 and steps it: on the
compiled backend when every model has a compiled version, on the engine's numpy path otherwise.
What it adds is the single-ship vocabulary (scalar time, (6,) states, scalar commands, an
exception on divergence) used by the manoeuvres, the studies and the scripts.

The equations (Kring, Huang & Sclavounos, their eq. 3: the instantaneous added mass on the left,
everything else explicit) are those of the engine,

    (M_RB + A_lhs) ν̇ = Σᵢ Fᵢ(t, η, ν, zᵢ) + F_gravity(η) − C_RB(ν) ν,
    η̇ = J(η) ν,   żᵢ = gᵢ(t, η, ν, zᵢ),

where A_lhs is the sum of the ``added_mass`` declared by the force models. Degrees of freedom
can be held (``free_dofs``): a held DOF keeps its initial velocity and its force equation is
dropped; a held rotation also keeps its Euler angle fixed.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.engine.batch import (
    BatchSimulator,
    EngineBackend,
    PerShipForceModel,
    batch_force_models,
)
from ship_gym.engine.compiled import StepReductions
from ship_gym.engine.results import SimulationDiverged, SimulationResult, steps_in
from ship_gym.engine.rigid_body import coriolis_force, gravity_force, left_hand_side
from ship_gym.forces.base import BatchForceModel, ForceModel
from ship_gym.hull.hull import Hull
from ship_gym.kinematics import rotation_matrix
from ship_gym.typing import IntegratorName
from ship_gym.waves.wave_field import WaveField

__all__ = [
    "SimulationDiverged",
    "SimulationResult",
    "Simulator",
    "engine_model",
    "left_hand_side",
    "steps_in",
]


def engine_model(model: ForceModel | BatchForceModel) -> BatchForceModel:
    """The engine's row version of one ship's force model.

    A model with a row version is converted (:func:`~ship_gym.engine.batch.batch_force_models`);
    any other :class:`~ship_gym.forces.base.ForceModel` runs as itself, once per step, through a
    :class:`~ship_gym.engine.batch.PerShipForceModel` (the engine's numpy path).
    """
    if isinstance(model, BatchForceModel):
        return model
    try:
        return batch_force_models([model])[0]
    except NotImplementedError:
        return PerShipForceModel([model])


def _state6(value: ArrayLike, name: str) -> NDArray:
    arr = np.asarray(value, float)
    if arr.shape != (6,):
        raise ValueError(f"{name} must have 6 components, got shape {arr.shape}")
    return arr


class Simulator:
    """Advance one ship in waves by a fixed physics step, on the engine.

    Parameters
    ----------
    hull : Hull
        Hull and loading condition (rigid-body mass matrix about O, G, ρ, g).
    forces : sequence of ForceModel
        Force models (Froude–Krylov + hydrostatics, radiation, diffraction, viscous, control…);
        kept in :attr:`forces` as given (their parameters; the engine holds the states).
    wave_field : WaveField, optional
        Incident waves (None: calm water).
    forward_speed : float
        Steady forward speed U [m/s] about which radiation is linearised.
    dt : float
        Physics time step [s].
    integrator : {"rk4", "holloway"}
        Time-stepping scheme (4 or 1 force evaluations per step; Holloway after a 2-step RK4
        start-up).
    free_dofs : sequence of bool, optional
        (6,) which DOFs are integrated; held DOFs keep their initial velocity.
    mu : array_like, optional
        Holloway blending factors per DOF (default 1: the acceleration is exact, the added mass
        being on the left).
    max_abs_velocity : float
        |ν| above which the state is declared diverged [m/s, rad/s].
    backend : {"auto", "compiled", "numpy"}
        The engine's path (``"auto"``: compiled when every model has a compiled version).

    Attributes
    ----------
    engine : BatchSimulator
        The batch of one ship that holds the state.
    """

    def __init__(
        self,
        hull: Hull,
        forces: Sequence[ForceModel],
        *,
        wave_field: WaveField | None = None,
        forward_speed: float = 0.0,
        dt: float = 0.05,
        integrator: IntegratorName = "rk4",
        free_dofs: Sequence[bool] | None = None,
        mu: ArrayLike | None = None,
        max_abs_velocity: float = 100.0,
        backend: EngineBackend = "auto",
    ) -> None:
        if integrator not in ("rk4", "holloway"):
            raise ValueError(f"integrator must be 'rk4' or 'holloway', got {integrator!r}")
        names = [f.name for f in forces]
        if len(set(names)) != len(names):
            raise ValueError(f"force model names must be unique, got {names}")
        self.hull = hull
        self.forces = list(forces)
        self.wave_field = wave_field
        self.engine = BatchSimulator(
            hull,
            [engine_model(f) for f in self.forces],
            [wave_field],
            forward_speed=forward_speed,
            dt=dt,
            integrator=integrator,
            free_dofs=free_dofs,
            mu=mu,
            max_abs_velocity=max_abs_velocity,
            backend=backend,
        )
        e = self.engine
        self.dt: float = e.dt
        self.integrator_name: IntegratorName = integrator
        self.free, self.mass_rb, self.added_mass_lhs = e.free, e.mass_rb, e.added_mass_lhs
        self.n_states: int = e.n_states

    # ------------------------------------------------------------------ state
    @property
    def t(self) -> float:
        """Time [s]."""
        return float(self.engine.t[0])

    @property
    def eta(self) -> NDArray:
        """(6,) position [m] and Euler angles [rad] (a copy; assign to change)."""
        return self.engine.eta[0].copy()

    @eta.setter
    def eta(self, value: ArrayLike) -> None:
        self.engine.eta[0] = _state6(value, "eta")

    @property
    def nu(self) -> NDArray:
        """(6,) body velocities [m/s, rad/s] (a copy; assign to change)."""
        return self.engine.nu[0].copy()

    @nu.setter
    def nu(self, value: ArrayLike) -> None:
        self.engine.nu[0] = _state6(value, "nu")

    @property
    def z(self) -> NDArray:
        """(n_states,) force-model states (a copy)."""
        return self.engine.z[0].copy()

    @property
    def n_steps(self) -> int:
        """Steps since the last :meth:`reset`."""
        return int(self.engine.n_steps[0])

    @property
    def forward_speed(self) -> float:
        """U [m/s] about which radiation is linearised (takes effect from the next step)."""
        return self.engine.forward_speed

    @forward_speed.setter
    def forward_speed(self, value: float) -> None:
        self.engine.forward_speed = value

    @property
    def max_abs_velocity(self) -> float:
        """|ν| above which the state is declared diverged [m/s, rad/s]."""
        return self.engine.max_abs_velocity

    @max_abs_velocity.setter
    def max_abs_velocity(self, value: float) -> None:
        self.engine.max_abs_velocity = float(value)

    @property
    def commands(self) -> dict[str, Any]:
        """Actuator commands in force (scalars); assign a new dict to change them."""
        return {k: (v[0] if np.ndim(v) else v) for k, v in self.engine.commands.items()}

    @commands.setter
    def commands(self, value: Mapping[str, Any]) -> None:
        self.engine.commands = {k: np.atleast_1d(np.asarray(v, float)) for k, v in value.items()}

    def reset(
        self,
        eta: ArrayLike | None = None,
        nu: ArrayLike | None = None,
        t0: float = 0.0,
    ) -> None:
        """Start a new simulation at time ``t0`` from (η, ν); memory and histories cleared.

        Parameters
        ----------
        eta : array_like, optional
            (6,) initial position/attitude (default zeros: the design waterline).
        nu : array_like, optional
            (6,) initial body velocities (default (U, 0, 0, 0, 0, 0)).
        t0 : float
            Initial time [s].
        """
        eta0 = np.zeros(6) if eta is None else _state6(eta, "eta")
        nu0 = None if nu is None else _state6(nu, "nu")
        self.engine.reset(None, eta0, nu0, t0=float(t0))

    # ------------------------------------------------------------------ stepping
    def _raise_if_diverged(self) -> None:
        if self.engine.diverged[0]:
            message = self.engine.divergence_messages.get(0, "the state diverged")
            raise SimulationDiverged(f"state {message.removeprefix('ship 0 ')}")

    def advance(
        self,
        n_steps: int,
        commands: Mapping[str, Any] | None = None,
        *,
        danger_roll: float = np.inf,
    ) -> StepReductions:
        """Take ``n_steps`` physics steps with the commands held (one compiled call).

        ``commands`` are merged into the current ones (scalars). Returns the engine's
        reductions (arrays of one ship).

        Raises
        ------
        SimulationDiverged
            If the state becomes non-finite or |ν| exceeds ``max_abs_velocity``; the ship keeps
            the state of the start of the step that failed, and stays frozen until
            :meth:`reset`.
        """
        self._raise_if_diverged()
        cmd = None
        if commands is not None:
            cmd = {k: np.atleast_1d(np.asarray(v, float)) for k, v in commands.items()}
        out = self.engine.advance(n_steps, cmd, danger_roll=danger_roll)
        self._raise_if_diverged()
        return out

    def step(self, commands: Mapping[str, Any] | None = None) -> None:
        """Advance by one physics step ``dt`` (commands held constant over the step).

        ``commands`` are merged into the current ones: a command stays in force until changed
        (e.g. the shaft speed set when the ship was built).

        Raises
        ------
        SimulationDiverged
            As :meth:`advance`.
        """
        self.advance(1, commands)

    def run(
        self,
        duration: float,
        *,
        record_every: int = 1,
        record_forces: bool = False,
        progress: bool = False,
    ) -> SimulationResult:
        """Step for ``duration`` seconds from the current state and record the series.

        Parameters
        ----------
        duration : float
            Simulated time [s].
        record_every : int
            Record every n-th step.
        record_forces : bool
            Also record the per-force breakdown (one extra force evaluation per record).
        progress : bool
            Show a tqdm progress bar.
        """
        self._raise_if_diverged()
        if not record_forces:
            return self.engine.record(duration, record_every=record_every, progress=progress)
        n = steps_in(duration, self.dt)
        rec: dict[str, list] = {"t": [], "eta": [], "nu": [], "el": []}
        rec_f: dict[str, list[NDArray]] = {}

        def record() -> None:
            rec["t"].append(self.t)
            rec["eta"].append(self.eta)
            rec["nu"].append(self.nu)
            rec["el"].append(self.elevation_at_ship())
            for k, v in self.force_breakdown().items():
                rec_f.setdefault(k, []).append(v)

        steps: Any = range(n)
        if progress:
            from tqdm import tqdm

            steps = tqdm(steps, desc="simulating", unit="step", mininterval=0.5)
        record()
        for i in steps:
            self.step()
            if (i + 1) % record_every == 0:
                record()
        return SimulationResult(
            np.array(rec["t"]),
            np.array(rec["eta"]),
            np.array(rec["nu"]),
            np.array(rec["el"]),
            {k: np.array(v) for k, v in rec_f.items()},
        )

    # ------------------------------------------------------------------ queries
    def force_breakdown(self) -> dict[str, NDArray]:
        """Per-force body-axis generalised forces at the current state (plus ``"gravity"`` and
        ``"coriolis"``, the rigid-body terms −C_RB(ν)ν)."""
        breakdown = {k: v[0] for k, v in self.engine.force_breakdown().items()}
        del breakdown["rigid_body"]
        eta, nu = self.eta, self.nu
        rot = rotation_matrix(eta[3], eta[4], eta[5])
        mass = self.hull.mass
        breakdown["gravity"] = gravity_force(mass.mass, self.engine.centre_of_gravity[0], rot,
                                             self.hull.g)  # fmt: skip
        breakdown["coriolis"] = -coriolis_force(self.engine.mass_rb, nu)
        return breakdown

    def actuator_angle(self, name: str) -> float:
        """Servo angle [rad] of the actuated force model ``name`` at the last accepted step.

        Raises
        ------
        ValueError
            If no force model of that name has a servo.
        """
        return float(self.engine.actuator_angles(name)[0])

    def elevation_at_ship(self) -> float:
        """Incident-wave elevation at O's horizontal position [m]."""
        if self.wave_field is None:
            return 0.0
        return float(self.wave_field.elevation(self.engine.eta[0, 0], self.engine.eta[0, 1],
                                               self.t))  # fmt: skip
