"""Roll equation-of-motion identification from a time series (McCue & Campbell).

McCue & Campbell fit a *guessed form* of the roll equation to a roll / roll-rate record. Their
form (eq. 2), with the subscript u for "unknown",

    ÿ + b_u1 ẏ + b_u3 ẏ³ + c_u1 y + c_u3 y³ = F_u sin(ωₑ t),

has linear + cubic damping and stiffness and a harmonic forcing whose encounter frequency ωₑ is
*known* (it is "comparatively trivial to approximate from a given data set"); the five unknowns
b_u1, b_u3, c_u1, c_u3, F_u are found by a Nelder–Mead simplex search on the phase-space error of
*piecewise* integrations (eq. 3):

    E = Σ_{j=1}^{N} ‖⟨y, ẏ⟩_j − ⟨φ, φ̇⟩_j‖,

the record being split into N pieces of m = n/N samples, each piece integrated from the data
point ⟨φ, φ̇⟩ at its start, ⟨y, ẏ⟩_j being the model state at the end of piece j. N is varied
"to find a solution balancing local and long-time behavior" and to avoid erroneous local minima:
N = 1 is a single free run (a rugged objective: phase errors accumulate over the whole record),
N → n a one-step prediction (a smooth objective that sees only short-time behaviour).

What this module adds, and the readings it takes:

* **Forcing phase.** The paper fits no phase: its data come from the same sin(ωₑt) clock, so the
  phase is known. ``fit_phase=True`` adds ε in F_u sin(ωₑt + ε) for records whose clock is not
  the forcing's.
* **Wave-elevation input** (the extension the paper's conclusion points to for random waves):
  the harmonic term may be replaced (``omega=None``) or complemented by ``K · u(t − τ)``, a gain
  K times a record column u (e.g. the incident-wave elevation at the ship [m]), shifted by a lag
  τ [s] (fitted when ``fit_input_lag=True``; τ < 0 is a lead). This is the simplest linear filter
  of the elevation: one gain and one delay, i.e. the right amplitude and phase of the roll moment
  at one frequency only. In irregular waves the physically meaningful input is the linear wave
  roll moment m(t) (Froude–Krylov + diffraction X₄(ω, β) of a BEM database), giving
  K ≈ 1/(I44 + A44): :func:`roll_excitation_moment` synthesises it from a known sea component
  by component, :func:`roll_excitation_from_elevation` filters a measured elevation record by
  X₄ (FFT; long-crested, known heading), :func:`roll_excitation_transfer` gives X₄.
* **Norm.** ‖·‖ is the Euclidean norm of (Δy, w·Δẏ) in the record's units (rad, rad/s), w = 1 by
  default as in the paper; ``compare="all"`` also counts the samples inside each piece (the paper
  compares the piece end points only, ``"endpoint"``).
* **Start of the simplex.** The paper gives none. By default an equation-error least-squares fit
  (φ̈ from the finite difference of φ̇, regressed on the terms of eq. 2 — the "least squares
  regression" the paper's conclusion mentions) starts the search; any start can be given.
* **Prediction.** As in the paper's figures 1, 3 and 6, the fitted equation is integrated
  *freely from the first data point* over the whole record (training window and beyond);
  :func:`predict_roll` can also start at the end of the training window.

Integration goes through :meth:`ship_gym.roll.equation.RollEquation.integrate`: all N
pieces are one batch (one compiled RK4 call), each piece's different start time entering as a
per-piece forcing phase ε + ωₑ t_j; a wave-elevation input enters as a callable moment looked up
from a table of the input at the RK4 half steps (linear interpolation of the record).
The record must be uniformly sampled; the RK4 step is the sample interval (or a fraction of it,
``substeps``).
"""

from __future__ import annotations

import csv
import dataclasses
import math
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Literal

import numpy as np
import numpy.typing as npt
from numpy.typing import NDArray

from ship_gym.roll.equation import RollEquation, RollTrajectory
from ship_gym.typing import FloatArray

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes

    from ship_gym.waves.wave_field import WaveField

__all__ = [
    "MCCUE_CAMPBELL_FITS",
    "PARAMETER_NAMES",
    "IdentificationResult",
    "McCueCampbellModel",
    "RollPrediction",
    "RollRecord",
    "WindowError",
    "equation_error_estimate",
    "identify_roll_equation",
    "load_roll_csv",
    "piece_layout",
    "piecewise_error",
    "plot_curves",
    "plot_time_history",
    "predict_roll",
    "roll_excitation_from_elevation",
    "roll_excitation_moment",
    "roll_excitation_transfer",
    "write_roll_csv",
]

Compare = Literal["endpoint", "all"]

#: Order of the model parameters in parameter vectors and reports.
PARAMETER_NAMES: tuple[str, ...] = (
    "b_u1",
    "b_u3",
    "c_u1",
    "c_u3",
    "forcing_amplitude",
    "forcing_phase",
    "input_gain",
    "input_lag",
)

#: McCue & Campbell's fitted eq. 2 coefficients (b_u1, b_u3, c_u1, c_u3, F_u) for the Edith
#: Terkol data (F = 0.0195, ωₑ = 0.527) from each initial condition ⟨φ₀, φ̇₀⟩.
MCCUE_CAMPBELL_FITS: dict[tuple[float, float], tuple[float, float, float, float, float]] = {
    (0.0, 0.0): (0.0095, -0.4445, 0.4063, 0.4209, 0.0200),
    (0.4, 0.0): (0.0060, 0.0639, 0.4344, -0.2403, 0.0200),
    (-0.4, -0.35): (0.0098, 0.0388, 0.5147, -0.7052, 0.0220),
}

_UNIFORM_RTOL = 1e-6  # relative tolerance on the sample interval for a "uniform" record


