"""The compiled backend of the row engine: K physics steps of N ships in one numba call.

:class:`CompiledBackend` takes the batch force models of a
:class:`~ship_gym.engine.batch.BatchSimulator` and packs their data into records (named tuples
of arrays: :class:`HullRecord`, :class:`WaveRecord`, :class:`RigidRecord`,
:class:`RadiationRecord`, :class:`DiffractionRecord`, :class:`PropulsionRecord`,
:class:`ManoeuvringRecord`, :class:`SurfacesRecord`); :meth:`CompiledBackend.advance` then runs, for
every ship, up to K steps with the commands held, calling the **same** numba kernels the
models use on rows:

* Froude–Krylov + hydrostatics on the instantaneous wetted hull
  (:func:`ship_gym.forces.froude_krylov._fk_core`, float64, or ``_fk_core_f32`` with float32
  wave sums);
* state-space radiation memory or Matusiak's constant coefficients (2a/2b);
* diffraction with the per-ship heading cache refreshed inside the loop
  (:func:`ship_gym.forces.diffraction.transfer_element`);
* viscous roll damping; Holtrop–Mennen resistance
  (:func:`ship_gym.forces.resistance.holtrop_total`); the B-series propeller
  (:func:`ship_gym.engine.batch_control.propeller_force`); Clarke manoeuvring forces
  (:func:`~ship_gym.engine.batch_control.manoeuvring_force`); rudder, fins, T-foil and flaps
  (:func:`~ship_gym.engine.batch_control.surface_group_force`) behind their sampled servos
  and feedback laws (:func:`ship_gym.control.actuators.actuator_target`,
  :func:`~ship_gym.control.actuators.servo_angle`);
* gravity, Coriolis–centripetal terms, kinematics; Holloway's μ-Taylor scheme after two RK4
  start-up steps per ship, or RK4.

Ships are independent in the loop (no reduction across ships reaches a state), so ship i of a
batch of N evolves bit for bit as the same ship alone; with ``parallel=True`` the ships are
spread over numba's threads. Per ship the call returns the task reductions over its K steps:
max |φ|, Σ φ², the number of steps with |φ| above a threshold, and whether it diverged (the
ship then keeps the state of the start of the failed step). The arithmetic is that of the
numpy path of :class:`BatchSimulator` (the reference, ``backend="numpy"``); the wave phasors
use the polynomial :func:`ship_gym.numerics.fastmath.sincos_turns` instead of libm, so the two
agree to rounding, not bit for bit (tested).

Not compiled (the engine falls back to its numpy path): per-ship Python models
(:class:`~ship_gym.engine.batch.PerShipForceModel`, e.g. added resistance in waves), a
resistance curve that is not Holtrop–Mennen, ``Diffraction(above_range="raise")``, the
``"propeller_thrust"`` commands of a rudder without a propeller.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, NamedTuple

import numba as nb
import numpy as np
from numpy.typing import NDArray

from ship_gym.control.actuators import actuator_target, servo_angle
from ship_gym.engine.batch_control import (
    BatchActuatedSurfaces,
    BatchHullManoeuvring,
    BatchPropeller,
    BatchResistance,
)
from ship_gym.engine.rigid_body import healthy_state, rigid_body_terms
from ship_gym.forces.diffraction import (
    CACHE_COLUMNS,
    diffraction_force,
    refresh_diffraction_cache,
)
from ship_gym.forces.froude_krylov import _fk_core, _fk_core_f32
from ship_gym.forces.lifting_surface import surface_group_force
from ship_gym.forces.manoeuvring import manoeuvring_force
from ship_gym.forces.propeller import propeller_force
from ship_gym.forces.radiation import state_space_radiation
from ship_gym.forces.resistance import holtrop_total
from ship_gym.numerics.angles import wrap_angle_scalar
from ship_gym.numerics.fastmath import sincos_turns

if TYPE_CHECKING:
    from ship_gym.engine.batch import BatchSimulator
    from ship_gym.engine.ship import Sea, ShipSetup
    from ship_gym.waves.wave_field import WaveField

__all__ = ["CompiledBackend", "CompiledShip", "StepReductions", "build_compiled_ship"]

_TWO_PI = 2.0 * math.pi
_HOLLOWAY_STARTUP = 2  # RK4 steps before μ-Taylor steps (as BatchSimulator)
_MAX_GROUPS = 4  # rudder, fins, T-foil, flaps


# ============================================================================================
# records
# ============================================================================================
class HullRecord(NamedTuple):
    """The Froude–Krylov kernel's hull layout (:class:`HullPanels`) and ρg [N/m³]."""

    body: NDArray
    tri: NDArray
    tri_last: NDArray
    tri_first: NDArray
    spread: NDArray
    weights: NDArray
    areas: NDArray
    rho_g: float
    single: bool


