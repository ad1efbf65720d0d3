#!/usr/bin/env bash
# System packages jbearing needs on a fresh Debian machine (run as root, or with sudo available).
# Idempotent and fast when everything is installed: it only asks dpkg, and runs apt-get (one
# update, one install) for the packages that are missing.
#
#   libhdf5-dev, pkg-config   the HDF5 C library (+ libhdf5_hl) that hdf5-metno links; needed to
#                             build the workspace at all, so this runs before clippy and tests
#   python3, python3-venv     the output test (tests/output.rs) builds a virtualenv and reads the
#                             HDF5 files with xarray / pyvista from PyPI wheels
#   ca-certificates           pip's HTTPS to PyPI
#   git                       the run information (commit) written into every result file
#   build-essential           the C toolchain and linker cargo needs
# Fonts are not needed: the plots embed DejaVu Sans (assets/fonts/).
set -euo pipefail

packages=(libhdf5-dev pkg-config python3 python3-venv ca-certificates git build-essential)

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
    as_root=()
elif command -v sudo >/dev/null 2>&1; then
    as_root=(sudo)
else
    echo "scripts/deps.sh: missing Debian packages: ${missing[*]}" >&2
    echo "install them as root: apt-get update && apt-get install -y ${missing[*]}" >&2
    exit 1
fi
echo "scripts/deps.sh: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
