"""Smoothing kernels for lattice noise, and the range bounds that follow from them.

Every kernel is a piecewise polynomial written as ``m`` tap weights
``w_k(t)``, ``k = 0 .. m-1``, polynomials of degree <= 5 in the fractional
position ``t`` in [0, 1). A coordinate ``x`` is split as ``u = x + shift``,
``i0 = floor(u)``, ``t = u - i0``; the taps sit on the lattice points
``i0 - left + k`` and lie at signed distance ``x - tap = t - shift + left - k``.
Odd-order B-splines (box, quadratic) are centred on lattice points, hence
``shift = 1/2``.

Kernels (names, with their aliases):

===============  ========================  ====  ==========================================
name             aliases                   taps  what it is
===============  ========================  ====  ==========================================
``box``          ``bspline1``              1     order-1 B-spline: nearest lattice value
``linear``       ``bspline2``, ``tent``    2     order-2 B-spline: two box filters, C0
``quadratic``    ``bspline3``              3     order-3 B-spline: three box filters, C1
``cubic``        ``bspline4``              4     order-4 B-spline: four box filters, C2
``catmull-rom``  ``interpolating-cubic``   4     interpolating cubic spline, C1, overshoots
``quintic``      ``fade``                  2     Perlin's quintic fade 6t^5-15t^4+10t^3, C2
===============  ========================  ====  ==========================================

The B-splines are Phillips' "box-filtered" family (section 2.1.1): an order-m
B-spline is m box filters in a row. ``catmull-rom`` and ``quintic`` pass
through the lattice values.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.polynomial import Polynomial

__all__ = ["Kernel", "KERNELS", "get_kernel", "kernel_names"]

MAX_TAPS = 4
MAX_DEGREE = 5


@dataclass(frozen=True)
class Kernel:
    """One smoothing kernel: tap polynomials and the bounds used for range normalisation.

    Attributes
    ----------
    name : str
    taps : int
        Number of lattice points that contribute along each axis (the support).
    shift : float
        0 or 1/2 (odd orders are centred on lattice points).
    left : int
        Index of the first tap relative to ``floor(x + shift)``.
    coef : ndarray, shape (4, 6)
        ``coef[k, p]``: coefficient of ``t**p`` in tap ``k`` (rows past ``taps`` are zero).
    interpolating : bool
        Whether the kernel passes through the lattice values.
    abs_sum_max : float
        ``S = sup_t sum_k |w_k(t)|``: with values in [-1, 1], ``|noise| <= S**d`` in d dimensions.
    moment_max : float
        ``Q = sup_t sum_k |w_k(t)| * (t - shift + left - k)**2``, used by the gradient-noise bound.
    """

    name: str
    taps: int
    shift: float
    left: int
    coef: np.ndarray
    interpolating: bool
    abs_sum_max: float
    moment_max: float

    def weights(self, t):
        """Tap weights at fractional positions ``t`` (array), shape ``t.shape + (taps,)``."""
        t = np.asarray(t, dtype=np.float64)
        powers = t[..., None] ** np.arange(MAX_DEGREE + 1)
        return powers @ self.coef[: self.taps].T

    def __call__(self, x):
        """The continuous 1-D kernel ``K(x)`` (so that ``noise(x) = sum_i K(x - i) v_i``)."""
        x = np.asarray(x, dtype=np.float64)
        out = np.zeros_like(x)
        # x - tap = t - shift + left - k  =>  t = x + shift - left + k (if in [0, 1))
        for k in range(self.taps):
            t = x + self.shift - self.left + k
            inside = (t >= 0) & (t < 1)
            out[inside] = self.weights(t[inside])[:, k]
        return out

    @cached_property
    def dcoef(self) -> np.ndarray:
        """``dcoef[k, p]``: coefficient of ``t**p`` in the derivative ``w_k'(t)`` (shape (4, 6), last column 0)."""
        d = np.zeros_like(self.coef)
        d[:, :-1] = self.coef[:, 1:] * np.arange(1, MAX_DEGREE + 1)
        return d

    def dweights(self, t):
        """Derivatives ``w_k'(t)`` of the tap weights, shape ``t.shape + (taps,)``."""
        t = np.asarray(t, dtype=np.float64)
        powers = t[..., None] ** np.arange(MAX_DEGREE + 1)
        return powers @ self.dcoef[: self.taps].T

    def derivative(self, x):
        """The kernel's derivative ``K'(x)`` (one-sided from the right at its knots)."""
        x = np.asarray(x, dtype=np.float64)
        out = np.zeros_like(x)
        for k in range(self.taps):
            t = x + self.shift - self.left + k
            inside = (t >= 0) & (t < 1)
            out[inside] = self.dweights(t[inside])[:, k]
        return out

    @cached_property
    def continuity(self) -> int:
        """Smoothness class of ``K``: -1 (jumps), 0 (C0), 1 (C1), 2 (C2) or more.

        Checked on the tap polynomials: across every knot the pieces of
        ``K`` and of its derivatives must meet, ``w_k^(j)(1) = w_{k-1}^(j)(0)``,
        and vanish at both ends of the support (exact rational coefficients,
        compared to 1e-12).
        """
        polys = [Polynomial(self.coef[k]) for k in range(self.taps)]
        order = -1
        for j in range(MAX_DEGREE + 1):
            ders = [p.deriv(j) for p in polys]
            ok = abs(ders[self.taps - 1](0.0)) < 1e-12 and abs(ders[0](1.0)) < 1e-12
            ok = ok and all(abs(ders[k](1.0) - ders[k - 1](0.0)) < 1e-12 for k in range(1, self.taps))
            if not ok:
                break
            order = j
        return order

    def value_bound(self, dim: int) -> float:
        """Largest possible ``|sum_i K(x - i) v_i|`` for values ``|v_i| <= 1`` in ``dim`` dimensions."""
        return self.abs_sum_max ** dim

    def gradient_bound(self, dim: int) -> float:
        """Largest possible ``|sum_i K(x - i) g_i . (x - i)|`` for unit vectors ``g_i`` in ``dim`` dimensions.

        Cauchy-Schwarz gives ``|g . r| <= |r|``; Jensen (concavity of the
        square root, weights ``|w_i| / W``) gives
        ``sum |w_i| |r_i| <= sqrt(W * sum_i |w_i| |r_i|^2)`` with
        ``W = prod_a S(t_a) <= S^d`` and, by the tensor product,
        ``sum_i |w_i| |r_i|^2 = sum_a Q(t_a) prod_{b != a} S(t_b) <= d Q S^(d-1)``.
        Hence the bound ``sqrt(d Q) S^(d - 1/2)``; for Perlin's quintic in 2-D it
        is ``sqrt(2)/2``, which unit gradients reach at a cell centre.
        """
        return float(np.sqrt(dim * self.moment_max) * self.abs_sum_max ** (dim - 0.5))


