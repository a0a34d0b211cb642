"""Build the noiselab gallery: the seed papers' figures, reproduced and measured.

Usage (both do the same thing, from any folder)::

    noiselab gallery [--out out/gallery] [--only GROUP] [--quick] [--force]
    python3 -m noiselab.gallery [same options]

Every registered figure is built into ``OUT/<group>/<name>/`` together with a
``manifest.json`` that records its content hash (figure function source +
parameters + noiselab version and source of the modules it uses). A figure
whose hash matches and whose files are all there is not rebuilt. Each figure
folder is written atomically (temporary folder, then rename), and so are the
pages: ``OUT/index.html`` (the seed papers' figures, each paper opening with
an introduction and a schematic) and ``OUT/lab.html`` (the lab's comparisons
and the derivatives). Nothing is downloaded: everything drawn is computed or
ships with a package (the snow backgrounds are drawn in code,
:mod:`noiselab.gallery.scenes`).
"""
import argparse
import json
import os
import sys
import time
import traceback
from pathlib import Path

import numpy as np

from noiselab._core import progress
from noiselab.io import atomic_output

from .html import render_pages
from .registry import content_hash, specs

DEFAULT_OUT = Path("out") / "gallery"   # under the current folder, never the package's
MANIFEST = "manifest.json"


def _manifest_path(out: Path, spec) -> Path:
    return out / spec.group / spec.name / MANIFEST


def read_manifest(out: Path, spec):
    """The manifest of a built figure, or None."""
    try:
        return json.loads(_manifest_path(out, spec).read_text())
    except (OSError, ValueError):
        return None


def is_up_to_date(out: Path, spec, quick: bool) -> bool:
    man = read_manifest(out, spec)
    if not man or man.get("error") or man.get("hash") != content_hash(spec, quick):
        return False
    return all((out / f).is_file() for f in man["files"])


def build_figure(out: Path, spec, quick: bool) -> dict:
    """Build one figure into ``out/group/name`` (atomically) and return its manifest."""
    folder = out / spec.group / spec.name
    folder.parent.mkdir(parents=True, exist_ok=True)
    params = spec.parameters(quick)
    man = {"key": spec.key, "source": spec.source, "title": spec.title, "params": params,
           "quick": quick, "hash": content_hash(spec, quick)}
    t0 = time.perf_counter()
    try:
        with atomic_output(folder, directory=True) as tmp:
            result = spec.func(Path(tmp), **params)
            files = []
            for f in result.files:
                f = Path(f)
                f = f if f.is_absolute() else Path(tmp) / f
                if not f.is_file():
                    raise FileNotFoundError(f"figure {spec.key} says it wrote {f.name} but did not")
                files.append((folder / f.relative_to(tmp)).relative_to(out).as_posix())
            if not files:
                raise ValueError(f"figure {spec.key} wrote no files")
            man.update(files=files, caption=result.caption, measured=_plain(result.measured),
                       seconds=time.perf_counter() - t0)
            (Path(tmp) / MANIFEST).write_text(json.dumps(man, indent=1))
    except Exception as exc:  # one broken figure must not stop the gallery
        man.update(files=[], caption="", measured={}, seconds=time.perf_counter() - t0,
                   error=f"{type(exc).__name__}: {exc}", traceback=traceback.format_exc())
        folder.mkdir(parents=True, exist_ok=True)
        with atomic_output(folder / MANIFEST) as tmp:
            Path(tmp).write_text(json.dumps(man, indent=1))
    return man


def _plain(measured):
    """Measured values as JSON-friendly Python numbers/strings/lists."""
    def conv(v):
        if hasattr(v, "tolist"):
            return v.tolist()
        if isinstance(v, (list, tuple)):
            return [conv(x) for x in v]
        return v
    return {str(k): conv(v) for k, v in measured.items()}


def _thumbnail(out: Path, spec, man) -> None:
    """Write the contents grid's thumbnail of a built figure (its first video's poster or first still), if out of date."""
    from PIL import Image

    from .html import IMAGE_EXT, THUMB_WIDTH, VIDEO_EXT, poster_of, thumbnail_of

    files = [out / f for f in man["files"]]
    posters = [poster_of(f) for f in files if f.suffix.lower() in VIDEO_EXT and poster_of(f) in files]
    stills = [f for f in files if f.suffix.lower() in IMAGE_EXT and f not in posters]
    # the first video's poster or the first still, whichever holds more (compresses to more bytes): a snowy
    # frame rather than its clean background, a page of trajectories rather than a first frame with one dot
    images = sorted(posters[:1] + stills[:1], key=lambda f: -f.stat().st_size)
    if not images:
        return
    source, thumb = images[0], out / thumbnail_of(spec)
    if thumb.is_file() and thumb.stat().st_mtime_ns >= source.stat().st_mtime_ns:
        return
    thumb.parent.mkdir(parents=True, exist_ok=True)
    with Image.open(source) as im:
        im = im.convert("RGBA" if im.mode in ("RGBA", "LA", "P") else "RGB")
        im.thumbnail((THUMB_WIDTH, THUMB_WIDTH), Image.LANCZOS)
        with atomic_output(thumb) as tmp:
            im.save(tmp, format="PNG", optimize=True)


