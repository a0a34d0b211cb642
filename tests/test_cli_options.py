"""Consistency of the command line: help on every option, one default fps, --frames N gives N frames,
and the published benchmark results are only written by an explicit --publish."""
import argparse
import inspect
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

@pytest.fixture
def fake_checkout(tmp_path, monkeypatch):
    """A scratch git checkout holding the published results, without a peer environment; run from inside it."""
    import noiselab.lab.checkout as checkout

    root = tmp_path / "checkout"
    published = root / "benchmarks"
    (published / "results").mkdir(parents=True)
    (published / "RESULTS.md").write_text("published\n")
    (root / "noiselab").mkdir()
    (root / "noiselab" / "__init__.py").write_text("")
    (root / "pyproject.toml").write_text("[project]\nname = 'noiselab'\n")
    monkeypatch.setattr(checkout, "package_parent", lambda: tmp_path / "site-packages")   # an installed noiselab
    monkeypatch.chdir(root)
    return root


@pytest.fixture
def fake_published(fake_checkout):
    """The published results (``benchmarks/`` of the scratch checkout)."""
    return fake_checkout / "benchmarks"


def test_bench_writes_to_out_bench_by_default(fake_published, capsys):
    assert main(["bench", "--dry-run"]) == 0
    out = capsys.readouterr().out
    assert str(Path("out") / "bench" / "RESULTS.md") in out and "benchmarks" not in out.split("would run")[1]
    assert "WARNING: section 4 (the peers) will be skipped" in out


def test_bench_publish_refuses_without_the_peers(fake_published, capsys):
    rc = main(["bench", "--publish"])
    err = capsys.readouterr().err
    assert rc == 2 and "refusing to publish without section 4 (the peers)" in err and "--allow-missing-peers" in err
    assert (fake_published / "RESULTS.md").read_text() == "published\n"
    assert main(["bench", "--publish", "--quick"]) == 2
    assert main(["bench", "--allow-missing-peers"]) == 2
    capsys.readouterr()
    assert main(["bench", "--publish", "--allow-missing-peers", "--dry-run"]) == 0
    out = capsys.readouterr().out
    assert "WARNING: section 4 (the peers) will be skipped" in out and str(fake_published / "RESULTS.md") in out


def test_run_all_refuses_to_publish_before_running_anything(fake_published, monkeypatch):
    import noiselab.lab.run as lab_run

    monkeypatch.setattr(lab_run, "machine_info", lambda: pytest.fail("an experiment ran"))
    with pytest.raises(lab_run.PublishError, match="peer environment missing"):
        lab_run.run_all(publish=True)
    with pytest.raises(lab_run.PublishError, match="--no-peers"):
        lab_run.run_all(publish=True, peers=False)
    with pytest.raises(lab_run.PublishError, match="quick"):
        lab_run.run_all(publish=True, quick=True, allow_missing_peers=True)
    assert lab_run.default_output() == Path("out") / "bench"
    assert (fake_published / "RESULTS.md").read_text() == "published\n"


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


def test_bench_publish_finds_the_checkout_from_a_subfolder(fake_checkout, capsys, monkeypatch):
    monkeypatch.chdir(fake_checkout / "benchmarks" / "results")
    assert main(["bench", "--publish", "--allow-missing-peers", "--dry-run"]) == 0
    assert str(fake_checkout / "benchmarks" / "RESULTS.md") in capsys.readouterr().out


def test_bench_publish_without_a_checkout_is_one_line_and_status_2(tmp_path, capsys, monkeypatch):
    import noiselab.lab.checkout as checkout
    import noiselab.lab.run as lab_run

    monkeypatch.setattr(checkout, "package_parent", lambda: tmp_path / "site-packages")
    monkeypatch.chdir(tmp_path)
    for argv in (["bench", "--publish"], ["bench", "--publish", "--allow-missing-peers", "--dry-run"]):
        rc = main(argv)
        err = capsys.readouterr().err
        assert rc == 2 and err.count("\n") == 1, err
        assert err.startswith("noiselab bench: error: ") and "git checkout" in err and str(tmp_path) in err
    assert not (tmp_path / "benchmarks").exists() and not (tmp_path / "out").exists()
    monkeypatch.setattr(lab_run, "machine_info", lambda: pytest.fail("an experiment ran"))
    with pytest.raises(checkout.CheckoutNotFound, match="git checkout"):
        lab_run.run_all(publish=True, allow_missing_peers=True)
    assert "no checkout was found" in lab_run.peers_missing_reason()


def test_bench_dry_run_from_any_folder_writes_nothing_and_names_its_output(tmp_path, capsys, monkeypatch):
    import noiselab.lab.checkout as checkout

    monkeypatch.setattr(checkout, "package_parent", lambda: tmp_path / "site-packages")
    monkeypatch.chdir(tmp_path)
    assert main(["bench", "--quick", "--output", "lab", "--dry-run"]) == 0
    out = capsys.readouterr().out
    assert f"would run the quick laboratory and write {Path('lab') / 'RESULTS.md'}" in out
    assert "WARNING: section 4 (the peers) will be skipped" in out and "no checkout was found" in out
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
