"""noiselab.stimuli: the display, contrast on the screen, phase scrambling, motion clouds."""
from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.fft

import noiselab
from noiselab import Display, analysis, spectral_noise, synthesize
from noiselab.spectral import envelopes as E
from noiselab.stimuli import (amplitude_swap, circular_aperture, cloud_envelope, gaussian_aperture, luminance_for,
                              motion_cloud, phase_scramble, raised_cosine_aperture, to_display)

D8 = Display(32.0, frame_rate=60.0, luminance=(0.5, 100.0), gamma=2.2, bits=8)
D10 = Display(32.0, frame_rate=60.0, luminance=(0.5, 100.0), gamma=2.2, bits=10)


# ---------------------------------------------------------------- Display: units
def test_display_is_frozen_and_exported():
    assert noiselab.Display is Display
    with pytest.raises(AttributeError):
        D8.bits = 10
    assert Display(32.0) == Display(32.0) and hash(Display(32.0)) == hash(Display(32.0))


def _pairs(d):
    return ((d.deg_to_px, d.px_to_deg), (d.px_to_deg, d.deg_to_px), (d.px_per_frame, d.deg_per_second),
            (d.deg_per_second, d.px_per_frame), (d.cycles_per_pixel, d.cycles_per_degree),
            (d.seconds_to_frames, d.frames_to_seconds), (d.frames_to_seconds, d.seconds_to_frames),
            (lambda x: d.cycles_per_frame(x, 256), lambda y: d.cycles_per_degree_from_frame(y, 256)))


def test_conversions_round_trip_exactly_for_power_of_two_factors():
    for ppd in (16.0, 32.0, 64.0, 0.5):
        for rate in (32.0, 64.0, 128.0):
            d = Display(ppd, frame_rate=rate)
            for x in (0.0, 0.1, 0.25, 1.0, 3.0, 7.5, 12.3, -4.4, 1e-7, 123456.789):
                for f, g in _pairs(d):
                    assert g(f(x)) == x


def test_conversions_round_trip_on_lab_values():
    # 6 pixel densities x 6 frame rates x 11 values x 7 conversions = 2,772 round trips (the figure in display.py)
    total = exact = 0
    for ppd in (16.0, 32.0, 40.0, 47.5, 60.0, 64.0):
        for rate in (50.0, 60.0, 75.0, 100.0, 120.0, 144.0):
            d = Display(ppd, frame_rate=rate)
            for x in (0.0, 0.25, 1.0, 2.0, 3.0, 4.0, 7.5, 12.0, 0.1, 0.3, 1.7):
                for f, g in _pairs(d)[:7]:
                    back = g(f(x))
                    total += 1
                    exact += back == x
                    assert abs(back - x) <= math.ulp(x)
    assert total == 2772 and exact / total >= 0.97
    # a whole number of pixels or frames comes back exactly from degrees and seconds
    d = Display(40.0, frame_rate=144.0)
    for n in range(1, 2000):
        assert d.deg_to_px(d.px_to_deg(float(n))) == n and d.seconds_to_frames(d.frames_to_seconds(float(n))) == n


def test_conversions_round_trip_within_one_ulp_for_any_float():
    rng = np.random.default_rng(3)
    worst = 0.0
    for _ in range(2000):
        d = Display(float(rng.uniform(5, 120)), frame_rate=float(rng.uniform(24, 240)))
        x = float(rng.uniform(-50, 50))
        for f, g in _pairs(d):
            worst = max(worst, abs(g(f(x)) - x) / math.ulp(x))
    assert worst <= 1.0
    arr = np.linspace(-3, 3, 101)
    d = Display(47.5, frame_rate=144.0)
    assert np.max(np.abs(d.deg_per_second(d.px_per_frame(arr)) - arr) / np.spacing(np.abs(arr) + 1e-300)) <= 1.0


def test_conversions_values():
    d = Display(32.0, frame_rate=120.0)
    assert d.cycles_per_pixel(4) == 0.125
    assert d.cycles_per_frame(4, 256) == 32.0
    assert d.band((2, 8), 256) == (16.0, 64.0)
    assert d.px_per_frame(7.5) == 2.0
    assert d.pixels(8) == 256 and d.frame_count(0.5) == 60
    arr = d.deg_to_px(np.array([1.0, 2.0]))
    assert arr.tolist() == [32.0, 64.0]
    # snow's c moves flakes of 4 cycles/deg at the stated speed: c / |w| px/frame
    c = d.snow_c(3.0, 4.0)
    assert c / (2 * np.pi * d.cycles_per_pixel(4.0)) == pytest.approx(d.px_per_frame(3.0), rel=1e-12)


def test_from_geometry_pixels_per_degree():
    d = Display.from_geometry(distance_cm=57.0, screen_width_cm=40.0, resolution_px=1920)
    assert d.pixels_per_degree == pytest.approx(1920 / 40.0 * 2 * 57.0 * math.tan(math.radians(0.5)), rel=1e-15)
    # at 57 cm one centimetre is about one degree
    assert d.pixels_per_degree == pytest.approx(48.0, rel=0.01)


# ---------------------------------------------------------------- Display: luminance
def test_gamma_law_and_inverse():
    d = Display(32.0, luminance=(2.0, 90.0), gamma=2.2, bits=8)
    v = np.arange(256)
    L = d.luminance_of(v)
    assert L[0] == 2.0 and L[-1] == 90.0
    assert np.allclose(L, 2.0 + 88.0 * (v / 255) ** 2.2, rtol=1e-15, atol=0)
    assert np.array_equal(d.value_of(L), v.astype(float))   # whole values come back exactly
    assert np.all(np.diff(d.value_of(np.linspace(2.0, 90.0, 1001))) > 0)


