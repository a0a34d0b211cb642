"""Phillips, "Creating noisy stimuli" (Perception 2004): figures 1-20."""
from __future__ import annotations

import numpy as np

from ..registry import Result, figure

NOISE = ("noiselab.lattice", "noiselab.fractal", "noiselab.analysis")
GEOM = NOISE + ("noiselab.geometry", "noiselab.io")


def _range(a):
    a = np.asarray(a)
    return [float(a.min()), float(a.max())]


@figure("phillips", "fig01", look="the same random values, smoothed more and more: the wider the box, the slower the wiggles",
        source="Phillips 2004, Fig. 1", title="One alternating random basis (a), box-filtered and renormalised (b)-(d)",
        params=dict(length=100, per_unit=20, freqs=(1 / 20, 1 / 10, 1 / 5), passes=3, measure_length=4000, seed=1),
        quick=dict(per_unit=8, measure_length=800), uses=NOISE)
def fig01(out, *, length, per_unit, freqs, passes, measure_length, seed):
    from scipy.ndimage import uniform_filter1d

    from noiselab import analysis
    from noiselab.lattice import LatticeNoise

    from .._common import pyplot, save_figure

    plt = pyplot()
    # (a): Phillips' basis, one random value per integer, alternating above and below zero
    basis = LatticeNoise(1, rng=seed, kernel="box", alternation="lattice")
    xi = np.arange(measure_length + 1)
    v = basis(xi.astype(float)[:, None])
    alternates = bool(np.all(v[xi % 2 == 0] > 0) and np.all(v[xi % 2 == 1] < 0))
    # (a) as the step function it is between the integers, sampled per_unit times per unit
    x = (np.arange(len(xi) * per_unit) + 0.5) / per_unit - 0.5
    step = np.repeat(v, per_unit)
    lo = measure_length / 2 - length / 2                       # plot a stretch from the middle: no filter edge
    shown = (x >= lo) & (x <= lo + length)
    fig, axes = plt.subplots(len(freqs) + 1, 1, figsize=(9, 1.75 * (len(freqs) + 1)), sharex=True, layout="constrained")
    a_in = (xi >= lo) & (xi <= lo + length)
    axes[0].vlines(xi[a_in] - lo, 0, v[a_in], color="k", lw=1)
    axes[0].plot(xi[a_in] - lo, v[a_in], "k.", ms=3)
    axes[0].set_title("(a) one random value per integer x, alternating above and below zero", fontsize=10, loc="left")

    def below(y, F):   # fraction of the power of y (over the whole measured stretch) below F cycle/unit
        return analysis.band_energy(y - y.mean(), (0.5, F * len(y) / per_unit), window="hann")

    measured = {"(a) alternates in sign at every integer": alternates,
                f"(a) fraction of power below {min(freqs):g} cycle/unit": below(step, min(freqs))}
    fractions = []
    for ax, F, tag in zip(axes[1:], freqs, "bcdefg"):
        width = int(round(per_unit / F))                   # a box of 1/F units: its first spectral zero is at F
        y = step.copy()
        for _ in range(passes):
            y = uniform_filter1d(y, width, mode="wrap")
        fractions.append(below(y, F))
        y = y[shown]
        y = y / np.abs(y).max()                            # renormalised to [-1, 1]
        ax.plot(x[shown] - lo, y, "k", lw=1)
        ax.set_title(f"({tag}) (a) box-filtered at {F:g} cycle/unit (box of {1 / F:g} units, {passes} passes), "
                     "renormalised", fontsize=10, loc="left")
        measured[f"({tag}) fraction of power below {F:g} cycle/unit"] = fractions[-1]
    for ax in axes:
        ax.axhline(0, color="0.6", lw=0.5)
        ax.set_ylim(-1.12, 1.12)
        ax.set_yticks([-1, 0, 1])
    axes[-1].set_xlabel("x (units)")
    axes[-1].set_xlim(-1, length + 1)
    most = "almost all (>= 99%)" if min(fractions) >= 0.99 else "not all (some < 99%)"
    return Result([save_figure(fig, out / "fig01.png")],
                  "(a) Phillips' basis: one random value per integer, alternating above (0, 1] and below [-1, 0) zero "
                  "(noiselab.LatticeNoise with kernel 'box' and alternation 'lattice'). (b)-(d) the same values (a), "
                  f"as a step function, filtered by a box of width 1/F ({passes} passes; the box's first spectral zero "
                  f"is at F) for F = {', '.join(f'{F:g}' for F in freqs)} cycle/unit, then renormalised to [-1, 1] "
                  f"(the stretch shown is x = {lo:g}..{lo + length:g}, relabelled 0..{length}). Measured over "
                  f"{measure_length} units (Hann window): (a) holds {measured[f'(a) fraction of power below {min(freqs):g} cycle/unit']:.1%} "
                  f"of its power below {min(freqs):g} cycle/unit (the alternation puts it near 1/2); each filtered curve "
                  f"holds {most} of its power below its F: {', '.join(f'{f:.2%}' for f in fractions)}.", measured)


@figure("phillips", "fig02", look="each lattice point looks up a table entry through the permutation; the stems are those entries",
        source="Phillips 2004, Fig. 2", title="Diagram: random-number tables, permutation table, basis function",
        params=dict(entries=16, table_size=256, seed=1), quick=dict(entries=8), uses=NOISE)
def fig02(out, *, entries, table_size, seed):
    from noiselab.lattice import LatticeNoise

    from .._common import pyplot, save_figure

    plt = pyplot()
    noise = LatticeNoise(1, rng=seed, kernel="box", alternation="lattice", table_size=table_size)
    perm = noise.perms[0][:entries]
    idx = np.arange(entries, dtype=float)
    basis = noise(idx[:, None])
    from_tables = np.where(np.arange(entries) % 2 == 0, noise.positive[perm], noise.negative[perm])
    agree = bool(np.allclose(basis, from_tables, atol=1e-9))
    fig = plt.figure(figsize=(12, 6.2))
    ax_p = fig.add_axes([0.05, 0.80, 0.55, 0.09])
    ax_p.set_xlim(0, entries), ax_p.set_ylim(0, 1), ax_p.axis("off")
    for i, p in enumerate(perm):
        ax_p.add_patch(plt.Rectangle((i, 0), 1, 1, fill=True, fc="#dde7f5" if i % 2 else "#f5e3dd", ec="k"))
        ax_p.text(i + 0.5, 0.5, str(int(p)), ha="center", va="center", fontsize=10)
        ax_p.text(i + 0.5, -0.12, str(i), ha="center", va="top", fontsize=10, color="0.4")
    ax_p.set_title(f"(a) permutation table, first {entries} of {table_size} entries: lattice point i (grey) -> table "
                   "index (in the box)", fontsize=10, pad=6)
    ax_t = fig.add_axes([0.67, 0.42, 0.30, 0.47])
    j = np.arange(table_size)
    ax_t.bar(j, noise.positive, width=1.0, color="#c0504d")
    ax_t.bar(j, noise.negative, width=1.0, color="#4f81bd")
    ax_t.scatter(perm[::2], noise.positive[perm[::2]], color="k", s=12, zorder=3)
    ax_t.scatter(perm[1::2], noise.negative[perm[1::2]], color="k", s=12, zorder=3)
    ax_t.set_title("(b) random-number tables: (0, 1] (red), [-1, 0) (blue);\nblack: the entries the permutation picks",
                   fontsize=10)
    ax_t.set_xlabel("table index"), ax_t.set_ylim(-1.05, 1.05)
    ax_b = fig.add_axes([0.05, 0.08, 0.55, 0.58])
    ax_b.vlines(idx, 0, basis, color="k", lw=2, label="basis: table[sign of i][perm[i]]")
    ax_b.plot(idx, basis, "ko", ms=4)
    smooth = LatticeNoise(1, rng=seed, kernel="catmull-rom", alternation="lattice", table_size=table_size)
    xs = np.linspace(0, entries - 1, 400)
    through = smooth(xs[:, None]) * smooth.bound      # undo the range normalisation: the curve through the stems
    ax_b.plot(xs, through, color="C2", lw=1.5, label="Catmull-Rom: through every stem")
    ax_b.axhline(0, color="0.6", lw=0.5)
    ax_b.set_ylim(-1.1, 1.1)
    ax_b.set_title("(c) the basis function: signs alternate with i", fontsize=10, loc="left")
    ax_b.set_xlabel("lattice point i")
    ax_b.legend(fontsize=10, loc="lower left", bbox_to_anchor=(0.0, 1.06), ncol=2, frameon=False)
    miss = float(np.max(np.abs(smooth(idx[:, None]) * smooth.bound - basis)))
    return Result([save_figure(fig, out / "fig02.png")],
                  "How noiselab.LatticeNoise builds Phillips' basis: two tables of random numbers (one on (0, 1], one on "
                  "[-1, 0)) (b), a shuffled permutation table that maps each lattice point to a table entry (a), "
                  "alternating between the positive and negative table, and the resulting basis function (c), with the "
                  "Catmull-Rom curve through it (LatticeNoise divides that curve by its overshoot bound 1.25 to keep "
                  "[-1, 1]; drawn here without the division, so it meets the stems).",
                  {"basis at the lattice points equals the table entries the permutation points to": agree,
                   "basis range": _range(basis), "largest |curve - stem| at the lattice points": miss})


