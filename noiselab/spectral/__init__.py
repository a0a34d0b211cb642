"""Spectral synthesis on the real-FFT half spectrum, and its envelopes.

- :func:`synthesize`: envelope x random amplitude x random phase, exact
  conjugacy on the self-conjugate planes, one ``irfftn``.
- :func:`spectral_noise`: isotropic band-limited ``1/f**exponent`` noise in 1, 2 or 3-D.
- :mod:`noiselab.spectral.envelopes`: motion plane (Eq. 2.8), parallel and
  non-parallel optical snow (Eq. 2.12, 2.14), tent (Eq. 3.3), thickened tent
  (3.2.1), sheared tent (Eq. 4.2), annulus band (3.2.2), power law (3.2.3).
- :func:`frequency_vectors`: broadcast angular frequency vectors (rad/sample).
- :mod:`noiselab.spectral.plan` (internal interface shared by the in-memory
  and dask paths): the noise plan, the Hermitian gain, the pruned
  leading-axis inverse FFT.

Units: envelopes take angular frequencies in rad/sample (rad/pixel, rad/frame)
in ``[-pi, pi]``; public band limits are in cycles/frame (cycles per frame
width) unless a name says otherwise (``annulus``'s ``band_cycles_per_sample``).
"""
from . import envelopes
from .frequencies import frequency_vectors, half_spectrum_shape
from .synthesis import AMPLITUDES, draw_coefficients, hermitian_plane, spectral_noise, synthesize

__all__ = [
    "synthesize",
    "spectral_noise",
    "frequency_vectors",
    "half_spectrum_shape",
    "hermitian_plane",
    "draw_coefficients",
    "envelopes",
    "AMPLITUDES",
]
