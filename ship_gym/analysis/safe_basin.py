"""Safe basins of roll motion and their erosion (McCue & Campbell; Soliman & Thompson 1991).

A *safe basin* is the set of initial conditions ⟨φ₀, φ̇₀⟩ from which the ship does not capsize
within a given time: a grid of initial roll [rad] and roll rate [rad/s] is integrated, and a cell
is *capsized* when |φ| exceeds the capsize angle (by default the vanishing angle of the restoring)
at any time step (McCue & Campbell, figure 8: "Safe basin ... grid of initial conditions").

* :func:`safe_basin` — a 1-DOF :class:`~ship_gym.roll.equation.RollEquation` (e.g. the
  Edith Terkol, McCue & Campbell eq. 1, or a fitted eq. 2 model): the whole grid is one batch of
  the compiled RK4 kernel (in chunks of rows, for the progress bar).
* :func:`s175_safe_basin` — the same through the 6-DOF simulator, a 1-DOF slice of a real hull:
  the S175 with only roll free (``ShipSetup(free_dofs=(False, False, False, True, False,
  False))``: nonlinear Froude–Krylov/hydrostatic restoring on the instantaneous wetted hull,
  Cummins radiation memory, diffraction, Ikeda viscous roll damping), in calm water or regular
  beam waves, the grid being ONE :class:`~ship_gym.engine.batch.BatchSimulator` of N = grid
  size ships, each reset with its own initial roll and roll rate. Heave and pitch are held at
  the upright free-floating equilibrium, so the restoring at large heel is that of the upright
  sinkage and trim, while the capsize angle is, by default, the vanishing angle of the GZ curve
  at free sinkage and trim (:func:`ship_gym.hull.righting_arm`, 66.2° for the S175 at its design
  KG) — the two differ by the sinkage the heeled ship would take.
* :func:`integrity_curve` — the basin's erosion with the forcing amplitude: the *integrity*
  (Rainey & Thompson's global integrity measure restricted to the grid window) is the safe area at
  forcing F divided by the safe area of the unforced basin on the same grid and duration.

Cells are labelled by their centre; the basin area on the grid is known to about one cell width
along its boundary. The analytic check (tested): with no damping and no forcing the energy
½φ̇² + V(φ) is conserved, so a cell is safe iff its energy is below the barrier V(φᵥ) and
|φ₀| < φᵥ — the boundary is the separatrix through the vanishing angle.

Results are frozen dataclasses written atomically to CSV / NetCDF and plotted to PNG
(:func:`write_basin`, :func:`write_integrity_csv`, :func:`plot_basin`, :func:`plot_integrity`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.io_utils import atomic_write, atomic_write_text
from ship_gym.roll.equation import RollEquation
from ship_gym.typing import FloatArray, IntegratorName

if TYPE_CHECKING:
    import xarray as xr

__all__ = [
    "IntegrityCurve",
    "SafeBasin",
    "integrity_curve",
    "plot_basin",
    "plot_integrity",
    "s175_integrity_curve",
    "s175_safe_basin",
    "safe_basin",
    "write_basin",
    "write_integrity_csv",
]


@dataclass(frozen=True)
class SafeBasin:
    """Capsize outcome of a grid of initial conditions ⟨φ₀, φ̇₀⟩.

    Attributes
    ----------
    roll : ndarray, shape (n_roll,)
        Initial roll of the grid columns [rad] (cell centres, increasing).
    roll_rate : ndarray, shape (n_rate,)
        Initial roll rate of the grid rows [rad/s] (cell centres, increasing).
    capsized : ndarray of bool, shape (n_rate, n_roll)
        |φ| exceeded :attr:`capsize_angle` within :attr:`duration`.
    capsize_time : ndarray, shape (n_rate, n_roll)
        Time to capsize [s] (from the start of the run); NaN where safe.
    duration : float
        Integration time [s].
    capsize_angle : float
        Roll limit [rad].
    model : str
        What was integrated (e.g. ``"edith-terkol"``, ``"s175"``).
    parameters : Mapping[str, float]
        The forcing and numerics (name with unit → value), e.g.
        ``{"forcing_amplitude [rad/s^2]": 0.02, "dt [s]": 0.05}``.
    """

    roll: FloatArray
    roll_rate: FloatArray
    capsized: NDArray[np.bool_]
    capsize_time: FloatArray
    duration: float
    capsize_angle: float
    model: str
    parameters: Mapping[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        shape = (self.roll_rate.size, self.roll.size)
        if self.capsized.shape != shape or self.capsize_time.shape != shape:
            raise ValueError(
                f"capsized and capsize_time must have shape (n_rate, n_roll) = {shape}, got "
                f"{self.capsized.shape} and {self.capsize_time.shape}"
            )

    @property
    def safe(self) -> NDArray[np.bool_]:
        """(n_rate, n_roll) bool: the safe cells."""
        return ~self.capsized

    @property
    def safe_fraction(self) -> float:
        """Fraction of the grid's cells that stay safe [-]."""
        return float(np.mean(~self.capsized))

    @property
    def cell_area(self) -> float:
        """Area of one grid cell in the (φ, φ̇) plane [rad²/s] (uniform grids)."""
        d_roll = (self.roll[-1] - self.roll[0]) / max(self.roll.size - 1, 1)
        d_rate = (self.roll_rate[-1] - self.roll_rate[0]) / max(self.roll_rate.size - 1, 1)
        return float(d_roll * d_rate)

    @property
    def safe_area(self) -> float:
        """Safe area in the (φ, φ̇) plane [rad²/s] (number of safe cells × cell area)."""
        return float(np.count_nonzero(~self.capsized)) * self.cell_area

    def integrity(self, reference: SafeBasin) -> float:
        """Safe area relative to a reference basin (usually the unforced one) on the same grid."""
        if reference.capsized.shape != self.capsized.shape:
            raise ValueError(
                f"reference basin grid {reference.capsized.shape} differs from "
                f"{self.capsized.shape}"
            )
        ref = reference.safe_fraction
        return self.safe_fraction / ref if ref > 0.0 else math.nan

    def to_dataset(self) -> xr.Dataset:
        """The basin as an :class:`xarray.Dataset` (dims roll_rate × roll; attrs: the rest)."""
        import xarray as xr

        attrs: dict[str, Any] = {
            "model": self.model,
            "duration_s": self.duration,
            "capsize_angle_rad": self.capsize_angle,
            "safe_fraction": self.safe_fraction,
            "source": "ship_gym.analysis.safe_basin",
        }
        attrs.update({_attr_name(k): float(v) for k, v in self.parameters.items()})
        return xr.Dataset(
            {
                "capsized": (("roll_rate", "roll"), self.capsized.astype(np.int8)),
                "capsize_time": (("roll_rate", "roll"), self.capsize_time, {"units": "s"}),
            },
            coords={
                "roll": ("roll", self.roll, {"units": "rad"}),
                "roll_rate": ("roll_rate", self.roll_rate, {"units": "rad/s"}),
            },
            attrs=attrs,
        )


