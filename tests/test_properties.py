"""Property-based bad-input suite: every public function, driven with bad values.

Each public function has one entry in :data:`TABLE`: a call with valid
arguments, the parameters to corrupt and the *kind* of bad values each takes,
and the documented contract of a result. For every example hypothesis picks
one parameter and a bad value for it (NaN, inf, negative, zero, huge, a wrong
type, a wrong shape, an empty array, ...) and the call must give

- a ``ValueError`` or ``TypeError`` whose message names that parameter, or
- a ``MemoryError`` from ``check_memory`` ("needs about ... GiB"), or
- a result satisfying the contract (finite, with the documented shape, dtype
  and range): a bad-looking value that is in fact allowed must give a right
  answer, never NaN, inf or silent zeros.

The suite runs under an address-space limit (``RLIMIT_AS``, the test process's
size + 6 GiB), so an allocation that was not estimated first fails at once
instead of swapping. Every name in ``noiselab._API`` and every callable in a
subpackage's ``__all__`` must have an entry (or, for the few that only draw or
do file I/O, an entry in :data:`EXCLUDED` with the reason):
:func:`test_every_public_function_has_an_entry` fails otherwise, so coverage
cannot drift. To cover a new function, add a line to ``TABLE``.

Examples are derandomized (the same on every run and machine, no database);
the count per entry is ``EXAMPLES`` (the run's header gives the total).
"""
from __future__ import annotations

import contextlib
import dataclasses
import importlib
import itertools
import math
import numbers
import re
import resource
import signal
import types
import warnings

import numpy as np
import pytest
import trimesh
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import noiselab
from noiselab import analysis as A
from noiselab import fractal as F
from noiselab import geometry as G
from noiselab import io as IO
from noiselab import lab as LAB
from noiselab import lattice as L
from noiselab import snowfall as S
from noiselab import spectral as SP
from noiselab import stimuli as STIM
from noiselab import testing as TST
from noiselab.spectral import envelopes as E

EXAMPLES = 25
settings.register_profile(
    "contract", max_examples=EXAMPLES, derandomize=True, database=None, deadline=None, print_blob=False,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
)
CALL_TIMEOUT_S = 120  # a single call past this is a hang (warm calls take milliseconds; a cold compile under load, tens of seconds)

NAN, INF = float("nan"), float("inf")
RNG = np.random.default_rng(2011)

# ---------------------------------------------------------------- bad values
SPECIAL_REALS = [NAN, INF, -INF, -1.0, 0.0, -0.0, 5e-324, 1e-300, 1e308, -1e308, 10**400, -(10**400), 2**63,
                 True, "1", None, 1j, [1.0], np.float32("nan"), np.float64(1e300), np.int64(-5)]
SPECIAL_INTS = [-1, 0, 1, 2, 2**31, 2**63, 2**64, 10**30, -(2**63), 1.5, NAN, INF, True, "3", None, [2],
                np.int64(2**62), np.uint64(2**64 - 1)]
SPECIAL_SHAPES = [(), (0,), (-1,), (1,), (1, 1), (2**63,), (2**31,), (2**20, 2**20, 2**20), (1.5, 2), "x", None,
                  (1, 1, 1), (0, 4, 4), (4, 0, 4), (2, 3), (3, 4, 5, 6), 7, [4, 4], (True, 4), (2**62, 2**62)]
SPECIAL_PAIRS = [(NAN, 1.0), (1.0,), (1.0, 2.0, 3.0), {1.0, 2.0}, "ab", (INF, 0.0), (2.0, 1.0), None,
                 (1e308, 1e308), (0.0, 0.0), (-1.0, 1.0), ("a", 1.0), 5, np.array([[1.0, 2.0]]), (10**400, 1),
                 (5e-324, 1e-300), (1.0, 1.0), [], {"lo": 1}]
SPECIAL_CHOICES = ["", "nope", None, 1, 1.5, ["x"], b"raise", "RAISE", NAN]
SPECIAL_SEEDS = [-1, 1.5, "x", 2**70, True, NAN, [1], -(2**63)]
SPECIAL_DTYPES = [np.int32, np.complex64, "float16", np.float16, "nope", None, object, int, 3, np.uint8]


