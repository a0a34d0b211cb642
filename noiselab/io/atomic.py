"""Write-to-temporary-then-rename, so a failed run leaves nothing half-written.

Every failure to write (a full disk, a read-only file system, no permission,
an output that is an existing folder, a parent that is a regular file)
becomes an :class:`~noiselab.io.errors.OutputError` naming the target and the
cause, and the temporary file or folder is removed, also when the run is
interrupted: by a ``KeyboardInterrupt`` in library use, and by SIGINT, SIGTERM
or SIGHUP under the command line, whose handler calls
:func:`remove_temporaries` and exits at once (``os._exit``) instead of raising
through whatever library code was running (an exception thrown into numba's
compiler or a half-built imageio writer broke them). For that, every
temporary file or folder and every encoder process is recorded here from the
moment it exists (:func:`hold_signals` closes the gap between creating it and
recording it) until it is renamed into place or removed.
"""
from __future__ import annotations

import contextlib
import ctypes
import ctypes.util
import errno
import os
import shutil
import signal
import tempfile
from pathlib import Path

from .errors import OutputError, output_error

__all__ = ["atomic_output", "prepare_output", "exchange_paths", "hold_signals", "defer_signal", "scratch_folder",
           "track_process", "forget_process", "remove_temporaries", "remove_and_block"]

_held = 0
_deferred = []
# what a stopping signal must remove: temporary path -> True for a folder
_temporaries = {}
# child processes writing into a temporary (ffmpeg): stopped before their file is removed
_processes = []


@contextlib.contextmanager
def hold_signals():
    """Hold a stopping signal (SIGINT/SIGTERM/SIGHUP handled by ``noiselab.cli``) until the block ends.

    Around the few steps that create something that must be cleaned up (a
    temporary file, the ffmpeg process) and record it, so an interruption
    never falls between creating it and knowing about it. A signal that came
    in the meantime is raised again when the block ends.
    """
    global _held
    _held += 1
    try:
        yield
    finally:
        _held -= 1
        if not _held and _deferred:
            signal.raise_signal(_deferred.pop())


def defer_signal(signum) -> bool:
    """Called by a signal handler: True (and the signal kept for later) inside :func:`hold_signals`."""
    if _held:
        _deferred[:] = [signum]
        return True
    return False


def _record(path, directory):
    _temporaries[str(path)] = directory


def _forget(path):
    _temporaries.pop(str(path), None)


def _remove(path, directory):
    if directory:
        shutil.rmtree(path, ignore_errors=True)
    else:
        with contextlib.suppress(OSError):
            os.unlink(path)


def track_process(proc):
    """Record a child process that writes into a temporary file, so a stopping signal ends it first.

    Start the process inside :func:`hold_signals` and record it there; call
    :func:`forget_process` once it has ended. Returns ``proc``.

    Examples
    --------
    >>> import subprocess, sys
    >>> with hold_signals():
    ...     proc = track_process(subprocess.Popen([sys.executable, "-c", "pass"]))
    >>> proc.wait()
    0
    >>> forget_process(proc)
    """
    _processes.append(proc)
    return proc


def forget_process(proc) -> None:
    """Drop a process recorded by :func:`track_process` (it has ended, or been stopped and waited for)."""
    with contextlib.suppress(ValueError):
        _processes.remove(proc)


def _stop_process(proc):
    # os.kill and os.waitpid, not Popen.kill/wait: the handler may have interrupted the main thread
    # inside Popen.wait, which holds a lock that a second wait() would wait on forever
    if proc.returncode is not None:
        return
    with contextlib.suppress(OSError):
        os.kill(proc.pid, signal.SIGKILL)
    with contextlib.suppress(OSError):
        os.waitpid(proc.pid, 0)


def remove_temporaries(*, keep_blockers=False) -> list:
    """Stop the recorded encoder processes and remove every recorded temporary file and folder.

    A folder's name is held by an empty file while the other folders go
    (:func:`remove_and_block`); the files are removed at the end, or, with
    ``keep_blockers``, left to the caller, which removes the returned paths
    just before the process exits (the command line's signal handler).

    What the command line's SIGINT/SIGTERM/SIGHUP handler calls before it
    exits; safe at any moment of the main thread (the records change only
    inside :func:`hold_signals` or in single steps). A process is stopped and
    waited for before its file is removed, so it cannot create the file again.
    Outputs already renamed into place are not recorded any more and stay.

    Examples
    --------
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> writing = atomic_output(os.path.join(d, "a.txt"))
    >>> tmp = writing.__enter__()           # a write under way ...
    >>> remove_temporaries()                 # ... when a stopping signal comes
    []
    >>> os.listdir(d)
    []
    """
    for proc in list(_processes):
        _stop_process(proc)
    _processes.clear()
    blockers = []
    for path, directory in list(_temporaries.items()):
        if directory:
            blockers += remove_and_block(path)
        else:
            _remove(path, directory)
    _temporaries.clear()
    if keep_blockers:
        return blockers
    for path in blockers:
        _remove(path, False)
    return []