@figure("phillips", "fig03", source="Phillips 2004, Fig. 3", title="A 5 degree arc with increasing noise amplitude (Eq. 3)",
        look="the bumps stay where they are from row to row; only their height grows",
        params=dict(arc_deg=5.0, cycles_per_degree=2.0, amplitudes=(0.0, 0.0005, 0.001, 0.002, 0.004), points=800, seed=2),
        quick=dict(points=200), uses=GEOM)
def fig03(out, *, arc_deg, cycles_per_degree, amplitudes, points, seed):
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import noisy_arc

    from .._common import pyplot, save_figure

    plt = pyplot()
    field = LatticeNoise(1, rng=seed)
    half = np.radians(arc_deg) / 2
    theta = np.linspace(-half, half, points)
    fig, ax = plt.subplots(figsize=(11, 1.9 * len(amplitudes)))
    measured = {}
    for k, a in enumerate(amplitudes):
        pts = noisy_arc(field, theta, radius=1.0, amplitude=a, frequency=cycles_per_degree * 180 / np.pi, phase=0.0)
        dy = -0.012 * k
        ax.plot(pts[:, 0], pts[:, 1] + dy, "k", lw=1.2)
        ax.text(-np.sin(half) * 1.08, np.cos(half) + dy, f"{a / max(amplitudes):.2f}" if max(amplitudes) else "0",
                ha="right", va="center", fontsize=13)
        if a:
            dev = np.linalg.norm(pts, axis=1) - 1.0
            measured[f"radial deviation / amplitude, amplitude {a:g}"] = _range(dev / a)
            peaks = int(np.sum((dev[1:-1] > dev[:-2]) & (dev[1:-1] >= dev[2:])))
    measured["undulations along the arc (local maxima of the deviation)"] = peaks
    ax.set_aspect("equal"), ax.axis("off")
    return Result([save_figure(fig, out / "fig03.png")],
                  f"f(theta) = noise(F theta) + r (sin theta, cos theta) over a {arc_deg:g} degree arc (r = 1), phase 0; "
                  "the amplitude (relative, left) grows downwards. The peaks and troughs stay in place; only their "
                  f"size changes. Phillips' '{cycles_per_degree:g} cycles per degree' is the lattice frequency F = "
                  f"{cycles_per_degree:g} lattice cells per degree of noise(F theta); value noise makes about one "
                  f"undulation per two cells, so a reader counts about {cycles_per_degree / 2:g} undulation per degree, "
                  f"{arc_deg * cycles_per_degree / 2:g} along the arc (measured: {peaks}).", measured)


def _independence(values, what, unit="seeds"):
    """Sentence and numbers for correlations that independent outputs should make 0 on average."""
    values = np.asarray(values, dtype=float)
    m, sd = float(values.mean()), float(values.std(ddof=1))
    se = sd / np.sqrt(len(values))
    word = ("consistent with independent outputs (|mean| < 2 standard errors)" if abs(m) < 2 * se
            else "not consistent with independent outputs (|mean| >= 2 standard errors)")
    return (f"{what} over {len(values)} {unit}: mean {m:+.3f}, sd {sd:.2f}, standard error {se:.3f}: {word}; a single "
            f"short sample scatters by the sd", [m, sd])


def _spread(pts):
    """Minor over major principal axis of a 2-D point cloud: 0 for a straight path, 1 for a round one."""
    ev = np.linalg.eigvalsh(np.cov(np.asarray(pts).T))
    return float(np.sqrt(max(ev[0], 0.0) / ev[1]))


@figure("phillips", "fig04", source="Phillips 2004, Fig. 4", title="A random trajectory: 1-D input (time), 2-D output (x, y)",
        look="the dot wanders in both x and y; its 1-second tail shows where it came from",
        params=dict(seconds=2.0, fps=50, cycles_per_second=1.5, tail_seconds=1.0, size=320, panels=4, candidates=16,
                    seeds=64, seed=3),
        quick=dict(fps=10, size=96, candidates=4, seeds=16), uses=GEOM)
def fig04(out, *, seconds, fps, cycles_per_second, tail_seconds, size, panels, candidates, seeds, seed):
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import trajectory, trajectory_frames

    from .._common import pyplot, save_figure, save_video

    plt = pyplot()
    t = np.arange(int(round(seconds * fps)) + 1) / fps
    # a 2 s path over 3 noise cells can come out nearly straight, which hides the 2-D output: show the
    # roundest of `candidates` seeds (largest minor/major principal-axis ratio), and say so
    paths = {k: trajectory(LatticeNoise(1, 2, rng=k), t, frequency=cycles_per_second) for k in range(seed, seed + candidates)}
    chosen = max(paths, key=lambda k: _spread(paths[k]))
    pts = paths[chosen]
    tail = int(round(tail_seconds * fps))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    # the same span on both axes, about the path's middle: the square video frames then show the path unstretched
    # (equal aspect), as the panels do
    half = 0.54 * float(np.max(hi - lo))
    mid = (lo + hi) / 2
    lim = ((mid[0] - half, mid[0] + half), (mid[1] - half, mid[1] + half))
    frames = trajectory_frames(pts, tail=tail, size=size, limits=lim)
    picks = np.linspace(tail, len(t) - 1, panels).astype(int)
    fig, axes = plt.subplots(1, panels, figsize=(3.2 * panels, 3.6), layout="constrained")
    for ax, i in zip(axes, picks):
        seg = pts[max(0, i - tail):i + 1]
        ax.plot(pts[:, 0], pts[:, 1], color="0.85", lw=1)              # the whole 2 s path, faint
        ax.plot(seg[:, 0], seg[:, 1], color="0.3", lw=2)                # the 1 s tail
        ax.plot(*pts[i], "ko", ms=8)
        ax.set_xlim(*lim[0]), ax.set_ylim(*lim[1]), ax.set_aspect("equal")
        ax.set_xlabel("x = noise_1(t)"), ax.set_ylabel("y = noise_2(t)")
        ax.set_title(f"t = {t[i]:.2f} s", fontsize=11)
    files = [save_figure(fig, out / "frames.png")] + save_video(out, "trajectory", frames, fps=fps)
    r = float(np.corrcoef(pts[:, 0], pts[:, 1])[0, 1])
    rs = [np.corrcoef(*trajectory(LatticeNoise(1, 2, rng=seed + 1000 + k), t, frequency=cycles_per_second).T)[0, 1]
          for k in range(seeds)]
    sentence, stats = _independence(rs, f"x-y correlation of a {seconds:g} s trajectory")
    return Result(files, f"A point whose (x, y) is 2-output noise of time: {seconds:g} s at {fps} frames/s, noise at "
                         f"{cycles_per_second:g} cycles/s; {panels} frames of the video, each with a {tail_seconds:g} s tail "
                         f"(dark) over the whole path (faint). Seed {chosen}, the roundest path of seeds {seed}-"
                         f"{seed + candidates - 1} (minor/major axis {_spread(pts):.2f}; x-y correlation {r:+.2f}). The two "
                         f"outputs are independent: {sentence}.",
                  {"x range": _range(pts[:, 0]), "y range": _range(pts[:, 1]), "x-y correlation, this trajectory": r,
                   "minor / major principal axis, this trajectory": _spread(pts),
                   f"x-y correlation over {seeds} other seeds (mean, sd)": stats})


@figure("phillips", "fig05", look="to the right more bumps (frequency), downwards bigger ones (amplitude); every curve closes",
        source="Phillips 2004, Fig. 5", title="Circles distorted in x and y by 2-D noise output",
        params=dict(amplitudes=(0.1, 0.2, 0.4), frequencies=(1.0, 2.0, 4.0), points=1440, seed=4),
        quick=dict(points=360), uses=GEOM)
def fig05(out, *, amplitudes, frequencies, points, seed):
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import noisy_circle

    from .._common import pyplot, save_figure

    plt = pyplot()
    field = LatticeNoise(2, 2, rng=seed)
    fig, axes = plt.subplots(len(amplitudes), len(frequencies), figsize=(3.0 * len(frequencies), 3.1 * len(amplitudes)),
                             layout="constrained")
    theta = np.linspace(0, 2 * np.pi, 200)
    gaps, bumps, rms = [], {}, {}
    for r, a in enumerate(amplitudes):
        for c, f in enumerate(frequencies):
            pts = noisy_circle(field, points, radius=1.0, amplitude=a, frequency=f, mode="xy", closed=True)
            ax = axes[r, c]
            ax.plot(np.cos(theta), np.sin(theta), color="0.8", lw=0.8, ls="--")
            loop = np.vstack([pts, pts[:1]])
            ax.plot(loop[:, 0], loop[:, 1], color="k", lw=1.6)
            ax.set_xlim(-1.6, 1.6), ax.set_ylim(-1.6, 1.6), ax.set_aspect("equal")
            ax.set_xticks([]), ax.set_yticks([])
            rad = np.hypot(pts[:, 0], pts[:, 1])
            # bumps: local maxima of the distance from the centre, counted around the closed curve
            nb = int(np.sum((rad > np.roll(rad, 1)) & (rad >= np.roll(rad, -1))))
            bumps[(a, f)] = nb
            base = noisy_circle(field, points, radius=1.0, amplitude=0.0, frequency=f, mode="xy", closed=True)
            rms[(a, f)] = float(np.sqrt(np.mean(np.sum((pts - base) ** 2, axis=1))))
            ax.set_title(f"({'abcdefghijkl'[r * len(frequencies) + c]}) a = {a:g}, F = {f:g}\n"
                         f"{nb} bumps, RMS shift {rms[(a, f)]:.3f}", fontsize=10)
            step = np.linalg.norm(np.diff(pts, axis=0), axis=1).mean()
            gaps.append(np.linalg.norm(pts[0] - pts[-1]) / step)
    by_f = [float(np.mean([bumps[(a, f)] for a in amplitudes])) for f in frequencies]
    rel = [float(np.mean([rms[(a, f)] / a for f in frequencies])) for a in amplitudes]
    grows = all(rms[(a1, f)] < rms[(a2, f)] for f in frequencies for a1, a2 in zip(amplitudes, amplitudes[1:]))
    return Result([save_figure(fig, out / "fig05.png")],
                  "Parametric circles (dashed: the undistorted unit circle), each point moved in x and y by a 2-output "
                  "noise of the angle; amplitude a grows downwards, frequency F (noise cells per radian) to the right. "
                  "The noise is read on a circle in its 2-D input space, so the curves close. The bump count (local "
                  f"maxima of the distance from the centre) {'grows' if all(np.diff(by_f) > 0) else 'does not grow'} with F: "
                  + ", ".join(f"{b:.3g} at F = {f:g}" for b, f in zip(by_f, frequencies))
                  + f" (mean over the rows). The RMS shift {'grows' if grows else 'does not always grow'} with a in "
                  f"every column, in proportion: RMS shift / a = {', '.join(f'{x:.3f}' for x in rel)} by row.",
                  {"closing step / mean step (1 = no seam)": [float(min(gaps)), float(max(gaps))],
                   "bumps per circle, rows a, columns F": [[bumps[(a, f)] for f in frequencies] for a in amplitudes],
                   "RMS shift per circle, rows a, columns F": [[rms[(a, f)] for f in frequencies] for a in amplitudes]})


