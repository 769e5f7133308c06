#!/usr/bin/env python
"""Benchmark the 6-DOF simulator on the reference case "S175-full" (DESIGN.md §5).

Reference case "S175-full": the S175 hull meshed to the deck with ≥ 1500 faces, free in 6 DOF
at zero speed in head seas (β = 180°), JONSWAP Hs = 5 m, Tp = 11 s, γ = 3.3, 50 components
(seed 0), radiation memory on, diffraction and Ikeda roll damping on, dt = 0.05 s. Timed in
the same run:

* **fast path**: :class:`ship_gym.engine.compiled.CompiledShip` (K steps per compiled
  call; Holloway's μ-Taylor scheme, 1 force evaluation per step; state-space memory; the
  Froude–Krylov kernel with float32 wave sums) on the 1500-face mesh (``MESH_1500``); also
  with float64 wave sums and on the default 2400-face mesh;
* **reference path**: :class:`Simulator` with direct convolution of the retardation functions
  and the numpy Froude–Krylov reference (``fk_method="reference"``), Holloway, same meshes (the
  convolution has no compiled version: the engine's numpy path);
* one ship on the engine's two paths (a :class:`Simulator` is the engine with N = 1), RK4 and
  Holloway, default mesh: the numpy path (``backend="numpy"``: the row models stepped from
  Python) against the compiled backend (K steps per numba call), and the reference path.

The compiled-path ships start at t = 60 s, after the sea's 50 s ramp, so that they are timed in
the full sea. Printed (and written with ``--json PATH``; the headline keys
``realtime_factor_fast``, ``realtime_factor_reference``, ``speedup``, ``memory_cost_ratio``,
``batched_ship_steps_per_s`` are CPU-time figures of the fast path and the reference path;
``realtime_factor_fast`` is the median over three seas of whole 1000-s runs of the free ship,
``realtime_factor_fast_block`` the fastest 100-step block interleaved with the other variants,
``realtime_factor_reference`` the fastest 3-step block of the reference path, so that
``speedup`` = long-run fast / fastest reference is on the conservative side):

* real-time factor (simulated s per s) of every variant, wall and CPU time
  (``time.perf_counter``, ``time.process_time``: on a shared machine the CPU time is the
  steadier figure), and the fast/reference ratio;
* the cost split of the fast path's step by term (each timed alone in a compiled loop,
  :meth:`CompiledShip.term_costs`);
* the cost of the memory term relative to constant coefficients (Matusiak case 2b), compiled;
* the accuracy cost of the 1500-face mesh: GZ curve and heave/roll/pitch natural periods from
  free decays, against 2400 and 9600 faces;
* the single-ship tables (RK4/Holloway real-time factors of both paths, the per-model cost
  split on the numpy path from the engine's timers ``engine.timings``, memory vs 2b on both
  paths, integrator accuracy against RK4 at dt/2);
* throughput (ship-steps/s) of :class:`ship_gym.engine.batch.BatchSimulator` for 1, 16 and 64
  ships on both paths, of 16 compiled :class:`Simulator` objects stepped in turn, and, with the
  fast path's settings, of a compiled BatchSimulator and of N CompiledShips stepped in turn.

Threads: ``NUMBA_NUM_THREADS``, ``OMP_NUM_THREADS``, ``OPENBLAS_NUM_THREADS`` and
``MKL_NUM_THREADS`` are set to 1 *before* numpy and numba are imported (no threadpoolctl in the
environment): every number is single-thread. (With OpenBLAS's default threads, a loaded 2-core
machine made one 64 × 129 × 129 matrix product take ≈ 20 ms instead of 0.07 ms.) Timings are
medians over interleaved blocks of steps, so that a varying machine load hits all variants
alike; the load average is printed with them.

Usage::

    python benchmarks/bench_simulator.py [--json PATH] [--quick]
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

from ship_gym.engine.batch import (  # noqa: E402
    BatchSimulator,
    EngineBackend,
    build_batch_simulator,
)
from ship_gym.engine.compiled import CompiledShip, build_compiled_ship  # noqa: E402
from ship_gym.engine.ship import ShipSetup, build_simulator, wave_field_for  # noqa: E402
from ship_gym.engine.simulator import Simulator  # noqa: E402
from ship_gym.forces.froude_krylov import _fk_one_ship, _fk_one_ship_f32  # noqa: E402
from ship_gym.hull import load_hull, righting_arm  # noqa: E402
from ship_gym.io_utils import atomic_write_text  # noqa: E402
from ship_gym.kinematics import rotation_matrix  # noqa: E402
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
    backend: EngineBackend = "auto",
) -> Simulator:
    """The S175 of a path (``build_simulator``) on the engine's ``backend``.

    ``build_simulator`` picks the compiled backend when every model has a compiled version (the
    reference path's convolution has none: numpy path). Another backend means a new
    :class:`Simulator` from the same force models, at the same state and commands.
    """
    sim = build_simulator(
        _setup(path, integrator, dt), sea, wave_heading=heading, rng=np.random.default_rng(seed)
    )
    on_it = sim.engine.compiled if backend == "compiled" else not sim.engine.compiled
    if backend == "auto" or on_it:
        return sim
    out = Simulator(
        sim.hull,
        sim.forces,
        wave_field=sim.wave_field,
        forward_speed=sim.forward_speed,
        dt=sim.dt,
        integrator=sim.integrator_name,
        free_dofs=sim.free,
        backend=backend,
    )
    out.commands = sim.commands
    out.reset(eta=sim.eta, nu=sim.nu, t0=sim.t)
    return out


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


def _cost_split(engine: BatchSimulator, n_steps: int, blocks: int = 5) -> dict[str, object]:
    """Time per evaluation of each force model and its share of a step, on the numpy path.

    The engine's own per-model timers (``engine.timings = {}``) during ``blocks`` blocks of
    ``n_steps`` steps of :meth:`BatchSimulator.step` (the numpy path whatever the backend; the
    compiled backend runs every model in one numba call: see
    :meth:`CompiledShip.term_costs`); the fastest block (least disturbed by other processes) is
    reported. The rest of the step (context, gravity, Coriolis, kinematics, integrator, Python)
    is ``rigid_body_integrator_overhead``.
    """
    best: dict[str, object] | None = None
    for _ in range(blocks):
        engine.timings = {}
        t0 = time.perf_counter()
        for _ in range(n_steps):
            engine.step()
        step = (time.perf_counter() - t0) / n_steps
        if best is None or step < best["step_us"] * 1e-6:  # type: ignore[operator]
            evals = engine.evaluations_per_step
            per_eval = {k: v / n_steps / evals for k, v in engine.timings.items()}
            percent = {k: 100.0 * v * evals / step for k, v in per_eval.items()}
            percent["rigid_body_integrator_overhead"] = 100.0 - sum(percent.values())
            best = {
                "step_us": step * 1e6,
                "evaluations_per_step": evals,
                "per_evaluation_us": {k: v * 1e6 for k, v in per_eval.items()},
                "percent_of_step": percent,
            }
    engine.timings = None
    assert best is not None
    return best


def _paired_ratio(a, b, n_steps: int, rounds: int) -> float:
    """Median over rounds of (time of ``a.advance(n_steps)``) / (time of ``b.advance(n_steps)``),
    run back to back."""
    ratios = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        a.advance(n_steps)
        t1 = time.perf_counter()
        b.advance(n_steps)
        t2 = time.perf_counter()
        ratios.append((t1 - t0) / (t2 - t1))
    return float(np.median(ratios))


# ============================================================================ compiled fast path
# The S175 mesh at the smallest resolution the reference case allows (≥ 1500 faces): 50
# sections, 10 panels per side below the waterline, 4 above, 2 across the deck (1500 faces).
# Its GZ curve is within 4 mm of a 9600-face mesh up to 60° (the default 2400-face mesh: 2 mm);
# printed below together with the natural periods from free decays.
MESH_1500 = {"n_sections": 50, "n_below": 10, "n_above": 4, "n_deck": 2}
MESHES = {"1500": MESH_1500, "2400": {}}
FAST_MESH = "1500"
FAST_PRECISION = "float32"
# the compiled-path ships start at this time, after the sea's 50 s ramp: timed in full waves
T_FULL_SEA = 1.2 * SEA.ramp_time


def _timed(jobs: dict[str, tuple[Callable[[], None], int]], rounds: int) -> dict[str, dict]:
    """Wall and CPU time per unit of each job: jobs round-robin, the fastest of ``rounds``
    blocks for each clock (``time.perf_counter``, ``time.process_time``)."""
    wall: dict[str, list[float]] = {k: [] for k in jobs}
    cpu: dict[str, list[float]] = {k: [] for k in jobs}
    for _ in range(rounds):
        for name, (block, units) in jobs.items():
            w0, c0 = time.perf_counter(), time.process_time()
            block()
            wall[name].append((time.perf_counter() - w0) / units)
            cpu[name].append((time.process_time() - c0) / units)
    return {k: {"wall": float(np.min(wall[k])), "cpu": float(np.min(cpu[k]))} for k in jobs}


def _compiled(mesh: str, precision: str, **setup_kw) -> CompiledShip:
    setup = ShipSetup(integrator="holloway", hull_overrides=dict(MESHES[mesh]), **setup_kw)
    field = wave_field_for(SEA, HEADING, np.random.default_rng(0))
    ship = build_compiled_ship(setup, field, sea=SEA, wave_heading=HEADING, precision=precision)
    ship.reset(t0=T_FULL_SEA)
    return ship


def _advancer(ship: CompiledShip | BatchSimulator | Simulator, n: int) -> Callable[[], None]:
    """A block of ``n`` steps in one ``advance`` call (one compiled call on that backend)."""

    def block() -> None:
        ship.advance(n)

    return block


@numba.njit(cache=False)
def _kernel_loop(n, kernel_args, single):  # pragma: no cover - compiled
    """The Froude–Krylov kernel alone, n calls in compiled code (no Python overhead)."""
    out = np.zeros(6)
    for _ in range(n):
        if single:
            _fk_one_ship_f32(*kernel_args, out)
        else:
            _fk_one_ship(*kernel_args, out)
    return out


def _kernel_args(ship: CompiledShip) -> tuple:
    """The kernel's arguments at the ship's current state (its sea folded to O)."""
    lay = ship.sim.forces[0].panels._layout  # the BatchFroudeKrylov model
    w = ship.wave_field
    amp = w.phasor(ship.t) * np.exp(
        -1j * w.wavenumber * (ship.eta[0] * np.cos(w.direction) + ship.eta[1] * np.sin(w.direction))
    )
    rot = rotation_matrix(*ship.eta[3:])
    return (
        lay.body, lay.triangles, lay.tri_last, lay.tri_first, lay.spread, lay.weights,
        lay.areas, rot, 0.0, 0.0, float(ship.eta[2]), np.ascontiguousarray(w.wavenumber),
        np.cos(w.direction), np.sin(w.direction), np.ascontiguousarray(amp),
        ship.hull.rho * ship.hull.g,
    )  # fmt: skip


def _long_runs(quick: bool) -> dict:
    """Real-time factor of the fast path over long runs (CPU time of the whole run, chunks of
    1000 steps): the block figures above are the fastest blocks, while the kernel's cost varies
    with the state (wetted hull, crossing panels) and the free ship drifts and turns away from
    head seas (the diffraction cache is refreshed inside the compiled loop as it turns).
    Fresh ships from t = 60 s, the sea of seed 0 and of two more seeds."""
    duration = 200.0 if quick else 1000.0
    n_steps = round(duration / DT)
    runs = []
    setup = ShipSetup(integrator="holloway", hull_overrides=dict(MESHES[FAST_MESH]))
    for seed in (-1, 0) if quick else (-1, 0, 1, 2):  # −1: a warm-up run, not kept
        field = wave_field_for(SEA, HEADING, np.random.default_rng(abs(seed)))
        ship = build_compiled_ship(
            setup, field, sea=SEA, wave_heading=HEADING, precision=FAST_PRECISION
        )
        ship.reset(t0=T_FULL_SEA)
        ship.advance(1)  # compiled already: the first call only binds
        if seed < 0:
            ship.advance(min(n_steps, 4000))
            continue
        chunks = []
        for _ in range(n_steps // 1000):
            c0 = time.process_time()
            ship.advance(1000)
            chunks.append(time.process_time() - c0)
        runs.append(
            {
                "seed": seed,
                "simulated_s": len(chunks) * 1000 * DT,
                "realtime_factor_cpu": len(chunks) * 1000 * DT / float(np.sum(chunks)),
                "slowest_chunk_realtime_factor_cpu": 1000 * DT / float(np.max(chunks)),
                "final_yaw_deg": float(np.degrees(ship.eta[5])),
                "drift_m": float(np.hypot(ship.eta[0], ship.eta[1])),
                "diffraction_refreshes": ship.n_refreshes,
            }
        )
    return {"duration_s": duration, "runs": runs}


def _actuator_overhead(quick: bool) -> dict:
    """CPU cost of the fast path with the actuators on (Holtrop resistance, B-series propeller,
    Clarke manoeuvring, rudder under the PID autopilot, roll fins under their controller) over
    the same force set without them, at the ship's service speed (Fn 0.25), the same sea and
    state: interleaved blocks of 1000 steps, min and median of the per-step ratio."""
    speed = 0.25 * float(np.sqrt(9.81 * 175.0))
    base = dict(integrator="holloway", hull_overrides=dict(MESHES[FAST_MESH]), speed=speed)
    field = wave_field_for(SEA, HEADING, np.random.default_rng(0))
    ships = {
        "without": build_compiled_ship(ShipSetup(**base), field, precision=FAST_PRECISION),
        "with": build_compiled_ship(
            ShipSetup(
                **base, propulsion=True, manoeuvring=True, rudder="autopilot", fins="controller"
            ),
            field,
            precision=FAST_PRECISION,
        ),
    }
    for ship in ships.values():
        ship.reset(t0=T_FULL_SEA)
        ship.advance(200)
    blocks = 3 if quick else 9
    times: dict[str, list[float]] = {k: [] for k in ships}
    for _ in range(blocks):
        for name, ship in ships.items():
            c0 = time.process_time()
            ship.advance(1000)
            times[name].append((time.process_time() - c0) / 1000)
    ratios = np.array(times["with"]) / np.array(times["without"])
    return {
        "step_us_cpu_without": 1e6 * float(np.min(times["without"])),
        "step_us_cpu_with": 1e6 * float(np.min(times["with"])),
        "ratio_min": float(ratios.min()),
        "ratio_median": float(np.median(ratios)),
        "realtime_factor_with_actuators_cpu": DT / float(np.median(times["with"])),
    }


def _compiled_section(quick: bool, rounds: int) -> dict:
    """Real-time factors of the compiled stepper (both meshes and precisions), of the
    reference path on the same meshes, and the cost split of the fast path's step."""
    warm = 40 if quick else 200  # compilation, start-up, waves ramped up
    ships = {(m, p): _compiled(m, p) for m in MESHES for p in ("float32", "float64")}
    refs = {m: _reference_sim(m) for m in MESHES}
    for s in ships.values():
        s.advance(warm)
    for r in refs.values():
        r.advance(3 if quick else 6)
    n_fast = 20 if quick else 100
    n_ref = 1 if quick else 3
    jobs = {f"compiled {p} {m}": (_advancer(s, n_fast), n_fast) for (m, p), s in ships.items()}
    jobs |= {f"reference {m}": (_advancer(r, n_ref), n_ref) for m, r in refs.items()}
    times = _timed(jobs, rounds)
    rtf = {k: {c: DT / v[c] for c in ("wall", "cpu")} for k, v in times.items()}

    # cost split of the fast path's step: every term timed alone in a compiled loop at the
    # ship's current state (CompiledShip.term_costs); the rest of the step (integrator, stage
    # copies, the call) is the difference to the step time measured in the same blocks
    fast = ships[(FAST_MESH, FAST_PRECISION)]
    two_b = _compiled(FAST_MESH, FAST_PRECISION, radiation="2b")
    two_b.advance(warm)
    # the kernel's cost depends on the state (wet vertices, crossing triangles): mean over
    # states 1 s apart
    samples = []
    for _ in range(2 if quick else 6):
        samples.append(fast.term_costs(repeats=20 if quick else 100, rounds=3 if quick else 5))
        fast.advance(20)
    costs = {k: float(np.mean([c[k] for c in samples])) for k in samples[0]}
    # paired blocks (memory vs 2b back to back), median of the ratios, like _paired_ratio
    ratios, steps = [], []
    for _ in range(5 if quick else 15):
        c0 = time.process_time()
        fast.advance(n_fast)
        c1 = time.process_time()
        two_b.advance(n_fast)
        c2 = time.process_time()
        ratios.append((c1 - c0) / (c2 - c1))
        steps.append((c1 - c0) / n_fast)
    memory_ratio = float(np.median(ratios))
    step = min(min(steps), times[f"compiled {FAST_PRECISION} {FAST_MESH}"]["cpu"])
    split_us = {k: v * 1e6 for k, v in costs.items()}
    split_us["integrator_and_call"] = step * 1e6 - sum(split_us.values())
    # (≈ 1 µs; it comes out negative when the block of steps hit cheaper states than the
    # kernel samples, or the machine load changed between the two measurements)
    return {
        "times": times,
        "rtf": rtf,
        "step_us_cpu": step * 1e6,
        "split_us_cpu": split_us,
        "memory_cost_ratio": memory_ratio,
        "n_faces": {m: int(ships[(m, "float64")].hull.mesh.faces.shape[0]) for m in MESHES},
        "n_states": fast.n_states,
    }


def _reference_sim(mesh: str) -> Simulator:
    setup = ShipSetup(
        radiation="convolution",
        fk_method="reference",
        integrator="holloway",
        hull_overrides=dict(MESHES[mesh]),
    )
    sim = build_simulator(setup, SEA, wave_heading=HEADING, rng=np.random.default_rng(0))
    sim.reset(eta=sim.eta.copy(), t0=T_FULL_SEA)
    return sim


def _decay_periods(ship: CompiledShip, dof: int, offset: float, duration: float) -> float:
    """Natural period [s] of a free decay in calm water: mean spacing of the upward zero
    crossings of the DOF's deviation from equilibrium (linear interpolation)."""
    eta = ship.initial_eta.copy()
    eta[dof] += offset
    ship.reset(eta=eta)
    rec = ship.run(round(duration / ship.dt))
    x = rec["eta"][:, dof] - ship.initial_eta[dof]
    t = rec["t"]
    up = np.flatnonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))
    crossings = t[up] + (t[up + 1] - t[up]) * (-x[up] / (x[up + 1] - x[up]))
    return float(np.mean(np.diff(crossings))) if crossings.size > 1 else float("nan")


