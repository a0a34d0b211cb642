"""The project's own promises: the README's set-up commands and what CI runs."""
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from _helpers import SETUP_COMMANDS

ROOT = Path(__file__).resolve().parents[1]


def _quick_start_commands():
    text = (ROOT / "README.md").read_text()
    block = re.search(r"## Quick start.*?```bash\n(.*?)```", text, re.S)
    assert block, "README has no Quick start bash block"
    return [line for line in block.group(1).splitlines() if line.strip()]


def test_readme_has_exactly_two_setup_commands():
    commands = _quick_start_commands()
    assert commands == list(SETUP_COMMANDS), commands


def test_install_sh_never_pip_installs_into_the_system_python():
    """PEP 668: pip runs only with the environment's own interpreter (.venv/bin/python)."""
    script = (ROOT / "install.sh").read_text()
    pip_lines = [line.strip() for line in script.splitlines()
                 if re.search(r"\bpip3?\s+install\b", line) and not line.strip().startswith("#")]
    assert pip_lines, "install.sh installs nothing with pip"
    assert all(line.startswith('"$python" -m pip install') for line in pip_lines), pip_lines
    assert re.search(r"^python=\.venv/bin/python$", script, re.M)
    assert "/.venv" in (ROOT / ".gitignore").read_text().split()


def test_test_extra_includes_hypothesis_and_the_dask_extra():
    import tomllib

    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    names = {re.split(r"[<>=\[ ]", r)[0] for r in extras["test"]}
    assert {"pytest", "pytest-xdist", "hypothesis", "noiselab"} <= names
    assert "noiselab[dask]" in extras["test"]
    assert {re.split(r"[<>=\[ ]", r)[0] for r in extras["dask"]} == {"dask", "distributed", "zarr"}


def test_ci_runs_the_readme_test_command_verbatim():
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert _quick_start_commands()[1] in ci


