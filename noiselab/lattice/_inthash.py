"""numba kernels for lattice noise addressed by an arithmetic integer hash (``hash="integer"``).

The lattice point ``(j_0, ..., j_{d-1})`` (each index already reduced
modulo its period) of output component ``c`` gets the 64-bit word

    ``h = fmix64(key_c + j_0 M_0 + ... + j_{d-1} M_{d-1})``  (mod 2**64)

with odd multipliers ``M_a`` and a seed-derived key per component;
``fmix64`` is MurmurHash3's 64-bit finaliser (a bijection: xor-shift,
multiply, xor-shift, multiply, xor-shift). The value basis reads the top 32
bits as a signed integer, ``v = (h >>s 32) / 2**31`` in ``[-1, 1)``; the
gradient basis picks the unit gradient ``grads[(h >> 32) mod n]``. There is
no permutation table and so no table period: rows and columns of the lattice
are independent draws (up to the hash's quality), unlike Phillips' nested
permutation, where every full-period row is a permutation of one table.

The linear prefix ``key + sum j_a M_a`` is separable (the grid path builds it
axis by axis over a block, :func:`block_values`), and the scattered kernels
(:func:`int_points`, :func:`int_points_jac`) walk the ``taps**d`` corners of a
chunk of points one corner at a time with the points in the inner loop:
every inner loop is straight-line integer and float code over contiguous
chunk arrays, which LLVM vectorises (no permutation gathers; the gradient
basis gathers only from the small gradient table). Every point's arithmetic
is one fixed sequence, so results do not depend on chunking or threads.
"""
from __future__ import annotations

import numba as nb
import numpy as np

from ._jit import _reduce, _wrap

CHUNK = 256
_TO_UNIT = 1.0 / 2147483648.0  # 2**-31: int32 range onto [-1, 1)
_C1 = np.uint64(0xFF51AFD7ED558CCD)
_C2 = np.uint64(0xC4CEB9FE1A85EC53)
_S33 = np.uint64(33)
_S32 = np.uint64(32)


@nb.njit(cache=True, nogil=True, inline="always")
def fmix64(h):
    """MurmurHash3's 64-bit finaliser (a bijection of uint64)."""
    h ^= h >> _S33
    h *= _C1
    h ^= h >> _S33
    h *= _C2
    h ^= h >> _S33
    return h


@nb.njit(cache=True, nogil=True, inline="always")
def hash_value(h):
    """The lattice value of a prefix word: top 32 bits of ``fmix64(h)``, signed, onto [-1, 1).

    ``fmix64``'s last step ``h ^= h >> 33`` leaves the top 33 bits alone, so
    it is skipped here: the same bits, two operations fewer.
    """
    h ^= h >> _S33
    h *= _C1
    h ^= h >> _S33
    h *= _C2
    return np.float64(np.int64(h) >> 32) * _TO_UNIT


@nb.njit(cache=True, nogil=True, inline="always")
def hash_index(h, n, nmask):
    """The gradient-table index of a prefix word: top 32 bits of ``fmix64(h)`` modulo ``n``."""
    top = np.int64(fmix64(h) >> _S32)
    if nmask >= 0:
        return top & nmask
    return top % n


@nb.njit(cache=True, nogil=True)
def block_prefix(h, lat, mult, first, key):
    """One axis of the linear prefix over a block: ``h'[m * nl + l] = h[m] + lat[l] * mult`` (uint64, wrapping).

    ``first``: ``h' = key + lat * mult`` (``h`` is ignored).
    """
    nl = lat.shape[0]
    m = 1 if first else h.shape[0]
    out = np.empty(m * nl, np.uint64)
    for i in range(m):
        hb = key if first else h[i]
        for l in range(nl):
            out[i * nl + l] = hb + np.uint64(lat[l]) * mult
    return out


@nb.njit(cache=True, nogil=True)
def block_values(h, out):
    """``out[m] = hash_value(h[m])`` over a block's prefix words."""
    for i in range(h.shape[0]):
        out[i] = hash_value(h[i])


@nb.njit(cache=True, nogil=True)
def block_gradients(h, grads, b, out):
    """``out[m] = grads[hash_index(h[m]), b]`` (component b of the gradient block)."""
    n = grads.shape[0]
    nmask = n - 1 if (n & (n - 1)) == 0 else -1
    for i in range(h.shape[0]):
        out[i] = grads[hash_index(h[i], n, nmask), b]


