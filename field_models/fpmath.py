"""Transcendental functions whose bits do not depend on the CPU, for floats and arrays alike.

numpy picks SIMD kernels for its transcendental ufuncs by CPU feature. On a CPU with AVX-512,
``np.arctan2`` and ``np.log`` round differently from the C library's ``math.atan2`` and
``math.log`` for a few arguments in a hundred and a few in ten thousand respectively; on other
CPUs the same calls give the C library's bits. A batched engine (arrays) that must give exactly
the bits of a one-trial engine (Python floats) can therefore not use ``np.arctan2`` on one side
and ``math.atan2`` on the other (DESIGN §4, "Not on the CPU either").

This module gives each function once, in two forms that do the same IEEE-754 operations in the
same order: :func:`atan2` / :func:`log` on Python floats and :func:`atan2_array` /
:func:`log_array` on numpy arrays. They are built only from operations the standard rounds
correctly (``+ - * /``, comparisons, ``frexp``), which numpy and CPython compute identically on
every CPU and at every SIMD dispatch level, so a value is the same in either form and on any
machine. The algorithms are fdlibm's (Sun Microsystems, 1993, freely redistributable), with
their coefficients; the argument reductions are simplified to few branches so the array forms
stay cheap. Both stay within 2 units in the last place of the exact value (tests check against
the C library on many arguments).

Not here, and why:

* ``sin`` and ``cos``: numpy computes float64 ``sin``/``cos`` with the C library at every
  dispatch level, so ``np.sin`` and ``math.sin`` agree (a test holds that at each level);
* ``exp``: the see quantisation takes it only on integer log indices, through one memoised
  scalar table that both engines read;
* ``tanh`` (the interception net): both engines call numpy's kernel (one machine, one kernel),
  and that kernel is the same at the AVX2 and AVX-512 levels; CPUs without AVX2 round it
  differently (see the README's section on determinism).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

Array = npt.NDArray[np.float64]

# fdlibm s_atan.c: atan(t) = t - t·(s1 + s2) for |t| <= 7/16.
_AT0, _AT1, _AT2, _AT3, _AT4, _AT5 = (
    3.33333333333329318027e-01,
    -1.99999999998764832476e-01,
    1.42857142725034663711e-01,
    -1.11111104054623557880e-01,
    9.09088713343650656196e-02,
    -7.69187620504482999495e-02,
)
_AT6, _AT7, _AT8, _AT9, _AT10 = (
    6.66107313738753120669e-02,
    -5.83357013379057348645e-02,
    4.97687799461593236017e-02,
    -3.65315727442169155270e-02,
    1.62858201153657823623e-02,
)
_ATAN_SMALL = 0.4375
"""Above this ratio the argument is reduced by atan(t) = π/4 + atan((t - 1)/(t + 1)), which
maps (7/16, 1] into [-0.392, 0): inside the polynomial's range."""
_QUARTER_PI_HI, _QUARTER_PI_LO = 7.85398163397448278999e-01, 3.06161699786838301793e-17
_HALF_PI_HI, _HALF_PI_LO = 1.57079632679489655800e00, 6.12323399573676603587e-17
_PI_HI, _PI_LO = 3.14159265358979311600e00, 1.22464679914735317720e-16

# fdlibm e_log.c: log(1 + f) with s = f / (2 + f).
_LG1, _LG2, _LG3, _LG4 = (
    6.666666666666735130e-01,
    3.999999999940941908e-01,
    2.857142874366239149e-01,
    2.222219843214978396e-01,
)
_LG5, _LG6, _LG7 = 1.818357216161805012e-01, 1.531383769920937332e-01, 1.479819860511658591e-01
_LN2_HI, _LN2_LO = 6.93147180369123816490e-01, 1.90821492927058770002e-10
_SQRT_HALF = 0.7071067811865476
"""Mantissas below √½ are doubled, so 1 + f lies in [√½, √2)."""


def _atan_tail(t: float) -> float:
    """t·(s1 + s2) of fdlibm's atan kernel (even and odd coefficients in two chains)."""
    z = t * t
    w = z * z
    s1 = z * (_AT0 + w * (_AT2 + w * (_AT4 + w * (_AT6 + w * (_AT8 + w * _AT10)))))
    s2 = w * (_AT1 + w * (_AT3 + w * (_AT5 + w * (_AT7 + w * _AT9))))
    return t * (s1 + s2)


