"""The README is a contract: every fenced Python and shell example in it runs as written.

The blocks run in README order in one scratch folder (as a reader would run
them, so a later block may use a file an earlier one wrote), Python blocks
with this interpreter, shell blocks with bash (``set -euo pipefail``) and this
interpreter's folder first on PATH (so ``python3`` is the one under test).
Only the quick start's two set-up lines are left out: CI runs them itself
(``.ci/run``, ``tests/test_project.py``).

Shell blocks run with ``NOISELAB_EXAMPLE_SIZE=small``: the ``noiselab``
command then caps each subcommand's sizes at its module's ``SMALL`` values
(``DEVELOPERS.md``), so the examples keep their text and the suite stays fast.
Python blocks must be small enough as written.
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
    env["NOISELAB_EXAMPLE_SIZE"] = "small"
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
        script.write_text(code if lang == "python" else "set -euo pipefail\n" + code + "\n")
        cmd = [sys.executable, str(script)] if lang == "python" else ["bash", str(script)]
        t0, c0 = time.perf_counter(), _child_cpu()
        proc = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600)
        timings.append((line, round(time.perf_counter() - t0, 1), round(_child_cpu() - c0, 1)))
        if proc.returncode != 0:
            tail = "\n".join((proc.stderr or proc.stdout).strip().splitlines()[-6:])
            failures.append(f"README.md line {line} ({lang}) exited {proc.returncode}:\n{tail}")
    print("README line, wall s, CPU s:", timings)
    assert not failures, "\n\n".join(failures) + f"\n(README line, wall s, CPU s: {timings})"
