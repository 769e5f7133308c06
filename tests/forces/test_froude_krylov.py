"""Nonlinear Froude–Krylov + hydrostatic kernel: fast vs reference, calm water vs hydrostatics."""

import numpy as np
import pytest

from ship_gym.forces.froude_krylov import (
    HullPanels,
    WaveComponents,
    froude_krylov_hydrostatic,
    froude_krylov_hydrostatic_batch,
)
from ship_gym.hull import equilibrium, load_hull, pressure_integral, righting_arm
from ship_gym.kinematics import rotation_matrix


@pytest.fixture(scope="module")
def s175():
    hull = load_hull("s175")
    return hull, HullPanels.from_mesh(hull.mesh)


def _sea(n: int, seed: int, amplitude: float = 0.5):
    rng = np.random.default_rng(seed)
    omega = np.sort(rng.uniform(0.3, 1.6, n))
    waves = WaveComponents.from_arrays(omega**2 / 9.81, rng.normal(0.5, 0.4, n))
    phasor = amplitude * rng.uniform(0.2, 1.0, n) * np.exp(1j * rng.uniform(0, 2 * np.pi, n))
    return waves, phasor


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_fast_matches_reference(s175, seed):
    # Same formulas, different code (polynomial sincos/exp vs libm; numba loops vs numpy).
    # The polynomials are accurate to a few ulp, so 1e-6 (the bar) is very loose.
    hull, panels = s175
    waves, phasor = _sea(50, seed)
    rng = np.random.default_rng(100 + seed)
    pos = np.array([rng.uniform(-500, 500), rng.uniform(-500, 500), rng.uniform(-1, 1)])
    rot = rotation_matrix(*rng.uniform(-0.4, 0.4, 2), rng.uniform(-np.pi, np.pi))
    fast = froude_krylov_hydrostatic(panels, waves, phasor, pos, rot, rho=hull.rho, g=hull.g)
    ref = froude_krylov_hydrostatic(
        panels, waves, phasor, pos, rot, rho=hull.rho, g=hull.g, method="reference"
    )
    scale = np.abs(ref[:3]).max(), np.abs(ref[3:]).max()
    np.testing.assert_allclose(fast[:3], ref[:3], rtol=0, atol=1e-6 * scale[0])
    np.testing.assert_allclose(fast[3:], ref[3:], rtol=0, atol=1e-6 * scale[1])


def test_batch_matches_single(s175):
    hull, panels = s175
    ships = []
    for s in range(4):
        waves, phasor = _sea(30, s)
        pos = np.array([10.0 * s, -5.0 * s, 0.2])
        rot = rotation_matrix(0.05 * s, -0.02 * s, 0.3 * s)
        ships.append((waves, phasor, pos, rot))
    single = np.array(
        [
            froude_krylov_hydrostatic(panels, w, c, p, r, rho=hull.rho, g=hull.g)
            for w, c, p, r in ships
        ]
    )
    batch = froude_krylov_hydrostatic_batch(
        panels,
        np.array([w.wavenumber for w, *_ in ships]),
        np.array([w.cos_direction for w, *_ in ships]),
        np.array([w.sin_direction for w, *_ in ships]),
        np.array([w.local_amplitudes(c, p[0], p[1]) for w, c, p, _ in ships]),
        np.array([p[2] for *_, p, _ in ships]),
        np.array([r for *_, r in ships]),
        rho=hull.rho,
        g=hull.g,
    )
    np.testing.assert_allclose(batch, single, rtol=1e-12, atol=1e-6)


def test_calm_water_reproduces_hull_hydrostatics_and_gz(s175):
    # In calm water the kernel integrates exactly the hydrostatic pressure that the hull module
    # integrates: forces agree to round-off, and the righting arm from the kernel's roll moment
    # (about G, at the hull module's free-floating equilibrium) equals righting_arm().
    hull, panels = s175
    waves, _ = _sea(10, 0)
    calm = np.zeros(10, complex)
    for heel_deg in (10.0, 35.0, 60.0):
        eq = equilibrium(hull, np.radians(heel_deg))
        rot = rotation_matrix(np.radians(heel_deg), eq.trim, 0.0)
        f = froude_krylov_hydrostatic(
            panels, waves, calm, np.array([0.0, 0.0, eq.heave]), rot, rho=hull.rho, g=hull.g
        )
        ref = pressure_integral(hull, eq.heave, np.radians(heel_deg), eq.trim)
        np.testing.assert_allclose(f[:3], ref.force, rtol=1e-10, atol=1e-6 * abs(ref.force[2]))
        r_g = rot @ hull.mass.cog + np.array([0.0, 0.0, eq.heave])
        m_about_g = f[3:] - np.cross(r_g - np.array([0.0, 0.0, eq.heave]), f[:3])
        gz = -m_about_g[0] / (hull.mass.mass * hull.g)
        assert gz == pytest.approx(righting_arm(hull, [heel_deg]).gz[0], abs=1e-9)


