"""Images and videos through imageio (FFmpeg for MP4, Pillow for PNG/GIF), NPY through numpy.

Array convention everywhere in noiselab: a video is ``(frames, height, width)``
with an optional trailing colour axis of 3 (RGB); x runs right along columns,
y down along rows. Float data are taken to be in [0, 1] (alpha, normalised
intensity) unless ``vmin``/``vmax`` say otherwise; float values outside [0, 1]
with no range stated are an error, never clipped silently.

Which formats keep a stimulus: ``.npy`` (the array itself), PNG and ``.mkv``
(FFV1, lossless 8-bit) and ``.mp4`` with ``lossless=True`` (H.264 RGB,
``-qp 0``) keep every grey level; the default ``.mp4`` (H.264 yuv420p,
crf 10) and ``.gif`` are lossy previews (``benchmarks/bench_stimuli.md``
measures the Michelson contrast after a round trip through each).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .._core import check_finite_array, check_real, renamed_parameters
from .._core import progress as progress_bar
from .atomic import atomic_output, forget_process, hold_signals, track_process
from .errors import InputError, cause, input_error, output_error

VIDEO_SUFFIXES = (".mp4", ".mkv", ".gif", ".npy")
IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".npy")
#: frames per second of every video noiselab writes unless told otherwise (CLI and library)
DEFAULT_FPS = 25.0


def to_uint8(array, vmin=None, vmax=None, *, clip=False) -> np.ndarray:
    """Map an array to uint8: ints in [0, 255] pass through, floats map [vmin, vmax] (default [0, 1]) to [0, 255].

    With no range stated, float values outside [0, 1] (beyond a float32
    rounding of 1e-6) are a ``ValueError`` saying how many and what range to
    state, unless ``clip=True``: a unit-variance noise field is never clipped
    silently. Values outside a *stated* range ``[vmin, vmax]`` are clipped to
    its ends (the caller chose the range). NaN or inf in ``array`` and a
    non-finite ``vmin``/``vmax`` are a ``ValueError``, complex or text arrays
    a ``TypeError``.

    Parameters
    ----------
    array : array_like
        Integers in [0, 255], or floats.
    vmin, vmax : float, optional
        The float range mapped to [0, 255] (default [0, 1]); values outside a stated range are clipped.
    clip : bool, default False
        Clip floats outside [0, 1] when no range is stated (otherwise a ``ValueError``).

    Returns
    -------
    ndarray of uint8

    Raises
    ------
    ValueError
        For NaN or inf in ``array``, a non-finite ``vmin`` / ``vmax``, or floats outside [0, 1]
        with no range stated and ``clip=False``.
    TypeError
        For complex or text arrays.

    Examples
    --------
    >>> import numpy as np
    >>> to_uint8(np.array([0.0, 0.5, 1.0])).tolist()
    [0, 128, 255]
    >>> to_uint8(np.array([-2.0, 0.0, 2.0]), vmin=-2, vmax=2).tolist()
    [0, 128, 255]
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
    if vmin is None and vmax is None and not clip and array.size:
        amin, amax = float(array.min()), float(array.max())
        if amin < -1e-6 or amax > 1 + 1e-6:
            out = int(np.count_nonzero((array < 0) | (array > 1)))
            raise ValueError(f"array: float values must lie in [0, 1] to be written as 8-bit grey levels, got "
                             f"[{amin:.4g}, {amax:.4g}] ({100 * out / array.size:.3g} % of the values outside); "
                             f"state the range to map with vmin/vmax (e.g. vmin={amin:.4g}, vmax={amax:.4g}), "
                             f"or pass clip=True to clip to [0, 1]")
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
    """Write one image (``(H, W)`` or ``(H, W, 3|4)``) to PNG/JPEG/TIFF, or the raw array to ``.npy``.

    Floats map ``[vmin, vmax]`` (default [0, 1]) to 0..255 through
    :func:`to_uint8`: with no range stated, values outside [0, 1] are a
    ``ValueError``, never clipped silently. PNG, TIFF, BMP and ``.npy`` are
    lossless; JPEG is not.

    Parameters
    ----------
    path : str or Path
        ``.png``, ``.jpg``, ``.tif`` (any format imageio writes) or ``.npy``.
    image : array_like (H, W) or (H, W, 3|4)
        Mapped to uint8 by :func:`to_uint8` (not for ``.npy``, which stores the array as is).
    vmin, vmax : float, optional
        The float range mapped to [0, 255] (default [0, 1]).

    Returns
    -------
    Path
        The written file (written atomically; missing folders are created).

    Raises
    ------
    ValueError
        For a non-finite image, one of the wrong shape, or floats outside [0, 1] with no range stated.
    noiselab.io.OutputError
        When the file cannot be written (an ``OSError``).

    Examples
    --------
    >>> import os, tempfile, numpy as np
    >>> write_image(os.path.join(tempfile.mkdtemp(), "a.png"), np.zeros((4, 4))).name
    'a.png'
    """
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


