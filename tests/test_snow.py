"""Falling snow: spectrum, motion, looping, tiling, hard cases and errors."""
import inspect
import itertools

import numpy as np
import pytest
import scipy.fft

import noiselab
from noiselab.snowfall import flake_speeds, iter_tiled_frames, rescale_opacity, snow, snow_spectrum, tile
from noiselab.snowfall.tent import tent_columns
from noiselab.spectral import envelopes as E
from noiselab.spectral import frequency_vectors
from _helpers import phase_correlation_shift, yx


_displacement = phase_correlation_shift


def _mean_displacement(v, steps=6):
    d = np.array([_displacement(v[t], v[t + 1]) for t in range(steps)], float)
    return d.mean(axis=0)


def test_output_is_float32_opacity_in_unit_range():
    a = snow((8, 32, 48), rng=0)
    assert a.shape == (8, 32, 48) and a.dtype == np.float32
    assert a.min() == 0.0 and a.max() == 1.0
    assert noiselab.snow((8, 32, 48), rng=0).tobytes() == a.tobytes()   # the top-level function
    assert noiselab.snowfall.composite is noiselab.composite


_LAYOUT = """
import types
import noiselab
import noiselab.snowfall.background                  # the subpackage, imported before the function is asked for
assert noiselab.snow is noiselab.snowfall.snow, noiselab.snow
assert type(noiselab.snowfall) is types.ModuleType   # a plain module: no class swapped
for old in ("from noiselab.snow import composite", "import noiselab.snow.tent"):
    try:
        exec(old)
    except ImportError as e:   # ModuleNotFoundError, or ImportError under an editable install made before 0.4
        assert "noiselab.snow" in str(e), e
    else:
        raise AssertionError(old + " still imports: the old subpackage path was removed in 0.4")
assert noiselab.snow is noiselab.snowfall.snow, noiselab.snow   # and a failed old import rebinds nothing
print("ok")
"""


def test_noiselab_snow_is_the_function_and_the_subpackage_is_snowfall():
    """``noiselab.snow`` is the function whatever was imported first; the old subpackage path (until 0.3) is gone."""
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-c", _LAYOUT], capture_output=True, text=True)
    assert out.stdout.strip() == "ok", out.stderr


@pytest.mark.parametrize("shape", [(8, 32, 32), (7, 33, 31), (5, 9, 7), (1, 8, 8), (4, 8, 8), (6, 16, 10), (3, 1, 16)])
def test_pruned_inverse_fft_equals_irfftn_of_the_spectrum(shape):
    kw = dict(rng=4, dtype=np.float64, c=0.8, direction=(1, 2), pan=(0.2, -0.1), band=(1, shape[2] / 2))
    S = snow_spectrum(shape, **yx(kw))
    raw = snow(shape, rescale=False, **yx(kw))
    ref = scipy.fft.irfftn(S, s=shape)
    np.testing.assert_allclose(raw, ref, rtol=0, atol=1e-14 * max(1.0, np.abs(ref).max()))
    # and the spectrum is exactly Hermitian where it must be: the round trip
    np.testing.assert_allclose(scipy.fft.rfftn(raw), S, rtol=0, atol=1e-12 * np.abs(S).max())


def test_energy_only_on_the_thickened_tent_inside_the_band():
    shape = (32, 64, 64)
    kw = dict(c=1.3, thickness=0.2, direction=(np.cos(0.4), np.sin(0.4)), pan=(0.3, 0.1))
    S = snow_spectrum(shape, rng=1, band=(6, 20), dtype=np.float64, **yx(kw))
    wt, wy, wx = frequency_vectors(shape)
    dense = (E.annulus(wy, wx, band_cycles_per_sample=(6 / 64, 20 / 64))
             * E.thickened_tent(wt, wy, wx, kw["c"], **yx(dict(direction=kw["direction"], pan=kw["pan"])),
                                thickness=kw["thickness"], tol=np.pi / shape[0]))
    np.testing.assert_array_equal(S != 0, dense > 0)
    # about 1 % of the spectrum carries energy at the default band
    frac = (snow_spectrum((64, 256, 256), rng=0) != 0).mean()
    assert 0.003 < frac < 0.02, frac