def _array(shape_fill):
    shape, fill = shape_fill
    n = math.prod(shape)
    if fill == "random":
        return RNG.standard_normal(shape)
    if fill == "unit":
        return RNG.random(shape)
    if fill == "nan":
        a = RNG.random(shape)
        if n:
            a.flat[n // 2] = NAN
        return a
    if fill == "inf":
        a = RNG.random(shape)
        if n:
            a.flat[0] = -INF
        return a
    if fill == "huge":
        return RNG.random(shape) * 1e300
    if fill == "tiny":
        return RNG.random(shape) * 1e-310
    if fill == "zeros":
        return np.zeros(shape)
    if fill == "negative":
        return -RNG.random(shape)
    if fill == "complex":
        return RNG.random(shape) + 1j
    if fill == "str":
        return np.full(shape, "a")
    if fill == "bool":
        return RNG.random(shape) > 0.5
    if fill == "int":
        return RNG.integers(-300, 300, shape)
    if fill == "float32":
        return RNG.random(shape).astype(np.float32) * np.float32(3e38)
    raise AssertionError(fill)


ARRAY_SHAPES = [(), (0,), (3,), (5,), (0, 0), (4, 4), (1, 16), (16, 16), (5, 2), (5, 3), (5, 4), (2, 16, 16),
                (4, 16, 16), (16, 16, 3), (4, 16, 16, 3), (2, 2, 2, 2, 2), (1, 1, 1)]
ARRAY_FILLS = ["random", "unit", "nan", "inf", "huge", "tiny", "zeros", "negative", "complex", "str", "bool", "int",
               "float32"]
SPECIAL_ARRAYS = [None, "abc", 3.0, [[1.0, 2.0], [3.0]], np.array([object()]), [], {1: 2}]


def _noise_variants():
    def nan_field(p):
        return np.full(len(p), NAN)

    def wrong_shape(p):
        return np.zeros(1)

    return [None, 1, "noise", nan_field, wrong_shape, L.LatticeNoise(1), L.LatticeNoise(5), L.LatticeNoise(2, 3),
            lambda p: np.full(len(p), 1e308)]


def _mesh_variants():
    empty = trimesh.Trimesh(vertices=np.zeros((3, 3)), faces=np.zeros((0, 3), int), process=False)
    nanmesh = G.sphere(0).copy()
    nanmesh.vertices[0] = NAN
    flat = trimesh.Trimesh(vertices=np.zeros((3, 3)), faces=[[0, 1, 2]], process=False)
    return [None, "mesh", np.zeros(3), np.zeros((4, 3)), empty, nanmesh, flat, [G.sphere(0)], *HUGE_MESHES]


def _huge_mesh(scale):
    """The unit sphere scaled to coordinates of ``scale`` (edge lengths overflow float64 past about 1e154)."""
    sphere = G.sphere(0)
    return trimesh.Trimesh(vertices=sphere.vertices * scale, faces=sphere.faces, process=False)


HUGE_MESHES = [_huge_mesh(1e300), _huge_mesh(1e200), _huge_mesh(1e150)]
# images, videos and point sets of huge values (every array-taking entry gets each, see test_huge_values)
HUGE_ARRAYS = [RNG.random((16, 16)) * 1e300, RNG.random((16, 16, 3)) * 1e300, RNG.random((4, 16, 16)) * 1e300,
               np.full((16, 16, 3), np.finfo(np.float64).max), RNG.random((16, 16, 3)).astype(np.float32) * 3e38]


KINDS = {
    "real": lambda: st.one_of(st.sampled_from(SPECIAL_REALS), st.floats(allow_nan=True, allow_infinity=True),
                              st.integers(-(2**70), 2**70)),
    "int": lambda: st.one_of(st.sampled_from(SPECIAL_INTS), st.integers(-(2**66), 2**66),
                             st.floats(allow_nan=True, allow_infinity=True)),
    # a count whose valid values cost time in proportion (steps, frames): only the bad and the extreme ones
    "count": lambda: st.sampled_from([v for v in SPECIAL_INTS if not (isinstance(v, int) and 2 < v < 2**40)]),
    "shape": lambda: st.one_of(st.sampled_from(SPECIAL_SHAPES),
                               st.lists(st.integers(-2, 40), min_size=0, max_size=4).map(tuple)),
    "pair": lambda: st.one_of(st.sampled_from(SPECIAL_PAIRS),
                              st.tuples(KINDS["real"](), KINDS["real"]())),
    "choice": lambda: st.one_of(st.sampled_from(SPECIAL_CHOICES), st.text(max_size=6)),
    "rng": lambda: st.one_of(st.sampled_from(SPECIAL_SEEDS), st.integers(-(2**70), 2**70)),
    "dtype": lambda: st.sampled_from(SPECIAL_DTYPES),
    "array": lambda: st.one_of(st.sampled_from(SPECIAL_ARRAYS),
                               st.tuples(st.sampled_from(ARRAY_SHAPES), st.sampled_from(ARRAY_FILLS)).map(_array)),
    "noise": lambda: st.sampled_from(_noise_variants()),
    "mesh": lambda: st.sampled_from(_mesh_variants()),
    "bool": lambda: st.sampled_from([None, "yes", 2, NAN, [True]]),
}


# ---------------------------------------------------------------- the table
@dataclasses.dataclass
class Entry:
    """One public function: ``call(**kwargs)``, valid ``kwargs``, the kind of bad value per fuzzed parameter.

    ``check(result, kwargs)`` asserts the documented contract of a result
    (default: every number in it finite). ``names`` maps a parameter to the
    words that may name it in an error message (default: its own name).
    Values in ``valid`` that are ``Fresh`` are rebuilt for every call (inputs a
    function may modify in place).
    """

    name: str
    call: object
    valid: dict
    fuzz: dict
    check: object = None
    names: dict = dataclasses.field(default_factory=dict)

    def __post_init__(self):
        # the analysers call every input array a "field" (noiselab.analysis's documented term) in their messages
        for p in ("video", "image", "volume"):
            if p in self.fuzz and p not in self.names and self.call.__module__.startswith("noiselab.analysis"):
                self.names[p] = (p, "field")


class Fresh:
    def __init__(self, make):
        self.make = make


def finite(result, _kwargs=None):
    """Every number reachable in ``result`` (arrays, tuples, dicts, dataclasses, meshes) is finite."""
    for value in _numbers(result):
        arr = np.asarray(value)
        if arr.dtype.kind in "fc":
            assert np.isfinite(arr).all(), f"non-finite result: {arr.ravel()[:8]}"


def _numbers(obj, depth=0):
    if depth > 4 or obj is None or isinstance(obj, (str, bytes, bool, types.FunctionType)):
        return
    if isinstance(obj, (numbers.Number, np.ndarray, np.generic)):
        yield obj
    elif isinstance(obj, dict):
        for v in obj.values():
            yield from _numbers(v, depth + 1)
    elif isinstance(obj, (list, tuple)):
        for v in obj:
            yield from _numbers(v, depth + 1)
    elif isinstance(obj, trimesh.Trimesh):
        yield np.asarray(obj.vertices)
    elif dataclasses.is_dataclass(obj):
        for f in dataclasses.fields(obj):
            if not f.name.startswith("_"):
                yield from _numbers(getattr(obj, f.name), depth + 1)


def shaped(expect_shape, dtype=None, lo=None, hi=None):
    """Contract: finite, ``shape == expect_shape(kwargs)``, optional dtype and value range."""
    def check(result, kwargs):
        finite(result)
        arr = np.asarray(result)
        want = expect_shape(kwargs)
        if want is not None:
            assert arr.shape == tuple(want), (arr.shape, want)
        if dtype is not None:
            want_dtype = dtype if isinstance(dtype, (type, np.dtype, str)) else dtype(kwargs)
            assert arr.dtype == np.dtype(want_dtype), arr.dtype
        if lo is not None and arr.size:
            assert arr.min() >= lo, arr.min()
        if hi is not None and arr.size:
            assert arr.max() <= hi, arr.max()
    return check


def fraction(result, _kwargs=None):
    assert isinstance(result, float) and 0.0 <= result <= 1.0 + 1e-9, result


def nonneg_float(result, _kwargs=None):
    assert isinstance(result, float) and math.isfinite(result) and result >= 0, result


def unit_mesh_vertices(result, _kwargs=None):
    finite(result)
    assert len(result.vertices) and len(result.faces)


IMG = RNG.random((16, 16))
VID = RNG.random((4, 16, 16))
ALPHA = VID.astype(np.float32)
W3 = SP.frequency_vectors((4, 8, 8))
W2 = SP.frequency_vectors((8, 8))
MESH = G.sphere(1)
N1, N2, N3 = L.LatticeNoise(1, rng=1), L.LatticeNoise(2, rng=2), L.LatticeNoise(3, rng=3)
V2 = L.LatticeNoise(2, 2, rng=4)
NI = L.LatticeNoise(2, 3, rng=5, hash="integer")
PTS2 = RNG.uniform(-4, 4, (5, 2))
MASK = np.zeros((16, 16), bool)
MASK[:, 8:] = True


def _shape_of(key, default=None):
    return lambda kw: tuple(np.atleast_1d(kw.get(key, default)))


def _lattice_call(dim_in=2, dim_out=1, points=None, **kw):
    noise = L.LatticeNoise(dim_in, dim_out, **kw)
    pts = np.zeros((3, noise.dim_in)) + 0.3 if points is None else points
    return noise(pts)


def _lattice_check(result, kw):
    finite(result)
    amp = kw.get("amplitude", 1.0)
    assert np.abs(result).max() <= amp * (1 + 1e-12)
    d_out = kw.get("dim_out", 1)
    assert result.shape == ((3,) if d_out == 1 else (3, d_out))


def _islice(gen, n=3):
    return list(itertools.islice(gen, n))


def _env(func, nw):
    """An envelope taking ``nw`` frequency arrays first: they are fuzzed as w0, w1, ..."""
    def call(**kw):
        ws = [kw.pop(f"w{i}") for i in range(nw)]
        return func(*ws, **kw)
    return call


def _env_entry(name, func, ws, valid, fuzz, **extra):
    valid = {**{f"w{i}": w for i, w in enumerate(ws)}, **valid}
    fuzz = {**{f"w{i}": "array" for i in range(len(ws))}, **fuzz}
    names = {f"w{i}": (n,) for i, n in enumerate(extra.pop("wnames", [f"w[{i}]" for i in range(len(ws))]))}
    names.update({f"w{i}": names[f"w{i}"] + ("frequency arrays",) for i in range(len(ws))})
    return Entry(name, _env(func, len(ws)), valid, fuzz, names=names, **extra)


SNOW_VALID = dict(shape=(4, 16, 16), rng=0, c=1.0, band=None, thickness=0.1, direction_yx=(1.0, 0.0),
                  pan_yx=(0.0, 0.0), beta=1.5, exponent=1.0, amplitude_distribution="uniform", dtype=np.float32,
                  on_alias="drop")
SNOW_FUZZ = dict(shape="shape", rng="rng", c="real", band="pair", thickness="real", direction_yx="pair", pan_yx="pair",
                 beta="real", exponent="real", amplitude_distribution="choice", dtype="dtype", on_alias="choice")
GEO_FIELD = dict(amplitude="real", frequency="real", phase="real")

TABLE = [
    # ------------------------------------------------------------ spectral
    Entry("spectral_noise", SP.spectral_noise,
          dict(shape=(16, 16), exponent=1.0, band=None, rng=0, amplitude_distribution="rayleigh", dtype=np.float32),
          dict(shape="shape", exponent="real", band="pair", rng="rng", amplitude_distribution="choice", dtype="dtype"),
          shaped(_shape_of("shape"), dtype=lambda kw: kw["dtype"])),
    Entry("synthesize", SP.synthesize, dict(shape=(8, 8), envelope=E.power_law, rng=0),
          dict(shape="shape", envelope="noise", rng="rng", amplitude_distribution="choice", dtype="dtype",
               normalize="choice"),
          shaped(_shape_of("shape"))),
    Entry("frequency_vectors", SP.frequency_vectors, dict(shape=(4, 8)), dict(shape="shape", dtype="dtype")),
    Entry("half_spectrum_shape", SP.half_spectrum_shape, dict(shape=(4, 8)), dict(shape="shape")),
    _env_entry("radial_frequency", E.radial_frequency, W2, {}, {}),
    _env_entry("power_law", E.power_law, W2, dict(exponent=1.0), dict(exponent="real")),
    _env_entry("annulus", E.annulus, W2, dict(band_cycles_per_sample=(0.1, 0.3)), dict(band_cycles_per_sample="pair"),
               check=shaped(lambda kw: None, lo=0, hi=1)),
    _env_entry("motion_plane", E.motion_plane, W3, dict(velocity_yx=(0.0, 1.0), tol=0.5),
               dict(velocity_yx="pair", tol="real"), wnames=["wt", "wy", "wx"]),
    _env_entry("optical_snow", E.optical_snow, W3, dict(direction_yx=(1.0, 0.0), speeds=(0.5, 2.0), tol=0.5),
               dict(direction_yx="pair", speeds="pair", tol="real"), wnames=["wt", "wy", "wx"]),
    _env_entry("nonparallel_optical_snow", E.nonparallel_optical_snow, W3,
               dict(direction_yx=(1.0, 0.0), speeds=(0.5, 2.0), pan_yx=(0.0, 1.0), tol=0.5),
               dict(direction_yx="pair", speeds="pair", pan_yx="pair", tol="real"), wnames=["wt", "wy", "wx"]),
    _env_entry("tent_surface", E.tent_surface, W2, dict(c=1.0, direction_yx=(1.0, 0.0), pan_yx=(0.0, 0.0)),
               dict(c="real", direction_yx="pair", pan_yx="pair"), wnames=["wy", "wx"]),
    _env_entry("tent", E.tent, W3, dict(c=1.0, direction_yx=(1.0, 0.0), tol=0.5),
               dict(c="real", direction_yx="pair", tol="real"), wnames=["wt", "wy", "wx"]),
    _env_entry("thickened_tent", E.thickened_tent, W3,
               dict(c=1.0, direction_yx=(1.0, 0.0), pan_yx=(0.0, 0.0), thickness=0.1, tol=0.5),
               dict(c="real", direction_yx="pair", pan_yx="pair", thickness="real", tol="real"),
               wnames=["wt", "wy", "wx"]),
    _env_entry("sheared_tent", E.sheared_tent, W3, dict(c=1.0, direction_yx=(1.0, 0.0), pan_yx=(0.0, 1.0), tol=0.5),
               dict(c="real", direction_yx="pair", pan_yx="pair", tol="real"), wnames=["wt", "wy", "wx"]),
    Entry("unit_direction", E.unit_direction, dict(direction=(3.0, 4.0)), dict(direction="pair"),
          lambda r, kw: np.testing.assert_allclose(np.hypot(*r), 1.0)),
    # ---------------------------------------------------------------- snow
    Entry("snow", S.snow, SNOW_VALID, SNOW_FUZZ,
          shaped(_shape_of("shape"), dtype=lambda kw: kw["dtype"], lo=0.0, hi=1.0)),
    Entry("snow_spectrum", S.snow_spectrum, {k: v for k, v in SNOW_VALID.items() if k != "beta"},
          {k: v for k, v in SNOW_FUZZ.items() if k != "beta"}),
    Entry("rescale_opacity", S.rescale_opacity, dict(field=Fresh(lambda: IMG.copy()), beta=1.5),
          dict(field="array", beta="real", lo="real", hi="real"), shaped(lambda kw: None, lo=0.0, hi=1.0)),
    Entry("composite", S.composite, dict(alpha=ALPHA, background=np.zeros((16, 16), np.uint8), intensity=250),
          dict(alpha="array", background="array", intensity="real"), shaped(lambda kw: None, lo=0, hi=255)),
    Entry("parallax_composite", S.parallax_composite, dict(foreground=ALPHA, mask=MASK),
          dict(foreground="array", mask="array", transmittance="real", veil="real", veiled_foreground="array"),
          lambda r, kw: (finite(r), [fraction(v) for v in r[1].values()])),
    Entry("michelson_contrast", S.michelson_contrast, dict(x=IMG), dict(x="array", mask="array"), fraction),
    Entry("tile", S.tile, dict(alpha=ALPHA, reps=(1, 2, 1)), dict(alpha="array", reps="shape"),
          shaped(lambda kw: None)),
    Entry("iter_tiled_frames", lambda **kw: _islice(S.iter_tiled_frames(**kw)), dict(alpha=ALPHA, reps=(2, 1)),
          dict(alpha="array", reps="shape", n_frames="int", start="int", crop="pair")),
    Entry("flake_speeds", S.flake_speeds, dict(c=1.0, band=(2, 8), width=32),
          dict(c="real", band="pair", width="int", height="int"),
          lambda r, kw: (finite(r), np.testing.assert_array_less(-1e-300, r))),
    # ------------------------------------------------------------- lattice
    Entry("LatticeNoise", _lattice_call, dict(dim_in=2, dim_out=1, rng=0),
          dict(dim_in="int", dim_out="int", rng="rng", kernel="choice", basis="choice", table_size="int",
               period="int", frequency="real", phase="real", amplitude="real", alternation="choice",
               hash="choice"),
          _lattice_check),
    Entry("LatticeNoise.__call__", lambda points, **kw: N2(points, **kw), dict(points=PTS2),
          dict(points="array", dtype="dtype", workers="int"),
          lambda r, kw: (finite(r), np.testing.assert_array_less(np.abs(r), 1 + 1e-12))),
    Entry("LatticeNoise.grid", lambda **kw: N2.grid(**kw), dict(shape=(4, 5), extent=[(0, 1), (0, 2)]),
          dict(shape="shape", extent="array", dtype="dtype", window="array"),
          lambda r, kw: (finite(r), np.testing.assert_array_less(np.abs(r), 1 + 1e-12))),
    # the derivative paths (points, grid; the table and the integer hash)
    Entry("LatticeNoise.gradient", lambda points, **kw: N2.gradient(points, **kw), dict(points=PTS2),
          dict(points="array", workers="int")),
    Entry("LatticeNoise(hash='integer').jacobian", lambda points, **kw: NI.jacobian(points, **kw),
          dict(points=PTS2), dict(points="array", workers="int")),
    Entry("LatticeNoise.jacobian_grid", lambda **kw: V2.jacobian_grid(**kw), dict(shape=(4, 5), extent=[(0, 1), (0, 2)]),
          dict(shape="shape", extent="array", window="array"), shaped(lambda kw: None)),
    Entry("grid_coordinates", L.grid_coordinates, dict(shape=(4,), extent=[(0, 2)]),
          dict(shape="shape", extent="array")),
    Entry("get_kernel", L.get_kernel, dict(kernel="cubic"), dict(kernel="choice"),
          lambda r, kw: finite(r.coef)),
    Entry("kernel_names", L.kernel_names, {}, {}, lambda r, kw: r and all(isinstance(n, str) for n in r)),
    Entry("fractal_sum", F.fractal_sum, dict(noise=N2, x=PTS2, octaves=4),
          dict(noise="noise", x="array", octaves="int", lacunarity="real", gain="real", dtype="dtype",
               spacing="real", workers="int")),
    Entry("turbulence", F.turbulence, dict(noise=N2, x=PTS2, octaves=4),
          dict(noise="noise", x="array", octaves="int", lacunarity="real", gain="real", dtype="dtype",
               spacing="real", workers="int"),
          lambda r, kw: (finite(r), np.testing.assert_array_less(-1e-300, np.asarray(r) + 1e-300))),
    Entry("fractal_sum(Grid)", lambda shape, **kw: F.fractal_sum(N2, L.Grid(shape, [(0, 1), (0, 1)]), **kw),
          dict(shape=(4, 4), octaves=4), dict(shape="shape", octaves="int", lacunarity="real", gain="real")),
    Entry("octaves_used", F.octaves_used, dict(octaves=8, spacing=0.1),
          dict(octaves="int", lacunarity="real", gain="real", spacing="real", frequency="real", dtype="dtype"),
          lambda r, kw: isinstance(r, int) and 0 <= r <= kw["octaves"]),
    # ------------------------------------------------------------ geometry
    Entry("displace", G.displace, dict(mesh=MESH, field=N3, amplitude=0.1, on_alias="ignore"),
          dict(mesh="mesh", field="noise", **GEO_FIELD, time="real", octaves="int", kind="choice",
               lacunarity="real", gain="real", direction="choice", samples_per_period="real",
               on_alias="choice"), unit_mesh_vertices),
    Entry("displace_frames", lambda **kw: _islice(G.displace_frames(**kw)),
          dict(mesh=MESH, field=L.LatticeNoise(4), times=[0.0, 0.5], amplitude=0.1, on_alias="ignore"),
          dict(mesh="mesh", field="noise", times="array", **GEO_FIELD)),
    Entry("evaluate_field", G.evaluate_field, dict(field=N2, points=PTS2),
          dict(field="noise", points="array", components="int", chunk_size="int")),
    Entry("field_max_frequency", G.field_max_frequency, dict(field=N2), dict(field="noise"),
          lambda r, kw: r > 0 and math.isfinite(r)),
    Entry("flow_field", G.flow_field, dict(field=V2, shape=(4, 4)),
          dict(field="noise", shape="shape", extent="array", **GEO_FIELD)),
    Entry("flow_glyphs", G.flow_glyphs, dict(field=L.LatticeNoise(3, 3), shape=(2, 2, 2)),
          dict(field="noise", shape="shape", extent="array", **GEO_FIELD, scale="real")),
    Entry("grid_points", G.grid_points, dict(shape=(3, 4), extent=((0, 1), (0, 1))),
          dict(shape="shape", extent="array")),
    Entry("height_map", G.height_map, dict(field=N2, shape=(6, 6), on_alias="ignore"),
          dict(field="noise", shape="shape", extent="array", **GEO_FIELD, octaves="int", kind="choice",
               lacunarity="real", gain="real", samples_per_period="real", on_alias="choice")),
    Entry("height_map_image", G.height_map_image, dict(heights=IMG), dict(heights="array", vmin="real", vmax="real"),
          shaped(lambda kw: None, dtype=np.uint8)),
    Entry("monge_surface", G.monge_surface, dict(field=N2, shape=(6, 6), on_alias="ignore"),
          dict(field="noise", shape="shape", extent="array", **GEO_FIELD, octaves="int", kind="choice",
               lacunarity="real", gain="real", samples_per_period="real"), unit_mesh_vertices),
    Entry("colored_surface", G.colored_surface, dict(field=V2, shape=(6, 6), on_alias="ignore"),
          dict(field="noise", shape="shape", extent="array", **GEO_FIELD, color="choice", value_range="pair",
               saturation="real", value="real", samples_per_period="real"), unit_mesh_vertices),
    Entry("noisy_arc", G.noisy_arc, dict(field=N1, theta=np.linspace(0, 1, 8)),
          dict(field="noise", theta="array", radius="real", **GEO_FIELD, mode="choice")),
    Entry("noisy_circle", G.noisy_circle, dict(field=N2, n=16),
          dict(field="noise", n="int", radius="real", **GEO_FIELD, mode="choice")),
    Entry("normalize", G.normalize, dict(mesh=Fresh(lambda: MESH.copy())), dict(mesh="mesh", size="real"),
          unit_mesh_vertices),
    Entry("octave_field", lambda **kw: G.octave_field(**kw)(PTS2), dict(field=N2, octaves=3),
          dict(field="noise", octaves="int", kind="choice", lacunarity="real", gain="real"),
          names={"field": ("field", "x", "points")}),   # the octave field is then called on 2-D points

    Entry("plane", G.plane, dict(resolution=4), dict(resolution="int", size="real"), unit_mesh_vertices),
    Entry("resolution_report", G.resolution_report, dict(mesh=MESH, max_frequency=2.0),
          dict(mesh="mesh", max_frequency="real", samples_per_period="real")),
    Entry("sampled_field", lambda points=PTS2, **kw: G.sampled_field(**kw)(points), dict(values=IMG),
          dict(values="array", extent="array", order="int", max_frequency="real", points="array")),
    Entry("sphere", G.sphere, dict(subdivisions=1), dict(subdivisions="int", radius="real", center="array"),
          unit_mesh_vertices),
    Entry("sphere_for_noise", G.sphere_for_noise, dict(max_frequency=0.5, max_subdivisions=3),
          dict(max_frequency="real", radius="real", samples_per_period="real", max_subdivisions="int"),
          unit_mesh_vertices),
    Entry("squashed_sphere", G.squashed_sphere, dict(subdivisions=1),
          dict(squash="real", subdivisions="int", radius="real", axis="int"), unit_mesh_vertices),
    Entry("streamlines", G.streamlines, dict(field=V2, seeds=np.zeros((2, 2)), n_steps=5),
          dict(field="noise", seeds="array", step="real", n_steps="count", **GEO_FIELD, method="choice")),
    Entry("subdivide_for_noise", G.subdivide_for_noise, dict(mesh=MESH, max_frequency=1.0),
          dict(mesh="mesh", max_frequency="real", samples_per_period="real", method="choice", max_faces="int"),
          unit_mesh_vertices),
    Entry("trajectory", G.trajectory, dict(field=L.LatticeNoise(1, 2), t=np.linspace(0, 1, 5)),
          dict(field="noise", t="array", **GEO_FIELD, dims="int")),
    Entry("vertex_normals", G.vertex_normals, dict(mesh=MESH), dict(mesh="mesh"),
          # unit normals; 0 where a vertex touches only zero-area faces (its normal is undefined)
          lambda r, kw: (finite(r), np.testing.assert_array_less(np.abs(np.linalg.norm(r, axis=1) - 0.5), 0.5 + 1e-9))),
    Entry("arrange", G.arrange, dict(meshes=[MESH, MESH]), dict(meshes="mesh", columns="int", spacing="real")),
    Entry("as_trimesh", G.as_trimesh, dict(mesh=MESH), dict(mesh="mesh"), unit_mesh_vertices),
    # ------------------------------------------------------------------ io
    Entry("to_uint8", IO.to_uint8, dict(array=IMG), dict(array="array", vmin="real", vmax="real"),
          shaped(lambda kw: None, dtype=np.uint8)),
    # ----------------------------------------------------------------- lab
    Entry("layered_lattice_snow", LAB.layered_lattice_snow, dict(shape=(4, 16, 16), rng=0, layers=2),
          dict(shape="shape", rng="rng", c="real", band="pair", layers="int", direction_yx="pair", kernel="choice",
               exponent="real", beta="real", dtype="dtype", start="int"),
          shaped(_shape_of("shape"), lo=0.0, hi=1.0)),
    Entry("particle_snow", LAB.particle_snow, dict(shape=(4, 16, 16), rng=0, flakes=20),
          dict(shape="shape", rng="rng", c="real", band="pair", flakes="int", direction_yx="pair",
               opacity="real", dtype="dtype"),
          shaped(_shape_of("shape"), lo=0.0, hi=1.0)),
    Entry("layer_plan", LAB.layer_plan, dict(shape=(4, 16, 16), layers=2),
          dict(shape="shape", c="real", band="pair", layers="int", kernel="choice", exponent="real")),
    Entry("lattice_peak", LAB.lattice_peak, dict(), dict(kernel="choice", basis="choice"),
          lambda r, kw: 0 < r < 1),
    # ------------------------------------------------------------ analysis
    Entry("power_spectrum", A.power_spectrum, dict(field=IMG),
          dict(field="array", window="choice", axes="shape", window_axes="shape", min_size="int")),
    Entry("power_band", A.power_band, dict(field=IMG),
          dict(field="array", drop="real", window="choice", axes="shape")),
    Entry("radial_spectrum", A.radial_spectrum, dict(field=IMG),
          dict(field="array", bins="int", window="choice", axes="shape", fmax="real")),
    Entry("spatiotemporal_spectrum", A.spatiotemporal_spectrum, dict(video=VID),
          dict(video="array", bins="int", window="choice")),
    Entry("band_energy", A.band_energy, dict(field=IMG, band=(2, 6)),
          dict(field="array", band="pair", window="choice", axes="shape"), fraction),
    Entry("spectral_slope", A.spectral_slope, dict(field=IMG),
          dict(field="array", band="pair", bins_per_octave="int", window="choice", axes="shape")),
    Entry("octave_energy", A.octave_energy, dict(field=IMG),
          dict(field="array", band="pair", window="choice", axes="shape")),
    Entry("orientation_energy", A.orientation_energy, dict(image=IMG),
          dict(image="array", band="pair", nbins="int", window="choice")),
    Entry("anisotropy", A.anisotropy, dict(image=IMG), dict(image="array", band="pair", nbins="int", window="choice")),
    Entry("motion_energy", A.motion_energy, dict(video=VID),
          dict(video="array", velocity_yx="pair", tol="real", band="pair", window="choice"), fraction),
    Entry("tent_energy", A.tent_energy, dict(video=VID, c=1.0, band=(2, 6)),
          dict(video="array", c="real", band="pair", direction_yx="pair", pan_yx="pair", thickness="real", tol="real"),
          fraction),
    Entry("sheared_tent_energy", A.sheared_tent_energy, dict(video=VID, c=1.0, band=(2, 6)),
          dict(video="array", c="real", band="pair", direction_yx="pair", pan_yx="pair", thickness="real", tol="real"),
          fraction),
    Entry("best_velocity", A.best_velocity, dict(video=VID), dict(video="array", band="pair", window="choice")),
    Entry("band_speeds", A.band_speeds, dict(video=VID, bands=[(2, 4), (4, 8)]),
          dict(video="array", bands="array", window="choice")),
    Entry("speed_profile", A.speed_profile, dict(video=VID),
          dict(video="array", bands="array", window="choice", min_energy="real", per_octave="real")),
    Entry("octave_bands", A.octave_bands, dict(lo=2, hi=16), dict(lo="real", hi="real", per_octave="real"),
          lambda r, kw: (finite(r), all(a < b for a, b in r))),
    Entry("video_spectrum", A.video_spectrum, dict(video=VID), dict(video="array", window="choice")),
    Entry("loop_seam", A.loop_seam, dict(video=VID), dict(video="array"), nonneg_float),
    Entry("tile_seam", A.tile_seam, dict(image=IMG), dict(image="array", tile="pair"), nonneg_float),
    Entry("analysis.michelson_contrast", A.michelson_contrast, dict(x=IMG), dict(x="array", mask="array"), fraction),
    Entry("rms_contrast", A.rms_contrast, dict(x=IMG), dict(x="array", mask="array"), nonneg_float),
    Entry("to_grey", A.to_grey, dict(x=RNG.random((4, 4, 3))), dict(x="array")),
]



def _fractions(*names, hi=1.0):
    """Contract: finite, and the named attributes (numbers or arrays) within [0, hi] (up to rounding)."""
    def check(result, _kwargs=None):
        finite(result)
        for name in names:
            v = result
            for part in name.split("."):
                v = getattr(v, part)
            v = np.asarray(np.nan if v is None else v, dtype=np.float64)   # None fails too
            assert v.size == 0 or (v.min() >= -1e-12 and v.max() <= hi + 1e-9), (name, v)
    return check


def _unit_rows(upward=False, allow_zero=False):
    """Contract: finite unit vectors (rows of length 1; 0 allowed where a normal is undefined), n_z >= 0 if upward."""
    def check(result, _kwargs=None):
        finite(result)
        norm = np.linalg.norm(np.asarray(result), axis=-1)
        ok = np.abs(norm - 1) < 1e-9
        if allow_zero:
            ok |= norm == 0
        assert ok.all(), norm[~ok][:8]
        if upward:
            assert np.asarray(result)[..., 2].min() >= 0
    return check


# analysis.quality and the derivatives
VID3 = RNG.random((4, 16, 16))
TABLE += [
    Entry("axis_artefacts", A.axis_artefacts, dict(image=IMG), dict(image="array", band="pair", window="choice"),
          _fractions("axis_power")),
    Entry("band_leakage", A.band_leakage, dict(field=IMG, band=(2, 6)),
          dict(field="array", band="pair", oversample="int", window="choice"),
          _fractions("below", "inside", "above", "aliased", "octaves", "octaves_aliased")),
    Entry("detect_period", A.detect_period, dict(field=np.tile(IMG[:, :4], (1, 4))),
          dict(field="array", axis="int", tol="real", max_lag="int", min_lag="int")),
    Entry("envelope_error", A.envelope_error,
          dict(field=IMG, target=lambda *w: np.ones(np.broadcast_shapes(*(x.shape for x in w)))),
          dict(field="array", target="noise", groups="int", support="real", window="choice"),
          _fractions("outside")),
    Entry("ring_anisotropy", A.ring_anisotropy, dict(image=IMG),
          dict(image="array", band="pair", window="choice", min_cells="int")),
    Entry("shell_slice_below", A.shell_slice_below, dict(lo=2.0, hi=8.0), dict(lo="real", hi="real", exponent="real"),
          fraction),
    Entry("slice_leakage", A.slice_leakage, dict(volume=VID3, band=(2, 6)),
          dict(volume="array", band="pair", axis="int", window="choice"),
          _fractions("volume.inside", "slices.inside", "slices.below")),
    Entry("tent_energy_per_band", A.tent_energy_per_band, dict(video=VID, c=1.0, band=(2, 8)),
          dict(video="array", c="real", band="pair", direction_yx="pair", per_octave="real", thickness="real",
               tol="real"),
          _fractions("fraction", "share")),
    Entry("value_statistics", A.value_statistics, dict(field=IMG, bounds=(-1, 2)),
          dict(field="array", variance="real", bounds="pair"),
          lambda r, kw: (finite(r), kw["bounds"] is None or r.range_used >= 0)),
    Entry("variance_striping", A.variance_striping, dict(field=IMG, period=4),
          dict(field="array", period="int", axis="int", phases="int"), nonneg_float),
    Entry("fractal_gradient", F.fractal_gradient, dict(noise=N2, x=PTS2, octaves=3),
          dict(noise="noise", x="array", octaves="int", lacunarity="real", gain="real", spacing="real",
               workers="int")),
    Entry("turbulence_gradient", F.turbulence_gradient, dict(noise=N2, x=PTS2, octaves=3),
          dict(noise="noise", x="array", octaves="int", lacunarity="real", gain="real", spacing="real",
               workers="int")),
    Entry("curl_noise", noiselab.curl_noise, dict(noise=N2, points=PTS2),
          dict(noise="noise", points="array", octaves="int", lacunarity="real", gain="real")),
    Entry("warp", lambda points=PTS2, **kw: noiselab.warp(**kw)(points), dict(noise=N2, warp_noise=V2),
          dict(noise="noise", warp_noise="noise", amount="real", points="array"),
          lambda r, kw: (finite(r), np.testing.assert_array_less(np.abs(r), 1 + 1e-12)),
          names={"noise": ("noise", "points", "dim_in"), "warp_noise": ("warp_noise", "noise", "points", "dim_in")}),
    Entry("monge_normals", noiselab.monge_normals, dict(field=N2, points=PTS2),
          dict(field="noise", points="array", **GEO_FIELD, octaves="int", kind="choice", lacunarity="real",
               gain="real"), _unit_rows(upward=True)),
    Entry("displaced_normals", noiselab.displaced_normals, dict(mesh=MESH, field=N3, amplitude=0.1),
          dict(mesh="mesh", field="noise", **GEO_FIELD, octaves="int", kind="choice", lacunarity="real",
               gain="real", normals="array", curvature="real"), _unit_rows(allow_zero=True)),
    Entry("normal_angles", noiselab.normal_angles, dict(a=np.eye(3), b=np.eye(3)[::-1].copy()),
          dict(a="array", b="array"),
          lambda r, kw: (finite(r), np.testing.assert_array_less(np.asarray(r), 180 + 1e-9),
                         np.testing.assert_array_less(-1e-12, np.asarray(r)))),
]

# the spectral engine's building blocks (spectral/synthesis.py)
TABLE += [
    Entry("hermitian_plane", SP.hermitian_plane, dict(plane=RNG.standard_normal((4, 5)) + 1j),
          dict(plane="array", support="array"), shaped(lambda kw: np.shape(kw["plane"]))),
    Entry("draw_coefficients", SP.draw_coefficients, dict(n=16, rng=np.random.default_rng(0)),
          dict(n="int", rng="rng", amplitude_distribution="choice", dtype="dtype"),
          shaped(lambda kw: (kw["n"],))),
]

# stimuli in physical units
DISPLAY = STIM.Display(32.0, frame_rate=60.0, luminance=(0.5, 100.0), gamma=2.2, bits=8)


def _uint_of(kw):
    return np.uint8 if kw.get("display", DISPLAY).bits <= 8 else np.uint16


def _display_method(name):
    def call(display=DISPLAY, **kw):
        return getattr(display, name)(**kw)
    return call


def _gamma_table(display):
    """A gamma law's table: the law itself, rising from L_min to L_max, never falling (at steep gammas the darkest
    levels may round to one float64 luminance: gamma 8 over 0.5-100 cd/m² gives levels 0 and 1 both 0.5)."""
    t, (lo, hi) = display.table, display.luminance
    law = lo + (hi - lo) * (np.arange(display.levels) / (display.levels - 1)) ** display.gamma
    np.testing.assert_allclose(t, law, rtol=1e-12, atol=0)
    assert t[0] == lo and t[-1] == hi and hi > lo and np.all(np.diff(t) >= 0), t


TABLE += [
    Entry("Display", STIM.Display, dict(pixels_per_degree=32.0, frame_rate=60.0, luminance=(0.5, 100.0), gamma=2.2,
                                        bits=8),
          dict(pixels_per_degree="real", frame_rate="real", luminance="pair", gamma="real", bits="int"),
          lambda r, kw: (finite(r.table), _gamma_table(r))),
    Entry("Display.from_lut", STIM.Display.from_lut, dict(lut=np.linspace(0.5, 90.0, 16), pixels_per_degree=30.0),
          dict(lut="array", pixels_per_degree="real", frame_rate="real"),
          lambda r, kw: np.testing.assert_array_less(0, np.diff(r.table))),
    Entry("Display.from_geometry", STIM.Display.from_geometry,
          dict(distance_cm=57.0, screen_width_cm=40.0, resolution_px=1920),
          dict(distance_cm="real", screen_width_cm="real", resolution_px="int"),
          lambda r, kw: finite(r.pixels_per_degree)),
    Entry("Display.luminance_of", _display_method("luminance_of"), dict(values=np.arange(256)),
          dict(values="array"), lambda r, kw: (finite(r), np.testing.assert_array_less(0.49, r))),
    Entry("Display.value_of", _display_method("value_of"), dict(luminance=np.linspace(1, 99, 7)),
          dict(luminance="array"), shaped(lambda kw: np.shape(kw["luminance"]), lo=0, hi=255)),
    Entry("Display.cycles_per_frame", _display_method("cycles_per_frame"), dict(cycles_per_degree=4.0, size=256),
          dict(cycles_per_degree="real", size="real")),
    Entry("Display.snow_c", _display_method("snow_c"), dict(deg_per_second=2.0, cycles_per_degree=4.0),
          dict(deg_per_second="real", cycles_per_degree="real")),
    Entry("Display.band", _display_method("band"), dict(band_cycles_per_degree=(1.0, 4.0), size=128),
          dict(band_cycles_per_degree="pair", size="real"), names=dict(band_cycles_per_degree=("band",))),
    Entry("stimuli.to_display", STIM.to_display,
          dict(field=IMG, display=DISPLAY, mean=40.0, contrast=0.2, contrast_kind="rms", dither=True, rng=0),
          dict(field="array", mean="real", contrast="real", contrast_kind="choice", dither="bool", rng="rng",
               clip="real", full_output="bool", aperture="array"),
          shaped(lambda kw: np.shape(kw["field"]), dtype=_uint_of)),
    Entry("stimuli.circular_aperture", STIM.circular_aperture, dict(shape=(16, 16), display=DISPLAY, diameter_deg=0.3),
          dict(shape="shape", diameter_deg="real"), shaped(lambda kw: tuple(kw["shape"])[-2:], lo=0, hi=1)),
    Entry("stimuli.raised_cosine_aperture", STIM.raised_cosine_aperture,
          dict(shape=(16, 16), display=DISPLAY, diameter_deg=0.4, ramp_deg=0.1),
          dict(shape="shape", diameter_deg="real", ramp_deg="real"),
          shaped(lambda kw: tuple(kw["shape"])[-2:], lo=0, hi=1)),
    Entry("stimuli.B_sf_from_octaves", STIM.B_sf_from_octaves, dict(sf_0=0.1, sf_bandwidth_octaves=1.0),
          dict(sf_0="real", sf_bandwidth_octaves="real"), lambda r, kw: (finite(r), np.testing.assert_array_less(-1e-300, r))),
    Entry("stimuli.octaves_from_B_sf", STIM.octaves_from_B_sf, dict(sf_0=0.1, B_sf=0.05),
          dict(sf_0="real", B_sf="real"), lambda r, kw: (finite(r), np.testing.assert_array_less(-1e-300, r))),
    Entry("stimuli.B_theta_from_hwhm", STIM.B_theta_from_hwhm, dict(orientation_hwhm_deg=15.0),
          dict(orientation_hwhm_deg="real"), lambda r, kw: (finite(r), np.testing.assert_array_less(-1e-300, r))),
    Entry("stimuli.hwhm_from_B_theta", STIM.hwhm_from_B_theta, dict(B_theta=0.2), dict(B_theta="real"),
          lambda r, kw: np.testing.assert_array_less(-1e-300, r)),
    Entry("stimuli.gaussian_aperture", STIM.gaussian_aperture, dict(shape=(16, 16), display=DISPLAY, sigma_deg=0.1),
          dict(shape="shape", sigma_deg="real"), shaped(lambda kw: tuple(kw["shape"])[-2:], lo=0, hi=1)),
    Entry("stimuli.luminance_for", STIM.luminance_for,
          dict(field=IMG, mean=40.0, contrast=0.2, contrast_kind="michelson"),
          dict(field="array", mean="real", contrast="real", contrast_kind="choice", clip="real",
               aperture="array", full_output="bool"),
          shaped(lambda kw: np.shape(kw["field"]), lo=0)),
    Entry("stimuli.trial_seeds", STIM.trial_seeds, dict(trials=3, rng=0), dict(trials="int", rng="rng"),
          lambda r, kw: (finite(r), np.testing.assert_equal(len(set(r)), kw["trials"]))),
    Entry("stimuli.phase_scramble", STIM.phase_scramble, dict(x=IMG, rng=0), dict(x="array", rng="rng"),
          shaped(lambda kw: np.shape(kw["x"]))),
    Entry("stimuli.amplitude_swap", STIM.amplitude_swap, dict(amplitude_from=IMG, phase_from=IMG[::-1].copy()),
          dict(amplitude_from="array", phase_from="array"), shaped(lambda kw: np.shape(kw["amplitude_from"]))),
    Entry("stimuli.motion_cloud", STIM.motion_cloud,
          dict(shape=(4, 16, 16), sf_0=0.15, B_sf=0.1, theta=0.5, B_theta=0.3, V_X=1.0, V_Y=0.0, B_V=0.5, rng=0),
          dict(shape="shape", sf_0="real", B_sf="real", theta="real", B_theta="real", V_X="real", V_Y="real",
               B_V="real", rng="rng", alpha="real", dtype="dtype"),
          shaped(_shape_of("shape"))),
    Entry("stimuli.cloud_envelope", STIM.cloud_envelope, dict(shape=(4, 16, 16), sf_0=0.15, B_sf=0.1),
          dict(shape="shape", sf_0="real", B_sf="real", theta="real", B_theta="real", B_V="real", alpha="real"),
          lambda r, kw: (finite(r), np.testing.assert_array_less(-1e-300, r))),
    _env_entry("log_gabor", E.log_gabor, W2, dict(sf_0=0.15, B_sf=0.1), dict(sf_0="real", B_sf="real"),
               check=shaped(lambda kw: None, lo=0, hi=1)),
    _env_entry("orientation", E.orientation, W2, dict(theta=0.3, B_theta=0.2), dict(theta="real", B_theta="real"),
               check=shaped(lambda kw: None, lo=0, hi=1), wnames=["wy", "wx"]),
    _env_entry("speed_envelope", E.speed_envelope, W3, dict(velocity_yx=(0.5, 1.0), B_V=0.5),
               dict(velocity_yx="pair", B_V="real"), check=shaped(lambda kw: None, lo=0, hi=1),
               wnames=["wt", "wy", "wx"]),
]


# the spectral assertions (noiselab.testing): a valid call may pass (the measurement) or fail the
# property (AssertionError, its message the result); bad input is a ValueError/TypeError naming the parameter
def _asserting(func):
    def call(**kw):
        try:
            return func(**kw)
        except AssertionError as exc:
            assert str(exc), "an assertion without a message"
            return str(exc)
    call.__module__ = func.__module__
    return call


PINK64 = SP.spectral_noise((64, 64), exponent=1.0, rng=1)
TABLE += [
    Entry("assert_power_law", _asserting(TST.assert_power_law), dict(field=PINK64, exponent=1.0),
          dict(field="array", exponent="real", band="pair", tol="real", false_alarm="real", window="choice")),
    Entry("assert_band_limited", _asserting(TST.assert_band_limited), dict(field=PINK64, band=(2, 16)),
          dict(field="array", band="pair", max_leakage="real", window="choice")),
    Entry("assert_isotropic", _asserting(TST.assert_isotropic), dict(field=PINK64),
          dict(field="array", band="pair", tol="real", false_alarm="real", window="choice")),
    Entry("assert_no_axis_artefacts", _asserting(TST.assert_no_axis_artefacts), dict(field=PINK64),
          dict(field="array", band="pair", false_alarm="real", window="choice")),
    Entry("assert_motion", _asserting(TST.assert_motion), dict(video=VID, velocity_yx=(0.0, 1.0)),
          dict(video="array", velocity_yx="pair", min_energy="real", tol="real", band="pair", window="choice")),
    Entry("assert_velocity", _asserting(TST.assert_velocity), dict(video=VID, vx=1.0, vy=0.0),
          dict(video="array", vx="real", vy="real", tol="real", false_alarm="real", band="pair", window="choice")),
    Entry("assert_orientation", _asserting(TST.assert_orientation), dict(field=PINK64, orientation_deg=30.0),
          dict(field="array", orientation_deg="real", tol="real", false_alarm="real", band="pair", window="choice")),
    Entry("assert_centre_frequency", _asserting(TST.assert_centre_frequency), dict(field=PINK64, sf_0=0.1),
          dict(field="array", sf_0="real", tol="real", false_alarm="real", band="pair", window="choice")),
    Entry("assert_tent", _asserting(TST.assert_tent), dict(video=VID, c=1.0, band=(2, 8)),
          dict(video="array", c="real", band="pair", direction_yx="pair", pan_yx="pair", thickness="real", tol="real",
               min_energy="real", window="choice")),
    Entry("assert_seamless", _asserting(TST.assert_seamless), dict(array=PINK64),
          dict(array="array", axes="shape", period="shape", false_alarm="real")),
]

# Parameters not fuzzed yet, and why: each is a bug to fix in that code, then its line here removed.
PENDING: dict = {
}

# Public callables without an entry, and why (each is still validated: these only draw or move files).
EXCLUDED = {
    "render_mesh": "renders with VTK (seconds per call); its inputs are checked in test_geometry_render",
    "render_sequence": "renders with VTK and writes a video; test_geometry_render",
    "render_stereo_pair": "renders with VTK; test_geometry_render",
    "render_turntable": "renders with VTK and writes a video; test_geometry_render",
    "plot_curves": "draws with matplotlib; its curves come from noisy_arc/noisy_circle/trajectory (covered)",
    "quiver_image": "draws with matplotlib; its field sampling is flow_field (covered)",
    "streamline_image": "draws with matplotlib; its lines come from streamlines (covered)",
    "trajectory_frames": "draws with matplotlib; its points come from trajectory (covered)",
    "figure_to_array": "takes a matplotlib figure, nothing numeric to corrupt",
    "load_model": "reads a bundled mesh file by name (test_geometry)",
    "pyvista_to_trimesh": "a VTK conversion (test_geometry_render)",
    "noise_floor": "takes a PowerSpectrum, which power_spectrum (covered) makes and checks",
    "require_pyvista": "imports pyvista or names what to install; nothing numeric",
    "trimesh_to_pyvista": "a VTK conversion (test_geometry_render)",
    "atomic_output": "a file-writing context manager (test_io)",
    "read_image": "file I/O (test_io)",
    "read_video": "file I/O (test_io)",
    "write_image": "file I/O; its array goes through to_uint8 (covered)",
    "write_video": "file I/O; its frames go through to_uint8 (covered)",
    "read_mesh": "file I/O (test_io)",
    "write_mesh": "file I/O (test_io)",
    "read_zarr": "file I/O, a zarr store (test_dask)",
    "load_npy": "file I/O: numpy.load of a path (test_cli_errors)",
    "iter_video": "file I/O: decodes a video file or a folder of PNGs (test_cli_errors)",
    "prepare_output": "file I/O: checks and creates an output path (test_cli_errors, its doctest)",
    "exchange_paths": "file I/O: swaps two paths on disk (its doctest)",
    "write_zarr": "file I/O, a zarr store; its array is a lattice grid's (covered) (test_dask)",
}

ENTRIES = {e.name: e for e in TABLE}
_SUBPACKAGES = ("spectral", "spectral.envelopes", "snowfall", "lattice", "fractal", "fields", "geometry", "stimuli",
                "analysis", "io", "lab", "testing")


def _public_callables():
    """Every public function: the names in ``noiselab._API`` and the callables in the subpackages' ``__all__``."""
    names = set(noiselab._API)
    for sub in _SUBPACKAGES:
        mod = importlib.import_module(f"noiselab.{sub}")
        for name in getattr(mod, "__all__", ()):
            obj = getattr(mod, name)
            if callable(obj) and not isinstance(obj, type) and not isinstance(obj, types.ModuleType):
                names.add(name)
    return names


def _covered(name):
    return name in ENTRIES or any(key.startswith(name + ".") or key.endswith("." + name) for key in ENTRIES)


def test_every_public_function_has_an_entry():
    public = _public_callables()
    missing = sorted(n for n in public if not _covered(n) and n not in EXCLUDED)
    assert not missing, f"public functions without an entry in tests/test_properties.py TABLE: {missing}"
    api_missing = sorted(n for n in noiselab._API if not _covered(n))
    assert not api_missing, f"noiselab._API names must be driven by the suite, not excluded: {api_missing}"
    covered = sorted(n for n in public if _covered(n))
    # the size of the run
    fuzzed = sum(1 for e in TABLE for p in e.fuzz if (e.name, p) not in PENDING)
    print(f"\n{len(covered)} public functions covered ({len(TABLE)} entries, {fuzzed} parameters fuzzed, "
          f"{len(PENDING)} pending; {len(FUZZED)} fuzzed entries x {EXAMPLES} examples = "
          f"{len(FUZZED) * EXAMPLES} examples per run); {len(EXCLUDED)} excluded (drawing or file I/O)")
    assert len(covered) + len(public & set(EXCLUDED)) == len(public)


# ---------------------------------------------------------------- running
@contextlib.contextmanager
def _time_limit(seconds):
    def fire(signum, frame):
        raise TimeoutError(f"call took more than {seconds} s (a hang or an unbounded computation)")
    old = signal.signal(signal.SIGALRM, fire)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


@pytest.fixture(scope="module", autouse=True)
def address_space_limit():
    """RLIMIT_AS = this process's size + 6 GiB: a missed estimate fails fast instead of swapping."""
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    with open("/proc/self/status") as fh:
        vm = next(int(line.split()[1]) * 1024 for line in fh if line.startswith("VmSize:"))
    limit = vm + (6 << 30)
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    yield
    resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def _resolve(valid):
    return {k: (v.make() if isinstance(v, Fresh) else v) for k, v in valid.items()}


def run_case(entry, param, value):
    """Call ``entry`` with ``param=value`` and check the outcome against the contract; returns the outcome."""
    kwargs = _resolve(entry.valid)
    kwargs[param] = value
    # the message names the corrupted parameter, or (for a conflict between two) another one of the call
    names = tuple(entry.names.get(param, (param,))) + tuple(n for p in (*entry.valid, *entry.fuzz)
                                                           for n in entry.names.get(p, (p,)))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)   # aliasing advice etc.; RuntimeWarnings stay errors
            warnings.simplefilter("error", RuntimeWarning)
            with _time_limit(CALL_TIMEOUT_S):
                result = entry.call(**kwargs)
    except (ValueError, TypeError) as exc:
        msg = str(exc)
        assert any(re.search(rf"(?<![A-Za-z_]){re.escape(n)}(?![A-Za-z_])", msg) for n in names), \
            f"{entry.name}({param}={value!r}): {type(exc).__name__} does not name {param!r}: {msg}"
        return type(exc).__name__
    except MemoryError as exc:
        assert "needs about" in str(exc) and "GiB" in str(exc), \
            f"{entry.name}({param}={value!r}): MemoryError not from check_memory (allocated first?): {exc}"
        return "MemoryError"
    check = entry.check or finite
    try:
        check(result, kwargs)
    except AssertionError as exc:
        raise AssertionError(f"{entry.name}({param}={value!r}) returned a result breaking its contract: {exc}") \
            from None
    return "result"


