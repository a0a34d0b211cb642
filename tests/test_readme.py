"""The README is a contract: every fenced Python and shell example in it runs as written.

The blocks run in README order in one scratch folder (as a reader would run
them, so a later block may use a file an earlier one wrote), Python blocks
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

ROOT = Path(__file__).resolve().parents[1]
SETUP_LINES = {"./install.sh && .venv/bin/noiselab gallery", "./install.sh test && .venv/bin/python -m pytest"}
LANGUAGES = {"python": "python", "py": "python", "bash": "bash", "sh": "bash", "shell": "bash", "console": "bash"}

#: what the test appends to each shell line that runs ``noiselab SUBCOMMAND`` (or ``python3 -m noiselab.SUBCOMMAND``)
SMALL_RUNS = {
    "snow": "--frames 8 --loops 1",   # an 8-frame period written once (as written: 64 frames, twice in an MP4)
    "mesh": "--frames 4 --size 128",  # 4 animation frames of 128 px (as written: 48 frames of 512 px)
    "gallery": "--quick",             # every figure at its quick size (as written: the full gallery, minutes)
    "bench": "--dry-run",             # check the options and the output folder, print the plan (a run takes minutes)
}
_SUBCOMMAND = re.compile(r"\bnoiselab[ .](" + "|".join(SMALL_RUNS) + r")\b")


def readme_blocks(text=None):
    """(line number, language, code) of every fenced python/shell block of the README, in order."""
    text = (ROOT / "README.md").read_text() if text is None else text
    blocks = []
    for m in re.finditer(r"^```([A-Za-z]*)[^\n]*\n(.*?)^```\s*$", text, re.M | re.S):
        lang = LANGUAGES.get(m.group(1).lower())
        if lang is None:
            continue
        code = m.group(2)
        if lang == "bash":
            code = "\n".join(line for line in code.splitlines() if line.strip() not in SETUP_LINES)
        if code.strip():
            blocks.append((text.count("\n", 0, m.start()) + 1, lang, code))
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


def test_every_small_run_rule_rewrites_a_readme_line():
    """The table follows the README: a rule for a command the README no longer shows is stale."""
    used = set()
    for _, lang, code in readme_blocks():
        if lang == "bash":
            used |= small_run(code)[1]
    assert used == set(SMALL_RUNS)


def test_block_extraction_finds_both_languages_and_leaves_out_only_the_setup_lines():
    sample = ("x\n```bash\n./install.sh && .venv/bin/noiselab gallery\n./install.sh test && .venv/bin/python -m pytest\n"
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


def test_every_readme_example_runs_as_written(tmp_path):
    blocks = readme_blocks()
    assert len(blocks) >= 5
    env = _env()
    failures, timings = [], []
    for line, lang, code in blocks:
        script = tmp_path / f"readme_line_{line}.{'py' if lang == 'python' else 'sh'}"
        script.write_text(code if lang == "python" else "set -euo pipefail\n" + small_run(code)[0] + "\n")
        cmd = [sys.executable, str(script)] if lang == "python" else ["bash", str(script)]
        t0, c0 = time.perf_counter(), _child_cpu()
        proc = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
        timings.append((line, round(time.perf_counter() - t0, 1), round(_child_cpu() - c0, 1)))
        if proc.returncode != 0:
            tail = "\n".join((proc.stderr or proc.stdout).strip().splitlines()[-6:])
            failures.append(f"README.md line {line} ({lang}, run as {script.name}) exited {proc.returncode}:\n{tail}")
    print("README line, wall s, CPU s:", timings)
    assert not failures, "\n\n".join(failures) + f"\n(README line, wall s, CPU s: {timings})"
