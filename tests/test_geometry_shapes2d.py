"""Geometry: noisy arcs and circles (Eq. 3), trajectories, Monge surfaces, height+colour surfaces, flow fields."""
import numpy as np
import pytest

import noiselab
from noiselab.geometry import (
    AliasingWarning,
    colored_surface,
    flow_field,
    flow_glyphs,
    grid_points,
    height_map,
    height_map_image,
    monge_surface,
    noisy_arc,
    noisy_circle,
    plot_curves,
    quiver_image,
    streamline_image,
    streamlines,
    trajectory,
    trajectory_frames,
)


def wave1(u):
    return np.sin(2.3 * u[:, 0]) * np.cos(0.7 * u[:, 0] + 0.4)


def wave1_2(u):
    return np.stack([np.sin(2.3 * u[:, 0]), np.cos(1.1 * u[:, 0] + 0.4)], axis=1)


def rotation(p):
    return np.stack([-p[:, 1], p[:, 0]], axis=1)


# ---------------------------------------------------------------- arcs, circles, trajectories
def test_radial_arc_keeps_angles_and_stays_within_amplitude():
    theta = np.linspace(-0.2, 0.8, 300)
    pts = noisy_arc(wave1, theta, radius=2.0, amplitude=0.3, frequency=5.0, phase=0.1)
    r = np.hypot(pts[:, 0], pts[:, 1])
    np.testing.assert_allclose(r, 2.0 + 0.3 * wave1((5.0 * theta + 0.1)[:, None]), atol=1e-12)
    np.testing.assert_allclose(np.arctan2(pts[:, 0], pts[:, 1]), theta, atol=1e-12)   # x = r sin, y = r cos
    clean = noisy_arc(wave1, theta, radius=2.0, amplitude=0.0)
    np.testing.assert_allclose(np.hypot(clean[:, 0], clean[:, 1]), 2.0)


def test_arc_in_the_papers_units_degrees():
    theta_deg = np.linspace(-2.5, 2.5, 101)                  # figure 3: a 5-degree arc, 2 cycles per degree
    deg = noisy_arc(wave1, theta_deg, amplitude=0.01, frequency=2.0, degrees=True)
    rad = noisy_arc(wave1, np.radians(theta_deg), amplitude=0.01, frequency=2.0 * 180 / np.pi)
    np.testing.assert_allclose(deg, rad, atol=1e-12)
    np.testing.assert_allclose(np.degrees(np.arctan2(deg[:, 0], deg[:, 1])), theta_deg, atol=1e-9)


def test_xy_arc_moves_points_by_the_2d_output():
    theta = np.linspace(0, 1, 50)
    pts = noisy_arc(wave1_2, theta, radius=1.0, amplitude=0.2, frequency=3.0, mode="xy")
    base = np.stack([np.sin(theta), np.cos(theta)], axis=1)
    np.testing.assert_allclose(pts - base, 0.2 * wave1_2(3.0 * theta[:, None]), atol=1e-12)
    with pytest.raises(ValueError, match="at least 2 components"):
        noisy_arc(wave1, theta, mode="xy")
    with pytest.raises(ValueError, match="mode must be"):
        noisy_arc(wave1, theta, mode="polar")


def test_closed_circle_has_no_seam_and_literal_eq3_does():
    noise2 = noiselab.LatticeNoise(2, rng=3)
    closed = noisy_circle(noise2, 720, amplitude=0.3, frequency=3.0)
    # Eq. 3 with a 1-D input: the noise at theta = 2 pi is not the noise at 0
    opened = noisy_circle(wave1, 720, amplitude=0.3, frequency=3.0, closed=False)
    assert abs(wave1(np.array([[6 * np.pi]]))[0] - wave1(np.array([[0.0]]))[0]) > 0.25
    def seam_ratio(c):
        steps = np.linalg.norm(np.diff(c, axis=0), axis=1)
        return np.linalg.norm(c[0] - c[-1]) / np.median(steps)
    assert seam_ratio(closed) < 3.0
    assert seam_ratio(opened) > 5.0
    r = np.hypot(closed[:, 0], closed[:, 1])
    assert r.min() >= 0.7 - 1e-12 and r.max() <= 1.3 + 1e-12 and np.ptp(r) > 0.05


