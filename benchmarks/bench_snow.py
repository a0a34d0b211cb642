"""Benchmark: ``noiselab.snow`` against its floor, a bare ``scipy.fft.irfftn`` of the same float32 output.

Run from the repository root::

    python3 benchmarks/bench_snow.py            # writes benchmarks/bench_snow.md
    python3 benchmarks/bench_snow.py --quick    # smaller, for a smoke test
    python3 benchmarks/bench_snow.py --baseline /work/main --no-memory --no-peer --append
        # also times snow from another checkout side by side (before/after), appends a dated section

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
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import scipy
import scipy.fft

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from noiselab.snowfall import snow  # noqa: E402
from noiselab.snowfall.render import rescale_opacity  # noqa: E402
from noiselab.lab.measure import Laps, Stopwatch, header_lines, interleaved, load_average, run_info  # noqa: E402
from noiselab.snowfall.tent import assemble, pruned_irfftn, tent_columns  # noqa: E402

PEER_PY = ROOT / "benchmarks" / ".venv-peers" / "bin" / "python"


def _random_half_spectrum(shape, dtype):
    T, H, W = shape
    rng = np.random.default_rng(0)
    cdt = np.complex64 if dtype == np.float32 else np.complex128
    S = np.empty((T, H, W // 2 + 1), cdt)
    S.real = rng.standard_normal(S.shape, dtype=np.float32)
    S.imag = rng.standard_normal(S.shape, dtype=np.float32)
    return S


def load_baseline(path):
    """``snow`` of the noiselab tree under ``path`` (another checkout), imported beside this one as ``noiselab_base``.

    The package is loaded from its own files under a module name of its own
    (its modules import each other relatively; numba caches its kernels by
    their files), so both trees are timed in one process.
    """
    import importlib
    import importlib.util

    pkg = Path(path).resolve() / "noiselab"
    spec = importlib.util.spec_from_file_location("noiselab_base", pkg / "__init__.py",
                                                  submodule_search_locations=[str(pkg)])
    mod = importlib.util.module_from_spec(spec)
    sys.modules["noiselab_base"] = mod
    spec.loader.exec_module(mod)
    base = importlib.import_module("noiselab_base.snowfall").snow
    assert Path(sys.modules[base.__module__].__file__).resolve().is_relative_to(pkg)
    return base


def timing(shape, rounds, workers, base=None, timer=None):
    """Interleaved rounds: floor (irfftn) and snow, float32 and float64, at each worker count; ratios per round.

    One :func:`noiselab.lab.measure.interleaved` call over every (case, worker count), the order reversed every
    other round; the stages of ``snow`` (float32) are one more candidate that returns their laps.
    """
    S32 = _random_half_spectrum(shape, np.float32)
    S64 = S32.astype(np.complex128)
    snow((4, 32, 32), rng=0)  # numba warm-up
    band = (shape[2] / 32, shape[2] / 4)

    def stages(r, w):
        sw = Stopwatch()
        cols = sw("build", lambda: tent_columns(shape, c=1.0, band=band, thickness=0.1, direction=(0, 1), pan=(0, 0),
                                                exponent=1.0))
        spec = sw("build", lambda: assemble(cols, np.random.default_rng(r), "uniform", np.float32))
        out = np.empty(shape, np.float32)
        lo, hi = sw("fft", lambda: pruned_irfftn(spec, cols, out, workers=w))
        sw("rescale", lambda: rescale_opacity(out, 1.5, lo=lo, hi=hi))
        return Laps({f"{k}@{w}": v for k, v in sw.laps.items()})

    def floor(S, w):
        y = scipy.fft.irfftn(S, s=shape, workers=w)
        assert y.dtype == (np.float32 if S.dtype == np.complex64 else np.float64)
        return y

    cands = {}
    for w in workers:
        cands.update({f"floor32@{w}": lambda r, w=w: floor(S32, w),
                      f"snow32@{w}": lambda r, w=w: snow(shape, rng=max(r, 0), workers=w),
                      f"floor64@{w}": lambda r, w=w: floor(S64, w),
                      f"snow64@{w}": lambda r, w=w: snow(shape, rng=max(r, 0), dtype=np.float64, workers=w),
                      f"stages@{w}": lambda r, w=w: stages(max(r, 0), w)})
        if base is not None:
            cands[f"base32@{w}"] = lambda r, w=w: base(shape, rng=max(r, 0), workers=w)
    if base is not None:
        base((4, 32, 32), rng=0)  # numba warm-up of the baseline tree
    t = interleaved(cands, repeats=rounds, order="alternate", round_arg=True, timer=timer)
    res = {"timings": t}
    w0 = workers[0]
    for w in workers:
        res[w] = {
            "floor32_s": t[f"floor32@{w}"],
            "snow32_s": t[f"snow32@{w}"],
            "floor64_s": t[f"floor64@{w}"],
            "snow64_s": t[f"snow64@{w}"],
            "ratio32": t.ratio(f"snow32@{w}", f"floor32@{w}"),
            "ratio64": t.ratio(f"snow64@{w}", f"floor64@{w}"),
            "ratio64_vs_floor32": t.ratio(f"snow64@{w}", f"floor32@{w}"),
            "build_frac": t.ratio(f"build@{w}", f"floor32@{w}"),
            "fft_frac": t.ratio(f"fft@{w}", f"floor32@{w}"),
            "rescale_frac": t.ratio(f"rescale@{w}", f"floor32@{w}"),
            "ratios32": [round(float(x), 3) for x in t.ratios(f"snow32@{w}", f"floor32@{w}")],
            # strong scaling against the first worker count, per round
            "speedup_floor32": t.ratio(f"floor32@{w0}", f"floor32@{w}"),
            "speedup_snow32": t.ratio(f"snow32@{w0}", f"snow32@{w}"),
        }
        if base is not None:
            res[w].update({"base32_s": t[f"base32@{w}"], "base_ratio32": t.ratio(f"base32@{w}", f"floor32@{w}"),
                           "snow_vs_base": t.ratio(f"snow32@{w}", f"base32@{w}"),
                           "base_ratios32": [round(float(x), 3) for x in t.ratios(f"base32@{w}", f"floor32@{w}")]})
    cols = tent_columns(shape, c=1.0, band=band, thickness=0.1, direction=(0, 1), pan=(0, 0), exponent=1.0)
    res["cells"] = int(cols.n_cells)
    res["columns"] = int(cols.ky.size)
    res["half_spectrum"] = int(shape[0] * shape[1] * (shape[2] // 2 + 1))
    return res


def _parallel_fraction(speedup, n_from, n_to):
    """Amdahl's parallel fraction implied by ``speedup`` going from ``n_from`` to ``n_to`` workers."""
    r = n_to / n_from
    return float("nan") if r == 1 else (1 - 1 / speedup) / (1 - 1 / r)


