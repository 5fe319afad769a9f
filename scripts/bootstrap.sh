#!/usr/bin/env bash
# Installs every Debian package that stiffpath's build, tests, benchmarks and tools need (idempotent).
# Optional groups, installed only when named: `bootstrap.sh linuxcnc` adds LinuxCNC for its integration tests,
# `bootstrap.sh bindings` GNU Octave (the MEX gateway's build and test) and matplotlib (the Python example),
# `bootstrap.sh browser` headless Chromium for the HTML report's browser test.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libopencv-dev libpng-dev gnuplot-nox
  python3 python3-dev pybind11-dev python3-numpy python3-pytest
  clang  # libFuzzer harnesses (scripts/dev.sh fuzz)
)
for group in "$@"; do
  case "$group" in
    # LinuxCNC 2.9 in user space (no real-time kernel needed for the tests): halcompile, Makefile.modinc, halrun,
    # halsampler/halstreamer and the linuxcnc Python module. About 87 packages, 69 MB of archives.
    linuxcnc) packages+=(linuxcnc-uspace linuxcnc-uspace-dev) ;;
    # Octave 7 with mkoctfile, and matplotlib. Measured on Debian 12 (an image with the base packages): see docs/matlab.md.
    bindings) packages+=(octave liboctave-dev python3-matplotlib) ;;
    # Debian's Chromium, run headless by the test labelled browser (docs/figures.md).
    browser) packages+=(chromium) ;;
    *) echo "bootstrap: unknown package group '$group' (known: linuxcnc, bindings, browser)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "bootstrap: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "bootstrap: run as root or install sudo" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
echo "bootstrap: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
