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
  kernels' frequencies from it; :func:`power_law_layers` and
  :func:`render_layers`: a power law over many octaves, octave by octave
  (kernels sized to their wavelengths).
- :func:`gabor_snow`: :func:`noiselab.snow`'s falling snow with no period,
  any window of any frame; :func:`snow_layers` are its moving-kernel noises;
  :func:`motion_cloud_noise`: a Motion Cloud (velocity and its bandwidth) the same way.
"""
from .noise import GaborNoise, truncation_error
from .snow import OPACITY_SIGMAS, gabor_snow, motion_cloud_noise, snow_layers, snow_opacity
from .spectra import from_envelope, power_law_layers, render_layers

__all__ = ["GaborNoise", "truncation_error", "from_envelope", "power_law_layers", "render_layers", "gabor_snow",
           "snow_layers", "snow_opacity", "motion_cloud_noise", "OPACITY_SIGMAS"]
