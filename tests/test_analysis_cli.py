"""``noiselab analyze``: the report's numbers, the figure, the JSON, and clear errors."""
import json
import re

import numpy as np
import pytest

from noiselab.cli import main
from noiselab.io import write_image, write_video

from test_analysis import band_texture, power_law_field


def _run(capsys, *argv):
    rc = main(["analyze", *map(str, argv)])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_report_of_a_1_over_f_image_gives_its_slope_and_isotropy(tmp_path, capsys):
    path = tmp_path / "pink.npy"
    np.save(path, power_law_field((256, 256), 1.0, seed=1).astype(np.float32))
    rc, out, _ = _run(capsys, path, "--band", 4, 64, "--json", tmp_path / "m.json")
    assert rc == 0
    slope = float(re.search(r"amplitude ([+-]\d+\.\d+)", out).group(1))
    assert abs(slope + 1) < 0.05
    aniso = float(re.search(r"anisotropy\s+(\d+\.\d+)", out).group(1))
    assert aniso < 0.05
    m = json.loads((tmp_path / "m.json").read_text())
    assert m["slope"]["band"] == [4, 64] and m["slope"]["amplitude"] == pytest.approx(slope, abs=1e-3)
    assert m["kind"] == "image" and "velocity" not in m


def test_png_grating_is_anisotropic_and_a_photo_like_crop_gets_a_hann_window(tmp_path, capsys):
    y, x = np.mgrid[:128, :128]
    write_image(tmp_path / "g.png", 0.5 + 0.4 * np.cos(2 * np.pi * (8 * x + 8 * y) / 128))
    rc, out, _ = _run(capsys, tmp_path / "g.png")
    assert rc == 0
    assert float(re.search(r"anisotropy\s+(\d+\.\d+)", out).group(1)) > 0.8
    assert float(re.search(r"Michelson (\d+\.\d+)", out).group(1)) == pytest.approx(0.8, abs=0.01)
    crop = power_law_field((512, 512), 2.0, seed=2)[:200, :200]
    np.save(tmp_path / "crop.npy", crop)
    rc, out, _ = _run(capsys, tmp_path / "crop.npy", "--band", 4, 50)
    assert "window        hann" in out and "does not tile" in out
    assert abs(float(re.search(r"amplitude ([+-]\d+\.\d+)", out).group(1)) + 2) < 0.2


@pytest.mark.parametrize("suffix", [".gif", ".npy"])
def test_video_report_gives_velocity_and_speed_per_band_and_plot(tmp_path, capsys, suffix):
    tex = band_texture(64, (3, 12), 3)
    tex = (tex - tex.min()) / (tex.max() - tex.min())
    video = np.stack([np.roll(tex, (t, -2 * t), axis=(0, 1)) for t in range(32)])  # vx = -2, vy = +1: loops
    path = tmp_path / f"v{suffix}"
    write_video(path, video, fps=10)
    plot = tmp_path / "fig.png"
    rc, out, _ = _run(capsys, path, "--plot", plot)
    assert rc == 0
    vx, vy = map(float, re.search(r"vx ([+-]\d+\.\d+)\s+vy ([+-]\d+\.\d+)", out).groups())
    assert vx == pytest.approx(-2, abs=0.05) and vy == pytest.approx(1, abs=0.05)
    rows = re.findall(r"^\s+\d+\.\d-\d+\.\d\s+([+-]\d+\.\d+)\s+([+-]\d+\.\d+)", out, re.M)
    assert len(rows) >= 3
    np.testing.assert_allclose(np.array(rows, float), [[-2, 1]] * len(rows), atol=0.1)
    assert float(re.search(r"loop seam\s+(\d+\.\d+)", out).group(1)) < 1.3
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([path.name, "fig.png"])