def test_from_lut():
    lut = np.cumsum(np.linspace(0.1, 1.0, 16)) + 0.3
    d = Display.from_lut(lut, 40.0, frame_rate=100.0)
    assert d.bits == 4 and d.luminance == (lut[0], lut[-1]) and d.gamma is None
    assert np.array_equal(d.luminance_of(np.arange(16)), lut)
    assert d.value_of(lut[5]) == 5.0


@pytest.mark.parametrize("kwargs, words", [
    (dict(bits=0), "bits must be an int in [1, 16]"),
    (dict(bits=17), "bits must be an int in [1, 16]"),
    (dict(luminance=(-1.0, 100.0)), "luminance (cd/m²)[0] must be in [0, 1e+12]"),
    (dict(luminance=(50.0, 10.0)), "0 <= L_min < L_max"),
    (dict(gamma=0.0), "gamma must be in [0.1, 10]"),
    (dict(frame_rate=0.0), "frame_rate (Hz) must be in (0, 1e+09]"),
])
def test_display_bad_input_names_parameter_and_limit(kwargs, words):
    with pytest.raises(ValueError) as exc:
        Display(32.0, **kwargs)
    assert words in str(exc.value)
    with pytest.raises(ValueError, match=r"pixels_per_degree must be in \(0"):
        Display(0.0)


def test_lut_must_be_monotonic_and_sized():
    with pytest.raises(ValueError, match=r"lut must be strictly increasing \(monotonic\): lut\[2\]"):
        Display.from_lut([0.0, 1.0, 1.0, 2.0], 32.0)
    with pytest.raises(ValueError, match=r"lut must hold 2\*\*bits entries for bits in 1..16"):
        Display.from_lut([0.0, 1.0, 2.0], 32.0)
    with pytest.raises(ValueError, match=r"lut must hold finite luminances in \[0"):
        Display.from_lut([-1.0, 1.0], 32.0)


def test_luminance_of_refuses_values_off_the_display():
    with pytest.raises(ValueError, match=r"values must be display values in \[0, 255\] \(8 bits\)"):
        D8.luminance_of([0, 256])
    with pytest.raises(ValueError, match=r"within the display's range \[0.5, 100\] cd/m²"):
        D8.value_of(120.0)


# ---------------------------------------------------------------- to_display
FIELD = spectral_noise((256, 256), exponent=1.0, band=(4, 64), rng=5, dtype=np.float64)


@pytest.mark.parametrize("display", [D8, D10], ids=["8bit", "10bit"])
@pytest.mark.parametrize("dither", [True, False])
@pytest.mark.parametrize("mean, contrast", [(40.0, 0.05), (50.0, 0.2), (30.0, 0.15)])
def test_rms_contrast_on_the_screen(display, dither, mean, contrast):
    v = to_display(FIELD, display, mean=mean, contrast=contrast, contrast_kind="rms", dither=dither, rng=1)
    assert v.dtype == (np.uint8 if display.bits <= 8 else np.uint16)
    L = display.luminance_of(v)
    assert abs(L.mean() / mean - 1) < 0.01
    assert abs(analysis.rms_contrast(L) / contrast - 1) < 0.02


@pytest.mark.parametrize("display, dither", [(D8, True), (D8, False), (D10, True), (D10, False)])
@pytest.mark.parametrize("mean, contrast", [(50.0, 0.176), (40.0, 0.5), (50.0, 0.98)])
def test_michelson_contrast_on_the_screen(display, dither, mean, contrast):
    v = to_display(FIELD, display, mean=mean, contrast=contrast, contrast_kind="michelson", dither=dither, rng=2)
    L = display.luminance_of(v)
    assert abs(L.mean() / mean - 1) < 0.01
    assert abs(analysis.michelson_contrast(L) / contrast - 1) < 0.02


def test_michelson_8bit_dithered_within_two_percent_at_high_contrast():
    v = to_display(FIELD, D8, mean=50.0, contrast=0.8, contrast_kind="michelson", rng=4)
    L = D8.luminance_of(v)
    assert abs(analysis.michelson_contrast(L) / 0.8 - 1) < 0.02 and abs(L.mean() / 50.0 - 1) < 0.01


def test_luminance_for_is_exact():
    for kind, c in (("rms", 0.2), ("michelson", 0.6), ("michelson", 1.0)):
        L = luminance_for(FIELD, mean=37.0, contrast=c, contrast_kind=kind)
        assert L.mean() == pytest.approx(37.0, rel=1e-12)
        got = L.std() / L.mean() if kind == "rms" else (L.max() - L.min()) / (L.max() + L.min())
        assert got == pytest.approx(c, rel=1e-12)


def test_michelson_one_needs_a_black_display():
    d = Display(32.0, luminance=(0.0, 100.0), bits=10)
    L = d.luminance_of(to_display(FIELD, d, mean=40.0, contrast=1.0, contrast_kind="michelson", rng=0))
    assert analysis.michelson_contrast(L) == 1.0 and abs(L.mean() / 40.0 - 1) < 0.01
    with pytest.raises(ValueError, match=r"needs luminances \[0, .*the display's range is \[0.5, 100\]"):
        to_display(FIELD, D8, mean=50.0, contrast=1.0, contrast_kind="michelson")
    with pytest.raises(ValueError, match="makes the darkest pixel's luminance negative"):
        luminance_for(FIELD, mean=50.0, contrast=0.5)


