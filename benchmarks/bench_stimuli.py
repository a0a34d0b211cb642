"""Benchmark: stimuli in physical units: requested against measured, and what each file format keeps.

Run from the repository root::

    python3 benchmarks/bench_stimuli.py           # writes benchmarks/bench_stimuli.md
    python3 benchmarks/bench_stimuli.py --quick   # smaller, printed only

1. Every stimulus kind of ``noiselab stimulus`` made through the library on
   one stated display, with the requested mean luminance, contrast and the
   kind's own parameter (spectral slope, orientation, speed) measured on
   ``display.luminance_of(values)``, the luminance the screen shows.
2. The same display values written to each output format and read back:
   the Michelson and RMS contrast and the mean luminance after the round
   trip (a user's report: a snow stimulus at Michelson 0.176 read back
   from its MP4 at 0.186).
3. Dithering below one display step: the luminance averaged over 64 seeds
   against the request, per pixel.
"""
from __future__ import annotations

import argparse
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import noiselab  # noqa: E402
from noiselab import Display, analysis as A  # noqa: E402
from noiselab.io import read_video, write_video  # noqa: E402
from noiselab.lab.measure import header_lines, markdown_table, run_info  # noqa: E402
from noiselab.stimuli import luminance_for, motion_cloud, phase_scramble, to_display  # noqa: E402

DISPLAY = Display(32.0, frame_rate=60.0, luminance=(0.5, 100.0), gamma=2.2, bits=8)


def _measured(values, d=DISPLAY):
    L = d.luminance_of(values)
    return L, float(L.mean()), A.rms_contrast(L), A.michelson_contrast(L)


def kinds(size_deg, duration):
    d = DISPLAY
    n, T = d.pixels(size_deg), d.frame_count(duration)
    rows = []
    mean, rms = 40.0, 0.2
    # 1/f patch: amplitude slope -1 over 0.5..8 cycles/deg
    x = noiselab.spectral_noise((n, n), exponent=1.0, band=d.band((0.5, 8), n), rng=1)
    v = to_display(x, d, mean=mean, contrast=rms, rng=1)
    L, m, r, _ = _measured(v)
    slope = A.spectral_slope(L, d.band((1, 6), n))
    rows.append(("1/f patch", f"mean {mean:g} cd/m², RMS {rms:g}, slope -1 (1..6 cycles/deg)",
                 f"mean {m:.3f}, RMS {r:.4f}, slope {float(slope):+.3f}"))
    # band-pass oriented noise: 4 cycles/deg, 45 deg +- 15 deg
    z = motion_cloud((n, n), sf_0=d.cycles_per_pixel(4), B_sf=d.cycles_per_pixel(2), theta=math.radians(45),
                     B_theta=math.radians(15), rng=2)
    v = to_display(z, d, mean=mean, contrast=rms, rng=2)
    L, m, r, _ = _measured(v)
    o = A.orientation_energy(L - L.mean(), d.band((2, 8), n))
    peak = float(o.angles[np.argmax(o.energy)])
    rows.append(("band-pass oriented noise", f"mean {mean:g}, RMS {rms:g}, 4 cycles/deg, 45 deg +- 15 deg",
                 f"mean {m:.3f}, RMS {r:.4f}, peak of orientation_energy {peak:.1f} deg (bin centre, wave vector)"))
    # snow: flakes of 4 cycles/deg fall at 2 deg/s; Michelson 0.176 (thesis Eq. 6.1's contrast)
    c = d.snow_c(2.0, 4.0)
    alpha = noiselab.snow((T, n, n), c=c, band=d.band((1, 8), n), rng=3)
    v = to_display(alpha, d, mean=mean, contrast=0.176, contrast_kind="michelson", rng=3)
    L, m, r, mich = _measured(v)
    f4 = d.cycles_per_frame(4, n)
    vy = A.band_speeds(L, [(f4 / 2 ** 0.25, f4 * 2 ** 0.25)])[0][1]
    rows.append(("snow", "mean 40, Michelson 0.176, 4 cycles/deg flakes at 2 deg/s down",
                 f"mean {m:.3f}, Michelson {mich:.4f}, speed at 4 cycles/deg {d.deg_per_second(vy):.3f} deg/s"))
    # motion cloud at (1.875, -0.9375) deg/s
    V = (1.875, -0.9375)
    z = motion_cloud((T, n, n), sf_0=d.cycles_per_pixel(4), B_sf=d.cycles_per_pixel(1), V_X=d.px_per_frame(V[0]),
                     V_Y=d.px_per_frame(V[1]), B_V=d.px_per_frame(0.1), rng=4)
    v = to_display(z, d, mean=mean, contrast=rms, rng=4)
    L, m, r, _ = _measured(v)
    bv = A.best_velocity(L)
    rows.append(("motion cloud", f"mean 40, RMS 0.2, velocity ({V[0]:g}, {V[1]:g}) deg/s",
                 f"mean {m:.3f}, RMS {r:.4f}, velocity ({d.deg_per_second(bv[0]):.4f}, "
                 f"{d.deg_per_second(bv[1]):.4f}) deg/s"))
    # phase-scrambled image: the 1/f patch's luminance, scrambled, shown at Michelson 0.5
    img = DISPLAY.luminance_of(to_display(x, d, mean=mean, contrast=rms, rng=1))
    s = phase_scramble(img, rng=5)
    v = to_display(s, d, mean=mean, contrast=0.5, contrast_kind="michelson", rng=5)
    L, m, _, mich = _measured(v)
    amp = np.abs(np.fft.rfft2(s)), np.abs(np.fft.rfft2(img))
    err = float(np.max(np.abs(amp[0] - amp[1])) / amp[1].max())
    corr = float(np.corrcoef(s.ravel(), img.ravel())[0, 1])
    rows.append(("phase-scrambled image", "mean 40, Michelson 0.5, amplitude spectrum kept, correlation 0",
                 f"mean {m:.3f}, Michelson {mich:.4f}, largest rfft amplitude error {err:.1e} (relative), "
                 f"correlation {corr:+.4f}"))
    return rows, n, T


