"""Compositing (Eq. 3.6), the two-contrast stimuli (Eq. 6.1), and the snow command."""
import subprocess
import sys

import numpy as np
import pytest

from noiselab.cli import main
from noiselab.io import read_image, read_video, write_image, write_video
from noiselab.snowfall import composite, michelson_contrast, parallax_composite, snow
from noiselab.snowfall.background import default_background


def test_composite_equation_3_6_uint8_grey():
    a = np.array([[[0.0, 0.25, 0.5, 1.0]]], np.float32)
    bg = np.array([[40, 40, 40, 40]], np.uint8)
    out = composite(a, bg, intensity=250)
    assert out.dtype == np.uint8 and out.shape == (1, 1, 4)
    np.testing.assert_array_equal(out[0, 0], np.rint(250 * a[0, 0] + (1 - a[0, 0]) * 40).astype(np.uint8))


def test_composite_never_wraps_uint8():
    a = np.ones((2, 3, 3), np.float32)
    out = composite(a, np.full((3, 3), 255, np.uint8), intensity=255)
    assert np.all(out == 255)  # 255 + anything in uint8 arithmetic would wrap to small values
    out = composite(np.full((1, 2, 2), 0.5, np.float32), np.full((2, 2), 250, np.uint8), intensity=255)
    assert np.all(out == 252)  # 252.5 rounds to even, stays in range


def test_composite_rgb_broadcasts_alpha_over_colour():
    a = snow((3, 16, 16), rng=0)
    bg = np.zeros((16, 16, 3), np.uint8)
    bg[..., 0], bg[..., 1], bg[..., 2] = 10, 100, 200
    out = composite(a, bg)
    assert out.shape == (3, 16, 16, 3)
    for ch, level in enumerate((10, 100, 200)):
        expect = np.clip(np.rint(250 * a + (1 - a) * level), 0, 255)
        np.testing.assert_array_equal(out[..., ch], expect)


def test_composite_float_background_and_video_background():
    a = np.full((2, 4, 4), 0.5, np.float32)
    bg = np.zeros((2, 4, 4), np.float64)
    bg[1] = 1.0
    out = composite(a, bg, intensity=255)
    assert out.dtype == np.float32
    np.testing.assert_allclose(out[0], 0.5)
    np.testing.assert_allclose(out[1], 1.0)
    # a still alpha over a video background is applied to every frame
    vid = np.zeros((5, 4, 4, 3), np.uint8)
    out = composite(np.full((4, 4), 1.0, np.float32), vid, intensity=100)
    assert out.shape == (5, 4, 4, 3) and np.all(out == 100)


def test_composite_errors():
    a = np.zeros((2, 8, 8), np.float32)
    with pytest.raises(ValueError, match=r"background shape \(8, 9\) does not match the snow"):
        composite(a, np.zeros((8, 9), np.uint8))
    with pytest.raises(ValueError, match=r"background shape \(3, 8, 8\) does not match"):
        composite(a, np.zeros((3, 8, 8), np.uint8))
    with pytest.raises(ValueError, match="float background must lie in"):
        composite(a, np.full((8, 8), 200.0))
    with pytest.raises(ValueError, match="intensity must be in"):
        composite(a, np.zeros((8, 8), np.uint8), intensity=300)
    with pytest.raises(ValueError, match=r"alpha must lie in \[0, 1\]"):
        composite(a + 2, np.zeros((8, 8), np.uint8))
    with pytest.raises(ValueError, match="NaN"):
        composite(a * np.nan, np.zeros((8, 8), np.uint8))


def test_parallax_composite_michelson_contrasts_of_eq_6_1():
    fg = snow((4, 32, 32), rng=1, beta=1.0)          # spans exactly [0, 1]
    mask = np.zeros((32, 32), bool)
    mask[8:24, 8:24] = True
    video, contrast = parallax_composite(fg, mask)
    assert video.dtype == np.uint8 and video.shape == fg.shape
    # thesis 6.1.1: 1 in the clear region, 0.176 under the veil
    lo_c, hi_c = fg[:, ~mask].min(), fg[:, ~mask].max()
    assert contrast["clear"] == pytest.approx((hi_c - lo_c) / (hi_c + lo_c), rel=1e-5)
    lo_v, hi_v = 178.5 + 76.5 * fg[:, mask].min(), 178.5 + 76.5 * fg[:, mask].max()
    assert contrast["veiled"] == pytest.approx((hi_v - lo_v) / (hi_v + lo_v), rel=1e-5)
    # with the full [0, 1] range in both regions: exactly the thesis's 1 and 0.176
    full = np.zeros((1, 2, 2), np.float32)
    full[0, :, 1] = 1
    _, c = parallax_composite(full, np.array([[True, True], [False, False]]))
    assert c["clear"] == 1.0 and round(c["veiled"], 3) == 0.176
    assert round(michelson_contrast([0.7 * 255, 255]), 3) == 0.176
    # the veiled region really is 255*0.7 + 0.3*I_fg
    np.testing.assert_allclose(video[:, 8:24, 8:24], np.rint(178.5 + 0.3 * 255 * fg[:, 8:24, 8:24]), atol=1)
    # a different foreground under the veil (motion-inconsistent experiment)
    fg2 = snow((4, 32, 32), rng=1, beta=1.0, direction_yx=(0, 1))
    v2, _ = parallax_composite(fg, mask, veiled_foreground=fg2)
    np.testing.assert_array_equal(v2[:, 0:8], video[:, 0:8])
    assert not np.array_equal(v2[:, 8:24, 8:24], video[:, 8:24, 8:24])
    with pytest.raises(ValueError, match="mask shape"):
        parallax_composite(fg, np.zeros((16, 16), bool))


