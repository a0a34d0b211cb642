"""Motion Clouds (Leon, Vanzetta, Masson & Perrinet 2012) with MotionClouds' parameters, in noiselab's conventions.

A motion cloud is a Gaussian random field whose amplitude spectrum is
MotionClouds' ``envelope_gabor``: a log-Gabor radial band (``sf_0``,
``B_sf``) times an orientation band (``theta``, ``B_theta``) times a speed
band around the motion plane of ``(V_X, V_Y)`` (thickness ``B_V``). The
parameters mean exactly what they mean in MotionClouds; the differences are
the conventions of noiselab:

- output ``(frames, height, width)``: MotionClouds' ``z[x, y, t]`` is
  ``cloud[t, y, x]``, so its ``fx`` is frequency along the columns (x right)
  and its ``fy`` along the rows (y down); ``V_X > 0`` moves right, ``V_Y > 0``
  down, both in px/frame (``noiselab.analysis.best_velocity`` reads them back);
- the exact Hermitian synthesis of :func:`noiselab.synthesize` (MotionClouds
  takes ``ifftn(...).real``, which loses half of the power off the
  self-conjugate planes), complex Gaussian coefficients (MotionClouds' random
  phase times ``randn`` amplitude);
- unit variance over the ensemble (``normalize="expected"``) rather than
  MotionClouds' ``rectif`` to a Michelson range: :func:`to_display` sets the
  contrast in cd/m².
"""
from __future__ import annotations

import numpy as np

from .._core import check_memory, check_real, check_shape, renamed_parameters
from ..spectral import envelopes as E
from ..spectral import frequency_vectors, half_spectrum_shape, synthesize

__all__ = ["motion_cloud", "cloud_envelope"]