# ------------------------------------------------------------------------------------ record
@dataclass(frozen=True, eq=False)
class RollRecord:
    """A uniformly sampled roll time series, optionally with one input column.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Time [s], strictly increasing with a constant step.
    roll : ndarray, shape (n,)
        Roll φ [rad].
    roll_rate : ndarray, shape (n,)
        Roll rate φ̇ [rad/s].
    excitation : ndarray, shape (n,) or None
        Input u(t) for the ``K u(t − τ)`` forcing term (e.g. wave elevation at the ship [m]).
    excitation_name : str or None
        Name of the input column.
    """

    t: FloatArray
    roll: FloatArray
    roll_rate: FloatArray
    excitation: FloatArray | None = None
    excitation_name: str | None = None

    def __post_init__(self) -> None:
        cols = {"t": self.t, "roll": self.roll, "roll_rate": self.roll_rate}
        if self.excitation is not None:
            cols["excitation"] = self.excitation
        n = None
        for name, value in cols.items():
            a = np.asarray(value, dtype=np.float64)
            if a.ndim != 1:
                raise ValueError(f"{name} must be 1-D, got shape {a.shape}")
            if n is None:
                n = a.size
            elif a.size != n:
                raise ValueError(f"{name} has {a.size} samples, t has {n}")
            bad = np.flatnonzero(~np.isfinite(a))
            if bad.size:
                raise ValueError(f"{name} is not finite at sample {int(bad[0])} ({a[bad[0]]!r})")
            object.__setattr__(self, name, a)
        assert n is not None
        if n < 3:
            raise ValueError(f"a roll record needs at least 3 samples, got {n}")
        dt = np.diff(self.t)
        bad = np.flatnonzero(dt <= 0.0)
        if bad.size:
            k = int(bad[0])
            raise ValueError(
                f"t must be strictly increasing: t[{k}] = {self.t[k]!r} s, "
                f"t[{k + 1}] = {self.t[k + 1]!r} s"
            )
        step = (self.t[-1] - self.t[0]) / (n - 1)
        worst = int(np.argmax(np.abs(dt - step)))
        if abs(dt[worst] - step) > _UNIFORM_RTOL * step:
            raise ValueError(
                f"t must be uniformly sampled (mean step {step!r} s, but t[{worst + 1}] − "
                f"t[{worst}] = {dt[worst]!r} s); resample the record to a constant step"
            )

    @property
    def n(self) -> int:
        """Number of samples."""
        return int(self.t.size)

    @property
    def dt(self) -> float:
        """Sample interval [s]."""
        return float((self.t[-1] - self.t[0]) / (self.n - 1))

    def index_at(self, time_s: float) -> int:
        """Index of the last sample at or before ``time_s`` [s] (clipped to the record)."""
        k = math.floor((float(time_s) - self.t[0]) / self.dt + 1e-9)
        return min(max(k, 0), self.n - 1)


def load_roll_csv(
    path: str | Path,
    *,
    time_column: str = "t",
    roll_column: str = "phi",
    rate_column: str = "phidot",
    excitation_column: str | None = None,
) -> RollRecord:
    """Read a roll record from a CSV file with a header row (lines starting with ``#`` skipped).

    Parameters
    ----------
    path : str or Path
        CSV file.
    time_column, roll_column, rate_column : str
        Names of the time [s], roll [rad] and roll-rate [rad/s] columns.
    excitation_column : str or None
        Optional input column (e.g. wave elevation at the ship [m]).

    Raises
    ------
    ValueError
        A missing column (the columns found are listed), a non-numeric cell (its line), a
        non-finite value, too few rows, or a non-increasing or non-uniform time column.
    """
    path = Path(path)
    with path.open(newline="", encoding="utf-8") as fh:
        lines = [(i + 1, line) for i, line in enumerate(fh) if not line.lstrip().startswith("#")]
    lines = [(i, line) for i, line in lines if line.strip()]
    if not lines:
        raise ValueError(f"{path}: no header row (the file is empty)")
    reader = csv.reader([line for _, line in lines])
    header = [h.strip() for h in next(reader)]
    wanted = {"time": time_column, "roll": roll_column, "rate": rate_column}
    if excitation_column is not None:
        wanted["excitation"] = excitation_column
    missing = [c for c in wanted.values() if c not in header]
    if missing:
        raise ValueError(f"{path}: missing column(s) {missing}; the header has {header}")
    index = {k: header.index(c) for k, c in wanted.items()}
    values: dict[str, list[float]] = {k: [] for k in wanted}
    for (line_no, _), row in zip(lines[1:], reader, strict=True):
        for key, col in index.items():
            try:
                values[key].append(float(row[col]))
            except (IndexError, ValueError) as exc:
                cell = row[col] if col < len(row) else "<missing>"
                raise ValueError(
                    f"{path}, line {line_no}: column {wanted[key]!r} is not a number ({cell!r})"
                ) from exc
    try:
        return RollRecord(
            t=np.array(values["time"]),
            roll=np.array(values["roll"]),
            roll_rate=np.array(values["rate"]),
            excitation=None if excitation_column is None else np.array(values["excitation"]),
            excitation_name=excitation_column,
        )
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from exc


def write_roll_csv(path: str | Path, record: RollRecord) -> Path:
    """Write a record as CSV (columns t, phi, phidot[, excitation name]), atomically."""
    from ship_gym.io_utils import atomic_write_text

    names = ["t", "phi", "phidot"]
    cols = [record.t, record.roll, record.roll_rate]
    if record.excitation is not None:
        names.append(record.excitation_name or "excitation")
        cols.append(record.excitation)
    rows = np.column_stack(cols)
    body = "\n".join(",".join(f"{v:.12g}" for v in row) for row in rows)
    return atomic_write_text(path, ",".join(names) + "\n" + body + "\n")


# ------------------------------------------------------------------ roll excitation input
# The physically meaningful input for K u(t − τ) in irregular waves: the linear wave roll moment
# (Froude–Krylov + diffraction) m(t) = Re Σ_j X₄(ω_j, β_j) a_j e^{−iθ_j(t)}, X₄ from the BEM
# database (per unit amplitude, capytaine's time convention x(t) = Re(X e^{−iωt}), crest at O at
# t = 0; ship_gym.hydro.database). With eq. 2 divided by the roll inertia, K ≈ 1/(I44 + A44(ωₙ)).
def roll_excitation_transfer(
    database: xr.Dataset, omega: npt.ArrayLike, heading: npt.ArrayLike, *, dof: str = "Roll"
) -> NDArray[np.complex128]:
    """Linear wave excitation X(ω, β) per unit amplitude of one DOF from a BEM database.

    X = Froude–Krylov + diffraction (the database's ``excitation_force``), body frame about O
    (:mod:`ship_gym.conventions`), capytaine's time convention: a wave ζ(O, t) = Re(a e^{−iωt})
    gives the moment Re(X a e^{−iωt}).

    Interpolation: linear in the real and imaginary parts, in ω and in β (headings completed to
    the full circle by :func:`ship_gym.hydro.database.mirror_headings` when needed, periodic in
    2π). Outside the database's finite frequencies (ω_min, ω_max): X(ω_min, β)(ω/ω_min)² below
    (wave-slope law of long waves, as :class:`ship_gym.forces.diffraction.Diffraction`), 0 above
    (short waves; the S175 database stops at 1.67 rad/s). A negative ω (an encounter frequency of
    a ship overtaking the waves) gives conj X(|ω|), the transfer function of a real system.

    Parameters
    ----------
    database : xarray.Dataset
        Hydrodynamic database with ``excitation_force`` (:func:`ship_gym.hydro.load_database`).
    omega : array_like
        Wave frequencies ω [rad/s].
    heading : array_like
        Relative wave headings β [rad] (π/2: waves travelling toward starboard); broadcasts with
        ``omega``.
    dof : str
        DOF label (``"Roll"``: X₄ [N·m/m]).

    Returns
    -------
    ndarray of complex
        X [N/m or N·m/m], shape ``broadcast(omega, heading)``.
    """
    from ship_gym.conventions import dof_index
    from ship_gym.hydro import as_arrays, mirror_headings

    w, b = np.broadcast_arrays(np.asarray(omega, dtype=float), np.asarray(heading, dtype=float))
    if not (np.all(np.isfinite(w)) and np.all(np.isfinite(b))):
        raise ValueError("omega [rad/s] and heading [rad] must be finite")
    i_dof = dof_index(dof)
    arrays = as_arrays(database)
    beta = np.mod(b, 2.0 * math.pi)
    grid = np.mod(arrays.wave_direction, 2.0 * math.pi)
    if np.any(beta < grid.min() - 1e-9) or np.any(beta > grid.max() + 1e-9):
        arrays = as_arrays(mirror_headings(database))
        grid = np.mod(arrays.wave_direction, 2.0 * math.pi)
    order = np.argsort(grid)
    grid, exc = grid[order], arrays.excitation_force[:, order, i_dof]  # (n_ω, n_β)
    if not np.all(np.isfinite(exc)):
        raise ValueError("the database's excitation_force holds NaN/inf at finite frequencies")
    # periodic heading axis: append the first heading one turn on
    grid = np.append(grid, grid[0] + 2.0 * math.pi)
    exc = np.concatenate([exc, exc[:, :1]], axis=1)
    beta = np.where(beta < grid[0], beta + 2.0 * math.pi, beta)
    j = np.clip(np.searchsorted(grid, beta, side="right"), 1, grid.size - 1)
    frac = np.clip((beta - grid[j - 1]) / (grid[j] - grid[j - 1]), 0.0, 1.0)
    w_grid = arrays.omega
    a = np.abs(w)
    a_in = np.clip(a, w_grid[0], w_grid[-1])
    k = np.clip(np.searchsorted(w_grid, a_in, side="right"), 1, w_grid.size - 1)
    s = (a_in - w_grid[k - 1]) / (w_grid[k] - w_grid[k - 1])
    out = np.zeros(w.shape, dtype=np.complex128)
    for dk, wk in ((k - 1, 1.0 - s), (k, s)):
        out += wk * ((1.0 - frac) * exc[dk, j - 1] + frac * exc[dk, j])
    out = np.where(a < w_grid[0], out * (a / w_grid[0]) ** 2, out)
    out = np.where(a > w_grid[-1] * (1.0 + 1e-12), 0.0, out)
    return np.where(w < 0.0, np.conj(out), out)


