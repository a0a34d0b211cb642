"""``snow``: Langer & Zhang's falling snow, an opacity video from one (pruned) inverse 3-D FFT."""
from __future__ import annotations

import math

import numpy as np

from .._core import progress as progress_bar
from .._core import (array_order, as_array, as_generator, check_finite_array, check_memory, check_real, check_real_sequence,
                     check_shape, dispatch, float_dtype, renamed_parameters, resolve_workers, swap_pair,
                     thread_pool)
from ..spectral.synthesis import check_distribution
from ..spectral.envelopes import unit_direction_yx
from . import _kernels
from .tent import assemble, pruned_irfftn, tent_columns, to_half_spectrum

__all__ = ["snow", "snow_spectrum", "rescale_opacity"]


def rescale_opacity(field, beta=1.5, *, lo=None, hi=None, workers=None):
    """Map a field to opacity in place: ``alpha = ((field - min) / (max - min)) ** beta`` (thesis 3.3).

    A constant field (``max == min``) has no structure to show and becomes
    fully transparent (``alpha = 0``) instead of dividing by zero. ``lo`` and
    ``hi`` may pass a known minimum and maximum (saves one pass). ``workers``:
    threads (scipy.fft's meaning, -1 every core), the field split in fixed
    chunks: the same values for any count.

    Parameters
    ----------
    field : ndarray of float32 or float64, C-contiguous
        Overwritten with the opacity.
    beta : float, default 1.5
        Exponent of the opacity curve (> 0); 1 keeps the rescaled field linear.
    lo, hi : float, optional
        The field's minimum and maximum, if known (both or neither; ``lo <= hi``).
    workers : int, optional
        Threads (scipy.fft's meaning); the values do not depend on the count.

    Returns
    -------
    ndarray
        ``field`` itself, now in ``[0, 1]``.

    Raises
    ------
    TypeError
        For a field that is not float32 or float64.
    ValueError
        For a non-contiguous or non-finite field, only one of ``lo`` and
        ``hi``, ``beta <= 0``, or a range that overflows the dtype.

    Examples
    --------
    >>> import numpy as np
    >>> rescale_opacity(np.array([-1.0, 0.0, 3.0]), beta=1.0)
    array([0.  , 0.25, 1.  ])
    >>> rescale_opacity(np.full(3, 7.0))
    array([0., 0., 0.])
    """
    return _opacity(field, None, beta, lo, hi, workers)


def opacity_copy(field, beta=1.5, *, lo=None, hi=None, out=None):
    """:func:`rescale_opacity` into a new array, ``field`` left as it is (one pass, one thread; the same bits).

    For a raw field that something else may still read (the chunked
    renderer's raw chunks, :mod:`noiselab.scale.spectral`): one pass that
    reads ``field`` and writes the opacity, instead of a copy and a pass
    over the copy.

    Parameters
    ----------
    field : ndarray of float32 or float64, C-contiguous
        The raw field (unchanged).
    beta : float, default 1.5
        Exponent of the opacity curve (> 0).
    lo, hi : float, optional
        The field's minimum and maximum, if known (both or neither; ``lo <= hi``).
    out : ndarray, optional
        Where to write: C-contiguous, ``field``'s shape and dtype, apart from
        ``field`` (a slice of a larger chunk, say). Default: a new array.

    Returns
    -------
    ndarray
        ``out``, or a new array of ``field``'s shape and dtype, in ``[0, 1]``.

    Raises
    ------
    TypeError
        For a field that is not float32 or float64.
    ValueError
        As :func:`rescale_opacity`.

    Examples
    --------
    >>> import numpy as np
    >>> x = np.array([-1.0, 0.0, 3.0])
    >>> opacity_copy(x, beta=1.0), x
    (array([0.  , 0.25, 1.  ]), array([-1.,  0.,  3.]))
    """
    return _opacity(field, True if out is None else out, beta, lo, hi, 1)


