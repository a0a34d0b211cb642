"""Spectral assertions for test suites: ``import noiselab.testing`` as you would ``numpy.testing``.

Each ``assert_*`` function measures a property a noise (or any image, video
or volume given as a numpy array) promises -- a power-law spectrum, a band
limit, isotropy, motion along a velocity or on the falling-snow tent, a
seamless tile or loop, no lattice-axis artefacts -- with the instruments of
:mod:`noiselab.analysis`. It raises ``AssertionError`` with a message that
says what was measured, what was expected, over which band, and the
tolerance with how it was derived; on success it returns the measurement.

Where a property is a sampling estimate (the power-law exponent, the
orientation modulation, the axis excess, a seam step), the tolerance follows
from the estimator's sampling law for the field at hand (independent
periodogram cells, exponential for a Gaussian field) so that a field truly
holding the property fails with probability ``false_alarm`` (default 1e-3;
``benchmarks/bench_testing.md`` counts the failures over 200 seeds). Where it
is a deterministic fraction of the spectrum (a band limit, energy on a motion
plane or tent), the threshold is a stated fraction. A velocity
(``assert_velocity``) is measured with its standard errors and judged in
velocity units (px/frame, or deg/s through a ``Display``); an orientation
(``assert_orientation``) in degrees and a centre spatial frequency
(``assert_centre_frequency``) in cycles/pixel or cycles/deg, each with its
standard error.

``noiselab.testing.strategies`` holds hypothesis strategies for noise
parameters (it imports hypothesis, a test extra, so it is not imported here).

Examples
--------
>>> import noiselab
>>> from noiselab.testing import assert_power_law, assert_isotropic
>>> img = noiselab.spectral_noise((128, 128), exponent=1.0, rng=3)
>>> fit = assert_power_law(img, 1.0)
>>> abs(fit.exponent - 1.0) <= fit.tolerance
True
"""
from .motion import MotionCheck, assert_motion, assert_tent
from .orientation import FrequencyCheck, OrientationCheck, assert_centre_frequency, assert_orientation
from .seams import SeamCheck, assert_seamless
from .velocity import VelocityCheck, assert_velocity
from .spectra import (
    AxisCheck,
    BandLimitCheck,
    IsotropyCheck,
    PowerLawCheck,
    assert_band_limited,
    assert_isotropic,
    assert_no_axis_artefacts,
    assert_power_law,
)

__all__ = [
    "assert_power_law",
    "PowerLawCheck",
    "assert_band_limited",
    "BandLimitCheck",
    "assert_isotropic",
    "IsotropyCheck",
    "assert_no_axis_artefacts",
    "AxisCheck",
    "assert_motion",
    "assert_tent",
    "MotionCheck",
    "assert_velocity",
    "VelocityCheck",
    "assert_orientation",
    "OrientationCheck",
    "assert_centre_frequency",
    "FrequencyCheck",
    "assert_seamless",
    "SeamCheck",
]
