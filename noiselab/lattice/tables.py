"""The random tables of lattice noise and the hashes built from them.

:func:`draw_tables` draws, from one generator and in a fixed order, what
Phillips' construction needs (the positive and negative value tables, the
unit gradients, one permutation per output component) and, for the integer
hash, a 32-bit key per component; :func:`signed_values` arranges the value
tables as the two alternations read them; :func:`period_masks` is the
kernels' fast form of the period; :func:`frozen` makes the one read-only
copy of a table that every path reads.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import _inthash as inthash

__all__ = ["Tables", "draw_tables", "signed_values", "period_masks", "axis_multipliers", "int_gradients", "frozen"]


class Tables(NamedTuple):
    """What :func:`draw_tables` draws."""

    positive: np.ndarray    # (n,) on (0, 1]
    negative: np.ndarray    # (n,) on [-1, 0)
    gradients: np.ndarray   # (n, dim_in) unit vectors
    keys: np.ndarray        # (dim_out,) uint32 integer-hash keys (zeros for the table hash), read-only
    perms: np.ndarray       # (dim_out, n) int64 permutations, read-only


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
    return Tables(positive, negative, np.ascontiguousarray(gradients), frozen(keys), frozen(perms))


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


def period_masks(period):
    """``period - 1`` where the period is a power of two (reduction by a mask), else -1 (by ``mod``)."""
    return np.where((period & (period - 1)) == 0, period - 1, -1).astype(np.int64)


def axis_multipliers(dim_in):
    """The integer hash's odd multiplier per axis."""
    return np.ascontiguousarray(inthash.MULT[:dim_in])


def int_gradients(dim_in, gradients):
    """The integer hash's gradient set (fixed and small in 1-3-D; the random unit gradients from 4-D on)."""
    return inthash.gradient_set(dim_in, gradients)


def frozen(table):
    """A read-only copy of ``table`` whose flag cannot be set back: a view of an immutable ``bytes`` buffer.

    The permutations and integer-hash keys are frozen, so that points, grids
    and every other path read one copy that cannot change after construction.

    Examples
    --------
    >>> p = frozen(np.arange(4))
    >>> p.flags.writeable
    False
    """
    table = np.ascontiguousarray(table)
    return np.frombuffer(table.tobytes(), dtype=table.dtype).reshape(table.shape)