def _poly_sup(coefs) -> float:
    """Exact supremum of a polynomial on [0, 1] (critical points and end points), rounded up."""
    p = Polynomial(coefs)
    crit = [r.real for r in p.deriv().roots() if abs(r.imag) < 1e-12 and 0.0 <= r.real <= 1.0]
    value = max(float(p(c)) for c in [0.0, 1.0, *crit])
    return value * (1.0 + 1e-12) + 1e-15


def _make(name, shift, rows, interpolating):
    taps = len(rows)
    coef = np.zeros((MAX_TAPS, MAX_DEGREE + 1))
    for k, row in enumerate(rows):
        coef[k, : len(row)] = row
    left = (taps - 1) // 2
    # Each tap weight keeps one sign on [0, 1) (checked in the tests), so
    # sum |w_k| and sum |w_k| r_k^2 are single polynomials whose suprema on
    # [0, 1] are found exactly from their critical points.
    signs = []
    for k in range(taps):
        mid = Polynomial(coef[k])(0.5)
        signs.append(1.0 if mid >= 0 else -1.0)
    abs_sum = sum((Polynomial(coef[k]) * s for k, s in enumerate(signs)), Polynomial([0.0]))
    moment = Polynomial([0.0])
    for k, s in enumerate(signs):
        r = Polynomial([-shift + left - k, 1.0])  # x - tap as a polynomial in t
        moment = moment + Polynomial(coef[k]) * s * r * r
    return Kernel(name, taps, shift, left, coef, interpolating,
                  _poly_sup(abs_sum.coef), _poly_sup(moment.coef))


