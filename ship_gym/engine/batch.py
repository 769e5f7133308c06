"""The engine: N ≥ 1 ships of one setup, each in its own sea, stepped together.

:class:`BatchSimulator` advances N ships that share the hull, the hydrodynamic database and the
force-model setup, but each has its own wave field (zero-padded to a common component count,
:func:`ship_gym.waves.wave_field.stack_fields`), its own state, its own time and its own
integrator history; one ship is N = 1 (:class:`ship_gym.engine.simulator.Simulator` is that
view). The equations (Kring–Huang–Sclavounos form, instantaneous added mass on the left) are
written with a leading batch axis:

    (M_RB + A_lhs) ν̇ₛ = Σᵢ Fᵢ(tₛ, ηₛ, νₛ, zₛ) + F_gravity(ηₛ) − C_RB(νₛ) νₛ,   η̇ₛ = J(ηₛ) νₛ,

with arrays ``eta`` (N, 6), ``nu`` (N, 6), ``z`` (N, n_states). One force evaluation is one
call per force model for all ships:

* Froude–Krylov + hydrostatics: one batched fast-kernel call
  (:func:`ship_gym.forces.froude_krylov.froude_krylov_hydrostatic_batch`);
* state-space radiation memory: the single-ship model's fitted A, B, C, D (ż = A z + B ν_p,
  μ = C z + D ν_p) applied to all ships in one compiled loop over their non-zeros (A is
  block-diagonal with 1×1/2×2 blocks: O(N · n_states), no BLAS call);
* diffraction: ships × components, with the single-ship model's per-heading cache of
  X_D(ω'ⱼ, βⱼ) kept per ship (refreshed when that ship's heading moved by more than the
  tolerance, exactly as :class:`ship_gym.forces.diffraction.Diffraction` does);
* viscous roll damping: numpy; rotation matrices, gravity, Coriolis–centripetal terms and
  kinematics J(η)ν: one fused numba loop over ships; the wave phasors cⱼ(t) (ramp included)
  and their folding to each ship's O: one numba loop over ships × components.

Ship s of a batch follows the trajectory it has alone (tested to 1e-9 relative over hundreds of
steps; ≈ 1e-14 observed; bit for bit on the compiled backend). The phasors are recomputed with
trig at every evaluation (2 × N × n_comp sin/cos): cheap next to the hull-panel sum, and it
keeps per-ship clocks and RK4 stage times trivial.

Two paths run the same row models: the compiled backend (:mod:`ship_gym.engine.compiled`, K
steps of all ships in one numba call) and the numpy path below (one call per model per
evaluation), which also runs models without a compiled version (:class:`PerShipForceModel`:
the Cummins convolution, added resistance in waves, a user's own :class:`ForceModel`).

Integrators
-----------
``"rk4"`` (4 evaluations per step) and ``"holloway"`` (Holloway's μ-Taylor scheme, 1 evaluation
per step after a 2-step RK4 start-up; the arithmetic of
:class:`ship_gym.numerics.integrators.HollowayIntegrator` on batch arrays, μ = 1 by default: the
acceleration is exact, the added mass being on the left). Histories are per ship, so a ship that
is reset restarts its own start-up while the others go on with one evaluation per step: the
start-up ships' extra RK4 stages are evaluated for those ships only.

Per-ship control
----------------
* :meth:`BatchSimulator.reset` resets a subset of ships (state, time, memory states,
  integrator history, optionally a new sea) and leaves the others untouched — the autoreset of
  a vector env.
* :meth:`BatchSimulator.step` takes ``commands``, a dict of arrays with a leading batch axis
  (e.g. ``{"rudder": (N,) angles}``), handed to every batch force model in the context;
  :class:`PerShipForceModel` wraps ordinary single-ship :class:`ForceModel` objects (one per
  ship, looped in Python) so that any actuator model can be used before a vectorised version
  exists.
* Divergence is detected per ship: a ship whose new state is non-finite or too fast is frozen at
  the state of the start of the failed step, flagged in :attr:`BatchSimulator.diverged` with a
  message in :attr:`BatchSimulator.divergence_messages`, and skipped until it is reset; the
  others continue.

"""

from __future__ import annotations

import copy
import math
import time
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, Literal, NamedTuple

import numba as nb
import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.conventions import ROLL, SURGE
from ship_gym.engine.batch_control import batch_control_model, trim_batch_shaft_speed
from ship_gym.engine.results import SimulationDiverged, SimulationResult, steps_in
from ship_gym.engine.rigid_body import healthy_state, left_hand_side, rigid_body_terms
from ship_gym.engine.ship import Sea, ShipSetup, build_force_models, database_of, ship_of
from ship_gym.forces.base import (
    BatchContext,
    BatchForceModel,
    BatchWaves,
    ForceContext,
    ForceModel,
    RowLayout,
    RowPart,
)
from ship_gym.forces.diffraction import (
    CACHE_COLUMNS,
    Diffraction,
    DiffractionRecord,
    diffraction_force,
    diffraction_row,
    refresh_diffraction_cache,
)
from ship_gym.forces.froude_krylov import (
    FroudeKrylovHydrostatics,
    HullPanels,
    WaveComponents,
    froude_krylov_hydrostatic,
    froude_krylov_hydrostatic_batch,
    froude_krylov_record,
    froude_krylov_row,
)
from ship_gym.forces.radiation import (
    ConstantCoefficientRadiation,
    RadiationMemory,
    radiation_record,
    radiation_row,
    speed_momentum_rows,
    state_space_radiation,
)
from ship_gym.forces.viscous import ViscousRollDamping, viscous_roll_row
from ship_gym.hull import equilibrium
from ship_gym.hull.hull import Hull
from ship_gym.hydro.forward_speed import SpeedTerms, check_speed_cutoff, check_speed_terms
from ship_gym.numerics.angles import wrap_angle_scalar
from ship_gym.typing import IntegratorName
from ship_gym.waves.wave_field import WaveField, stack_fields

if TYPE_CHECKING:
    from ship_gym.engine.compiled import StepReductions

EngineBackend = Literal["auto", "compiled", "numpy"]
"""``"compiled"``: K steps of all ships in one numba call (:mod:`ship_gym.engine.compiled`);
``"numpy"``: the reference path (one call per force model per evaluation); ``"auto"``:
compiled when every model has a compiled version."""

__all__ = [
    "BatchConstantRadiation",
    "BatchContext",
    "BatchDiffraction",
    "BatchForceModel",
    "BatchFroudeKrylov",
    "BatchSimulator",
    "BatchStateSpaceRadiation",
    "BatchViscousRoll",
    "PerShipForceModel",
    "batch_force_models",
    "build_batch_simulator",
]


_TWO_PI = 2.0 * math.pi
_HOLLOWAY_STARTUP = 2  # RK4 steps before μ-Taylor steps (HollowayIntegrator, startup="rk4")


# =============================================================================================
# sea arrays and context
# =============================================================================================
class _Seas:
    """Mutable (N, n_comp) component arrays of the ships' seas, zero-padded."""

    def __init__(self, fields: Sequence[WaveField | None], n_comp: int | None) -> None:
        seas = [WaveField.calm() if f is None else f for f in fields]
        stack = stack_fields(seas)
        n = max(1, stack.n_components, int(n_comp or 0))
        n_ships = stack.n_fields
        self.n_ships = n_ships
        self.n_comp = n

        def pad(a: NDArray) -> NDArray:
            out = np.zeros((n_ships, n))
            out[:, : a.shape[1]] = a
            return out

        self.amplitude = pad(stack.amplitude)
        self.omega = pad(stack.omega)
        self.wavenumber = pad(stack.wavenumber)
        self.direction = pad(stack.direction)
        self.phase = pad(stack.phase)
        self.kx = pad(stack.kx)
        self.ky = pad(stack.ky)
        self.cos_direction = np.cos(self.direction)
        self.sin_direction = np.sin(self.direction)
        self.ramp_time = np.array(stack.ramp_time, dtype=float)
        self.n_components = np.array([f.n_components for f in seas], dtype=np.int64)

    def replace(self, ship: int, wave_field: WaveField | None) -> None:
        f = WaveField.calm() if wave_field is None else wave_field
        if not isinstance(f, WaveField):
            raise ValueError(f"wave_field must be a WaveField or None; got {type(f).__name__}")
        m = f.n_components
        if m > self.n_comp:
            raise ValueError(
                f"wave field of ship {ship} has {m} components, more than the batch's padded "
                f"count {self.n_comp}; build the BatchSimulator with max_components ≥ {m}"
            )
        for name in ("amplitude", "omega", "wavenumber", "direction", "phase", "kx", "ky"):
            row = getattr(self, name)[ship]
            row[:] = 0.0
            row[:m] = getattr(f, name)
        self.cos_direction[ship] = np.cos(self.direction[ship])
        self.sin_direction[ship] = np.sin(self.direction[ship])
        self.ramp_time[ship] = f.ramp_time
        self.n_components[ship] = m


# =============================================================================================
# batch force models
# =============================================================================================
def _no_states(n: int) -> NDArray:
    return np.zeros((n, 0))


def _to_body(rotation: NDArray, f_earth: NDArray) -> NDArray:
    """(n, 6) body-axis force/moment from earth-axis ones: Rᵀ F, Rᵀ M."""
    out = np.empty_like(f_earth)
    _earth_to_body(rotation, f_earth, out)
    return out


