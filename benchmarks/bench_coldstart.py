"""Time to a first result: ``import noiselab`` plus the first call of each common path, cold and warm numba cache.

Run from the repository root::

    python benchmarks/bench_coldstart.py [--paths floor points3 grid2 fbm2 int32] [--runs 1] [--kernels] [--speed 7]
    python benchmarks/bench_coldstart.py --against <checkout of the last release> --runs 7

``floor``: what a first call costs before any kernel of noiselab's: import
numba and compile a one-line kernel, numba's first compilation in the
process (its registries; ``numba.np.arraymath`` imports scipy.linalg to look
for BLAS). Timed with the other paths, it adds a column: each path less the
floor of the same run, the part that noiselab's kernels and Python decide.

``--against``: each cold first call is timed with this tree and with
another checkout, interleaved run by run (the order alternating), so that
both columns see the same machine: on a shared machine the spread of one
path's cold time is 0.5-1.5 s, more than most changes to it.

Writes ``benchmarks/bench_coldstart.md`` beside this script. Each case runs
in a fresh Python process (``import noiselab`` included) and is measured as
the CPU time (user + system) of that child process, from
``resource.getrusage(RUSAGE_CHILDREN)`` before and after: CPU time does not
grow when the shared machine is busy, wall time does. "cold" is a process
whose ``NUMBA_CACHE_DIR`` is a new empty folder: everything the call needs
is compiled. "warm" is a second process on the same folder: numba loads the
machine code from its cache. The child also reports how many numba
specialisations it compiled or loaded (``len(fn.signatures)`` summed over
every dispatcher in ``noiselab.lattice``'s modules and in their dicts of
compiled variants; callees compiled only as part of another kernel are not
counted), which says where the cold time goes. ``--kernels`` times each
numba compilation of one more cold run (numba's ``numba:compile`` events)
and prints numba's own timing of its slowest passes over each of
noiselab's kernels (``pipeline_times``: lowering with LLVM's optimisation,
type inference, inlining).
"""
from __future__ import annotations

import argparse
import os
import resource
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
# the checkout the children import noiselab from (`--root`: another tree, e.g. an export of an older commit)
SOURCE = ROOT

from noiselab.lab.measure import header_lines, markdown_table, run_info  # noqa: E402

# the first call of each common path, as a user writes it (after `import numpy as np`, `import noiselab as nl`)
PATHS = {
    # what no kernel of noiselab's can remove: importing numba and its first compilation in a process (its type
    # and lowering registries; numba.np.arraymath imports scipy.linalg to look for BLAS), here of a one-line kernel
    "floor": ("numba's fixed cost: `numba.njit(lambda x: x + 1)(1)`, numba's first compilation in a process",
              "import numba\n"
              "numba.njit(lambda x: x + 1)(1)"),
    "points3": ("`LatticeNoise(3)(pts)`, 1e5 random 3-D points",
                "pts = np.random.default_rng(0).random((100_000, 3)) * 32\n"
                "nl.LatticeNoise(3)(pts)"),
    "points2": ("`LatticeNoise(2)(pts)`, 1e5 random 2-D points",
                "pts = np.random.default_rng(0).random((100_000, 2)) * 32\n"
                "nl.LatticeNoise(2)(pts)"),
    "jacobian3": ("`LatticeNoise(3).jacobian(pts)`, 1e3 random 3-D points",
                  "pts = np.random.default_rng(0).random((1000, 3)) * 32\n"
                  "nl.LatticeNoise(3).jacobian(pts)"),
    "grid2": ("`LatticeNoise(2).grid((512, 512), [(0, 32), (0, 32)])`",
              "nl.LatticeNoise(2).grid((512, 512), [(0, 32), (0, 32)])"),
    "fbm2": ("`fractal_sum(LatticeNoise(2), Grid((512, 512), ((0, 32), (0, 32))), octaves=6)`",
             "from noiselab.lattice import Grid\n"
             "nl.fractal_sum(nl.LatticeNoise(2), Grid((512, 512), ((0, 32), (0, 32))), octaves=6)"),
    "fbm1": ("`fractal_sum(LatticeNoise(1), Grid((4096,), ((0, 64),)), 6)`",
             "from noiselab.lattice import Grid\n"
             "nl.fractal_sum(nl.LatticeNoise(1), Grid((4096,), ((0, 64),)), 6)"),
    "grid2-all": ("every fused 2-D grid kernel: 64² grids, tap counts 1-4 x both bases x float32/float64 (16 calls)",
                  "for k in ['box', 'linear', 'quadratic', 'cubic']:\n"
                  "    for b in ('value', 'gradient'):\n"
                  "        for dt in (np.float64, np.float32):\n"
                  "            nl.LatticeNoise(2, kernel=k, basis=b).grid((64, 64), [(0, 8), (0, 8)], dtype=dt)"),
    "int32": ("`LatticeNoise(3, hash=\"integer\")(pts.astype(np.float32))`, 1e5 points",
              "pts = np.random.default_rng(0).random((100_000, 3)) * 32\n"
              "nl.LatticeNoise(3, hash=\"integer\")(pts.astype(np.float32))"),
    "intfbm2": ("`fractal_sum(LatticeNoise(2, kernel=\"quintic\", hash=\"integer\"), Grid((512, 512), ((0, 16), "
                "(0, 16))), 6, dtype=np.float32)`",
                "from noiselab.lattice import Grid\n"
                "nl.fractal_sum(nl.LatticeNoise(2, kernel='quintic', hash='integer'), "
                "Grid((512, 512), ((0, 16), (0, 16))), 6, dtype=np.float32)"),
}

