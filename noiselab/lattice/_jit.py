"""numba kernels for lattice noise (compiled once, cached on disk).

- :func:`eval_points`: scattered points, any dimension. Every point splits
  each coordinate into a lattice index and a fraction, evaluates the tap
  weights, and walks the ``taps**d`` lattice neighbours with the nested
  permutation hash ``h_{a+1} = P[(h_a + j_a) mod n]`` (Phillips 2.4.1),
  summing weight x value. Several octaves (fractal sums) are fused into one
  pass over the points. Dimensions 1-3 use the unrolled kernels of
  ``_points.py`` instead (3-D: over precombined hash tables, with the
  last axis's taps summed by :func:`axpy_lanes` / :func:`grad_axpy_lanes`).
  :func:`eval_points_jac` (values and Jacobians) is the same source compiled
  with its derivative flag (:func:`_make_eval_points`).
- the grid path: :func:`axis_weights` and :func:`dense_taps` (per-axis
  weights and distinct taps), :func:`hash_expand` / :func:`hash_expand_values`
  (the hashed block of lattice values), :func:`contract_last` /
  :func:`contract_mid` (one separable pass per axis), and :func:`final_pass` /
  :func:`final_pass_direct` (the last pass, fused over octaves).
- 2-D grids: :func:`pack_axis` for both axes (``grid_path`` packs them), then
  :func:`grid2d` per component: every octave in one pass, tile by tile,
  with the general path's sums (the same bits); its axis-1 contraction runs
  eight columns at a time (:func:`expand_dot8`). Both hashes: the integer
  hash's variant gets its lattice rows from ``_intgrid``.

All arithmetic is float64; only the final store may round to float32. The
specialisations are kept few so that a cold cache compiles quickly.
"""
from __future__ import annotations

import math

import numba as nb
import numpy as np
from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

# Beyond 2**52 a float64 has no fractional bits; beyond 2**62 it no longer
# fits an int64. Lattice indices are reduced modulo the period with fmod
# (exact for floats) before any conversion to int64.
_INT_SAFE = 4.0e15


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


