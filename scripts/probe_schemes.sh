#!/usr/bin/env bash
# Every shipped case with a rigorous Reynolds film under every time scheme the application can
# pick (bdf2, the default; backward_euler; crank_nicolson), as one batch: a copy of each case
# file with `solver.time_scheme` set (named <case>_<scheme>, beside copies of the tables) in a
# temporary directory. Prints the batch summary; exits 1 when a method failed or a run stalled.
# Not part of CI (about 4 minutes on 2 cores after the build): run it after a change to the
# inverse solver, the film or the case defaults. A shipped case broke for a day once without
# any test noticing (docs/results.md, the Flores feed-hole case); tests/cli.rs now runs that
# one, this script runs them all in every scheme.
#
# Usage: bash scripts/probe_schemes.sh [OUT]   (default OUT: results/probe)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/probe}
bash scripts/deps.sh
cargo build --release -q
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp cases/*.csv "$work/"
for case in cases/compressor_main.toml cases/compressor_rod.toml cases/flores2006_feed_hole.toml; do
    grep -q '^\[solver\]$' "$case" || { echo "$case: no [solver] section to set the scheme in" >&2; exit 2; }
    stem=$(basename "$case" .toml)
    for scheme in bdf2 backward_euler crank_nicolson; do
        sed -e '/^name *=/d' -e '/^time_scheme *=/d' \
            -e "s/^\[solver\]$/[solver]\ntime_scheme = \"$scheme\"/" \
            "$case" > "$work/${stem}_$scheme.toml"
    done
done
status=0
./target/release/jbearing batch "$work" --out "$out" --no-progress --force || status=$?
cat "$out/batch_summary.csv"
# A stalled step is accepted at its best point: the run is not failed, but the probe should say so.
if grep -q ' stalled' "$out/batch_summary.csv"; then status=1; fi
exit "$status"
