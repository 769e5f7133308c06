"""Figure: S175 heave and pitch RAOs in head seas at Fn 0, 0.186, 0.248 and 0.275.

Lines: the frequency-domain solver (:func:`ship_gym.hydro.rao.response_amplitude_operator`) with
the forward-speed linearisation of :mod:`ship_gym.hydro.forward_speed`; dashed: the same without
the Kirchhoff moment (``speed_terms="none"``, the time domain's model before issue #13); markers:
ShipX/VERES strip theory (tests/data, from the Marine Systems Simulator); crosses: the
time-domain engine's linear limit (regular waves of 0.1 m, state-space memory, nonlinear FK)
at a few wave lengths. Heave at the centre of gravity (as VERES), pitch over the wave slope k a.

A second figure (``--headings-out``) compares the solver with VERES at every heading at Fn 0.248
(β = 150, 120, 90, 60, 30°; tests/data/s175_veres_mss_all_headings.csv) with the engine's speed
terms and high-pass (issue #34).

Usage::

    python scripts/forward_speed_raos.py [--out docs/forward_speed/forward_speed_raos.png]
                                         [--headings-out docs/forward_speed/headings.png]
                                         [--no-time-domain]
"""

from __future__ import annotations

import argparse
import csv
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from tqdm import tqdm

from ship_gym.engine.ship import wave_field_for
from ship_gym.engine.simulator import Simulator
from ship_gym.forces.diffraction import Diffraction
from ship_gym.forces.froude_krylov import FroudeKrylovHydrostatics
from ship_gym.forces.radiation import RadiationMemory
from ship_gym.hull import equilibrium, load_hull
from ship_gym.hydro import as_arrays, load_database
from ship_gym.hydro.rao import response_amplitude_operator
from ship_gym.kinematics import encounter_frequency
from ship_gym.waves.sea_state import RegularWave

ROOT = Path(__file__).resolve().parents[1]
LPP, G = 175.0, 9.81
SPEEDS = {"0": (0.0, "0p000"), "0.186": (0.1862, "0p186"), "0.248": (0.2483, "0p248"),
          "0.275": (0.275, None)}  # fmt: skip
COLOURS = {"0": "0.3", "0.186": "tab:blue", "0.248": "tab:red", "0.275": "tab:green"}
HEAVE, PITCH = 2, 4


def reference(tag: str) -> np.ndarray:
    """(λ/L, ω, heave, pitch/k) columns of a VERES file."""
    rows = []
    with open(ROOT / "tests" / "data" / f"s175_head_seas_veres_mss_fn{tag}.csv") as fh:
        lines = [line for line in fh if not line.startswith("#")]
    for row in list(csv.reader(lines))[1:]:
        rows.append([float(row[0]), float(row[1]), float(row[4]), float(row[5])])
    return np.array(rows)


def heave_pitch(xi: np.ndarray, omega: np.ndarray, x_g: float) -> tuple[np.ndarray, np.ndarray]:
    k = omega**2 / G
    return np.abs(xi[..., HEAVE] - x_g * xi[..., PITCH]), np.abs(xi[..., PITCH]) / k


def time_domain(hull, db, base, omega: float, u: float) -> np.ndarray:
    """Complex heave/pitch amplitudes per unit wave amplitude of the engine's linear limit."""
    amp, dt, duration = 0.1, 0.1, 300.0
    w_e = float(encounter_frequency(omega, u, np.pi, G))
    field = wave_field_for(RegularWave(2 * amp, period=2 * np.pi / omega), np.pi)
    forces = [FroudeKrylovHydrostatics(hull, field), RadiationMemory(db), Diffraction(db, field)]
    free = (False, False, True, False, True, False)
    sim = Simulator(hull, forces, wave_field=field, dt=dt, free_dofs=free, forward_speed=u)
    sim.reset(eta=base)
    res = sim.run(duration)
    period = 2 * np.pi / abs(w_e)
    keep = res.t >= duration - max(1.0, np.floor(120.0 / period)) * period - 1e-9
    tt = res.t[keep]
    design = np.column_stack([np.cos(w_e * tt), np.sin(w_e * tt), np.ones_like(tt)])
    out = np.zeros(6, complex)
    for dof in (HEAVE, PITCH):
        c, *_ = np.linalg.lstsq(design, res.eta[keep, dof] - base[dof], rcond=None)
        out[dof] = complex(c[0], c[1]) / amp
    return out


def all_headings() -> np.ndarray:
    """Rows (U, Fn, β [deg], ω, λ/L, heave, roll/k, pitch/k) of the all-headings VERES file."""
    path = ROOT / "tests" / "data" / "s175_veres_mss_all_headings.csv"
    with open(path) as fh:
        lines = [line for line in fh if not line.startswith("#")]
    return np.array([[float(v) for v in row] for row in list(csv.reader(lines))[1:]])


