"""Mean added resistance in waves: the SNNM semi-empirical method, applied as a surge force.

Linear radiation and diffraction give forces that oscillate about zero: the *mean* (second-order)
longitudinal drift force of a ship in waves — the added resistance R_AW — is absent from the
linear models. This module estimates it with the semi-empirical method of Liu & Papanikolaou
(2016, 2020), the "SNNM" method (SNU, NTUA, NMRI, MARIN joint proposal), adopted for arbitrary
headings by the ITTC (2021) in the speed/power-trial procedure 7.5-04-01-01.1 and the
added-resistance procedure 7.5-02-07-02.2 (STAwave-2 is the ITTC's older, ±45°-from-the-bow
alternative). The method needs only main particulars; it does not use the hydrodynamic database.

Regular waves (amplitude ζ_a, frequency ω, wavelength λ = 2πg/ω², deep water), relative heading
α ∈ [0, π] (α = π head seas, 0 following seas: ship_gym's β folded to [0, π] by port–starboard
symmetry), ship speed U, Fn = U/√(gL):

    R_AW = R_AWR + R_AWM.

Reflection (short waves; Faltinsen et al. 1980 asymptote with empirical corrections), four
waterline segments — bow port/starboard (entrance angle E₁), stern (run angle E₂):

    R_AWR = (2.25/4) ρ g ζ_a² B Σᵢ Rᵢ,
    R₁ = α_T(T) [sin²(E₁ − α) + (2ωU/g)(cos E₁ cos(E₁ − α) − cos α)] (0.87/C_B)^{(1+4√Fn) f(α)}
         for E₁ ≤ α ≤ π,
    R₂ = α_T(T) [sin²(E₁ + α) + (2ωU/g)(cos E₁ cos(E₁ + α) − cos α)] (0.87/C_B)^{(1+4√Fn) f(α)}
         for π − E₁ ≤ α ≤ π,
    R₃ = −α_T(T*) [sin²(E₂ + α) + (2ωU/g)(cos E₂ cos(E₂ + α) − cos α)]   for 0 ≤ α ≤ π − E₂,
    R₄ = −α_T(T*) [sin²(E₂ − α) + (2ωU/g)(cos E₂ cos(E₂ − α) − cos α)]   for 0 ≤ α ≤ E₂,

with f(α) = −cos α for π − E₁ ≤ α ≤ π (else 0), the draught coefficient
α_T(T) = 1 − exp[−4π (T/λ − T/(2.5 L))] for λ/L ≤ 2.5 (else 0), the stern draught
T* = T (4 + √|cos α|)/5 for C_B ≤ 0.75, T (2 + √|cos α|)/3 above, and the waterline angles
E₁ = atan(0.495 B/L_E), E₂ = atan(0.495 B/L_R) (L_E, L_R: lengths of entrance and run, from the
ends of the waterline to where its breadth reaches 99 % of B).

Motion (long waves; heave and pitch radiation, Jinkine–Ferdinande form):

    R_AWM = 4 ρ g ζ_a² (B²/L) ω̄^{b₁} exp[(b₁/d₁)(1 − ω̄^{d₁})] a₁ a₂ a₃,
    ω̄ = 2.142 k_yy^{1/3} √(L/λ) [1 − (0.111/C_B)(ln(B/T) − ln 2.75)] (C_B/0.65)^{0.17}
        × [(−1.377 Fn² + 1.157 Fn)|cos α| + 0.618 (13 + cos 2α)/14],
    a₁ = 60.3 C_B^{1.34} (4 k_yy)² (0.87/C_B)^{−(1+Fn) cos α} (ln(B/T))^{−1} (1 − 2 cos α)/3
         for π/2 ≤ α ≤ π,
    a₂ = 0.0072 + 0.1676 Fn (Fn < 0.12),  Fn^{1.5} exp(−3.5 Fn) (Fn ≥ 0.12),
    a₃ = 1 + 28.7 atan(|T_A − T_F|/L),
    b₁ = 11 (ω̄ < 1), −8.5 (ω̄ ≥ 1),
    d₁ = 566 (L C_B/B)^{−2.66} (ω̄ < 1),  −566 (L/B)^{−2.66} [4 − 125 atan(|T_A − T_F|/L)] (ω̄ ≥ 1),

k_yy the pitch radius of gyration over L. The shape ω̄^{b₁} exp[(b₁/d₁)(1 − ω̄^{d₁})] peaks at
ω̄ = 1 with the value 1, so the peak of σ_AWM = R_AWM/(ρ g ζ_a² B²/L) is 4 a₁ a₂ a₃. (In head
seas a₁ a₂ reduces to 60.3 C_B^{1.34} (4k_yy)² (0.87/C_B)^{1+Fn} Fn^{1.5} e^{−3.5 Fn}/ln(B/T),
and d₁ ≈ ±13–15 for usual hulls: STAwave-2's 60.3 C_B^{1.34} Fn^{1.5} e^{−3.5 Fn} and d₁ = ±14
with the fine-hull factor (0.87/C_B)^{1+Fn} added.)

Following quadrant, 0 ≤ α < π/2 (less certain — read it with care)
-------------------------------------------------------------------
Liu & Papanikolaou (2020) interpolate a₁ and a₂ linearly in α between α = π/2 (the formulas
above) and α = 0, where they depend on the ship speed relative to the group velocity
V_g = g/(2ω) of the wave component. The primary text was not available to us and two public
implementations read it differently; this module uses the reading that satisfies the fore–aft
symmetry of the zero-speed problem exactly (at U = 0 a following wave pushes the ship ahead as
hard as a head wave holds it back, so R_AWM(α = 0) = −R_AWM(α = π)):

* a₁(0) = −A(0) at U = 0, 0 at U = V_g/2, +A(0) at U = V_g, A(Fn_r) beyond, linear in between,
  with A(Fn) = 60.3 C_B^{1.34} (4 k_yy)² (0.87/C_B)^{1+Fn}/ln(B/T) (the head-sea a₁) and
  Fn_r = (U − V_g)/√(gL);
* a₂(0) = a₂(0) = 0.0072 at U = 0 and at U = V_g, a₂(Fn) at U = V_g/2, a₂(Fn_r) beyond.

The S175 runs of this project (head and beam seas) never use this quadrant.

Irregular seas
--------------
With Q(ω, α, U) = R_AW/ζ_a² the quadratic transfer function of the mean force, a sea of spectrum
S(ω) and spreading D(θ) gives the mean

    R̄_AW = 2 ∫∫ Q(ω, β̄ + θ, U) S(ω) D(θ) dθ dω         (:func:`mean_added_resistance`),

and a wave field of discrete components (aⱼ² = 2 S(ωⱼ) Δω) gives R̄_AW = Σⱼ Q(ωⱼ, βⱼ, U) aⱼ²
(:class:`AddedResistance`). Cross-terms between components average to zero (slow drift, the
difference-frequency part, is not modelled).

Force model
-----------
:class:`AddedResistance` applies X = −r(t)² R̄_AW (r the wave field's start-up ramp: the mean force
is quadratic in the amplitude) along the body x axis through O; no sway drift force or yaw drift
moment (the method gives none). R̄_AW is recomputed on accepted steps only (:meth:`commit`) when
the heading ψ has moved by more than ``heading_tolerance_deg`` or the speed by more than
``speed_tolerance``, so the force is piecewise constant in time and every integrator stage of a
step sees the same value. The speed is the instantaneous surge velocity u (``speed="surge"``,
default: R_AW follows the ship as it slows down) or the radiation linearisation speed
(``speed="forward"``). Astern motion uses U = 0.

Overlap with the nonlinear Froude–Krylov model: the linear radiation and diffraction forces of
this project give no mean force, but the Froude–Krylov + hydrostatic force integrated over the
instantaneous wetted hull of a heaving and pitching ship does (the first-order vertical force
rotated by the pitch angle, the relative elevation at the waterline). For the S175 at 10 m/s in
regular head waves (ζ_a = 1 m, surge held) the simulator's wave models alone give σ_AW ≈ 8.8
at λ/L = 1.15 (SNNM: 9.6), 7.6 at λ/L = 1.0 (8.1), 2.0 at 0.8 (4.4), 6.0 at 1.3 (7.4) and ≈ 0 at
0.5 (1.9, all reflection) — ``scripts/roll_stabilisation.py --part rao``, with the forward-speed
linearisation of :mod:`ship_gym.hydro.forward_speed` (before it: 15.5 at λ/L = 1.15). With
that force model on, the SNNM total counts most of the motion part twice;
``components="reflection"`` adds only the short-wave part the Froude–Krylov force lacks (an
approximation too: its mean is ≈ 70–90 % of SNNM's motion part near the peak, less in longer
waves).

Validity
--------
Regression of model tests over C_B ≈ 0.5–0.9 (container ships to tankers and bulk carriers),
Fn ≤ ≈ 0.3, deep water, L ≥ 100 m, even keel or moderate trim. For the S175 (C_B = 0.57,
L/B = 6.9, B/T = 2.67, k_yy = 0.24) at Fn = 0.25 in head seas the peak σ_AW ≈ 9.9 at
λ/L ≈ 1.15 (motion part 9.4 + reflection 0.5; 6.3 at λ/L ≈ 1.0 for Fn = 0.15); see
``tests/forces/test_added_resistance.py`` for the checks against published values and their
tolerances.

References
----------
Faltinsen, O.M., Minsaas, K.J., Liapis, N. & Skjørdal, S.O. (1980). Prediction of resistance and
propulsion of a ship in a seaway. Proc. 13th Symposium on Naval Hydrodynamics, Tokyo, 505–529.
Jinkine, V. & Ferdinande, V. (1974). A method for predicting the added resistance of fast cargo
ships in head waves. International Shipbuilding Progress 21(238), 149–167.
Liu, S. & Papanikolaou, A. (2016). Fast approach to the estimation of the added resistance of
ships in head waves. Ocean Engineering 112, 211–225.
Liu, S. & Papanikolaou, A. (2020). Regression analysis of experimental data for added resistance
in waves of arbitrary heading and development of a semi-empirical formula. Ocean Engineering 206,
107357.
ITTC (2021). Recommended procedures 7.5-02-07-02.2, Prediction of power increase in irregular
waves from model test, and 7.5-04-01-01.1, Preparation, conduct and analysis of speed/power
trials (Rev. 06), annex on the SNNM method.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.conventions import GRAVITY, RHO_SEAWATER, SURGE, YAW, wrap_angle
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.hull.hull import Hull
from ship_gym.numerics.angles import wrap_angle_scalar
from ship_gym.waves.sea_state import IrregularSea
from ship_gym.waves.wave_field import WaveField

__all__ = [
    "AddedResistance",
    "SNNMParticulars",
    "added_resistance_coefficient",
    "added_resistance_qtf",
    "mean_added_resistance",
    "snnm_components",
]

SpeedSource = Literal["surge", "forward"]
Components = Literal["total", "reflection", "motion"]

_TWO_PI = 2.0 * math.pi


def _positive(name: str, value: float, unit: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r}; expected a finite number > 0 [{unit}]") from None
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name}={value!r}; expected a finite number > 0 [{unit}]")
    return v


@dataclass(frozen=True)
class SNNMParticulars:
    """Main particulars used by the SNNM formula.

    Parameters
    ----------
    length : float
        Length between perpendiculars L [m].
    beam : float
        Breadth B [m].
    draught_fore, draught_aft : float
        Draughts T_F, T_A at the perpendiculars [m].
    block_coefficient : float
        C_B on L [-].
    pitch_gyradius : float
        k_yy = r₅₅/L, the pitch radius of gyration over L [-] (usually 0.22–0.27).
    length_entrance, length_run : float
        L_E and L_R [m]: from the fore (aft) end of the waterline to where its breadth first
        reaches 99 % of B.
    """

    length: float
    beam: float
    draught_fore: float
    draught_aft: float
    block_coefficient: float
    pitch_gyradius: float
    length_entrance: float
    length_run: float

    def __post_init__(self) -> None:
        for name, unit in (
            ("length", "m"),
            ("beam", "m"),
            ("draught_fore", "m"),
            ("draught_aft", "m"),
            ("length_entrance", "m"),
            ("length_run", "m"),
        ):
            object.__setattr__(self, name, _positive(name, getattr(self, name), unit))
        cb = _positive("block_coefficient", self.block_coefficient, "-")
        if not cb < 1.0:
            raise ValueError(f"block_coefficient={cb!r}; expected a value in (0, 1)")
        object.__setattr__(self, "block_coefficient", cb)
        kyy = _positive("pitch_gyradius", self.pitch_gyradius, "-")
        if not kyy < 1.0:
            raise ValueError(f"pitch_gyradius={kyy!r}; expected r55/L in (0, 1) (usually ≈ 0.25)")
        object.__setattr__(self, "pitch_gyradius", kyy)
        if self.beam / self.draught <= 1.0:
            raise ValueError(
                f"B/T = {self.beam / self.draught:.4g} must exceed 1 (ln(B/T) divides a1)"
            )

    @property
    def draught(self) -> float:
        """Mean draught T = (T_F + T_A)/2 [m]."""
        return 0.5 * (self.draught_fore + self.draught_aft)

    @property
    def trim_angle(self) -> float:
        """atan(|T_A − T_F|/L) [rad]."""
        return math.atan(abs(self.draught_aft - self.draught_fore) / self.length)

    @property
    def entrance_angle(self) -> float:
        """E₁ = atan(0.495 B/L_E) [rad]."""
        return math.atan(0.495 * self.beam / self.length_entrance)

    @property
    def run_angle(self) -> float:
        """E₂ = atan(0.495 B/L_R) [rad]."""
        return math.atan(0.495 * self.beam / self.length_run)

    @classmethod
    def from_hull(cls, hull: Hull) -> SNNMParticulars:
        """Particulars of a :class:`~ship_gym.hull.hull.Hull` at its design waterline.

        L = L_pp, B and T from the particulars (even keel), C_B = ∇/(L_pp B T) with ∇ from the
        immersed mesh, k_yy from the pitch inertia about G, and L_E, L_R from the half-breadths
        of the immersed mesh's waterline vertices (linear interpolation to 0.99 B/2).
        """
        from ship_gym.hull.hydrostatics import hydrostatics

        if not isinstance(hull, Hull):
            raise ValueError(f"hull must be a Hull; got {type(hull).__name__}")
        p = hull.particulars
        volume = float(hydrostatics(hull).volume)
        inertia = np.asarray(hull.mass.inertia, dtype=float)
        kyy = math.sqrt(inertia[1, 1] / hull.mass.mass) / p.lpp
        l_e, l_r = _entrance_and_run(hull)
        return cls(
            length=p.lpp,
            beam=p.beam,
            draught_fore=p.draught,
            draught_aft=p.draught,
            block_coefficient=volume / (p.lpp * p.beam * p.draught),
            pitch_gyradius=kyy,
            length_entrance=l_e,
            length_run=l_r,
        )


def _entrance_and_run(hull: Hull) -> tuple[float, float]:
    """L_E, L_R [m] from the waterline vertices of the immersed mesh."""
    verts = hull.immersed_mesh.vertices
    on_wl = np.abs(verts[:, 2]) < 1e-6 * hull.particulars.lpp
    x = np.round(verts[on_wl, 0], 9)
    y = np.abs(verts[on_wl, 1])
    xs = np.unique(x)
    if xs.size < 3:
        raise ValueError("the immersed mesh has fewer than 3 waterline stations")
    half = np.array([y[x == v].max() for v in xs])
    target = 0.99 * half.max()
    full = np.flatnonzero(half >= target)
    i_aft, i_fwd = int(full[0]), int(full[-1])

    def crossing(i_in: int, i_out: int) -> float:
        # linear interpolation of the half-breadth between the last full and first fine station
        y0, y1 = half[i_in], half[i_out]
        f = (y0 - target) / (y0 - y1) if y0 != y1 else 0.0
        return float(xs[i_in] + f * (xs[i_out] - xs[i_in]))

    x_fwd = crossing(i_fwd, i_fwd + 1) if i_fwd + 1 < xs.size else float(xs[-1])
    x_aft = crossing(i_aft, i_aft - 1) if i_aft > 0 else float(xs[0])
    l_e = max(float(xs[-1]) - x_fwd, 1e-3 * hull.particulars.lpp)
    l_r = max(x_aft - float(xs[0]), 1e-3 * hull.particulars.lpp)
    return l_e, l_r


def _a2(fn: NDArray) -> NDArray:
    """a₂(Fn) of the head-to-beam quadrant."""
    fn = np.maximum(fn, 0.0)
    return np.where(fn < 0.12, 0.0072 + 0.1676 * fn, fn**1.5 * np.exp(-3.5 * fn))


def _alpha_t(draught: NDArray | float, k: NDArray, length: float) -> NDArray:
    """α_T = 1 − exp[−4π (T/λ − T/(2.5 L))] for λ/L ≤ 2.5, else 0 (T/λ = T k/(2π))."""
    x = draught * k / _TWO_PI - draught / (2.5 * length)
    return np.where(x > 0.0, -np.expm1(-4.0 * math.pi * np.maximum(x, 0.0)), 0.0)


def _fold_heading(beta: ArrayLike) -> NDArray:
    """ship_gym relative heading β (any value) → α ∈ [0, π] (π head seas), port–starboard
    symmetric."""
    b = np.asarray(beta, dtype=float)
    return np.abs(wrap_angle(b))


def snnm_components(
    omega: ArrayLike,
    beta: ArrayLike,
    speed: ArrayLike,
    particulars: SNNMParticulars,
    *,
    rho: float = RHO_SEAWATER,
    g: float = GRAVITY,
) -> tuple[NDArray, NDArray]:
    """Reflection and motion parts of R_AW/ζ_a² (module docstring) [N/m²].

    Parameters
    ----------
    omega : array_like
        Wave (not encounter) frequencies ω ≥ 0 [rad/s].
    beta : array_like
        Relative headings β [rad] (ship_gym: π head seas, 0 following; any value, folded to
        α = |β| ∈ [0, π]).
    speed : array_like
        Ship speed U [m/s] (negative values are taken as 0).
    particulars : SNNMParticulars
        The ship.
    rho, g : float
        Water density [kg/m³] and gravity [m/s²].

    Returns
    -------
    reflection, motion : numpy.ndarray
        R_AWR/ζ_a² and R_AWM/ζ_a² [N/m²], broadcast shape of the inputs.
    """
    if not isinstance(particulars, SNNMParticulars):
        raise ValueError(f"particulars must be SNNMParticulars; got {type(particulars).__name__}")
    rho = _positive("rho", rho, "kg/m^3")
    g = _positive("g", g, "m/s^2")
    w, alpha, u = np.broadcast_arrays(
        np.asarray(omega, dtype=float), _fold_heading(beta), np.asarray(speed, dtype=float)
    )
    if not (np.all(np.isfinite(w)) and np.all(np.isfinite(alpha)) and np.all(np.isfinite(u))):
        raise ValueError("omega, beta and speed must be finite")
    if np.any(w < 0.0):
        raise ValueError("omega must be >= 0 [rad/s] (wave frequencies, not encounter)")
    u = np.maximum(u, 0.0)
    p = particulars
    L, B, T, cb, kyy = p.length, p.beam, p.draught, p.block_coefficient, p.pitch_gyradius
    fn = u / math.sqrt(g * L)
    k = w * w / g
    cos_a = np.cos(alpha)

    # ---- reflection (short waves) ----------------------------------------------------------
    e1, e2 = p.entrance_angle, p.run_angle
    tau = 2.0 * w * u / g
    at_bow = _alpha_t(T, k, L)
    t_stern = T * (
        (4.0 + np.sqrt(np.abs(cos_a))) / 5.0 if cb <= 0.75 else (2.0 + np.sqrt(np.abs(cos_a))) / 3.0
    )
    at_stern = _alpha_t(t_stern, k, L)
    f_alpha = np.where(alpha >= math.pi - e1, -cos_a, 0.0)
    fine = (0.87 / cb) ** ((1.0 + 4.0 * np.sqrt(fn)) * f_alpha)
    r1 = np.where(
        alpha >= e1,
        at_bow
        * (np.sin(e1 - alpha) ** 2 + tau * (math.cos(e1) * np.cos(e1 - alpha) - cos_a))
        * fine,
        0.0,
    )
    r2 = np.where(
        alpha >= math.pi - e1,
        at_bow
        * (np.sin(e1 + alpha) ** 2 + tau * (math.cos(e1) * np.cos(e1 + alpha) - cos_a))
        * fine,
        0.0,
    )
    r3 = np.where(
        alpha <= math.pi - e2,
        -at_stern * (np.sin(e2 + alpha) ** 2 + tau * (math.cos(e2) * np.cos(e2 + alpha) - cos_a)),
        0.0,
    )
    r4 = np.where(
        alpha <= e2,
        -at_stern * (np.sin(e2 - alpha) ** 2 + tau * (math.cos(e2) * np.cos(e2 - alpha) - cos_a)),
        0.0,
    )
    reflection = (2.25 / 4.0) * rho * g * B * (r1 + r2 + r3 + r4)

    # ---- motion (long waves) ---------------------------------------------------------------
    trim = p.trim_angle
    ln_bt = math.log(B / T)
    w_bar = (
        2.142
        * kyy ** (1.0 / 3.0)
        * np.sqrt(k * L / _TWO_PI)
        * (1.0 - (0.111 / cb) * (ln_bt - math.log(2.75)))
        * (cb / 0.65) ** 0.17
        * (
            (-1.377 * fn**2 + 1.157 * fn) * np.abs(cos_a)
            + 0.618 * (13.0 + np.cos(2.0 * alpha)) / 14.0
        )
    )
    low = w_bar < 1.0
    d_low = 566.0 * (L * cb / B) ** -2.66
    d_high = -566.0 * (L / B) ** -2.66 * (4.0 - 125.0 * trim)
    wb_low = np.where(low, w_bar, 0.5)  # placeholders keep the unused branch finite
    wb_high = np.where(low, 2.0, w_bar)
    shape = np.where(
        low,
        wb_low**11.0 * np.exp((11.0 / d_low) * (1.0 - wb_low**d_low)),
        wb_high**-8.5 * np.exp((-8.5 / d_high) * (1.0 - wb_high**d_high)),
    )
    a_head = 60.3 * cb**1.34 * (4.0 * kyy) ** 2 / ln_bt  # a₁ without the speed/heading factors
    a1_hb = a_head * (0.87 / cb) ** (-(1.0 + fn) * cos_a) * (1.0 - 2.0 * cos_a) / 3.0
    a2_hb = _a2(fn)
    # following quadrant: interpolate between α = π/2 and α = 0 (module docstring)
    s = tau  # U/V_g with the group velocity V_g = g/(2ω)
    v_g = g / (2.0 * np.maximum(w, 1e-12))
    fn_r = np.maximum(u - v_g, 0.0) / math.sqrt(g * L)  # Froude number relative to V_g
    a1_zero = a_head * (0.87 / cb)  # head-sea a₁ at Fn = 0
    a1_0 = np.where(
        s <= 1.0,
        a1_zero * (2.0 * np.minimum(s, 1.0) - 1.0),
        a_head * (0.87 / cb) ** (1.0 + fn_r),
    )
    a2_fn = a2_hb
    a2_0 = np.where(
        s <= 0.5,
        0.0072 + (a2_fn - 0.0072) * 2.0 * s,
        np.where(s <= 1.0, a2_fn + (0.0072 - a2_fn) * (2.0 * s - 1.0), _a2(fn_r)),
    )
    x = 2.0 * alpha / math.pi  # 0 at α = 0, 1 at α = π/2
    following = alpha < 0.5 * math.pi
    a1_half = a_head / 3.0
    a1 = np.where(following, a1_0 + x * (a1_half - a1_0), a1_hb)
    a2 = np.where(following, a2_0 + x * (a2_fn - a2_0), a2_hb)
    a3 = 1.0 + 28.7 * trim
    motion = 4.0 * rho * g * B * B / L * shape * a1 * a2 * a3
    return reflection, motion


def added_resistance_qtf(
    omega: ArrayLike,
    beta: ArrayLike,
    speed: ArrayLike,
    particulars: SNNMParticulars,
    *,
    rho: float = RHO_SEAWATER,
    g: float = GRAVITY,
) -> NDArray:
    """Q = R_AW/ζ_a² [N/m²]: the mean added resistance per squared wave amplitude.

    Arguments as :func:`snnm_components`.
    """
    reflection, motion = snnm_components(omega, beta, speed, particulars, rho=rho, g=g)
    return reflection + motion


def added_resistance_coefficient(
    omega: ArrayLike,
    beta: ArrayLike,
    speed: ArrayLike,
    particulars: SNNMParticulars,
    *,
    rho: float = RHO_SEAWATER,
    g: float = GRAVITY,
) -> NDArray:
    """σ_AW = R_AW/(ρ g ζ_a² B²/L) [-], the usual non-dimensional added resistance.

    Arguments as :func:`snnm_components`.
    """
    p = particulars
    q = added_resistance_qtf(omega, beta, speed, p, rho=rho, g=g)
    return q / (rho * g * p.beam**2 / p.length)


def mean_added_resistance(
    sea: IrregularSea,
    beta: float,
    speed: float,
    particulars: SNNMParticulars,
    *,
    rho: float = RHO_SEAWATER,
    n_omega: int = 801,
    n_theta: int = 181,
    omega_range: tuple[float, float] | None = None,
) -> float:
    """Mean added resistance in an irregular sea, R̄_AW = 2 ∫∫ Q S D dθ dω [N].

    Trapezoidal quadrature over the sea's frequency band (``sea.omega_range``, where the
    discretised wave fields live, unless ``omega_range`` is given) and, for a short-crested sea,
    over θ ∈ [−π, π] of the cos-2s spreading.

    Parameters
    ----------
    sea : IrregularSea
        Spectrum (and spreading); its ``heading`` is ignored (``beta`` is the mean relative
        heading).
    beta : float
        Mean relative wave heading β̄ [rad] (π head seas).
    speed : float
        Ship speed U [m/s].
    particulars : SNNMParticulars
        The ship.
    rho : float
        Water density [kg/m³] (g is the sea's).
    n_omega, n_theta : int
        Quadrature points in ω and θ.
    omega_range : tuple of float, optional
        (ω_min, ω_max) [rad/s] of the quadrature.
    """
    if not isinstance(sea, IrregularSea):
        raise ValueError(f"sea must be an IrregularSea; got {type(sea).__name__}")
    lo, hi = sea.omega_range if omega_range is None else omega_range
    if not (0.0 <= lo < hi and math.isfinite(hi)):
        raise ValueError(f"omega_range must satisfy 0 <= lo < hi < inf; got {(lo, hi)!r}")
    if n_omega < 3 or n_theta < 3:
        raise ValueError("n_omega and n_theta must be >= 3")
    w = np.linspace(lo, hi, int(n_omega))
    s_w = sea.spectral_density(w)
    if sea.spreading_s is None:
        q = added_resistance_qtf(w, beta, speed, particulars, rho=rho, g=sea.g)
        return float(2.0 * np.trapezoid(q * s_w, w))
    theta = np.linspace(-math.pi, math.pi, int(n_theta))
    d = sea.spreading(theta)
    q = added_resistance_qtf(
        w[:, None], beta + theta[None, :], speed, particulars, rho=rho, g=sea.g
    )
    inner = np.trapezoid(q * d[None, :], theta, axis=1)
    return float(2.0 * np.trapezoid(inner * s_w, w))


class AddedResistance(ForceModel):
    """Mean added resistance in waves as a surge force X = −r(t)² Σⱼ Q(ωⱼ, βⱼ, U) aⱼ².

    See the module docstring for the method (SNNM, Liu & Papanikolaou 2020 / ITTC 2021), the
    caching and the approximations.

    Parameters
    ----------
    particulars : SNNMParticulars
        The ship (:meth:`SNNMParticulars.from_hull`).
    wave_field : WaveField or None
        The incident field (components aⱼ [m], ωⱼ [rad/s], χⱼ [rad]); None: calm water.
    rho, g : float
        Water density [kg/m³]; gravity [m/s²] (default: the wave field's).
    speed : {"surge", "forward"}
        U from the instantaneous surge velocity ν[0] or from ``ctx.forward_speed``.
    components : {"total", "reflection", "motion"}
        Which part of R_AW to apply (default both). "reflection" leaves out the motion part,
        e.g. where the nonlinear Froude–Krylov force already carries a share of it (module
        docstring); neither choice removes the overlap exactly.
    heading_tolerance_deg : float
        Change of ψ [deg] that triggers a recomputation of R̄_AW on an accepted step.
    speed_tolerance : float
        Change of U [m/s] that triggers a recomputation.
    name : str
        Key in the force breakdown.

    Attributes
    ----------
    mean_resistance : float
        R̄_AW [N] of the last update (ramp not applied).
    """

    def __init__(
        self,
        particulars: SNNMParticulars,
        wave_field: WaveField | None,
        *,
        rho: float = RHO_SEAWATER,
        g: float | None = None,
        speed: SpeedSource = "surge",
        components: Components = "total",
        heading_tolerance_deg: float = 0.5,
        speed_tolerance: float = 0.05,
        name: str = "added_resistance",
    ) -> None:
        if not isinstance(particulars, SNNMParticulars):
            raise ValueError(
                f"particulars must be SNNMParticulars; got {type(particulars).__name__}"
            )
        if wave_field is not None and not isinstance(wave_field, WaveField):
            raise ValueError(
                f"wave_field must be a WaveField or None; got {type(wave_field).__name__}"
            )
        if speed not in ("surge", "forward"):
            raise ValueError(f"speed={speed!r}; expected 'surge' or 'forward'")
        if components not in ("total", "reflection", "motion"):
            raise ValueError(
                f"components={components!r}; expected 'total', 'reflection' or 'motion'"
            )
        tol = float(heading_tolerance_deg)
        if not (math.isfinite(tol) and tol >= 0.0):
            raise ValueError(f"heading_tolerance_deg={heading_tolerance_deg!r}; expected >= 0")
        u_tol = float(speed_tolerance)
        if not (math.isfinite(u_tol) and u_tol >= 0.0):
            raise ValueError(f"speed_tolerance={speed_tolerance!r}; expected >= 0 [m/s]")
        if not isinstance(name, str) or not name:
            raise ValueError(f"name must be a non-empty string; got {name!r}")
        self.particulars = particulars
        self.wave_field = wave_field
        self.rho = _positive("rho", rho, "kg/m^3")
        if g is None:
            g = wave_field.g if wave_field is not None else GRAVITY
        self.g = _positive("g", g, "m/s^2")
        self.speed_source: str = speed
        self.components: str = components
        self.name = name
        self._heading_tol = math.radians(tol)
        self._speed_tol = u_tol
        self._psi_ref: float | None = None
        self._u_ref: float | None = None
        self.mean_resistance: float = 0.0

    @classmethod
    def from_hull(cls, hull: Hull, wave_field: WaveField | None, **kwargs) -> AddedResistance:
        """The model for a hull (:meth:`SNNMParticulars.from_hull`), with its ρ and g."""
        kwargs.setdefault("rho", hull.rho)
        kwargs.setdefault("g", hull.g)
        return cls(SNNMParticulars.from_hull(hull), wave_field, **kwargs)

    def __repr__(self) -> str:
        return (
            f"AddedResistance({self.particulars!r}, {self.wave_field!r}, "
            f"speed={self.speed_source!r}, name={self.name!r})"
        )

    # ------------------------------------------------------------------ physics
    def resistance_at(self, psi: float, speed: float) -> float:
        """R̄_AW = Σⱼ Q(ωⱼ, χⱼ − ψ, U) aⱼ² [N] at heading ψ [rad] and speed U [m/s] (no ramp)."""
        w = self.wave_field
        if w is None or w.n_components == 0:
            return 0.0
        reflection, motion = snnm_components(
            w.omega,
            np.asarray(w.direction) - float(psi),
            float(speed),
            self.particulars,
            rho=self.rho,
            g=self.g,
        )
        if self.components == "reflection":
            q = reflection
        elif self.components == "motion":
            q = motion
        else:
            q = reflection + motion
        return float(q @ (np.asarray(w.amplitude) ** 2))

    def _speed(self, ctx: ForceContext) -> float:
        if self.speed_source == "forward":
            return max(float(ctx.forward_speed), 0.0)
        return max(float(ctx.nu[SURGE]), 0.0)

    def _maybe_update(self, ctx: ForceContext) -> None:
        psi = float(ctx.eta[YAW])
        u = self._speed(ctx)
        if (
            self._psi_ref is None
            or self._u_ref is None
            or abs(u - self._u_ref) > self._speed_tol
            or abs(wrap_angle_scalar(psi - self._psi_ref)) > self._heading_tol
        ):
            self.mean_resistance = self.resistance_at(psi, u)
            self._psi_ref, self._u_ref = psi, u

    # ------------------------------------------------------------------ protocol
    def reset(self, t0: float, ctx: ForceContext) -> None:
        """Compute R̄_AW at the initial heading and speed."""
        self._psi_ref = None
        self._u_ref = None
        self._maybe_update(ctx)

    def commit(self, ctx: ForceContext, states: NDArray) -> None:
        """Recompute R̄_AW if ψ or U moved beyond the tolerances on this accepted step."""
        self._maybe_update(ctx)

    def evaluate(self, ctx: ForceContext, states: NDArray) -> tuple[NDArray, NDArray]:
        """(−r(t)² R̄_AW, 0, 0, 0, 0, 0) [N]; no states."""
        force = np.zeros(6)
        if self._psi_ref is None:  # used without reset (e.g. a bare evaluation)
            self._maybe_update(ctx)
        w = self.wave_field
        if w is None or self.mean_resistance == 0.0:
            return force, np.zeros(0)
        t = float(ctx.t)
        r = 1.0 if t >= w.ramp_time else float(w.ramp(t))
        force[SURGE] = -r * r * self.mean_resistance
        return force, np.zeros(0)