@pytest.mark.parametrize("shape,kw", [
    ((15, 48, 64), dict(c=0.9, thickness=0.0, direction=(1.0, 0.0), pan=(0.0, 0.0))),
    ((16, 64, 64), dict(c=0.9, thickness=0.35, direction=(-1.0, 1.0), pan=(0.5, -0.25))),
    ((9, 40, 48), dict(c=0.0, thickness=0.1, direction=(0.0, 1.0), pan=(0.3, 0.2))),
])
def test_snow_cells_are_the_envelopes_tent_surface_cells(shape, kw):
    # snow.tent evaluates spectral.envelopes.tent_surface at the band's cells (no second derivation);
    # its spectrum's support is the dense envelope's, thickened tent x annulus, cell for cell
    T, H, W = shape
    band = (4, 20)
    S = snow_spectrum(shape, rng=2, band=band, amplitude_distribution="fixed", dtype=np.float64, **yx(kw))
    wt, wy, wx = frequency_vectors(shape)
    dense = (E.annulus(wy, wx, band_cycles_per_sample=(band[0] / W, band[1] / W))
             * E.thickened_tent(wt, wy, wx, kw["c"], **yx(dict(direction=kw["direction"], pan=kw["pan"])),
                                thickness=kw["thickness"],
                                tol=np.pi / T))
    assert dense.any()
    np.testing.assert_array_equal(S != 0, dense > 0)
    # the unchecked form snow calls is tent_surface, bit for bit, and its terms are the surface's parts
    wt_s, a, b, _ = E.tent_surface_terms(wy[0], wx[0], kw["c"], E.unit_direction(kw["direction"]), kw["pan"])
    np.testing.assert_array_equal(wt_s, E.tent_surface(wy[0], wx[0], kw["c"],
                                                          **yx(dict(direction=kw["direction"], pan=kw["pan"]))))
    np.testing.assert_array_equal(wt_s, -kw["c"] * a - b)
    # (the band stays off the Nyquist row and column, where a pan's surface is not odd under k -> -k)
    # and the amplitude of each spatial column is the envelope's power law, split over its temporal bins
    col = np.sqrt((np.abs(S) ** 2).sum(axis=0))
    law = E.power_law(wy[0], wx[0], exponent=1.0) * (E.annulus(wy[0], wx[0], band_cycles_per_sample=(
        band[0] / W, band[1] / W)))
    np.testing.assert_allclose(col, law, rtol=1e-12, atol=0)


def test_spatial_spectrum_is_1_over_f_with_equal_energy_per_octave():
    S = snow_spectrum((32, 256, 256), rng=3, dtype=np.float64, amplitude_distribution="fixed", thickness=0.3)
    P = (np.abs(S) ** 2).sum(axis=0)                    # spatial power, summed over temporal bins
    fy = np.fft.fftfreq(256)[:, None] * 256
    fx = np.fft.rfftfreq(256)[None, :] * 256
    r = np.hypot(fy, fx)
    wgt = np.where((fx == 0) | (fx == 128), 1.0, 2.0)   # half spectrum: interior cells count twice
    octaves = [((r >= lo) & (r < 2 * lo) * 1).astype(bool) for lo in (8, 16, 32)]
    energy = [float((P * wgt)[m].sum()) for m in octaves]
    assert np.allclose(energy, np.mean(energy), rtol=0.05), energy
    # the thickness splits a column's power over its bins: per column power is exactly 1/|w|^2
    col = P[r > 0]
    w = 2 * np.pi * r[r > 0] / 256
    np.testing.assert_allclose(col[col > 0], (1 / w[col > 0]) ** 2, rtol=1e-9)


@pytest.mark.parametrize("direction", [(0, 1), (1, 0), (-1, 0), (0, -1), (1, 1), (-1, 2)])
def test_flakes_move_along_the_fall_direction(direction):
    # one ring of spatial frequency, speed c/|w| = 3 px/frame
    f = 8.0
    c = 3.0 * 2 * np.pi * f / 128
    v = snow((24, 128, 128), rng=2, c=c, band=(f, f + 0.5), thickness=0, direction_yx=direction[::-1],
             rescale=False, dtype=np.float64)
    d = np.asarray(direction, float) / np.hypot(*direction)
    measured = _mean_displacement(v)
    assert np.allclose(measured, 3.0 * d, atol=0.75), (measured, 3 * d)


