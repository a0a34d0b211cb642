"""Tileable fractal sums: the tile is their only period.

A ``LatticeNoise`` with ``period=P`` tiles with ``P / frequency`` input units.
Its octave ``o`` runs at ``lacunarity**o`` times the frequency; with the base
period it would repeat ``lacunarity**o`` times inside the tile, so a sum of
octaves would correlate with itself shifted by half (a quarter, ...) of the
tile. The measure here: the field with its smooth base octave taken out (an
ideal high-pass above the first octave's band), correlated with itself
shifted by 1/2, 1/4 and 1/8 of the tile along each axis. The old sum (every
octave at the base period, rebuilt here octave by octave) reads near 1 at
1/2 and 1/4 (above 0.4 at 1/8, where the octaves 1 and 2 do not repeat); the
per-octave periods read about 0 (|r| < 0.1).
"""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from noiselab import LatticeNoise, fractal_gradient, fractal_sum, turbulence
from noiselab.lattice import Grid

N, CELLS, OCTAVES = 256, 8, 6
TILE = Grid((N, N), ((0, CELLS), (0, CELLS)))
SHIFTS = (1 / 2, 1 / 4, 1 / 8)


def high_pass(field, cutoff):
    """``field`` without its spatial frequencies below ``cutoff`` cycles per tile (radially)."""
    spec = np.fft.fft2(field - field.mean())
    k = np.fft.fftfreq(field.shape[0], 1 / field.shape[0])
    spec[np.hypot(*np.meshgrid(k, k, indexing="ij")) < cutoff] = 0
    return np.fft.ifft2(spec).real


def shift_correlations(field):
    """Correlation of the high-passed field with itself shifted by each of SHIFTS of the tile, both axes."""
    g = high_pass(field, 2 * CELLS)  # the base octave (8 cells per tile) lies below 2 x 8 cycles
    return np.array([[np.corrcoef(g.ravel(), np.roll(g, int(N * s), axis=a).ravel())[0, 1] for a in (0, 1)]
                     for s in SHIFTS])


def old_sum(noise_kw, octaves, absval=False):
    """The sum with every octave at the base period (the behaviour before per-octave periods)."""
    total = 0.0
    for o in range(octaves):
        v = LatticeNoise(2, frequency=2.0 ** o, **noise_kw).grid(TILE.shape, TILE.extent)
        total = total + 0.5 ** o * (np.abs(v) if absval else v)
    return total


@pytest.mark.parametrize("hash", ["table", "integer"])
@pytest.mark.parametrize("absval", [False, True])
def test_tileable_sum_has_no_period_shorter_than_the_tile(hash, absval):
    kw = dict(rng=3, period=CELLS, hash=hash, kernel="quintic")
    func = turbulence if absval else fractal_sum
    field = func(LatticeNoise(2, **kw), TILE, OCTAVES)
    r = shift_correlations(field)
    if not absval:
        assert np.abs(r).max() < 0.1, r
    else:
        # |noise| keeps a mean pattern that repeats with every lattice cell (value noise varies less between
        # lattice points), and every shift here is a whole number of cells of every octave: a noise with no
        # period at all (a 4096-entry table, so nothing repeats in 8 cells) reads 0.1-0.35 at these shifts
        # too; the tileable sum must read no more than that
        free = shift_correlations(func(LatticeNoise(2, rng=3, hash=hash, kernel="quintic", table_size=4096), TILE,
                                       OCTAVES))
        assert np.abs(r - free).max() < 0.1 and r.max() < 0.25, (r, free)
    # the old sum, rebuilt: octave o repeats 2**o times inside the tile, so at a shift of 2**-k of the tile
    # the octaves o >= k (all of the high-passed field for k <= 1, most of it for k = 2, about half for
    # k = 3) match themselves; |.| of the base octave adds high frequencies that do not repeat, hence the
    # lower bounds for turbulence (measured 0.90, 0.67, 0.33 with the table hash, 0.87, 0.57, 0.20 with the
    # integer hash; at 1/8 that is near the lattice floor of |noise| described above)
    r_old = shift_correlations(old_sum(kw, OCTAVES, absval))
    assert (r_old > np.array([0.8, 0.45, 0.15] if absval else [0.9, 0.9, 0.4])[:, None]).all(), r_old
    # and the new sum still tiles exactly: the next tile over is the same field
    twice = func(LatticeNoise(2, **kw), Grid((2 * N, 2 * N), ((0, 2 * CELLS), (0, 2 * CELLS))), OCTAVES)
    assert np.allclose(twice[:N, :N], field, rtol=0, atol=1e-12)
    assert np.allclose(twice[N:, N:], field, rtol=0, atol=1e-12)
    assert np.allclose(twice[:N, N:], field, rtol=0, atol=1e-12)


@pytest.mark.parametrize("hash", ["table", "integer"])
def test_tileable_sum_edges_continue_across_the_seam(hash):
    """The tile's last row runs on into its first: the step across the seam is like any other step."""
    field = fractal_sum(LatticeNoise(2, rng=4, period=CELLS, hash=hash, kernel="quintic"), TILE, OCTAVES)
    for a in (0, 1):
        steps = np.abs(np.diff(field, axis=a))
        seam = np.abs(np.take(field, 0, axis=a) - np.take(field, -1, axis=a))
        assert seam.mean() < 1.3 * steps.mean(), (seam.mean(), steps.mean())


