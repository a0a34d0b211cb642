"""What limits lattice noise on scattered 3-D points: lower bounds measured beside noiselab and pyfastnoisesimd.

noiselab's target is pyfastnoisesimd's speed on 1e6 random 3-D points; noiselab's
table hash reaches 0.1-0.4x of it and the integer hash 0.5-0.8x
(``bench_lattice.md``). This script times, in the same interleaved rounds,
three kernels that do *less* than noiselab's and so bound what any
implementation of the same construction can reach here:

- ``lookups``: the table hash's memory reads alone. Phillips' construction
  hashes a corner ``(i, j, k)`` as ``perm[perm[perm[i] + j] + k]`` and reads
  its value from a table. The fewest reads it can take: the first two
  levels from one precombined ``n x n`` table and the last level folded
  into the values (:func:`noiselab.lattice._jit.pair_tables`): for quintic value noise (2 taps an
  axis) 4 reads of the 128 KiB pair table and 8 value reads a point, the
  value addresses depending on the pair reads. The kernel does exactly
  these reads, on tables built from noiselab's, and sums the eight values:
  no weights, no fractional parts.
  ``lookups-gradient`` does the same reads for gradient noise (8 gradient
  rows of 3 instead of 8 values) and ``lookups-4taps`` for a 4-tap kernel
  (Catmull-Rom: 16 pair-table reads, 64 values). noiselab's block kernel
  (:func:`noiselab.lattice._jit.table_block_kernel`) makes exactly these
  reads, from the same folded tables (:func:`noiselab.lattice._jit.pair_tables`),
  so each stays a lower bound for it, and for any kernel making the table
  hash's reads.
- ``table-kernel``: noiselab's table-hash block kernel called directly on the
  points (no wrapper: no input checks, no allocation of the output, no
  folded tables to look up); ``table-setup``: only its per-axis arithmetic
  (:func:`noiselab.lattice._jit._table_axis`: weights and taps of the three
  axes, block by block, no table read), summed into the output: what the
  bits' float64 arithmetic costs before the first read.
- ``int-minimal``: the shortest integer-hash value noise numba compiles:
  float32 in and out, floor, quintic fade, the eight corners hashed with
  noiselab's formula (``mix32(key ^ i M0 ^ j M1 ^ k M2)``), trilinear blend; no
  period, no exact split, no chunking. What numba and LLVM make of the
  simplest loop with the same arithmetic.
- ``int-minimal64``: ``int-minimal`` in float64 arithmetic (float32 in and
  out, each coordinate widened as read): what the same loop costs at 8
  float64 lanes instead of 16 float32 ones.
- ``int-same64``: the float64 bound of noiselab's own integer hash: a plain
  per-point numba loop with exactly noiselab's operations in noiselab's order
  (``x f + phase + shift``, the index modulo 2**32 in float64, both taps'
  weight polynomials from the kernel's coefficients, the eight corners as
  ``((w0 w1) w2) v`` summed in odometer order, the scale, one rounding to
  float32), no wrapper: no checks, no layouts, no octaves, no threads. Its
  output is checked bit for bit against noiselab's before timing.
- ``integer-columns``: noiselab's integer hash on the same points given as
  ``(3, N)`` columns (``axis=0``, structure of arrays as ``int-minimal``).
- the write floor (``np.full``) as everywhere in the benchmarks.

A second table times noiselab's opt-in float32 arithmetic
(``evaluate(pts32, arithmetic="float32")``, integer hash) beside
pyfastnoisesimd for quintic value (``Value``), quintic gradient (``Perlin``)
and Catmull-Rom value (``Cubic``), from ``(N, 3)`` rows and ``(3, N)``
columns, with the float64 arithmetic's rows for reference, and where its
time goes: its kernel alone, the same kernel made to take its float64 index
pass (the fallback for points out of float32 reach) in every block, and
``int-minimal`` in the same rounds; ``--f32-error``
instead measures the float32 arithmetic's largest difference from the
float64 result (1e6 points, 1-3-D, at 1e3 and at 1e12).

Run: ``benchmarks/.venv-peers/bin/python benchmarks/bench_limits.py [--repeats 7]``;
writes ``benchmarks/bench_limits.md``, the error table included (``--f32-error``: prints only it).
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numba as nb
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from bench_lattice import _fns_points, _peer  # noqa: E402  (pyfastnoisesimd as bench_lattice runs it)
from noiselab import LatticeNoise  # noqa: E402
from noiselab.lattice import _jit, points_path  # noqa: E402
from noiselab.lattice._jit import BLOCK, _table_axis, pair_tables, table_block_kernel  # noqa: E402
from noiselab.lattice.tables import axis_multipliers  # noqa: E402
from noiselab.lab.measure import interleaved, run_info  # noqa: E402

NPTS = 1_000_000
_M0, _M1, _M2 = np.uint32(0x9E3779B9), np.uint32(0x3C6EF373), np.uint32(0xDAA66D2D)
_C1, _C2 = np.uint32(0x85EBCA6B), np.uint32(0xC2B2AE35)
_S16, _S13 = np.uint32(16), np.uint32(13)
_U32 = np.uint32


def _make_lookups(TAPS, GRAD):
    """The reads of noiselab's 3-D table-hash kernel and nothing else, ``TAPS`` (2 or 4, compile-time) taps a side.

    Per point ``TAPS**2`` pair-table reads and ``TAPS**3`` value reads (``GRAD``: gradient rows, 3 components
    each, summed): for quintic value noise 4 and 8. The loops' trip counts are constants, as in the kernel,
    so LLVM unrolls them: the fastest any kernel making these reads can be.
    """
    @nb.njit(nogil=True)
    def lookups(pts, h2, tl, out):
        for p in range(pts.shape[0]):
            i0 = np.int64(np.floor(pts[p, 0])) & 255
            i1 = np.int64(np.floor(pts[p, 1])) & 255
            k = np.int64(np.floor(pts[p, 2])) & 255
            s = 0.0
            for a in range(TAPS):
                row = ((i0 + a) & 255) * 256
                for b in range(TAPS):
                    h = np.int64(h2[row + ((i1 + b) & 255)]) + k
                    # the row's reads summed as a tree (a serial chain of adds would bound the loop, not the reads)
                    if GRAD:
                        s += (tl[h, 0] + tl[h, 1] + tl[h, 2]) + (tl[h + 1, 0] + tl[h + 1, 1] + tl[h + 1, 2])
                    elif TAPS == 2:
                        s += tl[h] + tl[h + 1]
                    else:
                        s += (tl[h] + tl[h + 1]) + (tl[h + 2] + tl[h + 3])
            out[p] = s
    return lookups


table_lookups = _make_lookups(2, False)
table_lookups_gradient = _make_lookups(2, True)  # (2 taps)
table_lookups4 = _make_lookups(4, False)


@nb.njit(nogil=True)
def table_setup(pts, f, ph, shift, left, coef, n, out):
    """The per-axis arithmetic of noiselab's 2-tap table block kernel alone (no reads), summed per point."""
    X = np.empty((3, BLOCK))
    W = np.empty((3, 2, BLOCK))
    R = np.empty((3, 1, 1))
    J = np.empty((3, 2, BLOCK), np.int64)
    for p0 in range(0, pts.shape[0], BLOCK):
        m = min(BLOCK, pts.shape[0] - p0)
        for i in range(m):
            for a in range(3):
                X[a, i] = pts[p0 + i, a]
        for a in range(3):
            _table_axis(X[a], m, f[a], ph[a], shift, left, coef, n, W[a], R[a], J[a], 2, False)
        o = out[p0:p0 + m]
        for i in range(m):
            o[i] = (W[0, 0, i] + W[1, 1, i]) + (W[2, 0, i] + np.float64(J[0, 1, i] + J[1, 0, i] + J[2, 1, i]))


