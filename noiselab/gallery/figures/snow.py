"""Falling snow (Langer & Zhang 2003; L. Zhang's M.Sc. thesis): figures 3.1-3.5, 4.1, 6.2, 6.3 and the opacity video."""
from __future__ import annotations

import numpy as np

from ..registry import Result, figure

SNOW = ("noiselab.snow", "noiselab.spectral", "noiselab.analysis", "noiselab.io")
LAND = ("noiselab.lattice", "noiselab.fractal")


@figure("snow", "opacity", seed="Zhang 2003, video 'snow' (Sec. 3.5 I)", title="The opacity function alpha(x, y, t) itself",
        params=dict(frames=64, size=512, c=1.0, thickness=0.1, beta=1.5, seed=1),
        quick=dict(frames=8, size=64), uses=SNOW)
def opacity(out, *, frames, size, c, thickness, beta, seed):
    from noiselab import analysis
    from noiselab.snow import snow, flake_speeds

    from .._common import pyplot, save_figure, save_video

    alpha = snow((frames, size, size), seed=seed, c=c, thickness=thickness, beta=beta)
    band = (size / 32, size / 4)
    files = save_video(out, "opacity", alpha)
    spec = analysis.video_spectrum(alpha)
    on_tent = analysis.tent_energy(spec, c, band, (0, 1))
    prof = analysis.speed_profile(alpha)
    seam = analysis.loop_seam(alpha)
    near, far = flake_speeds(c, band, size)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5, 3.6))
    f = np.geomspace(band[0] / 2, band[1] * 2, 100)
    ax.loglog(f, c * size / (2 * np.pi * f), "k--", label="tent: c N / (2 pi f)")
    speed = np.hypot(*prof.velocity.T)
    ax.loglog(prof.centers, np.maximum(speed, 1e-3), "o-", color="C0", label="measured |v| per band")
    ax.axvspan(*band, color="0.9", zorder=0, label="synthesis band")
    ax.set_xlabel("spatial frequency (cycles/frame)")
    ax.set_ylabel("speed (px/frame)")
    ax.set_title("Speed per band: near (coarse) flakes fall faster")
    ax.legend(fontsize=8)
    files.append(save_figure(fig, out / "speed_per_band.png"))
    inside = (prof.centers >= band[0]) & (prof.centers <= band[1])
    return Result(files, f"The rendered opacity alpha = (rescaled inverse FFT of the thickened tent)^beta, "
                         f"{frames} frames of {size} x {size}, band {band[0]:g}..{band[1]:g} cycles/frame; "
                         f"below: the speed of each spatial-frequency band against the tent's prediction. "
                         f"Nearest flakes {near:.2f} px/frame, farthest {far:.2f} px/frame (flake_speeds).",
                  measured={"energy on the tent": on_tent,
                            "speed per band (cycles/frame: px/frame)": ", ".join(
                                f"{fc:.0f}: {s:.2f}" for fc, s in zip(prof.centers[inside], speed[inside])),
                            "mean vy/|v| in band (1 = straight down)": float(np.mean(prof.velocity[inside, 1] / np.maximum(speed[inside], 1e-9))) if inside.any() else float("nan"),
                            "loop seam (1 = seamless)": seam})


@figure("snow", "fig3_1", seed="Zhang 2003, Fig. 3.1", title="Falling snow composited over a winter scene",
        params=dict(frames=64, size=512, c=1.0, beta=1.5, intensity=250, seed=2),
        quick=dict(frames=8, size=64), uses=SNOW + LAND + ("noiselab.geometry",))
