#!/usr/bin/env bash
# Runs the criterion benches. `--ci` runs a short profile (well under a minute of measuring)
# that only checks the benches run; without it the full measurement that the tables of
# docs/performance.md come from.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ "${1:-}" == "--ci" ]]; then
  cargo bench --bench jbearing_benches -- --warm-up-time 0.05 --measurement-time 0.1 --sample-size 10 --noplot
else
  cargo bench --bench jbearing_benches -- "${@}"
fi
