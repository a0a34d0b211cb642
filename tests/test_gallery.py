"""The gallery: every figure builds (quick sizes), index.html opens in real headless Chromium with
no missing file and no console error, up-to-date figures are not rebuilt, --only builds one group."""
import html.parser
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import noiselab.gallery.build as build_mod
from noiselab.gallery import browser, registry

ROOT = Path(__file__).resolve().parents[1]


class _Refs(html.parser.HTMLParser):
    """Collect every src/href, the figures and their captions from index.html."""

    def __init__(self):
        super().__init__()
        self.refs, self.figures, self.videos, self._fig, self._in_caption = [], [], [], None, False
        self.posters, self.images, self.links, self.toc, self._href, self._in_toc = [], [], {}, [], None, False
        self._in_head, self._in_look, self.autoplay = False, False, []
        self.thumbs, self.sections, self.preload = [], [], []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        for key in ("src", "href", "poster"):   # files of the gallery (the references' links go out)
            if a.get(key) and not a[key].startswith(("data:", "#", "https://")):
                self.refs.append(a[key])
        if tag == "nav" and a.get("id") == "contents":
            self._in_toc = True
        if tag == "a":
            self._href = a.get("href")
            if self._in_toc and self._href and self._href.startswith("#"):
                self.toc.append(self._href[1:])
        if tag == "img" and "thumb" in (a.get("class") or ""):
            self.thumbs.append((a.get("src"), self._href))
        elif tag == "img":
            self.images.append(a.get("src"))
            if self._href:
                self.links[a.get("src")] = self._href
        if tag == "h2" and a.get("id"):
            self.sections.append(a["id"])
        if tag == "video" and a.get("poster"):
            self.posters.append(a["poster"])
        if tag == "video":
            self.autoplay.append("autoplay" in a)
            self.preload.append(a.get("preload"))
        if tag == "h3" and self._fig is not None:
            self._in_head = True
        if tag == "p" and "look" in (a.get("class") or "") and self._fig is not None:
            self._in_look = True
        if tag == "figure":
            self._fig = {"id": a.get("id"), "class": a.get("class", ""), "caption": "", "srcs": [], "head": "", "look": ""}
            self.figures.append(self._fig)
        if tag in ("img", "source") and self._fig is not None:
            self._fig["srcs"].append(a.get("src"))
        if tag == "source":
            self.videos.append(a.get("src"))
        if tag == "figcaption":
            self._in_caption = True

    def handle_endtag(self, tag):
        if tag == "h3":
            self._in_head = False
        if tag == "p":
            self._in_look = False
        if tag == "a":
            self._href = None
        if tag == "nav":
            self._in_toc = False
        if tag == "figcaption":
            self._in_caption = False
        if tag == "figure":
            self._fig = None

    def handle_data(self, data):
        if self._in_caption and self._fig is not None:
            self._fig["caption"] += data
        if self._in_head and self._fig is not None:
            self._fig["head"] += data
        if self._in_look and self._fig is not None:
            self._fig["look"] += data


def _parse(index):
    p = _Refs()
    p.feed(Path(index).read_text(encoding="utf-8"))
    return p


PAGES = ("index.html", "lab.html")


def _parse_all(out):
    """Both pages, read as one (the seed papers' page, then the lab's)."""
    p = _Refs()
    for name in PAGES:
        p.feed(Path(out, name).read_text(encoding="utf-8"))
    return p


def _cards():
    """The figures shown as cards: every registered one but the paper introductions' schematics and the README's picture."""
    return [s for s in registry.specs() if s.name != "intro" and s.group != "readme"]


