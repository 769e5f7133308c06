"""Hulls of the library: the S175 container ship and canonical hulls with closed-form checks.

All hulls are in the body frame of :mod:`ship_gym.conventions` (x forward, y starboard, z down,
origin amidships on the design waterline) and closed up to a deck.
"""

from __future__ import annotations

from collections.abc import Callable
from importlib import resources
from typing import Any

import numpy as np

from ship_gym.conventions import GRAVITY, RHO_SEAWATER
from ship_gym.hull.hull import Hull, Particulars
from ship_gym.hull.mass import MassProperties
from ship_gym.hull.mesh import PanelMesh, mesh_from_polygons
from ship_gym.hull.offsets import Station, hull_mesh_from_stations, read_offsets_csv

S175_REFERENCE = {
    "displacement_t": 24589.0,
    "displacement_shipx_t": 24609.6,
    "KB_m": 5.207,
    "KG_m": 9.55,
    "LCG_aft_of_midship_m": 2.55,
    "GMt_m": 0.996,
    "GMl_m": 204.4,
    "Cb": 0.570,
    "Cw": 0.704,
    "Cm": 0.967,
    "source": "ShipX/VERES S175 data check, Marine Systems Simulator (Fossen), MIT licence",
}


def s175(
    *,
    n_sections: int = 60,
    n_below: int = 12,
    n_above: int = 6,
    n_deck: int = 4,
    displacement_t: float = 24589.0,
    kg: float = 9.55,
    lcg: float = -2.55,
    radii_of_gyration: tuple[float, float, float] = (8.331, 42.0, 42.0),
    rho: float = RHO_SEAWATER,
    g: float = GRAVITY,
) -> Hull:
    """The ITTC S175 container ship, meshed to the deck (D = 15.4 m) from its offsets.

    Parameters
    ----------
    n_sections, n_below, n_above, n_deck : int
        Mesh resolution: sections along the hull, panels per side below/above the waterline,
        panels across the deck (default 2400 panels, 1440 immersed).
    displacement_t : float
        Mass of the loading condition [t].
    kg : float
        Height of G above the keel [m].
    lcg : float
        Longitudinal position of G [m], positive forward of amidships (−2.55 = 2.55 m aft).
    radii_of_gyration : tuple of float
        r44, r55, r66 about G [m].
    rho, g : float
        Water density [kg/m³] and gravity [m/s²].
    """
    return _offsets_hull(
        "s175",
        read_offsets_csv(),
        Particulars(175.0, 25.4, 9.5, 15.4, dict(S175_REFERENCE)),
        dict(n_sections=n_sections, n_below=n_below, n_above=n_above, n_deck=n_deck),
        (displacement_t, kg, lcg, radii_of_gyration),
        rho,
        g,
    )


def _offsets_hull(
    name: str,
    stations: list[Station],
    particulars: Particulars,
    resolution: dict[str, int],
    loading: tuple[float, float, float, tuple[float, float, float]],
    rho: float,
    g: float,
) -> Hull:
    """A hull meshed from offsets to its deck, with a loading (displacement [t], KG [m], LCG [m],
    radii of gyration [m])."""
    displacement_t, kg, lcg, radii = loading
    mesh = hull_mesh_from_stations(
        stations,
        draught=particulars.draught,
        depth=particulars.depth,
        name=name,
        **resolution,
    )
    mass = MassProperties.from_radii_of_gyration(
        displacement_t * 1e3, np.array([lcg, 0.0, particulars.draught - kg]), radii
    )
    return Hull(name, mesh, mass, particulars, rho, g)