def _mesh_accuracy(quick: bool) -> dict:
    """GZ curve and heave/roll/pitch natural periods on the meshes, against a fine mesh."""
    meshes = {
        **MESHES,
        "9600": {"n_sections": 120, "n_below": 24, "n_above": 12, "n_deck": 8},
    }
    heels = np.array([5.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0])
    out: dict[str, dict] = {}
    for name, kw in meshes.items():
        hull = load_hull("s175", **kw)
        gz = righting_arm(hull, heels).gz
        setup = ShipSetup(integrator="holloway", hull_overrides=dict(kw))
        ship = build_compiled_ship(setup, None, precision="float64")
        duration = 60.0 if quick else 120.0
        periods = {
            "heave": _decay_periods(ship, 2, 0.3, duration / 2),
            "roll": _decay_periods(ship, 3, np.radians(5.0), duration),
            "pitch": _decay_periods(ship, 4, np.radians(0.5), duration / 2),
        }
        out[name] = {
            "faces": int(hull.mesh.faces.shape[0]),
            "gz_m": gz.tolist(),
            "periods_s": periods,
        }
    fine = out["9600"]
    for v in out.values():
        v["gz_max_abs_diff_vs_9600_m"] = float(
            np.max(np.abs(np.array(v["gz_m"]) - np.array(fine["gz_m"])))
        )
        v["period_rel_diff_vs_9600"] = {
            k: v["periods_s"][k] / fine["periods_s"][k] - 1.0 for k in v["periods_s"]
        }
    out["heels_deg"] = heels.tolist()  # type: ignore[assignment]
    return out


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
    10 s ramp. Holloway runs with the engine's μ = 1 (the computed acceleration unblended, the
    added mass being on the left-hand side).
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


