"""The lattice's counter-based integer hash, as a public module for the other generators.

:mod:`noiselab.gabor` draws its impulses from the same 32-bit hash that the
lattice's ``hash="integer"`` uses (:mod:`._inthash` describes it), rather
than from a second hash of its own:

- :func:`mix32`: MurmurHash3's 32-bit finaliser less its last xor-shift, a
  bijection of ``uint32`` (compiled; callable from numba kernels and from
  Python, with the same bits);
- :func:`prime`: an axis's share of a cell's word, ``(j * M_a) mod 2**32``;
- :data:`MULT`: the odd per-axis multipliers ``M_a``.

A cell ``(j_0, ..., j_{d-1})`` of a seed-derived key gets the word
``mix32(key ^ prime(j_0, MULT[0]) ^ ... ^ prime(j_{d-1}, MULT[d-1]))``.

These are the lattice engine's own compiled functions (``noiselab.lattice._jit``),
re-exported, not copies. numba's ``cache=True`` keys a kernel on its own source
file: a kernel of another module that calls them is recompiled when its own
file changes, not when the engine's does, so a change to ``mix32`` is a change
of every hashing generator's bits (and of the package version that states it). A caller's
compiled file records a fingerprint of these functions' outputs
(``noiselab.gabor._kernels.HASH_FINGERPRINT``), checked by the tests, so changing the hash
means editing that file too, and numba recompiles its kernels.

Examples
--------
>>> from noiselab.lattice.hashing import mix32, prime, MULT
>>> int(mix32(0)), int(mix32(1)) != int(mix32(2))
(0, True)
>>> int(prime(3, MULT[0])) == (3 * int(MULT[0])) % 2**32
True
"""
from ._inthash import MULT
from ._jit import mix32, prime

__all__ = ["mix32", "prime", "MULT"]
