"""The lattice engine: every compiled kernel of lattice noise, in this one module.

numba's on-disk cache (``cache=True``) checks the source file a kernel is
defined in, so every kernel and every helper it calls live here: an edit
anywhere in this file recompiles them all, and nothing here depends on
compiled code elsewhere. There is no generated source and no hand-written
LLVM IR; every kernel runs as plain Python under ``NUMBA_DISABLE_JIT=1``
with the same values (``tests/test_lattice_engine.py``).

The point kernels are factories: closures over compile-time constants
(dimension, tap count, derivative flag, period flag, folded tables), which
numba folds before compiling and keys its cache by, so a first call
compiles the one variant it needs, with constant-trip loops that LLVM
unrolls.

- points: :func:`points_kernel` returns the kernel for a hash, dimension,
  tap count, derivative flag and period flag: :func:`_make_points` (the
  table hash: Phillips' nested permutation ``h_{a+1} = P[(h_a + j_a) mod n]``,
  2.4.1)
  and :func:`_make_int_points` (the integer hash, 256 points at a time, each
  level of the corner walk one loop over them); :func:`int_fast_kernel`
  (:func:`_make_int_fast`: the integer hash's 1-3-D values, the same bits,
  the last axis's taps unrolled in one loop over the points that LLVM
  vectorises); without a period of its own, :func:`int_two_taps_kernel`
  (:func:`_make_int_two_taps`: 2-tap kernels, every point's taps in
  registers) and :func:`int_block_kernel` (:func:`_make_int_block`: the
  others, block by block), both reading ``(N, d)`` rows or ``(d, N)``
  columns in place; :func:`table_block_kernel` (:func:`_make_table_block`:
  the table hash's 3-D values without a period over :func:`pair_tables`,
  block by block, either layout in place). Octaves are fused into one pass
  over the points.
- the separable grid passes: :func:`axis_dweights` (per-axis weight
  derivatives; the weights and distinct taps are numpy,
  :func:`.grid_path.octave_axis_taps`),
  :func:`hash_expand` / :func:`hash_expand_values` / :func:`block_prefix`
  (the hashed block of lattice values), :func:`contract_last` /
  :func:`contract_mid` (one pass per axis) and :func:`final_pass` /
  :func:`final_pass_direct` (the last pass, fused over octaves), for any
  dimension and either hash.
- 2-D and 3-D grids: :func:`grid_rows_kernel` (:func:`_make_grid_rows`), the
  same sums in one pass over the output's rows, every octave at once, each
  keeping a ring of its last ``taps`` contracted lattice rows; made per
  dimension, tap count (2, 4, or any), hash and basis.

Every tap weight is :func:`_weight` of the kernel's coefficients (data from
:mod:`.kernels`), written once. All arithmetic is float64; only the final
store may round to float32.
"""
from __future__ import annotations

import numba as nb
import numpy as np

# Beyond 2**52 a float64 has no fractional bits; beyond 2**62 it no longer
# fits an int64. Lattice indices are reduced modulo the period with fmod
# (exact for floats) before any conversion to int64.
_INT_SAFE = 4.0e15
# the integer hash (its definition: :mod:`._inthash`)
CHUNK = 256  # points per block of the integer hash's kernel
PERIOD_MAX = 1 << 32  # lattice coordinates are hashed as 32-bit words
_TO_UNIT = 1.0 / 2147483648.0  # 2**-31: int32 range onto [-1, 1)
_U32 = np.uint32
_U64 = np.uint64
_M1 = np.uint32(0x85EBCA6B)
_M2 = np.uint32(0xC2B2AE35)
_S16 = np.uint32(16)
_S13 = np.uint32(13)
_S32 = np.uint64(32)


@nb.njit(cache=True, nogil=True, inline="always")
def _reduce(fi, left, period, mask):
    """(fi - left) mod period for a float lattice index ``fi``, exact for any finite ``fi``.

    ``mask`` is ``period - 1`` when the period is a power of two (a bit mask
    then replaces the modulo), else -1. Past 2**52 (no fractional bits left)
    Python's float modulo, which is exact, reduces first.
    """
    if fi < _INT_SAFE and fi > -_INT_SAFE:
        i = np.int64(fi) - left
        if mask >= 0:
            return i & mask
        b = i % period
    else:
        b = np.int64(fi % float(period)) - left
        if mask >= 0:
            return b & mask
        b = b % period
    if b < 0:
        b += period
    return b


@nb.njit(cache=True, nogil=True, inline="always")
def _wrap(j, period, mask):
    """j mod period for 0 <= j < period + taps."""
    if mask >= 0:
        return j & mask
    if j >= period:
        j -= period
        if j >= period:
            j = j % period
    return j


@nb.njit(cache=True, nogil=True, inline="always")
def _hash(h, j, n, nmask):
    s = h + j
    if nmask >= 0:
        return s & nmask
    if s >= n:
        s -= n
        if s >= n:
            s = s % n
    return s


@nb.njit(cache=True, nogil=True)
def _next_corner(cnt, taps):
    """Advance the odometer ``cnt`` over the ``taps**d`` corners (last axis fastest).

    Returns the first axis whose tap changed (the levels from there on are
    recomputed), or -1 after the last corner.
    """
    a = cnt.shape[0] - 1
    while a >= 0:
        cnt[a] += 1
        if cnt[a] < taps:
            return a
        cnt[a] = 0
        a -= 1
    return -1


@nb.njit(cache=True, nogil=True, inline="always")
def _powers(t):
    """``t**2 .. t**5`` as :func:`_weight` takes them: independent products instead of a serial Horner chain."""
    t2 = t * t
    t3 = t2 * t
    t4 = t2 * t2
    return t2, t3, t4, t4 * t


@nb.njit(cache=True, nogil=True, inline="always")
def _weight(coef, k, t, t2, t3, t4, t5):
    """Tap ``k``'s weight at fraction ``t``: ``sum_p coef[k, p] t**p`` (``t2 .. t5`` its powers).

    The one place a weight polynomial is evaluated (points, grids, both
    hashes), so every path rounds alike. Summed from the powers in pairs
    rather than by Horner's rule: independent products, a shorter chain.
    """
    return (coef[k, 0] + coef[k, 1] * t) + (coef[k, 2] * t2 + coef[k, 3] * t3) + (coef[k, 4] * t4 + coef[k, 5] * t5)


@nb.njit(cache=True, nogil=True, inline="always")
def _dweight(dcoef, k, t, t2, t3, t4):
    """The derivative of :func:`_weight` (``dcoef``: :attr:`.kernels.Kernel.dcoef`)."""
    return (dcoef[k, 0] + dcoef[k, 1] * t) + (dcoef[k, 2] * t2 + dcoef[k, 3] * t3) + dcoef[k, 4] * t4


# ---------------------------------------------------------------- the integer hash
@nb.njit(cache=True, nogil=True, inline="always")
def mix32(h):
    """MurmurHash3's fmix32 less its last xor-shift (a bijection of uint32).

    Every step is truncated to 32 bits: numba widens uint32 arithmetic to 64
    bits, and the truncations let LLVM keep 32-bit lanes.
    """
    h = _U32(h ^ (h >> _S16))
    h = _U32(h * _M1)
    h = _U32(h ^ (h >> _S13))
    return _U32(h * _M2)


@nb.njit(cache=True, nogil=True, inline="always")
def hash_value(h, ft=np.float64):
    """The lattice value of a prefix word: ``int32(mix32(h)) / 2**31`` in [-1, 1) (in ``ft``: float32 rounds it)."""
    return ft(np.int32(mix32(h))) * ft(_TO_UNIT)


@nb.njit(cache=True, nogil=True, inline="always")
def hash_index(h, n):
    """The gradient index of a prefix word: ``(mix32(h) * n) >> 32`` (the top bits; ``h >> 28`` for n = 16)."""
    return np.int64((np.uint64(mix32(h)) * np.uint64(n)) >> _S32)


@nb.njit(cache=True, nogil=True, inline="always")
def prime(j, mult):
    """An axis's share of the prefix word: ``(j * M_a) mod 2**32`` for an index ``j`` (reduced or not: mod 2**32)."""
    return _U32(_U32(j) * mult)


