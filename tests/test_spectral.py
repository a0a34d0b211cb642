"""The spectral engine: exact conjugacy, expected power, envelopes, spectral_noise."""
import numpy as np
import pytest
import scipy.fft

from noiselab.spectral import envelopes as E
from noiselab.spectral import frequency_vectors, hermitian_plane, spectral_noise, synthesize
from _helpers import phase_correlation_shift

SHAPES = [(7,), (8,), (1,), (2,), (5, 6), (6, 7), (8, 8), (1, 8), (4, 6, 8), (5, 7, 9), (1, 8, 8), (3, 1, 4), (2, 2, 2)]


def _ones(*w):
    return np.ones(np.broadcast_shapes(*(x.shape for x in w)))


@pytest.mark.parametrize("shape", SHAPES)
def test_round_trip_reproduces_the_prescribed_spectrum(shape):
    field, S = synthesize(shape, _ones, rng=3, dtype=np.float64, amplitude_distribution="fixed", return_spectrum=True)
    assert field.shape == shape and field.dtype == np.float64
    # the FFT of the output is the spectrum we built, to float precision
    np.testing.assert_allclose(scipy.fft.rfftn(field), S, rtol=0, atol=1e-12)
    # and no cell lost or gained magnitude on the self-conjugate planes
    np.testing.assert_allclose(np.abs(S), 1.0, rtol=0, atol=1e-12)


@pytest.mark.parametrize("shape", [(6, 8), (5, 7), (4, 6, 8)])
def test_round_trip_float32(shape):
    field, S = synthesize(shape, _ones, rng=1, dtype=np.float32, amplitude_distribution="fixed", return_spectrum=True)
    assert field.dtype == np.float32 and S.dtype == np.complex64
    np.testing.assert_allclose(scipy.fft.rfftn(field.astype(np.float64)), S, rtol=0, atol=2e-5)


def test_plane_power_is_neither_lost_nor_doubled():
    # Parseval on the full spectrum: the field's sum of squares equals the
    # prescribed power, counting interior half-spectrum cells twice
    shape = (6, 8)
    field, S = synthesize(shape, _ones, rng=5, dtype=np.float64, amplitude_distribution="fixed", return_spectrum=True)
    weight = np.full(S.shape, 2.0)
    weight[:, 0] = 1
    weight[:, -1] = 1  # Nyquist column of an even width
    prescribed = float((weight * np.abs(S) ** 2).sum()) / np.prod(shape)
    assert np.isclose((field ** 2).sum(), prescribed, rtol=1e-12)
    # all 48 full-spectrum cells have |S| = 1, so sum(x**2) = 48 / 48; halving the
    # planes (kx = 0 and kx = 4: 12 of the 48 cells) would give 0.875
    assert np.isclose((field ** 2).sum(), 1.0, rtol=1e-12)


@pytest.mark.parametrize("amplitude", ["uniform", "rayleigh"])
def test_expected_power_equals_envelope_squared_on_every_cell(amplitude):
    shape = (4, 6)
    env = lambda wy, wx: 1.0 + np.abs(wy) + 0 * wx  # noqa: E731 - non-constant, symmetric
    target = env(*frequency_vectors(shape)) ** 2
    target = np.broadcast_to(target, (4, 4))
    acc = np.zeros((4, 4))
    n = 3000
    rng = np.random.default_rng(0)
    for _ in range(n):
        _, S = synthesize(shape, env, rng=rng, dtype=np.float64, amplitude_distribution=amplitude, return_spectrum=True)
        acc += np.abs(S) ** 2
    ratio = acc / n / target
    # planes (kx = 0 and kx = 3, Nyquist) included: no cell at half or double power
    assert np.all(np.abs(ratio - 1) < 0.12), ratio


def test_hermitian_plane_union_of_asymmetric_support_keeps_magnitudes():
    p = np.zeros((4, 4), complex)
    p[1, 2] = 3 * np.exp(0.7j)       # non-canonical cell, its mirror (3, 2) is empty
    p[2, 2] = 2 * np.exp(2.0j)       # self-conjugate cell
    q = hermitian_plane(p)
    assert np.isclose(q[3, 2], np.conj(q[1, 2]))
    assert np.isclose(abs(q[1, 2]), 3) and np.isclose(abs(q[3, 2]), 3)
    assert q[2, 2].imag == 0 and np.isclose(abs(q[2, 2]), 2)
    mirror = np.roll(np.flip(q), 1, axis=(0, 1))
    np.testing.assert_allclose(mirror, np.conj(q))


def test_frequency_vectors_are_broadcast_not_meshgrids():
    wt, wy, wx = frequency_vectors((64, 512, 512))
    assert wt.shape == (64, 1, 1) and wy.shape == (1, 512, 1) and wx.shape == (1, 1, 257)
    assert wx.max() == np.pi and wy.min() == -np.pi and wt.min() == -np.pi


def test_same_seed_bit_identical_and_generator_accepted():
    env = lambda wy, wx: E.annulus(wy, wx, band_cycles_per_sample=(0.05, 0.4))  # noqa: E731
    a = synthesize((16, 16), env, rng=11)
    b = synthesize((16, 16), env, rng=11)
    c = synthesize((16, 16), env, rng=np.random.default_rng(11))
    d = synthesize((16, 16), env, rng=12)
    assert a.tobytes() == b.tobytes() == c.tobytes()
    assert not np.array_equal(a, d)


