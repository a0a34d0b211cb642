"""``GaborNoise``: sparse Gabor convolution noise (Lagae et al. 2009) at points and on grids.

A noise is a sum of Gabor kernels ``w K exp(-pi sum_a (s_a d_a)**2) cos(2 pi f . d + phi)``
at impulses scattered by a Poisson process of cells: each cell of size
``1 / s_a`` along axis ``a`` holds a Poisson(``density``) number of impulses,
and every impulse's position, weight ``w`` (uniform in [-1, 1)), phase
``phi`` and row of the frequency table come from the lattice's counter-based
hash of (cell, impulse index, key) (:mod:`noiselab.lattice.hashing`). Nothing
is stored but the table and the key, so any point, window or chunk of the
same noise gives the same bits.

The expected power spectrum has a closed form (:meth:`GaborNoise.expected_spectrum`):
``lambda E[w**2] K**2 / 4`` times the table's mean of the two Gaussian lobes
``|E^(nu -+ f_m)|**2``; ``K`` makes the variance 1.
"""
from __future__ import annotations

import math

import numpy as np
import scipy.special

from .._core import as_generator, check_real, check_shape, check_finite_array, float_dtype, check_memory
from .._core import resolve_workers
from .._core.workers import map_blocks, run_split
from ..lattice.hashing import MULT
from . import _kernels

__all__ = ["GaborNoise", "truncation_error"]

MAX_DENSITY = 256.0  # impulses per cell (Poisson by inversion of one uniform stays exact far beyond)
_MULTS = np.ascontiguousarray(MULT[:3])


def truncation_error(truncation, dim):
    """The relative RMS error of truncating every kernel where its envelope falls to ``truncation``.

    A kernel is cut where ``exp(-pi sum (s_a d_a)**2) = truncation``; the
    energy it loses is the tail of its squared envelope past that ellipsoid:
    ``truncation**2`` in 2-D, the chi-square (3 degrees of freedom) tail
    ``P(chi2_3 > 4 ln(1/truncation))`` in 3-D. The noise's error has that
    share of its variance, so its relative RMS error is the square root.

    Parameters
    ----------
    truncation : float
        Envelope level at the cut, in (0, 0.5].
    dim : {2, 3}
        Dimension of the noise.

    Returns
    -------
    float
        The RMS of (truncated - untruncated) over the RMS of the noise.

    Examples
    --------
    >>> round(truncation_error(0.01, 2), 6), round(truncation_error(0.01, 3), 4)
    (0.01, 0.019)
    """
    truncation = check_real("truncation", truncation, lo=0.0, hi=0.5, lo_open=True)
    if dim not in (2, 3):
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    x = 4.0 * math.log(1.0 / truncation)
    tail = math.exp(-x / 2.0) if dim == 2 else float(scipy.special.gammaincc(1.5, x / 2.0))
    return math.sqrt(tail)


