#!/usr/bin/env python
"""Convergence study of the physics time step and the integrator for the S175 at zero speed.

Defaults
--------
**RK4 at Δt = 0.05 s** (the ``ShipSetup`` default). Against RK4 at Δt = 0.0125 s its relative
RMS error in heave, roll and pitch is ≤ 1.8e-7 (2e-5 %) in both seas below (irregular 1.7e-7,
steep regular 2.6e-8), at 80 force evaluations per simulated second. RK4 converges at fourth
order from Δt = 0.4 s down (observed 3.8–4.2; in the irregular sea the roll error falls more
slowly below Δt = 0.1 s, see Notes) and never diverged, so the time-integration error is far
below the modelling errors (e.g. ≈ 1 % of the state-space radiation fit): Δt = 0.1 s
(Matusiak's choice) gives ≤ 1.0e-6 at half the cost and is a sound "fast" setting; 0.2 s still
gives ≤ 1.6e-5. Holloway's scheme at 0.05 s: 0.039–0.063 % error, second order (observed
2.00–2.06), 4× cheaper than RK4 at the same Δt — but at equal cost (20 evaluations/s) RK4 at
0.2 s is 25–120× more accurate. (Numbers: 120 s runs, ``--json``; sampled on a 0.4 s grid;
measured on the engine of :class:`~ship_gym.engine.simulator.Simulator`, which reproduces the
retired Python simulator's errors to the printed digits.)

Method
------
The S175 (bundled hull and BEM database, zero speed, surge/sway/yaw held, heave/roll/pitch
free, state-space radiation, diffraction, Ikeda viscous roll damping, nonlinear Froude–Krylov +
hydrostatics on the instantaneous wetted hull; :func:`ship_gym.engine.ship.build_simulator`)
is simulated in two seas, each with the default 50 s start-up ramp (Matusiak eq. 12):

* ``irregular``: long-crested JONSWAP Hs = 5 m, Tp = 11 s, γ = 3.3, 50 components, relative
  heading β = 135° (bow-quartering), fixed seed;
* ``regular``: a steep regular wave H = 10 m, λ = 350 m (T = 15.0 s, H/λ = 1/35) at β = 60°
  (stern-quartering). λ = 175 m is too short to make the S175 roll at zero speed (T = 10.6 s
  against a roll period of 17.9 s: 0.6° in beam seas, 5° at 60°); λ = 350 m is near roll
  resonance and gives up to 21.5° roll, 2.9° pitch, 5.0 m heave — large, nonlinear roll (deck
  edge at ≈ 25°) with the |p|p damping and the wetted-surface changes fully active.

The diffraction model caches X_D per component and refreshes it when ψ has moved by more than
``heading_tolerance_deg`` (0.5° in ``build_simulator``); a refresh makes the diffraction force
*jump*, which would cap every scheme at first order. Here yaw is held and a held rotation keeps
its Euler angle, so ψ stays at its initial value and the cache is never refreshed: the study
freezes X_D anyway (tolerance 180°, ``--heading-tolerance``), and 0.5° (the package's cache) and
0 (X_D at the current heading at every evaluation) gave the same errors to the printed digits.

Notes: no scheme diverged at any Δt ≤ 0.4 s. In the irregular sea the RK4 roll error falls
more slowly below Δt = 0.1 s (3.6e-7, 1.7e-7, 3.2e-8 at 0.1, 0.05, 0.025 s: observed order 1.1
then 2.5) while heave and pitch keep fourth order (3.8–4.1); the likely cause is the waterline
cut of the Froude–Krylov integral (a force only piecewise smooth as mesh vertices cross the
surface), which weighs most on the small (≤ 4°) roll. It is ≤ 2e-5 % — irrelevant.

Each scheme — ``rk4`` (4 force evaluations per step) and ``holloway`` (Holloway's μ-Taylor
scheme with A(∞) on the left-hand side, 1, after a 2-step RK4 start-up) — is run at
Δt ∈ {0.4, 0.2, 0.1, 0.05, 0.025} s and compared with RK4 at Δt = 0.0125 s on a common 0.4 s
grid. The error of a DOF is the relative RMS error

    e = RMS(x − x_ref) / RMS(x_ref − x_ref(0))      (x_ref(0): the free-floating equilibrium)

over the whole record, reported for heave, roll and pitch and as their maximum; the observed
order between successive steps is log₂(e(Δt)/e(Δt/2)). Cost is the number of force evaluations
per simulated second (start-up included) and the wall time of the run (build excluded). A run
that raises :class:`~ship_gym.engine.simulator.SimulationDiverged` is reported as diverged.

Outputs: a figure (default ``out/convergence.png``: error against Δt and against evaluations per
simulated second, per sea and scheme), a printed table, and with ``--json PATH`` the numbers
(``dt``, per-scheme ``error``, ``order``, ``evaluations_per_second``, ``wall_s``, ``diverged``).
A full run (120 s per simulation, ``--duration``) costs ≈ 35 s of CPU on one core (the
schemes run on the compiled backend);
``--replot JSON`` redraws the table and figure from saved numbers.

Usage::

    python scripts/convergence_study.py [--output out/convergence.png] [--json PATH]
                                        [--duration 120] [--cases irregular regular]
                                        [--schemes rk4 holloway]
                                        [--dts 0.4 0.2 ...] [--heading-tolerance 180]
                                        [--replot JSON]
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ship_gym.engine.ship import ShipSetup, build_simulator, database_of
from ship_gym.engine.simulator import SimulationDiverged, Simulator
from ship_gym.forces.diffraction import Diffraction
from ship_gym.io_utils import from_json_value, to_json_value
from ship_gym.waves.sea_state import IrregularSea, RegularWave

DTS: tuple[float, ...] = (0.4, 0.2, 0.1, 0.05, 0.025)
REFERENCE_DT = 0.0125
SAMPLE_DT = 0.4  # comparison grid [s]: a multiple of every Δt
DURATION = 120.0  # [s]: 50 s ramp + 70 s
FREE_DOFS = (False, False, True, True, True, False)  # heave, roll, pitch
COMPARED = {"heave": 2, "roll": 3, "pitch": 4}
SEED = 20240611
FROZEN_HEADING = 180.0  # diffraction heading tolerance [deg] that never triggers a refresh
PACKAGE_HEADING_TOLERANCE = 0.5  # Diffraction's default [deg]

SCHEMES: dict[str, dict] = {
    "rk4": {"integrator": "rk4"},
    "holloway": {"integrator": "holloway"},
}


@dataclass(frozen=True)
class Case:
    """A sea and heading for the study."""

    name: str
    description: str
    sea: IrregularSea | RegularWave
    heading_deg: float
    seed: int | None = None


CASES: dict[str, Case] = {
    "irregular": Case(
        "irregular",
        "JONSWAP Hs 5 m, Tp 11 s, 50 components, beta 135 deg",
        IrregularSea(hs=5.0, tp=11.0, n_components=50),
        135.0,
        SEED,
    ),
    "regular": Case(
        "regular",
        "regular H 10 m, lambda 350 m (T 15.0 s), beta 60 deg",
        RegularWave(height=10.0, wavelength=350.0),
        60.0,
    ),
}


@dataclass
class Run:
    """One simulation: sampled motions and cost."""

    t: np.ndarray | None
    eta: np.ndarray | None
    evaluations_per_second: float
    wall_s: float
    diverged: bool
    diverged_at: float | None = None


def build(
    case: Case, scheme: str, dt: float, heading_tolerance_deg: float = FROZEN_HEADING
) -> Simulator:
    """The S175 simulator of a case (``build_simulator``), with its diffraction cache set.

    :class:`~ship_gym.forces.diffraction.Diffraction` caches X_D per component and refreshes it
    when ψ has moved by more than ``heading_tolerance_deg`` [deg] (0.5° in ``build_simulator``);
    a refresh makes the diffraction force jump (module docstring). The study freezes X_D at the
    initial heading (180°: never refreshed). The engine converts the force models when the
    :class:`Simulator` is built, so a different tolerance means a new Simulator from the
    replaced model list, at the same state and commands.
    """
    setup = ShipSetup(dt=dt, free_dofs=FREE_DOFS, **SCHEMES[scheme])
    rng = None if case.seed is None else np.random.default_rng(case.seed)
    sim = build_simulator(setup, case.sea, wave_heading=math.radians(case.heading_deg), rng=rng)
    if heading_tolerance_deg == PACKAGE_HEADING_TOLERANCE:
        return sim
    # the engine converts the models when the Simulator is built: replacing an entry of
    # sim.forces afterwards has no effect, so rebuild the Simulator with the new model list
    models = [
        Diffraction(database_of(setup), f.wave_field, heading_tolerance_deg=heading_tolerance_deg)
        if isinstance(f, Diffraction)
        else f
        for f in sim.forces
    ]
    rebuilt = Simulator(
        sim.hull,
        models,
        wave_field=sim.wave_field,
        forward_speed=setup.speed,
        dt=setup.dt,
        integrator=setup.integrator,
        free_dofs=setup.free_dofs,
    )
    rebuilt.commands = sim.commands
    rebuilt.reset(eta=sim.eta, nu=sim.nu, t0=sim.t)
    return rebuilt


def simulate(
    case: Case,
    scheme: str,
    dt: float,
    duration: float,
    heading_tolerance_deg: float = FROZEN_HEADING,
) -> Run:
    """Run ``scheme`` at ``dt`` for ``duration`` s, sampled every :data:`SAMPLE_DT`."""
    sim = build(case, scheme, dt, heading_tolerance_deg)
    every = round(SAMPLE_DT / dt)
    n0 = sim.engine.n_evaluations
    t0 = time.perf_counter()
    try:
        res = sim.run(duration, record_every=every)
    except SimulationDiverged:
        wall = time.perf_counter() - t0
        evals = (sim.engine.n_evaluations - n0) / max(sim.t, dt)
        return Run(None, None, evals, wall, True, sim.t)
    wall = time.perf_counter() - t0
    evals = (sim.engine.n_evaluations - n0) / duration
    return Run(res.t, res.eta, evals, wall, False)


def relative_errors(run: Run, ref: Run) -> dict[str, float]:
    """Relative RMS error per compared DOF (and ``max``) of ``run`` against ``ref``."""
    if run.diverged or run.eta is None:
        return {k: math.nan for k in (*COMPARED, "max")}
    assert ref.eta is not None and ref.t is not None and run.t is not None
    if run.t.shape != ref.t.shape or not np.allclose(run.t, ref.t, atol=1e-6):
        raise RuntimeError("sampling grids of run and reference differ")
    out = {}
    for name, i in COMPARED.items():
        motion = ref.eta[:, i] - ref.eta[0, i]
        scale = float(np.sqrt(np.mean(motion**2)))
        out[name] = float(np.sqrt(np.mean((run.eta[:, i] - ref.eta[:, i]) ** 2)) / scale)
    out["max"] = max(out[k] for k in COMPARED)
    return out


def observed_order(errors: list[float], dts: tuple[float, ...]) -> list[float]:
    """log(e_k/e_{k+1}) / log(Δt_k/Δt_{k+1}) between successive steps (NaN where undefined)."""
    orders = []
    for k in range(len(dts) - 1):
        a, b = errors[k], errors[k + 1]
        if np.isfinite(a) and np.isfinite(b) and a > 0 and b > 0:
            orders.append(math.log(a / b) / math.log(dts[k] / dts[k + 1]))
        else:
            orders.append(math.nan)
    return orders


def study(
    case: Case,
    duration: float,
    dts: tuple[float, ...],
    heading_tolerance_deg: float = FROZEN_HEADING,
    schemes: tuple[str, ...] = tuple(SCHEMES),
    log=print,
) -> dict:
    """Every scheme at every Δt against the RK4 reference for one case."""
    t0 = time.perf_counter()
    ref = simulate(case, "rk4", REFERENCE_DT, duration, heading_tolerance_deg)
    if ref.diverged:
        raise RuntimeError(f"{case.name}: the reference run diverged at t = {ref.diverged_at} s")
    assert ref.eta is not None
    amp = {
        name: float(np.sqrt(2) * np.sqrt(np.mean((ref.eta[:, i] - ref.eta[0, i]) ** 2)))
        for name, i in COMPARED.items()
    }
    log(
        f"[{case.name}] reference RK4 dt = {REFERENCE_DT} s: {ref.wall_s:.1f} s wall; "
        f"max |roll| = {np.degrees(np.abs(ref.eta[:, 3]).max()):.1f} deg, "
        f"max |pitch - trim| = {np.degrees(np.abs(ref.eta[:, 4] - ref.eta[0, 4]).max()):.1f} deg,"
        f" max |heave| = {np.abs(ref.eta[:, 2] - ref.eta[0, 2]).max():.2f} m"
    )
    results = {}
    for scheme in schemes:
        rows = {
            "error": {k: [] for k in (*COMPARED, "max")},
            "evaluations_per_second": [],
            "wall_s": [],
            "diverged": [],
            "diverged_at_s": [],
        }
        for dt in dts:
            run = simulate(case, scheme, dt, duration, heading_tolerance_deg)
            err = relative_errors(run, ref)
            for k, v in err.items():
                rows["error"][k].append(v)
            rows["evaluations_per_second"].append(run.evaluations_per_second)
            rows["wall_s"].append(run.wall_s)
            rows["diverged"].append(run.diverged)
            rows["diverged_at_s"].append(run.diverged_at)
            log(
                f"[{case.name}] {scheme:16s} dt = {dt:<6g} "
                + (
                    f"diverged at t = {run.diverged_at:.1f} s"
                    if run.diverged
                    else f"max error {100 * err['max']:.3g} %"
                )
                + f" ({run.wall_s:.1f} s wall)"
            )
        rows["order"] = observed_order(rows["error"]["max"], dts)
        results[scheme] = rows
    return {
        "description": case.description,
        "heading_deg": case.heading_deg,
        "seed": case.seed,
        "duration_s": duration,
        "dt": list(dts),
        "reference": {
            "integrator": "rk4",
            "dt": REFERENCE_DT,
            "evaluations_per_second": ref.evaluations_per_second,
            "wall_s": ref.wall_s,
            "rms_amplitude": amp,
        },
        "diffraction_heading_tolerance_deg": heading_tolerance_deg,
        "integrators": results,
        "total_wall_s": time.perf_counter() - t0,
    }


# ------------------------------------------------------------------------------------ output
def _pct(x: float) -> str:
    return "   div." if not np.isfinite(x) else f"{100 * x:7.3g}"


def format_table(results: dict) -> str:
    lines = []
    for name, res in results.items():
        lines.append(f"\n{name}: {res['description']}, {res['duration_s']:g} s")
        lines.append(
            f"{'scheme':16s} {'dt [s]':>6s} {'heave %':>8s} {'roll %':>8s} {'pitch %':>8s} "
            f"{'max %':>8s} {'order':>6s} {'eval/s':>7s} {'wall s':>7s}"
        )
        for scheme, rows in res["integrators"].items():
            for k, dt in enumerate(res["dt"]):
                e = rows["error"]
                order = rows["order"][k - 1] if k > 0 else math.nan
                lines.append(
                    f"{scheme:16s} {dt:6g} {_pct(e['heave'][k]):>8s} {_pct(e['roll'][k]):>8s} "
                    f"{_pct(e['pitch'][k]):>8s} {_pct(e['max'][k]):>8s} "
                    f"{'' if not np.isfinite(order) else f'{order:6.2f}':>6s} "
                    f"{rows['evaluations_per_second'][k]:7.0f} {rows['wall_s'][k]:7.1f}"
                )
    return "\n".join(lines)


def plot(results: dict, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    n = len(results)
    fig, axes = plt.subplots(n, 2, figsize=(11, 4.2 * n), squeeze=False)
    markers = {"rk4": "o", "holloway": "^"}
    for row, (name, res) in enumerate(results.items()):
        dts = np.array(res["dt"])
        ax_dt, ax_cost = axes[row]
        for scheme, rows in res["integrators"].items():
            err = np.array(rows["error"]["max"], float)
            cost = np.array(rows["evaluations_per_second"], float)
            ok = np.isfinite(err)
            label = scheme + (" (× = diverged)" if not ok.all() else "")
            (line,) = ax_dt.loglog(dts[ok], err[ok], marker=markers.get(scheme, "s"), label=label)
            ax_cost.loglog(
                cost[ok], err[ok], marker=markers.get(scheme, "s"), color=line.get_color()
            )
            ymin = np.nanmin(err) if ok.any() else 1e-3
            for d in dts[~ok]:
                ax_dt.plot(d, ymin, "x", color=line.get_color(), ms=9)
        for p, ls, anchor, factor in ((2, ":", "holloway", 2.0), (4, "--", "rk4", 0.3)):
            e_anchor = res["integrators"].get(anchor, {}).get("error", {}).get("max", [math.nan])
            if np.isfinite(e_anchor[0]):
                ref_line = factor * e_anchor[0] * (dts / dts[0]) ** p
                ax_dt.loglog(dts, ref_line, "k" + ls, lw=0.8, label=f"∝ Δt^{p}")
        ax_dt.invert_xaxis()
        ax_dt.set_xticks(dts, [f"{d:g}" for d in dts])
        ax_dt.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax_dt.set_xlabel("Δt [s]")
        ax_dt.set_ylabel("max relative RMS error (heave, roll, pitch)")
        ax_dt.set_title(f"{name}: {res['description']}", fontsize=9)
        ax_dt.grid(True, which="both", alpha=0.3)
        ax_dt.legend(fontsize=8)
        ax_cost.set_xlabel("force evaluations per simulated second")
        ax_cost.set_ylabel("max relative RMS error")
        ax_cost.set_title(f"{name}: error against cost", fontsize=9)
        ax_cost.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", type=Path, default=Path("out/convergence.png"))
    parser.add_argument("--json", type=Path, default=None, help="write the numbers to this file")
    parser.add_argument("--duration", type=float, default=DURATION, help="simulated time [s]")
    parser.add_argument("--cases", nargs="+", choices=list(CASES), default=list(CASES))
    parser.add_argument(
        "--dts", type=float, nargs="+", default=list(DTS), help="time steps [s] (decreasing)"
    )
    parser.add_argument("--schemes", nargs="+", choices=list(SCHEMES), default=list(SCHEMES))
    parser.add_argument(
        "--heading-tolerance",
        type=float,
        default=FROZEN_HEADING,
        help="diffraction heading tolerance [deg]: 180 freezes X_D (default), 0.5 is the "
        "package's cache (force jumps, first order)",
    )
    parser.add_argument(
        "--replot", type=Path, default=None, help="redo table and figure from a --json file"
    )
    args = parser.parse_args(argv)
    if args.replot is not None:
        results = from_json_value(json.loads(args.replot.read_text()))["cases"]
        print(format_table(results))
        plot(results, args.output)
        print(f"figure: {args.output}")
        return 0
    dts = tuple(args.dts)
    for dt in dts:
        k = SAMPLE_DT / dt
        if abs(k - round(k)) > 1e-9 or abs(dt / REFERENCE_DT - round(dt / REFERENCE_DT)) > 1e-9:
            parser.error(f"dt = {dt} must divide {SAMPLE_DT} s and be a multiple of {REFERENCE_DT}")
    if abs(args.duration / SAMPLE_DT - round(args.duration / SAMPLE_DT)) > 1e-9:
        parser.error(f"--duration must be a multiple of {SAMPLE_DT} s")
    t0 = time.perf_counter()
    results = {
        name: study(CASES[name], args.duration, dts, args.heading_tolerance, tuple(args.schemes))
        for name in args.cases
    }
    print(format_table(results))
    print(f"\ntotal {time.perf_counter() - t0:.0f} s")
    plot(results, args.output)
    print(f"figure: {args.output}")
    if args.json is not None:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        payload = {
            "reference_dt": REFERENCE_DT,
            "sample_dt": SAMPLE_DT,
            "free_dofs": list(FREE_DOFS),
            "error_definition": "RMS(x - x_ref) / RMS(x_ref - x_ref(0)) on the 0.4 s grid",
            "cases": results,
        }
        args.json.write_text(json.dumps(to_json_value(payload), indent=1))
        print(f"numbers: {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
