"""Consistency of the command line: help on every option, one default fps, --frames N gives N frames,
and the published benchmark results are written only by benchmarks/lab_run.py --publish."""
import argparse
import inspect
import sys
from pathlib import Path

import numpy as np
import pytest

from noiselab.cli import build_parser, main
from noiselab.io import DEFAULT_FPS, read_video


def _subparsers():
    parser = build_parser()
    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return action.choices


def test_every_option_of_every_subcommand_has_help():
    subs = _subparsers()
    assert {"snow", "noise", "mesh", "analyze", "bench", "gallery"} <= set(subs)
    missing = [f"{name} {'/'.join(a.option_strings) or a.dest}"
               for name, p in subs.items() for a in p._actions
               if not isinstance(a, argparse._HelpAction) and (not a.help or a.help == argparse.SUPPRESS)]
    assert missing == []


def test_one_default_fps_everywhere():
    from noiselab.geometry import render_sequence, render_turntable
    from noiselab.io import write_video

    fps = {name: next(a.default for a in p._actions if a.dest == "fps")
           for name, p in _subparsers().items() if any(a.dest == "fps" for a in p._actions)}
    assert set(fps) >= {"snow", "noise", "mesh"}
    for fn in (write_video, render_turntable, render_sequence):
        fps[fn.__name__] = inspect.signature(fn).parameters["fps"].default
    assert set(fps.values()) == {DEFAULT_FPS}, fps


@pytest.mark.parametrize("output, frames", [("a.npy", 6), ("a.gif", 6), ("frames", 6), ("a.mp4", 6)])
def test_frames_n_gives_n_frames_and_loops_only_repeat_an_mp4(tmp_path, capsys, output, frames):
    rc = main(["snow", "--frames", "6", "--width", "32", "--height", "32", "--no-background", "-o",
               str(tmp_path / output)])
    assert rc == 0, capsys.readouterr().err
    assert read_video(tmp_path / output).shape[0] == frames   # MP4 too: one period by default (--loops 1)


def test_loops_for_a_format_that_does_not_play_is_refused(tmp_path, capsys):
    rc = main(["snow", "--frames", "4", "--loops", "2", "--width", "16", "--height", "16", "-o", str(tmp_path / "a.gif")])
    err = capsys.readouterr().err
    assert rc == 2 and "--loops applies to .mp4 output only" in err
    rc = main(["snow", "--frames", "4", "--loops", "3", "--width", "16", "--height", "16", "--no-background",
               "-o", str(tmp_path / "a.mp4")])
    assert rc == 0 and read_video(tmp_path / "a.mp4").shape[0] == 12


def test_aliasing_error_names_the_command_line_flags(tmp_path, capsys):
    rc = main(["snow", "--c", "3", "--frames", "4", "--width", "32", "--height", "32", "-o", str(tmp_path / "a.gif")])
    err = capsys.readouterr().err
    assert rc == 2 and "--on-alias drop" in err and "--c 3" in err and "on_alias" not in err
    assert not (tmp_path / "a.gif").exists()
    rc = main(["snow", "--c", "3", "--on-alias", "drop", "--frames", "4", "--width", "32", "--height", "32",
               "-o", str(tmp_path / "a.gif")])
    assert rc == 0


# ----------------------------------------------------------------------------- bench

