"""Write ``s175_veres_mss_all_headings.csv`` from the VERES file ``input.re1`` of the MSS.

The file is the Marine Systems Simulator's ``HYDRO/vessels_shipx/s175/input.re1`` (git blob
b51d05c37afeba103e6632805cd98219e12e1cdc; see README.md in this folder). Run from the
repository root with the path of that file: ``python tests/data/extract_veres_mss.py RE1``.

Format of ``input.re1`` (VERES 4.02.3 motion transfer functions): eight header lines, then
"n_speeds n_headings n_frequencies n_dofs"; for each speed a line (speed [m/s], sinkage, trim,
motion origin x, z), for each heading a line (VERES heading [deg], 0 = head seas), for each
frequency a line (wave frequency [rad/s]) and n_dofs lines "dof Re Im" (translations [m/m],
rotations [rad/m], about the motion origin = the CG).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

G, LPP = 9.81, 175.0
HEADINGS_VERES = (0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0)
SPEEDS_KNOTS = (0.0, 15.0, 20.0)  # Fn 0, 0.186, 0.248 (the file also has 5 and 10 kn)
KNOT = 1852.0 / 3600.0
HEADER = "\n".join(
    [
        "# S175 container ship, regular seas at all headings: linear heave, roll and pitch RAOs",
        "# COMPUTED by ShipX / VERES 4.02.3 (SINTEF Ocean, 2-D linear strip theory; not",
        "# experiments), as published in the Marine Systems Simulator (MSS, T. I. Fossen and T.",
        "# Perez, MIT licence, Copyright (c) 2004 Thor I. Fossen):",
        "# HYDRO/vessels_shipx/s175/input.re1, git blob",
        "# b51d05c37afeba103e6632805cd98219e12e1cdc (commits cefea2a..736a3d1; replaced by",
        "# Capytaine data in MSS release 2.2.0). Extracted by tests/data/extract_veres_mss.py.",
        "# Same run as s175_head_seas_veres_mss_*.csv (Lpp 175 m, B 25.4 m, T 9.5 m, KG 9.55 m,",
        "# LCG 2.547 m aft of midship, r55 42.0 m, GMt 0.996 m); motions about the CG; no",
        "# sinkage or trim at speed. Columns: speed_m_s = U; froude = U/sqrt(g Lpp);",
        "# heading_deg = OUR relative heading beta (180 = head seas, 90 = beam, 0 = following;",
        "# VERES heading = 180 - beta); omega = wave frequency [rad/s]; lambda_over_L = 2 pi",
        "# g/(omega^2 Lpp); heave_rao = |xi3|/zeta_a [m/m]; roll_rao_nd = |xi4|/(k zeta_a);",
        "# pitch_rao_nd = |xi5|/(k zeta_a), k = omega^2/g.",
        "speed_m_s,froude,heading_deg,omega,lambda_over_L,heave_rao,roll_rao_nd,pitch_rao_nd",
    ]
)


def read_re1(path: Path) -> dict[tuple[float, float, float], np.ndarray]:
    """{(speed, VERES heading, ω): (6,) complex RAOs}."""
    lines = path.read_text().splitlines()
    n_speed, n_head, n_freq, n_dof = (int(v) for v in lines[9].split())
    out: dict[tuple[float, float, float], np.ndarray] = {}
    i = 10
    for _ in range(n_speed):
        speed = float(lines[i].split()[0])
        i += 1
        for _ in range(n_head):
            heading = float(lines[i])
            i += 1
            for _ in range(n_freq):
                omega = float(lines[i])
                i += 1
                rao = np.zeros(n_dof, dtype=complex)
                for _ in range(n_dof):
                    dof, re, im = lines[i].split()
                    rao[int(dof) - 1] = complex(float(re), float(im))
                    i += 1
                out[(speed, heading, omega)] = rao
    return out


def main(path: str) -> None:
    data = read_re1(Path(path))
    rows = [HEADER]
    for (speed, heading, omega), rao in sorted(data.items()):
        knots = speed / KNOT
        if heading not in HEADINGS_VERES or min(abs(knots - v) for v in SPEEDS_KNOTS) > 1e-3:
            continue
        k = omega**2 / G
        rows.append(
            f"{speed:.6g},{speed / np.sqrt(G * LPP):.4f},{180.0 - heading:g},{omega:.7g},"
            f"{2 * np.pi * G / (omega**2 * LPP):.5g},{abs(rao[2]):.6g},{abs(rao[3]) / k:.6g},"
            f"{abs(rao[4]) / k:.6g}"
        )
    out = Path(__file__).with_name("s175_veres_mss_all_headings.csv")
    out.write_text("\n".join(rows) + "\n")
    print(f"{len(rows) - 1} rows -> {out}")


if __name__ == "__main__":
    main(sys.argv[1])
