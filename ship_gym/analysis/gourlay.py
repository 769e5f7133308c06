"""Gourlay (2021): quadrature of the retardation functions — Filon against Simpson, sine against
cosine form — for the S175 sway acceleration kernel L22(t) (his Fig. 1–2).

Compares, for t up to 100 s:

* Filon quadrature (Gourlay eq. 4–10) on the database grid,
* Simpson's rule on the database grid (erratic at large t: Gourlay Fig. 2),
* Simpson's rule on a 5× finer grid (B/ω interpolated by a cubic spline; Gourlay §3),
* Filon on the 5× finer grid (reference),
* the sine form (Gourlay eq. 3) against the cosine form (eq. 2) (Gourlay Fig. 1).

Data: :func:`s175_case` takes the sway–sway coefficients of the bundled S175 database (the ω = ∞
entry gives A(∞)); :func:`synthetic_case` is an analytic sway-like case on Gourlay's grid
ω = 0:0.05:2.5 rad/s, with B(ω) = Σ cₖ xₖ²/(1 + xₖ²)³, xₖ = ω/aₖ, whose kernel
L(t) = Σ cₖ aₖt(1 + aₖt)e^{−aₖt}/8 is known exactly. ``scripts/reproduce_gourlay.py`` draws the
figure.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.interpolate import CubicSpline

from ship_gym.hydro.retardation import acceleration_kernel, kernel_decay

__all__ = [
    "LATE_T",
    "REFINE",
    "T_MAX",
    "compute",
    "plot",
    "s175_case",
    "summarise",
    "synthetic_case",
]

T_MAX = 100.0
"""End of the compared kernels [s] (Gourlay Fig. 1–2)."""
DT = 0.1
"""Time step of the compared kernels [s]."""
LATE_T = 50.0
"""Start of the "large t" window [s]."""
REFINE = 5
"""Refinement of the frequency grid (Gourlay: Δω = 0.05 → 0.01 rad/s)."""

# synthetic sway-like case: (c_k, a_k [rad/s])
SYNTHETIC_TERMS = ((1.0, 0.6), (0.5, 1.1))
SYNTHETIC_A_INF = 1.0


def synthetic_case() -> dict:
    """Analytic sway-like coefficients on Gourlay's grid, with the exact L(t)."""
    omega = np.arange(0.0, 2.5 + 1e-9, 0.05)
    b = np.zeros_like(omega)
    a_minus = np.zeros_like(omega)
    for c, a in SYNTHETIC_TERMS:
        x = omega / a
        b += c * x**2 / (1 + x**2) ** 3
        z = 1j * x + 1.0
        kh = c * (1.0 / z + 1.0 / z**2 - 2.0 / z**3) / 8.0  # K̂(iω) of a e^{−at}(1+at−a²t²)/8
        with np.errstate(divide="ignore", invalid="ignore"):
            a_minus += np.where(
                omega > 0, kh.imag / np.where(omega > 0, omega, 1.0), 3 * c / (8 * a)
            )

    def exact(t: np.ndarray) -> np.ndarray:
        return sum(
            (c * (a * t) * (1 + a * t) * np.exp(-a * t) / 8.0 for c, a in SYNTHETIC_TERMS),
            start=np.zeros_like(t, dtype=float),
        )

    return {
        "name": "synthetic sway-like case",
        "omega": omega,
        "damping": b,
        "added_mass": a_minus + SYNTHETIC_A_INF,
        "added_mass_inf": SYNTHETIC_A_INF,
        "exact": exact,
        "units": "normalised",
    }


def s175_case() -> dict:
    """Sway–sway coefficients of the bundled S175 database."""
    from ship_gym.hydro import load_database  # the database module is built separately

    ds = load_database("s175")
    omega_all = np.asarray(ds["omega"].values, dtype=float)
    sel = {"radiating_dof": "Sway", "influenced_dof": "Sway"}
    a_all = np.asarray(ds["added_mass"].sel(sel).values, dtype=float)
    b_all = np.asarray(ds["radiation_damping"].sel(sel).values, dtype=float)
    inf = np.isinf(omega_all)
    if np.any(inf):
        a_inf = float(a_all[inf][0])
    elif "added_mass_inf" in ds:
        a_inf = float(ds["added_mass_inf"].sel(sel).values)
    else:
        raise ValueError("the S175 database has no ω = ∞ entry (or added_mass_inf): need A(∞)")
    finite = np.isfinite(omega_all)
    order = np.argsort(omega_all[finite])
    return {
        "name": "S175 sway (L22)",
        "omega": omega_all[finite][order],
        "damping": b_all[finite][order],
        "added_mass": a_all[finite][order],
        "added_mass_inf": a_inf,
        "exact": None,
        "units": "SI (kg/s)",
    }


