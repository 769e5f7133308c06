"""Branch-free polynomial sin/cos/exp of ship_gym.numerics.fastmath against numpy (and mpmath)."""

import math
import re

import numba as nb
import numpy as np
import pytest

from ship_gym.numerics.fastmath import (
    cos_turns,
    cos_turns_f32,
    cos_turns_nonneg_f32,
    exp2_neg,
    exp2_neg_f32,
    exp2_neg_unclamped_f32,
    exp_neg,
    sincos,
    sincos_turns,
)

# The kernels call these from loops compiled with "reassoc": the functions must keep their own
# (exact) evaluation order there. Test them from such loops, as used.
_CALLER_FLAGS = {"contract", "nsz", "reassoc"}


@nb.njit(fastmath=_CALLER_FLAGS)
def _sincos_loop(x):
    s = np.empty_like(x)
    c = np.empty_like(x)
    for i in range(x.shape[0]):
        s[i], c[i] = sincos(x[i])
    return s, c


@nb.njit(fastmath=_CALLER_FLAGS)
def _sincos_turns_loop(t):
    s = np.empty_like(t)
    c = np.empty_like(t)
    for i in range(t.shape[0]):
        s[i], c[i] = sincos_turns(t[i])
    return s, c


@nb.njit(fastmath=_CALLER_FLAGS)
def _cos_turns_loop(t, m):
    out = np.empty_like(t)
    for i in range(t.shape[0]):
        out[i] = cos_turns(t[i], m)
    return out


@nb.njit(fastmath=_CALLER_FLAGS)
def _exp_loop(y):
    out = np.empty_like(y)
    for i in range(y.shape[0]):
        out[i] = exp_neg(y[i])
    return out


@nb.njit(fastmath=_CALLER_FLAGS)
def _exp2_loop(y):
    out = np.empty_like(y)
    for i in range(y.shape[0]):
        out[i] = exp2_neg(y[i])
    return out


@nb.njit(fastmath=_CALLER_FLAGS)
def _sincos_sum(x):
    # a reassociated reduction around the inlined sincos: the loop vectorises, and the Cody–Waite
    # reduction inside must survive it
    acc = 0.0
    for i in range(x.shape[0]):
        s, c = sincos(x[i])
        acc += s * s + c * c
    return acc


# π in extended precision where the platform has it (x86: 80-bit long double), for references
# of sin 2πt at large t (the double π alone is off by 1.2e-16 relative: 8e-14 rad at t = 100)
_PI_LD = np.longdouble("3.14159265358979323846264338327950288")
_EXTENDED = np.finfo(np.longdouble).eps < 1e-17


def _ulp_tol(n_ulp: float) -> float:
    return n_ulp * np.finfo(float).eps


# documented bounds of the kernel tier (cos_turns: absolute, per unit amplitude; exp2_neg: relative)
_COS_TURNS_TOL = 1e-12
_EXP2_NEG_RTOL = 1.2e-12


@pytest.mark.parametrize("limit", [1.0, 30.0, 1e3, 1e4, 1e6])
def test_sincos_matches_numpy(limit):
    # Absolute error of a few ulp of 1 at every magnitude (the range reduction is exact up to
    # |x| ~ 6.5e6): the wave kernels use |x| ≲ 100, sea-state generators larger phases.
    rng = np.random.default_rng(0)
    x = rng.uniform(-limit, limit, 200_000)
    s, c = _sincos_loop(x)
    np.testing.assert_allclose(s, np.sin(x), rtol=0, atol=_ulp_tol(10))
    np.testing.assert_allclose(c, np.cos(x), rtol=0, atol=_ulp_tol(10))


def test_sincos_special_values_and_identity():
    x = np.array([0.0, -0.0, np.pi / 6, np.pi / 4, np.pi / 2, np.pi, 2 * np.pi, -np.pi / 3, 1e-300])
    s, c = _sincos_loop(x)
    np.testing.assert_allclose(s, np.sin(x), rtol=0, atol=_ulp_tol(4))
    np.testing.assert_allclose(c, np.cos(x), rtol=0, atol=_ulp_tol(4))
    assert s[0] == 0.0 and c[0] == 1.0
    x = np.random.default_rng(1).uniform(-100, 100, 10_000)
    assert _sincos_sum(x) == pytest.approx(x.size, rel=1e-14)