def test_wave_crest_lifts_and_trough_drops(s175):
    # A long regular wave (λ = 3 L) with its crest at amidships adds buoyancy; a trough removes it.
    hull, panels = s175
    k = 2 * np.pi / (3 * 175.0)
    waves = WaveComponents.from_arrays(np.array([k]), np.array([0.0]))
    calm = froude_krylov_hydrostatic(
        panels, waves, np.zeros(1), np.zeros(3), np.eye(3), rho=hull.rho, g=hull.g
    )
    crest = froude_krylov_hydrostatic(
        panels, waves, np.array([2.0 + 0j]), np.zeros(3), np.eye(3), rho=hull.rho, g=hull.g
    )
    trough = froude_krylov_hydrostatic(
        panels, waves, np.array([-2.0 + 0j]), np.zeros(3), np.eye(3), rho=hull.rho, g=hull.g
    )
    assert crest[2] < calm[2] < trough[2]  # z down: more negative = more upward force
    # long wave: the change is close to the hydrostatic estimate −ρ g A_wp a·(mean cos over L)
    # reduced by the Smith effect e^{−k T_mean}; bound it loosely between 0.5 and 1.1 of ρgA_wp a
    a_wp = 3155.0
    lift = calm[2] - crest[2]
    assert 0.5 * hull.rho * hull.g * a_wp * 2.0 < lift < 1.1 * hull.rho * hull.g * a_wp * 2.0


def test_bad_method_is_rejected(s175):
    hull, panels = s175
    waves, phasor = _sea(3, 0)
    with pytest.raises(ValueError, match="method must be one of"):
        froude_krylov_hydrostatic(
            panels, waves, phasor, np.zeros(3), np.eye(3), rho=hull.rho, g=hull.g, method="x"
        )


# ----------------------------------------------------------------------------- fast-path edge cases
# The fast kernel skips work exactly: the wave sums of hull-top vertices that are certainly dry
# (with all their mesh neighbours) below the highest possible crest Σ|cⱼ|, the pressure sums of
# dry vertices, the decay terms below 2^−54, and all triangles that cannot cross the surface.
# These cases put each of those on an edge; fast and reference must still agree.


def _agree(panels, hull, waves, phasor, pos, rot, rtol=1e-9):
    fast = froude_krylov_hydrostatic(panels, waves, phasor, pos, rot, rho=hull.rho, g=hull.g)
    ref = froude_krylov_hydrostatic(
        panels, waves, phasor, pos, rot, rho=hull.rho, g=hull.g, method="reference"
    )
    scale = np.abs(ref[:3]).max(), np.abs(ref[3:]).max()
    np.testing.assert_allclose(fast[:3], ref[:3], rtol=0, atol=rtol * scale[0])
    np.testing.assert_allclose(fast[3:], ref[3:], rtol=0, atol=rtol * scale[1])
    return fast


@pytest.mark.parametrize(
    ("case", "heel_deg", "heave", "amplitude", "n"),
    [
        ("heeled 60 deg", 60.0, 0.0, 0.5, 50),
        ("deck immersed", 20.0, 8.0, 1.0, 50),
        ("huge waves", 10.0, 0.0, 8.0, 50),
        ("calm water with components", 35.0, 0.0, 0.0, 20),
        ("tiny sea, dry top skipped", 0.0, 0.0, 0.02, 30),
        ("fully submerged", 0.0, 30.0, 0.5, 30),
        ("out of the water", 0.0, -20.0, 0.5, 30),
    ],
)
def test_fast_matches_reference_in_adversarial_cases(s175, case, heel_deg, heave, amplitude, n):
    hull, panels = s175
    waves, phasor = _sea(n, 7, amplitude=max(amplitude, 1e-300))
    if amplitude == 0.0:
        phasor = np.zeros(n, complex)
    rot = rotation_matrix(np.radians(heel_deg), 0.02, 0.7)
    pos = np.array([-35.0, 12.0, heave])
    fast = _agree(panels, hull, waves, phasor, pos, rot)
    if case == "out of the water":
        np.testing.assert_array_equal(fast, 0.0)


def test_short_waves_decay_cutoff(s175):
    # k up to 3 rad/m on a deeply immersed hull (keel 15.5 m down): e^{−k d} < 2^−54 for the
    # shortest components over the bottom sub-blocks, which the kernel then leaves out
    hull, panels = s175
    rng = np.random.default_rng(11)
    waves = WaveComponents.from_arrays(rng.uniform(0.5, 3.0, 40), rng.uniform(-np.pi, np.pi, 40))
    phasor = 0.05 * np.exp(1j * rng.uniform(0, 2 * np.pi, 40))
    for heave in (0.3, 6.0):
        pos = np.array([3.0, 1.0, heave])
        _agree(panels, hull, waves, phasor, pos, rotation_matrix(0.1, 0.0, 0.2), rtol=1e-12)


