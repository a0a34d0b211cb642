"""LatticeNoise(hash="integer"): the arithmetic integer hash beside Phillips' permutation table.

The same guarantees as the table hash (range, determinism, both evaluation
paths, periods, derivatives, bit-identity across chunkings), and the
property it is there for: no 256-cell period and none of the nested
permutation's row/column artefacts.
"""
import numpy as np
import pytest

from noiselab import LatticeNoise, fractal_sum
from noiselab.analysis import axis_artefacts, detect_period
from noiselab.lattice import KERNELS, Grid, _inthash

RNG = np.random.default_rng(2024)
C1_KERNELS = [name for name, k in KERNELS.items() if k.continuity >= 1]


def _int(dim, dim_out=1, **kw):
    return LatticeNoise(dim, dim_out, hash="integer", **kw)


@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("dim", [1, 2, 3, 4])
def test_range_within_bound_and_not_vacuous(dim, basis):
    for name in ("box", "catmull-rom", "quintic"):
        noise = _int(dim, rng=3, kernel=name, basis=basis, frequency=1.7)
        v = noise(RNG.uniform(-50, 50, (4000 if dim < 4 else 1500, dim)))
        assert np.abs(v).max() <= 1.0, (name, dim, basis)
        # the bound is not vacuous: the field uses a good part of it
        assert np.abs(v).max() > (0.5 if basis == "value" else 0.25) / dim, (name, dim, basis)


def _mix32_py(h):
    """The documented hash word in plain Python integers (independent of the numba code)."""
    h &= 0xFFFFFFFF
    h ^= h >> 16
    h = (h * 0x85EBCA6B) & 0xFFFFFFFF
    h ^= h >> 13
    return (h * 0xC2B2AE35) & 0xFFFFFFFF


def _word(noise, c, j):
    """``mix32(key_c ^ j_0 M_0 ^ ... )`` for one lattice point (indices reduced mod 2**32)."""
    h = int(noise.keys[c])
    for a, ja in enumerate(j):
        h ^= ((int(ja) % (1 << 32)) * int(noise._mult[a])) & 0xFFFFFFFF
    return _mix32_py(h)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("dim", [1, 2, 3, 4])
def test_values_at_lattice_points_are_the_documented_hash(dim, dtype):
    # interpolating kernels pass through the lattice values: v = int32(mix32(key ^ j_0 M_0 ^ ...)) / 2**31
    noise = _int(dim, 2, rng=5, kernel="catmull-rom")
    j = RNG.integers(-1000, 1000, (200, dim))
    got = noise(j.astype(dtype))
    assert got.dtype == dtype
    for c in range(2):
        words = np.array([_word(noise, c, row) for row in j], dtype=np.uint32)
        want = words.view(np.int32).astype(np.float64) / 2.0 ** 31
        tol = 1e-15 if dtype == np.float64 else 1.2e-7   # float32: the values rounded to 24 bits
        np.testing.assert_allclose(got[:, c], want * noise.scale, rtol=0, atol=tol)
    # and they spread over [-1, 1): mean near 0, variance near 1/3
    vals = _int(1, rng=1, kernel="catmull-rom", amplitude=1.0)(np.arange(20000.0)) / 0.8
    assert abs(vals.mean()) < 0.02 and abs(vals.var() - 1 / 3) < 0.02