def _make_points(DIM, TAPS, DERIV, PERIODIC):
    """The table hash's point kernel for ``DIM`` input axes and ``TAPS`` taps (compile-time constants).

    ``DERIV``: values and Jacobians (else values). ``PERIODIC`` False: every
    axis's period is the table size n, so a tap's index needs no reduction of
    its own (the hash reduces ``h + j`` modulo n, and n is even, so the
    parity is the same). numba prunes the branches these constants rule out
    before typing; numbers and booleans are safe in numba's cache key (pickled
    with the closure), a function closed over is not (it pickles with a new id in every process).
    """

    @nb.njit(cache=True, nogil=True)
    def eval_points(pts, out, freqs, amps, phase, shift, left, taps, coef, dcoef, period, pmask,
                    perms, values, grads, basis, absval, buffers):
        """Evaluate (fractal sums of) lattice noise, and with ``DERIV`` its Jacobian, at scattered points.

        Parameters
        ----------
        pts : (N, d) float64
        out : written (not accumulated): (N, C) float32 or float64, the
            values; with ``DERIV`` (N, C, d + 1) float64, ``out[p, c, 0]`` the
            value and ``out[p, c, 1 + a]`` its derivative along input axis
            ``a`` in input units
        freqs : (O, d) float64, per-octave per-axis frequency
        amps : (O,) float64, per-octave amplitude (including range normalisation)
        phase : (d,) float64
        shift, left, taps, coef : the kernel (see ``kernels.Kernel``)
        dcoef : the tap polynomials' derivatives (``dcoef[k, p] = (p + 1)
            coef[k, p + 1]``; read only with ``DERIV``)
        period : (d,) int64, lattice period per axis
        pmask : (d,) int64, period - 1 for powers of two, else -1
        perms : (C, n) int64, one permutation per output component
        values : (2, n) float64, value table by lattice parity (both rows equal
            unless the sign alternates with the lattice position)
        grads : (n, d) float64 unit gradients (gradient basis only)
        basis : 0 value noise, 1 gradient noise
        absval : sum |octave| (turbulence) instead of octave
        buffers : the working arrays, :func:`point_buffers`

        ``taps`` is ignored (``TAPS`` is compiled in). Dimensions 1 to 3 have
        nested neighbour loops of constant trip count (LLVM unrolls them);
        higher dimensions walk the ``taps**d`` neighbours with an odometer
        that re-hashes only the levels whose tap changed.

        The derivative: a tensor-product term ``prod_a w_a(t_a) v``
        differentiates one factor at a time: along axis ``b`` it is
        ``w_b'(t_b) prod_{a != b} w_a v``, plus, in the gradient basis
        (``v = g . r`` with ``dr_a / dt_b = [a == b]``), ``prod_a w_a g_b``.
        ``t_a = F_a x_a + phi_a + shift - floor(...)``, so ``d/dx_a = F_a
        d/dt_a``. Turbulence's ``|n|`` differentiates to ``sign(n) n'`` (0
        where ``n == 0``: the crease has no derivative there). The values are
        the same sums with or without ``DERIV``.
        """
        npts = pts.shape[0]
        d = DIM
        ncomp = perms.shape[0]
        n = perms.shape[1]
        nmask = n - 1 if (n & (n - 1)) == 0 else -1
        noct = freqs.shape[0]
        nq = d + 1 if DERIV else 1  # the value, then (DERIV) one derivative per axis
        w, r, jj, cnt, hs, par, prod, dw, dprod, D, acc = buffers  # (acc zeroed per point)
        vals0 = values[0]
        vals1 = values[1]
        for p in range(npts):
            for c in range(ncomp):
                for q in range(nq):
                    acc[c, q] = 0.0
            for o in range(noct):
                for a in range(d):
                    u = pts[p, a] * freqs[o, a] + phase[a] + shift
                    fi = np.floor(u)
                    t = u - fi
                    per = period[a]
                    msk = pmask[a]
                    b = _reduce(fi, left, per, msk)
                    t2, t3, t4, t5 = _powers(t)
                    for k in range(TAPS):
                        w[a, k] = _weight(coef, k, t, t2, t3, t4, t5)
                        if DERIV:
                            dw[a, k] = _dweight(dcoef, k, t, t2, t3, t4)
                        r[a, k] = t - shift + (left - k)
                        jj[a, k] = _wrap(b + k, per, msk) if PERIODIC else b + k
                for c in range(ncomp):
                    perm = perms[c]
                    total = 0.0
                    if DERIV:
                        for a in range(d):
                            D[a] = 0.0
                    # d <= 3: per level the partial value s (and with DERIV: the derivative along
                    # this level's axis, sNdN, and along the axes above it, eN.., summed likewise)
                    if DIM == 1:
                        for k0 in range(TAPS):
                            j0 = jj[0, k0]
                            h = perm[_hash(0, j0, n, nmask)]
                            if basis == 0:
                                v = vals0[h] if (j0 & 1) == 0 else vals1[h]
                                if DERIV:
                                    D[0] += dw[0, k0] * v
                            else:
                                v = grads[h, 0] * r[0, k0]
                                if DERIV:
                                    D[0] += dw[0, k0] * v + w[0, k0] * grads[h, 0]
                            total += w[0, k0] * v
                    elif DIM == 2:
                        for k0 in range(TAPS):
                            j0 = jj[0, k0]
                            h1 = perm[_hash(0, j0, n, nmask)]
                            s1 = 0.0
                            s1d1 = 0.0
                            e0 = 0.0
                            for k1 in range(TAPS):
                                j1 = jj[1, k1]
                                h = perm[_hash(h1, j1, n, nmask)]
                                if basis == 0:
                                    v = vals0[h] if ((j0 + j1) & 1) == 0 else vals1[h]
                                    if DERIV:
                                        s1d1 += dw[1, k1] * v
                                else:
                                    v = grads[h, 0] * r[0, k0] + grads[h, 1] * r[1, k1]
                                    if DERIV:
                                        s1d1 += dw[1, k1] * v + w[1, k1] * grads[h, 1]
                                        e0 += w[1, k1] * grads[h, 0]
                                s1 += w[1, k1] * v
                            total += w[0, k0] * s1
                            if DERIV:
                                D[0] += dw[0, k0] * s1 + w[0, k0] * e0
                                D[1] += w[0, k0] * s1d1
                    elif DIM == 3:
                        for k0 in range(TAPS):
                            j0 = jj[0, k0]
                            h1 = perm[_hash(0, j0, n, nmask)]
                            s1 = 0.0
                            s1d1 = 0.0
                            s1d2 = 0.0
                            e10 = 0.0
                            for k1 in range(TAPS):
                                j1 = jj[1, k1]
                                h2 = perm[_hash(h1, j1, n, nmask)]
                                s2 = 0.0
                                s2d2 = 0.0
                                e20 = 0.0
                                e21 = 0.0
                                for k2 in range(TAPS):
                                    j2 = jj[2, k2]
                                    h = perm[_hash(h2, j2, n, nmask)]
                                    if basis == 0:
                                        v = vals0[h] if ((j0 + j1 + j2) & 1) == 0 else vals1[h]
                                        if DERIV:
                                            s2d2 += dw[2, k2] * v
                                    else:
                                        v = grads[h, 0] * r[0, k0] + grads[h, 1] * r[1, k1] + grads[h, 2] * r[2, k2]
                                        if DERIV:
                                            s2d2 += dw[2, k2] * v + w[2, k2] * grads[h, 2]
                                            e20 += w[2, k2] * grads[h, 0]
                                            e21 += w[2, k2] * grads[h, 1]
                                    s2 += w[2, k2] * v
                                s1 += w[1, k1] * s2
                                if DERIV:
                                    s1d1 += dw[1, k1] * s2 + w[1, k1] * e21
                                    s1d2 += w[1, k1] * s2d2
                                    e10 += w[1, k1] * e20
                            total += w[0, k0] * s1
                            if DERIV:
                                D[0] += dw[0, k0] * s1 + w[0, k0] * e10
                                D[1] += w[0, k0] * s1d1
                                D[2] += w[0, k0] * s1d2
                    else:
                        for a in range(d):
                            cnt[a] = 0
                        level = 0
                        while True:
                            for a in range(level, d):
                                kk = cnt[a]
                                j = jj[a, kk]
                                hs[a + 1] = perm[_hash(hs[a], j, n, nmask)]
                                par[a + 1] = par[a] + j
                                prod[a + 1] = prod[a] * w[a, kk]
                                if DERIV:  # the weight product with factor q differentiated
                                    for q in range(a):
                                        dprod[a + 1, q] = dprod[a, q] * w[a, kk]
                                    dprod[a + 1, a] = prod[a] * dw[a, kk]
                            h = hs[d]
                            if basis == 0:
                                v = vals0[h] if (par[d] & 1) == 0 else vals1[h]
                                if DERIV:
                                    for a in range(d):
                                        D[a] += dprod[d, a] * v
                            else:
                                v = 0.0
                                for a in range(d):
                                    v += grads[h, a] * r[a, cnt[a]]
                                if DERIV:
                                    for a in range(d):
                                        D[a] += dprod[d, a] * v + prod[d] * grads[h, a]
                            total += prod[d] * v
                            level = _next_corner(cnt, TAPS)
                            if level < 0:
                                break
                    amp = amps[o]
                    if absval:
                        acc[c, 0] += amp * abs(total)
                        if DERIV:
                            sgn = 1.0 if total > 0.0 else (-1.0 if total < 0.0 else 0.0)
                            for a in range(d):
                                acc[c, 1 + a] += (amp * freqs[o, a]) * (sgn * D[a])
                    else:
                        acc[c, 0] += amp * total
                        if DERIV:
                            for a in range(d):
                                acc[c, 1 + a] += (amp * freqs[o, a]) * D[a]
            for c in range(ncomp):
                if DERIV:
                    for q in range(nq):
                        out[p, c, q] = acc[c, q]
                else:
                    out[p, c] = acc[c, 0]

    return eval_points



@nb.njit(cache=True, nogil=True, inline="always")
def _axis_setup(pts, p0, m, a, f, ph, shift, left, taps, coef, dcoef, per, msk, mult_a, W, DW, R, M, jac,
                periodic):
    """Weights (and derivatives), signed distances and hashed tap offsets of one axis for a chunk."""
    for i in range(m):
        u = pts[p0 + i, a] * f + ph + shift  # same rounding as the grid path
        fi = np.floor(u)
        t = u - fi
        t2, t3, t4, t5 = _powers(t)
        for k in range(taps):
            W[a, k, i] = _weight(coef, k, t, t2, t3, t4, t5)
            R[a, k, i] = t - shift + (left - k)
            if jac:
                DW[a, k, i] = _dweight(dcoef, k, t, t2, t3, t4)
    for i in range(m):
        u = pts[p0 + i, a] * f + ph + shift
        b = _reduce(np.floor(u), left, per, msk)
        for k in range(taps):
            # without a period (2**32) the word's own wrap reduces the index: no reduction of its own
            M[a, k, i] = prime(_wrap(b + k, per, msk) if periodic else b + k, mult_a)


@nb.njit(cache=True, nogil=True, inline="always")
def _add_grad_derivs(T, DP, wp, grads, g, v, i, d):
    """``T[1 + b, i] += DP[b, i] v + wp g_b`` for every axis b: a gradient corner's derivative terms."""
    for b in range(d):
        T[1 + b, i] += DP[b, i] * v + wp * grads[g, b]


def _make_int_points(DIM, TAPS, DERIV, PERIODIC):
    """The integer hash's point kernel for ``DIM`` axes and ``TAPS`` taps (as :func:`_make_points`).

    ``PERIODIC`` False: every period is 2**32, which the 32-bit words reduce by themselves.
    """

    @nb.njit(cache=True, nogil=True)
    def int_points(pts, out, freqs, amps, phase, shift, left, taps, coef, dcoef, period, pmask,
                   keys, mult, grads, basis, absval):
        """Lattice noise with the integer hash (and with ``DERIV`` its Jacobian) at scattered points.

        Any dimension; octaves fused. ``pts`` (N, d) float64; ``out`` written:
        (N, C), or with ``DERIV`` (N, C, d + 1) float64 as the
        table hash's kernel (the value, then its derivative along each
        input axis); ``keys`` (C,) uint32 per component; ``mult`` (d,) uint32
        odd multipliers; ``grads`` (L, d) the gradient set
        (:func:`._inthash.gradient_set`). The other arguments are those of
        the table hash's kernel (:func:`_make_points`; ``dcoef`` is read only with ``DERIV``).

        Per chunk and octave: each axis's weights and hashed tap offsets
        ``M[a, k] = ((j + k) mod period) * M_a`` (uint32); then the corners in
        odometer order, the prefix words (xor) and weight products carried
        level by level, each level one vectorisable loop over the chunk. A
        corner's term ``prod_a w_a v`` differentiates along axis ``b`` to
        ``w_b' prod_{a != b} w_a v`` (plus, in the gradient basis, ``prod_a
        w_a g_b``); the product is formed per corner, ``w_0`` first and
        ``w_b'`` second (``DP``).
        """
        npts = pts.shape[0]
        d = DIM
        ncomp = keys.shape[0]
        n = grads.shape[0]
        noct = freqs.shape[0]
        nq = d + 1 if DERIV else 1  # the value, then (DERIV) one derivative per axis
        # its own arrays, of compile-time shapes: passed in, their strides unknown, 4-D values ran 0.83x
        W = np.empty((d, TAPS, CHUNK))
        if DERIV:
            DW = np.empty((d, TAPS, CHUNK))
            V = np.empty(CHUNK)  # the corner's values (value basis)
        else:
            DW = np.empty((1, 1, 1))  # not read
        R = np.empty((d, TAPS, CHUNK))
        M = np.empty((d, TAPS, CHUNK), np.uint32)
        HP = np.empty((d + 1, CHUNK), np.uint32)
        WP = np.empty((d + 1, CHUNK))
        DP = np.empty((d, CHUNK))
        T = np.empty((nq, CHUNK))
        ACC = np.empty((ncomp, nq, CHUNK))
        cnt = np.zeros(d, np.int64)
        for p0 in range(0, npts, CHUNK):
            m = min(CHUNK, npts - p0)
            for o in range(noct):
                for a in range(d):
                    _axis_setup(pts, p0, m, a, freqs[o, a], phase[a], shift, left, TAPS, coef, dcoef, period[a],
                                pmask[a], mult[a], W, DW, R, M, DERIV, PERIODIC)
                for c in range(ncomp):
                    key = keys[c]
                    for q in range(nq):
                        for i in range(m):
                            T[q, i] = 0.0
                    T0 = T[0]
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
                                    h1[i] = _U32(key ^ Ma[i])
                                    w1[i] = Wa[i]
                            else:
                                h0 = HP[a]
                                w0 = WP[a]
                                h1 = HP[a + 1]
                                w1 = WP[a + 1]
                                for i in range(m):
                                    h1[i] = _U32(h0[i] ^ Ma[i])
                                    w1[i] = w0[i] * Wa[i]
                        hd = HP[d]
                        wd = WP[d]
                        if DERIV:  # DP[b] = w_0 w_b' w_1 ... (w_0' w_1 ... for b = 0), the product skipping w_b
                            for b in range(d):
                                db = DP[b]
                                W0 = W[0, cnt[0]]
                                DWb = DW[b, cnt[b]]
                                for i in range(m):
                                    db[i] = DWb[i] if b == 0 else W0[i] * DWb[i]
                                for a in range(1, d):
                                    if a != b:
                                        Wa = W[a, cnt[a]]
                                        for i in range(m):
                                            db[i] *= Wa[i]
                        if basis == 0:
                            for i in range(m):
                                v = hash_value(hd[i])
                                if DERIV:
                                    V[i] = v
                                T0[i] += wd[i] * v
                            if DERIV:  # one loop per axis: each vectorises
                                for b in range(d):
                                    tb = T[1 + b]
                                    db = DP[b]
                                    for i in range(m):
                                        tb[i] += db[i] * V[i]
                        elif DIM == 1:
                            r0 = R[0, cnt[0]]
                            for i in range(m):
                                g = hash_index(hd[i], n)
                                v = grads[g, 0] * r0[i]
                                T0[i] += wd[i] * v
                                if DERIV:
                                    _add_grad_derivs(T, DP, wd[i], grads, g, v, i, d)
                        elif DIM == 2:
                            r0 = R[0, cnt[0]]
                            r1 = R[1, cnt[1]]
                            for i in range(m):
                                g = hash_index(hd[i], n)
                                v = grads[g, 0] * r0[i] + grads[g, 1] * r1[i]
                                T0[i] += wd[i] * v
                                if DERIV:
                                    _add_grad_derivs(T, DP, wd[i], grads, g, v, i, d)
                        elif DIM == 3:
                            r0 = R[0, cnt[0]]
                            r1 = R[1, cnt[1]]
                            r2 = R[2, cnt[2]]
                            for i in range(m):
                                g = hash_index(hd[i], n)
                                v = grads[g, 0] * r0[i] + grads[g, 1] * r1[i] + grads[g, 2] * r2[i]
                                T0[i] += wd[i] * v
                                if DERIV:
                                    _add_grad_derivs(T, DP, wd[i], grads, g, v, i, d)
                        else:
                            for i in range(m):
                                g = hash_index(hd[i], n)
                                v = 0.0
                                for a in range(d):
                                    v += grads[g, a] * R[a, cnt[a], i]
                                T0[i] += wd[i] * v
                                if DERIV:
                                    _add_grad_derivs(T, DP, wd[i], grads, g, v, i, d)
                        level = _next_corner(cnt, TAPS)
                        if level < 0:
                            break
                    amp = amps[o]
                    acc = ACC[c]
                    for i in range(m):
                        tot = T0[i]
                        v = abs(tot) if absval else tot
                        if o == 0:
                            acc[0, i] = amp * v
                        else:
                            acc[0, i] += amp * v
                        if DERIV:  # turbulence: the sign of the octave's value (0 at 0)
                            sg = (1.0 if tot > 0.0 else (-1.0 if tot < 0.0 else 0.0)) if absval else 1.0
                            for b in range(d):
                                db = (amp * freqs[o, b]) * (sg * T[1 + b, i])
                                if o == 0:
                                    acc[1 + b, i] = db
                                else:
                                    acc[1 + b, i] += db
            for i in range(m):
                for c in range(ncomp):
                    if DERIV:
                        for q in range(nq):
                            out[p0 + i, c, q] = ACC[c, q, i]
                    else:
                        out[p0 + i, c] = ACC[c, 0, i]

    return int_points


