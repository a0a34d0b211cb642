"""Exact derivatives of lattice noise: against central differences, both paths, curl noise, warping, normals.

Central-difference error model used for the tolerances (input units, step h):
C2 kernels (cubic, quintic) err by at most ``h**2 / 6 * sup|f'''|``; C1 kernels
(quadratic, catmull-rom) have a jump in ``f''`` at every lattice line, where
the error can reach ``h * sup|f''|``, so points within one step of a lattice
line are compared with that looser bound separately; rounding adds
``ulp(u) / h * |f'|``, which decides the step at 1e9 (ulp 1.2e-7 there).
"""
import warnings

import numpy as np
import pytest

from noiselab import LatticeNoise, curl_noise, displace, fractal_gradient, turbulence_gradient, warp
from noiselab.fractal import fractal_sum, turbulence
from noiselab.geometry import grid_points, monge_surface, vertex_normals
from noiselab.geometry.normals import displaced_normals, monge_normals, normal_angles
from noiselab.lattice import KERNELS, Grid, grid_path

SMOOTH = [name for name, k in KERNELS.items() if k.continuity >= 1]


def _noise(d, kernel, basis, dim_out=2, **kw):
    kw.setdefault("frequency", np.linspace(1.3, 2.1, d))
    kw.setdefault("phase", 0.37)
    kw.setdefault("amplitude", 1.7)
    return LatticeNoise(d, dim_out, rng=11 + d, kernel=kernel, basis=basis, **kw)


def _central(f, x, h):
    """Central differences of f at x along every input axis: (..., dim_out?, dim_in)."""
    d = x.shape[-1]
    cols = []
    for a in range(d):
        e = np.zeros(d)
        e[a] = h
        cols.append((np.asarray(f(x + e)) - np.asarray(f(x - e))) / (2 * h))
    return np.stack(cols, axis=-1)


def _near_knot(noise, x, h):
    """Points whose central-difference stencil crosses a lattice line of the kernel (per point)."""
    u = x * noise.frequency + noise.phase + noise.kernel.shift
    t = u - np.floor(u)
    reach = 1.01 * h * noise.frequency
    return ((t < reach) | (t > 1 - reach)).any(axis=-1)


def _compare(noise, x, h, tol_smooth, tol_knot):
    jac = noise.jacobian(x)
    fd = _central(noise, x, h).reshape(jac.shape)
    scale = 1.0 + np.abs(jac).max()
    err = np.abs(jac - fd).reshape(len(x), -1).max(axis=1) / scale
    knot = _near_knot(noise, x, h) if noise.kernel.continuity < 2 else np.zeros(len(x), bool)
    assert err[~knot].max() < tol_smooth, (err[~knot].max(), tol_smooth)
    if knot.any():
        assert err[knot].max() < tol_knot
    return err


# ------------------------------------------------------------------ kernels
def test_kernel_continuity_classes_and_derivative_polynomials():
    assert {n: k.continuity for n, k in KERNELS.items()} == {
        "box": -1, "linear": 0, "quadratic": 1, "cubic": 2, "catmull-rom": 1, "quintic": 2}
    t = np.linspace(0.05, 0.95, 19)
    for k in KERNELS.values():
        h = 1e-6
        fd = (k.weights(t + h) - k.weights(t - h)) / (2 * h)
        np.testing.assert_allclose(k.dweights(t), fd, atol=1e-8)
        # the continuous K' is the derivative of K
        x = np.linspace(-2.4, 2.4, 41) + 0.013
        np.testing.assert_allclose(k.derivative(x), (k(x + h) - k(x - h)) / (2 * h), atol=1e-7)


@pytest.mark.parametrize("kernel", ["box", "linear"])
def test_kernels_without_a_continuous_derivative_raise(kernel):
    noise = LatticeNoise(2, rng=0, kernel=kernel)
    for call in (lambda: noise.gradient(np.zeros((2, 2))), lambda: noise.jacobian(np.zeros((2, 2))),
                 lambda: noise.gradient_grid((4, 4), [(0, 1), (0, 1)]), lambda: curl_noise(noise, np.zeros((2, 2))),
                 lambda: fractal_gradient(noise, np.zeros((2, 2)), 3)):
        with pytest.raises(ValueError, match="no continuous first derivative.*kernel must be one of quadratic"):
            call()


