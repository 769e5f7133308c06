"""The compiled backend of the row engine: K physics steps of N ships in one numba call.

The engine knows the row protocol of :mod:`ship_gym.forces.base`, never a force by name. Each
model of a :class:`~ship_gym.engine.batch.BatchSimulator` packs itself
(:meth:`~ship_gym.forces.base.BatchForceModel.pack` → :class:`~ship_gym.forces.base.RowPart`:
a numba row kernel, its record of arrays, its number of ODE states, optional step-start and
step-end hooks). :class:`CompiledBackend` then **composes** the compiled step from those
kernels: it writes the source of one small module that imports the kernels by name and calls
them in the models' order (:func:`step_module`), keyed by the set of kernels, in a cache folder
(``SHIP_GYM_CACHE_DIR``, default ``~/.cache/ship_gym``; numba caches the machine code beside
it, so a second process does not compile again). Per evaluation of ship s the composed step

* computes the rigid-body terms (:func:`ship_gym.engine.rigid_body.rigid_body_terms`: R(φ, θ,
  ψ), gravity and Coriolis–centripetal terms, η̇ = J(η) ν) and the wave components at the
  ship's origin (:func:`_local_phasors`), which every kernel sees in a
  :class:`~ship_gym.forces.base.RowContext`;
* calls each model's kernel, which adds its body-axis force about O and writes the derivative
  of its own slice of the ODE states z;
* solves ν̇ = M⁻¹ F with the per-ship inverse of the free block of M_RB + A(∞).

Around the evaluations it runs Holloway's μ-Taylor scheme after two RK4 start-up steps per
ship, or RK4, and calls the models' step-start hooks (commands sampled and held) and step-end
hooks (accepted steps).

Ships are independent in the loop (no reduction across ships reaches a state), so ship i of a
batch of N evolves bit for bit as the same ship alone; with ``parallel=True`` the ships are
spread over numba's threads. Per ship the call returns the task reductions over its K steps:
max |φ|, Σ φ², the number of steps with |φ| above a threshold, and whether it diverged (the
ship then keeps the state of the start of the failed step). The arithmetic is that of the
numpy path of :class:`BatchSimulator` (the reference, ``backend="numpy"``); the wave phasors
use the polynomial :func:`ship_gym.numerics.fastmath.sincos_turns` instead of libm, so the two
agree to rounding, not bit for bit (tested).

A model whose ``pack`` returns ``None`` (per-ship Python models such as added resistance in
waves, a resistance curve that is not Holtrop–Mennen, ``Diffraction(above_range="raise")``, a
bare surface group) sends the batch to the numpy path; so do the commands a model declares
numpy only (:attr:`~ship_gym.forces.base.RowLayout.numpy_only_commands`).
"""

from __future__ import annotations

import hashlib
import importlib.util
import math
import os
import sys
import tempfile
from pathlib import Path
from string import Template
from typing import TYPE_CHECKING, Any, NamedTuple

import numba as nb
import numpy as np
from numpy.typing import NDArray

from ship_gym.engine.rigid_body import rigid_body_terms
from ship_gym.forces.base import RowLayout, RowPart, WaveRecord
from ship_gym.forces.diffraction import diffraction_force, diffraction_row
from ship_gym.forces.diffraction import refresh_diffraction_cache as refresh_diffraction_cache
from ship_gym.forces.froude_krylov import _fk_core, _fk_core_f32, froude_krylov_row
from ship_gym.forces.radiation import radiation_record, radiation_row, state_space_radiation
from ship_gym.forces.viscous import viscous_roll_row
from ship_gym.numerics.fastmath import sincos_turns

if TYPE_CHECKING:
    from types import ModuleType

    from ship_gym.engine.batch import BatchSimulator
    from ship_gym.engine.ship import Sea, ShipSetup
    from ship_gym.waves.wave_field import WaveField

__all__ = [
    "CompiledBackend",
    "CompiledShip",
    "StepReductions",
    "build_compiled_ship",
    "step_module",
]

_TWO_PI = 2.0 * math.pi
_HOLLOWAY_STARTUP = 2  # RK4 steps before μ-Taylor steps (as BatchSimulator)


class RigidRecord(NamedTuple):
    """Per-ship M_RB about O (N, 6, 6), weight m g [N], G (N, 3), held angles (3,), and the
    inverse of the free block of M_RB + A_lhs (N, 6, 6; zeros for held DOFs)."""

    mass: NDArray
    weight: float
    cog: NDArray
    held_angle: NDArray
    m_inv: NDArray


class StepReductions(NamedTuple):
    """What a task needs of K physics steps, per ship (N,).

    Attributes
    ----------
    max_abs_roll : numpy.ndarray
        max |φ| over the start state and the K new states [rad].
    sum_sq_roll : numpy.ndarray
        Σ φ² over the K new states [rad²].
    danger_steps : numpy.ndarray
        Number of the K new states with |φ| > the threshold.
    diverged : numpy.ndarray
        bool, the ships that diverged during the call.
    """

    max_abs_roll: NDArray
    sum_sq_roll: NDArray
    danger_steps: NDArray
    diverged: NDArray


