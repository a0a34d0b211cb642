"""2-D grids (both hashes) by the separable passes: equal to the points path, in range, bit-identical for any
window, band or chunk of the grid."""
import numpy as np
import pytest

from noiselab import LatticeNoise, fractal_sum, turbulence
from noiselab.lattice import KERNELS, Grid

# (shape, extent): dense, reversed axis with a negative start, wide and short, sparse (the taps of
# neighbouring samples far apart), and a grid sparser than the last octaves' lattices
GRIDS = [((19, 37), [(-1.3, 4.1), (2.0, 9.5)]), ((24, 16), [(5, 1), (0, 3)]), ((5, 130), [(0, 2), (0, 40)]),
         ((4, 6), [(0, 1000), (0, 700)]), ((9, 9), [(0, 30), (0, 30)])]
NOISES = [{}, {"period": (6, 10)}, {"dim_out": 2, "alternation": "lattice", "phase": (0.3, -2.7)},
          {"frequency": (0.7, 1.9), "table_size": 20}]
# the integer hash (no alternation, no table): a period past 2**16 that is no power of two, and the default 2**32
INT_NOISES = [{}, {"period": (6, 10)}, {"dim_out": 2, "phase": (0.3, -2.7)}, {"frequency": (0.7, 1.9)},
              {"period": (2 ** 26, 70001)}]


@pytest.mark.parametrize("name", list(KERNELS))
@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("hash", ["table", "integer"])
def test_grids_equal_the_points_path_and_stay_in_range(name, basis, hash):
    for kw in (NOISES if hash == "table" else INT_NOISES):
        noise = LatticeNoise(2, rng=3, kernel=name, basis=basis, hash=hash, **kw)
        for shape, ext in GRIDS:
            grid = noise.grid(shape, ext)
            pts = noise.grid_points(shape, ext)
            np.testing.assert_allclose(grid, noise(pts), rtol=0, atol=1e-12)
            assert np.abs(grid).max() <= noise.amplitude
            np.testing.assert_allclose(noise.evaluate_grid(shape, ext, octaves=4), noise.evaluate(pts, octaves=4),
                                       rtol=0, atol=1e-12)
            np.testing.assert_allclose(noise.evaluate_grid(shape, ext, octaves=3, absval=True),
                                       noise.evaluate(pts, octaves=3, absval=True), rtol=0, atol=1e-12)
            if noise.kernel.continuity >= 1:
                value, jac = noise.evaluate_grid_jacobian(shape, ext, octaves=3)
                pv, pj = noise.evaluate_jacobian(pts, octaves=3)
                np.testing.assert_allclose(value, pv, rtol=0, atol=1e-12)
                np.testing.assert_allclose(jac, pj, rtol=1e-12, atol=1e-12 * max(1.0, float(np.abs(pj).max())))


@pytest.mark.parametrize("name,basis,hash", [("cubic", "gradient", "table"), ("quintic", "value", "table"),
                                             ("quadratic", "gradient", "table"), ("quintic", "gradient", "integer"),
                                             ("catmull-rom", "value", "integer")])
def test_grids_are_bit_identical_across_windows_and_bands(name, basis, hash):
    noise = LatticeNoise(2, rng=4, kernel=name, basis=basis, hash=hash)
    shape, ext = (6, 1500), [(0.3, 2.0), (-7.0, 150.0)]
    g = Grid(shape, ext)
    whole = [fractal_sum(noise, g, 6), turbulence(noise, g, 6), noise.grid(shape, ext, dtype="float32")]
    win = [(1, 5), (333, 1207)]
    part = noise.grid(shape, ext, dtype="float32", window=win)
    np.testing.assert_array_equal(part, whole[2][1:5, 333:1207])
    np.testing.assert_array_equal(np.signbit(part), np.signbit(whole[2][1:5, 333:1207]))
    again = [fractal_sum(noise, g, 6, workers=3), turbulence(noise, g, 6, workers=2),
             noise.grid(shape, ext, dtype="float32", workers=4)]
    for x, y in zip(whole, again):
        np.testing.assert_array_equal(x, y)