# --------------------------------------------- analytic vs central differences
@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("kernel", SMOOTH)
@pytest.mark.parametrize("d", [1, 2, 3, 4])
def test_jacobian_matches_central_differences(d, kernel, basis):
    noise = _noise(d, kernel, basis)
    x = np.random.default_rng(d).uniform(-6, 6, (40, d))
    # h = 1e-5 units: C2 truncation <= 1e-10/6 * sup|f'''| ~ 1e-8; rounding ~ 1e-16/1e-5
    err = _compare(noise, x, 1e-5, tol_smooth=2e-7, tol_knot=1e-3)
    assert np.median(err) < 1e-8
    value, jac = noise.jacobian(x, return_value=True)
    np.testing.assert_allclose(value, noise(x), rtol=0, atol=1e-14)
    assert jac.shape == (40, 2, d)


@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("kernel", SMOOTH)
@pytest.mark.parametrize("d", [1, 2, 3, 4])
def test_jacobian_at_1e9(d, kernel, basis):
    # (a) central differences with a step scaled to the coordinate: at 1e9 a
    # float64 has a spacing of 1.2e-7, so h = 2**-10 units (exact steps) puts
    # the rounding error near 1.2e-7 / 1e-3 ~ 1e-4 |f'| and the C2 truncation
    # near 1e-6 / 6 * sup|f'''| ~ 1e-4 (relative to 1 + max|J|)
    noise = _noise(d, kernel, basis)
    x = 1e9 + np.random.default_rng(d).uniform(0, 8, (40, d))
    _compare(noise, x, 2.0 ** -10, tol_smooth=5e-4, tol_knot=1e-2)
    # (b) sharp: the lattice repeats every 256 cells, so at frequency 2 the
    # noise at 1e9 + r (1e9 = 128 * 7812500) is the noise at r; the only
    # difference is the 1.2e-7 rounding of the coordinate
    per = _noise(d, kernel, basis, frequency=2.0)
    r = (1e9 + np.random.default_rng(d + 10).uniform(0, 8, (40, d))) - 1e9   # exactly representable both ways
    jb, jr = per.jacobian(1e9 + r), per.jacobian(r)
    assert np.abs(jb - jr).max() < 1e-5 * (1 + np.abs(jr).max())


def test_gradient_is_the_scalar_jacobian_and_threads_are_bit_identical():
    noise = LatticeNoise(3, rng=4, kernel="quintic", frequency=[1, 2, 3], phase=[0.1, 0.2, 0.3])
    x = np.random.default_rng(0).uniform(-4, 4, (3, 5000, 3))
    g = noise.gradient(x)
    assert g.shape == (3, 5000, 3)
    np.testing.assert_array_equal(g, noise.jacobian(x)[..., 0, :])
    np.testing.assert_array_equal(noise.gradient(x, workers=2), g)
    one = LatticeNoise(1, rng=2)
    v, g1 = one.gradient(np.linspace(0, 4, 9), return_value=True)
    assert v.shape == (9,) and g1.shape == (9, 1)
    with pytest.raises(ValueError, match="dim_out=1.*use jacobian"):
        LatticeNoise(2, 2).gradient(np.zeros((1, 2)))
    with pytest.raises(ValueError, match="points must be finite"):
        noise.gradient(np.array([[0.0, np.nan, 0.0]]))
    with pytest.raises(ValueError, match="overflows float64"):
        LatticeNoise(2, frequency=1e300).gradient(np.array([[1e10, 0.0]]))
    with pytest.raises(ValueError, match=r"shape \(\.\.\., dim_in=3\)"):
        noise.jacobian(np.zeros((4, 2)))


@pytest.mark.parametrize("hash_", ["table", "integer"])
def test_jacobian_kernels_return_the_value_kernels_values(hash_):
    """Each scattered-point kernel is one source whose derivative lines a flag adds: the value its Jacobian
    kernel returns is the value kernel's, bit for bit, for octave sums and turbulence and every family with the
    same sums (the generic kernels in 1-5-D, the unrolled 1-3-D ones, the 3-D table kernels' value basis). The
    3-D table kernels' gradient basis sums the dot product's parts apart for the derivatives, and the integer
    hash's SIMD kernels (stock kernels, 1-3-D) round apart from its generic one: those agree to 1e-12, see
    tests/test_naive.py. From 4-D on one source serves every dimension (its corners counted, none unrolled):
    4-D without a period and 5-D with one cover it, each compiled specialisation 1.3-2.6 s of the cold suite."""
    import dataclasses

    rng = np.random.default_rng(3)
    custom = dataclasses.replace(KERNELS["quintic"], name="my-quintic")  # not stock: the integer hash's generic kernel
    cases = [(d, k, b, per) for d in (1, 2, 3, 4, 5) for k, b in (("cubic", "value"), ("quintic", "gradient"))
             for per in {4: (None,), 5: (2,)}.get(d, (None, 2))]  # period 2 < taps: the generic kernel in 1-3-D too
    for d, kernel, basis, period in cases:
        if hash_ == "integer" and d <= 3:
            kernel = custom
        elif hash_ == "table" and d == 3 and basis == "gradient" and period is None:
            continue
        noise = _noise(d, kernel, basis, dim_out=2, period=period, hash=hash_)
        x = rng.uniform(-9, 9, (300, d))
        for octaves, absval in ((1, False), (3, False), (3, True)):
            if period is not None and octaves > 1:
                continue  # tileable octave sums run each octave on its own (the same kernels)
            value, _ = noise.evaluate_jacobian(x, octaves=octaves, absval=absval)
            np.testing.assert_array_equal(value, noise.evaluate(x, octaves=octaves, absval=absval), err_msg=str(
                (d, basis, period, octaves, absval)))


