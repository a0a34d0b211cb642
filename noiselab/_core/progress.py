"""Progress bars (tqdm), silent unless asked for or attached to a terminal."""
from __future__ import annotations

import sys


def progress(iterable=None, *, total=None, desc=None, enabled=None, unit="it"):
    """Wrap ``iterable`` in a tqdm bar on stderr.

    ``enabled=None`` shows the bar only when stderr is a terminal, so tests and
    CI logs stay clean; ``True``/``False`` force it.
    """
    from tqdm.auto import tqdm  # (on first use: importing it took 0.05 s of every import of the package's core)

    if enabled is None:
        enabled = sys.stderr.isatty()
    return tqdm(iterable, total=total, desc=desc, disable=not enabled, unit=unit, leave=False, file=sys.stderr)
