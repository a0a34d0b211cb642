"""The instruments: spectra, 1/f slopes, isotropy, motion energy, seams and contrast.

Every generator in noiselab (spectral and lattice) is checked with these
functions, and they work on any image, video or volume given as a numpy array.

Conventions: a video is ``(frames, height, width)``, x right along columns, y
down along rows; spatial frequency in cycles/frame (cycles/pixel x frame
width ``N``, as in ``noiselab.spectral`` and ``noiselab.snow``), temporal frequency in cycles/video; velocities
``(vx, vy)`` in pixels/frame with sign (+y down). The power spectrum is
normalised so that its sum is the field's variance (Parseval); see
:mod:`noiselab.analysis.spectrum`. Pass a precomputed :class:`PowerSpectrum`
(from :func:`power_spectrum` or :func:`video_spectrum`) to several analysers
to pay for one FFT.

Modules: ``spectrum`` (power, radial, spatio-temporal spectra, band energy),
``slope`` (1/f slope, octave energy), ``isotropy`` (orientation energy,
anisotropy, Ulichney's ring anisotropy), ``motion`` (motion plane, tent, best velocity, speed per band),
``seams`` (loop and tile seams), ``contrast`` (Michelson, RMS), ``quality`` (the
measures a noise is judged by: band leakage and aliasing per octave, slices of
volumes, envelope error, variance and range, periods, lattice-axis artefacts,
motion per band).

Examples
--------
>>> import numpy as np
>>> from noiselab import analysis
>>> img = np.random.default_rng(0).standard_normal((128, 128))
>>> abs(analysis.spectral_slope(img, (4, 32))) < 0.05   # white noise: flat
True
"""
from .contrast import michelson_contrast, rms_contrast, to_grey
from .isotropy import Orientation, RingAnisotropy, anisotropy, orientation_energy, ring_anisotropy
from .motion import (
    SpeedProfile,
    band_speeds,
    best_velocity,
    motion_energy,
    octave_bands,
    sheared_tent_energy,
    speed_profile,
    tent_energy,
    video_spectrum,
)
from .quality import (
    AxisArtefacts,
    BandLeakage,
    BandMotion,
    EnvelopeError,
    Period,
    SliceLeakage,
    ValueStatistics,
    axis_artefacts,
    band_leakage,
    detect_period,
    envelope_error,
    shell_slice_below,
    slice_leakage,
    tent_energy_per_band,
    value_statistics,
    variance_striping,
)
from ._common import noise_floor
from .seams import loop_seam, tile_seam
from .slope import OctaveEnergy, Slope, octave_energy, spectral_slope
from .spectrum import (
    PowerBand,
    PowerSpectrum,
    RadialSpectrum,
    SpatiotemporalSpectrum,
    band_energy,
    power_band,
    power_spectrum,
    radial_spectrum,
    spatiotemporal_spectrum,
)

__all__ = [
    "PowerSpectrum",
    "RadialSpectrum",
    "SpatiotemporalSpectrum",
    "power_spectrum",
    "radial_spectrum",
    "spatiotemporal_spectrum",
    "band_energy",
    "noise_floor",
    "PowerBand",
    "power_band",
    "Slope",
    "spectral_slope",
    "OctaveEnergy",
    "octave_energy",
    "Orientation",
    "orientation_energy",
    "anisotropy",
    "RingAnisotropy",
    "ring_anisotropy",
    "motion_energy",
    "tent_energy",
    "sheared_tent_energy",
    "best_velocity",
    "band_speeds",
    "speed_profile",
    "SpeedProfile",
    "octave_bands",
    "video_spectrum",
    "loop_seam",
    "BandLeakage",
    "band_leakage",
    "SliceLeakage",
    "slice_leakage",
    "shell_slice_below",
    "EnvelopeError",
    "envelope_error",
    "ValueStatistics",
    "value_statistics",
    "Period",
    "detect_period",
    "AxisArtefacts",
    "axis_artefacts",
    "variance_striping",
    "BandMotion",
    "tent_energy_per_band",
    "tile_seam",
    "michelson_contrast",
    "rms_contrast",
    "to_grey",
]
