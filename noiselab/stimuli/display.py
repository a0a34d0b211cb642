"""A screen in physical units: pixels per degree, frames per second, cd/m² per display value.

:class:`Display` is a frozen description of a calibrated screen. It converts
the units a vision experiment is specified in (degrees of visual angle,
seconds, cycles/deg, deg/s, cd/m²) into the units noiselab's generators take
(pixels, frames, cycles/frame, cycles/pixel, px/frame, display values), and
back. Every conversion is the exact rational product ``x * a / b`` rounded
once to float64 (numbers; arrays in extended precision), so a value converted
and converted back returns itself to the last bit whenever the factor is a
power of two or the converted value is a double, and otherwise within one ulp
(float64 cannot do better: a factor below 1 maps two doubles onto one).
Measured over the lab values of ``tests/test_stimuli.py`` (2,772 round trips:
6 pixel densities x 6 frame rates x 11 values x 7 conversions) 97.5 % come back
bit for bit and all within one ulp; over random floats 92 %.

Luminance: a gamma law ``L = L_min + (L_max - L_min) * (v / (2**bits - 1))**gamma``
(the constructor) or a measured lookup table of ``2**bits`` increasing
luminances (:meth:`Display.from_lut`).
"""
from __future__ import annotations

import dataclasses
import math
from fractions import Fraction
from functools import cached_property

import numpy as np

from .._core import as_array, check_int, check_real, check_real_sequence

__all__ = ["Display"]

# the largest luminance accepted (cd/m²): the sun's disc is about 1.6e9
_MAX_LUMINANCE = 1e12


