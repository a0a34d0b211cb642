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
# pyfastnoisesimd ships no wheel for this Python: it builds from source and
# needs wheel plus numpy's headers, without build isolation (so it compiles
# against the numpy the venv runs). At run time it calls np.product, removed in
# NumPy 2: the benchmarks add the shim `np.product = np.prod` before importing it.
# Failures are reported and not fatal: the benchmarks list the peer as missing.
.venv-peers/bin/python -m pip install -q wheel
numpy_include=$(.venv-peers/bin/python -c "import numpy; print(numpy.get_include())")
CFLAGS="-I$numpy_include" .venv-peers/bin/python -m pip install -q --no-build-isolation pyfastnoisesimd \
    || echo "setup_peers.sh: could not install pyfastnoisesimd (skipped)"
