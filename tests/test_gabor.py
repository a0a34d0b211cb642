"""Sparse Gabor noise: the kernels against the slow reference, bits across paths and windows, truncation, errors."""
from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import naive
from noiselab.gabor import GaborNoise, truncation_error

RNG = np.random.default_rng(36)
ROOT = Path(__file__).resolve().parents[1]


def _noise(dim, moving=False, rows=3, density=3.0, rng=5):
    F = RNG.uniform(-0.2, 0.2, (rows, dim))
    s = RNG.uniform(0.05, 0.2, dim)
    vel = RNG.uniform(-2.0, 2.0, (rows, 2)) if moving else None
    return GaborNoise(F, bandwidth=s, velocities_yx=vel, density=density, rng=rng), F, s, vel


def _grid_points(origin, shape, step=1.0):
    axes = [o + np.arange(n) * step for o, n in zip(origin, shape)]
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)


@pytest.mark.parametrize("dim, moving", [(2, False), (3, False), (3, True)])
def test_points_equal_the_direct_sum_over_the_hashed_impulses(dim, moving):
    g, F, s, vel = _noise(dim, moving)
    pts = RNG.uniform(-60.0, 60.0, (40, dim))
    pts[:5] += RNG.uniform(-1e6, 1e6, (5, dim))   # far from the origin, negative cells included
    fast = g(pts, dtype=np.float64)
    ref = naive.gabor_noise(pts, key=g.key, freqs=F, bandwidth=s, velocity=vel, density=3.0)
    assert np.abs(ref).max() > 0.5
    np.testing.assert_allclose(fast, ref, rtol=0, atol=1e-12)


@pytest.mark.parametrize("dim, moving", [(2, False), (3, False), (3, True)])
def test_grid_equals_points_and_any_window_equals_the_same_region(dim, moving):
    g, *_ = _noise(dim, moving)
    shape = (24, 40) if dim == 2 else (6, 20, 24)
    origin = (-7, 13) if dim == 2 else (999_990, -3, 5)
    big = g.grid(shape, origin=origin, dtype=np.float64)
    assert np.array_equal(g(_grid_points(origin, shape), dtype=np.float64), big)
    sl = (slice(5, 17), slice(9, 30)) if dim == 2 else (slice(2, 5), slice(4, 15), slice(1, 20))
    sub_origin = tuple(o + s.start for o, s in zip(origin, sl))
    sub_shape = tuple(s.stop - s.start for s in sl)
    assert np.array_equal(g.grid(sub_shape, origin=sub_origin, dtype=np.float64), big[sl])
    # any thread count, any block split: the same bits
    assert np.array_equal(g.grid(shape, origin=origin, dtype=np.float64, workers=3), big)


def test_non_integer_steps_match_the_points_at_the_same_coordinates():
    g, *_ = _noise(2)
    origin, step = (0.3, -2.7), 0.37
    grid = g.grid((17, 23), origin=origin, step=step, dtype=np.float64, workers=2)
    pts = np.stack(np.meshgrid(origin[0] + np.arange(17) * step, origin[1] + np.arange(23) * step, indexing="ij"), -1)
    assert np.array_equal(g(pts, dtype=np.float64), grid)


def test_same_int_same_bits_other_int_other_noise():
    a = GaborNoise([[0.0, 0.1]], bandwidth=0.05, rng=7).grid((32, 32))
    b = GaborNoise([[0.0, 0.1]], bandwidth=0.05, rng=7).grid((32, 32))
    c = GaborNoise([[0.0, 0.1]], bandwidth=0.05, rng=8).grid((32, 32))
    assert np.array_equal(a, b)
    assert np.corrcoef(a.ravel(), c.ravel())[0, 1] < 0.3


def test_same_bits_in_another_process_and_without_the_jit():
    """The compiled kernels and plain Python (NUMBA_DISABLE_JIT=1) give the same values, in a fresh process."""
    code = ("import numpy as np; from noiselab.gabor import GaborNoise;"
            "g = GaborNoise([[0.0, 0.1, 0.05], [0.1, 0.0, 0.0]], bandwidth=(0.2, 0.1, 0.1), velocities_yx=[[1, 0], [0, -1]],"
            " density=2.0, rng=11);"
            "a = g.grid((2, 6, 7), origin=(3, -2, 4), dtype=np.float64);"
            "b = g(np.array([[3.5, 1.25, -9.0], [1e5, 2.0, 3.0]]), dtype=np.float64);"
            "print(repr(a.tolist()), repr(b.tolist()))")
    env = dict(os.environ, PYTHONPATH=str(ROOT), NUMBA_DISABLE_JIT="1")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    g = GaborNoise([[0.0, 0.1, 0.05], [0.1, 0.0, 0.0]], bandwidth=(0.2, 0.1, 0.1), velocities_yx=[[1, 0], [0, -1]],
                   density=2.0, rng=11)
    a = g.grid((2, 6, 7), origin=(3, -2, 4), dtype=np.float64)
    b = g(np.array([[3.5, 1.25, -9.0], [1e5, 2.0, 3.0]]), dtype=np.float64)
    ja, jb = out.split("] [")
    np.testing.assert_allclose(np.array(eval(ja + "]")), a, rtol=0, atol=1e-13)
    np.testing.assert_allclose(np.array(eval("[" + jb)), b, rtol=0, atol=1e-13)


