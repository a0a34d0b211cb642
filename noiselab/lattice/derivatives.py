"""Exact derivatives of lattice noise: the Jacobian ``d noise_c / d x_a`` on a grid, and its shapes.

In input units, by the chain rule through ``a * noise(F x + phi)``: ``a F_a``
times the lattice-space derivative, which is the kernel's derivative on one
axis of the tensor product (and, in the gradient basis, the gradient
component ``g_a`` weighted by the kernel). At scattered points the value and
the whole Jacobian come from one kernel
(:func:`.points_path.evaluate_points_jac`); on a grid
(:func:`grid_jacobian`) each partial derivative is one run of the grid
passes with the kernel's derivative on its axis
(:func:`.grid_path.render_grid` with ``deriv_axis``). The fields built from
these derivatives (curl noise, domain warping) are in :mod:`noiselab.fields`.
"""
from __future__ import annotations

import math

import numpy as np

from . import checks
from .grid import check_grid
from .grid_path import finish_grid, render_grid
from .points_path import shape_out

__all__ = ["grid_jacobian", "jacobian_views"]


def grid_jacobian(noise, shape, extent, *, window=None, octaves=1, lacunarity=2.0, gain=0.5, absval=False,
                  value=True, periods=None, workers=1):
    """Value (or None) and Jacobian ``window shape + (dim_out, dim_in)`` of the octave sum on a grid.

    ``periods``: a lattice period per octave; ``workers``: threads, resolved
    (both as in :func:`.grid_path.render_grid`).

    One set of grid passes per input axis with the kernel's derivative on
    that axis (and one for the value). Turbulence (``absval``) is summed
    octave by octave as ``sign(n_o) n_o'``. The Jacobian is a view of one
    contiguous ``(dim_in, dim_out, *shape)`` buffer.
    """
    checks.check_differentiable(noise.kernel)
    shape, ext = check_grid(shape, extent, noise.dim_in)
    with np.errstate(over="ignore"):
        freqs = noise.frequency[None, :] * (float(lacunarity) ** np.arange(octaves, dtype=np.float64))[:, None]
        amps = noise.scale * float(gain) ** np.arange(octaves, dtype=np.float64)
    checks.check_reach(np.ascontiguousarray(ext.T), freqs, noise.phase, "extent")  # before any allocation
    size = math.prod(shape)
    checks.check_large(size * noise.dim_out * (noise.dim_in + 2) * 8, "lattice noise jacobian grid")
    kw = dict(dtype=np.float64, window=window, lacunarity=lacunarity, gain=gain, periods=periods, workers=workers)
    d = noise.dim_in
    # one contiguous (dim_out, *shape) block per input axis, written in
    # place by the grid passes; returned as a (*shape, dim_out, dim_in) view
    out_shape = tuple(hi - lo for lo, hi in checks.check_window(window, shape, d))
    buf = np.empty((d, noise.dim_out) + out_shape)
    if not absval:
        val = render_grid(noise, shape, ext, octaves=octaves, **kw) if value else None
        for a in range(d):
            render_grid(noise, shape, ext, octaves=octaves, deriv_axis=a, out=buf[a], **kw)
    else:
        buf[...] = 0.0
        total = np.zeros((noise.dim_out,) + out_shape)
        octave, part = np.empty_like(total), np.empty_like(total)
        for o in range(octaves):
            render_grid(noise, shape, ext, octaves=o + 1, octave_start=o, out=octave, **kw)
            sgn = np.sign(octave)
            total += np.abs(octave)
            for a in range(d):
                render_grid(noise, shape, ext, octaves=o + 1, octave_start=o, deriv_axis=a, out=part, **kw)
                buf[a] += sgn * part
        val = finish_grid(total) if value else None
    checks.check_jac_finite(buf, "on this grid (extent)", checks.jac_bound(freqs, amps))
    jac = np.moveaxis(buf, (0, 1), (-1, -2))
    return val, jac


def jacobian_views(out, lead, dim_out, dim_in):
    """The value ``lead (+ (dim_out,))`` and Jacobian ``lead + (dim_out, dim_in)`` in the points kernels' output.

    ``out`` is :func:`.points_path.evaluate_points_jac`'s ``(N, dim_out,
    1 + dim_in)``, value first; both results are views of it (no copies).
    """
    jac = out[:, :, 1:].reshape(tuple(lead) + (dim_out, dim_in))
    return shape_out(out[:, :, 0], lead, dim_out), jac