def test_dithering_keeps_the_expected_luminance_below_one_step():
    x = spectral_noise((48, 48), band=(2, 12), rng=9, dtype=np.float64)
    mean, contrast = 40.0, 0.002
    step = float(D8.step_at(mean))
    L_req = luminance_for(x, mean=mean, contrast=contrast)
    assert np.ptp(L_req) < step   # the whole request lies within one display step (or straddles one)
    avg = np.mean([D8.luminance_of(to_display(x, D8, mean=mean, contrast=contrast, rng=s)) for s in range(64)],
                  axis=0)
    assert np.max(np.abs(avg - L_req)) < 0.2 * step
    # 64 frames drawn from one Generator (independent offsets): unbiased, and within 0.2 step too
    g = np.random.default_rng(11)
    avg_g = np.mean([D8.luminance_of(to_display(x, D8, mean=mean, contrast=contrast, rng=g)) for _ in range(64)],
                    axis=0)
    assert abs(np.mean(avg_g - L_req)) < 0.02 * step and np.max(np.abs(avg_g - L_req)) < 0.2 * step
    # within one image the thresholds are uniform and independent: a flat request half-way between two values
    half = 0.5 * (D8.luminance_of(100) + D8.luminance_of(101))
    flat = D8.luminance_of(to_display(np.r_[np.zeros(40000), 1.0], D8, mean=half, contrast=1e-9, rng=3))[:-1]
    assert np.mean(flat == D8.luminance_of(101)) == pytest.approx(0.5, abs=0.01)
    # without dithering the contrast is lost or doubled: the image has at most two values
    flat = D8.luminance_of(to_display(x, D8, mean=mean, contrast=contrast, dither=False))
    assert np.unique(flat).size <= 2


def test_dither_is_seeded():
    a = to_display(FIELD, D8, mean=40.0, contrast=0.1, rng=7)
    b = to_display(FIELD, D8, mean=40.0, contrast=0.1, rng=7)
    c = to_display(FIELD, D8, mean=40.0, contrast=0.1, rng=8)
    assert np.array_equal(a, b) and not np.array_equal(a, c)


def test_request_the_display_cannot_show():
    with pytest.raises(ValueError) as exc:
        to_display(FIELD, D8, mean=80.0, contrast=0.5, contrast_kind="rms")
    msg = str(exc.value)
    assert "display's range is [0.5, 100]" in msg and "largest rms contrast that fits" in msg
    best = float(msg.rsplit(" ", 1)[1])
    v = to_display(FIELD, D8, mean=80.0, contrast=best * 0.999, contrast_kind="rms")   # the stated limit fits
    assert analysis.rms_contrast(D8.luminance_of(v)) == pytest.approx(best * 0.999, rel=0.02)
    with pytest.raises(ValueError, match=r"mean = 120 cd/m² is outside the display's range \[0.5, 100\]"):
        to_display(FIELD, D8, mean=120.0, contrast=0.1)
    with pytest.raises(ValueError, match=r"contrast \(Michelson\) must be in \(0, 1\]"):
        to_display(FIELD, D8, mean=50.0, contrast=1.2, contrast_kind="michelson")
    with pytest.raises(ValueError, match=r"contrast \(Michelson\) must be in \(0, 1\]"):
        to_display(FIELD, D8, mean=50.0, contrast=0.0, contrast_kind="michelson")
    with pytest.raises(ValueError, match=r"contrast \(RMS\) must be in \(0"):
        to_display(FIELD, D8, mean=50.0, contrast=-0.1)
    with pytest.raises(ValueError, match="field must vary"):
        to_display(np.ones((8, 8)), D8, mean=50.0, contrast=0.1)
    with pytest.raises(TypeError, match="display must be a noiselab.Display"):
        to_display(FIELD, (0, 100), mean=50.0, contrast=0.1)



# a Gaussian 1/f patch: its tails leave a 0.5..100 cd/m² display at mean 50 and RMS contrast 0.25
PINK = spectral_noise((256, 256), exponent=1.0, rng=11, dtype=np.float64)


def test_clip_makes_a_gaussian_field_fit_at_the_requested_contrast():
    with pytest.raises(ValueError) as exc:
        to_display(PINK, D8, mean=50.0, contrast=0.25)
    msg = str(exc.value)
    k = float(msg.split("clip=")[1].split(" ")[0])   # the refusal names the option and a value that fits
    assert 2.0 < k < 6.0 and "% of the samples" in msg
    v, report = to_display(PINK, D8, mean=50.0, contrast=0.25, clip=k, rng=1, full_output=True)
    L = D8.luminance_of(v)
    # the requested contrast holds after clipping (not 0.25 times the clipped field's smaller spread)
    assert L.mean() == pytest.approx(50.0, rel=0.01)
    assert analysis.rms_contrast(L) == pytest.approx(0.25, rel=0.02)
    # the fraction reported is the fraction of samples beyond k standard deviations, counted here
    z = PINK - PINK.mean()
    expected = np.mean(np.abs(z) > k * z.std())
    assert report.clipped_fraction == pytest.approx(expected, abs=1e-12) and 0 < report.clipped_fraction < 1e-3
    assert report.clip == k and D8.luminance[0] <= report.luminance_range[0] < report.luminance_range[1] <= 100.0
    # a tighter clip clips more and still holds the contrast; the clipped pixels sit at the two ends
    v2, r2 = to_display(PINK, D8, mean=50.0, contrast=0.25, clip=2.0, dither=False, full_output=True)
    L2 = D8.luminance_of(v2)
    assert r2.clipped_fraction == pytest.approx(np.mean(np.abs(z) > 2.0 * z.std()), abs=1e-12)
    assert r2.clipped_fraction > 0.03 and analysis.rms_contrast(L2) == pytest.approx(0.25, rel=0.02)
    assert np.mean(L2 >= L2.max() - 1.0) > 0.01   # a pile-up at the clipped ends


