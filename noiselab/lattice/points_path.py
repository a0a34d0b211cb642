"""The points path: lattice noise (or its octave sum) at scattered points, by the fastest kernel that applies.

:func:`prepare_points` flattens the points to ``(N, dim_in)``;
:func:`evaluate_points` picks the kernel family and runs it over blocks of
points on ``workers`` threads (:func:`noiselab._core.run_split`: every
point's arithmetic is the same whatever the split, so any worker count
gives the same bits). The families, first that applies:

1. ``hash="integer"``: the SIMD kernels in 1-3-D with a stock kernel
   (:func:`int_simd_kernels`), else the generic integer-hash kernel;
2. 3-D, table hash, last period ``table_size``: the kernels over
   precombined hash tables (:func:`uses_hash_tables`);
3. 1-3-D: the kernels unrolled per dimension and tap count;
4. anything else: the generic per-point kernel.

Families 1-2 read float32 points and store the output dtype themselves, and
count non-finite inputs instead of checking them first; 3-4 compute and
write float64. :func:`evaluate_points_jac` is the same choice among the
same kernels compiled with their derivative flag (value and Jacobian, float64;
the integer hash's generic kernel, the 3-D table kernels, the unrolled ones,
the generic one): each family is one source whose derivative lines are
compiled (or, for the generated families, written) only for the Jacobian. These functions
read a noise's tables and change nothing but its cache of hash tables
(:func:`~.tables.cached_hash_tables`).
"""
from __future__ import annotations

import numpy as np

from .._core import as_array, check_finite_array, float_dtype, run_split
from . import checks
from ._compiled import (has_table_points, int_simd_factor, int_simd_kernels, inthash, jit, table_jacobian_kernel,
                        table_points_kernel, unrolled_jacobian_kernel, unrolled_points_kernel)
from .tables import cached_hash_tables

__all__ = ["prepare_points", "output_dtype", "shape_out", "evaluate_points", "evaluate_points_jac", "uses_hash_tables",
           "int_fast_kernels"]

# the 3-D scattered kernels' two-level hash table (uint16, n * n entries per
# output component; its entries reach 3n + 4 < 2**16) is used up to this
# size (n = 1024 for one component: 2 MiB)
MAX_H2_ENTRIES = 1 << 20


def uses_hash_tables(noise):
    """Whether the scattered kernel over precombined hash tables applies (3-D input; last period n)."""
    k = noise.kernel
    return (noise.hash == "table" and has_table_points(noise.dim_in, k.taps) and (noise.period >= k.taps).all()
            and noise.period[-1] == noise.table_size and noise.table_size ** 2 * noise.dim_out <= MAX_H2_ENTRIES)


def int_fast_kernels(noise):
    """The integer hash's SIMD kernels for this noise (``{variant: kernel}``), or None (4-D and up, custom kernels)."""
    if noise.hash != "integer":
        return None
    return int_simd_kernels(noise.dim_in, noise.kernel, noise.basis)


def prepare_points(noise, points, name="points"):
    """``(lead, flat)``: the points' leading shape and the points as contiguous ``(N, dim_in)`` rows.

    For ``dim_in == 1`` an array whose last axis is not 1 (or a scalar) is
    that many scalar inputs. float32 points stay float32 for the kernels
    that read them (exact widening, saving a copy); the others get float64.
    Non-finite points are refused here unless the kernel counts them.
    """
    points = as_array(name, points)
    tables = uses_hash_tables(noise) or int_fast_kernels(noise) is not None  # kernels that read float32, count NaN
    if not (points.dtype.kind == "f" and tables):  # the table kernels check
        points = check_finite_array(name, points)
    d = noise.dim_in
    if d == 1 and (points.ndim == 0 or points.shape[-1] != 1):
        lead = points.shape
        flat = points.reshape(-1, 1)
    else:
        if points.ndim == 0 or points.shape[-1] != d:
            raise ValueError(f"{name} must have shape (..., dim_in={d}), got {points.shape}")
        lead = points.shape[:-1]
        flat = points.reshape(-1, d)
    keep = tables and points.dtype == np.float32
    return lead, np.ascontiguousarray(flat, dtype=np.float32 if keep else np.float64)


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


