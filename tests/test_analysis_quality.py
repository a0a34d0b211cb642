"""The measures a noise is judged by (noiselab.analysis.quality), each on signals with a known answer."""
import numpy as np
import pytest

import noiselab
from noiselab import analysis as A


# ---------------------------------------------------------------- band leakage and aliasing
def test_band_leakage_puts_a_cosine_in_its_octave_and_band():
    y, x = np.mgrid[:64, :64]
    img = np.cos(2 * np.pi * 8 * x / 64)
    inside = A.band_leakage(img, (4, 16))
    assert inside.inside == pytest.approx(1.0) and inside.outside == pytest.approx(0.0, abs=1e-12)
    below = A.band_leakage(img, (10, 20))
    assert below.below == pytest.approx(1.0)
    k = np.nonzero(below.octaves > 0.5)[0][0]
    assert below.edges[k] == pytest.approx(5.0) and below.edges[k + 1] == pytest.approx(10.0)
    assert below.octaves.sum() == pytest.approx(1.0)


@pytest.mark.parametrize("shape,expected", [((4096,), 1 / 2), ((256, 256), 3 / 4), ((48, 48, 48), 7 / 8)])
def test_white_noise_twice_as_dense_as_the_output_aliases_all_but_one_cell_in_2_to_the_d(shape, expected):
    white = np.random.default_rng(1).standard_normal(shape)
    leak = A.band_leakage(white, (1, shape[-1] / 4), oversample=2)
    assert leak.aliased == pytest.approx(expected, abs=0.01)
    assert leak.octaves_aliased.sum() == pytest.approx(leak.aliased)
    # no aliasing asked for: nothing is past the field's own Nyquist
    assert A.band_leakage(white, (1, shape[-1] / 4)).aliased == 0.0


def test_lattice_noise_aliases_and_the_spectral_field_does_not():
    # 32 lattice cells over a 128 x 128 output (4 px per cell), rendered twice as densely: the smoother the
    # kernel, the less power past the output's Nyquist (2 cycles per cell)
    aliased = {k: A.band_leakage(noiselab.LatticeNoise(2, rng=2, kernel=k, period=32).grid((256, 256), [(0, 32)] * 2),
                                 (1, 64), oversample=2).aliased for k in ("box", "linear", "cubic")}
    assert aliased["box"] > 0.05 and aliased["box"] > 10 * aliased["linear"] > 100 * aliased["cubic"] > 0
    from scipy.signal import resample

    spec = noiselab.spectral_noise((128, 128), band=(4, 60), rng=3, dtype=np.float64)
    fine_spec = resample(resample(spec, 256, axis=0), 256, axis=1)  # the same trigonometric field, twice as dense
    leak = A.band_leakage(fine_spec, (4, 60), oversample=2)
    assert leak.aliased < 1e-20 and leak.inside == pytest.approx(1.0)


def test_band_leakage_rejects_a_band_past_the_output():
    with pytest.raises(ValueError, match="band"):
        A.band_leakage(np.random.default_rng(0).standard_normal((64, 64)), (4, 40), oversample=2)
    with pytest.raises(ValueError, match="oversample"):
        A.band_leakage(np.random.default_rng(0).standard_normal((64, 64)), (4, 8), oversample=0)


# ---------------------------------------------------------------- slices (Cook & DeRose)
def test_a_slice_of_a_band_limited_volume_is_not_band_limited():
    vol = noiselab.spectral_noise((48, 48, 48), exponent=0.0, band=(6, 12), rng=4, dtype=np.float64)
    s = A.slice_leakage(vol, (6, 12))
    assert s.volume.below < 1e-12 and s.volume.inside == pytest.approx(1.0)
    # known answer: the share of the shell's cells whose in-plane radius is under 6
    k = np.fft.fftfreq(48, 1 / 48)
    kz, ky, kx = np.meshgrid(k, k, k, indexing="ij")
    r, rxy = np.sqrt(kz**2 + ky**2 + kx**2), np.hypot(kx, ky)
    shell = (r >= 6) & (r <= 12)
    assert s.slices.below == pytest.approx(((rxy < 6) & shell).sum() / shell.sum(), abs=0.02)
    assert s.slices.below == pytest.approx(A.shell_slice_below(6, 12), abs=0.03)
    assert s.added_below == pytest.approx(s.slices.below)
    assert A.slice_leakage(vol, (6, 12), axis=2).slices.below == pytest.approx(s.slices.below, abs=0.03)


