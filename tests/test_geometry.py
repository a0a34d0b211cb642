"""Geometry: displacement along normals (Eq. 11), resolution checks, shapes, mesh I/O."""
import warnings

import numpy as np
import pytest
import trimesh

import noiselab
from noiselab.geometry import (
    AliasingWarning,
    displace,
    displace_frames,
    load_model,
    octave_field,
    resolution_report,
    sampled_field,
    sphere,
    sphere_for_noise,
    squashed_sphere,
    subdivide_for_noise,
    vertex_normals,
)
from noiselab.io import read_mesh, write_mesh


def waves(p):
    """A smooth stand-in field in [-1, 1] (a sum of plane waves), for properties that need a known field."""
    p = np.asarray(p, dtype=float)
    return (0.5 * np.sin(2.1 * p[:, 0] + 0.3) * np.cos(1.7 * p[:, 1])
            + 0.5 * np.sin(1.3 * p[:, 2] - 0.8 * p[:, 0] + 1.1))


def constant(value):
    return lambda p: np.full(len(p), float(value))


# ---------------------------------------------------------------- displace
def test_displacement_is_along_the_normal_by_amplitude_times_field():
    mesh = sphere(4)
    out = displace(mesh, waves, amplitude=0.2, frequency=1.5, phase=0.25)
    p = np.asarray(mesh.vertices)
    n = p / np.linalg.norm(p, axis=1, keepdims=True)     # a sphere's true normals
    delta = np.asarray(out.vertices) - p
    expected = 0.2 * waves(1.5 * p + 0.25)
    # along the normal ...
    along = np.einsum("ij,ij->i", delta, n)
    across = np.linalg.norm(delta - along[:, None] * n, axis=1)
    assert np.abs(along - expected).max() < 2e-3 * 0.2     # mesh normals vs exact: < 0.2% of the amplitude
    assert across.max() < 0.01 * 0.2
    # ... and the recorded displacement is exactly amplitude * s
    np.testing.assert_allclose(out.vertex_attributes["displacement"], expected, rtol=0, atol=1e-12)


def test_radii_stay_within_amplitude_and_use_it():
    out = displace(sphere(4), waves, amplitude=0.1)
    r = np.linalg.norm(out.vertices, axis=1)
    assert r.min() >= 0.9 - 1e-12 and r.max() <= 1.1 + 1e-12
    assert r.max() - r.min() > 0.1        # the field's range is used, not flattened


def test_input_mesh_is_never_modified_and_output_does_not_alias_it():
    mesh = sphere(3)
    v0, f0 = mesh.vertices.copy(), mesh.faces.copy()
    out = displace(mesh, waves, amplitude=0.3)
    np.testing.assert_array_equal(mesh.vertices, v0)
    np.testing.assert_array_equal(mesh.faces, f0)
    out.vertices[0] += 10.0
    out.faces[0] = [0, 0, 0]
    np.testing.assert_array_equal(mesh.vertices, v0)
    np.testing.assert_array_equal(mesh.faces, f0)


def test_watertightness_and_winding_are_kept():
    out = displace(sphere(4), waves, amplitude=0.15, frequency=2.0)
    assert out.is_watertight and out.is_winding_consistent
    assert out.volume > 0


def test_inside_out_sphere_is_still_displaced_outwards():
    inverted = sphere(3)
    inverted.invert()
    assert inverted.volume < 0
    out = displace(inverted, constant(1.0), amplitude=0.1)
    np.testing.assert_allclose(np.linalg.norm(out.vertices, axis=1), 1.1, atol=1e-3)