def test_no_components_is_calm_water(s175):
    hull, panels = s175
    empty = WaveComponents.from_arrays(np.zeros(0), np.zeros(0))
    waves, _ = _sea(3, 0)
    pos, rot = np.array([5.0, 5.0, 0.4]), rotation_matrix(0.2, 0.01, 0.0)
    f0 = froude_krylov_hydrostatic(panels, empty, np.zeros(0), pos, rot, rho=hull.rho, g=hull.g)
    f1 = froude_krylov_hydrostatic(panels, waves, np.zeros(3), pos, rot, rho=hull.rho, g=hull.g)
    np.testing.assert_allclose(f0, f1, rtol=1e-13, atol=1e-6)


def test_panels_from_arrays_match_from_mesh(s175):
    hull, panels = s175
    again = HullPanels(panels.vertices.tolist(), panels.triangles.tolist())
    waves, phasor = _sea(10, 3)
    args = (waves, phasor, np.array([1.0, 2.0, 0.1]), rotation_matrix(0.1, 0.02, 0.3))
    np.testing.assert_array_equal(
        froude_krylov_hydrostatic(again, *args, rho=hull.rho, g=hull.g),
        froude_krylov_hydrostatic(panels, *args, rho=hull.rho, g=hull.g),
    )
    with pytest.raises(ValueError, match="expected"):
        HullPanels(np.zeros((4, 2)), np.zeros((2, 3), int))


def test_parallel_batch_equals_serial(s175):
    hull, panels = s175
    n_ships = 5
    rng = np.random.default_rng(5)
    seas = [_sea(25, s) for s in range(n_ships)]
    args = (
        np.array([w.wavenumber for w, _ in seas]),
        np.array([w.cos_direction for w, _ in seas]),
        np.array([w.sin_direction for w, _ in seas]),
        np.array([w.local_amplitudes(c, *rng.uniform(-100, 100, 2)) for w, c in seas]),
        rng.uniform(-0.5, 0.5, n_ships),
        np.array([rotation_matrix(*rng.uniform(-0.3, 0.3, 3)) for _ in range(n_ships)]),
    )
    serial = froude_krylov_hydrostatic_batch(panels, *args, rho=hull.rho, g=hull.g)
    parallel = froude_krylov_hydrostatic_batch(panels, *args, rho=hull.rho, g=hull.g, parallel=True)
    np.testing.assert_array_equal(parallel, serial)
    empty = froude_krylov_hydrostatic_batch(panels, *(a[:0] for a in args), rho=hull.rho, g=hull.g)
    assert empty.shape == (0, 6)


# ----------------------------------------------------------------------------- float32 wave sums
# method="fast32" sums the wave terms in float32 (phases formed in float32, polynomials with
# errors ≲ 5e-7 of each term): ζ and the dynamic pressure carry ~1e-6 of their size, while the
# hydrostatic part and the integration stay float64. Against the reference the force and moment
# must agree to 2e-6 of their largest component (observed ≲ 3e-7 over these tests' seas and
# ≲ 6e-7 over S175-full states, 1500 faces, Hs 5 m: the tolerance leaves ≥ 3× room).
F32_TOL = 2e-6


def _agree32(panels, hull, waves, phasor, pos, rot):
    fast = froude_krylov_hydrostatic(
        panels, waves, phasor, pos, rot, rho=hull.rho, g=hull.g, method="fast32"
    )
    ref = froude_krylov_hydrostatic(
        panels, waves, phasor, pos, rot, rho=hull.rho, g=hull.g, method="reference"
    )
    scale = np.abs(ref[:3]).max(), np.abs(ref[3:]).max()
    np.testing.assert_allclose(fast[:3], ref[:3], rtol=0, atol=F32_TOL * scale[0])
    np.testing.assert_allclose(fast[3:], ref[3:], rtol=0, atol=F32_TOL * scale[1])
    return fast


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_fast32_matches_reference(s175, seed):
    hull, panels = s175
    waves, phasor = _sea(50, seed, amplitude=1.2)
    rng = np.random.default_rng(100 + seed)
    pos = np.array([rng.uniform(-500, 500), rng.uniform(-500, 500), rng.uniform(-1, 1)])
    rot = rotation_matrix(*rng.uniform(-0.4, 0.4, 2), rng.uniform(-np.pi, np.pi))
    _agree32(panels, hull, waves, phasor, pos, rot)


