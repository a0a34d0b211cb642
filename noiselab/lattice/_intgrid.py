"""The integer hash in the fused 2-D grid kernel (:func:`._jit.grid2d`): its lattice rows and its words.

The fused kernel is shared by both hashes; only the step that fills one
lattice row's values (or gradient components) against a tile's axis-1 taps
differs. The integer hash's row is ``hash_value(w0 ^ w1[l])`` (or the gradient
``grads[hash_index(w0 ^ w1[l])]``) with the words ``w0 = key ^ (j_0 M_0)`` of
the row and ``w1[l] = j_1 M_1`` of the taps (:func:`grid2d` makes them with
:func:`._inthash.block_prefix`, as the general path's ``int_prefix`` does), so
every lattice point gets the bits ``block_values`` / ``block_gradients`` give it
on the general path. :mod:`._inthash` imports :mod:`._jit`, so the kernel
cannot call it directly: :mod:`._jit` declares the two row functions
(:func:`._jit.int_row_values`, :func:`._jit.int_row_gradients`) and this
module gives numba their implementations (``@overload``; the integer-hash
variants of the kernel are compiled only after this module is imported,
through :mod:`._compiled`). Each row is one loop of 32-bit integer arithmetic
that LLVM vectorises, computed once per lattice row and tile, in cache.
numba's on-disk cache of the kernel (keyed by ``_jit.py``) does not notice
an edit of this file: clear ``NUMBA_CACHE_DIR`` after one.
"""
from __future__ import annotations

import numba as nb
import numpy as np
from numba.extending import overload

from . import _jit as jit
from ._inthash import block_prefix, hash_index, hash_value

__all__ = ["grid2d"]

_U32 = np.uint32
_U64 = np.uint64
_NO_PERM = np.empty(0, np.int64)
_NO_VALUES = np.empty((2, 0))


@overload(jit.int_row_values)
def _int_row_values(ext, at, word, words, start, m):
    def impl(ext, at, word, words, start, m):
        # unsigned offsets: no negative-index wrap, so the loop vectorises with plain loads and stores
        dst = _U64(at)
        src = _U64(start)
        for l in range(_U64(m)):
            ext[dst + l] = hash_value(_U32(word ^ words[src + l]))
    return impl


@nb.njit(cache=True, nogil=True, inline="always")
def _pick8(g, t0, t1, t2, t3, t4, t5, t6, t7):
    """``(t0, ..., t7)[g]`` for ``0 <= g < 8`` by selects on g's bits (a vectorised loop needs no gather)."""
    odd = (g & 1) != 0
    p01 = t1 if odd else t0
    p23 = t3 if odd else t2
    p45 = t5 if odd else t4
    p67 = t7 if odd else t6
    q0 = p23 if (g & 2) != 0 else p01
    q1 = p67 if (g & 2) != 0 else p45
    return q1 if g >= 4 else q0


@overload(jit.int_row_gradients)
def _int_row_gradients(ext, at0, at1, word, words, start, m, grads):
    def impl(ext, at0, at1, word, words, start, m, grads):
        # the 2-D set's 8 gradients held in registers and picked by selects: a gather from the table
        # (which LLVM cannot prove apart from ext) kept the loop scalar, at about three times the cost
        x0 = grads[0, 0]; x1 = grads[1, 0]; x2 = grads[2, 0]; x3 = grads[3, 0]
        x4 = grads[4, 0]; x5 = grads[5, 0]; x6 = grads[6, 0]; x7 = grads[7, 0]
        y0 = grads[0, 1]; y1 = grads[1, 1]; y2 = grads[2, 1]; y3 = grads[3, 1]
        y4 = grads[4, 1]; y5 = grads[5, 1]; y6 = grads[6, 1]; y7 = grads[7, 1]
        dst0 = _U64(at0)
        dst1 = _U64(at1)
        src = _U64(start)
        for l in range(_U64(m)):
            g = hash_index(_U32(word ^ words[src + l]), 8)
            ext[dst0 + l] = _pick8(g, x0, x1, x2, x3, x4, x5, x6, x7)
            ext[dst1 + l] = _pick8(g, y0, y1, y2, y3, y4, y5, y6, y7)
    return impl


def grid2d(lat0, off0, pos0, wa0, wb0, lat1, off1, base1, dense1, wa1, wb1, scales, key, mult, grads, basis, absval,
           out64, out32, nq, tile):
    """:func:`._jit.grid2d` with the integer hash: one component of a 2-D grid, every octave fused.

    The first eleven arguments are both axes packed by :func:`._jit.pack_axis` (lattice
    indices reduced modulo each octave's period, kept whole: packed with
    ``n = 2**32``); ``key`` is the component's ``(1,)`` uint32 key, ``mult``
    the axis multipliers and ``grads`` the gradient set (``L``, 2). The rest
    as for :func:`._jit.grid2d`.
    """
    assert grads.shape == (8, 2)  # the 2-D gradient set (:func:`._inthash.gradient_set`), picked by selects
    words0 = block_prefix(key, lat0, mult[0], True, key[0])
    words1 = block_prefix(key, lat1, mult[1], True, _U32(0))
    jit.grid2d(words0, off0, pos0, wa0, wb0, words1, off1, base1, np.zeros(dense1.shape[0], np.bool_), wa1, wb1,
               scales, _NO_PERM, _NO_VALUES, grads, basis, absval, out64, out32, nq, tile)