@renamed_parameters(show_progress="progress")
def write_video(path, frames, *, fps=DEFAULT_FPS, vmin=None, vmax=None, progress=None, quality=8,
                lossless=False) -> Path:
    """Write a video to ``.mp4`` (H.264), ``.mkv`` (FFV1), ``.gif``, ``.npy``, or a folder of PNG frames.

    ``frames`` is an array ``(T, H, W[, 3])`` or any iterable of frames (a lazy
    frame iterator is streamed and never held in memory, except for ``.npy``).
    A path without a suffix is a folder that receives ``frame_00000.png``, ...
    The file (or folder) appears only when writing succeeded. Frames go
    through :func:`to_uint8` (floats outside [0, 1] with no ``vmin``/``vmax``
    are an error).

    Lossless: ``.npy``, PNG frames, ``.mkv`` (FFV1, every grey level kept)
    and ``.mp4`` with ``lossless=True`` (H.264 in RGB with ``-qp 0``). Lossy:
    the default ``.mp4`` (yuv420p at ``quality``; it also maps grey levels to
    the limited video range) and ``.gif``.

    Parameters
    ----------
    path : str or Path
        ``.mp4``, ``.mkv``, ``.gif``, ``.npy``, or a path without suffix (a folder of PNG frames).
    frames : array_like (T, H, W[, 3]) or iterable of frames
        Mapped to uint8 by :func:`to_uint8` (not for ``.npy``).
    fps : float, default 25
        Frames per second (MP4 and GIF).
    vmin, vmax : float, optional
        The float range mapped to [0, 255] (default [0, 1]).
    progress : bool, optional
        A progress bar (default: when stderr is a terminal).
    quality : int, default 8
        MP4 quality, 0 to 10 (lossy MP4 only).
    lossless : bool, default False
        For ``.mp4``: H.264 in RGB with ``-qp 0`` instead of the lossy default.

    Returns
    -------
    Path
        The written file or folder.

    Raises
    ------
    ValueError
        For floats outside [0, 1] with no range stated, non-finite frames,
        frames of changing shape or an unknown suffix.
    noiselab.io.OutputError
        When the output cannot be written (an ``OSError``).

    Examples
    --------
    >>> import os, tempfile, numpy as np
    >>> write_video(os.path.join(tempfile.mkdtemp(), "v.npy"), np.zeros((2, 4, 4))).suffix
    '.npy'
    """
    path = Path(path)
    fps = float(fps)
    if not np.isfinite(fps) or fps <= 0:
        raise ValueError(f"fps must be a positive finite number, got {fps}")
    suffix = path.suffix.lower()
    it, count = _frame_source(frames)
    bar = progress_bar(it, total=count, desc=f"writing {path.name}", enabled=progress, unit="frame")
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
    if suffix not in (".mp4", ".mkv", ".gif"):
        raise ValueError(f"video path must end in .mp4, .mkv, .gif or .npy, or be a folder for PNG frames; got "
                         f"{path.name!r}")
    if not isinstance(lossless, (bool, np.bool_)):
        raise TypeError(f"lossless must be True or False, got {lossless!r}")
    with atomic_output(path) as tmp:
        if suffix == ".gif":
            # GIF is a preview format: frames are small uint8, so they are
            # gathered and written in one call (Pillow needs them all for the palette).
            gif = np.stack([to_uint8(frame, vmin, vmax) for frame in bar])
            Path(tmp).write_bytes(_encode(gif, ".gif", duration=1000.0 / fps, loop=0))
            return path
        _write_mp4(tmp, bar, fps, quality, vmin, vmax, codec="ffv1" if suffix == ".mkv" else
                   "x264rgb" if lossless else "x264")
    return path


def _codec_args(codec, quality, colour):
    """ffmpeg's output arguments: lossy H.264 (yuv420p), lossless H.264 in RGB (``-qp 0``) or FFV1 (lossless)."""
    if codec == "ffv1":
        return ["-vcodec", "ffv1", "-level", "3", "-pix_fmt", "gbrp" if colour else "gray"]
    if codec == "x264rgb":
        return ["-vcodec", "libx264rgb", "-qp", "0", "-preset", "veryfast", "-pix_fmt", "rgb24"]
    crf = int((1 - quality / 10.0) * 51)   # imageio-ffmpeg's quality -> crf (8 -> 10)
    # preset veryfast: 2.9x less encoder CPU than x264's default (medium) for 0.08 grey levels more mean
    # error and a 7 % larger file at crf 10 (benchmarks/bench_encode.py, 512^2 x 64 frames of snow); the
    # encoder was most of `noiselab snow`'s work
    return ["-vcodec", "libx264", "-pix_fmt", "yuv420p", "-crf", str(crf), "-preset", "veryfast"]


