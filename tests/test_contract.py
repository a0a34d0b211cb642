"""The bad-input contract: every reproducer of the fuzzing run, kept as a plain regression test.

Each case gives a ValueError/TypeError that names the parameter, a
MemoryError that states the size (refused *before* allocating), or the
right answer. The spectral_noise/synthesize cases live with the
spectral synthesis tests.
"""
import contextlib
import resource

import numpy as np
import pytest

import noiselab as nl
from noiselab._core import validate as V
from noiselab import analysis as A
from noiselab import geometry as G
from noiselab import io as IO
from noiselab import snowfall as S
from noiselab.fractal import octaves_used
from noiselab.lattice import Grid
from noiselab.spectral import envelopes as E

RNG = np.random.default_rng(11)


def image(n=32):
    return RNG.random((n, n))


@contextlib.contextmanager
def address_space(extra_gib=3):
    """Lower this process's RLIMIT_AS (soft) to its current size + ``extra_gib``: a missed estimate fails fast.

    A refusal by ``check_memory`` says "needs about ... GiB"; numpy's own
    "Unable to allocate" would mean the estimate came too late.
    """
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    with open("/proc/self/status") as fh:
        vm = next(int(line.split()[1]) * 1024 for line in fh if line.startswith("VmSize:"))
    limit = vm + (extra_gib << 30)
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


# --------------------------------------------------------------- _validate
def test_check_real_turns_huge_ints_into_a_value_error_naming_the_parameter():
    with pytest.raises(ValueError, match=r"^c must be finite .*401 digits"):
        V.check_real("c", 10**400)
    with pytest.raises(ValueError, match=r"c \(rad/frame\) must be finite"):
        nl.snow((4, 16, 16), c=10**400)
    assert V.check_real("x", 10**300) == 1e300


def test_check_shape_refuses_empty_and_unindexable_shapes():
    with pytest.raises(ValueError, match="shape must have at least one entry"):
        V.check_shape("shape", ())
    with pytest.raises(ValueError, match=r"shape \(9223372036854775808, 16, 16\) has more elements"):
        nl.snow((2**63, 16, 16))
    with pytest.raises(ValueError, match="shape must have at least one entry"):
        nl.synthesize((), lambda *w: 1.0)
    with pytest.raises(TypeError, match="shape must be a tuple of ints"):
        V.check_shape("shape", "64")


def test_check_memory_respects_the_address_space_limit():
    with address_space(2):
        limits = V.memory_limits()
        assert limits["address-space limit"] < (3 << 30)
        with pytest.raises(MemoryError, match=r"needs about 4 GiB .*\(address-space limit\)"):
            V.check_memory(4 << 30, "a test allocation")
    assert "address-space limit" not in V.memory_limits() or V.memory_limits()["address-space limit"] > (3 << 30)


@pytest.mark.parametrize("version", ["v2", "v1"])
def test_check_memory_respects_cgroup_limits(tmp_path, version):
    # a cgroup hierarchy in a temporary folder: the parent's limit binds the child's
    if version == "v2":
        text = "0::/jobs/me\n"
        child, parent = tmp_path / "jobs" / "me", tmp_path / "jobs"
        names = ("memory.max", "memory.current")
    else:
        text = "12:cpu:/\n4:memory:/jobs/me\n"
        child, parent = tmp_path / "memory" / "jobs" / "me", tmp_path / "memory" / "jobs"
        names = ("memory.limit_in_bytes", "memory.usage_in_bytes")
    child.mkdir(parents=True)
    (child / names[0]).write_text("max\n" if version == "v2" else "9223372036854771712\n")  # no limit here
    (child / names[1]).write_text(str(1 << 30))
    (parent / names[0]).write_text(str(5 << 30))
    (parent / names[1]).write_text(str(2 << 30))
    assert V._cgroup_room(text, str(tmp_path)) == 3 << 30
    (child / names[0]).write_text(str(1536 << 20))   # the child's own, tighter limit
    assert V._cgroup_room(text, str(tmp_path)) == 512 << 20
    assert V._cgroup_room("0::/\n", str(tmp_path / "nothing")) is None


