"""Tests of the laboratory: the alternative snow generators and the experiment machinery (no timing asserted)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from noiselab.analysis import band_speeds, octave_bands, tent_energy
from noiselab.lab import layer_plan, lattice_peak, layered_lattice_snow, particle_snow
from noiselab.lab.experiments import Config, knee, parallax_error, texture_quality
from noiselab.lab.measure import fit_exponent, fit_nlogn, time_against_floor
from noiselab.lab.run import md_table

SHAPE = (16, 128, 128)
BAND = (8.0, 32.0)


# ----------------------------------------------------------------------------- layered lattice snow

@pytest.fixture(scope="module")
def layered():
    return layered_lattice_snow(SHAPE, rng=3, band=BAND, c=1.0, layers=8)


def test_layered_range_dtype_and_shape(layered):
    assert layered.shape == SHAPE and layered.dtype == np.float32
    assert layered.min() == 0.0 and layered.max() == 1.0


def test_layered_obeys_parallax_law(layered):
    bands = octave_bands(BAND[0], BAND[1], 1)
    v = band_speeds(layered, bands)
    centres = np.sqrt([lo * hi for lo, hi in bands])
    law = 1.0 * SHAPE[2] / (2 * np.pi * centres)
    # falls straight down, in every band
    assert np.all(v[:, 1] > 0)
    assert np.all(np.abs(v[:, 0]) < 0.1 * v[:, 1])
    # speed x frequency constant: each band within 20 % of c N / (2 pi f)
    np.testing.assert_allclose(v[:, 1], law, rtol=0.2)
    # and the slope of log speed against log frequency is near -1
    assert fit_exponent(centres, v[:, 1]) == pytest.approx(-1.0, abs=0.2)


def test_layered_direction_and_c():
    a = layered_lattice_snow((12, 64, 64), rng=1, band=(4, 16), c=0.8, direction_yx=(0, 1), layers=4)
    v = band_speeds(a, [(4, 8), (8, 16)])
    assert np.all(v[:, 0] > 0) and np.all(np.abs(v[:, 1]) < 0.2 * v[:, 0])
    frozen = layered_lattice_snow((4, 32, 32), rng=1, c=0.0, layers=2)
    assert np.array_equal(frozen[0], frozen[3])


def test_layered_energy_mostly_on_tent(layered):
    # a lattice method puts most, not all, of its power on the tent (each layer is about an octave wide)
    assert 0.4 < tent_energy(layered, 1.0, BAND) < 0.99


def test_layer_plan_speeds_fall_with_frequency():
    plan = layer_plan((8, 256, 256), c=1.0, band=(8, 64), layers=6)
    f, v = plan["frequency"], plan["speed"]
    assert np.all(np.diff(f) > 0) and np.all(np.diff(v) < 0)
    np.testing.assert_allclose(v * f, 256 / (2 * np.pi), rtol=1e-12)
    assert f[0] == pytest.approx(8, rel=0.35) and f[-1] == pytest.approx(64, rel=0.1)
    assert 0.4 < lattice_peak() < 0.7


def test_layered_same_seed_same_bits():
    a = layered_lattice_snow((3, 48, 40), rng=7, layers=3)
    b = layered_lattice_snow((3, 48, 40), rng=np.random.default_rng(7), layers=3)
    c = layered_lattice_snow((3, 48, 40), rng=8, layers=3)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


# ----------------------------------------------------------------------------- particle snow

@pytest.fixture(scope="module")
def particles():
    return particle_snow(SHAPE, rng=2, band=BAND, c=1.0, flakes=600, return_flakes=True)


def test_particles_flakes_table(particles):
    a, fl = particles
    assert a.shape == SHAPE and a.dtype == np.float32
    assert 0.0 <= a.min() and a.max() <= 1.0 and a.max() > 0.5
    # speed and size both fall with depth (1/z), speed = c D / pi
    order = np.argsort(fl["depth"])
    assert np.all(np.diff(fl["speed"][order]) <= 0) and np.all(np.diff(fl["diameter"][order]) <= 0)
    np.testing.assert_allclose(fl["speed"], fl["diameter"] / np.pi)
    assert fl["diameter"].max() <= SHAPE[2] / (2 * BAND[0]) + 1e-9
    assert fl["diameter"].min() >= SHAPE[2] / (2 * BAND[1]) - 1e-9
    # uniform density in the viewing volume: more far flakes than near ones
    mid = math.sqrt(fl["depth"].min() * fl["depth"].max())
    assert np.sum(fl["depth"] > mid) > 2 * np.sum(fl["depth"] < mid)


def test_particles_move_down_faster_when_near(particles):
    a, _ = particles
    v = band_speeds(a, [(4, 8), (16, 32)])
    assert np.all(v[:, 1] > 0)  # down the image
    assert v[0, 1] > 1.2 * v[1, 1]  # low frequencies (near, large flakes) move faster


def test_single_flake_moves_by_its_speed():
    a, fl = particle_snow((6, 64, 64), rng=5, band=(4, 8), flakes=1, return_flakes=True)
    ys = [np.average(np.arange(64), weights=a[t].sum(axis=1)) for t in range(2)]
    assert ys[1] - ys[0] == pytest.approx(fl["speed"][0], abs=0.15) or fl["y"][0] > 64 - 12


def test_motion_blur_spreads_a_flake_along_its_motion_and_keeps_its_coverage():
    kw = dict(rng=5, band=(4, 8), flakes=1, opacity=0.5, return_flakes=True)
    sharp, fl = particle_snow((6, 64, 64), **kw)
    blurred, _ = particle_snow((6, 64, 64), motion_blur=True, **kw)
    assert fl["speed"][0] > 1.0  # moves more than a pixel per frame
    assert blurred.sum() == pytest.approx(sharp.sum(), rel=0.02)  # the same total coverage
    rows_sharp = (sharp[2] > 0).any(axis=1).sum()
    rows_blur = (blurred[2] > 0).any(axis=1).sum()
    cols_sharp = (sharp[2] > 0).any(axis=0).sum()
    cols_blur = (blurred[2] > 0).any(axis=0).sum()
    assert rows_blur > rows_sharp and cols_blur == cols_sharp  # longer along y (the fall), not across


def test_particles_same_seed_same_bits():
    a = particle_snow((3, 40, 48), rng=11, flakes=80)
    b = particle_snow((3, 40, 48), rng=11, flakes=80)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, particle_snow((3, 40, 48), rng=12, flakes=80))


# ----------------------------------------------------------------------------- bad input

@pytest.mark.parametrize("fn", [layered_lattice_snow, particle_snow])
@pytest.mark.parametrize("kwargs, match", [
    ({"shape": (4, 32)}, "shape"),
    ({"shape": (0, 32, 32)}, "shape"),
    ({"c": float("nan")}, "c"),
    ({"c": 4.0}, "c"),
    ({"band": (8, 4)}, "empty"),
    ({"band": (4, 40)}, "band"),
    ({"band": (0, 8)}, "band"),
    ({"direction_yx": (0, 0)}, "direction_yx"),
    ({"dtype": np.int32}, "dtype"),
    ({"rng": -1}, "rng"),
])
def test_bad_input_is_a_clear_error(fn, kwargs, match):
    args = {"shape": (4, 32, 32), **kwargs}
    with pytest.raises((ValueError, TypeError), match=match):
        fn(**args)


def test_generator_specific_bad_input():
    with pytest.raises(ValueError, match="layers"):
        layered_lattice_snow((2, 32, 32), layers=0)
    with pytest.raises(ValueError, match="flakes"):
        particle_snow((2, 32, 32), flakes=0)
    with pytest.raises(ValueError, match="opacity"):
        particle_snow((2, 32, 32), opacity=1.5)
    with pytest.raises(ValueError, match="kernel"):
        layered_lattice_snow((2, 32, 32), kernel="nope")


# ----------------------------------------------------------------------------- experiment machinery

def test_time_against_floor_counts_and_ratios():
    calls = {"n": 0}

    def case():
        calls["n"] += 1
        return np.ones(10)

    r = time_against_floor({"case": case}, lambda: np.ones(10), repeats=5, warmup=1)
    assert calls["n"] == 6 and len(r["case"]["times"]) == 5
    assert r["floor"]["ratio"] == 1.0 and r["case"]["ratio"] > 0
    with pytest.raises(ValueError, match="repeats"):
        time_against_floor({}, lambda: None, repeats=0)


def test_fits_recover_known_laws():
    n = np.array([1e3, 1e4, 1e5, 1e6])
    assert fit_exponent(n, 3e-9 * n**1.5) == pytest.approx(1.5)
    assert fit_nlogn(n, 1e-9 * n * np.log2(n)) == pytest.approx(1.0)
    with pytest.raises(ValueError):
        fit_exponent([10], [1])


def test_knee_is_cheapest_point_under_threshold():
    pts = [{"time_s": 1.0, "error": 0.3}, {"time_s": 2.0, "error": 0.01}, {"time_s": 0.5, "error": 0.5},
           {"time_s": 4.0, "error": 0.0}]
    assert knee(pts, 0.02)["time_s"] == 2.0
    assert knee(pts, 1e-9)["time_s"] == 4.0
    assert knee(pts, -1) is None


def test_texture_quality_tells_spectral_from_striped():
    from noiselab.spectral import spectral_noise

    iso = texture_quality(spectral_noise((128, 128), exponent=1.0, band=(4, 64), rng=0), 4.0, 2)
    assert abs(iso["slope_error"]) < 0.15 and iso["anisotropy"] < 0.1 and iso["band_leakage"] < 1e-6
    rows = np.random.default_rng(0).standard_normal((1, 128)) * np.ones((128, 1))
    striped = texture_quality(rows + 1e-3 * np.random.default_rng(1).standard_normal((128, 128)), 4.0, 2)
    assert striped["anisotropy"] > 0.5


def test_parallax_error_of_tent_snow_is_small():
    from noiselab.snowfall import snow

    a = snow(SHAPE, rng=0, band=BAND, c=1.0)
    centres, speed, law, err = parallax_error(a, 1.0, BAND)
    assert err < 0.1 and np.all(np.diff(speed) < 0)


def test_md_table_formats():
    t = md_table([{"a": 1234, "b": 1e-7, "c": float("nan"), "d": "x|y"}], [("a", "A"), ("b", "B"), ("c", "C"), ("d", "D")])
    assert t.splitlines()[2] == "| 1,234 | 1.00e-07 | - | x/y |"


def test_quick_experiments_make_well_formed_tables():
    from noiselab.lab.experiments import snow_experiment, texture_experiment

    cfg = Config.quick_config()
    rows = texture_experiment(cfg, dims=(2,))
    assert {r["method"] for r in rows} >= {"spectral (IFFT)", "value noise, cubic", "gradient noise, quintic"}
    for r in rows:
        for k in ("time_s", "x_fft_floor", "x_write_floor", "peak_mib", "slope_error", "anisotropy", "band_leakage"):
            assert np.isfinite(r[k]), (r["method"], k)
        assert r["time_s"] > 0 and r["peak_mib"] > 0 and 0 <= r["band_leakage"] <= 1
    spectral = next(r for r in rows if r["family"] == "spectral")
    assert spectral["band_leakage"] < 1e-6  # an exact spectrum has nothing outside its band
    assert all(r["band_leakage"] > 0.01 for r in rows if r["family"] == "lattice")
    snow_rows = snow_experiment(cfg)
    assert [r["method"].split(" (")[0] for r in snow_rows] == ["tent IFFT", "layered lattice", "particles",
                                                                "particles, motion-blurred",
                                                                "sparse Gabor, moving kernels"]
    tent, lay, par, blur, gabor = snow_rows
    assert gabor["loop_seam"] > 1.2   # no period: it does not loop either
    assert tent["loop_seam"] == pytest.approx(1.0, abs=0.05)  # the IFFT loops exactly
    assert min(lay["loop_seam"], par["loop_seam"], blur["loop_seam"]) > 1.2  # the others do not
    assert tent["tent_energy"] > max(lay["tent_energy"], par["tent_energy"], blur["tent_energy"])
    assert blur["mean_alpha"] == pytest.approx(par["mean_alpha"], rel=0.1)  # blur spreads coverage, keeps it


def test_failing_peer_is_reported_not_dropped():
    from noiselab.lab.peers import image_quality, run_group

    rng = np.random.default_rng(0)
    cases = {"good": lambda: rng.standard_normal((32, 32)), "broken": lambda: 1 / 0,
             "wrong shape": lambda: np.zeros((8, 8))}
    rows = run_group("g", cases, (32, 32), "write", 5, lambda a: image_quality(a, 0.0, (2.0, 8.0)))
    by = {r["case"]: r for r in rows}
    assert set(by) == {"good", "broken", "wrong shape"}
    assert by["broken"]["status"] == "failed" and "ZeroDivisionError" in by["broken"]["error"]
    assert by["wrong shape"]["status"] == "failed" and "shape" in by["wrong shape"]["error"]
    assert by["good"]["status"] == "ok" and abs(by["good"]["slope"]) < 0.3  # white noise: flat


def test_bench_cli_rejects_a_file_as_output(tmp_path, capsys):
    from noiselab.cli import main

    f = tmp_path / "file.txt"
    f.write_text("x")
    assert main(["bench", "--quick", "--output", str(f)]) == 2
    assert "--output" in capsys.readouterr().err


@pytest.mark.parametrize("modname", ["noiselab.lab.snowgen", "noiselab.lab.measure", "noiselab.lab.experiments",
                                     "noiselab.lab.run"])
def test_docstring_examples_run(modname):
    import doctest
    import importlib

    result = doctest.testmod(importlib.import_module(modname), optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0


def test_peak_rss_sees_a_known_allocation():
    from noiselab.lab.measure import peak_rss

    mib = peak_rss("import numpy as np", "np.ones((64, 1024, 1024), dtype=np.uint8)")
    assert mib is not None and 60 < mib < 80  # 64 MiB, plus little


def test_spectral_deviation_tells_1_over_f_from_white():
    from noiselab.lab.experiments import _spectral_deviation
    from noiselab.spectral import spectral_noise

    pink = spectral_noise((256, 256), exponent=1.0, band=(8, 64), rng=0, amplitude_distribution="fixed")
    white = np.random.default_rng(0).standard_normal((256, 256))
    assert _spectral_deviation(pink, (8, 64)) < 0.3
    assert _spectral_deviation(white, (8, 64)) > 3.0


def test_layered_frames_render_in_pieces():
    full = layered_lattice_snow((8, 32, 48), rng=4, layers=3, rescale=False, dtype=np.float64)
    piece = layered_lattice_snow((3, 32, 48), rng=4, layers=3, rescale=False, dtype=np.float64, start=5)
    assert np.array_equal(full[5:8], piece)
    with pytest.raises(ValueError, match="start"):
        layered_lattice_snow((2, 32, 32), start=-1)


# ----------------------------------------------------------------------------- the literature's measures

@pytest.mark.parametrize("kernel,basis", [("linear", "value"), ("catmull-rom", "value"), ("quintic", "gradient")])
def test_lattice_spectrum_is_the_mean_periodogram_of_periodic_lattice_noise(kernel, basis):
    from noiselab import LatticeNoise
    from noiselab.analysis import PowerSpectrum, envelope_error, power_spectrum
    from noiselab.lab.quality import lattice_spectrum

    n, cells = 96, 13  # 7.4 px per cell: every lattice point at another sampling phase
    mean = np.mean([power_spectrum(LatticeNoise(2, rng=s, kernel=kernel, basis=basis, period=cells)
                                   .grid((n, n), [(0, cells)] * 2)).power for s in range(24)], axis=0)
    spec = PowerSpectrum(power=mean, shape=(n, n), axes=(0, 1))
    err = envelope_error(spec, lattice_spectrum(kernel, basis, n, cells), groups=8, support=1e-4)
    # 24 realisations of 169 lattice values: each group's mean holds a few hundred independent draws
    assert err.rms_db < 0.6 and err.outside < 1e-3, (err.rms_db, err.outside)
    # the same field against the other basis' spectrum is visibly wrong
    other = "gradient" if basis == "value" else "value"
    assert envelope_error(spec, lattice_spectrum(kernel, other, n, cells), groups=8, support=1e-4).rms_db > 2 * err.rms_db


@pytest.mark.parametrize("kernel,basis", [("linear", "value"), ("cubic", "value"), ("quintic", "gradient")])
def test_lattice_variance_is_the_empirical_variance(kernel, basis):
    from noiselab import LatticeNoise
    from noiselab.lab.quality import lattice_variance

    noise = LatticeNoise(1, rng=4, kernel=kernel, basis=basis, table_size=1 << 16)
    line = noise.grid((1 << 18,), [(0, 1 << 14)])
    assert line.var() == pytest.approx(lattice_variance(noise), rel=0.03)


def test_quality_experiment_quick_reports_every_generator():
    from noiselab.lab.quality import quality_experiment, quality_section
    from noiselab.lattice import kernel_names

    q = quality_experiment(Config.quick_config())
    names = {r["method"] for r in q["image"]}
    assert names == {"spectral_noise (flat octave)"} | {f"{b} noise, {k}" for b in ("value", "gradient")
                                                         for k in kernel_names()}
    spectral = next(r for r in q["image"] if r["family"] == "spectral")
    assert spectral["outside"] < 1e-20 and spectral["period"] == 64
    # spectral_noise is scaled by its expected variance, so the mean variance over the seeds scatters about 1:
    # each independent cell's power is exponential (relative sd 1), so the mean over n cells and k seeds has
    # relative sd 1/sqrt(n k); allow 5 of those
    from noiselab.lab.quality import ULICHNEY_K

    f = np.hypot(*np.meshgrid(np.fft.fftfreq(64, 1 / 64), np.fft.rfftfreq(64, 1 / 64), indexing="ij"))  # cycles/frame
    cells = int(((f >= 4 / np.sqrt(2)) & (f <= 4 * np.sqrt(2))).sum())
    assert abs(spectral["variance_ratio"] - 1) < 5 / np.sqrt(cells * ULICHNEY_K)
    for r in q["image"]:
        if r["family"] == "lattice":
            assert r["period"] == 64 and r["within_bounds"] and r["outside"] > 0.05 and r["aliased"] > 0
            assert r["anisotropy"] > spectral["anisotropy"]
        assert all(np.isfinite(r[k]) for k in ("envelope_rms_db", "ulichney_db", "axis_excess", "striping"))
    # Cook & DeRose: slicing the band-limited spectral volume puts power under its band
    sv = next(r for r in q["volume"] if r["family"] == "spectral")
    assert sv["volume_below"] < 1e-20 and sv["slice_below"] > 0.1
    tent = next(r for r in q["motion"] if r["method"].startswith("tent IFFT, linear"))
    assert min(tent["tent_mean"]) > 0.999 and tent["off_envelope"] < 1e-9
    particles = next(r for r in q["motion"] if r["method"].startswith("particles"))
    assert max(particles["tent_mean"]) < 0.9
    md = quality_section({"quality": q})
    assert all(name in md for name in names) and "Cook & DeRose" in md
