"""The laboratory's figures: redrawn from a results dict alone (no measuring), and legible.

Legible, as drawn by matplotlib (text boxes from ``get_window_extent`` after
``canvas.draw()``): no two tick labels of a panel touch, no two numbered
point labels overlap and each stays inside its panel, every text lies inside
the figure at 8 points or more, and the figures are at most 1000 pixels wide
(the width a Markdown page shows without shrinking them). Checked on a small
synthetic run built to crowd them (a cluster of points, axes spanning less
than a decade and many decades, long names, a failed peer) and on the
published ``benchmarks/results/results.json``.
"""
from __future__ import annotations

import doctest
import importlib.util
import itertools
import json
import struct
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from matplotlib.text import Text  # noqa: E402

from noiselab.lab import figures as F  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
PUBLISHED = ROOT / "benchmarks" / "results" / "results.json"


def synthetic_results():
    """A small run's tables, shaped like ``run_all``'s, with crowded points and long names."""
    f = np.geomspace(1.0, 128.0, 16)
    texture = []
    for dim in (2, 3):
        for method, family, tilt in (("spectral (IFFT)", "spectral", 0.0), ("value noise, cubic", "lattice", 0.3),
                                     ("gradient noise, quintic", "lattice", -0.2)):
            power = f ** -dim * np.exp(tilt * np.sin(f))
            if family == "spectral":
                power = np.where(f < 4, 0.0, power)
            texture.append({"dim": dim, "method": method, "family": family,
                            "_spectrum": {"f": f.tolist(), "power": power.tolist()}})
    fb = np.geomspace(19.0, 110.0, 6)             # less than a decade
    snow = [{"method": m, "_curve": {"f": fb.tolist(), "speed": (k * 80 / fb).tolist(), "law": (80 / fb).tolist()}}
            for m, k in (("tent IFFT (noiselab.snow)", 1.0), ("particles (Reeves)", 0.8))]
    scaling = [{"method": m, "size": s, "voxels": 16 * s * s, "time_s": k * 1e-7 * s * s}
               for m, k in (("tent IFFT (noiselab.snow)", 1.0), ("layered lattice (8 layers)", 3.0))
               for s in (128, 256, 512, 1024)]
    flakes = [{"flakes": n, "time_s": 2e-6 * n} for n in (1000, 10_000, 100_000)]
    tex_scaling = [{"method": "spectral (IFFT)", "size": s, "voxels": s * s, "time_s": 1e-8 * s * s}
                   for s in (128, 256, 512)]
    cluster = [{"setting": f"crowded setting number {i}", "time_s": 2e-3 * (1 + 0.03 * i),
                "error": 2.0 * (1 + 0.04 * (i % 3))} for i in range(8)]
    far = [{"setting": "far and slow", "time_s": 6e-2, "error": 0.3},
           {"setting": "cheap and right", "time_s": 1.9e-3, "error": 0.08}]
    narrow = [{"setting": f"{k} octaves", "time_s": 1e-3 * (1 + 0.3 * k), "error": 0.5 ** k} for k in range(1, 7)]
    narrow.append({"setting": "all octaves", "time_s": 3.2e-3, "error": 1e-17})     # exact
    sweeps = [
        {"name": "three families, crowded in one corner", "threshold": 1.0, "knee": "cheap and right",
         "points": cluster + far},
        {"name": "octaves: a sweep whose name runs well past the width of its panel when set on one line",
         "threshold": 0.01, "knee": "6 octaves", "points": narrow},
        {"name": "precision", "threshold": 2e-3, "knee": "float32",
         "points": [{"setting": "float32", "time_s": 6.8e-3, "error": 2e-7},
                    {"setting": "float64", "time_s": 9.1e-3, "error": 1e-17}]},
    ]
    peers = [{"group": "lattice 6 octaves 512x512 (8 base cells, gain 1/2), a long scene name for the title",
              "case": c, "status": "ok", "points_per_s": v}
             for c, v in (("noiselab (gradient, quintic, float64)", 1.05e8),
                          ("pyfastnoisesimd (value, np.product shim)", 1.19e8), ("perlin-numpy", 1.4e6),
                          ("noise (pnoise2, per point)", 4.3e6))]
    peers.append({"group": peers[0]["group"], "case": "VTK vtkPerlinNoise (pyvista)", "status": "failed",
                  "error": "no module"})
    peers += [{"group": "1/f image 512x512", "case": c, "status": "ok", "points_per_s": v}
              for c, v in (("noiselab spectral_noise", 1.4e8), ("powerbox", 3.0e7), ("stimupy one_over_f", 1.8e7))]
    return {"texture": texture, "snow": snow, "scaling": scaling, "flakes": flakes, "texture_scaling": tex_scaling,
            "sweeps": sweeps, "peers": peers}


def _sources():
    out = [pytest.param(synthetic_results, id="synthetic")]
    out.append(pytest.param(lambda: F.read_results(PUBLISHED), id="published",
                            marks=pytest.mark.skipif(not PUBLISHED.exists(), reason="no published results.json")))
    return out


@pytest.fixture(scope="module", params=_sources())
def drawn(request):
    results = request.param()
    return results, F.lab_figures(results)


def _renderer(fig):
    fig.canvas.draw()
    return fig.canvas.get_renderer()


def _overlap(a, b):
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def _tick_labels(axis, renderer):
    lo, hi = sorted(axis.get_view_interval())
    boxes = []
    for tick in axis.get_major_ticks() + axis.get_minor_ticks():
        lab = tick.label1
        loc = tick.get_loc()
        if loc is None or not lab.get_visible() or not lab.get_text() or not lo * (1 - 1e-9) <= loc <= hi * (1 + 1e-9):
            continue
        boxes.append((lab.get_text(), lab.get_window_extent(renderer)))
    return boxes


