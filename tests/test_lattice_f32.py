"""The lattice points' opt-in float32 arithmetic (``evaluate(..., arithmetic="float32")``): its distance from the
float64 result and the slow reference, its bits across layouts, workers and chunkings, its refusals (its kernels as plain
Python: tests/test_lattice_engine.py)."""
import dataclasses

import numpy as np
import pytest

import naive
from noiselab import LatticeNoise
from noiselab.lattice.kernels import get_kernel

RNG = np.random.default_rng(32)
# the largest |float32 arithmetic - float64 arithmetic| over 1e6 random points, 1-3-D, quintic and Catmull-Rom value
# and gradient noise, near 0 and at 1e12, amplitude 1 (benchmarks/bench_limits.md:
# `python benchmarks/bench_limits.py --f32-error`); the tests allow 4 times it
MEASURED = 2.78e-6
CASES = [("quintic", "value"), ("quintic", "gradient"), ("catmull-rom", "value"), ("catmull-rom", "gradient")]


@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("kernel, basis", CASES)
def test_float32_arithmetic_stays_near_the_float64_result_and_the_reference(dim, kernel, basis):
    noise = LatticeNoise(dim, rng=5, kernel=kernel, basis=basis, hash="integer")
    ref = naive.NaiveLattice(dim, rng=5, kernel=kernel, basis=basis, hash="integer")
    x = RNG.uniform(-1000.0, 1000.0, (50_000, dim))
    for offset in (0.0, 1e12):   # the lattice index stays exact in float64: smooth and in range far out
        pts = x + offset
        fast, exact = noise.evaluate(pts, arithmetic="float32"), noise(pts)
        assert fast.dtype == np.float32 and fast.shape == exact.shape == (50_000,)
        assert np.abs(fast - exact).max() <= 4 * MEASURED
        assert np.abs(fast).max() <= noise.amplitude
        assert np.ptp(fast) > 0.5   # not vacuous: the noise varies over these points
    # the float64 default is today's arithmetic: the slow reference to 1e-12, and the float32 one within the bound
    few = x[:300]
    want = ref(few, noise.bound)[:, 0]
    np.testing.assert_allclose(noise.evaluate(few, arithmetic="float64"), want, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(noise.evaluate(few, arithmetic="float64"), noise(few))
    assert np.abs(noise.evaluate(few, arithmetic="float32") - want).max() <= 4 * MEASURED


def test_octaves_turbulence_and_components_in_float32_arithmetic():
    noise = LatticeNoise(3, 2, rng=6, kernel="quintic", hash="integer", amplitude=5.0)
    x = RNG.uniform(-50.0, 50.0, (20_000, 3))
    for kw, gains in (({"octaves": 4}, 1 + 0.5 + 0.25 + 0.125), ({"octaves": 3, "gain": 0.7, "absval": True},
                                                                 1 + 0.7 + 0.49)):
        fast, exact = noise.evaluate(x, arithmetic="float32", **kw), noise.evaluate(x, **kw)
        assert fast.dtype == np.float32 and fast.shape == (20_000, 2)
        assert np.abs(fast - exact).max() <= 4 * MEASURED * 5.0 * gains
        assert np.abs(fast).max() <= 5.0 * gains
        assert np.ptp(fast[:, 0]) > 1.0 and not np.array_equal(fast[:, 0], fast[:, 1])
    assert fast.min() >= 0   # turbulence: a sum of |noise|


@pytest.mark.parametrize("kernel, basis", CASES[:3])
def test_float32_arithmetic_bits_do_not_depend_on_layout_workers_or_chunking(kernel, basis):
    noise = LatticeNoise(3, rng=7, kernel=kernel, basis=basis, hash="integer")
    x = RNG.uniform(-300.0, 300.0, (30_000, 3))
    x[::7] += 1e12
    cols = np.ascontiguousarray(x.T)

    def f32(pts, **kw):
        return noise.evaluate(pts, octaves=2, arithmetic="float32", **kw)

    want = f32(x)
    same = [f32(cols, axis=0), f32(x, workers=3), f32(cols, axis=0, workers=2), f32(x, dtype=np.float32),
            np.concatenate([f32(x[:12345]), f32(x[12345:20001]), f32(x[20001:])]),
            f32(x.reshape(100, 300, 3)).reshape(-1), f32(cols.reshape(3, 300, 100), axis=0).reshape(-1)]
    for got in same:
        assert got.dtype == np.float32
        np.testing.assert_array_equal(got, want)
        np.testing.assert_array_equal(np.signbit(got), np.signbit(want))
    np.testing.assert_array_equal(f32(x[::2]), want[::2])   # strided rows: copied, the same bits
    x32 = x.astype(np.float32)   # float32 points are widened exactly as they are read
    np.testing.assert_array_equal(f32(x32), f32(x32.astype(np.float64)))
    np.testing.assert_array_equal(f32(np.ascontiguousarray(x32.T), axis=0), f32(x32))


def test_float32_arithmetic_refuses_what_it_does_not_do():
    x3, x4 = RNG.uniform(0.0, 9.0, (10, 3)), RNG.uniform(0.0, 9.0, (10, 4))
    cases = [(LatticeNoise(3, rng=1), x3, {}, "hash='table'"),
             (LatticeNoise(3, rng=1, hash="integer", period=(4, 4, 4)), x3, {}, "a period"),
             (LatticeNoise(4, rng=1, hash="integer"), x4, {}, "dim_in=4"),
             (LatticeNoise(3, rng=1, hash="integer"), x3, {"dtype": np.float64}, "dtype=")]
    for noise, pts, kw, what in cases:
        with pytest.raises(ValueError, match="arithmetic='float32' supports integer-hash values in 1-3-D") as info:
            noise.evaluate(pts, arithmetic="float32", **kw)
        assert what in str(info.value) and "arithmetic='float64'" in str(info.value)
        noise.evaluate(pts, arithmetic="float64", **kw)   # the float64 arithmetic does all of them
    noise = LatticeNoise(3, rng=1, hash="integer")
    for bad in ("float16", "Float32", 32, None, np.float32):
        with pytest.raises(ValueError, match="arithmetic must be one of"):
            noise.evaluate(x3, arithmetic=bad)
    with pytest.raises(ValueError, match="dtype must be float32 or float64"):
        noise.evaluate(x3, arithmetic="float32", dtype=np.int16)
    # the float32 kernels check the points as they go (a NaN fraction), with the float64 arithmetic's errors
    for kernel in ("quintic", "catmull-rom"):
        noise = LatticeNoise(3, rng=1, hash="integer", kernel=kernel)
        for bad, octaves, match in ((np.nan, 1, "finite"), (-np.inf, 1, "finite"), (1e308, 3, "overflows")):
            pts = RNG.uniform(0.0, 9.0, (9000, 3))
            pts[6789, 1] = bad
            for arithmetic in ("float32", "float64"):
                with pytest.raises(ValueError, match=match):
                    noise.evaluate(pts, octaves=octaves, arithmetic=arithmetic, workers=2)
        pts[6789, 1] = 1e307   # large but finite at every octave: the index is reduced exactly, no error
        assert np.isfinite(noise.evaluate(pts, octaves=3, arithmetic="float32")).all()


# ----------------------------------------------------------------- the float32 index
def _f32(noise, pts, **kw):
    return noise.evaluate(pts, arithmetic="float32", **kw)


@pytest.mark.parametrize("dim", [1, 2, 3])
@pytest.mark.parametrize("kernel, basis", CASES + [("linear", "value")])
def test_the_float32_index_gives_the_float64_index_s_bits(dim, kernel, basis):
    # float32 points take the index in float32 block by block where every |x f| stays below 2**31 (and x f is exact),
    # float64 points the index in float64: the same bits, points straddling the thresholds and far out included
    x = RNG.uniform(-300.0, 300.0, (3000, dim)).astype(np.float32)
    edge = np.float32([2.0 ** 24, 2.0 ** 29, 2.0 ** 31, 2.0 ** 31 - 128, 1e12, 3e38, 1e-40, -1e-40, -0.0, 0.5])
    x[1000:1000 + edge.size, 0] = edge   # one block with them (with octaves=3 the largest frequency is 4)
    x[1000 + edge.size:1000 + 2 * edge.size, -1] = -edge
    x[2600:2610, 0] = np.float32(2.0 ** 29 - 64)   # in reach at frequency 4 (x 4 < 2**31): the float32 pass
    for freq, kw in ((1.0, {}), (1.0, {"octaves": 3}), (1.0, {"octaves": 2, "absval": True}),
                     (0.25, {"octaves": 2}), (2.0 ** -60, {}), (1.0, {"octaves": 2, "lacunarity": 3.0})):
        noise = LatticeNoise(dim, 2, rng=9, kernel=kernel, basis=basis, hash="integer", frequency=freq)
        want = _f32(noise, x.astype(np.float64), **kw)
        got = _f32(noise, x, **kw)
        np.testing.assert_array_equal(got, want)
        np.testing.assert_array_equal(np.signbit(got), np.signbit(want))
        cols = np.ascontiguousarray(x.T)
        for other in (_f32(noise, cols, axis=0, **kw), _f32(noise, x, workers=2, **kw),
                      np.concatenate([_f32(noise, x[:777], **kw), _f32(noise, x[777:], **kw)], axis=0)):
            np.testing.assert_array_equal(other, want)
        assert np.isfinite(want).all() and (freq < 0.1 or np.ptp(want) > 0.3)   # not vacuous: the noise varies


def test_the_reach_check_picks_the_float32_index_only_where_it_is_exact():
    from noiselab.lattice import _jit
    reach = np.float32([2.0 ** -126, 2.0 ** 29]).view(np.uint32)   # lo, hi for frequencies 1 .. 4
    X = RNG.uniform(-1e3, 1e3, (3, 256)).astype(np.float32)
    assert _jit._reach32(X, 256, reach, 3)
    for bad in (2.0 ** 29, -(2.0 ** 29), np.inf, -np.inf, np.nan, 1e-40):   # x f >= 2**31; not finite; subnormal
        Y = X.copy()
        Y[2, 100] = bad
        assert not _jit._reach32(Y, 256, reach, 3)
        assert _jit._reach32(Y, 100, reach, 3)   # only the block's first m points count
    Y = X.copy()
    Y[1, 7] = -0.0
    Y[0, 8] = np.float32(2.0 ** 29 - 32)
    assert _jit._reach32(Y, 256, reach, 3)
    assert not _jit._reach32(X, 256, np.zeros(2, np.uint32), 3)   # hi = 0: a call the float32 index does not take


def test_float32_points_refused_as_float64_ones():
    noise = LatticeNoise(3, rng=1, hash="integer")
    for bad in (np.nan, np.inf):
        pts = RNG.uniform(0.0, 9.0, (9000, 3)).astype(np.float32)
        pts[6789, 2] = bad
        with pytest.raises(ValueError, match="finite"):
            _f32(noise, pts, workers=2)
        with pytest.raises(ValueError, match="finite"):
            _f32(noise, np.ascontiguousarray(pts.T), axis=0)


def test_a_two_tap_kernel_that_is_no_partition_of_unity_keeps_its_own_weights():
    # the lerps need w0 = 1 - w1; another 2-tap kernel takes the block kernel, which sums every tap's own weight
    quintic = get_kernel("quintic")
    soft = dataclasses.replace(quintic, name="soft", coef=0.75 * quintic.coef, abs_sum_max=0.75)
    x = RNG.uniform(-50.0, 50.0, (5000, 3)).astype(np.float32)
    for basis in ("value", "gradient"):
        noise = LatticeNoise(3, rng=2, kernel=soft, basis=basis, hash="integer")
        fast, exact = _f32(noise, x), noise(x)
        assert np.abs(fast - exact).max() <= 4 * MEASURED and np.ptp(exact) > 0.3