@pytest.fixture(scope="module")
def quick_gallery(tmp_path_factory):
    """The whole gallery at quick sizes, built once through the command line."""
    work = tmp_path_factory.mktemp("work")
    # a relative --out, from another working directory, as a user types it
    proc = subprocess.run([sys.executable, "-m", "noiselab", "gallery", "--quick", "--no-progress", "--out", "out/gallery"],
                          capture_output=True, text=True, cwd=work, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return work / "out" / "gallery", proc.stdout


def test_build_prints_where_index_is(quick_gallery):
    out, stdout = quick_gallery
    index = (out / "index.html").resolve()
    assert index.is_file()
    assert f"open {index}" in stdout
    assert "0 failed" in stdout


def test_every_figure_is_on_the_page_and_every_referenced_file_exists(quick_gallery):
    out, _ = quick_gallery
    page = _parse_all(out)
    ids = [f["id"] for f in page.figures]
    assert sorted(ids) == sorted(s.key.replace("/", "-") for s in _cards())
    # the lab's and the derivatives' figures are on a page of their own
    lab = _parse(out / "lab.html")
    assert {f["id"].split("-")[0] for f in lab.figures} == {"lab", "derivatives"}
    assert not [f for f in _parse(out / "index.html").figures if f["id"].split("-")[0] in ("lab", "derivatives")]
    # no image is shown twice (a video's poster is its still, never a second image beside it)
    shown = page.images + page.posters
    assert len(shown) == len(set(shown)), [i for i in shown if shown.count(i) > 1]
    # no video autoplays: the page's script plays the ones on screen; none loads before it is played
    assert page.autoplay and not any(page.autoplay)
    assert page.preload and set(page.preload) == {"none"}
    assert "IntersectionObserver" in (out / "index.html").read_text()
    assert not [f["id"] for f in page.figures if "failed" in f["class"]]
    assert all(f["srcs"] for f in page.figures), "a figure without an image or a video"
    assert page.refs
    missing = [r for r in page.refs if not (out / r).is_file()]
    assert not missing, missing
    # every video is an MP4 shown with a full-resolution poster still (no subsampled GIF preview, which aliases)
    assert page.videos and all(v.endswith(".mp4") for v in page.videos)
    assert len(page.posters) == len(page.videos)
    assert all(p == v[:-4] + "_poster.png" for p, v in zip(page.posters, page.videos))
    assert not [r for r in page.refs if r.endswith(".gif")]
    # every image is a link to itself (click to open it at full size)
    assert page.images and all(page.links.get(i) == i for i in page.images), page.images[:3]
    # nothing escapes the output folder (no absolute paths, no ..)
    assert all(not r.startswith("/") and ".." not in Path(r).parts for r in page.refs)


SEED_FIGURES = (["Zhang 2003, Fig. " + f for f in ("3.1", "3.2", "3.3", "3.4", "3.5", "4.1", "5.1", "5.2", "5.3", "5.4",
                                                  "5.5", "6.1", "6.2", "6.3")]
                + [f"Phillips 2004, Fig. {n}:" for n in range(1, 21)])


def test_captions_carry_seed_figure_parameters_and_measurements(quick_gallery):
    out, _ = quick_gallery
    page = _parse_all(out)
    captions = {f["id"]: " ".join(f["caption"].split()) for f in page.figures}
    heads = {f["id"]: " ".join(f["head"].split()) for f in page.figures}
    looks = {f["id"]: " ".join(f["look"].split()) for f in page.figures}
    every = " | ".join(heads.values())
    for seed in SEED_FIGURES:   # every figure of the seed documents is reproduced, named in a heading
        assert seed in every, seed
    for spec in _cards():
        key = spec.key.replace("/", "-")
        # the heading carries the figure number and the title; one line says what to look for
        assert heads[key].startswith(f"{spec.source}: {spec.title}"), (spec.key, heads[key][:80])
        if spec.group in ("snow", "phillips", "lab", "derivatives"):   # (a group added later may have none yet)
            assert spec.look, spec.key
        assert looks[key] == (f"What to look for: {spec.look}." if spec.look else ""), spec.key
        cap = captions[key]
        assert "Parameters: " in cap and "Measured: " in cap, spec.key
        for name in spec.params:
            assert f"{name}=" in cap, (spec.key, name)
        assert f"Rebuild alone: python3 -m noiselab gallery --only {spec.key}" in cap, spec.key
    # the parameters, measured numbers and rebuild command are folded away (one <details> per figure)
    text = (out / "index.html").read_text()
    assert text.count("<details>") == len([s for s in _cards() if s.group not in ("lab", "derivatives")])
    # the snow captions carry the snow measurements, the noise captions the noise ones
    snow = " ".join(c for k, c in captions.items() if k.startswith("snow-"))
    assert "energy on the tent" in snow and "speed per band" in snow and "loop seam" in snow
    noise = " ".join(c for k, c in captions.items() if not k.startswith("snow-"))
    assert "range" in noise and "slope" in noise and "anisotropy" in noise


def test_each_paper_opens_with_an_introduction_and_its_schematic(quick_gallery):
    out, _ = quick_gallery
    text = (out / "index.html").read_text()
    for group, image in (("snow", "snow/intro/snow_method.png"), ("phillips", "phillips/intro/lattice_method.png")):
        section = text[text.index(f'<h2 id="{group}">'):]
        intro = section[:section.index("<figure")]
        assert 'class="intro"' in intro and image in intro and len(intro) > 400, group
    # no build log on the page (it goes to the terminal)
    for page in PAGES:
        assert not re.search(r"\d+ built|up to date,|Last build", (out / page).read_text()), page


def test_the_page_opens_with_what_noiselab_is_the_references_and_a_thumbnail_grid(quick_gallery):
    from noiselab.gallery import html as page_html

    out, _ = quick_gallery
    text = (out / "index.html").read_text()
    first_section = text.index('<h2 id="snow">')
    # the statement, then the full references with links, then the contents, all before the first section
    assert text.index("noiselab is a Python laboratory") < text.index("The documents reproduced") \
        < text.index('<nav id="contents">') < first_section
    refs = text[text.index("The documents reproduced"):text.index('<nav id="contents">')]
    for words in ("Langer and L. Zhang", "SIGGRAPH 2003", "M.Sc. thesis", "McGill University",
                  "Perception 33(7), 837-854, 2004", 'href="https://doi.org/10.1068/p5141"'):
        assert words in refs, words
    assert refs.count("<li>") == 3 and refs.count('href="https://') == 3
    # every card has one thumbnail in the grid, a file of its own that links to the card
    for name in PAGES:
        page = _parse(out / name)
        ids = [f["id"] for f in page.figures]
        assert [href[1:] for _, href in page.thumbs] == ids
        assert all((out / src).is_file() and src.startswith("thumbs/") for src, _ in page.thumbs)
        assert len({src for src, _ in page.thumbs}) == len(ids)
    assert page_html.short_label(registry.specs("snow/fig3_1")[0]) == "Zhang Fig. 3.1"


def test_zhangs_figures_are_one_section_in_the_thesis_order(quick_gallery):
    out, _ = quick_gallery
    page = _parse(out / "index.html")
    assert page.sections[:3] == ["references", "snow", "phillips"]   # (a group added later follows them)
    ids = [f["id"] for f in page.figures]
    zhang = [f["head"] for f in page.figures if f["head"].startswith("Zhang")]
    assert len(zhang) == len([i for i in ids if i.split("-")[0] in ("snow", "stimuli")])
    # one block, before Phillips, with the thesis's figure numbers in order
    first_p = ids.index("phillips-fig01")
    assert all(i.split("-")[0] in ("snow", "stimuli") for i in ids[:first_p])
    numbers = [tuple(int(x) for x in re.search(r"(?:Fig|Sec)\. (\d+)\.(\d+)", h).groups()) for h in zhang]
    assert numbers == sorted(numbers), numbers
    assert ids.index("snow-fig3_1") < ids.index("snow-opacity")   # the opacity video after the figures it explains
    # the lab's page keeps registration order within each section (its sources are not a paper's figure numbers);
    # a figure of the lab group registered by a later module (gabor) still stands in the lab's section
    lab = [f["id"] for f in _parse(out / "lab.html").figures]
    assert lab == [s.key.replace("/", "-") for g in ("lab", "derivatives") for s in _cards() if s.group == g]
    # Langer & Zhang's sketch has one figure: it is named where the thesis redraws it
    assert any("Langer & Zhang 2003, Fig. 1" in h for h in zhang)
    # no seed figure twice
    figs = [re.search(r"(?:Zhang|Phillips) 2003?4?, Fig\. [\d.]+", h) for h in (f["head"] for f in page.figures)]
    named = [m.group(0) for m in figs if m]
    assert len(named) == len(set(named)), [n for n in named if named.count(n) > 1]


def test_table_of_contents_links_every_figure(quick_gallery):
    out, _ = quick_gallery
    for name in PAGES:
        page = _parse(out / name)
        ids = [f["id"] for f in page.figures]
        sections = [s for s in page.sections if s not in ("references", "contents")]
        assert [t for t in page.toc if t not in sections] == ids
        assert set(sections) <= set(page.toc)


def test_measured_values_are_sane(quick_gallery):
    out, _ = quick_gallery
    man = {s.key: build_mod.read_manifest(out, s) for s in registry.specs()}
    assert man["snow/opacity"]["measured"]["energy on the tent"] > 0.5
    assert 0.8 < man["snow/opacity"]["measured"]["loop seam (1 = seamless)"] < 1.25
    contrast = man["snow/fig6_2"]["measured"]["disc: Michelson contrast veiled / clear"]
    assert 0.8 < contrast[1] <= 1.0 and 0.1 < contrast[0] < 0.2 < contrast[1]
    # Fig. 1: (a) alternates, and (b)-(d), the same basis filtered at F, hold their power below F
    fig01 = man["phillips/fig01"]["measured"]
    assert fig01["(a) alternates in sign at every integer"] is True
    assert fig01["(a) fraction of power below 0.05 cycle/unit"] < 0.1
    assert all(fig01[f"({t}) fraction of power below {F:g} cycle/unit"] > 0.99 for t, F in zip("bcd", (0.05, 0.1, 0.2)))
    # Fig. 6: the construction from planes of 1-D basis functions is noiselab's evaluator
    fig06 = man["phillips/fig06"]["measured"]
    assert fig06["derived value at {14, 1}"] == fig06["noiselab's value there"]
    assert [v for k, v in fig06.items() if k.startswith("largest |construction")][0] < 1e-12
    # Fig. 17: every sphere resolves its finest octave (>= 2 vertices per period along the longest edge)
    assert min(man["phillips/fig17"]["measured"]["samples per period of the finest octave (longest edge), n = 1.."]) >= 2
    # Fig. 19: "10 % of the radius, on average" is the RMS displacement
    assert man["phillips/fig19"]["measured"]["RMS displacement / radius"] == pytest.approx([0.0, 0.05, 0.1], abs=1e-9)
    # Fig. 18: the cow visibly crumples: RMS displacement grows with s, to a few percent of its length at s = 0.5
    crumple = man["phillips/fig18"]["measured"]["RMS displacement / body length per s"]
    assert crumple[0] == 0 and all(b > a for a, b in zip(crumple, crumple[1:])) and crumple[-1] > 0.02
    # Fig. 4.1 and Fig. 7 loop without a jump (the last-to-first step is an ordinary one)
    assert 0.5 < man["snow/fig4_1"]["measured"]["loop seam of the panning composite (1 = seamless)"] < 1.5
    assert 0.5 < man["phillips/fig07"]["measured"]["loop seam (1 = seamless)"] < 1.5
    # Fig. 18: the stand-in cow is closed, and the undisplaced one has no flipped face
    fig18 = man["phillips/fig18"]["measured"]
    assert fig18["watertight"] is True and fig18["flipped faces per s"][0] == 0
    assert man["phillips/fig02"]["measured"]["basis at the lattice points equals the table entries the permutation points to"] is True
    # Fig. 5.1: Metelli's equations recover the episcotister's open area and luminance from Talbot's mean
    fig51 = man["stimuli/fig5_1"]["measured"]
    assert fig51["alpha from Eq. 5.1 (set 0.4)"] == pytest.approx(0.4, abs=0.03)
    assert fig51["t from Eq. 5.2 (set 8 cd/m²)"] == pytest.approx(8.0, abs=1.0)
    # Fig. 5.2: target and match agree by Michelson contrast (Eq. 5.4), not by luminance range (Eq. 5.1)
    by_m = [float(v) for v in man["stimuli/fig5_2"]["measured"]["alpha by Eq. 5.4 (M_centre / M_surround), target / match"].split(" / ")]
    by_r = [float(v) for v in man["stimuli/fig5_2"]["measured"]["alpha by Eq. 5.1 (range ratio), target / match"].split(" / ")]
    assert abs(by_m[0] - by_m[1]) < 0.03 < abs(by_r[0] - by_r[1])
    # Fig. 5.3: (a) the surround has the lower contrast (alpha < 1), (b) with other means, the higher
    fig53 = man["stimuli/fig5_3"]["measured"]
    assert fig53["(a) M_surround / M_centre (the surround's alpha, Eq. 5.4)"] < 0.8
    assert fig53["(b) M_surround / M_centre (the surround's alpha, Eq. 5.4)"] > 1.2
    lo, hi = man["phillips/fig16"]["measured"]["displacement / amplitude range (within [-1, 1])"]
    assert -1 <= lo < 0 < hi <= 1


def test_index_opens_in_headless_chromium_without_errors(quick_gallery):
    out, _ = quick_gallery
    report = browser.check_page(out / "index.html", timeout=90)
    assert report["console_errors"] == [], report["console_errors"]
    assert report["images"] and all(i["ok"] for i in report["images"]), [i for i in report["images"] if not i["ok"]]
    assert report["videos"] and all(v["error"] is None and v["ready"] >= 2 and v["w"] > 0 for v in report["videos"]), \
        report["videos"]
    check = json.loads(report["check"])   # the page's own verdict
    assert check["bad"] == [] and check["images"] == len(report["images"]) and check["videos"] == len(report["videos"])


def test_chromium_check_catches_a_missing_file_and_a_console_error(tmp_path):
    (tmp_path / "page.html").write_text('<!DOCTYPE html><html><head><link rel="icon" href="data:,"></head><body>'
                                        '<img src="nowhere.png"><script>console.error("broken")</script></body></html>')
    report = browser.check_page(tmp_path / "page.html", timeout=60)
    assert any("broken" in e for e in report["console_errors"])
    assert any("nowhere.png" in e or "ERR_FILE_NOT_FOUND" in e for e in report["console_errors"])
    assert [{k: i[k] for k in ("src", "ok", "w")} for i in report["images"]] == [{"src": "nowhere.png", "ok": False, "w": 0}]


def _mtimes(folder):
    return {p: p.stat().st_mtime_ns for p in Path(folder).rglob("*") if p.is_file()}


def test_up_to_date_figures_are_not_rebuilt(tmp_path):
    first = build_mod.build(tmp_path, only="lab", quick=True, show_progress=False)
    lab = [s.key for s in registry.specs("lab")]
    assert first["built"] == lab and not first["failed"]
    before = _mtimes(tmp_path / "lab")
    time.sleep(0.05)
    second = build_mod.build(tmp_path, only="lab", quick=True, show_progress=False)
    assert second["built"] == [] and second["skipped"] == lab
    assert _mtimes(tmp_path / "lab") == before
    # a changed parameter set (full instead of quick) changes the hash, so it rebuilds
    spec = registry.specs("lab/one_over_f")[0]
    assert registry.content_hash(spec, quick=True) != registry.content_hash(spec, quick=False)
    # a deleted output file, or a manifest from another version, rebuilds that figure only
    man = build_mod.read_manifest(tmp_path, spec)
    (tmp_path / man["files"][0]).unlink()
    third = build_mod.build(tmp_path, only="lab", quick=True, show_progress=False)
    assert third["built"] == ["lab/one_over_f"] and third["skipped"] == [k for k in lab if k != "lab/one_over_f"]
    mpath = tmp_path / "lab" / "kernels" / "manifest.json"
    m = json.loads(mpath.read_text())
    m["hash"] = "0" * 64
    mpath.write_text(json.dumps(m))
    fourth = build_mod.build(tmp_path, only="lab", quick=True, show_progress=False)
    assert fourth["built"] == ["lab/kernels"]
    forced = build_mod.build(tmp_path, only="lab/kernels", quick=True, force=True, show_progress=False)
    assert forced["built"] == ["lab/kernels"]


def test_hash_follows_the_modules_a_figure_uses():
    spec = registry.specs("snow/opacity")[0]
    assert "noiselab.snowfall" in spec.uses
    v = registry.module_version("noiselab.snowfall")
    assert v != "missing" and v != registry.module_version("noiselab.lattice")
    assert registry.module_version("noiselab.no_such_module") == "missing"
    # a helper shared by several figures is part of each one's hash (so changing it rebuilds them)
    fig14 = registry.specs("phillips/fig14")[0]
    assert "_octave_surfaces" in registry.function_sources(fig14.func)
    assert "_tiling" in registry.function_sources(registry.specs("snow/fig3_4")[0].func)


def _direct_imports(spec):
    """The units (subpackages; gallery modules) that a figure's own code and helpers import or reach."""
    import ast
    import textwrap

    found = set()
    for source in registry.function_sources(spec.func).values():
        found |= registry._imported(ast.parse(textwrap.dedent(source)), spec.func.__module__, False)
    return {registry._unit(m) for m in found}


def test_the_modules_of_a_figure_are_read_from_its_code():
    """Every module a figure's code imports, and every module those import, enters its hash; ``uses`` agrees."""
    for spec in registry.specs():
        modules = set(registry.figure_modules(spec))
        direct = _direct_imports(spec) - {"noiselab.gallery.registry"}
        assert direct <= modules, (spec.key, direct - modules)
        assert {registry._unit(u) for u in spec.uses} <= modules, spec.key
        # the hand list names every subpackage the figure calls (a wrong list is caught here)
        named = {registry._unit(u) for u in spec.uses}
        missing = {u for u in direct if not u.startswith("noiselab.gallery")} - named
        assert not missing, f"{spec.key}: uses= lacks {sorted(missing)}"
    curl = registry.specs("derivatives/curl_flow")[0]
    closure = set(registry.figure_modules(curl))
    assert {"noiselab.fields", "noiselab.lattice", "noiselab._core"} <= closure   # fields imports lattice, _core
    assert "noiselab.cli" not in closure and "noiselab.gallery.figures.snow" not in closure


def test_a_change_in_a_module_a_figure_reaches_rebuilds_it(monkeypatch):
    """Changing the source of a module the figure reaches only through another (fields -> lattice) changes its hash."""
    spec = registry.specs("derivatives/curl_flow")[0]
    before = registry.content_hash(spec, quick=True)
    real = registry.module_version
    monkeypatch.setattr(registry, "module_version", lambda m: real(m) + ("x" if m == "noiselab.lattice" else ""))
    assert registry.content_hash(spec, quick=True) != before
    monkeypatch.setattr(registry, "module_version", lambda m: real(m) + ("x" if m == "noiselab.cli" else ""))
    assert registry.content_hash(spec, quick=True) == before   # an unrelated module: no rebuild


def test_only_builds_only_that_group(tmp_path):
    report = build_mod.build(tmp_path, only="lab", quick=True, show_progress=False)
    assert set(report["built"]) == {s.key for s in registry.specs("lab")}
    assert sorted(p.name for p in tmp_path.iterdir() if p.is_dir()) == ["lab", "thumbs"]
    assert sorted(p.name for p in (tmp_path / "thumbs").iterdir()) == sorted(f"{k.replace('/', '-')}.png"
                                                                           for k in report["built"])
    page = _parse_all(tmp_path)
    assert not [r for r in page.refs if not (tmp_path / r).is_file() and r not in PAGES]
    built = [f for f in page.figures if f["srcs"]]
    assert {f["id"] for f in built} == {k.replace("/", "-") for k in report["built"]}
    assert all("Not built yet" in f["caption"] for f in page.figures if not f["srcs"])


def test_only_unknown_group_is_a_clear_error(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "noiselab", "gallery", "--only", "nope", "--out", str(tmp_path)],
                          capture_output=True, text=True, cwd=ROOT)
    assert proc.returncode == 2
    assert "nope" in proc.stderr and "snow" in proc.stderr and "phillips" in proc.stderr
    assert not (tmp_path / "index.html").exists()