@dataclasses.dataclass(frozen=True)
class Display:
    """A calibrated screen: geometry, refresh rate and luminance response.

    Parameters
    ----------
    pixels_per_degree : float
        Pixels per degree of visual angle at the centre of the screen, > 0.
    frame_rate : float
        Frames per second (Hz), > 0. Default 60.
    luminance : (L_min, L_max)
        Luminance in cd/m² at the lowest and the highest display value,
        ``0 <= L_min < L_max``. Default ``(0.5, 100.0)``.
    gamma : float
        Exponent of the gamma law, in ``[0.1, 10]``. Default 2.2. Display
        value ``v`` shows the luminance
        ``L(v) = L_min + (L_max - L_min) * (v / (2**bits - 1)) ** gamma``
        (cd/m²), and :meth:`value_of` inverts it:
        ``v = (2**bits - 1) * ((L - L_min) / (L_max - L_min)) ** (1 / gamma)``.
    bits : int
        Bits per display value, 1 to 16: values ``0 .. 2**bits - 1``.
    lut : tuple of float, optional
        Measured luminance of every display value (set by :meth:`from_lut`;
        ``gamma`` is then None).

    Raises
    ------
    ValueError
        A parameter outside its range (the message names it and the range).

    Examples
    --------
    >>> d = Display(32.0, frame_rate=120.0, luminance=(0.5, 100.0), gamma=2.2, bits=8)
    >>> d.cycles_per_pixel(4)                 # 4 cycles/deg
    0.125
    >>> d.cycles_per_frame(4, 256)            # on a 256-px (8 deg) frame
    32.0
    >>> d.px_per_frame(7.5)                   # 7.5 deg/s at 120 Hz
    2.0
    >>> float(d.luminance_of(255))
    100.0
    >>> v = 128   # the gamma law, written out
    >>> bool(np.isclose(d.luminance_of(v), 0.5 + (100.0 - 0.5) * (v / 255) ** 2.2))
    True
    """

    pixels_per_degree: float
    frame_rate: float = 60.0
    luminance: tuple = (0.5, 100.0)
    gamma: float | None = 2.2
    bits: int = 8
    lut: tuple | None = dataclasses.field(default=None, repr=False)

    def __post_init__(self):
        set_ = object.__setattr__  # frozen: the checked values replace the given ones once, here
        set_(self, "pixels_per_degree", check_real("pixels_per_degree", self.pixels_per_degree, lo=0.0,
                                                   hi=1e9, lo_open=True))
        set_(self, "frame_rate", check_real("frame_rate (Hz)", self.frame_rate, lo=0.0, hi=1e9, lo_open=True))
        set_(self, "bits", check_int("bits", self.bits, lo=1, hi=16))
        lo, hi = check_real_sequence("luminance (cd/m²)", self.luminance, length=2, lo=0.0, hi=_MAX_LUMINANCE)
        if not lo < hi:
            raise ValueError(f"luminance (cd/m²) must be (L_min, L_max) with 0 <= L_min < L_max, got ({lo:g}, {hi:g})")
        set_(self, "luminance", (lo, hi))
        if self.lut is None:
            set_(self, "gamma", check_real("gamma", self.gamma, lo=0.1, hi=10.0))
        else:
            if self.gamma is not None:
                raise ValueError("a Display has either gamma (a gamma law) or lut (a measured table); "
                                 "use Display.from_lut for a table")
            set_(self, "lut", _check_lut(self.lut, self.bits))
            if (lo, hi) != (self.lut[0], self.lut[-1]):
                raise ValueError(f"luminance (cd/m²) must be the table's ends ({self.lut[0]:g}, {self.lut[-1]:g}), "
                                 f"got ({lo:g}, {hi:g}); use Display.from_lut")

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_lut(cls, lut, pixels_per_degree, *, frame_rate=60.0):
        """A display whose luminance response is a measured table, one cd/m² value per display value.

        Parameters
        ----------
        lut : sequence of float
            ``2**bits`` luminances (cd/m², >= 0), strictly increasing, for
            ``bits`` in 1..16 (2, 4, ..., 65536 entries): entry ``v`` is the
            luminance of display value ``v``.
        pixels_per_degree, frame_rate : float
            As in :class:`Display`.

        Returns
        -------
        Display

        Raises
        ------
        ValueError
            A table whose length is not a power of two from 2 to 65536, that
            is not strictly increasing, or holds a negative or non-finite value.

        Examples
        --------
        >>> d = Display.from_lut([1.0, 30.0, 60.0, 90.0], 40.0)
        >>> d.bits, d.luminance
        (2, (1.0, 90.0))
        """
        table = _check_lut(lut, None)
        bits = int(len(table)).bit_length() - 1
        return cls(pixels_per_degree, frame_rate=frame_rate, luminance=(table[0], table[-1]), gamma=None,
                   bits=bits, lut=table)

    @classmethod
    def from_geometry(cls, *, distance_cm, screen_width_cm, resolution_px, frame_rate=60.0,
                      luminance=(0.5, 100.0), gamma=2.2, bits=8):
        """A display from the viewing distance, the screen's visible width and its horizontal resolution.

        The pixels per degree are those at the centre of the screen: one
        degree there spans ``2 * distance * tan(0.5 deg)`` cm. (Towards the
        edges of a flat screen a degree spans more pixels.)

        Parameters
        ----------
        distance_cm : float
            Eye to screen, cm, > 0.
        screen_width_cm : float
            Visible width of the picture, cm, > 0.
        resolution_px : int
            Pixels across that width, >= 1.
        frame_rate, luminance, gamma, bits
            As in :class:`Display`.

        Returns
        -------
        Display

        Examples
        --------
        >>> d = Display.from_geometry(distance_cm=57.0, screen_width_cm=40.0, resolution_px=1920)
        >>> round(d.pixels_per_degree, 2)
        47.75
        """
        distance = check_real("distance_cm", distance_cm, lo=0.0, hi=1e9, lo_open=True)
        width = check_real("screen_width_cm", screen_width_cm, lo=0.0, hi=1e9, lo_open=True)
        res = check_int("resolution_px", resolution_px, lo=1, hi=10**9)
        cm_per_degree = 2.0 * distance * math.tan(math.radians(0.5))
        return cls(res / width * cm_per_degree, frame_rate=frame_rate, luminance=luminance, gamma=gamma, bits=bits)

    # ------------------------------------------------------------------ space and time
    def deg_to_px(self, degrees):
        """Degrees of visual angle -> pixels (float; see :meth:`pixels` for a size)."""
        return _scale(_real("degrees", degrees), self.pixels_per_degree, 1.0)

    def px_to_deg(self, pixels):
        """Pixels -> degrees of visual angle."""
        return _scale(_real("pixels", pixels), 1.0, self.pixels_per_degree)

    def pixels(self, degrees) -> int:
        """A size in degrees as a whole number of pixels (rounded, at least 1): a ``shape`` entry.

        Examples
        --------
        >>> Display(32.0).pixels(8)
        256
        """
        px = self.deg_to_px(check_real("degrees", degrees, lo=0.0, lo_open=True, hi=1e12))
        return max(1, int(round(px)))

    def seconds_to_frames(self, seconds):
        """Seconds -> frames (float)."""
        return _scale(_real("seconds", seconds), self.frame_rate, 1.0)

    def frames_to_seconds(self, frames):
        """Frames -> seconds."""
        return _scale(_real("frames", frames), 1.0, self.frame_rate)

    def frame_count(self, seconds) -> int:
        """A duration as a whole number of frames (rounded, at least 1): a ``shape[0]`` entry.

        Examples
        --------
        >>> Display(32.0, frame_rate=120.0).frame_count(0.5)
        60
        """
        n = self.seconds_to_frames(check_real("seconds", seconds, lo=0.0, lo_open=True, hi=1e12))
        return max(1, int(round(n)))

    # ------------------------------------------------------------------ frequency and speed
    def cycles_per_pixel(self, cycles_per_degree):
        """Spatial frequency cycles/deg -> cycles/pixel (what ``annulus`` and ``motion_cloud``'s ``sf_0`` take).

        Examples
        --------
        >>> Display(32.0).cycles_per_pixel(4)
        0.125
        """
        return _scale(_real("cycles_per_degree", cycles_per_degree), 1.0, self.pixels_per_degree)

    def cycles_per_degree(self, cycles_per_pixel):
        """Spatial frequency cycles/pixel -> cycles/deg (inverse of :meth:`cycles_per_pixel`)."""
        return _scale(_real("cycles_per_pixel", cycles_per_pixel), self.pixels_per_degree, 1.0)

    def cycles_per_frame(self, cycles_per_degree, size):
        """Cycles/deg -> cycles/frame on a frame ``size`` pixels wide (what ``spectral_noise``'s ``band`` takes).

        Examples
        --------
        >>> Display(32.0).cycles_per_frame(4, 256)
        32.0
        """
        size = check_real("size (pixels)", size, lo=0.0, lo_open=True, hi=1e12)
        return _scale(_real("cycles_per_degree", cycles_per_degree), size, self.pixels_per_degree)

    def cycles_per_degree_from_frame(self, cycles_per_frame, size):
        """Cycles/frame on a frame ``size`` pixels wide -> cycles/deg (inverse of :meth:`cycles_per_frame`)."""
        size = check_real("size (pixels)", size, lo=0.0, lo_open=True, hi=1e12)
        return _scale(_real("cycles_per_frame", cycles_per_frame), self.pixels_per_degree, size)

    def band(self, band_cycles_per_degree, size):
        """A pass band ``(lo, hi)`` in cycles/deg as cycles/frame on a frame ``size`` px wide: ``spectral_noise``'s ``band``.

        Examples
        --------
        >>> import noiselab
        >>> d = Display(32.0)
        >>> d.band((2, 8), 256)
        (16.0, 64.0)
        >>> x = noiselab.spectral_noise((256, 256), band=d.band((2, 8), 256), rng=0)
        """
        lo, hi = check_real_sequence("band (cycles/deg)", band_cycles_per_degree, length=2, lo=0.0)
        return self.cycles_per_frame(lo, size), self.cycles_per_frame(hi, size)

    def px_per_frame(self, deg_per_second):
        """Speed deg/s -> px/frame (``motion_cloud``'s ``V_X``, ``V_Y``; ``snow``'s ``pan``).

        Examples
        --------
        >>> Display(32.0, frame_rate=120.0).px_per_frame(7.5)
        2.0
        """
        return _scale(_real("deg_per_second", deg_per_second), self.pixels_per_degree, self.frame_rate)

    def deg_per_second(self, px_per_frame):
        """Speed px/frame -> deg/s (inverse of :meth:`px_per_frame`)."""
        return _scale(_real("px_per_frame", px_per_frame), self.frame_rate, self.pixels_per_degree)

    def snow_c(self, deg_per_second, cycles_per_degree):
        """``snow``'s tent constant ``c`` (rad/frame) that moves flakes of ``cycles_per_degree`` at ``deg_per_second``.

        A flake at spatial frequency ``|w|`` rad/px falls at ``c / |w|``
        px/frame, so ``c = speed * |w|``: the flakes of finer grain move
        slower (the tent), and this fixes the speed at one frequency.

        Examples
        --------
        >>> import noiselab
        >>> d = Display(32.0, frame_rate=60.0)
        >>> c = d.snow_c(2.0, 4.0)        # 4 cycles/deg flakes fall at 2 deg/s
        >>> round(c, 4)
        0.8378
        >>> video = noiselab.snow((8, 64, 64), c=c, band=d.band((1, 8), 64), rng=0)
        """
        w = 2.0 * math.pi * self.cycles_per_pixel(check_real("cycles_per_degree", cycles_per_degree, lo=0.0))
        return float(self.px_per_frame(check_real("deg_per_second", deg_per_second)) * w)

    def lattice_extent(self, size_deg, cycles_per_degree):
        """The extent ``(0, stop)`` of a lattice grid axis ``size_deg`` wide whose base frequency is ``cycles_per_degree``.

        Lattice noise has about one feature per input unit, so an axis of
        ``size_deg`` degrees at ``f`` cycles/deg spans ``size_deg * f`` units;
        sample it with :meth:`pixels` ``(size_deg)`` points.

        Examples
        --------
        >>> import noiselab
        >>> d = Display(32.0)
        >>> ext = d.lattice_extent(4.0, 2.0)
        >>> ext
        (0.0, 8.0)
        >>> n = d.pixels(4.0)
        >>> img = noiselab.LatticeNoise(dim_in=2, rng=0).evaluate_grid((n, n), (ext, ext))
        """
        size = check_real("size_deg", size_deg, lo=0.0, lo_open=True, hi=1e12)
        f = check_real("cycles_per_degree", cycles_per_degree, lo=0.0, lo_open=True, hi=1e12)
        return (0.0, float(size * f))

    # ------------------------------------------------------------------ luminance
    @property
    def levels(self) -> int:
        """How many display values: ``2**bits``."""
        return 1 << self.bits

    @cached_property
    def table(self) -> np.ndarray:
        """The luminance (cd/m², float64) of every display value ``0 .. 2**bits - 1``, never decreasing.

        A gamma law's darkest levels may round to one float64 luminance at steep
        gammas (gamma 8 over 0.5-100 cd/m², 8 bits: levels 0 and 1 are both
        0.5, their true difference 6e-18 cd/m²); a measured table is strictly
        increasing (:meth:`from_lut` checks it).
        """
        if self.lut is not None:
            t = np.asarray(self.lut, dtype=np.float64)
        else:
            lo, hi = self.luminance
            t = lo + (hi - lo) * (np.arange(self.levels, dtype=np.float64) / (self.levels - 1)) ** self.gamma
            t[-1] = hi  # exact ends (x**gamma of 1.0 is 1.0, but keep it explicit)
        t.setflags(write=False)
        return t

    def luminance_of(self, values) -> np.ndarray:
        """The luminance in cd/m² (float64) that display values produce.

        Parameters
        ----------
        values : array_like of int
            Display values in ``0 .. 2**bits - 1``.

        Returns
        -------
        ndarray
            Same shape as ``values``.

        Raises
        ------
        ValueError
            A value that is not a whole number in ``0 .. 2**bits - 1``.

        Examples
        --------
        >>> d = Display(32.0, luminance=(0.0, 100.0), gamma=2.0, bits=8)
        >>> d.luminance_of([0, 255]).tolist()
        [0.0, 100.0]
        """
        v = as_array("values", values)
        if v.dtype.kind not in "biuf":
            raise TypeError(f"values must be integer display values, got dtype {v.dtype}")
        if v.dtype.kind == "f":
            if not np.all(np.isfinite(v)) or np.any(v != np.round(v)):
                raise ValueError(f"values must be whole display values in [0, {self.levels - 1}]")
        if v.size and (v.min() < 0 or v.max() > self.levels - 1):
            raise ValueError(f"values must be display values in [0, {self.levels - 1}] ({self.bits} bits), got "
                             f"[{v.min()}, {v.max()}]")
        return self.table[v.astype(np.int64)]

    def value_of(self, luminance) -> np.ndarray:
        """The continuous display value (float64) that gives ``luminance`` cd/m²: the inverse of :meth:`luminance_of`.

        Between two display values the luminance is taken linear (the
        response is known only at the values). Whole results are exact:
        ``value_of(luminance_of(v)) == v``.

        Raises
        ------
        ValueError
            A luminance outside ``[L_min, L_max]``, naming the limit.

        Examples
        --------
        >>> d = Display(32.0, luminance=(0.0, 100.0), gamma=1.0, bits=8)
        >>> float(d.value_of(50.0))
        127.5
        """
        L = np.asarray(_check_luminance("luminance", luminance, self), dtype=np.float64)
        t = self.table
        i = np.clip(np.searchsorted(t, L, side="right") - 1, 0, self.levels - 2)
        lo, hi = t[i], t[i + 1]
        return i + (L - lo) / (hi - lo)

    def step_at(self, luminance) -> np.ndarray:
        """The luminance step (cd/m²) between the two display values around ``luminance``.

        Examples
        --------
        >>> d = Display(32.0, luminance=(0.0, 255.0), gamma=1.0, bits=8)
        >>> float(d.step_at(100.0))
        1.0
        """
        v = np.floor(self.value_of(luminance)).astype(np.int64)
        v = np.minimum(v, self.levels - 2)
        return self.table[v + 1] - self.table[v]

    def as_dict(self) -> dict:
        """A JSON-ready description (for a stimulus's sidecar); ``Display(**d)`` or ``Display.from_lut`` rebuilds it."""
        d = {"pixels_per_degree": self.pixels_per_degree, "frame_rate": self.frame_rate,
             "luminance": list(self.luminance), "gamma": self.gamma, "bits": self.bits}
        if self.lut is not None:
            d["lut"] = list(self.lut)
        return d


