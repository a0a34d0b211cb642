"""The compiled kernels of sparse Gabor noise: impulses from the hash, and their sum at points or on a grid.

Every kernel and helper here is numba with ``cache=True`` and runs as plain
Python under ``NUMBA_DISABLE_JIT=1`` with the same values (the callers run
them inside ``np.errstate(over="ignore")``: uint32 arithmetic wraps on
purpose). All arithmetic is float64; only the final store may round to float32.

Internally every noise has three axes ``(0, 1, 2)``: ``(z, y, x)`` for a 3-D
field, ``(t, y, x)`` for moving kernels, and for a 2-D field axis 0 is absent
(``DIM == 2``: one layer of cells, ``d0 = 0``). An impulse of cell
``(j0, j1, j2)`` with index ``k`` has

- position ``p_a = (j_a + u_a) * cell_a`` (``u_a`` uniform in (0, 1) from the hash),
- weight ``w`` uniform in [-1, 1), phase ``phi`` uniform in [0, 2 pi),
- a row ``m`` of the frequency table ``freqs`` (cycles per unit) and of the
  velocity table ``vel`` (units of axes 1, 2 per unit of axis 0; zero for a
  still field),

and adds at the point ``q`` (``d0 = q0 - p0``, ``d_a = (q_a - p_a) - v_a d0``)

    ``w K prod_a exp(-pi (s_a d_a)**2) cos(2 pi sum_a f_a d_a + phi)``

when ``sum_a (s_a d_a)**2 < rho2`` (the truncation), written as the real part
of the complex product ``A R0 R1 R2`` with ``A = w K e^{i phi}`` and
``R_a = exp(-pi (s_a d_a)**2) e^{2 pi i f_a d_a}``, always multiplied in
that order, so that the point kernel and the grid kernel (which computes each
``R_a`` once per row or column) give the same bits. Both visit the cells in
lexicographic order and the impulses of a cell by index, and add each
contribution to a float64 sum in that order.
"""
from __future__ import annotations

import math

import numba as nb
import numpy as np

from ..lattice.hashing import mix32, prime

_U32 = np.uint32
_U64 = np.uint64
_LOW32 = np.int64(0xFFFFFFFF)
_GOLD = np.uint32(0x9E3779B9)
_GOLD2 = np.uint32(0x7F4A7C15)
_COUNT_SALT = np.uint32(0x5BD1E995)
_S32 = np.uint64(32)
_UNIT = 1.0 / 4294967296.0  # 2**-32
_TWO_PI = 2.0 * math.pi
MAX_COUNT = 4096  # the most impulses one cell may hold (the mean is checked far below it)
# A fingerprint of the lattice hash these kernels call (``mix32`` and ``prime`` on fixed inputs, and
# ``MULT``; tests/test_gabor.py recomputes it). numba's cache keys a kernel on its own file only, so
# a change to the hash in ``noiselab/lattice/_jit.py`` alone would leave the compiled Gabor kernels
# of this file stale in the cache: the test then fails until this line is updated, and the edit of
# this file is what makes numba recompile them.
HASH_FINGERPRINT = "6602aa104feb71df"


@nb.njit(cache=True, nogil=True)
def cell_word(key, j0, j1, j2, mults):
    """The cell's 32-bit word: ``mix32(key ^ prime(j0) ^ prime(j1) ^ prime(j2))`` (indices mod 2**32)."""
    h = _U32(key ^ prime(_U32(j0 & _LOW32), mults[0]))
    h = _U32(h ^ prime(_U32(j1 & _LOW32), mults[1]))
    h = _U32(h ^ prime(_U32(j2 & _LOW32), mults[2]))
    return mix32(h)


@nb.njit(cache=True, nogil=True)
def draw(base, j):
    """The ``j``-th uniform in (0, 1) of an impulse's word."""
    return (np.float64(mix32(_U32(base + _U32(_U32(j) * _GOLD2)))) + 0.5) * _UNIT


@nb.njit(cache=True, nogil=True)
def impulse_word(h, k):
    """The word of impulse ``k`` of the cell word ``h``."""
    return mix32(_U32(h ^ mix32(_U32(_U32(k + 1) * _GOLD))))


@nb.njit(cache=True, nogil=True)
def poisson_count(h, mean):
    """The cell's number of impulses: Poisson(``mean``) by inversion of one uniform from the cell word."""
    u = (np.float64(mix32(_U32(h ^ _COUNT_SALT))) + 0.5) * _UNIT
    p = math.exp(-mean)
    s = p
    n = 0
    while u > s and n < MAX_COUNT:
        n += 1
        p = p * mean / n
        s = s + p
    return n


