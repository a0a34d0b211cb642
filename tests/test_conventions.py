"""One word, one meaning: the public API's parameters against the conventions table, and every renamed spelling.

The table (``noiselab._core.conventions``) lists each parameter word of the
public API with its meaning, unit, type, default and whether it is
keyword-only. ``test_every_public_signature_follows_the_table`` walks every
public callable (the root's ``_API``, each subpackage's ``__all__``, the
public methods of the public classes) and holds its signature to the table,
so a new function cannot bring a new word, another default or another
calling form without an entry here. Renamed parameters kept their old
spelling, with a warning, until 0.4; since then the old spelling is a
TypeError that names the new one.
"""
import dataclasses
import importlib
import inspect
import pathlib
import re
import warnings

import numpy as np
import pytest
from packaging.version import Version

import noiselab
from noiselab import lab as LAB
from noiselab import snowfall as SNOW
from noiselab import spectral as SP
from noiselab.spectral import envelopes as E
from noiselab import stimuli as STIM
import noiselab.testing
from noiselab.gallery import scenes
from noiselab._core.conventions import REQUIRED, VARIES, WORDS
from noiselab.snowfall.background import default_background

DISPLAY = STIM.Display(32.0)
_W3 = SP.frequency_vectors((4, 8, 8))
IMG = np.linspace(0.0, 1.0, 256).reshape(16, 16)

# (name, function, the other arguments of a small call, its documented rng default)
RANDOM = [
    ("spectral_noise", SP.spectral_noise, dict(shape=(16, 16)), None),
    ("synthesize", SP.synthesize, dict(shape=(8, 8), envelope=lambda *w: np.ones(np.broadcast_shapes(
        *(np.shape(v) for v in w)))), None),
    ("draw_coefficients", SP.draw_coefficients, dict(n=16), None),
    ("snow", SNOW.snow, dict(shape=(4, 16, 16)), None),
    ("snow_spectrum", SNOW.snow_spectrum, dict(shape=(4, 16, 16)), None),
    ("motion_cloud", STIM.motion_cloud, dict(shape=(4, 16, 16), sf_0=0.15, B_sf=0.1), None),
    ("to_display", STIM.to_display, dict(field=IMG, display=DISPLAY, mean=40.0, contrast=0.2), None),
    ("phase_scramble", STIM.phase_scramble, dict(x=IMG), None),
    ("layered_lattice_snow", LAB.layered_lattice_snow, dict(shape=(2, 16, 16), layers=2), None),
    ("particle_snow", LAB.particle_snow, dict(shape=(2, 16, 16), flakes=10), None),
    # fixed pictures: the same picture every run unless asked otherwise
    ("default_background", default_background, dict(height=16, width=16), 7),
    ("house_scene", scenes.house_scene, dict(height=32, width=32), 0),
    ("city_scene", scenes.city_scene, dict(height=32, width=32), 1),
]
IDS = [r[0] for r in RANDOM]
# every one of them but draw_coefficients (which always called it rng) took seed= before
RENAMED = [r for r in RANDOM if r[0] != "draw_coefficients"]
RENAMED_IDS = [r[0] for r in RENAMED]


def _bits(x):
    return np.asarray(x).tobytes()


@pytest.mark.parametrize("name, fn, kw, default", RANDOM, ids=IDS)
def test_random_state_is_rng_with_the_documented_default(name, fn, kw, default):
    params = inspect.signature(fn).parameters
    assert "seed" not in params, f"{name} still shows seed= in its signature"
    assert params["rng"].default == default, f"{name}: rng defaults to {params['rng'].default!r}, not {default!r}"


@pytest.mark.parametrize("name, fn, kw, default", RENAMED, ids=RENAMED_IDS)
def test_seed_is_refused_naming_rng(name, fn, kw, default):
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        fn(**kw, rng=3)   # the new spelling never warns
    for old in (dict(seed=3), dict(seed=3, rng=3)):
        with pytest.raises(TypeError, match=r"seed= was removed in noiselab 0\.4; pass rng= instead"):
            fn(**kw, **old)


@pytest.mark.parametrize("name, fn, kw, default", [r for r in RANDOM if r[0] != "to_display"],
                         ids=[i for i in IDS if i != "to_display"])
def test_an_int_and_its_generator_give_the_same_bits(name, fn, kw, default):
    # (to_display's int rng steps a Weyl sequence of dither offsets, documented there; a Generator draws one)
    assert _bits(fn(**kw, rng=5)) == _bits(fn(**kw, rng=np.random.default_rng(5)))