def test_shell_slice_below_closed_form_and_trend():
    for lo, hi in ((8, 16), (4, 40), (10, 11)):
        closed = (hi**3 - (hi**2 - lo**2) ** 1.5 - lo**3) / (hi**3 - lo**3)
        assert A.shell_slice_below(lo, hi) == pytest.approx(closed, rel=1e-6)
    # a steeper spectrum keeps its power on spheres just above lo, whose caps under lo cover most of them
    assert A.shell_slice_below(8, 32, exponent=2.0) > A.shell_slice_below(8, 32) > 0


# ---------------------------------------------------------------- envelope error
def test_envelope_error_is_zero_for_the_exact_envelope_and_sampling_noise_for_a_draw():
    target = lambda f: np.where((f >= 4) & (f <= 64), f ** -2.0, 0.0)  # noqa: E731
    exact = noiselab.spectral_noise((128, 128), exponent=1.0, band=(4, 64), amplitude_distribution="fixed", rng=5, dtype=np.float64)
    e = A.envelope_error(exact, target)
    assert e.rms_db < 1e-6 and e.outside < 1e-20
    drawn = noiselab.spectral_noise((128, 128), exponent=1.0, band=(4, 64), rng=5)
    e = A.envelope_error(drawn, target)
    assert e.rms_db < 2.5 * e.noise_db and e.max_db < 5 * e.noise_db
    # white noise against 1/f**2: measured / target grows as f**2, i.e. as the target level falls
    white = A.envelope_error(np.random.default_rng(6).standard_normal((128, 128)), target)
    assert white.rms_db > 5 and np.all(np.diff(white.db) < 0)
    # power outside a band-limited target: the share of the cells outside the band
    f = np.hypot(*np.meshgrid(np.fft.fftfreq(128, 1 / 128), np.fft.fftfreq(128, 1 / 128)))
    share = ((f > 0) & ((f < 4) | (f > 64))).sum() / (f > 0).sum()
    assert white.outside == pytest.approx(share, abs=0.02)


def test_envelope_error_takes_an_array_target_of_either_layout():
    x = noiselab.spectral_noise((64, 64), exponent=0.0, band=(2, 32), amplitude_distribution="fixed", rng=7, dtype=np.float64)
    full = np.ones((64, 64))
    half = np.ones((64, 33))
    assert A.envelope_error(x, full).rms_db == pytest.approx(A.envelope_error(x, half).rms_db, abs=1e-12)
    with pytest.raises(ValueError, match="target"):
        A.envelope_error(x, np.ones((10, 10)))
    with pytest.raises(ValueError, match="target"):
        A.envelope_error(x, -half)


# ---------------------------------------------------------------- variance and range
def test_value_statistics_against_uniform_values():
    u = np.random.default_rng(8).uniform(-1, 1, 200_000)
    s = A.value_statistics(u, variance=1 / 3, bounds=(-1, 1))
    assert s.variance_ratio == pytest.approx(1.0, abs=0.01) and s.within_bounds and s.range_used > 0.999
    s = A.value_statistics(u, bounds=(-0.5, 0.5))
    assert s.within_bounds is False and s.range_used == pytest.approx(2.0, abs=1e-3) and s.variance_ratio is None
    with pytest.raises(ValueError, match="bounds"):
        A.value_statistics(u, bounds=(1, -1))


# ---------------------------------------------------------------- periods
def test_detect_period_finds_the_fft_domain_and_the_lattice_table():
    img = noiselab.spectral_noise((64, 64), rng=9)
    tiled = np.tile(img, (1, 3))
    assert A.detect_period(tiled, axis=1).period == 64
    assert A.detect_period(np.tile(img, (3, 1)), axis=0).period == 64
    assert A.detect_period(img[:, :48]).period is None
    # lattice noise repeats after its table: 64 cells of 4 samples
    line = noiselab.LatticeNoise(1, rng=3, table_size=64).grid((1024,), [(0, 256)])
    p = A.detect_period(line)
    assert p.period == 256 and p.difference < 1e-12
    white = A.detect_period(np.random.default_rng(10).standard_normal(2000))
    assert white.period is None and white.difference == pytest.approx(1.0, abs=0.1)


