"""What ``noiselab gallery --check`` looks for in the built images, besides what the browser reports.

Two detectors, each usable on its own:

* :func:`small_labels`: text that a reader sees smaller than ``min_px`` CSS pixels. A figure saved with
  :func:`noiselab.gallery._common.save_figure` records the size of its smallest text, in pixels of the PNG,
  in the PNG itself (a ``tEXt`` chunk, :data:`TEXT_PX_KEY`); the page shows the PNG at some width, so the
  text is seen at ``smallest * shown width / natural width``.
* :func:`duplicate_images`: images with identical bytes, or different bytes but identical pixels (the same
  frame saved twice, for instance a still beside the video whose poster it already is).

Examples
--------
>>> from noiselab.gallery.checks import shown_text_px
>>> shown_text_px(13.9, natural_width=1400, shown_width=1000)
9.928571428571429
"""
from __future__ import annotations

import hashlib
from pathlib import Path

__all__ = ["TEXT_PX_KEY", "MIN_TEXT_PX", "CHECK_WIDTH", "smallest_text_px", "shown_text_px", "small_labels",
           "duplicate_images"]

TEXT_PX_KEY = "noiselab:smallest-text-px"   # the PNG text key save_figure writes
MIN_TEXT_PX = 11.0    # CSS px: the smallest label a reader should have to read
CHECK_WIDTH = 1280    # CSS px: the window width the page is checked at


def smallest_text_px(path) -> float | None:
    """The smallest text in a PNG, in its own pixels, as recorded by ``save_figure``; None if not recorded."""
    from PIL import Image

    try:
        with Image.open(path) as im:
            value = getattr(im, "text", {}).get(TEXT_PX_KEY)
    except OSError:
        return None
    return float(value) if value else None


def shown_text_px(text_px: float, *, natural_width: float, shown_width: float) -> float:
    """Size of text of ``text_px`` image pixels when the image is drawn ``shown_width`` CSS px wide."""
    if natural_width <= 0:
        raise ValueError(f"natural_width must be > 0, got {natural_width}")
    return float(text_px) * float(shown_width) / float(natural_width)


def small_labels(images, root, *, min_px=MIN_TEXT_PX):
    """The images whose smallest text is seen below ``min_px`` CSS px.

    ``images`` are dicts as :func:`noiselab.gallery.browser.check_page` reports them (``src`` relative to
    ``root``, ``w`` the natural width, ``shown`` the width drawn on the page). Returns a list of
    ``(src, seen px)``, smallest first; images without a recorded text size are skipped.
    """
    found = []
    for im in images:
        if not im.get("w") or not im.get("shown"):
            continue
        px = smallest_text_px(Path(root) / im["src"])
        if px is None:
            continue
        seen = shown_text_px(px, natural_width=im["w"], shown_width=im["shown"])
        if seen < min_px:
            found.append((im["src"], round(seen, 2)))
    return sorted(found, key=lambda t: t[1])


def _pixel_digest(path):
    import numpy as np
    from PIL import Image

    with Image.open(path) as im:
        a = np.asarray(im.convert("RGBA"))
    return hashlib.sha256(repr(a.shape).encode() + a.tobytes()).hexdigest()


def duplicate_images(paths):
    """Groups of images that are the same picture: identical bytes, or identical decoded pixels.

    Returns a list of ``(reason, [paths])``, ``reason`` being ``"identical bytes"`` or ``"identical pixels"``;
    a file listed twice counts once.
    """
    paths = list(dict.fromkeys(Path(p) for p in paths))
    groups = []
    by_bytes, by_pixels = {}, {}
    for p in paths:
        by_bytes.setdefault(hashlib.sha256(p.read_bytes()).hexdigest(), []).append(p)
    for same in by_bytes.values():
        if len(same) > 1:
            groups.append(("identical bytes", same))
    for same in by_bytes.values():   # one representative per byte group: pixels compared across groups only
        by_pixels.setdefault(_pixel_digest(same[0]), []).append(same)
    for bunch in by_pixels.values():
        if len(bunch) > 1:
            groups.append(("identical pixels", [p for same in bunch for p in same]))
    return groups
