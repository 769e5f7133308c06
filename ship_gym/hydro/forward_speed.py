"""Linear seakeeping at forward speed from a zero-speed database: one stated linearisation.

The ship advances at the steady speed U along its body x axis. The hydrodynamic database is a
**zero-speed** BEM database; this module states how the package takes it to speed, once, for the
time-domain engine (:mod:`ship_gym.forces.radiation`, :mod:`ship_gym.forces.diffraction`) and for
the frequency-domain solver (:mod:`ship_gym.hydro.rao`), so that the two agree exactly in the
linear limit (a test).

Kinematics: body-axis perturbation velocity
-------------------------------------------
Let x = (x₁ … x₆) be the small displacements of O in the steadily translating (seakeeping)
frame, in our body-frame directions (:mod:`ship_gym.conventions`: x forward, y starboard,
z down, pitch bow up). The body-axis velocity of O minus the steady (U, 0, 0, 0, 0, 0) is, to
first order,

    ν_p = ẋ + U L x,      L[heave, pitch] = +1,  L[sway, yaw] = −1,  0 elsewhere,        (1)

(w = ż + U θ: a bow-up pitch tilts the body z axis aft, so the forward speed has a body-z
component; v = ẏ − U ψ likewise). ν_p is what the flow sees: the relative normal velocity of
strip theory, V = η̇₃ + U η₅ (Salvesen, Tuck & Faltinsen 1970, their η₅ bow-down in a z-up frame:
the same sign in ours, since heave and pitch flip together). :func:`speed_coupling_matrix`
returns L.

Radiation: Kirchhoff's equations linearised about U
---------------------------------------------------
In body axes the hydrodynamic momentum P = (P_lin, P_ang) of the radiated flow obeys
Kirchhoff's equations, F = −Ṗ_lin − ω × P_lin, M = −Ṗ_ang − ω × P_ang − v × P_lin (Lamb 1932
§124; Fossen 2011 §6.3: the added-mass Coriolis matrix C_A). Linearised about v = U e₁, the
terms of first order in the perturbation that survive are −Ṗ and the moment −U e₁ × P_lin, i.e.
(pitch) +U P_heave and (yaw) −U P_sway: a force U Lᵀ P with the same L as (1). With the
zero-speed memory model for the momentum of the radiated flow, P = A(∞) ν_p + λ, λ̇ = μ =
∫K(t − τ) ν_p(τ) dτ (Cummins), the radiation force at speed is

    F_rad = −A(∞) ν̇_p − μ + U Lᵀ (A(∞) ν_p + λ).                                            (2)

In the engine the U of the moment is the ship's own surge velocity u (the same to first order,
and exactly Kirchhoff's −v × P): the term is right at whatever speed a ship runs — a
per-episode initial speed, the speed loss of a turn — with nothing rebuilt or cached per speed.
The memory's ν_p = ν − U e₁ takes the engine's reference speed U only through its surge
component, whose memory dies out for a steady offset (B(0) = 0).

The surge component of ν_p is left out of the momentum P of the moment (P = A(∞) E ν_p + λ with
E = diag(0, 1, 1, 1, 1, 1), λ driven by the other five components): STF's slender-body theory
has no surge coupling either, and a ship running steadily at another speed than U (u − U a
constant surge "perturbation") would otherwise carry a spurious momentum (A₃₁ + its memory)
(u − U) whose moment changes the linear dynamics by ≈ 2 % in pitch (measured on the S175 at
U = 8.3 m/s, u = 10.4 m/s).

The A(∞) ν̇_p term is on the left-hand side, with the rigid-body mass; the rigid-body Coriolis
terms m U q, m U r of the body-axis equations cancel the U L ẋ part of ν̇_p exactly (so the
linearised rigid body is M_RB ẍ in the seakeeping frame, whatever the centre of gravity).

In the frequency domain (capytaine's x(t) = Re(X e^{−iω_e t}), s = −iω_e, ω_e the encounter
frequency), with the zero-speed impedance Z(ω) = s A(ω) + B(ω) acting on velocity, (2) is

    F_rad = −(s I − U Lᵀ) [A(ω) + B(ω)/s] (s I + U L) X                                        (3)

(:func:`radiation_impedance`; E of the next paragraph on the momentum of the Lᵀ factor).
Expanded as −[s² A(ω, U) + s B(ω, U)] X this gives exactly the forward-speed coefficients of
Salvesen, Tuck & Faltinsen (1970), their Table 1 without the transom (end) terms, e.g. A₃₅ =
A⁰₃₅ − U B⁰₃₃/ω², B₃₅ = B⁰₃₅ + U A⁰₃₃, A₅₃ = A⁰₅₃ + U B⁰₃₃/ω², B₅₃ = B⁰₅₃ − U A⁰₃₃, A₅₅ = A⁰₅₅ +
U² A⁰₃₃/ω², B₅₅ = B⁰₅₅ + U² B⁰₃₃/ω², and the sway–roll–yaw set (B₂₆ = B⁰₂₆ − U A⁰₂₂, A₆₆ = A⁰₆₆
+ U² A⁰₂₂/ω², …): :func:`speed_corrected_coefficients` returns them and a test checks them term
by term. The time domain (2) realises them without any speed-dependent kernel: K(t) and its
state-space fit stay the zero-speed ones, exact for every U (no per-speed cache, no
interpolation between speeds), and the U²/ω² terms that make A(ω, U) and B(ω, U) unbounded as ω
→ 0 — and their retardation functions ill-defined — never appear: they are the factorisation
(3).

Two planes. The vertical-plane terms (heave–pitch, with roll couplings) are always applied. In
the horizontal plane, the yaw moment −U P_sway is, in steady drift, the Munk moment
−U A₂₂(0) v, which the captive-test manoeuvring derivatives of
:mod:`ship_gym.forces.manoeuvring` already contain in total; with that model on, the horizontal
term would count it twice. ``speed_terms="vertical"`` therefore applies the pitch row only
(what :func:`ship_gym.engine.ship.build_simulator` does when ``manoeuvring=True``); ``"all"``
is the full theory (3); ``"none"`` drops the outer factor (the body-axis zero-speed model).

Excitation
----------
The Froude–Krylov force is integrated over the hull at its true position in the time domain,
so it sees the incident wave's spatial pattern k(ω) at the encounter timing; its linear value is
the database's ``Froude_Krylov_force`` at the **wave** frequency ω. The diffraction force is
the zero-speed database value at the wave frequency ω (the hull sees the wave pattern k(ω); a
look-up at ω_e would impose the pattern k(ω_e) = ω_e²/g, wrong by a factor (ω_e/ω)² — 2.6 in
head seas at Fn 0.25 near the heave resonance), oscillating at ω_e. No forward-speed correction
of the scattered potential is made (STF's U/(iω_e) diffraction terms are left out).

What the theory leaves out
--------------------------
* the steady wave field of the advancing hull and its interaction with the unsteady flow (the
  "m-terms"; the linearisation is about the uniform stream, Neumann–Kelvin-like);
* STF's transom end terms (the S175 has a cruiser stern; a transom hull gets U-terms at the
  stern section not modelled here), the U² terms beyond (3), and the surge added-mass (A₁₁) part
  of the Munk moment (slender-body: A₁₁ ≪ A₃₃);
* the speed dependence of the scattered wave (above);
* τ = U ω_e/g > 1/4: for low frequencies in following seas and high Froude numbers the zero-speed
  Green function misrepresents the radiated waves; strip theory and this linearisation are
  meant for Fn ≲ 0.4 and ω_e not small.

References
----------
Salvesen, N., Tuck, E. O. & Faltinsen, O. (1970), Ship motions and sea loads, *Trans. SNAME*
78, 250–287.
Newman, J. N. (1977), *Marine Hydrodynamics*, MIT Press, §4.13 (Kirchhoff's equations), §6.19.
Fossen, T. I. (2005), A nonlinear unified state-space model for ship maneuvering and control in
a seaway, *Int. J. Bifurcation and Chaos* 15(9), 2717–2746 (the transformation (1)).
Faltinsen, O. M. (1990), *Sea Loads on Ships and Offshore Structures*, CUP, §5 (strip theory).
"""

