"""Benchmark: sparse Gabor noise (``noiselab.gabor``) against the FFT snow and the two other families.

Run from the repository root::

    python3 benchmarks/bench_gabor.py            # writes benchmarks/bench_gabor.md
    python3 benchmarks/bench_gabor.py --quick    # smaller, for a smoke test (writes nothing)

What it measures, every timing side by side in one process (interleaved
rounds, median of the per-round ratios, :func:`noiselab.lab.measure.interleaved`),
one thread each (``workers=1``):

1. falling snow: a 512x512 frame of ``gabor_snow`` (at a new frame each
   round; the default 4 impulses per cell and 2) against the FFT snow's cost per frame (``snow((64, 512, 512))`` / 64),
   and a 64x64 window of frame 10**6 (the FFT snow computes its whole block
   for it); peak resident memory of each in a fresh process;
2. snow quality on the same scene (64x256x256, band 8..64 cycles/frame,
   c = 1): tent energy, speed per half-octave band against the tent law,
   spectral slope, for both; the FFT snow's extremes in standard deviations
   (``gabor.OPACITY_SIGMAS``);
3. 1/f textures 512x512 (equal energy per octave from 4 cycles/frame to
   Nyquist): the spectral field, a lattice fBm (gradient, quintic) and Gabor
   octave layers: time per sample against slope error, anisotropy, leakage
   (the lab's Pareto figures, ``noiselab.lab.experiments.texture_quality``).
"""
from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from noiselab import analysis as A  # noqa: E402
from noiselab.gabor import gabor_snow  # noqa: E402
from noiselab.lab.experiments import _gabor_texture, _lattice_texture, texture_quality  # noqa: E402
from noiselab.lab.measure import header_lines, interleaved, markdown_table, peak_rss, run_info  # noqa: E402
from noiselab.snowfall import snow  # noqa: E402
from noiselab.spectral import spectral_noise  # noqa: E402

COMMAND = "python3 benchmarks/bench_gabor.py"


def snow_timing(size, frames, repeats):
    block = (frames, size, size)
    gabor_snow((1, 32, 32), rng=0)   # compile (or load) the kernels
    cands = {
        "gabor frame": lambda r: gabor_snow((1, size, size), origin=(1000 * (r + 1), 0, 0), rng=0, width=size,
                                            workers=1),
        "gabor frame, density 2": lambda r: gabor_snow((1, size, size), origin=(1000 * (r + 1), 0, 0), rng=0,
                                                       width=size, density=2.0, workers=1),
        "fft block": lambda r: snow(block, rng=0, workers=1),
        "gabor 64x64 of frame 10**6": lambda r: gabor_snow((1, 64, 64), origin=(10 ** 6 + r, 0, 0), rng=0,
                                                           width=size, workers=1),
    }
    t = interleaved(cands, repeats=repeats, warmup=1, round_arg=True, min_repeats=5)
    per_frame_fft = t.median("fft block") / frames
    rows = [
        ["gabor_snow, one 512x512 frame" if size == 512 else f"gabor_snow, one {size}x{size} frame",
         f"{t.median('gabor frame') * 1e3:.1f}", f"{1 / t.median('gabor frame'):.1f}",
         f"{t.ratio('gabor frame', 'fft block') * frames:.2f}"],
        [f"gabor_snow, one {size}x{size} frame, density=2 (half the kernels)",
         f"{t.median('gabor frame, density 2') * 1e3:.1f}", f"{1 / t.median('gabor frame, density 2'):.1f}",
         f"{t.ratio('gabor frame, density 2', 'fft block') * frames:.2f}"],
        [f"snow (FFT), block {frames}x{size}x{size}, per frame", f"{per_frame_fft * 1e3:.1f}",
         f"{1 / per_frame_fft:.1f}", "1"],
        ["gabor_snow, 64x64 window of frame 10**6", f"{t.median('gabor 64x64 of frame 10**6') * 1e3:.2f}", "",
         f"{t.ratio('gabor 64x64 of frame 10**6', 'fft block') * frames:.3f}"],
        [f"snow (FFT), the same window: its whole block", f"{t.median('fft block') * 1e3:.0f}", "",
         f"{frames}"],
    ]
    return rows, t


def snow_memory(size, frames):
    setup = "import numpy as np\nfrom noiselab.gabor import gabor_snow\nfrom noiselab.snowfall import snow"
    return {
        "gabor frame": peak_rss(setup, f"gabor_snow((1, {size}, {size}), rng=0, width={size}, workers=1)"),
        "gabor 64x64 window": peak_rss(setup, f"gabor_snow((1, 64, 64), origin=(10**6, 0, 0), rng=0, width={size})"),
        "fft block": peak_rss(setup, f"snow(({frames}, {size}, {size}), rng=0, workers=1)"),
    }