@pytest.mark.parametrize("entry", TABLE, ids=[e.name for e in TABLE])
def test_valid_call_satisfies_the_contract(entry):
    # the table's valid call is itself right (so the fuzzed cases start from a working call)
    kwargs = _resolve(entry.valid)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        result = entry.call(**kwargs)
    (entry.check or finite)(result, kwargs)


def _case(entry):
    params = sorted(p for p in entry.fuzz if (entry.name, p) not in PENDING)
    return st.sampled_from(params).flatmap(
        lambda p: st.tuples(st.just(p), KINDS[entry.fuzz[p]]()))


FUZZED = [e for e in TABLE if any((e.name, p) not in PENDING for p in e.fuzz)]


@pytest.mark.parametrize("entry", FUZZED, ids=[e.name for e in FUZZED])
@settings(settings.get_profile("contract"))
@given(data=st.data())
def test_bad_input_gives_a_clear_error_or_the_right_answer(entry, data):
    param, value = data.draw(_case(entry), label="param, value")
    run_case(entry, param, value)


HUGE_CASES = [(e, p, v) for e in TABLE for p, kind in sorted(e.fuzz.items()) if (e.name, p) not in PENDING
              for v in {"mesh": HUGE_MESHES, "array": HUGE_ARRAYS}.get(kind, [])]


@pytest.mark.parametrize("entry, param, value", HUGE_CASES,
                         ids=[f"{e.name}-{p}-{i}" for i, (e, p, _) in enumerate(HUGE_CASES)])
def test_huge_values_give_a_clear_error_or_the_right_answer(entry, param, value):
    """Meshes with coordinates of 1e150-1e300 and images, videos and points of values up to float64's largest,
    for every mesh and array parameter (they are among the cases, not left to the random draw)."""
    run_case(entry, param, value)
