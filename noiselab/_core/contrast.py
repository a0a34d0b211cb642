"""Michelson contrast, the one formula shared by a generator and an analyser (internal).

:func:`noiselab.snowfall.parallax_composite` reports the Michelson contrast of
its two regions (thesis Eq. 6.1) and :mod:`noiselab.analysis` measures it;
a generator never imports an analyser, so the definition lives here, in the
shared base, and both ``noiselab.snowfall.michelson_contrast`` and
``noiselab.analysis.michelson_contrast`` are this function.
"""
from __future__ import annotations

import numpy as np

from .validate import as_array, check_finite_array

__all__ = ["masked_values", "michelson_contrast"]


def masked_values(x, mask):
    """The finite values of ``x`` (float64, flat) where the bool ``mask`` (broadcast to ``x``) is set, or all of them."""
    arr = check_finite_array("x", x)
    if arr.size == 0:
        raise ValueError("x is empty")
    if mask is None:
        return arr.astype(np.float64, copy=False).ravel()
    m = as_array("mask", mask)
    if m.dtype != np.bool_:
        raise TypeError(f"mask must be a boolean array, got dtype {m.dtype}")
    try:
        m = np.broadcast_to(m, arr.shape)
    except ValueError:
        raise ValueError(f"mask of shape {m.shape} does not match x of shape {arr.shape}") from None
    vals = arr[m].astype(np.float64)
    if vals.size == 0:
        raise ValueError("mask selects no pixel")
    return vals


def michelson_contrast(x, mask=None) -> float:
    """Michelson contrast ``(Lmax - Lmin) / (Lmax + Lmin)`` of non-negative intensities.

    Parameters
    ----------
    x : array_like
        Intensities (luminance, grey levels, alpha) >= 0: the measure is
        meaningless for signed data.
    mask : bool array, optional
        Pixels to use, broadcastable to ``x`` (e.g. an ``(H, W)`` region for a
        ``(T, H, W)`` video).

    Returns
    -------
    float
        In ``[0, 1]``.

    Raises
    ------
    ValueError
        For negative or non-finite intensities, a mask selecting nothing, or
        all-zero intensities.

    Examples
    --------
    >>> michelson_contrast([50, 150])
    0.5
    """
    v = masked_values(x, mask)
    lo, hi = float(v.min()), float(v.max())
    if lo < 0:
        raise ValueError(f"x: Michelson contrast needs non-negative intensities, got a minimum of {lo:g}")
    if hi == 0:
        raise ValueError("x: Michelson contrast is undefined for an all-zero region")
    return (hi - lo) / (hi + lo)
