"""zarr on dask: streaming a dask array into a store, opening a store lazily (the dask half of ``noiselab.io.zarr``).

:func:`noiselab.io.write_zarr` and :func:`noiselab.io.read_zarr` are the
public functions; ``io`` is a leaf below every layer and never imports dask,
so for a dask array it asks :mod:`noiselab._core.dispatch` for the
implementations registered here. The store's layout, its checks and its
atomic rename stay in one place, :func:`noiselab.io.zarr_store`; this module
only computes the chunks into it, on the scheduler the user chose
(:func:`noiselab.scale.compute`), each chunk written by the worker that
computed it.
"""
from __future__ import annotations

from pathlib import Path

from .._core import dispatch, require_dask
from ..io.zarr import zarr_store
from .run import compute

__all__ = ["write_dask_zarr", "read_dask_zarr"]


def _regular_chunks(data, chunks, da):
    """zarr's (regular) chunk shape for ``data``, and ``data`` regrouped to it."""
    if chunks is None:
        zchunks = tuple(max(max(c), 1) if c else 1 for c in data.chunks)
    else:
        zchunks = tuple(max(max(c), 1) if c else 1
                        for c in da.core.normalize_chunks(chunks, data.shape, dtype=data.dtype))
    regular = tuple(tuple([z] * (s // z) + ([s % z] if s % z else [])) if s else (0,)
                    for z, s in zip(zchunks, data.shape))
    return zchunks, (data if data.chunks == regular else data.rechunk(regular))


@dispatch.register("write_zarr")
def write_dask_zarr(path, data, *, chunks=None, scheduler=None, progress=None, **store):
    """:func:`noiselab.io.write_zarr` of a ``dask.array.Array``: computed chunk by chunk into the store.

    ``store`` holds the store's name, dims, coords, attrs, units, params and
    seed, as :func:`noiselab.io.zarr_store` takes them.

    Examples
    --------
    >>> import os, tempfile, dask.array as da
    >>> from noiselab.io import read_zarr
    >>> out = write_dask_zarr(os.path.join(tempfile.mkdtemp(), "o.zarr"), da.ones((4, 6), chunks=(3, 4)),
    ...                       scheduler="synchronous", progress=False)
    >>> read_zarr(out).chunksize, float(read_zarr(out).sum().compute())
    ((3, 4), 24.0)
    """
    da = require_dask("write_zarr", "zarr")
    if data.dtype.kind not in "biuf":
        raise TypeError(f"data must be a real numeric array, got dtype {data.dtype}")
    zchunks, data = _regular_chunks(data, chunks, da)
    with zarr_store(path, data.shape, data.dtype, zchunks, **store) as target:
        compute(da.store(data, target, lock=False, compute=False), scheduler=scheduler, progress=progress)
    return Path(path)


@dispatch.register("read_zarr")
def read_dask_zarr(path, array, *, name=None, as_xarray=False):
    """The lazy side of :func:`noiselab.io.read_zarr`: ``array`` (an opened ``zarr.Array``) as a dask array.

    With ``as_xarray``, the store at ``path`` opened by xarray and its array
    ``name`` returned as an ``xarray.DataArray`` (dims, coordinates,
    attributes; dask-backed).
    """
    dask_array = require_dask("read_zarr", "zarr")
    if not as_xarray:
        return dask_array.from_zarr(array)
    import xarray

    try:
        return xarray.open_zarr(str(path), consolidated=True)[name]
    except (KeyError, ValueError):  # a store without consolidated metadata (not written by write_zarr)
        return xarray.open_zarr(str(path), consolidated=False)[name]