@pytest.mark.parametrize("hash", ["table", "integer"])
def test_tileable_points_grid_threads_and_chunks_agree(hash):
    noise = LatticeNoise(2, rng=6, period=[4, 6], hash=hash, frequency=[1.0, 1.5])
    grid = Grid((48, 40), ((0, 4), (0, 4)))
    img, used = fractal_sum(noise, grid, 5, return_octaves=True)
    assert used == 4  # the fifth octave is past the grid's Nyquist
    pts = noise.grid_points(grid.shape, grid.extent)
    assert np.allclose(fractal_sum(noise, pts, used), img, rtol=0, atol=1e-12)
    assert np.array_equal(fractal_sum(noise, pts, 5, workers=3), fractal_sum(noise, pts, 5))
    win = noise.evaluate_grid(grid.shape, grid.extent, octaves=used, window=[(7, 30), (3, 40)])
    assert np.array_equal(win, img[7:30, 3:40])
    pytest.importorskip("dask")
    lazy = fractal_sum(noise, grid, 5, chunks=(13, (11, 29)))
    assert np.array_equal(lazy.compute(), img)
    lazy = turbulence(noise, grid, 5, chunks=17, normalize=True)
    assert np.array_equal(lazy.compute(), turbulence(noise, grid, 5, normalize=True))
    # float32 output is the rounded float64 sum
    assert np.array_equal(fractal_sum(noise, grid, 5, dtype=np.float32), img.astype(np.float32))


def test_tileable_gradient_is_the_derivative_and_tiles():
    noise = LatticeNoise(2, rng=7, period=CELLS, kernel="quintic", hash="integer")
    grid = Grid((64, 64), ((0, CELLS), (0, CELLS)))
    value, grad = fractal_gradient(noise, grid, 4, return_value=True)
    assert np.array_equal(value, fractal_sum(noise, grid, 4))
    shifted = fractal_gradient(noise, Grid((64, 64), ((CELLS, 2 * CELLS), (0, CELLS))), 4)
    assert np.allclose(shifted, grad, rtol=0, atol=1e-9)
    # central differences along x
    x = np.random.default_rng(0).uniform(0, CELLS, (50, 2))
    h = 1e-6
    num = (fractal_sum(noise, x + [0, h], 4) - fractal_sum(noise, x - [0, h], 4)) / (2 * h)
    assert np.allclose(fractal_gradient(noise, x, 4)[:, 1], num, rtol=0, atol=1e-5 * np.abs(num).max())


def test_tileable_sum_refuses_what_cannot_tile():
    noise = LatticeNoise(2, period=8)
    with pytest.raises(ValueError, match="lacunarity must be a whole number"):
        fractal_sum(noise, TILE, 4, lacunarity=2.5)
    with pytest.raises(ValueError, match="lacunarity must be a whole number"):
        fractal_sum(noise, TILE, 4, lacunarity=2.5, chunks=64)  # refused at the call, not when computed
    with pytest.raises(ValueError, match=r"exceeds table_size=256.*hash='integer'"):
        fractal_sum(noise, Grid((4096, 4096), ((0, 8), (0, 8))), 7)  # 8 * 2**6 = 512 cells > 256
    with pytest.raises(ValueError, match="exceeds 2\\*\\*32"):
        LatticeNoise(2, period=1 << 30, hash="integer").evaluate(np.zeros((1, 2)), octaves=4)
    # within the limits: a larger table, or the integer hash
    for noise in (LatticeNoise(2, period=8, table_size=512), LatticeNoise(2, period=8, hash="integer")):
        assert fractal_sum(noise, Grid((64, 64), ((0, 8), (0, 8))), 7).shape == (64, 64)
    # one octave and non-tileable noise take any lacunarity
    assert fractal_sum(LatticeNoise(2), TILE, 4, lacunarity=2.5).shape == (N, N)
    assert LatticeNoise(2, period=8).evaluate(np.zeros((3, 2)), lacunarity=2.5).shape == (3,)


def test_cli_tileable_noise_tiles_once(tmp_path):
    out = tmp_path / "t.npy"
    proc = subprocess.run([sys.executable, "-m", "noiselab", "noise", "--size", "256x256", "--cells", "8",
                           "--octaves", "6", "--tileable", "-o", str(out), "--dtype", "float64"],
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    field = np.load(out)
    assert np.abs(shift_correlations(field)).max() < 0.1
    assert "octave o at period cells x 2**o, table_size 256" in proc.stdout
    # 64 cells and 4 visible octaves: the finest octave's period is 512 cells, so the table grows to 512
    big = subprocess.run([sys.executable, "-m", "noiselab", "noise", "--size", "512x512", "--cells", "64",
                          "--octaves", "4", "--tileable", "-o", str(tmp_path / "big.npy"), "--dtype", "float64"],
                         capture_output=True, text=True)
    assert big.returncode == 0 and "octaves used 4/4" in big.stdout and "table_size 512" in big.stdout, big
    field = np.load(tmp_path / "big.npy")
    assert np.abs(field[0] - field[-1]).mean() < 1.3 * np.abs(np.diff(field, axis=0)).mean()  # the seam is a step
    bad = subprocess.run([sys.executable, "-m", "noiselab", "noise", "--size", "64x64", "--octaves", "3",
                          "--tileable", "--lacunarity", "2.5", "-o", str(tmp_path / "b.npy")],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "lacunarity" in bad.stderr and "Traceback" not in bad.stderr