def test_check_axes_and_sequences():
    assert V.check_axes("axes", (-1, 0), 3) == (0, 2)
    with pytest.raises(ValueError, match=r"axes\[0\] must be an int in \[-2, 1\], got 5"):
        V.check_axes("axes", (5,), 2)
    with pytest.raises(TypeError, match=r"axes\[0\] must be an int, got float"):
        V.check_axes("axes", (1.7,), 2)
    with pytest.raises(ValueError, match="distinct"):
        V.check_axes("axes", (1, -1), 2)
    with pytest.raises(TypeError, match="pan must be a sequence"):
        V.check_real_sequence("pan", {1, 2}, length=2)


# ---------------------------------------------------------- silent outputs
@pytest.mark.parametrize("dim", [1, 2, 3, 4])
def test_lattice_overflow_is_an_error_in_every_dimension(dim):
    noise = nl.LatticeNoise(dim, frequency=1e300)
    with pytest.raises(ValueError, match="points times the frequency .* overflows float64"):
        noise(np.full((1, dim), 1e10))
    # the same points at a sane frequency are fine, and stay in range
    v = nl.LatticeNoise(dim)(np.full((1, dim), 1e10))
    assert np.isfinite(v).all() and np.abs(v).max() <= 1


@pytest.mark.parametrize("kind", [nl.fractal_sum, nl.turbulence])
def test_fractal_octave_overflow_is_an_error_on_points_and_grids(kind):
    noise = nl.LatticeNoise(2)
    with pytest.raises(ValueError, match=r"lacunarity=2 over 1100 visible octaves overflows.*at most 997 octaves"):
        kind(noise, np.ones((2, 2)), 1100, gain=1.0)
    with pytest.raises(ValueError, match=r"lacunarity=10 .* overflows"):
        kind(noise, np.ones((2, 2)), 400, lacunarity=10, gain=0.9)
    # on a grid the octaves past the sampling's Nyquist are skipped: the right answer, no overflow
    g, used = kind(noise, Grid((4, 4), [(0, 1), (0, 1)]), 400, lacunarity=10, gain=0.9, return_octaves=True)
    assert used == 1 and np.isfinite(g).all()
    # within the limit, finite points whose scaled coordinates overflow are refused on every dimension
    with pytest.raises(ValueError, match="x times the frequency .* overflows float64"):
        kind(nl.LatticeNoise(1), np.full(3, 1e300), 40)
    v = kind(noise, np.ones((2, 2)), 990, gain=1.0)
    assert np.isfinite(v).all()


def test_gain_overflow_is_a_value_error_with_the_octave_limit():
    with pytest.raises(ValueError, match=r"gain=178 over octaves=138 .* at most 133 octaves"):
        nl.fractal_sum(nl.LatticeNoise(1), np.ones(3), 138, gain=178.0)
    with pytest.raises(ValueError, match="gain"):
        octaves_used(138, gain=178.0)
    v = nl.fractal_sum(nl.LatticeNoise(1), np.ones(3), 10, gain=178.0)
    assert np.isfinite(v).all()


def test_amplitude_past_float32_is_refused_not_inf():
    noise = nl.LatticeNoise(2, amplitude=3.7e38)
    with pytest.raises(ValueError, match=r"amplitude 3.7e\+38 exceeds the range of float32"):
        noise(np.ones((3, 2), np.float32))
    assert np.isfinite(noise(np.ones((3, 2)))).all()          # float64 output holds it
    with pytest.raises(ValueError, match="amplitude .* exceeds the range of float32"):
        noise.grid((4, 4), [(0, 1), (0, 1)], dtype=np.float32)
    with pytest.raises(ValueError, match="amplitude .* exceeds the range of float32"):
        nl.fractal_sum(nl.LatticeNoise(2, amplitude=1e38), np.ones((3, 2), np.float32), 4, gain=1.0)


