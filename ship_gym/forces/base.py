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

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, NamedTuple

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

    def pack(self, layout: RowLayout) -> RowPart | None:
        """The model on the compiled path: its row kernel and record (:class:`RowPart`).

        ``None`` (the default) or :class:`NotImplementedError` with the reason: the model has
        no kernel (for these options) and the batch runs on the numpy path.
        Called again whenever the engine's layout changes (a new sea, a new loading), so a
        model keeps what must persist (caches, actuator states) in its own arrays and puts
        views of them in the record.
        """
        return None


# =============================================================================================
# the row protocol of the compiled path
# =============================================================================================
class WaveRecord(NamedTuple):
    """The sea of each ship as the compiled loop holds it, (N, n_c) arrays per component j.

    Attributes
    ----------
    amplitude : numpy.ndarray
        aⱼ [m].
    omega_t, phase_t : numpy.ndarray
        ωⱼ/2π [turns/s] and εⱼ/2π [turns].
    ramp_time : numpy.ndarray
        (N,) Matusiak's start-up ramp [s] (0: none).
    kxt, kyt : numpy.ndarray
        kⱼ cos χⱼ/2π, kⱼ sin χⱼ/2π [turns/m].
    k2 : numpy.ndarray
        kⱼ/ln 2 [1/m] (the depth decay as a power of 2).
    kxt32, kyt32, k232 : numpy.ndarray
        float32 copies of kxt, kyt, k2.
    """

    amplitude: NDArray
    omega_t: NDArray
    phase_t: NDArray
    ramp_time: NDArray
    kxt: NDArray
    kyt: NDArray
    k2: NDArray
    kxt32: NDArray
    kyt32: NDArray
    k232: NDArray


class RowContext(NamedTuple):
    """What every row kernel sees of one evaluation of ship ``s`` besides its own record.

    Filled by the engine before the kernels run, in this order: rigid-body terms (``rot``),
    the wave components at the ship's origin (``mod``, ``offset``, ``local``, ``shared[0]``).

    Attributes
    ----------
    rot : numpy.ndarray
        (3, 3) rotation body → earth, R(φ, θ, ψ) [-].
    waves : WaveRecord
        The seas of all ships (row ``s`` is this ship's).
    mod : numpy.ndarray
        (n_c,) moduli r(t) aⱼ of the components at O [m] (r: the start-up ramp).
    offset : numpy.ndarray
        (n_c,) their phase offsets −arg c'ⱼ/2π in [−½, ½] [turns].
    local : numpy.ndarray
        (n_c,) complex amplitudes c'ⱼ at O [m].
    cmd : numpy.ndarray
        (N, n_cmd) the commands in force (columns from :meth:`RowLayout.column`).
    shared : numpy.ndarray
        Scalars passed between kernels within one evaluation: ``shared[0]`` Σⱼ|c'ⱼ| [m] (the
        crest bound of the Froude–Krylov kernel); further slots from :meth:`RowLayout.slot`
        (e.g. the propeller thrust that the rudder's slipstream reads), reset to 0 before the
        kernels run, in the order of the models.
    work : numpy.ndarray
        (6,) scratch for a kernel's own force before it adds it to ``out``.
    """

    rot: NDArray
    waves: WaveRecord
    mod: NDArray
    offset: NDArray
    local: NDArray
    cmd: NDArray
    shared: NDArray
    work: NDArray


