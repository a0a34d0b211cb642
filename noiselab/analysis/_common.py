"""Input checks, frequency grids and the half-spectrum container shared by every analyser.

Conventions (the same as the rest of noiselab):

- a *field* is a 1-, 2- or 3-D real array; a *video* is ``(frames, height, width)``,
  x to the right along columns, y down along rows;
- integer frequency indices ``k`` count cycles per length of their axis
  (cycles/frame for the spatial axes, cycles/video for time); angular
  frequencies ``w = 2 pi k / n`` are in radians per sample (rad/px, rad/frame);
- radial frequencies are in *cycles/frame*: cycles/pixel times the frame size
  ``N``, the length of the last axis (cycles per frame *width*, as in
  ``noiselab.spectral`` and ``noiselab.snow``); the circle of radius ``N / 2``
  (0.5 cycles/pixel) is the Nyquist limit of every axis.
"""
from __future__ import annotations

import numbers

import numpy as np

from .._core import as_array, check_finite_array, check_real, validate

__all__ = ["check_field", "check_video", "check_band", "frequency_index", "ref_size"]


def check_field(name, field, *, ndim=(1, 2, 3), min_size=4, allow_constant=False) -> np.ndarray:
    """Validate a real field and return it as float32 (float64 input stays float64).

    Rejects complex, empty, NaN/inf-bearing, wrong-dimensional, too small and
    (unless ``allow_constant``) constant input with a message that names
    ``name`` and says what is allowed.
    """
    if isinstance(field, (str, bytes)) or field is None:
        raise TypeError(f"{name} must be a numeric array, got {type(field).__name__}")
    arr = as_array(name, field)
    if arr.dtype.kind == "c":
        raise TypeError(f"{name} must be real; got a complex array (pass its real part, abs or power)")
    if arr.dtype.kind not in "biuf":
        raise TypeError(f"{name} must be a real numeric array, got dtype {arr.dtype}")
    allowed = (ndim,) if isinstance(ndim, int) else tuple(ndim)
    if arr.ndim not in allowed:
        dims = " or ".join(f"{d}-D" for d in allowed)
        hint = "; convert RGB to grey first (e.g. noiselab.analysis.to_grey)" if arr.ndim > max(allowed) else ""
        raise ValueError(f"{name} must be {dims}, got a {arr.ndim}-D array of shape {arr.shape}{hint}")
    if arr.size == 0:
        raise ValueError(f"{name} is empty (shape {arr.shape})")
    if min(arr.shape) < min_size:
        raise ValueError(
            f"{name} of shape {arr.shape} is too small to estimate anything: every axis needs at least {min_size} samples"
        )
    arr = check_finite_array(name, arr)
    if arr.dtype == np.bool_:
        arr = arr.astype(np.float32)
    if not allow_constant:
        lo, hi = arr.min(), arr.max()
        if lo == hi:
            raise ValueError(f"{name} is constant (every value is {lo}); a constant field has no spectrum, slope or motion")
    if arr.dtype != np.float64:
        arr = arr.astype(np.float32, copy=False)
    return arr


def check_video(name, video, *, min_frames=2, min_size=4, allow_constant=False) -> np.ndarray:
    """Validate a ``(frames, height, width)`` video (see :func:`check_field`)."""
    arr = check_field(name, video, ndim=3, min_size=1, allow_constant=allow_constant)
    t, h, w = arr.shape
    if t < min_frames:
        raise ValueError(f"{name} has {t} frame(s); this measurement needs at least {min_frames} (shape is (frames, height, width))")
    if h < min_size or w < min_size:
        raise ValueError(f"{name} frames of {h} x {w} are too small: height and width need at least {min_size} pixels")
    return arr


def ref_size(shape) -> int:
    """Frame size ``N`` used to express radial frequencies in cycles/frame: the last (width) axis."""
    return int(shape[-1])


def check_band(name, band, fmax, *, allow_none=False):
    """Validate a ``(lo, hi)`` band in cycles/frame with ``0 < lo < hi <= fmax`` (the Nyquist radius).

    noiselab's one band validator (:func:`noiselab._core.validate.check_band`) with ``lo > 0``.
    """
    return validate.check_band(name, band, fmax, lo_open=True, allow_none=allow_none)


def check_vector(name, value, *, nonzero=False, order="xy") -> np.ndarray:
    """Validate a 2-vector of finite reals; returned as ``(x, y)`` (``order="yx"``: given in array order ``(y, x)``)."""
    pair = "(y, x)" if order == "yx" else "(x, y)"
    if isinstance(value, (str, bytes, set, frozenset, dict)):
        raise TypeError(f"{name} must be an ordered {pair} pair, got a {type(value).__name__}")
    if not hasattr(value, "__len__") or len(value) != 2:
        raise ValueError(f"{name} must be a {pair} pair, got {value!r}")
    # within +-1e100 so that products with frequencies cannot overflow
    vec = np.array([check_real(f"{name}[{i}]", v, lo=-1e100, hi=1e100) for i, v in enumerate(value)], dtype=np.float64)
    if nonzero and not np.any(vec):
        raise ValueError(f"{name} must not be (0, 0)")
    return vec[::-1].copy() if order == "yx" else vec


def frequency_index(n: int, *, half: bool = False) -> np.ndarray:
    """Integer frequency index of an axis of length ``n`` in FFT order (``rfft`` order if ``half``)."""
    if half:
        return np.arange(n // 2 + 1, dtype=np.float64)
    return np.fft.fftfreq(n, 1.0 / n)


def half_weight(n: int) -> np.ndarray:
    """Multiplicity of each ``rfft`` column of an axis of length ``n``: 1 for DC (and Nyquist if ``n`` is even), else 2.

    A column of weight 2 stands for itself and its complex-conjugate mirror,
    which the half spectrum does not store.
    """
    w = np.full(n // 2 + 1, 2.0)
    w[0] = 1.0
    if n % 2 == 0:
        w[-1] = 1.0
    return w


def noise_floor(spec) -> float:
    """Power per cell below which a spectrum holds only rounding noise (``1e3 eps**2`` x mean square / cells).

    A band-limited field computed in floating point has ~``eps**2`` relative
    power outside its band, not zero; measuring a slope or an orientation
    there would measure the arithmetic.

    Parameters
    ----------
    spec : PowerSpectrum
        From :func:`noiselab.analysis.power_spectrum` (its dtype sets ``eps``).

    Returns
    -------
    float
        The power per cell under which a cell is taken as rounding noise.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.analysis import power_spectrum
    >>> spec = power_spectrum(np.random.default_rng(0).standard_normal((64, 64)))
    >>> bool(0 < noise_floor(spec) < 1e-20)
    True
    """
    eps = float(np.finfo(spec.power.dtype).eps)
    cells = int(np.prod([spec.shape[a] for a in spec.axes]))
    return 1e3 * eps**2 * (spec.total + spec.mean**2) / cells


def check_tol(name, tol) -> float:
    return check_real(name, tol, lo=0.0, hi=1e100)


def is_int(value) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_))