def test_grid_and_points_agree_past_2_to_the_53_cells():
    noise = nl.LatticeNoise(1, rng=5, kernel="box", frequency=21475.0)
    shape, extent = (4,), [(1.0, 559236275034.0)]
    grid = noise.grid(shape, extent)
    np.testing.assert_array_equal(grid, noise(noise.grid_points(shape, extent)))
    assert grid[-1] == pytest.approx(0.5170, abs=1e-4)
    # and in 2-D, across 2**52 (some octaves separable, some per point)
    noise2 = nl.LatticeNoise(2, rng=3, frequency=1e4)
    ext = [(0.0, 3e11), (5e11, 5e11 + 4.0)]
    np.testing.assert_array_equal(noise2.grid((5, 6), ext), noise2(noise2.grid_points((5, 6), ext)))


def test_flake_speeds_validates_its_parameters():
    with pytest.raises(ValueError, match=r"c \(rad/frame\) must be finite"):
        S.flake_speeds(c=np.nan)
    with pytest.raises(TypeError, match="width must be an int, got bool"):
        S.flake_speeds(width=True, height="x")
    with pytest.raises(TypeError, match="height must be an int, got str"):
        S.flake_speeds(height="x")
    near, far = S.flake_speeds(1.0, (16, 128), 512)
    assert near == pytest.approx(512 / (2 * np.pi * 16)) and far == pytest.approx(512 / (2 * np.pi * 128))


def test_rescale_opacity_lo_hi():
    with pytest.raises(ValueError, match="lo must be finite"):
        S.rescale_opacity(image(), lo=np.nan, hi=1.0)
    with pytest.raises(ValueError, match=r"hi must be in \[1, inf\), got 0"):
        S.rescale_opacity(image(), lo=1.0, hi=0.0)
    with pytest.raises(ValueError, match="lo and hi must be given together"):
        S.rescale_opacity(image(), lo=0.0)
    x = np.array([0.0, 0.5, 1.0])
    np.testing.assert_allclose(S.rescale_opacity(x.copy(), beta=1.0, lo=0.0, hi=1.0), x)


def test_parallax_composite_refuses_a_mask_without_a_clear_region():
    fg = RNG.random((2, 8, 8)).astype(np.float32)
    with pytest.raises(ValueError, match="every pixel veiled"):
        S.parallax_composite(fg, np.ones((8, 8), bool))
    with pytest.raises(ValueError, match="every pixel clear"):
        S.parallax_composite(fg, np.zeros((8, 8), bool))
    m = np.zeros((8, 8), bool)
    m[:, 4:] = True
    _, contrast = S.parallax_composite(fg, m)
    assert all(np.isfinite(v) and 0 <= v <= 1 for v in contrast.values())


@pytest.mark.parametrize("func", [S.tile, lambda a, r: list(S.iter_tiled_frames(a, r))])
def test_tiling_refuses_nan_complex_str_and_empty(func):
    with pytest.raises(ValueError, match="alpha must be finite; it holds 32 NaN"):
        func(np.full((2, 4, 4), np.nan), 1)
    with pytest.raises(TypeError, match="alpha must be a real numeric array, got dtype complex128"):
        func(np.zeros((2, 4, 4), complex), 1)
    with pytest.raises(TypeError, match="alpha must be a real numeric array, got dtype <U1"):
        func(np.zeros((2, 4, 4), "U1"), 1)
    with pytest.raises(ValueError, match=r"alpha is empty \(shape \(0, 4, 4\)\)"):
        func(np.zeros((0, 4, 4)), 1)


def test_tile_and_iter_tiled_frames_agree_on_an_int_reps():
    a = RNG.random((3, 4, 5))
    tiled = S.tile(a, (1, 2, 2))
    frames = np.stack(list(S.iter_tiled_frames(a, 2)))
    np.testing.assert_array_equal(frames, tiled)
    with pytest.raises(ValueError, match=r"alpha is empty"):
        list(S.iter_tiled_frames(np.zeros((0, 4, 4)), (1, 1), n_frames=3))
    with pytest.raises(ValueError, match=r"crop must be a pair \(height, width\)"):
        list(S.iter_tiled_frames(np.zeros((2, 4, 4)), (1, 1), crop=(2,)))
    with pytest.raises(TypeError, match="reps must be an int"):
        S.iter_tiled_frames(a, "2")


