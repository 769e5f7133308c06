"""McCue & Campbell: identification of a nonlinear roll equation — the reproduction's numbers.

Part 1 (:func:`part1`): their demonstration. The Edith Terkol equation (their eq. 1, with the
odd reading c₄|φ|φ³; :meth:`ship_gym.roll.equation.RollEquation.edith_terkol`) with F = 0.0195,
ωₑ = 0.527 is integrated for 1000 s (RK4, dt = 0.1 s) from ⟨φ₀, φ̇₀⟩ = (0, 0), (0.4, 0) and
(−0.4, −0.35). Their eq. 2 (linear + cubic damping and stiffness, F_u sin ωₑt) is fitted on
0–500 s by Nelder–Mead on the piecewise error of their eq. 3 for several numbers of pieces N
(:func:`fit_case`); the N whose fitted equation, run freely from the first data point, best
reproduces the *training* window is kept. Also: the paper's coefficients run on our data, the
cross-predictions of their figs. 5–6 (:func:`cross_predictions`) and the safe basins of their
fig. 8 (:func:`safe_basins`).

Part 2 (:func:`sixdof_study`): the extension the paper's conclusion points to. The S175 of the
6-DOF simulator (Holloway, dt = 0.05 s, zero speed, heave/roll/pitch free) in long-crested beam
seas (JONSWAP Hs 4 m, Tp 10 s, 100 components, seed 1) is recorded for 1000 s
(:func:`simulate_s175`); eq. 2 with the harmonic term replaced by K u(t − τ) is identified on the
first 600 s and run freely over the remaining 400 s (:func:`fit_input`), for three inputs u
(:data:`SIX_INPUTS`).

The method itself is :mod:`ship_gym.analysis.identification`; ``scripts/reproduce_mccue.py``
writes ``docs/mccue/results.json``, the CSV table and the figures from these results.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ship_gym.analysis import identification as ident
from ship_gym.roll.equation import RollEquation
from ship_gym.typing import FloatArray

__all__ = [
    "DT",
    "DURATION",
    "INITIAL_CONDITIONS",
    "OMEGA_E",
    "PIECES",
    "SIX_DT",
    "SIX_DURATION",
    "SIX_EDGE",
    "SIX_HS",
    "SIX_INPUTS",
    "SIX_PIECES",
    "SIX_SEED",
    "SIX_SETTLE",
    "SIX_TP",
    "SIX_TRAIN",
    "TRAIN_END",
    "F",
    "FitCase",
    "FitScan",
    "InputFit",
    "InputScan",
    "Part1",
    "SixDofStudy",
    "coefficient_rows",
    "cross_predictions",
    "fit_case",
    "fit_input",
    "ic_label",
    "paper_model",
    "part1",
    "safe_basins",
    "simulate_s175",
    "sixdof_study",
]

Log = Callable[[str], None]

F = 0.0195
"""Forcing amplitude of the data [rad/s²]."""
OMEGA_E = 0.85 * 0.62
"""Encounter frequency [rad/s]."""
DT = 0.1
"""Sample interval and RK4 step [s]."""
DURATION = 1000.0
"""Length of the data records [s]."""
TRAIN_END = 500.0
"""End of the training window [s]."""
INITIAL_CONDITIONS = ((0.0, 0.0), (0.4, 0.0), (-0.4, -0.35))
"""The paper's initial conditions ⟨φ₀ [rad], φ̇₀ [rad/s]⟩."""
PIECES = (1, 2, 5, 10, 20, 50, 100, 250)
"""Numbers of pieces N of eq. 3 scanned in part 1."""

SIX_HS, SIX_TP, SIX_SEED = 4.0, 10.0, 1
"""Part 2 sea: significant height [m], peak period [s], seed."""
SIX_DT = 0.05
"""Part 2 simulator time step [s]."""
SIX_SETTLE, SIX_DURATION, SIX_TRAIN = 100.0, 1000.0, 600.0
"""Part 2 start-up before the record, record length, end of the training window [s]."""
SIX_PIECES = (50, 100, 200)
"""Numbers of pieces N scanned in part 2."""
SIX_INPUTS = {
    "excitation": "roll excitation moment m(t), component-wise from the wave field [N·m]",
    "excitation_fft": "roll excitation moment from the elevation record, FFT-filtered by X₄ [N·m]",
    "elevation": "incident-wave elevation η(t) at the ship's origin [m]",
}
"""Part 2 inputs u(t) and their descriptions."""
SIX_EDGE = 50.0
"""Ends of the record left out when comparing the FFT path with the exact one [s]."""


