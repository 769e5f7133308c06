"""Vectorisable float64 sin/cos and exp for numba hot loops.

numba calls the scalar libm for ``math.cos``/``math.exp`` unless Intel SVML is available (it is not
in the pip builds of llvmlite), and a libm call blocks LLVM's loop vectoriser. These branch-free
polynomial versions are inlined by LLVM into the caller's loop and vectorise (AVX2/FMA; the cost
per element against libm is measured in docs/benchmarks.md), with errors of a few ulp.
They are checked against numpy in ``tests/numerics/test_fastmath.py``.

numba's on-disk cache (``cache=True``) of a *caller* is keyed on the caller's source file only:
after editing this module, delete the callers' ``__pycache__/*.nbi``/``*.nbc`` (e.g. of
:mod:`ship_gym.forces.froude_krylov`), or they keep the old polynomials inlined.

Design notes
------------
* The functions are ordinary ``@njit`` functions (not ``inline="always"``): numba inlines those at
  the IR level, where the *caller's* fastmath flags would apply. Left to LLVM's inliner, their
  instructions keep their own flags, ``{"contract"}`` only (fused multiply–adds), so a caller may
  use ``"reassoc"`` for its reductions without LLVM rewriting the Cody–Waite range reduction
  (which relies on the exact evaluation order).
* Angles in *turns* (:func:`sincos_turns`, :func:`cos_turns`): sin 2πt, cos 2πt. The range
  reduction is then a single exact subtraction t − rint(t); a kernel that scales its wavenumbers by
  1/2π once per call saves the Cody–Waite step per element. The phase error is that of forming t
  itself (one rounding), the same as for a phase formed in radians.
* Polynomials: near-minimax (Chebyshev-economised, 40-digit) fits; sin(π f/2) and cos(π f/2) on
  |f| ≤ 1/2 (degree 13/12, truncation < 5e-17), then two angle doublings;
  2^x on |x| ≤ 1/2 (degree 10, truncation 2.2e-16), scaled by 2^−n built from the exponent bits.
* Two accuracy tiers. :func:`sincos`, :func:`sincos_turns` and :func:`exp_neg` are accurate to
  a few ulp. :func:`cos_turns` and :func:`exp2_neg`, made for the wave-pressure kernel whose
  per-pair cost is nothing but these polynomials, drop one and two polynomial terms
  (absolute error ≲ 1e-12 of the amplitude, relative ≲ 1.2e-12): less time there (measured:
  docs/benchmarks.md), and forces that still agree with the libm reference to ~1e-13 (the
  kernel's tests ask 1e-6).
* A float32 tier (:func:`cos_turns_f32`, :func:`exp2_neg_f32`, errors ≲ 3e-7) and, for the
  float32 Froude–Krylov kernel's pair loops, leaner float32 variants one degree lower
  (:func:`cos_turns_nonneg_f32`, amplitude folded into the coefficients, ≲ 6e-7;
  :func:`exp2_neg_unclamped_f32`, no clamp, ≲ 2.5e-7 relative): 7 multiply/FMA operations
  per element each, less kernel time (measured: docs/benchmarks.md), forces as close to the
  float64 reference.
"""

from __future__ import annotations

import numba as nb
import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

_FLAGS = {"contract"}

