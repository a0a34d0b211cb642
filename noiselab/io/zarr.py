"""zarr stores with provenance, written atomically from dask (or numpy) arrays.

A store is a zarr group holding the data array (``"data"`` by default), with
named dimensions (zarr v3 ``dimension_names``, so ``xarray.open_zarr`` gives
a ``DataArray`` with dims and coordinates) and one coordinate array per named
dimension when coordinates are given. The data array's attributes carry the
provenance: what made it and with which parameters (``"params"``), the seed,
the noiselab version, the units.

The store is written under a temporary name beside the target (a dot folder
``.<name>.*.tmp``) and renamed onto it only after every chunk was written: a
failed run leaves no store under the final name, and a killed run only a
temporary folder (it is never mistaken for a result). Needs the extra
``pip install noiselab[dask]``.
"""
from __future__ import annotations

import datetime
import numbers
import warnings
from pathlib import Path

import numpy as np

from .atomic import atomic_output

__all__ = ["write_zarr", "read_zarr"]

_DEFAULT_NAME = "data"


def _jsonable(value, where="attrs"):
    """``value`` with numpy scalars and arrays turned into JSON types (zarr attributes are JSON)."""
    if isinstance(value, dict):
        return {str(k): _jsonable(v, f"{where}[{k!r}]") for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v, where) for v in value]
    if isinstance(value, np.ndarray):
        return _jsonable(value.tolist(), where)
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        return float(value)
    if isinstance(value, np.dtype):
        return value.name
    if value is None or isinstance(value, str):
        return value
    if isinstance(value, Path):
        return str(value)
    raise TypeError(f"{where} must be JSON-like (numbers, strings, lists, dicts), got {type(value).__name__}")


def _is_zarr_store(path):
    return any((path / f).exists() for f in ("zarr.json", ".zgroup", ".zarray"))


