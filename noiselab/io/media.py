"""Images and videos through imageio (FFmpeg for MP4, Pillow for PNG/GIF), NPY through numpy.

Array convention everywhere in noiselab: a video is ``(frames, height, width)``
with an optional trailing colour axis of 3 (RGB); x runs right along columns,
y down along rows. Float data are taken to be in [0, 1] (alpha, normalised
intensity) unless ``vmin``/``vmax`` say otherwise.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .._core import progress
from .._core import check_finite_array, check_real
from .atomic import atomic_output, forget_process, hold_signals, track_process
from .errors import InputError, cause, input_error, output_error

VIDEO_SUFFIXES = (".mp4", ".gif", ".npy")
IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".npy")
#: frames per second of every video noiselab writes unless told otherwise (CLI and library)
DEFAULT_FPS = 25.0


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
    data = _encode(to_uint8(image, vmin, vmax), suffix)
    with atomic_output(path) as tmp:
        Path(tmp).write_bytes(data)
    return path


def _encode(image, suffix, **kwargs) -> bytes:
    """Encode an image (or a GIF's frames) in memory, so that writing the file is one plain write.

    A failed write then raises one clean ``OSError`` here, instead of a second
    error when the encoder's half-closed file is collected.
    """
    import imageio.v3 as iio

    return iio.imwrite("<bytes>", image, extension=suffix, **kwargs)


def _frame_source(frames):
    """Return (iterator over frames, count or None) for an array or an iterable of frames."""
    if isinstance(frames, np.ndarray):
        if frames.ndim not in (3, 4) or (frames.ndim == 4 and frames.shape[-1] not in (3, 4)):
            raise ValueError(f"video must have shape (T, H, W) or (T, H, W, 3), got {frames.shape}")
        return iter(frames), frames.shape[0]
    count = len(frames) if hasattr(frames, "__len__") else None
    return iter(frames), count


def write_video(path, frames, *, fps=DEFAULT_FPS, vmin=None, vmax=None, show_progress=None, quality=8) -> Path:
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
            for i, frame in enumerate(bar):
                (tmp / f"frame_{i:05d}.png").write_bytes(_encode(to_uint8(frame, vmin, vmax), ".png"))
        return path
    if suffix not in (".mp4", ".gif"):
        raise ValueError(f"video path must end in .mp4, .gif or .npy, or be a folder for PNG frames; got {path.name!r}")
    with atomic_output(path) as tmp:
        if suffix == ".gif":
            # GIF is a preview format: frames are small uint8, so they are
            # gathered and written in one call (Pillow needs them all for the palette).
            gif = np.stack([to_uint8(frame, vmin, vmax) for frame in bar])
            Path(tmp).write_bytes(_encode(gif, ".gif", duration=1000.0 / fps, loop=0))
            return path
        _write_mp4(tmp, bar, fps, quality, vmin, vmax)
    return path


def _write_mp4(path, frames, fps, quality, vmin, vmax):
    """H.264 through imageio-ffmpeg's ffmpeg binary, with the arguments imageio's FFMPEG writer uses.

    ffmpeg runs here rather than through imageio's writer because that writer
    ignores ffmpeg's exit status: on a full disk it returns normally and leaves
    a truncated file. Here a failing ffmpeg raises ``OutputError`` with its
    reason (e.g. "No space left on device").
    """
    import subprocess
    import tempfile
    from fractions import Fraction

    import imageio_ffmpeg

    proc = None
    errlog = tempfile.TemporaryFile()
    try:
        for frame in frames:
            frame = to_uint8(frame, vmin, vmax)
            # yuv420p needs even sizes: odd frames are padded by one edge pixel.
            if frame.shape[0] % 2 or frame.shape[1] % 2:
                pad = [(0, frame.shape[0] % 2), (0, frame.shape[1] % 2)] + [(0, 0)] * (frame.ndim - 2)
                frame = np.pad(frame, pad, mode="edge")
            if proc is None:
                shape = frame.shape
                pix_fmt = {2: "gray", 3: "rgb24"}[frame.ndim] if frame.ndim == 2 or frame.shape[-1] == 3 else "rgba"
                crf = int((1 - quality / 10.0) * 51)   # imageio-ffmpeg's quality -> crf (8 -> 10)
                rate = str(Fraction(fps).limit_denominator())
                cmd = [imageio_ffmpeg.get_ffmpeg_exe(), "-y", "-f", "rawvideo", "-vcodec", "rawvideo",
                       "-s", f"{shape[1]}x{shape[0]}", "-pix_fmt", pix_fmt, "-r", rate, "-i", "-", "-an",
                       "-vcodec", "libx264", "-pix_fmt", "yuv420p", "-crf", str(crf), "-v", "error", str(path)]
                with hold_signals():   # never an ffmpeg running that `proc` (and a stopping signal) does not know
                    proc = track_process(subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.DEVNULL,
                                                          stderr=errlog))
            elif frame.shape != shape:
                raise ValueError(f"all frames must have one shape: frame of shape {frame.shape} after {shape}")
            try:
                proc.stdin.write(np.ascontiguousarray(frame).tobytes())
            except BrokenPipeError:   # ffmpeg stopped: its exit status and message say why
                break
        if proc is None:
            raise ValueError("no frames to write")
        try:
            proc.stdin.close()
        except BrokenPipeError:
            pass
        code = proc.wait()
        if code != 0:
            errlog.seek(0)
            lines = [ln.strip() for ln in errlog.read().decode(errors="replace").splitlines() if ln.strip()]
            text = "\n".join(lines)
            reason = cause(RuntimeError(text))   # an OS error named anywhere in ffmpeg's messages
            if reason == (lines[0] if lines else ""):
                reason = lines[-1].split("] ", 1)[-1] if lines else f"ffmpeg exited with status {code}"
            raise output_error(path, RuntimeError(reason))
    finally:
        if proc is not None and proc.poll() is None:   # interrupted: stop the encoder before the file is removed
            proc.kill()
            proc.wait()
        if proc is not None:
            forget_process(proc)
        errlog.close()


def _check_readable(path, what):
    if path.is_dir():
        raise InputError(path, f"it is a folder, not {what}")
    if not path.exists():
        raise FileNotFoundError(f"no such {what}: {str(path)!r}")
    try:
        with open(path, "rb") as fh:
            head = fh.read(1)
    except OSError as exc:
        raise input_error(path, exc) from None
    if not head:
        raise InputError(path, "the file is empty (0 bytes)")


def load_npy(path) -> np.ndarray:
    """``numpy.load`` of a ``.npy`` file (no pickles), with one-line ``InputError`` for a file numpy cannot read."""
    path = Path(path)
    _check_readable(path, "array file")
    try:
        return np.load(path, allow_pickle=False)
    except MemoryError:
        raise
    except Exception as exc:
        if isinstance(exc, OSError) or "truncated" in str(exc) or isinstance(exc, EOFError):
            raise input_error(path, exc) from None
        if "pickle" in str(exc):
            raise InputError(path, "it holds pickled Python objects, not a numeric array") from None
        raise InputError(path, f"not a valid .npy array file ({cause(exc)})") from None


def _imread(path, **kwargs):
    import imageio.v3 as iio

    try:
        return iio.imread(path, **kwargs)
    except MemoryError:
        raise
    except Exception as exc:   # any decoder failure on a user's file is an input error, said in one line
        raise _decode_error(path, exc, "image") from None


def _decode_error(path, exc, what):
    text = str(exc)
    if isinstance(exc, (OSError, EOFError)) and ("truncated" in text or getattr(exc, "errno", None)):
        return input_error(path, exc)
    if "Could not find a backend" in text or "Could not load meta" in text:
        return InputError(path, f"not a{'n' if what[0] in 'aeiou' else ''} {what} file that imageio can decode "
                                f"(truncated, or another format?)")
    return InputError(path, f"not a valid {Path(path).suffix.lstrip('.').upper() or what} {what} ({cause(exc)})")


def read_image(path, *, as_float=False) -> np.ndarray:
    """Read an image file (PNG/JPEG/TIFF...) or ``.npy`` array. ``as_float`` maps uint8 to [0, 1] float32.

    A missing file is a ``FileNotFoundError``; a file that cannot be decoded
    (truncated, empty, not an image, no read permission) an ``InputError``
    (a ``ValueError``) naming the file and the cause.
    """
    path = Path(path)
    _check_readable(path, "image file")
    if path.suffix.lower() == ".npy":
        image = load_npy(path)
    else:
        image = _imread(path)
        if image.ndim == 3 and image.shape[-1] == 4:
            image = image[..., :3]
    if as_float and image.dtype == np.uint8:
        image = image.astype(np.float32) / 255.0
    return image


def _png_frames(path):
    files = sorted(p for p in path.iterdir() if p.suffix.lower() == ".png")
    if not files:
        raise InputError(path, "the folder holds no PNG frames")
    return files


def iter_video(path, *, max_frames=None):
    """Yield the frames of a video file (``.mp4``/``.gif``) or a folder of PNG frames one at a time.

    Only one decoded frame is held at a time (``analyze`` streams long videos
    through this). Frames come as decoded (uint8, RGB or grey, alpha dropped).
    Unreadable files raise ``InputError`` naming the file (for a folder, the
    bad frame) and the cause.
    """
    path = Path(path)
    if path.is_dir():
        for f in _png_frames(path)[:max_frames]:
            _check_readable(f, "PNG frame")
            frame = _imread(f)
            yield frame[..., :3] if frame.ndim == 3 and frame.shape[-1] == 4 else frame
        return
    _check_readable(path, "video file")
    import imageio.v3 as iio

    n = 0
    try:
        for frame in iio.imiter(path):
            if max_frames is not None and n >= max_frames:
                break
            n += 1
            yield frame[..., :3] if frame.ndim == 3 and frame.shape[-1] == 4 else frame
    except MemoryError:
        raise
    except Exception as exc:
        raise _decode_error(path, exc, "video") from None
    if n == 0:
        raise InputError(path, "the video has no frames")


def read_video(path, *, as_float=False, max_frames=None) -> np.ndarray:
    """Read a video (``.mp4``/``.gif``/``.npy``, or a folder of PNG frames) as ``(T, H, W[, 3])``.

    Grey videos stored as RGB (equal channels, as GIF and MP4 store them) come
    back with the colour axis dropped. Unreadable input raises ``InputError``
    (a ``ValueError``) naming the file and the cause.
    """
    path = Path(path)
    if path.suffix.lower() == ".npy" and not path.is_dir():
        video = load_npy(path)
    else:
        frames = list(iter_video(path, max_frames=max_frames))
        if len({f.shape for f in frames}) > 1:
            raise InputError(path, f"the frames differ in shape ({frames[0].shape} and others)")
        video = np.stack(frames)
        del frames
    if video.ndim == 4 and video.shape[-1] == 4:
        video = video[..., :3]
    if video.ndim == 4 and video.shape[-1] == 3:
        spread = np.ptp(video.astype(np.int16), axis=-1) if video.dtype == np.uint8 else np.ptp(video, axis=-1)
        if spread.max() <= (2 if video.dtype == np.uint8 else 1e-6):
            video = video.mean(axis=-1).round().astype(video.dtype) if video.dtype == np.uint8 else video.mean(axis=-1)
    if as_float and video.dtype == np.uint8:
        video = video.astype(np.float32) / 255.0
    return video
