"""LatticeNoise: Phillips' basis, the properties the paper promises, both evaluation paths, hard cases."""
import numpy as np
import pytest

from noiselab import LatticeNoise
from noiselab.lattice import KERNELS, Grid, get_kernel, grid_coordinates

RNG = np.random.default_rng(12345)
ALL_KERNELS = list(KERNELS)


# --------------------------------------------------------------- kernels
@pytest.mark.parametrize("name", ALL_KERNELS)
def test_kernel_weights_partition_unity_and_keep_one_sign(name):
    k = get_kernel(name)
    t = np.linspace(0, 1, 2001)[:-1]
    w = k.weights(t)
    np.testing.assert_allclose(w.sum(axis=1), 1.0, atol=1e-13)
    # every tap keeps one sign on [0, 1): the range bound's proof relies on it
    for tap in range(k.taps):
        col = w[:, tap]
        assert (col >= -1e-15).all() or (col <= 1e-15).all(), (name, tap)
    # the bound S = sup sum |w| is attained (up to sampling) and never exceeded
    s = np.abs(w).sum(axis=1)
    assert s.max() <= k.abs_sum_max and s.max() > k.abs_sum_max - 1e-6


def test_kernel_family_and_aliases():
    assert get_kernel("bspline4") is KERNELS["cubic"]
    assert get_kernel("Catmull-Rom") is KERNELS["catmull-rom"]
    assert KERNELS["catmull-rom"].abs_sum_max == pytest.approx(1.25, abs=1e-9)
    # B-splines of order m are m box filters: the order-4 B-spline equals the
    # order-2 one convolved with itself (tent * tent), sampled
    x = np.linspace(-3, 3, 6001)
    dx = x[1] - x[0]
    tent = KERNELS["linear"](x)
    conv = np.convolve(tent, tent, mode="same") * dx
    np.testing.assert_allclose(conv, KERNELS["cubic"](x), atol=2e-3)
    with pytest.raises(ValueError, match="kernel must be one of"):
        get_kernel("gaussian")


@pytest.mark.parametrize("name", ["linear", "catmull-rom", "quintic"])
def test_interpolating_kernels_pass_through_the_hashed_lattice_values(name):
    # value at the integer lattice point (ix, iy) is the table value reached by
    # the nested permutation P[(P[ix] + iy) mod n] (Phillips 2.4.1), / bound
    noise = LatticeNoise(2, 2, rng=7, kernel=name)
    ij = RNG.integers(-600, 600, size=(200, 2))
    got = noise(ij.astype(float))
    n = noise.table_size
    for c in range(2):
        p = noise.perms[c]
        h = p[(p[ij[:, 0] % n] + ij[:, 1] % n) % n]
        expected = noise.values[0, h] * noise.scale
        np.testing.assert_allclose(got[:, c], expected, rtol=0, atol=1e-15)


@pytest.mark.parametrize("alternation", ["table", "lattice"])
@pytest.mark.parametrize("name", ["linear", "catmull-rom", "quintic"])
def test_3d_values_at_lattice_points_are_the_nested_permutation(name, alternation):
    # the 3-D point kernel must give P[(P[(P[ix] + iy) mod n] + iz) mod n]
    # exactly, with the lattice parity
    noise = LatticeNoise(3, 2, rng=8, kernel=name, alternation=alternation)
    ijk = RNG.integers(-700, 700, size=(300, 3))
    n = noise.table_size
    par = ijk.sum(axis=1) & 1
    for trial in range(2):
        got = noise(ijk.astype(float))
        for c in range(2):
            p = noise.perms[c]
            h = p[(p[(p[ijk[:, 0] % n] + ijk[:, 1] % n) % n] + ijk[:, 2] % n) % n]
            np.testing.assert_allclose(got[:, c], noise.values[par, h] * noise.scale, rtol=0, atol=1e-15)
        # the kernels read the public value table where it is
        noise.values[:] = -noise.values[:, ::-1]


def test_3d_gradient_tables_follow_changed_gradients():
    noise = LatticeNoise(3, rng=3, kernel="quintic", basis="gradient")
    x = RNG.uniform(-20, 20, (500, 3))
    before = noise(x)
    noise.gradients[:] = -noise.gradients
    np.testing.assert_allclose(noise(x), -before, rtol=0, atol=1e-15)


# ----------------------------------------------------------------- basis
def test_tables_permutations_and_alternation():
    noise = LatticeNoise(3, 4, rng=1)
    n = noise.table_size
    assert ((noise.positive > 0) & (noise.positive <= 1)).all()
    assert ((noise.negative >= -1) & (noise.negative < 0)).all()
    for p in noise.perms:
        assert sorted(p.tolist()) == list(range(n))
    # a different permutation for every output component
    assert len({tuple(p) for p in noise.perms}) == 4
    # "table": the alternated table holds exactly n/2 positive and n/2 negative values
    table = noise.values[0]
    assert (table[0::2] > 0).all() and (table[1::2] < 0).all()