def compute(case: dict) -> dict:
    """All kernels of the comparison on t = 0:0.1:100 s."""
    w = case["omega"]
    b = case["damping"]
    t = np.arange(0.0, T_MAX + 1e-9, DT)
    d = np.diff(w)
    uniform = bool(np.allclose(d, d.mean(), rtol=1e-6))
    # 5× finer grid from 0 (B(0) = 0 prepended when the database starts above 0)
    w0 = np.concatenate([[0.0], w]) if w[0] > 0 else w
    b0 = np.concatenate([[0.0], b]) if w[0] > 0 else b
    n_fine = REFINE * (w0.size - 1)
    n_fine += n_fine % 2
    w_fine = np.linspace(0.0, w0[-1], n_fine + 1)
    b_fine = CubicSpline(w0, b0)(w_fine)
    sine = {"damping": b}
    out = {
        "t": t,
        "filon": acceleration_kernel(w, t, method="filon", **sine),
        "simpson": acceleration_kernel(w, t, method="simpson", **sine),
        "simpson_fine": acceleration_kernel(w_fine, t, damping=b_fine, method="simpson"),
        "filon_fine": acceleration_kernel(w_fine, t, damping=b_fine, method="filon"),
        "cosine": acceleration_kernel(
            w,
            t,
            added_mass=case["added_mass"],
            added_mass_inf=case["added_mass_inf"],
            form="cosine",
            method="filon",
        ),
        "uniform": uniform,
        "delta_omega": float(d.min()),
        "delta_omega_fine": float(w_fine[1] - w_fine[0]),
    }
    if case["exact"] is not None:
        out["exact"] = case["exact"](t)
    return out


def summarise(case: dict, res: dict) -> dict:
    """Numbers for the JSON report."""
    t = res["t"]
    late = t >= LATE_T
    ref = res["filon_fine"]
    peak = float(np.max(np.abs(ref)))
    methods = ("filon", "simpson", "simpson_fine", "cosine")
    summary = {
        "case": case["name"],
        "units": case["units"],
        "omega_min": float(case["omega"][0]),
        "omega_max": float(case["omega"][-1]),
        "n_omega": int(case["omega"].size),
        "grid_uniform": res["uniform"],
        "delta_omega": res["delta_omega"],
        "delta_omega_fine": res["delta_omega_fine"],
        "t_max": T_MAX,
        "late_window_start": LATE_T,
        "max_abs_L_filon_fine": peak,
        "max_late_abs_diff_vs_filon_fine": {
            m: float(np.max(np.abs(res[m] - ref)[late])) for m in methods
        },
        "decay_ratio_last_5pct": {
            m: float(kernel_decay(t, res[m]).ratio) for m in (*methods, "filon_fine")
        },
        "L0": {m: float(res[m][0]) for m in (*methods, "filon_fine")},
    }
    if "exact" in res:
        summary["max_abs_error_vs_exact"] = {
            m: float(np.max(np.abs(res[m] - res["exact"]))) for m in (*methods, "filon_fine")
        }
        summary["max_late_abs_error_vs_exact"] = {
            m: float(np.max(np.abs(res[m] - res["exact"])[late])) for m in (*methods, "filon_fine")
        }
    return summary


def plot(case: dict, res: dict, path: Path) -> None:
    """Three panels (whole window, large t, sine vs cosine form) saved to ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = res["t"]
    dw = res["delta_omega"]
    fig, axes = plt.subplots(3, 1, figsize=(9, 10))
    ax = axes[0]
    ax.plot(t, res["filon"], label=f"Filon, Δω = {dw:.3g}")
    ax.plot(t, res["simpson"], label=f"Simpson, Δω = {dw:.3g}", alpha=0.8)
    ax.plot(t, res["simpson_fine"], "--", label=f"Simpson, Δω = {res['delta_omega_fine']:.3g}")
    if "exact" in res:
        ax.plot(t, res["exact"], "k:", label="exact")
    ax.set_title(f"{case['name']}: sine form (Gourlay eq. 3), cf. Gourlay Fig. 2")
    ax = axes[1]
    late = t >= LATE_T
    ax.plot(t[late], res["filon"][late], label="Filon")
    ax.plot(t[late], res["simpson"][late], label="Simpson", alpha=0.8)
    ax.plot(t[late], res["simpson_fine"][late], "--", label="Simpson, 5× finer")
    ax.set_title(f"large t (≥ {LATE_T:g} s)")
    ax = axes[2]
    ax.plot(t, res["filon"], label="sine form (eq. 3)")
    ax.plot(t, res["cosine"], label="cosine form (eq. 2)")
    ax.set_title("sine vs cosine form, Filon (cf. Gourlay Fig. 1)")
    ax.set_xlabel("t [s]")
    for ax in axes:
        ax.set_ylabel(f"L22(t) [{case['units']}]")
        ax.axhline(0.0, color="0.6", lw=0.5)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)
