"""Benchmark: ``spectral_noise`` and ``snow`` against a bare ``irfftn``, CPU time and wall time side by side.

Run from the repository root::

    python3 benchmarks/bench_spectral_floor.py                       # workers 1 and 2; appends to bench_spectral.md
    python3 benchmarks/bench_spectral_floor.py --workers 1 2 4 8 16  # a bigger machine
    python3 benchmarks/bench_spectral_floor.py --no-write --rounds 5
    python3 benchmarks/bench_spectral_floor.py --only spectral --before 1accfe0  # that revision's fill beside

Floor: ``scipy.fft.irfftn`` of a ready half spectrum (complex64) to the same
float32 output, with the same ``workers``. Every (case, worker count,
candidate) runs once per round in one process, in an order rotated each
round (``noiselab.lab.measure.interleaved``), timed twice: by the wall clock
and by this process's CPU time (``time.process_time``, all threads), which
other jobs on a shared machine do not inflate. Reported: the median of the
per-round ratios to the floor in the same round. A third column splits one
``spectral_noise`` call (one worker, medians) into the plan (Python
bookkeeping), the spectrum fill (draws, law, band, row power), the gain
(Hermitian planes, scaling) and the inverse FFT. ``--before REV`` adds
``spectral_noise`` with the spectral synthesis and kernels of that git
revision (``bench_spectral._before_module``) as a third candidate in the same
rounds, and its fill time in the stage split.
The snow section appends to ``bench_snow.md``: the same timings for
``snow((64, 512, 512))`` and its peak memory (the ``tracemalloc`` peak, and
the peak RSS growth in a fresh subprocess, against the float32 output).
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import scipy.fft

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from noiselab.lab.measure import Stopwatch, header_lines, interleaved, load_average, run_info  # noqa: E402
from noiselab.snowfall import snow  # noqa: E402
from noiselab.spectral import spectral_noise  # noqa: E402

SPECTRAL = [(1024, 1024), (128, 128, 128), (4096, 4096)]
SMALL = [(64, 64), (256, 256), (32, 32, 32)]  # --small: where the Python bookkeeping shows
SNOW = (64, 512, 512)


def _half(shape, dtype=np.float32):
    rng = np.random.default_rng(0)
    h = shape[:-1] + (shape[-1] // 2 + 1,)
    S = np.empty(h, np.complex64 if np.dtype(dtype) == np.float32 else np.complex128)
    S.real = rng.standard_normal(h, dtype=np.float32)
    S.imag = rng.standard_normal(h, dtype=np.float32)
    return S


def _both_clocks(cands, rounds):
    """Interleaved rounds of ``cands`` timed by the wall clock and by process CPU time: (wall, cpu) Timings."""
    wall = interleaved(cands, repeats=rounds, round_arg=True)
    cpu = interleaved(cands, repeats=rounds, round_arg=True, timer=time.process_time)
    return wall, cpu


def stages(shape, rounds, SY=None, dtype=np.float32):
    """Medians (ms, one worker) of one ``spectral_noise`` call's stages: plan, fill, gain + scaling, FFT.

    Since the synthesis in place, the scaling is part of the FFT's last pass and "gain" is the Hermitian planes.

    ``SY``: the synthesis module to split (default: the current one).
    """
    import noiselab.spectral.plan as PL
    if SY is None:
        import noiselab.spectral.synthesis as SY

    # the inverse FFT: the in-place passes (with the scaling folded into the last), or a revision's pruned irfftn
    fft_name = "_inverse_in_place" if hasattr(SY, "_inverse_in_place") else "_pruned_irfftn"
    orig = (SY.noise_plan, SY.map_blocks, SY.hermitian_gain, getattr(SY, fft_name))

    def one(r):
        sw = Stopwatch(time.process_time)
        calls = {"n": 0}

        def blocks(*a, **k):  # the first map_blocks is the fill, the second the scaling
            calls["n"] += 1
            return sw("fill" if calls["n"] == 1 else "gain", lambda: orig[1](*a, **k))

        SY.noise_plan = lambda *a, **k: sw("plan", lambda: orig[0](*a, **k))
        SY.map_blocks = blocks
        SY.hermitian_gain = lambda *a, **k: sw("gain", lambda: orig[2](*a, **k))
        setattr(SY, fft_name, lambda *a, **k: sw("fft", lambda: orig[3](*a, **k)))
        try:
            sw("call", lambda: SY.spectral_noise(shape, rng=max(r, 0), workers=1, dtype=dtype))
        finally:
            SY.noise_plan, SY.map_blocks, SY.hermitian_gain = orig[:3]
            setattr(SY, fft_name, orig[3])
        return sw.laps

    assert PL  # the plan module is where noise_plan lives; synthesis imports it by name
    t = interleaved({"one": one}, repeats=rounds, round_arg=True, timer=time.process_time)
    return {k: 1e3 * t[k] for k in ("plan", "fill", "gain", "fft", "call")}


def _peak_x_output(f):
    """The ``tracemalloc`` peak of one call of ``f`` over the size of what it returns."""
    from noiselab.lab.measure import peak_memory

    nbytes = []
    peak = peak_memory(lambda: nbytes.append(f().nbytes))
    return peak / nbytes[0]


def spectral(workers, rounds, before=None, dtypes=("float32",), shapes=SPECTRAL):
    for dt in dtypes:
        spectral_noise((8, 8), rng=0, dtype=dt)
        if before is not None:
            before.spectral_noise((8, 8), rng=0, dtype=dt)
    out = []
    for shape, dt in [(s, d) for d in dtypes for s in shapes]:
        S = _half(shape, dt)
        cands = {}
        for w in workers:
            cands[("floor", w)] = lambda r, w=w, S=S, shape=shape: scipy.fft.irfftn(S, s=shape, workers=w)
            cands[("spectral_noise", w)] = lambda r, w=w, shape=shape, dt=dt: spectral_noise(
                shape, rng=max(r, 0), workers=w, dtype=dt)
            if before is not None:
                cands[("before", w)] = lambda r, w=w, shape=shape, dt=dt: before.spectral_noise(
                    shape, rng=max(r, 0), workers=w, dtype=dt)
        wall, cpu = _both_clocks(cands, rounds)
        st = stages(shape, rounds, dtype=dt)
        st_before = stages(shape, rounds, before, dtype=dt) if before is not None else None
        peak = _peak_x_output(lambda: spectral_noise(shape, rng=0, workers=workers[-1], dtype=dt))
        peak_before = (_peak_x_output(lambda: before.spectral_noise(shape, rng=0, workers=workers[-1], dtype=dt))
                       if before is not None else None)
        for w in workers:
            extra = {} if before is None else {
                "before_cpu": cpu.ratio(("before", w), ("floor", w)),
                "before_wall": wall.ratio(("before", w), ("floor", w)),
                "before_fill": st_before["fill"], "before_peak": peak_before}
            out.append({**extra, "shape": shape, "dtype": np.dtype(dt).name, "peak": peak, "workers": w,
                        "floor_wall_ms": 1e3 * wall[("floor", w)],
                        "floor_cpu_ms": 1e3 * cpu[("floor", w)],
                        "wall": wall.ratio(("spectral_noise", w), ("floor", w)),
                        "cpu": cpu.ratio(("spectral_noise", w), ("floor", w)),
                        "cores_floor": cpu[("floor", w)] / wall[("floor", w)],
                        "cores_sn": cpu[("spectral_noise", w)] / wall[("spectral_noise", w)], "stages": st})
    return out


def last_pass_sweep(workers, rounds):
    """CPU ms of the in-place synthesis's last pass (``irfft`` of blocks of rows, scaled into the front) per block size.

    1024 x 1024 float32, full band: the ``(1024, 513)`` complex rows turned into samples ``rows`` at a time,
    each block's samples copied into a float32 output (as ``synthesis._inverse_in_place`` does).
    """
    n = 1024
    S = _half((n, n))
    out = np.empty((n, n), np.float32)
    blocks = (1024, 256, 64, 32, 16, 8)

    def run(rows, w):
        for r0 in range(0, n, rows):
            x = scipy.fft.irfft(S[r0:r0 + rows], n=n, axis=-1, workers=w)
            out[r0:r0 + rows] = x
            del x

    cands = {(b, w): (lambda b=b, w=w: run(b, w)) for b in blocks for w in workers}
    t = interleaved(cands, repeats=rounds, timer=time.process_time)
    return [(b, [1e3 * t[(b, w)] for w in workers]) for b in blocks]


def snow_timing(workers, rounds):
    snow((4, 32, 32), rng=0)
    S = _half(SNOW)
    cands = {}
    for w in workers:
        cands[("floor", w)] = lambda r, w=w: scipy.fft.irfftn(S, s=SNOW, workers=w)
        cands[("snow", w)] = lambda r, w=w: snow(SNOW, rng=max(r, 0), workers=w)
    wall, cpu = _both_clocks(cands, rounds)
    return [{"workers": w, "floor_wall_ms": 1e3 * wall[("floor", w)], "floor_cpu_ms": 1e3 * cpu[("floor", w)],
             "wall": wall.ratio(("snow", w), ("floor", w)), "cpu": cpu.ratio(("snow", w), ("floor", w))}
            for w in workers]


def snow_memory(workers):
    """Per worker count: the tracemalloc peak (this process) and the peak RSS growth (a fresh subprocess), MiB."""
    from noiselab.lab.measure import peak_memory, peak_rss

    S = _half(SNOW)
    res = {}
    for w in workers:
        res[("snow", w)] = {"traced_mib": peak_memory(lambda: snow(SNOW, rng=0, workers=w)) / 2**20,
                            "rss_mib": peak_rss("from noiselab.snowfall import snow", f"snow({SNOW}, rng=0, workers={w})"),
                            "out_mib": float(np.prod(SNOW)) * 4 / 2**20}
        res[("floor", w)] = {"traced_mib": peak_memory(lambda: scipy.fft.irfftn(S, s=SNOW, workers=w)) / 2**20,
                             "rss_mib": peak_rss(f"import numpy as np, scipy.fft\nS = np.ones({S.shape}, np.complex64)",
                                                 f"scipy.fft.irfftn(S, s={SNOW}, workers={w})")}
    return res


def _section(title, cmd, load0, intro, head):
    """The header lines of an appended report section, its intro paragraph and its table head."""
    return ["", title, "", *header_lines(run_info(cmd, ["scipy", "noiselab"], load=load0)),
            f"- load average (1 min) after the timing: {load_average():.1f}", "", intro, "", head,
            "|" + " --- |" * head.count(" | ") + " --- |"]


def _append(name, lines, write):
    text = "\n".join(lines + [""])
    print(text)
    if write:
        with open(ROOT / "benchmarks" / name, "a") as fh:
            fh.write(text)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--no-write", action="store_true")
    ap.add_argument("--only", choices=["spectral", "snow"], default=None)
    ap.add_argument("--before", default=None, help="git revision whose spectral synthesis and kernels to time beside")
    ap.add_argument("--dtypes", nargs="+", default=["float32"], choices=["float32", "float64"])
    ap.add_argument("--last-pass", action="store_true", help="only the last pass's cost per block of rows")
    ap.add_argument("--small", action="store_true", help=f"the shapes {SMALL} instead of {SPECTRAL}")
    a = ap.parse_args(argv)
    if a.rounds < 5:
        ap.error("--rounds must be at least 5")
    cmd = "python3 benchmarks/bench_spectral_floor.py" + (
        f" --workers {' '.join(map(str, a.workers))}" if a.workers != [1, 2] else "") + (
        f" --rounds {a.rounds}" if a.rounds != 7 else "") + (f" --only {a.only}" if a.only else "") + (
        f" --before {a.before}" if a.before else "") + (
        f" --dtypes {' '.join(a.dtypes)}" if a.dtypes != ["float32"] else "") + (" --small" if a.small else "")
    if a.last_pass:
        load0 = load_average()
        sweep = last_pass_sweep(a.workers, a.rounds)
        lines = _section(
            "## The in-place synthesis's last pass per block of rows (`bench_spectral_floor.py --last-pass`)",
            cmd + " --last-pass", load0,
            f"1024 x 1024 float32: `irfft` of the `(1024, 513)` complex64 rows, a block of rows per call, each "
            f"block's samples copied into the float32 output; CPU ms, median of {a.rounds} interleaved rounds.",
            "| rows per call (calls) | " + " | ".join(f"CPU ms, {w} worker(s)" for w in a.workers) + " |")
        for b, ms in sweep:
            lines.append(f"| {b} ({1024 // b}) | " + " | ".join(f"{m:.2f}" for m in ms) + " |")
        _append("bench_spectral.md", lines, not a.no_write)
        return
    if a.only != "snow":
        load0 = load_average()
        before = None
        if a.before:
            sys.path.insert(0, str(ROOT / "benchmarks"))
            from bench_spectral import _before_module
            before = _before_module(a.before)
        rows = spectral(a.workers, a.rounds, before, a.dtypes, SMALL if a.small else SPECTRAL)
        lines = _section(
            "## At the floor, CPU time and wall time (`bench_spectral_floor.py`)", cmd, load0,
            f"{', '.join(a.dtypes)}, full band, `exponent=1`; ratio = median over {a.rounds} interleaved rounds of "
            "spectral_noise / floor in the same round (floor = `scipy.fft.irfftn` of a complex half spectrum "
            "of the dtype to the same output, same `workers`); CPU = `time.process_time` (all threads of the "
            "process), which the other jobs on a shared machine do not inflate; cores = CPU / wall of the call; "
            "peak = `tracemalloc` peak of one call at the last worker count / the output's bytes.",
            "| shape | dtype | workers | floor wall / CPU ms | **ratio, CPU** | ratio, wall | cores used: floor, "
            "spectral_noise | 1-worker call, ms CPU: plan / fill / gain+scale / FFT (call) | peak x output |"
            + (f" `{a.before}`: ratio CPU, wall; 1-worker fill ms CPU; peak x output |" if before is not None
               else ""))
        for r in rows:
            st = r["stages"]
            lines.append(f"| {'x'.join(map(str, r['shape']))} | {r['dtype']} | {r['workers']} | "
                         f"{r['floor_wall_ms']:.1f} / "
                         f"{r['floor_cpu_ms']:.1f} | **{r['cpu']:.2f}** | {r['wall']:.2f} | {r['cores_floor']:.2f}, "
                         f"{r['cores_sn']:.2f} | {st['plan']:.2f} / {st['fill']:.2f} / {st['gain']:.2f} / "
                         f"{st['fft']:.2f} ({st['call']:.2f}) | {r['peak']:.3f} |"
                         + (f" {r['before_cpu']:.2f}, {r['before_wall']:.2f}; {r['before_fill']:.2f}; "
                            f"{r['before_peak']:.3f} |"
                            if before is not None else ""))
        _append("bench_spectral.md", lines, not a.no_write)
    if a.only != "spectral":
        load0 = load_average()
        rows = snow_timing(a.workers, a.rounds)
        mem = snow_memory(a.workers)
        lines = _section(
            "## Snow at the pruned-FFT limit, CPU and wall time, memory (`bench_spectral_floor.py`)", cmd,
            load0, f"`snow({SNOW})` float32, default scene; ratio = median over {a.rounds} interleaved rounds of "
            "snow / floor in the same round (floor = `scipy.fft.irfftn` of a complex64 `(T, H, W//2+1)` spectrum, "
            "same `workers`). Memory: the `tracemalloc` peak of one call (numpy arrays, `noiselab.lab.measure."
            "peak_memory`) and the peak RSS growth of one call in a fresh subprocess (`peak_rss`), against the "
            "64 MiB output.",
            "| workers | floor wall / CPU ms | **ratio, CPU** | ratio, wall | tracemalloc peak MiB (x output) "
            "| peak RSS growth MiB (x output) | floor: tracemalloc, RSS (x output) |")
        for r in rows:
            w = r["workers"]
            m, f = mem[("snow", w)], mem[("floor", w)]
            o = m["out_mib"]
            lines.append(f"| {w} | {r['floor_wall_ms']:.1f} / {r['floor_cpu_ms']:.1f} | **{r['cpu']:.2f}** | "
                         f"{r['wall']:.2f} | {m['traced_mib']:.1f} (**{m['traced_mib'] / o:.3f}**) | "
                         f"{m['rss_mib']:.1f} ({m['rss_mib'] / o:.3f}) | {f['traced_mib'] / o:.2f}, "
                         f"{f['rss_mib'] / o:.2f} |")
        _append("bench_snow.md", lines, not a.no_write)


if __name__ == "__main__":
    main()
