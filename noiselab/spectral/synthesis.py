"""Spectral synthesis on the real-FFT half spectrum: envelope x random amplitude x random phase, then ``irfftn``.

Conjugacy. A real field's spectrum obeys ``S(-k) = conj(S(k))`` (thesis
Eq. 2.7). On the half spectrum of ``rfftn`` (last axis ``0 .. W//2``) the
constraint is implicit everywhere except on the *self-conjugate planes*: the
``kx = 0`` plane and, for even ``W``, the ``kx = W/2`` (Nyquist) plane. Inside
each plane a cell ``k`` and its mirror ``-k`` (indices modulo the sizes) are
both stored, and ``irfftn`` silently keeps only the Hermitian part of whatever
is there -- a spectrum built carelessly loses half the power on those planes
(MotionClouds' ``ifftn(...).real`` loses it everywhere). Here each mirror pair
gets one random value and its conjugate, and the purely real cells (every index
0 or n/2) get a real value of the same magnitude (random sign), so every cell
keeps exactly its prescribed power and ``rfftn(irfftn(S)) == S`` to float
precision.

Random amplitudes are normalised to ``E[a**2] = 1``, so the expected power of
every cell equals the envelope squared:

- ``"uniform"``: ``a`` uniform on ``[0, sqrt(3)]`` (the thesis's ``rand([0,1])``, rescaled),
- ``"rayleigh"``: complex Gaussian coefficients (a Gaussian random field),
- ``"fixed"``: ``a = 1``, random phase only (``|S|`` equals the envelope exactly).

Random numbers. :func:`synthesize` and :func:`spectral_noise` take one 64-bit
word from the caller's generator as the key of a counter-based SplitMix64
stream; coefficient ``i`` (the ``i``-th supported cell in C order) is word
``i`` of that stream, turned into an amplitude and a phase by vectorised
float32 polynomials (``log`` for the Rayleigh amplitude, ``sin`` and ``cos``;
errors below 1e-9 before float32 rounding), so drawing costs about what
writing the spectrum does, any chunking gives the same values, and float32
and float64 fields of one seed share them (they agree to float32 precision).
Same seed, same bits on one machine; the bits changed from the earlier
``rng.random`` + ``cos``/``sin`` draws. :func:`draw_coefficients` keeps that
earlier scheme (``noiselab.snowfall`` uses it for its few cells).
"""
from __future__ import annotations

import inspect

import numpy as np
import scipy.fft

from .._core import (as_array, as_generator, check_int, check_memory, check_real, check_shape, dispatch,
                     float_dtype, map_blocks, renamed_parameters, resolve_workers)
from . import _kernels
from .frequencies import frequency_vectors, half_spectrum_shape
from .plan import (AMPLITUDE_MODES, CHUNK, complex_dtype, hermitian_gain, noise_plan,
                   self_conjugate_columns, stream_key)

__all__ = ["synthesize", "spectral_noise", "NORMALIZATIONS", "draw_coefficients", "hermitian_plane", "AMPLITUDES"]

AMPLITUDES = ("uniform", "rayleigh", "fixed")


def check_distribution(amplitude_distribution):
    """The random amplitude law's name, checked (``amplitude_distribution=``: one of :data:`AMPLITUDES`)."""
    if not isinstance(amplitude_distribution, str) or amplitude_distribution not in AMPLITUDES:
        raise ValueError(f"amplitude_distribution must be one of {AMPLITUDES}, got {amplitude_distribution!r}")
    return amplitude_distribution


@renamed_parameters(amplitude="amplitude_distribution")
def draw_coefficients(n, rng=None, amplitude_distribution="uniform", dtype=np.float32) -> np.ndarray:
    """``n`` random complex coefficients ``a * exp(i*phi)`` with ``E[|.|**2] = 1`` (see the module notes).

    The draws happen in one fixed order (all amplitudes, then all phases), so
    the same generator state always gives the same values.

    Parameters
    ----------
    n : int
        How many coefficients, ``n >= 0``.
    rng : int, numpy.random.Generator or None
        The generator drawn from (advanced by the draws), a non-negative int
        (a fresh ``default_rng(rng)``: the same int, the same values) or
        ``None`` (fresh entropy, not repeatable; the default, as SPEC 7 has it).
    amplitude_distribution : {"uniform", "rayleigh", "fixed"}
        The law of the random amplitude ``a`` (``E[a**2] = 1``): uniform on
        ``[0, sqrt(3))``, Rayleigh (complex Gaussian coefficients) or 1.
    dtype : float32 or float64
        Precision of the parts: complex64 or complex128 out.

    Examples
    --------
    >>> import numpy as np
    >>> z = draw_coefficients(100000, np.random.default_rng(0), "rayleigh")
    >>> z.dtype, round(float(np.mean(np.abs(z) ** 2)), 2)
    (dtype('complex64'), 1.0)
    """
    n = check_int("n", n, lo=0)
    amplitude = check_distribution(amplitude_distribution)
    fdt = float_dtype(dtype)
    cdt = complex_dtype(fdt)
    rng = as_generator(rng)   # checked before the memory estimate: a bad rng is named first
    # peak: the float64 amplitudes and phases, one float64 temporary (cos or sin), and the output
    check_memory(n * (3 * 8 + cdt.itemsize), f"draw_coefficients(n={n})")
    if amplitude == "uniform":
        a = rng.random(n, dtype=np.float64) * np.sqrt(3.0)
    elif amplitude == "rayleigh":
        a = np.sqrt(-np.log1p(-rng.random(n, dtype=np.float64)))
    else:
        a = np.ones(n)
    phi = rng.random(n, dtype=np.float64) * (2 * np.pi)
    out = np.empty(n, dtype=cdt)
    out.real = a * np.cos(phi)
    out.imag = a * np.sin(phi)
    return out


