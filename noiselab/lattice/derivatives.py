"""Fields built from lattice noise's exact derivatives: curl noise and domain warping.

- :func:`curl_noise`: a divergence-free velocity field (Bridson, Hourihan &
  Nordenstam 2007): in 2-D the rotated gradient ``(dpsi/dy, -dpsi/dx)`` of a
  scalar potential ``psi``; in 3-D the curl of a 3-component potential. Its
  divergence is a difference of equal mixed partials, zero up to rounding:
  no sources or sinks in a flow stimulus.
- :func:`warp`: domain warping, ``noise(x + amount * warp_noise(x))``, with
  its Jacobian by the chain rule ``J_noise(y) (I + amount J_warp(x))``. The
  result is itself a noise (``__call__``, ``jacobian``, ``gradient``), so
  warps compose and feed :func:`curl_noise` and
  :func:`noiselab.fractal.fractal_gradient`.

Anything with ``dim_in``, ``dim_out`` and ``jacobian(points, return_value=...)``
(a :class:`~noiselab.lattice.LatticeNoise` with a C1 kernel, a :class:`Warped`)
serves as ``noise``.
"""
from __future__ import annotations

import numpy as np

from .._core import check_finite_array, check_int, check_real, check_real_vector
from .core import Grid, LatticeNoise, _check_grid, grid_coordinates

__all__ = ["curl_noise", "warp", "Warped"]


def _check_noise(name, noise):
    if not (callable(getattr(noise, "jacobian", None)) and hasattr(noise, "dim_in") and hasattr(noise, "dim_out")):
        raise TypeError(f"{name} must be a LatticeNoise (or a warp of one): an object with dim_in, dim_out and "
                        f"jacobian(points); got {type(noise).__name__}")


def _as_points(points, dim, name="points"):
    """``points`` as float64 ``(..., dim)`` (for ``dim == 1`` a plain array is that many inputs)."""
    pts = check_finite_array(name, points).astype(np.float64, copy=False)
    if dim == 1 and (pts.ndim == 0 or pts.shape[-1] != 1):
        pts = pts[..., None]
    if pts.ndim == 0 or pts.shape[-1] != dim:
        raise ValueError(f"{name} must have shape (..., dim_in={dim}), got {np.shape(points)}")
    return pts


def _jacobian(noise, x, octaves, lacunarity, gain):
    """Jacobian ``(..., dim_out, dim_in)`` of ``noise`` (or of its fractal sum) at points or on a Grid."""
    if octaves == 1:
        if isinstance(x, Grid) and isinstance(noise, LatticeNoise):
            return noise.jacobian_grid(x.shape, x.extent)
        if isinstance(x, Grid):
            shape, ext = _check_grid(x.shape, x.extent, noise.dim_in)
            x = np.stack(np.meshgrid(*grid_coordinates(shape, ext), indexing="ij"), axis=-1)
        return noise.jacobian(_as_points(x, noise.dim_in))
    from ..fractal import fractal_gradient

    if not isinstance(x, Grid):
        x = _as_points(x, noise.dim_in)
    jac = fractal_gradient(noise, x, octaves, lacunarity=lacunarity, gain=gain)
    return jac[..., None, :] if noise.dim_out == 1 else jac


def curl_noise(noise, points, *, octaves=1, lacunarity=2.0, gain=0.5):
    r"""Divergence-free flow from a noise potential: its rotated gradient (2-D) or curl (3-D).

    Parameters
    ----------
    noise : LatticeNoise or Warped
        2-D: a scalar potential ``psi`` (``dim_in=2, dim_out=1``), giving
        ``v = (dpsi/dy, -dpsi/dx)`` (the streamfunction's velocity, tangent to
        the contours of ``psi``). 3-D: a vector potential ``A``
        (``dim_in=3, dim_out=3``), giving ``v = curl A``. The kernel needs a
        continuous first derivative (not ``box`` or ``linear``).
    points : array (..., 2 or 3), or Grid
        Where to evaluate (a ``noiselab.lattice.Grid`` uses the separable grid passes).
    octaves, lacunarity, gain : optional
        Use the fractal sum of ``noise`` as the potential (:func:`noiselab.fractal.fractal_gradient`).

    Returns
    -------
    ndarray ``(..., dim_in)``: the velocity, in potential units per input unit.

    Notes
    -----
    ``div v = d2psi/dxdy - d2psi/dydx``: both mixed partials are the same
    tensor-product sum, so the divergence vanishes identically and the
    finite-difference divergence of ``v`` is truncation and rounding only
    (``tests/test_derivatives.py`` measures it, against O(1) for plain
    vector noise: ``gallery/figures/derivatives.py``).

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab import LatticeNoise
    >>> v = curl_noise(LatticeNoise(2, seed=0), np.random.default_rng(0).uniform(0, 4, (100, 2)))
    >>> v.shape
    (100, 2)
    """
    _check_noise("noise", noise)
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


