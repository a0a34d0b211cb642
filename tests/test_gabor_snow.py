"""Gabor snow: windows of an endless scene, the tent, the speeds of the parallax law, and no repeat."""
from __future__ import annotations

import math

import numpy as np
import pytest

import noiselab
from noiselab import analysis as A
from noiselab.gabor import OPACITY_SIGMAS, gabor_snow, snow_layers

RNG = np.random.default_rng(7)


def test_a_window_is_the_same_region_of_a_larger_render_at_any_frame():
    for t0 in (0, -37, 10 ** 6):
        big = gabor_snow((6, 40, 48), origin=(t0, -10, 5), rng=3, width=128)
        win = gabor_snow((3, 16, 20), origin=(t0 + 2, -10 + 11, 5 + 17), rng=3, width=128, workers=2)
        assert np.array_equal(win, big[2:5, 11:27, 17:37])
    assert not np.array_equal(gabor_snow((1, 16, 16), rng=3, width=128), gabor_snow((1, 16, 16), rng=4, width=128))


def test_opacity_is_snow_s_map_and_composites():
    raw = gabor_snow((4, 64, 64), rng=1, width=128, rescale=False, dtype=np.float64)
    alpha = gabor_snow((4, 64, 64), rng=1, width=128, beta=1.5, dtype=np.float64)
    np.testing.assert_allclose(alpha, np.clip((raw / OPACITY_SIGMAS + 1) / 2, 0, 1) ** 1.5, rtol=1e-12, atol=1e-15)
    out = noiselab.composite(alpha.astype(np.float32), np.zeros((64, 64), np.uint8), intensity=250)
    assert out.min() >= 0 and out.max() <= 255 and out.std() > 1


@pytest.fixture(scope="module")
def clip():
    """64 frames of 256 x 256 px of the default scene at width 256 (bands 8..64 cycles/frame)."""
    return gabor_snow((64, 256, 256), rng=0, width=256, rescale=False)


def test_energy_lies_on_the_tent(clip):
    """Tent energy >= 0.9 (Hann in time: the clip does not loop, so 1.5 bins of tolerance for the window's lobe)."""
    energy = A.tent_energy(clip, 1.0, (8, 64), window="hann", tol=1.5)
    assert energy >= 0.9
    # the same analysis of a video with no motion finds almost nothing on the tent
    still = np.repeat(clip[:1], 64, axis=0)
    assert A.tent_energy(still, 1.0, (8, 64), window="hann", tol=1.5) < 0.5


def test_each_band_falls_at_the_tent_law(clip):
    """Speed per half-octave band within 5 % of c N / (2 pi f) averaged over the band's 1/f power."""
    bands = A.octave_bands(11.3, 45.3, per_octave=2)
    law = np.array([256 / (2 * math.pi) * (1 / lo - 1 / hi) / math.log(hi / lo) for lo, hi in bands])
    v = A.band_speeds(clip, bands)          # (vx, vy) per band
    np.testing.assert_allclose(v[:, 1] / law, 1.0, atol=0.05)
    assert np.all(np.abs(v[:, 0]) < 0.1 * law)   # straight down


def test_no_repeat_at_any_shift_up_to_four_fft_periods():
    """Correlation of the raw field with itself shifted by up to 4x the FFT snow's block (64, 512, 512) stays <= 0.05."""
    # the upper two octaves of the default band (small kernels: cheap points); 4000 points scattered over
    # 512 frames x 4096 x 4096 px: a correlation's sampling error is 1/sqrt(4000) = 0.016
    layers = snow_layers(rng=5, band=(64, 256))
    pts = RNG.uniform(0.0, 4096.0, (4000, 3)) * np.array([0.125, 1.0, 1.0])

    def field(p):
        return sum(w * g(p, dtype=np.float64) for w, g in layers)

    x = field(pts)
    period = np.array([64.0, 512.0, 512.0])
    shifts = [k * period * e for k in (1, 2, 3, 4) for e in np.eye(3)] + [k * period for k in (1, 2, 3, 4)]
    shifts += list(RNG.uniform(0.0, 4.0, (6, 3)) * period)
    for s in shifts:
        r = np.corrcoef(x, field(pts + np.round(s)))[0, 1]
        assert abs(r) <= 0.05, (s, r)
    # the measure sees a repeat where there is one: the same points, shifted by nothing
    assert np.corrcoef(x, field(pts))[0, 1] == pytest.approx(1.0)


