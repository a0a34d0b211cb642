"""The grid path of another checkout against this one, in one process: fBm grids, speed and bits.

Run from the repository root::

    python benchmarks/bench_grid_rows.py --base /path/to/other/checkout [--repeats 7] [--kernel quintic] \
        [--octaves 6] [--dims 3 2]

The other checkout's ``noiselab/lattice/grid_path.py`` and ``_jit.py`` are
loaded beside this tree's (as ``noiselab.lattice.grid_path_base`` and
``_jit_base``: numba caches them by their own file) and
``LatticeNoise.evaluate_grid`` is pointed at one or the other in turn.
Each row: an ``--octaves`` ``fractal_sum`` (6 by default) on a 128³ grid (4 lattice cells a side)
or a 512² grid (16 cells a side), both hashes and bases; the thread CPU time
of each path (median of ``--repeats`` interleaved rounds), the median of the
per-round ratios base / this, and whether both give the same bits (dtype,
values and sign bits). Prints a Markdown table.
"""
from __future__ import annotations

import argparse
import importlib.util
import os
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from noiselab import LatticeNoise, fractal_sum  # noqa: E402
from noiselab.lattice import Grid, core  # noqa: E402

CASES = [(3, "value", "table"), (3, "gradient", "table"), (3, "value", "integer"), (3, "gradient", "integer"),
         (2, "value", "table"), (2, "gradient", "table"), (2, "value", "integer"), (2, "gradient", "integer")]


def _load(name, path):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", required=True, help="the other checkout (its noiselab/lattice is loaded)")
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--kernel", default="quintic")
    parser.add_argument("--octaves", type=int, default=6)
    parser.add_argument("--dims", type=int, nargs="+", default=[3, 2], choices=[2, 3])
    args = parser.parse_args()
    lattice = Path(args.base) / "noiselab" / "lattice"
    base_jit = _load("noiselab.lattice._jit_base", lattice / "_jit.py")
    base_path = _load("noiselab.lattice.grid_path_base", lattice / "grid_path.py")
    base_path.jit = base_jit
    paths = {"base": base_path.render_grid, "this": core.render_grid}

    def run(which, noise, grid, dtype):
        core.render_grid = paths[which]
        return fractal_sum(noise, grid, args.octaves, dtype=dtype)

    print(f"load average (1 min) at start: {os.getloadavg()[0]:.1f}")
    print("| grid | noise | hash | dtype | base (ms) | this (ms) | base / this | same bits |")
    print("| --- | --- | --- | --- | ---: | ---: | ---: | --- |")
    for dim, basis, hash_ in [c for c in CASES if c[0] in args.dims]:
        n, cells = (128, 4) if dim == 3 else (512, 16)
        noise = LatticeNoise(dim, rng=1, kernel=args.kernel, basis=basis, hash=hash_)
        grid = Grid((n,) * dim, [(0.0, float(cells))] * dim)
        for dtype in (np.float32, np.float64):
            a, b = run("base", noise, grid, dtype), run("this", noise, grid, dtype)
            same = a.dtype == b.dtype and np.array_equal(a, b) and np.array_equal(np.signbit(a), np.signbit(b))
            tb, tt = [], []
            for _ in range(args.repeats):
                t = time.thread_time()
                run("base", noise, grid, dtype)
                tb.append(time.thread_time() - t)
                t = time.thread_time()
                run("this", noise, grid, dtype)
                tt.append(time.thread_time() - t)
            tb, tt = np.array(tb), np.array(tt)
            print(f"| {n}^{dim}, {args.octaves} octave(s) | {args.kernel} {basis} | {hash_} | {np.dtype(dtype).name} "
                  f"| {np.median(tb) * 1e3:.2f} | {np.median(tt) * 1e3:.2f} | {np.median(tb / tt):.2f} | {same} |",
                  flush=True)
    core.render_grid = paths["this"]
    print(f"load average (1 min) at the end: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
