"""What ``noiselab warmup`` costs, and what a first call costs after it, in fresh processes.

Run from the repository root::

    python benchmarks/bench_warmup.py [RUNS]

For each run: the four first calls of ``bench_coldstart.py`` (1e5 3-D
points, a 512² grid, a 6-octave fBm on it, float32 integer-hash points),
each in a fresh process on an empty ``NUMBA_CACHE_DIR`` (cold); then
``python -m noiselab warmup`` on another empty cache, and the same four
first calls on that cache. CPU seconds (user + system of the child) and, in
brackets, wall seconds; medians over the runs. Prints a Markdown table.
"""
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CALLS = {
    "`LatticeNoise(3)(pts)`, 1e5 random 3-D points":
        "import numpy as np, noiselab as nl\npts = np.random.default_rng(0).random((100_000, 3)) * 32\n"
        "nl.LatticeNoise(3)(pts)",
    "`LatticeNoise(2).grid((512, 512), [(0, 32), (0, 32)])`":
        "import noiselab as nl\nnl.LatticeNoise(2).grid((512, 512), [(0, 32), (0, 32)])",
    "`fractal_sum(LatticeNoise(2), Grid((512, 512), ((0, 32), (0, 32))), octaves=6)`":
        "import noiselab as nl\nfrom noiselab.lattice import Grid\n"
        "nl.fractal_sum(nl.LatticeNoise(2), Grid((512, 512), ((0, 32), (0, 32))), octaves=6)",
    "`LatticeNoise(3, hash=\"integer\")(pts.astype(np.float32))`, 1e5 points":
        "import numpy as np, noiselab as nl\npts = np.random.default_rng(0).random((100_000, 3)) * 32\n"
        "nl.LatticeNoise(3, hash='integer')(pts.astype(np.float32))",
}


def child(args, cache):
    """CPU seconds and wall seconds of ``python args`` with ``NUMBA_CACHE_DIR=cache``."""
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, PYTHONPATH=str(ROOT))
    env.pop("NUMBA_NUM_THREADS", None)
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, *args], env=env, check=True, cwd=tempfile.gettempdir(), stdout=subprocess.DEVNULL)
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime, time.perf_counter() - t0


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    runs = int(argv[0]) if argv else 2
    rows = {k: {"cold": [], "after": []} for k in CALLS}
    warm = []
    for _ in range(runs):
        for k, code in CALLS.items():
            d = tempfile.mkdtemp()
            rows[k]["cold"].append(child(["-c", code], d))
            shutil.rmtree(d)
        d = tempfile.mkdtemp()
        warm.append(child(["-m", "noiselab", "warmup"], d))
        for k, code in CALLS.items():
            rows[k]["after"].append(child(["-c", code], d))
        shutil.rmtree(d)

    def cell(xs):
        return f"{statistics.median(x[0] for x in xs):.1f} ({statistics.median(x[1] for x in xs):.1f})"

    print(f"`noiselab warmup` on an empty cache: {cell(warm)} s CPU (wall), {runs} run(s): "
          + ", ".join(f"{c:.1f} ({w:.1f})" for c, w in warm))
    print("\n| first call | cold: s CPU (wall) | after `noiselab warmup`: s CPU (wall) |\n| --- | ---: | ---: |")
    for k in CALLS:
        print(f"| {k} | {cell(rows[k]['cold'])} | {cell(rows[k]['after'])} |")


if __name__ == "__main__":
    main()