@pytest.mark.parametrize("dim", [1, 2, 3])
def test_gradients_are_the_documented_set(dim):
    # gradient noise with the linear kernel, one cell from a lattice point along axis a, is g_a(j) times the
    # distance (the other corners' weights vanish there): the gradient picked by the word's top bits
    noise = _int(dim, rng=8, kernel="linear", basis="gradient")
    grads = _inthash.gradient_set(dim, noise.gradients)
    assert grads.shape == ({1: 2, 2: 8, 3: 16}[dim], dim)
    np.testing.assert_allclose(np.linalg.norm(grads, axis=1), 1.0, rtol=1e-15)
    j = RNG.integers(-500, 500, (100, dim))
    for a in range(dim):
        x = j.astype(np.float64)
        x[:, a] += 0.25
        got = noise(x) / noise.scale
        idx = np.array([(_word(noise, 0, row) * len(grads)) >> 32 for row in j])
        # the far corner (j + e_a) contributes too: weight 1/4 times its dot product with -3/4 e_a
        far = j.copy()
        far[:, a] += 1
        idx_far = np.array([(_word(noise, 0, row) * len(grads)) >> 32 for row in far])
        want = 0.75 * grads[idx, a] * 0.25 + 0.25 * grads[idx_far, a] * -0.75
        np.testing.assert_allclose(got, want, atol=1e-14)
    # the 3-D set is Perlin's 16: the 12 cube-edge directions, four of them twice
    if dim == 3:
        edges = {tuple(np.round(g * np.sqrt(2)).astype(int)) for g in grads}
        assert len(edges) == 12 and all(sorted(map(abs, e)) == [0, 1, 1] for e in edges)


def test_deterministic_and_seeded():
    pts = RNG.uniform(-20, 20, (3000, 3))
    a = _int(3, rng=7, kernel="quintic")(pts)
    np.testing.assert_array_equal(a, _int(3, rng=7, kernel="quintic")(pts))
    np.testing.assert_array_equal(a, _int(3, rng=np.random.default_rng(7), kernel="quintic")(pts))
    b = _int(3, rng=8, kernel="quintic")(pts)
    assert abs(np.corrcoef(a, b)[0, 1]) < 0.1
    # components are independent too, and the first ones do not depend on dim_out
    two = _int(3, 2, rng=7, kernel="quintic")(pts)
    three = _int(3, 3, rng=7, kernel="quintic")(pts)
    np.testing.assert_array_equal(two, three[:, :2])
    assert abs(np.corrcoef(three[:, 0], three[:, 1])[0, 1]) < 0.1
    # and the integer hash is a different noise from the table hash of the same seed
    assert abs(np.corrcoef(a, LatticeNoise(3, rng=7, kernel="quintic")(pts))[0, 1]) < 0.1


@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("dim", [1, 2, 3])
def test_grid_and_points_agree(dim, basis):
    shape = {1: (300,), 2: (40, 30), 3: (12, 10, 9)}[dim]
    ext = [(-3.1, 4.5), (0.2, 6.0), (-2.0, 1.0)][:dim]
    for name in ("linear", "cubic", "catmull-rom", "quintic"):
        noise = _int(dim, 2, rng=2, kernel=name, basis=basis, frequency=1.3, phase=0.25)
        np.testing.assert_allclose(noise.grid(shape, ext), noise(noise.grid_points(shape, ext)), atol=1e-12)


def test_float32_output_error_against_float64():
    # float32 output is the float64 result rounded once: half a float32 ulp of it, never out of range
    for dim in (1, 2, 3):
        pts = RNG.uniform(-1e4, 1e4, (20000, dim))
        for name in (("catmull-rom", "quintic") if dim == 2 else ("quintic",)):   # 4-tap in 2-D (compile time)
            for basis in ("value", "gradient"):
                noise = _int(dim, rng=1, kernel=name, basis=basis, frequency=0.37, phase=0.2)
                v64, v32 = noise(pts), noise(pts, dtype=np.float32)
                assert v32.dtype == np.float32 and np.abs(v32).max() <= 1.0
                np.testing.assert_array_equal(v32, v64.astype(np.float32))


def test_chunkings_threads_and_windows_are_bit_identical():
    noise = _int(3, 2, rng=2, kernel="quintic", basis="gradient")
    pts = RNG.uniform(-30, 30, (5000, 3))
    pts[::5] += 1e13    # past 2**52: no fractional bits
    pts[::11] *= 1e17   # far out: those chunks take the exact reduction
    whole = noise(pts)
    parts = np.concatenate([noise(pts[i:i + 137]) for i in range(0, 5000, 137)])
    np.testing.assert_array_equal(whole, parts)
    np.testing.assert_array_equal(noise(pts, workers=3), whole)
    np.testing.assert_array_equal(np.array([noise(p) for p in pts[:40]]), whole[:40])
    shape, ext = (24, 20, 16), [(0, 5), (2, 9), (-1, 1)]
    full = noise.grid(shape, ext)
    np.testing.assert_array_equal(noise.grid(shape, ext, window=[(5, 19), (0, 20), (3, 11)]), full[5:19, :, 3:11])


