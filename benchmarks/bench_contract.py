"""What the bad-input checks cost on the hot paths.

    python3 benchmarks/bench_contract.py [--repeats 7]

Writes ``benchmarks/bench_contract.md`` beside this script. For each case the
checked call and the same call with the new check replaced by a no-op are
timed back to back in one process, one thread, interleaved; the reported
ratio is the median over ``--repeats`` (>= 5) of checked time / unchecked
time (1.00: free). The checks measured:

- ``check_reach``: the overflow check of ``x * frequency`` that scattered
  lattice points now get in every dimension (min and max over the points);
- envelope validation: finiteness and range of the frequency vectors;
- ``power_spectrum``'s range check of the field (max and min);
- ``check_jac_finite``: the pass over a derivative's output that refuses
  an overflowed one (amplitude * frequency too large), on points and grids.
"""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

import noiselab.lattice.checks as checks  # noqa: E402
import noiselab.spectral.envelopes as env  # noqa: E402
from noiselab import LatticeNoise  # noqa: E402
from noiselab.analysis import power_spectrum  # noqa: E402
from noiselab.spectral import frequency_vectors  # noqa: E402
from noiselab.lab.measure import header_lines, interleaved, run_info  # noqa: E402


def ratio(fn, patch, repeats):
    """Median of checked / unchecked time, interleaved rounds; ``patch()`` returns an undo callable.

    The unchecked candidate patches the check out, calls, and undoes the patch (two attribute writes, well
    under a microsecond, inside its timing). Returns (ratio, median checked seconds).
    """
    def unchecked():
        undo = patch()
        try:
            return fn()
        finally:
            undo()

    t = interleaved({"checked": fn, "unchecked": unchecked}, repeats=repeats, min_repeats=5)
    return t.ratio("checked", "unchecked"), t["checked"]


def no_reach():
    old = checks.check_reach
    checks.check_reach = lambda *a, **k: None
    return lambda: setattr(checks, "check_reach", old)


def no_jac_finite():
    old = checks.check_jac_finite
    checks.check_jac_finite = lambda *a, **k: None
    return lambda: setattr(checks, "check_jac_finite", old)


def no_env_checks():
    old = env._frequencies
    env._frequencies = lambda w, names=None: [np.asarray(x) for x in w]
    return lambda: setattr(env, "_frequencies", old)


def build_parser():
    """The command line (``--repeats``)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7, help="interleaved rounds (5 at least)")
    return ap


def main(argv=None):
    args = build_parser().parse_args(argv)
    repeats = max(5, args.repeats)
    info = run_info(f"python3 benchmarks/bench_contract.py --repeats {repeats}")
    rng = np.random.default_rng(0)
    rows = []
    for dim, kernel in [(1, "linear"), (2, "linear"), (2, "cubic"), (4, "cubic")]:
        noise = LatticeNoise(dim, kernel=kernel, rng=1)
        pts = rng.uniform(-100, 100, (1_000_000 // dim, dim))
        r, t = ratio(lambda: noise(pts), no_reach, repeats)
        rows.append((f"LatticeNoise({dim}, kernel={kernel!r}) on {len(pts):,} points", r, t))
    # the derivative paths: the finiteness check of the derivative (one pass over it)
    for dim in (2, 3):
        noise = LatticeNoise(dim, rng=1)
        pts = rng.uniform(-100, 100, (1_000_000 // dim, dim))
        r, t = ratio(lambda: noise.gradient(pts), no_jac_finite, repeats)
        rows.append((f"LatticeNoise({dim}).gradient on {len(pts):,} points", r, t))
    noise = LatticeNoise(2, rng=1)
    r, t = ratio(lambda: noise.gradient_grid((1024, 1024), [(0, 64), (0, 64)]), no_jac_finite, repeats)
    rows.append(("LatticeNoise(2).gradient_grid 1024 x 1024", r, t))
    wt, wy, wx = frequency_vectors((64, 256, 256))
    r, t = ratio(lambda: env.tent(wt, wy, wx, c=1.0, tol=np.pi / 64), no_env_checks, repeats)
    rows.append(("envelopes.tent on a (64, 256, 129) half spectrum", r, t))
    field = rng.standard_normal((1024, 1024))
    # the range check's two passes, against the whole spectrum
    t = interleaved({"call": lambda: power_spectrum(field), "minmax": lambda: (field.min(), field.max())},
                    repeats=repeats, min_repeats=5)
    rows.append(("power_spectrum 1024 x 1024: min+max / whole call", 1 + t.ratio("minmax", "call"), t["call"]))

    lines = [
        "# Cost of the bad-input checks",
        "",
        *header_lines(info, timing="one thread"),
        "",
        "Ratio = checked time / time with the check replaced by a no-op, median of the per-round ratios of "
        f"{repeats} interleaved rounds (one warm-up round, order rotated each round, "
        "`noiselab.lab.measure.interleaved`).",
        "",
        "| case | checked / unchecked | checked time (s) |",
        "| --- | ---: | ---: |",
    ]
    lines += [f"| {name} | {r:.3f} | {t:.4f} |" for name, r, t in rows]
    out = Path(__file__).with_suffix(".md")
    out.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