def _make_eval_points(DERIV):
    """:func:`eval_points` (``DERIV`` False) or :func:`eval_points_jac` (True): one source, two compiled kernels.

    ``DERIV`` is a constant of the closure: numba prunes the derivative
    branches before typing, so the value kernel compiles (and runs) no
    derivative code. A boolean is safe in numba's cache key (it is pickled
    with the closure); a function closed over is not (see :func:`_make_axis0`).
    """

    @nb.njit(cache=True, nogil=True)
    def eval_points(pts, out, freqs, amps, phase, shift, left, taps, coef, dcoef, period, pmask,
                    perms, values, grads, basis, absval):
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

        Dimensions 1 to 3 have unrolled neighbour loops; higher dimensions walk
        the ``taps**d`` neighbours with an odometer that re-hashes only the
        levels whose tap changed.

        The derivative: a tensor-product term ``prod_a w_a(t_a) v``
        differentiates one factor at a time: along axis ``b`` it is
        ``w_b'(t_b) prod_{a != b} w_a v``, plus, in the gradient basis
        (``v = g . r`` with ``dr_a / dt_b = [a == b]``), ``prod_a w_a g_b``.
        ``t_a = F_a x_a + phi_a + shift - floor(...)``, so ``d/dx_a = F_a
        d/dt_a``. Turbulence's ``|n|`` differentiates to ``sign(n) n'`` (0
        where ``n == 0``: the crease has no derivative there). The values are
        the same sums with or without ``DERIV``.
        """
        npts, d = pts.shape
        ncomp = perms.shape[0]
        n = perms.shape[1]
        nmask = n - 1 if (n & (n - 1)) == 0 else -1
        noct = freqs.shape[0]
        nq = d + 1 if DERIV else 1  # the value, then (DERIV) one derivative per axis
        w = np.empty((d, 4))
        r = np.empty((d, 4))
        jj = np.empty((d, 4), np.int64)
        cnt = np.zeros(d, np.int64)
        hs = np.zeros(d + 1, np.int64)
        par = np.zeros(d + 1, np.int64)
        prod = np.ones(d + 1)
        if DERIV:  # (the value kernel allocates, and compiles, none of these)
            dw = np.empty((d, 4))
            dprod = np.zeros((d + 1, d))
            D = np.zeros(d)
        acc = np.empty((ncomp, nq))  # zeroed per point
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
                    # powers first: independent products instead of a serial Horner chain
                    t2 = t * t
                    t3 = t2 * t
                    t4 = t2 * t2
                    t5 = t4 * t
                    for k in range(taps):
                        w[a, k] = ((coef[k, 0] + coef[k, 1] * t) + (coef[k, 2] * t2 + coef[k, 3] * t3)
                                   + (coef[k, 4] * t4 + coef[k, 5] * t5))
                        if DERIV:
                            dw[a, k] = ((dcoef[k, 0] + dcoef[k, 1] * t) + (dcoef[k, 2] * t2 + dcoef[k, 3] * t3)
                                        + dcoef[k, 4] * t4)
                        r[a, k] = t - shift + (left - k)
                        jj[a, k] = _wrap(b + k, per, msk)
                for c in range(ncomp):
                    perm = perms[c]
                    total = 0.0
                    if DERIV:
                        for a in range(d):
                            D[a] = 0.0
                    # d <= 3: per level the partial value s (and with DERIV: the derivative along
                    # this level's axis, sNdN, and along the axes above it, eN.., summed likewise)
                    if d == 1:
                        for k0 in range(taps):
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
                    elif d == 2:
                        for k0 in range(taps):
                            j0 = jj[0, k0]
                            h1 = perm[_hash(0, j0, n, nmask)]
                            s1 = 0.0
                            s1d1 = 0.0
                            e0 = 0.0
                            for k1 in range(taps):
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
                    elif d == 3:
                        for k0 in range(taps):
                            j0 = jj[0, k0]
                            h1 = perm[_hash(0, j0, n, nmask)]
                            s1 = 0.0
                            s1d1 = 0.0
                            s1d2 = 0.0
                            e10 = 0.0
                            for k1 in range(taps):
                                j1 = jj[1, k1]
                                h2 = perm[_hash(h1, j1, n, nmask)]
                                s2 = 0.0
                                s2d2 = 0.0
                                e20 = 0.0
                                e21 = 0.0
                                for k2 in range(taps):
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
                            level = _next_corner(cnt, taps)
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


# lattice noise at scattered points (any dimension), and the same with its Jacobian: two instances of one source
eval_points = _make_eval_points(False)
eval_points_jac = _make_eval_points(True)


@nb.njit(cache=True, nogil=True, inline="always")
def axis_weights(coords, freq, phase, shift, left, taps, coef, period, grad):
    mask = period - 1 if (period & (period - 1)) == 0 else -1
    """Per-sample tap weights and reduced first-tap indices along one grid axis.

    Returns ``fi`` (float floor index), ``base`` ((floor - left) mod period),
    ``w`` (N, taps) weights and, if ``grad``, ``rw`` (N, taps) = weight x signed distance.
    """
    nn = coords.shape[0]
    fis = np.empty(nn)
    base = np.empty(nn, np.int64)
    w = np.empty((nn, taps))
    rw = np.empty((nn, taps))
    for j in range(nn):
        u = coords[j] * freq + phase + shift
        fi = np.floor(u)
        t = u - fi
        fis[j] = fi
        base[j] = _reduce(fi, left, period, mask)
        t2 = t * t
        t3 = t2 * t
        t4 = t2 * t2
        t5 = t4 * t
        for k in range(taps):
            s = ((coef[k, 0] + coef[k, 1] * t) + (coef[k, 2] * t2 + coef[k, 3] * t3)
                 + (coef[k, 4] * t4 + coef[k, 5] * t5))
            w[j, k] = s
            if grad:
                rw[j, k] = s * (t - shift + (left - k))
    return fis, base, w, rw


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
    """The separable pass on the last (contiguous) axis: ``out[p, j] = sum_k w[j, k] * inp[p, pos[j, k]]``.

    Rows are taken eight at a time so that each sample's weights and tap
    positions are loaded once per eight rows.
    """
    npre = inp.shape[0]
    nj, taps = w.shape
    p0 = 0
    while p0 < npre:
        p1 = min(p0 + 8, npre)
        for j in range(nj):
            if taps == 4:
                a0 = pos[j, 0]; a1 = pos[j, 1]; a2 = pos[j, 2]; a3 = pos[j, 3]
                w0 = w[j, 0]; w1 = w[j, 1]; w2 = w[j, 2]; w3 = w[j, 3]
                for p in range(p0, p1):
                    out[p, j] = w0 * inp[p, a0] + w1 * inp[p, a1] + w2 * inp[p, a2] + w3 * inp[p, a3]
            elif taps == 2:
                a0 = pos[j, 0]; a1 = pos[j, 1]
                w0 = w[j, 0]; w1 = w[j, 1]
                for p in range(p0, p1):
                    out[p, j] = w0 * inp[p, a0] + w1 * inp[p, a1]
            else:
                for p in range(p0, p1):
                    s = w[j, 0] * inp[p, pos[j, 0]]
                    for k in range(1, taps):
                        s += w[j, k] * inp[p, pos[j, k]]
                    out[p, j] = s
        p0 = p1


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


@nb.njit(cache=True, nogil=True, inline="always")
def dense_taps(fis, base, taps, period):
    """Distinct lattice taps of one grid axis, by marking offsets from the smallest floor index.

    Returns ``lattice`` (reduced index of each distinct tap, in increasing
    raw order) and ``pos`` (N, taps): the position of each sample's taps in it.
    Used when the taps span few cells (dense grids); equivalent to ``np.unique``.
    """
    nn = fis.shape[0]
    j0 = 0
    for j in range(nn):
        if fis[j] < fis[j0]:
            j0 = j
    lo = fis[j0]
    span = 0
    for j in range(nn):
        r = np.int64(fis[j] - lo)
        if r > span:
            span = r
    span += taps
    index = np.empty(span, np.int64)  # (np.full: one more overload to compile)
    for r in range(span):
        index[r] = -1
    for j in range(nn):
        r = np.int64(fis[j] - lo)
        for k in range(taps):
            index[r + k] = 0
    count = 0
    for r in range(span):
        if index[r] == 0:
            index[r] = count
            count += 1
    lattice = np.empty(count, np.int64)
    for r in range(span):
        if index[r] >= 0:
            lattice[index[r]] = (base[j0] + r) % period
    pos = np.empty((nn, taps), np.int64)
    for j in range(nn):
        r = np.int64(fis[j] - lo)
        for k in range(taps):
            pos[j, k] = index[r + k]
    return lattice, pos


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
# numba leaves LLVM's SLP vectoriser off, so the straight-line sum over the
# last axis's taps (contiguous table entries) stays scalar; these intrinsics
# write it as one short vector operation. Every lane does the same IEEE
# multiply and add as the scalar code would (no reassociation, no FMA), so
# the results are bit-identical to the scalar expressions.

def _vector(builder, vty, values):
    v = ir.Constant(vty, ir.Undefined)
    for k, x in enumerate(values):
        v = builder.insert_element(v, x, ir.Constant(ir.IntType(32), k))
    return v


def _lanes(builder, v, width):
    return [builder.extract_element(v, ir.Constant(ir.IntType(32), k)) for k in range(width)]


def _load(context, builder, aryty, ary_v, idx, vty):
    ary = context.make_array(aryty)(context, builder, ary_v)
    ptr = builder.gep(ary.data, [idx])
    return builder.load(builder.bitcast(ptr, vty.as_pointer()), align=8)


@intrinsic
def axpy_lanes(typingctx, acc, w, arr, idx):
    """``acc[k] + w * arr[idx + k]`` for every lane k of the float64 tuple ``acc`` (1-D contiguous ``arr``)."""
    if not (isinstance(acc, types.UniTuple) and acc.dtype == types.float64):
        return None
    width = acc.count
    sig = acc(acc, w, arr, idx)

    def codegen(context, builder, signature, args):
        acc_v, w_v, arr_v, idx_v = args
        vty = ir.VectorType(ir.DoubleType(), width)
        v = _load(context, builder, signature.args[2], arr_v, idx_v, vty)
        a = _vector(builder, vty, [builder.extract_value(acc_v, k) for k in range(width)])
        wv = _vector(builder, vty, [w_v] * width)
        r = builder.fadd(a, builder.fmul(wv, v))
        return context.make_tuple(builder, signature.return_type, _lanes(builder, r, width))

    return sig, codegen


@intrinsic
def grad_axpy_lanes(typingctx, acc, w, r0, r1, r2, arr, idx, stride):
    """``acc[k] + w * ((g0 * r0 + g1 * r1) + g2 * r2[k])`` with ``g_a = arr[a * stride + idx + k]``.

    The gradient dot product of the scalar kernels, lane k being tap k of the
    last axis; ``r2`` is a float64 tuple of the last axis's signed distances.
    """
    if not (isinstance(acc, types.UniTuple) and acc.dtype == types.float64):
        return None
    width = acc.count
    sig = acc(acc, w, r0, r1, r2, arr, idx, stride)

    def codegen(context, builder, signature, args):
        acc_v, w_v, r0_v, r1_v, r2_v, arr_v, idx_v, stride_v = args
        vty = ir.VectorType(ir.DoubleType(), width)
        aryty = signature.args[5]
        g0 = _load(context, builder, aryty, arr_v, idx_v, vty)
        i1 = builder.add(idx_v, stride_v)
        g1 = _load(context, builder, aryty, arr_v, i1, vty)
        g2 = _load(context, builder, aryty, arr_v, builder.add(i1, stride_v), vty)
        dot = builder.fadd(builder.fmul(g0, _vector(builder, vty, [r0_v] * width)),
                           builder.fmul(g1, _vector(builder, vty, [r1_v] * width)))
        dot = builder.fadd(dot, builder.fmul(g2, _vector(builder, vty, [builder.extract_value(r2_v, k)
                                                                        for k in range(width)])))
        a = _vector(builder, vty, [builder.extract_value(acc_v, k) for k in range(width)])
        r = builder.fadd(a, builder.fmul(_vector(builder, vty, [w_v] * width), dot))
        return context.make_tuple(builder, signature.return_type, _lanes(builder, r, width))

    return sig, codegen


# ---------------------------------------------------------------- derivatives
@nb.njit(cache=True, nogil=True, inline="always")
def axis_dweights(coords, freq, phase, shift, left, taps, coef, dcoef, grad):
    """Derivatives along one grid axis of :func:`axis_weights`' ``w`` and ``rw``, in input units.

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
        t2 = t * t
        t3 = t2 * t
        t4 = t2 * t2
        t5 = t4 * t
        for k in range(taps):
            s = ((coef[k, 0] + coef[k, 1] * t) + (coef[k, 2] * t2 + coef[k, 3] * t3)
                 + (coef[k, 4] * t4 + coef[k, 5] * t5))
            ds = ((dcoef[k, 0] + dcoef[k, 1] * t) + (dcoef[k, 2] * t2 + dcoef[k, 3] * t3) + dcoef[k, 4] * t4)
            dw[j, k] = freq * ds
            if grad:
                drw[j, k] = freq * (ds * (t - shift + (left - k)) + s)
    return dw, drw


