"""``noiselab stimulus``: the common vision-science stimuli in physical units, with a JSON sidecar.

Kinds: ``pink`` (a 1/f**exponent patch), ``bandpass`` (log-Gabor band x
orientation band), ``snow`` (falling snow as a luminance modulation),
``cloud`` (a Motion Cloud) and ``scramble`` (a phase-scrambled image). Sizes
are in degrees, durations in seconds, frequencies in cycles/deg, speeds in
deg/s, luminance in cd/m² on the display the options describe; the output
holds the integer display values (``noiselab.stimuli.to_display``) and
``OUTPUT.json`` beside it every parameter, the display, the seed, the
noiselab version, the mean and contrast measured on the values written and,
with ``--clip K``, the fraction of the field clipped at K standard deviations.
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np

NAME = "stimulus"
HELP = ("a stimulus in physical units (deg, s, cycles/deg, deg/s, cd/m², contrast) on a described display: "
        "1/f patch, band-pass oriented noise, snow, motion cloud or phase-scrambled image, with a JSON sidecar")
KINDS = ("pink", "bandpass", "snow", "cloud", "scramble")
MOVING = ("snow", "cloud")
APERTURES = ("none", "circle", "raised-cosine", "gaussian")
# what each output format keeps (benchmarks/bench_stimuli.md measures the contrast after a round trip)
LOSSLESS = {".npy": True, ".png": True, ".mkv": True, ".mp4": False}


def add_arguments(p):
    p.add_argument("kind", choices=KINDS, help="which stimulus: " + ", ".join(KINDS))
    d = p.add_argument_group("display")
    d.add_argument("--ppd", type=float, default=None,
                   help="pixels per degree (default: from --distance-cm/--screen-width-cm/--resolution-px, else 32)")
    d.add_argument("--distance-cm", type=float, default=None, help="viewing distance in cm (with the next two)")
    d.add_argument("--screen-width-cm", type=float, default=None, help="visible screen width in cm")
    d.add_argument("--resolution-px", type=int, default=None, help="horizontal resolution in pixels")
    d.add_argument("--frame-rate", type=float, default=60.0, help="display frame rate in Hz (default 60)")
    d.add_argument("--luminance", type=float, nargs=2, default=(0.5, 100.0), metavar=("LMIN", "LMAX"),
                   help="luminance in cd/m² at the lowest and highest display value (default 0.5 100)")
    d.add_argument("--gamma", type=float, default=2.2, help="display gamma (default 2.2)")
    d.add_argument("--bits", type=int, default=8, help="bits per display value, 1..16 (default 8)")
    d.add_argument("--lut", default=None,
                   help=".npy file of 2**bits measured luminances (cd/m², increasing), instead of the gamma law")
    s = p.add_argument_group("stimulus")
    s.add_argument("--size", type=float, default=8.0, help="width and height in degrees (default 8)")
    s.add_argument("--duration", type=float, default=1.0, help="seconds, snow and cloud (default 1)")
    s.add_argument("--mean", type=float, default=40.0, help="mean luminance in cd/m² (default 40)")
    s.add_argument("--contrast", type=float, default=0.2, help="contrast (default 0.2)")
    s.add_argument("--contrast-kind", choices=("rms", "michelson"), default="rms",
                   help="rms: sd/mean of the luminance; michelson: (max-min)/(max+min) (default rms)")
    s.add_argument("--clip", type=float, default=None, metavar="K",
                   help="clip the field at +-K standard deviations, then scale it to the requested contrast (a "
                        "Gaussian field's tails otherwise leave the display); the sidecar records the fraction "
                        "clipped (default: no clipping)")
    s.add_argument("--aperture", choices=APERTURES, default="none",
                   help="window on the mean luminance: none, circle, raised-cosine (with --ramp) or gaussian (with "
                        "--aperture-sigma); the contrast is stated inside it (default none)")
    s.add_argument("--aperture-diameter", type=float, default=None, metavar="DEG",
                   help="circle and raised-cosine: outer diameter in degrees, ramp included (default: --size)")
    s.add_argument("--ramp", type=float, default=0.5, metavar="DEG",
                   help="raised-cosine: width of the cosine edge in degrees, inside the diameter (default 0.5)")
    s.add_argument("--aperture-sigma", type=float, default=None, metavar="DEG",
                   help="gaussian: the envelope's standard deviation in degrees (default: --size / 6)")
    s.add_argument("--no-dither", action="store_true", help="nearest display value instead of random dithering")
    s.add_argument("--seed", type=int, default=0, help="random seed (default 0); same seed, same stimulus")
    s.add_argument("--trials", type=int, default=None, metavar="N",
                   help="write N trials OUTPUT_000 .. with seeds derived from --seed (recorded; trial i is --seed "
                        "<its seed> on its own) and one OUTPUT_manifest.json listing every file, its seed, "
                        "parameters and measured contrast, luminance range and clipped fraction")
    k = p.add_argument_group("spectrum")
    k.add_argument("--exponent", type=float, default=1.0, help="pink: amplitude 1/f**exponent (default 1)")
    k.add_argument("--band-cpd", "--band", dest="band", type=float, nargs=2, default=None, metavar=("LO", "HI"),
                   help="pink and snow: spatial band in cycles/deg, Display.band(band_cycles_per_degree=) (default: "
                        "all for pink, 1 8 for snow; --band is the older spelling)")
    k.add_argument("--sf", type=float, default=4.0,
                   help="bandpass and cloud: peak spatial frequency in cycles/deg (default 4)")
    k.add_argument("--sf-bandwidth", type=float, default=2.0,
                   help="bandpass and cloud: MotionClouds' B_sf in cycles/deg (default 2: a log-width of ln 1.5)")
    k.add_argument("--sf-bandwidth-octaves", type=float, default=None, metavar="OCT",
                   help="bandpass and cloud: the spatial-frequency bandwidth in octaves, full width at half maximum "
                        "of the amplitude band, as papers state it (instead of --sf-bandwidth)")
    k.add_argument("--orientation", type=float, default=0.0,
                   help="bandpass and cloud: orientation of the wave vector in degrees, y down (default 0)")
    k.add_argument("--orientation-bandwidth", type=float, default=None,
                   help="bandpass and cloud: orientation bandwidth B_theta in degrees (default: every orientation)")
    k.add_argument("--orientation-hwhm", type=float, default=None, metavar="DEG",
                   help="bandpass and cloud: orientation bandwidth as half width at half height in degrees, as "
                        "papers state it (instead of --orientation-bandwidth)")
    k.add_argument("--velocity-yx", type=float, nargs=2, default=None, metavar=("VY", "VX"),
                   help="cloud: velocity in deg/s in array order, y down, x right (default 0 1); snow: the fall "
                        "speed is VY")
    k.add_argument("--velocity", type=float, nargs=2, default=None, metavar=("VX", "VY"),
                   help="the same in (x, y) order (the older spelling; --velocity 1 0 = --velocity-yx 0 1)")
    k.add_argument("--speed-bandwidth", type=float, default=0.5,
                   help="cloud: MotionClouds' B_V in deg/s (default 0.5)")
    k.add_argument("--snow-frequency", type=float, default=4.0,
                   help="snow: the spatial frequency (cycles/deg) whose flakes fall at VY deg/s (default 4)")
    k.add_argument("--image", default=None, help="scramble: the image file (PNG, JPEG, NPY) to phase-scramble")
    o = p.add_argument_group("output")
    o.add_argument("--output", "-o", default="out/stimulus.png",
                   help="file: .png (still), .mkv (lossless FFV1), .mp4 (lossy H.264 unless --lossless) or .npy "
                        "(the display values); OUTPUT.json beside it (default out/stimulus.png)")
    o.add_argument("--psychopy", action="store_true",
                   help="also write OUTPUT_psychopy.npy: float32 luminance in -1..1 (-1 = LMIN, 1 = LMAX, linear in "
                        "cd/m²), the image a PsychoPy window that corrects gamma itself takes (ImageStim, "
                        "colorSpace rgb; rows run down as in the PNG, and PsychoPy draws an array's first row at the "
                        "bottom: pass numpy.flipud of it); the PNG/video holds display values for a window that "
                        "does not")
    o.add_argument("--lossless", action="store_true", help=".mp4: H.264 in RGB with -qp 0 (lossless)")


def _display(args):
    from ..io import load_npy
    from ..stimuli import Display

    geometry = (args.distance_cm, args.screen_width_cm, args.resolution_px)
    if any(g is not None for g in geometry):
        if args.ppd is not None or any(g is None for g in geometry):
            raise ValueError("give --ppd, or all three of --distance-cm, --screen-width-cm, --resolution-px")
        return Display.from_geometry(distance_cm=args.distance_cm, screen_width_cm=args.screen_width_cm,
                                     resolution_px=args.resolution_px, frame_rate=args.frame_rate,
                                     luminance=tuple(args.luminance), gamma=args.gamma, bits=args.bits)
    ppd = 32.0 if args.ppd is None else args.ppd
    if args.lut is not None:
        return Display.from_lut(load_npy(args.lut), ppd, frame_rate=args.frame_rate)
    return Display(ppd, frame_rate=args.frame_rate, luminance=tuple(args.luminance), gamma=args.gamma,
                   bits=args.bits)


def _field(args, display, rng):
    """The stimulus as a float field in pixels and frames, and the pixel-unit arguments it was made with."""
    from ..snowfall import snow
    from ..spectral import spectral_noise
    from ..stimuli import motion_cloud, phase_scramble

    n = display.pixels(args.size)
    frames = display.frame_count(args.duration)
    from ..stimuli import B_sf_from_octaves, B_theta_from_hwhm

    if args.orientation_hwhm is not None and args.orientation_bandwidth is not None:
        raise ValueError("--orientation-hwhm and --orientation-bandwidth both set the orientation band; pass one")
    b_theta = np.inf if args.orientation_bandwidth is None else math.radians(args.orientation_bandwidth)
    if args.orientation_hwhm is not None:
        b_theta = B_theta_from_hwhm(orientation_hwhm_deg=args.orientation_hwhm)
    b_sf = args.sf_bandwidth if args.sf_bandwidth_octaves is None else B_sf_from_octaves(
        sf_0=args.sf, sf_bandwidth_octaves=args.sf_bandwidth_octaves)   # (cycles/deg in, cycles/deg out)
    if args.kind == "pink":
        band = None if args.band is None else display.band(args.band, n)
        used = dict(shape=(n, n), exponent=args.exponent, band=band)
        return spectral_noise(rng=rng, **used), used
    if args.kind in ("bandpass", "cloud"):
        used = dict(shape=(n, n) if args.kind == "bandpass" else (frames, n, n),
                    sf_0=display.cycles_per_pixel(args.sf), B_sf=display.cycles_per_pixel(b_sf),
                    theta=math.radians(args.orientation), B_theta=b_theta)
        if args.kind == "cloud":
            used.update(V_X=display.px_per_frame(args.velocity[0]), V_Y=display.px_per_frame(args.velocity[1]),
                        B_V=display.px_per_frame(args.speed_bandwidth))
        return motion_cloud(rng=rng, **used), used
    if args.kind == "snow":
        band = display.band((1.0, 8.0) if args.band is None else args.band, n)
        used = dict(shape=(frames, n, n), c=display.snow_c(args.velocity[1], args.snow_frequency), band=band)
        return snow(rng=rng, **used), used
    if args.image is None:
        raise ValueError("scramble needs --image FILE (the image to phase-scramble)")
    from ..analysis import to_grey
    from ..io import read_image

    image = to_grey(read_image(args.image)).astype(np.float64)
    return phase_scramble(image, rng=rng), dict(shape=image.shape, image=str(args.image))


def _aperture(args, display, shape):
    """The window of ``--aperture`` on the frames of ``shape`` (None for none), and what it was made with."""
    from ..stimuli import circular_aperture, gaussian_aperture, raised_cosine_aperture

    if args.aperture == "none":
        return None, None
    diameter = args.size if args.aperture_diameter is None else args.aperture_diameter
    if args.aperture == "circle":
        return circular_aperture(shape, display, diameter_deg=diameter), dict(kind="circle", diameter_deg=diameter)
    if args.aperture == "raised-cosine":
        used = dict(diameter_deg=diameter, ramp_deg=args.ramp)
        return raised_cosine_aperture(shape, display, **used), dict(kind="raised-cosine", **used)
    sigma = args.size / 6.0 if args.aperture_sigma is None else args.aperture_sigma
    return gaussian_aperture(shape, display, sigma_deg=sigma), dict(kind="gaussian", sigma_deg=sigma)


def _measured_in_aperture(L, w, mean):
    """Mean and the carrier's RMS contrast where the window is at least 0.5: ``(L - mean) / w`` weighted by ``w``."""
    inside = np.broadcast_to(w >= 0.5, L.shape)
    wi = np.broadcast_to(w, L.shape)[inside]
    d = L[inside] - mean
    return {"mean_cd_m2": float(L[inside].mean()),
            "rms_contrast": float(np.sqrt(np.sum(d * d / wi) / np.sum(wi)) / mean),
            "where": "pixels whose aperture weight w >= 0.5; the contrast is that of (L - mean) / w, weighted by w "
                     "(the carrier's, as requested)"}