def test_lattice_alternation_follows_lattice_parity():
    noise = LatticeNoise(2, rng=3, kernel="quintic", alternation="lattice")
    ij = RNG.integers(-300, 300, size=(500, 2))
    v = noise(ij.astype(float))
    sign = np.where((ij.sum(axis=1) % 2) == 0, 1.0, -1.0)
    assert (v * sign > 0).all()
    # the table alternation has no such checkerboard: signs agree with parity about half the time
    w = LatticeNoise(2, rng=3, kernel="quintic")(ij.astype(float))
    assert 0.35 < np.mean(w * sign > 0) < 0.65
    with pytest.raises(ValueError, match="period must be even"):
        LatticeNoise(2, alternation="lattice", period=5)


def test_first_components_do_not_depend_on_dim_out():
    x = RNG.uniform(-20, 20, (300, 2))
    one = LatticeNoise(2, 1, rng=9)(x)
    three = LatticeNoise(2, 3, rng=9)(x)
    np.testing.assert_array_equal(one, three[:, 0])
    assert np.corrcoef(three[:, 0], three[:, 1])[0, 1] < 0.3


# ------------------------------------------------------------ properties
@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("name", ALL_KERNELS)
def test_range_within_minus_one_one_and_not_vacuous(name, basis):
    noise = LatticeNoise(2, 2, rng=4, kernel=name, basis=basis)
    v = noise.grid((300, 300), [(0.0, 40.0), (-7.0, 33.0)])
    assert np.abs(v).max() <= 1.0
    assert np.abs(v).max() > 0.35 and v.std() > 0.08


def test_gradient_bound_is_tight():
    # at a cell centre, with every corner gradient pointing away from the
    # corner, quintic gradient noise reaches exactly the proved bound: output 1
    noise = LatticeNoise(2, rng=0, kernel="quintic", basis="gradient")
    p = noise.perms[0]
    n = noise.table_size
    for ix in (0, 1):
        for iy in (0, 1):
            r = np.array([0.5 - ix, 0.5 - iy])
            noise.gradients[p[(p[ix] + iy) % n]] = r / np.linalg.norm(r)
    v = noise(np.array([0.5, 0.5]))
    assert 1 - 1e-11 < v <= 1


def test_catmull_rom_overshoot_is_absorbed_by_the_bound():
    # adversarial table: values +-1 with the signs of the Catmull-Rom weights
    # at t = 1/2 make the raw sum reach S**2 = 1.5625; the output is exactly 1
    noise = LatticeNoise(2, rng=0, kernel="catmull-rom")
    p = noise.perms[0]
    n = noise.table_size
    sign = np.array([-1.0, 1.0, 1.0, -1.0])
    table = np.zeros(n)
    for a, ix in enumerate(range(-1, 3)):
        for b, iy in enumerate(range(-1, 3)):
            table[p[(p[ix % n] + iy % n) % n]] = sign[a] * sign[b]
    noise.values[:] = table
    v = noise(np.array([0.5, 0.5]))
    assert 1 - 1e-11 < v <= 1


def test_repeatable_and_seeded():
    x = RNG.uniform(-50, 50, (400, 3))
    a = LatticeNoise(3, rng=11)(x)
    b = LatticeNoise(3, rng=11)(x)
    c = LatticeNoise(3, rng=np.random.default_rng(11))(x)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(a, c)
    assert np.abs(a - LatticeNoise(3, rng=12)(x)).max() > 0.1
    with pytest.raises(ValueError, match="rng"):
        LatticeNoise(3, rng=-1)


def _power_spectrum_1d(values, cells):
    spec = np.abs(np.fft.rfft(values - values.mean())) ** 2
    freq = np.fft.rfftfreq(values.size, d=cells / values.size)  # cycles per lattice cell
    return freq, spec


def test_band_limited_spectrum_falls_off_above_lattice_frequency():
    noise = LatticeNoise(1, rng=2, kernel="cubic")
    cells = 4096
    v = noise.grid((cells * 16,), [(0, cells)])
    f, s = _power_spectrum_1d(v, cells)
    total = s.sum()
    assert s[f > 1].sum() / total < 5e-3
    bands = [s[(f >= lo) & (f < lo + 1)].sum() for lo in (1, 2, 3)]
    assert bands[0] > 10 * bands[1] > 0 and bands[1] > bands[2]
    # the box filter (order 1) is not band-limited: far more power above 1
    box = LatticeNoise(1, rng=2, kernel="box").grid((cells * 16,), [(0, cells)])
    fb, sb = _power_spectrum_1d(box, cells)
    assert sb[fb > 1].sum() / sb.sum() > 10 * s[f > 1].sum() / total