def _c(array: Any, dtype: type = np.float64) -> NDArray:
    return np.ascontiguousarray(array, dtype=dtype)


@nb.njit(cache=True, nogil=True)
def _local_phasors(t, x, y, amplitude, omega_t, phase_t, ramp_time, kxt, kyt, mod, offset, local):
    """The components at the ship's O: c'ⱼ = cⱼ(t) e^{−i kⱼ (x cos χⱼ + y sin χⱼ)} with
    cⱼ(t) = r(t) aⱼ e^{i(ωⱼt + εⱼ)} and Matusiak's ramp r (``batch._wave_phasors``), as
    modulus r aⱼ, phase offset −arg c'ⱼ/2π [turns] reduced to [−½, ½] (what the Froude–Krylov
    kernel takes, :func:`ship_gym.forces.froude_krylov._fk_core`) and complex c'ⱼ
    (diffraction); returns Σ|c'ⱼ|. omega_t, phase_t: ωⱼ/2π [turns/s], εⱼ/2π [turns]; kxt, kyt:
    kⱼ cos χⱼ/2π, kⱼ sin χⱼ/2π [turns/m]. No libm trig: one polynomial sin/cos per component.
    """
    if ramp_time > 0.0 and t < ramp_time:
        u = min(max(t / ramp_time, 0.0), 1.0)
        r = math.sin(0.5 * math.pi * u) ** 2
    else:
        r = 1.0
    crest = 0.0
    for j in range(amplitude.shape[0]):
        m = r * amplitude[j]
        turns = (kxt[j] * x + kyt[j] * y) - (omega_t[j] * t + phase_t[j])
        o = turns - np.rint(turns)
        mod[j] = m
        offset[j] = o
        crest += abs(m)
        sn, cs = sincos_turns(-o)
        local[j] = complex(m * cs, m * sn)
    return crest


