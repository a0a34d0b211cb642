"""numba's compile cache, used as numba documents it: importing noiselab changes nothing in numba.

A cold run fills the cache and a warm one loads it without writing a file; a
read-only cache folder passes to the next folder numba can write; a cache
damaged on disk is cleared by ``noiselab cache --clear`` (numba fails on the
damaged file; the command's one line says how to recover, naming
``NUMBA_CACHE_DIR``), after which a run gives the same values, bit for bit.

Each run is a small lattice-noise evaluation in a fresh process with its own
``NUMBA_CACHE_DIR``; a cold run compiles for about 3 s of CPU time.
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
out = LatticeNoise(1, rng=5)(x, dtype=np.dtype(sys.argv[1]))
print(hashlib.sha256(out.tobytes()).hexdigest())
"""

_SUBPACKAGES = ["noiselab", "noiselab._core", "noiselab.spectral", "noiselab.lattice", "noiselab.analysis",
                "noiselab.io", "noiselab.snowfall", "noiselab.fractal", "noiselab.testing", "noiselab.fields",
                "noiselab.geometry", "noiselab.stimuli", "noiselab.lab", "noiselab.scale", "noiselab.gallery",
                "noiselab.cli"]

# every class of numba.core.caching, attribute by attribute, and the import machinery, before and after
_NO_PATCH = """
import importlib, inspect, sys
import numba.core.caching as caching

def state():
    classes = {name: {k: id(v) for k, v in vars(cls).items()}
               for name, cls in vars(caching).items() if inspect.isclass(cls)}
    return classes, [type(f).__qualname__ for f in sys.meta_path], [id(h) for h in sys.path_hooks]

before = state()
for name in sys.argv[1:]:
    importlib.import_module(name)
after = state()
changed = sorted(name for name in before[0] if before[0][name] != after[0].get(name))
print("classes:", " ".join(changed) or "-")
print("meta_path:", "same" if before[1:] == after[1:] else f"{before[1]} -> {after[1]}")
"""


def test_importing_noiselab_changes_nothing_in_numba():
    """numba's cache classes (methods, attributes) and Python's finders are the same after every import."""
    env = dict(os.environ, PYTHONPATH=str(HERE) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    out = subprocess.run([sys.executable, "-c", _NO_PATCH, *_SUBPACKAGES], capture_output=True, text=True, env=env)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:2] == ["classes: -", "meta_path: same"], out.stdout


def test_importing_noiselab_before_numba_changes_nothing_in_numba():
    """Imported first, noiselab leaves no import hook that would patch numba when numba comes."""
    code = ("import sys\nfinders = [type(f).__qualname__ for f in sys.meta_path]\n"
            + "".join(f"import {name}\n" for name in _SUBPACKAGES)
            + "print([type(f).__qualname__ for f in sys.meta_path] == finders)\n"
            "import numba.core.caching as c\n"
            "print(sorted(k for k in vars(c.Cache) if 'noiselab' in k or k.startswith('_noiselab')))\n"
            "print(c.Cache.load_overload.__module__, c.Cache.save_overload.__module__, c.Cache.__init__.__module__)\n")
    env = dict(os.environ, PYTHONPATH=str(HERE) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:3] == ["True", "[]", " ".join(["numba.core.caching"] * 3)], out.stdout


def _expected(dtype):
    from noiselab import LatticeNoise

    out = LatticeNoise(1, rng=5)(np.linspace(-7.3, 9.1, 257), dtype=np.dtype(dtype))
    return hashlib.sha256(out.tobytes()).hexdigest()


def _env(cache, home, package=HERE):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), HOME=str(home), XDG_CACHE_HOME=str(home / ".cache"),
               PYTHONPATH=str(package) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    env.pop("NUMBA_DISABLE_JIT", None)
    return env


def _run(cache, home, dtype="float64", prefix=(), package=HERE, code=_RUN, args=None):
    argv = [*prefix, sys.executable, "-c", code, dtype] if args is None else [*prefix, sys.executable, *args]
    # run outside the checkout: ``python -c`` puts the working folder first on sys.path, and from the
    # repository root that would import the checkout's noiselab instead of ``package``
    proc = subprocess.run(argv, env=_env(cache, home, package), capture_output=True, text=True, timeout=600,
                          cwd=str(cache.parent))
    return proc.returncode, proc.stdout.strip(), [ln for ln in proc.stderr.splitlines() if ln.strip()]