@pytest.mark.parametrize("kw, word", [(dict(origin=(0.5, 0, 0)), "origin"), (dict(origin=(0, 0)), "origin"),
                                      (dict(c=4.0), "c"), (dict(band=(10, 300)), "band"),
                                      (dict(direction_yx=(0, 0)), "direction"), (dict(shape=(4, 4)), "shape"),
                                      (dict(beta=0.0), "beta"), (dict(thickness=2.0), "thickness"),
                                      (dict(width=2), "width"), (dict(pan_yx=(float("nan"), 0)), "pan_yx"),
                                      (dict(density=0.0), "density")])
def test_bad_arguments_name_the_parameter(kw, word):
    args = dict(shape=(2, 8, 8), rng=0)
    args.update(kw)
    with pytest.raises((ValueError, TypeError), match=word):
        gabor_snow(**args)


def test_motion_cloud_moves_at_its_velocity_and_spreads_with_its_bandwidth():
    from noiselab.gabor import motion_cloud_noise

    narrow = motion_cloud_noise(sf_0=0.1, B_sf=0.04, V_X=1.0, V_Y=0.5, B_V=0.05, rng=2)
    wide = motion_cloud_noise(sf_0=0.1, B_sf=0.04, V_X=1.0, V_Y=0.5, B_V=1.0, rng=2)
    a = narrow.grid((32, 96, 96), origin=(10 ** 6, 0, 0), dtype=np.float64)
    b = wide.grid((32, 96, 96), origin=(10 ** 6, 0, 0), dtype=np.float64)
    vx, vy = A.best_velocity(a, band=(4, 20))
    assert abs(vx - 1.0) < 0.1 and abs(vy - 0.5) < 0.1
    on_a = A.motion_energy(a, velocity_yx=(0.5, 1.0), tol=1.5, band=(4, 20), window="hann")
    on_b = A.motion_energy(b, velocity_yx=(0.5, 1.0), tol=1.5, band=(4, 20), window="hann")
    assert on_a > 0.8 and on_b < on_a - 0.2, (on_a, on_b)
    with pytest.raises(ValueError, match="B_V"):
        motion_cloud_noise(sf_0=0.1, B_sf=0.04, B_V=-1.0)


@pytest.mark.parametrize("chunks", [(2, 16, 16), (3, (10, 22), -1), 7])
def test_chunked_gabor_snow_is_the_in_memory_video_for_any_chunking(chunks):
    pytest.importorskip("dask")
    whole = gabor_snow((5, 32, 32), origin=(1000, -7, 3), rng=4)
    lazy = gabor_snow((5, 32, 32), origin=(1000, -7, 3), rng=4, chunks=chunks)
    assert lazy.shape == whole.shape and lazy.dtype == whole.dtype
    assert np.array_equal(lazy.compute(), whole)


def test_chunked_gabor_grid_is_the_in_memory_grid():
    pytest.importorskip("dask")
    from noiselab.gabor import GaborNoise

    noise = GaborNoise([[0.05, 0.02], [0.0, 0.1]], bandwidth=0.02, rng=2)
    whole = noise.grid((40, 30), origin=(5, -3))
    assert np.array_equal(noise.grid((40, 30), origin=(5, -3), chunks=(16, (10, 20))).compute(), whole)


@pytest.mark.parametrize("field, beta, error, word", [
    (np.zeros(4), float("nan"), ValueError, "beta"),
    (np.zeros(4), 0.0, ValueError, "beta"),
    (np.zeros(4, dtype=np.float32), 1.5, TypeError, "field"),
    ([0.0, 1.0], 1.5, TypeError, "field"),
])
def test_snow_opacity_refuses_bad_input_naming_it(field, beta, error, word):
    from noiselab.gabor import snow_opacity

    with pytest.raises(error, match=word):
        snow_opacity(field, beta=beta)
