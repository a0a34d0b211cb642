"""The integer hash (``hash="integer"``): an arithmetic hash of the lattice coordinates, no permutation table.

The lattice point ``(j_0, ..., j_{d-1})`` (each index already reduced modulo
its period, ``0 <= j_a < 2**32``) of output component ``c`` gets the 32-bit word

    ``h = mix32(key_c ^ (j_0 M_0) ^ ... ^ (j_{d-1} M_{d-1}))``  (products mod 2**32)

with odd per-axis multipliers ``M_a`` (:data:`MULT`), a seed-derived 32-bit
key per component, and ``mix32`` MurmurHash3's 32-bit finaliser less its last
xor-shift (a bijection: xor-shift, multiply, xor-shift, multiply; the top bits,
which carry the value and the gradient choice, are fully mixed). The products
are combined with xor, not added: a sum ``sum j_a M_a mod 2**32`` is a linear
form whose kernel holds short lattice vectors (about ``2**(32/d)`` cells
long: 256 cells in 4-D), so the field would repeat along an oblique
direction; xor is not linear over the integers and has no such lattice.

The value basis reads ``h`` as a signed integer, ``v = int32(h) / 2**31`` in
``[-1, 1)``. The gradient basis picks ``G[(h * L) >> 32]`` from a set of ``L``
unit gradients (:func:`gradient_set`): the top bits of ``h``. In 1-3-D the
set is fixed and small (the 2-D grid kernel selects it with bit tests
instead of a table gather): 1-D ``{+1, -1}``; 2-D the 8 unit vectors at
multiples of 45 degrees; 3-D Perlin's (2002) 16 cube-edge directions (12
distinct, 4 of them twice), normalised. From 4-D on, the instance's random
unit gradients.

There is no permutation table and so no table period: rows and columns of the
lattice are independent draws (up to the hash's quality; see
:mod:`noiselab.lab.hashes`), unlike Phillips' nested permutation, where every
full-period row is a permutation of one table. The default period is ``2**32``
cells per axis, the most a 32-bit coordinate holds.

This module holds the definition's data (:data:`MULT`, :func:`component_keys`,
:func:`gradient_set`); the hash itself (``mix32``, ``hash_value``,
``hash_index``) and the kernels that use it are compiled in :mod:`._jit`,
with every other lattice kernel (one source file, so numba's cache sees
every change).
"""
from __future__ import annotations

import numpy as np

# odd per-axis multipliers: the top 32 bits of a Weyl sequence in the golden ratio
MULT = np.array([((0x9E3779B97F4A7C15 * (a + 1)) % (1 << 64) >> 32) | 1 for a in range(32)], dtype=np.uint32)
INV_SQRT2 = 0.7071067811865476


def component_keys(draws):
    """The 32-bit keys of the components from the seed's 63-bit draws (their top 32 bits)."""
    return (np.asarray(draws, dtype=np.int64) >> 31).astype(np.uint32)


def _perlin3():
    """Perlin's (2002) 16 gradient directions of improved noise, as ``grad(h, x, y, z)`` picks them, normalised."""
    g = np.zeros((16, 3))
    for h in range(16):
        u = 0 if h < 8 else 1
        v = 1 if h < 4 else (0 if h in (12, 14) else 2)
        g[h, u] += -1.0 if h & 1 else 1.0
        g[h, v] += -1.0 if h & 2 else 1.0
    return g * INV_SQRT2


def gradient_set(d, table):
    """The unit gradients the integer hash picks from in ``d`` dimensions (``table``: the instance's, used from 4-D on).

    1-D ``[+1, -1]``; 2-D the axes then the diagonals, ``(1, 0), (-1, 0),
    (0, 1), (0, -1), (s, s), (-s, s), (s, -s), (-s, -s)`` with ``s = 1/sqrt 2``
    (index bit 0 flips x, bit 1 picks y or flips it); 3-D Perlin's 16.
    """
    if d == 1:
        return np.array([[1.0], [-1.0]])
    if d == 2:
        s = INV_SQRT2
        return np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0], [s, s], [-s, s], [s, -s], [-s, -s]])
    if d == 3:
        return _perlin3()
    return table  # the instance's own (read-only) table: one copy