@pytest.mark.parametrize(
    ("heel_deg", "heave", "amplitude"),
    [(60.0, 0.0, 0.5), (20.0, 8.0, 1.0), (10.0, 0.0, 8.0), (0.0, 30.0, 0.5), (0.0, -20.0, 0.5)],
)
def test_fast32_matches_reference_in_adversarial_cases(s175, heel_deg, heave, amplitude):
    # heeled, deck immersed, huge waves, fully submerged, out of the water (exactly zero)
    hull, panels = s175
    waves, phasor = _sea(50, 7, amplitude=amplitude)
    rot = rotation_matrix(np.radians(heel_deg), 0.02, 0.7)
    fast = _agree32(panels, hull, waves, phasor, np.array([-35.0, 12.0, heave]), rot)
    if heave == -20.0:
        np.testing.assert_array_equal(fast, 0.0)


def test_fast32_calm_water_is_hydrostatics(s175):
    # no wave terms: the float32 path reduces to the float64 hydrostatics (1e-12: only the
    # rounding of zero wave sums, which are exact zeros)
    hull, panels = s175
    waves, _ = _sea(10, 0)
    calm = np.zeros(10, complex)
    eq = equilibrium(hull, np.radians(20.0))
    rot = rotation_matrix(np.radians(20.0), eq.trim, 0.0)
    pos = np.array([0.0, 0.0, eq.heave])
    args = (panels, waves, calm, pos, rot)
    f32 = froude_krylov_hydrostatic(*args, rho=hull.rho, g=hull.g, method="fast32")
    f64 = froude_krylov_hydrostatic(*args, rho=hull.rho, g=hull.g, method="fast")
    np.testing.assert_allclose(f32, f64, rtol=1e-12, atol=1e-6)


def test_fast32_batch_equals_single(s175):
    hull, panels = s175
    ships = []
    for s in range(3):
        waves, phasor = _sea(30, s)
        ships.append(
            (
                waves,
                phasor,
                np.array([10.0 * s, -5.0 * s, 0.2]),
                rotation_matrix(0.05 * s, -0.02 * s, 0.3 * s),
            )
        )
    single = np.array(
        [
            froude_krylov_hydrostatic(
                panels, w, c, np.array([0.0, 0.0, p[2]]), r, rho=hull.rho, g=hull.g,
                method="fast32",
            )
            for w, c, p, r in [(w, w.local_amplitudes(c, p[0], p[1]), p, r) for w, c, p, r in ships]
        ]
    )  # fmt: skip
    batch = froude_krylov_hydrostatic_batch(
        panels,
        np.array([w.wavenumber for w, *_ in ships]),
        np.array([w.cos_direction for w, *_ in ships]),
        np.array([w.sin_direction for w, *_ in ships]),
        np.array([w.local_amplitudes(c, p[0], p[1]) for w, c, p, _ in ships]),
        np.array([p[2] for *_, p, _ in ships]),
        np.array([r for *_, r in ships]),
        rho=hull.rho,
        g=hull.g,
        single_precision=True,
    )
    np.testing.assert_array_equal(batch, single)


@pytest.mark.parametrize("heave", [0.3, 6.0])
def test_fast32_short_waves_take_the_clamped_decay(s175, heave):
    # k up to 40 rad/m: (k/ln 2)·d reaches the unclamped exponential's limit of 125 within
    # 2.2 m of the surface, so the waterline sub-blocks (d from 0 to several metres) run the
    # clamped 2^−y for the short components; the deep sub-blocks leave them out (cut-off).
    # Same 2e-6 bar as the other float32 tests.
    hull, panels = s175
    rng = np.random.default_rng(12)
    k = np.r_[rng.uniform(0.02, 0.3, 20), rng.uniform(20.0, 40.0, 20)]
    waves = WaveComponents.from_arrays(k, rng.uniform(-np.pi, np.pi, 40))
    phasor = np.r_[np.full(20, 0.4), np.full(20, 0.01)] * np.exp(1j * rng.uniform(0, 6.3, 40))
    _agree32(panels, hull, waves, phasor, np.array([3.0, 1.0, heave]), rotation_matrix(0.1, 0, 0.2))


@pytest.mark.parametrize("direction", [np.pi, 0.6, -2.2])
def test_fast32_long_crested_sea_matches_reference(s175, direction):
    # all components along one direction: the float32 kernel forms one projection per vertex
    # (its long-crested branch); same 2e-6 bar as the general branch
    hull, panels = s175
    rng = np.random.default_rng(21)
    omega = np.sort(rng.uniform(0.3, 1.6, 50))
    waves = WaveComponents.from_arrays(omega**2 / 9.81, np.full(50, direction))
    phasor = 1.2 * rng.uniform(0.2, 1.0, 50) * np.exp(1j * rng.uniform(0, 2 * np.pi, 50))
    rot = rotation_matrix(0.1, -0.03, 0.4)
    _agree32(panels, hull, waves, phasor, np.array([30.0, -8.0, 0.3]), rot)