def test_zero_area_faces_and_unreferenced_vertices_are_handled():
    base = sphere(2)
    v = np.vstack([base.vertices, [[5.0, 5.0, 5.0]]])        # an unreferenced vertex
    degenerate = [[0, 0, 1], [2, 2, 2]]                      # zero-area faces
    f = np.vstack([base.faces, degenerate])
    mesh = trimesh.Trimesh(v, f, process=False)
    normals = vertex_normals(mesh)
    assert np.all(np.isfinite(normals))
    np.testing.assert_array_equal(normals[-1], 0.0)
    out = displace(mesh, constant(1.0), amplitude=0.1, on_alias="ignore")
    assert np.all(np.isfinite(out.vertices))
    np.testing.assert_array_equal(out.vertices[-1], [5.0, 5.0, 5.0])    # no normal, no move
    np.testing.assert_allclose(np.linalg.norm(out.vertices[:-1], axis=1), 1.1, atol=0.02)


def test_area_weighted_normals_of_a_flat_sheet_point_up():
    m = noiselab.geometry.monge_surface(constant(0.0), (6, 5), on_alias="ignore")
    np.testing.assert_allclose(vertex_normals(m), np.tile([0.0, 0.0, 1.0], (30, 1)), atol=1e-12)


def test_open_mesh_is_displaced_along_its_normals():
    full = sphere(4)
    upper = full.triangles_center[:, 2] > 0
    # an open cap; the lower vertices stay in the array, unreferenced
    hemisphere = trimesh.Trimesh(full.vertices, full.faces[upper], process=False)
    assert not hemisphere.is_watertight
    out = displace(hemisphere, constant(1.0), amplitude=0.05)
    r = np.linalg.norm(out.vertices, axis=1)
    inner = np.asarray(hemisphere.vertices)[:, 2] > 0.2          # away from the open rim
    np.testing.assert_allclose(r[inner], 1.05, atol=2e-3)


def test_point_cloud_and_faceless_mesh_are_clear_errors():
    cloud = trimesh.PointCloud(np.random.default_rng(0).normal(size=(50, 3)))
    with pytest.raises(ValueError, match="point cloud"):
        displace(cloud, waves)
    with pytest.raises(ValueError, match="no faces"):
        displace(trimesh.Trimesh(vertices=np.eye(3), faces=np.zeros((0, 3), int), process=False), waves)
    with pytest.raises(TypeError, match="trimesh"):
        displace(np.zeros((4, 3)), waves)


@pytest.mark.parametrize("kwargs, match", [
    (dict(amplitude=float("nan")), "amplitude must be finite"),
    (dict(frequency=-1.0), "frequency must be >= 0"),
    (dict(frequency=[1.0, 2.0]), "frequency must be a number or a vector of 3"),
    (dict(phase=[0.0, np.inf, 0.0]), "phase must be finite"),
    (dict(octaves=0), r"octaves must be an int in \[1, 64\]"),
    (dict(kind="fbm"), "kind must be"),
    (dict(on_alias="maybe"), "on_alias must be"),
    (dict(gain=1.5), r"gain must be in \(0, 1\]"),
])
def test_bad_parameters_name_the_parameter(kwargs, match):
    with pytest.raises((ValueError, TypeError), match=match):
        displace(sphere(3), waves, **kwargs)


def test_bad_field_output_is_a_clear_error():
    with pytest.raises(ValueError, match="field must return"):
        displace(sphere(2), lambda p: np.zeros((len(p), 2, 2)), on_alias="ignore")
    with pytest.raises(ValueError, match="scalar per point"):
        displace(sphere(2), lambda p: np.zeros((len(p), 3)), on_alias="ignore")
    with pytest.raises(ValueError, match="NaN or inf"):
        displace(sphere(2), lambda p: np.full(len(p), np.nan), on_alias="ignore")
    with pytest.raises(TypeError, match="callable"):
        displace(sphere(2), 3.0)


def test_time_is_the_fourth_input_coordinate():
    seen = []

    def field(p):
        seen.append(p.copy())
        return np.sin(3 * p[:, 0] + p[:, 3])

    a = displace(sphere(3), field, 0.1, time=0.0)
    b = displace(sphere(3), field, 0.1, time=1.0)
    assert seen[0].shape[1] == 4 and np.all(seen[1][:, 3] == 1.0)
    assert np.abs(a.vertices - b.vertices).max() > 0.01          # the shape changes over time
    c = displace(sphere(3), field, 0.1, time=1.0)
    np.testing.assert_array_equal(b.vertices, c.vertices)         # and repeats exactly
    frames = list(displace_frames(sphere(3), field, [0.0, 1.0], amplitude=0.1))
    np.testing.assert_allclose(frames[1].vertices, b.vertices, atol=1e-12)