def test_to_uint8_refuses_inf_and_infinite_bounds():
    with pytest.raises(ValueError, match="array must be finite; it holds 1 NaN or inf"):
        IO.to_uint8(np.array([0.0, np.inf]))
    with pytest.raises(ValueError, match="vmax must be finite"):
        IO.to_uint8(np.array([0.0, 1.0]), vmax=np.inf)
    with pytest.raises(ValueError, match="vmax - vmin must be finite"):
        IO.to_uint8(np.array([0.0, 1.0]), vmin=-1e308, vmax=1e308)
    with pytest.raises(TypeError, match="complex"):
        IO.to_uint8(np.zeros(3, complex))
    np.testing.assert_array_equal(IO.to_uint8(np.array([-3e38, -1e38, 3e38]), vmin=-3e38, vmax=3e38), [0, 85, 255])


def test_power_spectrum_of_huge_values():
    x = image()
    big = x * 1e140          # float64: scaled before squaring, the right spectrum
    np.testing.assert_allclose(A.power_spectrum(big).power, A.power_spectrum(x).power * 1e280, rtol=1e-9)
    with pytest.raises(ValueError, match=r"field values reach 1e\+154.* below 1e150"):
        A.power_spectrum(np.where(x > 0.5, 1e154, 0.0))
    f32 = (x * 1e18).astype(np.float32)  # float32: transformed in float64, finite
    p = A.power_spectrum(f32)
    assert np.isfinite(p.power).all() and p.total == pytest.approx(float(f32.astype(np.float64).var()), rel=1e-5)


def test_resolution_report_is_finite_or_refused():
    mesh = G.sphere(1)
    with pytest.raises(ValueError, match=r"max_frequency \(cycles/unit\) must be in \[1e-300, 1e\+300\], got 0"):
        G.resolution_report(mesh, 0.0)
    with pytest.raises(ValueError, match="max_frequency"):
        G.resolution_report(mesh, 1e308)
    r = G.resolution_report(mesh, 1e300)
    assert not r.ok and r.subdivisions > 900 and np.isfinite([r.samples_per_period, r.target_edge]).all()
    with pytest.raises(ValueError, match="max_faces"):
        G.subdivide_for_noise(mesh, 1e300)
    assert len(G.subdivide_for_noise(mesh, 0.0).faces) == len(mesh.faces)   # a constant field: nothing to do
    with pytest.raises(ValueError, match="max_frequency"):
        G.sphere_for_noise(1e308)


# ----------------------------------------------------------- envelopes
def test_envelopes_validate_their_parameters():
    w = np.linspace(-1, 1, 5)
    with pytest.raises(ValueError, match="exponent must be finite"):
        E.power_law(w, exponent=np.nan)
    with pytest.raises(ValueError, match=r"exponent=1100 makes \|w\|\*\*\(-exponent\) overflow"):
        E.power_law(w, exponent=1100)
    with pytest.raises(ValueError, match=r"c \(rad/frame\) must be finite"):
        E.tent(w, w, w, c=np.nan, tol=1.0)
    with pytest.raises(TypeError, match=r"tol \(rad/frame\) must be a real number, got str"):
        E.tent(w, w, w, c=1.0, tol="x")
    with pytest.raises(ValueError, match=r"pan_yx \(px/frame\) must hold 2 real numbers, got 1"):
        E.sheared_tent(w, w, w, c=1.0, pan_yx=(1,), tol=1.0)
    with pytest.raises(ValueError, match="annulus needs lo <= hi"):
        E.annulus(w, band_cycles_per_sample=(0.3, 0.1))
    with pytest.raises(ValueError, match=r"wx must be finite"):
        E.tent_surface(w, w * np.nan, c=1.0)
    with pytest.raises(TypeError, match="direction must be a pair"):
        E.unit_direction("ab")
    with pytest.raises(ValueError, match="thickness must be in"):
        E.thickened_tent(w, w, w, c=1.0, thickness=2.0, tol=0.1)
    with pytest.raises(ValueError, match="must broadcast together"):
        E.radial_frequency(np.ones(3), np.ones(4))