# sin(π f / 2) = f · Σ _SIN[i] f^{2i},  cos(π f / 2) = Σ _COS[i] f^{2i},  |f| ≤ 1/2
_S0, _S1, _S2, _S3, _S4, _S5, _S6 = (
    1.5707963267948966,
    -0.6459640975062443,
    0.07969262624604301,
    -0.004681754132340976,
    0.0001604411507421909,
    -3.59864335298231e-06,
    5.633933781537854e-08,
)
_C0, _C1, _C2, _C3, _C4, _C5, _C6 = (
    1.0,
    -1.2337005501361513,
    0.25366950789986475,
    -0.02086348073494657,
    0.000919259950041661,
    -2.520013526428479e-05,
    4.6552961874867623e-07,
)
# kernel tier (see the module notes): cos(π f / 2) = Σ _K[i] f^{2i} (truncation 5.6e-14) and
# 2^x = Σ _Q[i] x^i (truncation 8.1e-13), |f|, |x| ≤ 1/2
_K0, _K1, _K2, _K3, _K4, _K5 = (
    0.9999999999999444,
    -1.2337005501201592,
    0.25366950715370434,
    -0.020863468002244645,
    0.0009191617369539572,
    -2.4850963357813638e-05,
)
_Q0, _Q1, _Q2, _Q3, _Q4, _Q5, _Q6, _Q7, _Q8 = (
    1.0,
    0.6931471805459335,
    0.2402265069581299,
    0.05550410941205933,
    0.009618129159402558,
    0.0013333450568000645,
    0.00015403455852453838,
    1.5310079402249296e-05,
    1.3255224878668817e-06,
)
# 2^x = Σ _P[i] x^i, |x| ≤ 1/2
_P0, _P1, _P2, _P3, _P4, _P5, _P6, _P7, _P8, _P9, _P10 = (
    1.0,
    0.69314718055995,
    0.24022650695910097,
    0.05550410866444772,
    0.009618129107606888,
    0.0013333558230164974,
    0.0001540353044173605,
    1.5252657260200837e-05,
    1.321544258792169e-06,
    1.0208690299958306e-07,
    7.072585949269223e-09,
)

# Cody–Waite split of 2π: the high part has 33 significant bits, so n·_TWO_PI_HI is exact for
# |n| < 2**20, i.e. |x| < ~6.5e6 rad.
_TWO_PI_HI = 6.2831853069365025
_TWO_PI_LO = 2.430840202602477e-10
_INV_TWO_PI = 0.15915494309189535
# log2(e) and ln 2 split for exp(−y) = 2^−n e^{n ln2 − y}
_LOG2E = 1.4426950408889634
_LN2_HI = 0.6931471803691238
_LN2_LO = 1.9082149292705877e-10
_INV_LN2 = _LOG2E
# 1.5·2^52: x + _MAGIC puts round(x) in the low mantissa bits (|x| < 2^51)
_MAGIC = 6755399441055744.0


@intrinsic
def _f64_bits(typingctx, x):  # pragma: no cover - compiled
    """Reinterpret a float64 as int64 (a plain LLVM bitcast: vectorises)."""

    def codegen(context, builder, sig, args):
        return builder.bitcast(args[0], ir.IntType(64))

    return types.int64(types.float64), codegen


@intrinsic
def _bits_f64(typingctx, x):  # pragma: no cover - compiled
    """Reinterpret an int64 as float64."""

    def codegen(context, builder, sig, args):
        return builder.bitcast(args[0], ir.DoubleType())

    return types.float64(types.int64), codegen


@nb.njit(fastmath=_FLAGS, cache=True)
def _sincos_unit(f: float) -> tuple[float, float]:  # pragma: no cover - compiled
    """(sin 2πf, cos 2πf) for |f| ≲ 1/2: polynomials for the quarter angle, two doublings."""
    w = f * f
    s = f * (_S0 + w * (_S1 + w * (_S2 + w * (_S3 + w * (_S4 + w * (_S5 + w * _S6))))))
    c = _C0 + w * (_C1 + w * (_C2 + w * (_C3 + w * (_C4 + w * (_C5 + w * _C6)))))
    u = s + s  # 2 sin(πf/2)
    s2 = u * c  # sin(πf)
    c2 = 1.0 - u * s  # cos(πf) = 1 − 2 sin²(πf/2)
    u2 = s2 + s2
    return u2 * c2, 1.0 - u2 * s2


@nb.njit(fastmath=_FLAGS, cache=True)
def sincos_turns(t: float) -> tuple[float, float]:  # pragma: no cover - compiled
    """(sin 2πt, cos 2πt), branch-free, for |t| < 2**51 turns (absolute error ≲ 2e-15)."""
    return _sincos_unit(t - np.rint(t))  # the subtraction is exact