def _mirror(a):
    """``a[-k]`` for every index ``k`` (indices modulo each axis length)."""
    for ax in range(a.ndim):
        a = np.roll(np.flip(a, ax), 1, ax)
    return a


def hermitian_plane(plane, support=None):
    """Make a self-conjugate plane Hermitian, ``P[-k] = conj(P[k])``, without losing or doubling power.

    Parameters
    ----------
    plane : complex ndarray
        Values on a self-conjugate plane (e.g. ``S[..., 0]``); any number of axes.
    support : bool ndarray, optional
        Where the envelope carries energy (default ``plane != 0``).

    Returns
    -------
    ndarray
        The Hermitian plane. Of each mirror pair the first in C order (the
        *canonical* cell) keeps its value and the other receives its conjugate;
        if only one of the two is in the support, its value is used for both
        (the support becomes symmetric, every supported cell keeps its
        magnitude). Self-conjugate cells become real with their magnitude kept:
        ``|v| * sign(Re v)``.

    Examples
    --------
    >>> import numpy as np
    >>> hermitian_plane(np.array([1 + 1j, 2 + 0j, 0j, 3j]))  # k=1 and k=3 are a mirror pair
    array([1.41421356+0.j, 2.        +0.j, 0.        +0.j, 2.        -0.j])
    """
    if plane is None or isinstance(plane, (str, bytes, dict, set, frozenset)):
        raise TypeError(f"plane must be a numeric (complex or real) array, got {type(plane).__name__}")
    plane = as_array("plane", plane)
    if plane.dtype.kind not in "biufc":
        raise TypeError(f"plane must be a numeric (complex or real) array, got dtype {plane.dtype}")
    if plane.dtype.kind in "biu":
        plane = plane.astype(np.float64)
    if not np.all(np.isfinite(plane)):
        raise ValueError("plane must be finite; it holds NaN or inf values (a spectrum with infinite power?)")
    if support is None:
        support = plane != 0
    else:
        support = as_array("support", support)
        if support.dtype.kind != "b":
            raise TypeError(f"support must be a bool array (True where the envelope carries energy), got dtype "
                            f"{support.dtype}")
        if support.shape != plane.shape:
            raise ValueError(f"support must have the plane's shape {plane.shape}, got {support.shape}")
    if plane.ndim == 0:
        v = plane[()]
        return _real_magnitudes(np.asarray(abs(v) * (1.0 if v.real >= 0 else -1.0)), plane.dtype)
    lin = np.arange(plane.size).reshape(plane.shape)
    lin_m = _mirror(lin)
    canonical = lin < lin_m
    selfconj = lin == lin_m
    mir = _mirror(plane)
    sup_m = _mirror(support)
    # canonical cells: own value, or the mirror's conjugate when only the mirror is supported
    take_mirror = canonical & ~support & sup_m
    out = np.where(take_mirror, np.conj(mir), plane)
    out = np.where(canonical | selfconj, out, np.conj(_mirror(out)))
    sc = out[selfconj]
    out[selfconj] = _real_magnitudes(np.abs(sc.astype(np.complex128)) * np.where(sc.real >= 0, 1.0, -1.0), out.dtype)
    return out


def _real_magnitudes(v, dtype):
    """``v`` (float64 signed magnitudes of self-conjugate cells) in ``dtype``; a ValueError if one is past its range."""
    fmax = float(np.finfo(dtype).max)
    if np.any(np.abs(v) > fmax):
        raise ValueError(f"plane holds a value whose magnitude {float(np.max(np.abs(v))):.3g} is past the largest "
                         f"{dtype} ({fmax:.3g}); scale it down or use complex128")
    return np.asarray(v).astype(dtype)