def evaluate_points(noise, flat, freqs, amps, absval, dtype, name="points", workers=1):
    """``sum_o amps[o] * b(noise(flat * freqs[o] + phase))`` at ``flat`` (N, dim_in): ``(N, dim_out)`` in ``dtype``.

    ``b`` is the identity or ``abs`` (``absval``); ``amps`` already holds the
    range normalisation (``noise.scale``). The computation is float64;
    float32 output is a rounding of the float64 result (the table kernels
    round as they store; the others write float64, one compiled
    specialisation each), except on the integer hash's float32 SIMD path
    (see ``LatticeNoise``'s Notes, Precision).
    """
    use_tables = uses_hash_tables(noise)
    fast = int_fast_kernels(noise)
    own = use_tables or fast is not None  # kernels that store the output dtype themselves
    out = np.empty((flat.shape[0], noise.dim_out), dtype=dtype if own else np.float64)
    if not own:
        flat = np.ascontiguousarray(flat, dtype=np.float64)
    if flat.shape[0]:
        k = noise.kernel
        freqs = np.ascontiguousarray(freqs, dtype=np.float64)
        amps = np.ascontiguousarray(amps, dtype=np.float64)
        basis = 0 if noise.basis == "value" else 1
        unrolled = unrolled_points_kernel(noise.dim_in, k.taps)
        if not own:
            checks.check_reach(flat, freqs, noise.phase, name)  # the table and SIMD kernels count overflows themselves
        if noise.hash == "integer":
            bad = _evaluate_int(noise, fast, flat, out, freqs, amps, absval, workers)
        elif use_tables:
            bad = run_split(table_points_kernel(noise.dim_in, k), flat, out,
                            (freqs, amps, noise.phase, k.shift, k.left, k.coef, noise.period, noise._pmask,
                             *cached_hash_tables(noise, basis), basis, bool(absval)), workers)
        elif unrolled is not None and (noise.period >= k.taps).all():
            bad = run_split(unrolled, flat, out, (freqs, amps, noise.phase, k.shift, k.left, k.coef, noise.period,
                                                  noise._pmask, noise._perms2, noise.values, noise.gradients, basis,
                                                  bool(absval)), workers)
        else:
            bad = run_split(jit.eval_points, flat, out, (freqs, amps, noise.phase, k.shift, k.left, k.taps, k.coef,
                                                         k.dcoef, noise.period, noise._pmask, noise.perms,
                                                         noise.values, noise.gradients, basis, bool(absval)), workers)
        if own and bad:
            check_finite_array(name, flat)  # raises for NaN or inf input
            raise ValueError(f"{name} times the frequency (and lacunarity**octave) overflows float64")
    return out if out.dtype == dtype else out.astype(dtype)


def _evaluate_int(noise, fast, flat, out, freqs, amps, absval, workers):
    """The integer hash at scattered points into ``out`` (``fast``: :func:`int_fast_kernels`); the non-finite count."""
    k = noise.kernel
    if fast is None:  # any dimension, any kernel: the generic kernel (float64, checked by the caller)
        run_split(inthash.int_points, flat, out,
                  (freqs, amps, noise.phase, k.shift, k.left, k.taps, k.coef, k.dcoef, noise.period,
                   noise._pmask, noise._keys, noise._mult, noise._int_grads, int(noise.basis == "gradient"),
                   bool(absval)),
                  workers)
        return 0
    if out.dtype == np.float64:
        variant = "s64f64"
    else:
        # float32 points whose split x * F + phi is exact in float32: no phase or shift, F = 2**e >= 1
        exact32 = (flat.dtype == np.float32 and k.shift == 0.0 and not noise.phase.any()
                   and bool(np.all((freqs >= 1.0) & (np.frexp(freqs)[0] == 0.5))))
        variant = "s32f32" if exact32 else "s64f32"
    factor = int_simd_factor(noise.basis, noise.dim_in)
    limit = noise.bound * float(np.abs(amps).sum())
    return run_split(fast[variant], flat, out, (freqs, amps * factor, noise.phase, noise._keys, noise._pmask,
                                                noise.period, limit, bool(absval)), workers)


def evaluate_points_jac(noise, flat, freqs, amps, absval, name="points", workers=1):
    """Values and Jacobians at points ``flat`` (N, d): float64 ``(N, dim_out, 1 + dim_in)``, value first.

    The octave sum as in :func:`evaluate_points`; with ``absval`` each
    octave's derivative is taken with the sign of its value (turbulence).
    The derivative is in input units (``amps * freqs`` times the lattice-space
    derivative); an overflowed one is refused (:func:`.checks.check_jac_finite`).
    """
    checks.check_differentiable(noise.kernel)
    flat = np.ascontiguousarray(flat, dtype=np.float64)
    freqs = np.ascontiguousarray(freqs, dtype=np.float64)
    amps = np.ascontiguousarray(amps, dtype=np.float64)
    out = np.empty((flat.shape[0], noise.dim_out, noise.dim_in + 1))
    if flat.shape[0]:
        checks.check_reach(flat, freqs, noise.phase, name)  # as for values: x * frequency + phase must stay finite
        k = noise.kernel
        basis = 0 if noise.basis == "value" else 1
        unrolled = unrolled_jacobian_kernel(noise.dim_in, k.taps)
        tabled = table_jacobian_kernel(noise.dim_in, k.taps)
        if noise.hash == "integer":
            run_split(inthash.int_points_jac, flat, out,
                      (freqs, amps, noise.phase, k.shift, k.left, k.taps, k.coef, k.dcoef, noise.period,
                       noise._pmask, noise._keys, noise._mult, noise._int_grads, basis, bool(absval)), workers)
        elif tabled is not None and uses_hash_tables(noise):
            run_split(tabled, flat, out, (freqs, amps, noise.phase, k.shift, k.left, k.coef, k.dcoef,
                                          noise.period, noise._pmask, *cached_hash_tables(noise, basis), basis,
                                          bool(absval)), workers)
        elif unrolled is not None and (noise.period >= k.taps).all():
            run_split(unrolled, flat, out, (freqs, amps, noise.phase, k.shift, k.left, k.coef, k.dcoef,
                                            noise.period, noise._pmask, noise._perms2, noise.values,
                                            noise.gradients, basis, bool(absval)), workers)
        else:
            run_split(jit.eval_points_jac, flat, out,
                      (freqs, amps, noise.phase, k.shift, k.left, k.taps, k.coef, k.dcoef, noise.period,
                       noise._pmask, noise.perms, noise.values, noise.gradients, basis, bool(absval)), workers)
        checks.check_jac_finite(out, f"at the given {name}", checks.jac_bound(freqs, amps))
    return out