def _attr_name(label: str) -> str:
    """'forcing_amplitude [rad/s^2]' → 'forcing_amplitude_rad_s2' (a NetCDF-friendly name)."""
    out = label.replace(" [", "_").replace("]", "").replace("/", "_").replace("^", "")
    return "".join(c if c.isalnum() or c == "_" else "_" for c in out)


@dataclass(frozen=True)
class IntegrityCurve:
    """Erosion of the safe basin with the forcing.

    Attributes
    ----------
    forcing : ndarray, shape (n,)
        Forcing values (amplitude F [rad/s²] for a roll equation; wave height [m] for the S175).
    forcing_label : str
        Name and unit of :attr:`forcing`.
    safe_fraction : ndarray, shape (n,)
        Safe fraction of the grid at each forcing [-].
    integrity : ndarray, shape (n,)
        safe_fraction / reference_safe_fraction [-].
    reference_safe_fraction : float
        Safe fraction of the unforced basin on the same grid and duration [-].
    basins : tuple of SafeBasin
        The basins, in the order of :attr:`forcing`.
    """

    forcing: FloatArray
    forcing_label: str
    safe_fraction: FloatArray
    integrity: FloatArray
    reference_safe_fraction: float
    basins: tuple[SafeBasin, ...] = ()


# ============================================================================ grids
def _grid(low: float, high: float, n: int, name: str, unit: str) -> FloatArray:
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 2:
        raise ValueError(f"the number of {name} grid points must be an integer >= 2, got {n!r}")
    if not (math.isfinite(low) and math.isfinite(high) and low < high):
        raise ValueError(f"{name} range must be finite with low < high [{unit}], got {low}, {high}")
    return np.linspace(low, high, int(n))


