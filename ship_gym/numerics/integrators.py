"""Explicit fixed-step integrators for second-order systems of n degrees of freedom.

The simulator's state is a position-like vector q (nq,), a velocity-like vector v (nv,) and,
optionally, extra first-order states z (nz,) (actuator lags, an autopilot integrator, the states
of a state-space radiation model…). The integrators advance

    q̇ = f(q, v)          kinematics: a user callable, default q̇ = v (then nq = nv)
    v̇ = a(t, q, v[, z])  the acceleration, from the right-hand side ``rhs``
    ż = g(t, q, v, z)    returned by ``rhs`` together with the acceleration

by one fixed step Δt [s] per call of ``step``. For a ship q = η (earth-fixed position and zyx
Euler angles), v = ν (body-axis velocities) and f(η, ν) = J(η) ν.

Calling conventions
-------------------
:class:`RK4` and :class:`AdamsBashforthMoulton` call

* ``rhs(t, q, v) -> a``                 when ``step`` is given no z,
* ``rhs(t, q, v, z) -> (a, zdot)``      when ``step`` is given z.

:class:`HollowayIntegrator` also hands the right-hand side the acceleration extrapolated from the
velocity history, ẍ_e (Holloway 2007, eq. 6), so that a force model may *lump* the added-mass
force −A ẍ into the force with ẍ → ẍ_e (Holloway eq. 10):

* ``rhs(t, q, v, acc_extrapolated) -> acc_computed``
* ``rhs(t, q, v, z, acc_extrapolated) -> (acc_computed, zdot)``

where ``acc_computed`` is ẍ_c = M⁻¹F (Holloway eq. 3–4 with m → the mass matrix; see
:func:`acceleration_from_force` to wrap a force callable). A right-hand side that does not use
``acc_extrapolated`` is simply an exact acceleration.

``step(t, q, v, rhs, z=None)`` returns ``(q_new, v_new, z_new)`` (``z_new`` is None when z was
None). Arrays are float64; the arrays handed to ``rhs`` and returned by ``step`` are fresh, so
they may be kept. ``rhs`` must be a function of its arguments only (it is called at intermediate
stages, and several times per instant during Holloway's start-up); force models with memory
update their own state from the accepted steps.

Integrators with history (:class:`AdamsBashforthMoulton`, :class:`HollowayIntegrator`) check
that each call's t is the previous t plus Δt, and must be :meth:`reset` after any discontinuous
change of the state (a new episode, an impulse). Changes that the derivatives do not feel, such
as wrapping an angle in q by 2π, are harmless: neither scheme keeps a history of q.

Force evaluations per step (after start-up)
--------------------------------------------
=========================================  ===========  ==========================================
scheme                                     evaluations  start-up
=========================================  ===========  ==========================================
:class:`RK4`                               4            none
:class:`AdamsBashforthMoulton` ``"PECE"``  2            3 RK4 steps + 1 evaluation
:class:`AdamsBashforthMoulton` ``"AB"``    1            3 RK4 steps + 1 evaluation
:class:`HollowayIntegrator`                1            ``"rk4"``: 2 RK4 steps, implicit ẍ solved;
                                                        ``"constant"``: none
=========================================  ===========  ==========================================

RK4 and ABM need the *stable form* of the equations of motion (Kring, Huang & Sclavounos eq. 3):
the instantaneous added mass on the left, in the mass matrix, and a right-hand side that does
not depend on the acceleration. Holloway's scheme does not: a rough estimate of the added mass
in μ suffices.

Performance
-----------
The arithmetic of every scheme is fused into a few numba kernels that loop over the DOF in
compiled code (no Python-level per-DOF loops); the Python overhead of a step is a handful of
kernel calls and array allocations. ``scripts/reproduce_holloway.py --benchmark`` measures it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, Literal, NamedTuple, cast

import numba as nb
import numpy as np
import numpy.typing as npt

from ship_gym.typing import FloatArray

__all__ = [
    "RK4",
    "AdamsBashforthMoulton",
    "HollowayIntegrator",
    "Trajectory",
    "acceleration_from_force",
    "holloway_mu",
    "integrate",
]

KinematicsFn = Callable[[FloatArray, FloatArray], FloatArray]
RhsFn = Callable[..., Any]

_F64 = np.dtype(np.float64)
_EMPTY: FloatArray = np.zeros(0)
_EMPTY.flags.writeable = False

# ---------------------------------------------------------------------------------------------
# numba kernels (compiled loops over the DOF; outputs written into preallocated arrays)
# ---------------------------------------------------------------------------------------------


@nb.njit(cache=True)
def _axpy2(x1, d1, x2, d2, c, o1, o2):  # pragma: no cover - compiled
    """o1 = x1 + c d1, o2 = x2 + c d2."""
    for i in range(x1.size):
        o1[i] = x1[i] + c * d1[i]
    for i in range(x2.size):
        o2[i] = x2[i] + c * d2[i]


@nb.njit(cache=True)
def _rk4_sum2(x1, k1a, k2a, k3a, k4a, x2, k1b, k2b, k3b, k4b, h, o1, o2):  # pragma: no cover
    """RK4 combination y + h/6 (k1 + 2k2 + 2k3 + k4) for two components."""
    c = h / 6.0
    for i in range(x1.size):
        o1[i] = x1[i] + c * (k1a[i] + 2.0 * (k2a[i] + k3a[i]) + k4a[i])
    for i in range(x2.size):
        o2[i] = x2[i] + c * (k1b[i] + 2.0 * (k2b[i] + k3b[i]) + k4b[i])


@nb.njit(cache=True)
def _axpy(x, d, c, out):  # pragma: no cover - compiled
    """out = x + c d."""
    for i in range(x.size):
        out[i] = x[i] + c * d[i]


@nb.njit(cache=True)
def _rk4_sum(x, k1, k2, k3, k4, h, out):  # pragma: no cover - compiled
    """RK4 combination x + h/6 (k1 + 2k2 + 2k3 + k4)."""
    c = h / 6.0
    for i in range(x.size):
        out[i] = x[i] + c * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i])


@nb.njit(cache=True)
def _ab4(x, hist, i0, i1, i2, i3, h, out):  # pragma: no cover - compiled
    """Adams–Bashforth 4: x + h/24 (55 f₀ − 59 f₋₁ + 37 f₋₂ − 9 f₋₃); rows of ``hist``."""
    c = h / 24.0
    for k in range(x.size):
        out[k] = x[k] + c * (
            55.0 * hist[i0, k] - 59.0 * hist[i1, k] + 37.0 * hist[i2, k] - 9.0 * hist[i3, k]
        )


@nb.njit(cache=True)
def _am4(x, f_new, hist, i0, i1, i2, h, out):  # pragma: no cover - compiled
    """Adams–Moulton 4 (3-step): x + h/24 (9 f₊₁ + 19 f₀ − 5 f₋₁ + f₋₂)."""
    c = h / 24.0
    for k in range(x.size):
        out[k] = x[k] + c * (9.0 * f_new[k] + 19.0 * hist[i0, k] - 5.0 * hist[i1, k] + hist[i2, k])


@nb.njit(cache=True)
def _bdf2(x0, x1, x2, dt, out):  # pragma: no cover - compiled
    """Second-order backward difference (Holloway eq. 6–7): (3x₀ − 4x₋₁ + x₋₂)/(2Δt)."""
    c = 0.5 / dt
    for i in range(x0.size):
        out[i] = (3.0 * x0[i] - 4.0 * x1[i] + x2[i]) * c


@nb.njit(cache=True)
def _holloway_update(q, v, ac, ae, mu, a1, a2, v2, dt, update_q, q_out, v_out):  # pragma: no cover
    """Holloway eq. 4, 7, 8 (and 9 if ``update_q``); recycles a2 ← ẍ and v2 ← ẋ."""
    c = 0.5 / dt
    h2 = 0.5 * dt * dt
    h3 = dt * dt * dt / 6.0
    for i in range(v.size):
        a = mu[i] * ac[i] + (1.0 - mu[i]) * ae[i]  # eq. 4
        j = (3.0 * a - 4.0 * a1[i] + a2[i]) * c  # eq. 7
        v_out[i] = v[i] + dt * a + h2 * j  # eq. 8
        if update_q:
            q_out[i] = q[i] + dt * v[i] + h2 * a + h3 * j  # eq. 9
        a2[i] = a
        v2[i] = v[i]


@nb.njit(cache=True)
def _taylor3_update(q, qd, qd1, qd2, qdd1, qdd2, dt, q_out):  # pragma: no cover - compiled
    """Eq. 9 for q̇ = f(q, v): q̈, q⃛ by eq. 6–7 on the q̇ history; recycles qd2, qdd2."""
    c = 0.5 / dt
    h2 = 0.5 * dt * dt
    h3 = dt * dt * dt / 6.0
    for i in range(q.size):
        qdd = (3.0 * qd[i] - 4.0 * qd1[i] + qd2[i]) * c
        qddd = (3.0 * qdd - 4.0 * qdd1[i] + qdd2[i]) * c
        q_out[i] = q[i] + dt * qd[i] + h2 * qdd + h3 * qddd
        qd2[i] = qd[i]
        qdd2[i] = qdd


@nb.njit(cache=True)
def _taylor2_update(z, zd, zd1, zd2, dt, z_out):  # pragma: no cover - compiled
    """Eq. 8 for a first-order state: z + Δt ż + Δt²/2 z̈, z̈ by eq. 7; recycles zd2 ← ż."""
    c = 0.5 / dt
    h2 = 0.5 * dt * dt
    for i in range(z.size):
        zdd = (3.0 * zd[i] - 4.0 * zd1[i] + zd2[i]) * c
        z_out[i] = z[i] + dt * zd[i] + h2 * zdd
        zd2[i] = zd[i]


# ---------------------------------------------------------------------------------------------
# validation helpers
# ---------------------------------------------------------------------------------------------


def _positive_dt(dt: float) -> float:
    try:
        value = float(dt)
    except (TypeError, ValueError):
        raise ValueError(f"dt = {dt!r}; expected a positive finite time step [s]") from None
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"dt = {dt!r}; expected a positive finite time step [s]")
    return value


def _check_kinematics(kinematics: KinematicsFn | None) -> KinematicsFn | None:
    if kinematics is not None and not callable(kinematics):
        raise ValueError(
            f"kinematics = {kinematics!r}; expected None (q̇ = v) or a callable (q, v) -> q̇"
        )
    return kinematics


def _state(x: Any, name: str) -> FloatArray:
    """A 1-D float64 array (no copy when ``x`` already is one)."""
    if type(x) is np.ndarray and x.dtype is _F64 and x.ndim == 1:
        return x
    arr = np.asarray(x, dtype=np.float64)
    if arr.ndim != 1:
        raise ValueError(f"{name} has shape {arr.shape}; expected a 1-D array")
    return arr


def _out(x: Any, n: int, name: str) -> FloatArray:
    """Validate a callable's output: float64 of shape (n,)."""
    if type(x) is np.ndarray and x.dtype is _F64 and x.shape == (n,):
        return x
    try:
        arr = np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {x!r}; expected a float array of shape ({n},)") from None
    if arr.shape != (n,):
        raise ValueError(f"{name} has shape {arr.shape}; expected ({n},)")
    return arr