# ---------------------------------------------------- wrong exception types
def test_overflow_errors_become_value_errors():
    img = image()
    with pytest.raises(ValueError, match=r"period must be an int in \[1, 4611686018427387904\]"):
        nl.LatticeNoise(2, period=2**64)
    with pytest.raises(ValueError, match="per_octave must be finite"):
        A.octave_bands(2, 16, per_octave=np.inf)
    with pytest.raises(ValueError, match="max_frequency"):
        G.subdivide_for_noise(G.sphere(1), 1e308)
    # a tiny lo is the right answer (octaves counted with the logs apart), not an OverflowError
    oe = A.octave_energy(img, (5e-324, None))
    assert len(oe.energy) == 1078 and np.isfinite(oe.energy).all()
    assert oe.energy.sum() == pytest.approx(A.octave_energy(img, (1.0, None)).energy.sum(), rel=1e-6)


def test_index_errors_become_value_errors():
    img = image()
    with pytest.raises(ValueError, match=r"value_range must hold 2 real numbers, got 1"):
        G.colored_surface(nl.LatticeNoise(2, 2), shape=(4, 4), value_range=(1.0,), on_alias="ignore")
    with pytest.raises(ValueError, match=r"points must have shape \(n, k\), got \(3,\)"):
        G.evaluate_field(nl.LatticeNoise(3), np.ones(3))
    with pytest.raises(MemoryError, match="radial_spectrum with bins=9223372036854775807 needs about"):
        A.radial_spectrum(img, bins=2**63 - 1)


def test_power_spectrum_argument_types():
    img = image()
    with pytest.raises(ValueError, match="window must be None or 'hann', got array"):
        A.power_spectrum(img, window=np.ones(16))
    with pytest.raises(TypeError, match="band must be an ordered .* got a set"):
        A.band_energy(img, {0.1, 0.2})
    with pytest.raises(ValueError, match=r"axes\[0\] must be an int in \[-2, 1\], got 5"):
        A.power_spectrum(img, axes=(5,))
    with pytest.raises(TypeError, match=r"axes\[0\] must be an int, got float"):
        A.power_spectrum(img, axes=(1.7,))
    assert A.power_spectrum(img, axes=(-1,)).axes == (1,)


# ------------------------------------------------------------ allocations
def test_allocations_are_estimated_before_they_happen():
    img = image()
    with address_space(3):
        with pytest.raises(MemoryError, match=r"LatticeNoise\(dim_out=100000000.* needs about"):
            nl.LatticeNoise(1, dim_out=10**8)
        with pytest.raises(MemoryError, match=r"grid coordinates for shape \(2147483648,\) needs about 16 GiB"):
            nl.LatticeNoise(1).grid((2**31,), [(0, 1)])
        with pytest.raises(MemoryError, match="grid_points"):
            nl.LatticeNoise(2).grid_points((2**16, 2**16), [(0, 1), (0, 1)])
        with pytest.raises(MemoryError, match="radial_spectrum with bins=2147483648 needs about 128 GiB"):
            A.radial_spectrum(img, bins=2**31)
        with pytest.raises(MemoryError, match=r"octave_bands with 6.44e\+09 bands needs about"):
            A.octave_bands(2, 16, per_octave=2**31)
        with pytest.raises(MemoryError, match="tiled frames"):
            S.iter_tiled_frames(np.zeros((1, 4, 4)), (2**16, 2**16))


# ------------------------------------ analysis.quality and the derivatives
def test_derivative_paths_refuse_coordinate_and_derivative_overflow():
    far = np.full((1, 2), 1e10)
    with pytest.raises(ValueError, match="points times the frequency"):
        nl.LatticeNoise(2, frequency=1e300).jacobian(far)
    with pytest.raises(ValueError, match="x times the frequency"):
        nl.fractal_gradient(nl.LatticeNoise(2, frequency=1e300), far, 1)
    with pytest.raises(ValueError, match="extent times the frequency"):
        nl.LatticeNoise(2, frequency=1e300).gradient_grid((2, 2), [(0, 1e10), (0, 1)])
    # the phase counts too: x * frequency + phase past float64
    with pytest.raises(ValueError, match="points times the frequency"):
        nl.LatticeNoise(2, phase=1.7e308).gradient(np.full((1, 2), 1e307))
    # coordinates fine, but the derivative (amplitude * frequency * ...) overflows: refused, not inf
    steep = nl.LatticeNoise(2, frequency=1e300, amplitude=1e10)
    with pytest.raises(ValueError, match="derivative at the given points overflows"):
        steep.jacobian(np.ones((1, 2)))
    with pytest.raises(ValueError, match=r"derivative on this grid \(extent\) overflows"):
        nl.LatticeNoise(2, frequency=1e10, amplitude=1e300).gradient_grid((4, 4), [(0, 1e-10), (0, 1e-10)])
    assert np.isfinite(nl.LatticeNoise(2, frequency=1e300).gradient(np.ones((3, 2)))).all()