def _positive(value: float, name: str, unit: str) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be a positive number [{unit}], got {value!r}")
    return v


# ============================================================================ roll equation
def safe_basin(
    equation: RollEquation,
    *,
    roll_range: tuple[float, float] = (-1.0, 1.0),
    roll_rate_range: tuple[float, float] = (-0.6, 0.6),
    n_roll: int = 101,
    n_rate: int = 101,
    duration: float = 200.0,
    dt: float = 0.05,
    capsize_angle: float | None = None,
    model: str = "roll-equation",
    progress: bool = False,
) -> SafeBasin:
    """Safe basin of a 1-DOF roll equation (the forcing starts at t = 0 with its own phase).

    Parameters
    ----------
    equation : RollEquation
        Model, with its forcing (F, ωₑ, ε).
    roll_range, roll_rate_range : (float, float)
        Grid window of initial roll [rad] and roll rate [rad/s] (cell centres at the ends).
    n_roll, n_rate : int
        Grid points along roll and roll rate.
    duration : float
        Integration time [s]; a whole number of ``dt``.
    dt : float
        RK4 step [s].
    capsize_angle : float, optional
        Roll limit [rad]; default the equation's vanishing angle.
    model : str
        Label stored in the result.
    progress : bool
        tqdm progress bar over chunks of grid rows.

    Returns
    -------
    SafeBasin
    """
    roll = _grid(*roll_range, n_roll, "roll", "rad")
    rate = _grid(*roll_rate_range, n_rate, "roll rate", "rad/s")
    duration = _positive(duration, "duration", "s")
    dt = _positive(dt, "dt", "s")
    limit = equation.vanishing_angle() if capsize_angle is None else capsize_angle
    if capsize_angle is None and not 0.0 < limit < math.inf:
        raise ValueError(
            f"the equation has no positive finite vanishing angle ({limit}): give capsize_angle "
            "[rad]"
        )
    limit = _positive(limit, "capsize_angle", "rad")
    capsized = np.empty((rate.size, roll.size), dtype=bool)
    t_cap = np.empty((rate.size, roll.size))
    chunk = max(1, math.ceil(20_000 / roll.size))  # ~20k trajectories per kernel call
    starts = range(0, rate.size, chunk)
    if progress:
        from tqdm import tqdm

        starts = tqdm(starts, desc=f"safe basin {model}", unit="chunk", mininterval=0.5)
    for i0 in starts:
        rows = slice(i0, min(i0 + chunk, rate.size))
        tr = equation.integrate(
            roll[None, :],
            rate[rows, None],
            t_end=duration,
            dt=dt,
            stop_at=limit,
            record_every=None,
        )
        capsized[rows] = tr.capsized
        t_cap[rows] = tr.capsize_time
    return SafeBasin(
        roll=roll,
        roll_rate=rate,
        capsized=capsized,
        capsize_time=t_cap,
        duration=duration,
        capsize_angle=limit,
        model=model,
        parameters={
            "forcing_amplitude [rad/s^2]": equation.forcing_amplitude,
            "forcing_frequency [rad/s]": equation.forcing_frequency,
            "forcing_phase [rad]": equation.forcing_phase,
            "dt [s]": dt,
        },
    )


