"""Stimuli in physical units: thesis Figs. 5.1-5.5 (the transparency displays Chapter 5 reviews) at stated contrasts on a stated display."""
from __future__ import annotations

import numpy as np

from ..registry import Result, figure

STIM = ("noiselab.stimuli", "noiselab.spectral", "noiselab.analysis", "noiselab.io")
# the display every figure here is shown on: 32 px/deg, 60 Hz, 0.5..100 cd/m², gamma 2.2, 8 bits
DISPLAY = dict(pixels_per_degree=32.0, frame_rate=60.0, luminance=(0.5, 100.0), gamma=2.2, bits=8)


def _display():
    from noiselab.stimuli import Display

    return Display(**DISPLAY)


def _show(luminance, display, seed):
    """Display values for an explicit luminance image: its own mean and Michelson contrast, so it is kept as is."""
    from noiselab.stimuli import to_display

    lo, hi = float(luminance.min()), float(luminance.max())
    return to_display(luminance, display, mean=float(luminance.mean()), contrast=(hi - lo) / (hi + lo),
                      contrast_kind="michelson", rng=seed)


def _texture(display, n, sf, theta_deg, bw_deg, seed):
    """Oriented band-pass noise (log-Gabor x orientation band) of unit variance, ``n`` x ``n`` px."""
    from noiselab.stimuli import motion_cloud

    return motion_cloud((n, n), sf_0=display.cycles_per_pixel(sf), B_sf=display.cycles_per_pixel(sf / 2),
                        theta=np.radians(theta_deg), B_theta=np.radians(bw_deg), rng=seed, dtype=np.float64)


def _plaid(n, cycles):
    """A 2-D sinusoidal background in [-1, 1]: the mean of a horizontal and a vertical sinusoid, ``cycles`` per side."""
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n
    return 0.5 * (np.sin(2 * np.pi * cycles * x) + np.sin(2 * np.pi * cycles * y))


def _disc_mask(n, radius, centre=(0.5, 0.5)):
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n
    return (x - centre[0]) ** 2 + (y - centre[1]) ** 2 <= radius ** 2


def _side_by_side(left, right, gap, fill):
    """Two luminance images with a ``gap``-pixel band of luminance ``fill`` between them."""
    band = np.full(left.shape[:-1] + (gap,), fill, dtype=np.float64)
    return np.concatenate([left, band, right], axis=-1)


@figure("stimuli", "fig5_1", source="Zhang 2003, Fig. 5.1 (after Metelli 1974)",
        title="Metelli's episcotister: a sectored disc rotating over a bipartite background, and what Talbot's law makes of it",
        params=dict(size_deg=6.0, a=80.0, b=20.0, t=8.0, alpha=0.4, revolutions_per_second=4.0, duration=1.0, seed=11),
        quick=dict(size_deg=2.0, duration=0.25), uses=STIM,
        look="(a) the disc with its open sector turning over the two halves; (b) averaged over a turn, a dark transparent layer over both")
