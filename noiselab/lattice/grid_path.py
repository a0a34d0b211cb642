"""The grid path: lattice noise (or its octave sum, or one partial derivative of it) on a regular grid.

:func:`render_grid` evaluates a window of a grid (the whole grid by
default). Per octave it chooses, on the *full* grid so that every window
and chunk chooses alike:

- the **separable** passes (:func:`grid_separable`): the tensor-product
  kernel applied one axis at a time to the block of lattice values the grid
  covers, axes ``d-1 .. 1`` contracted into rows (:func:`contract_rest`),
  then one fused pass along axis 0; octaves are batched within a memory
  budget. Every dimension and both hashes take these sums; 2-D and 3-D
  grids (:data:`FUSED_DIMS`) take them in one kernel, row by row
  (:func:`grid_rows`: a few rows of temporaries instead of blocks the size
  of the grid, the same bits);
- the **scattered** path (:func:`grid_scattered`), row by row through
  :func:`.points_path.evaluate_points`, for grids sparser than the octave's
  lattice (:func:`is_separable`), for 1-D grids (whose separable rows are
  one sample each) and past 2**52 lattice cells, where a float64 coordinate
  has no fractional bits left. Its octaves are summed in float64, so that
  float32 output is the float64 sum rounded once.

Along one axis the taps are either a dense run of lattice points or, when
they spread over many cells, the distinct ones (:func:`axis_taps`).
"""
from __future__ import annotations

import copy
import itertools
import math
import threading

import numpy as np

from .._core import float_dtype, map_blocks
from . import checks
from . import _jit as jit
from .grid import check_grid, coordinates
from .points_path import evaluate_points, evaluate_points_jac
from .tables import period_masks

__all__ = ["render_grid", "with_period", "finish_grid", "is_separable", "grid_scattered", "axis_taps", "block_hash",
           "int_prefix", "grid_separable", "contract_rest"]

# Past 2**52 lattice cells a float64 coordinate has no fractional bits: the
# separable grid pass (which works with lattice indices relative to the
# grid's first tap) is then replaced by the per-point path, which reduces
# every index exactly (fmod), so both paths give the same samples.
SEPARABLE_LIMIT = float(2 ** 52)
# the least work (samples x octaves) a band of a ``workers`` split gets: measured on
# 2-D quintic fBm (benchmarks/bench_lattice.md, "workers=2 on bigger calls"), two
# threads ran a 512^2 grid of 6 octaves or a 1024^2 grid of one octave slower than
# one (0.6-0.9x: a band repeats the column set-up and the Python call, about
# 0.2 ms), a 1024^2 grid of 6 octaves 1.26x and a 2048^2 grid of 6 octaves 1.7-1.8x
MIN_BAND = 1 << 21


