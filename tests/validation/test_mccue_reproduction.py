"""McCue & Campbell's identification of the Edith Terkol roll equation, through
:mod:`ship_gym.analysis.mccue` (the full study: ``scripts/reproduce_mccue.py``,
``docs/mccue/results.md``)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from ship_gym.analysis import mccue

RESULTS = Path(__file__).resolve().parents[2] / "docs" / "mccue" / "results.json"
LARGE = (-0.4, -0.35)  # their large-amplitude case, the one their fig. 8 is drawn for


@pytest.fixture(scope="module")
def large_case() -> mccue.FitCase:
    # N = 10 is the N the full scan selects for this case; the record is cut at 600 s (the
    # full study: 1000 s), which leaves the 0-500 s training window, and so the fit, unchanged
    # and keeps 100 s of prediction window. About 1 s of CPU.
    return mccue.fit_case(LARGE, (10,), duration=600.0)


def test_fit_recovers_the_published_coefficients(large_case: mccue.FitCase) -> None:
    """Their published eq. 2 coefficients for ⟨−0.4, −0.35⟩ are recovered.

    Tolerances: the paper gives 4 decimals and does not state its optimiser, start or N, so
    the fit is not expected to match to rounding; docs/mccue/results.md reports 2–7 % for the
    well-excited terms (c_u1 1.6 %, c_u3 2.4 %, b_u1 6.6 %, F_u 7.1 %). The bounds (5 % on the
    stiffness, 10 % on the linear damping and forcing) are about 1.5–3× those differences:
    tight enough to catch a wrong model, objective or data (the true small-angle stiffness
    0.384 is 25 % below their c_u1), loose enough for the last digits of an optimiser.
    The cubic damping b_u3 (φ̇ ≤ 0.6 rad/s, so φ̇³ ≤ 0.2) is weakly identifiable: ours 0.028
    against their 0.039; only its sign and a factor 2 are checked.
    """
    ours, paper = large_case.best.result.model, large_case.paper
    assert large_case.best.result.n_pieces == 10
    assert ours.c_u1 == pytest.approx(paper.c_u1, rel=0.05)
    assert ours.c_u3 == pytest.approx(paper.c_u3, rel=0.05)
    assert ours.b_u1 == pytest.approx(paper.b_u1, rel=0.10)
    assert ours.forcing_amplitude == pytest.approx(paper.forcing_amplitude, rel=0.10)
    assert 0.5 * paper.b_u3 < ours.b_u3 < 2.0 * paper.b_u3


def test_fit_predicts_beyond_the_training_window(large_case: mccue.FitCase) -> None:
    """Run freely from t = 0, the fitted equation reproduces the 40° steady roll after the
    training window (their fig. 6 "high fidelity"; the full study: NRMSE 0.004 over
    500–1000 s, the paper's coefficients 0.023)."""
    pred = large_case.best.prediction
    assert not pred.diverged
    assert pred.prediction_window is not None
    assert pred.prediction_window.nrmse_roll < 0.05
    assert pred.prediction_window.correlation_roll > 0.99
    steady = np.max(np.abs(large_case.record.roll[large_case.record.t >= 500.0]))
    assert math.degrees(steady) == pytest.approx(40.0, abs=2.0)


def test_fit_matches_the_stored_results(large_case: mccue.FitCase) -> None:
    """The module reproduces the stored full-run numbers of docs/mccue/results.json (the cut
    record leaves the training data unchanged); rel 1e-4 allows for the last bits of the
    compiled integrator on another machine."""
    stored = json.loads(RESULTS.read_text())["mccue_campbell"]
    (row,) = (
        r
        for r in stored["table"]
        if r["source"] == "ours" and r["initial_condition"] == "⟨-0.4, -0.35⟩"
    )
    model = large_case.best.result.model
    for key, value in (("b_u1", model.b_u1), ("b_u3", model.b_u3), ("c_u1", model.c_u1),
                       ("c_u3", model.c_u3), ("F_u", model.forcing_amplitude)):  # fmt: skip
        assert value == pytest.approx(row[key], rel=1e-4), key


def test_coefficient_rows_pair_ours_with_the_paper(large_case: mccue.FitCase) -> None:
    rows = mccue.coefficient_rows([large_case])
    assert [r["source"] for r in rows] == ["ours", "paper"]
    assert rows[1]["c_u1"] == 0.5147
    assert all(np.isfinite(r["nrmse_pred_500_1000"]) for r in rows)
