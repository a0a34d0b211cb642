"""Hot loops of spectral synthesis (numba, cached): random bits to uniforms, and the spectrum fills.

The fills walk the half spectrum as rows ``(R, K)`` (every leading index
flattened, the last axis ``kx`` along the row) and hand out the random
coefficients in C order to the cells that carry energy, exactly as a
``flatnonzero`` + scatter would, in one pass and without an index array.

Each coefficient arrives as its squared random amplitude ``a2`` and the
cosine and sine of its random phase (float32, see ``synthesis._draws``).
"""
from __future__ import annotations

import numpy as np
from numba import njit

_TWO_PI = 2.0 * np.pi


_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
# Taylor coefficients of sin and cos on [0, pi/2] (truncation error < 1e-9, below float32's resolution)
_S1, _S2, _S3, _S4, _S5, _S6 = -1.0 / 6, 1.0 / 120, -1.0 / 5040, 1.0 / 362880, -1.0 / 39916800, 1.0 / 6227020800
_C1, _C2, _C3, _C4 = -0.5, 1.0 / 24, -1.0 / 720, 1.0 / 40320
_C5, _C6, _C7 = -1.0 / 3628800, 1.0 / 479001600, -1.0 / 87178291200


@njit(cache=True, nogil=True, error_model="numpy")
def splitmix64(key, i):
    """Word ``i`` of the SplitMix64 stream started at ``key``: a counter-based generator (any ``i``, any order)."""
    z = key + np.uint64(i + 1) * _GOLDEN
    z = (z ^ (z >> np.uint64(30))) * _M1
    z = (z ^ (z >> np.uint64(27))) * _M2
    return z ^ (z >> np.uint64(31))


@njit(cache=True, nogil=True, error_model="numpy")
def coefficient_parts(key, start, u, c, s):
    """Coefficients ``start .. start+n-1`` of the stream ``key``: ``u`` uniform on ``(0, 1]``, ``c, s = cos, sin(th)``.

    One 64-bit word per coefficient: the high 32 bits give ``u``, the low 32
    bits the phase ``th = 2*pi * lo / 2**32`` (two bits pick the quadrant, the
    other thirty the angle inside it, whose sine and cosine are polynomials:
    the loop vectorises, no libm call).
    """
    scale = np.float32(2.0 ** -32)
    half = np.float32(0.5)
    quarter = (np.pi / 2) * 2.0 ** -30
    for i in range(u.size):
        z = splitmix64(key, start + i)
        hi = np.int64(z >> np.uint64(32))
        lo = np.int64(z & np.uint64(0xFFFFFFFF))
        u[i] = (np.float32(hi) + half) * scale
        x = np.float64(lo & 0x3FFFFFFF) * quarter
        x2 = x * x
        sn = x * (1.0 + x2 * (_S1 + x2 * (_S2 + x2 * (_S3 + x2 * (_S4 + x2 * (_S5 + x2 * _S6))))))
        cs = 1.0 + x2 * (_C1 + x2 * (_C2 + x2 * (_C3 + x2 * (_C4 + x2 * (_C5 + x2 * (_C6 + x2 * _C7))))))
        # rotate by the quadrant q (th = q*pi/2 + x); plain selects, so the loop vectorises
        q = lo >> 30
        swap = (q & 1) == 1
        cq = sn if swap else cs
        sq = cs if swap else sn
        cq = -cq if (q == 1 or q == 2) else cq
        sq = -sq if q >= 2 else sq
        c[i] = np.float32(cq)
        s[i] = np.float32(sq)


@njit(cache=True, nogil=True, error_model="numpy")
def count_envelope_rows(env2, counts):
    """Cells with ``env > 0`` per row; returns 1 if a value is not finite, 2 if one is negative, else 0."""
    R, K = env2.shape
    for r in range(R):
        n = 0
        for k in range(K):
            e = env2[r, k]
            if not np.isfinite(e):
                return 1
            if e < 0:
                return 2
            if e > 0:
                n += 1
        counts[r] = n
    return 0


