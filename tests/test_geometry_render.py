"""Geometry: off-screen rendering (pyvista) and the ``noiselab mesh`` command. Images are small (<= 128 px)."""
import numpy as np
import pytest

import noiselab
from noiselab.cli import main
from noiselab.geometry import (
    arrange,
    displace,
    displace_frames,
    load_model,
    render_mesh,
    render_sequence,
    render_turntable,
    sphere,
)
from noiselab.io import read_image, read_mesh, read_video, write_mesh

WHITE = 255


def foreground(img):
    return np.any(img.astype(int) < WHITE - 8, axis=2)


def test_rendered_sphere_fills_the_middle_of_a_white_image(tmp_path):
    img = render_mesh(sphere(3), tmp_path / "s.png", size=(96, 128))
    assert img.shape == (96, 128, 3) and img.dtype == np.uint8
    fg = foreground(img)
    assert 0.15 < fg.mean() < 0.8
    rows, cols = np.nonzero(fg)
    assert abs(rows.mean() - 48) < 6 and abs(cols.mean() - 64) < 6      # centred
    assert np.all(img[0, 0] == WHITE) and np.all(img[-1, -1] == WHITE)   # corners are background
    np.testing.assert_array_equal(read_image(tmp_path / "s.png"), img)
    # shaded, not flat: a lit sphere shows a range of tones
    assert np.ptp(img[fg].mean(axis=1)) > 60


def test_scene_layout_puts_x_right_and_y_up():
    left = sphere(2, center=(-2.0, 0.0, 0.0))
    right = sphere(2, center=(2.0, 0.0, 0.0))
    img = render_mesh([left, right], size=(64, 128), view="xy", colors=["red", "blue"]).astype(int)
    red = (img[..., 0] > 120) & (img[..., 2] < 80)
    blue = (img[..., 2] > 120) & (img[..., 0] < 80)
    assert red.sum() > 100 and blue.sum() > 100
    assert np.nonzero(red)[1].mean() < 50 < 78 < np.nonzero(blue)[1].mean()
    top = sphere(2, center=(0.0, 2.0, 0.0))
    bottom = sphere(2, center=(0.0, -2.0, 0.0))
    img = render_mesh([top, bottom], size=(128, 64), view="xy", colors=["red", "blue"]).astype(int)
    red = (img[..., 0] > 120) & (img[..., 2] < 80)
    blue = (img[..., 2] > 120) & (img[..., 0] < 80)
    assert np.nonzero(red)[0].mean() < np.nonzero(blue)[0].mean()       # +y is up: lower row index


def test_arranged_panels_show_growing_displacement():
    spheres = [displace(sphere(4), noiselab.LatticeNoise(3, rng=1), a, 2.0) for a in (0.0, 0.3)]
    img = render_mesh(arrange(spheres), size=(64, 128), view="xy")
    fg = foreground(img)
    left, right = fg[:, :64], fg[:, 64:]
    assert left.sum() > 200 and right.sum() > 200
    # the plain sphere's silhouette is a disc; the displaced one is not
    def roundness(mask):
        rows, cols = np.nonzero(mask)
        r = np.hypot(rows - rows.mean(), cols - cols.mean())
        edge = r[r > np.percentile(r, 90)]
        return edge.std() / edge.mean()
    assert roundness(right) > roundness(left)


def test_color_by_displacement_uses_the_colormap():
    out = displace(sphere(4), noiselab.LatticeNoise(3, rng=2), 0.2, 2.0)
    img = render_mesh(out, size=96, scalars="displacement").astype(int)
    fg = foreground(img)
    chroma = np.ptp(img[fg], axis=1)
    assert np.mean(chroma > 40) > 0.5                    # viridis is coloured, the default grey is not
    with pytest.raises(ValueError, match="not a vertex attribute"):
        render_mesh(sphere(2), size=32, scalars="displacement")


def test_turntable_turns_and_loops(tmp_path):
    ant = load_model("ant")
    video = render_turntable(ant, tmp_path / "t.gif", frames=4, size=64)
    assert video.shape == (4, 64, 64, 3)
    assert np.abs(video[1].astype(int) - video[0]).mean() > 2          # the view changes
    back = read_video(tmp_path / "t.gif")
    assert back.shape[0] == 4


def test_sequence_follows_the_shape_over_time(tmp_path):
    field = lambda p: np.sin(4 * p[:, 0] + 2 * p[:, 3])
    frames = displace_frames(sphere(3), field, [0.0, 0.0, 1.5], amplitude=0.2)
    video = render_sequence(frames, tmp_path / "b.mp4", size=64, fps=10)
    assert video.shape == (3, 64, 64, 3)
    np.testing.assert_array_equal(video[0], video[1])                   # same time, same picture
    assert np.abs(video[2].astype(int) - video[0]).mean() > 1            # later time, new shape
    assert (tmp_path / "b.mp4").stat().st_size > 0
    with pytest.raises(ValueError, match="different topology"):
        render_sequence([sphere(2), sphere(3)], size=32)


# ---------------------------------------------------------------- the command
def test_cli_writes_mesh_and_render_creating_folders(tmp_path, capsys):
    out_mesh = tmp_path / "a" / "b" / "s.ply"
    out_img = tmp_path / "c" / "s.png"
    rc = main(["mesh", "--shape", "squashed", "--field", "fractal", "--octaves", "2", "-a", "0.1", "-f", "1.5",
               "-o", str(out_mesh), "--render", str(out_img), "--size", "64"])
    assert rc == 0
    mesh = read_mesh(out_mesh)
    assert mesh.is_watertight
    r = np.linalg.norm(mesh.vertices * [1, 1, 1 / 0.95], axis=1)      # undo the squash
    assert r.min() > 1 - 0.16 and r.max() < 1 + 0.16 and np.ptp(r) > 0.01
    img = read_image(out_img)
    assert img.shape[:2] == (64, 64) and foreground(img).mean() > 0.1
    text = capsys.readouterr().out
    assert "vertices" in text and "watertight: True" in text


