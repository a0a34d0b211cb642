"""The fused 2-D grid kernel (both hashes): the same bits as the general separable path, any tiling or window."""
import numpy as np
import pytest

from noiselab import LatticeNoise, fractal_sum, turbulence
from noiselab.fractal import fractal_gradient
from noiselab.lattice import KERNELS, Grid, _jit, grid_path

# (shape, extent): dense, reversed axis with a negative start, wide and short, sparse (the taps of
# neighbouring samples far apart: the fallback packing), and a grid sparser than the last octaves' lattices
GRIDS = [((19, 37), [(-1.3, 4.1), (2.0, 9.5)]), ((24, 16), [(5, 1), (0, 3)]), ((5, 130), [(0, 2), (0, 40)]),
         ((4, 6), [(0, 1000), (0, 700)]), ((9, 9), [(0, 30), (0, 30)])]
NOISES = [{}, {"period": (6, 10)}, {"dim_out": 2, "alternation": "lattice", "phase": (0.3, -2.7)},
          {"frequency": (0.7, 1.9), "table_size": 20}]
# the integer hash (no alternation, no table): a period past 2**16 that is no power of two, whose octave
# periods (a tileable sum) grow to 2**29 cells, and the default 2**32
INT_NOISES = [{}, {"period": (6, 10)}, {"dim_out": 2, "phase": (0.3, -2.7)}, {"frequency": (0.7, 1.9)},
              {"period": (2 ** 26, 70001)}]


def _everything(noise):
    """Every grid evaluation that reaches the separable pass, on every grid."""
    out = []
    for shape, ext in GRIDS:
        g = Grid(shape, ext)
        for dt in ("float64", "float32"):
            out.append(noise.grid(shape, ext, dtype=dt))
            out.append(fractal_sum(noise, g, 4, dtype=dt))
        out.append(noise.grid(shape, ext, window=[(1, shape[0] - 1), (2, shape[1])]))
        out.append(turbulence(noise, g, 3))
        if noise.kernel.continuity >= 1:
            out.append(noise.jacobian_grid(shape, ext))
            if noise.dim_out == 1:
                out.append(fractal_gradient(noise, g, 3))
    return out


@pytest.mark.parametrize("name", list(KERNELS))
@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("hash", ["table", "integer"])
def test_fused_kernel_equals_the_general_separable_path(name, basis, hash, monkeypatch):
    noises = [LatticeNoise(2, seed=3, kernel=name, basis=basis, hash=hash, **kw)
              for kw in (NOISES if hash == "table" else INT_NOISES)]
    # the fused kernel ran, with this hash's variant (the integer hash's lattice words are uint32)
    kinds, kernel = [], _jit.grid2d
    monkeypatch.setattr(_jit, "grid2d", lambda *args: kinds.append(args[0].dtype) or kernel(*args))
    fused = [_everything(noise) for noise in noises]
    assert kinds and set(kinds) == {np.dtype(np.uint32 if hash == "integer" else np.int64)}
    monkeypatch.setattr(grid_path, "FUSED_2D", False)
    general = [_everything(noise) for noise in noises]
    for noise, a, b in zip(noises, fused, general):
        for x, y in zip(a, b):
            assert x.dtype == y.dtype and x.shape == y.shape
            np.testing.assert_array_equal(x, y)
            np.testing.assert_array_equal(np.signbit(x), np.signbit(y))  # the bits: a zero's sign too
        for x in (a[0], a[2]):  # the range bound holds on the fused path too (one octave, float64 and float32)
            assert np.abs(x).max() <= noise.amplitude


@pytest.mark.parametrize("name,basis,hash", [("cubic", "gradient", "table"), ("quintic", "value", "table"),
                                             ("quadratic", "gradient", "table"), ("quintic", "gradient", "integer"),
                                             ("catmull-rom", "value", "integer")])
def test_fused_kernel_is_bit_identical_across_tiles_and_windows(name, basis, hash, monkeypatch):
    noise = LatticeNoise(2, seed=4, kernel=name, basis=basis, hash=hash)
    shape, ext = (6, 1500), [(0.3, 2.0), (-7.0, 150.0)]  # wider than one automatic tile at 6 octaves
    g = Grid(shape, ext)
    whole = [fractal_sum(noise, g, 6), turbulence(noise, g, 6), noise.grid(shape, ext, dtype="float32")]
    win = [(1, 5), (333, 1207)]
    part = noise.grid(shape, ext, dtype="float32", window=win)
    np.testing.assert_array_equal(part, whole[2][1:5, 333:1207])
    for tile in (8, 24, 1504):
        monkeypatch.setattr(grid_path, "TILE_2D", tile)
        again = [fractal_sum(noise, g, 6), turbulence(noise, g, 6), noise.grid(shape, ext, dtype="float32")]
        for x, y in zip(whole, again):
            np.testing.assert_array_equal(x, y)
        np.testing.assert_array_equal(noise.grid(shape, ext, dtype="float32", window=win), part)
