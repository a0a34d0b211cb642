"""Regenerate ``benchmarks/RESULTS.md`` (the laboratory): same as ``python3 -m noiselab bench``.

It imports the noiselab of this checkout (not whichever is installed), so
``--publish`` writes this checkout's ``benchmarks/RESULTS.md``; the output of
an ordinary run goes under the current folder::

    python3 benchmarks/lab_run.py            # full run (2.5-5 min on 2 cores), writes out/bench/RESULTS.md
    python3 benchmarks/lab_run.py --publish  # ... and updates the published benchmarks/RESULTS.md
    python3 benchmarks/lab_run.py --quick --output /tmp/lab
"""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from noiselab.cli import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main(["bench", *sys.argv[1:]]))
