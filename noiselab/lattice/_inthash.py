"""The integer hash (``hash="integer"``): an arithmetic hash of the lattice coordinates, no permutation table.

The lattice point ``(j_0, ..., j_{d-1})`` (each index already reduced modulo
its period, ``0 <= j_a < 2**32``) of output component ``c`` gets the 32-bit word

    ``h = mix32(key_c ^ (j_0 M_0) ^ ... ^ (j_{d-1} M_{d-1}))``  (products mod 2**32)

with odd per-axis multipliers ``M_a`` (:data:`MULT`), a seed-derived 32-bit
key per component, and ``mix32`` MurmurHash3's 32-bit finaliser less its last
xor-shift (a bijection: xor-shift, multiply, xor-shift, multiply; the top bits,
which carry the value and the gradient choice, are fully mixed). The products
are combined with xor, not added: a sum ``sum j_a M_a mod 2**32`` is a linear
form whose kernel holds short lattice vectors (about ``2**(32/d)`` cells
long: 256 cells in 4-D), so the field would repeat along an oblique
direction; xor is not linear over the integers and has no such lattice.

The value basis reads ``h`` as a signed integer, ``v = int32(h) / 2**31`` in
``[-1, 1)``. The gradient basis picks ``G[(h * L) >> 32]`` from a set of ``L``
unit gradients (:func:`gradient_set`): the top bits of ``h``. In 1-3-D the
set is fixed and small so that the SIMD kernels select it with bit tests
instead of a table gather: 1-D ``{+1, -1}``; 2-D the 8 unit vectors at
multiples of 45 degrees; 3-D Perlin's (2002) 16 cube-edge directions (12
distinct, 4 of them twice), normalised. From 4-D on, the instance's random
unit gradients.

Everything is 32-bit integer arithmetic, so the scattered kernels
(``_intpoints.py``, generated) run 16 points per AVX-512 instruction.
There is no permutation table and so no table period: rows and columns of the
lattice are independent draws (up to the hash's quality; see
:mod:`noiselab.lab.hashes`), unlike Phillips' nested permutation, where every
full-period row is a permutation of one table. The default period is ``2**32``
cells per axis, the most a 32-bit coordinate holds.

This module holds the definition (:func:`mix32`, :func:`hash_value`,
:func:`hash_index`, :func:`gradient_set`), the grid path's block hashing
(:func:`block_prefix`, :func:`block_values`, :func:`block_gradients`) and the
generic scattered kernels for any dimension and kernel (:func:`int_points`,
and :func:`int_points_jac`, the same source compiled with its derivative
flag: :func:`_make_int_points`). Every point's arithmetic is one fixed
sequence, so results do not depend on chunking or threads.
"""
from __future__ import annotations

import numba as nb
import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from ._jit import _next_corner, _reduce, _wrap

CHUNK = 256
PERIOD_MAX = 1 << 32  # lattice coordinates are hashed as 32-bit words
_TO_UNIT = 1.0 / 2147483648.0  # 2**-31: int32 range onto [-1, 1)
_U32 = np.uint32
_M1 = np.uint32(0x85EBCA6B)
_M2 = np.uint32(0xC2B2AE35)
_S16 = np.uint32(16)
_S13 = np.uint32(13)
_S32 = np.uint64(32)
# odd per-axis multipliers: the top 32 bits of a Weyl sequence in the golden ratio
MULT = np.array([((0x9E3779B97F4A7C15 * (a + 1)) % (1 << 64) >> 32) | 1 for a in range(32)], dtype=np.uint32)
INV_SQRT2 = 0.7071067811865476


def component_keys(draws):
    """The 32-bit keys of the components from the seed's 63-bit draws (their top 32 bits)."""
    return (np.asarray(draws, dtype=np.int64) >> 31).astype(np.uint32)


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


@nb.njit(cache=True, nogil=True)
def mix32_linked(h):
    """:func:`mix32` as a function numba compiles once and links into its callers (where LLVM inlines it).

    The generated SIMD kernels hash up to 64 corners per point: with
    ``inline="always"`` numba copies and re-types ``mix32``'s IR at every one
    of them (seconds of a first call's compilation); a linked call is typed
    once, and the machine code is the same.
    """
    return mix32(h)


@nb.njit(cache=True, nogil=True, inline="always")
def hash_value(h):
    """The lattice value of a prefix word: ``int32(mix32(h)) / 2**31`` in [-1, 1)."""
    return np.float64(np.int32(mix32(h))) * _TO_UNIT


@nb.njit(cache=True, nogil=True, inline="always")
def hash_index(h, n):
    """The gradient index of a prefix word: ``(mix32(h) * n) >> 32`` (the top bits; ``h >> 28`` for n = 16)."""
    return np.int64((np.uint64(mix32(h)) * np.uint64(n)) >> _S32)


