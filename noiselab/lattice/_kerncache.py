"""The generated scattered-point kernels: written on first use into a cache folder, never kept in git.

``_generate.py`` writes three modules of unrolled numba kernels (the table
hash's ``points``, the Jacobians' ``jacobians`` and the integer hash's
``intpoints``). numba's on-disk cache (``cache=True``) needs each kernel to
live in a real file, so :func:`load` writes the module's source into a cache
folder named by a hash of the files the generator reads (``_generate.py``,
``kernels.py``, ``_inthash.py``) and of the hand-written functions the
integer hash's modules call (``_intdriver.py``: numba's cache of a caller
does not notice a changed callee), then imports it from there with
:mod:`importlib` as ``noiselab.lattice._<name>`` (its relative imports of
``._jit`` and ``._inthash`` work as they did in the package). A new
generator, a new kernel or a new hash constant gives a new folder, so a
stale module is never used; an unchanged one is written once per machine.

A file found in the cache is compared with the generator's text (a few
milliseconds, once per module and process): one that differs (truncated,
overwritten, damaged on disk) is written anew, or, where its folder cannot be
written, passed over for the next folder, and the ``noiselab`` logger says so
in one warning line. A signal that stops the process while a file is written
leaves no temporary file (the write is a held step of
:func:`noiselab.io.atomic.hold_signals`).

The folder is ``$NUMBA_CACHE_DIR/noiselab-kernels-<hash>`` when
``NUMBA_CACHE_DIR`` is set, else ``$XDG_CACHE_HOME/noiselab/kernels-<hash>``
(``~/.cache`` by default), else, when neither can be written, one under the
temporary directory. The file is written to a temporary name and moved into
place with :func:`os.replace`, so two processes racing to write it both
succeed and neither ever imports half a file; its modification time is set
to a fixed value, so whichever process wrote it, numba's cache (keyed by the
file's size and time) stays valid. A folder that cannot take the file (a
full disk, read-only, not a folder) passes to the next; when none can, the
kernels run from memory, uncached (compiled anew in each process), and the
``noiselab`` logger says so at INFO level: the results are the same.
"""
from __future__ import annotations

import functools
import hashlib
import importlib.util
import logging
import os
import sys
import tempfile
import threading
import types
from pathlib import Path

from .._core.jitcache import warn_once

# module name -> the generator function that writes its source (called with load()'s extra arguments)
GENERATORS = {"points": "generate", "jacobians": "generate_jacobians", "intpoints": "generate_int",
              "intpart": "generate_int_part"}
# the files whose content decides the generated text
_INPUTS = ("_generate.py", "kernels.py", "_inthash.py", "_intdriver.py")
_STAMP = 1_000_000_000  # the fixed mtime of a written module (see the module docstring)
_LOADED = {}
_LOCK = threading.RLock()  # one import per module when threads (workers=) ask at once
_HERE = Path(__file__).resolve().parent
_log = logging.getLogger("noiselab")


@functools.lru_cache(maxsize=None)
def source_hash() -> str:
    """A 16-hex-digit hash of the generator's inputs (the cache folder's name carries it).

    Read once per process, when the generator is imported (:func:`path`), so
    that one process never writes an older generator's text under a newer hash.
    """
    from . import _generate  # noqa: F401  (imported with the files it hashes)

    h = hashlib.sha256()
    for name in _INPUTS:
        h.update(name.encode() + b"\0" + (_HERE / name).read_bytes() + b"\0")
    return h.hexdigest()[:16]


def _writable(folder: Path) -> bool:
    from ..io.atomic import hold_signals

    try:
        folder.mkdir(parents=True, exist_ok=True)
        with hold_signals():   # a stopping signal waits for the probe to be gone
            probe = tempfile.NamedTemporaryFile(dir=folder, prefix=".probe-", delete=True)
            probe.close()
        return True
    except OSError:
        return False


def candidate_folders() -> list:
    """The folders the generated modules may go to, in the order tried (see the module docstring)."""
    key = source_hash()
    tried = []
    if os.environ.get("NUMBA_CACHE_DIR"):
        tried.append(Path(os.environ["NUMBA_CACHE_DIR"]) / f"noiselab-kernels-{key}")
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    tried.append(Path(base) / "noiselab" / f"kernels-{key}")
    user = os.getuid() if hasattr(os, "getuid") else "user"
    tried.append(Path(tempfile.gettempdir()) / f"noiselab-{user}-kernels-{key}")
    return tried