class GaborNoise:
    """Sparse Gabor convolution noise in 2-D or 3-D, with still or moving kernels.

    Parameters
    ----------
    frequencies : array_like, (M, dim)
        The kernel frequency table, cycles per unit along each axis, array
        order (``(fy, fx)`` or ``(fz, fy, fx)``); each impulse picks a row
        from the hash. The expected spectrum is the table's mean of Gaussian
        lobes at ``+-f_m`` (the builders in :mod:`noiselab.gabor` sample the
        table from a target spectrum).
    bandwidth : float or sequence of dim floats
        ``s_a``: the Gaussian envelope ``exp(-pi (s_a d_a)**2)`` per axis,
        whose lobe in frequency is ``exp(-pi nu**2 / s_a**2)`` (cycles per
        unit, > 0). The kernel's cell is ``1 / s_a`` units.
    velocities_yx : array_like, (M, 2), optional
        Only for ``dim = 3`` with axis 0 as time: row ``m``'s kernel centre
        moves by ``velocities_yx[m] = (vy, vx)`` units of axes 1, 2 per unit of
        axis 0, so its energy lies on the plane ``nu_t = -v . nu`` (a moving
        grating). Default: still kernels.
    density : float
        Mean number of impulses per cell (Poisson), in (0, 256]. The number
        of kernels that overlap a point is ``density`` times the cut
        ellipsoid's volume in cells (``ln(1/truncation)`` in 2-D,
        ``4/3 pi (ln(1/truncation) / pi)**1.5`` in 3-D: 4.6 and 7.4 at the
        default truncation).
    truncation : float
        Envelope level (relative to its peak) where each kernel is cut, in
        (0, 0.5]; the relative RMS error this makes is
        :func:`truncation_error` (0.01 in 2-D, 0.019 in 3-D at 0.01).
    rng : int, numpy.random.Generator or None
        The random state: draws the hash key (one 32-bit word). Default 0, a
        fixed function like :class:`noiselab.LatticeNoise`.

    Examples
    --------
    >>> import numpy as np
    >>> g = GaborNoise([[0.0, 0.1]], bandwidth=0.05, rng=1)
    >>> img = g.grid((64, 64))
    >>> img.shape, img.dtype
    ((64, 64), dtype('float32'))
    >>> bool(np.array_equal(g.grid((16, 16), origin=(8, 8)), img[8:24, 8:24]))
    True
    >>> pts = np.array([[8.0, 9.0], [30.0, 2.0]])
    >>> bool(np.array_equal(g(pts, dtype=np.float64), g.grid((64, 64), dtype=np.float64)[[8, 30], [9, 2]]))
    True
    """

    def __init__(self, frequencies, *, bandwidth, velocities_yx=None, density=4.0, truncation=0.01, rng=0):
        f = check_finite_array("frequencies", frequencies)
        if f.ndim != 2 or f.shape[1] not in (2, 3) or f.shape[0] < 1:
            raise ValueError(f"frequencies must be an (M, 2) or (M, 3) table with M >= 1, got shape {f.shape}")
        dim = f.shape[1]
        self.dim = dim
        self.frequencies = np.array(f, dtype=np.float64)
        self.frequencies.setflags(write=False)
        s = np.atleast_1d(np.asarray(bandwidth, dtype=object)) if not np.isscalar(bandwidth) else None
        if s is None:
            s = [check_real("bandwidth", bandwidth, lo=0.0, lo_open=True)] * dim
        else:
            if len(s) != dim:
                raise ValueError(f"bandwidth must be a number or {dim} numbers (one per axis), got {len(s)}")
            s = [check_real(f"bandwidth[{i}]", v, lo=0.0, lo_open=True) for i, v in enumerate(s)]
        self.bandwidth = np.array(s, dtype=np.float64)
        if velocities_yx is not None:
            if dim != 3:
                raise ValueError("velocities_yx needs a 3-D noise (axis 0 is time): frequencies of shape (M, 3)")
            v = check_finite_array("velocities_yx", velocities_yx).astype(np.float64)
            if v.shape != (f.shape[0], 2):
                raise ValueError(f"velocities_yx must be ({f.shape[0]}, 2), one (vy, vx) per frequency row, "
                                 f"got {v.shape}")
        else:
            v = np.zeros((f.shape[0], 2))
        self.velocities_yx = v
        self.velocities_yx.setflags(write=False)
        self.density = check_real("density", density, lo=0.0, hi=MAX_DENSITY, lo_open=True)
        self.truncation = check_real("truncation", truncation, lo=0.0, hi=0.5, lo_open=True)
        self.key = np.uint32(as_generator(rng).integers(0, 1 << 32, dtype=np.uint64))
        # internal three axes (axis 0 absent in 2-D)
        s3 = np.ones(3) if dim == 2 else np.empty(3)
        s3[3 - dim:] = self.bandwidth
        self._s3 = s3
        self._cell = 1.0 / s3
        self._rho2 = math.log(1.0 / self.truncation) / math.pi
        rmax = math.sqrt(self._rho2)
        reach = rmax / s3
        if dim == 3:
            vmax = np.abs(v).max(axis=0) if v.size else np.zeros(2)
            reach[1:] += vmax * reach[0]
        else:
            reach[0] = 0.0
        self._reach = reach * (1 + 1e-9) + 1e-9
        self._f3 = np.zeros((f.shape[0], 3))
        self._f3[:, 3 - dim:] = self.frequencies
        # variance 1: lambda E[w^2] K^2 / 2 * prod 1 / (sqrt(2) s_a) with lambda = density * prod s_a
        lam = self.density * float(np.prod(self.bandwidth))
        self._lambda = lam
        self._amp = math.sqrt(2.0 * 3.0 / (lam * float(np.prod(1.0 / (math.sqrt(2.0) * self.bandwidth)))))

    def __repr__(self):
        return (f"GaborNoise(dim={self.dim}, rows={len(self.frequencies)}, bandwidth={self.bandwidth.tolist()}, "
                f"density={self.density:g}, truncation={self.truncation:g}, "
                f"moving={bool(np.any(self.velocities_yx))})")

    @property
    def truncation_error(self):
        """The relative RMS error of the kernels' truncation (:func:`truncation_error`)."""
        return truncation_error(self.truncation, self.dim)

    def _rest(self):
        return (self.key, _MULTS, self._cell, self._reach, self.density, self._s3, self._rho2, self._amp,
                self._f3, self.velocities_yx)

    def __call__(self, points, *, dtype=np.float32, workers=None):
        """The noise at ``points`` (``(..., dim)``, array order), as ``dtype``; threads split the points.

        Parameters
        ----------
        points : array_like, (..., dim)
            Coordinates in units (samples), array order.
        dtype : float32 or float64
            Output dtype (the sum is float64; float32 rounds it once).
        workers : int, optional
            Threads (scipy.fft's meaning); the result does not depend on them.

        Returns
        -------
        ndarray, ``points.shape[:-1]``
            Zero-mean noise of variance 1 (less the truncation's share).
        """
        dt = float_dtype(dtype)
        p = check_finite_array("points", points)
        if p.ndim < 1 or p.shape[-1] != self.dim:
            raise ValueError(f"points must be (..., {self.dim}) for a {self.dim}-D noise, got shape {p.shape}")
        if p.size and float(np.abs(p).max()) > 2.0 ** 52 * float(self._cell.min()) / 4:
            raise ValueError("points must be within |x| < 2**50 cells of the origin (float64 keeps their fractions)")
        check_memory(int(p.size // max(1, self.dim)) * (32 + dt.itemsize), f"gabor noise at {p.shape[:-1]} points")
        flat = p.reshape(-1, self.dim).astype(np.float64)
        pts = np.zeros((flat.shape[0], 3))
        pts[:, 3 - self.dim:] = flat
        out = np.empty(flat.shape[0], dtype=np.float64)
        nw = resolve_workers(workers)
        kernel = _kernels.points_kernel(self.dim)
        with np.errstate(over="ignore"):
            run_split(kernel, pts, out, self._rest(), nw, min_block=1024)
        return out.astype(dt, copy=False).reshape(p.shape[:-1])

    def grid(self, shape, *, origin=None, step=1.0, dtype=np.float32, workers=None, chunks=None):
        """The noise on the grid ``origin + i * step`` of ``shape`` (array order), as ``dtype``.

        Each sample equals the noise at its point (:meth:`__call__`) to the
        bit when the coordinates are the same floats: on integer origins with
        integer steps, any window of a grid equals the same region of a
        larger one.

        Parameters
        ----------
        shape : tuple of dim ints
            Samples per axis.
        origin : sequence of dim floats, optional
            Coordinate of the first sample (default zeros).
        step : float or sequence of dim floats
            Spacing of the samples (> 0).
        dtype : float32 or float64
            Output dtype.
        workers : int, optional
            Threads (scipy.fft's meaning): blocks of rows (2-D) or layers
            (3-D); the result does not depend on them.
        chunks : int, "auto" or one entry per axis, optional
            Return a lazy ``dask.array.Array`` in these chunks, each chunk
            the grid of its window (needs ``noiselab[dask]``): bit-identical
            to the in-memory grid when the origin and step are integers.

        Returns
        -------
        ndarray, ``shape``
        """
        dim = self.dim
        shape = check_shape("shape", shape, ndim=dim)
        dt = float_dtype(dtype)
        o = np.zeros(dim) if origin is None else np.array(
            [check_real(f"origin[{i}]", v) for i, v in enumerate(_seq("origin", origin, dim))])
        st = np.array([check_real(f"step[{i}]", v, lo=0.0, lo_open=True) for i, v in enumerate(
            [step] * dim if np.isscalar(step) else _seq("step", step, dim))])
        if float(np.abs(o).max(initial=0) + np.max(np.array(shape) * st)) > 2.0 ** 50 * float(self._cell.min()):
            raise ValueError("origin + shape * step must stay within 2**50 cells of the origin")
        if chunks is not None:
            from .._core import dispatch

            return dispatch.chunked("gabor_grid")(self, shape, origin=o, step=st, dtype=dt, chunks=chunks)
        check_memory(int(np.prod(shape)) * (8 + dt.itemsize), f"gabor grid {shape}")
        out = np.empty(shape, dtype=dt)
        nw = resolve_workers(workers)
        kernel = _kernels.grid_kernel(dim)
        # split along axis 0 of the output into blocks (layers in 3-D, rows in 2-D)
        if dim == 2:
            o3, s3, view = np.array([0.0, o[0], o[1]]), np.array([1.0, st[0], st[1]]), out[None]
            split_axis = 1
        else:
            o3, s3, view = o, st, out
            split_axis = 0
        n = view.shape[split_axis]
        nb_ = min(max(1, nw), n) if nw > 1 else 1
        bounds = np.linspace(0, n, nb_ + 1).astype(np.int64)

        def block(ab):
            a, b = int(ab[0]), int(ab[1])
            sub = view[:, a:b] if split_axis == 1 else view[a:b]
            off = np.zeros(3, dtype=np.int64)
            off[split_axis] = a
            acc = np.empty(sub.shape)
            rows = [np.empty(sub.shape[1]) for _ in range(3)]
            cols = [np.empty(sub.shape[2]) for _ in range(3)]
            with np.errstate(over="ignore"):
                kernel(sub, o3, s3, off, *self._rest(), acc, *rows, *cols)

        map_blocks(block, list(zip(bounds[:-1], bounds[1:])), nb_)
        return out

    def expected_spectrum(self, *f):
        """The expected power spectral density at frequencies ``f`` (cycles per unit, array order, broadcast).

        ``S(nu) = lambda E[w**2] K**2 / 4 * mean_m (|E^(nu' - f_m)|**2 + |E^(nu' + f_m)|**2)``
        with ``|E^(u)|**2 = prod_a exp(-2 pi u_a**2 / s_a**2) / s_a**2`` and
        ``nu'`` the frequency in the kernel's moving frame
        (``nu'_0 = nu_0 + v_m . (nu_1, nu_2)``). It integrates to the
        variance, 1 (without truncation). A grid of unit step has
        ``np.abs(np.fft.fftn(x))**2 / x.size`` with this mean. Sparse grids
        (``np.meshgrid(..., sparse=True)``) of still kernels are summed axis
        by axis (fast); other inputs point by point.

        Parameters
        ----------
        *f : array_like
            ``dim`` arrays of frequencies in cycles per unit, broadcast together.

        Returns
        -------
        ndarray
            Power per unit of frequency volume.
        """
        if len(f) != self.dim:
            raise ValueError(f"expected_spectrum takes {self.dim} frequency arrays (array order), got {len(f)}")
        f = [check_finite_array(f"f[{i}]", x).astype(np.float64) for i, x in enumerate(f)]
        try:
            shape = np.broadcast_shapes(*[x.shape for x in f])
        except ValueError:
            raise ValueError(f"the frequency arrays must broadcast together, got {[x.shape for x in f]}") from None
        s = self.bandwidth
        rows = self.frequencies
        lobes = np.concatenate([rows, -rows])            # the lobes at +f_m and -f_m
        vel = np.concatenate([self.velocities_yx, self.velocities_yx])
        scale = self._lambda * (1.0 / 3.0) * self._amp ** 2 / 4.0 * float(np.prod(1.0 / s ** 2)) / len(rows)
        nd = len(shape)
        axes = [[i for i, n in enumerate(x.shape) if n != 1] for x in f]
        separable = (not np.any(self.velocities_yx) and all(x.ndim == nd for x in f) and all(len(a) <= 1 for a in axes)
                     and len({a[0] for a in axes if a}) == sum(1 for a in axes if a))
        if separable:   # a sparse grid (np.meshgrid(..., sparse=True)): one factor per axis, summed by einsum
            factors, subs = [], []
            for a, x in enumerate(f):
                e = np.exp(-2.0 * math.pi * (x.reshape(-1)[None, :] - lobes[:, a:a + 1]) ** 2 / s[a] ** 2)
                factors.append(e if axes[a] else e[:, 0])
                subs.append("m" + (chr(ord("a") + axes[a][0]) if axes[a] else ""))
            out_subs = "".join(chr(ord("a") + i) for i in range(nd) if any(ax and ax[0] == i for ax in axes))
            total = np.einsum(",".join(subs) + "->" + out_subs, *factors)
            full = tuple(n if any(ax and ax[0] == i for ax in axes) else 1 for i, n in enumerate(shape))
            return scale * total.reshape(full) * np.ones(shape)
        fb = [np.broadcast_to(x, shape).reshape(-1) for x in f]
        total = np.zeros(fb[0].shape)
        step = max(1, (1 << 22) // max(1, fb[0].size))
        for m0 in range(0, len(lobes), step):
            L, V = lobes[m0:m0 + step], vel[m0:m0 + step]
            nu0 = fb[0][None, :]
            if self.dim == 3 and np.any(V):
                nu0 = nu0 + V[:, :1] * fb[1][None, :] + V[:, 1:] * fb[2][None, :]
            e = (nu0 - L[:, :1]) ** 2 / s[0] ** 2
            for a in range(1, self.dim):
                e = e + (fb[a][None, :] - L[:, a:a + 1]) ** 2 / s[a] ** 2
            total += np.exp(-2.0 * math.pi * e).sum(axis=0)
        return scale * total.reshape(shape)


def _seq(name, value, n):
    if np.isscalar(value) or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be a sequence of {n} numbers, got {type(value).__name__}")
    value = list(value)
    if len(value) != n:
        raise ValueError(f"{name} must hold {n} numbers (array order), got {len(value)}")
    return value