def test_trajectory_is_amplitude_times_vector_noise_of_time():
    noise = noiselab.LatticeNoise(1, 3, rng=5)
    t = np.linspace(0, 2, 200)
    path = trajectory(noise, t, amplitude=2.0, frequency=3.0, dims=2)
    assert path.shape == (200, 2)
    np.testing.assert_allclose(path, 2.0 * noise((3.0 * t)[:, None])[:, :2], atol=1e-12)
    assert np.abs(np.diff(path, axis=0)).max() < 0.2           # smooth: small steps for small dt
    with pytest.raises(ValueError, match="vector"):
        trajectory(wave1, t)


def test_curve_plot_draws_dark_lines_on_white():
    arc = noisy_arc(wave1, np.linspace(0, np.pi, 200), amplitude=0.1, frequency=4.0)
    img = plot_curves([arc], size=128)
    assert img.shape == (128, 128, 3)
    dark = img.mean(axis=2) < 128
    assert 50 < dark.sum() < 0.2 * dark.size
    rows = np.nonzero(dark.any(axis=1))[0]
    # a half circle over y >= 0 through the top: ink spans most of the height and width
    assert np.ptp(rows) > 40


def test_trajectory_frames_show_the_point_moving():
    pts = np.stack([np.linspace(0, 1, 6), np.zeros(6)], axis=1)
    frames = trajectory_frames(pts, tail=2, size=64)
    assert frames.shape == (6, 64, 64, 3)
    def dark_cols(f):
        return np.nonzero((f.mean(axis=2) < 60).any(axis=0))[0].mean()
    assert dark_cols(frames[0]) < dark_cols(frames[-1])        # moves right


# ---------------------------------------------------------------- surfaces
def test_grid_and_height_map_take_shape_and_extent_in_array_axis_order():
    pts = grid_points((3, 5), ((10, 13), (0, 5)))              # (ny, nx), ((y0, y1), (x0, x1))
    assert pts.shape == (3, 5, 2)
    np.testing.assert_array_equal(pts[2, 4], [12.0, 4.0])       # (y, x) at [row, column]
    h = height_map(lambda p: 10 * p[:, 0] + p[:, 1], (3, 5), ((0, 3), (0, 5)), on_alias="ignore")
    np.testing.assert_array_equal(h[0], np.arange(5.0))          # x along columns
    np.testing.assert_array_equal(h[:, 0], [0.0, 10.0, 20.0])   # y along rows
    p3 = grid_points((2, 3, 4), ((0, 2), (0, 3), (0, 4)))
    np.testing.assert_array_equal(p3[1, 2, 3], [1.0, 2.0, 3.0])  # (z, y, x) at [z, y, x]
    with pytest.raises(ValueError, match="one per array axis"):
        grid_points((3, 5), ((0, 1), (0, 1), (0, 1)))


def test_height_map_of_lattice_noise_is_its_grid_with_the_same_shape_and_extent():
    # one order for shapes and extents: the same numbers give the same field, not its transpose
    noise = noiselab.LatticeNoise(2, rng=9)
    shape, extent = (32, 48), ((0.0, 4.0), (1.0, 7.0))            # non-square shape and extent
    ref = noise.grid(shape, extent)
    h = height_map(noise, shape, extent)
    assert h.shape == ref.shape == (32, 48)
    np.testing.assert_allclose(h, ref, rtol=0, atol=1e-12)
    # the swapped extent is another field (so the equality above says something)
    assert np.abs(height_map(noise, shape, extent[::-1]) - ref).max() > 0.1
    # octave sums: the lattice's own fractal sum over its Grid
    from noiselab.fractal import fractal_sum
    from noiselab.lattice import Grid

    np.testing.assert_allclose(height_map(noise, shape, extent, octaves=3, on_alias="ignore"),
                               fractal_sum(noise, Grid(shape, extent), 3), rtol=0, atol=1e-12)
    # the same order reads it back: a sampled field over the same extent interpolates the heights
    from noiselab.geometry import sampled_field

    back = sampled_field(h, extent)(grid_points(shape, extent).reshape(-1, 2)).reshape(shape)
    np.testing.assert_allclose(back, h, atol=1e-9)