@pytest.mark.parametrize("dim", [1, 2, 3, 4])
def test_periods_tile_exactly(dim):
    period = [5, 8, 6, 3][:dim]         # powers of two and not
    noise = _int(dim, rng=9, kernel="cubic", period=period, frequency=2.0)
    x = np.round(RNG.uniform(-10, 10, (500, dim)) * 64) / 64   # dyadic: x + period / frequency is exact
    v = noise(x)
    for a in range(dim):
        shifted = x.copy()
        shifted[:, a] += period[a] / 2.0
        np.testing.assert_array_equal(noise(shifted), v)
    # and a period that is not a repeat of the axis: half a period is a different field
    half = x.copy()
    half[:, 0] += 1.0
    assert np.abs(noise(half) - v).max() > 0.1


def test_no_table_period_and_no_row_mean_artefact():
    # 1-D, 1024 cells: the table hash repeats after its 256-entry table, the integer hash does not
    line_t = LatticeNoise(1, rng=0, kernel="linear").grid((4096,), [(0, 1024)])
    line_i = _int(1, rng=0, kernel="linear").grid((4096,), [(0, 1024)])
    assert detect_period(line_t).period == 4 * 256
    per = detect_period(line_i, min_lag=16)   # lags past the kernel's reach (4 samples per cell)
    assert per.period is None and per.difference > 0.3
    # 2-D, one full 256-cell period (both tile it exactly): Phillips' nested permutation makes every
    # lattice row a permutation of one table, so the row means of lattice-aligned samples are all equal
    ext = [(0, 256), (0, 256)]
    img_t = LatticeNoise(2, rng=1, kernel="catmull-rom").grid((256, 256), ext)
    img_i = _int(2, rng=1, kernel="catmull-rom", period=256).grid((256, 256), ext)
    art_t, art_i = axis_artefacts(img_t), axis_artefacts(img_i)
    assert art_t.mean_spread_excess < 1e-6 and art_t.row_mean_spread < 1e-6
    # independent rows: the row means spread like an isotropic field's (excess about 1)
    assert 0.3 < art_i.mean_spread_excess < 3.0
    assert 0.3 < art_i.row_mean_spread * np.sqrt(256) < 3.0 and 0.3 < art_i.column_mean_spread * np.sqrt(256) < 3.0


def test_huge_coordinates_stay_smooth_and_in_range():
    noise = _int(2, rng=4, kernel="quintic")
    t = np.linspace(0, 20, 2000)
    for origin in (1e9, 5e9, 1e12, -1e12):   # past the 2**32-cell default period and 2**40
        x = np.stack([origin + t, -0.5 * origin + 0.7 * t], axis=-1)
        v = noise(x)
        assert np.abs(v).max() <= 1 and v.std() > 0.05
        assert np.abs(np.diff(v)).max() < 0.1   # smooth: 100 samples per cell


@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("dim", [1, 2, 3, 4])
def test_derivatives_match_central_differences(dim, basis):
    pts = RNG.uniform(-5, 5, (60, dim))
    eps = 1e-6
    for name in C1_KERNELS:
        noise = _int(dim, 2, rng=6, kernel=name, basis=basis, frequency=1.9)
        val, jac = noise.jacobian(pts, return_value=True)
        np.testing.assert_allclose(val, noise(pts), atol=1e-13)
        fd = np.stack([(noise(pts + eps * e) - noise(pts - eps * e)) / (2 * eps) for e in np.eye(dim)], axis=-1)
        np.testing.assert_allclose(jac, fd, atol=2e-6 * dim, err_msg=f"{name} {basis} d={dim}")
    # the grid derivative agrees with the scattered one
    shape = (9,) * dim
    ext = [(0.0, 2.0)] * dim
    noise = _int(dim, 2, rng=6, kernel="quintic", basis=basis, frequency=1.9)
    np.testing.assert_allclose(noise.jacobian_grid(shape, ext), noise.jacobian(noise.grid_points(shape, ext)),
                               atol=1e-12)


