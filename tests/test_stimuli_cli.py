"""``noiselab stimulus``: physical units in, display values and a JSON sidecar out."""
from __future__ import annotations

import json

import numpy as np
import pytest

from noiselab import Display, analysis
from noiselab.cli import main
from noiselab.io import read_image, read_video


def _run(tmp_path, *argv):
    return main(["stimulus", *argv])


@pytest.mark.parametrize("argv, suffix", [
    (["pink", "--size", "4", "--band", "0.5", "8"], ".png"),
    (["bandpass", "--size", "4", "--sf", "4", "--orientation", "45", "--orientation-bandwidth", "15"], ".npy"),
    (["snow", "--size", "2", "--duration", "0.15"], ".mkv"),
    (["cloud", "--size", "2", "--duration", "0.15", "--velocity", "2", "0"], ".npy"),
])
def test_stimulus_kinds_write_values_and_sidecar(tmp_path, argv, suffix, capsys):
    out = tmp_path / f"s{suffix}"
    assert _run(tmp_path, *argv, "--mean", "30", "--contrast", "0.15", "--seed", "3", "-o", str(out)) == 0
    side = json.loads((tmp_path / f"s{suffix}.json").read_text())
    assert side["seed"] == 3 and side["kind"] == argv[0] and side["noiselab_version"]
    assert side["display"] == Display(32.0).as_dict()
    assert side["parameters"]["mean"] == 30.0 and side["output"]["lossless"] is True
    values = read_video(out) if suffix == ".mkv" else read_image(out)
    L = Display(32.0).luminance_of(values)
    assert L.mean() == pytest.approx(30.0, rel=0.01)
    assert analysis.rms_contrast(L) == pytest.approx(0.15, rel=0.02)
    assert side["measured_on_written_values"]["rms_contrast"] == pytest.approx(analysis.rms_contrast(L), rel=1e-9)
    n = Display(32.0).pixels(float(argv[argv.index("--size") + 1]))
    assert values.shape[-2:] == (n, n)


def test_stimulus_is_repeatable_and_cloud_moves_at_the_stated_speed(tmp_path):
    a, b = tmp_path / "a.npy", tmp_path / "b.npy"
    args = ["cloud", "--size", "2", "--duration", "0.5", "--velocity", "1.875", "-0.9375", "--speed-bandwidth",
            "0.05", "--sf", "4", "--sf-bandwidth", "1", "--frame-rate", "60", "--bits", "10"]
    assert _run(tmp_path, *args, "-o", str(a)) == 0 and _run(tmp_path, *args, "-o", str(b)) == 0
    va, vb = np.load(a), np.load(b)
    assert va.dtype == np.uint16 and np.array_equal(va, vb)
    v = analysis.best_velocity(Display(32.0, bits=10).luminance_of(va))
    assert np.allclose(v, [1.875 * 32 / 60, -0.9375 * 32 / 60], atol=0.05)   # deg/s -> px/frame


def test_phase_scrambled_image(tmp_path):
    img = tmp_path / "img.npy"
    np.save(img, np.random.default_rng(0).random((64, 48)))
    out = tmp_path / "s.png"
    assert _run(tmp_path, "scramble", "--image", str(img), "--contrast-kind", "michelson", "--contrast", "0.5",
                "-o", str(out)) == 0
    L = Display(32.0).luminance_of(read_image(out))
    assert L.shape == (64, 48) and analysis.michelson_contrast(L) == pytest.approx(0.5, rel=0.02)