# the child's view of noiselab's kernels: every dispatcher of noiselab.lattice's modules, module-level or kept in a
# dict of compiled variants (e.g. _jit._POINTS), each once
DISPATCHERS = """
import sys as _sys

def _dispatchers():
    _seen = {}
    for _name, _mod in list(_sys.modules.items()):
        if _name.startswith("noiselab.lattice"):
            for _v in list(vars(_mod).values()):
                for _f in (list(_v.values()) if isinstance(_v, dict) else [_v]):
                    if hasattr(_f, "signatures") and hasattr(_f, "py_func"):
                        _seen[id(_f)] = _f
    return list(_seen.values())
"""

# printed by the child after the call: the number of compiled (or cache-loaded) specialisations
COUNT = DISPATCHERS + """
print("SPECIALISATIONS", sum(len(_f.signatures) for _f in _dispatchers()))
"""


# the child's numba compilations, timed by numba's event API (nested: a kernel's time includes its callees')
LISTEN = """
import time as _time
from numba.core import event as _event

class _Compiles(_event.Listener):
    def __init__(self):
        self.start, self.done = {}, []

    def on_start(self, ev):  # the start and end events are two objects: keyed by dispatcher and argument types
        self.start[id(ev.data["dispatcher"]), str(ev.data["args"])] = _time.process_time()

    def on_end(self, ev):
        t0 = self.start.pop((id(ev.data["dispatcher"]), str(ev.data["args"])))
        self.done.append((_time.process_time() - t0, ev.data["dispatcher"].py_func.__qualname__))

_compiles = _Compiles()
_event.register("numba:compile", _compiles)
"""
REPORT = DISPATCHERS + """
for _t, _name in sorted(_compiles.done, reverse=True)[:6]:
    print("COMPILE", round(_t, 2), _name)
# numba's own timing of each pass of noiselab's kernels' compilations (init + run + finalize, CPU seconds)
for _f in _dispatchers():
    for _cres in list(_f.overloads.values()):
        for _passes in _cres.metadata.get("pipeline_times", {}).values():
            _top = sorted(((t.init + t.run + t.finalize, k.split("_", 1)[1]) for k, t in _passes.items()),
                          reverse=True)[:4]
            print("PASSES", _f.py_func.__qualname__.split(".")[-1], "; ".join(f"{k} {t:.2f}" for t, k in _top))
"""


SPEED = """
import time
from noiselab.lattice import Grid
from noiselab.lab.measure import interleaved
pts = np.random.default_rng(0).random((1_000_000, 3)) * 32
p32 = pts.astype(np.float32)
cands = {}
for h in ("table", "integer"):
    for label, kw in (("value cubic", {}), ("gradient quintic", {"basis": "gradient"}),
                      ("value catmull-rom", {"kernel": "catmull-rom"})):
        noise = nl.LatticeNoise(3, hash=h, **kw)
        cands[f"1e6 3-D points, {h} hash, {label}"] = (lambda n: lambda: n(pts))(noise)
ni = nl.LatticeNoise(3, hash="integer")
cands["1e6 3-D float32 points, integer hash, value cubic"] = lambda: ni(p32)
n2, n2g, n3 = nl.LatticeNoise(2), nl.LatticeNoise(2, basis="gradient"), nl.LatticeNoise(3)
n3g = nl.LatticeNoise(3, basis="gradient")
g2, g3 = Grid((512, 512), ((0, 32), (0, 32))), Grid((128, 128, 128), ((0, 16), (0, 16), (0, 16)))
cands["512^2 6-octave fBm, value cubic"] = lambda: nl.fractal_sum(n2, g2, octaves=6)
cands["512^2 6-octave fBm, gradient quintic"] = lambda: nl.fractal_sum(n2g, g2, octaves=6)
cands["128^3 6-octave fBm, value cubic"] = lambda: nl.fractal_sum(n3, g3, octaves=6)
cands["128^3 6-octave fBm, gradient quintic"] = lambda: nl.fractal_sum(n3g, g3, octaves=6)
cands["floor"] = lambda: np.full(1_000_000, 1.0)
t = interleaved(cands, repeats=REPEATS, timer=time.thread_time)
for k in cands:
    print("SPEED", repr((k, t[k], t.ratio("floor", k))))
"""