# ============================================================================================
# the composed step
# ============================================================================================
_STEP_SOURCE = Template('''\
"""Compiled step of ship_gym composed by ship_gym.engine.compiled.step_module (generated:
do not edit). Kernels, in the models' order: $names."""

import numba as nb
import numpy as np

from ship_gym.engine.compiled import _local_phasors
from ship_gym.engine.rigid_body import healthy_state, rigid_body_terms
from ship_gym.forces.base import RowContext
$imports

_HOLLOWAY_STARTUP = $startup


@nb.njit(cache=True, nogil=True)
def _evaluate(s, t, q, v, z, zo, ctx, rigid, ${rp}total, acc, zdot, qdot):
    """ν̇ (acc), ż and η̇ (qdot) of ship s at (t, q, v, z)."""
    rigid_body_terms(
        q, v, rigid.mass[s], rigid.weight, rigid.cog[s], rigid.held_angle, ctx.rot, total, qdot
    )
    w = ctx.waves
    shared = ctx.shared
    shared[0] = _local_phasors(
        t, q[0], q[1], w.amplitude[s], w.omega_t[s], w.phase_t[s], w.ramp_time[s], w.kxt[s],
        w.kyt[s], ctx.mod, ctx.offset, ctx.local,
    )
    for i in range(1, shared.shape[0]):
        shared[i] = 0.0
$kernels
    m_inv = rigid.m_inv[s]
    for i in range(6):
        a = 0.0
        for j in range(6):
            a += m_inv[i, j] * total[j]
        acc[i] = a


@nb.njit(cache=True, nogil=True)
def _advance_ship(
    s, n_steps, use_rk4, dt, mu, v_max, danger, t_arr, eta, nu, z, k_count, pending, hist,
    waves, rigid, ${rp}zo, n_shared, cmd, red_max, red_sum, red_danger,
):
    """Up to n_steps steps of ship s; returns the number of steps completed (fewer: it
    diverged, the state of that step's start kept). ``hist``: the Holloway histories (v1, v2,
    a1, a2, qd1, qd2, qdd1, qdd2, zd1, zd2), rows per ship."""
    v1, v2, a1, a2, qd1, qd2, qdd1, qdd2, zd1, zd2 = hist
    nz = z.shape[1]
    n_c = waves.amplitude.shape[1]
    q, v, zz = eta[s], nu[s], z[s]
    qs, vs, zs = np.empty(6), np.empty(6), np.empty(nz)
    q_new, v_new, z_new = np.empty(6), np.empty(6), np.empty(nz)
    a_c, d_c, g_c = np.empty(6), np.empty(6), np.empty(nz)
    a2s, d2, g2 = np.empty(6), np.empty(6), np.empty(nz)
    a3s, d3, g3 = np.empty(6), np.empty(6), np.empty(nz)
    a4s, d4, g4 = np.empty(6), np.empty(6), np.empty(nz)
    total = np.empty(6)
    ctx = RowContext(
        np.empty((3, 3)), waves, np.empty(n_c), np.empty(n_c), np.empty(n_c, dtype=np.complex128),
        cmd, np.zeros(n_shared), np.empty(6),
    )
    c = 0.5 / dt
    h2 = 0.5 * dt * dt
    h3 = dt * dt * dt / 6.0
    roll_max = abs(q[3])
    for step in range(n_steps):
        t = t_arr[s]
$starts
        _evaluate(s, t, q, v, zz, zo, ctx, rigid, ${rp}total, a_c, g_c, d_c)
        if use_rk4 or k_count[s] < _HOLLOWAY_STARTUP:
            hh = 0.5 * dt
            for stage in range(3):
                if stage == 0:
                    ca, ga, da, tt, cs = a_c, g_c, d_c, t + hh, hh
                    ao, go, do = a2s, g2, d2
                elif stage == 1:
                    ca, ga, da, tt, cs = a2s, g2, d2, t + hh, hh
                    ao, go, do = a3s, g3, d3
                else:
                    ca, ga, da, tt, cs = a3s, g3, d3, t + dt, dt
                    ao, go, do = a4s, g4, d4
                for i in range(6):
                    qs[i] = q[i] + cs * da[i]
                    vs[i] = v[i] + cs * ca[i]
                for i in range(nz):
                    zs[i] = zz[i] + cs * ga[i]
                _evaluate(s, tt, qs, vs, zs, zo, ctx, rigid, ${rp}total, ao, go, do)
            c6 = dt / 6.0
            for i in range(6):
                q_new[i] = q[i] + c6 * (d_c[i] + 2.0 * (d2[i] + d3[i]) + d4[i])
                v_new[i] = v[i] + c6 * (a_c[i] + 2.0 * (a2s[i] + a3s[i]) + a4s[i])
            for i in range(nz):
                z_new[i] = zz[i] + c6 * (g_c[i] + 2.0 * (g2[i] + g3[i]) + g4[i])
            if not healthy_state(q_new, v_new, z_new, v_max):
                red_max[s] = max(red_max[s], roll_max)
                return step
            if not use_rk4:  # start-up history (BatchSimulator._push_startup)
                for i in range(6):
                    v2[s, i] = v1[s, i]
                    v1[s, i] = v[i]
                    a2[s, i] = a1[s, i]
                    a1[s, i] = a_c[i]
                    qd2[s, i] = qd1[s, i]
                    qd1[s, i] = d_c[i]
                for i in range(nz):
                    zd2[s, i] = zd1[s, i]
                    zd1[s, i] = g_c[i]
                pending[s] = True
        else:
            # Holloway's μ-Taylor step (eq. 4, 6–9), history shifted only for a healthy step
            for i in range(6):
                ae = (3.0 * v[i] - 4.0 * v1[s, i] + v2[s, i]) * c  # eq. 6
                a = mu[i] * a_c[i] + (1.0 - mu[i]) * ae  # eq. 4
                jerk = (3.0 * a - 4.0 * a1[s, i] + a2[s, i]) * c  # eq. 7
                v_new[i] = v[i] + dt * a + h2 * jerk  # eq. 8
                a2s[i] = a
            if pending[s]:
                for i in range(6):
                    d2[i] = (-3.0 * qd2[s, i] + 4.0 * qd1[s, i] - d_c[i]) * c
                    d3[i] = (d_c[i] - qd2[s, i]) * c
            else:
                for i in range(6):
                    d2[i] = qdd2[s, i]
                    d3[i] = qdd1[s, i]
            for i in range(6):
                qdd = (3.0 * d_c[i] - 4.0 * qd1[s, i] + qd2[s, i]) * c
                qddd = (3.0 * qdd - 4.0 * d3[i] + d2[i]) * c
                q_new[i] = q[i] + dt * d_c[i] + h2 * qdd + h3 * qddd  # eq. 9
                d4[i] = qdd
            for i in range(nz):
                zdd = (3.0 * g_c[i] - 4.0 * zd1[s, i] + zd2[s, i]) * c
                z_new[i] = zz[i] + dt * g_c[i] + h2 * zdd
            if not healthy_state(q_new, v_new, z_new, v_max):
                red_max[s] = max(red_max[s], roll_max)
                return step
            for i in range(6):
                a2[s, i] = a1[s, i]
                a1[s, i] = a2s[i]
                v2[s, i] = v1[s, i]
                v1[s, i] = v[i]
                qd2[s, i] = qd1[s, i]
                qd1[s, i] = d_c[i]
                qdd2[s, i] = d3[i]
                qdd1[s, i] = d4[i]
            for i in range(nz):
                zd2[s, i] = zd1[s, i]
                zd1[s, i] = g_c[i]
            pending[s] = False
        t_new = t + dt
$ends
        for i in range(6):
            q[i] = q_new[i]
            v[i] = v_new[i]
        for i in range(nz):
            zz[i] = z_new[i]
        t_arr[s] = t_new
        k_count[s] += 1
        roll = q[3]
        ar = abs(roll)
        roll_max = max(roll_max, ar)
        red_sum[s] += roll * roll
        if ar > danger:
            red_danger[s] += 1
    red_max[s] = max(red_max[s], roll_max)
    return n_steps


@nb.njit(cache=True, nogil=True)
def advance_serial(
    ships, n_steps, use_rk4, dt, mu, v_max, danger, t_arr, eta, nu, z, k_count, pending, hist,
    waves, rigid, ${rp}zo, n_shared, cmd, red_max, red_sum, red_danger, done,
):
    for r in range(ships.shape[0]):
        s = ships[r]
        done[s] = _advance_ship(
            s, n_steps, use_rk4, dt, mu, v_max, danger, t_arr, eta, nu, z, k_count, pending,
            hist, waves, rigid, ${rp}zo, n_shared, cmd, red_max, red_sum, red_danger,
        )


@nb.njit(cache=True, nogil=True, parallel=True)
def advance_parallel(
    ships, n_steps, use_rk4, dt, mu, v_max, danger, t_arr, eta, nu, z, k_count, pending, hist,
    waves, rigid, ${rp}zo, n_shared, cmd, red_max, red_sum, red_danger, done,
):
    for r in nb.prange(ships.shape[0]):
        s = ships[r]
        # the records travel one by one, as arguments (numba's parfor finds a record's type
        # only from an argument of the function)
        done[s] = _advance_ship(
            s, n_steps, use_rk4, dt, mu, v_max, danger, t_arr, eta, nu, z, k_count, pending,
            hist, waves, rigid, ${rp}zo, n_shared, cmd, red_max, red_sum, red_danger,
        )
''')