# ---------------------------------------------------------------- fused 2-D grids
@intrinsic
def expand_dot8(typingctx, row, ridx, E, e0, v, B, M):
    """``row[ridx + p] = sum_m E[e0 + 8 m + p] * v[B + m]`` (m = 0 .. M-1, in order; p < 8), one vector of 8 lanes.

    A NaN in ``E`` marks no term: its product is not added (a lane's sum
    starts at -0.0, which added to x gives x). So the sum is the bare tap sum
    ``p_0 + p_1 + ...`` bit for bit, the sign of a zero included (an added
    product ``0 * v`` is -0.0 or +0.0 by the sign of v, and -0.0 + +0.0 = +0.0).
    """
    sig = types.void(row, ridx, E, e0, v, B, M)

    def codegen(context, builder, signature, args):
        row_v, ridx_v, E_v, e0_v, v_v, B_v, M_v = args
        dty = ir.DoubleType()
        vty = ir.VectorType(dty, 8)
        i64 = ir.IntType(64)
        acc = cgutils.alloca_once(builder, vty)
        builder.store(ir.Constant(vty, [-0.0] * 8), acc)
        Eary = context.make_array(signature.args[2])(context, builder, E_v)
        vary = context.make_array(signature.args[4])(context, builder, v_v)
        rary = context.make_array(signature.args[0])(context, builder, row_v)
        with cgutils.for_range(builder, M_v) as loop:
            m = loop.index
            eptr = builder.gep(Eary.data, [builder.add(e0_v, builder.mul(m, ir.Constant(i64, 8)))])
            e = builder.load(builder.bitcast(eptr, vty.as_pointer()), align=8)
            s = builder.load(builder.gep(vary.data, [builder.add(B_v, m)]))
            sv = builder.insert_element(ir.Constant(vty, ir.Undefined), s, ir.Constant(ir.IntType(32), 0))
            sv = builder.shuffle_vector(sv, ir.Constant(vty, ir.Undefined), ir.Constant(ir.VectorType(ir.IntType(32), 8), [0] * 8))
            cur = builder.load(acc)
            keep = builder.fcmp_unordered("uno", e, e)  # NaN: no term here
            builder.store(builder.select(keep, cur, builder.fadd(cur, builder.fmul(sv, e))), acc)
        rptr = builder.gep(rary.data, [ridx_v])
        builder.store(builder.load(acc), builder.bitcast(rptr, vty.as_pointer()), align=8)
        return context.get_dummy_value()

    return sig, codegen


