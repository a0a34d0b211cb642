"""The README and the user guide are a contract: every fenced Python and shell example in them runs as written.

The README's blocks run in README order in one scratch folder (as a reader would run
them, so a later block may use a file an earlier one wrote); the documentation
site's pages (``docs/**/*.md`` and ``docs/**/*.rst``, the pages generated at
build time excepted) run the same way, page after page in the order of
:func:`docs_pages`, in a second scratch folder. Python blocks
with this interpreter, shell blocks with bash (``set -euo pipefail``) and this
interpreter's folder first on PATH (so ``python3`` is the one under test).
Only the quick start's two set-up lines are left out: CI runs them itself
(``.ci/run``, ``tests/test_project.py``).

The README shows each command at the size a reader wants; the test runs the
shell blocks small by rewriting their text through one visible table,
:data:`SMALL_RUNS` (options appended to every line that runs that ``noiselab``
subcommand; argparse keeps an option's last value, so ``--frames 64 ...
--frames 8`` renders 8 frames). The product has no test switch: a reader's
``noiselab snow`` renders what the README says it renders. Python blocks must
be small enough as written.
"""
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest
from _helpers import SETUP_COMMANDS

ROOT = Path(__file__).resolve().parents[1]
SETUP_LINES = set(SETUP_COMMANDS)
LANGUAGES = {"python": "python", "py": "python", "bash": "bash", "sh": "bash", "shell": "bash", "console": "bash"}

#: what the test appends to each shell line that runs ``noiselab SUBCOMMAND`` (or ``python3 -m noiselab.SUBCOMMAND``)
SMALL_RUNS = {
    "snow": "--frames 8 --loops 1",   # an 8-frame period written once (as written: 64 frames, twice in an MP4)
    "mesh": "--frames 4 --size 128",  # 4 animation frames of 128 px (as written: 48 frames of 512 px)
    "gallery": "--quick",             # every figure at its quick size (as written: the full gallery, minutes)
    "bench": "--dry-run",             # check the options and the output folder, print the plan (a run takes minutes)
}
_SUBCOMMAND = re.compile(r"\bnoiselab[ .](" + "|".join(SMALL_RUNS) + r")\b")


DOCS = ROOT / "docs"
#: the guide's pages in reading order (the README's order before they moved); other pages follow by name
DOCS_ORDER = ["getting_started", "guide/conventions", "guide/layout", "guide/snow", "guide/lattice",
              "guide/derivatives", "guide/scale", "guide/analysis", "guide/geometry", "guide/gallery",
              "guide/laboratory", "guide/cli"]
#: folders of docs/ written at build time (conf.py, sphinx-gallery): not pages anyone wrote
DOCS_GENERATED = {"_build", "api", "benchmarks", "auto_examples", "_templates", "examples"}


def _keep(lang, code):
    if lang == "bash":
        code = "\n".join(line for line in code.splitlines() if line.strip() not in SETUP_LINES)
    return code if code.strip() else None


def readme_blocks(text=None):
    """(line number, language, code) of every fenced python/shell block of the README (or any Markdown), in order."""
    text = (ROOT / "README.md").read_text() if text is None else text
    blocks = []
    for m in re.finditer(r"^```([A-Za-z]*)[^\n]*\n(.*?)^```\s*$", text, re.M | re.S):
        lang = LANGUAGES.get(m.group(1).lower())
        code = _keep(lang, m.group(2)) if lang else None
        if code:
            blocks.append((text.count("\n", 0, m.start()) + 1, lang, code))
    return blocks


def rst_blocks(text):
    """(line number, language, code) of every ``.. code-block:: python|bash`` (or ``code``) block of a reST page."""
    import textwrap

    blocks = []
    for m in re.finditer(r"^([ \t]*)\.\. (?:code-block|code|sourcecode)::[ \t]*(\w+)[ \t]*\n((?:\1[ \t]+:.*\n)*)"
                         r"((?:[ \t]*\n|\1[ \t]+.*\n)*)", text, re.M):
        lang = LANGUAGES.get(m.group(2).lower())
        code = _keep(lang, textwrap.dedent(m.group(4)).strip("\n") + "\n") if lang else None
        if code:
            blocks.append((text.count("\n", 0, m.start()) + 1, lang, code))
    return blocks


def docs_pages():
    """The documentation site's hand-written pages (relative to docs/, no suffix), in reading order."""
    found = {}
    for path in sorted(DOCS.rglob("*")):
        rel = path.relative_to(DOCS)
        if path.suffix in (".md", ".rst") and rel.parts[0] not in DOCS_GENERATED:
            found[rel.with_suffix("").as_posix()] = path
    order = [name for name in DOCS_ORDER if name in found] + sorted(set(found) - set(DOCS_ORDER))
    return [(name, found[name]) for name in order]


def docs_blocks():
    """(page:line, language, code) of every runnable block of the site's pages, page after page."""
    blocks = []
    for name, path in docs_pages():
        text = path.read_text()
        found = readme_blocks(text) if path.suffix == ".md" else rst_blocks(text)
        if path.suffix == ".rst":
            # an .rst page is one session, as a reader follows it (names defined in one block are used in the
            # next): its python blocks run as one script, at the first block's place
            py = [code for _, lang, code in found if lang == "python"]
            first = next((i for i, (_, lang, _) in enumerate(found) if lang == "python"), None)
            found = [(line, lang, "\n".join(py) if i == first else code)
                     for i, (line, lang, code) in enumerate(found) if lang != "python" or i == first]
        blocks += [(f"docs/{path.relative_to(DOCS)}:{line}", lang, code) for line, lang, code in found]
    return blocks


