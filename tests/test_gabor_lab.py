"""The lab's third family (sparse Gabor rows) and a published report that states the version that made it."""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np
from packaging.version import Version

import noiselab
from noiselab.lab.experiments import Config, texture_experiment
from noiselab.lab.run import render_markdown

ROOT = Path(__file__).resolve().parents[1]


def stated_version(text):
    """The version a report says made it: its "Made by noiselab X" line, else the run table's noiselab column."""
    m = re.search(r"^Made by noiselab ([0-9][^\s]*?)\.?$", text, flags=re.M)
    if m:
        return Version(m.group(1))
    lines = text.splitlines()
    for i, line in enumerate(lines):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if "noiselab" in cells and i + 2 < len(lines):
            row = [c.strip() for c in lines[i + 2].strip().strip("|").split("|")]
            return Version(row[cells.index("noiselab")])
    raise AssertionError("the report states no noiselab version")


def test_the_published_report_is_not_older_than_the_package():
    """benchmarks/RESULTS.md must come from this version or a newer one: regenerate it with lab_run.py --publish."""
    stated = stated_version((ROOT / "benchmarks" / "RESULTS.md").read_text())
    assert stated >= Version(noiselab.__version__), (
        f"benchmarks/RESULTS.md was made by noiselab {stated}, older than {noiselab.__version__}: run "
        "`python3 benchmarks/lab_run.py --publish`")


def test_stated_version_reads_the_line_and_the_table():
    assert stated_version("# r\n\nMade by noiselab 0.3.0.\n") == Version("0.3.0")
    table = "| date | noiselab | numpy |\n| --- | --- | --- |\n| today | 0.1.0 | 2.4 |\n"
    assert stated_version(table) == Version("0.1.0") < Version("0.2.0")


def test_quick_texture_rows_hold_the_gabor_family():
    rows = texture_experiment(Config.quick_config(), dims=(2,))
    gabor = [r for r in rows if r["family"] == "gabor"]
    assert len(gabor) == 1
    g = gabor[0]
    for k in ("time_s", "slope_error", "anisotropy", "band_leakage", "peak_mib"):
        assert np.isfinite(g[k])
    lattice = [r for r in rows if r["family"] == "lattice"]
    # its spectrum is the spectral field's, blurred: a slope error far under the worst lattice sum's
    assert abs(g["slope_error"]) < max(abs(r["slope_error"]) for r in lattice)


def test_the_three_families_sweep_holds_every_family():
    from noiselab.lab.experiments import sweep_families

    sweep = sweep_families(Config.quick_config())
    names = [p["setting"] for p in sweep["points"]]
    assert "spectral (IFFT)" in names and any(n.startswith("value noise") for n in names)
    gabor = [p for p in sweep["points"] if p["setting"].startswith("sparse Gabor")]
    assert len(gabor) == 4 and all(p["time_s"] > 0 and np.isfinite(p["error"]) for p in gabor)
    assert [p["setting"] for p in gabor] == [f"sparse Gabor, {d} impulses/cell" for d in (1, 2, 4, 8)]
