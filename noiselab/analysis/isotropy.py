"""Isotropy: spectral energy against orientation, and one anisotropy index."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._core import as_array, check_int
from ._common import check_band, half_weight, noise_floor
from .spectrum import as_spectrum

__all__ = ["Orientation", "orientation_energy", "anisotropy", "RingAnisotropy", "ring_anisotropy"]


@dataclass(frozen=True)
class Orientation:
    """Spectral energy against the orientation of the frequency vector.

    Attributes
    ----------
    angles : ndarray
        Bin centres in degrees, in ``[0, 180)``, of the *wave vector*
        (``atan2(k_y, k_x)``; y points down the image). Stripes run
        perpendicular to it: a pattern of vertical stripes has its energy at 0.
    energy : ndarray
        Mean (radially whitened) power per cell in each orientation bin,
        normalised to mean 1: a flat line for an isotropic field.
    index : float
        The anisotropy index, ``max(m2, m4)``: 0 for isotropy, 1 for all the
        energy at a single orientation.
    m2, m4 : float
        Moduli of the second and fourth circular moments of ``energy``
        (``|sum E exp(i m theta)| / sum E``). ``m2`` sees one preferred
        orientation (oriented texture, motion streaks); ``m4`` sees a cross,
        the signature of an axis-aligned lattice, to which ``m2`` is blind.
    dominant : float
        The orientation of ``m2`` in degrees (the preferred wave-vector angle).
    axis_ratio : float
        Mean energy within 10 degrees of the x and y axes over the mean
        energy within 10 degrees of the diagonals (1 for isotropy, above 1
        for lattice noise showing its axes).
    """

    angles: np.ndarray
    energy: np.ndarray
    index: float
    m2: float
    m4: float
    dominant: float
    axis_ratio: float


def _plane(image, band, window, what):
    """The frame-averaged half power spectrum of an image or video, its frequency grid and the band's cells."""
    if isinstance(image, np.ndarray) or not hasattr(image, "power"):
        arr = as_array("image", image)
        if arr.ndim not in (2, 3):
            raise ValueError(f"image must be 2-D (height, width) or 3-D (frames, height, width), got shape {arr.shape}")
        spec = as_spectrum(arr, window=window, axes=(-2, -1))
    else:
        spec = image
    nd = len(spec.shape)
    if nd not in (2, 3) or spec.axes != (nd - 2, nd - 1):
        raise ValueError(f"{what} needs a spectrum over the two spatial axes of an image or video")
    h, w = spec.shape[-2:]
    n_ref = w
    ky = np.fft.fftfreq(h, 1.0 / h)[:, None] * (n_ref / h)
    kx = np.arange(w // 2 + 1, dtype=np.float64)[None, :] * (n_ref / w)
    r = np.hypot(kx, ky)
    lo, hi = check_band("band", (2.0, n_ref / 2.0) if band is None else band, n_ref / 2.0 * np.sqrt(2))
    p = spec.power
    if nd == 3:
        p = np.sum(p, axis=0, dtype=np.float64) / spec.shape[0]
    p = np.asarray(p, dtype=np.float64)
    inside = (r >= lo) & (r < hi)
    if not inside.any():
        raise ValueError(f"band ({lo:g}, {hi:g}) holds no frequency cell for a {h} x {w} image")
    weight = np.broadcast_to(half_weight(w)[None, :], r.shape)
    return spec, ky, kx, r, p, inside, weight, (lo, hi)


def orientation_energy(image, band=None, *, nbins=36, whiten=True, window=None) -> Orientation:
    """Energy against orientation of a 2-D image (or of each frame of a video, averaged).

    Every frequency cell of the band ``(lo, hi)`` cycles/frame is assigned to
    an orientation bin over ``[0, 180)`` degrees (a cell and its conjugate
    mirror share one orientation). With ``whiten`` each cell's power is first
    divided by a level of its radius (rings one cycle/frame wide), so that a
    steep 1/f spectrum does not hand the verdict to the handful of cells at the
    lowest frequencies:

    - ``True`` or ``"fit"`` (default): the level is a smooth fit of the radial
      spectrum (a quadratic in ``log f`` fitted to the log ring means with
      Tukey's biweight, so outlying rings do not pull it), or the ring's own
      mean where that is lower. A ring that stands above the trend (the one
      radius of a grating, a narrow band of oriented energy) keeps its excess
      and its orientation wins, whatever the noise floor around it; a smooth
      spectrum (1/f) is flattened, every radius counting by its cells.
    - ``"ring"``: every ring is divided by its own mean, so every radius counts
      the same. This outvotes a pattern whose energy sits on one ring by the
      noise of all the others (stripes with 1 % noise read 0.006).
    - ``False``: raw power (a 1/f field is then judged by its lowest rings).

    Parameters
    ----------
    image : array_like or PowerSpectrum
        ``(height, width)`` or ``(frames, height, width)``.
    band : (lo, hi), optional
        Cycles/frame; default ``(2, N/2)`` (below 2 cycles/frame the grid has too few
        cells to resolve orientation).
    nbins : int
        Orientation bins over 180 degrees (a multiple of 4 keeps the axes and
        diagonals on bin centres' symmetric positions).
    whiten : {True, "fit", "ring", False}
        Radial whitening (see above).
    window : {None, "hann"}
        See :func:`noiselab.analysis.power_spectrum`.

    Returns
    -------
    Orientation

    Examples
    --------
    >>> import numpy as np
    >>> y, x = np.mgrid[:64, :64]
    >>> o = orientation_energy(np.cos(2 * np.pi * (6 * x + 6 * y) / 64))
    >>> round(o.index, 2), round(o.dominant)
    (1.0, 45)
    """
    nbins = check_int("nbins", nbins, lo=4, hi=720)
    spec, ky, kx, r, p, inside, weight, (lo, hi) = _plane(image, band, window, "orientation_energy")
    cell_power = p
    if whiten:
        if whiten not in (True, "fit", "ring"):
            raise ValueError(f"whiten must be True, 'fit', 'ring' or False, got {whiten!r}")
        level, live = _ring_levels(r, p, weight, inside, noise_floor(spec), fit=whiten != "ring")
        # rings without power carry no orientation information: leave them out
        inside = inside & live
        cell_power = np.divide(p, level, out=np.zeros_like(p), where=inside)
    theta = np.mod(np.arctan2(ky, kx) + np.zeros_like(r), np.pi)
    # centre the bins on 0, 180/nbins, ...: shift by half a bin
    ob = np.floor(np.mod(theta / np.pi * nbins + 0.5, nbins)).astype(np.int64)
    sel = inside
    e_sum = np.bincount(ob[sel], weights=(weight * cell_power)[sel], minlength=nbins)
    e_cnt = np.bincount(ob[sel], weights=weight[sel], minlength=nbins)
    if not np.any(e_sum > 0):
        raise ValueError(f"the image has no power in band ({lo:g}, {hi:g}) cycles/frame")
    energy = np.divide(e_sum, e_cnt, out=np.zeros(nbins), where=e_cnt > 0)
    filled = e_cnt > 0
    angles = np.arange(nbins) * (180.0 / nbins)
    rad = np.deg2rad(angles)
    e = energy[filled]
    a = rad[filled]
    c2 = np.sum(e * np.exp(2j * a)) / np.sum(e)
    c4 = np.sum(e * np.exp(4j * a)) / np.sum(e)
    energy = energy / e.mean()
    dist_axis = np.minimum(np.abs(((angles + 45) % 90) - 45), 90)  # distance to nearest axis (0 or 90)
    near_axis = filled & (dist_axis <= 10)
    near_diag = filled & (np.abs(dist_axis - 45) <= 10)
    axis_ratio = float(energy[near_axis].mean() / energy[near_diag].mean()) if energy[near_diag].mean() > 0 else float("inf")
    dominant = float(np.rad2deg(np.angle(c2)) / 2.0) % 180.0
    return Orientation(
        angles=angles,
        energy=energy,
        index=float(max(abs(c2), abs(c4))),
        m2=float(abs(c2)),
        m4=float(abs(c4)),
        dominant=dominant,
        axis_ratio=axis_ratio,
    )


def anisotropy(image, band=None, *, nbins=36, window=None) -> float:
    """Anisotropy index of an image: 0 for an isotropic field, up to 1 for a single orientation.

    ``max(m2, m4)`` of :func:`orientation_energy` with its default whitening
    (a smooth fit of the radial spectrum): the larger of the two-fold (one
    preferred orientation) and four-fold (an axis-aligned cross, as lattice
    noise shows) circular moments. An isotropic random field gives a small
    positive value that shrinks with the number of cells (0.0036 for 1/f
    noise at 512 x 512, 0.19 averaged over 8 seeds in the 2-8 cycles/frame
    band of 256 x 256, which holds about 190 cells); stripes with 1 % noise
    give 0.9998 and single-octave lattice noise 0.52 (Catmull-Rom) to 0.98
    (cubic B-spline) (``tests/test_analysis.py``,
    ``tests/test_spectral_checks.py``). Rotating an oriented pattern leaves
    the index unchanged and turns :attr:`Orientation.dominant` with it. For
    the figure the blue-noise literature quotes, see :func:`ring_anisotropy`.

    Parameters
    ----------
    image : array_like (H, W)
        A finite 2-D field.
    band : (lo, hi), optional
        Radial band in cycles/frame (default: 2 to a quarter of the frame,
        where the field has power above the rounding floor).
    nbins : int, default 36
        Orientation bins over 180 degrees.
    window : {None, "hann"}, optional
        Spatial taper before the FFT; ``"hann"`` for fields that do not tile.

    Returns
    -------
    float
        In ``[0, 1]``.

    Raises
    ------
    ValueError
        For a non-finite image, or a band that is empty or past the
        Nyquist frequency.

    Examples
    --------
    >>> import numpy as np
    >>> rng = np.random.default_rng(0)
    >>> anisotropy(rng.standard_normal((256, 256))) < 0.05
    True
    >>> y, x = np.mgrid[:256, :256]
    >>> stripes = np.sin(2 * np.pi * x / 16) + 0.01 * rng.standard_normal((256, 256))
    >>> anisotropy(stripes) > 0.99   # all the energy is at one orientation
    True
    >>> orientation_energy(stripes, whiten="ring").index < 0.05   # ring by ring, the noise outvotes it
    True
    """
    return orientation_energy(image, band, nbins=nbins, window=window).index


def _robust_fit(x, y, w, degree, iterations=20):
    """Weighted polynomial fit of ``y(x)`` with Tukey's biweight, so that a few outlying points do not pull it."""
    rob = np.ones_like(y)
    coef = None
    for _ in range(iterations):
        ww = w * rob
        if np.count_nonzero(ww) <= degree:
            break
        coef = np.polynomial.polynomial.polyfit(x, y, degree, w=np.sqrt(ww))
        res = y - np.polynomial.polynomial.polyval(x, coef)
        order = np.argsort(np.abs(res))
        cum = np.cumsum(w[order])
        mad = np.abs(res)[order][np.searchsorted(cum, 0.5 * cum[-1])]
        scale = 1.4826 * mad
        if scale <= 0:
            break
        u = res / (4.685 * scale)
        new = np.where(np.abs(u) < 1, (1 - u**2) ** 2, 0.0)
        if np.allclose(new, rob):
            break
        rob = new
    return np.polynomial.polynomial.polyval(x, coef)


def _ring_levels(r, p, weight, inside, floor, *, fit=True):
    """Whitening level of every cell and the mask of the cells whose ring carries power.

    Rings are one cycle/frame wide (``rint(r)``). With ``fit`` the level is a
    smooth fit of the radial spectrum: a quadratic in ``log r`` fitted to the
    logarithm of the ring means (weighted by the rings' cells) with Tukey's
    biweight, so that a ring standing out from the trend (the one radius of a
    grating, a narrow band of oriented energy) keeps its excess instead of
    being divided away. Without ``fit`` every ring is divided by its own mean.
    """
    ring = np.rint(r).astype(np.int64)
    nring = int(ring.max()) + 1
    rs, ws, ps = ring[inside], weight[inside], p[inside]
    cnt = np.bincount(rs, weights=ws, minlength=nring)
    mean = np.divide(np.bincount(rs, weights=ws * ps, minlength=nring), cnt, out=np.zeros(nring), where=cnt > 0)
    radius = np.divide(np.bincount(rs, weights=ws * r[inside], minlength=nring), cnt, out=np.zeros(nring), where=cnt > 0)
    # rings at the rounding-noise floor are noise, not orientation
    live = mean > floor
    level = mean.copy()
    if fit and np.count_nonzero(live) >= 3:
        degree = 2 if np.count_nonzero(live) >= 6 else 1
        x, y = np.log(radius[live]), np.log(mean[live])
        trend = np.exp(_robust_fit(x, y, cnt[live], degree))
        # a ring above the trend keeps its excess; one below it counts like its cells (as ring by ring)
        level[live] = np.maximum(np.minimum(mean[live], trend), floor)
    return level[ring], live[ring]


@dataclass(frozen=True)
class RingAnisotropy:
    """Ulichney's anisotropy: the variance of the power around each ring over its mean squared.

    Attributes
    ----------
    centers : ndarray
        Ring radii in cycles/frame (rings one cycle/frame wide, centred on the integers).
    ratio : ndarray
        ``var / mean**2`` of the (frame-averaged) power over the ring's cells.
    db : ndarray
        ``10 log10(ratio)``.
    counts : ndarray
        Cells per ring (full spectrum).
    periodograms : int
        Periodograms averaged (frames of the input).
    mean_db : float
        Mean of :attr:`db` over the rings (each ring one vote), the single figure usually quoted.
    floor_db : float
        What an isotropic Gaussian field gives: ``-10 log10(periodograms)``
        (one periodogram's cells are exponential, ``var / mean**2 = 1``, 0 dB).
    """

    centers: np.ndarray
    ratio: np.ndarray
    db: np.ndarray
    counts: np.ndarray
    periodograms: int
    mean_db: float
    floor_db: float


def ring_anisotropy(image, band=None, *, window=None, min_cells=8) -> RingAnisotropy:
    """Ulichney's anisotropy in dB, ring by ring (as used to judge blue noise and procedural noise).

    For each ring of radius ``f`` (one cycle/frame wide) the periodogram's
    variance over the ring's cells divided by its mean squared (Ulichney,
    *Digital Halftoning*, 1987; Lagae et al., "A survey of procedural
    noise functions", 2010). A 3-D input ``(frames, height, width)`` is
    averaged over its K frames first, as Ulichney averages K periodograms:
    an isotropic Gaussian field then reads ``-10 log10 K`` dB (0 dB for one
    image), and anything well above that floor has structure around the ring.

    Parameters
    ----------
    image : array_like or PowerSpectrum
        ``(height, width)`` or ``(frames, height, width)`` (independent realisations).
    band : (lo, hi), optional
        Cycles/frame; default ``(2, N/2)``.
    window : {None, "hann"}
    min_cells : int
        Rings with fewer full-spectrum cells are left out (their variance means little).

    Returns
    -------
    RingAnisotropy

    Examples
    --------
    >>> import numpy as np
    >>> frames = np.random.default_rng(0).standard_normal((10, 128, 128))
    >>> round(ring_anisotropy(frames).mean_db)   # 10 white-noise periodograms: -10 dB
    -10
    """
    min_cells = check_int("min_cells", min_cells, lo=2)
    spec, ky, kx, r, p, inside, weight, (lo, hi) = _plane(image, band, window, "ring_anisotropy")
    k = spec.shape[0] if len(spec.shape) == 3 else 1
    ring = np.rint(r).astype(np.int64)
    nring = int(ring.max()) + 1
    rs, ws, ps = ring[inside], weight[inside], p[inside]
    cnt = np.bincount(rs, weights=ws, minlength=nring)
    s1 = np.bincount(rs, weights=ws * ps, minlength=nring)
    s2 = np.bincount(rs, weights=ws * ps * ps, minlength=nring)
    ok = (cnt >= min_cells) & (s1 > 0)
    if not ok.any():
        raise ValueError(f"band ({lo:g}, {hi:g}) holds no ring of at least {min_cells} cells with power")
    mean = s1[ok] / cnt[ok]
    ratio = np.maximum(s2[ok] / cnt[ok] - mean**2, 0.0) / mean**2
    with np.errstate(divide="ignore"):
        db = 10 * np.log10(ratio)
    finite = np.isfinite(db)
    return RingAnisotropy(centers=np.nonzero(ok)[0].astype(np.float64), ratio=ratio, db=db, counts=cnt[ok],
                          periodograms=k, mean_db=float(np.mean(db[finite])) if finite.any() else float("-inf"),
                          floor_db=-10 * np.log10(k) + 0.0)  # + 0.0: no "-0.0" for one periodogram
