"""Which lattice paths pay: each remaining grid path against the general one it replaces, side by side.

Run from the repository root::

    python benchmarks/bench_lattice_paths.py [--repeats 7]

Prints a Markdown table (and writes ``benchmarks/bench_lattice_paths.md``):
thread CPU time, one thread, median of ``--repeats`` interleaved rounds
(``noiselab.lab.measure.interleaved``), and the per-round ratio general /
special (above 1: the special path pays). The paths:

- the grid path (2-D and 3-D grids: the fused grid kernel,
  ``_jit._make_grid_rows``; 4-D grids: the separable passes; 1-D grids: the
  points path, the grid's points in blocks, one call per group of octaves)
  against the points path on the grid's points
  (``noise.evaluate(noise.grid_points(...))``): what a grid would cost
  without a grid path;
- 3-D table-hash points without a period by the block kernel
  (``points_path.TABLE_SPLIT``: per block of points the weights and taps
  vectorised, then the corner sum over folded tables; rows or columns read
  in place) against the per-point kernel on the same points (the same
  bits), and with ``--base <checkout>`` against that checkout's kernel split
  per chunk (0.4.0's, loaded beside this tree's and called directly: without
  the input checks this tree's call includes, so the ratio understates the
  gain; the same bits);
- 1-3-D integer-hash values by the kernels for 1-3-D
  (``points_path.INT_FAST_DIM``: the in-place kernels without a period of
  their own, the kernel vectorised across points with one) against the
  general integer-hash kernel (the same bits);
- 3-D integer-hash values without a period by the in-place kernels
  (``points_path.INT_BLOCK``: 2-tap kernels point by point, the others
  block by block, rows or columns read in place) against the vectorised
  kernel (the same bits).

The fused 2-D grid kernel this script measured first (a run at commit
c825318, kept in ``bench_lattice_paths.md``) ran at 0.72-0.79x the separable
passes once its hand-written vector intrinsic was gone, and was removed.
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


BASE = None  # ``--base``: another checkout's lattice engine, loaded beside this one


def _base_call(noise, pts):
    """The base's split kernel for 3-D table-hash points without a period (its ``table_fast_kernel``), checked
    against this tree's bits."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("noiselab.lattice._jit_base", BASE / "noiselab/lattice/_jit.py")
    jit = sys.modules.get(spec.name)
    if jit is None:
        jit = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = jit
        spec.loader.exec_module(jit)
    k, grad = noise.kernel, noise.basis == "gradient"
    kernel = jit.table_fast_kernel(k.taps, grad)
    tail = (noise.perms, noise.values, noise.gradients) if grad else \
        jit.pair_tables(noise.perms, noise.values) + (noise.gradients,)

    def call():
        out = np.empty((pts.shape[0], 1))
        kernel(pts, out, np.ones((1, 3)), np.array([noise.scale]), noise.phase, k.shift, k.left, k.taps, k.coef,
               k.dcoef, noise.period, noise._pmask, *tail, int(grad), False)
        return out[:, 0]

    if not np.array_equal(call(), noise(pts)):
        raise AssertionError("the base's kernel gives other bits than this tree's")
    return call