def test_stationary_statistics_across_the_plane():
    noise = LatticeNoise(2, rng=8)
    img = noise.grid((512, 512), [(0, 64), (0, 64)])
    blocks = img.reshape(4, 128, 4, 128).transpose(0, 2, 1, 3).reshape(16, -1)
    assert np.abs(blocks.mean(axis=1)).max() < 0.1
    stds = blocks.std(axis=1)
    assert stds.max() / stds.min() < 1.3
    # far away (1e9 cells) the statistics are the same
    far = noise.grid((512, 512), [(1e9, 1e9 + 64), (-1e9, -1e9 + 64)])
    assert abs(far.std() / img.std() - 1) < 0.15


def _anisotropy(img, cells):
    n = img.shape[0]
    spec = np.abs(np.fft.fft2(img - img.mean())) ** 2
    f = np.fft.fftfreq(n, d=cells / n)
    fy, fx = np.meshgrid(f, f, indexing="ij")
    r = np.hypot(fx, fy)
    ang = np.mod(np.arctan2(fy, fx), np.pi / 2)
    ring = (r > 0.05) & (r < 0.5)
    axis = ring & ((ang < np.pi / 16) | (ang > np.pi / 2 - np.pi / 16))
    diag = ring & (np.abs(ang - np.pi / 4) < np.pi / 16)
    return (spec[axis].mean()) / (spec[diag].mean())


@pytest.mark.parametrize("name,basis", [("cubic", "value"), ("quintic", "value"), ("quintic", "gradient")])
def test_nearly_isotropic(name, basis):
    # power along the lattice axes vs along the diagonals, in the main band
    ratios = [_anisotropy(LatticeNoise(2, rng=s, kernel=name, basis=basis).grid((256, 256), [(0, 32), (0, 32)]), 32)
              for s in range(3)]
    assert abs(np.mean(ratios) - 1) < 0.2, ratios


def test_pseudo_periodic_with_table_period_and_exact_period():
    noise = LatticeNoise(2, rng=5, table_size=64)
    x = RNG.uniform(-100, 100, (500, 2))
    for axis in range(2):
        shift = np.zeros(2)
        shift[axis] = 64
        np.testing.assert_allclose(noise(x + shift), noise(x), atol=1e-12)
    # no shorter period: values half a table away are unrelated
    assert np.corrcoef(noise(x), noise(x + [32, 0]))[0, 1] < 0.3
    # 3-D scattered points with exact periods, on both kernel families (the
    # table kernels need the last period to be the table size)
    for period in ((3, 5, 64), (3, 5, 6)):
        tile3 = LatticeNoise(3, rng=5, table_size=64, period=period, kernel="catmull-rom")
        x3 = RNG.uniform(-50, 50, (500, 3))
        for axis in range(3):
            step = np.zeros(3)
            step[axis] = period[axis]
            np.testing.assert_allclose(tile3(x3 + step), tile3(x3), atol=1e-12)
        assert np.corrcoef(tile3(x3), tile3(x3 + [0, 0, 1.5]))[0, 1] < 0.5
    # an exact period tiles: the grid over two periods is the one-period grid twice
    tile = LatticeNoise(2, rng=5, period=(3, 5), frequency=(1.0, 2.0))
    one = tile.grid((30, 50), [(0, 3), (0, 2.5)])
    two = tile.grid((60, 100), [(0, 6), (0, 5)])
    np.testing.assert_allclose(two[:30, :50], one, atol=1e-12)
    np.testing.assert_allclose(two[30:, 50:], one, atol=1e-12)


def test_eq2_amplitude_frequency_phase():
    base = LatticeNoise(2, rng=3)
    scaled = LatticeNoise(2, rng=3, amplitude=0.25, frequency=(2.0, 0.5), phase=(0.3, -1.7))
    x = RNG.uniform(-10, 10, (300, 2))
    expected = 0.25 * base(x * [2.0, 0.5] + [0.3, -1.7])
    np.testing.assert_allclose(scaled(x), expected, atol=1e-14)


# ------------------------------------------------------- evaluation paths
@pytest.mark.parametrize("dim", [1, 2, 3, 4, 5])
def test_grid_and_scattered_paths_agree(dim):
    shape = (23, 17, 9, 5, 4)[:dim]
    extent = [(-3.3, 5.1), (0.2, 7.7), (1e6, 1e6 + 4), (-20, -17), (0, 2)][:dim]
    for name, basis in [("cubic", "value"), ("quintic", "gradient"), ("catmull-rom", "value")]:
        noise = LatticeNoise(dim, 2, rng=6, kernel=name, basis=basis)
        grid = noise.grid(shape, extent)
        pts = noise(noise.grid_points(shape, extent))
        assert grid.shape == tuple(shape) + (2,)
        np.testing.assert_allclose(grid, pts, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ALL_KERNELS)
def test_grid_and_scattered_agree_for_every_kernel(name):
    # 1-D for every kernel (2-D and up are covered above for 2- and 4-tap kernels)
    for basis in ("value", "gradient"):
        for alternation in ("table", "lattice"):
            noise = LatticeNoise(1, 2, rng=6, kernel=name, basis=basis, alternation=alternation)
            ext = [(-2.5e3, 1e3 + 9)]
            np.testing.assert_allclose(noise.grid((4001,), ext), noise(noise.grid_points((4001,), ext)), atol=1e-12)


