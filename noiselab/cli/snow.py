"""``noiselab snow``: render falling snow (tent model) and composite it over a background.

``--frames N`` is the period of the snow and the number of frames written to
every format (an MP4 of N frames lasts N / fps seconds); ``--loops K`` repeats
the period K times in an MP4 only (a playback format that does not loop by
itself; a GIF loops by itself, NPY and PNG frames hold the data once). A video
background sets the length instead.
"""
from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np

from ..io.media import DEFAULT_FPS
from ..scale.commands import add_dask_arguments

NAME = "snow"
HELP = "render Langer & Zhang's falling snow by inverse FFT over a background, to MP4, GIF, PNG frames or NPY"


def add_arguments(p):
    g = p.add_argument_group("scene")
    g.add_argument("--width", type=int, default=None, help="frame width in px (default: the background's, else 512)")
    g.add_argument("--height", type=int, default=None, help="frame height in px (default: the background's, else 512)")
    g.add_argument("--frames", type=int, default=64,
                   help="frames in one period of the snow, and in the file (default 64); it loops seamlessly")
    g.add_argument("--loops", type=int, default=None,
                   help="MP4 only: how many periods to write (default 1: the file holds --frames frames); a GIF loops by itself, NPY and PNG "
                        "frames hold one period; a video background sets the length instead")
    g.add_argument("--tile", type=int, default=None, metavar="N",
                   help="render an N x N tile and repeat it over the frame (thesis 3.4; cheaper, periodic)")
    g.add_argument("--seed", type=int, default=0, help="random seed (default 0); same seed, same video")
    t = p.add_argument_group("tent model")
    t.add_argument("--c", type=float, default=1.0,
                   help="tent constant in rad/frame, 0..pi (default 1.0): flakes at spatial frequency |w| rad/px "
                        "fall at c/|w| px/frame (5.09*c px/frame for the nearest, 0.637*c for the farthest of the default band)")
    t.add_argument("--band", type=float, nargs=2, default=None, metavar=("LO", "HI"),
                   help="spatial band in cycles per frame width (default W/32 W/4: 16 128 at 512 px); HI <= W/2")
    t.add_argument("--thickness", type=float, default=0.1, help="relative tent thickness 0..1 (spread of c; default 0.1)")
    t.add_argument("--direction-yx", type=float, nargs=2, default=None, metavar=("DY", "DX"),
                   help="fall direction in array order, y down, x right, as snow(direction_yx=) (default 1 0: "
                        "straight down)")
    t.add_argument("--direction", type=float, nargs=2, default=None, metavar=("DX", "DY"),
                   help="the same in (x, y) order (the older spelling; --direction 1 2 = --direction-yx 2 1)")
    t.add_argument("--pan-yx", type=float, nargs=2, default=None, metavar=("UY", "UX"),
                   help="image velocity px/frame, array order, added by a panning camera (sheared tent), as "
                        "snow(pan_yx=) (default 0 0)")
    t.add_argument("--pan", type=float, nargs=2, default=None, metavar=("UX", "UY"),
                   help="the same in (x, y) order (the older spelling; --pan 1 0 = --pan-yx 0 1)")
    t.add_argument("--beta", type=float, default=1.5, help="opacity exponent alpha**beta (default 1.5)")
    t.add_argument("--exponent", type=float, default=1.0, help="amplitude 1/f**exponent (default 1)")
    t.add_argument("--amplitude-distribution", "--amplitude", dest="amplitude",
                   choices=("uniform", "rayleigh", "fixed"), default="uniform",
                   help="random amplitude law, snow(amplitude_distribution=) (default uniform, as the thesis; "
                        "--amplitude is the old spelling)")
    t.add_argument("--on-alias", choices=("raise", "drop"), default="raise",
                   help="energy past the temporal Nyquist (pi rad/frame, e.g. --c above 2.856): error (default) "
                        "or drop those cells")
    t.add_argument("--dtype", choices=("float32", "float64"), default="float32", help="precision (default float32)")
    t.add_argument("--workers", type=int, default=-1,
                   help="FFT threads: a count, or -1 for every core, -2 for all but one (default -1); "
                        "the video is the same for any count")
    o = p.add_argument_group("output")
    o.add_argument("--background", default=None,
                   help="image or video file (or folder of PNG frames) to snow on; default: a built-in landscape")
    o.add_argument("--no-background", action="store_true", help="write the opacity alpha itself (grey)")
    o.add_argument("--intensity", type=float, default=250.0, help="snow intensity 0..255 (default 250)")
    o.add_argument("--output", "-o", default="out/snow.mp4",
                   help="file .mp4, .gif, .npy or .zarr (one period of the opacity, on dask: see --chunks), "
                        "or a folder (no suffix) for PNG frames (default out/snow.mp4)")
    o.add_argument("--fps", type=float, default=DEFAULT_FPS,
                   help="frames per second of an MP4 or GIF (default %(default)g)")
    add_dask_arguments(o, "with .zarr output (the opacity, computed on dask): chunk shape TxHxW, e.g. 8x256x512 "
                          "(default: auto)")
    pr = o.add_mutually_exclusive_group()
    pr.add_argument("--progress", dest="progress", action="store_true", default=None, help="always show progress bars")
    pr.add_argument("--quiet", dest="progress", action="store_false", help="never show progress bars")