def test_near_flakes_fall_faster_in_proportion_to_inverse_frequency():
    speeds = {}
    c = 1.2
    for f in (6.0, 24.0):
        v = snow((32, 128, 128), rng=5, c=c, band=(f, f * 1.05), thickness=0, rescale=False, dtype=np.float64)
        speeds[f] = _mean_displacement(v, steps=12)[1]
    expect = {f: c * 128 / (2 * np.pi * f) for f in speeds}
    assert speeds[6.0] > 2.5 * speeds[24.0]
    for f in speeds:
        assert abs(speeds[f] - expect[f]) < 0.6, (speeds, expect)


def test_pan_adds_the_camera_velocity_to_every_flake():
    f = 8.0
    c = 2.0 * 2 * np.pi * f / 128  # 2 px/frame down
    v = snow((24, 128, 128), rng=1, c=c, band=(f, f + 0.5), thickness=0, pan_yx=(0.0, -2.0),
             rescale=False, dtype=np.float64)
    assert np.allclose(_mean_displacement(v), (-2.0, 2.0), atol=0.6)


def test_flake_speeds_documented_numbers():
    near, far = flake_speeds(1.0, (16, 128), 512)
    assert round(near, 3) == 5.093 and round(far, 3) == 0.637
    assert flake_speeds(2.0) == pytest.approx((2 * near, 2 * far))


def test_loop_is_seamless():
    a = snow((16, 64, 64), rng=7)
    steps = [np.abs(a[t + 1] - a[t]).mean() for t in range(15)]
    wrap = np.abs(a[0] - a[-1]).mean()
    assert min(steps) * 0.8 < wrap < max(steps) * 1.25
    # a non-periodic splice (two different videos) is a visible jump
    b = snow((16, 64, 64), rng=8)
    assert np.abs(b[0] - a[-1]).mean() > 1.5 * max(steps)


def test_tile_is_seamless_in_space_and_time():
    a = snow((8, 32, 32), rng=1)
    t = tile(a, (2, 2, 3))
    assert t.shape == (16, 64, 96)
    np.testing.assert_array_equal(t[8:, 32:, 64:], a)
    inner = np.abs(np.diff(a, axis=2)).mean()
    seam = np.abs(t[:, :, 32] - t[:, :, 31]).mean()
    assert 0.8 * inner < seam < 1.25 * inner
    with pytest.raises(ValueError, match="reps"):
        tile(a, (2, 2))


def test_iter_tiled_frames_is_lazy_and_matches_tile():
    a = snow((4, 16, 16), rng=2)
    it = iter_tiled_frames(a, (3, 2, 2))
    assert inspect.isgenerator(it)
    frames = np.stack(list(it))
    np.testing.assert_array_equal(frames, tile(a, (3, 2, 2)))
    # a billion frames cost nothing until asked for
    huge = iter_tiled_frames(a, (100, 100), n_frames=10 ** 9)
    first = list(itertools.islice(huge, 5))
    np.testing.assert_array_equal(first[4], first[0])
    assert first[0].shape == (1600, 1600)
    cropped = next(iter_tiled_frames(a, (2, 2), crop=(20, 30)))
    assert cropped.shape == (20, 30)


def test_still_frame():
    S = snow_spectrum((1, 32, 32), rng=0, dtype=np.float64)
    assert S.shape == (1, 32, 17) and (S != 0).sum() > 0
    a = snow((1, 32, 32), rng=0)
    assert a.shape == (1, 32, 32) and a.min() == 0 and a.max() == 1


def test_tiny_frames_and_odd_sizes():
    for shape in [(4, 8, 8), (3, 8, 9), (5, 9, 8)]:
        a = snow(shape, rng=0)
        assert a.shape == shape and np.isfinite(a).all() and a.max() == 1


def test_c_zero_is_frozen_snow():
    a = snow((6, 32, 32), rng=0, c=0.0)
    assert np.array_equal(a[0], a[3]) or np.abs(a - a[0]).max() < 1e-6
    S = snow_spectrum((6, 32, 32), rng=0, c=0.0)
    assert np.all(S[1:] == 0)


