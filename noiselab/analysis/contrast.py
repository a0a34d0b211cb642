"""Contrast: Michelson and RMS, over a whole image/video or a mask."""
from __future__ import annotations

import numpy as np

from .._core import check_finite_array
from .._core.contrast import masked_values, michelson_contrast  # one definition, shared with noiselab.snowfall

__all__ = ["michelson_contrast", "rms_contrast", "to_grey"]


def rms_contrast(x, mask=None) -> float:
    """RMS contrast: the standard deviation of the intensities over their mean (``std / mean``).

    The usual definition for luminance images (the root-mean-square of the
    Weber contrast ``(L - mean) / mean``); positive mean required.

    Parameters
    ----------
    x : array_like
        Finite intensities (luminances) with a positive mean.
    mask : array_like of bool, optional
        Only the intensities where it is True (broadcast against ``x``).

    Returns
    -------
    float
        ``std / mean`` (>= 0).

    Raises
    ------
    ValueError
        For non-finite intensities, a mask that selects nothing or a mean that is not positive.

    Examples
    --------
    >>> rms_contrast([50, 150])
    0.5
    """
    v = masked_values(x, mask)
    big = float(np.max(np.abs(v)))
    if big > 1e100 or 0 < big < 1e-100:
        v = v / big  # the contrast is scale-free: scaled, the squares neither overflow nor underflow
    mean = float(v.mean())
    if mean <= 0:
        raise ValueError(f"x: RMS contrast needs a positive mean intensity, got {mean:g}")
    return float(v.std() / mean)


def to_grey(x) -> np.ndarray:
    """Grey level of an RGB image or video (trailing axis of 3 or 4) with Rec. 709 luma weights; grey input passes through.

    float64 input gives float64 grey levels (any finite value, 1e300 included,
    keeps its size), other input float32. The weights sum to 1, so a grey
    level lies between its pixel's smallest and largest channel; where the
    rounding of that weighted sum would pass the dtype's largest value (input
    within an ulp of it) the result is that largest value.

    Parameters
    ----------
    x : array_like
        A finite image or video; RGB(A) when its last axis has 3 or 4 entries
        and it has at least 3 dimensions (alpha is ignored).

    Returns
    -------
    ndarray
        ``0.2126 R + 0.7152 G + 0.0722 B``, or ``x`` itself for grey input.

    Raises
    ------
    ValueError
        For a non-finite array.

    Examples
    --------
    >>> import numpy as np
    >>> to_grey(np.full((2, 2, 3), 1e300))[0, 0]
    np.float64(1e+300)
    >>> to_grey(np.ones((2, 2, 3), np.uint8)).dtype
    dtype('float32')
    """
    arr = check_finite_array("x", x)
    if arr.ndim >= 3 and arr.shape[-1] in (3, 4):
        dtype = np.float64 if arr.dtype == np.float64 else np.float32
        top = np.finfo(dtype).max
        with np.errstate(over="ignore"):
            arr = arr[..., :3].astype(dtype) @ np.array([0.2126, 0.7152, 0.0722], dtype=dtype)
        if not np.isfinite(arr).all():  # only a rounding past the largest value (the input is finite)
            np.clip(arr, -top, top, out=arr)
    return arr
