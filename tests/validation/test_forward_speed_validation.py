"""Seakeeping at forward speed (issue #13): the time domain's linear limit against the solver,
and the solver against published strip theory for the S175.

1. Linear limit at Fn 0.2 and 0.3 in head (180°), bow (135°), beam (90°) and quartering (45°)
   regular seas: the time-domain engine (nonlinear FK + hydrostatics at a = 0.1 m, state-space
   radiation memory with the Kirchhoff forward-speed moment, diffraction at the wave frequency,
   linear viscous roll; surge at U, sway and yaw held) against the frequency-domain RAO of
   :func:`ship_gym.hydro.rao.response_amplitude_operator` at the same speed. Both implement the
   one linearisation of :mod:`ship_gym.hydro.forward_speed`; criterion 2 % (the zero-speed
   criterion of tests/validation/test_simulator_validation.py, where the remaining differences
   are the FK quadrature and the memory fit).
2. The solver against ShipX/VERES strip theory for the S175 in head seas at Fn 0.186 and 0.248
   (tests/data/s175_head_seas_veres_mss_*.csv, from the Marine Systems Simulator; a computation,
   not model tests): heave and pitch peaks within 15 % (the issue's criterion), and the same
   comparison without the forward-speed moment misses it (so the test can fail).
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest

from ship_gym.engine.ship import wave_field_for
from ship_gym.engine.simulator import Simulator
from ship_gym.hydro.rao import natural_frequency, response_amplitude_operator
from ship_gym.kinematics import encounter_frequency
from ship_gym.waves.sea_state import RegularWave

from .test_simulator_validation import (
    AMPLITUDE,
    HEAVE,
    HOLD_HORIZONTAL,
    LINEAR_DT,
    PITCH,
    ROLL,
    fit_harmonic,
    ikeda_b1,
    linear_forces,
    s175,
)

LPP = 175.0
G = 9.81
DATA = Path(__file__).resolve().parents[1] / "data"

# dominant DOFs per heading. Beam seas: heave only — the beam-sea roll is the known FK-quadrature
# deviation of the zero-speed test (≈ 12.5 %, checked below to be unchanged by speed) and the
# beam-sea pitch is tiny (≈ 0.01 rad/m, where the same quadrature gives 2–5 %).
DOMINANT = {180: (HEAVE, PITCH), 135: (HEAVE, ROLL, PITCH), 90: (HEAVE,), 45: (HEAVE, ROLL, PITCH)}


def speed_of(froude: float) -> float:
    return froude * np.sqrt(G * LPP)


@functools.cache
def linear_run_at_speed(index: int, heading_deg: int, froude: float) -> tuple:
    """(time-domain, frequency-domain) complex amplitudes per unit wave amplitude (6,) each.

    The steady state is fitted over the last whole encounter periods of ≥ 120 s. Quartering seas
    meet the waves near the roll resonance (ω_e → ω_φ ≈ 0.35 rad/s) where the roll transient
    decays over 1/(ζ ω_φ) ≈ 300 s: those runs last 900 s (1800 s within 0.1 rad/s of ω_φ), the
    others 300 s.
    """
    s = s175()
    u = speed_of(froude)
    beta = np.radians(heading_deg)
    omega = float(s.arr.omega[index])
    w_e = float(encounter_frequency(omega, u, beta, G))
    wave = RegularWave(2 * AMPLITUDE, period=2 * np.pi / omega)
    field = wave_field_for(wave, beta)
    sim = Simulator(
        s.hull,
        linear_forces(field),
        wave_field=field,
        dt=LINEAR_DT,
        free_dofs=HOLD_HORIZONTAL,
        forward_speed=u,
    )
    sim.reset(eta=s.base)
    near_roll = abs(abs(w_e) - natural_frequency(s.db, "Roll")) < 0.1
    duration = 1800.0 if heading_deg < 90 and near_roll else 900.0 if heading_deg < 90 else 300.0
    res = sim.run(duration)
    period = 2 * np.pi / abs(w_e)
    t_start = duration - max(1.0, np.floor(120.0 / period)) * period
    td = np.zeros(6, complex)
    for dof in (HEAVE, ROLL, PITCH):
        td[dof] = fit_harmonic(res.t, res.eta[:, dof] - s.base[dof], w_e, t_start) / AMPLITUDE
    fd = response_amplitude_operator(
        s.db,
        omega=omega,
        heading=beta,
        forward_speed=u,
        extra_damping=np.diag([0, 0, 0, ikeda_b1(), 0, 0]),
        free_dofs=HOLD_HORIZONTAL,
    )[0]
    return td, fd, w_e


def _cases():
    out = []
    for index in (16, 12):  # ω = 0.710 rad/s (λ/L = 0.70), 0.543 rad/s (λ/L = 1.19)
        for froude in (0.0, 0.2, 0.3):  # Fn 0 also in test_simulator_validation (not at 45°)
            for heading in (180, 135, 90, 45):
                marks = [pytest.mark.slow] if index == 12 else []
                ident = f"w{index}-fn{froude}-beta{heading}"
                out.append(pytest.param(index, froude, heading, marks=marks, id=ident))
    return out


@pytest.mark.parametrize(("index", "froude", "heading"), _cases())
def test_linear_limit_at_speed_matches_frequency_domain(index, froude, heading):
    # Measured (ω index 16; heave / roll / pitch) before the diffraction's speed correction
    # (issue #34): Fn 0.2 head 0.5 / – / 1.7 %, bow 0.5 / 0.8 / 1.5 %, beam 0.3 / – / –,
    # quartering 0.8 / 0.6 / 0.7 %; Fn 0.3 head 0.5 / – / 1.2 %, bow 0.3 / 0.9 / 1.5 %, beam 0.4,
    # quartering 0.8 / 1.0 / 0.5 %. With it, head-sea pitch 2.3 % at both speeds (λ/L 0.7: a
    # small pitch, 0.2 k a, the difference of an excitation that the correction raised by
    # ω_e/ω ≈ 1.6–1.9 in head seas; the FK quadrature of the time domain is the known
    # remainder), hence 2.5 % for pitch in head seas, 2 % elsewhere. Before the forward-speed
    # linearisation the two differed by up to +115 % in heave at Fn 0.186 (issue #13).
    td, fd, w_e = linear_run_at_speed(index, heading, froude)
    w_roll = natural_frequency(s175().db, "Roll")
    for dof in DOMINANT[heading]:
        if dof == ROLL and abs(abs(w_e) - w_roll) < 0.03:
            # at the roll resonance (ζ ≈ 1 %) the steady state needs > 1000 s; not a linear-limit
            # check any more but one of the transient (measured: 15 % at 900 s, ω index 12)
            continue
        err = abs(td[dof] - fd[dof]) / abs(fd[dof])
        limit = 0.025 if (dof == PITCH and heading == 180 and froude > 0) else 0.02
        if dof == ROLL and abs(abs(w_e) - w_roll) < 0.1:
            # near the roll resonance the 1800 s run still carries a little transient
            # (measured 2.15 % at ω index 12, Fn 0.3, 45°, ω_e 0.279 rad/s since issue #34)
            limit = 0.025
        assert err < limit, (
            f"DOF {dof}: |ξ_td − ξ_fd|/|ξ_fd| = {err:.2%} at ω_e = {w_e:.3f} rad/s "
            f"(|ξ_td/ξ_fd| = {abs(td[dof] / fd[dof]):.4f}, phase "
            f"{np.degrees(np.angle(td[dof] / fd[dof])):+.2f}°)"
        )
    if heading == 90:
        # the zero-speed FK-quadrature deviation of beam-sea roll (12.5–12.7 % at this ω), no more
        err = abs(td[ROLL] - fd[ROLL]) / abs(fd[ROLL])
        assert err == pytest.approx(0.126, abs=0.01)


# ------------------------------------------------------------------------ strip theory (VERES)
def veres(tag: str) -> dict[str, np.ndarray]:
    """Columns of a VERES reference file (# comment lines, one header line, then numbers)."""
    lines = (DATA / f"s175_head_seas_veres_mss_fn{tag}.csv").read_text().splitlines()
    rows = [line for line in lines if line and not line.startswith("#")][1:]
    raw = np.array([[float(v) for v in row.split(",")] for row in rows])
    return {"lambda_l": raw[:, 0], "omega": raw[:, 1], "heave": raw[:, 4], "pitch": raw[:, 5]}


def solver_heave_pitch(omega: np.ndarray, u: float, speed_terms: str = "all") -> tuple:
    """Heave at the centre of gravity [m/m] and pitch / k [-] in head seas, heave–pitch free."""
    s = s175()
    xi = response_amplitude_operator(
        s.db, omega=omega, heading=np.pi, forward_speed=u, free_dofs=("Heave", "Pitch"),
        speed_terms=speed_terms,  # type: ignore[arg-type]
    )  # fmt: skip
    x_g = float(s.hull.mass.cog[0])  # VERES gives motions about the CG: z_G = z_O − x_G θ
    k = omega**2 / G
    return np.abs(xi[:, HEAVE] - x_g * xi[:, PITCH]), np.abs(xi[:, PITCH]) / k


@pytest.mark.parametrize(("tag", "froude"), [("0p186", 0.1862), ("0p248", 0.2483)])
def test_head_sea_peaks_against_strip_theory(tag, froude):
    # Measured: Fn 0.186 heave peak 1.115 vs 1.096 (+1.7 %), pitch 1.158 vs 1.118 (+3.6 %);
    # Fn 0.248 heave 1.452 vs 1.468 (−1.1 %), pitch 1.204 vs 1.210 (−0.5 %), at the same λ/L.
    # Without the Kirchhoff moment (speed_terms="none", the former time domain's model) the peaks
    # are 14–18 % high: 1.250 / 1.310 and 1.714 / 1.418.
    ref = veres(tag)
    u = speed_of(froude)
    s = s175()
    w_max = float(s.arr.omega[-1])
    keep = (ref["lambda_l"] > 0.5) & (ref["omega"] + ref["omega"] ** 2 * u / G <= w_max)
    omega = ref["omega"][keep]
    heave, pitch = solver_heave_pitch(omega, u)
    for name, ours, theirs in (
        ("heave", heave, ref["heave"][keep]),
        ("pitch", pitch, ref["pitch"][keep]),
    ):
        assert ours.max() == pytest.approx(theirs.max(), rel=0.15), name
    # the heave peak sits at the same wave length (±1 grid step of the reference; the pitch
    # curves are flat at their maximum, 1.20–1.21 over λ/L 1.39–1.63 in the reference)
    i, j = int(np.argmax(heave)), int(np.argmax(ref["heave"][keep]))
    assert abs(i - j) <= 1, f"heave peak at λ/L {ref['lambda_l'][keep][[i, j]]}"
    heave0, _ = solver_heave_pitch(omega, u, "none")
    assert heave0.max() > 1.12 * ref["heave"][keep].max()


def test_long_waves_at_zero_speed_against_strip_theory():
    # quasi-static limit: heave → 1, pitch/k → 1 (both codes): within 5 % for λ/L > 3
    ref = veres("0p000")
    keep = ref["lambda_l"] > 3.0
    heave, pitch = solver_heave_pitch(ref["omega"][keep], 0.0)
    np.testing.assert_allclose(heave, ref["heave"][keep], rtol=0.05)
    np.testing.assert_allclose(pitch, ref["pitch"][keep], rtol=0.06)


def test_a_ship_at_another_speed_than_the_build_speed():
    # Item 4 of issue #13: ships of one engine at different per-episode speeds. Kirchhoff's
    # moment takes each ship's own surge velocity and no momentum of the surge offset u − U, so
    # a ship at 10.36 m/s in an engine built for 8.28 m/s moves as in an engine built for
    # 10.36 m/s; what remains is the memory of the constant surge offset, whose steady force is
    # the fit's B(0) (≈ 1e-8 of the pair scale). Tolerance 1e-6 of the motion (measured ≈ 1e-11
    # on a pitch-rate kick; before the surge share was left out: 2 % in pitch).
    from ship_gym.engine.batch import BatchSimulator
    from ship_gym.engine.simulator import engine_model

    s = s175()
    omega = float(s.arr.omega[14])
    field = wave_field_for(RegularWave(2 * AMPLITUDE, period=2 * np.pi / omega), np.pi)
    u_build, u_ship = 8.28, 10.36

    def run(speeds: list[float], build: float) -> np.ndarray:
        models = [engine_model(f) for f in linear_forces(field)]
        sim = BatchSimulator(s.hull, models, [field] * len(speeds), forward_speed=build,
                             dt=LINEAR_DT, free_dofs=HOLD_HORIZONTAL)  # fmt: skip
        nu = np.zeros((len(speeds), 6))
        nu[:, 0] = speeds
        sim.reset(eta=np.tile(s.base, (len(speeds), 1)), nu=nu)
        return sim.run(2000)["eta"][:, -1]

    mixed = run([u_build, u_ship], u_build)
    alone = run([u_ship], u_ship)
    for dof in (HEAVE, PITCH):
        scale = np.ptp(alone[1000:, dof])
        assert np.abs(mixed[:, dof] - alone[:, dof]).max() < 1e-6 * scale, dof


# ----------------------------------------------------------------- added resistance at speed
def mean_surge_force(wave_length_over_l: float, froude: float, amplitude: float) -> float:
    """Mean earth-x force [N] on the S175 held at U in regular head waves (0 m: calm water).

    Linear radiation and diffraction have no mean; what remains is the mean of the nonlinear
    Froude–Krylov + hydrostatic pressure on the moving hull (with gravity, whose body-x part
    the pitch angle tilts), averaged over whole encounter periods after 150 s.
    """
    from ship_gym.kinematics import rotation_matrix

    s = s175()
    u = speed_of(froude)
    omega = np.sqrt(2 * np.pi * G / (wave_length_over_l * LPP))
    field = wave_field_for(RegularWave(max(2 * amplitude, 1e-12), period=2 * np.pi / omega), np.pi)
    sim = Simulator(
        s.hull, linear_forces(field), wave_field=field, dt=LINEAR_DT, free_dofs=HOLD_HORIZONTAL,
        forward_speed=u,
    )  # fmt: skip
    sim.reset(eta=s.base)
    period = 2 * np.pi / abs(float(encounter_frequency(omega, u, np.pi, G)))
    n_mean = round(np.floor(150.0 / period) * period / LINEAR_DT)
    n_total = round(300.0 / LINEAR_DT)
    fx = []
    for k in range(n_total):
        sim.step()
        if k >= n_total - n_mean:
            parts = sim.force_breakdown()
            total = sum(v for name, v in parts.items() if name != "coriolis")
            fx.append((rotation_matrix(*sim.eta[3:6]) @ total[:3])[0])
    return float(np.mean(fx))


@pytest.mark.parametrize(("froude", "wave_length"), [(0.2, 1.0), (0.275, 1.15)])
def test_froude_krylov_mean_force_at_speed_against_snnm_motion_part(froude, wave_length):
    # Issue #13 item 3, rechecked with the forward-speed linearisation: the engine's own mean
    # added resistance (FK on the moving hull, amplitude 1 m) against the motion part of the
    # SNNM formula (Liu & Papanikolaou), at its peak. Measured σ_aw = R̄/(ρ g ζ² B²/L): Fn 0.2,
    # λ/L 1.0: 5.2 vs 7.3; Fn 0.275, λ/L 1.15: 7.0 vs 9.9 — 70 % of SNNM's motion part (the
    # second-order radiation and diffraction parts are missing from the linear models; before
    # the forward-speed terms the FK mean exceeded SNNM near λ/L 1.15). Bounds 0.55–0.85: a
    # regression guard on a stated model deficit, not a validation.
    from ship_gym.forces.added_resistance import SNNMParticulars, snnm_components

    s = s175()
    rho, beam, amplitude = s.hull.rho, 25.4, 1.0
    scale = rho * G * amplitude**2 * beam**2 / LPP
    sigma = -(mean_surge_force(wave_length, froude, amplitude) - mean_surge_force(1.0, froude, 0.0))
    sigma /= scale
    omega = np.sqrt(2 * np.pi * G / (wave_length * LPP))
    _, motion = snnm_components(
        np.array([omega]), np.pi, speed_of(froude), SNNMParticulars.from_hull(s.hull)
    )
    ratio = sigma / (float(motion[0]) * amplitude**2 / scale)
    assert 0.55 < ratio < 0.85, f"σ_FK = {sigma:.2f}, ratio to SNNM motion part {ratio:.2f}"


# ------------------------------------------------------- every heading (issue #34)
VERES_ALL = DATA / "s175_veres_mss_all_headings.csv"


def veres_all_headings() -> np.ndarray:
    """Rows (speed, Fn, β [deg], ω, λ/L, heave, roll/k, pitch/k) of the all-headings file."""
    lines = VERES_ALL.read_text().splitlines()
    rows = [line for line in lines if line and not line.startswith("#")][1:]
    return np.array([[float(v) for v in row.split(",")] for row in rows])


@pytest.mark.parametrize("speed", [7.71667, 10.2889], ids=["fn0.186", "fn0.248"])
def test_every_heading_against_strip_theory(speed):
    # The solver with the engine's speed terms (radiated and scattered momentum, the default
    # high-pass) against VERES at β = 180, 150, 120, 90, 60, 30, 0° (heave–pitch free, λ/L >
    # 0.5, ω and ω_e inside the database). Measured peaks, Fn 0.186 / 0.248: heave −4.4 … +0.7 %
    # at every heading; pitch +14 / +10 % (head), +12 / +6 % (bow, 150°), −2 / −9 % (120°),
    # ±1 % (60°), −2 / −6 % (30°), −2 / −7 % (following); beam-sea pitch 0.042 / 0.058 k a
    # against VERES's 0.026 / 0.035 (before the scattered momentum: 1.04 / 1.49 k a, and 1.96 /
    # 2.40 k a in quartering seas). Tolerances: heave 6 %, pitch 15 % (3-D BEM against 2-D
    # strip theory; the head-sea pitch difference is discussed in docs/validation.md), beam
    # pitch 0.08 k a absolute.
    from ship_gym.hydro.forward_speed import default_speed_cutoff

    raw = veres_all_headings()
    s = s175()
    w_min, w_max = float(s.arr.omega[0]), float(s.arr.omega[-1])
    x_g = float(s.hull.mass.cog[0])
    cutoff = default_speed_cutoff(LPP, G)
    for heading in (180, 150, 120, 90, 60, 30, 0):
        rows = raw[(np.abs(raw[:, 0] - speed) < 1e-3) & (raw[:, 2] == heading)]
        omega = rows[:, 3]
        w_e = encounter_frequency(omega, speed, np.radians(heading), G)
        keep = (omega >= w_min) & (omega <= w_max) & (np.abs(w_e) <= w_max)
        keep &= (np.abs(w_e) > 0.02) & (rows[:, 4] > 0.5)
        omega, ref = omega[keep], rows[keep]
        xi = response_amplitude_operator(
            s.db, omega=omega, heading=np.radians(heading), forward_speed=speed,
            free_dofs=("Heave", "Pitch"), speed_cutoff=cutoff,
        )  # fmt: skip
        heave = np.abs(xi[:, HEAVE] - x_g * xi[:, PITCH])
        pitch = np.abs(xi[:, PITCH]) / (omega**2 / G)
        assert heave.max() == pytest.approx(ref[:, 5].max(), rel=0.06), heading
        if heading == 90:
            assert pitch.max() < 0.08, pitch.max()
        else:
            assert pitch.max() == pytest.approx(ref[:, 7].max(), rel=0.15), heading


@pytest.mark.parametrize("froude", [0.2, 0.3, 0.4])
def test_beam_seas_at_speed_have_no_spurious_pitch(froude):
    # Issue #34: S175, beam regular waves λ = 1.5 L. Before the scattered flow's momentum the
    # Kirchhoff moment of the radiated momentum pitched the ship (pitch 0.30 / 0.45 / 0.56 k a
    # at Fn 0.2 / 0.3 / 0.4, heave 1.04 / 0.85 / 0.71). Measured now (solver, heave–roll–pitch
    # free): pitch 0.020 / 0.030 / 0.038 k a, heave 1.04 / 1.04 / 1.03; the time domain
    # within 7 % of those small pitches and 0.3 % in heave (test above and below).
    s = s175()
    k = 2 * np.pi / (1.5 * LPP)
    omega = np.sqrt(G * k)
    xi = response_amplitude_operator(
        s.db, omega=omega, heading=np.pi / 2, forward_speed=speed_of(froude),
        free_dofs=("Heave", "Roll", "Pitch"),
    )[0]  # fmt: skip
    assert abs(xi[PITCH]) / k <= 0.05
    assert abs(xi[HEAVE]) >= 0.95


def test_beam_seas_at_speed_time_domain():
    # the engine at Fn 0.3 in the same beam sea (surge at U, sway and yaw held): pitch ≤ 0.05
    # k a and heave ≥ 0.95 (measured 0.028 and 1.035)
    s = s175()
    k = 2 * np.pi / (1.5 * LPP)
    omega = np.sqrt(G * k)
    field = wave_field_for(RegularWave(2 * AMPLITUDE, period=2 * np.pi / omega), np.pi / 2)
    sim = Simulator(
        s.hull, linear_forces(field), wave_field=field, dt=LINEAR_DT, free_dofs=HOLD_HORIZONTAL,
        forward_speed=speed_of(0.3),
    )  # fmt: skip
    sim.reset(eta=s.base)
    res = sim.run(300.0)
    t_start = 300.0 - 8 * 2 * np.pi / omega
    heave = fit_harmonic(res.t, res.eta[:, HEAVE] - s.base[HEAVE], omega, t_start) / AMPLITUDE
    pitch = fit_harmonic(res.t, res.eta[:, PITCH] - s.base[PITCH], omega, t_start) / AMPLITUDE
    assert abs(pitch) / k <= 0.05
    assert abs(heave) >= 0.95


def test_long_wave_limits_at_every_heading_and_speed():
    # Issue #34: in long waves the ship follows the wave at any speed: heave → 1, pitch → k a
    # |cos β|, roll → k a |sin β|, because the speed terms act on the motion relative to the
    # incident flow (the radiated and the scattered momentum cancel). At the database's lowest
    # frequency (λ = 200 L; surge, sway, heave, roll, pitch free, yaw held: without hull lift a
    # free yaw drifts), Fn 0–0.4, β 0–180° every 15°, with the theory's terms at every frequency
    # (speed_cutoff = 0): the speed changes heave by ≤ 0.2 % and pitch and roll by ≤ 2.5 % of k
    # a (measured 0.01 % in heave, 2.5 % in beam-sea pitch — a 0.05 → 0.07 k a remainder of
    # the zero-speed hull's own fore–aft asymmetry — and ≤ 0.6 % in roll). At rest the limits
    # hold within 0.05 k a (roll within 0.06: 1.5 % of dynamic amplification (ω/ω_φ)² and,
    # in oblique seas, the yaw held: 0.31 k a at 15° against sin 15° = 0.26).
    s = s175()
    omega = float(s.arr.omega[0])
    k = omega**2 / G
    free = ("Surge", "Sway", "Heave", "Roll", "Pitch")
    for heading in range(0, 181, 15):
        beta = np.radians(heading)
        at_rest = response_amplitude_operator(
            s.db, omega=omega, heading=beta, free_dofs=free
        )[0]  # fmt: skip
        assert abs(at_rest[HEAVE]) == pytest.approx(1.0, abs=0.002)
        assert abs(at_rest[PITCH]) / k == pytest.approx(abs(np.cos(beta)), abs=0.05)
        assert abs(at_rest[ROLL]) / k == pytest.approx(abs(np.sin(beta)), abs=0.06)
        for froude in (0.1, 0.2, 0.3, 0.4):
            xi = response_amplitude_operator(
                s.db, omega=omega, heading=beta, forward_speed=speed_of(froude),
                free_dofs=free, speed_cutoff=0.0,
            )[0]  # fmt: skip
            assert abs(xi[HEAVE]) == pytest.approx(abs(at_rest[HEAVE]), abs=0.002)
            for dof in (ROLL, PITCH):
                assert abs(xi[dof]) / k == pytest.approx(abs(at_rest[dof]) / k, abs=0.026), (
                    heading, froude, dof,
                )  # fmt: skip


# ------------------------------------------------------------ the horizontal plane at speed
@pytest.mark.parametrize("speed", [5.0, 10.0])
def test_default_setup_at_speed_keeps_a_bounded_heading_in_calm_water(speed):
    # Issue #34: ShipSetup(speed=U) frees all six DOFs; its manoeuvring model is now on by
    # default at speed (the hull's lift), with the vertical-plane speed terms. From a 1° drift
    # (sway velocity −U sin 1°) the heading settles (measured after 600 s: 10.3° at 5 m/s,
    # 12.4° at 10 m/s, and still by < 0.5° per 100 s); before, the horizontal Munk moment
    # turned the ship 112° / 241° in 100 s, and the vertical terms alone without the hull's
    # lift 20° / 203° in 600 s.
    from ship_gym.engine.ship import ShipSetup, build_simulator

    setup = ShipSetup(speed=speed, integrator="holloway", dt=0.1)
    assert setup.manoeuvring and setup.speed_terms == "vertical"
    sim = build_simulator(setup)
    nu = sim.nu.copy()
    nu[1] = -speed * np.sin(np.radians(1.0))
    sim.reset(eta=sim.eta.copy(), nu=nu)
    res = sim.run(600.0)
    yaw = np.degrees(res.eta[:, 5])
    late = res.t >= 500.0
    assert np.abs(yaw).max() < 15.0
    assert np.ptp(yaw[late]) < 1.0  # settled
    assert res.nu[-1, 0] == pytest.approx(speed, rel=0.01)


def test_simulate_command_at_speed_keeps_its_heading(tmp_path, capsys):
    # the tutorial command of issue #34 (it turned the S175 up to six times in 600 s and ended
    # going astern): the autopilot now holds the heading (measured: max 0.4°, 6.99 m/s)
    from ship_gym.cli import main

    out = tmp_path / "sim.nc"
    args = ["simulate", "--speed", "7", "--irregular", "2", "7", "--heading-deg", "45"]
    args += ["--duration", "600", "--output", str(out), "--plot", ""]
    assert main(args) == 0
    import xarray as xr

    with xr.open_dataset(out) as ds:
        yaw = np.degrees(ds["eta"].values[:, 5])
        surge = ds["nu"].values[:, 0]
    assert np.abs(yaw - yaw[0]).max() < 3.0
    assert surge[-1] == pytest.approx(7.0, rel=0.02)
    assert "steering: autopilot" in capsys.readouterr().out


# --------------------------------------------------------- capsize verdicts (issue #34)
def test_capsize_map_cells_capsize_only_by_physics():
    # The shipped map's cells (S175, KG 10.1 m, H 10.5 m, λ 1.5 L, autopilot, 600 s) whose
    # capsizes came from the radiated momentum alone (the -v2 model, kept as
    # diffraction_speed_terms=False): following seas at Fn 0.4 pitch-poled at 303 s, beam seas
    # at Fn 0.3 capsized in roll at 189 s. With the speed terms on the relative motion neither
    # capsizes (measured: max pitch 7.7° surf-riding at 20.1 m/s; beam-sea roll 11.7°, pitch
    # 0.7°); the old model still does here, so the test can fail.
    import dataclasses

    import ship_gym.analysis.capsize_map as cm
    from ship_gym.engine.ship import build_simulator

    cfg = cm.CapsizeMapConfig(
        hull_overrides={"kg": 10.1}, headings_deg=(0.0, 90.0), froude_numbers=(0.3, 0.4),
        duration=600.0,
    )  # fmt: skip
    angle = np.radians(cm.capsize_angle_of("s175", {"kg": 10.1}))
    for heading, froude, reason in ((0, 1, "pitch"), (1, 0, "roll")):
        setup, sea, beta, _ = cm.cell_setup(cfg, cm.Cell(0, heading, froude, 0))
        outcomes = {}
        for label, changes in (("now", {}), ("v2", {"diffraction_speed_terms": False,
                                                     "speed_cutoff": 0.0})):  # fmt: skip
            sim = build_simulator(
                dataclasses.replace(setup, **changes), sea, wave_heading=beta,
                rng=np.random.default_rng(0),
            )  # fmt: skip
            outcomes[label], _ = cm.simulate_until_capsize(sim, 600.0, angle, record_every=5)
        assert not outcomes["now"].capsized, (heading, froude)
        assert outcomes["now"].max_abs_pitch_deg < 15.0
        assert outcomes["v2"].capsized and outcomes["v2"].reason == reason