def _silent(_: str) -> None:
    pass


def _win(window: ident.WindowError | None) -> ident.WindowError:
    """The error measures of a window that is known to exist (the record covers both)."""
    if window is None:
        raise ValueError("the record does not cover the fit and prediction windows")
    return window


def ic_label(ic: tuple[float, float]) -> str:
    """Text label ⟨φ₀, φ̇₀⟩ of an initial condition."""
    return f"⟨{ic[0]:g}, {ic[1]:g}⟩"


def paper_model(ic: tuple[float, float]) -> ident.McCueCampbellModel:
    """McCue & Campbell's published eq. 2 coefficients for one initial condition."""
    b1, b3, c1, c3, f = ident.MCCUE_CAMPBELL_FITS[ic]
    return ident.McCueCampbellModel(b1, b3, c1, c3, f, OMEGA_E)


def _steady_amplitude(t: FloatArray, roll: FloatArray, t_from: float = 500.0) -> float:
    """Largest |roll| after t_from [rad] (the steady-state amplitude of figs. 5–6)."""
    return float(np.max(np.abs(roll[t >= t_from])))


# ---------------------------------------------------------------------------------- part 1
@dataclass(frozen=True)
class FitScan:
    """One fit of eq. 2 (one N) and its free run from t = 0.

    Attributes
    ----------
    result : IdentificationResult
        The identification.
    prediction : RollPrediction
        The fitted equation run freely from the first data point.
    fit_nrmse : float
        Roll NRMSE of the free run over the training window [-].
    """

    result: ident.IdentificationResult
    prediction: ident.RollPrediction
    fit_nrmse: float


@dataclass(frozen=True)
class FitCase:
    """Data from eq. 1 for one initial condition, the fits of eq. 2 and the paper's set.

    Attributes
    ----------
    ic : tuple of float
        Initial condition ⟨φ₀ [rad], φ̇₀ [rad/s]⟩.
    truth : RollEquation
        The data's equation (Edith Terkol, eq. 1).
    record : RollRecord
        The data, 0–1000 s.
    n_train : int
        Samples in the training window.
    scans : tuple of FitScan
        One fit per N scanned.
    best : FitScan
        The selected fit (smallest free-run NRMSE over the training window, not diverged).
    paper : McCueCampbellModel
        The paper's coefficients.
    paper_prediction : RollPrediction
        The paper's equation run freely on our data.
    paper_objective : float
        Eq. 3 error of the paper's coefficients at the selected N [rad, rad/s].
    data_range : tuple of float
        Largest |φ| [rad] and |φ̇| [rad/s] in the training window.
    """

    ic: tuple[float, float]
    truth: RollEquation
    record: ident.RollRecord
    n_train: int
    scans: tuple[FitScan, ...]
    best: FitScan
    paper: ident.McCueCampbellModel
    paper_prediction: ident.RollPrediction
    paper_objective: float
    data_range: tuple[float, float]