def test_every_figure_is_drawn(drawn):
    results, figs = drawn
    expected = {"texture", "snow", "scaling", "pareto"} | ({"peers"} if isinstance(results.get("peers"), list) else set())
    assert set(figs) == expected


def test_no_two_tick_labels_touch(drawn):
    _, figs = drawn
    for name, fig in figs.items():
        renderer = _renderer(fig)
        for ax in fig.get_axes():
            if not ax.axison:
                continue
            boxes = _tick_labels(ax.xaxis, renderer) + _tick_labels(ax.yaxis, renderer)
            for (ta, a), (tb, b) in itertools.combinations(boxes, 2):
                assert not _overlap(a, b), f"{name}, panel {ax.get_title()!r}: tick labels {ta!r} and {tb!r} overlap"
            for axis in (ax.xaxis, ax.yaxis):
                if axis.get_scale() == "log":   # every log axis keeps at least two labelled ticks
                    assert len(_tick_labels(axis, renderer)) >= 2, f"{name}: a log axis without two tick labels"


def test_point_labels_apart_and_inside_their_panel(drawn):
    results, figs = drawn
    fig = figs["pareto"]
    renderer = _renderer(fig)
    panels = [ax for ax in fig.get_axes() if ax.axison]
    assert len(panels) == len(results["sweeps"])
    for ax, sweep in zip(panels, results["sweeps"]):
        labels = [t for t in ax.texts if t.get_gid() == "point-label"]
        assert sorted(int(t.get_text()) for t in labels) == list(range(1, len(sweep["points"]) + 1))
        for t in labels:
            t.update_positions(renderer)
        boxes = [(t.get_text(), Text.get_window_extent(t, renderer)) for t in labels]
        frame = ax.get_window_extent(renderer)
        for text, b in boxes:
            assert frame.x0 <= b.x0 and b.x1 <= frame.x1 and frame.y0 <= b.y0 and b.y1 <= frame.y1, \
                f"point label {text} of {sweep['name']!r} leaves its panel"
        for (ta, a), (tb, b) in itertools.combinations(boxes, 2):
            assert not _overlap(a, b), f"{sweep['name']!r}: point labels {ta} and {tb} overlap"


def test_every_text_inside_the_figure_and_readable(drawn):
    _, figs = drawn
    for name, fig in figs.items():
        renderer = _renderer(fig)
        assert fig.bbox.width <= 1000, f"{name} is {fig.bbox.width:.0f} px wide"
        box = fig.bbox
        texts = [t for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip()]
        assert texts
        for t in texts:
            if t.get_gid() == "point-label":
                t.update_positions(renderer)
                b = Text.get_window_extent(t, renderer)
            else:
                b = t.get_window_extent(renderer)
            assert b.x0 >= box.x0 - 1 and b.x1 <= box.x1 + 1 and b.y0 >= box.y0 - 1 and b.y1 <= box.y1 + 1, \
                f"{name}: {t.get_text()[:40]!r} runs off the figure"
            assert t.get_fontsize() >= 8, f"{name}: {t.get_text()[:40]!r} at {t.get_fontsize()} pt"


def test_an_axis_short_of_a_decade_has_plain_numbers_with_units():
    figs = F.lab_figures({"sweeps": synthetic_results()["sweeps"][1:2]})
    fig = figs["pareto"]
    renderer = _renderer(fig)
    ax = next(a for a in fig.get_axes() if a.axison)
    labels = [t for t, _ in _tick_labels(ax.xaxis, renderer)]
    assert len(labels) >= 2 and all(t.endswith(" ms") for t in labels), labels


def test_replot_writes_every_figure_from_results_json(tmp_path):
    """``benchmarks/lab_run.py --replot`` redraws the PNGs of a run folder from its results.json alone."""
    results = synthetic_results()
    res_dir = tmp_path / "results"
    res_dir.mkdir()
    (res_dir / "results.json").write_text(json.dumps(results))
    spec = importlib.util.spec_from_file_location("lab_run", ROOT / "benchmarks" / "lab_run.py")
    lab_run = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(lab_run)
    assert lab_run.main(["--replot", "--output", str(tmp_path)]) == 0
    for name in F.FIGURE_FILES.values():
        data = (res_dir / name).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n", name
        width, height = struct.unpack(">II", data[16:24])
        assert 300 <= width <= 1000 and height >= 200, (name, width, height)
    assert lab_run.main(["--replot", "--output", str(tmp_path / "nowhere")]) == 2


def test_replot_refuses_a_corrupt_results_file_in_one_line(tmp_path, capsys):
    # not JSON, or JSON that is not an object: one line on stderr naming the file, status 2, no traceback, and
    # the figures already there untouched
    spec = importlib.util.spec_from_file_location("lab_run", ROOT / "benchmarks" / "lab_run.py")
    lab_run = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(lab_run)
    res_dir = tmp_path / "results"
    res_dir.mkdir()
    (res_dir / "pareto.png").write_bytes(b"earlier")
    for text, why in (("{bad", "not JSON"), ("[1, 2]", "a JSON list"), (b"\xff\xfe", "not JSON")):
        (res_dir / "results.json").write_bytes(text if isinstance(text, bytes) else text.encode())
        assert lab_run.main(["--replot", "--output", str(tmp_path)]) == 2
        err = capsys.readouterr().err.strip()
        assert err.count("\n") == 0 and why in err and "results.json" in err, err
        assert (res_dir / "pareto.png").read_bytes() == b"earlier"


def test_docstring_examples_run():
    result = doctest.testmod(F, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0
