#!/usr/bin/env bash
# Install the Debian packages SaltDEM needs (build, MPI, Python post-processing, tests).
# As root on Debian/Ubuntu it installs what is missing; otherwise it lists what is missing and
# how to install it, and exits non-zero.
set -euo pipefail
pkgs=(cmake ninja-build g++ make libopenmpi-dev openmpi-bin xz-utils ca-certificates
      python3 python3-numpy python3-scipy python3-matplotlib python3-pytest python3-yaml
      python3-pip python3-venv python3-setuptools python3-wheel)

if [ ! -f /etc/debian_version ] || ! command -v dpkg-query >/dev/null; then
  echo "setup: this is not a Debian-based system; install the equivalents of:" >&2
  echo "  ${pkgs[*]}" >&2
  echo "setup: then build with: cmake -S . -B build -DLAMMPS_SOURCE_DIR=/path/to/lammps && cmake --build build" >&2
  exit 1
fi

missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all required Debian packages are installed"
  exit 0
fi
echo "setup: missing Debian packages: ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "setup: not root; install them with:" >&2
  echo "  sudo apt-get install -y --no-install-recommends ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -q || echo "setup: apt-get update failed; trying the install with the current lists" >&2
apt-get install -y -q --no-install-recommends "${missing[@]}"