def write_index(out: Path, *, summary="") -> Path:
    """Write ``out/index.html`` and ``out/lab.html`` (atomically) from every registered figure's manifest; return the first.

    Also writes the thumbnails of the pages' contents grids (``out/thumbs/``). ``summary`` is accepted for
    older callers and not shown: the build's log goes to the terminal, not onto the page.
    """
    entries = []
    for spec in specs():
        man = read_manifest(out, spec)
        if man and not man.get("error") and not all((out / f).is_file() for f in man["files"]):
            man = None
        if man and not man.get("error"):
            man["stale"] = man.get("hash") != content_hash(spec, bool(man.get("quick")))
            if spec.name != "intro":
                _thumbnail(out, spec, man)
        entries.append((spec, man))
    for name, page in render_pages(out, entries).items():
        with atomic_output(out / name) as tmp:
            Path(tmp).write_text(page, encoding="utf-8")
    return out / "index.html"


def build(out=DEFAULT_OUT, *, only=None, quick=False, force=False, show_progress=None, log=None):
    """Build the gallery (or the group ``only``) into ``out`` and write ``out/index.html``.

    Returns a dict with ``index`` (path), ``built``, ``skipped`` and ``failed``
    (lists of figure keys) and ``seconds``.
    """
    chosen = specs(only)   # first, so a bad --only creates nothing
    out = Path(out).resolve()   # figure functions get absolute folders, whatever the working directory
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    built, skipped, failed = [], [], []
    bar = progress(chosen, total=len(chosen), desc="gallery", enabled=show_progress, unit="figure")
    for spec in bar:
        if hasattr(bar, "set_postfix_str"):
            bar.set_postfix_str(spec.key)
        if not force and is_up_to_date(out, spec, quick):
            skipped.append(spec.key)
            continue
        man = build_figure(out, spec, quick)
        if man.get("error"):
            failed.append(spec.key)
            if log:
                log(f"gallery: {spec.key} failed: {man['error']}")
        else:
            built.append(spec.key)
    seconds = time.perf_counter() - t0
    index = write_index(out)
    if not quick:
        publish_readme_picture(out, log=log)
    return {"index": index, "built": built, "skipped": skipped, "failed": failed, "seconds": seconds}


README_PICTURE = "readme/picture"                       # the figure drawn as the README's picture
README_PICTURE_PATH = Path("docs") / "_static" / "noiselab.png"   # where the README shows it, in a checkout