def test_new_functions_name_their_bad_arguments():
    n2, v2, pts = nl.LatticeNoise(2, rng=1), nl.LatticeNoise(2, 2, rng=2), np.ones((3, 2))
    cases = [
        (TypeError, "points", lambda: nl.curl_noise(n2, "abc")),
        (TypeError, "points", lambda: nl.warp(n2, v2)([[1.0, 2.0], [3.0]])),
        (TypeError, "amount", lambda: nl.warp(n2, v2, 1j)),
        (ValueError, "amount", lambda: nl.warp(n2, v2, 10**400)),
        (TypeError, "x", lambda: nl.fractal_gradient(n2, [[1.0, 2.0], [3.0]], 2)),
        (TypeError, "phase", lambda: nl.monge_normals(n2, pts, phase=1j)),
        (TypeError, "points", lambda: nl.monge_normals(n2, pts + 1j)),
        (ValueError, "curvature", lambda: nl.displaced_normals(G.sphere(1), nl.LatticeNoise(3), curvature=10**400)),
        (TypeError, "normals", lambda: nl.displaced_normals(G.sphere(1), nl.LatticeNoise(3), normals="abc")),
        (ValueError, "field must take 3-D points", lambda: nl.displaced_normals(G.sphere(1), nl.LatticeNoise(1))),
        (TypeError, "a", lambda: nl.normal_angles(None, np.eye(3))),
        (ValueError, "b must hold 3-D vectors", lambda: nl.normal_angles(np.eye(3), np.ones(2))),
        (TypeError, "target", lambda: A.envelope_error(image(), "noise")),
        (ValueError, "target", lambda: A.envelope_error(image(), lambda f: np.ones(3))),
        (TypeError, "bounds", lambda: A.value_statistics(image(), bounds={1.0, 2.0})),
        (ValueError, "variance must be in", lambda: A.value_statistics(image(), variance=5e-324)),
        (ValueError, "bounds .* too narrow", lambda: A.value_statistics(image(), bounds=(0, 5e-324))),
        (ValueError, "support must be in", lambda: A.envelope_error(image(), lambda f: f + 1.0, support=1.0)),
        (ValueError, "holds no spatial frequency", lambda: A.tent_energy_per_band(image()[None].repeat(4, 0)
                                                                                  + np.arange(4)[:, None, None],
                                                                                  1.0, (0.1, 0.2))),
    ]
    for exc, words, call in cases:
        with pytest.raises(exc, match=words):
            call()


def test_normals_of_steep_and_huge_surfaces_are_the_limits_not_nan():
    n2, pts = nl.LatticeNoise(2, rng=1), np.random.default_rng(0).uniform(0, 4, (50, 2))
    g = nl.fractal_gradient(n2, pts, 1)
    # |amplitude * frequency| -> inf: the normal turns horizontal, against the gradient
    steep = nl.monge_normals(n2, pts, amplitude=1e300)
    np.testing.assert_allclose(steep[:, :2], -g / np.linalg.norm(g, axis=1, keepdims=True), atol=1e-12)
    assert np.all(np.abs(steep[:, 2]) < 1e-290)
    # continuous across the switch to the scaled formula (|amplitude| * frequency = 1), and the plain formula below
    below = nl.monge_normals(n2, pts, amplitude=1 - 1e-9)
    np.testing.assert_allclose(below, nl.monge_normals(n2, pts, amplitude=1 + 1e-9), atol=1e-8)
    plain = np.concatenate([-g * (1 - 1e-9), np.ones((len(g), 1))], axis=1)
    np.testing.assert_allclose(below, plain / np.linalg.norm(plain, axis=1, keepdims=True), atol=1e-13)
    # displaced normals: continuous across the switch to the scaled formula (|amplitude| * frequency = 1)
    sphere, n3 = G.sphere(2), nl.LatticeNoise(3, rng=3)
    below = nl.displaced_normals(sphere, n3, 1 - 1e-9, curvature=1.0)
    above = nl.displaced_normals(sphere, n3, 1 + 1e-9, curvature=1.0)
    np.testing.assert_allclose(below, above, atol=1e-7)
    np.testing.assert_allclose(nl.displaced_normals(sphere, n3, 1e300, curvature=1.0),
                               nl.displaced_normals(sphere, n3, 1e12, curvature=1.0), atol=1e-9)
    # angles do not depend on the vectors' lengths, however large or small
    a, b = np.random.default_rng(1).standard_normal((2, 20, 3))
    np.testing.assert_allclose(nl.normal_angles(a * 1e300, b * 1e-300), nl.normal_angles(a, b), rtol=1e-12)


