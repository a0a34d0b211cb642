"""Stimuli in physical units: degrees, seconds, cd/m² and contrast on a described display.

- :class:`Display`: a screen (pixels per degree, frame rate, luminance range
  and gamma law or measured table, bit depth) and the unit conversions
  between what an experiment states and what the generators take;
- :func:`to_display`: a field shown at a mean luminance and an RMS or
  Michelson contrast, as integer display values (seeded dithering), clipped
  at ``clip`` standard deviations if asked, through an aperture if given;
- :func:`circular_aperture`, :func:`raised_cosine_aperture`,
  :func:`gaussian_aperture`: the windows a stimulus is seen through, in
  degrees, blending to the mean luminance;
- :func:`phase_scramble`, :func:`amplitude_swap`: an image's amplitude
  spectrum with random or another image's phases;
- :func:`motion_cloud`: MotionClouds' ``envelope_gabor`` with its parameters,
  in noiselab's ``(frames, height, width)``;
- :func:`trial_seeds`: one recorded seed per trial of an experiment,
  derived from its seed (the seeds of ``noiselab stimulus --trials``);
- :func:`B_sf_from_octaves`, :func:`B_theta_from_hwhm` and their inverses:
  bandwidths as papers state them (octaves FWHM, degrees HWHM) to and from
  MotionClouds' ``B_sf`` and ``B_theta``.

Layer 3 (beside ``fields`` and ``geometry``): built on ``spectral``; a
generator, so it measures what it needs itself rather than through
``noiselab.analysis``.
"""
from .aperture import circular_aperture, gaussian_aperture, raised_cosine_aperture
from .bandwidth import B_sf_from_octaves, B_theta_from_hwhm, hwhm_from_B_theta, octaves_from_B_sf
from .cloud import cloud_envelope, motion_cloud
from .contrast import CONTRAST_KINDS, DisplayReport, luminance_for, to_display
from .display import Display
from .scramble import amplitude_swap, phase_scramble
from .trials import trial_seeds

__all__ = ["Display", "to_display", "DisplayReport", "luminance_for", "CONTRAST_KINDS", "phase_scramble",
           "amplitude_swap", "motion_cloud", "cloud_envelope", "circular_aperture", "raised_cosine_aperture",
           "gaussian_aperture", "B_sf_from_octaves", "octaves_from_B_sf", "B_theta_from_hwhm", "hwhm_from_B_theta",
           "trial_seeds"]
