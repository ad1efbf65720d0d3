#!/usr/bin/env bash
# The main job of the README: the compressor cases of Yu & Sawicki (2002) as a batch.
# Installs the system packages (scripts/deps.sh), builds jbearing in release mode and runs both
# bearings in parallel. Results: results/compressor_{main,rod}.h5, *_cycle.png, *_orbit.png,
# *_summary.csv and results/batch_summary.csv.
#
# The load, speed and feed tables in cases/ are committed; `jbearing synth-loads` regenerates
# them from cases/machine/compressor.toml (the slider-crank model).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cargo run --release -- batch cases/compressor_main.toml cases/compressor_rod.toml --out results/ "$@"
