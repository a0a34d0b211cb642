"""``noiselab analyze FILE``: measure an image, video or volume with the analysis instruments.

Prints a short report (contrast, 1/f slope, anisotropy, energy per octave;
for videos the loop seam, the best single velocity and the speed of each
spatial-frequency band) and optionally writes a figure (``--plot``) and the
numbers as JSON (``--json``), both atomically.

Examples::

    noiselab analyze out/snow.mp4 --plot out/snow_analysis.png
    noiselab analyze photo.png --window hann --band 4 64
    noiselab analyze field.npy --as volume --json out/field.json
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

NAME = "analyze"
HELP = ("Measure an image, video or volume (PNG, NPY, MP4/GIF): 1/f slope, anisotropy, band energy and leakage, "
        "lattice artefacts, period, velocity and speed per band.")

_IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp")
_VIDEO_SUFFIXES = (".mp4", ".gif")


def add_arguments(parser):
    parser.add_argument("file", help="input: .png/.jpg/.tif image, .mp4/.gif video, .npy array, .zarr store, "
                                     "or a folder of PNG frames")
    parser.add_argument("--as", dest="kind", default="auto", choices=("auto", "image", "video", "volume", "signal"),
                        help="how to read a 3-D .npy array: (frames, height, width) video (auto) or a volume; "
                             "RGB (trailing axis of 3) is turned to grey (default: auto)")
    parser.add_argument("--band", nargs=2, type=float, metavar=("LO", "HI"), default=None,
                        help="band of the slope fit and the anisotropy in cycles/frame (default: 2 to a quarter "
                             "of the frame width, with each side moved to an edge where the field's power falls "
                             "off by 10x or more (noiselab.analysis.power_band); the report says which band it used)")
    parser.add_argument("--window", default="auto", choices=("auto", "none", "hann"),
                        help="spatial taper before the FFT: auto = Hann when the field does not tile "
                             "(tile seam above 1.5), else none (default: auto)")
    parser.add_argument("--bands-per-octave", type=int, default=2,
                        help="speed-per-band resolution for videos (default: %(default)s)")
    parser.add_argument("--max-frames", type=int, default=None, help="read at most this many frames of a video")
    parser.add_argument("--plot", default=None, metavar="PATH",
                        help="write a figure (radial spectrum; speed per band for videos) to PATH (.png/.pdf/.svg)")
    parser.add_argument("--json", default=None, metavar="PATH", help="write the measurements as JSON to PATH")


def _frame_count(path):
    """The number of frames of a video file or folder without decoding it (None when unknown)."""
    try:
        if path.is_dir():
            return sum(1 for p in path.iterdir() if p.suffix.lower() == ".png")
        if path.suffix.lower() == ".gif":
            from PIL import Image

            with Image.open(path) as im:
                return int(getattr(im, "n_frames", 1))
        import imageio_ffmpeg

        return int(imageio_ffmpeg.count_frames_and_secs(str(path))[0])   # a stream copy, no decoding
    except Exception:   # unreadable: iter_video below says why
        return None


def _stream_grey_video(path, max_frames=None):
    """Decode a video file or PNG-frame folder frame by frame into one grey float32 array.

    The frames are counted first (without decoding) and written one by one into
    the preallocated ``(frames, height, width)`` float32 result, so the peak is
    that array plus one decoded frame, not the decoded RGB video and its copies.
    """
    from ..analysis import to_grey
    from ..io import InputError, iter_video

    count = _frame_count(path)
    if count is not None and max_frames is not None:
        count = min(count, max_frames)
    out, n = None, 0
    for frame in iter_video(path, max_frames=max_frames):
        g = to_grey(frame.astype(np.float32) / 255.0 if frame.dtype == np.uint8 else frame.astype(np.float32))
        if out is None:
            out = np.empty((max(count or 1, 1),) + g.shape, np.float32)
        elif g.shape != out.shape[1:]:
            raise InputError(path, f"frame {n} has shape {g.shape}, the first {out.shape[1:]}")
        if n == out.shape[0]:   # the count was short: grow (rare)
            out = np.concatenate([out, np.empty_like(out[: max(1, n // 2)])])
        out[n] = g
        n += 1
    if out is None:
        raise InputError(path, "the video has no frames")
    return out if n == out.shape[0] else out[:n].copy()


def load(path, kind="auto", max_frames=None):
    """Read ``path`` and return ``(array, kind)`` with kind in image/video/volume/signal; RGB becomes grey."""
    from ..analysis import to_grey
    from ..io import InputError, load_npy, read_image

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".zarr":  # a store written by noiselab noise/write_zarr: read whole (the analysers work in memory)
        from ..io.zarr import read_zarr
        data = read_zarr(path)
        data = (data[:max_frames] if max_frames is not None and data.ndim == 3 and kind != "volume" else data).compute()
    elif path.is_dir() or suffix in _VIDEO_SUFFIXES:
        data = _stream_grey_video(path, max_frames)
        if data.ndim == 3 and data.shape[0] == 1:
            data = data[0]
    elif suffix in _IMAGE_SUFFIXES:
        data = to_grey(read_image(path, as_float=True))
    elif suffix == ".npy":
        data = load_npy(path)
        if data.size == 0:
            raise InputError(path, f"it holds an empty array of shape {data.shape}: nothing to measure")
        if data.dtype == np.uint8:
            data = data.astype(np.float32) / 255.0
        if data.ndim in (3, 4) and data.shape[-1] in (3, 4) and kind != "volume":
            data = to_grey(data)
        if max_frames is not None and data.ndim == 3 and kind != "volume":
            data = data[:max_frames]
    else:
        raise ValueError(f"cannot analyse {path.name!r}: expected .png/.jpg/.tif, .mp4/.gif, .npy or a folder of PNG frames")
    data = np.asarray(data)
    if data.dtype.kind not in "biuf":
        raise InputError(path, f"it holds {data.dtype} data, not a real numeric array")
    if data.size == 0:
        raise InputError(path, f"it holds an empty array of shape {data.shape}: nothing to measure")
    guess = {1: "signal", 2: "image", 3: "video"}.get(data.ndim)
    if guess is None:
        raise ValueError(f"{path.name} holds a {data.ndim}-D array of shape {data.shape}; expected 1-, 2- or 3-D (plus RGB)")
    if kind == "auto":
        kind = guess
    elif {"signal": 1, "image": 2, "video": 3, "volume": 3}[kind] != data.ndim:
        raise ValueError(f"--as {kind} does not fit a {data.ndim}-D array of shape {data.shape}")
    if data.dtype.kind != "f":
        data = data.astype(np.float32)
    return data, kind


def _fit_band(spec, n_ref, band):
    """The slope band and how it was found: ``(lo, hi, how)``, ``how`` a phrase for the report.

    The band asked for; else the default (2 to a quarter of the frame width)
    with each side replaced by an edge of :func:`noiselab.analysis.power_band`
    where the field's spectrum falls off a cliff (a band-limited field:
    snow, band-limited noise); a field with no edge keeps the default.
    """
    from ..analysis import power_band
    from ..analysis.slope import default_band

    if band is not None:
        return float(band[0]), float(band[1]), "given (--band)"
    lo, hi = default_band(n_ref)
    pb = power_band(spec)
    found = []
    if pb.limited[0]:
        lo = pb.lo
        found.append(f"falls {pb.drop[0]:.1f} decades below {pb.lo:g}")
    if pb.limited[1]:
        hi = pb.hi
        found.append(f"falls {pb.drop[1]:.1f} decades above {pb.hi:g}")
    elif pb.limited[0] and lo >= hi / 1.5:  # power only above N/4: up to Nyquist
        hi = pb.hi
    if not found:
        return lo, hi, "default: 2 to a quarter of the width (the power has no band edge)"
    return lo, hi, "found where the field has power (power_band: the power " + " and ".join(found) + ")"


def measure(data, kind, *, band=None, window="auto", bands_per_octave=2):
    """All the measurements of the report, as a dict of plain Python values (and arrays for the figure)."""
    from .. import analysis as A

    out = {"kind": kind, "shape": list(data.shape), "mean": float(np.mean(data, dtype=np.float64)),
           "std": float(np.std(data, dtype=np.float64))}
    if out["std"] == 0:
        raise ValueError(f"the {kind} is constant (every value is {out['mean']:g}): nothing to measure")
    if float(np.min(data)) >= 0 and out["mean"] > 0:
        out["rms_contrast"] = A.rms_contrast(data)
        out["michelson_contrast"] = A.michelson_contrast(data)
    spatial = kind in ("image", "video")
    if window == "auto":
        seam = A.tile_seam(data) if spatial else None
        out["tile_seam"] = seam
        window = "hann" if (seam is not None and seam > 1.5) else None
    elif window == "none":
        window = None
    out["window"] = window or "none"
    axes = (-2, -1) if kind == "video" else None
    spec = A.power_spectrum(data, window=window, axes=axes)
    n_ref = data.shape[-1]
    lo, hi, how = _fit_band(spec, n_ref, band)
    out["band"] = {"band": [lo, hi], "how": how}
    try:
        fit = A.spectral_slope(spec, (lo, hi))
        out["slope"] = {"amplitude": float(fit), "error": fit.error, "power": fit.power_slope,
                        "power_error": fit.power_error, "band": list(fit.band), "intercept": fit.intercept}
    except ValueError as exc:
        if band is not None:  # the user's band: tell them what is wrong with it
            raise
        out["slope"] = {"error_message": str(exc), "band": [lo, hi]}
    rs = A.radial_spectrum(spec, log=True)
    out["radial"] = {"frequency": rs.centers.tolist(), "amplitude": rs.amplitude.tolist()}
    if n_ref >= 8:
        oe = A.octave_energy(spec, (1.0, n_ref / 2.0))
        out["octave_energy"] = {"edges": oe.edges.tolist(), "fraction": oe.energy.tolist(), "spread": oe.spread}
    if spatial and min(data.shape[-2:]) >= 8:
        # over the band found or given (a band-limited field's floor outside it is not the field's orientation)
        o = A.orientation_energy(spec, None if how.startswith("default") else _orientation_band(lo, hi, data.shape))
        out["anisotropy"] = {"index": o.index, "m2": o.m2, "m4": o.m4, "dominant_deg": o.dominant,
                             "axis_ratio": o.axis_ratio, "angles_deg": o.angles.tolist(),
                             "energy": o.energy.tolist()}
    out["quality"] = _quality(data, kind, spec, (lo, hi), window)
    del spec
    if kind == "video" and data.shape[0] >= 3:
        try:
            out["loop_seam"] = A.loop_seam(data)
        except ValueError:  # frames all equal: a still
            out["loop_seam"] = None
    if kind == "video" and data.shape[0] >= 4 and out.get("loop_seam", 1) is None:
        out["velocity"] = None  # a still: no motion to measure
    elif kind == "video" and data.shape[0] >= 4:
        # time tapered (the video need not loop); each pixel's temporal mean removed, so a still
        # background under moving snow does not drag every band's velocity towards zero
        vspec = A.video_spectrum(data, window="hann", remove_static=True)
        v = A.best_velocity(vspec)
        out["velocity"] = [float(v[0]), float(v[1])]
        prof = A.speed_profile(vspec, per_octave=bands_per_octave)
        out["speed_per_band"] = {
            "bands": prof.bands.tolist(), "center": prof.centers.tolist(), "velocity": prof.velocity.tolist(),
            "speed": prof.speed.tolist(), "coherence": prof.coherence.tolist(), "energy": prof.energy.tolist(),
            "speed_x_w": prof.parallax.tolist(),
        }
    return out


def _orientation_band(lo, hi, shape):
    """``(lo, hi)`` kept inside what orientation_energy resolves: at least 2 cycles/frame, at most Nyquist."""
    lo, hi = max(lo, 2.0), min(hi, shape[-1] / 2.0)
    return (lo, hi) if hi > lo else None


def report(path, m) -> str:
    shape = " x ".join(map(str, m["shape"]))
    names = {"image": "(height x width)", "video": "(frames x height x width)", "volume": "(depth x height x width)",
             "signal": "(samples)"}
    lines = [f"{path}", f"  {m['kind']:<14}{shape} {names[m['kind']]}"]
    contrast = f"  {'mean':<14}{m['mean']:.4g}   std {m['std']:.4g}"
    if "rms_contrast" in m:
        contrast += f"   RMS contrast {m['rms_contrast']:.3f}   Michelson {m['michelson_contrast']:.3f}"
    lines.append(contrast)
    win = m["window"]
    if m.get("tile_seam") is not None:
        win += f" (tile seam {m['tile_seam']:.2f}: {'tiles' if m['tile_seam'] <= 1.5 else 'does not tile'})"
    lines.append(f"  {'window':<14}{win}")
    if "band" in m:
        lines.append(f"  {'band':<14}{m['band']['band'][0]:g}-{m['band']['band'][1]:g} cycles/frame, {m['band']['how']}")
    s = m["slope"]
    if "amplitude" in s:
        lines.append(f"  {'1/f slope':<14}amplitude {s['amplitude']:+.3f} +- {s['error']:.3f}   "
                     f"power {s['power']:+.3f} +- {s['power_error']:.3f}   over {s['band'][0]:g}-{s['band'][1]:g} cycles/frame")
    else:
        lines.append(f"  {'1/f slope':<14}n/a: {s['error_message']}")
    if "anisotropy" in m:
        a = m["anisotropy"]
        lines.append(f"  {'anisotropy':<14}{a['index']:.3f}   (two-fold {a['m2']:.3f}, four-fold {a['m4']:.3f}, "
                     f"axis/diagonal energy {a['axis_ratio']:.2f}, dominant wave vector {a['dominant_deg']:.0f} deg)")
    if "octave_energy" in m:
        o = m["octave_energy"]
        cells = "  ".join(f"{lo:g}-{hi:g}: {100 * f:.1f}%" for lo, hi, f in zip(o["edges"][:-1], o["edges"][1:], o["fraction"]))
        lines.append(f"  {'band energy':<14}{cells}   (spread {o['spread']:.2f})")
    lines += _quality_lines(m.get("quality", {}))
    if m.get("loop_seam") is None and "loop_seam" in m:
        lines.append(f"  {'loop seam':<14}n/a (the frames do not change)")
    elif "loop_seam" in m:
        lines.append(f"  {'loop seam':<14}{m['loop_seam']:.3f}   (1 = seamless loop)")
    if "velocity" in m and m["velocity"] is None:
        lines.append(f"  {'velocity':<14}n/a (the frames do not change)")
    elif "velocity" in m:
        vx, vy = m["velocity"]
        lines.append(f"  {'velocity':<14}vx {vx:+.3f}  vy {vy:+.3f} px/frame (best single velocity, +y down; "
                     "still part removed)")
        sp = m["speed_per_band"]
        lines.append(f"  speed per band (cycles/frame)      vx       vy    speed  speed*|w|  coherence  energy")
        for (lo, hi), (bvx, bvy), spd, pw, coh, e in zip(sp["bands"], sp["velocity"], sp["speed"], sp["speed_x_w"],
                                                         sp["coherence"], sp["energy"]):
            lines.append(f"  {'':<16}{lo:6.1f}-{hi:<6.1f}  {bvx:+7.3f}  {bvy:+7.3f}  {spd:7.3f}  {pw:9.3f}  {coh:9.3f}  {100 * e:5.1f}%")
    return "\n".join(lines)


def plot(path, m) -> Path:
    """Write the figure atomically (format from the suffix)."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    from ..io import atomic_output

    path = Path(path)
    panels = ["radial"] + (["orientation"] if "anisotropy" in m else []) + (["speed"] if "speed_per_band" in m else [])
    fig, axes = plt.subplots(1, len(panels), figsize=(4.6 * len(panels) + 0.6, 4.2), squeeze=False)
    ax = axes[0, 0]
    f = np.asarray(m["radial"]["frequency"])
    a = np.asarray(m["radial"]["amplitude"])
    ok = a > 0
    ax.loglog(f[ok], a[ok], ".-", lw=1, ms=3, label="radially averaged amplitude")
    s = m["slope"]
    if "amplitude" in s:
        lo, hi = s["band"]
        ff = np.geomspace(lo, hi, 20)
        ax.loglog(ff, 10 ** s["intercept"] * ff ** s["amplitude"], "r-", lw=2,
                  label=f"fit {s['amplitude']:+.2f} +- {s['error']:.2f} ({lo:g}-{hi:g})")
    ax.set_xlabel("spatial frequency (cycles/frame)")
    ax.set_ylabel("amplitude")
    ax.set_title("radial spectrum")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    if "orientation" in panels:
        an = m["anisotropy"]
        ax = axes[0, panels.index("orientation")]
        ax.plot(an["angles_deg"], an["energy"], "o-", ms=3)
        ax.axhline(1.0, color="k", lw=0.8, ls="--")
        ax.set_xlim(0, 180)
        ax.set_xticks(range(0, 181, 45))
        ax.set_xlabel("wave-vector orientation (deg, y down)")
        ax.set_ylabel("energy / mean (radially whitened)")
        ax.set_title(f"orientation: anisotropy {an['index']:.3f}")
        ax.grid(True, alpha=0.3)
    if "speed" in panels:
        sp = m["speed_per_band"]
        ax = axes[0, panels.index("speed")]
        c = np.asarray(sp["center"])
        v = np.asarray(sp["velocity"])
        ax.loglog(c, np.asarray(sp["speed"]), "o-", label="speed |v|")
        k = float(np.median(np.asarray(sp["speed"]) * c))
        ax.loglog(c, k / c, "k--", lw=1, label="speed x f constant (parallax law)")
        for ci, (vx, vy) in zip(c, v):
            ax.annotate(f"({vx:+.2f}, {vy:+.2f})", (ci, np.hypot(vx, vy)), fontsize=6, xytext=(3, 3),
                        textcoords="offset points")
        ax.set_xlabel("band centre (cycles/frame)")
        ax.set_ylabel("speed (px/frame)")
        ax.set_title("speed per band (vx, vy) px/frame")
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    try:
        with atomic_output(path) as tmp:
            fig.savefig(tmp, format=path.suffix.lstrip(".").lower() or "png", dpi=120)
    finally:
        plt.close(fig)
    return path


