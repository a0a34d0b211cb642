"""numba's on-disk compile cache made forgiving: a damaged, unwritable or missing cache costs a compilation, not a crash.

numba (checked with 0.68) fails inside a kernel's first call, or at import,
when its cache is not as it expects:

- a damaged index or data file (``*.nbi``, ``*.nbc``: truncated by a full
  disk, overwritten, copied half) raises pickle's ``EOFError`` or
  ``UnpicklingError`` from the first call;
- a cache that cannot be saved (a full disk, a folder made read-only)
  raises ``OSError`` after the kernel was compiled;
- with no writable folder at all (a read-only install with a read-only home)
  every ``cache=True`` kernel raises ``RuntimeError: cannot cache function
  ...: no locator available`` when its module is imported;
- two processes that compile different signatures of one kernel at once on
  an empty cache can leave the index naming the other one's data file
  (numba numbers data files by reading the index, then writing it; the two
  writes race), so a later process would load code compiled for other types.

:func:`install` wraps ``numba.core.caching.Cache``'s constructor, loader and
saver so that each of these becomes a compilation without the cache (the
loaded code is checked to be for the types asked for; a damaged index is
removed, so the next save writes a sound one), and the ``noiselab`` logger
says so in one line, once per process (:func:`warn_once`). The results are
the same, cached or not.

noiselab's ``_core`` calls :func:`install` on import; numba itself is patched
when it is imported (a one-shot import hook), so importing noiselab does
not import numba.
"""
from __future__ import annotations

import contextlib
import importlib.abc
import logging
import os
import sys
import threading

__all__ = ["install", "warn_once"]

_log = logging.getLogger("noiselab")
_TARGET = "numba.core.caching"
_warned = []
_lock = threading.Lock()


def warn_once(message: str) -> bool:
    """Log ``message`` as a warning on the ``noiselab`` logger, unless one was logged already; True if logged.

    Without a logging configuration Python prints a warning as the bare
    message on stderr: one line. A cache problem is said once per process,
    however many kernels it touches.

    Examples
    --------
    >>> import logging
    >>> logging.getLogger("noiselab").disabled = True   # (silence the doctest's stderr)
    >>> warn_once("first") in (True, False), warn_once("second")
    (True, False)
    >>> logging.getLogger("noiselab").disabled = False
    """
    with _lock:
        if _warned:
            return False
        _warned.append(message)
    _log.warning("noiselab: %s", message)
    return True


def _reason(exc) -> str:
    text = str(exc).splitlines()[0] if str(exc) else ""
    return f"{type(exc).__name__}: {text}"[:160] if text else type(exc).__name__


def _drop_index(cache) -> None:
    """Remove a cache's index file, so that the next save starts a sound one (its data files get overwritten)."""
    with contextlib.suppress(AttributeError, OSError):
        os.unlink(cache._cache_file._index_path)


def _patch(caching) -> None:
    Cache = caching.Cache
    if getattr(Cache, "_noiselab_guarded", False):
        return
    init, load, save = Cache.__init__, Cache.load_overload, Cache.save_overload

    def __init__(self, py_func):
        try:
            init(self, py_func)
        except RuntimeError as exc:
            if "no locator available" not in str(exc):
                raise
            warn_once(f"no folder can hold numba's compile cache (tried NUMBA_CACHE_DIR, the package's __pycache__ "
                      f"and the home folder, for {getattr(py_func, '__module__', '?')}): kernels are compiled anew "
                      "in every process; set NUMBA_CACHE_DIR to a writable folder")
            self.__class__ = caching.NullCache   # what numba uses for cache=False: loads nothing, saves nothing

    def load_overload(self, sig, target_context):
        try:
            cres = load(self, sig, target_context)
        except Exception as exc:   # a damaged file: pickle's, numba's or llvmlite's error while rebuilding
            _drop_index(self)
            warn_once(f"numba's compile cache in {self.cache_path} held a damaged file ({_reason(exc)}); "
                      "the kernel is compiled anew and the cache rewritten")
            return None
        if cres is not None and not _same_types(sig, cres):   # another process's entry, crossed in the race
            _drop_index(self)
            warn_once(f"numba's compile cache in {self.cache_path} named code compiled for other types (two "
                      "processes saved at once); the kernel is compiled anew and the cache rewritten")
            return None
        return cres

    def save_overload(self, sig, data):
        try:
            save(self, sig, data)
        except Exception as exc:   # a full disk, a folder made read-only, a damaged index read back
            warn_once(f"numba's compile cache in {self.cache_path} could not be written ({_reason(exc)}); "
                      "this kernel is compiled anew in the next process")

    Cache.__init__, Cache.load_overload, Cache.save_overload = __init__, load_overload, save_overload
    Cache._noiselab_guarded = True


def _same_types(sig, cres) -> bool:
    """Whether a loaded compile result is for the argument types ``sig`` asked for."""
    try:
        from numba.core import sigutils

        args, _ = sigutils.normalize_signature(sig)
        return tuple(cres.signature.args) == tuple(args)
    except Exception:   # not a result this check understands (another cache implementation): trust numba
        return True


class _Loader(importlib.abc.Loader):
    """numba.core.caching's own loader, patching the module once it has run."""

    def __init__(self, loader):
        self._loader = loader

    def create_module(self, spec):
        return self._loader.create_module(spec)

    def exec_module(self, module):
        self._loader.exec_module(module)
        _patch(module)

    def __getattr__(self, name):   # get_source, get_filename, ...: the real loader's
        return getattr(self._loader, name)


class _Hook(importlib.abc.MetaPathFinder):
    """Finds numba.core.caching through the other finders and hands it to :class:`_Loader`; then steps aside."""

    def find_spec(self, name, path=None, target=None):
        if name != _TARGET:
            return None
        with contextlib.suppress(ValueError):
            sys.meta_path.remove(self)
        for finder in sys.meta_path:
            spec = finder.find_spec(name, path, target) if hasattr(finder, "find_spec") else None
            if spec is not None:
                if spec.loader is not None and hasattr(spec.loader, "exec_module"):
                    spec.loader = _Loader(spec.loader)
                return spec
        return None


def install() -> None:
    """Guard numba's cache now if numba is imported, else as soon as it is (idempotent).

    Examples
    --------
    >>> install(); install()   # once is enough; again changes nothing
    >>> import numba.core.caching
    >>> numba.core.caching.Cache._noiselab_guarded
    True
    """
    module = sys.modules.get(_TARGET)
    if module is not None and hasattr(module, "Cache"):
        _patch(module)
    elif module is None and not any(isinstance(f, _Hook) for f in sys.meta_path):
        sys.meta_path.insert(0, _Hook())