DTMB5415_REFERENCE = {
    "Lpp_m": 142.0,
    "Lwl_m": 142.18,
    "Bwl_m": 19.06,
    "T_m": 6.15,
    "volume_m3": 8424.4,
    "wetted_surface_m2": 2972.6,
    "Cb": 0.507,
    "Cm": 0.821,
    "LCB_fwd_of_midship_m": -0.00683 * 142.0,
    "LCG_fwd_of_midship_m": -0.652,
    "GMt_m": 1.95,
    "kxx_over_B": 0.37,
    "kzz_over_Lpp": 0.25,
    "service_speed_kn": 18.0,
    "max_speed_kn": 30.0,
    "Fn_design": 0.28,
    "source": "SIMMAN 2014 workshop, US Navy combatant DTMB 5415, geometry and conditions "
    "(simman2014.dk); hull: Gothenburg 2010 IGES of mathLab/WaveBEMapp-DTMB-5415 (MIT)",
}


def dtmb5415(
    *,
    n_sections: int = 60,
    n_below: int = 12,
    n_above: int = 6,
    n_deck: int = 4,
    n_end: int = 8,
    depth: float = 12.5,
    displacement_t: float = 8635.0,
    kg: float = 7.555,
    lcg: float = -0.652,
    radii_of_gyration: tuple[float, float, float] = (7.05, 35.5, 35.5),
    rho: float = RHO_SEAWATER,
    g: float = GRAVITY,
) -> Hull:
    """The DTMB 5415 US Navy surface combatant (bare hull with sonar dome), meshed to the deck.

    The ITTC/SIMMAN benchmark of a fast displacement ship (Lpp = 142 m, design Froude numbers
    0.28–0.41, service speeds 18 and 30 kn). Offsets: ``ship_gym/data/dtmb5415/README.md``.

    Parameters
    ----------
    n_sections, n_below, n_above, n_deck, n_end : int
        Mesh resolution: sections along the hull, panels per side below/above the waterline,
        panels across the deck and across each end plate row (the 15 m wide transom is
        immersed: split, its panels stay below the ship's largest).
    depth : float
        Deck height above the baseline [m]; not part of the benchmark data (the hull surface
        ends 2.5–10 m above the waterline): an assumed flat deck, wall-sided above the offsets.
    displacement_t : float
        Mass of the loading condition [t] (SIMMAN volume 8424.4 m³ × 1.025 t/m³).
    kg : float
        Height of G above the keel [m]: 7.555 gives the SIMMAN GM = 1.95 m on this mesh.
    lcg : float
        Longitudinal position of G [m], positive forward of amidships (SIMMAN: −0.652 m).
    radii_of_gyration : tuple of float
        r44, r55, r66 about G [m]: 0.37 Bwl and 0.25 Lpp (SIMMAN kxx/B, kzz/Lpp; kyy = kzz).
    rho, g : float
        Water density [kg/m³] and gravity [m/s²].
    """
    path = resources.files("ship_gym.data").joinpath("dtmb5415/offsets.csv")
    return _offsets_hull(
        "dtmb5415",
        read_offsets_csv(str(path)),
        Particulars(142.0, 19.06, 6.15, depth, dict(DTMB5415_REFERENCE)),
        dict(n_sections=n_sections, n_below=n_below, n_above=n_above, n_deck=n_deck, n_end=n_end),
        (displacement_t, kg, lcg, radii_of_gyration),
        rho,
        g,
    )