def snow_quality(shape):
    T, H, W = shape
    band = (W / 32, W / 4)
    g = gabor_snow(shape, rng=0, width=W, rescale=False, workers=1)
    f = snow(shape, rng=0, rescale=False, workers=1)
    bands = A.octave_bands(band[0] * 2 ** 0.5, band[1] / 2 ** 0.5, per_octave=2)
    law = np.array([W / (2 * math.pi) * (1 / lo - 1 / hi) / math.log(hi / lo) for lo, hi in bands])
    g2 = gabor_snow(shape, rng=0, width=W, density=2.0, rescale=False, workers=1)
    rows = []
    for name, v in (("gabor_snow", g), ("gabor_snow, density=2", g2), ("snow (FFT)", f)):
        speed = A.band_speeds(v, bands)[:, 1] / law
        slope = np.mean([float(A.spectral_slope(v[i], band=(band[0], band[1]), window="hann"))
                         for i in range(0, T, max(1, T // 8))])
        rows.append([name, f"{A.tent_energy(v, 1.0, band):.3f}", f"{A.tent_energy(v, 1.0, band, window='hann'):.3f}",
                     f"{A.tent_energy(v, 1.0, band, window='hann', tol=1.5):.3f}",
                     " ".join(f"{s:.3f}" for s in speed), f"{np.max(np.abs(speed - 1)):.3f}", f"{slope:+.3f}"])
    return rows, bands


def fft_extremes(shape):
    x = snow(shape, rng=0, rescale=False, workers=1).astype(np.float64)
    s = x.std()
    return (x.max() - x.mean()) / s, (x.mean() - x.min()) / s


def texture_pareto(n, f0, repeats):
    methods = {
        "spectral (IFFT)": lambda s: spectral_noise((n, n), exponent=1.0, band=(f0, n / 2), rng=s),
        "lattice fBm, gradient quintic": lambda s: _lattice_texture(n, 2, f0, "quintic", "gradient", s),
        "sparse Gabor, octave layers": lambda s: _gabor_texture(n, 2, f0, s),
    }
    t = interleaved({k: (lambda r, fn=fn: fn(0)) for k, fn in methods.items()}, repeats=repeats, warmup=1,
                    round_arg=True, min_repeats=5)
    rows = []
    for name, fn in methods.items():
        q = texture_quality(fn(1), f0, 2)
        rows.append([name, f"{t.median(name) * 1e3:.1f}", f"{n * n / t.median(name):.3g}",
                     f"{t.ratio(name, 'spectral (IFFT)'):.2f}", f"{q['slope_error']:+.3f}",
                     f"{q['anisotropy']:.3f}", f"{q['band_leakage']:.3f}", f"{q['octave_ripple_db']:.2f}"])
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes, print only (writes no report)")
    ap.add_argument("--repeats", type=int, default=5, help="timed rounds (at least 5)")
    args = ap.parse_args(argv)
    size, frames = (128, 16) if args.quick else (512, 64)
    qshape = (16, 64, 64) if args.quick else (64, 256, 256)
    info = run_info(COMMAND + (" --quick" if args.quick else ""), ["scipy", "noiselab"])
    lines = ["# Sparse Gabor noise: falling snow with no period, and the third family", ""]
    lines += header_lines(info)
    lines += ["", "## 1. Falling snow: a frame, a distant window, memory", ""]
    rows, _ = snow_timing(size, frames, args.repeats)
    lines += markdown_table(["case", "median ms", "frames/s", "x FFT snow per frame (per-round ratio)"], rows)
    mem = snow_memory(size, frames)
    lines += ["", "Peak resident memory above the process's baseline (fresh process, after a warm-up call): "
              + ", ".join(f"{k} {v:.1f} MiB" for k, v in mem.items() if v is not None) + "."]
    lines += ["", f"## 2. Snow quality, {'x'.join(map(str, qshape))}, band {qshape[2] / 32:g}..{qshape[2] / 4:g} "
              "cycles/frame, c = 1", ""]
    qrows, bands = snow_quality(qshape)
    lines += markdown_table(["method", "tent energy (no window, tol 0.5)", "tent energy (Hann, tol 0.5)",
                             "tent energy (Hann, tol 1.5)", "speed / tent law per band", "max |speed/law - 1|",
                             "spatial amplitude slope (target -1)"], qrows)
    lines += ["", "Bands (cycles/frame): " + ", ".join(f"{lo:.1f}-{hi:.1f}" for lo, hi in bands) + "; the law is "
              "`c N / (2 pi f)` averaged over each band's 1/f power. The Gabor clip does not loop, so a window "
              "without a taper leaks at its ends and a Hann taper spreads each temporal line over about 3 bins "
              "(the FFT snow, periodic, loses the same share under the taper)."]
    hi, lo = fft_extremes((frames, size, size))
    lines += ["", f"FFT snow {frames}x{size}x{size} (rng=0): maximum {hi:.2f} and minimum -{lo:.2f} standard "
              "deviations from the mean: `gabor.OPACITY_SIGMAS` = 5.3 maps +-5.3 sd to opacity 1 and 0."]
    lines += ["", f"## 3. 1/f textures {size}x{size}: time against spectral error (the lab's Pareto figures)", ""]
    lines += markdown_table(["method", "median ms", "samples/s", "x spectral time", "slope error", "anisotropy",
                             "leakage", "ripple dB"], texture_pareto(size, 4.0, args.repeats))
    text = "\n".join(lines) + "\n"
    if args.quick:
        print(text)
        return 0
    out = ROOT / "benchmarks" / "bench_gabor.md"
    from noiselab.io import atomic_output

    with atomic_output(out) as tmp:
        Path(tmp).write_text(text)
    print(text)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