def _kernel_name(func: Any) -> tuple[str, str]:
    """(module, qualified name) of a module-level numba kernel, checked importable."""
    module = getattr(func, "__module__", None)
    name = getattr(func, "__qualname__", getattr(func, "__name__", None))
    if not module or not name or "." in name or "<" in name:
        raise NotImplementedError(
            f"row kernel {func!r} must be a numba.njit function at the top level of a module"
        )
    if getattr(sys.modules.get(module), name, None) is not func:
        raise NotImplementedError(f"row kernel {module}.{name} is not importable by that name")
    return module, name


def _source_stamp(modules: set[str]) -> str:
    """A digest of the source files the composed step depends on: every file of the
    ``ship_gym`` package and the modules of the kernels (a changed kernel is a new step)."""
    files: set[Path] = set(Path(__file__).resolve().parents[1].rglob("*.py"))  # the package
    for m in modules:
        f = getattr(sys.modules.get(m), "__file__", None)
        if f:
            files.add(Path(f))
    h = hashlib.sha256()
    for f in sorted(files):
        st = f.stat()
        h.update(f"{f}:{st.st_mtime_ns}:{st.st_size}\n".encode())
    return h.hexdigest()[:16]


def _cache_dir() -> Path:
    """Where composed steps are written: ``SHIP_GYM_CACHE_DIR``, else ``~/.cache/ship_gym``
    (the system's temporary folder when that is not writable)."""
    env = os.environ.get("SHIP_GYM_CACHE_DIR")
    candidates = [Path(env)] if env else []
    candidates += [Path.home() / ".cache" / "ship_gym", Path(tempfile.gettempdir()) / "ship_gym"]
    for d in candidates:
        try:
            (d / "steps").mkdir(parents=True, exist_ok=True)
            if os.access(d / "steps", os.W_OK):
                return d / "steps"
        except OSError:
            continue
    raise OSError("no writable folder for the composed compiled steps")


_STEPS: dict[tuple, ModuleType] = {}
_STAMPS: dict[frozenset, str] = {}


def step_module(parts: list[RowPart]) -> ModuleType:
    """The compiled step composed of ``parts``' kernels, in their order.

    The source (:data:`_STEP_SOURCE`) calls each kernel with its record ``recs[i]`` and its slice
    ``z[zo[i]:zo[i + 1]]`` of the ODE states, and each hook at the step start and end; it is
    written once per set of kernels (and source stamp of the package) in :func:`_cache_dir` and
    imported, so numba's disk cache serves the next process. Returns the module (functions
    ``advance_serial`` and ``advance_parallel``).
    """
    funcs = [(p.kernel, p.step_start, p.step_end) for p in parts]
    key = tuple(funcs)
    module = _STEPS.get(key)
    if module is not None:
        return module
    imports: list[str] = []
    names: dict[Any, str] = {}
    modules: set[str] = set()

    def alias(func: Any) -> str:
        if func not in names:
            mod, name = _kernel_name(func)
            names[func] = f"_k{len(names)}"
            modules.add(mod)
            imports.append(f"from {mod} import {name} as {names[func]}")
        return names[func]

    kernels, starts, ends = [], [], []
    for i, (kernel, start, end) in enumerate(funcs):
        z = f"z[zo[{i}] : zo[{i + 1}]]"
        zd = f"zdot[zo[{i}] : zo[{i + 1}]]"
        kernels.append(f"    {alias(kernel)}(s, t, q, v, {z}, {zd}, ctx, r{i}, total)")
        if start is not None:
            starts.append(f"        {alias(start)}(s, t, q, v, cmd, r{i})")
        if end is not None:
            ends.append(f"        {alias(end)}(s, t_new, q_new, v_new, r{i})")
    stamp_key = frozenset(modules)
    if stamp_key not in _STAMPS:
        _STAMPS[stamp_key] = _source_stamp(modules)
    source = _STEP_SOURCE.substitute(
        names=", ".join(f"{_kernel_name(k)[0]}.{_kernel_name(k)[1]}" for k, _, _ in funcs)
        or "none",
        imports="\n".join(imports),
        startup=_HOLLOWAY_STARTUP,
        kernels="\n".join(kernels) or "    pass",
        starts="\n".join(starts) or "        pass",
        ends="\n".join(ends) or "        pass",
        rp="".join(f"r{i}, " for i in range(len(funcs))),
    )
    digest = hashlib.sha256((source + _STAMPS[stamp_key]).encode()).hexdigest()[:20]
    name = f"ship_gym_step_{digest}"
    path = _cache_dir() / f"{name}.py"
    if not path.exists():  # written once: numba's cache is keyed by the file's time stamp
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(source, encoding="utf-8")
        if not path.exists():
            os.replace(tmp, path)
        else:
            tmp.unlink()
    module = sys.modules.get(name)
    if module is None:
        spec = importlib.util.spec_from_file_location(name, path)
        assert spec is not None and spec.loader is not None
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
    _STEPS[key] = module
    return module


