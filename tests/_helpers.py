"""Small measuring helpers shared by several test modules (not tests themselves)."""
import numpy as np
import scipy.fft

#: the README's two set-up commands, in order (the main job; the test suite, which ``.ci/run`` runs verbatim)
SETUP_COMMANDS = ("./install.sh && .venv/bin/noiselab gallery",
                  "./install.sh test && .venv/bin/python -m pytest -n auto --dist loadfile")


def phase_correlation_shift(a, b):
    """Integer shift (dx, dy) taking image ``a`` to image ``b``, by phase correlation (x right, y down)."""
    X = scipy.fft.rfft2(b) * np.conj(scipy.fft.rfft2(a))
    X /= np.abs(X) + 1e-30
    r = scipy.fft.irfft2(X, s=a.shape)
    iy, ix = np.unravel_index(np.argmax(r), r.shape)
    H, W = r.shape
    return int((ix + W // 2) % W - W // 2), int((iy + H // 2) % H - H // 2)


def yx(kw):
    """``kw`` with its ``direction``/``pan``/``velocity`` pairs, in (x, y) order as the envelopes and the slow
    references take them, turned into the public API's array-order keywords (``direction_yx=(dy, dx)``, ...)."""
    out = dict(kw)
    for old in ("direction", "pan", "velocity"):
        if old in out:
            value = out.pop(old)
            out[f"{old}_yx"] = (value[1], value[0])
    return out
