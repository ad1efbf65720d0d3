#!/usr/bin/env bash
# A sweep (or any batch) as a Slurm job array: task I of N runs shard I/N of the batch; all tasks
# write into one shared output directory; `jbearing merge` joins them afterwards.
#
#   sbatch --array=0-15 examples/cluster/slurm_array.sh cases/studies/rod_sweep.toml results/rod_sweep
#   # when all tasks are done (or: sbatch --dependency=afterany:JOBID merge.sh):
#   jbearing merge results/rod_sweep --out results/rod_sweep.nc
#
# A task that is preempted or fails can simply be resubmitted (sbatch --array=7 …): cases whose
# CASE.h5 exists are skipped (written atomically, so an existing file is a complete one).
#SBATCH --job-name=jbearing
#SBATCH --cpus-per-task=2
#SBATCH --mem-per-cpu=1G
#SBATCH --time=04:00:00
#SBATCH --output=slurm-%A_%a.out
set -euo pipefail
CASES=${1:?case file(s) or directory}
OUT=${2:?output directory}
JBEARING=${JBEARING:-jbearing}    # the release binary: cargo install --path . (or target/release/jbearing)
"$JBEARING" batch "$CASES" \
  --shard "${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}" \
  --jobs "${SLURM_CPUS_PER_TASK:-1}" \
  --out "$OUT"
