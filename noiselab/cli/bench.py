"""``noiselab bench``: run the laboratory (spectral against lattice, speed against error, the peers).

An ordinary run writes ``RESULTS.md``, ``results/*.png`` and
``results/results.json`` to ``out/bench/`` under the current folder
(``out/bench-quick/`` with ``--quick``, or ``--output DIR``), from an
installed noiselab anywhere, never over the published results.
``--publish`` writes the published ``benchmarks/RESULTS.md`` of the git
checkout and its plots (run it from the checkout; without one it stops with
one line and status 2); it refuses when the peers cannot run
(``benchmarks/.venv-peers`` missing, or ``--no-peers``) unless
``--allow-missing-peers``, and then says which section was skipped. The full run takes 2.5 to 5 minutes on the 2-core development
machine (161 s in the published run), ``--quick`` about 1 to 3 minutes of
tiny sizes (65 s of CPU, 164 s wall on the loaded machine) that only show the
pipeline works.

Examples::

    noiselab bench                          # -> out/bench/RESULTS.md
    noiselab bench --publish                # -> benchmarks/RESULTS.md, with the peers
    noiselab bench --quick --output /tmp/lab
"""
from __future__ import annotations

NAME = "bench"
HELP = "Run the laboratory experiments (spectral vs lattice, Pareto sweeps, peers); --publish updates benchmarks/RESULTS.md."


def add_arguments(parser):
    parser.add_argument("--quick", action="store_true",
                        help="CI-size run: tiny sizes, 1 to 3 minutes on 2 cores (numbers not meaningful)")
    parser.add_argument("--output", default=None, metavar="DIR",
                        help="folder for RESULTS.md (plots and JSON go to DIR/results/); default out/bench, "
                             "or out/bench-quick with --quick (never the published results)")
    parser.add_argument("--no-peers", action="store_true",
                        help="skip the peers (they need benchmarks/.venv-peers: bash benchmarks/setup_peers.sh)")
    parser.add_argument("--publish", action="store_true",
                        help="write the published benchmarks/RESULTS.md and benchmarks/results/ of the git "
                             "checkout (refused without the peers unless --allow-missing-peers)")
    parser.add_argument("--allow-missing-peers", action="store_true",
                        help="with --publish: publish even when the peers cannot run, without their section")
    parser.add_argument("--dry-run", action="store_true",
                        help="check the options, the output folder and the peer environment, print what would "
                             "run, and stop")


def run(args):
    from pathlib import Path

    from ..io import prepare_output
    from ..lab.checkout import published_dir
    from ..lab.run import PublishError, default_output, peers_missing_reason, run_all

    if args.allow_missing_peers and not args.publish:
        raise ValueError("--allow-missing-peers only applies with --publish")
    if args.publish and args.quick:
        raise PublishError("--publish and --quick exclude each other: quick numbers are never published")
    if args.publish and args.output is not None:
        raise PublishError("--publish writes to benchmarks/ of the git checkout; drop --output")
    out = published_dir() if args.publish else Path(args.output) if args.output is not None else default_output(args.quick)
    if out.exists() and not out.is_dir():
        raise ValueError(f"--output must be a folder, got the file {str(out)!r}")
    prepare_output(out / "RESULTS.md", create=not args.dry_run)
    peers_reason = "peers not run (--no-peers)" if args.no_peers else peers_missing_reason()
    if args.publish and peers_reason and not args.allow_missing_peers:
        raise PublishError(f"refusing to publish without section 4 (the peers): {peers_reason}; "
                           "run without --publish, or add --allow-missing-peers")
    if peers_reason:
        print(f"bench: WARNING: section 4 (the peers) will be skipped: {peers_reason}", flush=True)
    if args.dry_run:
        print(f"bench: dry run: would run the {'quick' if args.quick else 'full'} laboratory and write "
              f"{out / 'RESULTS.md'}{' (the published results)' if args.publish else ''}")
        return 0
    import scipy.fft

    with scipy.fft.set_workers(-1):  # every core for snow, spectral_noise and the analysers (explicit counts win)
        res = run_all(quick=args.quick, output=None if args.publish else out, peers=not args.no_peers,
                      publish=args.publish, allow_missing_peers=args.allow_missing_peers,
                      log=lambda m: print(m, flush=True))
    print(f"results: {res['path']}")
    for section, why in res.get("skipped", {}).items():
        print(f"bench: WARNING: section {section} was skipped: {why}", flush=True)
    return 0