def _status_kb(field):
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return 0


def memory_case(case, shape, workers=1):
    """Run in a fresh subprocess: peak RSS and tracemalloc peak of one case, above the post-import baseline."""
    import tracemalloc

    snow((4, 32, 32), rng=0)
    if case.startswith("floor"):
        dt = np.float32 if case == "floor32" else np.float64
        S = _random_half_spectrum(shape, dt)
        if dt == np.float64:
            S = S.astype(np.complex128)
        scipy.fft.irfftn(S[:1, :8, :5], s=(1, 8, 8))
        run = lambda: scipy.fft.irfftn(S, s=shape, workers=workers)  # noqa: E731
    else:
        dt = np.float32 if case == "snow32" else np.float64
        snow((4, 32, 32), rng=0, workers=workers)
        run = lambda: snow(shape, rng=0, dtype=dt, workers=workers)  # noqa: E731
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


def memory(shape, workers):
    res = {}
    for w in workers:
        for case in ("floor32", "snow32", "floor64", "snow64"):
            proc = subprocess.run([sys.executable, __file__, "--memory-case", case, "--shape", *map(str, shape),
                                   "--workers", str(w)], capture_output=True, text=True, cwd=ROOT)
            if proc.returncode != 0:
                raise RuntimeError(proc.stderr)
            res[(case, w)] = json.loads(proc.stdout.strip().splitlines()[-1])
    return res


def accuracy(shape):
    a32 = snow(shape, rng=0)
    a64 = snow(shape, rng=0, dtype=np.float64)
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


