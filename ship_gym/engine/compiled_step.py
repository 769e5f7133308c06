"""A fully compiled single-ship stepper for the reference force set (DESIGN.md §5).

:class:`CompiledShip` advances one ship by K steps in **one** numba call: no Python between the
force models, no array allocation per evaluation beyond the Froude–Krylov kernel's work
buffers. The force set is the fast path of :func:`ship_gym.engine.ship.build_simulator`
(the "S175-full" reference case):

* nonlinear Froude–Krylov + hydrostatics on the instantaneous wetted hull (the fast kernel of
  :mod:`ship_gym.forces.froude_krylov`, float64 or with float32 wave sums);
* Cummins radiation memory by the fitted state-space system (ż = A z + B ν_p, force
  −(C z + D ν_p), A(∞) on the left; :class:`ship_gym.forces.radiation.RadiationMemory`), or
  Matusiak's constant coefficients (case 2a/2b: −B_c ν_p, A_c on the left;
  :class:`ship_gym.forces.radiation.ConstantCoefficientRadiation`), for the cost comparison;
* linear diffraction F_D = Re Σⱼ conj(c'ⱼ)(X_D,ⱼ + Δψ ∂X_D,ⱼ/∂ψ) with the transfer functions
  cached at a reference heading (:class:`ship_gym.forces.diffraction.Diffraction`); when ψ
  leaves the tolerance band the cache is refreshed inside the compiled loop by the model's
  bilinear (ω', β) look-up, the same arithmetic as :meth:`Diffraction.heading_expansion`
  (only ``above_range="raise"`` with a component above the table returns to Python, to
  raise);
* viscous roll damping −(B1 p + B2 |p| p) (:class:`ship_gym.forces.viscous.ViscousRollDamping`);
* gravity, Coriolis–centripetal terms and kinematics J(η)ν;
* Holloway's μ-Taylor scheme (Holloway 2007, eq. 4, 6–9; one evaluation per step) after two
  RK4 start-up steps, or RK4 throughout.

The equations and the arithmetic are those of :class:`ship_gym.engine.batch.BatchSimulator`
(Kring–Huang–Sclavounos form, (M_RB + A(∞)) ν̇ = Σ F + F_g − C_RB(ν) ν), which agrees with
:class:`ship_gym.engine.simulator.Simulator`; ``tests/physics/test_compiled_step.py`` holds
the float64 stepper to both at rounding level over hundreds of steps, and the float32 one to
the float64 one with a stated tolerance. The wave phasors use the polynomial
:func:`ship_gym.forces.fastmath.sincos` (a few ulp from libm) instead of libm calls.

Not supported (use :class:`Simulator`/:class:`BatchSimulator`): other force models (control
surfaces, propulsion, added resistance), the convolution radiation path, Holloway's lumped
mode, ABM, per-step commands.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba as nb
import numpy as np
from numpy.typing import NDArray

from ship_gym.conventions import SURGE
from ship_gym.engine.ship import Sea, ShipSetup, build_force_models
from ship_gym.engine.simulator import SimulationDiverged, left_hand_side
from ship_gym.forces.diffraction import Diffraction, transfer_element
from ship_gym.forces.fastmath import sincos_turns
from ship_gym.forces.froude_krylov import FroudeKrylovHydrostatics, _fk_core, _fk_core_f32
from ship_gym.forces.radiation import ConstantCoefficientRadiation, RadiationMemory
from ship_gym.forces.viscous import ViscousRollDamping
from ship_gym.hull import equilibrium, load_hull
from ship_gym.hull.hull import Hull
from ship_gym.hydro import load_database
from ship_gym.typing import Precision, RowIntegratorName
from ship_gym.waves.wave_field import WaveField

__all__ = ["CompiledShip", "Precision", "build_compiled_ship"]


_TWO_PI = 2.0 * math.pi
_HOLLOWAY_STARTUP = 2  # RK4 steps before μ-Taylor steps (as HollowayIntegrator/BatchSimulator)
# status codes of _advance
_OK = 0
_STALE = 1  # the diffraction cache must be refreshed at heading status_psi[0]
_DIVERGED = 2


def _own(array: NDArray, dtype: type = np.float64) -> NDArray:
    """A fresh, writable, C-contiguous copy (numba compiles read-only arrays separately)."""
    return np.array(array, dtype=dtype, order="C", copy=True)


def _csr(matrix: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """(indptr, indices, values) of the non-zeros of a dense matrix, row by row."""
    m = np.asarray(matrix, dtype=float)
    rows, cols = np.nonzero(m)
    ptr = np.zeros(m.shape[0] + 1, dtype=np.int64)
    np.add.at(ptr, rows + 1, 1)
    return _own(np.cumsum(ptr), np.int64), _own(cols, np.int64), _own(m[rows, cols])


# ============================================================================================
# compiled pieces
# ============================================================================================
def _diffraction_tables(model: Diffraction | None, wave_field: WaveField | None, n_c: int):
    """The data of :func:`_refresh_diffraction`: the model's periodically extended table, its
    headings and frequencies, the components' χ, ω, k, the frequency rule, the difference step
    h, the ``above_range`` rule, work arrays and the refresh counter (dummies without a
    model, typed alike)."""
    count = np.zeros(1, dtype=np.int64)
    work = np.zeros((3, n_c, 6), dtype=np.complex128)
    if model is None or wave_field is None:
        return (
            np.zeros((2, 2, 6), dtype=np.complex128), np.arange(2.0), np.arange(1.0, 3.0),
            np.zeros(n_c), np.zeros(n_c), np.zeros(n_c), False, 1e-4, False, work, count,
        )  # fmt: skip
    w = wave_field
    table, beta = model.interpolation_table()
    return (
        _own(table, np.complex128), _own(beta), _own(model.omega), _own(w.direction),
        _own(w.omega), _own(w.wavenumber), model.frequency == "encounter", model.heading_step,
        model.above_range == "raise", work, count,
    )  # fmt: skip


@nb.njit(cache=True, nogil=True)
def _rigid_terms(q, v, mass, weight, cog, held_angle, rot, total, qdot):  # pragma: no cover
    """R(φ, θ, ψ), gravity − Coriolis (body axes, about O) and η̇ = J(η) ν of one ship.

    The arithmetic of ``ship_gym.engine.batch._ship_terms`` (one row); η̇ of a held angle
    is 0, and η̇'s angular rows are NaN where |cos θ| < 1e-9 (reported as a divergence).
    """
    cphi, sphi = math.cos(q[3]), math.sin(q[3])
    cth, sth = math.cos(q[4]), math.sin(q[4])
    cpsi, spsi = math.cos(q[5]), math.sin(q[5])
    rot[0, 0] = cpsi * cth
    rot[0, 1] = -spsi * cphi + cpsi * sth * sphi
    rot[0, 2] = spsi * sphi + cpsi * cphi * sth
    rot[1, 0] = spsi * cth
    rot[1, 1] = cpsi * cphi + sphi * sth * spsi
    rot[1, 2] = -cpsi * sphi + sth * spsi * cphi
    rot[2, 0] = -sth
    rot[2, 1] = cth * sphi
    rot[2, 2] = cth * cphi
    fx, fy, fz = rot[2, 0] * weight, rot[2, 1] * weight, rot[2, 2] * weight
    h0 = h1 = h2 = h3 = h4 = h5 = 0.0
    for j in range(6):
        h0 += mass[0, j] * v[j]
        h1 += mass[1, j] * v[j]
        h2 += mass[2, j] * v[j]
        h3 += mass[3, j] * v[j]
        h4 += mass[4, j] * v[j]
        h5 += mass[5, j] * v[j]
    u, vv, w, p, qq, rr = v[0], v[1], v[2], v[3], v[4], v[5]
    total[0] = fx - (qq * h2 - rr * h1)
    total[1] = fy - (rr * h0 - p * h2)
    total[2] = fz - (p * h1 - qq * h0)
    total[3] = (cog[1] * fz - cog[2] * fy) - ((vv * h2 - w * h1) + (qq * h5 - rr * h4))
    total[4] = (cog[2] * fx - cog[0] * fz) - ((w * h0 - u * h2) + (rr * h3 - p * h5))
    total[5] = (cog[0] * fy - cog[1] * fx) - ((u * h1 - vv * h0) + (p * h4 - qq * h3))
    for i in range(3):
        qdot[i] = rot[i, 0] * u + rot[i, 1] * vv + rot[i, 2] * w
    if abs(cth) < 1e-9:
        qdot[3] = np.nan
        qdot[4] = np.nan
        qdot[5] = np.nan
    else:
        tth = math.tan(q[4])
        qdot[3] = p + sphi * tth * qq + cphi * tth * rr
        qdot[4] = cphi * qq - sphi * rr
        qdot[5] = sphi / cth * qq + cphi / cth * rr
    for i in range(3):
        if held_angle[i]:
            qdot[3 + i] = 0.0


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
def _radiation(
    v, z, speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat, has_d,
    total, zdot,
):  # fmt: skip  # pragma: no cover - compiled
    """Radiation memory: ż = A z + B ν_p into zdot, −(C z + D ν_p) added to total; A, B, C in
    CSR form (A block-diagonal, B one non-zero per state: O(n_states))."""
    vp = np.empty(6)
    for i in range(6):
        vp[i] = v[i]
    vp[SURGE] -= speed
    for i in range(a_ptr.shape[0] - 1):
        s = 0.0
        for p in range(a_ptr[i], a_ptr[i + 1]):
            s += a_val[p] * z[a_idx[p]]
        for p in range(b_ptr[i], b_ptr[i + 1]):
            s += b_val[p] * vp[b_idx[p]]
        zdot[i] = s
    for o in range(6):
        s = 0.0
        for p in range(c_ptr[o], c_ptr[o + 1]):
            s += c_val[p] * z[c_idx[p]]
        f = -s
        if has_d:
            for j in range(6):
                f -= vp[j] * d_mat[o, j]
        total[o] += f


@nb.njit(cache=True, nogil=True)
def _transfer_at(heading, speed, diff, out):  # pragma: no cover - compiled
    """out[j] = X_D(ω'ⱼ, βⱼ) at ship heading ψ = ``heading`` [rad] for every component; returns
    the number of components above the table's ω_max.

    As :meth:`Diffraction.heading_expansion`: β = (χⱼ − ψ) mod 2π and, at encounter
    frequency, ω' = ωⱼ − kⱼ U cos β, then the model's own element look-up
    (:func:`ship_gym.forces.diffraction.transfer_element`).
    """
    table, beta_ext, omega_db, direction, omega_c, wavenumber, encounter = diff[:7]
    n_above = 0
    for j in range(direction.shape[0]):
        b = np.mod(direction[j] - heading, _TWO_PI)
        w = omega_c[j] - wavenumber[j] * speed * math.cos(b) if encounter else omega_c[j]
        n_above += transfer_element(w, b, table, beta_ext, omega_db, out, j)
    return n_above


@nb.njit(cache=True, nogil=True)
def _refresh_diffraction(psi, speed, diff, xd, dxd, diff_ref):  # pragma: no cover - compiled
    """Cache X_D and ∂X_D/∂ψ (central difference over ±h) at heading ψ, as
    :meth:`Diffraction.heading_expansion`; returns False, leaving the cache as it was, when the
    model must raise (``above_range="raise"`` and a component above ω_max)."""
    h, must_raise, work, count = diff[7:]
    above = _transfer_at(psi, speed, diff, work[0])
    if above > 0 and must_raise:
        return False
    _transfer_at(psi + h, speed, diff, work[1])
    _transfer_at(psi - h, speed, diff, work[2])
    for j in range(xd.shape[0]):
        for o in range(6):
            xd[j, o] = work[0, j, o]
            dxd[j, o] = (work[1, j, o] - work[2, j, o]) / (2.0 * h)
    diff_ref[0] = psi
    diff_ref[1] = speed
    count[0] += 1
    return True


@nb.njit(cache=True, nogil=True)
def _diffraction(psi, local, xd, dxd, diff_ref, total):  # pragma: no cover - compiled
    """F_D = Re Σⱼ conj(c'ⱼ)(X_D,ⱼ + Δψ ∂X_D,ⱼ/∂ψ), X_D cached at heading diff_ref[0]."""
    dpsi = (psi - diff_ref[0] + math.pi) % _TWO_PI - math.pi
    for o in range(6):
        s = 0.0
        for j in range(local.shape[0]):
            c = local[j]
            x = xd[j, o] + dpsi * dxd[j, o]
            s += c.real * x.real + c.imag * x.imag
        total[o] += s


@nb.njit(cache=True, nogil=True)
def _viscous_roll(v, b1, b2, total):  # pragma: no cover - compiled
    """Viscous roll damping −(B1 p + B2 |p| p) added to the roll moment."""
    p_roll = v[3]
    total[3] += -(b1 * p_roll + b2 * abs(p_roll) * p_roll)


@nb.njit(cache=True, nogil=True)
def _evaluate(
    t, q, v, z,
    # hull and Froude–Krylov
    body, tri, tri_last, tri_first, spread, weights, areas, rho_g, single,
    # waves
    amplitude, omega_t, phase_t, ramp_time, kxt, kyt, k2, kxt32, kyt32, k232,
    # rigid body
    mass, weight, cog, held_angle, m_inv,
    # radiation
    speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat, has_d,
    # diffraction
    has_diff, xd, dxd, diff_ref, tol, diff,
    # viscous roll
    b1, b2,
    # outputs
    acc, zdot, qdot, status_psi,
):  # fmt: skip  # pragma: no cover - compiled
    """ν̇, ż and η̇ at (t, q, v, z). A stale diffraction cache is refreshed first
    (:func:`_refresh_diffraction`); returns False (and the heading in status_psi[0]), before
    anything else is computed, when that refresh must be left to Python."""
    if has_diff:
        psi = q[5]
        ref = diff_ref[0]
        stale = np.isnan(ref) or diff_ref[1] != speed
        stale = stale or abs((psi - ref + math.pi) % _TWO_PI - math.pi) > tol
        if stale and not _refresh_diffraction(psi, speed, diff, xd, dxd, diff_ref):
            status_psi[0] = psi
            return False
    rot = np.empty((3, 3))
    total = np.empty(6)
    _rigid_terms(q, v, mass, weight, cog, held_angle, rot, total, qdot)
    n_c = amplitude.shape[0]
    local = np.empty(n_c, dtype=np.complex128)
    mod = np.empty(n_c)
    offset = np.empty(n_c)
    crest = _local_phasors(
        t, q[0], q[1], amplitude, omega_t, phase_t, ramp_time, kxt, kyt, mod, offset, local
    )
    # Froude–Krylov + hydrostatics (earth axes) → body axes
    fe = np.zeros(6)
    if single:
        _fk_core_f32(
            body, tri, tri_last, tri_first, spread, weights, areas, rot, q[2], kxt32, kyt32,
            k232, mod.astype(np.float32), offset.astype(np.float32), crest, rho_g, fe,
        )  # fmt: skip
    else:
        _fk_core(
            body, tri, tri_last, tri_first, spread, weights, areas, rot, q[2], kxt, kyt, k2,
            mod, offset, crest, rho_g, fe,
        )  # fmt: skip
    for i in range(3):
        total[i] += rot[0, i] * fe[0] + rot[1, i] * fe[1] + rot[2, i] * fe[2]
    for i in range(3):
        total[3 + i] += rot[0, i] * fe[3] + rot[1, i] * fe[4] + rot[2, i] * fe[5]
    _radiation(
        v, z, speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat, has_d,
        total, zdot,
    )  # fmt: skip
    if has_diff:
        _diffraction(q[5], local, xd, dxd, diff_ref, total)
    _viscous_roll(v, b1, b2, total)
    for i in range(6):
        s = 0.0
        for j in range(6):
            s += m_inv[i, j] * total[j]
        acc[i] = s
    return True


@nb.njit(cache=True, nogil=True)
def _advance(
    n_steps, use_rk4,
    # state (updated in place)
    t_arr, q, v, z, k_count, pending,
    v1, v2, a1, a2, qd1, qd2, qdd1, qdd2, zd1, zd2,
    # RK4 stage values and the number of evaluations of the current step already done
    a_c, zd, qd, a2s, g2, d2, a3s, g3, d3, a4s, g4, d4, resume,
    mu, dt, v_max,
    # model data (see _evaluate)
    body, tri, tri_last, tri_first, spread, weights, areas, rho_g, single,
    amplitude, omega_t, phase_t, ramp_time, kxt, kyt, k2, kxt32, kyt32, k232,
    mass, weight, cog, held_angle, m_inv,
    speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat, has_d,
    has_diff, xd, dxd, diff_ref, tol, diff,
    b1, b2,
    status_psi,
):  # fmt: skip  # pragma: no cover - compiled
    """Take up to n_steps steps; returns (steps taken, status code).

    Each step is committed only at its end, so a step interrupted by a stale diffraction cache
    (status _STALE) or a divergence (status _DIVERGED, state left at the start of that step)
    leaves the state of the last completed step. After _STALE, ``resume[0]`` holds the number
    of evaluations of the interrupted step already done (their values are kept in the stage
    arrays): the next call, after the refresh, continues with the stage that found the cache
    stale, so that every stage sees the cache the single-ship model would have used.
    """
    nz = z.shape[0]
    qs, vs, zs = np.empty(6), np.empty(6), np.empty(nz)
    q_new, v_new, z_new = np.empty(6), np.empty(6), np.empty(nz)
    c = 0.5 / dt
    h2 = 0.5 * dt * dt
    h3 = dt * dt * dt / 6.0
    for step in range(n_steps):
        t = t_arr[0]
        done = resume[0]
        resume[0] = 0
        ok = done > 0 or _evaluate(
            t, q, v, z, body, tri, tri_last, tri_first, spread, weights, areas, rho_g, single,
            amplitude, omega_t, phase_t, ramp_time, kxt, kyt, k2, kxt32, kyt32, k232, mass,
            weight, cog,
            held_angle, m_inv, speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx,
            c_val, d_mat, has_d, has_diff, xd, dxd, diff_ref, tol, diff, b1, b2, a_c, zd, qd,
            status_psi,
        )  # fmt: skip
        if not ok:
            return step, _STALE
        if use_rk4 or k_count[0] < _HOLLOWAY_STARTUP:
            # classical RK4 (the arithmetic of BatchSimulator._rk4), stage 1 given
            hh = 0.5 * dt
            ok = True
            for stage in range(max(done, 1) - 1, 3):
                if stage == 0:
                    ca, ga, da, tt = a_c, zd, qd, t + hh
                    cs = hh
                    ao, go, do = a2s, g2, d2
                elif stage == 1:
                    ca, ga, da, tt = a2s, g2, d2, t + hh
                    cs = hh
                    ao, go, do = a3s, g3, d3
                else:
                    ca, ga, da, tt = a3s, g3, d3, t + dt
                    cs = dt
                    ao, go, do = a4s, g4, d4
                for i in range(6):
                    qs[i] = q[i] + cs * da[i]
                    vs[i] = v[i] + cs * ca[i]
                for i in range(nz):
                    zs[i] = z[i] + cs * ga[i]
                ok = _evaluate(
                    tt, qs, vs, zs, body, tri, tri_last, tri_first, spread, weights, areas,
                    rho_g, single, amplitude, omega_t, phase_t, ramp_time, kxt, kyt, k2, kxt32,
                    kyt32, k232, mass, weight, cog, held_angle, m_inv, speed, a_ptr, a_idx,
                    a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat, has_d, has_diff, xd,
                    dxd, diff_ref, tol, diff, b1, b2, ao, go, do, status_psi,
                )  # fmt: skip
                if not ok:
                    resume[0] = stage + 1
                    break
            if not ok:
                return step, _STALE
            c6 = dt / 6.0
            for i in range(6):
                q_new[i] = q[i] + c6 * (qd[i] + 2.0 * (d2[i] + d3[i]) + d4[i])
                v_new[i] = v[i] + c6 * (a_c[i] + 2.0 * (a2s[i] + a3s[i]) + a4s[i])
            for i in range(nz):
                z_new[i] = z[i] + c6 * (zd[i] + 2.0 * (g2[i] + g3[i]) + g4[i])
            if not _healthy(q_new, v_new, z_new, v_max):
                return step, _DIVERGED
            if not use_rk4:  # start-up history (BatchSimulator._push_startup)
                for i in range(6):
                    v2[i] = v1[i]
                    v1[i] = v[i]
                    a2[i] = a1[i]
                    a1[i] = a_c[i]
                    qd2[i] = qd1[i]
                    qd1[i] = qd[i]
                for i in range(nz):
                    zd2[i] = zd1[i]
                    zd1[i] = zd[i]
                pending[0] = True
        else:
            # Holloway's μ-Taylor step (eq. 4, 6–9; BatchSimulator's _holloway_rows), computed
            # into q_new, v_new, z_new first: the history is shifted only for a healthy step
            for i in range(6):
                ae = (3.0 * v[i] - 4.0 * v1[i] + v2[i]) * c  # eq. 6
                a = mu[i] * a_c[i] + (1.0 - mu[i]) * ae  # eq. 4
                jerk = (3.0 * a - 4.0 * a1[i] + a2[i]) * c  # eq. 7
                v_new[i] = v[i] + dt * a + h2 * jerk  # eq. 8
                a2s[i] = a  # (blended acceleration, kept for the history)
            if pending[0]:
                for i in range(6):
                    d2[i] = (-3.0 * qd2[i] + 4.0 * qd1[i] - qd[i]) * c  # q̈ at t − 2Δt
                    d3[i] = (qd[i] - qd2[i]) * c  # q̈ at t − Δt
            else:
                for i in range(6):
                    d2[i] = qdd2[i]
                    d3[i] = qdd1[i]
            for i in range(6):
                qdd = (3.0 * qd[i] - 4.0 * qd1[i] + qd2[i]) * c
                qddd = (3.0 * qdd - 4.0 * d3[i] + d2[i]) * c
                q_new[i] = q[i] + dt * qd[i] + h2 * qdd + h3 * qddd  # eq. 9
                d4[i] = qdd
            for i in range(nz):
                zdd = (3.0 * zd[i] - 4.0 * zd1[i] + zd2[i]) * c
                z_new[i] = z[i] + dt * zd[i] + h2 * zdd
            if not _healthy(q_new, v_new, z_new, v_max):
                return step, _DIVERGED
            for i in range(6):
                a2[i] = a1[i]
                a1[i] = a2s[i]
                v2[i] = v1[i]
                v1[i] = v[i]
                qd2[i] = qd1[i]
                qd1[i] = qd[i]
                qdd2[i] = d3[i]
                qdd1[i] = d4[i]
            for i in range(nz):
                zd2[i] = zd1[i]
                zd1[i] = zd[i]
            pending[0] = False
        for i in range(6):
            q[i] = q_new[i]
            v[i] = v_new[i]
        for i in range(nz):
            z[i] = z_new[i]
        t_arr[0] = t + dt
        k_count[0] += 1
    return n_steps, _OK


@nb.njit(cache=True, nogil=True)
def _healthy(q, v, z, v_max):  # pragma: no cover - compiled
    """q, z finite and max |v| ≤ v_max (False for NaN): the simulators' divergence test."""
    good = True
    for i in range(q.shape[0]):
        good &= np.isfinite(q[i])
    for i in range(v.shape[0]):
        good &= abs(v[i]) <= v_max
    for i in range(z.shape[0]):
        good &= np.isfinite(z[i])
    return good


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
    n, v, z, speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat, has_d
):  # fmt: skip  # pragma: no cover - compiled
    total = np.zeros(6)
    zdot = np.empty(z.shape[0])
    for _ in range(n):
        _radiation(
            v, z, speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat,
            has_d, total, zdot,
        )  # fmt: skip
    return total


@nb.njit(cache=True)
def _loop_diffraction(n, psi, local, xd, dxd, diff_ref):  # pragma: no cover - compiled
    total = np.zeros(6)
    for _ in range(n):
        _diffraction(psi, local, xd, dxd, diff_ref, total)
    return total


@nb.njit(cache=True)
def _loop_rigid(n, q, v, mass, weight, cog, held_angle, b1, b2):  # pragma: no cover - compiled
    rot = np.empty((3, 3))
    total = np.empty(6)
    qdot = np.empty(6)
    for _ in range(n):
        _rigid_terms(q, v, mass, weight, cog, held_angle, rot, total, qdot)
        _viscous_roll(v, b1, b2, total)
    return total


# ============================================================================================
# Python front end
# ============================================================================================
@dataclass(frozen=True, eq=False)
class _Models:
    """The reference force set picked out of a list of single-ship force models."""

    froude_krylov: FroudeKrylovHydrostatics
    radiation: RadiationMemory | ConstantCoefficientRadiation
    diffraction: Diffraction | None
    viscous: ViscousRollDamping | None

    @classmethod
    def pick(cls, models: list) -> _Models:
        fk = rad = diff = visc = None
        for m in models:
            if m is None:
                continue
            if isinstance(m, FroudeKrylovHydrostatics) and fk is None:
                fk = m
            elif isinstance(m, RadiationMemory | ConstantCoefficientRadiation) and rad is None:
                rad = m
            elif isinstance(m, Diffraction) and diff is None:
                diff = m
            elif isinstance(m, ViscousRollDamping) and visc is None:
                visc = m
            else:
                raise NotImplementedError(
                    f"CompiledShip runs Froude–Krylov, state-space (or constant-coefficient) "
                    f"radiation, diffraction and viscous roll only; got {type(m).__name__} "
                    f"({m.name!r}): use Simulator or BatchSimulator"
                )
        if fk is None or rad is None:
            raise NotImplementedError(
                "CompiledShip needs a Froude–Krylov model and a RadiationMemory model"
            )
        if fk.method == "reference":
            raise ValueError("CompiledShip runs the fast Froude–Krylov kernel (fk_method 'fast')")
        if isinstance(rad, RadiationMemory) and (
            rad.method != "state_space" or rad.state_space is None or rad.lumped
        ):
            raise NotImplementedError(
                "CompiledShip needs RadiationMemory(method='state_space', lumped=False); the "
                "convolution (reference path) runs in Simulator"
            )
        return cls(fk, rad, diff, visc)


class CompiledShip:
    """One ship of the reference force set, stepped K steps per call in compiled code.

    Parameters
    ----------
    hull : Hull
        Hull and loading condition.
    models : sequence of ForceModel
        Exactly the fast-path reference set: :class:`FroudeKrylovHydrostatics` (fast kernel),
        :class:`RadiationMemory` (``method="state_space"``, not lumped), optionally
        :class:`Diffraction` and :class:`ViscousRollDamping` (as built by
        :func:`ship_gym.engine.ship.build_force_models`).
    wave_field : WaveField or None
        The incident sea (None: calm water).
    forward_speed : float
        Steady forward speed U [m/s].
    dt : float
        Time step [s].
    integrator : {"holloway", "rk4"}
        Holloway's μ-Taylor scheme (1 evaluation per step after 2 RK4 start-up steps) or RK4.
    precision : {"float64", "float32"}
        Wave sums of the Froude–Krylov kernel in float64 (``method="fast"``) or float32
        (``"fast32"``: about twice as fast; see :mod:`ship_gym.forces.froude_krylov`).
    free_dofs : sequence of bool, optional
        (6,) integrated DOFs; held DOFs keep their initial velocity (held angles their value).
    mu : array_like, optional
        Holloway blending per DOF (default 1: the acceleration is exact).
    initial_eta : array_like, optional
        (6,) default η of :meth:`reset` (default zeros).
    max_abs_velocity : float
        |ν| above which the state is declared diverged [m/s, rad/s].

    Attributes
    ----------
    t : float
        Time [s].
    eta, nu : numpy.ndarray
        (6,) state (views of the compiled loop's arrays: copy before keeping them).
    z : numpy.ndarray
        (n_states,) radiation memory states.
    n_steps : int
        Steps since the last reset.
    n_refreshes : int
        Diffraction cache refreshes (heading changes beyond the model's tolerance) since
        construction.
    """

    def __init__(
        self,
        hull: Hull,
        models: list,
        wave_field: WaveField | None,
        *,
        forward_speed: float = 0.0,
        dt: float = 0.05,
        integrator: RowIntegratorName = "holloway",
        precision: Precision = "float64",
        free_dofs: tuple[bool, ...] | None = None,
        mu: NDArray | None = None,
        initial_eta: NDArray | None = None,
        max_abs_velocity: float = 100.0,
    ) -> None:
        if not (np.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be a positive time step [s], got {dt!r}")
        if integrator not in ("holloway", "rk4"):
            raise ValueError(f"integrator must be 'holloway' or 'rk4', got {integrator!r}")
        if precision not in ("float64", "float32"):
            raise ValueError(f"precision must be 'float64' or 'float32', got {precision!r}")
        m = _Models.pick(list(models))
        self.hull = hull
        self.models = m
        self.dt = float(dt)
        self.integrator_name = integrator
        self.precision = precision
        self.forward_speed = float(forward_speed)
        self.max_abs_velocity = float(max_abs_velocity)
        self.wave_field = wave_field
        # waves (calm water: one zero component, as the Froude–Krylov model does), in turns
        if wave_field is None or wave_field.n_components == 0:
            amp, omega, phase, ramp = np.zeros(1), np.zeros(1), np.zeros(1), 0.0
            k, chi = np.zeros(1), np.zeros(1)
        else:
            w = wave_field
            amp, omega, phase, ramp = w.amplitude, w.omega, w.phase, float(w.ramp_time)
            k, chi = w.wavenumber, w.direction
        kxt = np.asarray(k, float) * np.cos(chi) / _TWO_PI
        kyt = np.asarray(k, float) * np.sin(chi) / _TWO_PI
        k2 = np.asarray(k, float) / math.log(2.0)
        self._waves = (
            *(_own(a) for a in (amp, np.asarray(omega) / _TWO_PI, np.asarray(phase) / _TWO_PI)),
            ramp,
            *(_own(a) for a in (kxt, kyt, k2)),
            *(_own(a, np.float32) for a in (kxt, kyt, k2)),
        )
        n_c = self._waves[0].shape[0]
        # rigid body and left-hand side
        picked = [x for x in (m.froude_krylov, m.radiation, m.diffraction, m.viscous) if x]
        free, mass_rb, a_lhs = left_hand_side(hull, picked, free_dofs)
        self.free = free
        self.mass_rb = mass_rb
        idx = np.flatnonzero(free)
        m_inv = np.zeros((6, 6))
        m_inv[np.ix_(idx, idx)] = np.linalg.inv((mass_rb + a_lhs)[np.ix_(idx, idx)])
        self._rigid = (
            _own(mass_rb),
            float(hull.mass.mass * hull.g),
            _own(hull.mass.cog),
            _own(~free[3:], np.bool_),
            _own(m_inv),
        )
        if isinstance(m.radiation, RadiationMemory):
            ss = m.radiation.state_space
            a, b, c, d = (np.asarray(x, dtype=float) for x in (ss.A, ss.B, ss.C, ss.D))
        else:  # Matusiak's constant coefficients: no states, force −B_c ν_p (D = B_c)
            a, b, c = np.zeros((0, 0)), np.zeros((0, 6)), np.zeros((6, 0))
            d = np.asarray(m.radiation.damping, dtype=float)
        self._radiation = (
            self.forward_speed, *_csr(a), *_csr(b), *_csr(c), _own(d), bool(np.any(d != 0.0)),
        )  # fmt: skip
        self.n_states = int(a.shape[0])
        lay = m.froude_krylov.panels._layout
        self._hull = (
            *(_own(a) for a in (lay.body,)),
            *(_own(a, np.int64) for a in (lay.triangles, lay.tri_last, lay.tri_first)),
            *(_own(a) for a in (lay.spread, lay.weights, lay.areas)),
            float(hull.rho * hull.g),
            precision == "float32",
        )  # fmt: skip
        has_diff = m.diffraction is not None and wave_field is not None
        self._has_diff = has_diff
        self._xd = np.zeros((n_c, 6), dtype=np.complex128)
        self._dxd = np.zeros((n_c, 6), dtype=np.complex128)
        self._diff_ref = np.array([np.nan, np.nan])  # heading and speed of the cache
        tol = m.diffraction.heading_tolerance if has_diff else 0.0
        self._diff_tol = float(tol)
        self._diff = _diffraction_tables(m.diffraction if has_diff else None, wave_field, n_c)
        visc = m.viscous.coefficients if m.viscous is not None else None
        self._viscous = (float(visc.b1), float(visc.b2)) if visc is not None else (0.0, 0.0)
        mu_arr = np.ones(6) if mu is None else np.broadcast_to(np.asarray(mu, float), (6,))
        if not (np.all(np.isfinite(mu_arr)) and np.all(mu_arr > 0.0)):
            raise ValueError(f"mu must be positive and finite, got {mu!r}")
        self.mu = np.ascontiguousarray(mu_arr, dtype=float).copy()
        self.initial_eta = np.zeros(6) if initial_eta is None else np.array(initial_eta, float)
        if self.initial_eta.shape != (6,):
            raise ValueError(f"initial_eta must have 6 components, got {initial_eta!r}")
        nz = self.n_states
        self._t = np.zeros(1)
        self.eta = np.zeros(6)
        self.nu = np.zeros(6)
        self.z = np.zeros(nz)
        self._k = np.zeros(1, dtype=np.int64)
        self._pending = np.zeros(1, dtype=np.bool_)
        self._hist = (*(np.zeros(6) for _ in range(8)), np.zeros(nz), np.zeros(nz))
        self._stages = tuple(np.zeros(nz if i % 3 == 1 else 6) for i in range(12))
        self._resume = np.zeros(1, dtype=np.int64)
        self._status_psi = np.zeros(1)
        self.n_steps = 0
        self._python_refreshes = 0
        self.reset()

    @property
    def n_refreshes(self) -> int:
        """Diffraction cache refreshes since construction (compiled and in Python)."""
        return int(self._diff[-1][0]) + self._python_refreshes

    # ------------------------------------------------------------------ state
    @property
    def t(self) -> float:
        """Time [s]."""
        return float(self._t[0])

    def reset(self, eta: NDArray | None = None, nu: NDArray | None = None, t0: float = 0.0):
        """Restart at ``t0`` from (η, ν) (defaults: :attr:`initial_eta`, (U, 0, …, 0)); the
        memory states, the integrator history and the diffraction cache are cleared."""
        e = self.initial_eta if eta is None else np.asarray(eta, float)
        if nu is None:
            n = np.zeros(6)
            n[SURGE] = self.forward_speed
        else:
            n = np.asarray(nu, float)
        if e.shape != (6,) or n.shape != (6,):
            raise ValueError("eta and nu must each have 6 components")
        if not np.isfinite(t0):
            raise ValueError(f"t0 must be finite, got {t0!r}")
        self._t[0] = float(t0)
        self.eta[:] = e
        self.nu[:] = n
        self.z[:] = 0.0
        self._k[0] = 0
        self._pending[0] = False
        for h in self._hist:
            h[:] = 0.0
        self._resume[0] = 0
        self._diff_ref[:] = np.nan
        self.n_steps = 0

    def _refresh_diffraction(self, psi: float) -> None:
        """X_D and ∂X_D/∂ψ at heading ψ (the single-ship rule, :class:`Diffraction`)."""
        w = self.wave_field
        assert w is not None and self.models.diffraction is not None
        xd, dxd, _, _ = self.models.diffraction.heading_expansion(
            w.direction, w.omega, w.wavenumber, psi, self.forward_speed
        )
        self._xd[:] = xd
        self._dxd[:] = dxd
        self._diff_ref[0] = psi
        self._diff_ref[1] = self.forward_speed
        self._python_refreshes += 1

    def advance(self, n_steps: int = 1) -> None:
        """Take ``n_steps`` steps of ``dt`` in one compiled call (diffraction refreshes included;
        a look-up that must raise comes back to Python, see :func:`_refresh_diffraction`).

        Raises
        ------
        SimulationDiverged
            If a step produces a non-finite or too fast state; the ship keeps the state of the
            start of that step.
        ValueError
            If the diffraction model has ``above_range="raise"`` and an encounter frequency
            leaves its table (raised by the model; the ship keeps the state of the last
            completed step).
        """
        left = int(n_steps)
        if left < 0:
            raise ValueError(f"n_steps must be ≥ 0, got {n_steps!r}")
        while left > 0:
            done, status = _advance(
                left, self.integrator_name == "rk4", self._t, self.eta, self.nu, self.z,
                self._k, self._pending, *self._hist, *self._stages, self._resume, self.mu,
                self.dt, self.max_abs_velocity,
                *self._hull, *self._waves, *self._rigid, *self._radiation, self._has_diff,
                self._xd, self._dxd, self._diff_ref, self._diff_tol, self._diff, *self._viscous,
                self._status_psi,
            )  # fmt: skip
            self.n_steps += done
            left -= done
            if status == _STALE:
                self._refresh_diffraction(float(self._status_psi[0]))
            elif status == _DIVERGED:
                raise SimulationDiverged(
                    f"state diverged at t = {self.t + self.dt:.3f} s (step {self.n_steps + 1}): "
                    f"eta = {np.round(self.eta, 4).tolist()}, nu = "
                    f"{np.round(self.nu, 4).tolist()}; try a smaller dt (now {self.dt} s)"
                )

    def term_costs(self, repeats: int = 200, rounds: int = 5) -> dict[str, float]:
        """CPU time [s] of one call of each term of an evaluation at the current state.

        Each term is run ``repeats`` times in a compiled loop (no Python in between), the
        fastest of ``rounds`` such loops is kept (``time.process_time``). Keys:
        ``"froude_krylov_hydrostatic"``, ``"wave_phasors"``, ``"radiation"``,
        ``"diffraction"`` (0 without it), ``"rigid_body_viscous_roll"`` (rotation, gravity,
        Coriolis, kinematics and the viscous roll damping). Timing only: the state is not
        changed.
        """
        import time

        amp, omega_t, phase_t, ramp, kxt, kyt, k2, kxt32, kyt32, k232 = self._waves
        n_c = amp.shape[0]
        mod, offset = np.empty(n_c), np.empty(n_c)
        local = np.empty(n_c, dtype=np.complex128)
        q, v, t = self.eta.copy(), self.nu.copy(), self.t
        rot = np.empty((3, 3))
        _rigid_terms(q, v, *self._rigid[:4], rot, np.empty(6), np.empty(6))
        crest = _local_phasors(t, q[0], q[1], amp, omega_t, phase_t, ramp, kxt, kyt, mod, offset,
                               local)  # fmt: skip
        if self._has_diff and np.isnan(self._diff_ref[0]):
            self._refresh_diffraction(float(q[5]))
        jobs = {
            "froude_krylov_hydrostatic": lambda n: _loop_fk(
                n, *self._hull, rot, q[2], kxt, kyt, k2, kxt32, kyt32, k232, mod, offset, crest
            ),
            "wave_phasors": lambda n: _loop_phasors(
                n, t, q, amp, omega_t, phase_t, ramp, kxt, kyt, mod.copy(), offset.copy(),
                local.copy(),
            ),
            "radiation": lambda n: _loop_radiation(n, v, self.z, *self._radiation),
            "diffraction": lambda n: _loop_diffraction(
                n, q[5], local, self._xd, self._dxd, self._diff_ref
            ),
            "rigid_body_viscous_roll": lambda n: _loop_rigid(
                n, q, v, *self._rigid[:4], *self._viscous
            ),
        }  # fmt: skip
        out: dict[str, float] = {}
        for name, job in jobs.items():
            if name == "diffraction" and not self._has_diff:
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


def build_compiled_ship(
    setup: ShipSetup,
    wave_field: WaveField | None,
    *,
    sea: Sea = None,
    wave_heading: float = np.pi,
    precision: Precision = "float64",
) -> CompiledShip:
    """A :class:`CompiledShip` of a setup at the free-floating equilibrium, heading north.

    The counterpart of :func:`ship_gym.engine.ship.build_simulator` and
    :func:`ship_gym.engine.batch.build_batch_simulator` (same models, same initial state)
    for a setup whose force set is the reference one (radiation ``"state_space"``, or
    ``"2a"``/``"2b"`` with ``sea`` given; no control models, no added resistance, not lumped).

    Parameters
    ----------
    setup : ShipSetup
        ``integrator`` "holloway" or "rk4".
    wave_field : WaveField or None
        The sea (:func:`ship_gym.engine.ship.wave_field_for`).
    sea, wave_heading
        As for :func:`build_force_models` (not needed for state-space radiation).
    precision : {"float64", "float32"}
        Wave-sum precision of the Froude–Krylov kernel.
    """
    if setup.integrator not in ("holloway", "rk4"):
        raise NotImplementedError(
            f"CompiledShip implements 'holloway' and 'rk4', not {setup.integrator!r}"
        )
    hull = load_hull(setup.hull, **setup.hull_overrides)
    database = load_database(setup.database)
    built = build_force_models(setup, hull, database, wave_field, sea, wave_heading)
    models, commands = built if isinstance(built, tuple) else (built, {})
    if commands:
        raise NotImplementedError(
            f"CompiledShip has no actuator commands; the setup needs {sorted(commands)}"
        )
    eq = equilibrium(hull)
    return CompiledShip(
        hull,
        models,
        wave_field,
        forward_speed=setup.speed,
        dt=setup.dt,
        integrator=setup.integrator,  # type: ignore[arg-type]
        precision=precision,
        free_dofs=setup.free_dofs,
        initial_eta=np.array([0.0, 0.0, eq.heave, 0.0, eq.trim, 0.0]),
    )