def warm_speed(repeats, cache_dir):
    """Warm run times in one process (thread CPU, medians) and their ratio to the floor (1e6 float64 writes)."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir), PYTHONPATH=str(SOURCE), NUMBA_NUM_THREADS="1")
    code = "import numpy as np\nimport noiselab as nl\n" + SPEED.replace("REPEATS", str(repeats))
    proc = subprocess.run([sys.executable, "-c", code], env=env, cwd=SOURCE, capture_output=True, text=True)
    if proc.returncode:
        raise RuntimeError(f"child failed:\n{proc.stderr}")
    import ast
    return [ast.literal_eval(line[6:]) for line in proc.stdout.splitlines() if line.startswith("SPEED")]


def compile_times(code, cache_dir):
    """The child's slowest numba compilations: ``[(cpu seconds, function name)]``, callees included in callers."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir), PYTHONPATH=str(SOURCE), NUMBA_NUM_THREADS="1")
    proc = subprocess.run([sys.executable, "-c", LISTEN + "import numpy as np\nimport noiselab as nl\n" + code + REPORT],
                          env=env, cwd=SOURCE, capture_output=True, text=True)
    if proc.returncode:
        raise RuntimeError(f"child failed:\n{proc.stderr}")
    return ([(float(line.split()[1]), line.split()[2]) for line in proc.stdout.splitlines() if line.startswith("COMPILE")],
            [line[7:] for line in proc.stdout.splitlines() if line.startswith("PASSES")])