KERNELS = {
    "box": _make("box", 0.5, [[1.0]], False),
    "linear": _make("linear", 0.0, [[1.0, -1.0], [0.0, 1.0]], True),
    "quadratic": _make("quadratic", 0.5, [[0.5, -1.0, 0.5], [0.5, 1.0, -1.0], [0.0, 0.0, 0.5]], False),
    "cubic": _make("cubic", 0.0, [
        [1 / 6, -3 / 6, 3 / 6, -1 / 6],
        [4 / 6, 0.0, -6 / 6, 3 / 6],
        [1 / 6, 3 / 6, 3 / 6, -3 / 6],
        [0.0, 0.0, 0.0, 1 / 6],
    ], False),
    "catmull-rom": _make("catmull-rom", 0.0, [
        [0.0, -0.5, 1.0, -0.5],
        [1.0, 0.0, -2.5, 1.5],
        [0.0, 0.5, 2.0, -1.5],
        [0.0, 0.0, -0.5, 0.5],
    ], True),
    "quintic": _make("quintic", 0.0, [
        [1.0, 0.0, 0.0, -10.0, 15.0, -6.0],
        [0.0, 0.0, 0.0, 10.0, -15.0, 6.0],
    ], True),
}

_ALIASES = {
    "bspline1": "box",
    "bspline2": "linear",
    "tent": "linear",
    "bspline3": "quadratic",
    "bspline4": "cubic",
    "interpolating-cubic": "catmull-rom",
    "catmull_rom": "catmull-rom",
    "catmullrom": "catmull-rom",
    "fade": "quintic",
}


def kernel_names() -> list[str]:
    """The canonical kernel names.

    Returns
    -------
    list of str
        The names :func:`get_kernel` and ``LatticeNoise(kernel=...)`` accept
        besides their aliases.

    Examples
    --------
    >>> "quintic" in kernel_names() and "cubic" in kernel_names()
    True
    """
    return list(KERNELS)


def get_kernel(kernel) -> Kernel:
    """Return the :class:`Kernel` for a name (or alias), or ``kernel`` itself if it is one.

    Parameters
    ----------
    kernel : str or Kernel
        A name of :func:`kernel_names` or an alias (``"bspline1"`` to
        ``"bspline4"``, ...), any case; a :class:`Kernel` passes through.

    Returns
    -------
    Kernel

    Raises
    ------
    TypeError
        For anything but a string or a :class:`Kernel`.
    ValueError
        For an unknown name (the message lists the allowed ones).

    Examples
    --------
    >>> get_kernel("bspline4").name
    'cubic'
    >>> round(get_kernel("catmull-rom").abs_sum_max, 6)
    1.25
    """
    if isinstance(kernel, Kernel):
        return kernel
    if not isinstance(kernel, str):
        raise TypeError(f"kernel must be a kernel name, got {type(kernel).__name__}")
    key = kernel.strip().lower()
    key = _ALIASES.get(key, key)
    if key not in KERNELS:
        allowed = ", ".join(list(KERNELS) + sorted(_ALIASES))
        raise ValueError(f"kernel must be one of {allowed}; got {kernel!r}")
    return KERNELS[key]