def _draws(key, start, n, mode, dtype=np.float32):
    """Coefficients ``start .. start+n-1`` of the stream ``key`` as ``(a**2, cos th, sin th)`` arrays.

    Word ``i`` of a counter-based SplitMix64 stream keyed by one 64-bit word
    of the caller's generator gives coefficient ``i``: ``u = (h + 1/2) / 2**32``
    (``h`` the high 32 bits, ``u`` rounded to float32, in ``(0, 1]``) and the
    phase ``th = 2*pi * l / 2**32`` (``l`` the low 32 bits). The amplitude
    ``a`` is ``sqrt(3) * u`` ("uniform"), ``sqrt(-log u)`` ("rayleigh": with
    the phase a complex Gaussian, Box-Muller) or 1 ("fixed"); ``E[a**2] = 1``.
    Computed in float32 arithmetic (``_kernels._amplitude2``, ``_phase``) and
    stored in float32 (the float64 path casts the same values), so one seed
    gives the same coefficients in both precisions and in any chunking.
    """
    a2 = np.empty(n, dtype=np.float32)
    c = np.empty(n, dtype=np.float32)
    s = np.empty(n, dtype=np.float32)
    _kernels.coefficient_parts(key, start, mode, a2, c, s)
    if dtype != np.float32:
        return a2.astype(dtype), c.astype(dtype), s.astype(dtype)
    return a2, c, s


def _row_groups(counts, chunk=CHUNK):
    """Split rows into consecutive groups of about ``chunk`` coefficients (a group starts where a multiple of ``chunk`` is passed).

    Returns ``(r0, r1, n)`` per group: rows ``r0..r1-1`` holding ``n``
    coefficients (possibly 0: such rows are still written, as zeros). Every row is in one group.
    """
    cum = np.cumsum(counts)
    before = cum - counts  # coefficients before each row
    ids = before // max(1, int(chunk))
    bounds = np.concatenate([[0], np.flatnonzero(np.diff(ids)) + 1, [counts.size]]).astype(np.int64)
    n = np.add.reduceat(counts, bounds[:-1]) if counts.size else np.zeros(0, np.int64)
    return [(int(a), int(b), int(m)) for a, b, m in zip(bounds[:-1], bounds[1:], n)]


