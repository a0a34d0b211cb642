"""The laboratory's figures, drawn from a results dict (a run's, or ``results.json`` read back).

:func:`lab_figures` draws them (matplotlib figures, not yet saved) and
:func:`write_figures` writes them as PNG files; :func:`read_results` reads a
saved ``results.json``. Redrawing needs no measurement::

    python3 benchmarks/lab_run.py --replot     # benchmarks/results/*.png from benchmarks/results/results.json

Every figure is sized for the width a Markdown page shows (at most 1000
pixels, fonts of at least 8 points at 100 dots per inch). The log axes carry
one labelled tick per decade when they span a decade or more, and plain
numbers with their unit (``2 ms``, ``30``) when they span less; tick labels
that would still touch are dropped. Points of the speed-against-error panels
are numbered, the numbers placed by a greedy search around each point so that
no two of them overlap (a leader line joins a number set further off), and a
key beside each panel names the settings.
"""
from __future__ import annotations

import json
import math
import textwrap
from pathlib import Path

import numpy as np

__all__ = ["lab_figures", "write_figures", "read_results", "FIGURE_FILES"]

DPI = 100
MAX_WIDTH_IN = 10.0
# name of each figure -> its file in the results folder
FIGURE_FILES = {"texture": "texture_spectra.png", "snow": "snow_parallax.png", "scaling": "snow_scaling.png",
                "pareto": "pareto.png", "peers": "peers.png"}
_STYLE = {"font.size": 10, "axes.titlesize": 10.5, "axes.labelsize": 10, "xtick.labelsize": 9,
          "ytick.labelsize": 9, "legend.fontsize": 8.5, "figure.titlesize": 10.5, "figure.dpi": DPI,
          "savefig.dpi": DPI, "lines.markersize": 6}
_KEY_FONT = 8.5
_OURS, _PEER = "C3", "C0"
_EXACT = 1e-15          # errors at or below this are exact (the sweeps store an exact result as 1e-17)
_PREFIX = [(1e9, "G"), (1e6, "M"), (1e3, "k"), (1.0, ""), (1e-3, "m"), (1e-6, "\u00b5"), (1e-9, "n")]


