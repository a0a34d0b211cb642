"""Falling snow (Langer & Zhang 2003; L. Zhang's M.Sc. thesis): figures 3.1-3.5, 4.1, 6.2, 6.3 and the opacity video."""
from __future__ import annotations

import numpy as np

from ..registry import Result, figure

SNOW = ("noiselab.snowfall", "noiselab.spectral", "noiselab.analysis", "noiselab.io", "noiselab.gallery.scenes")


@figure("snow", "opacity", source="Zhang 2003, video 'snow' (Sec. 3.5 I)", title="The opacity function alpha(x, y, t) itself",
        look="big flakes fall fast, small ones slowly: the measured speeds follow the tent's c N / (2 pi f) line",
        params=dict(frames=64, size=512, c=1.0, thickness=0.1, beta=1.5, seed=1),
        quick=dict(frames=8, size=64), uses=SNOW)
def opacity(out, *, frames, size, c, thickness, beta, seed):
    from noiselab import analysis
    from noiselab.snowfall import snow, flake_speeds

    from .._common import pyplot, save_figure, save_video

    alpha = snow((frames, size, size), rng=seed, c=c, thickness=thickness, beta=beta)
    band = (size / 32, size / 4)
    files = save_video(out, "opacity", alpha)
    spec = analysis.video_spectrum(alpha)
    on_tent = analysis.tent_energy(spec, c, band, direction_yx=(1, 0))
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
    ax.legend(fontsize=10)
    files.append(save_figure(fig, out / "speed_per_band.png"))
    inside = (prof.centers >= band[0]) & (prof.centers <= band[1])
    return Result(files, f"The rendered opacity alpha = (rescaled inverse FFT of the thickened tent)^beta, "
                         f"{frames} frames of {size} x {size}, band {band[0]:g}..{band[1]:g} cycles/frame; "
                         f"beside it: the speed of each spatial-frequency band against the tent's prediction. "
                         f"Nearest flakes {near:.2f} px/frame, farthest {far:.2f} px/frame (flake_speeds).",
                  measured={"energy on the tent": on_tent,
                            "speed per band (cycles/frame: px/frame)": ", ".join(
                                f"{fc:.0f}: {s:.2f}" for fc, s in zip(prof.centers[inside], speed[inside])),
                            "mean vy/|v| in band (1 = straight down)": float(np.mean(prof.velocity[inside, 1] / np.maximum(speed[inside], 1e-9))) if inside.any() else float("nan"),
                            "loop seam (1 = seamless)": seam})


def _speeds(alpha, size):
    """Speed per band inside the synthesis band, and the measured fall direction (degrees from straight down, + = right)."""
    from noiselab import analysis

    prof = analysis.speed_profile(alpha)
    speed = np.hypot(*prof.velocity.T)
    inside = (prof.centers >= size / 32) & (prof.centers <= size / 4)
    v = analysis.best_velocity(alpha, band=(size / 32, size / 4))
    return (", ".join(f"{fc:.0f}: {s:.2f}" for fc, s in zip(prof.centers[inside], speed[inside])),
            float(np.degrees(np.arctan2(v[0], v[1]))))


def _asked_angle(direction):
    return float(np.degrees(np.arctan2(direction[0], direction[1])))


def _composite_with_crop(alpha, background, box, intensity=250):
    """Eq. 3.6 frame by frame (background: one image or one per frame), each frame beside its 2x crop."""
    from .._common import alpha_to_rgb_composite
    from ..scenes import frame_with_crop

    out = None
    for t in range(len(alpha)):
        bg = background if background.ndim == 3 else background[t]
        f = frame_with_crop(alpha_to_rgb_composite(alpha[t], bg, intensity), box)
        if out is None:
            out = np.empty((len(alpha),) + f.shape, np.uint8)
        out[t] = f
    return out


@figure("snow", "fig3_1", source="Zhang 2003, Fig. 3.1; Langer & Zhang 2003, Fig. 1", title="Falling snow composited over a house on a winter day",
        look="the flakes in the 2x crop: large fast ones in front, small slow ones behind, all falling down and to the right",
        params=dict(frames=64, size=512, c=1.0, beta=3.0, intensity=250, direction=(0.4, 1.0), seed=2),
        quick=dict(frames=8, size=64), uses=SNOW)
