"""The analysers on signals whose answer is known in closed form.

Every test field is synthesised here with numpy alone (no noiselab
generator), so a failure points at the instrument, not at the thing measured.
"""
import numpy as np
import pytest

from noiselab import analysis as A
import noiselab


# ---------------------------------------------------------------- helpers
def power_law_field(shape, alpha, seed=0, random_amplitude=True):
    """Real field whose radially averaged amplitude falls as f**-alpha (f in cycles/frame), random phase."""
    rng = np.random.default_rng(seed)
    n = shape[-1]  # cycles/frame = cycles per frame width, as in noiselab
    grids = [np.fft.fftfreq(s, 1.0 / s) * (n / s) for s in shape[:-1]]
    grids.append(np.arange(shape[-1] // 2 + 1) * (n / shape[-1]))
    r2 = 0.0
    for i, g in enumerate(grids):
        sh = [1] * len(shape)
        sh[i] = g.size
        r2 = r2 + g.reshape(sh) ** 2
    f = np.sqrt(r2)
    f.flat[0] = 1.0
    amp = f ** -alpha
    amp.flat[0] = 0.0
    if random_amplitude:
        coef = rng.standard_normal(f.shape) + 1j * rng.standard_normal(f.shape)
    else:
        coef = np.exp(2j * np.pi * rng.random(f.shape))
    return np.fft.irfftn(amp * coef, s=shape, axes=tuple(range(len(shape))))


def fourier_shift_video(image, velocity, frames):
    """Translate ``image`` by ``velocity * t`` (px, sub-pixel allowed) with the Fourier shift theorem."""
    h, w = image.shape
    ky = np.fft.fftfreq(h)[:, None]
    kx = np.fft.fftfreq(w)[None, :]
    spec = np.fft.fft2(image)
    vx, vy = velocity
    return np.stack([np.fft.ifft2(spec * np.exp(-2j * np.pi * (kx * vx + ky * vy) * t)).real for t in range(frames)])


def band_texture(n, band, seed):
    """Random periodic texture with its power in the annulus ``band`` (cycles/frame)."""
    rng = np.random.default_rng(seed)
    ky = np.fft.fftfreq(n, 1.0 / n)[:, None]
    kx = np.fft.rfftfreq(n, 1.0 / n)[None, :]
    r = np.hypot(kx, ky)
    mask = (r >= band[0]) & (r <= band[1])
    coef = mask * (rng.standard_normal(r.shape) + 1j * rng.standard_normal(r.shape))
    return np.fft.irfft2(coef, s=(n, n))


def tent_video(shape, c, band, direction=(0.0, 1.0), pan=(0.0, 0.0), seed=0, count=300):
    """A falling-snow-like video: random gratings in ``band``, each moving at c/|w| along ``direction`` (+ pan).

    Each grating's temporal frequency is the nearest whole cycle per video, so
    the video loops and its energy sits within half a cell of the tent.
    """
    t_len, h, w = shape
    rng = np.random.default_rng(seed)
    d = np.asarray(direction, float) / np.hypot(*direction)
    t = np.arange(t_len)[:, None, None]
    y = np.arange(h)[None, :, None]
    x = np.arange(w)[None, None, :]
    video = np.zeros(shape)
    for _ in range(count):
        while True:
            kx, ky = rng.integers(-band[1], band[1] + 1, size=2)
            if band[0] <= np.hypot(kx, ky) <= band[1]:
                break
        wx, wy = 2 * np.pi * kx / w, 2 * np.pi * ky / h
        speed = c / np.hypot(wx, wy)
        wt = -(speed * d[0] + pan[0]) * wx - (speed * d[1] + pan[1]) * wy
        kt = np.round(wt * t_len / (2 * np.pi))
        video += rng.random() * np.cos(2 * np.pi * (kx * x / w + ky * y / h + kt * t / t_len) + rng.random() * 2 * np.pi)
    return video


# ---------------------------------------------------------------- power spectrum
@pytest.mark.parametrize("shape", [(257,), (64, 48), (33, 40), (9, 16, 15)])
def test_parseval_total_is_the_variance(shape):
    x = np.random.default_rng(1).standard_normal(shape) * 3 + 7
    spec = A.power_spectrum(x)
    assert spec.total == pytest.approx(x.var(), rel=1e-10)
    full = spec.full()
    assert full.shape == x.shape
    expected = np.abs(np.fft.fftn(x - x.mean())) ** 2 / x.size**2
    np.testing.assert_allclose(full, expected, rtol=1e-9, atol=1e-14)
    assert spec.mean == pytest.approx(7, abs=0.5)
    assert full.flat[0] == pytest.approx(0, abs=1e-20)  # DC removed


def test_float32_input_stays_float32_and_agrees_with_float64():
    x = np.random.default_rng(2).standard_normal((64, 64))
    p64 = A.power_spectrum(x).power
    p32 = A.power_spectrum(x.astype(np.float32)).power
    assert p32.dtype == np.float32 and p64.dtype == np.float64
    np.testing.assert_allclose(p32, p64, rtol=2e-3, atol=1e-9 * p64.max())


def test_hann_window_keeps_variance_and_cuts_leakage():
    rng = np.random.default_rng(3)
    white = rng.standard_normal((256, 256))
    assert A.power_spectrum(white, window="hann").total == pytest.approx(white.var(), rel=0.03)
    # a sinusoid that does not fit the frame (10.5 cycles): leakage far from its frequency
    x = np.arange(256)
    img = np.cos(2 * np.pi * 10.5 * x / 256)[None, :] * np.ones((256, 1))
    for window, lo, hi in ((None, 1e-2, 1), ("hann", 0, 1e-4)):
        rs = A.radial_spectrum(img, window=window)
        far = np.abs(rs.centers - 10.5) > 5
        frac = rs.energy[far].sum() / rs.energy.sum()
        assert lo < frac < hi, (window, frac)


# ---------------------------------------------------------------- radial spectrum
def test_radial_spectrum_of_two_sinusoids_puts_their_power_in_their_bins():
    y, x = np.mgrid[:128, :128]
    img = 2.0 * np.cos(2 * np.pi * 5 * x / 128) + 0.5 * np.sin(2 * np.pi * (12 * y) / 128)
    rs = A.radial_spectrum(img)
    assert rs.total == pytest.approx(2.0**2 / 2 + 0.5**2 / 2)
    e = dict(zip(rs.centers.round(6), rs.energy))
    assert e[5.0] == pytest.approx(2.0, rel=1e-9)
    assert e[12.0] == pytest.approx(0.125, rel=1e-9)
    assert sum(v for k, v in e.items() if k not in (5.0, 12.0)) < 1e-20


def test_radial_counts_are_ring_areas_and_white_noise_is_flat_with_exponential_scatter():
    white = np.random.default_rng(4).standard_normal((256, 256))
    rs = A.radial_spectrum(white)
    assert rs.centers[0] == 1 and rs.centers[-1] == 128
    ring = rs.centers > 20
    np.testing.assert_allclose(rs.counts[ring], 2 * np.pi * rs.centers[ring], rtol=0.1)
    # flat: every ring holds about 1 / (number of cells) of the variance per cell
    np.testing.assert_allclose(rs.power[ring], white.var() / white.size, rtol=0.25)
    # power of a Gaussian field's cell is exponential: its variance is its mean squared
    big = rs.counts > 300
    assert np.median(rs.variance[big] / rs.power[big] ** 2) == pytest.approx(1.0, abs=0.15)


def test_log_bins_are_geometric_and_cover_the_band():
    rs = A.radial_spectrum(np.random.default_rng(5).standard_normal((128, 128)), log=True)
    ratios = rs.edges[1:] / rs.edges[:-1]
    np.testing.assert_allclose(ratios, ratios[0])
    assert ratios[0] == pytest.approx(2 ** (1 / 8), rel=1e-6)
    assert np.all((rs.centers >= rs.edges[0]) & (rs.centers <= rs.edges[-1]))
    assert np.all(np.isfinite(rs.power)) and np.all(rs.counts > 0)


def test_video_radial_over_spatial_axes_averages_the_frames():
    rng = np.random.default_rng(6)
    video = rng.standard_normal((4, 32, 32))
    rs = A.radial_spectrum(video, axes=(-2, -1), fmax=16 * np.sqrt(2))
    assert rs.total == pytest.approx(np.mean([(f - video.mean()).var() + (f.mean() - video.mean()) ** 2 for f in video]) - 0, rel=0.05)
    per_frame = [A.radial_spectrum(f - video.mean() + 0.0).power for f in video]
    assert rs.power[5] == pytest.approx(np.mean([p[5] for p in per_frame]), rel=1e-6)


def test_spatiotemporal_spectrum_finds_a_drifting_grating():
    t, y, x = np.mgrid[:16, :64, :64]
    # 6 cycles/frame along x, drifting at +2 px/frame: w_t = -v w_x -> -(2 * 6 / 64) * 16 = -3 cycles/video
    video = np.cos(2 * np.pi * (6 * (x - 2 * t) / 64))
    st = A.spatiotemporal_spectrum(video)
    assert st.power.shape == (16, st.centers.size)
    it, ib = np.unravel_index(np.argmax(st.power), st.power.shape)
    assert st.centers[ib] == 6
    # the conjugate pair carries +-3 equally: power at +3 and -3 cycles/video
    p3 = st.power[list(st.temporal).index(3), ib]
    pm3 = st.power[list(st.temporal).index(-3), ib]
    assert p3 == pytest.approx(pm3) and p3 > 0
    assert abs(st.temporal[it]) == 3
    assert np.sum(st.power * st.counts) == pytest.approx(st.total)


def test_band_energy_fraction():
    y, x = np.mgrid[:64, :64]
    img = np.cos(2 * np.pi * 4 * x / 64) + np.cos(2 * np.pi * 20 * y / 64)
    assert A.band_energy(img, (3, 5)) == pytest.approx(0.5)
    assert A.band_energy(img, (3, 25)) == pytest.approx(1.0)
    assert A.band_energy(img, (6, 18)) == pytest.approx(0.0, abs=1e-20)


# ---------------------------------------------------------------- 1/f slope
@pytest.mark.parametrize("alpha", [0.5, 1.0, 1.5, 2.0])
def test_slope_recovered_within_0_05_at_512(alpha):
    img = power_law_field((512, 512), alpha, seed=int(alpha * 10))
    fit = A.spectral_slope(img, band=(4, 128))
    assert abs(fit + alpha) < 0.05, (alpha, float(fit), fit.error)
    assert 0 < fit.error < 0.05
    assert fit.power_slope == pytest.approx(2 * float(fit))
    assert fit.band == (4.0, 128.0)


def test_slope_in_1d_and_3d_and_non_square():
    assert abs(A.spectral_slope(power_law_field((4096,), 1.0, seed=1), (8, 1024)) + 1) < 0.08
    assert abs(A.spectral_slope(power_law_field((64, 64, 64), 1.5, seed=2), (4, 24)) + 1.5) < 0.05
    assert abs(A.spectral_slope(power_law_field((256, 512), 1.0, seed=3), (4, 128)) + 1) < 0.05


def test_hann_window_rescues_the_slope_of_a_non_periodic_crop():
    big = power_law_field((1024, 1024), 2.0, seed=7)
    crop = big[100:356, 300:556]
    plain = A.spectral_slope(crop, (4, 64))
    tapered = A.spectral_slope(crop, (4, 64), window="hann")
    assert abs(tapered + 2.0) < 0.15
    assert abs(plain + 2.0) > 2 * abs(tapered + 2.0)  # the edge jump flattens the plain estimate


def test_octave_energy_is_flat_for_1_over_f_and_not_for_steeper():
    flat = A.octave_energy(power_law_field((512, 512), 1.0, random_amplitude=False), (4, 256))
    assert len(flat.energy) == 6
    assert flat.spread < 0.1
    # 6 of the field's ~8.5 equal octaves (1 cycle/frame to the corners) lie in 4..256
    assert 0.6 < flat.energy.sum() < 0.8
    steep = A.octave_energy(power_law_field((512, 512), 1.5, random_amplitude=False), (4, 256))
    assert steep.spread > 1.0
    assert np.all(np.diff(steep.energy) < 0)


# ---------------------------------------------------------------- isotropy
def oriented_noise(n, angle_deg, width_deg=8.0, seed=0):
    rng = np.random.default_rng(seed)
    ky = np.fft.fftfreq(n, 1.0 / n)[:, None]
    kx = np.fft.rfftfreq(n, 1.0 / n)[None, :]
    theta = np.arctan2(ky, kx)
    d = np.angle(np.exp(2j * (theta - np.deg2rad(angle_deg)))) / 2  # orientation difference mod 180
    env = np.exp(-0.5 * (d / np.deg2rad(width_deg)) ** 2) / np.maximum(np.hypot(kx, ky), 1)
    return np.fft.irfft2(env * (rng.standard_normal(env.shape) + 1j * rng.standard_normal(env.shape)), s=(n, n))


def test_isotropic_noise_has_near_zero_anisotropy():
    assert A.anisotropy(power_law_field((512, 512), 1.0, seed=8)) < 0.03
    assert A.anisotropy(np.random.default_rng(9).standard_normal((256, 256))) < 0.03


def test_stripes_with_one_percent_noise_read_anisotropic_whatever_the_noise_floor():
    rng = np.random.default_rng(12)
    y, x = np.mgrid[:256, :256]
    for noise in (0.01, 0.1):
        stripes = np.sin(2 * np.pi * x / 16) + noise * rng.standard_normal((256, 256))
        o = A.orientation_energy(stripes)
        assert o.index > 0.9 and abs((o.dominant + 90) % 180 - 90) < 1, (noise, o.index, o.dominant)
        # whitened ring by ring, the one striped ring is outvoted by the rings of noise (the old index)
        assert A.orientation_energy(stripes, whiten="ring").index < 0.05


def test_a_band_of_oriented_energy_over_a_noise_floor_reads_anisotropic():
    # one octave (16-32 cycles/frame) of energy within 3 degrees of one orientation, plus 1 % white noise
    n, rng = 256, np.random.default_rng(13)
    ky, kx = np.fft.fftfreq(n, 1.0 / n)[:, None], np.fft.rfftfreq(n, 1.0 / n)[None, :]
    r, theta = np.hypot(kx, ky), np.arctan2(ky, kx)
    env = (r >= 16) & (r < 32) & (np.abs(np.angle(np.exp(2j * (theta - 0.5)))) / 2 < 0.05)
    img = np.fft.irfft2(env * (rng.standard_normal(env.shape) + 1j * rng.standard_normal(env.shape)), s=(n, n))
    img = img / img.std() + 0.01 * rng.standard_normal((n, n))
    o = A.orientation_energy(img)
    assert o.index > 0.9 and abs(o.dominant - np.rad2deg(0.5)) < 2


@pytest.mark.parametrize("exponent", [1.0, 2.0, 3.0])
def test_isotropic_power_law_fields_read_isotropic_not_judged_by_their_lowest_cells(exponent):
    img = noiselab.spectral_noise((256, 256), exponent=exponent, rng=14)
    assert A.anisotropy(img) < 0.1
    if exponent >= 2:  # unwhitened, the few lowest rings decide (and their handful of cells is far from isotropic)
        assert A.orientation_energy(img, whiten=False).index > 2 * A.anisotropy(img)


def test_ring_anisotropy_reads_the_periodogram_floor_and_the_striped_ring():
    rng = np.random.default_rng(15)
    for k in (1, 4, 16):  # K averaged white-noise periodograms: var / mean**2 = 1 / K
        ra = A.ring_anisotropy(rng.standard_normal((k, 128, 128) if k > 1 else (128, 128)))
        assert ra.periodograms == k and ra.floor_db == pytest.approx(-10 * np.log10(k))
        assert abs(ra.mean_db - ra.floor_db) < 0.6, (k, ra.mean_db)
    y, x = np.mgrid[:128, :128]
    ra = A.ring_anisotropy(np.sin(2 * np.pi * 8 * x / 128) + 0.01 * rng.standard_normal((128, 128)))
    striped = ra.db[ra.centers == 8][0]
    # two cells of the ring's 2 pi 8 ~ 50 hold everything: var / mean**2 ~ 50 / 2 - 1, about 14 dB
    assert 12 < striped < 16 and np.median(ra.db) < 1
    with pytest.raises(ValueError, match="min_cells"):
        A.ring_anisotropy(x, min_cells=1)


@pytest.mark.parametrize("angle", [0.0, 30.0, 75.0, 120.0])
def test_rotated_oriented_pattern_keeps_its_index_and_turns_its_orientation(angle):
    o = A.orientation_energy(oriented_noise(256, angle, seed=int(angle)))
    ref = A.orientation_energy(oriented_noise(256, 0.0, seed=1))
    assert o.index > 0.6
    assert o.index == pytest.approx(ref.index, abs=0.05)
    err = (o.dominant - angle + 90) % 180 - 90
    assert abs(err) < 3, (angle, o.dominant)
    assert o.angles[np.argmax(o.energy)] == pytest.approx(angle, abs=180 / 36)


def test_spatially_rotated_grating_turns_the_dominant_orientation():
    from scipy.ndimage import rotate

    y, x = np.mgrid[:256, :256]
    grating = np.cos(2 * np.pi * 16 * x / 256)
    for deg in (0, 25, 60):
        img = rotate(grating, deg, reshape=False, order=3, mode="reflect")[64:192, 64:192]
        o = A.orientation_energy(img, window="hann", whiten=False)
        assert o.index > 0.8
        # numpy rotate turns the image counterclockwise on screen (y down): the wave vector goes to -deg
        assert abs((o.dominant + deg + 90) % 180 - 90) < 3, (deg, o.dominant)


def test_axis_aligned_cross_is_seen_by_the_fourfold_moment():
    rng = np.random.default_rng(10)
    ky = np.fft.fftfreq(256, 1 / 256)[:, None]
    kx = np.fft.rfftfreq(256, 1 / 256)[None, :]
    cross = np.exp(-np.minimum(np.abs(kx), np.abs(ky)) / 4.0)
    img = np.fft.irfft2(cross * (rng.standard_normal(cross.shape) + 1j * rng.standard_normal(cross.shape)), s=(256, 256))
    o = A.orientation_energy(img)
    assert o.m2 < 0.05 and o.m4 > 0.3 and o.index == o.m4
    assert o.axis_ratio > 3


# ---------------------------------------------------------------- motion
RNG_IMAGE = np.random.default_rng(11).random((32, 32))


def test_integer_translation_lies_on_its_motion_plane_with_the_right_sign():
    # +2 px/frame right (x, axis 2) and 1 px/frame up (-y): loops after 32 frames
    video = np.stack([np.roll(RNG_IMAGE, (-t, 2 * t), axis=(0, 1)) for t in range(32)])
    assert A.motion_energy(video, velocity_yx=(-1, 2), tol=0.5) == pytest.approx(1.0, abs=1e-9)
    assert A.motion_energy(video, velocity_yx=(1, -2), tol=0.5) < 0.15  # the opposite motion
    assert A.motion_energy(video, velocity_yx=(0, 0), tol=0.5) < 0.15
    np.testing.assert_allclose(A.best_velocity(video), [2, -1], atol=1e-9)
    np.testing.assert_allclose(A.best_velocity(video, window=None), [2, -1], atol=1e-9)


def test_subpixel_translation_is_recovered_exactly():
    # looping: 0.5 * 128 = 64 px, -0.25 * 128 = -32 px over the video (no power at Nyquist, where
    # a half-pixel shift of a real image is not real)
    video = fourier_shift_video(band_texture(32, (1, 12), 12), (0.5, -0.25), 128)
    assert A.motion_energy(video, velocity_yx=(-0.25, 0.5), tol=0.5) == pytest.approx(1.0, abs=1e-9)
    np.testing.assert_allclose(A.best_velocity(video), [0.5, -0.25], atol=1e-9)
    # not looping: the temporal Hann window keeps the estimate exact and the plane within ~2 cells
    video = fourier_shift_video(band_texture(32, (1, 12), 13), (0.3, 0.7), 24)
    np.testing.assert_allclose(A.best_velocity(video), [0.3, 0.7], atol=1e-9)
    assert A.motion_energy(video, velocity_yx=(0.7, 0.3), tol=2, window="hann") > 0.97
    assert A.motion_energy(video, velocity_yx=(-0.7, -0.3), tol=2, window="hann") < 0.5


def test_fast_translation_beyond_temporal_aliasing_is_unwrapped():
    video = np.stack([np.roll(RNG_IMAGE, (5 * t, -7 * t), axis=(0, 1)) for t in range(32)])
    np.testing.assert_allclose(A.best_velocity(video), [-7, 5], atol=1e-9)
    assert A.motion_energy(video, velocity_yx=(5, -7), tol=0.5) == pytest.approx(1.0, abs=1e-9)


def test_band_speeds_of_a_video_shifted_by_a_known_amount_per_band():
    low = band_texture(64, (4, 8), seed=1)
    high = band_texture(64, (16, 28), seed=2)
    video = fourier_shift_video(low, (0.0, 2.0), 32) + fourier_shift_video(high, (-0.5, 0.25), 32)
    speeds = A.band_speeds(video, [(4, 8), (16, 32)])
    assert speeds.shape == (2, 2)
    np.testing.assert_allclose(speeds, [[0.0, 2.0], [-0.5, 0.25]], atol=1e-6)
    prof = A.speed_profile(video, [(4, 8), (16, 32)])
    assert np.all(prof.coherence > 0.999)
    assert prof.energy.sum() == pytest.approx(1.0, abs=1e-6)
    with pytest.raises(ValueError, match=r"bands\[0\].*Nyquist"):
        A.band_speeds(video, [(4, 100)])
    with pytest.raises(ValueError, match="holds no power"):
        A.band_speeds(video, [(10, 14)])


def test_tent_energy_and_parallax_of_a_synthetic_tent():
    c, band = 1.2, (4, 16)
    video = tent_video((32, 64, 64), c, band, seed=3)
    assert A.tent_energy(video, c, band, thickness=0, tol=0.5) == pytest.approx(1.0, abs=1e-9)
    assert A.tent_energy(video, c, band, direction_yx=(-1, 0), thickness=0, tol=0.5) < 0.3  # falling up is another tent
    assert A.tent_energy(video, c, band, direction_yx=(0, 1), thickness=0, tol=0.5) < 0.3
    assert A.tent_energy(video, c / 3, band, thickness=0, tol=0.5) < 0.5
    assert A.tent_energy(video, c, (4, 8), thickness=0, tol=0.5) < 0.8  # the band counts
    prof = A.speed_profile(video, A.octave_bands(4, 16, 2))
    # falling down: vy > 0, vx ~ 0; speed x |w| = c (motion parallax)
    assert np.all(prof.velocity[:, 1] > 0)
    assert np.all(np.abs(prof.velocity[:, 0]) < 0.1 * prof.velocity[:, 1])
    np.testing.assert_allclose(prof.parallax, c, rtol=0.15)
    assert prof.speed[0] > 1.5 * prof.speed[-1]


def test_tent_in_a_rotated_direction_and_sheared_tent():
    c, band = 1.0, (4, 16)
    d = (1.0, 1.0)
    video = tent_video((32, 64, 64), c, band, direction=d, seed=4)
    assert A.tent_energy(video, c, band, direction_yx=d[::-1], thickness=0, tol=0.5) == pytest.approx(1.0, abs=1e-9)
    assert A.tent_energy(video, c, band, thickness=0, tol=0.5) < 0.5
    v = A.best_velocity(video)
    assert v[0] > 0 and v[1] > 0 and v[0] == pytest.approx(v[1], rel=0.1)
    panned = tent_video((32, 64, 64), c, band, pan=(0.5, 0.0), seed=5)
    assert A.sheared_tent_energy(panned, c, band, pan_yx=(0.0, 0.5), thickness=0, tol=0.5) == pytest.approx(1.0, abs=1e-9)
    assert A.tent_energy(panned, c, band, thickness=0, tol=0.5) < 0.5
    assert A.best_velocity(panned)[0] == pytest.approx(0.5, abs=0.1)


# ---------------------------------------------------------------- seams
def test_loop_seam_is_one_for_a_perfect_loop_and_large_for_a_cut():
    loop = fourier_shift_video(band_texture(32, (2, 6), 3), (0.5, 0.25), 128)
    assert A.loop_seam(loop) == pytest.approx(1.0, abs=1e-9)
    assert A.loop_seam(loop[:100]) > 3


def test_loop_seam_takes_colour_videos_as_documented():
    t = np.arange(24)[:, None, None]
    x = np.arange(32)[None, None, :]
    loop = np.cos(2 * np.pi * (x / 32 - t / 24)) * np.ones((1, 8, 1))
    rgb = np.stack([loop, 0.5 * loop, np.roll(loop, 3, axis=2)], axis=-1)   # (T, H, W, 3)
    assert A.loop_seam(rgb) == pytest.approx(1.0, abs=1e-9)
    cut = rgb[:17]
    # the colour cost is the RMS over all three channels: the steps of the three channels pooled
    steps = [np.sqrt(np.mean((cut[i + 1] - cut[i]) ** 2)) for i in range(16)]
    assert A.loop_seam(cut) == pytest.approx(np.sqrt(np.mean((cut[0] - cut[-1]) ** 2)) / np.mean(steps), rel=1e-12)
    assert A.loop_seam(cut) > 3
    with pytest.raises(ValueError, match=r"video must be \(T, H, W\) or a colour \(T, H, W, 3\)"):
        A.loop_seam(np.zeros((4, 8, 8, 2)))


def test_tile_seam_of_periodic_and_cropped_textures():
    tex = band_texture(128, (2, 10), 4)
    assert A.tile_seam(tex) == pytest.approx(1.0, abs=0.25)
    assert A.tile_seam(np.tile(tex, (2, 3)), tile=128) == pytest.approx(1.0, abs=0.25)
    assert A.tile_seam(tex[:90, :100]) > 3
    assert A.tile_seam(np.tile(tex[:90, :100], (2, 2)), tile=(90, 100)) > 3
    with pytest.raises(ValueError, match="larger than the image"):
        A.tile_seam(tex, tile=200)


# ---------------------------------------------------------------- contrast
def test_michelson_and_rms_contrast_with_and_without_mask():
    img = np.array([[50.0, 150.0], [100.0, 100.0]])
    assert A.michelson_contrast(img) == pytest.approx(0.5)
    mask = np.array([[False, False], [True, True]])
    assert A.michelson_contrast(img, mask) == 0.0
    assert A.rms_contrast(img) == pytest.approx(np.std(img) / 100.0)
    assert A.rms_contrast(img[0]) == pytest.approx(0.5)
    video = np.stack([img, 2 * img])
    assert A.michelson_contrast(video, mask=np.array([[True, True], [False, False]])) == pytest.approx((300 - 50) / 350)
    with pytest.raises(ValueError, match="non-negative"):
        A.michelson_contrast(img - 80)
    with pytest.raises(ValueError, match="selects no pixel"):
        A.rms_contrast(img, np.zeros((2, 2), bool))
    with pytest.raises(ValueError, match="does not match"):
        A.rms_contrast(img, np.ones((3, 3), bool))
    with pytest.raises(ValueError, match="finite"):
        A.rms_contrast([1.0, np.nan])


# ---------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "field, exc, match",
    [
        (np.zeros((0, 8)), ValueError, "empty"),
        (np.full((32, 32), 3.0), ValueError, "constant"),
        (np.where(np.eye(32) > 0, np.nan, 1.0), ValueError, "NaN"),
        (np.ones((2, 8, 8, 8)), ValueError, "4-D"),
        (np.ones((3, 3)), ValueError, "too small"),
        (np.ones((16, 16)) * 1j, TypeError, "complex"),
    ],
)
def test_bad_fields_get_clear_errors(field, exc, match):
    with pytest.raises(exc, match=match):
        A.spectral_slope(field)
    with pytest.raises(exc, match=match):
        A.radial_spectrum(field)


def test_slope_never_returns_nan():
    img = band_texture(64, (8, 16), 5)
    with pytest.raises(ValueError, match="no power"):
        A.spectral_slope(img, (2, 30))  # band-limited: empty bins below 8
    with pytest.raises(ValueError, match="Nyquist"):
        A.spectral_slope(img, (2, 40))
    with pytest.raises(ValueError, match="at least 3"):
        A.spectral_slope(np.random.default_rng(0).standard_normal((16, 16)), (5, 5.5))
    with pytest.raises(ValueError, match="lo < hi"):
        A.spectral_slope(img, (10, 4))
    with pytest.raises(ValueError, match="too small"):
        A.spectral_slope(np.random.default_rng(0).standard_normal((6, 6)))


def test_bad_motion_arguments():
    video = np.random.default_rng(1).random((8, 16, 16))
    with pytest.raises(ValueError, match=r"c must be in \[0, 3.14"):
        A.tent_energy(video, 4.0, (2, 6))
    with pytest.raises(ValueError, match="direction_yx must not be"):
        A.tent_energy(video, 1.0, (2, 6), direction_yx=(0, 0))
    with pytest.raises(ValueError, match="Nyquist"):
        A.tent_energy(video, 1.0, (2, 9))
    with pytest.raises(ValueError, match="3-D"):
        A.motion_energy(video[0], velocity_yx=(0, 1))
    with pytest.raises(ValueError, match="at least 2"):
        A.best_velocity(video[:1])
    with pytest.raises(ValueError, match="at least 4 frames"):
        A.band_speeds(video[:3], [(2, 6)])
    with pytest.raises(ValueError, match="velocity"):
        A.motion_energy(video, velocity_yx=(np.nan, 1))
    with pytest.raises(ValueError, match="at least 3"):
        A.loop_seam(video[:2])
    with pytest.raises(ValueError, match="does not change"):
        A.loop_seam(np.ones((5, 4, 4)))


def test_one_spectrum_serves_several_analysers():
    video = tent_video((16, 32, 32), 1.0, (3, 8), seed=6, count=60)
    spec = A.video_spectrum(video)
    assert A.tent_energy(spec, 1.0, (3, 8), thickness=0, tol=0.5) == A.tent_energy(video, 1.0, (3, 8), thickness=0, tol=0.5)
    assert A.motion_energy(spec, velocity_yx=(1, 0)) == A.motion_energy(video, velocity_yx=(1, 0))
    with pytest.raises(ValueError, match="3-D spectrum"):
        A.best_velocity(A.power_spectrum(video[0]))


def test_input_is_left_alone_and_a_large_mean_is_removed_before_the_fft():
    x = np.random.default_rng(12).standard_normal((64, 64)).astype(np.float32)
    x0 = x.copy()
    A.power_spectrum(x)
    A.power_spectrum(x, window="hann")
    A.video_spectrum(x[None].repeat(3, axis=0), window="hann")
    np.testing.assert_array_equal(x, x0)
    # a float32 field whose mean is 1e5 times its fluctuation keeps its variance
    big = (np.float32(1e4) + np.float32(1e-1) * x).astype(np.float32)
    assert A.power_spectrum(big).total == pytest.approx(float(big.astype(np.float64).var()), rel=1e-3)
    assert abs(A.spectral_slope(big, (2, 16))) < 0.15  # still white


def test_removing_the_static_part_frees_the_band_speeds_from_a_still_background():
    c, band = 1.0, (4, 16)
    snow_like = tent_video((32, 64, 64), c, band, seed=7)
    still = 3 * snow_like.std() * band_texture(64, (2, 16), 8) / band_texture(64, (2, 16), 8).std()
    video = snow_like + still[None]
    bands = A.octave_bands(*band, per_octave=1)
    clean = A.speed_profile(snow_like, bands).speed
    mixed = A.speed_profile(video, bands).speed
    freed = A.speed_profile(video, bands, remove_static=True).speed
    assert np.all(mixed < 0.5 * clean)  # the still background drags every band towards zero
    np.testing.assert_allclose(freed, clean, rtol=0.05)
    with pytest.raises(ValueError, match="does not change in time"):
        A.best_velocity(np.stack([still] * 8), remove_static=True)


@pytest.mark.parametrize("module", ["", ".spectrum", ".slope", ".isotropy", ".motion", ".seams", ".contrast",
                                    ".quality"])
def test_docstring_examples_hold(module):
    import doctest
    import importlib

    mod = importlib.import_module("noiselab.analysis" + module)
    result = doctest.testmod(mod, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0


def test_power_band_finds_the_edges_of_band_limited_fields():
    """Band-limited noise, in float and quantised to 8 bits (a floor 5-6 decades above rounding), has its
    band found to the ring; the drop past each edge is several decades."""
    from noiselab import spectral_noise

    for band, n in (((16, 80), 256), ((4, 12), 128), ((3, 6), 64), ((2, 100), 256)):
        f = spectral_noise((n, n), exponent=1.0, band=band, rng=3)
        f8 = np.round((f - f.min()) / (f.max() - f.min()) * 255) / 255
        for field in (f, f8):
            pb = A.power_band(field)
            assert (pb.lo, pb.hi) == band and pb.limited == (True, True), (band, pb)
            assert min(pb.drop) > 2.0
    # power only near Nyquist: no upper edge, the band runs to N / 2
    pb = A.power_band(spectral_noise((256, 256), exponent=0.0, band=(40, 128), rng=1))
    assert (pb.lo, pb.hi, pb.limited) == (40.0, 128.0, (True, False)) and pb.drop[1] == 0
    # a video's spatial band, from its spectrum over the frame axes
    video = np.stack([spectral_noise((64, 64), band=(5, 20), rng=s) for s in range(4)])
    pb = A.power_band(A.power_spectrum(video, axes=(-2, -1)))
    assert (pb.lo, pb.hi) == (5.0, 20.0)


@pytest.mark.parametrize("exponent", [-1.0, 0.0, 0.5, 1.0, 2.0, 3.0])
@pytest.mark.parametrize("n", [64, 256, 1024])
def test_power_band_keeps_the_full_band_of_a_power_law(exponent, n):
    """1/f**k noise with no band limit (float, and 8-bit where the fine scales sink into quantisation):
    no edge, the band is every ring 1 .. N / 2."""
    f = power_law_field((n, n), exponent, seed=4)
    f8 = np.round((f - f.min()) / (f.max() - f.min()) * 255) / 255
    for field in (f, f8):
        pb = A.power_band(field)
        assert (pb.lo, pb.hi, pb.limited) == (1.0, n / 2, (False, False)), pb


def test_power_band_refuses_bad_drop():
    with pytest.raises(ValueError, match="drop"):
        A.power_band(np.random.default_rng(0).random((16, 16)), drop=0)
