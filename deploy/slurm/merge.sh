#!/usr/bin/env bash
# Join the shards written by generate.sh into $VLNVERSE_OUT (byte-identical to one run).
#SBATCH --job-name=vlnverse-merge
#SBATCH --cpus-per-task=1
#SBATCH --time=00:30:00
set -euo pipefail
: "${VLNVERSE_SHARDS:?set VLNVERSE_SHARDS to the array size N}"
: "${VLNVERSE_OUT:?set VLNVERSE_OUT to the dataset folder}"
XTASK=${XTASK:-cargo xtask}
parts=()
for ((k = 0; k < VLNVERSE_SHARDS; k++)); do parts+=("$VLNVERSE_OUT.shards/$k"); done
$XTASK merge --out "$VLNVERSE_OUT" "${parts[@]}"
rm -rf "$VLNVERSE_OUT.shards"