@nb.njit(cache=True, nogil=True, inline="always")
def _axis_setup(pts, p0, m, a, f, ph, shift, left, taps, coef, dcoef, per, msk, mult_a, W, DW, R, M, jac):
    """Weights (and derivatives), signed distances and hashed tap offsets of one axis for a chunk."""
    for i in range(m):
        u = pts[p0 + i, a] * f + ph + shift  # same rounding as the grid path
        fi = np.floor(u)
        t = u - fi
        t2 = t * t
        t3 = t2 * t
        t4 = t2 * t2
        t5 = t4 * t
        for k in range(taps):
            W[a, k, i] = ((coef[k, 0] + coef[k, 1] * t) + (coef[k, 2] * t2 + coef[k, 3] * t3)
                          + (coef[k, 4] * t4 + coef[k, 5] * t5))
            R[a, k, i] = t - shift + (left - k)
            if jac:
                DW[a, k, i] = ((dcoef[k, 0] + dcoef[k, 1] * t) + (dcoef[k, 2] * t2 + dcoef[k, 3] * t3)
                               + dcoef[k, 4] * t4)
    for i in range(m):
        u = pts[p0 + i, a] * f + ph + shift
        b = _reduce(np.floor(u), left, per, msk)
        for k in range(taps):
            M[a, k, i] = np.uint64(_wrap(b + k, per, msk)) * mult_a


@nb.njit(cache=True, nogil=True)
def int_points(pts, out, freqs, amps, phase, shift, left, taps, coef, period, pmask,
               keys, mult, grads, basis, absval):
    """Lattice noise with the integer hash at scattered points (any dimension; octaves fused).

    ``pts`` (N, d) float64; ``out`` (N, C) written; ``keys`` (C,) uint64 per
    component; ``mult`` (d,) uint64 odd multipliers; ``grads`` (n, d) unit
    gradients. The other arguments are those of ``_jit.eval_points``.
    Per chunk and octave: each axis's weights and hashed tap offsets
    ``M[a, k] = ((j + k) mod period) * M_a``; then the corners in odometer
    order, the prefix sums and weight products carried level by level, each
    level one vectorisable loop over the chunk.
    """
    npts, d = pts.shape
    ncomp = keys.shape[0]
    n = grads.shape[0]
    nmask = n - 1 if (n & (n - 1)) == 0 else -1
    noct = freqs.shape[0]
    W = np.empty((d, taps, CHUNK))
    R = np.empty((d, taps, CHUNK))
    M = np.empty((d, taps, CHUNK), np.uint64)
    HP = np.empty((d + 1, CHUNK), np.uint64)
    WP = np.empty((d + 1, CHUNK))
    T = np.empty(CHUNK)
    ACC = np.empty((ncomp, CHUNK))
    cnt = np.zeros(d, np.int64)
    dummy = np.empty((1, 1, 1))
    for p0 in range(0, npts, CHUNK):
        m = min(CHUNK, npts - p0)
        for o in range(noct):
            for a in range(d):
                _axis_setup(pts, p0, m, a, freqs[o, a], phase[a], shift, left, taps, coef, coef, period[a],
                            pmask[a], mult[a], W, dummy, R, M, False)
            for c in range(ncomp):
                key = keys[c]
                for i in range(m):
                    T[i] = 0.0
                for a in range(d):
                    cnt[a] = 0
                level = 0
                while True:
                    for a in range(level, d):
                        k = cnt[a]
                        Ma = M[a, k]
                        Wa = W[a, k]
                        if a == 0:
                            h1 = HP[1]
                            w1 = WP[1]
                            for i in range(m):
                                h1[i] = key + Ma[i]
                                w1[i] = Wa[i]
                        else:
                            h0 = HP[a]
                            w0 = WP[a]
                            h1 = HP[a + 1]
                            w1 = WP[a + 1]
                            for i in range(m):
                                h1[i] = h0[i] + Ma[i]
                                w1[i] = w0[i] * Wa[i]
                    hd = HP[d]
                    wd = WP[d]
                    if basis == 0:
                        for i in range(m):
                            T[i] += wd[i] * hash_value(hd[i])
                    elif d == 1:
                        r0 = R[0, cnt[0]]
                        for i in range(m):
                            g = hash_index(hd[i], n, nmask)
                            T[i] += wd[i] * (grads[g, 0] * r0[i])
                    elif d == 2:
                        r0 = R[0, cnt[0]]
                        r1 = R[1, cnt[1]]
                        for i in range(m):
                            g = hash_index(hd[i], n, nmask)
                            T[i] += wd[i] * (grads[g, 0] * r0[i] + grads[g, 1] * r1[i])
                    elif d == 3:
                        r0 = R[0, cnt[0]]
                        r1 = R[1, cnt[1]]
                        r2 = R[2, cnt[2]]
                        for i in range(m):
                            g = hash_index(hd[i], n, nmask)
                            T[i] += wd[i] * (grads[g, 0] * r0[i] + grads[g, 1] * r1[i] + grads[g, 2] * r2[i])
                    else:
                        for i in range(m):
                            g = hash_index(hd[i], n, nmask)
                            v = 0.0
                            for a in range(d):
                                v += grads[g, a] * R[a, cnt[a], i]
                            T[i] += wd[i] * v
                    a = d - 1
                    while a >= 0:
                        cnt[a] += 1
                        if cnt[a] < taps:
                            break
                        cnt[a] = 0
                        a -= 1
                    if a < 0:
                        break
                    level = a
                amp = amps[o]
                acc = ACC[c]
                for i in range(m):
                    v = abs(T[i]) if absval else T[i]
                    if o == 0:
                        acc[i] = amp * v
                    else:
                        acc[i] += amp * v
        for i in range(m):
            for c in range(ncomp):
                out[p0 + i, c] = ACC[c, i]


