"""zarr stores with provenance, written atomically from numpy (here) or dask arrays (by the scale-out layer).

A store is a zarr group holding the data array (``"data"`` by default), with
named dimensions (zarr v3 ``dimension_names``, so ``xarray.open_zarr`` gives
a ``DataArray`` with dims and coordinates) and one coordinate array per named
dimension when coordinates are given. The data array's attributes carry the
provenance: what made it and with which parameters (``"params"``), the seed,
the noiselab version, the units.

The store is written under a temporary name beside the target (a dot folder
``.<name>.*.tmp``) and renamed onto it only after every chunk was written: a
failed run leaves no store under the final name, and a killed run only a
temporary folder (it is never mistaken for a result).

``io`` is a leaf every layer may use, so it imports neither dask nor
:mod:`noiselab.scale`: :func:`write_zarr` writes a numpy array itself and hands
a dask array to the implementation that the scale-out layer registered under
``"write_zarr"`` (:mod:`noiselab.scale.zarr`, found through
:mod:`noiselab._core.dispatch`), which streams it chunk by chunk into the
store that :func:`zarr_store` opens; :func:`read_zarr` opens the store here and
lets ``"read_zarr"`` wrap it lazily. zarr is imported on use; it and dask are
the extra ``pip install noiselab[dask]``.
"""
from __future__ import annotations

import contextlib
import datetime
import numbers
import warnings
from pathlib import Path

import numpy as np

from .. import __version__  # the root's metadata: it imports no subpackage when it loads
from .._core import deps, dispatch, renamed_parameters
from .atomic import atomic_output

__all__ = ["write_zarr", "read_zarr", "zarr_store", "is_dask_array", "import_zarr"]

_DEFAULT_NAME = "data"


def import_zarr(what):
    """Import zarr (through the optional-dependency seam of ``noiselab._core.deps``) or name the extra.

    Examples
    --------
    >>> import_zarr("write_zarr").__name__
    'zarr'
    """
    try:
        return deps._import("zarr")
    except ImportError as exc:
        raise ImportError(f"{what} needs the optional package 'zarr', which is not installed: "
                          f"{deps.EXTRA_HINT}") from exc


def is_dask_array(data) -> bool:
    """Whether ``data`` is a ``dask.array.Array``, told without importing dask.

    Examples
    --------
    >>> import numpy as np
    >>> is_dask_array(np.zeros(3))
    False
    """
    return type(data).__module__.startswith("dask.") and hasattr(data, "dask") and hasattr(data, "chunks")


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


def _store_chunks(chunks, shape):
    """The zarr chunk shape for a numpy array: ``None`` lets zarr choose; an int or one entry per axis (-1: whole)."""
    if chunks is None:
        return "auto"
    entries = (chunks,) * len(shape) if isinstance(chunks, numbers.Integral) else tuple(chunks)
    if len(entries) != len(shape) or not all(isinstance(c, numbers.Integral) and not isinstance(c, bool)
                                             and (c >= 1 or c == -1) for c in entries):
        raise ValueError(f"chunks must be an int >= 1 or one per axis of the data ({len(shape)}), each >= 1 or -1 "
                         f"for the whole axis, got {chunks!r}")
    return tuple(max(n, 1) if c == -1 else min(int(c), max(n, 1)) for c, n in zip(entries, shape))


@contextlib.contextmanager
def zarr_store(path, shape, dtype, chunks, *, name=_DEFAULT_NAME, dims=None, coords=None, attrs=None, units=None,
               params=None, seed=None, what="write_zarr"):
    """Open a new store for one array, under a temporary name; rename it onto ``path`` when the block succeeds.

    Everything :func:`write_zarr` checks (the target, the name, the dims, the
    coordinates, the attributes) is checked before anything is created, so a
    bad argument leaves nothing on disk. The block receives the empty
    ``zarr.Array`` (filled with 0) to write into; the coordinate arrays and
    the provenance attributes are already in place, and the consolidated
    metadata is written after the block. This is the one writer of the store
    layout, used by :func:`write_zarr` for numpy arrays and by the scale-out
    layer for dask arrays (``chunks``: the zarr chunk shape, or ``"auto"``).

    Examples
    --------
    >>> import os, tempfile, numpy as np
    >>> out = os.path.join(tempfile.mkdtemp(), "s.zarr")
    >>> with zarr_store(out, (2, 3), "float32", (1, 3), dims=("y", "x")) as target:
    ...     target[:] = 1.0
    >>> float(read_zarr(out).sum().compute())
    6.0
    """
    zarr = import_zarr(what)
    path = Path(path)
    if path.exists() and not (path.is_dir() and _is_zarr_store(path)):
        raise FileExistsError(f"{str(path)!r} exists and is not a zarr store; not replacing it")
    if not isinstance(name, str) or not name or "/" in name:
        raise ValueError(f"name must be a non-empty string without '/', got {name!r}")
    shape = tuple(int(n) for n in shape)
    ndim = len(shape)
    if dims is None:
        dims = tuple(f"dim_{a}" for a in range(ndim))
    dims = tuple(dims)
    if len(dims) != ndim or not all(isinstance(d, str) and d for d in dims) or len(set(dims)) != ndim:
        raise ValueError(f"dims must be {ndim} distinct names, one per axis of the data, got {dims!r}")
    coords = dict(coords or {})
    for d, c in coords.items():
        if d not in dims:
            raise ValueError(f"coords: {d!r} is not one of dims {dims}")
        if np.ndim(c) != 1 or len(c) != shape[dims.index(d)]:
            raise ValueError(f"coords[{d!r}] must be 1-D of length {shape[dims.index(d)]}, got shape {np.shape(c)}")
    meta = {
        "noiselab_version": __version__,
        "created_utc": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "units": units,
        "seed": seed,
        "params": params or {},
    }
    meta.update(attrs or {})
    meta = _jsonable(meta)
    with atomic_output(path, directory=True) as tmp:
        root = zarr.open_group(str(tmp), mode="w", attributes={"noiselab": {"array": name}})
        target = root.create_array(name, shape=shape, chunks=chunks, dtype=dtype, dimension_names=dims,
                                   attributes=meta, fill_value=0)
        for d, c in coords.items():
            c = np.asarray(c)
            arr = root.create_array(d, shape=c.shape, dtype=c.dtype, dimension_names=(d,))
            arr[:] = c
        yield target
        with warnings.catch_warnings():
            # consolidated metadata lets xarray open the store in one read; zarr warns it is a v3 extension
            warnings.simplefilter("ignore")
            zarr.consolidate_metadata(str(tmp))