@njit(cache=True, nogil=True, error_model="numpy")
def fill_envelope(spec2, env2, r0, r1, a2, c, s):
    """Rows ``r0..r1-1`` of ``spec2``: ``env * sqrt(a2) * exp(i*th)`` on ``env > 0`` (coefficients in C order), 0 elsewhere."""
    K = spec2.shape[1]
    j = 0
    for r in range(r0, r1):
        for k in range(K):
            e = env2[r, k]
            if e > 0:
                cj = np.float64(c[j])
                sj = np.float64(s[j])
                # |exp(i*th)| = 1 to float64 precision, not just float32's
                m = e * np.sqrt(np.float64(a2[j]) / (cj * cj + sj * sj))
                spec2[r, k] = complex(m * cj, m * sj)
                j += 1
            else:
                spec2[r, k] = 0
    return j


@njit(cache=True, nogil=True, error_model="numpy")
def band_rows(q0, q1, wxsq, lo, hi, kbeg, kend):
    """Per row ``(i0, i1)`` of a ``(m0, m1, K)`` block, the kx interval ``[kbeg, kend)`` inside the band.

    ``lo`` and ``hi`` are the annulus limits in cycles/sample with their
    tolerance already applied. The radius grows with kx along a row, so the
    band is one interval; its ends are found by bisection on the same test.
    """
    m1 = q1.size
    K = wxsq.size
    for r in range(q0.size * m1):
        q = q0[r // m1] + q1[r % m1]
        # first k with f >= lo and f > 0
        a, b = 0, K
        while a < b:
            mid = (a + b) // 2
            f = np.sqrt(q + wxsq[mid]) / _TWO_PI
            if f >= lo and f > 0:
                b = mid
            else:
                a = mid + 1
        start = a
        # first k with f > hi
        a, b = start, K
        while a < b:
            mid = (a + b) // 2
            f = np.sqrt(q + wxsq[mid]) / _TWO_PI
            if f > hi:
                b = mid
            else:
                a = mid + 1
        kbeg[r] = start
        kend[r] = max(a, start)


@njit(cache=True, nogil=True, error_model="numpy")
def fill_power_law(spec2f, q0, q1, wxsq, kbeg, kend, r0, r1, a2, c, s, exponent, kint0, kint1, pw):
    """Rows ``r0..r1-1`` of a ``(m0*m1, K)`` block: ``|w|**-exponent * rad * exp(i*th)`` inside each row's band.

    ``spec2f`` is the block's float view ``(m0*m1, 2*K)`` (real and imaginary
    parts interleaved), written in its own precision. ``a2`` is the squared
    random amplitude of each coefficient, ``c, s`` its phase's cosine and sine.
    Writes into ``pw`` (one entry per coefficient) ``|S|**2`` for the
    interior cells ``kint0 <= kx < kint1`` (those that stand for two cells of
    the full spectrum) and 0 for the others.
    """
    m1 = q1.size
    K2 = spec2f.shape[1]
    ex = spec2f.dtype.type(-exponent)
    half = spec2f.dtype.type(0.5)
    scratch = np.empty(K2 // 2, dtype=spec2f.dtype)
    j = 0
    for r in range(r0, r1):
        q = q0[r // m1] + q1[r % m1]
        b0 = kbeg[r]
        b1 = kend[r]
        row = spec2f[r]
        for k in range(0, 2 * b0):
            row[k] = 0
        n = b1 - b0
        # slices, so that every index below is provably in range and the loops vectorise
        cc = c[j:j + n]
        ss = s[j:j + n]
        rr = a2[j:j + n]
        wx = wxsq[b0:b1]
        mb = scratch[:n]
        if exponent == 1.0:
            for t in range(n):
                r2 = spec2f.dtype.type(q + wx[t])
                # 1/|w| times the amplitude, and |exp(i*th)| = 1 to the output's precision
                mb[t] = np.sqrt(rr[t] / (r2 * (cc[t] * cc[t] + ss[t] * ss[t])))
        else:
            for t in range(n):
                r2 = spec2f.dtype.type(q + wx[t])
                mb[t] = r2 ** (ex * half) * np.sqrt(rr[t] / (cc[t] * cc[t] + ss[t] * ss[t]))
        out = row[2 * b0:2 * b1]
        for t in range(n):
            out[2 * t] = mb[t] * cc[t]
            out[2 * t + 1] = mb[t] * ss[t]
        for k in range(2 * b1, K2):
            row[k] = 0
        # |S|**2 of each coefficient, 0 on the self-conjugate planes (summed by the caller)
        pp = pw[j:j + n]
        for t in range(n):
            pp[t] = mb[t] * mb[t] * (cc[t] * cc[t] + ss[t] * ss[t])
        for t in range(n):
            k = b0 + t
            if k < kint0 or k >= kint1:
                pp[t] = 0
        j += n