def test_clip_without_need_changes_nothing_and_bad_clips_are_named():
    v, report = to_display(FIELD, D8, mean=40.0, contrast=0.1, clip=50.0, rng=3, full_output=True)
    assert report.clipped_fraction == 0.0
    assert np.array_equal(D8.luminance_of(v), D8.luminance_of(to_display(FIELD, D8, mean=40.0, contrast=0.1,
                                                                          rng=3)))
    assert to_display(FIELD, D8, mean=40.0, contrast=0.1, rng=3, full_output=True)[1].clipped_fraction == 0.0
    for bad in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="clip"):
            to_display(FIELD, D8, mean=40.0, contrast=0.1, clip=bad)
    with pytest.raises(TypeError, match="full_output"):
        to_display(FIELD, D8, mean=40.0, contrast=0.1, full_output="yes")
    # a clip that still leaves the display: the refusal says so and names the clip that fits
    with pytest.raises(ValueError, match=r"clipped at clip=8 standard deviations .*clip=\d"):
        to_display(PINK, D8, mean=50.0, contrast=0.25, clip=8.0)


# ---------------------------------------------------------------- apertures
def _radius_deg(n, ppd):
    y, x = np.mgrid[:n, :n] - (n - 1) / 2.0
    return np.hypot(y, x) / ppd


def test_aperture_shapes_in_degrees():
    d = Display(20.0)
    r = _radius_deg(101, 20.0)
    circle = circular_aperture((101, 101), d, diameter_deg=3.0)
    assert np.array_equal(circle, (r <= 1.5).astype(float))
    cos = raised_cosine_aperture((4, 101, 101), d, diameter_deg=4.0, ramp_deg=1.0)   # frames: one window
    assert cos.shape == (101, 101)
    assert np.all(cos[r <= 1.0] == 1.0) and np.all(cos[r >= 2.0] == 0.0)
    ramp = (r > 1.0) & (r < 2.0)
    assert np.allclose(cos[ramp], 0.5 + 0.5 * np.cos(np.pi * (r[ramp] - 1.0)), atol=1e-12)
    assert np.all(np.diff(cos[50, 50:]) <= 0)   # falls monotonically from the centre
    g = gaussian_aperture((101, 101), d, sigma_deg=0.75)
    assert g[50, 50] == 1.0 and g[50, 50 + 15] == pytest.approx(math.exp(-0.5), rel=1e-12)   # 15 px = 1 sigma
    for fn, kw, word in ((circular_aperture, dict(diameter_deg=0.0), "diameter_deg"),
                         (raised_cosine_aperture, dict(diameter_deg=2.0, ramp_deg=1.5), "ramp_deg"),
                         (raised_cosine_aperture, dict(diameter_deg=float("nan"), ramp_deg=0.5), "diameter_deg"),
                         (gaussian_aperture, dict(sigma_deg=-1.0), "sigma_deg")):
        with pytest.raises(ValueError, match=word):
            fn((32, 32), d, **kw)
    with pytest.raises(ValueError, match="shape"):
        circular_aperture((32,), d, diameter_deg=1.0)


BANDED = spectral_noise((128, 128), exponent=0.0, band=(8, 40), rng=21, dtype=np.float64)


@pytest.mark.parametrize("make", [
    lambda s: circular_aperture(s, D10, diameter_deg=3.0),
    lambda s: raised_cosine_aperture(s, D10, diameter_deg=3.5, ramp_deg=0.75),
    lambda s: gaussian_aperture(s, D10, sigma_deg=0.7),
], ids=["circle", "raised-cosine", "gaussian"])
def test_aperture_blends_to_the_mean_and_states_contrast_inside(make):
    mean, c = 40.0, 0.2
    w = make(BANDED.shape)
    # the luminance written, averaged over 64 dither seeds, against the formula computed here:
    # L = mean (1 + c w z / sd_w), z centred on its w-weighted mean, sd_w its w-weighted RMS
    z = BANDED - np.sum(w * BANDED) / w.sum()
    expected = mean * (1 + c * w * z / np.sqrt(np.sum(w * z * z) / w.sum()))
    avg = np.mean([D10.luminance_of(to_display(BANDED, D10, mean=mean, contrast=c, aperture=w, rng=s))
                   for s in range(64)], axis=0)
    assert np.max(np.abs(avg - expected)) < 0.05   # cd/m² (a 10-bit step at 40 cd/m² is about 0.13)
    # outside the window the mean luminance, everywhere (no dithering: one display value, the nearest)
    flat = D10.luminance_of(to_display(BANDED, D10, mean=mean, contrast=c, aperture=w, dither=False))
    if np.any(w == 0):
        out = flat[w == 0]
        assert out.min() == out.max() and abs(out[0] - mean) < 0.1
    # the frame's mean is the requested mean
    assert avg.mean() == pytest.approx(mean, rel=1e-3)


