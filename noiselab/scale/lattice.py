"""Chunked lattice grids and fractal sums: lazy ``dask.array`` arrays, bit-identical to in memory.

Lattice noise is pointwise, so a chunk is just a window of the full grid:
each chunk is one task that calls the grid path with ``window=`` (the
``(lo, hi)`` sample range of the chunk along every axis). Every decision that
could depend on the tile (separable or scattered path per octave, the octave
batches, which octaves are visible) is taken on the *full* grid, so any
chunking gives the same bits as ``noise.grid(shape, extent)`` in one piece
(tested for uneven chunkings in 1-4-D, vector output, periods, turbulence).
There is no global normalisation: the range is the analytic bound, as in
memory, and ``normalize=True`` divides by the same constant in every chunk.

The graph holds one copy of the noise (a few KiB of tables) as its own key,
so a distributed scheduler ships it to each worker once, not with every task.
"""
from __future__ import annotations

import copy
import numbers
import uuid

import numpy as np

from .._core import dispatch, require_dask

__all__ = ["chunked_grid", "chunked_sum", "normalize_grid_chunks"]


def normalize_grid_chunks(chunks, shape, dim_out, dtype):
    """dask chunks of a grid of ``shape`` (plus one whole chunk for ``dim_out > 1`` components).

    ``chunks`` is dask's chunk syntax over the grid axes: an int (every axis),
    ``"auto"``, or one entry per grid axis (an int, ``-1`` for the whole axis,
    ``"auto"`` or an explicit tuple of block sizes, which may be uneven). For
    vector noise an extra last entry for the component axis may be given; it
    must be ``-1`` or ``dim_out`` (the components of one sample are computed
    together).
    """
    from dask.array.core import normalize_chunks

    shape = tuple(int(s) for s in shape)
    ndim = len(shape)
    if isinstance(chunks, (bool, np.bool_)):
        raise TypeError(f"chunks must be an int, 'auto' or one entry per grid axis, got {chunks!r}")
    if isinstance(chunks, (str, numbers.Integral)):
        spec = (chunks,) * ndim
    elif isinstance(chunks, (tuple, list)):
        spec = tuple(chunks)
    else:
        raise TypeError(f"chunks must be an int, 'auto' or one entry per grid axis, got {type(chunks).__name__}")
    full = shape
    if dim_out > 1:
        if len(spec) == ndim + 1:
            last = spec[-1]
            if not (last == -1 or last == dim_out or (isinstance(last, (tuple, list)) and tuple(last) == (dim_out,))):
                raise ValueError(f"chunks: the component axis (dim_out={dim_out}) must be one chunk "
                                 f"(-1 or {dim_out}), got {last!r}")
            spec = spec[:-1]
        spec = spec + (dim_out,)
        full = shape + (dim_out,)
    if len(spec) != len(full):
        raise ValueError(f"chunks must have one entry per grid axis ({ndim}), got {len(spec)}: {chunks!r}")
    for a, c in enumerate(spec):
        if isinstance(c, (bool, np.bool_)):
            raise TypeError(f"chunks[{a}] must be an int, -1, 'auto' or a tuple of block sizes, got {c!r}")
        if isinstance(c, numbers.Integral) and c != -1 and c < 1:
            raise ValueError(f"chunks[{a}] must be >= 1 (or -1 for the whole axis), got {c}")
        if isinstance(c, (tuple, list)) and any(not isinstance(b, numbers.Integral) or b < 0 for b in c):
            raise ValueError(f"chunks[{a}] block sizes must be non-negative ints, got {c!r}")
    try:
        return normalize_chunks(spec, full, dtype=np.dtype(dtype))
    except (ValueError, TypeError, ZeroDivisionError) as exc:
        raise ValueError(f"chunks {chunks!r} do not fit the grid shape {shape}: {exc}") from None


def _noise_token(noise):
    """A deterministic token of a LatticeNoise's whole state (so equal noises share dask keys)."""
    from dask.base import tokenize

    k = noise.kernel
    return tokenize(type(noise).__qualname__, noise.dim_in, noise.dim_out, k.name, np.asarray(k.coef), k.shift,
                    k.left, k.taps, noise.basis, noise.alternation, getattr(noise, "hash", "table"), noise.table_size, noise.period,
                    noise.frequency, noise.phase, noise.scale, noise.perms, noise.values, noise.gradients)


def _build(prefix, render, noise, token, shape, chunks, args, dtype):
    """A dask array whose block at index ``idx`` is ``render(noise, window(idx), *args)``."""
    da = require_dask()
    import itertools

    from dask.highlevelgraph import HighLevelGraph

    name = f"{prefix}-{token}"
    noise_key = f"{prefix}-noise-{token}"
    grid_chunks = chunks[:len(shape)]
    starts = [np.concatenate([[0], np.cumsum(c)]).astype(int).tolist() for c in grid_chunks]
    extra = (0,) * (len(chunks) - len(shape))  # the component axis: one block
    dsk = {noise_key: noise}
    for idx in itertools.product(*[range(len(c)) for c in grid_chunks]):
        window = tuple((starts[a][i], starts[a][i + 1]) for a, i in enumerate(idx))
        dsk[(name,) + idx + extra] = (render, noise_key, window) + tuple(args)
    graph = HighLevelGraph.from_collections(name, dsk, dependencies=())
    return da.Array(graph, name, chunks, dtype=dtype)