def atan2(y: float, x: float) -> float:
    """The angle of (x, y) in (-π, π], as ``math.atan2`` defines it, with CPU-independent bits.

    Signed zeros, infinities and NaN follow ``math.atan2`` (handed to it: those results are
    exact constants, the same everywhere).
    """
    ay, ax = abs(y), abs(x)
    if not (ay < math.inf and ax < math.inf) or ay == 0.0 or ax == 0.0:
        return math.atan2(y, x)
    steep = ay > ax
    t = ax / ay if steep else ay / ax
    if t > _ATAN_SMALL:
        t = (t - 1.0) / (t + 1.0)
        a = _QUARTER_PI_HI - ((_atan_tail(t) - _QUARTER_PI_LO) - t)
    else:
        a = t - _atan_tail(t)
    if steep:
        a = (_HALF_PI_HI - a) + _HALF_PI_LO
    if x < 0.0:
        a = (_PI_HI - a) + _PI_LO
    return -a if y < 0.0 else a


def atan2_array(y: Array, x: Array) -> Array:
    """:func:`atan2` element by element: the same operations, so the same bits."""
    y = np.asarray(y, dtype=np.float64)
    x = np.asarray(x, dtype=np.float64)
    ay, ax = np.abs(y), np.abs(x)
    steep = ay > ax
    special = ~((ay < math.inf) & (ax < math.inf)) | (ay == 0.0) | (ax == 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.minimum(ay, ax) / np.maximum(ay, ax)
    wide = t > _ATAN_SMALL
    t = np.where(wide, (t - 1.0) / (t + 1.0), t)
    z = t * t
    w = z * z
    s1 = z * (_AT0 + w * (_AT2 + w * (_AT4 + w * (_AT6 + w * (_AT8 + w * _AT10)))))
    s2 = w * (_AT1 + w * (_AT3 + w * (_AT5 + w * (_AT7 + w * _AT9))))
    tail = t * (s1 + s2)
    a = np.where(wide, _QUARTER_PI_HI - ((tail - _QUARTER_PI_LO) - t), t - tail)
    a = np.where(steep, (_HALF_PI_HI - a) + _HALF_PI_LO, a)
    a = np.where(x < 0.0, (_PI_HI - a) + _PI_LO, a)
    a = np.where(y < 0.0, -a, a)
    if special.any():
        a[special] = [math.atan2(v, u) for v, u in zip(y[special], x[special], strict=True)]
    return a


def log(x: float) -> float:
    """The natural logarithm, as ``math.log`` for x > 0, with CPU-independent bits.

    Zero, negative, infinite and NaN arguments are handed to ``math.log`` (which raises
    ``ValueError`` for x <= 0, as before).
    """
    if not 0.0 < x < math.inf:
        return math.log(x)
    mantissa, exponent = math.frexp(x)  # x = m·2^e, m in [0.5, 1): exact
    if mantissa < _SQRT_HALF:
        mantissa += mantissa
        exponent -= 1
    f = mantissa - 1.0  # exact (Sterbenz)
    s = f / (2.0 + f)
    z = s * s
    w = z * z
    r = z * (_LG1 + w * (_LG3 + w * (_LG5 + w * _LG7))) + w * (_LG2 + w * (_LG4 + w * _LG6))
    half_f2 = 0.5 * f * f
    k = float(exponent)
    return k * _LN2_HI - ((half_f2 - (s * (half_f2 + r) + k * _LN2_LO)) - f)


def log_array(x: Array) -> Array:
    """:func:`log` element by element, for arrays of positive finite values.

    Raises:
        ValueError: If an element is not positive and finite (the scalar form's domain).
    """
    x = np.asarray(x, dtype=np.float64)
    if not bool(np.all((x > 0.0) & (x < math.inf))):
        raise ValueError("log_array: every element must be positive and finite")
    mantissa, exponent = np.frexp(x)
    low = mantissa < _SQRT_HALF
    mantissa = np.where(low, mantissa + mantissa, mantissa)
    k = (exponent - low).astype(np.float64)
    f = mantissa - 1.0
    s = f / (2.0 + f)
    z = s * s
    w = z * z
    r = z * (_LG1 + w * (_LG3 + w * (_LG5 + w * _LG7))) + w * (_LG2 + w * (_LG4 + w * _LG6))
    half_f2 = 0.5 * f * f
    out: Array = k * _LN2_HI - ((half_f2 - (s * (half_f2 + r) + k * _LN2_LO)) - f)
    return out
