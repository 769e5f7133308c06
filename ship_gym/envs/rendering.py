"""Pictures of a ship in waves for ``render_mode="rgb_array"`` and ``"human"``.

An environment describes the instant to draw with a frozen :class:`RenderSnapshot` (pose, main
dimensions, incident-wave elevation along and across the ship, a short history of motions and the
current commands); :func:`render_rgb` turns it into an ``(H, W, 3)`` ``uint8`` picture and
:class:`HumanViewer` shows the same picture in an interactive matplotlib window.

The picture has three panels:

* **side profile** — the hull outline, heaved and pitched, against the incident-wave elevation
  along the ship (vertical scale exaggerated so that metre-scale motions of a 175 m ship show);
* **midship section** — the hull section, heaved and rolled, against the elevation across the
  ship, at true scale, with the capsize roll limit (if given) drawn as dashed lines;
* **motion strip** — the history traces and the current commands as text.

Geometry follows :mod:`ship_gym.conventions`: η = (x, y, z, φ, θ, ψ) with z down, positive roll
starboard side down, positive pitch bow up; body frame origin amidships at the design waterline.
Body point (x, y, z_b) lies at depth z + (−x sin θ + cos θ (y sin φ + z_b cos φ)) below the mean
free surface (zyx Euler rotation, Fossen 2011 eq. 2.18, third row); the pictures draw the two
planar cuts of this (y = 0 for the profile, x = 0 for the section) in "up" coordinates.

matplotlib is imported inside the functions (``import ship_gym`` stays light). One figure per
picture size is kept and its artists are updated in place between frames (no figure is rebuilt
unless the set of history/command labels changes), which is several times faster than drawing a
new figure; every axis limit is a function of the snapshot alone, so the same snapshot always gives
the same pixels.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["HumanViewer", "RenderSnapshot", "render_rgb"]

_DPI = 100.0
_SEA_COLOUR = "#9ecae1"
_HULL_COLOUR = "#636363"
_SKY_COLOUR = "#f7fbff"


@dataclass(frozen=True)
class RenderSnapshot:
    """Everything needed to draw one instant of one episode.

    Attributes
    ----------
    time : float
        Simulation time [s].
    eta : NDArray
        (6,) pose: x, y, z [m] (z down), φ, θ, ψ [rad] (:mod:`ship_gym.conventions`).
    length, beam, draught, depth : float
        Length between perpendiculars, beam, design draught and moulded depth [m].
    profile_x : NDArray
        (n,) body-frame x stations along the ship [m].
    profile_elevation : NDArray
        (n,) incident-wave elevation at those stations [m, positive up].
    section_y : NDArray
        (m,) body-frame y stations across the ship amidships [m].
    section_elevation : NDArray
        (m,) incident-wave elevation at those stations [m, positive up].
    history_time : NDArray
        (k,) times of the history samples [s].
    history : Mapping[str, NDArray]
        Label with unit → (k,) trace, e.g. ``{"roll [deg]": ..., "pitch [deg]": ...}``.
    actions : Mapping[str, float]
        Label with unit → current physical command, e.g. ``{"rudder [deg]": 4.2}``.
    title : str
        Drawn above the panels (env id, sea state...).
    roll_limit : float or None
        Capsize roll angle [rad], drawn on the section view; None draws no limit.
    """

    time: float
    eta: NDArray
    length: float
    beam: float
    draught: float
    depth: float
    profile_x: NDArray
    profile_elevation: NDArray
    section_y: NDArray
    section_elevation: NDArray
    history_time: NDArray
    history: Mapping[str, NDArray]
    actions: Mapping[str, float]
    title: str = ""
    roll_limit: float | None = None

    def __post_init__(self) -> None:
        eta = np.asarray(self.eta, dtype=float)
        if eta.shape != (6,):
            raise ValueError(f"eta must have shape (6,), got {eta.shape}")
        for name in ("length", "beam", "draught", "depth"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"{name} must be a positive finite length [m], got {value!r}")
        if self.depth <= self.draught:
            raise ValueError(
                f"depth ({self.depth} m) must exceed draught ({self.draught} m) to draw a hull"
            )
        for xs, zs, what in (
            ("profile_x", "profile_elevation", "profile"),
            ("section_y", "section_elevation", "section"),
        ):
            a = np.asarray(getattr(self, xs))
            b = np.asarray(getattr(self, zs))
            if a.ndim != 1 or a.shape != b.shape or a.size < 2:
                raise ValueError(
                    f"{what}: {xs} and {zs} must be 1-D of equal length >= 2, got shapes "
                    f"{a.shape} and {b.shape}"
                )
        k = np.asarray(self.history_time).shape
        if len(k) != 1:
            raise ValueError(f"history_time must be 1-D, got shape {k}")
        for label, trace in self.history.items():
            if np.asarray(trace).shape != k:
                raise ValueError(
                    f"history[{label!r}] has shape {np.asarray(trace).shape}, expected {k} "
                    "(same as history_time)"
                )
        if self.roll_limit is not None and not (0.0 < self.roll_limit <= math.pi):
            raise ValueError(f"roll_limit must be in (0, pi] [rad] or None, got {self.roll_limit}")


# --------------------------------------------------------------------------- geometry


def _hull_profile(length: float, draught: float, depth: float) -> NDArray:
    """Closed side outline of a merchant hull, body frame (x forward [m], z_b down [m])."""
    half = 0.5 * length
    keel, deck = draught, draught - depth
    return np.array(
        [
            (-half, deck),  # transom top
            (-half, keel - 0.55 * draught),  # transom bottom
            (-half + 0.06 * length, keel),  # run
            (half - 0.08 * length, keel),  # forefoot
            (half - 0.01 * length, keel - 0.35 * draught),  # bulb/stem
            (half + 0.02 * length, deck),  # raked stem at the deck
            (-half, deck),
        ]
    )


def _hull_section(beam: float, draught: float, depth: float, n_bilge: int = 8) -> NDArray:
    """Closed midship section with round bilges, body frame (y starboard [m], z_b down [m])."""
    half = 0.5 * beam
    radius = min(0.35 * draught, 0.25 * beam)
    keel, deck = draught, draught - depth
    angles = np.linspace(0.0, 0.5 * np.pi, n_bilge)
    # starboard bilge from the side (angle 0) to the keel (angle pi/2), centre inside the hull
    sb = np.column_stack(
        [half - radius + radius * np.cos(angles), keel - radius + radius * np.sin(angles)]
    )
    port = sb[::-1] * np.array([-1.0, 1.0])
    return np.vstack([[(half, deck)], sb, port, [(-half, deck)], [(half, deck)]])


def _profile_up(outline: NDArray, eta: NDArray) -> NDArray:
    """Side outline (x, z_b) → earth (horizontal along ship [m], height above mean surface [m])."""
    theta = eta[4]
    c, s = math.cos(theta), math.sin(theta)
    x, zb = outline[:, 0], outline[:, 1]
    horizontal = x * c + zb * s
    down = eta[2] - x * s + zb * c
    return np.column_stack([horizontal, -down])


def _section_up(outline: NDArray, eta: NDArray) -> NDArray:
    """Section (y, z_b) → earth (horizontal across [m], height above mean surface [m])."""
    phi = eta[3]
    c, s = math.cos(phi), math.sin(phi)
    y, zb = outline[:, 0], outline[:, 1]
    horizontal = y * c - zb * s
    down = eta[2] + y * s + zb * c
    return np.column_stack([horizontal, -down])


def _sea_polygon(
    x: NDArray, elevation: NDArray, bottom: float, x_min: float, x_max: float
) -> NDArray:
    """Closed polygon of the water under an elevation curve down to ``bottom`` [m].

    The curve is continued flat (end values held) to ``x_min`` and ``x_max`` [m] so that the sea
    fills the panel however far the given stations reach.
    """
    order = np.argsort(x, kind="stable")
    xs, zs = np.asarray(x, float)[order], np.asarray(elevation, float)[order]
    left = [(min(x_min, xs[0]), zs[0])]
    right = [(max(x_max, xs[-1]), zs[-1])]
    curve = np.vstack([left, np.column_stack([xs, zs]), right])
    return np.vstack([curve, [(curve[-1, 0], bottom), (curve[0, 0], bottom)]])


def _finite(a: NDArray) -> NDArray:
    """Replace non-finite values (a diverged state) by 0 so the picture can still be drawn."""
    a = np.asarray(a, dtype=float)
    return np.where(np.isfinite(a), a, 0.0)


# --------------------------------------------------------------------------- the figure


@dataclass
class _Canvas:
    """A figure with its artists, kept between frames of the same size and label set.

    The axes, ticks, labels and legend (everything that depends only on the axis limits) are
    drawn once per set of limits and kept as a pixel background; each frame restores it and draws
    only the moving artists (``animated=True``) on top — matplotlib's blitting.
    """

    figure: Any
    canvas: Any
    artists: dict[str, Any] = field(default_factory=dict)
    moving: list[Any] = field(default_factory=list)
    layout_key: tuple = ()
    limits_key: tuple | None = None
    background: Any = None
    section_aspect: float = 1.0  # height / width of the section panel [pixels / pixels]


_CANVASES: dict[tuple[int, int], _Canvas] = {}


def _nice_ceil(value: float) -> float:
    """Smallest of {1, 2, 2.5, 5} × 10^k that is >= ``value`` (> 0)."""
    if not value > 0.0:
        return 1.0
    decade = 10.0 ** math.floor(math.log10(value))
    for m in (1.0, 2.0, 2.5, 5.0, 10.0):
        if m * decade >= value * (1.0 - 1e-12):
            return m * decade
    return 10.0 * decade  # pragma: no cover


def _outward(lo: float, hi: float, step: float) -> tuple[float, float]:
    """Round an interval outward to multiples of ``step``."""
    return math.floor(lo / step) * step, math.ceil(hi / step) * step


def _build(width: int, height: int, snapshot: RenderSnapshot) -> _Canvas:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Polygon

    fig = Figure(figsize=(width / _DPI, height / _DPI), dpi=_DPI, facecolor="white")
    canvas = FigureCanvasAgg(fig)
    grid = fig.add_gridspec(
        2,
        2,
        width_ratios=(2.0, 1.0),
        height_ratios=(1.15, 1.0),
        left=0.08,
        right=0.98,
        bottom=0.09,
        top=0.9,
        wspace=0.22,
        hspace=0.42,
    )
    ax_side = fig.add_subplot(grid[0, 0])
    ax_sec = fig.add_subplot(grid[0, 1])
    ax_strip = fig.add_subplot(grid[1, :])
    small: dict[str, Any] = {"fontsize": 7}
    a: dict[str, Any] = {"side": ax_side, "section": ax_sec, "strip": ax_strip}
    for ax in (ax_side, ax_sec):
        ax.set_facecolor(_SKY_COLOUR)
        ax.tick_params(labelsize=6, length=2)
    ax_strip.tick_params(labelsize=6, length=2)
    dummy = np.zeros((3, 2))
    # the sea is drawn over the hull, translucent, so the immersed part shows through
    sea_style = {"fc": _SEA_COLOUR, "ec": "#3182bd", "alpha": 0.6, "lw": 0.8, "zorder": 3}
    hull_style = {"fc": _HULL_COLOUR, "ec": "k", "lw": 0.8, "zorder": 2}
    a["side_hull"] = ax_side.add_patch(Polygon(dummy, closed=True, **hull_style))
    a["side_sea"] = ax_side.add_patch(Polygon(dummy, closed=True, **sea_style))
    ax_side.axhline(0.0, color="#08519c", lw=0.6, ls=":")
    ax_side.set_title("side profile (vertical scale exaggerated)", **small)
    ax_side.set_xlabel("x along ship [m]", **small)
    ax_side.set_ylabel("height [m]", **small)
    a["side_text"] = ax_side.text(
        0.01, 0.97, "", transform=ax_side.transAxes, va="top", zorder=5, **small
    )

    a["sec_hull"] = ax_sec.add_patch(Polygon(dummy, closed=True, **hull_style))
    a["sec_sea"] = ax_sec.add_patch(Polygon(dummy, closed=True, **sea_style))
    (a["sec_mast"],) = ax_sec.plot([], [], color="k", lw=1.0, zorder=4)
    (a["sec_limit_port"],) = ax_sec.plot([], [], color="#de2d26", lw=0.9, ls="--", zorder=4)
    (a["sec_limit_stbd"],) = ax_sec.plot([], [], color="#de2d26", lw=0.9, ls="--", zorder=4)
    ax_sec.set_title("midship section (looking forward)", **small)
    ax_sec.set_xlabel("y starboard [m]", **small)
    a["sec_text"] = ax_sec.text(
        0.02, 0.97, "", transform=ax_sec.transAxes, va="top", zorder=5, **small
    )

    a["traces"] = []
    for label in snapshot.history:
        (line,) = ax_strip.plot([], [], lw=0.9, label=label)
        a["traces"].append(line)
    if snapshot.history:
        ax_strip.legend(loc="upper left", fontsize=6, ncol=min(4, len(snapshot.history)))
    ax_strip.set_xlabel("time relative to now [s]", **small)
    ax_strip.grid(alpha=0.3)
    ax_strip.set_title("motions and commands", **small)
    ax_strip.axvline(0.0, color="0.4", lw=0.6)
    a["actions_text"] = ax_strip.text(
        0.995,
        0.96,
        "",
        transform=ax_strip.transAxes,
        ha="right",
        va="top",
        family="monospace",
        fontsize=6.5,
        zorder=5,
        bbox={"fc": "white", "ec": "0.7", "alpha": 0.85, "boxstyle": "round,pad=0.3"},
    )
    a["title"] = fig.text(0.5, 0.975, "", ha="center", va="top", fontsize=8)
    moving = [
        a["side_hull"],
        a["side_sea"],
        a["side_text"],
        a["sec_hull"],
        a["sec_sea"],
        a["sec_mast"],
        a["sec_limit_port"],
        a["sec_limit_stbd"],
        a["sec_text"],
        *a["traces"],
        a["actions_text"],
        a["title"],
    ]
    for artist in moving:
        artist.set_animated(True)
    box = ax_sec.get_position()
    aspect = (box.height * height) / (box.width * width)
    return _Canvas(figure=fig, canvas=canvas, artists=a, moving=moving, section_aspect=aspect)


def _layout_key(snapshot: RenderSnapshot) -> tuple:
    return (tuple(snapshot.history), tuple(snapshot.actions))


def _update(c: _Canvas, snap: RenderSnapshot) -> tuple:
    """Set every moving artist from ``snap``; return the axis limits it needs (rounded)."""
    a = c.artists
    eta = _finite(snap.eta)
    length, beam, draught, depth = snap.length, snap.beam, snap.draught, snap.depth

    # side profile: limits rounded outward to a "nice" step so they change rarely
    px, pz = _finite(snap.profile_x), _finite(snap.profile_elevation)
    sec_y, sec_z = _finite(snap.section_y), _finite(snap.section_elevation)
    hull = _profile_up(_hull_profile(length, draught, depth), eta)
    wave_amp = max(float(np.max(np.abs(pz))), float(np.max(np.abs(sec_z))))
    step = _nice_ceil(0.5 * depth)
    bottom, top = _outward(
        min(float(hull[:, 1].min()), -wave_amp) - 0.25 * depth,
        max(float(hull[:, 1].max()), wave_amp) + 0.25 * depth,
        step,
    )
    side_x = (-0.62 * length, 0.62 * length)
    a["side_sea"].set_xy(_sea_polygon(px, pz, bottom - depth, *side_x))
    a["side_hull"].set_xy(hull)
    a["side_text"].set_text(
        f"heave {-eta[2]:+.2f} m up   pitch {math.degrees(eta[4]):+.2f}°   "
        f"heading {math.degrees(eta[5]) % 360.0:.1f}°"
    )

    # midship section at true scale: the vertical span follows the panel's pixel aspect
    section = _section_up(_hull_section(beam, draught, depth), eta)
    reach = 0.5 * math.hypot(beam, 2.0 * depth) + abs(eta[2]) + wave_amp
    half_width = _nice_ceil(max(0.75 * beam, reach))
    half_height = half_width * c.section_aspect
    a["sec_sea"].set_xy(_sea_polygon(sec_y, sec_z, -2.0 * half_height, -half_width, half_width))
    a["sec_hull"].set_xy(section)
    phi = eta[3]
    mast = 1.1 * depth
    origin_up = -eta[2]
    # the ship's "up" (body -z) axis from O: body (0, 0, -mast) → (mast sin φ, -z + mast cos φ)
    a["sec_mast"].set_data(
        [0.0, mast * math.sin(phi)], [origin_up, origin_up + mast * math.cos(phi)]
    )
    show_limit = snap.roll_limit is not None
    if snap.roll_limit is not None:
        lim = snap.roll_limit
        for key, sign in (("sec_limit_port", -1.0), ("sec_limit_stbd", 1.0)):
            a[key].set_data(
                [0.0, sign * mast * math.sin(lim)], [origin_up, origin_up + mast * math.cos(lim)]
            )
    a["sec_limit_port"].set_visible(show_limit)
    a["sec_limit_stbd"].set_visible(show_limit)
    limit_txt = (
        f"   limit {math.degrees(snap.roll_limit):.0f}°" if snap.roll_limit is not None else ""
    )
    a["sec_text"].set_text(f"roll {math.degrees(phi):+.1f}°{limit_txt}")

    # motion strip against time relative to now, window and scale rounded
    t_now = float(snap.time) if math.isfinite(snap.time) else 0.0
    t = _finite(snap.history_time) - t_now
    lo_y, hi_y = math.inf, -math.inf
    for line, trace in zip(a["traces"], snap.history.values(), strict=True):
        y = _finite(trace)
        line.set_data(t, y)
        if y.size:
            lo_y, hi_y = min(lo_y, float(y.min())), max(hi_y, float(y.max()))
    if not math.isfinite(lo_y):
        lo_y, hi_y = -1.0, 1.0
    y_step = _nice_ceil(max(hi_y - lo_y, 1.0) / 4.0)
    y_lo, y_hi = _outward(lo_y, hi_y + 0.35 * (hi_y - lo_y) + 0.5 * y_step, y_step)  # legend room
    window = _nice_ceil(max(-float(t.min()) if t.size else 0.0, 1.0))
    a["actions_text"].set_text(
        "\n".join(f"{k}: {float(v):+8.3f}" for k, v in snap.actions.items()) or "(no commands)"
    )
    clock = f"t = {t_now:7.1f} s"
    a["title"].set_text(f"{snap.title}   {clock}" if snap.title else clock)
    return (
        side_x,
        (bottom, top),
        (-half_width, half_width),
        (-half_height, half_height),
        (-window, 0.3 * window),
        (y_lo, y_hi),
    )


def render_rgb(snapshot: RenderSnapshot, width: int = 640, height: int = 480) -> NDArray[np.uint8]:
    """Draw a snapshot as an RGB picture.

    Parameters
    ----------
    snapshot : RenderSnapshot
        The instant to draw.
    width, height : int
        Picture size [pixels], each in [64, 4096].

    Returns
    -------
    NDArray[np.uint8]
        (height, width, 3) RGB picture. The same snapshot gives the same pixels.
    """
    for name, value in (("width", width), ("height", height)):
        if not (isinstance(value, int | np.integer) and 64 <= value <= 4096):
            raise ValueError(
                f"{name} must be an integer number of pixels in [64, 4096], got {value!r}"
            )
    size = (int(width), int(height))
    c = _CANVASES.get(size)
    key = _layout_key(snapshot)
    if c is None or c.layout_key != key:
        c = _build(*size, snapshot)
        c.layout_key = key
        _CANVASES[size] = c
    limits = _update(c, snapshot)
    if limits != c.limits_key:
        a = c.artists
        side_x, side_y, sec_x, sec_y, strip_x, strip_y = limits
        a["side"].set_xlim(*side_x)
        a["side"].set_ylim(*side_y)
        a["section"].set_xlim(*sec_x)
        a["section"].set_ylim(*sec_y)
        a["strip"].set_xlim(*strip_x)
        a["strip"].set_ylim(*strip_y)
        c.canvas.draw()  # everything not animated: axes, ticks, labels, legend
        c.background = c.canvas.copy_from_bbox(c.figure.bbox)
        c.limits_key = limits
    else:
        c.canvas.restore_region(c.background)
    for artist in c.moving:
        if artist.get_visible():
            c.figure.draw_artist(artist)
    buffer = np.asarray(c.canvas.buffer_rgba())
    frame = np.ascontiguousarray(buffer[..., :3])
    if frame.shape != (size[1], size[0], 3):  # rounding of figsize * dpi
        frame = _fit(frame, size[1], size[0])
    return frame


def _fit(frame: NDArray[np.uint8], height: int, width: int) -> NDArray[np.uint8]:
    """Crop or pad (white) a picture to exactly (height, width, 3)."""
    out = np.full((height, width, 3), 255, dtype=np.uint8)
    h, w = min(height, frame.shape[0]), min(width, frame.shape[1])
    out[:h, :w] = frame[:h, :w]
    return out


class HumanViewer:
    """An interactive matplotlib window showing :func:`render_rgb` pictures.

    The window is opened on the first :meth:`show` (``plt.ion()``). On a non-interactive
    (headless) matplotlib backend nothing is opened: the first :meth:`show` warns once, with the
    backend name and how to get a window, and later calls only keep the picture in
    :attr:`last_frame`. Never raises for a missing display.

    Parameters
    ----------
    width, height : int
        Picture size [pixels].
    title : str
        Window title.
    """

    def __init__(self, width: int = 640, height: int = 480, title: str = "ship_gym") -> None:
        self.width = int(width)
        self.height = int(height)
        self.title = title
        self.last_frame: NDArray[np.uint8] | None = None
        self.headless: bool | None = None  # decided on the first show()
        self._figure: Any = None
        self._image: Any = None

    @staticmethod
    def _backend_is_interactive() -> tuple[bool, str]:
        import matplotlib

        backend = str(matplotlib.get_backend())
        try:
            from matplotlib.backends import BackendFilter, backend_registry

            non_interactive = set(backend_registry.list_builtin(BackendFilter.NON_INTERACTIVE))
        except ImportError:  # matplotlib < 3.9
            non_interactive = {"agg", "cairo", "pdf", "pgf", "ps", "svg", "template"}
        return backend.lower() not in non_interactive, backend

    def show(self, snapshot: RenderSnapshot) -> None:
        """Draw ``snapshot`` in the window (or only keep it, on a headless backend)."""
        frame = render_rgb(snapshot, self.width, self.height)
        self.last_frame = frame
        if self.headless is None:
            interactive, backend = self._backend_is_interactive()
            self.headless = not interactive
            if self.headless:
                warnings.warn(
                    f"render_mode='human': matplotlib backend {backend!r} cannot open a window "
                    "(headless); frames are not shown. Set MPLBACKEND=TkAgg or QtAgg on a machine "
                    "with a display, or use render_mode='rgb_array'.",
                    RuntimeWarning,
                    stacklevel=2,
                )
        if self.headless:
            return
        try:
            self._draw(frame)
        except Exception as exc:  # a display that went away must not kill a training run
            self.headless = True
            warnings.warn(
                f"render_mode='human': the window could not be drawn ({exc}); frames are no "
                "longer shown.",
                RuntimeWarning,
                stacklevel=2,
            )

    def _draw(self, frame: NDArray[np.uint8]) -> None:
        import matplotlib.pyplot as plt

        if self._figure is None or not plt.fignum_exists(self._figure.number):
            plt.ion()
            self._figure = plt.figure(
                figsize=(self.width / _DPI, self.height / _DPI), dpi=_DPI, num=self.title
            )
            ax = self._figure.add_axes((0.0, 0.0, 1.0, 1.0))
            ax.set_axis_off()
            self._image = ax.imshow(frame, interpolation="nearest")
        else:
            self._image.set_data(frame)
        self._figure.canvas.draw_idle()
        self._figure.canvas.flush_events()
        plt.pause(0.001)

    def close(self) -> None:
        """Close the window (if one was opened)."""
        if self._figure is not None:
            import matplotlib.pyplot as plt

            plt.close(self._figure)
            self._figure = None
            self._image = None