def test_python_m_noiselab_gallery_and_the_command_do_the_same_thing(tmp_path):
    a = subprocess.run([sys.executable, "-m", "noiselab.gallery", "--list"], capture_output=True, text=True, cwd=tmp_path)
    b = subprocess.run([sys.executable, "-m", "noiselab", "gallery", "--list"], capture_output=True, text=True)
    assert a.returncode == b.returncode == 0, a.stderr + b.stderr
    assert a.stdout == b.stdout
    assert len(a.stdout.splitlines()) == len(registry.specs())


def _installed_env(tmp_path):
    """An environment whose noiselab is a copy of the package outside any git checkout (as ``pip install`` makes)."""
    import shutil

    import noiselab

    site = tmp_path / "site-packages"
    shutil.copytree(Path(noiselab.__file__).parent, site / "noiselab",
                    ignore=shutil.ignore_patterns("__pycache__"))
    env = dict(os.environ, PYTHONPATH=str(site), MPLBACKEND="Agg")
    return site, env


def test_gallery_runs_from_an_installed_noiselab_in_any_folder(tmp_path):
    """No checkout needed: the builder is package code, the output goes where --out says."""
    site, env = _installed_env(tmp_path)
    work = tmp_path / "elsewhere"
    work.mkdir()
    proc = subprocess.run([sys.executable, "-m", "noiselab", "gallery", "--quick", "--no-progress", "--only",
                           "snow/fig3_2", "--out", "tmp"], capture_output=True, text=True, cwd=work, env=env,
                          timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    out = work / "tmp"
    man = json.loads((out / "snow" / "fig3_2" / "manifest.json").read_text())
    assert man["files"] and all((out / f).is_file() for f in man["files"]) and not man.get("error")
    page = _parse(out / "index.html")
    assert [f["id"] for f in page.figures if f["srcs"]] == ["snow-fig3_2"]
    assert f"open {(out / 'index.html').resolve()}" in proc.stdout
    assert sorted(p.name for p in work.iterdir()) == ["tmp"]          # nothing else in the current folder
    assert not [p for p in site.rglob("*") if p.suffix in (".html", ".png", ".mp4", ".json")]   # nor in the package


def test_bench_dry_run_from_an_installed_noiselab_in_any_folder(tmp_path):
    site, env = _installed_env(tmp_path)
    work = tmp_path / "elsewhere"
    work.mkdir()
    proc = subprocess.run([sys.executable, "-m", "noiselab", "bench", "--dry-run", "--output", "tmp"],
                          capture_output=True, text=True, cwd=work, env=env, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert f"write {Path('tmp') / 'RESULTS.md'}" in proc.stdout and "--peers-python" in proc.stdout
    assert list(work.iterdir()) == []                                   # a dry run writes nothing


def test_a_failing_figure_is_reported_and_leaves_no_half_written_folder(tmp_path):
    @registry.figure("zz_broken", "boom", source="Test, Fig. 0", title="broken", params=dict(n=1))
    def boom(out, *, n):
        (out / "partial.png").write_bytes(b"not a png")
        raise ValueError("deliberate failure")

    try:
        report = build_mod.build(tmp_path, only="zz_broken", show_progress=False)
    finally:
        del registry.REGISTRY["zz_broken/boom"]
    assert report["failed"] == ["zz_broken/boom"]
    folder = tmp_path / "zz_broken" / "boom"
    assert sorted(p.name for p in folder.iterdir()) == ["manifest.json"]
    assert "deliberate failure" in json.loads((folder / "manifest.json").read_text())["error"]


def test_index_marks_a_figure_whose_code_changed_as_out_of_date(tmp_path):
    build_mod.build(tmp_path, only="lab/kernels", quick=True, show_progress=False)
    assert "Out of date" not in (tmp_path / "lab.html").read_text()
    mpath = tmp_path / "lab" / "kernels" / "manifest.json"
    m = json.loads(mpath.read_text())
    m["hash"] = "f" * 64   # as if built by another version of the figure's code
    mpath.write_text(json.dumps(m))
    build_mod.build(tmp_path, only="lab/one_over_f", quick=True, show_progress=False)
    page = _parse(tmp_path / "lab.html")
    kernels = [f for f in page.figures if f["id"] == "lab-kernels"][0]
    assert "Out of date" in kernels["caption"] and kernels["srcs"]
    fresh = [f for f in page.figures if f["id"] == "lab-one_over_f"][0]
    assert "Out of date" not in fresh["caption"]


def test_docstring_examples_run():
    import doctest

    import noiselab.gallery
    from noiselab.gallery import scenes

    for mod in (noiselab.gallery, scenes):
        result = doctest.testmod(mod, optionflags=doctest.NORMALIZE_WHITESPACE)
        assert result.attempted > 0 and result.failed == 0, mod.__name__


def test_scenes_reject_bad_sizes_and_frames():
    from noiselab.gallery import scenes

    with pytest.raises(ValueError, match="height"):
        scenes.house_scene(0, 64)
    with pytest.raises(ValueError, match="width"):
        scenes.city_scene(64, 10**6)
    with pytest.raises(ValueError, match="frame must be"):
        scenes.frame_with_crop(np.zeros((8, 8, 2), np.uint8))
    with pytest.raises(ValueError, match="outside"):
        scenes.frame_with_crop(np.zeros((8, 8), np.uint8), box=(6, 0))


def test_a_periodic_background_wraps_and_the_crop_is_a_2x_enlargement():
    from noiselab.gallery import scenes

    pano = scenes.house_scene(64, 64, periodic=True)
    plain = scenes.house_scene(64, 64)
    # periodic: the left and right edge columns continue each other about as well as neighbouring columns do
    step = lambda a, b: float(np.abs(a.astype(int) - b.astype(int)).mean())
    inner = np.mean([step(pano[:, i], pano[:, i + 1]) for i in range(63)])
    assert step(pano[:, -1], pano[:, 0]) < 3 * inner + 1
    assert step(plain[:, -1], plain[:, 0]) > step(pano[:, -1], pano[:, 0])
    frame = np.arange(64 * 64, dtype=np.uint16).reshape(64, 64) % 251
    out = scenes.frame_with_crop(frame.astype(np.uint8), box=(10, 20), gap=4)
    crop = out[:, 68:]
    assert np.array_equal(crop[::2, ::2, 0], frame[10:42, 20:52])
    assert np.array_equal(crop[1::2, 1::2, 0], frame[10:42, 20:52])


def test_a_stimuli_figure_joins_zhangs_section_in_the_thesis_order(tmp_path):
    """Figures of the stimuli group (Zhang's Chapter 5 displays) stand among the thesis's other figures, by number."""
    from noiselab.gallery import html as page_html

    @registry.figure("stimuli", "zz_probe", source="Zhang 2003, Fig. 5.0", title="probe", params=dict(n=4))
    def probe(out, *, n):
        from noiselab.io import write_image

        return registry.Result([write_image(out / "probe.png", np.zeros((n, n), np.uint8))], "a probe", {"n": n})

    try:
        report = build_mod.build(tmp_path, only="stimuli/zz_probe", show_progress=False)
    finally:
        del registry.REGISTRY["stimuli/zz_probe"]
    assert report["built"] == ["stimuli/zz_probe"]
    assert page_html.page_of("stimuli") == "index.html"
    text = (tmp_path / "index.html").read_text()
    assert '<h2 id="stimuli">' not in text
    assert text.index('<h2 id="snow">') < text.index('id="snow-fig4_1"') < text.index('id="stimuli-zz_probe"') \
        < text.index('id="stimuli-fig5_4"') < text.index('id="snow-fig6_1"') < text.index('<h2 id="phillips">')
    assert "stimuli-zz_probe" not in (tmp_path / "lab.html").read_text()
    # a 4-pixel image is shown enlarged by a whole factor, nearest neighbour
    assert 'class="pixelated" width="256" height="256"' in text


def test_a_small_video_is_enlarged_like_the_small_still_beside_it(tmp_path):
    """A video narrower than the page's small-image width plays at the same whole-factor enlargement as a still."""
    from noiselab.gallery import html as page_html
    from noiselab.gallery._common import save_video
    from noiselab.io import write_image

    frames = np.linspace(0, 1, 4 * 48 * 48).reshape(4, 48, 48)
    files = save_video(tmp_path, "clip", frames) + [write_image(tmp_path / "still.png", np.zeros((48, 48), np.uint8))]
    text = page_html._media(files, tmp_path)
    k = -(-page_html.SMALL // 48)
    video = re.search(r"<video[^>]*>", text).group(0)
    still = re.search(r'<img src="still.png"[^>]*>', text).group(0)
    for tag in (video, still):
        assert f'class="pixelated" width="{48 * k}" height="{48 * k}"' in tag
    # a video as wide as the page's small-image width is shown at its own size
    big = save_video(tmp_path, "big", np.zeros((2, page_html.SMALL, page_html.SMALL)))
    assert "pixelated" not in page_html._media(big, tmp_path)


def test_label_band_keeps_the_stimulus_pixels_and_writes_each_label_over_its_panel():
    from noiselab.gallery._common import label_band

    rng = np.random.default_rng(0)
    image = rng.integers(0, 256, (40, 200), dtype=np.uint8)
    out = label_band(image, ["left", "right"], centres=[50, 150], height=24, size=16)
    assert out.shape == (64, 200) and out.dtype == np.uint8
    assert np.array_equal(out[24:], image)                  # the stimulus's displayed values are untouched
    band = out[:24]
    ink = np.flatnonzero((band < 128).any(axis=0))
    # ink under both labels, none at the far edges or between the two words
    assert ink.size and (ink < 100).any() and (ink >= 100).any()
    assert not (band[:, :5] < 128).any() and not (band[:, 97:103] < 128).any()
    rgb = label_band(np.repeat(image[..., None], 3, axis=-1), ["a"])
    assert rgb.shape == (70, 200, 3) and np.array_equal(rgb[30:, :, 1], image)
    with pytest.raises(TypeError, match="image must be uint8"):
        label_band(image.astype(float), ["a"])


def test_each_page_names_the_other_in_a_sentence_and_headings_start_with_a_capital(tmp_path):
    from noiselab.gallery import html as page_html

    pages = page_html.render_pages(tmp_path, [])
    text = {p: re.sub(r"<[^>]+>", "", t) for p, t in pages.items()}
    assert "The lab's comparisons and derivatives are on a page of their own." in html.unescape(text["index.html"])
    assert ("The seed papers' figures, reproduced and measured, are on a page of their own."
            in html.unescape(text["lab.html"]))
    # a card's heading is "source: title": both begin with a capital letter or a digit
    for spec in registry.specs(None):
        for part in (spec.source, spec.title):
            assert not part[0].islower(), (spec.key, part)


def test_small_label_detector_flags_text_seen_under_11_px(tmp_path):
    from noiselab.gallery import checks
    from noiselab.gallery._common import pyplot, save_figure

    plt = pyplot()
    paths = {}
    for name, size in (("small", 6), ("large", 14)):
        fig, ax = plt.subplots(figsize=(4, 3))
        ax.plot([0, 1], [0, 1])
        ax.tick_params(labelsize=size)
        ax.set_title("a title", fontsize=size)
        paths[name] = save_figure(fig, tmp_path / f"{name}.png", dpi=100)
    # the PNG records its smallest text in its own pixels (points * dpi / 72)
    assert checks.smallest_text_px(paths["small"]) == pytest.approx(6 * 100 / 72, abs=0.01)
    assert checks.smallest_text_px(paths["large"]) == pytest.approx(14 * 100 / 72, abs=0.01)
    from PIL import Image

    width = Image.open(paths["small"]).width
    shown = [{"src": "small.png", "w": width, "shown": width}, {"src": "large.png", "w": width, "shown": width}]
    assert [src for src, _ in checks.small_labels(shown, tmp_path)] == ["small.png"]
    # the same 14-pt labels drawn at half their width are read at 9.7 px: flagged
    half = [{"src": "large.png", "w": width, "shown": width / 2}]
    [(src, px)] = checks.small_labels(half, tmp_path)
    assert src == "large.png" and px == pytest.approx(14 * 100 / 72 / 2, abs=0.01)
    # an image with no recorded size (a photograph, a frame) is not judged
    Image.new("RGB", (8, 8)).save(tmp_path / "plain.png")
    assert checks.small_labels([{"src": "plain.png", "w": 8, "shown": 1}], tmp_path) == []
    with pytest.raises(ValueError, match="natural_width"):
        checks.shown_text_px(10, natural_width=0, shown_width=5)


def test_duplicate_detector_finds_same_bytes_and_same_pixels(tmp_path):
    from PIL import Image

    from noiselab.gallery import checks

    rng = np.random.default_rng(0)
    a = rng.integers(0, 256, (16, 16, 3), dtype=np.uint8)
    Image.fromarray(a).save(tmp_path / "a.png")
    (tmp_path / "a_copy.png").write_bytes((tmp_path / "a.png").read_bytes())
    Image.fromarray(a).save(tmp_path / "a_other_bytes.png", compress_level=0)   # same pixels, other bytes
    b = a.copy()
    b[0, 0, 0] ^= 1                                                                # one pixel differs
    Image.fromarray(b).save(tmp_path / "b.png")
    assert (tmp_path / "a.png").read_bytes() != (tmp_path / "a_other_bytes.png").read_bytes()
    groups = checks.duplicate_images(sorted(tmp_path.glob("*.png")))
    reasons = {reason: sorted(p.name for p in group) for reason, group in groups}
    assert reasons == {"identical bytes": ["a.png", "a_copy.png"],
                       "identical pixels": ["a.png", "a_copy.png", "a_other_bytes.png"]}
    assert checks.duplicate_images([tmp_path / "a.png", tmp_path / "b.png", tmp_path / "a.png"]) == []


def test_check_reports_small_labels_and_duplicates_on_a_built_page(tmp_path, capsys):
    """``--check`` on a page holding a still identical to a video's poster and a figure with tiny labels fails."""
    from noiselab.gallery._common import pyplot, save_figure, save_video

    @registry.figure("zz_bad", "twice", source="Test, Fig. 1", title="a still beside its video", params=dict(n=16))
    def twice(out, *, n):
        frames = np.linspace(0, 1, 4 * n * n).reshape(4, n, n)
        files = save_video(out, "clip", frames)
        from noiselab.io import to_uint8, write_image

        files.append(write_image(out / "still.png", to_uint8(frames[0], None, None)))
        return registry.Result(files, "bad")

    @registry.figure("zz_bad", "tiny", source="Test, Fig. 2", title="tiny labels", params=dict(n=1))
    def tiny(out, *, n):
        plt = pyplot()
        fig, ax = plt.subplots(figsize=(4, 3))
        ax.set_title("tiny", fontsize=5)
        return registry.Result([save_figure(fig, out / "tiny.png")], "bad")

    try:
        build_mod.build(tmp_path, only="zz_bad", show_progress=False)
        status = build_mod.check(tmp_path, pages=("index.html",))
    finally:
        del registry.REGISTRY["zz_bad/twice"], registry.REGISTRY["zz_bad/tiny"]
    err = capsys.readouterr().err
    assert status == 1
    assert "zz_bad/tiny/tiny.png: labels" in err
    assert "the same image twice" in err and "zz_bad/twice/still.png" in err and "zz_bad/twice/clip_poster.png" in err


def test_the_readme_shows_the_picture_the_gallery_draws(tmp_path):
    """The README's image is the file the gallery's readme/picture figure writes, published by a full build."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    shown = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", readme)
    assert build_mod.README_PICTURE_PATH.as_posix() in shown
    spec = registry.specs(build_mod.README_PICTURE)[0]
    # built (quick sizes, to keep the test short) into a scratch folder
    report = build_mod.build(tmp_path / "out", only=build_mod.README_PICTURE, quick=True, show_progress=False)
    assert report["built"] == [spec.key]
    man = build_mod.read_manifest(tmp_path / "out", spec)
    assert [Path(f).name for f in man["files"]] == [build_mod.README_PICTURE_PATH.name]
    # a quick build never publishes; a full one copies the bytes into a checkout's docs/_static/
    checkout = tmp_path / "checkout"
    (checkout / "docs" / "_static").mkdir(parents=True)
    (checkout / "README.md").write_text("![x](docs/_static/noiselab.png)")
    assert build_mod.publish_readme_picture(tmp_path / "out", checkout=checkout) is None
    man["quick"] = False
    (tmp_path / "out" / "readme" / "picture" / "manifest.json").write_text(json.dumps(man))
    target = build_mod.publish_readme_picture(tmp_path / "out", checkout=checkout)
    assert target == checkout / build_mod.README_PICTURE_PATH
    assert target.read_bytes() == (tmp_path / "out" / man["files"][0]).read_bytes()
    # another machine's renderer changes low bits, not the picture: the committed copy is left alone;
    # a different picture replaces it
    from PIL import Image

    built = np.asarray(Image.open(target).convert("RGB")).astype(int)
    noisy = np.clip(built + np.random.default_rng(1).integers(-3, 4, built.shape), 0, 255).astype(np.uint8)
    Image.fromarray(noisy).save(target)
    before = target.read_bytes()
    build_mod.publish_readme_picture(tmp_path / "out", checkout=checkout)
    assert target.read_bytes() == before
    Image.fromarray(255 - noisy).save(target)
    build_mod.publish_readme_picture(tmp_path / "out", checkout=checkout)
    assert target.read_bytes() == (tmp_path / "out" / man["files"][0]).read_bytes()
    # an installed noiselab (no README beside the package) is left alone
    assert build_mod.publish_readme_picture(tmp_path / "out", checkout=tmp_path / "nowhere") is None
    # the committed picture is a full-size build of that figure: as wide as its three panels, labels that read
    from noiselab.gallery import checks

    committed = ROOT / build_mod.README_PICTURE_PATH
    with Image.open(committed) as im:
        width = im.width
    assert width >= 3 * spec.params["panel"]
    # on a project page about 830 px wide, its labels are seen at 11 px or more
    assert checks.shown_text_px(checks.smallest_text_px(committed), natural_width=width, shown_width=830) >= 11


def test_the_readme_picture_opens_the_papers_page(quick_gallery):
    out, _ = quick_gallery
    text = (out / "index.html").read_text()
    assert text.index("noiselab is a Python laboratory") < text.index("readme/picture/noiselab.png") \
        < text.index("The documents reproduced")
    assert 'id="readme-picture"' not in "".join(f["id"] for f in _parse(out / "index.html").figures)


def test_check_finds_nothing_on_the_built_gallery(quick_gallery, capsys):
    """--check's every report (missing files, console errors, labels under 11 px, duplicate images) is empty."""
    out, _ = quick_gallery
    status = build_mod.check(out)
    captured = capsys.readouterr()
    assert status == 0, captured.err
    assert "0 duplicate images" in captured.out and "labels" not in captured.err
