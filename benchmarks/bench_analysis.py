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
import sys
import tracemalloc
from pathlib import Path

import numpy as np
import scipy
import scipy.fft

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import noiselab  # noqa: E402
from noiselab import analysis as A  # noqa: E402
from noiselab.lab.measure import header_lines, markdown_table, run_info  # noqa: E402
from noiselab.lab.measure import interleaved  # noqa: E402


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
    video = noiselab.snow(shape, rng=0)  # a realistic input: falling snow, float32
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
        "on a spectrum: motion_energy": lambda: A.motion_energy(spec, velocity_yx=(1, 0)),
        "on a spectrum: speed_profile (6 bands)": lambda: A.speed_profile(hann, bands),
        "on a spectrum: spatiotemporal_spectrum": lambda: A.spatiotemporal_spectrum(spec),
        "on a spectrum: radial_spectrum (3-D)": lambda: A.radial_spectrum(spec),
    }
    FLOOR = "floor: scipy.fft.rfftn(video)"
    t = interleaved(cases, repeats=rounds)
    rows = [(k, t[k], t.ratio(k, FLOOR)) for k in cases]
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
            fit = A.spectral_slope(power_law_field(n, alpha, 1000 * int(10 * alpha) + s), (4, n / 4))
            errs.append(float(fit) + alpha)
            ses.append(fit.error)
        errs = np.array(errs)
        out.append((alpha, float(np.mean(errs)), float(np.std(errs)), float(np.max(np.abs(errs))), float(np.mean(ses))))
    return out


def generator_figures():
    """The figures the spectral checks assert on, measured on noiselab's own generators."""
    from noiselab.lattice import Grid

    rows = []
    T, H, W = 32, 128, 128
    band = (W / 32, W / 4)
    tol = 0.5 + 0.1 * 1.0 * T / (2 * np.pi)
    raw = noiselab.snow((T, H, W), rng=1, c=1.0, thickness=0.1, rescale=False)
    alpha = noiselab.snow((T, H, W), rng=1, c=1.0, thickness=0.1)
    rows.append(("snow raw field: power on the tent (c=1, thickness 0.1), 32x128x128", f"{A.tent_energy(raw, 1.0, band, tol=tol):.12f}"))
    rows.append(("snow opacity (beta 1.5): power on the tent", f"{A.tent_energy(alpha, 1.0, band, tol=tol):.4f}"))
    rows.append(("snow opacity: power inside the band 4..32 cycles/frame", f"{A.band_energy(alpha, band, axes=(-2, -1)):.4f}"))
    prof = A.speed_profile(raw, A.octave_bands(*band, per_octave=2))
    rows.append(("snow: speed x w (w = 2 pi f / W rad/px) per half-octave band, c = 1 rad/frame", ", ".join(f"{x:.3f}" for x in prof.parallax)))
    rows.append(("snow: best single velocity (px/frame)", "({:+.3f}, {:+.3f})".format(*A.best_velocity(raw))))
    rows.append(("snow opacity: loop seam / tile seam", f"{A.loop_seam(alpha):.3f} / {A.tile_seam(alpha):.3f}"))
    for e in (0.5, 1.0, 2.0):
        img = noiselab.spectral_noise((512, 512), exponent=e, rng=int(10 * e))
        rows.append((f"spectral_noise exponent {e:g}: amplitude slope 4..128 at 512x512", f"{float(A.spectral_slope(img, (4, 128))):+.4f}"))
    rows.append(("spectral_noise 512x512: anisotropy", f"{A.anisotropy(noiselab.spectral_noise((512, 512), rng=9)):.4f}"))
    for k in ("box", "linear", "quadratic", "cubic", "catmull-rom", "quintic"):
        img = noiselab.LatticeNoise(2, rng=3, kernel=k, period=8).grid((256, 256), [(0, 8), (0, 8)])
        o = A.orientation_energy(img)
        rows.append((f"lattice value noise, {k}: power beyond the lattice frequency / anisotropy (m2, m4)",
                     f"{A.band_energy(img, (8, 128 * np.sqrt(2))):.2e} / {o.index:.3f} ({o.m2:.3f}, {o.m4:.3f})"))
    for g in (0.5, 2**-0.5, 1.0):
        img = noiselab.fractal_sum(noiselab.LatticeNoise(2, rng=4, kernel="cubic"), Grid((256, 256), [(0, 4), (0, 4)]), 8, gain=g)
        rows.append((f"fractal_sum (cubic) gain {g:.3f}: slope 8..64, Hann (expected {np.log2(g) - 1:+.2f})",
                     f"{float(A.spectral_slope(img, (8, 64), window='hann')):+.3f}"))
    return rows


def build_parser():
    """The command line (``--quick``, ``--rounds``)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller, for a smoke test (writes nothing)")
    ap.add_argument("--rounds", type=int, default=5, help="timed rounds (>= 5)")
    return ap


def main(argv=None):
    ap = build_parser()
    args = ap.parse_args(argv)
    shape = (16, 128, 128) if args.quick else (64, 512, 512)
    if args.rounds < 5:
        ap.error("--rounds must be >= 5 (median of at least 5)")
    rounds = args.rounds
    seeds = 4 if args.quick else 20
    n = 256 if args.quick else 512
    cmd = "python3 benchmarks/bench_analysis.py" + (" --quick" if args.quick else "") + (
        f" --rounds {rounds}" if rounds != 5 else "")
    info = run_info(cmd, ["scipy", "noiselab"])
    rows, mem, nbytes = timing(shape, rounds)
    acc = accuracy(n, seeds)
    gens = generator_figures()
    lines = [
        "# noiselab.analysis: speed, memory and slope accuracy",
        "",
        *header_lines(info),
        "",
        f"## Speed on a {' x '.join(map(str, shape))} float32 video (falling snow)",
        "",
        f"Median of {rounds} interleaved rounds after one warm-up round (order rotated each round, "
        "`noiselab.lab.measure.interleaved`); ratio = median of per-round (time / bare `scipy.fft.rfftn` of the video).",
        "",
        *markdown_table(["analyser", "median time (s)", "x rfftn"], [(k, f"{t:.3f}", f"{r:.2f}") for k, t, r in rows],
                        align="lrr"),
    ]
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
    lines += [
        "",
        "## The generators measured (the figures behind tests/test_spectral_checks.py)",
        "",
        "| measurement | value |",
        "| --- | --- |",
    ]
    lines += [f"| {k} | {v} |" for k, v in gens]
    text = "\n".join(lines) + "\n"
    print(text)
    if not args.quick:
        (ROOT / "benchmarks" / "bench_analysis.md").write_text(text)


if __name__ == "__main__":
    main()