def cloud_envelope(shape, *, sf_0, B_sf, theta=0.0, B_theta=np.inf, V_X=0.0, V_Y=0.0, B_V=0.5, alpha=0.0,
                   loggabor=True):
    """MotionClouds' ``envelope_gabor`` on the half spectrum of ``shape`` (``(T, H, W)`` or ``(H, W)``), peak 1.

    A callable-free array for :func:`noiselab.synthesize`; the parameters
    are those of :func:`motion_cloud`. Proportional to
    ``MotionClouds.envelope_gabor(fx, fy, ft, ...)`` at every cell (the
    orientation factor is divided by its peak, see
    :func:`noiselab.spectral.envelopes.orientation`).

    Examples
    --------
    >>> env = cloud_envelope((16, 32, 32), sf_0=0.125, B_sf=0.05, V_X=1.0)
    >>> env.shape, float(env.max())
    ((16, 32, 17), 1.0)
    """
    shape = check_shape("shape", shape, ndim={2, 3})
    sf_0 = check_real("sf_0 (cycles/pixel)", sf_0, lo=0.0, hi=0.5, lo_open=True)
    if not (isinstance(B_sf, (int, float, np.floating)) and B_sf == np.inf):
        B_sf = check_real("B_sf (cycles/pixel)", B_sf, lo=0.0, lo_open=True, hi=1e100)
    alpha = check_real("alpha", alpha, lo=-8.0, hi=8.0)
    if not isinstance(loggabor, (bool, np.bool_)):
        raise TypeError(f"loggabor must be True or False, got {loggabor!r}")
    if isinstance(B_theta, (int, float, np.floating)) and B_theta == 0:
        raise ValueError("B_theta (radians) must be >= 1e-6 or np.inf (every orientation); got 0 (a single "
                         "orientation has no energy on a discrete grid but along the axes)")
    V_X = check_real("V_X (px/frame)", V_X, lo=-1e6, hi=1e6)
    V_Y = check_real("V_Y (px/frame)", V_Y, lo=-1e6, hi=1e6)
    full = shape if len(shape) == 3 else (1,) + shape
    check_memory(6 * 8 * int(np.prod(half_spectrum_shape(full), dtype=np.float64)), f"motion cloud of shape {shape}")
    wt, wy, wx = frequency_vectors(full)
    fr = E.radial_frequency(wy, wx) / (2 * np.pi)  # cycles/pixel, as MotionClouds' frequency_radius
    pos = fr > 0
    inv_f = np.where(pos, 1.0 / np.where(pos, fr, 1.0), 0.0)  # MotionClouds' clean_division: 1/0 -> 0
    env = E.orientation(wy, wx, theta=theta, B_theta=B_theta)
    if alpha != 0:
        env = env * np.where(pos, np.where(pos, fr, 1.0) ** -alpha, 0.0)
    if B_sf == np.inf:
        env = env * (inv_f if loggabor else 1.0)
    elif loggabor:
        env = env * inv_f * E.log_gabor(wy, wx, sf_0=sf_0, B_sf=B_sf)
    else:
        env = env * np.exp(-0.5 * (fr - sf_0) ** 2 / B_sf ** 2)
    if full[0] > 1:
        env = env * E.speed_envelope(wt, wy, wx, velocity_yx=(V_Y, V_X), B_V=B_V)
    else:
        E.speed_envelope(wt, wy, wx, velocity_yx=(V_Y, V_X), B_V=B_V)  # checks the arguments all the same
    env = np.broadcast_to(env, full[:-1] + (full[-1] // 2 + 1,))
    top = float(env.max())
    if not top > 0:
        raise ValueError(f"the envelope is 0 on every cell of shape {shape}: sf_0={sf_0:g} cycles/pixel with "
                         f"B_sf={B_sf:g} selects no frequency of the grid")
    env = env / top
    return env if len(shape) == 3 else env[0]


@renamed_parameters(seed="rng")
def motion_cloud(shape, *, sf_0, B_sf, theta=0.0, B_theta=np.inf, V_X=0.0, V_Y=0.0, B_V=0.5, rng=None,
                 alpha=0.0, loggabor=True, dtype=np.float32, normalize="expected", workers=None):
    """A Motion Cloud: MotionClouds' ``envelope_gabor`` with random phases, ``(frames, height, width)``.

    Parameters
    ----------
    shape : (T, H, W) or (H, W)
        Frames, height, width (a 2-D shape: one still frame, no speed band).
    sf_0 : float
        Peak spatial frequency, cycles/pixel, in ``(0, 0.5]``
        (``display.cycles_per_pixel(cpd)`` from cycles/deg).
    B_sf : float
        Radial bandwidth, cycles/pixel, > 0 (``np.inf``: no band, a 1/f
        spectrum with ``loggabor``). From a bandwidth in octaves (FWHM):
        ``B_sf_from_octaves(sf_0=sf_0, sf_bandwidth_octaves=...)``.
    theta : float
        Mean orientation of the wave vector, radians (0: waves along x,
        vertical stripes; y is down, so a positive ``theta`` turns the wave
        vector, and the stripes, clockwise on the screen). It is PsychoPy's
        ``ori`` of a grating (degrees, 0 vertical bars, clockwise) in
        radians: ``theta = np.radians(ori)``.
    B_theta : float
        Orientation bandwidth, radians, ``>= 1e-6``; ``np.inf`` (default):
        isotropic. From a half width at half height in degrees:
        ``B_theta_from_hwhm(orientation_hwhm_deg=...)``.
    V_X, V_Y : float
        Velocity of the motion plane, px/frame (x right, y down), within +-1e6
        (``display.px_per_frame(deg_per_s)``).
    B_V : float
        Speed bandwidth, px/frame, >= 0 (0: a frozen texture, ``np.inf``:
        every frame independent).
    rng : int, numpy.random.Generator or None
    alpha : float
        Extra ``1/f**alpha`` colour (MotionClouds' ``envelope_color``), default 0.
    loggabor : bool
        MotionClouds' ``loggabor``: True (default) the log-Gabor radial band
        times ``1/f``; False a Gaussian ring of centre ``sf_0`` and width ``B_sf``.
    dtype : float32 or float64
    normalize : {"expected", "sample", None}
        As in :func:`noiselab.synthesize`: default unit variance over the ensemble.
    workers : int, optional
        scipy.fft's threads (the output does not depend on it).

    Returns
    -------
    ndarray
        Shape ``shape``, zero mean.

    Raises
    ------
    ValueError
        A parameter outside its range (named with its unit), or an envelope
        with no energy on the grid.

    Notes
    -----
    ``sf_0`` is where the power *per octave* peaks; the power per frequency
    cell peaks at ``sf_0 exp(-s**2)`` with ``s = ln((sf_0 + B_sf) / sf_0)``
    (0.848 ``sf_0`` for ``B_sf = sf_0 / 2``), and a moving cloud's spatial
    spectrum (summed over the frames) one factor ``exp(s**2 / 2)`` higher
    (``noiselab.stimuli.bandwidth`` derives these; ``tests/test_stimuli.py``
    measures them on the envelope).

    ``tests/test_stimuli.py`` compares the power spectrum averaged over 24
    seeds with ``MotionClouds.envelope_gabor(...)**2`` for the same
    parameters (MotionClouds from PyPI) and reads ``(V_X, V_Y)`` back with
    :func:`noiselab.analysis.best_velocity`.

    Examples
    --------
    >>> import numpy as np
    >>> from noiselab import Display
    >>> d = Display(32.0, frame_rate=60.0)
    >>> z = motion_cloud((32, 64, 64), sf_0=d.cycles_per_pixel(4.0), B_sf=0.05, theta=np.pi / 4,
    ...                  B_theta=np.radians(15), V_X=d.px_per_frame(1.875), rng=0)
    >>> z.shape, z.dtype
    ((32, 64, 64), dtype('float32'))
    """
    env = cloud_envelope(shape, sf_0=sf_0, B_sf=B_sf, theta=theta, B_theta=B_theta, V_X=V_X, V_Y=V_Y, B_V=B_V,
                         alpha=alpha, loggabor=loggabor)
    shape = check_shape("shape", shape, ndim={2, 3})
    return synthesize(shape, env, rng=rng, amplitude_distribution="rayleigh", dtype=dtype, normalize=normalize,
                      workers=workers)
