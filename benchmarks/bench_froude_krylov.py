#!/usr/bin/env python
"""Benchmark the nonlinear Froude–Krylov + hydrostatic kernel (DESIGN.md §5).

Reference case: the S175 hull (``load_hull("s175")``: 2400 vertices, 4796 triangles) floating at
its calm-water equilibrium with 5° heel and a yaw, in a sea of 50 components (k uniform in
0.01–0.3 rad/m, directions uniform over ±90°, Hs = 4 m). Measured in one run:

* ``method="fast"``, ``method="fast32"`` (float32 wave sums) and ``method="reference"`` time
  per evaluation (public API, Python overhead included), their ratios and the largest
  difference of each fast result from the reference (scaled by the largest force and moment
  component), and the fast paths' cost per (vertex, component) pair;
* the batched kernel (:func:`froude_krylov_hydrostatic_batch`) throughput in ship evaluations per
  second for 1, 16 and 64 ships (serial, the default) and, with ``--parallel``, the numba-threaded
  variant (``parallel=True``: prange over ships, ``NUMBA_NUM_THREADS`` threads);
* with ``--torch`` (and ``--parallel``), the batched kernels again while a small torch MLP runs
  between the calls, as in an RL loop (policy forward, then environment step): numba's OpenMP
  threads and torch's intra-op threads then share the cores (DESIGN.md §5).

Times are robust to other load on the machine: each is the smallest of several rounds' medians.

Usage::

    python benchmarks/bench_froude_krylov.py [--json PATH] [--components 50] [--parallel] [--torch]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from ship_gym.forces.froude_krylov import (
    HullPanels,
    WaveComponents,
    froude_krylov_hydrostatic,
    froude_krylov_hydrostatic_batch,
)
from ship_gym.hull import equilibrium, load_hull
from ship_gym.io_utils import atomic_write_text
from ship_gym.kinematics import rotation_matrix

SHIP_COUNTS = (1, 16, 64)


def _time(fn, budget: float = 1.0, rounds: int = 7, between=None) -> float:
    """Time of one call [s]: the smallest of ``rounds`` medians, within ~``budget`` seconds."""
    fn()  # warm-up (compilation, caches)
    t0 = time.perf_counter()
    fn()
    once = max(time.perf_counter() - t0, 1e-7)
    per_round = max(3, int(budget / rounds / once))
    medians = []
    for _ in range(rounds):
        samples = []
        for _ in range(per_round):
            if between is not None:
                between()
            t0 = time.perf_counter()
            fn()
            samples.append(time.perf_counter() - t0)
        medians.append(float(np.median(samples)))
    return min(medians)


def _sea(n: int, rng: np.random.Generator, hs: float = 4.0):
    k = rng.uniform(0.01, 0.3, n)
    chi = rng.uniform(-np.pi / 2, np.pi / 2, n)
    a = rng.uniform(0.5, 1.5, n)
    a *= np.sqrt((hs / 4.0) ** 2 * 2.0 / np.sum(a**2))  # Σ a²/2 = (Hs/4)²
    phasor = a * np.exp(1j * rng.uniform(0.0, 2.0 * np.pi, n))
    return WaveComponents.from_arrays(k, chi), phasor


def _torch_policy():
    """A small MLP forward pass on 64 observations (None when torch is not installed)."""
    try:
        import torch
    except ImportError:
        return None
    net = torch.nn.Sequential(
        torch.nn.Linear(32, 256), torch.nn.Tanh(), torch.nn.Linear(256, 256), torch.nn.Tanh()
    )
    obs = torch.randn(64, 32)

    def forward():
        with torch.no_grad():
            net(obs)

    return forward


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=Path, default=None, help="write the numbers here")
    parser.add_argument("--components", type=int, default=50)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--parallel", action="store_true", help="also time parallel=True")
    parser.add_argument("--torch", action="store_true", help="also time next to a torch MLP")
    args = parser.parse_args(argv)

    hull = load_hull("s175")
    panels = HullPanels.from_mesh(hull.mesh)
    rng = np.random.default_rng(args.seed)
    waves, phasor = _sea(args.components, rng)
    heel = np.radians(5.0)
    eq = equilibrium(hull, heel)
    pos = np.array([120.0, -40.0, eq.heave])
    rot = rotation_matrix(heel, eq.trim, 0.3)
    n_v, n_t, n_c = panels.vertices.shape[0], panels.triangles.shape[0], args.components

    def run(method):
        return froude_krylov_hydrostatic(
            panels, waves, phasor, pos, rot, rho=hull.rho, g=hull.g, method=method
        )

    fast, fast32, ref = run("fast"), run("fast32"), run("reference")
    scale = np.r_[[np.abs(ref[:3]).max()] * 3, [np.abs(ref[3:]).max()] * 3]
    err = float(np.max(np.abs(fast - ref) / scale))
    err32 = float(np.max(np.abs(fast32 - ref) / scale))
    t_fast = _time(lambda: run("fast"), budget=2.0)
    t_fast32 = _time(lambda: run("fast32"), budget=2.0)
    t_ref = _time(lambda: run("reference"), budget=2.0)
    print(f"S175: {n_v} vertices, {n_t} triangles, {n_c} wave components (Hs 4 m)")
    print(f"fast      : {t_fast * 1e6:9.1f} µs / evaluation")
    print(f"reference : {t_ref * 1e6:9.1f} µs / evaluation")
    print(f"speed-up  : {t_ref / t_fast:9.1f} ×   (max scaled difference {err:.1e})")
    print(f"fast      : {t_fast * 1e9 / (n_v * n_c):9.2f} ns / (vertex, component) pair, all in")
    print(f"real time : {0.05 / t_fast:9.0f} × at dt = 0.05 s, one evaluation per step")
    print(
        f"fast32    : {t_fast32 * 1e6:9.1f} µs / evaluation, {t_fast / t_fast32:.2f}× the fast "
        f"kernel, {t_fast32 * 1e9 / (n_v * n_c):.2f} ns / pair (max scaled difference from the "
        f"reference {err32:.1e})"
    )

    results: dict[str, object] = {
        "fast_us": t_fast * 1e6,
        "reference_us": t_ref * 1e6,
        "speedup": t_ref / t_fast,
        "ns_per_pair": t_fast * 1e9 / (n_v * n_c),
        "max_scaled_difference": err,
        "fast32_us": t_fast32 * 1e6,
        "fast32_max_scaled_difference": err32,
        "fast32_speedup_vs_fast": t_fast / t_fast32,
        "n_vertices": n_v,
        "n_triangles": n_t,
        "n_components": n_c,
    }

    brng = np.random.default_rng(args.seed + 1)
    ships = []
    for _ in range(max(SHIP_COUNTS)):
        w, c = _sea(n_c, brng)
        x, y = brng.uniform(-500.0, 500.0, 2)
        rot_s = rotation_matrix(*brng.uniform(-0.2, 0.2, 2), brng.uniform(-np.pi, np.pi))
        ships.append((w, w.local_amplitudes(c, x, y), eq.heave + brng.uniform(-0.5, 0.5), rot_s))

    def batch_args(n_ships: int):
        sel = ships[:n_ships]
        return (
            np.array([w.wavenumber for w, *_ in sel]),
            np.array([w.cos_direction for w, *_ in sel]),
            np.array([w.sin_direction for w, *_ in sel]),
            np.array([a for _, a, _, _ in sel]),
            np.array([z for *_, z, _ in sel]),
            np.array([r for *_, r in sel]),
        )

    policy = _torch_policy() if args.torch else None
    if args.torch and policy is None:
        print("torch is not installed: --torch ignored")
    variants = [("serial", False, None)]
    if args.parallel:
        variants.append(("parallel", True, None))
    if policy is not None:
        variants.append(("serial+torch", False, policy))
        if args.parallel:
            variants.append(("parallel+torch", True, policy))
    if args.parallel or policy is not None:
        import numba

        threads = f"numba threads {numba.get_num_threads()}"
        if policy is not None:
            import torch

            threads += f", torch threads {torch.get_num_threads()}"
        print(threads)
    for name, parallel, between in variants:
        throughput = {}
        for n_ships in SHIP_COUNTS:
            b = batch_args(n_ships)

            def call(b=b, parallel=parallel):
                return froude_krylov_hydrostatic_batch(
                    panels, *b, rho=hull.rho, g=hull.g, parallel=parallel
                )

            t = _time(call, budget=1.5, between=between)
            throughput[str(n_ships)] = n_ships / t
            print(
                f"batched {name:15s} {n_ships:3d} ships: {t * 1e3:8.3f} ms / call, "
                f"{n_ships / t:7.0f} ship evaluations / s"
            )
        suffix = "" if name == "serial" else "_" + name.replace("+", "_")
        results["batched_ship_evals_per_s" + suffix] = throughput

    if args.json is not None:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        atomic_write_text(args.json, json.dumps(results, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