def test_band_touching_nyquist():
    shape = (8, 32, 32)
    S = snow_spectrum(shape, rng=1, band=(4, 16), dtype=np.float64)
    assert np.any(S[:, :, 16] != 0)     # the Nyquist column carries energy
    raw = snow(shape, rng=1, band=(4, 16), rescale=False, dtype=np.float64)
    np.testing.assert_allclose(scipy.fft.rfftn(raw), S, atol=1e-12 * np.abs(S).max())


def test_band_errors():
    with pytest.raises(ValueError, match="past the Nyquist frequency 16"):
        snow((4, 32, 32), band=(4, 17))
    with pytest.raises(ValueError, match="band is empty"):
        snow((4, 32, 32), band=(8, 8))
    with pytest.raises(ValueError, match="holds no spatial frequency"):
        snow((4, 32, 32), band=(2.1, 2.2))
    with pytest.raises(ValueError, match="band"):
        snow((4, 32, 32), band=(1, 2, 3))


@pytest.mark.parametrize("kw,match", [
    (dict(c=float("nan")), "c \\(rad/frame\\) must be finite"),
    (dict(c=-0.1), "c \\(rad/frame\\) must be in \\[0, 3.14159\\]"),
    (dict(c=4.0), "c \\(rad/frame\\) must be in"),
    (dict(thickness=-1), "thickness must be in \\[0, 1\\]"),
    (dict(beta=0), "beta must be in \\(0, inf\\)"),
    (dict(beta=float("nan")), "beta must be finite"),
    (dict(direction_yx=(0, 0)), r"direction_yx must be a non-zero vector \(dy, dx\)"),
    (dict(direction_yx=(1, float("nan"))), "direction_yx must be finite"),
    (dict(direction_yx=(1, 2, 3)), r"direction_yx must be a pair \(dy, dx\)"),
    (dict(pan_yx=(0, float("inf"))), "pan_yx must be a finite pair"),
    (dict(on_alias="wrap"), "on_alias"),
    (dict(dtype=np.int32), "float32 or float64"),
])
def test_bad_parameters_are_named(kw, match):
    with pytest.raises((ValueError, TypeError), match=match):
        snow((4, 16, 16), **kw)


def test_bad_shapes_and_rng():
    with pytest.raises(ValueError, match="3 entries"):
        snow((16, 16))
    with pytest.raises(ValueError, match=r"shape\[0\]"):
        snow((0, 16, 16))
    with pytest.raises(ValueError, match="rng"):
        snow((2, 8, 8), rng=-1)


def test_temporal_aliasing_is_detected_with_the_largest_allowed_c():
    with pytest.raises(ValueError, match=r"Largest allowed c .* is 2\.85599") as err:
        snow((8, 32, 32), c=3.0, thickness=0.1)
    assert "on_alias='drop'" in str(err.value)
    snow((8, 32, 32), c=np.pi / 1.1, thickness=0.1)  # the limit itself is fine
    with pytest.raises(ValueError, match="largest pan speed"):
        snow((8, 32, 32), c=1.0, pan_yx=(0.0, 20.0))


def test_drop_mode_leaves_out_the_wrapped_cells():
    shape = (64, 64, 64)
    cols = tent_columns(shape, c=3.0, band=(2, 16), thickness=0.1, direction=(0, 1), pan=(0, 0),
                        exponent=1.0, on_alias="drop")
    assert cols.dropped > 0
    S = snow_spectrum(shape, c=3.0, thickness=0.1, on_alias="drop", rng=0, dtype=np.float64)
    kept = (S != 0).sum()
    ref = (snow_spectrum(shape, c=np.pi / 1.1, thickness=0.1, rng=0) != 0).sum()
    assert 0 < kept
    # every kept cell is within half a bin plus the thickness of the unwrapped tent
    wt, wy, wx = frequency_vectors(shape)
    near = E.thickened_tent(wt, wy, wx, 3.0, direction_yx=(1, 0), thickness=0.1, tol=np.pi / 64 + 1e-9)
    # (the Nyquist bin, +pi and -pi at once, is left out of the comparison)
    carrying = S != 0
    carrying[32] = False
    assert np.all(near[carrying] > 0)
    assert 0 < kept < ref