def test_lattice_field_with_wrong_input_dimension_is_named():
    noise3 = noiselab.LatticeNoise(3, rng=0)
    with pytest.raises(ValueError, match="takes 3-D points .* 4-D points"):
        displace(sphere(3), noise3, 0.1, time=0.5)


# ---------------------------------------------------------------- octaves and the lattice noise
def test_octave_field_matches_the_lattice_fractal_sum_and_turbulence():
    noise = noiselab.LatticeNoise(3, rng=4)
    x = np.random.default_rng(1).uniform(-3, 3, (2000, 3))
    generic_f = octave_field(lambda p: noise(p), 4, "fractal")
    generic_t = octave_field(lambda p: noise(p), 4, "turbulence")
    np.testing.assert_allclose(generic_f(x), noiselab.fractal_sum(noise, x, 4), atol=1e-12)
    np.testing.assert_allclose(generic_t(x), noiselab.turbulence(noise, x, 4), atol=1e-12)
    assert octave_field(noise, 4).max_frequency == 8.0
    assert np.all(generic_t(x) >= 0)


def test_displace_by_lattice_fractal_sum_is_repeatable_and_bounded():
    mesh = sphere_for_noise(2.0 * 2 ** 3)
    a = displace(mesh, noiselab.LatticeNoise(3, rng=7), 0.1, 2.0, octaves=4)
    b = displace(mesh, noiselab.LatticeNoise(3, rng=7), 0.1, 2.0, octaves=4)
    c = displace(mesh, noiselab.LatticeNoise(3, rng=8), 0.1, 2.0, octaves=4)
    np.testing.assert_array_equal(a.vertices, b.vertices)
    assert np.abs(a.vertices - c.vertices).max() > 1e-3
    s = a.vertex_attributes["displacement"]
    assert np.abs(s).max() <= 0.1 * (1 + 0.5 + 0.25 + 0.125)        # |noise| <= 1 per octave
    assert a.is_watertight


def test_turbulence_only_pushes_outwards():
    out = displace(sphere(4), noiselab.LatticeNoise(3, rng=2), 0.1, 1.0, octaves=3, kind="turbulence",
                   on_alias="ignore")
    assert np.linalg.norm(out.vertices, axis=1).min() >= 1.0 - 1e-3


def test_sampled_spectral_volume_works_as_a_field():
    rng = np.random.default_rng(0)
    spectrum = np.fft.rfftn(rng.standard_normal((16, 16, 16)))
    spectrum[4:-4, 4:-4, 4:] = 0          # band-limit, like a spectral noise volume
    vol = np.fft.irfftn(spectrum, s=(16, 16, 16), axes=(0, 1, 2))
    vol /= np.abs(vol).max()
    field = sampled_field(vol, extent=[(-2, 2)] * 3)
    # exact at the grid samples, periodic across the extent
    np.testing.assert_allclose(field(np.array([[-2.0, -1.75, 0.0]])), vol[0, 1, 8], atol=1e-12)
    np.testing.assert_allclose(field(np.array([[-1.9, 0.3, 1.1]])), field(np.array([[2.1, 0.3, 1.1]])), atol=1e-12)
    out = displace(sphere(4), field, 0.1)
    assert np.abs(out.vertex_attributes["displacement"]).max() <= 0.1 * 1.2


# ---------------------------------------------------------------- resolution
def test_aliasing_is_reported_counting_the_highest_octave():
    mesh = sphere(4)           # edges ~ 0.076: 4 samples per period up to ~3.2 cycles/unit
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        displace(mesh, waves, 0.1, frequency=2.0)                  # one octave: fine
    with pytest.warns(AliasingWarning, match="samples per period"):
        displace(mesh, waves, 0.1, frequency=2.0, octaves=3)     # top octave at 8 cycles/unit
    with pytest.raises(ValueError, match="too coarse"):
        displace(mesh, waves, 0.1, frequency=2.0, octaves=3, on_alias="raise")


