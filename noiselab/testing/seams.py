"""Assertion about seams: an array tiles (or loops) along its axes without a visible jump."""
from __future__ import annotations

import numbers
from dataclasses import dataclass

import numpy as np
from scipy import stats

from .._core import HIDE_ASSERTION_FRAMES, as_array, check_axes, check_finite_array, check_int
from .spectra import check_false_alarm

__all__ = ["SeamCheck", "assert_seamless"]


@dataclass(frozen=True)
class SeamCheck:
    """The steps across the seams of an array against its ordinary steps, per tested axis.

    Attributes
    ----------
    axes : tuple of int
    ratio : tuple of float
        Per axis: RMS step across its worst seam over the typical (geometric-mean) RMS ordinary step; about 1 when seamless.
    limit : tuple of float
        The largest ratio allowed on that axis.
    message : str
    """

    axes: tuple
    ratio: tuple
    limit: tuple
    message: str


def _step_mean_squares(arr, axis):
    """Mean square of every step ``x[i+1] - x[i]`` along ``axis`` (over the other axes), and of the wrap ``x[0] - x[-1]``."""
    other = tuple(a for a in range(arr.ndim) if a != axis)
    steps = np.mean(np.square(np.diff(arr, axis=axis)), axis=other) if other else np.square(np.diff(arr))
    first, last = np.take(arr, 0, axis=axis), np.take(arr, -1, axis=axis)
    wrap = float(np.mean(np.square(first - last)))
    return np.asarray(steps, dtype=np.float64), wrap


def _periods(period, axes, shape):
    if period is None:
        return {a: shape[a] for a in axes}
    if isinstance(period, numbers.Integral):
        period = (period,) * len(axes)
    if isinstance(period, (str, bytes, set, frozenset, dict)) or not hasattr(period, "__len__"):
        raise TypeError(f"period must be an int or one int per tested axis, got {type(period).__name__}")
    if len(period) != len(axes):
        raise ValueError(f"period must give one tile length per tested axis {axes}, got {len(period)}")
    out = {}
    for i, (a, p) in enumerate(zip(axes, period)):
        p = check_int(f"period[{i}]", p, lo=2, hi=shape[a])
        if shape[a] % p:
            raise ValueError(f"period[{i}] = {p} does not divide the array's length {shape[a]} along axis {a}")
        out[a] = p
    return out


def assert_seamless(array, axes=None, *, period=None, false_alarm=1e-3) -> SeamCheck:
    """Assert that ``array`` tiles (an image) or loops (a video's time axis) along ``axes`` without a seam.

    Along each axis the step across a seam -- from the last slice to the
    first (the wrap-around a tiling or a loop shows), and with ``period`` from
    slice ``j*period - 1`` to ``j*period`` -- must look like one more
    ordinary step. Every step's mean square (over the other axes) is taken,
    and the seams' log mean squares are compared with the one-sided
    prediction interval of the ordinary steps' log mean squares: mean +
    ``t sd sqrt(1 + 1/k)``, ``t`` Student's quantile with ``k - 1`` degrees of
    freedom at ``false_alarm`` split evenly over every seam tested
    (Bonferroni). A field that tiles fails with probability at most about
    ``false_alarm``; a smooth field cut anywhere jumps by many of its
    ordinary steps.

    Parameters
    ----------
    array : array_like
        Real, 1-D to 4-D; e.g. a tile ``(height, width)`` or a loop ``(frames, height, width)``.
    axes : int or tuple of int, optional
        The axes that must tile or loop (default: every axis).
    period : int or tuple of int, optional
        Tile length along each tested axis when the array holds several
        tiles side by side (must divide the length); default: the array is one tile.
    false_alarm : float
        Probability that a seamless array fails (1e-12 to 0.5).

    Returns
    -------
    SeamCheck

    Raises
    ------
    AssertionError
        If a seam steps further than the ordinary steps allow.
    ValueError, TypeError
        For bad input, naming the parameter.

    Examples
    --------
    >>> import noiselab
    >>> from noiselab.testing import assert_seamless
    >>> tile = noiselab.spectral_noise((128, 128), exponent=1.5, rng=0)
    >>> max(assert_seamless(tile).ratio) < 1.5
    True
    >>> assert_seamless(tile[:100, :100])
    Traceback (most recent call last):
    ...
    AssertionError: seams: ...
    """
    __tracebackhide__ = HIDE_ASSERTION_FRAMES  # a failure reports the caller's line and the message
    arr = check_finite_array("array", as_array("array", array))
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"array must be real and numeric, got dtype {arr.dtype}")
    if not 1 <= arr.ndim <= 4:
        raise ValueError(f"array must be 1-D to 4-D, got {arr.ndim}-D")
    axes = tuple(range(arr.ndim)) if axes is None else check_axes("axes", axes, arr.ndim)
    alpha = check_false_alarm(false_alarm)
    periods = _periods(period, axes, arr.shape)
    big = float(np.max(np.abs(arr))) if arr.size else 0.0
    scale = big if big > 0 else 1.0  # ratios only: divide by the magnitude so squares cannot overflow
    arr = arr.astype(np.float64) / scale
    seams_per_axis = {}
    for a in axes:
        n, p = arr.shape[a], periods[a]
        inner = [j * p - 1 for j in range(1, n // p)]  # steps j*p-1 -> j*p between tiles
        if n - 1 - len(inner) < 4:
            raise ValueError(f"array has {n} samples along axis {a}: comparing a seam with ordinary steps needs "
                             f"at least 4 ordinary steps ({n - 1 - len(inner)} here)")
        seams_per_axis[a] = inner
    n_seams = sum(len(s) + 1 for s in seams_per_axis.values())
    ratios, limits, parts, failed = [], [], [], []
    for a in axes:
        steps, wrap = _step_mean_squares(arr, a)
        inner = seams_per_axis[a]
        seam = np.concatenate([steps[inner], [wrap]])
        ordinary = np.delete(steps, inner)
        tiny = 1e-300
        lo = np.log(np.maximum(ordinary, tiny))
        k = lo.size
        mean, sd = float(lo.mean()), float(lo.std(ddof=1))
        t = float(stats.t.isf(alpha / n_seams, k - 1))
        # at least 1 + 1e-6 in RMS: a rigid translation's steps are equal, and summation order alone must not fail it
        limit_log = max(mean + t * sd * np.sqrt(1 + 1 / k), mean + 2e-6)
        worst = float(np.max(np.log(np.maximum(seam, tiny))))
        # RMS ratios (half the log mean-square differences)
        ratio, limit = float(np.exp(0.5 * (worst - mean))), float(np.exp(0.5 * (limit_log - mean)))
        if ordinary.max() <= tiny and seam.max() <= tiny:
            ratio = 1.0  # constant along this axis: nothing to see
        ratios.append(ratio)
        limits.append(limit)
        bad = not ratio <= limit
        failed.append(bad)
        what = "wrap-around" if not inner else f"worst of {len(inner) + 1} seams (period {periods[a]})"
        parts.append(f"axis {a}: {what} steps {ratio:.3g}x the typical ordinary step (allowed {limit:.3g}x from "
                     f"{k} ordinary steps{' -- SEAM' if bad else ''})")
    msg = ("seams: " + "; ".join(parts) + f". Limit: one-sided prediction interval of the ordinary steps' log mean "
           f"square, Student's t with k-1 dof at false_alarm={alpha:g} split over {n_seams} seam(s)")
    if any(failed):
        raise AssertionError(msg)
    return SeamCheck(axes=tuple(axes), ratio=tuple(ratios), limit=tuple(limits), message=msg)