def test_monge_surface_flow_field_and_normals_follow_the_array_axis_order():
    noise = noiselab.LatticeNoise(2, rng=9, kernel="cubic")
    shape, extent = (24, 36), ((0.0, 2.0), (1.0, 4.0))
    m = monge_surface(noise, shape, extent, amplitude=0.5)
    # vertex i * nx + j is the grid point (y_i, x_j) followed by its height
    np.testing.assert_array_equal(m.vertices[:, :2], grid_points(shape, extent).reshape(-1, 2))
    np.testing.assert_allclose(m.vertices[:, 2].reshape(shape), 0.5 * noise.grid(shape, extent), atol=1e-12)
    assert np.all(m.face_normals[:, 2] > 0)
    hue = colored_surface(noiselab.LatticeNoise(2, 2, rng=2), shape, extent, amplitude=0.5, on_alias="ignore")
    np.testing.assert_allclose(hue.vertices[:, 2].reshape(shape),
                               0.5 * noiselab.LatticeNoise(2, 2, rng=2).grid(shape, extent)[..., 0], atol=1e-12)
    # flow fields: vectors (v_y, v_x) at points (y, x), the lattice's vector grid in 2-D and 3-D
    flow = noiselab.LatticeNoise(2, 2, rng=4)
    pts, vec = flow_field(flow, shape, extent)
    np.testing.assert_array_equal(pts, grid_points(shape, extent))
    np.testing.assert_allclose(vec, flow.grid(shape, extent), rtol=0, atol=1e-12)
    flow3 = noiselab.LatticeNoise(3, 3, rng=5)
    shape3, extent3 = (3, 4, 5), ((0.0, 1.0), (0.0, 2.0), (1.0, 4.0))
    np.testing.assert_allclose(flow_field(flow3, shape3, extent3)[1], flow3.grid(shape3, extent3), atol=1e-12)
    # exact normals at the grid points: (-dz/dy, -dz/dx, 1) in the same order as a finite difference of the map
    fine, ext = (300, 200), ((0.0, 3.0), (0.0, 2.0))
    z, exact = noiselab.monge_normals(noise, grid_points(fine, ext), amplitude=0.5, return_heights=True)
    np.testing.assert_allclose(z, height_map(noise, fine, ext, amplitude=0.5), atol=1e-12)
    zy, zx = np.gradient(z, 3.0 / fine[0], 2.0 / fine[1])
    fd = np.stack([-zy, -zx, np.ones_like(z)], axis=-1)
    fd /= np.linalg.norm(fd, axis=-1, keepdims=True)
    assert noiselab.normal_angles(exact, fd)[1:-1, 1:-1].max() < 0.05      # degrees
    near = np.median(noiselab.normal_angles(noiselab.monge_normals(noise, m.vertices[:, :2], amplitude=0.5),
                                            noiselab.geometry.vertex_normals(m)))
    assert near < 1.0


def test_monge_surface_heights_normals_and_aliasing():
    m = monge_surface(lambda p: np.sin(p[:, 0]) * np.cos(p[:, 1]), (40, 30), ((0, 4), (0, 3)), amplitude=0.5)
    assert len(m.vertices) == 1200 and len(m.faces) == 2 * 39 * 29
    np.testing.assert_allclose(m.vertices[:, 2], 0.5 * np.sin(m.vertices[:, 0]) * np.cos(m.vertices[:, 1]))
    assert np.all(m.face_normals[:, 2] > 0)                     # wound to face up
    assert not m.is_watertight
    with pytest.warns(AliasingWarning, match="grid too coarse"):
        monge_surface(noiselab.LatticeNoise(2), (16, 16), ((0, 8), (0, 8)), octaves=3)