def test_synthesize_rejects_bad_envelopes():
    with pytest.raises(ValueError, match="finite"):
        synthesize((8, 8), lambda wy, wx: E.power_law(wy, wx) * 0 + np.inf)
    with pytest.raises(ValueError, match="non-negative"):
        synthesize((8, 8), lambda wy, wx: -np.ones((8, 5)))
    with pytest.raises(ValueError, match="amplitude"):
        synthesize((8, 8), _ones, amplitude_distribution="gaussian")
    with pytest.raises(ValueError, match=r"shape\[1\]"):
        synthesize((8, 0), _ones)


def _radial_power_slope(field, lo, hi):
    P = np.abs(np.fft.fft2(field)) ** 2
    fy = np.fft.fftfreq(field.shape[0])[:, None]
    fx = np.fft.fftfreq(field.shape[1])[None, :]
    r = np.hypot(fy, fx)
    edges = np.geomspace(lo, hi, 9)
    centres, power = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        m = (r >= a) & (r < b)
        centres.append(np.sqrt(a * b))
        power.append(P[m].mean())
    return np.polyfit(np.log(centres), np.log(power), 1)[0]


@pytest.mark.parametrize("exponent", [0.5, 1.0, 2.0])
def test_spectral_noise_power_slope(exponent):
    x = spectral_noise((256, 256), exponent=exponent, rng=2, normalize="sample")
    slope = _radial_power_slope(x, 4 / 256, 100 / 256)
    assert abs(slope + 2 * exponent) < 0.15, slope
    assert abs(float(x.std()) - 1) < 1e-5 and abs(float(x.mean())) < 1e-5


def test_spectral_noise_band_and_dimensions():
    x = spectral_noise((128, 128), band=(8, 16), rng=0, dtype=np.float64)
    P = np.abs(np.fft.fft2(x)) ** 2
    r = np.hypot(np.fft.fftfreq(128)[:, None], np.fft.fftfreq(128)[None, :]) * 128
    inside = (r >= 8) & (r <= 16)
    assert P[~inside].max() < 1e-18 * P[inside].max()
    for shape in [(100,), (9, 10, 11)]:
        y = spectral_noise(shape, rng=1)
        assert y.shape == shape and y.dtype == np.float32


def test_spectral_noise_bad_input():
    with pytest.raises(ValueError, match="past the Nyquist"):
        spectral_noise((64, 64), band=(4, 40))
    with pytest.raises(ValueError, match="empty"):
        spectral_noise((64, 64), band=(10, 10))
    with pytest.raises(ValueError, match="exponent must be finite"):
        spectral_noise((64, 64), exponent=float("nan"))
    with pytest.raises(ValueError, match="entries"):
        spectral_noise((4, 4, 4, 4))


_displacement = phase_correlation_shift


def test_motion_plane_envelope_translates_with_its_velocity():
    T = 16
    env = lambda wt, wy, wx: (E.motion_plane(wt, wy, wx, velocity_yx=(-1.0, 2.0), tol=np.pi / T)  # noqa: E731
                              * E.annulus(wy, wx, band_cycles_per_sample=(0.05, 0.3)))
    v = synthesize((T, 64, 64), env, rng=0, dtype=np.float64)
    assert _displacement(v[0], v[1]) == (2, -1)


def test_optical_snow_wedge_holds_its_planes_only():
    wt, wy, wx = frequency_vectors((32, 32, 32))
    m = E.optical_snow(wt, wy, wx, direction_yx=(1, 0), speeds=(0.5, 2.0), tol=1e-9)
    # a cell on the s = 1 plane is inside, one on s = 4 is outside
    ky, kt_in, kt_out = 3, -3, -12  # wt = -s * wy at wy = 2*pi*3/32
    assert m[kt_in % 32, ky, 0] == 1 and m[kt_out % 32, ky, 0] == 0
    n = E.nonparallel_optical_snow(wt, wy, wx, direction_yx=(1, 0), speeds=(1.0, 1.0), pan_yx=(0.0, 1.0), tol=1e-9)
    # velocity (1, 1): wt = -(wx + wy)
    assert n[(-(2 + 3)) % 32, 3, 2] == 1 and n[(-3) % 32, 3, 2] == 0


def test_power_law_and_annulus():
    w = np.array([0.0, 0.5, 1.0])
    np.testing.assert_allclose(E.power_law(w, exponent=1.0), [0.0, 2.0, 1.0])
    f = np.array([0.0, 0.1, 0.2, 0.3]) * 2 * np.pi
    np.testing.assert_array_equal(E.annulus(f, band_cycles_per_sample=(0.1, 0.2)), [0, 1, 1, 0])
    with pytest.raises(ValueError, match="non-zero"):
        E.unit_direction((0, 0))