def fit_case(
    ic: tuple[float, float],
    pieces: tuple[int, ...],
    *,
    duration: float = DURATION,
    train_end: float = TRAIN_END,
    max_evaluations: int = 3000,
    log: Log = _silent,
) -> FitCase:
    """Data from eq. 1, fits of eq. 2 for each N, the selected fit, the paper's coefficients.

    Parameters
    ----------
    ic : tuple of float
        Initial condition ⟨φ₀ [rad], φ̇₀ [rad/s]⟩ (a key of
        :data:`~ship_gym.analysis.identification.MCCUE_CAMPBELL_FITS`).
    pieces : tuple of int
        Numbers of pieces N scanned.
    duration : float
        Length of the data record [s] (the study: 1000 s).
    train_end : float
        End of the training window [s] (the study: 500 s).
    max_evaluations : int
        Nelder–Mead evaluations per fit.
    log : callable
        Receives one progress line per fit.

    Returns
    -------
    FitCase
        The data, the fits and the paper's set on the same data.
    """
    truth = RollEquation.edith_terkol(F, OMEGA_E)
    traj = truth.integrate(ic[0], ic[1], duration, DT)
    record = ident.RollRecord(traj.time, traj.phi, traj.phidot)
    n_train = record.index_at(train_end) + 1
    scans = []
    for n in pieces:
        res = ident.identify_roll_equation(
            record, omega=OMEGA_E, n_pieces=n, train_end=train_end, max_evaluations=max_evaluations
        )
        pred = ident.predict_roll(res.model, record, train_end=train_end)
        fit_nrmse = _win(pred.fit_window).nrmse_roll
        scans.append(FitScan(res, pred, fit_nrmse))
        log(
            f"  {ic_label(ic)} N = {n:4d}: b_u1 {res.model.b_u1:+.4f} b_u3 {res.model.b_u3:+.4f}"
            f" c_u1 {res.model.c_u1:.4f} c_u3 {res.model.c_u3:+.4f} F_u "
            f"{res.model.forcing_amplitude:.4f} | eq.3 {res.objective:.3g} | free-run NRMSE "
            f"fit {fit_nrmse:.3f} pred {_win(pred.prediction_window).nrmse_roll:.3f} "
            f"[{res.n_evaluations} ev, {res.cpu_time:.1f} s CPU]"
        )
    ok = [s for s in scans if np.isfinite(s.fit_nrmse) and not s.prediction.diverged]
    best = min(ok, key=lambda s: s.fit_nrmse)
    paper = paper_model(ic)
    paper_pred = ident.predict_roll(paper, record, train_end=train_end)
    n_best = best.result.n_pieces
    return FitCase(
        ic=ic,
        truth=truth,
        record=record,
        n_train=n_train,
        scans=tuple(scans),
        best=best,
        paper=paper,
        paper_prediction=paper_pred,
        paper_objective=ident.piecewise_error(paper, record, n_best, train_end=train_end),
        data_range=(
            float(np.max(np.abs(record.roll[:n_train]))),
            float(np.max(np.abs(record.roll_rate[:n_train]))),
        ),
    )


def cross_predictions(cases: list[FitCase]) -> list[dict[str, Any]]:
    """Each fitted model (ours and the paper's) run freely from every initial condition.

    Parameters
    ----------
    cases : list of FitCase
        The fits, one per initial condition.

    Returns
    -------
    list of dict
        One row per (fitted on, run from) pair: steady amplitudes over 500–1000 s [deg] of the
        truth, our model and the paper's, NRMSE over 500–1000 s [-] and divergence flags.
    """
    rows = []
    for source in cases:
        for target in cases:
            rec = target.record
            true_amp = _steady_amplitude(rec.t, rec.roll)
            row: dict[str, Any] = {
                "fitted_on": list(source.ic),
                "run_from": list(target.ic),
                "true_steady_amplitude_deg": math.degrees(true_amp),
            }
            models: tuple[tuple[str, ident.McCueCampbellModel], ...] = (
                ("ours", source.best.result.model),
                ("paper", source.paper),
            )
            for key, model in models:
                pred = ident.predict_roll(model, rec, train_end=TRAIN_END)
                amp = _steady_amplitude(pred.t, pred.roll)
                row[f"{key}_steady_amplitude_deg"] = math.degrees(amp)
                row[f"{key}_nrmse_500_1000"] = _win(pred.prediction_window).nrmse_roll
                row[f"{key}_diverged"] = pred.diverged
            rows.append(row)
    return rows


