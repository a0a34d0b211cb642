#!/usr/bin/env bash
# Install noiselab and everything it needs on a fresh machine:
#   - system libraries for headless 3-D rendering (VTK's EGL window on Mesa's
#     software renderer; without them VTK crashes the interpreter instead of raising)
#   - the noiselab package itself (editable), with optional extras.
# Usage: ./install.sh            # the package and its run-time dependencies
#        ./install.sh test       # ... plus the test extras
set -euo pipefail
cd "$(dirname "$0")"

system_packages=(libegl1 libgl1-mesa-dri)
# the gallery test opens index.html in real headless Chromium
[ "${1:-}" = test ] && system_packages+=(chromium)
missing=()
for pkg in "${system_packages[@]}"; do
    dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
    echo "install.sh: installing system packages: ${missing[*]}"
    sudo=""
    [ "$(id -u)" = 0 ] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

extras="${1:-}"
export PIP_ROOT_USER_ACTION=ignore PIP_DISABLE_PIP_VERSION_CHECK=1
python3 -m pip install -q -e ".${extras:+[$extras]}"
