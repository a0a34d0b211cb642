"""The points path: lattice noise (or its octave sum, or with its Jacobian) at scattered points.

:func:`prepare_points` takes the points in the caller's layout (``axis``:
which axis holds the coordinates; ``(N, d)`` rows or ``(d, N)`` columns are
read in place, without a copy) as ``(N, dim_in)`` rows;
:func:`evaluate_points` and :func:`evaluate_points_jac` run the one point
kernel of :mod:`._jit` that fits the noise (:func:`._jit.points_kernel`:
hash, dimension, tap count, derivative flag, and whether any axis has a
period of its own; 3-D table-hash noise without a period, from
:data:`PAIRS_MIN` points on, a block kernel over folded tables that reads
rows or columns in place, :data:`TABLE_SPLIT`; integer-hash values in 1-3-D a kernel
vectorised across points, :data:`INT_FAST_DIM`, and without a period of
their own one that reads rows or columns in place, :data:`INT_BLOCK`) over
blocks of points on ``workers`` threads (:func:`noiselab._core.run_split`,
or :func:`_run_block` / :func:`_run_table` for the in-place kernels: every point's arithmetic is
the same whatever the split, so any worker count gives the same bits). These
functions read a noise's tables and change nothing.
"""
from __future__ import annotations

import functools

import numpy as np

from .._core import as_array, check_finite_array, float_dtype, map_blocks, run_split
from . import _jit as jit
from . import checks

__all__ = ["prepare_points", "output_dtype", "shape_out", "evaluate_points", "evaluate_points_jac", "kernel_args"]


def prepare_points(noise, points, name="points", axis=-1):
    """``(lead, flat)``: the points' leading shape and the points as ``(N, dim_in)`` float64 rows.

    ``axis`` is the axis of ``points`` that holds the ``dim_in`` coordinates
    (numpy's convention: -1, the default, for ``(..., dim_in)``; 0 for
    structure-of-arrays ``(dim_in, ...)``); the others, in order, are the
    leading shape. For ``dim_in == 1`` with ``axis=-1`` an array whose last
    axis is not 1 (or a scalar) is that many scalar inputs. Two-dimensional
    float64 and float32 points are used in place in either layout (a
    transposed view for ``axis=0``; float32 ones are widened, exactly, where
    a kernel reads them: :func:`_run`); other points are copied to float64 rows.
    """
    points = as_array(name, points)
    if points.dtype.kind != "f":
        points = check_finite_array(name, points)  # integers pass; other kinds get check_finite_array's message
    d = noise.dim_in
    if points.ndim:
        if not isinstance(axis, (int, np.integer)) or not -points.ndim <= axis < points.ndim:
            raise ValueError(f"axis must be an integer in [{-points.ndim}, {points.ndim - 1}] for {name} of "
                             f"{points.ndim} dimension(s), got {axis!r}")
        axis = int(axis) % points.ndim
        if axis != points.ndim - 1:
            if points.shape[axis] != d:
                raise ValueError(f"{name} must have dim_in={d} coordinates along axis {axis}, got shape "
                                 f"{points.shape}")
            points = np.moveaxis(points, axis, -1)
    if d == 1 and (points.ndim == 0 or points.shape[-1] != 1):
        lead = points.shape
        flat = points.reshape(-1, 1)
    else:
        if points.ndim == 0 or points.shape[-1] != d:
            raise ValueError(f"{name} must have shape (..., dim_in={d}), got {points.shape}")
        lead = points.shape[:-1]
        flat = points.reshape(-1, d)
    return lead, flat if flat.dtype == np.float32 else flat.astype(np.float64, copy=False)


def output_dtype(points_dtype, dtype):
    """The output dtype: ``dtype`` if given, else float32 for float32 points and float64 otherwise."""
    if dtype is not None:
        return float_dtype(dtype)
    return np.dtype(np.float32) if points_dtype == np.float32 else np.dtype(np.float64)


def shape_out(out, lead, dim_out):
    """``(N, dim_out)`` rows as ``lead`` (one component) or ``lead + (dim_out,)``."""
    if dim_out == 1:
        return out.reshape(lead)
    return out.reshape(tuple(lead) + (dim_out,))