def safe_basins(case: FitCase, n_grid: int, cycles: int) -> dict[str, Any]:
    """Safe basins of the truth, of our fitted model and of the paper's (their fig. 8).

    Safe: no capsize within ``cycles`` forcing periods from t = 0, on a grid of initial
    ⟨φ₀, φ̇₀⟩ over ±1 rad × ±0.6 rad/s (:func:`ship_gym.analysis.safe_basin.safe_basin`).
    Capsize: |φ| beyond the truth's angle of vanishing stability (0.86 rad) for all three
    models (a fitted cubic with c_u3 < 0 vanishes near it; one with c_u3 > 0 never does).

    Parameters
    ----------
    case : FitCase
        The fit whose models are compared (the study: ⟨−0.4, −0.35⟩).
    n_grid : int
        Grid cells per axis.
    cycles : int
        Forcing periods simulated.

    Returns
    -------
    dict
        ``limit`` [rad], ``duration`` [s], the boolean ``truth``/``ours``/``paper`` grids, the
        axes ``phi`` [rad] and ``phidot`` [rad/s], cell-by-cell agreement with the truth and
        intersection over union of the safe sets [-], and the truth's safe fraction [-].
    """
    from ship_gym.analysis.safe_basin import safe_basin

    truth = case.truth
    limit = truth.vanishing_angle()
    duration = DT * round(cycles * 2 * math.pi / OMEGA_E / DT)
    out: dict[str, Any] = {"limit": limit, "duration": duration}
    for key, eq in (
        ("truth", truth),
        ("ours", case.best.result.model.roll_equation()),
        ("paper", case.paper.roll_equation()),
    ):
        basin = safe_basin(
            eq, roll_range=(-1.0, 1.0), roll_rate_range=(-0.6, 0.6), n_roll=n_grid,
            n_rate=n_grid, duration=duration, dt=DT, capsize_angle=limit, model=key,
        )  # fmt: skip
        out[key] = basin.safe
        out["phi"], out["phidot"] = basin.roll, basin.roll_rate
    for key in ("ours", "paper"):
        out[f"{key}_agreement"] = float(np.mean(out[key] == out["truth"]))
        # intersection over union of the safe sets: the agreement on the basin itself
        union = np.sum(out[key] | out["truth"])
        out[f"{key}_safe_iou"] = float(np.sum(out[key] & out["truth"]) / union)
    out["truth_safe_fraction"] = float(np.mean(out["truth"]))
    return out


def coefficient_rows(cases: list[FitCase]) -> list[dict[str, Any]]:
    """The coefficient table: ours (selected N) and the paper's, with their errors on our data.

    Parameters
    ----------
    cases : list of FitCase
        The fits, one per initial condition.

    Returns
    -------
    list of dict
        Two rows per case (``source`` "ours", "paper"): N, the coefficients, the eq. 3 error,
        free-run NRMSE over 0–500 s and 500–1000 s [-], correlation and largest error over
        500–1000 s [deg].
    """
    rows = []
    for case in cases:
        res = case.best.result
        for source, model, pred, objective in (
            ("ours", res.model, case.best.prediction, res.objective),
            ("paper", case.paper, case.paper_prediction, case.paper_objective),
        ):
            rows.append(
                {
                    "initial_condition": ic_label(case.ic),
                    "source": source,
                    "n_pieces": res.n_pieces,
                    "b_u1": model.b_u1,
                    "b_u3": model.b_u3,
                    "c_u1": model.c_u1,
                    "c_u3": model.c_u3,
                    "F_u": model.forcing_amplitude,
                    "eq3_error": objective,
                    "nrmse_fit_0_500": _win(pred.fit_window).nrmse_roll,
                    "nrmse_pred_500_1000": _win(pred.prediction_window).nrmse_roll,
                    "corr_pred_500_1000": _win(pred.prediction_window).correlation_roll,
                    "max_err_pred_deg": math.degrees(_win(pred.prediction_window).max_error_roll),
                }
            )
    return rows


