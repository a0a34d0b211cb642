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
"""
from __future__ import annotations

import numpy as np
from numba.extending import overload

from . import _jit as jit
from ._inthash import block_prefix, hash_index, hash_value

__all__ = ["grid2d"]

_U32 = np.uint32
_NO_PERM = np.empty(0, np.int64)
_NO_VALUES = np.empty((2, 0))


@overload(jit.int_row_values)
def _int_row_values(ext, at, word, words, start, m):
    def impl(ext, at, word, words, start, m):
        for l in range(m):
            ext[at + l] = hash_value(_U32(word ^ words[start + l]))
    return impl


@overload(jit.int_row_gradients)
def _int_row_gradients(ext, at0, at1, word, words, start, m, grads):
    def impl(ext, at0, at1, word, words, start, m, grads):
        n = grads.shape[0]
        for l in range(m):
            g = hash_index(_U32(word ^ words[start + l]), n)
            ext[at0 + l] = grads[g, 0]
            ext[at1 + l] = grads[g, 1]
    return impl


def grid2d(lat0, off0, pos0, wa0, wb0, lat1, off1, base1, dense1, wa1, wb1, scales, key, mult, grads, basis, absval,
           out64, out32, nq, tile):
    """:func:`._jit.grid2d` with the integer hash: one component of a 2-D grid, every octave fused.

    The first eleven arguments are :func:`._jit.pack_grid2d`'s (lattice
    indices reduced modulo each octave's period, kept whole: packed with
    ``n = 2**32``); ``key`` is the component's ``(1,)`` uint32 key, ``mult``
    the axis multipliers and ``grads`` the gradient set (``L``, 2). The rest
    as for :func:`._jit.grid2d`.
    """
    words0 = block_prefix(key, lat0, mult[0], True, key[0])
    words1 = block_prefix(key, lat1, mult[1], True, _U32(0))
    jit.grid2d(words0, off0, pos0, wa0, wb0, words1, off1, base1, np.zeros(dense1.shape[0], np.bool_), wa1, wb1,
               scales, _NO_PERM, _NO_VALUES, grads, basis, absval, out64, out32, nq, tile)