def test_circular_aperture_contrast_is_the_contrast_inside():
    w = circular_aperture(BANDED.shape, D8, diameter_deg=3.0)
    inside = w == 1
    for kind, c, measure in (("rms", 0.15, analysis.rms_contrast), ("michelson", 0.6, analysis.michelson_contrast)):
        L = D8.luminance_of(to_display(BANDED, D8, mean=45.0, contrast=c, contrast_kind=kind, aperture=w, rng=2))
        assert measure(L[inside]) == pytest.approx(c, rel=0.02), kind
        assert L[inside].mean() == pytest.approx(45.0, rel=0.01)
    assert np.ptp(L[~inside]) < 1.0   # outside: the display values around 45 cd/m² only (dithered)


def test_aperture_on_a_video_and_bad_apertures():
    video = noiselab.snow((6, 64, 64), rng=1)
    w = circular_aperture(video.shape, D10, diameter_deg=1.5)
    L = D10.luminance_of(to_display(video, D10, mean=30.0, contrast=0.2, aperture=w, dither=False))
    assert np.ptp(L[:, w == 0]) == 0 and analysis.rms_contrast(L[:, w == 1]) == pytest.approx(0.2, rel=0.03)
    for bad, words in ((np.ones((32, 32)), "aperture must broadcast"), (w * 2, r"aperture must hold weights in \[0, 1\]"),
                       (np.zeros((64, 64)), "aperture is 0 everywhere"), (np.full((64, 64), np.nan), "aperture")):
        with pytest.raises(ValueError, match=words):
            to_display(video, D10, mean=30.0, contrast=0.2, aperture=bad)

def test_to_display_on_a_snow_video():
    video = noiselab.snow((8, 64, 64), rng=0)
    v = to_display(video, D10, mean=30.0, contrast=0.176, contrast_kind="michelson", rng=0)
    assert v.shape == video.shape
    assert analysis.michelson_contrast(D10.luminance_of(v)) == pytest.approx(0.176, rel=0.02)


# ---------------------------------------------------------------- phase scrambling
def _corr(a, b):
    a, b = a - a.mean(), b - b.mean()
    return float(np.sum(a * b) / np.sqrt(np.sum(a * a) * np.sum(b * b)))


@pytest.mark.parametrize("shape, axes", [((128, 128), None), ((127, 130), None), ((16, 32, 33), None),
                                         ((6, 32, 32), (1, 2))])
def test_phase_scramble_keeps_amplitude_and_mean(shape, axes):
    rng = np.random.default_rng(0)
    x = rng.random(shape) + 3.0   # a positive mean (the DC sign must survive)
    s = phase_scramble(x, rng=1, axes=axes)
    ax = tuple(range(len(shape))) if axes is None else axes
    A, B = np.abs(scipy.fft.rfftn(x, axes=ax)), np.abs(scipy.fft.rfftn(s, axes=ax))
    assert np.max(np.abs(A - B)) <= 1e-9 * np.max(A)
    assert np.max(np.abs((A - B) / np.where(A > 0, A, 1))[A > 1e-6 * A.max()]) <= 1e-9
    assert np.allclose(s.mean(axis=ax), x.mean(axis=ax), rtol=1e-12, atol=0)
    assert abs(_corr(x, s)) < 0.05


def test_phase_scramble_of_a_natural_like_image_decorrelates():
    img = spectral_noise((128, 128), exponent=1.0, rng=3, dtype=np.float64) + 5.0
    r = [_corr(img, phase_scramble(img, rng=s)) for s in range(40)]
    assert abs(np.mean(r)) < 0.05          # over seeds the correlation averages out to 0
    s = phase_scramble(img, rng=0)
    assert s.mean() == pytest.approx(5.0, rel=1e-12)
    assert analysis.spectral_slope(s, (4, 32)) == pytest.approx(analysis.spectral_slope(img, (4, 32)), abs=1e-6)


def test_phase_scramble_seeded_and_dtype():
    x = np.random.default_rng(1).random((32, 32)).astype(np.float32)
    a, b = phase_scramble(x, rng=4), phase_scramble(x, rng=4)
    assert a.dtype == np.float32 and np.array_equal(a, b)
    assert not np.array_equal(a, phase_scramble(x, rng=5))


def test_amplitude_swap():
    rng = np.random.default_rng(2)
    a = spectral_noise((64, 64), exponent=2.0, rng=1, dtype=np.float64) + 1.0
    p = rng.random((64, 64))
    s = amplitude_swap(a, p)
    A, S, P = scipy.fft.rfftn(a), scipy.fft.rfftn(s), scipy.fft.rfftn(p)
    assert np.max(np.abs(np.abs(S) - np.abs(A))) <= 1e-9 * np.abs(A).max()
    keep = np.abs(A) > 1e-6 * np.abs(A).max()
    keep[0, 0] = False
    assert np.allclose(np.angle(S[keep] * np.conj(P[keep])), 0, atol=1e-6)
    assert s.mean() == pytest.approx(a.mean(), rel=1e-12)
    with pytest.raises(ValueError, match="must have one shape"):
        amplitude_swap(a, p[:10])


# ---------------------------------------------------------------- synthesize(normalize=)
def test_synthesize_normalize():
    env = lambda wy, wx: 1e-4 * E.annulus(wy, wx, band_cycles_per_sample=(0.05, 0.2))  # noqa: E731
    raw = synthesize((64, 64), env, rng=0, dtype=np.float64)
    assert raw.std() < 1e-3     # the envelope's scale: what a user's check found
    one = synthesize((64, 64), env, rng=0, dtype=np.float64, normalize="sample")
    assert np.mean(one ** 2) == pytest.approx(1.0, rel=1e-12)
    assert np.allclose(one / raw, (one / raw).flat[0])   # the same field, scaled
    ens = np.mean([np.mean(synthesize((64, 64), env, rng=s, dtype=np.float64, normalize="expected") ** 2)
                   for s in range(64)])
    assert ens == pytest.approx(1.0, abs=0.03)
    with pytest.raises(ValueError, match="normalize must be None or one of"):
        synthesize((8, 8), env, normalize="peak")