def test_fractal_sums_on_both_paths():
    noise = _int(2, rng=3, kernel="quintic", basis="gradient")
    g = Grid((48, 40), [(0, 3), (1, 4)])
    pts = noise.grid_points(g.shape, g.extent)
    np.testing.assert_allclose(fractal_sum(noise, g, 5), fractal_sum(noise, pts, 5), atol=1e-12)


def test_bad_hash_parameters_name_them():
    with pytest.raises(ValueError, match="hash must be one of"):
        LatticeNoise(2, hash="murmur")
    with pytest.raises(ValueError, match="alternation must be 'table' with hash='integer'"):
        LatticeNoise(2, hash="integer", alternation="lattice")
    with pytest.raises(ValueError, match="period must be at most 2\\*\\*32"):
        LatticeNoise(2, hash="integer", period=[8, 2 ** 33])
    for dtype in (np.float64, np.float32):
        for dim in (1, 2, 3, 4):
            bad = np.zeros((40, dim), dtype)
            bad[17, -1] = np.nan
            with pytest.raises(ValueError, match="finite"):
                _int(dim)(bad)
            bad[17, -1] = np.inf
            with pytest.raises(ValueError, match="finite"):
                _int(dim, kernel="quintic", basis="gradient")(bad)
    with pytest.raises(ValueError, match="overflows"):
        _int(3, frequency=1e300)(np.full((20, 3), 1e10))


@pytest.mark.parametrize("dim", [1, 2, 3])
def test_vectorised_point_kernel_gives_the_general_kernels_bits(dim):
    # points_path runs 1-3-D values through _jit._make_int_fast with a period, through the in-place kernels
    # without one: the same bits as the general kernel, for every stock kernel, both bases, turbulence, and
    # coordinates past the fast split. The general kernel runs as Python (its body; its helpers compiled): the
    # same bits as compiled (tests/test_lattice_engine.py), without compiling 24 value variants that no call
    # takes (about 55 s cold)
    from noiselab.lattice import _jit, points_path

    rng = np.random.default_rng(7)
    x = rng.uniform(-40, 40, (700, dim))
    x[::97] *= 1e15  # past _INT_SAFE at the higher octave: the exact reduction
    x = np.ascontiguousarray(x[np.union1d(np.arange(0, 700, 7), np.arange(0, 700, 97))])  # 106, 8 of them far out
    freqs = np.array([[1.0] * dim, [2.1] * dim, [7.3] * dim])
    amps = np.array([0.5, 0.3, 0.2])
    for name, basis in (("box", "value"), ("quadratic", "value"), ("cubic", "value"), ("linear", "gradient"),
                        ("quintic", "gradient"), ("catmull-rom", "gradient")):
        for period in (None, (5, 7, 3)[:dim]):
            n = LatticeNoise(dim, 2, rng=4, hash="integer", kernel=name, basis=basis, period=period)
            periodic = points_path._periodic(n)
            for absval in (False, True):
                args = points_path.kernel_args(n, freqs, amps, absval)
                want = np.empty((len(x), 2))
                got = np.empty((len(x), 2))
                _jit.points_kernel(True, dim, n.kernel.taps, False, periodic).py_func(x, want, *args)
                if periodic:
                    _jit.int_fast_kernel(dim, n.kernel.taps, basis == "gradient", True)(x, got, *args)
                else:
                    assert points_path._in_place(n, False)
                    assert points_path._run_block(n, x, got, freqs, amps, absval, 1) == 0
                np.testing.assert_array_equal(got.view(np.int64), want.view(np.int64))