def _write_mp4(path, frames, fps, quality, vmin, vmax, codec="x264"):
    """H.264 or FFV1 through imageio-ffmpeg's ffmpeg binary, with the arguments imageio's FFMPEG writer uses.

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
            if codec == "x264" and (frame.shape[0] % 2 or frame.shape[1] % 2):
                pad = [(0, frame.shape[0] % 2), (0, frame.shape[1] % 2)] + [(0, 0)] * (frame.ndim - 2)
                frame = np.pad(frame, pad, mode="edge")
            if proc is None:
                shape = frame.shape
                pix_fmt = {2: "gray", 3: "rgb24"}[frame.ndim] if frame.ndim == 2 or frame.shape[-1] == 3 else "rgba"
                rate = str(Fraction(fps).limit_denominator())
                cmd = [imageio_ffmpeg.get_ffmpeg_exe(), "-y", "-f", "rawvideo", "-vcodec", "rawvideo",
                       "-s", f"{shape[1]}x{shape[0]}", "-pix_fmt", pix_fmt, "-r", rate, "-i", "-", "-an",
                       *_codec_args(codec, quality, frame.ndim == 3), "-v", "error", "-f",
                       "matroska" if codec == "ffv1" else "mp4", str(path)]
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
    """``numpy.load`` of a ``.npy`` file (no pickles), with one-line ``InputError`` for a file numpy cannot read.

    Parameters
    ----------
    path : str or Path
        A ``.npy`` file.

    Returns
    -------
    ndarray

    Raises
    ------
    FileNotFoundError
        For a missing file.
    noiselab.io.InputError
        For a file numpy cannot read, or one holding pickled objects.

    Examples
    --------
    >>> import os, tempfile, numpy as np
    >>> p = os.path.join(tempfile.mkdtemp(), "a.npy"); np.save(p, np.arange(3))
    >>> load_npy(p).tolist()
    [0, 1, 2]
    """
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

    Parameters
    ----------
    path : str or Path
        An image file imageio reads, or a ``.npy`` array.
    as_float : bool, default False
        Return uint8 images as float32 in [0, 1].

    Returns
    -------
    ndarray
        ``(H, W)`` grey or ``(H, W, 3|4)`` colour, as decoded (or as stored in the ``.npy``).

    Raises
    ------
    FileNotFoundError
        For a missing file.
    noiselab.io.InputError
        For a file that cannot be decoded (a ``ValueError``).

    Examples
    --------
    >>> import os, tempfile, numpy as np
    >>> p = write_image(os.path.join(tempfile.mkdtemp(), "ramp.png"), np.linspace(0, 1, 12).reshape(3, 4))
    >>> read_image(p).shape, read_image(p, as_float=True).dtype
    ((3, 4), dtype('float32'))
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


# swscale's flags for decoding: accurate rounding and the chroma interpolated at full resolution
_EXACT_SCALER = ("-sws_flags", "accurate_rnd+full_chroma_int")


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

    Parameters
    ----------
    path : str or Path
        A ``.mp4`` or ``.gif`` file, or a folder of PNG frames.
    max_frames : int, optional
        Yield at most this many frames.

    Yields
    ------
    ndarray (H, W) or (H, W, 3) of uint8
        Each frame as decoded (a GIF or MP4 stores grey frames as RGB).

    Raises
    ------
    noiselab.io.InputError
        For a file or frame that cannot be decoded.

    Examples
    --------
    >>> import os, tempfile, numpy as np
    >>> p = write_video(os.path.join(tempfile.mkdtemp(), "v.gif"), np.random.default_rng(0).random((3, 8, 8)))
    >>> [f.shape[:2] for f in iter_video(p)]   # as decoded: a GIF's grey frames come as RGB
    [(8, 8), (8, 8), (8, 8)]
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
    # ffmpeg's own YUV -> RGB conversion, rounded: swscale's default path truncates (its RGB of an H.264 grey
    # ramp read 0.49 grey level low on average, one level low at about half the pixels), where this one gives
    # ffmpeg's grey decode (-pix_fmt gray) exactly (tests/test_io.py)
    kwargs = {} if path.suffix.lower() == ".gif" else dict(plugin="FFMPEG", output_params=list(_EXACT_SCALER))
    try:
        for frame in iio.imiter(path, **kwargs):
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
    back with the colour axis dropped. MP4 and MKV are decoded by ffmpeg with
    accurate rounding (``-sws_flags accurate_rnd+full_chroma_int``): a grey
    video reads back exactly as ffmpeg's own grey decode (``-pix_fmt gray``),
    so the reader adds no error to the codec's (measured on an H.264 grey ramp
    and on uniform noise, 256 x 64 x 8 frames: mean difference 0.0 level;
    swscale's default conversion read 0.49 level low). Unreadable input raises ``InputError``
    (a ``ValueError``) naming the file and the cause.

    Parameters
    ----------
    path : str or Path
        A ``.mp4``, ``.gif`` or ``.npy`` file, or a folder of PNG frames.
    as_float : bool, default False
        Return uint8 frames as float32 in [0, 1].
    max_frames : int, optional
        Read at most this many frames.

    Returns
    -------
    ndarray (T, H, W) or (T, H, W, 3)

    Raises
    ------
    FileNotFoundError
        For a missing file.
    noiselab.io.InputError
        For a file or frame that cannot be decoded (a ``ValueError``).

    Examples
    --------
    >>> import os, tempfile, numpy as np
    >>> frames = np.random.default_rng(0).random((4, 8, 8))
    >>> p = write_video(os.path.join(tempfile.mkdtemp(), "v.gif"), frames)
    >>> read_video(p).shape
    (4, 8, 8)
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
