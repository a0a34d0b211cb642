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
traceback. SIGINT, SIGTERM and SIGHUP stop a run the same way: temporary
files are removed, and the status is 128 + the signal number (130, 143, 129).
"""
from __future__ import annotations

import argparse
import contextlib
import importlib
import os
import pkgutil
import signal
import sys


class Terminated(KeyboardInterrupt):
    """Raised in the main thread by SIGINT, SIGTERM or SIGHUP: a KeyboardInterrupt, so every clean-up runs."""

    def __init__(self, signum):
        super().__init__(signum)
        self.signum = signum


def _on_signal(signum, frame):
    from ..io.atomic import defer_signal

    if defer_signal(signum):   # inside a step that must finish first (creating a temporary file): later
        return
    for s in (signal.SIGTERM, signal.SIGHUP, signal.SIGINT):   # a second signal must not cut the clean-up short
        signal.signal(s, signal.SIG_IGN)
    raise Terminated(signum)


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
    from ..io.errors import describe

    parser = build_parser()
    args = parser.parse_args(argv)
    previous = {}
    try:
        for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
            previous[s] = signal.signal(s, _on_signal)
    except ValueError:   # not the main thread: leave the signals alone
        previous = {}
    try:
        return int(args._run(args) or 0)
    except BrokenPipeError:   # the reader of our output went away (``| head``): stop quietly, as other tools do
        with contextlib.suppress(OSError):
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 128 + signal.SIGPIPE
    except (ValueError, TypeError, OSError, MemoryError, EOFError) as exc:
        print(f"noiselab {args.command}: error: {describe(exc)}", file=sys.stderr)
        return 2
    except Terminated as exc:
        what = "interrupted (SIGINT)" if exc.signum == signal.SIGINT else \
            f"terminated by {signal.Signals(exc.signum).name}"
        print(f"noiselab {args.command}: {what}; temporary files removed", file=sys.stderr)
        return 128 + exc.signum
    except KeyboardInterrupt:
        print(f"noiselab {args.command}: interrupted; temporary files removed", file=sys.stderr)
        return 130
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
