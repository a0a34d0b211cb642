"""``noiselab bench``: run the laboratory (spectral against lattice, speed against error, the peers).

Writes ``benchmarks/RESULTS.md``, ``benchmarks/results/*.png`` and
``benchmarks/results/results.json`` (or under ``--output``). The full run
takes about ten minutes on a 2-core machine; ``--quick`` takes well under a
minute and only shows that the pipeline works.

Examples::

    noiselab bench                          # regenerate benchmarks/RESULTS.md
    noiselab bench --quick --output /tmp/lab
    noiselab bench --no-peers
"""
from __future__ import annotations

NAME = "bench"
HELP = "Run the laboratory experiments (spectral vs lattice, Pareto sweeps, peers) and write benchmarks/RESULTS.md."


def add_arguments(parser):
    parser.add_argument("--quick", action="store_true", help="CI-size run: tiny sizes, seconds (numbers not meaningful)")
    parser.add_argument("--output", default=None, metavar="DIR",
                        help="folder for RESULTS.md (plots and JSON go to DIR/results/); default: benchmarks/ of "
                             "this checkout, or out/bench-quick/ with --quick (never the published results)")
    parser.add_argument("--no-peers", action="store_true",
                        help="skip the peers (they need benchmarks/.venv-peers: bash benchmarks/setup_peers.sh)")


def run(args):
    from pathlib import Path

    from ..lab.run import run_all

    if args.output is not None:
        out = Path(args.output)
        if out.exists() and not out.is_dir():
            raise ValueError(f"--output must be a folder, got the file {str(out)!r}")
        out.mkdir(parents=True, exist_ok=True)
    import scipy.fft

    with scipy.fft.set_workers(-1):  # every core for snow, spectral_noise and the analysers (explicit counts win)
        res = run_all(quick=args.quick, output=args.output, peers=not args.no_peers,
                      log=lambda m: print(m, flush=True))
    print(f"results: {res['path']}")
    return 0
