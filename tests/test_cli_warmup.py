"""``noiselab warmup`` fills numba's compile cache: a later process loads the kernels and compiles none.

Each run is a fresh process with its own ``NUMBA_CACHE_DIR``; the control
is the same first call on an empty cache, which must compile.
"""
import os
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent

# the default 3-D point call, then the compile statistics of the kernels it ran
_FIRST_CALL = """
import numpy as np
from noiselab import LatticeNoise
from noiselab.lattice import _jit
LatticeNoise(3)(np.random.default_rng(1).random((1 << 15, 3)) * 9)
hits = misses = 0
for fn in _jit._POINTS.values():
    hits += sum(fn.stats.cache_hits.values())
    misses += sum(fn.stats.cache_misses.values())
print(hits, misses)
"""


def _run(args, cache, tmp_path):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache), PYTHONPATH=str(HERE))
    env.pop("NUMBA_DISABLE_JIT", None)
    done = subprocess.run([sys.executable, *args], env=env, cwd=tmp_path, capture_output=True, text=True,
                          timeout=600, check=True)
    return done.stdout


def _cache_files(listing, cache):
    """The numba index files in the folders that ``noiselab cache`` lists inside ``cache`` (``NUMBA_CACHE_DIR``).

    (It also lists the ``__pycache__`` folders beside the sources, which the rest of a test run may fill when
    it runs without ``NUMBA_CACHE_DIR``, as CI does: they say nothing about this test's cache.)
    """
    return sorted(p.name for line in listing.splitlines()
                  if Path(line).is_dir() and Path(line).resolve().is_relative_to(Path(cache).resolve())
                  for p in Path(line).glob("*.nbi"))


def test_warmup_fills_the_cache_and_a_later_first_call_compiles_nothing(tmp_path):
    cold, warmed = tmp_path / "cold", tmp_path / "warmed"
    # the control: on an empty cache the first call compiles its kernel
    hits, misses = map(int, _run(["-c", _FIRST_CALL], cold, tmp_path).split())
    assert misses >= 1 and hits == 0
    # warmup on another empty cache: the listing of `noiselab cache` gains the lattice kernels' index files
    assert _cache_files(_run(["-m", "noiselab", "cache"], warmed, tmp_path), warmed) == []
    printed = _run(["-m", "noiselab", "warmup", "--only", "points3", "--jobs", "1"], warmed, tmp_path)
    assert "points3" in printed and "1 path(s) compiled" in printed
    files = _cache_files(_run(["-m", "noiselab", "cache"], warmed, tmp_path), warmed)
    assert any(name.startswith("_jit.") for name in files), files
    # and a new process's first call loads every kernel it runs from there
    hits, misses = map(int, _run(["-c", _FIRST_CALL], warmed, tmp_path).split())
    assert hits >= 1 and misses == 0
