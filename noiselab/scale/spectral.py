"""Chunked spectral noise and snow: lazy ``dask.array`` arrays from a pencil-decomposed inverse FFT.

``spectral_noise(..., chunks=)`` and ``snow(..., chunks=)`` reach
:func:`chunked_spectral_noise` and :func:`chunked_snow` through
:mod:`noiselab._core.dispatch` (registered below); the in-memory core never
imports this module. What both paths compute the same way comes from their
internal interfaces: :mod:`noiselab.spectral.plan` (the plan, the slab fill,
the Hermitian gain, the leading-axis inverse FFT) and
:mod:`noiselab.snowfall.tent` (the tent's columns and coefficients, the y-pass).

The inverse FFT is global, and ``dask.array.fft`` transforms only an axis
that sits in one chunk, so it is done here the way distributed FFTs do it:
separable 1-D ``scipy.fft`` passes with a rechunk (an all-to-all transpose)
between them.

Spectral noise (``spectral_noise(..., chunks=)``, 2-D and 3-D):

1. the half spectrum's block (only the rows and kx columns the band can
   reach, as in memory) is filled in slabs of its first axis; every row takes
   its words of the counter-based stream at its own offset, so the values do
   not depend on the chunking;
2. transpose to slabs of kx; every leading axis in turn: the kept rows back at
   their indices, ``ifft`` along that axis;
3. transpose to the output's chunks along the leading axes with kx whole:
   ``irfft`` along the last axis.

The in-memory synthesis makes the same one-axis passes over the same scaled
cells (in the field's own storage), so the two give the same bits.

The normalisation (``power``) and the self-conjugate planes (kx = 0 and
Nyquist) need the whole spectrum: a first pass fills every slab and keeps only
its row powers and its plane columns; one small task makes the planes
Hermitian and computes the gain; the second pass fills the slabs again and
feeds the FFT. The spectrum is never held whole. 1-D noise is one task (a
single FFT axis cannot be split by separable passes).

Snow (``snow(..., chunks=)``), the pruned FFT of :mod:`noiselab.snowfall.tent`
kept:

1. the tent's sparse spectrum (about 1 % of the video's cells) is drawn
   on the client exactly as in memory; the columns are ordered by kx, so a
   slab of kx holds a contiguous run of columns;
2. per kx slab, a few frames at a time: the direct inverse DFT along t of
   each tent column (its few bins), the values at their ``(ky, kx)`` cells,
   ``ifft`` along y on the slab's kx columns only (the band's kx columns;
   nothing past the band's largest kx exists): :func:`noiselab.snowfall.tent.y_pass`,
   as in memory;
3. per ``(t, y)`` chunk, the x-pass task takes its piece of every kx slab
   (without ``spill=``, the transpose without a concatenation: no dask rechunk) and
   gathers its rows a cache-sized slab at a time into a zero-padded block,
   ``irfft`` along x straight into the chunk, the chunk's extremes taken on
   the way (:func:`noiselab.snowfall.tent.irfft_rows`, as in memory).

The rescale to [0, 1] and ``alpha ** beta`` need the raw field's global
minimum and maximum. When the raw field fits in a quarter of the memory
there is (the workers' memory limits on a ``distributed`` cluster, else this
machine's available memory; :func:`_hold_raw`), steps 2-3 run once: each raw
chunk's extremes are gathered as it is made, and the rescale is applied to
the waiting raw chunks once the global extremes are known (the raw field is
held meanwhile). Otherwise the first pass of steps 2-3 returns only each
chunk's extremes (a tree-free reduction over tiny arrays), and the second
pass, which starts only after it (its first tasks depend on the extremes),
recomputes steps 2-3 and rescales each chunk as it is made: no stage holds
more than its own chunk, at the price of the FFT twice
(``benchmarks/bench_dask.md``). Both give the in-memory video's bits.
``rescale=False`` is one pass.
"""
from __future__ import annotations

import os
import uuid

import numpy as np
import scipy.fft

from .._core import as_generator, available_memory, dispatch, float_dtype, require_dask
from ..snowfall.render import opacity_copy, rescale_opacity
from ..snowfall.tent import assemble, irfft_rows, tent_columns, y_pass
from ..spectral import plan, spectral_noise
from .run import _active_client

__all__ = ["chunked_spectral_noise", "chunked_snow"]

_TARGET = 16 << 20  # bytes of a stage's chunk when the caller's chunk does not fix it
# "auto" output chunks: this size, not dask's array.chunk-size (128 MiB). A worker holds about 3 output chunks
# at once (the x-pass's input, its output, zarr's copy): 128 MiB chunks took a 600 MiB worker past its nanny's 95 %
# (benchmarks/bench_dask.md, "within the workers' memory")
_AUTO = 32 << 20
# the transposed stages' chunks (spectrum slabs, snow's t/y slabs) are at most this, whatever the output chunk
_SLAB_MAX = 32 << 20


def _out_chunks(chunks, shape, dtype):
    import dask

    from .lattice import normalize_grid_chunks

    if isinstance(chunks, str) and chunks == "auto":
        # the last pass makes whole rows: an "auto" chunk cut along the last axis made a task hold rows of
        # several chunks (a (128, 256, 1024) x-pass for (128, 256, 256) chunks of a 512 MiB video)
        chunks = ("auto",) * (len(shape) - 1) + (-1,)
    with dask.config.set({"array.chunk-size": _AUTO}):
        return normalize_grid_chunks(chunks, shape, 1, dtype)