def _scale(x, num, den):
    """``x * num / den`` rounded once: exactly (rationals) for a number, in extended precision for an array.

    One rounding: ``3 * 40 / 50`` in two float64 steps is
    2.4000000000000004, whose way back gives 3.0000000000000004; rounded
    once, 2.4 (the double nearest 12/5), and back 3.0.
    """
    if isinstance(x, float):
        return float(Fraction(x) * Fraction(num) / Fraction(den))
    ld = np.longdouble  # 64-bit mantissa on x86 (float64 elsewhere: two roundings there)
    return ((x.astype(ld) * ld(num)) / ld(den)).astype(np.float64)


def _real(name, x):
    """A finite real number or array, as float or float64 array (conversions accept both)."""
    if isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, (bool, np.bool_)):
        return check_real(name, x, lo=-_MAX_VALUE, hi=_MAX_VALUE)
    arr = as_array(name, x)
    if arr.dtype.kind not in "iuf":
        raise TypeError(f"{name} must be a real number or array, got dtype {arr.dtype}")
    arr = arr.astype(np.float64)
    if not np.all(np.isfinite(arr)) or (arr.size and np.max(np.abs(arr)) > _MAX_VALUE):
        raise ValueError(f"{name} must be finite, within +-{_MAX_VALUE:g}")
    return arr