def test_same_seed_same_bits_float32_close_to_float64():
    a = snow((8, 32, 32), rng=9)
    b = snow((8, 32, 32), rng=9)
    g = snow((8, 32, 32), rng=np.random.default_rng(9))
    assert a.tobytes() == b.tobytes() == g.tobytes()
    assert not np.array_equal(a, snow((8, 32, 32), rng=10))
    d = snow((8, 32, 32), rng=9, dtype=np.float64)
    assert d.dtype == np.float64 and np.abs(d - a).max() < 1e-4


@pytest.mark.parametrize("workers", [2, 3, -1])
def test_bit_identical_for_any_worker_count(workers):
    # frames are rendered in blocks shared among threads; each block is computed the same way by any thread,
    # and the t-pass is scipy's with workers: same bits for any count (odd sizes, many blocks, float64)
    for shape, kw in [((24, 96, 80), {}), ((20, 256, 256), {}), ((7, 33, 31), dict(dtype=np.float64, band=(1, 15))),
                      ((40, 64, 64), dict(rescale=False, pan_yx=(0.1, 0.3)))]:
        a = snow(shape, rng=5, workers=1, **kw)
        b = snow(shape, rng=5, workers=workers, **kw)
        assert a.tobytes() == b.tobytes(), shape
    assert snow((8, 32, 32), rng=1).tobytes() == snow((8, 32, 32), rng=1, workers=workers).tobytes()
    with scipy.fft.set_workers(2):  # None follows scipy's default, set_workers included
        assert snow((8, 32, 32), rng=1).tobytes() == snow((8, 32, 32), rng=1, workers=1).tobytes()
    with pytest.raises(ValueError, match="workers must be"):
        snow((8, 32, 32), workers=0)


def test_rescale_opacity_constant_field_and_nan():
    z = np.full((2, 3, 3), 4.0, np.float32)
    assert np.all(rescale_opacity(z) == 0)
    x = np.array([0.0, 1.0, 4.0])
    np.testing.assert_allclose(rescale_opacity(x.copy(), beta=1.5), [0, 0.125, 1.0])
    np.testing.assert_allclose(rescale_opacity(x.copy(), beta=2.0), [0, 1 / 16, 1.0])
    with pytest.raises(ValueError, match="NaN"):
        rescale_opacity(np.array([0.0, np.nan]))


@pytest.mark.parametrize("workers", [1, 2])
def test_peak_memory_stays_within_1_3_outputs(workers):
    # frame blocks end to end, no second full-size array, whatever the worker count
    import tracemalloc

    shape = (64, 512, 512)  # the benchmark's scene: 64 MiB of float32 output
    snow((2, 16, 16), rng=0)
    tracemalloc.start()
    a = snow(shape, rng=0, workers=workers)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert peak <= 1.3 * a.nbytes, peak / a.nbytes


def test_default_snow_falls_down_in_its_spectrum_and_images():
    shape = (16, 128, 128)
    a = snow(shape, rng=3).astype(np.float64)
    F = np.abs(np.fft.fftn(a - a.mean())) ** 2
    wt = np.fft.fftfreq(16)[:, None, None]
    wy = np.fft.fftfreq(128)[None, :, None]
    # downward motion: energy where wt and wy have opposite signs (wt = -v*wy)
    prod = np.broadcast_to(wt * wy, F.shape)
    down, up = F[prod < 0].sum(), F[prod > 0].sum()
    assert down > 20 * up
    dx, dy = _mean_displacement(a, steps=8)
    assert dy > 0.5 and abs(dx) < 0.5


def test_cli_workers_option_same_video_and_named_errors(tmp_path, capsys):
    from noiselab.cli import main

    outs = []
    for w in ("1", "2"):
        out = tmp_path / f"alpha{w}.npy"
        args = ["snow", "--width", "64", "--height", "48", "--frames", "24", "--loops", "1", "--no-background",
                "--output", str(out), "--quiet", "--workers", w]
        assert main(args) == 0
        outs.append(np.load(out))
    assert outs[0].tobytes() == outs[1].tobytes()
    assert main(["snow", "--width", "16", "--height", "16", "--frames", "2", "--workers", "0",
                 "--output", str(tmp_path / "x.npy"), "--quiet"]) == 2
    assert "workers must be" in capsys.readouterr().err