def _pair(result: Any, nv: int, nz: int, what: str) -> tuple[FloatArray, FloatArray]:
    """Unpack and validate ``(acceleration, zdot)`` from a right-hand side with aux states."""
    if not isinstance(result, tuple | list) or len(result) != 2:
        raise ValueError(
            f"rhs returned {type(result).__name__}; with aux states z it must return the tuple "
            f"({what}, zdot)"
        )
    acc, zdot = result
    return _out(acc, nv, what), _out(zdot, nz, "zdot")


def _check_shapes(q: FloatArray, v: FloatArray, identity: bool) -> None:
    if identity and q.shape != v.shape:
        raise ValueError(
            f"q has shape {q.shape} and v {v.shape}; with the default kinematics q̇ = v they "
            "must match (pass a kinematics callable otherwise)"
        )


# ---------------------------------------------------------------------------------------------
# shared RK4 core
# ---------------------------------------------------------------------------------------------


def _zstage(z: FloatArray, g: FloatArray, c: float) -> FloatArray:
    out = np.empty(z.size)
    _axpy(z, g, c, out)
    return out


_Evaluate = Callable[[float, FloatArray, FloatArray, FloatArray], tuple[FloatArray, FloatArray]]


def _rk4_core(
    t: float,
    q: FloatArray,
    v: FloatArray,
    z: FloatArray,
    h: float,
    evaluate: _Evaluate,
    kinematics: KinematicsFn | None,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """One classical RK4 step of (q, v, z); returns the new state and the stage-1 derivatives.

    ``evaluate(t, q, v, z) -> (a, zdot)``. Returns ``(q1, v1, z1, qdot0, a0, zdot0)``.
    """
    nq, nv, nz = q.size, v.size, z.size
    has_z = nz > 0

    def qdot(qs: FloatArray, vs: FloatArray) -> FloatArray:
        return vs if kinematics is None else _out(kinematics(qs, vs), nq, "kinematics q̇")

    a1, g1 = evaluate(t, q, v, z)
    d1 = qdot(q, v)
    q2, v2 = np.empty(nq), np.empty(nv)
    _axpy2(q, d1, v, a1, 0.5 * h, q2, v2)
    z2 = _zstage(z, g1, 0.5 * h) if has_z else z
    a2, g2 = evaluate(t + 0.5 * h, q2, v2, z2)
    d2 = qdot(q2, v2)
    q3, v3 = np.empty(nq), np.empty(nv)
    _axpy2(q, d2, v, a2, 0.5 * h, q3, v3)
    z3 = _zstage(z, g2, 0.5 * h) if has_z else z
    a3, g3 = evaluate(t + 0.5 * h, q3, v3, z3)
    d3 = qdot(q3, v3)
    q4, v4 = np.empty(nq), np.empty(nv)
    _axpy2(q, d3, v, a3, h, q4, v4)
    z4 = _zstage(z, g3, h) if has_z else z
    a4, g4 = evaluate(t + h, q4, v4, z4)
    d4 = qdot(q4, v4)
    q_new, v_new = np.empty(nq), np.empty(nv)
    _rk4_sum2(q, d1, d2, d3, d4, v, a1, a2, a3, a4, h, q_new, v_new)
    if has_z:
        z_new = np.empty(nz)
        _rk4_sum(z, g1, g2, g3, g4, h, z_new)
    else:
        z_new = z
    return q_new, v_new, z_new, d1, a1, g1


class _Integrator:
    """Common bookkeeping: time step, kinematics, evaluation counter, time continuity."""

    def __init__(self, dt: float, kinematics: KinematicsFn | None = None) -> None:
        self._dt = _positive_dt(dt)
        self._kinematics = _check_kinematics(kinematics)
        self.n_evaluations = 0
        """Number of calls of ``rhs`` since construction [-] (start-up included)."""
        self._t_next: float | None = None

    @property
    def dt(self) -> float:
        """Fixed time step Δt [s]."""
        return self._dt

    @property
    def kinematics(self) -> KinematicsFn | None:
        """The kinematics callable (q, v) -> q̇, or None for q̇ = v."""
        return self._kinematics

    def reset(self) -> None:
        """Forget all history: the next ``step`` starts afresh (with the start-up steps)."""
        self._t_next = None

    def _check_time(self, t: float) -> None:
        t_next = self._t_next
        if t_next is not None and abs(t - t_next) > 1e-6 * self._dt + 4e-16 * abs(t_next):
            raise ValueError(
                f"t = {t!r} s but this integrator's history ends at t = {t_next!r} s (previous "
                f"t + dt); call reset() after a jump in time or state"
            )

    def _plain_evaluator(self, rhs: RhsFn, nv: int, nz: int, aux: bool) -> _Evaluate:
        if aux:

            def evaluate(t: float, q: FloatArray, v: FloatArray, z: FloatArray):
                self.n_evaluations += 1
                return _pair(rhs(t, q, v, z), nv, nz, "acceleration")

        else:

            def evaluate(t: float, q: FloatArray, v: FloatArray, z: FloatArray):
                self.n_evaluations += 1
                return _out(rhs(t, q, v), nv, "rhs acceleration"), _EMPTY

        return evaluate


# ---------------------------------------------------------------------------------------------
# RK4
# ---------------------------------------------------------------------------------------------


class RK4(_Integrator):
    """Classical fourth-order Runge–Kutta; 4 right-hand-side evaluations per step.

    Stateless apart from the evaluation counter; global error O(Δt⁴).

    Parameters
    ----------
    dt : float
        Time step Δt [s].
    kinematics : callable, optional
        ``kinematics(q, v) -> q̇``; default q̇ = v.

    Examples
    --------
    >>> rk4 = RK4(0.1)
    >>> q, v, _ = rk4.step(0.0, np.array([1.0]), np.array([0.0]), lambda t, q, v: -q)
    """

    def step(
        self,
        t: float,
        q: npt.ArrayLike,
        v: npt.ArrayLike,
        rhs: RhsFn,
        z: npt.ArrayLike | None = None,
    ) -> tuple[FloatArray, FloatArray, FloatArray | None]:
        """Advance (q, v[, z]) from t [s] to t + Δt.

        Parameters
        ----------
        t : float
            Current time [s].
        q, v : array_like
            Position-like (nq,) and velocity-like (nv,) states [SI].
        rhs : callable
            ``rhs(t, q, v) -> a`` (nv,), or ``rhs(t, q, v, z) -> (a, zdot)`` when z is given.
        z : array_like, optional
            Auxiliary first-order states (nz,).

        Returns
        -------
        q_new, v_new, z_new
            The state at t + Δt; ``z_new`` is None when z is None.
        """
        q = _state(q, "q")
        v = _state(v, "v")
        _check_shapes(q, v, self._kinematics is None)
        aux = z is not None
        zz = _state(z, "z") if aux else _EMPTY
        evaluate = self._plain_evaluator(rhs, v.size, zz.size, aux)
        q_new, v_new, z_new, *_ = _rk4_core(t, q, v, zz, self._dt, evaluate, self._kinematics)
        return q_new, v_new, (z_new if aux else None)


# ---------------------------------------------------------------------------------------------
# Adams–Bashforth–Moulton
# ---------------------------------------------------------------------------------------------

AbmMode = Literal["PECE", "AB"]


class AdamsBashforthMoulton(_Integrator):
    """Fourth-order Adams–Bashforth predictor with a fourth-order Adams–Moulton corrector.

    Predictor (AB4)  y* = yₙ + Δt/24 (55 fₙ − 59 fₙ₋₁ + 37 fₙ₋₂ − 9 fₙ₋₃),
    corrector (AM4)  yₙ₊₁ = yₙ + Δt/24 (9 f(y*) + 19 fₙ − 5 fₙ₋₁ + fₙ₋₂),
    applied to y = (q, v, z), f = (q̇, v̇, ż) (Hairer, Nørsett & Wanner, *Solving ODEs I*, §III.1).

    Why this pair: it has the order of RK4 (global error O(Δt⁴)) at half RK4's cost, and it is
    the multistep family Kring, Huang & Sclavounos use with the stable form of the equations of
    motion. The corrector is what makes it usable for oscillators at a reasonable step. Spectral
    radius ρ per step for λ = ω(−ζ + i√(1 − ζ²)), from the schemes' companion matrices:

    * AB4 alone: stable on the imaginary axis for ωΔt < 0.43 (ζ = 0.05: < 0.42);
    * PECE: ρ − 1 ≈ 0.16 (ωΔt)⁶ on the imaginary axis (3.5e-5 per step at ωΔt = 0.25, 1.5e-3
      at 0.5) — an undamped oscillator gains amplitude very slowly, but any physical damping
      ζωΔt above that wins: stable up to ωΔt ≈ 0.76 for ζ = 0.01 and ≈ 0.92 for ζ = 0.05;
    * RK4 for comparison: stable for ωΔt < 2.83 (slightly dissipative).

    PEC mode (f(y*) kept in the history, 1 evaluation) is deliberately not offered: its
    parasitic roots make it unstable for ωΔt ≳ 0.21, worse than AB4 alone.

    Modes (``mode``):

    * ``"PECE"`` (default): predict, evaluate, correct, evaluate — 2 evaluations per step; the
      history holds f at the corrected states.
    * ``"AB"``: the predictor alone (yₙ₊₁ = y*) — 1 evaluation per step.

    Start-up: the first three steps after construction or :meth:`reset` are RK4 steps (4
    evaluations each), whose first-stage derivatives fill the history; the fourth step spends
    one extra evaluation on f at its initial state.

    Parameters
    ----------
    dt : float
        Time step Δt [s].
    kinematics : callable, optional
        ``kinematics(q, v) -> q̇``; default q̇ = v.
    mode : {"PECE", "AB"}
        See above.
    """

    _N_STARTUP = 3

    def __init__(
        self, dt: float, kinematics: KinematicsFn | None = None, mode: AbmMode = "PECE"
    ) -> None:
        super().__init__(dt, kinematics)
        if mode not in ("PECE", "AB"):
            raise ValueError(f"mode = {mode!r}; expected 'PECE' or 'AB'")
        self._mode: AbmMode = mode
        self.reset()

    @property
    def mode(self) -> AbmMode:
        """Predictor–corrector mode: ``"PECE"`` or ``"AB"``."""
        return self._mode

    @property
    def evaluations_per_step(self) -> int:
        """Right-hand-side evaluations per step after start-up [-]."""
        return 2 if self._mode == "PECE" else 1

    def reset(self) -> None:
        """Forget the history; the next three steps are RK4 start-up steps."""
        super().reset()
        self._k = 0
        self._head = -1
        self._shapes: tuple[int, int, int] | None = None
        self._aux: bool | None = None
        self._hq = self._hv = self._hz = _EMPTY
        self._need_f = False

    def _store(self, dq: FloatArray, a: FloatArray, g: FloatArray) -> None:
        slot = (self._head + 1) % 4
        self._hq[slot] = dq
        self._hv[slot] = a
        if g.size:
            self._hz[slot] = g
        self._head = slot

    def step(
        self,
        t: float,
        q: npt.ArrayLike,
        v: npt.ArrayLike,
        rhs: RhsFn,
        z: npt.ArrayLike | None = None,
    ) -> tuple[FloatArray, FloatArray, FloatArray | None]:
        """Advance (q, v[, z]) from t [s] to t + Δt; same arguments as :meth:`RK4.step`."""
        self._check_time(t)
        q = _state(q, "q")
        v = _state(v, "v")
        aux = z is not None
        zz = _state(z, "z") if aux else _EMPTY
        shapes = (q.size, v.size, zz.size)
        if self._shapes is None:
            _check_shapes(q, v, self._kinematics is None)
            self._shapes, self._aux = shapes, aux
            self._hq, self._hv, self._hz = (np.empty((4, n)) for n in shapes)
        elif shapes != self._shapes or aux != self._aux:
            raise ValueError(
                f"state sizes (nq, nv, nz) = {shapes} (z given: {aux}) differ from the "
                f"history's {self._shapes} (z given: {self._aux}); call reset() first"
            )
        nq, nv, nz = shapes
        h = self._dt
        kin = self._kinematics
        evaluate = self._plain_evaluator(rhs, nv, nz, aux)
        if self._k < self._N_STARTUP:
            q_new, v_new, z_new, d0, a0, g0 = _rk4_core(t, q, v, zz, h, evaluate, kin)
            self._store(d0, a0, g0)
            self._need_f = self._k == self._N_STARTUP - 1
        else:
            if self._need_f:
                a0, g0 = evaluate(t, q, v, zz)
                self._store(v if kin is None else _out(kin(q, v), nq, "kinematics q̇"), a0, g0)
                self._need_f = False
            i0 = self._head
            i1, i2, i3 = (i0 - 1) % 4, (i0 - 2) % 4, (i0 - 3) % 4
            qp, vp = np.empty(nq), np.empty(nv)
            _ab4(q, self._hq, i0, i1, i2, i3, h, qp)
            _ab4(v, self._hv, i0, i1, i2, i3, h, vp)
            zp = _EMPTY
            if nz:
                zp = np.empty(nz)
                _ab4(zz, self._hz, i0, i1, i2, i3, h, zp)
            ap, gp = evaluate(t + h, qp, vp, zp)
            dp = vp if kin is None else _out(kin(qp, vp), nq, "kinematics q̇")
            if self._mode == "AB":
                q_new, v_new, z_new = qp, vp, zp
                self._store(dp, ap, gp)
            else:
                q_new, v_new = np.empty(nq), np.empty(nv)
                _am4(q, dp, self._hq, i0, i1, i2, h, q_new)
                _am4(v, ap, self._hv, i0, i1, i2, h, v_new)
                z_new = _EMPTY
                if nz:
                    z_new = np.empty(nz)
                    _am4(zz, gp, self._hz, i0, i1, i2, h, z_new)
                a1, g1 = evaluate(t + h, q_new, v_new, z_new)
                d1 = v_new if kin is None else _out(kin(q_new, v_new), nq, "kinematics q̇")
                self._store(d1, a1, g1)
        self._k += 1
        self._t_next = t + h
        return q_new, v_new, (z_new if aux else None)


# ---------------------------------------------------------------------------------------------
# Holloway's μ-Taylor scheme
# ---------------------------------------------------------------------------------------------

StartupMode = Literal["rk4", "constant"]


def holloway_mu(mass: npt.ArrayLike, added_mass_estimate: npt.ArrayLike) -> FloatArray:
    """Holloway's blending coefficient μ = m/(m + A_e) (Holloway 2007, eq. 3–4), per DOF.

    Parameters
    ----------
    mass : array_like
        Rigid-body mass or inertia m per DOF [kg, kg m²]: a scalar, a vector (n,) or a mass
        matrix (n, n), of which the diagonal is used.
    added_mass_estimate : array_like
        Estimate A_e of the instantaneous (high-frequency) added mass per DOF, same units and
        forms as ``mass``. Holloway §5: anything inside a broad band works; μ = m/(m + A) is
        where the stabilisation error vanishes.

    Returns
    -------
    numpy.ndarray
        μ [-] with the broadcast shape of the diagonals (0-d for scalars).
    """

    def diag(x: npt.ArrayLike, name: str) -> FloatArray:
        arr = np.asarray(x, dtype=np.float64)
        if arr.ndim == 2:
            if arr.shape[0] != arr.shape[1]:
                raise ValueError(f"{name} has shape {arr.shape}; expected a square matrix")
            arr = np.diagonal(arr).copy()
        elif arr.ndim > 2:
            raise ValueError(f"{name} has shape {arr.shape}; expected scalar, (n,) or (n, n)")
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"{name} = {arr!r}; expected finite values")
        return arr

    m = diag(mass, "mass")
    a = diag(added_mass_estimate, "added_mass_estimate")
    if np.any(m <= 0.0):
        raise ValueError(f"mass = {m!r}; expected positive diagonal entries [kg, kg m²]")
    try:
        total = m + a
    except ValueError:
        raise ValueError(
            f"mass (shape {m.shape}) and added_mass_estimate (shape {a.shape}) do not broadcast"
        ) from None
    if np.any(total <= 0.0):
        raise ValueError(
            f"mass + added_mass_estimate = {total!r}; expected positive virtual masses"
        )
    return m / total


