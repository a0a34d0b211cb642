"""Stimuli in physical units: thesis Fig. 5.4 and 5.5 at stated contrasts on a stated display."""
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


@figure("stimuli", "fig5_4", source="Zhang 2003, Fig. 5.4 (after Singh & Anderson 2002)",
        title="Texture background with two low-contrast regions: texture continuing (left) and not (right)",
        params=dict(size_deg=8.0, mean=40.0, michelson_surround=0.6, transmittance=0.35, sf=3.0, seed=4),
        quick=dict(size_deg=3.0), uses=STIM,
        look="the left region reads as a transparent layer over the texture; the right one, whose texture breaks, reads as a patch")
def singh_anderson(out, *, size_deg, mean, michelson_surround, transmittance, sf, seed):
    from noiselab import analysis
    from noiselab.stimuli import luminance_for

    from .._common import save_image

    d = _display()
    n = d.pixels(size_deg)
    bg = luminance_for(_texture(d, n, sf, 45.0, 20.0, seed), mean=mean, contrast=michelson_surround,
                       contrast_kind="michelson")
    other = luminance_for(_texture(d, n, 1.6 * sf, -30.0, 20.0, seed + 1), mean=mean, contrast=michelson_surround,
                          contrast_kind="michelson")
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
                          f"mean of {mean:g} cd/m² and Michelson contrast {michelson_surround:g}, with two regions "
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