def test_cli_refines_a_coarse_input_file_and_can_refuse_it(tmp_path, capsys):
    coarse = tmp_path / "coarse.obj"
    write_mesh(coarse, sphere(1))
    out = tmp_path / "fine.stl"
    assert main(["mesh", "-i", str(coarse), "-f", "2", "-o", str(out)]) == 0
    assert "subdividing" in capsys.readouterr().out
    fine = read_mesh(out)
    assert len(fine.faces) > 16 * 80 and fine.is_watertight
    assert main(["mesh", "-i", str(coarse), "-f", "2", "-o", str(out), "--resolution", "raise"]) == 2
    assert "too coarse" in capsys.readouterr().err


def test_cli_plane_becomes_a_monge_surface_fine_enough_for_the_noise(tmp_path):
    out = tmp_path / "p.obj"
    assert main(["mesh", "--shape", "plane", "--field", "turbulence", "--octaves", "3", "-f", "1", "-a", "0.2",
                 "-o", str(out)]) == 0
    m = read_mesh(out)
    assert len(m.vertices) == 47 ** 2                # ceil(2 sqrt(2) * 4 * 4) + 1 per side: no refinement needed
    assert m.vertices[:, 2].min() >= -1e-12 and m.vertices[:, 2].max() > 0.01     # turbulence pushes up only
    from noiselab.geometry import resolution_report

    flat = m.copy()
    flat.vertices[:, 2] = 0
    assert resolution_report(flat, 4.0).ok                                         # 4 samples per top-octave period


def test_cli_vector_displacement_moves_vertices_off_the_normal(tmp_path):
    out = tmp_path / "v.ply"
    assert main(["mesh", "--shape", "sphere", "--subdivisions", "3", "-f", "1", "-a", "0.2",
                 "--direction", "vector", "-o", str(out)]) == 0
    moved = read_mesh(out).vertices - sphere(3).vertices
    n = sphere(3).vertices / np.linalg.norm(sphere(3).vertices, axis=1, keepdims=True)
    tangential = np.linalg.norm(moved - np.einsum("ij,ij->i", moved, n)[:, None] * n, axis=1)
    assert tangential.max() > 0.02


def test_cli_turntable_video(tmp_path):
    out = tmp_path / "v" / "t.gif"
    assert main(["mesh", "--shape", "sphere", "--subdivisions", "3", "-f", "1", "--render", str(out),
                 "--frames", "3", "--size", "32"]) == 0
    assert read_video(out).shape[0] == 3


@pytest.mark.parametrize("argv, match", [
    (["mesh", "--shape", "sphere"], "nothing to do"),
    (["mesh", "-o", "x.xyz"], "--output must end in"),
    (["mesh", "--render", "x.webm"], "--render must end in"),
    (["mesh", "-o", "x.ply", "--octaves", "3"], "single octave"),
    (["mesh", "-o", "x.ply", "-f", "-2"], "--frequency must be in"),
    (["mesh", "-i", "no/such/file.ply", "-o", "x.ply"], "no such mesh file"),
])
def test_cli_bad_input_is_a_one_line_error(argv, match, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert match in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


def test_stereo_pair_views_differ_by_the_separation():
    from noiselab.geometry import render_stereo_pair

    ant = load_model("ant")
    pair = render_stereo_pair(ant, size=64, separation=6.0, gap=4)
    assert pair.shape == (64, 132, 3)
    right_eye, left_eye = pair[:, :64].astype(int), pair[:, 68:].astype(int)
    assert np.abs(right_eye - left_eye).mean() > 0.5          # two viewpoints ...
    assert abs(foreground(right_eye).mean() - foreground(left_eye).mean()) < 0.05   # ... of the same object
    np.testing.assert_array_equal(pair[:, 64:68], 255)


def test_pyvista_meshes_are_accepted_and_converted():
    from noiselab.geometry.render import require_pyvista

    pv = require_pyvista()
    out = displace(pv.Sphere(radius=1.0, theta_resolution=40, phi_resolution=40), lambda p: np.ones(len(p)), 0.1)
    r = np.linalg.norm(out.vertices, axis=1)
    np.testing.assert_allclose(r, 1.1, atol=0.01)
    with pytest.raises(ValueError, match="no polygon faces"):
        displace(pv.PolyData(np.random.default_rng(0).normal(size=(20, 3))), lambda p: np.ones(len(p)))


def test_wireframe_draws_thin_dark_lines_not_a_filled_disc():
    surface = render_mesh(sphere(2), size=96, colors="black")
    wire = render_mesh(sphere(2), size=96, colors="black", style="wireframe")
    def white_inside(img):          # background showing through the middle of the object
        return float((img[32:64, 32:64].min(axis=2) > 240).mean())
    assert white_inside(surface) < 0.02
    assert white_inside(wire) > 0.2
    assert (wire.max(axis=2) < 100).mean() > 0.05              # and the lines are there, dark
    rows, cols = np.nonzero(foreground(wire))
    assert abs(rows.mean() - 48) < 8 and abs(cols.mean() - 48) < 8
    with pytest.raises(ValueError, match="style must be"):
        render_mesh(sphere(1), size=32, style="toon")
