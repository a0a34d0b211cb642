"""Hot loops of spectral synthesis (numba, cached): random bits to uniforms, and the spectrum fills.

The fills walk the half spectrum as rows ``(R, K)`` (every leading index
flattened, the last axis ``kx`` along the row) and hand out the random
coefficients in C order to the cells that carry energy, exactly as a
``flatnonzero`` + scatter would, in one pass and without an index array.

Each coefficient arrives as its squared random amplitude ``a2`` and the
cosine and sine of its random phase (float32, see ``synthesis._draws``).
A coefficient is one 64-bit word of a counter-based SplitMix64 stream, split
into two 32-bit halves: the high half gives the amplitude, the low half the
phase. Past the hash everything is 32-bit (16 float32 lanes of AVX-512), and
the power-law fill hashes a row's words in one loop and draws from them in a
second, so each loop vectorises at its own width.
"""
from __future__ import annotations

import numpy as np
from numba import njit
from numba.core.extending import overload
from numba.cpython.unsafe.numbers import viewer

_TWO_PI = 2.0 * np.pi


_GOLDEN = np.uint64(0x9E3779B97F4A7C15)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
# Taylor coefficients of sin and cos on [0, pi/4] (truncation error < 1e-9, below float32's resolution)
_S1, _S2, _S3, _S4 = -1.0 / 6, 1.0 / 120, -1.0 / 5040, 1.0 / 362880
_C1, _C2, _C3, _C4, _C5 = -0.5, 1.0 / 24, -1.0 / 720, 1.0 / 40320, -1.0 / 3628800


def _float_bits(x):
    """The bits of float32 ``x`` as an int32 (a bit cast: numpy with ``NUMBA_DISABLE_JIT``, one move compiled)."""
    return np.float32(x).view(np.int32)


def _bits_float(b):
    """The float32 whose bits are the int32 ``b`` (the inverse bit cast)."""
    return np.int32(b).view(np.float32)


@overload(_float_bits, inline="always")
def _float_bits_jit(x):
    return lambda x: viewer(x, np.int32)


@overload(_bits_float, inline="always")
def _bits_float_jit(b):
    return lambda b: viewer(b, np.float32)


@njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _halves(z):
    """The high and low 32 bits of word ``z`` as uint32: the amplitude's and the phase's bits."""
    return np.uint32(z >> np.uint64(32)), np.uint32(z & np.uint64(0xFFFFFFFF))


@njit(cache=True, nogil=True, error_model="numpy", inline="always")
def splitmix64(key, i):
    """Word ``i`` of the SplitMix64 stream started at ``key``: a counter-based generator (any ``i``, any order)."""
    z = key + np.uint64(i + 1) * _GOLDEN
    z = (z ^ (z >> np.uint64(30))) * _M1
    z = (z ^ (z >> np.uint64(27))) * _M2
    return z ^ (z >> np.uint64(31))


_LN2 = np.log(2.0)
_SQRT2 = np.sqrt(2.0)


@njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _amplitude2(h, mode):
    """float32 ``a**2`` from the high half ``h`` (uint32) of a word: ``u = (h + 1/2) / 2**32`` rounded to float32.

    ``u`` is in ``(0, 1]`` (the 128 largest ``h`` round to 1, where ``a**2``
    is 0 instead of about 1e-10); its float32 rounding keeps 24 significant
    bits at every scale, so the smallest ``u`` is ``2**-33`` as the exact
    ``(2h + 1) / 2**33`` has it. "rayleigh" (mode 1): ``-log u``; "uniform"
    (0): ``3 u**2``; "fixed" (2): 1. The log reads ``u``'s exponent ``e`` and
    mantissa ``m`` from its bits (``u = 2**e m``, ``m`` moved into
    ``[sqrt(1/2), sqrt(2))``) and takes ``log m = 2 atanh((m-1)/(m+1))`` to
    the ninth power (error below 1e-9). The error is float32 rounding: at most
    ``2**-22 * max(1, a**2)`` absolute against the exact law of the unrounded
    ``u`` (``tests/test_naive.py`` checks it).
    """
    u = np.float32(h) * np.float32(2.0 ** -32) + np.float32(2.0 ** -33)
    if mode == 1:
        b = _float_bits(u)
        e = (b >> np.int32(23)) - np.int32(127)
        m = _bits_float(np.int32((b & np.int32(0x7FFFFF)) | np.int32(0x3F800000)))  # [1, 2)
        big = m > np.float32(_SQRT2)
        m = m * np.float32(0.5) if big else m
        ef = np.float32(e + 1) if big else np.float32(e)
        t = (m - np.float32(1.0)) / (m + np.float32(1.0))
        t2 = t * t
        logm = np.float32(2.0) * t * (np.float32(1.0) + t2 * (np.float32(1.0 / 3) + t2 * (
            np.float32(1.0 / 5) + t2 * (np.float32(1.0 / 7) + t2 * np.float32(1.0 / 9)))))
        return -(ef * np.float32(_LN2) + logm)  # -log(2**e m)
    if mode == 0:
        return np.float32(3.0) * u * u
    return np.float32(1.0)


@njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _phase(lo):
    """float32 ``(cos th, sin th)`` for the phase ``th = 2*pi * l / 2**32`` of the low half ``l`` (uint32) of a word.

    Three bits pick the octant, 29 the angle inside it, reduced to ``y`` in
    ``[0, pi/4]`` whose sine and cosine are Taylor polynomials (error below
    1e-9); plain selects, so loops vectorise (16 float32 lanes) and call no libm.
    ``cos th**2 + sin th**2`` is 1 to float32 rounding (``2**-22``), so the
    power-law fill uses ``(c, s)`` as the unit phasor without dividing by its
    norm (:func:`fill_envelope` still divides, in float64).
    """
    octant = lo >> np.uint32(29)
    x = np.float32(np.int32(lo & np.uint32(0x1FFFFFFF))) * np.float32((np.pi / 4) * 2.0 ** -29)
    odd = (octant & np.uint32(1)) == np.uint32(1)
    y = np.float32(np.pi / 4) - x if odd else x
    y2 = y * y
    sn = y * (np.float32(1.0) + y2 * (np.float32(_S1) + y2 * (np.float32(_S2) + y2 * (
        np.float32(_S3) + y2 * np.float32(_S4)))))
    cs = np.float32(1.0) + y2 * (np.float32(_C1) + y2 * (np.float32(_C2) + y2 * (np.float32(_C3) + y2 * (
        np.float32(_C4) + y2 * np.float32(_C5)))))
    # inside the quadrant: angle x (even octant) or pi/2 - y (odd octant)
    cq = sn if odd else cs
    sq = cs if odd else sn
    q = octant >> np.uint32(1)  # th = q*pi/2 + (angle inside the quadrant)
    swap = (q & np.uint32(1)) == np.uint32(1)
    c2 = sq if swap else cq
    s2 = cq if swap else sq
    c2 = -c2 if (q == np.uint32(1) or q == np.uint32(2)) else c2
    s2 = -s2 if q >= np.uint32(2) else s2
    return c2, s2


@njit(cache=True, nogil=True, error_model="numpy")
def coefficient_parts(key, start, mode, a2, c, s):
    """Coefficients ``start .. start+n-1`` of the stream ``key`` into float32 ``a2, c, s``.

    Coefficient ``i`` is word ``i`` of :func:`splitmix64`: ``a2 = a**2``
    (:func:`_amplitude2` of its high half) and the cosine and sine of its
    phase (:func:`_phase` of its low half).
    """
    n = a2.size
    if mode == 1:
        for i in range(n):
            h, lo = _halves(splitmix64(key, start + i))
            a2[i] = _amplitude2(h, 1)
            x, y = _phase(lo)
            c[i] = x
            s[i] = y
    elif mode == 0:
        for i in range(n):
            h, lo = _halves(splitmix64(key, start + i))
            a2[i] = _amplitude2(h, 0)
            x, y = _phase(lo)
            c[i] = x
            s[i] = y
    else:
        for i in range(n):
            _, lo = _halves(splitmix64(key, start + i))
            a2[i] = np.float32(1.0)
            x, y = _phase(lo)
            c[i] = x
            s[i] = y