@dataclass(frozen=True)
class Part1:
    """The numbers of part 1 (the Edith Terkol demonstration).

    Attributes
    ----------
    pieces : tuple of int
        Numbers of pieces N scanned.
    cases : tuple of FitCase
        One per initial condition of :data:`INITIAL_CONDITIONS`.
    table : list of dict
        :func:`coefficient_rows`.
    cross : list of dict
        :func:`cross_predictions`.
    basin : dict
        :func:`safe_basins` of the last case (⟨−0.4, −0.35⟩).
    basin_grid : int
        Safe-basin cells per axis.
    """

    pieces: tuple[int, ...]
    cases: tuple[FitCase, ...]
    table: list[dict[str, Any]]
    cross: list[dict[str, Any]]
    basin: dict[str, Any]
    basin_grid: int

    def as_dict(self) -> dict[str, Any]:
        """The JSON record of ``docs/mccue/results.json`` (without figures and CPU time)."""
        basin = self.basin
        return {
            "conditions": {
                "forcing_amplitude": F,
                "omega_e": OMEGA_E,
                "dt": DT,
                "duration": DURATION,
                "train_end": TRAIN_END,
                "pieces_scanned": list(self.pieces),
                "selection": "N with the smallest free-run roll NRMSE over the training window",
            },
            "cases": [
                {
                    "initial_condition": list(c.ic),
                    "data_range_roll_rad": c.data_range[0],
                    "data_range_rate_rad_s": c.data_range[1],
                    "selected_n_pieces": c.best.result.n_pieces,
                    "scan": [
                        {
                            "n_pieces": s.result.n_pieces,
                            "identification": s.result.as_dict(),
                            "prediction": s.prediction.as_dict(),
                        }
                        for s in c.scans
                    ],
                    "paper_coefficients": c.paper.as_dict(),
                    "paper_prediction": c.paper_prediction.as_dict(),
                    "paper_eq3_error_at_selected_n": c.paper_objective,
                }
                for c in self.cases
            ],
            "table": self.table,
            "cross_predictions": self.cross,
            "safe_basin": {
                "grid": self.basin_grid,
                **{k: basin[k] for k in ("limit", "duration", "truth_safe_fraction")},
                **{k: basin[k] for k in ("ours_agreement", "paper_agreement")},
                **{k: basin[k] for k in ("ours_safe_iou", "paper_safe_iou")},
            },
        }


def part1(
    pieces: tuple[int, ...] = PIECES,
    basin_grid: int = 121,
    basin_cycles: int = 16,
    *,
    log: Log = _silent,
) -> Part1:
    """Fits for the three initial conditions, cross-predictions and safe basins.

    Parameters
    ----------
    pieces : tuple of int
        Numbers of pieces N scanned.
    basin_grid : int
        Safe-basin cells per axis.
    basin_cycles : int
        Forcing periods simulated for the safe basin.
    log : callable
        Receives the progress lines.

    Returns
    -------
    Part1
        The numbers.
    """
    cases = [fit_case(ic, pieces, log=log) for ic in INITIAL_CONDITIONS]
    return Part1(
        pieces=tuple(pieces),
        cases=tuple(cases),
        table=coefficient_rows(cases),
        cross=cross_predictions(cases),
        basin=safe_basins(cases[2], basin_grid, basin_cycles),
        basin_grid=basin_grid,
    )


