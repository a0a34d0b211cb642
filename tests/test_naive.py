"""The fast paths equal the slow, readable references of ``tests/naive.py`` on random inputs.

Only public, user-facing names are called (``noiselab.spectral``, ``noiselab.snowfall``,
``noiselab.analysis``, ``noiselab.LatticeNoise`` and its public attributes,
``noiselab.fractal_sum``, ...). Tolerances: 1e-12 in float64 (relative to the
field's scale where a field is not O(1)); float32 within the bound its
docstring states.
"""
import zlib

import numpy as np
import pytest

import naive
from _helpers import yx
from noiselab import LatticeNoise, fractal_gradient, fractal_sum, snow, turbulence, turbulence_gradient
from noiselab.analysis import motion_energy, radial_spectrum, spectral_slope, tent_energy
from noiselab.lattice import KERNELS, Grid
from noiselab.snowfall import snow_spectrum
from noiselab.spectral import draw_coefficients, envelopes, hermitian_plane, spectral_noise, synthesize

RNG = np.random.default_rng(20260501)


@pytest.fixture(autouse=True)
def _seed_per_test(request):
    """Each test draws its random inputs from its own name: the same inputs whichever tests run, in any order."""
    global RNG
    RNG = np.random.default_rng(zlib.crc32(request.node.nodeid.encode()))
TOL = 1e-12
F32_ULP = 2.0 ** -23  # float32's epsilon


def assert_close(got, want, tol=TOL, scale=None):
    """``|got - want| <= tol * scale`` everywhere, ``scale`` defaulting to ``max(1, max |want|)``."""
    got, want = np.asarray(got), np.asarray(want)
    assert got.shape == want.shape, (got.shape, want.shape)
    scale = max(1.0, float(np.max(np.abs(want), initial=0.0))) if scale is None else scale
    err = float(np.max(np.abs(got - want), initial=0.0))
    assert err <= tol * scale, f"max error {err:.3g} > {tol:.1g} x {scale:.3g}"


# ============================================================================ spectral

SHAPES = [(16,), (15,), (8, 12), (9, 7), (4, 6, 8), (5, 7, 9)]


@pytest.mark.parametrize("amplitude", ["uniform", "rayleigh", "fixed"])
def test_documented_float32_draws_are_the_exact_math_rounded(amplitude):
    # the float32 construction the reference reproduces bit for bit is the exact math of the
    # module notes to float32 rounding: cos and sin within 2**-23, a**2 within 2**-22 max(1, a**2) (a few
    # float32 roundings; absolute below 1, where the log sees only the 24 leading bits of u)
    key = naive.stream_key(11)
    a2, c, s = naive.coefficient_parts(key, 20000, amplitude)
    ea2, ec, es = naive.coefficient_parts_exact(key, 20000, amplitude)
    assert a2.dtype == c.dtype == s.dtype == np.float32
    assert np.max(np.abs(c - ec)) <= F32_ULP and np.max(np.abs(s - es)) <= F32_ULP
    assert np.all(np.abs(a2 - ea2) <= 2 * F32_ULP * np.maximum(1.0, ea2))
    assert abs(np.mean(ea2) - 1) < 0.03  # E[a**2] = 1


@pytest.mark.parametrize("amplitude", ["uniform", "rayleigh", "fixed"])
def test_draw_coefficients_equals_reference(amplitude):
    for n, seed in ((0, 1), (1, 2), (37, 3), (1000, 4)):
        got = draw_coefficients(n, np.random.default_rng(seed), amplitude, dtype=np.float64)
        assert got.dtype == np.complex128
        assert_close(got, naive.draw_coefficients(n, np.random.default_rng(seed), amplitude))
        # an int seed is a fresh default_rng(seed)
        assert np.array_equal(draw_coefficients(n, seed, amplitude, dtype=np.float64), got)


@pytest.mark.parametrize("shape", [(), (1,), (2,), (7,), (8,), (4, 6), (5, 5), (3, 4, 5), (4, 4, 2)])
def test_hermitian_plane_equals_reference(shape):
    plane = np.asarray(RNG.standard_normal(shape) + 1j * RNG.standard_normal(shape))
    plane[np.asarray(RNG.random(shape)) < 0.2] = 0  # holes: some pairs with one member outside the support
    support = plane != 0
    want = naive.hermitian_plane(plane, support)
    got = hermitian_plane(plane, support)
    assert_close(got, want)
    # Hermitian: P[-k] = conj(P[k]) exactly
    for k in np.ndindex(shape):
        assert got[naive.mirror_index(k, shape)] == np.conj(got[k])


