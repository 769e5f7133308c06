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

Excitation: the scattered flow's momentum
-----------------------------------------
The Froude–Krylov force is integrated over the hull at its true position in the time domain,
so it sees the incident wave's spatial pattern k(ω) at the encounter timing; its linear value is
the database's ``Froude_Krylov_force`` at the **wave** frequency ω. It has no speed term: the
incident flow is not carried by the body. The diffraction force is read from the zero-speed
database at the wave frequency ω (the hull sees the wave pattern k(ω); a look-up at ω_e would
impose the pattern k(ω_e) = ω_e²/g, wrong by a factor (ω_e/ω)² — 2.6 in head seas at Fn 0.25
near the heave resonance) and oscillates at ω_e.

The scattered flow carries momentum too, and Kirchhoff's moment acts on it exactly as on the
radiated flow's. Written as the force of a momentum, F_D = −Ṗ_D, the zero-speed diffraction
force gives P_D = F_D / (iω) per unit amplitude (capytaine's convention), and the excitation at
speed is

    F_exc = F_FK + F_D + U H(ω_e) Lᵀ P_D,      P_D = F_D / (iω) at zero speed.           (4)

The diffraction force and its momentum at speed. In Salvesen, Tuck & Faltinsen's theory the
sectional diffraction force at speed is the sectional complex mass at the encounter frequency,
z(ω_e) = a(ω_e) + i b(ω_e)/ω_e, times the incident flow's normal acceleration in the ship (∝ ω
ω_e): the relative-motion form. The zero-speed BEM force is the same with ω for ω_e. The
package takes the BEM force to speed by the hull's own complex-mass ratio,

    F_D(ω, ω_e) = (ω_e Z(ω_e)) / (ω Z(ω)) · F_D(ω),      P_D = Z(ω_e) / (iω Z(ω)) · F_D(ω),    (6)

with Z = Z₃₃ for surge, heave and pitch and Z = Z₂₂ for sway, roll and yaw
(:func:`complex_mass_table`, :func:`diffraction_at_speed`): exact at zero speed, and the
scattered momentum is then the complex mass at ω_e applied to the incident flow's velocity,
the same complex mass that the radiated momentum of a ship following the wave carries.

This is Salvesen, Tuck & Faltinsen's diffraction speed term (their −U/(iω_e) h₃ on pitch and
+U/(iω_e) h₂ on yaw, h_j their sectional diffraction force at speed, integrated along the hull):
their h_j is the sectional complex mass at ω_e, a + i b/ω_e, times the incident flow's normal
acceleration in the ship (∝ ω ω_e), so U h_j/(iω_e) is U times that complex mass applied to the
incident flow's velocity (∝ ω) — the scattered momentum, which (6) takes from the zero-speed BEM
with the hull's complex-mass ratio. In long waves the two momenta cancel — P + P_D = [A + B/s]
(ν_p − v_incident) → 0 for a ship that follows the wave — so **the speed terms act on the motion
relative to the incident flow**: heave → 1, pitch → the projected wave slope and roll → the beam
wave slope at every heading and speed (tested). Without (4) the radiation moment U P_heave of a
ship heaving with a beam sea pitches it (S175, λ = 1.5 L, Fn 0.3: pitch 0.45 k a; with it 0.03 k
a, VERES strip theory 0.026–0.035 k a at Fn 0.19–0.25). P_D stays bounded as ω_e → 0 (it is
divided by ω, not ω_e).

Low encounter frequency: the steady flow owns the steady momentum
------------------------------------------------------------------
The linearisation is about the uniform stream with the zero-speed Green function; at ω_e → 0
(steady trim or drift, surf-riding, slow quartering-sea encounters) its Kirchhoff moment becomes
the Munk moment of the zero-frequency added mass, U² A₃₃(0) θ in pitch (it takes 18 % / 33 % of
the S175's pitch stiffness at Fn 0.3 / 0.4) and U² A₂₂(0) ψ in yaw. A real hull balances these
by the steady flow's own forces (hull lift, sinkage and trim of the steady wave system; in the
horizontal plane the manoeuvring derivatives hold the total), which this theory does not model.
The moment therefore acts on the momentum through a first-order high-pass

    H(ω_e) = s / (s + ω_c),   s = −iω_e,   ω_c = c √(g/L),  c = 0.25 (default),           (5)