# ------------------------------------------------------------------ grid path
@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("d", [1, 2, 3])
def test_grid_jacobian_equals_points_path(d, basis):
    noise = _noise(d, "cubic" if d != 2 else "catmull-rom", basis)
    shape, ext = (23, 17, 9)[:d], [(-1, 2), (0.5, 3), (2, 4)][:d]
    value, jac = noise.jacobian_grid(shape, ext, return_value=True)
    pv, pj = noise.jacobian(noise.grid_points(shape, ext), return_value=True)
    assert jac.shape == tuple(shape) + (2, d)
    np.testing.assert_allclose(jac, pj, rtol=0, atol=1e-13)
    np.testing.assert_array_equal(value, noise.grid(shape, ext))
    # a window is bit-identical to the same slice of the full grid
    win = [(3, 11), (2, 9), (1, 5)][:d]
    part = noise.jacobian_grid(shape, ext, window=win)
    np.testing.assert_array_equal(part, jac[tuple(slice(a, b) for a, b in win)])


def test_grid_gradient_sparse_fallback_and_errors():
    # a grid much sparser than the lattice goes through the per-point path
    noise = LatticeNoise(3, rng=1, kernel="quadratic")
    shape, ext = (20, 20, 20), [(0, 900), (0, 700), (0, 800)]
    assert not grid_path.is_separable(noise.kernel.taps, [np.linspace(a, b, n) for n, (a, b) in zip(shape, ext)],
                                      noise.frequency)
    np.testing.assert_allclose(noise.gradient_grid(shape, ext), noise.gradient(noise.grid_points(shape, ext)),
                               rtol=0, atol=1e-13)
    with pytest.raises(ValueError, match="use jacobian_grid"):
        LatticeNoise(2, 3).gradient_grid((4, 4), [(0, 1), (0, 1)])


# ------------------------------------------------------------------ fractal
@pytest.mark.parametrize("basis", ["value", "gradient"])
@pytest.mark.parametrize("absval", [False, True])
def test_fractal_and_turbulence_gradients(absval, basis):
    value_fn, grad_fn = (turbulence, turbulence_gradient) if absval else (fractal_sum, fractal_gradient)
    noise = LatticeNoise(2, rng=3, basis=basis, frequency=1.5)
    x = np.random.default_rng(1).uniform(-5, 5, (200, 2))
    value, grad = grad_fn(noise, x, 5, normalize=True, return_value=True)
    np.testing.assert_allclose(value, value_fn(noise, x, 5, normalize=True), rtol=0, atol=1e-14)
    fd = _central(lambda p: value_fn(noise, p, 5, normalize=True), x, 1e-6)
    err = np.abs(grad - fd).max(axis=1)
    # cubic: C2 within each octave; turbulence has creases where an octave
    # crosses zero, where a stencil straddling one may disagree
    assert np.median(err) < 1e-8
    assert (err < 1e-6).mean() > (0.97 if absval else 0.999)
    # grid path (3 octaves: all visible at this spacing) equals the points path
    grid = Grid((40, 30), [(0, 2), (1, 3)])
    gv, gg, used = grad_fn(noise, grid, 3, return_value=True, return_octaves=True)
    pv, pg = grad_fn(noise, noise.grid_points(grid.shape, grid.extent), 3, return_value=True)
    assert used == 3 and gg.shape == (40, 30, 2)
    np.testing.assert_allclose(gg, pg, rtol=0, atol=1e-13)
    np.testing.assert_allclose(gv, value_fn(noise, grid, 3), rtol=0, atol=1e-14)
    # vector noise: (..., dim_out, dim_in) on both paths
    vec = LatticeNoise(2, 3, rng=4, basis=basis)
    vg = grad_fn(vec, grid, 3)
    assert vg.shape == (40, 30, 3, 2)
    np.testing.assert_allclose(vg, grad_fn(vec, vec.grid_points(grid.shape, grid.extent), 3), rtol=0, atol=1e-13)