@nb.njit(fastmath=_FLAGS, cache=True)
def cos_turns(t: float, amplitude: float = 1.0) -> float:  # pragma: no cover - compiled
    """amplitude · cos 2πt, branch-free, |t| < 2**51 turns; kernel tier: error ≲ 1e-12·|amplitude|.

    11 multiply/FMA operations, against 20 for :func:`sincos_turns`: with y = π f/2,
    f = t − rint(t), only a cosine polynomial is needed, because the doublings
    cos 2y = 2 cos²y − 1 use no sine. A harmonic a cos 2πt + b sin 2πt is |c| cos 2π(t − φ/2π)
    with c = a + ib, φ = arg c: fold the phase into t and the modulus into ``amplitude``.
    """
    f = t - np.rint(t)
    w = f * f
    c = _K0 + w * (_K1 + w * (_K2 + w * (_K3 + w * (_K4 + w * _K5))))
    c2 = (c + c) * c - 1.0  # cos(π f)
    return ((amplitude + amplitude) * c2) * c2 - amplitude  # amplitude · cos(2π f)


@nb.njit(fastmath=_FLAGS, cache=True)
def sincos(x: float) -> tuple[float, float]:  # pragma: no cover - compiled
    """(sin x, cos x) for |x| < 6.5e6 rad, branch-free (absolute error ≲ 2e-15).

    Cody–Waite reduction modulo 2π (exact: the caller's fastmath flags do not apply, see the
    module notes), then the polynomial core on the remainder in turns.
    """
    n = np.rint(x * _INV_TWO_PI)
    h = (x - n * _TWO_PI_HI) - n * _TWO_PI_LO  # |h| ≤ π (+ rounding)
    return _sincos_unit(h * _INV_TWO_PI)


@nb.njit(fastmath=_FLAGS, cache=True)
def _pow2_poly(x: float) -> float:  # pragma: no cover - compiled
    """2^x for |x| ≤ 1/2 (relative error ≲ 3e-16)."""
    return _P0 + x * (
        _P1
        + x
        * (
            _P2
            + x
            * (
                _P3
                + x * (_P4 + x * (_P5 + x * (_P6 + x * (_P7 + x * (_P8 + x * (_P9 + x * _P10))))))
            )
        )
    )


@nb.njit(fastmath=_FLAGS, cache=True)
def _pow2_neg_int(n: float) -> float:  # pragma: no cover - compiled
    """2^−n for an integral float n with −1023 < n < 1023, from the IEEE exponent bits."""
    return _bits_f64(_f64_bits((1023.0 + _MAGIC) - n) << 52)  # type: ignore[call-arg]  # numba's stub counts typingctx


@nb.njit(fastmath=_FLAGS, cache=True)
def exp2_neg(y: float) -> float:  # pragma: no cover - compiled
    """2^−y for −1000 ≤ y, branch-free; kernel tier: relative error ≲ 1.2e-12.

    y above 1020 is treated as 1020 (2^−1020 ≈ 9e-308). 11 multiply/FMA operations. Kernels
    that need e^{−k d} scale k by 1/ln 2 once and call this.
    """
    y = min(y, 1020.0)
    n = np.rint(y)
    x = n - y
    p = _Q0 + x * (
        _Q1 + x * (_Q2 + x * (_Q3 + x * (_Q4 + x * (_Q5 + x * (_Q6 + x * (_Q7 + x * _Q8))))))
    )
    return p * _pow2_neg_int(n)


@nb.njit(fastmath=_FLAGS, cache=True)
def exp_neg(y: float) -> float:  # pragma: no cover - compiled
    """e^{−y} for −700 ≤ y (y above 700 is treated as 700: e^{−700} ≈ 1e-304), branch-free.

    Relative error ≲ 5e-16: e^{−y} = 2^{−n} e^{r}, r = n ln2 − y (Cody–Waite), |r| ≤ ln2/2.
    """
    y = min(y, 700.0)
    n = np.rint(y * _LOG2E)
    r = (n * _LN2_HI - y) + n * _LN2_LO
    return _pow2_poly(r * _INV_LN2) * _pow2_neg_int(n)