def run(args) -> int:
    from .._core import check_int
    from ..io import atomic_output

    if args.max_frames is not None:
        check_int("--max-frames", args.max_frames, lo=1)
    check_int("--bands-per-octave", args.bands_per_octave, lo=1, hi=8)
    if args.plot is not None and Path(args.plot).suffix.lower() not in (".png", ".pdf", ".svg"):
        raise ValueError(f"--plot must end in .png, .pdf or .svg, got {args.plot!r}")
    from ..io import prepare_output

    for out in (args.plot, args.json):   # fail now, not after measuring
        if out is not None:
            prepare_output(out)
    data, kind = load(args.file, args.kind, args.max_frames)
    m = measure(data, kind, band=args.band, window=args.window, bands_per_octave=args.bands_per_octave)
    print(report(args.file, m))
    if args.plot is not None:
        plot(args.plot, m)
        print(f"  figure        {args.plot}")
    if args.json is not None:
        with atomic_output(args.json) as tmp:
            Path(tmp).write_text(json.dumps(m, indent=1))
        print(f"  numbers       {args.json}")
    return 0


def _quality(data, kind, spec, band, window):
    """The literature's measures (noiselab.analysis.quality) that apply to one array without its generator."""
    from .. import analysis as A

    q = {}
    st = A.value_statistics(data)
    q["range"] = {"min": st.min, "max": st.max, "range_sd": st.range_sd}
    try:
        leak = A.band_leakage(spec, band)
        q["band_leakage"] = {"band": list(leak.band), "below": leak.below, "inside": leak.inside, "above": leak.above,
                             "octave_edges": leak.edges.tolist(), "octave_fraction": leak.octaves.tolist()}
    except ValueError:
        pass
    if kind in ("image", "video") and min(data.shape[-2:]) >= 8:
        ra = A.ring_anisotropy(spec)
        q["ulichney"] = {"mean_db": ra.mean_db, "floor_db": ra.floor_db, "periodograms": ra.periodograms}
    if kind == "image" and min(data.shape) >= 8:
        art = A.axis_artefacts(data, window=window)
        q["axis_artefacts"] = {"axis_excess": art.axis_excess, "axis_power": art.axis_power,
                               "row_mean_spread": art.row_mean_spread, "column_mean_spread": art.column_mean_spread}
    if kind in ("image", "signal", "volume") and data.shape[-1] >= 8:
        q["period_x"] = A.detect_period(data, axis=-1).period
    if kind == "volume" and min(data.shape) >= 8:
        sl = A.slice_leakage(data, band, window=window)
        q["slice_leakage"] = {"band": list(sl.band), "volume_outside": sl.volume.outside,
                              "slice_outside": sl.slices.outside, "added_below": sl.added_below}
    return q