def cache_folder() -> Path:
    """The first folder of :func:`candidate_folders` that can be written (created)."""
    tried = candidate_folders()
    for folder in tried:
        if _writable(folder):
            return folder
    raise OSError(f"no writable folder for noiselab's generated kernels; tried {', '.join(map(str, tried))} "
                  "(set NUMBA_CACHE_DIR to a writable folder)")


def _write(target: Path, data: bytes) -> None:
    """Write ``data`` to ``target`` atomically (temporary file + os.replace)."""
    from ..io.atomic import hold_signals

    # held: a stopping signal (the command line's handler exits at once) waits for the
    # temporary file to be renamed or removed, so none is left in the cache folder
    with hold_signals():
        fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.stem}-", suffix=".tmp")
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data)
            os.utime(tmp, (_STAMP, _STAMP))
            os.replace(tmp, target)
        except BaseException:
            try:
                os.unlink(tmp)
            except OSError:
                pass
            raise


def _stem(name, args):
    """``_name`` or ``_name_arg1_arg2`` (``-`` written ``_``): the module's file stem and last name part."""
    return "_" + "_".join([name] + [str(a).replace("-", "_") for a in args])


def _check_name(name):
    if name not in GENERATORS:
        raise ValueError(f"name must be one of {sorted(GENERATORS)}, got {name!r}")


def _source(name, args):
    from . import _generate

    return getattr(_generate, GENERATORS[name])(*args)


def path(name: str, *args) -> Path | None:
    """The file of generated module ``name`` (one of :data:`GENERATORS`, with its arguments), written if missing.

    Each of :func:`candidate_folders` is tried in turn; a folder that cannot
    take the file (read-only, full, not a folder) passes to the next. None
    when none can: :func:`load` then runs the kernels uncached.
    """
    _check_name(name)
    data = _source(name, args).encode()
    failed = []
    for folder in candidate_folders():
        target = folder / f"{_stem(name, args)}.py"
        try:
            found = target.read_bytes()
        except OSError:   # missing (the usual first use), a folder, unreadable
            found = None
        if found == data:
            return target
        if found is not None or os.path.lexists(target):
            warn_once(f"the generated lattice kernels {target} differ from the generator's text (damaged?); "
                      "written anew")
        try:
            folder.mkdir(parents=True, exist_ok=True)
            _write(target, data)
            return target
        except OSError as exc:
            failed.append(f"{folder} ({exc.strerror or exc})")
    _log.info("noiselab: no folder could take the generated lattice kernels (%s); they run uncached, "
              "compiled anew in every process (set NUMBA_CACHE_DIR to a writable folder)", "; ".join(failed))
    return None


def _uncached_module(qual, name, args):
    """The generated module executed from memory, its kernels with ``cache=False`` (numba caches need a file).

    The fallback when no cache folder can be written (a full disk, a read-only
    home): the same kernels, compiled in every process instead of once per
    machine. Logged on the ``noiselab`` logger, not printed: a user's command
    keeps its one line of output, and nothing is wrong with the results.
    """
    source = _source(name, args).replace("cache=True", "cache=False")
    mod = types.ModuleType(qual)
    mod.__package__ = __package__
    sys.modules[qual] = mod
    try:
        exec(compile(source, f"<noiselab generated {qual}>", "exec"), mod.__dict__)
    except BaseException:
        del sys.modules[qual]
        raise
    return mod


def load(name: str, *args):
    """The generated module ``name`` (``"points"``, ``"jacobians"``, ``"intpoints"``), imported once per process.

    ``"intpart"`` with ``(d, kernel name, basis)`` is one part of the integer
    hash's kernels; ``_intpoints.INT_KERNELS`` loads the parts on demand.

    Examples
    --------
    >>> from noiselab.lattice import _kerncache
    >>> mod = _kerncache.load("points")
    >>> sorted(mod.KERNELS)[:2]
    [(1, 1), (1, 2)]
    """
    stem = _stem(name, args)
    mod = _LOADED.get(stem)
    if mod is not None:
        return mod
    with _LOCK:
        qual = f"{__package__}.{stem}"
        mod = sys.modules.get(qual)
        if mod is None:
            _check_name(name)
            file = path(name, *args)
            if file is None:
                mod = _uncached_module(qual, name, args)
                _LOADED[stem] = mod
                return mod
            spec = importlib.util.spec_from_file_location(qual, file)
            mod = importlib.util.module_from_spec(spec)
            sys.modules[qual] = mod  # before exec: numba and pickling look the module up by name
            try:
                spec.loader.exec_module(mod)
            except BaseException:
                del sys.modules[qual]
                raise
        _LOADED[stem] = mod
    return mod


if __name__ == "__main__":  # where the generated modules are (written if missing)
    for _name in ("points", "jacobians", "intpoints"):
        print(path(_name))