class WaveRecord(NamedTuple):
    """(N, n_c) component arrays per ship in turns: aⱼ [m], ωⱼ/2π, εⱼ/2π, kⱼcosχⱼ/2π,
    kⱼsinχⱼ/2π [turns/m], kⱼ/ln 2; float32 copies; (N,) ramp times [s]."""

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


class RigidRecord(NamedTuple):
    """Per-ship M_RB about O (N, 6, 6), weight m g [N], G (N, 3), held angles (3,), and the
    inverse of the free block of M_RB + A_lhs (N, 6, 6; zeros for held DOFs)."""

    mass: NDArray
    weight: float
    cog: NDArray
    held_angle: NDArray
    m_inv: NDArray


class RadiationRecord(NamedTuple):
    """State-space A, B, C in CSR form and D (6, 6) (constant coefficients: no states, D = B_c)."""

    speed: float
    a_ptr: NDArray
    a_idx: NDArray
    a_val: NDArray
    b_ptr: NDArray
    b_idx: NDArray
    b_val: NDArray
    c_ptr: NDArray
    c_idx: NDArray
    c_val: NDArray
    d_mat: NDArray
    has_d: bool
    p_inf: NDArray
    p_mem: NDArray
    cutoff: float


class DiffractionRecord(NamedTuple):
    """The diffraction table and the per-ship caches (:class:`BatchDiffraction`'s arrays)."""

    enabled: bool
    table: NDArray
    beta_ext: NDArray
    omega_db: NDArray
    direction: NDArray
    omega: NDArray
    wavenumber: NDArray
    encounter: bool
    kirchhoff: NDArray
    mass_grid: NDArray
    complex_mass: NDArray
    step: float
    tolerance: float
    xd: NDArray
    dxd: NDArray
    ref: NDArray
    work: NDArray
    refresh_count: NDArray


class PropulsionRecord(NamedTuple):
    """Holtrop–Mennen resistance, the propeller (:func:`propeller_force`'s arguments)."""

    has_resistance: bool
    holtrop: NDArray
    has_propeller: bool
    kt_c: NDArray
    kq_c: NDArray
    j0: float
    diameter: float
    rho_d4: float
    one_minus_w: float
    one_minus_t: float
    eta_r: float
    astern: float
    z_p: float
    y_p: float
    roll_sign: float
    shaft_col: int
    viscous_b1: float
    viscous_b2: float


class ManoeuvringRecord(NamedTuple):
    """:func:`manoeuvring_force`'s arguments."""

    enabled: bool
    c_yv: float
    c_yr: float
    c_nv: float
    c_nr: float
    cda: NDArray
    x: NDArray
    crossflow: bool
    roll_lever: float


class SurfacesRecord(NamedTuple):
    """Surface groups behind servos: concatenated surface geometry (ptr (G+1,)), per-group
    inflow and servo data (G,), and the actuators' per-ship states (G, N[, 6])."""

    n_groups: int
    ptr: NDArray
    pos: NDArray
    axis: NDArray
    chord: NDArray
    lead: NDArray
    area: NDArray
    span: NDArray
    rho: NDArray
    lift_slope: NDArray
    stall: NDArray
    transition: NDArray
    cd0: NDArray
    k_induced: NDArray
    cn: NDArray
    inflow: NDArray
    wake: NDArray
    gamma_v: NDArray
    gamma_r: NDArray
    prop_d: NDArray
    prop_x: NDArray
    thrust_mode: NDArray
    c_th: NDArray
    surface_limit: NDArray
    max_angle: NDArray
    max_rate: NDArray
    lag: NDArray
    kind: NDArray
    gains: NDArray
    ref_col: NDArray
    delta: NDArray
    integral: NDArray
    t_step: NDArray
    eta_step: NDArray
    nu_step: NDArray


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