def run_child(code, cache_dir, root=None):
    """CPU seconds (user + system) of one fresh process running ``code`` with the noiselab of ``root`` (default
    :data:`SOURCE`), and its specialisation count."""
    root = SOURCE if root is None else root
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir), PYTHONPATH=str(root), NUMBA_NUM_THREADS="1",
               OMP_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run([sys.executable, "-c", "import numpy as np\nimport noiselab as nl\n" + code + COUNT],
                          env=env, cwd=root, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode:
        raise RuntimeError(f"child failed:\n{proc.stderr}")
    spec = int(proc.stdout.split("SPECIALISATIONS")[-1])
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, spec


def cold_cpu(code, root):
    """CPU seconds of one cold process (a new empty numba cache) running ``code`` with ``root``'s noiselab."""
    cache = Path(tempfile.mkdtemp(prefix="nl-cold-"))
    try:
        return run_child(code, cache, root)[0]
    finally:
        shutil.rmtree(cache, ignore_errors=True)


def side_by_side(args, info, other):
    """``--against``: the cold first calls of this tree and of ``other``, interleaved run by run; Markdown lines."""
    roots = [SOURCE, other]
    rows, medians = [], {}
    for key in args.paths:
        times = {root: [] for root in roots}
        for i in range(args.runs):
            for root in (roots if i % 2 == 0 else roots[::-1]):
                times[root].append(cold_cpu(PATHS[key][1], root))
        cells = [f"{statistics.median(t):.2f} ({min(t):.2f}-{max(t):.2f})" for t in times.values()]
        medians[key] = statistics.median(times[SOURCE])
        rows.append([PATHS[key][0]] + cells)
        print(key, *cells, flush=True)
    lines = [f"# Time to a first result, side by side{(' (' + args.label + ')') if args.label else ''}", ""]
    lines += header_lines(info)
    lines += ["", f"CPU seconds (user + system) of a fresh process with an empty numba cache: `import noiselab`, "
              f"then the call; the median (and range) of {args.runs} runs of each tree, interleaved run by run.", ""]
    lines += markdown_table(["first call", "this tree", f"`{other.name}`"] + ["this tree less the floor"] * ("floor" in medians),
                            over_floor(rows, medians), "lrr" + "r" * ("floor" in medians))
    return lines


def over_floor(rows, medians):
    """``rows`` (one per key of ``medians``, in order) with one more column when ``floor`` was timed: each
    path's median less the floor's, measured in the same run: the part of the first call that is
    noiselab's own (its kernels' compilation, its Python) rather than numba's fixed cost."""
    if "floor" not in medians:
        return rows
    return [row + ["" if key == "floor" else f"{medians[key] - medians['floor']:.2f}"]
            for row, key in zip(rows, medians)]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--paths", nargs="+", choices=list(PATHS), default=list(PATHS), help="paths to time")
    parser.add_argument("--runs", type=int, default=1, help="cold/warm pairs per path (the median is reported)")
    parser.add_argument("--kernels", action="store_true",
                        help="also time each numba compilation of a cold run (where the cold time goes), and "
                             "numba's slowest passes over each kernel of noiselab's")
    parser.add_argument("--speed", type=int, default=0, metavar="REPEATS",
                        help="also time the warm calls in one process (REPEATS interleaved rounds, >= 5)")
    parser.add_argument("--label", default="", help="a note for the table's title (e.g. before/after)")
    parser.add_argument("--root", default=str(ROOT),
                        help="the checkout whose noiselab the children import (default: this one)")
    parser.add_argument("--against", metavar="ROOT",
                        help="another checkout: time each cold call with both trees, interleaved run by run")
    parser.add_argument("--output", default=str(Path(__file__).with_suffix(".md")), help="Markdown file to write")
    args = parser.parse_args(argv)
    global SOURCE
    SOURCE = Path(args.root).resolve()
    command = "python benchmarks/bench_coldstart.py " + shlex.join(argv if argv is not None else sys.argv[1:])
    info = run_info(command.strip())
    if args.against:
        Path(args.output).write_text("\n".join(side_by_side(args, info, Path(args.against).resolve())) + "\n")
        print(f"wrote {args.output}")
        return
    base = run_child("", Path(tempfile.mkdtemp(prefix="nl-cold-")))[0]  # `import noiselab` alone
    rows, medians = [], {}
    for key in args.paths:
        what, code = PATHS[key]
        colds, warms, specs = [], [], 0
        for _ in range(args.runs):
            cache = Path(tempfile.mkdtemp(prefix="nl-cold-"))
            try:
                cold, specs = run_child(code, cache)
                warm, _ = run_child(code, cache)
            finally:
                shutil.rmtree(cache, ignore_errors=True)
            colds.append(cold)
            warms.append(warm)
            print(f"{key}: cold {cold:.2f} s, warm {warm:.2f} s CPU, {specs} specialisations", flush=True)
        colds.sort()
        warms.sort()
        medians[key] = statistics.median(colds)
        rows.append([what, f"{colds[len(colds) // 2]:.1f}", f"{warms[len(warms) // 2]:.1f}", str(specs)])
    lines = [f"# Time to a first result{(' (' + args.label + ')') if args.label else ''}", ""]
    lines += header_lines(info)
    lines += ["", "CPU seconds (user + system) of a fresh process: `import noiselab`, then the call. "
              "Cold: an empty numba cache; warm: a second process on the same cache. "
              f"`import noiselab` alone: {base:.1f} s. Specialisations: numba signatures compiled "
              "(cold) or loaded (warm) by `noiselab.lattice`'s kernels.", ""]
    lines += markdown_table(["first call", "cold (s CPU)", "warm (s CPU)", "specialisations"]
                            + ["cold less the floor"] * ("floor" in medians), over_floor(rows, medians),
                            "lrrr" + "r" * ("floor" in medians))
    if args.kernels:
        lines += ["", "Where the cold time goes: the slowest numba compilations of one more cold run, CPU seconds "
                  "(numba's `numba:compile` events; a kernel's time includes its callees' compilation).", ""]
        krows = []
        for key in args.paths:
            cache = Path(tempfile.mkdtemp(prefix="nl-cold-"))
            try:
                top, passes = compile_times(PATHS[key][1], cache)
            finally:
                shutil.rmtree(cache, ignore_errors=True)
            krows.append([key, "; ".join(f"`{name}` {t:.1f}" for t, name in top[:4]), "<br>".join(passes)])
            print(key, krows[-1][1], "|", krows[-1][2], flush=True)
        lines += markdown_table(["path", "compilations (s CPU)", "numba's slowest passes of the kernel (s CPU)"], krows,
                                "lll")
    if args.speed:
        cache = Path(tempfile.mkdtemp(prefix="nl-warm-"))
        try:
            rows = warm_speed(args.speed, cache)
        finally:
            shutil.rmtree(cache, ignore_errors=True)
        lines += ["", f"Warm speed: one process, {args.speed} interleaved rounds, median thread CPU time; "
                  "x floor = time of writing 1e6 float64 (`np.full`) / time of the call, paired per round (one thread, `NUMBA_NUM_THREADS=1`; points float64 unless said).", ""]
        lines += markdown_table(["call", "ms", "x floor"], [[k, f"{t * 1e3:.2f}", f"{r:.3f}"] for k, t, r in rows],
                                "lrr")
        print("\n".join(lines[-len(rows) - 2:]), flush=True)
    Path(args.output).write_text("\n".join(lines) + "\n")
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
