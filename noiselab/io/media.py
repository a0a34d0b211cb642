"""Images and videos through imageio (FFmpeg for MP4, Pillow for PNG/GIF), NPY through numpy.

Array convention everywhere in noiselab: a video is ``(frames, height, width)``
with an optional trailing colour axis of 3 (RGB); x runs right along columns,
y down along rows. Float data are taken to be in [0, 1] (alpha, normalised
intensity) unless ``vmin``/``vmax`` say otherwise.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .._progress import progress
from .._validate import check_finite_array, check_real
from .atomic import atomic_output

VIDEO_SUFFIXES = (".mp4", ".gif", ".npy")
IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".npy")


def to_uint8(array, vmin=None, vmax=None) -> np.ndarray:
    """Map an array to uint8: ints in [0, 255] pass through, floats map [vmin, vmax] (default [0, 1]) to [0, 255].

    Values outside the range are clipped (after the mapping); NaN or inf in
    ``array`` and a non-finite ``vmin``/``vmax`` are a ``ValueError``, complex
    or text arrays a ``TypeError``.
    """
    if isinstance(array, (str, bytes)) or array is None:
        raise TypeError(f"array must be a real numeric array, got {type(array).__name__}")
    array = np.asarray(array)
    if array.dtype == np.uint8:
        return array
    # NaN and inf are errors (inf has no place on a 0..255 scale); complex and str are TypeErrors
    array = check_finite_array("array", array)
    if array.dtype.kind in "iu" and vmin is None and vmax is None:
        if array.size and (array.min() < 0 or array.max() > 255):
            raise ValueError("integer image values must be in [0, 255]; pass vmin/vmax to rescale")
        return array.astype(np.uint8)
    lo = 0.0 if vmin is None else check_real("vmin", vmin)
    hi = 1.0 if vmax is None else check_real("vmax", vmax)
    if not hi > lo:
        raise ValueError(f"vmax must be greater than vmin, got vmin={lo}, vmax={hi}")
    if not np.isfinite(hi - lo):
        raise ValueError(f"vmax - vmin must be finite (below 1.8e308), got vmin={lo:g}, vmax={hi:g}")
    # float32 unless the range or the values need float64's exponent
    scale = 255.0 / (hi - lo)
    if not np.isfinite(scale):
        raise ValueError(f"vmax - vmin = {hi - lo:.3g} is too small: 255 / (vmax - vmin) overflows")
    big = max(abs(lo), abs(hi), scale) > 1e30 or (array.size and max(abs(float(array.min())),
                                                                  abs(float(array.max()))) > 1e30)
    array = array.astype(np.float64 if big else np.float32, copy=False)
    with np.errstate(over="ignore"):  # overflow past vmax is clipped to 255 below
        scaled = (array - lo) * scale
    return np.clip(np.rint(scaled), 0, 255).astype(np.uint8)


def write_image(path, image, *, vmin=None, vmax=None) -> Path:
    """Write one image (``(H, W)`` or ``(H, W, 3|4)``) to PNG/JPEG/TIFF, or the raw array to ``.npy``."""
    path = Path(path)
    image = np.asarray(image)
    suffix = path.suffix.lower()
    if suffix not in IMAGE_SUFFIXES:
        raise ValueError(f"image path must end in one of {IMAGE_SUFFIXES}, got {path.name!r}")
    if suffix == ".npy":
        with atomic_output(path) as tmp:
            np.save(tmp, image)
        return path
    if image.ndim not in (2, 3) or (image.ndim == 3 and image.shape[-1] not in (3, 4)):
        raise ValueError(f"image must have shape (H, W) or (H, W, 3|4), got {image.shape}")
    import imageio.v3 as iio

    with atomic_output(path) as tmp:
        iio.imwrite(tmp, to_uint8(image, vmin, vmax))
    return path


def _frame_source(frames):
    """Return (iterator over frames, count or None) for an array or an iterable of frames."""
    if isinstance(frames, np.ndarray):
        if frames.ndim not in (3, 4) or (frames.ndim == 4 and frames.shape[-1] not in (3, 4)):
            raise ValueError(f"video must have shape (T, H, W) or (T, H, W, 3), got {frames.shape}")
        return iter(frames), frames.shape[0]
    count = len(frames) if hasattr(frames, "__len__") else None
    return iter(frames), count


def write_video(path, frames, *, fps=25.0, vmin=None, vmax=None, show_progress=None, quality=8) -> Path:
    """Write a video to ``.mp4`` (H.264), ``.gif``, ``.npy``, or a folder of PNG frames.

    ``frames`` is an array ``(T, H, W[, 3])`` or any iterable of frames (a lazy
    frame iterator is streamed and never held in memory, except for ``.npy``).
    A path without a suffix is a folder that receives ``frame_00000.png``, ...
    The file (or folder) appears only when writing succeeded.
    """
    path = Path(path)
    fps = float(fps)
    if not np.isfinite(fps) or fps <= 0:
        raise ValueError(f"fps must be a positive finite number, got {fps}")
    suffix = path.suffix.lower()
    it, count = _frame_source(frames)
    bar = progress(it, total=count, desc=f"writing {path.name}", enabled=show_progress, unit="frame")
    if suffix == ".npy":
        data = frames if isinstance(frames, np.ndarray) else np.stack(list(bar))
        with atomic_output(path) as tmp:
            np.save(tmp, data)
        return path
    if suffix == "":
        with atomic_output(path, directory=True) as tmp:
            import imageio.v3 as iio

            for i, frame in enumerate(bar):
                iio.imwrite(tmp / f"frame_{i:05d}.png", to_uint8(frame, vmin, vmax))
        return path
    if suffix not in (".mp4", ".gif"):
        raise ValueError(f"video path must end in .mp4, .gif or .npy, or be a folder for PNG frames; got {path.name!r}")
    import imageio.v2 as iio2
    import imageio.v3 as iio

    with atomic_output(path) as tmp:
        if suffix == ".gif":
            # GIF is a preview format: frames are small uint8, so they are
            # gathered and written in one call (Pillow needs them all for the palette).
            gif = np.stack([to_uint8(frame, vmin, vmax) for frame in bar])
            iio.imwrite(tmp, gif, extension=".gif", duration=1000.0 / fps, loop=0)
            return path
        # yuv420p needs even sizes: odd frames are padded by one edge pixel.
        writer = iio2.get_writer(tmp, format="FFMPEG", mode="I", fps=fps, codec="libx264",
                                 quality=quality, macro_block_size=1, pixelformat="yuv420p",
                                 ffmpeg_log_level="error")
        try:
            for frame in bar:
                frame = to_uint8(frame, vmin, vmax)
                if frame.shape[0] % 2 or frame.shape[1] % 2:
                    pad = [(0, frame.shape[0] % 2), (0, frame.shape[1] % 2)] + [(0, 0)] * (frame.ndim - 2)
                    frame = np.pad(frame, pad, mode="edge")
                writer.append_data(frame)
        finally:
            writer.close()
    return path


def read_image(path, *, as_float=False) -> np.ndarray:
    """Read an image file (PNG/JPEG/TIFF...) or ``.npy`` array. ``as_float`` maps uint8 to [0, 1] float32."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no such image file: {str(path)!r}")
    if path.suffix.lower() == ".npy":
        image = np.load(path)
    else:
        import imageio.v3 as iio

        image = iio.imread(path)
        if image.ndim == 3 and image.shape[-1] == 4:
            image = image[..., :3]
    if as_float and image.dtype == np.uint8:
        image = image.astype(np.float32) / 255.0
    return image