on both momenta (the radiated flow's by two filter states in the time domain, the scattered
flow's per wave component at its encounter frequency): the seakeeping theory keeps the wave
band (|H| ≥ 0.97 and a phase ≤ 14° for ω_e √(L/g) ≥ 1, the S175's heave–pitch band is
ω_e √(L/g) ≈ 2–5) and the steady and slowly varying part (|H| = 1/√2 at ω_e = ω_c, 0 at ω_e =
0) is left to the steady-flow models — the two-time-scale split of the unified manoeuvring–
seakeeping models (Bailey, Price & Temarel 1997; Fossen 2005). c = 0 gives STF's terms at every
frequency. The frequency-domain solver applies the same H, so time and frequency domain still
agree exactly in the linear limit.

What the theory leaves out
--------------------------
* the steady wave field of the advancing hull and its interaction with the unsteady flow (the
  "m-terms"; the linearisation is about the uniform stream, Neumann–Kelvin-like);
* STF's transom end terms (the S175 has a cruiser stern; a transom hull gets U-terms at the
  stern section not modelled here), the U² terms beyond (3), and the surge added-mass (A₁₁) part
  of the Munk moment (slender-body: A₁₁ ≪ A₃₃);
* the speed dependence of the scattered wave's complex mass (P_D is taken at ω, STF's at ω_e;
  the two agree in long waves, where the cancellation matters);
* the steady and slowly varying flow (5): below ω_c the Kirchhoff moment fades out and the
  steady-flow forces are those of the other models (hydrostatics at the actual attitude, the
  manoeuvring derivatives); surf-riding and broaching are governed by the nonlinear
  Froude–Krylov force, resistance and thrust, not by these terms;
* the zero-speed Green function at τ = U ω_e/g > 1/4: the radiated waves' pattern changes
  (no upstream waves), which strip theory ignores as well; the package's head-sea validation
  (τ 0.4–1.5) shows the resulting coefficients are still usable for motions (tests against
  strip theory and model tests).