from __future__ import annotations

from typing import Final, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.conventions import HEAVE, N_DOF, PITCH, SURGE, SWAY, YAW

__all__ = [
    "SPEED_TERMS",
    "SpeedTerms",
    "check_speed_terms",
    "momentum_rows",
    "radiation_impedance",
    "speed_corrected_coefficients",
    "speed_coupling_matrix",
]

SpeedTerms = Literal["all", "vertical", "none"]
SPEED_TERMS: Final[tuple[SpeedTerms, ...]] = ("all", "vertical", "none")

SURGE_FREE: Final[NDArray[np.float64]] = np.where(np.arange(N_DOF) == SURGE, 0.0, 1.0)
"""Diagonal of E: the velocity components whose momentum enters Kirchhoff's moment."""

MOMENT_ROWS: Final[tuple[int, int]] = (PITCH, YAW)
"""Rows that receive U Lᵀ P (eq. 2): the pitch and yaw moments."""

MOMENTUM_SOURCES: Final[tuple[int, int]] = (HEAVE, SWAY)
"""Momentum components they take: P_heave (pitch, sign +1) and P_sway (yaw, sign −1)."""


def check_speed_terms(speed_terms: SpeedTerms | str) -> SpeedTerms:
    """``speed_terms`` if it is one of :data:`SPEED_TERMS`, else a ValueError naming it."""
    if speed_terms not in SPEED_TERMS:
        raise ValueError(f"speed_terms={speed_terms!r}; expected one of {SPEED_TERMS}")
    return speed_terms


