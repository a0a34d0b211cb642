"""Exact derivatives of lattice noise: divergence-free flow, domain warping, exact normals."""
from __future__ import annotations

import warnings

import numpy as np

from ..registry import Result, figure

USES = ("noiselab.lattice", "noiselab.fractal", "noiselab.fields", "noiselab.geometry")


def _fd_divergence(field, x, h=1e-5):
    """Central-difference divergence of a 2-D vector field at points x (n, 2)."""
    return sum((field(x + h * np.eye(2)[a])[:, a] - field(x - h * np.eye(2)[a])[:, a]) / (2 * h) for a in range(2))


@figure("derivatives", "curl_flow", look="left, no colour (zero divergence) and closed streamlines; right, red sources and blue sinks",
        source="Phillips 2004, Figs. 9-10; Bridson et al. 2007",
        title="Curl noise: a divergence-free flow field beside plain vector noise",
        params=dict(samples=256, cells=4.0, arrows=24, seed=7), quick=dict(samples=64, arrows=12), uses=USES)
def curl_flow(out, *, samples, cells, arrows, seed):
    from noiselab.fields import curl_noise
    from noiselab.lattice import Grid, LatticeNoise

    from .._common import pyplot, save_figure

    plt = pyplot()
    potential = LatticeNoise(2, rng=seed, kernel="quintic")
    plain = LatticeNoise(2, 2, rng=seed, kernel="quintic")
    grid = Grid((samples, samples), [(0, cells), (0, cells)])
    v_curl = curl_noise(potential, grid)                      # (x, y, 2), axis 0 is x
    v_plain = plain.grid(grid.shape, grid.extent)
    step = cells / samples
    coords = np.arange(samples) * step
    measured = {}
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.6))
    x = np.random.default_rng(seed).uniform(0, cells, (2000, 2))
    for ax, name, v, fn in ((axes[0], "curl noise", v_curl, lambda p: curl_noise(potential, p)),
                            (axes[1], "plain vector noise", v_plain, plain)):
        vx, vy = v[..., 0].T, v[..., 1].T                      # rows y, columns x for matplotlib
        div_grid = np.gradient(vx, step, axis=1) + np.gradient(vy, step, axis=0)
        speed = np.hypot(vx, vy)
        ax.imshow(div_grid, origin="lower", extent=(0, cells, 0, cells), cmap="RdBu_r", vmin=-3, vmax=3)
        ax.streamplot(coords, coords, vx, vy, color="k", linewidth=0.6, density=1.3, arrowsize=0.7)
        ax.set_xlim(0, cells), ax.set_ylim(0, cells)
        fine = _fd_divergence(fn, x)
        ref = float(np.sqrt(np.mean(fn(x) ** 2)))
        measured[f"{name}: RMS divergence / RMS speed (central differences, h = 1e-5, 2000 points)"] = float(
            np.sqrt(np.mean(fine ** 2)) / ref)
        measured[f"{name}: RMS divergence / RMS speed (np.gradient on the {samples}^2 grid)"] = float(
            np.sqrt(np.mean(div_grid ** 2)) / np.sqrt(np.mean(speed ** 2)))
        ax.set_title(f"{name}: streamlines over the divergence (colour, +-3)", fontsize=10)
    return Result([save_figure(fig, out / "curl_flow.png")],
                  "Left: curl noise, the rotated exact gradient (dpsi/dy, -dpsi/dx) of a scalar lattice noise psi "
                  "(quintic kernel): its streamlines close on themselves and the divergence (colour) is zero up to "
                  "the grid's finite-difference truncation. Right: plain 2-component vector noise, the flow Phillips' "
                  "figure 9 draws: sources (red) and sinks (blue) of order one. The same seed, kernel and "
                  "frequency (one lattice cell per unit).", measured)


@figure("derivatives", "warp", look="the pattern folds and swirls as warps compose; the shading comes from the exact chain-rule gradient",
        source="The lab's own comparison (domain warping, Quilez 2002)",
        title="Domain warping and its exact gradient",
        params=dict(samples=384, cells=4.0, amount=0.8, seed=3), quick=dict(samples=96), uses=USES)