def _slab_bytes(out_chunks, dt, budget):
    """Bytes of a transposed stage's chunk: twice the caller's largest output chunk, 1 MiB to ``_SLAB_MAX``.

    At most a quarter of a worker's ``budget`` (:func:`_budget`), a task's
    arrays and their copies by the spill's writer short of the pause threshold.
    """
    cap = max(1 << 18, min(_SLAB_MAX, budget // 4))
    return min(cap, max(1 << 20, 2 * int(np.prod([max(c) for c in out_chunks])) * np.dtype(dt).itemsize))


def _blocks(n, size):
    size = int(max(1, min(n, size)))
    return tuple([size] * (n // size) + ([n % size] if n % size else []))


def _starts(blocks):
    return np.concatenate([[0], np.cumsum(blocks)]).astype(np.int64)


def _array(dsk, name, chunks, dtype, deps=()):
    import dask.array as da
    from dask.highlevelgraph import HighLevelGraph

    graph = HighLevelGraph.from_collections(name, dsk, dependencies=list(deps))
    return da.Array(graph, name, chunks, dtype=dtype)


def _graph(*arrays):
    out = {}
    for a in arrays:
        out.update(dict(a.__dask_graph__()))
    return out


# ------------------------------------------------------------------ the transpose on disk (spill=)


def _write_block(x, path, region):
    import zarr

    zarr.open_array(path, mode="r+")[tuple(slice(a, b) for a, b in region)] = x
    return int(x.nbytes)


def _written(sizes):
    return int(sum(sizes))


def _read_block(path, region, *after):
    import zarr

    return zarr.open_array(path, mode="r")[tuple(slice(a, b) for a, b in region)]


def _regions(chunks, idx):
    st = [_starts(c) for c in chunks]
    return [[int(st[a][i]), int(st[a][i + 1])] for a, i in enumerate(idx)]


def _spill_write(arr, new_chunks, spill, dsk):
    """Tasks writing ``arr`` into a zarr array under ``spill`` chunked on both chunkings' grid; returns (path, done key)."""
    import itertools

    import zarr

    zch = tuple(int(min(max(a), max(b))) for a, b in zip(arr.chunks, new_chunks))
    path = os.path.join(os.fspath(spill), f"{arr.name}.zarr")
    if isinstance(spill, _Scratch):
        path = spill.owned(path)  # every task holding the path keeps the folder until the graph is gone
    zarr.create_array(path, shape=arr.shape, chunks=zch, dtype=arr.dtype, compressors=None, fill_value=0,
                      overwrite=True)
    dsk.update(_graph(arr))
    w = f"spill-write-{arr.name}"
    keys = []
    for idx in itertools.product(*[range(len(c)) for c in arr.chunks]):
        dsk[(w,) + idx] = (_write_block, (arr.name,) + idx, path, _regions(arr.chunks, idx))
        keys.append((w,) + idx)
    done = f"spill-done-{arr.name}"
    dsk[done] = (_written, keys)
    return path, done


def _spill_read(path, done, chunks, dtype, name, dsk, after=()):
    """Tasks reading the spilled array in ``chunks`` once ``done`` (and ``after``) are computed."""
    import itertools

    for idx in itertools.product(*[range(len(c)) for c in chunks]):
        dsk[(name,) + idx] = (_read_block, path, _regions(chunks, idx), done) + tuple(after)
    return name


def _transpose(arr, new_chunks, spill, tok, tag):
    """``arr`` in ``new_chunks``: dask's rechunk (``spill=None``) or through a zarr array on disk."""
    if spill is None:
        return arr.rechunk(new_chunks)
    dsk = {}
    path, done = _spill_write(arr, new_chunks, spill, dsk)
    name = _spill_read(path, done, new_chunks, arr.dtype, f"spill-read-{tag}-{tok}", dsk)
    return _array(dsk, name, new_chunks, arr.dtype)


def _regular(chunks):
    """Regular chunks with the same largest block (a spilled transpose reads whole zarr chunks)."""
    return tuple(_blocks(sum(c), max(c)) for c in chunks)


# ------------------------------------------------------------------ spectral noise


def _sc_cols(p):
    return [j for j in plan.self_conjugate_columns(p.n) if j < p.K]


def _pass_a(p, i0, i1):
    slab, rowpow = plan.fill_slab(p, i0, i1)
    return rowpow, [slab[..., j].copy() for j in _sc_cols(p)]


def _gain(p, parts):
    """The Hermitian planes and the gain ``g``, from every slab's row powers and plane columns (as in memory)."""
    planes = [np.ascontiguousarray(np.concatenate([pl[k] for _, pl in parts], axis=0))
              for k, _ in enumerate(_sc_cols(p))]
    return plan.hermitian_gain(p, np.concatenate([r for r, _ in parts]), planes), planes


def _pass_b(p, i0, i1, gp):
    g, planes = gp
    slab, _ = plan.fill_slab(p, i0, i1)
    for k, j in enumerate(_sc_cols(p)):
        slab[..., j] = planes[k][i0:i1]
    slab *= g
    return slab


def _leading_passes(slab, index, shape):
    """``ifft`` along every leading axis of a kx slab, the kept rows put back at their indices first."""
    return plan.leading_ifft(slab, index, shape, workers=1, overwrite=False)


_CACHE = 1 << 18  # bytes of a pass's working block (the in-memory snow's 256 KiB)


def _last_pass(B, n, dt):
    """``irfft`` along the last axis into a new ``dt`` array, a slab of rows at a time (cache-sized, as in memory)."""
    out = np.empty(B.shape[:-1] + (n,), dtype=dt)
    Bf = B.reshape(-1, B.shape[-1])
    of = out.reshape(-1, n)
    rows = int(max(1, _CACHE // max(1, n * np.dtype(dt).itemsize)))
    for r0 in range(0, Bf.shape[0], rows):
        of[r0:r0 + rows] = scipy.fft.irfft(Bf[r0:r0 + rows], n=n, axis=1, workers=1)
    return out


def _xpass_chunk(path, region, cols, n, dt, sub, post, *after):
    """One output chunk from spilled complex rows: ``irfft`` of its rows ``sub`` rows at a time, its columns kept.

    ``region``: the chunk's ``[start, stop]`` along each leading axis;
    ``cols``: its ``[start, stop]`` along the last. A task holds the chunk
    and one block of ``sub`` rows, never the chunk's whole rows (the whole
    rows of a chunk cut along x are ``n / (stop - start)`` times the chunk);
    the x-pass of a row is recomputed for each chunk of its columns.
    ``post``: None, or ``(beta, (lo, hi))`` to rescale (snow).
    """
    import itertools

    import zarr

    z = zarr.open_array(path, mode="r")
    x0, x1 = cols
    out = np.empty(tuple(b - a for a, b in region) + (x1 - x0,), dtype=dt)
    for st in itertools.product(*[range(a, b, s) for (a, b), s in zip(region, sub)]):
        sl = tuple(slice(s0, min(s0 + s, b)) for s0, s, (_, b) in zip(st, sub, region))
        x = _last_pass(z[sl], n, dt)
        if x1 - x0 < n:
            x = np.ascontiguousarray(x[..., x0:x1])
        if post is not None:
            beta, (lo, hi) = post
            x = rescale_opacity(x, beta, lo=lo, hi=hi, workers=1)
        out[tuple(slice(q.start - a, q.stop - a) for q, (a, _) in zip(sl, region))] = x
    return out


def _post(beta, lohi):
    return beta, lohi


def _spilled_xpass(path, done, out_chunks, sub, n, dt, name, dsk, post=None):
    """Tasks making ``out_chunks`` straight from the spilled complex rows (:func:`_xpass_chunk`), no rechunk after."""
    import itertools

    st = [_starts(c) for c in out_chunks]
    for idx in itertools.product(*[range(len(c)) for c in out_chunks]):
        reg = [[int(st[a][i]), int(st[a][i + 1])] for a, i in enumerate(idx)]
        dsk[(name,) + idx] = (_xpass_chunk, path, reg[:-1], reg[-1], n, dt, sub, post, done)
    return _array(dsk, name, out_chunks, dt)


def _one_piece(shape, kw):
    return spectral_noise(shape, **kw)


@dispatch.register("spectral_noise")
def chunked_spectral_noise(shape, chunks, *, exponent, band, rng, amplitude, dtype, normalize, dc, spill=None):
    """:func:`noiselab.spectral.spectral_noise` as a lazy dask array in ``chunks`` (see the module notes).

    Called by ``spectral_noise`` when ``chunks`` is given, after it validated
    the arguments. The same bits as the in-memory field: the same cells, scaled
    by the same gain, through the same one-axis transforms.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.spectral import spectral_noise
    >>> lazy = spectral_noise((40, 36), band=(2, 12), rng=3, chunks=(16, 20))
    >>> lazy.chunks
    ((16, 16, 8), (20, 16))
    >>> ref = spectral_noise((40, 36), band=(2, 12), rng=3)
    >>> np.array_equal(lazy.compute(), ref)
    True
    """
    require_dask()
    import dask.array as da
    from dask import delayed

    shape = tuple(int(s) for s in shape)
    dt = float_dtype(dtype)
    out_chunks = _out_chunks(chunks, shape, dt)
    if len(shape) == 1:  # one FFT axis: one task
        kw = dict(exponent=exponent, band=band, rng=rng, amplitude_distribution=amplitude, dtype=dt,
                  normalize=normalize, dc=dc)
        x = da.from_delayed(delayed(_one_piece, pure=True)(shape, kw), shape, dtype=dt)
        return x.rechunk(out_chunks)
    p = plan.noise_plan(shape, exponent, band, rng, amplitude, dt, normalize=normalize, dc=dc, check=False)
    tok = uuid.uuid4().hex[:12]  # a fresh graph per call (the plan holds arrays; no reliable cheap token)
    b0 = p.bshape[0]
    rest = int(np.prod(p.bshape[1:]))
    item = p.cdt.itemsize
    budget, _ = _budget()
    slab_rows = _blocks(b0, max(1, min(_TARGET, max(1 << 18, budget // 4)) // max(1, rest * item)))
    st = _starts(slab_rows)
    pkey = f"spectral-plan-{tok}"
    a_name, g_name, b_name = f"spectral-a-{tok}", f"spectral-gain-{tok}", f"spectral-spectrum-{tok}"
    dsk = {pkey: p}
    for i in range(len(slab_rows)):
        dsk[(a_name, i)] = (_pass_a, pkey, int(st[i]), int(st[i + 1]))
    dsk[g_name] = (_gain, pkey, [(a_name, i) for i in range(len(slab_rows))])
    extra = (0,) * (len(p.bshape) - 1)
    for i in range(len(slab_rows)):
        dsk[(b_name, i) + extra] = (_pass_b, pkey, int(st[i]), int(st[i + 1]), g_name)
    bchunks = (slab_rows,) + tuple((m,) for m in p.bshape[1:])
    spec = _array(dsk, b_name, bchunks, p.cdt)
    # transpose 1: slabs of kx, leading axes whole
    full_lead = int(np.prod(shape[:-1]))
    ckx = max(1, _slab_bytes(out_chunks, dt, budget) // max(1, full_lead * item))
    kx_blocks = _blocks(p.K, ckx)
    budget, _ = _budget()
    # the x-pass over whole rows in tasks that fit a worker short of its pause threshold (a 128 x 256-row task of a
    # 1024-wide field, 262 MiB in and out, paused a 600 MiB worker for good)
    row_bytes = p.K * item + shape[-1] * dt.itemsize
    x_lead = _fit_rows(out_chunks[:-1], row_bytes, _xpass_cap(budget))
    lead = int(np.prod([max(c) for c in x_lead]))
    out_chunk = int(np.prod([max(c) for c in out_chunks])) * dt.itemsize
    _check_worker_memory([(f"a spectrum slab of {max(slab_rows) * rest} complex cells", max(slab_rows) * rest * item),
                         (f"a leading-axes slab of {full_lead} x {min(ckx, p.K)} complex cells, in and out",
                          2 * full_lead * min(ckx, p.K) * item),
                         (f"an x-pass chunk of {lead} rows, {p.K} complex cells in and {shape[-1]} out",
                          lead * row_bytes),
                         (f"an output chunk of {out_chunk >> 20} MiB, assembled and copied by the writer",
                          2 * out_chunk)], f"spectral_noise{shape} in chunks {chunks}")
    task = max(2 * full_lead * min(ckx, p.K) * item, lead * row_bytes, 2 * out_chunk)
    spill = _route(spill, task, (int(np.prod(p.bshape)) + full_lead * p.K) * item)
    spec = _transpose(spec, tuple((m,) for m in p.bshape[:-1]) + (kx_blocks,), spill, tok, "spectrum")
    s1 = spec.map_blocks(_leading_passes, p.index, shape, chunks=tuple((m,) for m in shape[:-1]) + (kx_blocks,),
                         dtype=p.cdt, name=f"spectral-lead-{tok}")
    # transpose 2: the output's chunks along the leading axes (or a part of them), kx whole
    if spill is not None:  # the x-pass reads the spilled rows a block at a time into the output's chunks
        dsk = {}
        path, done = _spill_write(s1, _regular(x_lead) + ((p.K,),), spill, dsk)
        return _spilled_xpass(path, done, out_chunks, tuple(max(c) for c in x_lead), shape[-1], dt,
                              f"spectral-x-{tok}", dsk)
    s1 = _transpose(s1, x_lead + ((p.K,),), spill, tok, "lead")
    out = s1.map_blocks(_last_pass, shape[-1], dt, chunks=x_lead + ((shape[-1],),), dtype=dt,
                        name=f"spectral-x-{tok}")
    return out.rechunk(out_chunks)


# ------------------------------------------------------------------ snow


def _snow_plan(cols, spec, K, ckx):
    """Per kx slab: its columns' ``(ky, local kx)`` cells and their sparse spectra, the columns in kx-major order."""
    order = np.lexsort((np.arange(cols.ky.size), cols.kx))  # kx-major, then the in-memory order
    kx_sorted = cols.kx[order]
    kx_blocks = _blocks(K, ckx)
    kst = _starts(kx_blocks)
    pieces = []
    for b in range(len(kx_blocks)):
        k0, k1 = int(kst[b]), int(kst[b + 1])
        a, z = np.searchsorted(kx_sorted, [k0, k1])
        pieces.append(dict(ky=cols.ky[order[a:z]].astype(np.int64), kx=(kx_sorted[a:z] - k0).astype(np.int64),
                           k=k1 - k0, spec=spec.take(order[a:z])))
    return kx_blocks, pieces


def _snow_slab(piece, T, H, cdt, *after):
    """t-pass on the slab's tent columns, the columns at their (ky, kx) cells, y-pass: ``(T, H, k)`` complex."""
    k = piece["k"]
    B = np.empty((T, H, k), dtype=cdt)
    spec = piece["spec"]
    prep = spec.prepare(piece["ky"], piece["kx"], k)
    tb = int(max(1, _CACHE // max(1, H * k * np.dtype(cdt).itemsize)))
    for t0 in range(0, T, tb):  # a few frames at a time, in cache, as in memory
        y_pass(spec, t0, piece["ky"], piece["kx"], B[t0:t0 + tb], prep)
    return B


def _snow_xpass(parts, k0s, W, dt, mode=None):
    """The x-pass of one ``(t, y)`` chunk straight from its pieces of the kx slabs: no concatenated rows.

    ``parts``: the chunk's ``(ct, cy, k)`` piece of each kx slab, the slabs
    starting at the columns ``k0s``. A slab of rows at a time (cache-sized,
    as in memory) is gathered into a zero-padded block of ``W//2 + 1``
    complex columns and transformed along x straight into the chunk
    (:func:`noiselab.snowfall.tent.irfft_rows`, what the in-memory renderer
    runs on the same values: the same bits), its extremes taken while it is
    in cache. ``mode``: None, the raw chunk; ``"both"``, ``(raw, extremes)``;
    ``"extremes"``, the extremes only (no chunk kept: the rows go through one
    slab of scratch); ``(beta, (lo, hi))``, the chunk rescaled.
    """
    ct, cy = parts[0].shape[:2]
    cdt = parts[0].dtype
    rows = int(max(1, min(cy, _CACHE // max(1, W * np.dtype(dt).itemsize))))
    P = np.zeros((rows, W // 2 + 1), dtype=cdt)  # columns past the slabs' last stay zero
    keep = mode != "extremes"
    out = np.empty((ct, cy, W), dtype=dt) if keep else np.empty((rows, W), dtype=dt)
    lo, hi = np.inf, -np.inf
    for t in range(ct):
        for y0 in range(0, cy, rows):
            r = min(rows, cy - y0)
            for k0, part in zip(k0s, parts):
                P[:r, k0:k0 + part.shape[2]] = part[t, y0:y0 + r]
            x = irfft_rows(P[:r], W, out[t, y0:y0 + r] if keep else out[:r])
            if mode is not None:
                lo, hi = min(lo, float(x.min())), max(hi, float(x.max()))
    if mode is None:
        return out
    ext = np.array([[[lo, hi]]], dtype=dt)
    if mode == "both":
        return out, ext
    if mode == "extremes":
        return ext
    beta, (glo, ghi) = mode
    return rescale_opacity(out, beta, lo=glo, hi=ghi, workers=1)


def _snow_spilled_chunk(path, region, cols, W, dt, sub, post, *after):
    """One output chunk of snow from its spilled complex rows (:func:`_xpass_chunk`'s plan, the snow's x-pass).

    The chunk's rows are read ``sub`` rows at a time; a cache-sized slab of
    them at a time is gathered into a zero-padded block and transformed along
    x (:func:`noiselab.snowfall.tent.irfft_rows`, as in memory) straight into
    the chunk when it spans the whole width, else into one slab of scratch
    whose columns ``cols`` are kept (the x-pass of a row is recomputed for
    each chunk of its columns, as in :func:`_xpass_chunk`). ``post``: None,
    or ``(beta, (lo, hi))`` to rescale the chunk in place at the end.
    """
    import itertools

    import zarr

    z = zarr.open_array(path, mode="r")
    x0, x1 = cols
    whole = x1 - x0 == W
    out = np.empty(tuple(b - a for a, b in region) + (x1 - x0,), dtype=dt)
    rows = int(max(1, _CACHE // max(1, W * np.dtype(dt).itemsize)))
    P = None
    for st in itertools.product(*[range(a, b, s) for (a, b), s in zip(region, sub)]):
        sl = tuple(slice(s0, min(s0 + s, b)) for s0, s, (_, b) in zip(st, sub, region))
        blk = z[sl]
        K = blk.shape[-1]
        if P is None:
            P = np.zeros((rows, W // 2 + 1), dtype=blk.dtype)  # columns past K stay zero
            scratch = None if whole else np.empty((rows, W), dtype=dt)
        src = blk.reshape(-1, K)
        dst = out[tuple(slice(q.start - a, q.stop - a) for q, (a, _) in zip(sl, region))]
        if not dst.flags.c_contiguous:  # a block of rows short of the chunk's: made apart, then copied in
            part = np.empty(dst.shape, dtype=dt)
        else:
            part = dst
        pf = part.reshape(-1, x1 - x0)
        for r0 in range(0, src.shape[0], rows):
            r = min(rows, src.shape[0] - r0)
            P[:r, :K] = src[r0:r0 + r]
            if whole:
                irfft_rows(P[:r], W, pf[r0:r0 + r])
            else:
                pf[r0:r0 + r] = irfft_rows(P[:r], W, scratch[:r])[:, x0:x1]
        if part is not dst:
            dst[...] = part
    if post is not None:
        beta, (lo, hi) = post
        rescale_opacity(out, beta, lo=lo, hi=hi, workers=1)
    return out


def _reduce_extremes(parts):
    lo = min(float(np.asarray(q)[..., 0].min()) for q in parts)
    hi = max(float(np.asarray(q)[..., 1].max()) for q in parts)
    return lo, hi


def _rescale_raws(parts, starts, shape, dt, beta, lohi):
    """An output chunk made of the raw x-pass blocks inside it, each rescaled straight into its place.

    One pass over each block (no concatenation, no copy): ``starts`` gives
    each block's offset along t and y in the chunk of ``shape``.
    """
    lo, hi = lohi
    out = np.empty(shape, dtype=dt)
    for x, (a, b) in zip(parts, starts):
        dst = out[a:a + x.shape[0], b:b + x.shape[1]]
        if dst.flags.c_contiguous:
            opacity_copy(x, beta, lo=lo, hi=hi, out=dst)
        else:
            dst[...] = opacity_copy(x, beta, lo=lo, hi=hi)
    return out


def _rescale_raw(x, beta, lohi):
    """A raw chunk rescaled with the global extremes, into a new array (dask may still hold the raw chunk)."""
    lo, hi = lohi
    return opacity_copy(x, beta, lo=lo, hi=hi)


def _hold_raw(nbytes):
    """Whether a raw field of ``nbytes`` may wait in memory for its global extremes (one FFT pass instead of two).

    Yes when it takes at most a quarter of the memory there is: the sum of the
    workers' memory limits when a ``distributed`` client is active (a worker
    without a limit counts as this machine's available memory), else this
    machine's available memory.
    """
    total = None
    client = _active_client()  # None without importing distributed when nobody did
    if client is not None:
        workers = client.scheduler_info().get("workers", {})
        limits = [int(w.get("memory_limit") or 0) for w in workers.values()]
        if limits:
            total = sum(lim if lim > 0 else available_memory() for lim in limits)
    if total is None:
        total = available_memory()
    return int(nbytes) <= total // 4


# what a worker process holds before any task of ours: python, numpy, scipy, numba, distributed and noiselab
# imported, the kernels compiled (240-266 MiB measured on the 2-core test machine, benchmarks/bench_dask.md)
_IMPORTS = 240 << 20


def _pause_fraction():
    """The fraction of its memory limit at which ``distributed`` pauses a worker (``worker.memory.pause``)."""
    import dask

    frac = dask.config.get("distributed.worker.memory.pause", 0.8)
    return float(frac) if frac else 0.95  # pausing switched off: the nanny's terminate threshold


def _budget():
    """``(budget, workers)``: the bytes a worker can give one computation before it is paused, and how many share it.

    Under an active ``distributed`` client: the smallest over its workers of
    the pause threshold (``distributed.worker.memory.pause``, 80 % of the
    memory limit by default) less what the worker process holds already (its
    measured memory, at least ``_IMPORTS``); a worker without a limit counts
    this machine's available memory. A task past that pauses its worker for
    good: the worker stops taking tasks and nothing it holds moves. Without a
    client (dask's local schedulers): this machine's available memory, one
    "worker".
    """
    client = _active_client()
    if client is not None:
        workers = list(client.scheduler_info().get("workers", {}).values())
        if workers:
            frac = _pause_fraction()
            room = []
            for w in workers:
                lim = int(w.get("memory_limit") or 0) or available_memory()
                used = max(int((w.get("metrics") or {}).get("memory") or 0), _IMPORTS)
                room.append(max(0, int(frac * lim) - used))
            return min(room), len(workers)
    return available_memory(), 1


def _xpass_cap(budget):
    """Bytes of an x-pass task (its complex rows in, its real rows out): a third of the budget, 1 to 64 MiB."""
    return int(min(2 * _SLAB_MAX, max(1 << 20, budget // 3)))


def _fit_rows(lead, row_bytes, cap):
    """Regular blocks of the leading axes for a pass over whole rows of ``row_bytes``: at most ``cap`` bytes a task.

    ``lead``: the caller's chunks of the leading axes. Unchanged when its
    largest block fits; else the first axes' blocks are cut to divisors of
    the caller's (so the output chunks are whole groups of them), one row at
    the least. The pass works row by row, so the values do not depend on it.
    """
    sizes = [max(c) for c in lead]
    if int(np.prod(sizes)) * row_bytes <= cap:
        return lead
    for a in range(len(sizes)):
        others = int(np.prod(sizes[:a] + sizes[a + 1:]))
        want = max(1, cap // max(1, others * row_bytes))
        sizes[a] = max(d for d in range(1, sizes[a] + 1) if sizes[a] % d == 0 and d <= want)
        if int(np.prod(sizes)) * row_bytes <= cap:
            break
    return tuple(_blocks(sum(c), z) for c, z in zip(lead, sizes))


class _OwnedPath(str):
    """A path in the graph's tasks that keeps its scratch folder alive; sent to a worker, a plain ``str``."""

    def __reduce__(self):
        return (str, (str(self),))


class _Scratch:
    """A temporary folder for an automatic spill, owned by the lazy array's graph.

    Made in dask's ``temporary-directory`` (else the system's temporary
    folder) through :func:`noiselab.io.atomic.scratch_folder`, so a stopping
    signal removes it; removed when the last graph that holds one of its paths
    is garbage-collected, or at the interpreter's exit.
    """

    def __init__(self):
        import weakref

        import dask

        from ..io.atomic import scratch_folder

        base = dask.config.get("temporary-directory", None)   # else the system's temporary folder
        cm = scratch_folder(os.path.join(os.fspath(base), "noiselab-spill") if base else None, suffix=".spill.tmp")
        self.path = os.fspath(cm.__enter__())
        weakref.finalize(self, cm.__exit__, None, None, None)

    def __fspath__(self):
        return self.path

    def owned(self, path):
        out = _OwnedPath(path)
        out.owner = self
        return out


def _route(spill, task, shared):
    """The transposes' route: ``spill`` as given, else an owned scratch folder when the in-memory rechunk would not fit.

    ``task``: the bytes of the largest task; ``shared``: the bytes that the
    in-memory rechunk spreads over the workers (the transposed arrays, and
    for one-pass snow the raw field waiting for its extremes). The rechunk is
    kept when ``task + shared / workers`` fits :func:`_budget`; past it, the
    transposes go through zarr arrays in a :class:`_Scratch` folder.
    """
    if spill is not None:
        return spill
    budget, n = _budget()
    if task + shared / n <= budget:
        return None
    return _Scratch()


def _worker_rooms():
    """Each worker of the active ``distributed`` client: ``(name, limit, used, pause, room)`` in bytes; [] without one.

    ``limit``: its memory limit (none: this machine's available memory);
    ``used``: its process memory as the scheduler last heard it; ``pause``:
    where ``distributed`` pauses it (:func:`_pause_fraction` of the limit);
    ``room``: the most one task may take there, its pause point (what it
    holds now may still be released: :func:`_budget` sizes the tasks from
    what it holds), and 0 for a worker that is paused already or holds more
    than its pause point: it takes no task until it is below it again.
    """
    client = _active_client()
    if client is None:
        return []
    frac = _pause_fraction()
    out = []
    for addr, w in client.scheduler_info().get("workers", {}).items():
        lim = int(w.get("memory_limit") or 0) or available_memory()
        used = int((w.get("metrics") or {}).get("memory") or 0)
        pause = int(frac * lim)
        room = 0 if w.get("status") == "paused" or used >= pause else pause
        out.append((str(w.get("name", addr)), lim, used, pause, room))
    return out


_PAUSE_GRACE_S = 5.0  # how long a worker past its pause point may take to come back below it


def _check_worker_memory(tasks, what):
    """A clear ``MemoryError`` when no worker has room for the largest task of a chunked transform.

    ``tasks``: ``(description, bytes)`` of each stage's largest task (its input
    and output arrays, a lower bound on what the worker holds while it runs).
    Checked before the graph is built against every worker of the active
    ``distributed`` cluster (:func:`_worker_rooms`): the point where
    ``distributed`` pauses it (``distributed.worker.memory.pause``, 80 % of
    its memory limit), none for a worker that is paused already or holds
    more than that. When the largest task fits no worker, the error names
    the memory it needs per worker and what each worker has; no client
    (dask's local schedulers): nothing to check. A worker given more would be
    paused for good, or restarted for memory again and again; a paused worker
    takes no task, so a cluster whose every worker is past its pause point
    would wait for ever. A worker past its pause point often comes back
    below it in a moment (garbage collected, memory returned, data spilled):
    the workers are looked at again for ``_PAUSE_GRACE_S`` (5 s) before the
    error.

    Examples
    --------
    >>> _check_worker_memory([("an x-pass chunk", 1 << 20)], "snow")  # no cluster here: nothing to check
    """
    import time

    rooms = _worker_rooms()
    if not rooms or not tasks:
        return
    desc, need = max(tasks, key=lambda t: t[1])
    # a worker past its pause point often falls below it again in a moment (distributed collects garbage and
    # returns memory, spills what it holds): look again for a few seconds before refusing
    deadline = time.monotonic() + _PAUSE_GRACE_S
    while need > max(r[4] for r in rooms) and max(r[3] for r in rooms) >= need and time.monotonic() < deadline:
        time.sleep(0.25)
        rooms = _worker_rooms()
    best = max(r[4] for r in rooms)
    if need <= best:
        return
    frac = _pause_fraction()

    def mib(x):
        return f"{x / 2**20:.1f} MiB" if x < 10 << 20 else f"{x / 2**20:.0f} MiB"

    have = "; ".join(f"worker {n}: {mib(u)} in use of its {mib(lim)} memory limit, paused at {mib(p)} ({frac:.0%})"
                     + (", paused now" if r == 0 else "")
                     for n, lim, u, p, r in sorted(rooms, key=lambda r: -r[4])[:4])
    more = f"; and {len(rooms) - 4} more" if len(rooms) > 4 else ""
    least_used = min(max(r[2], _IMPORTS) for r in rooms)
    raise MemoryError(f"{what} needs at least {mib(need)} per worker ({desc}), and the cluster's workers have at "
                      f"most {mib(best)} before distributed pauses them ({have}{more}): pass smaller chunks= (fewer "
                      f"frames or rows per chunk), free what the workers hold (client.restart()) or start them with "
                      f"memory_limit of at least {mib((need + least_used) / frac)}")


@dispatch.register("snow")
def chunked_snow(shape, chunks, *, rng, c, band, thickness, direction, pan, beta, exponent, amplitude, dtype,
                 on_alias, rescale, spill=None):
    """:func:`noiselab.snowfall.snow` as a lazy dask array in ``chunks`` (see the module notes).

    Called by ``snow`` when ``chunks`` is given, after it validated the
    arguments. Equal to the in-memory video to float rounding.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.snowfall import snow
    >>> lazy = snow((8, 48, 64), rng=1, chunks=(3, 20, 64))
    >>> lazy.chunks
    ((3, 3, 2), (20, 20, 8), (64,))
    >>> float(np.max(np.abs(lazy.compute() - snow((8, 48, 64), rng=1)))) < 1e-6
    True
    """
    require_dask()
    T, H, W = shape
    dt = float_dtype(dtype)
    cdt = plan.complex_dtype(dt)
    out_chunks = _out_chunks(chunks, (T, H, W), dt)
    cols = tent_columns((T, H, W), c=c, band=band, thickness=thickness, direction=direction, pan=pan,
                        exponent=exponent, on_alias=on_alias)
    K = int(cols.kx.max()) + 1
    spec = assemble(cols, as_generator(rng), amplitude, dt)  # the in-memory path's sparse spectrum
    budget, _ = _budget()
    ckx = max(1, _slab_bytes(out_chunks, dt, budget) // max(1, T * H * cdt.itemsize))
    slab = T * H * min(ckx, K) * cdt.itemsize
    row_bytes = K * cdt.itemsize + 2 * W * dt.itemsize  # complex rows in, raw and rescaled rows out
    x_ty = _fit_rows(out_chunks[:2], row_bytes, _xpass_cap(budget))
    ct, cy = max(x_ty[0]), max(x_ty[1])
    out_chunk = int(np.prod([max(c) for c in out_chunks])) * dt.itemsize
    _check_worker_memory([(f"a t/y slab of {T} x {H} x {min(ckx, K)} complex cells", slab),
                         (f"an x-pass chunk of {ct} x {cy} rows, {K} complex cells in and {W} out",
                          ct * cy * row_bytes),
                         (f"an output chunk of {out_chunk >> 20} MiB, assembled and copied by the writer",
                          2 * out_chunk)], f"snow{tuple(shape)} in chunks {chunks}")
    kx_blocks, pieces = _snow_plan(cols, spec, K, ckx)
    tok = uuid.uuid4().hex[:12]
    hold = rescale and _hold_raw(T * H * W * dt.itemsize)
    # in memory, the t/y transpose (twice when the FFT runs twice) and the raw field waiting for its extremes
    shared = T * H * K * cdt.itemsize * (1 if hold or not rescale else 2) + (T * H * W * dt.itemsize if hold else 0)
    spill = _route(spill, max(slab, ct * cy * row_bytes, 2 * out_chunk), shared)
    ty = x_ty if spill is None else _regular(x_ty)
    s2_chunks = ty + ((W,),)
    mm_chunks = tuple((1,) * len(c_) for c_ in ty) + ((2,),)

    def stage1(prefix, after=()):
        name = f"snow-{prefix}-ty-{tok}"
        dsk = {}
        for b, piece in enumerate(pieces):
            dsk[(name, 0, 0, b)] = (_snow_slab, piece, T, H, cdt) + tuple(after)
        return _array(dsk, name, ((T,), (H,), kx_blocks), cdt)

    import itertools
    import operator

    name = f"snow-alpha-{tok}"
    lohi = f"snow-lohi-{tok}"
    blocks = list(itertools.product(range(len(ty[0])), range(len(ty[1]))))
    if spill is not None:
        # the t- and y-passes once, spilled; the x-pass twice (extremes over whole rows, then each output chunk made
        # straight from the spilled rows a block at a time: no rechunk after it, a task holds its chunk and a block)
        dsk = {}
        path, done = _spill_write(stage1("s"), s2_chunks[:2] + ((K,),), spill, dsk)

        def read(i, j, *after):
            return (_read_block, path, _regions(ty + ((K,),), (i, j, 0)), done) + after

        sub = tuple(max(c) for c in ty)

        def chunks_from_spill(xname, post):
            st = [_starts(c) for c in out_chunks]
            for idx in itertools.product(*[range(len(c)) for c in out_chunks]):
                reg = [[int(st[a][i]), int(st[a][i + 1])] for a, i in enumerate(idx)]
                dsk[(xname,) + idx] = (_snow_spilled_chunk, path, reg[:-1], reg[-1], W, dt, sub, post, done)
            return _array(dsk, xname, out_chunks, dt)

        if not rescale:
            return chunks_from_spill(f"snow-raw-x-{tok}", None)
        mm = f"snow-extremes-{tok}"
        for i, j in blocks:
            dsk[(mm, i, j, 0)] = (_snow_xpass, [read(i, j)], [0], W, dt, "extremes")
        dsk[lohi] = (_reduce_extremes, [(mm, i, j, 0) for i, j in blocks])
        return chunks_from_spill(name, (_post, float(beta), lohi))
    kst = [int(k) for k in _starts(kx_blocks)[:-1]]
    tst, yst = _starts(ty[0]), _starts(ty[1])

    def xpass(s1, xname, mode, dsk):
        """The x-pass tasks ``(xname, i, j, 0)``: each gathers its rows from the pieces of the slabs (no rechunk)."""
        dsk.update(_graph(s1))
        part = f"{s1.name}-part"
        for i, j in blocks:
            sl = (slice(int(tst[i]), int(tst[i + 1])), slice(int(yst[j]), int(yst[j + 1])))
            for b in range(len(kx_blocks)):
                dsk[(part, i, j, b)] = (operator.getitem, (s1.name, 0, 0, b), sl)
            dsk[(xname, i, j, 0)] = (_snow_xpass, [(part, i, j, b) for b in range(len(kx_blocks))], kst, W, dt,
                                     mode)
        return dsk

    if not rescale:
        dsk = xpass(stage1("raw"), name, None, {})
        return _array(dsk, name, s2_chunks, dt).rechunk(out_chunks)
    mm = f"snow-extremes-{tok}"
    if hold:
        # one pass: the raw chunks wait (held by dask) while their extremes are reduced, then each is rescaled
        both, raw = f"snow-raw-x-{tok}", f"snow-raw-{tok}"
        dsk = xpass(stage1("raw"), both, "both", {})
        for i, j in blocks:
            dsk[(raw, i, j, 0)] = (operator.getitem, (both, i, j, 0), 0)
            dsk[(mm, i, j, 0)] = (operator.getitem, (both, i, j, 0), 1)
        dsk[lohi] = (_reduce_extremes, [(mm, i, j, 0) for i, j in blocks])
        ost = [_starts(c) for c in out_chunks[:2]]
        if len(out_chunks[2]) == 1 and all(set(o.tolist()) <= set(q.tolist()) for o, q in zip(ost, (tst, yst))):
            # each output chunk is whole x-pass blocks: rescaled straight into it, no rechunk after
            for io, jo in itertools.product(range(len(out_chunks[0])), range(len(out_chunks[1]))):
                (t0, t1), (y0, y1) = (ost[0][io], ost[0][io + 1]), (ost[1][jo], ost[1][jo + 1])
                inside = [(i, j) for i, j in blocks if t0 <= tst[i] < t1 and y0 <= yst[j] < y1]
                dsk[(name, io, jo, 0)] = (_rescale_raws, [(raw, i, j, 0) for i, j in inside],
                                          [(int(tst[i] - t0), int(yst[j] - y0)) for i, j in inside],
                                          (int(t1 - t0), int(y1 - y0), W), dt, float(beta), lohi)
            return _array(dsk, name, out_chunks, dt)
        for i, j in blocks:
            dsk[(name, i, j, 0)] = (_rescale_raw, (raw, i, j, 0), float(beta), lohi)
        return _array(dsk, name, s2_chunks, dt).rechunk(out_chunks)
    # pass 1: each chunk's extremes only; pass 2 waits for them, recomputes, rescales chunk by chunk
    dsk = xpass(stage1("a"), mm, "extremes", {})
    dsk[lohi] = (_reduce_extremes, [(mm, i, j, 0) for i, j in blocks])
    dsk = xpass(stage1("b", after=(lohi,)), name, (_post, float(beta), lohi), dsk)
    return _array(dsk, name, s2_chunks, dt).rechunk(out_chunks)