def _batch(
    n_ships: int, integrator: str, fast_mesh: bool = False, backend: EngineBackend = "auto"
) -> BatchSimulator:
    """BatchSimulator of the single-ship fast setup (default mesh, float64 wave sums), or
    (``fast_mesh``) with the compiled fast path's mesh and float32 wave sums, on ``backend``."""
    fields = [wave_field_for(SEA, HEADING, np.random.default_rng(seed)) for seed in range(n_ships)]
    setup = _setup("fast", integrator)
    if fast_mesh:
        setup = ShipSetup(
            radiation="state_space",
            fk_method="fast32" if FAST_PRECISION == "float32" else "fast",  # type: ignore[arg-type]
            integrator=integrator,  # type: ignore[arg-type]
            hull_overrides=dict(MESHES[FAST_MESH]),
        )
    return build_batch_simulator(setup, fields, backend=backend)


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

    # ------------------------------------------------------------- compiled fast path
    comp = _compiled_section(quick, rounds)
    fast_key = f"compiled {FAST_PRECISION} {FAST_MESH}"
    ref_key = f"reference {FAST_MESH}"
    print(
        "S175-full: S175 to the deck; JONSWAP Hs 5 m Tp 11 s, 50 components, head seas, U = 0; "
        f"dt = {DT:.3f} s; radiation memory on ({comp['n_states']} states), diffraction, Ikeda "
        "roll damping"
    )
    print(
        f"measured {when}, numba {numba.__version__}, 1 thread, load average {load0[0]:.2f} "
        f"({os.cpu_count()} cores shared with other work: CPU time is the steadier figure)"
    )
    print()
    print("real-time factor, single ship, one core (fastest block of each; wall / CPU time)")
    for name, r in comp["rtf"].items():
        mesh = name.split()[-1]
        t_us = comp["times"][name]["cpu"] * 1e6
        print(
            f"  {name:24s} {comp['n_faces'][mesh]:5d} faces: {r['wall']:8.1f}× wall, "
            f"{r['cpu']:8.1f}× CPU  ({t_us:8.1f} µs CPU / step)"
        )
    speed_up = {c: comp["rtf"][fast_key][c] / comp["rtf"][ref_key][c] for c in ("wall", "cpu")}
    print(
        f"  fast path = CompiledShip (Holloway, {FAST_PRECISION} wave sums, {FAST_MESH} faces); "
        f"reference path = Simulator (Holloway, convolution memory, numpy Froude–Krylov) on the "
        f"same mesh: speed-up {speed_up['wall']:.0f}× wall, {speed_up['cpu']:.0f}× CPU"
    )
    long = _long_runs(quick)
    long_rtf = [r["realtime_factor_cpu"] for r in long["runs"]]
    slowest = min(r["slowest_chunk_realtime_factor_cpu"] for r in long["runs"])
    print(
        f"  long runs ({long['duration_s']:.0f} s simulated each, whole-run CPU time, seeds "
        f"{[r['seed'] for r in long['runs']]}): "
        + ", ".join(f"{x:.0f}×" for x in long_rtf)
        + f" (slowest 50-s chunk {slowest:.0f}×; the free ship ends"
        f" {max(abs(r['final_yaw_deg']) for r in long['runs']):.0f}° off head seas at most,"
        f" {max(r['diffraction_refreshes'] for r in long['runs'])} diffraction refreshes at most)"
    )
    print(
        f"  headline (median of the long runs): {np.median(long_rtf):.0f}× real time, "
        f"{np.median(long_rtf) / comp['rtf'][ref_key]['cpu']:.0f}× the reference path"
    )
    actuators = _actuator_overhead(quick)
    print(
        f"  with actuators (propulsion, manoeuvring, rudder + autopilot, fins + controller): "
        f"{actuators['step_us_cpu_with']:.1f} vs {actuators['step_us_cpu_without']:.1f} µs CPU "
        f"per step, ratio min {actuators['ratio_min']:.3f}, median "
        f"{actuators['ratio_median']:.3f}; "
        f"{actuators['realtime_factor_with_actuators_cpu']:.0f}× real time"
    )
    goal_us = DT / 1000.0 * 1e6
    print(
        f"  goal ≥ 1000× real time = ≤ {goal_us:.0f} µs per step; fast path "
        f"{comp['step_us_cpu']:.1f} µs CPU per step"
    )
    print()
    print("cost split of the fast path's step (µs CPU; one evaluation per step)")
    for k, v in comp["split_us_cpu"].items():
        print(f"  {k:28s} {v:7.1f} µs  ({100 * v / comp['step_us_cpu']:5.1f} %)")
    print(
        "  (each term timed alone in a compiled loop at the ship's state; integrator_and_call = "
        "step − Σ terms)"
    )
    print(
        f"  memory term vs constant coefficients (case 2b): step time ratio "
        f"{comp['memory_cost_ratio']:.3f} (median of back-to-back block pairs, CPU time)"
    )

    # ------------------------------------------------------------- mesh resolution accuracy
    mesh_acc = _mesh_accuracy(quick)
    print()
    print("mesh resolution: GZ [m] and natural periods [s] (free decays, calm water) vs 9600 faces")
    print("  heel [deg]          " + " ".join(f"{h:6.0f}" for h in mesh_acc["heels_deg"]))
    for name, v in mesh_acc.items():
        if name == "heels_deg":
            continue
        per = v["periods_s"]
        rel = v["period_rel_diff_vs_9600"]
        print(
            f"  {v['faces']:5d} faces GZ      " + " ".join(f"{g:6.3f}" for g in v["gz_m"])
            + f"   max |ΔGZ| {1000 * v['gz_max_abs_diff_vs_9600_m']:.1f} mm"
        )  # fmt: skip
        print(
            "              periods "
            + ", ".join(f"{k} {per[k]:.2f} s ({100 * rel[k]:+.2f} %)" for k in per)
        )

    # ------------------------------------------------------------- one ship, both engine paths
    # the default mesh: the engine's numpy path (row models stepped from Python) against its
    # compiled backend (K steps in one numba call); the reference path (convolution memory) has
    # no compiled version and runs on the numpy path
    variants = {
        "fast/numpy": ("fast", "numpy"),
        "fast/compiled": ("fast", "compiled"),
        "reference/numpy": ("reference", "numpy"),
        "2b/numpy": ("2b", "numpy"),
        "2b/compiled": ("2b", "compiled"),
    }
    sims = {
        (v, integ): _sim(path, integ, backend=backend)  # type: ignore[arg-type]
        for v, (path, backend) in variants.items()
        for integ in INTEGRATORS
    }
    for sim in sims.values():
        sim.advance(warm)  # compilation, Holloway start-up, convolution history
    n_faces = int(sims[("fast/numpy", DEFAULT_INTEGRATOR)].hull.mesh.faces.shape[0])
    # blocks of similar wall time (≈ 0.1 s), so that each variant has the same chance of an
    # undisturbed block; Holloway: 4× the steps (1 evaluation per step instead of 4)
    block = {
        "fast/numpy": 10 if quick else 40,
        "fast/compiled": 20 if quick else 100,
        "reference/numpy": 1 if quick else 4,
        "2b/numpy": 10 if quick else 40,
        "2b/compiled": 20 if quick else 100,
    }
    step: dict[str, float] = {}
    for integ in INTEGRATORS:
        per = 4 if integ == "holloway" else 1
        jobs = {
            f"{v}/{integ}": (_advancer(sims[(v, integ)], per * n), per * n)
            for v, n in block.items()
        }
        step |= _interleaved(jobs, rounds)
    rtf = {integ: {v: DT / step[f"{v}/{integ}"] for v in variants} for integ in INTEGRATORS}

    print()
    print(
        f"one ship on the engine, default mesh {n_faces} faces: real-time factor (wall), numpy "
        "path (Python-level stepping) vs compiled backend (one call per block)"
    )
    print(
        f"  {'integrator':10s} {'fast numpy':>10s} {'compiled':>9s} {'ratio':>7s} "
        f"{'reference':>10s} {'numpy/ref':>9s} {'2b numpy':>9s} {'compiled':>9s}"
    )
    for integ in INTEGRATORS:
        r = rtf[integ]
        print(
            f"  {integ:10s} {r['fast/numpy']:10.1f} {r['fast/compiled']:9.1f} "
            f"{r['fast/compiled'] / r['fast/numpy']:6.1f}× {r['reference/numpy']:10.2f} "
            f"{r['fast/numpy'] / r['reference/numpy']:8.1f}× {r['2b/numpy']:9.1f} "
            f"{r['2b/compiled']:9.1f}"
        )
    print(
        "  (ratio: compiled / numpy; numpy/ref: fast setup / reference path, both on the numpy "
        "path; reference = convolution memory + numpy Froude–Krylov reference)"
    )
    print(f"  default integrator: {DEFAULT_INTEGRATOR} (see the accuracy table below)")

    # ------------------------------------------------------------- cost split by force
    print()
    print("cost split of a step on the numpy path (engine.timings; µs per evaluation; % of step)")
    splits = {}
    for path in ("fast", "reference"):
        for integ in INTEGRATORS:
            n = (20 if path == "fast" else 4) * (4 if integ == "holloway" else 1)
            n = max(2, n // 4) if quick else n
            splits[f"{path}/{integ}"] = s = _cost_split(sims[(f"{path}/numpy", integ)].engine, n)
            _print_split(f"{path} {integ}", s)
    print("  (the compiled backend's split by term: 'cost split of the fast path's step' above)")

    # ------------------------------------------------------------- memory vs constant coeffs
    memory_ratio = {
        f"{backend}/{integ}": _paired_ratio(
            sims[(f"fast/{backend}", integ)],
            sims[(f"2b/{backend}", integ)],
            block[f"fast/{backend}"] // 2 * (4 if integ == "holloway" else 1),
            5 if quick else 15,
        )
        for backend in ("numpy", "compiled")
        for integ in INTEGRATORS
    }
    rad = {
        k: splits[f"{k}/rk4"]["per_evaluation_us"]["radiation"]  # type: ignore[index]
        for k in ("fast", "reference")
    }
    split_2b = _cost_split(sims[("2b/numpy", "rk4")].engine, 5 if quick else 20)
    rad_2b = split_2b["per_evaluation_us"]["radiation"]  # type: ignore[index]
    # the same ratio from the per-evaluation costs: 2b step with the radiation model swapped
    component_ratio = 1.0 + 4.0 * (rad["fast"] - rad_2b) / split_2b["step_us"]  # type: ignore[operator]
    print()
    print("memory term vs constant coefficients (case 2b), fast setup, default mesh")
    for key, value in memory_ratio.items():
        print(
            f"  {key:18s}: step time memory / 2b = {value:.3f} (median of back-to-back block pairs)"
        )
    print(
        f"  radiation model per evaluation (numpy path): state-space {rad['fast']:.1f} µs, "
        f"convolution {rad['reference']:.1f} µs, 2b {rad_2b:.1f} µs; from these, rk4 memory / "
        f"2b = {component_ratio:.3f}"
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
    print(
        f"batched throughput, fast setup (default mesh {n_faces} faces, float64 wave sums), "
        "ship-steps / s (wall)"
    )
    sizes = (1, 4) if quick else (1, 16, 64)
    n_single = sizes[-2] if len(sizes) > 2 else sizes[-1]
    throughput: dict[str, dict[str, float]] = {}
    for integ in INTEGRATORS:
        jobs = {}
        steps_of: dict[str, int] = {}
        for backend in ("numpy", "compiled"):
            for n_ships in sizes:
                b = _batch(n_ships, integ, backend=backend)  # type: ignore[arg-type]
                b.advance(3)  # compile + Holloway start-up
                steps = max(1, (64 if integ == "holloway" else 16) // n_ships)
                steps *= 4 if backend == "compiled" else 1
                steps = max(1, steps // 4) if quick else steps
                steps_of[f"{backend} {n_ships}"] = steps
                jobs[f"{backend} {n_ships}"] = (_advancer(b, steps), steps * n_ships)
        singles = [_sim("fast", integ, seed, backend="compiled") for seed in range(n_single)]
        for s in singles:
            s.advance(3)
        per_single = steps_of[f"compiled {n_single}"]

        def all_singles(singles=singles, n=per_single) -> None:
            for s in singles:
                s.advance(n)

        jobs[f"{n_single} x Simulator"] = (all_singles, n_single * per_single)
        per = _interleaved(jobs, rounds)
        throughput[integ] = {k: 1.0 / v for k, v in per.items()}
        for backend in ("numpy", "compiled"):
            print(
                f"  {integ:8s} BatchSimulator(N) {backend:8s} "
                + ", ".join(f"{n}: {throughput[integ][f'{backend} {n}']:7.0f}" for n in sizes)
            )
        print(
            f"  {integ:8s} {n_single} × Simulator (compiled, in turn): "
            f"{throughput[integ][f'{n_single} x Simulator']:7.0f}"
        )
    tp = throughput[DEFAULT_INTEGRATOR]
    print(
        f"  {DEFAULT_INTEGRATOR}: compiled batch of {n_single} vs {n_single} Simulators in turn "
        f"{tp[f'compiled {n_single}'] / tp[f'{n_single} x Simulator']:.2f}×; compiled vs numpy "
        f"batch of {sizes[-1]} {tp[f'compiled {sizes[-1]}'] / tp[f'numpy {sizes[-1]}']:.2f}×"
    )
    # the fast path's settings (Holloway, float32 wave sums, 1500 faces): a compiled
    # BatchSimulator with N ships (one call for all), and N CompiledShips stepped one after the
    # other (ship-steps / s, wall and CPU)
    jobs = {}
    for n_ships in sizes:
        b = _batch(n_ships, "holloway", fast_mesh=True, backend="compiled")
        b.advance(3)
        steps = max(1, (64 if quick else 256) // n_ships)
        jobs[f"batch {n_ships}"] = (_advancer(b, steps), steps * n_ships)
    compiled_ships = [_compiled(FAST_MESH, FAST_PRECISION) for _ in range(sizes[-1])]
    for c in compiled_ships:
        c.advance(3)
    for n_ships in sizes:
        per_ship = max(1, (64 if quick else 256) // n_ships)

        def all_compiled(ships=compiled_ships[:n_ships], n=per_ship) -> None:
            for c in ships:
                c.advance(n)

        jobs[f"compiled {n_ships}"] = (all_compiled, n_ships * per_ship)
    fast_tp = _timed(jobs, rounds)
    batched_fast = {
        kind: {str(n): {c: 1.0 / fast_tp[f"{kind} {n}"][c] for c in ("wall", "cpu")} for n in sizes}
        for kind in ("batch", "compiled")
    }
    print(
        f"  fast-path settings (holloway, {FAST_PRECISION}, {FAST_MESH} faces, compiled), "
        "ship-steps / s wall (CPU):"
    )
    for kind, label in (("batch", "BatchSimulator(N)"), ("compiled", "N × CompiledShip")):
        print(
            f"    {label:18s} "
            + ", ".join(
                f"{n}: {v['wall']:7.0f} ({v['cpu']:7.0f})" for n, v in batched_fast[kind].items()
            )
        )

    elapsed = time.perf_counter() - t_start
    load1 = os.getloadavg()
    print(f"\ntotal {elapsed:.0f} s; load average at the end {load1[0]:.2f}")

    if args.json is not None:
        results = {
            "case": "S175-full",
            "measured_utc": when,
            "quick": quick,
            "threads": 1,
            "load_average": [load0[0], load1[0]],
            "dt": DT,
            # headline: the compiled fast path vs the reference path on the same mesh, CPU time
            "fast_path": (
                f"CompiledShip, holloway, {FAST_PRECISION} wave sums, {FAST_MESH}-face mesh"
            ),
            "reference_path": "Simulator, holloway, convolution memory, numpy Froude-Krylov",
            "n_faces": comp["n_faces"][FAST_MESH],
            "n_radiation_states": comp["n_states"],
            # headline fast-path figure: the median over seeds of whole 1000-s runs (what a
            # user gets); the fastest interleaved 100-step block is kept beside it
            "realtime_factor_fast": float(np.median(long_rtf)),
            "realtime_factor_fast_block": comp["rtf"][fast_key]["cpu"],
            "long_runs": long,
            "actuator_overhead": actuators,
            "realtime_factor_reference": comp["rtf"][ref_key]["cpu"],
            "speedup": float(np.median(long_rtf)) / comp["rtf"][ref_key]["cpu"],
            "speedup_block": speed_up["cpu"],
            "memory_cost_ratio": comp["memory_cost_ratio"],
            "batched_ship_steps_per_s": {n: v["cpu"] for n, v in batched_fast["batch"].items()},
            "realtime_factor_fast_wall": comp["rtf"][fast_key]["wall"],
            "realtime_factor_reference_wall": comp["rtf"][ref_key]["wall"],
            "speedup_wall": speed_up["wall"],
            "step_us_cpu_fast": comp["step_us_cpu"],
            "cost_split_fast_us_cpu": comp["split_us_cpu"],
            "compiled_realtime_factors": comp["rtf"],
            "compiled_times_s": comp["times"],
            "batched_fast_path": batched_fast,
            "mesh_accuracy": mesh_acc,
            "simulator_default_integrator": DEFAULT_INTEGRATOR,
            "simulator_n_faces": n_faces,
            # one ship, default mesh: integrator → variant ("fast/numpy", "fast/compiled",
            # "reference/numpy", "2b/numpy", "2b/compiled") → real-time factor (wall)
            "realtime_factor": rtf,
            # default integrator, ship-steps/s (wall): "numpy N", "compiled N" (BatchSimulator
            # of N ships), "M x Simulator" (M compiled Simulators stepped in turn)
            "engine_ship_steps_per_s": throughput[DEFAULT_INTEGRATOR],
            "memory_cost_ratio_by_backend_integrator": memory_ratio,
            "memory_cost_ratio_from_components": component_ratio,
            "radiation_us_per_evaluation": {**rad, "2b": rad_2b},
            "cost_split": splits,
            "accuracy_vs_rk4_half_dt": acc,
            "batched_by_integrator": throughput,
            "elapsed_s": elapsed,
        }
        args.json.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_text(args.json, json.dumps(results, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