def integrity_curve(
    equation: RollEquation,
    amplitudes: ArrayLike,
    *,
    progress: bool = False,
    **basin_kwargs: Any,
) -> IntegrityCurve:
    """Safe-basin integrity of a roll equation versus the forcing amplitude F.

    Parameters
    ----------
    equation : RollEquation
        Model; its forcing amplitude is replaced by each of ``amplitudes`` (frequency and phase
        kept).
    amplitudes : array_like
        Forcing amplitudes F [rad/s²], ≥ 0.
    progress : bool
        tqdm progress bar over the amplitudes.
    **basin_kwargs
        Passed to :func:`safe_basin` (grid, duration, dt, capsize_angle, model).

    Returns
    -------
    IntegrityCurve
        Integrity relative to the unforced basin (F = 0) computed on the same grid.
    """
    amps = np.atleast_1d(np.asarray(amplitudes, dtype=np.float64))
    if amps.ndim != 1 or amps.size == 0 or not np.all(np.isfinite(amps)) or np.any(amps < 0):
        raise ValueError(
            f"amplitudes must be a non-empty 1-D array of F >= 0 [rad/s^2], got {amplitudes!r}"
        )
    reference = safe_basin(replace(equation, forcing_amplitude=0.0), **basin_kwargs)
    iterator: Any = amps
    if progress:
        from tqdm import tqdm

        iterator = tqdm(amps, desc="integrity curve", unit="basin", mininterval=0.5)
    basins = tuple(
        safe_basin(replace(equation, forcing_amplitude=float(f)), **basin_kwargs) for f in iterator
    )
    fractions = np.array([b.safe_fraction for b in basins])
    ref = reference.safe_fraction
    return IntegrityCurve(
        forcing=amps,
        forcing_label="forcing amplitude F [rad/s^2]",
        safe_fraction=fractions,
        integrity=fractions / ref if ref > 0 else np.full_like(fractions, np.nan),
        reference_safe_fraction=ref,
        basins=basins,
    )