def same_picture(a, b, *, block=4, tol=2.0) -> bool:
    """Whether two images show the same picture: same size, and their ``block`` x ``block`` means differ by
    under ``tol`` grey levels on average.

    Another machine's renderer or FFT changes a few low bits, and the 256-colour dithering spreads them into
    a different pattern of pixels; neither is a new picture, so the checkout's copy is left alone.
    """
    from PIL import Image

    with Image.open(a) as ia, Image.open(b) as ib:
        x, y = np.asarray(ia.convert("RGB"), float), np.asarray(ib.convert("RGB"), float)
    if x.shape != y.shape:
        return False
    h, w = (x.shape[0] // block) * block, (x.shape[1] // block) * block

    def means(z):
        return z[:h, :w].reshape(h // block, block, w // block, block, 3).mean(axis=(1, 3))

    return bool(np.abs(means(x) - means(y)).mean() < tol)


def publish_readme_picture(out, *, checkout=None, log=None):
    """Copy the README's picture from a full-size build into a checkout's ``docs/_static/noiselab.png``.

    ``checkout`` defaults to the folder that holds the ``noiselab`` package when that folder is a
    checkout (it has ``README.md`` and ``docs/_static/``); an installed noiselab has none, and nothing is
    written. A quick build never publishes (its picture is small), and a copy that shows the same picture
    (:func:`same_picture`) is left as it is. Returns the path of the checkout's picture, or None.
    """
    from .registry import _ROOT

    root = Path(checkout) if checkout is not None else _ROOT
    target = root / README_PICTURE_PATH
    if not (root / "README.md").is_file() or not target.parent.is_dir():
        return None
    spec = specs(README_PICTURE)[0]
    man = read_manifest(Path(out), spec)
    if not man or man.get("error") or man.get("quick") or not man.get("files"):
        return None
    source = Path(out) / man["files"][0]
    if target.is_file() and (target.read_bytes() == source.read_bytes() or same_picture(target, source)):
        return target
    with atomic_output(target) as tmp:
        Path(tmp).write_bytes(source.read_bytes())
    if log:
        log(f"gallery: the README's picture {target} rewritten from {source}")
    return target


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--out", "-o", default=str(DEFAULT_OUT), help="output folder (default: %(default)s)")
    parser.add_argument("--only", action="append", metavar="NAME",
                        help="build only this figure group (or one figure, GROUP/NAME); repeatable")
    parser.add_argument("--quick", action="store_true", help="small, fast versions of every figure (for tests)")
    parser.add_argument("--force", action="store_true", help="rebuild figures even if they are up to date")
    parser.add_argument("--list", action="store_true", help="list the figure groups and figures, then exit")
    parser.add_argument("--check", action="store_true",
                        help="then open index.html and lab.html in headless Chromium (1280 px wide) and report missing files, "
                             "console errors, labels under 11 px and images shown twice")
    parser.add_argument("--progress", dest="show_progress", action="store_true", default=None,
                        help="always show the progress bar (default: only on a terminal)")
    parser.add_argument("--no-progress", dest="show_progress", action="store_false", help="never show the progress bar")


def run(args) -> int:
    if args.list:
        for spec in specs(args.only):
            print(f"{spec.key:32s} {spec.source}: {spec.title}")
        return 0
    report = build(args.out, only=args.only, quick=args.quick, force=args.force,
                   show_progress=args.show_progress, log=lambda m: print(m, file=sys.stderr))
    index = Path(report["index"]).resolve()
    print(f"gallery: {len(report['built'])} built, {len(report['skipped'])} up to date, "
          f"{len(report['failed'])} failed in {report['seconds']:.1f} s")
    print(f"gallery: open {index}")
    status = 1 if report["failed"] else 0
    if getattr(args, "check", False):
        status = check(index.parent) or status
    return status


def check(out, *, pages=("index.html", "lab.html"), width=None, min_px=None, echo=print) -> int:
    """Open the built pages in headless Chromium and report what a reader would trip over; return 1 if anything.

    Reports console errors, images that did not load, videos that cannot play, labels seen smaller than
    ``min_px`` CSS px in a ``width`` px wide window (:func:`noiselab.gallery.checks.small_labels`), and
    images shown more than once in another file (identical bytes or pixels, across both pages; the
    contents grid's thumbnails excepted).
    """
    from .browser import check_page
    from .checks import CHECK_WIDTH, MIN_TEXT_PX, duplicate_images, small_labels

    out = Path(out)
    width = CHECK_WIDTH if width is None else width
    min_px = MIN_TEXT_PX if min_px is None else min_px
    status, shown = 0, []
    for name in pages:
        page = check_page(out / name, width=width)
        bad = ([e for e in page["console_errors"]] + [f"image {i['src']} did not load" for i in page["images"] if not i["ok"]]
               + [f"video {v['src']} cannot play" for v in page["videos"] if v["error"] is not None or v["ready"] < 2])
        bad += [f"image {src}: labels {px:.1f} px at {width} px width (under {min_px:g})"
                for src, px in small_labels(page["images"], out, min_px=min_px)]
        shown += [out / i["src"] for i in page["images"] if i["ok"] and not i["src"].startswith("thumbs/")]
        shown += [out / v["poster"] for v in page["videos"] if v.get("poster")]
        for line in bad:
            echo(f"gallery: check: {name}: {line}", file=sys.stderr)
        echo(f"gallery: check {name} in {page['browser']}: {len(page['images'])} images, "
             f"{len(page['videos'])} videos, {len(bad)} problems")
        status = status or (1 if bad else 0)
    dups = duplicate_images(p for p in shown if p.is_file())
    for reason, group in dups:
        echo(f"gallery: check: the same image twice ({reason}): "
             + ", ".join(p.relative_to(out).as_posix() for p in group), file=sys.stderr)
    echo(f"gallery: check: {len(dups)} duplicate images among {len(set(shown))} shown")
    return status or (1 if dups else 0)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m noiselab.gallery", description=__doc__.split("\n\n")[0])
    add_arguments(parser)
    args = parser.parse_args(argv)
    try:
        return run(args)
    except (ValueError, TypeError, FileNotFoundError, MemoryError) as exc:
        print(f"gallery: error: {exc}", file=sys.stderr)
        return 2