def small_run(code):
    """``code`` (a shell block) with :data:`SMALL_RUNS` applied; returns ``(code, subcommands rewritten)``."""
    lines, used = [], set()
    for line in code.splitlines():
        m = _SUBCOMMAND.search(line)
        if m:
            command, hash_, comment = line.partition(" #")
            if command.rstrip().endswith("\\") or any(s in command[m.end():] for s in ("|", "&&", ";", "||")):
                raise ValueError(f"README shell line {line!r}: SMALL_RUNS only rewrites one command per line, "
                                 "without continuation lines or pipes")
            line = f"{command.rstrip()} {SMALL_RUNS[m.group(1)]}" + (f"  #{comment}" if hash_ else "")
            used.add(m.group(1))
        lines.append(line)
    return "\n".join(lines), used


def test_small_run_appends_the_table_options_to_noiselab_commands_only():
    code = ("python3 -m noiselab snow --frames 64 -o out/a.mp4   # a comment\n"
            "noiselab gallery\npython3 -m noiselab.gallery --list\nnoiselab noise -o x.png\necho noiselab snowman\n")
    small, used = small_run(code)
    assert small.splitlines() == ["python3 -m noiselab snow --frames 64 -o out/a.mp4 --frames 8 --loops 1  # a comment",
                                  "noiselab gallery --quick", "python3 -m noiselab.gallery --list --quick",
                                  "noiselab noise -o x.png", "echo noiselab snowman"]
    assert used == {"snow", "gallery"}
    with pytest.raises(ValueError, match="one command per line"):
        small_run("noiselab bench | tee log")


def test_every_small_run_rule_rewrites_a_readme_or_guide_line():
    """The table follows the README and the guide: a rule for a command neither shows any more is stale."""
    used = set()
    for _, lang, code in readme_blocks() + docs_blocks():
        if lang == "bash":
            used |= small_run(code)[1]
    assert used == set(SMALL_RUNS)


def test_block_extraction_finds_both_languages_and_leaves_out_only_the_setup_lines():
    sample = ("x\n```bash\n" + "\n".join(SETUP_COMMANDS) + "\n"
              "```\n```python\nprint(1)\n```\n```text\nnot run\n```\n```bash\necho hi\n```\n")
    assert readme_blocks(sample) == [(6, "python", "print(1)\n"), (12, "bash", "echo hi")]
    langs = {lang for _, lang, _ in readme_blocks()}
    assert langs == {"python", "bash"}


def _env():
    env = dict(os.environ)
    env["PATH"] = str(Path(sys.executable).parent) + os.pathsep + env.get("PATH", "")
    env["PYTHONPATH"] = str(ROOT) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["MPLBACKEND"] = "Agg"
    return env


def _child_cpu():
    import resource

    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def test_rst_block_extraction_reads_code_block_directives_only():
    sample = ("Title\n=====\n\n.. code-block:: python\n   :caption: x\n\n   import os\n   print(1)\n\n"
              "text\n\n.. code-block:: text\n\n   not run\n\n.. code-block:: bash\n\n   echo hi\n"
              f"   {SETUP_COMMANDS[1]}\n")
    assert rst_blocks(sample) == [(4, "python", "import os\nprint(1)\n"), (16, "bash", "echo hi")]


def test_the_guide_pages_are_found_in_reading_order_and_hold_the_moved_examples():
    names = [name for name, _ in docs_pages()]
    assert names[:len(DOCS_ORDER)] == DOCS_ORDER, names
    blocks = docs_blocks()
    assert {lang for _, lang, _ in blocks} == {"python", "bash"}
    assert len(blocks) >= 25, len(blocks)   # what the README held before it shrank, and the getting-started page's


def _run_blocks(blocks, tmp_path, what):
    env = _env()
    failures, timings = [], []
    for line, lang, code in blocks:
        label = re.sub(r"\W+", "_", f"{what}_line_{line}").lower()
        script = tmp_path / f"{label}.{'py' if lang == 'python' else 'sh'}"
        script.write_text(code if lang == "python" else "set -euo pipefail\n" + small_run(code)[0] + "\n")
        cmd = [sys.executable, str(script)] if lang == "python" else ["bash", str(script)]
        t0, c0 = time.perf_counter(), _child_cpu()
        proc = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
        timings.append((line, round(time.perf_counter() - t0, 1), round(_child_cpu() - c0, 1)))
        if proc.returncode != 0:
            tail = "\n".join((proc.stderr or proc.stdout).strip().splitlines()[-6:])
            failures.append(f"{what} line {line} ({lang}, run as {script.name}) exited {proc.returncode}:\n{tail}")
    print(f"{what} line, wall s, CPU s:", timings)
    assert not failures, "\n\n".join(failures) + f"\n({what} line, wall s, CPU s: {timings})"


def test_every_readme_example_runs_as_written(tmp_path):
    blocks = readme_blocks()
    assert len(blocks) >= 5
    _run_blocks(blocks, tmp_path, "README.md")


def test_every_guide_example_runs_as_written(tmp_path):
    """The examples that moved from the README into the guide keep running, in one folder, page after page."""
    _run_blocks(docs_blocks(), tmp_path, "docs")