# the largest magnitude a conversion takes: its product with any factor (at most 1e12) stays finite
_MAX_VALUE = 1e100


def _check_luminance(name, luminance, display):
    """Luminances (cd/m²) inside the display's range ``[L_min, L_max]``, as float64; the error names the limit."""
    L = as_array(name, luminance)
    if L.dtype.kind not in "biuf":
        raise TypeError(f"{name} must be real luminances in cd/m², got dtype {L.dtype}")
    L = L.astype(np.float64)
    if not np.all(np.isfinite(L)):
        raise ValueError(f"{name} must be finite luminances (cd/m²)")
    lo, hi = display.luminance
    if L.size and (L.min() < lo or L.max() > hi):
        raise ValueError(f"{name} must lie within the display's range [{lo:g}, {hi:g}] cd/m² "
                         f"(L_min, L_max), got [{L.min():.6g}, {L.max():.6g}]")
    return L


def _check_lut(lut, bits):
    """A measured table: 2**bits (1..16 bits) finite, non-negative, strictly increasing luminances, as a tuple."""
    t = as_array("lut", lut)
    if t.dtype.kind not in "biuf" or t.ndim != 1:
        raise ValueError(f"lut must be a flat sequence of luminances (cd/m²), got shape {t.shape} dtype {t.dtype}")
    n = t.size
    if n < 2 or n > 65536 or n & (n - 1):
        raise ValueError(f"lut must hold 2**bits entries for bits in 1..16 (2, 4, ..., 65536), got {n}")
    if bits is not None and n != 1 << bits:
        raise ValueError(f"lut must hold 2**bits = {1 << bits} entries for bits={bits}, got {n}")
    t = t.astype(np.float64)
    if not np.all(np.isfinite(t)) or t.min() < 0 or t.max() > _MAX_LUMINANCE:
        raise ValueError(f"lut must hold finite luminances in [0, {_MAX_LUMINANCE:g}] cd/m²")
    d = np.diff(t)
    if np.any(d <= 0):
        i = int(np.flatnonzero(d <= 0)[0])
        raise ValueError(f"lut must be strictly increasing (monotonic): lut[{i + 1}] = {t[i + 1]:g} cd/m² is not "
                         f"above lut[{i}] = {t[i]:g}")
    return tuple(float(x) for x in t)