# ============================================================================================
# the backend
# ============================================================================================
class CompiledBackend:
    """The compiled loop over a :class:`BatchSimulator`'s ships (module docstring).

    Built by :meth:`BatchSimulator.compiled_backend`; the models' records hold views of their
    own per-ship arrays (diffraction caches, actuator states), so the numpy path and this one
    can be mixed.

    Raises
    ------
    NotImplementedError
        When a model has no row kernel (the message names it).
    """

    def __init__(self, sim: BatchSimulator) -> None:
        self.sim = sim
        self.parts, layout = self._pack()
        self.module = step_module(self.parts)
        """The composed step (:func:`step_module`)."""
        self._layout = layout
        self.numpy_only_commands: frozenset[str] = frozenset(layout.numpy_only_commands)
        """Command keys that make a call run on the numpy path (see :meth:`handles_commands`)."""
        self._records_version = sim.layout_version
        self._records_cache = self._build_records(layout)
        self._entry: dict[Any, Any] = {}

    # ------------------------------------------------------------------ set-up
    def _pack(self) -> tuple[list[RowPart], RowLayout]:
        sim = self.sim
        layout = RowLayout(sim.n_ships, sim.n_components, sim.forward_speed, sim.seas)
        parts: list[RowPart] = []
        for f in sim.forces:
            part = f.pack(layout)
            if part is None:
                raise NotImplementedError(
                    f"force model {f.name!r} ({type(f).__name__}) has no compiled version"
                )
            if int(part.n_states) != int(f.n_states):
                raise NotImplementedError(
                    f"force model {f.name!r} packs {part.n_states} states but declares {f.n_states}"
                )
            parts.append(part)
        if not layout.command_keys:
            layout.column("unused", 0.0)
        return parts, layout

    @staticmethod
    def check(sim: BatchSimulator) -> None:
        """Raise NotImplementedError naming the first model without a compiled version."""
        CompiledBackend(sim)

    def record_of(self, kernel: Any) -> tuple | None:
        """The record of the first model whose row kernel is ``kernel`` (None without one)."""
        return next((p.record for p in self.parts if p.kernel is kernel), None)

    def handles_commands(self) -> bool:
        """Whether the compiled loop reads every command in force the way the numpy path does."""
        return not (self.numpy_only_commands & self.sim.commands.keys())

    def command_matrix(self) -> NDArray:
        """(N, n_cmd) the commands in force (arrays over N or scalars; defaults filled).

        Raises
        ------
        ValueError
            For a command of the wrong shape or not finite (naming its key).
        """
        sim = self.sim
        keys, defaults = self._layout.command_keys, self._layout.command_defaults
        out = np.empty((sim.n_ships, len(keys)))
        for j, (key, default) in enumerate(zip(keys, defaults, strict=True)):
            value = sim.commands.get(key, None)
            if value is None:
                if callable(default):
                    value = default()
                elif default is None:
                    raise ValueError(
                        f"no {key!r} command and no default (e.g. the propeller's shaft speed)"
                    )
                else:
                    value = default
            arr = np.asarray(value, dtype=float)
            if arr.ndim and arr.shape != (sim.n_ships,):
                raise ValueError(
                    f"commands[{key!r}] must be a scalar or an (N,) array over the ships; got "
                    f"shape {arr.shape}"
                )
            out[:, j] = arr
        if not np.isfinite(out).all():  # one check for all; name the offending key
            j = int(np.flatnonzero(~np.isfinite(out).all(axis=0))[0])
            key = keys[j]
            raise ValueError(f"commands[{key!r}] must be finite; got {sim.commands.get(key)!r}")
        return out

    def _records(self) -> tuple:
        """(waves, rigid, model records, state offsets, n_shared), rebuilt when a sea or a
        loading changed (the models are packed again)."""
        if self._records_version != self.sim.layout_version:
            parts, layout = self._pack()
            if [p.kernel for p in parts] != [p.kernel for p in self.parts]:
                raise AssertionError("a model changed its row kernel between two packings")
            self.parts, self._layout = parts, layout
            self._records_cache = self._build_records(layout)
            self._records_version = self.sim.layout_version
        return self._records_cache

    def _build_records(self, layout: RowLayout) -> tuple:
        sim = self.sim
        seas = sim.seas
        kxt = seas.kx / _TWO_PI
        kyt = seas.ky / _TWO_PI
        k2 = seas.wavenumber / math.log(2.0)
        waves = WaveRecord(
            _c(seas.amplitude), _c(seas.omega / _TWO_PI), _c(seas.phase / _TWO_PI),
            _c(seas.ramp_time), _c(kxt), _c(kyt), _c(k2), _c(kxt, np.float32),
            _c(kyt, np.float32), _c(k2, np.float32),
        )  # fmt: skip
        rigid = RigidRecord(*sim.rigid_rows())
        recs = tuple(p.record for p in self.parts)
        zo = np.zeros(len(self.parts) + 1, dtype=np.int64)
        zo[1:] = np.cumsum([int(p.n_states) for p in self.parts], dtype=np.int64)
        return waves, rigid, recs, zo, len(layout.slots)

    # ------------------------------------------------------------------ running
    def _call(self, args: tuple) -> None:
        """Call the compiled loop; after the first call, its compiled entry point directly.

        numba's dispatcher resolves the types of the record fields at every call (a cost per
        call: docs/benchmarks.md); the entry point of the specialisation it chose skips that.
        Should the argument types ever change (another array layout), the dispatcher is used again.
        """
        mod = self.module
        run = mod.advance_parallel if self.sim.parallel else mod.advance_serial
        entry = self._entry.get(run)
        if entry is not None:
            try:
                entry(*args)
                return
            except TypeError:
                del self._entry[run]
        run(*args)
        overload = run.overloads.get(tuple(nb.typeof(a) for a in args))
        if overload is not None:
            # numba builds CompileResult's fields from a list
            self._entry[run] = overload.entry_point

    def advance(
        self, ships: NDArray, n_steps: int, danger: float, cmd: NDArray | None = None
    ) -> tuple[StepReductions, NDArray]:
        """Up to ``n_steps`` steps of each of ``ships`` with the commands held.

        Returns the reductions over the steps (arrays over all N; zeros for ships not run) and
        the (N,) number of steps each ship completed (fewer than ``n_steps``: it diverged).
        """
        sim = self.sim
        n = sim.n_ships
        waves, rigid, recs, zo, n_shared = self._records()
        if cmd is None:
            cmd = self.command_matrix()
        red_max = np.zeros(n)
        red_sum = np.zeros(n)
        red_danger = np.zeros(n, dtype=np.int64)
        done = np.zeros(n, dtype=np.int64)
        st = sim.engine_state()
        if ships.dtype != np.int64 or not ships.flags.c_contiguous:
            ships = _c(ships, np.int64)
        args = (
            ships, int(n_steps), sim.integrator_name == "rk4", float(sim.dt), sim.mu,
            float(sim.max_abs_velocity), float(danger), st.t, st.eta, st.nu, st.z, st.k_count,
            st.pending, st.history, waves, rigid, *recs, zo, n_shared, cmd, red_max, red_sum,
            red_danger, done,
        )  # fmt: skip
        self._call(args)
        diverged = done < n_steps
        if ships.shape[0] != n:
            ran = np.zeros(n, dtype=bool)
            ran[ships] = True
            diverged &= ran
        return StepReductions(red_max, red_sum, red_danger, diverged), done


