#!/usr/bin/env bash
# The test command of the README: installs what the tests need on a fresh Debian machine with a
# Rust toolchain, then runs every test of the workspace.
set -euo pipefail
cd "$(dirname "$0")/.."
# System packages (HDF5 C library, Python venv for the output test); quick when installed.
bash scripts/deps.sh
cargo test --workspace --all-targets --no-fail-fast
# Doc tests are not part of --all-targets.
cargo test --workspace --doc
# The library examples (examples/*.rs) run to the end and check what they print against the
# physics they show (load carried, short-bearing theory below the finite film, mass balance).
# The test profile reuses the dependencies the tests just built.
for example in steady_bearing inverse_cycle mobility_beside; do
    cargo run -q --profile test --example "$example"
done
# The Python package (python/): built into a virtualenv, its pytest suite against the CLI.
bash scripts/test_python.sh