# ---------------------------------------------------------------------------------- part 2
def simulate_s175(
    progress: bool = False,
) -> tuple[ident.RollRecord, dict[str, Any], Any, FloatArray]:
    """Beam-sea roll record of the 6-DOF S175 with the wave elevation at the origin.

    Parameters
    ----------
    progress : bool
        Show the simulator's progress bar.

    Returns
    -------
    record : RollRecord
        Roll [rad], roll rate [rad/s] and wave elevation [m] every 0.1 s, t from 0 [s].
    meta : dict
        Simulation CPU time [s], the setup, the ship's fixed horizontal position [m], its drift
        [m] and heading [rad].
    wave_field : object
        The simulator's wave field.
    t_wave : numpy.ndarray
        The record's times on the wave field's clock [s].
    """
    from ship_gym.engine.ship import ShipSetup, build_simulator
    from ship_gym.waves.sea_state import IrregularSea

    setup = ShipSetup(
        integrator="holloway", dt=SIX_DT, free_dofs=(False, False, True, True, True, False)
    )
    sea = IrregularSea(hs=SIX_HS, tp=SIX_TP, n_components=100)
    sim = build_simulator(setup, sea, wave_heading=math.pi / 2, rng=np.random.default_rng(SIX_SEED))
    cpu0 = time.process_time()
    sim.run(SIX_SETTLE, record_every=2, progress=False)
    res = sim.run(SIX_DURATION, record_every=2, progress=progress)
    cpu = time.process_time() - cpu0
    phi, theta = res.eta[:, 3], res.eta[:, 4]
    p, q, r = res.nu[:, 3], res.nu[:, 4], res.nu[:, 5]
    phidot = p + (q * np.sin(phi) + r * np.cos(phi)) * np.tan(theta)  # Euler-angle rate
    t = res.t - res.t[0]
    record = ident.RollRecord(t, phi, phidot, res.elevation, "wave_elevation")
    # surge/sway/yaw velocities are held at 0, yet the earth position creeps (≈ 1.4 m over the
    # record, body-to-earth kinematics with roll and pitch): the mean position is used for m(t)
    # (phase error k·0.7 m ≤ 0.03 rad at the roll-resonant ω ≤ 0.6 rad/s)
    held = res.eta[:, [0, 1, 5]]
    drift = float(np.max(np.ptp(held[:, :2], axis=0)))
    if drift > 5.0 or np.ptp(held[:, 2]) > 1e-6:
        raise RuntimeError(f"surge, sway and yaw were expected to be held (drift {drift:.3g} m)")
    meta = {
        "simulation_cpu_s": cpu,
        "setup": repr(setup),
        "position": (float(held[:, 0].mean()), float(held[:, 1].mean())),
        "position_drift_m": drift,
        "ship_heading": float(held[0, 2]),
    }
    return record, meta, sim.wave_field, res.t


@dataclass(frozen=True)
class InputScan:
    """One fit of eq. 2 with K u(t − τ) (one N) and its free runs.

    Attributes
    ----------
    result : IdentificationResult
        The identification.
    prediction : RollPrediction
        Free run from t = 0.
    prediction_from_train_end : RollPrediction
        Free run from the end of the training window.
    """

    result: ident.IdentificationResult
    prediction: ident.RollPrediction
    prediction_from_train_end: ident.RollPrediction


@dataclass(frozen=True)
class InputFit:
    """The fits for one input u(t).

    Attributes
    ----------
    record : RollRecord
        The record with u(t) as its excitation column.
    scans : tuple of InputScan
        One per N of :data:`SIX_PIECES`.
    best : InputScan
        The N with the best free-run reproduction of the training window (not diverged).
    """

    record: ident.RollRecord
    scans: tuple[InputScan, ...]
    best: InputScan


def fit_input(
    record: ident.RollRecord,
    name: str,
    pieces: tuple[int, ...] = SIX_PIECES,
    *,
    train_end: float = SIX_TRAIN,
    max_evaluations: int = 2000,
    log: Log = _silent,
) -> InputFit:
    """Fits of eq. 2 with K u(t − τ) for each N; the N with the best free-run reproduction of
    the training window is selected.

    Parameters
    ----------
    record : RollRecord
        Roll record whose excitation column is the input u(t).
    name : str
        Name of the input (for the progress lines).
    pieces : tuple of int
        Numbers of pieces N scanned.
    train_end : float
        End of the training window [s].
    max_evaluations : int
        Nelder–Mead evaluations per fit.
    log : callable
        Receives one progress line per fit.

    Returns
    -------
    InputFit
        The scan and the selected fit.
    """
    scans = []
    for n in pieces:
        res = ident.identify_roll_equation(
            record, omega=None, n_pieces=n, train_end=train_end, fit_input_lag=True,
            max_evaluations=max_evaluations, restarts=0,
        )  # fmt: skip
        pred = ident.predict_roll(res.model, record, train_end=train_end)
        pred_end = ident.predict_roll(res.model, record, train_end=train_end, start_time=train_end)
        m = res.model
        log(
            f"  [{name}] N = {n:4d}: b_u1 {m.b_u1:+.4f} b_u3 {m.b_u3:+.3f} c_u1 {m.c_u1:.4f} "
            f"(ω_n {m.natural_frequency:.4f}) c_u3 {m.c_u3:+.3f} K {m.input_gain:+.4g} τ "
            f"{m.input_lag:+.2f} s | free run NRMSE fit {_win(pred.fit_window).nrmse_roll:.3f}, "
            f"held-out {_win(pred.prediction_window).nrmse_roll:.3f} (corr "
            f"{_win(pred.prediction_window).correlation_roll:.3f}) [{res.cpu_time:.0f} s CPU]"
        )
        scans.append(InputScan(res, pred, pred_end))
    ok = [s for s in scans if not s.prediction.diverged] or scans
    best = min(ok, key=lambda s: _win(s.prediction.fit_window).nrmse_roll)
    return InputFit(record, tuple(scans), best)


