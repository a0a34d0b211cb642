"""Domain warping: ``noise(x + amount * warp_noise(x))``, with its Jacobian by the chain rule.

``J_noise(y) (I + amount J_warp(x))``. The result is itself a noise
(``__call__``, ``jacobian``, ``gradient``), so warps compose and feed
:func:`noiselab.fields.curl_noise` and :func:`noiselab.fractal.fractal_gradient`.
Anything with ``dim_in``, ``dim_out`` and ``jacobian(points, return_value=...)``
(a :class:`~noiselab.lattice.LatticeNoise` with a C1 kernel, a :class:`Warped`)
serves as ``noise``.
"""
from __future__ import annotations

import numpy as np

from .._core import check_real_vector
from ._common import as_points, check_noise

__all__ = ["warp", "Warped"]


class Warped:
    """``noise(x + amount * warp_noise(x))``: a domain-warped noise with its exact Jacobian (see :func:`warp`).

    Parameters
    ----------
    noise : LatticeNoise or Warped
        The warped noise (``dim_in``, ``dim_out``, ``jacobian``).
    warp_noise : LatticeNoise or Warped
        The displacement, mapping the noise's input space to itself
        (``dim_in = dim_out = noise.dim_in``).
    amount : float or sequence of float, default 1
        Displacement scale, one number or one per input axis.

    Raises
    ------
    ValueError
        For a ``warp_noise`` of the wrong dimensions or a non-finite ``amount``.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab.lattice import LatticeNoise
    >>> w = Warped(LatticeNoise(2, rng=1), LatticeNoise(2, 2, rng=2), amount=0.5)
    >>> w(np.zeros((3, 2))).shape, w.gradient(np.zeros((3, 2))).shape
    ((3,), (3, 2))
    """

    def __init__(self, noise, warp_noise, amount=1.0):
        check_noise("noise", noise)
        check_noise("warp_noise", warp_noise)
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
        return self._displaced(as_points(points, self.dim_in))

    def __call__(self, points):
        """Values at points ``(..., dim_in)``, shaped as the inner noise's."""
        return self.noise(self._displaced(as_points(points, self.dim_in)))

    def jacobian(self, points, *, return_value=False):
        """Jacobian ``(..., dim_out, dim_in)`` by the chain rule ``J_noise(y) (I + diag(amount) J_warp(x))``."""
        x = as_points(points, self.dim_in)
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

    Raises
    ------
    ValueError
        For a ``warp_noise`` that does not map the noise's input space to
        itself, or a non-finite ``amount``.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab import LatticeNoise
    >>> w = warp(LatticeNoise(2, rng=1), LatticeNoise(2, 2, rng=2), amount=0.5)
    >>> x = np.random.default_rng(0).uniform(0, 4, (10, 2))
    >>> w(x).shape, w.gradient(x).shape
    ((10,), (10, 2))
    >>> warp(w, LatticeNoise(2, 2, rng=3), 0.25).jacobian(x).shape    # warps compose
    (10, 1, 2)
    """
    return Warped(noise, warp_noise, amount)