def warp_figure(out, *, samples, cells, amount, seed):
    from noiselab.fields import warp
    from noiselab.lattice import Grid, LatticeNoise

    from .._common import pyplot, save_figure

    plt = pyplot()
    base = LatticeNoise(2, rng=seed, kernel="quintic")
    once = warp(base, LatticeNoise(2, 2, rng=seed + 1, kernel="quintic"), amount)
    twice = warp(once, LatticeNoise(2, 2, rng=seed + 2, kernel="quintic", frequency=2.0), amount / 2)
    pts = base.grid_points((samples, samples), [(0, cells), (0, cells)])
    measured = {}
    fig, axes = plt.subplots(2, 3, figsize=(12, 8.2))
    for col, (name, f) in enumerate((("noise n(x)", base), ("n(x + a w1(x))", once),
                                     ("n(y + a/2 w2(x)), y = x + a w1(x)", twice))):
        value, grad = f.gradient(pts, return_value=True)
        axes[0, col].imshow(value.T, origin="lower", extent=(0, cells, 0, cells), cmap="gray", vmin=-1, vmax=1)
        axes[0, col].set_title(name, fontsize=10)
        # shaded as a height field lit from the upper left, with the exact normals
        n = np.concatenate([-0.15 * grad, np.ones(grad.shape[:-1] + (1,))], axis=-1)
        n /= np.linalg.norm(n, axis=-1, keepdims=True)
        light = np.array([-0.5, 0.5, 0.7]) / np.linalg.norm([-0.5, 0.5, 0.7])
        axes[1, col].imshow(np.clip(n @ light, 0, 1).T, origin="lower", extent=(0, cells, 0, cells), cmap="gray")
        axes[1, col].set_title("shaded with its exact gradient", fontsize=10)
        x = np.random.default_rng(seed).uniform(0, cells, (1000, 2))
        g = f.gradient(x)
        h = 1e-6
        fd = np.stack([(f(x + h * np.eye(2)[a]) - f(x - h * np.eye(2)[a])) / (2 * h) for a in range(2)], -1)
        measured[f"{name}: max |exact - central difference| / max |gradient| (1000 points, h = 1e-6)"] = float(
            np.abs(g - fd).max() / np.abs(g).max())
        measured[f"{name}: RMS |gradient|"] = float(np.sqrt(np.mean(np.sum(grad ** 2, -1))))
    for ax in axes.ravel():
        ax.set_xticks([]), ax.set_yticks([])
    grid_check = base.gradient_grid((samples, samples), [(0, cells), (0, cells)])
    measured["gradient_grid vs gradient on the same points (max abs difference)"] = float(
        np.abs(grid_check - base.gradient(pts)).max())
    del Grid
    return Result([save_figure(fig, out / "warp.png")],
                  f"Domain warping: the noise looked up at x + a w(x) (a = {amount} cells, w a 2-component noise), "
                  "then warped again by a finer field (warps compose). Bottom: each field shaded as a height map "
                  "with the gradient from the chain rule J_n(y)(I + a J_w(x)), no differencing.", measured)


@figure("derivatives", "normals", look="the face normals approach the exact ones as the mesh is refined; the exact ones need no mesh",
        source="Phillips 2004, Figs. 8, 14-20",
        title="Exact normals from the noise gradient against normals from the mesh's faces",
        params=dict(resolutions=(16, 32, 64, 128, 256), subdivisions=(2, 3, 4, 5, 6), shade=512, seed=1),
        quick=dict(resolutions=(16, 32, 64), subdivisions=(2, 3, 4), shade=128), uses=USES)
