#!/usr/bin/env python
"""IMO manoeuvring checks of the S175 at service speed, a speed trial and the autopilot step.

Runs on the 6-DOF simulator (all DOFs free, calm water, state-space radiation, dt = 0.1 s):

* 35° turning circle → advance, transfer, tactical diameter (MSC.137(76): ≤ 4.5 L, ≤ 5 L);
* 10°/10° and 20°/20° zig-zags → overshoot angles against the L/V-dependent limits, and the
  initial turning ability (≤ 2.5 L);
* speed trial: commanded shaft speed → steady speed, against the propeller's calm-water balance
  (1 − t) T(n, (1 − w) U) = R_T(U) (``Propeller.steady_speed_for``);
* autopilot: course keeping and a 20° heading step (overshoot, settling time);
* the Nomoto K′, T′ identified from the linearised sway–yaw model.

Outputs: a printed report, a figure (default ``out/manoeuvres.png``: turning track with the
advance and tactical diameter marked, zig-zag heading/rudder series, R vs (1 − t)T, autopilot
step) and with ``--json PATH`` the numbers: ``advance_over_L``, ``tactical_diameter_over_L``,
``zigzag10_first_overshoot_deg``, ``zigzag10_second_overshoot_deg``,
``zigzag20_first_overshoot_deg`` and more (limits, pass/fail table, speed trial, autopilot,
Nomoto indices, run times).

``--dt-check`` repeats the turning circle and the zig-zags at dt = 0.05 s and prints the relative
changes; ``--dof-check`` repeats them with heave, roll and pitch held (3-DOF manoeuvring).

Usage::

    python scripts/manoeuvres.py [--output out/manoeuvres.png] [--json PATH] [--dt 0.1]
                                 [--dt-check] [--dof-check] [--no-progress]
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from ship_gym.analysis import manoeuvres as man
from ship_gym.engine.ship import build_simulator
from ship_gym.hull import load_hull
from ship_gym.io_utils import atomic_write_text


def _trials(setup, progress: bool):
    tc = man.turning_circle(setup, 35.0, progress=progress)
    z10 = man.zigzag(setup, 10.0, progress=progress)
    z20 = man.zigzag(setup, 20.0, progress=progress)
    return tc, z10, z20


def _metric_vector(tc, z10, z20) -> dict[str, float]:
    return {
        "advance_over_L": tc.advance_over_L,
        "transfer_over_L": tc.transfer_over_L,
        "tactical_diameter_over_L": tc.tactical_diameter_over_L,
        "zigzag10_first_overshoot_deg": z10.first_overshoot_deg,
        "zigzag10_second_overshoot_deg": z10.second_overshoot_deg,
        "zigzag20_first_overshoot_deg": z20.first_overshoot_deg,
        "initial_turning_over_L": z10.initial_turning_over_L,
    }


def _compare(label: str, ref: dict[str, float], other: dict[str, float]) -> dict[str, float]:
    rel = {k: other[k] / ref[k] - 1.0 for k in ref}
    print(f"{label}: relative change of the metrics")
    for k, v in rel.items():
        print(f"  {k:32s} {ref[k]:9.4f} → {other[k]:9.4f}  ({v:+.3%})")
    return rel


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--hull", default="s175")
    parser.add_argument("--dt", type=float, default=0.1, help="physics time step [s]")
    parser.add_argument("--output", default="out/manoeuvres.png", help="figure (PNG)")
    parser.add_argument("--json", default=None, help="write the numbers to this JSON file")
    parser.add_argument("--dt-check", action="store_true", help="repeat at dt = 0.05 s")
    parser.add_argument(
        "--dof-check", action="store_true", help="repeat with heave, roll, pitch held"
    )
    parser.add_argument("--no-progress", action="store_true")
    args = parser.parse_args(argv)
    progress = not args.no_progress
    start = time.perf_counter()

    hull = load_hull(args.hull)
    length = hull.particulars.lpp
    setup = man.trial_setup(args.hull, dt=args.dt)
    speed = setup.speed
    print(
        f"{args.hull}: L = {length:.1f} m, service speed U = {speed:.4f} m/s (Fn 0.25), "
        f"L/V = {length / speed:.2f} s; 6 DOF free, calm water, state-space radiation, "
        f"dt = {setup.dt} s"
    )

    # ---------------------------------------------------------------- IMO trials
    tc, z10, z20 = _trials(setup, progress)
    payload = man.report(length, speed, tc, z10, z20)
    m = tc.metrics
    print(
        f"\nturning circle 35° (stbd): advance {tc.advance_over_L:.3f} L, transfer "
        f"{tc.transfer_over_L:.3f} L, tactical diameter {tc.tactical_diameter_over_L:.3f} L; "
        f"90° after {m.time_to_90:.0f} s, 180° after {m.time_to_180:.0f} s; at 540°: diameter "
        f"2U/r = {tc.steady_diameter_over_L:.2f} L, speed {tc.steady_speed:.2f} m/s "
        f"({tc.steady_speed / tc.approach_speed:.0%} of the approach), heel "
        f"{tc.steady_roll_deg:+.1f}° (max outward {tc.max_outward_heel_deg:.1f}°, inward "
        f"{tc.max_inward_heel_deg:.1f}°) [{tc.wall_time:.0f} s wall]"
    )
    for z in (z10, z20):
        shoots = ", ".join(f"{o:.2f}°" for o in z.metrics.overshoots_deg)
        print(
            f"{z.rudder_order_deg:g}°/{z.switch_deg:g}° zig-zag: overshoots {shoots}; first "
            f"reversal after {z.metrics.reversal_times[0]:.1f} s "
            f"({z.initial_turning_over_L:.3f} L run) [{z.wall_time:.0f} s wall]"
        )
    rows = man.imo_criteria([tc, z10, z20], length, speed)
    print("\nIMO MSC.137(76):")
    print(man.format_criteria(rows))

    # ---------------------------------------------------------------- Nomoto indices
    sim = build_simulator(setup)
    man.trim_shaft_speed(sim, speed)
    k, t = man.nomoto_of(sim)
    payload["nomoto"] = {
        "K_per_s": k,
        "T_s": t,
        "K_prime": k * length / speed,
        "T_prime": t * speed / length,
    }
    print(
        f"\nNomoto (linearised sway–yaw model): K = {k:.4f} 1/s, T = {t:.1f} s; "
        f"K′ = {k * length / speed:.2f}, T′ = {t * speed / length:.2f}"
    )

    # ---------------------------------------------------------------- speed trial
    n_service = float(sim.commands["shaft_speed"])
    shaft = [f * n_service for f in (0.6, 0.8, 1.0, 1.1)]
    st = man.speed_trial(setup, shaft, duration=300.0, progress=progress)
    payload["speed_trial"] = st.summary()
    payload["speed_trial_wake_fraction"] = st.wake_fraction
    payload["speed_trial_thrust_deduction"] = st.thrust_deduction
    print(
        f"\nspeed trial (0.6–1.1 × the trimmed service shaft speed; 300 s per shaft speed from "
        f"the predicted speed, Aitken-extrapolated; rudder 0°) [{st.wall_time:.0f} s wall]:"
    )
    print(
        "   rpm   U_sim [m/s]  U_pred [m/s]  error   U_pred+rudder  R_T [kN]  (1-t)T [kN]  "
        "rudder drag [kN]"
    )
    for p in st.points:
        print(
            f"  {p.rpm:6.1f}  {p.steady_speed:9.4f}  {p.predicted_speed:11.4f}  "
            f"{p.relative_error:+.2%}  {p.predicted_speed_with_rudder:11.4f}  "
            f"{p.resistance / 1e3:8.1f}  {p.net_thrust / 1e3:10.1f}  {p.rudder_drag / 1e3:10.1f}"
        )

    # ---------------------------------------------------------------- autopilot
    ap = man.autopilot_step(
        man.trial_setup(args.hull, dt=args.dt, rudder="autopilot"), 20.0, progress=progress
    )
    payload["autopilot"] = {
        "hold_max_deviation_deg": ap.hold_max_deviation_deg,
        "step_deg": ap.step_deg,
        "overshoot_pct": ap.overshoot_pct,
        "settling_time_1deg_s": ap.settling_time,
        "rise_time_10_90_s": ap.rise_time,
        "max_rudder_deg": ap.max_rudder_deg,
    }
    print(
        f"\nautopilot: course held within {ap.hold_max_deviation_deg:.2e}° over 200 s; 20° step: "
        f"overshoot {ap.overshoot_pct:.1f} %, rise (10–90 %) {ap.rise_time:.0f} s, settled "
        f"within ±1° after {ap.settling_time:.0f} s, max rudder {ap.max_rudder_deg:.1f}° "
        f"[{ap.wall_time:.0f} s wall]"
    )

    # ---------------------------------------------------------------- checks
    ref = _metric_vector(tc, z10, z20)
    if args.dt_check:
        other = _trials(man.trial_setup(args.hull, dt=0.05), progress)
        payload["dt_check_relative_change"] = _compare(
            f"dt 0.05 s vs {args.dt} s", ref, _metric_vector(*other)
        )
    if args.dof_check:
        held = man.trial_setup(
            args.hull, dt=args.dt, free_dofs=(True, True, False, False, False, True)
        )
        other = _trials(held, progress)
        payload["dof_check_relative_change"] = _compare(
            "heave, roll, pitch held vs all free", ref, _metric_vector(*other)
        )

    # ---------------------------------------------------------------- figure
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 3, figsize=(17, 10))
    man.plot_turning_circle(axes[0, 0], tc)
    man.plot_zigzag(axes[0, 1], z10)
    man.plot_zigzag(axes[0, 2], z20)
    man.plot_speed_trial(axes[1, 0], st)
    man.plot_heading_step(axes[1, 1], ap)
    ax = axes[1, 2]
    ax.plot(tc.t, tc.speed / tc.approach_speed, label="U/U₀")
    ax.plot(tc.t, tc.roll_deg / 10.0, label="heel/10° (+ into the turn)")
    ax.plot(tc.t, tc.yaw_rate_deg_s, label="r [°/s]")
    ax.plot(tc.t, tc.drift_deg / 10.0, label="drift/10°")
    ax.set(xlabel="t since the rudder order [s]", title="turning circle: speed, heel, r, drift")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    Path(args.output).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.output, dpi=100)
    plt.close(fig)
    print(f"\nwrote {args.output}")

    total = time.perf_counter() - start
    payload["wall_time_s"]["speed_trial"] = st.wall_time
    payload["wall_time_s"]["autopilot"] = ap.wall_time
    payload["wall_time_s"]["total"] = total
    payload["dt_s"] = setup.dt
    if args.json:
        text = json.dumps(payload, indent=2, default=float)
        if any(not math.isfinite(v) for v in _numbers(payload)):
            print("warning: non-finite numbers in the report", file=sys.stderr)
        atomic_write_text(Path(args.json), text)
        print(f"wrote {args.json}")
    print(f"total {total:.0f} s wall")
    return 0


def _numbers(obj):
    if isinstance(obj, dict):
        for v in obj.values():
            yield from _numbers(v)
    elif isinstance(obj, list | tuple):
        for v in obj:
            yield from _numbers(v)
    elif isinstance(obj, float | int | np.floating) and not isinstance(obj, bool):
        yield float(obj)


if __name__ == "__main__":
    raise SystemExit(main())
