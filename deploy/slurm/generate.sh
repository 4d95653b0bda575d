#!/usr/bin/env bash
# One shard of a VLNVerse-rs dataset per Slurm array task; join them with merge.sh.
#
#   sbatch --array=0-63 deploy/slurm/generate.sh      # VLNVERSE_SHARDS=64
#   sbatch --dependency=afterok:<array job id> deploy/slurm/merge.sh
#
# Settings (environment): VLNVERSE_PRESET (tiny | vlnverse) or VLNVERSE_CONFIG (a generation
# TOML), VLNVERSE_SHARDS (N, the array size), VLNVERSE_OUT (the final dataset folder; the shards
# go to $VLNVERSE_OUT.shards/K on storage every node sees), XTASK (how to run xtask; default
# `cargo xtask`, or the built binary target/release/xtask).
#SBATCH --job-name=vlnverse-generate
#SBATCH --cpus-per-task=4
#SBATCH --time=00:30:00
set -euo pipefail
: "${SLURM_ARRAY_TASK_ID:?run as a Slurm array task (or set SLURM_ARRAY_TASK_ID=K)}"
: "${VLNVERSE_SHARDS:?set VLNVERSE_SHARDS to the array size N}"
: "${VLNVERSE_OUT:?set VLNVERSE_OUT to the dataset folder}"
XTASK=${XTASK:-cargo xtask}
what=(--preset "${VLNVERSE_PRESET:-tiny}")
if [[ -n "${VLNVERSE_CONFIG:-}" ]]; then what=(--config "$VLNVERSE_CONFIG"); fi
threads=${SLURM_CPUS_PER_TASK:-1}
# Resumable: a requeued task finishes the scenes its predecessor left.
$XTASK generate "${what[@]}" --threads "$threads" \
  --shard "$SLURM_ARRAY_TASK_ID/$VLNVERSE_SHARDS" --out "$VLNVERSE_OUT.shards/$SLURM_ARRAY_TASK_ID"
