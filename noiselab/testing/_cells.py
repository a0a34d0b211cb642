"""The statistics the assertions stand on: independent periodogram cells and the laws they follow.

For a stationary Gaussian field sampled over its period, the discrete Fourier
coefficients of distinct frequencies are independent, and the power of a
cell ``k`` that is not its own mirror (``k != -k``) is ``S(k) E`` with ``E``
exponential of mean 1 (a chi-square with 2 degrees of freedom, halved). The
half spectrum that :func:`noiselab.analysis.power_spectrum` stores still holds
mirror pairs in its first (and, for even widths, last) column; the
functions here keep one cell of each pair and drop the self-mirrored ones
(chi-square with 1 dof), so that every cell they hand on is an independent
exponential draw. A Hann window correlates neighbouring cells: a sum over
many cells then has its variance multiplied by ``n sum(w**4) / sum(w**2)**2``
per windowed axis (35/18 for the periodic Hann window).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analysis import PowerSpectrum, noise_floor

# n sum(w^4) / (sum w^2)^2 for the periodic Hann window (exact for n >= 5): the variance of a sum of many
# tapered periodogram cells over that of untapered ones, per windowed axis
HANN_VARIANCE_FACTOR = 35.0 / 18.0


@dataclass(frozen=True)
class Cells:
    """The independent cells of a power spectrum (flat arrays, one entry per cell, DC left out)."""

    power: np.ndarray      # P (float64)
    radius: np.ndarray     # radial frequency, cycles/frame
    components: tuple      # per-axis frequencies, cycles/frame (the transformed axes, in order)
    floor: float           # the rounding floor of the spectrum (noise_floor)
    variance_factor: float  # 1 without a window, 35/18 per Hann-windowed axis
    n_ref: int             # the frame size N (last transformed axis)


def independent_cells(spec: PowerSpectrum) -> Cells:
    """One cell of each mirror pair of a half spectrum, DC and the self-mirrored cells left out.

    Only for spectra over every axis (images, volumes); a cell that is its
    own mirror (every index 0 or Nyquist) is real-valued (1 dof) and dropped.
    """
    shape, axes = spec.shape, spec.axes
    n_last = shape[axes[-1]]
    n_ref = int(n_last)
    idx = [np.broadcast_to(spec.frequency(a), spec.power.shape) for a in axes]
    last = idx[-1]
    keep = (last > 0) & (2 * last < n_last)  # columns whose mirror the half spectrum does not store
    decided = np.zeros(spec.power.shape, dtype=bool)
    for a, k in zip(axes[:-1], idx[:-1]):
        special = (k == 0) | (2 * np.abs(k) == shape[a])  # indices that are their own mirror on this axis
        keep |= ~keep & ~decided & ~special & (k > 0)
        decided |= ~special
    comps = tuple(np.asarray(k[keep], dtype=np.float64) * (n_ref / shape[a]) for a, k in zip(axes, idx))
    radius = np.sqrt(sum(c * c for c in comps))
    factor = HANN_VARIANCE_FACTOR ** len(spec.window_axes) if spec.window else 1.0
    return Cells(power=np.asarray(spec.power[keep], dtype=np.float64), radius=radius, components=comps,
                 floor=noise_floor(spec), variance_factor=factor, n_ref=n_ref)


def ring_index(radius: np.ndarray) -> np.ndarray:
    """Rings one cycle/frame wide centred on the integers (as ``noiselab.analysis`` bins orientation and axes)."""
    return np.rint(radius).astype(np.int64)


def live_band(cells: Cells, lo: float, hi: float) -> tuple[float, float] | None:
    """The longest run of rings inside ``[lo, hi]`` whose mean power stands above the rounding floor.

    The default band of the assertions (``band=None``): where the field has
    power, clipped to ``[lo, hi]``. None if no ring has power.
    """
    sel = (cells.radius >= lo - 0.5) & (cells.radius < hi + 0.5)
    if not sel.any():
        return None
    ring = ring_index(cells.radius[sel])
    n = int(ring.max()) + 1
    cnt = np.bincount(ring, minlength=n)
    tot = np.bincount(ring, weights=cells.power[sel], minlength=n)
    live = (cnt > 0) & (tot > cells.floor * np.maximum(cnt, 1))
    best, run_start, best_span = None, None, 0
    for i in range(n + 1):
        if i < n and live[i]:
            run_start = i if run_start is None else run_start
        elif run_start is not None:
            # only rings holding cells count; a run's length is its radial span
            if i - run_start > best_span:
                best, best_span = (run_start, i - 1), i - run_start
            run_start = None
    if best is None:
        return None
    # the run's rings are one cycle/frame wide: its ends are the outermost cells with power in them
    r = cells.radius[sel]
    ok = (ring >= best[0]) & (ring <= best[1]) & (cells.power[sel] > cells.floor)
    return max(lo, float(r[ok].min())), min(hi, float(r[ok].max()))
