#!/usr/bin/env bash
# A latsim sweep as a Slurm job array: TASKS array tasks each run one shard
# (the runs whose plan position modulo TASKS is the task's index) into one
# output directory on a file system every node shares, and one more job,
# started when every task has ended, writes results.csv and results.sqlite
# and names any run still missing.
#
# On the login node, from the directory the paths are relative to:
#
#   scripts/cluster/slurm_array.sh SWEEP.json OUT_DIR [TASKS]
#
# e.g. scripts/cluster/slurm_array.sh scenarios/sweeps/tracker_rate.json /shared/sweeps/tracker_rate 16
#
# A task that dies (node failure, time limit) leaves its claim behind; submit
# the same command again: finished runs are skipped, and the dead task's claims
# are retaken once their heartbeat is older than --stale-after (600 s). Set
# LATSIM to the latsim binary if it is not on PATH. Edit the #SBATCH lines for
# your site (partition, account, time, memory); --cpus-per-task is the number
# of runs each task runs at once.
#
#SBATCH --job-name=latsim-sweep
#SBATCH --cpus-per-task=4
#SBATCH --mem-per-cpu=1G
#SBATCH --time=04:00:00
#SBATCH --output=latsim-sweep-%A_%a.out
set -euo pipefail
LATSIM=${LATSIM:-latsim}

if [ -z "${SLURM_JOB_ID:-}" ]; then
  # Not inside a job: submit the array, then the collecting job after it.
  if [ $# -lt 2 ]; then
    echo "usage: $0 SWEEP.json OUT_DIR [TASKS]" >&2
    exit 2
  fi
  tasks=${3:-16}
  # Check every point of the sweep here, once, rather than fail in every task.
  "$LATSIM" sweep "$1" --out "$2" --check
  array=$(sbatch --parsable --array="0-$((tasks - 1))" --export="ALL,LATSIM=$LATSIM" "$0" "$1" "$2")
  sbatch --parsable --dependency="afterany:${array%%;*}" --job-name=latsim-collect --cpus-per-task=1 \
         --output=latsim-collect-%j.out --export="ALL,LATSIM=$LATSIM" "$0" "$1" "$2" --collect
  exit 0
fi

if [ "${3:-}" = "--collect" ]; then
  exec "$LATSIM" sweep "$1" --out "$2" --collect
fi
# The task's slice comes from SLURM_ARRAY_TASK_ID, _MIN, _MAX, _STEP and _COUNT.
exec "$LATSIM" sweep "$1" --out "$2" --shard env -j "${SLURM_CPUS_PER_TASK:-1}"