def _cli_words(message):
    """The library's error message in the command line's words (``--on-alias drop``, ``--c``, ``--pan``)."""
    for old, new in (("pass on_alias='drop'", "add --on-alias drop"), ('on_alias="drop"', "--on-alias drop"),
                     ("on_alias='drop'", "--on-alias drop"), ("largest allowed c ", "largest allowed --c "),
                     ("Largest allowed c ", "Largest allowed --c "), ("temporal aliasing: c=", "temporal aliasing: --c "),
                     ("and pan_yx=", "and --pan-yx "), (" with thickness=", " with --thickness ")):
        message = message.replace(old, new)
    return message


def _load_background(path):
    from ..io import InputError, load_npy, read_image, read_video

    p = Path(path)
    if p.is_dir() or p.suffix.lower() in (".mp4", ".gif"):
        bg = read_video(p)
        if bg.shape[0] == 1:
            bg = bg[0]
    elif p.suffix.lower() == ".npy":
        bg = load_npy(p)
    else:
        bg = read_image(p)
    if bg.size == 0:
        raise InputError(p, f"it holds an empty array of shape {bg.shape}")
    if bg.dtype.kind not in "biuf":
        raise InputError(p, f"it holds {bg.dtype} data, not an image")
    return bg


def _array_order(args):
    """``--direction-yx``/``--pan-yx`` from either spelling (the (x, y) flags swapped, never reinterpreted)."""
    for new, old, default in (("direction_yx", "direction", (1.0, 0.0)), ("pan_yx", "pan", (0.0, 0.0))):
        yx, xy = getattr(args, new, None), getattr(args, old, None)
        if yx is not None and xy is not None:
            raise ValueError(f"--{new.replace('_', '-')} and --{old} say the same thing in two orders; pass one")
        setattr(args, new, tuple(yx) if yx is not None else tuple(xy[::-1]) if xy is not None else default)
        setattr(args, old, None)


