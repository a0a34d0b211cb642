"""Atomic writing and the media helpers shared by every command."""
import numpy as np
import pytest

from noiselab.io import atomic_output, read_image, read_video, to_uint8, write_image, write_video


def test_atomic_output_leaves_nothing_when_writer_fails(tmp_path):
    target = tmp_path / "out.npy"
    with pytest.raises(RuntimeError):
        with atomic_output(target) as tmp:
            np.save(tmp, np.zeros(3))
            raise RuntimeError("boom")
    assert list(tmp_path.iterdir()) == []


def test_atomic_output_keeps_previous_file_on_failure(tmp_path):
    target = tmp_path / "out.npy"
    np.save(target, np.arange(3))
    with pytest.raises(RuntimeError):
        with atomic_output(target) as tmp:
            np.save(tmp, np.zeros(5))
            raise RuntimeError("boom")
    np.testing.assert_array_equal(np.load(target), np.arange(3))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.npy"]


def test_failed_video_write_leaves_no_file(tmp_path):
    def frames():
        yield np.zeros((8, 8), np.float32)
        raise RuntimeError("renderer failed mid-way")

    with pytest.raises(RuntimeError):
        write_video(tmp_path / "v.mp4", frames())
    assert list(tmp_path.iterdir()) == []


def test_to_uint8_maps_unit_interval_and_rejects_nan():
    # floats outside [0, 1] with no stated range are refused (they were clipped silently); clip=True
    # or a stated range clips, as asked
    out = to_uint8(np.array([0.0, 0.5, 1.0, 1.5, -1.0]), clip=True)
    np.testing.assert_array_equal(out, [0, 128, 255, 255, 0])
    np.testing.assert_array_equal(to_uint8(np.array([0.0, 0.5, 1.0, 1.5, -1.0]), vmin=0, vmax=1), [0, 128, 255, 255, 0])
    with pytest.raises(ValueError, match=r"float values must lie in \[0, 1\].*40 % of the values outside.*vmin/vmax"):
        to_uint8(np.array([0.0, 0.5, 1.0, 1.5, -1.0]))
    with pytest.raises(ValueError, match=r"must lie in \[0, 1\]"):
        write_image("never_written.png", np.random.default_rng(0).standard_normal((8, 8)))
    np.testing.assert_array_equal(to_uint8(np.array([1.0000001, -1e-7], np.float32)), [255, 0])  # float32 rounding
    with pytest.raises(ValueError, match="NaN"):
        to_uint8(np.array([np.nan]))
    with pytest.raises(ValueError, match=r"\[0, 255\]"):
        to_uint8(np.array([300]))


@pytest.mark.parametrize("suffix", [".gif", ".mp4", ".mkv", ".npy", ""])
def test_video_round_trip_preserves_shape_and_content(tmp_path, suffix):
    t = np.linspace(0, 1, 6, dtype=np.float32)[:, None, None]
    x = np.linspace(0, 1, 24, dtype=np.float32)[None, None, :]
    video = np.broadcast_to(0.2 + 0.6 * ((x + t) % 1.0), (6, 16, 24)).copy()
    path = write_video(tmp_path / f"v{suffix}", video, fps=10)
    back = read_video(path, as_float=True)
    assert back.shape == video.shape
    tol = 0.06 if suffix == ".mp4" else 1 / 255 + 1e-6
    if suffix == ".npy":
        tol = 0
    assert np.abs(back - video).max() <= tol


@pytest.mark.parametrize("suffix, kw", [(".mkv", {}), (".mp4", {"lossless": True})])
@pytest.mark.parametrize("shape", [(4, 17, 23), (3, 16, 16, 3)])
def test_lossless_video_keeps_every_grey_level(tmp_path, suffix, kw, shape):
    video = np.random.default_rng(1).integers(0, 256, shape).astype(np.uint8)
    back = read_video(write_video(tmp_path / f"v{suffix}", video, **kw))
    np.testing.assert_array_equal(back, video)