class HollowayIntegrator(_Integrator):
    """Holloway's stabilised μ-Taylor scheme (Holloway 2007, eq. 4, 6–9); one evaluation per step.

    At tₖ, with the velocity history ẋₖ₋₁, ẋₖ₋₂ and the acceleration history ẍₖ₋₁, ẍₖ₋₂:

    1. ẍ_e = (3ẋₖ − 4ẋₖ₋₁ + ẋₖ₋₂)/(2Δt)                         (eq. 6)
    2. ẍ_c = rhs(tₖ, xₖ, ẋₖ, ẍ_e)  — the acceleration from the force (eq. 3), with any added-mass
       force the model lumps in evaluated at ẍ_e (eq. 10)
    3. ẍₖ = μ ẍ_c + (1 − μ) ẍ_e, μ per DOF                      (eq. 4)
    4. x⃛ₖ = (3ẍₖ − 4ẍₖ₋₁ + ẍₖ₋₂)/(2Δt), on the *blended* ẍ       (eq. 7)
    5. ẋₖ₊₁ = ẋₖ + Δt ẍₖ + Δt²/2 x⃛ₖ                               (eq. 8)
    6. xₖ₊₁ = xₖ + Δt ẋₖ + Δt²/2 ẍₖ + Δt³/6 x⃛ₖ                    (eq. 9)

    μ = m/(m + A_e) (:func:`holloway_mu`) removes the added-mass feedback that makes explicit
    stepping unstable when the force contains −A ẍ. For a single DOF with the lumped force
    F = F_w − (A ẍ_e + B ẋ + C x) the scheme is stable for 0.2195/(A/m + 1) < μ <
    1.1401/(A/m + 1) at ζ = 0.2, ω_nΔt = 0.25 (ζ, ω_n of the virtual mass m + A; Holloway
    eq. 11 gives 0.22 and 1.14) and reduces exactly to the un-lumped scheme at μ = m/(m + A);
    see :mod:`ship_gym.analysis.holloway`. With an exact acceleration (no lumping) use μ = 1:
    the scheme is then a second-order explicit multistep method (global error O(Δt²)).

    Reading of the paper: the converted text prints the left sides of eq. 6 and 7 as ẋ_e(t)
    and ẍ(t); the text around them (and eq. 8–9, which use ẍ and x⃛) shows ẍ_e and x⃛ are meant.
    Which history eq. 7 differentiates (blended ẍ, computed ẍ_c or extrapolated ẍ_e) is not
    stated; only the blended ẍ reproduces eq. 11 (``scripts/reproduce_holloway.py``).

    Generalisations beyond the paper (same spirit, second order):

    * kinematics q̇ = f(q, v) other than q̇ = v: eq. 9 is applied to q with q̈, q⃛ from eq. 6–7
      on the history of q̇ = f(q, v) (one kinematics call per step);
    * auxiliary first-order states z: z + Δt ż + Δt²/2 z̈ with z̈ by eq. 7 on the ż history
      (eq. 8 applied to z).

    Start-up (``startup``): the scheme needs two steps of history.

    * ``"rk4"`` (default): the first two steps are RK4 steps in which every stage solves the
      implicit equation ẍ = rhs(t, q, v, ẍ) for the acceleration (chord iteration with the
      Jacobian ∂ẍ_c/∂ẍ_e from n + 1 evaluations once per start-up; exact in one iteration for a
      lumped linear added-mass force, checked by a further evaluation). The start is then
      fourth-order accurate and independent of μ; its stage-1 values fill the history
      (ẍ history = the solved accelerations). Costs about n + 17 evaluations once.
    * ``"constant"``: no special steps; the history is filled with the initial velocity and the
      first blended acceleration (ẍ_e = x⃛ = 0 at the first step), i.e. the body is assumed to
      have moved steadily before t₀. This introduces a start-up error that a stable μ damps out
      (Holloway introduces one deliberately in his Fig. 1); handy for stability studies.

    Parameters
    ----------
    dt : float
        Time step Δt [s].
    mu : array_like
        Blending coefficient μ [-] (> 0): a scalar or one value per velocity DOF (nv,).
    kinematics : callable, optional
        ``kinematics(q, v) -> q̇``; default q̇ = v.
    startup : {"rk4", "constant"}
        See above.
    """

    _N_HISTORY = 2
    _MAX_ITER = 50
    _SOLVE_RTOL = 1e-10

    def __init__(
        self,
        dt: float,
        mu: npt.ArrayLike,
        kinematics: KinematicsFn | None = None,
        startup: StartupMode = "rk4",
    ) -> None:
        super().__init__(dt, kinematics)
        mu_arr = np.array(mu, dtype=np.float64)
        if mu_arr.ndim > 1 or not np.all(np.isfinite(mu_arr)) or np.any(mu_arr <= 0.0):
            raise ValueError(f"mu = {mu!r}; expected a positive finite scalar or vector (nv,)")
        if startup not in ("rk4", "constant"):
            raise ValueError(f"startup = {startup!r}; expected 'rk4' or 'constant'")
        self._mu_input = mu_arr
        self._startup: StartupMode = startup
        self.reset()

    @classmethod
    def from_added_mass(
        cls,
        dt: float,
        mass: npt.ArrayLike,
        added_mass_estimate: npt.ArrayLike,
        kinematics: KinematicsFn | None = None,
        startup: StartupMode = "rk4",
    ) -> HollowayIntegrator:
        """Build with μ = m/(m + A_e) per DOF (:func:`holloway_mu`).

        Parameters
        ----------
        dt : float
            Time step Δt [s].
        mass, added_mass_estimate : array_like
            Mass/inertia and added-mass estimate per DOF [kg, kg m²]: scalars, vectors or
            matrices (diagonals used).
        kinematics, startup
            As for the constructor.
        """
        return cls(dt, holloway_mu(mass, added_mass_estimate), kinematics, startup)

    @property
    def mu(self) -> FloatArray:
        """Blending coefficient μ [-] as given (scalar or per DOF)."""
        return self._mu_input.copy()

    @property
    def startup(self) -> StartupMode:
        """Start-up mode, ``"rk4"`` or ``"constant"``."""
        return self._startup

    @property
    def n_startup_steps(self) -> int:
        """Steps after :meth:`reset` that are not μ-Taylor steps [-]."""
        return self._N_HISTORY if self._startup == "rk4" else 0

    @property
    def evaluations_per_step(self) -> int:
        """Right-hand-side evaluations per μ-Taylor step [-]."""
        return 1

    @property
    def last_acceleration(self) -> FloatArray | None:
        """Blended acceleration ẍₖ (eq. 4) of the last step [SI], or None before one."""
        return None if self._k == 0 else self._a1.copy()

    @property
    def last_extrapolated_acceleration(self) -> FloatArray | None:
        """ẍ_e (eq. 6) handed to ``rhs`` at the last μ-Taylor step [SI], or None."""
        return None if self._ae_last is None else self._ae_last.copy()

    def reset(self) -> None:
        """Forget the history; the next step starts with the start-up procedure."""
        super().reset()
        self._k = 0
        self._shapes: tuple[int, int, int] | None = None
        self._aux: bool | None = None
        self._mu = _EMPTY
        self._v1 = self._v2 = self._a1 = self._a2 = _EMPTY
        self._qd1 = self._qd2 = self._qdd1 = self._qdd2 = _EMPTY
        self._zd1 = self._zd2 = _EMPTY
        self._qdd_pending = False
        self._ae_last: FloatArray | None = None
        self._inv_jac: FloatArray | None = None

    # -- history ----------------------------------------------------------------------------

    def _allocate(self, nq: int, nv: int, nz: int, aux: bool) -> None:
        mu = self._mu_input
        if mu.ndim == 1 and mu.shape != (nv,):
            raise ValueError(f"mu has shape {mu.shape}; expected a scalar or ({nv},)")
        self._mu = np.ascontiguousarray(np.broadcast_to(mu, (nv,)), dtype=np.float64).copy()
        self._shapes, self._aux = (nq, nv, nz), aux
        self._v1, self._v2, self._a1, self._a2 = (np.zeros(nv) for _ in range(4))
        if self._kinematics is not None:
            self._qd1, self._qd2, self._qdd1, self._qdd2 = (np.zeros(nq) for _ in range(4))
        self._zd1, self._zd2 = np.zeros(nz), np.zeros(nz)

    @property
    def history(self) -> dict[str, FloatArray] | None:
        """Copy of the step history, rows (t − Δt, t − 2Δt), or None before two steps.

        Keys: ``"v"``, ``"a"`` (blended ẍ), and when used ``"qd"``, ``"qdd"``, ``"zd"``.
        Restore it with :meth:`set_history`.
        """
        if self._k < self._N_HISTORY or self._qdd_pending:
            return None
        out = {"v": np.stack([self._v1, self._v2]), "a": np.stack([self._a1, self._a2])}
        if self._kinematics is not None:
            out["qd"] = np.stack([self._qd1, self._qd2])
            out["qdd"] = np.stack([self._qdd1, self._qdd2])
        if self._aux:
            out["zd"] = np.stack([self._zd1, self._zd2])
        return out

    def set_history(
        self,
        t_next: float,
        v: npt.ArrayLike,
        a: npt.ArrayLike,
        qd: npt.ArrayLike | None = None,
        qdd: npt.ArrayLike | None = None,
        zd: npt.ArrayLike | None = None,
    ) -> None:
        """Install a history so that the next step (at ``t_next``) is a μ-Taylor step.

        Parameters
        ----------
        t_next : float
            Time of the next call of :meth:`step` [s].
        v, a : array_like
            (2, nv): velocities and blended accelerations at t − Δt (row 0) and t − 2Δt (row 1).
        qd, qdd : array_like, optional
            (2, nq): q̇ and q̈ at the same instants; required with a kinematics callable.
        zd : array_like, optional
            (2, nz): ż history; give it if the steps will carry auxiliary states z.
        """

        def rows(x: npt.ArrayLike | None, name: str, n: int | None) -> FloatArray:
            arr = np.array(x, dtype=np.float64)
            if arr.ndim != 2 or arr.shape[0] != 2 or (n is not None and arr.shape[1] != n):
                want = "(2, n)" if n is None else f"(2, {n})"
                raise ValueError(f"{name} history has shape {arr.shape}; expected {want}")
            return arr

        v_h = rows(v, "v", None)
        nv = v_h.shape[1]
        a_h = rows(a, "a", nv)
        if self._kinematics is not None:
            if qd is None or qdd is None:
                raise ValueError("with a kinematics callable, qd and qdd histories are required")
            qd_h = rows(qd, "qd", None)
            qdd_h = rows(qdd, "qdd", qd_h.shape[1])
            nq = qd_h.shape[1]
        else:
            nq = nv
        aux = zd is not None
        zd_h = rows(zd, "zd", None) if aux else np.zeros((2, 0))
        self.reset()
        self._allocate(nq, nv, zd_h.shape[1], aux)
        self._v1[:], self._v2[:] = v_h
        self._a1[:], self._a2[:] = a_h
        if self._kinematics is not None:
            self._qd1[:], self._qd2[:] = qd_h
            self._qdd1[:], self._qdd2[:] = qdd_h
        self._zd1[:], self._zd2[:] = zd_h
        self._k = self._N_HISTORY
        self._t_next = float(t_next)

    # -- start-up -----------------------------------------------------------------------------

    def _implicit_evaluator(self, rhs: RhsFn, nv: int, nz: int, aux: bool) -> _Evaluate:
        """evaluate(t, q, v, z) solving ẍ = rhs(t, q, v, [z,] ẍ) for ẍ (start-up only)."""
        guess = [np.zeros(nv)]

        def call(t: float, q: FloatArray, v: FloatArray, z: FloatArray, acc: FloatArray):
            self.n_evaluations += 1
            if aux:
                return _pair(rhs(t, q, v, z, acc.copy()), nv, nz, "acc_computed")
            return _out(rhs(t, q, v, acc.copy()), nv, "rhs acc_computed"), _EMPTY

        def evaluate(t: float, q: FloatArray, v: FloatArray, z: FloatArray):
            a = guess[0]
            if self._inv_jac is None:
                self._inv_jac = self._jacobian(call, t, q, v, z, a)
            for _ in range(self._MAX_ITER):
                g, zd = call(t, q, v, z, a)
                r = g - a
                scale = max(float(np.max(np.abs(g), initial=0.0)), float(np.max(np.abs(a))))
                if float(np.max(np.abs(r), initial=0.0)) <= self._SOLVE_RTOL * scale:
                    guess[0] = g
                    return g, zd
                a = a + self._inv_jac @ r
            raise RuntimeError(
                "Holloway start-up: the implicit acceleration ẍ = rhs(t, q, v, ẍ) did not "
                f"converge in {self._MAX_ITER} chord iterations at t = {t!r} s; the force is "
                "strongly nonlinear in acc_extrapolated (use startup='constant')"
            )

        return evaluate

    @staticmethod
    def _jacobian(call, t, q, v, z, a0) -> FloatArray:
        """(I − ∂ẍ_c/∂ẍ_e)⁻¹ by forward differences (n + 1 evaluations, one-off)."""
        n = a0.size
        g0, _ = call(t, q, v, z, a0)
        # a lumped added-mass force is affine in ẍ_e, for which any step is exact: a large one
        # keeps the rounding error of the quotient (≈ ε|g|/h) at ≈ 1e-12
        h = 1e-4 * max(1.0, float(np.max(np.abs(a0), initial=0.0)), float(np.max(np.abs(g0))))
        jac = np.empty((n, n))
        for i in range(n):  # start-up only: one evaluation per DOF, once per reset
            e = a0.copy()
            e[i] += h
            jac[:, i] = (call(t, q, v, z, e)[0] - g0) / h
        system = np.eye(n) - jac
        try:
            # the inverse of a float64 matrix is float64 (numpy's stub says floating)
            inv: FloatArray | None = cast(FloatArray, np.linalg.inv(system))
        except np.linalg.LinAlgError:
            inv = None
        if inv is None or not np.all(np.isfinite(inv)):
            raise ValueError(
                "Holloway start-up: I − ∂acc_computed/∂acc_extrapolated is singular, so the "
                "implicit acceleration is undefined (does the lumped added mass make m + A ≤ 0?)"
            )
        return inv

    # -- step ---------------------------------------------------------------------------------

    def step(
        self,
        t: float,
        q: npt.ArrayLike,
        v: npt.ArrayLike,
        rhs: RhsFn,
        z: npt.ArrayLike | None = None,
    ) -> tuple[FloatArray, FloatArray, FloatArray | None]:
        """Advance (q, v[, z]) from t [s] to t + Δt.

        Parameters
        ----------
        t : float
            Current time [s].
        q, v : array_like
            Position-like (nq,) and velocity-like (nv,) states [SI].
        rhs : callable
            ``rhs(t, q, v, acc_extrapolated) -> acc_computed`` (nv,), or
            ``rhs(t, q, v, z, acc_extrapolated) -> (acc_computed, zdot)`` when z is given;
            ``acc_extrapolated`` is ẍ_e of eq. 6 (during the RK4 start-up: the trial value of
            the implicit solve).
        z : array_like, optional
            Auxiliary first-order states (nz,).

        Returns
        -------
        q_new, v_new, z_new
            The state at t + Δt; ``z_new`` is None when z is None.
        """
        self._check_time(t)
        q = _state(q, "q")
        v = _state(v, "v")
        aux = z is not None
        zz = _state(z, "z") if aux else _EMPTY
        nq, nv, nz = q.size, v.size, zz.size
        kin = self._kinematics
        if self._shapes is None:
            _check_shapes(q, v, kin is None)
            self._allocate(nq, nv, nz, aux)
        elif (nq, nv, nz) != self._shapes or aux != self._aux:
            raise ValueError(
                f"state sizes (nq, nv, nz) = {(nq, nv, nz)} (z given: {aux}) differ from the "
                f"history's {self._shapes} (z given: {self._aux}); call reset() first"
            )
        dt = self._dt
        if self._k < self.n_startup_steps:
            evaluate = self._implicit_evaluator(rhs, nv, nz, aux)
            q_new, v_new, z_rk4, d0, a0, g0 = _rk4_core(t, q, v, zz, dt, evaluate, kin)
            self._push_startup(v, a0, d0, g0)
            self._k += 1
            self._t_next = t + dt
            return q_new, v_new, (z_rk4 if aux else None)

        first = self._k == 0  # only with startup="constant"
        if first:
            self._v1[:] = v
            self._v2[:] = v
        ae = np.empty(nv)
        _bdf2(v, self._v1, self._v2, dt, ae)  # eq. 6
        self.n_evaluations += 1
        if aux:
            ac, zd = _pair(rhs(t, q, v, zz, ae), nv, nz, "acc_computed")
        else:
            ac = _out(rhs(t, q, v, ae), nv, "rhs acc_computed")
            zd = _EMPTY
        self._ae_last = ae
        if first:
            a_first = self._mu * ac + (1.0 - self._mu) * ae
            self._a1[:] = a_first
            self._a2[:] = a_first
        q_new, v_new = np.empty(nq), np.empty(nv)
        _holloway_update(
            q, v, ac, ae, self._mu, self._a1, self._a2, self._v2, dt, kin is None, q_new, v_new
        )
        self._a1, self._a2 = self._a2, self._a1
        self._v1, self._v2 = self._v2, self._v1
        if kin is not None:
            qd = _out(kin(q, v), nq, "kinematics q̇")
            if first:
                self._qd1[:] = qd
                self._qd2[:] = qd
                self._qdd1[:] = 0.0
                self._qdd2[:] = 0.0
            elif self._qdd_pending:
                # after the RK4 start-up: q̈ at t − Δt (central) and t − 2Δt (forward difference)
                c = 0.5 / dt
                self._qdd2[:] = (-3.0 * self._qd2 + 4.0 * self._qd1 - qd) * c
                self._qdd1[:] = (qd - self._qd2) * c
                self._qdd_pending = False
            _taylor3_update(q, qd, self._qd1, self._qd2, self._qdd1, self._qdd2, dt, q_new)
            self._qd1, self._qd2 = self._qd2, self._qd1
            self._qdd1, self._qdd2 = self._qdd2, self._qdd1
        z_new: FloatArray | None = None
        if aux:
            if first:
                self._zd1[:] = zd
                self._zd2[:] = zd
            z_new = np.empty(nz)
            _taylor2_update(zz, zd, self._zd1, self._zd2, dt, z_new)
            self._zd1, self._zd2 = self._zd2, self._zd1
        self._k += 1
        self._t_next = t + dt
        return q_new, v_new, z_new

    def _push_startup(self, v: FloatArray, a: FloatArray, qd: FloatArray, zd: FloatArray) -> None:
        """Shift the start-up step's (v, ẍ, q̇, ż) at its initial time into the history."""
        self._v2, self._v1 = self._v1, self._v2
        self._v1[:] = v
        self._a2, self._a1 = self._a1, self._a2
        self._a1[:] = a
        if self._kinematics is not None:
            self._qd2, self._qd1 = self._qd1, self._qd2
            self._qd1[:] = qd
            self._qdd_pending = True
        if zd.size:
            self._zd2, self._zd1 = self._zd1, self._zd2
            self._zd1[:] = zd


