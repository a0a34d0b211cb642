"""Did the one-way house cost speed? The same public calls, before and after, side by side.

    python3 benchmarks/bench_layout.py [--before a776ea5] [--repeats 7]

Writes ``benchmarks/bench_layout.md`` beside this script. Two versions of a
package cannot share one interpreter, so each version runs in a worker process
of its own (the ``--before`` commit unpacked with ``git archive`` into a
temporary folder, and this checkout); the harness (:func:`noiselab.lab.measure.interleaved`)
sends both workers the same case in every round, in rotating order, and
records the CPU time each worker measured around the call (process time, one
thread: what the shared machine's other jobs do not inflate). The reported
ratio is the median over rounds of after / before, paired per round.
Only public calls that exist in both versions are timed.
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from noiselab.lab.measure import Laps, header_lines, interleaved, markdown_table, run_info  # noqa: E402

# The worker: reads a case name per line, runs it once, answers the CPU seconds it took.
WORKER = r'''
import json, os, sys, time
import numpy as np
import noiselab
from noiselab import LatticeNoise, fractal_sum, spectral_noise
from noiselab.lattice import Grid

rng = np.random.default_rng(0)
pts3 = rng.uniform(-50, 50, (1_000_000, 3))
pts3_32 = pts3.astype(np.float32)
value3 = LatticeNoise(3, kernel="quintic", rng=1)
gradient3 = LatticeNoise(3, kernel="quintic", basis="gradient", rng=1)
integer3 = LatticeNoise(3, kernel="quintic", hash="integer", rng=1)
plane = LatticeNoise(2, rng=1)
vector3 = LatticeNoise(3, 3, kernel="quintic", rng=2)
grid512 = Grid((512, 512), ((0, 32), (0, 32)))

CASES = {
    "spectral_noise 1024^2 float32": lambda: spectral_noise((1024, 1024), rng=1, dtype=np.float32),
    "snow 32x256x256": lambda: noiselab.snow((32, 256, 256), rng=1),
    "3-D value points 1e6 (table hash)": lambda: value3(pts3),
    "3-D gradient points 1e6 (table hash)": lambda: gradient3(pts3),
    "3-D value points 1e6 (integer hash, float32)": lambda: integer3(pts3_32),
    "2-D grid 512^2": lambda: plane.grid((512, 512), ((0, 32), (0, 32))),
    "2-D grid 512^2 on dask (4 chunks)": lambda: plane.grid((512, 512), ((0, 32), (0, 32)), chunks=256).compute(
        scheduler="synchronous"),
    "fractal_sum 512^2, 6 octaves": lambda: fractal_sum(plane, grid512, octaves=6),
    "curl_noise 1e5 3-D points": lambda: noiselab.curl_noise(vector3, pts3[:100_000]),
}
print(json.dumps(sorted(CASES)), flush=True)
for line in sys.stdin:
    name = json.loads(line)
    t0 = time.process_time()
    CASES[name]()
    print(json.dumps(time.process_time() - t0), flush=True)
'''


class Worker:
    """One interpreter running one version of noiselab (its tree first on ``sys.path``)."""

    def __init__(self, tree: Path, cache: Path):
        env = dict(os.environ, PYTHONPATH=str(tree), NUMBA_CACHE_DIR=str(cache), NUMBA_NUM_THREADS="1",
                   OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
        self.proc = subprocess.Popen([sys.executable, "-c", WORKER], cwd=tree, env=env, text=True,
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.cases = json.loads(self.proc.stdout.readline())

    def run(self, case: str) -> float:
        self.proc.stdin.write(json.dumps(case) + "\n")
        self.proc.stdin.flush()
        line = self.proc.stdout.readline()
        if not line:
            raise RuntimeError(f"the worker died running {case!r}")
        return json.loads(line)

    def close(self):
        self.proc.stdin.close()
        self.proc.wait(timeout=60)


def unpack(rev: str, into: Path) -> Path:
    """The package and its data at commit ``rev``, unpacked with ``git archive`` (no worktree registered)."""
    archive = into / "before.tar"
    with open(archive, "wb") as fh:
        subprocess.run(["git", "archive", rev, "noiselab"], cwd=ROOT, stdout=fh, check=True)
    with tarfile.open(archive) as tar:
        tar.extractall(into / "tree", filter="data")
    return into / "tree"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", default="a776ea5", help="the commit to compare with (default: main before the one-way layers)")
    ap.add_argument("--repeats", type=int, default=7, help="timed rounds (>= 5)")
    args = ap.parse_args(argv)
    command = "python3 benchmarks/bench_layout.py" + "".join(
        f" --{k} {v}" for k, v in (("before", args.before), ("repeats", args.repeats)))
    info = run_info(command, ("scipy",))
    rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, text=True,
                         capture_output=True, check=True).stdout.strip()
    with tempfile.TemporaryDirectory(prefix="noiselab-layout-") as tmp:
        tmp = Path(tmp)
        workers = {"before": Worker(unpack(args.before, tmp), tmp / "cache-before"),
                   "after": Worker(ROOT, tmp / "cache-after")}
        cases = [c for c in workers["before"].cases if c in workers["after"].cases]
        rows = []
        try:
            for case in cases:
                candidates = {side: (lambda w=w, s=side: Laps({f"{s} cpu": w.run(case)}))
                              for side, w in workers.items()}
                t = interleaved(candidates, repeats=args.repeats, warmup=2, min_repeats=5)
                rows.append([case, f"{t.median('before cpu') * 1e3:.1f}", f"{t.median('after cpu') * 1e3:.1f}",
                             f"{t.ratio('after cpu', 'before cpu'):.3f}"])
                print(" | ".join(rows[-1]), flush=True)
        finally:
            for w in workers.values():
                w.close()
    lines = ["# The one-way house: speed before and after", ""] + header_lines(info) + [
        "",
        f"Before: commit `{args.before}` (main before the layering); after: commit `{rev}`. Each version runs "
        "in its own worker process, one thread; both get the same case in each round (rotating order, 2 warm-up "
        "rounds that compile). Times are the worker's CPU time around the call (median over rounds); the ratio is "
        "the median over rounds of after / before measured in the same round (1.00: no change).",
        "",
    ] + markdown_table(["case", "before (ms CPU)", "after (ms CPU)", "after / before"], rows, "lrrr")
    (Path(__file__).with_suffix(".md")).write_text("\n".join(lines) + "\n")
    print(f"wrote {Path(__file__).with_suffix('.md')}")


if __name__ == "__main__":
    main()