def speed_coupling_matrix() -> NDArray[np.float64]:
    """L of eq. (1): ν_p = ẋ + U L x (body-axis perturbation velocity) [-, per unit speed].

    Returns
    -------
    numpy.ndarray
        (6, 6) with L[heave, pitch] = +1 and L[sway, yaw] = −1.
    """
    out = np.zeros((N_DOF, N_DOF))
    out[HEAVE, PITCH] = 1.0
    out[SWAY, YAW] = -1.0
    return out


def outer_coupling(speed_terms: SpeedTerms = "all") -> NDArray[np.float64]:
    """Lᵀ of eq. (2)–(3), restricted to the planes ``speed_terms`` selects (6, 6) [-]."""
    lt = speed_coupling_matrix().T
    terms = check_speed_terms(speed_terms)
    if terms == "none":
        lt[:] = 0.0
    elif terms == "vertical":
        lt[YAW, :] = 0.0
    return lt


def momentum_rows(matrix: ArrayLike, speed_terms: SpeedTerms = "all") -> NDArray[np.float64]:
    """The rows of Lᵀ ``matrix`` that are not zero: (2, m) for the pitch and yaw moments.

    For ``matrix`` = A(∞) (6, 6) or the map from memory states to λ (6, n), the force of
    eq. (2) is ``U * rows @ x`` added to (pitch, yaw) = :data:`MOMENT_ROWS`.

    Parameters
    ----------
    matrix : array_like
        (6, m) map to the six momentum components.
    speed_terms : {"all", "vertical", "none"}
        Planes kept (module docstring); a dropped plane's row is zero.

    Returns
    -------
    numpy.ndarray
        (2, m): +matrix[heave] (pitch row) and −matrix[sway] (yaw row).
    """
    m = np.asarray(matrix, dtype=float)
    if m.ndim != 2 or m.shape[0] != N_DOF:
        raise ValueError(f"matrix must have shape (6, m); got {m.shape}")
    lt = outer_coupling(speed_terms)
    return np.ascontiguousarray(lt[list(MOMENT_ROWS)] @ m)