# ----------------------------------------------------------------------------- float32 tier
# Single-precision variants for kernels that can afford ~3e-7 absolute/relative errors (the
# float32 Froude–Krylov kernel, :mod:`ship_gym.forces.froude_krylov`): twice the SIMD lanes and
# shorter polynomials. Every constant is a numpy float32 so that numba keeps the arithmetic in
# single precision (a Python float would promote it to float64).
_F32 = np.float32
# cos(π f) = Σ _CF[i] f^{2i}, |f| ≤ 1/2 (Chebyshev fit, truncation 2e-10)
_CF0, _CF1, _CF2, _CF3, _CF4, _CF5 = (
    _F32(0.9999999997801801),
    _F32(-4.934802137096509),
    _F32(4.058709159854577),
    _F32(-1.335212004883353),
    _F32(0.23493731757156133),
    _F32(-0.024396324610719836),
)
# 2^x = Σ _QF[i] x^i, |x| ≤ 1/2 (truncation 4e-11 relative)
_QF0, _QF1, _QF2, _QF3, _QF4, _QF5, _QF6 = (
    _F32(0.9999999999595387),
    _F32(0.6931472067162213),
    _F32(0.24022651213692603),
    _F32(0.05550327202259872),
    _F32(0.009618025590000943),
    _F32(0.001340043694502858),
    _F32(0.00015469736118983962),
)
_ONE_F32 = _F32(1.0)
_EXP2_CLAMP_F32 = _F32(126.0)
# 1.5·2^23: x + _MAGIC_F32 puts round(x) in the low mantissa bits of a float32 (|x| < 2^22)
_BIAS_MAGIC_F32 = _F32(127.0 + 12582912.0)


@intrinsic
def _f32_bits(typingctx, x):  # pragma: no cover - compiled
    """Reinterpret a float32 as int32 (a plain LLVM bitcast: vectorises)."""

    def codegen(context, builder, sig, args):
        return builder.bitcast(args[0], ir.IntType(32))

    return types.int32(types.float32), codegen


@intrinsic
def _bits_f32(typingctx, x):  # pragma: no cover - compiled
    """Reinterpret an int32 as float32."""

    def codegen(context, builder, sig, args):
        return builder.bitcast(args[0], ir.FloatType())

    return types.float32(types.int32), codegen


@nb.njit(fastmath=_FLAGS, cache=True)
def cos_turns_f32(t: np.float32, amplitude: np.float32) -> np.float32:  # pragma: no cover
    """amplitude · cos 2πt in float32, branch-free, |t| < 2**22 turns.

    Absolute error ≲ 3e-7·|amplitude| (float32 rounding; the polynomial's own truncation is
    2e-10): f = t − rint(t), a degree-10 even polynomial for cos(π f) and one doubling,
    cos 2πf = 2 cos²(πf) − 1 (9 multiply/FMA operations). Arguments must be float32.
    """
    f = t - np.rint(t)
    w = f * f
    c = _CF0 + w * (_CF1 + w * (_CF2 + w * (_CF3 + w * (_CF4 + w * _CF5))))
    return ((amplitude + amplitude) * c) * c - amplitude


@nb.njit(fastmath=_FLAGS, cache=True)
def exp2_neg_f32(y: np.float32) -> np.float32:  # pragma: no cover - compiled
    """2^−y in float32 for y ≥ −126, branch-free; relative error ≲ 2e-7.

    y above 126 is treated as 126 (2^−126 ≈ 1.2e-38, the smallest normal float32). A degree-6
    polynomial for 2^x, |x| ≤ 1/2, scaled by 2^−n built from the exponent bits. The argument
    must be float32.
    """
    y = min(y, _EXP2_CLAMP_F32)
    n = np.rint(y)
    x = n - y
    p = _QF0 + x * (_QF1 + x * (_QF2 + x * (_QF3 + x * (_QF4 + x * (_QF5 + x * _QF6)))))
    return p * _bits_f32(_f32_bits(_BIAS_MAGIC_F32 - n) << 23)  # type: ignore[call-arg]  # numba's stub counts typingctx


