"""Sparse Gabor convolution noise (Lagae et al. 2009): the lab's third family, between spectral and lattice noise.

Like lattice noise it is evaluated point by point from a counter-based hash
(any point, window or chunk gives the same bits, with no period short of
2**32 cells); like a spectral field its power spectrum is known in closed
form (:meth:`GaborNoise.expected_spectrum`) and can be shaped by sampling the
kernels' frequencies from a target.

- :class:`GaborNoise`: the noise (2-D, 3-D, still or moving kernels), at
  points and on grids; :func:`truncation_error` bounds the error of cutting
  the kernels.
- :func:`from_envelope`: the noise whose expected spectrum is a spectral
  field's (the envelope :func:`noiselab.synthesize` takes), by sampling the
  kernels' frequencies from it.
"""
from .noise import GaborNoise, truncation_error
from .spectra import from_envelope

__all__ = ["GaborNoise", "truncation_error", "from_envelope"]
