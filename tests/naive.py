"""Slow, readable references for noiselab's fast paths (stumpy's ``tests/naive.py`` pattern).

Plain numpy, written from the papers in ``shared/seeds`` and from noiselab's
docstrings, never from its kernels: loops where they make a formula plain,
dense full spectra, a direct sum over lattice points. ``tests/test_naive.py``
checks that every fast path equals these on random inputs.

Sources:
- Langer & Zhang, "Rendering falling snow using an inverse Fourier transform"
  (2003) and Zhang's thesis (McGill, 2003): ``[LZ]`` and ``[Z]`` below.
- Phillips, "Creating noisy stimuli", Perception 33 (2004): ``[P]``.
- Perlin, "Improving noise" (SIGGRAPH 2002) for the 3-D gradient set.

Nothing here imports noiselab: a reference that reused the package's code
would test nothing.
"""
from __future__ import annotations

import copy
import math

import numpy as np
import scipy.optimize

# ============================================================================ spectral synthesis
#
# noiselab.spectral.synthesis: a real field is irfftn(S) with
# S = envelope * a * exp(i*theta) on the half spectrum, exact conjugacy on the
# self-conjugate planes ([Z] Eq. 2.7 and 3.4), E[a**2] = 1.


def frequency_vectors(shape):
    """Angular frequencies (rad/sample) of the ``rfftn`` half spectrum, one broadcast vector per axis.

    ``w_i = 2*pi*fftfreq(n_i)`` (the last axis ``2*pi*rfftfreq``) as in [Z]
    section 2.2 (frequencies in ``[-pi, pi]``).
    """
    d = len(shape)
    out = []
    for i, n in enumerate(shape):
        f = np.fft.rfftfreq(n) if i == d - 1 else np.fft.fftfreq(n)
        view = [1] * d
        view[i] = f.size
        out.append((2 * np.pi * f).reshape(view))
    return out


_GOLDEN = 0x9E3779B97F4A7C15
_MASK64 = (1 << 64) - 1


def splitmix64(key, i):
    """Word ``i`` (array of ints) of the counter-based SplitMix64 stream keyed by ``key`` (Steele et al. 2014).

    The stream's state after ``i + 1`` steps is ``key + (i + 1) * golden``
    (mod 2**64); the word is Stafford's "mix13" finaliser of that state.
    Written with Python integers: nothing wraps by accident.
    """
    out = np.empty(len(i), dtype=np.uint64)
    for n, ii in enumerate(i):
        z = (int(key) + (int(ii) + 1) * _GOLDEN) & _MASK64
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & _MASK64
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & _MASK64
        out[n] = z ^ (z >> 31)
    return out


def _split_word(z):
    """The two halves of a stream word: ``u = (2h + 1) / 2**33`` in (0, 1) from the high 32 bits ``h``, and the low 32 bits ``l``."""
    h = (z >> np.uint64(32)).astype(np.int64)
    low = (z & np.uint64(0xFFFFFFFF)).astype(np.int64)
    return 2 * h + 1, low


def coefficient_parts_exact(key, n, amplitude):
    """Coefficient ``i`` = word ``i`` of the stream, in exact float64 math: ``(a**2, cos th, sin th)``.

    The construction documented in ``noiselab.spectral.synthesis``: ``u``
    uniform on (0, 1) from the high 32 bits, the phase ``th = 2*pi*l/2**32``
    from the low 32 bits; ``a = sqrt(3) u`` ("uniform", ``E[a**2] = 1``),
    ``a = sqrt(-log u)`` ("rayleigh": with the phase, Box-Muller's complex
    Gaussian) or 1 ("fixed").
    """
    w, low = _split_word(splitmix64(key, np.arange(n)))
    u = w / 2.0 ** 33
    a2 = {"uniform": 3 * u * u, "rayleigh": -np.log(u), "fixed": np.ones(n)}[amplitude]
    th = 2 * np.pi * low / 2.0 ** 32
    return a2, np.cos(th), np.sin(th)


def coefficient_parts(key, n, amplitude):
    """The same parts as :func:`coefficient_parts_exact`, in the float32 arithmetic noiselab documents.

    ``noiselab.spectral.synthesis`` stores the parts in float32, computed by
    polynomials whose truncation error is below 1e-9 (``spectral/_kernels.py``
    docstrings): ``u = (h + 1/2) / 2**32`` rounded to float32, ``-log u`` by an
    exact range reduction ``u = 2**e m`` (float32's exponent and mantissa,
    ``m`` moved into ``[sqrt(1/2), sqrt(2))``) and
    ``log m = 2 atanh((m - 1)/(m + 1))`` to the ninth power; the phase's
    three top bits pick an octant, the other 29 an angle ``y`` in
    ``[0, pi/4]`` whose sine (to ``y**9``) and cosine (to ``y**10``) are
    Taylor polynomials. Written here operation by operation in numpy
    float32, so the bits match; ``tests/test_naive.py`` checks these parts
    against the exact math of :func:`coefficient_parts_exact`.
    """
    f = np.float32
    z = splitmix64(key, np.arange(n))
    h = (z >> np.uint64(32)).astype(np.uint32)
    low = (z & np.uint64(0xFFFFFFFF)).astype(np.int64)
    u = h.astype(f) * f(2.0 ** -32) + f(2.0 ** -33)  # (h + 1/2) / 2**32 rounded to float32
    if amplitude == "rayleigh":
        b = u.view(np.int32)
        e = (b >> 23) - 127  # u = 2**e * m, m in [1, 2): float32's own exponent and mantissa
        m = ((b & 0x7FFFFF) | 0x3F800000).astype(np.int32).view(f)
        big = m > f(np.sqrt(2.0))
        m = np.where(big, m * f(0.5), m)
        ef = np.where(big, e + 1, e).astype(f)
        t = (m - f(1)) / (m + f(1))
        t2 = t * t
        logm = f(2) * t * (f(1) + t2 * (f(1 / 3) + t2 * (f(1 / 5) + t2 * (f(1 / 7) + t2 * f(1 / 9)))))
        a2 = -(ef * f(np.log(2.0)) + logm)  # -log(2**e m)
    elif amplitude == "uniform":
        a2 = f(3) * u * u
    else:
        a2 = np.ones(n, f)
    octant = low >> 29
    x = (low & 0x1FFFFFFF).astype(f) * f((np.pi / 4) * 2.0 ** -29)
    odd = (octant & 1) == 1
    y = np.where(odd, f(np.pi / 4) - x, x)
    y2 = y * y
    sn = y * (f(1) + y2 * (f(-1 / 6) + y2 * (f(1 / 120) + y2 * (f(-1 / 5040) + y2 * f(1 / 362880)))))
    cs = f(1) + y2 * (f(-1 / 2) + y2 * (f(1 / 24) + y2 * (f(-1 / 720) + y2 * (f(1 / 40320) + y2 * f(-1 / 3628800)))))
    # the angle inside the quadrant is y (even octant) or pi/2 - y (odd): swap sine and cosine
    cq, sq = np.where(odd, sn, cs), np.where(odd, cs, sn)
    q = octant >> 1  # th = q * pi/2 + angle
    c = np.where(q & 1, sq, cq)
    s = np.where(q & 1, cq, sq)
    c = np.where((q == 1) | (q == 2), -c, c)
    s = np.where(q >= 2, -s, s)
    return a2.astype(f), c.astype(f), s.astype(f)