def test_no_rng_is_fresh_entropy_not_a_fixed_stream():
    """SPEC 7's default: ``rng=None`` draws fresh entropy, so two calls differ (0 was the lattice's old default)."""
    assert _bits(SP.spectral_noise((32, 32))) != _bits(SP.spectral_noise((32, 32)))
    assert _bits(SP.draw_coefficients(32)) != _bits(SP.draw_coefficients(32))


def test_a_bad_rng_is_named_rng():
    for fn, kw in ((SP.spectral_noise, dict(shape=(8, 8))), (SNOW.snow, dict(shape=(2, 8, 8))),
                   (SP.draw_coefficients, dict(n=4)), (STIM.phase_scramble, dict(x=IMG))):
        with pytest.raises(ValueError, match="rng must be a non-negative int"):
            fn(**kw, rng=-1)
        with pytest.raises(TypeError, match="rng must be"):
            fn(**kw, rng=1.5)


def test_write_zarr_records_the_int_rng(tmp_path):
    pytest.importorskip("zarr")
    from noiselab.io import read_zarr, write_zarr

    out = write_zarr(tmp_path / "a.zarr", np.zeros((2, 3), np.float32), rng=4)
    assert read_zarr(out, as_xarray=True).attrs["seed"] == 4
    with pytest.raises(TypeError, match="seed= was removed .* pass rng= instead"):
        write_zarr(tmp_path / "b.zarr", np.zeros((2, 3), np.float32), seed=4)
    assert not (tmp_path / "b.zarr").exists()
    with pytest.raises(TypeError, match="rng must be the int"):
        write_zarr(tmp_path / "c.zarr", np.zeros((2, 3), np.float32), rng=np.random.default_rng(0))


# ------------------------------------------------------------------ one word for one thing
def _lattice2():
    from noiselab.lattice import LatticeNoise

    return LatticeNoise(2, rng=1)   # (LatticeNoise's own rng= arrives with the lattice engine)


def _pink():
    return SP.spectral_noise((64, 64), exponent=1.0, rng=1)




def _sine(p):
    return np.sin(p[:, 0]) * np.cos(p[:, 1])


def _sine2(p):
    return np.stack([np.sin(p[:, 1]), np.cos(p[:, 0])], axis=-1)