def test_fractal_and_turbulent_height_maps_differ_as_expected():
    noise = noiselab.LatticeNoise(2, rng=1)
    f = height_map(noise, (128, 128), ((0, 4), (0, 4)), octaves=4)
    t = height_map(noise, (128, 128), ((0, 4), (0, 4)), octaves=4, kind="turbulence")
    assert t.min() >= 0 and f.min() < 0
    one = height_map(noise, (128, 128), ((0, 4), (0, 4)))
    # more octaves add high-frequency energy: the mean gradient grows
    assert np.abs(np.diff(f, axis=1)).mean() > 1.3 * np.abs(np.diff(one, axis=1)).mean()


def test_hue_surface_takes_height_and_colour_from_the_two_outputs():
    noise = noiselab.LatticeNoise(2, 2, rng=2)
    m = colored_surface(noise, (32, 32), amplitude=0.5, color="hue")
    pts = grid_points((32, 32), ((0, 4), (0, 4))).reshape(-1, 2)
    out = noise(pts)
    np.testing.assert_allclose(m.vertices[:, 2], 0.5 * out[:, 0], atol=1e-12)
    colors = m.visual.vertex_colors[:, :3].astype(float)
    # the colour follows the second component: vertices with equal 2nd output have equal colour, and it varies
    order = np.argsort(out[:, 1])
    assert np.ptp(colors, axis=0).max() > 100
    assert np.abs(np.diff(colors[order], axis=0)).mean() < 10


def test_rgb_surface_maps_three_outputs_to_rgb():
    noise = noiselab.LatticeNoise(2, 4, rng=3)
    m = colored_surface(noise, (16, 16), color="rgb")
    out = noise(grid_points((16, 16), ((0, 4), (0, 4))).reshape(-1, 2))
    expected = np.rint(np.clip((out[:, 1:4] + 1) / 2, 0, 1) * 255)
    np.testing.assert_array_equal(m.visual.vertex_colors[:, :3], expected)
    with pytest.raises(ValueError, match="at least 4 components"):
        colored_surface(noiselab.LatticeNoise(2, 2), (16, 16), color="rgb")


def test_height_map_image_is_lighter_where_higher():
    h = np.outer(np.ones(4), np.arange(8.0))
    img = height_map_image(h)
    assert img.dtype == np.uint8 and img[0, 0] == 0 and img[0, -1] == 255
    assert np.all(np.diff(img[0].astype(int)) > 0)


# ---------------------------------------------------------------- flow
def test_flow_field_samples_vectors_on_the_grid():
    pts, vec = flow_field(rotation, (4, 5), ((0, 4), (0, 5)), amplitude=2.0)
    assert pts.shape == vec.shape == (4, 5, 2)
    np.testing.assert_allclose(vec, 2.0 * np.stack([-pts[..., 1], pts[..., 0]], axis=-1))
    np.testing.assert_array_equal(pts[3, 4], [3.0, 4.0])             # (y, x) at [row, column]
    p3, v3 = flow_field(lambda p: p[:, ::-1], (2, 3, 4), ((0, 2), (0, 3), (0, 4)))
    assert p3.shape == (2, 3, 4, 3)
    np.testing.assert_array_equal(p3[1, 2, 3], [1.0, 2.0, 3.0])      # (z, y, x) at [z, y, x]
    np.testing.assert_array_equal(v3[1, 2, 3], [3.0, 2.0, 1.0])