@pytest.mark.parametrize("modname", [
    "noiselab.spectral.frequencies", "noiselab.spectral.envelopes", "noiselab.spectral.synthesis",
    "noiselab.snowfall.render", "noiselab.snowfall.tent", "noiselab.snowfall.composite", "noiselab.snowfall.tiling",
    "noiselab.snowfall.background",
])
def test_docstring_examples_hold(modname):
    import doctest
    import importlib

    result = doctest.testmod(importlib.import_module(modname), optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0


# --- the fast paths: spectrum-side normalisation, the fused power-law fill, the pruned FFT, the draws ---

NOISE_CASES = [((256, 256), (1, 8)), ((16, 24), (1, 6)), ((9, 10, 12), (1, 5)), ((64,), (2, 20)), ((8, 8, 8), None),
               ((7, 9), None), ((12, 10, 8), (2, 4)), ((33, 32), (0, 16))]


@pytest.mark.parametrize("shape,band", NOISE_CASES)
def test_spectral_noise_is_synthesize_with_annulus_times_power_law(shape, band):
    # the fused kernel (band and 1/f evaluated per cell, pruned block, spectrum-side scaling) builds the
    # spectrum synthesize builds from the float64 envelope: same cells, same draws, same planes
    n = shape[-1]
    lo, hi = (band[0] / n, band[1] / n) if band else (0.0, 0.5 * np.sqrt(len(shape)) + 1.0)
    env = lambda *w: E.annulus(*w, band_cycles_per_sample=(lo, hi)) * E.power_law(*w, exponent=1.5)  # noqa: E731
    _, S = synthesize(shape, env, rng=7, amplitude_distribution="rayleigh", dtype=np.float64, return_spectrum=True)
    x = spectral_noise(shape, exponent=1.5, band=band, rng=7, dtype=np.float64)
    X = scipy.fft.rfftn(x)
    scale = np.sqrt(np.sum(np.abs(X) ** 2) / np.sum(np.abs(S) ** 2))
    np.testing.assert_allclose(X, S * scale, rtol=0, atol=1e-12 * np.abs(X).max())
    assert np.count_nonzero(S) > 0


@pytest.mark.parametrize("shape,band", NOISE_CASES)
def test_spectrum_side_normalisation_gives_zero_mean_unit_variance_exactly(shape, band):
    # normalize="sample": the spectrum is scaled by N / sqrt(sum |S|^2) before the FFT (Parseval, DC = 0)
    x = spectral_noise(shape, band=band, rng=3, dtype=np.float64, normalize="sample")
    assert abs(float(x.mean())) < 1e-14
    assert abs(float(x.std()) - 1.0) < 1e-13
    y = spectral_noise(shape, band=band, rng=3, dtype=np.float32, normalize="sample")
    assert abs(float(y.mean(dtype=np.float64))) < 1e-6
    assert abs(float(y.std(dtype=np.float64)) - 1.0) < 2e-6
    # float32 and float64 share their draws: the same field to float32 precision
    np.testing.assert_allclose(y, x, rtol=0, atol=1e-5)


def _plan_spectrum(shape, band, seed, dtype, **kw):
    """The whole half spectrum of ``spectral_noise`` built from the plan's slabs (the chunked path's pieces), scaled."""
    from noiselab.spectral import plan

    p = plan.noise_plan(shape, 1.0, band, seed, "rayleigh", dtype, **kw)
    parts = [plan.fill_slab(p, i0, min(p.bshape[0], i0 + 3)) for i0 in range(0, p.bshape[0], 3)] \
        if len(shape) > 1 else [_fill_one_row(p)]
    slabs = np.concatenate([s for s, _ in parts])
    cols = [j for j in plan.self_conjugate_columns(p.n) if j < p.K]
    planes = [np.ascontiguousarray(slabs[..., j]) for j in cols]
    g = plan.hermitian_gain(p, np.concatenate([r for _, r in parts]), planes)
    for k, j in enumerate(cols):
        slabs[..., j] = planes[k]
    full = np.zeros(shape[:-1] + (shape[-1] // 2 + 1,), dtype=slabs.dtype)
    full[np.ix_(*p.index, np.arange(p.K))] = slabs.reshape(tuple(ix.size for ix in p.index) + (p.K,))
    return full * g, p


def _fill_one_row(p):
    from noiselab.spectral import _kernels

    row = np.empty(p.K, dtype=p.cdt)
    rowpow = np.zeros(1)
    _kernels.fill_power_law(row.view(p.dt), p.Kr, p.q0, p.q1, p.wxsq, p.kbeg, p.kend, 0, 1, p.key, 0, p.mode,
                            p.exponent, p.qfloor, p.inv_qref, p.weight, p.sample, rowpow, np.empty(p.Kr, p.dt))
    return row, rowpow


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_in_place_synthesis_equals_irfftn_of_the_plans_whole_spectrum(dtype):
    # the spectrum is filled into the output's own storage and transformed there (pruned leading passes, the last
    # pass written back row block by row block): the field irfftn makes of the whole spectrum, to rounding
    tol = 1e-14 if dtype == np.float64 else 2e-6
    cases = [((64, 96), (2, 9)), ((20, 24, 30), (1, 4)), ((50,), (1, 6)), ((40, 33), None), ((12, 10, 9), None),
             ((30, 16, 20), (0, 10)), ((257, 130), (3, 40))]
    for shape, band in cases:
        for kw in ({}, {"normalize": "sample"}, {"dc": True, "band": None if band is None else (0, band[1])}):
            kw = dict({"band": band}, **kw)
            S, p = _plan_spectrum(shape, kw.pop("band"), 5, np.dtype(dtype), **kw)
            ref = scipy.fft.irfftn(S.astype(np.complex128), s=shape)
            got = spectral_noise(shape, band=p.band, rng=5, dtype=dtype, **kw)
            assert got.shape == shape and got.dtype == dtype and got.flags.c_contiguous
            np.testing.assert_allclose(got, ref, rtol=0, atol=tol * np.abs(ref).max())


def test_in_memory_and_chunked_fields_have_the_same_bits():
    # the in-place passes are the chunked path's (one axis at a time, the same scaled cells): equal bit for bit,
    # pruned or not, for any chunking and worker count
    pytest.importorskip("dask")
    cases = [((30, 32), dict(dc=True, band=(0, 16), exponent=2.0), (7, 9)),
             ((48, 40), dict(band=(4, 20), normalize="sample"), (13, 40)),
             ((17, 19, 15), dict(exponent=1.5), (5, 19, 15)),
             ((16, 20, 24), dict(band=(2, 12), amplitude_distribution="uniform"), (6, 7, 24)),
             ((12, 14, 18), dict(band=(1, 6), normalize="sample", dtype=np.float64), (12, 5, 9)),
             ((64, 66), dict(), (20, 66)), ((257,), dict(exponent=1.0, dc=True, amplitude_distribution="uniform"),
                                            (100,))]
    for shape, kw, chunks in cases:
        for seed in (11, 12):
            ref = spectral_noise(shape, rng=seed, workers=2, **kw)
            got = spectral_noise(shape, rng=seed, chunks=chunks, **kw).compute(scheduler="synchronous")
            assert got.dtype == ref.dtype and got.tobytes() == ref.tobytes(), (shape, kw, seed)


def test_peak_memory_is_at_most_1_1x_the_field():
    # one array of the field's size (its storage holds the spectrum, then the samples) and the last pass's
    # scratch: at most 1.1x the output for 2-D and 3-D fields from 4 MiB up (irfftn of a ready spectrum alone
    # holds both, 2x; so did spectral_noise before it synthesised in place)
    import tracemalloc

    for shape, kw in [((1024, 1024), {}), ((1024, 1024), {"dtype": np.float64, "band": (4, 100)}),
                      ((128, 128, 128), {}), ((100, 96, 110), {"band": (2, 20), "normalize": "sample"})]:
        warm = {k: v for k, v in kw.items() if k != "band"}
        spectral_noise((16,) * len(shape), rng=0, **warm)  # compiled before the count
        tracemalloc.start()
        try:
            x = spectral_noise(shape, rng=0, workers=2, **kw)
            _, peak = tracemalloc.get_traced_memory()
        finally:
            tracemalloc.stop()
        assert x.nbytes >= 4 << 20 and peak <= 1.1 * x.nbytes, (shape, kw, peak / x.nbytes)


def test_spectral_noise_same_seed_same_bits_and_band_edges():
    a = spectral_noise((48, 40), band=(3, 12), rng=21)
    b = spectral_noise((48, 40), band=(3, 12), rng=np.random.default_rng(21))
    c = spectral_noise((48, 40), band=(3, 12), rng=22)
    assert a.tobytes() == b.tobytes() and not np.array_equal(a, c)
    # return_spectrum and the in-place FFT path give the same bits
    env = lambda wy, wx: E.annulus(wy, wx, band_cycles_per_sample=(0.05, 0.4))  # noqa: E731
    f1 = synthesize((16, 18), env, rng=4)
    f2, _ = synthesize((16, 18), env, rng=4, return_spectrum=True)
    assert f1.tobytes() == f2.tobytes()
    # the band edges are inclusive, as the annulus says: 12 cycles/frame exactly is kept
    x = spectral_noise((64, 64), band=(4, 12), rng=0, dtype=np.float64)
    P = np.abs(np.fft.fft2(x)) ** 2
    assert P[0, 12] > 0 and P[12, 0] > 0 and P[0, 4] > 0 and P[0, 13] < 1e-20 and P[0, 3] < 1e-20


def test_coefficient_draws_are_complex_gaussian_and_uniform_in_phase():
    from noiselab.spectral.plan import AMPLITUDE_MODES
    from noiselab.spectral.synthesis import _draws

    n = 1 << 18
    a2, c, s = _draws(np.uint64(12345), 0, n, AMPLITUDE_MODES["rayleigh"])
    z = np.sqrt(a2.astype(np.float64)) * (c + 1j * s)
    se = 4 / np.sqrt(n)
    assert abs(np.mean(np.abs(z) ** 2) - 1) < 4 * se and abs(np.mean(z)) < se and abs(np.mean(z * z)) < 2 * se
    assert abs(np.mean(z.real ** 4) / np.var(z.real) ** 2 - 3) < 40 * se  # Gaussian kurtosis
    np.testing.assert_allclose(c * c + s * s, 1, atol=1e-6)
    # the phase is uniform: equal counts in 16 sectors (chi-square, 15 dof, p < 1e-6 would need > 50)
    counts = np.histogram(np.arctan2(s, c), 16, range=(-np.pi, np.pi))[0]
    assert ((counts - n / 16) ** 2 / (n / 16)).sum() < 50
    # |z|^2 is exponential: P(|z|^2 > 3) = e^-3
    assert abs(np.mean(a2 > 3) - np.exp(-3)) < 4 * np.sqrt(np.exp(-3) / n)
    # counter-based: any chunking of the stream gives the same coefficients
    a2b, cb, sb = _draws(np.uint64(12345), 1000, 500, AMPLITUDE_MODES["rayleigh"])
    assert a2b.tobytes() == a2[1000:1500].tobytes() and cb.tobytes() == c[1000:1500].tobytes()
    u2, _, _ = _draws(np.uint64(1), 0, n, AMPLITUDE_MODES["uniform"])
    assert abs(np.mean(u2) - 1) < 4 * se and u2.max() <= 3.0


def test_synthesize_follows_its_documented_draws_on_dense_and_sparse_rows():
    # coefficient i (the i-th cell with env > 0 in C order) is word i of the stream keyed by one word of
    # the generator: rows where every cell carries energy take the branch-free loop, the others the general
    # one; both must give env * sqrt(a2) * (c + i s) / |c + i s| before the planes are made Hermitian
    from noiselab.spectral.plan import AMPLITUDE_MODES, stream_key
    from noiselab.spectral.synthesis import _draws

    shape = (12, 10)
    env = np.ones((12, 6))
    env[3, 2] = 0.0          # a sparse row
    env[5, :] = 0.0          # an empty row
    env[7, 1:4] = [0.5, 2.0, 0.0]
    _, S = synthesize(shape, env, rng=9, amplitude_distribution="rayleigh", dtype=np.float64, return_spectrum=True)
    sup = env > 0
    a2, c, s = _draws(stream_key(np.random.default_rng(9)), 0, int(sup.sum()), AMPLITUDE_MODES["rayleigh"])
    z = np.sqrt(a2.astype(np.float64)) * (c + 1j * s.astype(np.float64)) / np.abs(c + 1j * s.astype(np.float64))
    ref = np.zeros(env.shape, complex)
    ref[sup] = env[sup] * z
    for j in (0, 5):
        ref[:, j] = hermitian_plane(ref[:, j], sup[:, j])
    np.testing.assert_allclose(S, ref, rtol=0, atol=1e-12)


# --- an unbiased ensemble (the round-trip power tests of powerbox and colorednoise, ported) ---

def _ensemble_power(shape, exponent, seeds, **kw):
    """Mean |fftn|**2 over seeds, the law's expected |X|**2 at unit variance, and |f| of every cell."""
    X = np.mean([np.abs(np.fft.fftn(spectral_noise(shape, exponent=exponent, rng=s, dtype=np.float64, **kw))) ** 2
                 for s in range(seeds)], axis=0)
    f = np.sqrt(sum(np.meshgrid(*[np.fft.fftfreq(n) ** 2 for n in shape], indexing="ij")))
    law = np.where(f > 0, np.where(f > 0, f, 1) ** (-2.0 * exponent), 0.0)
    return X, law / law.sum() * float(np.prod(shape)) ** 2, f


ROUND_TRIP = [((64,), 1.0, 400), ((63,), 1.5, 400), ((65,), 1.0, 400),
              ((48, 72), 1.0, 80), ((47, 71), 1.0, 80), ((48, 71), 0.5, 80),
              ((12, 14, 16), 1.0, 30), ((13, 15, 17), 1.0, 30), ((12, 15, 16), 1.5, 30)]


@pytest.mark.parametrize("shape,exponent,seeds", ROUND_TRIP)
def test_round_trip_power_is_the_law_on_average(shape, exponent, seeds):
    # powerbox's round trip: the power of the generated fields, averaged over realisations and binned by |k|,
    # is the input P(k) = |k|**(-2*exponent) (scaled to unit variance) at every |k|, odd and even sizes
    X, target, f = _ensemble_power(shape, exponent, seeds)
    edges = np.quantile(f[f > 0], np.linspace(0, 1, 7))
    edges[-1] += 1
    for a, b in zip(edges[:-1], edges[1:]):
        m = (f >= a) & (f < b)
        ratio = X[m].sum() / target[m].sum()
        # |X|**2 of a Gaussian field is exponential (sd = mean) and k, -k are one draw: the bin's sd
        sd = np.sqrt(np.sum(target[m] ** 2) / seeds) / target[m].sum() * np.sqrt(2)
        assert abs(ratio - 1) < 5 * sd + 0.01, (a, b, ratio, sd)
    # colorednoise's variance test: the realisations' variance is 1 on average (E[x**2] = 1, not each field's)
    v = [spectral_noise(shape, exponent=exponent, rng=s, dtype=np.float64).var() for s in range(seeds)]
    assert abs(np.mean(v) - 1) < 5 * np.std(v) / np.sqrt(seeds)


def test_sample_normalisation_keeps_each_field_at_unit_variance_and_biases_the_ensemble():
    # the documented trade: "sample" sets each field's variance to exactly 1 and lifts the ensemble's
    # high-frequency power above the law (1-D k**-2: about 1.5x); "expected" does not
    for normalize, lo, hi in [("sample", 1.3, 1.8), ("expected", 0.95, 1.05)]:
        X, target, f = _ensemble_power((64,), 1.0, 400, normalize=normalize)
        high = f >= 0.25
        assert lo < X[high].sum() / target[high].sum() < hi, normalize
    x = spectral_noise((64,), exponent=1.0, rng=1, normalize="sample", dtype=np.float64)
    assert abs(x.var() - 1) < 1e-13
    with pytest.raises(ValueError, match="normalize must be one of"):
        spectral_noise((64,), normalize="max")


def test_dc_term_kept_on_request_with_the_lowest_ring_amplitude():
    # a 1/f**2 random walk (exponent 1 in 1-D) has a displacement: dc=True keeps DC, with the law taken flat
    # below the lowest nonzero frequency, so |S(0)| = |S(1/n)| when every cell has amplitude exactly the law
    x = spectral_noise((256,), exponent=1.0, dc=True, rng=3, amplitude_distribution="fixed", dtype=np.float64)
    S = np.abs(np.fft.rfft(x))
    assert S[0] > 0 and abs(S[0] / S[1] - 1) < 1e-12 and abs(S[2] / S[1] - 2 ** -1.0) < 1e-12
    # non-square 2-D: the lowest ring is 1/24 cycles/sample, the (0, 1) cell along the 24-sample axis
    y = spectral_noise((16, 24), exponent=2.0, dc=True, rng=3, amplitude_distribution="fixed", dtype=np.float64)
    Y = np.abs(np.fft.fft2(y))
    assert abs(Y[0, 0] / Y[0, 1] - 1) < 1e-12 and Y[0, 0] > Y[1, 0]
    # the band must start at 0; a blue law is 0 at DC and stays 0
    z = spectral_noise((64,), exponent=-1.0, dc=True, band=(0, 32), rng=0, amplitude_distribution="fixed", dtype=np.float64)
    assert abs(np.fft.rfft(z)[0]) < 1e-12 * np.abs(np.fft.rfft(z)).max()
    with pytest.raises(ValueError, match="dc=True .* band"):
        spectral_noise((64,), dc=True, band=(1, 8))
    with pytest.raises(TypeError, match="dc must be"):
        spectral_noise((64,), dc="yes")
    # the ensemble: E[x**2] = 1 with DC in, and the walk's mean varies from field to field
    walks = np.stack([spectral_noise((128,), exponent=1.0, dc=True, rng=s, dtype=np.float64) for s in range(300)])
    m2 = np.mean(walks ** 2, axis=1)
    assert abs(m2.mean() - 1) < 5 * m2.std() / np.sqrt(300)
    assert walks.mean(axis=1).std() > 0.3
    no_dc = spectral_noise((128,), exponent=1.0, rng=0, dtype=np.float64)
    assert abs(no_dc.mean()) < 1e-14


# --- silent wrong output from the spectral engine ---

@pytest.mark.parametrize("shape,exponent", [((4096,), 8.0), ((65536,), 5.0), ((512, 512), 8.0), ((8192,), -8.0),
                                            ((4096,), 7.3), ((64, 64, 64), 6.5)])
def test_steep_exponents_are_right_in_float32(shape, exponent):
    # the float32 power sum used to overflow (all zeros, or std 2.9e13 at 2048**2): the law is now evaluated
    # relative to the band's loudest end and the sums are float64, so float32 gives the float64 field
    x32 = spectral_noise(shape, exponent=exponent, rng=4, dtype=np.float32)
    x64 = spectral_noise(shape, exponent=exponent, rng=4, dtype=np.float64)
    assert np.all(np.isfinite(x32)) and np.abs(x32).max() > 0
    np.testing.assert_allclose(x32, x64, rtol=0, atol=1e-5 * np.abs(x64).max())
    y32 = spectral_noise(shape, exponent=exponent, rng=4, dtype=np.float32, normalize="sample")
    assert abs(float(y32.std(dtype=np.float64)) - 1) < 1e-4


def test_empty_band_and_single_sample_shape_are_refused():
    with pytest.raises(ValueError, match=r"band \(0.1, 0.2\) cycles/frame holds no frequency"):
        spectral_noise((64, 64), band=(0.1, 0.2))
    with pytest.raises(ValueError, match="no nonzero frequency"):
        spectral_noise((1, 1))
    with pytest.raises(ValueError, match="no nonzero frequency"):
        spectral_noise((1,))
    assert spectral_noise((1, 2), rng=0).shape == (1, 2)  # one nonzero frequency is enough


def test_synthesize_huge_and_tiny_envelopes_are_scaled_or_refused():
    env = lambda wy, wx: E.annulus(wy, wx, band_cycles_per_sample=(0.05, 0.3))  # noqa: E731
    ref, S = synthesize((32, 32), env, rng=1, dtype=np.float64, return_spectrum=True)
    for k in (1e300, 1e-300):
        big, Sb = synthesize((32, 32), lambda wy, wx: k * env(wy, wx), rng=1, dtype=np.float64,
                             return_spectrum=True)
        np.testing.assert_allclose(big, k * ref, rtol=1e-12, atol=0)
        np.testing.assert_allclose(Sb, k * S, rtol=1e-12, atol=0)
    small = synthesize((32, 32), lambda wy, wx: 1e-35 * env(wy, wx), rng=1, dtype=np.float32)
    np.testing.assert_allclose(small, 1e-35 * ref, rtol=1e-5, atol=1e-40)
    with pytest.raises(ValueError, match="envelope is too large for float32"):
        synthesize((32, 32), lambda wy, wx: 1e300 * env(wy, wx), rng=1)


# --- workers ---

@pytest.mark.parametrize("workers", [2, 3, -1])
def test_output_is_bit_identical_for_any_worker_count(workers):
    # big enough to be filled on several threads (at least 2**16 cells), and a small one filled on one
    cases = [((384, 512), None), ((40, 64, 80), None), ((96, 128, 128), (2, 40)), ((1 << 18,), None),
             ((64, 80), (2, 12))]
    for shape, band in cases:
        for normalize in ("expected", "sample"):
            a = spectral_noise(shape, band=band, rng=5, normalize=normalize, workers=1)
            b = spectral_noise(shape, band=band, rng=5, normalize=normalize, workers=workers)
            assert a.tobytes() == b.tobytes(), (shape, band, normalize)
    env = lambda wt, wy, wx: E.annulus(wt, wy, wx, band_cycles_per_sample=(0.02, 0.4))  # noqa: E731
    a = synthesize((48, 64, 80), env, rng=2, workers=1)
    assert a.tobytes() == synthesize((48, 64, 80), env, rng=2, workers=workers).tobytes()
    assert a.tobytes() == synthesize((48, 64, 80), env, rng=2).tobytes()


def test_workers_is_validated():
    for bad in (0, -10_000):
        with pytest.raises(ValueError, match="workers must be"):
            spectral_noise((16, 16), workers=bad)
    for bad in (1.5, "2", True):
        with pytest.raises(TypeError, match="workers must be"):
            synthesize((16, 16), lambda wy, wx: 1.0 + 0 * wy * wx, workers=bad)


def test_analysers_give_the_same_bits_for_any_worker_count():
    from noiselab import analysis as A
    from noiselab.snowfall import snow

    img = spectral_noise((96, 128), rng=1)
    video = snow((16, 64, 64), rng=2)
    assert A.power_spectrum(img, workers=1).power.tobytes() == A.power_spectrum(img, workers=2).power.tobytes()
    r1, r2 = A.radial_spectrum(img, workers=1), A.radial_spectrum(img, workers=-1)
    assert r1.power.tobytes() == r2.power.tobytes()
    band = (4, 16)
    assert A.tent_energy(video, 1.0, band, workers=1) == A.tent_energy(video, 1.0, band, workers=2)
    bands = [(2, 8), (8, 32)]
    assert A.band_speeds(video, bands, workers=1).tobytes() == A.band_speeds(video, bands, workers=-1).tobytes()


# --- one band validator, one unit per name, the plan shared with the dask path ---
def test_one_band_validator_gives_one_message_everywhere():
    import noiselab.analysis as A
    from noiselab.snowfall import flake_speeds, snow

    img = spectral_noise((64, 64), band=(2, 16), rng=0)
    nyquist = "band[1] = 40 cycles/frame is past the Nyquist frequency 32 cycles/frame"
    for call in (lambda b: spectral_noise((64, 64), band=b), lambda b: snow((2, 64, 64), band=b),
                 lambda b: flake_speeds(1.0, b, 64), lambda b: A.spectral_slope(img, b)):
        with pytest.raises(ValueError, match=nyquist.replace("[", r"\[").replace("]", r"\]")):
            call((4, 40))
        with pytest.raises(ValueError, match="band is empty: need lo < hi, got lo=9, hi=5 cycles/frame"):
            call((9, 5))
        with pytest.raises(TypeError, match="band must be an ordered .* got a set"):
            call({4, 8})
        with pytest.raises(ValueError, match=r"band must be a \(lo, hi\) pair in cycles/frame"):
            call((1, 2, 3))
    # the generators' bands may start at 0 (DC stays out unless dc=True); an analyser's log bins need lo > 0
    assert spectral_noise((64, 64), band=(0, 8), rng=0).shape == (64, 64)
    with pytest.raises(ValueError, match=r"band\[0\] \(cycles/frame\) must be in \(0, inf\)"):
        A.spectral_slope(img, (0, 8))


def test_annulus_band_says_its_unit_and_the_old_keywords_name_it():
    w = 2 * np.pi * np.array([0.0, 0.1, 0.2, 0.3, 0.45])
    new = E.annulus(w, band_cycles_per_sample=(0.1, 0.3))
    np.testing.assert_array_equal(new, [0, 1, 1, 1, 0])
    with pytest.raises(TypeError, match="band_cycles_per_sample"):
        E.annulus(w)
    for old in (dict(lo=0.1, hi=0.3), dict(lo=0.1), dict(band_cycles_per_sample=(0.1, 0.3), lo=0.1, hi=0.3)):
        with pytest.raises(TypeError, match=r"lo= and hi= were removed in noiselab 0\.4; pass band_cycles_per_sample"):
            E.annulus(w, **old)
    with pytest.raises(TypeError, match="unexpected keyword argument 'band'"):
        E.annulus(w, band=(0.1, 0.3))
    # spectral_noise's band in cycles/frame is annulus's in cycles/sample times the width
    shape, band = (48, 64), (3, 11)
    x = spectral_noise(shape, band=band, rng=2, dtype=np.float64)
    ring = E.annulus(*frequency_vectors(shape), band_cycles_per_sample=(band[0] / 64, band[1] / 64))
    P = np.abs(scipy.fft.rfftn(x)) ** 2
    assert P[ring == 0].max() < 1e-20 * P.max() and np.all(P[ring > 0] > 0)


def test_chunked_spectral_noise_and_snow_are_chosen_by_the_dispatch_registry():
    pytest.importorskip("dask")
    from noiselab._core import dispatch
    from noiselab.scale import spectral as SC

    assert dispatch.chunked("spectral_noise") is SC.chunked_spectral_noise
    assert dispatch.chunked("snow") is SC.chunked_snow


def test_the_plan_fills_the_same_block_slab_by_slab():
    # the dask path fills the block in slabs of its first axis (plan.fill_slab); the in-memory path in row
    # groups, into the rows of the field's storage: the same values, the same gain, the same scaled cells
    from noiselab.spectral import plan
    from noiselab.spectral import synthesis as SY

    for shape, band in [((40, 36), (2, 12)), ((12, 16, 20), (1, 6)), ((10, 12, 14), None), ((30, 32), None)]:
        for workers in (1, 2):
            p = plan.noise_plan(shape, 1.0, band, 7, "rayleigh", np.float64)
            buf, rows = SY._storage(p.shape, p.dt)
            g_mem = SY._fill_in_place(p, buf, rows, workers)
            n0 = p.bshape[0]
            parts = [plan.fill_slab(p, i0, min(n0, i0 + 3)) for i0 in range(0, n0, 3)]
            slabs = np.concatenate([s for s, _ in parts])
            planes = [np.ascontiguousarray(slabs[..., j]) for j in plan.self_conjugate_columns(p.n) if j < p.K]
            g = plan.hermitian_gain(p, np.concatenate([r for _, r in parts]), planes)
            for k, j in enumerate(j for j in plan.self_conjugate_columns(p.n) if j < p.K):
                slabs[..., j] = planes[k]
            assert g_mem == g
            kept = rows[SY._kept_rows(p), :p.K]
            np.testing.assert_array_equal(kept, (slabs * g).reshape(kept.shape))
            others = np.ones(rows.shape[0], dtype=bool)
            others[SY._kept_rows(p)] = False
            assert not np.any(rows[others, :p.K])  # the rows the band cannot reach are 0 where the passes read


_NOJIT_CASES = """
import numpy as np
from noiselab.spectral import spectral_noise, synthesize
from noiselab.spectral.envelopes import annulus
env = lambda wy, wx: annulus(wy, wx, band_cycles_per_sample=(0.05, 0.3))
out = [spectral_noise((16, 18), rng=1), spectral_noise((6, 8, 6), band=(1, 3), rng=2, exponent=1.5,
                                                        amplitude_distribution="uniform"),
       spectral_noise((20,), rng=3, exponent=0.7, normalize="sample", dtype=np.float64),
       spectral_noise((9, 10), rng=4, exponent=2.0, amplitude_distribution="fixed"),
       synthesize((12, 10), env, rng=5, amplitude_distribution="rayleigh")]
"""


def test_spectral_kernels_give_the_same_bits_without_the_jit(tmp_path):
    # NUMBA_DISABLE_JIT=1 runs the kernels' Python source (the bit casts of the draw through numpy views):
    # the same bits as the compiled kernels, for every amplitude law and fill variant used here
    import os
    import subprocess
    import sys

    script = _NOJIT_CASES + "np.save(__import__('sys').argv[1], np.concatenate([o.ravel().astype(np.float64) " \
                            "for o in out]))\n"
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    path = tmp_path / "nojit.npy"
    subprocess.run([sys.executable, "-W", "ignore", "-c", script, str(path)], env=env, check=True, timeout=300)
    ns = {}
    exec(_NOJIT_CASES, ns)
    want = np.concatenate([o.ravel().astype(np.float64) for o in ns["out"]])
    got = np.load(path)
    assert got.shape == want.shape and got.tobytes() == want.tobytes()


def test_the_plans_cache_changes_no_bit_and_keeps_no_failure():
    # the plan's geometry (rows, band intervals, law reference) is kept for repeated arguments; the key is not
    from noiselab.spectral import plan

    plan._geometry.cache_clear()
    a = spectral_noise((40, 36), band=(2, 12), rng=3, exponent=1.5)
    b = spectral_noise((40, 36), band=(2, 12), rng=3, exponent=1.5)
    c = spectral_noise((40, 36), band=(2, 12), rng=4, exponent=1.5)
    assert plan._geometry.cache_info().hits >= 2
    assert a.tobytes() == b.tobytes() and not np.array_equal(a, c)
    for _ in range(2):
        with pytest.raises(ValueError, match="holds no frequency"):
            spectral_noise((8, 8), band=(0.1, 0.2), rng=0)