def stream_key(seed):
    """The coefficient stream's key: one 64-bit word of the caller's generator (``default_rng(seed)`` for an int)."""
    rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
    return int(rng.integers(0, 2 ** 64, dtype=np.uint64))


def draw_coefficients(n, rng, amplitude="uniform"):
    """``n`` coefficients ``a * exp(i*phi)`` drawn with ``rng.random``: all amplitudes first, then all phases.

    ``a`` uniform on ``[0, sqrt(3)]`` ([Z] 3.2: "an amplitude varying between
    0 and 1", rescaled to ``E[a**2] = 1``), ``sqrt(-log(1 - U))`` (Rayleigh) or
    1; ``phi`` uniform on ``[0, 2*pi)`` ([Z] 3.2: "a random phase varying
    between 0 and 2*pi"). complex128.
    """
    rng = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(rng)
    if amplitude == "uniform":
        a = rng.random(n) * np.sqrt(3.0)
    elif amplitude == "rayleigh":
        a = np.sqrt(-np.log1p(-rng.random(n)))
    else:
        a = np.ones(n)
    phi = rng.random(n) * (2 * np.pi)
    return a * np.cos(phi) + 1j * a * np.sin(phi)


def mirror_index(k, shape):
    """The index of ``-k`` (each component modulo its axis length)."""
    return tuple((-ki) % n for ki, n in zip(k, shape))


def hermitian_plane(plane, support=None):
    """Make a self-conjugate plane Hermitian, ``P[-k] = conj(P[k])`` ([Z] Eq. 3.4), cell by cell.

    Of each mirror pair ``(k, -k)`` the first in C order (the canonical cell)
    keeps its value and the other gets its conjugate; if only the other one
    is in the support, its value is used for both. A cell equal to its own
    mirror becomes real with its magnitude kept: ``|v| * sign(Re v)``
    (``+`` for ``Re v = 0``).
    """
    plane = np.asarray(plane, dtype=np.complex128)
    support = plane != 0 if support is None else np.asarray(support, dtype=bool)
    out = plane.copy()
    flat = list(np.ndindex(plane.shape))
    order = {k: i for i, k in enumerate(flat)}
    for k in flat:
        m = mirror_index(k, plane.shape)
        if m == k:
            v = plane[k]
            out[k] = abs(v) * (1.0 if v.real >= 0 else -1.0)
        elif order[k] < order[m]:
            v = plane[m].conjugate() if (not support[k] and support[m]) else plane[k]
            out[k] = v
            out[m] = np.conj(v)
    return out


