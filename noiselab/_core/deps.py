"""The optional dask extra: one place that imports it and says how to install it."""
from __future__ import annotations

import importlib

EXTRA_HINT = "pip install 'noiselab[dask]'"

_import = importlib.import_module  # one seam, so a test can make the extra look absent


def require_dask(what="chunks=", *modules):
    """Import ``dask.array`` (and ``modules``) or raise an ImportError naming the extra.

    Parameters
    ----------
    what : str
        The feature the caller asked for (named in the error).
    *modules : str
        Further modules the feature needs, e.g. ``"zarr"`` or ``"distributed"``.

    Returns
    -------
    module
        ``dask.array``.

    Examples
    --------
    >>> require_dask("chunks=").__name__
    'dask.array'
    """
    loaded = []
    for name in ("dask.array",) + tuple(modules):
        try:
            loaded.append(_import(name))
        except ImportError as exc:
            raise ImportError(f"{what} needs the optional package {name.split('.')[0]!r}, "
                              f"which is not installed: {EXTRA_HINT}") from exc
    return loaded[0]