class Warped:
    """``noise(x + amount * warp_noise(x))``: a domain-warped noise with its exact Jacobian (see :func:`warp`)."""

    def __init__(self, noise, warp_noise, amount=1.0):
        _check_noise("noise", noise)
        _check_noise("warp_noise", warp_noise)
        if warp_noise.dim_in != noise.dim_in or warp_noise.dim_out != noise.dim_in:
            raise ValueError(f"warp_noise must map the noise's input space to itself: dim_in = dim_out = "
                             f"{noise.dim_in}; got dim_in={warp_noise.dim_in}, dim_out={warp_noise.dim_out}")
        if isinstance(amount, (list, tuple, np.ndarray)) and np.ndim(amount) == 1 and len(amount) == 1:
            amount = amount[0]  # one number in a sequence: every axis
        self.amount = check_real_vector("amount", amount, noise.dim_in)
        self.noise, self.warp_noise = noise, warp_noise
        self.dim_in, self.dim_out = noise.dim_in, noise.dim_out

    def __repr__(self):
        return f"warp({self.noise!r}, {self.warp_noise!r}, amount={self.amount.tolist()})"

    def _displaced(self, x):
        w = np.asarray(self.warp_noise(x), dtype=np.float64).reshape(x.shape)
        return self._add(x, w)

    def _add(self, x, w):
        with np.errstate(over="ignore", invalid="ignore"):
            y = x + self.amount * w
        if not np.isfinite(y).all():
            raise ValueError(f"the warped points x + amount * warp_noise(x) overflow float64 (amount up to "
                             f"{np.abs(self.amount).max():.3g}); use a smaller amount or warp_noise amplitude")
        return y

    def warp_points(self, points):
        """The warped positions ``x + amount * warp_noise(x)``, shape ``(..., dim_in)``."""
        return self._displaced(_as_points(points, self.dim_in))

    def __call__(self, points):
        """Values at points ``(..., dim_in)``, shaped as the inner noise's."""
        return self.noise(self._displaced(_as_points(points, self.dim_in)))

    def jacobian(self, points, *, return_value=False):
        """Jacobian ``(..., dim_out, dim_in)`` by the chain rule ``J_noise(y) (I + diag(amount) J_warp(x))``."""
        x = _as_points(points, self.dim_in)
        wv, wj = self.warp_noise.jacobian(x, return_value=True)
        wv = np.asarray(wv, dtype=np.float64).reshape(x.shape)
        wj = np.asarray(wj).reshape(x.shape[:-1] + (self.dim_in, self.dim_in))
        y = self._add(x, wv)
        value, nj = self.noise.jacobian(y, return_value=True)
        nj = np.asarray(nj).reshape(x.shape[:-1] + (self.dim_out, self.dim_in))
        with np.errstate(over="ignore", invalid="ignore"):
            jac = np.matmul(nj, self.amount[:, None] * wj + np.eye(self.dim_in))
        if not np.isfinite(jac).all():
            raise ValueError(f"the warp's derivative overflows float64: amount (up to {np.abs(self.amount).max():.3g}) "
                             "times warp_noise's derivative; use a smaller amount")
        return (value, jac) if return_value else jac

    def gradient(self, points, *, return_value=False):
        """Gradient ``(..., dim_in)`` of a scalar warped noise (``dim_out == 1``)."""
        if self.dim_out != 1:
            raise ValueError(f"gradient is for scalar noise (dim_out=1), this noise has dim_out={self.dim_out}; "
                             "use jacobian")
        value, jac = self.jacobian(points, return_value=True)
        return (value, jac[..., 0, :]) if return_value else jac[..., 0, :]


def warp(noise, warp_noise, amount=1.0):
    r"""Domain warping: ``noise(x + amount * warp_noise(x))``, with its derivative by the chain rule.

    Parameters
    ----------
    noise : LatticeNoise or Warped
        The noise that is looked up (any ``dim_out``).
    warp_noise : LatticeNoise or Warped
        The displacement field, ``dim_in = dim_out = noise.dim_in`` (a scalar
        noise for 1-D input).
    amount : float or sequence of dim_in floats, default 1
        Displacement scale (input units per unit of ``warp_noise``), per axis if a sequence.

    Returns
    -------
    Warped
        Callable on points ``(..., dim_in)``, with ``jacobian(points)`` and
        (scalar noise) ``gradient(points)``, both accepting ``return_value``.
        It is a noise itself: warp it again, or pass it to :func:`curl_noise`
        or :func:`noiselab.fractal.fractal_gradient`.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab import LatticeNoise
    >>> w = warp(LatticeNoise(2, seed=1), LatticeNoise(2, 2, seed=2), amount=0.5)
    >>> x = np.random.default_rng(0).uniform(0, 4, (10, 2))
    >>> w(x).shape, w.gradient(x).shape
    ((10,), (10, 2))
    >>> warp(w, LatticeNoise(2, 2, seed=3), 0.25).jacobian(x).shape    # warps compose
    (10, 1, 2)
    """
    return Warped(noise, warp_noise, amount)
