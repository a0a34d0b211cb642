"""The hand-written, generic parts of the integer hash's SIMD drivers (``fast_*``, generated in ``_intpart_*``).

What depends on the kernel and the basis only through a few numbers is
written here once, with those numbers as arguments, so that numba compiles it
per (dimension, tap count, input and output type) instead of once per
(dimension, kernel, basis, type) in every generated module:
:func:`exact_split`, the split with the exact index reduction (any period,
any index). Its floating-point
expressions are those the generated fast splits evaluate, in the same order,
so the bits do not depend on which split ran (see ``_generate.py``).
"""
from __future__ import annotations

import numba as nb
import numpy as np

from ._inthash import MULT
from ._jit import _reduce

_U32 = np.uint32


@nb.njit(cache=True, nogil=True, inline="always")
def _scaled(x, f, q, shift):
    """``u = x F + phi + shift`` in float64.

    The generated splits add no shift for a kernel whose shift is 0; adding
    0.0 changes only ``u = -0.0`` (to +0.0), and no result: ``floor`` keeps
    the sign, ``u - floor(u)`` is +0.0 and the index 0 either way.
    """
    return np.float64(x) * f + q + shift


@nb.njit(cache=True, nogil=True)
def exact_split(pts, d, p0, m, freqs, o, phase, period, pmask, taps, left, shift, SR, TR, KR):
    """The exact split of points ``p0 .. p0 + m - 1`` at octave ``o`` into the drivers' rows; the non-finite count.

    Per axis ``a``: ``u = x F + phi + shift`` in float64 (a point with a
    non-finite ``u`` on any axis is counted and split as if at 0), ``l =
    floor(u)``, ``SR[a, i] = (u - l) - 1/2`` and ``TR[a, i] = u - l`` (read
    by the gradient basis only), both rounded once to the rows' type;
    ``KR[a * taps + k, i]`` is tap ``k``'s index ``(l - left + k) mod
    period``, reduced exactly (``_jit._reduce``, then stepped), times the
    axis's multiplier ``MULT[a]`` mod 2**32. ``pts`` is the ``(N, d)`` input
    (any float type); ``freqs``, ``phase``, ``period``, ``pmask`` as in the
    drivers; ``d`` (the dimension) and ``taps`` are passed as literals, so
    that the loops over axes and taps unroll (as fast as the generated
    splits were on this path), ``left`` and ``shift`` typed (int64, float64):
    one compilation per dimension, tap count and input and output type
    serves every kernel and both bases. The loops have no branch on the
    kernel or basis: LLVM would duplicate the loop per branch (loop
    unswitching), code that every driver linking this compiles again.
    """
    U = np.empty(d)  # a point's u per axis
    bad = 0
    for i in range(m):
        finite = True
        for a in range(d):
            U[a] = _scaled(pts[p0 + i, a], freqs[o, a], phase[a], shift)
            finite = finite and np.isfinite(U[a])
        if not finite:
            bad += 1
        for a in range(d):
            u = U[a] if finite else 0.0
            per = period[a]
            l = np.floor(u)  # noqa: E741
            SR[a, i] = (u - l) - 0.5
            TR[a, i] = u - l
            j = _reduce(l, left, per, pmask[a])
            for k in range(taps):  # (j + k) mod period, stepped (0 <= j < period): no modulo, no branch on the mask
                KR[a * taps + k, i] = _U32(_U32(j) * MULT[a])
                j += 1
                if j == per:
                    j = 0
    return bad
