"""numba kernels for lattice noise (compiled once, cached on disk).

Two hot loops:

- :func:`eval_points`: scattered points. Every point splits each coordinate
  into a lattice index and a fraction, evaluates the tap weights, and walks
  the ``taps**d`` lattice neighbours with the nested permutation hash
  ``h_{a+1} = P[(h_a + j_a) mod n]`` (Phillips 2.4.1), summing weight x value.
  Several octaves (fractal sums) are fused into one pass over the points.
- :func:`contract`: one separable pass of the grid path,
  ``out[p, j, q] (+)= scale * sum_k w[j, k] * inp[p, pos[j, k], q]``, which
  applies one axis of the tensor-product kernel to a block of lattice values.

All arithmetic is float64; only the final store may round to float32. The
specialisations are kept few (float32 / float64 output) so that a cold cache
compiles quickly.
"""
from __future__ import annotations

import math

import numba as nb
import numpy as np

# Beyond 2**52 a float64 has no fractional bits; beyond 2**62 it no longer
# fits an int64. Lattice indices are reduced modulo the period with fmod
# (exact for floats) before any conversion to int64.
_INT_SAFE = 4.0e15


@nb.njit(cache=True, nogil=True, inline="always")
def _reduce(fi, left, period):
    """(floor index - left) mod period, exact for any finite float ``fi``."""
    if fi < _INT_SAFE and fi > -_INT_SAFE:
        b = np.int64(fi) - left
    else:
        b = np.int64(fi % float(period)) - left
    b = b % period
    if b < 0:
        b += period
    return b


@nb.njit(cache=True, nogil=True)
def eval_points(pts, out, freqs, amps, phase, shift, left, taps, coef, period,
                perms, values, grads, basis, absval):
    """Evaluate (fractal sums of) lattice noise at scattered points.

    Parameters
    ----------
    pts : (N, d) float64
    out : (N, C) float32 or float64, written (not accumulated)
    freqs : (O, d) float64, per-octave per-axis frequency
    amps : (O,) float64, per-octave amplitude (including range normalisation)
    phase : (d,) float64
    shift, left, taps, coef : the kernel (see ``kernels.Kernel``)
    period : (d,) int64, lattice period per axis
    perms : (C, n) int64, one permutation per output component
    values : (2, n) float64, value table by lattice parity (both rows equal
        unless the sign alternates with the lattice position)
    grads : (n, d) float64 unit gradients (gradient basis only)
    basis : 0 value noise, 1 gradient noise
    absval : sum |octave| (turbulence) instead of octave
    """
    npts, d = pts.shape
    ncomp = perms.shape[0]
    n = perms.shape[1]
    noct = freqs.shape[0]
    w = np.empty((d, 4))
    r = np.empty((d, 4))
    base = np.empty(d, np.int64)
    cnt = np.zeros(d, np.int64)
    hs = np.zeros(d + 1, np.int64)
    par = np.zeros(d + 1, np.int64)
    prod = np.ones(d + 1)
    acc = np.zeros(ncomp)
    for p in range(npts):
        for c in range(ncomp):
            acc[c] = 0.0
        for o in range(noct):
            for a in range(d):
                u = pts[p, a] * freqs[o, a] + phase[a] + shift
                fi = math.floor(u)
                t = u - fi
                for k in range(taps):
                    s = coef[k, 5]
                    for q in range(4, -1, -1):
                        s = s * t + coef[k, q]
                    w[a, k] = s
                    r[a, k] = t - shift + (left - k)
                base[a] = _reduce(fi, left, period[a])
            for c in range(ncomp):
                # odometer over the taps**d neighbours, re-hashing only the
                # levels whose tap changed
                for a in range(d):
                    cnt[a] = 0
                level = 0
                total = 0.0
                while True:
                    for a in range(level, d):
                        j = base[a] + cnt[a]
                        if j >= period[a]:
                            j -= period[a]
                            if j >= period[a]:
                                j = j % period[a]
                        s_ = hs[a] + j
                        if s_ >= n:
                            s_ = s_ % n
                        hs[a + 1] = perms[c, s_]
                        par[a + 1] = par[a] + j
                        prod[a + 1] = prod[a] * w[a, cnt[a]]
                    h = hs[d]
                    if basis == 0:
                        total += prod[d] * values[par[d] & 1, h]
                    else:
                        dot = 0.0
                        for a in range(d):
                            dot += grads[h, a] * r[a, cnt[a]]
                        total += prod[d] * dot
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
                if absval:
                    acc[c] += amps[o] * abs(total)
                else:
                    acc[c] += amps[o] * total
        for c in range(ncomp):
            out[p, c] = acc[c]


@nb.njit(cache=True, nogil=True)
def axis_weights(coords, freq, phase, shift, left, taps, coef, period, grad):
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
        fi = math.floor(u)
        t = u - fi
        fis[j] = fi
        base[j] = _reduce(fi, left, period)
        for k in range(taps):
            s = coef[k, 5]
            for q in range(4, -1, -1):
                s = s * t + coef[k, q]
            w[j, k] = s
            if grad:
                rw[j, k] = s * (t - shift + (left - k))
    return fis, base, w, rw


@nb.njit(cache=True, nogil=True)
def contract(inp, pos, w, out, scale, mode):
    """One separable pass: ``out[p, j, q] (=, +=, += |.|) scale * sum_k w[j, k] inp[p, pos[j, k], q]``.

    ``mode`` 0 writes, 1 adds, 2 adds the absolute value. The sum over k runs
    in a fixed order, so any subset of rows j gives bit-identical results.
    """
    npre, _, npost = inp.shape
    nj, taps = w.shape
    tmp = np.empty(npost)
    for p in range(npre):
        for j in range(nj):
            w0 = w[j, 0] * scale
            r0 = inp[p, pos[j, 0]]
            for q in range(npost):
                tmp[q] = w0 * r0[q]
            for k in range(1, taps):
                wk = w[j, k] * scale
                rk = inp[p, pos[j, k]]
                for q in range(npost):
                    tmp[q] += wk * rk[q]
            o = out[p, j]
            if mode == 0:
                for q in range(npost):
                    o[q] = tmp[q]
            elif mode == 1:
                for q in range(npost):
                    o[q] += tmp[q]
            else:
                for q in range(npost):
                    o[q] += abs(tmp[q])