@nb.njit(inline="always")
def _corner(key, a, b, c):
    h = _U32(key ^ _U32(a * _M0) ^ _U32(b * _M1) ^ _U32(c * _M2))
    h = _U32(h ^ (h >> _S16))
    h = _U32(h * _C1)
    h = _U32(h ^ (h >> _S13))
    h = _U32(h * _C2)
    return np.float32(np.int32(h)) * np.float32(4.656612873077393e-10)


@nb.njit(inline="always")
def _fade(t):
    return t * t * t * (t * (t * np.float32(6.0) - np.float32(15.0)) + np.float32(10.0))


@nb.njit(nogil=True)
def int_minimal(x, y, z, key, out):
    """The shortest integer-hash quintic value noise: float32 structure-of-arrays in, float32 out."""
    for p in range(x.shape[0]):
        fx, fy, fz = np.floor(x[p]), np.floor(y[p]), np.floor(z[p])
        tx, ty, tz = _fade(x[p] - fx), _fade(y[p] - fy), _fade(z[p] - fz)
        i, j, k = _U32(np.int32(fx)), _U32(np.int32(fy)), _U32(np.int32(fz))
        i1, j1, k1 = _U32(i + _U32(1)), _U32(j + _U32(1)), _U32(k + _U32(1))
        v00 = _corner(key, i, j, k) + tz * (_corner(key, i, j, k1) - _corner(key, i, j, k))
        v01 = _corner(key, i, j1, k) + tz * (_corner(key, i, j1, k1) - _corner(key, i, j1, k))
        v10 = _corner(key, i1, j, k) + tz * (_corner(key, i1, j, k1) - _corner(key, i1, j, k))
        v11 = _corner(key, i1, j1, k) + tz * (_corner(key, i1, j1, k1) - _corner(key, i1, j1, k))
        v0 = v00 + ty * (v01 - v00)
        v1 = v10 + ty * (v11 - v10)
        out[p] = v0 + tx * (v1 - v0)