def _wave_frequency_from_encounter(
    omega_e: FloatArray, speed: float, heading: float, g: float
) -> FloatArray:
    """Invert ω_e = ω − ω² U cos β / g for ω ≥ 0 (unique when U cos β ≤ 0)."""
    c = speed * math.cos(heading) / g
    if abs(c) < 1e-15:
        return np.abs(omega_e)
    if c > 0.0:
        raise ValueError(
            f"the encounter-to-wave frequency mapping is not unique in following or quartering "
            f"seas with speed (U cos β = {speed * math.cos(heading):.4g} m/s > 0); use the "
            "component-wise roll_excitation_moment or a zero-speed record"
        )
    # c ω² − ω + ω_e = 0, the root that → ω_e as c → 0
    a = np.abs(omega_e)
    return 2.0 * a / (1.0 + np.sqrt(1.0 - 4.0 * c * a))


def roll_excitation_moment(
    wave_field: WaveField,
    database: xr.Dataset,
    t: npt.ArrayLike,
    *,
    ship_heading: float = 0.0,
    position: tuple[float, float] = (0.0, 0.0),
    forward_speed: float = 0.0,
    dof: str = "Roll",
) -> FloatArray:
    """Linear wave roll moment at the ship, synthesised component by component (exact input).

    For a known incident sea (a :class:`ship_gym.waves.wave_field.WaveField`, e.g. the
    Simulator's ``wave_field``), with the ship's origin O at (X₀, Y₀) + U t (cos ψ, sin ψ) in
    earth axes:

        m(t) = r(t) Re Σ_j X₄(ω_j, β_j) a_j e^{−iθ_j(t)},
        θ_j(t) = ω_e,j t + ε_j − k_j (X₀ cos χ_j + Y₀ sin χ_j),   β_j = χ_j − ψ,

    ω_e,j = ω_j − k_j U cos β_j the encounter frequency (:func:`ship_gym.kinematics.
    encounter_frequency`), r(t) the start-up ramp. Each term is the moment of the component
    whose elevation at O is Re(a_j e^{−iθ_j}) = a_j cos θ_j (the field's ζ), so the phases
    match the simulator's (:mod:`ship_gym.forces.diffraction`, phase mapping). X₄ is looked up
    at the wave frequency ω_j (the zero-speed transfer function of the component's spatial
    pattern, as :func:`ship_gym.hydro.rao.response_amplitude_operator` does), see
    :func:`roll_excitation_transfer` for the interpolation. Linear theory: the moment on the
    mean hull, not the simulator's moment on the instantaneous hull.

    Parameters
    ----------
    wave_field : WaveField
        Incident sea (amplitudes a_j [m], frequencies ω_j [rad/s], wavenumbers k_j [rad/m],
        directions χ_j [rad], phases ε_j [rad], ramp).
    database : xarray.Dataset
        Hydrodynamic database of the hull (:func:`ship_gym.hydro.load_database`).
    t : array_like
        Times [s] on the wave field's clock (the Simulator's ``SimulationResult.t``).
    ship_heading : float
        ψ [rad].
    position : tuple of float
        (X₀, Y₀) of O at t = 0 [m].
    forward_speed : float
        U [m/s].
    dof : str
        DOF of the moment (``"Roll"`` [N·m]).

    Returns
    -------
    ndarray, shape (n_t,)
        m(t) [N·m] (or [N] for a translational DOF).
    """
    from ship_gym.kinematics import encounter_frequency

    tt = np.atleast_1d(np.asarray(t, dtype=float))
    if tt.ndim != 1 or not np.all(np.isfinite(tt)):
        raise ValueError(f"t must be a finite 1-D array of times [s]; got shape {tt.shape}")
    for name, v in (("ship_heading", ship_heading), ("forward_speed", forward_speed)):
        if not math.isfinite(v):
            raise ValueError(f"{name} must be finite, got {v!r}")
    wf = wave_field
    beta = np.asarray(wf.direction) - ship_heading
    omega = np.asarray(wf.omega)
    w_e = encounter_frequency(omega, forward_speed, beta, wf.g)
    x = roll_excitation_transfer(database, omega, beta, dof=dof)
    x0, y0 = position
    eps = wf.phase - (wf.kx * x0 + wf.ky * y0)
    coef = x * np.asarray(wf.amplitude) * np.exp(-1j * eps)
    out = np.empty(tt.size)
    step = max(1, (1 << 20) // max(coef.size, 1))
    for i in range(0, tt.size, step):
        s = slice(i, i + step)
        out[s] = (np.exp(-1j * np.multiply.outer(tt[s], w_e)) @ coef).real
    return out * wf.ramp(tt)


def roll_excitation_from_elevation(
    elevation: npt.ArrayLike,
    dt: float,
    database: xr.Dataset,
    heading: float,
    *,
    forward_speed: float = 0.0,
    g: float | None = None,
    dof: str = "Roll",
) -> FloatArray:
    """Linear wave roll moment from a measured elevation record, by FFT filtering with X₄.

    What a user with only an elevation record at the ship can do:

        m = IFFT[ conj X₄(ω(f_k), β) · FFT[ζ](f_k) ],

    numpy's FFT having the e^{+iωt} kernel while X₄ is defined in the e^{−iωt} convention (hence
    the conjugate on the positive-frequency bins). Assumptions, to state with any result:

    * the elevation is the **incident** wave at the ship's origin O (not disturbed by the hull);
    * **long-crested** sea from one **known relative heading** β (a short-crested sea would need
      the directional spreading: one record cannot tell the directions apart);
    * **linear** superposition, and the record **periodic** (the FFT wraps around): the first and
      last ~ the impulse-response length of X₄ (tens of seconds for a ship's roll) carry
      wrap-around errors, unless the sea is periodic in the record (components on the FFT bins,
      where the filter is exact);
    * **zero speed**, or encounter mapping: a record measured on the moving ship oscillates at
      ω_e; ω is recovered from ω_e = ω − ω²U cos β/g, unique only for U cos β ≤ 0 (head to beam
      seas); following seas with speed raise ValueError.

    Parameters
    ----------
    elevation : array_like, shape (n,)
        ζ(O, t) [m], uniformly sampled.
    dt : float
        Sample interval [s].
    database : xarray.Dataset
        Hydrodynamic database (:func:`ship_gym.hydro.load_database`).
    heading : float
        Relative wave heading β [rad].
    forward_speed : float
        U [m/s].
    g : float or None
        Gravity [m/s²] (None: the database's ``attrs["g"]``, else standard gravity).
    dof : str
        DOF of the moment.

    Returns
    -------
    ndarray, shape (n,)
        m(t) [N·m].
    """
    from ship_gym.conventions import GRAVITY

    z = np.asarray(elevation, dtype=float)
    if z.ndim != 1 or z.size < 2 or not np.all(np.isfinite(z)):
        raise ValueError(f"elevation must be a finite 1-D record, got shape {z.shape}")
    if not (math.isfinite(dt) and dt > 0.0):
        raise ValueError(f"dt must be a positive sample interval [s], got {dt!r}")
    if not (math.isfinite(forward_speed) and math.isfinite(heading)):
        raise ValueError(f"heading and forward_speed must be finite, got {heading!r}, "
                         f"{forward_speed!r}")  # fmt: skip
    if g is None:
        g = float(getattr(database, "attrs", {}).get("g", GRAVITY))
    omega_e = 2.0 * math.pi * np.fft.rfftfreq(z.size, dt).astype(np.float64, copy=False)
    omega = _wave_frequency_from_encounter(omega_e, forward_speed, heading, g)
    x = roll_excitation_transfer(database, omega, heading, dof=dof)
    return np.fft.irfft(np.conj(x) * np.fft.rfft(z), n=z.size)


# ------------------------------------------------------------------------------------- model
@dataclass(frozen=True)
class McCueCampbellModel:
    """McCue & Campbell eq. 2 with an optional input term:

    ÿ + b_u1 ẏ + b_u3 ẏ³ + c_u1 y + c_u3 y³ = F_u sin(ωₑt + ε) + K u(t − τ).

    Attributes
    ----------
    b_u1 : float
        Linear damping [1/s].
    b_u3 : float
        Cubic damping [s/rad²].
    c_u1 : float
        Linear restoring [1/s²] (ωₙ² for small angles).
    c_u3 : float
        Cubic restoring [1/(rad² s²)].
    forcing_amplitude : float
        F_u [rad/s²].
    forcing_frequency : float
        ωₑ [rad/s] (known, not fitted; 0 without harmonic forcing).
    forcing_phase : float
        ε [rad].
    input_gain : float
        K [rad/s² per unit of the input, e.g. rad/(s² m)].
    input_lag : float
        τ [s].
    """

    b_u1: float
    b_u3: float
    c_u1: float
    c_u3: float
    forcing_amplitude: float = 0.0
    forcing_frequency: float = 0.0
    forcing_phase: float = 0.0
    input_gain: float = 0.0
    input_lag: float = 0.0

    @classmethod
    def from_vector(
        cls, values: Iterable[float], forcing_frequency: float = 0.0
    ) -> McCueCampbellModel:
        """Model from a vector in :data:`PARAMETER_NAMES` order."""
        kw = {k: float(v) for k, v in zip(PARAMETER_NAMES, values, strict=True)}
        return cls(**kw, forcing_frequency=float(forcing_frequency))

    def vector(self) -> FloatArray:
        """Parameters in :data:`PARAMETER_NAMES` order."""
        return np.array([getattr(self, k) for k in PARAMETER_NAMES], dtype=np.float64)

    def roll_equation(self) -> RollEquation:
        """The harmonic part as a :class:`RollEquation` (the input term is not included)."""
        return RollEquation.mccue_campbell(
            self.b_u1,
            self.b_u3,
            self.c_u1,
            self.c_u3,
            self.forcing_amplitude,
            self.forcing_frequency,
            self.forcing_phase,
        )

    @property
    def natural_frequency(self) -> float:
        """Small-angle natural frequency √c_u1 [rad/s] (NaN if c_u1 ≤ 0)."""
        return math.sqrt(self.c_u1) if self.c_u1 > 0.0 else math.nan

    def restoring(self, phi: npt.ArrayLike) -> FloatArray:
        """Stiffness curve c_u1 φ + c_u3 φ³ [rad/s²] at roll φ [rad]."""
        return self.roll_equation().restoring(phi)

    def damping(self, phidot: npt.ArrayLike) -> FloatArray:
        """Damping curve b_u1 φ̇ + b_u3 φ̇³ [rad/s²] at roll rate φ̇ [rad/s]."""
        return self.roll_equation().damping(phidot)

    def as_dict(self) -> dict[str, float]:
        """Parameters by name (and ωₑ, ωₙ) for reports."""
        out = {k: float(getattr(self, k)) for k in PARAMETER_NAMES}
        out["forcing_frequency"] = float(self.forcing_frequency)
        out["natural_frequency"] = self.natural_frequency
        return out


# ------------------------------------------------------------------------- piecewise layout
def piece_layout(n_samples: int, n_pieces: int) -> tuple[NDArray[np.int64], int]:
    """Start indices and length (in sample intervals) of the N pieces of eq. 3.

    The training samples 0 … n_samples − 1 are cut into N pieces of m = ⌊(n_samples − 1)/N⌋
    intervals each, piece j running from sample j·m to (j + 1)·m; the last
    (n_samples − 1) − N·m samples are not used.

    Raises
    ------
    ValueError
        If N < 1 or N > n_samples − 1 (a piece must span at least one interval).
    """
    n_pieces = int(n_pieces)
    if n_pieces < 1 or n_pieces > n_samples - 1:
        raise ValueError(
            f"n_pieces must be between 1 and the {n_samples - 1} sample intervals of the "
            f"training window, got {n_pieces}"
        )
    m = (n_samples - 1) // n_pieces
    return np.arange(n_pieces, dtype=np.int64) * m, m


class _InputTable:
    """Callable moment K·u(t − τ) for :meth:`RollEquation.integrate`, looked up from a table of
    the (linearly interpolated) input at the RK4 half steps of each piece."""

    def __init__(
        self, record: RollRecord, starts: NDArray[np.int64], n_steps: int, h: float, t0: float
    ) -> None:
        assert record.excitation is not None
        self.excitation = record.excitation
        self.half_times = record.t[starts][None, :] + 0.5 * h * np.arange(2 * n_steps + 1)[:, None]
        self.t0 = t0
        self.two_over_h = 2.0 / h
        self.record = record
        self.table = np.zeros_like(self.half_times)
        self.lag: float | None = None

    def set(self, gain: float, lag: float) -> None:
        if self.lag != lag:
            rec = self.record
            self.unit = np.interp(self.half_times - lag, rec.t, self.excitation)
            self.lag = lag
        self.table = gain * self.unit

    def __call__(self, t: float, phi: FloatArray, phidot: FloatArray) -> FloatArray:
        return self.table[round((t - self.t0) * self.two_over_h)]


@dataclass(frozen=True)
class _Problem:
    record: RollRecord
    starts: NDArray[np.int64]
    steps_per_piece: int  # in sample intervals
    substeps: int
    compare: Compare
    rate_weight: float
    stop_at: float

    @property
    def h(self) -> float:
        return self.record.dt / self.substeps

    def integrate(self, model: McCueCampbellModel, table: _InputTable | None) -> RollTrajectory:
        rec = self.record
        n_steps = self.steps_per_piece * self.substeps
        eq = model.roll_equation()
        moment = None
        if table is not None:
            table.set(model.input_gain, model.input_lag)
            moment = table
        # piece j starts at t_j: sin(ωₑ(t_j + s) + ε) = sin(ωₑ s + (ε + ωₑ t_j)), local time s
        phase = model.forcing_phase + model.forcing_frequency * rec.t[self.starts]
        with np.errstate(over="ignore", invalid="ignore"):
            return eq.integrate(
                rec.roll[self.starts],
                rec.roll_rate[self.starts],
                n_steps * self.h,
                self.h,
                moment=moment,
                t0=0.0,
                stop_at=self.stop_at,
                record_every=self.substeps if self.compare == "all" else None,
                forcing_phase=phase,
            )

    def errors(self, model: McCueCampbellModel, table: _InputTable | None) -> FloatArray:
        """‖⟨y, ẏ⟩ − ⟨φ, φ̇⟩‖ per piece (end point, or summed over the piece's samples)."""
        traj = self.integrate(model, table)
        rec = self.record
        m = self.steps_per_piece
        if self.compare == "all":
            idx = self.starts[None, :] + np.arange(1, m + 1)[:, None]
            y, v = traj.phi[1:], traj.phidot[1:]
        else:
            idx = (self.starts + m)[None, :]
            y, v = traj.phi[-1:], traj.phidot[-1:]
        with np.errstate(over="ignore", invalid="ignore"):
            d = np.hypot(y - rec.roll[idx], self.rate_weight * (v - rec.roll_rate[idx]))
        d = np.where(np.isfinite(d), d, 10.0 * self.stop_at)
        return d.sum(axis=0)


def _problem(
    record: RollRecord,
    n_pieces: int,
    train_end: float | None,
    substeps: int,
    compare: Compare,
    rate_weight: float,
) -> _Problem:
    if compare not in ("endpoint", "all"):
        raise ValueError(f"compare must be 'endpoint' or 'all', got {compare!r}")
    if int(substeps) != substeps or substeps < 1:
        raise ValueError(f"substeps must be a positive integer, got {substeps!r}")
    if not (np.isfinite(rate_weight) and rate_weight > 0.0):
        raise ValueError(f"rate_weight must be a positive number, got {rate_weight!r}")
    n_train = record.n if train_end is None else _train_samples(record, train_end)
    starts, m = piece_layout(n_train, n_pieces)
    # capsize guard: pieces of a diverging trial model are stopped (state held) far outside
    # the data, so the error stays finite and the simplex is pushed back
    scale = float(np.max(np.abs(record.roll)))
    return _Problem(
        record, starts, m, int(substeps), compare, float(rate_weight), max(10.0 * scale, 1.0)
    )


def _train_samples(record: RollRecord, train_end: float) -> int:
    if not np.isfinite(train_end) or train_end <= record.t[0]:
        raise ValueError(
            f"train_end must lie after the record's start t = {record.t[0]!r} s, got {train_end!r}"
        )
    return record.index_at(train_end) + 1


def piecewise_error(
    model: McCueCampbellModel,
    record: RollRecord,
    n_pieces: int,
    *,
    train_end: float | None = None,
    substeps: int = 1,
    compare: Compare = "endpoint",
    rate_weight: float = 1.0,
) -> float:
    """McCue & Campbell eq. 3: Σ_j ‖⟨y, ẏ⟩_j − ⟨φ, φ̇⟩_j‖ over N piecewise integrations.

    Parameters
    ----------
    model : McCueCampbellModel
        Trial equation.
    record : RollRecord
        Data (its input column is used when ``model.input_gain`` ≠ 0).
    n_pieces : int
        N.
    train_end : float or None
        Last time of the window used [s] (None: the whole record).
    substeps : int
        RK4 steps per sample interval.
    compare : {"endpoint", "all"}
        Compare at the piece end points (eq. 3) or at every sample of each piece.
    rate_weight : float
        w in ‖(Δy, w Δẏ)‖ [s].

    Returns
    -------
    float
        E [rad] (with the default w = 1, rad and rad/s are added as in the paper).
    """
    prob = _problem(record, n_pieces, train_end, substeps, compare, rate_weight)
    table = _table_for(prob, model.input_gain != 0.0)
    return float(prob.errors(model, table).sum())


def _table_for(prob: _Problem, needed: bool) -> _InputTable | None:
    if not needed:
        return None
    if prob.record.excitation is None:
        raise ValueError("the model has an input term but the record has no excitation column")
    return _InputTable(prob.record, prob.starts, prob.steps_per_piece * prob.substeps, prob.h, 0.0)


# ------------------------------------------------------------------- equation-error estimate
def _shifted(record: RollRecord, lag: float) -> FloatArray:
    assert record.excitation is not None
    return np.interp(record.t - lag, record.t, record.excitation)


def equation_error_estimate(
    record: RollRecord,
    omega: float | None,
    *,
    train_end: float | None = None,
    fit_phase: bool = False,
    use_input: bool = False,
    lags: npt.ArrayLike | float = 0.0,
) -> McCueCampbellModel:
    """Linear least-squares fit of eq. 2 to the data (equation error), the simplex's start.

    φ̈ is the second-order finite difference of the recorded φ̇; the regression
    φ̈ = −b_u1 φ̇ − b_u3 φ̇³ − c_u1 φ − c_u3 φ³ + A sin ωₑt [+ B cos ωₑt] [+ K u(t − τ)]
    is solved over the training window (F_u = A, or F_u = √(A² + B²), ε = atan2(B, A) with
    ``fit_phase``). With an input, each lag τ of ``lags`` is tried and the best kept.

    Parameters
    ----------
    record : RollRecord
        Data.
    omega : float or None
        ωₑ [rad/s]; None for no harmonic term.
    train_end : float or None
        End of the window [s] (None: whole record).
    fit_phase : bool
        Include the cos ωₑt column (a forcing phase).
    use_input : bool
        Include the input column K u(t − τ).
    lags : array_like or float
        Lags τ [s] tried for the input.

    Returns
    -------
    McCueCampbellModel
    """
    n = record.n if train_end is None else _train_samples(record, train_end)
    t = record.t[:n]
    y = record.roll[:n]
    v = record.roll_rate[:n]
    acc = np.gradient(record.roll_rate, record.t)[:n]
    base = [-v, -(v**3), -y, -(y**3)]
    if omega is not None:
        base.append(np.sin(omega * t))
        if fit_phase:
            base.append(np.cos(omega * t))
    if use_input and record.excitation is None:
        raise ValueError("use_input needs a record with an excitation column")
    best: tuple[float, FloatArray, float] | None = None
    for lag in np.atleast_1d(np.asarray(lags, dtype=np.float64)) if use_input else [0.0]:
        cols = list(base)
        if use_input:
            cols.append(_shifted(record, float(lag))[:n])
        a = np.column_stack(cols)
        scale = np.maximum(np.abs(a).max(axis=0), 1e-300)
        coef, *_ = np.linalg.lstsq(a / scale, acc, rcond=None)
        coef = coef / scale
        res = float(np.sum((a @ coef - acc) ** 2))
        if best is None or res < best[0]:
            best = (res, coef, float(lag))
    assert best is not None
    _, coef, lag = best
    b1, b3, c1, c3 = (float(c) for c in coef[:4])
    k = 4
    amplitude = phase = 0.0
    if omega is not None:
        amplitude = float(coef[k])
        k += 1
        if fit_phase:
            amplitude, phase = math.hypot(coef[k - 1], coef[k]), math.atan2(coef[k], coef[k - 1])
            k += 1
    gain = float(coef[k]) if use_input else 0.0
    return McCueCampbellModel(
        b1,
        b3,
        c1,
        c3,
        forcing_amplitude=amplitude,
        forcing_frequency=0.0 if omega is None else float(omega),
        forcing_phase=phase,
        input_gain=gain,
        input_lag=lag if use_input else 0.0,
    )


# ------------------------------------------------------------------------------ identification
@dataclass(frozen=True, eq=False)
class IdentificationResult:
    """Outcome of :func:`identify_roll_equation`.

    Attributes
    ----------
    model : McCueCampbellModel
        Fitted equation.
    initial_model : McCueCampbellModel
        Start of the simplex search.
    free_parameters : tuple of str
        Names of the fitted parameters (the others are held at the initial model's values).
    objective : float
        Eq. 3 at the fitted model [rad] (w = 1: rad and rad/s added).
    initial_objective : float
        Eq. 3 at the start.
    piece_errors : ndarray, shape (N,)
        Per-piece error at the fitted model.
    n_pieces : int
        N.
    steps_per_piece : int
        m, sample intervals per piece.
    train_end : float
        Time of the last sample of the training window [s] (the last
        ``unused_samples`` of it fall after the last piece).
    unused_samples : int
        Training samples after the end of the last piece (N·m intervals are used).
    compare : str
        ``"endpoint"`` (eq. 3) or ``"all"``.
    n_evaluations : int
        Objective evaluations (all simplex restarts).
    converged : bool
        The last simplex search met its tolerances.
    message : str
        scipy's message of the last search.
    cpu_time : float
        Process CPU time of the fit [s].
    """

    model: McCueCampbellModel
    initial_model: McCueCampbellModel
    free_parameters: tuple[str, ...]
    objective: float
    initial_objective: float
    piece_errors: FloatArray
    n_pieces: int
    steps_per_piece: int
    train_end: float
    unused_samples: int
    compare: str
    n_evaluations: int
    converged: bool
    message: str
    cpu_time: float

    def as_dict(self) -> dict:
        """JSON-ready summary."""
        return {
            "model": self.model.as_dict(),
            "initial_model": self.initial_model.as_dict(),
            "free_parameters": list(self.free_parameters),
            "objective": self.objective,
            "initial_objective": self.initial_objective,
            "n_pieces": self.n_pieces,
            "steps_per_piece": self.steps_per_piece,
            "train_end": self.train_end,
            "unused_samples": self.unused_samples,
            "compare": self.compare,
            "n_evaluations": self.n_evaluations,
            "converged": self.converged,
            "message": self.message,
            "cpu_time_s": self.cpu_time,
        }


def _reference_scales(record: RollRecord, n: int, omega: float | None) -> dict[str, float]:
    """Magnitudes that make each parameter's term comparable to φ̈ (the simplex's units)."""
    y = record.roll[:n]
    v = record.roll_rate[:n]
    y_max = max(float(np.max(np.abs(y))), 1e-6)
    v_max = max(float(np.max(np.abs(v))), 1e-6)
    w = v_max / y_max if omega is None else float(omega)
    out = {
        "b_u1": w,
        "b_u3": w / v_max**2,
        "c_u1": w**2,
        "c_u3": w**2 / y_max**2,
        "forcing_amplitude": w**2 * y_max,
        "forcing_phase": 1.0,
        "input_gain": 0.0,
        "input_lag": 1.0 / w,
    }
    if record.excitation is not None:
        u_max = max(float(np.max(np.abs(record.excitation[:n]))), 1e-12)
        out["input_gain"] = w**2 * y_max / u_max
    return out


def identify_roll_equation(
    record: RollRecord,
    *,
    omega: float | None,
    n_pieces: int = 50,
    train_end: float | None = None,
    fit_phase: bool = False,
    use_input: bool | None = None,
    fit_input_lag: bool = False,
    lag_grid: npt.ArrayLike | None = None,
    initial: McCueCampbellModel | None = None,
    compare: Compare = "endpoint",
    rate_weight: float = 1.0,
    substeps: int = 1,
    simplex_step: float = 0.1,
    xatol: float = 1e-7,
    max_evaluations: int = 4000,
    restarts: int = 2,
    progress: bool = False,
) -> IdentificationResult:
    """Fit McCue & Campbell's eq. 2 to a roll record by Nelder–Mead on eq. 3.

    Parameters
    ----------
    record : RollRecord
        Data; the fit uses t ≤ ``train_end``.
    omega : float or None
        Known encounter frequency ωₑ [rad/s] of the harmonic forcing F_u sin(ωₑt + ε); None
        drops the harmonic term (input-driven or free-decay fits).
    n_pieces : int
        N of eq. 3.
    train_end : float or None
        End of the training window [s] (None: the whole record).
    fit_phase : bool
        Fit ε (the paper does not: its forcing clock is the data's).
    use_input : bool or None
        Include K u(t − τ) from the record's excitation column (None: when the record has one).
    fit_input_lag : bool
        Fit τ (otherwise τ stays at the start value: the least-squares best of ``lag_grid``, or
        ``initial.input_lag``).
    lag_grid : array_like or None
        Lags τ [s] tried by the least-squares start (default: 41 values over ±half the mean roll
        period of the data).
    initial : McCueCampbellModel or None
        Start of the search (None: :func:`equation_error_estimate`).
    compare : {"endpoint", "all"}
        Error at the piece end points (eq. 3) or at every sample of each piece.
    rate_weight : float
        w in ‖(Δy, w Δẏ)‖ [s].
    substeps : int
        RK4 steps per sample interval.
    simplex_step : float
        Initial simplex edge, as a fraction of each parameter's scale (its start value, or a
        data-based reference magnitude when the start is near zero).
    xatol : float
        Simplex size at convergence, in those scaled units (≈ relative parameter change).
    max_evaluations : int
        Objective evaluations per simplex search.
    restarts : int
        Extra searches restarted from the best point with a fresh simplex (Nelder–Mead can
        stall on a collapsed simplex); stops early when a restart gains < 1e-9 relative.
    progress : bool
        Show a tqdm bar of the evaluations.

    Returns
    -------
    IdentificationResult
    """
    from scipy.optimize import minimize

    cpu0 = time.process_time()
    if omega is not None and not (np.isfinite(omega) and omega > 0.0):
        raise ValueError(f"omega must be a positive encounter frequency [rad/s], got {omega!r}")
    if use_input is None:
        use_input = record.excitation is not None
    if use_input and record.excitation is None:
        raise ValueError("use_input=True needs a record with an excitation column")
    if fit_input_lag and not use_input:
        raise ValueError("fit_input_lag needs the input term (use_input)")
    if fit_phase and omega is None:
        raise ValueError("fit_phase needs the harmonic forcing (omega)")
    prob = _problem(record, n_pieces, train_end, substeps, compare, rate_weight)
    n_train = record.n if train_end is None else _train_samples(record, train_end)
    scales = _reference_scales(record, n_train, omega)
    if initial is None:
        if lag_grid is None:
            half_period = math.pi / scales["b_u1"]
            lag_grid = np.linspace(-half_period, half_period, 41)
        initial = equation_error_estimate(
            record,
            omega,
            train_end=record.t[n_train - 1],
            fit_phase=fit_phase,
            use_input=use_input,
            lags=lag_grid if use_input else 0.0,
        )
    if omega is not None:
        initial = dataclasses.replace(initial, forcing_frequency=float(omega))
    free = ["b_u1", "b_u3", "c_u1", "c_u3"]
    if omega is not None:
        free.append("forcing_amplitude")
    if fit_phase:
        free.append("forcing_phase")
    if use_input:
        free.append("input_gain")
    if fit_input_lag:
        free.append("input_lag")
    if not use_input:
        initial = dataclasses.replace(initial, input_gain=0.0, input_lag=0.0)
    if omega is None:
        initial = dataclasses.replace(initial, forcing_amplitude=0.0, forcing_phase=0.0)
    free_idx = [PARAMETER_NAMES.index(k) for k in free]
    p0 = initial.vector()
    scale = np.array([max(abs(p0[i]), 0.1 * scales[PARAMETER_NAMES[i]], 1e-12) for i in free_idx])
    table = _table_for(prob, use_input)
    w_e = 0.0 if omega is None else float(omega)

    def model_of(x: FloatArray) -> McCueCampbellModel:
        p = p0.copy()
        p[free_idx] = x * scale
        return McCueCampbellModel.from_vector(p, forcing_frequency=w_e)

    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=max_evaluations * (restarts + 1), desc="Nelder-Mead", unit="eval")
    n_eval = 0

    def objective(x: FloatArray) -> float:
        nonlocal n_eval
        n_eval += 1
        if bar is not None:
            bar.update(1)
        return float(prob.errors(model_of(x), table).sum())

    x = p0[free_idx] / scale
    f0 = objective(x)
    f_best = f0
    res = None
    for attempt in range(restarts + 1):
        simplex = np.vstack([x, x + simplex_step * np.eye(x.size)])
        res = minimize(
            objective,
            x,
            method="Nelder-Mead",
            options={
                "initial_simplex": simplex,
                "xatol": xatol,
                "fatol": 1e-12 * max(f_best, 1e-300),
                "maxfev": max_evaluations,
            },
        )
        gain = (f_best - res.fun) / max(f_best, 1e-300)
        if res.fun <= f_best:
            x, f_best = res.x, float(res.fun)
        if attempt > 0 and gain < 1e-9:
            break
    if bar is not None:
        bar.close()
    assert res is not None
    model = model_of(x)
    errors = prob.errors(model, table)
    return IdentificationResult(
        model=model,
        initial_model=initial,
        free_parameters=tuple(free),
        objective=float(errors.sum()),
        initial_objective=f0,
        piece_errors=errors,
        n_pieces=int(prob.starts.size),
        steps_per_piece=prob.steps_per_piece,
        train_end=float(record.t[n_train - 1]),
        unused_samples=n_train - 1 - int(prob.starts[-1] + prob.steps_per_piece),
        compare=compare,
        n_evaluations=n_eval,
        converged=bool(res.success),
        message=str(res.message),
        cpu_time=time.process_time() - cpu0,
    )