# 3-D table-hash noise without a period or derivatives runs the block kernel over folded tables
# (:func:`._jit.pair_tables`, the same bits) from this many points on (building them takes about 0.6 ms for
# n = 256, once per set of tables: :func:`_folded`), and up to this many entries (n * n per component: 2 MiB for
# n = 1024); fewer points, or larger tables, take the per-point kernel
PAIRS_MIN = 1 << 15
MAX_PAIR_ENTRIES = 1 << 20


# integer-hash values (no Jacobian) in up to this many dimensions take the kernel vectorised across points
# (:func:`._jit.int_fast_kernel`, the same bits; 2.2-2.7x for 1e6 3-D points, 1.17x with a period of its own,
# benchmarks/bench_lattice_paths.md); 0 turns it off
INT_FAST_DIM = 3


# integer-hash values in 1-3-D without a period of their own take the in-place kernels, the same bits as the
# vectorised one: 2-tap kernels (quintic, linear) every point's taps in registers (:func:`._jit.int_two_taps_kernel`),
# the others block by block (:func:`._jit.int_block_kernel`); rows or columns read in place (1e6 3-D points:
# benchmarks/bench_lattice_paths.md); False turns them off
INT_BLOCK = True


# 3-D table-hash noise without a period or derivatives runs block by block over the folded tables, rows or columns
# read in place (:func:`._jit.table_block_kernel`, the same bits); False turns it off
TABLE_SPLIT = True


def _periodic(noise):
    """Whether any axis has a period other than the hash's own (n for the table hash, 2**32 for the integer)."""
    free = jit.PERIOD_MAX if noise.hash == "integer" else noise.table_size
    return bool((noise.period != free).any())


def _pairs(noise, npts, deriv):
    """Whether this call takes the 3-D table-hash block kernel over folded tables (:data:`TABLE_SPLIT`)."""
    return (TABLE_SPLIT and noise.hash == "table" and noise.dim_in == 3 and not deriv
            and npts >= PAIRS_MIN and not _periodic(noise) and noise.table_size & (noise.table_size - 1) == 0
            and noise.table_size ** 2 * noise.dim_out <= MAX_PAIR_ENTRIES)


def kernel_args(noise, freqs, amps, absval):
    """The point kernel's arguments after ``(points, out)`` (:func:`._jit.points_kernel`)."""
    k = noise.kernel
    basis = int(noise.basis == "gradient")
    head = (np.ascontiguousarray(freqs, dtype=np.float64), np.ascontiguousarray(amps, dtype=np.float64),
            noise.phase, k.shift, k.left, k.taps, k.coef, k.dcoef, noise.period, noise._pmask)
    if noise.hash == "integer":
        tail = (noise.keys, noise._mult, noise._int_grads)
    else:
        tail = (noise.perms, noise.values, noise.gradients)
    return head + tail + (basis, bool(absval))


def _in_place(noise, deriv):
    """Whether this call takes the integer hash's in-place kernels (:data:`INT_BLOCK`), which write any float dtype."""
    return (noise.hash == "integer" and noise.dim_in <= INT_FAST_DIM and not deriv and INT_BLOCK
            and not _periodic(noise))


def _layout(flat):
    """``(src, cols)``: C-contiguous rows ``(N, d)`` (``cols`` False) or columns ``(d, N)`` holding ``flat``.

    Rows and the transposed view of columns are read in place; any other
    layout is copied to rows.
    """
    if flat.flags.c_contiguous:
        return flat, False
    if flat.T.flags.c_contiguous:
        return flat.T, True
    return np.ascontiguousarray(flat), False


