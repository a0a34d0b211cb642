"""One place where a public function chooses between its in-memory and its dask implementation.

The in-memory core (``spectral``, ``lattice``, ``snow``, ``fractal``, ``io``)
never imports the scale-out layer, dask or distributed. A public function that
takes ``chunks=`` computes in memory when ``chunks`` is None and otherwise
asks :func:`chunked` for the dask implementation registered under its name.
The scale-out layer (:mod:`noiselab.scale`, above the core) registers its
implementations with :func:`register` when it is imported; :func:`chunked`
imports it on first need, by the name in ``SCALE_OUT``, so the core holds a
name, not an import. This is xarray-spatial's ``ArrayTypeFunctionMapping``
turned around: there the public function imports both implementations; here
the dask side is a layer above, so it registers itself.

Examples
--------
>>> from noiselab._core import dispatch
>>> dispatch.chunked("spectral_noise").__module__
'noiselab.scale.spectral'
"""
from __future__ import annotations

import importlib

__all__ = ["SCALE_OUT", "register", "chunked", "registered"]

SCALE_OUT = "noiselab.scale"    # the package whose import registers every dask implementation
_REGISTRY: dict = {}


def register(name: str):
    """Decorator: register ``fn`` as the dask implementation of the public function ``name``."""
    def deco(fn):
        if name in _REGISTRY and _REGISTRY[name] is not fn:
            raise RuntimeError(f"two dask implementations registered for {name!r}: "
                               f"{_REGISTRY[name].__module__} and {fn.__module__}")
        _REGISTRY[name] = fn
        return fn
    return deco


def chunked(name: str):
    """The dask implementation of ``name``, loading the scale-out layer on first need.

    Raises an ImportError naming the ``noiselab[dask]`` extra when dask is not
    installed (raised by the scale-out layer's own import of dask).
    """
    if name not in _REGISTRY:
        importlib.import_module(SCALE_OUT)
    try:
        return _REGISTRY[name]
    except KeyError:
        raise LookupError(f"no dask implementation is registered for {name!r} "
                          f"(known: {', '.join(sorted(_REGISTRY)) or 'none'})") from None


def registered() -> dict:
    """Name -> dask implementation, for what is registered so far (a copy)."""
    return dict(_REGISTRY)
