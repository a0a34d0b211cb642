"""The gallery's ``index.html``: every figure with its caption, every video playable.

The page is static and self-contained (no network, no scripts from elsewhere).
A small inline script checks, once the page has loaded, that every image
decoded and every video can play, and writes the result into
``<body data-check=...>`` and a status line, so a reader (or a headless
browser in the tests) sees at once whether anything is missing.
"""
from __future__ import annotations

import html
import os
from pathlib import Path

IMAGE_EXT = {".png", ".gif", ".jpg", ".jpeg", ".svg", ".webp"}
VIDEO_EXT = {".mp4", ".webm"}

_CSS = """
body { font-family: system-ui, sans-serif; margin: 0 auto; max-width: 1200px; padding: 1em 2em; color: #222; background: #fafafa; }
h1 { margin-bottom: 0.2em; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
nav a { margin-right: 1em; }
figure { background: #fff; border: 1px solid #ddd; border-radius: 6px; margin: 1.5em 0; padding: 1em; }
figure h3 { margin: 0 0 0.5em 0; font-size: 1.05em; }
.media { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
.media img, .media video { max-width: 100%; height: auto; border: 1px solid #eee; }
.media video { max-width: 560px; display: block; }
.media a.shot { display: block; max-width: 100%; }
.clip { font-size: 0.8em; } .clip a.full { color: #555; }
.toc { columns: 2; font-size: 0.9em; } .toc ol { margin: 0.2em 0 0.6em 0; } .toc li { break-inside: avoid; }
a.anchor { font-size: 0.75em; font-weight: normal; color: #999; text-decoration: none; margin-left: 0.4em; }
.hint { font-size: 0.9em; color: #555; }
code { background: #f0f0f0; padding: 0 0.25em; border-radius: 3px; }
figcaption { margin-top: 0.6em; line-height: 1.4; }
.seed { font-weight: 600; }
.params, .measured { font-family: ui-monospace, monospace; font-size: 0.85em; color: #444; }
.failed { border-color: #c33; } .failed figcaption { color: #a00; }
.missing { color: #888; font-style: italic; }
#status { font-size: 0.9em; color: #555; }
"""

_SCRIPT = """
(function () {
  function done(report) {
    document.body.setAttribute('data-check', JSON.stringify(report));
    var s = document.getElementById('status');
    if (s) { s.textContent = report.bad.length ? ('Problems: ' + report.bad.join(', '))
                                               : ('All ' + report.images + ' images and ' + report.videos + ' videos loaded.'); }
  }
  window.addEventListener('load', function () {
    var bad = [], imgs = document.querySelectorAll('img'), vids = document.querySelectorAll('video');
    imgs.forEach(function (im) { if (!im.complete || im.naturalWidth === 0) bad.push(im.getAttribute('src')); });
    var pending = vids.length;
    var report = {images: imgs.length, videos: vids.length, bad: bad};
    if (!pending) { done(report); return; }
    vids.forEach(function (v) {
      var src = v.querySelector('source') ? v.querySelector('source').getAttribute('src') : v.getAttribute('src');
      var settled = false;
      function settle(ok) { if (settled) return; settled = true; if (!ok) bad.push(src); if (--pending === 0) done(report); }
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


def _media(files, root):
    """HTML for a figure's files: images (each a link to itself at full size), videos with their poster, links."""
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
            attr = f' poster="{html.escape(_rel(poster, root), quote=True)}"' if poster in files else ""
            mime = "video/mp4" if ext == ".mp4" else "video/webm"
            parts.append(f'<div class="clip"><video controls loop muted autoplay playsinline preload="auto"{attr}>'
                         f'<source src="{src}" type="{mime}"></video>'
                         f'<a class="full" href="{src}" target="_blank">{html.escape(f.name)}: open full size</a></div>')
        elif ext in IMAGE_EXT:
            if f in posters or (ext == ".gif" and f.with_suffix("") in stems_with_video):
                continue  # shown as the video's poster
            parts.append(f'<a class="shot" href="{src}" target="_blank" title="open {html.escape(f.name)} at full size">'
                         f'<img src="{src}" alt="{html.escape(f.name)}" loading="eager"></a>')
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


def render_index(root: Path, entries, *, title="noiselab gallery", summary="") -> str:
    """Return the HTML of the index page.

    ``entries`` is a list of ``(spec, manifest_or_None)`` in display order;
    ``manifest`` holds ``files`` (relative to ``root``), ``caption``,
    ``measured``, ``params``, ``error``.
    """
    groups = []
    for spec, man in entries:
        if spec.group not in groups:
            groups.append(spec.group)
    toc = []
    for g in groups:
        items = "".join(f'<li><a href="#{html.escape(spec.key.replace("/", "-"))}">{html.escape(spec.seed)}: '
                        f'{html.escape(spec.title)}</a></li>' for spec, _ in entries if spec.group == g)
        toc.append(f'<li><a href="#{html.escape(g)}">{html.escape(g)}</a><ol>{items}</ol></li>')
    body = [f"<h1>{html.escape(title)}</h1>",
            f"<p>{html.escape(summary)}</p>" if summary else "",
            '<p id="status">Checking that every file loads…</p>',
            '<p class="hint">Click an image to open it at full size. Every caption ends with the parameters and the '
            'command that rebuilds that figure alone.</p>',
            '<nav id="contents"><h2>Contents</h2><ol class="toc">' + "".join(toc) + "</ol></nav>"]
    for g in groups:
        body.append(f'<h2 id="{html.escape(g)}">{html.escape(g)}</h2>')
        for spec, man in entries:
            if spec.group != g:
                continue
            anchor = html.escape(spec.key.replace("/", "-"))
            head = (f'<h3>{html.escape(spec.title)} <a class="anchor" href="#{anchor}" title="link to this figure">#</a>'
                    f' <a class="anchor" href="#contents" title="back to the contents">contents</a></h3>')
            seed = f'<span class="seed">{html.escape(spec.seed)}.</span> '
            if man is None:
                body.append(f'<figure id="{anchor}">{head}<figcaption>{seed}'
                            f'<span class="missing">Not built yet (build without --only).</span></figcaption></figure>')
                continue
            if man.get("error"):
                body.append(f'<figure id="{anchor}" class="failed">{head}<figcaption>{seed}'
                            f'Failed to build: {html.escape(man["error"])}</figcaption></figure>')
                continue
            files = [root / f for f in man["files"]]
            cap = [seed, html.escape(man["caption"])]
            cap.append(f'<br><span class="params">Parameters: {html.escape(format_params(man["params"]))}</span>')
            if man.get("measured"):
                cap.append(f'<br><span class="measured">Measured: {html.escape(format_measured(man["measured"]))}</span>')
            cap.append(f'<br><span class="params">Rebuild alone: <code>{html.escape(rebuild_command(spec))}</code></span>')
            cap.append(f'<br><span class="params">Built in {man.get("seconds", 0):.1f} s'
                       f'{" (quick sizes)" if man.get("quick") else ""}.</span>')
            if man.get("stale"):
                cap.append('<br><span class="missing">Out of date: its code, parameters or the noiselab modules it '
                           'uses changed since; build again to refresh it.</span>')
            body.append(f'<figure id="{anchor}">{head}{_media(files, root)}<figcaption>{"".join(cap)}</figcaption></figure>')
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{html.escape(title)}</title>"
            '<link rel="icon" href="data:,">'
            f"<style>{_CSS}</style></head>\n<body>\n" + "\n".join(b for b in body if b)
            + f"\n<script>{_SCRIPT}</script>\n</body></html>\n")