def _render_grid(noise, window, shape, ext, dtype):
    return noise.grid(shape, ext, dtype=dtype, window=window)


@dispatch.register("lattice_grid")
def chunked_grid(noise, shape, extent, *, dtype=np.float64, chunks="auto", window=None):
    """``noise.grid(shape, extent, dtype=dtype)`` as a lazy dask array in ``chunks``.

    Called by :meth:`noiselab.lattice.LatticeNoise.grid` when ``chunks`` is
    given; see there. Each chunk is ``noise.grid(..., window=chunk)``, so the
    result is bit-identical to the in-memory grid for any chunking.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.lattice import LatticeNoise
    >>> noise = LatticeNoise(2, rng=1)
    >>> lazy = noise.grid((100, 60), [(0, 4), (0, 3)], chunks=(30, (10, 50)))
    >>> lazy.chunks
    ((30, 30, 30, 10), (10, 50))
    >>> bool(np.array_equal(lazy.compute(), noise.grid((100, 60), [(0, 4), (0, 3)])))
    True
    """
    require_dask()
    from .._core import float_dtype
    from ..lattice.grid import check_grid

    if window is not None:
        raise ValueError("window= and chunks= cannot be combined: slice the chunked array instead "
                         "(dask computes only the chunks the slice touches)")
    dtype = float_dtype(dtype)
    shape, ext = check_grid(shape, extent, noise.dim_in)
    chunks = normalize_grid_chunks(chunks, shape, noise.dim_out, dtype)
    noise = copy.deepcopy(noise)  # later changes to the caller's noise must not reach the lazy array
    from dask.base import tokenize

    token = tokenize(_noise_token(noise), shape, ext, dtype.str, chunks)
    return _build("lattice-grid", _render_grid, noise, token, shape, chunks, (shape, ext, dtype), dtype)


def _render_sum(noise, window, shape, ext, dtype, used, lacunarity, gain, absval, norm):
    # exactly what noiselab.fractal._sum does on the whole grid, on a window of it
    out = noise.evaluate_grid(shape, ext, dtype=dtype, window=window, octaves=used, lacunarity=lacunarity, gain=gain,
                              absval=absval)
    if norm is not None:
        out /= np.asarray(norm, dtype=out.dtype)
    return out


def _render_sum_callable(noise, window, shape, ext, dtype, used, lacunarity, gain, absval, norm):
    # exactly what noiselab.fractal._sum does for a callable on a grid, on the window's points
    from ..fractal.octaves import callable_sum
    from ..lattice import grid_coordinates

    sub = [c[lo:hi] for c, (lo, hi) in zip(grid_coordinates(shape, ext), window)]
    pts = np.stack(np.meshgrid(*sub, indexing="ij"), axis=-1)
    return callable_sum(noise, pts, used, lacunarity, gain, absval, 1.0 if norm is None else norm, np.dtype(dtype))


@dispatch.register("fractal_sum")
def chunked_sum(noise, shape, ext, chunks, *, dtype, used, lacunarity, gain, absval, norm):
    """The fractal sum / turbulence of :func:`noiselab.fractal.fractal_sum` on a grid, as a lazy dask array.

    Called by ``fractal_sum`` and ``turbulence`` when ``chunks`` is given
    (after they validated the arguments and decided the octaves on the full
    grid); ``norm`` is the normalising constant or None.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.lattice import LatticeNoise, Grid
    >>> from noiselab.fractal import fractal_sum
    >>> noise, grid = LatticeNoise(3, rng=2), Grid((24, 20, 16), [(0, 2)] * 3)
    >>> lazy = fractal_sum(noise, grid, 5, chunks=(7, 20, 9))
    >>> bool(np.array_equal(lazy.compute(), fractal_sum(noise, grid, 5)))
    True
    """
    require_dask()
    from ..lattice import LatticeNoise

    shape = tuple(shape)
    is_lattice = isinstance(noise, LatticeNoise)
    dim_out = noise.dim_out if is_lattice else 1
    chunks = normalize_grid_chunks(chunks, shape, dim_out, dtype)
    from dask.base import tokenize

    if is_lattice:
        noise = copy.deepcopy(noise)
        token = tokenize(_noise_token(noise), shape, ext, np.dtype(dtype).str, chunks, used, lacunarity, gain,
                         absval, norm)
        render = _render_sum
    else:
        # an arbitrary callable has no reliable token: a fresh key
        token = uuid.uuid4().hex
        render = _render_sum_callable
        # vector output: probe one point for the number of components
        first = np.array([[e[0] for e in ext]], dtype=np.float64)
        probe = np.asarray(noise(first))
        if probe.ndim == 2:
            chunks = normalize_grid_chunks(chunks, shape, probe.shape[1], dtype)
    prefix = "turbulence" if absval else "fractal-sum"
    return _build(prefix, render, noise, token, shape, chunks,
                  (shape, ext, np.dtype(dtype), used, lacunarity, gain, absval, norm), np.dtype(dtype))
