"""``ship-gym identify``: fit McCue & Campbell's roll equation (eq. 2) to a roll time series.

Reads a CSV (header row; columns t [s], phi [rad], phidot [rad/s] by default, optionally an input
column such as the wave elevation at the ship [m]), fits

    ÿ + b_u1 ẏ + b_u3 ẏ³ + c_u1 y + c_u3 y³ = F_u sin(ωₑt [+ ε]) [+ K u(t − τ)]

by Nelder–Mead on the piecewise-integration error of McCue & Campbell eq. 3 over t ≤ --train-end,
integrates the fitted equation freely from the first data point over the whole record, and prints
the coefficients and the fit / prediction errors (:mod:`ship_gym.analysis.identification`).
"""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from ship_gym.cli.common import (
    CLIError,
    count,
    existing_file,
    positive_float,
    prepare_output,
    write_json,
    write_or_rescue,
)

if TYPE_CHECKING:
    from ship_gym.analysis import identification as ident


def add_commands(sub: argparse._SubParsersAction) -> None:
    """Register ``identify`` on the ``ship-gym`` parser."""
    p = sub.add_parser(
        "identify",
        help="fit a roll equation (McCue & Campbell eq. 2) to a roll time series by Nelder-Mead",
    )
    p.add_argument(
        "csv", type=existing_file, help="CSV with a header row: time, roll [rad], roll rate [rad/s]"
    )
    p.add_argument(
        "--omega",
        type=positive_float,
        default=None,
        help="encounter frequency of the harmonic forcing [rad/s] (omit for input-driven or "
        "free-decay fits)",
    )
    p.add_argument("--pieces", type=count, default=20, help="number N of piecewise integrations")
    p.add_argument(
        "--train-end",
        type=positive_float,
        default=None,
        help="end of the training window [s] (all)",
    )
    p.add_argument("--time-column", default="t")
    p.add_argument("--roll-column", default="phi")
    p.add_argument("--rate-column", default="phidot")
    p.add_argument(
        "--input-column",
        default=None,
        help="input column u for a forcing term K u(t - lag), e.g. wave elevation [m]",
    )
    p.add_argument("--fit-phase", action="store_true", help="also fit the forcing phase")
    p.add_argument("--fit-lag", action="store_true", help="also fit the input lag")
    p.add_argument(
        "--compare",
        default="endpoint",
        choices=("endpoint", "all"),
        help="error at the piece end points (eq. 3) or at every sample",
    )
    p.add_argument(
        "--max-evaluations", type=count, default=4000, help="Nelder-Mead evaluations (>= 1)"
    )
    p.add_argument("--json", default=None, help="write the numbers to this JSON file")
    p.add_argument("--plot", default=None, help="figure (PNG): time history and curves")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_identify)


def _cmd_identify(args: argparse.Namespace) -> int:
    from ship_gym.analysis import identification as ident

    prepare_output(args.json, "--json")
    prepare_output(args.plot, "--plot", suffixes=(".png",))
    record = ident.load_roll_csv(
        args.csv,
        time_column=args.time_column,
        roll_column=args.roll_column,
        rate_column=args.rate_column,
        excitation_column=args.input_column,
    )
    train_end = float(record.t[-1]) if args.train_end is None else args.train_end
    if not float(record.t[0]) < train_end <= float(record.t[-1]):
        raise CLIError(
            f"--train-end {train_end:g} s is outside the record ({float(record.t[0]):g} … "
            f"{float(record.t[-1]):g} s); expected a time within it"
        )
    result = ident.identify_roll_equation(
        record,
        omega=args.omega,
        n_pieces=args.pieces,
        train_end=train_end,
        fit_phase=args.fit_phase,
        use_input=args.input_column is not None,
        fit_input_lag=args.fit_lag,
        compare=args.compare,
        max_evaluations=args.max_evaluations,
        progress=not args.no_progress,
    )
    prediction = ident.predict_roll(result.model, record, train_end=result.train_end)
    m = result.model
    print(
        f"{args.csv}: {record.n} samples, dt = {record.dt:.4g} s, training t ≤ "
        f"{result.train_end:g} s, N = {result.n_pieces} pieces of {result.steps_per_piece} steps"
    )
    print(
        f"b_u1 = {m.b_u1:.5g} 1/s, b_u3 = {m.b_u3:.5g} s/rad², c_u1 = {m.c_u1:.5g} 1/s², "
        f"c_u3 = {m.c_u3:.5g} 1/(rad² s²), F_u = {m.forcing_amplitude:.5g} rad/s²"
        + (f", ε = {m.forcing_phase:.4g} rad" if args.fit_phase else "")
        + (f", K = {m.input_gain:.5g}, τ = {m.input_lag:.4g} s" if m.input_gain else "")
    )
    print(
        f"ω_n = √c_u1 = {m.natural_frequency:.4f} rad/s; eq. 3 error {result.initial_objective:.4g}"
        f" → {result.objective:.4g} in {result.n_evaluations} evaluations "
        f"({'converged' if result.converged else result.message})"
    )
    for name, w in (("fit", prediction.fit_window), ("prediction", prediction.prediction_window)):
        if w is not None:
            print(
                f"free run from t = {prediction.start_time:g} s, {name} window "
                f"[{w.t_start:g}, {w.t_end:g}] s: roll RMSE {w.rmse_roll:.4g} rad "
                f"(NRMSE {w.nrmse_roll:.3f}), correlation {w.correlation_roll:.3f}"
            )
    if args.json:
        payload = {
            "csv": str(args.csv),
            "identification": result.as_dict(),
            "prediction": prediction.as_dict(),
        }
        write_json(args.json, payload)
    if args.plot:
        _plot(record, result, prediction, args.plot)
    return 0


def _plot(
    record: ident.RollRecord,
    result: ident.IdentificationResult,
    prediction: ident.RollPrediction,
    path: str,
) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ship_gym.analysis import identification as ident

    fig = plt.figure(figsize=(11, 6.5))
    grid = fig.add_gridspec(2, 2)
    ax_t = fig.add_subplot(grid[0, :])
    ident.plot_time_history(
        ax_t, record, prediction, title=f"identified eq. 2, N = {result.n_pieces} pieces"
    )
    axes = [fig.add_subplot(grid[1, 0]), fig.add_subplot(grid[1, 1])]
    ident.plot_curves(axes, result.model, record, train_end=result.train_end)
    fig.tight_layout()
    write_or_rescue(path, lambda p: fig.savefig(p, dpi=110, format="png"), "--plot")
    plt.close(fig)
    print(f"wrote {path}")