# ============================================================================ S175 slice
def s175_safe_basin(
    *,
    wave_height: float = 0.0,
    wave_period: float = 18.0,
    wave_heading_deg: float = 90.0,
    wave_phase: float = 0.0,
    roll_range: tuple[float, float] | None = None,
    roll_rate_range: tuple[float, float] = (-0.5, 0.5),
    n_roll: int = 21,
    n_rate: int = 21,
    duration: float = 120.0,
    dt: float = 0.1,
    integrator: IntegratorName = "holloway",
    capsize_angle: float | None = None,
    hull: str = "s175",
    progress: bool = False,
) -> SafeBasin:
    """Safe basin of a real hull with only roll free, through the 6-DOF simulator (one batch).

    Parameters
    ----------
    wave_height : float
        Regular-wave height H [m]; 0 for calm water.
    wave_period : float
        Wave period [s] (the S175's roll-only natural period is ≈ 17.7 s).
    wave_heading_deg : float
        Relative wave heading β [deg] (90: beam seas, waves travelling to starboard).
    wave_phase : float
        Wave phase ε at the ship [rad] (no start-up ramp: the waves are on from t = 0, as the
        forcing of the 1-DOF model).
    roll_range : (float, float), optional
        Initial roll window [rad]; default ±1.15 × the capsize angle.
    roll_rate_range : (float, float)
        Initial roll-rate window [rad/s].
    n_roll, n_rate : int
        Grid points; N = n_roll × n_rate ships in one batch.
    duration : float
        Integration time [s].
    dt : float
        Physics step [s].
    integrator : {"holloway", "rk4"}
        Batch integrator (Holloway: one force evaluation per step).
    capsize_angle : float, optional
        Roll limit [rad]; default the vanishing angle of the hull's GZ curve.
    hull : str
        Library hull with a matching hydrodynamic database (``"s175"``).
    progress : bool
        tqdm progress bar over the time steps.

    Returns
    -------
    SafeBasin
    """
    from ship_gym.engine.batch import build_batch_simulator
    from ship_gym.engine.ship import ShipSetup, wave_field_for
    from ship_gym.hull import righting_arm
    from ship_gym.ship import hull_of
    from ship_gym.waves.sea_state import RegularWave

    duration = _positive(duration, "duration", "s")
    dt = _positive(dt, "dt", "s")
    n_steps = round(duration / dt)
    if abs(n_steps * dt - duration) > 1e-9 * duration:
        raise ValueError(f"duration {duration!r} s must be a whole number of dt = {dt!r} s")
    height = float(wave_height)
    if not (math.isfinite(height) and height >= 0.0):
        raise ValueError(f"wave_height must be >= 0 [m], got {wave_height!r}")
    if capsize_angle is None:
        gz = righting_arm(hull_of(hull), np.arange(0.0, 91.0, 5.0))
        if not math.isfinite(gz.vanishing_angle_deg):
            raise ValueError(f"hull {hull!r} has no vanishing angle below 90°: give capsize_angle")
        capsize_angle = math.radians(gz.vanishing_angle_deg)
    limit = _positive(capsize_angle, "capsize_angle", "rad")
    if roll_range is None:
        roll_range = (-1.15 * limit, 1.15 * limit)
    roll = _grid(*roll_range, n_roll, "roll", "rad")
    rate = _grid(*roll_rate_range, n_rate, "roll rate", "rad/s")

    heading = math.radians(float(wave_heading_deg))
    sea = None
    if height > 0.0:
        sea = RegularWave(
            height=height, period=_positive(wave_period, "wave_period", "s"),
            phase=float(wave_phase), ramp_time=0.0,
        )  # fmt: skip
    field_ = wave_field_for(sea, heading)
    setup = ShipSetup(
        hull=hull,
        database=hull,
        free_dofs=(False, False, False, True, False, False),
        dt=dt,
        integrator=integrator,
    )
    n = roll.size * rate.size
    sim = build_batch_simulator(setup, [field_] * n, sea=sea, wave_heading=heading)
    phi0, p0 = np.meshgrid(roll, rate)  # (n_rate, n_roll)
    eta = np.tile(sim.initial_eta, (n, 1))
    eta[:, 3] = phi0.ravel()
    nu = np.zeros((n, 6))
    nu[:, 3] = p0.ravel()  # roll only free, θ = 0: φ̇ = p
    sim.reset(eta=eta, nu=nu)

    capsized = np.abs(eta[:, 3]) > limit
    t_cap = np.where(capsized, 0.0, np.nan)
    steps: Any = range(n_steps)
    if progress:
        from tqdm import tqdm

        steps = tqdm(steps, desc=f"safe basin {hull} ({n} ships)", unit="step", mininterval=0.5)
    prev = np.abs(eta[:, 3])
    for k in steps:
        sim.step()
        now = np.abs(sim.eta[:, 3])
        crossing = ~capsized & ((now > limit) | sim.diverged)
        if crossing.any():
            frac = np.clip((limit - prev[crossing]) / (now[crossing] - prev[crossing]), 0.0, 1.0)
            frac = np.where(np.isfinite(frac), frac, 1.0)
            t_cap[crossing] = (k + frac) * dt
            capsized |= crossing
        prev = now
    params = {
        "wave_height [m]": height,
        "wave_period [s]": float(wave_period),
        "wave_heading [deg]": float(wave_heading_deg),
        "wave_phase [rad]": float(wave_phase),
        "dt [s]": dt,
    }
    return SafeBasin(
        roll=roll,
        roll_rate=rate,
        capsized=capsized.reshape(rate.size, roll.size),
        capsize_time=t_cap.reshape(rate.size, roll.size),
        duration=duration,
        capsize_angle=limit,
        model=hull,
        parameters=params,
    )