# ============================================================================================
# per-term timing loops (CompiledShip.term_costs)
# ============================================================================================
@nb.njit(cache=True)
def _loop_phasors(n, t, q, amplitude, omega_t, phase_t, ramp_time, kxt, kyt, mod, offset, local):
    crest = 0.0
    for _ in range(n):
        crest = _local_phasors(
            t, q[0], q[1], amplitude, omega_t, phase_t, ramp_time, kxt, kyt, mod, offset, local
        )
    return crest


@nb.njit(cache=True)
def _loop_fk(
    n, body, tri, tri_last, tri_first, spread, weights, areas, rho_g, single, rot, z0, kxt, kyt,
    k2, kxt32, kyt32, k232, mod, offset, crest,
):  # fmt: skip  # pragma: no cover - compiled
    fe = np.zeros(6)
    for _ in range(n):
        fe[:] = 0.0
        if single:
            _fk_core_f32(
                body, tri, tri_last, tri_first, spread, weights, areas, rot, z0, kxt32, kyt32,
                k232, mod.astype(np.float32), offset.astype(np.float32), crest, rho_g, fe,
            )  # fmt: skip
        else:
            _fk_core(
                body, tri, tri_last, tri_first, spread, weights, areas, rot, z0, kxt, kyt, k2,
                mod, offset, crest, rho_g, fe,
            )  # fmt: skip
    return fe


