#!/usr/bin/env python
"""Reproduce Gourlay (2021) Fig. 1–2 for the S175 sway acceleration kernel L22(t).

Compares, for t up to 100 s:

* Filon quadrature (Gourlay eq. 4–10) on the database grid,
* Simpson's rule on the database grid (erratic at large t: Gourlay Fig. 2),
* Simpson's rule on a 5× finer grid (B/ω interpolated by a cubic spline; Gourlay §3),
* Filon on the 5× finer grid (reference),
* the sine form (Gourlay eq. 3) against the cosine form (eq. 2) (Gourlay Fig. 1).

Data: ``ship_gym.hydro.load_database("s175")`` (xarray.Dataset with ``added_mass`` and
``radiation_damping`` over (omega, radiating_dof, influenced_dof)); the ω = ∞ entry gives A(∞)
and is dropped with any other non-finite ω. ``--synthetic`` runs instead on an analytic sway-like
case on Gourlay's grid ω = 0:0.05:2.5 rad/s, with B(ω) = Σ cₖ xₖ²/(1 + xₖ²)³, xₖ = ω/aₖ, whose
kernel L(t) = Σ cₖ aₖt(1 + aₖt)e^{−aₖt}/8 is known exactly.

Usage::

    python scripts/reproduce_gourlay.py [--synthetic] [--output out/gourlay_s175_sway.png]
                                        [--json out/gourlay_s175_sway.json]
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from ship_gym.analysis.gourlay import LATE_T, compute, plot, s175_case, summarise, synthetic_case


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--output", type=Path, default=Path("out/gourlay_s175_sway.png"))
    parser.add_argument("--json", type=Path, default=None, help="write the numbers here")
    parser.add_argument(
        "--synthetic", action="store_true", help="analytic sway-like case instead of the S175"
    )
    args = parser.parse_args(argv)
    case = synthetic_case() if args.synthetic else s175_case()
    res = compute(case)
    summary = summarise(case, res)
    plot(case, res, args.output)
    if args.json is not None:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(summary, indent=2) + "\n")
    diffs = summary["max_late_abs_diff_vs_filon_fine"]
    print(f"{case['name']}: figure {args.output}")
    for m, v in diffs.items():
        print(f"  max |L_{m} - L_filon_fine| for t >= {LATE_T:g} s: {v:.3e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