@dataclass(frozen=True)
class SixDofStudy:
    """The numbers of part 2 (identification from the 6-DOF S175).

    Attributes
    ----------
    record : RollRecord
        The simulated record (excitation column: the wave elevation [m]).
    meta : dict
        :func:`simulate_s175` meta data.
    m_exact : numpy.ndarray
        Roll excitation moment, component-wise from the wave field [N·m].
    m_fft : numpy.ndarray
        Roll excitation moment from the elevation record, FFT-filtered [N·m].
    fft_check : dict
        NRMSE and correlation of the FFT path against the component-wise moment [-].
    omega_lin : float
        Linear roll natural frequency of the hydro database [rad/s].
    i44 : float
        Roll inertia of the hull about O [kg·m²].
    a44 : float
        Roll added mass at ``omega_lin`` [kg·m²].
    gain_phys : float
        Physical gain 1/(I44 + A44) [rad/s² per N·m].
    fits : dict
        :class:`InputFit` per input name of :data:`SIX_INPUTS`.
    table : list of dict
        One summary row per input.
    """

    record: ident.RollRecord
    meta: dict[str, Any]
    m_exact: FloatArray
    m_fft: FloatArray
    fft_check: dict[str, Any]
    omega_lin: float
    i44: float
    a44: float
    gain_phys: float
    fits: dict[str, InputFit]
    table: list[dict[str, Any]]

    def as_dict(self) -> dict[str, Any]:
        """The JSON record of ``docs/mccue/results.json`` (without the CPU time)."""
        record, m_exact = self.record, self.m_exact
        main_fit = self.fits["excitation"].best
        return {
            "conditions": {
                "hull": "s175",
                "sea": f"JONSWAP Hs {SIX_HS} m Tp {SIX_TP} s, long-crested, beam (β = 90°), seed "
                f"{SIX_SEED}, 100 components",
                "speed": 0.0,
                "free_dofs": "heave, roll, pitch (surge, sway, yaw held)",
                "integrator": "holloway",
                "dt": SIX_DT,
                "record_dt": record.dt,
                "settle": SIX_SETTLE,
                "duration": SIX_DURATION,
                "train_end": SIX_TRAIN,
                "forcing_model": "K * u(t - lag), K and lag fitted, for each input u",
                "inputs": SIX_INPUTS,
                "selection": "N with the smallest free-run roll NRMSE over the training window",
            },
            "roll_std_deg": math.degrees(float(record.roll.std())),
            "roll_max_deg": math.degrees(float(np.abs(record.roll).max())),
            "roll_excitation_std_Nm": float(m_exact.std()),
            "fft_vs_componentwise_excitation": self.fft_check,
            "omega_natural_linear": self.omega_lin,
            "physical_gain": {"I44": self.i44, "A44_at_omega_n": self.a44, "gain": self.gain_phys},
            "table": self.table,
            "inputs": {
                name: {
                    "scan": [
                        {
                            "identification": s.result.as_dict(),
                            "prediction_from_start": s.prediction.as_dict(),
                            "prediction_from_train_end": s.prediction_from_train_end.as_dict(),
                        }
                        for s in fit.scans
                    ],
                    "selected_n_pieces": fit.best.result.n_pieces,
                }
                for name, fit in self.fits.items()
            },
            "selected_n_pieces": main_fit.result.n_pieces,
            "omega_natural_identified": main_fit.result.model.natural_frequency,
            "meta": self.meta,
        }


