"""The spectral checks: noiselab's own generators measured with noiselab.analysis.

Each check states the property the method promises (the seed papers) and
measures it on the generator's output with the same instruments a user
would point at any other image or video (their closed-form tests are in
``test_analysis.py``).

Units: ``c`` in rad/frame, bands in cycles/frame (cycles per frame width),
velocities in px/frame with +y down. The snow generator thickens the tent
by spreading ``c`` over ``c (1 +- thickness)`` and fills every temporal bin
that overlaps it; ``tent_energy(..., thickness=...)`` with its default
``tol=0.5`` accepts exactly those bins.
"""
import numpy as np
import pytest

import noiselab
from noiselab import analysis as A
from noiselab.lattice import Grid

T, H, W = 32, 128, 128
BAND = (W / 32, W / 4)  # snow's default band: 4..32 cycles/frame at 128 px (16..128 at 512)
CORNER = 128 * np.sqrt(2)  # the corner of a 256 x 256 spectrum, cycles/frame
KERNELS = ["box", "linear", "quadratic", "cubic", "catmull-rom", "quintic"]


@pytest.fixture(scope="module")
def raw_snow():
    return noiselab.snow((T, H, W), seed=1, c=1.0, thickness=0.1, rescale=False)


@pytest.fixture(scope="module")
def alpha_snow():
    return noiselab.snow((T, H, W), seed=1, c=1.0, thickness=0.1)


# ---------------------------------------------------------------- falling snow
def test_snow_energy_lies_on_the_tent_and_inside_the_band(raw_snow, alpha_snow):
    spec = A.video_spectrum(raw_snow)
    assert A.tent_energy(spec, 1.0, BAND, thickness=0.1) > 0.999999
    assert A.band_energy(raw_snow, BAND, axes=(-2, -1)) > 0.99999
    # the instruments can tell: falling up, sideways, or at another c is off the tent
    assert A.tent_energy(spec, 1.0, BAND, direction=(0, -1), thickness=0.1) < 0.2
    assert A.tent_energy(spec, 1.0, BAND, direction=(1, 0), thickness=0.1) < 0.5
    assert A.tent_energy(spec, 0.3, BAND, thickness=0.1) < 0.5
    # the opacity alpha = rescaled ** 1.5 is a nonlinear map of the field: most energy stays on the tent
    assert A.tent_energy(alpha_snow, 1.0, BAND, thickness=0.1) > 0.98
    assert A.band_energy(alpha_snow, BAND, axes=(-2, -1)) > 0.99


@pytest.mark.parametrize("c, thickness", [(0.5, 0.3), (2.0, 0.0)])
def test_thin_and_thick_tents_at_other_c(c, thickness):
    raw = noiselab.snow((T, H, W), seed=2, c=c, thickness=thickness, rescale=False)
    assert A.tent_energy(raw, c, BAND, thickness=thickness) > 0.999999


def test_parallax_law_speed_times_frequency_is_constant(raw_snow):
    prof = A.speed_profile(raw_snow, A.octave_bands(*BAND, per_octave=2))
    assert len(prof.centers) == 6
    # speed = c / |w|: speed x |w| equals c = 1 rad/frame in every band
    np.testing.assert_allclose(prof.parallax, 1.0, rtol=0.04)
    assert np.all(np.diff(prof.speed) < 0)  # near (large, low-frequency) flakes fall faster
    assert prof.speed[0] / prof.speed[-1] == pytest.approx(prof.centers[-1] / prof.centers[0], rel=0.1)
    assert np.all(prof.coherence > 0.95)


def test_snow_falls_down_by_default(raw_snow):
    v = A.best_velocity(raw_snow)
    assert v[1] > 0.5 and abs(v[0]) < 0.05 * v[1]
    speeds = A.band_speeds(raw_snow, A.octave_bands(*BAND, per_octave=1))
    assert speeds.shape == (3, 2)
    assert np.all(speeds[:, 1] > 0) and np.all(np.abs(speeds[:, 0]) < 0.05 * speeds[:, 1])


@pytest.mark.parametrize("angle", [30.0, 180.0, -120.0])
def test_snow_falls_in_a_rotated_direction(angle):
    d = (np.cos(np.deg2rad(angle)), np.sin(np.deg2rad(angle)))
    raw = noiselab.snow((T, H, W), seed=3, c=1.0, direction=d, rescale=False)
    assert A.tent_energy(raw, 1.0, BAND, direction=d, thickness=0.1) > 0.999999
    assert A.tent_energy(raw, 1.0, BAND, thickness=0.1) < 0.5
    for vx, vy in A.band_speeds(raw, A.octave_bands(*BAND, per_octave=1)):
        err = (np.rad2deg(np.arctan2(vy, vx)) - angle + 180) % 360 - 180
        assert abs(err) < 4, (angle, vx, vy)