def write_zarr(path, data, *, name=_DEFAULT_NAME, dims=None, coords=None, attrs=None, units=None,
               params=None, seed=None, chunks=None, scheduler=None, progress=None):
    """Write ``data`` to the zarr store ``path`` atomically, with provenance in the attributes.

    Parameters
    ----------
    path : str or Path
        The store (a folder, conventionally ``*.zarr``). Its parent must exist.
        An existing zarr store there is replaced (atomically); an existing
        folder that is not a zarr store is refused.
    data : dask.array.Array or numpy.ndarray
        What to write. A dask array is computed chunk by chunk on the workers
        and each chunk written where it was computed: no process ever holds
        more than a few chunks.
    name : str, default "data"
        The data array's name in the store.
    dims : sequence of str, optional
        One name per axis (e.g. ``("z", "y", "x")``); default ``dim_0, dim_1, ...``.
    coords : dict, optional
        ``dim -> 1-D array`` of coordinates, written as arrays beside the data.
    attrs : dict, optional
        Further JSON-like attributes.
    units, params, seed : optional
        Provenance: the data's units (e.g. ``"noise amplitude"``), the
        parameters that made it (a JSON-like dict), the seed.
    chunks : int or tuple, optional
        The store's chunk shape (default: the largest dask chunk per axis).
        zarr chunks are regular, so an unevenly chunked dask array is
        rechunked to them first (this only regroups whole dask chunks).
    scheduler, progress
        Where and how to compute: see :func:`noiselab.scale.compute`
        (default: the active ``distributed.Client``, else dask's threads; a
        progress bar when stderr is a terminal).

    Returns
    -------
    Path
        ``path``.

    Examples
    --------
    >>> import os, tempfile
    >>> from noiselab.lattice import LatticeNoise
    >>> vol = LatticeNoise(3, seed=1).grid((32, 32, 32), [(0, 4)] * 3, chunks=16, dtype="float32")
    >>> out = write_zarr(os.path.join(tempfile.mkdtemp(), "vol.zarr"), vol, dims=("z", "y", "x"), seed=1)
    >>> back = read_zarr(out)
    >>> back.shape, back.dtype.name, bool((back == vol).all().compute())
    ((32, 32, 32), 'float32', True)
    """
    from ..scale import compute, require_dask

    da = require_dask("write_zarr", "zarr")
    import zarr

    import noiselab

    path = Path(path)
    if path.exists() and not (path.is_dir() and _is_zarr_store(path)):
        raise FileExistsError(f"{str(path)!r} exists and is not a zarr store; not replacing it")
    if not isinstance(name, str) or not name or "/" in name:
        raise ValueError(f"name must be a non-empty string without '/', got {name!r}")
    if not isinstance(data, da.Array):
        data = np.asarray(data)
        if data.dtype.kind not in "biuf":
            raise TypeError(f"data must be a real numeric array, got dtype {data.dtype}")
        data = da.from_array(data, chunks="auto" if chunks is None else chunks)
    ndim = data.ndim
    if dims is None:
        dims = tuple(f"dim_{a}" for a in range(ndim))
    dims = tuple(dims)
    if len(dims) != ndim or not all(isinstance(d, str) and d for d in dims) or len(set(dims)) != ndim:
        raise ValueError(f"dims must be {ndim} distinct names, one per axis of the data, got {dims!r}")
    coords = dict(coords or {})
    for d, c in coords.items():
        if d not in dims:
            raise ValueError(f"coords: {d!r} is not one of dims {dims}")
        if np.ndim(c) != 1 or len(c) != data.shape[dims.index(d)]:
            raise ValueError(f"coords[{d!r}] must be 1-D of length {data.shape[dims.index(d)]}, got shape {np.shape(c)}")
    if chunks is None:
        zchunks = tuple(max(max(c), 1) if c else 1 for c in data.chunks)
    else:
        zchunks = tuple(max(max(c), 1) if c else 1
                        for c in da.core.normalize_chunks(chunks, data.shape, dtype=data.dtype))
    regular = tuple(tuple([z] * (s // z) + ([s % z] if s % z else [])) if s else (0,)
                    for z, s in zip(zchunks, data.shape))
    if data.chunks != regular:
        data = data.rechunk(regular)
    meta = {
        "noiselab_version": noiselab.__version__,
        "created_utc": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "units": units,
        "seed": seed,
        "params": params or {},
    }
    meta.update(attrs or {})
    meta = _jsonable(meta)
    with atomic_output(path, directory=True) as tmp:
        root = zarr.open_group(str(tmp), mode="w", attributes={"noiselab": {"array": name}})
        target = root.create_array(name, shape=data.shape, chunks=zchunks, dtype=data.dtype,
                                   dimension_names=dims, attributes=meta, fill_value=0)
        for d, c in coords.items():
            c = np.asarray(c)
            arr = root.create_array(d, shape=c.shape, dtype=c.dtype, dimension_names=(d,))
            arr[:] = c
        compute(da.store(data, target, lock=False, compute=False), scheduler=scheduler, progress=progress)
        with warnings.catch_warnings():
            # consolidated metadata lets xarray open the store in one read; zarr warns it is a v3 extension
            warnings.simplefilter("ignore")
            zarr.consolidate_metadata(str(tmp))
    return path


def read_zarr(path, *, name=None, as_xarray=False):
    """Open a zarr store lazily: a ``dask.array.Array`` (or an ``xarray.DataArray``).

    Parameters
    ----------
    path : str or Path
        A store written by :func:`write_zarr` (or any zarr array or group).
    name : str, optional
        The array in a group; default: the one :func:`write_zarr` recorded, else
        the group's only array.
    as_xarray : bool, default False
        Return an ``xarray.DataArray`` with the named dimensions, coordinates
        and the provenance attributes (needs xarray).

    Examples
    --------
    >>> import os, tempfile, numpy as np
    >>> out = write_zarr(os.path.join(tempfile.mkdtemp(), "a.zarr"), np.arange(6.0).reshape(2, 3),
    ...                  dims=("y", "x"), units="m")
    >>> read_zarr(out).sum().compute()
    np.float64(15.0)
    >>> da = read_zarr(out, as_xarray=True)
    >>> da.dims, da.attrs["units"]
    (('y', 'x'), 'm')
    """
    from ..scale import require_dask

    dask_array = require_dask("read_zarr", "zarr")
    import zarr

    path = Path(path)
    if not (path.is_dir() and _is_zarr_store(path)):
        raise FileNotFoundError(f"no zarr store at {str(path)!r}")
    node = zarr.open(str(path), mode="r")
    if isinstance(node, zarr.Array):
        if as_xarray:
            raise ValueError("as_xarray=True needs a zarr group (as write_zarr writes), not a bare array")
        return dask_array.from_zarr(node)
    if name is None:
        name = dict(node.attrs).get("noiselab", {}).get("array")
        if name is None:
            names = [k for k, _ in node.arrays()]
            if len(names) != 1:
                raise ValueError(f"name: the store holds arrays {sorted(names)}; say which to read")
            name = names[0]
    if name not in node:
        raise ValueError(f"name: no array {name!r} in {str(path)!r}")
    if as_xarray:
        import xarray

        try:
            return xarray.open_zarr(str(path), consolidated=True)[name]
        except (KeyError, ValueError):  # a store without consolidated metadata (not written by write_zarr)
            return xarray.open_zarr(str(path), consolidated=False)[name]
    return dask_array.from_zarr(node[name])