def test_turbulence_crease_has_derivative_zero_and_one_sided_slopes_either_side():
    # gradient noise with an interpolating kernel is exactly 0 at every
    # lattice point: |n| has a corner there
    noise = LatticeNoise(1, rng=5, basis="gradient", kernel="quintic")
    x = np.array([3.0, 7.0])
    slope = fractal_gradient(noise, x, 1)[:, 0]
    assert (np.abs(slope) > 1e-3).all()
    np.testing.assert_array_equal(turbulence_gradient(noise, x, 1)[:, 0], 0.0)      # sign(0) = 0, documented
    left = turbulence_gradient(noise, x - 1e-9, 1)[:, 0]
    right = turbulence_gradient(noise, x + 1e-9, 1)[:, 0]
    np.testing.assert_allclose(left, -np.abs(slope), rtol=1e-6)
    np.testing.assert_allclose(right, np.abs(slope), rtol=1e-6)


# ------------------------------------------------------------------ curl noise
def _divergence(field, x, h):
    d = x.shape[-1]
    return sum((field(x + h * np.eye(d)[a])[..., a] - field(x - h * np.eye(d)[a])[..., a]) / (2 * h)
               for a in range(d))


@pytest.mark.parametrize("d", [2, 3])
def test_curl_noise_is_divergence_free_and_vector_noise_is_not(d):
    potential = LatticeNoise(d, 1 if d == 2 else 3, rng=8, kernel="quintic", frequency=1.3)
    plain = LatticeNoise(d, d, rng=8, kernel="quintic", frequency=1.3)
    x = np.random.default_rng(d).uniform(0, 6, (400, d))
    h = 1e-5
    v = curl_noise(potential, x)
    div_curl = _divergence(lambda p: curl_noise(potential, p), x, h)
    div_plain = _divergence(plain, x, h)
    speed = np.sqrt((v ** 2).sum(-1)).mean()
    # FD truncation h^2/6 (|A'''| terms) and rounding eps/h: ~1e-9 of the speed; plain noise: order 1
    assert np.abs(div_curl).max() < 1e-7 * speed
    assert np.abs(div_plain).mean() > 0.1 * np.abs(plain.jacobian(x)).mean()
    if d == 2:
        # the flow runs along the potential's contours: v . grad(psi) = 0
        g = potential.gradient(x)
        assert np.abs((v * g).sum(-1)).max() < 1e-14 * (1 + np.abs(g).max() ** 2)
    # grid path and fractal potentials are divergence-free too
    grid = Grid((24,) * d, [(0, 2)] * d)
    vg = curl_noise(potential, grid, octaves=3)
    pts = potential.grid_points(grid.shape, grid.extent)
    np.testing.assert_allclose(vg, curl_noise(potential, pts, octaves=3), rtol=0, atol=1e-12)
    div_frac = _divergence(lambda p: curl_noise(potential, p, octaves=3), x[:50], h)
    assert np.abs(div_frac).max() < 1e-6 * speed


def test_curl_noise_rejects_other_shapes():
    with pytest.raises(ValueError, match="2-D scalar potential.*3-D vector potential"):
        curl_noise(LatticeNoise(2, 2), np.zeros((3, 2)))
    with pytest.raises(TypeError, match="noise must be a LatticeNoise"):
        curl_noise(lambda p: p, np.zeros((3, 2)))


# ------------------------------------------------------------------ warping
def test_warp_values_and_chain_rule_jacobian_compose():
    base = LatticeNoise(2, rng=1, kernel="cubic", frequency=1.5)
    disp = LatticeNoise(2, 2, rng=2, kernel="quintic")
    w = warp(base, disp, amount=[0.6, 0.3])
    x = np.random.default_rng(4).uniform(-3, 3, (300, 2))
    np.testing.assert_array_equal(w(x), base(x + [0.6, 0.3] * disp(x)))
    for f in (w, warp(w, LatticeNoise(2, 2, rng=3, basis="gradient"), 0.4)):
        value, grad = f.gradient(x, return_value=True)
        np.testing.assert_array_equal(value, f(x))
        fd = _central(f, x, 1e-6)
        assert np.abs(grad - fd).max() < 1e-7 * (1 + np.abs(grad).max())
    # a warped vector potential still gives divergence-free curl noise
    pot = warp(LatticeNoise(3, 3, rng=5), LatticeNoise(3, 3, rng=6), 0.5)
    y = np.random.default_rng(5).uniform(0, 4, (100, 3))
    assert np.abs(_divergence(lambda p: curl_noise(pot, p), y, 1e-5)).max() < 1e-7
    # fractal sums of a warp (generic object path) match their finite differences
    fg = fractal_gradient(w, x[:50], 3)
    fd = _central(lambda p: fractal_sum(w, p, 3), x[:50], 1e-6)
    assert np.abs(fg - fd).max() < 1e-6 * (1 + np.abs(fg).max())
    with pytest.raises(ValueError, match="warp_noise must map"):
        warp(base, LatticeNoise(2, 3), 1.0)
    with pytest.raises(ValueError, match="amount must be finite"):
        warp(base, disp, np.nan)


