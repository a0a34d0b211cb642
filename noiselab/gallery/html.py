"""The gallery's pages, ``index.html`` and ``lab.html``: every figure with its caption, every video playable.

The pages are static and self-contained (no network, no scripts from elsewhere;
the references' links point out). ``index.html`` opens with what noiselab is,
the README's picture and the references; each page then has a grid of
thumbnails, one per figure, and its sections (Zhang's figures in the thesis's
order, :func:`reading_order`).
Each figure is a card: its seed figure and title as the heading, the media,
one line on what to look for, the measured caption, and a ``<details>``
block with the parameters, the measured numbers and the rebuild command.
Videos do not autoplay and load nothing until played (``preload="none"``,
with a poster): an IntersectionObserver plays those on screen.
A small inline script checks, once the page has loaded, that every image
decoded (and, when the page is opened with ``?check``, that every video
loads and can play), and writes the result into
``<body data-check=...>`` and a status line, so a reader (or a headless
browser in the tests) sees at once whether anything is missing.
"""
from __future__ import annotations

import html
import os
import re
from pathlib import Path

IMAGE_EXT = {".png", ".gif", ".jpg", ".jpeg", ".svg", ".webp"}
VIDEO_EXT = {".mp4", ".webm"}

_CSS = """
body { font-family: system-ui, sans-serif; margin: 0 auto; max-width: 1400px; padding: 1em 2em; color: #222; background: #fafafa; font-size: 16px; }
h1 { margin-bottom: 0.2em; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
.intro { background: #fff; border-left: 4px solid #7a9cc6; padding: 0.6em 1.2em; margin: 1em 0 1.5em 0; }
.intro p { line-height: 1.5; max-width: 60em; }
.intro img { max-width: 100%; height: auto; }
figure { background: #fff; border: 1px solid #ddd; border-radius: 6px; margin: 1.5em 0; padding: 1em; }
figure h3 { margin: 0 0 0.5em 0; font-size: 1.1em; }
.media { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
.media img, .media video { max-width: 100%; height: auto; border: 1px solid #eee; }
.media .pixelated { image-rendering: pixelated; }
.media a.shot { display: block; max-width: 100%; }
.clip { font-size: 0.85em; } .clip a.full { color: #555; }
.lead { font-size: 1.1em; line-height: 1.5; max-width: 60em; }
.refs ol { line-height: 1.5; } .refs h2 { margin-top: 1em; }
#contents h3 { margin: 1em 0 0.4em 0; font-size: 1.05em; }
.grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(150px, 1fr)); gap: 0.6em; }
.grid a.tile { display: block; background: #fff; border: 1px solid #ddd; border-radius: 4px; padding: 4px;
               text-decoration: none; color: #1d4e89; font-size: 0.85em; text-align: center; }
.grid a.tile:hover { border-color: #7a9cc6; }
.grid img.thumb { display: block; width: 100%; height: 110px; object-fit: contain; background: #f4f4f4; margin-bottom: 3px; }
.grid .nothumb { display: block; height: 110px; line-height: 110px; color: #999; background: #f4f4f4; }
a.anchor { font-size: 0.75em; font-weight: normal; color: #999; text-decoration: none; margin-left: 0.4em; }
code { background: #f0f0f0; padding: 0 0.25em; border-radius: 3px; }
figcaption { margin-top: 0.6em; line-height: 1.45; }
figcaption p { margin: 0.4em 0; }
.look { font-weight: 600; color: #1d4e89; }
details { margin-top: 0.5em; color: #444; } summary { cursor: pointer; color: #555; }
.params, .measured { font-family: ui-monospace, monospace; font-size: 0.85em; color: #444; }
.failed { border-color: #c33; } .failed figcaption { color: #a00; }
.missing { color: #888; font-style: italic; }
footer { margin-top: 3em; border-top: 1px solid #ccc; padding-top: 0.5em; font-size: 0.9em; color: #555; }
"""