@nb.njit(inline="always")
def _mix_unit64(h):
    """noiselab's lattice value of a hashed word, in float64: ``int32(mix32(h)) / 2**31``."""
    h = _U32(h ^ (h >> _S16))
    h = _U32(h * _C1)
    h = _U32(h ^ (h >> _S13))
    h = _U32(h * _C2)
    return np.float64(np.int32(h)) * 4.656612873077393e-10


@nb.njit(inline="always")
def _corner64(key, a, b, c):
    return _mix_unit64(_U32(key ^ _U32(a * _M0) ^ _U32(b * _M1) ^ _U32(c * _M2)))


@nb.njit(inline="always")
def _fade64(t):
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0)


@nb.njit(nogil=True)
def int_minimal64(x, y, z, key, out):
    """``int_minimal`` in float64 arithmetic: float32 structure-of-arrays in, float32 out."""
    for p in range(x.shape[0]):
        X, Y, Z = np.float64(x[p]), np.float64(y[p]), np.float64(z[p])
        fx, fy, fz = np.floor(X), np.floor(Y), np.floor(Z)
        tx, ty, tz = _fade64(X - fx), _fade64(Y - fy), _fade64(Z - fz)
        i, j, k = _U32(np.int64(fx)), _U32(np.int64(fy)), _U32(np.int64(fz))
        i1, j1, k1 = _U32(i + _U32(1)), _U32(j + _U32(1)), _U32(k + _U32(1))
        v00 = _corner64(key, i, j, k) + tz * (_corner64(key, i, j, k1) - _corner64(key, i, j, k))
        v01 = _corner64(key, i, j1, k) + tz * (_corner64(key, i, j1, k1) - _corner64(key, i, j1, k))
        v10 = _corner64(key, i1, j, k) + tz * (_corner64(key, i1, j, k1) - _corner64(key, i1, j, k))
        v11 = _corner64(key, i1, j1, k) + tz * (_corner64(key, i1, j1, k1) - _corner64(key, i1, j1, k))
        v0 = v00 + ty * (v01 - v00)
        v1 = v10 + ty * (v11 - v10)
        out[p] = np.float32(v0 + tx * (v1 - v0))


