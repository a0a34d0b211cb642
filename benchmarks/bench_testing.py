"""Benchmark: the false-alarm rate and the detection power of the noiselab.testing assertions.

Run from the repository root (the peers' fields need powerbox, colorednoise and MotionClouds,
which the ``test`` extra installs)::

    python3 benchmarks/bench_testing.py              # 200 seeds per case, writes benchmarks/bench_testing.md
    python3 benchmarks/bench_testing.py --seeds 20   # a smoke test (writes nothing)

False alarms: each assertion is run with its defaults (``false_alarm=1e-3``)
and at ``false_alarm=0.05`` (where a miscalibration shows in 200 seeds) on
fields that hold the property -- noiselab's own generators and the peers'
(powerbox Gaussian random fields, colorednoise 1-D series, MotionClouds
videos) -- and the failures are counted. A calibrated test fails
``n * false_alarm`` times on average; the table gives the count, the
count a calibrated test exceeds with probability below 1e-3 (the binomial
quantile: "within" when the count does not pass it) and the Clopper-Pearson
95 % upper bound on the true rate.

Power: the same assertions on fields that break the property by a stated
amount -- a wrong exponent (+-0.2), a missing band edge, a 5 % anisotropy
(power ``1 + 0.05 cos 2 theta`` or ``cos 4 theta``), a seam (a crop, a cut
loop), the wrong sign of a velocity -- and the fraction of seeds detected.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from scipy import stats

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import colorednoise  # noqa: E402
import MotionClouds as mc  # noqa: E402
import powerbox  # noqa: E402

import noiselab  # noqa: E402
from noiselab import testing as T  # noqa: E402
from noiselab.lab.measure import header_lines, markdown_table, run_info  # noqa: E402


# ----------------------------------------------------------------------------- fields
def spectral(shape, exponent=1.0, band=None):
    return lambda s: noiselab.spectral_noise(shape, exponent=exponent, band=band, rng=s)


def pbox(n, amp_exponent, dim=2):
    return lambda s: powerbox.PowerBox(shape=(n,) * dim, size=(float(n),) * dim,
                                       pk=lambda k: k ** (-2.0 * amp_exponent), seed=s).delta_x()


def coloured(n, beta):
    return lambda s: colorednoise.powerlaw_psd_gaussian(beta, n, random_state=s)


def cloud(velocity, shape=(32, 64, 64)):
    t, h, w = shape
    fx, fy, ft = mc.get_grids(w, h, t)
    env = mc.envelope_gabor(fx, fy, ft, V_X=velocity[0], V_Y=velocity[1], B_V=0.1, sf_0=0.15, B_sf=0.1,
                            B_theta=np.inf)
    return lambda s: np.transpose(mc.rectif(mc.random_cloud(env, seed=s)), (2, 1, 0))


def modulated(n, depth, fold, exponent=1.0):
    """A Gaussian 1/f**exponent field whose power is modulated by ``1 + depth cos(fold theta)``."""
    ky, kx = np.fft.fftfreq(n)[:, None], np.fft.rfftfreq(n)[None, :]
    f = np.hypot(kx, ky)
    f[0, 0] = 1.0
    gain = np.sqrt(1 + depth * np.cos(fold * np.arctan2(ky, kx))) * f**-exponent
    gain[0, 0] = 0.0

    def make(s):
        rng = np.random.default_rng(s)
        spec = (rng.standard_normal(gain.shape) + 1j * rng.standard_normal(gain.shape)) * gain
        return np.fft.irfft2(spec, s=(n, n))
    return make


def crop(make, keep):
    return lambda s: make(s)[tuple(slice(0, k) for k in keep)]


def snow_alpha(shape=(16, 64, 64)):
    return lambda s: noiselab.snow(shape, rng=s, c=1.0)


def snow_raw(shape=(16, 64, 64)):
    return lambda s: noiselab.snow(shape, rng=s, c=1.0, rescale=False)


# ----------------------------------------------------------------------------- cases
def null_cases():
    """(assertion, field description, field maker, check(field, false_alarm))."""
    pl = T.assert_power_law
    return [
        ("assert_power_law", "noiselab spectral_noise 128^2, exponent 1", spectral((128, 128)),
         lambda x, fa: pl(x, 1.0, false_alarm=fa)),
        ("assert_power_law", "noiselab spectral_noise 256^2, exponent 2, band 4..64", spectral((256, 256), 2.0),
         lambda x, fa: pl(x, 2.0, band=(4, 64), false_alarm=fa)),
        ("assert_power_law", "noiselab spectral_noise 64^3, exponent 1.5", spectral((64, 64, 64), 1.5),
         lambda x, fa: pl(x, 1.5, false_alarm=fa)),
        ("assert_power_law", "noiselab spectral_noise 256^2 cropped to 160^2, hann, exponent 1",
         crop(spectral((256, 256)), (160, 160)), lambda x, fa: pl(x, 1.0, band=(4, 40), window="hann", false_alarm=fa)),
        ("assert_power_law", "powerbox 128^2, pk = k^-2 (exponent 1)", pbox(128, 1.0),
         lambda x, fa: pl(x, 1.0, false_alarm=fa)),
        ("assert_power_law", "powerbox 48^3, pk = k^-3 (exponent 1.5)", pbox(48, 1.5, 3),
         lambda x, fa: pl(x, 1.5, false_alarm=fa)),
        ("assert_power_law", "colorednoise 4096, beta 1 (exponent 0.5)", coloured(4096, 1.0),
         lambda x, fa: pl(x, 0.5, false_alarm=fa)),
        ("assert_power_law", "colorednoise 4096, beta 2 (exponent 1)", coloured(4096, 2.0),
         lambda x, fa: pl(x, 1.0, false_alarm=fa)),
        ("assert_isotropic", "noiselab spectral_noise 128^2, exponent 1", spectral((128, 128)),
         lambda x, fa: T.assert_isotropic(x, false_alarm=fa)),
        ("assert_isotropic", "noiselab spectral_noise 256^2, exponent 2, band 1..8", spectral((256, 256), 2.0, (1, 8)),
         lambda x, fa: T.assert_isotropic(x, band=(2, 8), false_alarm=fa)),
        ("assert_isotropic", "powerbox 128^2, exponent 1", pbox(128, 1.0),
         lambda x, fa: T.assert_isotropic(x, false_alarm=fa)),
        ("assert_isotropic", "white noise 128^2 (numpy)", lambda s: np.random.default_rng(s).standard_normal((128, 128)),
         lambda x, fa: T.assert_isotropic(x, false_alarm=fa)),
        ("assert_no_axis_artefacts", "noiselab spectral_noise 128^2, exponent 1", spectral((128, 128)),
         lambda x, fa: T.assert_no_axis_artefacts(x, false_alarm=fa)),
        ("assert_no_axis_artefacts", "powerbox 128^2, exponent 1.5", pbox(128, 1.5),
         lambda x, fa: T.assert_no_axis_artefacts(x, false_alarm=fa)),
        ("assert_seamless", "noiselab spectral_noise 128^2, exponent 1", spectral((128, 128)),
         lambda x, fa: T.assert_seamless(x, false_alarm=fa)),
        ("assert_seamless", "powerbox 128^2, exponent 1.5", pbox(128, 1.5),
         lambda x, fa: T.assert_seamless(x, false_alarm=fa)),
        ("assert_seamless", "MotionClouds 32 x 64^2, v = (1, 0): time axis", cloud((1.0, 0.0)),
         lambda x, fa: T.assert_seamless(x, axes=0, false_alarm=fa)),
        ("assert_seamless", "noiselab snow alpha 16 x 64^2: all axes", snow_alpha(),
         lambda x, fa: T.assert_seamless(x, false_alarm=fa)),
    ]


def threshold_cases():
    """Assertions whose threshold is a stated fraction (no false_alarm): failures at the defaults."""
    return [
        ("assert_band_limited", "noiselab spectral_noise 128^2, band 8..32", spectral((128, 128), 1.0, (8, 32)),
         lambda x: T.assert_band_limited(x, (8, 32))),
        ("assert_motion", "MotionClouds 32 x 64^2, v = (1, 0), B_V 0.1", cloud((1.0, 0.0)),
         lambda x: T.assert_motion(x, velocity_yx=(0.0, 1.0))),
        ("assert_motion", "MotionClouds 32 x 64^2, v = (0.5, -0.5), B_V 0.1", cloud((0.5, -0.5)),
         lambda x: T.assert_motion(x, velocity_yx=(-0.5, 0.5))),
        ("assert_tent", "noiselab snow (raw) 16 x 64^2, c = 1, band 2..16", snow_raw(),
         lambda x: T.assert_tent(x, 1.0, (2, 16))),
    ]


def power_cases():
    """(assertion, what breaks the property, field maker, check(field)) at the defaults (false_alarm=1e-3)."""
    pl = T.assert_power_law
    cases = []
    for d in (+0.2, -0.2):
        cases += [
            ("assert_power_law", f"exponent off by {d:+.1f}: spectral_noise 128^2 exponent 1",
             spectral((128, 128)), lambda x, d=d: pl(x, 1.0 + d)),
            ("assert_power_law", f"exponent off by {d:+.1f}: spectral_noise 64^2 exponent 1",
             spectral((64, 64)), lambda x, d=d: pl(x, 1.0 + d)),
            ("assert_power_law", f"exponent off by {d:+.1f}: powerbox 128^2 exponent 1",
             pbox(128, 1.0), lambda x, d=d: pl(x, 1.0 + d)),
            ("assert_power_law", f"exponent off by {d:+.1f}: colorednoise 4096 beta 1",
             coloured(4096, 1.0), lambda x, d=d: pl(x, 0.5 + d)),
        ]
    cases += [
        ("assert_band_limited", "missing upper edge: band 8..64 asserted as 8..32", spectral((128, 128), 1.0, (8, 64)),
         lambda x: T.assert_band_limited(x, (8, 32))),
        ("assert_band_limited", "missing lower edge: band 1..32 asserted as 8..32", spectral((128, 128), 1.0, (1, 32)),
         lambda x: T.assert_band_limited(x, (8, 32))),
        ("assert_power_law", "missing lower edge seen by the power law: band 8..32, asserted over 2..32",
         spectral((128, 128), 1.0, (8, 32)), lambda x: pl(x, 1.0, band=(2, 32))),
    ]
    for n in (128, 256, 512):
        cases.append(("assert_isotropic", f"5 % anisotropy (power 1 + 0.05 cos 2 theta), {n}^2 exponent 1",
                      modulated(n, 0.05, 2), lambda x: T.assert_isotropic(x)))
    for n in (256, 512):
        cases.append(("assert_isotropic", f"5 % axis cross (power 1 + 0.05 cos 4 theta), {n}^2 exponent 1",
                      modulated(n, 0.05, 4), lambda x: T.assert_isotropic(x)))
    cases += [
        ("assert_isotropic", "stripes: sin(2 pi 8 x / 128) added at the noise's RMS, 128^2",
         lambda s: (lambda x: x + x.std() * np.sin(2 * np.pi * 8 * np.arange(128) / 128))(spectral((128, 128))(s)),
         lambda x: T.assert_isotropic(x)),
        ("assert_no_axis_artefacts", "lattice noise (cubic, 8 cells, periodic) 128^2",
         lambda s: noiselab.LatticeNoise(2, rng=s, kernel="cubic", period=8).grid((128, 128), [(0, 8), (0, 8)]),
         lambda x: T.assert_no_axis_artefacts(x)),
        ("assert_seamless", "seam: spectral_noise 128^2 exponent 1.5 cropped to 120 x 128",
         crop(spectral((128, 128), 1.5), (120, 128)), lambda x: T.assert_seamless(x)),
        ("assert_seamless", "seam: spectral_noise 128^2 exponent 1 cropped to 120 x 128",
         crop(spectral((128, 128), 1.0), (120, 128)), lambda x: T.assert_seamless(x)),
        ("assert_seamless", "cut loop: MotionClouds 32 frames cut to 27", crop(cloud((1.0, 0.0)), (27,)),
         lambda x: T.assert_seamless(x, axes=0)),
        ("assert_seamless", "cut loop: snow alpha 16 frames cut to 13", crop(snow_alpha(), (13,)),
         lambda x: T.assert_seamless(x, axes=0)),
        ("assert_motion", "wrong velocity sign: MotionClouds v = (1, 0) asserted as (-1, 0)", cloud((1.0, 0.0)),
         lambda x: T.assert_motion(x, velocity_yx=(0.0, -1.0))),
        ("assert_motion", "wrong direction: MotionClouds v = (1, 0) asserted as (0, 1)", cloud((1.0, 0.0)),
         lambda x: T.assert_motion(x, velocity_yx=(1.0, 0.0))),
        ("assert_tent", "snow falling up: raw snow asserted with direction (0, -1)", snow_raw(),
         lambda x: T.assert_tent(x, 1.0, (2, 16), direction_yx=(-1, 0))),
    ]
    return cases


def fails(check, field):
    try:
        check(field)
    except AssertionError:
        return 1
    return 0


def run(seeds, base=1000):
    """Count the failures of every case over ``seeds`` seeds (the fields drawn once per seed and case)."""
    null_rows, thr_rows, pow_rows = [], [], []
    for name, what, make, check in null_cases():
        c3 = c5 = 0
        for s in range(base, base + seeds):
            x = make(s)
            c3 += fails(lambda f: check(f, 1e-3), x)
            c5 += fails(lambda f: check(f, 0.05), x)
        null_rows.append((name, what, c3, c5))
        print(name, what, c3, c5, flush=True)
    for name, what, make, check in threshold_cases():
        c = sum(fails(check, make(s)) for s in range(base, base + seeds))
        thr_rows.append((name, what, c))
        print(name, what, c, flush=True)
    for name, what, make, check in power_cases():
        c = sum(fails(check, make(s)) for s in range(base, base + seeds))
        pow_rows.append((name, what, c))
        print(name, what, c, flush=True)
    return null_rows, thr_rows, pow_rows


def calibrated_limit(n, p, tail=1e-3):
    """The failure count a test failing with probability ``p`` exceeds with probability below ``tail``."""
    return int(stats.binom.isf(tail, n, p))


def upper95(k, n):
    """Clopper-Pearson 95 % upper bound on a rate from ``k`` of ``n``."""
    return 1.0 if k == n else float(stats.beta.ppf(0.95, k + 1, n - k))


def report(seeds, null_rows, thr_rows, pow_rows, info, cpu):
    lim3, lim5 = calibrated_limit(seeds, 1e-3), calibrated_limit(seeds, 0.05)
    rows = []
    for name, what, c3, c5 in null_rows:
        rows.append((f"`{name}`", what, f"{c3} ({'within' if c3 <= lim3 else 'ABOVE'})", f"{upper95(c3, seeds):.3f}",
                     f"{c5} ({'within' if c5 <= lim5 else 'ABOVE'})", f"{c5 / seeds:.3f}"))
    total3 = sum(r[2] for r in null_rows)
    total5 = sum(r[3] for r in null_rows)
    n_all = seeds * len(null_rows)
    lines = [
        "# noiselab.testing: false-alarm rate and detection power",
        "",
        *header_lines(info),
        f"- CPU time of the run: {cpu:.0f} s",
        "",
        f"## False alarms over {seeds} seeds of fields that hold the property",
        "",
        f"Failures at the default `false_alarm=1e-3` (expected {seeds * 1e-3:.2f} per row; a calibrated test "
        f"exceeds {lim3} with probability < 1e-3) and at `false_alarm=0.05` (expected {seeds * 0.05:.0f}; "
        f"exceeds {lim5} with probability < 1e-3). '95 % bound': Clopper-Pearson upper bound on the rate at 1e-3.",
        "",
        *markdown_table(["assertion", "fields", "fails at 1e-3", "95 % bound", "fails at 0.05", "rate at 0.05"], rows,
                        align="llrrrr"),
        "",
        f"All rows together: {total3} of {n_all} at 1e-3 (rate {total3 / n_all:.4f}, Clopper-Pearson 95 % bound "
        f"{upper95(total3, n_all):.4f}); {total5} of {n_all} at 0.05 (rate {total5 / n_all:.4f}).",
        "",
        f"## Stated thresholds (deterministic fractions of the spectrum): failures over {seeds} seeds at the defaults",
        "",
        *markdown_table(["assertion", "fields", "fails", "rate"],
                        [(f"`{n}`", w, str(c), f"{c / seeds:.3f}") for n, w, c in thr_rows], align="llrr"),
        "",
        f"## Detection power over {seeds} seeds (defaults: `false_alarm=1e-3`, `min_energy=0.9`)",
        "",
        *markdown_table(["assertion", "what breaks the property", "detected", "power"],
                        [(f"`{n}`", w, f"{c} / {seeds}", f"{c / seeds:.3f}") for n, w, c in pow_rows], align="llrr"),
        "",
    ]
    return lines


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=200, help="seeds per case (200 for the report; fewer writes nothing)")
    args = ap.parse_args(argv)
    cmd = "python3 benchmarks/bench_testing.py" + (f" --seeds {args.seeds}" if args.seeds != 200 else "")
    info = run_info(cmd, ["scipy", "noiselab", "powerbox", "colorednoise", "MotionClouds"])
    t0 = time.process_time()
    null_rows, thr_rows, pow_rows = run(args.seeds)
    lines = report(args.seeds, null_rows, thr_rows, pow_rows, info, time.process_time() - t0)
    text = "\n".join(lines)
    if args.seeds >= 200:
        (ROOT / "benchmarks" / "bench_testing.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
