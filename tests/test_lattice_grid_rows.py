"""The fused grid kernel (2-D and 3-D grids row by row, every octave in one pass) against the separable passes
it stands in for: the same bits, sign bits included, for every tap count, hash, basis, dtype and octave batching."""
import numpy as np
import pytest

import naive

from noiselab import LatticeNoise, fractal_sum, turbulence
from noiselab.lattice import Grid, _jit, grid_path

# (dim, kernel, basis, hash): each tap count of each dimension (2 and 4 have their own kernels, 1 and 3 the
# shared one), both bases and both hashes
CASES = [(2, "quintic", "value", "table"), (2, "cubic", "gradient", "integer"), (2, "quadratic", "value", "integer"),
         (2, "box", "gradient", "table"), (3, "quintic", "gradient", "table"), (3, "quintic", "value", "integer"),
         (3, "catmull-rom", "value", "table"), (3, "quadratic", "gradient", "integer")]
SHAPES = {2: ((23, 17), [(-1.3, 2.9), (3.0, 0.5)]), 3: ((11, 9, 13), [(-1.3, 2.9), (3.0, 0.5), (0.0, 1.7)])}


def _separable(monkeypatch, call):
    """``call()`` by the separable passes (the fused kernel switched off)."""
    with monkeypatch.context() as m:
        m.setattr(grid_path, "FUSED_DIMS", ())
        return call()


def _fused(monkeypatch, call):
    """``call()``, checking that the fused kernel ran."""
    runs = []
    real = grid_path.grid_rows
    with monkeypatch.context() as m:
        m.setattr(grid_path, "grid_rows", lambda *a: runs.append(1) or real(*a))
        out = call()
    assert runs
    return out


def _same(a, b):
    assert a.dtype == b.dtype and a.shape == b.shape
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(np.signbit(a), np.signbit(b))


@pytest.mark.parametrize("dim,kernel,basis,hash_", CASES)
def test_the_fused_grid_kernel_gives_the_separable_passes_bits(dim, kernel, basis, hash_, monkeypatch):
    shape, ext = SHAPES[dim]
    noise = LatticeNoise(dim, 2 if dim == 2 else 1, rng=4, kernel=kernel, basis=basis, hash=hash_)
    calls = [lambda dt=dt: fractal_sum(noise, Grid(shape, ext), 5, dtype=dt) for dt in (np.float64, np.float32)]
    calls += [lambda: turbulence(noise, Grid(shape, ext), 4),
              lambda: noise.evaluate_grid(shape, ext, octaves=3, window=[(2, 9)] + [(1, 7)] * (dim - 1))]
    for call in calls:
        _same(_fused(monkeypatch, call), _separable(monkeypatch, call))


@pytest.mark.parametrize("hash_", ["table", "integer"])
def test_the_fused_kernel_sums_octave_batches_as_the_separable_passes(hash_, monkeypatch):
    # the separable passes sum a batch of octaves in float64, then add it into the output (in its dtype): the
    # fused kernel keeps the batches, so a sum split over several of them keeps its bits too
    noise = LatticeNoise(3, rng=6, kernel="quintic", basis="gradient", hash=hash_, period=(4, 8, 16))
    grid = Grid((10, 12, 8), [(0, 4), (0, 4), (0, 4)])
    monkeypatch.setattr(grid_path, "_octave_batches", lambda noise, full, octaves, nterm: [[o] for o in octaves])
    for dt in (np.float64, np.float32):
        call = lambda dt=dt: fractal_sum(noise, grid, 4, dtype=dt)  # noqa: E731
        _same(_fused(monkeypatch, call), _separable(monkeypatch, call))
    call = lambda: turbulence(noise, grid, 3)  # noqa: E731
    _same(_fused(monkeypatch, call), _separable(monkeypatch, call))


def test_the_fused_kernel_gives_the_separable_gradient_grids(monkeypatch):
    noise = LatticeNoise(3, rng=7, kernel="cubic", basis="gradient")
    shape, ext = SHAPES[3]
    call = lambda: noise.gradient_grid(shape, ext, return_value=True)  # noqa: E731
    for new, old in zip(_fused(monkeypatch, call), _separable(monkeypatch, call)):
        _same(new, old)


@pytest.mark.parametrize("coords", [np.linspace(-3, 5, 40), np.linspace(9, -2, 33), np.arange(6) * 97.3,
                                    np.linspace(0, 1e6, 50)])