def normals(out, *, resolutions, subdivisions, shade, seed):
    import trimesh

    from noiselab.geometry import displace, grid_points, monge_surface, vertex_normals
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry.normals import displaced_normals, monge_normals, normal_angles

    from .._common import pyplot, save_figure

    plt = pyplot()
    field2 = LatticeNoise(2, rng=seed)
    field3 = LatticeNoise(3, rng=seed)
    amp, ext = 0.5, ((0.0, 4.0), (0.0, 4.0))
    measured = {}
    monge = []
    for n in resolutions:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            mesh = monge_surface(field2, (n, n), ext, amplitude=amp)
        exact = monge_normals(field2, mesh.vertices[:, :2], amplitude=amp)
        ang = normal_angles(exact, vertex_normals(mesh)).reshape(n, n)[1:-1, 1:-1]
        monge.append((4.0 / n, np.median(ang), ang.max()))
        measured[f"Monge surface {n}x{n}: median / max angle, face vs exact normals (degrees)"] = (
            f"{np.median(ang):.3g} / {ang.max():.3g}")
        if n == resolutions[1]:
            coarse_angles = ang
    sphere_rows = []
    for sub in subdivisions:
        sphere = trimesh.creation.icosphere(sub)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            bumpy = displace(sphere, field3, amplitude=0.1, frequency=2.0)
        exact = displaced_normals(sphere, field3, amplitude=0.1, frequency=2.0, curvature=1.0)
        ang = normal_angles(exact, vertex_normals(bumpy))
        edge = float(np.mean(sphere.edges_unique_length))
        sphere_rows.append((edge, np.median(ang), ang.max()))
        measured[f"displaced sphere, icosphere({sub}), {len(sphere.vertices)} vertices: median / max angle "
                 "(degrees)"] = f"{np.median(ang):.3g} / {ang.max():.3g}"
    fig, axes = plt.subplots(1, 3, figsize=(14, 5.0), layout="constrained")
    pts = grid_points((shade, shade), ext)
    z, nrm = monge_normals(field2, pts, amplitude=amp, return_heights=True)
    light = np.array([-0.6, 0.5, 0.4]) / np.linalg.norm([-0.6, 0.5, 0.4])
    axes[0].imshow(np.clip(nrm @ light, 0, 1), origin="lower", extent=(0, 4, 0, 4), cmap="gray")
    axes[0].set_title(f"z = {amp} noise(x, y), Lambert-shaded\nwith exact normals ({shade}^2)", fontsize=10)
    for ax in axes[:2]:
        ax.set_xlabel("x (lattice cells)"), ax.set_ylabel("y (lattice cells)")
    im = axes[1].imshow(coarse_angles, origin="lower", extent=(0, 4, 0, 4), cmap="magma")
    # the colour bar's unit as its title: a side label stood beside the next panel's y label, the same words twice
    plt.colorbar(im, ax=axes[1], fraction=0.046).ax.set_title("degrees", fontsize=10)
    axes[1].set_title(f"angle between face and exact\nnormals, {resolutions[1]}^2 mesh", fontsize=10)
    for rows, label, mk in ((monge, "Monge surface", "o"), (sphere_rows, "displaced sphere (Eq. 11)", "s")):
        h = np.array([r[0] for r in rows])
        axes[2].loglog(h, [r[1] for r in rows], mk + "-", label=f"{label}: median")
        axes[2].loglog(h, [r[2] for r in rows], mk + "--", label=f"{label}: max", alpha=0.6)
    h = np.array([r[0] for r in monge])
    axes[2].loglog(h, monge[0][1] * (h / h[0]) ** 2, "k:", label="slope 2")
    from matplotlib.ticker import NullFormatter

    axes[2].xaxis.set_minor_formatter(NullFormatter())
    axes[2].set_xlabel("mesh edge length (input units)"), axes[2].set_ylabel("angle to the exact normals (degrees)")
    # the lines climb from lower left to upper right: headroom above them holds the legend, in the upper left
    lo, hi = axes[2].get_ylim()
    axes[2].set_ylim(lo, hi * (hi / lo) ** 0.5)
    axes[2].legend(fontsize=10, loc="upper left")
    axes[2].set_title("face normals converge to the\nexact ones at second order", fontsize=10)
    slope = np.polyfit(np.log(h), np.log([r[1] for r in monge]), 1)[0]
    measured["Monge surface: fitted order of convergence of the median angle"] = float(slope)
    return Result([save_figure(fig, out / "normals.png")],
                  "Normals of noise surfaces from the noise's exact gradient: for a Monge surface "
                  "(-z_x, -z_y, 1)/|.|; for a mesh displaced along its normals by h = a s(F p), "
                  "(1 + h k) n - grad_S h (k the base curvature, 1/R on a sphere). The area-weighted normals "
                  "recomputed from the mesh's faces approach them at second order in the edge length; the "
                  "exact ones need no mesh at all.", measured)
