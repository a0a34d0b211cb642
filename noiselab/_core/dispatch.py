"""One place where a public function chooses between its in-memory and its dask implementation.

The in-memory core (``spectral``, ``lattice``, ``snow``, ``fractal``, ``io``)
never imports the scale-out layer, dask or distributed, and names neither. A
public function that takes ``chunks=`` computes in memory when ``chunks`` is
None and otherwise asks :func:`chunked` for the dask implementation
registered under its name. The scale-out layer (above the core) registers its
implementations with :func:`register` when it is imported.

Which package that is, the core does not say: the package root declares it.
``noiselab/__init__.py`` is the one module that knows every layer (its
``_API`` table maps each top-level name to its subpackage), and Python
imports it before any subpackage, so it also holds ``_DISPATCH_PROVIDERS``:
the modules whose import fills this registry. :func:`chunked` imports them
on first need. An entry point in ``pyproject.toml`` would do the same through
the installed metadata, but then an editable install would need installing
again for the registry to change, and any installed distribution could
register implementations of noiselab's functions; the root's table needs
neither. This is xarray-spatial's ``ArrayTypeFunctionMapping`` turned
around: there the public function imports both implementations; here the
dask side is a layer above, so it registers itself.

Examples
--------
>>> from noiselab._core import dispatch
>>> fn = dispatch.chunked("spectral_noise")   # loads the scale-out layer, which registers its functions
>>> dispatch.registered()["spectral_noise"] is fn
True
"""
from __future__ import annotations

import importlib
import sys

__all__ = ["providers", "register", "chunked", "registered"]

_REGISTRY: dict = {}


def providers() -> tuple:
    """The modules whose import registers the dask implementations, as the package root declares them."""
    root = sys.modules.get(__name__.partition(".")[0])   # the package root, imported before any subpackage
    return tuple(getattr(root, "_DISPATCH_PROVIDERS", ()))


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
        for module in providers():
            importlib.import_module(module)
    try:
        return _REGISTRY[name]
    except KeyError:
        raise LookupError(f"no dask implementation is registered for {name!r} "
                          f"(known: {', '.join(sorted(_REGISTRY)) or 'none'})") from None


def registered() -> dict:
    """Name -> dask implementation, for what is registered so far (a copy)."""
    return dict(_REGISTRY)
