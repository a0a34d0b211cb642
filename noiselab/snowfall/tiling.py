"""Seamless tiling and looping of periodic videos (thesis 3.4), eagerly or one frame at a time."""
from __future__ import annotations

import math
import numbers

import numpy as np

from .._core import check_finite_array, check_int, check_memory

__all__ = ["tile", "iter_tiled_frames"]


def _check_video(alpha, ndims):
    """A finite real array of one of ``ndims`` dimensions, non-empty (NaN, complex and str are refused)."""
    alpha = check_finite_array("alpha", alpha)  # str, bytes and None are refused there by name
    if alpha.ndim not in ndims:
        shapes = " or ".join(("(T, H, W)", "(H, W)")[3 - d] for d in ndims)
        raise ValueError(f"alpha must have shape {shapes}, got {alpha.shape}")
    if alpha.size == 0:
        raise ValueError(f"alpha is empty (shape {alpha.shape}); every axis needs at least one sample")
    return alpha


def _reps(reps, ndim):
    if isinstance(reps, (bool, np.bool_)):
        raise TypeError(f"reps must be an int or {ndim} ints, got bool")
    if isinstance(reps, numbers.Integral):
        reps = (reps,) * ndim
    if isinstance(reps, (str, bytes, set, frozenset, dict)) or not hasattr(reps, "__iter__"):
        raise TypeError(f"reps must be an int or {ndim} ints, got {type(reps).__name__}")
    reps = tuple(reps)
    if len(reps) != ndim:
        raise ValueError(f"reps must be an int or {ndim} ints (one per axis of a {ndim}-D array), got {reps!r}")
    return tuple(check_int(f"reps[{i}]", r, lo=1) for i, r in enumerate(reps))


def tile(alpha, reps):
    """Repeat a periodic video along t, y and x: ``reps = (rt, ry, rx)`` (or one int for all).

    Spectral snow is periodic in all three axes, so the result has no seams
    and loops: frame ``T - 1`` steps to frame ``0`` like any other frame. A
    still ``(H, W)`` takes ``reps = (ry, rx)``. For outputs too big to hold,
    use :func:`iter_tiled_frames`.

    Parameters
    ----------
    alpha : ndarray (T, H, W) or (H, W)
        A periodic video or still, finite and non-empty.
    reps : int or tuple of int
        ``(rt, ry, rx)`` for a video, ``(ry, rx)`` for a still, or one int for
        every axis; each >= 1.

    Returns
    -------
    ndarray
        ``(rt*T, ry*H, rx*W)`` (or ``(ry*H, rx*W)``), the dtype of ``alpha``.

    Raises
    ------
    ValueError
        For an array of another dimension, an empty or non-finite one, a
        repetition below 1 or of the wrong length.
    MemoryError
        When the tiled array would not fit (estimated before allocating).

    Examples
    --------
    >>> import numpy as np
    >>> tile(np.zeros((4, 8, 8), np.float32), (2, 3, 1)).shape
    (8, 24, 8)
    """
    alpha = _check_video(alpha, (3, 2))
    reps = _reps(reps, alpha.ndim)
    n = math.prod(alpha.shape) * math.prod(reps)
    check_memory(n * alpha.itemsize, f"tile{reps}")
    return np.tile(alpha, reps)


def iter_tiled_frames(alpha, reps=(1, 1), *, n_frames=None, start=0, crop=None):
    """Yield the frames of a tiled, looped video one at a time, never holding the whole video.

    Parameters
    ----------
    alpha : ndarray (T, H, W)
        A periodic video (e.g. from :func:`noiselab.snow.snow`).
    reps : int, (ry, rx) or (rt, ry, rx)
        Spatial repetitions (one int: the same along y and x, as in
        :func:`tile`); with three entries ``rt`` also sets the number of
        frames to ``rt * T`` (unless ``n_frames`` is given).
    n_frames : int, optional
        Number of frames to yield (default ``rt * T``); frame ``i`` is
        ``alpha[(start + i) % T]`` tiled, so any length loops seamlessly.
    start : int
        First frame index (modulo ``T``).
    crop : (height, width), optional
        Cut each tiled frame to this size (at most the tiled size).

    Yields
    ------
    ndarray (H*ry, W*rx) or ``crop``

    Raises
    ------
    ValueError
        For an ``alpha`` that is not a finite, non-empty ``(T, H, W)`` video, a
        repetition below 1, a negative ``n_frames`` or a ``crop`` larger than
        the tiled frame.

    Examples
    --------
    >>> import numpy as np
    >>> a = np.arange(2 * 2 * 2, dtype=np.float32).reshape(2, 2, 2)
    >>> frames = list(iter_tiled_frames(a, (1, 2), n_frames=3))
    >>> len(frames), frames[0].shape, bool((frames[2] == frames[0]).all())
    (3, (2, 4), True)
    """
    alpha = _check_video(alpha, (3,))
    if isinstance(reps, numbers.Integral) and not isinstance(reps, (bool, np.bool_)):
        reps = (reps, reps)
    if isinstance(reps, (str, bytes, set, frozenset, dict)) or not hasattr(reps, "__len__"):
        raise TypeError(f"reps must be an int, (ry, rx) or (rt, ry, rx), got {type(reps).__name__}")
    if len(reps) == 3:
        rt, ry, rx = _reps(reps, 3)
    else:
        ry, rx = _reps(reps, 2)
        rt = 1
    T, H, W = alpha.shape
    n_frames = rt * T if n_frames is None else check_int("n_frames", n_frames, lo=0)
    start = check_int("start", start)
    check_memory(H * ry * W * rx * alpha.itemsize * 2, f"tiled frames of {H * ry} x {W * rx}")
    if crop is not None:
        if isinstance(crop, (str, bytes, set, frozenset, dict)) or not hasattr(crop, "__len__") or len(crop) != 2:
            raise ValueError(f"crop must be a pair (height, width) of ints, got {crop!r}")
        ch, cw = (check_int("crop[0]", crop[0], lo=1), check_int("crop[1]", crop[1], lo=1))
        if ch > H * ry or cw > W * rx:
            raise ValueError(f"crop {(ch, cw)} is larger than the tiled frame {(H * ry, W * rx)}")
    return _frames(alpha, ry, rx, n_frames, start, None if crop is None else (ch, cw))


def _frames(alpha, ry, rx, n_frames, start, crop):
    T = alpha.shape[0]
    for i in range(n_frames):
        frame = np.tile(alpha[(start + i) % T], (ry, rx))
        yield frame if crop is None else frame[: crop[0], : crop[1]]