def _opacity(field, copy, beta, lo, hi, workers):
    """``rescale_opacity`` in place (``copy`` None), into a new array (``copy`` True) or into the array ``copy``."""
    beta = check_real("beta", beta, lo=0, lo_open=True)
    field = as_array("field", field)
    if field.dtype not in (np.float32, np.float64):
        raise TypeError(f"field must be float32 or float64, got {field.dtype}")
    if isinstance(copy, np.ndarray):
        if copy.shape != field.shape or copy.dtype != field.dtype or not copy.flags.c_contiguous:
            raise ValueError(f"out must be a C-contiguous {field.dtype} array of shape {field.shape}, got "
                             f"{copy.dtype} {copy.shape}")
        if np.shares_memory(copy, field):
            raise ValueError("out must not overlap field (rescale_opacity maps a field in place)")
        dest = copy
    else:
        dest = np.empty_like(field) if copy else field
    if field.size == 0:
        return dest
    flat = field.reshape(-1)
    if not flat.flags.c_contiguous:
        raise ValueError("field must be C-contiguous to be rescaled in place")
    dflat = dest.reshape(-1)
    if (lo is None) != (hi is None):
        raise ValueError("lo and hi must be given together (the field's known minimum and maximum) or not at all")
    if lo is None:
        lo, hi = flat.min(), flat.max()
        if not (np.isfinite(lo) and np.isfinite(hi)):
            check_finite_array("field", field)
    else:
        lo = check_real("lo", lo)
        hi = check_real("hi", hi, lo=lo)
    ft = field.dtype.type
    span64 = float(hi) - float(lo)
    if not math.isfinite(span64) or span64 > float(np.finfo(field.dtype).max):
        raise ValueError(f"field spans [{float(lo):g}, {float(hi):g}]: the range overflows {field.dtype}; rescale it")
    span = ft(hi) - ft(lo)
    if not span > 0:
        dest[...] = 0
        return dest
    if not math.isfinite(1.0 / span64):
        raise ValueError(f"field spans only {span64:.3g}: 1 / (max - min) overflows; rescale it")
    # round the scale up so that the maximum maps to exactly 1 (then clipped)
    scale = ft(1) / span
    while (ft(hi) - ft(lo)) * scale < 1:
        scale = np.nextafter(scale, ft(np.inf))
    nw = resolve_workers(workers)
    step = 1 << 20  # fixed chunks (not per worker): each element is mapped alone, so any count gives the same bits
    chunks = [(flat[i:i + step], dflat[i:i + step]) for i in range(0, flat.size, step)]
    def run(c):  # in place, or into the new array (a separate kernel: see rescale_power_into)
        if copy is not None:
            _kernels.rescale_power_into(c[0], c[1], float(lo), float(scale), beta)
        else:
            _kernels.rescale_power(c[0], float(lo), float(scale), beta)

    if nw <= 1 or len(chunks) <= 1:
        run((flat, dflat))
    else:
        list(thread_pool(min(nw, len(chunks))).map(run, chunks))
    return dest


def _check_params(shape, c, band, thickness, direction_yx, pan_yx, beta, exponent, amplitude, on_alias):
    """The checked parameters; ``direction`` and ``pan`` come back in the tent code's (x, y) order."""
    shape = check_shape("shape", shape, ndim=3)
    T, H, W = shape
    c = check_real("c (rad/frame)", c, lo=0, hi=np.pi)
    thickness = check_real("thickness", thickness, lo=0, hi=1)
    beta = check_real("beta", beta, lo=0, lo_open=True)
    exponent = check_real("exponent", exponent, lo=-8, hi=8)
    direction = unit_direction_yx("direction_yx", direction_yx)
    try:
        p = swap_pair("pan_yx", check_real_sequence("pan_yx", pan_yx, length=2, lo=-1e100, hi=1e100))
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"pan_yx must be a finite pair (uy, ux) in px/frame: {exc}") from None
    check_distribution(amplitude)
    if on_alias not in ("raise", "drop"):
        raise ValueError(f"on_alias must be 'raise' or 'drop', got {on_alias!r}")
    if band is None:
        band = (W / 32, W / 4)
    return shape, c, band, thickness, direction, (float(p[0]), float(p[1])), beta, exponent