def _lab_run():
    """``benchmarks/lab_run.py``, the checkout's publisher of ``benchmarks/RESULTS.md``, as a module."""
    import importlib.util

    path = Path(__file__).resolve().parents[1] / "benchmarks" / "lab_run.py"
    spec = importlib.util.spec_from_file_location("lab_run", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_bench_writes_to_out_bench_by_default(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["bench", "--dry-run"]) == 0
    out = capsys.readouterr().out
    assert str(Path("out") / "bench" / "RESULTS.md") in out and "benchmarks" not in out.split("would run")[1]
    assert "WARNING: section 4 (the peers) will be skipped" in out and "--peers-python" in out


def test_the_package_writes_into_no_checkout():
    """The published report's writer lives in benchmarks/, not in the package: no checkout finder, no --publish."""
    import importlib.util

    from noiselab.cli import build_parser

    assert importlib.util.find_spec("noiselab.lab.checkout") is None
    sub = next(a for a in build_parser()._actions if a.__class__.__name__ == "_SubParsersAction")
    options = {o for action in sub.choices["bench"]._actions for o in action.option_strings}
    assert "--publish" not in options and "--peers-python" in options


def test_lab_run_publish_refuses_before_running_anything(tmp_path, capsys):
    lab_run = _lab_run()
    published, missing = tmp_path / "benchmarks", tmp_path / "no-peers" / "python"
    for argv, needle in ((["--publish"], r"refusing to publish without section 4 \(the peers\)"),
                         (["--publish", "--no-peers"], "--no-peers"),
                         (["--publish", "--quick", "--allow-missing-peers"], "quick"),
                         (["--publish", "--output", "x", "--allow-missing-peers"], "drop --output"),
                         (["--allow-missing-peers"], "only applies with --publish")):
        with pytest.raises(ValueError, match=needle):
            lab_run.publish_argv(argv, published=published, peers_python=missing)
    argv = lab_run.publish_argv(["--publish", "--allow-missing-peers", "--dry-run"], published=published,
                                peers_python=missing)
    assert argv[-2:] == ["--output", str(published)] and argv[:2] == ["--peers-python", str(missing)]
    assert main(["bench", *argv]) == 0
    out = capsys.readouterr().out
    assert "WARNING: section 4 (the peers) will be skipped" in out and str(published / "RESULTS.md") in out
    assert not published.exists()   # a dry run writes nothing
    assert lab_run.publish_argv(["--quick"], published=published, peers_python=missing)[-1] == "--quick"


def test_run_all_without_a_peer_interpreter_names_the_option(tmp_path):
    import noiselab.lab.run as lab_run

    assert "--peers-python" in lab_run.peers_missing_reason(None)
    assert "setup_peers.sh" in lab_run.peers_missing_reason(tmp_path / "python")
    assert lab_run.peers_missing_reason(sys.executable) is None
    assert lab_run.default_output() == Path("out") / "bench"


def test_analyze_streams_video_frames_into_one_grey_array(tmp_path):
    """Frames are decoded one by one into a preallocated float32 array: peak near that array's size."""
    import tracemalloc

    from noiselab.cli.analyze import load
    from noiselab.io import write_video

    rng = np.random.default_rng(0)
    video = rng.integers(0, 256, (48, 64, 96, 3), dtype=np.uint8)
    write_video(tmp_path / "v.gif", video)
    # load once before measuring: the first load in a process imports scipy, imageio's plugins and the
    # analysers (about 10 MB of module objects that tracemalloc would count) unless earlier tests did
    load(tmp_path / "v.gif")
    tracemalloc.start()
    data, kind = load(tmp_path / "v.gif")
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert kind == "video" and data.shape == (48, 64, 96) and data.dtype == np.float32
    grey = np.asarray(video, np.float32) / 255 @ np.array([0.2126, 0.7152, 0.0722], np.float32)
    assert np.abs(data - read_video(tmp_path / "v.gif", as_float=True) @ np.array([0.2126, 0.7152, 0.0722], np.float32)
                  ).max() < 1e-6
    assert np.abs(data - grey).max() <= 0.5   # GIF's palette quantises; this checks orientation and scale
    assert peak < 1.5 * data.nbytes, (peak, data.nbytes)   # reading it all first would take 3x (RGB uint8 + float32)


def test_bench_dry_run_from_any_folder_writes_nothing_and_names_its_output(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["bench", "--quick", "--output", "lab", "--dry-run"]) == 0
    out = capsys.readouterr().out
    assert f"would run the quick laboratory and write {Path('lab') / 'RESULTS.md'}" in out
    assert "WARNING: section 4 (the peers) will be skipped" in out and "--peers-python" in out
    assert list(tmp_path.iterdir()) == []   # a dry run creates not even the folder


@pytest.mark.parametrize("frames", [3, 64])
def test_snow_frames_is_honoured_as_given(tmp_path, capsys, frames):
    """No size is capped behind the user's back: --frames 64 writes 64 frames."""
    assert main(["snow", "--frames", str(frames), "--width", "16", "--height", "16", "--no-background",
                 "-o", str(tmp_path / "a.npy")]) == 0
    assert np.load(tmp_path / "a.npy").shape == (frames, 16, 16)
    assert capsys.readouterr().err == ""


def test_mesh_frames_and_size_are_honoured_as_given(tmp_path, capsys):
    from noiselab.io import read_video

    assert main(["mesh", "--shape", "sphere", "--subdivisions", "1", "--frames", "5", "--size", "48",
                 "--render", str(tmp_path / "m.gif")]) == 0, capsys.readouterr().err
    assert read_video(tmp_path / "m.gif").shape[:3] == (5, 48, 48)