@renamed_parameters(seed="rng", amplitude="amplitude_distribution")
def synthesize(shape, envelope, *, rng=None, amplitude_distribution="uniform", dtype=np.float32, return_spectrum=False,
               workers=None, normalize=None):
    """Real random field with the given amplitude envelope: ``irfftn(envelope * a * exp(i*phi))``.

    Parameters
    ----------
    shape : tuple of int
        Shape of the real output, 1 to 3 axes (or more), e.g. ``(T, H, W)``.
    envelope : callable or ndarray
        ``envelope(*w)`` receives the broadcast frequency vectors of
        :func:`frequency_vectors` (rad/sample, one per axis) and returns the
        amplitude, broadcastable to the half spectrum ``(..., W//2 + 1)``; or
        that amplitude array itself. Must be finite and non-negative.
    rng : int, numpy.random.Generator or None
        Random phases and amplitudes, drawn only on the envelope's support,
        one 64-bit word of the generator per supported cell, in C order.
    amplitude_distribution : {"uniform", "rayleigh", "fixed"}
        Distribution of the random amplitude (``E[a**2] = 1``).
    dtype : float32 or float64
        Output dtype (the spectrum is complex64 or complex128). The random
        coefficients are the same float32 draws for both, so the two fields of
        one seed agree to float32 precision.
    return_spectrum : bool
        Also return the half spectrum ``S`` with ``rfftn(field) == S``.
    workers : int, optional
        Threads, with scipy.fft's meaning (-1: every core), for the inverse
        FFT and the spectrum fill; the output is bit-identical for any count.
        Default (None): scipy's default (one thread unless set with
        ``scipy.fft.set_workers``).
    normalize : {None, "expected", "sample"}
        None (default): the field is ``irfftn(S)`` as drawn, its variance
        whatever the envelope makes. ``"expected"``: field (and spectrum)
        scaled so that the *ensemble* mean square is 1 (``sum`` of the
        envelope squared over the full spectrum, Parseval; no random number
        involved), as :func:`spectral_noise`'s default. ``"sample"``: this
        field's mean square is exactly 1. Either is the variance when the
        envelope is 0 at DC; the mean is scaled with the rest, never removed.

    Returns
    -------
    field : ndarray
        ``irfftn(S, shape)``, zero mean when the envelope is 0 at DC.
    spectrum : ndarray, only with ``return_spectrum``.

    Notes
    -----
    One pass counts and checks the envelope row by row, one pass per chunk of
    rows draws the coefficients and writes them into the spectrum (zeros
    elsewhere), in C order, without an index array; the self-conjugate planes
    are then made Hermitian and ``irfftn`` runs (not in place: measured slower).
    An envelope so large or so small that the spectrum or the FFT's sums would
    leave the dtype's range is divided by its maximum before the FFT and the
    field multiplied by it after; a field whose values themselves do not fit
    the dtype is a ``ValueError``.
    Timings against a bare ``irfftn``: ``benchmarks/bench_spectral.md``.

    Raises
    ------
    ValueError
        For an impossible shape, or an envelope that is not finite or does not
        broadcast to the half spectrum.

    Examples
    --------
    >>> import numpy as np, scipy.fft
    >>> from noiselab.spectral import envelopes as E
    >>> env = lambda wy, wx: E.annulus(wy, wx, band_cycles_per_sample=(0.05, 0.3))
    >>> f, S = synthesize((32, 32), env, rng=1, dtype=np.float64, return_spectrum=True)
    >>> bool(np.allclose(scipy.fft.rfftn(f), S))
    True
    """
    shape = check_shape("shape", shape)
    dt = float_dtype(dtype)
    cdt = complex_dtype(dt)
    amplitude = check_distribution(amplitude_distribution)
    if normalize is not None and normalize not in NORMALIZATIONS:
        raise ValueError(f"normalize must be None or one of {NORMALIZATIONS}, got {normalize!r}")
    hshape = half_spectrum_shape(shape)
    n_out = int(np.prod(shape))
    n_half = int(np.prod(hshape))
    check_memory(n_out * dt.itemsize + n_half * cdt.itemsize + 20 * CHUNK, f"synthesize{shape}")
    env = _envelope_array(envelope, shape, hshape)
    K = hshape[-1]
    R = n_half // K
    env2 = env.reshape(R, K)
    counts = np.zeros(R, dtype=np.int64)
    top = np.zeros(1)
    if _kernels.count_envelope_rows(env2, counts, top) != 0:
        if not np.all(np.isfinite(env)):
            raise ValueError("envelope must be finite everywhere (an infinite amplitude at DC? multiply by an annulus)")
        raise ValueError("envelope must be non-negative (it is an amplitude)")
    nw = resolve_workers(workers)
    # keep the spectrum and the FFT's partial sums (at most n_half cells of |S| <= 5 env) inside the dtype's range
    fi = np.finfo(dt)
    emax = float(top[0])
    rescale = emax > 0 and not (float(fi.tiny) / float(fi.eps) <= emax <= float(fi.max) / (8.0 * n_half))
    if rescale:
        env2 = env2 / emax
    rng = as_generator(rng)
    mode = AMPLITUDE_MODES[amplitude]
    spec = np.empty(hshape, dtype=cdt)
    spec2 = spec.reshape(R, K)
    key = stream_key(rng)
    groups = _row_groups(counts)
    starts = np.concatenate([[0], np.cumsum([g[2] for g in groups])[:-1]]).astype(np.int64)

    def fill(i):
        r0, r1, n = groups[i]
        u, c, s = _draws(key, int(starts[i]), n, mode)
        _kernels.fill_envelope(spec2, env2, counts, r0, r1, u, c, s)

    map_blocks(fill, range(len(groups)), nw if int(counts.sum()) >= _MIN_PARALLEL else 1)
    for j in self_conjugate_columns(shape[-1]):
        spec[..., j] = hermitian_plane(spec[..., j], env[..., j] > 0)
    field = scipy.fft.irfftn(spec, s=shape, workers=workers)  # (overwrite_x=True measured slower: in-place strided passes)
    if rescale:
        with np.errstate(over="ignore", invalid="ignore"):
            big = float(np.max(np.abs(field), initial=0.0)) * emax
            if not big <= float(fi.max):
                raise ValueError(f"envelope is too large for {dt}: its maximum {emax:.3g} gives field values "
                                 f"of {big:.3g}, past the dtype's largest {float(fi.max):.3g}; scale it down "
                                 f"or use float64")
            field = (field.astype(np.float64) * emax).astype(dt)
            if return_spectrum:
                spec = (spec.astype(np.complex128) * emax).astype(cdt)
                if not np.all(np.isfinite(spec.view(dt))):
                    raise ValueError(f"envelope is too large for the {cdt} spectrum: its maximum {emax:.3g}; "
                                     f"scale it down or use float64")
    if normalize is not None:
        g = _normal_gain(field, env, shape, emax, normalize)
        field = (field.astype(np.float64) * g).astype(dt)
        if return_spectrum:
            spec = (spec.astype(np.complex128) * g).astype(cdt)
    if field.dtype != dt:
        field = field.astype(dt)
    return (field, spec) if return_spectrum else field