@nb.njit(cache=True)
def _loop_radiation(
    n, v, z, speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat, has_d,
    p_inf, p_mem, cutoff,
):  # fmt: skip  # pragma: no cover - compiled
    total = np.zeros(6)
    zdot = np.empty(z.shape[0])
    for _ in range(n):
        state_space_radiation(
            v, z, speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat,
            has_d, p_inf, p_mem, cutoff, total, zdot,
        )  # fmt: skip
    return total


@nb.njit(cache=True)
def _loop_diffraction(n, psi, u, local, xd, dxd, diff_ref):  # pragma: no cover - compiled
    total = np.zeros(6)
    for _ in range(n):
        diffraction_force(psi, u, local, xd, dxd, diff_ref, total)
    return total


@nb.njit(cache=True)
def _loop_rigid(n, q, v, mass, weight, cog, held_angle, b1, b2):  # pragma: no cover - compiled
    rot = np.empty((3, 3))
    total = np.empty(6)
    qdot = np.empty(6)
    for _ in range(n):
        rigid_body_terms(q, v, mass, weight, cog, held_angle, rot, total, qdot)
        p_roll = v[3]
        total[3] += -(b1 * p_roll + b2 * abs(p_roll) * p_roll)
    return total


# ============================================================================================
# one ship
# ============================================================================================
class CompiledShip:
    """One ship on the compiled engine: a :class:`BatchSimulator` of N = 1 with a single-ship
    face (states as (6,) views, :class:`SimulationDiverged` raised, a recorded :meth:`run`).

    Built by :func:`build_compiled_ship`. Any force set the engine compiles works (control
    models included); commands go to :meth:`advance`.

    Attributes
    ----------
    sim : BatchSimulator
        The engine (``backend="compiled"``).
    """

    def __init__(self, sim: BatchSimulator) -> None:
        if sim.n_ships != 1:
            raise ValueError(f"CompiledShip holds one ship, got a batch of {sim.n_ships}")
        self.sim = sim
        self.hull = sim.hull
        self.dt = sim.dt
        self.forward_speed = sim.forward_speed
        self.integrator_name = sim.integrator_name
        self.n_states = sim.n_states
        self.wave_field = sim.wave_fields[0]
        self.backend = sim._compiled_backend()
        if self.backend is None:
            raise NotImplementedError(f"no compiled version: {sim._compiled_error}")

    @property
    def initial_eta(self) -> NDArray:
        """(6,) default initial η of :meth:`reset` (the free-floating equilibrium)."""
        return self.sim.initial_eta

    @property
    def max_abs_velocity(self) -> float:
        """|ν| above which the ship is declared diverged [m/s, rad/s] (the engine's)."""
        return self.sim.max_abs_velocity

    @max_abs_velocity.setter
    def max_abs_velocity(self, value: float) -> None:
        self.sim.max_abs_velocity = float(value)

    @property
    def eta(self) -> NDArray:
        """(6,) position and Euler angles (a view)."""
        return self.sim.eta[0]

    @property
    def nu(self) -> NDArray:
        """(6,) body velocities (a view)."""
        return self.sim.nu[0]

    @property
    def z(self) -> NDArray:
        """(n_states,) radiation memory states (a view)."""
        return self.sim.z[0]

    @property
    def t(self) -> float:
        """Time [s]."""
        return float(self.sim.t[0])

    @property
    def n_steps(self) -> int:
        """Steps since the last reset."""
        return int(self.sim.n_steps[0])

    @property
    def n_refreshes(self) -> int:
        """Diffraction cache refreshes inside the compiled loop since construction."""
        return sum(int(getattr(f, "refresh_count", 0)) for f in self.sim.forces)

    def reset(self, eta: NDArray | None = None, nu: NDArray | None = None, t0: float = 0.0):
        """Restart at ``t0`` from (η, ν) (defaults: the equilibrium, (U, 0, …, 0))."""
        self.sim.reset(eta=eta, nu=nu, t0=t0)

    def advance(self, n_steps: int = 1, commands: dict | None = None) -> None:
        """Take ``n_steps`` steps in one compiled call.

        Raises
        ------
        SimulationDiverged
            If a step produces a non-finite or too fast state; the ship keeps the state of the
            start of that step.
        """
        from ship_gym.engine.results import SimulationDiverged

        if int(n_steps) < 0:
            raise ValueError(f"n_steps must be ≥ 0, got {n_steps!r}")
        if self.sim.diverged[0]:
            raise SimulationDiverged(self.sim.divergence_messages[0])
        if int(n_steps) == 0:
            return
        cmd = None if commands is None else {k: np.atleast_1d(v) for k, v in commands.items()}
        self.sim.advance(int(n_steps), cmd)
        if self.sim.diverged[0]:
            raise SimulationDiverged(self.sim.divergence_messages[0])

    def run(self, n_steps: int, *, record_every: int = 1) -> dict[str, NDArray]:
        """Take ``n_steps`` steps, recording every ``record_every``-th state.

        Returns
        -------
        dict
            ``"t"`` (n_rec,), ``"eta"`` and ``"nu"`` (n_rec, 6), the initial state included.
        """
        if record_every < 1:
            raise ValueError(f"record_every must be ≥ 1, got {record_every!r}")
        ts, etas, nus = [self.t], [self.eta.copy()], [self.nu.copy()]
        left = int(n_steps)
        while left > 0:
            n = min(record_every, left)
            self.advance(n)
            left -= n
            if n == record_every:
                ts.append(self.t)
                etas.append(self.eta.copy())
                nus.append(self.nu.copy())
        return {"t": np.array(ts), "eta": np.array(etas), "nu": np.array(nus)}

    def term_costs(self, repeats: int = 200, rounds: int = 5) -> dict[str, float]:
        """CPU time [s] of one call of each term of an evaluation at the current state.

        Each term runs ``repeats`` times in a compiled loop (no Python in between), the
        fastest of ``rounds`` loops is kept (``time.process_time``). Keys:
        ``"froude_krylov_hydrostatic"``, ``"wave_phasors"``, ``"radiation"``,
        ``"diffraction"`` (0 without it), ``"rigid_body_viscous_roll"``. Timing only.
        """
        import time

        b = self.backend
        waves, rigid, _, _, _ = b._records()
        w: list[Any] = [x[0] if np.ndim(x) else float(x[0]) for x in waves]
        amp, omega_t, phase_t, ramp, kxt, kyt, k2, kxt32, kyt32, k232 = w
        n_c = amp.shape[0]
        mod, offset = np.empty(n_c), np.empty(n_c)
        local = np.empty(n_c, dtype=np.complex128)
        q, v, t = self.eta.copy(), self.nu.copy(), self.t
        rot = np.empty((3, 3))
        mass, weight, cog, held = rigid.mass[0], rigid.weight, rigid.cog[0], rigid.held_angle
        rigid_body_terms(q, v, mass, weight, cog, held, rot, np.empty(6), np.empty(6))
        crest = _local_phasors(
            t, q[0], q[1], amp, omega_t, phase_t, ramp, kxt, kyt, mod, offset, local
        )
        h: Any = b.record_of(froude_krylov_row)
        hull = (h.body, h.tri, h.tri_last, h.tri_first, h.spread, h.weights, h.areas, h.rho_g)
        rad = b.record_of(radiation_row)
        if rad is None:
            rad = radiation_record(self.sim.forward_speed, None, None)
        diff: Any = b.record_of(diffraction_row)
        visc = b.record_of(viscous_roll_row) or (0.0, 0.0)
        if diff is not None:
            xd, dxd, diff_ref = diff.xd[0], diff.dxd[0], diff.ref[0]
        else:
            xd = dxd = np.zeros((n_c, 8), np.complex128)
            diff_ref = np.array([q[5], v[0]])
        jobs = {
            "froude_krylov_hydrostatic": lambda n: _loop_fk(
                n, *hull, h.single, rot, q[2], kxt, kyt, k2, kxt32, kyt32, k232, mod, offset,
                crest,
            ),
            "wave_phasors": lambda n: _loop_phasors(
                n, t, q, amp, omega_t, phase_t, ramp, kxt, kyt, mod.copy(), offset.copy(),
                local.copy(),
            ),
            "radiation": lambda n: _loop_radiation(n, v, self.z.copy(), *rad),
            "diffraction": lambda n: _loop_diffraction(n, q[5], v[0], local, xd, dxd, diff_ref),
            "rigid_body_viscous_roll": lambda n: _loop_rigid(
                n, q, v, mass, weight, cog, held, visc[0], visc[1]
            ),
        }  # fmt: skip
        out: dict[str, float] = {}
        for name, job in jobs.items():
            if name == "diffraction" and diff is None:
                out[name] = 0.0
                continue
            job(1)  # compile
            best = np.inf
            for _ in range(rounds):
                c0 = time.process_time()
                job(repeats)
                best = min(best, (time.process_time() - c0) / repeats)
            out[name] = float(best)
        return out