def box_mesh(
    length: float, beam: float, height: float, z_top: float, n: tuple[int, int, int]
) -> PanelMesh:
    """Closed box mesh centred on x = y = 0, spanning z ∈ [z_top, z_top + height] (z down).

    Parameters
    ----------
    length, beam, height : float
        Box dimensions [m].
    z_top : float
        z of the top face [m] (negative above the waterline).
    n : tuple of int
        Panels along x, y and z.
    """
    nx, ny, nz = n
    xs = np.linspace(-length / 2, length / 2, nx + 1)
    ys = np.linspace(-beam / 2, beam / 2, ny + 1)
    zs = np.linspace(z_top, z_top + height, nz + 1)
    verts: list[np.ndarray] = []
    polys: list[list[int]] = []

    def grid(origin: np.ndarray, du: np.ndarray, dv: np.ndarray, us, vs) -> None:
        base = sum(len(v) for v in verts)
        pts = origin + us[:, None, None] * du + vs[None, :, None] * dv
        verts.append(pts.reshape(-1, 3))
        nv = len(vs)
        for i in range(len(us) - 1):
            for j in range(len(vs) - 1):
                a = base + i * nv + j
                polys.append([a, a + nv, a + nv + 1, a + 1])

    ex, ey, ez = np.eye(3)
    x0, y0 = -length / 2, -beam / 2
    # each face parametrised (u, v) so that du × dv points outward
    grid(np.array([x0, y0, z_top + height]), ex, ey, xs - x0, ys - y0)  # bottom (+z)
    grid(np.array([x0, y0, z_top]), ey, ex, ys - y0, xs - x0)  # deck (−z)
    grid(np.array([x0, -y0, z_top]), ez, ex, zs - z_top, xs - x0)  # starboard (+y)
    grid(np.array([x0, y0, z_top]), ex, ez, xs - x0, zs - z_top)  # port (−y)
    grid(np.array([-x0, y0, z_top]), ey, ez, ys - y0, zs - z_top)  # bow (+x)
    grid(np.array([x0, y0, z_top]), ez, ey, zs - z_top, ys - y0)  # stern (−x)
    return mesh_from_polygons(np.vstack(verts), polys, name="box", merge_tolerance=1e-9 * length)


def box_barge(
    *,
    length: float = 100.0,
    beam: float = 20.0,
    draught: float = 5.0,
    depth: float = 10.0,
    kg: float = 5.0,
    panel_size: float = 2.0,
    rho: float = RHO_SEAWATER,
    g: float = GRAVITY,
) -> Hull:
    """A rectangular barge floating at even keel (GM = T/2 + B²/(12T) − KG).

    Parameters
    ----------
    length, beam, draught, depth : float
        Dimensions [m].
    kg : float
        Height of G above the keel [m].
    panel_size : float
        Target panel edge length [m]; the draught is always a mesh line.
    """
    if not 0.0 < draught < depth:
        raise ValueError(f"need 0 < draught < depth, got draught={draught}, depth={depth}")
    nx = max(2, round(length / panel_size))
    ny = max(2, round(beam / panel_size))
    n_below = max(1, round(draught / panel_size))
    n_above = max(1, round((depth - draught) / panel_size))
    # two stacked boxes share the waterline so that it is a mesh line
    below = box_mesh(length, beam, draught, 0.0, (nx, ny, n_below))
    above = box_mesh(length, beam, depth - draught, draught - depth, (nx, ny, n_above))
    mesh = _join_at_waterline(below, above, "box_barge")
    volume = length * beam * draught
    mass = MassProperties.from_radii_of_gyration(
        rho * volume,
        np.array([0.0, 0.0, draught - kg]),
        (0.35 * beam, 0.25 * length, 0.25 * length),
    )
    gm = draught / 2 + beam**2 / (12 * draught) - kg
    ref = {
        "volume_m3": volume,
        "KB_m": draught / 2,
        "GMt_m": gm,
        "BMl_m": length**2 / (12 * draught),
    }
    return Hull("box_barge", mesh, mass, Particulars(length, beam, draught, depth, ref), rho, g)


def _join_at_waterline(below: PanelMesh, above: PanelMesh, name: str) -> PanelMesh:
    """Union of two closed meshes that touch along z = 0, dropping the shared face panels."""
    polys = []
    verts = np.vstack([below.vertices, above.vertices])
    for mesh, offset in ((below, 0), (above, below.n_vertices)):
        on_plane = np.all(np.abs(mesh.vertices[mesh.faces][:, :, 2]) < 1e-9, axis=1)
        polys.extend((mesh.faces[~on_plane] + offset).tolist())
    scale = float(np.ptp(verts, axis=0).max())
    return mesh_from_polygons(verts, polys, name=name, merge_tolerance=1e-9 * scale)