def test_resolution_report_numbers():
    mesh = sphere(3)
    r = resolution_report(mesh, 4.0)
    edges = mesh.edges_unique_length
    assert r.max_edge == pytest.approx(edges.max())
    assert r.samples_per_period == pytest.approx(0.25 / edges.max())
    assert not r.ok and r.subdivisions == int(np.ceil(np.log2(edges.max() / (0.25 / 4))))
    assert resolution_report(mesh, 0.5).ok


@pytest.mark.parametrize("method", ["adaptive", "midpoint"])
def test_subdivision_reaches_the_needed_resolution_and_no_further(method):
    mesh = sphere(1)
    fine = subdivide_for_noise(mesh, 6.0, method=method)
    r = resolution_report(fine, 6.0)
    assert r.ok and fine.is_watertight
    assert fine.volume == pytest.approx(mesh.volume, rel=1e-12)          # the surface is unchanged
    assert r.max_edge > r.target_edge / 2                                # one halving fewer would do
    one_less = sphere(1)
    for _ in range(resolution_report(mesh, 6.0).subdivisions - 1):
        one_less = one_less.subdivide()
    assert not resolution_report(one_less, 6.0).ok


def test_adaptive_subdivision_refines_only_where_needed():
    ant = load_model("ant")
    adaptive = subdivide_for_noise(ant, 3.0)
    uniform = subdivide_for_noise(ant, 3.0, method="midpoint")
    assert resolution_report(adaptive, 3.0).ok and adaptive.is_watertight and adaptive.is_winding_consistent
    assert adaptive.volume == pytest.approx(ant.volume, rel=1e-9)
    assert len(adaptive.faces) < len(uniform.faces) / 4


def test_subdivision_refuses_impossible_sizes():
    with pytest.raises(ValueError, match="max_faces"):
        subdivide_for_noise(sphere(1), 1000.0, max_faces=100_000)
    with pytest.raises(ValueError, match="method must be"):
        subdivide_for_noise(sphere(1), 8.0, method="bisect")


def test_sphere_for_noise_is_the_coarsest_good_icosphere():
    s = sphere_for_noise(8.0)
    assert resolution_report(s, 8.0).ok
    level = int(round(np.log(((len(s.vertices) - 2) / 10)) / np.log(4)))
    assert not resolution_report(sphere(level - 1), 8.0).ok


# ---------------------------------------------------------------- shapes
def test_squashed_sphere_is_five_percent_lower_and_keeps_it_under_small_noise():
    s = squashed_sphere(0.05, subdivisions=4)
    assert s.vertices[:, 2].max() == pytest.approx(0.95)
    assert s.vertices[:, 0].max() == pytest.approx(1.0)
    out = displace(s, waves, amplitude=0.1 * 0.95)
    assert out.is_watertight
    assert np.abs(out.vertex_attributes["displacement"]).max() <= 0.095 + 1e-12


def test_bundled_model_loads_offline_and_displaces():
    ant = load_model("ant")
    assert ant.is_watertight and max(ant.extents) == pytest.approx(2.0)
    out = displace(ant, noiselab.LatticeNoise(3, rng=1), amplitude=0.05, frequency=2.0, on_alias="ignore")
    moved = np.linalg.norm(out.vertices - ant.vertices, axis=1)
    assert moved.max() <= 0.05 + 1e-12 and moved.max() > 0.005
    with pytest.raises(ValueError, match="cow"):
        load_model("cow")