def test_sparse_grid_falls_back_and_still_agrees():
    noise = LatticeNoise(2, rng=1)
    ext = [(0, 5000), (0, 3000)]  # 100 cells per sample
    np.testing.assert_allclose(noise.grid((50, 30), ext), noise(noise.grid_points((50, 30), ext)), atol=1e-12)


@pytest.mark.parametrize("name,basis", [("quintic", "value"), ("cubic", "gradient")])
def test_chunkings_are_bit_identical(name, basis):
    noise = LatticeNoise(3, 2, rng=2, kernel=name, basis=basis)
    pts = RNG.uniform(-30, 30, (20000, 3))
    pts[::5] += 1e13  # past 2**52: no fractional bits
    pts[::11] *= 1e18  # past 2**63: some chunks on the exact (fmod) path
    whole = noise(pts)
    parts = np.concatenate([noise(pts[i:i + 137]) for i in range(0, 20000, 137)])
    np.testing.assert_array_equal(whole, parts)
    # threads split the points into blocks: the same bits
    np.testing.assert_array_equal(noise(pts, workers=3), whole)
    # every point alone, for a sample
    np.testing.assert_array_equal(np.array([noise(p) for p in pts[:50]]), whole[:50])
    if name != "quintic":
        return
    shape, ext = (40, 30, 20), [(0, 5), (2, 9), (-1, 1)]
    full = noise.grid(shape, ext)
    win = noise.grid(shape, ext, window=[(13, 29), (0, 30), (5, 20)])
    np.testing.assert_array_equal(win, full[13:29, :, 5:20])


def test_float32_output_and_input():
    noise = LatticeNoise(2, rng=3)
    x64 = RNG.uniform(-100, 100, (1000, 2))
    x32 = x64.astype(np.float32)
    v32 = noise(x32)
    assert v32.dtype == np.float32
    np.testing.assert_allclose(v32, noise(x32.astype(np.float64)), atol=1e-7)
    # 3-D: the table kernels read float32 points and write float32 output
    # themselves: exactly the rounded float64 evaluation of the widened points
    noise3 = LatticeNoise(3, 2, rng=3, kernel="quintic")
    p32 = RNG.uniform(-100, 100, (3000, 3)).astype(np.float32)
    v3 = noise3(p32)
    assert v3.dtype == np.float32
    np.testing.assert_array_equal(v3, noise3(p32.astype(np.float64)).astype(np.float32))
    np.testing.assert_array_equal(noise3(p32, dtype=np.float64), noise3(p32.astype(np.float64)))
    g32 = noise.grid((64, 64), [(0, 8), (0, 8)], dtype=np.float32)
    assert g32.dtype == np.float32
    np.testing.assert_allclose(g32, noise.grid((64, 64), [(0, 8), (0, 8)]), atol=1e-7)


# ------------------------------------------------------------ hard cases
@pytest.mark.parametrize("origin", [1e6, 1e9, 2.2e9, 1e12, -1e12])
def test_huge_coordinates_stay_smooth_in_range_and_non_degenerate(origin):
    noise = LatticeNoise(2, rng=4)
    # 2000 samples along a diagonal over 20 cells
    t = np.linspace(0, 20, 2000)
    x = np.stack([origin + t, -0.5 * origin + 0.7 * t], axis=-1)
    v = noise(x)
    assert np.abs(v).max() <= 1
    assert v.std() > 0.1                               # not constant
    steps = np.abs(np.diff(v))
    # smooth: no step larger than the kernel's slope bound times the step
    # (plus float64 coordinate quantisation at 1e12: ulp ~ 1.2e-4 cells)
    assert steps.max() < 0.05
    assert np.unique(np.round(v, 12)).size > 1900      # no stair-steps
    # and it is the same function as near the origin, shifted by whole table periods
    n = noise.table_size
    near = noise(x - np.round(x[0] / n) * n)
    np.testing.assert_allclose(near, v, atol=1e-3 if abs(origin) >= 1e12 else 1e-6)


def test_negative_coordinates_and_exact_integers_are_continuous():
    noise = LatticeNoise(1, rng=2, kernel="cubic")
    eps = 1e-12
    for x0 in (-3.0, -1.0, 0.0, 2.0):
        assert abs(noise(x0 - eps) - noise(x0)) < 1e-10
        assert abs(noise(x0 + eps) - noise(x0)) < 1e-10