# ---------------------------------------------------------------------------------- prediction
@dataclass(frozen=True)
class WindowError:
    """Agreement of a free-run prediction with the data over one time window.

    Attributes
    ----------
    t_start, t_end : float
        Window [s].
    rmse_roll : float
        Root-mean-square roll error [rad].
    nrmse_roll : float
        rmse_roll / standard deviation of the data's roll in the window [-].
    correlation_roll : float
        Pearson correlation of predicted and recorded roll [-].
    max_error_roll : float
        Largest |roll error| [rad].
    rmse_rate : float
        RMS roll-rate error [rad/s].
    nrmse_rate : float
        rmse_rate / standard deviation of the recorded roll rate [-].
    std_roll_data, std_roll_model : float
        Standard deviations of the recorded and predicted roll [rad].
    """

    t_start: float
    t_end: float
    rmse_roll: float
    nrmse_roll: float
    correlation_roll: float
    max_error_roll: float
    rmse_rate: float
    nrmse_rate: float
    std_roll_data: float
    std_roll_model: float


def _window_error(
    t: FloatArray, y: FloatArray, v: FloatArray, phi: FloatArray, phidot: FloatArray
) -> WindowError:
    with np.errstate(invalid="ignore", over="ignore"):
        e = y - phi
        ev = v - phidot
        s_phi = float(np.std(phi))
        s_v = float(np.std(phidot))
        rmse = float(np.sqrt(np.mean(e**2)))
        rmse_v = float(np.sqrt(np.mean(ev**2)))
        corr = (
            float(np.corrcoef(y, phi)[0, 1])
            if np.all(np.isfinite(y)) and np.std(y) > 0 and s_phi > 0
            else math.nan
        )
        return WindowError(
            t_start=float(t[0]),
            t_end=float(t[-1]),
            rmse_roll=rmse,
            nrmse_roll=rmse / s_phi if s_phi > 0 else math.nan,
            correlation_roll=corr,
            max_error_roll=float(np.max(np.abs(e))),
            rmse_rate=rmse_v,
            nrmse_rate=rmse_v / s_v if s_v > 0 else math.nan,
            std_roll_data=s_phi,
            std_roll_model=float(np.std(y)),
        )