def _make_axis0(GRAD):
    """:func:`_axis0_octave` for one basis (``grad`` a compile-time constant).

    Passed as an argument, ``grad`` was a run-time bool: the kernel compiled
    all 16 loops of both bases, and each :func:`grid2d` that linked it
    optimised them again (LLVM prunes the other basis only after inlining).
    """

    @nb.njit(cache=True, nogil=True)
    def _axis0_octave(dst, doff, prev, poff, has_prev, R, nt, taps, x0, x1, x2, x3, dy, a0, a1, a2, a3,
                      b0, b1, b2, b3):
        """One octave of :func:`grid2d`'s axis-0 pass: ``dst[doff + q] = (prev[poff + q] +) T0[q] (+ T1[q])``.

        ``T0 = sum_k a_k R[x_k + q]`` (the value term, or the gradient's first
        term), ``T1 = sum_k b_k R[x_k + dy + q]`` (the gradient's second term).
        The sums are :func:`final_pass`'s: for 2 and 4 taps each term's tap sum
        is added to the running sum, for 1 and 3 taps every tap product is.
        Offsets and ``nt`` are uint64; ``dst`` and ``prev`` are different arrays
        (so that the loop vectorises). Not inlined by numba (its IR inliner
        deep-copies every branch into each call site: seconds of compilation;
        with one call site it still compiled 0.3 s slower than linking).
        """
        grad = GRAD
        if taps == 4 and grad:
            y0 = x0 + dy
            y1 = x1 + dy
            y2 = x2 + dy
            y3 = x3 + dy
            if has_prev:
                for q in range(nt):
                    dst[doff + q] = ((prev[poff + q] + (a0 * R[x0 + q] + a1 * R[x1 + q] + a2 * R[x2 + q] + a3 * R[x3 + q]))
                                     + (b0 * R[y0 + q] + b1 * R[y1 + q] + b2 * R[y2 + q] + b3 * R[y3 + q]))
            else:
                for q in range(nt):
                    dst[doff + q] = ((a0 * R[x0 + q] + a1 * R[x1 + q] + a2 * R[x2 + q] + a3 * R[x3 + q])
                                     + (b0 * R[y0 + q] + b1 * R[y1 + q] + b2 * R[y2 + q] + b3 * R[y3 + q]))
        elif taps == 2 and grad:
            y0 = x0 + dy
            y1 = x1 + dy
            if has_prev:
                for q in range(nt):
                    dst[doff + q] = (prev[poff + q] + (a0 * R[x0 + q] + a1 * R[x1 + q])) + (b0 * R[y0 + q] + b1 * R[y1 + q])
            else:
                for q in range(nt):
                    dst[doff + q] = (a0 * R[x0 + q] + a1 * R[x1 + q]) + (b0 * R[y0 + q] + b1 * R[y1 + q])
        elif taps == 4:
            if has_prev:
                for q in range(nt):
                    dst[doff + q] = prev[poff + q] + (a0 * R[x0 + q] + a1 * R[x1 + q] + a2 * R[x2 + q] + a3 * R[x3 + q])
            else:
                for q in range(nt):
                    dst[doff + q] = a0 * R[x0 + q] + a1 * R[x1 + q] + a2 * R[x2 + q] + a3 * R[x3 + q]
        elif taps == 2:
            if has_prev:
                for q in range(nt):
                    dst[doff + q] = prev[poff + q] + (a0 * R[x0 + q] + a1 * R[x1 + q])
            else:
                for q in range(nt):
                    dst[doff + q] = a0 * R[x0 + q] + a1 * R[x1 + q]
        elif taps == 3:  # every tap product added to the running sum by itself
            if grad:
                y0 = x0 + dy
                y1 = x1 + dy
                y2 = x2 + dy
                if has_prev:
                    for q in range(nt):
                        dst[doff + q] = (((((prev[poff + q] + a0 * R[x0 + q]) + a1 * R[x1 + q]) + a2 * R[x2 + q])
                                          + b0 * R[y0 + q]) + b1 * R[y1 + q]) + b2 * R[y2 + q]
                else:
                    for q in range(nt):
                        dst[doff + q] = ((((a0 * R[x0 + q] + a1 * R[x1 + q]) + a2 * R[x2 + q]) + b0 * R[y0 + q])
                                         + b1 * R[y1 + q]) + b2 * R[y2 + q]
            elif has_prev:
                for q in range(nt):
                    dst[doff + q] = ((prev[poff + q] + a0 * R[x0 + q]) + a1 * R[x1 + q]) + a2 * R[x2 + q]
            else:
                for q in range(nt):
                    dst[doff + q] = (a0 * R[x0 + q] + a1 * R[x1 + q]) + a2 * R[x2 + q]
        else:  # one tap
            if grad:
                y0 = x0 + dy
                if has_prev:
                    for q in range(nt):
                        dst[doff + q] = (prev[poff + q] + a0 * R[x0 + q]) + b0 * R[y0 + q]
                else:
                    for q in range(nt):
                        dst[doff + q] = a0 * R[x0 + q] + b0 * R[y0 + q]
            elif has_prev:
                for q in range(nt):
                    dst[doff + q] = prev[poff + q] + a0 * R[x0 + q]
            else:
                for q in range(nt):
                    dst[doff + q] = a0 * R[x0 + q]

    return _axis0_octave