@nb.njit(cache=True, nogil=True, inline="always")
def prime(j, mult):
    """An axis's share of the prefix word: ``(j * M_a) mod 2**32`` for a reduced index ``0 <= j < 2**32``."""
    return _U32(_U32(j) * mult)


def _perlin3():
    """Perlin's (2002) 16 gradient directions of improved noise, as ``grad(h, x, y, z)`` picks them, normalised."""
    g = np.zeros((16, 3))
    for h in range(16):
        u = 0 if h < 8 else 1
        v = 1 if h < 4 else (0 if h in (12, 14) else 2)
        g[h, u] += -1.0 if h & 1 else 1.0
        g[h, v] += -1.0 if h & 2 else 1.0
    return g * INV_SQRT2


def gradient_set(d, table):
    """The unit gradients the integer hash picks from in ``d`` dimensions (``table``: the instance's, used from 4-D on).

    1-D ``[+1, -1]``; 2-D the axes then the diagonals, ``(1, 0), (-1, 0),
    (0, 1), (0, -1), (s, s), (-s, s), (s, -s), (-s, -s)`` with ``s = 1/sqrt 2``
    (index bit 0 flips x, bit 1 picks y or flips it); 3-D Perlin's 16.
    """
    if d == 1:
        return np.array([[1.0], [-1.0]])
    if d == 2:
        s = INV_SQRT2
        return np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0], [s, s], [-s, s], [s, -s], [-s, -s]])
    if d == 3:
        return _perlin3()
    return np.ascontiguousarray(table, dtype=np.float64)


_LANES = 16