def winter_scene(out, *, frames, size, c, beta, intensity, direction, seed):
    from noiselab import analysis
    from noiselab.snowfall import snow

    from .._common import save_image, save_video
    from ..scenes import house_scene

    bg = house_scene(size, size)
    alpha = snow((frames, size, size), rng=seed, c=c, beta=beta, direction_yx=direction[::-1])  # params: (dx, dy)
    video = _composite_with_crop(alpha, bg, (int(0.36 * size), int(0.3 * size)), intensity)
    files = [save_image(out / "a_background.png", bg)] + save_video(out, "house", video)
    speeds, angle = _speeds(alpha, size)
    grey = analysis.to_grey(video[..., :size, :])
    return Result(files, "(a) The background, drawn in code in place of the painting *Jimmy's place*: a house on a sunny "
                         "winter day with snow on the ground and none falling. (b) The video: falling snow composited over "
                         f"it with Eq. 3.6, I = {intensity} alpha + (1 - alpha) I_bg, alpha^beta with beta = {beta:g} (the thesis "
                         "uses 1.5 and sets beta per background, higher for lighter snow: at 1.5 the flakes veil this "
                         f"bright scene like grain, mean opacity {float(np.mean(alpha ** (1.5 / beta))):.2f}; at {beta:g}, "
                         f"{alpha.mean():.2f}); "
                         f"right, the outlined quarter enlarged 2x (nearest neighbour). The fall direction asked is "
                         f"{_asked_angle(direction):+.0f} degrees from straight down (+ = to the right); measured on alpha, "
                         f"{angle:+.0f}. The video loops seamlessly.",
                  measured={"energy on the tent": analysis.tent_energy(alpha, c, (size / 32, size / 4),
                                                                         direction_yx=direction[::-1]),
                            "speed per band of alpha (cycles/frame: px/frame)": speeds,
                            "fall direction, degrees from down (asked, measured)": [_asked_angle(direction), angle],
                            "mean opacity alpha": float(alpha.mean()),
                            "loop seam of the composite (1 = seamless)": analysis.loop_seam(grey),
                            "background RMS contrast": analysis.rms_contrast(analysis.to_grey(bg))})


@figure("snow", "fig3_2", source="Zhang 2003, Fig. 3.2", title="The tent surface w_t = C w_y / |w| (C = 1)",
        look="a surface that depends only on the direction of (w_x, w_y): every velocity's motion plane, tilted by 1/speed",
        params=dict(C=1.0, grid=61, frames=32, size=64, seed=3), quick=dict(grid=21, frames=8, size=32),
        uses=SNOW)
def tent_plot(out, *, C, grid, frames, size, seed):
    from noiselab import analysis
    from noiselab.snowfall import snow

    from .._common import pyplot, save_figure

    plt = pyplot()
    w = np.linspace(-np.pi, np.pi, grid)
    wx, wy = np.meshgrid(w, w)
    r = np.hypot(wx, wy)
    wt = np.divide(C * wy, r, out=np.zeros_like(r), where=r > 0)
    fig = plt.figure(figsize=(11.5, 4.6))
    ax = fig.add_axes([0.0, 0.05, 0.46, 0.86], projection="3d")
    ax.plot_surface(wx, wy, wt, cmap="viridis", linewidth=0, antialiased=True)
    ax.set_xlabel(r"$\omega_x$ (rad/px)"), ax.set_ylabel(r"$\omega_y$ (rad/px)"), ax.set_zlabel(r"$\omega_t$ (rad/frame)", labelpad=6)
    ax.set_zticks([-1, 0, 1])
    ax.set_box_aspect(None, zoom=0.85)
    ax.set_title(f"(a) the tent, Eq. 3.3, C = {C:g}")
    # what a rendered video actually holds: its power in the (w_y, w_t) plane at w_x = 0
    # averaged over 4 videos: each column's amplitude is uniform random, and in one video a column whose draw lands
    # near 0 leaves a dark gap in the lines (seed 3: |w_y| = 1.77, 5 decades below its neighbours)
    videos = 4
    sl = 0.0
    for k in range(videos):
        alpha = snow((frames, size, size), rng=seed + k, c=C, thickness=0.0, band=(size / 16, size / 2.5), beta=1.0)
        sl = sl + np.fft.fftshift(np.abs(np.fft.fftn(alpha - alpha.mean()))[:, :, 0] ** 2, axes=(0, 1)) / videos
        first = alpha if k == 0 else first
    ax2 = fig.add_axes([0.58, 0.13, 0.38, 0.76])
    fy = np.fft.fftshift(np.fft.fftfreq(size)) * 2 * np.pi
    ft = np.fft.fftshift(np.fft.fftfreq(frames)) * 2 * np.pi
    ax2.pcolormesh(fy, ft, np.log10(sl + sl.max() * 1e-6), shading="nearest", cmap="magma")
    ax2.set_xlabel(r"$\omega_y$ (rad/px)"), ax2.set_ylabel(r"$\omega_t$ (rad/frame)")
    ax2.set_title(rf"(b) power of rendered videos at $\omega_x$ = 0 (log, mean of {videos})")
    tent = analysis.tent_energy(first, C, (size / 16, size / 2.5))   # the first video's, seed ``seed``
    return Result([save_figure(fig, out / "tent.png")],
                  "(a) The tent surface of Eq. 3.3 plotted over w_x, w_y in [-pi, pi]. (b) The power spectrum "
                  f"of {videos} {frames} x {size} x {size} snow videos (thin tent, beta = 1; seeds {seed}-"
                  f"{seed + videos - 1}, averaged, since one video's random amplitudes leave gaps) in the w_x = 0 "
                  "plane: the energy "
                  "lies on two horizontal lines w_t = -+C (numpy's sign convention: w_t = -C w_y/|w|), the tent's "
                  "section at w_x = 0.",
                  measured={"energy on the tent": tent})