def test_panning_camera_gives_the_sheared_tent():
    pan = (0.5, 0.0)
    raw = noiselab.snow((T, H, W), seed=4, c=1.0, pan=pan, rescale=False)
    assert A.sheared_tent_energy(raw, 1.0, BAND, pan=pan, thickness=0.1) > 0.999999
    assert A.tent_energy(raw, 1.0, BAND, thickness=0.1) < 0.7
    prof = A.speed_profile(raw, A.octave_bands(*BAND, per_octave=1))
    # every layer carries the pan, to within the velocity resolution of a band: one temporal bin
    # (2 pi / T rad/frame) over the band's |w| (the tent is quantised to whole bins)
    resolution = (2 * np.pi / T) / (2 * np.pi * prof.centers / W)
    assert np.all(np.abs(prof.velocity[:, 0] - 0.5) < 0.3 * resolution), (prof.velocity, resolution)
    assert np.all(np.diff(prof.velocity[:, 1]) < 0)  # and still falls with parallax


def test_aliased_cells_dropped_leave_no_backward_motion():
    raw = noiselab.snow((T, H, W), seed=5, c=3.0, thickness=0.1, on_alias="drop", rescale=False)
    assert A.tent_energy(raw, 3.0, BAND, thickness=0.1) > 0.999999
    speeds = A.band_speeds(raw, A.octave_bands(*BAND, per_octave=2))
    assert np.all(speeds[:, 1] > 0)


def test_snow_loops_and_tiles_seamlessly(alpha_snow):
    assert A.loop_seam(alpha_snow) == pytest.approx(1.0, abs=0.1)
    assert A.loop_seam(alpha_snow[: T - 5]) > 1.5  # a cut loop is seen
    assert A.tile_seam(alpha_snow) < 1.25
    tiled = noiselab.tile(alpha_snow, (2, 2, 2))
    assert A.loop_seam(tiled) == pytest.approx(1.0, abs=0.1)
    assert A.tile_seam(tiled, tile=(H, W)) < 1.25
    frames = np.stack(list(noiselab.iter_tiled_frames(alpha_snow, (2, 3), n_frames=T + 8, start=3)))
    steps = np.sqrt(np.mean(np.diff(frames.astype(np.float64), axis=0) ** 2, axis=(1, 2)))
    seam = T - 3 - 1  # frame index where the loop wraps: alpha[T-1] -> alpha[0]
    assert steps[seam] / np.delete(steps, seam).mean() == pytest.approx(1.0, abs=0.1)
    assert A.tile_seam(frames, tile=(H, W)) < 1.25


# ---------------------------------------------------------------- spectral noise
@pytest.mark.parametrize("exponent", [0.5, 1.0, 2.0])
def test_spectral_noise_has_its_1_over_f_slope(exponent):
    img = noiselab.spectral_noise((512, 512), exponent=exponent, seed=int(10 * exponent))
    fit = A.spectral_slope(img, (4, 128))
    assert abs(fit + exponent) < 0.05, (exponent, fit)


def test_spectral_noise_band_volume_and_octaves():
    img = noiselab.spectral_noise((256, 256), exponent=1.0, band=(8, 64), seed=6)
    assert A.band_energy(img, (8, 64 + 1e-9)) > 0.99999
    assert abs(A.spectral_slope(img, (8, 64)) + 1) < 0.06
    with pytest.raises(ValueError, match="no power"):
        A.spectral_slope(img, (2, 64))  # outside its band there is nothing to fit
    vol = noiselab.spectral_noise((64, 64, 64), exponent=1.5, seed=7)
    assert abs(A.spectral_slope(vol, (4, 24)) + 1.5) < 0.05
    pink = noiselab.spectral_noise((512, 512), exponent=1.0, amplitude="fixed", seed=8)
    assert A.octave_energy(pink, 4, 256).spread < 0.1  # equal energy per octave


def test_spectral_noise_is_isotropic_and_tiles():
    img = noiselab.spectral_noise((512, 512), seed=9)
    assert A.anisotropy(img) < 0.02
    assert A.anisotropy(img[:300, :300], window="hann") < 0.03
    assert A.tile_seam(img) < 1.25


# ---------------------------------------------------------------- lattice noise
@pytest.fixture(scope="module")
def lattice_images():
    """Periodic (tileable) value noise, 8 lattice cells across 256 px, for every kernel."""
    return {
        k: noiselab.LatticeNoise(2, seed=3, kernel=k, period=8).grid((256, 256), [(0, 8), (0, 8)])
        for k in KERNELS
    }