def _taps_1d(kernel, x):
    """Lattice points and weights of a noiselab kernel at the points ``x`` (1-D): ``(points, weights)``, shape (len(x), taps)."""
    x = np.asarray(x, dtype=float)
    u = x + kernel.shift
    i0 = np.floor(u)
    t = u - i0
    k = np.arange(kernel.taps)
    pts = (i0[:, None] - kernel.left + k[None, :]).astype(np.int64)
    powers = t[:, None] ** np.arange(kernel.coef.shape[1])[None, :]
    return pts, powers @ kernel.coef[:kernel.taps].T


@figure("phillips", "fig06", look="2-D noise is 1-D noise along x on every integer row, then smoothed again across the rows",
        source="Phillips 2004, Fig. 6", title="2-D noise from planes of 1-D basis functions, one per integer y",
        params=dict(point=(14.0, 1.0), planes=(-1, 4), xrange=(9, 20), kernel="cubic", checks=200, seed=6),
        quick=dict(checks=20), uses=NOISE)
def fig06(out, *, point, planes, xrange, kernel, checks, seed):
    from noiselab.lattice import LatticeNoise

    from .._common import pyplot, save_figure

    plt = pyplot()
    noise = LatticeNoise(2, rng=seed, kernel=kernel)
    K = noise.kernel
    n = noise.table_size
    P = noise.perms[0]

    def lattice(iy, ix):
        """Value at the lattice point (y, x): the nested permutation of section 2.4.1, table[P[P[y] + x]]."""
        iy, ix = np.broadcast_arrays(np.asarray(iy) % n, np.asarray(ix) % n)
        return noise.values[(iy + ix) & 1, P[(P[iy] + ix) % n]]

    def plane(iy, x):
        """The 1-D basis function of plane y = iy (a row of lattice values), smoothed along x by the kernel."""
        pts, w = _taps_1d(K, x)
        return np.sum(w * lattice(iy, pts), axis=1)

    def derived(y, x):
        """Filter across the planes: f(y) = sum_j w(y - j) plane_j(x), then noiselab's range normalisation."""
        pts, w = _taps_1d(K, np.atleast_1d(y))
        rows = np.array([[plane(j, np.atleast_1d(xx))[0] for j, xx in zip(row, [x] * len(row))] for row in pts])
        return np.sum(w * rows, axis=1) / noise.bound

    px, py = point
    # the construction agrees with noiselab's evaluator (which takes (y, x): axis 0 is the plane index)
    rng = np.random.default_rng(seed)
    test = rng.uniform(-40, 40, (checks, 2))
    ours = np.array([derived(yy, xx)[0] for yy, xx in test])
    err = float(np.max(np.abs(ours - noise(test))))
    linear = LatticeNoise(2, rng=seed, kernel="linear")
    grid_y, grid_x = np.meshgrid(np.arange(*planes), np.arange(*xrange), indexing="ij")
    at_integers = linear(np.stack([grid_y.ravel(), grid_x.ravel()], 1).astype(float)).reshape(grid_y.shape) * linear.bound
    table_ok = bool(np.max(np.abs(lattice(grid_y, grid_x) - at_integers)) < 1e-12)
    value = float(derived(py, px)[0])
    direct = float(noise(np.array([[py, px]]))[0])

    xs = np.linspace(xrange[0], xrange[1] - 1, 400)
    ix = np.arange(xrange[0], xrange[1])
    ys = np.arange(*planes)
    fig = plt.figure(figsize=(14, 4.8), layout="constrained")
    gs = fig.add_gridspec(1, 3, width_ratios=[1, 1.3, 0.8])
    # (a) one plane
    ax = fig.add_subplot(gs[0])
    iy = int(np.floor(py))
    ax.vlines(ix, 0, lattice(iy, ix), color="k", lw=1)
    ax.plot(ix, lattice(iy, ix), "ko", ms=3, label="lattice values table[P[P[y] + x]]")
    ax.plot(xs, plane(iy, xs), color="C0", lw=1.5, label=f"smoothed ({kernel})")
    ax.axvline(px, color="C3", lw=0.8, ls="--")
    ax.axhline(0, color="0.6", lw=0.5)
    ax.set_ylim(-1.15, 1.45), ax.set_xlabel("x"), ax.legend(fontsize=10, loc="upper left", ncol=1)
    ax.set_title(f"(a) the 1-D basis function of plane y = {iy}", fontsize=10, loc="left")
    # (b) the planes, one per integer y, and the values at x = px across them
    ax3 = fig.add_subplot(gs[1], projection="3d")
    at_px = np.array([plane(j, np.array([px]))[0] for j in ys])
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    for j, vj in zip(ys, at_px):
        corners = [(xrange[0], j, -1), (xrange[1] - 1, j, -1), (xrange[1] - 1, j, 1), (xrange[0], j, 1)]
        ax3.add_collection3d(Poly3DCollection([corners], facecolor=(0.55, 0.7, 0.9, 0.12), edgecolor="0.6", lw=0.5))
        ax3.plot(xs, np.full_like(xs, j), plane(j, xs), color="C0", lw=1.2)
        ax3.plot([px, px], [j, j], [0, vj], color="C3", lw=0.8)
        ax3.scatter([px], [j], [vj], color="C3", s=16, depthshade=False)
    yy = np.linspace(ys[0], ys[-1], 200)
    across = np.array([derived(t, px)[0] for t in yy]) * noise.bound
    ax3.plot(np.full_like(yy, px), yy, across, color="C3", lw=2)
    ax3.scatter([px], [py], [value * noise.bound], color="k", s=40, depthshade=False)
    ax3.set_xlabel("x"), ax3.set_ylabel("y (plane)"), ax3.set_zlabel("value")
    ax3.set_zlim(-1, 1), ax3.set_ylim(ys[0] - 0.3, ys[-1] + 0.3), ax3.set_yticks(ys), ax3.view_init(elev=18, azim=-38)
    ax3.set_title(f"(b) planes y = {ys[0]}..{ys[-1]}; red: their values at x = {px:g}\nand the curve across them",
                  fontsize=10, loc="left")
    # (c) the function across the planes, sampled at y = py
    axc = fig.add_subplot(gs[2])
    axc.plot(ys, at_px, "o", color="C3", ms=5, label=f"plane values at x = {px:g}")
    axc.plot(yy, across, color="C3", lw=1.5, label="filtered across y")
    axc.plot([py], [value * noise.bound], "ko", ms=7)
    axc.annotate(f"noise({{{px:g}, {py:g}}}) = {value:.4f}", (py, value * noise.bound), xytext=(12, 28),
                 textcoords="offset points", fontsize=10, arrowprops=dict(arrowstyle="->", lw=0.8))
    axc.axhline(0, color="0.6", lw=0.5), axc.set_xlabel("y"), axc.set_ylim(-1.15, 1.45), axc.set_xticks(ys)
    axc.legend(fontsize=10, loc="upper left")
    axc.set_title(f"(c) across the planes at x = {px:g},\nsampled at y = {py:g}", fontsize=10, loc="left")
    agree = "equal" if err < 1e-12 else "differ"
    return Result([save_figure(fig, out / "fig06.png")],
                  "How noiselab.LatticeNoise extends 1-D noise to a 2-D input (section 2.4.1). Every integer y has its own "
                  "1-D basis function along x: the lattice values table[P[P[y] + x]] (the nested permutation, alternating "
                  f"table, {n} entries) smoothed by the {kernel} B-spline; (a) shows the one at y = {int(np.floor(py))}. (b) The "
                  f"planes side by side: for the input {{x, y}} = {{{px:g}, {py:g}}} each plane gives its value at x = {px:g} "
                  f"(red dots), and those values, filtered across y by the same kernel and sampled at y = {py:g} (c), are "
                  f"noise({{{px:g}, {py:g}}}). This construction and noiselab's evaluator {agree} (largest difference "
                  f"{err:.1e} over {checks} random points; 'equal' means below 1e-12).",
                  {f"derived value at {{{px:g}, {py:g}}}": value, "noiselab's value there": direct,
                   f"largest |construction - noiselab| over {checks} random points": err,
                   "lattice values table[P[P[y] + x]] equal linear-kernel noise at the integers (to 1e-12)": table_ok})