def episcotister(out, *, size_deg, a, b, t, alpha, revolutions_per_second, duration, seed):
    from .._common import save_image, save_video

    d = _display()
    n, frames = d.pixels(size_deg), d.frame_count(duration)
    y, x = (np.mgrid[0:n, 0:n] + 0.5) / n
    background = np.where(x < 0.5, a, b)                  # the bipartite background, a (left) and b (right) cd/m²
    inside = _disc_mask(n, 0.36)
    angle = np.arctan2(y - 0.5, x - 0.5) % (2 * np.pi)
    turn = 2 * np.pi * revolutions_per_second / d.frame_rate    # radians per frame
    per_turn = int(round(2 * np.pi / turn))
    frames = max(frames, per_turn)
    video = np.empty((frames, n, n))
    for k in range(frames):
        open_sector = ((angle - k * turn) % (2 * np.pi)) < 2 * np.pi * alpha   # the open sector, relative area alpha
        video[k] = np.where(inside & ~open_sector, t, background)
    values = _show(video, d, seed)
    files = save_video(out, "episcotister", values, fps=d.frame_rate)
    # (b) Talbot's law: what the eye sees when the disc turns fast enough is the mean over one turn
    shown = d.luminance_of(values)
    talbot = shown[:per_turn].mean(axis=0)
    files.append(save_image(out / "b_talbot.png", np.clip(np.rint(d.value_of(talbot)), 0, 255).astype(np.uint8)))
    left, right = inside & (x < 0.5), inside & (x >= 0.5)
    clear_l, clear_r = ~inside & (x < 0.45), ~inside & (x > 0.55)
    A, B = float(talbot[clear_l].mean()), float(talbot[clear_r].mean())
    P, Q = float(talbot[left].mean()), float(talbot[right].mean())
    alpha_m = (P - Q) / (A - B)                              # Metelli's Eq. 5.1
    t_m = (A * Q - B * P) / (A + Q - B - P)                  # Eq. 5.2
    return Result(files, f"(a) The episcotister as a video: a disc of luminance t = {t:g} cd/m² with an open sector of "
                         f"relative area alpha = {alpha:g} turning at {revolutions_per_second:g} revolutions per second over "
                         f"a background of a = {a:g} cd/m² (left) and b = {b:g} cd/m² (right). (b) Its mean over one "
                         f"turn ({per_turn} frames at {d.frame_rate:g} Hz), Talbot's law: inside the disc p = alpha a + "
                         f"(1 - alpha) t on the left and q = alpha b + (1 - alpha) t on the right, seen as a dark transparent "
                         f"layer over the bipartite background. Metelli's equations recover the layer from the four "
                         f"luminances: alpha = (p - q) / (a - b) (Eq. 5.1), t = (aq - bp) / (a + q - b - p) (Eq. 5.2), "
                         f"here measured on the displayed luminance ({size_deg:g} deg on {d.pixels_per_degree:g} px/deg, "
                         f"{d.luminance[0]:g}..{d.luminance[1]:g} cd/m², gamma {d.gamma:g}, {d.bits} bits, dithered).",
                  measured={"a / b / p / q after one turn (cd/m²)": f"{A:.2f} / {B:.2f} / {P:.2f} / {Q:.2f}",
                            f"alpha from Eq. 5.1 (set {alpha:g})": alpha_m,
                            f"t from Eq. 5.2 (set {t:g} cd/m²)": t_m,
                            "Michelson contrast inside / outside the disc (Eq. 5.4: their ratio)":
                                f"{(P - Q) / (P + Q):.3f} / {(A - B) / (A + B):.3f}"})


@figure("stimuli", "fig5_2", source="Zhang 2003, Fig. 5.2 (after Singh & Anderson 2002)",
        title="Transmittance matching: a target disc and a matching disc of another mean luminance, over a sinusoidal background",
        params=dict(size_deg=8.0, mean=40.0, michelson_surround=0.8, alpha_target=0.6, match_mean=20.0, cycles=4.0,
                    seed=12),
        quick=dict(size_deg=2.0), uses=STIM,
        look="the two central discs look equally transparent: the same Michelson contrast, though their luminance ranges differ by half")