def test_image_round_trip_and_bad_suffix(tmp_path):
    img = (np.arange(12 * 10 * 3) % 256).astype(np.uint8).reshape(12, 10, 3)
    write_image(tmp_path / "a.png", img)
    np.testing.assert_array_equal(read_image(tmp_path / "a.png"), img)
    with pytest.raises(ValueError, match="must end in"):
        write_image(tmp_path / "a.xyz", img)


def test_atomic_output_gives_ordinary_permissions(tmp_path):
    import os
    import stat

    umask = os.umask(0o022)
    try:
        with atomic_output(tmp_path / "a.npy") as tmp:
            np.save(tmp, np.zeros(2))
        mode = stat.S_IMODE(os.stat(tmp_path / "a.npy").st_mode)
    finally:
        os.umask(umask)
    assert mode == 0o644


def test_write_zarr_of_a_numpy_array_needs_neither_dask_nor_the_scale_layer(tmp_path):
    # io is a leaf below every layer: writing a numpy array loads zarr only (in a fresh interpreter)
    import json
    import subprocess
    import sys
    import textwrap

    code = textwrap.dedent(f"""
        import json, sys
        import numpy as np
        import zarr
        from noiselab.io import write_zarr
        out = write_zarr({str(tmp_path / "n.zarr")!r}, np.arange(12, dtype="f4").reshape(3, 4), dims=("y", "x"),
                         coords={{"x": np.arange(4) / 2}}, units="m", rng=3, params={{"k": np.int64(2)}},
                         chunks=(2, -1))
        arr = zarr.open_group(str(out), mode="r")["data"]
        print(json.dumps({{"loaded": sorted(m for m in sys.modules if m.split(".")[0] == "dask"
                                           or m.startswith("noiselab.scale") or m == "distributed"),
                          "data": arr[:].tolist(), "chunks": list(arr.chunks), "attrs": dict(arr.attrs),
                          "dims": list(arr.metadata.dimension_names)}}))
    """)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    got = json.loads(proc.stdout)
    assert got["loaded"] == []
    assert got["data"] == np.arange(12.0).reshape(3, 4).tolist() and got["chunks"] == [2, 4]
    assert got["dims"] == ["y", "x"] and got["attrs"]["units"] == "m" and got["attrs"]["seed"] == 3
    assert got["attrs"]["params"] == {"k": 2}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["n.zarr"]


def test_write_zarr_of_a_numpy_array_checks_before_writing(tmp_path):
    from noiselab.io import read_zarr, write_zarr

    for bad in (0, (2,), (2, 0), (2, 2.5), True):
        with pytest.raises(ValueError, match="chunks must be"):
            write_zarr(tmp_path / "c.zarr", np.zeros((3, 4)), chunks=bad)
    with pytest.raises(TypeError, match="real numeric array"):
        write_zarr(tmp_path / "c.zarr", np.array(["a", "b"]))
    with pytest.raises(ValueError, match=r"coords\['x'\] must be 1-D of length 4"):
        write_zarr(tmp_path / "c.zarr", np.zeros((3, 4)), dims=("y", "x"), coords={"x": np.arange(3)})
    with pytest.raises(ValueError, match="name must be a non-empty string"):
        write_zarr(tmp_path / "c.zarr", np.zeros(3), name="a/b")
    assert list(tmp_path.iterdir()) == []
    # a chunk larger than the axis is clipped to it; -1 is the whole axis
    out = write_zarr(tmp_path / "c.zarr", np.arange(6.0).reshape(2, 3), chunks=(5, -1))
    back = read_zarr(out)
    assert back.chunksize == (2, 3) and np.array_equal(back.compute(), np.arange(6.0).reshape(2, 3))