@pytest.mark.parametrize("amplitude", ["uniform", "rayleigh", "fixed"])
@pytest.mark.parametrize("shape", SHAPES)
def test_synthesize_equals_reference_on_a_random_envelope(shape, amplitude):
    hshape = shape[:-1] + (shape[-1] // 2 + 1,)
    env = RNG.random(hshape) * (RNG.random(hshape) > 0.3)  # random amplitudes, random support (asymmetric)
    seed = int(RNG.integers(1 << 30))
    want_f, want_S = naive.synthesize(shape, env, seed, amplitude)
    f, S = synthesize(shape, env, rng=seed, amplitude_distribution=amplitude, dtype=np.float64, return_spectrum=True)
    assert f.dtype == np.float64 and S.dtype == np.complex128
    assert_close(S, want_S)
    assert_close(f, want_f)
    # float32 draws the same coefficients: the field agrees to float32 precision
    f32 = synthesize(shape, env, rng=seed, amplitude_distribution=amplitude, dtype=np.float32)
    assert f32.dtype == np.float32
    assert_close(f32, want_f, tol=1e-6)


@pytest.mark.parametrize("shape", [(32,), (12, 10), (6, 8, 9)])
def test_synthesize_equals_reference_on_a_callable_envelope(shape):
    n = shape[-1]

    def env(*w):
        return envelopes.annulus(*w, band_cycles_per_sample=(1.5 / n, 0.4)) * envelopes.power_law(*w, exponent=1.3)

    want_f, _ = naive.synthesize(shape, env, 5, "rayleigh")
    assert_close(synthesize(shape, env, rng=5, amplitude_distribution="rayleigh", dtype=np.float64), want_f)
    # the coefficients with exact (not float32) math give the same field to float32 precision
    exact_f, _ = naive.synthesize(shape, env, 5, "rayleigh", parts=naive.coefficient_parts_exact)
    assert_close(want_f, exact_f, tol=1e-5)


NOISE_CASES = [
    dict(exponent=1.0), dict(exponent=0.5, band=(1, 3)), dict(exponent=2.3, dc=True),
    dict(exponent=-1.0, band=(0.5, 4)), dict(exponent=0.0, normalize="sample"),
    dict(exponent=1.5, band=(0, 3), dc=True, normalize="sample", amplitude="uniform"),
    dict(exponent=2.0, amplitude="fixed"), dict(exponent=-0.7, dc=True, band=(0, 5)),
]


@pytest.mark.parametrize("case", NOISE_CASES, ids=lambda c: "-".join(f"{k}={v}" for k, v in c.items()))
@pytest.mark.parametrize("shape", SHAPES)
def test_spectral_noise_equals_reference(shape, case):
    kw = {**dict(amplitude="rayleigh", normalize="expected", band=None, dc=False), **case}
    if kw["band"] is not None:
        kw["band"] = (kw["band"][0], min(kw["band"][1], shape[-1] / 2))
    seed = int(RNG.integers(1 << 30))
    want = naive.spectral_noise(shape, seed=seed, **kw)
    api = {("amplitude_distribution" if k == "amplitude" else k): v for k, v in kw.items()}
    got = spectral_noise(shape, rng=seed, dtype=np.float64, **api)
    assert got.dtype == np.float64
    assert_close(got, want)
    got32 = spectral_noise(shape, rng=seed, dtype=np.float32, **api)
    assert_close(got32, want, tol=1e-5)


def test_spectral_noise_expected_variance_is_one_over_the_ensemble():
    # the reference's "expected" normalisation is the ensemble's: check it (not the package) by sampling
    v = np.mean([np.mean(naive.spectral_noise((24,), exponent=1.0, seed=s) ** 2) for s in range(300)])
    assert abs(v - 1) < 0.1


# ============================================================================ the tent (falling snow)

TENT_CASES = [
    ((8, 32, 32), dict()),  # the default band (W/32, W/4): 1..8 cycles/frame here, 16..128 at 512 px
    ((7, 24, 30), dict(c=0.8, thickness=0.3, direction=(1.0, 2.0), pan=(0.3, -0.2), band=(2, 9))),
    ((6, 20, 20), dict(c=0.5, thickness=0.0, exponent=1.5, band=(2, 10))),
    ((1, 16, 16), dict(thickness=0.2)),
    ((5, 16, 18), dict(c=0.3, thickness=1.0, direction=(-1.0, 0.0), pan=(-0.5, 0.2), band=(1, 9))),
    ((6, 16, 16), dict(c=2.5, thickness=0.5, band=(1, 8), on_alias="drop")),  # the cells past Nyquist left out
    ((4, 128, 128), dict(band=(16, 32), c=0.4)),
]


@pytest.mark.parametrize("shape,kw", TENT_CASES)
def test_tent_support_and_amplitudes_equal_reference(shape, kw):
    # amplitude="fixed": |S| is the envelope itself, independent of the order of the draws
    want = naive.tent_spectrum(shape, seed=1, amplitude="fixed", **kw)
    got = snow_spectrum(shape, rng=1, amplitude_distribution="fixed", dtype=np.float64, **yx(kw))
    assert got.shape == want.shape
    assert np.array_equal(got != 0, want != 0), "the tent's cells differ"
    assert (want != 0).any()
    assert_close(np.abs(got), np.abs(want))


@pytest.mark.parametrize("amplitude", ["uniform", "rayleigh"])
@pytest.mark.parametrize("shape,kw", TENT_CASES[:6])
def test_tent_spectrum_and_snow_equal_reference(shape, kw, amplitude):
    want = naive.tent_spectrum(shape, seed=7, amplitude=amplitude, **kw)
    assert_close(snow_spectrum(shape, rng=7, amplitude_distribution=amplitude, dtype=np.float64, **yx(kw)), want)
    raw = np.fft.irfftn(want, s=shape, axes=(0, 1, 2))
    assert_close(snow(shape, rng=7, amplitude_distribution=amplitude, dtype=np.float64, rescale=False, **yx(kw)), raw)
    alpha = snow(shape, rng=7, amplitude_distribution=amplitude, dtype=np.float64, beta=1.5, **yx(kw))
    assert_close(alpha, naive.rescale_opacity(raw, 1.5))


@pytest.mark.parametrize("c,direction,pan", [(1.0, (0.0, 1.0), (0.0, 0.0)), (0.7, (1.0, -2.0), (0.3, 0.1)),
                                             (2.0, (-1.0, 0.0), (-0.5, 0.0))])
def test_envelopes_equal_reference(c, direction, pan):
    wt, wy, wx = naive.frequency_vectors((6, 10, 12))
    surf, along = naive.tent_surface(wy, wx, c, direction, pan)
    assert_close(envelopes.tent_surface(wy, wx, c, direction_yx=direction[::-1], pan_yx=pan[::-1]), surf)
    tol = np.pi / 6
    want = (np.abs(wt - surf) <= tol).astype(float)
    sheared = envelopes.sheared_tent(wt, wy, wx, c, direction_yx=direction[::-1], pan_yx=pan[::-1], tol=tol)
    assert np.array_equal(sheared, want)
    if pan == (0.0, 0.0):
        assert np.array_equal(envelopes.tent(wt, wy, wx, c, direction_yx=direction[::-1], tol=tol), want)
    thick = (np.abs(wt - surf) <= tol + 0.3 * c * along).astype(float)
    assert np.array_equal(envelopes.thickened_tent(wt, wy, wx, c, thickness=0.3, tol=tol,
                                                     **yx(dict(direction=direction, pan=pan))), thick)
    cells, law = naive.noise_envelope((6, 10, 12), 1.5, (2, 4), False)  # band (2, 4) cycles per 12 samples
    got = envelopes.annulus(wt, wy, wx, band_cycles_per_sample=(2 / 12, 4 / 12)) * envelopes.power_law(wt, wy, wx, exponent=1.5)
    assert np.array_equal(got > 0, cells)
    # the reference law is in cycles/sample, the envelope's in rad/sample: a constant factor (2 pi)**-1.5
    assert_close(got[cells], law[cells] * (2 * np.pi) ** -1.5)


def test_tent_moves_flakes_at_c_over_w():
    # the reference's sign, checked on a translating pattern: a cosine of spatial frequency |w| moving
    # down at c/|w| px/frame has all its energy on the reference tent (and none on the opposite one)
    T, H, W = 16, 32, 32
    c = np.pi / 4
    w = 2 * np.pi * 4 / H
    t, y, x = np.mgrid[:T, :H, :W].astype(float)
    video = np.cos(w * (y - c / w * t))
    assert naive.tent_energy(video, c, (2, 8), thickness=0) > 1 - 1e-12
    assert naive.tent_energy(video, c, (2, 8), direction=(0, -1), thickness=0) < 1e-12


# ============================================================================ analysers


def _field(shape, exponent=1.0, seed=0):
    """A random field with roughly 1/f**exponent amplitude (any shape): white noise filtered in plain numpy."""
    rng = np.random.default_rng(seed)
    F = np.fft.fftn(rng.standard_normal(shape))
    f = naive.radial_frequency_cpf(shape)
    f.flat[0] = 1.0
    return np.real(np.fft.ifftn(F / f ** exponent)) + 3.0  # a mean, which the spectra must ignore


def _assert_radial(got, want):
    for name in ("centers", "power", "counts", "mean_frequency"):
        assert_close(getattr(got, name), want[name], scale=float(np.max(np.abs(want[name]))))
    assert_close(got.variance, want["variance"], scale=float(np.max(want["power"])) ** 2)
    assert_close(got.total, want["total"], scale=want["total"])


@pytest.mark.parametrize("log", [False, True])
@pytest.mark.parametrize("shape", [(64,), (32, 48), (40, 40), (8, 16, 16), (6, 12, 10)])
def test_radial_spectrum_equals_reference(shape, log):
    field = _field(shape, seed=len(shape))
    _assert_radial(radial_spectrum(field, log=log), naive.radial_spectrum(field, log=log))


def test_radial_spectrum_with_edges_and_of_a_video_equals_reference():
    field = _field((30, 36), exponent=0.5, seed=3)
    edges = np.array([0.7, 2.0, 3.3, 7.0, 12.5, 18.0])
    _assert_radial(radial_spectrum(field, bins=edges), naive.radial_spectrum(field, edges=edges))
    video = _field((6, 16, 20), seed=4)
    _assert_radial(radial_spectrum(video, axes=(-2, -1)), naive.radial_spectrum(video, frames=True))


@pytest.mark.parametrize("shape,band,bpo", [((64, 64), (2, 16), 8), ((96, 80), (3, 20), 4), ((128,), (2, 40), 6),
                                            ((16, 32, 32), (2, 8), 8)])
def test_spectral_slope_equals_reference(shape, band, bpo):
    field = _field(shape, exponent=1.0, seed=9)
    got = spectral_slope(field, band, bins_per_octave=bpo)
    slope, intercept, error = naive.spectral_slope(field, band, bpo)
    assert abs(float(got) - slope) <= TOL and abs(got.intercept - intercept) <= TOL
    assert abs(got.error - error) <= TOL * max(1.0, error)
    assert abs(got.power_slope - 2 * slope) <= 2 * TOL


def _video(shape, velocity, seed):
    """Random texture translating at an integer velocity, plus a little noise."""
    rng = np.random.default_rng(seed)
    img = rng.random(shape[1:])
    vx, vy = velocity
    v = np.stack([np.roll(img, (vy * t, vx * t), axis=(0, 1)) for t in range(shape[0])])
    return v + 0.3 * rng.random(shape)


@pytest.mark.parametrize("velocity,tol,band,window", [
    ((1.0, 2.0), 0.5, None, None), ((0.5, -1.0), 1.0, (2, 6), None), ((1.0, 2.0), 1.5, None, "hann"),
    ((-2.0, 0.0), 0.0, (1, 8), None), ((0.3, 0.4), 2.5, (3, 7), "hann"),
])
def test_motion_energy_equals_reference(velocity, tol, band, window):
    video = _video((8, 12, 16), (1, 2), seed=5)
    got = motion_energy(video, velocity_yx=velocity[::-1], tol=tol, band=band, window=window)
    assert abs(got - naive.motion_energy(video, velocity, tol, band, window)) <= TOL


@pytest.mark.parametrize("kw", [dict(), dict(thickness=0.0, tol=1.0), dict(direction=(1, 1), pan=(0.5, 0)),
                                dict(window="hann", thickness=0.3)])
def test_tent_energy_equals_reference(kw):
    shape = (8, 16, 16)
    video = np.fft.irfftn(naive.tent_spectrum(shape, seed=2, c=0.9, band=(2, 7)), s=shape, axes=(0, 1, 2))
    video = video / video.std() + 0.2 * np.random.default_rng(1).random(shape)
    got = tent_energy(video, 0.9, (2, 7), **yx(kw))
    assert abs(got - naive.tent_energy(video, 0.9, (2, 7), **kw)) <= TOL
    assert naive.tent_energy(video, 0.9, (2, 7)) > 0.5  # most of the power is on the tent it was built on


# ============================================================================ lattice


@pytest.mark.parametrize("name", sorted(KERNELS))
def test_kernels_equal_reference(name):
    assert set(KERNELS) == set(naive.KERNELS)
    k = KERNELS[name]
    y = np.concatenate([RNG.uniform(-2.5, 2.5, 2000), np.arange(-5, 6) / 2])  # knots included
    assert_close(k(y), naive.KERNELS[name](y))
    if name in naive.DERIVATIVES:
        assert k.continuity >= 1
        assert_close(k.derivative(y), naive.DERIVATIVES[name](y))
        # the reference derivative is the reference kernel's (off the knots, where K'' jumps)
        h, yr = 1e-6, y[:2000]
        assert_close((naive.KERNELS[name](yr + h) - naive.KERNELS[name](yr - h)) / (2 * h),
                     naive.DERIVATIVES[name](yr), tol=1e-8)
    else:
        assert k.continuity < 1


@pytest.mark.parametrize("name", sorted(KERNELS))
def test_range_bounds_equal_reference(name):
    S, Q = naive.kernel_sums(name)
    assert S == pytest.approx({"catmull-rom": 1.25}.get(name, 1.0), abs=1e-13)  # the documented values
    for d in (1, 2, 3, 4):
        for basis, want in (("value", S ** d), ("gradient", np.sqrt(d * Q) * S ** (d - 0.5))):
            bound = LatticeNoise(d, kernel=name, basis=basis).bound
            # proved bound, rounded up by at most 1e-11 (kernels.py: suprema "rounded up")
            assert want <= bound <= want * (1 + 1e-11), (d, basis, bound, want)


@pytest.mark.parametrize("hash", ["table", "integer"])
def test_tables_from_the_seed_equal_the_public_attributes(hash):
    for d, c, n in ((1, 1, 256), (3, 2, 256), (2, 3, 10)):
        noise = LatticeNoise(d, c, rng=17, table_size=n, hash=hash)
        ref = naive.NaiveLattice(d, c, rng=17, table_size=n, hash=hash)
        assert np.array_equal(noise.perms, np.stack(ref.perms))
        assert np.array_equal(noise.positive, ref.positive) and np.array_equal(noise.negative, ref.negative)
        assert np.allclose(noise.gradients, ref.gradients, rtol=0, atol=1e-15)
        interleaved = np.where(np.arange(n) % 2 == 0, ref.positive, ref.negative)
        assert np.array_equal(noise.values, np.stack([interleaved, interleaved]))
        assert np.array_equal(noise.period, ref.period)


def _pair(dim, dim_out=1, **kw):
    return LatticeNoise(dim, dim_out, **kw), naive.NaiveLattice(dim, dim_out, **kw)


def _points(n, dim, lo=-20.0, hi=20.0):
    return RNG.uniform(lo, hi, (n, dim))


def _want(ref, noise, x):
    """The reference at points ``x``, shaped as the package returns it."""
    v = ref(x.reshape(-1, noise.dim_in), noise.bound)
    return v[:, 0].reshape(x.shape[:-1]) if noise.dim_out == 1 else v.reshape(x.shape[:-1] + (noise.dim_out,))


def _check_float32(noise, x, want):
    """float32 points give float32 output: a rounding of the float64 result (either hash: every path computes
    in float64 and rounds once)."""
    got = noise(x.astype(np.float32))
    x32 = x.astype(np.float32).astype(np.float64)
    assert got.dtype == np.float32
    want32 = want(x32)
    assert np.all(np.abs(got - want32) <= np.spacing(np.abs(want32).astype(np.float32)) + 1e-12)
    got = noise(x, dtype=np.float32)
    assert got.dtype == np.float32
    assert np.all(np.abs(got - want(x)) <= np.spacing(np.abs(want(x)).astype(np.float32)) + 1e-12)


@pytest.mark.parametrize("hash", ["table", "integer"])
@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("kernel", sorted(KERNELS))
def test_every_kernel_and_basis_in_2d_points_and_grid(kernel, basis, hash):
    noise, ref = _pair(2, rng=3, kernel=kernel, basis=basis, hash=hash, frequency=(1.3, 0.7), phase=(0.2, -1.1),
                       amplitude=1.5)
    x = _points(150, 2)
    assert_close(noise(x), _want(ref, noise, x))
    _check_float32(noise, x, lambda p: _want(ref, noise, p))
    shape, extent = (11, 13), [(-3.0, 5.0), (2.0, 9.0)]
    pts = naive.grid_points(shape, extent)
    assert np.array_equal(noise.grid_points(shape, extent), pts)
    want = _want(ref, noise, pts)
    assert_close(noise.grid(shape, extent), want)
    g32 = noise.grid(shape, extent, dtype=np.float32)
    assert g32.dtype == np.float32
    assert np.all(np.abs(g32 - want) <= np.spacing(np.abs(want).astype(np.float32)) + 1e-12)


DIM_CASES = [(d, k) for d in (1, 2, 3, 4) for k in ("cubic", "quintic")]


@pytest.mark.parametrize("hash", ["table", "integer"])
@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("dim,kernel", DIM_CASES)
def test_every_dimension_points_and_grids(dim, kernel, basis, hash):
    dim_out = 2 if dim in (2, 3) else 1
    noise, ref = _pair(dim, dim_out, rng=dim, kernel=kernel, basis=basis, hash=hash, frequency=1.7, phase=0.3)
    x = _points(100 if dim < 4 else 40, dim)
    assert_close(noise(x), _want(ref, noise, x))
    _check_float32(noise, x, lambda p: _want(ref, noise, p))
    if dim == 1:  # a plain array of scalar inputs
        assert_close(noise(x[:, 0]), _want(ref, noise, x))
    # a power-of-two frequency and no phase: the integer hash's all-float32 kernel (exact float32 split)
    noise2, ref2 = _pair(dim, rng=dim, kernel=kernel, basis=basis, hash=hash, frequency=2.0)
    assert_close(noise2(x), _want(ref2, noise2, x))
    _check_float32(noise2, x, lambda p: _want(ref2, noise2, p))
    shape = {1: (17,), 2: (9, 7), 3: (5, 6, 4), 4: (3, 4, 3, 2)}[dim]
    extent = [(-2.0 + a, 1.5 + 2 * a) for a in range(dim)]
    want = _want(ref, noise, naive.grid_points(shape, extent))
    assert_close(noise.grid(shape, extent), want)
    # a grid sparser than the lattice takes the per-point path
    sparse = [(0.0, 400.0 + 37 * a) for a in range(dim)]
    assert_close(noise.grid(shape, sparse), _want(ref, noise, naive.grid_points(shape, sparse)))


@pytest.mark.parametrize("hash", ["table", "integer"])
@pytest.mark.parametrize("dim", [1, 2, 3, 4])
def test_periods_table_sizes_and_alternation(dim, hash):
    cases = [dict(table_size=10, kernel="catmull-rom"), dict(period=6, kernel="quadratic", basis="gradient"),
             dict(period=[5, 8, 7, 4][:dim], kernel="box")]
    if hash == "table":
        cases += [dict(alternation="lattice", period=6, kernel="linear"),
                  dict(alternation="lattice", table_size=12, kernel="cubic"), dict(period=512, kernel="quintic")]
    for kw in cases:
        noise, ref = _pair(dim, rng=5, hash=hash, frequency=1.3, **kw)
        x = _points(60 if dim < 4 else 25, dim, -30, 30)
        assert_close(noise(x), _want(ref, noise, x))
        shape = (7,) * dim if dim < 4 else (3, 2, 3, 4)
        extent = [(-4.0, 4.5)] * dim
        assert_close(noise.grid(shape, extent), _want(ref, noise, naive.grid_points(shape, extent)))
        if "period" in kw:  # tiles exactly with period / frequency
            shifted = x + np.asarray(noise.period) / 1.3
            assert_close(noise(shifted), noise(x), tol=1e-9)


C1 = sorted(naive.DERIVATIVES)


def _want_jac(ref, noise, x):
    j = ref.jacobian(x.reshape(-1, noise.dim_in), noise.bound)
    return j[:, 0] if noise.dim_out == 1 else j


@pytest.mark.parametrize("hash", ["table", "integer"])
@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("kernel", C1)
def test_jacobian_every_c1_kernel_in_2d(kernel, basis, hash):
    noise, ref = _pair(2, 2, rng=9, kernel=kernel, basis=basis, hash=hash, frequency=(2.1, 0.9), phase=0.4,
                       amplitude=0.8)
    x = _points(80, 2)
    value, jac = noise.jacobian(x, return_value=True)
    assert_close(jac, _want_jac(ref, noise, x))
    assert_close(value, _want(ref, noise, x))
    shape, extent = (9, 10), [(-1.0, 3.0), (0.5, 4.0)]
    pts = naive.grid_points(shape, extent).reshape(-1, 2)
    assert_close(noise.jacobian_grid(shape, extent), _want_jac(ref, noise, pts).reshape(shape + (2, 2)))


@pytest.mark.parametrize("hash", ["table", "integer"])
@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("dim", [1, 2, 3, 4])
def test_gradient_every_dimension(dim, basis, hash):
    noise, ref = _pair(dim, rng=12, kernel="cubic", basis=basis, hash=hash, frequency=1.9, phase=-0.6)
    x = _points(50 if dim < 4 else 20, dim)
    value, grad = noise.gradient(x, return_value=True)
    assert_close(grad, _want_jac(ref, noise, x))
    assert_close(value, _want(ref, noise, x))
    shape = {1: (13,), 2: (6, 7), 3: (4, 5, 3), 4: (2, 3, 2, 3)}[dim]
    extent = [(-1.0, 2.0 + a) for a in range(dim)]
    pts = naive.grid_points(shape, extent).reshape(-1, dim)
    assert_close(noise.gradient_grid(shape, extent), _want_jac(ref, noise, pts).reshape(shape + (dim,)))


@pytest.mark.parametrize("kernel", ["box", "linear"])
def test_derivatives_refused_for_kernels_without_a_continuous_derivative(kernel):
    with pytest.raises(ValueError, match="kernel"):
        LatticeNoise(2, kernel=kernel).gradient(np.zeros((1, 2)))


OCTAVE_CASES = [(1, "cubic", "value"), (2, "quintic", "gradient"), (2, "catmull-rom", "value"),
                (3, "quadratic", "value"), (3, "quintic", "gradient"), (4, "cubic", "value")]


@pytest.mark.parametrize("hash", ["table", "integer"])
@pytest.mark.parametrize("dim,kernel,basis", OCTAVE_CASES)
def test_fractal_sum_and_turbulence_points_and_grids(dim, kernel, basis, hash):
    noise, ref = _pair(dim, rng=21, kernel=kernel, basis=basis, hash=hash, frequency=1.1, phase=0.25)
    x = _points(60 if dim < 4 else 20, dim, -6, 6)
    octaves = 4 if dim < 4 else 3
    shape = {1: (40,), 2: (12, 14), 3: (6, 7, 5), 4: (3, 3, 4, 3)}[dim]
    # samples 0.09 apart: finer than the last octave's lattice (1.1 * 2**3 cells per unit), so every octave is visible
    extent = [(-1.5 + 0.2 * a, -1.5 + 0.2 * a + 0.09 * n) for a, n in enumerate(shape)]
    pts = naive.grid_points(shape, extent).reshape(-1, dim)
    total = sum(0.5 ** o for o in range(octaves))
    for func, turb in ((fractal_sum, False), (turbulence, True)):
        want = naive.fractal_sum(ref, x, noise.bound, octaves, turbulence=turb)[:, 0]
        got, used = func(noise, x, octaves, return_octaves=True)
        assert used == octaves
        assert_close(got, want)
        assert_close(func(noise, x, octaves, normalize=True), want / total)
        got32 = func(noise, x, octaves, dtype=np.float32)
        assert got32.dtype == np.float32
        tol32 = F32_ULP * total if hash == "table" else 8e-7 * total
        assert_close(got32, want, tol=tol32, scale=1.0)
        want_grid = naive.fractal_sum(ref, pts, noise.bound, octaves, turbulence=turb)[:, 0].reshape(shape)
        got_grid, used = func(noise, Grid(shape, extent), octaves, return_octaves=True)
        assert used == octaves
        assert_close(got_grid, want_grid)
        g32 = func(noise, Grid(shape, extent), octaves, dtype=np.float32)
        assert g32.dtype == np.float32
        assert_close(g32, want_grid, tol=F32_ULP * total, scale=1.0)


def test_fractal_sum_with_another_lacunarity_and_gain_and_vector_noise():
    noise, ref = _pair(2, 3, rng=4, kernel="catmull-rom", frequency=0.8)
    x = _points(70, 2, -5, 5)
    want = naive.fractal_sum(ref, x, noise.bound, 5, lacunarity=1.9, gain=0.6)
    assert_close(fractal_sum(noise, x, 5, lacunarity=1.9, gain=0.6), want)
    want = naive.fractal_sum(ref, x, noise.bound, 5, lacunarity=2.5, gain=0.3, turbulence=True)
    assert_close(turbulence(noise, x, 5, lacunarity=2.5, gain=0.3), want)


TILE_CASES = [(1, "cubic", "value", 3), (2, "quintic", "gradient", [4, 3]), (2, "catmull-rom", "value", 5),
              (3, "quintic", "value", 3)]


@pytest.mark.parametrize("hash", ["table", "integer"])
@pytest.mark.parametrize("dim,kernel,basis,period", TILE_CASES)
def test_tileable_octave_sums_take_a_period_per_octave(dim, kernel, basis, period, hash):
    """A tileable noise's octave o has the lattice period ``period * lacunarity**o`` (the reference's
    ``NaiveLattice.octave``): fractal sums, turbulence and their gradients, on points and grids."""
    noise, ref = _pair(dim, rng=5, kernel=kernel, basis=basis, hash=hash, period=period, frequency=1.3, phase=0.2)
    x = _points(50 if dim < 3 else 25, dim, -6, 6)
    shape = {1: (40,), 2: (12, 14), 3: (6, 7, 5)}[dim]
    extent = [(-1.5 + 0.2 * a, -1.5 + 0.2 * a + 0.07 * n) for a, n in enumerate(shape)]  # every octave visible
    pts = naive.grid_points(shape, extent).reshape(-1, dim)
    for lacunarity, octaves in ((2.0, 4), (3.0, 3)):
        kw = dict(lacunarity=lacunarity)
        for func, turb in ((fractal_sum, False), (turbulence, True)):
            want = naive.fractal_sum(ref, x, noise.bound, octaves, lacunarity, turbulence=turb)[:, 0]
            assert_close(func(noise, x, octaves, **kw), want)
            want_grid = naive.fractal_sum(ref, pts, noise.bound, octaves, lacunarity, turbulence=turb)[:, 0]
            got_grid, used = func(noise, Grid(shape, extent), octaves, return_octaves=True, **kw)
            assert used == octaves
            assert_close(got_grid, want_grid.reshape(shape))
        for func, turb in ((fractal_gradient, False), (turbulence_gradient, True)):
            want = naive.fractal_gradient(ref, x, noise.bound, octaves, lacunarity, turbulence=turb)[:, 0]
            value, grad = func(noise, x, octaves, return_value=True, **kw)
            assert_close(grad, want)
            assert_close(value, naive.fractal_sum(ref, x, noise.bound, octaves, lacunarity, turbulence=turb)[:, 0])
        want = naive.fractal_gradient(ref, pts, noise.bound, octaves, lacunarity)[:, 0].reshape(shape + (dim,))
        assert_close(fractal_gradient(noise, Grid(shape, extent), octaves, **kw), want)
    # the reference with one period for every octave (the old sum) is another function
    old = naive.NaiveLattice(dim, rng=5, kernel=kernel, basis=basis, hash=hash, period=period, frequency=1.3,
                             phase=0.2)
    old.tileable = False
    assert np.abs(naive.fractal_sum(old, x, noise.bound, 4)[:, 0] - fractal_sum(noise, x, 4)).max() > 0.01


@pytest.mark.parametrize("hash", ["table", "integer"])
@pytest.mark.parametrize("dim,kernel,basis", [(1, "quintic", "value"), (2, "cubic", "gradient"),
                                              (3, "catmull-rom", "value"), (4, "quadratic", "gradient")])
def test_fractal_and_turbulence_gradients(dim, kernel, basis, hash):
    noise, ref = _pair(dim, rng=8, kernel=kernel, basis=basis, hash=hash, frequency=1.2)
    x = _points(40 if dim < 4 else 15, dim, -4, 4)
    for func, turb in ((fractal_gradient, False), (turbulence_gradient, True)):
        want = naive.fractal_gradient(ref, x, noise.bound, 3, turbulence=turb)[:, 0]
        value, grad = func(noise, x, 3, return_value=True)
        assert_close(grad, want)
        assert_close(value, naive.fractal_sum(ref, x, noise.bound, 3, turbulence=turb)[:, 0])
    shape = {1: (20,), 2: (8, 9), 3: (4, 5, 4), 4: (3, 2, 3, 2)}[dim]
    extent = [(-1.0 + 0.3 * a, -1.0 + 0.3 * a + 0.15 * n) for a, n in enumerate(shape)]  # every octave visible
    pts = naive.grid_points(shape, extent).reshape(-1, dim)
    want = naive.fractal_gradient(ref, pts, noise.bound, 3)[:, 0].reshape(shape + (dim,))
    got, used = fractal_gradient(noise, Grid(shape, extent), 3, return_octaves=True)
    assert used == 3
    assert_close(got, want)


@pytest.mark.parametrize("shape,extent,frequency,octaves", [
    ((256, 256), [(0, 4), (0, 4)], 1.0, 60), ((64,), [(0, 2)], 3.0, 10), ((16, 300), [(0, 1), (0, 300)], 1.0, 8),
    ((32, 32), [(0, 100), (0, 100)], 1.0, 5), ((8, 8, 8), [(0, 1)] * 3, 2.0, 40)])
def test_visible_octaves_follow_the_documented_rule(shape, extent, frequency, octaves):
    noise = LatticeNoise(len(shape), frequency=frequency, kernel="linear")
    spacing = [(hi - lo) / n for n, (lo, hi) in zip(shape, extent)]
    _, used = fractal_sum(noise, Grid(shape, extent), octaves, return_octaves=True)
    assert used == naive.visible_octaves(octaves, spacing, frequency)