def test_default_background_is_rgb_landscape():
    img = default_background(48, 64)
    assert img.shape == (48, 64, 3) and img.dtype == np.uint8
    assert img[0].mean() < img[-1].mean()                # dark sky above, white snowy ground below
    assert np.array_equal(img, default_background(48, 64))


def test_cli_snow_writes_npy_and_says_where(tmp_path, capsys):
    out = tmp_path / "deep" / "er" / "snow.npy"
    rc = main(["snow", "--width", "32", "--height", "24", "--frames", "6", "--output", str(out), "--quiet"])
    assert rc == 0
    assert str(out) in capsys.readouterr().out
    video = np.load(out)
    assert video.shape == (6, 24, 32, 3) and video.dtype == np.uint8   # --frames 6: 6 frames (loops are for MP4)
    assert not np.array_equal(video[3], video[0])


def test_cli_snow_png_frames_and_alpha_only(tmp_path):
    out = tmp_path / "frames"
    assert main(["snow", "--width", "16", "--height", "16", "--frames", "3", "--loops", "1",
                 "--no-background", "--output", str(out), "--quiet"]) == 0
    files = sorted(out.iterdir())
    assert [f.name for f in files] == ["frame_00000.png", "frame_00001.png", "frame_00002.png"]
    alpha = snow((3, 16, 16), rng=0)
    np.testing.assert_array_equal(read_image(files[1]), np.rint(alpha[1] * 255).astype(np.uint8))


def test_cli_snow_over_image_and_video_backgrounds(tmp_path):
    img = tmp_path / "bg.png"
    write_image(img, np.full((20, 30, 3), 30, np.uint8))
    out = tmp_path / "a.npy"
    assert main(["snow", "--background", str(img), "--frames", "4", "--loops", "1", "--output", str(out), "--quiet"]) == 0
    assert np.load(out).shape == (4, 20, 30, 3)
    vid = tmp_path / "bg.npy"
    np.save(vid, np.zeros((9, 20, 30), np.uint8))
    out2 = tmp_path / "b.gif"
    assert main(["snow", "--background", str(vid), "--frames", "4", "--output", str(out2), "--quiet"]) == 0
    assert read_video(out2).shape[:3] == (9, 20, 30)  # the snow loops over the whole background video


def test_cli_snow_bad_input_is_a_one_line_error(tmp_path):
    img = tmp_path / "bg.png"
    write_image(img, np.zeros((20, 30), np.uint8))
    cases = [
        (["--c", "5"], "c (rad/frame) must be in"),
        (["--background", str(img), "--width", "64"], "is 30 x 20 px"),
        (["--background", str(tmp_path / "missing.png")], "no such"),
        (["--band", "4", "40", "--width", "32", "--height", "32"], "past the Nyquist"),
        (["--c", "3.0", "--width", "32", "--height", "32"], "Largest allowed --c"),
    ]
    for extra, msg in cases:
        proc = subprocess.run([sys.executable, "-m", "noiselab", "snow", "--frames", "2", "--output",
                               str(tmp_path / "x.npy"), *extra], capture_output=True, text=True)
        assert proc.returncode == 2, (extra, proc.stderr)
        assert msg in proc.stderr and "Traceback" not in proc.stderr
        assert not (tmp_path / "x.npy").exists()


def test_cli_tile_option(tmp_path):
    out = tmp_path / "t.npy"
    assert main(["snow", "--width", "40", "--height", "24", "--tile", "16", "--frames", "4", "--loops", "1",
                 "--no-background", "--output", str(out), "--quiet"]) == 0
    v = np.load(out)
    assert v.shape == (4, 24, 40)
    np.testing.assert_array_equal(v[:, :, :16], v[:, :, 16:32])  # 16 px tiles


def test_write_video_mp4_roundtrip_of_snow(tmp_path):
    # the quick start's format: an MP4 that reads back with the right shape
    out = tmp_path / "s.mp4"
    assert main(["snow", "--width", "32", "--height", "32", "--frames", "4", "--loops", "1",
                 "--output", str(out), "--quiet"]) == 0
    assert read_video(out).shape[:3] == (4, 32, 32)
    write_video(tmp_path / "x.gif", np.zeros((2, 8, 8), np.uint8))
