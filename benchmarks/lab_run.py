"""Run the laboratory of this checkout and, with ``--publish``, replace the published ``benchmarks/RESULTS.md``.

The package's ``noiselab bench`` writes where ``--output`` says and never
into a checkout; publishing is this script's job. It imports the noiselab of
this checkout (not whichever is installed) and runs the peers with this
checkout's ``benchmarks/.venv-peers/bin/python`` (``bash
benchmarks/setup_peers.sh`` makes it)::

    python3 benchmarks/lab_run.py            # full run (2.5-5 min on 2 cores), writes out/bench/RESULTS.md
    python3 benchmarks/lab_run.py --publish  # ... into benchmarks/RESULTS.md and benchmarks/results/
    python3 benchmarks/lab_run.py --quick --output /tmp/lab
    python3 benchmarks/lab_run.py --replot   # redraw benchmarks/results/*.png from results.json, no measuring
    python3 benchmarks/lab_run.py --replot --output /tmp/lab   # ... /tmp/lab/results/*.png

``--publish`` refuses a quick run, an ``--output`` folder, and a run without
the peers (their environment missing, or ``--no-peers``) unless
``--allow-missing-peers``; a refusal is one line on stderr and status 2,
before any experiment runs.
"""
import argparse
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent          # benchmarks/ of the checkout: where the published report lives
sys.path.insert(0, str(HERE.parent))

PEERS_PYTHON = HERE / ".venv-peers" / "bin" / "python"
COMMAND = "python3 benchmarks/lab_run.py --publish"


def publish_argv(argv, *, published=HERE, peers_python=PEERS_PYTHON):
    """The ``noiselab bench`` arguments for this script's ``argv``; a ValueError says why publishing is refused."""
    parser = argparse.ArgumentParser(add_help=False)
    parser.add_argument("--publish", action="store_true")
    parser.add_argument("--allow-missing-peers", action="store_true")
    ours, rest = parser.parse_known_args(argv)
    peers = ["--peers-python", str(peers_python)] if "--peers-python" not in rest else []
    if not ours.publish:
        if ours.allow_missing_peers:
            raise ValueError("--allow-missing-peers only applies with --publish")
        return peers + rest
    if "--quick" in rest:
        raise ValueError("--publish and --quick exclude each other: quick numbers are never published")
    if "--output" in rest or any(a.startswith("--output=") for a in rest):
        raise ValueError(f"--publish writes to {published}; drop --output")
    if not ours.allow_missing_peers:
        from noiselab.lab.run import peers_missing_reason

        reason = "peers not run (--no-peers)" if "--no-peers" in rest else peers_missing_reason(peers_python)
        if reason:
            raise ValueError(f"refusing to publish without section 4 (the peers): {reason}; "
                             "run without --publish, or add --allow-missing-peers")
    return peers + rest + ["--output", str(published)]


def replot(argv, *, published=HERE):
    """Redraw the figures of a finished run from its ``results/results.json``; returns the files written."""
    parser = argparse.ArgumentParser(prog="lab_run.py --replot")
    parser.add_argument("--replot", action="store_true")
    parser.add_argument("--output", default=str(published), metavar="DIR",
                        help="the run's folder (its results/results.json is read); default benchmarks/")
    args = parser.parse_args(argv)
    from noiselab.lab.figures import read_results, write_figures

    res_dir = Path(args.output) / "results"
    return write_figures(read_results(res_dir / "results.json"), res_dir)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if "--replot" in argv:
        try:
            written = replot(argv)
        except (OSError, ValueError) as exc:  # missing, corrupt or unwritable: one line, no traceback
            print(f"lab_run: error: {exc}", file=sys.stderr)
            return 2
        for path in written:
            print(f"lab_run: wrote {path}")
        return 0
    try:
        bench_argv = publish_argv(argv)
    except ValueError as exc:
        print(f"lab_run: error: {exc}", file=sys.stderr)
        return 2
    from noiselab.cli import build_parser
    from noiselab.cli import main as noiselab_main

    if "--publish" in argv:   # the header names this script as the command that regenerates the report
        args = build_parser().parse_args(["bench", *bench_argv])
        args.report_command = COMMAND
        from noiselab.cli.bench import run

        return run(args)
    return noiselab_main(["bench", *bench_argv])


if __name__ == "__main__":
    sys.exit(main())