_axis0_value = _make_axis0(False)
_axis0_grad = _make_axis0(True)


@nb.njit(cache=True, nogil=True)
def _row_range(rows, o, a, b):
    """``(min, max)`` of ``rows[o, a:b]`` as a loop over the row (no array view in grid2d's hot loops)."""
    lo = rows[o, a]
    hi = lo
    for q in range(a, b):
        v = rows[o, q]
        lo = v if v < lo else lo  # not min/max: each compiles an overload of its own
        hi = v if v > hi else hi
    return lo, hi


def int_row_values(ext, at, word, words, start, m):
    """The integer hash's values of one lattice row: ``ext[at + l] = hash_value(word ^ words[start + l])``, l < m.

    Called only by the compiled :func:`grid2d` (the integer-hash variants):
    numba compiles the implementation that ``_intgrid`` registers for it with
    ``@overload``, since the hash lives in ``_inthash``, which imports this module.
    """
    raise NotImplementedError("compiled only: the integer-hash grid kernel's row of lattice values (_intgrid)")


def int_row_gradients(ext, at0, at1, word, words, start, m, grads):
    """The integer hash's gradients of one lattice row, ``b = 0, 1``:
    ``ext[at_b + l] = grads[hash_index(word ^ words[start + l]), b]``.

    As :func:`int_row_values` (compiled only; the implementation is ``_intgrid``'s).
    """
    raise NotImplementedError("compiled only: the integer-hash grid kernel's row of lattice gradients (_intgrid)")