References
----------
Salvesen, N., Tuck, E. O. & Faltinsen, O. (1970), Ship motions and sea loads, *Trans. SNAME*
78, 250–287.
Newman, J. N. (1977), *Marine Hydrodynamics*, MIT Press, §4.13 (Kirchhoff's equations), §6.19.
Fossen, T. I. (2005), A nonlinear unified state-space model for ship maneuvering and control in
a seaway, *Int. J. Bifurcation and Chaos* 15(9), 2717–2746 (the transformation (1)).
Faltinsen, O. M. (1990), *Sea Loads on Ships and Offshore Structures*, CUP, §5 (strip theory).
Bailey, P. A., Price, W. G. & Temarel, P. (1997), A unified mathematical model describing the
manoeuvring of a ship travelling in a seaway, *Trans. RINA* 140, 131–149.
"""

from __future__ import annotations

from typing import Final, Literal

import numba as nb
import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.conventions import HEAVE, N_DOF, PITCH, SURGE, SWAY, YAW

__all__ = [
    "CUTOFF_FRACTION",
    "SPEED_TERMS",
    "SpeedTerms",
    "check_speed_cutoff",
    "check_speed_terms",
    "complex_mass_table",
    "default_speed_cutoff",
    "diffraction_at_speed",
    "low_frequency_factor",
    "momentum_coefficients",
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


CUTOFF_FRACTION: Final[float] = 0.25
"""c of eq. (5): the Kirchhoff moment's high-pass corner ω_c = c √(g/L) [-]."""


def default_speed_cutoff(length: float, g: float) -> float:
    """ω_c = :data:`CUTOFF_FRACTION` √(g/L) of eq. (5) [rad/s] for a hull of length L [m]."""
    length, g = float(length), float(g)
    if not (np.isfinite(length) and length > 0.0 and np.isfinite(g) and g > 0.0):
        raise ValueError(f"length {length!r} m and g {g!r} m/s² must be positive and finite")
    return CUTOFF_FRACTION * float(np.sqrt(g / length))


def check_speed_cutoff(cutoff: float, name: str = "speed_cutoff") -> float:
    """``cutoff`` [rad/s] as a float if finite and ≥ 0, else a ValueError naming ``name``."""
    try:
        value = float(cutoff)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={cutoff!r}; expected a frequency ≥ 0 [rad/s]") from None
    if not (np.isfinite(value) and value >= 0.0):
        raise ValueError(f"{name}={cutoff!r}; expected a finite frequency ≥ 0 [rad/s]")
    return value


def low_frequency_factor(omega_e: ArrayLike, cutoff: float) -> NDArray[np.complex128]:
    """H(ω_e) = s/(s + ω_c), s = −iω_e, of eq. (5) [-] (1 where ω_c = 0).

    Parameters
    ----------
    omega_e : array_like
        Signed encounter frequencies [rad/s] (H(−ω_e) = conj H(ω_e): a real filter).
    cutoff : float
        ω_c [rad/s] (0: no filter).
    """
    w = np.asarray(omega_e, dtype=float)
    c = check_speed_cutoff(cutoff, "cutoff")
    if c == 0.0:
        return np.ones(w.shape, dtype=complex)
    s = -1j * w
    return s / (s + c)


def momentum_coefficients(speed_terms: SpeedTerms = "all") -> tuple[float, float]:
    """(Lᵀ[pitch, heave], Lᵀ[yaw, sway]) of eq. (2) in the planes ``speed_terms`` keeps: the
    factors of the pitch moment on P_heave (+1) and of the yaw moment on P_sway (−1), 0 for a
    dropped plane."""
    lt = outer_coupling(speed_terms)
    return float(lt[PITCH, HEAVE]), float(lt[YAW, SWAY])


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
    cutoff: float = 0.0,
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
    cutoff : float, optional
        ω_c [rad/s] of the moment's high-pass H(ω_e) (eq. 5); 0: STF's terms at every ω_e.

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
    return s * complex_mass @ inner - u * low_frequency_factor(w, cutoff)[:, None, None] * moment


def speed_corrected_coefficients(
    added_mass: ArrayLike,
    damping: ArrayLike,
    omega_e: ArrayLike,
    forward_speed: float,
    speed_terms: SpeedTerms = "all",
    cutoff: float = 0.0,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A(ω_e, U), B(ω_e, U) such that R = s² A(ω_e, U) + s B(ω_e, U) (eq. 3, STF Table 1).

    Parameters
    ----------
    added_mass, damping, omega_e, forward_speed, speed_terms, cutoff
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
    if check_speed_cutoff(cutoff, "cutoff") > 0.0:
        # R = s² A(U) + s B(U) with s = −iω_e: A(U) = −Re R/ω_e², B(U) = −Im R/ω_e
        r = radiation_impedance(a, b, w, u, speed_terms, cutoff)
        return -r.real / (w * w)[:, None, None], -r.imag / w[:, None, None]
    lmat, lt = speed_coupling_matrix(), outer_coupling(speed_terms)
    e = np.diag(SURGE_FREE)
    w2 = (w * w)[:, None, None]
    # R = s²A + sB + sU(AL − LᵀAE) + U(BL − LᵀBE) − U² LᵀAL − (U²/s) LᵀBL, s² = −ω_e²
    # (EL = L: the coupling has no surge row)
    a_u = a + (u * (lt @ b @ e - b @ lmat) + u * u * (lt @ a @ lmat)) / w2
    b_u = b + u * (a @ lmat - lt @ a @ e) + u * u * (lt @ b @ lmat) / w2
    return a_u, b_u


# ------------------------------------------------------------------ relative-motion diffraction
def complex_mass_table(
    omega: ArrayLike,
    added_mass: ArrayLike,
    damping: ArrayLike,
    added_mass_zero: ArrayLike | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
    """The heave and sway complex masses Z(ω) = A(ω) + i B(ω)/ω of eq. (6) on a grid.

    Parameters
    ----------
    omega : array_like
        (n,) finite database frequencies [rad/s], increasing.
    added_mass, damping : array_like
        (n, 6, 6) zero-speed A [kg, …] and B [kg/s, …].
    added_mass_zero : array_like, optional
        (6, 6) A(0): prepended at ω = 0 with B/ω = 0.

    Returns
    -------
    grid : numpy.ndarray
        (m,) frequencies [rad/s].
    table : numpy.ndarray
        (2, m) complex: Z₃₃ (heave) and Z₂₂ (sway) [kg].
    """
    w = np.asarray(omega, dtype=float)
    a = np.asarray(added_mass, dtype=float)
    b = np.asarray(damping, dtype=float)
    rows = [
        a[:, HEAVE, HEAVE] + 1j * b[:, HEAVE, HEAVE] / w,
        a[:, SWAY, SWAY] + 1j * b[:, SWAY, SWAY] / w,
    ]
    grid = w
    if added_mass_zero is not None:
        a0 = np.asarray(added_mass_zero, dtype=float)
        grid = np.concatenate([[0.0], w])
        rows = [
            np.concatenate([[a0[HEAVE, HEAVE]], rows[0]]),
            np.concatenate([[a0[SWAY, SWAY]], rows[1]]),
        ]
    return np.ascontiguousarray(grid), np.ascontiguousarray(np.array(rows, dtype=complex))


@nb.njit(cache=True, nogil=True)
def complex_mass_at(w, grid, table, row):  # pragma: no cover - compiled
    """Z(w) of ``table[row]`` (:func:`complex_mass_table`), linear in |w| and clamped at the
    grid's ends; conj for w < 0 (B/ω is odd in ω)."""
    aw = abs(w)
    n = grid.shape[0]
    if aw <= grid[0]:
        z = table[row, 0]
    elif aw >= grid[n - 1]:
        z = table[row, n - 1]
    else:
        i = min(max(np.searchsorted(grid, aw, side="right") - 1, 0), n - 2)
        f = (aw - grid[i]) / (grid[i + 1] - grid[i])
        z = (1.0 - f) * table[row, i] + f * table[row, i + 1]
    return z.conjugate() if w < 0.0 else z


@nb.njit(cache=True, nogil=True)
def speed_correct_element(w_wave, w_enc, kirchhoff, grid, table, out, j):  # pragma: no cover
    """Take the zero-speed diffraction force out[j, :6] (at the wave frequency) to speed by
    eq. (6) and write the scattered momentum's moment factors (eq. 4–5) in out[j, 6:8].

    ``kirchhoff`` = (Lᵀ[pitch, heave], Lᵀ[yaw, sway], ω_c, enabled); ``grid``, ``table`` from
    :func:`complex_mass_table`. At zero speed (w_enc == w_wave) X_D is left bit for bit; not
    enabled (0), X_D is left as it is and the moment factors are zero.
    """
    if not (kirchhoff[3] > 0.0 and w_wave > 0.0):
        out[j, 6] = 0.0j
        out[j, 7] = 0.0j
        return
    filt = 1.0 + 0.0j
    cutoff = kirchhoff[2]
    if cutoff > 0.0:
        s = -1j * w_enc
        filt = s / (s + cutoff)
    x_heave = out[j, HEAVE]
    x_sway = out[j, SWAY]
    ratio_v = 1.0 + 0.0j  # Z(ω_e)/Z(ω), vertical plane (heave) and horizontal plane (sway)
    ratio_h = 1.0 + 0.0j
    if w_enc != w_wave:
        z0 = complex_mass_at(w_wave, grid, table, 0)
        if z0 != 0.0:
            ratio_v = complex_mass_at(w_enc, grid, table, 0) / z0
        z0 = complex_mass_at(w_wave, grid, table, 1)
        if z0 != 0.0:
            ratio_h = complex_mass_at(w_enc, grid, table, 1) / z0
        for o in range(6):
            vertical = o == 0 or o == 2 or o == 4
            out[j, o] = out[j, o] * (w_enc / w_wave) * (ratio_v if vertical else ratio_h)
    # P_D = X_D(ω) Z(ω_e) / (iω Z(ω)): bounded as ω_e → 0
    out[j, 6] = kirchhoff[0] * x_heave * ratio_v / (1j * w_wave) * filt
    out[j, 7] = kirchhoff[1] * x_sway * ratio_h / (1j * w_wave) * filt


def diffraction_at_speed(
    diffraction_force: ArrayLike,
    omega: ArrayLike,
    omega_e: ArrayLike,
    forward_speed: float,
    complex_mass: tuple[NDArray[np.float64], NDArray[np.complex128]],
    speed_terms: SpeedTerms = "all",
    cutoff: float = 0.0,
) -> NDArray[np.complex128]:
    """The diffraction force at speed with its Kirchhoff moment, eq. (4) and (6) [N/m, N·m/m].

    Parameters
    ----------
    diffraction_force : array_like
        (n, 6) zero-speed F_D(ω, β) per unit amplitude (capytaine's time convention).
    omega, omega_e : array_like
        (n,) wave and encounter frequencies [rad/s].
    forward_speed : float
        U [m/s].
    complex_mass : tuple
        (grid, table) of :func:`complex_mass_table`.
    speed_terms, cutoff
        As :func:`radiation_impedance`.

    Returns
    -------
    numpy.ndarray
        (n, 6) complex: (ω_e Z(ω_e))/(ω Z(ω)) F_D + U H Lᵀ P_D, P_D = F_D Z(ω_e)/(iω Z(ω)).
    """
    f = np.asarray(diffraction_force, dtype=complex).reshape(-1, N_DOF)
    u, w_e = _speed_and_frequency(forward_speed, omega_e)
    w = np.asarray(omega, dtype=float).reshape(-1)
    if w.shape[0] != f.shape[0] or np.any(~(w > 0.0)):
        raise ValueError(f"omega must hold {f.shape[0]} wave frequencies > 0 [rad/s]; got {w}")
    pitch, yaw = momentum_coefficients(speed_terms)
    kirchhoff = np.array([pitch, yaw, check_speed_cutoff(cutoff, "cutoff"), 1.0])
    grid, table = complex_mass
    work = np.zeros((f.shape[0], N_DOF + 2), dtype=complex)
    work[:, :N_DOF] = f
    w_enc = w_e if u != 0.0 else w
    for j in range(f.shape[0]):
        speed_correct_element(w[j], w_enc[j], kirchhoff, grid, table, work, j)
    out = work[:, :N_DOF].copy()
    out[:, PITCH] += u * work[:, N_DOF]
    out[:, YAW] += u * work[:, N_DOF + 1]
    return out