# ============================================================================ output
def write_basin(basin: SafeBasin, path: str | Path) -> Path:
    """Write a basin atomically: ``.nc`` → NetCDF (xarray), anything else → CSV (long format).

    The CSV has a ``#`` header with the metadata, then one row per cell:
    ``roll_rad, roll_rate_rad_s, capsized, capsize_time_s`` (capsize_time empty when safe).
    """
    path = Path(path)
    if path.suffix == ".nc":
        ds = basin.to_dataset()
        return atomic_write(path, lambda p: ds.to_netcdf(p))
    lines = [
        f"# safe basin: model={basin.model}, duration={basin.duration:g} s, capsize_angle="
        f"{basin.capsize_angle:.6f} rad, safe_fraction={basin.safe_fraction:.6f}",
        "# " + ", ".join(f"{k}={v:g}" for k, v in basin.parameters.items()),
        "roll_rad,roll_rate_rad_s,capsized,capsize_time_s",
    ]
    for i, p in enumerate(basin.roll_rate):
        for j, r in enumerate(basin.roll):
            t = basin.capsize_time[i, j]
            ts = "" if math.isnan(t) else f"{t:.4f}"
            lines.append(f"{r:.6f},{p:.6f},{int(basin.capsized[i, j])},{ts}")
    return atomic_write_text(path, "\n".join(lines) + "\n")


def write_integrity_csv(curve: IntegrityCurve, path: str | Path) -> Path:
    """Write an integrity curve atomically as CSV (forcing, safe fraction, integrity)."""
    label = _attr_name(curve.forcing_label)
    lines = [
        f"# reference (unforced) safe fraction = {curve.reference_safe_fraction:.6f}",
        f"{label},safe_fraction,integrity",
    ]
    lines += [
        f"{f:.6g},{s:.6f},{g:.6f}"
        for f, s, g in zip(curve.forcing, curve.safe_fraction, curve.integrity, strict=True)
    ]
    return atomic_write_text(path, "\n".join(lines) + "\n")


def _draw_basin(ax: Any, basin: SafeBasin, equation: RollEquation | None, title: str) -> Any:
    import matplotlib.colors as mcolors

    d_roll = basin.roll[1] - basin.roll[0]
    d_rate = basin.roll_rate[1] - basin.roll_rate[0]
    extent = (
        basin.roll[0] - d_roll / 2, basin.roll[-1] + d_roll / 2,
        basin.roll_rate[0] - d_rate / 2, basin.roll_rate[-1] + d_rate / 2,
    )  # fmt: skip
    t = np.where(basin.capsized, np.maximum(basin.capsize_time, 1e-3), np.nan)
    t_max = max(basin.duration, 1.0)
    im = ax.imshow(
        t, origin="lower", extent=extent, aspect="auto", cmap="inferno",
        norm=mcolors.LogNorm(vmin=max(t_max / 1000, 1e-2), vmax=t_max), interpolation="nearest",
    )  # fmt: skip
    safe = np.where(basin.capsized, np.nan, 1.0)
    ax.imshow(
        safe, origin="lower", extent=extent, aspect="auto", cmap="Blues", vmin=0.0, vmax=1.2,
        interpolation="nearest",
    )  # fmt: skip
    if equation is not None:
        xs = np.linspace(extent[0], extent[1], 400)
        ys = np.linspace(extent[2], extent[3], 400)
        xx, yy = np.meshgrid(xs, ys)
        ev = float(equation.potential_energy(equation.vanishing_angle()))
        ax.contour(
            xx, yy, 0.5 * yy**2 + equation.potential_energy(xx), levels=[ev], colors="cyan",
            linewidths=0.8, linestyles="--",
        )  # fmt: skip
    for s in (-1, 1):
        ax.axvline(s * basin.capsize_angle, color="w", lw=0.6, ls=":")
    ax.set_xlabel("initial roll φ₀ [rad]")
    ax.set_ylabel("initial roll rate φ̇₀ [rad/s]")
    ax.set_title(title, fontsize=9)
    return im