@pytest.mark.parametrize("dim, shape", [(2, (384, 384)), (3, (48, 96, 96))])
def test_truncation_error_is_the_stated_bound(dim, shape):
    """Cutting the kernels at 1 % of their peak changes the noise by the stated relative RMS (measured)."""
    F = [[0.0, 0.1]] if dim == 2 else [[0.03, 0.0, 0.1]]
    s = 0.05 if dim == 2 else 0.08
    cut = GaborNoise(F, bandwidth=s, truncation=0.01, rng=3).grid(shape, dtype=np.float64)
    full = GaborNoise(F, bandwidth=s, truncation=1e-9, rng=3).grid(shape, dtype=np.float64)
    measured = math.sqrt(np.mean((cut - full) ** 2) / np.mean(full ** 2))
    bound = truncation_error(0.01, dim)
    assert 0.7 * bound < measured < 1.3 * bound, (measured, bound)


def test_variance_is_one_and_float32_rounds_the_float64_sum_once():
    g = GaborNoise([[0.0, 0.08], [0.08, 0.0]], bandwidth=0.04, rng=4)
    x64 = g.grid((512, 512), dtype=np.float64)
    x32 = g.grid((512, 512))
    assert x32.dtype == np.float32
    assert np.array_equal(x32, x64.astype(np.float32))
    # float32's error, measured: half an ulp of values of RMS 1
    assert np.abs(x32 - x64).max() < 6e-7 * np.abs(x64).max()
    # about 6 cells of 25 px per side: the variance of this one field is 1 within its sampling spread
    assert 0.75 < x64.var() < 1.25
    assert abs(x64.mean()) < 0.15


def test_expected_spectrum_integrates_to_the_variance():
    g = GaborNoise([[0.0, 0.1], [0.07, 0.07]], bandwidth=(0.03, 0.05), rng=0)
    f = np.linspace(-0.5, 0.5, 801)
    fy, fx = np.meshgrid(f, f, indexing="ij")
    total = g.expected_spectrum(fy, fx).sum() * (f[1] - f[0]) ** 2
    assert abs(total - 1.0) < 1e-6
    gm = GaborNoise([[0.0, 0.0, 0.1]], bandwidth=(0.1, 0.05, 0.05), velocities_yx=[[1.0, 0.5]], rng=0)
    f = np.linspace(-0.6, 0.6, 121)
    ft, fy, fx = np.meshgrid(f, f, f, indexing="ij")
    S = gm.expected_spectrum(ft, fy, fx)
    assert abs(S.sum() * (f[1] - f[0]) ** 3 - 1.0) < 1e-3
    # a moving kernel's energy lies on the plane ft = -(vy fy + vx fx)
    i = np.unravel_index(np.argmax(S), S.shape)
    assert abs(ft[i] + 1.0 * fy[i] + 0.5 * fx[i]) < 0.011


@pytest.mark.parametrize("dim", [2, 3])
def test_expected_spectrum_on_sparse_grids_equals_the_point_by_point_sum(dim):
    g = GaborNoise(RNG.uniform(-0.3, 0.3, (200, dim)), bandwidth=RNG.uniform(0.03, 0.1, dim), rng=1)
    sparse = np.meshgrid(*[np.linspace(-0.5, 0.5, n) for n in (20, 24, 28)[:dim]], indexing="ij", sparse=True)
    fast = g.expected_spectrum(*sparse)
    slow = g.expected_spectrum(*[x.ravel() for x in np.broadcast_arrays(*sparse)]).reshape(fast.shape)
    np.testing.assert_allclose(fast, slow, rtol=1e-12, atol=1e-12 * slow.max())