# (what, the old spelling's call, the new spelling's call, the deprecated word)
OLD_AND_NEW = [
    ("snow show_progress", lambda: SNOW.snow((2, 16, 16), rng=1, show_progress=False),
     lambda: SNOW.snow((2, 16, 16), rng=1, progress=False), "show_progress"),
    ("spectral_noise amplitude", lambda: SP.spectral_noise((16, 16), rng=1, amplitude="uniform"),
     lambda: SP.spectral_noise((16, 16), rng=1, amplitude_distribution="uniform"), "amplitude"),
    ("synthesize amplitude", lambda: SP.synthesize((8, 8), np.ones((8, 5)), rng=1, amplitude="fixed"),
     lambda: SP.synthesize((8, 8), np.ones((8, 5)), rng=1, amplitude_distribution="fixed"), "amplitude"),
    ("snow amplitude", lambda: SNOW.snow((2, 16, 16), rng=1, amplitude="rayleigh"),
     lambda: SNOW.snow((2, 16, 16), rng=1, amplitude_distribution="rayleigh"), "amplitude"),
    ("snow_spectrum amplitude", lambda: SNOW.snow_spectrum((2, 16, 16), rng=1, amplitude="fixed"),
     lambda: SNOW.snow_spectrum((2, 16, 16), rng=1, amplitude_distribution="fixed"), "amplitude"),
    ("draw_coefficients amplitude", lambda: SP.draw_coefficients(8, 1, amplitude="rayleigh"),
     lambda: SP.draw_coefficients(8, 1, amplitude_distribution="rayleigh"), "amplitude"),
    ("height_map on_aliasing", lambda: noiselab.geometry.height_map(_sine, (8, 8), on_aliasing="ignore"),
     lambda: noiselab.geometry.height_map(_sine, (8, 8), on_alias="ignore"), "on_aliasing"),
    ("monge_surface on_aliasing",
     lambda: noiselab.geometry.monge_surface(_sine, (8, 8), on_aliasing="ignore").vertices,
     lambda: noiselab.geometry.monge_surface(_sine, (8, 8), on_alias="ignore").vertices, "on_aliasing"),
    ("displace on_aliasing",
     lambda: noiselab.displace(noiselab.geometry.sphere(1), _lattice2_3d(), 0.1, on_aliasing="ignore").vertices,
     lambda: noiselab.displace(noiselab.geometry.sphere(1), _lattice2_3d(), 0.1, on_alias="ignore").vertices,
     "on_aliasing"),
    ("assert_power_law tolerance", lambda: noiselab.testing.assert_power_law(_pink(), 1.0, tolerance=0.5).tolerance,
     lambda: noiselab.testing.assert_power_law(_pink(), 1.0, tol=0.5).tolerance, "tolerance"),
    ("assert_isotropic tolerance", lambda: noiselab.testing.assert_isotropic(_pink(), tolerance=0.5).depth2,
     lambda: noiselab.testing.assert_isotropic(_pink(), tol=0.5).depth2, "tolerance"),
    ("envelopes.tent tolerance", lambda: E.tent(*_W3, c=1.0, tolerance=0.5), lambda: E.tent(*_W3, c=1.0, tol=0.5),
     "tolerance"),
    ("envelopes.motion_plane tolerance", lambda: E.motion_plane(*_W3, velocity_yx=(0.0, 1.0), tolerance=0.5),
     lambda: E.motion_plane(*_W3, velocity_yx=(0.0, 1.0), tol=0.5), "tolerance"),
    ("detect_period axis by position",
     lambda: noiselab.analysis.detect_period(np.tile(_pink(), (2, 1)), 0).period,
     lambda: noiselab.analysis.detect_period(np.tile(_pink(), (2, 1)), axis=0).period, "axis"),
    ("squashed_sphere axis by position", lambda: noiselab.geometry.squashed_sphere(0.1, 1, 1.0, 0).vertices,
     lambda: noiselab.geometry.squashed_sphere(0.1, 1, 1.0, axis=0).vertices, "axis"),
    ("to_display kind", lambda: STIM.to_display(IMG, DISPLAY, mean=40.0, contrast=0.2, kind="michelson", rng=1),
     lambda: STIM.to_display(IMG, DISPLAY, mean=40.0, contrast=0.2, contrast_kind="michelson", rng=1), "kind"),
    ("luminance_for kind", lambda: STIM.luminance_for(IMG, mean=40.0, contrast=0.2, kind="michelson"),
     lambda: STIM.luminance_for(IMG, mean=40.0, contrast=0.2, contrast_kind="michelson"), "kind"),
    ("streamlines normalize", lambda: noiselab.geometry.streamlines(_sine2, [[0.5, 0.5]], n_steps=5, normalize=True),
     lambda: noiselab.geometry.streamlines(_sine2, [[0.5, 0.5]], n_steps=5, unit_speed=True), "normalize"),
    ("plot_curves axes", lambda: noiselab.geometry.plot_curves(np.eye(2), size=32, axes=True),
     lambda: noiselab.geometry.plot_curves(np.eye(2), size=32, show_axes=True), "axes"),
    ("octave_energy lo, hi", lambda: noiselab.analysis.octave_energy(_pink(), 4, 32).energy,
     lambda: noiselab.analysis.octave_energy(_pink(), (4, 32)).energy, "lo"),
    ("octave_energy lo=", lambda: noiselab.analysis.octave_energy(_pink(), lo=2.0).energy,
     lambda: noiselab.analysis.octave_energy(_pink(), (2.0, None)).energy, "lo"),
    ("LatticeNoise seed", lambda: noiselab.LatticeNoise(3, seed=5)(np.full((4, 3), 0.3)),
     lambda: noiselab.LatticeNoise(3, rng=5)(np.full((4, 3), 0.3)), "seed"),
    ("evaluate_grid_jacobian value", lambda: noiselab.LatticeNoise(2, rng=2).evaluate_grid_jacobian(
        (6, 5), [(0, 1), (0, 1)], value=False)[1],
     lambda: noiselab.LatticeNoise(2, rng=2).evaluate_grid_jacobian((6, 5), [(0, 1), (0, 1)],
                                                                     return_value=False)[1], "value"),
]


def _lattice2_3d():
    from noiselab.lattice import LatticeNoise

    return LatticeNoise(3, rng=1)


@pytest.mark.parametrize("what, old, new, word", OLD_AND_NEW, ids=[c[0] for c in OLD_AND_NEW])
def test_an_old_spelling_is_refused_naming_the_new_one(what, old, new, word):
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        new()   # the new spelling never warns
    from noiselab._core.renamed import REMOVED_IN

    with pytest.raises(TypeError, match=word) as caught:
        old()
    assert f"removed in noiselab {REMOVED_IN}" in str(caught.value), "the error says since when"
    assert Version(REMOVED_IN) <= Version(noiselab.__version__), "the message names a release not yet made"