@njit(cache=True, nogil=True, error_model="numpy")
def count_envelope_rows(env2, counts, emax):
    """Cells with ``env > 0`` per row, and ``emax[0]`` the largest value; returns 1 if a value is not finite, 2 if one is negative, else 0."""
    R, K = env2.shape
    top = 0.0
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
                top = max(top, e)
        counts[r] = n
    emax[0] = top
    return 0


@njit(cache=True, nogil=True, error_model="numpy")
def fill_envelope(spec2, env2, counts, r0, r1, a2, c, s):
    """Rows ``r0..r1-1`` of ``spec2``: ``env * sqrt(a2) * exp(i*th)`` on ``env > 0`` (coefficients in C order), 0 elsewhere.

    ``counts[r]`` is the number of cells with ``env > 0`` in row ``r``: a row
    with all of them takes a branch-free loop (unsigned offsets, so it
    vectorises) computing exactly the same values as the general one.
    """
    K = spec2.shape[1]
    j = 0
    for r in range(r0, r1):
        if counts[r] == K:
            uj = np.uint64(j)
            for i in range(K):
                t = np.uint64(i)
                e = env2[r, t]
                cj = np.float64(c[uj + t])
                sj = np.float64(s[uj + t])
                m = e * np.sqrt(np.float64(a2[uj + t]) / (cj * cj + sj * sj))
                spec2[r, t] = complex(m * cj, m * sj)
            j += K
            continue
        for k in range(K):
            e = env2[r, k]
            if e > 0:
                cj = np.float64(c[j])
                sj = np.float64(s[j])
                # |exp(i*th)| = 1 to float64 precision, not just float32's (the general path keeps it: a fixed
                # amplitude is then exactly 1 in float64; spectral_noise's fill uses (c, s) as they are)
                m = e * np.sqrt(np.float64(a2[j]) / (cj * cj + sj * sj))
                spec2[r, k] = complex(m * cj, m * sj)
                j += 1
            else:
                spec2[r, k] = 0
    return j