def test_cli_rejects_unknown_command_with_usage_error():
    proc = subprocess.run([sys.executable, "-m", "noiselab", "no-such-command"], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "invalid choice" in proc.stderr


def test_install_sh_installs_into_an_active_virtualenv_and_links_dot_venv(tmp_path):
    """With a virtualenv active, install.sh installs there and `.venv` runs that environment's noiselab."""
    files = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=ROOT, capture_output=True,
                           text=True, check=True).stdout.split()
    repo = tmp_path / "repo"
    for name in files:
        src = ROOT / name
        if src.is_file():
            (repo / name).parent.mkdir(parents=True, exist_ok=True)
            (repo / name).write_bytes(src.read_bytes())
            (repo / name).chmod(src.stat().st_mode)
    env_dir = tmp_path / "env"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(env_dir)], check=True)
    # the new environment sees this interpreter's packages (pip among them), so pip has nothing to download
    # but the build tools, also when this interpreter is itself a virtualenv
    import site
    import sysconfig

    purelib = Path(subprocess.run([str(env_dir / "bin" / "python"), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                                  capture_output=True, text=True, check=True).stdout.strip())
    parents = [p for p in dict.fromkeys(site.getsitepackages() + [sysconfig.get_paths()["purelib"]]) if Path(p).is_dir()]
    (purelib / "_parent_env.pth").write_text("\n".join(parents) + "\n")
    env = {k: v for k, v in __import__("os").environ.items() if k not in ("PYTHONPATH", "CONDA_PREFIX")}
    env.update(VIRTUAL_ENV=str(env_dir), PATH=f"{env_dir / 'bin'}:{env['PATH']}")
    proc = subprocess.run(["./install.sh"], cwd=repo, env=env, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    out = proc.stdout.splitlines()
    assert all(line.startswith("install.sh: ") for line in out) and len(out) <= 6, out   # a few lines, not dpkg's
    assert (repo / ".venv").is_symlink() and (repo / ".venv").resolve() == env_dir.resolve()
    where = subprocess.run([str(repo / ".venv" / "bin" / "python"), "-c", "import noiselab; print(noiselab.__file__)"],
                           cwd=tmp_path, env=env, capture_output=True, text=True)
    assert where.stdout.strip() == str(repo / "noiselab" / "__init__.py"), where.stderr
    version = subprocess.run([str(repo / ".venv" / "bin" / "noiselab"), "--version"], env=env, capture_output=True,
                             text=True)
    assert version.stdout.strip().startswith("noiselab "), version.stderr


def test_readme_is_a_two_minute_read_of_at_most_150_lines():
    """Everything else lives on the documentation site (docs/, CONTRIBUTING.md says where)."""
    lines = (ROOT / "README.md").read_text().splitlines()
    assert len(lines) <= 150, len(lines)
    text = "\n".join(lines)
    for heading in ("## Quick start", "## Falling snow", "## Lattice noise", "## Measuring noise", "## Where things are",
                    "## Citing the seeds"):
        assert heading in text, heading


def test_install_sh_offers_the_docs_extra_and_the_test_extra_includes_it():
    import tomllib

    extras = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["optional-dependencies"]
    assert {re.split(r"[<>=\[ ]", r)[0] for r in extras["docs"]} >= {"sphinx", "numpydoc", "sphinx-gallery",
                                                                      "pydata-sphinx-theme", "myst-parser"}
    assert "noiselab[docs]" in extras["test"]
    script = (ROOT / "install.sh").read_text()
    assert re.search(r'^\s*"" \| test \| dask \| docs\) ;;$', script, re.M)
    proc = subprocess.run(["bash", str(ROOT / "install.sh"), "nonsense"], capture_output=True, text=True)
    assert proc.returncode == 1 and "'docs'" in proc.stderr


def test_the_contributor_guide_is_contributing_md():
    """The guide is where GitHub and contributors look for it, and nothing points to an older name."""
    old = "DEVELOPERS" + ".md"
    guide = ROOT / "CONTRIBUTING.md"
    assert guide.is_file() and "## Ground rules" in guide.read_text()
    assert "`CONTRIBUTING.md`" in (ROOT / "README.md").read_text()
    assert not (ROOT / old).exists()
    skip = {".git", ".venv", "_build", "out", ".venv-peers", "__pycache__", ".pytest_cache"}
    stale = []
    for folder, dirs, files in os.walk(ROOT):
        dirs[:] = [d for d in dirs if d not in skip]
        for name in files:
            path = Path(folder) / name
            if path.suffix in (".md", ".py", ".toml", ".sh", ".txt", ".rst", ".cfg") and old in path.read_text(
                    errors="replace"):
                stale.append(str(path.relative_to(ROOT)))
    assert stale == []


def test_docs_reports_and_code_speak_of_noiselab_not_of_its_issue_tracker():
    """A reader of the docs, a benchmark report or a comment meets noiselab's own targets and reasons.

    Tracker numbers and "the issue asks" mean nothing to a user (and the tracker is not public): every
    target is stated as noiselab's, with the figure and the command that measured it.
    """
    tracker = re.compile(r"\b[Ii]ssues? (?:#?\d+)|\bthe issue\b|[Ii]ssue's\b")
    skip = {".git", ".venv", "_build", "out", ".venv-peers", "__pycache__", ".pytest_cache", "results"}
    found = []
    for top in ("README.md", "CONTRIBUTING.md", "docs", "benchmarks", "noiselab", "tests"):
        paths = [ROOT / top] if (ROOT / top).is_file() else []
        for folder, dirs, files in os.walk(ROOT / top):
            dirs[:] = [d for d in dirs if d not in skip and not d.startswith(".")]
            paths += [Path(folder) / name for name in files]
        for path in paths:
            if path.suffix not in (".md", ".py", ".rst", ".txt") or path == Path(__file__):
                continue
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                if tracker.search(line):
                    found.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()[:100]}")
    assert found == [], "\n".join(found)