# ------------------------------------------------------------------ normals
def test_monge_normals_match_a_dense_finite_difference_surface():
    field = LatticeNoise(2, rng=1, kernel="cubic")
    n = 1024                                   # 256 samples per lattice cell
    ext = ((0.0, 4.0), (0.0, 4.0))
    pts = grid_points((n, n), ext)
    z, exact = monge_normals(field, pts, amplitude=0.5, frequency=1.0, phase=0.25, return_heights=True)
    step = 4.0 / n
    zy, zx = np.gradient(z, step, step)       # rows are y, columns x; second order inside
    fd = np.stack([-zy, -zx, np.ones_like(z)], axis=-1)     # normals in (y, x) order, as the points
    fd /= np.linalg.norm(fd, axis=-1, keepdims=True)
    ang = normal_angles(exact, fd)[1:-1, 1:-1]
    # central differences err by step^2/6 |z'''|: ~1e-5 in slope, ~1e-3 degrees
    assert ang.max() < 2e-3
    assert exact[..., 2].min() > 0


def test_mesh_face_normals_converge_to_the_exact_normals():
    # Monge surface: the normals recomputed from the mesh's faces approach the
    # exact ones at second order (x4 per halving of the grid step)
    field = LatticeNoise(2, rng=1)
    medians = []
    for n in (32, 64, 128):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            mesh = monge_surface(field, (n, n), amplitude=0.5)
        exact = monge_normals(field, mesh.vertices[:, :2], amplitude=0.5)
        medians.append(np.median(normal_angles(exact, vertex_normals(mesh)).reshape(n, n)[1:-1, 1:-1]))
    assert medians[0] / medians[1] > 3 and medians[1] / medians[2] > 3
    # displaced sphere (Eq. 11): the exact normal from the gradient and the base normal
    import trimesh

    field3 = LatticeNoise(3, rng=0)
    medians = []
    for sub in (3, 4, 5):
        sphere = trimesh.creation.icosphere(sub)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            bumpy = displace(sphere, field3, amplitude=0.1, frequency=2.0)
        exact = displaced_normals(sphere, field3, amplitude=0.1, frequency=2.0, curvature=1.0)
        medians.append(np.median(normal_angles(exact, vertex_normals(bumpy))))
    assert medians[0] / medians[1] > 3 and medians[1] / medians[2] > 3 and medians[2] < 0.05
    # without the curvature term the sphere's normals are off by the first-order error
    flat = displaced_normals(sphere, field3, amplitude=0.1, frequency=2.0)
    assert np.median(normal_angles(flat, vertex_normals(bumpy))) > 2 * medians[2]


@pytest.mark.parametrize("period", [(2, 3), (5, 6), (256, 256)])
def test_tiling_and_alternation_carry_over_to_the_gradient(period):
    # periods below the tap count (generic kernel), non-powers of two, and the
    # lattice-parity alternation: the gradient tiles with the noise and matches its differences
    noise = LatticeNoise(2, rng=6, kernel="cubic", period=period, frequency=[1.5, 0.75], alternation="lattice"
                         if all(p % 2 == 0 for p in period) else "table")
    x = np.random.default_rng(2).uniform(-3, 3, (200, 2))
    g = noise.gradient(x)
    shift = np.array(period) / noise.frequency
    np.testing.assert_allclose(noise.gradient(x + shift), g, rtol=0, atol=1e-9)
    fd = _central(noise, x, 1e-6)
    assert np.abs(g - fd).max() < 1e-7 * (1 + np.abs(g).max())
    grid = noise.gradient_grid((16, 12), [(0, 2), (0, 3)])
    np.testing.assert_allclose(grid, noise.gradient(noise.grid_points((16, 12), [(0, 2), (0, 3)])), rtol=0, atol=1e-13)