@nb.njit(inline="always")
def _taps64(x, ph, shift, left, mult, c):
    """One axis as noiselab computes it for a 2-tap kernel: both weights and both hashed offsets."""
    u = np.float64(x) + ph + shift
    fi = np.floor(u)
    t = u - fi
    j = _U32(np.int64(fi - np.floor(fi * 2.3283064365386963e-10) * 4294967296.0) - left)
    t2 = t * t
    t3 = t2 * t
    t4 = t2 * t2
    t5 = t4 * t
    w0 = (c[0, 0] + c[0, 1] * t) + (c[0, 2] * t2 + c[0, 3] * t3) + (c[0, 4] * t4 + c[0, 5] * t5)
    w1 = (c[1, 0] + c[1, 1] * t) + (c[1, 2] * t2 + c[1, 3] * t3) + (c[1, 4] * t4 + c[1, 5] * t5)
    return w0, w1, _U32(j * mult), _U32(_U32(j + _U32(1)) * mult)


@nb.njit(nogil=True)
def int_same64(x, y, z, ph, shift, left, mult, coef, key, scale, out):
    """noiselab's float64 arithmetic for 3-D 2-tap value noise, point by point: its float32 output, bit for bit."""
    for p in range(x.shape[0]):
        a0, a1, ma0, ma1 = _taps64(x[p], ph[0], shift, left, mult[0], coef)
        b0, b1, mb0, mb1 = _taps64(y[p], ph[1], shift, left, mult[1], coef)
        c0, c1, mc0, mc1 = _taps64(z[p], ph[2], shift, left, mult[2], coef)
        total = 0.0
        for i in range(2):
            wa = a0 if i == 0 else a1
            ha = _U32(key ^ (ma0 if i == 0 else ma1))
            for j in range(2):
                w = wa * (b0 if j == 0 else b1)
                h = _U32(ha ^ (mb0 if j == 0 else mb1))
                total += (w * c0) * _mix_unit64(_U32(h ^ mc0))
                total += (w * c1) * _mix_unit64(_U32(h ^ mc1))
        out[p] = np.float32(scale * total)


def measure(repeats):
    rng = np.random.default_rng(0)
    pts32 = rng.uniform(0.0, 100.0, (NPTS, 3)).astype(np.float32)
    pts = pts32.astype(np.float64)
    soa = [np.ascontiguousarray(pts32[:, a]) for a in range(3)]
    table = LatticeNoise(3, rng=1, kernel="quintic")
    integer = LatticeNoise(3, rng=1, kernel="quintic", hash="integer")  # 2 taps: int_same64 follows its arithmetic
    h2, vl = (t[0] for t in pair_tables(table.perms, table.values))
    gradient = LatticeNoise(3, rng=1, kernel="quintic", basis="gradient")
    catmull = LatticeNoise(3, rng=1, kernel="catmull-rom")
    gh2, gl = (t[0] for t in pair_tables(gradient.perms, gradient.values, gradient.gradients))
    ch2, cvl = (t[0] for t in pair_tables(catmull.perms, catmull.values))
    kt = table.kernel
    kernel = table_block_kernel(2, False)
    direct = (np.ones((1, 3)), np.array([table.scale]), table.phase, kt.shift, kt.left, kt.coef,
              *pair_tables(table.perms, table.values), False)
    out2 = np.empty((NPTS, 1))
    pair, outs2 = _jit.points_pair(pts), _jit.out_pair(out2)
    kernel(pair, False, 0, NPTS, outs2, *direct)
    if not (np.array_equal(out2[:, 0], table(pts)) and points_path._pairs(table, NPTS, False)):
        raise AssertionError("table-kernel is no longer the kernel noiselab runs: update it beside the engine")
    cols = np.ascontiguousarray(pts32.T)
    out64, out32 = np.empty(NPTS), np.empty(NPTS, np.float32)
    key = np.uint32(0x2545F491)
    k = integer.kernel
    same = (integer.phase, float(k.shift), int(k.left), axis_multipliers(3), k.coef,
            integer.keys[0], float(integer.scale), np.empty(NPTS, np.float32))
    int_same64(*soa, *same)
    if not np.array_equal(same[-1], integer(pts32)):
        raise AssertionError("int-same64 no longer computes noiselab's bits: update it beside the engine")
    cands = {
        "floor32": lambda: np.full(NPTS, 0.5, np.float32),
        "table": lambda: table(pts),
        "lookups": lambda: table_lookups(pts, h2, vl, out64),
        "table-kernel": lambda: kernel(pair, False, 0, NPTS, outs2, *direct),
        "table-setup": lambda: table_setup(pts, np.ones(3), table.phase, kt.shift, kt.left, kt.coef,
                                           table.table_size, out64),
        "table-gradient": lambda: gradient(pts),
        "lookups-gradient": lambda: table_lookups_gradient(pts, gh2, gl, out64),
        "table-catmull-rom": lambda: catmull(pts),
        "lookups-4taps": lambda: table_lookups4(pts, ch2, cvl, out64),
        "integer": lambda: integer(pts32),
        "int-minimal": lambda: int_minimal(*soa, key, out32),
        "int-minimal64": lambda: int_minimal64(*soa, key, out32),
        "int-same64": lambda: int_same64(*soa, *same),
    }
    cands["integer-columns"] = lambda: integer(cols, axis=0)
    fns = _peer("fns")
    if fns is not None:
        cands["fns"] = _fns_points(fns, fns.NoiseType.Value, pts32)
    return interleaved(cands, repeats=repeats, timer=time.thread_time)  # its warm-up round compiles


