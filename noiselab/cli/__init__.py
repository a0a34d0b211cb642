"""The ``noiselab`` command.

Each subcommand lives in its own module in this package (``snow.py``,
``noise.py``, ...) and defines::

    NAME = "snow"                       # the subcommand's name
    HELP = "one line for noiselab -h"
    def add_arguments(parser): ...      # fill an argparse parser
    def run(args) -> int: ...           # do the work, return the exit status

Modules are discovered here, so adding a command is adding one file.
Errors that come from bad input or the machine's state (``ValueError``,
``TypeError``, any ``OSError``: a missing or unreadable input, an output that
cannot be written, a full disk; ``MemoryError``) are printed as one line on
stderr naming the file and the cause, with exit status 2, never as a
traceback. SIGINT, SIGTERM and SIGHUP stop a run at any moment (while
modules are imported, while numba compiles, while a writer is built or
closed): the handler stops the encoder, removes the temporary files, prints
one line and ends the process at once with status 128 + the signal number
(130, 143, 129). It does not raise an exception into the code that was running
(an exception thrown into numba's compiler corrupted it and crashed the
process; one thrown into a half-built imageio writer made its destructor
print a traceback); the finished output, if the final rename came first, stays.
"""
from __future__ import annotations

# Only modules the interpreter has loaded already come before the handlers are installed (below):
# a SIGINT that falls here gives Python's own KeyboardInterrupt traceback.
import contextlib
import os
import signal
import sys

_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
_command = "noiselab"   # what the one-line message names: "noiselab snow" once the command is known


class Terminated(KeyboardInterrupt):
    """A stop by SIGINT, SIGTERM or SIGHUP, as an exception (``signum`` says which).

    The command line's handler no longer raises it (it exits at once, see the
    module docstring); it remains for callers that catch it.
    """

    def __init__(self, signum):
        super().__init__(signum)
        self.signum = signum


def _stop_message(signum) -> str:
    what = "interrupted (SIGINT)" if signum == signal.SIGINT else f"terminated by {signal.Signals(signum).name}"
    return f"{_command}: {what}; temporary files removed"


def _children():
    """The ids of this process's child processes (Linux; an empty list elsewhere)."""
    pids = []
    with contextlib.suppress(OSError):
        for task in os.listdir("/proc/self/task"):
            with open(f"/proc/self/task/{task}/children") as f:
                pids += [int(p) for p in f.read().split()]
    return pids


def _on_signal(signum, frame):
    # Only what was imported already is used here: an import inside a handler could wait on a
    # lock that the interrupted main thread holds. Before noiselab.io.atomic exists, nothing
    # can have been recorded (no temporary file, no encoder).
    atomic = sys.modules.get("noiselab.io.atomic")
    if atomic is not None and getattr(atomic, "defer_signal", None) and atomic.defer_signal(signum):
        return   # inside a step that must finish first (creating and recording a temporary): later
    for s in _SIGNALS:   # a second signal must not cut the clean-up short
        signal.signal(s, signal.SIG_IGN)
    blockers = []
    try:
        if atomic is not None and getattr(atomic, "remove_temporaries", None):
            # files hold the removed folders' names until the very end: threads of a chunked run may
            # still be writing chunks, and a zarr store would make the folders again
            blockers = atomic.remove_temporaries(keep_blockers=True)
        for pid in _children():   # other helpers (a peer benchmark) end with us, as with a terminal's Ctrl-C
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGTERM)
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):   # a write the signal interrupted may refuse a re-entrant flush
                stream.flush()
        lead = "\n" if _isatty(2) else ""   # a terminal's "^C" or progress bar keeps its own line
        with contextlib.suppress(OSError):
            os.write(2, f"{lead}{_stop_message(signum)}\n".encode())
    finally:
        for path in blockers:
            with contextlib.suppress(OSError):
                os.unlink(path)
        # no exception unwinds through the interrupted code, no destructor or exit handler
        # runs: the process ends here
        os._exit(128 + signum)


def _isatty(fd) -> bool:
    try:
        return os.isatty(fd)
    except OSError:
        return False


