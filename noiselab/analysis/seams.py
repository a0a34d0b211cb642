"""Periodicity: the seam cost of looping a video and of tiling an image.

Both compare the step *across* the seam with the ordinary steps beside it,
as root-mean-square differences, so the answer is 1 for a perfect loop or tile
(the seam looks like any other step) and grows with a visible jump.
"""
from __future__ import annotations

import numbers

import numpy as np

from .._core import as_array, check_int
from ._common import check_field, check_video

__all__ = ["loop_seam", "tile_seam"]


def _rms(a) -> float:
    return float(np.sqrt(np.mean(np.square(a, dtype=np.float64))))


def loop_seam(video) -> float:
    """Loop seam cost: RMS step from the last frame to the first over the mean RMS step between consecutive frames.

    1 for a perfect loop (frame ``T-1`` to frame 0 is an ordinary step), larger
    when looping the video jumps. Needs at least 3 frames and a video that
    changes in time.

    Parameters
    ----------
    video : array_like (T, H, W[, 3])
        A finite video of at least 3 frames that changes in time.

    Returns
    -------
    float
        The ratio (>= 0); 1 for a seamless loop.

    Raises
    ------
    ValueError
        For fewer than 3 frames, a non-finite video or one that never changes.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(16)[:, None, None]; x = np.arange(32)[None, None, :]
    >>> loop = np.cos(2 * np.pi * (x / 32 - t / 16)) * np.ones((1, 8, 1))
    >>> round(loop_seam(loop), 6)
    1.0
    >>> loop_seam(loop[:12]) > 3
    True
    >>> round(loop_seam(np.stack([loop, 2 * loop, loop], axis=-1)), 6)   # (T, H, W, 3): colour
    1.0
    """
    v = as_array("video", video)
    if v.ndim == 4:   # a colour video: every channel's steps count, as pixels of a frame three times as wide
        if v.shape[-1] != 3:
            raise ValueError(f"video must be (T, H, W) or a colour (T, H, W, 3), got shape {v.shape}")
        v = v.reshape(v.shape[0], v.shape[1], v.shape[2] * 3)
    arr = _scale_free(check_video("video", v, min_frames=3, min_size=1, allow_constant=True))
    steps = [_rms(arr[t + 1].astype(np.float64) - arr[t]) for t in range(arr.shape[0] - 1)]
    ordinary = float(np.mean(steps))
    if ordinary == 0:
        raise ValueError("video does not change from frame to frame: the loop seam is undefined")
    return _rms(arr[0].astype(np.float64) - arr[-1]) / ordinary


def _scale_free(arr):
    """The seam costs are ratios of RMS steps: divide huge or tiny values by their magnitude so squares stay finite."""
    big = max(abs(float(arr.max())), abs(float(arr.min())))
    if big > 1e100 or 0 < big < 1e-100:
        return arr.astype(np.float64) / big
    return arr


def _axis_seam(arr, axis, tile):
    """RMS step across the seams along ``axis`` over the RMS of the steps right beside them."""
    n = arr.shape[axis]
    diffs = np.diff(arr.astype(np.float64), axis=axis)  # step i -> i + 1 at index i
    seams = [j * tile - 1 for j in range(1, n // tile + 1) if j * tile < n]
    if seams:
        seam = np.take(diffs, seams, axis=axis)
        beside = sorted({i + d for i in seams for d in (-1, 1) if 0 <= i + d < n - 1} - set(seams))
        ordinary = np.take(diffs, beside, axis=axis)
    else:
        # the image is one tile: its wrap-around (last to first) is the seam,
        # beside it the first and the last ordinary steps
        seam = np.take(arr, [0], axis=axis).astype(np.float64) - np.take(arr, [n - 1], axis=axis)
        ordinary = np.take(diffs, [0, n - 2], axis=axis)
    o = _rms(ordinary)
    if o == 0:  # flat beside the seams (piecewise-constant texture): compare with every ordinary step
        keep = np.ones(n - 1, dtype=bool)
        keep[seams] = False
        o = _rms(np.compress(keep, diffs, axis=axis)) if seams else _rms(diffs)
    if o == 0:
        raise ValueError(f"image does not change beside its seams along axis {axis}: the tile seam is undefined")
    return _rms(seam) / o


def tile_seam(image, tile=None) -> float:
    """Tile seam cost: RMS step across tile edges over the RMS of the steps just inside them (max over x and y).

    The reference steps are the ones right beside each seam (one pixel into
    each tile), so a smooth image that changes slowly across the frame is
    compared with its local gradient, not a global average.

    Parameters
    ----------
    image : array_like
        ``(height, width)`` image, or ``(frames, height, width)`` (spatial tiling of every frame).
    tile : int or (th, tw), optional
        Tile size in pixels when ``image`` holds several tiles side by side (the
        seams are the steps from pixel ``j*tile - 1`` to ``j*tile``). Default: the
        image is a single tile and its wrap-around (last row/column to the first)
        is the seam it would show when tiled.

    Returns
    -------
    float: 1 for a seamless tile, larger for a visible seam.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> ky, kx = np.fft.fftfreq(64)[:, None], np.fft.rfftfreq(64)[None, :]
    >>> lowpass = np.exp(-(kx**2 + ky**2) / 0.005)          # smooth periodic texture
    >>> periodic = np.fft.irfft2(lowpass * rng.standard_normal(lowpass.shape), s=(64, 64))
    >>> bool(0.8 < tile_seam(periodic) < 1.25), bool(0.8 < tile_seam(np.tile(periodic, (2, 3)), tile=64) < 1.25)
    (True, True)
    >>> tile_seam(periodic[:40, :40]) > 3                   # a crop does not tile
    True
    >>> y, x = np.mgrid[:32, :32]
    >>> tile_seam(x + y + 0.0) > 10
    True
    """
    arr = _scale_free(check_field("image", image, ndim=(2, 3), min_size=2, allow_constant=True))
    h, w = arr.shape[-2:]
    if tile is None:
        th, tw = h, w
    elif isinstance(tile, numbers.Integral):
        th = tw = check_int("tile", tile, lo=2)
    else:
        if isinstance(tile, (str, bytes, set, frozenset, dict)) or not hasattr(tile, "__len__"):
            raise TypeError(f"tile must be an int or an ordered (height, width) pair, got {type(tile).__name__}")
        if len(tile) != 2:
            raise ValueError(f"tile must be an int or a (height, width) pair, got {tile!r}")
        th, tw = check_int("tile[0]", tile[0], lo=2), check_int("tile[1]", tile[1], lo=2)
    if th > h or tw > w:
        raise ValueError(f"tile {th} x {tw} is larger than the image {h} x {w}")
    if h < 3 or w < 3:
        raise ValueError(f"image of {h} x {w} is too small to compare a seam with ordinary steps (needs 3 x 3)")
    return max(_axis_seam(arr, arr.ndim - 2, th), _axis_seam(arr, arr.ndim - 1, tw))