def _num(v):
    """A float from a table entry (``results.json`` keeps NaN and inf as strings); NaN for None."""
    if v is None:
        return math.nan
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def read_results(path):
    """Read a laboratory ``results.json`` (as written by ``noiselab bench``) into a dict.

    Parameters
    ----------
    path : str or Path
        The file (``<output>/results/results.json``).

    Returns
    -------
    dict
        The tables of the run, as :func:`noiselab.lab.run.run_all` returns them.

    Examples
    --------
    >>> import json, os, tempfile
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = os.path.join(d, "results.json")
    ...     with open(p, "w") as f:
    ...         _ = f.write(json.dumps({"sweeps": []}))
    ...     read_results(p)
    {'sweeps': []}
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no laboratory results at {path} (run `noiselab bench` first)")
    try:
        results = json.loads(path.read_text())
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ValueError(f"{path} is not a laboratory results file (not JSON: {exc}); run `noiselab bench` "
                         "again") from None
    if not isinstance(results, dict):
        raise ValueError(f"{path} is not a laboratory results file (a JSON {type(results).__name__}, not an "
                         "object); run `noiselab bench` again")
    return results


# ----------------------------------------------------------------------------- tick labels

def _si(v, unit):
    """``v`` with an SI prefix and ``unit``: 0.002 s -> '2 ms', 3e8 -> '300 M'."""
    if v == 0 or not math.isfinite(v):
        return f"{v:g}{(' ' + unit) if unit else ''}"
    for scale, p in _PREFIX:
        if abs(v) >= scale * (1 - 1e-9):
            break
    text = f"{v / scale:.3g}"
    return f"{text} {p}{unit}".rstrip() if (p or unit) else text


def _plain(v, sci=False):
    """A compact number: plain between 1e-3 and 1e4 (unless ``sci``), else mathtext powers of ten."""
    if v == 0 or not math.isfinite(v):
        return f"{v:g}"
    if 1e-3 <= abs(v) < 1e4 and not sci:
        return f"{v:g}"
    e = math.floor(math.log10(abs(v)) + 1e-9)
    m = v / 10.0 ** e
    if abs(m - 1) < 1e-6:
        return rf"$10^{{{e}}}$"
    return rf"${m:.2g}\times10^{{{e}}}$"


def _log_ticks(axis, unit=None, max_labels=6):
    """Labelled ticks for a log ``axis`` (``ax.xaxis``/``ax.yaxis``) at its current limits.

    Powers of ten when at least two fall inside (every k-th decade past
    ``max_labels``); otherwise 1-2-5 (or 1..9) multiples, labelled as plain
    numbers. Minor ticks stay unlabelled. ``unit`` (``"s"``, ``""``) switches
    to SI prefixes (``2 ms``, ``300 M``).
    """
    from matplotlib.ticker import FixedLocator, FuncFormatter, LogLocator, NullFormatter

    lo, hi = sorted(axis.get_view_interval())
    lo, hi = max(lo, 1e-300), max(hi, 1e-300)
    k0, k1 = math.floor(math.log10(lo)) - 1, math.ceil(math.log10(hi)) + 1
    ticks = []
    for subs in ((1,), (1, 2, 5), (1, 2, 3, 5), (1, 2, 3, 4, 5, 6, 7, 8, 9)):
        ticks = [s * 10.0 ** k for k in range(k0, k1 + 1) for s in subs if lo <= s * 10.0 ** k <= hi * (1 + 1e-9)]
        if len(ticks) >= (2 if subs == (1,) else 3):
            break
    if len(ticks) > max_labels:
        stride = math.ceil(len(ticks) / max_labels)
        ticks = ticks[::stride]
    axis.set_major_locator(FixedLocator(ticks))
    sci = any(not 1e-3 <= t < 1e4 for t in ticks)        # one style per axis: all plain or all powers of ten
    fmt = (lambda v: _si(v, unit)) if unit is not None else (lambda v: _plain(v, sci))
    axis.set_major_formatter(FuncFormatter(lambda v, pos: fmt(v)))
    axis.set_minor_locator(LogLocator(base=10, subs="auto", numticks=12))
    axis.set_minor_formatter(NullFormatter())


def _visible_ticklabels(axis, renderer):
    out = []
    lo, hi = sorted(axis.get_view_interval())
    for tick in axis.get_major_ticks():
        lab = tick.label1
        if tick.get_loc() is None or not (lo * (1 - 1e-9) <= tick.get_loc() <= hi * (1 + 1e-9)):
            continue
        if lab.get_visible() and lab.get_text():
            out.append((tick.get_loc(), lab.get_window_extent(renderer)))
    return out


def _declutter(axis, renderer, pad=3.0):
    """Blank the major tick labels of ``axis`` that would touch the one kept before them."""
    from matplotlib.ticker import FuncFormatter

    labels = sorted(_visible_ticklabels(axis, renderer), key=lambda t: t[0])
    kept, last = [], None
    for loc, bb in labels:
        if last is None or not _touch(bb, last, pad):
            kept.append(loc)
            last = bb
    if len(kept) == len(labels):
        return
    old = axis.get_major_formatter()
    keep = np.array(kept)
    axis.set_major_formatter(FuncFormatter(
        lambda v, pos: old(v, pos) if keep.size and np.min(np.abs(keep / v - 1)) < 1e-6 else ""))


def _touch(a, b, pad=0.0):
    """Whether display boxes ``a`` and ``b`` come within ``pad`` pixels of each other."""
    return a.x0 < b.x1 + pad and b.x0 < a.x1 + pad and a.y0 < b.y1 + pad and b.y0 < a.y1 + pad


# ----------------------------------------------------------------------------- point labels

def _place_labels(ax, xy, texts, renderer, sizes=None, fontsize=8.5):
    """Number the points ``xy`` (data coordinates) of ``ax`` with ``texts``, no two labels overlapping.

    A greedy search: each label, in turn, takes the first spot around its
    point (12 directions on rings 6 to 50 points beyond its marker, whose
    size in points ``sizes`` gives) whose box stays inside the axes and
    clear of the markers and of the labels placed before it; a leader line
    joins a label set beyond the first two rings. With
    no clear spot left the label takes the one that overlaps least. Returns
    the annotations (their ``gid`` is ``"point-label"``).
    """
    from matplotlib.text import Text
    from matplotlib.transforms import Bbox

    disp = ax.transData.transform(np.asarray(xy, float))
    px = DPI / 72.0
    sizes = np.broadcast_to(6.0 if sizes is None else np.asarray(sizes, float), (len(disp),))
    halves = 0.5 * sizes * px + 1
    markers = [Bbox.from_extents(x - h, y - h, x + h, y + h) for (x, y), h in zip(disp, halves)]
    frame = ax.get_window_extent(renderer)
    placed, out = [], []
    angles = np.deg2rad(np.arange(0, 360, 30) + 15)
    rings = (0, 4, 9, 15, 22, 30, 40, 52)

    def put(ann, dx, dy):
        ann.set_position((dx, dy))
        ann.set_ha("left" if dx > 2 else "right" if dx < -2 else "center")
        ann.set_va("bottom" if dy > 2 else "top" if dy < -2 else "center")
        ann.update_positions(renderer)
        return Text.get_window_extent(ann, renderer)       # the number alone, not its leader line

    for i, text in enumerate(texts):
        ann = ax.annotate(text, xy=xy[i], xytext=(0, 0), textcoords="offset points", fontsize=fontsize,
                          gid="point-label", annotation_clip=False,
                          arrowprops=dict(arrowstyle="-", lw=0.6, color="0.4", shrinkA=0,
                                          shrinkB=halves[i] / px))
        best, best_cost = None, math.inf
        for r, a in ((r, a) for r in rings for a in angles):
            reach = r + halves[i] / px + 2          # points from the centre
            dx, dy = reach * math.cos(a), reach * math.sin(a)
            bb = put(ann, dx, dy)
            cost = 0.0
            if not (bb.x0 >= frame.x0 + 1 and bb.x1 <= frame.x1 - 1 and bb.y0 >= frame.y0 + 1
                    and bb.y1 <= frame.y1 - 1):
                cost += 1e6
            for other in placed + markers:
                if _touch(bb, other, 1.0):
                    w = min(bb.x1, other.x1) - max(bb.x0, other.x0) + 2
                    h = min(bb.y1, other.y1) - max(bb.y0, other.y0) + 2
                    cost += max(w, 0) * max(h, 0) + 1
            if cost < best_cost:
                best, best_cost = (dx, dy, r), cost
            if cost == 0:
                break
        dx, dy, r = best
        placed.append(put(ann, dx, dy))
        if r <= 4:            # next to its point: no leader line
            ann.arrowprops = None
            ann.arrow_patch = None
        out.append(ann)
    return out


# ----------------------------------------------------------------------------- the figures

def _new_figure(w, h):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(min(w, MAX_WIDTH_IN), h), dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _freeze(fig):
    """Draw ``fig`` once with its constrained layout, then keep that layout; returns the renderer."""
    fig.canvas.draw()
    fig.set_layout_engine("none")
    return fig.canvas.get_renderer()


def _finish(fig, renderer):
    """Drop touching tick labels on every log axis of ``fig`` and draw it again."""
    fig.canvas.draw()
    for ax in fig.get_axes():
        if not ax.axison:
            continue
        for axis in (ax.xaxis, ax.yaxis):
            if axis.get_scale() == "log":
                _declutter(axis, renderer)
    fig.canvas.draw()
    return fig


def _wrap(text, width):
    return "\n".join(textwrap.wrap(text, width, break_on_hyphens=False)) or text


def _fit_title(artist, box, renderer, width):
    """Rewrap the title ``artist`` until it fits inside the display box ``box``."""
    raw = artist.get_text().replace("\n", " ")
    while width > 12:
        artist.set_text(_wrap(raw, width))
        bb = artist.get_window_extent(renderer)
        if bb.x0 >= box.x0 and bb.x1 <= box.x1:
            return
        width -= 4


def plot_texture(rows):
    """Radial power spectra of the 1/f textures, 2-D and 3-D, with the target power law."""
    fig = _new_figure(10, 4.6)
    axes = fig.subplots(1, 2)
    handles = {}
    for ax, dim in zip(axes, (2, 3)):
        for r in rows:
            if r["dim"] != dim or not any(k in r["method"] for k in ("spectral", "cubic", "catmull", "quintic")):
                continue
            sp = r["_spectrum"]
            f, p = np.asarray(sp["f"], float), np.asarray(sp["power"], float)
            (line,) = ax.loglog(f, np.where(p > 0, p, np.nan), lw=2.2 if r["family"] == "spectral" else 1.2,
                                label=r["method"])
            handles.setdefault(r["method"], line)
            if r["family"] == "spectral":
                inband = p > p.max() * 1e-9
                f_in, p_in = f[inband], p[inband]
                ref = np.exp(np.mean(np.log(p_in * f_in ** dim)))
                (tl,) = ax.loglog(f_in, ref * f_in ** -dim, "k--", lw=1, label="target: power ~ f^-d (d = 2, 3)")
                handles.setdefault("target", tl)
                ax.set_ylim(bottom=p_in.min() * 1e-2)
        ax.set_title(f"1/f texture {dim}-D: radial power spectrum")
        ax.set_xlabel("cycles/frame")
        ax.set_ylabel("power per cell")
        _log_ticks(ax.xaxis)
        _log_ticks(ax.yaxis)
    fig.legend(list(handles.values()), [h.get_label() for h in handles.values()], loc="outside lower center",
               ncols=3)
    return _finish(fig, _freeze(fig))


def plot_snow(rows):
    """Measured fall speed per band of each snow method, with the parallax law."""
    fig = _new_figure(8, 5.2)
    ax = fig.subplots()
    law_done = False
    for r in rows:
        c = r["_curve"]
        ax.loglog(c["f"], c["speed"], "o-", label=r["method"], ms=5)
        if not law_done:
            ax.loglog(c["f"], c["law"], "k--", label="parallax law c N / (2 pi f)", zorder=5)
            law_done = True
    ax.set_xlabel("band centre (cycles/frame)")
    ax.set_ylabel("measured fall speed (px/frame)")
    ax.set_title("Falling snow: speed per band")
    _log_ticks(ax.xaxis)
    _log_ticks(ax.yaxis)
    fig.legend(loc="outside lower center", ncols=2)
    return _finish(fig, _freeze(fig))


def plot_scaling(srows, frows, texture_rows=None):
    """Time against size: snow per method, particles against flakes, 2-D textures."""
    fig = _new_figure(10, 5.4)
    axes = fig.subplots(1, 3)
    for ax, rows, key, title, xlabel in (
            (axes[0], srows, "voxels", "Snow: time\nagainst output size", "output voxels (frames x W x W)"),
            (axes[2], texture_rows or [], "voxels", "2-D 1/f texture:\ntime against size", "pixels (N x N)")):
        for m in dict.fromkeys(r["method"] for r in rows):
            rs = [r for r in rows if r["method"] == m]
            ax.loglog([r[key] for r in rs], [_num(r["time_s"]) for r in rs], "o-", ms=4, label=m)
        ax.set_title(title)
        ax.set_xlabel(xlabel)
        if rows:
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), fontsize=8)
    axes[1].loglog([r["flakes"] for r in frows], [_num(r["time_s"]) for r in frows], "o-", ms=4)
    axes[1].set_title("Particle snow: time\nagainst flakes")
    axes[1].set_xlabel("flakes")
    for ax in axes:
        ax.set_ylabel("median time")
        if ax.lines:
            _log_ticks(ax.xaxis, unit="")
            _log_ticks(ax.yaxis, unit="s")
    return _finish(fig, _freeze(fig))


def _key_text(pts, knee, exact, width):
    lines = []
    pad = len(str(len(pts)))
    for i, p in enumerate(pts):
        tag = (" (knee)" if knee[i] else "") + (" (exact)" if exact[i] else "")
        number = str(i + 1).rjust(pad, "\u2007")          # figure spaces: digits line up
        lines += textwrap.wrap(f"{number}  {p['setting']}{tag}", width, subsequent_indent="\u2007" * (pad + 2),
                               break_on_hyphens=False)
    return "\n".join(lines)


def _sweep_panel(sub, s):
    """One speed-against-error sweep in the subfigure ``sub``: the plot and, beside it, its key."""
    from matplotlib.lines import Line2D

    ax, kax = sub.subplots(1, 2, width_ratios=[1.3, 1])
    kax.axis("off")
    pts = s["points"]
    t = np.array([_num(p["time_s"]) for p in pts])
    err = np.array([_num(p["error"]) for p in pts])
    exact = err <= _EXACT
    real = err[np.isfinite(err) & ~exact]
    thr = _num(s.get("threshold"))
    floor_ = min([*(real / 10), *([thr / 10] if math.isfinite(thr) and thr > 0 else [])], default=1e-9)
    y = np.where(exact, floor_, err)
    knee = np.array([p["setting"] == s.get("knee") for p in pts], bool)
    ax.set_xscale("log")
    ax.set_yscale("log")
    handles, names = [], []
    if math.isfinite(thr) and thr > 0:
        handles.append(ax.axhline(thr, color="k", ls=":", lw=1.2))
        names.append("threshold")
    ok = np.isfinite(t) & np.isfinite(y)
    sizes = np.where(knee, 14.0, np.where(exact, 7.0, 6.0))
    ax.plot(t[ok & ~exact & ~knee], y[ok & ~exact & ~knee], "o", color="C0", ms=6)
    if (ok & exact & ~knee).any():
        ax.plot(t[ok & exact & ~knee], y[ok & exact & ~knee], "v", color="C0", ms=7)
        handles.append(Line2D([], [], ls="", marker="v", color="C0", ms=7))
        names.append("exact (error 0)")
    if (ok & knee).any():
        ax.plot(t[ok & knee], y[ok & knee], "*", color="C3", ms=14, zorder=4)
        handles.append(Line2D([], [], ls="", marker="*", color="C3", ms=12))
        names.append("knee")
    ax.margins(x=0.12, y=0.15)
    ax.set_xlabel("time (median)")
    ax.set_ylabel("error")
    _log_ticks(ax.xaxis, unit="s", max_labels=4)
    _log_ticks(ax.yaxis)
    key = kax.text(0.0, 1.0, _key_text(pts, knee, exact, 40), transform=kax.transAxes, va="top", ha="left",
                   fontsize=_KEY_FONT, linespacing=1.25, gid="key")
    key.set_in_layout(False)      # rewrapped to the panel's width once the layout is drawn (_fit_key)
    leg = kax.legend(handles, names, loc="lower left", bbox_to_anchor=(-0.02, 0.0), frameon=False,
                     fontsize=_KEY_FONT, handlelength=1.6, borderaxespad=0.0)
    sub.suptitle(s["name"], fontsize=10.5)
    keep = [i for i in range(len(pts)) if ok[i]]
    return dict(ax=ax, sub=sub, key=key, legend=leg, key_args=(pts, knee, exact),
                xy=[(t[i], y[i]) for i in keep], texts=[str(i + 1) for i in keep], sizes=sizes[keep])


def _fit_key(panel, renderer):
    """Rewrap a key until it stays inside its subfigure and clear of the legend below it."""
    key, sub = panel["key"], panel["sub"]
    box = sub.bbox
    leg = panel["legend"].get_window_extent(renderer)
    for width in range(40, 12, -2):
        key.set_text(_key_text(*panel["key_args"], width))
        bb = key.get_window_extent(renderer)
        if bb.x1 <= box.x1 - 3 and bb.y0 >= box.y0 and not _touch(bb, leg, 2):
            return


def _key_lines(s):
    return sum(len(textwrap.wrap(f"{i + 1}  {p['setting']} (knee) (exact)", 30)) for i, p in enumerate(s["points"]))


def plot_pareto(sweeps):
    """Speed against error of every sweep: numbered points, a key of the settings, the threshold and the knee."""
    cols = 2
    nrows = max(1, (len(sweeps) + cols - 1) // cols)
    need = [max(_key_lines(s) for s in sweeps[r * cols:(r + 1) * cols]) for r in range(nrows)] if sweeps else [1]
    heights = [max(2.9, 1.6 + 0.165 * n) for n in need]
    fig = _new_figure(MAX_WIDTH_IN, sum(heights))
    subs = np.atleast_1d(fig.subfigures(nrows, cols, height_ratios=heights, wspace=0.02, hspace=0.01)).ravel()
    panels = [_sweep_panel(sub, s) for sub, s in zip(subs, sweeps)]
    for sub in subs[len(sweeps):]:
        sub.set_visible(False)
    renderer = _freeze(fig)
    for p in panels:
        _fit_title(p["sub"]._suptitle, p["sub"].bbox, renderer, 70)
        _fit_key(p, renderer)
        _place_labels(p["ax"], p["xy"], p["texts"], renderer, sizes=p["sizes"])
    return _finish(fig, renderer)


def plot_peers(prows):
    """Points per second of each peer and of noiselab (red), one panel per scene, fastest on top."""
    from matplotlib.patches import Patch

    groups = list(dict.fromkeys(r["group"] for r in prows))
    sizes = [max(1, sum(1 for r in prows if r["group"] == g)) for g in groups]
    heights = [0.9 + 0.27 * n for n in sizes]
    fig = _new_figure(MAX_WIDTH_IN, sum(heights) + 0.5)
    axes = np.atleast_1d(fig.subplots(len(groups), 1, height_ratios=heights))
    for ax, g in zip(axes, groups):
        rs = [r for r in prows if r["group"] == g]
        ok = sorted((r for r in rs if r["status"] == "ok"), key=lambda r: _num(r["points_per_s"]))
        bad = [r for r in rs if r["status"] != "ok"]
        v = [_num(r["points_per_s"]) for r in ok]
        names = [r["case"] for r in bad] + [r["case"] for r in ok]
        ours = [r["case"].startswith("noiselab") for r in ok]
        lo = 10 ** math.floor(math.log10(min(v) * 0.7)) if v else 1.0
        hi = max(v) * 3.5 if v else 10.0
        ax.barh(range(len(bad), len(names)), [x - lo for x in v], left=lo,
                color=[_OURS if o else _PEER for o in ours], height=0.7)
        for i, (x, o) in enumerate(zip(v, ours)):
            ax.text(x * 1.08, len(bad) + i, _si(x, ""), va="center", ha="left", fontsize=8.5,
                    fontweight="bold" if o else "normal")
        for i in range(len(bad)):
            ax.text(lo * 1.1, i, "failed (see the table)", va="center", ha="left", fontsize=8.5, color="0.35")
        ax.set_yticks(range(len(names)), names, fontsize=8.5)
        for lab, name in zip(ax.get_yticklabels(), names):
            if name.startswith("noiselab"):
                lab.set_fontweight("bold")
        ax.set_ylim(-0.6, len(names) - 0.4)
        ax.set_xscale("log")
        ax.set_xlim(lo, hi)
        ax.set_title(g, loc="left")
        _log_ticks(ax.xaxis, unit="")
    axes[-1].set_xlabel("points per second (longer is faster)")
    fig.legend([Patch(color=_OURS), Patch(color=_PEER)], ["noiselab", "peer"], loc="outside upper right",
               ncols=2)
    renderer = _freeze(fig)
    for ax in axes:
        _fit_title(ax.title, fig.bbox, renderer, 110)
    return _finish(fig, renderer)


def lab_figures(results):
    """Draw the laboratory's figures from a results dict; returns {name: matplotlib Figure}.

    Parameters
    ----------
    results : dict
        A run's tables (:func:`noiselab.lab.run.run_all`'s return, or
        :func:`read_results` of its ``results.json``). Figures whose tables
        are missing (the peers of a run without them) are left out.

    Returns
    -------
    dict
        Figure name (a key of :data:`FIGURE_FILES`) -> drawn figure.

    Examples
    --------
    >>> figs = lab_figures({"sweeps": [{"name": "demo", "threshold": 0.1, "knee": "b", "points": [
    ...     {"setting": "a", "time_s": 1e-3, "error": 0.5}, {"setting": "b", "time_s": 2e-3, "error": 0.05}]}]})
    >>> sorted(figs)
    ['pareto']
    """
    import matplotlib

    figs = {}
    with matplotlib.rc_context(_STYLE):
        if results.get("texture"):
            figs["texture"] = plot_texture(results["texture"])
        if results.get("snow"):
            figs["snow"] = plot_snow(results["snow"])
        if results.get("scaling") and results.get("flakes") is not None:
            figs["scaling"] = plot_scaling(results["scaling"], results["flakes"], results.get("texture_scaling"))
        if results.get("sweeps"):
            figs["pareto"] = plot_pareto(results["sweeps"])
        if isinstance(results.get("peers"), list) and results["peers"]:
            figs["peers"] = plot_peers(results["peers"])
    return figs


def write_figures(results, folder):
    """Draw the laboratory's figures from ``results`` and write them as PNG files into ``folder``.

    Parameters
    ----------
    results : dict
        As for :func:`lab_figures`.
    folder : str or Path
        An existing folder (a run's ``results/``); the files are named by
        :data:`FIGURE_FILES`.

    Returns
    -------
    list of Path
        The files written.

    Examples
    --------
    >>> import tempfile
    >>> run = {"sweeps": [{"name": "demo", "threshold": 0.1, "knee": None,
    ...                    "points": [{"setting": "a", "time_s": 1e-3, "error": 0.5}]}]}
    >>> with tempfile.TemporaryDirectory() as d:
    ...     [p.name for p in write_figures(run, d)]
    ['pareto.png']
    """
    from ..io import atomic_output

    folder = Path(folder)
    written = []
    for name, fig in lab_figures(results).items():
        path = folder / FIGURE_FILES[name]
        with atomic_output(path) as tmp:
            fig.savefig(tmp, dpi=DPI, format="png")
        written.append(path)
    return written
