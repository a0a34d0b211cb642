"""fractal_sum (Eq. 9), turbulence (Eq. 10), octave skipping, and the ``noiselab noise`` command."""
import numpy as np
import pytest

from noiselab import LatticeNoise, fractal_sum, turbulence
from noiselab.cli import main
from noiselab.fractal import octaves_used
from noiselab.lattice import Grid

RNG = np.random.default_rng(99)


def test_fractal_sum_is_eq9_with_paper_defaults():
    noise = LatticeNoise(2, rng=1)
    x = RNG.uniform(-20, 20, (500, 2))
    expected = sum(noise(2.0 ** f * x) / 2.0 ** f for f in range(5))
    np.testing.assert_allclose(fractal_sum(noise, x, 5), expected, atol=1e-13)


def test_turbulence_is_eq10_and_non_negative():
    noise = LatticeNoise(3, rng=2, kernel="quintic", basis="gradient")
    x = RNG.uniform(-20, 20, (500, 3))
    expected = sum(np.abs(noise(2.0 ** f * x)) / 2.0 ** f for f in range(5))
    t = turbulence(noise, x, 5)
    np.testing.assert_allclose(t, expected, atol=1e-13)
    assert t.min() >= 0


def test_lacunarity_gain_and_normalize():
    noise = LatticeNoise(1, rng=3)
    x = np.linspace(0, 30, 1000)
    expected = sum(0.7 ** o * noise(3.0 ** o * x) for o in range(4))
    np.testing.assert_allclose(fractal_sum(noise, x, 4, lacunarity=3.0, gain=0.7), expected, atol=1e-13)
    norm = fractal_sum(noise, x, 4, normalize=True)
    assert np.abs(norm).max() <= 1
    np.testing.assert_allclose(norm * (1 + 0.5 + 0.25 + 0.125), fractal_sum(noise, x, 4), atol=1e-13)
    with pytest.raises(ValueError, match="lacunarity"):
        fractal_sum(noise, x, 4, lacunarity=1.0)
    with pytest.raises(ValueError, match="gain"):
        fractal_sum(noise, x, 4, gain=0)
    with pytest.raises(ValueError, match="octaves"):
        fractal_sum(noise, x, 0)


@pytest.mark.parametrize("summer", [fractal_sum, turbulence])
def test_grid_and_points_agree(summer):
    noise = LatticeNoise(2, 2, rng=4, kernel="catmull-rom")
    grid = Grid((96, 80), [(-3.0, 9.0), (100.0, 110.0)])
    g, used = summer(noise, grid, 6, return_octaves=True)
    p = summer(noise, noise.grid_points(*grid), used)
    assert g.shape == (96, 80, 2)
    np.testing.assert_allclose(g, p, atol=1e-12)


def test_octaves_past_nyquist_are_skipped_and_reported():
    noise = LatticeNoise(2, rng=5)
    # 256 samples over 4 cells: 64 samples per cell; octave o has 2**o / 64
    # cells per sample, aliasing from o = 7 on
    img, used = fractal_sum(noise, Grid((256, 256), [(0, 4), (0, 4)]), 60, return_octaves=True)
    assert used == 7
    assert np.isfinite(img).all() and np.abs(img).max() < 2
    # what is skipped is only aliasing: the skipped octaves would add energy
    # at the sampling Nyquist (white, pixel-to-pixel), not in the band
    forced = sum(0.5 ** o * noise.grid((256, 256), [(0, 4 * 2 ** o), (0, 4 * 2 ** o)]) for o in range(9))
    diff = forced - img
    # successive-pixel differences are as large as the values: uncorrelated
    assert np.corrcoef(diff[:, :-1].ravel(), diff[:, 1:].ravel())[0, 1] < 0.5
    # a finely sampled axis keeps octaves even if the other is coarse
    _, used_mixed = fractal_sum(noise, Grid((4096, 4), [(0, 4), (0, 4)]), 60, return_octaves=True)
    assert used_mixed == 11