class BatchFroudeKrylov(BatchForceModel):
    """Nonlinear Froude–Krylov + hydrostatics for all ships: one batched kernel call.

    Parameters
    ----------
    panels : HullPanels
        Shared hull geometry.
    rho, g : float
        Water density [kg/m³] and gravity [m/s²].
    method : {"fast", "fast32", "reference"}
        ``"fast"``: :func:`froude_krylov_hydrostatic_batch` (one call per evaluation);
        ``"fast32"``: the same with the wave sums in float32 (``single_precision=True``);
        ``"reference"``: the numpy reference, looped over ships (for checks only).
    parallel : bool
        Ask the batched kernel for its numba-threaded variant (ships over threads; threads as
        numba has them — mind torch's in the same process, DESIGN.md §5). Default serial.
    """

    name = "froude_krylov_hydrostatic"

    def __init__(
        self,
        panels: HullPanels,
        *,
        rho: float,
        g: float,
        method: str = "fast",
        parallel: bool = False,
    ) -> None:
        if method not in ("fast", "fast32", "reference"):
            raise ValueError(f"method must be 'fast', 'fast32' or 'reference', got {method!r}")
        self.parallel = bool(parallel)
        self.panels = panels
        self.rho = float(rho)
        self.g = float(g)
        self.method = method

    @classmethod
    def from_model(cls, model: FroudeKrylovHydrostatics) -> BatchFroudeKrylov:
        """The batch version of a single-ship model (its hull; its sea is not used)."""
        return cls(model.panels, rho=model.hull.rho, g=model.hull.g, method=model.method)

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        w = ctx.waves
        amp = ctx.local_phasor  # WaveComponents.local_amplitudes, all ships at once
        if self.method in ("fast", "fast32"):
            extra = {"parallel": True} if self.parallel else {}
            if self.method == "fast32":
                extra["single_precision"] = True
            f = froude_krylov_hydrostatic_batch(
                self.panels,
                w.wavenumber,
                w.cos_direction,
                w.sin_direction,
                amp,
                ctx.eta[:, 2],
                ctx.rotation,
                rho=self.rho,
                g=self.g,
                **extra,
            )
        else:
            f = np.empty((ctx.n, 6))
            for i in range(ctx.n):
                m = int(w.n_components[i]) or 1
                waves = WaveComponents(
                    np.ascontiguousarray(w.wavenumber[i, :m]),
                    np.ascontiguousarray(w.cos_direction[i, :m]),
                    np.ascontiguousarray(w.sin_direction[i, :m]),
                )
                f[i] = froude_krylov_hydrostatic(
                    self.panels,
                    waves,
                    ctx.wave_phasor[i, :m],
                    ctx.eta[i, :3],
                    ctx.rotation[i],
                    rho=self.rho,
                    g=self.g,
                    method="reference",
                )
        return _to_body(ctx.rotation, f), _no_states(ctx.n)

    def pack(self, layout: RowLayout) -> RowPart | None:
        if self.method == "reference":
            raise NotImplementedError("the reference Froude–Krylov kernel is numpy only")
        record = froude_krylov_record(
            self.panels._layout, self.rho * self.g, self.method == "fast32"
        )
        return RowPart(froude_krylov_row, record)