@nb.njit(cache=True, nogil=True)
def impulse(h, k, j0, j1, j2, cell, nrows):
    """Impulse ``k`` of cell ``(j0, j1, j2)``: position, weight, phase and table row."""
    b = impulse_word(h, k)
    p0 = (np.float64(j0) + draw(b, 0)) * cell[0]
    p1 = (np.float64(j1) + draw(b, 1)) * cell[1]
    p2 = (np.float64(j2) + draw(b, 2)) * cell[2]
    w = 2.0 * draw(b, 3) - 1.0
    phi = _TWO_PI * draw(b, 4)
    m = np.int64((_U64(mix32(_U32(b + _U32(_U32(5) * _GOLD2)))) * _U64(nrows)) >> _S32)
    return p0, p1, p2, w, phi, m


@nb.njit(cache=True, nogil=True)
def factor(d, s, f):
    """``exp(-pi (s d)**2) e^{2 pi i f d}`` as (real, imaginary), and ``(s d)**2``."""
    q = (s * d) * (s * d)
    e = math.exp(-math.pi * q)
    th = _TWO_PI * (f * d)
    return e * math.cos(th), e * math.sin(th), q


@nb.njit(cache=True, nogil=True)
def cell_range(lo, hi, size):
    """The cell indices ``floor(lo / size) .. floor(hi / size)``."""
    return np.int64(math.floor(lo / size)), np.int64(math.floor(hi / size))


def _make_points(DIM):
    @nb.njit(cache=True, nogil=True)
    def points_kernel(pts, out, key, mults, cell, reach, mean, scale, rho2, amp, freqs, vel):
        """Sum the impulses at each point of ``pts`` (``(n, 3)``, axis 0 ignored in 2-D) into ``out``."""
        nrows = freqs.shape[0]
        for i in range(pts.shape[0]):
            q0 = pts[i, 0] if DIM == 3 else 0.0
            q1 = pts[i, 1]
            q2 = pts[i, 2]
            if DIM == 3:
                a0, b0 = cell_range(q0 - reach[0], q0 + reach[0], cell[0])
            else:
                a0, b0 = 0, 0
            a1, b1 = cell_range(q1 - reach[1], q1 + reach[1], cell[1])
            a2, b2 = cell_range(q2 - reach[2], q2 + reach[2], cell[2])
            acc = 0.0
            for j0 in range(a0, b0 + 1):
                for j1 in range(a1, b1 + 1):
                    for j2 in range(a2, b2 + 1):
                        h = cell_word(key, j0, j1, j2, mults)
                        n = poisson_count(h, mean)
                        for k in range(n):
                            p0, p1, p2, w, phi, m = impulse(h, k, j0, j1, j2, cell, nrows)
                            if DIM == 3:
                                d0 = q0 - p0
                                r0r, r0i, s0 = factor(d0, scale[0], freqs[m, 0])
                            else:
                                d0 = 0.0
                                r0r, r0i, s0 = 1.0, 0.0, 0.0
                            if s0 >= rho2:
                                continue
                            d1 = (q1 - p1) - vel[m, 0] * d0
                            d2 = (q2 - p2) - vel[m, 1] * d0
                            s1 = (scale[1] * d1) * (scale[1] * d1)
                            s2 = (scale[2] * d2) * (scale[2] * d2)
                            if (s0 + s1) + s2 >= rho2:
                                continue
                            r1r, r1i, _ = factor(d1, scale[1], freqs[m, 1])
                            r2r, r2i, _ = factor(d2, scale[2], freqs[m, 2])
                            ar = (w * amp) * math.cos(phi)
                            ai = (w * amp) * math.sin(phi)
                            pr = ar * r0r - ai * r0i
                            pi_ = ar * r0i + ai * r0r
                            qr = pr * r1r - pi_ * r1i
                            qi = pr * r1i + pi_ * r1r
                            acc += qr * r2r - qi * r2i
            out[i] = acc

    return points_kernel