def _normal_gain(field, env, shape, emax, normalize):
    """The factor that gives ``synthesize``'s field a mean square of 1: expected (from the envelope) or of this sample."""
    if normalize == "sample":
        ms = float(np.mean(np.square(field, dtype=np.float64)))
    else:
        # E|S_k|**2 = env_k**2 (E[a**2] = 1); the half spectrum holds every cell twice but the self-conjugate columns
        e = env / emax if emax > 0 else env
        full = 2.0 * float(np.sum(np.square(e)))
        for j in self_conjugate_columns(shape[-1]):
            full -= float(np.sum(np.square(e[..., j])))
        ms = full * (emax / float(np.prod(shape, dtype=np.float64))) ** 2 if emax > 0 else 0.0
    if not ms > 0:
        raise ValueError(f"normalize={normalize!r} needs a field with power: the envelope is 0 everywhere")
    return 1.0 / np.sqrt(ms)


def _envelope_array(envelope, shape, hshape):
    """``envelope`` (a callable of the frequency vectors, or an array) as a float64 array of the half-spectrum shape."""
    d = len(shape)
    if callable(envelope):
        try:
            inspect.signature(envelope).bind(*range(d))
        except TypeError as exc:
            raise TypeError(f"envelope must be a callable taking {d} frequency arrays (one per axis of shape "
                            f"{shape}), or an amplitude array; it does not accept {d} positional arguments: "
                            f"{exc}") from None
        except ValueError:  # no signature to inspect (some builtins): just call it
            pass
        try:
            env = envelope(*frequency_vectors(shape))
        except (ValueError, TypeError) as exc:
            raise type(exc)(f"envelope must be a callable of the {d} frequency arrays (rad/sample) returning the "
                            f"amplitude there; calling it raised: {exc}") from exc
        what = "envelope(*w) must return"
    else:
        env, what = envelope, "envelope must be a callable or"
    if env is None or isinstance(env, (str, bytes, dict, set, frozenset)):
        raise TypeError(f"{what} a real amplitude array broadcastable to the half spectrum {hshape}, got "
                        f"{type(env).__name__}")
    env = as_array("envelope", env)
    if env.dtype.kind not in "biuf":
        raise TypeError(f"{what} a real amplitude array broadcastable to the half spectrum {hshape}, got dtype "
                        f"{env.dtype}" + (" (pass its magnitude)" if env.dtype.kind == "c" else ""))
    try:
        return np.broadcast_to(env.astype(np.float64, copy=False), hshape)
    except ValueError:
        raise ValueError(f"{what} a real amplitude array broadcastable to the half spectrum {hshape} "
                         f"(shape {shape}), got shape {env.shape}") from None


# fewer cells than this are filled on the calling thread (measured: threads cost more)
_MIN_PARALLEL = 1 << 16
# bytes of samples the last pass (kx to x) makes per call: 1/32 of the field, within 64 KiB .. 1 MiB (a field of
# 1 MiB or less: the whole field). The peak
# is the field's storage (1 + 2/n times the field) plus this scratch; fewer, bigger calls cost a little less
# (1024 x 1024 float32, 1 worker, CPU: 2.33 ms in one call, 2.48 in 16, 2.51 in 32, 2.70 in 64;
# `python3 benchmarks/bench_spectral_floor.py --last-pass`, benchmarks/bench_spectral.md 2026-11-27)
LAST_PASS_BYTES = (1 << 16, 1 << 20)


def _storage(shape, dt):
    """The field's storage: a flat float array of ``prod(shape[:-1])`` rows of ``2*(n//2 + 1)`` floats.

    Each row holds the row's half spectrum (``n//2 + 1`` complex cells) until
    the last pass, which writes the row's ``n`` samples to the front of the
    storage (``n`` floats per row, one after the other), where ``irfftn``
    would have made a second array. Returns ``(buf, rows)``: ``rows`` is the
    ``(prod(shape[:-1]), n//2 + 1)`` complex view of ``buf``.
    """
    nrows = int(np.prod(shape[:-1], dtype=np.int64))
    h = shape[-1] // 2 + 1
    buf = np.empty(nrows * 2 * h, dtype=dt)
    return buf, buf.view(complex_dtype(dt)).reshape(nrows, h)


def _kept_rows(p):
    """The storage rows (indices into ``_storage``'s rows) of the block's rows, in the block's C order."""
    shape, index = p.shape, p.index
    if len(shape) == 1:
        return np.zeros(1, dtype=np.int64)
    if len(shape) == 2:
        return index[0].astype(np.int64)
    return (index[0][:, None] * shape[1] + index[1][None, :]).astype(np.int64).reshape(-1)


