"""The random tables of lattice noise and the hashes built from them.

:func:`draw_tables` draws, from one generator and in a fixed order, what
Phillips' construction needs (the positive and negative value tables, the
unit gradients, one permutation per output component) and, for the integer
hash, a 32-bit key per component; :func:`signed_values` arranges the value
tables as the two alternations read them; :func:`period_masks` and
:func:`doubled_permutations` are the kernels' fast forms of the period and
permutation; :func:`hash_tables` precombines the nested permutation with
the values (or gradients) for the 3-D scattered kernels, and
:func:`cached_hash_tables` keeps them on a noise until its tables change.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ._compiled import inthash

__all__ = ["Tables", "draw_tables", "signed_values", "doubled_permutations", "period_masks", "axis_multipliers",
           "int_gradients", "hash_tables", "cached_hash_tables"]


class Tables(NamedTuple):
    """What :func:`draw_tables` draws."""

    positive: np.ndarray    # (n,) on (0, 1]
    negative: np.ndarray    # (n,) on [-1, 0)
    gradients: np.ndarray   # (n, dim_in) unit vectors
    keys: np.ndarray        # (dim_out,) uint32 integer-hash keys (zeros for the table hash)
    perms: np.ndarray       # (dim_out, n) int64 permutations


def draw_tables(rng, n, dim_in, dim_out, integer_hash):
    """The random tables of one noise, drawn from ``rng`` in a fixed order.

    The order (values, gradients, keys, permutations, components last) is
    part of the seed's meaning: the first components of a ``dim_out=k``
    noise equal those of a smaller ``dim_out``, and the integer hash's keys
    are drawn only for it, so the table hash's draws are unchanged.

    Examples
    --------
    >>> t = draw_tables(np.random.default_rng(0), 8, 2, 3, False)
    >>> t.perms.shape, t.gradients.shape, bool((t.positive > 0).all() and (t.negative < 0).all())
    ((3, 8), (8, 2), True)
    """
    positive = 1.0 - rng.random(n)          # (0, 1]
    negative = rng.random(n) - 1.0          # [-1, 0)
    gradients = rng.standard_normal((n, dim_in))
    norms = np.linalg.norm(gradients, axis=1, keepdims=True)
    gradients /= np.where(norms > 0, norms, 1.0)
    # the integer hash's per-component 64-bit keys (before the permutations, so that a smaller dim_out gets
    # the first keys)
    keys = inthash.component_keys(rng.integers(0, 1 << 63, size=dim_out, dtype=np.int64)) \
        if integer_hash else np.zeros(dim_out, np.uint32)
    perms = np.stack([rng.permutation(n) for _ in range(dim_out)]).astype(np.int64)
    return Tables(positive, negative, np.ascontiguousarray(gradients), keys, perms)


def signed_values(positive, negative, alternation):
    """The ``(2, n)`` value table the kernels read, row by the sign's parity (see ``LatticeNoise``'s ``alternation``).

    ``"table"``: both rows interleave the tables (even entries positive, odd
    negative), so the permutation alone picks the sign. ``"lattice"``: row 0
    positive, row 1 negative, picked by the lattice point's parity.
    """
    if alternation == "table":
        interleaved = np.where(np.arange(positive.shape[0]) % 2 == 0, positive, negative)
        return np.stack([interleaved, interleaved])
    return np.stack([positive, negative])


def doubled_permutations(perms):
    """``[P, P]`` per component as uint64, so that ``P2[P[i] + j]`` needs no ``mod n`` for ``j < n``."""
    return np.ascontiguousarray(np.concatenate([perms, perms], axis=1), dtype=np.uint64)


def period_masks(period):
    """``period - 1`` where the period is a power of two (reduction by a mask), else -1 (by ``mod``)."""
    return np.where((period & (period - 1)) == 0, period - 1, -1).astype(np.int64)


def axis_multipliers(dim_in):
    """The integer hash's odd multiplier per axis."""
    return np.ascontiguousarray(inthash.MULT[:dim_in])


def int_gradients(dim_in, gradients):
    """The integer hash's gradient set (fixed and small in 1-3-D; the random unit gradients from 4-D on)."""
    return inthash.gradient_set(dim_in, gradients)


def hash_tables(perms, values, gradients, basis):
    """Precombined hash tables for the 3-D scattered kernels: ``(H2, VL, G)``.

    ``H2[c, q0 * n + q1] = P_c[(P_c[q0] + q1) mod n]`` (the first two
    nested levels in one load), plus, for value noise (``basis == 0``), the
    parity row offset ``S * ((q0 + q1 + h) & 1)``; ``VL[c, r * S + x] =
    values[(r + x) & 1, P_c[x mod n]]`` for ``x < S = 2n + 4``: the last
    level folded into the values, and run on past 2n so that the last
    axis's taps ``x, x + 1, ...`` are contiguous without a wrap (the last
    axis's period must be n). ``G[c, a * S + x] = gradients[P_c[x mod n], a]``
    likewise (``basis == 1``).

    Examples
    --------
    >>> perms = np.array([[1, 0, 3, 2]])
    >>> H2, VL, G = hash_tables(perms, np.ones((2, 4)), np.ones((4, 3)), 1)
    >>> H2.shape, G.shape, H2.dtype.name
    ((1, 16), (1, 36), 'uint16')
    """
    dim_out, n = perms.shape
    S = 2 * n + 4
    q = np.arange(n)
    x = np.arange(S)
    H2 = np.empty((dim_out, n * n), dtype=np.uint16)
    VL = np.zeros((dim_out, 2 * S))
    G = np.zeros((dim_out, gradients.shape[1] * S))
    for c, P in enumerate(perms):
        h = P[(P[q][:, None] + q[None, :]) % n]
        if basis == 0:
            h = h + S * ((q[:, None] + q[None, :] + h) & 1)
            for r in range(2):
                VL[c, r * S:(r + 1) * S] = values[(r + x) & 1, P[x % n]]
        else:
            G[c] = gradients[P[x % n]].T.ravel()
        H2[c] = h.ravel()
    return H2, VL, G


def cached_hash_tables(noise, basis):
    """:func:`hash_tables` of ``noise``'s current tables, kept on it until they change.

    Rebuilt whenever the permutations, values or gradients change (they are
    public attributes), so the tables never go stale.
    """
    src = noise.values if basis == 0 else noise.gradients
    key = (basis, noise.perms.tobytes(), src.tobytes())
    cache = getattr(noise, "_tables_cache", None)
    if cache is not None and cache[0] == key:
        return cache[1]
    tables = hash_tables(noise.perms, noise.values, noise.gradients, basis)
    noise._tables_cache = (key, tables)
    return tables