def _make_grid(DIM):
    @nb.njit(cache=True, nogil=True)
    def grid_kernel(out, origin, step, off, key, mults, cell, reach, mean, scale, rho2, amp, freqs, vel, acc,
                    f1r, f1i, g1, f2r, f2i, g2):
        """Sum the impulses on the grid ``origin + (i + off) * step`` (``out``: (n0, n1, n2); n0 = 1 in 2-D) by splatting.

        ``acc`` is a float64 scratch of ``out``'s shape; ``f1r``.. ``g2`` per-row and per-column scratch.
        """
        n0, n1, n2 = acc.shape
        acc[:] = 0.0
        # the block's first sample along each axis (the kernel's coordinates are origin + (i + off) * step)
        b0o = origin[0] + off[0] * step[0]
        b1o = origin[1] + off[1] * step[1]
        b2o = origin[2] + off[2] * step[2]
        if DIM == 3:
            a0, b0 = cell_range(b0o - reach[0], b0o + (n0 - 1) * step[0] + reach[0], cell[0])
        else:
            a0, b0 = 0, 0
        a1, b1 = cell_range(b1o - reach[1], b1o + (n1 - 1) * step[1] + reach[1], cell[1])
        a2, b2 = cell_range(b2o - reach[2], b2o + (n2 - 1) * step[2] + reach[2], cell[2])
        nrows = freqs.shape[0]
        rmax = math.sqrt(rho2)
        for j0 in range(a0, b0 + 1):
            for j1 in range(a1, b1 + 1):
                for j2 in range(a2, b2 + 1):
                    h = cell_word(key, j0, j1, j2, mults)
                    n = poisson_count(h, mean)
                    for k in range(n):
                        p0, p1, p2, w, phi, m = impulse(h, k, j0, j1, j2, cell, nrows)
                        ar = (w * amp) * math.cos(phi)
                        ai = (w * amp) * math.sin(phi)
                        if DIM == 3:
                            # the layers i0 this impulse may reach: |s0 d0| < rmax (one index of slack each side)
                            i0lo = max(0, np.int64(math.floor((p0 - rmax / scale[0] - b0o) / step[0])) - 1)
                            i0hi = min(n0 - 1, np.int64(math.floor((p0 + rmax / scale[0] - b0o) / step[0])) + 1)
                        else:
                            i0lo, i0hi = 0, 0
                        for i0 in range(i0lo, i0hi + 1):
                            if DIM == 3:
                                q0 = origin[0] + (i0 + off[0]) * step[0]
                                d0 = q0 - p0
                                r0r, r0i, s0 = factor(d0, scale[0], freqs[m, 0])
                            else:
                                d0 = 0.0
                                r0r, r0i, s0 = 1.0, 0.0, 0.0
                            if s0 >= rho2:
                                continue
                            pr = ar * r0r - ai * r0i
                            pi_ = ar * r0i + ai * r0r
                            # the moving centre on this layer, and the rows and columns within reach
                            c1 = p1 + vel[m, 0] * d0
                            c2 = p2 + vel[m, 1] * d0
                            # the cut ellipsoid's section on this layer: radius sqrt(rho2 - s0) in cells
                            rem = math.sqrt(rho2 - s0)
                            half1 = rem / scale[1]
                            half2 = rem / scale[2]
                            i1lo = max(0, np.int64(math.floor((c1 - half1 - b1o) / step[1])) - 1)
                            i1hi = min(n1 - 1, np.int64(math.floor((c1 + half1 - b1o) / step[1])) + 1)
                            i2lo = max(0, np.int64(math.floor((c2 - half2 - b2o) / step[2])) - 1)
                            i2hi = min(n2 - 1, np.int64(math.floor((c2 + half2 - b2o) / step[2])) + 1)
                            if i1lo > i1hi or i2lo > i2hi:
                                continue
                            for i1 in range(i1lo, i1hi + 1):
                                q1 = origin[1] + (i1 + off[1]) * step[1]
                                d1 = (q1 - p1) - vel[m, 0] * d0
                                s1 = (scale[1] * d1) * (scale[1] * d1)
                                g1[i1] = s1
                                if s0 + s1 < rho2:
                                    r1r, r1i, _ = factor(d1, scale[1], freqs[m, 1])
                                    f1r[i1] = pr * r1r - pi_ * r1i
                                    f1i[i1] = pr * r1i + pi_ * r1r
                            for i2 in range(i2lo, i2hi + 1):
                                q2 = origin[2] + (i2 + off[2]) * step[2]
                                d2 = (q2 - p2) - vel[m, 1] * d0
                                s2 = (scale[2] * d2) * (scale[2] * d2)
                                g2[i2] = s2
                                f2r[i2], f2i[i2], _ = factor(d2, scale[2], freqs[m, 2])
                            for i1 in range(i1lo, i1hi + 1):
                                t01 = s0 + g1[i1]
                                if t01 >= rho2:
                                    continue
                                qr = f1r[i1]
                                qi = f1i[i1]
                                # the columns inside the cut form one run (g2 grows with |d2|, rounding
                                # included): find its ends, then add without a test (a loop LLVM vectorises)
                                lo = i2lo
                                while lo <= i2hi and t01 + g2[lo] >= rho2:
                                    lo += 1
                                hi = i2hi
                                while hi >= lo and t01 + g2[hi] >= rho2:
                                    hi -= 1
                                row = acc[i0, i1]
                                for i2 in range(lo, hi + 1):
                                    row[i2] += qr * f2r[i2] - qi * f2i[i2]
        for i0 in range(n0):
            for i1 in range(n1):
                for i2 in range(n2):
                    out[i0, i1, i2] = acc[i0, i1, i2]

    return grid_kernel


_CACHE = {}


def points_kernel(dim):
    """The point kernel of a 2-D or 3-D noise (made once, kept)."""
    key = ("points", dim)
    if key not in _CACHE:
        _CACHE[key] = _make_points(dim)
    return _CACHE[key]


def grid_kernel(dim):
    """The grid kernel of a 2-D or 3-D noise (made once, kept)."""
    key = ("grid", dim)
    if key not in _CACHE:
        _CACHE[key] = _make_grid(dim)
    return _CACHE[key]