F32_ROWS = (("quintic", "value", "Value"), ("quintic", "gradient", "Perlin"), ("catmull-rom", "value", "Cubic"))


def measure_f32(repeats):
    """noiselab's float32 arithmetic against pyfastnoisesimd, both layouts: ``{row: Timings}``."""
    pts32 = np.random.default_rng(0).uniform(0.0, 100.0, (NPTS, 3)).astype(np.float32)
    cols = np.ascontiguousarray(pts32.T)
    fns = _peer("fns")
    out = {}
    for kname, basis, peer in F32_ROWS:
        noise = LatticeNoise(3, rng=1, kernel=kname, basis=basis, hash="integer")
        cands = {"f32a": lambda n=noise: n.evaluate(pts32, arithmetic="float32"),
                 "f32aT": lambda n=noise: n.evaluate(cols, axis=0, arithmetic="float32"),
                 "f64a": lambda n=noise: n(pts32), "f64aT": lambda n=noise: n(cols, axis=0)}
        if fns is not None:
            cands["fns"] = _fns_points(fns, getattr(fns.NoiseType, peer), pts32)
        if kname == "quintic" and basis == "value":  # where the time goes: the kernel alone, with either index
            k, res, o1 = noise.kernel, np.empty((NPTS, 1), np.float32), np.empty(NPTS, np.float32)
            kern = _jit.int_two_taps_kernel(3, False, True, True)
            rest = (np.ones((1, 3)), np.array([noise.scale]), noise.phase, k.shift, k.left,
                    k.coef.astype(np.float32), noise.keys, noise._mult, False)
            reach = np.float32([2.0 ** -126, 2.0 ** 31]).view(np.uint32)   # as points_path._run_block sets it
            res = _jit.out_pair(res)
            src32 = _jit.points_pair(pts32)
            cands["kernel"] = lambda: kern(src32, False, 0, NPTS, res, *rest, reach)
            cands["kernel64"] = lambda: kern(src32, False, 0, NPTS, res, *rest, np.zeros(2, np.uint32))
            cands["minimal"] = lambda: int_minimal(cols[0], cols[1], cols[2], np.uint32(noise.keys[0]), o1)
            cands["floor32"] = lambda: np.full(NPTS, 0.5, np.float32)
        out[(kname, basis, peer)] = interleaved(cands, repeats=repeats, timer=time.thread_time)
    return out