def _anisotropy_words(value):
    """The word for an anisotropy index, by thresholds stated in the caption."""
    if value < 0.05:
        return f"{value:.2f}: isotropic (< 0.05; white and 1/f noise give 0.004-0.01)"
    if value < 0.5:
        return f"{value:.2f}: mildly anisotropic (0.05-0.5)"
    return (f"{value:.2f}: strongly anisotropic (>= 0.5): the axis-aligned four-fold cross that every single-octave "
            "lattice noise shows (see lab/kernels)")


ISOTROPY_SEED = 16   # the seed Fig. 20 picks its kernel with: Figs. 7 and 8 use the same pick


@figure("phillips", "fig07", source="Phillips 2004, Fig. 7", title="2-D noise varying over time (3-D input, scalar output)",
        look="each blob drifts and changes shape slowly from one frame to the next; the video loops without a jump",
        params=dict(frames=80, size=256, cells=4.0, cells_per_frame=0.05, panels=4, step=4, seed=5),
        quick=dict(frames=20, size=64, cells_per_frame=0.2, step=1), uses=NOISE)
def fig07(out, *, frames, size, cells, cells_per_frame, panels, step, seed):
    from noiselab import analysis
    from noiselab.lattice import LatticeNoise

    from .._common import pyplot, save_figure, save_video

    plt = pyplot()
    (basis, kernel), score = _most_isotropic(ISOTROPY_SEED)
    # time wraps after frames * cells_per_frame lattice cells (an exact lattice period on the t axis), so the
    # video loops: its last frame steps into its first like any other step
    t_cells = frames * cells_per_frame
    if abs(t_cells - round(t_cells)) > 1e-9:
        raise ValueError(f"frames * cells_per_frame must be a whole number of cells for a loop, got {t_cells:g}")
    noise = LatticeNoise(3, rng=seed, basis=basis, kernel=kernel, period=(int(round(t_cells)), 256, 256))
    vol = noise.grid((frames, size, size), [(0, t_cells), (0, cells), (0, cells)])
    lo, hi = float(vol.min()), float(vol.max())
    video = (vol - lo) / (hi - lo)          # grey levels stretched over the measured range
    picks = [k * step for k in range(panels)]
    fig, axes = plt.subplots(1, panels, figsize=(3.2 * panels, 3.5), layout="constrained")
    for ax, i in zip(axes, picks):
        ax.imshow(video[i], cmap="gray", vmin=0, vmax=1, extent=(0, cells, cells, 0))
        ax.set_xlabel("x (lattice cells)"), ax.set_ylabel("y (lattice cells)")
        ax.set_title(f"frame {i}: t = {i * cells_per_frame:.2f} cells", fontsize=11)
    files = [save_figure(fig, out / "frames.png")] + save_video(out, "solid_noise", video)
    # measured in the blobs' band (half to twice the lattice rate), as Fig. 20 picks the kernel: over all
    # frequencies the gradient basis's near-zero low end leaves the axis-aligned high-frequency cross to dominate
    band = (cells / 2, 2 * cells)
    aniso = analysis.anisotropy(vol[0], band, window="hann")
    step_corr = float(np.corrcoef(vol[0].ravel(), vol[step].ravel())[0, 1])
    seam = analysis.loop_seam(vol)
    return Result(files, f"noise(x, y, t) as grey level: {size} x {size} pixels over {cells:g} lattice cells, time moving "
                         f"{cells_per_frame:g} cells per frame; frames {', '.join(map(str, picks))} ({step * cells_per_frame:g} "
                         f"cells apart, correlation {step_corr:.2f} between neighbouring panels) and the video. The t axis "
                         f"has an exact lattice period of {t_cells:g} cells, so the {frames}-frame video loops (loop seam "
                         f"{seam:.2f}, 1 = an ordinary step). {basis.capitalize()} noise with the {kernel} kernel, the most "
                         f"isotropic candidate of Fig. 20. Grey levels stretch the measured range [{lo:.2f}, {hi:.2f}] to "
                         f"black..white. Anisotropy of frame 0 over {band[0]:g}-{band[1]:g} cycles/frame (Hann window) "
                         f"{_anisotropy_words(aniso)}.",
                  {"range": _range(vol), "anisotropy of frame 0 in the blobs' band (Hann window)": aniso,
                   "correlation between neighbouring panels": step_corr, "loop seam (1 = seamless)": seam,
                   "roll-off slope above the lattice frequency": float(analysis.spectral_slope(vol[0], (2 * cells, 8 * cells),
                                                                                            window="hann"))})


def _render(meshes, path, size, **kw):
    from noiselab.geometry import render_mesh

    render_mesh(meshes, path, size=size, **kw)
    return path