def test_scale_free_measures_of_huge_and_tiny_fields():
    x = np.random.default_rng(0).standard_normal(100)
    for scale in (1e300, 1e-310):
        assert A.detect_period(np.tile(x, 3) * scale).period == 100
    line = nl.LatticeNoise(1, rng=0, kernel="linear").grid((4096,), [(0, 256)])
    assert A.variance_striping(line * 1e300, 16) == pytest.approx(A.variance_striping(line, 16), rel=1e-9)
    with pytest.raises(ValueError, match="variance would overflow"):
        A.value_statistics(line * 1e300)
    # a power law in a band of any width: log-frequency integration, no k**18 overflow; converged for e=8
    assert A.shell_slice_below(2, 1e300, exponent=8) == pytest.approx(A.shell_slice_below(2, 1e10, exponent=8))
    assert 0 <= A.shell_slice_below(2, 1e300) < 1e-200
    # a subnormal band edge: octave edges lo * 2**k without overflow
    leak = A.band_leakage(image(), (5e-324, 1e-300))
    assert leak.inside == 0 and np.isfinite(leak.edges).all()
    assert leak.below + leak.inside + leak.above + leak.aliased == pytest.approx(1)
    # a sub-band with no frequency cell: fraction 0 and share 0, not NaN
    video = np.random.default_rng(2).random((4, 16, 16))
    m = A.tent_energy_per_band(video, 1.0, (1, 1.02))
    assert np.isfinite(m.fraction).all()
    m = A.tent_energy_per_band(video, 1.0, (2, 8), per_octave=4)
    assert np.isfinite(m.fraction).all() and (m.fraction[m.share == 0] == 0).all() and (m.share == 0).any()


def test_envelope_error_depends_on_the_target_shape_not_its_scale():
    x = nl.spectral_noise((64, 64), exponent=1.0, band=(4, 32), rng=0, dtype=np.float64)

    def target(f):
        return np.where((f >= 4) & (f <= 32), f ** -2.0, 0.0)

    base = A.envelope_error(x, target)
    for scale in (1e-200, 1e250):   # sums of 1e250 targets would overflow; 1e-200 ones underflow in x**2
        e = A.envelope_error(x, lambda f: target(f) * scale)
        np.testing.assert_allclose(e.db, base.db, rtol=1e-9, atol=1e-9)
        assert e.outside == pytest.approx(base.outside) and e.rms_db == pytest.approx(base.rms_db)
        assert e.gain_db == pytest.approx(base.gain_db - 10 * np.log10(scale))
        np.testing.assert_allclose(e.target_level, base.target_level * scale, rtol=1e-9)


# ------------------------------------ the spectral engine's building blocks (the last PENDING lines)
def test_synthesize_envelope_a_str_is_a_type_error_naming_envelope():
    with pytest.raises(TypeError, match="envelope must be a callable or a real amplitude array"):
        nl.spectral.synthesize((8, 8), "annulus", rng=0)


def test_synthesize_envelope_of_the_wrong_arity_is_a_type_error_naming_envelope():
    with pytest.raises(TypeError, match="envelope must be a callable taking 2 frequency arrays"):
        nl.spectral.synthesize((8, 8), lambda w: w, rng=0)


