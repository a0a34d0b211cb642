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
    noise2 = noiselab.LatticeNoise(2, seed=3)
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
    noise = noiselab.LatticeNoise(1, 3, seed=5)
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
def test_grid_and_height_map_follow_the_image_convention():
    pts = grid_points((3, 5), ((0, 5), (10, 13)))
    assert pts.shape == (3, 5, 2)
    np.testing.assert_array_equal(pts[2, 4], [4.0, 12.0])
    h = height_map(lambda p: p[:, 0] + 10 * p[:, 1], (3, 5), ((0, 5), (0, 3)), on_aliasing="ignore")
    np.testing.assert_array_equal(h[0], np.arange(5.0))          # x along columns
    np.testing.assert_array_equal(h[:, 0], [0.0, 10.0, 20.0])   # y along rows


def test_height_map_of_lattice_noise_matches_its_grid_path():
    noise = noiselab.LatticeNoise(2, seed=9)
    h = height_map(noise, (32, 48), ((0, 6), (0, 4)))
    # the lattice's grid takes shape and extent in the same axis order (x first)
    ref = noise.grid((48, 32), [(0, 6), (0, 4)])
    np.testing.assert_allclose(h, ref.T, atol=1e-12)


def test_monge_surface_heights_normals_and_aliasing():
    m = monge_surface(lambda p: np.sin(p[:, 0]) * np.cos(p[:, 1]), (40, 30), ((0, 3), (0, 4)), amplitude=0.5)
    assert len(m.vertices) == 1200 and len(m.faces) == 2 * 39 * 29
    np.testing.assert_allclose(m.vertices[:, 2], 0.5 * np.sin(m.vertices[:, 0]) * np.cos(m.vertices[:, 1]))
    assert np.all(m.face_normals[:, 2] > 0)                     # wound to face up
    assert not m.is_watertight
    with pytest.warns(AliasingWarning, match="grid too coarse"):
        monge_surface(noiselab.LatticeNoise(2), (16, 16), ((0, 8), (0, 8)), octaves=3)


def test_fractal_and_turbulent_height_maps_differ_as_expected():
    noise = noiselab.LatticeNoise(2, seed=1)
    f = height_map(noise, (128, 128), ((0, 4), (0, 4)), octaves=4)
    t = height_map(noise, (128, 128), ((0, 4), (0, 4)), octaves=4, kind="turbulence")
    assert t.min() >= 0 and f.min() < 0
    one = height_map(noise, (128, 128), ((0, 4), (0, 4)))
    # more octaves add high-frequency energy: the mean gradient grows
    assert np.abs(np.diff(f, axis=1)).mean() > 1.3 * np.abs(np.diff(one, axis=1)).mean()


def test_hue_surface_takes_height_and_colour_from_the_two_outputs():
    noise = noiselab.LatticeNoise(2, 2, seed=2)
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
    noise = noiselab.LatticeNoise(2, 4, seed=3)
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
    pts, vec = flow_field(rotation, (4, 5), ((0, 5), (0, 4)), amplitude=2.0)
    assert pts.shape == vec.shape == (4, 5, 2)
    np.testing.assert_allclose(vec, 2.0 * np.stack([-pts[..., 1], pts[..., 0]], axis=-1))
    p3, v3 = flow_field(lambda p: p[:, ::-1], (2, 3, 4), ((0, 4), (0, 3), (0, 2)))
    assert p3.shape == (2, 3, 4, 3)
    np.testing.assert_array_equal(p3[1, 2, 3], [3.0, 2.0, 1.0])      # (x, y, z) at [z, y, x]


def test_streamlines_rk4_and_solve_ivp_agree_and_follow_the_flow():
    seeds = np.array([[1.0, 0.0], [0.0, 0.5]])
    rk = streamlines(rotation, seeds, step=0.05, n_steps=126)
    iv = streamlines(rotation, seeds, step=0.05, n_steps=126, method="solve_ivp")
    np.testing.assert_allclose(np.linalg.norm(rk, axis=2), np.broadcast_to([[1.0], [0.5]], (2, 127)), atol=1e-6)   # circles
    np.testing.assert_allclose(rk, iv, atol=1e-4)
    unit = streamlines(lambda p: 5.0 * rotation(p), seeds, step=0.01, n_steps=10, normalize=True)
    np.testing.assert_allclose(np.linalg.norm(np.diff(unit, axis=1), axis=2), 0.01, rtol=1e-3)
    with pytest.raises(ValueError, match="seeds must have shape"):
        streamlines(rotation, np.zeros((3, 5)))


def test_lattice_flow_streamlines_are_smooth():
    noise = noiselab.LatticeNoise(2, 2, seed=0)
    lines = streamlines(noise, np.random.default_rng(0).uniform(0, 4, (20, 2)), step=0.02, n_steps=100)
    steps = np.linalg.norm(np.diff(lines, axis=1), axis=2)
    assert steps.max() <= 0.02 * 1.0 + 1e-9                 # |v| <= 1 per component... and speed bounded
    turn = np.abs(np.diff(steps, axis=1)).max()
    assert turn < 0.002                                    # no jumps in speed along a line


def test_quiver_and_glyphs_draw_something():
    img = quiver_image(noiselab.LatticeNoise(2, 2, seed=1), shape=(8, 8), size=128, streamline_seeds=5)
    dark = img.mean(axis=2) < 128
    assert dark.sum() > 100 and dark[:, :64].any() and dark[:, 64:].any()
    glyphs = flow_glyphs(noiselab.LatticeNoise(3, 3, seed=1), (3, 3, 3))
    assert glyphs.n_points > 27 and glyphs.n_cells > 27
    lo, hi = np.asarray(glyphs.bounds)[0::2], np.asarray(glyphs.bounds)[1::2]
    assert np.all(lo > -1.5) and np.all(hi < 4.0)           # arrows stay within about a cell of the grid