@renamed_parameters(seed="rng")
def write_zarr(path, data, *, name=_DEFAULT_NAME, dims=None, coords=None, attrs=None, units=None,
               params=None, rng=None, chunks=None, scheduler=None, progress=None):
    """Write ``data`` to the zarr store ``path`` atomically, with provenance in the attributes.

    Parameters
    ----------
    path : str or Path
        The store (a folder, conventionally ``*.zarr``). Its parent must exist.
        An existing zarr store there is replaced (atomically); an existing
        folder that is not a zarr store is refused.
    data : numpy.ndarray or dask.array.Array
        What to write: a real numeric array. A numpy array is written here in
        one go. A dask array is handed to the scale-out layer
        (``noiselab.scale.zarr``), which computes it chunk by chunk on the
        workers and writes each chunk where it was computed: no process ever
        holds more than a few chunks.
    name : str, default "data"
        The data array's name in the store.
    dims : sequence of str, optional
        One name per axis (e.g. ``("z", "y", "x")``); default ``dim_0, dim_1, ...``.
    coords : dict, optional
        ``dim -> 1-D array`` of coordinates, written as arrays beside the data.
    attrs : dict, optional
        Further JSON-like attributes.
    units, params, rng : optional
        Provenance: the data's units (e.g. ``"noise amplitude"``), the
        parameters that made it (a JSON-like dict), the int ``rng=`` that
        drew it (stored as the ``"seed"`` attribute; a ``Generator`` has no
        record and is refused).
    chunks : int or tuple, optional
        The store's chunk shape. For a numpy array: an int (every axis) or one
        entry per axis (``-1``: the whole axis); default: zarr's choice. For a
        dask array: dask's chunk syntax, default the largest dask chunk per
        axis; zarr chunks are regular, so an unevenly chunked dask array is
        rechunked to them first (this only regroups whole dask chunks).
    scheduler, progress
        For a dask array, where and how to compute: see
        :func:`noiselab.scale.compute` (default: the active
        ``distributed.Client``, else dask's threads; a progress bar when
        stderr is a terminal). Not used for a numpy array.

    Returns
    -------
    Path
        ``path``.

    Examples
    --------
    >>> import os, tempfile
    >>> from noiselab.lattice import LatticeNoise
    >>> vol = LatticeNoise(3, rng=1).grid((32, 32, 32), [(0, 4)] * 3, chunks=16, dtype="float32")
    >>> out = write_zarr(os.path.join(tempfile.mkdtemp(), "vol.zarr"), vol, dims=("z", "y", "x"), rng=1)
    >>> back = read_zarr(out)
    >>> back.shape, back.dtype.name, bool((back == vol).all().compute())
    ((32, 32, 32), 'float32', True)
    """
    if rng is not None and (isinstance(rng, (bool, np.bool_)) or not isinstance(rng, numbers.Integral)):
        raise TypeError(f"rng must be the int (or None) that drew the data, to be recorded; got {type(rng).__name__}")
    store = dict(name=name, dims=dims, coords=coords, attrs=attrs, units=units, params=params, seed=rng)
    if is_dask_array(data):
        return dispatch.chunked("write_zarr")(path, data, chunks=chunks, scheduler=scheduler, progress=progress,
                                              **store)
    import_zarr("write_zarr")  # the missing extra is named before the data is looked at
    data = np.asarray(data)
    if data.dtype.kind not in "biuf":
        raise TypeError(f"data must be a real numeric array, got dtype {data.dtype}")
    with zarr_store(path, data.shape, data.dtype, _store_chunks(chunks, data.shape), **store) as target:
        target[...] = data
    return Path(path)


def read_zarr(path, *, name=None, as_xarray=False):
    """Open a zarr store lazily: a ``dask.array.Array`` (or an ``xarray.DataArray``).

    The store is found and checked here; the lazy array is made by the
    scale-out layer (``noiselab.scale.zarr``, registered as ``"read_zarr"``).

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
    zarr = import_zarr("read_zarr")
    path = Path(path)
    if not (path.is_dir() and _is_zarr_store(path)):
        raise FileNotFoundError(f"no zarr store at {str(path)!r}")
    node = zarr.open(str(path), mode="r")
    lazy = dispatch.chunked("read_zarr")
    if isinstance(node, zarr.Array):
        if as_xarray:
            raise ValueError("as_xarray=True needs a zarr group (as write_zarr writes), not a bare array")
        return lazy(path, node)
    if name is None:
        name = dict(node.attrs).get("noiselab", {}).get("array")
        if name is None:
            names = [k for k, _ in node.arrays()]
            if len(names) != 1:
                raise ValueError(f"name: the store holds arrays {sorted(names)}; say which to read")
            name = names[0]
    if name not in node:
        raise ValueError(f"name: no array {name!r} in {str(path)!r}")
    return lazy(path, node[name], name=name, as_xarray=as_xarray)
