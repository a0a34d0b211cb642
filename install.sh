#!/usr/bin/env bash
# Install noiselab and everything it needs on a fresh machine:
#   - system libraries for headless 3-D rendering (VTK's EGL window on Mesa's
#     software renderer; without them VTK crashes the interpreter instead of raising),
#     and python3-venv where the system Python lacks it;
#   - the noiselab package itself (editable), with optional extras, into a
#     virtual environment: the project's own `.venv/`, or the virtualenv / conda
#     env that is active when this runs (then `.venv` is made a link to it).
# Either way `.venv/bin/noiselab` and `.venv/bin/python` run the installed noiselab,
# so the distribution's Python is never touched (PEP 668).
# Usage: ./install.sh            # the package and its run-time dependencies
#        ./install.sh test       # ... plus the test extras (pytest, hypothesis, dask, the docs tools, chromium)
#        ./install.sh docs       # ... plus the documentation tools (sphinx, numpydoc, sphinx-gallery, theme)
#        ./install.sh dask       # ... plus dask, distributed and zarr
set -euo pipefail
cd "$(dirname "$0")"

say() { echo "install.sh: $*"; }
die() { echo "install.sh: error: $*" >&2; exit 1; }

extras="${1:-}"
case "$extras" in
    "" | test | dask | docs) ;;
    *) die "unknown extra '$extras' (expected nothing, 'test', 'docs' or 'dask')" ;;
esac

# --- which environment -------------------------------------------------------
active=""
if [ -n "${VIRTUAL_ENV:-}" ] && [ -x "${VIRTUAL_ENV}/bin/python" ]; then
    active="$VIRTUAL_ENV"
elif [ -n "${CONDA_PREFIX:-}" ] && [ -x "${CONDA_PREFIX}/bin/python" ]; then
    active="$CONDA_PREFIX"
fi
if [ -n "$active" ] && [ "$(cd "$active" && pwd -P)" = "$(cd .venv 2>/dev/null && pwd -P || true)" ]; then
    active=""   # the active env is this project's own .venv: keep it as it is
fi

# a .venv left half-made (e.g. by `python3 -m venv` without ensurepip: a python but no pip) is made again
if [ -z "$active" ] && [ -d .venv ] && [ ! -L .venv ] && ! .venv/bin/python -m pip --version >/dev/null 2>&1; then
    [ -f .venv/.noiselab-install ] || die ".venv exists without pip and was not made by install.sh; move it away first"
    say "the virtual environment .venv is incomplete (no pip): making it again"
    rm -rf .venv
fi

# the Python that builds .venv: the first python3 on PATH that is 3.11 or newer
base_python=""
if [ -z "$active" ] && [ ! -x .venv/bin/python ]; then
    for candidate in python3 python3.13 python3.12 python3.11; do
        if command -v "$candidate" >/dev/null 2>&1 \
           && "$candidate" -c 'import sys; sys.exit(sys.version_info < (3, 11))' 2>/dev/null; then
            base_python="$(command -v "$candidate")"
            break
        fi
    done
    [ -n "$base_python" ] || die "noiselab needs Python 3.11 or newer (python3 on PATH is $(python3 --version 2>&1 || echo missing))"
fi

# --- system packages ---------------------------------------------------------
system_packages=(libegl1 libgl1-mesa-dri)
# the gallery test opens index.html in real headless Chromium
[ "$extras" = test ] && system_packages+=(chromium)
if [ -n "$base_python" ] && ! "$base_python" -c 'import venv, ensurepip' >/dev/null 2>&1; then
    # Debian and Ubuntu ship venv's pip bootstrap (ensurepip) in a separate package
    version="$("$base_python" -c 'import sys; print("%d.%d" % sys.version_info[:2])')"
    if apt-cache show "python${version}-venv" >/dev/null 2>&1; then
        system_packages+=("python${version}-venv")
    else
        system_packages+=(python3-venv)
    fi
fi
missing=()
if command -v dpkg >/dev/null 2>&1; then
    for pkg in "${system_packages[@]}"; do
        dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
    done
else
    say "not a Debian/Ubuntu system: install the equivalents of ${system_packages[*]} yourself if they are missing"
fi
if [ ${#missing[@]} -gt 0 ]; then
    command -v apt-get >/dev/null 2>&1 || die "please install these system packages first: ${missing[*]}"
    say "installing system packages: ${missing[*]}"
    sudo=""
    if [ "$(id -u)" != 0 ]; then
        command -v sudo >/dev/null 2>&1 || die "system packages missing (${missing[*]}) and not root and no sudo"
        sudo="sudo"
    fi
    log="$(mktemp "${TMPDIR:-/tmp}/noiselab-apt.XXXXXX.log")"
    if ! { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq \
            --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
        tail -n 25 "$log" >&2
        die "apt-get failed (full log: $log)"
    fi
    rm -f "$log"
fi

# --- the environment ---------------------------------------------------------
if [ -n "$active" ]; then
    if [ -e .venv ] && [ ! -L .venv ]; then
        [ -f .venv/.noiselab-install ] || die ".venv exists and was not made by install.sh; move it away first"
        say "replacing the project's .venv by a link to the active environment $active"
        rm -rf .venv
    fi
    ln -sfn "$active" .venv
    say "installing into the active environment $active (.venv links to it)"
elif [ ! -x .venv/bin/python ]; then
    [ -L .venv ] && rm -f .venv     # a link to an environment that is gone
    say "creating the virtual environment .venv with $base_python ($("$base_python" --version 2>&1))"
    mkdir -p .venv && touch .venv/.noiselab-install     # ours, also if venv stops half-way
    "$base_python" -m venv .venv || die "could not create .venv with $base_python"
else
    say "using the existing virtual environment .venv"
fi
python=.venv/bin/python

# --- noiselab ----------------------------------------------------------------
export PIP_ROOT_USER_ACTION=ignore PIP_DISABLE_PIP_VERSION_CHECK=1
say "installing noiselab${extras:+[$extras]} and its dependencies with pip (a few minutes the first time)"
"$python" -m pip install -q -e ".${extras:+[$extras]}"
# numba compiles each kernel on its first call; compile the default ones now, in parallel processes, so that
# the gallery and a first script start warm (8-10 s; NOISELAB_NO_WARMUP=1 skips it)
if [ -z "${NOISELAB_NO_WARMUP:-}" ]; then
    say "compiling the default kernels ahead (noiselab warmup)"
    "$python" -m noiselab warmup >/dev/null || say "noiselab warmup failed: first calls will compile instead"
fi
say "done: $("$python" -m noiselab --version) in $(cd .venv && pwd -P)"
say "run it as .venv/bin/noiselab (or: source .venv/bin/activate; then noiselab ...)"
