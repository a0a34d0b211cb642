"""Points that overflow the lattice: refused by the in-place kernels' own count, with the checks' errors."""
import numpy as np
import pytest

from noiselab import LatticeNoise
from noiselab.lattice import points_path

N = points_path.PAIRS_MIN + 5  # enough points for the table hash's block kernel


@pytest.mark.parametrize("hash_,kernel,basis", [("table", "quintic", "value"), ("table", "catmull-rom", "gradient"),
                                                ("integer", "quintic", "gradient"), ("integer", "catmull-rom", "value")])
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_in_place_kernels_refuse_non_finite_and_overflowing_points_with_the_checks_errors(hash_, kernel, basis,
                                                                                           dtype):
    noise = LatticeNoise(3, rng=1, kernel=kernel, basis=basis, hash=hash_)
    pts = np.random.default_rng(0).uniform(-50, 50, (N, 3)).astype(dtype)
    assert points_path._in_place(noise, False) or points_path._pairs(noise, N, False)  # the path under test
    good = noise(pts)
    assert np.isfinite(good).all()
    for bad_value, match in ((np.nan, "finite"), (np.inf, "finite"), (-np.inf, "finite")):
        for where in (0, N // 2, N - 1):
            x = pts.copy()
            x[where, where % 3] = bad_value
            with pytest.raises(ValueError, match=match):
                noise(x)
            with pytest.raises(ValueError, match=match):
                noise(np.ascontiguousarray(x.T), axis=0, workers=2)
    # finite points whose lattice coordinate overflows float64 in a later octave
    x = pts.astype(np.float64)
    x[7, 1] = 1e300
    with pytest.raises(ValueError, match="overflows float64"):
        noise.evaluate(x, octaves=12, lacunarity=1e3)
    # huge but finite lattice coordinates are not refused, and stay in range
    x[7, 1] = 1e250
    assert np.abs(noise(x)).max() <= 1.0 and np.abs(noise.evaluate(x, octaves=2)).max() <= 1.5
    assert np.array_equal(noise(pts), good)  # the refusals left nothing behind