def build_compiled_ship(
    setup: ShipSetup,
    wave_field: WaveField | None,
    *,
    sea: Sea = None,
    wave_heading: float = np.pi,
    precision: str | None = None,
) -> CompiledShip:
    """One ship of ``setup`` at the free-floating equilibrium on the compiled engine.

    Parameters
    ----------
    setup : ShipSetup
        ``integrator`` "holloway" or "rk4"; every model must have a compiled version.
    wave_field : WaveField or None
        The sea (:func:`ship_gym.engine.ship.wave_field_for`).
    sea, wave_heading
        As for :func:`ship_gym.engine.batch.build_batch_simulator` (2a/2b radiation).
    precision : {"float64", "float32"}, optional
        Wave sums of the Froude–Krylov kernel (overrides ``setup.fk_method``).
    """
    import dataclasses

    from ship_gym.engine.batch import build_batch_simulator

    if precision is not None:
        if precision not in ("float64", "float32"):
            raise ValueError(f"precision must be 'float64' or 'float32', got {precision!r}")
        setup = dataclasses.replace(setup, fk_method="fast32" if precision == "float32" else "fast")
    sim = build_batch_simulator(
        setup, [wave_field], sea=sea, wave_heading=wave_heading, backend="compiled"
    )
    return CompiledShip(sim)