@figure("snow", "fig3_3", source="Zhang 2003, Fig. 3.3", title="The city background (the thesis's 'sydney'), 512 x 512",
        look="a crisp, sunny scene with dark edges everywhere: the flakes of Fig. 3.4 will be seen against it",
        params=dict(size=512), quick=dict(size=64), uses=("noiselab.analysis", "noiselab.io", "noiselab.gallery.scenes"))
def city_background(out, *, size):
    from noiselab import analysis

    from .._common import save_image
    from ..scenes import city_scene

    bg = city_scene(size, size)
    grey = analysis.to_grey(bg)
    return Result([save_image(out / "city.png", bg)],
                  f"The background of Figs. 3.4 and 3.5, {size} x {size}: the thesis's photograph of Sydney on a sunny day "
                  "cannot ship, so the gallery draws a harbour city in code (towers, a tower with a turret, shell roofs, "
                  "a steel arch bridge, water).",
                  measured={"RMS contrast": analysis.rms_contrast(grey),
                            "luminance range (0-255)": [float(grey.min()), float(grey.max())]})


def _tiling(out, tile, frames, size, c, beta, direction, seed, seeds):
    from noiselab import analysis
    from noiselab.snowfall import snow, iter_tiled_frames

    from .._common import save_image, save_video
    from ..scenes import city_scene

    reps = size // tile
    alpha = snow((frames, tile, tile), rng=seed, c=c, beta=beta, direction_yx=direction[::-1])  # params: (dx, dy)
    tiled = np.stack(list(iter_tiled_frames(alpha, (reps, reps))))
    video = _composite_with_crop(tiled, city_scene(size, size), (int(0.3 * size), int(0.3 * size)))
    zoom = max(1, 256 // tile)     # the tile enlarged with nearest neighbour, so its flakes can be counted
    tile_img = np.rint(255 * alpha[0]).astype(np.uint8).repeat(zoom, 0).repeat(zoom, 1)
    files = [save_image(out / f"a_tile{tile}.png", tile_img)] + save_video(out, f"tiled{tile}", video)
    # the seam statistic (tile_seam: RMS step across the tile edges / RMS step beside them, the larger of x and y)
    # is noisy and, being a max of two ratios, biased above 1: one value says nothing on its own, so it is compared
    # with the same statistic on interior lines (the tile rolled by half a tile), over this tile and `seeds` others
    tiles = [alpha] + [snow((frames, tile, tile), rng=seed + 1000 + k, c=c, direction_yx=direction[::-1])
                       for k in range(seeds)]
    seam = np.array([analysis.tile_seam(a) for a in tiles])
    inner = np.array([analysis.tile_seam(np.roll(a, (tile // 2, tile // 2), axis=(1, 2))) for a in tiles])
    diff = seam - inner
    se = float(diff.std(ddof=1) / np.sqrt(len(diff)))
    speeds, angle = _speeds(alpha, tile)
    coarsest = 32.0     # px: the default band starts at tile/32 cycles per tile, a wavelength of 32 px at any tile size
    measured = {f"seam statistic at the tile edges, {len(tiles)} tiles (mean, sd; biased above 1)": [float(seam.mean()), float(seam.std(ddof=1))],
                "same statistic on interior lines (mean, sd)": [float(inner.mean()), float(inner.std(ddof=1))],
                "edges minus interior (mean, standard error)": [float(diff.mean()), se],
                "repeat period / wavelength of the coarsest flakes": tile / coarsest,
                "speed per band of the tile (cycles/tile: px/frame)": speeds,
                "fall direction, degrees from down (asked, measured)": [_asked_angle(direction), angle],
                "loop seam (1 = seamless)": analysis.loop_seam(tiled),
                "energy on the tent (one tile)": analysis.tent_energy(alpha, c, (tile / 32, tile / 4),
                                                                   direction_yx=direction[::-1])}
    verdict = (f"the edges score {seam.mean():.3f} against {inner.mean():.3f} on interior lines (the statistic is biased "
               f"above 1 for any line), a difference of {diff.mean():+.3f} +- {se:.3f} (standard error over {len(tiles)} tiles): "
               + ("no seam measurable (|difference| < 2 standard errors)" if abs(diff.mean()) < 2 * se
                  else "a measurable seam (|difference| >= 2 standard errors)"))
    return files, measured, verdict, angle


@figure("snow", "fig3_4", source="Zhang 2003, Fig. 3.4", title="Tiling XYT: the city under 4 x 4 snow tiles of 128 x 128",
        look="no tile edges anywhere, and snow falling down and to the left, unlike the house's",
        params=dict(tile=128, frames=64, size=512, c=1.0, beta=3.0, direction=(-0.4, 1.0), seeds=4, seed=4),
        quick=dict(tile=32, frames=8, size=128, seeds=2), uses=SNOW)
def tiling_128(out, *, tile, frames, size, c, beta, direction, seeds, seed):
    files, measured, verdict, angle = _tiling(out, tile, frames, size, c, beta, direction, seed, seeds)
    return Result(files, f"(a) One frame of a {tile} x {tile} snow tile, enlarged {max(1, 256 // tile)}x (nearest neighbour); "
                         f"(b) the {size} x {size} city of Fig. 3.3 under {size // tile} x {size // tile} copies of it (beta = {beta:g}, as "
                         "in Fig. 3.1), with "
                         "its outlined quarter enlarged 2x. The tiles are periodic in x, y and t, so they join without "
                         f"seams; measured on alpha: {verdict}. The snow falls {angle:+.0f} degrees from straight down "
                         "(measured; - = to the left), while the house's snow (Fig. 3.1) falls to the right: the "
                         f"thesis's point that the fall direction is free. The pattern repeats every {tile} px, {tile / 32:g} wavelengths of the "
                         "coarsest flakes (32 px): too long to be noticed, as the thesis finds.", measured)


@figure("snow", "fig3_5", source="Zhang 2003, Fig. 3.5", title="Tiling failure: 8 x 8 tiles of 64 x 64 repeat visibly",
        look="the same flakes repeating on a 64-pixel grid (clearest in the 2x crop): a pattern, not snowfall",
        params=dict(tile=64, frames=64, size=512, c=1.0, beta=3.0, direction=(-0.4, 1.0), seeds=4, seed=4),
        quick=dict(tile=16, frames=8, size=128, seeds=2), uses=SNOW)
def tiling_64(out, *, tile, frames, size, c, beta, direction, seeds, seed):
    files, measured, verdict, _ = _tiling(out, tile, frames, size, c, beta, direction, seed, seeds)
    return Result(files, f"(a) One frame of a {tile} x {tile} tile, enlarged {max(1, 256 // tile)}x; (b) "
                         f"{size // tile} x {size // tile} = {(size // tile) ** 2} copies over the city. What fails is not "
                         f"the seams ({verdict}; the same test as Fig. 3.4) but the period: the pattern repeats every "
                         f"{tile} px, only {tile / 32:g} wavelengths of the coarsest flakes (32 px) against 4 in Fig. 3.4, "
                         "so the eye finds the repeat (the thesis's perceptual judgement; the ratio is measured, the "
                         "judgement is not).", measured)


@figure("snow", "fig4_1", source="Zhang 2003, Fig. 4.1", title="The sheared tent for a panning camera, and the panning video",
        look="the house slides right 1 px per frame and the snow drifts right with it; the loop has no jump",
        params=dict(C=1.0, s=0.3, grid=61, frames=64, size=256, pan=1, beta=3.0, seed=6),
        quick=dict(grid=21, frames=8, size=32), uses=SNOW)
def sheared_tent(out, *, C, s, grid, frames, size, pan, beta, seed):
    from noiselab import analysis
    from noiselab.snowfall import snow

    from .._common import pyplot, save_figure, save_video
    from ..scenes import house_scene

    plt = pyplot()
    w = np.linspace(-np.pi, np.pi, grid)
    wl, wv = np.meshgrid(w, w)   # w_l: across the fall (x), w_v: along it (y)
    r = np.hypot(wl, wv)
    wt = np.divide(C * wv, r, out=np.zeros_like(r), where=r > 0) - s * wl
    fig = plt.figure(figsize=(6, 5))
    ax = fig.add_subplot(projection="3d")
    ax.plot_surface(wl, wv, wt, cmap="viridis", linewidth=0)
    ax.set_xlabel(r"$\omega_l$ (rad/px, across the fall)"), ax.set_ylabel(r"$\omega_v$ (rad/px, along it)")
    ax.set_zlabel(r"$\omega_t$ (rad/frame)")
    ax.set_title(f"Eq. 4.3: C = {C:g}, s_l = {s:g}")
    files = [save_figure(fig, out / "sheared_tent.png")]
    alpha = snow((frames, size, size), rng=seed, c=C, beta=beta, pan_yx=(0.0, pan))
    # the background is a panorama periodic in x with period `size`; panning `pan` whole px per frame, it comes
    # back to where it started after size/pan frames, and the snow (periodic in `frames`) loops within that, so the
    # whole video loops without a jump (a background cut from a longer strip jumps back by pan*frames px instead)
    if size % pan:
        raise ValueError(f"pan must divide size for a seamless loop: pan={pan}, size={size}")
    length = size // pan
    pano = house_scene(size, size, periodic=True)
    bgs = np.stack([np.roll(pano, pan * t, axis=1) for t in range(length)])
    video = _composite_with_crop(alpha[np.arange(length) % frames], bgs, (size // 4, size // 4))
    files += save_video(out, "panning", video)
    band = (size / 32, size / 4)
    v = analysis.best_velocity(alpha, band=band)
    on_sheared = analysis.sheared_tent_energy(alpha, C, band, direction_yx=(1, 0), pan_yx=(0.0, pan))
    on_plain = analysis.tent_energy(alpha, C, band)
    seam = analysis.loop_seam(analysis.to_grey(video[:, :, :size]))
    return Result(files, f"Left: the sheared tent of Eq. 4.3 (C = {C:g}, s_l = {s:g}). Right: snow rendered on the sheared "
                         f"tent for a camera pan adding {pan} px/frame to the right, composited over the house "
                         f"(the thesis's 'panningsnowscene'), which pans {pan} px/frame too; beside it, the outlined quarter "
                         f"2x. The house is drawn periodic in x with period {size} px, so the video ({length} frames, the "
                         f"{frames}-frame snow looping {length // frames} times) loops without the jump a cut strip "
                         f"makes: loop seam {seam:.2f} (1 = an ordinary step). {on_sheared:.1%} of the energy lies on the "
                         f"sheared tent against {on_plain:.1%} on the unsheared one; the best single velocity has "
                         f"vx = {v[0]:.2f} px/frame for a pan of {pan} px/frame: "
                         + ("the snow drifts with the background (|vx - pan| < 0.1 px/frame), unlike the thesis's "
                            "panningsnowscene, whose snow moved under 1 px/frame behind a 1 px/frame background "
                            "(its s_l/pi ~ C limit); here the pan is given in px/frame and added to every flake."
                            if abs(v[0] - pan) < 0.1 else
                            "the snow does not keep up with the background (|vx - pan| >= 0.1 px/frame), as in the "
                            "thesis's panningsnowscene."),
                  measured={"energy on the sheared tent": on_sheared,
                            "energy on the unsheared tent (for comparison)": on_plain,
                            "best single velocity (vx, vy) px/frame": [float(v[0]), float(v[1])],
                            "loop seam of alpha": analysis.loop_seam(alpha),
                            "loop seam of the panning composite (1 = seamless)": seam})


@figure("snow", "fig6_1", source="Zhang 2003, Fig. 6.1", title="The background images of the transparency stimuli",
        look="black and white only: the white regions will be veiled (low contrast), the black ones left clear",
        params=dict(size=512), quick=dict(size=64), uses=("noiselab.io",))
def backgrounds(out, *, size):
    from .._common import checkerboard, disc, moon, pyplot, save_figure

    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(12, 4.3), layout="constrained")
    whites = {}
    for ax, (name, img) in zip(axes, (("checkerboard", checkerboard(size)), ("moon", moon(size)), ("disc", disc(size)))):
        ax.imshow(img, cmap="gray", vmin=0, vmax=1, interpolation="nearest")
        ax.set_title(f"({'abc'[len(whites)]}) {name}", fontsize=14)
        ax.set_xticks([]), ax.set_yticks([])
        whites[name] = float(img.mean())
    return Result([save_figure(fig, out / "backgrounds.png")],
                  f"(a) checkerboard (4 x 4 squares), (b) moon (a disc minus a shifted disc), (c) disc, {size} x {size} "
                  "as in the thesis, drawn in code. Their white regions become the veiled, low-contrast regions of Fig. 6.2.",
                  measured={f"{k}: white fraction": v for k, v in whites.items()})


@figure("snow", "fig6_2", source="Zhang 2003, Fig. 6.2", title="Motion-parallax transparency stimuli: checkerboard, moon, disc",
        look="the snow seems to pass behind a light veil over the white regions of each pattern",
        params=dict(frames=64, size=512, c=1.0, transmittance=0.3, seed=7), quick=dict(frames=8, size=64), uses=SNOW)
def parallax(out, *, frames, size, c, transmittance, seed):
    from noiselab.snowfall import parallax_composite, snow

    from .._common import checkerboard, disc, moon, save_video

    fg = snow((frames, size, size), rng=seed, c=c, beta=1.0)   # the thesis rescales to [0, 255] without beta
    panels = [np.rint(255 * fg).astype(np.uint8)]
    measured, ranges = {}, []
    for name, bg in (("checkerboard", checkerboard(size)), ("moon", moon(size)), ("disc", disc(size))):
        mask = bg > 0.5
        video, contrast = parallax_composite(fg, mask, transmittance=transmittance)
        panels.append(video)
        measured[f"{name}: Michelson contrast veiled / clear"] = [contrast["veiled"], contrast["clear"]]
        inside = fg[:, mask]
        lo, hi = float(inside.min()), float(inside.max())
        ranges.append((lo, hi))
        # Eq. 6.1 with the foreground's actual extremes inside the veiled region
        measured[f"{name}: foreground range in the veiled region; contrast it predicts"] = [
            lo, hi, transmittance * (hi - lo) / (2 * (1 - transmittance) + transmittance * (hi + lo))]
    gap = np.full((frames, size, 8), 255, np.uint8)
    strip = np.concatenate([x for p in panels for x in (p, gap)][:-1], axis=2)
    files = save_video(out, "stimuli", strip)
    ideal = transmittance / (2 - transmittance)
    veiled = [v[0] for k, v in measured.items() if "Michelson" in k]
    return Result(files, "Left to right: (a) the motion parallax (tent-model snow, beta = 1) and it composited with Eq. 6.1 "
                         f"(I = 255 (1 - {transmittance:g}) + {transmittance:g} I_fg over the white regions, I_fg elsewhere) "
                         "over (b) the checkerboard, (c) the moon, (d) the disc of Fig. 6.1. The thesis's veiled contrast "
                         f"0.176 is Eq. 6.1 for a foreground spanning the full 0..255: {transmittance:g} / (2 - "
                         f"{transmittance:g}) = {ideal:.3f}. Ours spans "
                         + ", ".join(f"{lo:.2f}-{hi:.2f}" for lo, hi in ranges)
                         + " of that range inside the three veiled regions (rescaling to [0, 1] is over the whole "
                         f"video), which gives the measured {min(veiled):.3f}-{max(veiled):.3f}; the clear regions "
                         "measure 1, as in the thesis.", measured)


@figure("snow", "fig6_3", source="Zhang 2003, Fig. 6.3", title="Motion-inconsistent stimulus: the disc falls down-left, the surround down-right",
        look="play it: inside the disc the snow falls down-left, around it down-right, yet the disc still looks veiled",
        params=dict(frames=64, size=512, c=1.0, transmittance=0.3, seed=8), quick=dict(frames=8, size=64), uses=SNOW)
def motion_inconsistent(out, *, frames, size, c, transmittance, seed):
    from noiselab import analysis
    from noiselab.snowfall import parallax_composite, snow

    from .._common import disc, save_video

    surround = snow((frames, size, size), rng=seed, c=c, beta=1.0, direction_yx=(1.0, 1.0))
    centre = snow((frames, size, size), rng=seed, c=c, beta=1.0, direction_yx=(1.0, -1.0))
    mask = disc(size, 0.3) > 0.5
    video, contrast = parallax_composite(surround, mask, transmittance=transmittance, veiled_foreground=centre)
    files = save_video(out, "motion_inconsistent", video)
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