@pytest.mark.parametrize("argv, words", [
    (["pink", "--mean", "90", "--contrast", "0.5"], "largest rms contrast that fits"),
    (["pink", "--bits", "17"], "bits must be an int in [1, 16]"),
    (["snow", "-o", "x.png"], "a PNG holds one frame"),
    (["scramble"], "scramble needs --image"),
    (["pink", "-o", "x.tif"], "output must end in .png, .mkv, .mp4 or .npy"),
    (["pink", "--contrast-kind", "michelson", "--contrast", "1.5"], "contrast (Michelson) must be in (0, 1]"),
    (["cloud", "--bits", "10", "--duration", "0.1", "--size", "1", "-o", "x.mkv"], "videos hold 8-bit values"),
])
def test_stimulus_errors_are_one_line_and_exit_2(tmp_path, argv, words, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert _run(tmp_path, *argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("noiselab stimulus: error: ") and words in err and err.count("\n") == 1


def test_clip_flag_fits_a_gaussian_patch_and_records_the_clipped_fraction(tmp_path, capsys):
    out = tmp_path / "p.npy"
    args = ["pink", "--size", "8", "--mean", "50", "--contrast", "0.25", "--seed", "2", "-o", str(out)]
    assert _run(tmp_path, *args) == 2
    err = capsys.readouterr().err
    assert "--clip " in err and "% of the samples" in err and err.count("\n") == 1
    assert _run(tmp_path, *args, "--clip", "3") == 0
    side = json.loads((tmp_path / "p.npy.json").read_text())
    m = side["measured_on_written_values"]
    L = Display(32.0).luminance_of(np.load(out))
    assert m["clip_sd"] == 3.0 and side["parameters"]["clip"] == 3.0
    assert 0.0 < m["clipped_fraction"] < 0.01
    assert m["rms_contrast"] == pytest.approx(0.25, rel=0.02) and analysis.rms_contrast(L) == pytest.approx(
        0.25, rel=0.02)


@pytest.mark.parametrize("aperture, extra", [("circle", []), ("raised-cosine", ["--ramp", "0.5"]),
                                             ("gaussian", ["--aperture-sigma", "0.5"])])
def test_aperture_flag_blends_to_the_mean_and_records_the_window(tmp_path, aperture, extra):
    out = tmp_path / "a.npy"
    assert _run(tmp_path, "bandpass", "--size", "4", "--aperture", aperture, "--aperture-diameter", "3", *extra,
                "--mean", "30", "--contrast", "0.2", "--bits", "10", "--no-dither", "-o", str(out)) == 0
    side = json.loads((tmp_path / "a.npy.json").read_text())
    assert side["aperture"]["kind"] == aperture
    d = Display(32.0, bits=10)
    L = d.luminance_of(np.load(out))
    n = L.shape[0]
    r = np.hypot(*(np.mgrid[:n, :n] - (n - 1) / 2.0)) / 32.0
    far = r >= (1.5 if aperture != "gaussian" else 1.9)   # past the edge, or 3.8 sigma out
    assert np.ptp(L[far]) < 0.15 and abs(L[far].mean() - 30.0) < 0.15   # the mean luminance (one 10-bit value)
    m = side["measured_on_written_values"]["in_aperture"]
    assert m["rms_contrast"] == pytest.approx(0.2, rel=0.05) and m["mean_cd_m2"] == pytest.approx(30.0, rel=0.02)
    if aperture == "circle":
        assert analysis.rms_contrast(L[r <= 1.45]) == pytest.approx(0.2, rel=0.03)


def test_bandwidths_in_octaves_and_hwhm_degrees(tmp_path):
    from noiselab.stimuli import B_sf_from_octaves, B_theta_from_hwhm

    out = tmp_path / "b.npy"
    assert _run(tmp_path, "bandpass", "--size", "4", "--sf", "4", "--sf-bandwidth-octaves", "1", "--orientation",
                "30", "--orientation-hwhm", "10", "-o", str(out)) == 0
    used = json.loads((tmp_path / "b.npy.json").read_text())["pixel_units"]
    assert used["B_sf"] == pytest.approx(B_sf_from_octaves(sf_0=4.0, sf_bandwidth_octaves=1.0) / 32.0, rel=1e-12)
    assert used["B_theta"] == pytest.approx(B_theta_from_hwhm(orientation_hwhm_deg=10.0), rel=1e-12)
    # the stripes' wave vector at 30 deg (y down), measured on the written values
    z = np.load(out).astype(float)
    p = np.abs(np.fft.fft2(z - z.mean())) ** 2
    fy, fx = np.meshgrid(np.fft.fftfreq(z.shape[0]), np.fft.fftfreq(z.shape[1]), indexing="ij")
    mean = np.degrees(0.5 * np.angle(np.sum(p * np.exp(2j * np.arctan2(fy, fx))))) % 180.0
    assert mean == pytest.approx(30.0, abs=3.0)
    assert _run(tmp_path, "bandpass", "--orientation-hwhm", "10", "--orientation-bandwidth", "5", "-o",
                str(out)) == 2


def test_trials_write_distinct_reproducible_stimuli_and_one_manifest(tmp_path, capsys):
    from noiselab.stimuli import trial_seeds

    out = tmp_path / "t" / "pink.npy"
    args = ["pink", "--size", "2", "--mean", "50", "--contrast", "0.25", "--clip", "3", "--seed", "7"]
    assert _run(tmp_path, *args, "--trials", "3", "-o", str(out)) == 0
    manifest = json.loads((tmp_path / "t" / "pink_manifest.json").read_text())
    seeds = [t["seed"] for t in manifest["trials"]]
    # the manifest's seeds are the API's, and numpy's SeedSequence derivation it documents
    assert seeds == trial_seeds(3, rng=7) and len(set(seeds)) == 3 and manifest["experiment_seed"] == 7
    assert seeds == [int(c.generate_state(1)[0]) for c in np.random.SeedSequence(7).spawn(3)]
    assert manifest["display"] == Display(32.0).as_dict() and manifest["parameters"]["contrast"] == 0.25
    files = [tmp_path / "t" / t["file"] for t in manifest["trials"]]
    assert [f.name for f in files] == ["pink_000.npy", "pink_001.npy", "pink_002.npy"]
    values = [np.load(f) for f in files]
    assert not np.array_equal(values[0], values[1]) and not np.array_equal(values[1], values[2])
    for t, v in zip(manifest["trials"], values):
        L = Display(32.0).luminance_of(v)
        m = t["measured_on_written_values"]
        assert m["rms_contrast"] == pytest.approx(analysis.rms_contrast(L), rel=1e-12)
        assert m["rms_contrast"] == pytest.approx(0.25, rel=0.03)
        assert m["luminance_range_cd_m2"] == [L.min(), L.max()] and 0 < m["clipped_fraction"] < 0.02
    # a trial on its own: the same command with its recorded seed, without --trials, gives the same values
    one = tmp_path / "one.npy"
    assert _run(tmp_path, *args[:-1], str(seeds[1]), "-o", str(one)) == 0
    assert np.array_equal(np.load(one), values[1])
    # the same experiment seed makes the same set again
    again = tmp_path / "again" / "pink.npy"
    assert _run(tmp_path, *args, "--trials", "3", "-o", str(again)) == 0
    assert np.array_equal(np.load(tmp_path / "again" / "pink_002.npy"), values[2])
    capsys.readouterr()
    assert _run(tmp_path, *args, "--trials", "0", "-o", str(out)) == 2
    assert "--trials must be an int in [1, 100000]" in capsys.readouterr().err


def test_psychopy_output_is_luminance_in_minus_one_to_one(tmp_path):
    out = tmp_path / "s.png"
    assert _run(tmp_path, "pink", "--size", "2", "--luminance", "2", "120", "--mean", "40", "--psychopy",
                "-o", str(out)) == 0
    side = json.loads((tmp_path / "s.png.json").read_text())
    pp = np.load(tmp_path / side["output"]["psychopy"])
    d = Display(32.0, luminance=(2.0, 120.0))
    L = d.luminance_of(read_image(out))
    assert pp.dtype == np.float32 and pp.shape == L.shape and -1 <= pp.min() and pp.max() <= 1
    # -1 is L_min and 1 is L_max, linear in cd/m² between
    assert np.allclose(2.0 + (pp + 1.0) / 2.0 * 118.0, L, rtol=0, atol=1e-4)
    assert np.mean(pp) == pytest.approx(2.0 * (40.0 - 2.0) / 118.0 - 1.0, abs=0.01)