def _csr(matrix: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    m = np.asarray(matrix, dtype=float)
    rows, cols = np.nonzero(m)
    ptr = np.zeros(m.shape[0] + 1, dtype=np.int64)
    np.add.at(ptr, rows + 1, 1)
    return _c(np.cumsum(ptr), np.int64), _c(cols, np.int64), _c(m[rows, cols])


# ============================================================================================
# kernels
# ============================================================================================
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


@nb.njit(cache=True, nogil=True)
def _viscous_roll(v, b1, b2, total):  # pragma: no cover - compiled
    """Viscous roll damping −(B1 p + B2 |p| p) added to the roll moment."""
    p_roll = v[3]
    total[3] += -(b1 * p_roll + b2 * abs(p_roll) * p_roll)


@nb.njit(cache=True, nogil=True)
def _evaluate(
    s, t, q, v, z, hull, waves, rigid, rad, diff, prop, man, surf, cmd, targets, work6,
    local, mod, offset, acc, zdot, qdot,
):  # fmt: skip  # pragma: no cover - compiled
    """ν̇, ż and η̇ of ship s at (t, q, v, z); the actuators' targets are held."""
    if diff.enabled:
        psi = q[5]
        ref = diff.ref[s, 0]
        stale = np.isnan(ref) or abs(wrap_angle_scalar(psi - ref)) > diff.tolerance
        if stale:
            dtab = (
                diff.table, diff.beta_ext, diff.omega_db, diff.direction[s], diff.omega[s],
                diff.wavenumber[s], diff.encounter, diff.kirchhoff, diff.mass_grid,
                diff.complex_mass, diff.step, False, diff.work[s], diff.refresh_count[s : s + 1],
            )  # fmt: skip
            speed = diff.ref[s, 1]  # U_s: the ship's speed at its reset
            if np.isnan(speed):
                speed = rad.speed
            refresh_diffraction_cache(psi, speed, dtab, diff.xd[s], diff.dxd[s], diff.ref[s])
    rot = np.empty((3, 3))
    total = np.empty(6)
    rigid_body_terms(
        q, v, rigid.mass[s], rigid.weight, rigid.cog[s], rigid.held_angle, rot, total, qdot
    )
    crest = _local_phasors(
        t, q[0], q[1], waves.amplitude[s], waves.omega_t[s], waves.phase_t[s],
        waves.ramp_time[s], waves.kxt[s], waves.kyt[s], mod, offset, local,
    )  # fmt: skip
    fe = np.zeros(6)
    if hull.single:
        _fk_core_f32(
            hull.body, hull.tri, hull.tri_last, hull.tri_first, hull.spread, hull.weights,
            hull.areas, rot, q[2], waves.kxt32[s], waves.kyt32[s], waves.k232[s],
            mod.astype(np.float32), offset.astype(np.float32), crest, hull.rho_g, fe,
        )  # fmt: skip
    else:
        _fk_core(
            hull.body, hull.tri, hull.tri_last, hull.tri_first, hull.spread, hull.weights,
            hull.areas, rot, q[2], waves.kxt[s], waves.kyt[s], waves.k2[s], mod, offset, crest,
            hull.rho_g, fe,
        )  # fmt: skip
    for i in range(3):
        total[i] += rot[0, i] * fe[0] + rot[1, i] * fe[1] + rot[2, i] * fe[2]
    for i in range(3):
        total[3 + i] += rot[0, i] * fe[3] + rot[1, i] * fe[4] + rot[2, i] * fe[5]
    state_space_radiation(
        v, z, rad.speed, rad.a_ptr, rad.a_idx, rad.a_val, rad.b_ptr, rad.b_idx, rad.b_val,
        rad.c_ptr, rad.c_idx, rad.c_val, rad.d_mat, rad.has_d, rad.p_inf, rad.p_mem, rad.cutoff,
        total, zdot,
    )  # fmt: skip
    if diff.enabled:
        diffraction_force(q[5], v[0], local, diff.xd[s], diff.dxd[s], diff.ref[s], total)
    p_roll = v[3]
    total[3] += -(prop.viscous_b1 * p_roll + prop.viscous_b2 * abs(p_roll) * p_roll)
    # control forces, in the order of the batch models (resistance, propeller, hull, surfaces)
    if prop.has_resistance and v[0] != 0.0:
        total[0] += -math.copysign(holtrop_total(prop.holtrop, abs(v[0])), v[0])
    thrust = 0.0
    if prop.has_propeller:
        thrust = propeller_force(
            v[0], cmd[s, prop.shaft_col], prop.kt_c, prop.kq_c, prop.j0, prop.diameter,
            prop.rho_d4, prop.one_minus_w, prop.one_minus_t, prop.eta_r, prop.astern, prop.z_p,
            prop.y_p, prop.roll_sign, work6,
        )  # fmt: skip
        for i in range(6):
            total[i] += work6[i]
    if man.enabled:
        manoeuvring_force(
            v, man.c_yv, man.c_yr, man.c_nv, man.c_nr, man.cda, man.x, man.crossflow,
            man.roll_lever, work6,
        )  # fmt: skip
        for i in range(6):
            total[i] += work6[i]
    for g in range(surf.n_groups):
        angle = servo_angle(
            surf.delta[g, s], targets[g], t - surf.t_step[g, s], surf.max_rate[g], surf.lag[g]
        )
        lim = surf.surface_limit[g]
        angle = min(max(angle, -lim), lim)
        mode = surf.thrust_mode[g]
        th = thrust if mode == 1 else surf.c_th[g]
        surface_group_force(
            v, angle, surf.inflow[g], surf.wake[g], surf.gamma_v[g], surf.gamma_r[g],
            surf.prop_d[g], surf.prop_x[g], mode, th, surf.pos, surf.axis, surf.chord,
            surf.lead, surf.area, surf.span, surf.rho, surf.lift_slope, surf.stall,
            surf.transition, surf.cd0, surf.k_induced, surf.cn, surf.ptr[g], surf.ptr[g + 1],
            work6,
        )  # fmt: skip
        for i in range(6):
            total[i] += work6[i]
    m_inv = rigid.m_inv[s]
    for i in range(6):
        a = 0.0
        for j in range(6):
            a += m_inv[i, j] * total[j]
        acc[i] = a


@nb.njit(cache=True, nogil=True)
def _advance_ship(
    s, n_steps, use_rk4, dt, mu, v_max, danger, t_arr, eta, nu, z, k_count, pending, hist,
    hull, waves, rigid, rad, diff, prop, man, surf, cmd, red_max, red_sum, red_danger,
):  # fmt: skip  # pragma: no cover - compiled
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
    local = np.empty(n_c, dtype=np.complex128)
    mod, offset = np.empty(n_c), np.empty(n_c)
    work6 = np.empty(6)
    n_g = surf.n_groups
    targets = np.zeros(_MAX_GROUPS)
    rates = np.zeros(_MAX_GROUPS)
    c = 0.5 / dt
    h2 = 0.5 * dt * dt
    h3 = dt * dt * dt / 6.0
    roll_max = abs(q[3])
    for step in range(n_steps):
        t = t_arr[s]
        for g in range(n_g):  # commands sampled at the step start, held over the step
            targets[g], rates[g] = actuator_target(
                surf.kind[g], surf.gains[g], q, v, surf.integral[g, s],
                cmd[s, surf.ref_col[g]], surf.max_angle[g],
            )  # fmt: skip
        _evaluate(
            s, t, q, v, zz, hull, waves, rigid, rad, diff, prop, man, surf, cmd, targets,
            work6, local, mod, offset, a_c, g_c, d_c,
        )  # fmt: skip
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
                _evaluate(
                    s, tt, qs, vs, zs, hull, waves, rigid, rad, diff, prop, man, surf, cmd,
                    targets, work6, local, mod, offset, ao, go, do,
                )  # fmt: skip
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
        for g in range(n_g):  # the actuators' accepted step (actuator_commit_rows)
            elapsed = t_new - surf.t_step[g, s]
            surf.delta[g, s] = servo_angle(
                surf.delta[g, s], targets[g], elapsed, surf.max_rate[g], surf.lag[g]
            )
            surf.integral[g, s] += elapsed * rates[g]
            surf.t_step[g, s] = t_new
            for i in range(6):
                surf.eta_step[g, s, i] = q_new[i]
                surf.nu_step[g, s, i] = v_new[i]
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
def _advance_serial(
    ships, n_steps, use_rk4, dt, mu, v_max, danger, t_arr, eta, nu, z, k_count, pending, hist,
    hull, waves, rigid, rad, diff, prop, man, surf, cmd, red_max, red_sum, red_danger, done,
):  # fmt: skip  # pragma: no cover - compiled
    for r in range(ships.shape[0]):
        s = ships[r]
        done[s] = _advance_ship(
            s, n_steps, use_rk4, dt, mu, v_max, danger, t_arr, eta, nu, z, k_count, pending,
            hist, hull, waves, rigid, rad, diff, prop, man, surf, cmd, red_max, red_sum,
            red_danger,
        )  # fmt: skip


@nb.njit(cache=True, nogil=True, parallel=True)
def _advance_parallel(
    ships, n_steps, use_rk4, dt, mu, v_max, danger, t_arr, eta, nu, z, k_count, pending, hist,
    hull, waves, rigid, rad, diff, prop, man, surf, cmd, red_max, red_sum, red_danger, done,
):  # fmt: skip  # pragma: no cover - compiled
    for r in nb.prange(ships.shape[0]):
        s = ships[r]
        done[s] = _advance_ship(
            s, n_steps, use_rk4, dt, mu, v_max, danger, t_arr, eta, nu, z, k_count, pending,
            hist, hull, waves, rigid, rad, diff, prop, man, surf, cmd, red_max, red_sum,
            red_danger,
        )  # fmt: skip


# ============================================================================================
# the backend
# ============================================================================================
class CompiledBackend:
    """The compiled loop over a :class:`BatchSimulator`'s ships (module docstring).

    Built by :meth:`BatchSimulator.compiled_backend`; shares the simulator's state arrays, the
    diffraction caches of its :class:`BatchDiffraction` and the actuator states of its
    :class:`BatchActuatedSurfaces` (views), so the numpy path and this one can be mixed.

    Raises
    ------
    NotImplementedError
        From :meth:`check` when a model has no compiled version (the message names it).
    """

    def __init__(self, sim: BatchSimulator) -> None:
        from ship_gym.engine.batch import (
            BatchConstantRadiation,
            BatchDiffraction,
            BatchFroudeKrylov,
            BatchStateSpaceRadiation,
            BatchViscousRoll,
        )

        self.check(sim)
        self.sim = sim
        n = sim.n_ships
        fk = next(f for f in sim.forces if isinstance(f, BatchFroudeKrylov))
        lay = fk.panels._layout
        self.hull = HullRecord(
            _c(lay.body), _c(lay.triangles, np.int64), _c(lay.tri_last, np.int64),
            _c(lay.tri_first, np.int64), _c(lay.spread), _c(lay.weights), _c(lay.areas),
            float(fk.rho * fk.g), fk.method == "fast32",
        )  # fmt: skip
        radiation_kinds = BatchStateSpaceRadiation | BatchConstantRadiation
        rad_model = next((f for f in sim.forces if isinstance(f, radiation_kinds)), None)
        if isinstance(rad_model, BatchStateSpaceRadiation):
            a, b, c = rad_model.matrices
            d = rad_model.feedthrough
            p_inf, p_mem = rad_model.momentum_added_mass, rad_model.momentum_memory
            cutoff = rad_model.speed_cutoff
        else:  # constant coefficients (Matusiak 2a/2b): no forward-speed momentum terms
            a, b, c = np.zeros((0, 0)), np.zeros((0, 6)), np.zeros((6, 0))
            d = np.zeros((6, 6)) if rad_model is None else rad_model.damping
            p_inf, p_mem = np.zeros((2, 6)), np.zeros((2, 0))
            cutoff = 0.0
        self.radiation = RadiationRecord(
            sim.forward_speed, *_csr(a), *_csr(b), *_csr(c), _c(d), bool(np.any(d != 0.0)),
            _c(p_inf), _c(p_mem), float(cutoff),
        )  # fmt: skip
        diff = next((f for f in sim.forces if isinstance(f, BatchDiffraction)), None)
        n_c = sim.n_components
        if diff is not None:
            tab = diff.lookup
            enc, h, tol = diff.encounter, diff.template.heading_step, diff.tolerance
            correction = diff.speed_correction
            xd, dxd, ref = diff.caches
        else:
            tab = (np.zeros((2, 2, 6), np.complex128), np.arange(2.0), np.arange(1.0, 3.0))
            enc, h, tol = False, 1e-4, 0.0
            correction = (np.zeros(4), np.arange(2.0), np.ones((2, 2), np.complex128))
            xd = np.zeros((n, n_c, CACHE_COLUMNS), np.complex128)
            dxd, ref = xd.copy(), np.full((n, 2), np.nan)
        self._diff_static = (diff is not None, *tab)
        self._diff_rest = (enc, *correction, float(h), float(tol), xd, dxd, ref)
        # work arrays and refresh counters per ship: ships refresh concurrently in the
        # parallel loop
        self._diff_work = (
            np.zeros((n, 3, n_c, CACHE_COLUMNS), np.complex128),
            np.zeros(n, np.int64),
        )
        visc = next((f for f in sim.forces if isinstance(f, BatchViscousRoll)), None)
        res = next((f for f in sim.forces if isinstance(f, BatchResistance)), None)
        pro = next((f for f in sim.forces if isinstance(f, BatchPropeller)), None)
        self._command_keys: list[str] = []
        self._command_defaults: list[Any] = []
        shaft_col = 0
        if pro is not None:
            shaft_col = self._column("shaft_speed", pro.default_shaft_speed)
        kt = (pro.params[:2]) if pro is not None else (np.zeros(4), np.zeros(4))
        scal = pro.params[2:] if pro is not None else (1.0,) * 10
        self.propulsion = PropulsionRecord._make((
            res is not None, _c(res.kernel_parameters() if res else np.zeros(1)),
            pro is not None, _c(kt[0]), _c(kt[1]), *(float(x) for x in scal), shaft_col,
            float(visc.b1) if visc else 0.0, float(visc.b2) if visc else 0.0,
        ))  # fmt: skip
        man = next((f for f in sim.forces if isinstance(f, BatchHullManoeuvring)), None)
        if man is not None:
            p = man.params
            self.manoeuvring = ManoeuvringRecord(
                True, float(p[0]), float(p[1]), float(p[2]), float(p[3]), _c(p[4]), _c(p[5]),
                bool(p[6]), float(p[7]),
            )  # fmt: skip
        else:
            self.manoeuvring = ManoeuvringRecord(
                False, 0.0, 0.0, 0.0, 0.0, np.zeros(0), np.zeros(0), False, 0.0
            )
        self.surfaces = self._surfaces(sim, pro is not None)
        # a rudder without a propeller takes its slipstream from these commands on the numpy
        # path (BatchActuatedSurfaces._thrust); the compiled loop knows only the rudder's C_Th
        has_rudder = any(
            isinstance(f, BatchActuatedSurfaces) and f.rudder is not None for f in sim.forces
        )
        self.numpy_only_commands: frozenset[str] = frozenset(
            () if pro is not None or not has_rudder
            else ("propeller_thrust", "propeller_thrust_coefficient")
        )  # fmt: skip
        """Command keys that make a call run on the numpy path (see :meth:`handles_commands`)."""
        self._records_version = -1
        self._records_cache: tuple = ()
        self._entry: dict[Any, Any] = {}

    # ------------------------------------------------------------------ set-up
    @staticmethod
    def check(sim: BatchSimulator) -> None:
        """Raise NotImplementedError naming the first model without a compiled version."""
        from ship_gym.engine.batch import (
            BatchConstantRadiation,
            BatchDiffraction,
            BatchFroudeKrylov,
            BatchStateSpaceRadiation,
            BatchViscousRoll,
        )

        counts: dict[type, int] = {}
        groups = 0
        for f in sim.forces:
            kind = type(f)
            counts[kind] = counts.get(kind, 0) + 1
            if isinstance(f, BatchFroudeKrylov):
                if f.method == "reference":
                    raise NotImplementedError("the reference Froude–Krylov kernel is numpy only")
            elif isinstance(f, BatchDiffraction):
                if f.template.above_range == "raise":
                    raise NotImplementedError("Diffraction(above_range='raise') is numpy only")
            elif isinstance(f, BatchResistance):
                f.kernel_parameters()  # raises for a curve that is not Holtrop–Mennen
            elif isinstance(f, BatchActuatedSurfaces):
                if f.servo is None:
                    raise NotImplementedError(f"the bare surface group {f.name!r} is numpy only")
                groups += 1
            elif not isinstance(
                f, BatchStateSpaceRadiation | BatchConstantRadiation | BatchViscousRoll
                | BatchPropeller | BatchHullManoeuvring,
            ):  # fmt: skip
                raise NotImplementedError(
                    f"force model {f.name!r} ({type(f).__name__}) has no compiled version"
                )
        if counts.get(BatchFroudeKrylov, 0) != 1:
            raise NotImplementedError("the compiled loop needs exactly one Froude–Krylov model")
        for kind, k in counts.items():
            if k > 1 and kind is not BatchActuatedSurfaces:
                raise NotImplementedError(f"more than one {kind.__name__} model")
        if groups > _MAX_GROUPS:
            raise NotImplementedError(f"more than {_MAX_GROUPS} actuated surface groups")
        radiation_states = sum(
            int(f.n_states) for f in sim.forces if isinstance(f, BatchStateSpaceRadiation)
        )
        if radiation_states != sim.n_states:
            raise NotImplementedError("only the radiation memory may have ODE states")

    def _column(self, key: str, default: Any) -> int:
        self._command_keys.append(key)
        self._command_defaults.append(default)
        return len(self._command_keys) - 1

    def _surfaces(self, sim: BatchSimulator, has_propeller: bool) -> SurfacesRecord:
        groups = [f for f in sim.forces if isinstance(f, BatchActuatedSurfaces)]
        n, g_n = sim.n_ships, len(groups)
        geo = [np.concatenate([g.geometry[i] for g in groups]) if groups else None
               for i in range(13)]  # fmt: skip
        shapes = ((0, 3),) * 4 + ((0,),) * 9
        geo = [_c(x) if x is not None else np.zeros(sh) for x, sh in zip(geo, shapes, strict=True)]
        ptr = np.zeros(g_n + 1, dtype=np.int64)
        for i, g in enumerate(groups):
            ptr[i + 1] = ptr[i] + g.geometry[0].shape[0]
        scal: dict[str, list] = {k: [] for k in (
            "inflow", "wake", "gamma_v", "gamma_r", "prop_d", "prop_x", "thrust_mode", "c_th",
            "surface_limit", "max_angle", "max_rate", "lag", "kind", "gains", "ref_col",
        )}  # fmt: skip
        states = {k: np.zeros((max(g_n, 1), n)) for k in ("delta", "integral", "t_step")}
        for k in ("eta_step", "nu_step"):
            states[k] = np.zeros((max(g_n, 1), n, 6))
        for i, g in enumerate(groups):
            assert g.servo is not None  # bare surface groups are refused by _check
            scal["inflow"].append(g.inflow)
            scal["wake"].append(g.wake_fraction)
            scal["gamma_v"].append(g.straightening[0])
            scal["gamma_r"].append(g.straightening[1])
            scal["prop_d"].append(g.propeller_geometry[0])
            scal["prop_x"].append(g.propeller_geometry[1])
            mode, c_th = 0, 0.0
            if g.rudder is not None:
                if has_propeller:
                    mode = 1
                elif g.rudder.thrust_coefficient is not None:
                    mode, c_th = 2, float(g.rudder.thrust_coefficient)
            scal["thrust_mode"].append(mode)
            scal["c_th"].append(c_th)
            scal["surface_limit"].append(g.surface_limit)
            scal["max_angle"].append(g.servo.max_angle)
            scal["max_rate"].append(g.servo.max_rate)
            scal["lag"].append(g.servo.lag)
            scal["kind"].append(g.kind)
            scal["gains"].append(g.gains)
            if g.kind == 1:
                key = g.controller.heading_key
                # without a heading command: the heading at each ship's reset
                scal["ref_col"].append(self._column(key, lambda g=g: g.states.initial_heading))
            elif g.kind == 0:
                scal["ref_col"].append(self._column(g.command_key, 0.0))
            else:
                scal["ref_col"].append(self._column(f"{g.name}_unused", 0.0))
            for k in ("delta", "integral", "t_step", "eta_step", "nu_step"):  # share the rows
                states[k][i] = getattr(g.states, k)
                setattr(g.states, k, states[k][i])
        if not self._command_keys:
            self._column("unused", 0.0)
        ints = {"inflow", "thrust_mode", "kind", "ref_col"}
        arrays = {
            k: _c(v, np.int64) if k in ints else _c(v)
            for k, v in scal.items() if k != "gains"
        }  # fmt: skip
        for k in ints:
            if g_n == 0:
                arrays[k] = np.zeros(1, np.int64)
        for k in arrays:
            if arrays[k].shape[0] == 0:
                arrays[k] = np.zeros(1)
        gains = _c(scal["gains"]) if g_n else np.zeros((1, 4))
        return SurfacesRecord._make((
            g_n, ptr, *geo, arrays["inflow"], arrays["wake"], arrays["gamma_v"],
            arrays["gamma_r"], arrays["prop_d"], arrays["prop_x"], arrays["thrust_mode"],
            arrays["c_th"], arrays["surface_limit"], arrays["max_angle"], arrays["max_rate"],
            arrays["lag"], arrays["kind"], gains, arrays["ref_col"], *states.values(),
        ))  # fmt: skip

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
        out = np.empty((sim.n_ships, len(self._command_keys)))
        for j, (key, default) in enumerate(
            zip(self._command_keys, self._command_defaults, strict=True)
        ):
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
            key = self._command_keys[j]
            raise ValueError(f"commands[{key!r}] must be finite; got {sim.commands.get(key)!r}")
        return out

    def _records(self) -> tuple:
        """(waves, rigid, diffraction) records, rebuilt when a sea or a loading changed."""
        if self._records_version != self.sim.layout_version:
            self._records_cache = self._build_records()
            self._records_version = self.sim.layout_version
        return self._records_cache

    def _build_records(self) -> tuple:
        sim = self.sim
        seas = sim._seas
        kxt = seas.kx / _TWO_PI
        kyt = seas.ky / _TWO_PI
        k2 = seas.wavenumber / math.log(2.0)
        waves = WaveRecord(
            _c(seas.amplitude), _c(seas.omega / _TWO_PI), _c(seas.phase / _TWO_PI),
            _c(seas.ramp_time), _c(kxt), _c(kyt), _c(k2), _c(kxt, np.float32),
            _c(kyt, np.float32), _c(k2, np.float32),
        )  # fmt: skip
        idx = sim._free_idx
        m_inv = np.zeros((sim.n_ships, 6, 6))
        m_inv[:, idx[:, None], idx[None, :]] = np.transpose(sim._ship_m_inv_t, (0, 2, 1))
        rigid = RigidRecord(
            _c(sim._ship_mass_rb), float(sim._weight), _c(sim._ship_cog),
            _c(sim._held_angles, np.bool_), _c(m_inv),
        )  # fmt: skip
        en, tab, beta, omega_db = self._diff_static
        diff = DiffractionRecord(
            en, tab, beta, omega_db, _c(seas.direction), _c(seas.omega), _c(seas.wavenumber),
            *self._diff_rest, *self._diff_work,
        )  # fmt: skip
        return waves, rigid, diff

    # ------------------------------------------------------------------ running
    def _call(self, args: tuple) -> None:
        """Call the compiled loop; after the first call, its compiled entry point directly.

        numba's dispatcher resolves the types of the ≈ 150 record fields at every call (a cost
        per call: docs/benchmarks.md); the entry point of the specialisation it chose skips that.
        Should the argument types ever change (another array layout), the dispatcher is used again.
        """
        run = _advance_parallel if self.sim.parallel else _advance_serial
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
            self._entry[run] = overload.entry_point  # type: ignore[attr-defined]  # numba builds CompileResult's fields from a list

    def advance(
        self, ships: NDArray, n_steps: int, danger: float, cmd: NDArray | None = None
    ) -> tuple[StepReductions, NDArray]:
        """Up to ``n_steps`` steps of each of ``ships`` with the commands held.

        Returns the reductions over the steps (arrays over all N; zeros for ships not run) and
        the (N,) number of steps each ship completed (fewer than ``n_steps``: it diverged).
        """
        sim = self.sim
        n = sim.n_ships
        waves, rigid, diff = self._records()
        if cmd is None:
            cmd = self.command_matrix()
        red_max = np.zeros(n)
        red_sum = np.zeros(n)
        red_danger = np.zeros(n, dtype=np.int64)
        done = np.zeros(n, dtype=np.int64)
        hist = (
            sim._v1, sim._v2, sim._a1, sim._a2, sim._qd1, sim._qd2, sim._qdd1, sim._qdd2,
            sim._zd1, sim._zd2,
        )  # fmt: skip
        if ships.dtype != np.int64 or not ships.flags.c_contiguous:
            ships = _c(ships, np.int64)
        args = (
            ships, int(n_steps), sim.integrator_name == "rk4", float(sim.dt),
            sim.mu, float(sim.max_abs_velocity), float(danger), sim.t, sim.eta, sim.nu, sim.z,
            sim._k, sim._pending, hist, self.hull, waves, rigid, self.radiation, diff,
            self.propulsion, self.manoeuvring, self.surfaces, cmd, red_max, red_sum, red_danger,
            done,
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
        _viscous_roll(v, b1, b2, total)
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
        return int(self.backend._diff_work[1].sum())

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
        waves, rigid, diff = b._records()
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
        h = b.hull
        hull = (h.body, h.tri, h.tri_last, h.tri_first, h.spread, h.weights, h.areas, h.rho_g)
        r = b.radiation
        rad = tuple(r)
        diff_ref = diff.ref[0] if diff.enabled else np.array([q[5], v[0]])
        p = b.propulsion
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
            "diffraction": lambda n: _loop_diffraction(
                n, q[5], v[0], local, diff.xd[0], diff.dxd[0], diff_ref
            ),
            "rigid_body_viscous_roll": lambda n: _loop_rigid(
                n, q, v, mass, weight, cog, held, p.viscous_b1, p.viscous_b2
            ),
        }  # fmt: skip
        out: dict[str, float] = {}
        for name, job in jobs.items():
            if name == "diffraction" and not diff.enabled:
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