_SCRIPT = """
(function () {
  function done(report) {
    document.body.setAttribute('data-check', JSON.stringify(report));
    var s = document.getElementById('status');
    if (s) { s.textContent = report.bad.length ? ('Problems: ' + report.bad.join(', '))
                                               : ('All ' + report.images + ' images loaded' + (report.videosChecked
                                                  ? ' and all ' + report.videos + ' videos play.' : '; ' + report.videos + ' videos load when played.')); }
  }
  // videos play only while at least half of them is on screen (never all at once)
  if ('IntersectionObserver' in window) {
    var io = new IntersectionObserver(function (entries) {
      entries.forEach(function (e) {
        var v = e.target;
        if (e.isIntersecting) { var p = v.play(); if (p && p.catch) p.catch(function () {}); } else { v.pause(); }
      });
    }, {threshold: 0.5});
    document.querySelectorAll('video').forEach(function (v) { io.observe(v); });
  }
  window.addEventListener('load', function () {
    var bad = [], imgs = document.querySelectorAll('img'), vids = document.querySelectorAll('video');
    imgs.forEach(function (im) { if (!im.complete || im.naturalWidth === 0) bad.push(im.getAttribute('src')); });
    // a reader's page loads no video until it is played (preload="none"); opened with ?check, every video is
    // loaded and must reach its first frame (the headless check in noiselab/gallery/browser.py does that)
    var checkVideos = /[?&]check(=|&|$)/.test(window.location.search);
    var pending = checkVideos ? vids.length : 0;
    var report = {images: imgs.length, videos: vids.length, bad: bad, videosChecked: checkVideos};
    if (!pending) { done(report); return; }
    vids.forEach(function (v) {
      var src = v.querySelector('source') ? v.querySelector('source').getAttribute('src') : v.getAttribute('src');
      var settled = false;
      function settle(ok) { if (settled) return; settled = true; if (!ok) bad.push(src); if (--pending === 0) done(report); }
      v.preload = 'auto';
      if (v.readyState >= 2) { settle(true); return; }
      v.addEventListener('loadeddata', function () { settle(true); });
      v.addEventListener('error', function () { settle(false); }, true);
      var s = v.querySelector('source'); if (s) s.addEventListener('error', function () { settle(false); });
      v.load();
    });
  });
})();
"""


def _rel(path: Path, root: Path) -> str:
    return Path(os.path.relpath(path, root)).as_posix()


def poster_of(video: Path) -> Path:
    """The still shown before a video plays: ``stem_poster.png`` beside ``stem.mp4``."""
    return video.with_name(video.stem + "_poster.png")


def _png_size(path: Path):
    """(width, height) of a PNG from its header, or None."""
    try:
        with open(path, "rb") as f:
            head = f.read(24)
    except OSError:
        return None
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


SMALL = 256   # px: smaller images (tiles) are shown enlarged by a whole factor, nearest neighbour


