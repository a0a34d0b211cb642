"""Frequency vectors for the real-FFT half spectrum, broadcast instead of meshgridded.

Units: every vector is in **radians per sample** (radians/pixel along x and y,
radians/frame along t), in ``[-pi, pi]``, as in Zhang's thesis. One cycle per
pixel is ``2*pi`` rad/px; ``f`` cycles per frame of ``n`` pixels is
``2*pi*f/n`` rad/px.

Layout: for an array of shape ``(n0, ..., nd)`` the half spectrum produced by
``scipy.fft.rfftn`` has shape ``(n0, ..., nd//2 + 1)``; axis ``i`` gets the
vector ``2*pi*fftfreq(ni)`` (the last axis ``2*pi*rfftfreq(nd)``) reshaped to
broadcast along its own axis only, e.g. ``(T,1,1), (1,H,1), (1,1,W//2+1)``.
Envelopes are functions of these vectors, so a 64 x 512 x 512 spectrum costs
three short vectors, not three full grids.
"""
from __future__ import annotations

import numpy as np
import scipy.fft

from .._core import check_memory, check_shape, float_dtype

__all__ = ["frequency_vectors", "half_spectrum_shape"]


def half_spectrum_shape(shape) -> tuple[int, ...]:
    """Shape of the ``rfftn`` half spectrum of a real array of ``shape``.

    Parameters
    ----------
    shape : tuple of int
        Shape of the real array.

    Returns
    -------
    tuple of int
        ``shape`` with its last entry ``n`` replaced by ``n // 2 + 1``.

    Examples
    --------
    >>> half_spectrum_shape((64, 512, 512))
    (64, 512, 257)
    """
    shape = check_shape("shape", shape)
    return shape[:-1] + (shape[-1] // 2 + 1,)


def frequency_vectors(shape, *, dtype=np.float64) -> tuple[np.ndarray, ...]:
    """Angular frequencies (rad/sample) of the ``rfftn`` half spectrum, one broadcastable vector per axis.

    Parameters
    ----------
    shape : tuple of int
        Shape of the real array (e.g. ``(T, H, W)``).
    dtype : float32 or float64, optional
        Float dtype of the vectors.

    Returns
    -------
    tuple of ndarray
        ``w[i]`` has length ``shape[i]`` (the last one ``shape[-1]//2 + 1``)
        along axis ``i`` and length 1 elsewhere.

    Examples
    --------
    >>> wt, wy, wx = frequency_vectors((4, 8, 8))
    >>> wt.shape, wy.shape, wx.shape
    ((4, 1, 1), (1, 8, 1), (1, 1, 5))
    >>> float(wx[0, 0, -1])  # the Nyquist frequency, pi rad/px
    3.141592653589793
    """
    shape = check_shape("shape", shape)
    dtype = float_dtype(dtype)
    check_memory(sum(shape) * 8 * 3, f"frequency_vectors{shape}")  # fftfreq's float64 and its product
    d = len(shape)
    out = []
    for i, n in enumerate(shape):
        f = scipy.fft.rfftfreq(n) if i == d - 1 else scipy.fft.fftfreq(n)
        w = (2 * np.pi * f).astype(dtype)
        view = [1] * d
        view[i] = w.size
        out.append(w.reshape(view))
    return tuple(out)