@nb.njit(cache=True, nogil=True)
def int_points_jac(pts, out, freqs, amps, phase, shift, left, taps, coef, dcoef, period, pmask,
                   keys, mult, grads, basis, absval):
    """Values and Jacobians with the integer hash at scattered points (any dimension; octaves fused).

    ``out`` (N, C, d + 1) float64 as in ``_jit.eval_points_jac``; the other
    arguments as in :func:`int_points`. A corner's term ``prod_a w_a v``
    differentiates along axis ``b`` to ``w_b' prod_{a != b} w_a v`` (plus, in
    the gradient basis, ``prod_a w_a g_b``).
    """
    npts, d = pts.shape
    ncomp = keys.shape[0]
    n = grads.shape[0]
    nmask = n - 1 if (n & (n - 1)) == 0 else -1
    noct = freqs.shape[0]
    W = np.empty((d, taps, CHUNK))
    DW = np.empty((d, taps, CHUNK))
    R = np.empty((d, taps, CHUNK))
    M = np.empty((d, taps, CHUNK), np.uint64)
    H = np.empty(CHUNK, np.uint64)
    WP = np.empty(CHUNK)
    DP = np.empty((d, CHUNK))
    V = np.empty(CHUNK)
    T = np.empty((d + 1, CHUNK))
    ACC = np.empty((ncomp, d + 1, CHUNK))
    cnt = np.zeros(d, np.int64)
    for p0 in range(0, npts, CHUNK):
        m = min(CHUNK, npts - p0)
        for o in range(noct):
            for a in range(d):
                _axis_setup(pts, p0, m, a, freqs[o, a], phase[a], shift, left, taps, coef, dcoef, period[a],
                            pmask[a], mult[a], W, DW, R, M, True)
            for c in range(ncomp):
                key = keys[c]
                for q in range(d + 1):
                    for i in range(m):
                        T[q, i] = 0.0
                for a in range(d):
                    cnt[a] = 0
                while True:
                    # the corner's prefix word and weight products (value and each axis's derivative)
                    k = cnt[0]
                    for i in range(m):
                        H[i] = key + M[0, k, i]
                        WP[i] = W[0, k, i]
                        DP[0, i] = DW[0, k, i]
                    for b in range(1, d):
                        DP[b, :m] = WP[:m] * DW[b, cnt[b], :m]
                    for a in range(1, d):
                        k = cnt[a]
                        for i in range(m):
                            H[i] += M[a, k, i]
                        for b in range(d):
                            if b != a:
                                for i in range(m):
                                    DP[b, i] *= W[a, k, i]
                        for i in range(m):
                            WP[i] *= W[a, k, i]
                    if basis == 0:
                        for i in range(m):
                            V[i] = hash_value(H[i])
                        for i in range(m):
                            T[0, i] += WP[i] * V[i]
                        for b in range(d):
                            for i in range(m):
                                T[1 + b, i] += DP[b, i] * V[i]
                    else:
                        for i in range(m):
                            g = hash_index(H[i], n, nmask)
                            v = 0.0
                            for a in range(d):
                                v += grads[g, a] * R[a, cnt[a], i]
                            T[0, i] += WP[i] * v
                            for b in range(d):
                                T[1 + b, i] += DP[b, i] * v + WP[i] * grads[g, b]
                    a = d - 1
                    while a >= 0:
                        cnt[a] += 1
                        if cnt[a] < taps:
                            break
                        cnt[a] = 0
                        a -= 1
                    if a < 0:
                        break
                amp = amps[o]
                for i in range(m):
                    tot = T[0, i]
                    sg = 1.0
                    if absval:
                        sg = 1.0 if tot > 0.0 else (-1.0 if tot < 0.0 else 0.0)
                        tot = abs(tot)
                    if o == 0:
                        ACC[c, 0, i] = amp * tot
                    else:
                        ACC[c, 0, i] += amp * tot
                    for b in range(d):
                        db = (amp * freqs[o, b]) * (sg * T[1 + b, i])
                        if o == 0:
                            ACC[c, 1 + b, i] = db
                        else:
                            ACC[c, 1 + b, i] += db
        for i in range(m):
            for c in range(ncomp):
                for q in range(d + 1):
                    out[p0 + i, c, q] = ACC[c, q, i]