@array_order(("direction", "direction_yx"), ("pan", "pan_yx"))
@renamed_parameters(seed="rng", show_progress="progress", amplitude="amplitude_distribution")
def snow(shape=(64, 512, 512), *, rng=None, c=1.0, band=None, thickness=0.1, direction_yx=(1.0, 0.0),
         pan_yx=(0.0, 0.0), beta=1.5, exponent=1.0, amplitude_distribution="uniform", dtype=np.float32,
         on_alias="raise", rescale=True, progress=None, workers=None, chunks=None, spill=None):
    """Falling-snow opacity ``alpha(t, y, x)`` in [0, 1] from the tent model (Langer & Zhang 2003).

    Energy sits on the thickened tent ``wt = -c*(d . w)/|w| - pan . w`` inside
    an annulus band, with ``1/|w|**exponent`` amplitude and random phase; one
    inverse 3-D FFT (pruned to the cells that carry energy) gives a periodic
    video, rescaled to [0, 1] and raised to ``beta``.

    Parameters
    ----------
    shape : (T, H, W)
        Frames, height, width. ``T = 1`` gives a still.
    rng : int, numpy.random.Generator or None
        The random state (SPEC 7): the same int, the same bits; a
        ``Generator`` is drawn from; ``None`` (default) is fresh entropy.
    c : float
        Tent constant in rad/frame, ``0 <= c <= pi`` (thesis Eq. 3.3). A flake
        at spatial frequency ``|w|`` rad/px moves at ``c/|w|`` px/frame: with
        the default band at 512 px (16..128 cycles/frame, ``|w|`` =
        ``2*pi*16/512 .. 2*pi*128/512``) the nearest flakes move at
        ``5.09*c`` px/frame and the farthest at ``0.637*c`` (see
        :func:`noiselab.snow.flake_speeds`). ``c = 0`` freezes the snow.
    band : (lo, hi), optional
        Spatial pass band in cycles/frame (cycles per frame *width*),
        inclusive. Default ``(W/32, W/4)``: 16..128 at 512 px. ``hi`` may reach
        the Nyquist frequency ``W/2``, not pass it.
    thickness : float
        Relative thickness of the tent, in [0, 1]: the tent constant spreads
        over ``c*(1 - thickness) .. c*(1 + thickness)`` (a range of speeds per
        spatial frequency, thesis 3.2.1). 0 is the thin tent (one temporal bin
        per spatial frequency).
    direction_yx : (dy, dx)
        Fall direction in array order (y down the rows, x right along the
        columns), any angle and length; default ``(1, 0)``, straight down.
        (``direction=(dx, dy)``, the old (x, y) spelling, is refused since
        0.4.)
    pan_yx : (uy, ux)
        Image velocity in px/frame, array order, that a panning camera adds
        to every flake (the sheared tent, Eq. 4.2); ``(0, 0)`` for a still
        camera. (``pan=(ux, uy)``: the old spelling, refused since 0.4.)
    beta : float
        Opacity exponent, ``alpha ** beta`` after rescaling (thesis: 1.5).
    exponent : float
        Amplitude ``1/|w|**exponent``; 1 is the thesis's 1/f.
    amplitude_distribution : {"uniform", "rayleigh", "fixed"}
        Random amplitude law (thesis: uniform).
    dtype : float32 or float64
        Output dtype; float32 (default) computes in complex64.
    on_alias : {"raise", "drop"}
        Energy past the temporal Nyquist frequency (pi rad/frame) would wrap
        around and move backwards: by default raise a ``ValueError`` naming
        the largest allowed ``c`` (and pan); ``"drop"`` leaves those cells out.
    rescale : bool
        ``False`` returns the raw zero-mean field (the inverse FFT itself).
    progress : bool or None
        Progress bar over the frames of the final FFT pass.
    workers : int, optional
        Threads, with scipy.fft's meaning (-1: every core): the t-pass runs on
        them inside scipy, the blocks of frames of the y- and x-passes are
        shared among them. The output is bit-identical for any count.
        Default (None): scipy's default, one thread unless set with
        ``scipy.fft.set_workers`` (``noiselab snow`` uses every core).
    chunks : int, tuple or "auto", optional
        Return a lazy ``dask.array.Array`` in these ``(t, y, x)`` chunks,
        computed by the same pruned FFT split into pencils, with the extremes
        for the rescale found by a dask reduction (:mod:`noiselab.scale.spectral`;
        needs ``noiselab[dask]``). Equal to the in-memory video to float rounding.
    spill : path, optional
        With ``chunks``: a directory (on storage every worker sees) for the
        transposed t/y-pass output as a zarr array: the t- and y-passes then
        run once and no worker holds more than its chunks (videos bigger than
        the cluster's memory). The caller removes it after computing.
        Default: chosen by itself. Dask's in-memory rechunk when the largest
        task plus each worker's share of the transposed arrays fits what the
        workers have short of ``distributed``'s pause threshold (80 % of the
        memory limit, less what the worker holds; no client: this machine's
        available memory), else a temporary folder of its own in dask's
        ``temporary-directory``, removed with the lazy array's graph
        (``docs/guide/scale.md``).

    Returns
    -------
    ndarray, shape (T, H, W), ``dtype``
        Opacity in [0, 1] (or the raw field). Periodic in t, y and x: it loops
        and tiles seamlessly.

    Notes
    -----
    A video of ``T`` frames holds temporal frequencies in steps of
    ``2*pi/T`` rad/frame, so each spatial frequency's speed is quantised to
    that grid (a cell gets the temporal bins its thickened surface overlaps);
    the thickness and a longer ``T`` smooth the range of speeds. Its 1/f
    amplitude is split evenly over those bins, so the spatial spectrum does
    not depend on the thickness.

    Raises
    ------
    ValueError
        For an impossible shape, ``c`` outside ``[0, pi]``, a band past the
        spatial Nyquist frequency, a zero direction, or (``on_alias="raise"``)
        a ``c`` or pan whose tent passes the temporal Nyquist frequency (the
        message names the largest allowed value).
    MemoryError
        When the video would not fit (estimated before allocating).

    Examples
    --------
    >>> a = snow((16, 64, 64), rng=0)
    >>> a.shape, a.dtype, float(a.min()), float(a.max())
    ((16, 64, 64), dtype('float32'), 0.0, 1.0)
    """
    (T, H, W), c, band, thickness, direction, pan, beta, exponent = _check_params(
        shape, c, band, thickness, direction_yx, pan_yx, beta, exponent, amplitude_distribution, on_alias)
    nw = resolve_workers(workers)
    dt = float_dtype(dtype)
    if spill is not None and chunks is None:
        raise ValueError("spill= is the chunked path's scratch directory: pass chunks= too")
    if chunks is not None:  # lazy, on dask: the implementation noiselab.scale.spectral registers
        return dispatch.chunked("snow")((T, H, W), chunks, rng=rng, c=c, band=band, thickness=thickness,
                                        direction=direction, pan=pan, beta=beta, exponent=exponent,
                                        amplitude=amplitude_distribution, dtype=dt, on_alias=on_alias,
                                        rescale=rescale,
                                        spill=spill)
    cols = tent_columns((T, H, W), c=c, band=band, thickness=thickness, direction=direction, pan=pan,
                        exponent=exponent, on_alias=on_alias)
    item = dt.itemsize
    # the output, the sparse spectrum (a bin, a value and a sort key per cell) and one padded block per thread
    # (pruned_irfftn: about 256 KiB of frames of W//2 + 1 complex columns, one frame at the least)
    check_memory(T * H * W * item + 4 * cols.n_cells * (16 + 2 * item)
                 + nw * max(1 << 18, H * (W // 2 + 1) * 2 * item), f"snow{(T, H, W)}")
    rng = as_generator(rng)
    spec = assemble(cols, rng, amplitude_distribution, dt)
    out = np.empty((T, H, W), dtype=dt)
    with progress_bar(total=T, desc="snow", enabled=progress, unit="frame") as bar:
        lo, hi = pruned_irfftn(spec, cols, out, bar=bar, workers=workers)
    if rescale:
        rescale_opacity(out, beta, lo=lo, hi=hi, workers=nw)
    return out


@array_order(("direction", "direction_yx"), ("pan", "pan_yx"))
@renamed_parameters(seed="rng", amplitude="amplitude_distribution")
def snow_spectrum(shape=(64, 512, 512), *, rng=None, c=1.0, band=None, thickness=0.1, direction_yx=(1.0, 0.0),
                  pan_yx=(0.0, 0.0), exponent=1.0, amplitude_distribution="uniform", dtype=np.float32,
                  on_alias="raise"):
    """The half spectrum ``S`` (``(T, H, W//2 + 1)``) that :func:`snow` inverts for the same arguments.

    ``scipy.fft.irfftn(S, s=shape)`` equals ``snow(..., rescale=False)`` to
    float precision; for analysis and tests (it is dense, so it costs the full
    spectrum's memory).

    Parameters
    ----------
    shape, rng, c, band, thickness, direction_yx, pan_yx, exponent, amplitude_distribution, dtype, on_alias
        As for :func:`snow` (the same checks, the same random draws).

    Returns
    -------
    ndarray of complex64 or complex128, shape ``(T, H, W // 2 + 1)``
        The dense half spectrum; zero off the thickened tent and outside the band.

    Raises
    ------
    ValueError
        For the arguments :func:`snow` refuses (a ``c`` or pan that aliases
        past the temporal Nyquist frequency with ``on_alias="raise"``, a band
        past the spatial Nyquist frequency, a zero direction, ...).

    Examples
    --------
    >>> import numpy as np, scipy.fft
    >>> S = snow_spectrum((8, 32, 32), rng=0, dtype=np.float64)
    >>> S.shape, round(float((S != 0).mean()), 3)   # the share of cells that carry energy
    ((8, 32, 17), 0.025)
    >>> raw = snow((8, 32, 32), rng=0, dtype=np.float64, rescale=False)
    >>> bool(np.allclose(scipy.fft.irfftn(S, s=(8, 32, 32)), raw))
    True
    """
    (T, H, W), c, band, thickness, direction, pan, _, exponent = _check_params(
        shape, c, band, thickness, direction_yx, pan_yx, 1.0, exponent, amplitude_distribution, on_alias)
    dt = float_dtype(dtype)
    cols = tent_columns((T, H, W), c=c, band=band, thickness=thickness, direction=direction, pan=pan,
                        exponent=exponent, on_alias=on_alias)
    return to_half_spectrum(assemble(cols, as_generator(rng), amplitude_distribution, dt), cols)
