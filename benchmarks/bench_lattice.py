"""Lattice noise: speed against the floor and the installed peers, and precision at large coordinates.

Run with the peers' environment (see CONTRIBUTING.md)::

    benchmarks/.venv-peers/bin/python benchmarks/bench_lattice.py [--quick]

Writes ``benchmarks/bench_lattice.md`` beside this script. Every timing is
the median of ``--repeats`` (>= 5) runs, the candidates of one table
interleaved in the same process, one thread; every ratio is the median of
the ratios of back-to-back runs (robust to the load drifting on a shared
machine). The floor is writing a float64
array of the output's size (``np.full``); "x floor" is floor time / our time
(1.0 would be as fast as merely writing the output).
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numba as nb  # noqa: E402
import numpy as np  # noqa: E402

if not hasattr(np, "product"):  # pyfastnoisesimd 0.4.2 still calls np.product (removed in NumPy 2)
    np.product = np.prod

from noiselab import LatticeNoise, fractal_sum  # noqa: E402
from noiselab._core import run_split  # noqa: E402
from noiselab.lattice import Grid, kernel_names  # noqa: E402
from noiselab.lab.measure import Timings as Times, header_lines, interleaved, run_info  # noqa: E402
from noiselab.lattice._jit import pair_tables  # noqa: E402  (the table hash's folded tables, for its read bound)


def _peer(name):
    try:
        if name == "fnl":
            import pyfastnoiselite.pyfastnoiselite as mod
        elif name == "fns":
            import pyfastnoisesimd as mod
        elif name == "noise":
            import noise as mod
        elif name == "opensimplex":
            import opensimplex as mod
        elif name == "vnoise":
            import vnoise as mod
        elif name == "perlin_numpy":
            import perlin_numpy as mod
        elif name == "vtk":
            import vtk as mod
        else:
            raise ImportError(name)
        return mod
    except Exception as exc:  # a missing peer is reported, not fatal
        print(f"peer {name} unavailable: {exc}", file=sys.stderr)
        return None


def bench(cands: dict, repeats: int, clock=None) -> Times:
    """Time candidates interleaved (one warm-up round, order rotated each round), ``repeats`` rounds.

    ``clock``: the timer (wall time by default; ``time.process_time`` for CPU time).
    """
    return interleaved(cands, repeats=repeats, timer=clock)


# --------------------------------------------------------------------------- grids
GRID_HEAD = "## 2-D grids against pyfastnoisesimd and the floor"
# (n, lattice cells per side): the target's 1024^2 grid of 16 cells, and the denser 512^2 grid of 32 cells
# that the lab's peer comparison renders (noiselab/lab/peers.py, CELLS_1)
GRID_SETTINGS = ((1024, 16), (512, 32))


def _fns_noise(fns, basis, octaves, cells, n):
    """pyfastnoisesimd's like-for-like noise: Value(Fractal) for value, Perlin(Fractal) for gradient noise.

    One worker (the calling thread); frequency = lattice cells per sample; the
    fractal FBM with noiselab's octaves, lacunarity 2 and gain 0.5.
    """
    f = fns.Noise(seed=1, numWorkers=1)
    base = "Value" if basis == "value" else "Perlin"
    f.noiseType = getattr(fns.NoiseType, base if octaves == 1 else base + "Fractal")
    f.frequency = cells / n
    if octaves > 1:
        f.fractal.fractalType = fns.FractalType.FBM
        f.fractal.octaves = octaves
        f.fractal.lacunarity = 2.0
        f.fractal.gain = 0.5
    return f


def grid_section(repeats, quick, lines):
    fns = _peer("fns")
    lines.append(GRID_HEAD + "\n")
    lines.append("One thread; times are the thread's CPU time (`time.thread_time`: on the shared machine the wall "
                 "clock also counts the other jobs' share of the core). Every row's candidates are timed interleaved "
                 "in the same rounds: noiselab "
                 "(`LatticeNoise(2, kernel=..., basis=...)`, table hash; `.grid` for one octave, `fractal_sum(noise, "
                 "Grid(...), 6)` for six), pyfastnoisesimd's like-for-like noise (value: `Value` / `ValueFractal`; "
                 "gradient: `Perlin` / `PerlinFractal`; float32, 1 worker, `genAsGrid`, frequency = cells per "
                 "sample, FBM with 6 octaves, lacunarity 2, gain 0.5) and the floor (writing the output: "
                 "`np.full(shape, 0.5)` in the output's dtype). `x FNS` = pyfastnoisesimd time / time, `x floor` = "
                 "floor time / time (1.0 would be as fast as writing the output), each the median of the "
                 "per-round ratios. noiselab computes in float64 (the float32 column rounds the float64 sum as it "
                 "stores). `used`: the octaves `fractal_sum` evaluates (it drops octaves finer than the sample "
                 "spacing: 5 of 6 on the 512^2, 32-cell grid; pyfastnoisesimd computes all 6). pyfastnoisesimd's "
                 "value and Perlin noise interpolate with the quintic fade, so the quintic rows are the like-for-"
                 "like ones; the other kernels do more work per sample (a 4-tap kernel sums 16 lattice points in "
                 "2-D, the quintic 4).\n")
    summary = {}
    kernels = ["cubic", "quintic"] if quick else kernel_names()
    for n, cells in GRID_SETTINGS:
        shape = (n, n)
        npts = n * n
        grid = Grid(shape, [(0.0, float(cells)), (0.0, float(cells))])
        lines.append(f"### {n} x {n}, {cells} lattice cells per side\n")
        lines.append("| kernel | basis | octaves | float64 pts/s | x floor | x FNS | float32 pts/s | x floor | x FNS "
                     "| FNS pts/s |")
        lines.append("|---|---|---|---|---|---|---|---|---|---|")
        for kname in kernels:
            for basis in ("value", "gradient"):
                noise = LatticeNoise(2, rng=1, kernel=kname, basis=basis)
                cands = {"floor_float64": lambda: np.full(shape, 0.5),
                         "floor_float32": lambda: np.full(shape, 0.5, dtype=np.float32)}
                if fns is not None:
                    for octaves in (1, 6):
                        f = _fns_noise(fns, basis, octaves, cells, n)
                        cands[f"fns{octaves}"] = lambda f=f: f.genAsGrid([1, *shape])
                for dt in ("float64", "float32"):
                    cands[f"one_{dt}"] = lambda dt=dt, noise=noise: noise.grid(shape, grid.extent, dtype=dt)
                    cands[f"six_{dt}"] = lambda dt=dt, noise=noise: fractal_sum(noise, grid, 6, dtype=dt)
                # this thread's CPU time: other jobs preempting it on the shared machine do not count, and every
                # candidate (pyfastnoisesimd with one worker included) runs in the calling thread
                t = bench(cands, repeats, clock=time.thread_time)
                _, used = fractal_sum(noise, grid, 6, return_octaves=True)
                for label, key, fkey in (("1", "one", "fns1"), (f"6 (used {used})", "six", "fns6")):
                    row = [kname, basis, label]
                    for dt in ("float64", "float32"):
                        k_ = f"{key}_{dt}"
                        xfns = t.ratio(fkey, k_) if fkey in t else None
                        row += [f"{npts / t[k_]:.3g}", f"{t.ratio('floor_' + dt, k_):.2f}",
                                f"{xfns:.2f}" if xfns is not None else "n/a"]
                        summary[(n, kname, basis, key, dt)] = (npts / t[k_], t.ratio("floor_" + dt, k_), xfns)
                    row.append(f"{npts / t[fkey]:.3g}" if fkey in t else "n/a")
                    lines.append("| " + " | ".join(row) + " |")
        lines.append("")
    fns_rows = [v[2] for k, v in summary.items() if v[2] is not None]
    if fns_rows:
        grad = [v[2] for k, v in summary.items() if k[2] == "gradient" and v[2] is not None]
        dense = [v[2] for k, v in summary.items() if k[0] == 512 and v[2] is not None]
        quint = [v[2] for k, v in summary.items() if k[1] == "quintic" and v[2] is not None]
        lines.append(f"Range of `x FNS` over the tables: all rows {min(fns_rows):.2f}-{max(fns_rows):.2f}; gradient "
                     f"rows {min(grad):.2f}-{max(grad):.2f}; the 512^2, 32-cell rows {min(dense):.2f}-{max(dense):.2f}; "
                     f"the quintic rows {min(quint):.2f}-{max(quint):.2f}.\n")
    shape = (1024, 1024)
    cells = 16.0
    npts = shape[0] * shape[1]
    grid = Grid(shape, [(0.0, cells), (0.0, cells)])

    # other grid peers, one octave, measured once side by side
    lines.append("### Other peers on the 1024 x 1024 grid (one octave)\n")
    lines.append("CPU time of the calling thread (`time.thread_time`), as above.\n")
    lines.append("| implementation | precision | pts/s | x floor | note |")
    lines.append("|---|---|---|---|---|")
    cands = {"floor": lambda: np.full(shape, 0.5)}
    notes = {}
    noise = LatticeNoise(2, rng=1, kernel="quintic")
    cands["noiselab value quintic (float64)"] = lambda: noise.grid(shape, grid.extent)
    xs = np.arange(shape[1]) * (cells / shape[1])
    fnl = _peer("fnl")
    if fnl is not None:
        coords = np.ascontiguousarray(np.stack(np.meshgrid(xs, xs, indexing="ij")[::-1]).reshape(2, -1).astype(np.float32))
        lite = fnl.FastNoiseLite(1)
        lite.noise_type = fnl.NoiseType.NoiseType_Value
        lite.frequency = 1.0
        cands["pyfastnoiselite value (gen_from_coords)"] = lambda: lite.gen_from_coords(coords)
        notes["pyfastnoiselite value (gen_from_coords)"] = ("float32", "coordinates prepared outside the timing")
    osx = _peer("opensimplex")
    if osx is not None:
        osx.seed(1)
        cands["opensimplex noise2array"] = lambda: osx.noise2array(xs, xs)
        notes["opensimplex noise2array"] = ("float64", "OpenSimplex2 (not lattice value noise), numba")
    vn = _peer("vnoise")
    if vn is not None:
        vobj = vn.Noise(1)
        cands["vnoise noise2 (grid_mode)"] = lambda: vobj.noise2(xs, xs, grid_mode=True)
        notes["vnoise noise2 (grid_mode)"] = ("float64", "Perlin gradient noise in NumPy")
    pn = _peer("perlin_numpy")
    if pn is not None:
        cands["perlin-numpy generate_perlin_noise_2d"] = lambda: pn.generate_perlin_noise_2d(shape, (16, 16), rng=np.random.default_rng(1))
        notes["perlin-numpy generate_perlin_noise_2d"] = ("float64", "gradient noise, whole-grid NumPy")
    t = bench(cands, repeats, clock=time.thread_time)
    for k, v in t.items():
        if k == "floor":
            continue
        prec, note = notes.get(k, ("float64", ""))
        lines.append(f"| {k} | {prec} | {npts / v:.3g} | {t.ratio('floor', k):.2f} | {note} |")
    # per-point Python-loop peers: measured on a subset, rate extrapolated
    sub = 128
    slow = {}
    nz = _peer("noise")
    if nz is not None:
        slow["noise.pnoise2 (Python loop, 128x128)"] = lambda: [nz.pnoise2(x, y) for x in xs[:sub] for y in xs[:sub]]
    vtk = _peer("vtk")
    if vtk is not None:
        pv = vtk.vtkPerlinNoise()
        slow["VTK vtkPerlinNoise.EvaluateFunction (Python loop, 128x128)"] = \
            lambda: [pv.EvaluateFunction(x, y, 0.0) for x in xs[:sub] for y in xs[:sub]]
    if slow:
        ts = bench(slow, max(3, repeats // 2), clock=time.thread_time)
        for k, v in ts.items():
            lines.append(f"| {k} | float32 inside | {sub * sub / v:.3g} | {t['floor'] / (v * npts / (sub * sub)):.4f} | "
                         "one call per point |")
    lines.append("")
    return summary


# ----------------------------------------------------------------------- scattered
def scattered_section(repeats, quick, lines):
    npts = 1_000_000
    rng = np.random.default_rng(0)
    pts = rng.uniform(0.0, 100.0, (npts, 3))
    pts32 = pts.astype(np.float32)
    lines.append("## Scattered points: 1,000,000 random 3-D points in [0, 100)^3\n")
    lines.append("One thread, CPU time of the calling thread (`time.thread_time`; every candidate runs in it). "
                 "Computation in float64; the float32 column returns float32 (from float32 input). "
                 "`x floor` = time of `np.full(1_000_000, 0.5)` / time; `x FNL` = pyfastnoiselite value noise "
                 "(float32) time / time.\n")
    lines.append("| kernel (taps) | basis | float64 pts/s | x floor | x FNL | float32 pts/s | x floor | x FNL |")
    lines.append("|---|---|---|---|---|---|---|---|")
    fnl = _peer("fnl")
    coords = np.ascontiguousarray(pts32.T)
    summary = {}
    kernels = ["cubic", "quintic"] if quick else kernel_names()
    for kname in kernels:
        for basis in ("value", "gradient"):
            noise = LatticeNoise(3, rng=1, kernel=kname, basis=basis)
            cands = {"floor": lambda: np.full(npts, 0.5),
                     "f64": lambda noise=noise: noise(pts),
                     "f32": lambda noise=noise: noise(pts32)}
            if fnl is not None:
                lite = fnl.FastNoiseLite(1)
                lite.noise_type = fnl.NoiseType.NoiseType_Value
                lite.frequency = 1.0
                cands["fnl"] = lambda lite=lite: lite.gen_from_coords(coords)
            t = bench(cands, repeats, clock=time.thread_time)
            xf = lambda k: f"{t.ratio('fnl', k):.2f}" if "fnl" in t else "n/a"  # noqa: E731
            lines.append(f"| {kname} ({noise.kernel.taps}) | {basis} | {npts / t['f64']:.3g} | {t.ratio('floor', 'f64'):.3f} | "
                         f"{xf('f64')} | {npts / t['f32']:.3g} | {t.ratio('floor', 'f32'):.3f} | {xf('f32')} |")
            summary[(kname, basis)] = (npts / t["f64"], t.ratio("fnl", "f64") if "fnl" in t else None)
            if "fnl" in t:
                summary["fnl"] = npts / t["fnl"]
    # two threads (opt-in workers=2), and 60-octave fractal sums, beside the one-thread figure
    lines.append("\n### Two threads, and fractal sums (value noise, float64)\n")
    lines.append("`workers=2` splits the points into two blocks evaluated on two threads (bit-identical to one); "
                 "pyfastnoiselite stays on one thread. `fractal_sum(noise, pts, 60)` evaluates the octaves whose "
                 "amplitude is above float64 resolution (54 of 60; without `spacing=` nothing tells which octaves "
                 "the points can resolve); `x 1 octave` = time of one octave / time. Wall-clock time (`time.perf_counter`: "
                 "the CPU time of two threads adds up), so on the shared machine the other jobs' load lowers the "
                 "`workers=2` row.\n")
    lines.append("| kernel | evaluation | octaves used | pts/s | x 1 octave | x FNL |")
    lines.append("|---|---|---|---|---|---|")
    for kname in ("quintic", "cubic"):
        noise = LatticeNoise(3, rng=1, kernel=kname)
        _, used60 = fractal_sum(noise, pts[:10], 60, return_octaves=True)
        _, used6 = fractal_sum(noise, pts[:10], 6, return_octaves=True)
        cands = {"one": lambda noise=noise: noise(pts),
                 "two": lambda noise=noise: noise(pts, workers=2),
                 "six": lambda noise=noise: fractal_sum(noise, pts, 6),
                 "sixty": lambda noise=noise: fractal_sum(noise, pts, 60)}
        if fnl is not None:
            lite = fnl.FastNoiseLite(1)
            lite.noise_type = fnl.NoiseType.NoiseType_Value
            lite.frequency = 1.0
            cands["fnl"] = lambda lite=lite: lite.gen_from_coords(coords)
        t = bench(cands, repeats)
        for key, label, used in (("one", "one thread", 1), ("two", "`workers=2`", 1),
                                 ("six", "`fractal_sum(..., 6)`", used6), ("sixty", "`fractal_sum(..., 60)`", used60)):
            xf = f"{t.ratio('fnl', key):.2f}" if "fnl" in t else "n/a"
            lines.append(f"| {kname} | {label} | {used} | {npts / t[key]:.3g} | {t.ratio('one', key):.3f} | {xf} |")
            summary[(kname, "value", key)] = (npts / t[key], t.ratio("fnl", key) if "fnl" in t else None,
                                              t.ratio("one", key), used)
    # peers
    lines.append("\n### Peers on the same points\n")
    lines.append("| implementation | precision | pts/s |")
    lines.append("|---|---|---|")
    cands = {}
    if fnl is not None:
        for label, nt in (("value", fnl.NoiseType.NoiseType_Value), ("perlin", fnl.NoiseType.NoiseType_Perlin)):
            lite = fnl.FastNoiseLite(1)
            lite.noise_type = nt
            lite.frequency = 1.0
            cands[f"pyfastnoiselite {label}"] = lambda lite=lite: lite.gen_from_coords(coords)
    fns = _peer("fns")
    if fns is not None:
        for label, nt in (("value", fns.NoiseType.Value), ("perlin", fns.NoiseType.Perlin)):
            cands[f"pyfastnoisesimd {label} (1 worker)"] = _fns_points(fns, nt, pts32)
    vn = _peer("vnoise")
    if vn is not None:
        vobj = vn.Noise(1)
        cands["vnoise noise3 (points)"] = lambda: vobj.noise3(pts[:, 0], pts[:, 1], pts[:, 2], grid_mode=False)
    t = bench(cands, repeats, clock=time.thread_time) if cands else {}
    for k, v in t.items():
        lines.append(f"| {k} | {'float64' if 'vnoise' in k else 'float32'} | {npts / v:.3g} |")
        summary[k] = npts / v
    nz = _peer("noise")
    if nz is not None:
        sub = pts[:20000]
        ts = bench({"noise": lambda: [nz.pnoise3(*p) for p in sub]}, max(3, repeats // 2), clock=time.thread_time)
        lines.append(f"| noise.pnoise3 (Python loop) | float32 | {sub.shape[0] / ts['noise']:.3g} |")
    lines.append("")
    return summary


# ------------------------------------------------------------------- integer hash
HASH_HEAD = "## Scattered points: the table hash, the integer hash's SIMD kernels and the SIMD peers"


def _fns_points(fns, noise_type, pts32):
    """pyfastnoisesimd on the float32 points, one worker, frequency 1: a candidate callable (coordinates aligned once)."""
    aligned = fns.empty_coords(pts32.shape[0])
    aligned[:] = pts32.T
    f = fns.Noise(seed=1, numWorkers=1)
    f.noiseType = noise_type
    f.frequency = 1.0
    return lambda: f.genFromCoords(aligned)


def _max_err(a, b):
    return float(np.max(np.abs(np.asarray(a, np.float64) - np.asarray(b, np.float64))))


def hash_section(repeats, lines, npts=1_000_000):
    """Both hashes beside pyfastnoisesimd / pyfastnoiselite (1 thread) and the floor, interleaved in one process.

    Timed in process CPU time (``time.process_time``), one thread each: on a
    2-core machine shared with other jobs, wall time counts the time the
    process waits for a core; CPU time does not. pyfastnoisesimd is run with
    ``numWorkers=1``.
    """
    rng = np.random.default_rng(0)
    fns = _peer("fns")
    fnl = _peer("fnl")
    lines.append(HASH_HEAD + "\n")
    lines.append(f"{npts:,} random points in [0, 100)^d, one thread, CPU time (median of the interleaved rounds). "
                 "Columns: the table hash (Phillips' permutation, float64 points); the integer hash with float64 "
                 "points (float64 arithmetic); float32 points at frequency 1 (the float32 SIMD kernel: its split "
                 "is exact there); float32 points at frequency 0.37 (float64 split, float32 arithmetic); the peer "
                 "(float32 coordinates; pyfastnoisesimd given its own aligned (3, N) buffer). `x peer` = peer time "
                 "/ time (> 1: noiselab faster); `x floor` = time of writing the float32 output "
                 "(`np.full(N, 0.5, np.float32)`) / time. `err32`: max |float32 - float64| of the integer hash at "
                 "the same (float32-representable) points.\n")
    lines.append("| d | noise | peer | table f64 pts/s | integer f64 pts/s | x peer | integer f32 pts/s | x peer "
                 "| x floor | integer f32, F=0.37 pts/s | x peer | peer pts/s | err32 |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = [(3, "quintic", "value", "Value"), (3, "quintic", "gradient", "Perlin"),
            (3, "catmull-rom", "value", "Cubic"), (3, "cubic", "value", "Cubic"),
            (2, "quintic", "value", "Value"), (2, "quintic", "gradient", "Perlin"),
            (2, "catmull-rom", "value", "ValueCubic"),
            (1, "quintic", "value", None), (1, "quintic", "gradient", None), (1, "catmull-rom", "value", None)]
    summary = {}
    for d, kname, basis, peer in rows:
        pts32 = rng.uniform(0.0, 100.0, (npts, d)).astype(np.float32)
        pts = pts32.astype(np.float64)
        table = LatticeNoise(d, rng=1, kernel=kname, basis=basis)
        integer = LatticeNoise(d, rng=1, kernel=kname, basis=basis, hash="integer")
        general = LatticeNoise(d, rng=1, kernel=kname, basis=basis, hash="integer", frequency=0.37)
        cands = {"floor": lambda: np.full(npts, 0.5, np.float32), "table": lambda: table(pts),
                 "integer": lambda: integer(pts), "integer32": lambda: integer(pts32),
                 "general32": lambda: general(pts32)}
        peer_name = None
        if d == 3 and fns is not None:
            cands["peer"] = _fns_points(fns, getattr(fns.NoiseType, peer), pts32)
            peer_name = f"FNS {peer}"
        elif d == 2 and fnl is not None:
            lite = fnl.FastNoiseLite(1)
            lite.noise_type = {"Value": fnl.NoiseType.NoiseType_Value, "Perlin": fnl.NoiseType.NoiseType_Perlin,
                               "ValueCubic": fnl.NoiseType.NoiseType_ValueCubic}[peer]
            lite.frequency = 1.0
            coords = np.ascontiguousarray(pts32.T)
            cands["peer"] = lambda lite=lite, coords=coords: lite.gen_from_coords(coords)
            peer_name = f"FNL {peer}"
        t = bench(cands, repeats, clock=time.process_time)
        err32 = max(_max_err(integer(pts32), integer(pts)), _max_err(general(pts32), general(pts)))
        xp = lambda k: f"{t.ratio('peer', k):.2f}" if "peer" in t else "n/a"  # noqa: E731
        lines.append(f"| {d} | {kname} {basis} | {peer_name or 'none'} | {npts / t['table']:.3g} | "
                     f"{npts / t['integer']:.3g} | {xp('integer')} | {npts / t['integer32']:.3g} | {xp('integer32')} | "
                     f"{t.ratio('floor', 'integer32'):.3f} | {npts / t['general32']:.3g} | {xp('general32')} | "
                     f"{npts / t['peer'] if 'peer' in t else float('nan'):.3g} | {err32:.1e} |")
        summary[(d, kname, basis)] = {k: (npts / t[k], t.ratio("peer", k) if "peer" in t else None)
                                      for k in ("table", "integer", "integer32", "general32")}
    lines.append("")
    return summary


# ------------------------------------------------------------------ noiselab's speed targets
TARGET_HEAD = "## The speed targets: pyfastnoisesimd on one thread, the write floor, and `workers=2`"
# (kernel, basis, pyfastnoisesimd's like-for-like noise) of the targets' 3-D points rows
TARGET_POINTS = (("quintic", "value", "Value"), ("quintic", "gradient", "Perlin"), ("catmull-rom", "value", "Cubic"))
TARGET_GRID = (512, 16)  # 512^2 samples over 16 lattice cells per side: fractal_sum keeps all 6 octaves


def _hashed(dim, kname, basis, hname):
    return LatticeNoise(dim, rng=1, kernel=kname, basis=basis, **({} if hname == "table" else {"hash": hname}))


def _target_cell(t, key, n, fkey):
    """``pts/s (x FNS, x floor)`` of candidate ``key`` (its dtype's floor)."""
    floor = "floor32" if key.endswith("32") else "floor64"
    xf = f"{t.ratio(fkey, key):.2f}" if fkey in t else "n/a"
    return f"{n / t[key]:.3g}", xf, f"{t.ratio(floor, key):.3f}"


def _scaling(cands, repeats):
    """``"speed-up (cores)"``: the wall-clock speed-up of ``two`` over ``one`` and the cores ``two`` obtained.

    Wall time (median of the per-round ratios): CPU time would add both
    threads. The cores obtained (process CPU time / wall time of ``two``,
    median of ``repeats`` calls) tell a shared machine's load apart from the
    code: near 1, the other jobs held the second core.
    """
    t = bench(cands, repeats)  # perf_counter
    cores = []
    for _ in range(repeats):
        w0, c0 = time.perf_counter(), time.process_time()
        cands["two"]()
        cores.append((time.process_time() - c0) / (time.perf_counter() - w0))
    return f"{t.ratio('one', 'two'):.2f} ({np.median(cores):.1f})"


def _points_limit(noise, kname, basis, hname, pts, cols32):
    """``(name, call)``: a lower bound of the points row's time (``benchmarks/bench_limits.py``), or None.

    The table hash: its block kernel's reads alone, for the row's taps and
    basis, on ``noise``'s own folded tables. The integer hash: ``int-minimal``,
    which exists for quintic value noise only.
    """
    from bench_limits import _make_lookups, int_minimal  # (kernels of the limits' script, beside this one)

    if hname == "table":
        taps, grad = noise.kernel.taps, basis == "gradient"
        tables = pair_tables(noise.perms, noise.values, noise.gradients if grad else None)
        h2, tl = (t[0] for t in tables)
        reads, out = _make_lookups(taps, grad), np.empty(pts.shape[0])
        name = "`lookups" + ("-gradient" if grad else "-4taps" if taps == 4 else "") + "`"
        return name, lambda: reads(pts, h2, tl, out)
    if (kname, basis) == ("quintic", "value"):
        out32, key = np.empty(cols32.shape[1], np.float32), np.uint32(noise.keys[0])
        return "`int-minimal`", lambda: int_minimal(cols32[0], cols32[1], cols32[2], key, out32)
    return None


def targets_section(repeats, lines, npts=1_000_000):
    """The speed targets, both hashes: 3-D points and 512^2 6-octave fBm grids against pyfastnoisesimd."""
    fns = _peer("fns")
    rng = np.random.default_rng(0)
    pts32 = rng.uniform(0.0, 100.0, (npts, 3)).astype(np.float32)
    pts = pts32.astype(np.float64)
    lines.append(TARGET_HEAD + "\n")
    lines.append(f"One thread unless stated. Single-thread rows: CPU time of the calling thread (`time.thread_time`; "
                 "pyfastnoisesimd with `numWorkers=1` runs in the calling thread), median of the interleaved rounds; "
                 "`x FNS` = pyfastnoisesimd time / time (> 1: noiselab faster) and `x floor` = time of writing the "
                 "output in its dtype (`np.full(..., 0.5)`) / time, each the median of the per-round ratios. "
                 "f64: float64 points (or float64 output) computed in float64; f32: float32 points in, float32 out "
                 "(or `dtype=float32` for grids). `err32` = max |f32 - f64| at the same (float32-representable) "
                 "points. `w2` = wall-clock time of `workers=1` / time of `workers=2` on the f32 call (wall time, "
                 "since the CPU time of two threads adds up), and in brackets the cores the `workers=2` call obtained "
                 "(process CPU time / wall time): on this shared 2-core machine a figure near 1 means the other "
                 "jobs held the second core, so the speed-up measures the load, not the code.\n")
    lines.append(f"### {npts:,} random 3-D points in [0, 100)^3\n")
    lines.append("`(d, N)`: the same points as `(3, N)` columns (`noise(pts.T, axis=0)`, read in place: structure of "
                 "arrays, as pyfastnoisesimd takes them), `x FNS` of the f64 and f32 calls. `a32`: the float32 "
                 "arithmetic on the float32 points (`noise.evaluate(pts32, arithmetic=\"float32\")`, integer hash "
                 "only), `x FNS` from `(N, 3)` rows and `(3, N)` columns.\n")
    lines.append("| noise | hash | FNS | f64 pts/s | x FNS | x floor | f32 pts/s | x FNS | x floor | err32 "
                 "| FNS pts/s | w2 wall (cores) | (d, N) f64 x FNS | (d, N) f32 x FNS | a32 x FNS | (d, N) a32 x FNS |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    cols, cols32 = np.ascontiguousarray(pts.T), np.ascontiguousarray(pts32.T)
    summary, limit_rows = {}, []
    for kname, basis, peer in TARGET_POINTS:
        for hname in ("table", "integer"):
            noise = _hashed(3, kname, basis, hname)
            cands = {"floor64": lambda: np.full(npts, 0.5), "floor32": lambda: np.full(npts, 0.5, np.float32),
                     "f64": lambda noise=noise: noise(pts), "f32": lambda noise=noise: noise(pts32),
                     "f64T": lambda noise=noise: noise(cols, axis=0), "f32T": lambda noise=noise: noise(cols32, axis=0)}
            if hname == "integer":
                cands["a32"] = lambda noise=noise: noise.evaluate(pts32, arithmetic="float32")
                cands["a32T"] = lambda noise=noise: noise.evaluate(cols32, axis=0, arithmetic="float32")
            limit = _points_limit(noise, kname, basis, hname, pts, cols32)
            if limit is not None:
                cands["limit"] = limit[1]
            if fns is not None:
                cands["fns"] = _fns_points(fns, getattr(fns.NoiseType, peer), pts32)
            t = bench(cands, repeats, clock=time.thread_time)
            err32 = _max_err(noise(pts32), noise(pts))
            a32 = [_target_cell(t, k, npts, "fns")[1] if k in t else "n/a" for k in ("a32", "a32T")]
            w2 = _scaling({"one": lambda noise=noise: noise(pts32),
                           "two": lambda noise=noise: noise(pts32, workers=2)}, repeats)
            c64, c32 = _target_cell(t, "f64", npts, "fns"), _target_cell(t, "f32", npts, "fns")
            fns_rate = f"{npts / t['fns']:.3g}" if "fns" in t else "n/a"
            lines.append(f"| 3-D points, {kname} {basis} | {hname} | {peer} | {' | '.join(c64)} | {' | '.join(c32)} "
                         f"| {err32:.1e} | {fns_rate} | {w2} | {_target_cell(t, 'f64T', npts, 'fns')[1]} "
                         f"| {_target_cell(t, 'f32T', npts, 'fns')[1]} | {' | '.join(a32)} |")
            summary[("points", kname, basis, hname)] = (t, err32, w2)
            if limit is not None:
                call = "f64" if hname == "table" else "a32T"
                xf = f"{t.ratio('fns', 'limit'):.2f}" if "fns" in t else "n/a"
                limit_rows.append(f"| 3-D points, {kname} {basis} | {hname} | {limit[0]} | {xf} | "
                                  f"{_target_cell(t, call, npts, 'fns')[1]} | {t.ratio('limit', call):.2f} |")
    lines.append("\nWhat limits the points, timed in the same rounds as the rows above: the table hash's reads alone "
                 "(`lookups`: the pair-table and value reads of noiselab's block kernel and nothing else, on the same "
                 "folded tables, float64 points; `benchmarks/bench_limits.py`) against the float64 call; for the "
                 "integer hash, the shortest numba loop with its arithmetic (`int-minimal`: float32 columns in and "
                 "out, floor, quintic fade, eight hashed corners, trilinear blend; no checks, blocks, octaves or "
                 "fallback) against the float32 arithmetic from `(3, N)` columns. `x limit` = the limit's time / "
                 "the call's (1.0: the call as fast as its limit).\n")
    lines.append("| noise | hash | limit | limit x FNS | call x FNS | x limit |")
    lines.append("|---|---|---|---|---|---|")
    lines += limit_rows
    n, cells = TARGET_GRID
    shape = (n, n)
    grid = Grid(shape, [(0.0, float(cells)), (0.0, float(cells))])
    lines.append(f"\n### {n} x {n} grid, {cells} lattice cells per side, 6-octave fBm (`fractal_sum(noise, Grid, 6)`)\n")
    lines.append("pyfastnoisesimd: `ValueFractal` / `PerlinFractal`, FBM, 6 octaves, lacunarity 2, gain 0.5, "
                 "`genAsGrid`, float32, 1 worker. `used`: octaves `fractal_sum` evaluates. `w2`: "
                 "`fractal_sum(..., workers=2)` (two bands of rows on two threads) against `workers=1`, float32.\n")
    lines.append("| noise | hash | used | f64 pts/s | x FNS | x floor | f32 pts/s | x FNS | x floor | err32 | FNS pts/s "
                 "| w2 wall (cores) |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for basis in ("value", "gradient"):
        for hname in ("table", "integer"):
            noise = _hashed(2, "quintic", basis, hname)
            cands = {"floor64": lambda: np.full(shape, 0.5), "floor32": lambda: np.full(shape, 0.5, np.float32),
                     "f64": lambda noise=noise: fractal_sum(noise, grid, 6),
                     "f32": lambda noise=noise: fractal_sum(noise, grid, 6, dtype=np.float32)}
            if fns is not None:
                f = _fns_noise(fns, basis, 6, cells, n)
                cands["fns"] = lambda f=f: f.genAsGrid([1, *shape])
            t = bench(cands, repeats, clock=time.thread_time)
            _, used = fractal_sum(noise, grid, 6, return_octaves=True)
            err32 = _max_err(fractal_sum(noise, grid, 6, dtype=np.float32), fractal_sum(noise, grid, 6))
            w2 = _scaling({"one": lambda noise=noise: fractal_sum(noise, grid, 6, dtype=np.float32),
                           "two": lambda noise=noise: fractal_sum(noise, grid, 6, dtype=np.float32, workers=2)},
                          repeats)
            c64, c32 = _target_cell(t, "f64", n * n, "fns"), _target_cell(t, "f32", n * n, "fns")
            fns_rate = f"{n * n / t['fns']:.3g}" if "fns" in t else "n/a"
            lines.append(f"| {n}^2 fBm, quintic {basis} | {hname} | {used} | {' | '.join(c64)} | {' | '.join(c32)} "
                         f"| {err32:.1e} | {fns_rate} | {w2} |")
            summary[("grid", "quintic", basis, hname)] = (t, err32, w2)
    grid3_rows(repeats, lines, fns, summary)
    scaling_rows(repeats, lines, summary)
    lines.append("")
    return summary


@nb.njit(nogil=True)
def _stream_points(pts, out):
    """The memory traffic of a points call without the noise: read ``(N, 3)`` float32, write one float32 a point."""
    for i in range(pts.shape[0]):
        out[i] = pts[i, 0] + pts[i, 1] + pts[i, 2]


def scaling_rows(repeats, lines, summary):
    """``workers=2`` against 1 on bigger calls than the targets' (whose fixed costs bound their speed-up)."""
    lines.append("\n### `workers=2` on bigger calls\n")
    lines.append("The calls above take 1-10 ms, so their fixed costs (a band's set-up: its column weights and the "
                 "Python call, about 0.2 ms on the 512^2 fBm; a thread hand-off) bound the speed-up. The same calls, "
                 "larger: wall-clock speed-up of `workers=2` over `workers=1` (median of the per-round ratios) and "
                 "the cores the `workers=2` call obtained. The control row splits a loop that only streams the points' "
                 "memory the same way: what two threads gain when the memory traffic is all there is.\n")
    lines.append("| call | size | w2 wall (cores) |")
    lines.append("|---|---|---|")
    rng = np.random.default_rng(1)
    pts32 = rng.uniform(0.0, 100.0, (4_000_000, 3)).astype(np.float32)
    pts = pts32.astype(np.float64)
    grid = Grid((2048, 2048), [(0.0, 64.0), (0.0, 64.0)])
    calls = {
        "3-D points, quintic value, table hash, float64": ("4e6 points", _hashed(3, "quintic", "value", "table"), pts),
        "3-D points, quintic value, integer hash, float32": ("4e6 points", _hashed(3, "quintic", "value", "integer"),
                                                             pts32),
        "2-D fBm, quintic value, table hash, float32": ("2048^2, 6 octaves", _hashed(2, "quintic", "value", "table"),
                                                        grid),
        "2-D fBm, quintic gradient, integer hash, float32": ("2048^2, 6 octaves",
                                                             _hashed(2, "quintic", "gradient", "integer"), grid),
    }
    out32 = np.empty(pts32.shape[0], np.float32)
    w2 = _scaling({"one": lambda: run_split(_stream_points, pts32, out32, (), 1),
                   "two": lambda: run_split(_stream_points, pts32, out32, (), 2)}, repeats)
    lines.append(f"| control: read the points, write one float32 each (no noise) | 4e6 points | {w2} |")
    summary[("scaling", "control")] = w2
    for name, (size, noise, x) in calls.items():
        if isinstance(x, Grid):
            def call(w, noise=noise, x=x):
                return fractal_sum(noise, x, 6, dtype=np.float32, workers=w)
        else:
            def call(w, noise=noise, x=x):
                return noise(x, workers=w)
        w2 = _scaling({"one": lambda call=call: call(1), "two": lambda call=call: call(2)}, repeats)
        lines.append(f"| {name} | {size} | {w2} |")
        summary[("scaling", name)] = w2


TARGET_GRID3 = (128, 4)  # 128^3 samples over 4 lattice cells per side: all 6 octaves resolved (the 6th at 1 cell a sample)


def grid3_rows(repeats, lines, fns, summary):
    """3-D grids, one octave and a 6-octave fBm, both hashes, against pyfastnoisesimd's 3-D ``genAsGrid``."""
    n, cells = TARGET_GRID3
    shape = (n, n, n)
    grid = Grid(shape, [(0.0, float(cells))] * 3)
    lines.append(f"\n### {n}^3 grid, {cells} lattice cells per side, one octave and 6-octave fBm\n")
    lines.append("`noise.grid(...)` for one octave, `fractal_sum(noise, Grid, 6)` for six; pyfastnoisesimd's "
                 "`Value`/`Perlin` (`ValueFractal`/`PerlinFractal` for six octaves), `genAsGrid`, float32, 1 worker; "
                 "`w2` as above.\n")
    lines.append("| noise | hash | octaves | f64 pts/s | x FNS | x floor | f32 pts/s | x FNS | x floor | err32 "
                 "| FNS pts/s | w2 wall (cores) |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|")
    size = n ** 3
    for octaves in (1, 6):
        for basis in ("value", "gradient"):
            for hname in ("table", "integer"):
                noise = _hashed(3, "quintic", basis, hname)

                def call(dtype=np.float64, workers=1, noise=noise, octaves=octaves):
                    return fractal_sum(noise, grid, octaves, dtype=dtype, workers=workers)

                cands = {"floor64": lambda: np.full(shape, 0.5), "floor32": lambda: np.full(shape, 0.5, np.float32),
                         "f64": call, "f32": lambda call=call: call(np.float32)}
                if fns is not None:
                    f = _fns_noise(fns, basis, octaves, cells, n)
                    cands["fns"] = lambda f=f: f.genAsGrid(list(shape))
                t = bench(cands, repeats, clock=time.thread_time)
                err32 = _max_err(call(np.float32), call())
                w2 = _scaling({"one": lambda call=call: call(np.float32),
                               "two": lambda call=call: call(np.float32, 2)}, repeats)
                c64, c32 = _target_cell(t, "f64", size, "fns"), _target_cell(t, "f32", size, "fns")
                fns_rate = f"{size / t['fns']:.3g}" if "fns" in t else "n/a"
                lines.append(f"| {n}^3, quintic {basis} | {hname} | {octaves} | {' | '.join(c64)} "
                             f"| {' | '.join(c32)} | {err32:.1e} | {fns_rate} | {w2} |")
                summary[("grid3", octaves, basis, hname)] = (t, err32, w2)


def _splice(path, head, section):
    """Replace the section starting at ``head`` (to the next ``## `` heading) in ``path``, or append it."""
    text = Path(path).read_text() if Path(path).exists() else ""
    if head in text:
        a = text.index(head)
        b = text.find("\n## ", a + 1)
        text = text[:a] + section.rstrip("\n") + "\n" + (text[b:] if b >= 0 else "")
    else:
        text = text.rstrip("\n") + "\n\n" + section
    Path(path).write_text(text)


# ----------------------------------------------------------------------- precision
def precision_section(lines):
    origins = [0.0, 1e6, 1e9, 2.2e9, 1e12]
    nsamp = 4001
    steps = np.linspace(0.0, 4.0, nsamp)  # 4 lattice cells, 0.001-cell steps
    lines.append("## Precision far from the origin\n")
    lines.append("4001 samples along x from the origin over 4 lattice cells (steps of 0.001 cell), y = 0.3, "
                 "z = 0.7 (frequency 1 everywhere). `distinct` = number of distinct output values (4001 for a smooth "
                 "function; few = stair-steps; 1 = constant), `max|v|` = largest magnitude, `max step` = largest "
                 "change between neighbouring samples.\n")
    lines.append("| implementation | " + " | ".join(f"x0 = {o:g}" for o in origins) + " |")
    lines.append("|---|" + "---|" * len(origins))

    def evaluate(fn):
        cells = []
        for o in origins:
            x = o + steps
            try:
                v = np.asarray(fn(x), dtype=np.float64)
                cells.append(f"{np.unique(v).size} / {np.abs(v).max():.3g} / {np.abs(np.diff(v)).max():.2g}")
            except Exception as exc:  # noqa: BLE001
                cells.append(f"error: {type(exc).__name__}")
        return cells

    rows = {}
    for kname, basis in (("cubic", "value"), ("quintic", "value"), ("quintic", "gradient")):
        noise = LatticeNoise(3, rng=1, kernel=kname, basis=basis)
        rows[f"noiselab {basis} {kname} (float64)"] = \
            lambda x, noise=noise: noise(np.stack([x, np.full_like(x, 0.3), np.full_like(x, 0.7)], axis=-1))
    nz = _peer("noise")
    if nz is not None:
        rows["noise.pnoise3"] = lambda x: [nz.pnoise3(float(v), 0.3, 0.7) for v in x]
    fnl = _peer("fnl")
    if fnl is not None:
        for label, nt in (("value", fnl.NoiseType.NoiseType_Value), ("perlin", fnl.NoiseType.NoiseType_Perlin)):
            lite = fnl.FastNoiseLite(1)
            lite.noise_type = nt
            lite.frequency = 1.0
            rows[f"pyfastnoiselite {label}"] = lambda x, lite=lite: lite.gen_from_coords(
                np.ascontiguousarray(np.stack([x, np.full_like(x, 0.3), np.full_like(x, 0.7)]).astype(np.float32)))
    fns = _peer("fns")
    if fns is not None:
        for label, nt in (("value", fns.NoiseType.Value), ("perlin", fns.NoiseType.Perlin)):
            f = fns.Noise(seed=1, numWorkers=1)
            f.noiseType = nt
            f.frequency = 1.0

            def run(x, f=f):
                c = fns.empty_coords(x.size)  # padded to the SIMD width
                c[:] = 0.0
                c[0, : x.size] = x
                c[1, : x.size] = 0.3
                c[2, : x.size] = 0.7
                return f.genFromCoords(c)[: x.size]
            rows[f"pyfastnoisesimd {label}"] = run
    vtk = _peer("vtk")
    if vtk is not None:
        pv = vtk.vtkPerlinNoise()
        rows["VTK vtkPerlinNoise (documented range about +-1)"] = lambda x: [pv.EvaluateFunction(float(v), 0.3, 0.7) for v in x]
    osx = _peer("opensimplex")
    if osx is not None:
        osx.seed(1)
        rows["opensimplex noise3"] = lambda x: [osx.noise3(float(v), 0.3, 0.7) for v in x]
    vn = _peer("vnoise")
    if vn is not None:
        vobj = vn.Noise(1)
        rows["vnoise noise3"] = lambda x: vobj.noise3(x, np.full_like(x, 0.3), np.full_like(x, 0.7), grid_mode=False)
    results = {}
    for name, fn in rows.items():
        cells = evaluate(fn)
        results[name] = cells
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    lines.append("\nEach cell: distinct / max|v| / max step.\n")
    return results


def build_parser():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="cubic and quintic only")
    ap.add_argument("--output", default=str(Path(__file__).with_suffix(".md")))
    ap.add_argument("--hash-only", action="store_true",
                    help="run only the integer-hash section and replace it in the output file (the rest is kept)")
    ap.add_argument("--grid-only", action="store_true",
                    help="run only the 2-D grid section and replace it in the output file (the rest is kept)")
    ap.add_argument("--targets-only", action="store_true",
                    help="run only noiselab's speed targets section (both hashes, pyfastnoisesimd, floor, workers=2) and "
                         "replace it in the output file (the rest is kept)")
    return ap


def _one_section(args, flag, section, head, packages, repeats, *, end_load, rest):
    """Run one section alone and splice it into the report under ``head``, with its own command and load."""
    cmd = (f"benchmarks/.venv-peers/bin/python benchmarks/bench_lattice.py {flag}"
           + (f" --repeats {args.repeats}" if args.repeats != 5 else ""))
    lines = []
    load = os.getloadavg()[0]
    section(repeats, lines)
    info = run_info(cmd, packages, load=load)
    loads = f"load average {load:.1f} at start" + (f" and {os.getloadavg()[0]:.1f} at the end" if end_load else "")
    lines.insert(1, f"Run alone (`{cmd}`), {info['date']}, {info['machine']}, {info['cores']} cores ({info['cpu']}) "
                    f"shared with other jobs, {loads}; " + ", ".join(f"{k} {v}" for k, v in info["versions"].items())
                    + f"; median of {repeats} interleaved rounds. {rest}\n")
    _splice(args.output, head, "\n".join(lines) + "\n")
    print("\n".join(lines))


def main(argv=None):
    args = build_parser().parse_args(argv)
    repeats = max(5, args.repeats)
    if args.grid_only:
        cmd = ("benchmarks/.venv-peers/bin/python benchmarks/bench_lattice.py --grid-only"
               + (" --quick" if args.quick else "") + (f" --repeats {args.repeats}" if args.repeats != 5 else ""))
        lines = []
        load = os.getloadavg()[0]
        info = run_info(cmd, ["pyfastnoisesimd"], load=load)
        gsum = grid_section(repeats, args.quick, lines)
        lines.insert(1, f"Run alone (`{cmd}`), {info['date']}, {info['machine']}, {info['cores']} cores ({info['cpu']}, "
                        f"AVX-512: pyfastnoisesimd runs its AVX-512 path) shared with other jobs, load average "
                        f"{load:.1f} at start and {os.getloadavg()[0]:.1f} at the end; "
                        + ", ".join(f"{k} {v}" for k, v in info["versions"].items()) + f"; median of {repeats} "
                        "interleaved rounds. The rest of this file is from the run in its header. Float64 summary of "
                        "this run:\n\n" + "\n".join(_grid_summary(gsum)) + "\n")
        _splice(args.output, GRID_HEAD, "\n".join(lines) + "\n")
        print("\n".join(lines))
        return
    if args.targets_only:
        return _one_section(args, "--targets-only", targets_section, TARGET_HEAD, ["pyfastnoisesimd", "dask"], repeats,
                            end_load=True, rest="The rest of this file is from the runs named in their sections.")
    if args.hash_only:
        return _one_section(args, "--hash-only", hash_section, HASH_HEAD, ["pyfastnoisesimd"], repeats,
                            end_load=False, rest="The rest of this file is from the run in its header.")
    cmd = ("benchmarks/.venv-peers/bin/python benchmarks/bench_lattice.py" + (" --quick" if args.quick else "")
           + (f" --repeats {args.repeats}" if args.repeats != 5 else ""))
    info = run_info(cmd, ["noise", "pyfastnoiselite", "pyfastnoisesimd", "opensimplex", "vnoise", "perlin-numpy", "vtk"])
    lines = ["# Lattice noise benchmark\n",
             *header_lines(info, timing=f"one thread; median of {repeats} interleaved rounds per table (order rotated "
                           f"each round, `noiselab.lab.measure.interleaved`); ratios: median of the {repeats} per-round "
                           "ratios\n")]
    body = []
    gsum = grid_section(repeats, args.quick, body)
    ssum = scattered_section(repeats, args.quick, body)
    hash_section(repeats, body)
    targets_section(repeats, body)
    precision_section(body)
    lines.append("## Summary (float64 unless stated; ratios > 1 mean noiselab is faster)\n")
    lines += _grid_summary(gsum)
    for kname in ("quintic", "cubic"):
        r = ssum.get((kname, "value"))
        if r:
            fnl_txt = f", {r[1]:.2f}x pyfastnoiselite value noise (float32)" if r[1] else ""
            lines.append(f"- 1e6 scattered 3-D points, value noise, {kname} kernel: {r[0]:.3g} pts/s{fnl_txt} (one thread)")
        r = ssum.get((kname, "value", "two"))
        if r:
            fnl_txt = f", {r[1]:.2f}x pyfastnoiselite (one thread)" if r[1] else ""
            lines.append(f"- the same with `workers=2` (two threads, wall time: see its table): {r[0]:.3g} pts/s{fnl_txt}")
        r = ssum.get((kname, "value", "sixty"))
        if r:
            lines.append(f"- the same, `fractal_sum(noise, pts, 60)` ({r[3]} octaves used): {r[0]:.3g} pts/s, "
                         f"{1 / r[2]:.1f}x the time of one octave")
    lines.append("")
    lines += body
    Path(args.output).write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


def _grid_summary(gsum):
    """The summary's grid lines (float64 output; the like-for-like pyfastnoisesimd noise)."""
    out = []
    for n, cells in GRID_SETTINGS:
        for kname in ("quintic", "cubic"):
            for basis in ("value", "gradient"):
                for key, label in (("one", "one octave"), ("six", "6-octave fractal sum")):
                    r = gsum.get((n, kname, basis, key, "float64"))
                    if r:
                        peer = ("Value" if basis == "value" else "Perlin") + ("Fractal" if key == "six" else "")
                        fns_txt = f", {r[2]:.2f}x pyfastnoisesimd {peer}" if r[2] is not None else ""
                        out.append(f"- 2-D grid {n}^2 ({cells} cells), {basis} noise, {kname}, {label}: {r[0]:.3g} "
                                   f"pts/s ({r[1]:.2f}x the write floor{fns_txt})")
    return out


if __name__ == "__main__":
    main()