def _layout(p, nrows, nw):
    """What the in-place synthesis derives from the plan's geometry alone, kept in the plan's ``memo``.

    ``kept`` (storage rows of the block's rows), its runs, the rows the band
    cannot reach (a mask, or None), each fill row's offset in the storage,
    the runs of the second axis's kept indices (3-D), and the fill's row
    groups for ``nw`` threads with their first coefficients.
    """
    got = p.memo.get(("in place", nw))
    if got is not None:
        return got
    kept = _kept_rows(p)
    others = None
    if kept.size < nrows:
        others = np.ones(nrows, dtype=bool)
        others[kept] = False
    L = 2 * (p.n // 2 + 1)
    # where each fill row starts in the storage: a storage row, or (3-D, every frequency) a whole (ky, kx) plane
    rowoff = (kept if p.R == kept.size else kept[::p.Kr // p.K]) * L
    total = int(p.counts.sum())
    nw = nw if total >= _MIN_PARALLEL else 1
    # about four groups per thread, few calls; the grouping changes no bit (each row's cells depend on the row alone)
    groups = _row_groups(p.counts, max(CHUNK, -(-total // (4 * nw))))
    starts = [int(x) for x in np.concatenate([[0], np.cumsum([g[2] for g in groups])[:-1]])]
    got = dict(kept=kept, kept_runs=_runs(kept), others=others, rowoff=rowoff, nw=nw, groups=groups,
               starts=starts, lead_runs=_runs(p.index[1]) if len(p.shape) == 3 else None)
    p.memo[("in place", nw)] = got
    return got


def _fill_in_place(p, buf, rows, nw):
    """Fill the plan's block, scaled, into the storage rows it stands for; zero the rest the transforms read.

    The same coefficients, the same row powers, the same Hermitian planes
    and the same gain ``g`` (the field's unit variance) as
    :func:`noiselab.spectral.plan.fill_slab` and
    :func:`~noiselab.spectral.plan.hermitian_gain` give the chunked path,
    and the same scaling (the cells times ``g``): only where each row is
    written differs. The other rows' first ``K`` cells and every row's cells
    from ``K`` are set to 0. Returns ``g``.
    """
    K = p.K
    lay = _layout(p, rows.shape[0], nw)
    kept, groups, starts = lay["kept"], lay["groups"], lay["starts"]
    if K < rows.shape[1]:  # kx past the band: 0 for the last pass (which then needs no padded copy of its rows)
        rows[:, K:] = 0
    if lay["others"] is not None:  # rows the band cannot reach: read by the leading passes, so zero
        rows[lay["others"], :K] = 0
    rowpow = np.zeros(p.R)

    def fill(i):
        r0, r1, _ = groups[i]
        scratch = np.empty(p.Kr, dtype=p.dt)
        _kernels.fill_power_law(buf, p.Kr, p.q0, p.q1, p.wxsq, p.kbeg, p.kend, r0, r1, p.key, starts[i],
                                p.mode, p.exponent, p.qfloor, p.inv_qref, p.weight, p.sample, rowpow, scratch,
                                lay["rowoff"])

    map_blocks(fill, range(len(groups)), lay["nw"])
    cols = [j for j in self_conjugate_columns(p.n) if j < K]
    planes = [rows[kept, j] for j in cols]  # gathered (the kept rows), made Hermitian, put back
    g = hermitian_gain(p, rowpow, planes)
    for j, plane in zip(cols, planes):
        rows[kept, j] = plane
    planes = plane = None  # freed before the scaling's buffers (a strided view is scaled through numpy's)
    for sl in lay["kept_runs"]:  # scaled as the chunked path scales its slabs (the same cells times the same g)
        rows[sl, :K] *= g
    return g


def _runs(ix):
    """Consecutive runs of the increasing indices ``ix`` as slices."""
    cut = np.flatnonzero(np.diff(ix) != 1) + 1
    return [slice(int(a[0]), int(a[-1]) + 1) for a in np.split(ix, cut)]


def _ifft_in_place(view, axis, workers):
    """Inverse FFT of the complex ``view`` along ``axis``, written into ``view``."""
    out = scipy.fft.ifft(view, axis=axis, overwrite_x=True, workers=workers)
    if not np.may_share_memory(out, view):  # scipy's in-place transform of a complex input, kept if it copies
        view[...] = out


def _inverse_in_place(buf, rows, p, workers=None, lead_runs=None):
    """The field from the spectrum in its storage (see :func:`_storage`): its ``irfftn``, in ``buf``.

    The leading axes are transformed in place, on the first ``K`` cells of
    every row (beyond them the spectrum is 0); along the first axis only
    the rows of the second axis the band reaches (3-D). The last pass turns
    blocks of rows into samples (``irfft``) and writes them to the front of
    the storage: row ``i``'s samples go to floats ``i*n .. (i+1)*n - 1``,
    which hold no row after the block's last, so nothing is overwritten
    before it is read. One axis per pass, as the chunked path transforms
    (the same one-axis transforms of the same values: the same bits).
    Returns the field, a C-contiguous view of ``buf``.
    """
    shape, K, n = p.shape, p.K, p.n
    cv = rows.reshape(tuple(shape[:-1]) + (rows.shape[1],))
    if len(shape) == 3:
        for sl in lead_runs if lead_runs is not None else _runs(p.index[1]):
            _ifft_in_place(cv[:, sl, :K], 0, workers)
        _ifft_in_place(cv[:, :, :K], 1, workers)
    elif len(shape) == 2:
        _ifft_in_place(cv[:, :K], 0, workers)
    nrows = rows.shape[0]
    field = buf[:nrows * n].reshape(nrows, n)
    rowbytes = n * p.dt.itemsize
    lo, hi = LAST_PASS_BYTES
    # a field of 1 MiB or less in one call (its scratch is small in bytes, and calls cost more than at scale)
    step = nrows if nrows * rowbytes <= hi else max(1, min(hi, max(lo, nrows * rowbytes // 32)) // rowbytes)
    for r0 in range(0, nrows, step):
        r1 = min(nrows, r0 + step)
        x = scipy.fft.irfft(rows[r0:r1], n=n, axis=-1, workers=workers)
        field[r0:r1] = x
        del x  # before the next block's scratch is made
    return field.reshape(shape)


def _spectral_field(shape, exponent, band, rng, amplitude, dt, *, normalize, dc, workers, nw):
    """:func:`spectral_noise`'s field, synthesised in its own storage (no second array of its size).

    The spectrum is filled and scaled into the rows of the output's storage
    (:func:`_fill_in_place`), then transformed there (:func:`_inverse_in_place`).
    """
    p = noise_plan(shape, exponent, band, rng, amplitude, dt, normalize=normalize, dc=dc)
    buf, rows = _storage(p.shape, p.dt)
    _fill_in_place(p, buf, rows, nw)
    return _inverse_in_place(buf, rows, p, workers=workers, lead_runs=_layout(p, rows.shape[0], nw)["lead_runs"])


NORMALIZATIONS = ("expected", "sample")


@renamed_parameters(seed="rng", amplitude="amplitude_distribution")
def spectral_noise(shape, *, exponent=1.0, band=None, rng=None, amplitude_distribution="rayleigh", dtype=np.float32,
                   normalize="expected", dc=False, workers=None, chunks=None, spill=None):
    """Isotropic band-limited ``1/f**exponent`` noise in 1, 2 or 3 dimensions, zero mean and unit variance.

    Parameters
    ----------
    shape : int or tuple of int
        ``(n,)``, ``(H, W)`` or ``(D, H, W)``; isotropic in samples (pixels).
        At least one axis of 2 samples or more.
    exponent : float
        The *amplitude* exponent: amplitude falls as ``f**-exponent``, power
        as ``f**(-2 exponent)``, ``-8 <= exponent <= 8`` (1: a 1/f image, a
        random walk's ``1/f**2`` power in 1-D; 2: power ``1/f**4``). In 2-D,
        ``exponent=1`` gives equal energy per octave. Any accepted exponent is
        right in float32 too: the law is evaluated relative to its value at
        the band's loudest end, so no power overflows or underflows to 0.
    band : (lo, hi), optional
        Pass band in cycles per frame along the last axis (cycles per
        ``shape[-1]`` samples), inclusive; ``hi`` at most the Nyquist frequency
        ``shape[-1]/2``. Default: every frequency (DC only with ``dc=True``).
        A band holding no frequency of the grid is a ``ValueError``.
    rng : int, numpy.random.Generator or None
        The random state (SPEC 7): the same int, the same bits; a
        ``Generator`` is drawn from; ``None`` (default) is fresh entropy.
    amplitude_distribution : {"rayleigh", "uniform", "fixed"}
        The law of the random amplitudes. Default: complex Gaussian coefficients, i.e. a Gaussian field.
    dtype : float32 or float64
    normalize : {"expected", "sample"}
        ``"expected"`` (default): the spectrum is scaled by the analytic
        variance, so the *ensemble* has unit variance and exactly the
        requested power at every frequency (the mean power spectrum over seeds
        follows the law; one field's variance scatters around 1, the more the
        steeper the law). ``"sample"``: each field is rescaled to exactly
        zero mean and unit sample variance (the earlier default); one field's
        slope is unchanged, but averaged over seeds the power is no longer the
        law (1.50x too high at high frequency for 1-D ``k**-2``:
        dividing by the sample variance biases the ensemble).
    dc : bool
        Keep the DC term (the band must start at 0): the field gets a random
        mean, e.g. the displacement of a random walk (``exponent=1`` in 1-D).
        The power law is infinite at ``f = 0`` for ``exponent > 0``, so it is
        taken flat below the grid's lowest nonzero frequency (``1/max(shape)``
        cycles/sample; the ``fmin`` convention of colorednoise): DC gets the
        amplitude of the lowest ring. For ``exponent <= 0`` the law is finite
        at 0 and used as is (0 for ``exponent < 0``, 1 for white noise). The
        variance is then taken about 0 (``"expected"``: the ensemble's
        ``E[x**2] = 1``) or about the field's mean (``"sample"``).
    workers : int, optional
        Threads, with scipy.fft's meaning (-1: every core). Used by every FFT
        pass and by the spectrum fill; the output is bit-identical for any
        count. Default (None): scipy's default, one thread unless set with
        ``scipy.fft.set_workers`` (the library does not take cores a caller
        did not give it; the command line uses every core).
    chunks : int, tuple or "auto", optional
        Return a lazy ``dask.array.Array`` in these chunks (dask's syntax, one
        entry per axis), computed by a pencil-decomposed inverse FFT that never
        holds the whole field (:mod:`noiselab.scale.spectral`; needs
        ``noiselab[dask]``). The same bits as the in-memory field.
    spill : path, optional
        With ``chunks``: a directory (on storage every worker sees) for the
        two transposes as zarr arrays, so no worker ever holds more than its
        chunks (for fields bigger than the cluster's memory). The caller
        removes it after computing. Default: chosen by itself, by the rule
        :func:`noiselab.snowfall.snow` states (dask's in-memory rechunk when
        it fits the workers short of their pause threshold, else a temporary
        folder of its own, removed with the lazy array's graph).

    Returns
    -------
    ndarray of ``dtype``, shape ``shape``
        The field (a lazy ``dask.array.Array`` with ``chunks``): zero mean and
        unit variance over the ensemble (``"expected"``) or exactly
        (``"sample"``).

    Raises
    ------
    ValueError
        For an impossible shape, an exponent outside ``[-8, 8]``, a band past
        the Nyquist frequency or holding no frequency of the grid, ``dc=True``
        with a band that does not start at 0, an unknown ``amplitude_distribution`` or
        ``normalize``.
    MemoryError
        When the field would not fit (estimated before allocating).

    Notes
    -----
    The same field as ``synthesize(shape, annulus * power_law, ...)`` rescaled,
    built without the float64 envelope: the band and the power law are
    evaluated cell by cell while the coefficients are written, each row's band
    is one kx interval, and only the rows and columns the band can reach are
    transformed along the leading axes (a pruned inverse FFT, as in
    :mod:`noiselab.snowfall`). The synthesis runs in the output's own storage:
    the half spectrum is written into its rows (``n//2 + 1`` complex cells
    hold a row's ``n`` samples), transformed there, and the last pass writes
    each block of rows' samples back to the front, so the peak memory is the
    field and a small scratch (at most 1.1x the output for 2-D and 3-D
    fields from 4 MiB up; ``irfftn`` of a ready spectrum holds 2x). Mean and
    variance are set on the spectrum (DC is 0 unless ``dc``; Parseval gives
    the variance), so the field needs no pass after the FFT. The passes are
    those of the chunked path (one axis at a time): the two give the same
    bits. Timings (ratio to a bare ``irfftn`` of the
    output at equal workers, and peak memory): ``benchmarks/bench_spectral.md``.

    Examples
    --------
    >>> import numpy as np
    >>> x = spectral_noise((64, 64), exponent=1.0, band=(2, 16), rng=0)
    >>> x.shape, x.dtype, abs(float(x.mean())) < 1e-6
    ((64, 64), dtype('float32'), True)
    >>> y = spectral_noise((64, 64), exponent=1.0, band=(2, 16), rng=0, normalize="sample")
    >>> round(float(y.std()), 3)
    1.0
    >>> walks = np.stack([spectral_noise((256,), exponent=1.0, dc=True, rng=s) for s in range(200)])
    >>> round(float(np.mean(walks ** 2)), 1)   # E[x**2] = 1 over the ensemble
    1.0
    """
    shape = check_shape("shape", shape, ndim={1, 2, 3})
    exponent = check_real("exponent", exponent, lo=-8, hi=8)
    amplitude = check_distribution(amplitude_distribution)
    if normalize not in NORMALIZATIONS:
        raise ValueError(f"normalize must be one of {NORMALIZATIONS}, got {normalize!r}")
    if not isinstance(dc, (bool, np.bool_)):
        raise TypeError(f"dc must be True or False, got {dc!r}")
    nw = resolve_workers(workers)
    dt = float_dtype(dtype)
    if spill is not None and chunks is None:
        raise ValueError("spill= is the chunked path's scratch directory: pass chunks= too")
    if chunks is not None:  # lazy, on dask: the implementation noiselab.scale.spectral registers
        return dispatch.chunked("spectral_noise")(shape, chunks, exponent=exponent, band=band, rng=rng,
                                                  amplitude=amplitude, dtype=dt, normalize=normalize, dc=bool(dc),
                                                  spill=spill)
    return _spectral_field(shape, exponent, band, rng, amplitude, dt, normalize=normalize, dc=bool(dc),
                           workers=workers, nw=nw)