def _quality_lines(q):
    lines = []
    if "band_leakage" in q:
        b = q["band_leakage"]
        lines.append(f"  {'band leakage':<14}{100 * b['below']:.2f}% below, {100 * b['above']:.2f}% above "
                     f"{b['band'][0]:g}-{b['band'][1]:g} cycles/frame")
    if "ulichney" in q:
        u = q["ulichney"]
        lines.append(f"  {'Ulichney':<14}{u['mean_db']:+.1f} dB   (isotropic Gaussian field: {u['floor_db']:+.1f} dB "
                     f"for {u['periodograms']} periodogram(s))")
    if "axis_artefacts" in q:
        a = q["axis_artefacts"]
        lines.append(f"  {'lattice axes':<14}axis excess {a['axis_excess']:.2f} (1 = isotropic)   row/column-mean "
                     f"spread {a['row_mean_spread']:.3f} / {a['column_mean_spread']:.3f} sd")
    if "period_x" in q:
        p = q["period_x"]
        lines.append(f"  {'period (x)':<14}" + ("none within half the width" if p is None else f"repeats every {p} samples"))
    if "slice_leakage" in q:
        s = q["slice_leakage"]
        lines.append(f"  {'slices':<14}outside {s['band'][0]:g}-{s['band'][1]:g}: volume {100 * s['volume_outside']:.2f}%, "
                     f"2-D slices {100 * s['slice_outside']:.2f}% (+{100 * s['added_below']:.2f}% below)")
    if "range" in q:
        r = q["range"]
        lines.append(f"  {'range':<14}{r['min']:.4g} .. {r['max']:.4g}   ({r['range_sd']:.2f} sd)")
    return lines