def build_parser():
    """The command line (``--quick``, ``--rounds``, ``--shape``, ``--workers``, ``--no-peer``; ``--memory-case`` is internal)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--rounds", type=int, default=9)
    ap.add_argument("--memory-case", default=None)
    ap.add_argument("--shape", type=int, nargs=3, default=None)
    ap.add_argument("--no-peer", action="store_true")
    ap.add_argument("--workers", type=int, nargs="+", default=None,
                    help="worker counts, the same on both sides (default: 1 and every core)")
    ap.add_argument("--baseline", default=None,
                    help="another noiselab checkout (e.g. `git worktree add /tmp/base main`): its snow float32 is "
                         "timed in the same rounds (before/after in one process)")
    ap.add_argument("--cpu", action="store_true", help="time CPU (time.process_time) instead of the wall clock")
    ap.add_argument("--no-memory", action="store_true", help="skip the memory subprocesses (and their table)")
    ap.add_argument("--append", action="store_true",
                    help="append the report to bench_snow.md as a dated section instead of replacing the file")
    return ap


def main(argv=None):
    args = build_parser().parse_args(argv)
    workers = args.workers or [1, os.cpu_count() or 1]
    shape = tuple(args.shape) if args.shape else ((16, 128, 128) if args.quick else (64, 512, 512))
    if args.memory_case:
        print(json.dumps(memory_case(args.memory_case, shape, workers[0])))
        return
    rounds = 5 if args.quick else max(5, args.rounds)
    load0 = load_average()
    base = load_baseline(args.baseline) if args.baseline else None
    tm = timing(shape, rounds, workers, base, time.process_time if args.cpu else None)
    load1 = load_average()
    mem = None if args.no_memory else memory(shape, workers)
    acc = accuracy(shape)
    pr = None if args.no_peer else peer(shape, 5)
    cmd = "python3 benchmarks/bench_snow.py" + (" --quick" if args.quick else "") + (
        f" --rounds {args.rounds}" if args.rounds != 9 else "") + (
        " --workers " + " ".join(map(str, args.workers)) if args.workers else "") + (
        " --shape " + " ".join(map(str, args.shape)) if args.shape else "") + (" --no-peer" if args.no_peer else "") + (
        f" --baseline {args.baseline}" if args.baseline else "") + (" --cpu" if args.cpu else "") + (
        " --no-memory" if args.no_memory else "") + (" --append" if args.append else "")
    T, H, W = shape
    out_mib = T * H * W * 4 / 2**20
    lines = [
        "# bench_snow: falling snow against the inverse-FFT floor",
        "",
        *header_lines(run_info(cmd, ["scipy", "noiselab"], load=load0)),
        f"- shape (T, H, W) = {shape}, default scene (band {W / 32:g}..{W / 4:g} cycles/frame, c = 1, "
        f"thickness 0.1, beta 1.5); the same worker count on both sides (scipy.fft `workers=`; snow's `workers=`)",
        f"- timing: {rounds} interleaved rounds after one warm-up round (`noiselab.lab.measure.interleaved`, the order "
        f"reversed every other round), median of per-round ratios; load average (1 min) "
        f"{load0:.1f} before and {load1:.1f} after the timing, on {os.cpu_count()} cores",
        "",
        "## Speed (floor = bare `scipy.fft.irfftn` of a `(T, H, W//2+1)` spectrum to the same output, same workers)",
        "",
        f"- clock: {'CPU time of this process (`time.process_time`)' if args.cpu else 'wall clock'}",
        "",
        "| workers | case | median time (s) | ratio to its floor |",
        "| --- | --- | --- | --- |",
    ]
    for w in workers:
        t = tm[w]
        lines += [
            f"| {w} | floor float32 (complex64 -> float32) | {t['floor32_s']:.3f} | 1 |",
            f"| {w} | `snow` float32 | {t['snow32_s']:.3f} | **{t['ratio32']:.2f}** |",
            f"| {w} | floor float64 (complex128 -> float64) | {t['floor64_s']:.3f} | 1 |",
            f"| {w} | `snow` float64 | {t['snow64_s']:.3f} | {t['ratio64']:.2f} "
            f"({t['ratio64_vs_floor32']:.2f} x the float32 floor) |",
        ]
        if base is not None:
            lines.append(f"| {w} | `snow` float32 of the baseline tree ({args.baseline}) | {t['base32_s']:.3f} | "
                         f"{t['base_ratio32']:.2f} (this tree: {t['snow_vs_base']:.2f} x the baseline's time) |")
    lines += ["", "Target: `snow` float32 at most 0.6 x the floor at every worker count.", ""]
    for w in workers:
        t = tm[w]
        lines += [f"{w} worker(s): per-round float32 ratios {t['ratios32']}; stages of `snow` (float32) as fractions "
                  f"of the float32 floor: spectrum build (sparse tent cells + random draws, one thread) "
                  f"{t['build_frac']:.3f}, pruned inverse FFT {t['fft_frac']:.3f}, rescale + `alpha**1.5` "
                  f"{t['rescale_frac']:.3f}." + (f" Baseline tree's per-round float32 ratios {t['base_ratios32']}."
                                                 if base is not None else ""), ""]
    if len(workers) > 1:
        base = workers[0]
        lines += ["## Strong scaling (float32)", "",
                  f"Speed-up = median over rounds of (time at {base} / time at n workers), same round; p = Amdahl's "
                  "parallel fraction it implies (`speedup = 1 / ((1 - p) + p / n)`). The machine is shared with "
                  "other jobs: a busy second core lowers both sides.", "",
                  "| workers | floor speed-up (p) | `snow` speed-up (p) |", "| --- | --- | --- |"]
        for w in workers[1:]:
            t = tm[w]
            lines.append(f"| {base} -> {w} | {t['speedup_floor32']:.2f} "
                         f"({_parallel_fraction(t['speedup_floor32'], base, w):.2f}) | {t['speedup_snow32']:.2f} "
                         f"({_parallel_fraction(t['speedup_snow32'], base, w):.2f}) |")
        t1 = tm[base]
        serial = t1["build_frac"] / t1["ratio32"]
        lines += ["", f"From the {base}-worker profile instead (robust to the load): the spectrum build (sparse tent "
                  f"cells + random draws) is the only serial stage, {100 * serial:.0f} % of `snow`'s time; every other "
                  f"stage runs on the workers, so p <= {1 - serial:.2f} (Amdahl's bound on 2 workers: "
                  f"{1 / (serial + (1 - serial) / 2):.2f} x).", ""]
    tm1 = tm
    lines += [
        f"What is exploited: {tm1['cells']:,} of the {tm1['half_spectrum']:,} half-spectrum cells carry energy "
        f"({100 * tm1['cells'] / tm1['half_spectrum']:.2f} %), in {tm1['columns']:,} spatial columns; the spectrum is "
        "built on those cells only; for each block of frames the inverse DFT along t is a direct sum over each "
        "column's few bins, scattered to the block's cells, transformed along y on the `kx <= band[1]` columns only "
        "and along x (the only full-size pass, complex-to-real, from a zero-padded block kept per thread) straight "
        "into the output, the blocks shared among the workers (the min/max for the rescale is taken while each slab "
        "of rows is in cache).",
        "",
    ]
    if mem is not None:
        lines += [f"## Memory (output: {out_mib:.0f} MiB float32; measured in a fresh subprocess per case)", "",
                  "| workers | case | peak RSS above baseline (MiB) | x float32 output | tracemalloc peak (MiB) | "
                  "x output |", "| --- | --- | --- | --- | --- | --- |"]
    for w in (workers if mem is not None else []):
        for case, name in (("floor32", "floor float32 (input spectrum not counted)"), ("snow32", "`snow` float32"),
                           ("floor64", "floor float64 (input spectrum not counted)"), ("snow64", "`snow` float64")):
            m = mem[(case, w)]
            lines.append(f"| {w} | {name} | {m['rss_peak_mib']:.0f} | {m['rss_peak_mib'] / out_mib:.2f} | "
                         f"{m['traced_peak_mib']:.0f} | {m['traced_peak_mib'] / out_mib:.2f} |")
    if mem is not None:
        lines += ["", "Target: `snow` float32 at most 1.27 x the float32 output (tracemalloc), at every worker count."]
    lines += [
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
    md = ROOT / "benchmarks" / ("bench_snow.md" if not args.quick else "bench_snow_quick.md")
    if args.append:  # a dated section after the earlier records: its headings one level down
        lines = [("#" + ln if ln.startswith("#") else ln) for ln in lines]
        lines[0] = f"## bench_snow run of {time.strftime('%Y-%m-%d %H:%M', time.gmtime())} UTC"
        text = (md.read_text().rstrip("\n") + "\n\n" if md.exists() else "") + "\n".join(lines)
    else:
        text = "\n".join(lines)
    md.write_text(text)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