def hemisphere(
    *,
    radius: float = 1.0,
    freeboard: float | None = None,
    n_theta: int = 16,
    n_phi: int = 48,
    zg: float | None = None,
    rho: float = RHO_SEAWATER,
    g: float = GRAVITY,
) -> Hull:
    """A floating hemisphere (flat face on the waterline), closed above by a short cylinder.

    Parameters
    ----------
    radius : float
        Hemisphere radius a [m]; displaced volume 2πa³/3.
    freeboard : float, optional
        Height of the vertical cylinder above the waterline [m] (default a/2).
    n_theta, n_phi : int
        Panels along a meridian of the hemisphere and around it.
    zg : float, optional
        z of G [m] (z down); default a/2 (below the metacentre, which lies on the waterline,
        so GM = z_G).
    """
    a = float(radius)
    if a <= 0.0:
        raise ValueError(f"radius must be positive [m], got {radius!r}")
    fb = 0.5 * a if freeboard is None else float(freeboard)
    # rings: from the deck centre, deck edge, cylinder, waterline, down to the bottom pole
    theta = np.linspace(0.0, np.pi / 2, n_theta + 1)  # 0 at the waterline, π/2 at the bottom
    ring_r = np.concatenate(
        [[0.0, a], np.full(max(1, round(n_theta * fb / a / 1.5)), a), a * np.cos(theta[1:])]
    )
    n_cyl = len(ring_r) - 2 - n_theta
    ring_z = np.concatenate(
        [[-fb, -fb], np.linspace(-fb, 0.0, n_cyl + 1)[1:], a * np.sin(theta[1:])]
    )
    phi = np.linspace(0.0, 2 * np.pi, n_phi, endpoint=False)
    verts = np.concatenate(
        [
            np.column_stack([r * np.cos(phi), r * np.sin(phi), np.full(n_phi, z)])
            for r, z in zip(ring_r, ring_z, strict=True)
        ]
    )
    polys = []
    for i in range(len(ring_r) - 1):
        for j in range(n_phi):
            j1 = (j + 1) % n_phi
            polys.append([i * n_phi + j, (i + 1) * n_phi + j, (i + 1) * n_phi + j1, i * n_phi + j1])
    mesh = mesh_from_polygons(verts, polys, name="hemisphere", merge_tolerance=1e-9 * a)
    if mesh.volume < 0:
        mesh = mesh.flipped()
    volume = 2.0 / 3.0 * np.pi * a**3
    zg_ = 0.5 * a if zg is None else float(zg)
    r_gyr = np.sqrt(0.4) * a
    mass = MassProperties.from_radii_of_gyration(
        rho * volume, np.array([0.0, 0.0, zg_]), (r_gyr, r_gyr, r_gyr)
    )
    ref = {"volume_m3": volume, "KB_m": a - 3 * a / 8, "added_mass_inf_nd": 0.5}
    return Hull("hemisphere", mesh, mass, Particulars(2 * a, 2 * a, a, a + fb, ref), rho, g)