def round_trips(size_deg, duration):
    d = DISPLAY
    n, T = d.pixels(size_deg), d.frame_count(duration)
    n -= n % 2  # even sizes: the default MP4's yuv420p would pad an odd frame
    alpha = noiselab.snow((T, n, n), c=d.snow_c(2.0, 4.0), band=d.band((1, 8), n), rng=3)
    rows = []
    for label, mich in (("snow, Michelson 0.176", 0.176), ("snow, Michelson 0.05", 0.05)):
        v = to_display(alpha, d, mean=40.0, contrast=mich, contrast_kind="michelson", rng=7)
        _, m0, r0, c0 = _measured(v)
        rows.append((label, "(written values)", "lossless", f"{c0:.4f}", f"{r0:.4f}", f"{m0:.3f}", "0"))
        with tempfile.TemporaryDirectory() as tmp:
            tmp = Path(tmp)
            cases = [("NPY", lambda: read_video(write_video(tmp / "v.npy", v)), "lossless"),
                     ("PNG frames", lambda: read_video(write_video(tmp / "frames", v)), "lossless"),
                     ("MKV (FFV1)", lambda: read_video(write_video(tmp / "v.mkv", v, fps=60)), "lossless"),
                     ("MP4 lossless (H.264 RGB -qp 0)",
                      lambda: read_video(write_video(tmp / "l.mp4", v, fps=60, lossless=True)), "lossless"),
                     ("MP4 default (H.264 yuv420p crf 10)", lambda: read_video(write_video(tmp / "d.mp4", v, fps=60)),
                      "lossy")]
            for name, trip, kind in cases:
                back = trip()
                ref = v[: back.shape[0]]
                _, m, r, c = _measured(back)
                changed = int(np.count_nonzero(back != ref))
                rows.append((label, name, kind, f"{c:.4f}", f"{r:.4f}", f"{m:.3f}",
                             f"{100 * changed / ref.size:.1f} %"))
    return rows, (T, n, n)


def dithering(n, seeds):
    x = noiselab.spectral_noise((n, n), band=(2, n // 4), rng=9, dtype=np.float64)
    rows = []
    for contrast in (0.001, 0.002, 0.004):
        step = float(DISPLAY.step_at(40.0))
        req = luminance_for(x, mean=40.0, contrast=contrast)
        avg = np.mean([DISPLAY.luminance_of(to_display(x, DISPLAY, mean=40.0, contrast=contrast, rng=s))
                       for s in range(seeds)], axis=0)
        nodither = DISPLAY.luminance_of(to_display(x, DISPLAY, mean=40.0, contrast=contrast, dither=False))
        rows.append((f"{contrast:g}", f"{np.ptp(req) / step:.2f}", f"{np.max(np.abs(avg - req)) / step:.3f}",
                     f"{A.rms_contrast(avg):.5f}", f"{A.rms_contrast(nodither):.5f}"))
    return rows, step


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller stimuli, printed only")
    args = ap.parse_args(argv)
    size, dur = (2.0, 0.25) if args.quick else (8.0, 1.0)
    cmd = "python3 benchmarks/bench_stimuli.py" + (" --quick" if args.quick else "")
    info = run_info(cmd, ["scipy", "imageio", "imageio-ffmpeg", "noiselab"])
    krows, n, T = kinds(size, dur)
    trows, tshape = round_trips(size / 2, dur / 2)
    drows, step = dithering(64 if args.quick else 128, 64)
    d = DISPLAY
    lines = [
        "# noiselab.stimuli: requested against measured, and what each file format keeps",
        "",
        *header_lines(info),
        "",
        f"Display: {d.pixels_per_degree:g} px/deg, {d.frame_rate:g} Hz, {d.luminance[0]:g}..{d.luminance[1]:g} cd/m², "
        f"gamma {d.gamma:g}, {d.bits} bits; every figure is measured on `display.luminance_of(values)`.",
        "",
        f"## Each stimulus kind ({size:g} deg = {n} px square, videos {dur:g} s = {T} frames)",
        "",
        *markdown_table(["kind", "requested", "measured"], krows),
        "",
        f"## Round trip through each output format (snow, {' x '.join(map(str, tshape))} display values)",
        "",
        "Contrast and mean luminance of the values read back; the last column is the share of values changed.",
        "",
        *markdown_table(["stimulus", "format", "kind", "Michelson", "RMS", "mean (cd/m²)", "values changed"], trows,
                        align="lllrrrr"),
        "",
        f"## Dithering below one display step (mean 40 cd/m², one step = {step:.3f} cd/m², 64 consecutive seeds 0..63)",
        "",
        *markdown_table(["RMS contrast", "request's range (steps)", "largest error of the seed mean (steps)",
                         "RMS of the seed mean", "RMS without dithering"], drows, align="rrrrr"),
    ]
    text = "\n".join(lines) + "\n"
    print(text)
    if not args.quick:
        (ROOT / "benchmarks" / "bench_stimuli.md").write_text(text)


if __name__ == "__main__":
    main()