class RowPart(NamedTuple):
    """A model on the compiled path: kernels and their record.

    Attributes
    ----------
    kernel : numba dispatcher
        ``kernel(s, t, eta, nu, z, zdot, ctx, rec, out)``: adds the model's body-axis force
        and moment about O [N, N·m] of ship ``s`` at time ``t`` [s], state η (6,), ν (6,) and
        its own ODE states ``z`` (n_states,) to ``out`` (6,), and writes ż into ``zdot``;
        ``ctx`` is the :class:`RowContext`, ``rec`` the record below. Must be
        ``numba.njit(cache=True)`` at module level (the engine imports it by name).
    record : tuple
        The model's parameters for all ships (a tuple or NamedTuple of arrays and scalars;
        per-ship data as rows indexed by ``s``).
    n_states : int
        The model's ODE states per ship (its slice of the engine's ``z``).
    step_start : numba dispatcher or None
        ``step_start(s, t, eta, nu, cmd, rec)`` at the start of each step (commands sampled
        and held over the step: a servo's target).
    step_end : numba dispatcher or None
        ``step_end(s, t, eta, nu, rec)`` after each accepted step, with the new state.
    """

    kernel: Callable[..., Any]
    record: tuple
    n_states: int = 0
    step_start: Callable[..., Any] | None = None
    step_end: Callable[..., Any] | None = None


class RowLayout:
    """What :meth:`BatchForceModel.pack` sees of the engine (one per packing).

    Attributes
    ----------
    n_ships : int
        N.
    n_components : int
        Padded wave component count n_c.
    forward_speed : float
        Steady forward speed U [m/s].
    seas : Any
        The per-ship wave component arrays (``direction``, ``omega``, ``wavenumber``: (N, n_c)
        [rad, rad/s, rad/m]).
    command_keys : list of str
        Command columns of :attr:`RowContext.cmd`, in order.
    command_defaults : list
        Their values when the command is missing (a number, a callable, or None: required).
    slots : dict
        Names of the :attr:`RowContext.shared` slots → index.
    numpy_only_commands : set of str
        Command keys that the compiled kernels do not read as the numpy path does: a call
        with one of them runs on the numpy path.
    """

    def __init__(self, n_ships: int, n_components: int, forward_speed: float, seas: Any) -> None:
        self.n_ships = int(n_ships)
        self.n_components = int(n_components)
        self.forward_speed = float(forward_speed)
        self.seas = seas
        self.command_keys: list[str] = []
        self.command_defaults: list[Any] = []
        self.slots: dict[str, int] = {"crest": 0}
        self.numpy_only_commands: set[str] = set()

    def column(self, key: str, default: Any) -> int:
        """The column of command ``key`` in :attr:`RowContext.cmd` (added if new)."""
        if key in self.command_keys:
            return self.command_keys.index(key)
        self.command_keys.append(key)
        self.command_defaults.append(default)
        return len(self.command_keys) - 1

    def slot(self, name: str) -> int:
        """The index of the shared scalar ``name`` in :attr:`RowContext.shared` (added if new)."""
        return self.slots.setdefault(name, len(self.slots))


_NO_WAVES = WaveRecord._make((
    *(np.zeros((1, 0)) for _ in range(3)), np.zeros(1), *(np.zeros((1, 0)) for _ in range(3)),
    *(np.zeros((1, 0), np.float32) for _ in range(3)),
))  # fmt: skip
"""No wave components (the row-by-row faces of :class:`RowKernelModel`)."""


