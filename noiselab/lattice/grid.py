"""What a regular grid is: :class:`Grid`, :func:`check_grid` and the one formula for its sample coordinates.

Public helpers for every layer that samples lattice noise on a grid
(:mod:`noiselab.fractal`, :mod:`noiselab.fields`, the dask path): they
check a grid the way :meth:`~noiselab.lattice.LatticeNoise.grid` does and
place its samples at exactly the same coordinates, so a sample gets the
same bits on every path.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .._core import check_finite_array, check_shape
from .checks import check_large

__all__ = ["Grid", "check_grid", "grid_coordinates", "coordinates"]


class Grid(NamedTuple):
    """A regular grid: ``shape`` (one count per input axis) over ``extent``.

    ``extent`` holds one ``(start, stop)`` pair per input axis in the noise's
    input units, stop excluded as in ``numpy.arange``: sample ``j`` along axis
    ``a`` sits at ``start + j * (stop - start) / shape[a]``.

    Parameters
    ----------
    shape : tuple of int
        Samples per input axis, in the noise's axis order (``(ny, nx)`` for images).
    extent : sequence of (start, stop)
        One pair per input axis, stop excluded.

    Examples
    --------
    >>> from noiselab.lattice import LatticeNoise
    >>> grid = Grid((64, 128), ((0, 2), (0, 4)))
    >>> LatticeNoise(2, rng=0).grid(*grid).shape
    (64, 128)
    """

    shape: tuple
    extent: tuple


def check_grid(shape, extent, dim):
    """Check a grid of ``dim`` input axes: ``(shape, extent)`` as a tuple of ints and a ``(dim, 2)`` float64 array.

    Parameters
    ----------
    shape : int or sequence of int
        Samples per axis (>= 0 each), ``dim`` of them.
    extent : sequence of (start, stop)
        One finite pair per axis (for ``dim == 1`` a single pair is enough).
    dim : int
        The number of input axes (``LatticeNoise.dim_in``).

    Returns
    -------
    shape : tuple of int
    extent : ndarray, shape (dim, 2), float64

    Raises
    ------
    TypeError, ValueError
        Naming ``shape`` or ``extent`` and what they must be.

    Examples
    --------
    >>> shape, ext = check_grid((4, 3), [(0, 2), (0, 1)], 2)
    >>> shape, ext.tolist()
    ((4, 3), [[0.0, 2.0], [0.0, 1.0]])
    >>> check_grid((4,), [(0, 2), (0, 1)], 1)
    Traceback (most recent call last):
    ...
    ValueError: extent must be one (start, stop) pair per input axis, shape (1, 2); got shape (2, 2)
    """
    shape = check_shape("shape", shape, ndim=dim, min_size=0)
    try:
        ext = check_finite_array("extent", extent).astype(np.float64)
    except TypeError as exc:
        raise TypeError(f"extent must be one (start, stop) pair of reals per input axis: {exc}") from None
    if dim == 1 and ext.shape == (2,):
        ext = ext[None]
    if ext.shape != (dim, 2):
        raise ValueError(f"extent must be one (start, stop) pair per input axis, shape ({dim}, 2); got shape {ext.shape}")
    if not np.isfinite(ext).all():
        raise ValueError("extent must be finite")
    return shape, ext


def grid_coordinates(shape, extent):
    """Per-axis sample coordinates of a grid: ``start + j * ((stop - start) / n)``.

    Both evaluation paths, every window and every octave use exactly this
    formula, so the same sample always gets the same coordinate bits.

    Parameters
    ----------
    shape : tuple of int
        Samples per axis.
    extent : sequence of (start, stop)
        One pair per axis, stop excluded.

    Returns
    -------
    list of ndarray of float64
        One array of ``shape[a]`` coordinates per axis.

    Examples
    --------
    >>> [c.tolist() for c in grid_coordinates((4,), [(0, 2)])]
    [[0.0, 0.5, 1.0, 1.5]]
    """
    shape, ext = check_grid(shape, extent, len(check_shape("shape", shape, min_size=0)))
    return coordinates(shape, ext)


def coordinates(shape, ext):
    """:func:`grid_coordinates` of an already checked shape and (dim, 2) float64 extent (:func:`check_grid`).

    Examples
    --------
    >>> [c.tolist() for c in coordinates((2, 3), np.array([[0.0, 1.0], [0.0, 3.0]]))]
    [[0.0, 0.5], [0.0, 1.0, 2.0]]
    """
    check_large(8 * sum(shape), f"grid coordinates for shape {shape}")
    return [ext[a, 0] + np.arange(n, dtype=np.float64) * ((ext[a, 1] - ext[a, 0]) / max(n, 1))
            for a, n in enumerate(shape)]
