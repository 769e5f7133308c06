"""Gourlay (2021) Fig. 1–2: Filon against Simpson quadrature of the sway acceleration kernel.

On the analytic sway-like case the exact L(t) is known; on the S175 database the reference is
Filon on a 5× finer grid (Gourlay §3). Gourlay's findings, as tests: Simpson's rule on the
database grid is erratic at large t (t ≥ 50 s) where Filon is not, refining the grid cures it,
and the cosine form differs from the sine form mainly at t = 0 (L(0) must be 0).
"""

from __future__ import annotations

import numpy as np
import pytest

from ship_gym.analysis import gourlay


@pytest.fixture(scope="module", params=["synthetic", "s175"])
def comparison(request):
    case = gourlay.synthetic_case() if request.param == "synthetic" else gourlay.s175_case()
    res = gourlay.compute(case)
    return case, res, gourlay.summarise(case, res)


def test_simpson_is_erratic_at_large_t_and_filon_is_not(comparison):
    _, _, s = comparison
    peak = s["max_abs_L_filon_fine"]
    late = s["max_late_abs_diff_vs_filon_fine"]
    # measured: Filon 0.09 % (synthetic) / 0.02 % (S175) of the peak, Simpson 33 % / 34 %
    assert late["filon"] < 2e-3 * peak
    assert late["simpson"] > 0.1 * peak
    assert late["simpson"] > 100.0 * late["filon"]
    # on the 5× finer grid Simpson agrees with Filon (measured 2e-5 / 1e-5 of the peak)
    assert late["simpson_fine"] < 1e-4 * peak


def test_sine_form_starts_at_zero_and_the_cosine_form_does_not(comparison):
    _, _, s = comparison
    assert s["L0"]["filon"] == 0.0 and s["L0"]["filon_fine"] == 0.0
    assert abs(s["L0"]["cosine"]) > 0.1 * s["max_abs_L_filon_fine"]  # measured 27 % / 76 %


def test_filon_matches_the_exact_kernel_of_the_synthetic_case():
    case = gourlay.synthetic_case()
    res = gourlay.compute(case)
    err = np.abs(res["filon"] - res["exact"]).max()
    peak = np.abs(res["exact"]).max()
    # measured 1.5 % of the peak, all of it the truncation of B(ω) at 2.5 rad/s (the finer
    # Filon grid on the same ω range has the same error); Simpson 33 %
    assert err < 0.02 * peak
    assert np.abs(res["simpson"] - res["exact"]).max() > 10.0 * err


def test_figure_is_written(tmp_path):
    case = gourlay.synthetic_case()
    path = tmp_path / "gourlay.png"
    gourlay.plot(case, gourlay.compute(case), path)
    assert path.stat().st_size > 10_000