def test_sincos_is_continuous_across_reduction_boundaries():
    # The reduction switches n = rint(x / 2π) at odd multiples of π (and the turn versions at
    # half-integers): no jump beyond round-off either side of the switch.
    k = np.arange(-50, 51)
    centres = (2 * k + 1) * np.pi
    offsets = np.array([-1e-9, -1e-12, -1e-15, 0.0, 1e-15, 1e-12, 1e-9])
    x = (centres[:, None] + offsets[None, :] * np.maximum(1.0, np.abs(centres[:, None]))).ravel()
    s, c = _sincos_loop(x)
    np.testing.assert_allclose(s, np.sin(x), rtol=0, atol=_ulp_tol(10))
    np.testing.assert_allclose(c, np.cos(x), rtol=0, atol=_ulp_tol(10))
    # consecutive floats around x = π: monotone sin, cos ≈ −1
    xs = np.nextafter(np.pi, 0.0) + np.arange(-20, 21) * np.spacing(np.pi)
    s, c = _sincos_loop(xs)
    assert np.all(np.diff(s) <= 0.0)
    np.testing.assert_allclose(c, -1.0, rtol=0, atol=_ulp_tol(4))
    # turns: around every half-integer
    t = (np.arange(-20, 21) + 0.5)[:, None] + np.array([-1e-12, -1e-15, 0.0, 1e-15, 1e-12])[None, :]
    t = t.ravel()
    if not _EXTENDED:
        t = t[np.abs(t) < 2]
    s, c = _sincos_turns_loop(t)
    ref = 2 * _PI_LD * t.astype(np.longdouble)
    np.testing.assert_allclose(s, np.sin(ref).astype(float), rtol=0, atol=_ulp_tol(10))
    np.testing.assert_allclose(c, np.cos(ref).astype(float), rtol=0, atol=_ulp_tol(10))
    np.testing.assert_allclose(_cos_turns_loop(t, 1.0), c, rtol=0, atol=_COS_TURNS_TOL)


@pytest.mark.parametrize("limit", [0.5, 5.0, 100.0])
def test_sincos_turns_and_cos_turns(limit):
    if limit > 2 and not _EXTENDED:
        pytest.skip("needs an extended-precision reference for 2πt")
    rng = np.random.default_rng(2)
    t = rng.uniform(-limit, limit, 100_000)
    ref = 2 * _PI_LD * t.astype(np.longdouble)  # the exact phase of the double t
    s, c = _sincos_turns_loop(t)
    np.testing.assert_allclose(s, np.sin(ref).astype(float), rtol=0, atol=_ulp_tol(10))
    np.testing.assert_allclose(c, np.cos(ref).astype(float), rtol=0, atol=_ulp_tol(10))
    for m in (1.0, -2.5, 0.0):
        np.testing.assert_allclose(
            _cos_turns_loop(t, m),
            m * np.cos(ref).astype(float),
            rtol=0,
            atol=_COS_TURNS_TOL * abs(m),
        )
    # a harmonic as modulus and phase offset (how the wave kernel uses it)
    a, b = 0.7, -1.3
    phase = np.arctan2(b, a) / (2 * np.pi)
    h = _cos_turns_loop(t - phase, np.hypot(a, b))
    href = (a * np.cos(ref) + b * np.sin(ref)).astype(float)
    atol = (_COS_TURNS_TOL + _ulp_tol(4) * max(1, limit)) * np.hypot(a, b)
    np.testing.assert_allclose(h, href, rtol=0, atol=atol)


def test_exp_neg_matches_numpy():
    # the wave kernels use y = k d in [0, 45] (beyond, e^−y < 3e-20 is negligible)
    rng = np.random.default_rng(3)
    y = np.concatenate([rng.uniform(0.0, 45.0, 200_000), rng.uniform(0.0, 1e-3, 1000)])
    e = _exp_loop(y)
    np.testing.assert_allclose(e, np.exp(-y), rtol=_ulp_tol(4), atol=0)
    y = np.linspace(0.0, 700.0, 20_001)
    np.testing.assert_allclose(_exp_loop(y), np.exp(-y), rtol=_ulp_tol(8), atol=0)
    # negative arguments (growth) are exact too, within the documented range
    y = np.linspace(-700.0, 0.0, 2001)
    np.testing.assert_allclose(_exp_loop(y), np.exp(-y), rtol=_ulp_tol(8), atol=0)