def winter_scene(out, *, frames, size, c, beta, intensity, seed):
    from noiselab import analysis
    from noiselab.snow import snow

    from .._common import alpha_to_rgb_composite, save_image, save_video, terrain

    bg = terrain(size, size, grid=max(64, min(384, size * 3 // 4)))
    alpha = snow((frames, size, size), seed=seed, c=c, beta=beta)
    video = alpha_to_rgb_composite(alpha, bg, intensity)
    files = [save_image(out / "a_background.png", bg), save_image(out / "b_frame.png", video[0])]
    files += save_video(out, "house", video)
    prof = analysis.speed_profile(alpha)
    speed = np.hypot(*prof.velocity.T)
    inside = (prof.centers >= size / 32) & (prof.centers <= size / 4)
    return Result(files, "(a) The background: the painting of the thesis is not available, so the scene is noiselab's "
                         "own: a fractal-sum Monge surface (Phillips Eq. 9, 6 octaves of lattice noise) rendered with "
                         "pyvista, coloured by height and slope (meadow, rock, snow), lit by a low sun, with distance "
                         "haze, so the lab's two families meet in one picture. "
                         f"(b) One frame of falling snow composited over it with Eq. 3.6, I = {intensity} alpha + (1 - alpha) I_bg; "
                         "the video loops seamlessly.",
                  measured={"energy on the tent": analysis.tent_energy(alpha, c, (size / 32, size / 4)),
                            "speed per band of alpha (cycles/frame: px/frame)": ", ".join(
                                f"{fc:.0f}: {s:.2f}" for fc, s in zip(prof.centers[inside], speed[inside])),
                            "loop seam of the composite (1 = seamless)": analysis.loop_seam(analysis.to_grey(video.astype(np.float32))),
                            "background RMS contrast": analysis.rms_contrast(bg)})


@figure("snow", "fig3_2", seed="Zhang 2003, Fig. 3.2", title="The tent surface w_t = C w_y / |w| (C = 1)",
        params=dict(C=1.0, grid=61, frames=32, size=64, seed=3), quick=dict(grid=21, frames=8, size=32),
        uses=SNOW)
def tent_plot(out, *, C, grid, frames, size, seed):
    from noiselab import analysis
    from noiselab.snow import snow

    from .._common import pyplot, save_figure

    plt = pyplot()
    w = np.linspace(-np.pi, np.pi, grid)
    wx, wy = np.meshgrid(w, w)
    r = np.hypot(wx, wy)
    wt = np.divide(C * wy, r, out=np.zeros_like(r), where=r > 0)
    fig = plt.figure(figsize=(11.5, 4.6))
    ax = fig.add_axes([0.0, 0.05, 0.46, 0.86], projection="3d")
    ax.plot_surface(wx, wy, wt, cmap="viridis", linewidth=0, antialiased=True)
    ax.set_xlabel("w_x"), ax.set_ylabel("w_y"), ax.set_zlabel("w_t", labelpad=6), ax.set_zticks([-1, 0, 1])
    ax.set_box_aspect(None, zoom=0.85)
    ax.set_title(f"(a) the tent, Eq. 3.3, C = {C:g}")
    # what a rendered video actually holds: its power in the (w_y, w_t) plane at w_x = 0
    alpha = snow((frames, size, size), seed=seed, c=C, thickness=0.0, band=(size / 16, size / 2.5), beta=1.0)
    P = np.abs(np.fft.fftn(alpha - alpha.mean())) ** 2
    sl = np.fft.fftshift(P[:, :, 0], axes=(0, 1))
    ax2 = fig.add_axes([0.58, 0.13, 0.38, 0.76])
    fy = np.fft.fftshift(np.fft.fftfreq(size)) * 2 * np.pi
    ft = np.fft.fftshift(np.fft.fftfreq(frames)) * 2 * np.pi
    ax2.pcolormesh(fy, ft, np.log10(sl + sl.max() * 1e-6), shading="nearest", cmap="magma")
    ax2.set_xlabel("w_y (rad/px)"), ax2.set_ylabel("w_t (rad/frame)")
    ax2.set_title("(b) power of a rendered video at w_x = 0 (log)")
    tent = analysis.tent_energy(alpha, C, (size / 16, size / 2.5))
    return Result([save_figure(fig, out / "tent.png")],
                  "(a) The tent surface of Eq. 3.3 plotted over w_x, w_y in [-pi, pi]. (b) The power spectrum "
                  f"of a {frames} x {size} x {size} snow video (thin tent, beta = 1) in the w_x = 0 plane: the energy "
                  "lies on two horizontal lines w_t = -+C (numpy's sign convention: w_t = -C w_y/|w|), the tent's "
                  "section at w_x = 0.",
                  measured={"energy on the tent": tent})


def _tiling(out, tile, frames, size, c, seed, seeds):
    from noiselab import analysis
    from noiselab.snow import snow, iter_tiled_frames

    from .._common import alpha_to_rgb_composite, save_image, save_video, terrain

    reps = size // tile
    alpha = snow((frames, tile, tile), seed=seed, c=c)
    tiled = np.stack(list(iter_tiled_frames(alpha, (reps, reps))))
    bg = terrain(size, size, seed=5, grid=max(64, min(384, size * 3 // 4)))
    video = alpha_to_rgb_composite(tiled, bg)
    files = [save_image(out / f"a_tile{tile}.png", alpha[0]), save_image(out / "b_frame.png", video[0])]
    files += save_video(out, f"tiled{tile}", video)
    # the seam statistic (tile_seam: RMS step across the tile edges / RMS step beside them, the larger of x and y)
    # is noisy and, being a max of two ratios, biased above 1; so it is compared with the same statistic on
    # interior lines (the tile rolled by half a tile), over this tile and `seeds` others
    tiles = [alpha] + [snow((frames, tile, tile), seed=seed + 1000 + k, c=c) for k in range(seeds)]
    seam = np.array([analysis.tile_seam(a) for a in tiles])
    inner = np.array([analysis.tile_seam(np.roll(a, (tile // 2, tile // 2), axis=(1, 2))) for a in tiles])
    diff = seam - inner
    se = float(diff.std(ddof=1) / np.sqrt(len(diff)))
    measured = {"tile seam of the tiled alpha, all frames (1 = no seam)": analysis.tile_seam(tiled, tile),
                f"seam statistic at the tile edges, {len(tiles)} tiles (mean, sd)": [float(seam.mean()), float(seam.std(ddof=1))],
                f"same statistic on interior lines (mean, sd)": [float(inner.mean()), float(inner.std(ddof=1))],
                "loop seam (1 = seamless)": analysis.loop_seam(tiled),
                "energy on the tent (one tile)": analysis.tent_energy(alpha, c, (tile / 32, tile / 4))}
    verdict = (f"the edges score {seam.mean():.3f} against {inner.mean():.3f} on interior lines, a difference of "
               f"{diff.mean():+.3f} +- {se:.3f} (standard error over {len(tiles)} tiles): "
               + ("no seam measurable (|difference| < 2 standard errors)" if abs(diff.mean()) < 2 * se
                  else "a measurable seam (|difference| >= 2 standard errors)"))
    return files, measured, verdict


@figure("snow", "fig3_4", seed="Zhang 2003, Fig. 3.4", title="Tiling XYT: 128 x 128 tiles, 4 x 4 of them",
        params=dict(tile=128, frames=64, size=512, c=1.0, seeds=4, seed=4), quick=dict(tile=32, frames=8, size=128, seeds=2),
        uses=SNOW + LAND + ("noiselab.geometry",))
def tiling_128(out, *, tile, frames, size, c, seeds, seed):
    files, measured, verdict = _tiling(out, tile, frames, size, c, seed, seeds)
    return Result(files, f"(a) One frame of a {tile} x {tile} snow tile; (b) the {size} x {size} scene composited with "
                         f"{size // tile} x {size // tile} copies of it (the thesis's 'sydney' over noiselab's fractal-sum terrain, as in Fig. 3.1). "
                         f"The tiles are periodic in x, y and t; seams measured on the alpha: {verdict}.", measured)


@figure("snow", "fig3_5", seed="Zhang 2003, Fig. 3.5", title="Tiling failure: 64 x 64 tiles, 8 x 8 of them",
        params=dict(tile=64, frames=64, size=512, c=1.0, seeds=4, seed=4), quick=dict(tile=16, frames=8, size=128, seeds=2),
        uses=SNOW + LAND + ("noiselab.geometry",))
def tiling_64(out, *, tile, frames, size, c, seeds, seed):
    files, measured, verdict = _tiling(out, tile, frames, size, c, seed, seeds)
    return Result(files, f"(a) One frame of a {tile} x {tile} tile; (b) {size // tile} x {size // tile} = {(size // tile) ** 2} "
                         f"copies in the frame. Seams, measured: {verdict}. What fails here is the period: the thesis "
                         f"finds a {tile}-pixel repeat short enough to be seen as a repeating pattern (a perceptual "
                         "judgement, not measured here).", measured)


@figure("snow", "fig4_1", seed="Zhang 2003, Fig. 4.1", title="The sheared tent for a panning camera, and the panning video",
        params=dict(C=1.0, s=0.3, grid=61, frames=64, size=384, pan=1.0, seed=6),
        quick=dict(grid=21, frames=8, size=64), uses=SNOW + LAND + ("noiselab.geometry",))
def sheared_tent(out, *, C, s, grid, frames, size, pan, seed):
    from noiselab import analysis
    from noiselab.snow import snow

    from .._common import alpha_to_rgb_composite, pyplot, save_figure, save_video, terrain

    plt = pyplot()
    w = np.linspace(-np.pi, np.pi, grid)
    wl, wv = np.meshgrid(w, w)   # w_l: across the fall (x), w_v: along it (y)
    r = np.hypot(wl, wv)
    wt = np.divide(C * wv, r, out=np.zeros_like(r), where=r > 0) - s * wl
    fig = plt.figure(figsize=(5.5, 4.5))
    ax = fig.add_subplot(projection="3d")
    ax.plot_surface(wl, wv, wt, cmap="viridis", linewidth=0)
    ax.set_xlabel("w_l (x)"), ax.set_ylabel("w_v (y)"), ax.set_zlabel("w_t")
    ax.set_title(f"Eq. 4.3: C = {C:g}, s_l = {s:g}")
    files = [save_figure(fig, out / "sheared_tent.png")]
    alpha = snow((frames, size, size), seed=seed, c=C, pan=(pan, 0.0))
    wide = terrain(size, size + int(np.ceil(abs(pan) * frames)) + 1, seed=8, grid=max(64, min(384, size * 3 // 4)))
    # the background pans with the same image velocity as the camera's pan adds to the snow
    bg = np.stack([wide[:, int(round(len(wide[0]) - size - 1 - pan * t)):][:, :size] for t in range(frames)])
    video = alpha_to_rgb_composite(alpha, bg)
    files += save_video(out, "panning", video)
    band = (size / 32, size / 4)
    v = analysis.best_velocity(alpha, band=band)
    on_sheared = analysis.sheared_tent_energy(alpha, C, band, (0, 1), (pan, 0.0))
    on_plain = analysis.tent_energy(alpha, C, band)
    return Result(files, f"The sheared tent of Eq. 4.3 (C = {C:g}, s_l = {s:g}); the video renders snow with the sheared tent "
                         f"for a camera pan adding {pan:g} px/frame to the right, composited over noiselab's fractal-sum terrain (as in Fig. 3.1), panning "
                         f"at the same image velocity (the thesis's 'panningsnowscene'). {on_sheared:.1%} of the energy lies "
                         f"on the sheared tent against {on_plain:.1%} on the unsheared one; the best single velocity has "
                         f"vx = {v[0]:.2f} px/frame for a pan of {pan:g}.",
                  measured={"energy on the sheared tent": on_sheared,
                            "energy on the unsheared tent (for comparison)": on_plain,
                            "best single velocity (vx, vy) px/frame": [float(v[0]), float(v[1])],
                            "loop seam of alpha": analysis.loop_seam(alpha)})


@figure("snow", "fig6_2", seed="Zhang 2003, Fig. 6.2", title="Motion-parallax transparency stimuli: checkerboard, moon, disc",
        params=dict(frames=64, size=512, c=1.0, transmittance=0.3, seed=7), quick=dict(frames=8, size=64), uses=SNOW)
def parallax(out, *, frames, size, c, transmittance, seed):
    from noiselab.snow import parallax_composite, snow

    from .._common import checkerboard, disc, moon, pyplot, save_figure, save_video

    fg = snow((frames, size, size), seed=seed, c=c, beta=1.0)   # the thesis rescales to [0, 255] without beta
    panels = [("(a) motion parallax", (255 * fg[0]).astype(np.uint8))]
    files, measured = [], {}
    for name, bg in (("checkerboard", checkerboard(size)), ("moon", moon(size)), ("disc", disc(size))):
        video, contrast = parallax_composite(fg, bg > 0.5, transmittance=transmittance)
        files += save_video(out, name, video)
        panels.append((f"({'bcd'[len(panels) - 1]}) {name}", video[0]))
        measured[f"{name}: Michelson contrast veiled / clear"] = [contrast["veiled"], contrast["clear"]]
    files += save_video(out, "parallax", fg)
    plt = pyplot()
    fig, axes = plt.subplots(1, 4, figsize=(14, 3.8))
    for ax, (title, img) in zip(axes, panels):
        ax.imshow(img, cmap="gray", vmin=0, vmax=255)
        ax.set_title(title), ax.axis("off")
    files.insert(0, save_figure(fig, out / "frames.png"))
    return Result(files, "One frame of (a) the motion parallax (tent-model snow, beta = 1) and of it composited with Eq. 6.1 "
                         f"(I = 255 (1 - {transmittance:g}) + {transmittance:g} I_fg over the white regions, I_fg elsewhere) "
                         "over (b) a checkerboard, (c) a moon, (d) a disc. The thesis computes contrasts 0.176 (veiled) and 1 (clear).",
                  measured)


@figure("snow", "fig6_3", seed="Zhang 2003, Fig. 6.3", title="Motion-inconsistent stimulus: the disc falls down-left, the surround down-right",
        params=dict(frames=64, size=512, c=1.0, transmittance=0.3, seed=8), quick=dict(frames=8, size=64), uses=SNOW)
def motion_inconsistent(out, *, frames, size, c, transmittance, seed):
    from noiselab import analysis
    from noiselab.snow import parallax_composite, snow

    from .._common import disc, save_image, save_video

    surround = snow((frames, size, size), seed=seed, c=c, beta=1.0, direction=(1.0, 1.0))
    centre = snow((frames, size, size), seed=seed, c=c, beta=1.0, direction=(-1.0, 1.0))
    mask = disc(size, 0.3) > 0.5
    video, contrast = parallax_composite(surround, mask, transmittance=transmittance, veiled_foreground=centre)
    files = [save_image(out / "frame.png", video[0])] + save_video(out, "motion_inconsistent", video)
    # velocity measured on the composite, in a square inside the disc and in a corner of the surround
    q = size // 5
    lo, hi = size // 2 - q, size // 2 + q
    v_in = analysis.best_velocity(video[:, lo:hi, lo:hi].astype(np.float32), window="hann")
    v_out = analysis.best_velocity(video[:, :2 * q, :2 * q].astype(np.float32), window="hann")
    angle = float(np.degrees(np.arccos(np.clip(np.dot(v_in, v_out) / (np.linalg.norm(v_in) * np.linalg.norm(v_out)), -1, 1))))
    return Result(files, "The moon experiment with a central disc whose snow falls at 90 degrees to the surround's: "
                         "down-left (-1, 1) inside the low-contrast disc, down-right (1, 1) around it (Eq. 6.1 with "
                         "a different foreground in the veiled region). A still frame cannot show motion; measured on the "
                         f"composite video, the two best velocities are {angle:.0f} degrees apart (90 asked).",
                  measured={"best velocity inside the disc (vx, vy)": [float(v_in[0]), float(v_in[1])],
                            "angle between them (degrees)": angle,
                            "best velocity in the surround (vx, vy)": [float(v_out[0]), float(v_out[1])],
                            "Michelson contrast veiled / clear": [contrast["veiled"], contrast["clear"]]})