def transmittance_matching(out, *, size_deg, mean, michelson_surround, alpha_target, match_mean, cycles, seed):
    from noiselab import analysis

    from .._common import label_band, save_image

    d = _display()
    n = d.pixels(size_deg)
    plaid = _plaid(n, cycles)
    surround = mean * (1 + michelson_surround * plaid)       # Michelson contrast of the surround
    centre = _disc_mask(n, 0.2)
    outer = _disc_mask(n, 0.48)
    # the target: the same mean as its surround, a fixed range; the match: another mean, its range set so that
    # its Michelson contrast (range / 2 mean, Eq. 5.3) equals the target's, which is what observers matched
    target = np.where(centre, mean * (1 + alpha_target * michelson_surround * plaid), surround)
    match = np.where(centre, match_mean * (1 + alpha_target * michelson_surround * plaid), surround)
    field = mean * (1 - michelson_surround) * 0.8
    target, match = np.where(outer, target, field), np.where(outer, match, field)
    gap = max(4, n // 12)
    L = _side_by_side(target, match, gap, field)
    values = _show(L, d, seed)
    shown = d.luminance_of(values)
    path = save_image(out / "fig5_2.png", label_band(values, [f"target (mean {mean:g} cd/m²)",
                                                               f"match (mean {match_mean:g} cd/m²)"],
                                                      centres=[n / 2, n + gap + n / 2]))
    left, right = shown[:, :n], shown[:, n + gap:]
    m_s = analysis.michelson_contrast(left, outer & ~_disc_mask(n, 0.24))
    m_t, m_m = analysis.michelson_contrast(left, centre), analysis.michelson_contrast(right, centre)
    range_t = float(np.ptp(left[centre]))
    range_m = float(np.ptp(right[centre]))
    range_s = float(np.ptp(left[outer & ~_disc_mask(n, 0.24)]))
    return Result([path], f"Left, the target: a central disc at the mean of its surround ({mean:g} cd/m²) with its "
                          f"luminance range reduced to {alpha_target:g} of the surround's, over a 2-D sinusoidal "
                          f"background ({cycles:g} cycles per side, Michelson contrast {michelson_surround:g}). Right, the "
                          f"match: the same background, the central disc at a mean of {match_mean:g} cd/m² with its range "
                          f"set so that its Michelson contrast (Eq. 5.3, range / (2 mean)) equals the target's. Singh & "
                          f"Anderson's observers matched transmittance by Michelson contrast (Eq. 5.4), not by luminance "
                          f"range (Metelli's Eq. 5.1): the two alphas below agree for Eq. 5.4 and differ for Eq. 5.1. "
                          f"{size_deg:g} deg per display on {d.pixels_per_degree:g} px/deg, "
                          f"{d.luminance[0]:g}..{d.luminance[1]:g} cd/m², gamma {d.gamma:g}, {d.bits} bits (dithered).",
                  measured={"Michelson surround / target / match": f"{m_s:.3f} / {m_t:.3f} / {m_m:.3f}",
                            "alpha by Eq. 5.4 (M_centre / M_surround), target / match": f"{m_t / m_s:.3f} / {m_m / m_s:.3f}",
                            "alpha by Eq. 5.1 (range ratio), target / match":
                                f"{range_t / range_s:.3f} / {range_m / range_s:.3f}"})


@figure("stimuli", "fig5_3", source="Zhang 2003, Fig. 5.3 (after Singh & Anderson 2002)",
        title="A centre with a larger luminance range than its surround: the surround becomes the transparent layer",
        params=dict(size_deg=8.0, range_centre=40.0, range_surround=20.0, means=((40.0, 40.0), (60.0, 20.0)),
                    cycles=4.0, seed=13),
        quick=dict(size_deg=2.0), uses=STIM,
        look="left, the centre reads as a hole in a hazy surround; right, with the same ranges but other means, much less so")
def larger_range(out, *, size_deg, range_centre, range_surround, means, cycles, seed):
    from noiselab import analysis

    from .._common import label_band, save_image

    d = _display()
    n = d.pixels(size_deg)
    plaid = _plaid(n, cycles)
    centre = _disc_mask(n, 0.22)
    panels = []
    for m_c, m_s in means:   # the same two luminance ranges, different means
        panels.append(np.where(centre, m_c + 0.5 * range_centre * plaid, m_s + 0.5 * range_surround * plaid))
    gap = max(4, n // 12)
    fill = float(np.mean([m for pair in means for m in pair]))
    L = _side_by_side(panels[0], panels[1], gap, fill)
    values = _show(L, d, seed)
    shown = d.luminance_of(values)
    path = save_image(out / "fig5_3.png", label_band(values, [f"(a) means {means[0][0]:g} / {means[0][1]:g}",
                                                               f"(b) means {means[1][0]:g} / {means[1][1]:g}"],
                                                      centres=[n / 2, n + gap + n / 2]))
    measured = {}
    ring = ~_disc_mask(n, 0.26)
    for tag, (m_c, m_s), img in (("(a)", means[0], shown[:, :n]), ("(b)", means[1], shown[:, n + gap:])):
        mc, ms = analysis.michelson_contrast(img, centre), analysis.michelson_contrast(img, ring)
        measured[f"{tag} range centre / surround (cd/m²)"] = f"{np.ptp(img[centre]):.1f} / {np.ptp(img[ring]):.1f}"
        measured[f"{tag} Michelson centre / surround"] = f"{mc:.3f} / {ms:.3f}"
        measured[f"{tag} M_surround / M_centre (the surround's alpha, Eq. 5.4)"] = ms / mc
    return Result([path], f"The same 2-D sinusoid ({cycles:g} cycles per side) in a central disc with a luminance range "
                          f"of {range_centre:g} cd/m² and in its surround with {range_surround:g} cd/m². (a) Both at a mean "
                          f"of {means[0][0]:g} cd/m²: the centre has the larger Michelson contrast, so the surround is seen "
                          f"as a transparent layer with a hole through which the centre shows (against Metelli's magnitude "
                          f"constraint, which asks the transparent region for the smaller range). (b) The same two ranges "
                          f"at means {means[1][0]:g} (centre) and {means[1][1]:g} cd/m² (surround): the surround's "
                          f"Michelson contrast now exceeds the centre's, and the percept weakens: contrast, not range, "
                          f"decides. {size_deg:g} deg per display on {d.pixels_per_degree:g} px/deg, "
                          f"{d.luminance[0]:g}..{d.luminance[1]:g} cd/m², gamma {d.gamma:g}, {d.bits} bits (dithered).",
                  measured=measured)


@figure("stimuli", "fig5_4", source="Zhang 2003, Fig. 5.4 (after Singh & Anderson 2002)",
        title="Texture background with two low-contrast regions: texture continuing (left) and not (right)",
        params=dict(size_deg=12.0, mean=40.0, michelson_surround=0.9, transmittance=0.5, sf=2.0, seed=4),
        quick=dict(size_deg=3.0), uses=STIM,
        look="the left region reads as a transparent layer over the texture; the right one, whose texture breaks, reads as a patch")
def singh_anderson(out, *, size_deg, mean, michelson_surround, transmittance, sf, seed):
    from noiselab import analysis
    from noiselab.stimuli import luminance_for

    from .._common import save_image

    d = _display()
    n = d.pixels(size_deg)
    # the textures' deviations are clipped at 2 standard deviations before the Michelson contrast is set: otherwise a
    # few extreme pixels take the whole range and the texture itself spans a third of it (too faint to read, above
    # all under the layer)
    bg = luminance_for(_texture(d, n, sf, 45.0, 20.0, seed), mean=mean, contrast=michelson_surround,
                       contrast_kind="michelson", clip=2.0)
    other = luminance_for(_texture(d, n, 1.6 * sf, -30.0, 20.0, seed + 1), mean=mean, contrast=michelson_surround,
                          contrast_kind="michelson", clip=2.0)
    y, x = np.mgrid[0:n, 0:n]
    inside_y = (y > n * 0.3) & (y < n * 0.7)
    left = inside_y & (x > n * 0.08) & (x < n * 0.44)
    right = inside_y & (x > n * 0.56) & (x < n * 0.92)
    L = bg.copy()
    # a transparent layer of transmittance t over a region: contrast scaled by t about the region's mean (Eq. 5.4)
    L[left] = mean + transmittance * (bg[left] - mean)
    L[right] = mean + transmittance * (other[right] - mean)
    values = _show(L, d, seed)
    shown = d.luminance_of(values)
    path = save_image(out / "fig5_4.png", values)
    surround = ~(left | right)
    m = {r: analysis.michelson_contrast(shown, mask) for r, mask in
         (("surround", surround), ("left", left), ("right", right))}
    m_under = analysis.michelson_contrast(bg, left)   # the background's own contrast under the left layer
    return Result([path], f"A {size_deg:g} deg texture (log-Gabor band at {sf:g} cycles/deg, 45 deg +- 20 deg) at a "
                          f"mean of {mean:g} cd/m² and Michelson contrast {michelson_surround:g} (deviations clipped at "
                          f"2 sd), with two regions "
                          f"seen through a layer of transmittance {transmittance:g}: the left one continues the "
                          f"background's texture, the right one holds another texture ({1.6 * sf:.2g} cycles/deg, "
                          f"-30 deg) at the same low contrast. Singh & Anderson: transparency is seen on the left "
                          f"only. Shown on a display of {d.pixels_per_degree:g} px/deg, "
                          f"{d.luminance[0]:g}..{d.luminance[1]:g} cd/m², gamma {d.gamma:g}, {d.bits} bits "
                          f"(dithered); contrasts measured on the displayed luminance.",
                  measured={"Michelson surround / left / right": f"{m['surround']:.3f} / {m['left']:.3f} / "
                                                                 f"{m['right']:.3f}",
                            "alpha = M_left / M_surround (Eq. 5.4)": m["left"] / m["surround"],
                            "M_left / M(background under the layer): the transmittance": m["left"] / m_under,
                            "mean luminance (cd/m²)": float(shown.mean())})


def _square_wave(display, frames, n, period_deg, speed, direction):
    """Bars (1) and gaps (0) of a square wave moving along ``direction`` (unit (dx, dy), y down) at ``speed`` deg/s."""
    period = display.deg_to_px(period_deg)
    step = display.px_per_frame(speed)
    y, x = np.mgrid[0:n, 0:n].astype(float)
    along = direction[0] * x + direction[1] * y
    t = np.arange(frames)[:, None, None]
    phase = (along[None] - step * t) / period
    return (phase % 1.0) < 0.5


@figure("stimuli", "fig5_5", source="Zhang 2003, Fig. 5.5 (after Stoner & Albright 1990)",
        title="Two square-wave gratings moving up-left and up-right, superimposed with a transmittance",
        params=dict(size_deg=6.0, duration=1.0, period_deg=1.0, speed=2.0, background=60.0, t_sw=0.5, seed=5),
        quick=dict(size_deg=2.0, duration=0.25), uses=STIM,
        look="where the gratings cross, the intersections' luminance decides whether they slide apart or move up together as a plaid")
def stoner_albright(out, *, size_deg, duration, period_deg, speed, background, t_sw, seed):
    from noiselab import analysis

    from .._common import save_video

    d = _display()
    n, frames = d.pixels(size_deg), d.frame_count(duration)
    r2 = 1 / np.sqrt(2)
    a = _square_wave(d, frames, n, period_deg, speed, (-r2, -r2))   # moving up-left
    b = _square_wave(d, frames, n, period_deg, speed, (r2, -r2))    # moving up-right
    # each grating's bars transmit t_sw of the background; where they overlap t_sw**2 (the multiplicative rule)
    L = background * np.where(a, t_sw, 1.0) * np.where(b, t_sw, 1.0)
    values = _show(L, d, seed)
    shown = d.luminance_of(values)
    files = save_video(out, "gratings", values, fps=d.frame_rate)   # its poster is the first frame
    lum = {k: float(shown[m].mean()) for k, m in (("background", ~a & ~b), ("bar", a & ~b), ("overlap", a & b))}
    # measured in the band of the fundamental: the hard edges' harmonics alias on the pixel grid
    f0 = n / d.deg_to_px(period_deg)
    va = analysis.best_velocity(np.where(a, 1.0, 0.0), band=(0.8 * f0, 1.2 * f0))
    vb = analysis.best_velocity(np.where(b, 1.0, 0.0), band=(0.8 * f0, 1.2 * f0))
    to_deg = d.deg_per_second
    return Result(files, f"Two square-wave gratings ({period_deg:g} deg period, {speed:g} deg/s) moving up-left and "
                         f"up-right over a {background:g} cd/m² background, each bar a layer of transmittance "
                         f"T_sw = {t_sw:g}, the overlap T_o = T_sw² (Stoner & Albright's multiplicative condition "
                         f"T_sw² <= T_o <= T_sw: seen as two gratings sliding over each other). {size_deg:g} deg, "
                         f"{duration:g} s at {d.frame_rate:g} Hz on a display of {d.pixels_per_degree:g} px/deg, "
                         f"{d.luminance[0]:g}..{d.luminance[1]:g} cd/m², gamma {d.gamma:g}, {d.bits} bits (dithered).",
                  measured={"luminance background / bar / overlap (cd/m²)": f"{lum['background']:.2f} / "
                                                                            f"{lum['bar']:.2f} / {lum['overlap']:.2f}",
                            "T_o measured (overlap / background)": lum["overlap"] / lum["background"],
                            "Michelson contrast bar vs background":
                                (lum["background"] - lum["bar"]) / (lum["background"] + lum["bar"]),
                            f"velocity of grating a, b at the fundamental (deg/s; stated +-{speed / np.sqrt(2):.3f} "
                            f"per axis)": f"({to_deg(va[0]):.3f}, {to_deg(va[1]):.3f}), "
                                          f"({to_deg(vb[0]):.3f}, {to_deg(vb[1]):.3f})"})
