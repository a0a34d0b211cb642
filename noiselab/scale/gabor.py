"""Chunked sparse Gabor noise and Gabor snow: lazy ``dask.array`` arrays, bit-identical to in memory.

Gabor noise is evaluated window by window from a counter hash (any window
equals the same region of a larger render to the bit), so a chunk is one task
rendering its window with the in-memory path: no communication between
chunks, no global pass. Gabor snow's opacity map is fixed (not rescaled to a
block's extremes), so it is applied chunk by chunk.

The graph holds one copy of the noise (or of the snow's layers: a few KiB of
frequency tables) as its own key, shipped to each worker once.
"""
from __future__ import annotations

import numpy as np

from .._core import dispatch, require_dask
from .lattice import _build, normalize_grid_chunks

__all__ = ["chunked_gabor_grid", "chunked_gabor_snow"]


def _layers_token(layers):
    from dask.base import tokenize

    return tokenize([(float(w), g.dim, g.frequencies, g.velocities_yx, g.bandwidth, g.density, g.truncation,
                      g.key) for w, g in layers])


def _render_grid(noise, window, origin, step, dtype):
    lo = np.array([a for a, _ in window], dtype=float)
    shape = tuple(b - a for a, b in window)
    return noise.grid(shape, origin=origin + lo * step, step=step, dtype=dtype)


@dispatch.register("gabor_grid")
def chunked_gabor_grid(noise, shape, *, origin, step, dtype, chunks):
    """``noise.grid(shape, origin=origin, step=step, dtype=dtype)`` as a lazy dask array in ``chunks``.

    Called by :meth:`noiselab.gabor.GaborNoise.grid` when ``chunks`` is given.
    Each chunk starts at ``origin + start * step``: bit-identical to the
    in-memory grid when those are the same floats (integer origins and steps).
    """
    require_dask()
    from dask.base import tokenize

    chunks = normalize_grid_chunks(chunks, shape, 1, dtype)
    origin, step = np.asarray(origin, dtype=float), np.asarray(step, dtype=float)
    token = tokenize(_layers_token([(1.0, noise)]), shape, origin, step, np.dtype(dtype).str, chunks)
    return _build("gabor-grid", _render_grid, noise, token, shape, chunks, (origin, step, dtype), dtype)


def _render_snow(layers, window, origin, beta, dtype, rescale):
    from ..gabor import render_layers, snow_opacity

    shape = tuple(b - a for a, b in window)
    start = [o + a for o, (a, _) in zip(origin, window)]
    x = render_layers(layers, shape, origin=start, dtype=np.float64, workers=1)
    return snow_opacity(x, beta=beta, dtype=dtype) if rescale else x.astype(dtype, copy=False)


@dispatch.register("gabor_snow")
def chunked_gabor_snow(layers, shape, *, origin, beta, dtype, rescale, chunks):
    """:func:`noiselab.gabor.gabor_snow` as a lazy dask array in ``chunks`` (called by it when ``chunks`` is given).

    Each chunk is ``gabor_snow`` of its window (origin shifted by the chunk's
    start), so any chunking gives the in-memory bits.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.gabor import gabor_snow
    >>> lazy = gabor_snow((4, 32, 48), rng=3, chunks=(2, 16, (16, 32)))
    >>> lazy.chunks
    ((2, 2), (16, 16), (16, 32))
    >>> bool(np.array_equal(lazy.compute(), gabor_snow((4, 32, 48), rng=3)))
    True
    """
    require_dask()
    from dask.base import tokenize

    chunks = normalize_grid_chunks(chunks, shape, 1, dtype)
    origin = tuple(int(o) for o in origin)
    token = tokenize(_layers_token(layers), shape, origin, float(beta), np.dtype(dtype).str, bool(rescale), chunks)
    return _build("gabor-snow", _render_snow, layers, token, shape, chunks, (origin, beta, dtype, rescale), dtype)