def render_grid(noise, shape, extent, *, dtype, window, octaves, lacunarity=2.0, gain=0.5, absval=False,
                deriv_axis=None, octave_start=0, out=None, periods=None, workers=1):
    """Octaves ``octave_start .. octaves-1`` of the octave sum on a window of the grid: ``window shape (+ (dim_out,))``.

    ``periods``: the lattice period of every octave, ``(octaves, dim_in)``
    (a tileable noise's octave sum, :func:`.checks.octave_periods`); default
    ``noise.period`` for all. Every pass below takes its octave's period.

    ``deriv_axis``: the partial derivative along that input axis instead (the
    same passes, with the kernel's derivative on that axis). ``out``: a
    contiguous ``(dim_out, *window shape)`` buffer of ``dtype`` to write
    into (the derivative grids' own); the result is then a view of it.

    ``workers`` > 1 (a thread count, already resolved) splits the window's
    first axis into that many bands rendered on pooled threads
    (:func:`render_bands`); a band is a window of the full grid, so the
    result is bit-identical for any count.
    """
    dtype = float_dtype(dtype)
    shape, ext = check_grid(shape, extent, noise.dim_in)
    coords = coordinates(shape, ext)
    sl = checks.check_window(window, shape, noise.dim_in)
    out_shape = tuple(hi - lo for lo, hi in sl)
    size = math.prod(out_shape)
    # the output, its copy or (float32) a float64 sum of the scattered octaves, a float64 row of coordinates
    checks.check_large(size * noise.dim_out * (dtype.itemsize + 8) + size * 8, f"lattice noise grid {shape}")
    checks.check_amplitude(noise.amplitude * checks.total_gain(octaves, gain), dtype,
                           "amplitude (times the sum of the octaves' gains)")
    if size == 0:
        return finish_grid(np.zeros((noise.dim_out,) + out_shape, dtype=dtype))
    bands = min(workers, out_shape[0], size * (octaves - octave_start) // MIN_BAND)
    full = list(coords)
    sub = [coords[a][lo:hi] for a, (lo, hi) in enumerate(sl)]
    separable, sparse = classify_octaves(noise, full, octave_start, octaves, lacunarity, gain, periods)
    if bands > 1 and (sparse or noise.dim_in not in FUSED_DIMS):  # the fused kernel splits its rows itself
        if out is None:
            out = np.empty((noise.dim_out,) + out_shape, dtype=dtype)
        render_bands(lambda win, part: render_grid(noise, shape, ext, dtype=dtype, window=win, octaves=octaves,
                                                   lacunarity=lacunarity, gain=gain, absval=absval,
                                                   deriv_axis=deriv_axis, octave_start=octave_start, out=part,
                                                   periods=periods),
                     sl, out, bands)
        return finish_grid(out)
    # the separable pass writes every sample unless it accumulates |.| (turbulence); octaves added one by one
    # (the scattered path) are summed in float64 and the sum rounded once, as every other path rounds its own
    writes_all = bool(separable) and not absval
    in64 = bool(sparse) and dtype != np.float64
    if out is None:
        out = (np.empty if writes_all or in64 else np.zeros)((noise.dim_out,) + out_shape, dtype=dtype)
    else:  # the caller's contiguous (dim_out, *out_shape) float64 buffer (the derivative grids)
        assert out.shape == (noise.dim_out,) + out_shape and out.flags.c_contiguous and out.dtype == dtype
        if not writes_all:
            out[...] = 0.0
    total = np.zeros(out.shape) if in64 else out
    if separable:
        grid_separable(noise, sub, full, separable, total, absval, deriv_axis, max(bands, 1))
    # grids sparser than an octave's lattice, and 1-D grids: the per-point path, consecutive octaves of one
    # period in one call (its kernels add the octaves in the same order, in float64: the same sums)
    for _, group in itertools.groupby(sparse, key=lambda octave: tuple(octave[2])):
        freqs, amps, periods = zip(*group)
        grid_scattered(with_period(noise, periods[0]), sub, np.array(freqs), np.array(amps), total, absval, deriv_axis)
    if in64:
        out[...] = total
        del total  # before finish_grid's copy: the memory check above counts the sum or the copy, not both
    return finish_grid(out)


def classify_octaves(noise, full, octave_start, octaves, lacunarity, gain, periods):
    """The octaves' ``(freq, amp, period)``: those the separable passes take, and those sparser than the grid."""
    separable, sparse = [], []
    ends = [float(max(abs(c[0]), abs(c[-1]))) if c.size else None for c in full]  # (Python floats: inf, no warning)
    for o in range(octave_start, octaves):
        freq = noise.frequency * lacunarity ** o
        amp = noise.scale * gain ** o
        reach = max((0.0 if end is None else end * float(freq[a])) + abs(float(noise.phase[a]))
                    for a, end in enumerate(ends))
        if not math.isfinite(reach):
            raise ValueError(f"extent times the frequency (and lacunarity**octave) overflows float64 "
                             f"({freq.max():.3g} lattice cells per unit); keep |x * frequency| below 1.7e308")
        exact = reach < SEPARABLE_LIMIT
        period = noise.period if periods is None else periods[o]
        (separable if exact and is_separable(noise.kernel.taps, full, freq) else sparse).append((freq, amp, period))
    return separable, sparse


def render_bands(render, window, out, bands):
    """``render(band window, band of out)`` for ``bands`` bands of the window's first axis, on pooled threads.

    ``out`` is the window's ``(dim_out, *window shape)`` buffer. A band of it
    is contiguous when there is one component; otherwise the band renders
    into its own buffer and is copied in (``render`` gets ``None``).
    """
    lo0, hi0 = window[0]
    cuts = np.linspace(lo0, hi0, bands + 1).astype(np.int64).tolist()

    def one(b):
        lo, hi = cuts[b], cuts[b + 1]
        part = out[:, lo - lo0:hi - lo0]
        if part.flags.c_contiguous:
            render([(lo, hi)] + list(window[1:]), part)
        else:
            part[...] = np.moveaxis(render([(lo, hi)] + list(window[1:]), None), -1, 0)

    map_blocks(one, range(bands), bands)


def with_period(noise, period):
    """``noise``, or a shallow copy of it with another lattice period (one octave of a tileable sum)."""
    if np.array_equal(period, noise.period):
        return noise
    twin = copy.copy(noise)
    twin.period = np.asarray(period, dtype=np.int64)
    twin._pmask = period_masks(twin.period)
    return twin


def finish_grid(out):
    """``(dim_out, *shape)`` as ``shape`` (one component) or ``shape + (dim_out,)``."""
    if out.shape[0] == 1:
        return out[0]
    return np.ascontiguousarray(np.moveaxis(out, 0, -1))


def is_separable(taps, full_coords, freq):
    """Separable if the lattice block is not much larger than the grid (decided on the full grid), in 2-D and up.

    A 1-D grid's separable rows are one sample each, so the per-row work of
    the passes outweighs the sums: the points path ran the same grid
    4.3-33x faster than 0.6.1's passes (262,144 samples, 6 octaves, both
    hashes and bases, ``python benchmarks/bench_lattice_paths.py --only
    "(262144,)"``, ``benchmarks/bench_lattice_paths.md``).
    """
    if len(full_coords) == 1:
        return False
    block = 1.0
    samples = 1.0
    for a, c in enumerate(full_coords):
        n = c.shape[0]
        span = abs(c[-1] - c[0]) * freq[a] if n > 1 else 0.0
        block *= min(n * taps, span + taps + 1)
        samples *= n
    return block <= 4.0 * samples + 4096


# the dimensions whose separable octaves take the fused kernel (:func:`grid_rows`); the others, the passes
FUSED_DIMS = (2, 3)
# the fused path's axis taps of the last few grids (:func:`shared_axis_taps`): a 512^2 fBm's set-up is 0.2 ms of 2
AXIS_TAPS_KEPT = 8
AXIS_TAPS_BYTES = 32 << 20  # and at most this much memory (a 4096-sample axis, 6 octaves, 4 taps: 1.5 MiB)
_AXIS_TAPS = {}
_KEPT_LOCK = threading.Lock()
# the points of one call of the scattered path: a block of whole rows of axis 0 (one row at least)
SCATTERED_BLOCK = 1 << 16


def grid_scattered(noise, sub, freqs, amps, out, absval, deriv_axis=None):
    """Octaves (``freqs`` ``(k, d)``, ``amps`` ``(k,)``) added into the float64 ``out`` by the points path, a
    block of rows of axis 0 at a time.

    Blocks of about :data:`SCATTERED_BLOCK` points keep the temporary small
    and the calls few (one per row cost 1.5-2x the time on 512² grids,
    ``benchmarks/bench_lattice_paths.md``); per-point results do not depend
    on the blocking.
    """
    d = noise.dim_in
    rest = np.stack(np.meshgrid(*sub[1:], indexing="ij"), axis=-1).reshape(-1, d - 1) \
        if d > 1 else np.zeros((1, 0))
    nrow = sub[0].shape[0]
    flat_out = out.reshape(noise.dim_out, nrow, -1)
    step = max(1, SCATTERED_BLOCK // max(1, rest.shape[0]))
    for j0 in range(0, nrow, step):
        j1 = min(nrow, j0 + step)
        pts = np.empty((j1 - j0, rest.shape[0], d))
        pts[:, :, 0] = sub[0][j0:j1, None]
        pts[:, :, 1:] = rest
        pts = pts.reshape(-1, d)
        if deriv_axis is None:
            vals = evaluate_points(noise, pts, freqs, amps, absval, np.dtype(np.float64))
        else:
            vals = evaluate_points_jac(noise, pts, freqs, amps, absval)[:, :, 1 + deriv_axis]
        for c in range(noise.dim_out):
            flat_out[c, j0:j1] += vals[:, c].reshape(j1 - j0, -1)


def axis_taps(noise, coords_a, freq_a, a, grad, deriv=False, period=None):
    """Weights, tap positions and the reduced lattice indices of the distinct taps along one axis.

    ``deriv``: the weights' derivatives along this axis in input units
    instead (:func:`_jit.axis_dweights`), for the derivative grids.
    ``period``: the octave's lattice period along this axis (default
    ``noise.period[a]``). One octave of :func:`octave_axis_taps`.
    """
    period = int(noise.period[a] if period is None else period)
    return octave_axis_taps(noise, coords_a, np.array([freq_a], dtype=np.float64), a, grad,
                            np.array([period], dtype=np.int64), deriv=deriv)[0]


def shared_axis_taps(noise, coords_a, freqs, a, grad, periods, deriv=False):
    """:func:`octave_axis_taps`, kept for the last :data:`AXIS_TAPS_KEPT` argument sets (at most
    :data:`AXIS_TAPS_BYTES` in all; larger sets are not kept), its arrays read-only.

    They depend on the grid's coordinates, the octaves' frequencies and
    periods, the phase and the kernel, not on the hash tables: many noises
    (seeds) on one grid, or one grid rendered again, reuse them, as an FFT
    reuses its plan. About 0.2 ms of a 2 ms 512^2 6-octave fBm
    (``benchmarks/bench_workers.md``, "The set-up of a grid"). Read-only
    because every caller shares them: the fused path only stacks and reads
    them.
    """
    k = noise.kernel
    key = (k.name, k.taps, k.shift, k.left, k.coef.tobytes(), k.dcoef.tobytes() if deriv else b"",
           coords_a.tobytes(), freqs.tobytes(), periods.tobytes(), float(noise.phase[a]), bool(grad), bool(deriv))
    taps = kept(_AXIS_TAPS, key)
    if taps is not None:
        return taps
    taps = octave_axis_taps(noise, coords_a, freqs, a, grad, periods, deriv=deriv)
    size = sum(arr.nbytes for arrays in taps for arr in {id(x): x for x in arrays}.values())
    if size > AXIS_TAPS_BYTES // 4:
        return taps  # too big to keep
    for arrays in taps:
        for arr in arrays:
            arr.flags.writeable = False
    keep(_AXIS_TAPS, key, taps, size)
    return taps


def kept(store, key):
    """What :func:`keep` put in ``store`` under ``key`` (now the most recently used), or None."""
    with _KEPT_LOCK:
        entry = store.pop(key, None)
        if entry is not None:
            store[key] = entry
    return None if entry is None else entry[0]


def keep(store, key, value, size):
    """Keep ``value`` (``size`` bytes) in ``store``: the last :data:`AXIS_TAPS_KEPT` entries, within
    :data:`AXIS_TAPS_BYTES`."""
    with _KEPT_LOCK:
        store[key] = (value, size)
        while len(store) > AXIS_TAPS_KEPT or sum(n for _, n in store.values()) > AXIS_TAPS_BYTES:
            del store[next(iter(store))]


def octave_axis_taps(noise, coords_a, freqs, a, grad, periods, deriv=False):
    """:func:`axis_taps` for several octaves of one axis at once (``freqs``, ``periods``: one per octave), in numpy.

    The point kernels' arithmetic, element by element (the same bits as the
    sample-by-sample reference ``tests/naive.py`` ``grid_axis_taps``,
    ``tests/test_lattice_grid_rows.py``), the distinct taps numbered in
    increasing order (dense: marked offsets from the smallest floor index;
    spread over many cells: ``np.unique``). numpy rather than kernels: a
    first grid compiles two kernels less (about 0.9 s CPU,
    ``benchmarks/bench_coldstart.md``), for about 0.1 ms more a 2-D fBm.
    Returns one ``(lattice, pos, w, rw)`` per octave (``rw``: the weights
    times the signed distances with ``grad``, else ``w``).
    """
    k = noise.kernel
    taps = k.taps
    nn = coords_a.shape[0]
    u = coords_a[None, :] * freqs[:, None] + noise.phase[a] + k.shift
    fis = np.floor(u)
    t = (u - fis)[None]  # taps first: numpy's inner loops then run along the samples
    if max(-fis.min(), fis.max()) < jit._INT_SAFE:
        i = fis.astype(np.int64) - k.left
    else:  # past it, reduce the float exactly first (as _jit._reduce)
        small = np.abs(fis) < jit._INT_SAFE
        i = np.where(small, np.where(small, fis, 0.0).astype(np.int64),
                     np.mod(np.where(small, 0.0, fis), periods[:, None].astype(np.float64)).astype(np.int64)) - k.left
    base = np.mod(i, periods[:, None])  # a power-of-two period's mask gives the same (two's complement)
    t2 = t * t
    t3 = t2 * t
    t4 = t2 * t2
    t5 = t4 * t
    c = k.coef[:taps].T[:, :, None, None]
    w = (c[0] + c[1] * t) + (c[2] * t2 + c[3] * t3) + (c[4] * t4 + c[5] * t5)
    rw = w * ((t - k.shift) + (k.left - np.arange(taps))[:, None, None]) if grad else w
    w = np.ascontiguousarray(w.transpose(1, 2, 0))  # (octaves, samples, taps)
    rw = np.ascontiguousarray(rw.transpose(1, 2, 0)) if grad else w
    # the dense octaves' distinct taps: offsets from each octave's smallest floor marked in one array
    j0 = np.argmin(fis, axis=1)
    lo = fis[np.arange(len(freqs)), j0]
    dense = (fis.max(axis=1) - lo) <= 4 * taps * nn + 64
    rel = (fis - lo[:, None]).astype(np.int64)
    size = np.where(dense, rel.max(axis=1) + taps, 0)
    off = np.concatenate([[0], np.cumsum(size)])
    marks = off[:-1, None, None] + rel[:, :, None] + np.arange(taps)
    mark = np.zeros(int(off[-1]), dtype=bool)
    mark[marks[dense].ravel()] = True
    index = np.cumsum(mark) - 1
    out = []
    for o in range(len(freqs)):
        wo, rwo = w[o], rw[o]
        if deriv:
            wo, rwo = jit.axis_dweights(coords_a, freqs[o], noise.phase[a], k.shift, k.left, taps, k.coef, k.dcoef,
                                        grad)
            rwo = rwo if grad else wo
        if dense[o]:
            first = index[off[o] - 1] + 1 if off[o] else 0
            lattice = np.mod(base[o, j0[o]] + np.flatnonzero(mark[off[o]:off[o + 1]]), periods[o])
            out.append((lattice, index[marks[o]] - first, wo, rwo))
        else:
            r = rel[o][:, None] + np.arange(taps)
            uniq, inv = np.unique(r, return_inverse=True)
            out.append(((base[o, j0[o]] + uniq) % periods[o], inv.reshape(r.shape).astype(np.int64), wo, rwo))
    return out


def block_hash(perm, n, lattices):
    """Hash the block of lattice points: ``h_{a+1} = P[(h_a + j_a) mod n]``, and the index parity (flat)."""
    h = par = np.zeros(1, np.int64)
    for a, lat in enumerate(lattices):  # no lattices: the single empty prefix
        h, par = jit.hash_expand(h, par, np.ascontiguousarray(lat, dtype=np.int64), perm, n, a == 0)
    return h, par


def int_prefix(key, mult, lattices):
    """The integer hash's prefix words ``key ^ j_0 M_0 ^ ...`` over the block of lattice points (flat).

    ``key`` is the component's ``(1,)`` uint32 key, ``mult`` the axis multipliers.
    """
    h = key.copy()  # writable, as every axis's result: one compiled specialisation (the keys are read-only)
    for a, lat in enumerate(lattices):
        h = jit.block_prefix(h, np.ascontiguousarray(lat, dtype=np.int64), mult[a], a == 0, key[0])
    return h


def _octave_batches(noise, full, octaves, nterm):
    """Octaves in batches whose partially contracted blocks fit a memory budget (decided on the full grid)."""
    post_full = int(np.prod([c.shape[0] for c in full[1:]], dtype=np.int64))
    budget = max(64 << 20, 2 * 8 * full[0].shape[0] * post_full)
    taps = noise.kernel.taps
    batches, cur, used = [], [], 0
    for octave in octaves:
        freq = octave[0]
        span = abs(full[0][-1] - full[0][0]) * freq[0] if full[0].shape[0] > 1 else 0.0
        rows = min(full[0].shape[0] * taps, span + taps + 1)
        need = 8 * rows * post_full * nterm
        if cur and used + need > budget:
            batches.append(cur)
            cur, used = [], 0
        cur.append(octave)
        used += need
    batches.append(cur)
    return batches


def grid_separable(noise, sub, full, octaves, out, absval, deriv_axis=None, bands=1):
    """Separable grid path: per octave and term, contract axes d-1..1; then one fused pass on axis 0.

    ``deriv_axis``: the derivative along that input axis instead (the
    same passes, with the kernel's derivative on that axis). ``bands``: the
    threads the fused kernel's rows are split over (2-D and 3-D only).
    """
    d = noise.dim_in
    grad = noise.basis == "gradient"
    integer = noise.hash == "integer"
    nterm = d if grad else 1
    batches = _octave_batches(noise, full, octaves, nterm)
    if d in FUSED_DIMS:
        flat = [o for batch in batches for o in batch]
        # every octave's taps along one axis at once; an axis like one already done (a square grid, equal
        # phases) reuses them
        done = {}
        per_axis = []
        for a in range(d):
            freqs = np.array([freq[a] for freq, _, _ in flat], dtype=np.float64)
            pers = np.array([per[a] for _, _, per in flat], dtype=np.int64)
            key = (sub[a].tobytes(), freqs.tobytes(), pers.tobytes(), float(noise.phase[a]), a == deriv_axis)
            if key not in done:
                done[key] = shared_axis_taps(noise, sub[a], freqs, a, grad, pers, deriv=a == deriv_axis)
            per_axis.append(done[key])
        axes_per_octave = [[per_axis[a][o] for a in range(d)] for o in range(len(flat))]
        grid_rows(noise, [o for batch in batches for o in batch], [len(batch) for batch in batches],
                  axes_per_octave, out, absval, bands)
        return
    post = int(np.prod([c.shape[0] for c in sub[1:]], dtype=np.int64))
    nj = sub[0].shape[0]
    for bi, batch in enumerate(batches):
        axes_per_octave = [[axis_taps(noise, sub[a], freq[a], a, grad, deriv=a == deriv_axis, period=per[a])
                            for a in range(d)] for freq, _, per in batch]
        rows = sum(len(axes[0][0]) for axes in axes_per_octave) * nterm
        for c in range(noise.dim_out):
            inter_all = np.empty((rows, post))
            poss, ws, scales = [], [], []
            row0 = 0
            for (freq, amp, _), axes in zip(batch, axes_per_octave):
                lattices = [ax[0] for ax in axes]
                bshape = tuple(len(lat) for lat in lattices)
                block = np.empty(int(np.prod(bshape, dtype=np.int64)))
                if integer:
                    h = int_prefix(noise.keys[c:c + 1], noise._mult, lattices)
                    if not grad:
                        jit.block_values(h, block)
                elif grad:
                    h, par = block_hash(noise.perms[c], noise.table_size, lattices)
                else:
                    # hash all but the last level, then hash and look up in one pass
                    h, par = block_hash(noise.perms[c], noise.table_size, lattices[:-1])
                    jit.hash_expand_values(h, par, np.ascontiguousarray(lattices[-1], dtype=np.int64),
                                           noise.perms[c], noise.table_size, d == 1, noise.values, block)
                for b in range(nterm):
                    if grad and integer:
                        jit.block_gradients(h, noise._int_grads, b, block)
                    elif grad:
                        jit.gather_gradients(h, noise.gradients, b, block)
                    target = inter_all[row0:row0 + bshape[0]]
                    contract_rest(block.reshape(bshape), axes, b if grad else -1, target)
                    _, pos0, w0, rw0 = axes[0]
                    poss.append(pos0 + row0)
                    ws.append(rw0 if (grad and b == 0) else w0)
                    scales.append(amp)
                    row0 += bshape[0]
            group_start = (np.arange(len(batch) + 1) * nterm if absval else np.array([0, len(ws)])).astype(np.int64)
            mode = 2 if absval else (0 if bi == 0 else 1)
            poss = np.ascontiguousarray(np.stack(poss))
            ws = np.ascontiguousarray(np.stack(ws))
            scales = np.asarray(scales, dtype=np.float64)
            target = out[c].reshape(nj, post)
            if mode == 0 and target.dtype == np.float64:
                jit.final_pass_direct(inter_all, poss, ws, scales, target)
            else:
                jit.final_pass(inter_all, poss, ws, scales, group_start, target, mode)


def _block_hash_np(perm, n, lattices):
    """:func:`block_hash` in numpy (the same integers): ``h_{a+1} = P[(h_a + j_a) mod n]`` and the parity, flat."""
    h = np.zeros(1, np.int64)
    par = np.zeros(1, np.int64)
    for lat in lattices:
        h = perm[(h[:, None] + lat[None, :]) % n].ravel()
        par = ((par[:, None] + lat[None, :]) & 1).ravel()
    return h, par


def _int_prefix_np(key, mult, lattices):
    """:func:`int_prefix` in numpy (the same words): ``key ^ (j_0 M_0 mod 2**32) ^ ...`` over the block, flat."""
    h = np.full(1, key, dtype=np.uint32)
    for a, lat in enumerate(lattices):
        h = (h[:, None] ^ (lat.astype(np.uint32) * np.uint32(mult[a]))[None, :]).ravel()
    return h


def grid_rows(noise, octaves, batch_sizes, axes_per_octave, out, absval, bands=1):
    """The 2-D and 3-D separable path in one kernel (:func:`_jit._make_grid_rows`): every octave, row by row.

    ``octaves``: the ``(freq, amp, period)`` of the separable octaves, in
    order, in batches of ``batch_sizes`` (:func:`_octave_batches`: the
    batches fix how the octaves are summed, so the bits are those of
    :func:`grid_separable`'s passes); ``axes_per_octave``: their
    :func:`axis_taps`. A sample's taps are consecutive lattice rows,
    ``pos[j, k] = pos[j, 0] + k`` (the distinct taps are numbered in
    increasing order, and the integers between two taps of one sample are
    its taps too), so the ``taps`` rows one output row needs never share a
    slot of the kernel's ring (row ``r`` in slot ``r mod taps``).

    ``bands`` > 1 splits the output's rows into that many bands, one kernel
    call each on pooled threads, after the set-up (every axis's taps, the
    hash prefixes) is made once for the whole window. A band's ring fills
    from its own first row, and a row's sum does not depend on the rows
    before it: the bits of one call. (Rendering each band as its own window
    repeated the set-up: 17 % more CPU time in all on a 1024^2 fBm,
    ``benchmarks/bench_workers.md``.)
    """
    d = noise.dim_in
    kernel = jit.grid_rows_kernel(d, noise.kernel.taps, noise.hash == "integer", noise.basis == "gradient")
    geometry, components = rows_plan(noise, axes_per_octave)
    scales = np.array([amp for _, amp, _ in octaves], dtype=np.float64)
    batch_start = np.concatenate([[0], np.cumsum(batch_sizes)]).astype(np.int64)
    P0, W0, RW0, shapes, pre_off, lat2, lat2_off, P1, W1, RW1, P2, W2, RW2 = geometry
    nj = out.shape[1]
    for c in range(noise.dim_out):
        pre, par, perm, mult2, values, folded = components[c]
        rows = out[c].reshape(nj, -1)

        def band(lo_hi, pre=pre, par=par, perm=perm, mult2=mult2, rows=rows, values=values, folded=folded):
            lo, hi = lo_hi  # a row slice of P0 / W0 / RW0, made contiguous (the kernel's one specialisation)
            p0, w0, rw0 = (np.ascontiguousarray(x[:, lo:hi]) for x in (P0, W0, RW0))
            kernel(shapes, pre, par, pre_off, lat2, lat2_off, p0, w0, rw0, P1, W1, RW1, P2, W2, RW2, scales,
                   batch_start, bool(absval), perm, int(noise.table_size), values, folded, mult2,
                   *jit.out_pair(rows[lo:hi]))

        cuts = np.linspace(0, nj, bands + 1).astype(np.int64).tolist()
        map_blocks(band, list(zip(cuts[:-1], cuts[1:])), bands)


# the fused kernel's arguments of the last few grids (:func:`rows_plan`), kept with the axis taps
# they were made from, under the same bounds
_ROW_PLANS = {}


def rows_plan(noise, axes_per_octave):
    """The fused kernel's arguments made from the axis taps and the hash tables: ``(geometry, components)``.

    ``geometry``: the stacked taps and offsets; ``components``: per output
    component the hash prefixes (and parities), the table and the folded
    look-ups. Made from kept axis taps
    (:func:`shared_axis_taps`), a plan is kept as they are, for the last
    :data:`AXIS_TAPS_KEPT` grids within :data:`AXIS_TAPS_BYTES`, keyed on
    those very taps (held here, so that their ids stay theirs) and on the
    tables' bytes: the serial set-up of a repeated 512^2 fBm, the part
    ``workers`` cannot split, 0.31-0.35 -> 0.18-0.19 ms
    (``benchmarks/bench_workers.md``). The arrays stay writeable (a read-only
    array is another numba type, another compilation); nothing writes them.
    """
    pieces = [ax for axes in axes_per_octave for ax in axes]
    taps_kept = all(not arr.flags.writeable for ax in pieces for arr in ax)
    if taps_kept:
        grad = noise.basis == "gradient"
        tables = (noise.keys, noise._mult) if noise.hash == "integer" else (noise.perms, noise.values)
        key = (tuple(map(id, pieces)), noise.dim_in, noise.kernel.taps, noise.hash, grad, noise.table_size,
               noise.gradients.tobytes() if grad else b"") + tuple(t.tobytes() for t in tables)
        entry = kept(_ROW_PLANS, key)
        if entry is not None:
            return entry[1]
    plan, size = _make_rows_plan(noise, axes_per_octave)
    if taps_kept and size <= AXIS_TAPS_BYTES // 4:
        keep(_ROW_PLANS, key, (axes_per_octave, plan), size)
    return plan


def _make_rows_plan(noise, axes_per_octave):
    """:func:`rows_plan`'s arguments, made, and their size in bytes."""
    d = noise.dim_in
    grad = noise.basis == "gradient"
    integer = noise.hash == "integer"
    noct = len(axes_per_octave)
    taps = noise.kernel.taps
    mids = [axes[1] for axes in axes_per_octave] if d == 3 else \
        [(None, np.zeros((1, taps), np.int64), np.ones((1, taps)), np.ones((1, taps)))] * noct

    def stack(items, k, transpose=False):  # (C order: np.stack keeps transposed inputs' order, another numba type)
        return np.ascontiguousarray(np.stack([it[k].T if transpose else it[k] for it in items]))

    first = [axes[0] for axes in axes_per_octave]
    last = [axes[-1] for axes in axes_per_octave]
    rk = 3 if grad else 2  # the ramp weights (gradient basis), else the weights again
    P0, W0, RW0 = stack(first, 1), stack(first, 2), stack(first, rk)
    P1, W1, RW1 = stack(mids, 1), stack(mids, 2), stack(mids, rk)
    P2, W2, RW2 = stack(last, 1, True), stack(last, 2, True), stack(last, rk, True)
    shapes = np.array([[len(axes[0][0]), len(axes[1][0]) if d == 3 else 1, len(axes[-1][0])]
                       for axes in axes_per_octave], dtype=np.int64)
    lat2 = np.concatenate([np.ascontiguousarray(ax[0], dtype=np.int64) for ax in last])
    lat2_off = np.concatenate([[0], np.cumsum(shapes[:, 2])]).astype(np.int64)
    pre_off = np.concatenate([[0], np.cumsum(shapes[:, 0] * shapes[:, 1])]).astype(np.int64)
    grads = noise._int_grads if integer else noise.gradients
    if grads is None:
        grads = np.zeros((1, d))
    heads = [[np.asarray(ax[0], dtype=np.int64) for ax in axes[:-1]] for axes in axes_per_octave]
    components = []
    for c in range(noise.dim_out):
        if integer:
            pre = np.concatenate([_int_prefix_np(noise.keys[c], noise._mult, lat) for lat in heads])
            components.append((pre, pre, np.zeros(1, np.int64), noise._mult[d - 1], noise.values, grads))
        else:
            hp = [_block_hash_np(noise.perms[c], noise.table_size, lat) for lat in heads]
            perm = noise.perms[c]
            components.append((np.concatenate([h for h, _ in hp]), np.concatenate([q for _, q in hp]), perm,
                               np.uint32(0)) + folded_tables(perm, noise.values, noise.gradients if grad else None))
    geometry = (P0, W0, RW0, shapes, pre_off, lat2, lat2_off, P1, W1, RW1, P2, W2, RW2)
    size = sum(x.nbytes for x in geometry) + sum(x.nbytes for comp in components for x in comp[:2])
    return (geometry, components), size


def folded_tables(perm, values, grads):
    """The table hash's last level folded into the look-ups, for the fused grid kernel: one read a lattice point.

    ``VL[r, x] = values[(r + x) & 1, P[x mod n]]`` and ``GP[x] = grads[P[x mod n]]``
    for ``x < 2n`` (``grads`` ``None``, the value basis: a ``(1, 1)`` placeholder).
    A prefix ``h < n`` plus a reduced lattice index ``j < n`` (a table-hash
    period is at most the table size; the kernel reduces past ``2n``) reads
    ``GP[h + j]``, or ``VL[(p - h) & 1, h + j]`` for the value of parity
    ``(p + j) & 1``: the same numbers as ``P[(h + j) mod n]`` looked up.
    """
    length = 2 * perm.shape[0]
    folded = np.zeros((1, 1)) if grads is None else np.ascontiguousarray(jit.fold_last_level(perm, values, grads,
                                                                                             length))
    return jit.fold_last_level(perm, values, None, length), folded


def contract_rest(block, axes, use_r, target):
    """Contract axes d-1 .. 1 of a lattice block into ``target`` (rows of axis 0 x the other grid axes).

    Axis ``use_r`` takes the gradient ramp weights.
    """
    cur = block
    d = cur.ndim
    if d == 1:
        target[:, 0] = cur
        return
    for a in range(d - 1, 0, -1):
        _, pos, w, rw = axes[a]
        weights = rw if a == use_r else w
        pre = int(np.prod(cur.shape[:a], dtype=np.int64))
        post = int(np.prod(cur.shape[a + 1:], dtype=np.int64))
        if a == 1:
            nxt = target.reshape(pre, pos.shape[0], post)
        else:
            nxt = np.empty((pre, pos.shape[0], post))
        if post == 1:
            jit.contract_last(cur.reshape(pre, cur.shape[a]), np.ascontiguousarray(pos.T), np.ascontiguousarray(weights.T),
                              nxt.reshape(pre, pos.shape[0]))
        else:
            jit.contract_mid(cur.reshape(pre, cur.shape[a], post), pos, weights, nxt)
        cur = nxt.reshape(cur.shape[:a] + (pos.shape[0],) + cur.shape[a + 1:])
