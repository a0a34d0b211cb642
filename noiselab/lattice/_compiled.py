"""The one module of the lattice path that imports the compiled kernels, and the lookups into their tables.

Everything numba compiles lives in the kernel modules: :mod:`._jit` (the
generic per-point kernels and the grid passes), :mod:`._inthash` (the
integer hash and its generic kernels), :mod:`._intgrid` (the integer hash
in the fused 2-D grid kernel), and the specialised families that
``_generate.py`` writes and :mod:`._kerncache` generates on first use into a
cache folder (never into git): ``points`` (unrolled per dimension and tap
count, and the 3-D kernels over precombined hash tables), ``jacobians``
(the same templates written with their derivative lines) and ``intpoints``
(the integer hash's SIMD kernels, one module per dimension, kernel and
basis, loaded on first lookup). The rest of the
lattice code (:mod:`.tables`, :mod:`.points_path`, :mod:`.grid_path`,
:mod:`.derivatives`) reaches them only through this module: ``jit``,
``inthash`` and ``intgrid`` for the generic kernels, and the functions below
for the specialised ones, so a change in where or how the kernels are built
touches these lines only.

Each generated module is loaded on first use: its kernels cost import (and
generation) time that a user of another path does not need to pay.
"""
from __future__ import annotations

import numpy as np

from . import _intgrid as intgrid
from . import _inthash as inthash
from . import _jit as jit
from . import _kerncache
from .kernels import KERNELS, Kernel

__all__ = ["jit", "inthash", "intgrid", "PERIOD_MAX", "has_table_points", "table_points_kernel",
           "unrolled_points_kernel", "int_simd_kernels", "int_simd_factor", "unrolled_jacobian_kernel",
           "table_jacobian_kernel"]

# without ``period``, the integer hash reduces lattice indices modulo 2**32 per axis (its words are 32-bit)
PERIOD_MAX = inthash.PERIOD_MAX


def _is_stock(kernel: Kernel) -> bool:
    """Whether ``kernel`` has a stock kernel's name and coefficients (then kernels with them written in apply)."""
    stock = KERNELS.get(kernel.name)
    return stock is not None and np.array_equal(stock.coef, kernel.coef)


def has_table_points(dim: int, taps: int) -> bool:
    """Whether a scattered kernel over precombined hash tables exists for ``dim`` and ``taps`` (3-D only)."""
    return (dim, taps) in _kerncache.load("points").TABLE_KERNELS


def table_points_kernel(dim: int, kernel: Kernel):
    """The 3-D table kernel: with this kernel's coefficients written in if it is a stock kernel."""
    table_kernels = _kerncache.load("points").TABLE_KERNELS
    if _is_stock(kernel) and (dim, kernel.name) in table_kernels:
        return table_kernels[(dim, kernel.name)]
    return table_kernels.get((dim, kernel.taps))


def unrolled_points_kernel(dim: int, taps: int):
    """The per-point kernel unrolled for ``dim`` and ``taps`` (1-3-D), or None."""
    return _kerncache.load("points").KERNELS.get((dim, taps))


def int_simd_kernels(dim: int, kernel: Kernel, basis: str):
    """The integer hash's SIMD kernels (``{variant: kernel}``, variants ``s32f32``, ``s64f32``, ``s64f64``), or None.

    None for 4-D and up and for kernels other than the stock ones (those take
    the generic :func:`._inthash.int_points`).
    """
    stock = KERNELS.get(kernel.name)
    if (dim > 3 or stock is None or not np.array_equal(stock.coef, kernel.coef) or stock.shift != kernel.shift
            or stock.left != kernel.left):
        return None
    int_kernels = _kerncache.load("intpoints").INT_KERNELS   # each family's module loads on its first lookup
    return {v: int_kernels[(dim, kernel.name, basis, v)] for v in ("s32f32", "s64f32", "s64f64")}


def int_simd_factor(basis: str, dim: int) -> float:
    """The factor folded into the SIMD kernels' amplitudes (their gradient sets are not unit length)."""
    return _kerncache.load("intpoints").FACTOR[basis][dim - 1]


def unrolled_jacobian_kernel(dim: int, taps: int):
    """The per-point value-and-Jacobian kernel unrolled for ``dim`` and ``taps``, or None."""
    return _kerncache.load("jacobians").JAC_KERNELS.get((dim, taps))


def table_jacobian_kernel(dim: int, taps: int):
    """The 3-D value-and-Jacobian kernel over precombined hash tables, or None."""
    return _kerncache.load("jacobians").JAC_TABLE_KERNELS.get((dim, taps))
