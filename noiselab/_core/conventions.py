"""The conventions table: every parameter word of noiselab's public API, what it means and how it is passed.

Data only. One entry per word: its meaning, its unit, its type, its default
and whether it is keyword-only. A word means one thing everywhere; where a
function must differ (a fixed picture's ``rng``, snow's refusal to alias),
``per_function`` names it with ``(default, keyword_only)`` and ``note`` says
why. ``default=VARIES`` marks a word whose default is each function's own (a
size, a shape); ``keyword_only=None`` a word taken either way (the data a
function works on). ``tests/test_conventions.py`` holds every public
signature to this table, and ``docs/guide/conventions.md`` shows it.

Conventions behind the words:

- random state: ``rng`` as SPEC 7 (an int, a ``numpy.random.Generator`` or
  ``None``; default ``None``, fresh entropy), as scipy and scikit-image;
- ``workers`` as scipy.fft, ``axis``/``axes``/``dtype`` as numpy;
- per-axis pairs in array order, like shapes: ``(y, x)``, said in the name
  (``direction_yx``, ``pan_yx``, ``velocity_yx``), never ``(x, y)``;
- one unit per kind of quantity: spatial frequency in cycles/frame (cycles per
  width of the last axis), tent constants in rad/frame, speeds in px/frame;
  another unit is said in the name (``band_cycles_per_degree``,
  ``band_cycles_per_sample``);
- ``exponent`` is always the *amplitude* exponent: amplitude ~ f**-exponent,
  power ~ f**(-2 exponent) (power slope -2 is ``exponent=1``).
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

__all__ = ["Word", "WORDS", "REQUIRED", "VARIES"]

REQUIRED = "required"   # no default: the caller must pass it
VARIES = "varies"       # each function's own default (see the word's note)


class Word(NamedTuple):
    meaning: str
    unit: str = ""
    type: str = ""
    default: object = VARIES
    keyword_only: bool | None = None
    per_function: dict = {}
    note: str = ""


WORDS = {
    'a': Word(
        'Normals (any length), broadcastable against each other.',
        unit='',
        type='array_like (..., 3)',
        default=REQUIRED,
        keyword_only=False),
    'absval': Word(
        'Sum ``|noise|`` (turbulence): ``b = abs``.',
        unit='',
        type='bool, default False',
        default=False,
        keyword_only=True),
    'alpha': Word(
        'Opacity in [0, 1] (from :func:`noiselab.snowfall.snow`).',
        unit='',
        type='ndarray, (T, H, W) or (H, W)',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'alternation': Word(
        'How the negative and positive tables alternate.',
        unit='',
        type='{"table", "lattice"}, default "table"',
        default='table',
        keyword_only=True),
    'amount': Word(
        'Displacement scale (input units per unit of ``warp_noise``), per axis if a sequence.',
        unit='',
        type='float or sequence of dim_in floats, default 1',
        default=1.0,
        keyword_only=False),
    'amplitude': Word(
        ("A scale factor on a field's output: displacement in the mesh's or curve's input units, a flow's speed, "
         "the noise's value scale."),
        unit='output units',
        type='float',
        default=VARIES,
        keyword_only=None,
        note=("each geometry helper's default suits its figure (0.1 on a unit circle, 0.5 for a surface); "
              "positional after field in the geometry functions (Phillips' a, F, phi)")),
    'amplitude_distribution': Word(
        ("The law of the random amplitude a of each spectral coefficient (E[a**2] = 1): 'uniform' on [0, sqrt(3)),"
         " 'rayleigh' (complex Gaussian coefficients: a Gaussian field) or 'fixed' (a = 1)."),
        unit='',
        type="{'uniform', 'rayleigh', 'fixed'}",
        default='uniform',
        keyword_only=True,
        per_function={'noiselab.spectral_noise': ('rayleigh', True),
                      'noiselab.spectral.draw_coefficients': ('uniform', False)},
        note=('spectral_noise promises a Gaussian field (Rayleigh); snow follows the thesis (uniform); '
              'draw_coefficients keeps its third place by position')),
    'amplitude_from': Word(
        'Real arrays of one shape.',
        unit='',
        type='array_like',
        default=REQUIRED,
        keyword_only=False),
    'argv': Word(
        'Command-line arguments (None: sys.argv[1:]).',
        unit='',
        type='',
        default=None,
        keyword_only=False),
    'aperture': Word(
        ('A window of weights in [0, 1] (e.g. ``circular_aperture``) that broadcasts against the field: the '
         'stimulus blends to the mean luminance where it is 0, and its contrast is stated inside it.'),
        unit='',
        type='array_like or None',
        default=None,
        keyword_only=True),
    'arithmetic': Word(
        ('The floating type a sum is computed in: "float64" (the result rounded once to the output dtype) or '
         '"float32" (faster, float32 rounding, float32 output; only where a float32 kernel exists, a ValueError '
         'elsewhere).'),
        unit='',
        type='{"float64", "float32"}',
        default='float64',
        keyword_only=True,
        note='a separate word from ``dtype``: dtype says what is returned, arithmetic what it is computed in'),
    'array': Word(
        'Integers in [0, 255], or floats.',
        unit='',
        type='array_like',
        default=REQUIRED,
        keyword_only=False),
    'as_float': Word(
        'Return uint8 images as float32 in [0, 1].',
        unit='',
        type='bool, default False',
        default=False,
        keyword_only=True),
    'as_xarray': Word(
        ('Return an ``xarray.DataArray`` with the named dimensions, coordinates and the provenance attributes '
         '(needs xarray).'),
        unit='',
        type='bool, default False',
        default=False,
        keyword_only=True),
    'attrs': Word(
        'Further JSON-like attributes.',
        unit='',
        type='dict, optional',
        default=None,
        keyword_only=True),
    'axes': Word(
        "Array axes, numpy's meaning (None: all).",
        unit='',
        type='int, tuple of int or None',
        default=None,
        keyword_only=True,
        per_function={'noiselab.testing.assert_seamless': (None, False)},
        note="assert_seamless takes the axes second by position, as numpy's testing helpers take theirs"),
    'axis': Word(
        "One array axis, numpy's meaning (negative counts from the end).",
        unit='',
        type='int',
        default=-1,
        keyword_only=True,
        per_function={'noiselab.analysis.slice_leakage': (0, True),
                      'noiselab.geometry.squashed_sphere': (2, True),
                      'noiselab.analysis.PowerSpectrum.frequency': (REQUIRED, False)},
        note=("slice_leakage slices a volume across its leading axis (a video's frames); squashed_sphere's axis is"
              ' a coordinate axis of 3-D space (2: z), not an array axis; PowerSpectrum.frequency asks which '
              "axis's frequencies, its one argument")),
    'azimuth': Word(
        'Camera turns (degrees) about the view-up and the horizontal axis, and zoom (applied after the fit).',
        unit='degrees',
        type='float',
        default=0.0,
        keyword_only=True),
    'b': Word(
        'Normals (any length), broadcastable against each other.',
        unit='',
        type='array_like (..., 3)',
        default=REQUIRED,
        keyword_only=False),
    'B_sf': Word(
        'Radial bandwidth, cycles/pixel, > 0 (``np.inf``: no band, a 1/f spectrum with ``loggabor``).',
        unit='cycles/pixel',
        type='float',
        default=REQUIRED,
        keyword_only=True),
    'B_theta': Word(
        'Orientation bandwidth, radians, ``>= 1e-6``; ``np.inf`` (default): isotropic.',
        unit='radians',
        type='float',
        default=math.inf,
        keyword_only=True),
    'B_V': Word(
        'Speed bandwidth, px/frame, >= 0 (0: a frozen texture, ``np.inf``: every frame independent).',
        unit='px/frame',
        type='float',
        default=0.5,
        keyword_only=True),
    'background': Word(
        ('A still ``(H, W)`` / ``(H, W, 3)`` or a video ``(T, H, W)`` / ``(T, H, W, 3)``; grey or RGB (alpha is '
         'broadcast over colour); uint8 (0..255) or float (0..1).'),
        unit='',
        type='ndarray',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'band': Word(
        ('A spatial pass band, always one (lo, hi) pair, inclusive, in cycles/frame (cycles per width of the last '
         "axis); None: the function's default band."),
        unit='cycles/frame',
        type='(lo, hi) or None',
        default=VARIES,
        keyword_only=None,
        note=('required where the band is what a function measures, None where it has a default band; positional '
              'on the analysers and assertions that measure in a band, keyword-only on the generators')),
    'band_cycles_per_degree': Word(
        'A pass band (lo, hi) in cycles per degree of visual angle.',
        unit='cycles/degree',
        type='(lo, hi)',
        default=REQUIRED,
        keyword_only=False),
    'bands': Word(
        'Spatial-frequency bands in cycles/frame.',
        unit='cycles/frame',
        type='sequence of (lo, hi)',
        default=VARIES,
        keyword_only=False,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'basis': Word(
        '``"value"``: Phillips\' random values.',
        unit='',
        type='{"value", "gradient"}, default "value"',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'beta': Word(
        'Opacity exponent, ``alpha ** beta`` after rescaling (thesis: 1.5).',
        unit='',
        type='float',
        default=1.5,
        keyword_only=None),
    'bins': Word(
        'Number of bins, or their edges in cycles/frame.',
        unit='',
        type='int or array_like, optional',
        default=None,
        keyword_only=True),
    'bins_per_octave': Word(
        'Radial bins per octave of the spectrum the slope is fitted to.',
        unit='',
        type='int',
        default=8,
        keyword_only=True),
    'bits': Word(
        'Bits per display value, 1 to 16: values ``0 ..',
        unit='',
        type='int',
        default=8,
        keyword_only=None),
    'bounds': Word(
        'The analytic range.',
        unit='',
        type='(lo, hi), optional',
        default=None,
        keyword_only=True),
    'c': Word(
        "The tent constant of Langer & Zhang's snow: a layer at |w| rad/px falls at c/|w| px/frame, 0 <= c <= pi.",
        unit='rad/frame',
        type='float',
        default=VARIES,
        keyword_only=None,
        note='1.0 on the generators; required by the analysers that measure a tent'),
    'center': Word(
        "The sphere's centre, (x, y, z) in mesh coordinates.",
        unit='mesh units',
        type='(x, y, z), default (0, 0, 0)',
        default=(0.0, 0.0, 0.0),
        keyword_only=False),
    'chunk_size': Word(
        'Points per call.',
        unit='points',
        type='int, default 1_048_576',
        default=1048576,
        keyword_only=True),
    'chunks': Word(
        ("Return a lazy dask array in these chunks (dask's syntax), computed on the scale layer (needs "
         'noiselab[dask]); None: in memory.'),
        unit='',
        type="int, tuple, 'auto' or None",
        default=None,
        keyword_only=True),
    'clim': Word(
        'The colour limits (lo, hi) of the scalars (None: their range).',
        unit='',
        type='',
        default=None,
        keyword_only=True),
    'clip': Word(
        ('Clip instead of refusing: a writer clips floats outside [0, 1] when no range is stated (otherwise a '
         '``ValueError``); ``to_display`` and ``luminance_for`` clip the field at ``clip`` standard deviations '
         'of its mean before scaling it to the requested contrast (None: no clipping, a request off the display '
         'is refused).'),
        unit='standard deviations (to_display, luminance_for)',
        type='bool (writers) or float > 0 (to_display, luminance_for)',
        default=False,
        keyword_only=True,
        per_function={'noiselab.stimuli.to_display': (None, True),
                      'noiselab.stimuli.luminance_for': (None, True)},
        note=("to_display's and luminance_for's clip is a number of standard deviations (None: none), as a "
              "Gaussian field's tails are what leaves a display; the writers' clip is a yes or no to [0, 1]")),
    'close': Word(
        'Close the figure afterwards (pyplot figures only).',
        unit='',
        type='bool, default True',
        default=True,
        keyword_only=True),
    'closed': Word(
        'Sample the field on a circle of its input space, so the curve closes.',
        unit='',
        type='bool, default True',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'cmap': Word(
        'A matplotlib colour map name for the scalars.',
        unit='',
        type='',
        default='viridis',
        keyword_only=True),
    'color': Word(
        'A matplotlib colour (name or RGB), or a colouring scheme where the function says so.',
        unit='',
        type='',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'colors': Word(
        'One per mesh (matplotlib names or RGB); default a pale blue-grey.',
        unit='',
        type='colour or list of colours',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'columns': Word(
        'Meshes per row of the arrangement (None: about a square).',
        unit='',
        type='',
        default=None,
        keyword_only=False),
    'components': Word(
        'The number of output components expected.',
        unit='',
        type='int, optional',
        default=None,
        keyword_only=True),
    'contrast': Word(
        '``contrast_kind="rms"``: standard deviation over mean of the luminance, > 0.',
        unit='fraction',
        type='float',
        default=REQUIRED,
        keyword_only=True),
    'contrast_kind': Word(
        'See noiselab.stimuli.to_display.',
        unit='',
        type='{"rms", "michelson"}',
        default='rms',
        keyword_only=True),
    'coords': Word(
        '``dim -> 1-D array`` of coordinates, written as arrays beside the data.',
        unit='',
        type='dict, optional',
        default=None,
        keyword_only=True),
    'create': Word(
        'Make missing folders; False only checks.',
        unit='',
        type='bool, default True',
        default=True,
        keyword_only=True),
    'crop': Word(
        'Cut each tiled frame to this size (at most the tiled size).',
        unit='',
        type='(height, width), optional',
        default=None,
        keyword_only=True),
    'cross': Word(
        'Cross-eyed (True) or parallel (False) stereo order.',
        unit='',
        type='',
        default=True,
        keyword_only=True),
    'curvature': Word(
        "The base's normal curvature ``kappa`` (1/R for a sphere of radius R).",
        unit='',
        type='float or (n,) array',
        default=0.0,
        keyword_only=True),
    'curves': Word(
        '2-D curves, each an (n, 2) array of (x, y) plot points.',
        unit='plot units',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'cycles_per_degree': Word(
        'Spatial frequency in cycles per degree of visual angle.',
        unit='cycles/degree',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'cycles_per_frame': Word(
        'Spatial frequency in cycles per frame width.',
        unit='cycles/frame',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'cycles_per_pixel': Word(
        'Spatial frequency in cycles per pixel.',
        unit='cycles/pixel',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'data': Word(
        'What to write: a real numeric array.',
        unit='',
        type='numpy.ndarray or dask.array.Array',
        default=REQUIRED,
        keyword_only=False),
    'dc': Word(
        'Keep the DC term (the band must start at 0): the field gets a random mean, e.g.',
        unit='',
        type='bool',
        default=False,
        keyword_only=True),
    'deg_per_second': Word(
        'A speed in degrees of visual angle per second.',
        unit='deg/s',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'degrees': Word(
        ("``theta`` in degrees and ``frequency`` in cycles per degree (the paper's units: figure 3 is a 5-degree "
         'arc at 2 cycles per degree).'),
        unit='degrees',
        type='bool',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'dim': Word(
        'The number of input dimensions.',
        unit='',
        type='',
        default=REQUIRED,
        keyword_only=False,
        per_function={'noiselab.gabor.from_envelope': (2, True), 'noiselab.gabor.power_law_layers': (2, True)},
        note=('from_envelope and power_law_layers take 2 or 3 by keyword, 2 by default (the envelope or the band '
              'is what they are about)')),
    'dim_in': Word(
        'Input dimension d >= 1 (1: a curve of time, 2: an image, 3: solid noise, ...).',
        unit='',
        type='int',
        default=REQUIRED,
        keyword_only=False),
    'dim_out': Word(
        'Output components; each has its own permutation table (Phillips 2.3.1).',
        unit='',
        type='int, default 1',
        default=1,
        keyword_only=False),
    'dims': Word(
        'Output components kept (2 or 3; default all).',
        unit='',
        type='int, optional',
        default=None,
        keyword_only=True),
    'direction': Word(
        '``"normal"`` (default) is Eq.',
        unit='',
        type='{"normal", "vector"}',
        default='normal',
        keyword_only=True),
    'direction_yx': Word(
        'A fall direction in array order (dy, dx): y down the rows, x right along the columns; any length.',
        unit='',
        type='(dy, dx)',
        default=(1.0, 0.0),
        keyword_only=True),
    'directory': Word(
        'The output is a folder.',
        unit='',
        type='bool, default False',
        default=False,
        keyword_only=True),
    'display': Word(
        'The screen (luminance range, gamma law or measured table, bits).',
        unit='',
        type='Display',
        default=REQUIRED,
        keyword_only=False,
        per_function={'noiselab.testing.assert_velocity': (None, True),
                      'noiselab.testing.assert_centre_frequency': (None, True)},
        note=('optional and keyword-only on assert_velocity, where it turns px/frame into deg/s, and on '
              'assert_centre_frequency, where it turns cycles/pixel into cycles/deg')),
    'distance_cm': Word(
        'Eye to screen, cm, > 0.',
        unit='cm',
        type='float',
        default=REQUIRED,
        keyword_only=True),
    'diameter_deg': Word(
        "An aperture's outer diameter, degrees of visual angle.",
        unit='deg',
        type='float > 0',
        default=REQUIRED,
        keyword_only=True),
    'dither': Word(
        ('True (default): random dithering between the two display values around each requested luminance, with '
         'probabilities that make the expected luminance of every pixel exactly the requested one.'),
        unit='',
        type='bool',
        default=True,
        keyword_only=True),
    'drop': Word(
        'Decades of power (1: a factor of 10) that an edge must fall by, in (0, 30].',
        unit='dB (power_band) or fraction',
        type='float, default 1',
        default=1.0,
        keyword_only=True),
    'dtype': Word(
        'The floating output dtype, float32 or float64 (None: follows the input).',
        unit='',
        type='float32, float64 or None',
        default=VARIES,
        keyword_only=True,
        per_function={'noiselab.spectral.draw_coefficients': (np.float32, False)},
        note=('float32 for the large generators (the error allows it), float64 for grids and analysis; '
              'draw_coefficients keeps its fourth place by position')),
    'elevation': Word(
        'Camera turns (degrees) about the view-up and the horizontal axis, and zoom (applied after the fit).',
        unit='degrees',
        type='float',
        default=0.0,
        keyword_only=True),
    'envelope': Word(
        ('``envelope(*w)`` receives the broadcast frequency vectors of :func:`frequency_vectors` (rad/sample, one '
         'per axis) and returns the amplitude, broadcastable to the half spectrum ``(..., W//2 + 1)``; or that '
         'amplitude array itself.'),
        unit='',
        type='callable or ndarray',
        default=REQUIRED,
        keyword_only=False),
    'exponent': Word(
        ('The amplitude exponent: amplitude ~ f**-exponent, power ~ f**(-2 exponent); 1 is 1/f amplitude (power '
         'slope -2), 0 white.'),
        unit='',
        type='float',
        default=VARIES,
        keyword_only=None,
        note='1.0 on the generators; required by assert_power_law (what it checks)'),
    'extent': Word(
        'A region in array order, ((y0, y1), (x0, x1)) (one pair per axis), in input units.',
        unit='input units',
        type='sequence of (lo, hi)',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'false_alarm': Word(
        'Probability that a field holding the property fails (1e-12 to 0.5).',
        unit='',
        type='float',
        default=0.001,
        keyword_only=True),
    'field': Word(
        ('Points ``(n, 3)`` (``(n, 4)`` when ``time`` is given) -> values ``(n,)``: a '
         '``noiselab.LatticeNoise(3)``, a fractal sum, a :func:`sampled_field`...'),
        unit='',
        type='callable',
        default=REQUIRED,
        keyword_only=False),
    'fig': Word(
        'A matplotlib figure.',
        unit='',
        type='matplotlib.figure.Figure',
        default=REQUIRED,
        keyword_only=False),
    'fit': Word(
        ('Zoom so that the scene fills the image (4% margin; from a subsample of up to 20,000 vertices); otherwise'
         " pyvista's fit of the bounding sphere to the height."),
        unit='',
        type='bool',
        default=True,
        keyword_only=True),
    'flakes': Word(
        ('Number of flakes, 1..10**8; default ``H * W / 16`` (16384 at 512 x 512), which gives a mean opacity near'
         ' that of :func:`noiselab.snowfall.snow` with the default band (about 0.35; see ``benchmarks/RESULTS.md``).'),
        unit='',
        type='int, optional',
        default=None,
        keyword_only=True),
    'fmax': Word(
        ('Upper limit in cycles/frame; default ``N / 2`` (the inscribed Nyquist circle; the corners beyond it hold'
         ' an incomplete annulus).'),
        unit='cycles/frame',
        type='float, optional',
        default=None,
        keyword_only=True),
    'foreground': Word(
        'The motion parallax in [0, 1] (e.g.',
        unit='',
        type='ndarray (T, H, W) or (H, W)',
        default=REQUIRED,
        keyword_only=False),
    'fps': Word(
        'Frames per second (MP4 and GIF).',
        unit='frames/s',
        type='float, default 25',
        default=25.0,
        keyword_only=True),
    'frame_rate': Word(
        'Frames per second (Hz), > 0.',
        unit='Hz',
        type='float',
        default=60.0,
        keyword_only=None),
    'frames': Word(
        'Mapped to uint8 by :func:`to_uint8` (not for ``.npy``).',
        unit='',
        type='array_like (T, H, W[, 3]) or iterable of frames',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'frequency': Word(
        ("The field's spatial frequency: points are scaled by it before evaluation (cycles per input unit of the "
         'mesh, curve or extent).'),
        unit='1/input unit',
        type='float or sequence',
        default=1.0,
        keyword_only=None,
        note="positional after amplitude in the geometry functions (Phillips' a, F, phi)"),
    'gain': Word(
        'Octaves summed (>= 1; one is ``__call__``), their frequency (> 1) and amplitude (> 0) ratios.',
        unit='amplitude ratio between octaves',
        type='int, float, float; default 1, 2, 0.5',
        default=0.5,
        keyword_only=True),
    'full_output': Word(
        ("Return ``(result, report)`` with what the function did besides the result (as scipy's "
         '``full_output``): ``to_display``\'s :class:`~noiselab.stimuli.DisplayReport`.'),
        unit='',
        type='bool, default False',
        default=False,
        keyword_only=True),
    'gamma': Word(
        'Exponent of the gamma law, in ``[0.1, 10]``.',
        unit='',
        type='float',
        default=2.2,
        keyword_only=None),
    'gap': Word(
        'Pixels between the two images of a stereo pair.',
        unit='px',
        type='',
        default=8,
        keyword_only=True),
    'group': Word(
        'The gallery group (page section) a figure belongs to.',
        unit='',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'groups': Word(
        'Number of target-level groups.',
        unit='',
        type='int',
        default=16,
        keyword_only=True),
    'hash': Word(
        'How a lattice point is addressed.',
        unit='',
        type='{"table", "integer"}, default "table"',
        default='table',
        keyword_only=True),
    'height': Word(
        "Accepted for symmetry with ``snow``'s shape (>= 1); no effect.",
        unit='',
        type='int, optional',
        default=None,
        keyword_only=False),
    'heights': Word(
        'Finite heights.',
        unit='',
        type='array_like (H, W)',
        default=REQUIRED,
        keyword_only=False),
    'hi': Word(
        "The field's minimum and maximum, if known (both or neither; ``lo <= hi``).",
        unit='',
        type='float, optional',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'image': Word(
        '``(height, width)`` or ``(frames, height, width)``.',
        unit='',
        type='array_like or PowerSpectrum',
        default=REQUIRED,
        keyword_only=False),
    'intensity': Word(
        ('Snow intensity on the 0..255 scale (thesis: 250, below saturation); used as ``intensity/255`` for float '
         'backgrounds.'),
        unit='display value',
        type='float',
        default=250,
        keyword_only=False),
    'kernel': Word(
        '``"box"``, ``"linear"``, ``"quadratic"``, ``"cubic"`` (B-splines of order 1-4, i.e.',
        unit='',
        type='str, optional',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'kind': Word(
        'How the octaves combine (Phillips Eq.',
        unit='',
        type='{"fractal", "turbulence"}, default "fractal"',
        default='fractal',
        keyword_only=None),
    'lacunarity': Word(
        'Octaves summed (>= 1; one is ``__call__``), their frequency (> 1) and amplitude (> 0) ratios.',
        unit='frequency ratio between octaves',
        type='int, float, float; default 1, 2, 0.5',
        default=2.0,
        keyword_only=True),
    'layers': Word(
        'Depth layers, 1..256 (more layers: a closer approximation, linear cost).',
        unit='',
        type='int',
        default=8,
        keyword_only=True),
    'limits': Word(
        'Default: fitted to the trajectory.',
        unit='',
        type='((xmin, xmax), (ymin, ymax)), optional',
        default=None,
        keyword_only=True),
    'lines': Word(
        'Streamlines, an (m, n, 2) array of (x, y) plot points.',
        unit='plot units',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'linewidth': Word(
        "Line width in points (matplotlib's).",
        unit='pt',
        type='',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'lo': Word(
        "The field's minimum and maximum, if known (both or neither; ``lo <= hi``).",
        unit='',
        type='float, optional',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'log': Word(
        'Log-spaced bins (geometric centres).',
        unit='',
        type='bool',
        default=False,
        keyword_only=True),
    'loggabor': Word(
        ("MotionClouds' ``loggabor``: True (default) the log-Gabor radial band times ``1/f``; False a Gaussian "
         'ring of centre ``sf_0`` and width ``B_sf``.'),
        unit='',
        type='bool',
        default=True,
        keyword_only=True),
    'look': Word(
        'One line for the reader: what to look for in the figure.',
        unit='',
        type='',
        default='',
        keyword_only=True),
    'lossless': Word(
        'For ``.mp4``: H.264 in RGB with ``-qp 0`` instead of the lossy default.',
        unit='',
        type='bool, default False',
        default=False,
        keyword_only=True),
    'luminance': Word(
        'Luminance in cd/m² at the lowest and the highest display value, ``0 <= L_min < L_max``.',
        unit='cd/m²',
        type='(L_min, L_max)',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'lut': Word(
        'Measured luminance of every display value (set by :meth:`from_lut`; ``gamma`` is then None).',
        unit='',
        type='tuple of float, optional',
        default=VARIES,
        keyword_only=False,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'make_parents': Word(
        'Create missing parent folders (with ``create``).',
        unit='',
        type='bool, default True',
        default=True,
        keyword_only=True),
    'marker_size': Word(
        'Marker area (matplotlib points squared).',
        unit='',
        type='float, default 60',
        default=60.0,
        keyword_only=True),
    'mask': Word(
        ('The geometric pattern: bool, or a background image whose bright half (above the middle of its range) is '
         'the veiled region.'),
        unit='',
        type='ndarray (H, W) or (T, H, W)',
        default=VARIES,
        keyword_only=False,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'max_faces': Word(
        'The most faces the result may have.',
        unit='',
        type='int, default 50_000_000',
        default=50000000,
        keyword_only=True),
    'max_frames': Word(
        'Read at most this many frames.',
        unit='',
        type='int, optional',
        default=None,
        keyword_only=True),
    'max_frequency': Word(
        ("Highest frequency of the displacement, in cycles per unit of the mesh's coordinates: ``frequency * "
         'lacunarity**(octaves - 1)`` for an octave sum of a unit-frequency lattice noise.'),
        unit='cycles per input unit',
        type='float in (0, 1e300]',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'max_lag': Word(
        'The largest lag tried (None: half the axis).',
        unit='samples',
        type='int, optional',
        default=None,
        keyword_only=True),
    'max_leakage': Word(
        'Allowed fraction of the power outside the band (0 to 1).',
        unit='',
        type='float, optional',
        default=None,
        keyword_only=True),
    'max_subdivisions': Word(
        'The most subdivisions allowed (level 9: 2.6 million vertices).',
        unit='',
        type='int, default 9',
        default=9,
        keyword_only=True),
    'mean': Word(
        "Mean luminance, cd/m², inside the display's ``luminance`` range.",
        unit="cd/m² (stimuli) or the field's unit",
        type='float',
        default=REQUIRED,
        keyword_only=True),
    'mesh': Word(
        'The base (undisplaced) mesh, as given to ``displace``.',
        unit='',
        type='trimesh.Trimesh or pyvista.PolyData',
        default=REQUIRED,
        keyword_only=False),
    'meshes': Word(
        'Several meshes are drawn in one scene (see :func:`arrange` for figure layouts).',
        unit='',
        type='trimesh.Trimesh, pyvista.PolyData, or a list of them',
        default=REQUIRED,
        keyword_only=False),
    'method': Word(
        "Fixed-step Runge-Kutta for all seeds at once, or scipy's adaptive RK45 per seed.",
        unit='',
        type='{"rk4", "solve_ivp"}, default "rk4"',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'min_cells': Word(
        'Rings with fewer full-spectrum cells are left out (their variance means little).',
        unit='',
        type='int',
        default=8,
        keyword_only=True),
    'min_energy': Word(
        'Smallest share of the power a default band must hold to be kept.',
        unit='',
        type='float, default 0.001',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'min_lag': Word(
        'The smallest lag tried.',
        unit='samples',
        type='int, optional',
        default=1,
        keyword_only=True),
    'min_size': Word(
        ("Fewest samples accepted along any axis (a video's time axis may have 2: "
         ':func:`noiselab.analysis.video_spectrum` checks it).'),
        unit='',
        type='int',
        default=4,
        keyword_only=True),
    'mode': Word(
        'Distort the radius (figure 3) or x and y independently (figure 5).',
        unit='',
        type='{"radial", "xy"}',
        default='radial',
        keyword_only=True),
    'motion_blur': Word(
        ("Average each flake over the frame's shutter interval (slower by about the flake's speed in half pixels "
         'per frame).'),
        unit='',
        type='bool',
        default=False,
        keyword_only=True),
    'n': Word(
        'How many coefficients, ``n >= 0``.',
        unit='',
        type='int',
        default=VARIES,
        keyword_only=False,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'n_frames': Word(
        ('Number of frames to yield (default ``rt * T``); frame ``i`` is ``alpha[(start + i) % T]`` tiled, so any '
         'length loops seamlessly.'),
        unit='',
        type='int, optional',
        default=None,
        keyword_only=True),
    'n_steps': Word(
        'Steps per streamline.',
        unit='',
        type='int, default 200',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'name': Word(
        "The points' name in error messages (for callers that take them under another name).",
        unit='',
        type='str, default "points"',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'nbins': Word(
        ("Orientation bins over 180 degrees (a multiple of 4 keeps the axes and diagonals on bin centres' "
         'symmetric positions).'),
        unit='',
        type='int',
        default=36,
        keyword_only=True),
    'noise': Word(
        'The basis noise (any callable on points works, without the fast paths).',
        unit='',
        type='LatticeNoise or callable',
        default=REQUIRED,
        keyword_only=False),
    'normalize': Word(
        ("Scale the output's values to a standard range: spectral fields to unit variance ('expected': over the "
         "ensemble, 'sample': this field; None: as drawn), fractal sums by the sum of the octave gains into [-1, "
         '1] (True or False).'),
        unit='',
        type="{'expected', 'sample', None} (spectral) or bool (fractal)",
        default=VARIES,
        keyword_only=True,
        note=("'expected' where a unit-variance field is the promise (spectral_noise, motion_cloud), None in "
              "synthesize (the envelope's own scale), False in the fractal sums (Phillips' Eq. 9 is unnormalised)")),
    'normals': Word(
        ('Base unit normals; default the welded area-weighted vertex normals ``displace`` uses (flipped outwards '
         'for an inside-out closed mesh).'),
        unit='',
        type='(n, 3) array, optional',
        default=None,
        keyword_only=True),
    'octaves': Word(
        'Octaves summed (>= 1; one is ``__call__``), their frequency (> 1) and amplitude (> 0) ratios.',
        unit='',
        type='int, float, float; default 1, 2, 0.5',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'on_alias': Word(
        ("What to do when a request would alias (energy or detail past the Nyquist frequency): 'raise' a "
         "ValueError naming the largest allowed value, 'warn' (AliasingWarning), 'ignore', or 'drop' the cells "
         'that would alias.'),
        unit='',
        type='str',
        default='warn',
        keyword_only=True,
        per_function={'noiselab.snow': ('raise', True),
                      'noiselab.snowfall.snow_spectrum': ('raise', True)},
        note=('snow refuses by default: aliased snow moves backwards, a wrong video, where an undersampled mesh is'
              ' only coarse (warned)')),
    'only': Word(
        'Figure keys or groups to select (None: all).',
        unit='',
        type='',
        default=None,
        keyword_only=False),
    'opacity': Word(
        "Opacity of a flake's core, in (0, 1].",
        unit='fraction',
        type='float',
        default=0.9,
        keyword_only=True),
    'order': Word(
        'Spline order (1 linear, 3 cubic).',
        unit='',
        type='int, default 3',
        default=3,
        keyword_only=True),
    'oversample': Word(
        'How many times denser than the output ``field`` is sampled (1: no aliasing measurement).',
        unit='',
        type='int',
        default=1,
        keyword_only=True),
    'pan_yx': Word(
        'A camera pan as the image velocity it adds, in array order (uy, ux).',
        unit='px/frame',
        type='(uy, ux)',
        default=(0.0, 0.0),
        keyword_only=True),
    'params': Word(
        "Provenance: the data's units (e.g.",
        unit='',
        type='optional',
        default=None,
        keyword_only=True),
    'path': Word(
        'Also write the image there (PNG, ...).',
        unit='',
        type='str or Path, optional',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'per_octave': Word(
        'Default bands per octave.',
        unit='bands per octave',
        type='int, default 2',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'period': Word(
        'Exact lattice period per axis: the noise then tiles with period ``period / frequency`` in input units.',
        unit='samples (analysis) or lattice cells (LatticeNoise)',
        type='int or sequence of int, optional',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'periodic': Word(
        'Wrap the grid; otherwise clamp points to its edge.',
        unit='',
        type='bool, default True',
        default=True,
        keyword_only=True),
    'phase': Word(
        'An offset added to the scaled points before evaluation.',
        unit='input units',
        type='float or sequence',
        default=0.0,
        keyword_only=None,
        note='positional after frequency in the geometry functions'),
    'phase_from': Word(
        'Real arrays of one shape.',
        unit='',
        type='array_like',
        default=REQUIRED,
        keyword_only=False),
    'phases': Word(
        'Phase bins; default ``round(period)`` (one per sample for an integer period), at most 64.',
        unit='',
        type='int, optional',
        default=None,
        keyword_only=True),
    'pixels': Word(
        'A length in pixels.',
        unit='px',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'pixels_per_degree': Word(
        'Pixels per degree of visual angle at the centre of the screen, > 0.',
        unit='px/degree',
        type='float',
        default=REQUIRED,
        keyword_only=False),
    'plane': Word(
        'Values on a self-conjugate plane (e.g.',
        unit='',
        type='complex ndarray',
        default=REQUIRED,
        keyword_only=False),
    'points': Word(
        'As for ``__call__``.',
        unit='',
        type='array_like, shape (..., dim_in)',
        default=REQUIRED,
        keyword_only=False),
    'poly': Word(
        'A pyvista PolyData mesh.',
        unit='',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'probe': Word(
        'Create and remove a temporary file beside the target.',
        unit='',
        type='bool, default True',
        default=True,
        keyword_only=True),
    'progress': Word(
        'A progress bar on stderr: None shows it when stderr is a terminal, True always, False never.',
        unit='',
        type='bool or None',
        default=None,
        keyword_only=True),
    'px_per_frame': Word(
        'A speed in pixels per frame.',
        unit='px/frame',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'quality': Word(
        'MP4 quality, 0 to 10 (lossy MP4 only).',
        unit="imageio's 0-10 scale",
        type='int, default 8',
        default=8,
        keyword_only=True),
    'ramp_deg': Word(
        "Width of a raised-cosine aperture's edge, degrees, inside its diameter.",
        unit='deg',
        type='float, 0 < ramp_deg <= diameter_deg / 2',
        default=REQUIRED,
        keyword_only=True),
    'orientation_deg': Word(
        ('An orientation in degrees, modulo 180: the direction of the wave vector, x right, y down (0: vertical '
         "stripes; a positive angle turns them clockwise on the screen, as PsychoPy's ``ori``)."),
        unit='deg',
        type='float',
        default=REQUIRED,
        keyword_only=True),
    'orientation_hwhm_deg': Word(
        'Orientation bandwidth as papers state it: half width at half height of the amplitude band, degrees.',
        unit='deg',
        type='float in (0, 90]',
        default=REQUIRED,
        keyword_only=True),
    'quick': Word(
        'Parameter overrides for a fast build of the figure.',
        unit='',
        type='',
        default=None,
        keyword_only=True),
    'radius': Word(
        'Radius of the undistorted circle.',
        unit='mesh units',
        type='float, default 1',
        default=1.0,
        keyword_only=False),
    'remove_static': Word(
        "Subtract each pixel's temporal mean first.",
        unit='',
        type='bool, default False',
        default=False,
        keyword_only=True),
    'reps': Word(
        '``(rt, ry, rx)`` for a video, ``(ry, rx)`` for a still, or one int for every axis; each >= 1.',
        unit='',
        type='int or tuple of int',
        default=VARIES,
        keyword_only=False,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'rescale': Word(
        '``False`` returns the raw zero-mean field (the inverse FFT itself).',
        unit='',
        type='bool',
        default=True,
        keyword_only=True),
    'resolution': Word(
        'Vertices per side (>= 2).',
        unit='',
        type='int, default 64',
        default=64,
        keyword_only=False),
    'resolution_px': Word(
        'Pixels across that width, >= 1.',
        unit='px',
        type='int',
        default=REQUIRED,
        keyword_only=True),
    'return_flakes': Word(
        ('Also return the flakes: a dict of arrays ``x``, ``y`` (px at frame 0), ``depth``, ``diameter`` (px) and '
         '``speed`` (px/frame).'),
        unit='',
        type='bool',
        default=False,
        keyword_only=True),
    'return_heights': Word(
        'Also return the heights z (computed in the same pass), as ``(z, normals)``.',
        unit='',
        type='bool',
        default=False,
        keyword_only=True),
    'return_octaves': Word(
        'Also return the number of octaves used.',
        unit='',
        type='bool',
        default=False,
        keyword_only=True),
    'return_spectrum': Word(
        'Also return the half spectrum ``S`` with ``rfftn(field) == S``.',
        unit='',
        type='bool',
        default=False,
        keyword_only=True),
    'return_value': Word(
        'Also return the noise values (computed in the same pass), as ``(value, jacobian)``.',
        unit='',
        type='bool, default False',
        default=False,
        keyword_only=True,
        per_function={'noiselab.LatticeNoise.evaluate_grid_jacobian': (True, True)},
        note=('evaluate_grid_jacobian is the evaluation interface other packages call: it always returns the pair '
              '(value or None, jacobian), the value by default')),
    'rng': Word(
        ('The random state (SPEC 7): an int (the same int gives the same bits across runs, processes, evaluation '
         'paths and chunkings), a numpy.random.Generator (drawn from, advanced) or None (fresh OS entropy, not '
         'repeatable). write_zarr records the int that drew its data.'),
        unit='',
        type='int, numpy.random.Generator or None',
        default=None,
        keyword_only=True,
        per_function={'noiselab.spectral.draw_coefficients': (None, False),
                      'noiselab.geometry.quiver_image': (0, True),
                      'noiselab.LatticeNoise': (0, True),
                      'noiselab.gabor.GaborNoise': (0, True),
                      'noiselab.gabor.from_envelope': (0, True),
                      'noiselab.gabor.power_law_layers': (0, True)},
        note=('draw_coefficients keeps rng second by position (its calling form since 0.1); quiver_image draws a '
              'fixed picture: the same every run unless another rng is passed; a LatticeNoise is a fixed function '
              "(as Perlin's reference noise and the SIMD peers' default seed are), so LatticeNoise(3) is the same "
              'noise in every process: rng=0; so is a GaborNoise (from_envelope makes one)')),
    'samples_per_period': Word(
        'Samples per period of the highest octave below which the grid aliases.',
        unit='samples',
        type='float, default 4',
        default=4.0,
        keyword_only=True),
    'saturation': Word(
        'HSV saturation of the colours, in [0, 1].',
        unit='',
        type='',
        default=0.85,
        keyword_only=True),
    'scalars': Word(
        'Colour by a vertex attribute instead (e.g.',
        unit='',
        type='str, optional',
        default=None,
        keyword_only=True),
    'scale': Word(
        'Glyph length per unit of flow (None: fitted to the grid spacing).',
        unit='input units',
        type='',
        default=None,
        keyword_only=True),
    'scheduler': Word(
        "``None``: the active ``distributed.Client`` if there is one, else dask's default (threads).",
        unit='',
        type='None, str or distributed.Client, optional',
        default=None,
        keyword_only=True),
    'screen_width_cm': Word(
        'Visible width of the picture, cm, > 0.',
        unit='cm',
        type='float',
        default=REQUIRED,
        keyword_only=True),
    'seconds': Word(
        'A duration in seconds.',
        unit='s',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'seeds': Word(
        'Start positions.',
        unit='',
        type='array_like (m, d)',
        default=REQUIRED,
        keyword_only=False),
    'separation': Word(
        "Degrees between the two eyes' views.",
        unit='degrees',
        type='',
        default=5.0,
        keyword_only=True),
    'sf_0': Word(
        ('Peak spatial frequency, cycles/pixel, in ``(0, 0.5]`` (``display.cycles_per_pixel(cpd)`` from '
         'cycles/deg); the expected centre frequency of assert_centre_frequency, cycles/pixel or cycles/deg with '
         'a ``display``.'),
        unit='cycles/pixel',
        type='float',
        default=REQUIRED,
        keyword_only=True),
    'sf_bandwidth_octaves': Word(
        'Spatial-frequency bandwidth as papers state it: full width at half maximum of the amplitude band, octaves.',
        unit='octaves',
        type='float in (0, 20]',
        default=REQUIRED,
        keyword_only=True),
    'shape': Word(
        "An array shape in numpy's order: (n,), (ny, nx), (nz, ny, nx) or (T, H, W).",
        unit='samples',
        type='tuple of int',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'show_axes': Word(
        "Draw matplotlib's axes (ticks and frame) around a plot.",
        unit='',
        type='bool',
        default=False,
        keyword_only=True),
    'show_edges': Word(
        "Draw the mesh's edges.",
        unit='',
        type='',
        default=False,
        keyword_only=True),
    'size': Word(
        "Largest extent after :func:`normalize`; None keeps the file's units.",
        unit='px (images) or mesh units (meshes)',
        type='float or None, default 2',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'sigma_deg': Word(
        "A Gaussian aperture's standard deviation, degrees.",
        unit='deg',
        type='float > 0',
        default=REQUIRED,
        keyword_only=True),
    'size_deg': Word(
        'A size in degrees of visual angle.',
        unit='degrees',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'slope': Word(
        'The fitted slope (the float the result is).',
        unit='',
        type='',
        default=REQUIRED,
        keyword_only=False),
    'smooth_shading': Word(
        'Interpolate normals across faces when rendering.',
        unit='',
        type='',
        default=True,
        keyword_only=True),
    'source': Word(
        ("The figure of a seed document a gallery figure reproduces (e.g. 'Phillips 2004, Fig. 12'), or that it is"
         " the lab's own."),
        unit='',
        type='',
        default=REQUIRED,
        keyword_only=True),
    'spacing': Word(
        'Sample spacing of scattered points (e.g.',
        unit='input units',
        type='float, optional',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'spec': Word(
        'From :func:`noiselab.analysis.power_spectrum` (its dtype sets ``eps``).',
        unit='',
        type='PowerSpectrum',
        default=REQUIRED,
        keyword_only=False),
    'spill': Word(
        ('With ``chunks``: a directory (on storage every worker sees) for the two transposes as zarr arrays, so no'
         " worker ever holds more than its chunks (for fields bigger than the cluster's memory)."),
        unit='',
        type='path, optional',
        default=None,
        keyword_only=True),
    'spin': Word(
        'Degrees the camera turns about the view-up axis over the sequence.',
        unit='degrees',
        type='',
        default=0.0,
        keyword_only=True),
    'squash': Word(
        'Fraction removed along ``axis``, in ``[0, 1)``.',
        unit='',
        type='float, default 0.05',
        default=0.05,
        keyword_only=False),
    'start': Word(
        'First frame index (modulo ``T``).',
        unit='',
        type='int',
        default=0,
        keyword_only=True),
    'step': Word(
        "Step size in the field's input units (per unit of speed).",
        unit='input units',
        type='float, default 0.01',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'streamline_seeds': Word(
        'How many streamlines to trace from random start points (0: none).',
        unit='',
        type='',
        default=0,
        keyword_only=True),
    'style': Word(
        "Shaded surface (default), or the paper's wire-frame look (unlit lines).",
        unit='',
        type='{"surface", "wireframe", "points"}',
        default='surface',
        keyword_only=True),
    'subdivisions': Word(
        'Subdivision levels of the icosahedron (>= 0).',
        unit='',
        type='int, default 4',
        default=4,
        keyword_only=False),
    'support': Word(
        'Where the envelope carries energy (default ``plane != 0``).',
        unit='',
        type='bool ndarray, optional',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    't': Word(
        'The path parameter.',
        unit='',
        type='array_like (n,)',
        default=REQUIRED,
        keyword_only=False),
    'table_size': Word(
        'Entries n of the permutation table and of each value table (even, >= 2).',
        unit='entries',
        type='int, default 256',
        default=256,
        keyword_only=True),
    'tail': Word(
        'Earlier samples drawn behind the point.',
        unit='',
        type='int, default 25',
        default=25,
        keyword_only=True),
    'target': Word(
        ("``target(f)`` of the radial frequency in cycles/frame (over all the spectrum's axes), or the expected "
         "power per cell as an array in ``rfftn`` layout (or full ``fftn`` layout) of the field's shape."),
        unit='',
        type='callable or ndarray',
        default=REQUIRED,
        keyword_only=False),
    'theta': Word(
        "Angles in radians, measured from +y towards +x (the paper's ``{sin, cos}``).",
        unit='radians',
        type='array (n,)',
        default=VARIES,
        keyword_only=None,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'thickness': Word(
        'Relative thickness of the tent, in [0, 1]: the tent constant spreads over ``c*(1 - thickness) ..',
        unit='relative (fraction of c)',
        type='float',
        default=0.1,
        keyword_only=True),
    'tile': Word(
        ('Tile size in pixels when ``image`` holds several tiles side by side (the seams are the steps from pixel '
         '``j*tile - 1`` to ``j*tile``).'),
        unit='',
        type='int or (th, tw), optional',
        default=None,
        keyword_only=False),
    'time': Word(
        'A 4th input coordinate: step it for a boiling or undulating shape.',
        unit='',
        type='float, optional',
        default=None,
        keyword_only=False),
    'times': Word(
        'The times at which to evaluate a time-varying field, one frame each.',
        unit='field time units',
        type='sequence of float',
        default=REQUIRED,
        keyword_only=False),
    'title': Word(
        "A gallery figure's title.",
        unit='',
        type='',
        default=REQUIRED,
        keyword_only=True),
    'tol': Word(
        ('The accepted deviation, in the unit of what it bounds: temporal-frequency cells off a motion plane or '
         'tent (assert_motion, assert_tent), a velocity per component for assert_velocity (px/frame, deg/s with a '
         '``display``), degrees for assert_orientation, octaves for assert_centre_frequency, a relative difference '
         'for detect_period, the measured statistic for the other assertions (None: '
         "derived from the estimator's sampling law)."),
        unit='',
        type='float or None',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'transmittance': Word(
        'Fraction of the foreground seen through the veil.',
        unit='fraction',
        type='float in [0, 1]',
        default=0.3,
        keyword_only=True),
    'trials': Word(
        "How many trials of an experiment (each with its own seed, as ``noiselab stimulus --trials``), >= 1.",
        unit='',
        type='int',
        default=REQUIRED,
        keyword_only=False),
    'unit_speed': Word(
        'Follow the direction only (unit speed).',
        unit='',
        type='bool, default False',
        default=False,
        keyword_only=True),
    'units': Word(
        "Provenance: the data's units (e.g.",
        unit='',
        type='optional',
        default=None,
        keyword_only=True),
    'uses': Word(
        'The noiselab modules a figure calls (their source is part of its content hash).',
        unit='',
        type='',
        default=(),
        keyword_only=True),
    'V_X': Word(
        ('Velocity of the motion plane, px/frame (x right, y down), within +-1e6 '
         '(``display.px_per_frame(deg_per_s)``).'),
        unit='px/frame',
        type='float',
        default=0.0,
        keyword_only=True),
    'V_Y': Word(
        ('Velocity of the motion plane, px/frame (x right, y down), within +-1e6 '
         '(``display.px_per_frame(deg_per_s)``).'),
        unit='px/frame',
        type='float',
        default=0.0,
        keyword_only=True),
    'value': Word(
        'HSV value (brightness) of the colours, in [0, 1].',
        unit='',
        type='',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'value_range': Word(
        'The field values mapped to the ends of the colour scale.',
        unit='',
        type='',
        default=(-1.0, 1.0),
        keyword_only=True),
    'values': Word(
        'Display values in ``0 ..',
        unit='',
        type='array_like of int',
        default=REQUIRED,
        keyword_only=False),
    'variance': Word(
        'The analytic (expected) variance (> 0; the ratio to it must fit float64).',
        unit='',
        type='float, optional',
        default=None,
        keyword_only=True),
    'vector': Word(
        'The last axis of ``values`` holds components.',
        unit='',
        type='bool, default False',
        default=False,
        keyword_only=True),
    'veil': Word(
        'Luminance of the veil.',
        unit='display value',
        type='float in [0, 255]',
        default=255.0,
        keyword_only=True),
    'veiled_foreground': Word(
        ("A different foreground for the veiled region (the thesis's ``motion_inconsistent`` experiment: another "
         'fall direction there).'),
        unit='',
        type='ndarray, optional',
        default=None,
        keyword_only=True),
    'velocity_yx': Word(
        'An image velocity in array order (vy, vx): +y down the rows, +x right.',
        unit='px/frame',
        type='(vy, vx)',
        default=VARIES,
        keyword_only=True,
        note='(0, 0) where a still image is the natural default; required by assert_motion'),
    'video': Word(
        'A finite grey video (at least 2 frames).',
        unit='',
        type='array_like (T, H, W)',
        default=REQUIRED,
        keyword_only=False),
    'view': Word(
        '``"iso"`` (default), or ``"xy"`` (looking down -z: x right, y up), ``"xz"``, ``"yz"``...',
        unit='',
        type='str or camera position',
        default='iso',
        keyword_only=True),
    'vmax': Word(
        "Heights mapped to black and white (default: the array's range).",
        unit='',
        type='float, optional',
        default=None,
        keyword_only=None),
    'vmin': Word(
        "Heights mapped to black and white (default: the array's range).",
        unit='',
        type='float, optional',
        default=None,
        keyword_only=None),
    'volume': Word(
        '3-D field ``(depth, height, width)``.',
        unit='',
        type='array_like',
        default=REQUIRED,
        keyword_only=False),
    'vx': Word(
        ('An expected image velocity, x component (+x right): px/frame, or deg/s when a ``display`` is given '
         '(assert_velocity).'),
        unit='px/frame (deg/s with display)',
        type='float',
        default=REQUIRED,
        keyword_only=True),
    'vy': Word(
        ('An expected image velocity, y component (+y down the rows): px/frame, or deg/s when a ``display`` is '
         'given (assert_velocity).'),
        unit='px/frame (deg/s with display)',
        type='float',
        default=REQUIRED,
        keyword_only=True),
    'warp_noise': Word(
        'The displacement field, ``dim_in = dim_out = noise.dim_in`` (a scalar noise for 1-D input).',
        unit='',
        type='LatticeNoise or Warped',
        default=REQUIRED,
        keyword_only=False),
    'weld': Word(
        ('Give vertices at exactly the same position (split at UV or crease seams, or an unmerged STL soup) one '
         'common normal, so that the displaced surface does not crack open along seams (default True).'),
        unit='',
        type='bool',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'what': Word(
        'The feature the caller asked for (named in the error).',
        unit='',
        type='str',
        default='chunks=',
        keyword_only=False),
    'whiten': Word(
        'Radial whitening (see above).',
        unit='',
        type='{True, "fit", "ring", False}',
        default=True,
        keyword_only=True),
    'width': Word(
        'Frame width in pixels (>= 1).',
        unit='',
        type='int, default 512',
        default=512,
        keyword_only=False,
        per_function={'noiselab.gabor.gabor_snow': (512, True), 'noiselab.gabor.snow_layers': (512, True)},
        note=('the Gabor snow takes it by keyword: there it is the scene\'s frame width that cycles/frame refer '
              'to, not the width of the window rendered')),
    'window': Word(
        "A taper before the FFT for fields that do not tile: None or 'hann'.",
        unit='',
        type="None or 'hann'",
        default=None,
        keyword_only=True,
        per_function={'noiselab.analysis.best_velocity': ('hann', True),
                      'noiselab.analysis.band_speeds': ('hann', True),
                      'noiselab.analysis.speed_profile': ('hann', True),
                      'noiselab.testing.assert_velocity': ('hann', True)},
        note=("the velocity estimators taper time by default (a video's ends rarely match); the lattice's grid "
              "methods use window= for a window of samples until the lattice engine's rework renames it")),
    'window_axes': Word(
        'Axes the window is applied along (default: the transformed axes).',
        unit='',
        type='tuple of int, optional',
        default=None,
        keyword_only=True),
    'workers': Word(
        ("Threads, with scipy.fft's meaning: None is scipy's current default (one thread unless a "
         'scipy.fft.set_workers block says otherwise), -1 every core, n > 0 that many; the result has the same '
         'bits for any count.'),
        unit='',
        type='int or None',
        default=None,
        keyword_only=True),
    'x': Word(
        'Points, or ``noiselab.lattice.Grid(shape, extent)`` for a regular grid.',
        unit='',
        type='array (..., dim_in) or Grid',
        default=REQUIRED,
        keyword_only=False),
    'zoom': Word(
        'Camera turns (degrees) about the view-up and the horizontal axis, and zoom (applied after the fit).',
        unit='',
        type='float',
        default=1.0,
        keyword_only=True),
    # ---- sparse Gabor noise (noiselab.gabor)
    'bandwidth': Word(
        ("A Gabor kernel's envelope ``exp(-pi (s d)**2)`` per axis: ``s`` is the width of its spectral lobe "
         '``exp(-pi nu**2 / s**2)`` in cycles/sample (> 0), and ``1 / s`` samples its cell.'),
        unit='cycles/sample',
        type='float or sequence of dim floats',
        default=REQUIRED,
        keyword_only=True),
    'density': Word(
        'Mean number of Gabor impulses per kernel cell (Poisson), in (0, 256].',
        unit='impulses per cell',
        type='float, default 4',
        default=4.0,
        keyword_only=True),
    'frequencies': Word(
        'The Gabor kernels\' frequency table, one row per kernel kind, cycles/sample along each axis, array order.',
        unit='cycles/sample',
        type='array_like (M, dim)',
        default=REQUIRED,
        keyword_only=False),
    'origin': Word(
        ('Coordinate (array order) of a window\'s first sample: ``(t, y, x)`` frames and pixels for snow, any '
         'reals for a Gabor grid (default zeros).'),
        unit='samples',
        type='sequence of floats (whole samples for snow)',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'rows': Word(
        'Size of a Gabor frequency table drawn from a target (per octave for snow), 1 to 2**20.',
        unit='',
        type='int',
        default=VARIES,
        keyword_only=True,
        note="the default is each function's own (a size, a shape, a name: what that function is for)"),
    'truncation': Word(
        ("Level of a Gabor kernel's envelope (relative to its peak) where it is cut, in (0, 0.5]; "
         ':func:`noiselab.gabor.truncation_error` is the error it makes.'),
        unit='',
        type='float, default 0.01',
        default=0.01,
        keyword_only=None,
        per_function={'noiselab.gabor.truncation_error': (REQUIRED, False)},
        note='truncation_error takes the level it reports on (required)'),
    'weighted_noises': Word(
        'A list of (weight, GaborNoise) pairs summed in order (noiselab.gabor.power_law_layers, snow_layers).',
        unit='',
        type='list of (float, GaborNoise)',
        default=REQUIRED,
        keyword_only=False),
    'velocities_yx': Word(
        ("Each Gabor kernel's (vy, vx), array order, in samples of axes 1, 2 per sample of axis 0 (time): one "
         'row per frequency row; None for still kernels.'),
        unit='px/frame',
        type='array_like (M, 2) or None',
        default=None,
        keyword_only=True),
}