_S28 = np.uint32(28)
_S29 = np.uint32(29)
_S31 = np.uint32(31)
_SQ = 0.7071067811865476  # 1/sqrt 2, _inthash.INV_SQRT2


@nb.njit(cache=True, nogil=True, inline="always")
def _grad_dot(h, r0, r1, r2, DIM, ft=np.float64):
    """``g . r`` for the gradient :func:`hash_index` picks from the fixed 1-3-D set, by bit tests (no gather).

    The sets of :func:`._inthash.gradient_set`: 1-D ``{+1, -1}`` (bit 31 of
    ``mix32(h)``); 2-D the axes then the diagonals (bits 29-31: bit 29 flips
    x, bit 30 picks y or flips it); 3-D Perlin's 16 (bits 28-31). Each is
    the table kernel's ``g_0 r_0 + ... + g_{d-1} r_{d-1}`` less its zero
    terms: the same products (``+-s r``, ``+-r``) summed in a commutative
    pair, so the same value but possibly for the sign of a zero, which a sum
    of weighted corners started from +0 does not keep. The loop vectoriser
    declines table gathers on some machines; selects it takes. ``ft``: the
    arithmetic's type (the float32 kernels pass float32 distances).
    """
    sq = ft(_SQ)
    x = mix32(h)
    if DIM == 1:
        return -r0 if (x >> _S31) != 0 else r0
    if DIM == 2:
        i = x >> _S29
        if i < 4:
            a = r0 if i < 2 else r1
            return -a if (i & 1) != 0 else a
        sx = -sq if (i & 1) != 0 else sq
        sy = -sq if (i & 2) != 0 else sq
        return sx * r0 + sy * r1
    i = x >> _S28
    ru = r0 if i < 8 else r1
    rv = r1 if i < 4 else (r0 if (i == 12 or i == 14) else r2)
    su = -sq if (i & 1) != 0 else sq
    sv = -sq if (i & 2) != 0 else sq
    return su * ru + sv * rv


@nb.njit(cache=True, nogil=True, inline="always")
def _split(pts, p0, m, a, f, ph, shift, left, taps, coef, mult_a, W, R, M, U):
    """:func:`_axis_setup` without a period of its own and without derivatives, in loops that vectorise.

    The same values (the same operations in the same order); ``M[a, k] =
    (j + k) M_a`` mod 2**32, the word's own wrap the reduction. Returns False,
    having written nothing of use, where a coordinate is out of int64 range or
    not finite (``_axis_setup`` then reduces exactly).
    """
    ok = True
    for i in range(m):
        u = pts[p0 + i, a] * f + ph + shift
        U[i] = u
        ok &= (u < _INT_SAFE) & (u > -_INT_SAFE)
    if not ok:
        return False
    for i in range(m):
        u = U[i]
        fi = np.floor(u)
        t = u - fi
        t2, t3, t4, t5 = _powers(t)
        j = _U32(np.int64(fi) - left)
        for k in range(taps):
            W[a, k, i] = _weight(coef, k, t, t2, t3, t4, t5)
            R[a, k, i] = t - shift + (left - k)
            M[a, k, i] = _U32(_U32(j + _U32(k)) * mult_a)
    return True


def _make_int_fast(DIM, TAPS, GRAD, PERIODIC):
    """The integer hash's value kernel for 1-3-D without derivatives, vectorised across points.

    The same arguments and the same bits as :func:`_make_int_points` (``GRAD``:
    the gradient basis, compiled in, so ``basis`` is ignored; the gradient set
    is the fixed 1-3-D one, selected by bit tests: :func:`_grad_dot`). Per
    chunk and octave, the split: each axis's weights, signed distances and
    hashed tap offsets (:func:`_split`, or :func:`_axis_setup` with a period
    or out-of-range coordinates); then the corners: for each tap of the axes
    before the last, one loop over the chunk whose body is the last axis's
    taps (a constant-trip loop over the closure constant ``TAPS``, which LLVM
    unrolls into straight-line code), so that LLVM's loop vectoriser runs
    across points (32-bit lanes for the hash; few arrays, one stored). Each
    corner's term ``((w_0 w_1) w_2) v`` is added in odometer order from 0, as
    the general kernel does. 2.5-3.3x the general kernel for 1e6 3-D points
    (``benchmarks/bench_lattice_paths.md``).
    """

    @nb.njit(cache=True, nogil=True)
    def int_fast(pts, out, freqs, amps, phase, shift, left, taps, coef, dcoef, period, pmask,
                 keys, mult, grads, basis, absval):
        """Lattice noise with the integer hash at scattered points, 1-3-D values (as :func:`_make_int_points`)."""
        npts = pts.shape[0]
        ncomp = keys.shape[0]
        noct = freqs.shape[0]
        W = np.empty((DIM, TAPS, CHUNK))
        DW = np.empty((1, 1, 1))  # not read
        R = np.empty((DIM, TAPS, CHUNK))
        M = np.empty((DIM, TAPS, CHUNK), np.uint32)
        U = np.empty(CHUNK)
        T = np.empty(CHUNK)
        ACC = np.empty((ncomp, CHUNK))
        for p0 in range(0, npts, CHUNK):
            m = min(CHUNK, npts - p0)
            for o in range(noct):
                for a in range(DIM):
                    if PERIODIC or not _split(pts, p0, m, a, freqs[o, a], phase[a], shift, left, TAPS, coef, mult[a],
                                              W, R, M, U):
                        _axis_setup(pts, p0, m, a, freqs[o, a], phase[a], shift, left, TAPS, coef, dcoef, period[a],
                                    pmask[a], mult[a], W, DW, R, M, False, PERIODIC)
                amp = amps[o]
                first = o == 0
                for c in range(ncomp):
                    key = keys[c]
                    acc = ACC[c]
                    if DIM > 1:  # the taps of the axes before the last outside, the last axis's inside the loop over points
                        for i in range(m):
                            T[i] = 0.0
                        for k0 in range(TAPS):
                            for k1 in range(TAPS if DIM == 3 else 1):
                                L = DIM - 1  # the last axis
                                M0 = M[0, k0]
                                W0 = W[0, k0]
                                R0 = R[0, k0]
                                M1 = M[1, k1]  # (3-D only)
                                W1 = W[1, k1]
                                R1 = R[1, k1]
                                for i in range(m):
                                    if DIM == 3:
                                        h1 = _U32(_U32(key ^ M0[i]) ^ M1[i])
                                        w1 = W0[i] * W1[i]
                                    else:
                                        h1 = _U32(key ^ M0[i])
                                        w1 = W0[i]
                                    total = T[i]
                                    for k in range(TAPS):
                                        h = _U32(h1 ^ M[L, k, i])
                                        w = w1 * W[L, k, i]
                                        if not GRAD:
                                            v = hash_value(h)
                                        elif DIM == 3:
                                            v = _grad_dot(h, R0[i], R1[i], R[2, k, i], 3)
                                        else:
                                            v = _grad_dot(h, R0[i], R[1, k, i], 0.0, 2)
                                        total += w * v
                                    T[i] = total
                    for i in range(m):
                        if DIM > 1:
                            total = T[i]
                        else:
                            total = 0.0
                            for k in range(TAPS):
                                h = _U32(key ^ M[0, k, i])
                                v = _grad_dot(h, R[0, k, i], 0.0, 0.0, 1) if GRAD else hash_value(h)
                                total += W[0, k, i] * v
                        tv = abs(total) if absval else total
                        if first:
                            acc[i] = amp * tv
                        else:
                            acc[i] += amp * tv
            for i in range(m):
                for c in range(ncomp):
                    out[p0 + i, c] = ACC[c, i]

    return int_fast


BLOCK = 256  # points per block of :func:`_make_int_block` (its buffers, about 26 KiB for 3-D, stay in L1)
_TWO32 = 4294967296.0  # 2**32: lattice indices are hashed modulo 2**32
_INV_TWO32 = 1.0 / 4294967296.0
_TWO31 = np.float32(2147483648.0)  # 2**31: float32 lattice indices below it convert to int32 exactly


