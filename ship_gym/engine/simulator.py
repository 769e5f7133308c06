"""The 6-DOF two-stage time-domain simulator.

Equations of motion in the stable form of Kring, Huang & Sclavounos (their eq. 3): the
instantaneous (infinite-frequency) added mass on the left, everything else explicit,

    (M_RB + A_lhs) ν̇ = Σᵢ Fᵢ(t, η, ν, zᵢ) + F_gravity(η) − C_RB(ν) ν,
    η̇ = J(η) ν,   żᵢ = gᵢ(t, η, ν, zᵢ),

where A_lhs is the sum of the ``added_mass`` declared by the force models (A(∞) for the Cummins
radiation model, A(ω_c) for Matusiak's constant-coefficient cases) and zᵢ are force models' own
states (e.g. the state-space radiation memory). With Holloway's scheme the radiation added mass
may instead be *lumped* into the force with the extrapolated acceleration (Holloway eq. 10); the
blending factor μ then stabilises the explicit step (Holloway eq. 4, default μ = m/(m + A_e)).

Degrees of freedom can be held (``free_dofs``): a held DOF keeps its initial velocity (e.g. a
steady forward speed in surge) and its force equation is dropped; a held rotation also keeps its
Euler angle fixed.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ship_gym.conventions import DOF_NAMES
from ship_gym.engine.integrators import RK4, AdamsBashforthMoulton, HollowayIntegrator
from ship_gym.engine.rigid_body import coriolis_force, gravity_force
from ship_gym.engine.rigid_body import kinematics as rigid_kinematics
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.hull.hull import Hull
from ship_gym.kinematics import rotation_matrix
from ship_gym.typing import IntegratorName
from ship_gym.waves.wave_field import WaveField

if TYPE_CHECKING:
    import xarray as xr


class SimulationDiverged(RuntimeError):
    """The state became non-finite or absurd; the simulator keeps its last valid state."""


@dataclass
class SimulationResult:
    """Time series of a run.

    Attributes
    ----------
    t : numpy.ndarray
        (n,) times [s].
    eta : numpy.ndarray
        (n, 6) positions [m] and Euler angles [rad].
    nu : numpy.ndarray
        (n, 6) body velocities [m/s, rad/s].
    elevation : numpy.ndarray
        (n,) incident-wave elevation at O's horizontal position [m] (0 in calm water).
    forces : dict
        Per-force body-axis generalised forces (n, 6) at the recorded states (if recorded).
    """

    t: np.ndarray
    eta: np.ndarray
    nu: np.ndarray
    elevation: np.ndarray
    forces: dict[str, np.ndarray] = field(default_factory=dict)

    def to_dataset(self) -> xr.Dataset:
        """The series as an ``xarray.Dataset`` (dims ``time``, ``dof``)."""
        import xarray as xr

        data = {
            "eta": (("time", "dof"), self.eta),
            "nu": (("time", "dof"), self.nu),
            "wave_elevation": (("time",), self.elevation),
        }
        for name, f in self.forces.items():
            data[f"force_{name}"] = (("time", "dof"), f)
        ds = xr.Dataset(data, coords={"time": self.t, "dof": list(DOF_NAMES)})
        ds["eta"].attrs["units"] = "m (x, y, z) and rad (roll, pitch, yaw)"
        ds["nu"].attrs["units"] = "m/s (u, v, w) and rad/s (p, q, r)"
        return ds


def left_hand_side(
    hull: Hull, forces: Sequence, free_dofs: Sequence[bool] | None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Held-DOF mask, rigid-body mass matrix and the added mass the models put on the left.

    Parameters
    ----------
    hull : Hull
        Mass properties.
    forces : sequence
        Force models; each may declare ``added_mass`` (6×6) for the left-hand side.
    free_dofs : sequence of bool or None
        Which DOFs are integrated (None: all).

    Returns
    -------
    free : numpy.ndarray
        (6,) bool.
    mass_rb, added_mass : numpy.ndarray
        (6, 6) M_RB about O and Σ A_lhs [kg, kg·m, kg·m²].
    """
    free = np.ones(6, bool) if free_dofs is None else np.asarray(free_dofs, bool)
    if free.shape != (6,):
        raise ValueError(f"free_dofs must have 6 booleans, got {free_dofs!r}")
    a_lhs = np.zeros((6, 6))
    for f in forces:
        if f.added_mass is not None:
            a_lhs = a_lhs + np.asarray(f.added_mass, float)
    return free, hull.mass.rigid_body_matrix(), a_lhs