def _run_block(noise, flat, out, freqs, amps, absval, workers, min_block=4096, f32=False):
    """The integer hash's block kernel over ``flat`` into ``out``, in ``workers`` contiguous ranges of points.

    As :func:`noiselab._core.run_split`, but every thread gets the whole
    arrays and its range ``[lo, hi)``: a slice of ``(d, N)`` columns is no
    longer C-contiguous, which the kernel needs to read them in place.
    ``f32``: the float32-arithmetic variants (float32 ``out``). Returns the
    count of NaN fractions (a NaN point or an overflowing ``x * frequency``),
    which :func:`evaluate_points` refuses.
    """
    src, cols = _layout(flat)
    k = noise.kernel
    gradient = noise.basis == "gradient"
    freqs = np.ascontiguousarray(freqs, dtype=np.float64)
    coef = k.coef.astype(np.float32) if f32 else k.coef
    # the float32 arithmetic's index is computed in float32 for float32 points without phase or shift at power-of-two
    # frequencies, block by block where every |x| is in reach: x f exact and below 2**31 (:func:`._jit._reach32`)
    fast = f32 and src.itemsize == 4 and k.shift == 0 and not noise.phase.any() and (np.frexp(freqs)[0] == 0.5).all()
    reach = np.float32([min(2.0 ** -126 / min(freqs.min(), 1.0), 2.0 ** 127), min(2.0 ** 31 / freqs.max(), 2.0 ** 127)]
                       if fast else [0, 0]).view(np.uint32)
    # 2-tap kernels: every point's taps in registers (the float32 arithmetic's lerps: those whose weights sum to 1)
    if k.taps == 2 and (not f32 or np.array_equal(k.coef[0] + k.coef[1], np.eye(1, k.coef.shape[1])[0])):
        kernel = jit.int_two_taps_kernel(noise.dim_in, gradient, f32, src.itemsize == 4)
    else:
        kernel = jit.int_block_kernel(noise.dim_in, k.taps, gradient, f32, src.itemsize == 4)
    rest = (freqs, np.ascontiguousarray(amps, dtype=np.float64), noise.phase, k.shift, k.left, coef, noise.keys,
            noise._mult, bool(absval), reach)
    return _in_ranges(kernel, src, cols, out, rest, workers, min_block)