@pytest.mark.parametrize("kernel", ["box", "quadratic", "cubic"])
def test_a_samples_taps_are_consecutive_rows_as_the_ring_needs(coords, kernel):
    # the fused kernel keeps lattice row r in slot r mod taps: one sample's taps must be consecutive rows, on
    # the dense path (marked offsets) and on the spread one (np.unique) alike
    noise = LatticeNoise(1, rng=0, kernel=kernel)
    lattice, pos, _, _ = grid_path.axis_taps(noise, coords, 1.0, 0, False)
    np.testing.assert_array_equal(pos, pos[:, :1] + np.arange(noise.kernel.taps))
    assert pos.min() == 0 and pos.max() == len(lattice) - 1


def _reference_taps(noise, coords, freq, grad, period, deriv):
    """One axis's taps by ``tests/naive.py`` (the derivative weights by the engine's ``_jit.axis_dweights``)."""
    k = noise.kernel
    lattice, pos, w, rw = naive.grid_axis_taps(coords, freq, noise.phase[0], k.shift, k.left, k.coef[:k.taps],
                                               period, grad)
    if deriv:
        w, rw = _jit.axis_dweights(coords, freq, noise.phase[0], k.shift, k.left, k.taps, k.coef, k.dcoef, grad)
    return lattice, pos, w, rw


@pytest.mark.parametrize("kernel", ["box", "linear", "quadratic", "cubic", "quintic", "catmull-rom"])
@pytest.mark.parametrize("basis", ["value", "gradient"])
def test_the_axes_taps_in_numpy_equal_the_reference(kernel, basis):
    # every octave of an axis in one set of numpy operations: the kernels' weights, floors, distinct taps and
    # their places, bit for bit, on dense and spread axes, near 2**52 cells and for any period
    noise = LatticeNoise(1, rng=1, kernel=kernel, basis=basis, phase=0.3)
    grad = basis == "gradient"
    freqs = np.array([1.0, 0.37, 3.3, 2.0 ** 10])
    for coords in (np.linspace(-3, 5, 40), np.linspace(9, -2, 33), np.arange(6) * 97.3, np.linspace(0, 16, 512),
                   np.linspace(4.1e15, 4.1e15 + 60, 7), np.linspace(-4.3e15, -4.3e15 + 100, 9)):
        for periods in (np.array([256, 20, 7, 3]), np.full(4, 1 << 32)):
            for deriv in (False, True):
                got = grid_path.octave_axis_taps(noise, coords, freqs, 0, grad, periods, deriv=deriv)
                for o in range(4):
                    want = _reference_taps(noise, coords, freqs[o], grad, int(periods[o]), deriv)
                    for x, y in zip(want[:3] + (want[3] if grad else want[2],), got[o]):
                        assert x.dtype == y.dtype
                        np.testing.assert_array_equal(x, y)


@pytest.mark.parametrize("basis", ["value", "gradient"])
def test_the_folded_tables_read_what_the_two_hash_levels_read(basis):
    # the fused kernel reads the last hash level and the look-up in one: VL[(p - h) & 1, h + j] is the value of
    # parity (p + j) & 1 at P[(h + j) mod n], GP[h + j] the gradient there, for every prefix h and index j < n
    noise = LatticeNoise(3, rng=9, basis=basis, table_size=64)
    perm, n = noise.perms[0], noise.table_size
    vl, gp = grid_path.folded_tables(perm, noise.values, noise.gradients if basis == "gradient" else None)
    h, j, p = np.meshgrid(np.arange(n), np.arange(n), np.arange(2), indexing="ij")
    x = h + j
    np.testing.assert_array_equal(vl[(p - h) & 1, x], noise.values[(p + j) & 1, perm[x % n]])
    if basis == "gradient":
        np.testing.assert_array_equal(gp[x], noise.gradients[perm[x % n]])
    else:
        assert gp.shape == (1, 1)


@pytest.mark.parametrize("hash_", ["table", "integer"])
def test_one_compiled_specialisation_serves_every_grid_call(hash_):
    # one octave or several, float64 or float32, a window, two threads, turbulence: the fused kernel is compiled
    # once per dimension, tap class, hash and basis (another argument type, e.g. a stacked array in Fortran order,
    # compiles it again: 1.5-2 s more on a first call)
    for dim in (2, 3):
        noise = LatticeNoise(dim, rng=1, kernel="quintic", hash=hash_)
        g = Grid((33, 20, 9)[:dim], [(0, 3), (0.5, 2), (0, 1)][:dim])
        noise.grid(g.shape, g.extent)
        noise.grid(g.shape, g.extent, dtype=np.float32, window=[(3, 20)] + [(0, n) for n in g.shape[1:]])
        fractal_sum(noise, g, 4, dtype=np.float32)
        turbulence(noise, g, 3, workers=2)
        assert len(_jit.grid_rows_kernel(dim, 2, hash_ == "integer", False).signatures) == 1