def _speed_and_frequency(speed: float, omega_e: ArrayLike) -> tuple[float, NDArray]:
    u = float(speed)
    if not np.isfinite(u):
        raise ValueError(f"forward_speed must be finite [m/s]; got {speed!r}")
    w = np.atleast_1d(np.asarray(omega_e, dtype=float))
    if w.ndim != 1 or not np.all(np.isfinite(w)):
        raise ValueError(f"omega_e must be finite encounter frequencies [rad/s]; got {omega_e!r}")
    if u != 0.0 and np.any(np.abs(w) < 1e-9):
        raise ValueError(
            "encounter frequency ω_e = 0 at forward speed: the linear forward-speed theory is "
            "singular there (the ship rides the wave); choose another wave frequency or heading"
        )
    return u, w


def radiation_impedance(
    added_mass: ArrayLike,
    damping: ArrayLike,
    omega_e: ArrayLike,
    forward_speed: float,
    speed_terms: SpeedTerms = "all",
) -> NDArray[np.complex128]:
    """R(ω_e, U) of eq. (3): F_rad = −R X for the displacement amplitude X.

    Parameters
    ----------
    added_mass, damping : array_like
        (n, 6, 6) zero-speed A and B at |ω_e| [kg, …], [kg/s, …] (output, input).
    omega_e : array_like
        (n,) encounter frequencies [rad/s] (either sign; ≠ 0 when U ≠ 0).
    forward_speed : float
        U [m/s].
    speed_terms : {"all", "vertical", "none"}
        Planes of the outer factor (module docstring).

    Returns
    -------
    numpy.ndarray
        (n, 6, 6) complex, capytaine's time convention (s = −iω_e).
    """
    u, w = _speed_and_frequency(forward_speed, omega_e)
    a = np.asarray(added_mass, dtype=float).reshape(-1, N_DOF, N_DOF)
    b = np.asarray(damping, dtype=float).reshape(-1, N_DOF, N_DOF)
    s = (-1j * w)[:, None, None]
    if u == 0.0:
        return s * s * a + s * b
    inner = s * np.eye(N_DOF) + u * speed_coupling_matrix()  # ν_p per unit displacement
    complex_mass = a + b / s
    moment = outer_coupling(speed_terms) @ complex_mass @ (inner * SURGE_FREE[:, None])
    return s * complex_mass @ inner - u * moment


def speed_corrected_coefficients(
    added_mass: ArrayLike,
    damping: ArrayLike,
    omega_e: ArrayLike,
    forward_speed: float,
    speed_terms: SpeedTerms = "all",
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A(ω_e, U), B(ω_e, U) such that R = s² A(ω_e, U) + s B(ω_e, U) (eq. 3, STF Table 1).

    Parameters
    ----------
    added_mass, damping, omega_e, forward_speed, speed_terms
        As :func:`radiation_impedance`.

    Returns
    -------
    added_mass, damping : numpy.ndarray
        (n, 6, 6) real speed-corrected coefficients [kg, …], [kg/s, …] (no end terms).
    """
    u, w = _speed_and_frequency(forward_speed, omega_e)
    a = np.asarray(added_mass, dtype=float).reshape(-1, N_DOF, N_DOF)
    b = np.asarray(damping, dtype=float).reshape(-1, N_DOF, N_DOF)
    if u == 0.0:
        return a.copy(), b.copy()
    lmat, lt = speed_coupling_matrix(), outer_coupling(speed_terms)
    e = np.diag(SURGE_FREE)
    w2 = (w * w)[:, None, None]
    # R = s²A + sB + sU(AL − LᵀAE) + U(BL − LᵀBE) − U² LᵀAL − (U²/s) LᵀBL, s² = −ω_e²
    # (EL = L: the coupling has no surge row)
    a_u = a + (u * (lt @ b @ e - b @ lmat) + u * u * (lt @ a @ lmat)) / w2
    b_u = b + u * (a @ lmat - lt @ a @ e) + u * u * (lt @ b @ lmat) / w2
    return a_u, b_u