@pytest.mark.parametrize("call, match", [
    (lambda: SNOW.snow((2, 8, 8), show_progress=False, progress=False), "show_progress= was removed"),
    (lambda: SP.spectral_noise((8, 8), amplitude="fixed", amplitude_distribution="fixed"), "amplitude= was removed"),
    (lambda: noiselab.LatticeNoise(2, seed=1, rng=1), "seed= was removed .* pass rng="),
    (lambda: noiselab.geometry.height_map(_sine, (8, 8), on_aliasing="ignore", on_alias="ignore"),
     "on_aliasing= was removed"),
    (lambda: noiselab.testing.assert_power_law(_pink(), 1.0, tolerance=1.0, tol=1.0), "tolerance= was removed"),
    (lambda: noiselab.analysis.detect_period(_pink(), 0, axis=0), "pass axis= as a keyword"),
    (lambda: noiselab.analysis.octave_energy(_pink(), 2.0, band=(2.0, 8.0)), "lo and hi were removed"),
])
def test_both_spellings_at_once_is_a_type_error(call, match):
    with pytest.raises(TypeError, match=match):
        call()


def test_a_gallery_figure_names_its_source_not_a_seed(monkeypatch):
    from noiselab.gallery import registry

    monkeypatch.setattr(registry, "REGISTRY", {})
    registry.figure("zz", "new", source="Phillips 2004, Fig. 1", title="t")(_sine)
    with pytest.raises(TypeError, match="seed= was removed .* pass source= instead"):
        registry.figure("zz", "old", seed="Phillips 2004, Fig. 1", title="t")
    assert registry.REGISTRY["zz/new"].source == "Phillips 2004, Fig. 1" and "zz/old" not in registry.REGISTRY


def test_a_bad_amplitude_distribution_is_named():
    with pytest.raises(ValueError, match="amplitude_distribution must be one of"):
        SP.spectral_noise((8, 8), amplitude_distribution="gauss")
    with pytest.raises(ValueError, match="amplitude_distribution must be one of"):
        SNOW.snow((2, 8, 8), amplitude_distribution="gauss")


@pytest.mark.parametrize("fn", [noiselab.fractal_sum, noiselab.turbulence, noiselab.fractal_gradient,
                                noiselab.turbulence_gradient])
def test_workers_defaults_to_scipy_fft_s_none(fn):
    """``workers=None`` (scipy.fft's meaning) everywhere outside the lattice, so a set_workers block reaches it."""
    import scipy.fft

    assert inspect.signature(fn).parameters["workers"].default is None
    pts = np.linspace(0.0, 3.0, 40).reshape(20, 2)
    one = fn(_lattice2(), pts, 3)
    with scipy.fft.set_workers(2):
        assert _bits(fn(_lattice2(), pts, 3)) == _bits(one)


@pytest.mark.parametrize("fn", [SNOW.snow, noiselab.io.write_video, noiselab.geometry.render_sequence,
                                noiselab.geometry.render_turntable, noiselab.io.write_zarr])
def test_progress_is_one_word_with_one_default(fn):
    params = inspect.signature(fn).parameters
    assert "show_progress" not in params and params["progress"].default is None


@pytest.mark.parametrize("fn", [noiselab.analysis.detect_period, noiselab.analysis.variance_striping,
                                noiselab.analysis.slice_leakage, noiselab.geometry.squashed_sphere])
def test_axis_is_keyword_only(fn):
    assert inspect.signature(fn).parameters["axis"].kind is inspect.Parameter.KEYWORD_ONLY


# ------------------------------------------------------------------ array order for per-axis pairs
def _falling_video():
    return SNOW.snow((16, 32, 32), rng=2, c=1.0, band=(2, 8), direction_yx=(1.0, 1.0), pan_yx=(0.0, 0.5),
                     rescale=False, dtype=np.float64)


def _moving_video():
    img = np.random.default_rng(0).random((32, 32))
    return np.stack([np.roll(img, (t, 2 * t), axis=(0, 1)) for t in range(32)])   # (vy, vx) = (1, 2)