def _enlarged(png: Path) -> str:
    """Attributes that show a PNG narrower than ``SMALL`` (or a video with such a poster) enlarged by a whole factor."""
    size = _png_size(png) if png.suffix.lower() == ".png" else None
    if size and 0 < size[0] < SMALL:
        k = -(-SMALL // size[0])
        return f' class="pixelated" width="{size[0] * k}" height="{size[1] * k}"'
    return ""


def _image(f: Path, root: Path) -> str:
    src = html.escape(_rel(f, root), quote=True)
    attr = _enlarged(f)
    return (f'<a class="shot" href="{src}" target="_blank" title="open {html.escape(f.name)} at full size">'
            f'<img src="{src}" alt="{html.escape(f.name)}"{attr} loading="eager"></a>')


def _media(files, root):
    """HTML for a figure's files: images (each a link to itself at full size), videos with their poster, links.

    Each image is shown once: a video's poster is its still, never a second image beside it. Videos do not
    autoplay; the page's script plays the ones on screen.
    """
    files = [Path(f) for f in files]
    videos = [f for f in files if f.suffix.lower() in VIDEO_EXT]
    stems_with_video = {f.with_suffix("") for f in videos}
    posters = {poster_of(v) for v in videos}
    parts = []
    for f in files:
        src = html.escape(_rel(f, root), quote=True)
        ext = f.suffix.lower()
        if ext in VIDEO_EXT:
            poster = poster_of(f)
            attr = ""
            if poster in files:   # a small video is enlarged like a small image, so a still beside it matches it
                attr = f' poster="{html.escape(_rel(poster, root), quote=True)}"' + _enlarged(poster)
            mime = "video/mp4" if ext == ".mp4" else "video/webm"
            parts.append(f'<div class="clip"><video controls loop muted playsinline preload="none"{attr}>'
                         f'<source src="{src}" type="{mime}"></video>'
                         f'<br><a class="full" href="{src}" target="_blank">{html.escape(f.name)}: open full size</a></div>')
        elif ext in IMAGE_EXT:
            if f in posters or (ext == ".gif" and f.with_suffix("") in stems_with_video):
                continue  # shown as the video's poster
            parts.append(_image(f, root))
    links = [f'<a href="{html.escape(_rel(f, root), quote=True)}">{html.escape(f.name)}</a>'
             for f in files if f.suffix.lower() not in IMAGE_EXT | VIDEO_EXT]
    out = '<div class="media">' + "".join(parts) + "</div>"
    if links:
        out += '<div class="files">Files: ' + ", ".join(links) + "</div>"
    return out


def rebuild_command(spec) -> str:
    """The command that rebuilds one figure alone."""
    return f"python3 -m noiselab gallery --only {spec.key}"


def format_params(params: dict) -> str:
    return ", ".join(f"{k}={v!r}" if isinstance(v, str) else f"{k}={v}" for k, v in params.items())


def format_measured(measured: dict) -> str:
    def fmt(v):
        if isinstance(v, float):
            return f"{v:.4g}"
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(fmt(x) for x in v) + "]"
        return str(v)

    return "; ".join(f"{k} = {fmt(v)}" for k, v in measured.items())


# the two pages: the seed papers' reproductions, then the lab's own figures; a group not named here goes on the
# first page, after the named ones
PAGES = {"index.html": ("readme", "snow", "stimuli", "phillips"), "lab.html": ("lab", "derivatives")}
PAGE_TITLES = {"index.html": "noiselab gallery: the seed papers' figures, reproduced and measured",
               "lab.html": "noiselab lab: comparisons and derivatives"}
# how each page names the other one, in a sentence of its own
PAGE_SUBJECTS = {"index.html": "The seed papers' figures, reproduced and measured,",
                 "lab.html": "The lab's comparisons and derivatives"}
# groups shown inside another group's section (Zhang's transparency stimuli belong with the rest of the thesis)
SECTION_OF = {"stimuli": "snow"}
GROUP_TITLES = {"snow": "Falling snow and perceptual transparency (Langer & Zhang 2003; Zhang 2003)",
                "phillips": "Noisy stimuli (Phillips 2004)",
                "stimuli": "Transparency stimuli (Zhang 2003, Chapter 5)",
                "lab": "The lab's comparisons", "derivatives": "Derivatives of lattice noise"}
INTROS = {
    "snow": "Langer and Zhang render falling snow without particles. A near flake looks bigger and moves faster than "
            "a far one, so in the Fourier domain a flake's size (its spatial frequency) fixes its speed: all the "
            "energy of falling snow lies on one surface, the tent. The method fills the tent with random phases and "
            "a 1/f amplitude inside a band of spatial frequencies, takes one inverse 3-D FFT, and uses the result as "
            "the opacity of white snow over a picture. Every component is periodic, so the snow tiles in space and "
            "loops in time. The figures follow the thesis: Chapter 3 (the method, tiling), Chapter 4 (a panning "
            "camera), Chapter 5 (the transparency displays it reviews, rendered in cd/m² on a stated display) and "
            "Chapter 6 (the same snow as a stimulus for perceptual transparency).",
    "phillips": "Phillips builds psychophysical stimuli from lattice noise: random numbers at the integer points of "
                "a lattice, found through a permutation table and smoothed by a kernel. The input can be 1-D (time: "
                "a trajectory), 2-D (a texture, a height field) or 3-D (a solid, or 2-D over time), the output a "
                "scalar or a vector (flow fields, colours). Summing octaves gives fractal sums (Eq. 9) and turbulence "
                "(Eq. 10); displacing a mesh along its normals by noise gives the noisy spheres and the cow (Eq. 11).",
    "lab": "The lab's own comparisons, with no seed figure: spectral synthesis against lattice noise, every "
           "smoothing kernel, quality measures from the literature, and the hash question, all measured with the "
           "same instruments.",
    "derivatives": "Exact derivatives of lattice noise: curl noise, domain warping, and surface normals from the "
                   "gradient rather than from the mesh.",
}
INTRO = "intro"   # a figure of this name is drawn in its group's introduction, not as a card
FRONT = "readme"  # the group whose figures open index.html under the statement (the README's picture), not as cards

# what the gallery is, and the documents it reproduces (shown at the top of index.html)
STATEMENT = ("noiselab is a Python laboratory for procedural noise: spectral synthesis (falling snow from one inverse "
             "FFT, motion clouds, 1/f textures) and lattice noise (value and gradient noise, fractal sums, "
             "turbulence, noisy curves, surfaces and meshes), with the instruments that measure what was made "
             "(spectra, speeds, contrasts in cd/m²). This page rebuilds the figures of the documents below with "
             "noiselab; every caption says what was measured on the figure it sits under.")
REFERENCES = (
    ("M. S. Langer and L. Zhang. Rendering falling snow using an inverse Fourier transform. "
     "ACM SIGGRAPH 2003 Sketches & Applications, San Diego, 2003.",
     "https://dl.acm.org/action/doSearch?AllField=Rendering+falling+snow+using+an+inverse+Fourier+transform",
     "ACM Digital Library"),
    ("L. Zhang. Rendering falling snow using an inverse Fourier transform. M.Sc. thesis, School of Computer "
     "Science, McGill University, Montreal, August 2003 (supervisor M. S. Langer).",
     "https://escholarship.mcgill.ca/catalog?q=Rendering+falling+snow+using+an+inverse+Fourier+transform",
     "McGill eScholarship"),
    ("F. Phillips. Creating noisy stimuli. Perception 33(7), 837-854, 2004.",
     "https://doi.org/10.1068/p5141", "doi:10.1068/p5141"),
)

THUMBS = "thumbs"   # folder of the contents grid's thumbnails, under the output folder
THUMB_WIDTH = 200   # px


def thumbnail_of(spec) -> str:
    """Path, relative to the output folder, of a figure's thumbnail in the contents grid."""
    return f"{THUMBS}/{spec.group}-{spec.name}.png"


def _section(group: str) -> str:
    return SECTION_OF.get(group, group)


_NUMBER = re.compile(r"(?:Fig|Sec)\.\s*(\d+)(?:\.(\d+))?")


def reading_order(spec) -> tuple:
    """Where a card stands in its section: by the first figure (or section) number its source names.

    ``"Zhang 2003, Fig. 5.4"`` -> (5, 4, 0); ``"... (Sec. 3.5 I)"`` -> (3, 5, 1), after Fig. 3.5; a source
    with no number keeps its registration order after the numbered ones.
    """
    m = _NUMBER.search(spec.source)
    if not m:
        return (10 ** 6, 0, 0)
    return (int(m.group(1)), int(m.group(2) or 0), 1 if m.group(0).startswith("Sec") else 0)


def short_label(spec) -> str:
    """The grid's label of a figure: its figure number (``Zhang Fig. 3.1``), or its title's first words."""
    m = re.search(r"^([A-Z][A-Za-z&. ]*?)\s+\d{4},\s*(Fig\.\s*[\d.]+)", spec.source)
    if m:
        return f"{m.group(1).split()[0]} {m.group(2)}"
    m = re.search(r"^([A-Z]\w*) \d{4}, video\b.*?(Sec\.\s*[\d.]+)", spec.source)
    if m:
        return f"{m.group(1)} {m.group(2)}, video"
    words = spec.title.split()
    return " ".join(words[:4]) + ("…" if len(words) > 4 else "")


def page_of(group: str) -> str:
    """The page a group's figures appear on."""
    for page, groups in PAGES.items():
        if group in groups:
            return page
    return "index.html"


def _card(spec, man, root):
    anchor = html.escape(spec.key.replace("/", "-"))
    head = (f'<h3>{html.escape(spec.source)}: {html.escape(spec.title)} '
            f'<a class="anchor" href="#{anchor}" title="link to this figure">#</a>'
            f' <a class="anchor" href="#contents" title="back to the contents">contents</a></h3>')
    if man is None:
        return (f'<figure id="{anchor}">{head}<figcaption>'
                f'<span class="missing">Not built yet (build without --only).</span></figcaption></figure>')
    if man.get("error"):
        return (f'<figure id="{anchor}" class="failed">{head}<figcaption>'
                f'Failed to build: {html.escape(man["error"])}</figcaption></figure>')
    files = [root / f for f in man["files"]]
    cap = []
    if spec.look:
        cap.append(f'<p class="look">What to look for: {html.escape(spec.look)}.</p>')
    cap.append(f'<p>{html.escape(man["caption"])}</p>')
    if man.get("stale"):
        cap.append('<p class="missing">Out of date: its code, parameters or the noiselab modules it uses changed '
                   'since; build again to refresh it.</p>')
    more = [f'<p class="params">Parameters: {html.escape(format_params(man["params"]))}</p>']
    if man.get("measured"):
        more.append(f'<p class="measured">Measured: {html.escape(format_measured(man["measured"]))}</p>')
    more.append(f'<p class="params">Rebuild alone: <code>{html.escape(rebuild_command(spec))}</code></p>')
    more.append(f'<p class="params">Built in {man.get("seconds", 0):.1f} s{" (quick sizes)" if man.get("quick") else ""}.</p>')
    cap.append("<details><summary>Parameters, measured numbers, rebuild command</summary>" + "".join(more) + "</details>")
    return f'<figure id="{anchor}">{head}{_media(files, root)}<figcaption>{"".join(cap)}</figcaption></figure>'


def _intro(group, entries, root):
    parts = [f'<div class="intro"><p>{html.escape(INTROS[group])}</p>' if group in INTROS else '<div class="intro">']
    for spec, man in entries:
        if spec.group == group and spec.name == INTRO and man and not man.get("error"):
            parts.append(_media([root / f for f in man["files"]], root))
            parts.append(f'<p>{html.escape(man["caption"])}</p>')
    return "".join(parts) + "</div>"


def _grid(sections, entries, root):
    """The contents: per section, a grid of thumbnails, each a link to its figure's card."""
    parts = []
    for g, cards in sections:
        tiles = []
        for spec, man in cards:
            anchor = html.escape(spec.key.replace("/", "-"))
            thumb = thumbnail_of(spec)
            img = (f'<img class="thumb" src="{html.escape(thumb, quote=True)}" alt="">'
                   if (root / thumb).is_file() else '<span class="nothumb">not built</span>')
            tiles.append(f'<a class="tile" href="#{anchor}" title="{html.escape(spec.source)}: '
                         f'{html.escape(spec.title)}">{img}<span>{html.escape(short_label(spec))}</span></a>')
        parts.append(f'<h3><a href="#{html.escape(g)}">{html.escape(GROUP_TITLES.get(g, g))}</a></h3>'
                     f'<div class="grid">{"".join(tiles)}</div>')
    return '<nav id="contents"><h2>Contents</h2>' + "".join(parts) + "</nav>"


def _front(spec, man, root):
    """The README's picture under the page's opening statement (its caption below it, no card of its own)."""
    if not man or man.get("error"):
        return ""
    return (f'<div class="front" id="{html.escape(spec.key.replace("/", "-"))}">' + _media([root / f for f in man["files"]], root)
            + f'<p>{html.escape(man["caption"])}</p></div>')


def _references():
    items = "".join(f'<li>{html.escape(text)} <a href="{html.escape(url, quote=True)}">{html.escape(label)}</a></li>'
                    for text, url, label in REFERENCES)
    return f'<div class="refs"><h2 id="references">The documents reproduced</h2><ol>{items}</ol></div>'


def render_pages(root: Path, entries, *, summary="") -> dict:
    """Return ``{file name: HTML}`` for the gallery's pages (``index.html``, ``lab.html``).

    ``entries`` is a list of ``(spec, manifest_or_None)`` in registration order;
    ``manifest`` holds ``files`` (relative to ``root``), ``caption``,
    ``measured``, ``params``, ``error``. ``index.html`` opens with what
    noiselab is and the full references of the documents it reproduces;
    each page then shows a grid of thumbnails (``thumbs/``, see
    :func:`thumbnail_of`) that jump to the figures, and one section per paper
    (Zhang's figures in the thesis's order, :func:`reading_order`) with its
    introduction and schematic (the figure named ``intro``). ``summary`` is
    accepted for older callers and not shown: a page holds no build log.
    """
    pages = {}
    for page, title in PAGE_TITLES.items():
        groups = []
        for spec, _ in entries:
            g = _section(spec.group)
            if page_of(spec.group) == page and g not in groups and g != FRONT:
                groups.append(g)
        order = list(PAGES[page])
        groups.sort(key=lambda g: order.index(g) if g in order else len(order))
        sections = []
        for g in groups:
            cards = [(spec, man) for spec, man in entries if _section(spec.group) == g and spec.name != INTRO]
            if page == "index.html":   # the papers' figures in their order; the lab's in registration order
                cards.sort(key=lambda e: reading_order(e[0]))   # stable: registration order within a number
            sections.append((g, cards))
        other = [p for p in PAGE_TITLES if p != page][0]
        body = [f"<h1>{html.escape(title)}</h1>"]
        if page == "index.html":
            body.append(f'<p class="lead">{html.escape(STATEMENT)}</p>')
            body += [_front(spec, man, root) for spec, man in entries if spec.group == FRONT]
            body.append(_references())
        body.append(f'<p>Click a thumbnail to jump to its figure, an image to open it at full size; a video loads '
                    f'when you play it, and plays while on screen. {html.escape(PAGE_SUBJECTS[other])} are on '
                    f'<a href="{other}">a page of their own</a>.</p>')
        body.append(_grid(sections, entries, root))
        for g, cards in sections:
            body.append(f'<h2 id="{html.escape(g)}">{html.escape(GROUP_TITLES.get(g, g))}</h2>')
            body.append(_intro(g, entries, root))
            body += [_card(spec, man, root) for spec, man in cards]
        body.append('<footer><p id="status">Checking that every file loads…</p></footer>')
        pages[page] = ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                       '<meta name="viewport" content="width=device-width, initial-scale=1">'
                       f"<title>{html.escape(title)}</title>"
                       '<link rel="icon" href="data:,">'
                       f"<style>{_CSS}</style></head>\n<body>\n" + "\n".join(b for b in body if b)
                       + f"\n<script>{_SCRIPT}</script>\n</body></html>\n")
    return pages


def render_index(root: Path, entries, *, title=None, summary="") -> str:
    """The HTML of ``index.html`` alone (the seed papers' page); see :func:`render_pages`."""
    return render_pages(root, entries)["index.html"]
