#!/usr/bin/env bash
# Create the benchmark environment with the peers noiselab is measured against.
# It sits beside the project (benchmarks/.venv-peers, git-ignored), sees the
# project's own dependencies through --system-site-packages, and keeps the
# peers out of noiselab's own install.
# Usage: bash benchmarks/setup_peers.sh   then   benchmarks/.venv-peers/bin/python benchmarks/<script>.py
# It takes about 80 s (wall, 63 s CPU, on the shared 2-core machine, 2026-11-27): pyfastnoisesimd has no
# wheel for this Python and is compiled from source (its SIMD variants), the rest install from wheels.
set -euo pipefail
cd "$(dirname "$0")"
[ -x .venv-peers/bin/python ] || python3 -m venv --system-site-packages .venv-peers
export PIP_DISABLE_PIP_VERSION_CHECK=1
# noiselab's own environment (install.sh's .venv, or NOISELAB_PYTHON) is not the system Python: its
# site-packages (numba among them) are added after the peers' own by a .pth file
project_python="${NOISELAB_PYTHON:-../.venv/bin/python}"
if [ -x "$project_python" ]; then
    "$project_python" -c "import sysconfig; print(sysconfig.get_paths()['purelib'])" \
        > "$(.venv-peers/bin/python -c "import sysconfig; print(sysconfig.get_paths()['purelib'])")/noiselab-env.pth"
fi
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