def _snapshot(folder):
    """Every file under ``folder`` with its size and modification time: a run that loads only changes none."""
    return {str(p.relative_to(folder)): (p.stat().st_size, p.stat().st_mtime_ns)
            for p in Path(folder).rglob("*") if p.is_file()}


def _assert_clean(result, dtype):
    rc, digest, err = result
    assert rc == 0, "\n".join(err)
    assert digest == _expected(dtype), "\n".join(err)
    assert not any("Traceback" in ln for ln in err), err


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
    under a hash of its source file's folder.
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
    _assert_clean(_run(cache, home), "float64")   # warm: nothing compiled or written
    assert _snapshot(cache) == files


def _read_only_prefix(paths):
    """A command prefix under which ``paths`` are read-only: chmod for a user; a read-only bind mount for root."""
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


def test_a_read_only_cache_is_passed_over(tmp_path, warm_cache):
    """A warm cache that cannot be written (a shared, read-only one): numba uses it or the next folder; same values."""
    cache, home = warm_cache[0], tmp_path / "home"
    home.mkdir()
    package = tmp_path / "install"   # a copy: numba may write into its __pycache__
    shutil.copytree(HERE / "noiselab", package / "noiselab", ignore=shutil.ignore_patterns("__pycache__"))
    before = _snapshot(cache)
    prefix = _read_only_prefix([cache])
    try:
        result = _run(cache, home, prefix=prefix, package=package)
    finally:
        _writable_again([cache])
    _assert_clean(result, "float64")
    assert _snapshot(cache) == before


def test_noiselab_cache_lists_and_clears_the_kernels_cache(warm_cache):
    """``noiselab cache`` names the folders numba filled; ``--clear`` empties them; a run fills them again."""
    cache, home = warm_cache
    rc, out, err = _run(cache, home, args=["-m", "noiselab", "cache"])
    assert rc == 0, err
    listed = [Path(line) for line in out.splitlines()]
    nb = [p for p in cache.rglob("*") if p.suffix in (".nbi", ".nbc")]
    assert nb and all(any(parent in listed for parent in p.parents) for p in nb), (listed, nb)
    rc, out, err = _run(cache, home, args=["-m", "noiselab", "cache", "--clear"])
    assert rc == 0 and out.startswith("noiselab cache: removed "), (out, err)
    assert not [p for p in cache.rglob("*") if p.suffix in (".nbi", ".nbc")]
    _assert_clean(_run(cache, home), "float64")   # compiled anew, same values
    assert [p for p in cache.rglob("*") if p.suffix in (".nbi", ".nbc")]


def _damage(cache, pattern, how):
    files = sorted(cache.rglob(pattern))
    assert files, pattern
    rng = np.random.default_rng(0)
    for f in files:
        data = f.read_bytes()
        f.write_bytes({"empty": b"", "half": data[: len(data) // 2],
                       "garbage": rng.integers(0, 256, len(data), dtype=np.uint8).tobytes()}[how])
    return files


_CLI_RUN = ["-m", "noiselab", "noise", "--dims", "1", "--size", "64", "--output"]


def test_a_damaged_cache_is_named_and_cleared_by_noiselab_cache(tmp_path, warm_cache):
    """A truncated index makes numba fail; the command says to clear the cache; after ``--clear`` it runs."""
    cache, home = warm_cache
    out_file = tmp_path / "curve.npy"
    rc, _, err = _run(cache, home, args=[*_CLI_RUN, str(out_file)])   # the command's own kernels, cached
    assert rc == 0, err
    _damage(cache, "*.nbi", "half")
    rc, _, err = _run(cache, home, args=[*_CLI_RUN, str(out_file)])
    assert rc == 2 and len(err) == 1, err   # numba raises reading the damaged index: one line naming the cure
    assert "noiselab cache --clear" in err[0] and "NUMBA_CACHE_DIR" in err[0], err
    rc, _, err = _run(cache, home, args=["-m", "noiselab", "cache", "--clear"])
    assert rc == 0, err
    rc, _, err = _run(cache, home, args=[*_CLI_RUN, str(out_file)])
    assert rc == 0 and not err, err
    _assert_clean(_run(cache, home), "float64")
