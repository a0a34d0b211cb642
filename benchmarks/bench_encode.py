"""End-to-end ``noiselab snow``: synthesis, compositing and encoding, each against its own floor.

Stages, measured in one process as CPU time (the process's own and, for ffmpeg, its children's),
median of ``--repeats`` rounds:

- synthesis: ``snow(shape)`` against a bare ``scipy.fft.irfftn`` of the same float32 output;
- compositing: ``composite`` of every frame plus the uint8 conversion, against one ``np.multiply``
  pass over the same frames;
- encoding: ffmpeg encoding the same uint8 frames from memory with each x264 preset (the floor: FFV1,
  lossless and nearly free), with the file size and the mean absolute error of the decoded frames;
- the whole command ``noiselab snow`` (a subprocess; its CPU time includes ffmpeg's).

Usage: ``python3 benchmarks/bench_encode.py [--sizes 512 1024] [--frames 64] [--repeats 5]``.
"""
from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy.fft


def _children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def _encode(raw, n, args, path):
    import imageio_ffmpeg

    c0 = _children_cpu()
    cmd = [imageio_ffmpeg.get_ffmpeg_exe(), "-y", "-f", "rawvideo", "-vcodec", "rawvideo", "-s", f"{n}x{n}",
           "-pix_fmt", "gray", "-r", "25", "-i", "-", "-an", *args, "-v", "error", path]
    subprocess.run(cmd, input=raw, check=True)
    cpu = _children_cpu() - c0
    back = subprocess.run([imageio_ffmpeg.get_ffmpeg_exe(), "-i", path, "-f", "rawvideo", "-pix_fmt", "gray",
                           "-v", "error", "-"], capture_output=True, check=True).stdout
    err = np.abs(np.frombuffer(back, np.uint8).astype(np.int16) - np.frombuffer(raw, np.uint8)).mean()
    return cpu, os.path.getsize(path) / 1e6, err


def _cpu(fn):
    t = time.process_time()
    out = fn()
    return time.process_time() - t, out


PRESETS = {"x264 crf 10, preset medium (before)": ["-vcodec", "libx264", "-pix_fmt", "yuv420p", "-crf", "10"],
           "x264 crf 10, preset veryfast (now)": ["-vcodec", "libx264", "-pix_fmt", "yuv420p", "-crf", "10",
                                                  "-preset", "veryfast"],
           "FFV1, lossless (floor)": ["-vcodec", "ffv1", "-level", "3", "-pix_fmt", "gray", "-f", "matroska"]}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[512, 1024])
    parser.add_argument("--frames", type=int, default=64)
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args(argv)
    from noiselab.snowfall import composite, snow

    snow((8, 64, 64), rng=0)   # compile outside the timings
    tmp = tempfile.mkdtemp()
    print(f"# bench_encode: {args.frames} frames, CPU seconds, median of {args.repeats}; load {os.getloadavg()[0]:.1f}")
    for n in args.sizes:
        shape = (args.frames, n, n)
        spec = np.zeros((args.frames, n, n // 2 + 1), np.complex64)
        rows = {k: [] for k in ["synthesis", "irfftn floor", "composite + uint8", "multiply floor", "command"]}
        enc = {k: [] for k in PRESETS}
        bg = np.linspace(0.1, 0.9, n * n, dtype=np.float32).reshape(n, n)
        for _ in range(args.repeats):
            t, alpha = _cpu(lambda: snow(shape, rng=1))
            rows["synthesis"].append(t)
            rows["irfftn floor"].append(_cpu(lambda: scipy.fft.irfftn(spec, s=shape))[0])
            t, frames = _cpu(lambda: [(composite(a, bg) * 255 + 0.5).astype(np.uint8) for a in alpha])
            rows["composite + uint8"].append(t)
            rows["multiply floor"].append(_cpu(lambda: [np.multiply(a, bg) for a in alpha])[0])
            raw = np.stack(frames).tobytes()
            for name, ffargs in PRESETS.items():
                enc[name].append(_encode(raw, n, ffargs, os.path.join(tmp, "o.mkv" if "FFV1" in name else "o.mp4")))
            c0, p0 = _children_cpu(), time.process_time()
            subprocess.run([sys.executable, "-m", "noiselab", "snow", "--width", str(n), "--height", str(n),
                            "--frames", str(args.frames), "--output", os.path.join(tmp, "cmd.mp4")],
                           check=True, stdout=subprocess.DEVNULL)
            rows["command"].append(_children_cpu() - c0)
        print(f"\n## {n}^2 x {args.frames} frames\n\n| stage | CPU s | against its floor |\n| --- | --- | --- |")
        med = {k: statistics.median(v) for k, v in rows.items()}
        print(f"| synthesis `snow` | {med['synthesis']:.2f} | {med['synthesis'] / med['irfftn floor']:.2f}x irfftn "
              f"({med['irfftn floor']:.2f} s) |")
        print(f"| composite + uint8 | {med['composite + uint8']:.2f} | "
              f"{med['composite + uint8'] / med['multiply floor']:.2f}x one multiply pass |")
        floor = statistics.median(c for c, _, _ in enc["FFV1, lossless (floor)"])
        for name, res in enc.items():
            cpu = statistics.median(c for c, _, _ in res)
            print(f"| encode: {name} | {cpu:.2f} | {cpu / floor:.2f}x FFV1; {res[-1][1]:.2f} MB, "
                  f"mean error {res[-1][2]:.2f} grey levels |")
        print(f"| whole `noiselab snow` (subprocess, incl. import and ffmpeg) | {med['command']:.2f} | |")


if __name__ == "__main__":
    main()