_SNOW_CASES = """
import numpy as np
from noiselab.snowfall import snow
out = [snow((6, 24, 32), rng=3), snow((5, 20, 18), rng=4, beta=1.0, dtype=np.float64, pan_yx=(0.2, -0.1)),
       snow((4, 16, 20), rng=5, beta=2.0, thickness=0.5), snow((3, 17, 15), rng=6, rescale=False),
       snow((40, 32, 16), rng=7, workers=2)]
"""


def test_snow_kernels_give_the_same_bits_without_the_jit(tmp_path):
    # NUMBA_DISABLE_JIT=1 runs the kernels' Python source (the t-pass scatter, the opacity map for beta 1, 1.5
    # and others, in place and into a new array): the same bits as the compiled kernels
    import os
    import subprocess
    import sys

    script = _SNOW_CASES + ("from noiselab.snowfall.render import opacity_copy\n"
                            "out.append(opacity_copy(np.linspace(-2, 3, 11, dtype=np.float32), 2.5))\n"
                            "np.save(__import__('sys').argv[1], np.concatenate([o.ravel().astype(np.float64) "
                            "for o in out]))\n")
    path = tmp_path / "nojit.npy"
    subprocess.run([sys.executable, "-W", "ignore", "-c", script, str(path)],
                   env=dict(os.environ, NUMBA_DISABLE_JIT="1"), check=True, timeout=300)
    from noiselab.snowfall.render import opacity_copy

    ns = {}
    exec(_SNOW_CASES, ns)
    ns["out"].append(opacity_copy(np.linspace(-2, 3, 11, dtype=np.float32), 2.5))
    want = np.concatenate([o.ravel().astype(np.float64) for o in ns["out"]])
    got = np.load(path)
    assert got.shape == want.shape and got.tobytes() == want.tobytes()


def test_snow_through_scipy_fft_functions_gives_the_same_bits(monkeypatch):
    # the passes call pocketfft's binding (writing into a given array); scipy.fft's public functions, the
    # fallback for a scipy without that module, run the same transforms: the same bits, in memory and chunked
    from noiselab.snowfall import tent

    if tent._pocketfft is None:
        pytest.skip("this scipy has no pocketfft binding: the fallback is the only path")
    ns = {}
    exec(_SNOW_CASES, ns)
    monkeypatch.setattr(tent, "_pocketfft", None)
    ns2 = {}
    exec(_SNOW_CASES, ns2)
    for a, b in zip(ns["out"], ns2["out"]):
        assert a.dtype == b.dtype and a.tobytes() == b.tobytes()


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("beta", [1.0, 1.5, 2.0])
def test_opacity_copy_equals_rescale_opacity_and_keeps_the_field(dtype, beta):
    from noiselab.snowfall.render import opacity_copy

    x = np.random.default_rng(3).standard_normal((5, 7, 9)).astype(dtype)
    keep = x.copy()
    got = opacity_copy(x, beta, lo=float(x.min()), hi=float(x.max()))
    assert got is not x and np.array_equal(x, keep)   # the field is not touched
    want = rescale_opacity(x.copy(), beta)
    assert got.dtype == dtype and got.tobytes() == want.tobytes()
    assert got.min() == 0 and got.max() == 1
    assert np.all(opacity_copy(np.full(4, 2.0, dtype)) == 0)   # a constant field: transparent
    with pytest.raises(ValueError, match="beta"):
        opacity_copy(x, 0.0)
    big = np.full((7, 7, 9), -1, dtype)   # into a slab of a larger array, the rest untouched
    assert opacity_copy(x, beta, out=big[1:6]) is not None and big[1:6].tobytes() == want.tobytes()
    assert np.all(big[0] == -1) and np.all(big[6] == -1)
    with pytest.raises(ValueError, match="out must not overlap field"):
        opacity_copy(x, beta, out=x)
    with pytest.raises(ValueError, match="out must be a C-contiguous"):
        opacity_copy(x, beta, out=big[:, 1:6])
