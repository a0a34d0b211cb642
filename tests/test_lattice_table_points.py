"""The table hash's 3-D block kernel (``_jit.table_block_kernel``): the per-point kernel's bits on hard inputs."""
import numpy as np
import pytest

from noiselab import LatticeNoise
from noiselab.lattice import _jit as jit
from noiselab.lattice import points_path

RNG = np.random.default_rng(41)


def _hard_points(n):
    x = RNG.uniform(-300, 300, (n, 3))
    x[::7] += 1e12      # beyond the table many times over
    x[::11] *= 1e18     # past 2**63: no int64 holds the lattice index
    x[::13] *= -1e250
    x[::17] = np.round(x[::17])    # exact lattice points (t = 0)
    x[::19] = -np.round(x[::19])
    x32 = RNG.uniform(-300, 300, (n, 3)).astype(np.float32)
    x32[::23] *= np.float32(1e30)
    x32[::29] = np.round(x32[::29])
    return x, x32


@pytest.fixture
def spy(monkeypatch):
    """Counts the calls that took the block kernel."""
    calls = []
    run = points_path._run_table
    monkeypatch.setattr(points_path, "_run_table", lambda *a, **k: calls.append(1) or run(*a, **k))
    return calls


@pytest.mark.parametrize("kw", [{"kernel": "quintic"}, {"kernel": "quintic", "basis": "gradient"},
                                {"kernel": "catmull-rom", "dim_out": 2}, {},
                                {"alternation": "lattice", "kernel": "linear"},
                                {"table_size": 64, "basis": "gradient", "kernel": "quadratic"}])
def test_the_block_kernel_gives_the_per_point_kernels_bits(kw, monkeypatch, spy):
    noise = LatticeNoise(3, rng=5, **kw)
    x, x32 = _hard_points(3000)
    monkeypatch.setattr(points_path, "PAIRS_MIN", 0)
    results = []
    for block in (True, False):
        monkeypatch.setattr(points_path, "TABLE_SPLIT", block)
        results.append([noise.evaluate(x, octaves=3), noise.evaluate(x, octaves=2, absval=True),
                        noise(x32), noise.evaluate(x32, octaves=2, dtype=np.float64),
                        noise.evaluate(x, dtype=np.float32)])
    assert len(spy) == 5   # the block kernel ran for every call with TABLE_SPLIT, and only then
    for a, b in zip(*results):
        assert a.dtype == b.dtype
        np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(np.signbit(a), np.signbit(b))
    assert np.ptp(results[0][0]) > 0.5   # not vacuous: the noise varies over these points
    # columns in place, strided rows (copied) and any number of threads: the same bits
    monkeypatch.setattr(points_path, "TABLE_SPLIT", True)
    np.testing.assert_array_equal(noise.evaluate(np.ascontiguousarray(x.T), octaves=3, axis=0, workers=2),
                                  results[0][0])
    np.testing.assert_array_equal(noise(np.ascontiguousarray(x32.T), axis=0, workers=3), results[0][2])
    np.testing.assert_array_equal(noise.evaluate(x, octaves=2, absval=True, workers=3), results[0][1])
    np.testing.assert_array_equal(noise(x[::2]), noise(np.ascontiguousarray(x[::2])))


def test_the_block_kernel_follows_the_live_tables(monkeypatch, spy):
    # the folded tables are reused while the tables are unchanged, and rebuilt when they change
    monkeypatch.setattr(points_path, "PAIRS_MIN", 0)
    x, _ = _hard_points(500)
    a, b = LatticeNoise(3, rng=1), LatticeNoise(3, rng=2)
    first = a(x)
    assert not np.array_equal(b(x), first)
    np.testing.assert_array_equal(a(x), first)
    a.values[:] = -a.values
    np.testing.assert_array_equal(a(x), -first)
    g = LatticeNoise(3, rng=1, basis="gradient")
    before = g(x)
    g.gradients[:] = -g.gradients
    np.testing.assert_array_equal(g(x), -before)
    assert len(spy) == 6


@pytest.mark.parametrize("gradient", [False, True])
def test_the_block_kernel_runs_as_plain_python_with_the_same_bits(gradient):
    # the kernel's own body as Python (its helpers compiled), rows and columns: the per-point kernel's values
    noise = LatticeNoise(3, 2, rng=4, kernel="quintic", basis="gradient" if gradient else "value")
    x, _ = _hard_points(300)
    kernel = jit.table_block_kernel(2, gradient)
    freqs, amps = np.array([[1.0, 1.0, 1.0], [2.0, 2.5, 2.0]]), np.array([0.7, 0.3]) * noise.scale
    k = noise.kernel
    tables = jit.pair_tables(noise.perms, noise.values, noise.gradients if gradient else None)
    outs = []
    for fn, src, cols in ((kernel, x, False), (kernel.py_func, x, False), (kernel.py_func, x.T.copy(), True)):
        out = np.empty((300, 2))
        fn(jit.points_pair(src), cols, 0, 300, jit.out_pair(out), freqs, amps, noise.phase, k.shift, k.left, k.coef,
           *tables, False)
        outs.append(out)
    ref = np.empty((300, 2))   # the per-point kernel on the same arguments
    jit.points_kernel(False, 3, 2, False, False)(x, ref, freqs, amps, noise.phase, k.shift, k.left, k.taps, k.coef,
                                                 k.dcoef, noise.period, noise._pmask, noise.perms, noise.values,
                                                 noise.gradients, int(gradient), False,
                                                 jit.point_buffers(3, 2))
    for out in outs:
        np.testing.assert_array_equal(out, ref)
    assert np.ptp(ref) > 0.3
