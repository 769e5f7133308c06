"""The force protocol, for one ship (:class:`ForceModel`) and for rows of N ships
(:class:`BatchForceModel`, what the engine runs), and the per-evaluation contexts they share.

A force model returns a generalised force (Fx, Fy, Fz, Mx, My, Mz) in **body axes about the body
origin O** (:mod:`ship_gym.conventions`) for the instantaneous state. Models with memory carry it
either

* as extra first-order ODE states ``z`` (``n_states > 0``) integrated with the ship by the same
  integrator (``evaluate`` returns their derivative) — e.g. the state-space radiation memory; or
* as a history updated only on accepted steps in :meth:`ForceModel.commit` — e.g. the direct
  convolution of the retardation function.

Everything that several models need at one evaluation (rotation matrix, wave phasors at the ship,
the steady forward speed, the rudder/fin commands) is computed once by the simulator and passed in
a :class:`ForceContext`.

Kring–Huang–Sclavounos (their eq. 3): the instantaneous (infinite-frequency) added mass is kept on
the left-hand side of the equations of motion; a model that contributes such a term declares it in
:attr:`ForceModel.added_mass` and must then *not* include it in its force.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray


@dataclass
class ForceContext:
    """Quantities shared by all force models at one evaluation (built by the simulator).

    Attributes
    ----------
    t : float
        Time [s].
    eta : numpy.ndarray
        (6,) position of O (NED) [m] and zyx Euler angles [rad].
    nu : numpy.ndarray
        (6,) body velocities (u, v, w, p, q, r) [m/s, rad/s].
    rotation : numpy.ndarray
        (3, 3) body-to-earth rotation matrix R(φ, θ, ψ).
    forward_speed : float
        Steady forward speed U [m/s] about which radiation is linearised (perturbation velocity
        ν − (U, 0, 0, 0, 0, 0)).
    wave_phasor : numpy.ndarray or None
        (n,) complex amplitudes cⱼ(t) of the incident components [m], ramp included
        (:meth:`ship_gym.waves.WaveField.phasor`); None in calm water.
    commands : dict
        Actuator commands (rudder angle [rad], fin angles [rad], shaft speed [rev/s], …).
    shared : dict
        Quantities that a model derives during this evaluation for models after it in the
        simulator's list (models are evaluated in list order), e.g. ``"propeller_thrust"`` [N]
        published by the propeller for the rudder's slipstream. Fresh at every evaluation.
    """

    t: float
    eta: np.ndarray
    nu: np.ndarray
    rotation: np.ndarray
    forward_speed: float = 0.0
    wave_phasor: np.ndarray | None = None
    commands: dict = field(default_factory=dict)
    shared: dict = field(default_factory=dict)


class ForceModel:
    """Base class of force models (subclass and override; all methods have safe defaults).

    Attributes
    ----------
    name : str
        Key of this force in the simulator's per-force breakdown.
    n_states : int
        Number of extra first-order states the model integrates with the ship.
    added_mass : numpy.ndarray or None
        (6, 6) instantaneous added mass this model moves to the left-hand side [kg, kg·m,
        kg·m²], or None.
    """

    name: str = "force"
    n_states: int = 0
    added_mass: np.ndarray | None = None

    def initial_states(self) -> np.ndarray:
        """Initial values of the model's ODE states (length :attr:`n_states`)."""
        return np.zeros(self.n_states)

    def reset(self, t0: float, ctx: ForceContext) -> None:
        """Forget all memory; called when a simulation (re)starts at time ``t0``."""

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Generalised force and state derivatives.

        Parameters
        ----------
        ctx : ForceContext
            The shared evaluation context.
        states : numpy.ndarray
            The model's own ODE states (length :attr:`n_states`).

        Returns
        -------
        force : numpy.ndarray
            (6,) force [N] and moment about O [N·m] in body axes.
        states_dot : numpy.ndarray
            (n_states,) time derivative of the states.
        """
        raise NotImplementedError

    def commit(self, ctx: ForceContext, states: np.ndarray) -> None:
        """Record an accepted step (state at the *end* of the step); default: nothing."""


# =============================================================================================
# rows of N ships (the engine's protocol)
# =============================================================================================
@dataclass
class BatchWaves:
    """Per-row wave component arrays of the ships in a :class:`BatchContext` (zero-padded).

    Attributes
    ----------
    wavenumber, omega, direction : numpy.ndarray
        (n, n_comp) kⱼ [rad/m], ωⱼ [rad/s], χⱼ [rad].
    cos_direction, sin_direction : numpy.ndarray
        (n, n_comp) cos χⱼ, sin χⱼ.
    kx, ky : numpy.ndarray
        (n, n_comp) kⱼ cos χⱼ, kⱼ sin χⱼ [rad/m].
    n_components : numpy.ndarray
        (n,) number of real (unpadded) components of each ship's sea.
    """

    wavenumber: NDArray
    omega: NDArray
    direction: NDArray
    cos_direction: NDArray
    sin_direction: NDArray
    kx: NDArray
    ky: NDArray
    n_components: NDArray


@dataclass
class BatchContext:
    """Quantities shared by the batch force models at one evaluation (rows = ``ships``).

    Attributes
    ----------
    ships : numpy.ndarray
        (n,) indices into the batch of the rows evaluated (all ships, or a subset: ships in
        their integrator start-up, or the ships not frozen by divergence).
    all_ships : bool
        True when the rows are exactly ships 0…N−1 (models may skip fancy indexing).
    t : numpy.ndarray
        (n,) times [s] (each ship has its own clock).
    eta, nu : numpy.ndarray
        (n, 6) positions/Euler angles and body velocities.
    rotation : numpy.ndarray
        (n, 3, 3) body-to-earth rotation matrices.
    forward_speed : float
        Steady forward speed U [m/s] (shared).
    wave_phasor : numpy.ndarray
        (n, n_comp) complex cⱼ(t) [m], ramp included (zeros for padding and calm seas).
    local_phasor : numpy.ndarray
        (n, n_comp) the phasors folded to each ship's O, c'ⱼ = cⱼ(t) e^{−i kⱼ (x cos χⱼ +
        y sin χⱼ)} (:meth:`WaveComponents.local_amplitudes`): ζ(O, t) = Re Σⱼ c'ⱼ.
    waves : BatchWaves
        The rows' wave component arrays.
    commands : dict
        Actuator commands: arrays with a leading axis over **all** N ships (take
        ``value[ctx.ships]``, :meth:`rows`) or scalars shared by all ships.
    shared : dict
        Quantities a model derives during this evaluation for the models after it (fresh at
        every evaluation, like :attr:`ForceContext.shared`); :class:`PerShipForceModel` keeps
        one dict per ship in it.
    """

    ships: NDArray[np.int64]
    all_ships: bool
    t: NDArray
    eta: NDArray
    nu: NDArray
    rotation: NDArray
    forward_speed: float
    wave_phasor: NDArray
    local_phasor: NDArray
    waves: BatchWaves
    commands: dict = field(default_factory=dict)
    shared: dict = field(default_factory=dict)

    def rows(self, array: NDArray) -> NDArray:
        """``array[ships]`` for an array with a leading axis over all N ships."""
        return array if self.all_ships else array[self.ships]

    @property
    def n(self) -> int:
        """Number of rows."""
        return int(self.t.shape[0])


class BatchForceModel:
    """Protocol of force models acting on many ships at once (subclass and override).

    Like :class:`ship_gym.forces.base.ForceModel` with a leading batch axis: ``evaluate``
    returns body-axis forces about O, (n, 6), and state derivatives (n, n_states) for the rows
    of the context. Per-ship internal data (caches, histories) is indexed by ``ctx.ships``.

    Attributes
    ----------
    name : str
        Key of the force in breakdowns.
    n_states : int
        Extra first-order states per ship.
    added_mass : numpy.ndarray or None
        (6, 6) instantaneous added mass moved to the left-hand side (shared by all ships).
    """

    name: str = "force"
    n_states: int = 0
    added_mass: NDArray | None = None

    def bind(self, n_ships: int, n_comp: int) -> None:
        """Called once by the simulator: batch size and padded wave component count."""

    def initial_states(self, ships: NDArray[np.int64]) -> NDArray:
        """(len(ships), n_states) initial values of the states of ``ships`` (default zeros)."""
        return np.zeros((len(ships), self.n_states))

    def reset(self, ships: NDArray[np.int64], ctx: BatchContext) -> None:
        """Forget the memory of ``ships`` (a reset of those ships at ``ctx.t``)."""

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        """(n, 6) body-axis force and moment about O, and (n, n_states) state derivatives."""
        raise NotImplementedError

    def commit(self, ctx: BatchContext, states: NDArray) -> None:
        """Record accepted steps of the rows of ``ctx`` (state at the end of the step)."""