def report_f32(tf):
    lines = ["## The float32 arithmetic against pyfastnoisesimd\n",
             "1,000,000 random 3-D float32 points in [0, 100)^3, integer hash, one thread, the same clock and "
             "rounds as above (interleaved per row). `f32 arith`: `noise.evaluate(pts32, arithmetic=\"float32\")` "
             "from `(N, 3)` rows, `(3, N)`: the same from columns (`axis=0`); `f64 arith`: `noise(pts32)`, "
             "today's default. `x FNS` = pyfastnoisesimd's time / noiselab's (median of the per-round ratios).\n",
             "| noise | FNS | FNS pts/s | f32 arith (N, 3) x FNS | f32 arith (3, N) x FNS | f64 arith (N, 3) x FNS "
             "| f64 arith (3, N) x FNS | f32 / f64 speed-up (N, 3) |",
             "|---|---|---|---|---|---|---|---|"]
    for (kname, basis, peer), t in tf.items():
        xf = [f"{t.ratio('fns', k):.2f}" if "fns" in t else "n/a" for k in ("f32a", "f32aT", "f64a", "f64aT")]
        rate = f"{NPTS / t['fns']:.3g}" if "fns" in t else "n/a"
        lines.append(f"| {kname} {basis} | {peer} | {rate} | {' | '.join(xf)} | {t.ratio('f64a', 'f32a'):.2f} |")
    t = tf[F32_ROWS[0]]
    if "fns" in t:
        ms = {k: 1e3 * t[k] for k in ("f32a", "kernel", "kernel64", "minimal", "floor32", "fns")}
        lines += ["", "Where the float32 arithmetic's time goes (quintic value, `(N, 3)` rows, ms per 1e6 points, "
                  "medians of the same rounds): "
                  f"the call {ms['f32a']:.2f}; its compiled kernel alone (`_jit.int_two_taps_kernel(3, False, "
                  f"True)`, no wrapper) {ms['kernel']:.2f}, so the wrapper (the argument checks, the output, the "
                  f"threads' split) {ms['f32a'] - ms['kernel']:.2f}; the same kernel made to take the float64 "
                  f"index pass in every block (`kernel64`: the fallback for blocks out of float32 reach) "
                  f"{ms['kernel64']:.2f}; `int-minimal` on the same points as `(3, N)` columns (the shortest "
                  f"float32 loop with this hash, no blocks, no checks, no octaves) {ms['minimal']:.2f}, "
                  f"{t.ratio('fns', 'minimal'):.2f}x pyfastnoisesimd; pyfastnoisesimd's whole call {ms['fns']:.2f}; "
                  f"writing the output {ms['floor32']:.2f}.",
                  "",
                  f"What limits it: the kernel takes {t.ratio('kernel', 'minimal'):.2f}x `int-minimal`'s time, "
                  "which itself stays under 1.0x pyfastnoisesimd. The difference is the work that the kernel's "
                  "guarantees add to `int-minimal`'s loop: each block of 256 points gathered from either layout "
                  "and checked (every |x f| below 2**31 and exact in float32, NaN and inf refused, so that the "
                  "index is the float64 index's bits), the corner loop compiled with its float64 fallback "
                  "beside it, the weights from the kernel's own coefficients by Horner's rule (`int-minimal` "
                  "writes its fade by hand), octaves, components and turbulence, and each block's sums stored "
                  "and copied out."]
    return lines + [""]


