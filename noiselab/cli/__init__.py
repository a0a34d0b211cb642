"""The ``noiselab`` command.

Each subcommand lives in its own module in this package (``snow.py``,
``noise.py``, ...) and defines::

    NAME = "snow"                       # the subcommand's name
    HELP = "one line for noiselab -h"
    def add_arguments(parser): ...      # fill an argparse parser
    def run(args) -> int: ...           # do the work, return the exit status

Modules are discovered here, so adding a command is adding one file.
Errors that come from bad input (``ValueError``, ``TypeError``,
``FileNotFoundError``, ``MemoryError``) are printed as one line on stderr with
exit status 2, never as a traceback.
"""
from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys


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
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args._run(args) or 0)
    except (ValueError, TypeError, FileNotFoundError, MemoryError) as exc:
        print(f"noiselab {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