class RowKernelModel(BatchForceModel, ForceModel):
    """A force written once, as a row kernel: compiled, on the numpy path and for one ship.

    Subclass, set :attr:`kernel` (a module-level ``numba.njit(cache=True)`` function with the
    :class:`RowPart` signature) and override :meth:`record`. The engine's compiled loop calls
    the kernel in its composed step; the numpy path (:meth:`evaluate` with a
    :class:`BatchContext`) and the single-ship :class:`ForceModel` face (:meth:`evaluate` with
    a :class:`ForceContext`) call the **same** kernel row by row, so the paths cannot disagree.
    A kernel that reads the waves at the ship (``ctx.mod``, ``ctx.local``) runs compiled only:
    the row-by-row faces pass no wave components.

    Attributes
    ----------
    kernel : numba dispatcher
        The row kernel.
    """

    kernel: Any = None
    step_start: Any = None
    step_end: Any = None

    def record(self, layout: RowLayout) -> tuple:
        """The kernel's record for ``layout.n_ships`` ships (override)."""
        raise NotImplementedError

    def _static(self, name: str) -> Any:
        """A kernel attribute as the class holds it (a dispatcher on a class is a descriptor
        that would bind the instance as its first argument)."""
        for cls in type(self).__mro__:
            if name in cls.__dict__:
                value = cls.__dict__[name]
                return value.__func__ if isinstance(value, staticmethod) else value
        return getattr(self, name)

    def pack(self, layout: RowLayout) -> RowPart | None:
        kernel = self._static("kernel")
        if kernel is None:
            return None
        return RowPart(
            kernel, self.record(layout), int(self.n_states), self._static("step_start"),
            self._static("step_end"),
        )  # fmt: skip

    def _rows(
        self, n_ships: int, ships: NDArray, t: NDArray, eta: NDArray, nu: NDArray,
        rotation: NDArray, forward_speed: float, commands: Any, states: NDArray,
    ) -> tuple[NDArray, NDArray]:  # fmt: skip
        if self._static("step_start") is not None or self._static("step_end") is not None:
            raise NotImplementedError(f"{self.name!r} has step hooks: it runs compiled only")
        layout = RowLayout(n_ships, 0, forward_speed, None)
        rec = self.record(layout)
        kernel = self._static("kernel")
        cmd = np.zeros((n_ships, max(len(layout.command_keys), 1)))
        for j, (key, default) in enumerate(
            zip(layout.command_keys, layout.command_defaults, strict=True)
        ):
            value = commands.get(key, None)
            if value is None:
                value = default() if callable(default) else default
            if value is None:
                raise ValueError(f"no {key!r} command and no default")
            arr = np.broadcast_to(np.asarray(value, dtype=float), (n_ships,))
            cmd[:, j] = arr
        n = len(ships)
        force = np.zeros((n, 6))
        zdot = np.zeros((n, int(self.n_states)))
        states = np.ascontiguousarray(states, dtype=float).reshape(n, int(self.n_states))
        for i, s in enumerate(ships):
            ctx = RowContext(
                np.ascontiguousarray(rotation[i]), _NO_WAVES, np.zeros(0), np.zeros(0),
                np.zeros(0, np.complex128), cmd, np.zeros(len(layout.slots)), np.zeros(6),
            )  # fmt: skip
            kernel(
                int(s), float(t[i]), np.ascontiguousarray(eta[i]), np.ascontiguousarray(nu[i]),
                states[i], zdot[i], ctx, rec, force[i],
            )  # fmt: skip
        return force, zdot

    def evaluate(self, ctx: Any, states: NDArray) -> tuple[NDArray, NDArray]:
        """The kernel row by row: (n, 6) forces and (n, n_states) ż for a
        :class:`BatchContext`; (6,) and (n_states,) for a :class:`ForceContext`."""
        if isinstance(ctx, BatchContext):
            n_ships = int(np.max(ctx.ships)) + 1 if len(ctx.ships) else 0
            n_ships = max(n_ships, getattr(self, "_n_ships", 0))
            return self._rows(
                n_ships, ctx.ships, np.broadcast_to(ctx.t, (ctx.n,)), ctx.eta, ctx.nu,
                ctx.rotation, ctx.forward_speed, ctx.commands, states,
            )  # fmt: skip
        force, zdot = self._rows(
            1, np.zeros(1, np.int64), np.array([ctx.t]), np.atleast_2d(ctx.eta),
            np.atleast_2d(ctx.nu), ctx.rotation[None], ctx.forward_speed, ctx.commands,
            np.atleast_2d(states),
        )  # fmt: skip
        return force[0], zdot[0]

    def bind(self, n_ships: int, n_comp: int) -> None:
        self._n_ships = int(n_ships)

    def reset(self, *args: Any) -> None:
        """Nothing to forget (a model with memory overrides this)."""

    def commit(self, *args: Any) -> None:
        """Nothing to record (a model with memory overrides this)."""

    def initial_states(self, ships: Any = None) -> NDArray:
        """Zeros: (n_states,) for one ship, (len(ships), n_states) for rows of ships."""
        if ships is None:
            return np.zeros(int(self.n_states))
        return np.zeros((len(ships), int(self.n_states)))
