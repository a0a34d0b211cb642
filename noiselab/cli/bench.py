"""``noiselab bench``: run the laboratory (spectral against lattice, speed against error, the peers).

A run writes ``RESULTS.md``, ``results/*.png`` and ``results/results.json``
to ``out/bench/`` under the current folder (``out/bench-quick/`` with
``--quick``, or ``--output DIR``), from an installed noiselab anywhere. The
package writes into no git checkout: the published ``benchmarks/RESULTS.md``
is the checkout's business (``python benchmarks/lab_run.py --publish``). The
peers run with ``--peers-python`` (an interpreter with them installed; in a
checkout ``benchmarks/.venv-peers/bin/python``, made by ``bash
benchmarks/setup_peers.sh``); without it their section says it was skipped.
The full run takes 2.5 to 5 minutes on the 2-core development machine (161 s
in the published run), ``--quick`` about 1 to 3 minutes of tiny sizes (65 s
of CPU, 164 s wall on the loaded machine) that only show the pipeline works.

Examples::

    noiselab bench                          # -> out/bench/RESULTS.md
    noiselab bench --quick --output /tmp/lab
"""
from __future__ import annotations

NAME = "bench"
HELP = "Run the laboratory experiments (spectral vs lattice, Pareto sweeps, peers) and write RESULTS.md."


def add_arguments(parser):
    parser.add_argument("--quick", action="store_true",
                        help="CI-size run: tiny sizes, 1 to 3 minutes on 2 cores (numbers not meaningful)")
    parser.add_argument("--output", default=None, metavar="DIR",
                        help="folder for RESULTS.md (plots and JSON go to DIR/results/); default out/bench, "
                             "or out/bench-quick with --quick")
    parser.add_argument("--no-peers", action="store_true", help="skip the peers")
    parser.add_argument("--peers-python", default=None, metavar="PYTHON",
                        help="interpreter of an environment with the peers installed (in a checkout: "
                             "benchmarks/.venv-peers/bin/python, made by bash benchmarks/setup_peers.sh); "
                             "without it the peers are skipped")
    parser.add_argument("--dry-run", action="store_true",
                        help="check the options, the output folder and the peer interpreter, print what would "
                             "run, and stop")


def run(args):
    from pathlib import Path

    from ..io import prepare_output
    from ..lab.run import default_output, peers_missing_reason, run_all

    out = Path(args.output) if args.output is not None else default_output(args.quick)
    if out.exists() and not out.is_dir():
        raise ValueError(f"--output must be a folder, got the file {str(out)!r}")
    prepare_output(out / "RESULTS.md", create=not args.dry_run)
    peers_reason = "peers not run (--no-peers)" if args.no_peers else peers_missing_reason(args.peers_python)
    if peers_reason:
        print(f"bench: WARNING: section 4 (the peers) will be skipped: {peers_reason}", flush=True)
    if args.dry_run:
        print(f"bench: dry run: would run the {'quick' if args.quick else 'full'} laboratory and write "
              f"{out / 'RESULTS.md'}")
        return 0
    import scipy.fft

    with scipy.fft.set_workers(-1):  # every core for snow, spectral_noise and the analysers (explicit counts win)
        res = run_all(quick=args.quick, output=out, peers=not args.no_peers, peers_python=args.peers_python,
                      log=lambda m: print(m, flush=True), command=getattr(args, "report_command", None))
    print(f"results: {res['path']}")
    for section, why in res.get("skipped", {}).items():
        print(f"bench: WARNING: section {section} was skipped: {why}", flush=True)
    return 0
