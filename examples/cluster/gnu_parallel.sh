#!/usr/bin/env bash
# A sweep over N shards on one machine (or several, with parallel's --sshlogin), then the merge.
#
#   bash examples/cluster/gnu_parallel.sh cases/studies/rod_sweep.toml results/rod_sweep 4
#
# The same without GNU parallel (what tests/sweep.rs runs):
#   for i in 0 1 2 3; do jbearing batch CASE --shard $i/4 --out OUT & done; wait
set -euo pipefail
CASES=${1:?case file(s) or directory}
OUT=${2:?output directory}
N=${3:-4}
JBEARING=${JBEARING:-jbearing}
parallel --halt never --line-buffer \
  "$JBEARING" batch "$CASES" --shard {}/"$N" --jobs 1 --no-progress --out "$OUT" ::: $(seq 0 $((N - 1)))
"$JBEARING" merge "$OUT" --out "$OUT.nc"