def _deinterleave_codegen(d, lanes=_LANES):
    """Codegen for ``deinterleave{d}(pts, p, X_0, ..., X_{d-1}, i)``: see :func:`deinterleave3`."""
    def codegen(context, builder, signature, args):
        src = context.make_array(signature.args[0])(context, builder, args[0])
        elt = context.get_data_type(signature.args[0].dtype)
        width = signature.args[0].dtype.bitwidth // 8
        i64 = ir.IntType(64)
        start = builder.mul(args[1], ir.Constant(i64, d))
        whole = ir.VectorType(elt, lanes * d)
        vec = builder.load(builder.bitcast(builder.gep(src.data, [start]), whole.as_pointer()), align=width)
        for a in range(d):
            rty = signature.args[2 + a]
            row = context.make_array(rty)(context, builder, args[2 + a])
            mask = ir.Constant(ir.VectorType(ir.IntType(32), lanes), [d * j + a for j in range(lanes)])
            part = builder.shuffle_vector(vec, ir.Constant(whole, ir.Undefined), mask)
            relt = context.get_data_type(rty.dtype)
            if relt != elt:
                part = builder.fpext(part, ir.VectorType(relt, lanes))
            ptr = builder.bitcast(builder.gep(row.data, [args[-1]]), ir.VectorType(relt, lanes).as_pointer())
            builder.store(part, ptr, align=rty.dtype.bitwidth // 8)
        return context.get_dummy_value()

    return codegen


def _deinterleave_sig(pts, p, rows, i):
    if not (isinstance(pts, types.Array) and pts.layout == "C" and pts.ndim == 2 and p == types.int64
            and i == types.int64 and all(isinstance(r, types.Array) and r.ndim == 1 for r in rows)):
        return None
    return types.void(pts, p, *rows, i)


@intrinsic
def deinterleave2(typingctx, pts, p, x0, x1, i):
    """As :func:`deinterleave3`, for 2-D points."""
    sig = _deinterleave_sig(pts, p, (x0, x1), i)
    return None if sig is None else (sig, _deinterleave_codegen(2))


@intrinsic
def deinterleave3(typingctx, pts, p, x0, x1, x2, i):
    """Copy 16 points ``pts[p:p + 16]`` of a C-contiguous ``(N, 3)`` array to ``x0[i:i + 16]``, ``x1``, ``x2``.

    The 48 coordinates are loaded as one vector and split with shuffles
    (vpermt2ps on AVX-512), widened from float32 when the rows are float64.
    LLVM does not vectorise the stride-3 loop ``x_a[i] = pts[p + i, a]``
    itself; there it costs about as much as the noise. (This is the
    transposition the SIMD peers avoid by taking each coordinate as its own
    array.) The caller keeps ``p + 16 <= N`` and ``i + 16 <= len(x_a)``.
    """
    sig = _deinterleave_sig(pts, p, (x0, x1, x2), i)
    return None if sig is None else (sig, _deinterleave_codegen(3))


@intrinsic
def flipsign(typingctx, x, m):
    """``x`` with its sign flipped where bit 31 of the uint32 ``m`` is set (``-x`` if so, else ``x``), as one xor.

    The gradient kernels pick signs from hash bits; a compare and a select per
    sign would cost three instructions where the xor of the sign bit costs one.
    """
    if not (isinstance(x, types.Float) and m == types.uint32):
        return None

    def codegen(context, builder, signature, args):
        val, mask = args
        bits = x.bitwidth
        ity = ir.IntType(bits)
        sign = builder.and_(mask, ir.Constant(ir.IntType(32), 0x80000000))
        if bits == 64:
            sign = builder.shl(builder.zext(sign, ity), ir.Constant(ity, 32))
        return builder.bitcast(builder.xor(builder.bitcast(val, ity), sign), val.type)

    return x(x, m), codegen


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
            M[a, k, i] = prime(_wrap(b + k, per, msk), mult_a)


@nb.njit(cache=True, nogil=True, inline="always")
def _add_grad_derivs(T, DP, wp, grads, g, v, i, d):
    """``T[1 + b, i] += DP[b, i] v + wp g_b`` for every axis b: a gradient corner's derivative terms."""
    for b in range(d):
        T[1 + b, i] += DP[b, i] * v + wp * grads[g, b]


def _make_int_points(DERIV):
    """:func:`int_points` (``DERIV`` False) or :func:`int_points_jac` (True): one source, two compiled kernels.

    ``DERIV`` is a constant of the closure: numba prunes the derivative
    branches before typing, so the value kernel compiles no derivative code
    (a boolean is safe in numba's cache key; a function closed over is not).
    """

    @nb.njit(cache=True, nogil=True)
    def int_points(pts, out, freqs, amps, phase, shift, left, taps, coef, dcoef, period, pmask,
                   keys, mult, grads, basis, absval):
        """Lattice noise with the integer hash (and with ``DERIV`` its Jacobian) at scattered points.

        Any dimension; octaves fused. ``pts`` (N, d) float64; ``out`` written:
        (N, C), or with ``DERIV`` (N, C, d + 1) float64 as in
        ``_jit.eval_points_jac`` (the value, then its derivative along each
        input axis); ``keys`` (C,) uint32 per component; ``mult`` (d,) uint32
        odd multipliers; ``grads`` (L, d) the gradient set
        (:func:`gradient_set`). The other arguments are those of
        ``_jit.eval_points`` (``dcoef`` is read only with ``DERIV``).

        Per chunk and octave: each axis's weights and hashed tap offsets
        ``M[a, k] = ((j + k) mod period) * M_a`` (uint32); then the corners in
        odometer order, the prefix words (xor) and weight products carried
        level by level, each level one vectorisable loop over the chunk. A
        corner's term ``prod_a w_a v`` differentiates along axis ``b`` to
        ``w_b' prod_{a != b} w_a v`` (plus, in the gradient basis, ``prod_a
        w_a g_b``); the product is formed per corner, ``w_0`` first and
        ``w_b'`` second (``DP``).
        """
        npts, d = pts.shape
        ncomp = keys.shape[0]
        n = grads.shape[0]
        noct = freqs.shape[0]
        nq = d + 1 if DERIV else 1  # the value, then (DERIV) one derivative per axis
        W = np.empty((d, taps, CHUNK))
        if DERIV:
            DW = np.empty((d, taps, CHUNK))
            V = np.empty(CHUNK)  # the corner's values (value basis)
        else:
            DW = np.empty((1, 1, 1))  # not read
        R = np.empty((d, taps, CHUNK))
        M = np.empty((d, taps, CHUNK), np.uint32)
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
                    _axis_setup(pts, p0, m, a, freqs[o, a], phase[a], shift, left, taps, coef, dcoef, period[a],
                                pmask[a], mult[a], W, DW, R, M, DERIV)
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
                        elif d == 1:
                            r0 = R[0, cnt[0]]
                            for i in range(m):
                                g = hash_index(hd[i], n)
                                v = grads[g, 0] * r0[i]
                                T0[i] += wd[i] * v
                                if DERIV:
                                    _add_grad_derivs(T, DP, wd[i], grads, g, v, i, d)
                        elif d == 2:
                            r0 = R[0, cnt[0]]
                            r1 = R[1, cnt[1]]
                            for i in range(m):
                                g = hash_index(hd[i], n)
                                v = grads[g, 0] * r0[i] + grads[g, 1] * r1[i]
                                T0[i] += wd[i] * v
                                if DERIV:
                                    _add_grad_derivs(T, DP, wd[i], grads, g, v, i, d)
                        elif d == 3:
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
                        level = _next_corner(cnt, taps)
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


# the integer hash at scattered points (any dimension), and the same with its Jacobian: two instances of one source
int_points = _make_int_points(False)
int_points_jac = _make_int_points(True)
