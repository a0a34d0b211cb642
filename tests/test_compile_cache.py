"""The compile cache (numba's ``*.nbi``/``*.nbc`` files) never breaks a run.

A cold cache, one cache filled by several processes at once, a read-only
cache (and a read-only install and home), and a cache whose files were
truncated or overwritten: every run gives the same values, bit for bit, as an
undisturbed one, with at most one warning line on stderr, and a damaged cache
is repaired by the run that meets it (the next run prints nothing and loads
everything: no cache file changes).

Each case runs a small lattice-noise evaluation in a fresh process with its
own ``NUMBA_CACHE_DIR`` (numba's files for ``lattice/_jit.py``, where every
lattice kernel is compiled, land there); a cold run compiles for a few
seconds of CPU time.
"""
import hashlib
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent.parent

_RUN = """
import hashlib, sys
import numpy as np
from noiselab import LatticeNoise
x = np.linspace(-7.3, 9.1, 257)
out = LatticeNoise(1, seed=5)(x, dtype=np.dtype(sys.argv[1]))
print(hashlib.sha256(out.tobytes()).hexdigest())
"""


def _expected(dtype):
    from noiselab import LatticeNoise

    out = LatticeNoise(1, seed=5)(np.linspace(-7.3, 9.1, 257), dtype=np.dtype(dtype))
    return hashlib.sha256(out.tobytes()).hexdigest()


def _env(cache, home, package=HERE):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), HOME=str(home), XDG_CACHE_HOME=str(home / ".cache"),
               PYTHONPATH=str(package) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    env.pop("NUMBA_DISABLE_JIT", None)
    return env


def _start(cache, home, dtype="float64", prefix=(), package=HERE):
    # run outside the checkout: ``python -c`` puts the working folder first on sys.path, and from the
    # repository root that would import the checkout's noiselab instead of ``package``
    return subprocess.Popen([*prefix, sys.executable, "-c", _RUN, dtype], env=_env(cache, home, package),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=str(cache.parent))


def _finish(proc):
    out, err = proc.communicate(timeout=600)
    return proc.returncode, out.strip(), [ln for ln in err.splitlines() if ln.strip()]


def _run(cache, home, dtype="float64", **kw):
    return _finish(_start(cache, home, dtype, **kw))


def _snapshot(folder):
    """Every file under ``folder`` with its size and modification time: a run that loads only changes none."""
    return {str(p.relative_to(folder)): (p.stat().st_size, p.stat().st_mtime_ns)
            for p in Path(folder).rglob("*") if p.is_file()}


def _assert_clean(result, dtype, *, warnings=0, needle=None):
    rc, digest, err = result
    assert rc == 0, "\n".join(err)
    assert digest == _expected(dtype), "\n".join(err)
    assert len(err) <= warnings, err   # at most this many lines (a warning); never a traceback
    assert not any("Traceback" in ln for ln in err), err
    if needle is not None and err:
        assert needle in err[0], err


@pytest.fixture(scope="module")
def _filled(tmp_path_factory):
    """A cache filled by one cold run (float64) at ``root/cache``, with a pristine copy at ``root/pristine``."""
    root = tmp_path_factory.mktemp("warm")
    cache, home = root / "cache", root / "home"
    home.mkdir()
    _assert_clean(_run(cache, home), "float64")
    shutil.copytree(cache, root / "pristine")
    return root


@pytest.fixture
def warm_cache(_filled):
    """The filled cache, as it was after the cold run, at the path where it was filled, and its home.

    At that path, not a copy elsewhere: numba files a kernel's compiled code
    under a hash of its source file's folder, and the generated modules live in
    the cache folder itself, so a copy in another place would be a cold cache
    for them (and damage done to it would go unread).
    """
    cache = _filled / "cache"
    shutil.rmtree(cache)
    shutil.copytree(_filled / "pristine", cache)
    return cache, _filled / "home"


def test_a_cold_cache_is_filled_then_used(warm_cache):
    cache, home = warm_cache
    files = _snapshot(cache)
    assert any(f.endswith(".nbi") for f in files) and any(f.endswith(".nbc") for f in files)
    assert not any(f.endswith(".py") for f in files)   # numba's files only: no source is written at run time
    _assert_clean(_run(cache, home), "float64")   # warm: nothing printed, nothing compiled or written
    assert _snapshot(cache) == files