def read_video(path, *, as_float=False, max_frames=None) -> np.ndarray:
    """Read a video (``.mp4``/``.gif``/``.npy``, or a folder of PNG frames) as ``(T, H, W[, 3])``.

    Grey videos stored as RGB (equal channels, as GIF and MP4 store them) come
    back with the colour axis dropped.
    """
    path = Path(path)
    if path.is_dir():
        import imageio.v3 as iio

        files = sorted(p for p in path.iterdir() if p.suffix.lower() == ".png")
        if not files:
            raise ValueError(f"folder {str(path)!r} holds no PNG frames")
        video = np.stack([iio.imread(p) for p in files[:max_frames]])
    elif not path.is_file():
        raise FileNotFoundError(f"no such video file: {str(path)!r}")
    elif path.suffix.lower() == ".npy":
        video = np.load(path)
    else:
        import imageio.v3 as iio

        frames = []
        for i, frame in enumerate(iio.imiter(path)):
            if max_frames is not None and i >= max_frames:
                break
            frames.append(frame)
        if not frames:
            raise ValueError(f"video {str(path)!r} has no frames")
        video = np.stack(frames)
    if video.ndim == 4 and video.shape[-1] == 4:
        video = video[..., :3]
    if video.ndim == 4 and video.shape[-1] == 3:
        spread = np.ptp(video.astype(np.int16), axis=-1) if video.dtype == np.uint8 else np.ptp(video, axis=-1)
        if spread.max() <= (2 if video.dtype == np.uint8 else 1e-6):
            video = video.mean(axis=-1).round().astype(video.dtype) if video.dtype == np.uint8 else video.mean(axis=-1)
    if as_float and video.dtype == np.uint8:
        video = video.astype(np.float32) / 255.0
    return video