@pytest.mark.parametrize(
    "content, args, match",
    [
        (np.full((32, 32), np.nan), [], "NaN"),
        (np.ones((32, 32)), [], "constant"),
        (np.ones((2, 3, 8, 8, 8)), [], "5-D"),
        (np.random.default_rng(0).random((32, 32)), ["--band", "4", "40"], "Nyquist"),
        (np.random.default_rng(0).random((32, 32)), ["--as", "video"], "does not fit"),
        (np.random.default_rng(0).random((32, 32)), ["--plot", "fig.txt"], "--plot must end"),
    ],
)
def test_bad_input_is_a_one_line_error_with_status_2(tmp_path, capsys, content, args, match, monkeypatch):
    monkeypatch.chdir(tmp_path)
    np.save(tmp_path / "x.npy", content)
    rc, out, err = _run(capsys, tmp_path / "x.npy", *args)
    assert rc == 2
    assert re.search(match, err) and len(err.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.npy"]


def test_missing_and_unknown_files(tmp_path, capsys):
    rc, _, err = _run(capsys, tmp_path / "nope.png")
    assert rc == 2 and "no such" in err
    (tmp_path / "x.txt").write_text("hello")
    rc, _, err = _run(capsys, tmp_path / "x.txt")
    assert rc == 2 and "cannot analyse" in err


def test_a_still_video_and_a_tiny_image_are_reported_not_refused(tmp_path, capsys):
    frame = band_texture(32, (2, 8), 5)
    np.save(tmp_path / "still.npy", np.stack([frame] * 6))
    rc, out, _ = _run(capsys, tmp_path / "still.npy")
    assert rc == 0 and "loop seam     n/a (the frames do not change)" in out
    assert "velocity      n/a (the frames do not change)" in out
    np.save(tmp_path / "tiny.npy", np.random.default_rng(0).random((6, 6)))
    rc, out, _ = _run(capsys, tmp_path / "tiny.npy")
    assert rc == 0 and "1/f slope     n/a" in out


def test_report_gives_the_literature_measures(tmp_path, capsys):
    import noiselab

    # a tiled FFT field with stripes added: the period, the axis excess and Ulichney's dB must all show it
    field = noiselab.spectral_noise((64, 64), rng=3, dtype=np.float64)
    striped = np.tile(field, (1, 3)) + 2.0 * np.sin(2 * np.pi * np.arange(192) / 16)[None, :]
    np.save(tmp_path / "s.npy", striped)
    rc, out, _ = _run(capsys, tmp_path / "s.npy", "--json", tmp_path / "s.json")
    assert rc == 0
    assert "repeats every 64 samples" in out
    assert float(re.search(r"axis excess (\d+\.\d+)", out).group(1)) > 10
    assert float(re.search(r"Ulichney\s+([+-]\d+\.\d+) dB", out).group(1)) > 3
    q = json.loads((tmp_path / "s.json").read_text())["quality"]
    assert q["period_x"] == 64 and q["range"]["max"] == pytest.approx(float(striped.max()))
    # a band-limited volume: nothing outside its band, a quarter of its slices' power under it (Cook & DeRose)
    np.save(tmp_path / "v.npy", noiselab.spectral_noise((48, 48, 48), exponent=0.0, band=(6, 12), rng=4))
    rc, out, _ = _run(capsys, tmp_path / "v.npy", "--as", "volume", "--band", 6, 12, "--json", tmp_path / "v.json")
    sl = json.loads((tmp_path / "v.json").read_text())["quality"]["slice_leakage"]
    assert rc == 0 and sl["volume_outside"] < 1e-9 and 0.2 < sl["slice_outside"] < 0.3
    assert "2-D slices" in out


def test_default_band_of_band_limited_snow_is_found_and_reported(tmp_path, capsys):
    """Snow whose band is 12-48 cycles/frame, written to an 8-bit MP4: the default band is found from the
    power (not 2 to a quarter of the width over the compression floor), and the slope and anisotropy over it
    are those over the band given by hand."""
    video = tmp_path / "s.mp4"
    assert main(["snow", "--band", "12", "48", "--no-background", "--width", "128", "--height", "128",
                 "--frames", "16", "--quiet", "-o", str(video)]) == 0
    capsys.readouterr()
    rc, out, _ = _run(capsys, video, "--json", tmp_path / "m.json")
    assert rc == 0
    assert re.search(r"band\s+12-48 cycles/frame, found where the field has power", out), out
    m = json.loads((tmp_path / "m.json").read_text())
    assert m["band"]["band"] == [12, 48] and m["slope"]["band"] == [12, 48]
    assert abs(m["slope"]["amplitude"] + 1) < 0.1 and m["anisotropy"]["index"] < 0.05
    rc, given, _ = _run(capsys, video, "--band", 12, 48, "--json", tmp_path / "g.json")
    assert "band          12-48 cycles/frame, given (--band)" in given
    g = json.loads((tmp_path / "g.json").read_text())
    assert g["slope"]["amplitude"] == m["slope"]["amplitude"] and g["anisotropy"]["index"] == m["anisotropy"]["index"]


def test_default_band_of_band_limited_noise_and_of_full_band_1_over_f(tmp_path, capsys):
    import noiselab

    np.save(tmp_path / "b.npy", noiselab.spectral_noise((256, 256), exponent=1.0, band=(16, 80), rng=2))
    rc, out, _ = _run(capsys, tmp_path / "b.npy", "--json", tmp_path / "b.json")
    m = json.loads((tmp_path / "b.json").read_text())
    assert rc == 0 and m["band"]["band"] == [16, 80] and abs(m["slope"]["amplitude"] + 1) < 0.05, out
    # 1/f with no band limit keeps the default band, and says so
    np.save(tmp_path / "p.npy", power_law_field((256, 256), 1.0, seed=1).astype(np.float32))
    rc, out, _ = _run(capsys, tmp_path / "p.npy", "--json", tmp_path / "p.json")
    m = json.loads((tmp_path / "p.json").read_text())
    assert rc == 0 and m["band"]["band"] == [2, 64] and "the power has no band edge" in out
    assert abs(m["slope"]["amplitude"] + 1) < 0.05