def plot_basin(
    basin: SafeBasin,
    path: str | Path,
    *,
    separatrix_of: RollEquation | None = None,
    reference: SafeBasin | None = None,
) -> Path:
    """Plot a basin (safe cells blue; capsized cells coloured by time to capsize) to PNG.

    Parameters
    ----------
    basin : SafeBasin
    path : str or Path
        PNG file, written atomically.
    separatrix_of : RollEquation, optional
        Draw the unforced, undamped separatrix ½φ̇² + V(φ) = V(φᵥ) of this equation (dashed).
    reference : SafeBasin, optional
        Unforced basin: the integrity is printed in the title.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.0, 5.2), dpi=120)
    head = f"{basin.model}: safe fraction {basin.safe_fraction:.3f}"
    if reference is not None:
        head += f", integrity {basin.integrity(reference):.3f}"
    params = ", ".join(
        f"{k.split(' [')[0]} {v:g}" for k, v in basin.parameters.items() if not k.startswith("dt")
    )
    title = "\n".join(
        [head, f"{basin.duration:g} s, φ_c = {math.degrees(basin.capsize_angle):.1f}°", params]
    )
    im = _draw_basin(ax, basin, separatrix_of, title)
    fig.colorbar(im, ax=ax, label="time to capsize [s]")
    fig.tight_layout()
    return _save(fig, path)


def plot_integrity(
    curve: IntegrityCurve,
    path: str | Path,
    *,
    separatrix_of: RollEquation | None = None,
    n_panels: int = 4,
) -> Path:
    """Integrity versus forcing, above a row of basins showing the erosion; PNG, atomic."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n_panels = min(n_panels, len(curve.basins))
    fig = plt.figure(figsize=(3.2 * max(n_panels, 2), 7.0), dpi=110)
    grid = fig.add_gridspec(2, max(n_panels, 1), height_ratios=[1.0, 1.1])
    ax = fig.add_subplot(grid[0, :])
    ax.plot(curve.forcing, curve.integrity, "o-", label="integrity (safe area / unforced)")
    ax.plot(curve.forcing, curve.safe_fraction, "s--", ms=3, label="safe fraction of the grid")
    ax.set_xlabel(curve.forcing_label)
    ax.set_ylabel("[-]")
    ax.set_ylim(-0.02, max(1.05, float(np.nanmax(curve.integrity)) + 0.05))
    ax.grid(alpha=0.3)
    ax.legend()
    model = curve.basins[0].model if curve.basins else ""
    ax.set_title(f"{model}: erosion of the safe basin")
    if n_panels:
        picks = np.unique(np.linspace(0, len(curve.basins) - 1, n_panels).round().astype(int))
        for col, k in enumerate(picks):
            b = curve.basins[k]
            a = fig.add_subplot(grid[1, col])
            _draw_basin(
                a, b, separatrix_of,
                f"{curve.forcing_label.split(' [')[0]} = {curve.forcing[k]:.3g}: "
                f"integrity {curve.integrity[k]:.2f}",
            )  # fmt: skip
            if col:
                a.set_ylabel("")
    fig.tight_layout()
    return _save(fig, path)


def _save(fig: Any, path: str | Path) -> Path:
    import matplotlib.pyplot as plt

    try:
        return atomic_write(path, lambda p: fig.savefig(p, format="png"))
    finally:
        plt.close(fig)


def s175_integrity_curve(
    wave_heights: Sequence[float],
    *,
    progress: bool = False,
    **basin_kwargs: Any,
) -> IntegrityCurve:
    """Integrity of the S175 roll-only basin versus regular beam-wave height [m].

    The reference is the calm-water basin on the same grid; ``basin_kwargs`` go to
    :func:`s175_safe_basin`.
    """
    heights = np.asarray(list(wave_heights), dtype=np.float64)
    if (
        heights.ndim != 1
        or heights.size == 0
        or np.any(~np.isfinite(heights))
        or np.any(heights < 0)
    ):
        raise ValueError(
            f"wave_heights must be a non-empty list of H >= 0 [m], got {wave_heights!r}"
        )
    reference = s175_safe_basin(wave_height=0.0, progress=progress, **basin_kwargs)
    basins = tuple(
        reference
        if h == 0.0
        else s175_safe_basin(wave_height=float(h), progress=progress, **basin_kwargs)
        for h in heights
    )
    fractions = np.array([b.safe_fraction for b in basins])
    ref = reference.safe_fraction
    return IntegrityCurve(
        forcing=heights,
        forcing_label="wave height H [m]",
        safe_fraction=fractions,
        integrity=fractions / ref if ref > 0 else np.full_like(fractions, np.nan),
        reference_safe_fraction=ref,
        basins=basins,
    )