def test_sixty_octaves_on_points_neither_overflow_nor_run_all():
    noise = LatticeNoise(3, rng=6, kernel="quintic")
    x = RNG.uniform(-1e3, 1e3, (200, 3))
    v, used = fractal_sum(noise, x, 60, return_octaves=True)
    assert used == octaves_used(60) == 54   # 2**-54 is below float64 resolution
    assert np.isfinite(v).all() and np.abs(v).max() < 2
    v32, used32 = fractal_sum(noise, x.astype(np.float32), 60, return_octaves=True)
    assert used32 == 25 and v32.dtype == np.float32
    # with gain 1 every octave counts, up to coordinates ~ 2**59 * 1e3: still finite and in range
    t, used1 = turbulence(noise, x, 60, gain=1.0, return_octaves=True)
    assert used1 == 60 and np.isfinite(t).all() and t.max() <= 60
    # a point spacing skips octaves past its Nyquist as on a grid
    assert fractal_sum(noise, x, 60, spacing=0.01, return_octaves=True)[1] == 7


def test_fractal_spectrum_follows_one_over_f():
    # gain 1/2 per octave doubling (Hurst exponent H = 1): octave o has
    # amplitude 2**-o on a lattice 2**o times denser, so its 1-D power
    # density is 4**-o * 2**-o at f ~ 2**o: power ~ f**-(2H + 1) = f**-3
    noise = LatticeNoise(1, rng=7, kernel="cubic")
    n, cells = 1 << 16, 64
    v = fractal_sum(noise, Grid((n,), [(0, cells)]), 10)
    spec = np.abs(np.fft.rfft(v - v.mean())) ** 2
    f = np.fft.rfftfreq(n, d=cells / n)
    centres = 0.25 * 2.0 ** np.arange(8)              # 0.25 .. 32 cycles per cell
    power = [spec[(f >= c / np.sqrt(2)) & (f < c * np.sqrt(2))].mean() for c in centres]
    slope = np.polyfit(np.log(centres), np.log(power), 1)[0]
    assert -3.4 < slope < -2.6, slope


def test_generic_callable_noise():
    noise = LatticeNoise(2, rng=8)
    x = RNG.uniform(-5, 5, (100, 2))
    np.testing.assert_allclose(fractal_sum(lambda p: noise(p), x, 4), fractal_sum(noise, x, 4), atol=1e-13)
    with pytest.raises(TypeError, match="noise must be"):
        fractal_sum(3, x, 4)


# ------------------------------------------------------------------- CLI
def test_cli_writes_image_npy_video_and_curve(tmp_path, capsys):
    png = tmp_path / "a" / "b" / "noise.png"
    assert main(["noise", "--size", "64x48", "--octaves", "3", "--kernel", "quintic", "-o", str(png)]) == 0
    import imageio.v3 as iio

    img = iio.imread(png)
    assert img.shape == (64, 48) and img.std() > 5
    npy = tmp_path / "vol" / "v.npy"
    assert main(["noise", "--dims", "3", "--size", "8x16x16", "--sum", "turbulence", "--octaves", "2",
                 "--dtype", "float64", "-o", str(npy)]) == 0
    vol = np.load(npy)
    assert vol.shape == (8, 16, 16) and vol.dtype == np.float64 and vol.min() >= 0
    gif = tmp_path / "t.gif"
    assert main(["noise", "--dims", "3", "--size", "4x16x16", "--basis", "gradient", "-o", str(gif)]) == 0
    assert len(iio.imread(gif, index=None)) == 4
    curve = tmp_path / "c.png"
    assert main(["noise", "--dims", "1", "--size", "500", "--cells", "10", "-o", str(curve)]) == 0
    assert curve.stat().st_size > 1000
    out = capsys.readouterr().out
    assert "octaves used 3/3" in out


def test_cli_tileable_field_tiles(tmp_path):
    npy = tmp_path / "tile.npy"
    assert main(["noise", "--size", "32x40", "--cells", "4x5", "--tileable", "--dtype", "float64", "-o", str(npy)]) == 0
    tile = np.load(npy)
    # wrapping around: the last column continues into the first like any interior step
    wrap = np.abs(tile[:, 0] - tile[:, -1]).max()
    inner = np.abs(np.diff(tile, axis=1)).max()
    assert wrap <= inner * 1.5


def test_cli_bad_input_exits_2(tmp_path, capsys):
    assert main(["noise", "--dims", "3", "-o", str(tmp_path / "x.png")]) == 2
    assert "must end in" in capsys.readouterr().err
    assert main(["noise", "--kernel", "nope", "-o", str(tmp_path / "x.png")]) == 2
    assert main(["noise", "--tileable", "--cells", "2.5", "-o", str(tmp_path / "x.png")]) == 2
    assert not list(tmp_path.iterdir())
