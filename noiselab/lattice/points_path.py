"""The points path: lattice noise (or its octave sum, or with its Jacobian) at scattered points.

:func:`prepare_points` takes the points in the caller's layout (``axis``:
which axis holds the coordinates; ``(N, d)`` rows or ``(d, N)`` columns are
read in place, without a copy) as ``(N, dim_in)`` rows;
:func:`evaluate_points` and :func:`evaluate_points_jac` run the one point
kernel of :mod:`._jit` that fits the noise (:func:`._jit.points_kernel`:
hash, dimension, tap count, derivative flag, and whether any axis has a
period of its own) over blocks of points on ``workers`` threads
(:func:`noiselab._core.run_split`: every point's arithmetic is the same
whatever the split, so any worker count gives the same bits). These
functions read a noise's tables and change nothing.
"""
from __future__ import annotations

import numpy as np

from .._core import as_array, check_finite_array, float_dtype, run_split
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
    float64 points are used in place in either layout (a transposed view for
    ``axis=0``); other points are copied to float64 rows.
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
    return lead, flat.astype(np.float64, copy=False)


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


def kernel_args(noise, freqs, amps, absval):
    """The point kernel's arguments after ``(points, out)`` (:func:`._jit.points_kernel`)."""
    k = noise.kernel
    head = (np.ascontiguousarray(freqs, dtype=np.float64), np.ascontiguousarray(amps, dtype=np.float64),
            noise.phase, k.shift, k.left, k.taps, k.coef, k.dcoef, noise.period, noise._pmask)
    if noise.hash == "integer":
        tail = (noise.keys, noise._mult, noise._int_grads)
    else:
        tail = (noise.perms, noise.values, noise.gradients)
    return head + tail + (int(noise.basis == "gradient"), bool(absval))


def _kernel(noise, deriv):
    """The compiled point kernel for this noise (one per hash, dimension, taps, derivative and period flag)."""
    integer = noise.hash == "integer"
    free = jit.PERIOD_MAX if integer else noise.table_size  # the period an axis has without ``period``
    return jit.points_kernel(integer, noise.dim_in, noise.kernel.taps, deriv, bool((noise.period != free).any()))


def evaluate_points(noise, flat, freqs, amps, absval, dtype, name="points", workers=1):
    """``sum_o amps[o] * b(noise(flat * freqs[o] + phase))`` at ``flat`` (N, dim_in): ``(N, dim_out)`` in ``dtype``.

    ``b`` is the identity or ``abs`` (``absval``); ``amps`` already holds the
    range normalisation (``noise.scale``). The computation is float64;
    float32 output is the float64 result rounded once.
    """
    out = np.empty((flat.shape[0], noise.dim_out))
    if flat.shape[0]:
        checks.check_reach(flat, freqs, noise.phase, name)  # NaN, inf and overflowing x * frequency
        run_split(_kernel(noise, False), flat, out, kernel_args(noise, freqs, amps, absval), workers)
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
        run_split(_kernel(noise, True), flat, out, kernel_args(noise, freqs, amps, absval), workers)
        checks.check_jac_finite(out, f"at the given {name}", checks.jac_bound(freqs, amps))
    return out