def _csr(matrix: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """(indptr, indices, values) of the non-zeros of a dense matrix, row by row."""
    m = np.asarray(matrix, float)
    rows, cols = np.nonzero(m)
    ptr = np.zeros(m.shape[0] + 1, dtype=np.int64)
    np.add.at(ptr, rows + 1, 1)
    return np.cumsum(ptr), cols.astype(np.int64), np.ascontiguousarray(m[rows, cols])


@nb.njit(cache=True)
def _state_space_rows(
    v, z, speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat, has_d,
    p_inf, p_mem, cutoff, force, zdot,
):  # fmt: skip  # pragma: no cover - compiled
    """:func:`ship_gym.forces.radiation.state_space_radiation` per row (force zeroed first)."""
    for s in range(z.shape[0]):
        for o in range(6):
            force[s, o] = 0.0
        state_space_radiation(
            v[s], z[s], speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val,
            d_mat, has_d, p_inf, p_mem, cutoff, force[s], zdot[s],
        )  # fmt: skip


class BatchStateSpaceRadiation(BatchForceModel):
    """Radiation memory by the fitted state-space system, all ships in one compiled loop.

    Force −(C z + D ν_p) and ż = A z + B ν_p per ship (rows of z), ν_p = ν − (U, 0, …, 0);
    A(∞) on the left-hand side (:class:`ship_gym.forces.radiation.RadiationMemory`,
    ``method="state_space"``). A is block-diagonal with 1×1 and 2×2 blocks and B has one
    non-zero per state (modal realisation), so the products are done on the non-zeros (CSR)
    in a numba loop: O(N · n_states), and no BLAS call (a multi-threaded BLAS on a loaded
    2-core machine made a dense (64 × 129) @ (129 × 129) product take many times longer than on
    an idle one; docs/benchmarks.md).
    """

    name = "radiation"

    def __init__(
        self,
        a: NDArray,
        b: NDArray,
        c: NDArray,
        d: NDArray,
        a_inf: NDArray,
        speed_terms: SpeedTerms = "all",
        *,
        momentum: tuple[NDArray, NDArray] | None = None,
        speed_cutoff: float = 0.0,
    ) -> None:
        a, b, c, d = (np.asarray(x, float) for x in (a, b, c, d))
        n = a.shape[0]
        if a.shape != (n, n) or b.shape != (n, 6) or c.shape != (6, n) or d.shape != (6, 6):
            raise ValueError(
                f"state-space shapes A {a.shape}, B {b.shape}, C {c.shape}, D {d.shape}; "
                "expected (n, n), (n, 6), (6, n), (6, 6)"
            )
        self.speed_terms: SpeedTerms = check_speed_terms(speed_terms)
        self.speed_cutoff = check_speed_cutoff(speed_cutoff)
        """ω_c [rad/s] of the Kirchhoff moment's high-pass (0: none; else two more states)."""
        n_filter = 2 if self.speed_cutoff > 0.0 else 0
        rows: tuple[NDArray, NDArray] = (
            speed_momentum_rows(a_inf, a, b, c, speed_terms) if momentum is None else momentum
        )
        self.momentum_added_mass, self.momentum_memory = rows
        """(2, 6) and (2, n): the pitch and yaw rows of Lᵀ A(∞) and Lᵀ C A⁻¹
        (:mod:`ship_gym.hydro.forward_speed` eq. 2)."""
        surge = -np.linalg.solve(a, b[:, SURGE]) if n else np.zeros(0)
        self._surge_steady = np.concatenate([surge, np.zeros(n_filter)])
        """z per m/s of a steady surge perturbation, −A⁻¹ B e₁ (:meth:`steady_surge_states`)."""
        self.matrices = (a, b, c)
        """The dense A (n, n), B (n, 6), C (6, n) of the fit."""
        self.feedthrough = d
        """D (6, 6) of the fit."""
        self._a = _csr(a)
        self._b = _csr(b)
        self._c = _csr(c)
        self._d = np.ascontiguousarray(d)
        self._has_d = bool(np.any(d != 0.0))
        self.n_states = int(n) + n_filter
        self.added_mass = np.asarray(a_inf, float)

    def steady_surge_states(self, surge_offset: NDArray) -> NDArray:
        """Memory states (n, n_states) of ships that have run at U + ``surge_offset`` [m/s] for
        ever: z = −A⁻¹ B e₁ (u − U), so that a ship reset at another speed than the engine's
        U starts without the transient of a surge step (its steady memory force is the fit's
        B(0) (u − U) ≈ 0)."""
        offset = np.asarray(surge_offset, dtype=float).reshape(-1)
        return offset[:, None] * self._surge_steady[None, :]

    @classmethod
    def from_model(cls, model: RadiationMemory) -> BatchStateSpaceRadiation:
        """Reuse the fitted matrices of a single-ship ``RadiationMemory(method="state_space")``."""
        if model.method != "state_space" or model.state_space is None:
            raise NotImplementedError(
                "the Cummins convolution has no row version; it runs per ship "
                "(PerShipForceModel) on the engine's numpy path"
            )
        ss = model.state_space
        return cls(
            ss.A, ss.B, ss.C, ss.D, model.A_inf, model.speed_terms,
            momentum=(model.momentum_added_mass, model.momentum_memory),
            speed_cutoff=model.speed_cutoff,
        )  # fmt: skip

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        force = np.empty((ctx.n, 6))
        zdot = np.empty((ctx.n, self.n_states))
        _state_space_rows(
            ctx.nu, np.ascontiguousarray(states), ctx.forward_speed, *self._a, *self._b,
            *self._c, self._d, self._has_d, self.momentum_added_mass, self.momentum_memory,
            self.speed_cutoff, force, zdot,
        )  # fmt: skip
        return force, zdot

    def pack(self, layout: RowLayout) -> RowPart | None:
        record = radiation_record(
            layout.forward_speed, self.matrices, self.feedthrough,
            (self.momentum_added_mass, self.momentum_memory), self.speed_cutoff,
        )  # fmt: skip
        return RowPart(radiation_row, record, self.n_states)


class BatchConstantRadiation(BatchForceModel):
    """Matusiak's constant-coefficient radiation (case 2a/2b): force −B_c ν_p, A_c on the left."""

    name = "radiation"

    def __init__(self, added_mass: NDArray, damping: NDArray) -> None:
        self.added_mass = np.asarray(added_mass, float)
        self.damping = np.asarray(damping, float)
        """B_c (6, 6) [N·s/m, …]."""
        self._bt = np.ascontiguousarray(self.damping.T)

    @classmethod
    def from_model(cls, model: ConstantCoefficientRadiation) -> BatchConstantRadiation:
        """Same coefficients as a single-ship model."""
        return cls(model.added_mass, model.damping)

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        vp = ctx.nu.copy()
        vp[:, SURGE] -= ctx.forward_speed
        return -(vp @ self._bt), _no_states(ctx.n)

    def pack(self, layout: RowLayout) -> RowPart | None:
        # constant coefficients (Matusiak 2a/2b): D = B_c, no states, no momentum terms
        return RowPart(radiation_row, radiation_record(layout.forward_speed, None, self.damping))


@nb.njit(cache=True)
def _stale_headings(ships, psi, psi_ref, tol, out):  # pragma: no cover
    """The single-ship cache rule per row: no cache or |Δψ| > tol (wrapped)."""
    for r in range(ships.shape[0]):
        ref = psi_ref[ships[r]]
        out[r] = np.isnan(ref) or abs(wrap_angle_scalar(psi[r] - ref)) > tol


@nb.njit(cache=True)
def _diffraction_rows(ships, psi, u, local, xd, dxd, ref, out):  # pragma: no cover
    """:func:`ship_gym.forces.diffraction.diffraction_force` per row (X_D cached per ship;
    ``u`` the rows' surge velocities [m/s]; ``ref`` (N, 2) the caches' heading and speed)."""
    for r in range(ships.shape[0]):
        s = ships[r]
        for o in range(6):
            out[r, o] = 0.0
        diffraction_force(psi[r], u[r], local[r], xd[s], dxd[s], ref[s], out[r])


class BatchDiffraction(BatchForceModel):
    """Linear diffraction F_D = Re Σⱼ X_D(ω'ⱼ, βⱼ) conj(c'ⱼ) for all ships (numpy, ships × comps).

    The transfer functions come from a single-ship :class:`Diffraction` model (its table,
    interpolation, frequency choice and heading tolerance); the per-component cache of X_D is
    kept per ship and refreshed when that ship's heading has moved by more than the tolerance
    since its last refresh (the single-ship rule).

    Parameters
    ----------
    template : Diffraction
        Supplies :meth:`Diffraction.diffraction_transfer` and the options (its own wave field
        is not used).
    """

    name = "diffraction"

    def __init__(self, template: Diffraction) -> None:
        if not isinstance(template, Diffraction):
            raise ValueError(f"template must be a Diffraction model; got {type(template).__name__}")
        self.template = template
        self.tolerance = template.heading_tolerance
        """Heading change [rad] beyond which a ship's cache is refreshed."""
        self.encounter = template.frequency == "encounter"
        """Whether X_D is looked up at the encounter frequency."""
        table, beta = template.interpolation_table()
        self.lookup: tuple[NDArray, NDArray, NDArray] = (
            np.ascontiguousarray(table, dtype=np.complex128),
            np.ascontiguousarray(beta, dtype=float),
            np.ascontiguousarray(template.omega, dtype=float),
        )
        """The bilinear look-up's table X_D (n_ω, n_β + 2, 6), its headings and frequencies:
        the arguments of :func:`~ship_gym.forces.diffraction.refresh_diffraction_cache`, shared
        by this model's numpy path and the compiled backend."""
        grid, mass = template.complex_mass
        self.speed_correction: tuple[NDArray, NDArray, NDArray] = (
            np.ascontiguousarray(template.kirchhoff, dtype=float),
            np.ascontiguousarray(grid, dtype=float),
            np.ascontiguousarray(mass, dtype=np.complex128),
        )
        """The speed correction's parameters and complex-mass table
        (:func:`ship_gym.forces.diffraction.kirchhoff_parameters`,
        :attr:`ship_gym.forces.diffraction.Diffraction.complex_mass`)."""
        self.bind(1, 1)

    def bind(self, n_ships: int, n_comp: int) -> None:
        self._ref = np.full((n_ships, 2), np.nan)
        self._xd = np.zeros((n_ships, n_comp, CACHE_COLUMNS), dtype=complex)
        self._dxd = np.zeros((n_ships, n_comp, CACHE_COLUMNS), dtype=complex)

    @property
    def caches(self) -> tuple[NDArray, NDArray, NDArray]:
        """The per-ship caches (X_D with the moment factors (N, n_c, 8), their ∂/∂ψ, and the
        reference heading [rad] and the ship's speed U_s [m/s] (N, 2)): the arrays themselves,
        shared with the compiled backend."""
        return self._xd, self._dxd, self._ref

    def reset(self, ships: NDArray[np.int64], ctx: BatchContext) -> None:
        # the speed of the linearisation: each ship's surge velocity at its reset
        # (ship_gym.forces.diffraction, "Interpolation and caching")
        self._ref[ships, 0] = np.nan
        self._ref[ships, 1] = ctx.nu[:, SURGE]

    def _refresh(self, ships: NDArray[np.int64], psi: NDArray, ctx: BatchContext, rows) -> None:
        # the compiled backend's own refresh (one implementation of the look-up: a ship's cache
        # is bit-identical whichever path filled it, so a reset and replay reproduces a run)
        w = ctx.waves
        must_raise = self.template.above_range == "raise"
        work = np.zeros((3, w.direction.shape[1], CACHE_COLUMNS), np.complex128)
        count = np.zeros(1, np.int64)
        for ship, row, heading in zip(ships, rows, psi, strict=True):
            speed = self._ref[ship, 1]
            if np.isnan(speed):  # never reset: the engine's speed
                speed = float(ctx.forward_speed)
            args = (
                *self.lookup, np.ascontiguousarray(w.direction[row], dtype=float),
                np.ascontiguousarray(w.omega[row], dtype=float),
                np.ascontiguousarray(w.wavenumber[row], dtype=float), self.encounter,
                *self.speed_correction, float(self.template.heading_step), must_raise, work,
                count,
            )  # fmt: skip
            if not refresh_diffraction_cache(
                float(heading), float(speed), args, self._xd[ship], self._dxd[ship],
                self._ref[ship],
            ):  # fmt: skip
                # a component above ω_max with above_range="raise": the model's own error
                self.template.heading_expansion(
                    w.direction[row], w.omega[row], w.wavenumber[row], float(heading),
                    float(speed),
                )  # fmt: skip
                raise AssertionError("the diffraction model accepted what its kernel refused")

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        psi = np.ascontiguousarray(ctx.eta[:, 5])
        u = np.ascontiguousarray(ctx.nu[:, SURGE])
        stale = np.empty(ctx.n, dtype=np.bool_)
        _stale_headings(ctx.ships, psi, self._ref[:, 0], self.tolerance, stale)
        if stale.any():
            rows = np.flatnonzero(stale)
            self._refresh(ctx.ships[rows], psi[rows], ctx, rows)
        force = np.empty((ctx.n, 6))
        _diffraction_rows(
            ctx.ships, psi, u, ctx.local_phasor, self._xd, self._dxd, self._ref, force
        )
        return force, _no_states(ctx.n)

    def pack(self, layout: RowLayout) -> RowPart | None:
        if self.template.above_range == "raise":  # the model's own error needs the numpy path
            raise NotImplementedError("Diffraction(above_range='raise') is numpy only")
        n, n_c, seas = layout.n_ships, layout.n_components, layout.seas
        work = getattr(self, "_row_work", None)
        if work is None or work[0].shape != (n, 3, n_c, CACHE_COLUMNS):
            # per ship: ships refresh concurrently in the parallel loop
            work = (np.zeros((n, 3, n_c, CACHE_COLUMNS), np.complex128), np.zeros(n, np.int64))
            self._row_work = work
        c = np.ascontiguousarray
        record = DiffractionRecord(
            *self.lookup, c(seas.direction, float), c(seas.omega, float),
            c(seas.wavenumber, float), self.encounter, *self.speed_correction,
            float(self.template.heading_step), float(self.tolerance),
            float(layout.forward_speed), self._xd, self._dxd, self._ref, *work,
        )  # fmt: skip
        return RowPart(diffraction_row, record)

    @property
    def refresh_count(self) -> int:
        """Cache refreshes inside the compiled loop since the model was first packed."""
        work = getattr(self, "_row_work", None)
        return 0 if work is None else int(work[1].sum())


class BatchViscousRoll(BatchForceModel):
    """Viscous roll damping −(B1 p + B2 |p| p) in roll for all ships."""

    name = "viscous_roll"

    def __init__(self, b1: float, b2: float, *, name: str = "viscous_roll") -> None:
        self.b1 = float(b1)
        self.b2 = float(b2)
        self.name = name

    @classmethod
    def from_model(cls, model: ViscousRollDamping) -> BatchViscousRoll:
        """Same coefficients as a single-ship model."""
        c = model.coefficients
        return cls(c.b1, c.b2, name=model.name)

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        p = ctx.nu[:, ROLL]
        force = np.zeros((ctx.n, 6))
        force[:, ROLL] = -(self.b1 * p + self.b2 * np.abs(p) * p)
        return force, _no_states(ctx.n)

    def pack(self, layout: RowLayout) -> RowPart | None:
        return RowPart(viscous_roll_row, (self.b1, self.b2))


class PerShipForceModel(BatchForceModel):
    """Adapter: one ordinary single-ship :class:`ForceModel` per ship, looped in Python.

    The hook for actuator models (rudder, fins…) before they have a vectorised version: ship
    s sees a :class:`ForceContext` with its own time, state, rotation, its wave phasors (its
    real components only) and ``commands = {key: value[s]}``. States, ``reset`` and ``commit``
    are forwarded per ship.

    Parameters
    ----------
    models : sequence of ForceModel
        One model per ship (same ``name``, ``n_states`` and ``added_mass`` for all).
    """

    def __init__(self, models: Sequence[ForceModel]) -> None:
        self.models = list(models)
        if not self.models:
            raise ValueError("PerShipForceModel needs one ForceModel per ship; got none")
        first = self.models[0]
        for m in self.models[1:]:
            if m.name != first.name or int(m.n_states) != int(first.n_states):
                raise ValueError("all per-ship models must have the same name and n_states")
            a, b = m.added_mass, first.added_mass
            same = (a is None and b is None) or (
                a is not None and b is not None and np.array_equal(a, b)
            )
            if not same:
                raise ValueError("all per-ship models must declare the same added_mass")
        self.name = first.name
        self.n_states = int(first.n_states)
        self.added_mass = first.added_mass

    def initial_states(self, ships: NDArray[np.int64]) -> NDArray:
        out = np.zeros((len(ships), self.n_states))
        for i, s in enumerate(ships):
            out[i] = self.models[int(s)].initial_states()
        return out

    def _ship_context(self, ctx: BatchContext, i: int) -> ForceContext:
        s = int(ctx.ships[i])
        m = int(ctx.waves.n_components[i])
        commands = {k: (v[s] if np.ndim(v) else v) for k, v in ctx.commands.items()}
        return ForceContext(
            t=float(ctx.t[i]),
            eta=ctx.eta[i],
            nu=ctx.nu[i],
            rotation=ctx.rotation[i],
            forward_speed=ctx.forward_speed,
            wave_phasor=ctx.wave_phasor[i, :m] if m else None,
            commands=commands,
            shared=ctx.shared.setdefault(("ship", s), {}),
        )

    def bind(self, n_ships: int, n_comp: int) -> None:
        if len(self.models) != n_ships:
            raise ValueError(
                f"PerShipForceModel holds {len(self.models)} models for a batch of {n_ships}"
            )

    def reset(self, ships: NDArray[np.int64], ctx: BatchContext) -> None:
        for i, s in enumerate(ships):
            self.models[int(s)].reset(float(ctx.t[i]), self._ship_context(ctx, i))

    def evaluate(self, ctx: BatchContext, states: NDArray) -> tuple[NDArray, NDArray]:
        force = np.empty((ctx.n, 6))
        zdot = np.empty((ctx.n, self.n_states))
        for i, s in enumerate(ctx.ships):
            f, zd = self.models[int(s)].evaluate(self._ship_context(ctx, i), states[i])
            force[i] = f
            zdot[i] = zd
        return force, zdot

    def commit(self, ctx: BatchContext, states: NDArray) -> None:
        for i, s in enumerate(ctx.ships):
            self.models[int(s)].commit(self._ship_context(ctx, i), states[i])


def batch_force_models(
    models: Sequence[ForceModel | BatchForceModel],
) -> list[BatchForceModel]:
    """Batch versions of one ship's force models (as built by ``build_force_models``).

    Froude–Krylov, state-space radiation memory, constant-coefficient radiation, diffraction and
    viscous roll damping are converted (their sea-independent data reused), and so are the
    control models with a vectorised version in :mod:`ship_gym.engine.batch_control`
    (resistance, propeller, hull manoeuvring, rudder / fins / T-foil / flaps behind their
    servos, with the heading autopilot, fin or ride controller); a :class:`BatchForceModel` is
    passed through. Anything else (added resistance in waves) raises ``NotImplementedError``
    (wrap one instance per ship in :class:`PerShipForceModel`).
    """
    out: list[BatchForceModel] = []
    for m in models:
        if isinstance(m, BatchForceModel):
            out.append(m)
        elif isinstance(m, FroudeKrylovHydrostatics):
            out.append(BatchFroudeKrylov.from_model(m))
        elif isinstance(m, RadiationMemory):
            out.append(BatchStateSpaceRadiation.from_model(m))
        elif isinstance(m, ConstantCoefficientRadiation):
            out.append(BatchConstantRadiation.from_model(m))
        elif isinstance(m, Diffraction):
            out.append(BatchDiffraction(m))
        elif isinstance(m, ViscousRollDamping):
            out.append(BatchViscousRoll.from_model(m))
        else:
            try:
                out.append(batch_control_model(m))
            except NotImplementedError:
                raise NotImplementedError(
                    f"no batch version of force model {type(m).__name__!r} ({m.name!r}); wrap "
                    "one instance per ship in PerShipForceModel"
                ) from None
    return out


# =============================================================================================
# vectorised rigid-body terms
# =============================================================================================
@nb.njit(cache=True)
def _ship_terms(eta, nu, mass, weight, cog, held, rot, total, qdot):  # pragma: no cover
    """:func:`ship_gym.engine.rigid_body.rigid_body_terms` per row: R(φ, θ, ψ), gravity −
    Coriolis (body axes, about O) and η̇ = J(η) ν (0 for a held angle), with ``mass``
    (n, 6, 6) M_RB about O and ``cog`` (n, 3) G of each row (per-ship loading)."""
    for s in range(eta.shape[0]):
        rigid_body_terms(eta[s], nu[s], mass[s], weight, cog[s], held, rot[s], total[s], qdot[s])


@nb.njit(cache=True)
def _wave_phasors(
    t, x, y, amplitude, omega, phase, ramp_time, k, cos_dir, sin_dir, c_out, local_out
):  # pragma: no cover - compiled
    """Per ship and component: cⱼ(t) = r(t) aⱼ e^{i(ωⱼt + εⱼ)} (Matusiak's ramp r) and the
    phasor folded to O, c'ⱼ = cⱼ e^{−i kⱼ (x cos χⱼ + y sin χⱼ)}."""
    for s in range(t.shape[0]):
        ts, tf = t[s], ramp_time[s]
        if tf > 0.0:
            if ts >= tf:
                r = 1.0
            else:
                u = min(max(ts / tf, 0.0), 1.0)
                r = math.sin(0.5 * math.pi * u) ** 2
        else:
            r = 1.0
        xs, ys = x[s], y[s]
        for j in range(amplitude.shape[1]):
            a = r * amplitude[s, j]
            arg = omega[s, j] * ts + phase[s, j]
            cre, cim = a * math.cos(arg), a * math.sin(arg)
            c_out[s, j] = complex(cre, cim)
            sp = k[s, j] * (xs * cos_dir[s, j] + ys * sin_dir[s, j])
            cs, sn = math.cos(sp), math.sin(sp)
            local_out[s, j] = complex(cre * cs + cim * sn, cim * cs - cre * sn)


@nb.njit(cache=True)
def _earth_to_body(rot, f, out):  # pragma: no cover - compiled
    """out = (Rᵀ F, Rᵀ M) per ship."""
    for s in range(rot.shape[0]):
        for i in range(3):
            out[s, i] = rot[s, 0, i] * f[s, 0] + rot[s, 1, i] * f[s, 1] + rot[s, 2, i] * f[s, 2]
            out[s, 3 + i] = rot[s, 0, i] * f[s, 3] + rot[s, 1, i] * f[s, 4] + rot[s, 2, i] * f[s, 5]


@nb.njit(cache=True)
def _holloway_rows(
    ships,
    q,
    v,
    z,
    ac,
    zd,
    qd,
    mu,
    dt,
    v1,
    v2,
    a1,
    a2,
    qd1,
    qd2,
    qdd1,
    qdd2,
    zd1,
    zd2,
    pending,
    q_new,
    v_new,
    z_new,
):  # pragma: no cover - compiled
    """Holloway's μ-Taylor step (eq. 4, 6–9) for rows r of ships s = ships[r].

    The arithmetic of ``integrators._bdf2``, ``_holloway_update``, ``_taylor3_update`` (η with
    η̇ = J(η) ν) and ``_taylor2_update`` (first-order states); the per-ship histories (rows s
    of v1, v2, a1, a2, qd1, qd2, qdd1, qdd2, zd1, zd2; index 1 the newest) are shifted in place.
    After the RK4 start-up (``pending``) q̈ at the two previous instants comes from the q̇
    history, as in :class:`ship_gym.numerics.integrators.HollowayIntegrator`.
    """  # fmt: skip
    c = 0.5 / dt
    h2 = 0.5 * dt * dt
    h3 = dt * dt * dt / 6.0
    for r in range(ships.shape[0]):
        s = ships[r]
        for i in range(v.shape[1]):
            ae = (3.0 * v[r, i] - 4.0 * v1[s, i] + v2[s, i]) * c  # eq. 6
            a = mu[i] * ac[r, i] + (1.0 - mu[i]) * ae  # eq. 4
            j = (3.0 * a - 4.0 * a1[s, i] + a2[s, i]) * c  # eq. 7
            v_new[r, i] = v[r, i] + dt * a + h2 * j  # eq. 8
            a2[s, i] = a1[s, i]
            a1[s, i] = a
            v2[s, i] = v1[s, i]
            v1[s, i] = v[r, i]
        if pending[s]:
            for i in range(q.shape[1]):
                qdd2[s, i] = (-3.0 * qd2[s, i] + 4.0 * qd1[s, i] - qd[r, i]) * c
                qdd1[s, i] = (qd[r, i] - qd2[s, i]) * c
            pending[s] = False
        for i in range(q.shape[1]):
            qdd = (3.0 * qd[r, i] - 4.0 * qd1[s, i] + qd2[s, i]) * c
            qddd = (3.0 * qdd - 4.0 * qdd1[s, i] + qdd2[s, i]) * c
            q_new[r, i] = q[r, i] + dt * qd[r, i] + h2 * qdd + h3 * qddd  # eq. 9
            qd2[s, i] = qd1[s, i]
            qd1[s, i] = qd[r, i]
            qdd2[s, i] = qdd1[s, i]
            qdd1[s, i] = qdd
        for i in range(z.shape[1]):
            zdd = (3.0 * zd[r, i] - 4.0 * zd1[s, i] + zd2[s, i]) * c
            z_new[r, i] = z[r, i] + dt * zd[r, i] + h2 * zdd
            zd2[s, i] = zd1[s, i]
            zd1[s, i] = zd[r, i]


@nb.njit(cache=True)
def _healthy_rows(q, v, z, v_max, ok):  # pragma: no cover - compiled
    """ok[r]: :func:`ship_gym.engine.rigid_body.healthy_state` of row r."""
    for r in range(q.shape[0]):
        ok[r] = healthy_state(q[r], v[r], z[r], v_max)


# =============================================================================================
# the simulator
# =============================================================================================
class EngineState(NamedTuple):
    """The state of a batch that the compiled loop advances in place (rows per ship).

    Attributes
    ----------
    t : numpy.ndarray
        (N,) time [s].
    eta, nu : numpy.ndarray
        (N, 6) position and Euler angles [m, rad]; body velocities [m/s, rad/s].
    z : numpy.ndarray
        (N, n_states) the models' ODE states, concatenated in the models' order.
    k_count : numpy.ndarray
        (N,) steps since reset (Holloway's start-up).
    pending : numpy.ndarray
        (N,) bool, the η̇ history still holds the start-up's first differences.
    history : tuple of numpy.ndarray
        Holloway's histories (v1, v2, a1, a2, qd1, qd2, qdd1, qdd2, zd1, zd2).
    """

    t: NDArray
    eta: NDArray
    nu: NDArray
    z: NDArray
    k_count: NDArray
    pending: NDArray
    history: tuple


def _servo_driven(model: Any) -> bool:
    """A batch force model with a servo and the angle it has reached (an actuator)."""
    return getattr(model, "servo", None) is not None and hasattr(model, "angle")


class BatchSimulator:
    """N ships of one hull and setup, each in its own sea, stepped together (module docstring).

    Parameters
    ----------
    hull : Hull
        Hull and loading condition (shared).
    forces : sequence of BatchForceModel
        Batch force models (:func:`batch_force_models` converts single-ship ones).
    wave_fields : sequence of WaveField or None
        One sea per ship (None: calm water); the batch size N is their number. Component
        arrays are zero-padded to a common count.
    forward_speed : float
        Steady forward speed U [m/s] (shared).
    dt : float
        Physics time step [s].
    integrator : {"rk4", "holloway"}
        4 or 1 force evaluations per step (Holloway: after a 2-step RK4 start-up per ship).
    free_dofs : sequence of bool, optional
        (6,) integrated DOFs; held DOFs keep their initial velocity.
    mu : array_like, optional
        Holloway blending factors per DOF; default 1 (the acceleration is exact).
    max_abs_velocity : float
        |ν| above which a ship is declared diverged [m/s, rad/s].
    initial_eta : array_like, optional
        (6,) default initial η of :meth:`reset` (default zeros; :func:`build_batch_simulator`
        sets the free-floating equilibrium).
    max_components : int, optional
        Padded component count (≥ the largest field's); room for larger seas given to
        :meth:`reset` later.
    commands : mapping, optional
        Initial actuator commands ((N,) arrays or scalars), in force from the first reset.

    Attributes
    ----------
    t : numpy.ndarray
        (N,) time of each ship [s].
    eta, nu : numpy.ndarray
        (N, 6) states.
    z : numpy.ndarray
        (N, n_states) force-model states.
    n_steps : numpy.ndarray
        (N,) steps since each ship's last reset.
    diverged : numpy.ndarray
        (N,) bool, ships frozen by divergence until reset.
    divergence_messages : dict
        Ship index → message of its divergence.
    commands : dict
        Last commands given to :meth:`step` (arrays with a leading axis of N).
    n_evaluations : int
        Batched force evaluations (calls of every model) since construction.
    timings : dict or None
        Set to ``{}`` to accumulate the wall time [s] spent in each model's ``evaluate`` (by
        name); None (default) times nothing.
    """

    def __init__(
        self,
        hull: Hull,
        forces: Sequence[BatchForceModel],
        wave_fields: Sequence[WaveField | None],
        *,
        forward_speed: float = 0.0,
        dt: float = 0.05,
        integrator: IntegratorName = "rk4",
        free_dofs: Sequence[bool] | None = None,
        mu: ArrayLike | None = None,
        max_abs_velocity: float = 100.0,
        initial_eta: ArrayLike | None = None,
        max_components: int | None = None,
        commands: Mapping[str, ArrayLike] | None = None,
        backend: EngineBackend = "auto",
        parallel: bool = False,
    ) -> None:
        if backend not in ("auto", "compiled", "numpy"):
            raise ValueError(f"backend must be 'auto', 'compiled' or 'numpy', got {backend!r}")
        if not (np.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be a positive time step [s], got {dt!r}")
        fields = list(wave_fields)
        if not fields:
            raise ValueError("wave_fields must hold one WaveField (or None) per ship; got none")
        names = [f.name for f in forces]
        if len(set(names)) != len(names):
            raise ValueError(f"force model names must be unique, got {names}")
        for f in forces:
            if not isinstance(f, BatchForceModel):
                raise ValueError(
                    f"forces must be BatchForceModel instances (see batch_force_models); got "
                    f"{type(f).__name__}"
                )
        if integrator not in ("rk4", "holloway"):
            raise ValueError(
                f"integrator must be 'rk4' or 'holloway' in BatchSimulator, got {integrator!r}"
            )
        self.hull = hull
        self.forces = list(forces)
        self.n_ships = len(fields)
        self._seas = _Seas(fields, max_components)
        self.wave_fields: list[WaveField | None] = list(fields)
        """The ships' seas (as given; None: calm water)."""
        for f in self.forces:
            f.bind(self.n_ships, self._seas.n_comp)
        self._forward_speed = float(forward_speed)
        self.dt = float(dt)
        self.integrator_name: IntegratorName = integrator
        self.max_abs_velocity = float(max_abs_velocity)
        self.free, self.mass_rb, a_lhs = left_hand_side(hull, self.forces, free_dofs)
        self.added_mass_lhs = a_lhs
        idx = np.flatnonzero(self.free)
        self._free_idx = idx
        self._m_free_inv_t = np.linalg.inv((self.mass_rb + a_lhs)[np.ix_(idx, idx)]).T.copy()
        self._all_free = bool(self.free.all())
        self._held_angles = ~self.free[3:]
        self._weight = float(hull.mass.mass * hull.g)
        self._cog = np.asarray(hull.mass.cog, float)
        # per-ship loading (set_centre_of_gravity): G, M_RB about O and the inverse of the free
        # block of M_RB + A_lhs, one row per ship; all the hull's until a ship's G is moved
        self._ship_cog = np.tile(self._cog, (self.n_ships, 1))
        self._ship_mass_rb = np.tile(self.mass_rb, (self.n_ships, 1, 1))
        self._ship_m_inv_t = np.tile(self._m_free_inv_t, (self.n_ships, 1, 1))
        self._uniform_loading = True
        sizes = [int(f.n_states) for f in self.forces]
        bounds = np.concatenate([[0], np.cumsum(sizes)]).astype(int)
        self._slices = [slice(bounds[i], bounds[i + 1]) for i in range(len(self.forces))]
        self.n_states = int(bounds[-1])
        if mu is None:
            mu = np.ones(6)  # exact acceleration (added mass on the left): no blending
        self.mu = np.broadcast_to(np.asarray(mu, float), (6,)).copy()
        if not (np.all(np.isfinite(self.mu)) and np.all(self.mu > 0.0)):
            raise ValueError(f"mu must be positive and finite, got {mu!r}")
        self.initial_eta = (
            np.zeros(6) if initial_eta is None else np.asarray(initial_eta, float).copy()
        )
        if self.initial_eta.shape != (6,):
            raise ValueError(f"initial_eta must have 6 components, got {initial_eta!r}")
        n, nz = self.n_ships, self.n_states
        self.t = np.zeros(n)
        self.eta = np.tile(self.initial_eta, (n, 1))
        self.nu = np.zeros((n, 6))
        self.nu[:, SURGE] = self.forward_speed
        self.z = np.zeros((n, nz))
        self.n_steps = np.zeros(n, dtype=np.int64)
        self.diverged = np.zeros(n, dtype=bool)
        self.divergence_messages: dict[int, str] = {}
        self.commands: dict = dict(commands or {})
        self.n_evaluations = 0
        # per-ship integrator history (Holloway) — rows indexed by ship
        self._k = np.zeros(n, dtype=np.int64)
        self._v1, self._v2 = np.zeros((n, 6)), np.zeros((n, 6))
        self._a1, self._a2 = np.zeros((n, 6)), np.zeros((n, 6))
        self._qd1, self._qd2 = np.zeros((n, 6)), np.zeros((n, 6))
        self._qdd1, self._qdd2 = np.zeros((n, 6)), np.zeros((n, 6))
        self._zd1, self._zd2 = np.zeros((n, nz)), np.zeros((n, nz))
        self._pending = np.zeros(n, dtype=bool)
        self._all = np.arange(n, dtype=np.int64)
        self._waves_all = self._waves_rows(self._all, True)
        self.timings: dict[str, float] | None = None
        self.layout_version = 0
        """Incremented when a ship's sea or loading changes (the compiled records follow)."""
        self.backend: EngineBackend = backend
        self.parallel = bool(parallel)
        """Spread the ships over numba's threads in the compiled loop (may be changed later)."""
        self._compiled: Any = None
        self._compiled_error: str | None = None
        self.reset()

    @property
    def forward_speed(self) -> float:
        """Steady forward speed U [m/s] about which radiation is linearised (shared).

        A new value takes effect from the next step (the compiled records are rebuilt) and
        becomes the default surge speed of :meth:`reset`.
        """
        return self._forward_speed

    @forward_speed.setter
    def forward_speed(self, value: float) -> None:
        u = float(value)
        if not np.isfinite(u):
            raise ValueError(f"forward_speed must be a finite speed [m/s], got {value!r}")
        if u != self._forward_speed:
            self._forward_speed = u
            self._compiled = None
            self._compiled_error = None

    # ------------------------------------------------------------------ engine state
    @property
    def seas(self) -> _Seas:
        """The per-ship wave component arrays (N, n_c) (``amplitude`` [m], ``omega`` [rad/s],
        ``phase`` [rad], ``direction`` [rad], ``wavenumber``, ``kx``, ``ky`` [rad/m]) and the
        (N,) ``ramp_time`` [s]; replaced in place by :meth:`reset` with a new sea."""
        return self._seas

    def rigid_rows(self) -> tuple[NDArray, float, NDArray, NDArray, NDArray]:
        """Per-ship rigid-body data for the compiled loop: M_RB about O (N, 6, 6), the weight
        m g [N], G (N, 3), the held angles (3,) and the inverse of the free block of
        M_RB + A_lhs (N, 6, 6; zeros for held DOFs)."""
        idx = self._free_idx
        m_inv = np.zeros((self.n_ships, 6, 6))
        m_inv[:, idx[:, None], idx[None, :]] = np.transpose(self._ship_m_inv_t, (0, 2, 1))
        c = np.ascontiguousarray
        return (
            c(self._ship_mass_rb, float), float(self._weight), c(self._ship_cog, float),
            c(self._held_angles, np.bool_), m_inv,
        )  # fmt: skip

    def engine_state(self) -> EngineState:
        """The arrays the compiled loop advances in place (:class:`EngineState`, views)."""
        return EngineState(
            self.t, self.eta, self.nu, self.z, self._k, self._pending,
            (
                self._v1, self._v2, self._a1, self._a2, self._qd1, self._qd2, self._qdd1,
                self._qdd2, self._zd1, self._zd2,
            ),
        )  # fmt: skip

    # ------------------------------------------------------------------ compiled backend
    @property
    def compiled(self) -> bool:
        """Whether :meth:`advance` runs the compiled loop (``backend`` and the models allow)."""
        return self._compiled_backend() is not None

    def _compiled_backend(self) -> Any:
        if self.backend == "numpy":
            return None
        if self._compiled is None and self._compiled_error is None:
            from ship_gym.engine.compiled import CompiledBackend

            try:
                self._compiled = CompiledBackend(self)
            except NotImplementedError as exc:
                self._compiled_error = str(exc)
        if self._compiled is None and self.backend == "compiled":
            raise NotImplementedError(
                f"backend='compiled' is not available for these models: {self._compiled_error}"
            )
        return self._compiled

    def advance(
        self,
        n_steps: int,
        commands: Mapping[str, ArrayLike] | None = None,
        *,
        danger_roll: float = math.inf,
    ) -> StepReductions:
        """Take ``n_steps`` physics steps with the commands held; return the task reductions.

        With the compiled backend (:mod:`ship_gym.engine.compiled`) the K steps of all ships
        run in one compiled call; otherwise :meth:`step` is called K times. Both return the
        same :class:`~ship_gym.engine.compiled.StepReductions` (max |φ| including the start
        state, Σφ², steps with |φ| > ``danger_roll``, ships diverged during the call).

        Parameters
        ----------
        n_steps : int
            Physics steps K (≥ 1).
        commands : mapping, optional
            Merged into :attr:`commands` first (as :meth:`step`).
        danger_roll : float
            Roll angle counted as dangerous [rad].
        """
        from ship_gym.engine.compiled import StepReductions

        k = int(n_steps)
        if k < 1:
            raise ValueError(f"n_steps must be ≥ 1, got {n_steps!r}")
        previous = self.commands
        if commands is not None:
            self.commands = {**self.commands, **commands}
        backend = self._compiled_backend()
        if backend is not None and not backend.handles_commands():
            if self.backend == "compiled":
                keys = sorted(backend.numpy_only_commands & self.commands.keys())
                self.commands = previous  # a refused command changes nothing
                raise NotImplementedError(
                    f"commands {keys} are read by the numpy path only (a rudder without a "
                    "propeller)"
                )
            backend = None
        cmd = None
        if backend is not None:
            try:
                cmd = backend.command_matrix()
            except ValueError:
                self.commands = previous  # a refused command changes nothing
                raise
        if backend is None:
            max_abs = np.abs(self.eta[:, ROLL])
            sum_sq = np.zeros(self.n_ships)
            danger = np.zeros(self.n_ships, dtype=np.int64)
            newly = np.zeros(self.n_ships, dtype=bool)
            for _ in range(k):
                newly |= self.step()
                roll = self.eta[:, ROLL]
                absr = np.abs(roll)
                np.maximum(max_abs, absr, out=max_abs)
                sum_sq += roll * roll
                danger += absr > danger_roll
            return StepReductions(max_abs, sum_sq, danger, newly)
        ships = self._all if not self.diverged.any() else np.flatnonzero(~self.diverged)
        if ships.size == 0:
            z = np.zeros(self.n_ships)
            return StepReductions(z, z.copy(), np.zeros(self.n_ships, np.int64), z > 0)
        reductions, done = backend.advance(ships, k, danger_roll, cmd)
        self.n_steps += done
        self.n_evaluations += k * self.evaluations_per_step
        if not reductions.diverged.any():
            return reductions
        for s in np.flatnonzero(reductions.diverged):
            self.diverged[s] = True
            self.divergence_messages[int(s)] = (
                f"ship {s} diverged at t = {self.t[s] + self.dt:.3f} s (step "
                f"{self.n_steps[s] + 1}): eta = {np.round(self.eta[s], 4).tolist()}, "
                f"nu = {np.round(self.nu[s], 4).tolist()}; try a smaller dt (now {self.dt} s) "
                f"or another integrator (now {self.integrator_name!r})"
            )
        return reductions

    # ------------------------------------------------------------------ properties
    @property
    def n_components(self) -> int:
        """Padded wave component count."""
        return self._seas.n_comp

    @property
    def evaluations_per_step(self) -> int:
        """Force evaluations per step after start-up (4 for RK4, 1 for Holloway)."""
        return 4 if self.integrator_name == "rk4" else 1

    # ------------------------------------------------------------------ helpers
    def _as_ships(self, indices: ArrayLike | None) -> NDArray[np.int64]:
        if indices is None:
            return self._all.copy()
        idx = np.asarray(indices)
        if idx.dtype == bool:
            if idx.shape != (self.n_ships,):
                raise ValueError(f"a boolean mask must have shape ({self.n_ships},)")
            return np.flatnonzero(idx)
        idx = np.atleast_1d(idx).astype(np.int64)
        if idx.ndim != 1 or np.any(idx < 0) or np.any(idx >= self.n_ships):
            raise ValueError(f"ship indices must lie in 0…{self.n_ships - 1}, got {indices!r}")
        if np.unique(idx).size != idx.size:
            raise ValueError(f"ship indices must be distinct, got {indices!r}")
        return idx

    def _rows6(self, value: ArrayLike, n: int, name: str) -> NDArray:
        arr = np.asarray(value, float)
        if arr.shape == (6,):
            return np.tile(arr, (n, 1))
        if arr.shape != (n, 6):
            raise ValueError(f"{name} must have shape (6,) or ({n}, 6), got {arr.shape}")
        return arr.copy()

    def _waves_rows(self, ships: NDArray[np.int64], all_ships: bool) -> BatchWaves:
        s = self._seas
        if all_ships:
            return BatchWaves(
                s.wavenumber, s.omega, s.direction, s.cos_direction, s.sin_direction,
                s.kx, s.ky, s.n_components,
            )  # fmt: skip
        return BatchWaves(
            s.wavenumber[ships], s.omega[ships], s.direction[ships], s.cos_direction[ships],
            s.sin_direction[ships], s.kx[ships], s.ky[ships], s.n_components[ships],
        )  # fmt: skip

    def _context(
        self, ships: NDArray[np.int64], all_ships: bool, t: NDArray, eta: NDArray, nu: NDArray
    ) -> tuple[BatchContext, NDArray, NDArray]:
        """The context of the rows, their gravity − Coriolis force and η̇ (one kernel each)."""
        n = t.shape[0]
        eta = np.ascontiguousarray(eta)
        nu = np.ascontiguousarray(nu)
        rot = np.empty((n, 3, 3))
        rigid = np.empty((n, 6))
        qdot = np.empty((n, 6))
        if all_ships:
            mass_rb, cog = self._ship_mass_rb, self._ship_cog
        else:
            mass_rb, cog = self._ship_mass_rb[ships], self._ship_cog[ships]
        _ship_terms(eta, nu, mass_rb, self._weight, cog, self._held_angles, rot, rigid, qdot)
        seas = self._seas
        if all_ships:
            waves = self._waves_all
            amp, omega, phase, ramp = seas.amplitude, seas.omega, seas.phase, seas.ramp_time
        else:
            waves = self._waves_rows(ships, False)
            amp, omega = seas.amplitude[ships], seas.omega[ships]
            phase, ramp = seas.phase[ships], seas.ramp_time[ships]
        c = np.empty((n, seas.n_comp), dtype=complex)
        local = np.empty((n, seas.n_comp), dtype=complex)
        _wave_phasors(
            np.ascontiguousarray(t, dtype=float), eta[:, 0].copy(), eta[:, 1].copy(),
            amp, omega, phase, ramp, waves.wavenumber, waves.cos_direction,
            waves.sin_direction, c, local,
        )  # fmt: skip
        ctx = BatchContext(
            ships=ships,
            all_ships=all_ships,
            t=t,
            eta=eta,
            nu=nu,
            rotation=rot,
            forward_speed=self.forward_speed,
            wave_phasor=c,
            local_phasor=local,
            waves=waves,
            commands=self.commands,
        )
        return ctx, rigid, qdot

    # ------------------------------------------------------------------ reset
    def reset(
        self,
        indices: ArrayLike | None = None,
        eta: ArrayLike | None = None,
        nu: ArrayLike | None = None,
        *,
        t0: float | ArrayLike = 0.0,
        wave_fields: Sequence[WaveField | None] | None = None,
    ) -> None:
        """Restart the ships ``indices`` (default all) at t0 from (η, ν); others untouched.

        Memory states, integrator history, divergence flag and step count of those ships are
        cleared.

        Parameters
        ----------
        indices : array_like of int or bool mask, optional
            Ships to reset.
        eta : array_like, optional
            (6,) or (n, 6) initial η (default :attr:`initial_eta`).
        nu : array_like, optional
            (6,) or (n, 6) initial ν (default (U, 0, 0, 0, 0, 0)).
        t0 : float or array_like
            Initial time(s) [s].
        wave_fields : sequence of WaveField or None, optional
            New seas for those ships (one per index; None entries give calm water), at most
            :attr:`n_components` components each.
        """
        ships = self._as_ships(indices)
        n = ships.size
        if n == 0:
            return
        new_eta = self._rows6(self.initial_eta if eta is None else eta, n, "eta")
        if nu is None:
            new_nu = np.zeros((n, 6))
            new_nu[:, SURGE] = self.forward_speed
        else:
            new_nu = self._rows6(nu, n, "nu")
        new_t = np.broadcast_to(np.asarray(t0, float), (n,)).copy()
        if not np.all(np.isfinite(new_t)):
            raise ValueError(f"t0 must be finite, got {t0!r}")
        if wave_fields is not None:
            wf = list(wave_fields)
            if len(wf) != n:
                raise ValueError(f"wave_fields must hold {n} fields (one per ship), got {len(wf)}")
            for s, f in zip(ships, wf, strict=True):
                self._seas.replace(int(s), f)
                self.wave_fields[int(s)] = f
            self.layout_version += 1
        self.t[ships] = new_t
        self.eta[ships] = new_eta
        self.nu[ships] = new_nu
        z0 = []
        for model in self.forces:
            z = model.initial_states(ships)
            if isinstance(model, BatchStateSpaceRadiation):
                # a ship starting at another speed than U has been running at it
                z = z + model.steady_surge_states(new_nu[:, SURGE] - self.forward_speed)
            z0.append(z)
        self.z[ships] = np.concatenate(z0, axis=1) if z0 else np.zeros((n, 0))
        self.n_steps[ships] = 0
        self._k[ships] = 0
        self._pending[ships] = False
        self.diverged[ships] = False
        for s in ships:
            self.divergence_messages.pop(int(s), None)
        all_ships = n == self.n_ships and bool(np.all(ships == self._all))
        ctx, _, _ = self._context(ships, all_ships, new_t, new_eta, new_nu)
        for model in self.forces:
            model.reset(ships, ctx)

    # ------------------------------------------------------------------ per-ship loading
    def set_centre_of_gravity(self, indices: ArrayLike | None, cog: ArrayLike) -> None:
        """Move the centre of gravity G of ships ``indices`` (their loading condition).

        The mass and the inertia tensor about G stay the hull's; M_RB about O (Fossen 2011,
        eq. 3.44), the gravity moment and the inverse of M_RB + A_lhs of those ships follow G.
        The nonlinear Froude–Krylov + hydrostatic force integrates the pressure on the hull
        panels and does not depend on G, so the restoring moment — GZ and GM — is consistent
        with the new G by construction. Force models tuned on the hull's loading (viscous roll
        damping at the roll natural frequency, controller gains) keep their values. Persistent
        across :meth:`reset`.

        Parameters
        ----------
        indices : array_like of int or bool mask, optional
            Ships to change (None: all).
        cog : array_like
            (3,) or (n, 3) G in the body frame [m] (z down from the design waterline: a
            higher G has a more negative z_G).
        """
        ships = self._as_ships(indices)
        n = ships.size
        if n == 0:
            return
        g = np.asarray(cog, float)
        if g.shape == (3,):
            g = np.tile(g, (n, 1))
        if g.shape != (n, 3) or not np.all(np.isfinite(g)):
            raise ValueError(f"cog must be finite with shape (3,) or ({n}, 3) [m], got {cog!r}")
        from ship_gym.hull.mass import MassProperties

        mass = self.hull.mass
        idx = self._free_idx
        for s, gs in zip(ships, g, strict=True):
            m_rb = MassProperties(mass.mass, gs, mass.inertia).rigid_body_matrix()
            self._ship_cog[s] = gs
            self._ship_mass_rb[s] = m_rb
            lhs = (m_rb + self.added_mass_lhs)[np.ix_(idx, idx)]
            self._ship_m_inv_t[s] = np.linalg.inv(lhs).T
        self._uniform_loading = bool(np.all(self._ship_cog == self._cog))
        self.layout_version += 1

    @property
    def centre_of_gravity(self) -> NDArray:
        """(N, 3) centre of gravity of each ship in the body frame [m] (a copy)."""
        return self._ship_cog.copy()

    def elevation(self, x: ArrayLike, y: ArrayLike) -> NDArray:
        """Incident-wave elevation [m, positive up] at earth points, each ship in its own sea.

        ζₛ(X, Y) = rₛ(tₛ) Σⱼ aₛⱼ cos(ωₛⱼ tₛ + εₛⱼ − kₛⱼ (X cos χₛⱼ + Y sin χₛⱼ)) at each ship's
        own time tₛ, ramp rₛ included (:mod:`ship_gym.waves.wave_field`).

        Parameters
        ----------
        x, y : array_like
            (N, P) north and east coordinates [m] (row s: points in ship s's sea).

        Returns
        -------
        numpy.ndarray
            (N, P) elevations [m].
        """
        from ship_gym.waves.wave_field import ramp_factor

        xx = np.asarray(x, float)
        yy = np.asarray(y, float)
        if xx.ndim != 2 or xx.shape != yy.shape or xx.shape[0] != self.n_ships:
            raise ValueError(
                f"x and y must both have shape ({self.n_ships}, P), got {xx.shape} and {yy.shape}"
            )
        seas = self._seas
        r = ramp_factor(self.t, seas.ramp_time)
        arg = (seas.omega * self.t[:, None] + seas.phase)[:, None, :] - (
            seas.kx[:, None, :] * xx[:, :, None] + seas.ky[:, None, :] * yy[:, :, None]
        )
        return r[:, None] * np.einsum("nc,npc->np", seas.amplitude, np.cos(arg))

    # ------------------------------------------------------------------ right-hand side
    def _generalised_force(
        self, ctx: BatchContext, rigid: NDArray, z: NDArray, breakdown: dict | None = None
    ) -> tuple[NDArray, NDArray]:
        """Σ forces + gravity − Coriolis (``rigid``, modified in place) and ż of the rows."""
        total = rigid
        zdot = np.empty((ctx.n, self.n_states))
        timings = self.timings
        for f, sl in zip(self.forces, self._slices, strict=True):
            if timings is None:
                force, zd = f.evaluate(ctx, z[:, sl])
            else:
                t0 = time.perf_counter()
                force, zd = f.evaluate(ctx, z[:, sl])
                timings[f.name] = timings.get(f.name, 0.0) + time.perf_counter() - t0
            total += force
            zdot[:, sl] = zd
            if breakdown is not None:
                breakdown[f.name] = force
        self.n_evaluations += 1
        return total, zdot

    def _acceleration(
        self, total: NDArray, ships: NDArray[np.int64] | None = None, all_ships: bool = True
    ) -> NDArray:
        if self._uniform_loading:
            if self._all_free:
                return total @ self._m_free_inv_t
            acc = np.zeros_like(total)
            acc[:, self._free_idx] = total[:, self._free_idx] @ self._m_free_inv_t
            return acc
        inv_t = self._ship_m_inv_t if all_ships or ships is None else self._ship_m_inv_t[ships]
        if self._all_free:
            return np.einsum("ni,nij->nj", total, inv_t)
        acc = np.zeros_like(total)
        acc[:, self._free_idx] = np.einsum("ni,nij->nj", total[:, self._free_idx], inv_t)
        return acc

    def _rhs(
        self, ships: NDArray[np.int64], all_ships: bool, t: NDArray, q: NDArray, v: NDArray,
        z: NDArray,
    ) -> tuple[NDArray, NDArray, NDArray]:  # fmt: skip
        """(acceleration, zdot, q̇) of the rows."""
        ctx, rigid, qdot = self._context(ships, all_ships, t, q, v)
        total, zdot = self._generalised_force(ctx, rigid, z)
        return self._acceleration(total, ships, all_ships), zdot, qdot

    # ------------------------------------------------------------------ integrators
    def _rk4(
        self, ships, all_ships, t, q, v, z, first: tuple[NDArray, NDArray, NDArray]
    ) -> tuple[NDArray, NDArray, NDArray]:
        """Classical RK4 (the arithmetic of ``integrators._rk4_core``); stage 1 given."""
        h = self.dt
        a1, g1, d1 = first
        c = 0.5 * h
        q2, v2, z2 = q + c * d1, v + c * a1, z + c * g1
        a2, g2, d2 = self._rhs(ships, all_ships, t + c, q2, v2, z2)
        q3, v3, z3 = q + c * d2, v + c * a2, z + c * g2
        a3, g3, d3 = self._rhs(ships, all_ships, t + c, q3, v3, z3)
        q4, v4, z4 = q + h * d3, v + h * a3, z + h * g3
        a4, g4, d4 = self._rhs(ships, all_ships, t + h, q4, v4, z4)
        c6 = h / 6.0
        q_new = q + c6 * (d1 + 2.0 * (d2 + d3) + d4)
        v_new = v + c6 * (a1 + 2.0 * (a2 + a3) + a4)
        z_new = z + c6 * (g1 + 2.0 * (g2 + g3) + g4)
        return q_new, v_new, z_new

    def _holloway(
        self, ships: NDArray[np.int64], q, v, z, ac, zd, qd
    ) -> tuple[NDArray, NDArray, NDArray]:
        """Holloway μ-Taylor step of the rows ``ships`` (HollowayIntegrator.step arithmetic)."""
        q_new, v_new, z_new = np.empty_like(q), np.empty_like(v), np.empty_like(z)
        _holloway_rows(
            ships, np.ascontiguousarray(q), np.ascontiguousarray(v), np.ascontiguousarray(z),
            ac, zd, qd, self.mu, self.dt, self._v1, self._v2, self._a1, self._a2,
            self._qd1, self._qd2, self._qdd1, self._qdd2, self._zd1, self._zd2,
            self._pending, q_new, v_new, z_new,
        )  # fmt: skip
        return q_new, v_new, z_new

    def _push_startup(self, ships: NDArray[np.int64], v, a, qd, zd) -> None:
        self._v2[ships] = self._v1[ships]
        self._v1[ships] = v
        self._a2[ships] = self._a1[ships]
        self._a1[ships] = a
        self._qd2[ships] = self._qd1[ships]
        self._qd1[ships] = qd
        self._pending[ships] = True
        self._zd2[ships] = self._zd1[ships]
        self._zd1[ships] = zd

    # ------------------------------------------------------------------ stepping
    def step(self, commands: Mapping[str, ArrayLike] | None = None) -> NDArray[np.bool_]:
        """Advance every non-diverged ship by one physics step ``dt``.

        Parameters
        ----------
        commands : mapping, optional
            Actuator commands (arrays with a leading axis of N, or scalars for all ships),
            held over the step and merged into the current ones: a command stays in force
            until changed (as in :meth:`Simulator.step`).

        Returns
        -------
        numpy.ndarray
            (N,) bool, the ships that diverged in this step (they keep the state of the start
            of the step and are skipped until :meth:`reset`; see :attr:`divergence_messages`).
        """
        if commands is not None:
            self.commands = {**self.commands, **commands}
        newly = np.zeros(self.n_ships, dtype=bool)
        if self.diverged.any():
            ships = np.flatnonzero(~self.diverged)
            if ships.size == 0:
                return newly
            all_ships = False
            t, q, v, z = self.t[ships], self.eta[ships], self.nu[ships], self.z[ships]
        else:
            ships, all_ships = self._all, True
            t, q, v, z = self.t, self.eta, self.nu, self.z
        ac, zd, qd = self._rhs(ships, all_ships, t, q, v, z)
        if self.integrator_name == "rk4":
            q_new, v_new, z_new = self._rk4(ships, all_ships, t, q, v, z, (ac, zd, qd))
        else:
            k = self._k[ships]
            startup = k < _HOLLOWAY_STARTUP
            if not startup.any():
                q_new, v_new, z_new = self._holloway(ships, q, v, z, ac, zd, qd)
            else:
                q_new, v_new, z_new = np.empty_like(q), np.empty_like(v), np.empty_like(z)
            if startup.any() and not startup.all():
                r = np.flatnonzero(~startup)
                sr = ships[r]
                q_new[r], v_new[r], z_new[r] = self._holloway(
                    sr, q[r], v[r], z[r], ac[r], zd[r], qd[r]
                )
            if np.any(startup):
                r = np.flatnonzero(startup)
                sr = ships[r]
                every = r.size == self.n_ships
                q_new[r], v_new[r], z_new[r] = self._rk4(
                    sr, every, t[r], q[r], v[r], z[r], (ac[r], zd[r], qd[r])
                )
                self._push_startup(sr, v[r], ac[r], qd[r], zd[r])
            self._k[ships] = k + 1
        ok = np.empty(q_new.shape[0], dtype=np.bool_)
        _healthy_rows(q_new, v_new, z_new, self.max_abs_velocity, ok)
        if not ok.all():
            for row in np.flatnonzero(~ok):
                s = int(ships[row])
                newly[s] = True
                self.divergence_messages[s] = (
                    f"ship {s} diverged at t = {t[row] + self.dt:.3f} s (step "
                    f"{self.n_steps[s] + 1}): eta = {np.round(q_new[row], 4).tolist()}, "
                    f"nu = {np.round(v_new[row], 4).tolist()}; try a smaller dt (now {self.dt} s) "
                    f"or another integrator (now {self.integrator_name!r})"
                )
            self.diverged |= newly
            keep = np.flatnonzero(ok)
            ships, all_ships = ships[keep], False
            q_new, v_new, z_new = q_new[keep], v_new[keep], z_new[keep]
        if all_ships:
            self.t += self.dt
            self.eta, self.nu, self.z = q_new, v_new, z_new
            self.n_steps += 1
        else:
            self.t[ships] += self.dt
            self.eta[ships], self.nu[ships], self.z[ships] = q_new, v_new, z_new
            self.n_steps[ships] += 1
        if ships.size and any(type(f).commit is not BatchForceModel.commit for f in self.forces):
            ctx, _, _ = self._context(ships, all_ships, self.t[ships], q_new, v_new)
            for f, sl in zip(self.forces, self._slices, strict=True):
                f.commit(ctx, z_new[:, sl])
        return newly

    def run(self, n_steps: int, *, record_every: int = 1) -> dict[str, NDArray]:
        """Take ``n_steps`` steps and record the states.

        Returns
        -------
        dict
            ``"t"`` (n_rec, N), ``"eta"`` and ``"nu"`` (n_rec, N, 6), ``"diverged"`` (N,),
            the initial state included.
        """
        rec_t, rec_eta, rec_nu = [self.t.copy()], [self.eta.copy()], [self.nu.copy()]
        for i in range(int(n_steps)):
            self.step()
            if (i + 1) % record_every == 0:
                rec_t.append(self.t.copy())
                rec_eta.append(self.eta.copy())
                rec_nu.append(self.nu.copy())
        return {
            "t": np.array(rec_t),
            "eta": np.array(rec_eta),
            "nu": np.array(rec_nu),
            "diverged": self.diverged.copy(),
        }

    def record(
        self, duration: float, *, ship: int = 0, record_every: int = 1, progress: bool = False
    ) -> SimulationResult:
        """Advance every ship for ``duration`` seconds; the series of one ship.

        The engine's counterpart of :meth:`Simulator.run`: chunks of ``record_every`` steps
        (one compiled call each when the backend is compiled), the state of ship ``ship`` and
        the incident-wave elevation at its O after each chunk, the initial state included.

        Parameters
        ----------
        duration : float
            Simulated time [s], a positive multiple of ``dt``.
        ship : int
            The recorded ship.
        record_every : int
            Steps between records.
        progress : bool
            Show a tqdm progress bar.

        Raises
        ------
        SimulationDiverged
            If the recorded ship diverges (the series up to its last valid state is kept in
            the exception's ``result`` attribute).
        """
        n = steps_in(duration, self.dt)
        if isinstance(record_every, bool) or not isinstance(record_every, int) or record_every < 1:
            raise ValueError(f"record_every must be an integer ≥ 1, got {record_every!r}")
        s = int(self._as_ships([ship])[0])
        rec_t, rec_eta, rec_nu = [], [], []

        def keep() -> None:
            rec_t.append(float(self.t[s]))
            rec_eta.append(self.eta[s].copy())
            rec_nu.append(self.nu[s].copy())

        def result() -> SimulationResult:
            t, eta = np.array(rec_t), np.array(rec_eta)
            field = self.wave_fields[s]  # ζ at O from the recorded states, after the run
            zeta = np.zeros_like(t) if field is None else field.elevation(eta[:, 0], eta[:, 1], t)
            return SimulationResult(t, eta, np.array(rec_nu), zeta)

        bar = None
        if progress:
            from tqdm import tqdm

            bar = tqdm(total=n, desc="simulating", unit="step", mininterval=0.5)
        keep()
        left = n
        try:
            while left > 0:
                k = min(record_every, left)
                self.advance(k)
                left -= k
                if self.diverged[s]:
                    exc = SimulationDiverged(self.divergence_messages[s])
                    exc.result = result()
                    raise exc
                keep()
                if bar is not None:
                    bar.update(k)
        finally:
            if bar is not None:
                bar.close()
        return result()

    def force_breakdown(self) -> dict[str, NDArray]:
        """(N, 6) body-axis forces per model at the current states (all ships), plus
        ``"rigid_body"``: gravity − Coriolis–centripetal."""
        breakdown: dict[str, NDArray] = {}
        ctx, rigid, _ = self._context(self._all, True, self.t, self.eta, self.nu)
        breakdown["rigid_body"] = rigid.copy()
        self._generalised_force(ctx, rigid, self.z, breakdown)
        return breakdown

    def actuator_angles(self, name: str) -> NDArray:
        """(N,) servo angles [rad] of the actuated force model ``name`` (a copy).

        Raises
        ------
        ValueError
            If no force model of that name has a servo.
        """
        return self.actuator_model(name).angle.copy()

    def actuator_names(self) -> tuple[str, ...]:
        """Names of the servo-driven batch force models (rudder, fins, T-foil…), in force
        order (each is :meth:`actuator_model`)."""
        return tuple(f.name for f in self.forces if _servo_driven(f))

    def actuator_model(self, name: str):
        """The servo-driven batch force model named ``name``."""
        for f in self.forces:
            if f.name == name and _servo_driven(f):
                return f
        raise ValueError(
            f"no servo-driven force model named {name!r}; the models are "
            f"{[f.name for f in self.forces]}"
        )

    def elevation_at_ships(self) -> NDArray:
        """(N,) incident-wave elevation at each ship's O [m] (ζ = Re Σⱼ c'ⱼ)."""
        ctx, _, _ = self._context(self._all, True, self.t, self.eta, self.nu)
        return ctx.local_phasor.sum(axis=1).real


# =============================================================================================
# assembly
# =============================================================================================
def build_batch_simulator(
    setup: ShipSetup,
    wave_fields: Sequence[WaveField | None],
    *,
    sea: Sea = None,
    wave_heading: float = np.pi,
    max_components: int | None = None,
    extra_forces: Sequence[BatchForceModel] = (),
    control: Literal["batch", "per_ship"] = "batch",
    backend: EngineBackend = "auto",
    parallel: bool = False,
) -> BatchSimulator:
    """A batch of ships of one setup at the free-floating equilibrium, heading north.

    The batch counterpart of :func:`ship_gym.engine.ship.build_simulator`: ship s with
    ``wave_fields[s]`` behaves as ``build_simulator(setup, sea, wave_heading=…, rng=…)`` whose
    wave field is that one (make the fields with
    :func:`ship_gym.engine.ship.wave_field_for`).

    Parameters
    ----------
    setup : ShipSetup
        Ship, models and numerics (the Cummins convolution runs per ship on the numpy path).
    wave_fields : sequence of WaveField or None
        One sea per ship.
    sea : RegularWave or IrregularSea, optional
        Needed only for constant-coefficient radiation (2a/2b: the peak frequency sets ω_e).
    wave_heading : float
        Relative heading β [rad] used for ω_e of the 2a/2b coefficients.
    max_components : int, optional
        Padded component count (room for larger seas at reset).
    extra_forces : sequence of BatchForceModel
        Added after the setup's models (e.g. actuators, :class:`PerShipForceModel`).
    control : {"batch", "per_ship"}
        ``"batch"`` (default): the setup's control models (propulsion, manoeuvring, rudder,
        fins, T-foil, with their servos and controllers) by their vectorised versions
        (:mod:`ship_gym.engine.batch_control`); ``"per_ship"``: each copied once per ship and
        wrapped in a :class:`PerShipForceModel` (a Python loop over ships; the reference the
        vectorised versions are tested against). Models without a batch version (added
        resistance in waves) are per ship in both cases.
    backend : {"auto", "compiled", "numpy"}
        Engine path of :meth:`BatchSimulator.advance` (``"auto"``: compiled when every model
        has a compiled version).
    parallel : bool
        Spread the ships over numba's threads in the compiled loop.

    Notes
    -----
    The initial commands are broadcast to (N,) arrays in :attr:`BatchSimulator.commands`. With
    propulsion at a positive speed, each ship's shaft speed is trimmed on its assembled surge
    balance at its initial state, as :func:`ship_gym.engine.ship.build_simulator` does
    (:func:`ship_gym.engine.batch_control.trim_batch_shaft_speed`).
    """
    from ship_gym.forces.propeller import Propeller

    if control not in ("batch", "per_ship"):
        raise ValueError(f"control must be 'batch' or 'per_ship', got {control!r}")
    fields = list(wave_fields)
    ship = ship_of(setup)
    hull = ship.hull
    database = database_of(setup, ship)
    template = next((f for f in fields if f is not None), None)
    # a calm template still yields a Diffraction model (its table is all the batch needs)
    template_field = WaveField.calm() if template is None else template
    built = build_force_models(setup, hull, database, template_field, sea, wave_heading)
    models, commands = built if isinstance(built, tuple) else (built, {})
    n_ships = len(fields)
    batch_models: list[BatchForceModel] = []
    wave_models = (
        FroudeKrylovHydrostatics, RadiationMemory, ConstantCoefficientRadiation, Diffraction,
        ViscousRollDamping,
    )  # fmt: skip
    for m in models:
        vectorised: list[BatchForceModel] | None = None
        if control == "batch" or isinstance(m, wave_models):
            try:
                vectorised = batch_force_models([m])
            except NotImplementedError:
                if isinstance(m, FroudeKrylovHydrostatics | Diffraction):
                    raise
        if vectorised is not None:
            batch_models += vectorised
        else:  # control models run per ship: one independent copy per ship
            copies = [m] + [copy.deepcopy(m) for _ in range(n_ships - 1)]
            batch_models.append(PerShipForceModel(copies))
    batch_models += list(extra_forces)
    eq = equilibrium(hull)
    batch = BatchSimulator(
        hull,
        batch_models,
        fields,
        forward_speed=setup.speed,
        dt=setup.dt,
        integrator=setup.integrator,
        free_dofs=setup.free_dofs,
        initial_eta=np.array([0.0, 0.0, eq.heave, 0.0, eq.trim, 0.0]),
        max_components=max_components,
        commands={k: np.full(n_ships, v) if np.ndim(v) == 0 else v for k, v in commands.items()},
        backend=backend,
        parallel=parallel,
    )
    if setup.propulsion and setup.speed > 0.0:
        propeller = next(m for m in models if isinstance(m, Propeller))
        trim_batch_shaft_speed(batch, propeller, setup.speed)
    return batch