XY_OLD_AND_NEW = [
    ("snow direction, pan", lambda: SNOW.snow((4, 16, 16), rng=1, direction=(0.3, 1.0), pan=(0.2, 0.0)),
     lambda: SNOW.snow((4, 16, 16), rng=1, direction_yx=(1.0, 0.3), pan_yx=(0.0, 0.2))),
    ("snow_spectrum direction", lambda: SNOW.snow_spectrum((4, 16, 16), rng=1, direction=(-1.0, 0.5)),
     lambda: SNOW.snow_spectrum((4, 16, 16), rng=1, direction_yx=(0.5, -1.0))),
    ("layered_lattice_snow direction", lambda: LAB.layered_lattice_snow((2, 16, 16), rng=1, layers=2, direction=(1, 1)),
     lambda: LAB.layered_lattice_snow((2, 16, 16), rng=1, layers=2, direction_yx=(1, 1))),
    ("particle_snow direction", lambda: LAB.particle_snow((2, 16, 16), rng=1, flakes=10, direction=(1.0, 0.2)),
     lambda: LAB.particle_snow((2, 16, 16), rng=1, flakes=10, direction_yx=(0.2, 1.0))),
    ("motion_energy velocity by position", lambda: noiselab.analysis.motion_energy(_moving_video(), (2, 1), tol=0.5),
     lambda: noiselab.analysis.motion_energy(_moving_video(), velocity_yx=(1, 2), tol=0.5)),
    ("tent_energy direction by position, pan",
     lambda: noiselab.analysis.tent_energy(_falling_video(), 1.0, (2, 8), (1.0, 1.0), pan=(0.5, 0.0)),
     lambda: noiselab.analysis.tent_energy(_falling_video(), 1.0, (2, 8), direction_yx=(1.0, 1.0), pan_yx=(0.0, 0.5))),
    ("sheared_tent_energy direction, pan by position",
     lambda: noiselab.analysis.sheared_tent_energy(_falling_video(), 1.0, (2, 8), (1.0, 1.0), (0.5, 0.0)),
     lambda: noiselab.analysis.sheared_tent_energy(_falling_video(), 1.0, (2, 8), direction_yx=(1.0, 1.0),
                                                   pan_yx=(0.0, 0.5))),
    ("tent_energy_per_band direction by position",
     lambda: noiselab.analysis.tent_energy_per_band(_falling_video(), 1.0, (2, 8), (1.0, 1.0)).fraction,
     lambda: noiselab.analysis.tent_energy_per_band(_falling_video(), 1.0, (2, 8), direction_yx=(1.0, 1.0)).fraction),
    ("assert_motion velocity by position", lambda: noiselab.testing.assert_motion(_moving_video(), (2, 1)).energy,
     lambda: noiselab.testing.assert_motion(_moving_video(), velocity_yx=(1, 2)).energy),
    ("envelopes.thickened_tent direction, pan by position",
     lambda: E.thickened_tent(*_W3, 1.0, (0.5, 1.0), (0.2, 0.0), thickness=0.1, tol=0.5),
     lambda: E.thickened_tent(*_W3, 1.0, direction_yx=(1.0, 0.5), pan_yx=(0.0, 0.2), thickness=0.1, tol=0.5)),
    ("envelopes.tent_surface direction, pan", lambda: E.tent_surface(*_W3[1:], 1.0, direction=(1.0, 0.0), pan=(0, 1)),
     lambda: E.tent_surface(*_W3[1:], 1.0, direction_yx=(0.0, 1.0), pan_yx=(1, 0))),
    ("envelopes.motion_plane velocity by position", lambda: E.motion_plane(*_W3, (2.0, -1.0), tol=0.5),
     lambda: E.motion_plane(*_W3, velocity_yx=(-1.0, 2.0), tol=0.5)),
    ("envelopes.optical_snow direction, speeds by position", lambda: E.optical_snow(*_W3, (0, 1), (0.5, 2.0), tol=0.5),
     lambda: E.optical_snow(*_W3, direction_yx=(1, 0), speeds=(0.5, 2.0), tol=0.5)),
    ("envelopes.speed_envelope velocity", lambda: E.speed_envelope(*_W3, velocity=(1.0, 0.5), B_V=0.5),
     lambda: E.speed_envelope(*_W3, velocity_yx=(0.5, 1.0), B_V=0.5)),
    ("assert_tent direction, pan",
     lambda: noiselab.testing.assert_tent(_falling_video(), 1.0, (2, 8), direction=(1, 1), pan=(0.5, 0)).energy,
     lambda: noiselab.testing.assert_tent(_falling_video(), 1.0, (2, 8), direction_yx=(1, 1), pan_yx=(0, 0.5)).energy),
]


