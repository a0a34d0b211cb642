"""Benchmark: ``noiselab.snow`` against its floor, a bare ``scipy.fft.irfftn`` of the same float32 output.

Run from the repository root::

    python3 benchmarks/bench_snow.py            # writes benchmarks/bench_snow.md
    python3 benchmarks/bench_snow.py --quick    # smaller, for a smoke test

Everything is measured side by side in one process, interleaved round by
round, and reported as ratios (median of the per-round ratios), because the
machine is shared. Memory is measured in fresh subprocesses (one per case):
the peak resident set size above the post-import baseline (``VmHWM`` after
resetting it through ``/proc/self/clear_refs``) and the ``tracemalloc`` peak
(numpy arrays only; the FFT library's scratch is not traced).
MotionClouds (a peer, ``benchmarks/.venv-peers``) is measured for reference
when its environment is present.
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import scipy
import scipy.fft

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import noiselab  # noqa: E402
from noiselab.snow import snow  # noqa: E402
from noiselab.snow.render import rescale_opacity  # noqa: E402
from noiselab.snow.tent import assemble, pruned_irfftn, tent_columns  # noqa: E402

PEER_PY = ROOT / "benchmarks" / ".venv-peers" / "bin" / "python"


def _random_half_spectrum(shape, dtype):
    T, H, W = shape
    rng = np.random.default_rng(0)
    cdt = np.complex64 if dtype == np.float32 else np.complex128
    S = np.empty((T, H, W // 2 + 1), cdt)
    S.real = rng.standard_normal(S.shape, dtype=np.float32)
    S.imag = rng.standard_normal(S.shape, dtype=np.float32)
    return S


def timing(shape, rounds):
    """Interleaved rounds: floor (irfftn) and snow, in float32 and float64; ratios per round."""
    S32 = _random_half_spectrum(shape, np.float32)
    S64 = S32.astype(np.complex128)
    snow((4, 32, 32), seed=0)  # numba warm-up
    for f in (lambda: scipy.fft.irfftn(S32, s=shape), lambda: snow(shape, seed=0)):
        f()
    rows = {k: [] for k in ("floor32", "snow32", "floor64", "snow64", "build", "fft", "rescale")}
    for r in range(rounds):
        t0 = time.perf_counter(); y = scipy.fft.irfftn(S32, s=shape); t1 = time.perf_counter()  # noqa: E702
        assert y.dtype == np.float32
        del y
        t2 = time.perf_counter(); a = snow(shape, seed=r); t3 = time.perf_counter()  # noqa: E702
        del a
        t4 = time.perf_counter(); y = scipy.fft.irfftn(S64, s=shape); t5 = time.perf_counter()  # noqa: E702
        del y
        t6 = time.perf_counter(); a = snow(shape, seed=r, dtype=np.float64); t7 = time.perf_counter()  # noqa: E702
        del a
        # the stages of snow (float32)
        s0 = time.perf_counter()
        cols = tent_columns(shape, c=1.0, band=(shape[2] / 32, shape[2] / 4), thickness=0.1, direction=(0, 1),
                            pan=(0, 0), exponent=1.0)
        C = assemble(cols, np.random.default_rng(r), "uniform", np.float32)
        s1 = time.perf_counter()
        out = np.empty(shape, np.float32)
        lo, hi = pruned_irfftn(C, cols, out)
        s2 = time.perf_counter()
        rescale_opacity(out, 1.5, lo=lo, hi=hi)
        s3 = time.perf_counter()
        del out, C
        for k, v in (("floor32", t1 - t0), ("snow32", t3 - t2), ("floor64", t5 - t4), ("snow64", t7 - t6),
                     ("build", s1 - s0), ("fft", s2 - s1), ("rescale", s3 - s2)):
            rows[k].append(v)
    rows = {k: np.array(v) for k, v in rows.items()}
    return {
        "floor32_s": float(np.median(rows["floor32"])),
        "snow32_s": float(np.median(rows["snow32"])),
        "floor64_s": float(np.median(rows["floor64"])),
        "snow64_s": float(np.median(rows["snow64"])),
        "ratio32": float(np.median(rows["snow32"] / rows["floor32"])),
        "ratio64": float(np.median(rows["snow64"] / rows["floor64"])),
        "ratio64_vs_floor32": float(np.median(rows["snow64"] / rows["floor32"])),
        "build_frac": float(np.median(rows["build"] / rows["floor32"])),
        "fft_frac": float(np.median(rows["fft"] / rows["floor32"])),
        "rescale_frac": float(np.median(rows["rescale"] / rows["floor32"])),
        "ratios32": [round(float(x), 3) for x in rows["snow32"] / rows["floor32"]],
        "cells": int(cols.n_cells),
        "columns": int(cols.ky.size),
        "half_spectrum": int(shape[0] * shape[1] * (shape[2] // 2 + 1)),
    }


def _status_kb(field):
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return 0


def memory_case(case, shape):
    """Run in a fresh subprocess: peak RSS and tracemalloc peak of one case, above the post-import baseline."""
    import tracemalloc

    snow((4, 32, 32), seed=0)
    if case.startswith("floor"):
        dt = np.float32 if case == "floor32" else np.float64
        S = _random_half_spectrum(shape, dt)
        if dt == np.float64:
            S = S.astype(np.complex128)
        scipy.fft.irfftn(S[:1, :8, :5], s=(1, 8, 8))
        run = lambda: scipy.fft.irfftn(S, s=shape)  # noqa: E731
    else:
        dt = np.float32 if case == "snow32" else np.float64
        run = lambda: snow(shape, seed=0, dtype=dt)  # noqa: E731
    try:
        with open("/proc/self/clear_refs", "w") as fh:
            fh.write("5")  # reset VmHWM to the current RSS
        reset = True
    except OSError:
        reset = False
    base = _status_kb("VmRSS")
    tracemalloc.start()
    out = run()
    _, traced = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    hwm = _status_kb("VmHWM")
    assert out.dtype == dt
    return {"rss_peak_mib": (hwm - base) / 1024, "traced_peak_mib": traced / 2**20, "hwm_reset": reset,
            "output_mib": out.nbytes / 2**20}


def memory(shape):
    res = {}
    for case in ("floor32", "snow32", "floor64", "snow64"):
        proc = subprocess.run([sys.executable, __file__, "--memory-case", case, "--shape", *map(str, shape)],
                              capture_output=True, text=True, cwd=ROOT)
        if proc.returncode != 0:
            raise RuntimeError(proc.stderr)
        res[case] = json.loads(proc.stdout.strip().splitlines()[-1])
    return res


def accuracy(shape):
    a32 = snow(shape, seed=0)
    a64 = snow(shape, seed=0, dtype=np.float64)
    d = np.abs(a32.astype(np.float64) - a64)
    return {"max_abs_diff": float(d.max()), "mean_abs_diff": float(d.mean())}


PEER_SCRIPT = r"""
import json, time, sys, numpy as np, scipy.fft
import MotionClouds as mc
T, H, W = map(int, sys.argv[1:4]); rounds = int(sys.argv[4])
S = (np.random.default_rng(0).standard_normal((T, H, W // 2 + 1)) + 0j).astype(np.complex64)
def mc_run():
    fx, fy, ft = mc.get_grids(W, H, T)
    env = mc.envelope_gabor(fx, fy, ft, V_X=0., V_Y=1.)
    return mc.rectif(mc.random_cloud(env))
mc_run(); scipy.fft.irfftn(S, s=(T, H, W))
r = []
for _ in range(rounds):
    t0 = time.perf_counter(); scipy.fft.irfftn(S, s=(T, H, W)); t1 = time.perf_counter()
    m = mc_run(); t2 = time.perf_counter()
    r.append((t2 - t1) / (t1 - t0))
import resource
print(json.dumps({"ratio": float(np.median(r)), "maxrss_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                  "version": __import__("importlib.metadata").metadata.version("MotionClouds")}))
"""


def peer(shape, rounds):
    if not PEER_PY.exists():
        return None
    proc = subprocess.run([str(PEER_PY), "-c", PEER_SCRIPT, *map(str, shape), str(rounds)],
                          capture_output=True, text=True, cwd="/tmp")
    if proc.returncode != 0:
        return {"error": proc.stderr.strip().splitlines()[-1] if proc.stderr.strip() else "failed"}
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--rounds", type=int, default=9)
    ap.add_argument("--memory-case", default=None)
    ap.add_argument("--shape", type=int, nargs=3, default=None)
    ap.add_argument("--no-peer", action="store_true")
    args = ap.parse_args()
    shape = tuple(args.shape) if args.shape else ((16, 128, 128) if args.quick else (64, 512, 512))
    if args.memory_case:
        print(json.dumps(memory_case(args.memory_case, shape)))
        return
    rounds = 5 if args.quick else max(5, args.rounds)
    tm = timing(shape, rounds)
    mem = memory(shape)
    acc = accuracy(shape)
    pr = None if args.no_peer else peer(shape, 5)
    cmd = "python3 benchmarks/bench_snow.py" + (" --quick" if args.quick else "")
    T, H, W = shape
    out_mib = T * H * W * 4 / 2**20
    lines = [
        "# bench_snow: falling snow against the inverse-FFT floor",
        "",
        f"- command: `{cmd}`",
        f"- date: {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M UTC}",
        f"- machine: {platform.machine()}, {os.cpu_count()} cores (shared with other jobs), {platform.platform()}",
        f"- versions: python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}, "
        f"noiselab {noiselab.__version__}",
        f"- shape (T, H, W) = {shape}, default scene (band {W / 32:g}..{W / 4:g} cycles/frame, c = 1, "
        f"thickness 0.1, beta 1.5); single-threaded FFTs on both sides",
        f"- timing: {rounds} interleaved rounds, median of per-round ratios",
        "",
        "## Speed (floor = bare `scipy.fft.irfftn` of a `(T, H, W//2+1)` spectrum to the same output)",
        "",
        "| case | median time (s) | ratio to its floor |",
        "| --- | --- | --- |",
        f"| floor float32 (complex64 -> float32) | {tm['floor32_s']:.3f} | 1 |",
        f"| `snow` float32 | {tm['snow32_s']:.3f} | **{tm['ratio32']:.2f}** |",
        f"| floor float64 (complex128 -> float64) | {tm['floor64_s']:.3f} | 1 |",
        f"| `snow` float64 | {tm['snow64_s']:.3f} | {tm['ratio64']:.2f} ({tm['ratio64_vs_floor32']:.2f} x the float32 floor) |",
        "",
        f"Per-round float32 ratios: {tm['ratios32']}. Target: at most 1.2.",
        "",
        "Stages of `snow` (float32), as fractions of the float32 floor:",
        f"spectrum build (sparse tent cells + random draws) {tm['build_frac']:.3f}, "
        f"pruned inverse FFT {tm['fft_frac']:.3f}, rescale + `alpha**1.5` {tm['rescale_frac']:.3f}.",
        "",
        f"What is exploited: {tm['cells']:,} of the {tm['half_spectrum']:,} half-spectrum cells carry energy "
        f"({100 * tm['cells'] / tm['half_spectrum']:.2f} %), in {tm['columns']:,} spatial columns; the spectrum is "
        "built on those cells only, the inverse FFT along t runs on those columns only, along y on the "
        "`kx <= band[1]` columns only, and only the last pass (complex-to-real along x) is full size, written into the "
        "output a few frames at a time (the min/max for the rescale is taken while each chunk is in cache).",
        "",
        f"## Memory (output: {out_mib:.0f} MiB float32; measured in a fresh subprocess per case)",
        "",
        "| case | peak RSS above baseline (MiB) | x float32 output | tracemalloc peak (MiB) |",
        "| --- | --- | --- | --- |",
    ]
    for case, name in (("floor32", "floor float32 (input spectrum not counted)"), ("snow32", "`snow` float32"),
                       ("floor64", "floor float64 (input spectrum not counted)"), ("snow64", "`snow` float64")):
        m = mem[case]
        lines.append(f"| {name} | {m['rss_peak_mib']:.0f} | {m['rss_peak_mib'] / out_mib:.2f} | "
                     f"{m['traced_peak_mib']:.0f} |")
    lines += [
        "",
        "Target: `snow` float32 at most 2.5 x the float32 output.",
        "",
        "## float32 against float64 (same seed)",
        "",
        f"Largest |alpha32 - alpha64| = {acc['max_abs_diff']:.2e}, mean {acc['mean_abs_diff']:.2e} "
        f"(alpha in [0, 1]; one 8-bit grey level is {1 / 255:.2e}).",
        "",
    ]
    if pr is not None:
        lines += ["## Peer, for reference", ""]
        if "error" in pr:
            lines.append(f"MotionClouds could not be measured: {pr['error']}")
        else:
            lines.append(
                f"MotionClouds {pr['version']} (`get_grids` + `envelope_gabor` + `random_cloud` + `rectif`, "
                f"same shape, in `benchmarks/.venv-peers`): {pr['ratio']:.1f} x a bare `irfftn` in its own process; "
                f"its process peaked at {pr['maxrss_mib']:.0f} MiB RSS (ru_maxrss, whole process).")
        lines.append("")
    text = "\n".join(lines)
    (ROOT / "benchmarks" / ("bench_snow.md" if not args.quick else "bench_snow_quick.md")).write_text(text)
    print(text)


if __name__ == "__main__":
    main()