# ---------------------------------------------------------------- lattice-axis artefacts
def test_axis_artefacts_isotropic_striped_and_lattice():
    rng = np.random.default_rng(11)
    white = rng.standard_normal((256, 256))
    a = A.axis_artefacts(white)
    assert a.axis_excess == pytest.approx(1.0, abs=0.15) and a.mean_spread_excess == pytest.approx(1.0, abs=0.15)
    # white noise: the mean of 256 samples has sd 1/16 of theirs
    assert a.row_mean_spread == pytest.approx(1 / 16, rel=0.15) and a.column_mean_spread == pytest.approx(1 / 16, rel=0.15)
    striped = A.axis_artefacts(white + 0.5 * rng.standard_normal((1, 256)))
    assert striped.axis_excess > 20 and striped.column_mean_spread > 0.4 and striped.row_mean_spread < 0.1
    # the column means' variance is the power on the ky = 0 axis
    spec = A.power_spectrum(white).full()
    assert (a.column_mean_spread * white.std()) ** 2 == pytest.approx(spec[0, :].sum(), rel=1e-9)
    # a periodic lattice shows its axes; the spectral field does not
    lat = noiselab.LatticeNoise(2, rng=12, kernel="cubic", period=16).grid((256, 256), [(0, 16), (0, 16)])
    past = A.axis_artefacts(lat, (32, 128))  # past twice the lattice frequency, the tails run along the axes
    assert past.axis_excess > 3
    for s in (13, 14):  # about 450 axis cells: 1 +- 0.05
        assert A.axis_artefacts(noiselab.spectral_noise((256, 256), rng=s), (16, 128)).axis_excess == pytest.approx(1, abs=0.2)


def test_variance_striping_of_linear_value_noise_matches_its_kernel():
    # var(t) of linear value noise is (1 - t)**2 + t**2 times the values' variance: 1 at lattice points, 1/2 mid-cell
    line = noiselab.LatticeNoise(1, rng=14, kernel="linear", table_size=1 << 16).grid((1 << 18,), [(0, 1 << 14)])
    t = np.arange(16) / 16
    s = (1 - t) ** 2 + t**2
    assert A.variance_striping(line, 16) == pytest.approx((s.max() - s.min()) / s.mean(), abs=0.05)
    img = noiselab.LatticeNoise(2, rng=15, kernel="linear", table_size=1 << 12).grid((512, 512), [(0, 64), (0, 64)])
    assert A.variance_striping(img, 8, axis=1) == pytest.approx((s[::2].max() - s[::2].min()) / s[::2].mean(), abs=0.1)
    stationary = noiselab.spectral_noise((1 << 18,), exponent=0.0, rng=16)
    assert A.variance_striping(stationary, 16) < 0.1
    with pytest.raises(ValueError, match="period"):
        A.variance_striping(line, 1)


# ---------------------------------------------------------------- motion per band
def test_tent_energy_per_band_of_snow_and_of_a_still():
    from noiselab.snowfall import snow

    video = snow((16, 64, 64), rng=17, band=(4, 16), c=1.0, rescale=False, dtype=np.float64)
    m = A.tent_energy_per_band(video, 1.0, (4, 16))
    assert m.bands.shape == (2, 2) and np.all(m.fraction > 0.999)
    assert m.share.sum() == pytest.approx(A.band_energy(video, (4, 16), axes=(-2, -1)), abs=1e-9)
    still = np.repeat(noiselab.spectral_noise((64, 64), band=(4, 16), rng=18)[None], 16, axis=0)
    rng = np.random.default_rng(19)
    moving_still = still + 1e-3 * rng.standard_normal(still.shape)
    assert np.all(A.tent_energy_per_band(moving_still, 1.0, (4, 16)).fraction < 0.2)
