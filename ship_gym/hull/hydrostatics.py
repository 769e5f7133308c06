"""Calm-water hydrostatics by pressure integration over the exactly clipped wetted hull.

The hydrostatic pressure p = ρ g ζ (ζ the depth below the calm free surface, earth frame, z down)
is linear over each triangle of the hull mesh, so after cutting the triangles at the waterline
(:func:`ship_gym.hull.mesh.clip_triangles`) its force and moment are integrated exactly
(:func:`ship_gym.hull.mesh.pressure_resultant`). Displacement and centre of buoyancy follow from
the force and moment; waterplane properties from the projected wetted surface (for a closed hull,
∫_wet n_z f dS = ∫_waterplane f dA for any f(x, y)).

The pose of the ship is given by the position of the body origin O below the calm surface
(``heave`` [m], z down) and the heel φ and trim θ [rad] (zyx Euler angles with ψ = 0).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, root

from ship_gym.hull.hull import Hull
from ship_gym.hull.mesh import PanelMesh, clip_triangles, pressure_resultant
from ship_gym.kinematics import rotation_matrix


@dataclass(frozen=True)
class PressureResult:
    """Hydrostatic resultant at one pose (earth axes).

    Attributes
    ----------
    force : numpy.ndarray
        (3,) buoyancy force [N] (z down, so ``force[2] < 0``).
    moment : numpy.ndarray
        (3,) moment about G [N·m].
    volume : float
        Displaced volume [m³].
    centre_of_buoyancy : numpy.ndarray
        (3,) centre of buoyancy [m], earth frame.
    """

    force: np.ndarray
    moment: np.ndarray
    volume: float
    centre_of_buoyancy: np.ndarray


def _posed_triangles(mesh: PanelMesh, heave: float, heel: float, trim: float) -> np.ndarray:
    tri, _ = mesh.triangles_with_owner
    rot = rotation_matrix(heel, trim, 0.0)
    return tri @ rot.T + np.array([0.0, 0.0, heave])


def wetted_triangles(
    mesh: PanelMesh, heave: float = 0.0, heel: float = 0.0, trim: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """Wetted part of the hull in calm water at a pose.

    Parameters
    ----------
    mesh : PanelMesh
        Closed hull mesh, body frame.
    heave : float
        Depth of the body origin O below the calm surface [m].
    heel, trim : float
        Roll φ and pitch θ [rad].

    Returns
    -------
    triangles, depth : numpy.ndarray
        (n, 3, 3) wet triangles [m] in the earth frame and (n, 3) depths of their vertices [m].
    """
    tri = _posed_triangles(mesh, heave, heel, trim)
    wet, depth, _, _ = clip_triangles(tri, tri[:, :, 2])
    return wet, depth


def pressure_integral(
    hull: Hull, heave: float = 0.0, heel: float = 0.0, trim: float = 0.0
) -> PressureResult:
    """Buoyancy force and its moment about G at a pose in calm water.

    Parameters
    ----------
    hull : Hull
        The hull (mesh to the deck, loading condition, ρ, g).
    heave, heel, trim : float
        Pose: depth of O [m], roll φ [rad], pitch θ [rad].
    """
    tri, depth = wetted_triangles(hull.mesh, heave, heel, trim)
    rot = rotation_matrix(heel, trim, 0.0)
    g_earth = rot @ hull.mass.cog + np.array([0.0, 0.0, heave])
    force, moment = pressure_resultant(tri, hull.rho * hull.g * depth, g_earth)
    volume = -force[2] / (hull.rho * hull.g)
    if volume > 0.0:
        # r_B from M_G = (r_B − r_G) × F with F vertical: horizontal components only
        fz = force[2]
        cb = g_earth + np.array([-moment[1] / fz, moment[0] / fz, 0.0])
        cb[2] = _vertical_centre(tri, depth) if len(tri) else np.nan
    else:
        cb = np.full(3, np.nan)
    return PressureResult(force, moment, float(volume), cb)


def _vertical_centre(tri: np.ndarray, depth: np.ndarray) -> float:
    """z of the centre of buoyancy [m]: ∫ z p n_z dS / ∫ p n_z dS = ∫ z dV / V for p ∝ depth."""
    # ∫_V z dV = ∫_S (z²/2) n_z dS (divergence theorem; the waterplane at z = 0 adds nothing)
    va_z = 0.5 * np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])[:, 2]
    z = depth  # earth z of the vertices equals their depth in calm water
    z2 = (z**2).sum(axis=1) + z[:, 0] * z[:, 1] + z[:, 1] * z[:, 2] + z[:, 0] * z[:, 2]
    moment = np.sum(va_z * z2 / 12.0)  # ∫ z²/2 over a triangle = S (Σzᵢ² + Σ_{i<j} zᵢzⱼ)/12
    volume = np.sum(va_z * z.mean(axis=1))
    return float(moment / volume)


def _quadratic_surface_integrals(tri: np.ndarray) -> dict[str, float]:
    """∫ n_z f dS over triangles for f ∈ {1, x, y, x², y², xy} (edge-midpoint rule, exact)."""
    va_z = 0.5 * np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])[:, 2]
    mids = 0.5 * (tri + np.roll(tri, -1, axis=1))
    x, y = mids[:, :, 0], mids[:, :, 1]
    out = {}
    for key, f in (
        ("1", np.ones_like(x)),
        ("x", x),
        ("y", y),
        ("xx", x * x),
        ("yy", y * y),
        ("xy", x * y),
    ):
        out[key] = float(np.sum(va_z * f.mean(axis=1)))
    return out


@dataclass(frozen=True)
class Hydrostatics:
    """Hydrostatic particulars of a floating position (upright or not), earth-aligned axes.

    Lengths in [m], areas [m²], volume [m³], stiffness in SI units about the body origin O;
    heights (KB, KM, KG) measured from the keel of the design condition.

    Attributes
    ----------
    heave, heel, trim : float
        The pose [m, rad, rad].
    volume : float
        Displaced volume ∇ [m³].
    displacement : float
        ρ∇ [kg].
    centre_of_buoyancy : numpy.ndarray
        (3,) [m] earth frame.
    waterplane_area : float
        A_wp [m²].
    centre_of_flotation : numpy.ndarray
        (2,) x, y of the waterplane centroid [m].
    it, il : float
        Transverse and longitudinal second moments of the waterplane about its centroid [m⁴].
    bmt, bml, kb, gmt, gml : float
        Metacentric radii, KB and metacentric heights [m].
    stiffness : numpy.ndarray
        (6, 6) linear hydrostatic + gravity restoring matrix about O in our frame (z down),
        heave–roll–pitch block (capytaine's formulas rotated to z down; zero elsewhere).
    """

    heave: float
    heel: float
    trim: float
    volume: float
    displacement: float
    centre_of_buoyancy: np.ndarray
    waterplane_area: float
    centre_of_flotation: np.ndarray
    it: float
    il: float
    bmt: float
    bml: float
    kb: float
    gmt: float
    gml: float
    stiffness: np.ndarray


def hydrostatics(
    hull: Hull, heave: float = 0.0, heel: float = 0.0, trim: float = 0.0
) -> Hydrostatics:
    """Hydrostatic particulars at a pose (default: the design waterline, even keel).

    The restoring matrix follows the standard linear expressions (e.g. capytaine's
    ``compute_hydrostatic_stiffness``) written in our z-down frame:
    C33 = ρgA_wp, C34 = ρg∫y dA, C35 = −ρg∫x dA, C44 = ρg(∫y² dA − ∇z_B) + m g z_G,
    C55 = ρg(∫x² dA − ∇z_B) + m g z_G, C45 = −ρg∫xy dA (symmetrised), with waterplane integrals
    taken about O's vertical and z_B, z_G relative to O.
    """
    tri, _ = wetted_triangles(hull.mesh, heave, heel, trim)
    res = pressure_integral(hull, heave, heel, trim)
    wp = _quadratic_surface_integrals(tri)
    rho_g = hull.rho * hull.g
    area = wp["1"]
    xf, yf = wp["x"] / area, wp["y"] / area
    it = wp["yy"] - area * yf**2
    il = wp["xx"] - area * xf**2
    vol = res.volume
    o_earth = np.array([0.0, 0.0, heave])
    rot = rotation_matrix(heel, trim, 0.0)
    zb = res.centre_of_buoyancy[2] - o_earth[2]
    zg = (rot @ hull.mass.cog)[2]
    mg = hull.mass.mass * hull.g
    c = np.zeros((6, 6))
    c[2, 2] = rho_g * area
    c[2, 3] = c[3, 2] = rho_g * wp["y"]
    c[2, 4] = c[4, 2] = -rho_g * wp["x"]
    c[3, 3] = rho_g * (wp["yy"] - vol * zb) + mg * zg
    c[4, 4] = rho_g * (wp["xx"] - vol * zb) + mg * zg
    c[3, 4] = c[4, 3] = -rho_g * wp["xy"]
    t = hull.particulars.draught
    kb = t - (res.centre_of_buoyancy[2] - heave)
    bmt, bml = it / vol, il / vol
    kg = hull.kg
    return Hydrostatics(
        heave=heave,
        heel=heel,
        trim=trim,
        volume=vol,
        displacement=hull.rho * vol,
        centre_of_buoyancy=res.centre_of_buoyancy,
        waterplane_area=area,
        centre_of_flotation=np.array([xf, yf]),
        it=it,
        il=il,
        bmt=bmt,
        bml=bml,
        kb=kb,
        gmt=kb + bmt - kg,
        gml=kb + bml - kg,
        stiffness=c,
    )


@dataclass(frozen=True)
class Equilibrium:
    """Free-floating calm-water position at a given heel.

    Attributes
    ----------
    heave : float
        Sinkage of O below the calm surface [m] (positive: deeper than the design waterline).
    trim : float
        Pitch θ [rad] (positive bow up).
    heel : float
        Imposed roll φ [rad].
    righting_arm : float
        GZ [m] at this heel (positive restoring).
    """

    heave: float
    trim: float
    heel: float
    righting_arm: float


def equilibrium(
    hull: Hull,
    heel: float = 0.0,
    *,
    guess: tuple[float, float] = (0.0, 0.0),
    tol: float = 1e-10,
) -> Equilibrium:
    """Sinkage and trim that balance weight and buoyancy at a fixed heel (free trim).

    Solves F_z(buoyancy) + m g = 0 and M_y(about G) = 0 for (heave, trim) by Powell's hybrid
    method; residuals scaled by m g and m g L.

    Parameters
    ----------
    hull : Hull
        The hull and loading condition.
    heel : float
        Imposed heel φ [rad].
    guess : tuple of float
        Starting (heave [m], trim [rad]).
    tol : float
        Tolerance on the scaled residuals.

    Raises
    ------
    RuntimeError
        When no floating position exists (the hull sinks or the solver fails).
    """
    mg = hull.mass.mass * hull.g
    length = hull.particulars.lpp

    def residual(v: np.ndarray) -> np.ndarray:
        r = pressure_integral(hull, v[0], heel, v[1])
        return np.array([(r.force[2] + mg) / mg, r.moment[1] / (mg * length)])

    # MINPACK's finite-difference step is relative to |x| (absolute only at x = 0): a guess of
    # round-off size (1e-17 m from an upright equilibrium) would give steps of 1e-25 m and a
    # singular Jacobian, so such a guess starts from exactly zero
    start = np.asarray(guess, dtype=float).copy()
    start[np.abs(start) < np.array([1e-9 * hull.particulars.draught, 1e-9])] = 0.0
    sol = root(residual, start, method="hybr", tol=tol)
    res = residual(sol.x)
    if not sol.success and np.max(np.abs(res)) > 1e-6:
        raise RuntimeError(
            f"{hull.name}: no free-floating equilibrium found at heel {np.degrees(heel):.2f} deg "
            f"(residuals {res}); is the mass ({hull.mass.mass:.4g} kg) larger than the closed "
            f"hull can float?"
        )
    heave, trim = float(sol.x[0]), float(sol.x[1])
    r = pressure_integral(hull, heave, heel, trim)
    return Equilibrium(heave, trim, float(heel), float(-r.moment[0] / mg))


@dataclass(frozen=True)
class RightingArmCurve:
    """Calm-water GZ curve at free sinkage and trim.

    Attributes
    ----------
    heel_deg : numpy.ndarray
        Heel angles [deg].
    gz : numpy.ndarray
        Righting arms [m] (positive restoring).
    heave, trim : numpy.ndarray
        Equilibrium sinkage [m] and trim [rad] at each heel.
    vanishing_angle_deg : float
        Angle of vanishing stability [deg] (first down-crossing of GZ after its positive range;
        NaN if GZ stays positive over the range computed).
    max_gz : float
        Largest GZ [m] and ``angle_max_gz_deg`` the heel where it occurs [deg].
    """

    heel_deg: np.ndarray
    gz: np.ndarray
    heave: np.ndarray
    trim: np.ndarray
    vanishing_angle_deg: float
    max_gz: float
    angle_max_gz_deg: float


def righting_arm(
    hull: Hull, heel_deg: np.ndarray | float, *, refine_vanishing: bool = True
) -> RightingArmCurve:
    """Righting arm GZ [m] in calm water at free sinkage and trim, with the vanishing angle.

    Parameters
    ----------
    hull : Hull
        Hull and loading condition.
    heel_deg : array_like
        Heel angles [deg] (starboard down positive); evaluated in increasing order from 0 so
        each equilibrium starts from its neighbour's.
    refine_vanishing : bool
        Locate the angle of vanishing stability by root-finding between grid points.
    """
    heels = np.atleast_1d(np.asarray(heel_deg, dtype=float))
    if not np.all(np.isfinite(heels)) or np.any(np.abs(heels) > 180.0):
        raise ValueError(f"heel angles must be finite and within ±180 deg, got {heel_deg!r}")
    order = np.argsort(np.abs(heels))
    gz = np.empty_like(heels)
    heave = np.empty_like(heels)
    trim = np.empty_like(heels)
    guess = (0.0, 0.0)
    for i in order:
        eq = equilibrium(hull, np.radians(heels[i]), guess=guess)
        gz[i], heave[i], trim[i] = eq.righting_arm, eq.heave, eq.trim
        guess = (eq.heave, eq.trim)
    vanishing = _vanishing_angle(hull, heels, gz, heave, trim, refine_vanishing)
    k = int(np.argmax(gz))
    return RightingArmCurve(heels, gz, heave, trim, vanishing, float(gz[k]), float(heels[k]))


def _vanishing_angle(
    hull: Hull,
    heels: np.ndarray,
    gz: np.ndarray,
    heave: np.ndarray,
    trim: np.ndarray,
    refine: bool,
) -> float:
    pos = heels > 0.0
    h, z = heels[pos], gz[pos]
    order = np.argsort(h)
    h, z = h[order], z[order]
    down = np.flatnonzero((z[:-1] > 0.0) & (z[1:] <= 0.0))
    if down.size == 0:
        return float("nan")
    i = int(down[0])
    if not refine:
        return float(h[i] + (h[i + 1] - h[i]) * z[i] / (z[i] - z[i + 1]))
    idx = np.flatnonzero(pos)[order[i]]
    guess = (float(heave[idx]), float(trim[idx]))

    def f(angle_deg: float) -> float:
        return equilibrium(hull, np.radians(angle_deg), guess=guess).righting_arm

    return float(brentq(f, h[i], h[i + 1], xtol=1e-6))