def wigley(
    *,
    length: float = 100.0,
    beam: float = 10.0,
    draught: float = 6.25,
    depth: float = 10.0,
    kg: float | None = None,
    n_stations: int = 41,
    n_sections: int = 40,
    n_below: int = 8,
    n_above: int = 4,
    rho: float = RHO_SEAWATER,
    g: float = GRAVITY,
    a2: float = 0.0,
) -> Hull:
    """The Wigley hull y = (B/2)(1 − ξ²)(1 + a₂ ξ²)(1 − (z/T)²), ξ = 2x/L, below the waterline,
    wall-sided above.

    a₂ = 0 is the classic parabolic Wigley hull; a₂ = 0.2 with L/B = 10, B/T = 1.6 is Journée's
    Wigley III (Journée 1992, Delft University of Technology, Ship Hydromechanics Laboratory
    report 909: L 3 m, B 0.3 m, T 0.1875 m, ∇ 0.0780 m³, C_B 0.462, k_yy 0.25 L).

    Closed forms: displaced volume (2/3) T B (L/2) (4/3 + 4 a₂/15) ((4/9) L B T at a₂ = 0),
    waterplane area B (L/2) (4/3 + 4 a₂/15), KB = 5 T/8.

    Parameters
    ----------
    length, beam, draught, depth : float
        Dimensions [m].
    kg : float, optional
        Height of G above the keel [m]; default KB + BM − 0.1 B (a stable ship).
    a2 : float
        Coefficient of the waterline's fullness term (1 + a₂ ξ²) [-], in [0, 1].
    """
    a2 = float(a2)
    if not (np.isfinite(a2) and 0.0 <= a2 <= 1.0):
        raise ValueError(f"a2={a2!r}; expected a fullness coefficient in [0, 1]")
    xs = np.linspace(-length / 2, length / 2, n_stations)
    zeta = np.linspace(0.0, 1.0, 41)  # fraction of draught below the waterline
    stations = []
    for x in xs:
        xi2 = (2 * x / length) ** 2
        hb = 0.5 * beam * (1 - xi2) * (1 + a2 * xi2) * (1 - zeta**2)
        height = draught * (1 - zeta)  # above keel
        stations.append(Station(float(x), hb[::-1], height[::-1]))
    mesh = hull_mesh_from_stations(
        stations,
        draught=draught,
        depth=depth,
        n_sections=n_sections,
        n_below=n_below,
        n_above=n_above,
        n_deck=2,
        name="wigley",
    )
    waterline = 4.0 / 3.0 + 4.0 * a2 / 15.0  # ∫₋₁¹ (1 − ξ²)(1 + a₂ ξ²) dξ
    volume = 2.0 / 3.0 * draught * beam * length / 2.0 * waterline
    # KB: ∫∫ 2y (T − z) / V with the separable profile → KB = T − (T·∫ζ(1−ζ²)/∫(1−ζ²)) = 5T/8
    kb = 5.0 * draught / 8.0
    # ∫ (2y)³/12 dx = B³/12 (L/2) ∫₋₁¹ [(1 − ξ²)(1 + a₂ ξ²)]³ dξ (Gauss–Legendre, exact)
    nodes, weights = np.polynomial.legendre.leggauss(8)
    cube = float(np.sum(weights * ((1 - nodes**2) * (1 + a2 * nodes**2)) ** 3))
    it = beam**3 / 12.0 * length / 2.0 * cube
    bm = it / volume
    kg_ = kb + bm - 0.1 * beam if kg is None else float(kg)
    mass = MassProperties.from_radii_of_gyration(
        rho * volume,
        np.array([0.0, 0.0, draught - kg_]),
        (0.35 * beam, 0.25 * length, 0.25 * length),
    )
    ref = {
        "volume_m3": volume,
        "waterplane_area_m2": beam * length / 2.0 * waterline,
        "KB_m": kb,
        "BMt_m": bm,
    }
    return Hull("wigley", mesh, mass, Particulars(length, beam, draught, depth, ref), rho, g)


HULLS: dict[str, Callable[..., Hull]] = {
    "s175": s175,
    "dtmb5415": dtmb5415,
    "box_barge": box_barge,
    "hemisphere": hemisphere,
    "wigley": wigley,
}


def load_hull(name: str, **overrides: Any) -> Hull:
    """A library hull by name, with keyword overrides of its builder's parameters.

    Parameters
    ----------
    name : str
        A library hull (:data:`HULLS`). A ship file's hull: ``ship_gym.ship.load_ship(path).hull``.
    **overrides
        Keyword arguments of the builder (e.g. ``kg=10.0``, ``n_sections=80``).
    """
    try:
        builder = HULLS[name.lower()]
    except KeyError:
        raise ValueError(f"unknown hull {name!r}; expected one of {sorted(HULLS)}") from None
    try:
        return builder(**overrides)
    except TypeError as exc:
        import inspect

        allowed = [p for p in inspect.signature(builder).parameters]
        raise ValueError(
            f"bad override for hull {name!r}: {exc}; allowed keywords: {allowed}"
        ) from None