def test_moving_kernels_move():
    """The mean of x(t+1, y, x + v) x(t, y, x) peaks at the kernels' velocity."""
    g = GaborNoise([[0.0, 0.0, 0.12]], bandwidth=(0.02, 0.04, 0.04), velocities_yx=[[0.0, 3.0]], rng=9)
    v = g.grid((2, 96, 160), dtype=np.float64)
    lags = range(-6, 7)
    corr = [np.mean(v[1, :, 10 + k:140 + k] * v[0, :, 10:140]) for k in lags]
    assert list(lags)[int(np.argmax(corr))] == 3


# ---------------------------------------------------------------- bad input
BAD_REALS = [float("nan"), float("inf"), -1.0, 0.0, "1", None, 1j, True, 10 ** 400]


@settings(max_examples=30, deadline=None, derandomize=True)
@given(st.sampled_from(["bandwidth", "density", "truncation"]), st.sampled_from(BAD_REALS))
def test_bad_parameters_give_an_error_naming_them(name, value):
    kw = dict(bandwidth=0.05, density=4.0, truncation=0.01)
    kw[name] = value
    with pytest.raises((ValueError, TypeError), match=name):
        GaborNoise([[0.0, 0.1]], **kw)


@settings(max_examples=30, deadline=None, derandomize=True)
@given(st.sampled_from([np.zeros((0, 2)), np.zeros((3,)), np.zeros((2, 4)), np.array([[np.nan, 0.1]]),
                        np.array([["a", "b"]]), [[0.1], [0.2, 0.3]], None, np.zeros((2, 1))]))
def test_bad_frequency_tables_are_refused(table):
    with pytest.raises((ValueError, TypeError), match="frequencies"):
        GaborNoise(table, bandwidth=0.05)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(st.sampled_from([np.zeros((4, 3)), np.zeros((4,)), np.array([[np.inf, 0.0]]), np.array([[1e300, 0.0]]),
                        "xy", np.ones((2, 2), dtype=complex)]))
def test_bad_points_are_refused(points):
    g = GaborNoise([[0.0, 0.1]], bandwidth=0.05)
    with pytest.raises((ValueError, TypeError), match="points"):
        g(points)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(st.sampled_from([("shape", (0, 4)), ("shape", (4,)), ("shape", (2 ** 62, 2 ** 62)), ("origin", (0.0,)),
                        ("origin", (float("nan"), 0.0)), ("step", 0.0), ("step", -1.0), ("step", (1.0, float("inf"))),
                        ("dtype", np.int32), ("dtype", "float16"), ("workers", 0), ("workers", 1.5),
                        ("origin", (1e300, 0.0))]))
def test_bad_grid_arguments_are_refused(case):
    name, value = case
    g = GaborNoise([[0.0, 0.1]], bandwidth=0.05)
    kw = dict(shape=(4, 4))
    kw[name] = value
    with pytest.raises((ValueError, TypeError, MemoryError), match=name if name != "origin" or value[0] != 1e300
                       else "origin"):
        g.grid(**kw)


def test_velocity_needs_three_axes_and_one_row_per_frequency():
    with pytest.raises(ValueError, match="velocities_yx"):
        GaborNoise([[0.0, 0.1]], bandwidth=0.05, velocities_yx=[[1.0, 0.0]])
    with pytest.raises(ValueError, match="velocities_yx"):
        GaborNoise([[0.0, 0.0, 0.1]], bandwidth=0.05, velocities_yx=[[1.0, 0.0], [0.0, 1.0]])
    with pytest.raises(ValueError, match="dim"):
        truncation_error(0.01, 4)


def test_the_recorded_hash_fingerprint_is_the_lattice_hash_of_today():
    """A change to the lattice's hash must touch the Gabor kernels' file, or numba's cache keeps the old ones."""
    import hashlib

    from noiselab.gabor import _kernels
    from noiselab.lattice.hashing import MULT, mix32, prime

    words = np.array([int(mix32(np.uint32(i * 2654435761 % 2**32))) for i in range(4096)], dtype=np.uint32)
    primes = np.array([int(prime(np.int64(j), MULT[a])) for j in (-5, 0, 7, 123456789) for a in range(4)],
                      dtype=np.uint32)
    fingerprint = hashlib.sha256(words.tobytes() + primes.tobytes() + MULT.tobytes()).hexdigest()[:16]
    assert fingerprint == _kernels.HASH_FINGERPRINT, (
        f"the lattice hash changed (fingerprint {fingerprint}): set HASH_FINGERPRINT in "
        "noiselab/gabor/_kernels.py to it, so that numba recompiles the Gabor kernels")