def _render_tiles(meshes, path, labels, columns=3, cell=300, panel_in=3.2, **kw):
    """Render each mesh on its own (same view) and lay the images out as labelled panels (``panel_in`` inches each)."""
    from noiselab.geometry import render_mesh

    from .._common import pyplot, save_figure

    plt = pyplot()
    rows = -(-len(labels) // columns)   # from the labels: ``meshes`` may be a generator (one mesh in memory at a time)
    fig, axes = plt.subplots(rows, columns, figsize=(panel_in * columns, panel_in * rows), squeeze=False)
    for ax in axes.ravel():
        ax.axis("off")
    for ax, mesh, label in zip(axes.ravel(), meshes, labels):
        ax.imshow(render_mesh(mesh, size=cell, **kw))
        ax.set_title(label, fontsize=12)
    fig.tight_layout()
    return save_figure(fig, path)


@figure("phillips", "fig08", source="Phillips 2004, Fig. 8", title="A Monge surface z = noise(x, y) and its depth map",
        look="the same hills twice: as a lit surface and as a grey-level depth map (lighter = higher)",
        params=dict(grid=160, cells=4.0, amplitude=1.6, size=480, seed=6), quick=dict(grid=32, size=160), uses=GEOM)
def fig08(out, *, grid, cells, amplitude, size, seed):
    from noiselab import analysis
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import height_map, height_map_image, monge_surface

    (basis, kernel), _ = _most_isotropic(ISOTROPY_SEED)
    noise = LatticeNoise(2, rng=seed, basis=basis, kernel=kernel)
    ext = ((0.0, cells), (0.0, cells))
    surf = monge_surface(noise, (grid, grid), ext, amplitude=amplitude)
    h = height_map(noise, (size, size), ext)           # the depth map at the render's pixel size
    lim = float(np.abs(h).max()) * amplitude
    files = [_render(surf, out / "surface.png", size, elevation=-12, scalars="height", cmap="gist_earth",
                     clim=(-1.15 * lim, 1.15 * lim)), out / "depth.png"]
    height_map_image(h, files[1])
    band = (cells / 2, 2 * cells)     # the blobs' band, as in Figs. 7 and 20
    aniso = analysis.anisotropy(h, band, window="hann")
    return Result(files, f"Left: perspective view of z = {amplitude:g} noise(x, y) over {cells:g} x {cells:g} lattice cells "
                         f"({grid} x {grid} vertices), coloured by height (gist_earth: dark blue at the bottom, through green, to "
                         f"light brown at the top); right: the depth map, {size} x {size} pixels like the render, lighter = "
                         f"higher. {basis.capitalize()} noise with the {kernel} kernel, the most isotropic candidate of "
                         f"Fig. 20. Anisotropy over {band[0]:g}-{band[1]:g} cycles/frame (the blobs' band; Hann window) "
                         f"{_anisotropy_words(aniso)}.",
                  {"range": _range(h), "anisotropy in the blobs' band (Hann window)": aniso,
                   "roll-off slope above the lattice frequency": float(analysis.spectral_slope(h, (2 * cells, size / 4),
                                                                                            window="hann"))})


@figure("phillips", "fig09", look="arrows that turn smoothly from place to place; the grey streamlines follow them",
        source="Phillips 2004, Fig. 9", title="A 2-D flow field: 2-D input, 2-D output",
        params=dict(arrows=20, cells=4.0, size=512, streamlines=60, seed=7), quick=dict(arrows=10, size=200, streamlines=10),
        uses=GEOM)
def fig09(out, *, arrows, cells, size, streamlines, seed):
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import flow_field, quiver_image

    field = LatticeNoise(2, 2, rng=seed)
    ext = ((0.0, cells), (0.0, cells))
    quiver_image(field, out / "fig09.png", shape=(arrows, arrows), extent=ext, size=size, streamline_seeds=streamlines, rng=seed)
    _, vec = flow_field(field, (64, 64), ext)
    ang = np.arctan2(vec[..., 0], vec[..., 1])   # vectors are (v_y, v_x), in array-axis order
    return Result([out / "fig09.png"], f"At each (x, y) a 2-vector from 2-output noise, over {cells:g} x {cells:g} cells; "
                                       "grey: streamlines through the field.",
                  {"vx range": _range(vec[..., 1]), "vy range": _range(vec[..., 0]),
                   "mean resultant length of directions (0 = no preferred direction)": float(np.hypot(np.cos(ang).mean(), np.sin(ang).mean()))})


def _streamline_3d(field, start, cells, step=0.02, steps=600):
    """A streamline of a 3-output field from ``start`` (x, y, z), unit speed, midpoint rule, until it leaves the box."""
    def unit(q):
        v = field(np.asarray(q, float)[None, ::-1])[0][::-1]    # the field takes (z, y, x); vectors read as the arrows
        return v / max(float(np.linalg.norm(v)), 1e-12)

    line = [np.asarray(start, float)]
    for _ in range(steps):
        q = line[-1]
        mid = q + 0.5 * step * cells * unit(q)
        nxt = q + step * cells * unit(mid)
        if np.any(nxt < 0) or np.any(nxt > cells):
            break
        line.append(nxt)
    return np.array(line)


@figure("phillips", "fig10", source="Phillips 2004, Fig. 10", title="A 3-D vector field, as a cross-fusible stereo pair",
        look="cross your eyes until the two boxes fuse: near arrows (dark red) stand in front of far ones (pale blue), "
             "and neighbours point alike, as the two streamlines show",
        params=dict(glyphs=4, cells=2.0, size=900, eye_deg=5.0, seed=8), quick=dict(glyphs=3, size=360), uses=GEOM)
def fig10(out, *, glyphs, cells, size, eye_deg, seed):
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import flow_field

    from .._common import pyplot, save_figure

    plt = pyplot()
    field = LatticeNoise(3, 3, rng=seed)
    ext = ((0.0, cells),) * 3
    # the arrows' tails at the centres of a glyphs^3 grid of equal sub-cubes (flow_field samples lo + i (hi - lo) / n,
    # so the extent is shifted by half a spacing): the field fills the box evenly instead of its lower corner
    spacing = cells / glyphs
    pts, vec = flow_field(field, (glyphs,) * 3, ((spacing / 2, cells + spacing / 2),) * 3)   # (z, y, x), (v_z, v_y, v_x)
    p = pts.reshape(-1, 3)[:, ::-1]
    v = vec.reshape(-1, 3)[:, ::-1]
    scale = 1.1 * spacing / float(np.percentile(np.linalg.norm(v, axis=1), 90))   # most arrows about a spacing long
    # depth along the line of sight of the mean view: 0 nearest, 1 farthest; colour and width follow it
    elev, azim = np.radians(22.0), np.radians(-30.0)
    eye = np.array([np.cos(elev) * np.cos(azim), np.cos(elev) * np.sin(azim), np.sin(elev)])
    depth = -(p + 0.5 * v * scale - cells / 2) @ eye
    depth = (depth - depth.min()) / max(float(np.ptp(depth)), 1e-12)
    from matplotlib.colors import LinearSegmentedColormap

    cmap = LinearSegmentedColormap.from_list("near_far", ["#7f0f0f", "#c2562f", "#7fa7cf"])
    colours = [cmap(d) for d in depth]
    starts = [(0.15 * cells, 0.5 * cells, 0.45 * cells), (0.8 * cells, 0.25 * cells, 0.7 * cells)]
    lines = [np.concatenate([_streamline_3d(lambda q: -field(q), s_, cells, steps=60)[::-1],
                             _streamline_3d(field, s_, cells, steps=60)[1:]]) for s_ in starts]
    # cross-fused viewing: the left image is the right eye's view, turned by half the vergence the other way
    fig = plt.figure(figsize=(size / 100, size / 200 + 0.4))
    # the wireframe box: the field's cube, widened (the same on every axis, so it stays a cube) to hold every arrow head
    heads = p + v * scale
    lo, hi = min(0.0, float(heads.min())), max(float(cells), float(heads.max()))
    box = np.array([[x, y, z] for x in (lo, hi) for y in (lo, hi) for z in (lo, hi)])
    edges = [(i, j) for i in range(8) for j in range(i + 1, 8) if np.sum(box[i] != box[j]) == 1]
    order = np.argsort(-depth)     # far arrows first, so near ones are drawn over them
    for k, az in enumerate((-30 + eye_deg / 2, -30 - eye_deg / 2)):
        ax = fig.add_axes((0.5 * k, 0.0, 0.5, 0.92), projection="3d")
        ax.set_proj_type("persp", focal_length=0.6)
        for i, j in edges:
            ax.plot(*np.c_[box[i], box[j]], color="0.6", lw=1.0)
        for line in lines:
            ax.plot(*line.T, color="0.1", lw=2.2)
        for a in order:
            ax.quiver(*p[a], *(v[a] * scale), color=colours[a], linewidth=1.5 + 2.5 * (1 - depth[a]),
                      arrow_length_ratio=0.3)
        ax.view_init(elev=22, azim=az)
        ax.set_xlim(lo, hi), ax.set_ylim(lo, hi), ax.set_zlim(lo, hi)
        ax.set_box_aspect((1, 1, 1)), ax.set_axis_off()
        ax.set_title("left: the right eye's view" if k == 0 else "right: the left eye's view", fontsize=12)
    length = [float(np.sum(np.linalg.norm(np.diff(line, axis=0), axis=1))) for line in lines]
    # local smoothness, measured: the angle between neighbouring arrows along each axis of the glyph grid
    unit = vec / np.linalg.norm(vec, axis=-1, keepdims=True)
    cos = np.concatenate([np.sum(unit[1:] * unit[:-1], -1).ravel(), np.sum(unit[:, 1:] * unit[:, :-1], -1).ravel(),
                          np.sum(unit[:, :, 1:] * unit[:, :, :-1], -1).ravel()])
    fine_pts, fine = flow_field(field, (24,) * 3, ext)
    fu = fine / np.linalg.norm(fine, axis=-1, keepdims=True)
    fine_cos = np.sum(fu[1:] * fu[:-1], -1)
    return Result([save_figure(fig, out / "stereo.png")],
                  f"{glyphs}^3 arrows of 3-output noise of (x, y, z) over {cells:g}^3 lattice cells in a wireframe box "
                  f"seen in perspective, each arrow coloured and thickened by its depth (dark red near, pale blue far), "
                  f"with two streamlines (dark grey) through the field: they bend gradually, which is what 'locally "
                  f"smooth' means here. The two views differ by {eye_deg:g} degrees of azimuth (left image = right eye, "
                  "for cross-fusing). Arrow length is proportional to the vector's magnitude.",
                  {**{f"v{c} range": _range(vec[..., i]) for i, c in enumerate("zyx")},
                   "streamline lengths (cells)": length,
                   f"median angle between neighbouring arrows {spacing:.2f} cells apart (degrees)":
                       float(np.degrees(np.arccos(np.clip(np.median(cos), -1, 1)))),
                   f"median angle between neighbours {cells / 23:.3f} cells apart (degrees)":
                       float(np.degrees(np.arccos(np.clip(np.median(fine_cos), -1, 1))))})


@figure("phillips", "fig11", source="Phillips 2004, Fig. 11", title="Height and colour from one vector-valued noise",
        look="hills and valleys, seen from low and lit from the side, whose colour changes independently of their height",
        params=dict(grid=128, cells=3.0, amplitude=1.3, size=520, seeds=32, seed=9), quick=dict(grid=24, size=200, seeds=8),
        uses=GEOM)
def fig11(out, *, grid, cells, amplitude, size, seeds, seed):
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import colored_surface

    ext = ((0.0, cells), (0.0, cells))
    # the colour components use their measured spread (2nd to 98th percentile), not the bound [-1, 1] that the
    # noise almost never reaches: over [-1, 1] the hue covered only about 76-263 degrees and the RGB was muddy
    f_hue, f_rgb = LatticeNoise(2, 2, rng=seed), LatticeNoise(2, 4, rng=seed + 1)
    vr_hue = tuple(float(q) for q in np.percentile(f_hue.grid((grid, grid), ext)[..., 1], [2, 98]))
    vr_rgb = tuple(float(q) for q in np.percentile(f_rgb.grid((grid, grid), ext)[..., 1:], [2, 98]))
    hue = colored_surface(f_hue, (grid, grid), ext, amplitude=amplitude, color="hue", value_range=vr_hue)
    rgb = colored_surface(f_rgb, (grid, grid), ext, amplitude=amplitude, color="rgb", value_range=vr_rgb,
                          on_alias="ignore")
    # a low, lit view: the hills and valleys read by their shading; the colours are softened a third towards grey
    # for the render only (the measured colours below are the surface's own), so shading is not swamped by hue
    shown = []
    for m in (hue, rgb):
        m = m.copy()
        c = np.asarray(m.visual.vertex_colors).astype(float)
        c[:, :3] = 0.67 * c[:, :3] + 0.33 * 190.0
        m.visual.vertex_colors = np.clip(np.rint(c), 0, 255).astype(np.uint8)
        shown.append(m)
    # the fit leaves a 4% margin around the farthest vertex; a zoom past 1 pushed both surfaces out of their frames,
    # so each is drawn slightly smaller than the fit and in its own labelled panel
    path = _render_tiles(shown, out / "fig11.png", ["hue (component 2)", "RGB (components 2-4)"], columns=2,
                         cell=size, panel_in=size / 100, elevation=-5, azimuth=20, zoom=0.92)
    cols = np.asarray(rgb.visual.vertex_colors)[:, :3].astype(float)
    here = [float(np.corrcoef(cols[:, i], cols[:, j])[0, 1]) for i, j in ((0, 1), (0, 2), (1, 2))]
    from matplotlib.colors import rgb_to_hsv

    hues = 360 * rgb_to_hsv(np.asarray(hue.visual.vertex_colors)[:, :3] / 255.0)[:, 0]
    covered = float(np.mean(np.histogram(hues, bins=36, range=(0, 360))[0] > 0))
    z = np.asarray(hue.vertices)[:, 2]
    # over only 3 x 3 lattice cells two independent smooth fields correlate by chance: the spread over seeds says how much
    pooled = []
    for k in range(seeds):
        c = LatticeNoise(2, 4, rng=seed + 100 + k).grid((grid, grid), ext)[..., 1:].reshape(-1, 3)
        pooled += [np.corrcoef(c[:, i], c[:, j])[0, 1] for i, j in ((0, 1), (0, 2), (1, 2))]
    sentence, stats = _independence(pooled, f"the R-G, R-B, G-B correlations of 3 x 3-cell surfaces (3 pairs x {seeds} seeds)",
                                    unit="values")
    return Result([path],
                  f"Left: 2-output noise, component 1 = height (z = {amplitude:g} noise, relief {np.ptp(z):.2f} over "
                  f"{cells:g} cells), component 2 = hue, its 2nd-98th percentile stretched over the whole hue circle "
                  f"({100 * covered:.0f}% of 10-degree hue bins used). Right: 4-output noise, component 1 = height, "
                  "components 2-4 = R, G, B, stretched the same way. Here the RGB channels correlate by "
                  f"{', '.join(f'{r:+.2f}' for r in here)}; {sentence}.",
                  {"relief (max - min height) over the surface": float(np.ptp(z)),
                   "hue circle covered (fraction of 10-degree bins)": covered,
                   "RGB channel correlations, this surface (R-G, R-B, G-B)": here,
                   f"channel correlations over {seeds} seeds (mean, sd)": stats})


def _slope_sentence(slopes, dim, gain=0.5, tolerance=0.25):
    """Compare fractal-sum amplitude slopes (over seeds) with the target log2(gain) - dim/2."""
    slopes = np.asarray(slopes, dtype=float)
    target = np.log2(gain) - dim / 2
    m, sd = float(slopes.mean()), float(slopes.std(ddof=1))
    word = "matches" if abs(m - target) <= tolerance else "misses"
    return (f"the amplitude spectrum's slope over the octaves, {m:.2f} +- {sd:.2f} (mean, sd over {len(slopes)} seeds), "
            f"{word} the target log2(gain) - d/2 = {target:g} for gain {gain:g} in {dim}-D (within {tolerance:g}: "
            f"{'yes' if word == 'matches' else 'no'}); 1/f (-1) would need gain {2 ** (dim / 2 - 1):.3g}"), [m, sd], target


def _octave_plots(out, name, kind, octaves, length, samples, cells, seed, seeds=1, zoom=None):
    from noiselab import analysis
    from noiselab.fractal import fractal_sum, turbulence
    from noiselab.lattice import LatticeNoise

    from .._common import pyplot, save_figure

    plt = pyplot()
    noise = LatticeNoise(1, rng=seed, frequency=cells / length)
    x = np.linspace(0, length, samples, endpoint=False)[:, None]
    fn = fractal_sum if kind == "fractal" else turbulence
    ns = list(range(1, octaves + 1)) if kind == "fractal" else [octaves]
    rows = len(ns) + (1 if zoom else 0)
    fig, axes = plt.subplots(rows, 1, figsize=(9, 1.6 * rows + 0.5), squeeze=False, layout="constrained")
    measured = {}
    for ax, n in zip(axes[:, 0], ns):
        y = fn(noise, x, n)
        if kind != "fractal":   # the same octaves signed, as in Fig. 12: where they cross zero, |noise| creases
            ax.plot(x[:, 0], fractal_sum(noise, x, n), color="C0", lw=0.8, alpha=0.6, label=f"fracsum(x, {n}) (Fig. 12)")
        ax.plot(x[:, 0], y, "k", lw=0.9, label=f"turb(x, {n})" if kind != "fractal" else None)
        if kind != "fractal":
            ax.legend(fontsize=10, loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=2, frameon=False)
        ax.axhline(0, color="0.7", lw=0.5)
        ax.set_xlim(0, length)
        ax.set_title(f"n = {n} octave{'s' if n > 1 else ''}", fontsize=11, loc="left")
        ax.set_ylabel("value")
        measured[f"n = {n}: range"] = _range(y)
    if zoom:
        ax = axes[-1, 0]
        keep = (x[:, 0] >= zoom[0]) & (x[:, 0] <= zoom[1])
        ax.plot(x[keep, 0], y[keep], "k", lw=1.1)
        for n in range(1, octaves + 1):   # the creases: where an octave's noise crosses zero, |noise| folds
            o = noise(x[keep] * 2 ** (n - 1))
            z = np.nonzero(np.diff(np.sign(o)))[0]
            ax.plot(x[keep, 0][z], y[keep][z], "v", ms=4 + 1.2 * (octaves - n), color=f"C{n - 1}",
                    label=f"{n}", ls="none")
        ax.set_xlim(*zoom)
        ax.legend(fontsize=10, loc="upper right", bbox_to_anchor=(1.0, -0.3), ncol=octaves, frameon=False,
                  title="creases of octave", title_fontsize=10)
        ax.set_title(f"zoom on x = {zoom[0]:g}..{zoom[1]:g}: each marker is a crease (one octave's noise crosses zero)",
                     fontsize=11, loc="left")
        axes[-2, 0].axvspan(*zoom, color="C1", alpha=0.15)
    axes[-1, 0].set_xlabel("x (input units)")
    sentence = ""
    if kind == "fractal":
        band = (cells / 2, cells * 2 ** (octaves - 1) / 4)   # value noise holds its power below half its lattice rate
        slopes = [analysis.spectral_slope(fn(LatticeNoise(1, rng=seed + k, frequency=cells / length), x, octaves), band,
                                          window="hann") for k in range(seeds)]
        sentence, stats, target = _slope_sentence(slopes, 1)
        measured[f"n = {octaves}: amplitude slope over {band[0]:g}-{band[1]:g} cycles/plot, {seeds} seeds (mean, sd; target {target:g})"] = stats
    return [save_figure(fig, out / f"{name}.png")], measured, sentence


@figure("phillips", "fig12", look="the large-scale shape stays; each octave adds finer, smaller wiggles on top",
        source="Phillips 2004, Fig. 12", title="Fractal sums of n = 1..5 octaves (Eq. 9)",
        params=dict(octaves=5, length=10.0, samples=4096, cells=8.0, seeds=16, seed=10), quick=dict(samples=1024, seeds=4),
        uses=NOISE)
def fig12(out, *, octaves, length, samples, cells, seeds, seed):
    files, measured, sentence = _octave_plots(out, "fig12", "fractal", octaves, length, samples, cells, seed, seeds)
    return Result(files, f"fracsum(x, n) = sum_F noise(2^F x) / 2^F for n = 1..{octaves}; the low-frequency carrier stays "
                         f"while each octave adds detail ({cells:g} lattice cells over the plot). Measured: {sentence}.",
                  measured)


@figure("phillips", "fig13", source="Phillips 2004, Fig. 13", title="Turbulence: 5 octaves of |noise| (Eq. 10)",
        look="every octave's zero crossings become sharp creases; grey-blue: the signed sum of the same octaves (Fig. 12)",
        params=dict(octaves=5, length=10.0, samples=8192, cells=8.0, zoom=(2.0, 3.5), seed=10), quick=dict(samples=2048),
        uses=NOISE)
def fig13(out, *, octaves, length, samples, cells, zoom, seed):
    files, measured, _ = _octave_plots(out, "fig13", "turbulence", octaves, length, samples, cells, seed, zoom=zoom)
    return Result(files, f"turb(x, {octaves}) = sum_F |noise(2^F x)| / 2^F over {cells:g} lattice cells, the exact octaves "
                         "of Fig. 12 (same seed, same lattice), with Fig. 12's signed n = 5 sum drawn behind; below, a zoom "
                         "with every crease marked: wherever one octave's noise crosses zero its magnitude folds, so the "
                         "sum has a kink there, at every scale.", measured)


def _octave_surfaces(out, kind, octaves, grid, cells, amplitude, size, seed, seeds=1):
    from noiselab import analysis
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import height_map, monge_surface

    noise = LatticeNoise(2, rng=seed)
    ext = ((0.0, cells), (0.0, cells))
    meshes = [monge_surface(noise, (grid, grid), ext, amplitude=amplitude, octaves=n, kind=kind, on_alias="ignore")
              for n in range(1, octaves + 1)]
    _render_tiles(meshes, out / "surfaces.png", [f"({'abcdefgh'[n - 1]}) n = {n}" for n in range(1, octaves + 1)],
                  cell=size // 3, elevation=10, scalars="height", cmap="gist_earth", clim=(-amplitude * 1.2, amplitude * 1.2))
    h = height_map(noise, (grid, grid), ext, octaves=octaves, kind=kind, on_alias="ignore")
    aniso = analysis.anisotropy(h, window="hann")
    spp = (grid - 1) / (cells * 2 ** (octaves - 1))
    measured = {f"n = {octaves}: range": _range(h), "anisotropy (Hann window)": aniso,
                "vertices per period of the finest octave": spp}
    sentence = (f"One {grid} x {grid} mesh for every n: {spp:.1f} vertices per period of the finest octave of "
                f"n = {octaves} ({'>= 6' if spp >= 6 else '< 6'}). Anisotropy of the n = {octaves} height map "
                f"{_anisotropy_words(aniso)}.")
    if kind == "fractal":
        band = (cells / 2, min(grid / 4, cells * 2 ** (octaves - 1) / 4))
        slopes = [analysis.spectral_slope(height_map(LatticeNoise(2, rng=seed + k), (grid, grid), ext, octaves=octaves,
                                                     kind=kind, on_alias="ignore"), band, window="hann")
                  for k in range(seeds)]
        s2, stats, target = _slope_sentence(slopes, 2)
        sentence += f" Spectrum: {s2}."
        measured[f"n = {octaves}: amplitude slope over {band[0]:g}-{band[1]:g} cycles/frame, {seeds} seeds (mean, sd; target {target:g})"] = stats
    return [out / "surfaces.png"], measured, sentence


@figure("phillips", "fig14", look="the same hills in every panel, with finer and finer roughness as octaves are added",
        source="Phillips 2004, Fig. 14", title="Fractal-sum surfaces, n = 1..5 octaves",
        params=dict(octaves=5, grid=320, cells=3.0, amplitude=0.5, size=900, seeds=8, seed=11),
        quick=dict(grid=32, size=300, seeds=3), uses=GEOM)
def fig14(out, *, octaves, grid, cells, amplitude, size, seeds, seed):
    files, measured, sentence = _octave_surfaces(out, "fractal", octaves, grid, cells, amplitude, size, seed, seeds)
    return Result(files, f"Monge surfaces z = {amplitude:g} fracsum(x, y, n), (a)-(e): n = 1..{octaves} from the top left, "
                         f"{grid} x {grid} vertices over {cells:g} x {cells:g} cells; colour = height. {sentence}", measured)


@figure("phillips", "fig15", look="sharp creases along the valleys, where each octave's noise changes sign",
        source="Phillips 2004, Fig. 15", title="Turbulence surfaces, n = 1..5 octaves",
        params=dict(octaves=5, grid=320, cells=3.0, amplitude=0.5, size=900, seed=11), quick=dict(grid=32, size=300), uses=GEOM)
def fig15(out, *, octaves, grid, cells, amplitude, size, seed):
    files, measured, sentence = _octave_surfaces(out, "turbulence", octaves, grid, cells, amplitude, size, seed)
    return Result(files, f"The same octaves summed as magnitudes (Eq. 10): z = {amplitude:g} turb(x, y, n), (a)-(e): "
                         f"n = 1..{octaves}. The folds of |noise| make crease lines along the valleys. {sentence}", measured)


def _spheres(field, specs, radius=1.0, base=None, samples_per_period=4.0, max_frequency=np.inf, max_subdivisions=6,
             min_frequency=0.0):
    """Displace a sphere (or ``base``) per (amplitude, frequency, octaves, kind); return meshes and radial ranges.

    Each sphere is subdivided for its highest octave, but not for more than ``max_frequency``.
    """
    from noiselab.geometry import displace, sphere_for_noise

    meshes, ranges = [], []
    for a, f, n, kind in specs:
        top = max(min(f * 2 ** (n - 1), max_frequency), min_frequency)   # min_frequency: a smooth silhouette
        mesh = base if base is not None else sphere_for_noise(top, radius, samples_per_period=samples_per_period,
                                                                        max_subdivisions=max_subdivisions)
        d = displace(mesh, field, amplitude=a, frequency=f, octaves=n, kind=kind, on_alias="ignore")
        meshes.append(d)
        if a:
            ranges.append(np.asarray(d.vertex_attributes["displacement"]) / a)
    return meshes, ranges


@figure("phillips", "fig16", look="top row: the same bumps growing taller; bottom row: more and smaller bumps",
        source="Phillips 2004, Fig. 16", title="Unit spheres displaced by noise (Eq. 11): amplitude, then frequency",
        params=dict(amplitudes=(0.1, 0.2, 0.3, 0.4), frequency=2.0, frequencies=(1.0, 2.0, 4.0, 8.0), amplitude=0.25,
                    size=1000, seed=12),
        quick=dict(frequencies=(1.0, 2.0, 3.0, 4.0), size=400), uses=GEOM)
def fig16(out, *, amplitudes, frequency, frequencies, amplitude, size, seed):
    from noiselab.lattice import LatticeNoise

    field = LatticeNoise(3, rng=seed)
    first, r1 = _spheres(field, [(a, frequency, 1, "fractal") for a in amplitudes])
    second, r2 = _spheres(field, [(amplitude, f, 1, "fractal") for f in frequencies])
    cell = size // 4
    lim = 0.5 * max(max(amplitudes), amplitude)
    kw = dict(view="xy", scalars="displacement", cmap="RdBu_r", clim=(-lim, lim))
    files = [_render_tiles(first, out / "amplitude.png", [f"({t}) a = {a:g}, F = {frequency:g}" for t, a in zip("abcd", amplitudes)],
                           columns=4, cell=cell, **kw),
             _render_tiles(second, out / "frequency.png", [f"({t}) a = {amplitude:g}, F = {f:g}" for t, f in zip("efgh", frequencies)],
                           columns=4, cell=cell, **kw)]
    allr = np.concatenate(r1 + r2)
    rms = [float(np.sqrt(np.mean(r ** 2))) for r in r1 + r2]
    return Result(files, f"p' = p + s n_p with s = a noise(F p), seen along z. Top row (a)-(d): F = {frequency:g}, a = "
                         f"{', '.join(f'{a:g}' for a in amplitudes)}. Bottom row (e)-(h): a = {amplitude:g}, "
                         f"F = {', '.join(f'{f:g}' for f in frequencies)}. Colour: the displacement s, red outwards, blue "
                         f"inwards, on one scale (+-{lim:g}) for every sphere, so small low-frequency bumps show too. Each sphere "
                         "is subdivided to the resolution its noise needs (4 vertices per period).",
                  {"displacement / amplitude range (within [-1, 1])": _range(allr),
                   "RMS displacement / amplitude per sphere, (a)-(h)": rms,
                   "vertices per sphere": [len(m.vertices) for m in first + second]})


@figure("phillips", "fig17", source="Phillips 2004, Fig. 17", title="Spheres displaced by fractal (left) and turbulent (right) sums, n = 1..6",
        look="each added octave adds finer wrinkles on top of the same large bumps; turbulence only pushes outwards",
        params=dict(octaves=6, frequency=1.0, amplitude=0.3, samples_per_period=6.0, size=900, seed=13),
        quick=dict(octaves=3, size=360), uses=GEOM)
def fig17(out, *, octaves, frequency, amplitude, samples_per_period, size, seed):
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import displace, resolution_report, sphere_for_noise

    field = LatticeNoise(3, rng=seed)
    finest = frequency * 2 ** (octaves - 1)
    # one mesh for every n, fine enough for the finest octave of the largest n: a mesh refined per n makes
    # detail jump where the refinement changes, and too coarse a mesh makes n and n + 1 look the same
    base = sphere_for_noise(finest, samples_per_period=samples_per_period, max_subdivisions=8)
    spp = resolution_report(base, finest).samples_per_period
    ranges = {"fractal": [], "turbulence": []}

    def displaced(kind):
        for n in range(1, octaves + 1):
            d = displace(base, field, amplitude=amplitude, frequency=frequency, octaves=n, kind=kind, on_alias="ignore")
            ranges[kind].append(np.asarray(d.vertex_attributes["displacement"]) / amplitude)
            yield d

    labels = "abcdefghijklmnop"
    cell = size // 3
    files = [_render_tiles(displaced("fractal"), out / "fractal.png",
                           [f"({labels[n - 1]}) fractal, n = {n}" for n in range(1, octaves + 1)], columns=3, cell=cell,
                           view="xy"),
             _render_tiles(displaced("turbulence"), out / "turbulence.png",
                           [f"({labels[octaves + n - 1]}) turbulence, n = {n}" for n in range(1, octaves + 1)],
                           columns=3, cell=cell, view="xy")]
    ok = spp >= 6.0
    return Result(files, f"s = a fracsum(F p, n) ({labels[0]})-({labels[octaves - 1]}) and a turb(F p, n) "
                         f"({labels[octaves]})-({labels[2 * octaves - 1]}), a = {amplitude:g}, F = {frequency:g}, n = 1..{octaves} "
                         f"from the top left. One icosphere of {len(base.vertices):,} vertices for every n, subdivided for "
                         f"the finest octave of n = {octaves} ({finest:g} cycles/unit): measured along its longest edge, "
                         f"{spp:.2f} vertices per period ({'>= 6: every octave of every n drawn' if ok else '< 6: the finest octave is under-drawn'}).",
                  {"fractal: displacement / amplitude range": _range(np.concatenate(ranges["fractal"])),
                   "turbulence: displacement / amplitude range (>= 0)": _range(np.concatenate(ranges["turbulence"])),
                   "samples per period of the finest octave (longest edge), n = 1..": [
                       spp * 2 ** (octaves - n) for n in range(1, octaves + 1)],
                   "vertices per sphere": len(base.vertices)})


@figure("phillips", "fig18", source="Phillips 2004, Fig. 18", title="Any mesh: a cow displaced with s = 0 to 0.5 in steps of 0.1",
        look="the cow's smooth hide crumples more and more as s grows, until at 0.5 it folds into itself",
        params=dict(amplitudes=(0.0, 0.1, 0.2, 0.3, 0.4, 0.5), length=4.0, frequency=3.0, resolution=110, size=960, seed=14),
        quick=dict(amplitudes=(0.0, 0.25, 0.5), resolution=48, size=360), uses=GEOM)
def fig18(out, *, amplitudes, length, frequency, resolution, size, seed):
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import resolution_report, subdivide_for_noise

    from .._common import cow

    base = subdivide_for_noise(cow(resolution, size=length), frequency, samples_per_period=6.0)
    field = LatticeNoise(3, rng=seed)
    meshes, ranges = _spheres(field, [(a, frequency, 1, "fractal") for a in amplitudes], base=base)
    n0 = base.face_normals
    flips = [int((np.einsum("ij,ij->i", n0, m.face_normals) < 0).sum()) for m in meshes]
    rms = [float(np.sqrt(np.mean(np.sum((m.vertices - base.vertices) ** 2, axis=1)))) for m in meshes]
    labels = [f"({t}) s = {a:g}" for t, a in zip("abcdefgh", amplitudes)]
    files = [_render_tiles(meshes, out / "fig18.png", labels, columns=3, cell=size // 3, view="xz", azimuth=-35,
                           elevation=12, colors="#cdbfa8")]
    rep = resolution_report(base, frequency)
    return Result(files, f"Phillips' cow is a model file we cannot ship, so the cow is built in code: a smooth union of "
                         f"ellipsoids and capsules (barrel body, legs, head, muzzle, horns, ears, udder, tail) contoured by "
                         f"marching cubes, closed and in one part, {length:g} units long, {len(base.vertices):,} vertices "
                         f"({rep.samples_per_period:.1f} per period of the noise along the longest edge). Each vertex moves "
                         f"along its normal by s noise(F p), F = {frequency:g} cycles/unit, s = "
                         f"{', '.join(f'{a:g}' for a in amplitudes)}: the RMS displacement is "
                         f"{', '.join(f'{100 * r / length:.1f}%' for r in rms)} of the body's length. Faces turned over "
                         f"(normal against the undisplaced one: the hide folding into itself): "
                         f"{', '.join(f'{100 * f / len(base.faces):.1f}%' for f in flips)}.",
                  {"displacement / amplitude range": _range(np.concatenate(ranges)) if ranges else "n/a",
                   "RMS displacement / body length per s": [r / length for r in rms],
                   "vertices": len(base.vertices), "watertight": bool(base.is_watertight),
                   "flipped faces per s": flips, "faces": len(base.faces)})


@figure("phillips", "fig19", source="Phillips 2004, Fig. 19", title="Squashed spheres (5%) with noise from 0 to 10% of the radius",
        look="the first is smooth, the second gently dented, the third clearly lumpy: RMS 0, 5 and 10% of the radius",
        params=dict(squash=0.05, levels=(0.0, 0.05, 0.1), frequency=2.0, size=960, seed=15), quick=dict(size=360), uses=GEOM)
def fig19(out, *, squash, levels, frequency, size, seed):
    from noiselab.lattice import LatticeNoise
    from noiselab.geometry import displace, squashed_sphere

    base = squashed_sphere(squash, subdivisions=6)
    field = LatticeNoise(3, rng=seed)
    # "noise up to 10 % of the radius of curvature, on average": the RMS displacement, not the amplitude; the
    # unit-amplitude displacement's RMS on this mesh calibrates the amplitude of each level
    unit = np.asarray(displace(base, field, amplitude=1.0, frequency=frequency, on_alias="ignore")
                      .vertex_attributes["displacement"])
    unit_rms = float(np.sqrt(np.mean(unit ** 2)))
    meshes, rms = [], []
    for lev in levels:
        d = displace(base, field, amplitude=lev / unit_rms, frequency=frequency, on_alias="ignore")
        meshes.append(d)
        rms.append(float(np.sqrt(np.mean(np.asarray(d.vertex_attributes["displacement"]) ** 2))))
    z = [float(np.ptp(m.vertices[:, 2]) / np.ptp(m.vertices[:, 0])) for m in meshes]
    labels = [f"({t}) RMS noise {100 * lev:g}% of r" for t, lev in zip("abc", levels)]
    files = [_render_tiles(meshes, out / "fig19.png", labels, columns=3, cell=size // 3, view="xz", elevation=15,
                           colors="#d8d2c4")]
    return Result(files, f"Three spheres (radius r = 1) squashed by {100 * squash:g}% vertically, seen slightly from above, with "
                         f"noise of frequency {frequency:g} whose RMS displacement is {', '.join(f'{100 * x:g}' for x in levels)}% "
                         f"of the radius (Phillips: 'up to 10% of the radius of curvature, on average'): amplitudes "
                         f"{', '.join(f'{lev / unit_rms:.3g}' for lev in levels)}, since a unit amplitude displaces by "
                         f"{unit_rms:.3f} r RMS on this mesh. Measured RMS: {', '.join(f'{100 * x:.1f}%' for x in rms)}.",
                  {"RMS displacement / radius": rms, "amplitude used": [lev / unit_rms for lev in levels],
                   "height / width of each shape": z})


ISOTROPY_CANDIDATES = (("value", "cubic"), ("value", "quintic"), ("gradient", "cubic"), ("gradient", "catmull-rom"),
                       ("gradient", "quintic"))


def _isotropy_scores(candidates, trial_size, trial_seeds, seed):
    """Anisotropy and plateau fraction of 2-D slices of each (basis, kernel): ``({name: anisotropy}, {name: plateau})``."""
    from noiselab import analysis
    from noiselab.lattice import LatticeNoise

    # choose the basis and kernel that give the most isotropic blobs: anisotropy of 2-D slices in the blobs' band
    # (half to twice the lattice rate), mean over seeds; also the plateau fraction (pixels whose gradient is below
    # a tenth of its RMS), which shows the flat squares that value noise with the quintic fade makes at lattice points
    cells = 8.0
    scores, plateaus = {}, {}
    for basis, kernel in candidates:
        a, p = [], []
        for k in range(trial_seeds):
            img = LatticeNoise(2, rng=seed + k, basis=basis, kernel=kernel).grid((trial_size, trial_size),
                                                                                [(0, cells), (0, cells)])
            a.append(analysis.anisotropy(img, (cells / 2, min(2 * cells, trial_size / 2 - 1)), window="hann"))
            gy, gx = np.gradient(img)
            g = np.hypot(gx, gy)
            p.append(np.mean(g < 0.1 * np.sqrt(np.mean(g ** 2))))
        scores[f"{basis}/{kernel}"] = float(np.mean(a))
        plateaus[f"{basis}/{kernel}"] = float(np.mean(p))
    return scores, plateaus


def _most_isotropic(seed, trial_size=256, trial_seeds=3):
    """The (basis, kernel) that :func:`fig20` picks: the lowest anisotropy of the candidates, and its score."""
    scores, _ = _isotropy_scores(ISOTROPY_CANDIDATES, trial_size, trial_seeds, seed)
    best = min(scores, key=scores.get)
    return best.split("/"), scores[best]


@figure("phillips", "fig20", look="the same amplitude everywhere: only the size of the blobs changes, from few large to many small",
        source="Phillips 2004, Fig. 20", title="Stimuli: constant amplitude, frequency increasing",
        params=dict(frequencies=(0.75, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0), amplitude=0.12,
                    candidates=(("value", "cubic"), ("value", "quintic"), ("gradient", "cubic"), ("gradient", "catmull-rom"),
                                ("gradient", "quintic")),
                    trial_size=256, trial_seeds=3, size=900, seed=16),
        quick=dict(frequencies=(1.0, 2.0, 3.0), trial_size=64, trial_seeds=2, size=360), uses=GEOM)
def fig20(out, *, frequencies, amplitude, candidates, trial_size, trial_seeds, size, seed):
    from noiselab.lattice import LatticeNoise

    scores, plateaus = _isotropy_scores(candidates, trial_size, trial_seeds, seed)
    cells = 8.0
    best = min(scores, key=scores.get)
    basis, kernel = best.split("/")
    meshes, ranges = _spheres(LatticeNoise(3, rng=seed, basis=basis, kernel=kernel),
                              [(amplitude, f, 1, "fractal") for f in frequencies], samples_per_period=8.0, min_frequency=4.0)
    labels = [f"({t}) F = {f:g}" for t, f in zip("abcdefghijkl", frequencies)]
    files = [_render_tiles(meshes, out / "fig20.png", labels, columns=3, cell=size // 3, view="xy",
                           colors="#d8d2c4")]
    return Result(files, f"Spheres with a = {amplitude:g} and F = {', '.join(f'{f:g}' for f in frequencies)} (left to right, "
                         "top to bottom), finely subdivided (8 vertices per period) and smooth-shaded in place of "
                         f"RenderMan's analytic spheres. The noise is {basis} noise with the {kernel} kernel, chosen as the "
                         f"most isotropic of {', '.join(scores)} by the anisotropy of {trial_size} x {trial_size} slices over "
                         f"{cells:g} cells in the blobs' band, {cells / 2:g}-{2 * cells:g} cycles/frame (Hann window, mean of "
                         f"{trial_seeds} seeds; 0 = isotropic): " + ", ".join(f"{k} {v:.3f}" for k, v in scores.items())
                         + ". Plateau fraction (gradient below a tenth of its RMS): "
                         + ", ".join(f"{k} {100 * v:.1f}%" for k, v in plateaus.items()) + ".",
                  {"displacement / amplitude range": _range(np.concatenate(ranges)),
                   "anisotropy of the candidates (mean over seeds)": ", ".join(f"{k}: {v:.3f}" for k, v in scores.items()),
                   "plateau fraction of the candidates": ", ".join(f"{k}: {v:.3f}" for k, v in plateaus.items()),
                   "vertices per sphere": [len(m.vertices) for m in meshes]})