def headings_figure(db, x_g: float, out: Path) -> None:
    """Heave and pitch at Fn 0.248 in bow, beam and quartering seas: solver vs VERES."""
    from ship_gym.hydro.forward_speed import default_speed_cutoff

    raw = all_headings()
    u = 10.2889
    headings = (150, 120, 90, 60, 30)
    w_max = float(as_arrays(db).omega[-1])
    fig, axes = plt.subplots(2, len(headings), figsize=(14, 5.2), sharex=True)
    lam = np.linspace(0.4, 3.0, 120)
    omega = np.sqrt(2 * np.pi * G / (lam * LPP))
    for col, beta in enumerate(headings):
        b = np.radians(beta)
        w_e = encounter_frequency(omega, u, b, G)
        ok = (np.abs(w_e) <= w_max) & (np.abs(w_e) > 0.02)
        xi = response_amplitude_operator(
            db, omega=omega[ok], heading=b, forward_speed=u, free_dofs=("Heave", "Pitch"),
            speed_cutoff=default_speed_cutoff(LPP, G),
        )  # fmt: skip
        h, p = heave_pitch(xi, omega[ok], x_g)
        ref = raw[(np.abs(raw[:, 0] - u) < 1e-3) & (raw[:, 2] == beta)]
        ref = ref[(ref[:, 4] >= 0.4) & (ref[:, 4] <= 3.0)]
        for row, (ours, theirs, unit) in enumerate(
            ((h, ref[:, 5], "heave at CG [m/m]"), (p, ref[:, 7], "pitch / (k ζₐ) [-]"))
        ):
            ax = axes[row, col]
            ax.plot(lam[ok], ours, "-", color="tab:red", lw=1.6, label="ship_gym (solver)")
            ax.plot(ref[:, 4], theirs, "o", color="tab:red", mfc="none", ms=5, label="VERES")
            ax.grid(alpha=0.3)
            if col == 0:
                ax.set_ylabel(unit)
            if row == 0:
                ax.set_title(f"β = {beta}°")
            else:
                ax.set_xlabel("wave length λ/L [-]")
    axes[0, 0].legend(fontsize=8)
    fig.suptitle("S175 at Fn 0.248 in bow, beam and quartering seas: solver vs ShipX/VERES")
    fig.tight_layout()
    fig.savefig(out, dpi=150)
    print(f"wrote {out}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "--out", type=Path, default=ROOT / "docs/forward_speed/forward_speed_raos.png"
    )
    parser.add_argument(
        "--headings-out",
        type=Path,
        default=ROOT / "docs/forward_speed/forward_speed_headings.png",
    )
    parser.add_argument("--no-time-domain", action="store_true", help="skip the engine's points")
    args = parser.parse_args()
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.headings_out.parent.mkdir(parents=True, exist_ok=True)

    hull, db = load_hull("s175"), load_database("s175")
    arr = as_arrays(db)
    eq = equilibrium(hull)
    base = np.array([0.0, 0.0, eq.heave, 0.0, eq.trim, 0.0])
    x_g = float(hull.mass.cog[0])
    lam = np.linspace(0.4, 3.0, 140)
    omega_all = np.sqrt(2 * np.pi * G / (lam * LPP))

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharex=True)
    td_points = [0.8, 1.0, 1.2, 1.5, 2.0]
    jobs = [(fn, lr) for fn in SPEEDS for lr in td_points] if not args.no_time_domain else []
    td_results: dict[str, list[tuple[float, float, float]]] = {fn: [] for fn in SPEEDS}
    for fn, lr in tqdm(jobs, desc="time-domain linear limits", unit="run"):
        u = SPEEDS[fn][0] * np.sqrt(G * LPP)
        w = float(np.sqrt(2 * np.pi * G / (lr * LPP)))
        if w + w**2 * u / G > arr.omega[-1]:
            continue
        h, p = heave_pitch(time_domain(hull, db, base, w, u), np.array(w), x_g)
        td_results[fn].append((lr, float(h), float(p)))

    for fn, (froude, tag) in SPEEDS.items():
        u = froude * np.sqrt(G * LPP)
        ok = omega_all + omega_all**2 * u / G <= arr.omega[-1]
        w = omega_all[ok]
        colour = COLOURS[fn]
        for terms, style in (("all", "-"), ("none", "--")):
            if terms == "none" and froude in (0.0, 0.275):
                continue
            xi = response_amplitude_operator(
                db, omega=w, heading=np.pi, forward_speed=u, free_dofs=("Heave", "Pitch"),
                speed_terms=terms,
            )  # fmt: skip
            h, p = heave_pitch(xi, w, x_g)
            label = f"Fn {fn}" + ("" if terms == "all" else ", no Kirchhoff moment")
            axes[0].plot(lam[ok], h, style, color=colour, lw=1.6 if terms == "all" else 1.0,
                         label=label)  # fmt: skip
            axes[1].plot(lam[ok], p, style, color=colour, lw=1.6 if terms == "all" else 1.0)
        if tag is not None:
            ref = reference(tag)
            sel = (ref[:, 0] >= 0.4) & (ref[:, 0] <= 3.0)
            kw = dict(color=colour, mfc="none", ms=5, ls="none")
            axes[0].plot(ref[sel, 0], ref[sel, 2], "o", label=f"VERES Fn {fn}", **kw)
            axes[1].plot(ref[sel, 0], ref[sel, 3], "o", **kw)
        if td_results[fn]:
            pts = np.array(td_results[fn])
            lab = "time domain (engine)" if fn == "0" else None
            axes[0].plot(pts[:, 0], pts[:, 1], "x", color=colour, ms=7, mew=1.6, label=lab)
            axes[1].plot(pts[:, 0], pts[:, 2], "x", color=colour, ms=7, mew=1.6)
    axes[0].set_ylabel("heave at CG |ξ₃|/ζₐ [m/m]")
    axes[1].set_ylabel("pitch |ξ₅|/(k ζₐ) [-]")
    for ax in axes:
        ax.set_xlabel("wave length λ/L [-]")
        ax.grid(alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    axes[1].legend(handles, labels, fontsize=7, ncol=2, loc="lower right")
    fig.suptitle("S175 in head seas: ship_gym (solver = engine's linear limit) vs ShipX/VERES")
    fig.tight_layout()
    fig.savefig(args.out, dpi=150)
    print(f"wrote {args.out}")
    headings_figure(db, x_g, args.headings_out)
    for fn, pts in td_results.items():
        for lr, h, p in pts:
            print(f"Fn {fn} λ/L {lr:.2f}: engine heave {h:.3f}, pitch/k {p:.3f}")


if __name__ == "__main__":
    main()
