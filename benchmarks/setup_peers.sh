#!/usr/bin/env bash
# Create the benchmark environment with the peers noiselab is measured against.
# It sits beside the project (benchmarks/.venv-peers, git-ignored), sees the
# project's own dependencies through --system-site-packages, and keeps the
# peers out of noiselab's own install.
# Usage: bash benchmarks/setup_peers.sh   then   benchmarks/.venv-peers/bin/python benchmarks/<script>.py
set -euo pipefail
cd "$(dirname "$0")"
[ -x .venv-peers/bin/python ] || python3 -m venv --system-site-packages .venv-peers
export PIP_DISABLE_PIP_VERSION_CHECK=1
.venv-peers/bin/python -m pip install -q -r requirements-peers.txt
# Packages that may fail to build on a given Python/NumPy: installed one by one, failures reported, not fatal.
for optional in pyfastnoisesimd; do
    .venv-peers/bin/python -m pip install -q "$optional" || echo "setup_peers.sh: could not install $optional (skipped)"
done