def remove_and_block(path, tries=100) -> list:
    """Remove the folder ``path`` and put an empty file at its name; ``[path]`` when the file is there, else ``[]``.

    The threads of a chunked run (dask's) may still be writing into a
    temporary folder when a stopping signal removes it, and a zarr store
    makes a chunk's missing parent folders, so it would build the folder
    again behind the removal. While a file holds the folder's name, every
    such write fails. The caller removes the file just before the process
    exits (:func:`remove_temporaries`). A folder built again between the
    removal and the file is removed again, up to ``tries`` times.

    Examples
    --------
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> os.makedirs(os.path.join(d, "t.tmp", "c", "0"))
    >>> remove_and_block(os.path.join(d, "t.tmp")) == [os.path.join(d, "t.tmp")]
    True
    >>> os.path.isfile(os.path.join(d, "t.tmp"))
    True
    """
    for _ in range(tries):
        shutil.rmtree(path, ignore_errors=True)
        try:
            os.close(os.open(path, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600))
        except FileExistsError:
            continue   # a writing thread made the folder again
        except OSError:
            return []
        return [path]
    return []


@contextlib.contextmanager
def scratch_folder(beside, suffix=".scratch.tmp"):
    """A temporary folder next to ``beside`` (hidden, named after it), removed afterwards, also when stopped.

    ``beside=None`` puts it in the system's temporary folder.

    For intermediate data that must not outlive the run (a spilled transpose),
    recorded like :func:`atomic_output`'s temporaries so that a stopping
    signal removes it too.

    Examples
    --------
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> with scratch_folder(os.path.join(d, "out.zarr")) as tmp:
    ...     os.path.isdir(tmp) and tmp.name.startswith(".out.zarr.")
    True
    >>> os.listdir(d)
    []
    """
    # beside=None: in the system's temporary folder (mkdtemp's own choice: an unguessable name)
    prefix, where = (".noiselab.", None) if beside is None else (f".{Path(beside).name}.", Path(beside).parent)
    with hold_signals():
        tmp = Path(tempfile.mkdtemp(prefix=prefix, suffix=suffix, dir=where))
        _record(tmp, True)
    try:
        yield tmp
    finally:
        _remove(tmp, True)
        _forget(tmp)


def _first_existing(path: Path) -> Path:
    p = path
    while not os.path.lexists(p) and p != p.parent:
        p = p.parent
    return p


def prepare_output(path, *, directory=False, make_parents=True, probe=True, create=True) -> Path:
    """Check that ``path`` can be written, creating missing parent folders; raise ``OutputError`` if not.

    Call it before long work so a run fails at once, not after minutes of
    rendering. ``directory=True`` for an output that is a folder (PNG frames).
    ``probe`` creates and removes a temporary file beside the target, which
    catches a read-only file system or a folder without write permission.
    ``create=False`` checks only: missing folders are not made, the probe runs
    in the nearest folder that exists.

    Parameters
    ----------
    path : str or Path
        The output file (or folder, with ``directory``).
    directory : bool, default False
        The output is a folder.
    make_parents : bool, default True
        Create missing parent folders (with ``create``).
    probe : bool, default True
        Create and remove a temporary file beside the target.
    create : bool, default True
        Make missing folders; False only checks.

    Returns
    -------
    Path
        ``path`` as a :class:`pathlib.Path`.

    Raises
    ------
    noiselab.io.OutputError
        When the output cannot be written there (an ``OSError``: a read-only
        file system, no permission, a folder where a file is wanted, ...).

    Examples
    --------
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> prepare_output(os.path.join(d, "new", "a.png")).name
    'a.png'
    >>> open(os.path.join(d, "file"), "w").close()
    >>> prepare_output(os.path.join(d, "file", "a.png"))
    Traceback (most recent call last):
    ...
    noiselab.io.errors.OutputError: cannot write '.../file/a.png': ... is a file, not a folder
    """
    path = Path(path)
    parent = path.parent if str(path.parent) else Path(".")
    if not parent.is_dir():
        existing = _first_existing(parent)
        if os.path.lexists(existing) and not existing.is_dir():
            raise OutputError(path, f"{str(existing)!r} is a file, not a folder", errno.ENOTDIR)
        if not make_parents:
            raise OutputError(path, f"the folder {str(parent)!r} does not exist", errno.ENOENT)
        if not create:
            parent = existing
        else:
            try:
                parent.mkdir(parents=True, exist_ok=True)
            except OSError as exc:
                raise output_error(path, exc) from None
    if directory and path.exists() and not path.is_dir():
        raise OutputError(path, "it is an existing file, not a folder for frames", errno.ENOTDIR)
    if not directory and path.is_dir():
        raise OutputError(path, "it is an existing folder", errno.EISDIR)
    if probe:
        try:
            with hold_signals():   # a stopping signal waits for the probe to be gone
                fd, name = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".probe", dir=parent)
                os.close(fd)
                os.unlink(name)
        except OSError as exc:
            raise output_error(path, exc) from None
    return path


_RENAME_EXCHANGE = 2
_AT_FDCWD = -100