def _in_ranges(kernel, src, cols, out, rest, workers, min_block):
    """A block kernel ``kernel(points, cols, lo, hi, outputs, *rest)`` over ``workers`` contiguous ranges of the
    points (at least ``min_block`` each), on pooled threads; the sum of their counts of NaN fractions. The points
    go as :func:`._jit.points_pair` makes them (one specialisation reads either dtype)."""
    npts = out.shape[0]
    n = min(workers, max(1, npts // min_block))
    bounds = np.linspace(0, npts, n + 1).astype(np.int64).tolist()
    outs, pair = jit.out_pair(out), jit.points_pair(src)
    return sum(map_blocks(lambda ab: kernel(pair, cols, ab[0], ab[1], outs, *rest), zip(bounds[:-1], bounds[1:]), n))


_FOLDED = {}  # the last few folded tables, keyed by the tables' bytes (building them: 0.6 ms for n = 256)


def _folded(noise, gradient):
    """:func:`._jit.pair_tables` of the noise's live tables (the values', or the gradients'), reused while unchanged."""
    grads = noise.gradients if gradient else None
    key = (noise.perms.shape, noise.perms.tobytes(), noise.values.tobytes(),
           None if grads is None else grads.tobytes())
    tables = _FOLDED.get(key)
    if tables is None:  # (another thread may clear the dict meanwhile: this call keeps its own reference)
        tables = jit.pair_tables(noise.perms, noise.values, grads)
        if len(_FOLDED) >= 4:
            _FOLDED.clear()
        _FOLDED[key] = tables
    return tables


def _run_table(noise, flat, out, freqs, amps, absval, workers, min_block=4096):
    """The table hash's 3-D block kernel over ``flat`` into ``out``, rows or columns in place, as :func:`_run_block`."""
    src, cols = _layout(flat)
    k = noise.kernel
    gradient = noise.basis == "gradient"
    kernel = jit.table_block_kernel(k.taps, gradient)
    rest = ((np.ascontiguousarray(freqs, dtype=np.float64), np.ascontiguousarray(amps, dtype=np.float64),
             noise.phase, k.shift, k.left, k.coef) + _folded(noise, gradient) + (bool(absval),))
    return _in_ranges(kernel, src, cols, out, rest, workers, min_block)


def _run(noise, flat, out, freqs, amps, absval, deriv, workers):
    """The point kernel for this noise and call over ``flat`` into ``out``, on ``workers`` threads.

    For the calls the in-place kernels do not take (:func:`evaluate_points` runs those itself).
    """
    gradient = noise.basis == "gradient"
    if noise.hash == "integer" and noise.dim_in <= INT_FAST_DIM and not deriv:  # the same bits, vectorised
        # float32 points read in place (each coordinate widened to float64 as it is read: the same values,
        # without a float64 copy of the points; 1e6 3-D points: benchmarks/bench_lattice_paths.md)
        kernel = jit.int_fast_kernel(noise.dim_in, noise.kernel.taps, gradient, _periodic(noise))
        run_split(kernel, flat, out, kernel_args(noise, freqs, amps, absval), workers)
        return
    flat = flat.astype(np.float64, copy=False)  # the other kernels are compiled for float64 points only
    kernel = jit.points_kernel(noise.hash == "integer", noise.dim_in, noise.kernel.taps, deriv, _periodic(noise))
    if noise.hash == "table":  # its working arrays from here: each block (thread) its own (:func:`._jit.point_buffers`)
        kernel = functools.partial(_with_buffers, kernel, (noise.dim_in, noise.dim_out, deriv))
    run_split(kernel, flat, out, kernel_args(noise, freqs, amps, absval), workers)


def _with_buffers(kernel, shape, points, part, *rest):
    """``kernel`` on one block of points with working arrays of its own (:func:`._jit.point_buffers` ``(*shape)``)."""
    return kernel(points, part, *rest, jit.point_buffers(*shape))


def evaluate_points(noise, flat, freqs, amps, absval, dtype, name="points", workers=1, f32=False):
    """``sum_o amps[o] * b(noise(flat * freqs[o] + phase))`` at ``flat`` (N, dim_in): ``(N, dim_out)`` in ``dtype``.

    ``b`` is the identity or ``abs`` (``absval``); ``amps`` already holds the
    range normalisation (``noise.scale``). The computation is float64;
    float32 output is the float64 result rounded once. With ``f32`` (checked:
    :func:`.checks.check_arithmetic`) the in-place kernels compute in float32
    from each point's fractions on, into float32 ``dtype``.
    """
    # the in-place kernels round each float64 result once as they store it, as astype would: float32 output
    # without a float64 array first
    block, table = f32 or _in_place(noise, False), _pairs(noise, flat.shape[0], False)
    out = np.empty((flat.shape[0], noise.dim_out), dtype if block or table else np.float64)
    if (block or table) and flat.shape[0]:
        # the in-place kernels count the NaN fractions (a NaN or infinite point, an overflowing x * frequency) as
        # they go, instead of a pass over the points before (its max and min: 1-2 ms of 1e6 3-D points'
        # 7-13 ms, benchmarks/bench_limits.md); a count refuses the call with the same error
        if block:
            bad = _run_block(noise, flat, out, freqs, amps, absval, workers, f32=f32)
        else:
            bad = _run_table(noise, flat, out, freqs, amps, absval, workers)
        if bad:
            checks.check_reach(flat, freqs, noise.phase, name)  # raises
            raise ValueError(f"{name} times the frequency plus the phase is not finite at {bad} point(s)")
    elif flat.shape[0]:
        checks.check_reach(flat, freqs, noise.phase, name)  # NaN, inf and overflowing x * frequency
        _run(noise, flat, out, freqs, amps, absval, False, workers)
    return out if out.dtype == dtype else out.astype(dtype)


def evaluate_points_jac(noise, flat, freqs, amps, absval, name="points", workers=1):
    """Values and Jacobians at points ``flat`` (N, d): float64 ``(N, dim_out, 1 + dim_in)``, value first.

    The octave sum as in :func:`evaluate_points`; with ``absval`` each
    octave's derivative is taken with the sign of its value (turbulence).
    The derivative is in input units (``amps * freqs`` times the lattice-space
    derivative); an overflowed one is refused (:func:`.checks.check_jac_finite`).
    """
    checks.check_differentiable(noise.kernel)
    out = np.empty((flat.shape[0], noise.dim_out, noise.dim_in + 1))
    if flat.shape[0]:
        checks.check_reach(flat, freqs, noise.phase, name)  # as for values: x * frequency + phase must stay finite
        _run(noise, flat, out, freqs, amps, absval, True, workers)
        checks.check_jac_finite(out, f"at the given {name}", checks.jac_bound(freqs, amps))
    return out