def run(args) -> int:
    from ..io import write_video
    from ..snowfall import composite, iter_tiled_frames, snow
    from ..snowfall.background import default_background

    from ..io import prepare_output

    if args.frames < 1:
        raise ValueError(f"--frames must be >= 1, got {args.frames}")
    _array_order(args)
    out = Path(args.output)
    mp4 = out.suffix.lower() == ".mp4"
    if args.loops is not None and args.loops < 1:
        raise ValueError(f"--loops must be >= 1, got {args.loops}")
    if args.loops not in (None, 1) and not mp4:
        raise ValueError(f"--loops applies to .mp4 output only (a GIF loops by itself; NPY and PNG frames hold "
                         f"one period of --frames {args.frames}), got --loops {args.loops} for {out.name!r}")
    loops = (1 if args.loops is None else args.loops) if mp4 else 1  # the length asked for, no more
    if args.background and args.no_background:
        raise ValueError("--background and --no-background exclude each other")
    if out.suffix.lower() not in ("", ".mp4", ".gif", ".npy", ".zarr"):
        raise ValueError(f"--output must end in .mp4, .gif, .npy or .zarr, or be a folder for PNG frames; "
                         f"got {out.name!r}")
    prepare_output(out, directory=out.suffix.lower() in ("", ".zarr"))   # fail now, not after rendering
    background = None
    if args.background:
        background = _load_background(args.background)
        if background.ndim not in (2, 3, 4):
            raise ValueError(f"background must be an image or a video, got an array of shape {background.shape}")
    # frame size: from the background, or the options; both must agree
    if background is not None:
        is_video = background.ndim == 4 or (background.ndim == 3 and background.shape[-1] != 3)
        bh, bw = background.shape[1:3] if is_video else background.shape[:2]
        if background.ndim == 4 and background.shape[-1] != 3:
            raise ValueError(f"background {args.background!r} has {background.shape[-1]} channels per pixel; "
                             "expected grey or RGB (3)")
        if (args.width not in (None, bw)) or (args.height not in (None, bh)):
            raise ValueError(f"background {args.background!r} is {bw} x {bh} px but --width/--height ask for "
                             f"{args.width} x {args.height}; drop them or resize the background")
        H, W = bh, bw
    else:
        H = 512 if args.height is None else args.height
        W = 512 if args.width is None else args.width
        is_video = False
    if H < 1 or W < 1:
        raise ValueError(f"--width and --height must be >= 1, got {W} x {H}")
    T = args.frames
    if Path(args.output).suffix.lower() == ".zarr" or args.chunks is not None or args.scheduler is not None:
        from ..scale.commands import write_snow_zarr  # chunked on dask, streamed to zarr

        return write_snow_zarr(args, (T, H, W), Path(args.output))
    n_out = T * loops
    if background is not None and is_video:
        n_out = background.shape[0]  # the snow loops over the whole background video
    th, tw = (H, W) if args.tile is None else (args.tile, args.tile)
    if args.tile is not None and args.tile < 1:
        raise ValueError(f"--tile must be >= 1, got {args.tile}")
    band = None if args.band is None else tuple(args.band)
    if band is not None and args.tile is not None:
        band = tuple(b * tw / W for b in band)  # keep the flakes' size in pixels
    t0 = time.perf_counter()
    try:
        alpha = snow((T, th, tw), rng=args.seed, c=args.c, band=band, thickness=args.thickness,
                     direction_yx=args.direction_yx, pan_yx=args.pan_yx, beta=args.beta, exponent=args.exponent,
                     amplitude_distribution=args.amplitude, dtype=args.dtype, on_alias=args.on_alias,
                     progress=args.progress, workers=args.workers)
    except ValueError as exc:   # name the flags a command-line user types, not the Python keywords
        raise ValueError(_cli_words(str(exc))) from None
    t_render = time.perf_counter() - t0
    reps = (math.ceil(H / th), math.ceil(W / tw))
    alpha_frames = iter_tiled_frames(alpha, reps, n_frames=n_out, crop=(H, W))

    if args.no_background:
        frames = alpha_frames
    else:
        if background is None:
            background = default_background(H, W)
            is_video = False
        bg = background   # its frame size, channels and length were checked above
        if bg.dtype != np.uint8 and bg.dtype.kind in "iu":
            bg = bg.astype(np.uint8) if bg.size and bg.min() >= 0 and bg.max() <= 255 else bg
        frames = (composite(a, bg[i] if is_video else bg, intensity=args.intensity)
                  for i, a in enumerate(alpha_frames))

    class _Sized:  # lets the writer show a bar with a total
        def __init__(self, it, n):
            self.it, self.n = it, n

        def __iter__(self):
            return iter(self.it)

        def __len__(self):
            return self.n

    write_video(out, _Sized(frames, n_out), fps=args.fps, progress=args.progress)
    what = "opacity" if args.no_background else "snow scene"
    print(f"wrote {what} to {out} ({n_out} frames of {W} x {H} px at {args.fps:g} fps, {n_out / args.fps:.2f} s; "
          f"period {T} frames, rendered in {t_render:.2f} s)")
    return 0