@pytest.mark.parametrize("what, old, new", XY_OLD_AND_NEW, ids=[c[0] for c in XY_OLD_AND_NEW])
def test_an_x_y_pair_is_refused_naming_the_array_order_keyword(what, old, new):
    """The old ``(x, y)`` keyword (or position), removed in 0.4: a TypeError naming the array-order keyword, never
    silently read as ``(y, x)``."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        new()
    with pytest.raises(TypeError, match=r"_yx=\(y, x\).*array order"):
        old()


def test_array_order_means_y_first():
    """``direction_yx=(1, 0)`` falls down the rows; ``(0, 1)`` moves right along the columns (measured motion)."""
    down = SNOW.snow((16, 32, 32), rng=3, c=1.0, band=(2, 8), direction_yx=(1.0, 0.0), rescale=False)
    right = SNOW.snow((16, 32, 32), rng=3, c=1.0, band=(2, 8), direction_yx=(0.0, 1.0), rescale=False)
    vx, vy = noiselab.analysis.best_velocity(down)          # best_velocity reports (vx, vy)
    assert vy > 0.5 and abs(vx) < 0.1 * vy
    vx, vy = noiselab.analysis.best_velocity(right)
    assert vx > 0.5 and abs(vy) < 0.1 * vx
    assert noiselab.analysis.tent_energy(down, 1.0, (2, 8), direction_yx=(1.0, 0.0)) > 0.999
    assert noiselab.analysis.tent_energy(down, 1.0, (2, 8), direction_yx=(0.0, 1.0)) < 0.5


@pytest.mark.parametrize("call", [
    lambda: SNOW.snow((2, 8, 8), direction=(0, 1), direction_yx=(1, 0)),
    lambda: SNOW.snow((2, 8, 8), pan=(0, 0), pan_yx=(0, 0)),
    lambda: noiselab.analysis.motion_energy(_moving_video(), (2, 1), velocity_yx=(1, 2)),
    lambda: noiselab.analysis.motion_energy(_moving_video(), (2, 1), (1, 2)),
])
def test_both_orders_at_once_is_a_type_error(call):
    with pytest.raises(TypeError, match=r"=\(x, y\) was removed .*_yx=\(y, x\)|positional arguments"):
        call()


@pytest.mark.parametrize("fn, words", [
    (SNOW.snow, ("direction_yx", "pan_yx")), (SNOW.snow_spectrum, ("direction_yx", "pan_yx")),
    (LAB.layered_lattice_snow, ("direction_yx",)), (LAB.particle_snow, ("direction_yx",)),
    (noiselab.analysis.motion_energy, ("velocity_yx",)), (noiselab.analysis.tent_energy, ("direction_yx", "pan_yx")),
    (noiselab.analysis.sheared_tent_energy, ("direction_yx", "pan_yx")),
    (noiselab.analysis.tent_energy_per_band, ("direction_yx",)), (noiselab.testing.assert_motion, ("velocity_yx",)),
    (noiselab.testing.assert_tent, ("direction_yx", "pan_yx")),
])
def test_per_axis_pairs_are_keyword_only_in_array_order(fn, words):
    params = inspect.signature(fn).parameters
    assert not {"direction", "pan", "velocity"} & set(params)
    for w in words:
        assert params[w].kind is inspect.Parameter.KEYWORD_ONLY


def test_the_command_line_takes_array_order_and_the_old_flags_swapped(tmp_path):
    from noiselab.cli import main

    a, b = tmp_path / "a.npy", tmp_path / "b.npy"
    common = ["snow", "--frames", "4", "--width", "32", "--height", "32", "--seed", "3", "--no-background"]
    assert main(common + ["--direction-yx", "2", "1", "--pan-yx", "0", "0.5", "--output", str(a)]) == 0
    assert main(common + ["--direction", "1", "2", "--pan", "0.5", "0", "--output", str(b)]) == 0
    assert np.load(a).tobytes() == np.load(b).tobytes()
    c = tmp_path / "c.npy"   # the same numbers in the other order are another fall direction
    assert main(common + ["--direction-yx", "1", "2", "--pan-yx", "0", "0.5", "--output", str(c)]) == 0
    assert np.load(a).tobytes() != np.load(c).tobytes()
    assert main(common + ["--direction-yx", "2", "1", "--direction", "1", "2", "--output", str(c)]) == 2



# ------------------------------------------------------------------ every public signature against the table
# where the public API lives: the root's names, then each subpackage's __all__ (noiselab.testing included)
PUBLIC_MODULES = ["noiselab"] + [f"noiselab.{s}" for s in noiselab._SUBPACKAGES] + ["noiselab.testing"]
# classes users construct; every other dataclass or named tuple is a result, whose fields are not parameters
INPUT_CLASSES = {"Display", "Grid", "LatticeNoise", "Warped"}


def _is_result(cls):
    named_tuple = issubclass(cls, tuple) and hasattr(cls, "_fields")
    return (dataclasses.is_dataclass(cls) or named_tuple) and cls.__name__ not in INPUT_CLASSES


def public_callables():
    """``(public name, callable)`` for every public function, constructor and method, each once."""
    seen = set()
    for module_name in PUBLIC_MODULES:
        module = importlib.import_module(module_name)
        names = list(noiselab._API) if module_name == "noiselab" else list(getattr(module, "__all__", []))
        for name in names:
            obj = getattr(module, name, None)
            if obj is None or inspect.ismodule(obj) or id(obj) in seen:
                continue
            seen.add(id(obj))
            if inspect.isclass(obj):
                if not _is_result(obj) and not issubclass(obj, BaseException):
                    yield f"{module_name}.{name}", obj
                for attr, value in vars(obj).items():
                    if not attr.startswith("_") and not isinstance(value, property) and (
                            callable(value) or isinstance(value, (staticmethod, classmethod))):
                        yield f"{module_name}.{name}.{attr}", getattr(obj, attr)
            elif callable(obj):
                yield f"{module_name}.{name}", obj


def public_parameters():
    """``(public name, inspect.Parameter)`` for every parameter of every public callable."""
    for qual, fn in public_callables():
        try:
            sig = inspect.signature(fn)
        except (TypeError, ValueError):   # a builtin without a signature
            continue
        for p in sig.parameters.values():
            if p.name not in ("self", "cls") and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
                yield qual, p


def _same_default(got, want):
    if want == REQUIRED:
        return got is inspect.Parameter.empty
    if isinstance(want, type) or isinstance(got, type):
        return got is want
    try:
        return bool(got == want) and type(got) is type(want)
    except (TypeError, ValueError):
        return False


def _violations():
    out = []
    for qual, p in public_parameters():
        word = WORDS.get(p.name)
        if word is None:
            out.append(f"{qual}({p.name}=): not in the conventions table (noiselab/_core/conventions.py)")
            continue
        default, keyword_only = word.per_function.get(qual, (word.default, word.keyword_only))
        if default != VARIES and not _same_default(p.default, default):
            shown = "required" if p.default is inspect.Parameter.empty else repr(p.default)
            out.append(f"{qual}({p.name}=): default {shown}, the table says {default!r}")
        if keyword_only is not None and (p.kind is p.KEYWORD_ONLY) != keyword_only:
            out.append(f"{qual}({p.name}=): {'keyword-only' if p.kind is p.KEYWORD_ONLY else 'positional'}, the "
                       f"table says {'keyword-only' if keyword_only else 'positional'}")
    return out


def test_every_public_signature_follows_the_table():
    bad = _violations()
    assert not bad, "signatures that drift from the conventions table:\n" + "\n".join(bad)


def test_the_table_has_no_stale_entries():
    used = {p.name for _, p in public_parameters()}
    assert not set(WORDS) - used, f"words no public callable takes: {sorted(set(WORDS) - used)}"
    names = {qual for qual, _ in public_callables()}
    for w, word in WORDS.items():
        for qual in word.per_function:
            assert qual in names, f"{w}: per_function names {qual}, which is not public"
        assert word.meaning.strip(), f"{w} has no meaning"
        if word.per_function or word.default == VARIES:
            assert word.note, f"{w}: a per-function default needs its reason (note=)"


def test_the_walk_reaches_every_kind_of_public_callable():
    """Functions, constructors and methods of the root, the subpackages and noiselab.testing; results are not inputs."""
    names = {qual for qual, _ in public_callables()}
    for qual in ("noiselab.spectral_noise", "noiselab.snow", "noiselab.snowfall.snow_spectrum", "noiselab.LatticeNoise.grid",
                 "noiselab.Display.band", "noiselab.analysis.motion_energy", "noiselab.testing.assert_tent",
                 "noiselab.geometry.height_map", "noiselab.io.write_video", "noiselab.fields.Warped.gradient"):
        assert qual in names, qual
    assert "noiselab.analysis.PowerSpectrum" not in names   # a result: its fields are not parameters


# ------------------------------------------------------------------ the docs page shows the table
def render_table():
    """The Markdown table of docs/guide/conventions.md, from the conventions module."""
    def cell(text):
        text = re.sub(r":(?:func|class|meth|mod|data):`~?([^`]+)`", r"`\1`", str(text)).replace("``", "`")
        return text.replace("|", "\\|").replace("\n", " ")

    def default_of(word):
        return {VARIES: "per function", REQUIRED: "required"}.get(word.default, f"`{word.default!r}`") \
            if isinstance(word.default, str) and word.default in (VARIES, REQUIRED) or not isinstance(
                word.default, type) else f"`{word.default.__name__}`"

    rows = ["| word | meaning | unit | type | default | keyword-only |", "|---|---|---|---|---|---|"]
    for name in sorted(WORDS, key=str.lower):
        w = WORDS[name]
        kw = {True: "yes", False: "no", None: "either"}[w.keyword_only]
        meaning = w.meaning + (f" *Where it differs:* {w.note}." if w.note else "")
        if w.per_function:
            meaning += " " + "; ".join(f"`{q.replace('noiselab.', '')}`: `{d!r}`"
                                       for q, (d, _) in w.per_function.items()) + "."
        rows.append(f"| `{name}` | {cell(meaning)} | {cell(w.unit)} | {cell(w.type)} | {cell(default_of(w))} | {kw} |")
    return "\n".join(rows) + "\n"


DOCS_PAGE = pathlib.Path(__file__).resolve().parents[1] / "docs" / "guide" / "conventions.md"
START, END = "<!-- conventions table: start -->\n", "<!-- conventions table: end -->"


def test_the_docs_page_shows_the_table():
    text = DOCS_PAGE.read_text()
    assert START in text and END in text, "docs/guide/conventions.md lost its table markers"
    shown = text.split(START, 1)[1].split(END, 1)[0]
    assert shown == render_table(), ("docs/guide/conventions.md is out of date with noiselab/_core/conventions.py: "
                                     "rewrite it with `python tests/test_conventions.py`")



def test_the_stimulus_command_says_its_units_and_array_order(tmp_path):
    """``--band-cpd`` (cycles/degree: the unit in the name) and ``--velocity-yx``; the old flags mean the same."""
    from noiselab.cli import main

    out = {k: tmp_path / f"{k}.npy" for k in ("new", "old", "swapped")}
    cloud = ["stimulus", "cloud", "--ppd", "16", "--size", "2", "--duration", "0.1", "--seed", "2"]
    assert main(cloud + ["--velocity-yx", "0.5", "2", "-o", str(out["new"])]) == 0
    assert main(cloud + ["--velocity", "2", "0.5", "-o", str(out["old"])]) == 0
    assert main(cloud + ["--velocity-yx", "2", "0.5", "-o", str(out["swapped"])]) == 0
    assert np.load(out["new"]).tobytes() == np.load(out["old"]).tobytes()
    assert np.load(out["new"]).tobytes() != np.load(out["swapped"]).tobytes()
    assert main(cloud + ["--velocity-yx", "0", "1", "--velocity", "1", "0", "-o", str(out["old"])]) == 2
    pink = ["stimulus", "pink", "--ppd", "16", "--size", "2", "--seed", "2", "-o"]
    assert main(pink + [str(out["new"]), "--band-cpd", "1", "4"]) == 0
    assert main(pink + [str(out["old"]), "--band", "1", "4"]) == 0
    assert np.load(out["new"]).tobytes() == np.load(out["old"]).tobytes()


def test_2d_curl_noise_is_the_documented_formula_in_array_order():
    """``curl_noise`` on (y, x) points returns (v_y, v_x) = (dpsi/dx, -dpsi/dy), as its docstring says."""
    noise = _lattice2()
    pts = np.random.default_rng(4).uniform(0.0, 4.0, (50, 2))   # (y, x)
    grad = noise.gradient(pts)                                   # (dpsi/dy, dpsi/dx): one per point axis
    v = noiselab.curl_noise(noise, pts)
    np.testing.assert_allclose(v[:, 0], grad[:, 1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(v[:, 1], -grad[:, 0], rtol=0, atol=1e-12)
    assert "(v_y, v_x) = (dpsi/dx, -dpsi/dy)" in " ".join(noiselab.curl_noise.__doc__.split())


if __name__ == "__main__":   # rewrite the docs page's table from the module
    text = DOCS_PAGE.read_text()
    head, rest = text.split(START, 1)
    DOCS_PAGE.write_text(head + START + render_table() + END + rest.split(END, 1)[1])
