"""Hull manoeuvring forces in sway and yaw: Clarke et al. (1983) derivatives and cross-flow drag.

Which part of the hull's horizontal-plane force comes from where
-----------------------------------------------------------------
The hull force in sway and yaw of manoeuvring theory, −(added mass)·ν̇ + (velocity terms), is
split between three models so that nothing is counted twice:

==============================================  ===========================================
term                                            model
==============================================  ===========================================
ideal-fluid inertia Y_v̇, Y_ṙ, N_v̇, N_ṙ (and     radiation (:mod:`ship_gym.forces.radiation`):
K_v̇, K_ṙ …) — "added mass"                       A(∞) of the BEM on the left-hand side
wave-radiation damping, A(ω) − A(∞)             radiation memory μ(t) (→ 0 for the slow
                                                manoeuvring motions: B₂₂, B₂₆, B₆₆ → 0 as
                                                ω → 0 at zero speed)
rigid-body Coriolis (m u r in sway …)           simulator (C_RB(ν)ν)
speed-dependent circulatory ("lift") and        **this module**: Y_v, Y_r, N_v, N_r
Munk-moment terms, ∝ u                          (Clarke, Gedling & Hine 1983)
viscous cross-flow drag, ∝ |v + x r|(v + x r)   **this module** (strip integral, Hoerner C_D)
roll moment of the hull's lateral force         **this module**: K = −z_H Y
roll damping (incl. Ikeda's hull-lift part)     :mod:`ship_gym.forces.viscous`
rudder, propeller                               their own models
==============================================  ===========================================

The added-mass derivatives of Clarke et al. (Y'_v̇ …) are therefore **not** used: the BEM
supplies them through A(∞). With this model on, the radiation memory applies its forward-speed
(Kirchhoff) moment in the vertical plane only (``speed_terms="vertical"``,
:mod:`ship_gym.hydro.forward_speed`): its horizontal part, −U P_sway, is in steady drift the Munk
moment, which together with the lift-like damping appears once, inside Clarke's captive-test
derivatives — *total* hydrodynamic derivatives (potential + viscous) about amidships.

Linear derivatives (Clarke, Gedling & Hine 1983, their regression eqs.)
-----------------------------------------------------------------------
In the prime system (SNAME 1950): Y' = Y/(½ρL²u²), N' = N/(½ρL³u²), v' = v/u, r' = rL/u, so
that

    Y = ½ρL² |u| Y'_v v + ½ρL³ u Y'_r r,      N = ½ρL³ u N'_v v + ½ρL⁴ |u| N'_r r,         (1)

with L = Lpp and u the instantaneous surge velocity (so that the derivatives follow the speed
loss in a turn; the direct damping terms take |u| so that they stay dissipative astern, where
the regressions are not valid anyway). With T the draught, B the beam and C_B the block
coefficient:

    Y'_v = −π (T/L)² [1 + 0.40 C_B B/T],
    Y'_r = −π (T/L)² [−1/2 + 2.2 B/L − 0.080 B/T],
    N'_v = −π (T/L)² [1/2 + 2.4 T/L],
    N'_r = −π (T/L)² [1/4 + 0.039 B/T − 0.56 B/L].                                     (2)

S175 (L = 175 m, B = 25.4 m, T = 9.5 m, C_B = 0.570): Y'_v = −0.01490, Y'_r = +0.00365,
N'_v = −0.00584, N'_r = −0.00253. Son & Nomoto (1982) give −0.0116, 0.00242, −0.00385, −0.00222
for the same hull at d = 8.5 m, where eq. (2) gives −0.0124, 0.00311, −0.00457, −0.00211.

Cross-flow drag (Faltinsen 1990 §6; Fossen 2011 §6.6)
-----------------------------------------------------
For large drift angles and at low speed the lateral flow separates at the bilges. With the local
lateral (xz-projected) area dA(x) = T(x) dx and the 2-D drag coefficient C_D(x) of the section
of breadth B(x) and draught T(x) (its double-body image has height 2T):

    Y_cf = −½ρ ∫ C_D(x) T(x) |v + x r| (v + x r) dx,
    N_cf = −½ρ ∫ C_D(x) T(x) x |v + x r| (v + x r) dx,                                   (3)

integrated over strips of the immersed hull mesh (:meth:`CrossFlowStrips.from_mesh`) or, without
a mesh, over a rectangular lateral plane L × T. C_D(B/2T) is Hoerner's curve for ship-like
sections (Hoerner 1965, as digitised by Leite et al. 1998): 1.97 for a thin plate (the ends),
≈ 0.75 for the S175 midship (B/2T = 1.34), ≈ 0.56 for very flat sections. Eq. (3) opposes the
local lateral velocity everywhere. At the small drift of straight-line manoeuvres it is
second-order small beside eq. (1); at zero speed it is the only sway/yaw damping besides the
radiation memory.

Roll moment
-----------
The hull's lateral force acts over the draught; it is applied at the centroid z_H of the
immersed lateral area (from the mesh; T/2 without one): K = −z_H (Y + Y_cf). This gives the
outward heel of a steady turn against the centrifugal force at G (Son & Nomoto 1982). No Y_p, K_p
terms: roll damping is :mod:`ship_gym.forces.viscous`'s.

Caveats: Clarke's regressions come from captive tests of conventional hulls (mostly with
rudders fitted); the rudder model adds its own contribution, so a part of the rudder's share of
Y_v and N_r (≈ 10–20 %) may be counted twice. Coupling with heel (Y_φ, N_φ …) and the nonlinear
manoeuvring terms beyond eq. (3) are not modelled.

References
----------
Clarke, D., Gedling, P. & Hine, G. (1983). The application of manoeuvring criteria in hull
design using linear theory. Trans. RINA 125, 45–68.
Hoerner, S.F. (1965). Fluid-Dynamic Drag. Hoerner Fluid Dynamics.
Leite, A.J.P., Aranha, J.A.P., Umeda, C. & de Conti, M.B. (1998). Current forces in tankers and
bifurcation of equilibrium of turret systems: hydrodynamic model and experiments. Applied Ocean
Research 20, 145–156.
Faltinsen, O.M. (1990). Sea Loads on Ships and Offshore Structures. Cambridge Univ. Press.
Fossen, T.I. (2011). Handbook of Marine Craft Hydrodynamics and Motion Control, ch. 6–7.
Son, K.H. & Nomoto, K. (1982). On the coupled motion of steering and rolling of a high-speed
container ship. Naval Arch. & Ocean Eng. 20, 73–83.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, TypedDict, Unpack

import numba as nb
import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.conventions import RHO_SEAWATER
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.typing import FloatArray

if TYPE_CHECKING:
    from ship_gym.hull.hull import Hull
    from ship_gym.hull.mesh import PanelMesh

__all__ = [
    "CrossFlowStrips",
    "HullManoeuvring",
    "LinearDerivatives",
    "clarke_derivatives",
    "hoerner_crossflow_coefficient",
]

_HOERNER_B_2T = np.array(
    [0.0, 0.18, 0.35, 0.45, 0.47, 0.49, 0.56, 0.65, 0.83, 0.99, 1.31, 1.64, 1.86, 2.31, 2.60,
     3.01, 3.45, 3.74, 4.0]
)  # fmt: skip
_HOERNER_CD = np.array(
    [1.966, 1.966, 1.898, 1.787, 1.584, 1.245, 1.084, 0.999, 0.880, 0.828, 0.760, 0.691, 0.657,
     0.631, 0.596, 0.587, 0.586, 0.560, 0.559]
)  # fmt: skip
"""Hoerner's 2-D cross-flow drag coefficient of ship sections vs B/(2T) (Hoerner 1965, digitised
by Leite et al. 1998; the steep drop near B/2T ≈ 0.5 is the change from a sharp-edged to a
round-bilged flow)."""


def _positive(name: str, value: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r}; expected a positive number") from None
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name}={value!r}; expected a finite positive number")
    return v


def hoerner_crossflow_coefficient(
    breadth_over_twice_draught: float | ArrayLike,
) -> float | NDArray[np.float64]:
    """2-D cross-flow drag coefficient C_D of a ship section (Hoerner 1965) [-].

    Parameters
    ----------
    breadth_over_twice_draught : float or array_like
        B/(2T) of the section [-], ≥ 0; held constant beyond the data (B/2T > 4).

    Returns
    -------
    float or numpy.ndarray
        C_D based on the section's draught (lateral area per unit length T) [-].
    """
    r = np.asarray(breadth_over_twice_draught, dtype=float)
    if not np.all(np.isfinite(r) & (r >= 0.0)):
        raise ValueError(
            f"breadth_over_twice_draught={breadth_over_twice_draught!r}; expected finite "
            "values >= 0"
        )
    out = np.interp(r, _HOERNER_B_2T, _HOERNER_CD)
    return float(out) if out.ndim == 0 else out


@dataclass(frozen=True)
class LinearDerivatives:
    """Nondimensional linear sway/yaw derivatives about amidships (prime system, eq. 1).

    Normalisation: Y'_v = Y_v/(½ρL²u), Y'_r = Y_r/(½ρL³u), N'_v = N_v/(½ρL³u),
    N'_r = N_r/(½ρL⁴u), L = Lpp.

    Attributes
    ----------
    Y_v, Y_r, N_v, N_r : float
        Y'_v, Y'_r, N'_v, N'_r [-].
    """

    Y_v: float
    Y_r: float
    N_v: float
    N_r: float

    def __post_init__(self) -> None:
        for name in ("Y_v", "Y_r", "N_v", "N_r"):
            v = getattr(self, name)
            if not math.isfinite(v):
                raise ValueError(f"{name}={v!r}; expected a finite nondimensional derivative")


def clarke_derivatives(
    lpp: float, beam: float, draught: float, block_coefficient: float
) -> LinearDerivatives:
    """Linear sway/yaw derivatives from main particulars, eq. (2) (Clarke, Gedling & Hine 1983).

    Parameters
    ----------
    lpp : float
        Length between perpendiculars L [m].
    beam : float
        Beam B [m].
    draught : float
        Draught T [m].
    block_coefficient : float
        C_B [-], in (0, 1].

    Returns
    -------
    LinearDerivatives
        Y'_v, Y'_r, N'_v, N'_r in the normalisation of :class:`LinearDerivatives`.
    """
    length = _positive("lpp", lpp)
    b = _positive("beam", beam)
    t = _positive("draught", draught)
    cb = _positive("block_coefficient", block_coefficient)
    if cb > 1.0:
        raise ValueError(f"block_coefficient={block_coefficient!r}; expected a value in (0, 1]")
    k = math.pi * (t / length) ** 2
    return LinearDerivatives(
        Y_v=-k * (1.0 + 0.40 * cb * b / t),
        Y_r=-k * (-0.5 + 2.2 * b / length - 0.080 * b / t),
        N_v=-k * (0.5 + 2.4 * t / length),
        N_r=-k * (0.25 + 0.039 * b / t - 0.56 * b / length),
    )


@dataclass(frozen=True)
class CrossFlowStrips:
    """Strips of the hull for the cross-flow drag integral, eq. (3).

    Attributes
    ----------
    x : numpy.ndarray
        (n,) longitudinal position of each strip's lateral-area centroid [m].
    lateral_area : numpy.ndarray
        (n,) immersed lateral (xz-projected) area of each strip, ∫ T(x) dx [m²].
    drag_coefficient : numpy.ndarray
        (n,) Hoerner C_D of each strip [-].
    roll_lever : float
        Depth z_H of the centroid of the whole lateral area below the waterline [m].
    """

    x: NDArray[np.float64]
    lateral_area: NDArray[np.float64]
    drag_coefficient: NDArray[np.float64]
    roll_lever: float

    def __post_init__(self) -> None:
        arrays = []
        for name in ("x", "lateral_area", "drag_coefficient"):
            a = np.array(getattr(self, name), dtype=float)
            if a.ndim != 1 or not np.all(np.isfinite(a)):
                raise ValueError(f"{name} must be a finite 1-D array, got shape {a.shape}")
            a.flags.writeable = False
            object.__setattr__(self, name, a)
            arrays.append(a)
        if not (len(arrays[0]) == len(arrays[1]) == len(arrays[2]) and len(arrays[0]) > 0):
            raise ValueError(
                f"x, lateral_area and drag_coefficient must have one equal, non-zero length; got "
                f"{[len(a) for a in arrays]}"
            )
        if np.any(arrays[1] < 0.0) or np.any(arrays[2] < 0.0):
            raise ValueError("lateral_area and drag_coefficient must be >= 0")
        if not math.isfinite(self.roll_lever):
            raise ValueError(f"roll_lever={self.roll_lever!r}; expected a finite depth [m]")

    @classmethod
    def from_particulars(
        cls, lpp: float, beam: float, draught: float, n_strips: int = 40
    ) -> CrossFlowStrips:
        """Rectangular lateral plane L × T with one C_D(B/2T) (no hull mesh at hand).

        Parameters
        ----------
        lpp, beam, draught : float
            L, B, T [m].
        n_strips : int
            Number of equal strips.
        """
        length = _positive("lpp", lpp)
        b = _positive("beam", beam)
        t = _positive("draught", draught)
        if int(n_strips) != n_strips or n_strips < 1:
            raise ValueError(f"n_strips={n_strips!r}; expected a positive integer")
        n = int(n_strips)
        dx = length / n
        x = -0.5 * length + dx * (np.arange(n, dtype=np.float64) + 0.5)
        cd = float(hoerner_crossflow_coefficient(b / (2.0 * t)))
        return cls(x, np.full(n, t * dx), np.full(n, cd), 0.5 * t)

    @classmethod
    def from_mesh(cls, mesh: PanelMesh, n_strips: int = 50) -> CrossFlowStrips:
        """Strips of an immersed hull mesh (the part below z = 0, open at the waterline).

        Each strip's lateral area is half the |y|-projected area of its panels (both sides);
        its breadth is the z-projected area of its downward-facing panels per unit length, so
        that B/(2T) = A_bottom/(2 A_lateral) needs no strip width.

        Parameters
        ----------
        mesh : PanelMesh
            Immersed hull mesh in the body frame (e.g. ``Hull.immersed_mesh``).
        n_strips : int
            Number of strips of equal length between the mesh's ends.
        """
        if int(n_strips) != n_strips or n_strips < 1:
            raise ValueError(f"n_strips={n_strips!r}; expected a positive integer")
        n = int(n_strips)
        va = np.asarray(mesh.vector_areas)
        c = np.asarray(mesh.centroids)
        if len(va) == 0:
            raise ValueError(f"mesh {mesh.name!r} has no panels; expected an immersed hull mesh")
        lat = 0.5 * np.abs(va[:, 1])
        bottom = np.maximum(va[:, 2], 0.0)
        x0, x1 = float(c[:, 0].min()), float(c[:, 0].max())
        if not x1 > x0:
            raise ValueError(f"mesh {mesh.name!r} has no length; expected an immersed hull mesh")
        edges = np.linspace(x0, x1, n + 1)
        idx = np.clip(np.searchsorted(edges, c[:, 0], side="right") - 1, 0, n - 1)
        # weighted counts are float64 (numpy's stub types every bincount as intp)
        a_lat = np.bincount(idx, weights=lat, minlength=n).astype(np.float64, copy=False)
        a_bot = np.bincount(idx, weights=bottom, minlength=n)
        x_mom = np.bincount(idx, weights=lat * c[:, 0], minlength=n)
        keep = a_lat > 1e-9 * max(float(a_lat.max()), 1e-300)
        x = x_mom[keep] / a_lat[keep]
        ratio = a_bot[keep] / (2.0 * a_lat[keep])
        cd = np.asarray(hoerner_crossflow_coefficient(ratio))
        z_h = float(np.sum(lat * c[:, 2]) / np.sum(lat))
        return cls(x, a_lat[keep], cd, z_h)


class _HullManoeuvringOptions(TypedDict, total=False):
    """The keyword arguments of :class:`HullManoeuvring` that :meth:`~HullManoeuvring.from_hull`
    passes on."""

    derivatives: LinearDerivatives | None
    roll_lever: float | None
    crossflow: bool
    rho: float


# the arguments of manoeuvring_force after ν: c_yv, c_yr, c_nv, c_nr, ½ρ C_D dA, x, the
# cross-flow switch and z_H
ManoeuvringKernelParameters = tuple[float, float, float, float, FloatArray, FloatArray, bool, float]


class HullManoeuvring(ForceModel):
    """Hull sway/yaw manoeuvring forces (force model ``"hull_manoeuvring"``).

    Force = eq. (1) (linear derivatives, Clarke et al. 1983) + eq. (3) (cross-flow drag), with
    the roll moment K = −z_H Y; what is and is not included is tabulated in the module docstring
    (:mod:`ship_gym.forces.manoeuvring`). No surge force, heave, pitch; no states.

    Parameters
    ----------
    lpp, beam, draught : float
        L, B, T [m].
    block_coefficient : float
        C_B [-].
    strips : CrossFlowStrips, optional
        Strips of the cross-flow integral (default: :meth:`CrossFlowStrips.from_particulars`).
    derivatives : LinearDerivatives, optional
        Nondimensional derivatives (default: :func:`clarke_derivatives`).
    roll_lever : float, optional
        z_H [m], depth below the waterline at which the lateral force acts (default: the
        strips' lateral-area centroid); 0 switches the roll moment off.
    crossflow : bool
        Include eq. (3).
    rho : float
        Water density [kg/m³].
    """

    name = "hull_manoeuvring"

    def __init__(
        self,
        lpp: float,
        beam: float,
        draught: float,
        block_coefficient: float,
        *,
        strips: CrossFlowStrips | None = None,
        derivatives: LinearDerivatives | None = None,
        roll_lever: float | None = None,
        crossflow: bool = True,
        rho: float = RHO_SEAWATER,
    ) -> None:
        self.lpp = _positive("lpp", lpp)
        self.beam = _positive("beam", beam)
        self.draught = _positive("draught", draught)
        self.block_coefficient = _positive("block_coefficient", block_coefficient)
        self.rho = _positive("rho", rho)
        self.derivatives = (
            clarke_derivatives(self.lpp, self.beam, self.draught, self.block_coefficient)
            if derivatives is None
            else derivatives
        )
        if not isinstance(self.derivatives, LinearDerivatives):
            raise ValueError(
                f"derivatives={derivatives!r}; expected a LinearDerivatives instance or None"
            )
        self.strips = (
            CrossFlowStrips.from_particulars(self.lpp, self.beam, self.draught)
            if strips is None
            else strips
        )
        if not isinstance(self.strips, CrossFlowStrips):
            raise ValueError(f"strips={strips!r}; expected a CrossFlowStrips instance or None")
        if roll_lever is None:
            self.roll_lever = self.strips.roll_lever
        else:
            self.roll_lever = float(roll_lever)
            if not math.isfinite(self.roll_lever):
                raise ValueError(f"roll_lever={roll_lever!r}; expected a finite depth [m]")
        self.crossflow = bool(crossflow)
        h = 0.5 * self.rho
        d = self.derivatives
        length = self.lpp
        # dimensional coefficients per unit speed: Y = (c_yv |u|) v + (c_yr u) r, …
        self._c_yv = h * length**2 * d.Y_v
        self._c_yr = h * length**3 * d.Y_r
        self._c_nv = h * length**3 * d.N_v
        self._c_nr = h * length**4 * d.N_r
        self._cda = h * self.strips.drag_coefficient * self.strips.lateral_area
        self._x = self.strips.x
        self._cda_c = np.ascontiguousarray(self._cda, dtype=float)
        self._x_c = np.ascontiguousarray(self._x, dtype=float)

    @classmethod
    def from_hull(
        cls,
        hull: Hull,
        *,
        n_strips: int = 50,
        block_coefficient: float | None = None,
        **kwargs: Unpack[_HullManoeuvringOptions],
    ) -> HullManoeuvring:
        """Model for a :class:`~ship_gym.hull.Hull`, with strips from its immersed mesh.

        Parameters
        ----------
        hull : Hull
            The hull (particulars, immersed mesh, ρ).
        n_strips : int
            Number of cross-flow strips.
        block_coefficient : float, optional
            C_B [-]; default ``hull.particulars.reference["Cb"]`` if present, else
            m/(ρ L B T).
        **kwargs
            Further keyword arguments of :class:`HullManoeuvring`.
        """
        p = hull.particulars
        if block_coefficient is None:
            cb = p.reference.get("Cb")
            if cb is None:
                cb = hull.mass.mass / (hull.rho * p.lpp * p.beam * p.draught)
            block_coefficient = float(cb)
        strips = CrossFlowStrips.from_mesh(hull.immersed_mesh, n_strips)
        kwargs.setdefault("rho", hull.rho)
        return cls(
            p.lpp,
            p.beam,
            p.draught,
            block_coefficient,
            strips=strips,
            **kwargs,
        )

    # ------------------------------------------------------------------ parts
    def linear_force(self, nu: ArrayLike) -> tuple[float, float]:
        """(Y, N) of eq. (1) [N, N·m] for body velocities ν = (u, v, w, p, q, r)."""
        nn = np.asarray(nu)
        u, v, r = float(nn[0]), float(nn[1]), float(nn[5])
        au = abs(u)
        return (
            self._c_yv * au * v + self._c_yr * u * r,
            self._c_nv * u * v + self._c_nr * au * r,
        )

    def crossflow_force(self, nu: ArrayLike) -> tuple[float, float]:
        """(Y_cf, N_cf) of eq. (3) [N, N·m] for body velocities ν = (u, v, w, p, q, r)."""
        nn = np.asarray(nu)
        v, r = float(nn[1]), float(nn[5])
        vl = v + self._x * r
        f = self._cda * np.abs(vl) * vl
        return -float(f.sum()), -float(f @ self._x)

    # ------------------------------------------------------------------ ForceModel
    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(0, Y, 0, K, 0, N) about O in body axes [N, N·m]; no states."""
        nu = np.asarray(ctx.nu, dtype=float)
        if nu.shape != (6,) or not np.all(np.isfinite(nu)):
            raise ValueError(f"ctx.nu={ctx.nu!r}; expected a finite (6,) velocity vector")
        force = np.empty(6)
        manoeuvring_force(nu, *self.kernel_parameters(), force)
        return force, np.zeros(0)

    def kernel_parameters(self) -> ManoeuvringKernelParameters:
        """The arguments of :func:`manoeuvring_force` after ν: the dimensional Clarke factors
        (Y_v, Y_r, N_v, N_r scaled by ½ρ and L) [N·s/m, N·s, N·s, N·m·s], the strips' ½ρ C_D
        dA [kg/m] and x [m], the cross-flow switch and z_H [m]."""
        return (
            self._c_yv, self._c_yr, self._c_nv, self._c_nr, self._cda_c, self._x_c,
            bool(self.crossflow), float(self.roll_lever),
        )  # fmt: skip

    def __repr__(self) -> str:
        d = self.derivatives
        return (
            f"HullManoeuvring(L={self.lpp:g} m, B={self.beam:g} m, T={self.draught:g} m, "
            f"C_B={self.block_coefficient:g}; Y'v={d.Y_v:.5f}, Y'r={d.Y_r:.5f}, "
            f"N'v={d.N_v:.5f}, N'r={d.N_r:.5f}; z_H={self.roll_lever:.3g} m, "
            f"{len(self.strips.x)} strips)"
        )


# =============================================================================================
# row kernels (numba; the engine's numpy path and its compiled loop call these)
# =============================================================================================
@nb.njit(cache=True, nogil=True)
def manoeuvring_force(nu, c_yv, c_yr, c_nv, c_nr, cda, x, crossflow, roll_lever, out):
    """HullManoeuvring.evaluate for one ship: eq. (1) + eq. (3), K = −z_H Y; writes out (6,)."""
    u, v, r = nu[0], nu[1], nu[5]
    au = abs(u)
    y = c_yv * au * v + c_yr * u * r
    n = c_nv * u * v + c_nr * au * r
    if crossflow:
        yc = 0.0
        nc = 0.0
        for k in range(x.shape[0]):
            vl = v + x[k] * r
            f = cda[k] * abs(vl) * vl
            yc += f
            nc += f * x[k]
        y += -yc
        n += -nc
    out[0] = 0.0
    out[1] = y
    out[2] = 0.0
    out[3] = -roll_lever * y
    out[4] = 0.0
    out[5] = n


@nb.njit(cache=True, nogil=True, inline="always")
def manoeuvring_row(s, t, q, v, z, zdot, ctx, rec, out):  # pragma: no cover - compiled
    """Row kernel: :func:`manoeuvring_force` with ``rec`` the tuple of
    :meth:`HullManoeuvring.kernel_parameters`."""
    work = ctx.work
    manoeuvring_force(v, rec[0], rec[1], rec[2], rec[3], rec[4], rec[5], rec[6], rec[7], work)
    for i in range(6):
        out[i] += work[i]