def _write(path, values, display, args):
    import imageio.v3 as iio

    from ..io import atomic_output, write_image, write_video

    suffix = path.suffix.lower()
    if suffix == ".npy":
        write_image(path, values)   # the display values themselves
    elif suffix == ".png":
        if values.ndim != 2:
            raise ValueError(f"{path.name}: a PNG holds one frame; write the {args.kind} video to .mkv, .mp4 or .npy")
        if values.dtype == np.uint8:
            write_image(path, values)
        else:   # a 16-bit grey PNG keeps a 10- to 16-bit display's values
            with atomic_output(path) as tmp:
                Path(tmp).write_bytes(iio.imwrite("<bytes>", values, extension=".png"))
    elif suffix in (".mkv", ".mp4"):
        if values.dtype != np.uint8:
            raise ValueError(f"{path.name}: videos hold 8-bit values; a {display.bits}-bit display's stimulus goes "
                             f"to .npy (or --bits 8)")
        video = values if values.ndim == 3 else values[None]
        write_video(path, video, fps=display.frame_rate, lossless=args.lossless, progress=False)
    else:
        raise ValueError(f"output must end in .png, .mkv, .mp4 or .npy, got {path.name!r}")


def _jsonable(x):
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(v) for v in x]
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (np.floating, float)):
        return None if not math.isfinite(x) else float(x)
    return x