def sixdof_study(progress: bool = False, *, log: Log = _silent) -> SixDofStudy:
    """Simulate the S175 in beam seas and identify eq. 2 with K u(t − τ) for the three inputs.

    Parameters
    ----------
    progress : bool
        Show the simulator's progress bar.
    log : callable
        Receives the progress lines.

    Returns
    -------
    SixDofStudy
        The numbers.
    """
    from ship_gym.hull import load_hull
    from ship_gym.hydro import as_arrays, load_database
    from ship_gym.hydro.rao import natural_frequency

    record, meta, field, t_wave = simulate_s175(progress=progress)
    db = load_database("s175")
    omega_lin = natural_frequency(db, "Roll")
    arrays = as_arrays(db)
    i44 = float(load_hull("s175").mass.rigid_body_matrix()[3, 3])
    a44 = float(np.interp(omega_lin, arrays.omega, arrays.added_mass[:, 3, 3]))
    gain_phys = 1.0 / (i44 + a44)
    assert record.excitation is not None
    log(
        f"S175 beam seas Hs {SIX_HS} m Tp {SIX_TP} s: roll std "
        f"{math.degrees(record.roll.std()):.2f}°, max "
        f"{math.degrees(np.abs(record.roll).max()):.2f}°, elevation std "
        f"{record.excitation.std():.2f} m [{meta['simulation_cpu_s']:.0f} s CPU]"
    )
    # the inputs: exact (component-wise) and FFT-filtered roll excitation, and the elevation
    m_exact = ident.roll_excitation_moment(
        field, db, t_wave, ship_heading=meta["ship_heading"], position=meta["position"]
    )
    m_fft = ident.roll_excitation_from_elevation(record.excitation, record.dt, db, math.pi / 2)
    inner = (record.t >= SIX_EDGE) & (record.t <= record.t[-1] - SIX_EDGE)
    fft_check = {
        "nrmse_whole_record": float(np.std(m_fft - m_exact) / np.std(m_exact)),
        "nrmse_interior": float(np.std((m_fft - m_exact)[inner]) / np.std(m_exact[inner])),
        "interior": [SIX_EDGE, float(record.t[-1] - SIX_EDGE)],
        "correlation_whole_record": float(np.corrcoef(m_fft, m_exact)[0, 1]),
    }
    log(
        f"roll excitation: std {m_exact.std() / 1e6:.2f} MN·m; FFT path vs component-wise: "
        f"NRMSE {fft_check['nrmse_whole_record']:.4f} (whole record), "
        f"{fft_check['nrmse_interior']:.4f} ({SIX_EDGE:.0f} s ends left out); physical gain "
        f"1/(I44 + A44(ω_n)) = {gain_phys:.4g} rad/s² per N·m (I44 {i44:.4g}, A44 {a44:.4g} "
        "kg·m²)"
    )
    records = {
        "excitation": ident.RollRecord(
            record.t, record.roll, record.roll_rate, m_exact, "roll_excitation_moment"
        ),
        "excitation_fft": ident.RollRecord(
            record.t, record.roll, record.roll_rate, m_fft, "roll_excitation_moment_fft"
        ),
        "elevation": record,
    }
    fits = {name: fit_input(rec, name, log=log) for name, rec in records.items()}
    rows = []
    for name, fit in fits.items():
        m = fit.best.result.model
        pw = _win(fit.best.prediction.prediction_window)
        pe = _win(fit.best.prediction_from_train_end.prediction_window)
        rows.append(
            {
                "input": name,
                "n_pieces": fit.best.result.n_pieces,
                "omega_n": m.natural_frequency,
                "gain": m.input_gain,
                "gain_over_physical": m.input_gain / gain_phys if name != "elevation" else None,
                "lag_s": m.input_lag,
                "nrmse_heldout": pw.nrmse_roll,
                "corr_heldout": pw.correlation_roll,
                "nrmse_heldout_from_600": pe.nrmse_roll,
                "corr_heldout_from_600": pe.correlation_roll,
                "std_roll_model_deg": math.degrees(pw.std_roll_model),
            }
        )
    return SixDofStudy(
        record=record,
        meta=meta,
        m_exact=m_exact,
        m_fft=m_fft,
        fft_check=fft_check,
        omega_lin=omega_lin,
        i44=i44,
        a44=a44,
        gain_phys=gain_phys,
        fits=fits,
        table=rows,
    )
