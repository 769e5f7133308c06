"""Closed panel meshes from station offsets (lines plan → mesh to the deck).

Each station is a half-section y(z) from the keel up. The builder

1. inserts a point exactly at the design waterline (so the immersed mesh is cut along panel
   edges) and extends the section wall-sided from its highest offset up to the deck;
2. re-samples the part below and the part above the waterline separately at equal girth
   (arc-length) steps, so every section has the same number of points and the waterline is a
   mesh line;
3. interpolates each girth point longitudinally through the stations with monotone cubic (PCHIP)
   splines, which neither overshoot nor create bumps between stations, at cosine-spaced
   sections (finer at the ends, where the shape changes fastest);
4. joins the sections into a tube (starboard side, deck, port side) and closes both ends with flat
   end plates (transom, stem), giving a watertight mesh with outward normals.
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from importlib import resources

import numpy as np
from scipy.interpolate import PchipInterpolator

from ship_gym.hull.mesh import PanelMesh, mesh_from_polygons


@dataclass(frozen=True, eq=False)
class Station:
    """One half-section of a lines plan.

    Parameters
    ----------
    x : float
        Longitudinal position [m], positive forward of amidships (body frame).
    half_breadth : numpy.ndarray
        Half breadths y ≥ 0 [m], from the keel up.
    height : numpy.ndarray
        Heights above the baseline [m], non-decreasing (equal heights: a flat bottom).
    """

    x: float
    half_breadth: np.ndarray
    height: np.ndarray

    def __post_init__(self) -> None:
        y = np.asarray(self.half_breadth, dtype=float)
        z = np.asarray(self.height, dtype=float)
        if y.shape != z.shape or y.ndim != 1 or len(y) < 2:
            raise ValueError(
                f"station at x = {self.x} m: half_breadth and height must be 1-D of equal length "
                f">= 2, got shapes {y.shape} and {z.shape}"
            )
        if np.any(np.diff(z) < 0.0):
            raise ValueError(
                f"station at x = {self.x} m: heights must not decrease from the keel up"
            )
        if np.any(y < 0.0):
            raise ValueError(f"station at x = {self.x} m: half breadths must be >= 0")
        object.__setattr__(self, "half_breadth", y)
        object.__setattr__(self, "height", z)


def read_offsets_csv(path: str | None = None) -> list[Station]:
    """Read stations from a CSV with columns station, x_aft_of_midship_m, half_breadth_m,
    z_above_keel_m (the S175 format; see ``ship_gym/data/s175/README.md``).

    Parameters
    ----------
    path : str, optional
        CSV file; default the bundled S175 offsets.

    Returns
    -------
    list of Station
        Sorted from aft to forward; x converted to positive forward.
    """
    if path is None:
        text = resources.files("ship_gym.data").joinpath("s175/offsets.csv").read_text()
    else:
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    rows = list(csv.DictReader(text.splitlines()))
    required = {"station", "x_aft_of_midship_m", "half_breadth_m", "z_above_keel_m"}
    if not rows or not required <= set(rows[0]):
        raise ValueError(f"offsets file {path or 's175'} must have columns {sorted(required)}")
    by_station: dict[str, list[tuple[float, float, float]]] = {}
    for r in rows:
        by_station.setdefault(r["station"], []).append(
            (
                -float(r["x_aft_of_midship_m"]),
                float(r["half_breadth_m"]),
                float(r["z_above_keel_m"]),
            )
        )
    stations = []
    for pts in by_station.values():
        arr = np.array(pts[::-1])  # files list each section from the top down to the keel
        stations.append(Station(float(arr[0, 0]), arr[:, 1], arr[:, 2]))
    return sorted(stations, key=lambda s: s.x)


def _resample_by_girth(
    y: np.ndarray, z: np.ndarray, n: int, bend_length: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """n + 1 points along the polyline (y, z) at equal steps of girth plus bending.

    The measure of each segment is its length plus ``bend_length`` × half the turning angle [rad]
    at each of its ends, so points gather where the section bends (the bilge) instead of being
    spread evenly along flat bottom and straight side.
    """
    seg = np.hypot(np.diff(y), np.diff(z))
    if seg.sum() <= 0.0:
        return np.full(n + 1, y[0]), np.full(n + 1, z[0])
    keep = seg > 0.0
    ang = np.unwrap(np.arctan2(np.diff(z)[keep], np.diff(y)[keep]))
    turn = np.zeros(len(seg))
    if len(ang) > 1:
        t = np.abs(np.diff(ang))
        idx = np.flatnonzero(keep)
        turn[idx[:-1]] += 0.5 * t
        turn[idx[1:]] += 0.5 * t
    s = np.concatenate([[0.0], np.cumsum(seg + bend_length * turn)])
    u = np.linspace(0.0, s[-1], n + 1)
    return np.interp(u, s, y), np.interp(u, s, z)


def _section_points(
    st: Station, draught: float, depth: float, n_below: int, n_above: int
) -> tuple[np.ndarray, np.ndarray]:
    """Girth-resampled (y, height) of one station, keel → waterline → deck."""
    y, h = st.half_breadth, st.height
    if y[0] > 0.0:  # flat bottom reaching the centreline
        y, h = np.concatenate([[0.0], y]), np.concatenate([[h[0]], h])
    if h[-1] < depth:  # wall-sided extension to the deck
        y, h = np.concatenate([y, [y[-1]]]), np.concatenate([h, [depth]])
    keel = h[0]
    if keel >= draught:  # station entirely above the waterline: immersed part collapses
        yb, hb = np.full(n_below + 1, y[0]), np.full(n_below + 1, keel)
        ya, ha = _resample_by_girth(y, h, n_above)
        hb[-1] = ha[0]
        return np.concatenate([yb, ya[1:]]), np.concatenate([hb, ha[1:]])
    below = h < draught
    above = h > draught
    wl = int(np.searchsorted(h, draught, side="left"))
    y_wl = float(np.interp(draught, h[wl - 1 : wl + 1], y[wl - 1 : wl + 1]))
    bend = 0.25 * draught
    yb, hb = _resample_by_girth(
        np.append(y[below], y_wl), np.append(h[below], draught), n_below, bend
    )
    ya, ha = _resample_by_girth(
        np.insert(y[above], 0, y_wl), np.insert(h[above], 0, draught), n_above
    )
    return np.concatenate([yb, ya[1:]]), np.concatenate([hb, ha[1:]])


def hull_mesh_from_stations(
    stations: list[Station],
    *,
    draught: float,
    depth: float,
    n_sections: int = 60,
    n_below: int = 10,
    n_above: int = 6,
    n_deck: int = 4,
    n_end: int = 1,
    name: str = "hull",
) -> PanelMesh:
    """Closed mesh to the deck from a lines plan.

    Parameters
    ----------
    stations : list of Station
        At least two stations, any longitudinal spacing.
    draught : float
        Design draught T [m] above the baseline; the mesh origin is put at this waterline.
    depth : float
        Moulded depth D [m] (deck height above the baseline).
    n_sections : int
        Number of sections along the hull (≥ 2), cosine-spaced.
    n_below, n_above : int
        Panels per side along the girth below and above the waterline.
    n_deck : int
        Panels across the deck.
    n_end : int
        Panels across each end plate (transom, stem) per girth row; > 1 keeps a wide immersed
        transom from setting the largest panel (and so the highest frequency a BEM resolves).

    Returns
    -------
    PanelMesh
        Watertight, outward normals, body frame (x forward, y starboard, z down, z = 0 at the
        design waterline).
    """
    for label, value, low in (
        ("n_sections", n_sections, 2),
        ("n_below", n_below, 1),
        ("n_above", n_above, 1),
        ("n_deck", n_deck, 1),
        ("n_end", n_end, 1),
    ):
        if int(value) != value or value < low:
            raise ValueError(f"{label} must be an integer >= {low}, got {value!r}")
    if len(stations) < 2:
        raise ValueError(f"need at least 2 stations, got {len(stations)}")
    if not 0.0 < draught < depth:
        raise ValueError(f"need 0 < draught < depth [m], got draught={draught}, depth={depth}")
    stations = sorted(stations, key=lambda s: s.x)
    xs = np.array([s.x for s in stations])
    if np.any(np.diff(xs) <= 0.0):
        raise ValueError("stations must have distinct x positions")
    pts = [_section_points(s, draught, depth, n_below, n_above) for s in stations]
    ys = np.array([p[0] for p in pts])  # (n_stations, n_girth)
    hs = np.array([p[1] for p in pts])
    u = 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, n_sections)))
    x_sec = xs[0] + (xs[-1] - xs[0]) * u
    y_sec = np.clip(PchipInterpolator(xs, ys, axis=0)(x_sec), 0.0, None)
    h_sec = PchipInterpolator(xs, hs, axis=0)(x_sec)
    # exact waterline and deck heights (PCHIP of constants is exact, but be explicit)
    h_sec[:, n_below] = draught
    h_sec[:, -1] = depth
    n_g = n_below + n_above + 1  # points per half girth, keel (0) to deck edge (n_g - 1)

    # loop per section: starboard keel→deck edge, deck across to port, port deck edge→keel (excl.)
    loops = []
    for i in range(n_sections):
        stbd = np.column_stack([np.full(n_g, x_sec[i]), y_sec[i], draught - h_sec[i]])
        port = stbd * np.array([1.0, -1.0, 1.0])
        yd = np.linspace(y_sec[i, -1], -y_sec[i, -1], n_deck + 1)[1:-1]
        deck = np.column_stack([np.full(len(yd), x_sec[i]), yd, np.full(len(yd), draught - depth)])
        loops.append(np.vstack([stbd, deck, port[::-1][:-1]]))
    n_loop = len(loops[0])
    port_start = n_g + n_deck - 1  # loop index of the port deck edge
    verts = np.vstack(loops)
    polys: list[list[int]] = []
    for i in range(n_sections - 1):
        a, b = i * n_loop, (i + 1) * n_loop
        for k in range(n_loop):
            k1 = (k + 1) % n_loop
            quad = [a + k, b + k, b + k1, a + k1]
            # port panels start one vertex later, so that every non-planar quad is split along
            # the mirror image of its starboard twin's diagonal: an exactly symmetric hull
            polys.append(quad[1:] + quad[:1] if k >= port_start else quad)
    # end plates: rows between starboard point j and port point j; top row closes over the deck
    extra: list[np.ndarray] = []  # end-plate vertices between starboard and port (n_end > 1)
    for i, forward in ((0, False), (n_sections - 1, True)):
        base = i * n_loop
        stbd_idx = [base + j for j in range(n_g)]
        deck_idx = [base + n_g + k for k in range(n_deck - 1)]
        port_idx = [base + (n_loop - j) % n_loop for j in range(n_g)]  # port_idx[0] = keel
        # level j: starboard point j, n_end - 1 points across, port point j
        levels = []
        for j in range(n_g - 1):
            a, b = verts[stbd_idx[j]], verts[port_idx[j]]
            first = len(verts) + sum(len(e) for e in extra)
            t = np.arange(1, n_end if j < n_g - 2 else 1)[:, None] / n_end
            extra.append(a + t * (b - a))
            levels.append([stbd_idx[j], *range(first, first + len(t)), port_idx[j]])
        for j in range(n_g - 2):
            lo, hi = levels[j], levels[j + 1]
            if j < n_g - 3:
                for c in range(n_end):
                    poly = [lo[c], hi[c], hi[c + 1], lo[c + 1]]
                    polys.append(poly[::-1] if forward else poly)
            else:  # last row: split below, whole above; starts off the split edge (fan)
                poly = [hi[0], hi[-1], *lo[::-1]]
                polys.append([poly[0], *poly[:0:-1]] if forward else poly)
        top = [stbd_idx[-2], stbd_idx[-1], *deck_idx, port_idx[-1], port_idx[-2]]
        polys.append(top[::-1] if forward else top)
    if extra:
        verts = np.vstack([verts, *extra])
    scale = float(np.ptp(verts[:, 0]) + np.ptp(verts[:, 2]))
    mesh = mesh_from_polygons(verts, polys, name=name, merge_tolerance=1e-7 * scale)
    mesh.check(closed=True)
    return mesh
