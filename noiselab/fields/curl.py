"""Curl noise: a divergence-free velocity field from lattice noise's exact derivatives.

Bridson, Hourihan & Nordenstam 2007: in 2-D the rotated gradient of a scalar
potential ``psi`` (in array order, ``(v_y, v_x) = (dpsi/dx, -dpsi/dy)``); in 3-D the curl of a
3-component potential. Its divergence is a difference of equal mixed
partials, zero up to rounding: no sources or sinks in a flow stimulus.
"""
from __future__ import annotations

import numpy as np

from .._core import check_int, check_real
from ..fractal import fractal_gradient
from ..lattice import Grid, LatticeNoise, grid_coordinates
from ..lattice.grid import check_grid
from ._common import as_points, check_noise

__all__ = ["curl_noise"]


def _jacobian(noise, x, octaves, lacunarity, gain):
    """Jacobian ``(..., dim_out, dim_in)`` of ``noise`` (or of its fractal sum) at points or on a Grid."""
    if octaves == 1:
        if isinstance(x, Grid) and isinstance(noise, LatticeNoise):
            return noise.jacobian_grid(x.shape, x.extent)
        if isinstance(x, Grid):
            shape, ext = check_grid(x.shape, x.extent, noise.dim_in)
            x = np.stack(np.meshgrid(*grid_coordinates(shape, ext), indexing="ij"), axis=-1)
        return noise.jacobian(as_points(x, noise.dim_in))
    if not isinstance(x, Grid):
        x = as_points(x, noise.dim_in)
    jac = fractal_gradient(noise, x, octaves, lacunarity=lacunarity, gain=gain)
    return jac[..., None, :] if noise.dim_out == 1 else jac


def curl_noise(noise, points, *, octaves=1, lacunarity=2.0, gain=0.5):
    r"""Divergence-free flow from a noise potential: its rotated gradient (2-D) or curl (3-D).

    Parameters
    ----------
    noise : LatticeNoise or Warped
        2-D: a scalar potential ``psi`` (``dim_in=2, dim_out=1``) of points
        in array order ``(y, x)``, giving the velocity in the same order,
        ``(v_y, v_x) = (dpsi/dx, -dpsi/dy)``: component ``i`` is along point
        axis ``i``, ``v[..., 0] = dpsi/dp_1`` and ``v[..., 1] = -dpsi/dp_0``
        (the streamfunction's velocity, tangent to the contours of ``psi``). 3-D: a vector potential ``A``
        (``dim_in=3, dim_out=3``), giving ``v = curl A``. The kernel needs a
        continuous first derivative (not ``box`` or ``linear``).
    points : array (..., 2 or 3), or Grid
        Where to evaluate (a ``noiselab.lattice.Grid`` uses the grid path).
    octaves, lacunarity, gain : optional
        Use the fractal sum of ``noise`` as the potential (:func:`noiselab.fractal.fractal_gradient`).

    Returns
    -------
    ndarray ``(..., dim_in)``: the velocity, in potential units per input unit, one component per point
    axis in the points' order.

    Notes
    -----
    ``div v = d2psi/dxdy - d2psi/dydx``: both mixed partials are the same
    tensor-product sum, so the divergence vanishes identically and the
    finite-difference divergence of ``v`` is truncation and rounding only
    (``tests/test_derivatives.py`` measures it, against O(1) for plain
    vector noise: ``noiselab/gallery/figures/derivatives.py``).

    Raises
    ------
    ValueError
        For a noise that is neither a 2-D scalar potential nor a 3-D vector
        potential, or a kernel without a continuous first derivative.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab import LatticeNoise
    >>> v = curl_noise(LatticeNoise(2, rng=0), np.random.default_rng(0).uniform(0, 4, (100, 2)))
    >>> v.shape
    (100, 2)
    """
    check_noise("noise", noise)
    octaves = check_int("octaves", octaves, lo=1, hi=10_000)
    check_real("lacunarity", lacunarity, lo=1.0, lo_open=True)  # checked even when one octave leaves them unused
    check_real("gain", gain, lo=0.0, lo_open=True)
    if noise.dim_in == 2 and noise.dim_out == 1:
        jac = _jacobian(noise, points, octaves, lacunarity, gain)[..., 0, :]
        return np.stack([jac[..., 1], -jac[..., 0]], axis=-1)
    if noise.dim_in == 3 and noise.dim_out == 3:
        J = _jacobian(noise, points, octaves, lacunarity, gain)   # J[..., c, a] = dA_c / dx_a
        return np.stack([J[..., 2, 1] - J[..., 1, 2], J[..., 0, 2] - J[..., 2, 0], J[..., 1, 0] - J[..., 0, 1]],
                        axis=-1)
    raise ValueError("noise must be a 2-D scalar potential (dim_in=2, dim_out=1) or a 3-D vector potential "
                     f"(dim_in=3, dim_out=3); got dim_in={noise.dim_in}, dim_out={noise.dim_out}")