def _install_handlers():
    """Install the stopping handler for SIGINT, SIGTERM and SIGHUP; return the previous ones ({} off the main thread)."""
    try:
        return {s: signal.signal(s, _on_signal) for s in _SIGNALS}
    except ValueError:   # not the main thread (signal.signal refuses at once): leave the signals alone
        return {}


def _is_the_program() -> bool:
    """Whether this process is the ``noiselab`` command (its script, or ``python -m noiselab``), not a caller of main()."""
    argv0 = os.path.normpath(sys.argv[0]) if sys.argv and sys.argv[0] else ""
    return os.path.basename(argv0) == "noiselab" or argv0.endswith(os.path.join("noiselab", "__main__.py"))


def _name_in(argv) -> str:
    """``noiselab CMD`` for the message, CMD the first word of ``argv`` (default ``sys.argv[1:]``) not an option."""
    words = [a for a in (sys.argv[1:] if argv is None else argv) if not str(a).startswith("-")]
    return f"noiselab {words[0]}" if words else "noiselab"


if _is_the_program():   # handled from here on, not only once main() runs: the imports below take time
    _command = _name_in(None)
    _install_handlers()

import argparse  # noqa: E402
import importlib  # noqa: E402
import pkgutil  # noqa: E402


def _command_modules():
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        if hasattr(module, "NAME") and hasattr(module, "run"):
            yield module


def build_parser() -> argparse.ArgumentParser:
    from .. import __version__

    parser = argparse.ArgumentParser(prog="noiselab", description="Procedural noise laboratory: spectral and lattice noise, measured.")
    parser.add_argument("--version", action="version", version=f"noiselab {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    sub.required = True
    for module in _command_modules():
        p = sub.add_parser(module.NAME, help=getattr(module, "HELP", None), description=getattr(module, "HELP", None))
        module.add_arguments(p)
        p.set_defaults(_run=module.run)
    return parser


def main(argv=None) -> int:
    """Run the ``noiselab`` command with ``argv`` (default ``sys.argv[1:]``) and return its exit status.

    As the program (``argv`` None: the ``noiselab`` script, ``python -m
    noiselab``) the stopping handlers stay installed until the process ends, so
    a signal after the work (while Python shuts down) ends the same way; a
    caller that passes ``argv`` (a test) gets its own handlers back.
    """
    global _command
    before, _command = _command, _name_in(argv)
    previous = _install_handlers()   # first: a signal while the subcommands are imported is handled too
    try:
        from ..io.errors import describe

        parser = build_parser()
        args = parser.parse_args(argv)
        _command = f"noiselab {args.command}"
        return _run(args, describe)
    finally:
        if argv is not None:   # a caller in this process: as it was
            _command = before
            for s, handler in previous.items():
                signal.signal(s, handler)


def _from_numba_cache(exc) -> bool:
    """Whether ``exc`` was raised while numba read its on-disk compile cache (a damaged ``*.nbi``/``*.nbc``)."""
    tb = exc.__traceback__
    while tb is not None:
        if tb.tb_frame.f_code.co_filename.replace(os.sep, "/").endswith("numba/core/caching.py"):
            return True
        tb = tb.tb_next
    return False


def _run(args, describe) -> int:
    try:
        return int(args._run(args) or 0)
    except BrokenPipeError:   # the reader of our output went away (``| head``): stop quietly, as other tools do
        with contextlib.suppress(OSError):
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 128 + signal.SIGPIPE
    except Exception as exc:
        if _from_numba_cache(exc):   # a damaged compile cache: say how to clear it, not what pickle saw
            from .._core.jitcache import CACHE_HINT

            print(f"noiselab {args.command}: error: {CACHE_HINT} ({type(exc).__name__}: {exc})", file=sys.stderr)
            return 2
        if not isinstance(exc, (ValueError, TypeError, OSError, MemoryError, EOFError)):
            raise
        print(f"noiselab {args.command}: error: {describe(exc)}", file=sys.stderr)
        return 2
    except Terminated as exc:
        print(_stop_message(exc.signum), file=sys.stderr)
        return 128 + exc.signum
    except KeyboardInterrupt:
        print(f"noiselab {args.command}: interrupted; temporary files removed", file=sys.stderr)
        return 130