F32_ERROR_HEAD = [
    "## The float32 arithmetic's error\n",
    "Largest |`evaluate(x, arithmetic=\"float32\")` - `evaluate(x)`| over 1,000,000 random points (computed once, "
    "not timed), amplitude 1, integer hash, `LatticeNoise(dim, rng=1, kernel=..., basis=...)`, x uniform in "
    "[-1000, 1000)^dim plus the offset; and the largest |value| of the float32 result (the amplitude bound is 1). "
    "The quintic rows are the largest: a 2-tap kernel's corners are blended as nested float32 lerps "
    "`v0 + w (v1 - v0)`, `w` its second tap's polynomial (`10 t^3 - 15 t^4 + 6 t^5`) by Horner's rule; until "
    "0.6.0 the power-basis weights, whose terms up to 15 cancel in float32, gave up to 4.46e-6. "
    "`tests/test_lattice_f32.py` allows 4x the largest (2.78e-6 when the test was written) and |value| <= "
    "amplitude.\n"]


def f32_error(npts=NPTS):
    """The float32 arithmetic's largest |difference| from the float64 result, and the largest |value| (amplitude 1)."""
    rng = np.random.default_rng(5)
    lines = ["| dim | noise | offset | max abs diff | max abs value |", "|---|---|---|---|---|"]
    worst = 0.0
    for dim in (1, 2, 3):
        for offset in (0.0, 1e12):
            x = rng.uniform(-1000.0, 1000.0, (npts, dim)) + offset
            for kname, basis, _ in F32_ROWS + (("catmull-rom", "gradient", ""),):
                noise = LatticeNoise(dim, rng=1, kernel=kname, basis=basis, hash="integer")
                fast, ref = noise.evaluate(x, arithmetic="float32"), noise(x)
                diff = float(np.abs(fast.astype(np.float64) - ref).max())
                worst = max(worst, diff)
                lines.append(f"| {dim} | {kname} {basis} | {offset:.0e} | {diff:.2e} "
                             f"| {float(np.abs(fast).max()):.4f} |")
    return lines + ["", f"largest: {worst:.2e}"]