def test_synthesize_envelope_returning_the_wrong_shape_is_a_value_error_naming_envelope():
    with pytest.raises(ValueError, match=r"envelope\(\*w\) must return .* half spectrum \(8, 5\).* got shape \(3,\)"):
        nl.spectral.synthesize((8, 8), lambda wy, wx: np.ones(3), rng=0)
    # a constant (a scalar broadcast to the half spectrum) is a valid envelope
    assert np.isfinite(nl.spectral.synthesize((8, 8), 1.0, rng=0)).all()


def test_draw_coefficients_n_negative_or_huge():
    with pytest.raises(ValueError, match=r"n must be an int in \[0, inf\]"):
        nl.spectral.draw_coefficients(-1, np.random.default_rng(0))
    with address_space(3):
        with pytest.raises(MemoryError, match=r"draw_coefficients\(n=2147483648\) needs about 64 GiB"):
            nl.spectral.draw_coefficients(2**31, np.random.default_rng(0))
    assert nl.spectral.draw_coefficients(0, np.random.default_rng(0)).shape == (0,)


def test_draw_coefficients_takes_an_int_seed_as_rng():
    a = nl.spectral.draw_coefficients(8, 5)
    np.testing.assert_array_equal(a, nl.spectral.draw_coefficients(8, np.random.default_rng(5)))
    with pytest.raises(TypeError, match="rng must be a non-negative int, a numpy.random.Generator or None"):
        nl.spectral.draw_coefficients(8, "x")
    with pytest.raises(ValueError, match="rng must be"):
        nl.spectral.draw_coefficients(8, -1)


def test_draw_coefficients_dtype_is_float32_or_float64():
    with pytest.raises(TypeError, match="dtype must be float32 or float64"):
        nl.spectral.draw_coefficients(8, 0, dtype="nope")
    assert nl.spectral.draw_coefficients(8, 0, dtype=np.float64).dtype == np.complex128


def test_hermitian_plane_refuses_non_finite_and_non_array_planes():
    with pytest.raises(ValueError, match="plane must be finite"):
        nl.spectral.hermitian_plane(np.array([1.0, np.nan, 2.0]))
    with pytest.raises(ValueError, match="plane must be finite"):
        nl.spectral.hermitian_plane(np.array([1.0, 2.0, np.inf + 0j]))
    for bad in ("abc", None, [[1.0, 2.0], [3.0]]):
        with pytest.raises(TypeError, match="plane must be a"):
            nl.spectral.hermitian_plane(bad)


def test_hermitian_plane_support_must_be_a_bool_array_of_the_planes_shape():
    plane = np.array([1 + 1j, 2 + 0j, 0j, 3j])
    with pytest.raises(TypeError, match="support must be a"):
        nl.spectral.hermitian_plane(plane, "abc")
    with pytest.raises(TypeError, match="support must be a bool array"):
        nl.spectral.hermitian_plane(plane, np.ones(4))
    with pytest.raises(ValueError, match=r"support must have the plane's shape \(4,\)"):
        nl.spectral.hermitian_plane(plane, np.ones(3, bool))
    np.testing.assert_array_equal(nl.spectral.hermitian_plane(plane, plane != 0), nl.spectral.hermitian_plane(plane))


def test_map_blocks_keeps_order_uses_the_calling_thread_and_raises_after_every_thread_stops():
    import threading
    import time

    from noiselab._core import map_blocks

    caller = threading.get_ident()
    seen = []

    def work(b):
        seen.append(threading.get_ident())
        time.sleep(0.01 * (b % 3))  # blocks finish out of order
        return b * b

    assert map_blocks(work, range(7), 3) == [b * b for b in range(7)]
    assert caller in seen and len(set(seen)) > 1  # the caller works beside the pool
    assert map_blocks(work, [5], 4) == [25]
    done = []

    def fail(b):
        if b == 0:
            raise ValueError("block 0 failed")
        time.sleep(0.05)
        done.append(b)

    with pytest.raises(ValueError, match="block 0 failed"):
        map_blocks(fail, range(6), 2)
    finished = list(done)
    assert len(finished) <= 1  # after the failure no thread took another block ...
    time.sleep(0.2)
    assert done == finished  # ... and none was still running when the error surfaced
