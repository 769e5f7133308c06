#!/usr/bin/env python
"""Benchmark the 6-DOF simulator on the reference case "S175-full" (DESIGN.md §5).

Reference case "S175-full": the S175 hull meshed to the deck (``load_hull("s175")``, 2400
faces), free in 6 DOF at zero speed in head seas (β = 180°), JONSWAP Hs = 5 m, Tp = 11 s,
γ = 3.3, 50 components (seed 0), radiation memory on, diffraction and Ikeda roll damping on,
dt = 0.05 s. Two paths, timed in the same run:

* fast path: state-space radiation memory + the numba Froude–Krylov kernel;
* reference path: direct convolution of the retardation functions + the numpy Froude–Krylov
  reference (``fk_method="reference"``).

Printed (and written with ``--json PATH``):

* real-time factor (simulated s per wall s) of both paths, single ship, for RK4 (4 force
  evaluations per step, the ``ShipSetup`` default) and Holloway's μ-Taylor scheme (1 evaluation
  per step), and their ratio;
* the cost split of a step by force model (µs per evaluation and % of the step; the rest is the
  rigid-body terms, the context, the integrator and Python overhead);
* the cost of the memory term relative to constant coefficients (Matusiak case 2b);
* the accuracy of each integrator against RK4 at dt/2 over a short run (why RK4 is the
  default);
* the throughput of :class:`ship_gym.dynamics.batch.BatchSimulator` for 1, 16 and 64 ships
  (ship-steps/s), and of 16 independent :class:`Simulator` objects for comparison.

Threads: ``NUMBA_NUM_THREADS``, ``OMP_NUM_THREADS``, ``OPENBLAS_NUM_THREADS`` and
``MKL_NUM_THREADS`` are set to 1 *before* numpy and numba are imported (no threadpoolctl in the
environment): every number is single-thread. (With OpenBLAS's default threads, a loaded 2-core
machine made one 64 × 129 × 129 matrix product take ≈ 20 ms instead of 0.07 ms.) Timings are
medians over interleaved blocks of steps, so that a varying machine load hits all variants
alike; the load average is printed with them.

Usage::

    python scripts/bench_simulator.py [--json PATH] [--quick]
"""

from __future__ import annotations

import os