@dataclass(frozen=True, eq=False)
class RollPrediction:
    """Free integration of a fitted model from one data point over the rest of the record.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Times [s] (the record's, from the start point on).
    roll, roll_rate : ndarray, shape (n,)
        Predicted roll [rad] and roll rate [rad/s] (held after a divergence).
    start_time : float
        Where the free run starts from the data [s].
    train_end : float
        End of the training window [s].
    fit_window : WindowError or None
        Agreement over [start_time, train_end] (None if the run starts at train_end).
    prediction_window : WindowError or None
        Agreement over (train_end, end] (None if the record ends at train_end).
    diverged : bool
        |y| left 10 × the data's largest roll (a capsize of the model).
    """

    t: FloatArray
    roll: FloatArray
    roll_rate: FloatArray
    start_time: float
    train_end: float
    fit_window: WindowError | None
    prediction_window: WindowError | None
    diverged: bool

    def as_dict(self) -> dict:
        """JSON-ready summary (windows only, no series)."""
        return {
            "start_time": self.start_time,
            "train_end": self.train_end,
            "fit_window": None if self.fit_window is None else vars(self.fit_window),
            "prediction_window": (
                None if self.prediction_window is None else vars(self.prediction_window)
            ),
            "diverged": self.diverged,
        }


def predict_roll(
    model: McCueCampbellModel,
    record: RollRecord,
    *,
    train_end: float,
    start_time: float | None = None,
    substeps: int = 1,
) -> RollPrediction:
    """Integrate the fitted equation freely from the data point at ``start_time``.

    The paper's figures start at the first data point and run over the training window and the
    500 s beyond; ``start_time=train_end`` predicts only beyond the training window.

    Parameters
    ----------
    model : McCueCampbellModel
        Fitted equation.
    record : RollRecord
        Data (initial state, the input column, and the reference for the errors).
    train_end : float
        End of the training window [s].
    start_time : float or None
        Start of the free run [s] (None: the record's start).
    substeps : int
        RK4 steps per sample interval.

    Returns
    -------
    RollPrediction
    """
    i0 = 0 if start_time is None else record.index_at(start_time)
    if i0 >= record.n - 1:
        raise ValueError(f"start_time {start_time!r} s leaves nothing to predict")
    prob = _Problem(
        record,
        np.array([i0], dtype=np.int64),
        record.n - 1 - i0,
        int(substeps),
        "all",
        1.0,
        max(10.0 * float(np.max(np.abs(record.roll))), 1.0),
    )
    table = None
    if model.input_gain != 0.0:
        table = _table_for(prob, True)
    traj = prob.integrate(model, table)
    y = traj.phi[:, 0]
    v = traj.phidot[:, 0]
    t = record.t[i0:]
    k_end = record.index_at(train_end)
    fit = pred = None
    if k_end > i0:
        s = slice(0, k_end - i0 + 1)
        fit = _window_error(t[s], y[s], v[s], record.roll[i0 : k_end + 1],
                            record.roll_rate[i0 : k_end + 1])  # fmt: skip
    if k_end < record.n - 1:
        s = slice(max(k_end + 1 - i0, 0), None)
        k1 = max(k_end + 1, i0)
        pred = _window_error(t[s], y[s], v[s], record.roll[k1:], record.roll_rate[k1:])
    return RollPrediction(
        t=t,
        roll=y,
        roll_rate=v,
        start_time=float(t[0]),
        train_end=float(record.t[k_end]),
        fit_window=fit,
        prediction_window=pred,
        diverged=bool(np.any(traj.capsized)),
    )