# ---------------------------------------------------------------- motion clouds
def _mc_envelope(shape, **p):
    """MotionClouds' own envelope_gabor on our half spectrum (T, H, W//2+1), from its (x, y, t) fftshifted grids."""
    MC = pytest.importorskip("MotionClouds")
    T, H, W = shape
    fx, fy, ft = MC.get_grids(W, H, T)
    env = MC.envelope_gabor(fx, fy, ft, **p)                     # (W, H, T), centred
    env = np.fft.ifftshift(env).transpose(2, 1, 0)               # (T, H, W), numpy's order
    return env[..., : W // 2 + 1]


def _not_nyquist(shape):
    T, H, W = shape
    m = np.ones((T, H, W // 2 + 1), bool)
    for ax, n in ((0, T), (1, H)):
        if n % 2 == 0:
            idx = [slice(None)] * 3
            idx[ax] = n // 2
            m[tuple(idx)] = False
    if W % 2 == 0:
        m[..., W // 2] = False   # MotionClouds puts the Nyquist cell at -0.5, rfft at +0.5: aliased, left out
    return m


CLOUDS = [
    dict(sf_0=0.15, B_sf=0.08, theta=np.pi / 4, B_theta=np.pi / 12, V_X=1.0, V_Y=0.5, B_V=0.3),
    dict(sf_0=0.1, B_sf=0.05, theta=0.0, B_theta=np.inf, V_X=-0.5, V_Y=1.5, B_V=0.5),
    dict(sf_0=0.2, B_sf=0.1, theta=-1.0, B_theta=0.3, V_X=0.0, V_Y=0.0, B_V=0.2, loggabor=False),
]


@pytest.mark.parametrize("params", CLOUDS)
def test_cloud_envelope_is_motionclouds_envelope_gabor(params):
    shape = (16, 32, 24)
    ours = cloud_envelope(shape, **params)
    theirs = _mc_envelope(shape, **params)
    m = _not_nyquist(shape)
    scale = theirs[m].max() / ours[m].max()
    assert np.allclose(ours[m] * scale, theirs[m], rtol=1e-9, atol=1e-12 * theirs[m].max())


@pytest.mark.parametrize("params", CLOUDS[:2])
def test_motion_cloud_ensemble_power_matches_motionclouds(params):
    shape = (16, 32, 32)
    n = 24
    power = np.mean([np.abs(scipy.fft.rfftn(motion_cloud(shape, rng=s, dtype=np.float64, **params))) ** 2
                     for s in range(n)], axis=0)
    target = _mc_envelope(shape, **params) ** 2
    m = _not_nyquist(shape)
    target = target / target[m].sum() * power[m].sum()
    strong = m & (target > 0.05 * target[m].max())
    # each cell's power over 24 seeds of a complex Gaussian: relative sd 1/sqrt(24) = 0.2; pooled over the band
    ratio = power[strong].sum() / target[strong].sum()
    assert ratio == pytest.approx(1.0, abs=0.05)
    assert np.corrcoef(power[m], target[m])[0, 1] > 0.95
    assert np.median(power[strong] / target[strong]) == pytest.approx(1.0, abs=0.15)


@pytest.mark.parametrize("v", [(1.0, 0.0), (0.0, 1.0), (-1.5, 0.75), (0.6, -1.2)])
def test_best_velocity_reads_the_cloud_velocity_back(v):
    z = motion_cloud((32, 64, 64), sf_0=0.12, B_sf=0.05, V_X=v[0], V_Y=v[1], B_V=0.05, rng=1, dtype=np.float64)
    got = analysis.best_velocity(z)
    assert np.allclose(got, v, atol=0.05), got


def test_motion_cloud_unit_variance_and_still():
    var = np.mean([motion_cloud((8, 32, 32), sf_0=0.125, B_sf=0.05, rng=s).var() for s in range(16)])
    assert var == pytest.approx(1.0, abs=0.1)
    still = motion_cloud((64, 64), sf_0=0.125, B_sf=0.05, theta=np.pi / 2, B_theta=0.2, rng=0, dtype=np.float64)
    S = np.abs(scipy.fft.rfft2(still)) ** 2
    # theta = pi/2: waves along y, so the energy sits on the ky axis side, not the kx one
    assert S[1:20, :3].sum() > 20 * S[:3, 1:20].sum()


def test_motion_cloud_bad_input():
    with pytest.raises(ValueError, match=r"sf_0 \(cycles/pixel\) must be in \(0, 0.5\]"):
        motion_cloud((4, 16, 16), sf_0=0.7, B_sf=0.1)
    with pytest.raises(ValueError, match=r"B_sf \(cycles/pixel\) must be in \(0"):
        motion_cloud((4, 16, 16), sf_0=0.2, B_sf=0.0)
    with pytest.raises(ValueError, match=r"B_V \(px/frame\) must be in \[0"):
        motion_cloud((4, 16, 16), sf_0=0.2, B_sf=0.1, B_V=-1.0)
    with pytest.raises(ValueError, match=r"B_theta \(radians\) must be >= 1e-6 or np.inf"):
        motion_cloud((4, 16, 16), sf_0=0.2, B_sf=0.1, B_theta=0.0)


# ---------------------------------------------------------------- bandwidths as papers state them
def test_octave_and_hwhm_converters_measure_the_envelopes_half_heights():
    from noiselab.stimuli import B_sf_from_octaves, B_theta_from_hwhm, hwhm_from_B_theta, octaves_from_B_sf

    sf_0 = 0.1
    for octaves in (0.5, 1.0, 1.5, 3.0):
        b = B_sf_from_octaves(sf_0=sf_0, sf_bandwidth_octaves=octaves)
        assert octaves_from_B_sf(sf_0=sf_0, B_sf=b) == pytest.approx(octaves, rel=1e-12)
        # the log-Gabor amplitude band falls to half exactly `octaves` apart, centred (in log f) on sf_0
        f = sf_0 * 2.0 ** (np.array([-0.5, 0.5]) * octaves)
        g = E.log_gabor(2 * np.pi * f, sf_0=sf_0, B_sf=b)
        assert np.allclose(g, 0.5, atol=1e-12)
    for hwhm in (5.0, 15.0, 30.0, 60.0):
        b = B_theta_from_hwhm(orientation_hwhm_deg=hwhm)
        assert hwhm_from_B_theta(B_theta=b) == pytest.approx(hwhm, rel=1e-12)
        a = np.radians(hwhm)   # the orientation band's amplitude at HWHM from theta, either side
        for side in (-1, 1):
            w = E.orientation(np.array(np.sin(0.3 + side * a)), np.array(np.cos(0.3 + side * a)), theta=0.3, B_theta=b)
            assert float(w) == pytest.approx(0.5, abs=1e-12)
    assert hwhm_from_B_theta(B_theta=0.85) == math.inf and hwhm_from_B_theta() == math.inf
    with pytest.raises(ValueError, match="sf_bandwidth_octaves"):
        B_sf_from_octaves(sf_0=0.1, sf_bandwidth_octaves=0.0)
    with pytest.raises(ValueError, match="orientation_hwhm_deg"):
        B_theta_from_hwhm(orientation_hwhm_deg=120.0)


def test_where_a_motion_clouds_power_peaks():
    # the documented peaks, measured on the envelope along the x axis (1024 px: cells of 1/1024 cycles/px)
    sf_0, B_sf = 0.1, 0.05
    s = math.log((sf_0 + B_sf) / sf_0)
    n = 1024
    f = np.arange(n // 2 + 1) / n
    still = cloud_envelope((8, n), sf_0=sf_0, B_sf=B_sf)[0] ** 2          # power per cell, along wy = 0
    assert f[np.argmax(still)] == pytest.approx(sf_0 * math.exp(-s * s), abs=1.0 / n)
    assert f[np.argmax(f * f * still)] == pytest.approx(sf_0, abs=1.0 / n)   # power per octave peaks at sf_0
    assert f[np.argmax(f * still)] == pytest.approx(sf_0 * math.exp(-s * s / 2), abs=1.0 / n)   # per ring
    # drifting: each spatial frequency's power summed over the frames grows with |w| (speed band B_V |w| wide)
    moving = (cloud_envelope((64, 8, n), sf_0=sf_0, B_sf=B_sf, V_X=1.0, B_V=0.5)[:, 0, :] ** 2).sum(axis=0)
    peak = f[np.argmax(moving)]
    assert peak == pytest.approx(sf_0 * math.exp(-s * s / 2), abs=1.5 / n)
    assert peak / f[np.argmax(still)] == pytest.approx(math.exp(s * s / 2), abs=0.02)


def test_theta_is_psychopys_ori_in_radians():
    # theta = 0: the wave vector along x, vertical stripes (PsychoPy's ori = 0 grating); theta > 0 turns the
    # wave vector from +x towards +y, which is down the screen: clockwise, as PsychoPy's ori
    z = motion_cloud((128, 128), sf_0=0.1, B_sf=0.02, theta=math.radians(30.0), B_theta=math.radians(5.0), rng=1)
    p = np.abs(np.fft.fft2(z)) ** 2
    fy, fx = np.meshgrid(np.fft.fftfreq(128), np.fft.fftfreq(128), indexing="ij")
    angle = np.degrees(np.arctan2(fy, fx)) % 180.0          # wave-vector angle, y down, mod 180
    mean = np.degrees(0.5 * np.angle(np.sum(p * np.exp(2j * np.radians(angle))))) % 180.0
    assert mean == pytest.approx(30.0, abs=2.0)
    # on screen (row 0 at the top) the stripes run along the direction perpendicular to the wave vector:
    # stepping along (dx, dy) = (-sin 30, cos 30) the field changes least
    along = np.mean((z[1:, :-1] - z[:-1, 1:]) ** 2)   # a step of (dx, dy) = (+1, -1): 15 deg from the stripes
    across = np.mean((z[1:, 1:] - z[:-1, :-1]) ** 2)  # (+1, +1): 15 deg from the wave vector
    assert along < across


def test_trial_seeds_are_distinct_reproducible_and_numpys_derivation():
    from noiselab.stimuli import trial_seeds

    seeds = trial_seeds(50, rng=2026)
    assert len(set(seeds)) == 50 and all(0 <= s < 2**32 for s in seeds)
    assert seeds == trial_seeds(50, rng=2026)                 # the same on every run
    assert trial_seeds(10, rng=2026) == seeds[:10]             # a longer run extends a shorter one
    assert seeds == [int(c.generate_state(1)[0]) for c in np.random.SeedSequence(2026).spawn(50)]
    assert set(seeds).isdisjoint(trial_seeds(50, rng=2027))
    g1, g2 = np.random.default_rng(5), np.random.default_rng(5)
    assert trial_seeds(4, rng=g1) == trial_seeds(4, rng=g2)   # a Generator: one draw of its stream
    with pytest.raises(ValueError, match="trials"):
        trial_seeds(0, rng=1)
    with pytest.raises(ValueError, match="rng"):
        trial_seeds(3, rng=-1)


def test_trial_seeds_tell_coinciding_words_apart(monkeypatch):
    from noiselab.stimuli import trials as T

    class Same:   # every child's first word is the same: the later trials take further words of their own stream
        def __init__(self, k):
            self.k = k

        def generate_state(self, n):
            return np.array([7] + [1000 * self.k + j for j in range(1, n)], dtype=np.uint32)

    class Seq:
        def __init__(self, entropy):
            pass

        def spawn(self, n):
            return [Same(k) for k in range(n)]

    monkeypatch.setattr(T.np.random, "SeedSequence", Seq)
    assert T.trial_seeds(3, rng=0) == [7, 1001, 2001]


def test_luminance_for_clips_and_windows_as_to_display():
    d = Display(32.0, luminance=(0.5, 100.0), gamma=2.2, bits=8)
    x = spectral_noise((128, 128), exponent=1.0, rng=0)
    w = circular_aperture((128, 128), d, diameter_deg=3.0)
    with pytest.raises(ValueError, match=r"largest RMS contrast it allows is .*clip=[0-9.]+ \(standard deviations\)"):
        luminance_for(x, mean=50.0, contrast=0.45)
    L, report = luminance_for(x, mean=50.0, contrast=0.45, clip=2.0, full_output=True)
    z = (x - x.mean()) / x.std()
    assert report.clip == 2.0 and report.clipped_fraction == pytest.approx(np.mean(np.abs(z) > 2.0), abs=1e-12)
    assert L.std() / L.mean() == pytest.approx(0.45, rel=1e-9) and L.mean() == pytest.approx(50.0, rel=1e-12)
    assert report.luminance_range == (L.min(), L.max()) and L.min() > 0
    # the clipped tails are flat: as many samples at each end as were clipped there
    assert np.count_nonzero(L == L.max()) == np.count_nonzero(z > 2.0)
    L, report = luminance_for(x, mean=50.0, contrast=0.25, clip=3.0, aperture=w, full_output=True)
    assert np.all(L[w == 0] == 50.0)
    inside = L[w == 1]
    assert inside.std() / inside.mean() == pytest.approx(0.25, rel=0.02)
    v, shown = to_display(x, d, mean=50.0, contrast=0.25, clip=3.0, aperture=w, rng=1, full_output=True)
    assert shown == report   # the luminance to_display shows, before it picks display values
    with pytest.raises(ValueError, match="aperture"):
        luminance_for(x, mean=50.0, contrast=0.25, aperture=np.ones((3, 3)))
    with pytest.raises(ValueError, match="clip"):
        luminance_for(x, mean=50.0, contrast=0.25, clip=0.0)


def test_the_guides_running_an_experiment_section_runs(tmp_path, monkeypatch):
    # docs/guide/stimuli.rst as tests/test_readme.py runs it (its python blocks as one script, then its shell
    # blocks), here on its own: the trial set, the aperture, the clipping and the PsychoPy array must all work
    import os
    import subprocess
    import sys
    from pathlib import Path

    from test_readme import rst_blocks

    page = Path(__file__).resolve().parents[1] / "docs" / "guide" / "stimuli.rst"
    text = page.read_text()
    section = text[text.index("Running an experiment"):]
    for needed in ("trial_seeds(", "raised_cosine_aperture(", "clip=3.0", "np.flipud", "visual.ImageStim",
                   "--trials", "--psychopy"):
        assert needed in section, needed
    blocks = rst_blocks(text)
    monkeypatch.chdir(tmp_path)
    exec("\n".join(code for _, lang, code in blocks if lang == "python"), {"__name__": "guide"})
    manifest = __import__("json").loads((tmp_path / "out" / "trials" / "manifest.json").read_text())
    assert [t["seed"] for t in manifest["trials"]] == noiselab.stimuli.trial_seeds(4, rng=2026)
    assert all(abs(t["rms_contrast_inside"] - 0.25) < 0.01 and t["clipped_fraction"] > 0 for t in manifest["trials"])
    shell = [code for _, lang, code in blocks if lang == "bash" and "--trials" in code]
    assert len(shell) == 1
    bindir = str(Path(sys.executable).parent)
    env = dict(os.environ, PATH=bindir + os.pathsep + os.environ.get("PATH", ""),
               PYTHONPATH=str(Path(noiselab.__file__).parents[1]))
    subprocess.run(["bash", "-e", "-c", shell[0]], cwd=tmp_path, env=env, check=True, capture_output=True, timeout=600)
    cli = __import__("json").loads((tmp_path / "out" / "trials" / "pink_manifest.json").read_text())
    assert len(cli["trials"]) == 20 and [t["seed"] for t in cli["trials"]] == noiselab.stimuli.trial_seeds(20, rng=2026)
    first = np.load(tmp_path / "out" / "trials" / cli["trials"][0]["psychopy"])
    assert first.dtype == np.float32 and -1 <= first.min() and first.max() <= 1