for _var in ("NUMBA_NUM_THREADS", "OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import datetime  # noqa: E402
import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from pathlib import Path  # noqa: E402

import numba  # noqa: E402
import numpy as np  # noqa: E402

from ship_gym.dynamics.batch import BatchSimulator, build_batch_simulator  # noqa: E402
from ship_gym.dynamics.ship import ShipSetup, build_simulator, wave_field_for  # noqa: E402
from ship_gym.dynamics.simulator import Simulator  # noqa: E402
from ship_gym.waves.sea_state import IrregularSea  # noqa: E402

DT = 0.05
HEADING = np.pi
SEA = IrregularSea(hs=5.0, tp=11.0, n_components=50)
INTEGRATORS = ("rk4", "holloway")
DEFAULT_INTEGRATOR = "rk4"


def _setup(path: str, integrator: str, dt: float = DT) -> ShipSetup:
    if path == "fast":
        return ShipSetup(radiation="state_space", fk_method="fast", integrator=integrator, dt=dt)
    if path == "reference":
        return ShipSetup(
            radiation="convolution", fk_method="reference", integrator=integrator, dt=dt
        )
    if path == "2b":
        return ShipSetup(radiation="2b", fk_method="fast", integrator=integrator, dt=dt)
    raise ValueError(path)


def _sim(
    path: str,
    integrator: str,
    seed: int = 0,
    sea: IrregularSea = SEA,
    dt: float = DT,
    heading: float = HEADING,
) -> Simulator:
    return build_simulator(
        _setup(path, integrator, dt), sea, wave_heading=heading, rng=np.random.default_rng(seed)
    )


def _interleaved(jobs: dict[str, tuple[Callable[[], None], int]], rounds: int) -> dict[str, float]:
    """Fastest wall time per unit of each job; jobs run round-robin, ``rounds`` blocks each.

    ``jobs[name] = (block, units)``: one call of ``block`` does ``units`` units of work. The
    minimum over blocks is the estimate least disturbed by other processes on the machine.
    """
    times: dict[str, list[float]] = {k: [] for k in jobs}
    for _ in range(rounds):
        for name, (block, units) in jobs.items():
            t0 = time.perf_counter()
            block()
            times[name].append((time.perf_counter() - t0) / units)
    return {k: float(np.min(v)) for k, v in times.items()}


def _stepper(sim, n: int) -> Callable[[], None]:
    def block() -> None:
        for _ in range(n):
            sim.step()

    return block


def _cost_split(sim: Simulator, n_steps: int, blocks: int = 5) -> dict[str, object]:
    """Time per evaluation of each force model and its share of a step.

    Each model's ``evaluate`` is wrapped (then restored) during ``blocks`` blocks of
    ``n_steps`` real steps; the fastest block (least disturbed by other processes) is reported.
    The rest of the step (context, gravity, Coriolis, kinematics, integrator, Python) is
    ``rigid_body_integrator_overhead``.
    """
    spent: dict[str, float] = {}
    calls: dict[str, int] = {}
    for f in sim.forces:

        def timed(ctx, states, _ev=f.evaluate, _name=f.name):
            t0 = time.perf_counter()
            out = _ev(ctx, states)
            spent[_name] += time.perf_counter() - t0
            calls[_name] += 1
            return out

        f.evaluate = timed  # type: ignore[method-assign]
    best: dict[str, object] | None = None
    try:
        for _ in range(blocks):
            for f in sim.forces:
                spent[f.name], calls[f.name] = 0.0, 0
            t0 = time.perf_counter()
            for _ in range(n_steps):
                sim.step()
            step = (time.perf_counter() - t0) / n_steps
            if best is None or step * 1e6 < best["step_us"]:  # type: ignore[operator]
                evals = max(calls.values()) / n_steps
                per_eval = {k: spent[k] / max(calls[k], 1) for k in spent}
                percent = {k: 100.0 * spent[k] / n_steps / step for k in spent}
                percent["rigid_body_integrator_overhead"] = 100.0 - sum(percent.values())
                best = {
                    "step_us": step * 1e6,
                    "evaluations_per_step": evals,
                    "per_evaluation_us": {k: v * 1e6 for k, v in per_eval.items()},
                    "percent_of_step": percent,
                }
    finally:
        for f in sim.forces:
            del f.evaluate  # back to the class method
    assert best is not None
    return best


def _paired_ratio(a, b, n_steps: int, rounds: int) -> float:
    """Median over rounds of (time of n_steps of a) / (time of n_steps of b), run back to back."""
    ratios = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        for _ in range(n_steps):
            a.step()
        t1 = time.perf_counter()
        for _ in range(n_steps):
            b.step()
        t2 = time.perf_counter()
        ratios.append((t1 - t0) / (t2 - t1))
    return float(np.median(ratios))


def _batch_cost_split(batch: BatchSimulator, n_steps: int) -> dict[str, object]:
    """The same split for a BatchSimulator (its built-in per-model timers; fastest of blocks)."""
    best: dict[str, object] | None = None
    for _ in range(5):
        batch.timings = {}
        t0 = time.perf_counter()
        for _ in range(n_steps):
            batch.step()
        step = (time.perf_counter() - t0) / n_steps
        if best is None or step < best["step_us"] * 1e-6:  # type: ignore[operator]
            evals = batch.evaluations_per_step
            per_eval = {k: v / n_steps / evals for k, v in batch.timings.items()}
            percent = {k: 100.0 * v * evals / step for k, v in per_eval.items()}
            percent["rigid_body_integrator_overhead"] = 100.0 - sum(percent.values())
            best = {
                "step_us": step * 1e6,
                "evaluations_per_step": evals,
                "per_evaluation_us": {k: v * 1e6 for k, v in per_eval.items()},
                "percent_of_step": percent,
            }
    batch.timings = None
    assert best is not None
    return best


def _print_split(label: str, s: dict) -> None:
    parts = ", ".join(
        f"{k} {s['per_evaluation_us'][k]:.0f} µs ({s['percent_of_step'][k]:.1f} %)"
        for k in s["per_evaluation_us"]
    )
    rest = s["percent_of_step"]["rigid_body_integrator_overhead"]
    print(
        f"  {label:28s} step {s['step_us']:7.0f} µs, {s['evaluations_per_step']:.0f} eval/step: "
        f"{parts}; rigid body + integrator + overhead {rest:.1f} %"
    )


def _accuracy(duration: float) -> dict[str, dict[str, float]]:
    """RMS error of heave, roll, pitch vs RK4 at dt/2, relative to the RMS motion.

    Same sea as the reference case but bow-quartering (β = 135°, so that roll is excited) and a
    10 s ramp. ``holloway_mu1``: Holloway with μ = 1 (the computed acceleration unblended,
    :class:`HollowayIntegrator`'s advice for an exact acceleration) instead of the
    simulator's default μ = m/(m + A∞).
    """
    sea = IrregularSea(hs=5.0, tp=11.0, n_components=50, ramp_time=10.0)
    beta = np.radians(135.0)
    truth = _sim("fast", "rk4", sea=sea, dt=DT / 2, heading=beta).run(duration)
    ref = truth.eta[::2]
    out: dict[str, dict[str, float]] = {}
    candidates: dict[str, Simulator] = {
        "rk4": _sim("fast", "rk4", sea=sea, heading=beta),
        "holloway": _sim("fast", "holloway", sea=sea, heading=beta),
    }
    src = _sim("fast", "holloway", sea=sea, heading=beta)
    mu1 = Simulator(
        src.hull,
        src.forces,
        wave_field=src.wave_field,
        dt=DT,
        integrator="holloway",
        mu=np.ones(6),
    )
    mu1.reset(eta=src.eta.copy())
    candidates["holloway_mu1"] = mu1
    for name, sim in candidates.items():
        try:
            eta = sim.run(duration).eta
        except Exception as exc:  # a diverging variant is a result too
            out[name] = {"error": str(exc)[:80]}  # type: ignore[dict-item]
            continue
        err = {}
        for dof, label in ((2, "heave"), (3, "roll"), (4, "pitch")):
            rms = float(np.sqrt(np.mean((ref[:, dof] - ref[:, dof].mean()) ** 2)))
            err[label] = float(np.sqrt(np.mean((eta[:, dof] - ref[:, dof]) ** 2)) / rms)
        out[name] = err
    return out


def _batch(n_ships: int, integrator: str) -> BatchSimulator:
    fields = [wave_field_for(SEA, HEADING, np.random.default_rng(seed)) for seed in range(n_ships)]
    return build_batch_simulator(_setup("fast", integrator), fields)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path, default=None, help="write the numbers here")
    parser.add_argument("--quick", action="store_true", help="short smoke run")
    args = parser.parse_args(argv)
    quick = args.quick
    t_start = time.perf_counter()
    rounds = 3 if quick else 9
    warm = 5 if quick else 20
    when = datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")
    load0 = os.getloadavg()

    # ------------------------------------------------------------- single ship, both paths
    paths = ("fast", "reference", "2b")
    sims = {(path, integ): _sim(path, integ) for path in paths for integ in INTEGRATORS}
    for sim in sims.values():
        for _ in range(warm):  # compilation, Holloway start-up, convolution history
            sim.step()
    fk = sims[("fast", "rk4")].forces[0]
    n_faces = int(fk.hull.mesh.faces.shape[0])
    n_states = int(sims[("fast", "rk4")].n_states)
    # blocks of similar wall time (≈ 0.1 s), so that each variant has the same chance of an
    # undisturbed block
    block = {
        "fast": 10 if quick else 40,
        "reference": 1 if quick else 4,
        "2b": 10 if quick else 40,
    }
    for integ in INTEGRATORS:
        if integ == "holloway":
            block = {k: 4 * v for k, v in block.items()}
        jobs = {f"{p}/{integ}": (_stepper(sims[(p, integ)], block[p]), block[p]) for p in block}
        if integ == "rk4":
            step_rk4 = _interleaved(jobs, rounds)
        else:
            step_hol = _interleaved(jobs, rounds)
    step = {**step_rk4, **step_hol}
    rtf = {integ: {p: DT / step[f"{p}/{integ}"] for p in block} for integ in INTEGRATORS}

    print(
        f"S175-full: S175 to the deck, {n_faces} faces; JONSWAP Hs 5 m Tp 11 s, 50 components, "
        f"head seas, U = 0; dt = {DT:.3f} s; {n_states} radiation states (fast path)"
    )
    print(f"measured {when}, numba {numba.__version__}, 1 thread, load average {load0[0]:.2f}")
    print()
    print("real-time factor (single ship, single thread)")
    print(f"  {'integrator':10s} {'fast':>9s} {'reference':>10s} {'speed-up':>9s} {'2b':>9s}")
    for integ in INTEGRATORS:
        r = rtf[integ]
        print(
            f"  {integ:10s} {r['fast']:9.1f} {r['reference']:10.2f} "
            f"{r['fast'] / r['reference']:8.1f}× {r['2b']:9.1f}"
        )
    print(f"  default integrator: {DEFAULT_INTEGRATOR} (see the accuracy table below)")

    # ------------------------------------------------------------- cost split by force
    print()
    print("cost split of a step (µs per evaluation; % of the step)")
    splits = {}
    for path in ("fast", "reference"):
        for integ in INTEGRATORS:
            n = (20 if path == "fast" else 4) * (4 if integ == "holloway" else 1)
            n = max(2, n // 4) if quick else n
            splits[f"{path}/{integ}"] = s = _cost_split(sims[(path, integ)], n)
            _print_split(f"Simulator {path} {integ}", s)
    for integ in INTEGRATORS:
        b1 = _batch(1, integ)
        for _ in range(3):
            b1.step()
        n = (5 if quick else 20) * (4 if integ == "holloway" else 1)
        splits[f"batch1/{integ}"] = s = _batch_cost_split(b1, n)
        _print_split(f"BatchSimulator(N=1) {integ}", s)

    # ------------------------------------------------------------- memory vs constant coeffs
    memory_ratio = {
        integ: _paired_ratio(
            sims[("fast", integ)],
            sims[("2b", integ)],
            (5 if quick else 20) * (4 if integ == "holloway" else 1),
            5 if quick else 15,
        )
        for integ in INTEGRATORS
    }
    rad = {
        k: splits[f"{k}/rk4"]["per_evaluation_us"]["radiation"]  # type: ignore[index]
        for k in ("fast", "reference")
    }
    split_2b = _cost_split(sims[("2b", "rk4")], 5 if quick else 20)
    rad_2b = split_2b["per_evaluation_us"]["radiation"]  # type: ignore[index]
    # the same ratio from the per-evaluation costs: 2b step with the radiation model swapped
    component_ratio = 1.0 + 4.0 * (rad["fast"] - rad_2b) / split_2b["step_us"]  # type: ignore[operator]
    print()
    print("memory term vs constant coefficients (case 2b), fast path")
    for integ in INTEGRATORS:
        print(
            f"  {integ:8s}: step time memory / 2b = {memory_ratio[integ]:.3f} "
            "(median of back-to-back block pairs)"
        )
    print(
        f"  radiation model per evaluation: state-space {rad['fast']:.1f} µs, convolution "
        f"{rad['reference']:.1f} µs, 2b {rad_2b:.1f} µs; from these, rk4 memory / 2b = "
        f"{component_ratio:.3f}"
    )

    # ------------------------------------------------------------- accuracy of the schemes
    duration = 10.0 if quick else 30.0
    acc = _accuracy(duration)
    print()
    print(
        f"accuracy over {duration:g} s (β = 135°, 10 s ramp) vs RK4 at dt/2: RMS error / RMS motion"
    )
    for name, err in acc.items():
        print(f"  {name:13s} " + ", ".join(f"{k} {v:.2e}" if isinstance(v, float) else f"{k} {v}"
                                            for k, v in err.items()))  # fmt: skip

    # ------------------------------------------------------------- batched throughput
    print()
    print("batched throughput, fast path (ship-steps / s)")
    sizes = (1, 4) if quick else (1, 16, 64)
    throughput: dict[str, dict[str, float]] = {}
    for integ in INTEGRATORS:
        jobs = {}
        for n_ships in sizes:
            b = _batch(n_ships, integ)
            for _ in range(3):  # compile + Holloway start-up
                b.step()
            steps = max(1, (64 if integ == "holloway" else 16) // n_ships)
            steps = max(1, steps // 4) if quick else steps
            jobs[str(n_ships)] = (_stepper(b, steps), steps * n_ships)
        n_single = sizes[-2] if len(sizes) > 2 else sizes[-1]
        singles = [_sim("fast", integ, seed) for seed in range(n_single)]
        for s in singles:
            for _ in range(3):
                s.step()

        def all_singles(singles=singles) -> None:
            for s in singles:
                s.step()

        jobs[f"{n_single}x single"] = (all_singles, n_single)
        per = _interleaved(jobs, rounds)
        throughput[integ] = {k: 1.0 / v for k, v in per.items()}
        print(f"  {integ:8s} " + ", ".join(f"{k}: {v:7.0f}" for k, v in throughput[integ].items()))
    ratio = (
        throughput["rk4"][str(sizes[-2] if len(sizes) > 2 else sizes[-1])]
        / throughput["rk4"][f"{n_single}x single"]
    )
    print(f"  batch of {n_single} vs {n_single} single simulators (rk4): {ratio:.2f}×")

    elapsed = time.perf_counter() - t_start
    load1 = os.getloadavg()
    print(f"\ntotal {elapsed:.0f} s; load average at the end {load1[0]:.2f}")

    if args.json is not None:
        batched = throughput[DEFAULT_INTEGRATOR]
        results = {
            "case": "S175-full",
            "measured_utc": when,
            "quick": quick,
            "threads": 1,
            "load_average": [load0[0], load1[0]],
            "n_faces": n_faces,
            "n_radiation_states": n_states,
            "dt": DT,
            "default_integrator": DEFAULT_INTEGRATOR,
            "realtime_factor_fast": rtf[DEFAULT_INTEGRATOR]["fast"],
            "realtime_factor_reference": rtf[DEFAULT_INTEGRATOR]["reference"],
            "speedup": rtf[DEFAULT_INTEGRATOR]["fast"] / rtf[DEFAULT_INTEGRATOR]["reference"],
            "memory_cost_ratio": memory_ratio[DEFAULT_INTEGRATOR],
            "batched_ship_steps_per_s": {k: v for k, v in batched.items() if "single" not in k},
            "single_simulators_ship_steps_per_s": {
                k.split("x")[0]: v for k, v in batched.items() if "single" in k
            },
            "realtime_factor": rtf,
            "memory_cost_ratio_by_integrator": memory_ratio,
            "memory_cost_ratio_from_components": component_ratio,
            "radiation_us_per_evaluation": {**rad, "2b": rad_2b},
            "cost_split": splits,
            "accuracy_vs_rk4_half_dt": acc,
            "batched_by_integrator": throughput,
            "elapsed_s": elapsed,
        }
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(results, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