def test_exp_neg_extremes():
    e = _exp_loop(np.array([0.0, 700.0, 745.0, 1e300, np.inf, np.nan]))
    assert e[0] == 1.0
    # clamped at y = 700: tiny, positive, finite (never an inf/garbage exponent)
    assert e[1] == pytest.approx(math.exp(-700.0), rel=1e-14)
    assert np.all(e[2:5] == e[1])
    assert np.isnan(e[5])


def test_exp2_neg_matches_numpy():
    rng = np.random.default_rng(4)
    y = rng.uniform(0.0, 65.0, 200_000)  # (k/ln2) d for k d ≤ 45
    np.testing.assert_allclose(_exp2_loop(y), np.exp2(-y), rtol=_EXP2_NEG_RTOL, atol=0)
    y = np.arange(-1000.0, 1021.0)  # integers: exact powers of two
    np.testing.assert_array_equal(_exp2_loop(y), np.exp2(-y))
    y = np.linspace(-1000.0, 1020.0, 100_001)
    np.testing.assert_allclose(_exp2_loop(y), np.exp2(-y), rtol=_EXP2_NEG_RTOL, atol=0)
    e = _exp2_loop(np.array([1020.0, 2000.0, np.inf]))
    assert np.all(e == np.exp2(-1020.0))


def test_loops_vectorise():
    # The point of these functions: loops calling them compile to AVX/SSE vector code with no
    # libm calls (checked on the assembly; skipped where the target has no 256-bit vectors).
    sig = _sincos_sum.signatures[0] if _sincos_sum.signatures else None
    if sig is None:
        _sincos_sum(np.zeros(4))
        sig = _sincos_sum.signatures[0]
    asm = _sincos_sum.inspect_asm(sig)
    if "ymm" not in asm and "zmm" not in asm:
        pytest.skip("no 256-bit vector code on this target")
    calls = [line for line in asm.splitlines() if "call" in line]
    assert not [line for line in calls if re.search(r"\b(sin|cos|exp|sincos)\b", line)]
    assert "vroundpd" in asm or "vrndscalepd" in asm


# ----------------------------------------------------------------------------- float32 tier
@nb.njit(fastmath=_CALLER_FLAGS)
def _cos_turns_f32_loop(t, m):
    out = np.empty_like(t)
    for i in range(t.shape[0]):
        out[i] = cos_turns_f32(t[i], m[i])
    return out


@nb.njit(fastmath=_CALLER_FLAGS)
def _exp2_f32_loop(y):
    out = np.empty_like(y)
    for i in range(y.shape[0]):
        out[i] = exp2_neg_f32(y[i])
    return out


@nb.njit(fastmath=_CALLER_FLAGS)
def _cos_turns_nonneg_f32_loop(t, m):
    out = np.empty_like(t)
    for i in range(t.shape[0]):
        out[i] = cos_turns_nonneg_f32(t[i], m[i])
    return out


@nb.njit(fastmath=_CALLER_FLAGS)
def _cos_turns_nonneg_f32_row(t, m):
    # as in the Froude–Krylov kernel: one amplitude for the whole loop (its folded
    # coefficients are loop-invariant)
    out = np.empty_like(t)
    for i in range(t.shape[0]):
        out[i] = cos_turns_nonneg_f32(t[i], m)
    return out


@nb.njit(fastmath=_CALLER_FLAGS)
def _exp2_unclamped_f32_loop(y):
    out = np.empty_like(y)
    for i in range(y.shape[0]):
        out[i] = exp2_neg_unclamped_f32(y[i])
    return out


def test_cos_turns_f32_matches_numpy():
    # float32 arguments up to 20 turns (the Froude–Krylov kernel's phases stay below ~10):
    # the result is compared with the float64 cosine of the *float32* argument, so only the
    # function's own error counts. Documented bound 3e-7·|amplitude| (float32 rounding of a
    # degree-10 polynomial and one doubling; the truncation is 2e-10); the result is float32.
    rng = np.random.default_rng(3)
    t = np.concatenate([rng.uniform(-20, 20, 200_000), np.arange(-8, 8.25, 0.25)])
    t = t.astype(np.float32)
    m = rng.uniform(0.0, 3.0, t.size).astype(np.float32)
    out = _cos_turns_f32_loop(t, m)
    assert out.dtype == np.float32
    ref = m.astype(float) * np.cos(2.0 * np.pi * t.astype(float))
    assert np.max(np.abs(out - ref) / np.maximum(m, 1e-30)) < 3e-7