# ------------------------------------------------------------------------------------- plots
def plot_time_history(
    ax: Axes,
    record: RollRecord,
    prediction: RollPrediction,
    *,
    title: str = "",
    degrees: bool = True,
) -> None:
    """Recorded and predicted roll against time, the training window shaded."""
    k = 180.0 / math.pi if degrees else 1.0
    ax.plot(record.t, k * record.roll, color="0.2", lw=1.0, label="data")
    ax.plot(prediction.t, k * prediction.roll, color="C3", lw=1.0, ls="--", label="fitted eq. 2")
    ax.axvspan(record.t[0], prediction.train_end, color="C0", alpha=0.08, label="training")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("roll [deg]" if degrees else "roll [rad]")
    if title:
        ax.set_title(title, fontsize=9)
    ax.legend(loc="upper right", fontsize=7)
    ax.grid(alpha=0.3)


def plot_curves(
    axes: Sequence[Axes],
    model: McCueCampbellModel,
    record: RollRecord,
    *,
    truth: RollEquation | None = None,
    train_end: float | None = None,
    phi_max: float | None = None,
    phidot_max: float | None = None,
) -> None:
    """Stiffness (restoring) and damping curves of the fitted model, and the truth if known.

    The ranges of roll and roll rate covered by the training data are shaded (the fit is only
    meaningful inside them, McCue & Campbell fig. 2).
    """
    n = record.n if train_end is None else record.index_at(train_end) + 1
    y_rng = float(np.max(np.abs(record.roll[:n])))
    v_rng = float(np.max(np.abs(record.roll_rate[:n])))
    phi = np.linspace(-1, 1, 401) * (phi_max or 2.0 * y_rng)
    phidot = np.linspace(-1, 1, 401) * (phidot_max or 2.0 * v_rng)
    for ax, x, fit, true, rng, label in (
        (axes[0], phi, model.restoring(phi), None if truth is None else truth.restoring(phi),
         y_rng, "roll φ [rad]"),
        (axes[1], phidot, model.damping(phidot),
         None if truth is None else truth.damping(phidot), v_rng, "roll rate φ̇ [rad/s]"),
    ):  # fmt: skip
        if true is not None:
            ax.plot(x, true, color="0.2", lw=1.2, label="true")
        ax.plot(x, fit, color="C3", lw=1.2, ls="--", label="fitted")
        ax.axvspan(-rng, rng, color="C0", alpha=0.08, label="data range")
        ax.set_xlabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("restoring [rad/s²]")
    axes[1].set_ylabel("damping [rad/s²]")
