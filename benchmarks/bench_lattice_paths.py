"""Which lattice paths pay: each remaining grid path against the general one it replaces, side by side.

Run from the repository root::

    python benchmarks/bench_lattice_paths.py [--repeats 7]

Prints a Markdown table (and writes ``benchmarks/bench_lattice_paths.md``):
thread CPU time, one thread, median of ``--repeats`` interleaved rounds
(``noiselab.lab.measure.interleaved``), and the per-round ratio general /
special (above 1: the special path pays). The paths:

- the fused 2-D grid kernel (``grid_path.FUSED_2D``) against the general
  separable passes (lattice block, contractions, last pass) on 2-D grids;
- the points path on a grid's points (``noise(noise.grid_points(...))``)
  against the separable grid, 3-D: what a grid would cost without a grid path.
"""
from __future__ import annotations

import argparse
import os
import shlex
import sys
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

import noiselab as nl  # noqa: E402
from noiselab.lab.measure import header_lines, interleaved, markdown_table, run_info  # noqa: E402
from noiselab.lattice import Grid, grid_path  # noqa: E402


def _fused(flag, fn):
    def run():
        old = grid_path.FUSED_2D
        grid_path.FUSED_2D = flag
        try:
            return fn()
        finally:
            grid_path.FUSED_2D = old
    return run


def cases():
    g2 = Grid((512, 512), ((0, 32), (0, 32)))
    out = []
    for label, kw in (("value cubic", {}), ("gradient quintic", {"basis": "gradient"})):
        for h in ("table", "integer"):
            n = nl.LatticeNoise(2, hash=h, **kw)
            call = (lambda n: lambda: nl.fractal_sum(n, g2, octaves=6))(n)
            out.append((f"512^2 6-octave fBm, {h} hash, {label}: fused 2-D kernel vs separable passes",
                        _fused(True, call), _fused(False, call)))
    shape, ext = (64, 64, 64), [(0, 8)] * 3
    for label, kw in (("value cubic", {}), ("gradient quintic", {"basis": "gradient"})):
        n = nl.LatticeNoise(3, **kw)
        pts = n.grid_points(shape, ext)
        out.append((f"64^3 grid, table hash, {label}: separable grid vs points path",
                    (lambda n: lambda: n.grid(shape, ext))(n), (lambda n, p: lambda: n(p))(n, pts)))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--output", default=str(Path(__file__).with_suffix(".md")))
    args = ap.parse_args(argv)
    command = "python benchmarks/bench_lattice_paths.py " + shlex.join(argv if argv is not None else sys.argv[1:])
    info = run_info(command.strip())
    rows = []
    for what, special, general in cases():
        t = interleaved({"special": special, "general": general}, repeats=args.repeats, timer=time.thread_time)
        rows.append([what, f"{t['special'] * 1e3:.2f}", f"{t['general'] * 1e3:.2f}",
                     f"{t.ratio('general', 'special'):.2f}"])
        print(rows[-1], flush=True)
    lines = ["# Which lattice paths pay", ""] + header_lines(info) + [
        "", "Thread CPU time, one thread, median of the interleaved rounds; ratio = general / special per round.", ""]
    lines += markdown_table(["path (special vs general)", "special (ms)", "general (ms)", "ratio"], rows, "lrrr")
    Path(args.output).write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