def test_a_removed_temporary_folder_stays_removed_while_threads_still_write_into_it(tmp_path):
    # a chunked run's threads keep writing chunks (making missing parents, as a zarr store does)
    # after the signal handler removed the folder: the file at its name makes every such write fail
    import threading

    from noiselab.io.atomic import remove_and_block

    folder = tmp_path / ".out.zarr.x.spill.tmp"
    folder.mkdir()
    started, errors, writes = threading.Event(), [], [0]

    def writer():
        k = 0
        while True:
            try:
                (folder / "c" / str(k % 7)).mkdir(parents=True, exist_ok=True)
                (folder / "c" / str(k % 7) / "0").write_bytes(b"chunk")
            except OSError as exc:
                errors.append(exc)
                return
            writes[0] += 1
            k += 1
            started.set()

    thread = threading.Thread(target=writer)
    thread.start()
    assert started.wait(10)
    assert remove_and_block(folder) == [folder]
    thread.join(10)
    assert not thread.is_alive() and errors  # the writer failed on the file, it did not rebuild the folder
    assert folder.is_file() and [p.name for p in tmp_path.iterdir()] == [folder.name]
    folder.unlink()


def _ffmpeg_decode(path, pix_fmt, shape, *flags):
    """ffmpeg's own decode of a video file to raw ``pix_fmt`` frames (the reference the reader must match)."""
    import subprocess

    import imageio_ffmpeg

    out = subprocess.run([imageio_ffmpeg.get_ffmpeg_exe(), "-v", "error", "-i", str(path), *flags, "-f", "rawvideo",
                          "-pix_fmt", pix_fmt, "-"], capture_output=True, check=True).stdout
    dtype = np.dtype("<u2") if pix_fmt == "rgb48le" else np.uint8
    return np.frombuffer(out, dtype).reshape(shape)


@pytest.mark.parametrize("content", ["ramp", "noise"])
def test_lossy_mp4_reads_back_as_ffmpegs_own_grey_decode(tmp_path, content):
    from noiselab.io import read_video

    T, H, W = 6, 48, 256
    if content == "ramp":
        video = np.broadcast_to(np.arange(256, dtype=np.uint8), (T, H, W)).copy()
    else:
        video = np.random.default_rng(3).integers(0, 256, (T, H, W), dtype=np.uint8)
    path = write_video(tmp_path / "v.mp4", video, fps=25)   # H.264 yuv420p: lossy
    read = read_video(path).astype(np.float64)
    grey = _ffmpeg_decode(path, "gray", (T, H, W)).astype(np.float64)
    assert read.shape == (T, H, W)
    assert abs(np.mean(read - grey)) <= 0.05 and np.mean(np.abs(read - grey)) <= 0.05   # grey levels
    assert np.mean(grey != video) > 0.1   # (the codec does change values: the comparison is not trivial)


def test_lossy_colour_mp4_reads_back_without_bias(tmp_path):
    from noiselab.io import read_video

    T, H, W = 4, 32, 64
    rng = np.random.default_rng(4)
    video = (np.linspace(0, 255, W)[None, None, :, None] * np.array([1.0, 0.6, 0.3]) + rng.normal(0, 20, (T, H, W, 3)))
    video = np.clip(video, 0, 255).astype(np.uint8)
    path = write_video(tmp_path / "c.mp4", video, fps=25)
    read = read_video(path).astype(np.float64)
    # the reference: the decoder's own Y'CbCr 4:2:0 planes, converted here in float64 (BT.601, limited range,
    # each chroma sample held over its 2 x 2 pixels); the reader interpolates chroma, so single pixels differ,
    # but its conversion must add no bias
    planes = _ffmpeg_decode(path, "yuv420p", (T, H * W * 3 // 2)).astype(np.float64)
    y = (planes[:, :H * W].reshape(T, H, W) - 16) * 255 / 219

    def chroma(a, b):
        return ((planes[:, a:b].reshape(T, H // 2, W // 2) - 128) * 255 / 224).repeat(2, 1).repeat(2, 2)

    u, v = chroma(H * W, H * W * 5 // 4), chroma(H * W * 5 // 4, H * W * 3 // 2)
    exact = np.clip(np.stack([y + 1.402 * v, y - 0.344136 * u - 0.714136 * v, y + 1.772 * u], axis=-1), 0, 255)
    assert read.shape == (T, H, W, 3)
    assert np.all(np.abs(np.mean(read - exact, axis=(0, 1, 2))) <= 0.05), np.mean(read - exact, axis=(0, 1, 2))