# Leaner float32 variants for the Froude–Krylov kernel's two pair loops (less kernel time there
# than :func:`cos_turns_f32` / :func:`exp2_neg_f32`, measured: docs/benchmarks.md; forces as
# close to the float64 reference; tests/numerics/test_fastmath.py,
# tests/forces/test_froude_krylov.py).
# One degree lower each, with the coefficients refitted in float32 (discrete minimax by linear
# programming, rounding one coefficient to float32 at a time, low order first, and refitting the
# rest).
# cos(π f) = Σ _CN[i] f^{2i}, |f| ≤ 1/2, minimax for the error of 2 cos²(π f) − 1 (weight
# 4|cos π f|): 9.5e-8 with the float32 coefficients
_CN0, _CN1, _CN2, _CN3, _CN4 = (
    _F32(1.0),
    _F32(-4.934799671173096),
    _F32(4.058586597442627),
    _F32(-1.333335518836975),
    _F32(0.22338685393333435),
)
# 2^x = Σ _QN[i] x^i, |x| ≤ 1/2, relative minimax with _QN0 = 1: 1.4e-7 with the float32
# coefficients
_QN0, _QN1, _QN2, _QN3, _QN4, _QN5 = (
    _F32(1.0),
    _F32(0.6931470036506653),
    _F32(0.24022236466407776),
    _F32(0.0555076003074646),
    _F32(0.009671743959188461),
    _F32(0.0013260943815112114),
)
# 1.5·2^23: n + _MAGIC_F32 holds the integer n in its low mantissa bits (|n| < 2^22)
_MAGIC_F32 = _F32(12582912.0)


@nb.njit(fastmath=_FLAGS, cache=True)
def cos_turns_nonneg_f32(t: np.float32, amplitude: np.float32) -> np.float32:  # pragma: no cover
    """amplitude · cos 2πt in float32 for amplitude ≥ 0, branch-free, |t| < 2**22 turns.

    Absolute error ≲ 6e-7·amplitude (polynomial 9.5e-8, the rest float32 rounding, of the
    folded coefficients among others; measured 5.2e-7). With
    f = t − rint(t) and c ≈ cos(π f) (degree-8 even polynomial):
    amplitude · cos 2πf = (√(2·amplitude) c)² − amplitude, and the factor √(2·amplitude) is
    folded into the coefficients: a loop with a fixed amplitude computes them once, and each
    element costs 7 multiply/FMA operations (phase included: 8), against 9 for
    :func:`cos_turns_f32`. A negative amplitude gives NaN. Arguments must be float32.
    """
    f = t - np.rint(t)
    w = f * f
    r = np.sqrt(amplitude + amplitude)
    c = r * _CN0 + w * (r * _CN1 + w * (r * _CN2 + w * (r * _CN3 + w * (r * _CN4))))
    return c * c - amplitude


@nb.njit(fastmath=_FLAGS, cache=True)
def exp2_neg_unclamped_f32(y: np.float32) -> np.float32:  # pragma: no cover - compiled
    """2^−y in float32 for −126 ≤ y ≤ 125, branch-free, no clamp; relative error ≲ 2.5e-7.

    A degree-5 polynomial for 2^x, |x| ≤ 1/2, x = rint(y) − y, whose exponent field is then
    lowered by rint(y) with an integer subtraction (no float multiply). Outside the range the
    result is garbage: callers bound y themselves (the Froude–Krylov kernel checks
    (k/ln 2)·max d per pressure sub-block and falls back to :func:`exp2_neg_f32`). The
    argument must be float32.
    """
    n = np.rint(y)
    x = n - y
    p = _QN0 + x * (_QN1 + x * (_QN2 + x * (_QN3 + x * (_QN4 + x * _QN5))))
    return _bits_f32(_f32_bits(p) - (_f32_bits(n + _MAGIC_F32) << 23))  # type: ignore[call-arg]  # numba's stub counts typingctx