def steps_in(duration: float, dt: float) -> int:
    """Number of steps of ``dt`` [s] in ``duration`` [s] (ValueError unless a positive
    multiple, to 1e-9 relative)."""
    n = round(duration / dt)
    if n < 1 or abs(n * dt - duration) > 1e-9 * max(1.0, duration):
        raise ValueError(f"duration {duration} s must be a positive multiple of dt = {dt} s")
    return n


class Simulator:
    """Advance a ship in waves by a fixed physics step.

    Parameters
    ----------
    hull : Hull
        Hull and loading condition (rigid-body mass matrix about O, G, ρ, g).
    forces : sequence of ForceModel
        Force models (Froude–Krylov + hydrostatics, radiation, diffraction, viscous, control…).
    wave_field : WaveField, optional
        Incident waves shared by the models through the context (None: calm water).
    forward_speed : float
        Steady forward speed U [m/s] about which radiation is linearised.
    dt : float
        Physics time step [s].
    integrator : {"rk4", "abm", "holloway"}
        Time-stepping scheme (4, 2 or 1 force evaluations per step).
    free_dofs : sequence of bool, optional
        (6,) which DOFs are integrated; held DOFs keep their initial velocity.
    mu : array_like, optional
        Holloway blending factors per DOF; default 1 (exact acceleration) unless a force model
        lumps added mass into the force, then m/(m + A_e) with A_e the diagonal of
        ``lumped_added_mass`` (Holloway eq. 4).
    lumped_added_mass : numpy.ndarray, optional
        (6, 6) added mass that a lumped-mode force model puts in the force (Holloway eq. 10);
        only used for the default μ.
    max_abs_velocity : float
        |ν| above which the state is declared diverged [m/s, rad/s].
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
        mu: np.ndarray | None = None,
        lumped_added_mass: np.ndarray | None = None,
        max_abs_velocity: float = 100.0,
    ) -> None:
        if not (np.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be a positive time step [s], got {dt!r}")
        names = [f.name for f in forces]
        if len(set(names)) != len(names):
            raise ValueError(f"force model names must be unique, got {names}")
        self.hull = hull
        self.forces = list(forces)
        self.wave_field = wave_field
        self.forward_speed = float(forward_speed)
        self.dt = float(dt)
        self.max_abs_velocity = float(max_abs_velocity)
        self.free, self.mass_rb, a_lhs = left_hand_side(hull, self.forces, free_dofs)
        self.added_mass_lhs = a_lhs
        m = self.mass_rb + a_lhs
        idx = np.flatnonzero(self.free)
        self._free_idx = idx
        self._m_free_inv = np.linalg.inv(m[np.ix_(idx, idx)])
        sizes = [int(f.n_states) for f in self.forces]
        bounds = np.concatenate([[0], np.cumsum(sizes)]).astype(int)
        self._slices = [slice(bounds[i], bounds[i + 1]) for i in range(len(self.forces))]
        self.n_states = int(bounds[-1])
        self.integrator_name = integrator
        held_angles = ~self.free[3:]
        if held_angles.any():
            # a held rotation holds its Euler angle (not only its body rate: with φ, θ ≠ 0 the
            # Euler-rate matrix would still turn a ship whose yaw rate r is held at 0)
            def kinematics(eta: np.ndarray, nu: np.ndarray) -> np.ndarray:
                rate = rigid_kinematics(eta, nu)
                rate[3:][held_angles] = 0.0
                return rate

        else:
            kinematics = rigid_kinematics
        if integrator == "rk4":
            self.integrator = RK4(self.dt, kinematics=kinematics)
        elif integrator == "abm":
            self.integrator = AdamsBashforthMoulton(self.dt, kinematics=kinematics)
        elif integrator == "holloway":
            if mu is None and lumped_added_mass is None:
                # the acceleration is exact (added mass on the left): no blending needed, and
                # μ < 1 only adds error (Holloway 2007: errors vanish at μ = m/(m + A) where A
                # is the added mass *hidden in the force*, here none)
                mu = np.ones(6)
            elif mu is None:
                m_d = np.diag(self.mass_rb)
                mu = m_d / (m_d + np.diag(lumped_added_mass))
            self.integrator = HollowayIntegrator(
                self.dt, np.asarray(mu, float), kinematics=kinematics
            )
        else:
            raise ValueError(f"integrator must be 'rk4', 'abm' or 'holloway', got {integrator!r}")
        self.t = 0.0
        self.eta = np.zeros(6)
        self.nu = np.zeros(6)
        self.z = np.zeros(self.n_states)
        self.commands: dict = {}
        self.n_steps = 0

    # ------------------------------------------------------------------ state
    def reset(
        self,
        eta: np.ndarray | None = None,
        nu: np.ndarray | None = None,
        t0: float = 0.0,
    ) -> None:
        """Start a new simulation at time ``t0`` from (η, ν); memory and histories cleared.

        Parameters
        ----------
        eta : numpy.ndarray, optional
            (6,) initial position/attitude (default zeros: the design waterline).
        nu : numpy.ndarray, optional
            (6,) initial body velocities (default (U, 0, 0, 0, 0, 0)).
        t0 : float
            Initial time [s].
        """
        self.t = float(t0)
        self.eta = np.zeros(6) if eta is None else np.asarray(eta, float).copy()
        if nu is None:
            self.nu = np.array([self.forward_speed, 0, 0, 0, 0, 0], float)
        else:
            self.nu = np.asarray(nu, float).copy()
        if self.eta.shape != (6,) or self.nu.shape != (6,):
            raise ValueError("eta and nu must each have 6 components")
        self.z = np.concatenate([f.initial_states() for f in self.forces] or [np.zeros(0)])
        self.integrator.reset()
        ctx = self._context(self.t, self.eta, self.nu, None)
        for f in self.forces:
            f.reset(self.t, ctx)
        self.n_steps = 0

    def _context(
        self, t: float, eta: np.ndarray, nu: np.ndarray, acc_e: np.ndarray | None
    ) -> ForceContext:
        phasor = None if self.wave_field is None else self.wave_field.phasor(t)
        return ForceContext(
            t=t,
            eta=eta,
            nu=nu,
            rotation=rotation_matrix(eta[3], eta[4], eta[5]),
            forward_speed=self.forward_speed,
            wave_phasor=phasor,
            acceleration_extrapolated=acc_e,
            commands=self.commands,
        )

    def _generalised_force(
        self, ctx: ForceContext, z: np.ndarray, breakdown: dict | None = None
    ) -> tuple[np.ndarray, np.ndarray]:
        total = gravity_force(self.hull.mass.mass, self.hull.mass.cog, ctx.rotation, self.hull.g)
        total = total - coriolis_force(self.mass_rb, ctx.nu)
        zdot = np.empty(self.n_states)
        for f, sl in zip(self.forces, self._slices, strict=True):
            force, zd = f.evaluate(ctx, z[sl])
            total = total + force
            zdot[sl] = zd
            if breakdown is not None:
                breakdown[f.name] = force
        return total, zdot

    def _acceleration(self, total: np.ndarray) -> np.ndarray:
        acc = np.zeros(6)
        acc[self._free_idx] = self._m_free_inv @ total[self._free_idx]
        return acc

    def _rhs_explicit(self, t: float, q: np.ndarray, v: np.ndarray, z: np.ndarray):
        total, zdot = self._generalised_force(self._context(t, q, v, None), z)
        return self._acceleration(total), zdot

    def _rhs_holloway(
        self, t: float, q: np.ndarray, v: np.ndarray, z: np.ndarray, acc_e: np.ndarray
    ):
        total, zdot = self._generalised_force(self._context(t, q, v, acc_e), z)
        return self._acceleration(total), zdot

    # ------------------------------------------------------------------ stepping
    def step(self, commands: dict | None = None) -> None:
        """Advance by one physics step ``dt`` (commands held constant over the step).

        ``commands`` are merged into the current ones: a command stays in force until changed
        (e.g. the shaft speed set when the ship was built).

        Raises
        ------
        SimulationDiverged
            If the new state is non-finite or |ν| exceeds ``max_abs_velocity``; the simulator
            keeps the state of the start of the step.
        """
        if commands is not None:
            self.commands = {**self.commands, **commands}
        rhs: Callable = (
            self._rhs_holloway if self.integrator_name == "holloway" else self._rhs_explicit
        )
        q, v, z = self.integrator.step(self.t, self.eta, self.nu, rhs, self.z)
        if z is None:
            z = np.zeros(0)
        bad = not (np.all(np.isfinite(q)) and np.all(np.isfinite(v)) and np.all(np.isfinite(z)))
        if bad or np.max(np.abs(v)) > self.max_abs_velocity:
            raise SimulationDiverged(
                f"state diverged at t = {self.t + self.dt:.3f} s (step {self.n_steps + 1}): "
                f"eta = {np.round(q, 4).tolist()}, nu = {np.round(v, 4).tolist()}; "
                f"try a smaller dt (now {self.dt} s) or another integrator "
                f"(now {self.integrator_name!r})"
            )
        self.t += self.dt
        self.eta, self.nu, self.z = q, v, z
        self.n_steps += 1
        ctx = self._context(self.t, self.eta, self.nu, None)
        for f, sl in zip(self.forces, self._slices, strict=True):
            f.commit(ctx, self.z[sl])

    def force_breakdown(self) -> dict[str, np.ndarray]:
        """Per-force body-axis generalised forces at the current state (plus gravity, Coriolis).

        Not available for lumped-mode models between steps (they need ν̇ₑ); those report the
        force with ν̇ₑ = 0.
        """
        breakdown: dict[str, np.ndarray] = {}
        ctx = self._context(self.t, self.eta, self.nu, np.zeros(6))
        self._generalised_force(ctx, self.z, breakdown)
        breakdown["gravity"] = gravity_force(
            self.hull.mass.mass, self.hull.mass.cog, ctx.rotation, self.hull.g
        )
        breakdown["coriolis"] = -coriolis_force(self.mass_rb, self.nu)
        return breakdown

    def actuator_angle(self, name: str) -> float:
        """Servo angle [rad] of the actuated force model ``name`` at the last accepted step.

        Raises
        ------
        ValueError
            If no force model of that name has a servo.
        """
        for f in self.forces:
            if f.name == name and hasattr(f, "angle"):
                return float(f.angle)
        raise ValueError(
            f"no servo-driven force model named {name!r}; the models are "
            f"{[f.name for f in self.forces]}"
        )

    def elevation_at_ship(self) -> float:
        """Incident-wave elevation at O's horizontal position [m]."""
        if self.wave_field is None:
            return 0.0
        return float(self.wave_field.elevation(self.eta[0], self.eta[1], self.t))

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
        n = steps_in(duration, self.dt)
        rec_t, rec_eta, rec_nu, rec_el = [], [], [], []
        rec_f: dict[str, list[np.ndarray]] = {}

        def record() -> None:
            rec_t.append(self.t)
            rec_eta.append(self.eta.copy())
            rec_nu.append(self.nu.copy())
            rec_el.append(self.elevation_at_ship())
            if record_forces:
                for k, v in self.force_breakdown().items():
                    rec_f.setdefault(k, []).append(v)

        steps = range(n)
        if progress:
            from tqdm import tqdm

            steps = tqdm(steps, desc="simulating", unit="step", mininterval=0.5)
        record()
        for i in steps:
            self.step()
            if (i + 1) % record_every == 0:
                record()
        return SimulationResult(
            np.array(rec_t),
            np.array(rec_eta),
            np.array(rec_nu),
            np.array(rec_el),
            {k: np.array(v) for k, v in rec_f.items()},
        )