@pytest.mark.parametrize("dim", [2, 3])
def test_nan_and_inf_are_clear_errors(dim):
    noise = LatticeNoise(dim)
    bad = np.zeros((5000, dim))
    bad[4321, -1] = np.nan
    with pytest.raises(ValueError, match="points must be finite; it holds 1 NaN"):
        noise(bad)
    bad[17, 0] = -np.inf
    with pytest.raises(ValueError, match="holds 2 NaN or inf"):
        noise(bad, workers=2)
    with pytest.raises(ValueError, match="workers"):
        noise(np.zeros((3, dim)), workers=0)
    # finite points whose scaled coordinates overflow are an error too, not garbage
    with pytest.raises(ValueError, match="overflows float64"):
        LatticeNoise(3, frequency=4.0)(np.array([[1e308, 0.0, 0.0]]))
    with pytest.raises(ValueError, match="extent must be finite"):
        noise.grid((4,) * dim, [(0, np.inf)] + [(0, 1)] * (dim - 1))


@pytest.mark.parametrize("dim", [1, 2, 3, 4, 5])
def test_any_input_dimension_and_empty_arrays(dim):
    noise = LatticeNoise(dim, 3, rng=1, kernel="quintic")
    x = RNG.uniform(-9, 9, (7, 5, dim))
    v = noise(x)
    assert v.shape == (7, 5, 3)
    assert np.abs(v).max() <= 1 and v.std() > 0.05
    assert noise(np.zeros((0, dim))).shape == (0, 3)
    assert noise.grid((0,) * dim, [(0, 1)] * dim).shape == (0,) * dim + (3,)


def test_scalar_input_for_one_dimension():
    noise = LatticeNoise(1, rng=3)
    t = np.linspace(0, 10, 50)
    assert noise(t).shape == (50,)
    assert np.ndim(noise(2.5)) == 0
    np.testing.assert_array_equal(noise(t), noise(t[:, None]))


def test_bad_parameters_name_the_parameter():
    with pytest.raises(ValueError, match="dim_in"):
        LatticeNoise(0)
    with pytest.raises(ValueError, match="table_size must be even"):
        LatticeNoise(2, table_size=255)
    with pytest.raises(ValueError, match="basis"):
        LatticeNoise(2, basis="simplex")
    with pytest.raises(ValueError, match="frequency"):
        LatticeNoise(2, frequency=0)
    with pytest.raises(ValueError, match=r"shape \(\.\.\., dim_in=3\)"):
        LatticeNoise(3)(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="extent"):
        LatticeNoise(2).grid((4, 4), [(0, 1)])
    with pytest.raises(ValueError, match="window"):
        LatticeNoise(2).grid((4, 4), [(0, 1), (0, 1)], window=[(0, 5), (0, 4)])


def test_grid_coordinates_follow_arange_convention():
    (c,) = grid_coordinates((5,), [(1.0, 2.0)])
    np.testing.assert_allclose(c, [1.0, 1.2, 1.4, 1.6, 1.8])
    g = Grid((5,), [(1.0, 2.0)])
    assert g.shape == (5,)


# ------------------------------------------------------- the evaluation interface
@pytest.mark.parametrize("hash_", ["table", "integer"])
@pytest.mark.parametrize("d", [2, 3])
def test_evaluation_interface_is_what_the_calls_and_fractal_sums_return(d, hash_):
    """``evaluate``/``evaluate_grid`` and their Jacobian twins give the user calls' and fractal sums' bits."""
    from noiselab import fractal_gradient, fractal_sum, turbulence

    noise = LatticeNoise(d, 2 if d == 3 else 1, rng=7, kernel="quintic", hash=hash_)
    pts = np.random.default_rng(1).uniform(-6, 6, (500, d))
    np.testing.assert_array_equal(noise.evaluate(pts), noise(pts))
    np.testing.assert_array_equal(noise.evaluate(pts.astype(np.float32)), noise(pts.astype(np.float32)))
    np.testing.assert_array_equal(noise.evaluate(pts, octaves=5, name="x"), fractal_sum(noise, pts, 5))
    np.testing.assert_array_equal(noise.evaluate(pts, octaves=4, absval=True, gain=0.6), turbulence(noise, pts, 4, gain=0.6))
    value, jac = noise.evaluate_jacobian(pts, octaves=3)
    fv, fj = fractal_gradient(noise, pts, 3, return_value=True)
    np.testing.assert_array_equal(value, fv)
    np.testing.assert_array_equal(jac, fj if noise.dim_out > 1 else fj[..., None, :])
    np.testing.assert_array_equal(noise.evaluate_jacobian(pts)[1], noise.jacobian(pts))
    shape, ext = (24, 20, 6)[:d], [(0, 3), (-1, 2), (0, 1)][:d]
    np.testing.assert_array_equal(noise.evaluate_grid(shape, ext), noise.grid(shape, ext))
    np.testing.assert_array_equal(noise.evaluate_grid(shape, ext, octaves=3), fractal_sum(noise, Grid(shape, ext), 3))
    none, gj = noise.evaluate_grid_jacobian(shape, ext, octaves=2, return_value=False)
    assert none is None
    np.testing.assert_array_equal(gj, noise.evaluate_grid_jacobian(shape, ext, octaves=2)[1])
    np.testing.assert_array_equal(noise.evaluate_grid_jacobian(shape, ext)[1], noise.jacobian_grid(shape, ext))
    for bad in (dict(octaves=0), dict(lacunarity=1.0), dict(gain=0.0)):
        with pytest.raises(ValueError, match=next(iter(bad))):
            noise.evaluate(pts, **bad)
        with pytest.raises(ValueError, match=next(iter(bad))):
            noise.evaluate_grid(shape, ext, **bad)
    with pytest.raises(ValueError, match=r"x must have shape"):
        noise.evaluate(np.zeros((3, d + 1)), name="x")