# ---------------------------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------------------------


def acceleration_from_force(
    force: Callable[..., npt.ArrayLike], mass_matrix: npt.ArrayLike
) -> Callable[..., FloatArray]:
    """Wrap a generalised-force callable into an acceleration callable a = M⁻¹ F.

    M⁻¹ is computed once. The wrapper passes every argument through, so it works for each
    calling convention of this module (e.g. ``force(t, q, v, acc_extrapolated) -> F`` gives
    ``rhs(t, q, v, acc_extrapolated) -> M⁻¹F`` for :class:`HollowayIntegrator`). With auxiliary
    states the force callable returns ``(F, zdot)`` and only F is multiplied.

    Parameters
    ----------
    force : callable
        Generalised force [N, N m] per DOF, shape (n,).
    mass_matrix : array_like
        Generalised mass matrix M (n, n) [kg, kg m, kg m²], or its diagonal (n,), or a scalar.
    """
    m = np.asarray(mass_matrix, dtype=np.float64)
    if m.ndim > 2 or (m.ndim == 2 and m.shape[0] != m.shape[1]):
        raise ValueError(f"mass_matrix has shape {m.shape}; expected (n, n), (n,) or a scalar")
    if not np.all(np.isfinite(m)):
        raise ValueError(f"mass_matrix = {m!r}; expected finite values")
    if m.ndim < 2:
        if np.any(m <= 0.0):
            raise ValueError(f"mass_matrix = {m!r}; expected positive masses")
        inv = 1.0 / m

        def apply(f: FloatArray) -> FloatArray:
            return inv * f

    else:
        try:
            inv_m = np.linalg.inv(m)
        except np.linalg.LinAlgError:
            raise ValueError(f"mass_matrix = {m!r} is singular") from None

        def apply(f: FloatArray) -> FloatArray:
            return inv_m @ f

    def rhs(*args: Any) -> Any:
        out = force(*args)
        if isinstance(out, tuple):
            f, zdot = out
            return apply(np.asarray(f, dtype=np.float64)), zdot
        return apply(np.asarray(out, dtype=np.float64))

    return rhs