def _make(args, display, path, seed):
    """Make, write and measure one stimulus with ``seed``: its values, what was measured, the pixel-unit arguments."""
    from ..analysis import michelson_contrast, rms_contrast
    from ..stimuli import to_display

    rng = np.random.default_rng(seed)
    field, used = _field(args, display, rng)
    window, window_used = _aperture(args, display, field.shape)
    try:
        values, report = to_display(field, display, mean=args.mean, contrast=args.contrast,
                                    contrast_kind=args.contrast_kind, dither=not args.no_dither, rng=rng,
                                    clip=args.clip, aperture=window, full_output=True)
    except ValueError as exc:   # the library's option is --clip here
        raise ValueError(str(exc).replace("clip=", "--clip ")) from None
    _write(path, values, display, args)
    L = display.luminance_of(values)
    measured = {"mean_cd_m2": float(L.mean()), "rms_contrast": rms_contrast(L),
                "michelson_contrast": michelson_contrast(L), "luminance_range_cd_m2": [float(L.min()), float(L.max())],
                "clip_sd": args.clip, "clipped_fraction": report.clipped_fraction}
    if window is not None:
        measured["in_aperture"] = _measured_in_aperture(L, window, args.mean)
    if args.psychopy:
        from ..io import atomic_output

        lo, hi = display.luminance
        with atomic_output(_psychopy_path(path)) as tmp:
            with open(tmp, "wb") as f:
                np.save(f, (2.0 * (L - lo) / (hi - lo) - 1.0).astype(np.float32))
    return values, measured, used, window_used