def test_check_grid_names_shape_and_extent():
    from noiselab.lattice.grid import check_grid

    shape, ext = check_grid([3, 2], [(0, 1), (2, 4)], 2)
    assert shape == (3, 2) and ext.dtype == np.float64 and ext.tolist() == [[0, 1], [2, 4]]
    with pytest.raises(ValueError, match="shape"):
        check_grid((3,), [(0, 1), (2, 4)], 2)
    with pytest.raises(ValueError, match="extent"):
        check_grid((3, 2), [(0, np.inf), (2, 4)], 2)


@pytest.mark.parametrize("module", ["noiselab.lattice.core", "noiselab.lattice.grid", "noiselab.lattice.tables",
                                    "noiselab.fractal.octaves", "noiselab.fields.curl", "noiselab.fields.warp"])
def test_docstring_examples_run(module):
    import doctest
    import importlib

    result = doctest.testmod(importlib.import_module(module), optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0


def test_default_kernel_is_chosen_per_basis():
    """Gradient noise defaults to Perlin's quintic fade, value noise to Phillips' cubic B-spline; a named kernel wins."""
    assert LatticeNoise(3, basis="gradient").kernel.name == "quintic"
    assert LatticeNoise(3).kernel.name == "cubic"
    assert LatticeNoise(3, basis="gradient", kernel="cubic").kernel.name == "cubic"
    assert LatticeNoise(2, kernel="quintic").kernel.name == "quintic"
    x = np.random.default_rng(0).uniform(0, 64, (20000, 3))
    default = LatticeNoise(3, basis="gradient", rng=2)
    assert np.array_equal(default(x), LatticeNoise(3, basis="gradient", rng=2, kernel="quintic")(x))
    # the quintic default reaches further into its bound than the cubic B-spline did (0.76 against 0.57 here)
    assert np.abs(default(x)).max() > 0.7 > np.abs(LatticeNoise(3, basis="gradient", rng=2, kernel="cubic")(x)).max()


@pytest.mark.parametrize("dim,dim_out,hash_", [(2, 1, "table"), (2, 1, "integer"), (2, 2, "table"), (3, 1, "table"),
                                               (3, 3, "integer")])
def test_grid_workers_split_into_bands_and_keep_the_bits(monkeypatch, dim, dim_out, hash_):
    from noiselab import fractal_sum, turbulence
    from noiselab.lattice import grid_path

    bands = []
    real = grid_path.map_blocks

    def counting(fn, blocks, n):  # the split must really happen, else equality proves nothing
        blocks = list(blocks)
        bands.append(len(blocks))
        return real(fn, blocks, n)

    monkeypatch.setattr(grid_path, "MIN_BAND", 1)
    monkeypatch.setattr(grid_path, "map_blocks", counting)
    noise = LatticeNoise(dim, dim_out, rng=5, kernel="quintic", hash=hash_)
    shape = (37, 29, 11)[:dim]
    ext = [(0, 3), (1, 4.5), (-2, 0)][:dim]
    for dtype in (np.float32, np.float64):
        one = noise.grid(shape, ext, dtype=dtype)
        assert np.array_equal(noise.grid(shape, ext, dtype=dtype, workers=3), one)
        assert bands[-1] == 3
    win = [(5, 30)] + [(0, s) for s in shape[1:]]  # a window is split alike
    assert np.array_equal(noise.grid(shape, ext, window=win, workers=-1), one[5:30])
    g = Grid(shape, ext)
    one_fbm, one_turb = fractal_sum(noise, g, 5), turbulence(noise, g, 4)
    assert np.array_equal(fractal_sum(noise, g, 5, workers=2), one_fbm)
    assert bands[-1] == 2
    assert np.array_equal(turbulence(noise, g, 4, workers=4), one_turb)
    assert bands[-1] == 4
    if dim_out == 1:
        h, grad = noise.gradient_grid(shape, ext, return_value=True)
        h2, grad2 = noise.gradient_grid(shape, ext, return_value=True, workers=2)
        assert np.array_equal(h, h2) and np.array_equal(grad, grad2)
    # more threads than rows: one band a row
    three_rows = noise.grid((3,) + shape[1:], ext)
    assert np.array_equal(noise.grid((3,) + shape[1:], ext, workers=8), three_rows)
    assert bands[-1] == 3


def _count_bands(monkeypatch):
    """The number of bands of every grid kernel call from now on (a list that fills)."""
    from noiselab.lattice import grid_path

    calls = []
    real = grid_path.map_blocks

    def counting(fn, blocks, n):
        blocks = list(blocks)
        calls.append(len(blocks))
        return real(fn, blocks, n)

    monkeypatch.setattr(grid_path, "map_blocks", counting)
    return calls


def test_grid_workers_is_validated_and_small_grids_stay_on_one_thread(monkeypatch):
    calls = _count_bands(monkeypatch)
    noise = LatticeNoise(2, rng=1)
    small = noise.grid((512, 512), [(0, 4), (0, 4)], workers=2)  # 262,144 samples x 1 octave: below one band
    assert calls == [1] and small.shape == (512, 512)
    noise.grid((1024, 1024), [(0, 4), (0, 4)], workers=2)  # 1 Mi samples x 1 octave: still one band
    assert calls == [1, 1]
    noise.evaluate_grid((1024, 1024), [(0, 4), (0, 4)], octaves=4, workers=2)  # 4 Mi sample-octaves: two bands
    assert calls == [1, 1, 2]
    for bad in (0, -1000, 1.5, True):
        with pytest.raises((ValueError, TypeError), match="workers"):
            noise.grid((8, 8), [(0, 1), (0, 1)], workers=bad)


def test_workers_none_follows_scipy_fft_and_a_first_call_does_not_import_it(monkeypatch):
    # workers=None is scipy.fft's current default: a set_workers block around the call splits it; without
    # scipy.fft imported (no block can be open) it is 1, and a first lattice call does not import scipy.fft
    # (0.05-0.15 s) or tqdm only to learn that
    import subprocess
    import sys

    import scipy.fft

    calls = _count_bands(monkeypatch)
    noise = LatticeNoise(2, rng=1)
    one = noise.evaluate_grid((1024, 1024), [(0, 4), (0, 4)], octaves=4)
    with scipy.fft.set_workers(2):
        two = noise.evaluate_grid((1024, 1024), [(0, 4), (0, 4)], octaves=4)
    assert calls == [1, 2] and np.array_equal(one, two)
    code = ("import sys; from noiselab import LatticeNoise; LatticeNoise(2, rng=1).grid((8, 8), [(0, 1), (0, 1)]); "
            "print(sorted(m for m in ('scipy.fft', 'tqdm') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=600)
    assert out.stdout.strip() == "[]"


@pytest.mark.parametrize("dim", [2, 3])
def test_grid_bands_share_one_set_up(monkeypatch, dim):
    # two threads split the fused kernel's rows, not the window: every axis's taps are made once, as for one
    from noiselab import fractal_sum
    from noiselab.lattice import grid_path

    made = []
    real = grid_path.octave_axis_taps

    def counting(noise, coords_a, *args, **kwargs):
        made.append(coords_a.shape[0])
        return real(noise, coords_a, *args, **kwargs)

    monkeypatch.setattr(grid_path, "MIN_BAND", 1)
    monkeypatch.setattr(grid_path, "octave_axis_taps", counting)
    monkeypatch.setattr(grid_path, "AXIS_TAPS_KEPT", 0)  # none kept: each call makes its own
    monkeypatch.setattr(grid_path, "_AXIS_TAPS", {})
    noise = LatticeNoise(dim, rng=3, kernel="quintic")
    g = Grid((40, 24, 9)[:dim], [(0, 3), (0, 2), (0, 1)][:dim])
    one = fractal_sum(noise, g, 4, dtype=np.float32)
    n_one = len(made)
    two = fractal_sum(noise, g, 4, dtype=np.float32, workers=2)
    assert np.array_equal(one, two)
    assert len(made) - n_one == n_one and made[n_one:] == made[:n_one]  # the whole axes, once each


def test_a_grid_s_axis_taps_are_shared_read_only_and_keyed_on_all_they_depend_on(monkeypatch):
    # the fused path keeps the axis taps of the last grids: the same bits whether made or reused, and never
    # reused for another phase, frequency, kernel or period
    from noiselab import fractal_sum
    from noiselab.lattice import grid_path

    made = []
    real = grid_path.octave_axis_taps

    def counting(*args, **kwargs):
        made.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(grid_path, "_AXIS_TAPS", {})
    monkeypatch.setattr(grid_path, "octave_axis_taps", counting)
    g = Grid((33, 20), [(0, 3), (0.5, 2)])
    first = fractal_sum(LatticeNoise(2, rng=1, kernel="quintic"), g, 4)
    n_made = len(made)
    assert n_made == 2  # two different axes
    # another seed on the same grid: the taps are reused, the values are the seed's own
    other = fractal_sum(LatticeNoise(2, rng=2, kernel="quintic"), g, 4)
    assert len(made) == n_made and not np.array_equal(other, first)
    monkeypatch.setattr(grid_path, "_AXIS_TAPS", {})
    assert np.array_equal(fractal_sum(LatticeNoise(2, rng=2, kernel="quintic"), g, 4), other)  # made afresh: same
    made.clear()
    for noise in (LatticeNoise(2, rng=1, kernel="quintic", phase=0.25), LatticeNoise(2, rng=1, kernel="cubic"),
                  LatticeNoise(2, rng=1, kernel="quintic", frequency=1.5),
                  LatticeNoise(2, rng=1, kernel="quintic", basis="gradient"),
                  LatticeNoise(2, rng=1, kernel="quintic", period=8)):
        before = len(made)
        fractal_sum(noise, g, 4)
        assert len(made) > before, noise
    cached, _ = next(iter(grid_path._AXIS_TAPS.values()))
    with pytest.raises(ValueError, match="read-only"):
        cached[0][2][...] = 0.0
    assert len(grid_path._AXIS_TAPS) <= grid_path.AXIS_TAPS_KEPT
    # a memory bound: taps bigger than a quarter of it are not kept, and what is kept stays within it
    monkeypatch.setattr(grid_path, "AXIS_TAPS_BYTES", 40_000)
    monkeypatch.setattr(grid_path, "_AXIS_TAPS", {})
    fractal_sum(LatticeNoise(2, rng=1, kernel="quintic"), Grid((2000, 8), [(0, 30), (0, 1)]), 4)
    assert [n for _, n in grid_path._AXIS_TAPS.values()] and max(n for _, n in grid_path._AXIS_TAPS.values()) <= 10_000
    for width in (40, 41, 42, 43, 44, 45):
        fractal_sum(LatticeNoise(2, rng=1, kernel="quintic"), Grid((width, 300), [(0, 3), (0, 20)]), 4)
    assert sum(n for _, n in grid_path._AXIS_TAPS.values()) <= 40_000


@pytest.mark.parametrize("hash_", ["table", "integer"])
def test_a_grid_s_kernel_arguments_are_kept_per_tables_and_made_again_when_they_change(monkeypatch, hash_):
    # the fused kernel's arguments (stacked taps, hash prefixes, folded tables) are kept with the axis taps:
    # reused only for the same taps and the same tables' contents, made again (same bits as made afresh)
    # for another seed, a table edited in place or another basis
    from noiselab import fractal_sum
    from noiselab.lattice import grid_path

    made = []
    real = grid_path._make_rows_plan

    def counting(*args):
        made.append(1)
        return real(*args)

    monkeypatch.setattr(grid_path, "_ROW_PLANS", {})
    monkeypatch.setattr(grid_path, "_make_rows_plan", counting)
    g = Grid((40, 24, 9), [(0, 3), (0.5, 2), (0, 1)])
    noise = LatticeNoise(3, rng=1, kernel="quintic", hash=hash_)
    first = fractal_sum(noise, g, 3)
    assert np.array_equal(fractal_sum(noise, g, 3), first) and len(made) == 1  # kept: not made again
    np.testing.assert_allclose(fractal_sum(noise, noise.grid_points(*g), 3), first, rtol=0, atol=1e-12)  # the points'
    other = fractal_sum(LatticeNoise(3, rng=2, kernel="quintic", hash=hash_), g, 3)
    assert len(made) == 2 and not np.array_equal(other, first)
    if hash_ == "table":  # the value table is not frozen: an edit in place is seen by the next grid
        noise.values[...] *= -1.0
        assert np.array_equal(fractal_sum(noise, g, 3), -first) and len(made) == 3
    grad = LatticeNoise(3, rng=1, kernel="quintic", hash=hash_, basis="gradient")
    plain = fractal_sum(grad, g, 3)
    monkeypatch.setattr(grid_path, "_ROW_PLANS", {})
    assert np.array_equal(fractal_sum(grad, g, 3), plain)  # made afresh: the same bits
    assert len(grid_path._ROW_PLANS) == 1
    # made from taps that are not kept, the arguments are not kept either; the count and memory bounds hold
    monkeypatch.setattr(grid_path, "AXIS_TAPS_KEPT", 0)
    monkeypatch.setattr(grid_path, "_ROW_PLANS", {})
    fractal_sum(grad, g, 3)
    assert not grid_path._ROW_PLANS
    monkeypatch.setattr(grid_path, "AXIS_TAPS_KEPT", 2)
    for rng in range(4):
        fractal_sum(LatticeNoise(3, rng=rng, kernel="quintic", hash=hash_), g, 3)
    assert len(grid_path._ROW_PLANS) == 2
    monkeypatch.setattr(grid_path, "AXIS_TAPS_BYTES", 1000)
    monkeypatch.setattr(grid_path, "_ROW_PLANS", {})
    monkeypatch.setattr(grid_path, "_AXIS_TAPS", {})
    fractal_sum(noise, g, 3)
    assert not grid_path._ROW_PLANS