# ---------------------------------------------------------------- mesh files
@pytest.mark.parametrize("suffix", [".ply", ".obj", ".stl", ".glb", ".off"])
def test_mesh_round_trip(tmp_path, suffix):
    mesh = displace(sphere(3), waves, 0.1)
    path = write_mesh(tmp_path / "deep" / "er" / f"m{suffix}", mesh)
    back = read_mesh(path)
    assert len(back.faces) == len(mesh.faces) and len(back.vertices) == len(mesh.vertices)
    assert back.is_watertight
    assert back.volume == pytest.approx(mesh.volume, rel=1e-5)
    assert sorted(p.name for p in path.parent.iterdir()) == [path.name]      # no temporary left


def test_vertex_colors_survive_ply_and_glb(tmp_path):
    surf = noiselab.geometry.colored_surface(
        lambda p: np.stack([np.sin(p[:, 0]), np.cos(p[:, 1])], axis=1), (16, 16), on_alias="ignore")
    for suffix in (".ply", ".glb"):
        back = read_mesh(write_mesh(tmp_path / f"c{suffix}", surf))
        np.testing.assert_array_equal(back.visual.vertex_colors, surf.visual.vertex_colors)


def test_mesh_writing_errors_leave_nothing(tmp_path):
    with pytest.raises(ValueError, match="must end in one of"):
        write_mesh(tmp_path / "m.xyz", sphere(1))
    with pytest.raises(ValueError, match="no faces"):
        write_mesh(tmp_path / "m.ply", trimesh.Trimesh(vertices=np.eye(3), faces=np.zeros((0, 3), int)))
    assert list(tmp_path.iterdir()) == []
    trimesh.PointCloud(np.eye(3)).export(tmp_path / "cloud.ply")
    with pytest.raises(ValueError, match="no triangle faces"):
        read_mesh(tmp_path / "cloud.ply")
    with pytest.raises(FileNotFoundError):
        read_mesh(tmp_path / "missing.ply")