@nb.njit(cache=True, nogil=True, inline="always")
def _block_load(src, cols, p0, m, X, DIM):
    """The block's coordinates as rows ``X[a, :m]`` (float64, or the points' own dtype), from the ``(float64,
    float32)`` pair of :func:`points_pair`: ``N`` points as rows ``(N, DIM)`` or, with ``cols``, columns
    ``(DIM, N)``, raveled.

    Both dtypes' loads are compiled and one of them runs: a float32 call after
    a float64 one no longer compiles the kernel again (1.3-2.2 s each). Every index here
    is a loop counter from 0 over a slice of the block: an index computed as
    ``p0 + i`` (which numba must check for a negative value) kept LLVM from
    vectorising these loops (about 2.5 ms more on 1e6 3-D points). Rows are
    read at the compile-time stride ``DIM``.
    """
    src64, src32 = src
    if src32.shape[0] > 0:
        _load_rows(src32, src32.shape[0] // DIM, cols, p0, m, X, DIM)
    else:
        _load_rows(src64, src64.shape[0] // DIM, cols, p0, m, X, DIM)


@nb.njit(cache=True, nogil=True, inline="always")
def _load_rows(flat, n, cols, p0, m, X, DIM):
    """:func:`_block_load` from one raveled array of ``n`` points."""
    if cols:
        for a in range(DIM):
            xs = flat[a * n + p0:a * n + p0 + m]
            Xa = X[a]
            for i in range(m):
                Xa[i] = xs[i]
    else:
        xs = flat[p0 * DIM:(p0 + m) * DIM]
        for i in range(m):
            for a in range(DIM):
                X[a, i] = xs[i * DIM + a]


def points_pair(src):
    """C-contiguous points (rows or columns) as the block kernels take them: ``(float64 raveled, float32 raveled)``,
    the other dtype's empty (:func:`_block_load`)."""
    flat = src.reshape(-1)
    if flat.dtype == np.float64:
        return flat, np.empty(0, np.float32)
    return np.empty(0), flat


@nb.njit(cache=True, nogil=True, inline="always")
def _reach32(X, m, reach, DIM):
    """Whether every coordinate of a block of float32 points ``X`` has ``lo <= |x| < hi`` or is 0: then
    :func:`_tj` computes its fractions and indices in float32.

    ``reach`` holds the bits of ``lo`` and ``hi`` (uint32), compared with the
    bits of ``|x|`` (monotone in ``|x|``; NaN's above inf's), in two reductions
    that vectorise. For a call without phase or shift whose frequencies ``f``
    are powers of two (:func:`.points_path._run_block` sets ``hi = 2**31 / max
    f`` and ``lo = 2**-126 / min(f, 1)``; ``hi = 0`` for any other call): ``u
    = x f`` is then exact in float32 (no overflow, no underflow), so ``u -
    floor(u)`` rounds as :func:`_fraction`'s float64 difference rounded to
    float32 (the one rounding of the same exact value), and ``|u| < 2**31``:
    the int32 index is the index mod 2**32. Any other block takes :func:`_index32`.
    """
    hi, lo, top = _U32(0), _U32(0x7FFFFFFF), _U32(0x7FFFFFFF)
    for a in range(DIM):
        Xa = X[a].view(np.uint32)
        for i in range(m):
            b = _U32(Xa[i] & top)
            hi, lo = max(hi, b), min(lo, b if b != 0 else top)
    return hi < reach[1] and lo >= reach[0]


@nb.njit(cache=True, nogil=True, inline="always")
def _index32(X, a, m, f, ph, shift, left, TT, JJ):
    """Axis ``a`` of a block that :func:`_reach32` refuses: :func:`_fraction` in float64 for every point, into
    ``TT[a]`` (float32) and ``JJ[a]``; returns the count of NaN fractions."""
    bad = 0
    for i in range(m):
        TT[a, i], JJ[a, i] = _fraction(np.float64(X[a, i]), f, ph, shift, left, np.float32)
        bad += TT[a, i] != TT[a, i]  # a NaN fraction: x f + phase NaN or infinite (_run_block refuses it)
    return bad


@nb.njit(cache=True, nogil=True, inline="always")
def _tj(fast, X, TT, JJ, a, i, f, left):
    """Point ``i``'s ``(t, j)`` on axis ``a`` in the float32 arithmetic: in float32 from ``X`` where the block
    passed :func:`_reach32` (``fast``), else from :func:`_index32`'s ``TT``, ``JJ``. The same values either way."""
    if fast:
        u = X[a, i] * np.float32(f)
        fi = np.floor(u)
        return np.float32(u - fi), _U32(np.int64(np.int32(fi)) - left)
    return TT[a, i], JJ[a, i]


@nb.njit(cache=True, nogil=True, inline="always")
def _block_axis(X, a, m, f, ph, shift, left, coef, mult_a, W, R, M, TF, JJ, TAPS, GRAD, F32, fast, ft):
    """One axis of a block without a period: weights, hashed tap offsets and (``GRAD``) signed distances.

    The values of :func:`_split` for every finite coordinate, in one branch-free
    loop: the lattice index enters the hash only modulo 2**32 (the word's own
    wrap), so it is reduced in float64 first, ``q = fi - floor(fi 2**-32) 2**32``
    (exact: every step is an integer or a power-of-two scaling, and the
    difference, an integer in [0, 2**32), is representable), and converted
    once, whatever the coordinate's size; no int64 overflow past 2**63 and no
    fallback to the exact per-point reduction. The float32 arithmetic (``F32``,
    ``ft`` float32) takes ``t`` and ``j`` from :func:`_tj` instead.
    """
    Xa = X[a]
    Ta = TF[a]
    bad = 0
    for i in range(m):
        if F32:  # (a NaN fraction: counted by :func:`_index32`)
            t, j = _tj(fast, X, TF, JJ, a, i, f, left)
        else:  # (the same rounding as the grid path)
            t, j = _fraction(Xa[i], f, ph, shift, left, ft)
            bad += t != t  # a NaN fraction (x f + phase NaN or infinite): counted, the points checked after the call
        Ta[i] = t
        t2, t3, t4, t5 = _powers(t)
        for k in range(TAPS):
            W[a, k, i] = _weight(coef, k, t, t2, t3, t4, t5)
            M[a, k, i] = _U32(_U32(j + _U32(k)) * mult_a)
    if GRAD:
        for k in range(TAPS):
            Rk = R[a, k]
            for i in range(m):
                Rk[i] = Ta[i] - ft(shift) + ft(left - k)
    return bad


@nb.njit(cache=True, nogil=True, inline="always")
def _store_block(out, p0, m, ACC):
    """A block's sums ``ACC[c, :m]`` into rows ``p0 .. p0 + m`` of the output (rounded once if it is float32).

    ``out``: :func:`out_pair`'s ``(float64 rows, float32 rows)``, one of them
    empty. Inlined by numba: a separate compiled function would be one more
    specialisation to compile on a first call (about 0.3 s CPU cold,
    ``benchmarks/bench_coldstart.md``). Every index from 0 (:func:`_block_load`).
    """
    out64, out32 = out
    ob, ob32 = out64[p0:p0 + m], out32[p0:p0 + m]
    for c in range(ACC.shape[0]):
        Ac = ACC[c]
        if out64.shape[0] > 0:
            for i in range(m):
                ob[i, c] = Ac[i]
        else:
            for i in range(m):
                ob32[i, c] = Ac[i]


def out_pair(out):
    """An output array as the block kernels take it: ``(float64 rows, float32 rows)``, the other dtype's empty.

    One compiled specialisation then writes either dtype (a float32 call
    after a float64 one used to compile the kernel again, 1.5-2 s).
    """
    if out.dtype == np.float64:
        return out, np.empty((0, out.shape[1]), np.float32)
    return np.empty((0, out.shape[1])), out


def _make_int_block(DIM, TAPS, GRAD, F32=False, X32=False):
    """The integer hash's 1-3-D value kernel without a period, block by block, reading either layout in place.

    The bits of :func:`_make_int_fast` (the same operations in the same order
    for every point) with its own arguments: ``(src, cols, lo, hi, out, freqs,
    amps, phase, shift, left, coef, keys, mult, absval, reach)``, where
    ``src`` holds C-contiguous ``(N, DIM)`` rows or, with ``cols``, ``(DIM, N)``
    columns (float32 or float64, widened as read: :func:`points_pair`), and the kernel fills ``out[lo:hi]``
    (so threads share one call's arrays without slicing the columns). Per
    block of :data:`BLOCK` points: the coordinates (:func:`_block_load`),
    each axis's set-up (:func:`_block_axis`), then :func:`_make_int_fast`'s
    corner loops; every loop runs over the block from index 0, which LLVM
    vectorises across points (8 float64 lanes with AVX-512). ``F32``: float32
    arithmetic from each fraction on (``coef`` float32), the block kept in the
    points' dtype (``X32``: float32 points), each point's index from :func:`_tj` (``reach``: the
    bits of :func:`_reach32`'s ``(lo, hi)``; ignored without ``F32``).
    """
    FT = np.float32 if F32 else np.float64
    UNIT = FT(1.0 if F32 else _TO_UNIT)  # the float32 arithmetic's 2**-31 joins the amplitude (:func:`_lerp_corners`)

    @nb.njit(cache=True, nogil=True)
    def int_block(src, cols, lo, hi, out, freqs, amps, phase, shift, left, coef, keys, mult, absval, reach):
        """Lattice noise with the integer hash at scattered points, 1-3-D values without a period."""
        ncomp = keys.shape[0]
        noct = freqs.shape[0]
        # arrays of compile-time shapes (passed in, their strides unknown, the cubic kernel ran 0.60x on 1e6 3-D
        # points); the block kept in the points' dtype with F32 (X32: float32 points)
        X = np.empty((DIM, BLOCK), np.float32 if F32 and X32 else np.float64)
        TF, JJ = np.empty((DIM, BLOCK), FT), np.empty((DIM, BLOCK) if F32 else (1, 1), np.uint32)
        W = np.empty((DIM, TAPS, BLOCK), FT)
        R = np.empty((DIM, TAPS, BLOCK), FT)  # (read by value noise too, unused: plain Python's indices stay in range)
        M = np.empty((DIM, TAPS, BLOCK), np.uint32)
        T = np.empty(BLOCK, FT)
        ACC = np.empty((ncomp, BLOCK), FT)
        bad = 0
        for p0 in range(lo, hi, BLOCK):
            m = min(BLOCK, hi - p0)
            _block_load(src, cols, p0, m, X, DIM)
            fast = F32 and _reach32(X, m, reach, DIM)
            for o in range(noct):
                for a in range(DIM):
                    if F32 and not fast:
                        bad += _index32(X, a, m, freqs[o, a], phase[a], shift, left, TF, JJ)
                    bad += _block_axis(X, a, m, freqs[o, a], phase[a], shift, left, coef, mult[a], W, R, M, TF, JJ,
                                       TAPS, GRAD, F32, fast, FT)
                amp = FT(amps[o]) * FT(_TO_UNIT if F32 and not GRAD else 1.0)
                first = o == 0
                for c in range(ncomp):
                    key = keys[c]
                    acc = ACC[c]
                    if DIM > 1:  # as :func:`_make_int_fast`: the last axis's taps inside the loop over points
                        T[:m] = 0.0
                        for k0 in range(TAPS):
                            for k1 in range(TAPS if DIM == 3 else 1):
                                M0, W0, R0 = M[0, k0], W[0, k0], R[0, k0]
                                M1, W1, R1 = M[1, k1], W[1, k1], R[1, k1]  # (3-D only)
                                for i in range(m):
                                    h1 = _U32(_U32(key ^ M0[i]) ^ M1[i]) if DIM == 3 else _U32(key ^ M0[i])
                                    w1 = W0[i] * W1[i] if DIM == 3 else W0[i]
                                    total = T[i]
                                    for k in range(TAPS):
                                        h = _U32(h1 ^ M[DIM - 1, k, i])
                                        w = w1 * W[DIM - 1, k, i]
                                        # (branches on GRAD and DIM themselves: numba compiles only the one taken)
                                        v = (_grad_dot(h, R0[i], R1[i] if DIM == 3 else R[1, k, i],
                                                       R[2, k, i] if DIM == 3 else FT(0.0), DIM, FT) if GRAD
                                             else FT(np.int32(mix32(h))) * UNIT)
                                        total += w * v
                                    T[i] = total
                    for i in range(m):
                        if DIM > 1:
                            total = T[i]
                        else:
                            total = FT(0.0)
                            for k in range(TAPS):
                                h = _U32(key ^ M[0, k, i])
                                v = (_grad_dot(h, R[0, k, i], FT(0.0), FT(0.0), 1, FT) if GRAD
                                     else FT(np.int32(mix32(h))) * UNIT)
                                total += W[0, k, i] * v
                        tv = abs(total) if absval else total
                        acc[i] = amp * tv if first else acc[i] + amp * tv
            _store_block(out, p0, m, ACC)
        return bad

    return int_block


@nb.njit(cache=True, nogil=True, inline="always")
def _fraction(x, f, ph, shift, left, ft):
    """One axis of one point: its fraction ``t`` (in ``ft``) and its first tap's index ``j`` (exact, mod 2**32)."""
    u = x * f + ph + shift  # same rounding as the grid path
    fi = np.floor(u)
    q = fi - np.floor(fi * _INV_TWO32) * _TWO32  # fi mod 2**32, exactly (:func:`_block_axis`)
    return ft(u - fi), _U32(np.int64(q) - left)


@nb.njit(cache=True, nogil=True)
def _two_taps(t, j, shift, left, coef, mult_a, grad, ft):
    """One axis of one point for a 2-tap kernel (``t, j``: :func:`_fraction`): ``(w0, w1, m0, m1, r0, r1)``
    as :func:`_block_axis` makes them.

    A plain compiled function, not inlined by numba: LLVM inlines it into the
    kernel with ``grad`` known, and numba compiles its body once instead of
    once per call site (inlined at numba's level, :func:`_make_int_two_taps`
    took 6.6 s to compile instead of 2.0 s). ``ft``: the arithmetic's type.
    """
    t2, t3, t4, t5 = _powers(t)
    w0 = _weight(coef, 0, t, t2, t3, t4, t5)
    w1 = _weight(coef, 1, t, t2, t3, t4, t5)
    m0 = _U32(_U32(j + _U32(0)) * mult_a)
    m1 = _U32(_U32(j + _U32(1)) * mult_a)
    r0, r1 = (t - ft(shift) + ft(left - 0), t - ft(shift) + ft(left - 1)) if grad else (ft(0.0), ft(0.0))
    return w0, w1, m0, m1, r0, r1


@nb.njit(cache=True, nogil=True)
def _two_corners(total, h1, w1, c0, c1, n0, n1, ra, rb, s0, s1, dim, grad, ft):
    """``total`` plus the last axis's two corners: ``(w1 c_k) v(h1 ^ n_k)`` for k = 0, 1, in that order.

    ``v`` is :func:`hash_value` or (``grad``) :func:`_grad_dot` of the
    signed distances ``ra``, ``rb`` (the axes before the last) and ``s_k``
    (the last axis's), as :func:`_make_int_fast` forms them for ``dim``.
    """
    for k in range(2):
        v = _corner(_U32(h1 ^ (n0 if k == 0 else n1)), ra, rb, s0 if k == 0 else s1, dim, grad, ft, ft(_TO_UNIT))
        total += (w1 * (c0 if k == 0 else c1)) * v
    return total


@nb.njit(cache=True, nogil=True, inline="always")
def _corner(h, ra, rb, s, dim, grad, ft, unit):
    """A corner's value: :func:`hash_value` of ``h`` (its ``2**-31`` replaced by ``unit``) or (``grad``)
    :func:`_grad_dot` of ``ra, rb, s`` for ``dim``."""
    if not grad:
        return ft(np.int32(mix32(h))) * unit
    if dim == 3:
        return _grad_dot(h, ra, rb, s, 3, ft)
    if dim == 2:
        return _grad_dot(h, ra, s, ft(0.0), 2, ft)
    return _grad_dot(h, s, ft(0.0), ft(0.0), 1, ft)


@nb.njit(cache=True, nogil=True)
def _lerp_taps(t, j, shift, left, coef, mult_a, grad):
    """:func:`_two_taps` for the float32 arithmetic: ``(w1, m0, m1, r0, r1)``, ``w1`` the second tap's weight by
    Horner's rule from its power-basis coefficients ``coef[1]`` (float32), its partner ``1 - w1`` left to
    :func:`_lerp_corners` (LLVM drops the power-basis weights :func:`_two_taps` computes, unused)."""
    w = coef[1, 5]
    for p in range(4, -1, -1):
        w = w * t + coef[1, p]
    r0 = t - np.float32(shift) + np.float32(left) if grad else np.float32(0.0)
    r1 = t - np.float32(shift) + np.float32(left - 1) if grad else np.float32(0.0)
    return w, _U32(j * mult_a), _U32(_U32(j + _U32(1)) * mult_a), r0, r1


@nb.njit(cache=True, nogil=True)
def _lerp_corners(h1, w, n0, n1, ra, rb, s0, s1, dim, grad):
    """The last axis's two corners (as :func:`_two_corners`) blended in float32: ``v0 + w (v1 - v0)``.

    Value noise blends ``int32(mix32(h))`` unscaled: its ``2**-31`` (:func:`hash_value`) joins the amplitude,
    once a point (exact, as a power of two) instead of once a corner."""
    v0 = _corner(_U32(h1 ^ n0), ra, rb, s0, dim, grad, np.float32, np.float32(1.0))
    return v0 + w * (_corner(_U32(h1 ^ n1), ra, rb, s1, dim, grad, np.float32, np.float32(1.0)) - v0)


def _make_int_two_taps(DIM, GRAD, F32=False, X32=False):
    """The integer hash's 1-3-D values without a period for 2-tap kernels (quintic, linear), point by point.

    The arguments and bits of :func:`_make_int_block`; instead of each axis's
    weights and offsets in arrays, every point's are computed in registers
    (:func:`_two_taps`) and its 2**DIM corners summed at once
    (:func:`_two_corners`, in :func:`_make_int_fast`'s order and products),
    in one loop over the block that LLVM vectorises across points.
    1.63-1.74x :func:`_make_int_fast` for 1e6 3-D float32 quintic value
    points (``benchmarks/bench_lattice_paths.md``). ``F32``: float32 arithmetic
    from each fraction on, the index as :func:`_make_int_block`'s, for kernels
    that are a partition of unity (``w0 = 1 - w1``): ``coef`` is the second
    tap's coefficients alone (:func:`_lerp_taps`) and the corners are blended
    as nested lerps, the last axis first (:func:`_lerp_corners`).
    """
    FT = np.float32 if F32 else np.float64
    Z = FT(0.0)
    B = 1 if DIM > 1 else 0  # the second and third axes' rows (the first's where there is none)
    C = 2 if DIM > 2 else 0

    @nb.njit(cache=True, nogil=True)
    def int_two_taps(src, cols, lo, hi, out, freqs, amps, phase, shift, left, coef, keys, mult, absval, reach):
        """Lattice noise with the integer hash at scattered points, 1-3-D values of a 2-tap kernel."""
        ncomp = keys.shape[0]
        noct = freqs.shape[0]
        X = np.empty((DIM, BLOCK), np.float32 if F32 and X32 else np.float64)  # (as :func:`_make_int_block`)
        TT, JJ = np.empty((DIM, BLOCK) if F32 else (1, 1), FT), np.empty((DIM, BLOCK) if F32 else (1, 1), np.uint32)
        ACC = np.empty((ncomp, BLOCK), FT)
        bad = 0
        for p0 in range(lo, hi, BLOCK):
            m = min(BLOCK, hi - p0)
            _block_load(src, cols, p0, m, X, DIM)
            fast = F32 and _reach32(X, m, reach, DIM)
            for o in range(noct):
                amp = FT(amps[o]) * FT(_TO_UNIT if F32 and not GRAD else 1.0)  # (:func:`_lerp_corners`)
                first = o == 0
                if F32 and not fast:  # the exact float64 index in its own loop: the corner loop stays float32
                    for a in range(DIM):
                        bad += _index32(X, a, m, freqs[o, a], phase[a], shift, left, TT, JJ)
                fa, fb, fc = freqs[o, 0], freqs[o, B], freqs[o, C]
                for c in range(ncomp):
                    key = keys[c]
                    acc = ACC[c]
                    for i in range(m):
                        if F32:  # nested lerps, the last axis first
                            ta, ja = _tj(fast, X, TT, JJ, 0, i, fa, left)
                            a1, am0, am1, ar0, ar1 = _lerp_taps(ta, ja, shift, left, coef, mult[0], GRAD)
                            if DIM == 1:
                                total = _lerp_corners(key, a1, am0, am1, Z, Z, ar0, ar1, DIM, GRAD)
                            else:
                                tb, jb = _tj(fast, X, TT, JJ, B, i, fb, left)
                                b1, bm0, bm1, br0, br1 = _lerp_taps(tb, jb, shift, left, coef, mult[B], GRAD)
                                if DIM == 2:
                                    x0 = _lerp_corners(_U32(key ^ am0), b1, bm0, bm1, ar0, Z, br0, br1, DIM, GRAD)
                                    x1 = _lerp_corners(_U32(key ^ am1), b1, bm0, bm1, ar1, Z, br0, br1, DIM, GRAD)
                                else:
                                    tc, jc = _tj(fast, X, TT, JJ, C, i, fc, left)
                                    c1, cm0, cm1, cr0, cr1 = _lerp_taps(tc, jc, shift, left, coef, mult[C], GRAD)
                                    ha0, ha1 = _U32(key ^ am0), _U32(key ^ am1)
                                    y00 = _lerp_corners(_U32(ha0 ^ bm0), c1, cm0, cm1, ar0, br0, cr0, cr1, 3, GRAD)
                                    y01 = _lerp_corners(_U32(ha0 ^ bm1), c1, cm0, cm1, ar0, br1, cr0, cr1, 3, GRAD)
                                    y10 = _lerp_corners(_U32(ha1 ^ bm0), c1, cm0, cm1, ar1, br0, cr0, cr1, 3, GRAD)
                                    y11 = _lerp_corners(_U32(ha1 ^ bm1), c1, cm0, cm1, ar1, br1, cr0, cr1, 3, GRAD)
                                    x0, x1 = y00 + b1 * (y01 - y00), y10 + b1 * (y11 - y10)
                                total = x0 + a1 * (x1 - x0)
                        else:
                            ta, ja = _fraction(X[0, i], fa, phase[0], shift, left, FT)
                            bad += ta != ta
                            a0, a1, am0, am1, ar0, ar1 = _two_taps(ta, ja, shift, left, coef, mult[0], GRAD, FT)
                            if DIM == 1:  # (1.0 * w) v is w v exactly
                                total = _two_corners(Z, key, FT(1.0), a0, a1, am0, am1, Z, Z, ar0, ar1, DIM, GRAD, FT)
                            else:
                                tb, jb = _fraction(X[B, i], fb, phase[B], shift, left, FT)
                                bad += tb != tb
                                b0, b1, bm0, bm1, br0, br1 = _two_taps(tb, jb, shift, left, coef, mult[B], GRAD, FT)
                                if DIM == 2:
                                    total = _two_corners(Z, _U32(key ^ am0), a0, b0, b1, bm0, bm1, ar0, Z, br0, br1,
                                                         DIM, GRAD, FT)
                                    total = _two_corners(total, _U32(key ^ am1), a1, b0, b1, bm0, bm1, ar1, Z, br0,
                                                         br1, DIM, GRAD, FT)
                                else:
                                    tc, jc = _fraction(X[C, i], fc, phase[C], shift, left, FT)
                                    bad += tc != tc
                                    c0, c1, cm0, cm1, cr0, cr1 = _two_taps(tc, jc, shift, left, coef, mult[C], GRAD,
                                                                           FT)
                                    ha0 = _U32(key ^ am0)
                                    ha1 = _U32(key ^ am1)
                                    total = _two_corners(Z, _U32(ha0 ^ bm0), a0 * b0, c0, c1, cm0, cm1, ar0, br0, cr0,
                                                         cr1, DIM, GRAD, FT)
                                    total = _two_corners(total, _U32(ha0 ^ bm1), a0 * b1, c0, c1, cm0, cm1, ar0, br1,
                                                         cr0, cr1, DIM, GRAD, FT)
                                    total = _two_corners(total, _U32(ha1 ^ bm0), a1 * b0, c0, c1, cm0, cm1, ar1, br0,
                                                         cr0, cr1, DIM, GRAD, FT)
                                    total = _two_corners(total, _U32(ha1 ^ bm1), a1 * b1, c0, c1, cm0, cm1, ar1, br1,
                                                         cr0, cr1, DIM, GRAD, FT)
                        tv = abs(total) if absval else total
                        acc[i] = amp * tv if first else acc[i] + amp * tv
            _store_block(out, p0, m, ACC)
        return bad

    return int_two_taps



@nb.njit(cache=True, nogil=True, inline="always")
def _table_axis(x, m, f, ph, shift, left, coef, n, W, R, J, TAPS, GRAD):
    """One axis of a block for the table hash without a period: weights, (GRAD) signed distances, taps.

    For a table size n that is a power of two. The values of :func:`_make_points`' per-point set-up (the
    same operations in the same order), in one loop from index 0 (:func:`_block_load`) that LLVM vectorises:
    the first tap reduced in float64, ``fi - floor(fi / n) n`` (exact, as in :func:`_block_axis`; no branch
    for huge coordinates), then ``J[k]`` tap ``k`` modulo n.
    """
    inv = 1.0 / n
    bad = 0
    for i in range(m):
        u = x[i] * f + ph + shift  # same rounding as the grid path
        fi = np.floor(u)
        t = u - fi
        bad += t != t  # a NaN fraction (x f + phase NaN or infinite): counted, the points checked after the call
        j = (np.int64(fi - np.floor(fi * inv) * n) - left) & (n - 1)  # (any int64 of a NaN: masked in range)
        t2, t3, t4, t5 = _powers(t)
        for k in range(TAPS):
            J[k, i] = (j + k) & (n - 1)
            W[k, i] = _weight(coef, k, t, t2, t3, t4, t5)
            if GRAD:
                R[k, i] = t - shift + (left - k)
    return bad


def _make_table_block(TAPS, GRAD):
    """The table hash's 3-D values without a period or derivatives, block by block, reading either layout in place.

    The bits of :func:`_make_points` for ``DIM`` 3 (its corner sums in its nested order) with the arguments of
    :func:`_make_int_block` less the hash's: ``(src, cols, lo, hi, out, freqs, amps, phase, shift, left, coef,
    H2, TL, absval)``, ``H2`` and ``TL`` the folded tables of :func:`pair_tables` (values, or ``GRAD``
    gradients). Per block of :data:`BLOCK` points: the coordinates (:func:`_block_load`), each axis's set-up
    (:func:`_table_axis`, vectorised across points), then per point the corner sum from 4 (2 taps) or 16
    (4 taps) pair-table reads.
    """

    @nb.njit(cache=True, nogil=True)
    def table_block(src, cols, lo, hi, out, freqs, amps, phase, shift, left, coef, H2, TL, absval):
        """Lattice noise with the table hash at scattered 3-D points, values (as :func:`_make_points`)."""
        ncomp = H2.shape[0]
        noct = freqs.shape[0]
        n = (TL.shape[1] // 2 - 4) // 2  # the table size n, from the folded tables' run 2 (2n + 4)
        un = _U64(n)
        X = np.empty((3, BLOCK))
        W = np.empty((3, TAPS, BLOCK))
        R = np.empty((3, TAPS, BLOCK) if GRAD else (3, 1, 1))
        J = np.empty((3, TAPS, BLOCK), np.int64)
        ACC = np.empty((ncomp, BLOCK))
        bad = 0
        for p0 in range(lo, hi, BLOCK):
            m = min(BLOCK, hi - p0)
            _block_load(src, cols, p0, m, X, 3)
            for c in range(ncomp):
                for i in range(m):
                    ACC[c, i] = 0.0
            for o in range(noct):
                for a in range(3):
                    bad += _table_axis(X[a], m, freqs[o, a], phase[a], shift, left, coef, n, W[a], R[a], J[a], TAPS,
                                       GRAD)
                amp = amps[o]
                for c in range(ncomp):
                    H = H2[c]
                    V = TL[c]
                    acc = ACC[c]
                    for i in range(m):  # unsigned indices: no check for a negative one (:func:`_block_load`)
                        b2 = _U64(J[2, 0, i])
                        total = 0.0
                        for k0 in range(TAPS):
                            row = _U64(J[0, k0, i]) * un
                            s1 = 0.0
                            for k1 in range(TAPS):
                                hb = _U64(H[row + _U64(J[1, k1, i])]) + b2
                                s2 = 0.0
                                for k2 in range(TAPS):
                                    x = hb + _U64(k2)
                                    if GRAD:
                                        v = V[x, 0] * R[0, k0, i] + V[x, 1] * R[1, k1, i] + V[x, 2] * R[2, k2, i]
                                    else:
                                        v = V[x]
                                    s2 += W[2, k2, i] * v
                                s1 += W[1, k1, i] * s2
                            total += W[0, k0, i] * s1
                        acc[i] += amp * (abs(total) if absval else total)
            _store_block(out, p0, m, ACC)
        return bad

    return table_block


def point_buffers(dim, ncomp, deriv=False):
    """The working arrays of one call of the table hash's per-point kernel (:func:`_make_points`), its last argument.

    Each axis's weights, ramps and taps, the corner odometer, each level's
    hash, parity and weight product (with ``deriv`` the derivatives'
    products), a point's sums, with the zeros and ones the kernel starts
    from. Allocated by the caller: in the kernel, numba compiled its
    ``np.empty`` / ``np.zeros`` / ``np.ones`` for each shape and dtype on a
    first call, 0.5 s CPU of a first 2-D call and 1.2 s of a first Jacobian
    (``benchmarks/bench_coldstart.md``); these tiny arrays gain nothing from
    compile-time shapes (the same warm speed, ``benchmarks/bench_coldstart.md``).
    """
    d, nq = dim, dim + 1 if deriv else 1
    extra = (np.empty((d, 4)), np.zeros((d + 1, d)), np.zeros(d)) if deriv else \
        (np.empty((0, 4)), np.zeros((0, d)), np.zeros(0))
    return (np.empty((d, 4)), np.empty((d, 4)), np.empty((d, 4), np.int64), np.zeros(d, np.int64),
            np.zeros(d + 1, np.int64), np.zeros(d + 1, np.int64), np.ones(d + 1)) + extra + \
        (np.empty((ncomp, nq)),)


_POINTS = {}


def _variant(store, key, make, args):
    """The kernel ``make(*args)``, kept in ``store`` under ``key``: made on first request; numba compiles it on its
    first call (or loads it from its cache)."""
    fn = store.get(key)
    if fn is None:
        fn = store[key] = make(*args)
    return fn


def points_kernel(integer, dim, taps, deriv, periodic):
    """The compiled point kernel for this hash, dimension, tap count, derivative flag and period flag.

    Its arguments: ``(pts, out, freqs, amps, phase, shift, left, taps, coef,
    dcoef, period, pmask, perms, values, grads, basis, absval)`` for the table
    hash (:func:`_make_points`), ``(..., pmask, keys, mult, grads, basis,
    absval)`` for the integer hash (:func:`_make_int_points`). Made on first
    request; numba compiles it on its first call (or loads it from its cache).
    """
    key = (bool(integer), int(dim), int(taps), bool(deriv), bool(periodic))
    return _variant(_POINTS, key, _make_int_points if integer else _make_points, key[1:])


def int_fast_kernel(dim, taps, gradient, periodic):
    """The integer hash's vectorised value kernel (:func:`_make_int_fast`) for 1-3-D, as :func:`points_kernel`."""
    key = ("fast", int(dim), int(taps), bool(gradient), bool(periodic))
    return _variant(_POINTS, key, _make_int_fast, key[1:])


def table_block_kernel(taps, gradient):
    """The table hash's 3-D block kernel without a period (:func:`_make_table_block`), as :func:`points_kernel`."""
    key = ("table", int(taps), bool(gradient))
    return _variant(_POINTS, key, _make_table_block, key[1:])


def int_block_kernel(dim, taps, gradient, f32=False, x32=False):
    """The integer hash's block kernel (:func:`_make_int_block`) for 1-3-D values without a period.

    ``x32``: float32 points, which the float32 arithmetic keeps in float32 (one kernel for both dtypes without it).
    """
    key = ("block", int(dim), int(taps), bool(gradient), bool(f32), bool(f32 and x32))
    return _variant(_POINTS, key, _make_int_block, key[1:])


def int_two_taps_kernel(dim, gradient, f32=False, x32=False):
    """The integer hash's 2-tap kernel (:func:`_make_int_two_taps`) for 1-3-D values without a period (``x32``:
    as :func:`int_block_kernel`)."""
    key = ("two", int(dim), bool(gradient), bool(f32), bool(f32 and x32))
    return _variant(_POINTS, key, _make_int_two_taps, key[1:])


def fold_last_level(perm, values, grads, length):
    """The table hash's last level folded into its look-up, for ``x < length``: one read a lattice point.

    ``values[(r + x) & 1, P[x mod n]]`` for each parity ``r``, ``(2, length)``;
    with ``grads``, ``grads[P[x mod n]]``, ``(length, d)``. The fused grid
    kernel (:func:`.grid_path.folded_tables`) and the point block kernel
    (:func:`pair_tables`) read these.
    """
    x = np.arange(length)
    px = perm[x % perm.shape[0]]
    if grads is not None:
        return grads[px]
    return values[(np.arange(2)[:, None] + x) & 1, px]


def pair_tables(perms, values, grads=None):
    """The 3-D table-hash block kernel's folded tables ``(H2, TL)``, built from the live tables at each call.

    ``H2[c, q0 * n + q1] = P_c[(P_c[q0] + q1) mod n] + S ((q0 + q1 + h) & 1)``
    (two hash levels in one read, plus the parity row's offset);
    ``TL[c, r S + x] = values[(r + x) & 1, P_c[x mod n]]`` for ``x < S = 2n + 4``
    (the last level folded into the values, run on past 2n so that ``h + j``
    needs no reduction), or with ``grads`` the gradients ``grads[P_c[x mod n]]``
    (the same for both parities).
    """
    dim_out, n = perms.shape
    S = 2 * n + 4
    q = np.arange(n)
    H2 = np.empty((dim_out, n * n), dtype=np.uint16)
    TL = np.empty((dim_out, 2 * S) if grads is None else (dim_out, 2 * S, grads.shape[1]))
    for c in range(dim_out):
        P = perms[c]
        h = P[(P[q][:, None] + q[None, :]) % n]
        H2[c] = (h + S * ((q[:, None] + q[None, :] + h) & 1)).ravel()
        folded = fold_last_level(P, values, grads, S)
        TL[c] = folded.ravel() if grads is None else np.concatenate([folded, folded])  # (both parities alike)
    return H2, TL


# ---------------------------------------------------------------- grids
@nb.njit(cache=True, nogil=True)
def contract_mid(inp, pos, w, out):
    """One separable pass on a middle axis: ``out[p, j, q] = sum_k w[j, k] * inp[p, pos[j, k], q]``."""
    npre, _, npost = inp.shape
    nj, taps = w.shape
    for p in range(npre):
        for j in range(nj):
            o = out[p, j]
            r0 = inp[p, pos[j, 0]]
            w0 = w[j, 0]
            for q in range(npost):
                o[q] = w0 * r0[q]
            for k in range(1, taps):
                rk = inp[p, pos[j, k]]
                wk = w[j, k]
                for q in range(npost):
                    o[q] += wk * rk[q]


@nb.njit(cache=True, nogil=True)
def contract_last(inp, pos, w, out):
    """The separable pass on the last (contiguous) axis: ``out[p, j] = sum_k w[k, j] * inp[p, pos[k, j]]``.

    ``pos`` and ``w`` are ``(taps, N)``: one contiguous row per tap, so the
    loop over a row's samples reads them in order and LLVM vectorises it
    with gathers from the row (rows taken eight at a time, the samples
    outside, ran scalar). The taps are summed in order,
    ``((w_0 v_0 + w_1 v_1) + w_2 v_2) + ...``.
    """
    npre = inp.shape[0]
    taps, nj = w.shape
    for p in range(npre):
        r = inp[p]
        o = out[p]
        if taps == 2:
            a0 = pos[0]; a1 = pos[1]
            w0 = w[0]; w1 = w[1]
            for j in range(nj):
                o[j] = w0[j] * r[a0[j]] + w1[j] * r[a1[j]]
        elif taps == 4:
            a0 = pos[0]; a1 = pos[1]; a2 = pos[2]; a3 = pos[3]
            w0 = w[0]; w1 = w[1]; w2 = w[2]; w3 = w[3]
            for j in range(nj):
                o[j] = w0[j] * r[a0[j]] + w1[j] * r[a1[j]] + w2[j] * r[a2[j]] + w3[j] * r[a3[j]]
        else:
            for j in range(nj):
                s = w[0, j] * r[pos[0, j]]
                for k in range(1, taps):
                    s += w[k, j] * r[pos[k, j]]
                o[j] = s


@nb.njit(cache=True, nogil=True)
def hash_expand(h, par, lat, perm, n, first):
    """One level of the nested hash over a block: ``h'[m, l] = P[(h[m] + lat[l]) mod n]``, flattened.

    ``first``: the first level, ``h' = P[lat mod n]`` (``h`` is ignored).
    Also carries the lattice parity ``par'[m, l] = par[m] + lat[l]`` (low bit).
    """
    nl = lat.shape[0]
    m = 1 if first else h.shape[0]
    hn = np.empty(m * nl, np.int64)
    pn = np.empty(m * nl, np.int64)
    for i in range(m):
        hb = 0 if first else h[i]
        pb = 0 if first else par[i]
        for l in range(nl):
            s = hb + lat[l]
            if s >= n:
                s -= n
                if s >= n:
                    s = s % n
            hn[i * nl + l] = perm[s]
            pn[i * nl + l] = (pb + lat[l]) & 1
    return hn, pn


@nb.njit(cache=True, nogil=True)
def gather_gradients(h, grads, b, out):
    """``out[m] = grads[h[m], b]`` (component b of the gradient block)."""
    for i in range(h.shape[0]):
        out[i] = grads[h[i], b]


@nb.njit(cache=True, nogil=True)
def final_pass(inter, pos, w, scales, group_start, out, mode):
    """The last separable pass (axis 0), fused over terms (octaves, gradient components).

    ``out[j, q] (=, +=) sum_g F(sum_{t in g} scales[t] sum_k w[t, j, k] inter[pos[t, j, k], q])``
    with ``F`` the identity (mode 0 writes, 1 adds) or ``|.|`` (mode 2 adds).
    ``inter`` holds the rows of every term's partially contracted block;
    ``pos`` indexes them. Rows j are independent and every sum runs in a
    fixed order, so any subset of rows or columns is bit-identical.
    """
    nterm, nj, taps = w.shape
    npost = inter.shape[1]
    ngroup = group_start.shape[0] - 1
    acc = np.empty(npost)
    tmp = np.empty(npost)
    for j in range(nj):
        for g in range(ngroup):
            buf = tmp if (mode == 2 and g > 0) else acc
            for t in range(group_start[g], group_start[g + 1]):
                first = t == group_start[g]
                sc = scales[t]
                if taps == 4:
                    w0 = w[t, j, 0] * sc; w1 = w[t, j, 1] * sc; w2 = w[t, j, 2] * sc; w3 = w[t, j, 3] * sc
                    r0 = inter[pos[t, j, 0]]; r1 = inter[pos[t, j, 1]]
                    r2 = inter[pos[t, j, 2]]; r3 = inter[pos[t, j, 3]]
                    if first:
                        for q in range(npost):
                            buf[q] = w0 * r0[q] + w1 * r1[q] + w2 * r2[q] + w3 * r3[q]
                    else:
                        for q in range(npost):
                            buf[q] += w0 * r0[q] + w1 * r1[q] + w2 * r2[q] + w3 * r3[q]
                elif taps == 2:
                    w0 = w[t, j, 0] * sc; w1 = w[t, j, 1] * sc
                    r0 = inter[pos[t, j, 0]]; r1 = inter[pos[t, j, 1]]
                    if first:
                        for q in range(npost):
                            buf[q] = w0 * r0[q] + w1 * r1[q]
                    else:
                        for q in range(npost):
                            buf[q] += w0 * r0[q] + w1 * r1[q]
                else:
                    for k in range(taps):
                        wk = w[t, j, k] * sc
                        rk = inter[pos[t, j, k]]
                        if first and k == 0:
                            for q in range(npost):
                                buf[q] = wk * rk[q]
                        else:
                            for q in range(npost):
                                buf[q] += wk * rk[q]
            if mode == 2:
                if g == 0:
                    for q in range(npost):
                        acc[q] = abs(acc[q])
                else:
                    for q in range(npost):
                        acc[q] += abs(tmp[q])
        o = out[j]
        if mode == 0:
            for q in range(npost):
                o[q] = acc[q]
        else:
            for q in range(npost):
                o[q] += acc[q]


@nb.njit(cache=True, nogil=True)
def final_pass_direct(inter, pos, w, scales, out):
    """:func:`final_pass` for float64 output written directly (mode 0, one group): no buffer, no copy.

    The arithmetic, term by term and tap by tap, is the same as in
    :func:`final_pass`, so both give the same bits.
    """
    nterm, nj, taps = w.shape
    npost = inter.shape[1]
    for j in range(nj):
        o = out[j]
        for t in range(nterm):
            sc = scales[t]
            if taps == 4:
                w0 = w[t, j, 0] * sc; w1 = w[t, j, 1] * sc; w2 = w[t, j, 2] * sc; w3 = w[t, j, 3] * sc
                r0 = inter[pos[t, j, 0]]; r1 = inter[pos[t, j, 1]]
                r2 = inter[pos[t, j, 2]]; r3 = inter[pos[t, j, 3]]
                if t == 0:
                    for q in range(npost):
                        o[q] = w0 * r0[q] + w1 * r1[q] + w2 * r2[q] + w3 * r3[q]
                else:
                    for q in range(npost):
                        o[q] += w0 * r0[q] + w1 * r1[q] + w2 * r2[q] + w3 * r3[q]
            elif taps == 2:
                w0 = w[t, j, 0] * sc; w1 = w[t, j, 1] * sc
                r0 = inter[pos[t, j, 0]]; r1 = inter[pos[t, j, 1]]
                if t == 0:
                    for q in range(npost):
                        o[q] = w0 * r0[q] + w1 * r1[q]
                else:
                    for q in range(npost):
                        o[q] += w0 * r0[q] + w1 * r1[q]
            else:
                for k in range(taps):
                    wk = w[t, j, k] * sc
                    rk = inter[pos[t, j, k]]
                    if t == 0 and k == 0:
                        for q in range(npost):
                            o[q] = wk * rk[q]
                    else:
                        for q in range(npost):
                            o[q] += wk * rk[q]


def _make_grid_rows(DIM, TAPS, INTEGER, GRAD):
    """The fused grid kernel for ``DIM`` (2 or 3) input axes, ``TAPS`` taps (2, 4, or 0: any), a hash and a basis.

    ``INTEGER``: the integer hash (else the table hash); ``GRAD``: the
    gradient basis. Made by :func:`grid_rows_kernel`; each constant prunes
    the code the others need, so a first grid compiles one small kernel.

    One pass over the output's rows (axis 0) does what the separable passes
    do with whole-block arrays (:func:`hash_expand_values` or the gradient
    gathers, :func:`contract_last`, :func:`contract_mid`, :func:`final_pass`):
    each octave keeps its last ``taps`` partially contracted lattice rows
    in a ring, and a lattice row is hashed, contracted along the last axis
    and then the middle one only when an output row first needs it. The
    temporaries are a few rows, not blocks the size of the grid (whose
    fresh pages, zeroed by the system on first touch, cost the separable
    passes much of their time on 3-D grids: ``benchmarks/bench_lattice_paths.md``).
    Every sum is the separable passes' own, term by term and tap by tap, so
    the bits are theirs.
    """

    @nb.njit(cache=True, nogil=True)
    def grid_rows(shapes, pre, par, pre_off, lat2, lat2_off, P0, W0, RW0, P1, W1, RW1, P2, W2, RW2,
                  scales, batch_start, absval, perm, n, values, grads, mult2, out64, out32):
        """All octaves of one output component on a 2-D or 3-D grid window: ``out64`` or ``out32`` (N0, N1 * N2),
        written.

        Per octave ``o`` (``shapes[o]``: its lattice block ``(L0, L1, L2)``,
        ``L1 = 1`` in 2-D): ``pre`` / ``par`` the hash prefix of axes 0 and 1
        (``L0 * L1`` from ``pre_off[o]``; table hash: the nested hash and the
        parity, integer hash: the prefix words), ``lat2`` the last axis's
        reduced lattice indices (from ``lat2_off[o]``). ``P0``, ``W0``, ``RW0``
        (octaves, N0, taps) and ``P1``... (octaves, N1, taps) are the tap
        positions, weights and gradient ramp weights of axes 0 and 1; ``P2``,
        ``W2``, ``RW2`` the last axis's, ``(octaves, taps, N2)``. The
        octaves ``batch_start[i] .. batch_start[i + 1]`` are summed together
        as :func:`final_pass` sums a batch (``absval``: its mode 2), each
        scaled by ``scales[o]``. Table hash: ``values`` and ``grads`` are folded over the
        permutation (:func:`.grid_path.folded_tables`: the last hash level and the look-up in one read).
        The output is ``out64`` when it is float64 (one batch without
        ``absval`` is then summed in place, as :func:`final_pass_direct`
        does), else ``out32``; the other is empty (:func:`out_pair`): one
        specialisation serves both dtypes (a second dtype used to compile the
        kernel again, 1.5-2 s).
        """
        dim = DIM
        noct = shapes.shape[0]
        taps = TAPS if TAPS > 0 else P0.shape[2]
        n0 = P0.shape[1]
        n1 = P1.shape[1]
        n2 = P2.shape[2]
        nterm = dim if GRAD else 1
        post = n1 * n2
        ng = grads.shape[0]
        l1m = 1
        l2m = 1
        for o in range(noct):
            if shapes[o, 1] > l1m:
                l1m = shapes[o, 1]
            if shapes[o, 2] > l2m:
                l2m = shapes[o, 2]
        ring = np.empty((noct, nterm, taps, post))
        tag = np.empty((noct, taps), np.int64)
        for o in range(noct):
            for s in range(taps):
                tag[o, s] = -1
        plane = np.empty(l1m * l2m * nterm)  # a lattice row's values, or its gradients' components side by side
        tmp = np.empty((nterm, l1m * n2))
        acc = np.empty(post)
        gsum = np.empty(post)
        for j in range(n0):
            for o in range(noct):
                l1 = shapes[o, 1]
                l2 = shapes[o, 2]
                for k in range(taps):
                    r = P0[o, j, k]
                    s = r % taps
                    if tag[o, s] == r:
                        continue
                    tag[o, s] = r
                    # hash lattice row r of this octave: its plane of values (or gradient components)
                    row = pre_off[o] + r * l1
                    lat = lat2[lat2_off[o]:lat2_off[o] + l2]
                    for i1 in range(l1):
                        hb = pre[row + i1]
                        pl = i1 * l2
                        if INTEGER:
                            hu = _U32(hb)
                            for l in range(l2):
                                word = _U32(hu ^ prime(lat[l], mult2))
                                if GRAD:
                                    g = hash_index(word, ng)
                                    for b in range(nterm):
                                        plane[(pl + l) * nterm + b] = grads[g, b]
                                else:
                                    plane[pl + l] = hash_value(word)
                        else:
                            pb = par[row + i1]
                            vr = values[(pb - hb) & 1]  # parity (pb + j) & 1 at h + j
                            for l in range(l2):
                                sh = hb + lat[l]
                                if GRAD:
                                    x = sh if sh < 2 * n else sh % n
                                    for b in range(nterm):
                                        plane[(pl + l) * nterm + b] = grads[x, b]
                                elif sh < 2 * n:
                                    plane[pl + l] = vr[sh]
                                else:  # past the folded tables: reduced, the parity row again
                                    plane[pl + l] = values[(pb + lat[l] - sh % n) & 1, sh % n]
                    # contract the last axis into tmp (3-D) or the ring (2-D), every term in one pass (the gradient
                    # basis: the last term takes the ramp weights)
                    w2 = W2[o]
                    rw2 = RW2[o]
                    p2 = P2[o]
                    last = nterm - 1 if GRAD else 1
                    for i1 in range(l1):
                        src = plane[i1 * l2 * nterm:(i1 + 1) * l2 * nterm]
                        t = tmp[:, i1 * n2:(i1 + 1) * n2] if DIM == 3 else ring[o, :, s]
                        for q in range(n2):
                            x0 = p2[0, q] * nterm
                            if TAPS == 2 or TAPS == 4:
                                x1 = x0 + nterm  # a sample's taps are consecutive lattice points
                                c0 = w2[0, q]
                                c1 = w2[1, q]
                                if TAPS == 4:
                                    x2 = x1 + nterm
                                    x3 = x2 + nterm
                                    c2 = w2[2, q]
                                    c3 = w2[3, q]
                                    for b in range(last):
                                        t[b, q] = c0 * src[x0 + b] + c1 * src[x1 + b] + c2 * src[x2 + b] \
                                            + c3 * src[x3 + b]
                                    if GRAD:
                                        t[dim - 1, q] = rw2[0, q] * src[x0 + dim - 1] + rw2[1, q] * src[x1 + dim - 1] \
                                            + rw2[2, q] * src[x2 + dim - 1] + rw2[3, q] * src[x3 + dim - 1]
                                else:
                                    for b in range(last):
                                        t[b, q] = c0 * src[x0 + b] + c1 * src[x1 + b]
                                    if GRAD:
                                        t[dim - 1, q] = rw2[0, q] * src[x0 + dim - 1] + rw2[1, q] * src[x1 + dim - 1]
                            else:
                                for b in range(nterm):
                                    wb = rw2 if (GRAD and b == dim - 1) else w2
                                    v = wb[0, q] * src[x0 + b]
                                    for kk in range(1, taps):
                                        v += wb[kk, q] * src[x0 + kk * nterm + b]
                                    t[b, q] = v
                    for b in range(nterm):
                        dst = ring[o, b, s]
                        if DIM == 3:
                            w1 = RW1[o] if (GRAD and b == 1) else W1[o]
                            for j1 in range(n1):
                                d1 = dst[j1 * n2:(j1 + 1) * n2]
                                if TAPS == 2:  # the taps' products summed in one pass (the same sums)
                                    c0 = w1[j1, 0]
                                    c1 = w1[j1, 1]
                                    s0 = tmp[b, P1[o, j1, 0] * n2:(P1[o, j1, 0] + 1) * n2]
                                    s1 = tmp[b, (P1[o, j1, 0] + 1) * n2:(P1[o, j1, 0] + 2) * n2]
                                    for q in range(n2):
                                        d1[q] = c0 * s0[q] + c1 * s1[q]
                                    continue
                                for kk in range(taps):
                                    c = w1[j1, kk]
                                    src = tmp[b, P1[o, j1, kk] * n2:(P1[o, j1, kk] + 1) * n2]
                                    if kk == 0:
                                        for q in range(n2):
                                            d1[q] = c * src[q]
                                    else:
                                        for q in range(n2):
                                            d1[q] += c * src[q]
            # axis 0: the octaves' terms, batch by batch, as final_pass sums them
            f64 = out64.shape[0] > 0
            # one batch of plain sums into a float64 output: summed in place (final_pass_direct), no copy
            direct = f64 and batch_start.shape[0] == 2 and not absval
            total = out64[j] if direct else acc
            for bi in range(batch_start.shape[0] - 1):
                first = True
                for o in range(batch_start[bi], batch_start[bi + 1]):
                    sc = scales[o]
                    if TAPS == 2:  # every term in one pass (the same sums, in the same order)
                        rg = ring[o]
                        s0 = P0[o, j, 0] % taps
                        s1 = 1 - s0
                        ea0 = (RW0[o, j, 0] if GRAD else W0[o, j, 0]) * sc
                        ea1 = (RW0[o, j, 1] if GRAD else W0[o, j, 1]) * sc
                        eb0 = W0[o, j, 0] * sc
                        eb1 = W0[o, j, 1] * sc
                        for q in range(post):
                            v = ea0 * rg[0, s0, q] + ea1 * rg[0, s1, q]
                            if not (first or absval):
                                v = total[q] + v
                            for b in range(1, nterm):
                                v = v + (eb0 * rg[b, s0, q] + eb1 * rg[b, s1, q])
                            if not absval:
                                total[q] = v
                            elif o == batch_start[bi]:
                                acc[q] = abs(v)
                            else:
                                acc[q] += abs(v)
                        first = False
                        continue
                    for b in range(nterm):
                        w0 = RW0[o, j] if (GRAD and b == 0) else W0[o, j]
                        buf = gsum if (absval and o > batch_start[bi]) else total
                        init = first or (absval and b == 0)
                        r0 = ring[o, b, P0[o, j, 0] % taps]
                        if TAPS == 4:
                            r1 = ring[o, b, P0[o, j, 1] % taps]
                            r2 = ring[o, b, P0[o, j, 2] % taps]
                            r3 = ring[o, b, P0[o, j, 3] % taps]
                            e0 = w0[0] * sc
                            e1 = w0[1] * sc
                            e2 = w0[2] * sc
                            e3 = w0[3] * sc
                            if init:
                                for q in range(post):
                                    buf[q] = e0 * r0[q] + e1 * r1[q] + e2 * r2[q] + e3 * r3[q]
                            else:
                                for q in range(post):
                                    buf[q] += e0 * r0[q] + e1 * r1[q] + e2 * r2[q] + e3 * r3[q]
                        else:
                            for kk in range(taps):
                                ek = w0[kk] * sc
                                rk = ring[o, b, P0[o, j, kk] % taps]
                                if init and kk == 0:
                                    for q in range(post):
                                        buf[q] = ek * rk[q]
                                else:
                                    for q in range(post):
                                        buf[q] += ek * rk[q]
                        first = False
                    if absval:
                        if o == batch_start[bi]:
                            for q in range(post):
                                acc[q] = abs(acc[q])
                        else:
                            for q in range(post):
                                acc[q] += abs(gsum[q])
                if direct:
                    pass
                elif bi == 0 and not absval:
                    for q in range(post):
                        if f64:
                            out64[j, q] = acc[q]
                        else:
                            out32[j, q] = acc[q]
                else:
                    for q in range(post):
                        if f64:
                            out64[j, q] += acc[q]
                        else:
                            out32[j, q] += acc[q]

    return grid_rows

_GRID_ROWS = {}


def grid_rows_kernel(dim, taps, integer, grad):
    """The fused grid kernel (:func:`_make_grid_rows`) for a dimension (2 or 3), tap count, hash and basis.

    Tap counts other than 2 and 4 share one kernel (``TAPS`` 0). Made on
    first request; numba compiles it on its first call (or loads it from its cache).
    """
    key = (int(dim), int(taps) if taps in (2, 4) else 0, bool(integer), bool(grad))
    return _variant(_GRID_ROWS, key, _make_grid_rows, key)


@nb.njit(cache=True, nogil=True)
def hash_expand_values(h, par, lat, perm, n, first, values, out):
    """The last level of :func:`hash_expand` fused with the value lookup: ``out[m, l] = values[parity, h']``."""
    nl = lat.shape[0]
    m = 1 if first else h.shape[0]
    for i in range(m):
        hb = 0 if first else h[i]
        pb = 0 if first else par[i]
        for l in range(nl):
            s = hb + lat[l]
            if s >= n:
                s -= n
                if s >= n:
                    s = s % n
            out[i * nl + l] = values[(pb + lat[l]) & 1, perm[s]]


# ---------------------------------------------------------------- vector helpers

# ---------------------------------------------------------------- derivatives
@nb.njit(cache=True, nogil=True)
def axis_dweights(coords, freq, phase, shift, left, taps, coef, dcoef, grad):
    """Derivatives along one grid axis of its weights ``w`` and ``rw`` (:func:`.grid_path.octave_axis_taps`),
    in input units.

    Returns ``dw`` (N, taps) ``= F w'(t)`` and, if ``grad``, ``drw`` (N, taps)
    ``= F (w'(t) r + w(t))`` (the product rule on ``w r``, ``dr/dt = 1``).
    """
    nn = coords.shape[0]
    dw = np.empty((nn, taps))
    drw = np.empty((nn, taps))
    for j in range(nn):
        u = coords[j] * freq + phase + shift
        fi = np.floor(u)
        t = u - fi
        t2, t3, t4, t5 = _powers(t)
        for k in range(taps):
            s = _weight(coef, k, t, t2, t3, t4, t5)
            ds = _dweight(dcoef, k, t, t2, t3, t4)
            dw[j, k] = freq * ds
            if grad:
                drw[j, k] = freq * (ds * (t - shift + (left - k)) + s)
    return dw, drw

@nb.njit(cache=True, nogil=True)
def block_prefix(h, lat, mult, first, key):
    """One axis of the prefix over a block: ``h'[m * nl + l] = h[m] ^ (lat[l] * mult)`` (uint32).

    ``first``: ``h' = key ^ (lat * mult)`` (``h`` is ignored).
    """
    nl = lat.shape[0]
    m = 1 if first else h.shape[0]
    out = np.empty(m * nl, np.uint32)
    for i in range(m):
        hb = key if first else h[i]
        for l in range(nl):
            out[i * nl + l] = _U32(hb ^ prime(lat[l], mult))
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
    for i in range(h.shape[0]):
        out[i] = grads[hash_index(h[i], n), b]