def report(t, repeats, load, cmd):
    info = run_info(cmd, ["pyfastnoisesimd"], load=load)
    rate = {k: NPTS / t[k] for k in t}
    names = [k for k in ("table", "table-kernel", "table-setup", "lookups", "table-gradient", "lookups-gradient",
                         "table-catmull-rom", "lookups-4taps",
                         "integer", "integer-columns", "int-same64", "int-minimal64", "int-minimal",
                         "fns", "floor32")
             if k in rate]
    lines = ["# What limits lattice noise on scattered 3-D points\n",
             f"- date: {info['date']}",
             f"- command: `{cmd}`",
             f"- machine: {info['machine']}, {info['cores']} cores ({info['cpu']}), shared with other jobs; "
             f"load average (1 min) at start {load:.1f}, at the end {os.getloadavg()[0]:.1f}",
             "- versions: " + ", ".join(f"{k} {v}" for k, v in info["versions"].items()),
             f"- timing: one thread, CPU time of the calling thread (`time.thread_time`), median of {repeats} "
             "interleaved rounds; `x FNS` and `x floor` are medians of the per-round ratios\n",
             "1,000,000 random points in [0, 100)^3, quintic value noise. The candidates are described in the "
             "script's docstring: `table` and `integer` are noiselab (`LatticeNoise(3, kernel=\"quintic\")` on "
             "float64 points; the same with `hash=\"integer\"` on float32 points); `lookups` does only the table "
             "hash's reads; `int-minimal` is the shortest integer-hash kernel numba compiles; `fns` is "
             "pyfastnoisesimd's `Value` (1 worker, its own aligned coordinates).\n",
             "| candidate | pts/s | x FNS | x floor | time / `lookups` |",
             "|---|---|---|---|---|"]
    for k in names:
        xf = f"{t.ratio('fns', k):.2f}" if "fns" in rate else "n/a"
        lines.append(f"| {k} | {rate[k]:.3g} | {xf} | {t.ratio('floor32', k):.3f} | {t.ratio(k, 'lookups'):.2f} |")
    lines += ["", "Reading (the figures of this run):", ""]
    if "fns" in rate:
        ms = {k: 1e3 * t[k] for k in t}
        lines.append(f"- The table hash's reads alone run at {t.ratio('fns', 'lookups'):.2f}x pyfastnoisesimd: no "
                     "kernel that makes these reads reaches 1x on these points, whatever its arithmetic (the plain "
                     "nested permutation would read 22 entries a point, not 12).")
        lines.append(f"- noiselab's table hash against its own read bound (time of the reads / time of noiselab): "
                     f"quintic value {1 / t.ratio('table', 'lookups'):.2f}x, quintic gradient "
                     f"{1 / t.ratio('table-gradient', 'lookups-gradient'):.2f}x, Catmull-Rom value "
                     f"{1 / t.ratio('table-catmull-rom', 'lookups-4taps'):.2f}x.")
        lines.append(f"- What limits it (quintic value, {ms['table']:.1f} ms): the kernel alone (`table-kernel`) "
                     f"takes {ms['table-kernel']:.1f} ms ({t.ratio('table-kernel', 'lookups'):.2f}x the reads); the "
                     f"rest, {ms['table'] - ms['table-kernel']:.1f} ms, is the call's wrapper (the argument "
                     "checks, the output's allocation, the folded tables' look-up; the kernel counts bad points as it "
                     "goes, no pass over the points before it). Within the kernel, the per-axis "
                     f"float64 arithmetic that the bits need (`table-setup`: weights and taps, no read) takes "
                     f"{ms['table-setup']:.1f} ms, {t.ratio('table-setup', 'lookups'):.2f}x the reads' "
                     f"{ms['lookups']:.1f} ms (both read the points and write the output): the kernel runs it "
                     "vectorised "
                     "block by block and then the reads point by point, so its time is about their sum "
                     f"({ms['table-setup'] + ms['lookups']:.1f} ms). 0.8x "
                     "the read bound would need the arithmetic and the reads to overlap almost entirely.")
        lines.append(f"- The integer hash has no reads. The simplest numba kernel with its arithmetic runs at "
                     f"{t.ratio('fns', 'int-minimal'):.2f}x pyfastnoisesimd; noiselab's (`integer`, float64 "
                     f"arithmetic, any period) takes {t.ratio('integer', 'int-minimal'):.2f}x its time, "
                     f"{t.ratio('integer-columns', 'int-minimal'):.2f}x with `(3, N)` columns.")
        lines.append(f"- The float64 bound: the same loop in float64 arithmetic (`int-minimal64`) runs at "
                     f"{t.ratio('fns', 'int-minimal64'):.2f}x pyfastnoisesimd, and a plain per-point loop with exactly "
                     f"noiselab's operations (`int-same64`, its bits) at {t.ratio('fns', 'int-same64'):.2f}x: "
                     "1.0x the peer is beyond float64 arithmetic on this CPU. noiselab's call takes "
                     f"{t.ratio('integer', 'int-same64'):.2f}x the time of `int-same64` "
                     f"({t.ratio('integer-columns', 'int-same64'):.2f}x from `(3, N)` columns): the rest is its "
                     "wrapper (the argument checks, the output's allocation) and its blocks (the coordinates gathered "
                     "into a block, each point's sum stored and copied out).")
    lines.append("")
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--output", default=str(Path(__file__).with_suffix(".md")))
    ap.add_argument("--f32-error", action="store_true",
                    help="print the float32 arithmetic's largest difference from float64 instead of timing")
    ap.add_argument("--f32-only", action="store_true", help="time only the float32-arithmetic rows (print them)")
    args = ap.parse_args(argv)
    if args.f32_error:
        print("\n".join(f32_error()))
        return
    if args.f32_only:
        print("\n".join(report_f32(measure_f32(args.repeats))))
        return
    cmd = "benchmarks/.venv-peers/bin/python benchmarks/bench_limits.py" + (
        f" --repeats {args.repeats}" if args.repeats != 7 else "")
    load = os.getloadavg()[0]
    t = measure(args.repeats)
    lines = report(t, args.repeats, load, cmd) + report_f32(measure_f32(args.repeats)) + F32_ERROR_HEAD + f32_error()
    Path(args.output).write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