def _psychopy_path(path):
    return path.with_name(f"{path.stem}_psychopy.npy")


def _summary(measured, args):
    text = (f"mean {measured['mean_cd_m2']:.4g} cd/m², RMS contrast {measured['rms_contrast']:.4g}, Michelson "
            f"{measured['michelson_contrast']:.4g} (requested {args.contrast_kind} {args.contrast:g} at "
            f"{args.mean:g} cd/m²)")
    if args.clip is not None:
        text += f"; clipped at {args.clip:g} sd: {100 * measured['clipped_fraction']:.3g} % of the samples"
    if "in_aperture" in measured:
        text += (f"; inside the {args.aperture} aperture: mean {measured['in_aperture']['mean_cd_m2']:.4g} cd/m², "
                 f"RMS contrast {measured['in_aperture']['rms_contrast']:.4g}")
    return text


def run(args):
    from .. import __version__
    from ..io import atomic_output, prepare_output

    if args.velocity_yx is not None and args.velocity is not None:
        raise ValueError("--velocity-yx and --velocity say the same thing in two orders; pass one")
    # (vx, vy) from here on, as MotionClouds' V_X, V_Y
    args.velocity = (tuple(args.velocity_yx[::-1]) if args.velocity_yx is not None
                     else tuple(args.velocity) if args.velocity is not None else (1.0, 0.0))
    path = Path(args.output)
    suffix = path.suffix.lower()
    if suffix not in LOSSLESS:
        raise ValueError(f"output must end in .png, .mkv, .mp4 or .npy, got {path.name!r}")
    if suffix == ".png" and args.kind in MOVING:
        raise ValueError(f"{path.name}: a PNG holds one frame; write the {args.kind} video to .mkv, .mp4 or .npy")
    if args.trials is not None and not 1 <= args.trials <= 100000:
        raise ValueError(f"--trials must be an int in [1, 100000], got {args.trials}")
    display = _display(args)
    lossless = LOSSLESS[suffix] or (suffix == ".mp4" and args.lossless)
    common = {
        "noiselab_version": __version__,
        "command": ["noiselab"] + sys.argv[1:] if Path(sys.argv[0]).name in ("noiselab", "__main__.py") else None,
        "kind": args.kind,
        "parameters": {k: v for k, v in vars(args).items() if not k.startswith("_") and k != "command"},
        "display": display.as_dict(),
    }
    output = {"format": suffix.lstrip("."), "lossless": lossless,
              "values": "display values: luminance = display's law (or lut) of each value"}
    if args.trials is None:
        prepare_output(path)
        if args.psychopy:
            prepare_output(_psychopy_path(path))
        values, measured, used, window_used = _make(args, display, path, args.seed)
        sidecar = {**common, "seed": args.seed, "pixel_units": used, "aperture": window_used,
                   "output": {"path": path.name, **output, "shape": list(values.shape), "dtype": str(values.dtype),
                              "psychopy": _psychopy_path(path).name if args.psychopy else None},
                   "measured_on_written_values": measured}
        side = path.with_name(path.name + ".json")
        with atomic_output(side) as tmp:
            Path(tmp).write_text(json.dumps(_jsonable(sidecar), indent=2) + "\n")
        print(f"noiselab stimulus: wrote {path} ({values.shape} {values.dtype}, "
              f"{'lossless' if lossless else 'LOSSY: H.264 changes grey levels'}) and {side.name}; "
              + _summary(measured, args))
        return 0
    from ..stimuli import trial_seeds

    seeds = trial_seeds(args.trials, rng=args.seed)
    paths = [path.with_name(f"{path.stem}_{i:0{max(3, len(str(args.trials - 1)))}d}{path.suffix}")
             for i in range(args.trials)]
    manifest_path = path.with_name(f"{path.stem}_manifest.json")
    for p in (*paths, *(map(_psychopy_path, paths) if args.psychopy else ()), manifest_path):
        prepare_output(p)
    trials = []
    for i, (p, seed) in enumerate(zip(paths, seeds)):
        values, measured, used, window_used = _make(args, display, p, seed)
        trials.append({"trial": i, "file": p.name, "seed": seed, "shape": list(values.shape),
                       "psychopy": _psychopy_path(p).name if args.psychopy else None,
                       "dtype": str(values.dtype), "measured_on_written_values": measured})
    manifest = {**common, "experiment_seed": args.seed,
                "seed_derivation": ("noiselab.stimuli.trial_seeds(trials, rng=experiment_seed): "
                                    "numpy.random.SeedSequence(experiment_seed).spawn(trials)[i].generate_state(1)[0]"
                                    "; trial i is the same command with --seed <its seed> and without --trials"),
                "pixel_units": used, "aperture": window_used, "output": output, "trials": trials}
    with atomic_output(manifest_path) as tmp:
        Path(tmp).write_text(json.dumps(_jsonable(manifest), indent=2) + "\n")
    where = "" if window_used is None else f" inside the {args.aperture} aperture"
    rms = [t["measured_on_written_values"]["in_aperture" if window_used else "rms_contrast"] for t in trials]
    rms = [r["rms_contrast"] if isinstance(r, dict) else r for r in rms]
    print(f"noiselab stimulus: wrote {args.trials} trials {paths[0].name} .. {paths[-1].name} and "
          f"{manifest_path.name}; RMS contrast{where} {min(rms):.4g} .. {max(rms):.4g} (requested "
          f"{args.contrast_kind} {args.contrast:g} at {args.mean:g} cd/m²)")
    return 0