class Trajectory(NamedTuple):
    """Sampled solution from :func:`integrate`: time [s] (N+1,), q (N+1, nq), v (N+1, nv), z."""

    t: FloatArray
    q: FloatArray
    v: FloatArray
    z: FloatArray | None


def integrate(
    integrator: RK4 | AdamsBashforthMoulton | HollowayIntegrator,
    rhs: RhsFn,
    t0: float,
    q0: npt.ArrayLike,
    v0: npt.ArrayLike,
    n_steps: int,
    z0: npt.ArrayLike | None = None,
) -> Trajectory:
    """Reset ``integrator`` and take ``n_steps`` steps from (t0, q0, v0[, z0]).

    Parameters
    ----------
    integrator : RK4, AdamsBashforthMoulton or HollowayIntegrator
        The scheme; it is reset first.
    rhs : callable
        Right-hand side in the integrator's calling convention.
    t0 : float
        Initial time [s].
    q0, v0 : array_like
        Initial position-like (nq,) and velocity-like (nv,) states [SI].
    n_steps : int
        Number of steps (≥ 0).
    z0 : array_like, optional
        Initial auxiliary states (nz,).

    Returns
    -------
    Trajectory
        Times t0 + kΔt, k = 0…n_steps, and the states (``z`` None without z0).
    """
    if isinstance(n_steps, bool) or not isinstance(n_steps, int | np.integer) or n_steps < 0:
        raise ValueError(f"n_steps = {n_steps!r}; expected a non-negative integer")
    q = _state(np.array(q0, dtype=np.float64), "q0")
    v = _state(np.array(v0, dtype=np.float64), "v0")
    z = None if z0 is None else _state(np.array(z0, dtype=np.float64), "z0")
    dt = integrator.dt
    times = float(t0) + dt * np.arange(n_steps + 1, dtype=np.float64)
    qs = np.empty((n_steps + 1, q.size))
    vs = np.empty((n_steps + 1, v.size))
    zs = None if z is None else np.empty((n_steps + 1, z.size))
    qs[0], vs[0] = q, v
    if zs is not None:
        zs[0] = z
    integrator.reset()
    for k in range(n_steps):
        q, v, z = integrator.step(float(times[k]), q, v, rhs, z)
        qs[k + 1], vs[k + 1] = q, v
        if zs is not None:
            zs[k + 1] = z
    return Trajectory(times, qs, vs, zs)