def test_lattice_band_limits_follow_the_kernel(lattice_images):
    f_lattice = 8.0  # one cycle per lattice cell, in cycles/frame
    beyond = {k: A.band_energy(img, (f_lattice, CORNER)) for k, img in lattice_images.items()}
    beyond2 = {k: A.band_energy(img, (2 * f_lattice, CORNER)) for k, img in lattice_images.items()}
    # the box (nearest value) stair is not band-limited; the B-spline family gets tighter with order
    assert beyond["box"] > 0.1
    assert beyond["box"] > 10 * beyond["linear"] > 10 * beyond["quadratic"] > 10 * beyond["cubic"]
    assert beyond["cubic"] < 1e-4 and beyond2["cubic"] < 1e-6
    for k in ("linear", "quadratic", "cubic", "catmull-rom", "quintic"):
        assert beyond[k] < 1e-2, (k, beyond[k])
        assert A.tile_seam(lattice_images[k]) < 1.3, k  # period=8 over 8 cells tiles


def test_lattice_noise_shows_its_axes_where_spectral_noise_does_not(lattice_images):
    # about 190 cells in this band: one isotropic field measures 0.17 +- 0.06 (300 seeds, before and after
    # the spectral rewrite alike: 0.170 and 0.174), so average eight seeds (0.17 +- 0.02)
    spectral = [noiselab.spectral_noise((256, 256), exponent=2.0, band=(1, 8), seed=s) for s in range(10, 18)]
    assert np.mean([A.anisotropy(x, (2, 8)) for x in spectral]) < 0.25
    for k, img in lattice_images.items():
        # the default whitening weights the rings that stand above the radial trend (here the main lobe, where
        # Catmull-Rom is least anisotropic: 0.52, the B-splines 0.85-0.98): the cross still dominates
        o = A.orientation_energy(img)
        assert o.index > 0.4 and o.m4 > 3 * o.m2 and o.axis_ratio > 3, (k, o.m2, o.m4, o.axis_ratio)
        ring = A.orientation_energy(img, whiten="ring")  # every radius alike: the tails past the pass band
        assert ring.axis_ratio > 10, k  # the energy past the pass band runs along the lattice axes


def test_non_periodic_lattice_noise_needs_the_window():
    img = noiselab.LatticeNoise(2, seed=5, kernel="cubic").grid((256, 256), [(0, 8), (0, 8)])
    assert A.tile_seam(img) > 3  # not periodic over the frame
    # the edge jump of the periodic FFT adds a 1/f^2 power cross; the Hann window removes it
    assert A.band_energy(img, (16, CORNER)) > 100 * A.band_energy(A.power_spectrum(img, window="hann"), (16, CORNER))


@pytest.mark.parametrize("kernel", ["cubic", "quintic"])
@pytest.mark.parametrize("gain", [0.5, 2**-0.5, 1.0])
def test_fractal_sum_slope_follows_the_gain(kernel, gain):
    # octave o has amplitude gain**o at 2**o times the frequency: in 2-D the energy per
    # octave falls as gain**2 per octave over 4x the cells, so the amplitude slope is log2(gain) - 1
    noise = noiselab.LatticeNoise(2, seed=4, kernel=kernel)
    img, used = noiselab.fractal_sum(noise, Grid((256, 256), [(0, 4), (0, 4)]), 8, gain=gain, return_octaves=True)
    assert used >= 6
    fit = A.spectral_slope(img, (8, 64), window="hann")
    assert abs(fit - (np.log2(gain) - 1)) < 0.12, (kernel, gain, fit)


def test_the_thesis_scene_at_full_size():
    # Langer & Zhang's own configuration: 64 frames of 512 x 512, band 16..128 cycles/frame
    alpha = noiselab.snow((64, 512, 512), seed=11, c=1.0)
    spec = A.video_spectrum(alpha)
    assert A.tent_energy(spec, 1.0, (16, 128), thickness=0.1) > 0.98
    assert A.band_energy(A.power_spectrum(alpha, axes=(-2, -1)), (16, 128)) > 0.99
    prof = A.speed_profile(alpha, A.octave_bands(16, 128, per_octave=1))
    # nearest flakes 512 / (2 pi 16) = 5.1 px/frame, farthest 0.64 px/frame (c = 1)
    np.testing.assert_allclose(prof.parallax, 1.0, rtol=0.04)
    assert np.all(prof.velocity[:, 1] > 0)
    assert A.loop_seam(alpha) == pytest.approx(1.0, abs=0.05)