def _make_grid2d(GRAD, USE32, INT):
    """:func:`grid2d`'s compiled kernel for one basis, output dtype and hash (compile-time constants).

    With ``grad``, the output dtype and the hash (``INT``: the integer hash)
    frozen in the closure numba prunes the other bases', dtypes' and hashes'
    code before compiling (numba caches each variant on disk: closure values
    are part of its cache key), so the table-hash variants compile no integer
    hash code. The integer-hash variants call :func:`int_row_values` /
    :func:`int_row_gradients`, compiled from ``_intgrid``'s implementation
    (numba's cache of this kernel does not notice a change there: clear the
    cache after editing it, as for any callee in another file). The tap count stays a
    run-time value: a kernel per tap count as well compiled no faster for one
    grid and 3.8 times slower for all of them (the test suite): 63 s against
    17 s CPU for the 16 grids of ``bench_coldstart.py``'s ``grid2-all``.
    """

    TABLE = not INT

    @nb.njit(cache=True, nogil=True)
    def grid2d(lat0, off0, pos0, wa0, wb0, lat1, off1, base1, dense1, wa1, wb1, scales, perm, values, grads, basis,
               absval, out64, out32, nq, tile):
        """A 2-D grid of lattice noise, every octave fused, in tiles of ``tile`` columns.

        Octave ``o`` has the distinct lattice taps ``lat0[off0[o]:off0[o + 1]]``
        along axis 0 and ``lat1[off1[o]:off1[o + 1]]`` along axis 1 (reduced
        modulo the table size n; with the integer hash ``INT``, the taps'
        words instead, uint32: ``key ^ (j_0 M_0)`` along axis 0 and ``j_1 M_1``
        along axis 1, whose xor a lattice point's value or gradient hashes,
        and ``perm``, ``values`` and ``dense1`` are unused (``dense1`` all
        False)), each output row's taps ``pos0[o]`` (nj, taps)
        in the first and each column's first tap ``base1[o]`` (nq,) in the second
        (a sample's taps are consecutive distinct taps); ``dense1[o]``: the axis-1
        taps are consecutive lattice points modulo n. Weights per axis: ``wa``
        (the kernel) and ``wb`` (kernel x signed distance, the gradient basis's
        ramp), ``wa0[o]`` (nj, taps) and ``wa1[o]`` (taps, nq) (:func:`pack_axis`).
        ``scales[o]``: the octave's amplitude. For dense axis-1 taps the last hash
        level is folded into a table run on past n (gradient: its two
        components; value: the values by parity row, as in
        ``LatticeNoise._hash_tables``), so a lattice row's values are a
        contiguous run of it. The flattened output (nj * nq,) is ``out64``
        (float64) or ``out32`` (float32), the other one empty (one compiled
        kernel for both dtypes): written, or with ``absval`` (turbulence) added to.

        The arithmetic is that of the general separable path (``hash_expand``,
        ``gather_gradients``, or the integer hash's ``block_values`` and
        ``block_gradients``, ``contract_last``, ``final_pass``), tap by tap and
        term by term in the same order, so the bits are the same. A lattice row
        ``r`` of octave ``o`` is hashed and contracted along axis 1 only when an
        output row first needs it, into a ring of ``2**ceil(log2 taps)`` rows per
        octave that stays in cache (rows are never held as a block in memory).
        The axis-1 contraction runs eight columns at a time (:func:`expand_dot8`)
        over the block's lattice values with the weights spread out to each
        column's offset (NaN elsewhere, which adds no term): it equals the
        tap sum bit for bit, a zero's sign included. The hot loops index flat arrays with
        unsigned offsets (no negative-index wrap: they vectorise) and make no array
        views (each costs an atomic reference count). Each sample depends only on its row
        and column, not on the tile, so any window is the same slice of the
        full grid, bit for bit.
        """
        noct, nj, taps = pos0.shape
        n = perm.shape[0]
        grad = GRAD
        # chosen here, not held in the closure: numba's cache key pickles the closure's values, and a
        # dispatcher pickles with a new id in every process (the cache never hit). numba prunes the
        # other choice before typing (GRAD is a constant).
        axis0 = _axis0_grad if GRAD else _axis0_value
        nterm = 2 if grad else 1
        S = 1
        while S < taps:
            S *= 2
        smask = S - 1
        L = 8
        tile = L if tile < L else tile  # (not min/max: each is one more overload to compile)
        tile = ((nq if nq < tile else tile) + L - 1) // L * L  # whole blocks of eight lanes (the ring rows are padded)
        ring = np.empty(noct * S * nterm * tile)  # rows (octave, slot, term) of tile columns
        tags = np.empty((noct, S), np.int64)
        bufs = np.empty(2 * tile)  # two running sums of a row (acc at 0, tmp at tile); no array is chosen at run
        # time in the loops below (each such choice costs an atomic reference count)
        width = 1
        for o in range(noct):
            cnt = off1[o + 1] - off1[o]
            width = cnt if cnt > width else width
        lmin = np.empty(noct, np.int64)
        lmax = np.empty(noct, np.int64)
        use_ext = False
        for o in range(noct):
            use_ext = use_ext or dense1[o]
        use_ext = use_ext and n <= 1 << 16
        ext_len = n + width
        # the extended tables (when used), then room for a row's lattice values hashed one by one
        vbase = 2 * ext_len if use_ext else 0
        ext = np.empty(vbase + 2 * width)
        if TABLE and use_ext:  # (TABLE a constant: the integer-hash variants compile no table code)
            for x in range(ext_len):
                xm = x % n
                h = perm[xm]
                if grad:
                    ext[x] = grads[h, 0]
                    ext[ext_len + x] = grads[h, 1]
                else:
                    ext[x] = values[x & 1, h]
                    ext[ext_len + x] = values[(1 + x) & 1, h]
        nblk_max = tile // L
        # widest block of eight columns, in lattice taps: (largest first-tap span within the block) + taps
        mmax = taps
        for o in range(noct):
            for qa in range(0, nq, L):
                lo_, hi_ = _row_range(base1, o, qa, qa + L if qa + L < nq else nq)
                mmax = hi_ - lo_ + taps if hi_ - lo_ + taps > mmax else mmax
        expand = mmax <= 4 * L  # else (columns sparser than the lattice) a plain per-column loop
        if not expand:
            mmax = 1
        # not filled here (np.full is one more overload to compile): each block's rows are set to NaN
        # below before its weights are written, and expand_dot8 reads no further
        E = np.empty(noct * nterm * nblk_max * mmax * L)
        bB = np.empty((noct, nblk_max), np.int64)
        bM = np.empty((noct, nblk_max), np.int64)
        u = np.uint64
        for q0 in range(0, nq, tile):
            q1 = q0 + tile if q0 + tile < nq else nq
            nt = q1 - q0
            for o in range(noct):
                lo, hi = _row_range(base1, o, q0, q1)
                lmin[o] = lo
                lmax[o] = hi + taps - 1
                for s in range(S):
                    tags[o, s] = -1
                if expand:
                    # the axis-1 weights spread out: block of 8 columns x (its taps), zero off each column's taps
                    for blk in range((nt + L - 1) // L):
                        qa = q0 + blk * L
                        qb = qa + L if qa + L < q1 else q1
                        lo_, hi_ = _row_range(base1, o, qa, qb)
                        mb = hi_ - lo_ + taps
                        bB[o, blk] = lo_ - lo
                        bM[o, blk] = mb
                        for b in range(nterm):
                            e0 = ((o * nterm + b) * nblk_max + blk) * mmax * L
                            wsrc = wb1 if b == 1 else wa1
                            for x in range(mb * L):
                                E[e0 + x] = np.nan  # no tap of this column (expand_dot8 adds nothing)
                            for q in range(qa, qb):
                                d = base1[o, q] - lo_
                                for k in range(taps):
                                    E[e0 + (d + k) * L + (q - qa)] = wsrc[o, k, q]
            for j in range(nj):
                for o in range(noct):
                    for k in range(taps):
                        r = pos0[o, j, k]
                        slot = r & smask
                        if tags[o, slot] == r:
                            continue
                        tags[o, slot] = r
                        # lattice row r: its values against this tile's axis-1 taps lo .. lo + m - 1
                        lo = lmin[o]
                        m = lmax[o] + 1 - lo
                        if INT:  # a constant: the table-hash variants compile none of this
                            # the integer hash's words: lat0 holds key ^ j_0 M_0, lat1 holds j_1 M_1
                            v0 = vbase
                            v1 = vbase + width
                            if grad:
                                int_row_gradients(ext, v0, v1, lat0[off0[o] + r], lat1, off1[o] + lo, m, grads)
                            else:
                                int_row_values(ext, v0, lat0[off0[o] + r], lat1, off1[o] + lo, m)
                        elif use_ext and dense1[o]:
                            i0 = lat0[off0[o] + r]
                            h1 = perm[i0]
                            p0 = i0 & 1
                            first = lat1[off1[o] + lo]
                            s0 = h1 + first
                            s0 = s0 - n if s0 >= n else s0
                            if grad:
                                v0 = s0
                                v1 = ext_len + s0
                            else:
                                v0 = ((p0 + first + s0) & 1) * ext_len + s0
                                v1 = v0
                        else:
                            i0 = lat0[off0[o] + r]
                            h1 = perm[i0]
                            p0 = i0 & 1
                            v0 = vbase
                            v1 = vbase + width
                            for l in range(m):
                                i1 = lat1[off1[o] + lo + l]
                                s = h1 + i1
                                s = s - n if s >= n else s
                                h = perm[s]
                                if grad:
                                    ext[v0 + l] = grads[h, 0]
                                    ext[v1 + l] = grads[h, 1]
                                else:
                                    ext[v0 + l] = values[(p0 + i1) & 1, h]
                        row0 = ((o * S + slot) * nterm) * tile
                        if expand:
                            for b in range(nterm):
                                vb = v1 if b == 1 else v0
                                ebase = (o * nterm + b) * nblk_max * mmax * L
                                for blk in range((nt + L - 1) // L):
                                    expand_dot8(ring, row0 + b * tile + blk * L, E, ebase + blk * mmax * L, ext,
                                                vb + bB[o, blk], bM[o, blk])
                        else:
                            # contract_last's sums, column by column
                            for b in range(nterm):
                                vb = v1 if b == 1 else v0
                                wsrc = wb1 if b == 1 else wa1
                                for q in range(nt):
                                    c = vb + base1[o, q0 + q] - lo
                                    sa = wsrc[o, 0, q0 + q] * ext[c]  # left to right, as contract_last sums
                                    for kk in range(1, taps):
                                        sa += wsrc[o, kk, q0 + q] * ext[c + kk]
                                    ring[row0 + b * tile + q] = sa
                # the axis-0 pass: octave by octave, each octave's terms in order, each a tap sum added to the
                # running sum (between two buffers; the last octave straight into the output row)
                ntu = u(nt)
                dy = u(tile if grad else 0)  # the second term's rows follow the first's
                for o in range(noct):
                    sc = scales[o]
                    rb = o * S * nterm * tile
                    x0 = u(rb + (pos0[o, j, 0] & smask) * nterm * tile)
                    x1 = u(rb + (pos0[o, j, 1 % taps] & smask) * nterm * tile)
                    x2 = u(rb + (pos0[o, j, 2 % taps] & smask) * nterm * tile)
                    x3 = u(rb + (pos0[o, j, 3 % taps] & smask) * nterm * tile)
                    if grad:
                        a0 = wb0[o, j, 0] * sc; a1 = wb0[o, j, 1 % taps] * sc
                        a2 = wb0[o, j, 2 % taps] * sc; a3 = wb0[o, j, 3 % taps] * sc
                    else:
                        a0 = wa0[o, j, 0] * sc; a1 = wa0[o, j, 1 % taps] * sc
                        a2 = wa0[o, j, 2 % taps] * sc; a3 = wa0[o, j, 3 % taps] * sc
                    b0 = wa0[o, j, 0] * sc; b1 = wa0[o, j, 1 % taps] * sc
                    b2 = wa0[o, j, 2 % taps] * sc; b3 = wa0[o, j, 3 % taps] * sc
                    if not absval and o == noct - 1:  # the last octave straight into the output row
                        if USE32:  # a constant: numba prunes the other branch, so compiles one output dtype
                            axis0(out32, u(j * nq + q0), bufs, u(0 if o % 2 == 1 else tile), o > 0, ring, ntu,
                                  taps, x0, x1, x2, x3, dy, a0, a1, a2, a3, b0, b1, b2, b3)
                        else:
                            axis0(out64, u(j * nq + q0), bufs, u(0 if o % 2 == 1 else tile), o > 0, ring, ntu,
                                  taps, x0, x1, x2, x3, dy, a0, a1, a2, a3, b0, b1, b2, b3)
                    else:
                        # turbulence: each octave into tmp, |.| summed into acc; else acc and tmp in turn (no
                        # array is chosen at run time: each choice costs an atomic reference count)
                        into_tmp = absval or o % 2 == 1
                        axis0(bufs, u(tile if into_tmp else 0), bufs, u(0 if into_tmp else tile),
                              o > 0 and not absval, ring, ntu, taps, x0, x1, x2, x3, dy,
                              a0, a1, a2, a3, b0, b1, b2, b3)
                        if absval and o == 0:
                            for q in range(nt):
                                bufs[q] = abs(bufs[tile + q])
                        elif absval:
                            for q in range(nt):
                                bufs[q] += abs(bufs[tile + q])
                if absval:
                    ob = j * nq + q0
                    if USE32:
                        for q in range(nt):
                            out32[ob + q] += bufs[q]
                    else:
                        for q in range(nt):
                            out64[ob + q] += bufs[q]

    return grid2d


_GRID2D = {}


def grid2d(lat0, off0, pos0, wa0, wb0, lat1, off1, base1, dense1, wa1, wb1, scales, perm, values, grads, basis,
           absval, out64, out32, nq, tile):
    """A 2-D grid of lattice noise, every octave fused (the compiled kernel for this basis, dtype and hash).

    The arguments and the result are those of the kernel :func:`_make_grid2d`
    compiles (its docstring): ``basis`` 0 (value) or 1 (gradient), the
    output float32 when ``out32`` is not empty, the integer hash when
    ``lat0`` holds its uint32 words (``_intgrid.grid2d`` makes them).
    Only the variant called is compiled.
    """
    key = (basis == 1, out32.shape[0] > 0, lat0.dtype == np.uint32)
    fn = _GRID2D.get(key)
    if fn is None:
        fn = _GRID2D[key] = _make_grid2d(*key)
    fn(lat0, off0, pos0, wa0, wb0, lat1, off1, base1, dense1, wa1, wb1, scales, perm, values, grads, basis,
       absval, out64, out32, nq, tile)


@nb.njit(cache=True, nogil=True, inline="always")
def _span(x):
    """``x.max() - x.min()`` (NaN if any is NaN, 0 if empty) as a loop: numba's max and min compile slowly."""
    if x.shape[0] == 0:
        return 0.0
    lo = x[0]
    hi = x[0]
    nan = False
    for j in range(x.shape[0]):
        v = x[j]
        nan = nan or v != v
        lo = v if v < lo else lo  # no NaN is left when the span is used
        hi = v if v > hi else hi
    return np.nan if nan else hi - lo


def _make_pack_axis(DERIV):
    """:func:`pack_axis`'s compiled kernel with ``deriv`` a constant (a plain grid never compiles
    :func:`axis_dweights`)."""

    @nb.njit(cache=True, nogil=True)
    def pack_axis(coords, freqs, phase, shift, left, taps, coef, dcoef, periods, n, grad, deriv, last):
        """Every octave's distinct taps and weights along one grid axis, packed for :func:`grid2d`.

        ``periods`` (O,): the lattice period of each octave along this axis
        (all equal, unless a tileable octave sum scales them by ``lacunarity**o``).

        Per octave: :func:`axis_weights` (or, with ``deriv``, :func:`axis_dweights`)
        and :func:`dense_taps`, as ``LatticeNoise._axis_taps`` computes them.
        Returns ``ok`` (False when an octave's taps span too many cells for
        :func:`dense_taps`: the caller then packs ``_axis_taps``' sparse result),
        ``lat`` (the distinct taps modulo n, octave after octave), ``off``
        (octave o's taps are ``lat[off[o]:off[o + 1]]``), ``pos`` (O, N, taps),
        ``base`` (O, N) = ``pos[:, :, 0]``, the weights ``wa``, ``wb`` (O, N, taps),
        or (O, taps, N) with ``last``, and ``dense`` (O,): the taps are
        consecutive lattice points modulo n (and the period a multiple of n).
        """
        noct = freqs.shape[0]
        nn = coords.shape[0]
        cap = noct * (4 * taps * nn + 64 + taps)
        lat = np.empty(cap, np.int64)
        off = np.empty(noct + 1, np.int64)  # (np.zeros: one more overload to compile)
        off[0] = 0
        pos = np.empty((noct, nn, taps), np.int64)
        base = np.empty((noct, nn), np.int64)
        if last:
            wa = np.empty((noct, taps, nn))
            wb = np.empty((noct, taps, nn))
        else:
            wa = np.empty((noct, nn, taps))
            wb = np.empty((noct, nn, taps))
        dense = np.empty(noct, np.bool_)  # every octave's entry is written before True is returned
        for o in range(noct):
            period = periods[o]
            fis, fbase, w, rw = axis_weights(coords, freqs[o], phase, shift, left, taps, coef, period, grad)
            if DERIV:  # a constant: numba prunes the call when False
                w, rw = axis_dweights(coords, freqs[o], phase, shift, left, taps, coef, dcoef, grad)
            span = _span(fis)
            if not span <= 4 * taps * nn + 64:
                return False, lat[:0], off, pos, base, wa, wb, dense
            lattice, p = dense_taps(fis, fbase, taps, period)
            cnt = lattice.shape[0]
            consecutive = period % n == 0
            for i in range(cnt):
                lat[off[o] + i] = lattice[i] % n
                if i > 0 and (lattice[i] - lattice[i - 1]) % period != 1:
                    consecutive = False
            off[o + 1] = off[o] + cnt
            dense[o] = consecutive
            for j in range(nn):
                base[o, j] = p[j, 0]
                for k in range(taps):
                    pos[o, j, k] = p[j, k]
                    if last:
                        wa[o, k, j] = w[j, k]
                        wb[o, k, j] = rw[j, k]
                    else:
                        wa[o, j, k] = w[j, k]
                        wb[o, j, k] = rw[j, k]
        return True, lat[:off[noct]], off, pos, base, wa, wb, dense

    return pack_axis


_PACK_AXIS = {}


def pack_axis(coords, freqs, phase, shift, left, taps, coef, dcoef, periods, n, grad, deriv, last):
    """Every octave's distinct taps and weights along one grid axis, packed for :func:`grid2d`.

    The arguments and results of the kernel :func:`_make_pack_axis` compiles
    for this ``deriv`` (its docstring).
    """
    key = bool(deriv)
    fn = _PACK_AXIS.get(key)
    if fn is None:
        fn = _PACK_AXIS[key] = _make_pack_axis(key)
    return fn(coords, freqs, phase, shift, left, taps, coef, dcoef, periods, n, grad, deriv, last)
