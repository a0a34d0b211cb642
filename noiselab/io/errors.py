"""Errors for files that cannot be read or written, each one line naming the file and the cause.

The command line prints these as ``noiselab CMD: error: MESSAGE`` with exit
status 2 (``noiselab.cli.main``); library callers can catch them as the
``ValueError`` (unreadable input) or ``OSError`` (unwritable output) they are.
"""
from __future__ import annotations

import errno as _errno
import os
from pathlib import Path

__all__ = ["InputError", "OutputError", "cause", "describe", "input_error", "output_error"]

# errno values whose strerror text we look for in a tool's own message (ffmpeg, Pillow)
_KNOWN = (_errno.ENOSPC, _errno.EDQUOT, _errno.EFBIG, _errno.EROFS, _errno.EACCES, _errno.EPERM, _errno.EIO,
          _errno.EISDIR, _errno.ENOTDIR, _errno.ENOENT)


class InputError(ValueError):
    """A file that exists (or was named) but cannot be read as what it should be.

    Examples
    --------
    >>> str(InputError("a.png", "truncated PNG data"))
    "cannot read 'a.png': truncated PNG data"
    """

    def __init__(self, path, reason):
        self.path, self.reason = str(path), str(reason)
        super().__init__(f"cannot read {self.path!r}: {self.reason}")


class OutputError(OSError):
    """A file or folder that cannot be written (full disk, read-only file system, no permission, bad path).

    Examples
    --------
    >>> import errno
    >>> e = OutputError("out/a.png", "No space left on device", errno.ENOSPC)
    >>> str(e), e.errno == errno.ENOSPC
    ("cannot write 'out/a.png': No space left on device", True)
    """

    def __init__(self, path, reason, code=None):
        super().__init__(code, reason)
        self.path, self.reason = str(path), str(reason)

    def __str__(self):
        return f"cannot write {self.path!r}: {self.reason}"


def _one_line(text) -> str:
    lines = [ln.strip() for ln in str(text).splitlines() if ln.strip()]
    return lines[0] if lines else ""


def cause(exc) -> str:
    """The cause of ``exc`` in a few words: the OS's text for its errno, else its message's first line.

    Examples
    --------
    >>> import errno
    >>> cause(OSError(errno.EROFS, "Read-only file system", "/x"))
    'Read-only file system'
    >>> cause(OSError("writing failed: No space left on device"))
    'No space left on device'
    """
    if isinstance(exc, (InputError, OutputError)):
        return exc.reason
    code = getattr(exc, "errno", None)
    if isinstance(exc, OSError) and code and code != _errno.EPIPE:
        return exc.strerror or os.strerror(code)
    text = str(exc)
    for known in _KNOWN:   # a tool's message that names an OS error (ffmpeg, Pillow, numpy)
        if os.strerror(known) in text:
            return os.strerror(known)
    line = _one_line(text)
    if isinstance(exc, MemoryError):
        return "out of memory" + (f" ({line})" if line else "")
    return line or type(exc).__name__


def input_error(path, exc) -> InputError:
    """``InputError`` for ``path`` from the exception a reader raised."""
    if isinstance(exc, InputError):
        return exc
    if isinstance(exc, PermissionError):
        return InputError(path, "permission denied")
    try:
        empty = Path(path).is_file() and Path(path).stat().st_size == 0
    except OSError:
        empty = False
    if empty:
        return InputError(path, "the file is empty (0 bytes)")
    if isinstance(exc, EOFError):
        return InputError(path, "the file ends too early (truncated)")
    return InputError(path, cause(exc))


def output_error(path, exc) -> OutputError:
    """``OutputError`` for ``path`` from the exception a writer raised."""
    if isinstance(exc, OutputError):
        return exc
    reason = cause(exc)
    code = getattr(exc, "errno", None)
    if not code:
        code = next((k for k in _KNOWN if os.strerror(k) == reason), None)
    return OutputError(path, reason, code)


def describe(exc) -> str:
    """One line for the command line: the message, with the file name when the exception carries one.

    Examples
    --------
    >>> import errno
    >>> describe(PermissionError(errno.EACCES, "Permission denied", "out/a.png"))
    "'out/a.png': Permission denied"
    >>> describe(ValueError("--size must be >= 1\\nsecond line"))
    '--size must be >= 1'
    """
    if isinstance(exc, (InputError, OutputError)):
        return str(exc)
    if isinstance(exc, OSError) and getattr(exc, "filename", None):
        target = f"{exc.filename!r}" + (f" -> {exc.filename2!r}" if getattr(exc, "filename2", None) else "")
        return f"{target}: {cause(exc)}"
    if isinstance(exc, MemoryError):
        return cause(exc)
    return _one_line(str(exc)) or type(exc).__name__
