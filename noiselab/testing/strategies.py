"""Hypothesis strategies for noise parameters: shapes, bands, exponents, velocities, seeds.

This module imports hypothesis (the ``test`` extra), so ``noiselab.testing``
does not import it: ``from noiselab.testing import strategies`` in a test
suite that has hypothesis.

Examples
--------
>>> from hypothesis import given
>>> from noiselab.testing import strategies as nst
>>> @given(nst.shapes(ndim=2), nst.seeds())
... def test_shape(shape, seed):
...     assert len(shape) == 2 and min(shape) >= 16
>>> test_shape()
"""
from __future__ import annotations

from hypothesis import strategies as st

from .._core import check_int, check_real

__all__ = ["shapes", "bands", "exponents", "velocities", "seeds"]


def shapes(*, ndim=2, min_side=16, max_side=128, powers_of_two=False):
    """Field shapes with ``ndim`` axes of ``min_side`` to ``max_side`` samples (powers of two if asked).

    Examples
    --------
    >>> from hypothesis import find
    >>> find(shapes(ndim=3, powers_of_two=True), lambda s: True)   # the simplest
    (16, 16, 16)
    """
    ndim = check_int("ndim", ndim, lo=1, hi=4)
    lo = check_int("min_side", min_side, lo=4, hi=1 << 16)
    hi = check_int("max_side", max_side, lo=lo, hi=1 << 16)
    if powers_of_two:
        exps = [e for e in range(2, 17) if lo <= 1 << e <= hi]
        if not exps:
            raise ValueError(f"no power of two between min_side={lo} and max_side={hi}")
        side = st.sampled_from([1 << e for e in exps])
    else:
        side = st.integers(lo, hi)
    return st.tuples(*[side] * ndim)


def bands(width, *, min_octaves=1.0, lo_min=1.0):
    """Pass bands ``(lo, hi)`` in cycles/frame for frames ``width`` pixels wide: ``lo_min <= lo``, ``hi <= width / 2``, at least ``min_octaves`` wide.

    Examples
    --------
    >>> from hypothesis import find
    >>> find(bands(64), lambda b: b[1] > 16)
    (1.0, 17.0)
    """
    width = check_int("width", width, lo=8, hi=1 << 20)
    octs = check_real("min_octaves", min_octaves, lo=0.0, hi=20.0)
    lo_min = check_real("lo_min", lo_min, lo=0.0, lo_open=True, hi=width / 4.0)
    nyq = width / 2.0
    top = nyq / 2.0**octs
    if top < lo_min:
        raise ValueError(f"min_octaves={octs:g} does not fit between lo_min={lo_min:g} and Nyquist {nyq:g}")
    return st.floats(lo_min, top).flatmap(lambda lo: st.tuples(st.just(lo), st.floats(min(lo * 2.0**octs, nyq), nyq)))


def exponents(*, lo=0.0, hi=2.5):
    """Amplitude exponents (1 for 1/f), rounded to 0.05 so that failures read well.

    Examples
    --------
    >>> from hypothesis import find
    >>> find(exponents(), lambda e: e > 1)
    1.05
    """
    lo = check_real("lo", lo, lo=-10.0, hi=10.0)
    hi = check_real("hi", hi, lo=lo, hi=10.0)
    return st.integers(int(round(lo * 20)), int(round(hi * 20))).map(lambda k: k / 20.0)


def velocities(*, max_speed=2.0):
    """Velocities ``(vx, vy)`` in px/frame, each component a multiple of 1/4 within ``max_speed``.

    Examples
    --------
    >>> from hypothesis import find
    >>> find(velocities(), lambda v: v[0] < 0)
    (-0.25, 0.0)
    """
    top = check_real("max_speed", max_speed, lo=0.0, hi=1e3)
    comp = st.integers(-int(top * 4), int(top * 4)).map(lambda k: k / 4.0)
    return st.tuples(comp, comp)


def seeds():
    """Seeds for noiselab's generators (non-negative ints below 2**32).

    Examples
    --------
    >>> from hypothesis import find
    >>> find(seeds(), lambda s: s > 5)
    6
    """
    return st.integers(0, 2**32 - 1)
