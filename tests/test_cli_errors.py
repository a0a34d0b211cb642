"""The command line never shows a traceback for a user's mistake or the machine's state.

Every case: one line on stderr naming the file and the cause, exit status 2,
and nothing left behind (no partial output, no temporary file).
"""
import errno
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import pytest

from noiselab.cli import main
from noiselab.io import write_image, write_video
from noiselab.io.errors import OutputError, describe, input_error, output_error


def _one_line_error(capsys, rc, *needles):
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert rc == 2, err
    assert len(lines) == 1, err
    assert "Traceback" not in err
    for needle in needles:
        assert needle in lines[0], lines[0]
    return lines[0]


def _listing(folder):
    return sorted(str(p.relative_to(folder)) for p in Path(folder).rglob("*"))


# ----------------------------------------------------------------------------- inputs

def _bad_inputs(d):
    """name -> path of each kind of corrupt input noiselab refuses."""
    d.mkdir(exist_ok=True)
    rng = np.random.default_rng(0)
    write_image(d / "good.png", rng.random((32, 32)))
    png = (d / "good.png").read_bytes()
    write_video(d / "good.gif", rng.random((4, 16, 16)))
    gif = (d / "good.gif").read_bytes()
    write_video(d / "good.mp4", rng.random((8, 16, 16)))
    mp4 = (d / "good.mp4").read_bytes()
    cases = {
        "truncated.png": png[: len(png) // 2], "zero.png": b"", "text.png": b"not an image\n",
        "truncated.gif": gif[: len(gif) // 2], "truncated.mp4": mp4[: len(mp4) // 2], "zero.mp4": b"",
        "zero.npy": b"", "text.npy": b"hello\n",
    }
    paths = {}
    for name, data in cases.items():
        (d / name).write_bytes(data)
        paths[name] = d / name
    frames = d / "frames"
    frames.mkdir(exist_ok=True)
    write_image(frames / "frame_00000.png", rng.random((16, 16)))
    (frames / "frame_00001.png").write_bytes(png[:40])
    paths["frames"] = frames
    return paths


BAD = ["truncated.png", "zero.png", "text.png", "truncated.gif", "truncated.mp4", "zero.mp4", "zero.npy", "text.npy",
       "frames"]


@pytest.mark.parametrize("name", BAD)
def test_analyze_of_a_corrupt_input_is_one_line(tmp_path, capsys, name):
    path = _bad_inputs(tmp_path / "in")[name]
    out = tmp_path / "out"
    out.mkdir()
    rc = main(["analyze", str(path), "--json", str(out / "m.json"), "--plot", str(out / "m.png")])
    line = _one_line_error(capsys, rc, "cannot read", path.name if name != "frames" else "frame_00001.png")
    assert _listing(out) == []
    assert "noiselab analyze: error:" in line


@pytest.mark.parametrize("name", BAD)
def test_snow_over_a_corrupt_background_is_one_line(tmp_path, capsys, name):
    path = _bad_inputs(tmp_path / "in")[name]
    out = tmp_path / "out"
    out.mkdir()
    rc = main(["snow", "--background", str(path), "--frames", "4", "--output", str(out / "s.gif")])
    _one_line_error(capsys, rc, "cannot read", path.name if name != "frames" else "frame_00001.png")
    assert _listing(out) == []


def test_snow_over_a_video_background_with_four_channels_is_one_line_before_rendering(tmp_path, capsys):
    path = tmp_path / "rgba.npy"
    np.save(path, np.zeros((3, 16, 16, 4), np.uint8))
    rc = main(["snow", "--background", str(path), "--frames", "4", "--output", str(tmp_path / "out" / "s.gif")])
    _one_line_error(capsys, rc, "rgba.npy", "4 channels per pixel", "grey or RGB")
    assert _listing(tmp_path / "out") == []


def test_an_input_without_read_permission_is_one_line(tmp_path, capsys, monkeypatch):
    """Root reads any file, so the denial is raised where noiselab opens the file."""
    import noiselab.io.media as media

    path = _bad_inputs(tmp_path / "in")["zero.png"].with_name("good.png")

    def denied(file, *args, **kwargs):
        raise PermissionError(errno.EACCES, "Permission denied", str(file))

    monkeypatch.setattr(media, "open", denied, raising=False)
    rc = main(["analyze", str(path)])
    _one_line_error(capsys, rc, "cannot read", "good.png", "permission denied")
    rc = main(["snow", "--background", str(path), "--frames", "2", "--output", str(tmp_path / "s.gif")])
    _one_line_error(capsys, rc, "good.png", "permission denied")
    assert not (tmp_path / "s.gif").exists()


def test_error_mapping_names_the_file_and_the_cause():
    assert str(input_error("a.png", PermissionError(errno.EACCES, "Permission denied"))) == \
        "cannot read 'a.png': permission denied"
    for code in (errno.ENOSPC, errno.EROFS, errno.EACCES, errno.EDQUOT):
        e = output_error("out/v.mp4", OSError(code, os.strerror(code), "/tmp/.v.123.tmp.mp4"))
        assert isinstance(e, OutputError) and e.errno == code
        assert str(e) == f"cannot write 'out/v.mp4': {os.strerror(code)}"   # the target, not the temporary name
    # a tool that reports the OS error only in its text (ffmpeg, Pillow): the cause is still found
    e = output_error("a.mp4", RuntimeError("[out#0/mp4] Error writing trailer: No space left on device"))
    assert str(e) == "cannot write 'a.mp4': No space left on device" and e.errno == errno.ENOSPC
    assert describe(PermissionError(errno.EACCES, "Permission denied", "x/y.png")) == "'x/y.png': Permission denied"
    assert "\n" not in describe(ValueError("first\nsecond"))


def test_mesh_input_trimesh_cannot_read_is_one_line(tmp_path, capsys):
    bad = tmp_path / "model.ply"
    bad.write_text("this is not a ply file\n")
    rc = main(["mesh", "-i", str(bad), "-o", str(tmp_path / "out.ply")])
    _one_line_error(capsys, rc, "cannot read", "model.ply")
    empty = tmp_path / "empty.obj"
    empty.write_bytes(b"")
    rc = main(["mesh", "-i", str(empty), "-o", str(tmp_path / "out.ply")])
    _one_line_error(capsys, rc, "empty.obj", "empty")
    assert not (tmp_path / "out.ply").exists()


@pytest.mark.parametrize("size", ["10x", "x10", "10xx10", "ten", "10x0"])
def test_noise_size_must_be_whole(tmp_path, capsys, size):
    rc = main(["noise", "--size", size, "-o", str(tmp_path / "n.png")])
    _one_line_error(capsys, rc, "--size")
    assert _listing(tmp_path) == []


@pytest.mark.parametrize("shape", [(0,), (0, 5), (3, 0, 4)])
def test_analyze_of_an_empty_array_is_one_clear_line(tmp_path, capsys, shape):
    np.save(tmp_path / "e.npy", np.zeros(shape, np.float32))
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")   # not numpy's warnings either
        rc = main(["analyze", str(tmp_path / "e.npy")])
    _one_line_error(capsys, rc, "e.npy", "empty array", str(shape).replace(",)", ",)"))


# ----------------------------------------------------------------------------- outputs

def _commands(tmp_path, out):
    """Each subcommand writing `out` (suffix chosen per command); small and fast."""
    src = tmp_path / "src.npy"
    np.save(src, np.random.default_rng(0).random((32, 32)).astype(np.float32))
    return {
        "noise-png": ["noise", "--size", "32", "-o", f"{out}.png"],
        "noise-npy": ["noise", "--size", "32", "-o", f"{out}.npy"],
        "noise-mp4": ["noise", "--dims", "3", "--size", "4x16x16", "-o", f"{out}.mp4"],
        "snow-gif": ["snow", "--frames", "4", "--width", "32", "--height", "32", "-o", f"{out}.gif"],
        "snow-mp4": ["snow", "--frames", "4", "--width", "32", "--height", "32", "-o", f"{out}.mp4"],
        "snow-npy": ["snow", "--frames", "4", "--width", "32", "--height", "32", "--no-background", "-o", f"{out}.npy"],
        "mesh-ply": ["mesh", "--shape", "sphere", "--subdivisions", "1", "--resolution", "ignore", "-o", f"{out}.ply"],
        "mesh-render": ["mesh", "--shape", "sphere", "--subdivisions", "1", "--resolution", "ignore", "--size", "32",
                        "--render", f"{out}.png"],
        "analyze-json": ["analyze", str(src), "--json", f"{out}.json"],
        "analyze-plot": ["analyze", str(src), "--plot", f"{out}.png"],
        "bench": ["bench", "--quick", "--dry-run", "--no-peers", "--output", f"{out}"],
    }


CMDS = ["noise-png", "noise-npy", "noise-mp4", "snow-gif", "snow-mp4", "snow-npy", "mesh-ply", "mesh-render",
        "analyze-json", "analyze-plot"]


@pytest.mark.parametrize("cmd", CMDS + ["bench"])
def test_output_whose_parent_is_a_regular_file(tmp_path, capsys, cmd):
    (tmp_path / "afile").write_text("x")
    args = _commands(tmp_path, tmp_path / "afile" / "sub" / "o")[cmd]
    rc = main(args)
    _one_line_error(capsys, rc, "cannot write", "afile", "is a file, not a folder")
    assert (tmp_path / "afile").read_text() == "x"


@pytest.mark.parametrize("cmd", CMDS)
def test_output_that_is_an_existing_folder(tmp_path, capsys, cmd):
    args = _commands(tmp_path, tmp_path / "o")[cmd]
    target = Path(args[-1])
    target.mkdir()
    (target / "keep").write_text("k")
    rc = main(args)
    _one_line_error(capsys, rc, "cannot write", target.name, "existing folder")
    assert _listing(target) == ["keep"]


def test_gallery_and_frames_folder_outputs_refuse_a_file(tmp_path, capsys):
    (tmp_path / "g").write_text("x")
    rc = main(["gallery", "--quick", "--only", "lab", "--out", str(tmp_path / "g")])
    _one_line_error(capsys, rc, "cannot write", "existing file")
    rc = main(["snow", "--frames", "2", "--width", "16", "--height", "16", "-o", str(tmp_path / "g")])
    _one_line_error(capsys, rc, "cannot write", "existing file, not a folder")
    assert _listing(tmp_path) == ["g"]


@pytest.fixture
def full_disk(monkeypatch):
    """Every temporary output file is a link to /dev/full: the kernel answers every write with ENOSPC."""
    real = tempfile.mkstemp

    def mkstemp(*args, **kwargs):
        fd, name = real(*args, **kwargs)
        if ".tmp" not in os.path.basename(name):
            return fd, name
        os.close(fd)
        os.unlink(name)
        os.symlink("/dev/full", name)
        return os.open(name, os.O_WRONLY), name

    monkeypatch.setattr(tempfile, "mkstemp", mkstemp)


@pytest.mark.parametrize("cmd", CMDS)
def test_full_disk_enospc_is_one_line_and_leaves_nothing(tmp_path, capsys, full_disk, cmd):
    out = tmp_path / "out"
    out.mkdir()
    rc = main(_commands(tmp_path, out / "o")[cmd])
    _one_line_error(capsys, rc, "cannot write", str(out / "o"), "No space left on device")
    assert _listing(out) == []


def test_full_disk_while_writing_png_frames_leaves_nothing(tmp_path, capsys, monkeypatch):
    real = Path.write_bytes
    calls = []

    def write_bytes(self, data):
        calls.append(self)
        if len(calls) == 3:   # the third frame meets a full disk
            real(self, data[: len(data) // 2])
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(self))
        return real(self, data)

    monkeypatch.setattr(Path, "write_bytes", write_bytes)
    rc = main(["snow", "--frames", "4", "--width", "16", "--height", "16", "-o", str(tmp_path / "frames")])
    _one_line_error(capsys, rc, "cannot write", "frames'", "No space left on device")
    assert len(calls) == 3 and _listing(tmp_path) == []


@pytest.mark.parametrize("code", [errno.EROFS, errno.EACCES])
def test_read_only_or_forbidden_folder_is_one_line(tmp_path, capsys, monkeypatch, code):
    """Root may write anywhere, so the refusal is raised where noiselab creates its files."""
    def refuse(*args, **kwargs):
        raise OSError(code, os.strerror(code), kwargs.get("dir", args[-1] if args else None))

    monkeypatch.setattr(tempfile, "mkstemp", refuse)
    monkeypatch.setattr(tempfile, "mkdtemp", refuse)
    for args in (["noise", "--size", "16", "-o", str(tmp_path / "n.png")],
                 ["snow", "--frames", "2", "--width", "16", "--height", "16", "-o", str(tmp_path / "f")],
                 ["mesh", "--shape", "sphere", "--subdivisions", "1", "--resolution", "ignore",
                  "-o", str(tmp_path / "m.ply")]):
        rc = main(args)
        _one_line_error(capsys, rc, "cannot write", os.strerror(code))
    assert _listing(tmp_path) == []


def test_mp4_writer_reports_ffmpeg_failure_instead_of_a_truncated_file(tmp_path, full_disk):
    with pytest.raises(OutputError, match="No space left on device") as info:
        write_video(tmp_path / "v.mp4", np.random.default_rng(0).random((8, 32, 32)))
    assert info.value.errno == errno.ENOSPC
    assert _listing(tmp_path) == []


# ----------------------------------------------------------------------------- signals and folders

def _wait_for_temporary(folder, timeout=120):
    t0 = time.monotonic()
    while time.monotonic() - t0 < timeout:
        tmp = [p for p in Path(folder).iterdir() if ".tmp" in p.name]
        if tmp:
            return tmp
        time.sleep(0.05)
    raise AssertionError(f"no temporary file appeared in {folder}")


@pytest.mark.parametrize("sig, output", [(signal.SIGTERM, "s.mp4"), (signal.SIGHUP, "frames"),
                                         (signal.SIGINT, "s.mp4")])
def test_sigterm_and_sighup_remove_temporary_files(tmp_path, sig, output):
    out = tmp_path / "out"
    out.mkdir()
    proc = subprocess.Popen([sys.executable, "-m", "noiselab", "snow", "--frames", "8", "--loops", "1",
                             "--width", "64", "--height", "64", "--background", str(_long_background(tmp_path)),
                             "-o", str(out / output)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        _wait_for_temporary(out)
        proc.send_signal(sig)
        _, err = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 128 + sig, err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and signal.Signals(sig).name in lines[0] and "Traceback" not in err, err
    time.sleep(0.5)   # an orphaned encoder would still be writing: give it time to show up
    assert _listing(out) == []


def _long_background(tmp_path):
    """A grey video background long enough (3000 frames of 64 x 64) that writing takes a while."""
    path = tmp_path / "bg.npy"
    if not path.exists():
        np.save(path, np.full((3000, 64, 64), 100, np.uint8))
    return path


def test_replacing_an_output_folder_never_leaves_a_moment_without_it(tmp_path, monkeypatch):
    from noiselab.io import atomic_output, exchange_paths

    target = tmp_path / "frames"
    target.mkdir()
    (target / "old").write_text("old")
    # every rename noiselab does while replacing the folder must leave `target` in place
    seen = []
    for name in ("replace", "rename"):
        real = getattr(os, name)

        def checked(src, dst, *a, _real=real, **k):
            _real(src, dst, *a, **k)
            seen.append(target.is_dir())

        monkeypatch.setattr(os, name, checked)
    with atomic_output(target, directory=True) as tmp:
        (tmp / "new").write_text("new")
    assert _listing(target) == ["new"]
    assert all(seen), seen
    assert _listing(tmp_path) == ["frames", "frames/new"]
    # the exchange itself: both names exist before and after, contents swapped
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir(), b.mkdir(), (a / "1").write_text("1")
    assert exchange_paths(a, b) and _listing(b) == ["1"] and _listing(a) == []


# ----------------------------------------------------------------------------- the io doctests

@pytest.mark.parametrize("modname", ["noiselab.io.errors", "noiselab.io.atomic", "noiselab.io.mesh"])
def test_io_docstring_examples_run(modname):
    import doctest
    import importlib

    result = doctest.testmod(importlib.import_module(modname), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0


class _Exited(Exception):
    """What the handler's os._exit raises in these in-process tests."""


@pytest.fixture
def handler_without_exit(monkeypatch):
    """The command line's signal handler, called in this process: os._exit raises, no real signal or child is touched."""
    import noiselab.cli as cli

    def fake_exit(code):
        raise _Exited(code)

    monkeypatch.setattr(signal, "signal", lambda *a: None)   # the handler's own re-arming is not under test
    monkeypatch.setattr(os, "_exit", fake_exit)
    monkeypatch.setattr(cli, "_children", lambda: [])
    monkeypatch.setattr(cli, "_command", "noiselab test")
    return cli._on_signal


def test_a_signal_inside_a_held_step_waits_for_its_end(monkeypatch, handler_without_exit):
    """The window between creating a temporary file (or starting ffmpeg) and recording it is closed."""
    from noiselab.io import atomic

    steps = []
    with pytest.raises(_Exited) as info:
        with atomic.hold_signals():
            handler_without_exit(signal.SIGTERM, None)   # arrives mid-step: nothing happens yet
            steps.append("finished")
            monkeypatch.setattr(signal, "raise_signal", lambda s: handler_without_exit(s, None))
    assert steps == ["finished"] and info.value.args == (128 + signal.SIGTERM,)


def test_the_handler_stops_the_encoder_removes_temporaries_and_says_one_line(tmp_path, capfd, handler_without_exit):
    """What the handler does before it exits, in order: stop the encoder, remove the temporaries, one line."""
    from noiselab.io import atomic

    (tmp_path / "done.png").write_bytes(b"old")
    encoder = atomic.track_process(subprocess.Popen(["sleep", "60"]))
    try:
        with pytest.raises(_Exited) as info:
            with atomic.atomic_output(tmp_path / "v.mp4") as tmp, atomic.atomic_output(tmp_path / "f",
                                                                                     directory=True) as folder:
                (folder / "frame_00000.png").write_bytes(b"x")
                assert tmp.exists() and _listing(tmp_path) != ["done.png"]
                handler_without_exit(signal.SIGHUP, None)
        assert info.value.args == (128 + signal.SIGHUP,)
        assert not os.path.exists(f"/proc/{encoder.pid}")   # killed and reaped (no zombie) by the handler
    finally:
        encoder.kill()
    assert _listing(tmp_path) == ["done.png"]
    assert capfd.readouterr().err.splitlines()[-1:] == ["noiselab test: terminated by SIGHUP; temporary files removed"]
    assert atomic._temporaries == {} and atomic._processes == []