def _renameat2():
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6", use_errno=True)
        fn = libc.renameat2
    except (OSError, AttributeError):
        return None
    fn.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    fn.restype = ctypes.c_int
    return fn


def exchange_paths(a, b) -> bool:
    """Swap two existing paths in one atomic step (Linux ``renameat2(RENAME_EXCHANGE)``).

    Returns False where the system or file system cannot (then nothing was
    changed). Used to replace an output folder: at every moment either the old
    or the new folder is at the target's name.

    Parameters
    ----------
    a, b : str or Path
        Two existing paths on one file system.

    Returns
    -------
    bool
        True when they were swapped, False when the system cannot (nothing changed).

    Examples
    --------
    >>> import os, tempfile
    >>> d = tempfile.mkdtemp(); a, b = os.path.join(d, "a"), os.path.join(d, "b")
    >>> os.mkdir(a); os.mkdir(b); open(os.path.join(a, "from_a"), "w").close()
    >>> exchange_paths(a, b) and os.listdir(b) == ["from_a"] and os.listdir(a) == []
    True
    """
    fn = _renameat2()
    if fn is None:
        return False
    rc = fn(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE)
    if rc == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.ENOSYS, errno.EINVAL, errno.ENOTSUP, errno.EOPNOTSUPP):
        return False
    raise OSError(code, os.strerror(code), str(a), None, str(b))


def _replace_folder(tmp: Path, path: Path):
    """Put the folder ``tmp`` at ``path``; return the recorded temporary name of the old folder (or None).

    Called inside :func:`hold_signals`: a stopping signal comes either before
    (the old output stays) or after (the new one is in place, and the old one
    at a recorded name that the caller, or the signal handler, removes).
    """
    if not os.path.lexists(path):
        os.replace(tmp, path)
        _forget(tmp)
        return None
    if exchange_paths(tmp, path):     # the new folder is at `path`, the old one at `tmp`, still recorded
        return tmp
    # no atomic exchange here (not Linux, or a file system without it): move the old folder
    # aside and the new one in; for that instant neither is at `path`
    old = Path(tempfile.mkdtemp(prefix=f".{path.name}.old.", dir=path.parent))
    _record(old, True)
    os.replace(path, old / path.name)
    try:
        os.replace(tmp, path)
    except BaseException:
        os.replace(old / path.name, path)
        _remove(old, True)
        _forget(old)
        raise
    _forget(tmp)
    return old


def _ours(exc, tmp: Path) -> bool:
    """Whether an OSError raised while writing concerns the output (no file named, or the temporary one)."""
    name = getattr(exc, "filename", None)
    return name is None or str(name).startswith(str(tmp))


@contextlib.contextmanager
def atomic_output(path, *, directory=False):
    """Yield a temporary path beside ``path``; rename it onto ``path`` on success.

    The temporary name keeps the target's suffix (writers such as imageio pick
    the format from it). On any exception (and on ``KeyboardInterrupt``) the
    temporary file or folder is removed and the target is left exactly as it
    was; an ``OSError`` from writing becomes an ``OutputError`` naming ``path``
    and the cause. An existing folder is replaced atomically
    (:func:`exchange_paths`): the old or the new one is always there.

    Examples
    --------
    >>> import numpy as np, tempfile, os
    >>> d = tempfile.mkdtemp()
    >>> with atomic_output(os.path.join(d, "a.npy")) as tmp:
    ...     np.save(tmp, np.zeros(3))
    >>> sorted(os.listdir(d))
    ['a.npy']
    """
    path = Path(path)
    prepare_output(path, directory=directory, make_parents=False, probe=False)
    parent = path.parent if str(path.parent) else Path(".")
    tmp = None
    try:
        with hold_signals():   # an interruption must not fall between creating the file and recording it
            try:
                if directory:
                    tmp = Path(tempfile.mkdtemp(prefix=f".{path.name}.", suffix=".tmp", dir=parent))
                else:
                    fd, name = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".tmp" + "".join(path.suffixes),
                                                dir=parent)
                    os.close(fd)
                    tmp = Path(name)
                _record(tmp, directory)
            except OSError as exc:
                raise output_error(path, exc) from None
        yield tmp
        # mkstemp/mkdtemp create owner-only files; give the result the
        # permissions an ordinary open() would (0666/0777 less the umask).
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, (0o777 if directory else 0o666) & ~umask)
        with hold_signals():   # the rename and its record change together: a signal sees the old or the new state
            if directory:
                old = _replace_folder(tmp, path)
            else:
                os.replace(tmp, path)
                _forget(tmp)
                old = None
    except BaseException as exc:
        if tmp is None:
            raise
        _remove(tmp, directory)
        _forget(tmp)
        if isinstance(exc, OutputError) and exc.path.startswith(str(tmp)):   # a writer named our temporary
            raise OutputError(path, exc.reason, exc.errno) from exc
        if isinstance(exc, OSError) and not isinstance(exc, OutputError) and _ours(exc, tmp):
            raise output_error(path, exc) from exc
        raise
    if old is not None:   # the replaced folder, moved aside (still recorded until it is gone)
        _remove(old, True)
        _forget(old)
