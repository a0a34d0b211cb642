"""Where numba's compile cache keeps noiselab's compiled kernels, and how to clear it.

noiselab's hot kernels are numba functions with ``cache=True``: numba writes
their machine code to disk on the first call and loads it in later processes,
as numba documents (https://numba.readthedocs.io/en/stable/developer/caching.html).
noiselab does not change how numba's cache works: importing noiselab leaves
numba's classes and Python's import machinery as they were.

numba keeps a kernel's files (``*.nbi`` index, ``*.nbc`` data) in the first
of these folders it can write:

- ``$NUMBA_CACHE_DIR/<folder>_<sha1 of the folder's path>`` when
  ``NUMBA_CACHE_DIR`` is set;
- the ``__pycache__`` folder beside the kernel's source file;
- the user-wide cache, ``~/.cache/numba/<folder>_<sha1 of the folder's path>`` on Linux.

A cache damaged on disk (a file truncated by a full disk, copied half) makes
numba raise from a kernel's first call (``EOFError``, ``UnpicklingError``).
The cure is to remove noiselab's cache files, which :func:`clear_cache` does
(from the command line: ``noiselab cache --clear``; ``noiselab cache``
lists the folders), or to point ``NUMBA_CACHE_DIR`` at an empty folder. The
next call compiles the kernels again (seconds) and fills the cache anew.
"""
from __future__ import annotations

import hashlib
import os
import shutil
from pathlib import Path

__all__ = ["cache_folders", "clear_cache", "CACHE_HINT"]

_PACKAGE = Path(__file__).resolve().parents[1]   # the noiselab package folder
_SUFFIXES = (".nbi", ".nbc")

CACHE_HINT = ("numba's compile cache of noiselab's kernels may be damaged: run `noiselab cache --clear` "
              "(or set NUMBA_CACHE_DIR to an empty folder) and run again")


def _source_folders() -> list:
    """noiselab's package folders that hold Python source (where ``cache=True`` kernels can live)."""
    return sorted({p.parent for p in _PACKAGE.rglob("*.py") if "__pycache__" not in p.parts})


def _subpath(folder: Path) -> str:
    """numba's name for a source folder inside a cache root: the folder's name and the SHA-1 of its path."""
    folder = os.path.abspath(folder)
    return f"{os.path.basename(folder)}_{hashlib.sha1(folder.encode()).hexdigest()}"


def _user_wide_root() -> Path | None:
    try:
        from numba.misc.appdirs import AppDirs   # read numba's own answer; nothing is changed
    except ImportError:   # pragma: no cover - another numba layout
        return None
    return Path(AppDirs(appname="numba", appauthor=False).user_cache_dir)


def cache_folders(*, existing: bool = True) -> list:
    """The folders where numba (and noiselab's generated kernels) keep noiselab's compiled code.

    Parameters
    ----------
    existing : bool, optional
        Only the folders that exist now (default); False lists every place
        numba would look.

    Returns
    -------
    list of pathlib.Path

    Examples
    --------
    >>> all(isinstance(p, Path) for p in cache_folders(existing=False))
    True
    """
    folders = []
    roots = []
    env = os.environ.get("NUMBA_CACHE_DIR")
    if env:
        roots.append(Path(env))
        # noiselab's generated kernel modules and numba's files for them
        folders += sorted(Path(env).glob("noiselab-kernels-*")) if Path(env).is_dir() else []
    user = _user_wide_root()
    if user is not None:
        roots.append(user)
    for src in _source_folders():
        folders.append(src / "__pycache__")
        folders += [root / _subpath(src) for root in roots]
    xdg = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "noiselab"
    folders.append(xdg)
    return [f for f in folders if not existing or f.is_dir()]


def clear_cache() -> list:
    """Remove noiselab's compiled-kernel cache files; the next call compiles the kernels anew (seconds).

    The cure for a cache damaged on disk (numba raises ``EOFError`` or an
    unpickling error from a kernel's first call). Python's own ``*.pyc``
    files in ``__pycache__`` are kept; only numba's ``*.nbi``/``*.nbc`` files
    go there, and noiselab's own cache folders are removed whole.

    Returns
    -------
    list of pathlib.Path
        The files and folders removed.

    Examples
    --------
    >>> isinstance(clear_cache(), list)   # doctest: +SKIP
    True
    """
    removed = []
    for folder in cache_folders():
        if folder.name == "__pycache__":
            for f in sorted(folder.iterdir()):
                if f.suffix in _SUFFIXES:
                    f.unlink(missing_ok=True)
                    removed.append(f)
        else:
            shutil.rmtree(folder, ignore_errors=True)
            removed.append(folder)
    return removed