@njit(cache=True, nogil=True, error_model="numpy")
def band_rows(q0, q1, wxsq, lo, hi, allow_dc, kbeg, kend):
    """Per row ``(i0, i1)`` of a ``(m0, m1, K)`` block, the kx interval ``[kbeg, kend)`` inside the band.

    ``lo`` and ``hi`` are the annulus limits in cycles/sample with their
    tolerance already applied; DC (``f = 0``) is in the band only with
    ``allow_dc``. The radius grows with kx along a row, so the band is one
    interval; its ends are found by bisection on the same test.
    """
    m1 = q1.size
    K = wxsq.size
    for r in range(q0.size * m1):
        q = q0[r // m1] + q1[r % m1]
        # first k with f >= lo and (f > 0 or DC allowed)
        a, b = 0, K
        while a < b:
            mid = (a + b) // 2
            f = np.sqrt(q + wxsq[mid]) / _TWO_PI
            if f >= lo and (f > 0 or allow_dc):
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


def _make_fill_power_law(mode, exponent_one, sample, quarter, unit):
    """:func:`fill_power_law` compiled for one amplitude law, ``exponent == 1`` or not, sample power or not (constants, so each loop vectorises).

    ``quarter``: ``2 * exponent`` when that is an integer other than 2 (the
    exponents 0.5, 1.5, 2, ... -1, ...), else None. Then ``|w|**-exponent =
    (qn**-0.25)**quarter`` by square roots and a fixed chain of products (a
    few roundings, vectorised) instead of a scalar ``pow`` per cell; otherwise
    ``pow`` (1024^2 float32: 1.59-1.68x a bare ``irfftn`` against 2.24-2.39x,
    ``benchmarks/bench_spectral_exponents.md``).
    """
    qpos = quarter is not None and quarter > 0
    qn_pow = 0 if quarter is None else abs(quarter)

    @njit(cache=True, nogil=True, error_model="numpy")
    def fill(specf, K, q0, q1, wn, kbeg, kend, r0, r1, key, start, exponent, qfloor, inv_qref, weight, rowpow,
             scratch, words, rowoff):
        """Rows ``r0..r1-1`` of a ``(m0*m1, K)`` block: ``e * a * exp(i*th)`` inside each row's band, 0 outside.

        The coefficients are words ``start, start+1, ...`` of the stream ``key``
        (the ``j``-th cell of the rows in C order takes word ``start + j``): the
        same float32 values as :func:`coefficient_parts` (so :func:`synthesize`
        with the same envelope draws the same), without the arrays between the
        two. Per row, one loop hashes the row's words into ``words`` (uint32,
        ``(2, K)`` at least: high and low halves; 64-bit integer lanes) and a
        second one draws and writes the cells from them (32-bit lanes only,
        twice as many per vector).

        ``e = qn ** (-exponent/2)`` with ``qn = max(q * inv_qref + wn[kx],
        qfloor * inv_qref)``: the power law divided by its value at ``|w|**2 =
        1/inv_qref`` (the caller picks the band's loudest end, so ``e <= 1``:
        no float32 overflow for any exponent; ``qfloor`` makes the law flat
        below the lowest nonzero frequency, which only DC can be). ``q = q0[i0]
        + q1[i1]`` is the row's part of ``|w|**2`` (float64) and ``wn = wxsq *
        inv_qref`` the kx part, already scaled, both in the block's precision,
        as ``qn`` and the cell. The magnitude is ``sqrt(a2 / qn)`` for
        ``exponent == 1`` (one division, whose result is also ``e**2``), else
        ``e * sqrt(a2)``; with ``unit`` (the float64 block) it is divided by
        ``sqrt(c**2 + s**2)`` too, so that a fixed amplitude is exactly 1 and
        the cells are :func:`fill_envelope`'s to float64 rounding; float32
        uses ``(c, s)`` as they are (on the unit circle to ``2**-22``).

        ``specf`` is a flat float view (real and imaginary parts
        interleaved); row ``r`` is its ``2*K`` floats from ``rowoff[r]``: one
        after the other in a block (``rowoff[r] = 2*K*r``), or each at its own
        place in a larger spectrum (the in-place synthesis writes the rows of
        the output's storage). ``rowpow[r]`` receives the row's power
        weighted by ``weight[kx]``: expected (``e**2``) or, with ``sample``, drawn
        (``|S|**2 = m**2 (c**2 + s**2)``); ``scratch`` (at least ``K`` floats) holds a row's terms,
        summed in float64 in a fixed order.

        Indices are unsigned offsets rather than slices: no negative-index
        wrap-around, so the loops vectorise, and no per-row array views (whose
        reference counting cost more than a short row's arithmetic).
        """
        m1 = q1.size
        T = specf.dtype.type
        ex = T(-0.5 * exponent)
        zero = T(0)
        one = np.uint64(1)
        two = np.uint64(2)
        qf = T(qfloor * inv_qref)
        hi_w = words[0]
        lo_w = words[1]
        j = start
        for r in range(r0, r1):
            qs = T((q0[r // m1] + q1[r % m1]) * inv_qref)
            b0 = kbeg[r]
            b1 = kend[r]
            base = np.uint64(rowoff[r])
            for k in range(2 * b0):
                specf[base + np.uint64(k)] = zero
            n = b1 - b0
            ob = base + np.uint64(2 * b0)
            ub = np.uint64(b0)
            for i in range(n):
                h, lo = _halves(splitmix64(key, j + i))
                hi_w[np.uint64(i)] = h
                lo_w[np.uint64(i)] = lo
            for i in range(n):
                t = np.uint64(i)
                a2 = T(_amplitude2(hi_w[t], mode))
                c32, s32 = _phase(lo_w[t])
                qn = max(qs + wn[ub + t], qf)
                if exponent_one:
                    e2 = T(1) / qn
                    m = np.sqrt(a2 * e2)
                elif quarter is not None:
                    r4 = np.sqrt(np.sqrt(qn))
                    b = T(1) / r4 if qpos else r4
                    e = T(1)
                    nq = qn_pow
                    while nq:
                        if nq & 1:
                            e = e * b
                        b = b * b
                        nq >>= 1
                    m = e * np.sqrt(a2)
                    e2 = e * e
                else:
                    e = qn ** ex
                    m = e * np.sqrt(a2)
                    e2 = e * e
                cc = T(c32)
                ss = T(s32)
                if unit:  # float64: (c, s) put on float64's unit circle, as synthesize does
                    m = m / np.sqrt(cc * cc + ss * ss)
                specf[ob + two * t] = m * cc
                specf[ob + two * t + one] = m * ss
                if sample:  # the drawn |S|**2, to the last bit of the output's precision
                    scratch[t] = m * m * (cc * cc + ss * ss) * weight[ub + t]
                else:
                    scratch[t] = e2 * weight[ub + t]
            # four running sums (a fixed order, so the same float every time; one chain would wait on each add)
            p0 = 0.0
            p1 = 0.0
            p2 = 0.0
            p3 = 0.0
            i = 0
            while i + 4 <= n:
                p0 += np.float64(scratch[i])
                p1 += np.float64(scratch[i + 1])
                p2 += np.float64(scratch[i + 2])
                p3 += np.float64(scratch[i + 3])
                i += 4
            while i < n:
                p0 += np.float64(scratch[i])
                i += 1
            rowpow[r] = (p0 + p1) + (p2 + p3)
            for k in range(2 * b1, 2 * K):
                specf[base + np.uint64(k)] = zero
            j += n

    return fill


_FILLS = {}


def fill_power_law(specf, K, q0, q1, wxsq, kbeg, kend, r0, r1, key, start, mode, exponent, qfloor, inv_qref,
                   weight, sample, rowpow, scratch, rowoff=None):
    """See :func:`_make_fill_power_law`'s kernel; dispatches to the variant for ``mode``, ``exponent == 1``, ``sample``.

    ``rowoff`` (int64, one per row, in floats of ``specf``): where each row
    starts; default: rows one after the other, ``2*K`` floats each.
    """
    two = 2.0 * float(exponent)
    quarter = int(two) if two == int(two) and exponent != 1.0 else None
    # unit follows the dtype, which numba specialises on anyway: no extra compiled variant
    flags = (int(mode), bool(exponent == 1.0), bool(sample), quarter, specf.dtype == np.float64)
    f = _FILLS.get(flags)
    if f is None:
        f = _FILLS[flags] = _make_fill_power_law(*flags)
    wn = (wxsq * float(inv_qref)).astype(specf.dtype)  # the kx part of |w|**2 / qref, in the block's precision
    words = np.empty((2, max(1, int(K))), dtype=np.uint32)
    if rowoff is None:
        rowoff = np.arange(r1, dtype=np.int64) * (2 * int(K))
    f(specf, K, q0, q1, wn, kbeg, kend, r0, r1, key, start, exponent, qfloor, inv_qref, weight, rowpow, scratch,
      words, rowoff)


@njit(cache=True, nogil=True, error_model="numpy")
def hermitian_symmetric_plane(P, map0, map1):
    """Make a self-conjugate plane ``P`` (2-D view) Hermitian in place, for a support symmetric under ``k -> -k``.

    ``map0[i]``, ``map1[i]`` are the positions of the mirrors ``-k`` along each
    axis. As :func:`noiselab.spectral.hermitian_plane` does when the support
    is symmetric: the first cell of each mirror pair in C order keeps its
    value, the other gets its conjugate, a self-conjugate cell ``v`` becomes
    ``|v| * sign(Re v)``. Returns the plane's ``sum |P|**2`` (float64).
    """
    m0, m1 = P.shape
    power = 0.0
    for i in range(m0):
        a = map0[i]
        for k in range(m1):
            b = map1[k]
            own = i * m1 + k
            mir = a * m1 + b
            v = P[i, k]
            if mir < own:
                w = P[a, b]
                v = complex(w.real, -w.imag)
            elif mir == own:
                mag = np.sqrt(np.float64(v.real) * np.float64(v.real) + np.float64(v.imag) * np.float64(v.imag))
                v = complex(mag if v.real >= 0 else -mag, 0.0)
            P[i, k] = v
            power += np.float64(v.real) * np.float64(v.real) + np.float64(v.imag) * np.float64(v.imag)
    return power