def test_exp2_neg_f32_matches_numpy():
    # relative error ≲ 2e-7 over the kernel's range (y = k d / ln 2 ≥ 0), clamped at 2^−126
    rng = np.random.default_rng(4)
    y = np.concatenate([rng.uniform(0.0, 130.0, 200_000), np.arange(0.0, 130.0, 0.5)])
    y = y.astype(np.float32)
    out = _exp2_f32_loop(y)
    assert out.dtype == np.float32
    ref = np.exp2(-np.minimum(y.astype(float), 126.0))
    assert np.max(np.abs(out / ref - 1.0)) < 2e-7
    assert _exp2_f32_loop(np.array([0.0], np.float32))[0] == pytest.approx(1.0, abs=1e-7)


def test_cos_turns_nonneg_f32_matches_numpy():
    # Same check as for cos_turns_f32, against the documented bound 6e-7·amplitude (a degree-8
    # polynomial, 9.5e-8 with its float32 coefficients, the amplitude's √(2a) folded into them:
    # measured 5.2e-7), over amplitudes from 0 to 1e3, per element and fixed per loop.
    rng = np.random.default_rng(5)
    t = np.concatenate([rng.uniform(-20, 20, 200_000), np.arange(-8, 8.25, 0.25)])
    t = t.astype(np.float32)
    ref = np.cos(2.0 * np.pi * t.astype(float))
    for m in (
        rng.uniform(0.0, 3.0, t.size).astype(np.float32),
        rng.uniform(1e-3, 1e3, t.size).astype(np.float32),
    ):
        out = _cos_turns_nonneg_f32_loop(t, m)
        assert out.dtype == np.float32
        assert np.max(np.abs(out - m * ref) / np.maximum(m, 1e-30)) < 6e-7
    for m in (np.float32(0.37), np.float32(2.3)):
        out = _cos_turns_nonneg_f32_row(t, m)
        assert np.max(np.abs(out - float(m) * ref)) < 6e-7 * float(m)
    zero = _cos_turns_nonneg_f32_loop(t[:100], np.zeros(100, np.float32))
    np.testing.assert_array_equal(zero, 0.0)


def test_exp2_neg_unclamped_f32_matches_numpy():
    # relative error ≲ 2.5e-7 (measured 2e-7: a degree-5 polynomial, 1.4e-7 with its float32
    # coefficients) over its whole range −126 ≤ y ≤ 125, exact at integers (powers of two,
    # built by an integer subtraction on the exponent field)
    rng = np.random.default_rng(6)
    y = np.concatenate([rng.uniform(-126.0, 125.0, 200_000), np.arange(-126.0, 125.5, 0.5)])
    y = y.astype(np.float32)
    out = _exp2_unclamped_f32_loop(y)
    assert out.dtype == np.float32
    assert np.max(np.abs(out / np.exp2(-y.astype(float)) - 1.0)) < 2.5e-7
    n = np.arange(-126.0, 126.0, dtype=np.float32)
    np.testing.assert_array_equal(_exp2_unclamped_f32_loop(n), np.exp2(-n.astype(float)))


def test_float32_loops_vectorise_in_single_precision():
    # 8 lanes: the loops must compile to packed single-precision code with no double-precision
    # arithmetic (a Python float constant would silently promote them) and no libm calls
    _cos_turns_f32_loop(np.zeros(8, np.float32), np.ones(8, np.float32))
    _exp2_f32_loop(np.zeros(8, np.float32))
    _cos_turns_nonneg_f32_row(np.zeros(8, np.float32), np.float32(1.0))
    _exp2_unclamped_f32_loop(np.zeros(8, np.float32))
    loops = (
        _cos_turns_f32_loop,
        _exp2_f32_loop,
        _cos_turns_nonneg_f32_row,
        _exp2_unclamped_f32_loop,
    )
    for fn in loops:
        asm = fn.inspect_asm(fn.signatures[0])
        if "ymm" not in asm and "zmm" not in asm:
            pytest.skip("no 256-bit vector code on this target")
        assert re.search(r"v\w*ps\s+%[yz]mm", asm)
        assert not re.search(r"v(add|sub|mul|fmadd\w*)pd\b", asm)
        calls = [line for line in asm.splitlines() if "call" in line]
        assert not [line for line in calls if re.search(r"\b(cos|exp2?f?)\b", line)]