def self_conjugate_columns(width):
    """kx indices whose plane is its own mirror: 0, and ``W/2`` for an even width ``W > 1``."""
    return [0] + ([width // 2] if width % 2 == 0 and width > 1 else [])


def synthesize(shape, envelope, seed, amplitude="uniform", parts=coefficient_parts):
    """The spectral plan of :func:`noiselab.spectral.synthesize`, in float64: returns ``(field, S)``.

    1. The envelope on the half spectrum (a callable gets the frequency vectors).
    2. Coefficient ``j`` of the stream (:func:`coefficient_parts`) goes to the
       ``j``-th cell with ``env > 0`` in C order:
       ``S = env * sqrt(a**2) * (c + i s) / |c + i s|`` (the phase normalised
       to float64's unit circle), 0 elsewhere.
    3. The self-conjugate planes (kx = 0, W/2) made Hermitian with the
       envelope's support (:func:`hermitian_plane`).
    4. ``field = irfftn(S)``.
    """
    hshape = tuple(shape[:-1]) + (shape[-1] // 2 + 1,)
    env = envelope(*frequency_vectors(shape)) if callable(envelope) else envelope
    env = np.broadcast_to(np.asarray(env, dtype=np.float64), hshape)
    cells = np.flatnonzero(env > 0)
    a2, c, s = (p.astype(np.float64) for p in parts(stream_key(seed), cells.size, amplitude))
    S = np.zeros(hshape, dtype=np.complex128)
    S.flat[cells] = env.flat[cells] * np.sqrt(a2 / (c * c + s * s)) * (c + 1j * s)
    for j in self_conjugate_columns(shape[-1]):
        S[..., j] = hermitian_plane(S[..., j], env[..., j] > 0)
    return np.fft.irfftn(S, s=shape, axes=range(len(shape))), S


def noise_envelope(shape, exponent, band, dc):
    """The envelope of :func:`noiselab.spectral.spectral_noise` (its cells and their relative amplitudes).

    The annulus ``lo <= f <= hi`` ([Z] 3.2.2; ``f`` the radial frequency in
    cycles/sample, the band given in cycles per ``shape[-1]`` samples,
    inclusive to a relative 1e-12; DC only with ``dc``; no band: every
    frequency) times the power law ``f**-exponent`` ([Z] 3.2.3), taken flat
    below the grid's lowest nonzero frequency ``1/max(shape)`` (only DC is
    there) and 0 at DC for ``exponent < 0``. Returns ``(cells, law)``: the
    boolean cells that take a coefficient, and the law there.
    """
    w = frequency_vectors(shape)
    f = np.sqrt(sum(wi ** 2 for wi in w)) / (2 * np.pi)
    n = shape[-1]
    if band is None:
        cells = (f > 0) | dc
    else:
        lo, hi = band[0] / n, band[1] / n
        cells = (f >= lo * (1 - 1e-12)) & (f <= hi * (1 + 1e-12)) & ((f > 0) | dc)
    fmin = 1.0 / max(m for m in shape if m > 1)
    with np.errstate(divide="ignore"):
        law = np.maximum(f, fmin) ** -exponent if exponent > 0 else np.where(f > 0, f, 0.0) ** -exponent
    if exponent < 0:
        law = np.where(f > 0, law, 0.0)
    return np.broadcast_to(cells, f.shape), np.broadcast_to(law, f.shape)


def spectral_noise(shape, exponent=1.0, band=None, seed=0, amplitude="rayleigh", normalize="expected", dc=False):
    """:func:`noiselab.spectral.spectral_noise` from its definition: annulus x power law, one coefficient per cell.

    The cells of :func:`noise_envelope` take the stream's coefficients in C
    order (DC included with ``dc``, even where the law is 0 there), the
    self-conjugate planes are made Hermitian, and the field is scaled to unit
    variance: ``"expected"`` divides by the ensemble's standard deviation,
    ``sqrt(sum over the full spectrum of law**2) / N`` (Parseval, ``E[a**2] = 1``;
    about 0, so DC counts), ``"sample"`` by this field's own standard deviation
    about its mean.
    """
    cells, law = noise_envelope(shape, exponent, band, dc)
    idx = np.flatnonzero(cells)
    a2, c, s = (p.astype(np.float64) for p in coefficient_parts(stream_key(seed), idx.size, amplitude))
    S = np.zeros(law.shape, dtype=np.complex128)
    S.flat[idx] = law.flat[idx] * np.sqrt(a2 / (c * c + s * s)) * (c + 1j * s)
    for j in self_conjugate_columns(shape[-1]):
        S[..., j] = hermitian_plane(S[..., j], cells[..., j])
    field = np.fft.irfftn(S, s=shape, axes=range(len(shape)))
    if normalize == "sample":
        return field / field.std()
    full = np.where(cells, law, 0.0) ** 2
    weight = np.full(shape[-1] // 2 + 1, 2.0)  # a half-spectrum column stands for itself and its mirror
    weight[self_conjugate_columns(shape[-1])] = 1.0
    expected_power = float(np.sum(full * weight))  # sum over the full spectrum of E|S|**2
    return field * (np.prod(shape) / np.sqrt(expected_power))


# ============================================================================ the tent (falling snow)


def tent_surface(wy, wx, c, direction=(0.0, 1.0), pan=(0.0, 0.0)):
    """Temporal frequency (rad/frame) of the tent at spatial frequency ``(wy, wx)`` rad/px, and its thickness unit.

    [Z] Eq. 3.3 ``w_t = C w_v / |w|`` with numpy's FFT sign (a pattern moving
    at ``v`` has ``w_t = -v . w``, [Z] Eq. 2.8): flakes falling along the unit
    direction ``d`` at ``c / |w|`` px/frame give ``w_t = -c (d . w) / |w|``; a
    panning camera adds ``-pan . w`` (the sheared tent, [Z] Eq. 4.2). Returns
    ``(w_t, |d . w| / |w|)``; both 0 at DC.
    """
    wy, wx = np.broadcast_arrays(np.asarray(wy, dtype=float), np.asarray(wx, dtype=float))
    d = np.array(direction, dtype=float) / np.hypot(*direction)
    r = np.hypot(wy, wx)
    along = np.zeros(r.shape)
    np.divide(d[0] * wx + d[1] * wy, r, out=along, where=r > 0)
    return -c * along - (pan[0] * wx + pan[1] * wy), np.abs(along)


def tent_spectrum(shape, seed=0, c=1.0, band=None, thickness=0.1, direction=(0.0, 1.0), pan=(0.0, 0.0),
                  exponent=1.0, amplitude="uniform", on_alias="drop"):
    """The falling-snow half spectrum of :func:`noiselab.snowfall.snow_spectrum`, cell by cell ([LZ], [Z] ch. 3-4).

    - Band ([Z] 3.2.2): the spatial cells with ``lo <= |f| <= hi`` (cycles per
      frame *width*, inclusive; default ``(W/32, W/4)``, i.e. 16..128 cycles/frame
      at 512 px), DC excluded; ``f = (ky/H, kx/W)`` cycles/pixel.
    - Tent ([Z] Eq. 3.3, ``w_t = C w_v / |w|``): with numpy's FFT sign a pattern
      moving at ``v`` has ``w_t = -v . w`` ([Z] Eq. 2.8 measured with numpy), so
      flakes falling along the unit direction ``d`` at ``c/|w|`` px/frame lie on
      ``w_t = -c (d . w)/|w|``; a panning camera adds ``-pan . w`` (the sheared
      tent, [Z] Eq. 4.2). Thickened ([Z] 3.2.1): the constant spread over
      ``c (1 +- thickness)``, a half-width ``thickness c |d . w|/|w|``.
    - A cell gets the temporal bins ``n`` its (thickened) surface overlaps,
      ``|n - T w_t / (2 pi)| <= 1/2 + half-width`` in bins, within the
      Nyquist range ``|n| <= T/2`` (``n`` and ``n + T`` are one bin; bins past
      it are left out, ``on_alias="drop"``: the reference never raises); a
      still (``T = 1``) has the single bin 0.
    - Amplitude ``|w|**-exponent`` ([Z] 3.2.3, ``|w|`` in rad/px) split evenly
      over the cell's bins (divided by the square root of their count).
    - Random coefficients (:func:`draw_coefficients`) in the order: spatial
      cells in C order of ``(ky, kx)`` indices, then bins by increasing ``n``;
      the self-conjugate planes made Hermitian ([Z] Eq. 3.4).
    """
    T, H, W = shape
    lo, hi = (W / 32, W / 4) if band is None else band
    cells, bins, amps = [], [], []
    for ky in range(H):
        for kx in range(W // 2 + 1):
            fy, fx = np.fft.fftfreq(H)[ky], kx / W
            f = np.hypot(fy, fx) * W  # cycles/frame
            if not (f > 0 and lo * (1 - 1e-12) <= f <= hi * (1 + 1e-12)):
                continue
            wy, wx = 2 * np.pi * fy, 2 * np.pi * fx
            r = np.hypot(wy, wx)
            wt, along = (float(v) for v in tent_surface(wy, wx, c, direction, pan))
            half = thickness * c * along
            if T == 1:
                mine = [0]
            else:
                x, hw = wt * T / (2 * np.pi), half * T / (2 * np.pi)
                mine = []
                for n in range(-T, T + 1):
                    if abs(n - x) <= 0.5 + hw and abs(n) <= T / 2 and n % T not in [m % T for m in mine]:
                        mine.append(n)
            for n in mine:
                cells.append((ky, kx))
                bins.append(n % T)
                amps.append(r ** -float(exponent) / np.sqrt(len(mine)))
    coef = draw_coefficients(len(cells), np.random.default_rng(seed) if not isinstance(seed, np.random.Generator)
                             else seed, amplitude) * np.array(amps)
    S = np.zeros((T, H, W // 2 + 1), dtype=np.complex128)
    support = np.zeros(S.shape, dtype=bool)
    for (ky, kx), b, v in zip(cells, bins, coef):
        S[b, ky, kx] = v
        support[b, ky, kx] = True
    for j in self_conjugate_columns(W):
        S[:, :, j] = hermitian_plane(S[:, :, j], support[:, :, j])
    return S


def rescale_opacity(field, beta=1.5):
    """Opacity ``((f - min) / (max - min)) ** beta`` ([Z] 3.3, beta = 1.5)."""
    return ((field - field.min()) / (field.max() - field.min())) ** beta


# ============================================================================ analysers


def power_spectrum(field, window=None, window_axes=None):
    """Full power spectrum ``|FFT(f - mean f)|**2 / n**2`` (``fftn`` layout), summing to the variance (Parseval).

    ``window="hann"``: the field is multiplied by a periodic Hann window
    ``1/2 - 1/2 cos(2 pi j / n)`` along ``window_axes`` (default all) and the
    power divided by the window's mean square.
    """
    f = np.asarray(field, dtype=np.float64)
    f = f - f.mean()
    scale = 1.0
    if window == "hann":
        for ax in range(f.ndim) if window_axes is None else window_axes:
            n = f.shape[ax]
            w = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(n) / n)
            shape = [1] * f.ndim
            shape[ax] = n
            f = f * w.reshape(shape)
            scale *= np.mean(w ** 2)
    P = np.abs(np.fft.fftn(f)) ** 2 / f.size ** 2 / scale
    if window is None:
        P.flat[0] = 0.0  # the mean was removed: DC holds only its rounding
    return P


def radial_frequency_cpf(shape):
    """Radial frequency of every full-spectrum cell in cycles/frame: ``|k_i N / n_i|`` with ``N`` the last axis's length."""
    N = shape[-1]
    grids = np.meshgrid(*[np.fft.fftfreq(n, 1.0 / n) * (N / n) for n in shape], indexing="ij")
    return np.sqrt(sum(g ** 2 for g in grids))


def radial_spectrum(field, edges=None, log=False, frames=False):
    """Radially averaged power spectrum: per bin ``[e_b, e_{b+1})`` the mean power per full-spectrum cell.

    Default bins: one per integer frequency ``k = 1 .. floor(N/2)`` (``k +- 1/2``);
    with ``log``, 8 per octave from 1 to ``N/2`` (edges widened by 1e-9).
    ``frames``: a video's spatial spectrum, each frame's (mean removed)
    power averaged over the frames. Returns a dict with ``centers`` (arithmetic,
    or geometric for log bins), ``power``, ``counts``, ``variance`` (of the cell
    powers), ``mean_frequency``, ``total``; empty bins dropped.
    """
    f = np.asarray(field, dtype=np.float64)
    if frames:
        P = np.mean([power_spectrum(fr) for fr in f], axis=0)
    else:
        P = power_spectrum(f)
    r = radial_frequency_cpf(P.shape)
    fmax = P.shape[-1] / 2.0
    if edges is None:
        if log:
            nb = max(int(np.ceil(np.log2(fmax) * 8)), 1)
            edges = np.geomspace(1 - 1e-9, fmax * (1 + 1e-9), nb + 1)
        else:
            edges = np.arange(0.5, np.floor(fmax) + 0.5 + 1e-9, 1.0)
    out = {k: [] for k in ("centers", "power", "counts", "variance", "mean_frequency")}
    for lo, hi in zip(edges[:-1], edges[1:]):
        inside = (r >= lo) & (r < hi)
        if not inside.any():
            continue
        p = P[inside]
        out["centers"].append(np.sqrt(lo * hi) if log else (lo + hi) / 2)
        out["power"].append(p.mean())
        out["counts"].append(p.size)
        out["variance"].append(p.var())
        out["mean_frequency"].append(r[inside].mean())
    out = {k: np.array(v, dtype=np.float64) for k, v in out.items()}
    out["total"] = float(P.sum())
    return out


def spectral_slope(field, band, bins_per_octave=8):
    """Slope of ``log10 sqrt(P)`` against ``log10 f`` over ``band`` (1/f amplitude gives -1).

    Log-spaced bins (``bins_per_octave``, the top edge inclusive), each at its
    cells' mean frequency, fitted by least squares weighted by the bins' cell
    counts. Returns ``(slope, intercept, standard error)``.
    """
    lo, hi = band
    nb = max(int(np.ceil(np.log2(hi / lo) * bins_per_octave)), 1)
    edges = np.geomspace(lo, hi, nb + 1)
    edges[-1] *= 1 + 1e-12
    rs = radial_spectrum(field, edges=edges, log=True)
    x, y, w = np.log10(rs["mean_frequency"]), 0.5 * np.log10(rs["power"]), rs["counts"]
    slope, intercept = np.polyfit(x, y, 1, w=np.sqrt(w))  # polyfit weights multiply the residuals
    resid = y - (intercept + slope * x)
    sxx = np.sum(w * (x - np.average(x, weights=w)) ** 2)
    return slope, intercept, np.sqrt(np.sum(w * resid ** 2) / max(x.size - 2, 1) / sxx)


def _surface_fraction(video, kt_surface, tol, band, window):
    """Fraction of the power on the cells within ``tol`` temporal bins (mod T) of ``kt_surface(ky, kx)``, in ``band``."""
    T, H, W = video.shape
    P = power_spectrum(video, window=window, window_axes=(0,))
    on = 0.0
    for kt in range(T):
        for ky in range(H):
            for kx in range(W):
                fy, fx = np.fft.fftfreq(H, 1.0 / H)[ky], np.fft.fftfreq(W, 1.0 / W)[kx]
                r = np.hypot(fx, fy * W / H)  # cycles/frame
                if band is not None and not (r > 0 and band[0] <= r <= band[1]):
                    continue
                pred, width = kt_surface(fy, fx)
                dist = (kt - pred) % T
                if min(dist, T - dist) <= tol + width + 1e-9:
                    on += P[kt, ky, kx]
    return on / P.sum()


def motion_energy(video, velocity, tol=1.0, band=None, window=None):
    """Fraction of a video's power on the motion plane ``w_t = -v . w`` ([Z] Eq. 2.8, numpy's FFT sign).

    In bins: ``k_t = -T (v_x k_x / W + v_y k_y / H)``; a cell counts when its
    temporal bin is within ``tol`` of that, modulo ``T``.
    """
    T, H, W = video.shape
    vx, vy = velocity
    return _surface_fraction(video, lambda ky, kx: (-T * (vx * kx / W + vy * ky / H), 0.0), tol, band, window)


def tent_energy(video, c, band, direction=(0.0, 1.0), pan=(0.0, 0.0), thickness=0.1, tol=0.5, window=None):
    """Fraction of the power on the (thickened, sheared) tent inside ``band`` (see :func:`tent_spectrum`)."""
    T, H, W = video.shape

    def surface(ky, kx):
        wt, along = tent_surface(2 * np.pi * ky / H, 2 * np.pi * kx / W, c, direction, pan)
        return float(wt) * T / (2 * np.pi), thickness * c * float(along) * T / (2 * np.pi)

    return _surface_fraction(video, surface, tol, band, window)


# ============================================================================ lattice noise ([P] section 2)


def bspline(m, y):
    """Centred B-spline of order ``m`` ([P] 2.1.1: ``m`` box filters in a row), by truncated powers.

    ``B_m(y) = 1/(m-1)! sum_k (-1)**k C(m, k) (y + m/2 - k)_+**(m-1)``; the
    box (``m = 1``) is 1 on ``[-1/2, 1/2)``.
    """
    y = np.asarray(y, dtype=np.float64)
    out = np.zeros_like(y)
    for k in range(m + 1):
        z = y + m / 2 - k
        part = np.where(z >= 0, np.where(z >= 0, z, 0.0) ** (m - 1), 0.0)
        out += (-1) ** k * math.comb(m, k) * part
    return out / math.factorial(m - 1)


def catmull_rom(y):
    """The interpolating (Catmull-Rom, Keys a = -1/2) cubic kernel."""
    a = np.abs(np.asarray(y, dtype=np.float64))
    return np.where(a < 1, 1.5 * a ** 3 - 2.5 * a ** 2 + 1,
                    np.where(a < 2, -0.5 * a ** 3 + 2.5 * a ** 2 - 4 * a + 2, 0.0))


def fade(t):
    """Perlin's quintic fade ``6t^5 - 15t^4 + 10t^3``."""
    return t ** 3 * (t * (6 * t - 15) + 10)


def quintic(y):
    """Perlin's (2002) interpolant as a kernel: ``1 - fade(|y|)`` on ``|y| < 1``."""
    a = np.abs(np.asarray(y, dtype=np.float64))
    return np.where(a < 1, 1 - fade(np.minimum(a, 1.0)), 0.0)


KERNELS = {
    "box": lambda y: bspline(1, y),
    "linear": lambda y: bspline(2, y),
    "quadratic": lambda y: bspline(3, y),
    "cubic": lambda y: bspline(4, y),
    "catmull-rom": catmull_rom,
    "quintic": quintic,
}


def _bspline_derivative(m):
    return lambda y: bspline(m - 1, np.asarray(y) + 0.5) - bspline(m - 1, np.asarray(y) - 0.5)


def _catmull_rom_derivative(y):
    y = np.asarray(y, dtype=np.float64)
    a = np.abs(y)
    return np.sign(y) * np.where(a < 1, 4.5 * a ** 2 - 5 * a, np.where(a < 2, -1.5 * a ** 2 + 5 * a - 4, 0.0))


def _quintic_derivative(y):
    y = np.asarray(y, dtype=np.float64)
    a = np.minimum(np.abs(y), 1.0)
    return -np.sign(y) * 30 * a ** 2 * (1 - a) ** 2


DERIVATIVES = {  # the C1 kernels' derivatives (B_m' = B_{m-1}(y + 1/2) - B_{m-1}(y - 1/2))
    "quadratic": _bspline_derivative(3),
    "cubic": _bspline_derivative(4),
    "catmull-rom": _catmull_rom_derivative,
    "quintic": _quintic_derivative,
}


def _sup_on_unit(f):
    """``sup`` of a function on [0, 1]: a dense grid, then Brent's method around the best sample."""
    t = np.linspace(0.0, 1.0, 4097)
    v = f(t)
    i = int(np.argmax(v))
    best = float(v[i])
    lo, hi = t[max(i - 1, 0)], t[min(i + 1, t.size - 1)]
    res = scipy.optimize.minimize_scalar(lambda s: -float(f(np.array([s]))[0]), bounds=(lo, hi), method="bounded",
                                         options={"xatol": 1e-13})
    return max(best, -float(res.fun))


def kernel_sums(kernel):
    """``S = sup_y sum_i |K(y - i)|`` and ``Q = sup_y sum_i |K(y - i)| (y - i)**2`` (noiselab's range bounds).

    With lattice values in [-1, 1] a tensor-product kernel keeps value noise
    within ``S**d``, gradient noise within ``sqrt(d Q) S**(d - 1/2)``
    (Cauchy-Schwarz and Jensen: the ``LatticeNoise`` docstring).
    """
    K = KERNELS[kernel]
    near = np.arange(-3, 4)

    def abs_sum(t):
        return np.sum(np.abs(K(t[:, None] - near)), axis=1)

    def moment(t):
        z = t[:, None] - near
        return np.sum(np.abs(K(z)) * z ** 2, axis=1)

    return _sup_on_unit(abs_sum), _sup_on_unit(moment)


def grid_axis_taps(coords, freq, phase, shift, left, coef, period, grad):
    """One grid axis's taps sample by sample: ``(lattice, pos, w, rw)`` as the grid path makes them.

    ``u = x freq + phase + shift``, ``fi = floor(u)``, ``t = u - fi``; tap
    ``k`` of a sample sits on lattice point ``fi - left + k`` with weight
    ``sum_p coef[k, p] t**p``, summed from the powers in pairs as the engine's
    one weight polynomial is (``(c0 + c1 t) + (c2 t2 + c3 t3) + (c4 t4 + c5 t5)``,
    ``t4 = t2 t2``: float64 rounds a different order differently).
    ``lattice``: the distinct taps' indices modulo ``period`` (exact Python
    integers), in increasing order of the unreduced index; ``pos``: each
    sample's taps' places in it; ``rw``: the weights times the signed
    distances ``t - shift + left - k`` (``grad``), else the weights.
    """
    taps = coef.shape[0]
    w = np.empty((len(coords), taps))
    rw = np.empty((len(coords), taps))
    floors = []
    for j, x in enumerate(coords):
        u = x * freq + phase + shift
        fi = np.floor(u)
        t = u - fi
        floors.append(int(fi))
        t2 = t * t
        t3 = t2 * t
        t4 = t2 * t2
        t5 = t4 * t
        for k in range(taps):
            c = coef[k]
            w[j, k] = (c[0] + c[1] * t) + (c[2] * t2 + c[3] * t3) + (c[4] * t4 + c[5] * t5)
            rw[j, k] = w[j, k] * (t - shift + (left - k)) if grad else w[j, k]
    lo = min(floors)
    raw = np.array([[f - lo + k for k in range(taps)] for f in floors], dtype=np.int64)
    offsets, pos = np.unique(raw, return_inverse=True)
    lattice = np.array([(lo - left + int(r)) % period for r in offsets], dtype=np.int64)
    return lattice, pos.reshape(raw.shape).astype(np.int64), w, rw


def mix32(h):
    """MurmurHash3's 32-bit finaliser less its last xor-shift, on uint32 words (Python ints inside)."""
    out = np.empty(len(h), dtype=np.uint32)
    for n, v in enumerate(h):
        v = int(v) & 0xFFFFFFFF
        v ^= v >> 16
        v = (v * 0x85EBCA6B) & 0xFFFFFFFF
        v ^= v >> 13
        out[n] = (v * 0xC2B2AE35) & 0xFFFFFFFF
    return out


def axis_multiplier(a):
    """The odd multiplier ``M_a`` of axis ``a``: the top 32 bits of the golden-ratio Weyl sequence's term ``a + 1``, odd."""
    return ((_GOLDEN * (a + 1)) & _MASK64) >> 32 | 1


def integer_gradient_set(d, random_gradients):
    """The unit gradients the integer hash picks from: ``{+1, -1}`` (1-D); the 8 at 45 degrees (2-D, in the
    documented order: axes then diagonals); Perlin's 2002 16 cube-edge directions, normalised (3-D); the
    instance's random unit gradients from 4-D on."""
    if d == 1:
        return np.array([[1.0], [-1.0]])
    if d == 2:
        s = 1 / np.sqrt(2)
        return np.array([[1, 0], [-1, 0], [0, 1], [0, -1], [s, s], [-s, s], [s, -s], [-s, -s]], dtype=float)
    if d == 3:
        g = np.zeros((16, 3))
        for h in range(16):  # Perlin's grad(): u = x if h < 8 else y; v = y if h < 4, x if h in (12, 14), else z
            u = 0 if h < 8 else 1
            v = 1 if h < 4 else (0 if h in (12, 14) else 2)
            g[h, u] += -1.0 if h & 1 else 1.0
            g[h, v] += -1.0 if h & 2 else 1.0
        return g / np.sqrt(2)
    return random_gradients


class NaiveLattice:
    """Phillips' lattice noise ``a * noise(F x + phi)`` ([P] Eq. 2) by a direct sum over lattice points.

    Tables from the seed, in the order ``LatticeNoise`` documents: ``n``
    positive values on (0, 1] (``1 - U``), ``n`` negative on [-1, 0)
    (``U - 1``), ``n`` Gaussian gradients normalised to unit length, (integer
    hash only) one 63-bit draw per component whose top 32 bits are its key,
    then one permutation of ``0..n-1`` per output component ([P] 2.3.1).

    ``noise(y) = sum_i prod_a K(y_a - i_a) v(i)`` over the integer lattice
    points ``i`` near ``y = F x + phi``, with
    - table hash ([P] 2.1.1, 2.4.1): ``h = P[(... P[(P[j_0] + j_1) mod n] ...) + j_{d-1}) mod n]``,
      ``j_a = i_a mod period_a``; ``v = values[h]`` with the tables interleaved
      (even entries positive, odd negative: ``alternation="table"``) or the
      sign by the parity of ``i_0 + ... + i_{d-1}`` (``"lattice"``, [P] figure 1);
    - integer hash: ``h = mix32(key_c ^ (j_0 M_0) ^ ... ^ (j_{d-1} M_{d-1}))``,
      ``v = int32(h) / 2**31``;
    - gradient basis (Perlin 1985): ``v = g(h) . (y - i)`` with the table's
      unit gradient ``g[h]`` or, for the integer hash, ``G[(h L) >> 32]`` of
      :func:`integer_gradient_set`.
    The result is multiplied by ``a / bound`` by the caller (see
    ``test_naive``: the bound is checked on its own).
    """

    def __init__(self, dim_in, dim_out=1, *, rng=0, kernel=None, basis="value", table_size=256, period=None,
                 frequency=1.0, phase=0.0, amplitude=1.0, alternation="table", hash="table"):
        d, n = dim_in, table_size
        if kernel is None:  # Phillips' cubic B-spline for values, Perlin's quintic fade for gradients
            kernel = "cubic" if basis == "value" else "quintic"
        self.d, self.c, self.n = d, dim_out, n
        self.kernel, self.basis, self.alternation, self.hash = kernel, basis, alternation, hash
        self.frequency = np.broadcast_to(np.asarray(frequency, dtype=float), (d,))
        self.phase = np.broadcast_to(np.asarray(phase, dtype=float), (d,))
        self.amplitude = float(amplitude)
        default = n if hash == "table" else 1 << 32
        self.period = np.broadcast_to(np.asarray(default if period is None else period, dtype=np.int64), (d,))
        self.tileable = period is not None
        rng = np.random.default_rng(rng)
        self.positive = 1.0 - rng.random(n)
        self.negative = rng.random(n) - 1.0
        g = rng.standard_normal((n, d))
        self.gradients = g / np.linalg.norm(g, axis=1, keepdims=True)
        if hash == "integer":
            self.keys = [int(k) >> 31 for k in rng.integers(0, 1 << 63, size=dim_out, dtype=np.int64)]
        self.perms = [rng.permutation(n) for _ in range(dim_out)]
        self.int_gradients = integer_gradient_set(d, self.gradients)

    def _lattice_value(self, c, i, r):
        """The basis at lattice points ``i`` (``(N, d)`` ints) for component ``c``; ``r = y - i`` for gradients."""
        j = i % self.period
        if self.hash == "table":
            P = self.perms[c]
            h = np.zeros(len(i), dtype=np.int64)
            for a in range(self.d):
                h = P[(h + j[:, a]) % self.n]
            if self.basis == "gradient":
                return np.sum(self.gradients[h] * r, axis=1)
            if self.alternation == "table":
                return np.where(h % 2 == 0, self.positive[h], self.negative[h])
            return np.where(i.sum(axis=1) % 2 == 0, self.positive[h], self.negative[h])
        word = np.full(len(i), self.keys[c], dtype=np.uint64)
        for a in range(self.d):
            word ^= (j[:, a].astype(np.uint64) * np.uint64(axis_multiplier(a))) & np.uint64(0xFFFFFFFF)
        h = mix32(word)
        if self.basis == "value":
            return h.view(np.int32) / 2.0 ** 31
        G = self.int_gradients
        pick = (h.astype(np.uint64) * np.uint64(len(G))) >> np.uint64(32)
        return np.sum(G[pick.astype(np.int64)] * r, axis=1)

    def raw(self, x, derivative=None):
        """``sum_i prod_a K(y_a - i_a) v(i)`` at points ``x`` (``(N, d)``), shape ``(N, dim_out)``.

        ``derivative=b``: its derivative along ``y_b`` instead (``K'`` on axis
        ``b``, plus ``prod K g_b`` in the gradient basis), in lattice units.
        """
        x = np.asarray(x, dtype=np.float64).reshape(-1, self.d)
        y = x * self.frequency + self.phase
        base = np.floor(y).astype(np.int64)
        K = KERNELS[self.kernel]
        out = np.zeros((len(x), self.c))
        # every kernel's support lies within |y - i| < 2: the points floor(y) - 1 .. floor(y) + 2 of each axis
        for offsets in np.ndindex(*(4,) * self.d):
            i = base + np.array(offsets) - 1
            r = y - i
            w = np.prod(K(r), axis=1)
            if derivative is not None:
                others = np.prod(np.delete(K(r), derivative, axis=1), axis=1)
                dw = DERIVATIVES[self.kernel](r[:, derivative]) * others
            for c in range(self.c):
                v = self._lattice_value(c, i, r)
                if derivative is None:
                    out[:, c] += w * v
                else:
                    out[:, c] += dw * v
                    if self.basis == "gradient":
                        grad = self._gradient_component(c, i, derivative)
                        out[:, c] += w * grad
        return out

    def _gradient_component(self, c, i, b):
        """Component ``b`` of the lattice gradient at ``i`` (``d/dy_b`` of ``g . (y - i)``)."""
        e = np.zeros((len(i), self.d))
        e[:, b] = 1.0
        return self._lattice_value(c, i, e)

    def __call__(self, x, bound):
        """``a * noise(F x + phi) / bound`` at points ``(N, d)``: ``(N, dim_out)``."""
        return self.amplitude * self.raw(x) / bound

    def jacobian(self, x, bound):
        """``d/dx_b`` of :meth:`__call__` (chain rule: ``a F_b / bound`` times the lattice derivative): ``(N, C, d)``."""
        return np.stack([self.amplitude * self.frequency[b] * self.raw(x, derivative=b) / bound
                         for b in range(self.d)], axis=-1)

    def octave(self, o, lacunarity):
        """Octave ``o``'s noise: this one, or for a tileable noise the same tables with the lattice period
        ``period * lacunarity**o``, so that octave ``o`` (at ``lacunarity**o x``) repeats once per tile."""
        if not self.tileable:
            return self
        twin = copy.copy(self)
        twin.period = self.period * int(lacunarity) ** o
        return twin

    def at_octave(self, o, lacunarity):
        """Octave ``o`` at ``lacunarity**o x`` (its own period when tileable): a callable on points."""
        noise = self.octave(o, lacunarity)
        return lambda x, bound: noise(np.asarray(x, dtype=np.float64) * lacunarity ** o, bound)


def grid_points(shape, extent):
    """The grid's sample points ``start + j * ((stop - start) / n)`` per axis (``noiselab.lattice.Grid``), ``(*shape, d)``."""
    coords = [lo + np.arange(n) * ((hi - lo) / n) for n, (lo, hi) in zip(shape, extent)]
    return np.stack(np.meshgrid(*coords, indexing="ij"), axis=-1)


def fractal_sum(noise, x, bound, octaves, lacunarity=2.0, gain=0.5, turbulence=False):
    """[P] Eq. 9 (fractal sum) or Eq. 10 (turbulence): ``sum_o gain**o (|.|) noise(lacunarity**o x)``."""
    total = 0.0
    for o in range(octaves):
        v = noise.at_octave(o, lacunarity)(x, bound)
        total = total + gain ** o * (np.abs(v) if turbulence else v)
    return total


def fractal_gradient(noise, x, bound, octaves, lacunarity=2.0, gain=0.5, turbulence=False):
    """Derivative of :func:`fractal_sum`: ``sum_o gain**o lacunarity**o (sign n_o) n_o'(lacunarity**o x)``, ``(N, C, d)``."""
    total = 0.0
    for o in range(octaves):
        xo = np.asarray(x, dtype=np.float64) * lacunarity ** o
        twin = noise.octave(o, lacunarity)
        j = twin.jacobian(xo, bound) * lacunarity ** o
        if turbulence:
            j = j * np.sign(twin(xo, bound))[:, :, None]
        total = total + gain ** o * j
    return total


def visible_octaves(octaves, spacing, frequency=1.0, lacunarity=2.0, gain=0.5, eps=2.0 ** -53):
    """How many octaves a grid can show (``noiselab.fractal``'s rule): stop at the first octave past the
    first whose lattice is finer than the sampling on every axis (``spacing * F * L**o > 1``), or whose
    remaining amplitude ``sum_{k >= o} g**k`` is at most ``eps`` (half float64's epsilon) times the part
    already summed."""
    total = sum(gain ** k for k in range(octaves))
    used, partial = 0, 0.0
    for o in range(octaves):
        if o > 0 and total - partial <= eps * partial:
            break
        if o > 0 and all(s * f * lacunarity ** o > 1 for s, f in zip(spacing, np.broadcast_to(frequency, len(spacing)))):
            break
        partial += gain ** o
        used += 1
    return used


# ============================================================================ sparse Gabor noise
#
# noiselab.gabor: Lagae, Lefebvre, Drettakis & Dutre, "Procedural noise using
# sparse Gabor convolution" (SIGGRAPH 2009): n(x) = sum_i w_i g(x - x_i) over a
# Poisson process of impulses, g(x) = K exp(-pi a^2 |x|^2) cos(2 pi F.x + phi),
# here with a per-axis envelope s_a, kernels that may move (centre x_i + v (t - t_i)),
# and each cell's impulses drawn from the integer hash of (cell, index, key).

_GOLD32 = 0x9E3779B9
_GOLD2_32 = 0x7F4A7C15
_COUNT_SALT = 0x5BD1E995


def _mix32_int(v):
    return int(mix32([v])[0])


def gabor_cell_impulses(key, cell_index, cell, density, rows):
    """The impulses of one cell: [(position (3,), weight, phase, table row)], from the hash words.

    Cell word ``h = mix32(key ^ j0 M0 ^ j1 M1 ^ j2 M2)``; count = Poisson(density)
    by inversion of ``u = (mix32(h ^ salt) + 0.5) / 2**32``; impulse ``k``'s word
    ``b = mix32(h ^ mix32((k + 1) * golden))`` and its draws ``mix32(b + j * golden2)``.
    """
    word = int(key)
    for a, j in enumerate(cell_index):
        word ^= ((int(j) & 0xFFFFFFFF) * axis_multiplier(a)) & 0xFFFFFFFF
    h = _mix32_int(word)
    u = (_mix32_int(h ^ _COUNT_SALT) + 0.5) / 2.0 ** 32
    n, p = 0, math.exp(-density)
    total = p
    while u > total and n < 4096:
        n += 1
        p = p * density / n
        total += p
    out = []
    for k in range(n):
        b = _mix32_int(h ^ _mix32_int(((k + 1) * _GOLD32) & 0xFFFFFFFF))
        d = [(_mix32_int((b + j * _GOLD2_32) & 0xFFFFFFFF) + 0.5) / 2.0 ** 32 for j in range(5)]
        row = (_mix32_int((b + 5 * _GOLD2_32) & 0xFFFFFFFF) * rows) >> 32
        pos = np.array([(cell_index[a] + d[a]) * cell[a] for a in range(3)])
        out.append((pos, 2.0 * d[3] - 1.0, 2.0 * math.pi * d[4], row))
    return out


def gabor_noise(points, *, key, freqs, bandwidth, velocity=None, density=4.0, truncation=0.01):
    """Sparse Gabor noise at ``points`` ``(n, dim)`` by a direct sum over the impulses of nearby cells.

    Cells are ``1 / s_a`` units along axis ``a`` and hold Poisson(``density``)
    impulses; a kernel is cut where its envelope falls to ``truncation``
    (``sum (s_a d_a)^2 < ln(1/truncation) / pi``); ``K`` gives variance 1:
    ``lambda E[w^2] K^2 / 2 * prod 1 / (sqrt(2) s_a) = 1`` with
    ``lambda = density * prod s_a`` and ``E[w^2] = 1/3``.
    """
    points = np.asarray(points, dtype=np.float64)
    n, dim = points.shape
    s = np.broadcast_to(np.asarray(bandwidth, dtype=np.float64), (dim,))
    freqs = np.asarray(freqs, dtype=np.float64)
    vel = np.zeros((len(freqs), 2)) if velocity is None else np.asarray(velocity, dtype=np.float64)
    s3 = np.ones(3)
    s3[3 - dim:] = s
    f3 = np.zeros((len(freqs), 3))
    f3[:, 3 - dim:] = freqs
    cell = 1.0 / s3
    rho2 = math.log(1.0 / truncation) / math.pi
    lam = density * np.prod(s)
    K = math.sqrt(6.0 / (lam * np.prod(1.0 / (math.sqrt(2.0) * s))))
    vmax = np.abs(vel).max(axis=0)
    reach = math.sqrt(rho2) / s3
    reach[1:] += vmax * (reach[0] if dim == 3 else 0.0)
    out = np.zeros(n)
    for i in range(n):
        q = np.zeros(3)
        q[3 - dim:] = points[i]
        lo = np.floor((q - reach) / cell).astype(int) - 1
        hi = np.floor((q + reach) / cell).astype(int) + 1
        if dim == 2:
            lo[0] = hi[0] = 0
        for j0 in range(lo[0], hi[0] + 1):
            for j1 in range(lo[1], hi[1] + 1):
                for j2 in range(lo[2], hi[2] + 1):
                    for pos, w, phi, m in gabor_cell_impulses(key, (j0, j1, j2), cell, density, len(freqs)):
                        d = q - pos
                        if dim == 2:
                            d[0] = 0.0
                        d[1:] -= vel[m] * d[0]
                        r2 = float(np.sum((s3 * d) ** 2)) if dim == 3 else float(np.sum((s3[1:] * d[1:]) ** 2))
                        if r2 < rho2:
                            out[i] += w * K * math.exp(-math.pi * r2) * math.cos(2 * math.pi * float(f3[m] @ d) + phi)
    return out