def test_streamlines_rk4_and_solve_ivp_agree_and_follow_the_flow():
    seeds = np.array([[1.0, 0.0], [0.0, 0.5]])
    rk = streamlines(rotation, seeds, step=0.05, n_steps=126)
    iv = streamlines(rotation, seeds, step=0.05, n_steps=126, method="solve_ivp")
    np.testing.assert_allclose(np.linalg.norm(rk, axis=2), np.broadcast_to([[1.0], [0.5]], (2, 127)), atol=1e-6)   # circles
    np.testing.assert_allclose(rk, iv, atol=1e-4)
    unit = streamlines(lambda p: 5.0 * rotation(p), seeds, step=0.01, n_steps=10, unit_speed=True)
    np.testing.assert_allclose(np.linalg.norm(np.diff(unit, axis=1), axis=2), 0.01, rtol=1e-3)
    with pytest.raises(ValueError, match="seeds must have shape"):
        streamlines(rotation, np.zeros((3, 5)))


def test_lattice_flow_streamlines_are_smooth():
    noise = noiselab.LatticeNoise(2, 2, rng=0)
    lines = streamlines(noise, np.random.default_rng(0).uniform(0, 4, (20, 2)), step=0.02, n_steps=100)
    steps = np.linalg.norm(np.diff(lines, axis=1), axis=2)
    assert steps.max() <= 0.02 * 1.0 + 1e-9                 # |v| <= 1 per component... and speed bounded
    turn = np.abs(np.diff(steps, axis=1)).max()
    assert turn < 0.002                                    # no jumps in speed along a line


def test_quiver_and_glyphs_draw_something():
    img = quiver_image(noiselab.LatticeNoise(2, 2, rng=1), shape=(8, 8), size=128, streamline_seeds=5)
    dark = img.mean(axis=2) < 128
    assert dark.sum() > 100 and dark[:, :64].any() and dark[:, 64:].any()
    glyphs = flow_glyphs(noiselab.LatticeNoise(3, 3, rng=1), (3, 3, 3))
    assert glyphs.n_points > 27 and glyphs.n_cells > 27
    lo, hi = np.asarray(glyphs.bounds)[0::2], np.asarray(glyphs.bounds)[1::2]
    assert np.all(lo > -1.5) and np.all(hi < 4.0)           # arrows stay within about a cell of the grid
    # the mesh's coordinates are the grid points (z, y, x): a flat extent along z gives a flat cloud of arrows
    flat = flow_glyphs(lambda p: np.tile([0.0, 0.0, 1.0], (len(p), 1)), (2, 4, 4), ((0, 0.2), (0, 4), (0, 4)))
    size = np.asarray(flat.bounds)[1::2] - np.asarray(flat.bounds)[0::2]
    assert size[0] < 0.5 and size[1] > 2.5 and size[2] > 2.5


def test_quiver_and_streamline_images_draw_x_right_and_y_up():
    # an extent wide in x (axis 1) and narrow in y (axis 0), arrows pointing along +x: the ink is wide, not tall
    along_x = lambda p: np.stack([np.zeros(len(p)), np.ones(len(p))], axis=1)      # (v_y, v_x) = (0, 1)
    img = quiver_image(along_x, shape=(2, 12), extent=((0.0, 1.0), (0.0, 6.0)), size=200, amplitude=0.3)
    rows, cols = np.nonzero(img.mean(axis=2) < 128)
    assert np.ptp(cols) > 3 * np.ptp(rows)
    # a streamline of that flow runs along x: one horizontal line; y grows upwards
    line = streamlines(along_x, [[0.5, 0.0]], step=0.1, n_steps=40)
    np.testing.assert_allclose(line[0, -1], [0.5, 4.0], atol=1e-12)
    img = streamline_image(line, size=100, limits=((0.0, 4.0), (0.0, 4.0)))
    rows, cols = np.nonzero(img.mean(axis=2) < 128)
    assert np.ptp(cols) > 80 and np.ptp(rows) < 5 and rows.mean() > 80     # y = 0.5 of 4: near the bottom