def test_numba_face_pass_matches_the_numpy_reference():
    import importlib

    D = importlib.import_module("noiselab.geometry.displace")
    mesh = displace(load_model("ant"), waves, 0.05, on_alias="ignore")
    v, f = D._arrays(mesh)
    sums, volume, longest, lengths = D.face_pass(v, f, 1)
    unit = D.unit_rows(sums.copy())
    a, ab, bc, ca, cross = D._face_geometry(v, f)
    np.testing.assert_allclose(unit, D._area_weighted_normals(cross, f, len(v)), atol=1e-12)
    reference = D._edge_lengths(ab, bc, ca)
    np.testing.assert_allclose(np.sort(lengths), np.sort(reference), rtol=1e-12)
    assert longest == pytest.approx(reference.max(), rel=1e-12)
    strided = D.face_pass(v, f, 3)
    assert strided[2] == longest and len(strided[3]) == 3 * -(-len(f) // 3)
    assert volume == pytest.approx(mesh.volume, rel=1e-9)
    bad = trimesh.Trimesh(v, np.vstack([f, [[0, 1, len(v) + 5]]]), process=False, validate=False)
    with pytest.raises(ValueError, match="index vertices outside"):
        displace(bad, waves)


def test_seams_are_welded_so_the_surface_does_not_crack():
    soup = sphere(3)
    soup.unmerge_vertices()                      # every face has its own corners, like an STL or a UV seam
    assert len(soup.vertices) == 3 * len(soup.faces)
    welded = displace(soup, waves, 0.1, on_alias="ignore")
    cracked = displace(soup, waves, 0.1, weld=False, on_alias="ignore")
    merged = welded.copy()
    merged.merge_vertices()
    assert len(merged.vertices) == len(sphere(3).vertices) and merged.is_watertight
    np.testing.assert_allclose(np.sort(merged.vertices, axis=0),
                               np.sort(displace(sphere(3), waves, 0.1).vertices, axis=0), atol=1e-12)
    gaps = np.linalg.norm(cracked.vertices - welded.vertices, axis=1)
    assert gaps.max() > 1e-3                     # without welding the copies move apart
    inverted = soup.copy()
    inverted.invert()
    out = displace(inverted, constant(1.0), 0.1, on_alias="ignore")
    np.testing.assert_allclose(np.linalg.norm(out.vertices, axis=1), 1.1, atol=0.02)   # still outwards


def test_results_do_not_depend_on_chunking_or_per_axis_frequency_is_used():
    mesh = sphere(4)
    a = displace(mesh, waves, 0.1, frequency=[1.0, 2.0, 0.5], phase=[0.1, 0.2, 0.3])
    b = displace(mesh, waves, 0.1, frequency=[1.0, 2.0, 0.5], phase=[0.1, 0.2, 0.3], chunk_size=1000)
    np.testing.assert_array_equal(a.vertices, b.vertices)
    p = np.asarray(mesh.vertices)
    expected = 0.1 * waves(p * [1.0, 2.0, 0.5] + [0.1, 0.2, 0.3])
    np.testing.assert_allclose(a.vertex_attributes["displacement"], expected, atol=1e-15)


def test_spectral_noise_volume_displaces_a_sphere_smoothly():
    vol = noiselab.spectral_noise((32, 32, 32), exponent=1.0, band=(1, 4), rng=0, dtype=np.float64)
    # band 1..4 cycles per 3 units: 4/3 cycles/unit at most, which an icosphere of level 4 samples well
    field = sampled_field(vol / np.abs(vol).max(), extent=[(-1.5, 1.5)] * 3, max_frequency=4 / 3)
    mesh = sphere(4)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = displace(mesh, field, 0.1)
    with pytest.warns(AliasingWarning):       # without the band, the grid's Nyquist (5.3 cycles/unit) is assumed
        displace(mesh, sampled_field(vol, extent=[(-1.5, 1.5)] * 3), 0.1)
    s = out.vertex_attributes["displacement"]
    assert out.is_watertight and np.ptp(s) > 0.05
    # band-limited (<= 4 cycles over 3 units): neighbouring vertices (edges ~0.076) move alike
    e = mesh.edges_unique
    assert np.abs(s[e[:, 0]] - s[e[:, 1]]).max() < 0.25 * np.ptp(s)


def test_nan_vertices_are_a_clear_error():
    bad = sphere(1)
    bad.vertices[0] = np.nan
    with pytest.raises(ValueError, match="vertices must be finite"):
        displace(bad, waves)


@pytest.mark.parametrize("module", ["fields", "displace", "shapes", "curves", "surfaces", "flow", "render",
                                    "normals"])
def test_docstring_examples_run(module):
    import doctest
    import importlib

    mod = importlib.import_module(f"noiselab.geometry.{module}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", AliasingWarning)
        result = doctest.testmod(mod, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0


def test_vector_displacement_moves_vertices_by_the_3d_field():
    noise = noiselab.LatticeNoise(3, 3, rng=5)
    mesh = sphere(3)
    out = displace(mesh, noise, 0.1, 1.0, direction="vector")
    p = np.asarray(mesh.vertices)
    np.testing.assert_allclose(out.vertices - p, 0.1 * noise(p), atol=1e-12)
    n = p / np.linalg.norm(p, axis=1, keepdims=True)
    np.testing.assert_allclose(out.vertex_attributes["displacement"],
                               np.einsum("ij,ij->i", out.vertices - p, n), atol=1e-3)
    with pytest.raises(ValueError, match="at least 3 components"):
        displace(mesh, waves, direction="vector")
    with pytest.raises(ValueError, match="direction must be"):
        displace(mesh, waves, direction="tangent")


def test_texture_coordinates_and_colours_are_kept():
    mesh = sphere(2)
    uv = np.random.default_rng(0).random((len(mesh.vertices), 2))
    mesh.visual = trimesh.visual.TextureVisuals(uv=uv)
    out = displace(mesh, waves, 0.1, on_alias="ignore")
    np.testing.assert_array_equal(out.visual.uv, uv)
    painted = sphere(2)
    painted.visual.face_colors = [255, 0, 0, 255]
    out = displace(painted, waves, 0.1, on_alias="ignore")
    np.testing.assert_array_equal(out.visual.face_colors[:, :3], np.tile([255, 0, 0], (len(out.faces), 1)))
