#!/usr/bin/env bash
# The system tools descgen's tests use as oracles, from Debian/Ubuntu packages:
#   liburdfdom-tools        check_urdf (urdfdom, what ROS parses URDF with)
#   python3-tf2             the tf2 C++ core, for Debian's /usr/bin/python3
#   python3-geometry-msgs   the messages tf2's Python binding needs
#   graphviz                dot (evidence/frames.svg)
#   chromium-headless-shell a browser for the test of `descgen view`
# Installs whatever is missing (as root, or with sudo); where that is impossible, says which
# packages are missing and exits 1, so `make test` never runs with its oracle tests skipped.
set -euo pipefail

PACKAGES=(liburdfdom-tools python3-tf2 python3-geometry-msgs graphviz chromium-headless-shell)

missing=()
for package in "${PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$package")
    fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

say() { echo "make test: $*" >&2; }
if ! command -v apt-get >/dev/null 2>&1; then
    say "the tests need these Debian/Ubuntu packages, and this machine has no apt-get: ${missing[*]}"
    say "install their equivalents (check_urdf, tf2 for the system python3, Graphviz, a headless Chromium), then run make test again"
    exit 1
fi
SUDO=()
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
        SUDO=(sudo)
    else
        say "the tests need these packages, and installing them needs root: sudo apt-get install ${missing[*]}"
        exit 1
    fi
fi
say "installing the tests' system oracles: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
if ! { "${SUDO[@]}" apt-get update -q && "${SUDO[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"; }; then
    say "could not install: ${missing[*]} (apt-get failed above); install them, then run make test again"
    exit 1
fi