def test_processes_compiling_at_once_share_one_empty_cache(tmp_path):
    """Three processes fill one empty cache at once, two kernel signatures (float32 and float64 output) crossing.

    numba numbers its data files by reading the index and writing it back;
    processes saving different signatures at once can leave an index entry
    naming another signature's file. Whatever they leave, every run gives
    the right values (a crossed entry is detected and recompiled, with one
    warning line), and after one repairing round the cache is complete.
    """
    cache, home = tmp_path / "cache", tmp_path / "home"
    home.mkdir()
    dtypes = ["float64", "float32", "float64"]
    procs = [_start(cache, home, d) for d in dtypes]
    for proc, dtype in zip(procs, dtypes):
        _assert_clean(_finish(proc), dtype, warnings=1, needle="compile")
    for dtype in ("float32", "float64"):   # a crossed entry is replaced here
        _assert_clean(_run(cache, home, dtype), dtype, warnings=1, needle="compile")
    files = _snapshot(cache)
    for dtype in ("float32", "float64"):
        _assert_clean(_run(cache, home, dtype), dtype)
    assert _snapshot(cache) == files
    assert not [f for f in files if ".tmp" in f]


def _read_only_prefix(paths):
    """A command prefix under which ``paths`` are read-only: chmod for a user; a read-only bind mount for root.

    root writes through any permission bits, so for root the folders are
    bind-mounted read-only in a private mount namespace (``unshare``; the
    kernel refuses every write with EROFS, as on a read-only file system).
    """
    if os.geteuid() != 0:
        for p in paths:
            for sub in [p, *p.rglob("*")]:
                sub.chmod(sub.stat().st_mode & ~0o222)
        return []
    unshare = shutil.which("unshare")
    if not unshare or subprocess.run([unshare, "-rm", "true"], capture_output=True).returncode != 0:
        pytest.skip("running as root without user namespaces (unshare -rm): no folder can be made read-only")
    mounts = " && ".join(f"mount --bind {shlex.quote(str(p))} {shlex.quote(str(p))} && "
                         f"mount -o remount,bind,ro {shlex.quote(str(p))} {shlex.quote(str(p))}" for p in paths)
    return [unshare, "-rm", "sh", "-c", mounts + ' && exec "$@"', "sh"]


def _writable_again(paths):
    for p in paths:
        for sub in [p, *p.rglob("*")]:
            sub.chmod(sub.stat().st_mode | 0o200)


@pytest.mark.parametrize("what", ["cache", "cache, install and home"])
def test_a_read_only_cache_runs_with_at_most_one_warning(tmp_path, warm_cache, what):
    """A warm cache that cannot be written (a shared, read-only one); then also a read-only install and home.

    numba skips a cache folder it cannot write and uses the next one (the
    package's __pycache__, the home's); with none left it raised at import
    ("no locator available"): now the kernels are compiled in the process,
    with one warning line naming NUMBA_CACHE_DIR.
    """
    cache, home = warm_cache[0], tmp_path / "home"
    home.mkdir()
    package = tmp_path / "install"   # a copy: numba may write into its __pycache__ when that is writable
    shutil.copytree(HERE / "noiselab", package / "noiselab", ignore=shutil.ignore_patterns("__pycache__"))
    read_only = [cache] if what == "cache" else [cache, package, home]
    before = _snapshot(cache)
    prefix = _read_only_prefix(read_only)
    try:
        result = _run(cache, home, prefix=prefix, package=package)
    finally:
        _writable_again(read_only)
    _assert_clean(result, "float64", warnings=1 if what != "cache" else 0, needle="NUMBA_CACHE_DIR")
    if what != "cache":
        assert len(result[2]) == 1   # said once, however many kernels
    assert _snapshot(cache) == before


def _damage(cache, pattern, how):
    files = sorted(cache.rglob(pattern))
    assert files, pattern
    rng = np.random.default_rng(0)
    for f in files:
        data = f.read_bytes()
        f.write_bytes({"empty": b"", "half": data[: len(data) // 2],
                       "garbage": rng.integers(0, 256, len(data), dtype=np.uint8).tobytes()}[how])
    return files


@pytest.mark.parametrize("pattern, how", [("*.nbi", "empty"), ("*.nbi", "half"), ("*.nbc", "half"),
                                          ("*.nbc", "garbage")])
def test_a_damaged_cache_is_recompiled_and_repaired(tmp_path, warm_cache, pattern, how):
    """Truncated or overwritten numba index/data files: recompiled, then repaired."""
    cache, home = warm_cache
    _damage(cache, pattern, how)
    _assert_clean(_run(cache, home), "float64", warnings=1, needle="compile")
    files = _snapshot(cache)
    _assert_clean(_run(cache, home), "float64")   # repaired: nothing printed, nothing written
    assert _snapshot(cache) == files
