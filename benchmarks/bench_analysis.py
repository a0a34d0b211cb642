"""Benchmark: the analysers on a 64 x 512 x 512 float32 video, against their floor, and the slope accuracy.

Run from the repository root::

    python3 benchmarks/bench_analysis.py           # writes benchmarks/bench_analysis.md
    python3 benchmarks/bench_analysis.py --quick   # smaller, for a smoke test

Speed: each analyser is timed side by side with its floor, a bare
``scipy.fft.rfftn`` of the same float32 video, interleaved round by round
(median of the per-round ratios, >= 5 rounds), because the machine is
shared. "on a spectrum" rows reuse one precomputed ``video_spectrum``: the
pass over the spectrum alone. Memory: ``tracemalloc`` peak of one
end-to-end call (numpy arrays only; the FFT library's scratch is not
traced), in units of the float32 video (64 MiB at 64 x 512 x 512); the
complex64 half spectrum is 1.0x of that.

Accuracy: the amplitude slope recovered from 1/f**alpha fields synthesised
with numpy (complex Gaussian coefficients, as in ``tests/test_analysis.py``)
at 512 x 512 over 4..128 cycles/frame, 20 seeds per alpha.
"""
from __future__ import annotations

import argparse
import datetime
import platform
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np
import scipy
import scipy.fft

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import noiselab  # noqa: E402
from noiselab import analysis as A  # noqa: E402


def power_law_field(n, alpha, seed):
    rng = np.random.default_rng(seed)
    ky = np.fft.fftfreq(n, 1.0 / n)[:, None]
    kx = np.arange(n // 2 + 1)[None, :]
    f = np.hypot(kx, ky)
    f[0, 0] = 1.0
    amp = f**-alpha
    amp[0, 0] = 0.0
    coef = rng.standard_normal(f.shape) + 1j * rng.standard_normal(f.shape)
    return np.fft.irfft2(amp * coef, s=(n, n))


def timing(shape, rounds):
    video = noiselab.snow(shape, seed=0)  # a realistic input: falling snow, float32
    c, band = 1.0, (shape[-1] / 32, shape[-1] / 4)
    bands = A.octave_bands(*band, per_octave=2)
    spec = A.video_spectrum(video)
    hann = A.video_spectrum(video, window="hann")
    cases = {
        "floor: scipy.fft.rfftn(video)": lambda: scipy.fft.rfftn(video),
        "video_spectrum(video)": lambda: A.video_spectrum(video),
        "tent_energy(video, ...)": lambda: A.tent_energy(video, c, band),
        "band_speeds(video, 6 bands)": lambda: A.band_speeds(video, bands),
        "best_velocity(video)": lambda: A.best_velocity(video),
        "spectral_slope(video, axes=(-2, -1))": lambda: A.spectral_slope(video, band, axes=(-2, -1)),
        "anisotropy(video) (frames averaged)": lambda: A.anisotropy(video),
        "loop_seam(video)": lambda: A.loop_seam(video),
        "on a spectrum: tent_energy": lambda: A.tent_energy(spec, c, band),
        "on a spectrum: motion_energy": lambda: A.motion_energy(spec, (0, 1)),
        "on a spectrum: speed_profile (6 bands)": lambda: A.speed_profile(hann, bands),
        "on a spectrum: spatiotemporal_spectrum": lambda: A.spatiotemporal_spectrum(spec),
        "on a spectrum: radial_spectrum (3-D)": lambda: A.radial_spectrum(spec),
    }
    for f in cases.values():  # warm-up
        f()
    times = {k: [] for k in cases}
    for _ in range(rounds):
        for k, f in cases.items():
            t0 = time.perf_counter()
            f()
            times[k].append(time.perf_counter() - t0)
    floor = np.array(times["floor: scipy.fft.rfftn(video)"])
    rows = []
    for k, t in times.items():
        t = np.array(t)
        rows.append((k, float(np.median(t)), float(np.median(t / floor))))
    # memory: one end-to-end call each
    mem = []
    unit = video.nbytes
    del spec, hann
    for k in ("video_spectrum(video)", "tent_energy(video, ...)", "band_speeds(video, 6 bands)",
              "spectral_slope(video, axes=(-2, -1))", "on a spectrum: radial_spectrum (3-D)"):
        if k.startswith("on a spectrum"):
            s = A.video_spectrum(video)
            tracemalloc.start()
            A.radial_spectrum(s)
        else:
            tracemalloc.start()
            cases[k]()
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        mem.append((k, peak / 2**20, peak / unit))
    return rows, mem, video.nbytes


def accuracy(n, seeds):
    out = []
    for alpha in (0.5, 1.0, 1.5, 2.0):
        errs, ses = [], []
        for s in range(seeds):
            fit = A.spectral_slope(power_law_field(n, alpha, 1000 + s), (4, n / 4))
            errs.append(float(fit) + alpha)
            ses.append(fit.error)
        errs = np.array(errs)
        out.append((alpha, float(np.mean(errs)), float(np.std(errs)), float(np.max(np.abs(errs))), float(np.mean(ses))))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    shape = (16, 128, 128) if args.quick else (64, 512, 512)
    rounds = 5
    seeds = 4 if args.quick else 20
    n = 256 if args.quick else 512
    rows, mem, nbytes = timing(shape, rounds)
    acc = accuracy(n, seeds)
    cmd = "python3 benchmarks/bench_analysis.py" + (" --quick" if args.quick else "")
    lines = [
        "# noiselab.analysis: speed, memory and slope accuracy",
        "",
        f"- date: {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC",
        f"- machine: {platform.machine()}, {platform.processor() or 'cpu'}, shared with other jobs; "
        f"Python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}",
        f"- command: `{cmd}`",
        "",
        f"## Speed on a {' x '.join(map(str, shape))} float32 video (falling snow)",
        "",
        f"Median of {rounds} interleaved rounds; ratio = median of per-round (time / bare `scipy.fft.rfftn` of the video).",
        "",
        "| analyser | median time (s) | x rfftn |",
        "| --- | ---: | ---: |",
    ]
    lines += [f"| {k} | {t:.3f} | {r:.2f} |" for k, t, r in rows]
    lines += [
        "",
        f"## Peak traced memory (numpy arrays), in units of the float32 video ({nbytes / 2**20:.0f} MiB)",
        "",
        "| call | peak (MiB) | x video |",
        "| --- | ---: | ---: |",
    ]
    lines += [f"| {k} | {m:.0f} | {r:.2f} |" for k, m, r in mem]
    lines += [
        "",
        f"## Slope recovery at {n} x {n} (band 4..{n // 4} cycles/frame, {seeds} seeds per alpha)",
        "",
        "| alpha | mean error | std | max abs error | mean reported fit error |",
        "| ---: | ---: | ---: | ---: | ---: |",
    ]
    lines += [f"| {a:g} | {m:+.4f} | {s:.4f} | {mx:.4f} | {se:.4f} |" for a, m, s, mx, se in acc]
    text = "\n".join(lines) + "\n"
    print(text)
    if not args.quick:
        (ROOT / "benchmarks" / "bench_analysis.md").write_text(text)


if __name__ == "__main__":
    main()