def cases():
    from noiselab.lattice import points_path

    out = []
    # 2-D and 3-D grids take the fused kernel (grid_path.FUSED_DIMS), 4-D ones the separable passes, 1-D ones the
    # points path by octaves (grid_path.is_separable): the 1-D rows measure what the grid's blocks add to it
    for d, shape, cells in ((1, (1 << 18,), 4096), (2, (512, 512), 32), (3, (64, 64, 64), 8), (4, (24,) * 4, 4)):
        ext = [(0, cells)] * d
        for label, kw in (("value cubic", {}), ("gradient quintic", {"basis": "gradient"})):
            for h in ("table", "integer"):
                n = nl.LatticeNoise(d, hash=h, **kw)
                pts = n.grid_points(shape, ext)
                octaves = 6 if d <= 2 else 1
                path = "fused grid kernel" if d in (2, 3) else "separable passes" if d > 3 else "grid path"
                out.append((f"{shape} grid, {octaves} octave(s), {h} hash, {label}: {path} vs points path",
                            (lambda n, o, s, e: lambda: n.evaluate_grid(s, e, octaves=o))(n, octaves, shape, ext),
                            (lambda n, p, o: lambda: n.evaluate(p, octaves=o))(n, pts, octaves)))
    from noiselab.lattice import grid_path

    def with_block(block, fn):
        def run():
            old = grid_path.SCATTERED_BLOCK
            grid_path.SCATTERED_BLOCK = block
            try:
                return fn()
            finally:
                grid_path.SCATTERED_BLOCK = old
        return run

    # octaves sparser than the grid (the scattered path): blocks of rows against one row per call; and the
    # integer hash's 2-D fBm grids, denser and sparser than the finest octave, against the points path
    for cells, label, kw in ((32, "value cubic", {}), (64, "value cubic", {}), (16, "value quintic", {"kernel": "quintic"}),
                             (64, "value quintic", {"kernel": "quintic"}), (16, "gradient quintic", {"basis": "gradient"}),
                             (64, "gradient quintic", {"basis": "gradient"})):
        n = nl.LatticeNoise(2, hash="integer", **kw)
        shape, ext = (512, 512), [(0, cells), (0, cells)]
        call = (lambda n, s, e: lambda: n.evaluate_grid(s, e, octaves=6))(n, shape, ext)
        if "cubic" in label:
            out.append((f"512^2 grid, {cells} cells, 6 octaves, integer hash, {label}: scattered octaves in blocks of "
                        "rows vs one row per call", with_block(1 << 16, call), with_block(1, call)))
        pts2 = n.grid_points(shape, ext)
        out.append((f"512^2 grid, {cells} cells, 6 octaves, integer hash, {label}: grid path vs points path",
                    call, (lambda n, p: lambda: n.evaluate(p, octaves=6))(n, pts2)))
    pts = np.random.default_rng(0).random((1_000_000, 3)) * 32

    def with_attrs(attrs, fn):
        def run():
            old = {k: getattr(points_path, k) for k in attrs}
            for k, v in attrs.items():
                setattr(points_path, k, v)
            try:
                return fn()
            finally:
                for k, v in old.items():
                    setattr(points_path, k, v)
        return run

    table_cases = (("value cubic", {}), ("value quintic", {"kernel": "quintic"}),
                   ("value catmull-rom", {"kernel": "catmull-rom"}),
                   ("gradient quintic", {"basis": "gradient", "kernel": "quintic"}))
    for label, kw in table_cases:
        n = nl.LatticeNoise(3, **kw)
        call = (lambda n: lambda: n(pts))(n)
        out.append((f"1e6 3-D points, table hash, {label}: block kernel vs per-point kernel",
                    with_attrs({"PAIRS_MIN": 0, "TABLE_SPLIT": True}, call),
                    with_attrs({"PAIRS_MIN": 0, "TABLE_SPLIT": False}, call)))
    n = nl.LatticeNoise(3)
    call = (lambda n: lambda: n(pts.T, axis=0))(n)
    out.append(("1e6 3-D points as (3, N) columns, table hash, value cubic: block kernel vs per-point kernel",
                with_attrs({"PAIRS_MIN": 0, "TABLE_SPLIT": True}, call),
                with_attrs({"PAIRS_MIN": 0, "TABLE_SPLIT": False}, call)))
    if BASE is not None:   # the kernel split per chunk that the block kernel replaced (``--base``: main cc234ff)
        for label, kw in table_cases:
            n = nl.LatticeNoise(3, **kw)
            out.append((f"1e6 3-D points, table hash, {label}: block kernel vs the base's split kernel",
                        (lambda n: lambda: n(pts))(n), _base_call(n, pts)))

    def with_fast(dims, fn):
        return with_attrs({"INT_FAST_DIM": dims}, fn)

    p32 = pts.astype(np.float32)
    for label, kw in (("value cubic", {}), ("gradient quintic", {"basis": "gradient"}),
                      ("value catmull-rom", {"kernel": "catmull-rom"}), ("value cubic, period 7", {"period": 7})):
        n = nl.LatticeNoise(3, hash="integer", **kw)
        call = (lambda n: lambda: n(pts))(n)
        special = "vectorised kernel" if "period" in kw else "in-place kernel"  # (the 1-3-D kernel this call takes)
        out.append((f"1e6 3-D points, integer hash, {label}: {special} vs general kernel",
                    with_fast(3, call), with_fast(0, call)))
    call = (lambda n: lambda: n(p32))(nl.LatticeNoise(3, hash="integer"))
    out.append(("1e6 3-D float32 points, integer hash, value cubic: in-place kernel vs general kernel",
                with_fast(3, call), with_fast(0, call)))
    for label, kw in (("value cubic", {}), ("gradient quintic", {"basis": "gradient"})):
        n = nl.LatticeNoise(3, hash="integer", **kw)
        out.append((f"1e6 3-D float32 points, integer hash, {label}: read in place vs a float64 copy first",
                    (lambda n: lambda: n(p32))(n), (lambda n: lambda: n(p32.astype(np.float64), dtype=np.float32))(n)))
    # the in-place kernels (INT_BLOCK: 2-tap kernels point by point, the others block by block) against the
    # vectorised kernel they replace without a period, on float32 points as the speed targets
    c32 = np.ascontiguousarray(p32.T)
    for label, kw, layout in (("value quintic", {"kernel": "quintic"}, "rows"),
                              ("value quintic", {"kernel": "quintic"}, "columns"),
                              ("gradient quintic", {"basis": "gradient", "kernel": "quintic"}, "rows"),
                              ("value catmull-rom", {"kernel": "catmull-rom"}, "rows"), ("value cubic", {}, "rows")):
        n = nl.LatticeNoise(3, hash="integer", **kw)
        call = ((lambda n: lambda: n(p32)) if layout == "rows" else (lambda n: lambda: n(c32, axis=0)))(n)
        out.append((f"1e6 3-D float32 points as {layout}, integer hash, {label}: in-place kernel vs vectorised kernel",
                    with_attrs({"INT_BLOCK": True}, call), with_attrs({"INT_BLOCK": False}, call)))
    for d, label, kw in ((2, "value cubic", {}), (2, "gradient quintic", {"basis": "gradient"}),
                         (1, "value cubic", {})):
        n = nl.LatticeNoise(d, hash="integer", **kw)
        call = (lambda n, p: lambda: n(p))(n, np.ascontiguousarray(pts[:, :d]))
        out.append((f"1e6 {d}-D points, integer hash, {label}: in-place kernel vs general kernel",
                    with_fast(3, call), with_fast(0, call)))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--output", default=str(Path(__file__).with_suffix(".md")))
    ap.add_argument("--only", default="", help="run only the rows whose description contains this text")
    ap.add_argument("--base", default=None, help="a checkout whose table-hash split kernel to measure beside")
    args = ap.parse_args(argv)
    global BASE
    BASE = Path(args.base) if args.base else None
    command = "python benchmarks/bench_lattice_paths.py " + shlex.join(argv if argv is not None else sys.argv[1:])
    info = run_info(command.strip())
    rows = []
    for what, special, general in cases():
        if args.only not in what:
            continue
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
