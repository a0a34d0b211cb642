"""The lattice points' opt-in float32 arithmetic (``evaluate(..., arithmetic="float32")``): its distance from the
float64 result and the slow reference, its bits across layouts, workers and chunkings, its refusals, and its kernels
as plain Python."""
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import naive
from noiselab import LatticeNoise

RNG = np.random.default_rng(32)
HERE = Path(__file__).resolve().parent.parent
# the largest |float32 arithmetic - float64 arithmetic| over 1e6 random points, 1-3-D, quintic and Catmull-Rom value
# and gradient noise, near 0 and at 1e12, amplitude 1 (benchmarks/bench_limits.md:
# `python benchmarks/bench_limits.py --f32-error`); the tests allow 4 times it
MEASURED = 4.46e-6
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


_CASE = """
import sys
import numpy as np
import noiselab as nl
x = np.random.default_rng(1).uniform(-9, 9, (300, 3))
x[::5] += 1e12
out = []
for d in (1, 2, 3):
    for k, b in (("quintic", "value"), ("quintic", "gradient"), ("catmull-rom", "value"), ("catmull-rom", "gradient")):
        n = nl.LatticeNoise(d, 2, rng=3, hash="integer", kernel=k, basis=b)
        out += [n.evaluate(x[:, :d], octaves=2, arithmetic="float32"),
                n.evaluate(np.ascontiguousarray(x[:, :d].T), axis=0, octaves=2, absval=True, arithmetic="float32")]
np.savez(sys.argv[1], *out)
"""


def test_float32_kernels_run_as_plain_python_with_the_same_bits(tmp_path):
    # NUMBA_DISABLE_JIT=1 runs the float32 kernels' Python source (numpy float32 scalars): the same bits, in another
    # process each time
    results = []
    for flag in ("0", "1"):
        env = dict(os.environ, NUMBA_DISABLE_JIT=flag, PYTHONPATH=str(HERE))
        subprocess.run([sys.executable, "-c", _CASE, str(tmp_path / f"jit{flag}.npz")], env=env, check=True,
                       cwd=tmp_path, timeout=900)
        data = np.load(tmp_path / f"jit{flag}.npz")
        results.append([data[k] for k in sorted(data.files, key=lambda s: int(s.split("_")[1]))])
    assert len(results[0]) == len(results[1]) == 24
    for compiled, plain in zip(*results):
        assert compiled.dtype == plain.dtype == np.float32
        np.testing.assert_array_equal(compiled, plain)
        np.testing.assert_array_equal(np.signbit(compiled), np.signbit(plain))
        assert np.ptp(compiled) > 0.1
