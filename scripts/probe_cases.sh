#!/usr/bin/env bash
# Every shipped case with a rigorous Reynolds film under every solver choice a user can make in
# its [solver] section, as one batch: each time scheme (bdf2, the default; backward_euler;
# crank_nicolson), BDF2 with the local error control off (step_error_tolerance = 0), and the
# short-bearing rigorous film (rigorous_film = "short_bearing"). A copy of each case file with
# the key set (named <case>_<variant>, beside copies of the tables) in a temporary directory.
# Prints the batch summary; exits 1 when a method failed or a run stalled.
# Not part of CI (about 7 minutes on 2 cores after the build): run it after a change to the
# inverse solver, the film, the mobility method or the case defaults. A shipped case broke for
# a day once without any test noticing (docs/results.md, the Flores feed-hole case); tests/cli.rs
# now runs that one, this script runs them all in every variant.
#
# Usage: bash scripts/probe_cases.sh [OUT]   (default OUT: results/probe)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-results/probe}
bash scripts/deps.sh
cargo build --release -q
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp cases/*.csv "$work/"
# variant name, then the [solver] key and value it sets.
variants=(
    "bdf2|time_scheme = \"bdf2\""
    "backward_euler|time_scheme = \"backward_euler\""
    "crank_nicolson|time_scheme = \"crank_nicolson\""
    "no_error_control|step_error_tolerance = 0.0"
    "short_bearing_film|rigorous_film = \"short_bearing\""
)
for case in cases/compressor_main.toml cases/compressor_rod.toml cases/flores2006_feed_hole.toml; do
    grep -q '^\[solver\]$' "$case" || { echo "$case: no [solver] section to set a key in" >&2; exit 2; }
    stem=$(basename "$case" .toml)
    for v in "${variants[@]}"; do
        name=${v%%|*}
        line=${v#*|}
        key=${line%% *}
        sed -e '/^name *=/d' -e "/^$key *=/d" \
            -e "s/^\[solver\]$/[solver]\n$line/" \
            "$case" > "$work/${stem}_$name.toml"
    done
done
status=0
./target/release/jbearing batch "$work" --out "$out" --no-progress --force || status=$?
cat "$out/batch_summary.csv"
# A stalled step is accepted at its best point: the run is not failed, but the probe should say so.
if grep -q ' stalled' "$out/batch_summary.csv"; then status=1; fi
exit "$status"
