"""Contrast: Michelson and RMS, over a whole image/video or a mask."""
from __future__ import annotations

import numpy as np

from .._core import as_array, check_finite_array

__all__ = ["michelson_contrast", "rms_contrast", "to_grey"]


def _values(x, mask):
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

    Examples
    --------
    >>> michelson_contrast([50, 150])
    0.5
    """
    v = _values(x, mask)
    lo, hi = float(v.min()), float(v.max())
    if lo < 0:
        raise ValueError(f"x: Michelson contrast needs non-negative intensities, got a minimum of {lo:g}")
    if hi == 0:
        raise ValueError("x: Michelson contrast is undefined for an all-zero region")
    return (hi - lo) / (hi + lo)


def rms_contrast(x, mask=None) -> float:
    """RMS contrast: the standard deviation of the intensities over their mean (``std / mean``).

    The usual definition for luminance images (the root-mean-square of the
    Weber contrast ``(L - mean) / mean``); positive mean required.

    Examples
    --------
    >>> rms_contrast([50, 150])
    0.5
    """
    v = _values(x, mask)
    big = float(np.max(np.abs(v)))
    if big > 1e100 or 0 < big < 1e-100:
        v = v / big  # the contrast is scale-free: scaled, the squares neither overflow nor underflow
    mean = float(v.mean())
    if mean <= 0:
        raise ValueError(f"x: RMS contrast needs a positive mean intensity, got {mean:g}")
    return float(v.std() / mean)


def to_grey(x) -> np.ndarray:
    """Grey level of an RGB image or video (trailing axis of 3 or 4) with Rec. 709 luma weights; grey input passes through."""
    arr = check_finite_array("x", x)
    if arr.ndim >= 3 and arr.shape[-1] in (3, 4):
        arr = arr[..., :3].astype(np.float32) @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)
    return arr
